"""The transient's growth on a held contact set against the eigenvalue with the edges
held, computed once and stored.

Run ``python tests/data/make_transient_growth.py`` to regenerate
``tests/data/transient_growth.json`` (ten minutes or more on a loaded machine).  The case
is the single patch past the fold of docs/stability.md (Pe = fHPe = 1.5,
K2/K1 = k2/k1 = 1, lam = 1): invalid, so no steady state of the transient's elements
exists there, and unstable, with the pair 0.7856 +- 1.3827i k2/Delta^2 (edges free,
derivation S1-S9).  The transient's steps on the patch's contact set held fixed
(:func:`~thermocontact.solvers.transient.held_set_steps`, the linearisation of its steps
under a perturbation too small to change the set; the far temperatures held), kicked by
the load and run to t = 10 l^2/kappa2, grow as e^(b t): ``b`` fitted to the rigid
approach over 5 <= t <= 10 by the matrix pencil (two exponentials: a complex pair).
Stored per element width (``m`` elements across the contact, its edges on element
boundaries) and step: ``b`` in units of ``l^2/kappa2`` and ``k2/Delta^2``; and the
eigenvalues of the linearised patch with its edges held (S17) and free, n = 12, 16, 24.
"""

from __future__ import annotations

import json
from dataclasses import replace
import pathlib
import time

import numpy as np

import thermocontact as tc
from thermocontact.io.files import atomic_write
from thermocontact.solvers.stability import linearised, newton
from thermocontact.solvers.transient import TransientSpec, held_set_steps

OUT = pathlib.Path(__file__).resolve().parent / "transient_growth.json"
CASE = dict(pe=1.5, fhpe=1.5, K2_over_K1=1.0, lam=1.0)
UNTIL = 10.0
FIT_FROM = 5.0
#: (elements across the contact, steps to UNTIL): the step halved at m = 32, the
#: elements doubled at dt = 0.01.
LEVELS = ((32, 500), (32, 1000), (32, 2000), (32, 4000), (16, 1000), (64, 1000),
          (128, 1000))


def held_set_case(solution, m, steps):
    """The transient's spec and the contact set of ``solution`` (a steady single
    patch) in the units of the Hertz half-width: ``m`` elements across the contact, its
    edges on element boundaries, the window from 4 elements behind it to beyond
    ``x = 1`` (a window holds Hertz's contact)."""
    a = np.sqrt(solution.load_ratio)             # Delta/l
    centre = solution.sigma_over_delta * a
    h = 2.0 * a / m
    behind, ahead = 4, max(4, int(np.ceil((1.0 - (centre + a)) / h)) + 1)
    window = (centre - a - behind * h, centre + a + ahead * h)
    p = solution.parameters
    spec = TransientSpec(pe_hertz=p.pe / a, fhpe_hertz=p.fhpe / a,
                         K2_over_K1=p.K2_over_K1, k2_over_k1=p.k2_over_k1,
                         until=UNTIL, steps=steps, elements=m + behind + ahead,
                         window=window, lam=CASE["lam"], initial="steady", hold="theta",
                         perturb=0.1)
    active = np.zeros(spec.elements, dtype=bool)
    active[behind:behind + m] = True
    return spec, active


def pencil_rate(t, y, *, count=2, start=FIT_FROM, every=0.05):
    """The rate ``b`` (largest imaginary part) of ``y(t) ~ sum_k A_k e^(b_k t)``,
    ``count`` terms, over ``t >= start`` sampled every ``every`` (matrix pencil: the
    shift of the samples' Hankel matrix restricted to its leading singular vectors),
    and the next singular value relative to the first (what the terms leave)."""
    dt = t[1] - t[0]
    stride = max(1, int(round(every / dt)))
    y = y[t >= start - 1e-12][::stride]
    rows = y.size // 2
    H = np.array([y[i:i + rows + 1] for i in range(y.size - rows)])
    _, sv, Vh = np.linalg.svd(H, full_matrices=False)
    V = Vh[:count].conj().T
    z = np.linalg.eigvals(np.linalg.pinv(V[:-1]) @ V[1:]).astype(complex)
    rates = np.log(z) / (dt * stride)
    return complex(rates[np.argmax(rates.imag)]), float(sv[count] / sv[0])


def main():
    sol = tc.solve(CASE["pe"], CASE["fhpe"], CASE["K2_over_K1"], lam=CASE["lam"])
    L = sol.load_ratio
    model = tc.Model(CASE["pe"], CASE["K2_over_K1"])
    eigen = {"held": [], "free": []}
    for n in (12, 16, 24):
        lin = linearised(model.solve_at(n, CASE["fhpe"], lam=CASE["lam"],
                                        check_validity=False))
        for edges, guess in (("held", 0.24 + 1.8j), ("free", 0.79 + 1.38j)):
            matrix = replace(lin, edges=edges).matrix
            b, step = newton(matrix, guess, steps=30, tol=1e-13, floor=1e-4)
            eigen[edges].append({"n": n, "b": [b.real, b.imag], "newton_step": step})
            print(edges, n, b, flush=True)
    rows = []
    for m, steps in LEVELS:
        t0 = time.perf_counter()
        spec, active = held_set_case(sol, m, steps)
        t, _, _, D = held_set_steps(spec, active)
        b, rest = pencil_rate(t, D)
        rows.append({"m": m, "steps": steps, "dt": spec.dt, "h": spec.grid()[1],
                     "b_l": [b.real, b.imag], "b": [b.real * L, b.imag * L],
                     "residual": rest, "seconds": time.perf_counter() - t0})
        print(rows[-1], flush=True)
    record = {"case": CASE, "load_ratio": L, "sigma_over_delta": sol.sigma_over_delta,
              "valid": bool(sol.validity.valid), "until": UNTIL, "fit_from": FIT_FROM,
              "eigenvalues": eigen, "levels": rows}
    with atomic_write(OUT) as fh:
        fh.write(json.dumps(record, indent=1) + "\n")


if __name__ == "__main__":
    main()
