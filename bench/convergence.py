"""Convergence and cost of the "paper", "product", "galerkin" and "graded" methods against a fine reference.

Run: ``python bench/convergence.py [--out-dir DIR] [--paper-max-n N] [--no-plot]``.

For a fixed set of cases (all ``lam = -1``, ``fhpe = 0.2``) it measures, for each
method and ``n = 16, 32, ..., 512`` (the paper method also 1024; the graded method
``n = 8 ... 512``),

* ``P_H/P`` and ``sigma/Delta`` and their relative errors against a reference
  solution, each relative to ``max(|reference|, 0.01)``;
* wall times of the assembly (``METHODS[method].assemble(par, n)``), of the linear solve
  (``solve_system`` without validity) and of the validity checks (``assess``),
  separately, and of a first assembly at ``n`` in the process (below).

The reference is the graded method at ``n = 1024``.  Its own error is estimated
as ``|x(1024) - x(512)|`` (the larger of the two quantities, relative as above),
conservative for a method that converges faster than order 5, and it is checked
against a second method, graded collocation at ``n = 512``.  No error is given for
the reference row itself.  The default solve (automatic ``n``) is compared with the
reference for every case.

Times are the best of several repeats for small ``n`` (one for large ``n``), the
minimum taken separately for each part; ``t_total_s`` is assembly plus linear
solve, the cost of one solve to the error shown.  Tables that depend on ``n`` only
(the graded point geometry, the common quadrature rules) are built once per ``n``
in a process and reused by every later solve at that ``n``: the repeats measure
that steady state, and ``t_first_assembly_s`` the first repeat, started without
the graded point geometry.  ``solve()`` is not timed: it also solves coarser levels for its
error estimate, so a call of it costs more than one ``solve_system``.

Output: a table and a summary of the accuracy targets on stdout, progress on
stderr, ``convergence.csv`` and ``convergence.png`` in ``--out-dir`` (default: the
repository's ``docs``).  On Ctrl-C the rows finished so far are written to the CSV.
A benchmark, not a test: it asserts nothing.
"""

from __future__ import annotations

import argparse
import csv
import datetime
import math
import os
import platform
import subprocess
import sys
import time
from dataclasses import replace
from pathlib import Path

import numpy as np

import thermocontact
from thermocontact import METHODS, Parameters, SolveError
from thermocontact.solvers.refinement import error_estimate
from thermocontact.solvers.single_patch import solve_system
from thermocontact.analysis.validity import assess
from thermocontact.discretisation.representations import ROWS

LAM = -1.0
FHPE = 0.2
#: (label, pe, K2/K1, k2/k1 or None for k2/k1 = K2/K1)
CASES = [
    ("Pe=5 K2/K1=10", 5.0, 10.0, None),
    ("Pe=10 K2/K1=10", 10.0, 10.0, None),
    ("Pe=5 K2/K1=100", 5.0, 100.0, None),
    ("Pe=10 K2/K1=100", 10.0, 100.0, None),
    ("Pe=100 K2/K1=10", 100.0, 10.0, None),
    ("Pe=1000 K2/K1=100", 1000.0, 100.0, None),
    ("Pe=1000 K2/K1=1000", 1000.0, 1000.0, None),
    ("Pe=5 K2/K1=10 k2/k1=1", 5.0, 10.0, 1.0),
]
METHOD_ORDER = ("paper", "product", "galerkin", "graded")
#: The method the targets are judged on (the package default).
DEFAULT = "graded"
NS = [16, 32, 64, 128, 256, 512]
NS_GRADED = [8, 16, 32, 64, 128, 256, 512]
REF_METHOD, REF_N = "graded", 1024
CHECK_METHOD, CHECK_N = "graded-collocation", 512
#: Reference considered converged up to this Pe (all: see the reference check).
PE_REF_CONVERGED = math.inf
TARGETS = (1e-6, 1e-8)
#: Target 1: error < 1e-8 with n <= 256 for Pe <= 10, K2/K1 <= 100.
T1 = dict(tol=1e-8, n_max=256, pe_max=10.0, K_max=100.0)
#: Target 2: error < 1e-6 with n <= 1024 for Pe <= 1000.
T2 = dict(tol=1e-6, n_max=1024, pe_max=1000.0)
#: Target 3: one solve to 1e-8 under 20 ms.
T3_SECONDS = 0.020
COLUMNS = ["case", "method", "n", "load_ratio", "sigma_over_delta", "err_load_ratio",
           "err_sigma", "t_first_assembly_s", "t_assembly_s", "t_solve_s", "t_total_s",
           "t_validity_s"]
_T0 = time.perf_counter()


def progress(msg):
    """Print ``msg`` to stderr with the elapsed time."""
    print(f"[{time.perf_counter() - _T0:7.1f} s] {msg}", file=sys.stderr, flush=True)


def repeats_for(n):
    """Number of timing repeats at ``n``: more for cheap small systems."""
    return 5 if n <= 64 else 3 if n <= 256 else 1


def clear_point_caches():
    """Forget the per-``n`` point geometry of the graded moments (a first call's cost)."""
    from thermocontact.numerics import moment_engine as graded

    graded.clear_geometry()


def timed_solve(par, method, n, repeats):
    """Assemble, solve and check validity ``repeats`` times; best times of each part.

    The first repeat starts without the graded point geometry, which depends on
    ``n`` only and is built once per ``n`` in a process: its assembly time is
    reported as the first call's.  Later repeats reuse it, as every solve at the
    same ``n`` does (other parameters, sweeps, the levels of the error estimate).

    Returns
    -------
    sol : ContactSolution
    t_first, t_assembly, t_solve, t_validity : float
        Seconds: the first assembly, then each part's minimum over the repeats.
    """
    t_first = t_asm = t_sol = t_val = math.inf
    sol = None
    clear_point_caches()
    for i in range(repeats):
        ROWS.clear()  # the validity checks' row operators, cached per process
        t0 = time.perf_counter()
        blocks = METHODS[method].assemble(par, n)
        t1 = time.perf_counter()
        sol = solve_system(par, blocks, method, lam=LAM, check_validity=False)
        t2 = time.perf_counter()
        validity = assess(par, blocks.representation, sol.phi, sol.psi, sol.load_ratio,
                          sol.sigma_over_delta, sol.lam)
        t3 = time.perf_counter()
        if i == 0:
            t_first = t1 - t0
        t_asm, t_sol, t_val = min(t_asm, t1 - t0), min(t_sol, t2 - t1), min(t_val, t3 - t2)
    return replace(sol, validity=validity), t_first, t_asm, t_sol, t_val


def rel_err(x, ref):
    """``|x - ref| / max(|ref|, 0.01)``, as in the solver's error estimate."""
    return abs(x - ref) / max(abs(ref), 0.01)


def make_row(label, method, n, sol, times, ref):
    """One CSV row; ``ref`` is the reference solution or None (the reference row).

    ``times`` = (first assembly, assembly, linear solve, validity) in seconds.
    """
    t_first, t_asm, t_sol, t_val = times
    if sol is None:
        L = s = eL = es = math.nan
    else:
        L, s = sol.load_ratio, sol.sigma_over_delta
        eL = es = math.nan
        if ref is not None:
            eL, es = rel_err(L, ref.load_ratio), rel_err(s, ref.sigma_over_delta)
    return dict(case=label, method=method, n=n, load_ratio=L, sigma_over_delta=s,
                err_load_ratio=eL, err_sigma=es, t_first_assembly_s=t_first,
                t_assembly_s=t_asm, t_solve_s=t_sol, t_total_s=t_asm + t_sol,
                t_validity_s=t_val)


def err_max(row):
    """Larger of the two relative errors of a row (NaN if unknown)."""
    return max(row["err_load_ratio"], row["err_sigma"])


def run_case(label, pe, K, k, paper_max_n, rows, refinfo):
    """Measure one case, appending to ``rows``; reference data go to ``refinfo``."""
    par = Parameters(pe, FHPE, K, k)
    t_case = time.perf_counter()
    ref, *ref_times = timed_solve(par, REF_METHOD, REF_N, 1)
    ref_row = make_row(label, REF_METHOD, REF_N, ref, ref_times, None)
    check, *_ = timed_solve(par, CHECK_METHOD, CHECK_N, 1)
    check_diff = max(rel_err(check.load_ratio, ref.load_ratio),
                     rel_err(check.sigma_over_delta, ref.sigma_over_delta))
    progress(f"{label}: reference {REF_METHOD} n={REF_N} "
             f"({ref_times[1]:.2f} s assembly, {ref_times[2]:.2f} s solve); {CHECK_METHOD} differs by "
             f"{check_diff:.1e}")
    t0 = time.perf_counter()
    auto = thermocontact.solve(pe, FHPE, K, k2_over_k1=k, lam=LAM)
    t_auto = time.perf_counter() - t0
    auto_err = max(rel_err(auto.load_ratio, ref.load_ratio),
                   rel_err(auto.sigma_over_delta, ref.sigma_over_delta))
    sols = {}
    for method in METHOD_ORDER:
        t_m = time.perf_counter()
        ns = NS_GRADED if method == "graded" else NS
        ns = ns + ([n for n in (1024,) if n <= paper_max_n] if method == "paper" else [])
        for n in ns:
            try:
                sol, *times = timed_solve(par, method, n, repeats_for(n))
            except SolveError as exc:
                progress(f"{label}: {method} n={n} failed: {exc}")
                sol, times = None, [math.nan] * 4
            rows.append(make_row(label, method, n, sol, times, ref))
            sols[method, n] = sol
        if method == REF_METHOD:
            rows.append(ref_row)
        progress(f"{label}: {method:7s} n={ns[0]}..{ns[-1]} done "
                 f"({time.perf_counter() - t_m:.1f} s)")
    # Reference error: conservative |x(n_ref) - x(n_ref/2)|, and the solver's own
    # Richardson estimate from n_ref/4, n_ref/2, n_ref.
    fine = sols.get((REF_METHOD, REF_N // 2))
    conservative = richardson = math.nan
    if fine is not None:
        conservative = max(rel_err(fine.load_ratio, ref.load_ratio),
                           rel_err(fine.sigma_over_delta, ref.sigma_over_delta))
        levels = [sols.get((REF_METHOD, REF_N // 4)), fine, ref]
        if all(lv is not None for lv in levels):
            richardson = error_estimate(levels)
    refinfo[label] = dict(pe=pe, K=K, k=k, sol=ref, conservative=conservative,
                          richardson=richardson, converged=pe <= PE_REF_CONVERGED,
                          check=check_diff, auto=auto, auto_err=auto_err, t_auto=t_auto)
    progress(f"{label}: done ({time.perf_counter() - t_case:.1f} s)")


def header_lines():
    """Provenance for the CSV header comment."""
    try:
        commit = subprocess.run(["git", "rev-parse", "--short", "HEAD"],
                                cwd=Path(__file__).resolve().parent, capture_output=True,
                                text=True, timeout=10).stdout.strip() or "unknown"
    except (OSError, subprocess.SubprocessError):
        commit = "unknown"
    proc = platform.processor() or platform.machine() or "unknown"
    # BLAS threading changes the timings a lot on small machines: record it.
    threads = "BLAS limited to 1 thread (threadpoolctl)"
    return (f"# thermocontact convergence benchmark; commit {commit}; "
            f"thermocontact {thermocontact.__version__}; "
            f"date {datetime.datetime.now().isoformat(timespec='seconds')}; "
            f"machine {proc}, {os.cpu_count()} cpus, {platform.system()}; "
            f"python {platform.python_version()}, numpy {np.__version__}; "
            f"{threads}; "
            f"lam={LAM:g} fhpe={FHPE:g}; reference {REF_METHOD} n={REF_N} "
            f"(its row has no errors)")


def write_csv(path, rows, refinfo):
    """Write ``rows`` with the provenance and reference-error comment lines."""
    path.parent.mkdir(parents=True, exist_ok=True)
    with open(path, "w", newline="") as fh:
        fh.write(header_lines() + "\n")
        for label, info in refinfo.items():
            fh.write(f"# reference error estimate {label}: |x({REF_N})-x({REF_N // 2})| "
                     f"{info['conservative']:.2e}, Richardson {info['richardson']:.2e}, "
                     f"{CHECK_METHOD} n={CHECK_N} differs by {info['check']:.2e}; default "
                     f"solve n={info['auto'].n} error {info['auto_err']:.2e} "
                     f"(estimate {info['auto'].error_estimate:.2e}, "
                     f"{1e3 * info['t_auto']:.0f} ms)\n")
        writer = csv.DictWriter(fh, fieldnames=COLUMNS)
        writer.writeheader()
        for r in rows:
            writer.writerow({c: ("" if isinstance(v, float) and math.isnan(v) else
                                 f"{v:.16g}" if isinstance(v, float) else v)
                             for c, v in r.items()})


def series(rows, label, method):
    """Measured (n, max error, row) of one case and method, n ascending."""
    out = [(r["n"], err_max(r), r) for r in rows
           if r["case"] == label and r["method"] == method and not math.isnan(err_max(r))]
    return sorted(out, key=lambda t: t[0])


def first_reached(pts, tol):
    """Index of the first point from which the error stays below ``tol``, or None."""
    idx = None
    for i in range(len(pts) - 1, -1, -1):
        if pts[i][1] < tol:
            idx = i
        else:
            break
    return idx


def time_to_reach(pts, tol):
    """Total time to reach ``tol``, interpolated in log-log; (time, exact) or None.

    ``exact`` is False when already the coarsest point is below ``tol`` (the time is
    then an upper bound).
    """
    i = first_reached(pts, tol)
    if i is None:
        return None
    t1, e1 = pts[i][2]["t_total_s"], pts[i][1]
    if i == 0:
        return t1, False
    t0, e0 = pts[i - 1][2]["t_total_s"], pts[i - 1][1]
    if e1 <= 0.0 or e0 <= e1:
        return t1, True
    frac = (math.log(tol) - math.log(e0)) / (math.log(e1) - math.log(e0))
    return math.exp(math.log(t0) + frac * (math.log(t1) - math.log(t0))), True


def fmt_time(res):
    if res is None:
        return "not reached"
    t, exact = res
    return f"{'' if exact else '<='}{1e3 * t:.1f} ms"


def print_table(rows, refinfo):
    """The measured table, one block per case."""
    print(f"{'method':8s} {'n':>5s} {'P_H/P':>16s} {'sigma/Delta':>16s} {'err P_H/P':>10s} "
          f"{'err sigma':>10s} {'t_asm ms':>9s} {'t_solve ms':>10s} {'t_total ms':>10s} "
          f"{'1st asm ms':>10s} {'valid. ms':>9s}")
    for label, info in refinfo.items():
        ref = info["sol"]
        note = "" if info["converged"] else "  NOT CONVERGED"
        print(f"\n{label}: reference P_H/P = {ref.load_ratio:.12f}, "
              f"sigma/Delta = {ref.sigma_over_delta:.12f}, valid = {ref.valid}; "
              f"ref. error <= {info['conservative']:.1e} (|x({REF_N})-x({REF_N // 2})|), "
              f"Richardson {info['richardson']:.1e}, {CHECK_METHOD} differs by "
              f"{info['check']:.1e}{note}\n  default solve: n = {info['auto'].n}, error "
              f"{info['auto_err']:.1e}, estimate {info['auto'].error_estimate:.1e}, "
              f"{1e3 * info['t_auto']:.0f} ms (all levels, validity included)")
        for r in rows:
            if r["case"] != label:
                continue
            e = [("      ref" if r["method"] == REF_METHOD and r["n"] == REF_N else
                  "      nan") if math.isnan(x) else f"{x:10.2e}"
                 for x in (r["err_load_ratio"], r["err_sigma"])]
            print(f"{r['method']:8s} {r['n']:5d} {r['load_ratio']:16.12f} "
                  f"{r['sigma_over_delta']:16.12f} {e[0]:>10s} {e[1]:>10s} "
                  f"{1e3 * r['t_assembly_s']:9.2f} {1e3 * r['t_solve_s']:10.2f} "
                  f"{1e3 * r['t_total_s']:10.2f} {1e3 * r['t_first_assembly_s']:10.2f} "
                  f"{1e3 * r['t_validity_s']:9.2f}")


def print_summary(rows, refinfo):
    """Time to reach each target per method, and PASS/FAIL of the targets."""
    print("\nTime (total, one assembly + solve) to reach a relative error, "
          "interpolated in log-log between measured n;\n'reached' means the error "
          "stays below the target for every larger measured n.")
    for label, info in refinfo.items():
        parts = []
        for tol in TARGETS:
            res = {m: time_to_reach(series(rows, label, m), tol) for m in METHOD_ORDER}
            if res["paper"] and res[DEFAULT]:
                ratio = f"{res['paper'][0] / res[DEFAULT][0]:.1f}"
            elif res[DEFAULT]:
                pts = series(rows, label, "paper")
                tmax = max((p[2]["t_total_s"] for p in pts), default=math.nan)
                ratio = f">{tmax / res[DEFAULT][0]:.1f}"
            else:
                ratio = "n/a"
            flag = " (below ref. error)" if tol <= info["conservative"] else ""
            times = ", ".join(f"{m} {fmt_time(res[m])}" for m in METHOD_ORDER)
            parts.append(f"{tol:.0e}{flag}: {times}, paper/{DEFAULT} {ratio}")
        print(f"  {label}:\n      " + "\n      ".join(parts))

    print(f"\nTargets (for the default method, {DEFAULT}; paper shown for comparison):")
    all_ok = True
    for label, info in refinfo.items():
        pe, K = info["pe"], info["K"]
        pts = {m: series(rows, label, m) for m in METHOD_ORDER}

        def n_reached(method, tol):
            i = first_reached(pts[method], tol)
            return None if i is None else pts[method][i][0]

        if pe <= T1["pe_max"] and K <= T1["K_max"]:
            n_p, n_pp = n_reached(DEFAULT, T1["tol"]), n_reached("paper", T1["tol"])
            ok = n_p is not None and n_p <= T1["n_max"]
            all_ok &= ok
            print(f"  [{'PASS' if ok else 'FAIL'}] {label}: error < 1e-8 with n <= 256: "
                  f"{DEFAULT} n = {n_p or 'not reached'} (paper: {n_pp or 'not reached'})")
            if n_p is not None:
                r = next(p[2] for p in pts[DEFAULT] if p[0] == n_p)
                ok3 = r["t_total_s"] < T3_SECONDS
                all_ok &= ok3
                interp = time_to_reach(pts[DEFAULT], T1["tol"])
                print(f"  [{'PASS' if ok3 else 'FAIL'}] {label}: 1e-8 solve under 20 ms: "
                      f"n = {n_p} takes {1e3 * r['t_total_s']:.1f} ms = "
                      f"{1e3 * r['t_assembly_s']:.1f} assembly + "
                      f"{1e3 * r['t_solve_s']:.1f} linear solve "
                      f"(interpolated {fmt_time(interp)}); first assembly at this n "
                      f"{1e3 * r['t_first_assembly_s']:.1f} ms, validity checks "
                      f"{1e3 * r['t_validity_s']:.1f} ms")
            else:
                all_ok = False
                print(f"  [FAIL] {label}: 1e-8 solve under 20 ms: 1e-8 not reached")
        if pe <= T2["pe_max"]:
            n_p, n_pp = n_reached(DEFAULT, T2["tol"]), n_reached("paper", T2["tol"])
            ok = n_p is not None and n_p <= T2["n_max"]
            all_ok &= ok
            extra = ""
            if not ok:
                extra = (f"; at n = {REF_N} only estimated: <= {info['conservative']:.1e}"
                         f" (|x({REF_N})-x({REF_N // 2})|), Richardson {info['richardson']:.1e}")
            ref_note = "" if info["converged"] else " [reference not converged]"
            print(f"  [{'PASS' if ok else 'FAIL'}] {label}: error < 1e-6 with n <= 1024: "
                  f"{DEFAULT} n = {n_p or 'not reached'} (paper: {n_pp or 'not reached'})"
                  f"{extra}{ref_note}")
        if pe <= T1["pe_max"]:
            ok = info["auto_err"] < 1e-8
            all_ok &= ok
            print(f"  [{'PASS' if ok else 'FAIL'}] {label}: default solve (n = "
                  f"{info['auto'].n}) agrees with the reference to 1e-8: "
                  f"{info['auto_err']:.1e}")
    print(f"\nAll targets met: {'yes' if all_ok else 'NO'}")


def plot(rows, refinfo, path):
    """Error against n and against total time, one row of panels per case."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    labels = list(refinfo)
    fig, axes = plt.subplots(len(labels), 2, figsize=(10, 2.6 * len(labels)),
                             squeeze=False, sharex="col")
    style = {"paper": dict(color="tab:orange", marker="s"),
             "product": dict(color="tab:blue", marker="o"),
             "galerkin": dict(color="tab:green", marker="^"),
             "graded": dict(color="tab:purple", marker="D")}
    for row_ax, label in zip(axes, labels):
        info = refinfo[label]
        for method in METHOD_ORDER:
            pts = series(rows, label, method)
            if not pts:
                continue
            n = [p[0] for p in pts]
            e = [max(p[1], 1e-17) for p in pts]
            t = [p[2]["t_total_s"] for p in pts]
            row_ax[0].loglog(n, e, label=method, **style[method])
            row_ax[1].loglog(t, e, label=method, **style[method])
        for ax in row_ax:
            for tol in TARGETS:
                ax.axhline(tol, color="grey", lw=0.7, ls=":")
            if np.isfinite(info["conservative"]):
                ax.axhline(info["conservative"], color="tab:red", lw=0.8, ls="--",
                           label="ref. error est.")
            ax.grid(True, which="major", alpha=0.3)
        title = label + ("" if info["converged"] else " (reference not converged)")
        row_ax[0].set_title(title, fontsize=9, loc="left")
        row_ax[0].set_ylabel("max rel. error")
        row_ax[0].set_xscale("log", base=2)
        row_ax[1].axvline(T3_SECONDS, color="grey", lw=0.7, ls="-.")
    axes[0, 0].legend(fontsize=8)
    axes[-1, 0].set_xlabel("n")
    axes[-1, 1].set_xlabel("total time per solve [s] (assembly + solve)")
    fig.suptitle(f"thermocontact convergence, lam = {LAM:g}, fhpe = {FHPE:g}; "
                 f"reference {REF_METHOD} n = {REF_N}", fontsize=10)
    fig.tight_layout()
    path.parent.mkdir(parents=True, exist_ok=True)
    fig.savefig(path, dpi=110)
    plt.close(fig)


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--out-dir", type=Path,
                    default=Path(__file__).resolve().parent.parent / "docs",
                    help="where convergence.csv and convergence.png go (default: docs)")
    ap.add_argument("--paper-max-n", type=int, default=1024,
                    help="largest n of the paper method (512 or 1024, default 1024)")
    ap.add_argument("--no-plot", action="store_true", help="skip the PNG")
    args = ap.parse_args(argv)
    csv_path, png_path = args.out_dir / "convergence.csv", args.out_dir / "convergence.png"

    rows, refinfo = [], {}
    try:
        # Every row is complete when appended (its case's reference comes first).
        for label, pe, K, k in CASES:
            run_case(label, pe, K, k, args.paper_max_n, rows, refinfo)
    except KeyboardInterrupt:
        write_csv(csv_path, rows, refinfo)
        print(f"\ninterrupted: {len(rows)} finished rows written to {csv_path}",
              file=sys.stderr)
        return 130
    write_csv(csv_path, rows, refinfo)
    print_table(rows, refinfo)
    print_summary(rows, refinfo)
    if not args.no_plot:
        plot(rows, refinfo, png_path)
    progress(f"wrote {csv_path}" + ("" if args.no_plot else f" and {png_path}"))
    return 0


if __name__ == "__main__":
    from thermocontact.execution.executors import one_blas_thread

    # Small matrices on two cores: one BLAS thread is fastest (as in the CLI).
    with one_blas_thread():
        sys.exit(main())
