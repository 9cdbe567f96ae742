"""Limiting cases with independent solutions, used to check the main solver.

Besides the contact's two limits below, :func:`layer_neutral_speed` gives the
thermoelastic instability of a conducting layer between non-conducting pads in
closed form (derivation, "Thermoelastic instability of layers", L11), an
independent check of the layered dispersion relation.

Two limits are provided, in the dimensionless contact coordinate ``-1 < s < 1``
with the pressure ``phat(s) >= 0`` (compressive) normalised to unit integral:

* :func:`hertz_pressure`, the isothermal (Hertz) pressure;
* :func:`barber_insulated`, Barber's insulated, non-distorting cylinder sliding on
  a conducting half-plane that receives all the frictional heat.  It solves

  .. math::

     \\frac{1}{\\pi}\\,\\mathrm{PV}\\!\\int_{-1}^{1}\\frac{\\hat p(r)}{s-r}\\,dr
     - F\\int_{-1}^{1}\\hat p(r)\\,\\mathrm{sgn}(s-r)\\,dr
     = \\frac{2}{\\pi} L\\,(\\sigma + s), \\qquad |s| < 1,            (B1 = D23)

  with ``integral phat = 1`` and ``phat`` bounded (square-root zero) at both
  ends.  ``F = fHPe``, ``L = P_H / P`` and ``sigma`` is the contact offset over
  ``Delta``.  The method is a Galerkin projection of a sine series, entirely
  independent of the Gauss–Chebyshev collocation of the main solver.

Two properties of (B1) are worth knowing.  Both kernels are odd (the sgn
kernel is the stationary half-plane's), so an even pressure gives an odd left
side: ``phat`` is even and ``sigma = 0`` for every ``F``, not only at first
order.  And ``L`` falls
through zero at ``F = 0.57888694...``: beyond it no positive load produces a
contact of that width (``L = P_H / P`` would be negative).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..io.results import Result
from ..problem.validation import check_integer, check_nonnegative

__all__ = ["BarberSolution", "barber_insulated", "hertz_pressure", "layer_compliance",
           "layer_neutral_speed", "layer_thermal_displacement"]

#: Default number of sine terms.  ``L`` converges like ``n**-6`` (measured), so
#: it is at round-off here for ``F <= 5``; the pressure converges like ``n**-3``
#: next to the edges and ``n**-4`` inside, giving about 2e-10 and 1e-12 here.
DEFAULT_TERMS = 1024

# Points per block when evaluating the series, to bound the (points x terms)
# work array (16 MB at the default n).
_BLOCK = 2048


def hertz_pressure(s):
    """Normalised Hertz pressure ``(2/pi) sqrt(1 - s^2)``.

    This is the ``F = 0`` solution of (B1), with ``L = 1`` and ``sigma = 0``:
    ``(1/pi) PV integral sqrt(1 - r^2) / (s - r) dr = s``.  Its integral over
    ``[-1, 1]`` is 1.

    Parameters
    ----------
    s : array_like
        Dimensionless position, ``x / a``.

    Returns
    -------
    ndarray
        ``phat(s)``; zero for ``|s| >= 1``.
    """
    s = np.asarray(s, dtype=float)
    return (2.0 / np.pi) * np.sqrt(np.maximum(1.0 - s * s, 0.0))


@dataclass(frozen=True, eq=False, repr=False)
class BarberSolution(Result):
    """Solution of Barber's insulated-cylinder problem (B1) for one ``F``.

    The pressure is the sine series in ``s = cos(t)``

    .. math:: \\hat p(\\cos t) = \\sum_{j=0}^{n-1} b_j \\sin((j+1)t)
              = \\sqrt{1-s^2}\\sum_j b_j U_j(s),                          (B2)

    with ``b_0 = 2/pi`` fixed by ``integral phat = 1``.

    Attributes
    ----------
    fhpe : float
        Heating parameter ``F = fHPe >= 0``.
    load_ratio : float
        ``L = P_H / P``: Hertz load for the same half-width over the actual load.
    sigma_over_delta : float
        Contact offset ``sigma / Delta`` (zero up to round-off, by symmetry).
    coefficients : ndarray, shape (n,)
        ``b_j`` of (B2), read-only.
    n : int
        Number of terms.
    """

    fhpe: float
    load_ratio: float
    sigma_over_delta: float
    coefficients: np.ndarray
    n: int

    def pressure(self, s):
        """Evaluate the pressure series (B2).

        Parameters
        ----------
        s : array_like
            Dimensionless position.

        Returns
        -------
        ndarray
            ``phat(s)``, same shape as ``s``; zero for ``|s| >= 1``.
        """
        s = np.asarray(s, dtype=float)
        flat = s.ravel()
        out = np.zeros(flat.shape)
        inside = np.flatnonzero(np.abs(flat) < 1.0)
        k = np.arange(1, self.n + 1, dtype=float)
        for start in range(0, inside.size, _BLOCK):
            idx = inside[start:start + _BLOCK]
            # sin((j+1) t) term by term rather than a U_j recurrence: exact to
            # round-off even next to the edges, where U_j(s) ~ j + 1 is large.
            t = np.arccos(flat[idx])
            out[idx] = np.sin(np.outer(t, k)) @ self.coefficients
        return out.reshape(s.shape)


def _parity_block(F, n, parity):
    """Galerkin rows ``m = parity, parity + 2, ... <= n`` of (B3).

    ``int_0^pi sin(k t) cos(m t) dt`` vanishes unless ``k + m`` is odd, so the
    rows of even ``m`` involve only the odd ``b_j`` and ``L sigma``, and the rows
    of odd ``m`` only the even ``b_j`` (``j >= 2``) and ``L``.  Solving the two
    blocks separately is exact and four times cheaper than the full system.

    Returns
    -------
    b : ndarray
        The ``b_j`` with ``j = 1 + parity, 3 + parity, ... <= n - 1``.
    scalar : float
        ``L`` for ``parity = 1``, ``L sigma`` for ``parity = 0``.
    """
    b0 = 2.0 / np.pi
    m = np.arange(parity, n + 1, 2, dtype=float)[:, None]
    j = np.arange(1 + parity, n, 2, dtype=float)[None, :]
    # Moment of the b_j bracket of (B4); with k + m odd, S_km / k = 2/(k^2-m^2).
    G = 1.0 / ((j + 2.0) ** 2 - m**2) - 1.0 / (j**2 - m**2)
    m = m[:, 0]
    if parity:
        # b_0 bracket: ramp moment 2/m^2, sin(2t) moment 4/(4 - m^2).
        g0 = 1.0 / m**2 + 1.0 / (4.0 - m**2)
        ones = np.zeros_like(m)
    else:
        # Only m = 0 survives: ramp moment pi^2/2, constant moment pi.
        g0 = np.where(m == 0.0, 0.25 * np.pi**2, 0.0)
        ones = np.where(m == 0.0, np.pi, 0.0)

    rows = m.size
    A = np.zeros((rows, rows))
    # cos((j+1) theta) against cos(m theta): pi/2 on j = m - 1.
    A[np.arange(1, rows), np.arange(rows - 1)] = 0.5 * np.pi
    A[:, : rows - 1] -= 2.0 * F * G
    # (2/pi) L cos(theta) gives L in row m = 1; (2/pi) L sigma gives 2 L sigma
    # in row m = 0.
    A[0, rows - 1] = -1.0 if parity else -2.0
    rhs = F * (2.0 * b0 * g0 - ones)
    if parity:
        rhs[0] -= 0.5 * np.pi * b0  # the known b_0 term of row m = 1
    x = np.linalg.solve(A, rhs)
    return x[:-1], float(x[-1])


def barber_insulated(fhpe, n=DEFAULT_TERMS):
    """Solve Barber's insulated-cylinder problem (B1) by a Galerkin method.

    With ``s = cos(theta)`` and the series (B2), the finite Hilbert transform
    ``(1/pi) PV integral sqrt(1-r^2) U_j(r) / (s - r) dr = T_{j+1}(s)`` and
    ``integral phat(r) sgn(s - r) dr = 2 C(s) - 1`` turn (B1) into

    .. math::

       \\sum_j b_j \\cos((j+1)\\theta) - F\\,[2C - 1]
       = \\frac{2}{\\pi}\\,(L\\sigma + L\\cos\\theta),                      (B3)

    where the cumulative load ``C(cos theta) = integral_theta^pi phat sin t dt``
    is, exactly,

    .. math::

       C = b_0\\Big[\\frac{\\pi-\\theta}{2} + \\frac{\\sin 2\\theta}{4}\\Big]
         + \\sum_{j\\ge1}\\frac{b_j}{2}\\Big[\\frac{\\sin(j+2)\\theta}{j+2}
         - \\frac{\\sin j\\theta}{j}\\Big].                                 (B4)

    (B3) is projected onto ``cos(m theta)``, ``m = 0..n``, over ``(0, pi)``
    using the closed-form moments ``int cos k t cos m t = (pi/2) delta_km``,
    ``int sin k t cos m t = 2k/(k^2 - m^2)`` (``k + m`` odd, else 0) and
    ``int (pi - t) cos m t = pi^2/2`` (``m = 0``), ``(1 - (-1)^m)/m^2``.
    That gives ``n + 1`` linear equations for ``b_1..b_{n-1}``, ``L`` and
    ``L sigma``, which split exactly by parity (:func:`_parity_block`); the
    ``m = 0`` row is the boundedness (consistency) condition.
    The edge behaviour ``(1 -+ s)^{3/2} log(1 -+ s)`` makes ``b_j`` decay like
    ``j^-4``, so ``L`` converges like ``n^-6`` and the pressure like ``n^-3``
    (uniformly; ``n^-4`` away from the edges).

    Parameters
    ----------
    fhpe : float
        ``F = fHPe``, finite and ``>= 0``.
    n : int, optional
        Number of sine terms, ``>= 1``.  With the default, ``L`` is at
        round-off for ``F <= 5`` and the pressure is within about 2e-10 of the
        limit ``n -> infinity`` (1e-12 away from the edges).  The error grows
        with ``F``, so raise ``n`` well beyond ``F = 5``.

    Returns
    -------
    BarberSolution

    Raises
    ------
    ValueError
        If ``fhpe`` is not finite and ``>= 0``, or ``n`` is not an integer
        ``>= 1``.
    """
    F = check_nonnegative("fhpe", fhpe)
    n = check_integer("n", n, 1)

    b_even, load_ratio = _parity_block(F, n, 1)
    b_odd, l_sigma = _parity_block(F, n, 0)
    # sigma is only defined while L != 0; at the zero-load F it is indeterminate.
    sigma = l_sigma / load_ratio if load_ratio != 0.0 else math.nan

    coefficients = np.empty(n)
    coefficients[0] = 2.0 / np.pi
    coefficients[2::2] = b_even
    coefficients[1::2] = b_odd
    coefficients.setflags(write=False)
    return BarberSolution(F, load_ratio, sigma, coefficients, n)


def layer_compliance(layer, thickness, m, family):
    """Inward displacement of a free layer's faces per unit pressure ``P e^{imx}`` on
    both faces, m/Pa (L11a; plane strain, no shear on the faces): with
    ``x = m d/2``,

    * symmetric (equal pressures, the thickness compressed):
      ``(1 - nu)/(mu m) sinh^2 x/(x + sinh x cosh x)``;
    * antisymmetric (opposite pressures, the layer bent):
      ``(1 - nu)/(mu m) cosh^2 x/(sinh x cosh x - x)``.

    Both tend to the half-plane's ``(1 - nu)/(mu m)`` for a thick layer; the
    antisymmetric one to the plate's ``12 (1 - nu)/(mu m^4 d^3)`` for a thin one.
    From Airy's stress function ``cosh``/``y sinh`` (symmetric) or
    ``sinh``/``y cosh`` (antisymmetric) in ``y``.
    """
    x = 0.5 * m * thickness
    sh, ch = math.sinh(x), math.cosh(x)
    base = (1.0 - layer.nu) / (layer.mu * m)
    if family == "symmetric":
        return base * sh * sh / (x + sh * ch)
    return base * ch * ch / (sh * ch - x)


def layer_thermal_displacement(layer, thickness, m, family):
    """Outward displacement of a free layer's faces per unit face temperature, m/K,
    for the steady temperature ``cosh(m y)/cosh(m d/2)`` (symmetric) or
    ``sinh(m y)/sinh(m d/2)`` (antisymmetric) about the mid-plane ``y = 0``
    (L11b, plane strain).

    The displacement potential ``Omega = a y sinh(m y)/(2 m cosh(m d/2))`` (or with
    ``cosh`` and ``sinh`` exchanged), ``a = alpha (1 + nu)/(1 - nu)``, leaves
    tractions at the faces that Airy's stress function ``F`` cancels, with
    ``F = 2 mu Omega`` and ``dF/dy = 2 mu dOmega/dy`` there.  The face's
    displacement is ``dOmega/dy`` plus Airy's,
    ``-F_y/mu + ((1 - nu) F_yyy + nu m^2 F_y)/(2 mu m^2)``.
    """
    mu, nu = layer.mu, layer.nu
    pot = layer.alpha * (1.0 + nu) / (1.0 - nu)
    c = 0.5 * thickness
    x = m * c
    sh, ch = math.sinh(x), math.cosh(x)
    if family == "symmetric":
        om, dom = c * sh / (2.0 * m * ch), (sh + x * ch) / (2.0 * m * ch)
        Fc, Fp = 2.0 * mu * pot * om, 2.0 * mu * pot * dom
        det = sh * ch + x
        A = (Fc * (sh + x * ch) - c * sh * Fp) / det      # F = A cosh + B y sinh
        B = (ch * Fp - m * sh * Fc) / det
        F3 = A * m**3 * sh + B * (3.0 * m * m * sh + m**3 * c * ch)
    else:
        om, dom = c * ch / (2.0 * m * sh), (ch + x * sh) / (2.0 * m * sh)
        Fc, Fp = 2.0 * mu * pot * om, 2.0 * mu * pot * dom
        det = sh * ch - x
        A = (Fc * (ch + x * sh) - c * ch * Fp) / det      # F = A sinh + B y cosh
        B = (sh * Fp - m * ch * Fc) / det
        F3 = A * m**3 * ch + B * (3.0 * m * m * ch + m**3 * c * sh)
    return pot * dom - Fp / mu + ((1.0 - nu) * F3 + nu * m * m * Fp) / (2.0 * mu * m * m)


def layer_neutral_speed(layer, thickness, m, friction, family, pad=None):
    """The neutral speed of a conducting layer (full thickness ``d``) rubbing on both
    faces against non-conducting pads, m/s (L11): all the frictional heat enters the
    layer, the pads only yield elastically, and the neutral mode is at rest on the
    layer, where the temperature is steady (``gamma = m``):

    ``V = K m t (C_layer + C_pad)/(f W)``,

    ``t = tanh(m d/2)`` (symmetric) or ``coth(m d/2)`` (antisymmetric), ``C_layer``
    of :func:`layer_compliance`, ``C_pad = (1 - nu_p)/(mu_p m)`` of an elastic
    half-plane pad (0 for a rigid one, ``pad=None``) and ``W`` of
    :func:`layer_thermal_displacement`.  Plane strain, no Dundurs term."""
    x = 0.5 * m * thickness
    t = math.tanh(x) if family == "symmetric" else 1.0 / math.tanh(x)
    c_pad = 0.0 if pad is None else (1.0 - pad.nu) / (pad.mu * m)
    return (layer.K * m * t * (layer_compliance(layer, thickness, m, family) + c_pad)
            / (friction * layer_thermal_displacement(layer, thickness, m, family)))
