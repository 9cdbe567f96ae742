"""Independent verification of the Green's-function kernels from the field equations.

The kernels in :mod:`thermocontact.physics.green_functions` are checked against reference values
built here from the underlying partial differential equations, without using the
closed forms the kernels implement.

Setting and conventions
-----------------------
The body is an elastic, heat-conducting half-plane ``y < 0`` with surface
``y = 0``, conductivity ``K``, diffusivity ``kappa``, thermal expansion ``alpha``,
Poisson's ratio ``nu`` (plane strain) and distortivity
``delta = alpha (1 + nu) / K``.  The outward surface displacement ``w`` is the
normal displacement toward ``+y``.  A line heat source ``Q`` (per unit length and
time, entering the body) sits at ``x = 0`` on the otherwise insulated surface.

* Moving body: the material moves with velocity ``-v`` along ``x``; in the frame
  of the source the steady heat equation is ``-v dT/dx = kappa lap T`` and the
  surface condition is ``K dT/dy(x, 0) = Q delta_D(x)``.
* Stationary body: ``v = 0``, steady conduction.

Reference routes
----------------
1. Temperature: superposition in time of instantaneous surface line sources.  An
   energy ``E`` per unit length released at the surface of the insulated
   half-plane gives ``T = E / (2 pi K t) exp(-r**2 / (4 kappa t))`` (the full-plane
   kernel ``E / (4 pi rho c kappa t) exp(...)`` with ``rho c = K / kappa``, doubled by
   the image that makes the surface adiabatic).  Heat released a time ``tau`` ago
   has been carried by the material to ``x = -v tau``, so the steady surface
   temperature is ``integral_0^inf Q / (2 pi K tau)
   exp(-(x + v tau)**2 / (4 kappa tau)) d tau``, evaluated by adaptive quadrature.
2. Elasticity: the plane-strain Navier equations with a thermal body force are
   solved exactly for a single Fourier mode ``T = A exp(m y) cos(k x)`` by
   coefficient matching on an exponential-polynomial basis (a small linear
   system), with a traction-free surface.  The outward displacement is found to
   be ``2 alpha (1 + nu) A / (m + k)``, which is the statement
   ``w_hat(k) = 2 alpha (1 + nu) integral T_hat(k, y) exp(-|k| |y|) dy``.  In real
   space this is Maysel's formula with the Flamant (Boussinesq) stress,
   ``w(x) = (2 alpha (1 + nu) / pi) integral T(x', y') |y'| / ((x - x')**2 + y'**2) dA``
   (the kernel ``|y| / (pi (x**2 + y**2))`` has Fourier transform
   ``exp(-|k| |y|)``, also checked numerically below).
3. Moving-body distortion, two ways:

   a. Fourier route: ``T_hat(k, y) = Q exp(gamma y) / (K gamma)`` with
      ``gamma = sqrt(k**2 - i v k / kappa)``, ``Re gamma > 0``, hence
      ``w_hat = 2 delta Q / (gamma (gamma + |k|))``; inverted numerically with the
      non-integrable parts subtracted analytically.
   b. Real-space route: Maysel's formula applied to the time superposition of
      instantaneous sources.  The ``x'`` integral of a Gaussian against the
      Flamant kernel is a Voigt profile, ``pi Re wofz((x + v tau + i |y|) /
      (2 sqrt(kappa tau)))``, leaving a two-dimensional quadrature that fixes the
      rigid-body constant by itself (no free constant).

4. Stationary body: Maysel's formula in gradient form,
   ``dw/dx = (2 alpha (1 + nu) / pi) integral dT/dx' |y'| / ((x - x')**2 + y'**2) dA``
   with the steady line-source field ``T = -(Q / (pi K)) ln r + const`` (flux
   ``Q / (pi r)`` through a half-circle of length ``pi r``), integrated numerically.
5. The regularised gradient kernel is compared with ``mpmath`` at 30 digits.
"""

from __future__ import annotations

import json

import mpmath
import numpy as np
import pytest
from scipy.integrate import IntegrationWarning, quad
from scipy.special import k0, wofz

from conftest import DATA, assert_ulps
from thermocontact.physics import green_functions as kernels

pytestmark = pytest.mark.filterwarnings(
    f"error::{IntegrationWarning.__module__}.{IntegrationWarning.__name__}"
)

#: Two dimensional parameter sets ``(Q, K, kappa, v, alpha, nu)``, deliberately
#: far from unity so that a wrong prefactor cannot cancel.
PARAMS = [
    (3.1, 2.5, 0.7, 1.9, 1.3e-5, 0.3),
    (0.45, 40.0, 1.2e-5, 0.02, 2.2e-5, 0.25),
]

#: Dimensionless positions ``u = v x / (2 kappa)`` at which fields are compared.
U_POINTS = [-30.0, -4.0, -1.0, -0.2, 0.2, 0.7, 2.0, 9.0, 40.0]


def _quad_pieces(f, points, epsrel=1e-12, epsabs=0.0):
    """Integrate ``f`` over consecutive intervals given by ``points``.

    Parameters
    ----------
    f : callable
        Scalar integrand.
    points : sequence of float
        Increasing break points; the first may be ``-inf``, the last ``inf``.
    epsrel, epsabs : float, optional
        Tolerances passed to :func:`scipy.integrate.quad` for each piece.

    Returns
    -------
    float
        Sum of the piecewise integrals.
    """
    total = 0.0
    for lo, hi in zip(points[:-1], points[1:]):
        if hi > lo:
            total += quad(f, lo, hi, epsabs=epsabs, epsrel=epsrel, limit=400)[0]
    return total


def _age_breakpoints(x, v, kappa):
    """Break points in the source age ``tau`` for the moving-source integrals.

    Downstream (``x < 0``) the integrand peaks where the heated material passes
    the field point, ``tau0 = |x| / v``; the natural time scale is ``4 kappa / v**2``.

    Parameters
    ----------
    x : float
        Field point on the surface.
    v, kappa : float
        Speed and diffusivity.

    Returns
    -------
    list of float
    """
    ts = 4.0 * kappa / v**2
    s0 = v * abs(x) / (4.0 * kappa)
    if x < 0:
        return [0.0, ts * s0 / 4, ts * s0, ts * (4 * s0 + 1), np.inf]
    s1 = max(s0, 1.0)
    return [0.0, ts * s1 / 4, ts * s1, np.inf]


def instantaneous_surface_source(x, y, t, energy, K, kappa):
    """Temperature of an insulated half-plane after an instantaneous surface source.

    Parameters
    ----------
    x, y : float or ndarray
        Field point, ``y <= 0``; the source is at the origin.
    t : float
        Time since the release, ``t > 0``.
    energy : float
        Released heat per unit length.
    K, kappa : float
        Conductivity and diffusivity.

    Returns
    -------
    float or ndarray
        ``energy / (2 pi K t) exp(-(x**2 + y**2) / (4 kappa t))``.
    """
    return energy / (2 * np.pi * K * t) * np.exp(-(x * x + y * y) / (4 * kappa * t))


def moving_surface_temperature(x, Q, K, kappa, v):
    """Steady surface temperature of the moving body by superposition in time.

    Parameters
    ----------
    x : float
        Surface point (non-zero).
    Q, K, kappa, v : float
        Source strength, conductivity, diffusivity, speed.

    Returns
    -------
    float
    """

    def f(tau):
        return instantaneous_surface_source(x + v * tau, 0.0, tau, Q, K, kappa)

    return _quad_pieces(f, _age_breakpoints(x, v, kappa))


def moving_surface_temperature_gradient(x, Q, K, kappa, v):
    """``dT/dx`` on the surface of the moving body by superposition in time.

    The ``x``-derivative is taken under the integral sign (analytically on the
    Gaussian), then integrated over the source age.

    Parameters
    ----------
    x : float
        Surface point (non-zero).
    Q, K, kappa, v : float
        Source strength, conductivity, diffusivity, speed.

    Returns
    -------
    float
    """

    def f(tau):
        xi = x + v * tau
        g = instantaneous_surface_source(xi, 0.0, tau, Q, K, kappa)
        return -xi / (2 * kappa * tau) * g

    return _quad_pieces(f, _age_breakpoints(x, v, kappa))


def solve_thermoelastic_mode(k, m, A, E, nu, alpha):
    """Exact plane-strain response of a traction-free half-plane to one Fourier mode.

    The temperature is ``T = A exp(m y) cos(k x)`` in ``y < 0`` (``k, m > 0``).  With
    ``u_x = f(y) sin(k x)`` and ``u_y = g(y) cos(k x)``, the Navier equations
    ``mu lap u + (lam + mu) grad div u = beta grad T``, ``beta = (3 lam + 2 mu) alpha``,
    reduce to

    ``mu (f'' - k**2 f) - (lam + mu) k (k f + g') + beta k T_y = 0``,
    ``mu (g'' - k**2 g) + (lam + mu) (k f' + g'') - beta T_y' = 0``

    (``T_y = A exp(m y)``), with ``sigma_yy = lam (k f + g') + 2 mu g' - beta T_y = 0``
    and ``sigma_xy = mu (f' - k g) = 0`` at ``y = 0``.  ``f`` and ``g`` are expanded on
    ``y**j exp(s y)`` for ``s`` in ``{k, m}`` (degree 1, or degree 2 if ``m = k``),
    which contains all decaying solutions; the residuals are matched term by term
    and the (over-determined, consistent) system is solved by least squares.

    Parameters
    ----------
    k, m : float
        Wavenumber and decay rate of the temperature mode.
    A : float
        Temperature amplitude.
    E, nu, alpha : float
        Young's modulus, Poisson's ratio, expansion coefficient.

    Returns
    -------
    w0 : float
        Outward surface displacement amplitude ``g(0)``.
    residual : float
        Relative norm of the residual of the matched equations (round-off if solved).
    rank : int
        Rank of the system (equal to the number of unknowns if unique).
    n_unknowns : int
    """
    lam = E * nu / ((1 + nu) * (1 - 2 * nu))
    mu = E / (2 * (1 + nu))
    beta = (3 * lam + 2 * mu) * alpha
    if np.isclose(m, k):
        m = k
        basis = [(k, 0), (k, 1), (k, 2)]
    else:
        basis = [(k, 0), (k, 1), (m, 0), (m, 1)]
    nb = len(basis)
    index = {b: i for i, b in enumerate(basis)}
    # d/dy (y^j e^{sy}) = j y^{j-1} e^{sy} + s y^j e^{sy}
    D = np.zeros((nb, nb))
    for (s, j), i in index.items():
        D[i, i] += s
        if j > 0:
            D[index[(s, j - 1)], i] += j
    P = np.eye(nb)
    Z = np.zeros_like(P)
    F = np.hstack([P, Z])  # coefficients of f as a linear map of the unknowns
    G = np.hstack([Z, P])  # coefficients of g
    t_vec = np.zeros(nb)
    t_vec[index[(m, 0)]] = A
    eq_x = mu * (D @ D @ F - k * k * F) - (lam + mu) * k * (k * F + D @ G)
    rhs_x = -beta * k * t_vec
    eq_y = mu * (D @ D @ G - k * k * G) + (lam + mu) * (k * D @ F + D @ D @ G)
    rhs_y = beta * (D @ t_vec)
    at0 = np.array([1.0 if j == 0 else 0.0 for (_, j) in basis])  # value at y = 0
    bc_n = at0 @ (lam * (k * F + D @ G) + 2 * mu * (D @ G))
    bc_t = at0 @ (mu * (D @ F - k * G))
    M = np.vstack([eq_x, eq_y, bc_n, bc_t])
    rhs = np.concatenate([rhs_x, rhs_y, [beta * (at0 @ t_vec), 0.0]])
    coef, _, rank, _ = np.linalg.lstsq(M, rhs, rcond=None)
    residual = np.linalg.norm(M @ coef - rhs) / max(np.linalg.norm(rhs), 1e-300)
    return float(at0 @ (G @ coef)), float(residual), int(rank), M.shape[1]


def _inverse_fourier_real(R, x, a, scale):
    """``(1/pi) integral_0^inf Re[R(k) exp(i k x)] dk`` for ``x != 0``.

    This is the inverse transform ``(1/2pi) integral R(k) exp(i k x) dk`` of a
    Hermitian transform (``R(-k) = conj R(k)``).  The integral is done in the
    scaled wavenumber ``p = k / a`` on ``R / scale`` so that absolute tolerances
    are meaningful.  On ``[0, 4]`` the substitution ``p = t**2`` removes
    ``p**(-1/2)`` and ``p**(1/2)`` behaviour at the origin; the tail uses QAWF
    (Fourier-weighted quadrature).

    Parameters
    ----------
    R : callable
        Complex transform, integrable on ``(0, inf)``.
    x : float
        Non-zero position.
    a : float
        Wavenumber scale.
    scale : float
        Magnitude of ``R`` near ``k ~ a`` times ``a`` (the size of the result).

    Returns
    -------
    float
    """
    X = a * x
    aX = abs(X)
    sg = np.sign(X)

    def r(p):
        return R(a * p) * (a / scale)

    def head(t):
        p = t * t
        rp = r(p)
        return 2 * t * (rp.real * np.cos(p * X) - rp.imag * np.sin(p * X))

    h = quad(head, 0.0, 2.0, epsabs=1e-13, epsrel=1e-10, limit=1000)[0]
    tc = quad(lambda p: r(p).real, 4.0, np.inf, weight="cos", wvar=aX, epsabs=1e-13, limlst=200)[0]
    ts = quad(lambda p: r(p).imag, 4.0, np.inf, weight="sin", wvar=aX, epsabs=1e-13, limlst=200)[0]
    return scale * (h + tc - sg * ts) / np.pi


def _gamma(k, kappa, v):
    """``sqrt(k**2 - i v k / kappa)`` with positive real part (``k > 0``)."""
    return np.sqrt(k * k - 1j * v * k / kappa)


def fourier_surface_temperature(x, Q, K, kappa, v):
    """Surface temperature from ``T_hat(k, 0) = Q / (K gamma)``.

    ``Q / (K sqrt(k**2 + a**2))`` (inverse ``Q K0(a |x|) / (pi K)``) is subtracted
    to make the remainder decay like ``k**-2``.

    Returns
    -------
    float
    """
    a = v / (2 * kappa)

    def R(k):
        return Q / (K * _gamma(k, kappa, v)) - Q / (K * np.sqrt(k * k + a * a))

    return Q * k0(a * abs(x)) / (np.pi * K) + _inverse_fourier_real(R, x, a, Q / K)


def fourier_slope(x, Q, K, kappa, v, alpha, nu):
    """Outward slope of the moving body from ``i k w_hat``.

    ``w_hat = 2 delta Q / (gamma (gamma + |k|))``; its large-``k`` part
    ``i delta Q k / (k**2 + a**2)`` (inverse ``-delta Q sgn(x) exp(-a |x|) / 2``) is
    subtracted.

    Returns
    -------
    float
    """
    delta = alpha * (1 + nu) / K
    a = v / (2 * kappa)

    def R(k):
        g = _gamma(k, kappa, v)
        return 1j * k * 2 * delta * Q / (g * (g + k)) - 1j * delta * Q * k / (k * k + a * a)

    return -delta * Q * np.sign(x) * np.exp(-a * abs(x)) / 2 + _inverse_fourier_real(
        R, x, a, delta * Q
    )


def fourier_displacement(x, Q, K, kappa, v, alpha, nu):
    """Outward displacement of the moving body from ``w_hat``, far upstream value 0.

    Near ``k = 0``, ``w_hat ~ 2 delta Q / gamma**2 = i (2 delta kappa Q / v) / k``.
    The principal-value part ``i B b**2 / (k (k**2 + b**2))``, ``B = 2 delta kappa Q / v``,
    whose inverse is ``-B sgn(x) (1 - exp(-b |x|)) / 2``, is subtracted.  The
    principal-value inverse tends to ``-B/2`` far upstream (the regular remainder
    vanishes there by the Riemann-Lebesgue lemma), so ``B/2`` is added to make the
    undisturbed far-upstream surface ``w = 0``.

    Returns
    -------
    float
    """
    delta = alpha * (1 + nu) / K
    b = v / (2 * kappa)
    B = 2 * delta * kappa * Q / v

    def R(k):
        g = _gamma(k, kappa, v)
        return 2 * delta * Q / (g * (g + k)) - 1j * B * b * b / (k * (k * k + b * b))

    pv = -B * np.sign(x) * (1 - np.exp(-b * abs(x))) / 2 + _inverse_fourier_real(R, x, b, B)
    return pv + B / 2


def maysel_moving_distortion(x, Q, K, kappa, v, alpha, nu, derivative=False):
    """Outward displacement (or slope) of the moving body from Maysel's formula.

    Substituting the time superposition of route 1 into
    ``w = (2 alpha (1 + nu) / pi) integral T |y'| / ((x - x')**2 + y'**2) dA``, doing
    the ``x'`` integral as a Voigt profile and putting ``y' = -2 sqrt(kappa tau) eta``:

    ``w(x) = (2 alpha (1 + nu) Q sqrt(kappa) / (pi K)) integral_0^inf tau**-0.5 dtau
    integral_0^inf exp(-eta**2) Re wofz(z) d eta``,
    ``z = (x + v tau) / (2 sqrt(kappa tau)) + i eta``.

    The slope uses ``wofz'(z) = -2 z wofz(z) + 2 i / sqrt(pi)`` and
    ``dz/dx = 1 / (2 sqrt(kappa tau))``.

    Parameters
    ----------
    x : float
        Surface point (non-zero).
    Q, K, kappa, v, alpha, nu : float
        Source, material and speed parameters.
    derivative : bool, optional
        Return ``dw/dx`` instead of ``w``.

    Returns
    -------
    float
    """

    def inner(tau):
        a = (x + v * tau) / (2 * np.sqrt(kappa * tau))
        if derivative:

            def f(eta):
                z = a + 1j * eta
                dw = (-2 * z * wofz(z) + 2j / np.sqrt(np.pi)) / (2 * np.sqrt(kappa * tau))
                return np.exp(-eta * eta) * dw.real

        else:

            def f(eta):
                return np.exp(-eta * eta) * wofz(a + 1j * eta).real

        return quad(f, 0.0, np.inf, epsabs=0.0, epsrel=1e-11, limit=200)[0] / np.sqrt(tau)

    pref = 2 * alpha * (1 + nu) * Q * np.sqrt(kappa) / (np.pi * K)
    return pref * _quad_pieces(inner, _age_breakpoints(x, v, kappa), epsrel=1e-10)


def maysel_stationary_slope(x, Q, K, alpha, nu):
    """Outward slope of the stationary body from Maysel's formula in gradient form.

    ``dw/dx = (2 alpha (1 + nu) / pi) integral_{y<0} integral dT/dx'(x', y)
    |y| / ((x - x')**2 + y**2) dx' dy`` with ``dT/dx' = -(Q / (pi K)) x' / (x'**2 + y**2)``.

    With ``x' = |y| t`` and ``xi = x / |y|`` the inner integral is
    ``-(Q / (pi K |y|)) integral t / ((t**2 + 1) ((xi - t)**2 + 1)) dt``; folding
    ``t -> -t`` onto ``t > 0`` turns it into the cancellation-free
    ``integral_0^inf 4 xi t**2 / ((t**2 + 1) ((xi - t)**2 + 1) ((xi + t)**2 + 1)) dt``,
    which stays accurate when ``|y| >> |x|`` (where the unfolded integrand is
    nearly odd).

    Parameters
    ----------
    x : float
        Surface point (non-zero).
    Q, K, alpha, nu : float

    Returns
    -------
    float
    """
    ax = abs(x)

    def inner(y):
        ay = abs(y)
        xi = x / ay

        def f(t):
            return 4 * xi * t * t / ((t * t + 1) * ((xi - t) ** 2 + 1) * ((xi + t) ** 2 + 1))

        lo, hi = sorted((1.0, abs(xi)))
        return -(Q / (np.pi * K * ay)) * _quad_pieces(f, [0.0, lo, hi, 10 * hi, np.inf])

    outer = _quad_pieces(inner, [-np.inf, -10 * ax, -ax, 0.0], epsrel=1e-11)
    return 2 * alpha * (1 + nu) / np.pi * outer


# ---------------------------------------------------------------------------
# Checks of the reference building blocks
# ---------------------------------------------------------------------------


def test_instantaneous_source_solves_heat_problem():
    """The instantaneous surface line source satisfies the half-plane problem.

    Checks the heat equation ``T_t = kappa lap T`` by central differences at an
    interior point, the adiabatic surface (``dT/dy = 0`` at ``y = 0``) and the energy
    balance ``(K / kappa) integral_{y<0} T dA = E``.  Tolerances: rtol 1e-6 for the
    differences (step 1e-4 gives truncation ~1e-8 and round-off ~1e-8 relative),
    rtol 1e-10 for the quadrature of the energy.
    """
    E, K, kappa = 2.3, 1.7, 0.4
    x, y, t = 0.35, -0.6, 0.8
    h = 1e-4

    def T(xx, yy, tt):
        return instantaneous_surface_source(xx, yy, tt, E, K, kappa)

    dt = (T(x, y, t + h) - T(x, y, t - h)) / (2 * h)
    lap = (
        T(x + h, y, t) + T(x - h, y, t) + T(x, y + h, t) + T(x, y - h, t) - 4 * T(x, y, t)
    ) / h**2
    assert dt == pytest.approx(kappa * lap, rel=1e-6)
    assert (T(x, h, t) - T(x, -h, t)) / (2 * h) == pytest.approx(0.0, abs=1e-14)
    energy = quad(
        lambda yy: quad(lambda xx: T(xx, yy, t), -np.inf, np.inf, epsrel=1e-12)[0],
        -np.inf,
        0.0,
        epsrel=1e-12,
    )[0]
    assert K / kappa * energy == pytest.approx(E, rel=1e-10)


@pytest.mark.parametrize("k, m", [(1.0, 1.0), (2.5, 2.5), (1.0, 0.5), (1.0, 3.0), (0.7, 2.0)])
@pytest.mark.parametrize("nu", [0.0, 0.3, 0.45])
def test_thermoelastic_mode_displacement(k, m, nu):
    """A Fourier temperature mode produces ``w = 2 alpha (1 + nu) A / (m + k)``.

    Independent elasticity: the Navier equations are solved exactly for
    ``T = A exp(m y) cos(k x)`` (see :func:`solve_thermoelastic_mode`).  For a
    harmonic mode (``m = k``) this is ``(1 + nu) alpha A / k``; for general ``m``
    it is the Laplace transform of ``exp(k y)``, i.e. the Maysel/Fourier kernel
    ``w_hat = 2 alpha (1 + nu) integral T_hat exp(-|k| |y|) dy``.  Positive heating
    gives outward (``+y``) displacement.  The answer must not depend on ``E``.
    rtol 1e-12: the solution is exact up to round-off in a well-conditioned
    linear system of at most 10 x 8.
    """
    A, alpha = 1.7, 1.3e-1
    expected = 2 * alpha * (1 + nu) * A / (m + k)
    for E in (2.0, 7.0e3):
        w0, residual, rank, n = solve_thermoelastic_mode(k, m, A, E, nu, alpha)
        assert rank == n
        assert residual < 1e-12
        assert w0 == pytest.approx(expected, rel=1e-12)
    if m == k:
        assert w0 == pytest.approx((1 + nu) * alpha * A / k, rel=1e-12)


@pytest.mark.parametrize("k, y", [(0.3, -0.5), (2.0, -1.3), (5.0, -0.05)])
def test_flamant_kernel_transform(k, y):
    """The real-space Maysel kernel ``|y| / (pi (x**2 + y**2))`` transforms to ``exp(-|k||y|)``.

    This ties the real-space form used in :func:`maysel_moving_distortion` and
    :func:`maysel_stationary_slope` to the Fourier-mode elasticity result.
    rtol 1e-9: QAWF quadrature of a smooth, algebraically decaying integrand.
    """
    ay = abs(y)
    val = 2 * quad(lambda x: ay / (np.pi * (x * x + y * y)), 0, np.inf, weight="cos", wvar=k)[0]
    assert val == pytest.approx(np.exp(-k * ay), rel=1e-9)


@pytest.mark.parametrize("x, y, tau", [(0.4, -0.3, 0.2), (-2.0, -1.5, 3.0), (1.0, -0.02, 0.5)])
def test_voigt_identity(x, y, tau):
    """Gaussian times Flamant kernel integrates to ``pi Re wofz``.

    ``integral exp(-(x' + v tau)**2 / (4 kappa tau)) |y| / ((x - x')**2 + y**2) dx'
    = pi Re wofz((x + v tau + i |y|) / (2 sqrt(kappa tau)))``, the step used in the
    real-space route.  rtol 1e-10: direct adaptive quadrature.
    """
    kappa, v = 0.7, 1.9
    c = -v * tau

    def f(xp):
        return np.exp(-((xp - c) ** 2) / (4 * kappa * tau)) * abs(y) / ((x - xp) ** 2 + y * y)

    direct = _quad_pieces(f, [-np.inf, min(c, x) - 5, min(c, x), max(c, x), max(c, x) + 5, np.inf])
    voigt = np.pi * wofz((x + v * tau + 1j * abs(y)) / (2 * np.sqrt(kappa * tau))).real
    assert direct == pytest.approx(voigt, rel=1e-10)


# ---------------------------------------------------------------------------
# Claims (a) and (b): moving-body temperature and its gradient
# ---------------------------------------------------------------------------


@pytest.mark.parametrize("params", PARAMS)
@pytest.mark.parametrize("u", U_POINTS)
def test_moving_surface_temperature(params, u):
    """Claim (a): ``T(x) = Q / (pi K) * cylinder_temperature(v x / (2 kappa))``.

    Reference: time superposition of instantaneous sources (route 1), in
    dimensional variables.  rtol 1e-10: the quadrature is run at epsrel 1e-12 on a
    smooth integrand split at its peak; the observed agreement is ~1e-14.
    """
    Q, K, kappa, v, _, _ = params
    x = 2 * kappa * u / v
    ref = moving_surface_temperature(x, Q, K, kappa, v)
    assert Q / (np.pi * K) * kernels.cylinder_temperature(u) == pytest.approx(ref, rel=1e-10)


@pytest.mark.parametrize("params", PARAMS)
@pytest.mark.parametrize("u", U_POINTS)
def test_moving_surface_temperature_gradient(params, u):
    """Claim (b): ``dT/dx = -(v / (2 pi kappa K)) Q cylinder_temperature_gradient(u)``.

    Reference: ``x``-derivative of the time superposition (route 1).  rtol 1e-10
    for the same reason as claim (a).
    """
    Q, K, kappa, v, _, _ = params
    x = 2 * kappa * u / v
    ref = moving_surface_temperature_gradient(x, Q, K, kappa, v)
    got = -(v / (2 * np.pi * kappa * K)) * Q * kernels.cylinder_temperature_gradient(u)
    assert got == pytest.approx(ref, rel=1e-10)


def test_hot_wake_is_downstream():
    """The wake (``u < 0``, ``x < 0``) is hotter than the mirror upstream point.

    Reference: route 1 at ``u = -/+ 1``.  Exact inequality on the reference, then
    the kernel must order the same way.
    """
    Q, K, kappa, v, _, _ = PARAMS[0]
    x = 2 * kappa / v
    assert moving_surface_temperature(-x, Q, K, kappa, v) > moving_surface_temperature(x, Q, K, kappa, v)
    assert kernels.cylinder_temperature(-1.0) > kernels.cylinder_temperature(1.0)


# ---------------------------------------------------------------------------
# Claim (c): moving-body distortion
# ---------------------------------------------------------------------------


@pytest.mark.parametrize("params", PARAMS)
@pytest.mark.parametrize("u", U_POINTS)
def test_moving_distortion_fourier(params, u):
    """Claim (c) by the Fourier route (route 3a).

    ``w = (2 delta kappa Q / v) cylinder_displacement(u)`` and
    ``dw/dx = -delta Q cylinder_slope(u)``; the Fourier surface temperature is also
    checked against claim (a) to confirm the transform used.  Tolerance: rtol
    1e-8 with an absolute floor of 1e-10 of the natural scale (``2 delta kappa Q / v``
    for ``w``, ``delta Q`` for the slope, ``Q / K`` for ``T``), because the slope is
    exactly zero downstream; the subtracted quadratures reach ~1e-15 in practice.
    """
    Q, K, kappa, v, alpha, nu = params
    delta = alpha * (1 + nu) / K
    x = 2 * kappa * u / v
    w_scale = 2 * delta * kappa * Q / v
    s_scale = delta * Q

    T = fourier_surface_temperature(x, Q, K, kappa, v)
    assert Q / (np.pi * K) * kernels.cylinder_temperature(u) == pytest.approx(
        T, rel=1e-8, abs=1e-10 * Q / K
    )
    w = fourier_displacement(x, Q, K, kappa, v, alpha, nu)
    assert w_scale * kernels.cylinder_displacement(u) == pytest.approx(w, rel=1e-8, abs=1e-10 * w_scale)
    s = fourier_slope(x, Q, K, kappa, v, alpha, nu)
    assert -s_scale * kernels.cylinder_slope(u) == pytest.approx(s, rel=1e-8, abs=1e-10 * s_scale)


#: Maysel's route's nested quadratures at every parameter set and position, stored
#: (``tests/data/make_maysel_references.py``: about ten seconds).
MAYSEL = DATA / "maysel_references.json"


@pytest.mark.parametrize("index", range(10))
def test_moving_distortion_maysel(index):
    """Claim (c) by the real-space route (route 3b): Maysel plus time superposition.

    This route has no free rigid-body constant: it gives ``w -> 0`` far upstream
    and ``w = 2 delta kappa Q / v`` downstream by itself.  Tolerance: rtol 1e-8 with
    an absolute floor of 1e-10 of the scale (the downstream slope is exactly
    zero); the nested quadratures run at epsrel 1e-10/1e-11, stored.
    """
    case = json.loads(MAYSEL.read_text())["cases"][index]
    params, u = tuple(case["params"]), case["u"]
    assert params in PARAMS
    Q, K, kappa, v, alpha, nu = params
    delta = alpha * (1 + nu) / K
    w_scale = 2 * delta * kappa * Q / v
    s_scale = delta * Q
    w, s = case["w"], case["slope"]
    assert w_scale * kernels.cylinder_displacement(u) == pytest.approx(w, rel=1e-8, abs=1e-10 * w_scale)
    assert -s_scale * kernels.cylinder_slope(u) == pytest.approx(s, rel=1e-8, abs=1e-10 * s_scale)


def test_maysel_reference_of_one_case_again():
    """The stored quadratures of one case, computed again: the route gives what was
    stored (to its own tolerance, 1e-9 relative)."""
    cases = json.loads(MAYSEL.read_text())["cases"]
    assert len(cases) == 10 == 5 * len(PARAMS)  # every case stored is tested above
    case = cases[1]
    Q, K, kappa, v, alpha, nu = params = tuple(case["params"])
    x = 2 * kappa * case["u"] / v
    assert maysel_moving_distortion(x, *params) == pytest.approx(case["w"], rel=1e-9)
    assert maysel_moving_distortion(x, *params, derivative=True) == pytest.approx(
        case["slope"], rel=1e-9, abs=1e-12 * alpha * (1 + nu) / K * Q)


# ---------------------------------------------------------------------------
# Claim (d): stationary body
# ---------------------------------------------------------------------------


@pytest.mark.parametrize("x", [-3.0, -0.4, 0.1, 2.0, 25.0])
def test_stationary_slope(x):
    """Claim (d): ``dw/dx = -delta Q half_plane_slope(x) = -delta Q sgn(x) / 2``.

    Reference: Maysel's formula in gradient form with the steady line-source
    temperature (route 4), by nested quadrature.  The gradient form fixes the
    otherwise free rigid rotation to the antisymmetric one, matching the kernel;
    the physical content is the jump ``-delta Q`` at the source (a bulge toward
    the other body for ``Q > 0``).  rtol 1e-9: nested quadrature at epsrel
    1e-11/1e-12 of integrands split at their peaks.
    """
    Q, K, alpha, nu = 3.1, 2.5, 1.3e-5, 0.3
    delta = alpha * (1 + nu) / K
    ref = maysel_stationary_slope(x, Q, K, alpha, nu)
    assert -delta * Q * kernels.half_plane_slope(x) == pytest.approx(ref, rel=1e-9)


# ---------------------------------------------------------------------------
# Claim (e): regularised gradient kernel
# ---------------------------------------------------------------------------


def _regular_reference(u, c):
    """``c M(c u) - 1/u`` at 30 significant digits with mpmath."""
    with mpmath.workdps(30):
        uu = mpmath.mpf(u)
        cc = mpmath.mpf(c)
        z = cc * uu
        a = abs(z)
        m = mpmath.exp(-z) * (mpmath.besselk(0, a) + mpmath.sign(z) * mpmath.besselk(1, a))
        return cc * m - 1 / uu


_CU = np.concatenate(
    [
        np.geomspace(1e-14, 9e-4, 14),
        [9.99e-4, 1e-3, 1.001e-3, 1.8e-3, 5e-3],
        np.geomspace(1e-2, 60.0, 16),
        [0.25, 0.28, 0.2831818858845216, 0.29, 0.35],
    ]
)

#: Zero of ``M(x) - 1/x`` (upstream, ``x > 0``), from mpmath.findroot.
_ROOT = 0.2831818858845216


@pytest.mark.parametrize("c", [0.01, 1.0, 150.0])
def test_regular_gradient_kernel_against_mpmath(c):
    """Claim (e): ``cylinder_temperature_gradient_regular(u, c) = c M(c u) - 1/u``.

    Reference: mpmath at 30 digits, for ``|c u|`` from 1e-14 (series branch) across
    the switch at 1e-3 up to 60, both signs.  Tolerance: rtol 1e-13 everywhere
    except in ``0.2 < c u < 0.4``.  There ``c M(c u) - 1/u`` passes through zero (at
    ``c u = 0.28318...``) as the difference of two ``O(1/u)`` terms, so no
    double-precision evaluation of that difference can be relatively accurate;
    the error is bounded there (and everywhere) by ``1e-14 |1/u|``.
    """
    cu = np.concatenate([-_CU, _CU])
    u = cu / c
    got = kernels.cylinder_temperature_gradient_regular(u, c)
    ref = np.array([float(_regular_reference(ui, c)) for ui in u])
    near_zero = (cu > 0.2) & (cu < 0.4)
    np.testing.assert_allclose(got[~near_zero], ref[~near_zero], rtol=1e-13, atol=0)
    assert np.all(np.abs(got - ref) <= 1e-14 * np.abs(1 / u))
    assert abs(float(_regular_reference(_ROOT, 1.0))) < 1e-15


def test_far_upstream_gradient_kernel_is_minus_one_over_u_to_an_ulp():
    """Beyond c u = 22 the regular gradient kernel skips its Bessel functions: the
    values equal c M(c u) - 1/u formed in full, on both sides of the threshold and for
    scales from 1e-3 to 1e4, to an ulp of each (x M(x) stays below 1e-18 there, far
    under half an ulp of 1/u; an ulp, not the last bit, for the vector units' exp on
    the masked points: conftest.assert_ulps)."""
    from thermocontact.physics.green_functions import (UPSTREAM_NEGLIGIBLE,
                                                       cylinder_temperature_gradient)

    x = np.linspace(UPSTREAM_NEGLIGIBLE, 400.0, 5000)
    assert np.max(x * cylinder_temperature_gradient(x)) < 1e-18
    for c in np.geomspace(1e-3, 1e4, 30):
        u = np.concatenate([np.linspace(0.5, 2.0, 301) * UPSTREAM_NEGLIGIBLE / c,
                            np.linspace(-3.0, 3.0, 301)])
        u = u[np.abs(c * u) >= 1e-3]
        full = c * cylinder_temperature_gradient(c * u) - 1.0 / u
        assert_ulps(kernels.cylinder_temperature_gradient_regular(u, c), full, ulps=1,
                    scale="each")


def test_kernel_values_do_not_depend_on_the_other_points():
    """The kernels take shortcuts on whole arrays (no mask where every point is
    upstream, or every drop is wide): a point's value is the same in an array of its
    own kind, in a mixed one and alone, for both signs of a moving body's scale, to two
    ulps of each value (the same formulas; the vector units' last bits depend on the
    CPU and the array: conftest.assert_ulps)."""
    from thermocontact.physics.green_functions import cylinder_displacement_drop

    rng = np.random.default_rng(3)
    up = rng.uniform(1e-6, 30.0, 400)
    mixed = np.concatenate([up, -up[:100], [0.0]])
    h_wide, h_any = rng.uniform(2e-3, 5.0, 400), np.geomspace(1e-9, 5.0, 400)

    def alone(f, *arrays):
        return np.array([f(*(np.array([a[i]]) for a in arrays))[0]
                         for i in range(arrays[0].size)])
    for f in (kernels.cylinder_displacement, lambda u: kernels.moving_slope(u, 7.0),
              lambda u: kernels.moving_slope(u, -7.0),
              lambda u: kernels.cylinder_temperature_gradient_regular(u, 7.0)):
        values = f(mixed[mixed != 0.0])
        assert_ulps(values[:up.size], f(up), ulps=2, scale="each")
        assert_ulps(values, alone(f, mixed[mixed != 0.0]), ulps=2, scale="each")
    assert_ulps(cylinder_displacement_drop(up, h_wide),
                alone(cylinder_displacement_drop, up, h_wide), ulps=2, scale="each")
    both = cylinder_displacement_drop(up, np.where(np.arange(400) < 200, h_wide, h_any))
    assert_ulps(both[:200], cylinder_displacement_drop(up[:200], h_wide[:200]), ulps=2,
                scale="each")
    assert_ulps(both, alone(cylinder_displacement_drop, up,
                            np.where(np.arange(400) < 200, h_wide, h_any)), ulps=2, scale="each")


def test_kernels_keep_their_types_and_their_sign_of_the_scale():
    """A number gives a 0-d array as before, whatever path it takes; a moving slope's
    sign is that of its scale, 0 and NaN included (np.sign)."""
    from thermocontact.physics.green_functions import cylinder_displacement_drop

    for u in (2.0, -2.0):
        assert isinstance(kernels.cylinder_displacement(u), np.ndarray)
        assert isinstance(cylinder_displacement_drop(abs(u), 0.5), np.ndarray)
    u = np.array([0.5, 1.0])
    assert np.array_equal(kernels.moving_slope(u, 0.0), np.zeros(2))
    assert np.isnan(kernels.moving_slope(u, np.nan)).all()
    assert np.array_equal(kernels.moving_slope(u, -2.0), -kernels.cylinder_slope(-2.0 * u))
