"""Maps: grid specifications, chunks kept on disk and resumed, the same numbers in this
process, on a process pool and on a Dask cluster, and the boundary located on each line."""

import concurrent.futures as cf
from concurrent.futures.process import BrokenProcessPool
import json
import math
import os
import re

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
import xarray as xr

from conftest import DATA, assert_same_result, data_script
from thermocontact import solve
from thermocontact.cli import main
from thermocontact.execution.executors import ExecutionError, check_scheduler, connect, run
from thermocontact.io.chunks import ChunkStore
from thermocontact.problem.validation import InputError
from thermocontact.io.datasets import read_dataset, write_dataset
from thermocontact.studies.maps import MAX_AXIS_POINTS, MapSpec, compute_map, parse_axis

#: A small map that crosses the boundary: Pe = 1, 3, 10 and fHPe to 0.8 (the gap
#: closes outside the leading edge near fHPe = 0.65).
X, Y = "fhpe:0:0.8:9", "pe:1:10:3:log"
FIXED = {"K2_over_K1": 10.0, "lam": 1.0}


def small_spec(**kw):
    return MapSpec(parse_axis("--x", X), parse_axis("--y", Y), dict(FIXED), **kw)


@pytest.fixture(scope="module")
def reference():
    """The small map, uninterrupted, in this process."""
    return compute_map(small_spec(), workers=1)


@pytest.mark.parametrize("spec, words", [
    ("velocity:0:1:5", "parameter must be one of"),
    ("fhpe:0:1", "name:start:stop:count[:log]"),
    ("fhpe:a:1:5", "start and stop must be numbers"),
    ("fhpe:1:0:5", "stop must be greater than start"),
    ("fhpe:0:0:5", "stop must be greater than start"),
    ("fhpe:0:1:1", "count must be 2 to"),
    (f"fhpe:0:1:{MAX_AXIS_POINTS + 1}", "count must be 2 to"),
    ("fhpe:0:1:2.5", "count must be an integer"),
    ("fhpe:0:1:5:log", "log axis must stay positive"),
    ("fhpe:-1:1:5:log", "log axis must stay positive"),
    ("fhpe:0:1:5:lin", "fifth field must be 'log'"),
    ("fhpe:0:inf:5", "must be a finite real number"),
])
def test_bad_axes_are_refused_in_one_line(spec, words, capsys):
    with pytest.raises(InputError, match=words.replace("[", r"\[").replace("]", r"\]")):
        parse_axis("--x", spec)
    rc = main(["map", "--x", spec, "--y", "pe:1:10:3", "--K2-over-K1", "10", "--lam", "1",
               "--out", "never.nc"])
    err = capsys.readouterr().err
    assert rc == 2 and err.startswith("error: --x") and err.count("\n") == 1
    assert not os.path.exists("never.nc")


def test_bad_grids_are_refused():
    """The same parameter twice, a missing fixed input, both closures, a corner out of
    the solver's range, too many points."""
    x = parse_axis("--x", X)
    with pytest.raises(InputError, match="y must name a parameter other than x's"):
        MapSpec(x, parse_axis("--y", "fhpe:0:1:3"), dict(FIXED))
    with pytest.raises(InputError, match="K2_over_K1 must be given"):
        MapSpec(x, parse_axis("--y", Y), {"lam": 1.0})
    with pytest.raises(InputError, match="exactly one of lam and sigma"):
        MapSpec(x, parse_axis("--y", Y), {**FIXED, "sigma_over_delta": 0.1})
    with pytest.raises(InputError, match="pe"):
        MapSpec(x, parse_axis("--y", "pe:-1:10:3"), dict(FIXED))
    with pytest.raises(InputError, match="at most 1000000 points"):
        MapSpec(parse_axis("--x", "fhpe:0:1:4000"), parse_axis("--y", "pe:1:2:400"),
                dict(FIXED))


def test_map_points_equal_plain_solves(reference):
    """Every point is Model.solve's answer at that point (polish near zero only: the
    margins to 1e-6, the verdicts exactly); failed points carry a reason."""
    from thermocontact import solve

    ds = reference
    for j in (0, 2):
        for i in (0, 4, 8):
            pe, f = float(ds.pe[j]), float(ds.fhpe[i])
            sol = solve(pe, f, 10.0, lam=1.0, tol=1e-6)
            point = ds.isel(pe=j, fhpe=i)
            assert float(point.load_ratio) == pytest.approx(sol.load_ratio, abs=1e-13)
            assert bool(point.valid) == sol.valid
            assert float(point.gap_margin) == pytest.approx(sol.validity.gap_margin, abs=1e-6)
            assert str(point.status.values) == sol.status
    assert set(np.unique(ds.status.values)) <= {"converged", "not converged"}


def test_boundary_on_each_line_equals_the_path_follower(reference):
    """The boundary point of each line is the event that `boundary` locates along fhpe
    independently (its own n and samples), to 1e-7 relative; so are the points traced
    between the lines where the boundary bends (near its nose at Pe ~ 2, 14 points
    between Pe = 1, 3.2 and 10; three of them checked).  The follower's events at
    these points are stored by tests/data/make_boundary_paths.py, at the points' Pe
    (the same here to 1e-9: the event moves by less than 1e-10 with it)."""
    ds = reference
    between = ds.boundary_between_lines.values == 1
    assert (~between).sum() >= 2 and between.sum() >= 3
    made = data_script("make_boundary_paths")
    stored = json.loads((DATA / "boundary_paths.json").read_text())
    assert (stored["x"], stored["y"], stored["fixed"]) == (X, Y, FIXED) == (made.X, made.Y,
                                                                            made.FIXED)
    picked = made.picked(ds)
    assert len(picked) == len(stored["points"])
    for bx, by, point in zip(ds.boundary_x.values[picked], ds.boundary_y.values[picked],
                             stored["points"]):
        assert by == pytest.approx(point["pe"], rel=1e-9, abs=0)
        assert min(abs(a - bx) for a in point["events"]) < 1e-7 * bx


def test_resume_after_interruption_is_identical(tmp_path, reference):
    """Interrupted after two lines, the run keeps them; run again it computes only the
    missing line, and the dataset, written and read back, equals the uninterrupted one."""
    store = tmp_path / "m.nc.parts"
    calls = []

    def interrupted(func, tasks):
        for task in tasks:
            if len(calls) == 2:
                raise KeyboardInterrupt
            calls.append(task["outer"])
            yield func(task)

    with pytest.raises(KeyboardInterrupt):
        compute_map(small_spec(), workers=interrupted, store_path=store)
    assert ChunkStore(store, small_spec().manifest()).done() == {0, 1}

    def counting(func, tasks):
        calls.append(len(tasks))
        return map(func, tasks)

    ds = compute_map(small_spec(), workers=counting, store_path=store)
    assert calls[-1] == 1
    write_dataset(ds, tmp_path / "m.nc")
    xr.testing.assert_identical(read_dataset(tmp_path / "m.nc"), reference)


def test_a_broken_executor_keeps_finished_work(tmp_path):
    """A worker that dies (BrokenProcessPool) ends the run with ExecutionError; the
    finished lines are on disk."""

    class Dying(cf.ThreadPoolExecutor):
        count = 0

        def submit(self, fn, *args):
            Dying.count += 1
            if Dying.count == 3:
                fut = cf.Future()
                fut.set_exception(BrokenProcessPool("a worker died"))
                return fut
            return super().submit(fn, *args)

    with Dying(1) as pool, pytest.raises(ExecutionError, match="run again to resume"):
        compute_map(small_spec(), workers=pool, store_path=tmp_path / "parts")
    assert len(ChunkStore(tmp_path / "parts", small_spec().manifest()).done()) >= 1


def test_different_arguments_are_refused(tmp_path):
    store = tmp_path / "parts"
    ChunkStore(store, small_spec().manifest())
    with pytest.raises(InputError, match="different run .*tol"):
        ChunkStore(store, small_spec(tol=1e-7).manifest())


def test_process_pool_gives_the_same_numbers(reference):
    ds = compute_map(small_spec(), workers=2)
    xr.testing.assert_identical(ds, reference)


def test_dask_cluster_gives_the_same_numbers(reference, tmp_path, capsys):
    """A real scheduler and two worker processes on the loopback interface, started here:
    the same dataset as in this process, through the API and through --scheduler."""
    distributed = pytest.importorskip("distributed")
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True,
                                  host="127.0.0.1", dashboard_address=None) as cluster:
        with distributed.Client(cluster) as client:
            ds = compute_map(small_spec(), workers=client)
        xr.testing.assert_identical(ds, reference)
        # A worker's address is refused, naming what answered there.
        worker = next(iter(cluster.workers.values())).address
        with pytest.raises(InputError,
                           match="answered as a Dask (Nanny|Worker): give the address "):
            connect(worker, timeout=5.0)
        # From inside a running event loop (a notebook's) too: the probe has its own.
        import asyncio

        from thermocontact.execution.executors import _identity

        async def inside():
            return _identity(cluster.scheduler_address, 5.0)
        assert asyncio.run(inside()) == "Scheduler"
        out = tmp_path / "d.nc"
        rc = main(["map", "--x", X, "--y", Y, "--K2-over-K1", "10", "--lam", "1",
                   "--out", str(out), "--scheduler", cluster.scheduler_address])
        assert rc == 0, capsys.readouterr().err
    back = read_dataset(out)
    np.testing.assert_array_equal(back.load_ratio.values, reference.load_ratio.values)
    assert (tmp_path / "d.png").stat().st_size > 10_000
    assert not (tmp_path / "d.nc.parts").exists()


@pytest.mark.parametrize("address, words", [
    ("localhost", "scheduler must be an address"),
    ("tcp://", "scheduler must be an address"),
    ("tcp://127.0.0.1:99999", "port must be 1 to 65535"),
    ("tcp://127.0.0.1", "must be an address with a port"),
    ("tcp://[::1]", "must be an address with a port"),
    ("tcp://[::1:8786", "must be an address with a port"),
])
def test_bad_scheduler_addresses(address, words, capsys):
    with pytest.raises(InputError, match=words):
        check_scheduler(address)
    rc = main(["map", "--x", X, "--y", Y, "--K2-over-K1", "10", "--lam", "1",
               "--out", "never.nc", "--scheduler", address])
    err = capsys.readouterr().err
    assert rc == 2 and err.startswith("error: --scheduler") and err.count("\n") == 1


def test_ipv6_scheduler_address_accepted():
    for address in ("tcp://[::1]:8786", "[::1]:8786", "tls://[fe80::1%eth0]:8786"):
        assert check_scheduler(address) == address


@pytest.mark.parametrize("family,host", [("AF_INET", "127.0.0.1"), ("AF_INET6", "[::1]")])
def test_no_scheduler_at_the_address(family, host, monkeypatch):
    """A refused connection is one line at once, not after the client's timeout: the
    plain connection refuses it, before Dask's handshake or a client (either of which
    would wait) is tried."""
    pytest.importorskip("distributed")
    import socket

    import distributed

    from thermocontact.execution import executors

    def waits(*args, **kwargs):
        raise AssertionError("a refused connection went on to wait for a scheduler")
    monkeypatch.setattr(executors, "_identity", waits)
    monkeypatch.setattr(distributed, "Client", waits)
    try:
        with socket.socket(getattr(socket, family)) as s:  # a port nobody listens on
            s.bind((host.strip("[]"), 0))
            port = s.getsockname()[1]
    except OSError:
        pytest.skip(f"no {family} loopback here")
    with pytest.raises(InputError, match=f"scheduler tcp://{re.escape(host)}:{port} did not "
                                         f"answer"):
        connect(f"tcp://{host}:{port}", timeout=5.0)


@pytest.fixture
def listener():
    """``listener(reply)``: the address of a loopback port that accepts connections and
    sends ``reply`` (bytes) on each, or nothing at all (None), and keeps them open."""
    import socket
    import threading

    servers, held = [], []

    def start(reply):
        server = socket.socket()
        server.bind(("127.0.0.1", 0))
        server.listen(8)
        servers.append(server)

        def serve():
            while True:
                try:
                    conn, _ = server.accept()
                except OSError:  # closed at the test's end
                    return
                held.append(conn)
                if reply is not None:
                    conn.sendall(reply)

        threading.Thread(target=serve, daemon=True).start()
        return f"tcp://127.0.0.1:{server.getsockname()[1]}"

    yield start
    for sock in servers + held:
        sock.close()


def test_a_peer_that_is_not_a_scheduler(listener, capsys, tmp_path, monkeypatch):
    """A port that accepts and says nothing, or answers in another protocol, is refused
    in one line within the timeout: no client waiting without end, no traceback of a
    half-made client's close."""
    distributed = pytest.importorskip("distributed")

    def made(*args, **kwargs):
        raise AssertionError("a client was made for a peer that is not a scheduler")
    with monkeypatch.context() as patched:
        # The handshake's own timeout ends the wait; no client (which would wait without
        # end on a silent peer) is made.
        patched.setattr(distributed, "Client", made)
        silent = listener(None)
        with pytest.raises(InputError, match=f"scheduler {silent} gave no Dask identity "
                                             ".no answer in Dask's protocol within "
                                             "1.5 s"):
            connect(silent, timeout=1.5)
    web = listener(b"HTTP/1.0 400 Bad Request\r\n\r\n" * 64)
    monkeypatch.chdir(tmp_path)
    rc = main(["map", "--x", X, "--y", Y, "--K2-over-K1", "10", "--lam", "1",
               "--out", "never.nc", "--scheduler", web])
    err = capsys.readouterr().err
    assert rc == 2 and err.startswith(f"error: --scheduler {web} gave no Dask identity "
                                      "(an answer not in Dask's protocol: ")
    assert err.count("\n") == 1



def test_every_output_path_checked_before_any_work(tmp_path, capsys, monkeypatch):
    """A folder where the picture goes, or a file where the unfinished work goes, is
    refused in one line before any work, leaving nothing: a rerun cannot claim a
    complete map without its picture."""
    import thermocontact.api as api

    def boom(*args, **kwargs):
        raise AssertionError("computed before the output paths were checked")
    monkeypatch.setattr(api, "compute_map", boom)
    argv = ["map", "--x", X, "--y", Y, "--K2-over-K1", "10", "--lam", "1", "--out"]
    (tmp_path / "pic.png").mkdir()
    (tmp_path / "w.nc.parts").write_text("x")
    for out, words in (("pic.nc", "--out's picture must be a file"),
                       ("w.nc", "--out's unfinished work must be a folder")):
        assert main(argv + [str(tmp_path / out)]) == 2
        err = capsys.readouterr().err.strip().splitlines()
        assert len(err) == 1 and words in err[0], err
    assert sorted(os.listdir(tmp_path)) == ["pic.png", "w.nc.parts"]


def test_map_out_where_nothing_can_be_created(capsys):
    """As root, os.access says /proc is writable: the dataset is refused in one line
    anyway, before any work."""
    import tempfile

    if not (os.path.isdir("/proc") and os.access("/proc", os.W_OK)):
        pytest.skip("os.access does not claim /proc is writable here")
    try:
        os.close(tempfile.mkstemp(dir="/proc")[0])
        pytest.skip("files can be created in /proc here")
    except OSError:
        pass
    assert main(["map", "--x", X, "--y", Y, "--K2-over-K1", "10", "--lam", "1",
                 "--out", "/proc/m.nc"]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "--out must be in a writable folder" in err[0]


def test_command_writes_refuses_and_completes(tmp_path, capsys):
    """The command writes dataset and picture and removes its parts; run again it has
    nothing to compute; with other arguments on the same --out it refuses."""
    out = tmp_path / "m.nc"
    args = ["map", "--x", X, "--y", Y, "--K2-over-K1", "10", "--lam", "1", "--out", str(out),
            "--workers", "1"]
    assert main(args) == 0
    text = capsys.readouterr().out
    assert "27 points" in text and (tmp_path / "m.png").exists()
    ds = read_dataset(out)
    assert ds.attrs["thermocontact_version"] and ds.attrs["method"] == "graded"
    assert json.loads(ds.attrs["manifest"])["x"] == "fhpe:0.0:0.8:9"
    assert ds.boundary_x.attrs["parameter"] == "fhpe"
    assert main(args) == 0 and "nothing to compute" in capsys.readouterr().out
    rc = main(args[:-2] + ["--tol", "1e-7", "--workers", "1"])
    err = capsys.readouterr().err
    assert rc == 2 and "holds a different map" in err


def test_failed_points_carry_their_reason():
    """Past the pole where no finite offset reaches lam (fhpe = 0 with --sigma is
    refused): a failed point has status 'failed', NaN values and the solver's message."""
    spec = MapSpec(parse_axis("--x", "fhpe:0:0.4:3"), parse_axis("--y", "pe:1:2:2"),
                   {"K2_over_K1": 10.0, "sigma_over_delta": 0.1})
    ds = compute_map(spec)
    point = ds.isel(pe=0, fhpe=0)
    assert str(point.status.values) == "failed"
    assert "sigma_over_delta cannot be imposed when fhpe = 0" in str(point.reason.values)
    assert np.isnan(float(point.load_ratio)) and int(point.valid) == 0
    assert (ds.status.values[:, 1:] != "failed").all()


def test_run_yields_every_task_once():
    assert sorted(run(abs, [-1, -2, 3], workers=1)) == [(0, 1), (1, 2), (2, 3)]
    assert sorted(run(abs, [-1, -2, 3], workers=lambda f, t: map(f, t))) == [(0, 1), (1, 2),
                                                                              (2, 3)]
    with pytest.raises(InputError, match="workers must be"):
        list(run(abs, [1], workers="many"))


def _worker_state(_):
    import gc

    from threadpoolctl import threadpool_info

    return gc.get_freeze_count(), [i["num_threads"] for i in threadpool_info()
                                   if i["user_api"] == "blas"]


@pytest.mark.parametrize("method", ["fork", "forkserver"])
def test_pool_workers_run_on_one_blas_thread_with_their_start_frozen(method, monkeypatch):
    """A local pool's workers use one BLAS thread each and keep the objects they start
    with out of the garbage collector's reach (gc.freeze), whether they are forked (this
    process has no other thread) or started by a fork server (it has: then BLAS is
    limited by the initialiser, before any task)."""
    from thermocontact.execution import executors

    monkeypatch.setattr(executors, "_start_method", lambda fork=True: method)
    for _, (frozen, threads) in run(_worker_state, [0, 1], workers=2):
        assert frozen > 100 and threads and set(threads) == {1}


def test_workers_are_forked_only_where_no_other_thread_runs(monkeypatch):
    """fork with this process alone on its thread; a fork server, told to import the
    library (and what a caller adds) before its first worker, while another thread
    runs, or wherever fork is refused (the explorer's server)."""
    import multiprocessing
    import multiprocessing.context
    import threading

    from thermocontact.execution.executors import process_context

    if "forkserver" not in multiprocessing.get_all_start_methods():
        pytest.skip("no fork server on this platform")
    told = []
    monkeypatch.setattr(multiprocessing.context.ForkServerContext, "set_forkserver_preload",
                        lambda self, names: told.append(list(names)))
    assert process_context(fork=False, preload=["json"]).get_start_method() == "forkserver"
    assert told and {"thermocontact.api", "json"} <= set(told[-1])
    if threading.active_count() == 1:
        assert process_context().get_start_method() == "fork"
    stop = threading.Event()
    other = threading.Thread(target=stop.wait)
    other.start()
    try:
        assert process_context().get_start_method() == "forkserver"
    finally:
        stop.set()
        other.join()


def test_the_callers_preparation_runs_beside_workers_elsewhere_only():
    """run_chunks' ``meanwhile`` runs once, in a thread of this process, while workers
    elsewhere compute (never in a run in this process, where it would only compete);
    its failure does not fail the run."""
    import threading

    from thermocontact.execution.resumable import MEANWHILE_THREAD, run_chunks

    seen = []

    def prepare():
        seen.append(threading.current_thread() is not threading.main_thread())
        raise RuntimeError("the caller tries again after the run")

    tasks = [-1, -2, 3, -4]

    def helpers():
        return [t for t in threading.enumerate() if t.name == MEANWHILE_THREAD]
    out = run_chunks(abs, tasks, {"kind": "test"}, workers=2, meanwhile=prepare)
    assert out == {0: 1, 1: 2, 2: 3, 3: 4} and seen == [True]
    assert helpers() == []  # joined: a later pool may fork
    seen.clear()
    for here in (1, lambda f, t: map(f, t)):
        run_chunks(abs, tasks, {"kind": "test"}, workers=here, meanwhile=prepare)
    assert seen == []
    # A run that fails while the preparation is still at work leaves no thread behind.
    import time

    with pytest.raises(ValueError):
        run_chunks(_fails_at_three, tasks, {"kind": "test"}, workers=2,
                   meanwhile=lambda: time.sleep(0.5))
    assert helpers() == []


def _fails_at_three(x):
    if x == 3:
        raise ValueError("the third task fails")
    return x


def test_progress_line_reports_rate_and_time_left():
    """10 of 100 chunks 5 s after the first report: 2 chunks/s, 45 s left."""
    import io

    from thermocontact.execution.progress import ProgressLine

    bar = ProgressLine("map", "lines", stream=io.StringIO())
    assert bar.text(0, 100, now=100.0) == "map: 0/100 lines (0%)"
    assert bar.text(10, 100, now=105.0) == "map: 10/100 lines (10%), 2 lines/s, 0:45 left"


@pytest.mark.parametrize("argv, words", [
    (["--x", "fhpe:0:0.5:2", "--y", "pe:1:5:2", "--K2-over-K1", "10", "--lam", "0",
      "--fhpe", "0.3"], "--fhpe must not be given: it is an axis"),
    (["--x", "sigma:0:0.1:2", "--y", "pe:1:5:2", "--K2-over-K1", "10", "--fhpe", "0.2",
      "--sigma", "0.05"], "--sigma must not be given: it is an axis"),
    (["--x", "fhpe:0:0.5:2", "--y", "K2-over-K1:1:5:2", "--pe", "5", "--lam", "0",
      "--K2-over-K1", "10"], "--K2-over-K1 must not be given: it is an axis"),
])
def test_value_for_a_dimensionless_axis_refused_in_one_line(argv, words, capsys, tmp_path):
    """A value for the parameter an axis maps is refused, not silently replaced."""
    rc = main(["map", *argv, "--out", str(tmp_path / "never.nc")])
    err = capsys.readouterr().err
    assert rc == 2 and words in err and err.count("\n") == 1, err
    assert os.listdir(tmp_path) == []


@pytest.mark.parametrize("extra, words", [
    (["--friction", "-0.1"], "friction must be"),
    (["--friction", "0.2", "--speed", "1"], "--speed must not be given: it is an axis"),
    (["--friction", "0.2", "--pe", "5"], "--pe belongs to a dimensionless map"),
    (["--friction", "0.2", "--radius", "-1mm"], "radius"),
    (["--friction", "0.2", "--method", "paper"], "--method belongs to a dimensionless map"),
    (["--friction", "0.2", "--delta1-over-delta2", "2"],
     "--delta1-over-delta2 belongs to a dimensionless map"),
])
def test_bad_operating_maps_are_refused_in_one_line(extra, words, capsys):
    rc = main(["map", "--cylinder", "copper", "--half-plane", "steel", "--lam", "-1",
               "--x", "load:1e2:1e6:3:log", "--y", "speed:0.01:100:3:log", "--out", "never.nc",
               *([] if "--radius" in extra else ["--radius", "10mm"]), *extra])
    err = capsys.readouterr().err
    assert rc == 2 and words in err and err.count("\n") == 1, err
    assert not os.path.exists("never.nc")


@pytest.mark.parametrize("model, fhpe, closure", [
    # Along fHPe, with edge terms (delta1 != delta2: the gap sampled from 1e-6) and a
    # line that crosses the boundary.
    ({"pe": 0.7, "K2_over_K1": 1.0, "delta1_over_delta2": 0.3}, [0.0, 0.3, 0.9, 1.5],
     {"lam": 1.0}),
    # Along lam and along sigma; sigma with fHPe = 0 is refused at that point only.
    ({"pe": 5.0, "K2_over_K1": 10.0}, 0.4, {"lam": [-1.0, 0.0, 1.0]}),
    ({"pe": 5.0, "K2_over_K1": 10.0}, [0.0, 0.3], {"sigma_over_delta": 0.1}),
])
@pytest.mark.parametrize("polish", [False, True])
def test_a_line_solved_together_equals_its_points_solved_one_by_one(model, fhpe, closure,
                                                                    polish):
    """Model.solve_many (a map's grid line: systems shared, the validity of all points
    at one n evaluated together) gives at every point what Model.solve gives there
    (every field, the margins and their positions included: the flags exactly, the
    numbers to the rounding, conftest.assert_same_result), or the same error."""
    import warnings

    from thermocontact import Model
    from thermocontact.problem.parameters import ConvergenceWarning

    m = Model(model["pe"], model["K2_over_K1"],
              delta1_over_delta2=model.get("delta1_over_delta2", 1.0), tol=1e-6)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", ConvergenceWarning)
        together = m.solve_many(fhpe, polish=polish, **closure)
        count = len(together)
        points = [(np.broadcast_to(fhpe, count)[i],
                   {k: np.broadcast_to(v, count)[i] for k, v in closure.items()})
                  for i in range(count)]
        for sol, (f, kw) in zip(together, points):
            try:
                alone = m.solve(float(f), polish=polish, **{k: float(v) for k, v in kw.items()})
            except InputError as exc:
                assert isinstance(sol, InputError) and str(sol) == str(exc)
                continue
            assert_same_result(sol, alone)
            assert_same_result(sol.validity.to_dict(), alone.validity.to_dict())
    assert any(isinstance(s, InputError) for s in together) == ("sigma_over_delta" in closure)
    if "delta1_over_delta2" in model:
        valid = [s.valid for s in together]
        assert True in valid and False in valid  # the line crosses the boundary
        assert any(np.isfinite(s.validity.edge_layer_log_widths).any()
                   or s.validity.edge_log_coefficients != (0.0, 0.0) for s in together)


def test_a_line_with_proven_condition_is_the_same_line():
    """Model.solve_many(rcond="bound"), as the map solves its lines: every solution and
    validity is that of the estimated path (conftest.assert_same_result), and its rcond a proven lower bound
    (derivation section 6b) at most LAPACK's estimate; an unknown choice is refused by
    name."""
    import warnings

    from thermocontact import Model
    from thermocontact.problem.parameters import ConvergenceWarning
    from thermocontact.numerics.dense import CERTIFIED_RCOND

    m = Model(0.7, 1.0, delta1_over_delta2=0.3, tol=1e-6)
    fhpe = np.linspace(0.0, 1.5, 100)  # enough points at n = 32 for anchors
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", ConvergenceWarning)
        bounded = m.solve_many(fhpe, lam=1.0, polish=False, rcond="bound")
        estimated = m.solve_many(fhpe, lam=1.0, polish=False)
    for b, e in zip(bounded, estimated, strict=True):
        assert_same_result(b.replace(rcond=e.rcond), e)
        assert_same_result(b.validity.to_dict(), e.validity.to_dict())
        # A proven lower bound is at most the true number, LAPACK's estimate at least
        # it but for rounding (a few ulps of it, which other CPUs' kernels move).
        assert CERTIFIED_RCOND <= b.rcond <= e.rcond * (1 + 16 * np.finfo(float).eps)
    assert sum(b.rcond < e.rcond for b, e in zip(bounded, estimated)) >= len(fhpe) // 2
    with pytest.raises(InputError, match="rcond"):
        m.solve_many(fhpe, lam=1.0, rcond="exact")


@pytest.mark.parametrize("axis, fixed", [("lam:-1:1:3", {"fhpe": 0.2}),
                                         ("sigma_over_delta:0.1:0.3:2", {"fhpe": 0.2})])
def test_a_closure_on_an_axis_is_the_coordinate(axis, fixed):
    """A map along lam or sigma builds its dataset (a field of the axis's name once
    clashed with the coordinate), and each point is the plain solve at the
    coordinate's value."""
    spec = MapSpec(parse_axis("--x", axis), parse_axis("--y", "pe:1:5:2"),
                   {"K2_over_K1": 10.0, **fixed})
    ds = compute_map(spec)
    name = spec.x.name
    assert list(ds[name].values) == list(spec.x.values)
    sol = solve(5.0, 0.2, 10.0, **{name: float(spec.x.values[-1])}, tol=1e-6)
    assert float(ds.load_ratio.isel(pe=1, **{name: -1})) == pytest.approx(sol.load_ratio,
                                                                        rel=1e-6)


def test_a_line_s_events_from_a_first_guess_are_brent_s(monkeypatch):
    """The benchmark map's lines at Pe = 2 and 10 (fHPe 0-0.8 in 200 points), each
    crossing the boundary: Brent's method started from the margin's zero interpolated
    through the samples around the event finds the same events (inequality, edge,
    validity either side) at the same places to the events' tolerance
    (BOUNDARY_RTOL, each), with fewer single-point solves than started from the
    bracket; on a coarse line (fHPe in 41 points) no more solves than without."""
    from thermocontact.solvers.single_patch import Model
    from thermocontact.studies import maps

    calls = []
    solve_at = Model.solve_at
    monkeypatch.setattr(Model, "solve_at",
                        lambda self, *a, **k: calls.append(1) or solve_at(self, *a, **k))
    spec = MapSpec(parse_axis("--x", "fhpe:0:0.8:200"), parse_axis("--y", "pe:2:10:2:log"),
                   {"K2_over_K1": 10.0, "lam": 1.0}, tol=1e-6)
    guessed, plain = [], []
    for found in (guessed, plain):
        calls.clear()
        found += [maps.evaluate_chunk(task)["events"] for task in spec.tasks()]
        found.append(len(calls))
        monkeypatch.setattr(maps, "interpolated_root", lambda xs, values, tol: None)
    assert guessed[-1] < plain[-1]
    monkeypatch.undo()
    monkeypatch.setattr(Model, "solve_at",
                        lambda self, *a, **k: calls.append(1) or solve_at(self, *a, **k))
    coarse = MapSpec(parse_axis("--x", "fhpe:0:0.8:41"), parse_axis("--y", "pe:2:10:2:log"),
                     {"K2_over_K1": 10.0, "lam": 1.0}, tol=1e-6)
    counts = []
    for _ in range(2):
        calls.clear()
        for task in coarse.tasks():
            maps.evaluate_chunk(task)
        counts.append(len(calls))
        monkeypatch.setattr(maps, "interpolated_root", lambda xs, values, tol: None)
    assert counts[0] <= counts[1]
    for a, b in zip(guessed[:-1], plain[:-1], strict=True):
        assert len(a) == len(b) >= 1
        for e, f in zip(a, b):
            assert {k: v for k, v in e.items() if k not in ("at", "position")} == \
                   {k: v for k, v in f.items() if k not in ("at", "position")}
            # Each within the tolerance of the root: within two of each other.
            assert abs(e["at"] - f["at"]) <= 2 * maps.BOUNDARY_RTOL * abs(f["at"])


def _same_record(a, b):
    """Equal JSON records, types included, NaN equal to NaN."""
    assert type(a) is type(b)
    if isinstance(a, dict):
        assert list(a) == list(b)
        for k in a:
            _same_record(a[k], b[k])
    elif isinstance(a, list):
        assert len(a) == len(b)
        for x, y in zip(a, b):
            _same_record(x, y)
    elif isinstance(a, float) and a != a:
        assert b != b
    else:
        assert a == b and (not isinstance(a, float) or math.copysign(1, a) == math.copysign(1, b))


_JSON_SCALARS = (st.none() | st.booleans() | st.integers() | st.text()
                 | st.floats(allow_nan=True, allow_infinity=True))


@settings(max_examples=300, deadline=None)
@given(st.recursive(_JSON_SCALARS | st.tuples(_JSON_SCALARS),
                    lambda inner: st.lists(inner, max_size=5)
                    | st.dictionaries(st.text(max_size=5) | st.integers(), inner, max_size=5),
                    max_leaves=30))
def test_a_record_as_stored_is_its_json_round_trip(record):
    """as_stored (a chunk's result without a store) is json.loads(json.dumps(record)),
    types, signs of zero and NaN included: the record itself where it is JSON's own
    types, else the round trip (tuples, integer keys)."""
    from thermocontact.execution.resumable import as_stored

    _same_record(as_stored(record), json.loads(json.dumps(record)))


def test_records_that_are_not_json_s_own_types_take_the_round_trip():
    """NumPy numbers, integer enums, dict and str subclasses, a surrogate pair (which
    the round trip joins into one character), an integer too long for text, nesting
    deeper than the check's recursion: as_stored gives what the round trip gives (or
    its error)."""
    import collections
    import enum

    from thermocontact.execution.resumable import as_stored

    class Level(enum.IntEnum):
        HIGH = 3

    class Name(str):
        pass
    deep = []
    for _ in range(600):
        deep = [deep]
    for record in ({"a": [np.float64(1.5), np.float64("nan")]}, [Level.HIGH, True, 1],
                   collections.OrderedDict(b=1.0), [Name("x")], {"s": "\ud83d\ude00"},
                   {"s": "caf\u00e9"}, deep):
        _same_record(as_stored(record), json.loads(json.dumps(record)))
    for record in ([10**5000], [float("nan"), -0.0]):
        try:
            expected = json.loads(json.dumps(record))
        except ValueError as exc:
            with pytest.raises(type(exc)):
                as_stored(record)
        else:
            _same_record(as_stored(record), expected)


def test_a_grid_line_s_record_is_stored_as_it_is():
    """A map line's record is made of JSON's own types: kept as it is, no round trip."""
    from thermocontact.execution.resumable import as_stored
    from thermocontact.studies.maps import evaluate_chunk

    spec = MapSpec(parse_axis("--x", "fhpe:0:0.8:12"), parse_axis("--y", "pe:2:3:2"),
                   {"K2_over_K1": 10.0, "lam": 1.0}, tol=1e-6)
    record = evaluate_chunk(spec.tasks()[0])
    assert as_stored(record) is record
    _same_record(record, json.loads(json.dumps(record)))


@pytest.mark.parametrize("suffix", [".nc", ".zarr"])
def test_a_map_written_reads_back_identical_without_warnings(reference, tmp_path, suffix):
    """NetCDF and Zarr (format 2: format 3 warns of fixed-length strings and
    consolidated metadata) hold the whole map, status strings and attributes included."""
    import warnings

    if suffix == ".zarr":
        pytest.importorskip("zarr")
    path = tmp_path / f"m{suffix}"
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        write_dataset(reference, path)
    xr.testing.assert_identical(read_dataset(path), reference)


def test_one_blas_thread_holds_both_libraries_loaded_after_it_is_asked():
    """Asked for before NumPy and SciPy are imported (as the command line asks), the
    limit still holds both libraries' BLAS to one thread: threadpoolctl limits only the
    libraries loaded when it is called, and the helper loads both first."""
    import subprocess
    import sys

    code = ("from thermocontact.execution.executors import one_blas_thread\n"
            "one_blas_thread()\n"
            "import numpy, scipy.linalg\n"
            "from threadpoolctl import threadpool_info\n"
            "info = [i for i in threadpool_info() if i['user_api'] == 'blas']\n"
            "print(len(info), max(i['num_threads'] for i in info))\n")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                         check=True, timeout=120)
    count, threads = map(int, out.stdout.split())
    assert count >= 1 and threads == 1
