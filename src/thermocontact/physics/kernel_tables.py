"""The moving body's Bessel products by table: piecewise polynomials on geometric panels.

The kernels of :mod:`~thermocontact.physics.green_functions` are products of the
exponentially scaled Bessel functions,

    E(x) = i0e(x),   N(x) = i0e(x) - i1e(x),   G+-(a) = k0e(a) +- k1e(a),   T(a) = k0e(a),

evaluated at every node of every moment of a grid line's assemblies and validity
checks (some 400 000 values a line of the benchmark map).  SciPy evaluates each
Bessel function by its own Chebyshev series, 40 to 60 ns a value on the benchmark's
machine, and a kernel needs two of them; a table evaluates the product at once, in
about a third of that.

Each table covers ``2^-10 <= x < 2^22`` in octaves ``[2^E, 2^(E + 1))`` (``E`` and ``N``,
analytic at 0, also ``[0, 2^-10)`` as one more panel), each octave cut into
:data:`PANELS` panels of equal length (the ratio of a panel's ends at most
``1 + 2/PANELS``), and holds on each panel the polynomial of degree :data:`DEGREE`
through the function's SciPy values at the panel's Chebyshev points, in the panel's
variable ``t in [-1, 1]``.  The functions are analytic on ``x > 0`` with at most a
pole or a logarithm at ``x = 0``, so on a panel ``[a, b]`` the interpolant's
truncation error falls like ``rho^-(DEGREE + 1)``, ``rho = c + sqrt(c^2 - 1)``,
``c = (b + a)/(b - a) = 129``: about ``1e-17`` of the value at degree 6 (at degree
5, 3e-15: measured 26 ulps next to the pole of ``G+-``).  What remains is the samples'
own rounding (SciPy's, a few ulps; for ``N`` and ``G-`` at large ``x`` the
cancellation of the difference, about ``eps x``) times the interpolant's Lebesgue
constant (about 2.2 for 7 Chebyshev points), and the evaluation's rounding.
Measured against mpmath (``tests/test_kernel_tables.py``): relative errors of at most
8 ulps for ``E`` and ``G+``, and for ``N`` and ``G-`` at most ``8 (1 + x)`` and
``16 (1 + x)`` ulps, the bounds SciPy's own differences meet (``G-`` up to 32 ulps
next to ``x = 2``, where SciPy's ``K0``, ``K1`` change formula and are up to 24 ulps
off themselves).  Outside the table's range (and at NaN) the value is SciPy's.
"""

from __future__ import annotations

import functools

import numpy as np
from scipy.special import i0e, i1e, k0e, k1e

__all__ = ["DEGREE", "PANELS", "RANGE", "GeometricTable", "displacement_table",
           "gradient_tables", "slope_table", "temperature_table"]

#: Panels per octave.
PANELS = 64
#: Degree of each panel's polynomial.
DEGREE = 6
#: The tables' range ``[2^-10, 2^22)``, as exponents of two.
RANGE = (-10, 22)
#: A double's mantissa bits below the top ``log2(PANELS)``: the position in a panel.
_FRACTION_BITS = 52 - int(np.log2(PANELS))
_FRACTION_MASK = (1 << _FRACTION_BITS) - 1


class GeometricTable:
    """A function of ``x > 0`` by piecewise polynomials on geometric panels.

    Parameters
    ----------
    f : callable
        Vectorised; sampled once, at the panels' Chebyshev points, and evaluating the
        points outside the panels (and NaN).
    analytic : bool, optional
        ``f`` is analytic at ``x = 0``: one more panel, ``[0, 2^-10)``, covers the
        points below the octaves (the graded quadratures' nodes next to a source).
    """

    def __init__(self, f, analytic=False):
        low, high = RANGE
        self.f = f
        self.low, self.high = 2.0**low, 2.0**high
        panel = np.arange((high - low) * PANELS)
        self.panels = panel.size
        # Panel p of the octave [2^E, 2^(E + 1)): x's bits shifted (__call__), less the
        # lowest octave's.
        self.offset = (1023 + low) * PANELS
        octave, j = np.divmod(panel, PANELS)
        scale = 2.0 ** (octave + low)
        half = scale / (2 * PANELS)
        centre = (1.0 + j / PANELS) * scale + half
        #: The panel [0, 2^low) where f is analytic at 0 (None otherwise).
        self.bottom = None
        if analytic:
            self.bottom = panel.size
            centre = np.append(centre, 0.5 * self.low)
            half = np.append(half, 0.5 * self.low)
        k = np.arange(DEGREE + 1)
        t = np.cos(np.pi * (k + 0.5) / (DEGREE + 1))
        samples = f(centre[:, None] + half[:, None] * t[None, :])
        # The monomial coefficients in t, highest power first, one row per power, fitted
        # to the samples' differences from one of them (a few percent of the value on a
        # panel): the inverse Vandermonde matrix's entries, up to about 10, then round
        # that small part only, and the constant term is the sample plus it.
        base = samples[:, :1]
        c = ((samples - base) @ np.linalg.inv(np.vander(t, DEGREE + 1)).T).T
        c[-1] += base[:, 0]
        self.coefficients = np.ascontiguousarray(c)

    def __call__(self, x):
        """The function at ``x`` (an array of any shape)."""
        x = np.asarray(x, dtype=float)
        shape = x.shape
        x = np.ascontiguousarray(x).reshape(-1)
        # The bits of a double x = 2^E (1 + f): above the mantissa's top 46 bits, the
        # biased exponent and f's top 6 bits, that is 64 E + floor(64 f) plus a
        # constant: the panel; the 46 bits below, 64 f less its floor, in [0, 1): t.
        # (A negative x, NaN or an infinity lands outside the panels.)
        bits = x.view(np.int64)
        j = bits >> _FRACTION_BITS
        j -= self.offset
        t = (bits & _FRACTION_MASK).astype(float)
        t *= 2.0 ** (1 - _FRACTION_BITS)
        t -= 1.0
        outside = j.view(np.uint64) >= self.panels
        rest = None
        if outside.any():
            j[outside] = 0
            if self.bottom is not None:
                below = outside & (x >= 0.0) & (x < self.low)
                j[below] = self.bottom
                t[below] = x[below] * (2.0 / self.low) - 1.0
                outside &= ~below
            if outside.any():
                rest = outside
        c = self.coefficients
        y = np.take(c[0], j)
        for k in range(1, DEGREE + 1):
            y *= t
            y += np.take(c[k], j)
        if rest is not None:
            y[rest] = self.f(x[rest])
        return y.reshape(shape)


@functools.cache
def displacement_table() -> GeometricTable:
    """``E(x) = exp(-x) I0(x) = i0e(x)`` (derivation eq. D5)."""
    return GeometricTable(i0e, analytic=True)


def _slope(x):
    return i0e(x) - i1e(x)


@functools.cache
def slope_table() -> GeometricTable:
    """``N(x) = exp(-x) [I0(x) - I1(x)]`` (derivation eq. D7)."""
    return GeometricTable(_slope, analytic=True)


def _upstream(a):
    return k0e(a) + k1e(a)


def _wake(a):
    return k0e(a) - k1e(a)


@functools.cache
def gradient_tables() -> tuple[GeometricTable, GeometricTable]:
    """``k0e(a) + k1e(a)`` and ``k0e(a) - k1e(a)``: ``exp(2a) M(a)`` upstream and
    ``M(-a)`` in the wake (derivation eqs. D9, D10)."""
    return GeometricTable(_upstream), GeometricTable(_wake)


#: ``ln 2 - gamma``, of the ascending series of ``K0``.
_LN2_MINUS_EULER = float(np.log(2.0) - np.euler_gamma)


def _k0e(a):
    """``k0e(a)``: SciPy's, but for ``0 < a < 2^-10`` (below the table's panels, where
    the graded quadratures' nodes next to a source put some two in five of the
    temperature kernel's values) by the ascending series
    ``K0(a) = (ln 2 - gamma - ln a) I0(a) + sum_k H_k q^k/(k!)^2``, ``q = a^2/4``,
    ``H_k`` the harmonic numbers, to ``k = 2`` (the next term is ``1e-21`` of the
    value there), times ``exp(a)``."""
    a = np.asarray(a, dtype=float)
    small = (a > 0.0) & (a < 2.0**RANGE[0])
    if not small.any():
        return k0e(a)
    out = np.empty_like(a)
    x = a[small]
    q = 0.25 * x * x
    i0 = 1.0 + q * (1.0 + 0.25 * q)
    out[small] = np.exp(x) * ((_LN2_MINUS_EULER - np.log(x)) * i0 + q * (1.0 + 0.375 * q))
    other = ~small
    if other.any():
        out[other] = k0e(a[other])
    return out


@functools.cache
def temperature_table() -> GeometricTable:
    """``k0e(a) = exp(a) K0(a)``: the temperature kernel ``exp(-u) K0(|u|)`` is
    ``k0e(|u|) exp(-u - |u|)`` (derivation eq. D8).  Below the panels, ``K0``'s
    ascending series (:func:`_k0e`); at 0, beyond them and at NaN, SciPy's value."""
    return GeometricTable(_k0e)
