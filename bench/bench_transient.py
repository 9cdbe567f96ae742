"""Cost of the transient contact against its number of steps, and of its history sum.

Run: ``python bench/bench_transient.py [STEPS ...]`` (default 250 500 1000 2000 4000).
A benchmark, not a test: it prints two markdown tables and asserts nothing.

* ``thermocontact.api.transient`` (Pe_l = 5.43, fHPe_l = 0.75, K2/K1 = 10, lambda = 1,
  240 elements, ``dt = 0.005``, so ``until = 0.005 steps``), one cold run per row (the
  lag tables' cache cleared), split into the lag tables (:func:`lag_tables`, both
  bodies), the rest of the operators (the tables' spatial FFTs and the current step's
  matrices) and the stepping (everything after the operators: the set solves, the
  online history, the records).
* The history sum alone, with the same kernels as the run (both bodies, two outputs
  and the spatial modes): :class:`OnlineConvolution` against the direct ``O(L^2)``
  sum ``y[n] = sum_{m=1}^{n-1} A[m] x[n - m]`` for random complex inputs, their time
  ratio and their largest difference relative to the largest history.

Wall times on a shared machine vary with its load; the stepping's CPU time (this
process, all its threads) is given beside them.  The last rows give each cost's growth
exponent against ``L`` (the least-squares slope of ``log cost`` against ``log L``, and
the slope between the last two rows).
"""

from __future__ import annotations

import sys
import time

import numpy as np

CASE = dict(pe_hertz=5.43, fhpe_hertz=0.75, K2_over_K1=10.0, lam=1.0, elements=240)
DT = 0.005


class _Timed:
    """A callable wrapper adding up the time spent in ``func``."""

    def __init__(self, func):
        self.func, self.seconds, self.cpu = func, 0.0, 0.0

    def __call__(self, *args, **kwargs):
        t0, c0 = time.perf_counter(), time.process_time()
        try:
            return self.func(*args, **kwargs)
        finally:
            self.seconds += time.perf_counter() - t0
            self.cpu += time.process_time() - c0


def run_row(steps):
    """One cold transient run: (total, tables, other operators, stepping) in seconds, the
    stepping's CPU seconds, the status, and the kernels it convolved."""
    import thermocontact.api as api
    from thermocontact.discretisation import history
    from thermocontact.solvers import transient as solver

    history.TABLES.clear()
    tables = _Timed(history.lag_tables)
    operators = _Timed(history.transient_element_operators)
    kept = {}

    def operators_kept(*args, **kwargs):
        out = operators(*args, **kwargs)
        kept["kernels"] = out.kernels
        return out

    saved = history.lag_tables, solver.transient_element_operators
    history.lag_tables, solver.transient_element_operators = tables, operators_kept
    try:
        t0, c0 = time.perf_counter(), time.process_time()
        run = api.transient(until=steps * DT, steps=steps, **CASE)
        total, cpu = time.perf_counter() - t0, time.process_time() - c0
    finally:
        history.lag_tables, solver.transient_element_operators = saved
    history.TABLES.clear()
    return (total, tables.seconds, operators.seconds - tables.seconds,
            total - operators.seconds, cpu - operators.cpu, run.status, kept["kernels"])


def direct_history(kernel, x):
    """``y[n] = sum_{m=1}^{n-1} A[m] x[n - m]`` for ``n = 1 .. L``, one step at a time."""
    L = kernel.shape[0]
    A = np.ascontiguousarray(np.transpose(kernel[:, :, 0, :], (2, 1, 0)))   # (modes, out, L)
    xr = np.ascontiguousarray(x[::-1, 0, :].T)    # (modes, L + 1), xr[:, j] = x[L - j]
    y = np.zeros((L + 1, A.shape[1], A.shape[0]), dtype=complex)
    for n in range(2, L + 1):
        # x[n - m] for m = 1 .. n - 1 is xr[:, L - n + m]
        y[n] = np.matmul(A[:, :, 1:n], xr[:, L - n + 1:L, None])[:, :, 0].T
    return y


def online_history(kernel, x):
    from thermocontact.numerics.online_convolution import OnlineConvolution

    L = kernel.shape[0]
    conv = OnlineConvolution(kernel)
    y = np.zeros((L + 1, kernel.shape[1], kernel.shape[3]), dtype=complex)
    for n in range(1, L + 1):
        y[n] = conv.history(n)
        conv.push(x[n])
    return y


def history_row(kernels, seed=0):
    """Both bodies' histories: (online s, direct s, largest difference / largest value)."""
    rng = np.random.default_rng(seed)
    online = direct = 0.0
    diff = 0.0
    for kernel in kernels:
        L, _, inputs, modes = kernel.shape
        x = rng.standard_normal((L + 1, inputs, modes)) \
            + 1j * rng.standard_normal((L + 1, inputs, modes))
        t0 = time.perf_counter()
        a = online_history(kernel, x)
        online += time.perf_counter() - t0
        t0 = time.perf_counter()
        b = direct_history(kernel, x)
        direct += time.perf_counter() - t0
        diff = max(diff, np.max(np.abs(a - b)) / np.max(np.abs(b)))
    return online, direct, diff


def exponents(L, values):
    """Least-squares slope of log(values) against log(L), and the last two rows' slope."""
    lx, ly = np.log(np.asarray(L, float)), np.log(np.asarray(values, float))
    return np.polyfit(lx, ly, 1)[0], (ly[-1] - ly[-2]) / (lx[-1] - lx[-2])


def main(steps_list=(250, 500, 1000, 2000, 4000)):
    from thermocontact.execution.executors import cpu_count

    print(f"transient: Pe_l = {CASE['pe_hertz']}, fHPe_l = {CASE['fhpe_hertz']}, "
          f"K2/K1 = {CASE['K2_over_K1']}, lambda = {CASE['lam']}, "
          f"{CASE['elements']} elements, dt = {DT}; {cpu_count()} cores\n")
    rows = []
    for steps in steps_list:
        total, tables, other, stepping, cpu, status, kernels = run_row(steps)
        online, direct, diff = history_row(kernels)
        rows.append((steps, total, tables, other, stepping, online, direct, diff, status, cpu))
        print(f"  L = {steps}: {total:.1f} s, {status}", file=sys.stderr, flush=True)
    print("| L | total s | tables s | other operators s | stepping s | ms/step | "
          "stepping CPU ms/step | history online s | history direct s | direct/online | "
          "max rel. diff | status |")
    print("|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---|")
    for L, total, tables, other, stepping, online, direct, diff, status, cpu in rows:
        print(f"| {L} | {total:.2f} | {tables:.2f} | {other:.2f} | {stepping:.2f} | "
              f"{1e3 * stepping / L:.2f} | {1e3 * cpu / L:.2f} | {online:.3f} | "
              f"{direct:.3f} | {direct / online:.1f} | {diff:.1e} | {status} |")
    L = [r[0] for r in rows]
    print("\ngrowth exponent of each cost against L (least squares over all rows; "
          "last two rows):\n")
    print("| cost | exponent (fit) | exponent (last pair) |")
    print("|---|---:|---:|")
    for name, col in (("total", 1), ("tables", 2), ("other operators", 3), ("stepping", 4),
                      ("stepping CPU", 9), ("history online", 5), ("history direct", 6)):
        fit, last = exponents(L, [r[col] for r in rows])
        print(f"| {name} | {fit:.2f} | {last:.2f} |")


if __name__ == "__main__":
    main(tuple(int(a) for a in sys.argv[1:]) or (250, 500, 1000, 2000, 4000))
