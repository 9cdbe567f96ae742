"""Kernel moments against the Chebyshev bases: adaptive quadrature, closed forms,
and refinement of the rules."""

import numpy as np
import pytest
from scipy.integrate import quad

import thermocontact.numerics.moments as mm
from thermocontact.physics.green_functions import cylinder_slope, cylinder_temperature_gradient_regular
from thermocontact.numerics.moments import kernel_moments, sgn_moments

S = np.array([-0.999, -0.3, 0.0, 0.5, 0.99999, 1.0, 1.001, -1.2])


def quad_moment(kernel, s, j, bounded):
    """Adaptive quadrature in t = arccos r, split at t_s (u = 0 only where s - cos t
    rounds to zero next to t_s; there a tiny u stands in for it)."""
    k0 = kernel
    kernel = lambda u: k0(np.where(u == 0.0, 1e-300, u))
    if bounded:
        f = lambda t: kernel(np.array([[s - np.cos(t)]]))[0, 0] * np.sin(t) * np.sin((j + 1) * t)
    else:
        f = lambda t: kernel(np.array([[s - np.cos(t)]]))[0, 0] * np.cos(j * t)
    ts = np.arccos(np.clip(s, -1, 1))
    opts = dict(limit=400, epsabs=1e-15, epsrel=1e-13)
    return sum(quad(f, a, b, **opts)[0] for a, b in ((0, ts), (ts, np.pi)) if b > a)


@pytest.mark.parametrize("c", [5.0, 1000.0])
def test_slope_kernel_moments_match_quadrature(c):
    """N(c u) H(u) moments equal adaptive quadrature to 5e-15 (abs; values <= 1)."""
    kern = lambda u: cylinder_slope(c * u)
    B, T = kernel_moments(kern, S, 64, scale=c)
    for k in (0, 1, 3, 4, 6):
        for j in (0, 5, 63):
            assert abs(B[k, j] - quad_moment(kern, S[k], j, True)) < 5e-15
            assert abs(T[k, j] - quad_moment(kern, S[k], j, False)) < 5e-15


def test_log_kernel_moments_match_quadrature():
    """c M(c u) - 1/u moments (c = 5, logarithmic at u = 0) equal adaptive quadrature
    to 1e-13 (abs; values up to 8)."""
    kern = lambda u: cylinder_temperature_gradient_regular(u, 5.0)
    B, T = kernel_moments(kern, S, 64)
    for k in (0, 1, 3, 4, 7):
        for j in (0, 5, 63):
            assert abs(B[k, j] - quad_moment(kern, S[k], j, True)) < 1e-13
            assert abs(T[k, j] - quad_moment(kern, S[k], j, False)) < 1e-13


@pytest.mark.parametrize("c", [1e3, 1e5, 1e6])
def test_moments_stable_under_refinement(c):
    """Moments of both kernels change by less than 1e-13 relative to their largest
    value when every Gauss-Legendre rule goes from 16 to 24 points (c up to 1e6:
    kernels of width 1e-6 and the near-pole -1/u beyond it)."""
    kernels = [lambda u: cylinder_temperature_gradient_regular(u, c),
               lambda u: cylinder_slope(c * u)]
    try:
        first = [kernel_moments(k, S, 64) for k in kernels]
        mm._GL = 24
        for f in (mm._gauss_legendre, mm._graded_reference, mm._inner_reference, mm._common):
            f.cache_clear()
        second = [kernel_moments(k, S, 64) for k in kernels]
    finally:
        mm._GL = 16
        for f in (mm._gauss_legendre, mm._graded_reference, mm._inner_reference, mm._common):
            f.cache_clear()
    for (b1, t1), (b2, t2) in zip(first, second):
        scale = max(np.abs(t1).max(), np.abs(b1).max())
        assert np.abs(b1 - b2).max() < 1e-13 * scale
        assert np.abs(t1 - t2).max() < 1e-13 * scale


def test_sgn_closed_form_matches_graded_rule():
    """The closed-form sgn moments equal the graded rule applied to sgn (1e-14)."""
    s = S[:6]
    B, T = sgn_moments(s, 40)
    B2, T2 = kernel_moments(np.sign, s, 40)
    assert np.abs(B - B2).max() < 1e-14 and np.abs(T - T2).max() < 1e-14


def test_moments_of_constant_kernel():
    """K = 1: B = (pi/2)[j = 0] and T = pi [j = 0] exactly (1e-14)."""
    B, T = kernel_moments(lambda u: np.ones_like(u), S, 16)
    eb = np.zeros(16); eb[0] = np.pi / 2
    et = np.zeros(16); et[0] = np.pi
    assert np.abs(B - eb).max() < 1e-14 and np.abs(T - et).max() < 1e-14
