"""Shared test helpers: the stored independent references (tests/data/make_references.py)."""

import json
import pathlib
from functools import lru_cache

from threadpoolctl import threadpool_limits

# The matrices are small: one BLAS thread, as the command line and every map worker
# use (several threads competing for two cores made the suite three times slower).
threadpool_limits(1)


@lru_cache(maxsize=None)
def references() -> dict:
    """The values written by ``python tests/data/make_references.py``."""
    return json.loads((pathlib.Path(__file__).parent / "data" / "references.json").read_text())
