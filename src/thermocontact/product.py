"""Product integration: every kernel integrated exactly against the Chebyshev bases.

The unknowns are represented as in the paper's scheme (``phi`` and ``psi`` as
polynomials of degree ``n - 1``, carried by their values at the Gauss nodes) and
the equations are collocated at the same points, but no kernel is sampled: the
Cauchy parts use the exact finite Hilbert transforms of ``U_j`` and ``T_j``, the
half-plane's ``sgn`` kernel its exact antiderivatives, and the moving body's
kernels ``N H`` and ``c M(c u) - 1/u`` their moments computed to machine
precision by :func:`~thermocontact.moments.kernel_moments` (derivation section
10).  The discretisation error is then that of approximating the solution by
polynomials, whatever the Peclet number.
"""

from __future__ import annotations

import numpy as np

from .assembly import Blocks, register
from .kernels import cylinder_slope, cylinder_temperature_gradient_regular
from .moments import kernel_moments, sgn_moments
from .parameters import Parameters
from .quadrature import bounded_rule, singular_rule

__all__ = ["assemble_product", "coefficient_maps"]


def coefficient_maps(n: int):
    """Matrices taking nodal ``phi`` to ``U``-coefficients and nodal ``psi`` to ``T``-coefficients.

    Returns
    -------
    to_u, to_t : ndarray, shape (n, n)
    """
    th_b = np.pi * np.arange(n, 0, -1) / (n + 1)
    j = np.arange(n)[:, None]
    to_u = (2.0 / (n + 1)) * np.sin((j + 1) * th_b[None, :]) * np.sin(th_b)[None, :]
    th_s = np.pi * (2 * np.arange(n, 0, -1) - 1) / (2 * n)
    to_t = (2.0 / n) * np.cos(j * th_s[None, :])
    to_t[0] *= 0.5
    return to_u, to_t


@register("product")
def assemble_product(par: Parameters, n: int) -> Blocks:
    """Assemble the blocks by product integration (exact moments).

    Parameters
    ----------
    par : Parameters
    n : int

    Returns
    -------
    Blocks
        In the same nodal form as the paper's scheme, so the solver and the
        validity checks apply unchanged.
    """
    pr = bounded_rule(n)
    fr = singular_rule(n)
    sk = pr.collocation
    sh = fr.collocation
    eta = par.eta
    rho = par.K2_over_K1
    c = par.cylinder_scale
    d = par.delta1_over_delta2
    to_u, to_t = coefficient_maps(n)
    j = np.arange(n)

    # Contact equation (D14) at s_k, on coefficients.
    # T_{j+1}(cos t) = cos((j + 1) t) at the collocation angles.
    C = np.cos((j[None, :] + 1) * np.arccos(sk)[:, None])
    sgn_b, sgn_s = sgn_moments(sk, n)
    if d:
        nh_b, nh_s = kernel_moments(lambda u: cylinder_slope(c * u), sk, n, scale=c)
    else:
        nh_b = nh_s = 0.0
    Tp = d * (1.0 + eta) * nh_b + 0.5 * (1.0 - eta) * sgn_b
    Tq = d * nh_s - 0.5 * sgn_s

    # Heat equation (D18) at s'_k, divided by pi (1 + rho).
    mr_b, mr_s = kernel_moments(lambda u: cylinder_temperature_gradient_regular(u, c), sh, n)
    # -U_{j-1}(cos t) = -sin(j t)/sin t (0 for j = 0); sin t > 0 at every s'_k.
    th = np.arccos(sh)[:, None]
    cauchy_t = -np.sin(j[None, :] * th) / np.sin(th)
    Hq = cauchy_t + (rho / (1.0 + rho)) * mr_s / np.pi
    # 2 rho/(1 + rho)^2 written so that no power overflows for extreme ratios.
    Hp = (2.0 / ((1.0 + rho) * (1.0 + 1.0 / rho))) * mr_b / np.pi


    def integrate(kernel, s_pts, scale=None):
        b, t = kernel_moments(kernel, np.asarray(s_pts, dtype=float), n, scale=scale)
        return b @ to_u, t @ to_t

    return Blocks(n, pr, fr, sk, C @ to_u, Tp @ to_u, Tq @ to_t, Hp @ to_u, Hq @ to_t,
                  integrate)
