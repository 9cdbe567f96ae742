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
the same COUNT x COUNT map on a process pool of 2 workers against the LAPACK work of
the linear systems it solves, its *floor*: first the map is solved once in one process
with LAPACK's solver watched (not timed), which records every system that the grid
lines' stacks hand to LAPACK (every level of every point's refinement in ``n``, the
events' solves, the refinements to n = 64; their sizes and counts) and keeps the first
64 matrices and right-hand sides of each size as they are handed over (equilibrated,
in LAPACK's order).  The floor is then as many ``dgesv`` calls (``getrf`` and
``getrs`` in one) of those sizes, cycling through the kept matrices, on copies made
beforehand outside the timing, overwritten in place, without finiteness checks: the
LAPACK work alone.  REPEATS maps, each in a fresh process of its own, run between
REPEATS + 1 floor loops (the machine's speed drifts: each map's ratio is taken to the
mean of the loops on either side of it).  It prints each map's times and ratio, in
wall time and in CPU time (the workers' and the map's own process's against the floor
loop's: on a shared machine the less disturbed measure), and the median ratios, the
run's measure (one repeat disturbed by the host does not make it); the maps must be
identical (a digest of every variable and attribute), or no ratio is given.  Then a
quarter of the floor pinned to each core in turn, to show how far the cores' speeds
differ during the run.  (Before 2026-11-28 the floor was ``lu_solve(lu_factor(A), b)``
at SciPy's defaults, which check every entry for finiteness and copy the matrix, for
COUNT^2 systems of the most frequent size only: 1.6 times the processor time of the
LAPACK work at 66 unknowns here, and not the systems the map solves.)
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
    from thermocontact.studies.maps import compute_map

    spec = map_spec(count)
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


#: Matrices kept per size by :func:`systems` (the floor cycles through them).
KEPT = 64
#: Systems per timed block of the floor (their copies made before it).
BLOCK = 256


def systems(count):
    """``{size: (solves, matrices, right-hand sides)}``: every system the map's grid
    lines hand to LAPACK (``gesv``, or ``getrf`` above its size limit), counted by size,
    and the first :data:`KEPT` of each size as handed over, the map solved once in this
    process (one BLAS thread, as a worker)."""
    from thermocontact.execution.executors import one_blas_thread

    import thermocontact.numerics.dense as sp
    from thermocontact.studies.maps import compute_map

    seen, inside = {}, [False]
    chunk, gesv, getrf = sp._solve_chunk, sp.dgesv, sp.dgetrf

    def record(a, b):
        k = a.shape[0]
        solves, mats, rhs = seen.setdefault(k, [0, [], []])
        seen[k][0] = solves + 1
        if len(mats) < KEPT:
            mats.append(np.array(a, order="F"))
            rhs.append(np.zeros(k) if b is None else np.array(b))

    def watched_chunk(A0t, A1t, b, *args, **kwargs):
        inside[0] = True
        try:
            return chunk(A0t, A1t, b, *args, **kwargs)
        finally:
            inside[0] = False

    def watched_gesv(a, b, **kwargs):
        if inside[0]:
            record(a, b)
        return gesv(a, b, **kwargs)

    def watched_getrf(a, **kwargs):
        if inside[0]:
            record(a, None)
        return getrf(a, **kwargs)
    sp._solve_chunk, sp.dgesv, sp.dgetrf = watched_chunk, watched_gesv, watched_getrf
    try:
        with one_blas_thread():
            compute_map(map_spec(count), workers=1)
    finally:
        sp._solve_chunk, sp.dgesv, sp.dgetrf = chunk, gesv, getrf
    return {k: (v[0], np.array(v[1]), np.array(v[2])) for k, v in sorted(seen.items())}


def floor_time(found, fraction=1.0):
    """``(wall, CPU)`` seconds of the LAPACK work of the systems ``found``
    (:func:`systems`; ``fraction`` of each size's count): ``dgesv`` on each, in place
    (``overwrite_a``, ``overwrite_b``), no checks; the copies it overwrites are made
    before each block of :data:`BLOCK` solves, outside the timing."""
    from scipy.linalg.lapack import dgesv

    wall = cpu = 0.0
    for k, (solves, mats, rhs) in found.items():
        solves = int(round(fraction * solves))
        # Each matrix stored transposed, C-contiguous: its transpose is in LAPACK's
        # (Fortran) order, as the map hands it over.
        A = np.empty((min(BLOCK, solves), k, k))
        B = np.empty((min(BLOCK, solves), k))
        for start in range(0, solves, BLOCK):
            m = min(BLOCK, solves - start)
            for j in range(m):
                A[j] = mats[(start + j) % len(mats)].T
                B[j] = rhs[(start + j) % len(rhs)]
            c0, t0 = time.process_time(), time.perf_counter()
            for j in range(m):
                dgesv(A[j].T, B[j], overwrite_a=True, overwrite_b=True)
            wall += time.perf_counter() - t0
            cpu += time.process_time() - c0
    return wall, cpu


def map_spec(count):
    from thermocontact.studies.maps import MapSpec, parse_axis

    return MapSpec(parse_axis("--x", f"fhpe:0:0.8:{count}"),
                   parse_axis("--y", f"pe:0.5:100:{count}:log"),
                   {"K2_over_K1": 10.0, "lam": 1.0}, tol=1e-6)


def against_lu(count=200, repeats=3):
    """The map on 2 workers against the LAPACK work of its systems, ``repeats`` times:
    floor, map, floor, map, ..., floor, each map's ratio taken to the mean of the floor
    loops on either side of it; the median ratio is the run's."""
    import os

    if repeats < 1:
        sys.exit(f"bench_map.py: REPEATS must be at least 1, got {repeats}")
    load = os.getloadavg()[0]
    found = systems(count)
    total = sum(v[0] for v in found.values())
    print(f"{count} x {count} map: {total} systems handed to LAPACK, by unknowns: "
          + ", ".join(f"{k}: {v[0]}" for k, v in found.items()))
    lu = [floor_time(found)]
    maps, digests = [], set()
    for _ in range(repeats):
        # Each map in a process of its own, as the first map of a run would be (the
        # modules of this package imported; xarray's first dataset not yet made).
        done = subprocess.run([sys.executable, __file__, "--one-map", str(count)],
                              capture_output=True, text=True)
        if done.returncode != 0:
            sys.exit(f"bench_map.py: the map's process failed:\n{done.stderr}")
        out = done.stdout.split()
        wall, cpu, digest = float(out[0]), float(out[1]), out[2]
        maps.append((wall, cpu))
        digests.add(digest)
        lu.append(floor_time(found))
    if len(digests) > 1:
        print("the repeats' maps differ: no ratio")
        return
    print(f"the map on 2 workers against its floor in one process; each map between two "
          "floor loops, its ratio taken to their mean:")
    ratios, cpu_ratios = [], []
    for r, (wall, cpu) in enumerate(maps):
        t_lu = 0.5 * (lu[r][0] + lu[r + 1][0])
        cpu_lu = 0.5 * (lu[r][1] + lu[r + 1][1])
        ratios.append(wall / t_lu)
        cpu_ratios.append(cpu / cpu_lu)
        print(f"  map {wall:5.1f} s (CPU {cpu:5.1f} s), floor {lu[r][0]:.2f} s before "
              f"(CPU {lu[r][1]:.2f} s), {lu[r + 1][0]:.2f} s after (CPU {lu[r + 1][1]:.2f} "
              f"s): ratio {ratios[-1]:.1f}, CPU ratio {cpu_ratios[-1]:.1f}")
    # On a machine shared with other work a single run's wall times depend on the load;
    # the median of the repeats does much less (and the CPU times less still: a ratio
    # of at most 6 in wall time on 2 busy workers is one of at most 12 in CPU time).
    print(f"median ratio {np.median(ratios):.1f} (CPU {np.median(cpu_ratios):.1f}); the maps "
          f"are identical; load average before {load:.2f}, after {os.getloadavg()[0]:.2f} "
          "(2 cores)")
    cores = per_core_floor(found, 0.25)
    if cores:
        print("a quarter of the floor pinned to each core in turn: "
              + ", ".join(f"core {c} {t:.2f} s" for c, t in cores.items())
              + f" (the slowest {max(cores.values()) / min(cores.values()) - 1:.0%} slower: "
              "the map runs on every core, the floor on one)")


def one_map(count):
    """Print the wall and CPU seconds of the map on 2 workers (the workers', ended and
    waited for, and this process's) and a digest of the whole dataset."""
    import hashlib
    import resource

    from thermocontact.studies.maps import compute_map

    spec = map_spec(count)
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    c0, t0 = time.process_time(), time.perf_counter()
    ds = compute_map(spec, workers=2)
    wall = time.perf_counter() - t0
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    cpu = (time.process_time() - c0 + after.ru_utime + after.ru_stime
           - before.ru_utime - before.ru_stime)
    digest = hashlib.sha256()
    for name in sorted(ds.variables):
        digest.update(name.encode())
        digest.update(np.ascontiguousarray(ds[name].values).tobytes())
    digest.update(repr(sorted(ds.attrs.items())).encode())
    print(wall, cpu, digest.hexdigest())


def per_core_floor(found, fraction):
    """``{core: seconds}`` of ``fraction`` of the floor in this process pinned to each
    core it may use in turn (empty where affinity cannot be set): on a shared machine
    the cores' speeds can differ for minutes at a time."""
    import os

    if not hasattr(os, "sched_setaffinity"):
        return {}
    allowed = sorted(os.sched_getaffinity(0))
    out = {}
    try:
        for core in allowed:
            os.sched_setaffinity(0, {core})
            out[core] = floor_time(found, fraction)[0]
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
