"""Reference values of a fast real mode of valid steady contacts, computed once and stored.

Run ``python tests/data/make_edge_mode.py`` to regenerate ``tests/data/edge_mode.json``
(a few minutes).  The case is path (a) of docs/zones.md (Pe = 5, K2/K1 = k2/k1 = 10,
lam = 1) at fHPe = 0.65, a valid contact before the event: its count (derivation S12,
n = 12, |b| <= 1e6) finds one real eigenvalue near 2e4 k2/Delta^2 (docs/stability.md,
"Fast modes at the edges").  Stored per n: the root by Newton's method from the previous
n's, Newton's last step and the smallest two singular values of M at the root relative
to the largest; and the count at n = 12 with its located root.
"""

from __future__ import annotations

import json
import pathlib
import warnings

import numpy as np

import thermocontact as tc
from thermocontact.io.files import atomic_write
from thermocontact.solvers.stability import linearised, newton

OUT = pathlib.Path(__file__).resolve().parent / "edge_mode.json"
CASE = dict(pe=5.0, K2_over_K1=10.0, fhpe=0.65, lam=1.0)
LEVELS = (8, 12, 16, 24, 32, 48)


def main():
    warnings.simplefilter("ignore")
    sol = tc.solve(CASE["pe"], CASE["fhpe"], CASE["K2_over_K1"], lam=CASE["lam"])
    verdict = tc.stability(sol)
    print(verdict.to_dict(), flush=True)
    model = tc.Model(CASE["pe"], CASE["K2_over_K1"])
    b, rows = complex(verdict.eigenvalues[0]), []
    for n in LEVELS:
        lin = linearised(model.solve_at(n, CASE["fhpe"], lam=CASE["lam"], check_validity=False))
        b, step = newton(lin.matrix, b, steps=20, tol=1e-13, floor=1e-4)
        sv = np.linalg.svd(lin.matrix(b), compute_uv=False)
        rows.append({"n": n, "b": b.real, "imag": b.imag, "newton_step": step,
                     "smallest_singular_value": sv[-1] / sv[0],
                     "second_singular_value": sv[-2] / sv[0]})
        print(rows[-1], flush=True)
    record = {"case": CASE, "valid": bool(sol.validity.valid),
              "verdict": verdict.to_dict(), "levels": rows}
    with atomic_write(OUT) as fh:
        fh.write(json.dumps(record, indent=1) + "\n")


if __name__ == "__main__":
    main()
