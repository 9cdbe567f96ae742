"""One way to run independent tasks, wherever they run.

:func:`run` takes a picklable function and a list of picklable tasks and yields
``(index, result)`` as each task finishes.  Where the tasks run is the
``workers`` argument, as scipy's ``workers=``:

* ``1``: in this process;
* an int ``N > 1`` or ``None`` (all cores): a local process pool, one BLAS thread
  per worker (the tasks are many small solves: processes, not threads, scale);
* a ``concurrent.futures.Executor``, or a ``dask.distributed`` ``Client``;
* a map-like callable, ``workers(func, tasks)`` returning the results in order.

At most a few tasks per worker are in flight, so an interrupt stops the run
promptly, and the caller can store each result as it arrives: whatever finished
before a failure (an interrupt, a killed worker, a lost scheduler) is kept.
"""

from __future__ import annotations

import concurrent.futures as cf
import multiprocessing
import os
import re
from functools import partial

from ..problem.errors import ExecutionError
from ..problem.validation import InputError, check_integer

__all__ = ["ExecutionError", "check_scheduler", "connect", "cpu_count", "one_blas_thread",
           "process_context", "run", "runs_elsewhere", "side_process"]

#: Tasks in flight per worker.
IN_FLIGHT = 2
#: Most local worker processes.
MAX_WORKERS = 1024


def cpu_count() -> int:
    """Cores this process may use."""
    try:
        return len(os.sched_getaffinity(0))
    except AttributeError:  # not on Linux
        return os.cpu_count() or 1


def one_blas_thread():
    """NumPy's and SciPy's BLAS on one thread: the limits, applied at once (a context
    manager that restores them at its exit).

    The matrices of this package are small, and one thread is faster than several
    competing for the cores.  ``threadpoolctl`` limits only the libraries loaded when it
    is called, and NumPy and SciPy each bring their own, SciPy's loaded with
    :mod:`scipy.linalg`: both are loaded here first, so that neither keeps its default
    threads (asked for before them, the limit held nothing)."""
    import numpy  # noqa: F401
    import scipy.linalg  # noqa: F401
    from threadpoolctl import threadpool_limits

    return threadpool_limits(limits=1, user_api="blas")


def _start_method(fork=True) -> str:
    """``fork`` where it is safe (POSIX, no other thread in this process) and ``fork``
    is true: the workers start at once, with the modules already imported, whatever
    ``__main__`` is (a notebook, standard input).  Otherwise ``forkserver`` or
    ``spawn``."""
    import threading

    methods = multiprocessing.get_all_start_methods()
    if fork and "fork" in methods and threading.active_count() == 1:
        return "fork"
    return "forkserver" if "forkserver" in methods else "spawn"


#: What a fork server imports before it forks its first worker (the process's one
#: server: the union of every caller's, fixed when it starts): the library's calls and
#: what they import, NumPy and SciPy among them, so that each worker starts with them
#: imported (about half a second less a worker).
_PRELOAD = {"thermocontact.api": None}


def process_context(fork=True, preload=()):
    """The ``multiprocessing`` context of worker processes (:func:`_start_method`; a
    fork server importing the library and ``preload`` once, before its first worker).

    Parameters
    ----------
    fork : bool
        False: never ``fork`` (a process whose threads may hold locks at any time, a
        server's).
    preload : sequence of str
        Modules a fork server imports besides the library's, where it has not started
        yet.
    """
    method = _start_method(fork)
    if method == "forkserver":
        _PRELOAD.update(dict.fromkeys(preload))
        ctx = multiprocessing.get_context(method)
        ctx.set_forkserver_preload(list(_PRELOAD))
        return ctx
    return multiprocessing.get_context(method)


def _interrupts_held(call, *args):
    """``call(*args)`` with Ctrl-C (SIGINT) held back in this thread, for a call that may
    start worker processes: a child starts with the signal held, so that an interrupt
    while it starts is not a traceback of its start-up (:func:`_admit_interrupts` lets it
    through once the child is ready); this process receives a held interrupt when the
    call returns."""
    import signal

    if not hasattr(signal, "pthread_sigmask"):
        return call(*args)
    old = signal.pthread_sigmask(signal.SIG_BLOCK, {signal.SIGINT})
    try:
        return call(*args)
    finally:
        signal.pthread_sigmask(signal.SIG_SETMASK, old)


def _admit_interrupts(ignore):
    """In a child started by :func:`_interrupts_held`: drop an interrupt that arrived
    while it started (its parent, which held the signal too, receives its own), then
    ignore Ctrl-C (``ignore``: the parent stops the child) or take it as before."""
    import signal

    if not hasattr(signal, "pthread_sigmask"):
        return
    before = signal.signal(signal.SIGINT, signal.SIG_IGN)  # discards a pending one
    signal.pthread_sigmask(signal.SIG_UNBLOCK, {signal.SIGINT})
    if not ignore:
        signal.signal(signal.SIGINT, before)


def _single_thread(ignore_interrupts=False):
    """Worker initialiser: Ctrl-C admitted (:func:`_admit_interrupts`), one BLAS thread
    (the workers are the parallelism), and the objects the worker starts with (a forked
    worker's: its parent's modules) frozen out of the garbage collector's reach, so that
    its full collections walk only what its tasks made (a grid line's collections take
    half the time) and leave the pages it shares with its parent unwritten."""
    import gc

    # NumPy's and SciPy's BLAS loaded now (a fork server's worker has neither yet) and
    # limited here, before any task; loaded while Ctrl-C is still held, as every other
    # step of the worker's start.
    one_blas_thread()
    _admit_interrupts(ignore_interrupts)
    gc.freeze()


def _import_quietly(modules):
    """Side-process start: ignore Ctrl-C (the parent stops the process), import ``modules``."""
    import importlib

    _single_thread(ignore_interrupts=True)
    for name in modules:
        importlib.import_module(name)


def side_process(*modules):
    """One worker process that imports ``modules`` now, while this process computes.

    For work whose imports cost as much as the computation before it (a picture:
    Matplotlib takes about as long to import as a `contact` to solve): submit the
    work to the returned executor when its input is ready.  ``None`` where only one
    core is available, where the overlap gains nothing; the caller then works here.
    The caller shuts the executor down.
    """
    if cpu_count() < 2:
        return None
    ctx = process_context()
    pool = cf.ProcessPoolExecutor(1, mp_context=ctx, initializer=_import_quietly,
                                  initargs=(modules,))
    _interrupts_held(pool.submit, int)  # starts the process, and so its imports
    return pool


#: A scheduler address: protocol://host:port (an IPv6 host in brackets) or host:port.
#: The port is required: distributed refuses an address without one only after a long
#: wait.  (``inproc://`` names a scheduler in this process, which an address given here
#: cannot reach.)
_ADDRESS = re.compile(r"^(?:(?P<protocol>tcp|tls|ucx|ws|wss)://)?"
                      r"(?P<host>\[[0-9A-Fa-f:.%\w]+\]|[^\s/:\[\]]+):(?P<port>\d{1,5})/?$")


def _host_port(address):
    """``(host, port)`` of a checked address."""
    m = _ADDRESS.match(address)
    return m.group("host").strip("[]"), int(m.group("port"))


def check_scheduler(address) -> str:
    """``address`` if it looks like a Dask scheduler address (``tcp://host:port``,
    ``tcp://[::1]:port``)."""
    if not isinstance(address, str) or not _ADDRESS.match(address.strip()):
        raise InputError(f"scheduler must be an address with a port, such as "
                         f"tcp://127.0.0.1:8786, got {address!r}", parameters=("scheduler",))
    address = address.strip()
    if not 0 < _host_port(address)[1] < 65536:
        raise InputError(f"scheduler port must be 1 to 65535, got {address!r}",
                         parameters=("scheduler",))
    return address


def connect(address, timeout=10.0):
    """A ``dask.distributed`` client of the scheduler at ``address``.

    Raises
    ------
    InputError
        dask.distributed is not installed, the address is malformed, or no scheduler
        answers there within ``timeout`` seconds (at once where the connection is
        refused).
    """
    import socket

    address = check_scheduler(address)
    try:
        from distributed import Client
    except ImportError:
        raise InputError("scheduler needs dask.distributed: pip install "
                         "'thermocontact[dask]'", parameters=("scheduler",)) from None
    # A plain connection first: refused, it fails at once, where a Client would retry
    # until its timeout and then take as long again to close.
    try:
        socket.create_connection(_host_port(address), timeout=timeout).close()
    except OSError as exc:
        raise InputError(f"scheduler {address} did not answer "
                         f"({exc.strerror or type(exc).__name__})",
                         parameters=("scheduler",)) from None
    # Then Dask's own handshake and an identity request, within the timeout: a Client
    # waits without end on a peer that accepts and says nothing, and one that fails
    # leaves a half-made Client whose close waits 20 s more and prints a traceback.
    kind = _identity(address, timeout)
    if kind != "Scheduler":
        raise InputError(f"scheduler {address} answered as a Dask {kind}: give the address "
                         "the cluster's workers connect to", parameters=("scheduler",))
    try:
        return Client(address, timeout=timeout, set_as_default=False)
    except Exception as exc:  # noqa: BLE001 - any failure to connect is one line
        raise InputError(f"scheduler {address} did not answer within {timeout:g} s "
                         f"({type(exc).__name__})", parameters=("scheduler",)) from None


def _identity(address, timeout) -> str:
    """The ``type`` of the reply to Dask's ``identity`` request at ``address``
    (``"Scheduler"``, ``"Worker"``, ``"Nanny"``), within ``timeout`` seconds.

    Raises
    ------
    InputError
        No reply in Dask's protocol within ``timeout`` seconds.
    """
    import asyncio
    import concurrent.futures

    from distributed.comm import connect as open_comm
    from distributed.security import Security

    # The connection arguments a Client would use (TLS from dask's configuration).
    args = Security().get_connection_args("client")

    async def ask():
        comm = await open_comm(address, timeout=timeout, **args)
        try:
            await comm.write({"op": "identity", "reply": True})
            return await comm.read()
        finally:
            comm.abort()

    def probe():
        # A loop of its own, in a thread of its own: the caller's may be running
        # (a notebook).
        return asyncio.run(asyncio.wait_for(ask(), timeout))

    why = f"no answer in Dask's protocol within {timeout:g} s"
    with concurrent.futures.ThreadPoolExecutor(1) as pool:
        try:
            reply = pool.submit(probe).result()
        except asyncio.TimeoutError:
            reply = None
        except Exception as exc:  # noqa: BLE001 - whatever the peer sent, one line
            # (bytes of another protocol read as a frame's length: MemoryError,
            # ValueError; a connection closed or reset: OSError)
            why = f"an answer not in Dask's protocol: {type(exc).__name__}"
            reply = None
    if not (isinstance(reply, dict) and isinstance(reply.get("type"), str)):
        raise InputError(f"scheduler {address} gave no Dask identity ({why})",
                         parameters=("scheduler",))
    return reply["type"]


def _is_dask_client(obj) -> bool:
    return type(obj).__name__ == "Client" and hasattr(obj, "submit") and hasattr(obj, "gather")


def run(func, tasks, *, workers=1, progress=None):
    """Run ``func`` on every task; yield ``(index, result)`` as each finishes.

    Parameters
    ----------
    func : callable
        Picklable (module level) unless ``workers == 1``.
    tasks : sequence
    workers : int, None, Executor, dask Client or callable
        Where to run (module docstring).
    progress : callable, optional
        ``progress(done, total)`` before the first task and after each.

    Raises
    ------
    ExecutionError
        The executor broke; the results yielded so far are complete.
    """
    tasks = list(tasks)
    total = len(tasks)
    if progress is not None:
        progress(0, total)
    for done, (i, result) in enumerate(_run(func, tasks, workers), start=1):
        if progress is not None:
            progress(done, total)
        yield i, result


def runs_elsewhere(workers, count: int) -> bool:
    """Whether :func:`run` sends ``count`` tasks to processes other than this one: a
    process pool of more than one worker, an executor or a Dask client (a map-like
    callable may run them here)."""
    if _is_count(workers):
        n = cpu_count() if workers is None else workers
        return min(n, count) > 1
    return isinstance(workers, cf.Executor) or _is_dask_client(workers)


def _is_count(workers) -> bool:
    """Whether ``workers`` is a number of local processes (None: one per core)."""
    return isinstance(workers, (int, type(None))) and not isinstance(workers, bool)


def _run(func, tasks, workers):
    if _is_count(workers):
        n = cpu_count() if workers is None else check_integer("workers", workers, 1, MAX_WORKERS)
        n = min(n, max(len(tasks), 1))
        if n == 1:
            # One BLAS thread here too: the same arithmetic as in a worker.
            with one_blas_thread():
                for i, task in enumerate(tasks):
                    yield i, func(task)
            return
        ctx = process_context()
        with cf.ProcessPoolExecutor(n, mp_context=ctx, initializer=_single_thread) as pool:
            try:
                # A submit may start a worker: interrupts held meanwhile.
                yield from _as_completed(partial(_interrupts_held, pool.submit), cf.wait,
                                         cf.FIRST_COMPLETED, func, tasks, n)
            except BaseException:
                pool.shutdown(wait=False, cancel_futures=True)
                raise
        return
    if isinstance(workers, cf.Executor):
        n = getattr(workers, "_max_workers", None) or cpu_count()
        yield from _as_completed(workers.submit, cf.wait, cf.FIRST_COMPLETED, func, tasks, n)
        return
    if _is_dask_client(workers):
        from distributed import wait

        def submit(f, t):
            return workers.submit(_one_blas_thread, f, t, pure=False)

        n = max(1, sum(workers.nthreads().values()))
        with workers.as_current():  # wait() looks for the current client
            yield from _as_completed(submit, wait, "FIRST_COMPLETED", func, tasks, n)
        return
    if callable(workers):
        yield from enumerate(workers(func, tasks))
        return
    raise InputError(f"workers must be a number of processes, an executor or a map-like "
                     f"callable, got {workers!r}")


def _one_blas_thread(func, task):
    """``func(task)`` with BLAS on one thread: a Dask worker's tasks, like a pool's
    processes, must not each start a BLAS thread per core."""
    with one_blas_thread():
        return func(task)


def _as_completed(submit, wait, first_completed, func, tasks, n):
    """Keep ``IN_FLIGHT * n`` tasks submitted; yield each as it finishes."""
    pending = {}
    queue = iter(enumerate(tasks))

    def top_up():
        for i, task in queue:
            pending[submit(func, task)] = i
            if len(pending) >= IN_FLIGHT * n:
                break

    top_up()
    try:
        while pending:
            finished, _ = wait(list(pending), return_when=first_completed)
            for fut in finished:
                i = pending.pop(fut)
                try:
                    result = fut.result()
                except (InputError, KeyboardInterrupt):
                    raise
                except Exception as exc:
                    if type(exc).__name__ in ("BrokenProcessPool", "CancelledError",
                                              "CommClosedError", "KilledWorker", "TimeoutError",
                                              "OSError", "FutureCancelledError"):
                        raise ExecutionError(f"the executor failed ({type(exc).__name__}: "
                                             f"{exc}); finished work is kept, run again to "
                                             f"resume") from None
                    raise
                yield i, result
            top_up()
    finally:
        for fut in pending:
            fut.cancel()
