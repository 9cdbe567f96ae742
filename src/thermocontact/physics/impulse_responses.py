"""A half-plane's surface response to an instantaneous surface line source, in time.

The time-domain Green's functions of the transient contact (derivation section 19,
eqs. R1-R6).  One half-plane ``y < 0`` (diffusivity ``kappa``, distortivity ``delta``)
whose material moves toward ``-x`` at speed ``v``; at ``t = 0`` an energy ``E`` per
unit length is released at the surface point ``xi``.  In the transient contact's units
(lengths in ``l``, time in ``l^2/kappa2``) with the body's diffusivity ratio
``r = kappa/kappa2`` and its convection speed ``s = v l/kappa2`` (``2 Pe_l`` for the
cylinder, ``0`` for the stationary half-plane), the surface temperature and the
outward displacement are, per unit of time ``tau`` after the release and with
``U = x - xi + s tau``:

* temperature (Carslaw and Jaeger, image-doubled): ``exp(-U^2/(4 r tau))/(2 tau)``
  times ``E/(pi K)`` (R1);
* displacement (Barber's transient distortion, eq. T8):
  ``(4 r/(pi^(3/2) U)) F(U/(2 sqrt(r tau)))`` times ``delta E``, ``F`` Dawson's
  integral (R2).

Their integrals over ``tau`` from 0 to infinity are the steady kernels (D5), (D8) of
:mod:`thermocontact.physics.green_functions` (R3); their Laplace transforms in
``tau`` are (T3), (T9).  What the contact needs is each integrated over a constant
element of width ``h`` centred ``X`` away from the point of evaluation:

* ``sqrt(pi r tau) [erf(z+) - erf(z-)] / (2 tau)`` (R4),
* ``(4 r/pi^(3/2)) [Phi(z+) - Phi(z-)]`` (R5),

``z+- = (X + s tau +- h/2)/(2 sqrt(r tau))`` and ``Phi(Z) = integral_0^Z F(z)/z dz``
(R6), here by a cubic Hermite table on ``[0, 16]`` (its derivative ``F(z)/z`` is known)
and the asymptotic series beyond.
"""

from __future__ import annotations

import numpy as np
from scipy.special import dawsn, erf

__all__ = ["dawson_log_integral", "element_displacement", "element_temperature",
           "PHI_INFINITY"]

#: ``Phi(infinity) = pi^(3/2)/4`` (R6).
PHI_INFINITY = np.pi ** 1.5 / 4.0
_Z_MAX = 16.0
_STEP = 1.0 / 2048.0


def _dawson_ratio(z):
    """``F(z)/z``, 1 at ``z = 0``."""
    z = np.asarray(z, dtype=float)
    small = np.abs(z) < 1e-4
    zz = np.where(small, 1.0, z)
    return np.where(small, 1.0 - 2.0 * z * z / 3.0, dawsn(zz) / zz)


def _table():
    nodes = np.arange(0.0, _Z_MAX + 0.5 * _STEP, _STEP)
    x, w = np.polynomial.legendre.leggauss(12)
    mid = 0.5 * (nodes[1:] + nodes[:-1])
    pts = mid[:, None] + 0.5 * _STEP * x[None, :]
    cells = 0.5 * _STEP * (_dawson_ratio(pts) @ w)
    # Compensated running sum: the plain one drifts by 1.5e-14 over the 32768 cells.
    total = np.add.accumulate(cells)
    before = np.concatenate([[0.0], total[:-1]])
    added = total - before
    lost = (before - (total - added)) + (cells - added)
    values = np.concatenate([[0.0], total + np.add.accumulate(lost)])
    return values, _dawson_ratio(nodes)


_VALUES, _SLOPES = _table()
#: The asymptotic series of ``PHI_INFINITY - Phi(Z)``: ``sum a_n / Z^(2n+1)``,
#: ``a_n = (2n - 1)!!/(2^(n+1) (2n + 1))`` (from ``F(z) ~ sum (2n-1)!!/(2^(n+1) z^(2n+1))``).
_ASYMPTOTIC = np.array([1.0 / 2, 1.0 / 12, 3.0 / 40, 15.0 / 112, 105.0 / 288,
                        945.0 / 704, 10395.0 / 1664])


def dawson_log_integral(Z):
    """``Phi(Z) = integral_0^Z F(z)/z dz`` (R6), odd, ``PHI_INFINITY`` at infinity.

    Equivalently ``(sqrt(pi)/2) integral_0^(pi/2) erf(Z cos theta) d theta``.  A cubic
    Hermite interpolation of its values and exact slopes on a grid of ``1/2048`` for
    ``|Z| <= 16`` (error below 1e-15), the asymptotic series beyond (its first omitted
    term ``135135/(3840 Z^15)`` is below 4e-17).
    """
    Z = np.asarray(Z, dtype=float)
    a = np.abs(Z)
    inside = a < _Z_MAX
    t = np.where(inside, a, 0.0) / _STEP
    i = np.minimum(t.astype(np.intp), _VALUES.size - 2)
    f = t - i
    y0, y1 = _VALUES[i], _VALUES[i + 1]
    d0, d1 = _SLOPES[i] * _STEP, _SLOPES[i + 1] * _STEP
    f2, f3 = f * f, f * f * f
    inner = (y0 * (2 * f3 - 3 * f2 + 1) + d0 * (f3 - 2 * f2 + f) + y1 * (-2 * f3 + 3 * f2)
             + d1 * (f3 - f2))
    big = np.where(inside, _Z_MAX, a)
    inv = 1.0 / big
    inv2 = inv * inv
    tail = np.zeros_like(big)
    for coef in _ASYMPTOTIC[::-1]:
        tail = tail * inv2 + coef
    outer = PHI_INFINITY - tail / big
    return np.sign(Z) * np.where(inside, inner, outer)


def _arguments(X, tau, h, r, s):
    root = 2.0 * np.sqrt(r * tau)
    U = X + s * tau
    return (U + 0.5 * h) / root, (U - 0.5 * h) / root


def element_temperature(X, tau, h, r=1.0, s=0.0):
    """Temperature (R4) of an element of width ``h`` at ``X`` from its centre, per unit
    ``tau``, ``tau > 0``; times ``E/(pi K)`` per unit element-flux."""
    zp, zm = _arguments(X, tau, h, r, s)
    return np.sqrt(np.pi * r / tau) * 0.5 * (erf(zp) - erf(zm))


def element_temperature_sigma(X, sigma, h, r=1.0, s=0.0):
    """(R4) times ``d tau/d sigma = 2 sigma`` with ``tau = sigma^2``: bounded at 0."""
    zp, zm = _arguments(X, sigma * sigma, h, r, s)
    return np.sqrt(np.pi * r) * (erf(zp) - erf(zm))


def element_displacement(X, tau, h, r=1.0, s=0.0):
    """Displacement (R5) of an element of width ``h`` at ``X`` from its centre, per unit
    ``tau``; times ``delta E`` per unit element-flux."""
    zp, zm = _arguments(X, tau, h, r, s)
    return (4.0 * r / np.pi ** 1.5) * (dawson_log_integral(zp) - dawson_log_integral(zm))
