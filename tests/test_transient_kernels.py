"""Checks of the transient kernels against independent routes (derivation, section
"Transient kernels: a perturbation e^{bt}", eqs. T1-T12).

* b -> 0: the steady kernels of :mod:`thermocontact.physics.green_functions`
  (Carslaw and Jaeger's and Barber's closed forms, Dundurs' sgn/2 and the Cauchy
  kernel), and the stationary half-plane's divergent constants (eqs. T6, T11).
* The Laplace transform in time, by adaptive quadrature, of the instantaneous
  line source's surface temperature ``E/(2 pi K t) exp(-(x + v t)^2/(4 k t))`` and
  of its surface displacement (Maysel's formula applied to it: a Dawson function).
* For the stationary half-plane, the Fourier integrals of the temperature
  ``1/(K gamma)`` and of the displacement ``2 delta/(gamma (gamma + |k|))`` (D3),
  ``gamma = sqrt(k^2 + b)``, by QUADPACK's Fourier quadrature: also for imaginary
  ``b``, where the time integral does not converge absolutely.
* Symmetries, short-time (large |b|) limits, bad input, and the moments of the
  edge-graded representation.
"""

from __future__ import annotations

import mpmath
import numpy as np
import pytest
from scipy.integrate import quad
from scipy.special import dawsn, i0, k0, modstruve

from conftest import assert_ulps
from thermocontact.numerics import moment_engine
from thermocontact.physics import green_functions as steady
from thermocontact.physics import transient_green_functions as tk
from thermocontact.problem.validation import InputError

#: Points spanning small and large |u|, both sides of the source.
U = np.array([-40.0, -7.0, -1.3, -0.2, -1e-3, -1e-6, 1e-6, 1e-3, 0.2, 1.3, 7.0, 40.0])
#: Peclet numbers c = v Delta/(2k), signed for the displacement and slope.
PECLET = [0.05, 1.0, 30.0]
#: Rates tending to zero along several directions of the complex plane.
TINY = [1e-30, 1e-30 * np.exp(0.25j * np.pi), 1e-30 * np.exp(-0.9j * np.pi)]


def _close(actual, expected, rtol):
    """Relative agreement where ``expected`` is non-zero; where it is zero (a steady
    wake), ``actual`` below ``rtol`` times the largest ``|expected|``."""
    actual, expected = np.asarray(actual), np.asarray(expected)
    zero = expected == 0.0
    assert np.all(np.abs(actual[zero]) < rtol * np.max(np.abs(expected)))
    err = np.abs(actual[~zero] / expected[~zero] - 1.0)
    assert err.max() < rtol, err.max()


# --- b -> 0: the steady kernels --------------------------------------------------

@pytest.mark.parametrize("c", PECLET)
@pytest.mark.parametrize("b", [0.0] + TINY)
def test_moving_body_tends_to_steady_kernels(c, b):
    live = np.abs(c * U) < 300.0  # the steady exp(-u) K0(|u|) underflows beyond
    _close(tk.transient_temperature(U[live], c, b), steady.cylinder_temperature(c * U[live]),
           1e-12)
    _close(tk.transient_temperature_gradient(U[live], c, b),
           c * steady.cylinder_temperature_gradient(c * U[live]), 1e-12)
    _close(tk.transient_temperature_gradient_regular(U, c, b),
           steady.cylinder_temperature_gradient_regular(U, c), 1e-12)
    for sc in (c, -c):
        _close(tk.transient_slope(U, sc, b), steady.moving_slope(U, sc), 1e-12)
    _close(c * tk.transient_displacement(U, c, b), steady.cylinder_displacement(c * U), 1e-12)


@pytest.mark.parametrize("b", TINY)
def test_stationary_half_plane_tends_to_steady_kernels(b):
    # Gradient: the Cauchy kernel (D12); slope: Dundurs' sgn/2 (D4).
    _close(tk.transient_temperature_gradient(U, 0.0, b), 1.0 / U, 1e-12)
    assert np.max(np.abs(tk.transient_temperature_gradient_regular(U, 0.0, b))) < 1e-12
    _close(tk.transient_slope(U, 0.0, b), steady.half_plane_slope(U), 1e-12)
    # Temperature: K0(sqrt(b)|u|) = -ln|u| - ln(sqrt(b)/2) - gamma_E + O(b u^2 ln): the
    # constant diverges like ln sqrt(b), the u-dependence is the steady logarithm (T6).
    shifted = tk.transient_temperature(U, 0.0, b) + np.log(np.sqrt(b) / 2.0) + np.euler_gamma
    assert np.max(np.abs(shifted + np.log(np.abs(U)))) < 1e-12


def test_stationary_displacement_small_b_expansion():
    """``W = 2/(pi sqrt b) - |u|/2 + (2/(3 pi)) sqrt(b) u^2 + O(b |u|^3)`` (eq. T11)."""
    u = np.array([-3.0, -0.5, 0.25, 2.0])
    for b in (1e-8, 1e-8 * np.exp(0.5j * np.pi), 1e-8 * np.exp(-0.75j * np.pi)):
        rb = np.sqrt(b)
        rest = tk.transient_displacement(u, 0.0, b) - 2.0 / (np.pi * rb) + 0.5 * np.abs(u)
        coefficient = rest / (rb * u * u)
        assert np.max(np.abs(coefficient - 2.0 / (3.0 * np.pi))) < 1e-3


# --- Laplace transforms of the time-domain Green's functions ---------------------

def _cquad(f, a, b, **kw):
    opts = dict(epsabs=0.0, epsrel=1e-12, limit=400)
    return (quad(lambda t: f(t).real, a, b, **opts, **kw)[0]
            + 1j * quad(lambda t: f(t).imag, a, b, **opts, **kw)[0])


def _laplace(g, u, c, b):
    """``integral_0^inf exp(-b t) g(t) dt``, split at the arrival of the source's heat."""
    peak = abs(u) / (2.0 * abs(c)) if c else u * u / 4.0
    split = 4.0 * (peak + u * u + 1.0)
    f = lambda t: np.exp(-b * t) * g(t) if t > 0.0 else 0.0j  # noqa: E731
    return _cquad(f, 0.0, split, points=[peak]) + _cquad(f, split, np.inf)


def _dawson_bracket(z):
    """``1/z - F(z)(1 + 2 z^2)/z^2`` (``F`` Dawson's integral): ``z^2 d(F(z)/z)/dz``."""
    if abs(z) < 1e-2:
        return -4.0 * z / 3.0 + 16.0 * z**3 / 15.0 - 16.0 * z**5 / 35.0
    if abs(z) > 1e3:
        return -1.0 / z**3 - 1.0 / z**5 - 2.25 / z**7
    return 1.0 / z - dawsn(z) * (1.0 + 2.0 * z * z) / (z * z)


def _time_domain(u, c, b):
    """Temperature, displacement and slope kernels from the instantaneous source.

    Dimensionless time ``t = k t_phys/Delta^2``; the source has moved ``X = u + 2 c t``
    behind the point.  Temperature ``exp(-X^2/(4t))/(2t)`` (units ``Q/(pi K)``);
    displacement ``(4/pi^1.5) F(z)/X``, ``z = X/(2 sqrt t)`` (units ``delta Q Delta``);
    slope ``-d/dX`` of it.
    """
    def temperature(t):
        x = u + 2.0 * c * t
        return np.exp(-x * x / (4.0 * t)) / (2.0 * t)

    def displacement(t):
        z = (u + 2.0 * c * t) / (2.0 * np.sqrt(t))
        return 4.0 / np.pi**1.5 / (2.0 * np.sqrt(t)) * (dawsn(z) / z if abs(z) > 1e-8 else 1.0)

    def slope(t):
        z = (u + 2.0 * c * t) / (2.0 * np.sqrt(t))
        return -4.0 / np.pi**1.5 / (4.0 * t) * _dawson_bracket(z)

    return [_laplace(g, u, c, b) for g in (temperature, displacement, slope)]


POINTS = (-2.0, 0.05, 1.0)


# The last case: a small rate of a moving body, whose rho = sqrt(b + c^2 s^2) turns over
# at s ~ sqrt|b|/c (upstream: in its wake the slope ~ b/c^2 is below the reference's
# own accuracy).
@pytest.mark.parametrize("c, b, points", [
    (0.0, 0.5, POINTS), (0.0, 2.0 + 3.0j, POINTS), (0.7, 10.0 - 4.0j, POINTS),
    (-2.0, 0.5, POINTS), (5.0, 2.0 + 3.0j, POINTS), (3.0, 1e-3 + 1e-3j, (0.02, 0.05, 1.0))])
def test_laplace_transform_of_instantaneous_source(c, b, points):
    for u in points:
        ref = _time_domain(u, c, b)
        got = [tk.transient_temperature(u, c, b), tk.transient_displacement(u, c, b),
               tk.transient_slope(u, c, b)]
        for g, r in zip(got, ref):
            assert abs(g - r) < 1e-11 * abs(r), (u, g, r)


# --- Fourier integrals of the stationary half-plane ------------------------------

@pytest.mark.parametrize("b", [1.0j, 3.0 - 2.0j, 0.4])
def test_stationary_half_plane_fourier_integrals(b):
    """``T = (Q/(pi K)) int_0^inf cos(k u)/gamma dk`` and
    ``dw/dx = -(2 delta Q/pi) int_0^inf k/(gamma (gamma + k)) sin(k u) dk``
    (from ``w_hat = (2 delta Q/b)(1 - |k|/gamma)``), each less its ``b = 1`` tail
    (``K0`` and ``(pi/4)(I0 - L0)``, Gradshteyn and Ryzhik 3.754) so that what is left
    decays like ``k^-3``; the differences are formed free of cancellation."""
    b = complex(b)

    def fourier(f, u, weight):
        opts = dict(weight=weight, wvar=u, epsabs=1e-12, limlst=200)
        return (quad(lambda k: f(k).real, 0.0, np.inf, **opts)[0]
                + 1j * quad(lambda k: f(k).imag, 0.0, np.inf, **opts)[0])

    def temperature_rest(k):  # 1/gamma - 1/g1
        g, h = np.sqrt(k * k + b), np.sqrt(k * k + 1.0)
        return (1.0 - b) / (g * h * (g + h))

    def slope_rest(k):  # k/(gamma (gamma + k)) - 1/(2 g1)
        g, h = np.sqrt(k * k + b), np.sqrt(k * k + 1.0)
        return (k * (1.0 - b) / (h + g) + k / (h + k) - b) / (2.0 * h * g * (g + k))

    for u in (0.3, 1.7):
        t_ref = fourier(temperature_rest, u, "cos") + k0(u)
        s_ref = (2.0 / np.pi) * (fourier(slope_rest, u, "sin")
                                 + 0.25 * np.pi * (i0(u) - modstruve(0, u)))
        assert abs(tk.transient_temperature(u, 0.0, b) - t_ref) < 1e-12 * abs(t_ref)
        assert abs(tk.transient_slope(u, 0.0, b) - s_ref) < 1e-12 * abs(s_ref)
        assert abs(tk.transient_slope(-u, 0.0, b) + s_ref) < 1e-12 * abs(s_ref)


# --- symmetries ------------------------------------------------------------------

ALL = [tk.transient_temperature, tk.transient_temperature_gradient,
       tk.transient_temperature_gradient_regular, tk.transient_displacement, tk.transient_slope]


@pytest.mark.parametrize("kernel", ALL)
def test_real_rate_gives_real_kernel_and_conjugation(kernel):
    u = np.array([-3.0, -0.4, 0.01, 0.7, 5.0])
    for c in (0.0, 2.5):
        assert np.isrealobj(kernel(u, c, 1.7))
        assert np.isrealobj(kernel(u, c, 1.7 + 0.0j))
        z = kernel(u, c, 1.7 + 0.9j)
        np.testing.assert_allclose(kernel(u, c, 1.7 - 0.9j), np.conj(z), rtol=1e-14)


def test_mirror_symmetry_in_the_direction_of_motion():
    """A body moving toward +x is the mirror image of one moving toward -x."""
    u = np.array([-3.0, -0.4, 0.01, 0.7, 5.0])
    b = 0.8 + 2.0j
    for c in (0.3, 4.0):
        for kernel, parity in [(tk.transient_temperature, 1), (tk.transient_displacement, 1),
                               (tk.transient_temperature_gradient, -1), (tk.transient_slope, -1)]:
            np.testing.assert_allclose(kernel(u, -c, b), parity * kernel(-u, c, b), rtol=1e-13)


def test_slope_jumps_by_one_at_the_source():
    """``w'' = -delta Q`` at the source at every rate: ``S(0+) - S(0-) = 1``, ``S(0)`` the mean."""
    for c, b in [(0.0, 3.0 + 1.0j), (2.0, 0.5j), (-1.0, 4.0)]:
        left, mid, right = tk.transient_slope(np.array([-1e-13, 0.0, 1e-13]), c, b)
        assert abs(right - left - 1.0) < 1e-11
        assert abs(mid - 0.5 * (left + right)) < 1e-11


# --- short times: large |b| ------------------------------------------------------

def test_large_rate_localises_the_stationary_slope():
    """``S = sgn(u) P(sqrt(b)|u|)``, ``P(z) ~ (4/z^3 + 24/z^5 + 540/z^7 + 25200/z^9)/pi``:
    the kernel decays on the conduction length ``sqrt(k/|b|)`` (eq. T12)."""
    b = 1e4 * np.exp(0.3j * np.pi)
    u = np.array([0.5, 1.0, 2.0, -1.5])
    z = np.sqrt(b) * np.abs(u)
    series = np.sign(u) * (4.0 / z**3 + 24.0 / z**5 + 540.0 / z**7 + 25200.0 / z**9) / np.pi
    np.testing.assert_allclose(tk.transient_slope(u, 0.0, b), series, rtol=1e-7)


@pytest.mark.parametrize("kernel", [tk.transient_temperature, tk.transient_slope,
                                    tk.transient_temperature_gradient])
def test_large_rate_convection_is_negligible(kernel):
    """At short times the moving body conducts like the stationary one: on the
    conduction length the kernels differ by O(c/sqrt|b|)."""
    c, x = 3.0, np.array([-2.0, -0.5, 0.3, 1.0])
    errors = []
    for mag in (1e4, 1e6, 1e8):
        b = mag * np.exp(0.2j * np.pi)
        u = x / np.sqrt(mag)
        errors.append(np.max(np.abs(kernel(u, c, b) / kernel(u, 0.0, b) - 1.0)))
    assert errors[0] < 0.1
    assert 5.0 < errors[0] / errors[1] < 20.0 and 5.0 < errors[1] / errors[2] < 20.0


# --- bad input -------------------------------------------------------------------

@pytest.mark.parametrize("c, b", [(1.0, -2.0), (0.0, 0.0), (1.0, float("nan")), ("x", 1.0)])
def test_bad_input_is_refused(c, b):
    with pytest.raises(InputError):
        tk.transient_slope([0.5], c, b)


# --- moments on the edge-graded representation -----------------------------------

def _split_moments(kernel, s, n, **kw):
    """Moments of a complex kernel: of its real and imaginary parts, separately."""
    re = moment_engine.moments(lambda u: kernel(u).real, s, n, **kw)
    im = moment_engine.moments(lambda u: kernel(u).imag, s, n, **kw)
    return [r + 1j * i for r, i in zip(re, im)]


def test_graded_moments_at_small_rate_equal_the_steady_ones():
    n = 8
    s = np.cos(moment_engine.stretch(np.pi * (np.arange(n, 0, -1) - 0.5) / n))
    c, b = 5.0, 1e-30 * np.exp(0.3j * np.pi)
    pairs = [
        (lambda u: tk.transient_temperature_gradient_regular(u, c, b),
         lambda u: steady.cylinder_temperature_gradient_regular(u, c),
         dict(scale=c, logarithmic=True)),
        (lambda u: tk.transient_slope(u, c, b), lambda u: steady.cylinder_slope(c * u),
         dict(scale=c)),
        (lambda u: tk.transient_slope(u, 0.0, b), steady.half_plane_slope, dict(scale=1.0)),
    ]
    for transient, reference, kw in pairs:
        for got, ref in zip(_split_moments(transient, s, n, **kw),
                            moment_engine.moments(reference, s, n, **kw)):
            assert np.max(np.abs(got - ref)) < 1e-12 * np.max(np.abs(ref))


@pytest.mark.parametrize("kernel, kw", [
    (lambda u: tk.transient_temperature_gradient_regular(u, 5.0, 2.0 + 7.0j),
     dict(scale=5.0, logarithmic=True)),
    (lambda u: tk.transient_slope(u, 0.0, 4.0 - 3.0j), dict(scale=np.sqrt(5.0))),
])
def test_graded_moments_of_a_complex_rate_against_quadrature(kernel, kw):
    """One entry of each moment matrix against a separate quadrature in ``tau``: 20-point
    Gauss-Legendre on panels halving toward the point's own ``tau_s`` (where the kernel
    jumps or is logarithmic) from both sides, 52 deep."""
    n, j, row = 8, 3, 5
    tau = np.pi * (np.arange(n, 0, -1) - 0.5) / n  # the points of the test above
    tau_s = tau[row]
    bounded, singular = _split_moments(kernel, np.cos(moment_engine.stretch(tau)), n, **kw)
    x, w = np.polynomial.legendre.leggauss(20)
    offsets, weights = [], []
    for length, side in ((tau_s, -1.0), (np.pi - tau_s, 1.0)):
        far = length * 2.0 ** -np.arange(53)  # panel [far/2, far] of distances from tau_s
        near = np.append(far[1:], 0.0)
        d = 0.5 * (far + near)[:, None] + 0.5 * (far - near)[:, None] * x
        offsets.append(side * d.ravel())
        weights.append((0.5 * (far - near)[:, None] * w).ravel())
    d, w_nodes = np.concatenate(offsets), np.concatenate(weights)
    t_nodes = tau_s + d
    t = moment_engine.stretch(t_nodes)
    # s - cos t without cancellation next to tau_s: t - t_s = d - cos(2 tau_s + d) sin d.
    dt = d - np.cos(2.0 * tau_s + d) * np.sin(d)
    u = 2.0 * np.sin(moment_engine.stretch(tau_s) + 0.5 * dt) * np.sin(0.5 * dt)
    common = w_nodes * kernel(u) * moment_engine.stretch_derivative(t_nodes) * np.cos(j * t_nodes)
    b_ref, s_ref = np.sum(common * np.sin(t) ** 2), np.sum(common)
    assert abs(bounded[row, j] - b_ref) < 1e-12 * np.max(np.abs(bounded))
    assert abs(singular[row, j] - s_ref) < 1e-12 * np.max(np.abs(singular))


def test_regular_gradient_series_against_mpmath():
    """``G - 1/u`` near the source, where the series (T5) replaces the Bessel functions
    (``|mu u| < 1e-2``), and just beyond, against 40-digit ``mpmath`` at complex rates;
    and the temperature formed in the same pass (the series of ``K0`` there), to 2e-15."""
    mpmath.mp.dps = 40
    for c, b in [(0.0, 3.0 + 4.0j), (0.5, 3.0 + 4.0j), (-2.0, 1.0 - 6.0j)]:
        mu = np.sqrt(c * c + b)
        u = np.array([-2e-2, -9e-3, -2e-3, -1e-7, 1e-7, 9e-4, 9e-3, 2e-2]) / abs(mu)
        got = tk.transient_temperature_gradient_regular(u, c, b)
        temperature, again = tk.transient_temperature_and_gradient_regular(u, c, b)
        np.testing.assert_array_equal(again, got)
        for ui, g, t in zip(u, got, temperature):
            x, m = mpmath.mpf(ui), mpmath.sqrt(mpmath.mpc(c * c + b))
            k0, k1 = mpmath.besselk(0, m * abs(x)), mpmath.besselk(1, m * abs(x))
            ref = complex(mpmath.exp(-c * x) * (c * k0 + m * mpmath.sign(x) * k1) - 1 / x)
            # 5e-13: the cancellation of 1/u against mu K1 just beyond the series
            assert abs(g - ref) < 5e-13 * abs(ref), (c, ui, g, ref)
            t_ref = complex(mpmath.exp(-c * x) * k0)
            assert abs(t - t_ref) < 2e-15 * abs(t_ref), (c, ui, t, t_ref)


@pytest.mark.parametrize("c, b", [(0.0, 1.0 + 1.0j), (5.0, 0.3 - 2.0j), (3.0, 0.0), (-2.0, 0.5)])
def test_displacement_and_slope_in_one_pass(c, b):
    """The one quadrature pass of both kernels gives each as its own does, to a few ulps
    (the same sums, formed in arrays of another shape: conftest.assert_ulps)."""
    u = np.concatenate([U, [0.0]])
    w, s = tk.transient_displacement_and_slope(u, c, b)
    assert_ulps(w, tk.transient_displacement(u, c, b))
    assert_ulps(s, tk.transient_slope(u, c, b))


@pytest.mark.parametrize("b", [1.0 + 1.0j, 1e-3 + 1e4j, 0.4])
def test_stationary_half_plane_at_a_point_and_its_mirror_image(b):
    """The stationary half-plane's quadrature in phi is formed once for ``u`` and ``-u``
    (``D = rho`` on either side), each side's integrand on it: at points of both signs
    in one call, each side's values are those of a call at that side's points alone, to
    1e-14 of the largest, the displacement even and the slope odd."""
    u = np.geomspace(1e-8, 2.0, 120)
    w, s = tk.transient_displacement_and_slope(np.concatenate([-u[::-1], u]), 0.0, b)
    wp, sp = tk.transient_displacement_and_slope(u, 0.0, b)
    wn, sn = tk.transient_displacement_and_slope(-u[::-1], 0.0, b)
    for got, ref in ((w, np.concatenate([wn, wp])), (s, np.concatenate([sn, sp])),
                     (wn[::-1], wp), (-sn[::-1], sp)):
        assert np.abs(got - ref).max() < 1e-14 * np.abs(ref).max()


@pytest.mark.parametrize("c, b", [(0.0, 1e-4 + 1e-4j), (50.0, 1e-3 + 0.5j), (-30.0, 1e-3 + 2e3j),
                                  (1000.0, 1e-3 + 30j)])
def test_series_next_to_the_source_is_the_quadrature(monkeypatch, c, b):
    """Next to the source (``|u| lam <= 1/2``) the displacement and slope are their series
    in ``|u|`` (derivation, "Transient kernels", *Evaluation*): against the graded
    quadrature at every point (the series switched off), at the stability tables' nodes
    (down to ``|u| = 2^-36``, both sides) and at ``u = 0``, to 1e-14 of the largest
    value."""
    from thermocontact.numerics.tabulated_moments import kernel_nodes

    u = np.concatenate([kernel_nodes(), [0.0]])
    series = tk.transient_displacement_and_slope(u, c, b)
    monkeypatch.setattr(tk, "_SERIES_REACH", -1.0)
    graded = tk.transient_displacement_and_slope(u, c, b)
    for got, ref in zip(series, graded):
        assert np.abs(got - ref).max() < 1e-14 * np.abs(ref).max()


@pytest.mark.parametrize("c", [0.0, 1.5, -20.0])
def test_displacement_and_slope_of_several_rates_in_one_pass(c):
    """Several rates in one pass (each on its own rules) give each rate's kernels as one
    at a time do: to rounding (a real rate among complex ones is computed in complex
    arithmetic), over the series' reach and the graded rule's."""
    u = np.concatenate([-np.geomspace(1e-8, 3.0, 40), np.geomspace(1e-8, 3.0, 40)])
    rates = [0.4, 1e-3 + 2.0j, 3e4 - 1e5j, 1e-3 + 1e6j]
    W, S = tk.transient_displacement_and_slope(u, c, rates)
    assert W.shape == S.shape == (len(rates), u.size)
    for j, b in enumerate(rates):
        w, s = tk.transient_displacement_and_slope(u, c, b)
        np.testing.assert_allclose(W[j], w, rtol=1e-14, atol=0.0)
        np.testing.assert_allclose(S[j], s, rtol=1e-14, atol=1e-300)
