"""Element operators: constant elements, Green's functions integrated exactly over each.

Equal elements of width ``h`` (units of the Hertz half-width ``l``) carry constant
pressure ``p_k`` and heat-flux difference ``q_k`` (derivation section 14b).  Each
operator maps them to the gap (units ``l^2/R``) and the surface temperature difference
(units ``f v P/(pi K2)``) at the elements' centres:

* Flamant: the gap gains ``-(1/2) integral p(Y) ln|X - Y| dY``;
* the cylinder's thermal bulge ``-(pi/2) F (d/c) integral E(c(X - Y)) (p + q) dY``
  (D5; ``integral exp(-v) I0(v) dv = v exp(-v) (I0 + I1)``);
* the stationary half-plane's ``+(pi/2) F integral |X - Y|/2 (p - q) dY`` (D4);
* the temperatures: ``rho integral q1 exp(-u) K0(|u|) dY + integral q2 ln|X - Y| dY``
  (D8, D12; ``u = c (X - Y)``, ``integral exp(-v) K0(v) dv = v exp(-v) (K0 - K1)`` for
  ``v > 0``).

The same operators with the time-domain tables of :mod:`.history` in place of the
steady kernels are the transient contact's (section 19).
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import cached_property

import numpy as np
from scipy.special import i0e, i1e, k0e, k1e

__all__ = ["ElementOperators", "displacement_integral", "element_matrix", "flamant_operator",
           "log_integral", "steady_element_operators", "temperature_integral"]


def log_integral(u):
    """Antiderivative of ``ln|u|``: ``u ln|u| - u`` (0 at ``u = 0``)."""
    a = np.abs(u)
    with np.errstate(divide="ignore", invalid="ignore"):
        out = u * np.log(np.where(a > 0.0, a, 1.0)) - u
    return out


def displacement_integral(v):
    """Antiderivative of ``E(v)`` (``exp(-v) I0(v)``, 1 for ``v <= 0``), 0 at 0."""
    vp = np.maximum(v, 0.0)
    return np.where(v > 0.0, vp * (i0e(vp) + i1e(vp)), v)


def temperature_integral(v):
    """Antiderivative of ``exp(-v) K0(|v|)``: ``-1`` at ``v = 0``, continuous."""
    a = np.abs(v)
    with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
        ahead = a * np.exp(-2.0 * a) * (k0e(a) - k1e(a))
        behind = -a * (k0e(a) + k1e(a))
    out = np.where(v > 0.0, ahead, behind)
    return np.where(a == 0.0, -1.0, out)


def element_matrix(antiderivative, X, Y, h, scale=1.0):
    """``M[i, k] = integral over element k of K(scale (X_i - Y))`` by the antiderivative."""
    u = X[:, None] - Y[None, :]
    return (antiderivative(scale * (u + 0.5 * h)) - antiderivative(scale * (u - 0.5 * h))) / scale


@dataclass(frozen=True)
class ElementOperators:
    """Gap and temperature operators on ``(p, q)``, ``q1 = (p + q)/2``, ``q2 = (p - q)/2``.

    ``gap = g0 - D + Gp p + Gq q`` and ``theta1 - theta2 = Tp p + Tq q`` at the centres
    (section 14b), each body's thermal part also kept alone: ``gap1``, ``gap2`` (the
    thermal bulges per unit ``q1``, ``q2``) and ``theta1``, ``theta2`` (each body's
    temperature rise per unit ``q1``, ``q2``), so that
    ``Gp = flamant + (gap1 + gap2)/2``, ``Gq = (gap1 - gap2)/2``,
    ``Tp = (theta1 - theta2)/2``, ``Tq = (theta1 + theta2)/2``.
    """

    flamant: np.ndarray
    gap1: np.ndarray
    gap2: np.ndarray
    theta1: np.ndarray
    theta2: np.ndarray

    @cached_property
    def Gp(self):
        return self.flamant + 0.5 * (self.gap1 + self.gap2)

    @cached_property
    def Gq(self):
        return 0.5 * (self.gap1 - self.gap2)

    @cached_property
    def Tp(self):
        return 0.5 * (self.theta1 - self.theta2)

    @cached_property
    def Tq(self):
        return 0.5 * (self.theta1 + self.theta2)


def flamant_operator(X, h):
    """``-(1/2) integral over each element of ln|X_i - Y| dY`` (D1, undifferentiated)."""
    return -0.5 * element_matrix(log_integral, X, X, h)


def steady_element_operators(par, X, h) -> ElementOperators:
    """The steady operators (section 14b) of a stationary half-plane without the Dundurs
    term, ``par.pe = Pe_l`` and ``par.fhpe = F_l`` in units of ``l``."""
    F, c, d, rho = par.fhpe, par.cylinder_scale, par.delta1_over_delta2, par.K2_over_K1
    # Per unit q1 = (p + q)/2: -pi F d E(cu)/c; per unit q2: +pi F |u|/2 (D4, D5).
    gap1 = -np.pi * F * (d / c) * element_matrix(displacement_integral, X, X, h, c)
    gap2 = np.pi * F * element_matrix(lambda u: 0.25 * u * np.abs(u), X, X, h)
    theta1 = rho * element_matrix(temperature_integral, X, X, h, c)
    theta2 = -element_matrix(log_integral, X, X, h)
    return ElementOperators(flamant_operator(X, h), gap1, gap2, theta1, theta2)
