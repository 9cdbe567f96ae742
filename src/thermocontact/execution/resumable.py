"""Work cut into chunks that are kept as they finish, so that a run resumes.

A map's grid lines, an operating map's ray samples, a study's paths: each is a list
of independent tasks whose results are JSON records.  :func:`run_chunks` runs them
wherever :func:`~.executors.run` sends them and keeps each result in a
:class:`~thermocontact.io.chunks.ChunkStore` as it arrives; run again with the same
manifest, it computes only what is missing.
"""

from __future__ import annotations

import json
import threading

from ..io.chunks import ChunkStore
from .executors import run, runs_elsewhere

__all__ = ["as_stored", "run_chunks"]


#: The name of :func:`run_chunks`' thread for the caller's preparation.
MEANWHILE_THREAD = "thermocontact: the caller's preparation"


def run_chunks(func, tasks, manifest, store_path=None, *, workers=1, progress=None,
               what="the map", meanwhile=None) -> dict:
    """``{index: func(task)}`` for every task, each kept in ``store_path`` as it finishes
    and read from there when present (a resumed run computes only what is missing).

    ``what`` names the run in the refusal of a store that holds another run's work.
    ``meanwhile``, a callable, is the caller's own preparation for what follows the run
    (the imports of its dataset, about a second): with workers outside this process it
    runs in a thread of its own once the first chunk is in, while the workers compute
    the rest (not before: no process is forked beside a thread).

    Every result is as its stored (JSON) form reads back (:func:`as_stored`), so a
    resumed run's results equal an uninterrupted run's exactly.
    """
    store = None if store_path is None else ChunkStore(store_path, manifest, what)
    chunks = {} if store is None else {i: store.get(i) for i in store.done()}
    todo = [i for i in range(len(tasks)) if i not in chunks]

    def report(done, total):
        if progress is not None:
            progress(len(tasks) - total + done, len(tasks))

    helper = None
    if meanwhile is not None and not runs_elsewhere(workers, len(todo)):
        meanwhile = None  # here it would only take the tasks' own time
    try:
        for k, result in run(func, [tasks[i] for i in todo], workers=workers,
                             progress=report):
            if meanwhile is not None and helper is None:
                helper = threading.Thread(target=_quietly, args=(meanwhile,), daemon=True,
                                          name=MEANWHILE_THREAD)
                helper.start()
            i = todo[k]
            if store is not None:
                store.put(i, result)
                chunks[i] = store.get(i)
            else:
                chunks[i] = as_stored(result)
    finally:
        # Not left running, even when the run is interrupted: a process pool started
        # after it would not fork beside a thread.
        if helper is not None:
            helper.join()
    return chunks


#: The types a JSON record reads back as themselves (strings: without surrogates, which
#: the round trip pairs; integers: of fewer digits than Python converts to text).
_SCALARS = frozenset({float, bool, type(None)})
_DIGITS_LIMIT = 10**4000


def as_stored(result):
    """``result`` as its JSON record reads back, ``json.loads(json.dumps(result))``: the
    object itself where it is made of JSON's own types only (dicts with string keys,
    lists, strings without surrogates, integers, floats, booleans, None), which the
    round trip leaves equal (a float's repr reads back to the same float, NaN and
    infinities included); else the round trip (tuples become lists, NumPy numbers
    Python's).  A grid line's record is checked in a fifth of the round trip's time
    (which was 2.6 ms of the parent's per line).  The record is not copied: the
    callers' tasks return fresh records."""
    try:
        plain = _plain(result)
    except RecursionError:  # deeper than a record: the round trip's own verdict
        plain = False
    return result if plain else json.loads(json.dumps(result))


def _scalar(v) -> bool:
    kind = type(v)
    if kind in _SCALARS:
        return True
    if kind is str:
        return v.isascii() or not any("\ud800" <= c <= "\udfff" for c in v)
    return kind is int and -_DIGITS_LIMIT < v < _DIGITS_LIMIT


def _plain(x) -> bool:
    if _scalar(x):
        return True
    kind = type(x)
    if kind is list:  # (floats first: a grid line's record is mostly floats)
        return all(type(v) in _SCALARS or _scalar(v) or _plain(v) for v in x)
    if kind is dict:
        return all(type(k) is str and _scalar(k)
                   and (type(v) in _SCALARS or _scalar(v) or _plain(v))
                   for k, v in x.items())
    return False


def _quietly(prepare):
    """``prepare()``, its failure left to the caller's own attempt after the run."""
    try:
        prepare()
    except Exception:  # noqa: BLE001 - the caller does the same work again and reports
        pass
