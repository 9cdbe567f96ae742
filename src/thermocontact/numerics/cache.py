"""Per-process caches bounded in bytes, which can be listed and cleared.

Assemblies, the geometry of the moment rules and the validity checks' row
operators depend only on the discretisation and a few parameters, so sweeps and
repeated solves reuse them.  Each is kept in a :class:`BoundedCache`: least
recently used entries are dropped once the arrays held exceed the cache's budget,
and :func:`clear_caches` empties all of them.  A worker process of a pool starts
with empty caches and fills its own.
"""

from __future__ import annotations

from collections import OrderedDict
from contextlib import contextmanager
from functools import lru_cache
from threading import RLock

import numpy as np

__all__ = ["BoundedCache", "cache_info", "clear_caches", "release_freed_memory", "small_cache"]

_ALL: dict[str, "BoundedCache"] = {}
#: The functools caches of small, n-dependent tables (rules, coefficient matrices).
_SMALL: list = []


def nbytes(value) -> int:
    """Bytes of the arrays held by ``value`` (arrays, tuples, lists, dicts, objects' dicts;
    a broadcast view by the entries it holds distinct)."""
    if isinstance(value, np.ndarray):
        if value.size and 0 in value.strides:
            # A broadcast view: its distinct entries only.
            return value.itemsize * int(np.prod([d for d, st in zip(value.shape, value.strides)
                                                 if st != 0]))
        return value.nbytes
    if isinstance(value, (tuple, list)):
        return sum(nbytes(v) for v in value)
    if isinstance(value, dict):
        return sum(nbytes(v) for v in value.values())
    if hasattr(value, "__dict__"):
        return sum(nbytes(v) for v in vars(value).values())
    return 0


class BoundedCache:
    """A least-recently-used mapping whose arrays stay below ``max_bytes``.

    Parameters
    ----------
    name : str
        Listed by :func:`cache_info`; unique per process.
    max_bytes : int
        Budget.  An entry larger than the budget is computed but not kept.
    """

    def __init__(self, name: str, max_bytes: int):
        self.name = name
        self.max_bytes = int(max_bytes)
        self._data: OrderedDict = OrderedDict()
        self._sizes: dict = {}
        self._bytes = 0
        self._lock = RLock()
        _ALL[name] = self

    def get(self, key, build):
        """The value under ``key``, computed by ``build()`` when absent."""
        with self._lock:
            if key in self._data:
                self._data.move_to_end(key)
                return self._data[key]
        value = build()
        size = nbytes(value)
        with self._lock:
            if size <= self.max_bytes and key not in self._data:
                self._data[key] = value
                self._sizes[key] = size
                self._bytes += size
                while self._bytes > self.max_bytes:
                    old, _ = self._data.popitem(last=False)
                    self._bytes -= self._sizes.pop(old)
        return value

    def find(self, key):
        """The value under ``key`` (counted as used), or None when absent."""
        with self._lock:
            if key not in self._data:
                return None
            self._data.move_to_end(key)
            return self._data[key]

    @contextmanager
    def transient(self, when=True):
        """Drop, at the end of the block, the entries added within it: for work whose
        entries are not used again (the blocks of points of a large assembly).  With
        ``when`` false the block keeps them, as any other."""
        if not when:
            yield self
            return
        with self._lock:
            before = set(self._data)
        try:
            yield self
        finally:
            with self._lock:
                for key in [k for k in self._data if k not in before]:
                    self.discard(key)

    def discard(self, key):
        """Drop ``key``'s entry, if any."""
        with self._lock:
            if key in self._data:
                del self._data[key]
                self._bytes -= self._sizes.pop(key)

    def clear(self):
        with self._lock:
            self._data.clear()
            self._sizes.clear()
            self._bytes = 0

    @property
    def bytes(self) -> int:
        return self._bytes

    def __len__(self):
        return len(self._data)

    def __contains__(self, key):
        with self._lock:
            return key in self._data

    def __repr__(self):
        return (f"BoundedCache({self.name!r}: {len(self)} entries, "
                f"{self._bytes / 2**20:.1f} of {self.max_bytes / 2**20:.0f} MiB)")


def small_cache(maxsize: int):
    """``functools.lru_cache(maxsize)`` for a small table, emptied by :func:`clear_caches`."""
    def deco(func):
        cached = lru_cache(maxsize=maxsize)(func)
        _SMALL.append(cached)
        return cached
    return deco


def clear_caches() -> None:
    """Empty the library's caches of this process: the bounded ones and the small
    tables' of every layer that may register them (numerics and those above it).
    Kept: the physics layer's tables (the kernels' fixed tables, made once; a layup's
    face conditions, made in milliseconds), the registries of materials and units, and
    the explorer's latest contacts."""
    for cache in _ALL.values():
        cache.clear()
    for cached in _SMALL:
        cached.cache_clear()


def cache_info() -> dict[str, tuple[int, int, int]]:
    """Per cache: entries, bytes held and budget."""
    return {name: (len(c), c.bytes, c.max_bytes) for name, c in _ALL.items()}


_LIBC = []


def release_freed_memory():
    """Return to the system the heap pages that freed arrays left, where the C library
    can (glibc's ``malloc_trim``; nothing elsewhere): before each stage of a large
    level (n >= 512) of a solve.

    glibc takes arrays below its mmap threshold from the heap, and the threshold rises
    to the size of every large array freed (up to 32 MB): after the first large
    temporary, arrays of a few MB come from the heap and leave freed pages resident,
    30-50 MB beyond what is held at n = 1024, until they are reused or trimmed.
    """
    if not _LIBC:
        import ctypes
        import ctypes.util

        try:
            libc = ctypes.CDLL(ctypes.util.find_library("c") or "libc.so.6")
            libc.malloc_trim.argtypes = [ctypes.c_size_t]
        except (OSError, AttributeError):
            libc = None
        _LIBC.append(libc)
    if _LIBC[0] is not None:
        _LIBC[0].malloc_trim(0)
