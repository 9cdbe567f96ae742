"""Checks of the transient contact's time-domain responses against independent routes.

One half-plane, diffusivity ratio ``r = kappa/kappa2``, convection speed
``s = v l/kappa2`` (lengths in ``l``, time ``tau`` in ``l^2/kappa2``), whose surface point
``xi`` releases an energy ``E`` at ``tau = 0``; ``U = x - xi + s tau``:

* (R1) temperature ``exp(-U^2/(4 r tau))/(2 tau)`` times ``E/(pi K)`` per unit ``tau``;
* (R2) displacement ``(4 r/(pi^(3/2) U)) F(U/(2 sqrt(r tau)))`` times ``delta E``.

What is checked, and against what:

* ``Phi(Z) = int_0^Z F(z)/z dz`` against mpmath quadrature (across ``Z = 16``, where the
  table gives way to the asymptotic series), its oddness and ``Phi(inf) = pi^(3/2)/4``
  (from ``F(z)/z = int_0^1 exp(-z^2 (1 - t^2)) dt``).
* The Laplace transforms in ``tau`` of (R1), (R2), by adaptive quadrature, against the
  kernels (T3), (T9) of :mod:`thermocontact.physics.transient_green_functions`.  In the
  body's own units (``Delta = l``, time ``k t/l^2 = r tau``) the rate ``b`` (units
  ``kappa2/l^2``) is ``B = b/r`` and the Peclet number ``c = v l/(2 kappa) = s/(2 r)``:
  ``exp(-b tau - U^2/(4 r tau)) = exp(-c u) exp(-(B + c^2) r tau - u^2/(4 r tau))``, and
  ``int_0^inf exp(-p t - a/t) dt/(2 t) = K0(2 sqrt(a p))`` gives (T3) with no other
  factor; the displacement's ``4 r dtau`` is ``4 dt'`` of (T8) in the body's time
  ``t' = r tau``, so (T9) has no other factor either.  The same for the element forms
  (R4), (R5) against (T3), (T9) integrated over the element.
* The tables of :func:`thermocontact.discretisation.history.lag_tables`:
  (i) summed over lags, the steady element integrals (section 14b) of a moving body,
  the displacement's algebraic tail accounted for by its expansion, whose decay is
  measured; (ii) the stationary body's finite-time temperature in closed form,
  ``int_0^T exp(-u^2/(4 r tau))/(2 tau) dtau = E1(u^2/(4 r T))/2``; (iii) the balance
  of heat (``int dx`` of (R1) is ``sqrt(pi r/tau)``) and of displacement (``int dx`` of
  (R2) is ``2 r``, the Fourier form at ``k = 0``), the window's truncated tails added
  from ``int_Z^inf F(z)/z dz = (sqrt(pi)/2) int_0^(pi/2) erfc(Z cos theta) dtheta``;
  (iv) entries against QUADPACK in time.
* :class:`thermocontact.numerics.online_convolution.OnlineConvolution` against the
  direct sum, and its refusal of calls out of order.
"""

from __future__ import annotations

import mpmath
import numpy as np
import pytest
from scipy.integrate import quad
from scipy.special import dawsn, erf, erfc, exp1

from thermocontact.discretisation.element_operators import (displacement_integral,
                                                            temperature_integral)
from thermocontact.discretisation.history import lag_tables
from thermocontact.numerics.online_convolution import OnlineConvolution
from thermocontact.physics import impulse_responses as ir
from thermocontact.physics.transient_green_functions import (transient_displacement,
                                                             transient_temperature)


# --------------------------------------------------------------------------- a. Phi

def _dawson_ratio_mp(z):
    """``F(z)/z = 1F1(1; 3/2; -z^2)`` (Abramowitz and Stegun 7.1.21, 13.1.27)."""
    return mpmath.hyp1f1(1, 1.5, -z * z)


def _phi_mpmath(Z):
    """``int_0^Z F(z)/z dz`` at 30 digits."""
    with mpmath.workdps(30):
        a = abs(Z)
        edges = [mpmath.mpf(0)] + [mpmath.mpf(e) for e in (1, 4, 16, 64, 256) if e < a] \
            + [mpmath.mpf(a)]
        return float(mpmath.sign(Z) * mpmath.quad(_dawson_ratio_mp, edges))


@pytest.mark.parametrize("Z", [1e-7, 3e-3, 0.4, 1.0, 2.7, 7.3, 15.5, 15.9999, 16.0,
                               16.0001, 16.7, 23.0, 60.0, 300.0])
def test_phi_against_mpmath(Z):
    got = ir.dawson_log_integral(np.array([Z, -Z]))
    ref = _phi_mpmath(Z)
    assert abs(got[0] - ref) <= 1e-15                     # the documented accuracy
    assert got[1] == -got[0]                              # odd, exactly


def test_phi_at_infinity_and_continuity_at_the_switch():
    with mpmath.workdps(30):
        total = mpmath.quad(_dawson_ratio_mp, [0, 1, 4, 16, 64, mpmath.inf])
        exact = mpmath.pi ** 1.5 / 4
    assert abs(total - exact) < 1e-25
    assert ir.PHI_INFINITY == pytest.approx(float(exact), rel=1e-16)
    far = ir.dawson_log_integral(np.array([1e8, 1e300, np.inf, -np.inf]))
    assert far[0] == pytest.approx(float(exact) - 0.5e-8, rel=1e-15)     # Phi ~ Phi_inf - 1/(2Z)
    np.testing.assert_array_equal(far[1:], [ir.PHI_INFINITY, ir.PHI_INFINITY,
                                            -ir.PHI_INFINITY])
    # Across Z = 16 (the table's end and the series' start) the slope is F(16)/16.
    e = 1e-7
    jump = ir.dawson_log_integral(16.0 + e) - ir.dawson_log_integral(16.0 - e)
    assert jump == pytest.approx(2 * e * dawsn(16.0) / 16.0, rel=1e-6)


# ------------------------------------------------------------- b. Laplace transforms

def _point_temperature(u, tau, r, s):
    U = u + s * tau
    return np.exp(-U * U / (4.0 * r * tau)) / (2.0 * tau)


def _point_displacement(u, tau, r, s):
    U = u + s * tau
    return 4.0 * r / (np.pi ** 1.5 * U) * dawsn(U / (2.0 * np.sqrt(r * tau)))


def _laplace(response, b, r, s, scales, decays):
    """``int_0^inf exp(-b tau) response(tau) dtau`` by QUADPACK in ``y = ln tau``.

    Cut at ``tau = 1e-40`` (every response vanishes there like a power or faster) and
    where the exponential factor is below ``exp(-80)``; ``scales`` are break points.
    """
    rate = b.real + (s * s / (4.0 * r) if decays else 0.0)
    lo, hi = np.log(1e-40), np.log(80.0 / rate)
    pts = sorted(p for p in np.log(np.asarray(scales, dtype=float)) if lo < p < hi)
    out = []
    for part in (np.real, np.imag):
        def g(y):
            t = np.exp(y)
            return part(t * response(t) * np.exp(-b * t))
        out.append(quad(g, lo, hi, points=pts or None, limit=400, epsabs=0.0,
                        epsrel=1e-13)[0])
    return complex(out[0], out[1])


#: (r, s, b, u): a moving body both ways and on both sides of the source (the cylinder
#: of Pe_l = 5.43 and k1/k2 = 0.1 among them), and the stationary one; real and complex b.
LAPLACE_CASES = [(0.1, 10.86, 0.5, 0.3), (0.1, 10.86, 0.5, -0.3), (1.0, 3.0, 2 + 3j, -1.0),
                 (1.0, 3.0, 2 + 3j, 0.5), (2.5, -4.0, 1 - 2j, 0.7), (2.5, -4.0, 1 - 2j, -0.2),
                 (1.0, 0.0, 0.5, 0.05), (1.0, 0.0, 0.5, -2.0), (1.0, 0.0, 2 + 3j, 0.3),
                 (0.4, 0.0, 0.7 + 0.2j, 1.1)]


def _scales(u, r, s):
    return [u * u / (4.0 * r), abs(u / s) if s else 1.0, 1.0]


@pytest.mark.parametrize("r, s, b, u", LAPLACE_CASES)
def test_point_responses_laplace_transform_to_the_rate_kernels(r, s, b, u):
    b = complex(b)
    c, B = s / (2.0 * r), b / r
    T = transient_temperature(np.array([u]), c, B)[0]
    W = transient_displacement(np.array([u]), c, B)[0]
    LT = _laplace(lambda t: _point_temperature(u, t, r, s), b, r, s, _scales(u, r, s), True)
    LW = _laplace(lambda t: _point_displacement(u, t, r, s), b, r, s, _scales(u, r, s), False)
    assert abs(LT - T) <= 1e-12 * abs(T)
    assert abs(LW - W) <= 1e-12 * abs(W)


@pytest.mark.parametrize("r, s, b, X", [(0.1, 10.86, 0.5, -0.8), (1.0, 3.0, 2 + 3j, 0.6),
                                        (2.5, -4.0, 1 - 2j, -0.5), (1.0, 0.0, 0.5, 0.9)])
def test_element_responses_laplace_transform_to_the_element_integrals(r, s, b, X):
    """(R4), (R5) of the module against (T3), (T9) integrated over the element (24-point
    Gauss-Legendre: the element is away from the source, the kernels smooth on it)."""
    b, h = complex(b), 0.2
    c, B = s / (2.0 * r), b / r
    x, w = np.polynomial.legendre.leggauss(24)
    u = X + 0.5 * h * x
    T = 0.5 * h * (w @ transient_temperature(u, c, B))
    W = 0.5 * h * (w @ transient_displacement(u, c, B))
    edges = [abs(X - 0.5 * h), abs(X + 0.5 * h)]
    scales = [e * e / (4.0 * r) for e in edges] + ([e / abs(s) for e in edges] if s else []) + [1]
    LT = _laplace(lambda t: ir.element_temperature(X, t, h, r, s), b, r, s, scales, True)
    LW = _laplace(lambda t: ir.element_displacement(X, t, h, r, s), b, r, s, scales, False)
    assert abs(LT - T) <= 1e-12 * abs(T)
    assert abs(LW - W) <= 1e-12 * abs(W)


# ------------------------------------------------------------------------ c. tables

def _offsets(N, h):
    return h * np.arange(-(N - 1), N, dtype=float)


def _steady(antiderivative, X, h, c):
    return (antiderivative(c * (X + 0.5 * h)) - antiderivative(c * (X - 0.5 * h))) / c


@pytest.mark.parametrize("N, h, dt, steps, r, s", [
    (20, 0.1, 0.1, 600, 1.0, 2.0), (20, 0.1, 0.1, 600, 1.0, -2.0),
    (40, 0.025, 0.005, 100, 0.1, 10.86), (20, 0.1, 0.02, 600, 2.5, 7.0)])
def test_temperature_table_sums_to_the_steady_element_integral(N, h, dt, steps, r, s):
    """A moving body's temperature tail dies like exp(-s^2 tau/(4 r)): below exp(-50)."""
    assert s * s * steps * dt / (4.0 * r) >= 50.0
    T, _ = lag_tables(N, h, dt, steps, r, s)
    X = _offsets(N, h)
    ref = _steady(temperature_integral, X, h, s / (2.0 * r))
    assert np.max(np.abs(T.sum(axis=1) - ref)) <= 1e-12 * np.max(np.abs(ref))


def test_displacement_table_sums_to_the_steady_element_integral_with_its_tail():
    """The displacement's tail is algebraic.  For ``s tau >> |u|, sqrt(r tau)``,
    ``F(z) ~ 1/(2z) + 1/(4 z^3)`` in (R2) gives

        w ~ (4 r^1.5/(pi^1.5 s^2)) tau^-1.5 - (8 r^1.5 u/(pi^1.5 s^3)) tau^-2.5
            + (8 r^2.5/(pi^1.5 s^4)) tau^-2.5
            + ((12 r^1.5 u^2/s^4 - 32 r^2.5 u/s^5)/pi^1.5) tau^-3.5 + ...

    so each step's entry decays like ``tau^-1.5`` (the same for every offset), the
    difference between offsets (the slope) like ``tau^-2.5``, and the slope's remainder
    after ``T`` like ``T^-1.5``, then ``T^-2.5`` once the first term is added back.
    """
    N, h, dt, steps, r, s = 20, 0.1, 0.5, 400, 1.0, 2.0
    _, W = lag_tables(N, h, dt, steps, r, s)
    X = _offsets(N, h)
    ref = _steady(displacement_integral, X, h, s / (2.0 * r)) / (s / (2.0 * r))
    ref_diff = ref - ref[N - 1]
    u2 = X * X + h * h / 12.0 - h * h / 12.0      # element mean of u^2, minus offset 0's
    k = np.pi ** 1.5
    errors = []
    for M in (200, 400):
        T = M * dt
        diff = W[:, :M].sum(axis=1) - W[N - 1, :M].sum()
        first = -(16.0 / 3.0) * r ** 1.5 * X * h * T ** -1.5 / (k * s ** 3)
        second = 0.4 * T ** -2.5 * h * (12 * r ** 1.5 * u2 / s ** 4 - 32 * r ** 2.5 * X / s ** 5) / k
        errors.append([np.max(np.abs(diff - ref_diff)), np.max(np.abs(diff + first - ref_diff)),
                       np.max(np.abs(diff + first + second - ref_diff))])
    ratio = np.array(errors[0]) / np.array(errors[1])
    # Doubling T divides the remainders by 2^1.5, 2^2.5, 2^3.5.
    np.testing.assert_allclose(np.log2(ratio), [1.5, 2.5, 3.5], atol=0.06)
    assert errors[1][2] <= 1e-8 * np.max(np.abs(ref_diff))
    # The decay of the entries themselves between tau = 100 and 200.
    m1, m2 = 200, 399
    t1, t2 = (m1 + 0.5) * dt, (m2 + 0.5) * dt
    for d in (N - 11, N - 1, N + 9):
        assert np.log(W[d, m2] / W[d, m1]) / np.log(t2 / t1) == pytest.approx(-1.5, abs=0.015)
        if d != N - 1:
            slope = W[d] - W[N - 1]
            assert np.log(slope[m2] / slope[m1]) / np.log(t2 / t1) == pytest.approx(-2.5, abs=0.02)
            lead = -8.0 * r ** 1.5 * X[d] * h * dt * t2 ** -2.5 / (k * s ** 3)
            assert slope[m2] == pytest.approx(lead, rel=0.01)


@pytest.mark.parametrize("r", [1.0, 0.35])
def test_stationary_temperature_table_to_a_finite_time(r):
    """``sum_{m < M} A[d, m] = int_elem E1(u^2/(4 r T))/2 du``, ``T = M dt``, whose
    antiderivative is ``(u E1(a u^2) + sqrt(pi/a) erf(sqrt(a) u))/2``, ``a = 1/(4 r T)``."""
    N, h, dt, steps = 20, 0.1, 0.01, 300
    T, _ = lag_tables(N, h, dt, steps, r, 0.0)
    X = _offsets(N, h)

    def antiderivative(u, a):
        with np.errstate(invalid="ignore"):
            first = np.where(u == 0.0, 0.0, u * exp1(a * u * u))
        return 0.5 * (first + np.sqrt(np.pi / a) * erf(np.sqrt(a) * u))

    for M in (1, 7, 100, 300):
        a = 1.0 / (4.0 * r * M * dt)
        ref = antiderivative(X + 0.5 * h, a) - antiderivative(X - 0.5 * h, a)
        got = T[:, :M].sum(axis=1)
        assert np.max(np.abs(got - ref)) <= 1e-10 * np.max(np.abs(ref))
    # One entry by QUADPACK of the closed form's integrand (log-singular at u = 0).
    a = 1.0 / (4.0 * r * steps * dt)
    ref0 = quad(lambda u: 0.5 * exp1(a * u * u), -0.5 * h, 0.5 * h, points=[0.0],
                epsabs=0.0, epsrel=1e-13)[0]
    assert T[N - 1].sum() == pytest.approx(ref0, rel=1e-10)


def _psi(Z):
    """``int_Z^inf F(z)/z dz = (sqrt(pi)/2) int_0^(pi/2) erfc(Z sin phi) dphi`` (from
    ``F(z)/z = int_0^1 exp(-z^2 (1 - t^2)) dt``, ``t = cos phi``); ``erfc`` is below
    1e-300 beyond ``Z sin phi = 27``."""
    top = np.arcsin(min(1.0, 27.0 / Z))
    pts = [np.arcsin(k / Z) for k in (1.0, 4.0) if k < Z * np.sin(top)] or None
    return 0.5 * np.sqrt(np.pi) * quad(lambda p: erfc(Z * np.sin(p)), 0.0, top, points=pts,
                                       epsabs=0.0, epsrel=1e-13, limit=200)[0]


@pytest.mark.parametrize("r, s", [(1.0, 2.0), (1.0, 0.0), (0.4, -3.0)])
def test_tables_balance_heat_and_displacement(r, s):
    """Over all offsets, lag ``m`` holds the heat ``2 sqrt(pi r)(sqrt((m+1)dt) - sqrt(m dt))``
    (exponentially small tails outside the window) and the displacement ``2 r dt``, less
    what lies outside ``|x| < L = (N - 1/2) h`` (added back from (R5)'s complement)."""
    N, h, dt, steps = 170, 0.1, 0.01, 100
    L = (N - 0.5) * h
    assert L - abs(s) * steps * dt > 14.0 * np.sqrt(r * steps * dt)   # erfc(7) ~ 4e-23
    T, W = lag_tables(N, h, dt, steps, r, s)
    m = np.arange(steps)
    heat = 2.0 * np.sqrt(np.pi * r) * (np.sqrt((m + 1) * dt) - np.sqrt(m * dt))
    np.testing.assert_allclose(T.sum(axis=0), heat, rtol=1e-12, atol=0)
    x, w = np.polynomial.legendre.leggauss(20)
    for lag in (0, 1, 9, 99):
        a, b = np.sqrt(lag * dt), np.sqrt((lag + 1) * dt)
        sig = 0.5 * (a + b) + 0.5 * (b - a) * x
        outside = []
        for sg in sig:
            root = 2.0 * np.sqrt(r) * sg
            outside.append(_psi((L + s * sg * sg) / root) + _psi((L - s * sg * sg) / root))
        missing = 4.0 * r / np.pi ** 1.5 * (0.5 * (b - a)) * np.sum(w * 2.0 * sig * outside)
        assert W[:, lag].sum() + missing == pytest.approx(2.0 * r * dt, rel=1e-12)
        assert missing > 1e-3 * 2.0 * r * dt          # the tails are not negligible


def _entry_reference(X, m, dt, h, r, s, floor):
    """An entry of each table by QUADPACK in ``sigma = sqrt(tau)``: the temperature from
    erf written here, the displacement from (R5); break points where the convected
    pulse crosses the element's edges."""
    a, b = np.sqrt(m * dt), np.sqrt((m + 1) * dt)
    pts = []
    if s != 0.0:
        for edge in (X - 0.5 * h, X + 0.5 * h):
            t = -edge / s
            if a * a < t < b * b:
                pts.append(np.sqrt(t))

    def temp(sg):
        root = 2.0 * np.sqrt(r) * sg
        U = X + s * sg * sg
        return np.sqrt(np.pi * r) * (erf((U + 0.5 * h) / root) - erf((U - 0.5 * h) / root))

    def disp(sg):
        return 2.0 * sg * ir.element_displacement(X, sg * sg, h, r, s)

    kw = dict(points=sorted(pts) or None, limit=400, epsrel=1e-13)
    return quad(temp, a, b, epsabs=floor[0], **kw)[0], quad(disp, a, b, epsabs=floor[1], **kw)[0]


@pytest.mark.parametrize("N, h, dt, r, s, offsets", [
    (8, 0.1, 0.01, 1.0, 0.0, (0, 1, -1, 5)),
    (60, 0.02, 0.05, 1.0, 20.0, (0, 1, -1, -25, -50, -59)),
    (60, 0.02, 0.05, 0.1, 20.0, (0, 1, -1, -25, -50, -59)),
    (40, 0.025, 0.005, 0.1, 10.86, (0, 1, -1, -2, -20))])
def test_table_entries_against_adaptive_quadrature(N, h, dt, r, s, offsets):
    T, W = lag_tables(N, h, dt, 3, r, s)
    scale_T, scale_W = np.max(np.abs(T)), np.max(np.abs(W))
    for lag in (0, 1, 2):
        for d in offsets:
            ref_T, ref_W = _entry_reference(d * h, lag, dt, h, r, s,
                                            (1e-13 * scale_T, 1e-13 * scale_W))
            assert abs(T[d + N - 1, lag] - ref_T) <= 1e-10 * scale_T
            assert abs(W[d + N - 1, lag] - ref_W) <= 1e-10 * scale_W


# ------------------------------------------------------------- d. the online history

def _direct(A, x):
    L = A.shape[0]
    y = np.zeros((L + 1, A.shape[1], A.shape[3]), dtype=np.result_type(A, x))
    for n in range(1, L + 1):
        for m in range(1, n):
            y[n] += np.einsum("oik,ik->ok", A[m], x[n - m])
    return y


@pytest.mark.parametrize("L", [1, 2, 3, 17, 64, 100, 300])
@pytest.mark.parametrize("complex_", [False, True])
def test_online_convolution_equals_the_direct_sum(L, complex_):
    rng = np.random.default_rng(L + 1000 * complex_)
    shape = (L, 2, 3, 4)
    A = rng.standard_normal(shape)
    x = rng.standard_normal((L + 1, 3, 4))
    if complex_:
        A = A + 1j * rng.standard_normal(shape)
        x = x + 1j * rng.standard_normal(x.shape)
    conv = OnlineConvolution(A)
    ref = _direct(A, x)
    scale = max(1.0, np.max(np.abs(ref)))
    for n in range(1, L + 1):
        y = conv.history(n).copy()
        assert np.iscomplexobj(y) == complex_
        np.testing.assert_allclose(y, ref[n], rtol=0, atol=1e-13 * scale * np.log2(L + 1))
        conv.push(x[n])
    assert not np.any(ref[1])          # step 1 has no history


def test_online_convolution_refuses_calls_out_of_order():
    """History before push, one step at a time; asking again in a step adds nothing."""
    A = np.ones((8, 1, 1, 1))
    conv = OnlineConvolution(A)
    with pytest.raises(ValueError):
        conv.history(2)
    with pytest.raises(ValueError):
        conv.push(np.ones((1, 1)))                 # step 1's history not yet asked
    conv.history(1)
    conv.push(np.ones((1, 1)))
    with pytest.raises(ValueError):
        conv.history(1)
    with pytest.raises(ValueError):
        conv.history(3)
    assert conv.history(2)[0, 0] == 1.0
    assert conv.history(2)[0, 0] == 1.0           # the same, not added twice
    conv.push(np.ones((1, 1)))
    with pytest.raises(ValueError):
        conv.push(np.ones((1, 1)))                 # step 3's history not yet asked
    assert conv.history()[0, 0] == 2.0             # x[1] + x[2]
