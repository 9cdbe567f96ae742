"""Reference eigenvalues of a steady single patch at increasing n, computed once and stored.

Run ``python tests/data/make_stability_convergence.py`` to regenerate
``tests/data/stability_convergence.json`` (a few minutes).  The case is the growing
pair past the fold of the ray K2/K1 = k2/k1 = 1, lam = 1, fH = 1 at Pe = 1.5
(docs/stability.md, "Past the paper"): the eigenvalue b (units k2/Delta^2) of the
contact linearised at fixed load (derivation section 18) is found by Newton's method
on det M(b) at n = 8 from Beyn's estimate, then at each larger n from the previous
n's root.  Stored per n: the root, Newton's last step and the smallest singular value
of M at the root relative to the largest.
"""

from __future__ import annotations

import json
import pathlib
import warnings

import numpy as np

from thermocontact import Model
from thermocontact.io.files import atomic_write
from thermocontact.solvers.stability import linearised, newton

OUT = pathlib.Path(__file__).resolve().parent / "stability_convergence.json"
CASE = dict(pe=1.5, K2_over_K1=1.0, fhpe=1.5, lam=1.0)
LEVELS = (8, 12, 16, 20, 24, 32)
#: Beyn's estimate at n = 8 (docs/stability/stability_study.json).
START = 0.7610748136758606 + 1.334553895858362j


def main():
    warnings.simplefilter("ignore")
    model = Model(CASE["pe"], CASE["K2_over_K1"])
    b, rows = START, []
    for n in LEVELS:
        sol = model.solve_at(n, CASE["fhpe"], lam=CASE["lam"], check_validity=False)
        matrix = linearised(sol).matrix
        b, step = newton(matrix, b, steps=12, tol=1e-13)
        sv = np.linalg.svd(matrix(b), compute_uv=False)
        rows.append({"n": n, "b": [b.real, b.imag], "newton_step": step,
                     "smallest_singular_value": sv[-1] / sv[0],
                     "second_singular_value": sv[-2] / sv[0]})
        print(rows[-1], flush=True)
    with atomic_write(OUT) as fh:
        fh.write(json.dumps({"case": CASE, "levels": rows}, indent=1) + "\n")


if __name__ == "__main__":
    main()
