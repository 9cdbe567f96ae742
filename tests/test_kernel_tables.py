"""The tabulated Bessel products against mpmath, and against SciPy's own evaluation."""

import mpmath
import numpy as np
import pytest
from scipy.special import i0e, i1e, k0e, k1e

from thermocontact.physics.kernel_tables import (RANGE, displacement_table, gradient_tables,
                                                 slope_table, temperature_table)

EPS = np.finfo(float).eps


def _exact(name, x):
    x = mpmath.mpf(float(x))
    if name == "E":
        return mpmath.exp(-x) * mpmath.besseli(0, x)
    if name == "N":
        return mpmath.exp(-x) * (mpmath.besseli(0, x) - mpmath.besseli(1, x))
    if name == "T":
        return mpmath.exp(x) * mpmath.besselk(0, x)
    sign = 1 if name == "G+" else -1
    return mpmath.exp(x) * (mpmath.besselk(0, x) + sign * mpmath.besselk(1, x))


TABLES = {"E": (displacement_table, lambda x: i0e(x)),
          "N": (slope_table, lambda x: i0e(x) - i1e(x)),
          "G+": (lambda: gradient_tables()[0], lambda x: k0e(x) + k1e(x)),
          "G-": (lambda: gradient_tables()[1], lambda x: k0e(x) - k1e(x)),
          "T": (temperature_table, k0e)}
#: Relative error allowed, in units of eps: a constant and a growth in x.  N and G-
#: are differences of two functions of nearly equal size for large x (as SciPy's
#: are: each sample from which the tables are fitted carries that cancellation, and
#: SciPy's own G- is up to 24 eps off next to x = 2, where its K0, K1 change formula;
#: the same bounds hold for SciPy's values, measured on 600 points of [0.3, 4]).
BOUNDS = {"E": (8, 0.0), "N": (8, 8.0), "G+": (8, 0.0), "G-": (16, 16.0), "T": (8, 0.0)}


@pytest.mark.parametrize("name", sorted(TABLES))
def test_table_against_mpmath(name):
    mpmath.mp.dps = 30
    table, _ = TABLES[name]
    rng = np.random.default_rng(7)
    low, high = RANGE
    x = np.exp(rng.uniform(low * np.log(2.0), high * np.log(2.0), 120))
    exact = np.array([float(_exact(name, v)) for v in x])
    err = np.abs(table()(x) - exact) / np.abs(exact)
    flat, growth = BOUNDS[name]
    allowed = EPS * (flat + growth * x)
    assert np.all(err <= allowed), (x[err > allowed], err[err > allowed])


def test_temperature_table_below_the_panels_against_mpmath():
    """Below 2^-10, k0e by K0's ascending series, within 8 ulps of mpmath down to
    1e-300 (measured 1.3 on 400 points; SciPy's own 3.3)."""
    mpmath.mp.dps = 30
    x = np.geomspace(1e-300, 2.0**RANGE[0], 40, endpoint=False)
    exact = np.array([float(_exact("T", v)) for v in x])
    err = np.abs(temperature_table()(x) - exact) / exact
    assert np.all(err <= 8 * EPS), (x[err > 8 * EPS], err[err > 8 * EPS])


@pytest.mark.parametrize("name", sorted(TABLES))
def test_table_agrees_with_scipy_and_falls_back_outside(name):
    table, scipy_form = TABLES[name]
    rng = np.random.default_rng(8)
    x = np.exp(rng.uniform(np.log(1e-3), np.log(1e4), 20000))
    if name in ("E", "N", "T"):  # the panel below the octaves (T: K0's series) too
        x = np.concatenate([x, [0.0] if name != "T" else [],
                            np.geomspace(1e-300, 2.0**RANGE[0], 2000)])
    ref = scipy_form(x)
    flat, growth = BOUNDS[name]
    # Both within their bounds of the exact value: at most their sum apart.
    assert np.all(np.abs(table()(x) - ref) <= 2 * EPS * (flat + growth * x)
                  * np.abs(ref))
    # Outside the range, and NaN: SciPy's value itself.
    low, high = RANGE
    out = np.array([2.0**high, 1e300, np.nan, np.inf]
                   + ([] if name in ("E", "N") else [0.0] if name == "T"
                      else [0.0, 2.0**low / 3]))
    with np.errstate(invalid="ignore"):
        np.testing.assert_array_equal(table()(out), scipy_form(out))
    # Any shape.
    grid = x[:12].reshape(3, 4)
    np.testing.assert_array_equal(table()(grid), table()(grid.ravel()).reshape(3, 4))
