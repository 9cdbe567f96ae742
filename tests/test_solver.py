"""The general solver: exact limits, balance laws, linearity, convergence in n."""

from functools import lru_cache

import numpy as np
import pytest
from scipy.integrate import quad

from thermocontact import METHODS, InputError, SolveError, solve
from thermocontact.numerics.moment_engine import stretch, stretch_derivative


def integral_over_contact(f, singular=False):
    """integral_{-1}^{1} g(s) ds by adaptive quadrature in tau, s = cos T(tau).

    An exact change of variables for any g; it turns the edge behaviour of both
    representations (sqrt, 1/sqrt and the graded cosine series) into smooth
    integrands.  ``f`` is g itself, or with ``singular`` g sqrt(1 - s^2), which stays
    finite at the edges (a heat flux).
    """
    def g(tau):
        t = stretch(np.array([tau]))[0]
        w = stretch_derivative(tau)
        return f(np.cos(t)) * w if singular else f(np.cos(t)) * np.sin(t) * w
    return quad(g, 0.0, np.pi, limit=400, epsabs=1e-14, epsrel=1e-13)[0]


CASES = [
    dict(pe=5.0, fhpe=0.2, K2_over_K1=10.0, k2_over_k1=1.0),
    dict(pe=1.0, fhpe=0.3, K2_over_K1=3.0, k2_over_k1=0.5, delta1_over_delta2=2.0),
    dict(pe=2.0, fhpe=0.1, K2_over_K1=0.5, k2_over_k1=1.0, delta1_over_delta2=0.0),
]


@pytest.mark.parametrize("method", sorted(METHODS))
@pytest.mark.parametrize("pe,K,n", [(5, 10, 32), (0.1, 1, 64), (10, 100, 128)])
@pytest.mark.parametrize("lam", [-1.0, 0.0, 2.5])
def test_no_coupling_is_hertz(pe, K, n, lam, method):
    """fHPe = 0: P_H/P = 1, sigma = 0 and the elliptical pressure, to 1e-12, for any lam.

    With no thermal coupling the heat problem decouples from the contact problem;
    every representation holds the constant bounded factor phi = 2/pi of the Hertz
    pressure exactly.  The pressure (2/pi) sqrt(1 - s^2) is compared through the
    rules' edge factors: next to an edge the graded nodes round to +-1 in s.
    """
    sol = solve(pe, 0.0, K, lam=lam, n=n, method=method)
    assert abs(sol.load_ratio - 1.0) < 1e-12
    assert abs(sol.sigma_over_delta) < 1e-12
    ef = sol.representation.pressure_rule.edge_factor
    assert np.max(np.abs(sol.pressure[1:-1] - (2.0 / np.pi) * ef)) < 1e-12
    assert abs(sol.lam - lam) < 1e-12
    assert sol.valid


def test_graded_edge_factor_rounding():
    """The graded representation puts nodes where the pressure is ~ tau^3 small, so
    the factor phi = p/sqrt(1 - s^2) at the outermost nodes and at the edges carries
    rounding amplified with n: in the Hertz case (exact phi = 2/pi) the error of
    phi(+-1) is 1.6e-12, 3.4e-12, 4.4e-10, 5.0e-8 at n = 32, 64, 128, 256 (about n^7
    beyond 64), while the pressure itself is exact to 5e-14.  Asserted: below 1e-10
    for n <= 64 (the n the automatic choice takes up to Pe = 1000) and below 1e-6 at
    n = 256, the largest n it takes (derivation section 12)."""
    for n, bound in ((32, 1e-10), (64, 1e-10), (256, 1e-6)):
        sol = solve(5, 0.0, 10, lam=-1.0, n=n)
        edge = sol.representation.phi_at(sol.phi, np.array([-1.0, 1.0]))
        assert np.max(np.abs(edge - 2.0 / np.pi)) < bound, n


@pytest.mark.parametrize("method", sorted(METHODS))
@pytest.mark.parametrize("case", CASES)
@pytest.mark.parametrize("lam", [-1.0, 0.3, 2.0])
def test_heat_balance(case, lam, method):
    """lam recovered from the heat-flux distribution by adaptive quadrature equals the
    imposed lam (abs. 1e-10), and q1 + q2 equals the frictional heat f p v (1e-12
    relative to max(1, |q1|))."""
    sol = solve(lam=lam, n=48, method=method, **case)
    # q sqrt(1 - s^2) = psi + eta p sqrt(1 - s^2)
    basis = sol.representation
    val = integral_over_contact(
        lambda s: basis.psi_at(sol.psi, s) + sol.eta * sol.pressure_at(s) * np.sqrt(1 - s * s),
        singular=True)
    assert abs(val - lam) < 1e-10
    p = sol.pressure_at(sol.flux_s)
    # Relative to the fluxes, which reach 2e3 at the graded nodes next to the edges.
    scale = np.maximum(1.0, np.abs(sol.flux_cylinder))
    assert np.max(np.abs(sol.flux_cylinder + sol.flux_half_plane - p) / scale) < 1e-12


@pytest.mark.parametrize("method", sorted(METHODS))
@pytest.mark.parametrize("case", CASES)
def test_load_equilibrium(case, method):
    """The pressure carries the load: its integral by adaptive quadrature is 1
    (abs. 1e-12)."""
    sol = solve(lam=-1.0, n=48, method=method, **case)
    assert abs(integral_over_contact(lambda s: sol.pressure_at(s)) - 1.0) < 1e-12


@pytest.mark.parametrize("method", sorted(METHODS))
@pytest.mark.parametrize("case", CASES)
def test_lam_and_sigma_formulations_agree(case, method):
    """Solving for sigma at a given lam, then for lam at that sigma, returns the same
    lam and P_H/P (rel. 1e-10): the two closures are the same linear system."""
    a = solve(lam=0.4, n=40, method=method, **case)
    b = solve(sigma_over_delta=a.sigma_over_delta, n=40, method=method, **case)
    assert abs(b.lam - 0.4) < 1e-10
    assert abs(b.load_ratio / a.load_ratio - 1) < 1e-10


@pytest.mark.parametrize("method", sorted(METHODS))
@pytest.mark.parametrize("case", CASES)
def test_affine_in_lam(case, method):
    """L and L*sigma are affine in lam (the equations are linear): the midpoint
    solution is the mean of the end solutions (abs. 1e-12)."""
    s0, s1, sm = (solve(lam=x, n=40, method=method, **case) for x in (-1.0, 3.0, 1.0))
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
    L = [solve(5, 0.2, 10, k2_over_k1=1, lam=-1, n=n, method="paper").load_ratio
         for n in (64, 128, 256, 512)]
    d = np.abs(np.diff(L))
    orders = np.log2(d[:-1] / d[1:])
    assert np.all((orders > 0.85) & (orders < 1.15)), orders
    # Richardson estimate of the n = 512 error is below 1e-4.
    assert d[-1] < 1e-4


def test_convergence_check_reports_change():
    """check_convergence reports |L(2n) - L(n)| equal to two separate solves."""
    a = solve(5, 0.2, 10, k2_over_k1=1, lam=-1, n=32, check_convergence=True)
    b = solve(5, 0.2, 10, k2_over_k1=1, lam=-1, n=64)
    assert a.method == "graded" and not a.auto_n
    assert a.load_ratio_change == pytest.approx(abs(b.load_ratio - a.load_ratio), rel=1e-12)


def test_approaches_barber_insulated_cylinder_at_first_order():
    """lam = -1, fHPe = 0.2, k2/k1 = 1: as K2/K1 grows the general solver approaches
    Barber's insulated, non-distorting cylinder (independent Galerkin solution in
    thermocontact.physics.reference_solutions, accurate to 1e-15) at first order in K1/K2: with product
    integration (n = 128, discretisation error ~1e-10) the error falls by
    10.06, 10.06, 10.007, 10.004 per decade of K2/K1 = 10 ... 1e5 (asserted within
    0.1 of 10), and (K2/K1)(P_H/P - Barber) tends to 0.0873 (to 1e-4 at 1e4, 1e5).
    The heat left in the cylinder is q1 = p/(1 + K2/K1) + q'/2 with q' = O(K1/K2)
    (derivation section 9)."""
    from thermocontact.physics.reference_solutions import barber_insulated

    LB = barber_insulated(0.2).load_ratio
    rhos = np.array([10, 100, 1e3, 1e4, 1e5])
    err = np.array([solve(5, 0.2, rho, k2_over_k1=1, lam=-1, n=128).load_ratio - LB
                    for rho in rhos])
    ratios = err[:-1] / err[1:]
    assert np.all(np.abs(ratios - 10) < 0.1), ratios
    assert np.all(np.abs(err[-2:] * rhos[-2:] - 0.0873) < 1e-4)


@lru_cache(maxsize=None)
def _reference(items):
    return solve(n=256, **dict(items))


def reference(**case):
    """Graded solution at n = 256 (within 1e-15 of n = 512), computed once per case."""
    return _reference(tuple(sorted(case.items())))


def rel_err(a, b):
    """The error measure of thermocontact.solvers.single_patch.error_estimate, of a against b."""
    return max(abs(a.load_ratio - b.load_ratio) / max(abs(b.load_ratio), 0.01),
               abs(a.sigma_over_delta - b.sigma_over_delta) / max(abs(b.sigma_over_delta), 0.01))


def test_product_integration_converges_at_fourth_order():
    """Pe = 5, K2/K1 = k2/k1 = 10 (cylinder kernels of width 1/50): product
    integration converges algebraically at observed order ~4 in n (orders 3.7 and
    3.9 between n = 32, 64, 128, 256; asserted 3.5-4.5), the rate set by the
    (1 -+ s)^{3/2} ln(1 -+ s) edge terms of the pressure (derivation section 8);
    between n = 128 and 256 P_H/P changes by 1.5e-9 and sigma/Delta by 2.1e-9
    (asserted below 3e-9)."""
    sols = [solve(5, 0.2, 10, lam=-1, n=n, method="product") for n in (32, 64, 128, 256)]
    L = np.array([x.load_ratio for x in sols])
    d = np.abs(np.diff(L))
    orders = np.log2(d[:-1] / d[1:])
    assert np.all((orders > 3.5) & (orders < 4.5)), orders
    assert d[-1] < 3e-9
    assert abs(sols[-1].sigma_over_delta - sols[-2].sigma_over_delta) < 3e-9


def test_galerkin_matches_collocation_at_twice_n():
    """Pe = 5, K2/K1 = k2/k1 = 10: the Galerkin projection at n has about the error of
    product collocation at 2n (observed: relative errors of sigma/Delta 3.1e-6, 2.0e-7,
    1.2e-8 at n = 32, 64, 128 against collocation's 2.9e-6, 1.9e-7, 1.2e-8 at 64, 128,
    256; asserted within a factor 2), measured against the edge-graded solution at
    n = 96 (its estimate 7e-16; it differs from collocation at n = 512 by 8e-10, that
    method's own error)."""
    ref = solve(5, 0.2, 10, lam=-1, n=96)
    for n in (32, 64, 128):
        g = solve(5, 0.2, 10, lam=-1, n=n, method="galerkin")
        p = solve(5, 0.2, 10, lam=-1, n=2 * n, method="product")
        eg, ep = rel_err(g, ref), rel_err(p, ref)
        assert 0.5 < eg / ep < 2.0, (n, eg, ep)


def test_methods_agree_as_n_grows():
    """The paper's scheme converges to the product-integration solution at its own
    first-order rate: the difference halves with each doubling of n (observed ratios
    1.970 and 1.986 for n = 128, 256, 512; asserted 1.9-2.1; Pe = 5, K2/K1 = 10,
    k2/k1 = 1)."""
    ref = solve(5, 0.2, 10, k2_over_k1=1, lam=-1, n=96).load_ratio  # n = 256's to 1e-15
    diff = np.array([abs(solve(5, 0.2, 10, k2_over_k1=1, lam=-1, n=n, method="paper").load_ratio - ref)
                     for n in (128, 256, 512)])
    ratios = diff[:-1] / diff[1:]
    assert np.all((ratios > 1.9) & (ratios < 2.1)), ratios


@pytest.mark.parametrize("case", [
    dict(pe=5, fhpe=0.2, K2_over_K1=10, k2_over_k1=1, lam=-1),
    dict(pe=5, fhpe=0.2, K2_over_K1=10, lam=-1),
    dict(pe=1, fhpe=0.3, K2_over_K1=1, lam=0),
])
@pytest.mark.parametrize("n", [128, 256])
def test_error_estimate_tracks_true_error(case, n):
    """The Richardson error estimate (levels n/4, n/2, n) of the Chebyshev Galerkin
    method is within a factor of 10 of its true error, measured against the graded
    method at n = 256 (error below 1e-12; observed ratios 1.02-1.07)."""
    ref = reference(**case)
    sol = solve(n=n, method="galerkin", **case)
    ratio = sol.error_estimate / rel_err(sol, ref)
    assert 0.1 < ratio < 10, ratio


def test_automatic_n_meets_tolerance():
    """Without n the solver doubles n from 8 until the estimate is below tol; the
    result (n = 32, estimate 7e-11) agrees with n = 256 (error below 1e-12) to 1e-8
    in the estimate's measure (observed 6e-13; Pe = 5, K2/K1 = 10)."""
    sol = solve(5, 0.2, 10, lam=-1)
    assert sol.auto_n and sol.converged and sol.error_estimate <= 1e-8
    assert sol.method == "graded" and sol.n <= 64
    ref = solve(5, 0.2, 10, lam=-1, n=256, tol=1.0)
    assert rel_err(sol, ref) < 1e-8
    loose = solve(5, 0.2, 10, lam=-1, tol=1e-2)
    assert loose.n < sol.n and loose.error_estimate <= 1e-2


def test_bad_tolerance_refused():
    with pytest.raises(InputError, match="tol"):
        solve(5, 0.2, 10, lam=-1, tol=0)


def test_approach_to_barber_with_equal_capacities_is_half_order():
    """With k2/k1 = K2/K1 (the paper's choice) the cylinder's kernels sharpen as K2/K1
    grows and its share of the heat falls only like (K1/K2)^{1/2}: at Pe = 5,
    fHPe = 0.2 the distance to Barber's solution falls by 3.09 from K2/K1 = 100 to
    1000 (sqrt(10) = 3.16; asserted within 5 %), with sqrt(K2/K1) times it 0.103,
    0.106."""
    from thermocontact.physics.reference_solutions import barber_insulated

    LB = barber_insulated(0.2).load_ratio
    # n = 128: error estimates below 1e-14, the ratio as at n = 512 to 1e-12.
    d = [solve(5, 0.2, rho, lam=-1, n=128).load_ratio - LB for rho in (100.0, 1000.0)]
    assert abs(d[0] / d[1] / np.sqrt(10) - 1) < 0.05


def test_a_heat_partition_met_again_is_checked_alike():
    """A grid line's heat partition is checked once per system: met again, -0.0 is the
    checked 0.0 (not a signed zero in the result) and a value the checks refuse (True,
    equal to 1.0) is refused as the first time; parameters at another fHPe refuse a bad
    fHPe as the constructor does, the constructor naming fHPe first."""
    import math

    from thermocontact.problem.parameters import Parameters
    from thermocontact.solvers.single_patch import Model, _solve_patches

    model = Model(5.0, 10.0)
    blocks, systems = model.blocks(16), {}
    par = model.parameters_at(0.2)

    def lam_of(lam):
        return _solve_patches([par], blocks, model.method, [(lam, None, None)], None,
                              systems)[0]
    first, again = lam_of(0.0), lam_of(-0.0)
    assert again.lam == 0.0 and math.copysign(1.0, again.lam) == 1.0
    assert np.array_equal(again.phi, first.phi)
    lam_of(1.0)
    assert isinstance(lam_of(True), InputError)
    for bad in (-1.0, float("nan"), float("inf")):
        with pytest.raises(InputError, match="fhpe") as alone:
            Parameters(5.0, bad, 10.0)
        with pytest.raises(InputError, match="fhpe") as moved:
            par.with_fhpe(bad)
        assert str(alone.value) == str(moved.value)
    with pytest.raises(InputError, match="fhpe"):
        Parameters(5.0, -1.0, -1.0)
    with pytest.raises(InputError, match="pure rolling"):
        Parameters(5.0, 0.0, 10.0, speed_ratio=1.0).with_fhpe(0.1)
    assert par.with_fhpe(0.3) == Parameters(5.0, 0.3, 10.0)
