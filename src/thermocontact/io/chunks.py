"""Finished work kept on disk as it finishes, so that a run can resume.

A :class:`ChunkStore` is a folder holding a manifest (the arguments of the run,
as JSON) and one JSON file per finished chunk, each written atomically.  Opening
a store whose manifest differs from the run's is refused, naming what differs, so
that two runs are never mixed; opening it with the same manifest finds the chunks
already done.  JSON keeps every float exactly (``repr`` round-trips), so a resumed
run's results equal an uninterrupted run's.
"""

from __future__ import annotations

import json
import os
import re
import shutil

from ..problem.validation import InputError
from .files import WriteError, atomic_write

__all__ = ["ChunkStore", "discard", "manifest_difference"]

MANIFEST = "manifest.json"
_CHUNK = re.compile(r"^chunk-(\d{6})\.json$")


def manifest_difference(old: dict, new: dict) -> str:
    """The keys whose values differ, as ``"key: old -> new"`` (first three)."""
    keys = sorted(set(old) | set(new))
    diff = [f"{k}: {old.get(k)!r} -> {new.get(k)!r}" for k in keys if old.get(k) != new.get(k)]
    more = f" and {len(diff) - 3} more" if len(diff) > 3 else ""
    return "; ".join(diff[:3]) + more


class ChunkStore:
    """Chunks of one run in ``folder``, under the run's ``manifest``.

    Parameters
    ----------
    folder : str or os.PathLike
    manifest : dict
        JSON-serialisable description of the run: chunks are resumed only under an
        equal manifest.
    what : str
        What the store holds, for messages (e.g. ``"the map map.nc"``).
    """

    def __init__(self, folder, manifest: dict, what: str = "the run"):
        self.folder = os.fspath(folder)
        self.manifest = json.loads(json.dumps(manifest))
        self.what = what
        path = os.path.join(self.folder, MANIFEST)
        if os.path.isdir(self.folder) and os.path.exists(path):
            with open(path) as fh:
                try:
                    old = json.load(fh)
                except json.JSONDecodeError:
                    old = {}
            if old != self.manifest:
                raise InputError(
                    f"{self.folder} holds the unfinished work of a different run "
                    f"({manifest_difference(old, self.manifest)}); run with the same "
                    f"arguments to resume it, or remove the folder")
        elif os.path.exists(self.folder) and not os.path.isdir(self.folder):
            raise InputError(f"{self.folder} exists and is not a folder: cannot keep "
                             f"the finished work of {what} there")
        else:
            try:
                os.makedirs(self.folder, exist_ok=True)
            except OSError as exc:
                raise WriteError(self.folder, exc) from None
            with atomic_write(path) as fh:
                json.dump(self.manifest, fh, indent=1)

    def done(self) -> set[int]:
        """Indices of the finished chunks."""
        found = set()
        for name in os.listdir(self.folder):
            m = _CHUNK.match(name)
            if m:
                found.add(int(m.group(1)))
        return found

    def _path(self, index: int) -> str:
        return os.path.join(self.folder, f"chunk-{index:06d}.json")

    def put(self, index: int, result: dict):
        """Keep chunk ``index`` (atomically: a chunk is on disk whole or not at all)."""
        with atomic_write(self._path(index)) as fh:
            json.dump(result, fh, allow_nan=True, separators=(",", ":"))

    def get(self, index: int) -> dict:
        """Chunk ``index`` as it was put."""
        with open(self._path(index)) as fh:
            return json.load(fh)



def discard(folder):
    """Delete a store's folder (once the run's output holds everything)."""
    shutil.rmtree(os.fspath(folder), ignore_errors=True)
