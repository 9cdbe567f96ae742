"""Methods on the edge-graded representation: collocation and Galerkin projection.

The unknowns are cosine series in ``tau`` (:mod:`thermocontact.graded`); every
operator of the contact equation (D14) and the heat equation (D18) is a moment
computed by :func:`thermocontact.graded.moments`: the Cauchy kernels as principal
values, ``sgn`` and ``N H`` with their jump, ``c M(c u) - 1/u`` with its
logarithm.  The equations are enforced at points equally spaced in ``tau``
(``graded-collocation``) or projected on cosines in ``tau`` (``graded``, the
default; derivation section 12).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..numerics import edge_graded as graded
from .system import Blocks, register
from .representations import GradedBasis
from ..physics.green_functions import cylinder_slope, cylinder_temperature_gradient_regular
from ..problem.parameters import Parameters
from .product_integration import range_projections

__all__ = ["GradedRule", "assemble_graded", "assemble_graded_collocation", "graded_rules"]


@dataclass(frozen=True)
class GradedRule:
    """Nodes of one unknown and the weights of its integral over ``[-1, 1]``.

    Attributes
    ----------
    nodes : ndarray, shape (n,)
        ``r_i = cos T(tau_i)``, ascending.
    weights : ndarray, shape (n,)
        ``integral p dr = weights @ phi`` (pressure) or
        ``integral q' dr = weights @ psi`` (flux), exact for the cosine series.
    edge_factor : ndarray, shape (n,)
        ``sqrt(1 - r_i^2) = sin T(tau_i)``, from ``tau`` (next to an edge ``r_i``
        may round to 1).
    """

    nodes: np.ndarray
    weights: np.ndarray
    edge_factor: np.ndarray


def graded_rules(n: int):
    """The pressure's and the flux's :class:`GradedRule` (same nodes, own weights)."""
    to_cos = graded.coefficient_matrix(n)
    t = graded.stretch(graded.nodes(n))
    r, sin_t = np.cos(t), np.sin(t)
    wb, ws = graded.weight_integrals(n)
    return GradedRule(r, wb @ to_cos, sin_t), GradedRule(r, ws @ to_cos, sin_t)


def _operators(par: Parameters, n: int, tk, th):
    """Operators of (D14) at ``sk`` and (D18, divided by ``pi (1 + rho)``) at ``sh``.

    On the cosine coefficients of ``phi`` and ``psi``; the same combination of
    kernels as :func:`thermocontact.product._coefficient_blocks`.  The points are
    given by their ``tau``.
    """
    sk, sh = np.cos(graded.stretch(tk)), np.cos(graded.stretch(th))
    eta = par.eta
    rho = par.K2_over_K1
    c = par.cylinder_scale
    d = par.delta1_over_delta2
    cauchy = lambda u: 1.0 / u  # noqa: E731
    cb, _ = graded.moments(cauchy, sk, n, scale=1.0, cauchy=True, tau=tk)
    sg_b, sg_s = graded.moments(np.sign, sk, n, scale=1.0, tau=tk)
    if d:
        nh_b, nh_s = graded.moments(lambda u: cylinder_slope(c * u), sk, n, scale=c, tau=tk)
    else:
        nh_b = nh_s = 0.0
    C = cb / np.pi
    Tp = d * (1.0 + eta) * nh_b + 0.5 * (1.0 - eta) * sg_b
    Tq = d * nh_s - 0.5 * sg_s
    _, cs = graded.moments(cauchy, sh, n, scale=1.0, cauchy=True, tau=th)
    mr_b, mr_s = graded.moments(lambda u: cylinder_temperature_gradient_regular(u, c), sh, n,
                                scale=c, logarithmic=True, tau=th)
    Hq = (cs + (rho / (1.0 + rho)) * mr_s) / np.pi
    # 2 rho/(1 + rho)^2 written so that no power overflows for extreme ratios.
    Hp = (2.0 / ((1.0 + rho) * (1.0 + 1.0 / rho))) * mr_b / np.pi
    return C, Tp, Tq, Hp, Hq


def _integrator(n):
    to_cos = graded.coefficient_matrix(n)

    def integrate(kernel, s_pts, scale=None):
        b, q = graded.moments(kernel, np.asarray(s_pts, dtype=float), n, scale=scale)
        return b @ to_cos, q @ to_cos

    return integrate


def _points(m: int, shift: float):
    """``cos T(tau_k)``, ``tau_k = pi (k - shift) / m`` for ``k = m - 1 ... 1`` or ``m ... 1``."""
    k = np.arange(m, 0, -1) if shift else np.arange(m - 1, 0, -1)
    tau = np.pi * (k - shift) / m
    return tau, np.cos(graded.stretch(tau))


#: Automatic n: from 8, and at most 256, beyond which the rounding of the edge values
#: of phi (about n^7, derivation section 12) passes 1e-7.
AUTO_RANGE = (8, 256)


@register("graded-collocation", AUTO_RANGE)
def assemble_graded_collocation(par: Parameters, n: int) -> Blocks:
    """Collocate (D14) at ``tau = pi (k - 1/2)/(n + 1)`` and (D18) at ``tau = pi k / n``.

    The analogues in ``tau`` of the zeros of ``T_{n+1}`` and ``U_{n-1}``.

    Returns
    -------
    Blocks
    """
    pr, fr = graded_rules(n)
    to_cos = graded.coefficient_matrix(n)
    tk, sk = _points(n + 1, 0.5)
    th, _ = _points(n, 0.0)
    C, Tp, Tq, Hp, Hq = _operators(par, n, tk, th)
    return Blocks(n, pr, fr, sk, C @ to_cos, Tp @ to_cos, Tq @ to_cos, Hp @ to_cos,
                  Hq @ to_cos, _integrator(n), basis=GradedBasis(n))


@register("graded", AUTO_RANGE)
def assemble_graded(par: Parameters, n: int) -> Blocks:
    """Project (D14) on ``cos(k tau)``, ``k <= n``, and (D18) on ``sin((k + 1) tau) sin tau``, ``k < n - 1``.

    By the midpoint rule on ``2n`` points in ``tau``: the rows of
    :func:`thermocontact.product.range_projections`, taken in ``tau``.

    Returns
    -------
    Blocks
    """
    pr, fr = graded_rules(n)
    to_cos = graded.coefficient_matrix(n)
    t, p1, p2 = range_projections(n)
    s = np.cos(graded.stretch(t))
    C, Tp, Tq, Hp, Hq = _operators(par, n, t, t)
    return Blocks(n, pr, fr, s, p1 @ C @ to_cos, p1 @ Tp @ to_cos, p1 @ Tq @ to_cos,
                  p2 @ Hp @ to_cos, p2 @ Hq @ to_cos, _integrator(n),
                  const_column=p1.sum(axis=1), linear_column=p1 @ s, basis=GradedBasis(n))
