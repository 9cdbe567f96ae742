"""The surface temperatures of moving bodies by the Carslaw-Jaeger moving line source,
computed once by adaptive quadrature and stored.

Run ``python tests/data/make_moving_source_references.py`` to regenerate
``tests/data/moving_source_references.json`` (a few seconds).  For each case (steel on
cast iron at 5e4 N/m and 2 m/s, the half-plane at rest or moving at -1.5 m/s) the
contact of half-width :data:`HALF_WIDTH` is solved at n = 48, and each moving body's
surface temperature at the points :data:`POINTS` (units of the half-width) is

    T(x) = (1/(pi K)) int q(xi) exp(-u) K0(|u|) d xi,    u = v (x - xi) / (2 k),

with the body's own signed speed, over the solution's own flux, by QUADPACK in
``theta = arccos r`` (asked for 1e-10 relative): independently of the package's moments.
``tests/test_engineering.py`` solves each case again, checks that it is the same
solution (``load_ratio`` and ``sigma_over_delta`` to 1e-12) and the package's
temperatures against the stored ones to 1e-8.
"""

from __future__ import annotations

import json
import pathlib

import numpy as np
from scipy.integrate import quad
from scipy.special import k0

from thermocontact import solve
from thermocontact.problem.materials import get_material
from thermocontact.studies.physical_contact import PhysicalProblem

OUT = pathlib.Path(__file__).resolve().parent / "moving_source_references.json"
STEEL, IRON = get_material("steel"), get_material("cast-iron")
#: The contact's half-width, m.
HALF_WIDTH = 4e-5
#: The points, units of the half-width.
POINTS = (-0.6, 0.1, 0.8)
#: The half-plane's speed, m/s, of each case.
SPEEDS2 = (0.0, -1.5)
N = 48


def problem(speed2):
    """The case's physical problem."""
    return PhysicalProblem(cylinder=STEEL, half_plane=IRON, radius=0.45, load=5e4, speed=2.0,
                           friction=0.35, lam=-1.0, speed2=speed2)


def solution(speed2):
    """The case's dimensionless solution at :data:`N`."""
    return solve(**problem(speed2).to_dimensionless(HALF_WIDTH), n=N)


def moving_source(sol, speed2, s, body):
    """Body ``body``'s (0: the cylinder; 1: the moving half-plane) surface temperature
    at ``s`` (K) by quadrature of the moving line source over the solution's flux."""
    p = problem(speed2)
    basis = sol.representation
    c, K, sign = ((sol.parameters.cylinder_scale, STEEL.K, 1.0) if body == 0
                  else (sol.parameters.half_plane_scale, IRON.K, -1.0))
    kern = lambda r: np.exp(-c * (s - r)) * k0(abs(c * (s - r)))  # noqa: E731

    # q1, q2 = ((1 +- eta) sqrt(1-r^2) phi +- psi / sqrt(1-r^2)) / 2; in theta = arccos r
    # (no square roots at the edges) p dr = phi w(r) sin(theta) d theta, split at the
    # source point's logarithm.
    def f(th):
        r = np.cos(th)
        return 0.5 * kern(r) * ((1 + sign * sol.eta) * basis.phi_at(sol.phi, r)
                                * basis.pressure_weight(r) * np.sin(th)
                                + sign * basis.psi_at(sol.psi, r))
    opts = dict(limit=400, epsabs=1e-12, epsrel=1e-10)
    ts = np.arccos(s)
    ref = quad(f, 0.0, ts, **opts)[0] + quad(f, ts, np.pi, **opts)[0]
    return p.friction * p.sliding_speed * p.load / np.pi / K * ref


def bodies(speed2):
    """The moving bodies of a case."""
    return (0, 1) if speed2 else (0,)


def main():
    from thermocontact.io.files import atomic_write

    out = []
    for speed2 in SPEEDS2:
        sol = solution(speed2)
        temps = [[moving_source(sol, speed2, s, b) for s in POINTS] for b in bodies(speed2)]
        out.append({"speed2": speed2, "load_ratio": float(sol.load_ratio),
                    "sigma_over_delta": float(sol.sigma_over_delta), "temperatures": temps})
        print(speed2, temps)
    with atomic_write(OUT, "w") as fh:
        json.dump({"n": N, "half_width": HALF_WIDTH, "points": list(POINTS), "cases": out},
                  fh, indent=1)


if __name__ == "__main__":
    main()
