"""Green's-function kernels of the sliding-contact problem, in dimensionless form.

Every kernel takes the dimensionless separation ``u`` between a field point and a
line source.  For the moving cylinder (body 1) ``u = v (x - xi) / (2 k1)``, i.e.
``u = Pe * (k2/k1) * (s - r)`` in contact coordinates; the cylinder's surface moves
in the ``-x`` direction, so ``u > 0`` is upstream of the source (material that has
not yet passed it) and ``u < 0`` is downstream (its hot wake).  See
``docs/derivation.md`` sections 2-4 for the derivations and checks.

All functions are vectorised over ``u`` and use the exponentially scaled Bessel
functions, so that no factor ``exp(+-u)`` is ever formed on its own: the products
``E``, ``N``, ``M`` and ``k0e`` by the tables of :mod:`.kernel_tables` (SciPy's values to a
few ulps, at a third of their cost), the rest by SciPy's.
"""

from __future__ import annotations

import numpy as np
from scipy.special import k0e, k1e

from .kernel_tables import displacement_table, gradient_tables, slope_table, temperature_table

__all__ = [
    "cylinder_displacement",
    "cylinder_displacement_drop",
    "cylinder_slope",
    "cylinder_temperature",
    "cylinder_temperature_gradient",
    "cylinder_temperature_gradient_regular",
    "half_plane_slope",
    "moving_slope",
]


def cylinder_displacement(u):
    """Outward surface displacement of the moving body per unit heat input.

    ``E(u) = exp(-u) I0(u)`` for ``u >= 0`` and ``E(u) = 1`` for ``u < 0``, in units
    of ``2 delta1 k1 Q1 / v`` (derivation eq. D5, Barber's moving-source solution,
    the paper's eq. 1).  ``E`` is continuous at ``u = 0`` and ``-dE/du`` is
    :func:`cylinder_slope`.

    Parameters
    ----------
    u : array_like
        Dimensionless separation ``v (x - xi) / (2 k1)``.

    Returns
    -------
    ndarray
        ``E(u)``, in ``(0, 1]``.
    """
    u = np.asarray(u, dtype=float)
    up = u > 0.0
    table = displacement_table()
    if u.ndim and up.all():
        return table(u)  # (an array of upstream points: no mask)
    out = np.ones(u.shape)
    out[up] = table(u[up])
    return out


def cylinder_slope(u):
    """Slope kernel ``N(u) H(u)`` of the moving body's thermal distortion.

    ``N(u) = exp(-u) [I0(u) - I1(u)]`` (derivation eq. D7; the paper's eq. 2 writes
    ``I0(-u)``, harmless since ``I0`` is even, and drops the Heaviside factor from
    eq. 12 onward).  The outward slope is ``dw1/dx = -delta1 q1 N(u) H(u)``.  At
    ``u = 0`` the step takes its mean value 1/2.

    Parameters
    ----------
    u : array_like
        Dimensionless separation ``v (x - xi) / (2 k1)``.

    Returns
    -------
    ndarray
        ``N(u) H(u)``; 0 downstream, 1 at the source, ``~ (2 pi u)**-0.5 / (2u)``
        far upstream.
    """
    u = np.asarray(u, dtype=float)
    out = np.where(u == 0.0, 0.5, 0.0)
    up = u > 0.0  # the Bessel functions only upstream, where they are needed
    out[up] = slope_table()(u[up])
    return out


def cylinder_temperature(u):
    """Surface temperature of the moving body per unit line heat input.

    ``exp(-u) K0(|u|)`` in units of ``Q1 / (pi K1)`` (Carslaw and Jaeger's moving
    line source, the paper's eq. 15; derivation eq. D8).  Logarithmically singular
    at ``u = 0``; the hot wake is at ``u < 0``.

    Parameters
    ----------
    u : array_like
        Dimensionless separation, non-zero.

    Returns
    -------
    ndarray
    """
    u = np.asarray(u, dtype=float)
    a = np.abs(u)
    # exp(-u) K0(|u|) = k0e(|u|) * exp(-u - |u|): the exponent is 0 downstream.
    return temperature_table()(a) * np.exp(-u - a)


def cylinder_temperature_gradient(u):
    """Kernel ``M(u)`` of the moving body's surface temperature gradient.

    ``M(u) = exp(-u) [K0(|u|) + sgn(u) K1(|u|)]`` so that
    ``dT1/dx = -(v / (2 pi k1 K1)) * integral M(u) q1 dxi`` (derivation eqs. D9, D10).
    The paper's ``M = exp(-u) [K0(u) + K1(u)]`` is not real for ``u < 0``; this is
    its continuation.  ``M(u) = 1/u - ln|u| + O(1)`` as ``u -> 0``.

    Parameters
    ----------
    u : array_like
        Dimensionless separation, non-zero.

    Returns
    -------
    ndarray
    """
    u = np.asarray(u, dtype=float)
    out = np.zeros(u.shape)
    # exp(-2u) upstream, 1 in the wake; the Bessel functions only where the scale
    # does not underflow (exp(-745) is below the smallest subnormal; NaN passes).
    live = ~(u >= 372.0)
    x = u[live]
    out[live] = _gradient(x, np.abs(x))
    return out[()]


def _gradient(x, a):
    """``M(x) = exp(-x - a) [k0e(a) + sgn(x) k1e(a)]`` with ``a = |x|``: the formula of
    :func:`cylinder_temperature_gradient` without its cut-off (callers keep ``x < 372``).
    Upstream ``exp(-2a) [k0e(a) + k1e(a)]``, in the wake ``k0e(a) - k1e(a)``, each by
    its table (:func:`.kernel_tables.gradient_tables`)."""
    upstream, wake = gradient_tables()
    out = np.empty(np.shape(x))
    up = x > 0.0
    down = ~up
    xu = a[up]
    out[up] = np.exp(-2.0 * xu) * upstream(xu)
    out[down] = wake(a[down])
    return out


#: ``c u`` beyond which ``c M(c u)`` no longer changes ``c M(c u) - 1/u`` in floating
#: point (:func:`cylinder_temperature_gradient_regular`).
UPSTREAM_NEGLIGIBLE = 22.0


def cylinder_temperature_gradient_regular(u, scale):
    """The Cauchy-free part ``c M(c u) - 1/u`` of the scaled gradient kernel.

    With ``c = Pe k2/k1`` and ``u = s - r`` this is the kernel left in the heat
    equation after its ``1/(s - r)`` part is taken out (derivation eq. D16); it is
    only logarithmically singular at ``u = 0``.

    Parameters
    ----------
    u : array_like
        Separation ``s - r`` in contact coordinates, non-zero.
    scale : float
        ``c = Pe k2/k1 > 0``.

    Returns
    -------
    ndarray
    """
    u = np.asarray(u, dtype=float)
    cu = scale * u
    # For small |cu| the two terms cancel to O(ln|cu|); form the difference with
    # the series of k1e to keep full relative accuracy there.
    small = np.abs(cu) < 1e-3
    # Far upstream c M(c u) = c exp(-2cu) [...] is below half an ulp of 1/u
    # (x M(x) < 1e-18 for x >= 22): the kernel is -1/u there to the last bit, without
    # its Bessel functions.
    upstream = cu >= UPSTREAM_NEGLIGIBLE
    out = np.full_like(cu, np.nan)  # (NaN where u is)
    if np.any(upstream):
        out[upstream] = -1.0 / u[upstream]
    # Between, M's two forms (_gradient's), each on its own side: none of these points
    # is beyond the gradient's own cut-off (|c u| < 22 upstream).
    near, wake = gradient_tables()
    ahead = (cu >= 1e-3) & ~upstream
    if np.any(ahead):
        x = cu[ahead]
        out[ahead] = scale * (np.exp(-2.0 * x) * near(x)) - 1.0 / u[ahead]
    behind = cu <= -1e-3
    if np.any(behind):
        out[behind] = scale * wake(-cu[behind]) - 1.0 / u[behind]
    if np.any(small):
        x = cu[small]
        out[small] = scale * _regular_series(x)
    return out


def _regular_series(x):
    """``M(x) - 1/x`` for ``|x| < 1e-3`` from the ascending Bessel series.

    With ``L = ln(z/2) + gamma`` and ``z = |x|``:
    ``K0(z) = -L + (z^2/4)(1 - L) + O(z^4 ln z)`` and
    ``K1(z) = 1/z + (z/2)(L - 1/2) + (z^3/16)(L - 5/4) + O(z^5 ln z)``
    (Abramowitz and Stegun 9.6.11, 9.6.13); the neglected terms are below 1e-13
    of the result for ``|x| < 1e-3``.
    """
    z = np.abs(x)
    sg = np.sign(x)
    lg = np.log(z / 2.0) + np.euler_gamma
    k0 = -lg + 0.25 * z * z * (1.0 - lg)
    k1_rest = sg * (0.5 * z * (lg - 0.5) + z**3 / 16.0 * (lg - 1.25))
    e = np.exp(-x)
    # exp(-x) sgn(x) K1(|x|) - 1/x = (exp(-x) - 1)/x + exp(-x) * k1_rest
    return e * k0 + np.expm1(-x) / x + e * k1_rest


def half_plane_slope(u):
    """Slope kernel ``sgn(u)/2`` of the stationary half-plane's thermal distortion.

    The outward slope is ``dw2/dx = -delta2 * integral q2(xi) sgn(x - xi)/2 dxi``
    (Dundurs; the paper's eq. 3 with its inward sign convention; derivation eq. D4).

    Parameters
    ----------
    u : array_like
        Separation ``x - xi`` in any units.

    Returns
    -------
    ndarray
    """
    return 0.5 * np.sign(np.asarray(u, dtype=float))


def moving_slope(u, scale):
    """Slope kernel ``sgn(c) N(c u) H(c u)`` of a moving half-plane's distortion.

    A body whose surface moves through the contact toward ``-x`` (``c > 0``, the
    cylinder) or ``+x`` (``c < 0``) has outward slope
    ``dw/dx = -delta * integral q(xi) sgn(c) N(c u) H(c u) dxi`` with ``u = s - r``
    and ``c = v Delta/(2 k)`` signed (derivation eq. D7 and, for ``c < 0``, its
    mirror image, section 5b).  ``cylinder_slope(c u)`` is the case ``c > 0``.

    Parameters
    ----------
    u : array_like
        Separation ``s - r`` in contact coordinates.
    scale : float
        Signed ``c``, non-zero.

    Returns
    -------
    ndarray
    """
    slope = cylinder_slope(scale * np.asarray(u, dtype=float))
    if np.ndim(scale) == 0 and scale > 0.0:
        return slope  # sgn(c) N H, without a product by 1
    return np.sign(scale) * slope


#: The 2-point Gauss–Legendre rule on [-1, 1].
_GAUSS_2 = np.polynomial.legendre.leggauss(2)


def cylinder_displacement_drop(a, h):
    """``E(a) - E(a + h)`` elementwise for ``a, h >= 0``: the slope kernel integrated.

    The difference has an absolute error of about ``eps E(a)``, which enters the gap
    multiplied by ``F d / c``: below ``1e-10`` of the gap's ``(|s| - 1)^{3/2}``
    term for ``h >= 1e-3``.  For ``h < 1e-3`` the drop is the integral of
    ``N H = -E'`` over ``[a, a + h]`` by 2-point Gauss–Legendre (relative error
    about ``h^4 / 4320``, 3e-15 at ``h = 1e-3``), accurate however close to the edge.
    """
    a, h = np.asarray(a, dtype=float), np.asarray(h, dtype=float)
    if a.ndim == 2 and h.shape == (a.shape[0], 1):
        return _drop_rows(a, h[:, 0])
    a, h = np.broadcast_arrays(a, h)
    small = h < 1e-3
    if a.ndim and not small.any():
        return cylinder_displacement(a) - cylinder_displacement(a + h)
    out = np.empty(a.shape)
    big = ~small
    above = a[big]
    out[big] = cylinder_displacement(above) - cylinder_displacement(above + h[big])
    if np.any(small):
        x, wq = _GAUSS_2
        hs = h[small][:, None]
        pts = a[small][:, None] + 0.5 * hs * (1.0 + x[None, :])
        out[small] = 0.5 * hs[:, 0] * (cylinder_slope(pts) @ wq)
    return out


def _drop_rows(a, h):
    """:func:`cylinder_displacement_drop` of rows ``a`` (k, m) each with its own ``h``
    (k,) (the gap's points, each its own distance past the edge): the same operations
    on each value, the rows of small and wide ``h`` taken whole instead of value by
    value."""
    small = h < 1e-3
    if not small.any():
        return cylinder_displacement(a) - cylinder_displacement(a + h[:, None])
    out = np.empty(a.shape)
    wide = np.flatnonzero(~small)
    if wide.size:
        above = a[wide]
        out[wide] = cylinder_displacement(above) - cylinder_displacement(above + h[wide, None])
    narrow = np.flatnonzero(small)
    x, wq = _GAUSS_2
    hs = np.repeat(h[narrow], a.shape[1])[:, None]
    pts = a[narrow].reshape(-1)[:, None] + 0.5 * hs * (1.0 + x[None, :])
    out[narrow] = (0.5 * hs[:, 0] * (cylinder_slope(pts) @ wq)).reshape(narrow.size, -1)
    return out
