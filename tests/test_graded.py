"""The edge-graded representation: its map, its moments, and its convergence."""

from functools import lru_cache

import mpmath as mp
import numpy as np
import pytest

from conftest import assert_ulps, references
from thermocontact import solve
from thermocontact.numerics import moment_engine as graded
from thermocontact.numerics.moments import chebyshev_lagrange
from thermocontact.physics.green_functions import cylinder_slope, cylinder_temperature_gradient_regular


def test_stretch_and_inverse():
    """T(tau) = tau - sin(2 tau)/2 is inverted to 1e-14 relative (also near tau = 0,
    where T ~ (2/3) tau^3; near tau = pi a value of t cannot fix tau that well, which
    is why the methods carry tau), and the increment T(tau + d) - T(tau) is free of
    cancellation."""
    tau = np.concatenate([np.geomspace(1e-6, 1, 30), np.linspace(1, np.pi - 0.1, 30)])
    t = graded.stretch(tau)
    assert np.max(np.abs(graded.stretch_inverse(t) / tau - 1)) < 1e-14
    assert np.isnan(graded.stretch_inverse(np.array([np.nan, 1.0]))[0])
    assert abs(graded.stretch(np.array([1e-6]))[0] / (2 / 3 * 1e-18) - 1) < 1e-11
    with mp.workdps(40):
        d = np.array([1e-12, 1e-6, 0.3])
        exact = np.array([float(mp.mpf(0.7) + x - mp.sin(2 * (mp.mpf(0.7) + x)) / 2
                                - (mp.mpf(0.7) - mp.sin(mp.mpf(1.4)) / 2)) for x in d])
        assert np.max(np.abs(graded.stretch_increment(0.7, d) / exact - 1)) < 1e-12


def test_x_minus_sin_has_full_relative_accuracy():
    """x - sin x (Taylor series by Horner's rule below |x| = 1/2, the difference above)
    equals 40-digit mpmath to 2e-15 relative (observed 6e-16), from 1e-8 to 3 and at
    both signs."""
    with mp.workdps(40):
        x = np.concatenate([-np.geomspace(1e-8, 3, 40), np.geomspace(1e-8, 3, 40), [0.4999, 0.5]])
        exact = np.array([float(mp.mpf(v) - mp.sin(mp.mpf(v))) for v in x])
        assert np.max(np.abs(graded._x_minus_sin(x) / exact - 1)) < 2e-15


def test_chebyshev_lagrange_interpolates_exactly():
    """The barycentric Lagrange basis of the 30 Chebyshev points on [0, 1] reproduces a
    polynomial of degree 29 to 1e-13 at points in [0, 1] (observed 7e-15; at the nodes
    it is the unit vector) and cos(j d) on [h, 2h] for j < n to 2e-14 (observed 8e-15;
    n = 256, h = pi/66, the common rule's panel): the interpolation the full sides rely
    on."""
    x = np.linspace(0.0, 1.0, 101)
    xc, lag = chebyshev_lagrange(x, 30)
    _, at_nodes = chebyshev_lagrange(xc, 30)
    assert np.array_equal(at_nodes, np.eye(30))
    poly = np.polynomial.chebyshev.Chebyshev(np.random.default_rng(1).normal(size=30), [0, 1])
    assert np.max(np.abs(lag @ poly(xc) - poly(x))) < 1e-13 * np.max(np.abs(poly(xc)))
    h, j = np.pi / 66, np.arange(256)
    assert np.max(np.abs(lag @ np.cos(np.outer(h * (1 + xc), j)) - np.cos(np.outer(h * (1 + x), j)))) < 2e-14


@pytest.mark.parametrize("name", ["sgn", "NH", "mr"])
def test_moments_against_mpmath(name):
    """Moments of sgn, N(cu)H(u) and c M(cu) - 1/u (c = 50) against the cosine bases,
    at points inside, next to and outside the contact, equal mpmath quadrature at 30
    digits (20 for the Bessel-K kernel; tests/data/make_references.py) to 1e-12
    relative (observed 1e-14).  The logarithmic kernel is graded as the methods grade
    it: 20 halvings below its scale, the last panel after x = e y^6."""
    ref = references()["graded_moments"][name]
    c = ref["c"]
    kern = {
        "sgn": (np.sign, dict(scale=1.0)),
        "NH": (lambda u: cylinder_slope(c * u), dict(scale=c)),
        "mr": (lambda u: cylinder_temperature_gradient_regular(u, c),
               dict(scale=c, logarithmic=True)),
    }[name]
    s = np.array(ref["s"])
    # The stored inputs: the points' tau equals the reference's up to the inversion's
    # rounding (which differs in the last bits between NumPy versions), and the
    # moments are taken at the reference's tau.
    tau = np.array(ref["tau_s"])
    np.testing.assert_allclose(graded.tau_of(s), tau, rtol=0, atol=1e-15)
    nb, ns = graded.moments(kern[0], s, 12, tau=tau, **kern[1])
    index = {v: k for k, v in enumerate(ref["s"])}
    for sk, j, weight, value in ref["values"]:
        got = (nb if weight == "b" else ns)[index[sk], j]
        assert abs(got - value) < 1e-12 * max(1.0, abs(value)), (sk, j, weight)


def test_moments_next_to_an_edge_at_large_scale():
    """At c = Pe k2/k1 = 1e5 the kernel c M(cu) - 1/u varies, on the row of the
    Galerkin points nearest an edge (n = 64, tau_s = 0.012), across the panels just
    beyond the replaced interval.  Its moment against cos(63 tau) T' equals 20-digit
    mpmath quadrature (tests/data/make_references.py) to 1e-14 of the row's largest
    entry (observed 4e-15; a construction with three geometric panels up to the
    side's end was off by 3e-14)."""
    from thermocontact.discretisation.representations import range_projections

    ref = references()["graded_edge_row"]
    c, n, j = ref["c"], ref["n"], ref["j"]
    tau, _, _ = range_projections(n)
    k = int(np.argmin(tau))
    assert tau[k] == ref["tau_s"]
    s = np.cos(graded.stretch(tau))
    kern = lambda u: cylinder_temperature_gradient_regular(u, c)  # noqa: E731
    _, ms = graded.moments(kern, s[[k]], n, scale=c, logarithmic=True, tau=tau[[k]])
    err = abs(ms[0, j] - ref["value"]) / np.abs(ms[0]).max()
    assert err < 1e-14, err


def test_cauchy_moments_next_to_an_edge():
    """On the row of the Galerkin points nearest an edge (n = 128, tau_s = 0.0061) the
    principal value against the flux weight T' cos(127 tau) equals 30-digit quadrature
    of the subtracted integrand (tests/data/make_references.py) to 1e-12 of the row's
    largest entry (observed 6e-14).  A recurrence in cos(tau) for that row's short
    side, whose phase error the cancellation between the two sides amplifies, gave
    2.5e-11."""
    from thermocontact.discretisation.representations import range_projections

    ref = references()["graded_cauchy_edge_row"]
    n, j = ref["n"], ref["j"]
    tau, _, _ = range_projections(n)
    k = int(np.argmin(tau))
    assert tau[k] == ref["tau_s"]
    s = np.cos(graded.stretch(tau))
    _, ms = graded.moments(lambda u: 1.0 / u, s[[k]], n, scale=1.0, cauchy=True, tau=tau[[k]])
    err = abs(ms[0, j] - ref["value"]) / np.abs(ms[0]).max()
    assert err < 1e-12, err


def test_cauchy_moments_are_principal_values():
    """The principal values (1/pi) PV int p(r)/(s - r) dr of the graded bases equal
    30-digit quadrature with the pole subtracted (tests/data/make_references.py) to
    1e-11, also at points 1e-6 from an edge, where the graded interval is strongly
    asymmetric."""
    ref = references()["graded_cauchy"]
    s = np.array(ref["s"])
    # The reference was made at these points (on another CPU: its arccos may differ in
    # the last bits).
    assert_ulps(graded.tau_of(s), np.array(ref["tau_s"]), ulps=8, scale="each")
    b, _ = graded.moments(lambda u: 1.0 / u, s, 10, scale=1.0, cauchy=True)
    index = {v: k for k, v in enumerate(ref["s"])}
    for sk, j, value in ref["values"]:
        got = b[index[sk], j] / np.pi
        assert abs(got - value) < 1e-11 * max(1, abs(value)), (sk, j)


@lru_cache(maxsize=None)
def _solution(method, n, pe=5.0, K=10.0):
    return solve(pe, 0.2, K, lam=-1, n=n, method=method)


def rel_err(a, b):
    return max(abs(a.load_ratio - b.load_ratio) / max(abs(b.load_ratio), 0.01),
               abs(a.sigma_over_delta - b.sigma_over_delta) / max(abs(b.sigma_over_delta), 0.01))


def test_graded_converges_faster_than_any_low_order():
    """Pe = 5, K2/K1 = k2/k1 = 10: the graded Galerkin method's error against graded
    collocation at n = 256 (a second method) is 4e-3, 2.9e-7, 7e-13 at n = 8, 16, 32:
    it falls by more than 1e3 per doubling (observed factors 1.4e4 and 4e5, orders 14
    and 19, growing: faster than algebraic), where the Chebyshev methods' order is 4."""
    ref = _solution("graded-collocation", 256)
    err = np.array([rel_err(_solution("graded", n), ref) for n in (8, 16, 32)])
    assert np.all(err[:-1] / err[1:] > 1e3), err
    assert err[-1] < 1e-11
    # The Chebyshev Galerkin method at n = 256 agrees to its own error (7e-10).
    assert rel_err(_solution("galerkin", 256), ref) < 2e-9


def test_pe_1000_converged():
    """Pe = 1000, K2/K1 = k2/k1 = 100 (cylinder kernels of width 1e-5): graded Galerkin
    at n = 64 and graded collocation at n = 256 agree to 1e-9 (observed 2.3e-10), and
    with the automatic choice the estimate is below 1e-6 and the true error below it."""
    ref = _solution("graded-collocation", 256, 1000.0, 100.0)
    assert rel_err(_solution("graded", 64, 1000.0, 100.0), ref) < 1e-9
    auto = solve(1000.0, 0.2, 100.0, lam=-1, tol=1e-6)
    assert auto.converged and auto.error_estimate < 1e-6
    assert rel_err(auto, ref) < auto.error_estimate


@pytest.mark.parametrize("pe,K", [(5.0, 10.0), (10.0, 100.0), (1000.0, 100.0)])
def test_graded_error_estimate_is_an_upper_bound(pe, K):
    """The graded methods converge faster than order 5, so the Richardson estimate
    (order capped at 5) bounds the error from above: at the n chosen for tol = 1e-8
    the true error (against graded collocation at n = 256) is below the estimate or
    at the level of rounding (1e-10 at Pe = 1000, where the heat equation's rows next
    to the edges are large; observed 6e-11), and the estimate is not wasteful by
    more than 1e4 there."""
    ref = _solution("graded-collocation", 256, pe, K)
    sol = solve(pe, 0.2, K, lam=-1)
    true = rel_err(sol, ref)
    assert true <= max(sol.error_estimate, 1e-10)
    assert true > 1e-4 * sol.error_estimate or true < 1e-10


def test_a_coarse_series_is_held_by_a_finer_one_and_checked_there():
    """The prolongation from n to 2n (and 4n) is exact: the prolonged nodal values are
    the same cosine series (phi and psi at random points to 1e-14), and the margins of
    a coarse solution evaluated by the finer level's operators are its own: to 1e-12
    from n = 16 (measured 4e-13), and to 1e-10 at n = 8, whose own moments of the gap's
    kernels are accurate to about 4e-11 only.  Representations that do not hold each other give None."""
    from thermocontact import Model
    from thermocontact.analysis.validity import assess
    from thermocontact.discretisation.representations import Chebyshev, EdgeGraded

    rng = np.random.default_rng(4)
    coarse = EdgeGraded(12)
    values = rng.standard_normal(12)
    tau = rng.uniform(0.0, np.pi, 50)
    for fine in (EdgeGraded(24), EdgeGraded(48), EdgeGraded(13)):
        held = coarse.prolong(np.array([values, 2 * values]), fine)
        here = graded.cosine_value(coarse.to_cos @ values, tau)
        there = graded.cosine_value(fine.to_cos @ held[0], tau)
        assert np.max(np.abs(there - here)) < 1e-14 * np.max(np.abs(values)) * 10
        assert_ulps(held[1], coarse.prolong(2 * values[None, :], fine)[0])  # row alone
    assert coarse.prolong(values[None, :], EdgeGraded(8)) is None
    assert coarse.prolong(values[None, :], EdgeGraded(24, alpha=0.4)) is None
    assert coarse.prolong(values[None, :], Chebyshev(24)) is None
    assert Chebyshev(12).prolong(values[None, :], Chebyshev(24)) is None
    for pe, fhpe, d in ((7.0, 0.3, 1.0), (0.7, 0.9, 0.3), (50.0, 0.5, 1.0)):
        m = Model(pe, 10.0, delta1_over_delta2=d)
        for n, tol in ((8, 1e-10), (16, 1e-12), (32, 1e-12)):
            sol = m.solve_at(n, fhpe, lam=1.0, check_validity=False)
            fine = m.blocks(2 * n).representation
            phi, psi = sol.representation.prolong(np.array([sol.phi, sol.psi]), fine)
            own = assess(sol.parameters, sol.representation, sol.phi, sol.psi,
                         sol.load_ratio, sol.sigma_over_delta, sol.lam, polish=False)
            held = assess(sol.parameters, fine, phi, psi, sol.load_ratio,
                          sol.sigma_over_delta, sol.lam, polish=False)
            for k, v in own.margins().items():
                assert held.margins()[k] == pytest.approx(v, abs=tol * max(1.0, abs(v))), \
                    (pe, n, k)


@pytest.mark.parametrize("n", [4, 8, 33, 256])
def test_far_field_by_the_rules_symmetry_is_the_whole_tables_product(n):
    """The common rule's nodes mirror about pi/2 (node N - 1 - k is pi - tau_k to
    rounding, N even), the premise of the far field's half table; its product equals
    the product with the whole table cos(j tau_k) to 1e-13 of the values' size."""
    from thermocontact.numerics.moment_engine import _common, _far_product
    from thermocontact.numerics.moments import panel_rule

    _, _, tau, _, _ = panel_rule(n)
    assert tau.size % 2 == 0
    assert np.max(np.abs(tau[::-1] - (np.pi - tau))) < 1e-15
    values = np.random.default_rng(n).standard_normal((5, tau.size))
    out = np.empty((5, n))
    _far_product(values, _common(n)[3], out)
    whole = values @ np.cos(np.multiply.outer(tau, np.arange(n)))
    assert np.max(np.abs(out - whole)) < 1e-13 * np.abs(values).sum(axis=1).max()


def test_points_beyond_an_edge_skip_the_side_they_have_not():
    """Points beyond the leading edge have no contact on their right: the moments
    evaluate no kernel there, and give those points what they get in a block with
    interior points (where that side is integrated for the interior ones)."""
    calls = []

    def kernel(u):
        calls.append(np.size(u))
        return cylinder_slope(3.0 * u)

    out = 1.0 + np.geomspace(1e-8, 10.0, 7)
    alone = graded.moments(kernel, out, 16, scale=3.0)
    alone_values = sum(calls)
    calls.clear()
    inside = np.array([-0.5, 0.2, 0.9])
    mixed = graded.moments(kernel, np.concatenate([inside, out]), 16, scale=3.0)
    for a, b in zip(alone, mixed):
        assert np.allclose(a, b[3:], rtol=1e-14, atol=1e-15 * np.abs(a).max())
    # Far field and one side's inner and outer nodes per point: the other side's
    # nodes (as many again) are not evaluated.
    assert alone_values < 0.75 * sum(calls) * out.size / (out.size + inside.size)


@pytest.mark.parametrize("n", [16, 64])
def test_points_beyond_an_edge_move_the_edge_geometry(monkeypatch, n):
    """Points beyond an edge share that edge's tau_s: their geometry is the edge
    point's, built once and moved by s - clip(s).  Their moments equal those of a
    geometry built for them alone, to a few ulps of the largest (the same formulas in
    other arrays: conftest.assert_ulps), on both sides, for a kernel that carries
    each point's own parameter (the gap's) and for a pressure of another edge exponent
    (its weights moved with the geometry)."""
    built = []
    init = graded._Geometry.__init__

    def counting(self, s, *args):
        built.append(np.array(s))
        init(self, s, *args)
    monkeypatch.setattr(graded._Geometry, "__init__", counting)
    sides = [1.0 + np.geomspace(1e-8, 30.0, 9), -1.0 - np.geomspace(1e-6, 3.0, 4)]
    kernels = [lambda u: cylinder_slope(3.0 * u),
               lambda u: cylinder_temperature_gradient_regular(u, 40.0)]

    def run():
        graded.clear_geometry()
        out = []
        for s in sides:
            h = 3.0 * (np.abs(s) - 1.0)[:, None]
            drop = lambda u, h=h: cylinder_slope(3.0 * u - h) * h  # noqa: E731
            for kern, log in zip(kernels + [drop], (False, True, False)):
                out += graded.moments(kern, s, n, scale=3.0, logarithmic=log)
                out += graded.moments(kern, s, n, scale=3.0, logarithmic=log, from_edge=True)
            out += graded.moments(kernels[0], s[3:4], n, scale=3.0)  # one point alone
            out += graded.moments(kernels[0], s, n, scale=3.0, cmap=graded.graded_map(0.3))
        return out

    moved = run()
    # Built: the two edge points, nothing else.
    assert sorted(float(b[0]) for b in built) == [-1.0, 1.0] and all(b.size == 1 for b in built)
    monkeypatch.setattr(graded._Geometry, "moved",
                        lambda self, s, key: graded._Geometry(s, self.n, None, self.cmap))
    built.clear()
    alone = run()
    assert len(built) == 2 + 2 * len(sides)
    for a, b in zip(moved, alone):
        assert_ulps(a, b)


@pytest.mark.parametrize("alpha", [0.2, 0.8])
def test_another_edge_exponent_shares_the_point_geometry(monkeypatch, alpha):
    """The point geometry does not depend on the pressure's edge exponent: the moments
    of another alpha at points seen before form no geometry.  Their pressure weights,
    formed from the geometry's of alpha = 1/2 (moment_engine._edge_power), give the
    moments of a smooth kernel that the midpoint rule on 4096 points gives with the
    weight in closed form (bounded_weight; its error O(m^-(6 alpha + 6))), to 2e-14 of
    the largest (observed 6e-15), at points inside, at and beyond the edges (a moved
    geometry's)."""
    built = []
    init = graded._Geometry.__init__

    def counting(self, s, *args):
        built.append(s.size)
        init(self, s, *args)
    monkeypatch.setattr(graded._Geometry, "__init__", counting)
    kernel = lambda u: np.cos(3.0 * u)  # noqa: E731
    n, m = 16, 4096
    tq = np.pi * (np.arange(m) + 0.5) / m
    r = np.cos(graded.stretch(tq))
    basis = np.cos(np.outer(tq, np.arange(n))) * (np.pi / m)
    weights = np.stack([graded.bounded_weight(tq, alpha), graded.singular_weight(tq)])
    graded.clear_geometry()
    for s in (np.array([-1.0, -0.999, -0.3, 0.2, 0.99999, 1.0]), 1.0 + np.geomspace(1e-6, 2.0, 4)):
        graded.moments(kernel, s, n)
        before = len(built)
        got = graded.moments(kernel, s, n, cmap=graded.graded_map(alpha))
        assert len(built) == before
        for g, w in zip(got, weights):
            want = (kernel(s[:, None] - r[None, :]) * w) @ basis
            assert np.abs(g - want).max() < 2e-14 * np.abs(want).max()


@pytest.mark.parametrize("alpha", [0.1, 0.37, 0.9])
def test_edge_power_keeps_relative_accuracy_next_to_either_edge(alpha):
    """The pressure weight of an edge exponent, formed from sin^2 t T' (alpha = 1/2),
    T' and cos t, equals w(cos t) sin t T' from the half-angles
    (moment_engine._pressure_factor) to a few ulps of each value, down to t = 1e-12
    from either edge; zero where the weight of alpha = 1/2 is."""
    rng = np.random.default_rng(7)
    near = np.geomspace(1e-12, 1e-2, 200)
    t = np.concatenate([near, rng.uniform(0.0, np.pi, 400), np.pi - near])
    t_prime = rng.uniform(0.1, 2.0, t.size)
    got = graded._edge_power(np.sin(t) ** 2 * t_prime, t_prime, np.cos(t), alpha)
    assert_ulps(got, graded._pressure_factor(t, alpha) * t_prime, ulps=16, scale="each")
    assert graded._edge_power(np.zeros(2), np.array([0.0, 1.0]), np.ones(2), alpha).tolist() == [0, 0]


def test_the_flux_rows_are_kept_once_for_every_edge_exponent():
    """The Cauchy, sign and logarithm rows of the edge-graded representation keep their
    flux half without the edge exponent: another exponent at the same points gets the
    kept array itself and forms its pressure half alone, which equals the one formed
    beside the flux half to a few ulps of the largest."""
    from thermocontact import clear_caches
    from thermocontact.discretisation.representations import EdgeGraded

    (s, aux), _ = EdgeGraded(16).collocation_points()
    a, b = EdgeGraded(16, alpha=0.3), EdgeGraded(16, alpha=0.7)
    names = ("cauchy", "sign", "logarithm")
    clear_caches()
    together = [getattr(b, name)(s, aux) for name in names]
    clear_caches()
    for name, (p_both, q_both) in zip(names, together):
        _, q = getattr(a, name)(s, aux)
        p_alone, q_b = getattr(b, name)(s, aux)
        assert q_b is q
        assert_ulps(p_alone, p_both)
        assert_ulps(q, q_both)


def test_kernel_called_once_per_block():
    """A block of points small enough (KERNEL_ENTRIES) calls its kernel once, on the far
    field's and both sides' nodes side by side, and gets the same numbers as when each
    part is evaluated on its own (a larger block's path)."""
    calls = []

    def kernel(u):
        calls.append(u.shape)
        return cylinder_temperature_gradient_regular(u, 7.0)

    s = np.array([-0.9, -0.2, 0.3, 0.95])
    once = graded.moments(kernel, s, 16, scale=7.0, logarithmic=True)
    assert len(calls) == 1 and calls[0][0] == s.size
    calls.clear()
    old = graded.KERNEL_ENTRIES
    try:
        graded.KERNEL_ENTRIES = 64  # the far field a few columns at a time, sides apart
        apart = graded.moments(kernel, s, 16, scale=7.0, logarithmic=True)
    finally:
        graded.KERNEL_ENTRIES = old
    assert len(calls) > 4
    for a, b in zip(once, apart):
        assert_ulps(a, b)


def test_a_blockwise_kernel_is_called_on_each_part_apart():
    """A kernel whose values depend on the array it is given (``elementwise = False``:
    the transient distortion's quadrature takes its depth per block of points) is called
    on the far field's nodes and on each side's innermost interval and outer panels
    apart, as the moments always called it; the numbers are those of the same kernel
    called once on all of them, where it is elementwise."""
    shapes = []

    def blockwise(u):
        shapes.append(u.shape)
        return cylinder_temperature_gradient_regular(u, 7.0)
    blockwise.elementwise = False
    s = np.array([-0.9, -0.2, 0.3, 0.95])
    apart = graded.moments(blockwise, s, 16, scale=7.0, logarithmic=True)
    assert len(shapes) == 1 + 2 * 2 and all(shape[0] == s.size for shape in shapes)
    once = graded.moments(lambda u: cylinder_temperature_gradient_regular(u, 7.0), s, 16,
                          scale=7.0, logarithmic=True)
    for a, b in zip(apart, once):
        assert_ulps(a, b)
