"""Solves per second of a map in this process, on a process pool and on a Dask cluster;
a map against the linear algebra it needs.

Run: ``python bench/bench_map.py [COUNT]`` (default 100: a COUNT x COUNT map over
fHPe 0-0.8 and Pe 0.5-100, K2/K1 = 10, lambda = 1, tolerance 1e-6).  A benchmark,
not a test: it prints a table and asserts nothing.  Each row times one whole map
from a cold start of its workers (imports and assemblies included); the
LocalCluster's start is timed separately.  The last column compares the cost of a
grid point with that of one plain ``solve`` (fresh assembly, closed-form polish)
at a point of the grid.

``python bench/bench_map.py --against-lu [COUNT [REPEATS]]`` (defaults 200 and 3) times
the same COUNT x COUNT map on a process pool of 2 workers and, in the same run, COUNT^2
LU solves (``scipy.linalg.lu_factor`` and ``lu_solve``, one system at a time) of the
size of the map's systems at its most frequent ``n`` (``2n + 2`` unknowns), in this
process: REPEATS maps, each in a fresh process of its own, between REPEATS + 1 LU loops
(the machine's speed drifts: each map's ratio is taken to the mean of the loops on
either side of it).  It prints each map's times and ratio, in wall time and in CPU time
(the workers' and the map's own process's: on a shared machine the less disturbed
measure), and the median ratio, the run's measure (one repeat disturbed by the host
does not make it); the maps must be identical (a digest of every variable and
attribute), or no ratio is given.  Then a quarter of the LU solves pinned to each core
in turn, to show how far the cores' speeds differ during the run.
"""

from __future__ import annotations

import subprocess
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


def against_lu(count=200, repeats=3):
    """The map on 2 workers against ``count**2`` LU solves of its systems' size,
    ``repeats`` times: LU, map, LU, map, ..., LU, each map's ratio taken to the mean of
    the LU loops on either side of it; the median ratio is the run's."""
    import os

    if repeats < 1:
        sys.exit(f"bench_map.py: REPEATS must be at least 1, got {repeats}")
    load = os.getloadavg()[0]
    # The size of the map's systems at its most frequent n, 32 (checked below).
    size = 66
    lu = [_timed(lu_time, size, count * count)]
    maps, digests = [], set()
    for _ in range(repeats):
        # Each map in a process of its own, as the first map of a run would be (the
        # modules of this package imported; xarray's first dataset not yet made).
        done = subprocess.run([sys.executable, __file__, "--one-map", str(count)],
                              capture_output=True, text=True)
        if done.returncode != 0:
            sys.exit(f"bench_map.py: the map's process failed:\n{done.stderr}")
        out = done.stdout.split()
        wall, cpu, n, share, digest = float(out[0]), float(out[1]), int(out[2]), \
            float(out[3]), out[4]
        maps.append((wall, cpu))
        digests.add(digest)
        if 2 * n + 2 != size:
            print(f"the map's most frequent n is {n}, not 32: the LU solves are of the wrong "
                  "size; no ratio")
            return
        lu.append(_timed(lu_time, size, count * count))
    if len(digests) > 1:
        print("the repeats' maps differ: no ratio")
        return
    print(f"{count} x {count} map on 2 workers against {count * count} LU solves of {size} "
          f"unknowns (n = {n}, {100 * share:.0f} % of the points) in one process; "
          "each map between two LU loops, its ratio taken to their mean:")
    ratios, cpu_ratios = [], []
    for r, (wall, cpu) in enumerate(maps):
        t_lu = 0.5 * (lu[r][0] + lu[r + 1][0])
        cpu_lu = 0.5 * (lu[r][1] + lu[r + 1][1])
        ratios.append(wall / t_lu)
        cpu_ratios.append(cpu / cpu_lu)
        print(f"  map {wall:5.1f} s (CPU {cpu:5.1f} s), LU {lu[r][0]:.2f} s before, "
              f"{lu[r + 1][0]:.2f} s after: ratio {ratios[-1]:.1f} (CPU ratio "
              f"{cpu_ratios[-1]:.1f})")
    # On a machine shared with other work a single run's wall times depend on the load;
    # the median of the repeats does much less (and the CPU times less still: a ratio
    # of at most 6 in wall time on 2 busy workers is one of at most 12 in CPU time).
    print(f"median ratio {np.median(ratios):.1f} (CPU {np.median(cpu_ratios):.1f}); the maps "
          f"are identical; load average before {load:.2f}, after {os.getloadavg()[0]:.2f} "
          "(2 cores)")
    cores = per_core_lu(size, count * count // 4)
    if cores:
        print("a quarter of the LU solves pinned to each core in turn: "
              + ", ".join(f"core {c} {t:.2f} s" for c, t in cores.items())
              + f" (the slowest {max(cores.values()) / min(cores.values()) - 1:.0%} slower: "
              "the map runs on every core, the reference on one)")


def _timed(func, *args):
    """``(wall seconds, CPU seconds of this process)`` of ``func(*args)``, which returns
    its own wall time."""
    c0 = time.process_time()
    wall = func(*args)
    return wall, time.process_time() - c0


def one_map(count):
    """Print the wall and CPU seconds of the map on 2 workers (the workers', ended and
    waited for, and this process's), its most frequent ``n`` and that ``n``'s share of
    the points, and a digest of the whole dataset."""
    import hashlib
    import resource

    from thermocontact.studies.maps import MapSpec, compute_map, parse_axis

    spec = MapSpec(parse_axis("--x", f"fhpe:0:0.8:{count}"),
                   parse_axis("--y", f"pe:0.5:100:{count}:log"),
                   {"K2_over_K1": 10.0, "lam": 1.0}, tol=1e-6)
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    c0, t0 = time.process_time(), time.perf_counter()
    ds = compute_map(spec, workers=2)
    wall = time.perf_counter() - t0
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    cpu = (time.process_time() - c0 + after.ru_utime + after.ru_stime
           - before.ru_utime - before.ru_stime)
    ns = ds.n.values[ds.n.values > 0]
    n = int(np.bincount(ns).argmax())
    digest = hashlib.sha256()
    for name in sorted(ds.variables):
        digest.update(name.encode())
        digest.update(np.ascontiguousarray(ds[name].values).tobytes())
    digest.update(repr(sorted(ds.attrs.items())).encode())
    print(wall, cpu, n, np.mean(ns == n), digest.hexdigest())


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
        against_lu(*(int(a) for a in sys.argv[2:4]))
    elif len(sys.argv) > 1 and sys.argv[1] == "--one-map":
        one_map(int(sys.argv[2]))
    else:
        main(int(sys.argv[1]) if len(sys.argv) > 1 else 100)
