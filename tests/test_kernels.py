"""Internal consistency of the kernels: antiderivatives, limits, continuations.

The physical derivations are checked against the PDEs in test_green_functions.py.
"""

import numpy as np
import pytest
from scipy.integrate import quad
from scipy.special import k0, k1

from thermocontact.physics.green_functions import (
    cylinder_displacement,
    cylinder_slope,
    cylinder_temperature,
    cylinder_temperature_gradient,
    cylinder_temperature_gradient_regular,
    half_plane_slope,
)


@pytest.mark.parametrize("u", [1e-6, 0.3, 2.0, 40.0, 900.0])
def test_slope_is_minus_derivative_of_displacement(u):
    """int_0^u N H = E(0) - E(u) by quadrature (rel. 1e-10)."""
    val, _ = quad(lambda x: float(cylinder_slope(x)), 0, u, limit=200)
    assert abs(val - (1.0 - cylinder_displacement(u))) < 1e-10 * max(1.0, val)


def test_displacement_continuous_and_constant_downstream():
    """E = 1 for u <= 0 and E(0+) = 1: the moving body's distortion has no jump."""
    assert cylinder_displacement(-5.0) == 1.0
    assert abs(cylinder_displacement(1e-12) - 1.0) < 1e-11
    assert cylinder_slope(-1.0) == 0.0 and abs(cylinder_slope(1e-12) - 1.0) < 1e-11


@pytest.mark.parametrize("u", [-30.0, -2.0, -1e-3, 1e-3, 0.7, 25.0])
def test_gradient_is_minus_derivative_of_temperature(u):
    """d/du [exp(-u) K0(|u|)] = -M(u), by a 4th-order central difference (rel. 1e-7)."""
    h = 1e-4 * max(abs(u), 1e-2)
    f = cylinder_temperature
    d = (f(u - 2 * h) - 8 * f(u - h) + 8 * f(u + h) - f(u + 2 * h)) / (12 * h)
    assert abs(-d - cylinder_temperature_gradient(u)) < 1e-7 * abs(cylinder_temperature_gradient(u))


@pytest.mark.parametrize("u", [-3.0, -0.2, 0.2, 3.0])
def test_gradient_matches_unscaled_bessel(u):
    """M(u) = exp(-u)(K0(|u|) + sgn(u) K1(|u|)) with unscaled Bessel functions (rel. 1e-13)."""
    ref = np.exp(-u) * (k0(abs(u)) + np.sign(u) * k1(abs(u)))
    assert abs(cylinder_temperature_gradient(u) / ref - 1) < 1e-13


def test_gradient_small_argument_form():
    """M(u) - 1/u + ln|u| tends to a constant as u -> 0 from either side.

    The constant is ln 2 - gamma - 1 (expansion of exp(-u)/u and K0); checked to 1e-6 at
    |u| = 1e-8, where the next term, about 1.5 |u ln u|, is 3e-7.
    """
    const = np.log(2) - np.euler_gamma - 1.0
    for u in (1e-8, -1e-8):
        val = cylinder_temperature_gradient_regular(np.array([u]), 1.0)[0] + np.log(abs(u))
        assert abs(val - const) < 1e-6


def test_gradient_no_overflow_far_upstream_and_downstream():
    """Finite for |u| up to 1e6: the scaled Bessel functions avoid exp overflow."""
    u = np.array([-1e6, -700.0, 700.0, 1e6])
    assert np.all(np.isfinite(cylinder_temperature_gradient(u)))
    assert np.all(np.isfinite(cylinder_displacement(u)))


def test_regular_part_scales_on_series_branch():
    """c M(c u) - 1/u for c = 50 at points where |c u| < 1e-3 (the ascending-series
    branch) against 40-digit mpmath, rel. 1e-13."""
    import mpmath as mp

    with mp.workdps(40):
        c = 50.0
        for u in (-1.9e-5, -3e-9, 4e-12, 1.5e-5):
            z = mp.mpf(c) * mp.mpf(u)
            ref = mp.mpf(c) * mp.e**(-z) * (mp.besselk(0, abs(z)) + mp.sign(z) * mp.besselk(1, abs(z))) - 1 / mp.mpf(u)
            val = cylinder_temperature_gradient_regular(np.array([u]), c)[0]
            assert abs(val / float(ref) - 1) < 1e-13


def test_half_plane_slope_odd():
    """sgn/2 kernel is odd and of unit jump."""
    assert half_plane_slope(2.0) == 0.5 and half_plane_slope(-1e-9) == -0.5
