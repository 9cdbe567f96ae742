"""Time per solve and the change in P_H/P between n and 2n, for n = 16 ... 256.

Run: ``python bench/bench_solve.py``.  A benchmark, not a test: it prints a table
and asserts nothing.  Times are the best of several repeats of one full
``solve`` call with the assembly cache cleared: assembly, linear solve and
validity checks at n, and the solves at n/2 and n/4 of the error estimate.
``bench/convergence.py`` times assembly and one solve separately.
"""

from __future__ import annotations

import time

from thermocontact import solve

CASES = {
    "Pe=5 K2/K1=10 (k2/k1=10)": dict(pe=5, fhpe=0.2, K2_over_K1=10, lam=-1),
    "Pe=5 K2/K1=10 k2/k1=1": dict(pe=5, fhpe=0.2, K2_over_K1=10, k2_over_k1=1, lam=-1),
    "Pe=10 K2/K1=100 (k2/k1=100)": dict(pe=10, fhpe=0.2, K2_over_K1=100, lam=-1),
    "Pe=1 K2/K1=1 lam=0": dict(pe=1, fhpe=0.3, K2_over_K1=1, lam=0),
}
NS = [16, 32, 64, 128, 256]


def best_time(func, repeats=5):
    from thermocontact import clear_caches

    best = float("inf")
    for _ in range(repeats):
        clear_caches()  # time the assembly too, not a cached one
        t0 = time.perf_counter()
        out = func()
        best = min(best, time.perf_counter() - t0)
    return best, out


def main():
    print(f"{'case':32s} {'n':>5s} {'ms/solve':>9s} {'P_H/P':>14s} {'|L(2n)-L(n)|':>13s}")
    for name, kw in CASES.items():
        for n in NS:
            t, sol = best_time(lambda: solve(n=n, **kw))
            fine = solve(n=2 * n, **kw)
            change = abs(fine.load_ratio - sol.load_ratio)
            print(f"{name:32s} {n:5d} {1e3 * t:9.2f} {sol.load_ratio:14.10f} {change:13.2e}")
        print()


if __name__ == "__main__":
    from thermocontact.execution.executors import one_blas_thread

    with one_blas_thread():
        main()
