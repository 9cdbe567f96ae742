"""Contact inequalities: the gap's closed forms against brute-force quadrature, the
Hertz gap, and detection of tensile pressure, interpenetration and negative load."""

import json

import numpy as np
import pytest

from conftest import DATA, assert_ulps, data_script
from thermocontact import solve

HERTZ_EDGE = 2 * np.sqrt(2) / 3  # g ~ (2 sqrt 2 / 3) (|s| - 1)^1.5 for Hertz

def hertz_gap(s):
    """Exact Hertz gap in units of Delta^2/R: (|s| sqrt(s^2 - 1) - arccosh|s|)/2."""
    a = np.abs(s)
    return 0.5 * (a * np.sqrt(a * a - 1) - np.arccosh(a))

def test_hertz_gap_exact():
    """fHPe = 0: gap equals the closed-form Hertz gap on both sides to 1e-13 relative to
    the largest gap checked (|s| up to 31, g up to ~480)."""
    sol = solve(5, 0.0, 10, lam=-1, n=16)
    t = np.geomspace(1e-7, 30, 50)
    s = np.concatenate([-1 - t, 1 + t])
    ref = hertz_gap(s)
    assert np.max(np.abs(sol.gap_at(s) - ref)) < 1e-13 * np.max(ref)
    v = sol.validity
    assert v.valid and v.min_gap == 0.0 and v.min_pressure == 0.0
    assert abs(v.pressure_margin - 2 / np.pi) < 1e-12
    # g/(|s|-1)^1.5 -> 2 sqrt2/3 at the edge; the grid starts at 1e-8 (next term O(1e-8)).
    assert abs(v.gap_margin - HERTZ_EDGE) < 1e-6

GAP = data_script("make_gap_references")
GAP_RECORD = json.loads((DATA / "gap_references.json").read_text())


@pytest.mark.parametrize("index", range(len(GAP.CASES)))
def test_gap_closed_form_matches_quadrature(index):
    """The gap (Chebyshev: Cauchy moments in closed form; graded: logarithmic moments;
    both: E antiderivative, exact sgn) equals nested adaptive quadrature of the slope
    mismatch to 1e-9 (abs, quadrature tolerance); with a moving half-plane too.  The
    quadratures are stored (tests/data/make_gap_references.py), each with the solution
    it integrated: the same solution is solved here (P_H/P and sigma/Delta to 1e-12)."""
    rec = GAP_RECORD["cases"][index]
    case, s, method = GAP.CASES[index]
    assert (rec["parameters"], rec["s"], rec["method"]) == (case, s, method)
    sol = GAP.solution(case, method)
    for key in ("load_ratio", "sigma_over_delta"):
        assert abs(getattr(sol, key) - rec[key]) <= 1e-12 * max(1.0, abs(rec[key])), \
            "not the stored solution: run tests/data/make_gap_references.py again"
    assert abs(sol.gap_at(s)[0] - rec["gap"]) < 1e-9 * max(1.0, abs(rec["gap"]))


def test_gap_quadrature_of_one_case_again():
    """The stored quadrature of the cheapest case, computed again here: the script's
    brute force itself still gives what it stored (to the quadrature's 1e-11)."""
    index = 0
    case, s, method = GAP.CASES[index]
    ref = GAP.brute_force_gap(GAP.solution(case, method), s)
    assert abs(ref - GAP_RECORD["cases"][index]["gap"]) < 1e-11 * max(1.0, abs(ref))


@pytest.mark.parametrize("lam", [-1.0, 0.5])
def test_edge_gap_follows_edge_pressure(lam):
    """Near an edge the gap is Hertz-like: g/(|s|-1)^1.5 -> (pi/2L)(2 sqrt2/3) phi(+-1),
    with phi = p/sqrt(1-s^2) (local analysis, derivation section 7); checked at
    |s| - 1 = 1e-10 to rel. 1e-3 (next term O((|s|-1)^0.5))."""
    sol = solve(5, 0.3, 10, k2_over_k1=1, lam=lam, n=64)
    for edge in (-1.0, 1.0):
        s = edge * (1 + 1e-10)
        margin = sol.gap_at(s)[0] / 1e-15
        phi_edge = sol.representation.phi_at(sol.phi, edge)
        expected = np.pi / (2 * sol.load_ratio) * HERTZ_EDGE * phi_edge
        assert abs(margin / expected - 1) < 1e-3

def test_edge_log_term_makes_contact_invalid():
    """Heat into a non-distorting cylinder at its leading edge (lam = 1,
    delta1/delta2 = 0, fHPe = 0.3): the pressure carries k sqrt(1-s) ln(1-s) with
    k > 0 at s = +1, tensile just inside that edge.  The polynomial representation
    sees it only through a drift of phi_n(1) = p/sqrt(1-s^2) at s = 1 of
    -sqrt(2) k ln 2 per doubling of n (it resolves 1 - s down to ~1/n^2): with
    product integration the drifts for n = 128 ... 512 are 0.9944 and 0.9972 of the
    prediction (asserted within 1 %; 0.9986 to n = 1024), and by n = 256 the discrete
    pressure itself is tensile next to the edge (the margin is taken outside the
    tolerated layer of 1e-6 half-widths, whose width the edge margin judges: too wide
    here)."""
    sols = [solve(5, 0.3, 10, k2_over_k1=1, delta1_over_delta2=0, lam=1, n=n, method="product")
            for n in (128, 256, 512)]
    for sol in sols:
        k_minus, k_plus = sol.validity.edge_log_coefficients
        assert k_plus > 0 and not sol.valid and sol.load_ratio > 0
    phi1 = np.array([s.representation.phi_at(s.phi, 1.0) for s in sols])
    drift = np.diff(phi1)
    predicted = -np.sqrt(2) * sols[-1].validity.edge_log_coefficients[1] * np.log(2)
    ratio = drift / predicted
    assert np.all(np.abs(ratio - 1) < 0.01), ratio
    v = sols[1].validity
    assert v.pressure_margin < 0 and 0.999 < v.pressure_margin_at <= 1.0 - 1e-6
    assert v.gap_margin < 0 and 1.0 < v.gap_margin_at < 1.01
    assert v.edge_margins[1] < 0 and v.edge_layer_widths[1] > 1e-6

def test_equal_distortivities_have_no_edge_log_term():
    """delta1 = delta2: the step kernels' jumps cancel at the edges, k = 0 exactly."""
    sol = solve(5, 0.3, 10, k2_over_k1=1, lam=1, n=64)
    assert sol.validity.edge_log_coefficients == (0.0, 0.0)

def test_interpenetration_away_from_edges_detected():
    """lam = 4, delta1/delta2 = 5, fHPe = 0.3: compressive everywhere, but the bodies
    overlap near s = 2.2 (n = 64 ... 256 with product integration; the closed-form gap
    is checked against quadrature above)."""
    sol = solve(5, 0.3, 10, k2_over_k1=1, delta1_over_delta2=5, lam=4, n=64)
    v = sol.validity
    assert v.pressure_margin > 0 and v.min_pressure == 0.0
    assert v.min_gap < 0 and not v.valid
    assert 2.0 < v.min_gap_at < 2.5
    assert sol.gap_at(v.min_gap_at)[0] == pytest.approx(v.min_gap, rel=1e-13)

def test_negative_load_is_invalid():
    """Past the limiting contact width (fHPe = 1 here) P_H/P < 0: not valid."""
    sol = solve(5, 1.0, 10, k2_over_k1=1, lam=-1, n=32)
    assert sol.load_ratio < 0
    assert not sol.validity.positive_load and not sol.valid

def test_boundary_is_the_zero_of_the_exact_gap_margin():
    """The Fig. 4 boundary (Pe = 5, K2/K1 = 10, lam = 1, along fHPe), located by the
    sweep's Brent iteration on the margins, equals bisection to 1e-13 of the gap
    margin of plain solves to 1e-9 (observed 8e-14), and there the gap margin
    sampled independently at 20001 points of 1e-4 <= s - 1 <= 0.1 is zero to 1e-8
    (observed 7e-11; the sampled margin of 160 points had put the boundary 7.5e-5
    higher in fHPe)."""
    from scipy.optimize import bisect

    from thermocontact.studies.sweeps import sweep

    curve = sweep("fig4", dict(pe=5, K2_over_K1=10, lam=1.0), "fhpe",
                  np.linspace(0.6, 0.7, 3), n=64, xtol=1e-12)
    (b,) = curve.boundaries
    assert b.inequality == "gap" and not b.valid_after and 1.0 < b.position < 1.02
    root = bisect(lambda f: solve(5, f, 10, lam=1.0, n=64).validity.gap_margin, 0.6, 0.7,
                  xtol=1e-13)
    assert abs(root - b.at) < 1e-9
    sol = solve(5, root, 10, lam=1.0, n=64)
    tt = np.geomspace(1e-4, 1e-1, 20001)
    assert abs(np.min(sol.gap_at(1.0 + tt) / tt**1.5)) < 1e-8

def test_edge_layer_width_and_thresholded_verdict():
    """A cylinder 2.65 % more distortive than cast iron (delta1/delta2 = 1.0265) has
    positive edge coefficients at both edges: strictly invalid, but its tensile layers
    are e^-3500 half-widths wide (ln width = -a/k with a, k of D22), so it is valid
    against the 1e-6 threshold, and says so.  The bracket a + k ln(1 - s) of (D22)
    has slope k per unit ln(1 - s): checked on delta1/delta2 = 2 between 1 - s = 1e-5
    and 1e-7 to 1 % (observed 0.3 % at n = 128)."""
    from thermocontact.analysis.validity import EDGE_LAYER_TOLERANCE
    sol = solve(5, 0.05, 0.97, k2_over_k1=1.046, delta1_over_delta2=1.0265, lam=-1)
    v = sol.validity
    assert min(v.edge_log_coefficients) > 0 and v.valid and not v.strictly_valid
    assert all(-5000 < lw < -3000 for lw in v.edge_layer_log_widths)
    assert "strictly invalid" in v.reason and "e^-" in v.reason
    sol = solve(5, 0.3, 10, delta1_over_delta2=2, lam=-1, n=128)
    k = sol.validity.edge_log_coefficients[1]
    e = np.array([1e-5, 1e-6, 1e-7])
    bracket = sol.pressure_at(1 - e) / np.sqrt(e)
    assert np.allclose(np.diff(bracket) / (k * np.log(e[1:] / e[:-1])), 1.0, atol=1e-2)
    # The edge margin is the bracket at the tolerated depth (to its model error, 1e-3).
    assert abs(sol.validity.edge_margins[1] - bracket[1] * np.sqrt(1.0)
               - k * np.log(EDGE_LAYER_TOLERANCE / 1e-6)) < 1e-3

@pytest.mark.parametrize("fhpe, lam", [(0.3, -1.0), (0.66, 1.0), (0.4, 3.0)])
def test_margins_are_the_minima_of_the_closed_forms(fhpe, lam):
    """The reported gap and pressure margins (least samples polished on a 17-point
    Chebyshev interpolant) equal Brent's bounded minimisation of the closed forms
    themselves to 1e-12 (observed below 1e-14)."""
    from scipy.optimize import minimize_scalar
    sol = solve(5, fhpe, 10, lam=lam, n=64)
    v = sol.validity
    assert sol.load_ratio > 0
    y0 = np.log(abs(v.gap_margin_at) - 1.0)
    side = np.sign(v.gap_margin_at)
    res = minimize_scalar(lambda y: sol.gap_at([side * (1 + np.exp(y))])[0] / np.exp(1.5 * y),
                          bounds=(y0 - 0.3, y0 + 0.3), method="bounded",
                          options={"xatol": 1e-10})
    assert abs(res.fun - v.gap_margin) < 1e-12
    phi = lambda s: sol.representation.phi_at(sol.phi, np.array([s]))[0]  # noqa: E731
    a = v.pressure_margin_at
    res = minimize_scalar(phi, bounds=(max(a - 0.01, -1), min(a + 0.01, 1)), method="bounded",
                          options={"xatol": 1e-12})
    assert v.pressure_margin <= res.fun + 1e-12


def test_polish_finds_a_closed_forms_minimum_and_keeps_the_sample_where_undefined():
    """Between its neighbours the least sample of (x - 0.3)^2 + 1 is polished to the
    exact minimum 1 at 0.3 (to rounding); a function undefined (NaN) somewhere between
    the neighbours leaves the sampled minimum as it is, never an error."""
    from thermocontact.numerics.extrema import polish_minimum

    x = np.linspace(0.0, 1.0, 6)
    f = lambda t: (t - 0.3) ** 2 + 1.0  # noqa: E731
    at, value = polish_minimum(f, x, f(x), 1)
    assert abs(at - 0.3) < 1e-7 and abs(value - 1.0) < 1e-15
    holed = lambda t: np.where(np.abs(t - 0.25) < 0.02, np.nan, f(t))  # noqa: E731
    assert polish_minimum(holed, x, f(x), 1) == (x[1], f(x[1]))


def test_sampled_margins_equal_the_polished_ones():
    """Margins read off local interpolants of their samples (polish=False, maps) equal
    the closed-form polish to 1e-6 (observed 6.4e-8 for the gap, 1e-14 for the pressure,
    over 216 solutions; here a third of them), with identical verdicts; within 1e-4 of
    zero they are polished on the closed forms, so the verdict is the closed form's."""
    from thermocontact import Model
    from thermocontact.analysis.validity import POLISH_BAND
    worst = [0.0, 0.0]
    for pe, K in ((0.5, 1.0), (5.0, 10.0), (50.0, 100.0)):
        model = Model(pe, K)
        for lam in (-1.0, 0.0, 1.0):
            for f in np.linspace(0.05, 0.8, 8):
                try:
                    a = model.solve_at(32, f, lam=lam)
                except Exception:  # lam beyond the reach of a finite sigma
                    continue
                b = model.solve_at(32, f, lam=lam, polish=False)
                assert a.valid == b.valid
                worst[0] = max(worst[0], abs(a.validity.gap_margin - b.validity.gap_margin))
                worst[1] = max(worst[1], abs(a.validity.pressure_margin
                                             - b.validity.pressure_margin))
                for m in ("gap_margin", "pressure_margin"):
                    if abs(getattr(b.validity, m)) <= POLISH_BAND:
                        assert getattr(b.validity, m) == getattr(a.validity, m)
    assert worst[0] < 1e-6 and worst[1] < 1e-6, worst

def test_overlap_layer_outside_an_edge_is_judged_beyond_the_tolerated_width():
    """Steel on cast iron, lam = 1 (Pe = 46.35, fHPe = 2.79; k > 0 at the leading edge):
    outside that edge g/t^1.5 = b + k' ln t with k' > 0 (its values at t = 1e-8 ... 1e-5
    lie on one straight line in ln t to 1 % of the rise), so the bodies overlap in a
    layer of a few 1e-8 half-widths, the face of the logarithm that makes the tensile
    layer inside.  The gap margin is taken beyond the tolerated width, at t >= 1e-6,
    where it converges (n = 64 and 128: 0.0777 and 0.0772), and the solution is valid."""
    from thermocontact.analysis.validity import EDGE_LAYER_TOLERANCE, gap

    kw = dict(pe=46.35468324286389, fhpe=2.7894821519125217,
              K2_over_K1=0.8016528925619835, k2_over_k1=0.8250431488801054,
              delta1_over_delta2=0.8207398661944115, lam=1.0)
    sols = [solve(n=n, **kw) for n in (64, 128)]
    sol = sols[-1]
    assert sol.validity.edge_log_coefficients[1] > 0
    t = np.array([1e-8, 1e-7, 1e-6, 1e-5])
    g, _ = gap(sol.parameters, sol.representation, sol.phi, sol.psi, sol.load_ratio,
               sol.sigma_over_delta, sol.lam, 1.0 + t)
    m = g / t**1.5
    slope = np.polyfit(np.log(t), m, 1)[0]
    assert slope > 0 and m[0] < 0 < m[2]
    assert np.max(np.abs(np.polyval(np.polyfit(np.log(t), m, 1), np.log(t)) - m)) < 0.01 * (m[-1] - m[0])
    margins = [s.validity.gap_margin for s in sols]
    assert sol.validity.gap_margin_at >= 1.0 + EDGE_LAYER_TOLERANCE
    assert abs(margins[0] - margins[1]) < 1e-3 and sol.valid
    # The sampled margins (maps) agree: the side's samples keep their even spacing in
    # ln t from the tolerated width on.
    from thermocontact import Model

    model = Model(kw["pe"], kw["K2_over_K1"], k2_over_k1=kw["k2_over_k1"],
                  delta1_over_delta2=kw["delta1_over_delta2"])
    sampled = model.solve_at(128, kw["fhpe"], lam=1.0, polish=False).validity
    assert abs(sampled.gap_margin - margins[1]) < 1e-7

def test_a_line_without_heat_forms_no_thermal_kernels():
    """The gaps of solutions all at fHPe = 0 skip the moving bodies' kernels (every
    thermal term is F times them): the same numbers as the same solutions evaluated
    beside a heated one, whose kernels are then formed, to a few ulps (products of
    another shape: conftest.assert_ulps)."""
    from thermocontact import Model
    from thermocontact.analysis.validity import gaps

    m = Model(5.0, 10.0, n=16)
    cold, hot = (m.solve_at(16, f, lam=0.5, check_validity=False) for f in (0.0, 0.3))
    s = np.concatenate([-1.0 - np.geomspace(1e-6, 10, 7), 1.0 + np.geomspace(1e-6, 10, 7)])

    def of(sols):
        def column(get):
            return np.array([get(x) for x in sols])
        return gaps(sols[0].parameters, sols[0].representation, column(lambda x: x.phi),
                    column(lambda x: x.psi), column(lambda x: x.parameters.fhpe),
                    column(lambda x: x.load_ratio), column(lambda x: x.sigma_over_delta),
                    column(lambda x: x.lam), s)
    alone, beside = of([cold]), of([cold, hot])
    assert_ulps(alone[0][0], beside[0][0])
    assert_ulps(alone[1][0], beside[1][0])

def test_fewer_pressure_samples_move_the_margin_by_rounding_only(monkeypatch):
    """The pressure margin from pressure_samples(n) samples (513 up to n = 32, 32 a
    period of the highest cosine) equals the one from 2049 to 1e-11, sampled
    (polish=False) or polished, with the same verdicts, at n = 8, 16 and 32 (observed
    2.7e-12 here, on a sampled margin of -0.82; 5.9e-13 over a 200 x 200 map)."""
    import thermocontact.analysis.validity as validity
    from thermocontact import Model

    assert [validity.pressure_samples(n) for n in (8, 32, 64, 128, 1024)] == [
        513, 513, 1025, 2049, 2049]
    cases = []
    for pe, K in ((0.5, 1.0), (5.0, 10.0), (50.0, 100.0)):
        model = Model(pe, K)
        for n in (8, 16, 32):
            for lam, f in ((-1.0, 0.3), (1.0, 0.66), (3.0, 0.4), (0.0, 0.05)):
                for polish in (False, True):
                    try:
                        cases.append((model.solve_at(n, f, lam=lam, polish=polish), polish))
                    except Exception:  # lam beyond the reach of a finite sigma
                        pass
    monkeypatch.setattr(validity, "pressure_samples", lambda n: 2049)
    worst = 0.0
    for sol, polish in cases:
        dense = validity.assess(sol.parameters, sol.representation, sol.phi, sol.psi,
                                sol.load_ratio, sol.sigma_over_delta, sol.lam,
                                polish=polish)
        assert dense.valid == sol.valid
        worst = max(worst, abs(dense.pressure_margin - sol.validity.pressure_margin))
    assert len(cases) > 50 and worst < 1e-11, worst

def test_edge_brackets_of_many_solutions_are_each_as_alone():
    """The edge margins, layers and their log widths of many solutions, formed per edge
    for all at once, equal the same formulas applied to each solution and edge alone
    (D22, D22b) to two ulps of each value (NaN where NaN, the signs of zero, and the
    layers' verdicts exactly), for both exponents' kinds and with and without the
    Dundurs term's factor."""
    from thermocontact.analysis.validity import (_EDGE_DEPTH, EDGE_LAYER_TOLERANCE,
                                                 _edge_brackets, _expm1_over)

    def alone(p_near, k_log, exponents, t):
        e, count = _EDGE_DEPTH, p_near.shape[0]
        margins, widths = np.zeros((count, 2)), np.full((count, 2), -np.inf)
        layer = np.zeros((count, 2), dtype=bool)
        for j in range(count):
            for i in range(2):
                r, kt = 0.5 - exponents[i], k_log[j, i] * t
                a = p_near[j, i] / e ** exponents[i] - kt * _expm1_over(r, np.log(e))
                at_edge = a - kt / r if r > 0.0 else (-np.inf * np.sign(kt) if kt else a)
                tolerated = a + kt * _expm1_over(r, np.log(EDGE_LAYER_TOLERANCE))
                if kt and at_edge < 0.0:
                    layer[j, i] = True
                    margins[j, i] = tolerated
                    widths[j, i] = (0.0 if a <= 0.0 else -a / kt if r == 0.0
                                    else np.log1p(-a * r / kt) / r)
                else:
                    margins[j, i] = max(tolerated if kt else a, 0.0)
        return margins, widths, layer
    rng = np.random.default_rng(5)
    for alpha in (0.5, 0.3, 0.7):
        for t in (1.0, 0.83):
            p, k = rng.normal(0.0, 1e-2, (3000, 2)), rng.normal(0.0, 1.0, (3000, 2))
            k[::7], k[1::11], p[2::13], p[3::17] = 0.0, -0.0, 0.0, -0.0
            k[5::97], p[6::89], k[8::50], p[9::31] = np.nan, np.nan, 1e-12, 1e4
            exponents = np.array([1.0 - alpha, alpha])
            with np.errstate(all="ignore"):
                expected = alone(p, k, exponents, t)
            for got, want in zip(_edge_brackets(p, k, exponents, t), expected):
                if got.dtype.kind == "f":
                    assert_ulps(got, want, ulps=2, scale="each", equal_nan=True)
                    zero = (got == 0.0) & (want == 0.0)
                    assert np.array_equal(np.signbit(got[zero]), np.signbit(want[zero]))
                else:
                    assert np.array_equal(got, want)
