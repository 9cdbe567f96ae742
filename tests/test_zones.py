"""Contact sets of several zones (derivation section 14)."""

import numpy as np
import pytest
from numpy.polynomial import Polynomial

from thermocontact.discretisation.operator import outside_operators
from thermocontact.discretisation.representations import EdgeGraded
from thermocontact.problem.parameters import Parameters
from thermocontact.solvers.single_patch import Model
from thermocontact.solvers.zones import ZoneModel


def test_outside_integrals_against_quadrature():
    """The Cauchy kernel's integral from an edge outward (the kernel of
    outside_operators), against adaptive quadrature (QUADPACK) of
    ln|(s - r)/(e - r)| q'(r) dr = ln|...| psi(cos t) dt, in tau (t = T(tau), where psi
    is its cosine series and the logarithm at either edge is tamed by T' ~ tau^2): no
    moment machinery."""
    from scipy.integrate import quad

    from thermocontact.numerics import moment_engine as graded

    rep = EdgeGraded(24)
    psi = np.random.default_rng(1).standard_normal(24)
    a = rep.to_cos @ psi
    for side, tt in ((1.0, 0.3), (-1.0, 0.02)):
        lb, lq = rep.integrate(lambda e: np.log1p(side * tt / e), [side * (1 + tt)],
                               scale=1.0, from_edge=True)

        def f(tau):
            t = float(graded.stretch(np.array([tau]))[0])
            e = 2 * np.sin(t / 2) ** 2 if side > 0 else -2 * np.cos(t / 2) ** 2
            series = float(np.cos(np.arange(24) * tau) @ a)
            return float(np.log1p(side * tt / e)) * series * float(
                graded.stretch_derivative(np.array([tau]))[0])
        ref = quad(f, 0.0, np.pi, epsabs=1e-14, epsrel=1e-12, limit=400)[0]
        assert (lq @ psi)[0] == pytest.approx(ref, rel=1e-9, abs=1e-12)


@pytest.mark.parametrize("args, n, seed", [
    ((5.0, 0.3, 10.0, 10.0, 0.5), 24, 2),
    # The moving half-plane (D32b), on either side of the contact: where its material
    # has and has not yet passed.
    ((3.0, 0.3, 10.0, 4.0, 0.5, 0.6), 20, 5),
    ((3.0, 0.3, 10.0, 4.0, 0.5, -0.4), 20, 5),
])
def test_outside_integrals_are_the_operators_integrated(args, n, seed):
    """d/dtt of the integrated contact and heat operators is the contact and heat
    operator outside (central differences of the closed forms against
    contact_operators and heat_operators)."""
    from thermocontact.discretisation.operator import contact_operators, heat_operators
    par = Parameters(*args)
    rep = EdgeGraded(n)
    rng = np.random.default_rng(seed)
    phi, psi = rng.standard_normal(n), rng.standard_normal(n)
    h = 1e-3
    for side in (1.0, -1.0):
        for tt in (0.2, 0.7):
            # A fourth-order central difference in tt.
            ops = outside_operators(par, rep, side, tt + h * np.array([-2, -1, 1, 2]))
            stencil = np.array([1.0, -8.0, 8.0, -1.0]) / (12 * h)
            s = np.array([side * (1 + tt)])
            C, Tp, Tq = contact_operators(par, rep, s)
            Hp, Hq = heat_operators(par, rep, s)
            for M, ref, v in ((ops[0], C, phi), (ops[1], Tp, phi), (ops[2], Tq, psi),
                              (ops[3], Hp, phi), (ops[4], Hq, psi)):
                deriv = side * stencil @ (M @ v)
                assert deriv == pytest.approx((ref @ v)[0], rel=1e-7, abs=1e-10)


@pytest.mark.parametrize("d, lam", [(1.0, 1.0), (0.5, -0.3)])
def test_one_zone_is_the_single_patch(d, lam):
    """One zone reproduces the core at Pe = Pe_l Delta, fHPe = fHPe_l Delta: P_H/P is
    Delta^2 and sigma/Delta the centre over Delta, to 1e-10 (the same blocks)."""
    pe_l, f_l = 5.0, 0.2
    sol = ZoneModel(10.0, delta1_over_delta2=d, n=32).solve([[-0.9, 0.8]], pe_l, f_l, lam)
    L, sigma = sol.single_patch()
    D = sol.half_widths[0]
    core = Model(pe_l * D, 10.0, delta1_over_delta2=d, n=32).solve_at(32, f_l * D, lam=lam)
    assert L == pytest.approx(core.load_ratio, abs=1e-10)
    assert sigma == pytest.approx(core.sigma_over_delta, abs=1e-10)
    # The margins are the core's in units of l: the gap's times Delta^(1/2), the
    # pressure's over Delta.
    v, vc = sol.validity, core.validity
    assert v.valid == vc.valid
    assert v.pressure_margin == pytest.approx(vc.pressure_margin / D, rel=1e-7)
    assert v.gap_margin == pytest.approx(vc.gap_margin * D**0.5, rel=1e-6)


def test_no_heat_is_hertz():
    sol = ZoneModel(10.0, n=16).solve([[-1.3, 0.7]], 2.0, 0.0, 0.5)
    np.testing.assert_allclose(sol.edges, [[-1.0, 1.0]], atol=1e-12)
    X = np.linspace(-0.999, 0.999, 41)
    np.testing.assert_allclose(sol.pressure_at(X), (2 / np.pi) * np.sqrt(1 - X * X), atol=1e-12)
    assert sol.valid


@pytest.fixture(scope="module")
def quartic():
    """Two zones of the isothermal initial gap g0 = A (X^2 - c^2)^2 (A = 1/32, c = 2),
    solved, with the closed form's edges a, b (section 14)."""
    A, c = 1 / 32, 2.0
    prof = A * Polynomial([-c * c, 0, 1]) ** 2
    sol = ZoneModel(10.0, n=32, profile=prof).solve([[-2.6, -1.4], [1.3, 2.7]], 1.0, 0.0, 0.0)
    return sol, prof, A, np.sqrt(c * c - 0.5 / np.sqrt(A)), np.sqrt(c * c + 0.5 / np.sqrt(A))


def test_two_zones_of_a_quartic_profile_against_the_closed_form(quartic):
    """g0 = A (X^2 - c^2)^2: p = (8A/pi)|X| sqrt((X^2 - a^2)(b^2 - X^2)) on two zones with
    a^2 + b^2 = 2c^2 and b^2 - a^2 = 1/sqrt(A) (section 14)."""
    sol, prof, A, a, b = quartic
    np.testing.assert_allclose(sol.edges, [[-b, -a], [a, b]], atol=1e-12)
    np.testing.assert_allclose(sol.loads, [0.5, 0.5], atol=1e-12)
    s = np.cos(np.linspace(0.01, np.pi - 0.01, 60))
    for centre, half, phi in zip(sol.centres, sol.half_widths, sol.phi):
        X = centre + half * s
        exact = (8 * A / np.pi) * np.abs(X) * np.sqrt((X * X - a * a) * (b * b - X * X))
        np.testing.assert_allclose(sol.representation.pressure_at(phi, s), exact, atol=1e-12)
    assert sol.valid
    assert sol.validity.gap_margin > 0


def test_gap_of_two_zones_against_the_closed_form(quartic):
    """The gap outside two zones (D31a, section 14) against the closed form of the
    quartic profile: the slope mismatch g0'(Y) - (1/2) int p(xi)/(Y - xi) dxi of the
    closed-form pressure is 4 A Y X(Y), X(Y) = +-sqrt((Y^2 - a^2)(Y^2 - b^2)) (+ beyond b,
    - between the zones), checked here by quadrature at three points (the factor 1/2 is
    Hertz's: with p = (2/pi) sqrt(1 - xi^2) it gives the slope X of X^2/2 inside); its
    integral from the edge, 2 A |F(u) - F(+-d)| with u = Y^2 - c^2 and d = (b^2 - a^2)/2,
    against the solver's gap, open between and beyond the zones."""
    from scipy.integrate import quad

    from thermocontact.analysis.zone_validity import zone_gap
    sol, prof, A, a, b = quartic
    c2, d = 0.5 * (a * a + b * b), 0.5 * (b * b - a * a)

    def p(x):
        return (8 * A / np.pi) * abs(x) * np.sqrt(max((x * x - a * a) * (b * b - x * x), 0.0))

    for Y in (0.3, -0.5, 2.9):
        held = sum(quad(lambda x: p(x) / (Y - x), lo, hi, epsabs=1e-14, epsrel=1e-13,
                        limit=200)[0] for lo, hi in ((-b, -a), (a, b)))
        closed = 4 * A * Y * np.sqrt((Y * Y - a * a) * (Y * Y - b * b)) * np.sign(abs(Y) - b)
        assert prof.deriv()(Y) - 0.5 * held == pytest.approx(closed, rel=1e-12)

    def F(u):
        r = np.sqrt(np.maximum(u * u - d * d, 0.0))  # 0 at an edge, less rounding
        return 0.5 * (u * r - d * d * np.log(np.abs(u + r)))
    for X0, X in ((a, [0.5 * a, 0.0]), (b, [1.05 * b, 2 * b])):
        gap = zone_gap(sol.parameters, sol.representation, sol.edges, sol.phi, sol.psi,
                       prof, np.array(X), X0)
        ref = 2 * A * np.abs(F(np.array(X) ** 2 - c2) - F(X0 * X0 - c2))
        np.testing.assert_allclose(gap, ref, rtol=1e-11, atol=1e-12)
        assert np.all(gap > 0)


def test_element_antiderivatives():
    """The second method's closed-form element integrals against adaptive quadrature."""
    from scipy.integrate import quad

    from thermocontact.physics.green_functions import cylinder_displacement, cylinder_temperature
    from thermocontact.discretisation.element_operators import (
        displacement_integral as _displacement_integral, temperature_integral as _temperature_integral)
    for a, b in ((0.1, 2.0), (-1.5, -0.2), (-0.5, 0.7)):
        breaks = [0.0] if a < 0 < b else None
        ref_e = quad(lambda v: cylinder_displacement(np.array(v)), a, b, points=breaks)[0]
        ref_t = quad(lambda v: cylinder_temperature(np.array(v)), a, b, points=breaks)[0]
        assert _displacement_integral(np.array(b)) - _displacement_integral(np.array(a)) == (
            pytest.approx(ref_e, rel=1e-12))
        assert _temperature_integral(np.array(b)) - _temperature_integral(np.array(a)) == (
            pytest.approx(ref_t, rel=1e-9))


def test_two_zones_with_heat_confirmed_by_the_second_method():
    """Two zones of the quartic profile with frictional heat: the element method on
    the undifferentiated Green's functions (an active set on 350 elements) finds the
    same zones, edges within one element and loads within 2e-3."""
    from thermocontact.solvers.elements import solve_elements
    A, c = 1 / 32, 2.0
    prof = A * Polynomial([-c * c, 0, 1]) ** 2
    sol = ZoneModel(10.0, n=32, profile=prof).solve([[-2.6, -1.1], [1.1, 2.6]], 3.0, 0.2, 1.0)
    assert sol.valid
    el = solve_elements(Parameters(3.0, 0.2, 10.0), 1.0, profile=prof, domain=(-3.5, 3.5),
                        elements=350)
    assert el.zones.shape == (2, 2)
    np.testing.assert_allclose(el.zones, sol.edges, atol=1.01 * el.h)
    np.testing.assert_allclose(el.loads, sol.loads, atol=2e-3)
    # Its active set chatters by one element at an edge (the heat flux's edge
    # singularity on constant elements): the state returned has no tension, and the
    # chattering element overlaps by less than 1e-3 of l^2/R (a gap one element from
    # an edge is of order h^(3/2), 3e-3).
    assert el.chatter <= 1
    assert np.all(el.pressure >= 0.0) and el.gap.min() > -1e-3


def test_two_zones_without_symmetry_confirmed_by_the_second_method():
    """A tilted quartic: the gap's return between the zones decides how the load is
    shared (no symmetry to do it); the second method agrees to half an element."""
    from thermocontact.solvers.elements import solve_elements
    prof = Polynomial([0, 0.05]) + (1 / 32) * Polynomial([-4.0, 0, 1]) ** 2
    sol = ZoneModel(10.0, n=32, profile=prof).solve([[-2.6, -1.1], [1.1, 2.6]], 1.0, 0.0, 0.0)
    el = solve_elements(Parameters(1.0, 0.0, 10.0), 0.0, profile=prof, domain=(-3.5, 3.5),
                        elements=500)
    np.testing.assert_allclose(el.zones, sol.edges, atol=0.51 * el.h)
    np.testing.assert_allclose(el.loads, sol.loads, atol=1e-5)
    assert sol.loads[0] == pytest.approx(0.579331, abs=1e-6)


def test_zones_command_solves_and_reports(capsys):
    """`thermocontact zones --json`: one zone followed from Hertz's, the record's keys,
    the zone equal to the single patch at the same load (P_H/P = Delta^2)."""
    import json

    from thermocontact.cli import main
    args = ["zones", "--pe-hertz", "5.43", "--fhpe-hertz", "0.5", "--K2-over-K1", "10",
            "--lam", "1", "-n", "24", "--json"]
    assert main(args) == 0
    rec = json.loads(capsys.readouterr().out)
    assert rec["status"] == "solved" and rec["valid"] is True
    assert {"status", "message", "valid", "zones", "complementarity"} <= rec.keys()
    (zone,) = rec["zones"]
    assert zone["load"] == pytest.approx(1.0, abs=1e-12)
    D = 0.5 * (zone["b"] - zone["a"])
    core = Model(5.43 * D, 10.0, n=24).solve_at(24, 0.5 * D, lam=1.0)
    assert D * D == pytest.approx(core.load_ratio, abs=1e-10)
    assert rec["complementarity"]["pressure_margin"] > 0
    assert rec["complementarity"]["gap_margin"] > 0


def test_past_the_boundary_no_single_zone_and_no_nucleated_zone(capsys):
    """Path (a) past the paper's boundary (Pe = 5, K2/K1 = 10, lam = 1): the single zone
    followed from Hertz's fails where the core's boundary says (fHPe_l = 0.665362 /
    sqrt(P_H/P) = 0.72295), the gap closing just ahead of the leading edge, and a zone
    nucleated there does not hold (Newton's method shrinks it to nothing or merges it
    into the main zone)."""
    from thermocontact.studies.contact_sets import find_contact_set
    res = find_contact_set(5.43, 0.75, 10.0, lam=1.0, n=16)
    assert res.status == "no steady solution"
    assert res.event["fhpe_hertz"] == pytest.approx(0.72295, rel=2e-4)
    assert res.event["failure"].startswith("gap margin")
    assert res.solution is not None and res.solution.valid is False
    nucleated = [a for a in res.attempts if a["tried"] == "zone where the gap closed"]
    assert len(nucleated) == 2
    assert all(a["result"].startswith("no convergence (Newton's method leaves this contact "
                                      "set") for a in nucleated)


def test_contact_zones_in_physical_units(capsys):
    """`contact --zones`: the contact set in metres, newtons and pascals, equal to the
    single patch's valid branch of the same problem (steel on cast iron at 1 m/s); a
    moving half-plane's in tests/test_contact_set_closures.py."""
    import json

    from thermocontact.cli import main
    args = ["contact", "--cylinder", "steel", "--half-plane", "cast-iron", "--radius",
            "450mm", "--load", "200kN/m", "--speed", "1m/s", "--friction", "0.35",
            "--lam", "-1"]
    assert main(args + ["--zones", "--json"]) == 0
    rec = json.loads(capsys.readouterr().out)
    assert main(args + ["--json"]) == 0
    single = json.loads(capsys.readouterr().out)
    (branch,) = [b for b in single["branches"] if b["valid"]]
    (zone,) = rec["zones"]
    assert rec["status"] == "solved" and rec["valid"] is True
    assert zone["load"] == pytest.approx(2e5, rel=1e-12)
    assert zone["a"] == pytest.approx(branch["a"], rel=1e-6)
    assert zone["b"] == pytest.approx(branch["b"], rel=1e-6)
    # The contact set's fields are those of its n = 32 per zone, not refined further;
    # the single patch's are refined to 1e-5 (observed apart: 1.3e-5).
    assert zone["peak_pressure"] == pytest.approx(branch["peak_pressure"], rel=1e-4)
    assert rec["theory_applicable"] is True and rec["theory_reasons"] == []


def test_conductance_in_si_units(capsys, tmp_path):
    """h = h0 (p/p_ref)^m as a Biot number at the mean Hertz pressure P/(2 l):
    Bi0 = h0 (P/(2 l p_ref))^m l/K2 (p_ref omitted: the mean Hertz pressure itself);
    one outside the solved range is refused naming h0 and its allowed range, by
    `contact` and, before any point is computed, by `map`."""
    from thermocontact.cli import main
    from thermocontact.problem.materials import get_material
    from thermocontact.problem.conductance import PhysicalConductance
    from thermocontact.studies.physical_contact import PhysicalProblem
    prob = PhysicalProblem(get_material("steel"), get_material("copper"), 0.01, 3e5, 40.0,
                           0.3, 1.0)
    ell, K2 = prob.hertz_half_width, get_material("copper").K
    p_mean = 3e5 / (2 * ell)
    assert PhysicalConductance(5e6, 0.95, 2e9).biot(prob) == pytest.approx(
        (5e6 * (p_mean / 2e9) ** 0.95 * ell / K2, 0.95), rel=1e-14)
    assert PhysicalConductance(5e6, 0.95).biot(prob)[0] == pytest.approx(5e6 * ell / K2,
                                                                          rel=1e-14)
    # The h0 range the refusal states is the solved Biot range at this load: its ends
    # are accepted, a little beyond them refused.
    import re

    from thermocontact.problem.validation import InputError
    from thermocontact.problem.conductance import BIOT_RANGE
    with pytest.raises(InputError) as err:
        PhysicalConductance(1e300, 0.95, 2e9).biot(prob)
    lo, hi = map(float, re.search(r"h0 must be in \[(\S+), (\S+)\]", str(err.value)).groups())
    factor = (p_mean / 2e9) ** 0.95 * ell / K2
    # (printed to three digits)
    np.testing.assert_allclose([lo * factor, hi * factor], BIOT_RANGE, rtol=5e-3)
    for h0, ok in ((lo * 1.01, True), (hi * 0.99, True), (lo * 0.99, False), (hi * 1.01, False)):
        if ok:
            PhysicalConductance(h0, 0.95, 2e9).biot(prob)
        else:
            with pytest.raises(InputError):
                PhysicalConductance(h0, 0.95, 2e9).biot(prob)
    args = ["--cylinder", "steel", "--half-plane", "copper", "--friction", "0.3", "--lam",
            "1", "--radius", "0.01", "--zones", "--conductance", "1e300:0"]
    assert main(["contact", "--load", "3e5", "--speed", "40"] + args) == 2
    assert "conductance h0 = 1e+300 W/(m^2 K)" in capsys.readouterr().err
    assert main(["map", "--x", "speed:5:40:3", "--y", "load:3e4:3e5:3", "--out",
                 str(tmp_path / "never.nc")] + args) == 2
    err = capsys.readouterr().err
    assert "h0 must be in [" in err and len(err.strip().splitlines()) == 1


def test_interface_conductance_limits():
    """h -> infinity is perfect contact (the temperature equation (D33) undifferentiated
    against (D18) with its closures: edges to 1e-8); h -> 0 lets no temperature
    difference drive the heat across, so q = q1 - q2 is set by lam alone: uniform
    (m = 0) or proportional to the pressure (m = 1)."""
    pe, F, lam = 5.0, 0.3, 0.6
    ref = ZoneModel(10.0, n=32).solve([[-1, 1]], pe, F, lam)
    stiff = ZoneModel(10.0, n=32, conductance=(1e10, 0.0)).solve([[-1.1, 0.9]], pe, F, lam)
    np.testing.assert_allclose(stiff.edges, ref.edges, atol=1e-8)
    errors = {}
    for m in (0.0, 1.0):
        for n in (32, 64):
            weak = ZoneModel(10.0, n=n, conductance=(1e-9, m)).solve([[-1, 1]], pe, F, lam)
            rep, (a, b) = weak.representation, weak.edges[0]
            s = np.cos(np.linspace(0.3, np.pi - 0.3, 40))
            # q = q' + eta p with q' = psi/sqrt(1 - s^2).
            q = (rep.psi_at(weak.psi[0], s) / np.sqrt(1 - s * s)
                 + weak.parameters.eta * rep.pressure_at(weak.phi[0], s))
            expected = (lam / (b - a) if m == 0.0 else lam * rep.pressure_at(weak.phi[0], s))
            errors[m, n] = np.abs(q - expected).max()
            assert weak.heat_partitions.sum() == pytest.approx(lam, abs=1e-12)
    # With m = 1 q vanishes like the pressure at the edges, as the representation
    # does: fast convergence.  With m = 0 q is bounded but not zero at the edges, and
    # q'/sqrt(1 - s^2) carries that only algebraically (observed order above 2).
    assert errors[1.0, 32] < 1e-6 and errors[1.0, 64] < 1e-8
    assert errors[0.0, 64] < 1e-5
    assert np.log2(errors[0.0, 32] / errors[0.0, 64]) > 2.0


def test_conductance_restores_a_single_zone_past_the_boundary(capsys):
    """Path (a), 10 % past the perfect-contact boundary (Pe_l = 5.976 on the ray
    fHPe_l = 0.13307 Pe_l): no steady contact set with perfect contact, one valid zone
    with a conductance that vanishes with the pressure (h0 l/K2 = 10, m = 1)."""
    import json

    from thermocontact.cli import main
    args = ["zones", "--pe-hertz", "5.976", "--fhpe-hertz", "0.795", "--K2-over-K1", "10",
            "--lam", "1", "-n", "16", "--json"]
    assert main(args + ["--conductance", "10:1"]) == 0
    rec = json.loads(capsys.readouterr().out)
    assert rec["status"] == "solved" and rec["valid"] is True and len(rec["zones"]) == 1
    assert main(args) == 0
    rec = json.loads(capsys.readouterr().out)
    assert rec["status"] == "no steady solution" and rec["valid"] is False
    assert main(args + ["--conductance", "10"]) == 2
    assert "--conductance must be h0:m" in capsys.readouterr().err


def test_other_starts_reach_the_same_zone():
    """Uniqueness evidence as the crossing study records it: from Hertz's zone, the
    zone widened, narrowed, shifted or split in two, Newton's method returns to the
    same single zone (or fails); no other valid contact set appears."""
    from thermocontact.studies.contact_sets import other_starts
    model = ZoneModel(10.0, n=16)
    sol = model.solve([[-1.3, 0.7]], 5.0, 0.5, 1.0)
    outcomes = {o["start"]: o for o in other_starts(model, sol, 1.0)}
    assert len(outcomes) == 6
    split = outcomes.pop("split in two")
    assert all(o["same"] and o["valid"] for o in outcomes.values())
    # The split: one part shrinks to nothing (or Newton's method reaches the zone).
    assert split.get("same", True) or not split["valid"]


def test_conductance_jacobian_is_the_derivative():
    """The temperature rows' derivative through Bi(p) (Newton's method for m != 0)
    against a difference of the rows themselves."""
    model = ZoneModel(10.0, n=16, conductance=(10.0, 1.0))
    system = model.system([[-1.0, 0.9]], 5.0, 0.5, 1.0)
    rep = model.representation()
    rows = [rep.pressure_rows(sh, ah) for sh, ah in system.points]
    cond = model.conductance
    x = np.random.default_rng(3).standard_normal(system.b.size)
    x[:16] = np.abs(x[:16]) + 1.0  # a positive pressure, away from the clipping

    def rows_times(x):
        p = [r @ x[:16] for r in rows]
        return system.matrix(0.5, [cond.biot(q) for q in p], 0.7) @ x, p
    r0, p = rows_times(x)
    J = system.matrix(0.5, [cond.biot(q) for q in p], 0.7) + system.conductance_jacobian(
        x, [cond.biot(q) for q in p], [cond.dbiot(q) for q in p], rows, 0.7)
    v = 1e-6 * np.random.default_rng(4).standard_normal(x.size)
    np.testing.assert_allclose(rows_times(x + v)[0] - r0, J @ v, atol=1e-10 * np.abs(J @ v).max())


def test_a_stalled_path_is_followed_again_with_twice_the_unknowns(monkeypatch):
    """Where the continuation cannot follow the path with n unknowns per zone it is
    followed once more with 2n, and the answer says both; a path that fails for a
    physical reason (no steady solution) is not repeated."""
    from thermocontact.studies import contact_sets as cs
    calls = []

    def follow(path, *args, n, **kwargs):
        calls.append(n)
        if n < 20:
            return cs.ContactSetResult("not converged", "stalled at fHPe_l = 0.5", None)
        return cs.ContactSetResult("solved", "one zone", None)
    monkeypatch.setattr(cs, "follow_contact_set", follow)
    res = cs.find_contact_set(5.0, 1.0, 10.0, lam=1.0, n=12)
    assert calls == [12, 24] and res.status == "solved"
    assert res.message == "one zone (with n = 24: with n = 12, stalled at fHPe_l = 0.5)"
    calls.clear()
    monkeypatch.setattr(cs, "follow_contact_set", lambda *a, n, **k: calls.append(n) or
                        cs.ContactSetResult("no steady solution", "gap closes", None))
    assert cs.find_contact_set(5.0, 1.0, 10.0, lam=1.0, n=12).status == "no steady solution"
    assert calls == [12]


def test_a_set_found_short_of_the_point_is_not_the_answer():
    """Where the path stops short (not converged, a fold), the last set followed is
    reported as such, never as the answer's zones or validity at the point asked for."""
    from thermocontact.studies.contact_sets import ContactSetResult
    hertz = ZoneModel(10.0, n=8).solve([[-1.0, 1.0]], 2.0, 0.0, 1.0)
    rec = ContactSetResult("not converged", "stalled", hertz, reached=0.3).to_dict()
    assert rec["valid"] is None and rec["zones"] == [] and rec["complementarity"] is None
    assert rec["last_followed"]["t"] == 0.3 and rec["last_followed"]["valid"] is True
    done = ContactSetResult("solved", "one zone", hertz).to_dict()
    assert done["valid"] is True and len(done["zones"]) == 1 and "last_followed" not in done


def test_a_contact_set_far_past_what_the_steps_resolve_ends_within_its_budget(monkeypatch):
    """fHPe_l = 1e6 (the single zone fails near 5; the continuation's steps, fractions
    of the path, never resolve it): the evaluations of the defects, both resolutions
    together, stop at the budget, "not converged" with where the zone got to, and the
    progress is told even though no step is accepted."""
    from thermocontact import contact_set
    from thermocontact.studies import contact_sets

    evaluations = []
    defects = ZoneModel.defects
    monkeypatch.setattr(ZoneModel, "defects",
                        lambda self, *a, **k: evaluations.append(1) or defects(self, *a, **k))
    monkeypatch.setattr(contact_sets, "MAX_EVALUATIONS", 60)
    told = []
    res = contact_set(5, 1e6, 10, lam=0, progress=told.append)
    assert res.status == "not converged" and res.message.startswith(
        "stopped after 60 evaluations of the contact set's defects, the most allowed")
    assert len(evaluations) == 60 and res.reached == 0.0 and res.answer is None
    assert len(told) >= 59 and set(told) == {0.0}
    # Within the budget the same path to a reachable point is answered as before.
    assert contact_set(5.43, 0.3, 10, lam=1, n=16).status == "solved"


def test_a_continuation_needing_too_many_steps_ends_in_bounded_time(monkeypatch):
    """With a step budget of 3 the path from Hertz's zone to fHPe_l = 0.5 (solved in
    more steps without it: test_zones_command_solves_and_reports) ends short of it, as "not converged", naming where it got to; the
    distortivity ratio far past the materials' (1e6) is refused at once."""
    from thermocontact import contact_set
    from thermocontact.problem.validation import InputError
    from thermocontact.studies import contact_sets

    monkeypatch.setattr(contact_sets, "MAX_STEPS", 3)
    res = contact_set(5.43, 0.5, 10, lam=1, n=8)
    assert res.status == "not converged" and "3 steps, the most allowed" in res.message
    assert 0.0 < res.reached < 1.0
    with pytest.raises(InputError, match=r"delta1_over_delta2 must be in \[0, 1000\]"):
        contact_set(5.43, 0.5, 10, lam=1, delta1_over_delta2=1e6)


def test_a_target_beyond_the_range_is_refused_with_its_own_value():
    """fHPe_l = 1e300 is refused naming 1e300, not the first step's 1.25e299."""
    from thermocontact import contact_set
    from thermocontact.problem.validation import InputError

    with pytest.raises(InputError, match=r"fhpe_hertz must be in \[0, 1e\+06\], got 1e\+300"):
        contact_set(5, 1e300, 10, lam=0)
    with pytest.raises(InputError,
                       match=r"pe_hertz must be in \[1e-12, 1e\+06\], got 10000000.0"):
        contact_set(1e7, 0.5, 10, lam=0)


def test_a_physical_contact_set_tells_its_progress():
    """contact_set(cylinder=...) tells the percentage of the path from Hertz's zone followed,
    up to 100 at the answer (the command shows it after 2 s)."""
    from thermocontact import contact_set

    told = []
    found = contact_set(cylinder="steel", half_plane="copper", radius=0.01, load=1e4,
                        speed=2.0, friction=0.3, lam=1.0, dundurs=False,
                        progress=lambda done, total: told.append((done, total)))
    assert found.status == "solved"
    assert told and told[-1] == (100, 100) and all(t == 100 for _, t in told)
    assert [d for d, _ in told] == sorted(d for d, _ in told)
