"""Tests of the limiting-case solutions in :mod:`thermocontact.physics.reference_solutions`.

Barber's problem is checked against quantities computed without its Galerkin
machinery: the integral equation (B1) is evaluated by adaptive quadrature
(QUADPACK's Cauchy-weight rule for the principal value), and the first-order
load correction is derived by hand and by quadrature.
"""

from __future__ import annotations

import dataclasses
import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from scipy.integrate import quad

from thermocontact.physics.reference_solutions import BarberSolution, barber_insulated, hertz_pressure

# First-order load correction L = 1 + L1 F + O(F^2): with 2 C0 - 1 =
# (2/pi)(s sqrt(1 - s^2) + arcsin s) for the Hertz pressure, the normalisation
# condition integral s f(s) / sqrt(1 - s^2) ds = 0 of the O(F) problem gives
# L1 = -(2/pi) (2/3 + 2) = -16 / (3 pi).
L1_EXACT = -16.0 / (3.0 * math.pi)

QUAD = {"epsabs": 1e-13, "epsrel": 1e-13, "limit": 200}


def _scalar(func):
    return lambda x: float(func(x))


def _hilbert(p, s):
    """``(1/pi) PV integral_{-1}^{1} p(r) / (s - r) dr`` by quadrature.

    QUADPACK's Cauchy rule handles a window around ``s``; the rest is
    integrated in ``t = arccos r``, which removes the square-root edge
    behaviour that otherwise limits QUADPACK to about 1e-11.
    """
    d = 0.5 * min(1.0 - abs(s), 0.2)
    a, b = s - d, s + d
    # weight='cauchy' computes PV integral p(r) / (r - s) dr.
    window = -quad(p, a, b, weight="cauchy", wvar=s, **QUAD)[0]

    def outer(t):
        return p(math.cos(t)) * math.sin(t) / (s - math.cos(t))

    left = quad(outer, math.acos(a), math.pi, **QUAD)[0]
    right = quad(outer, 0.0, math.acos(b), **QUAD)[0]
    return (window + left + right) / math.pi


def _sgn_integral(p, s):
    """``integral_{-1}^{1} p(r) sgn(s - r) dr`` by quadrature (in ``t``)."""
    ts = math.acos(s)

    def load(t):
        return p(math.cos(t)) * math.sin(t)

    return quad(load, ts, math.pi, **QUAD)[0] - quad(load, 0.0, ts, **QUAD)[0]


def _residual(sol, s):
    """Left minus right side of (B1) at ``s``, all integrals by quadrature."""
    p = _scalar(sol.pressure)
    lhs = _hilbert(p, s) - sol.fhpe * _sgn_integral(p, s)
    rhs = (2.0 / math.pi) * sol.load_ratio * (sol.sigma_over_delta + s)
    return lhs - rhs


# --------------------------------------------------------------------------
# Hertz pressure
# --------------------------------------------------------------------------


def test_hertz_pressure_integrates_to_one():
    """integral_{-1}^{1} phat ds = 1 to 1e-13.

    QUADPACK resolves the square-root edges of this closed form to a few ulp,
    so the tolerance only allows for its requested accuracy.
    """
    total = quad(_scalar(hertz_pressure), -1.0, 1.0, **QUAD)[0]
    assert total == pytest.approx(1.0, abs=1e-13)


def test_hertz_pressure_vanishes_outside_contact():
    """Exactly zero for |s| >= 1 and positive inside: no tolerance needed."""
    s = np.array([-3.0, -1.0, 1.0, 1.5])
    assert np.all(hertz_pressure(s) == 0.0)
    assert np.all(hertz_pressure(np.linspace(-0.999, 0.999, 11)) > 0.0)


@pytest.mark.parametrize("s", [-0.93, -0.41, 0.0, 0.27, 0.66, 0.995])
def test_hertz_pressure_solves_unheated_equation(s):
    """(1/pi) PV integral phat/(s-r) dr = (2/pi) s, i.e. (B1) with F=0, L=1, sigma=0.

    Tolerance 1e-12: the principal value is by quadrature, requested to 1e-13.
    """
    assert _hilbert(_scalar(hertz_pressure), s) == pytest.approx(
        2.0 * s / math.pi, abs=1e-12
    )


# --------------------------------------------------------------------------
# Barber's insulated cylinder
# --------------------------------------------------------------------------


def test_barber_without_heating_is_hertz():
    """At F = 0 the solution is Hertz: L = 1, sigma = 0, phat = (2/pi) sqrt(1-s^2).

    Tolerance 1e-14: the system is then diagonal, so only round-off remains.
    """
    sol = barber_insulated(0.0)
    assert sol.load_ratio == pytest.approx(1.0, abs=1e-14)
    assert abs(sol.sigma_over_delta) <= 1e-14
    s = np.linspace(-1.0, 1.0, 401)
    np.testing.assert_allclose(sol.pressure(s), hertz_pressure(s), rtol=0, atol=1e-14)


@pytest.mark.parametrize("fhpe", [0.1, 0.5, 1.0])
def test_barber_satisfies_integral_equation(fhpe):
    """(B1) holds at random interior points to 5e-12.

    Every integral is by adaptive quadrature (requested to 1e-13), independent
    of the Galerkin projection.  The series' own pointwise residual is below
    1e-12 here: with b_j ~ j^-4 the truncated tail falls like n^-4 away from
    the edges.  Measured residuals are about 1e-12.
    """
    sol = barber_insulated(fhpe)
    rng = np.random.default_rng(20240611)
    for s in rng.uniform(-0.95, 0.95, size=6):
        assert abs(_residual(sol, s)) < 5e-12, s


@pytest.mark.parametrize("s", [-0.99999, -0.999, 0.9999])
def test_barber_satisfies_integral_equation_near_edges(s):
    """(B1) holds next to the contact edges to 5e-10.

    The looser tolerance is the truncation of the series, not quadrature: near
    s = +-1 the tail sum_{j>=n} b_j cos((j+1) theta) adds up coherently, giving
    a residual ~ n^-3 (about 1e-10 at the default n; 7e-11 measured).
    """
    assert abs(_residual(barber_insulated(0.5), s)) < 5e-10


def test_barber_pressure_is_normalised_and_vanishes_at_edges():
    """integral phat = 1 to 1e-12, and phat = 0 at and beyond s = +-1 exactly.

    The integral is by quadrature in t = arccos s (requested to 1e-13); the
    series has b_0 = 2/pi, so the exact value is 1.
    """
    sol = barber_insulated(0.5)
    total = quad(lambda t: float(sol.pressure(math.cos(t))) * math.sin(t),
                 0.0, math.pi, **QUAD)[0]
    assert total == pytest.approx(1.0, abs=1e-12)
    assert np.all(sol.pressure([-2.0, -1.0, 1.0, 1.0 + 1e-12]) == 0.0)


def test_barber_convergence_order():
    """L converges like n^-6 (observed order 6.0 +- 0.3).

    The edge terms (1 -+ s)^{3/2} log(1 -+ s) make b_j ~ j^-4; the Galerkin
    error in L is then O(n^-6).  Measured orders at F = 0.5 for n = 16..128
    are 5.94, 5.98, 6.00; beyond n ~ 256 the error is at round-off, so the
    reference n = 2048 is exact for this purpose.
    """
    fhpe = 0.5
    ref = barber_insulated(fhpe, 2048).load_ratio
    ns = np.array([16, 32, 64, 128])
    err = np.array([abs(barber_insulated(fhpe, n).load_ratio - ref) for n in ns])
    orders = np.log2(err[:-1] / err[1:])
    assert np.all((orders > 5.7) & (orders < 6.3)), orders


@pytest.mark.parametrize("fhpe", [0.1, 0.2, 0.5, 1.0, 2.0])
def test_barber_default_accuracy(fhpe):
    """The default n gives L to 1e-13, confirmed by Richardson extrapolation.

    With error ~ C n^-6, L(256) + (L(256) - L(128)) / 63 removes the leading
    term; it agrees with the default-n value (and with n = 2048) to 1e-13,
    which bounds the default's error at that level (measured <= 1e-14; the
    pair 64/128 is still pre-asymptotic at F = 2, off by 1.5e-12).
    """
    default = barber_insulated(fhpe).load_ratio
    l128 = barber_insulated(fhpe, 128).load_ratio
    l256 = barber_insulated(fhpe, 256).load_ratio
    extrapolated = l256 + (l256 - l128) / 63.0
    assert default == pytest.approx(extrapolated, abs=1e-13)
    assert default == pytest.approx(barber_insulated(fhpe, 2048).load_ratio, abs=1e-13)


def test_first_order_load_correction_by_quadrature():
    """L1 = -integral s (2 C0(s) - 1) / sqrt(1-s^2) ds equals -16/(3 pi) to 1e-11.

    C0 is the Hertz cumulative load, here by nested quadrature; the outer
    integral uses QUADPACK's algebraic weight for 1/sqrt(1-s^2).  Tolerance
    covers the nested quadrature's ~1e-13 error.
    """

    def cumulative(s):
        return quad(_scalar(hertz_pressure), -1.0, s, epsabs=1e-13, epsrel=1e-13)[0]

    l1 = -quad(lambda s: s * (2.0 * cumulative(s) - 1.0), -1.0, 1.0,
               weight="alg", wvar=(-0.5, -0.5), epsabs=1e-12, epsrel=1e-12)[0]
    assert l1 == pytest.approx(L1_EXACT, abs=1e-11)


def test_first_order_perturbation_in_heating():
    """Small F: sigma has no O(F) term and L = 1 + L1 F + O(F^2).

    By symmetry phat is even and the sgn and Hilbert terms odd, so the
    consistency condition forces sigma = 0 (at every order, in fact); checked
    to 1e-14.  The slope is estimated by the Richardson difference
    2 D(h) - D(2h), D(h) = (L(h) - 1)/h, whose O(h^2) error at h = 1e-4 is
    ~3e-10 (measured) plus round-off 1e-16/h; tolerance 1e-8.
    """
    h = 1e-4
    small = [barber_insulated(f) for f in (h, 2 * h)]
    for sol in small:
        assert abs(sol.sigma_over_delta) <= 1e-14
    d1, d2 = ((sol.load_ratio - 1.0) / sol.fhpe for sol in small)
    assert 2.0 * d1 - d2 == pytest.approx(L1_EXACT, abs=1e-8)


def test_load_ratio_decreases_with_heating():
    """L falls monotonically from 1 for small F, and crosses zero near F = 0.579.

    Heat flowing into the half-plane makes it bulge into the contact, so the
    same width needs more load, i.e. a smaller L = P_H / P.  Strict inequality
    needs no tolerance (steps in L are ~0.017 here).  The zero crossing is
    bracketed coarsely as a regression check.
    """
    fs = np.linspace(0.0, 0.5, 31)
    loads = np.array([barber_insulated(f, 256).load_ratio for f in fs])
    assert np.all(np.diff(loads) < 0.0)
    assert barber_insulated(0.57, 256).load_ratio > 0.0
    assert barber_insulated(0.59, 256).load_ratio < 0.0


@settings(max_examples=20, deadline=None)
@given(
    fhpe=st.floats(min_value=0.0, max_value=1.3),
    s=st.floats(min_value=0.0, max_value=1.0),
)
def test_barber_pressure_even_and_nonnegative(fhpe, s):
    """phat(s) = phat(-s) to 1e-15, phat >= 0 below F ~ 1.377, sigma = 0 to 1e-14.

    Evenness follows from the symmetry of (B1); the sin((j+1) t) sums for
    s and -s differ only by round-off.  Nonnegativity holds until the edge
    coefficient changes sign at F ~ 1.377 (beyond the zero-load F anyway).
    """
    sol = barber_insulated(fhpe, 256)
    p_plus, p_minus = sol.pressure([s, -s])
    assert p_plus == pytest.approx(p_minus, abs=1e-15)
    assert p_plus >= 0.0
    assert abs(sol.sigma_over_delta) <= 1e-14


def test_pressure_preserves_shape():
    """Output shape follows input shape; values match scalar calls to 1e-15.

    Batched and scalar evaluation sum the series in different BLAS orders, so
    they may differ by a few ulp.
    """
    sol = barber_insulated(0.3, 64)
    s = np.array([[-0.5, 0.1], [0.7, 1.2]])
    out = sol.pressure(s)
    assert out.shape == s.shape
    assert np.ndim(sol.pressure(0.2)) == 0
    for value, point in zip(out.ravel(), s.ravel()):
        assert value == pytest.approx(float(sol.pressure(point)), abs=1e-15)


def test_solution_is_immutable():
    """Frozen dataclass with read-only coefficients; nothing numerical to tolerate."""
    sol = barber_insulated(0.2, 32)
    assert isinstance(sol, BarberSolution)
    assert sol.n == 32 and sol.coefficients.shape == (32,)
    with pytest.raises(dataclasses.FrozenInstanceError):
        sol.load_ratio = 1.0
    with pytest.raises(ValueError):
        sol.coefficients[0] = 0.0


@pytest.mark.parametrize("bad", [-1e-3, -1.0, math.nan, math.inf, -math.inf, "x", None])
def test_rejects_invalid_fhpe(bad):
    """fhpe must be finite and >= 0; the message is one line naming fhpe."""
    with pytest.raises(ValueError, match="fhpe") as info:
        barber_insulated(bad)
    assert "\n" not in str(info.value) and ">= 0" in str(info.value)


@pytest.mark.parametrize("bad", [0, -4, 2.5, "10"])
def test_rejects_invalid_term_count(bad):
    """n must be an integer >= 1; the message names n."""
    with pytest.raises(ValueError, match="n must be"):
        barber_insulated(0.1, bad)
