"""The paper's method: Gauss–Chebyshev collocation with kernels sampled at nodes.

Every regular kernel is sampled at the quadrature nodes (the paper's eqs. 25-27,
as corrected in derivation section 6).  The Cauchy parts are exact; the step
kernels ``N H`` and ``sgn`` and the logarithm of ``M`` are not, which limits the
convergence to low algebraic order (measured in ``tests/test_solver.py``).
"""

from __future__ import annotations

import numpy as np

from .system import Blocks, register
from ..physics.green_functions import cylinder_slope, cylinder_temperature_gradient_regular
from ..problem.parameters import Parameters
from ..numerics.quadrature import bounded_rule, singular_rule

__all__ = ["assemble_paper"]


def _contact_kernels(par: Parameters, u):
    """Kernels ``K_p`` and ``K_q`` of the contact equation (derivation D14).

    ``K_p = d N(c u) H(u) + sgn(u)/2`` acts on the pressure and
    ``K_q = d N(c u) H(u) - sgn(u)/2`` on the heat-flux difference, with
    ``d = delta1/delta2`` and ``c = Pe k2/k1``.
    """
    nh = par.delta1_over_delta2 * cylinder_slope(par.cylinder_scale * u)
    half_sgn = 0.5 * np.sign(u)
    return nh + half_sgn, nh - half_sgn


@register("paper")
def assemble_paper(par: Parameters, n: int) -> Blocks:
    """Assemble the collocation blocks of the paper's scheme.

    Parameters
    ----------
    par : Parameters
        Only ``pe``, the conductivity, diffusivity and distortivity ratios are
        used; ``fhpe`` is applied by the solver.
    n : int
        Nodes per unknown function.

    Returns
    -------
    Blocks
    """
    pr = bounded_rule(n)
    fr = singular_rule(n)
    s = pr.collocation[:, None]
    sh = fr.collocation[:, None]
    eta = par.eta
    rho = par.K2_over_K1
    c = par.cylinder_scale

    # Contact equation at s_k.
    up = s - pr.nodes[None, :]
    uq = s - fr.nodes[None, :]
    C = pr.weights[None, :] / (np.pi * up)
    kp, kq_on_p = _contact_kernels(par, up)
    # q = q' + eta p: the pressure carries K_p and eta * K_q.
    Tp = pr.weights[None, :] * (kp + eta * kq_on_p)
    _, kq = _contact_kernels(par, uq)
    Tq = fr.weights[None, :] * kq

    # Heat equation (D18) at s'_k, divided by pi (1 + rho).
    vq = sh - fr.nodes[None, :]
    vp = sh - pr.nodes[None, :]
    Hq = (fr.weights[None, :] / np.pi) * (
        1.0 / vq + (rho / (1.0 + rho)) * cylinder_temperature_gradient_regular(vq, c)
    )
    Hp = (pr.weights[None, :] / np.pi) * (
        2.0 / ((1.0 + rho) * (1.0 + 1.0 / rho)) * cylinder_temperature_gradient_regular(vp, c)
    )

    def integrate(kernel, s_pts, scale=None):
        s_pts = np.asarray(s_pts, dtype=float)[:, None]
        return (pr.weights[None, :] * kernel(s_pts - pr.nodes[None, :]),
                fr.weights[None, :] * kernel(s_pts - fr.nodes[None, :]))

    return Blocks(n, pr, fr, pr.collocation, C, Tp, Tq, Hp, Hq, integrate)
