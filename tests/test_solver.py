"""The general solver: exact limits, balance laws, linearity, convergence in n."""

import numpy as np
import pytest
from scipy.integrate import quad

from thermocontact import InputError, SolveError, solve
from thermocontact.limits import hertz_pressure
from thermocontact.quadrature import u_series_coefficients, u_series_value

CASES = [
    dict(pe=5.0, fhpe=0.2, K2_over_K1=10.0, k2_over_k1=1.0),
    dict(pe=1.0, fhpe=0.3, K2_over_K1=3.0, k2_over_k1=0.5, delta1_over_delta2=2.0),
    dict(pe=2.0, fhpe=0.1, K2_over_K1=0.5, k2_over_k1=1.0, delta1_over_delta2=0.0),
]


@pytest.mark.parametrize("pe,K,n", [(5, 10, 32), (0.1, 1, 64), (10, 100, 128)])
@pytest.mark.parametrize("lam", [-1.0, 0.0, 2.5])
def test_no_coupling_is_hertz(pe, K, n, lam):
    """fHPe = 0: P_H/P = 1, sigma = 0 and the elliptical pressure, to 1e-12, for any lam.

    With no thermal coupling the heat problem decouples from the contact problem; the
    collocation is exact for the constant bounded factor of the Hertz pressure.
    """
    sol = solve(pe, 0.0, K, lam=lam, n=n)
    assert abs(sol.load_ratio - 1.0) < 1e-12
    assert abs(sol.sigma_over_delta) < 1e-12
    assert np.max(np.abs(sol.pressure - hertz_pressure(sol.s))) < 1e-12
    assert abs(sol.lam - lam) < 1e-12
    assert sol.valid


@pytest.mark.parametrize("case", CASES)
@pytest.mark.parametrize("lam", [-1.0, 0.3, 2.0])
def test_heat_balance(case, lam):
    """lam recovered from the heat-flux distribution by adaptive quadrature equals the
    imposed lam (abs. 1e-10), and q1 + q2 equals the frictional heat f p v (1e-12)."""
    sol = solve(lam=lam, n=48, **case)
    b = np.polynomial.chebyshev.chebfit(sol.flux_s, sol.flux_difference * np.sqrt(1 - sol.flux_s**2), sol.n - 1)
    # integral of q = integral (q sqrt(1-s^2)) / sqrt(1-s^2): Gauss-Jacobi weight by quad.
    val, _ = quad(lambda s: np.polynomial.chebyshev.chebval(s, b), -1, 1, weight="alg", wvar=(-0.5, -0.5), limit=200)
    assert abs(val - lam) < 1e-10
    p = sol.pressure_at(sol.flux_s)
    assert np.max(np.abs(sol.flux_cylinder + sol.flux_half_plane - p)) < 1e-12


@pytest.mark.parametrize("case", CASES)
def test_load_equilibrium(case):
    """The pressure carries the load: its integral by adaptive Gauss-Jacobi quadrature of
    p/sqrt(1-s^2) with weight sqrt(1-s^2) is 1 (abs. 1e-12)."""
    sol = solve(lam=-1.0, n=48, **case)
    a = u_series_coefficients(sol.phi)
    val, _ = quad(lambda s: u_series_value(a, s), -1, 1,
                  weight="alg", wvar=(0.5, 0.5), limit=200)
    assert abs(val - 1.0) < 1e-12


@pytest.mark.parametrize("case", CASES)
def test_lam_and_sigma_formulations_agree(case):
    """Solving for sigma at a given lam, then for lam at that sigma, returns the same
    lam and P_H/P (rel. 1e-10): the two closures are the same linear system."""
    a = solve(lam=0.4, n=40, **case)
    b = solve(sigma_over_delta=a.sigma_over_delta, n=40, **case)
    assert abs(b.lam - 0.4) < 1e-10
    assert abs(b.load_ratio / a.load_ratio - 1) < 1e-10


@pytest.mark.parametrize("case", CASES)
def test_affine_in_lam(case):
    """L and L*sigma are affine in lam (the equations are linear): the midpoint
    solution is the mean of the end solutions (abs. 1e-12)."""
    s0, s1, sm = (solve(lam=x, n=40, **case) for x in (-1.0, 3.0, 1.0))
    assert abs(sm.load_ratio - 0.5 * (s0.load_ratio + s1.load_ratio)) < 1e-12
    lsig = [s.load_ratio * s.sigma_over_delta for s in (s0, s1, sm)]
    assert abs(lsig[2] - 0.5 * (lsig[0] + lsig[1])) < 1e-12


def test_unreachable_lam_is_refused():
    """The lam at which P_H/P vanishes is reached by no finite sigma: SolveError."""
    case = CASES[0]
    a, b = solve(lam=0.0, n=32, **case), solve(lam=1.0, n=32, **case)
    lam_star = -a.load_ratio / (b.load_ratio - a.load_ratio)
    with pytest.raises(SolveError, match="no finite sigma_over_delta"):
        solve(lam=lam_star, n=32, **case)


def test_sigma_without_coupling_is_refused():
    with pytest.raises(InputError, match="fhpe = 0"):
        solve(5, 0.0, 10, sigma_over_delta=0.2)


def test_nearly_uncoupled_sigma_is_ill_conditioned():
    """fHPe = 1e-12 with sigma imposed is numerically singular: SolveError, not noise."""
    with pytest.raises(SolveError, match="ill-conditioned"):
        solve(5, 1e-12, 10, sigma_over_delta=0.2, n=32)


def test_paper_scheme_converges_at_first_order():
    """The paper's collocation converges at observed order ~1 in n for P_H/P
    (Pe = 5, K2/K1 = 10, k2/k1 = 1, fHPe = 0.2): successive differences between
    n = 64, 128, 256, 512 halve (measured orders 0.92 and 0.97, rising toward 1), as
    the step kernels sampled at the nodes predict."""
    L = [solve(5, 0.2, 10, k2_over_k1=1, lam=-1, n=n).load_ratio for n in (64, 128, 256, 512)]
    d = np.abs(np.diff(L))
    orders = np.log2(d[:-1] / d[1:])
    assert np.all((orders > 0.85) & (orders < 1.15)), orders
    # Richardson estimate of the n = 512 error is below 1e-4.
    assert d[-1] < 1e-4


def test_convergence_check_reports_change():
    """check_convergence reports |L(2n) - L(n)| equal to two separate solves."""
    a = solve(5, 0.2, 10, k2_over_k1=1, lam=-1, n=32, check_convergence=True)
    b = solve(5, 0.2, 10, k2_over_k1=1, lam=-1, n=64)
    assert a.load_ratio_change == pytest.approx(abs(b.load_ratio - a.load_ratio), rel=1e-12)


def test_approaches_barber_insulated_cylinder_at_first_order():
    """lam = -1, fHPe = 0.2, k2/k1 = 1: as K2/K1 grows the general solver approaches
    Barber's insulated, non-distorting cylinder (independent Galerkin solution in
    thermocontact.limits, accurate to 1e-15) at first order in K1/K2: the error
    falls by 10.0 and 10.1 per decade of K2/K1 = 10, 100, 1000 (asserted 9.5-10.6),
    with (K2/K1)(P_H/P - Barber) ~ 0.089.  The heat left in the cylinder is
    q1 = p/(1 + K2/K1) + q'/2 with q' = O(K1/K2) (derivation section 5)."""
    from thermocontact.limits import barber_insulated

    LB = barber_insulated(0.2).load_ratio
    err = np.array([solve(5, 0.2, rho, k2_over_k1=1, lam=-1, n=512).load_ratio - LB
                    for rho in (10, 100, 1000)])
    ratios = err[:-1] / err[1:]
    assert np.all((ratios > 9.5) & (ratios < 10.6)), ratios
    assert np.all(np.abs(err * np.array([10, 100, 1000]) - 0.089) < 0.002)
