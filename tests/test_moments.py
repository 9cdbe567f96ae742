"""Kernel moments against the Chebyshev bases: adaptive quadrature, closed forms,
and refinement of the rules."""

import numpy as np
import pytest

import thermocontact.numerics.moments as mm
from conftest import references
from thermocontact.physics.green_functions import cylinder_slope, cylinder_temperature_gradient_regular
from thermocontact.numerics.moment_engine import chebyshev_moments as kernel_moments
from thermocontact.numerics.moments import sgn_moments

S = np.array([-0.999, -0.3, 0.0, 0.5, 0.99999, 1.0, 1.001, -1.2])


@pytest.mark.parametrize("key, tol", [("NH_5", 5e-15), ("NH_1000", 5e-15), ("mr_5", 1e-13)])
def test_kernel_moments_match_quadrature(key, tol):
    """Moments of N(c u) H(u) (c = 5, 1000; values <= 1) and of c M(c u) - 1/u (c = 5,
    logarithmic at u = 0; values up to 8) equal 25-digit mpmath quadrature in
    t = arccos r (tests/data/make_references.py) to 5e-15 and 1e-13 absolute."""
    ref = references()["chebyshev_moments"][key]
    c = ref["c"]
    assert ref["s"] == S.tolist()
    if key.startswith("NH"):
        B, T = kernel_moments(lambda u: cylinder_slope(c * u), S, 64, scale=c)
    else:
        B, T = kernel_moments(lambda u: cylinder_temperature_gradient_regular(u, c), S, 64)
    for k, j, weight, value in ref["values"]:
        got = (B if weight == "b" else T)[k, j]
        assert abs(got - value) < tol, (k, j, weight, got - value)


def _clear_rules():
    """Forget every cached rule and geometry, so that a changed GAUSS_POINTS takes effect."""
    from thermocontact.numerics import moment_engine as graded

    for f in (mm.gauss_legendre, mm._graded_reference, mm.inner_reference, mm.panel_rule,
              graded.weight_integrals):
        f.cache_clear()
    graded.BASES.clear()
    graded.clear_geometry()


@pytest.mark.parametrize("c", [1e3, 1e5, 1e6])
def test_moments_stable_under_refinement(c, monkeypatch):
    """Moments of both kernels, for both maps (Chebyshev and edge-graded), change by
    less than 1e-13 relative to their largest value when every Gauss-Legendre rule,
    the common panels' included, goes from 16 to 24 points (c up to 1e6: kernels of
    width 1e-6 and the near-pole -1/u beyond it)."""
    from thermocontact.numerics import moment_engine as graded

    kernels = [(lambda u: cylinder_temperature_gradient_regular(u, c), True),
               (lambda u: cylinder_slope(c * u), False)]

    def both(k, log):
        return (kernel_moments(k, S, 64, scale=c, logarithmic=log),
                graded.moments(k, S, 64, scale=c, logarithmic=log))

    _clear_rules()
    first = [both(*k) for k in kernels]
    assert mm.panel_rule(64)[2].size == mm.panel_rule(64)[0] * 16
    monkeypatch.setattr(mm, "GAUSS_POINTS", 24)
    _clear_rules()
    assert mm.panel_rule(64)[2].size == mm.panel_rule(64)[0] * 24  # refined for real
    second = [both(*k) for k in kernels]
    monkeypatch.undo()
    _clear_rules()
    for pair1, pair2 in zip(first, second):
        for (b1, t1), (b2, t2) in zip(pair1, pair2):
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
