"""Solves per second of a map in this process, on a process pool and on a Dask cluster;
a map against the linear algebra it needs.

Run: ``python bench/bench_map.py [COUNT]`` (default 100: a COUNT x COUNT map over
fHPe 0-0.8 and Pe 0.5-100, K2/K1 = 10, lambda = 1, tolerance 1e-6).  A benchmark,
not a test: it prints a table and asserts nothing.  Each row times one whole map
from a cold start of its workers (imports and assemblies included); the
LocalCluster's start is timed separately.  The last column compares the cost of a
grid point with that of one plain ``solve`` (fresh assembly, closed-form polish)
at a point of the grid.

``python bench/bench_map.py --against-lu [COUNT]`` (default 200) times the same
COUNT x COUNT map on a process pool of 2 workers and, in the same run, COUNT^2 LU
solves (``scipy.linalg.lu_factor`` and ``lu_solve``, one system at a time) of the
size of the map's systems at its most frequent ``n`` (``2n + 2`` unknowns), in this
process, once before the map and once after it (the machine's speed drifts: the
ratio is taken to their mean); it prints the times and the ratio, in wall time and
in CPU time (the workers' and this process's: on a shared machine the less
disturbed measure); then a quarter of the LU solves pinned to each core in turn, to
show how far the cores' speeds differ during the run.
"""

from __future__ import annotations

import sys
import time

import numpy as np


def one_solve_time(repeats=5):
    from thermocontact import clear_caches, solve

    best = float("inf")
    for _ in range(repeats):
        clear_caches()
        t0 = time.perf_counter()
        solve(5.0, 0.4, 10.0, lam=1.0, tol=1e-6)
        best = min(best, time.perf_counter() - t0)
    return best


def main(count=100):
    from thermocontact.execution.executors import cpu_count
    from thermocontact.studies.maps import MapSpec, compute_map, parse_axis

    spec = MapSpec(parse_axis("--x", f"fhpe:0:0.8:{count}"),
                   parse_axis("--y", f"pe:0.5:100:{count}:log"),
                   {"K2_over_K1": 10.0, "lam": 1.0}, tol=1e-6)
    points = count * count
    solve_s = one_solve_time()
    print(f"{count} x {count} map ({points} points) on {cpu_count()} cores; one plain solve "
          f"{1e3 * solve_s:.1f} ms")
    print(f"{'executor':28s} {'wall s':>8s} {'points/s':>9s} {'efficiency':>10s} "
          f"{'point/solve':>11s}")
    rows, ref = [], None

    def record(name, workers, t, ds):
        nonlocal ref
        rate = points / t
        base = rows[0][2] if rows else rate
        eff = rate / (base * workers)
        rows.append((name, t, rate))
        per_point = t * workers / points
        print(f"{name:28s} {t:8.1f} {rate:9.1f} {eff:10.2f} {per_point / solve_s:11.3f}")
        if ref is None:
            ref = ds
        else:
            same = np.array_equal(ds.load_ratio.values, ref.load_ratio.values, equal_nan=True)
            print(f"{'':28s} same numbers as in one process: {same}")

    t0 = time.perf_counter()
    ds = compute_map(spec, workers=1)
    record("this process (1 core)", 1, time.perf_counter() - t0, ds)
    t0 = time.perf_counter()
    ds = compute_map(spec, workers=2)
    record("process pool, 2 workers", 2, time.perf_counter() - t0, ds)
    try:
        import distributed
    except ImportError:
        print("dask.distributed not installed: no cluster row")
        return
    t0 = time.perf_counter()
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True,
                                  host="127.0.0.1", dashboard_address=None) as cluster, \
            distributed.Client(cluster) as client:
        start = time.perf_counter() - t0
        t0 = time.perf_counter()
        ds = compute_map(spec, workers=client)
        record("Dask LocalCluster, 2 workers", 2, time.perf_counter() - t0, ds)
    print(f"(the cluster took {start:.1f} s to start, not counted)")


def lu_time(size, count):
    """Seconds of ``count`` LU solves of one well-conditioned ``size`` x ``size``
    system, one at a time, in this process."""
    from scipy.linalg import lu_factor, lu_solve

    rng = np.random.default_rng(0)
    A = rng.standard_normal((size, size)) + size * np.eye(size)
    b = rng.standard_normal(size)
    t0 = time.perf_counter()
    for _ in range(count):
        lu_solve(lu_factor(A), b)
    return time.perf_counter() - t0


def against_lu(count=200):
    """The map on 2 workers against ``count**2`` LU solves of its systems' size."""
    import os
    import resource

    from thermocontact.studies.maps import MapSpec, compute_map, parse_axis

    spec = MapSpec(parse_axis("--x", f"fhpe:0:0.8:{count}"),
                   parse_axis("--y", f"pe:0.5:100:{count}:log"),
                   {"K2_over_K1": 10.0, "lam": 1.0}, tol=1e-6)
    load = os.getloadavg()[0]
    # The size of the map's systems at its most frequent n, 32 (checked below).
    size = 66
    c0 = time.process_time()
    t_before = lu_time(size, count * count)
    cpu_before = time.process_time() - c0
    children = resource.getrusage(resource.RUSAGE_CHILDREN)
    c0, t0 = time.process_time(), time.perf_counter()
    ds = compute_map(spec, workers=2)
    t_map = time.perf_counter() - t0
    # CPU seconds of the map: the workers' (ended and waited for) and this process's.
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    cpu_map = (time.process_time() - c0 + after.ru_utime + after.ru_stime
               - children.ru_utime - children.ru_stime)
    ns = ds.n.values[ds.n.values > 0]
    n = int(np.bincount(ns).argmax())
    c0 = time.process_time()
    t_after = lu_time(2 * n + 2, count * count)
    cpu_after = time.process_time() - c0
    if 2 * n + 2 != size:
        print(f"(the map's most frequent n is {n}, not 32: the solves before it do not count)")
        t_before, cpu_before = t_after, cpu_after
    cpu_lu = 0.5 * (cpu_before + cpu_after)
    t_lu = 0.5 * (t_before + t_after)
    print(f"{count} x {count} map on 2 workers: {t_map:.1f} s; {count * count} LU solves of "
          f"{2 * n + 2} unknowns (n = {n}, {100 * np.mean(ns == n):.0f} % of the points) in "
          f"one process: {t_before:.2f} s before the map, {t_after:.2f} s after; ratio "
          f"{t_map / t_lu:.1f} (to their mean)")
    # On a machine shared with other work the wall times depend on the load; the CPU
    # times much less (a ratio of at most 6 in wall time on 2 workers is one of at
    # most 12 in CPU time, with both workers busy throughout).
    print(f"CPU time: map {cpu_map:.1f} s, LU solves {cpu_lu:.2f} s; ratio "
          f"{cpu_map / cpu_lu:.1f}")
    print(f"load average before {load:.2f}, after {os.getloadavg()[0]:.2f} (2 cores)")
    cores = per_core_lu(2 * n + 2, count * count // 4)
    if cores:
        print("a quarter of the LU solves pinned to each core in turn: "
              + ", ".join(f"core {c} {t:.2f} s" for c, t in cores.items())
              + f" (the slowest {max(cores.values()) / min(cores.values()) - 1:.0%} slower: "
              "the map runs on every core, the reference on one)")


def per_core_lu(size, count):
    """``{core: seconds}`` of ``count`` LU solves in this process pinned to each core
    it may use in turn (empty where affinity cannot be set): on a shared machine the
    cores' speeds can differ for minutes at a time."""
    import os

    if not hasattr(os, "sched_setaffinity"):
        return {}
    allowed = sorted(os.sched_getaffinity(0))
    out = {}
    try:
        for core in allowed:
            os.sched_setaffinity(0, {core})
            out[core] = lu_time(size, count)
    except OSError:  # affinity refused here (some containers)
        return {}
    finally:
        os.sched_setaffinity(0, allowed)
    return out if len(out) > 1 else {}


if __name__ == "__main__":
    if len(sys.argv) > 1 and sys.argv[1] == "--against-lu":
        against_lu(int(sys.argv[2]) if len(sys.argv) > 2 else 200)
    else:
        main(int(sys.argv[1]) if len(sys.argv) > 1 else 100)
