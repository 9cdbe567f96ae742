"""The gap outside the contact by brute-force quadrature, computed once and stored.

Run ``python tests/data/make_gap_references.py`` to regenerate
``tests/data/gap_references.json`` (about half a minute).  For each case, the solution at
n = 24 (the product method on the Chebyshev series, or the edge-graded one) and the gap at
one point ``s`` outside the contact by nested adaptive quadrature (QUADPACK) of the
terms of the contact equation (D14) (derivation D20-D21): the slope mismatch ``G(t)``
integrated from the edge, independently of the package's moments and closed forms.
``tests/test_validity.py`` solves each case again and checks the package's gap against
the stored one to 1e-9; the stored ``load_ratio`` and ``sigma_over_delta`` say that the
solution is the same one (to 1e-12), or that this script must be run again.
"""

from __future__ import annotations

import json
import math
import pathlib

import numpy as np
from scipy.integrate import quad

from thermocontact import solve
from thermocontact.discretisation.representations import EdgeGraded
from thermocontact.physics.green_functions import cylinder_slope

OUT = pathlib.Path(__file__).resolve().parent / "gap_references.json"
#: Unknowns per function of every case's solution.
N = 24

# The brute-force integrands below are called a few hundred thousand times each: their
# series and the graded map T(tau) = tau - sin(2 tau)/2 are summed on scalars (the same
# formulas as the package's, without an array call per point).
def _cosine_series(a):
    """``tau -> sum_j a_j cos(j tau)``, on scalars."""
    j = np.arange(len(a))
    return lambda tau: float(np.cos(j * tau) @ a)

def _stretch(tau):
    return tau - 0.5 * math.sin(2.0 * tau)

def _stretch_derivative(tau):
    return 2.0 * math.sin(tau) ** 2

def _half_plane_slope(par, t):
    """The half-plane's kernel of (D14) at t - r, |t| >= 1: sgn/2 when it is stationary,
    sgn(c2) N(c2 u) H(c2 u) of (D14b) when it moves (pointwise, no moments)."""
    c2 = par.half_plane_scale
    if c2 == 0.0:
        return lambda r: 0.5 * np.sign(t)
    return lambda r: np.sign(c2) * (cylinder_slope(c2 * (t - r)) if c2 * (t - r) != 0.0
                                    else 0.5)

def brute_force_slope_mismatch_chebyshev(sol, t):
    """G(t) for |t| >= 1 by adaptive quadrature of the terms of (D14) in
    theta = arccos r, for the Chebyshev representation: p dr = phi sin^2(theta) dtheta
    and q' dr = psi dtheta, free of the edges' square roots (at |t| = 1 the Cauchy
    integrand sin^2(theta)/(t - cos(theta)) is t + cos(theta))."""
    par = sol.parameters
    F, d, c = par.fhpe, par.delta1_over_delta2, par.cylinder_scale
    from thermocontact.numerics.quadrature import t_series_coefficients, u_series_coefficients

    # phi = sum a_j U_j(cos theta) = sum a_j sin((j + 1) theta)/sin(theta) and
    # psi = sum b_j cos(j theta), summed on scalars at each theta.
    a = u_series_coefficients(sol.phi)
    b = t_series_coefficients(sol.psi)
    ja, jb = np.arange(1, a.size + 1), np.arange(b.size)
    opts = dict(limit=200, epsabs=1e-13, epsrel=1e-12)
    def over_theta(f):
        def g(th):
            phi = float(np.sin(ja * th) @ a) / math.sin(th)
            return f(math.cos(th), th, phi, float(np.cos(jb * th) @ b))
        return quad(g, 0.0, np.pi, **opts)[0]
    nh = lambda r: d * cylinder_slope(c * (t - r))  # noqa: E731
    hp = _half_plane_slope(par, t)
    if abs(t) == 1.0:
        cauchy = over_theta(lambda r, th, phi, psi: phi * (t + r)) / np.pi
    else:
        cauchy = over_theta(lambda r, th, phi, psi: phi * math.sin(th) ** 2 / (t - r)) / np.pi
    kp = over_theta(lambda r, th, phi, psi: phi * math.sin(th) ** 2 * (nh(r) + hp(r)))
    # q = psi/sqrt(1-r^2) + eta p
    kq = over_theta(lambda r, th, phi, psi: (psi + sol.eta * phi * math.sin(th) ** 2)
                    * (nh(r) - hp(r)))
    L, sig = sol.load_ratio, sol.sigma_over_delta
    return cauchy - F * (kp + kq) - 2 / np.pi * L * (sig + t)

def brute_force_slope_mismatch(sol, t):
    """G(t) for |t| >= 1 by adaptive quadrature of the contact equation's terms (D14).

    For the graded representation the integrals are taken over r = cos T(tau) in
    tau, with p dr = phi sin^2 T T' dtau and q' dr = psi T' dtau.
    """
    par = sol.parameters
    F, d, c = par.fhpe, par.delta1_over_delta2, par.cylinder_scale
    basis = sol.representation
    if not isinstance(basis, EdgeGraded):
        return brute_force_slope_mismatch_chebyshev(sol, t)
    phi_of, psi_of = (_cosine_series(basis.to_cos @ v) for v in (sol.phi, sol.psi))
    alpha = basis.alpha
    def w_sin(tt):  # w(cos T) sin T, w = (1 - r)^alpha (1 + r)^(1 - alpha)
        return (1 - math.cos(tt)) ** alpha * (1 + math.cos(tt)) ** (1 - alpha) * math.sin(tt)

    def over_tau(f):
        def g(tau):
            tt = _stretch(tau)
            return f(math.cos(tt), tt, tau)
        # Pieces: each edge's power of tau or pi - tau, and the near-singular
        # integrand of points just outside an edge, in a piece of its own.
        opts = dict(limit=400, epsabs=1e-14, epsrel=1e-13)
        cuts = [0.0, 0.2, 0.5 * np.pi, np.pi - 0.2, np.pi]
        return sum(quad(g, lo, hi, **opts)[0] for lo, hi in zip(cuts[:-1], cuts[1:]))

    def p_dr(r, tt, tau):
        return phi_of(tau) * w_sin(tt) * _stretch_derivative(tau)
    def q_dr(r, tt, tau):
        return psi_of(tau) * _stretch_derivative(tau)

    nh = lambda r: d * cylinder_slope(c * (t - r))
    hp = _half_plane_slope(par, t)
    if abs(t) == 1.0:
        # w sin T / (t - cos T) at an edge, in half-angles: 2 sin^(2a-1) cos^(3-2a) at
        # t = 1, -2 sin^(2a+1) cos^(1-2a) at t = -1 (t (1 + t cos T) for a = 1/2).
        def edge_factor(tt):
            sn, cs = math.sin(0.5 * tt), math.cos(0.5 * tt)
            if t > 0:
                return 2.0 * sn ** (2 * alpha - 1) * cs ** (3 - 2 * alpha)
            return -2.0 * sn ** (2 * alpha + 1) * cs ** (1 - 2 * alpha)
        cauchy = over_tau(lambda r, tt, tau: phi_of(tau) * _stretch_derivative(tau)
                          * edge_factor(tt)) / np.pi
    else:
        cauchy = over_tau(lambda r, tt, tau: p_dr(r, tt, tau) / (t - r)) / np.pi
    kp = over_tau(lambda r, tt, tau: p_dr(r, tt, tau) * (nh(r) + hp(r)))
    # q = q' + eta p
    kq = over_tau(lambda r, tt, tau: (q_dr(r, tt, tau) + sol.eta * p_dr(r, tt, tau))
                  * (nh(r) - hp(r)))
    L, sig = sol.load_ratio, sol.sigma_over_delta
    return cauchy - F * (kp + kq) - 2 / np.pi * L * (sig + t)

def brute_force_gap(sol, s):
    """Gap by quadrature of G - G(edge) from the edge to s (derivation D20-D21).
    G - G(edge) grows like (|t| - 1)^exponent from the edge (1/2, or the Dundurs
    term's): with |t| = 1 + w^2 the integrand 2 w (G - G(edge)) vanishes like
    w^(1 + 2 exponent) and QUADPACK certifies its accuracy.
    """
    L = sol.load_ratio
    side = 1.0 if s > 1 else -1.0
    g1 = brute_force_slope_mismatch(sol, side)
    j = quad(lambda w: 2 * w * (brute_force_slope_mismatch(sol, side * (1 + w * w)) - g1),
             0.0, np.sqrt(abs(s) - 1.0), epsabs=1e-13, epsrel=1e-12)[0]
    return -side * np.pi / (2 * L) * j

GAP_CASES = [
    (dict(pe=5, fhpe=0.3, K2_over_K1=10, k2_over_k1=1, lam=-1), -2.5),
    (dict(pe=5, fhpe=0.3, K2_over_K1=10, k2_over_k1=1, lam=-1), 1.05),
    (dict(pe=2, fhpe=0.2, K2_over_K1=3, k2_over_k1=0.5, delta1_over_delta2=2.0, lam=0.5), 4.0),
]

#: A half-plane moving through the contact (section 5b), each direction on each side:
#: its kernel acts on the side its material reaches first and vanishes on the other.
MOVING_GAP_CASES = [
    (dict(pe=2, fhpe=0.4, K2_over_K1=3, k2_over_k1=0.5, speed_ratio=0.7, lam=0.3), 1.3),
    (dict(pe=2, fhpe=0.4, K2_over_K1=3, k2_over_k1=0.5, speed_ratio=0.7, lam=0.3), -1.3),
    (dict(pe=2, fhpe=0.4, K2_over_K1=3, k2_over_k1=0.5, speed_ratio=-1.5, lam=0.3), -3.0),
    (dict(pe=2, fhpe=0.4, K2_over_K1=3, k2_over_k1=0.5, speed_ratio=-1.5, lam=0.3), 1.02),
    # The Dundurs term's edge exponents (section 5c), 0.648 at the edge whose side is
    # checked (beyond an edge of exponent 0.352 the quadrature's integrand is too
    # nearly singular for QUADPACK to certify 1e-9; that side's gap differs from it
    # by 2e-10 at s = -1.4 with B = 1).
    (dict(pe=5, fhpe=0.3, K2_over_K1=10, k2_over_k1=1, beta_f=1.0, lam=-1), 1.05),
    (dict(pe=5, fhpe=0.3, K2_over_K1=10, k2_over_k1=1, beta_f=-1.0, lam=-1), -1.4),
]


#: Every case: its parameters, the point s and the method.
CASES = ([c + ("product",) for c in GAP_CASES]
         + [c + ("graded",) for c in GAP_CASES[:2] + MOVING_GAP_CASES])


def solution(case, method):
    """The case's solution at :data:`N`."""
    return solve(n=N, method=method, **case)


def main():
    from thermocontact.io.files import atomic_write

    out = []
    for case, s, method in CASES:
        sol = solution(case, method)
        out.append({"parameters": case, "s": s, "method": method,
                    "load_ratio": float(sol.load_ratio),
                    "sigma_over_delta": float(sol.sigma_over_delta),
                    "gap": float(brute_force_gap(sol, s))})
        print(method, case, s, out[-1]["gap"])
    with atomic_write(OUT, "w") as fh:
        json.dump({"n": N, "cases": out}, fh, indent=1)


if __name__ == "__main__":
    main()
