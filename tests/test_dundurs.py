"""The Dundurs term -(B/2) p of the contact equation (derivation section 5c): the
closed-form isothermal sliding contact, the edge exponents built into the
representation, the direction of sliding, and the edge terms of dissimilar
distortivities."""

import numpy as np
import pytest

from thermocontact import solve
from thermocontact.cli import main
from thermocontact.problem.validation import InputError


def closed_form(B):
    """Isothermal sliding (F = 0) with b = B/2 (D14f): alpha = 1/2 + arctan(b)/pi,
    sigma/Delta = 1 - 2 alpha, P_H/P = 1/(4 alpha (1 - alpha))."""
    alpha = 0.5 + np.arctan(0.5 * B) / np.pi
    return alpha, 1.0 - 2.0 * alpha, 1.0 / (4.0 * alpha * (1.0 - alpha))


@pytest.mark.parametrize("B", [0.6, -1.4, 3.0])
def test_isothermal_sliding_is_the_closed_form(B):
    """Exact at every n (the representation carries the exact solution's weight):
    load ratio and offset to 1e-12, the pressure C (1 - s)^alpha (1 + s)^(1 - alpha)
    to 2e-10 (measured 2.6e-12 at B = 0.6, 2.5e-11 at -1.4 and 1.2e-10 at 3: the
    moments of a weight with the powers tau^(6 alpha + 5) at the edges, which the
    panel rules integrate less exactly than the entire weight of B = 0)."""
    alpha, sigma, L = closed_form(B)
    for n in (8, 32):
        sol = solve(5, 0.0, 10, beta_f=B, lam=-1, n=n)
        assert abs(sol.load_ratio - L) < 1e-12 and abs(sol.sigma_over_delta - sigma) < 1e-12
        s = np.array([-0.999999, -0.5, 0.3, 0.999999])
        C = np.sin(np.pi * alpha) / (2 * np.pi * alpha * (1 - alpha))
        exact = C * (1 - s) ** alpha * (1 + s) ** (1 - alpha)
        assert np.max(abs(sol.pressure_at(s) - exact)) < 2e-10
        assert sol.validity.valid


def test_sliding_direction_reverses_the_term():
    """The friction on the cylinder points along v1 - v2: with the half-plane's
    surface faster (R = 2) the isothermal contact is the mirror image."""
    alpha, sigma, L = closed_form(0.8)
    sol = solve(5, 0.0, 10, beta_f=0.8, speed_ratio=2.0, lam=0.0)
    assert abs(sol.sigma_over_delta + sigma) < 1e-12 and abs(sol.load_ratio - L) < 1e-12
    assert sol.parameters.edge_exponent == pytest.approx(1.0 - alpha, abs=1e-15)


def test_thermal_contact_keeps_its_fast_convergence():
    """With B the edge exponents are built in, so the default method converges as fast
    as without: n = 32 agrees with n = 128 to 1e-12 (Pe = 5, K2/K1 = 10, fHPe = 0.3)."""
    for B in (0.5, -0.5):
        kw = dict(pe=5, fhpe=0.3, K2_over_K1=10, lam=1.0, beta_f=B)
        assert abs(solve(n=32, **kw).load_ratio - solve(n=128, **kw).load_ratio) < 1e-12
        auto = solve(**kw)
        assert auto.n <= 32 and auto.error_estimate < 1e-8


def test_small_term_is_continuous():
    kw = dict(pe=5, fhpe=0.2, K2_over_K1=10, lam=-1)
    base, small = solve(**kw), solve(beta_f=1e-9, **kw)
    assert 0.0 < abs(small.load_ratio - base.load_ratio) < 1e-8
    assert abs(small.sigma_over_delta - base.sigma_over_delta) < 1e-8


def test_edge_term_of_dissimilar_distortivities():
    """With delta1 != delta2 the logarithm of (D22) becomes kappa (1 -+ s)^(1/2),
    kappa = -+ pi k / b (D22b): p/(1 -+ s)^exponent - kappa (1 -+ s)^(1/2 - exponent)
    tends to a constant at both edges (at 1e-5 and 1e-6 within 2e-5), whereas
    without the kappa term it would move by 0.23 between those depths."""
    sol = solve(5, 0.3, 10, delta1_over_delta2=0.5, beta_f=1.0, lam=-1.0, n=256)
    rep, v = sol.representation, sol.validity
    kappa = np.array([np.pi, -np.pi]) * np.array(v.edge_log_coefficients) / sol.parameters.free_term
    for side, exponent, k in ((-1, 1 - rep.alpha, kappa[0]), (1, rep.alpha, kappa[1])):
        e = np.array([1e-5, 1e-6])
        p = rep.pressure_matrix(side * (1 - e)) @ sol.phi
        bracket = p / e**exponent - k * e ** (0.5 - exponent)
        assert abs(bracket[0] - bracket[1]) < 2e-5 * abs(bracket[1])
    assert v.valid and v.strictly_valid


def test_tensile_layer_width_under_the_term():
    """delta1/delta2 = 2, B = 1: heat into the less distortive body at the leading
    edge, whose exponent 0.648 exceeds the edge term's 1/2, opens a tensile layer; its
    width w from the bracket brackets the pressure's sign change (negative at w/2,
    positive at 2w), and the verdict holds it against the tolerated 1e-6."""
    sol = solve(5, 0.3, 10, delta1_over_delta2=2.0, beta_f=1.0, lam=-1.0)
    v = sol.validity
    w = np.exp(v.edge_layer_log_widths[1])
    assert 1e-6 < w < 1e-4 and not v.valid and "tensile layer" in v.reason
    p = sol.representation.pressure_matrix(1.0 - np.array([0.5 * w, 2 * w])) @ sol.phi
    assert p[0] < 0.0 < p[1]
    assert v.edge_layer_log_widths[0] == -np.inf  # exponent 0.352 < 1/2: no layer


def test_methods_without_exponents_refuse_the_term(capsys):
    with pytest.raises(InputError, match="beta_f != 0 needs"):
        solve(5, 0.2, 10, beta_f=0.5, lam=-1, method="galerkin")
    args = ["solve", "--pe", "5", "--fhpe", "0.2", "--K2-over-K1", "10", "--lam", "-1"]
    for bad in (["--beta-f", "0.5", "--method", "product"], ["--beta-f", "25"],
                ["--beta-f", "inf"]):
        assert main(args + bad) == 2
        err = capsys.readouterr().err.strip().splitlines()
        assert len(err) == 1 and "--beta-f" in err[0]  # named as the command line spells it


def test_beta_of_two_materials_is_twice_dundurs_constant():
    """beta of the paper's eq. 10 equals -2 beta_D with Dundurs' own form
    beta_D = [mu1 (kappa2 - 1) - mu2 (kappa1 - 1)] / [mu1 (kappa2 + 1) + mu2 (kappa1 + 1)],
    kappa = 3 - 4 nu (plane strain), i.e. twice Dundurs' constant of the bodies
    labelled the other way; zero for one material, odd under exchange."""
    from thermocontact.problem.materials import dundurs_beta, get_material

    names = ["steel", "cast-iron", "copper", "aluminium-alloy", "alumina"]
    for a in names:
        for b in names:
            m1, m2 = get_material(a), get_material(b)
            k1, k2 = 3 - 4 * m1.nu, 3 - 4 * m2.nu
            beta_d = ((m1.mu * (k2 - 1) - m2.mu * (k1 - 1))
                      / (m1.mu * (k2 + 1) + m2.mu * (k1 + 1)))
            assert dundurs_beta(m1, m2) == pytest.approx(-2 * beta_d, abs=1e-14)
            assert dundurs_beta(m1, m2) == pytest.approx(-dundurs_beta(m2, m1), abs=1e-15)
            assert abs(dundurs_beta(m1, m2)) <= 1.0


def test_physical_contact_keeps_the_term_by_default(capsys):
    """copper on steel, f = 0.3: beta f from the materials enters the solve; the
    paper's model (--no-dundurs) drops it; the dimensionless map refuses the flag."""
    import json

    from thermocontact.problem.materials import dundurs_beta, get_material

    args = ["contact", "--cylinder", "copper", "--half-plane", "steel", "--radius", "50mm",
            "--load", "5kN/m", "--speed", "10", "--friction", "0.3", "--lam", "0", "--json"]
    assert main(args) == 0
    on = json.loads(capsys.readouterr().out)
    assert main(args + ["--no-dundurs"]) == 0
    off = json.loads(capsys.readouterr().out)
    B = dundurs_beta(get_material("copper"), get_material("steel")) * 0.3
    assert on["beta_f"] == pytest.approx(B, rel=1e-14) and off["beta_f"] == 0.0
    sol = solve(on["pe"], on["fhpe"], get_material("steel").K / get_material("copper").K,
                k2_over_k1=get_material("steel").k / get_material("copper").k,
                delta1_over_delta2=(get_material("copper").distortivity
                                    / get_material("steel").distortivity),
                beta_f=B, lam=0.0)
    half = on["half_width"]
    assert on["offset"] == pytest.approx(sol.sigma_over_delta * half, rel=1e-6)
    assert abs(on["offset"] - off["offset"]) > 0.1 * abs(off["offset"])
    assert main(["map", "--x", "fhpe:0:0.5:3", "--y", "pe:1:5:3", "--K2-over-K1", "10",
                 "--lam", "1", "--no-dundurs", "--out", "x.nc"]) == 2
    assert "--dundurs belongs to an operating map" in capsys.readouterr().err


def test_edge_verdict_is_continuous_as_the_term_vanishes():
    """The bracket of (D22b) becomes the logarithm of (D22) as b -> 0: margins and layer
    widths for B = 1e-318, 1e-16 and 1e-3 approach those of B = 0 (delta1/delta2 = 2 and
    0.5, where both edges carry edge terms), without overflow."""
    for d in (2.0, 0.5):
        kw = dict(pe=5, fhpe=0.3, K2_over_K1=10, delta1_over_delta2=d, lam=0.2, n=64)
        ref = solve(**kw).validity
        for B, rel in ((1e-318, 1e-12), (1e-16, 1e-12), (1e-3, 0.2)):
            v = solve(beta_f=B, **kw).validity
            assert v.valid == ref.valid and v.strictly_valid == ref.strictly_valid
            assert np.allclose(v.edge_margins, ref.edge_margins, rtol=rel)
            finite = np.isfinite(ref.edge_layer_log_widths)
            assert np.array_equal(finite, np.isfinite(v.edge_layer_log_widths))
            assert np.allclose(np.array(v.edge_layer_log_widths)[finite],
                               np.array(ref.edge_layer_log_widths)[finite], rtol=rel)


def test_layer_at_an_edge_whose_exponent_is_below_one_half():
    """delta1/delta2 = 0, B = -0.2: the leading edge's exponent is 0.468 < 1/2, so the
    pressure's (1 - s)^0.468 term governs at the very edge; its coefficient is negative
    there and the bracket, positive further in, vanishes at 2.7e-8 half-widths: a
    tolerated layer, whose width brackets the pressure's sign change."""
    sol = solve(5, 0.3, 10, k2_over_k1=10, delta1_over_delta2=0.0, lam=0.8, beta_f=-0.2, n=256)
    v = sol.validity
    w = np.exp(v.edge_layer_log_widths[1])
    assert 1e-8 < w < 1e-7 and v.valid and not v.strictly_valid
    p = sol.representation.pressure_matrix(1.0 - np.array([0.5 * w, 2 * w])) @ sol.phi
    assert p[0] < 0.0 < p[1]


def test_margins_are_continuous_where_a_layer_appears():
    """delta1/delta2 = 0, B = -1, Pe = 1: between fHPe = 0.979 and 0.980 a layer opens
    at the leading edge (exponent below 1/2); the margins move by less than 1e-2 and
    the verdict holds, the tolerated band being excluded from the pressure and gap
    margins wherever an edge term exists."""
    a, b = (solve(1, F, 10, delta1_over_delta2=0.0, lam=0.0, beta_f=-1.0, n=64).validity
            for F in (0.979, 0.980))
    assert a.edge_layer_log_widths[1] == -np.inf < b.edge_layer_log_widths[1]
    for name in ("pressure", "gap", "edge"):
        assert abs(a.margins()[name] - b.margins()[name]) < 1e-2
    assert a.valid and b.valid
