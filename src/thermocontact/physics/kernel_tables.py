"""The moving body's Bessel products by table: piecewise polynomials on geometric panels.

The kernels of :mod:`~thermocontact.physics.green_functions` are products of the
exponentially scaled Bessel functions,

    E(x) = i0e(x),   N(x) = i0e(x) - i1e(x),   G+-(a) = k0e(a) +- k1e(a),

evaluated at every node of every moment of a grid line's assemblies and validity
checks (some 400 000 values a line of the benchmark map).  SciPy evaluates each
Bessel function by its own Chebyshev series, 40 to 60 ns a value here, and a kernel
needs two of them; a table evaluates the product at once in about 25 ns.

Each table covers ``2^-10 <= x < 2^22`` in octaves ``[2^(e-1), 2^e)``, each cut into
:data:`PANELS` panels of equal length (ratio of their ends at most ``1 + 2/PANELS``),
and holds on each panel the polynomial of degree :data:`DEGREE` through the function's
SciPy values at the panel's Chebyshev points, in the panel's variable
``t in [-1, 1]``.  The functions are analytic on ``x > 0`` with at most a pole or a
logarithm at ``x = 0``, so on a panel whose ends have ratio ``1 + 1/32`` the
interpolant's truncation error falls like ``rho^-(DEGREE + 1)`` with ``rho`` about
``4 * 65``: below ``1e-16`` of the value at degree 5.  What remains is the samples'
own rounding (SciPy's, a few ulps; for ``N`` and ``G-`` at large ``x`` the
cancellation of the difference, about ``eps x``) times the interpolant's Lebesgue
constant (about 2.1 for 6 Chebyshev points), and the evaluation's rounding.
Measured against mpmath (``tests/test_kernel_tables.py``): relative errors of at most
a few 1e-15 for ``x <= 16``, growing like ``eps x`` beyond for ``N`` and ``G-`` (as
SciPy's own differences do).  Outside the table's range (and at NaN) the value is
SciPy's.
"""

from __future__ import annotations

import functools

import numpy as np
from scipy.special import i0e, i1e, k0e, k1e

__all__ = ["DEGREE", "PANELS", "RANGE", "GeometricTable", "displacement_table",
           "gradient_tables", "slope_table"]

#: Panels per octave.
PANELS = 64
#: Degree of each panel's polynomial.
DEGREE = 6
#: The tables' range ``[2^-10, 2^22)``, as exponents of two.
RANGE = (-10, 22)


class GeometricTable:
    """A function of ``x > 0`` by piecewise polynomials on geometric panels.

    Parameters
    ----------
    f : callable
        Vectorised; sampled once, at the panels' Chebyshev points.
    fallback : callable, optional
        Evaluates the points outside :data:`RANGE` (default ``f``).
    """

    def __init__(self, f, fallback=None):
        low, high = RANGE
        self.f, self.fallback = f, f if fallback is None else fallback
        self.low, self.high = 2.0**low, 2.0**high
        # frexp's exponent e of x in [2^(e-1), 2^e): the lowest octave has e = low + 1.
        self.first = low + 1
        panel = np.arange((high - low) * PANELS)
        octave, j = np.divmod(panel, PANELS)
        scale = 2.0 ** (octave + self.first)
        left = (0.5 + j / (2 * PANELS)) * scale
        half = scale / (4 * PANELS)
        k = np.arange(DEGREE + 1)
        t = np.cos(np.pi * (k + 0.5) / (DEGREE + 1))
        samples = f((left + half)[:, None] + half[:, None] * t[None, :])
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
        m, e = np.frexp(x)
        # x = m 2^e, m in [1/2, 1): panel j of the octave, and t in [-1, 1] on it.
        u = (m - 0.5) * (2 * PANELS)
        with np.errstate(invalid="ignore"):  # (NaN and infinities: outside, below)
            j = u.astype(np.int64)
        t = u - j
        t *= 2.0
        t -= 1.0
        e -= self.first
        e *= PANELS
        j += e
        outside = ~((x >= self.low) & (x < self.high))
        any_outside = outside.any()
        if any_outside:
            j[outside] = 0
        c = self.coefficients
        y = np.take(c[0], j)
        for k in range(1, DEGREE + 1):
            y *= t
            y += np.take(c[k], j)
        if any_outside:
            y[outside] = self.fallback(x[outside])
        return y


@functools.cache
def displacement_table() -> GeometricTable:
    """``E(x) = exp(-x) I0(x) = i0e(x)`` (derivation eq. D5)."""
    return GeometricTable(i0e)


def _slope(x):
    return i0e(x) - i1e(x)


@functools.cache
def slope_table() -> GeometricTable:
    """``N(x) = exp(-x) [I0(x) - I1(x)]`` (derivation eq. D7)."""
    return GeometricTable(_slope)


def _upstream(a):
    return k0e(a) + k1e(a)


def _wake(a):
    return k0e(a) - k1e(a)


@functools.cache
def gradient_tables() -> tuple[GeometricTable, GeometricTable]:
    """``k0e(a) + k1e(a)`` and ``k0e(a) - k1e(a)``: ``exp(2a) M(a)`` upstream and
    ``M(-a)`` in the wake (derivation eqs. D9, D10)."""
    return GeometricTable(_upstream), GeometricTable(_wake)
