"""Cost of the layered thermoelastic instability against its speed goals.

Run: ``python bench/bench_tei.py``.  A benchmark, not a test: it prints one markdown
table and asserts nothing.

The worked automotive disc of docs/tei.md (grey cast iron 12 mm, organic pads 10 mm on
a steel backing plate they slip on, f = 0.4, no Dundurs term, plane strain, R = 120 mm):

* the critical-speed curve over 200 wavelengths (5 mm to 2 pi R) for both families
  (goal: 2 s): scans at every 20th wavelength, both families' run together, and
  continuations between them;
* the hot-spot table for n = 1 ... 60, both families (goal: 1 s);
* a stop from 30 m/s at 8 m/s^2 for n = 1 ... 60 (goal: 5 s);
* and, for scale, one critical speed by a scan, one neutral point by Newton's method,
  one evaluation of the dispersion function and one depth discretisation's eigenvalues.

Each row of a goal is one cold run in this process with one BLAS thread (as the
command runs), the library's caches emptied before it (``clear_caches``; the physics'
few tables of a layup, made in a few milliseconds, are kept); a row for scale is the
mean of a few runs, the first of them cold.  Each row gives its wall and CPU times
(this process) and the ratio to the goal.  On a shared machine
the wall time varies with the load; the CPU time is the one to compare.
"""

from __future__ import annotations

import math
import time

import numpy as np
from thermocontact.execution.executors import one_blas_thread


def _time(func, repeat=1):
    t0, c0 = time.perf_counter(), time.process_time()
    for _ in range(repeat):
        func()
    return (time.perf_counter() - t0) / repeat, (time.process_time() - c0) / repeat


def main():
    from thermocontact import clear_caches
    from thermocontact.discretisation.tei_depth import layup_modes
    from thermocontact.physics.tei_layers import layups
    from thermocontact.problem.materials import get_material
    from thermocontact.studies.brake_stop import stop_amplification, stop_history
    from thermocontact.studies.tei import hot_spot_table
    from thermocontact.studies.tei_layers import Layered, neutral_curves, neutral_point

    iron = get_material("cast-iron")
    pad = get_material("organic-composite-brake-block")
    radius = 0.12

    def systems():
        lay = layups(iron, pad, 0.4, dundurs=False, slider_thickness=0.012,
                     counterface_thickness=0.010)
        # A fresh layup (its caches empty) for each row.
        return [Layered(k, v) for k, v in lay.items()]

    ms = np.geomspace(2 * math.pi / (2 * math.pi * radius), 2 * math.pi / 0.005, 200)
    sy = systems()
    m = 7 / radius
    vc, b = sy[0].critical(m)
    rows = [
        ("critical-speed curve, 200 wavelengths, both families", 2.0,
         lambda: neutral_curves(systems(), ms), 1),
        ("hot-spot table n = 1 ... 60, both families", 1.0,
         lambda: hot_spot_table(systems(), radius, 1, 60), 1),
        ("stop 30 m/s at 8 m/s^2, n = 1 ... 60", 5.0,
         lambda: stop_amplification(systems(), radius, (1, 60), stop_history("30:8")), 1),
        ("one critical speed by a scan", None, lambda: systems()[0].critical(m), 3),
        ("one neutral point by Newton's method", None,
         lambda: neutral_point(sy[0], m * 1.01, vc, b.imag * 1.01), 10),
        ("one dispersion function (det M, 12 x 12)", None,
         lambda: sy[0].dispersion(b, m, vc), 200),
        ("one depth discretisation (n = 16 per body), eigenvalues", None,
         lambda: layup_modes(sy[0].layup, m, vc, 16), 20),
    ]
    print("| task | wall (s) | CPU (s) | goal (s) | CPU / goal |")
    print("|---|---|---|---|---|")
    with one_blas_thread():
        for name, goal, func, repeat in rows:
            clear_caches()          # each row cold: no collocation kept from the one before
            wall, cpu = _time(func, repeat)
            ratio = "" if goal is None else f"{cpu / goal:.2f}"
            print(f"| {name} | {wall:.4g} | {cpu:.4g} | {'' if goal is None else goal} | "
                  f"{ratio} |")


if __name__ == "__main__":
    main()
