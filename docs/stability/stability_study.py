"""The stability study of docs/stability.md: eigenvalues of steady single patches.

For each case (a point of the paper's Figs. 2-5, or of a crossing path of
docs/zones.md approaching its event) the eigenvalues of the contact linearised at
fixed load (derivation section 18) in the ellipse Re b in [0.5, 10], |Im b| <= 10
(units k2/Delta^2) by Beyn's method at n = 8 (32 contour points), each checked by
Newton's method, then
followed by Newton's method at n = 12 and 16 (their convergence in n).  Writes
stability_study.json beside this file, case by case (an interrupted study resumes);
``--table`` prints the tables of docs/stability.md from it.

    python docs/stability/stability_study.py [--table] [--only NAME ...]
"""

import json
import pathlib
import sys
import time
import warnings

import numpy as np

from thermocontact import Model
from thermocontact.io.files import atomic_write
from thermocontact.solvers.stability import beyn, linearised, newton

HERE = pathlib.Path(__file__).resolve().parent
OUT = HERE / "stability_study.json"
REGION = (0.5, 10.0, 10.0)
POINTS = 32
LEVELS = (8, 12, 16)

#: (name, Pe, K2/K1, fHPe, lam): k2/k1 = K2/K1, delta1 = delta2, as in the paper.
CASES = [
    ("fig4 lam=-1 fHPe=0.3", 5.0, 10.0, 0.3, -1.0),
    ("fig4 lam=1 fHPe=0.3", 5.0, 10.0, 0.3, 1.0),
    ("fig3 Pe=1 fHPe=0.5", 1.0, 10.0, 0.5, -1.0),
    ("fig2 K=1 fHPe=0.3", 5.0, 1.0, 0.3, -1.0),
    ("fig5 fHPe=0.3 lam=3", 5.0, 10.0, 0.3, 3.0),
    # Past the paper: a ray with folds (K2/K1 = 1, lam = 1, fH = 1: a fold of the load
    # at Pe = 1.2343) and strong coupling (K2/K1 = 10, lam = 1, fH = 0.5).
    ("ray K=1 fH=1 Pe=1.0", 1.0, 1.0, 1.0, 1.0),
    ("ray K=1 fH=1 Pe=1.5", 1.5, 1.0, 1.5, 1.0),
    ("ray K=10 fH=0.5 Pe=4.2", 4.2, 10.0, 2.1, 1.0),
]
#: The crossing paths (docs/zones.md): the single patch's event at Pe_event, fHPe_event;
#: along the ray fHPe = fH Pe, at fractions of Pe_event.
PATHS = [("a", 5.0, 10.0, 0.665362, 1.0), ("c", 0.2, 1.0, 0.670502, 0.5),
         ("b", 10.0, 100.0, 0.331226, 1.0)]
FRACTIONS = (0.9, 1.0)
for name, pe, K, f, lam in PATHS:
    for x in FRACTIONS:
        CASES.append((f"path ({name}) {x:g} Pe*", x * pe, K, x * f, lam))


def case(pe, K, fhpe, lam):
    model = Model(pe, K)
    record = {"pe": pe, "K2_over_K1": K, "fhpe": fhpe, "lam": lam}
    sol = model.solve(fhpe, lam=lam)
    record.update(load_ratio=sol.load_ratio, sigma_over_delta=sol.sigma_over_delta,
                  valid=bool(sol.validity.valid))
    t0 = time.time()
    lin = {n: linearised(model.solve_at(n, fhpe, lam=lam, check_validity=False))
           for n in LEVELS}
    found, rank = beyn(lin[LEVELS[0]].matrix, REGION, points=POINTS)
    found = [b for b in found if b.imag >= 0]
    modes = []
    for b in found:
        path = []
        for n in LEVELS:
            b, step = newton(lin[n].matrix, b)
            sv = np.linalg.svd(lin[n].matrix(b), compute_uv=False)
            path.append({"n": n, "b": [b.real, b.imag], "step": step,
                         "smallest_singular_value": sv[-1] / sv[0]})
        modes.append(path)
    record.update(rank=int(rank), modes=modes, seconds=time.time() - t0)
    return record


def main(argv):
    warnings.simplefilter("ignore")
    done = json.loads(OUT.read_text()) if OUT.exists() else {}
    if "--table" in argv:
        for name, r in done.items():
            modes = "; ".join(
                " -> ".join(f"{m['b'][0]:.4g}{m['b'][1]:+.4g}i" for m in path)
                for path in r["modes"]) or "none"
            print(f"| {name} | {r['load_ratio']:.4f} | {'yes' if r['valid'] else 'no'} | "
                  f"{modes} |")
        return
    only = argv[argv.index("--only") + 1:] if "--only" in argv else None
    for name, pe, K, f, lam in CASES:
        if name in done or (only and name not in only):
            continue
        done[name] = case(pe, K, f, lam)
        # Whole or not at all: an interrupted study resumes from the cases done.
        with atomic_write(OUT) as fh:
            fh.write(json.dumps(done, indent=1))
        print(name, done[name]["modes"], flush=True)


if __name__ == "__main__":
    main(sys.argv[1:])
