"""Shared test helpers: the stored independent references (tests/data/make_references.py)."""

import json
import pathlib
from functools import lru_cache


@lru_cache(maxsize=None)
def references() -> dict:
    """The values written by ``python tests/data/make_references.py``."""
    return json.loads((pathlib.Path(__file__).parent / "data" / "references.json").read_text())
