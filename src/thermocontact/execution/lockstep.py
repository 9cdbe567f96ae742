"""Sequential computations run in lockstep, their requests answered in batches.

A computation that asks for many small evaluations one after another (a speed scan
asking for ``det M`` at a few points at a time) spends most of its time in the
per-call cost of the array library.  Several independent such computations (the
scans of a curve's wavelengths) can share that cost: each runs until it asks, and
when every one still running has asked, their requests are answered by one call per
kind of request, the points of all of them stacked.

Each computation runs in a thread of its own, but only one at a time, in a fixed
order, each handing control straight to the next when it asks (the last to the
driver, which answers the round's requests): threads here are coroutines whose code is
ordinary sequential code (it may ask from inside a callback of SciPy's root
finders), not parallelism.  The order of the computations and of the batches is
fixed, so a run is repeatable; each computation gets the answers it would get
alone, as long as the batched evaluation gives every point the value it gives it
alone (elementwise array operations and stacked LAPACK calls do).
"""

from __future__ import annotations

import threading

__all__ = ["run_lockstep"]


class _Cancelled(BaseException):
    """Raised inside a computation's thread to end it (another failed, or Ctrl-C)."""


class _Signal:
    """A one-shot handover between threads: :meth:`set` by one, consumed by the
    :meth:`wait` of another (a bare lock held while unset: a fraction of the cost of
    an event's condition, the switch being most of a request's overhead)."""

    def __init__(self):
        self._lock = threading.Lock()
        self._lock.acquire()

    def set(self):
        try:
            self._lock.release()
        except RuntimeError:               # already set
            pass

    def wait(self):
        self._lock.acquire()


class _Baton:
    """Whose turn it is: the computations of a round, each handing control straight
    to the next when it asks or ends (one switch of threads per request, not two
    through the driver), the last to the driver."""

    def __init__(self):
        self.back = _Signal()              # the round is over (or one failed)
        self.order = ()
        self.pos = 0
        self.closed = False                # cancelling: nobody is waiting

    def run_round(self, order):
        """Run each of ``order`` in turn until it asks or ends (in the driver's thread:
        blocks until the last has, or one has failed)."""
        self.order, self.pos = order, 0
        order[0].turn.set()
        self.back.wait()

    def pass_on(self, task):
        """``task`` (the one running) has asked or ended: the next of the round runs,
        or the driver if it was the last or failed."""
        if self.closed:
            return
        self.pos += 1
        if task.error is None and self.pos < len(self.order):
            self.order[self.pos].turn.set()
        else:
            self.back.set()


class _Task:
    """One computation's thread and its handshake with the others."""

    def __init__(self, func, baton):
        self.func = func
        self.baton = baton
        self.turn = _Signal()              # control handed to the task
        self.request = None                # (key, payload) while waiting for an answer
        self.answer = None
        self.result = None
        self.error = None
        self.finished = False
        self.cancelled = False
        self.thread = threading.Thread(target=self._run, daemon=True)

    def _wait(self):
        self.turn.wait()

    def _run(self):
        self._wait()
        try:
            if not self.cancelled:
                self.result = self.func(self.ask)
        except _Cancelled:
            pass
        except BaseException as exc:  # noqa: BLE001 (handed to the driver, raised there)
            self.error = exc
        self.finished = True
        self.baton.pass_on(self)

    def ask(self, key, payload):
        """Leave ``(key, payload)`` for the driver, hand control on and wait for the
        answer."""
        if self.cancelled:
            raise _Cancelled
        self.request = (key, payload)
        self.baton.pass_on(self)
        self._wait()
        if self.cancelled:
            raise _Cancelled
        answer, self.answer = self.answer, None
        return answer


def run_lockstep(funcs, evaluate, finished=None):
    """Run computations in lockstep, their requests answered in batches.

    Parameters
    ----------
    funcs : sequence of callable
        ``func(ask)``: a computation, which calls ``ask(key, payload)`` for each
        evaluation it needs and gets its answer back.
    evaluate : callable
        ``evaluate(key, payloads)``: the answers to the payloads of one key (a list
        of the same length, in order), computed together.  Called once per key in
        each round, the keys in the order first asked.
    finished : callable, optional
        ``finished(i, result)``, told as computation ``i`` returns (for progress).

    Returns
    -------
    list
        Each computation's result, in order.

    Notes
    -----
    A round runs every computation still running, in order, until it asks or
    returns; then the requests are answered.  An exception in a computation or in
    ``evaluate`` (or a ``KeyboardInterrupt`` in the caller) ends the others at
    their next request, and is raised here once all threads have ended.
    """
    baton = _Baton()
    tasks = [_Task(f, baton) for f in funcs]
    for task in tasks:
        task.thread.start()
    live = list(tasks)
    try:
        while live:
            baton.run_round(live)
            for task in live:
                if task.error is not None:
                    raise task.error
            done = [t for t in live if t.finished]
            live = [t for t in live if not t.finished]
            for task in done if finished is not None else ():
                finished(tasks.index(task), task.result)
            groups = {}
            for task in live:
                groups.setdefault(task.request[0], []).append(task)
            for key, group in groups.items():
                answers = evaluate(key, [t.request[1] for t in group])
                for task, answer in zip(group, answers):
                    task.request, task.answer = None, answer
    finally:
        baton.closed = True
        for task in tasks:
            if not task.finished:
                task.cancelled = True
                task.turn.set()
        for task in tasks:
            task.thread.join()
    return [t.result for t in tasks]
