"""The cost of a contact set's stability verdict, and of the zones' terms in it.

Run: ``python bench/bench_stability_zones.py [--repeats R]``.  A benchmark, not a test: it
prints a table and asserts nothing.  Two zones of the tilted quartic of section 14 (Pe_l = 1,
K2/K1 = 10, lam = 0.5, n = 12) at fHPe_l = 0 and 0.2, each solved first (not timed); then
``thermocontact.stability`` with its defaults, the per-process caches cleared before each,
timed in turn (interleaved, ``R`` times) with the zones' transient kernels at each other's
points interpolated on Chebyshev panels (derivation S21, the default) and evaluated at every
point (N (n + 12) arguments a pair), with wall and processor time, the evaluations of M(b)
and the verdict, and the ratio of the processor times.  BLAS is limited to one thread.
"""

from __future__ import annotations

import argparse
import time

import numpy as np
from numpy.polynomial import Polynomial

import thermocontact as tc
from thermocontact.discretisation.linearised_set import LinearisedContactSet
from thermocontact.execution.executors import one_blas_thread
from thermocontact.numerics.cache import clear_caches
from thermocontact.solvers.zones import ZoneModel

PROFILE = Polynomial([0, 0.05]) + (1 / 32) * Polynomial([-4.0, 0, 1]) ** 2


def every_point(self, b):
    """The zones' kernels at every argument (the reference the panels replace)."""
    return {pair: self._kernels(u, b) for pair, (u, _, _) in self._pairs.items()}


def verdict(sol):
    clear_caches()
    w0, c0 = time.perf_counter(), time.process_time()
    res = tc.stability(sol)
    return res, time.perf_counter() - w0, time.process_time() - c0


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--repeats", type=int, default=2)
    repeats = parser.parse_args().repeats
    panels = LinearisedContactSet._cross_kernels
    print(f"{'fHPe_l':>7} {'kernels':>12} {'wall s':>8} {'cpu s':>8} {'evals':>6} {'verdict':>8}")
    with one_blas_thread():
        for fhpe in (0.0, 0.2):
            sol = ZoneModel(10.0, n=12, profile=PROFILE).solve([[-2.6, -1.1], [1.1, 2.6]],
                                                               1.0, fhpe, 0.5)
            cpu = {"panels": [], "every point": []}
            for _ in range(repeats):
                for name, method in (("panels", panels), ("every point", every_point)):
                    LinearisedContactSet._cross_kernels = method
                    try:
                        res, wall, proc = verdict(sol)
                    finally:
                        LinearisedContactSet._cross_kernels = panels
                    cpu[name].append(proc)
                    print(f"{fhpe:7.2f} {name:>12} {wall:8.2f} {proc:8.2f} "
                          f"{res.evaluations:6d} {res.status:>8}")
            print(f"{'':7} cpu ratio (every point / panels, medians): "
                  f"{np.median(cpu['every point']) / np.median(cpu['panels']):.2f}")


if __name__ == "__main__":
    main()
