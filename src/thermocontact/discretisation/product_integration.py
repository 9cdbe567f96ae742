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

from .system import Blocks, register
from ..physics.green_functions import cylinder_slope, cylinder_temperature_gradient_regular
from ..numerics.moments import kernel_moments, sgn_moments
from ..problem.parameters import Parameters
from ..numerics.quadrature import bounded_rule, singular_rule, t_coefficient_matrix, u_coefficient_matrix

__all__ = ["assemble_galerkin", "assemble_product", "coefficient_maps", "range_projections"]


def coefficient_maps(n: int):
    """Matrices taking nodal ``phi`` to ``U``-coefficients and nodal ``psi`` to ``T``-coefficients.

    Returns
    -------
    to_u, to_t : ndarray, shape (n, n)
    """
    return u_coefficient_matrix(n), t_coefficient_matrix(n)


def _coefficient_blocks(par: Parameters, n: int, sk, sh):
    """The equations' operators on the coefficients of ``phi`` (U) and ``psi`` (T).

    Contact equation (D14) at ``sk``, heat equation (D18, divided by
    ``pi (1 + rho)``) at ``sh``.

    Returns
    -------
    C, Tp, Tq : ndarray, shape (len(sk), n)
    Hp, Hq : ndarray, shape (len(sh), n)
    """
    eta = par.eta
    rho = par.K2_over_K1
    c = par.cylinder_scale
    d = par.delta1_over_delta2
    j = np.arange(n)
    # T_{j+1}(cos t) = cos((j + 1) t).
    C = np.cos((j[None, :] + 1) * np.arccos(sk)[:, None])
    sgn_b, sgn_s = sgn_moments(sk, n)
    if d:
        nh_b, nh_s = kernel_moments(lambda u: cylinder_slope(c * u), sk, n, scale=c)
    else:
        nh_b = nh_s = 0.0
    Tp = d * (1.0 + eta) * nh_b + 0.5 * (1.0 - eta) * sgn_b
    Tq = d * nh_s - 0.5 * sgn_s
    mr_b, mr_s = kernel_moments(lambda u: cylinder_temperature_gradient_regular(u, c), sh, n,
                                scale=c, logarithmic=True)
    # -U_{j-1}(cos t) = -sin(j t)/sin t (0 for j = 0); sin t > 0 at every point.
    th = np.arccos(sh)[:, None]
    cauchy_t = -np.sin(j[None, :] * th) / np.sin(th)
    Hq = cauchy_t + (rho / (1.0 + rho)) * mr_s / np.pi
    # 2 rho/(1 + rho)^2 written so that no power overflows for extreme ratios.
    Hp = (2.0 / ((1.0 + rho) * (1.0 + 1.0 / rho))) * mr_b / np.pi
    return C, Tp, Tq, Hp, Hq


def _integrator(n):
    to_u, to_t = coefficient_maps(n)

    def integrate(kernel, s_pts, scale=None):
        b, t = kernel_moments(kernel, np.asarray(s_pts, dtype=float), n, scale=scale)
        return b @ to_u, t @ to_t

    return integrate


@register("product")
def assemble_product(par: Parameters, n: int) -> Blocks:
    """Assemble the blocks by product integration (exact moments), collocated.

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
    to_u, to_t = coefficient_maps(n)
    C, Tp, Tq, Hp, Hq = _coefficient_blocks(par, n, pr.collocation, fr.collocation)
    return Blocks(n, pr, fr, pr.collocation, C @ to_u, Tp @ to_u, Tq @ to_t, Hp @ to_u,
                  Hq @ to_t, _integrator(n))


#: Quadrature points per unknown of the Galerkin projections.
OVERSAMPLING = 2


def range_projections(n: int):
    """Points and projections of the two equations on their range spaces.

    On ``m = 2n`` midpoints ``t_k = pi (k - 1/2)/m`` (descending), the rows
    ``(pi/m) cos(j t_k)``, ``j <= n``, project a function of ``t`` on ``cos(j t)``
    (the contact equation, ``T_j`` with weight ``1/sqrt(1-s^2)`` when ``s = cos t``),
    and ``(pi/m) sin((j + 1) t_k) sin t_k``, ``j <= n - 2``, on
    ``sin((j + 1) t) sin t`` (the heat equation, ``U_j`` with weight
    ``sqrt(1-s^2)``).  The graded methods use the same rows in ``tau``.

    Returns
    -------
    t : ndarray, shape (m,)
    p1 : ndarray, shape (n + 1, m)
    p2 : ndarray, shape (n - 1, m)
    """
    m = OVERSAMPLING * n
    t = np.pi * (np.arange(m, 0, -1) - 0.5) / m
    w = np.pi / m
    p1 = w * np.cos(np.arange(n + 1)[:, None] * t[None, :])
    p2 = w * np.sin((np.arange(n - 1)[:, None] + 1) * t[None, :]) * np.sin(t)[None, :]
    return t, p1, p2


@register("galerkin")
def assemble_galerkin(par: Parameters, n: int) -> Blocks:
    """Product integration with each equation projected onto its own range space.

    The Cauchy operators map ``sqrt(1-r^2) U_j`` to ``T_{j+1}`` and
    ``T_j/sqrt(1-r^2)`` to ``-U_{j-1}``, so the contact equation is projected onto
    ``T_0 ... T_n`` with weight ``1/sqrt(1-s^2)`` and the heat equation onto
    ``U_0 ... U_{n-2}`` with weight ``sqrt(1-s^2)``, both by Gauss–Chebyshev
    quadrature on ``2n`` points (exact for the polynomial parts).  The system keeps
    the collocation's shape (``n + 1`` and ``n - 1`` rows), each equation stays
    separate (the Hertz solution is exact at ``fHPe = 0``), and the error is about
    that of collocation at ``2n`` (derivation section 10).

    Returns
    -------
    Blocks
    """
    pr = bounded_rule(n)
    fr = singular_rule(n)
    to_u, to_t = coefficient_maps(n)
    t, p1, p2 = range_projections(n)
    s = np.cos(t)
    C, Tp, Tq, Hp, Hq = _coefficient_blocks(par, n, s, s)
    return Blocks(n, pr, fr, s, p1 @ C @ to_u, p1 @ Tp @ to_u, p1 @ Tq @ to_t,
                  p2 @ Hp @ to_u, p2 @ Hq @ to_t, _integrator(n),
                  const_column=p1.sum(axis=1), linear_column=p1 @ s)
