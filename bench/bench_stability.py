"""The cost of a stability verdict: one point, and a map with and without it.

Run: ``python bench/bench_stability.py [--workers W] [--no-points] [--map N|NxM ...]``.  A
benchmark, not a test: it prints tables and asserts nothing. For each case the steady solution
is solved first (not timed), then ``thermocontact.stability`` with its defaults (n = 12, Re b
>= 1e-3, |b| <= 1e6) is timed five times: fresh (a new process's first verdict, its own wall
and processor time: imports done, the modules ``thermocontact.stability`` loads on first use
among them, and the steady contact solved before the clock starts, everything the verdict
builds on the clock), cold (the per-process caches cleared: the kernel
table built, every kernel evaluated), a neighbour (the point at 1.05 Pe next: the table and
the half-plane's kernel moments kept, the cylinder's evaluated anew, as for the first point of
a map's row or a new point of a path), warm (the same point again: every kernel's moments
kept, the floor: the assembly, the determinants, Newton's method) and along (the point at 1.05
fHPe, the same Pe: the cylinder's moments kept where the samples repeat, as for the next point
of a map's row); wall and CPU time, and the evaluations of M(b). Then for each shape a map
(``N``: N x N, default 4 x 4; ``NxM``: N values of fHPe, M of Pe, long rows of constant Pe as
in a large map) over fHPe and Pe with and without ``stability=True``, both on the same ``W``
workers (default 1: this process; the stability's rows run there too), after a 2 x 2 map,
which pays for the first calls, the caches cleared before each, and the ratio of their times.
BLAS is limited to one thread (the products are small; threads only compete on a shared
machine).
"""

from __future__ import annotations

import subprocess
import sys
import time

import thermocontact as tc

CASES = {
    "Fig. 4: Pe=5 fHPe=0.2 K2/K1=10 lam=-1": dict(pe=5, fhpe=0.2, K2_over_K1=10, lam=-1),
    "past the fold: Pe=fHPe=1.5 K2/K1=1 lam=1": dict(pe=1.5, fhpe=1.5, K2_over_K1=1, lam=1),
    "Fig. 3: Pe=1 fHPe=0.5 K2/K1=10 lam=-1": dict(pe=1, fhpe=0.5, K2_over_K1=10, lam=-1),
    "path (b): Pe=10 fHPe=0.33 K2/K1=100 lam=1": dict(pe=10, fhpe=0.331226, K2_over_K1=100,
                                                      lam=1),
}


def timed(func):
    w0, c0 = time.perf_counter(), time.process_time()
    out = func()
    return out, time.perf_counter() - w0, time.process_time() - c0


FRESH = """
import sys, time
from thermocontact.execution.executors import one_blas_thread
with one_blas_thread():
    import thermocontact as tc
    # What tc.stability imports on its first call.
    import thermocontact.api, thermocontact.solvers.stability
    import thermocontact.studies.contact_sets, thermocontact.studies.physical_contact
    sol = tc.solve(**{kw})
    w0, c0 = time.perf_counter(), time.process_time()
    tc.stability(sol)
    print(time.perf_counter() - w0, time.process_time() - c0)
"""


def fresh(kw):
    """A new process's first verdict of the contact ``kw``: wall and processor time."""
    out = subprocess.run([sys.executable, "-c", FRESH.format(kw=kw)], capture_output=True,
                         text=True, check=True).stdout.split()
    return float(out[0]), float(out[1])


def one_point():
    print(f"{'case':44s} {'verdict':>7s} {'modes':>5s} {'evals':>5s} {'fresh wall/cpu':>14s} "
          f"{'cold wall/cpu':>14s} {'neighbour wall/cpu':>18s} {'warm wall/cpu':>14s} "
          f"{'along wall/cpu':>14s}")
    for name, kw in CASES.items():
        w_fresh, c_fresh = fresh(kw)
        sol = tc.solve(**kw)
        near = tc.solve(**{**kw, "pe": 1.05 * kw["pe"]})
        along = tc.solve(**{**kw, "fhpe": 1.05 * kw["fhpe"]})
        tc.clear_caches()
        res, w_cold, c_cold = timed(lambda: tc.stability(sol))
        _, w_near, c_near = timed(lambda: tc.stability(near))
        _, w_warm, c_warm = timed(lambda: tc.stability(sol))
        _, w_along, c_along = timed(lambda: tc.stability(along))
        print(f"{name:44s} {str(res.stable):>7s} {res.unstable_modes!s:>5s} "
              f"{res.evaluations:5d} {w_fresh:6.2f}s/{c_fresh:5.2f}s "
              f"{w_cold:6.2f}s/{c_cold:5.2f}s "
              f"{w_near:10.2f}s/{c_near:5.2f}s {w_warm:6.2f}s/{c_warm:5.2f}s "
              f"{w_along:6.2f}s/{c_along:5.2f}s")


def a_map(shape, workers=1):
    """The map of ``shape`` "N" (N x N) or "NxM" (N values of fHPe, M of Pe), with and
    without its stability, on the same ``workers``."""
    nx, ny = (int(v) for v in (shape.split("x") if "x" in shape else (shape, shape)))
    axes = (tc.Axis("fhpe", 0.1, 0.6, nx), tc.Axis("pe", 1.0, 10.0, ny, log=True))
    kw = dict(K2_over_K1=10, lam=1, tol=1e-6, workers=workers)
    # The process's first map pays for imports and first calls that any later map does
    # not (0.3 s against 0.9 s of CPU for the 6 x 6 map): a 2 x 2 map first.
    tc.parameter_map(tc.Axis("fhpe", 0.1, 0.2, 2), tc.Axis("pe", 1.0, 2.0, 2), **kw)
    tc.clear_caches()
    _, plain, plain_cpu = timed(lambda: tc.parameter_map(*axes, **kw))
    tc.clear_caches()
    ds, with_it, with_cpu = timed(lambda: tc.parameter_map(*axes, stability=True, **kw))
    points = nx * ny
    print(f"\n{nx} x {ny} map over fHPe in [0.1, 0.6], Pe in [1, 10] (K2/K1 = 10, lam = 1), "
          f"{workers} worker{'s' * (workers != 1)} (cpu: this process's)")
    print(f"  without stability: {plain:8.2f} s wall, {plain_cpu:8.2f} s cpu "
          f"({1e3 * plain / points:.1f} ms a point)")
    print(f"  with stability:    {with_it:8.2f} s wall, {with_cpu:8.2f} s cpu "
          f"({1e3 * with_it / points:.1f} ms a point)")
    print(f"  ratio {with_it / plain:.1f} (wall), {with_cpu / plain_cpu:.1f} (cpu); "
          f"verdicts: {int((ds['stable'] == 1).sum())} stable, "
          f"{int((ds['stable'] == 0).sum())} unstable, "
          f"{int((ds['stable'] == -2).sum())} not certified")


def main(argv):
    workers = 1
    if "--workers" in argv:
        at = argv.index("--workers")
        workers = int(argv[at + 1])
        argv = argv[:at] + argv[at + 2:]
    points = "--no-points" not in argv
    argv = [a for a in argv if a != "--no-points"]
    shapes = argv[argv.index("--map") + 1:] if "--map" in argv else ["4"]
    if points:
        one_point()
    for shape in shapes:
        a_map(shape, workers)


if __name__ == "__main__":
    from thermocontact.execution.executors import one_blas_thread

    with one_blas_thread():
        main(sys.argv[1:])
