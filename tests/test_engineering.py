"""The physical front end: dimensional round trip, Hertz in SI units, the branch
finder, units on the command line, temperatures by independent quadrature, and
bad input."""

import json

import numpy as np
import pytest

from conftest import DATA, data_script
from thermocontact import InputError, solve
from thermocontact.cli import main
from thermocontact.analysis.fields import contact_fields, surface_temperatures
from thermocontact.numerics.continuation import secant
from thermocontact.studies.physical_contact import PhysicalProblem, contact
from thermocontact.studies.ray import brackets, follow, interpolated_roots
from thermocontact.problem.materials import MaterialError, get_material

STEEL, IRON = get_material("steel"), get_material("cast-iron")


def problem(**kw):
    args = dict(cylinder=STEEL, half_plane=IRON, radius=0.45, load=2e5, speed=20.0,
                friction=0.35, lam=-1.0)
    args.update(kw)
    return PhysicalProblem(**args)


def test_dimensionless_groups_by_hand():
    """Pe, fHPe and the ratios from their definitions (derivation D13), rel. 1e-14."""
    p = problem()
    d = 1e-5
    A = 2 * (1 - STEEL.nu**2) / STEEL.E + 2 * (1 - IRON.nu**2) / IRON.E
    delta2 = IRON.alpha * (1 + IRON.nu) / IRON.K
    pe = 20.0 * d / (2 * IRON.k)
    dim = p.to_dimensionless(d)
    assert dim["pe"] == pytest.approx(pe, rel=1e-14)
    assert dim["fhpe"] == pytest.approx(0.35 * IRON.k * delta2 / A * pe, rel=1e-14)
    assert dim["K2_over_K1"] == pytest.approx(IRON.K / STEEL.K, rel=1e-14)
    assert dim["k2_over_k1"] == pytest.approx(IRON.k / STEEL.k, rel=1e-14)
    assert dim["delta1_over_delta2"] == pytest.approx(STEEL.distortivity / delta2, rel=1e-14)


def test_round_trip_physical_dimensionless_physical():
    """Pick a half-width, solve the dimensionless problem, turn P_H/P into the load it
    carries; the physical solver given that load returns the half-width (rel. 1e-9)
    and the offset (rel. 1e-7).  The forward solve uses n = 256; the physical solver
    stops where its estimate meets the target 1e-10, and both discretisations agree to
    rounding there (delta1 != delta2: P_H/P and sigma/Delta still converge fast), so
    the round trip tests the inversion itself."""
    p = problem()
    d0 = 1.2e-5
    sol = solve(**p.to_dimensionless(d0), n=256)
    load = p.hertz_load(d0) / sol.load_ratio
    res = contact(problem(load=load), tol=1e-10)
    b = res.primary
    assert b.converged and b.error_estimate <= 1e-10
    assert abs(b.half_width / d0 - 1) < 1e-9
    assert abs(b.offset / (sol.sigma_over_delta * d0) - 1) < 1e-7


def test_friction_zero_is_hertz_in_si():
    """f = 0: the textbook plane-strain Hertz half-width b = sqrt(4 P R / (pi E*)) and
    peak pressure 2P/(pi b), 1/E* = (1-nu1^2)/E1 + (1-nu2^2)/E2, to 1e-10."""
    P, R = 2e5, 0.45
    res = contact(problem(friction=0.0, load=P, radius=R))
    estar = 1 / ((1 - STEEL.nu**2) / STEEL.E + (1 - IRON.nu**2) / IRON.E)
    b = np.sqrt(4 * P * R / (np.pi * estar))
    assert len(res.branches) == 1
    br = res.primary
    assert abs(br.half_width / b - 1) < 1e-10
    assert abs(br.peak_pressure / (2 * P / (np.pi * b)) - 1) < 1e-10
    assert abs(br.offset) < 1e-10 * b and br.valid
    assert br.flash_temperature == 0.0


class _SyntheticRay:
    """``L`` with ``Pe^2 - Pe_H^2 L = (Pe - 1)(Pe - 2)(Pe - 3)/(Pe - 2.5)`` at
    ``Pe_H = 1``: roots of D26 at 1, 2, 3 and a pole at 2.5 between them."""

    calls = 0

    def load_ratio(self, pe, n):
        self.calls += 1
        return pe**2 - (pe - 1) * (pe - 2) * (pe - 3) / (pe - 2.5)


@pytest.mark.parametrize("depth", [0.005, 0.002])
def test_continuation_brackets_three_close_roots(depth):
    """L = 1 + 2x + 2.5x^2 - depth in x = ln Pe, Pe_H = 1: three roots of D26 within a
    factor 1.5 in Pe (0.87 ... 1.24 at depth 0.005), which a step of the continuation
    that predicts L exactly could straddle; each gets its own bracket."""
    class Parabola:
        def load_ratio(self, pe, n):
            x = np.log(pe)
            return 1 + 2 * x + 2.5 * x * x - depth

    pes = np.geomspace(0.1, 10.0, 2001)
    g = pes**2 - Parabola().load_ratio(pes, None)
    dense = pes[np.flatnonzero(np.sign(g[:-1]) != np.sign(g[1:]))]
    assert len(dense) == 3
    scan = follow(Parabola(), 0.1, 10.0, pe_h=1.0)
    found = [(scan.pe[i], scan.pe[i + 1]) for i in brackets(scan.pe, scan.load_ratio, 1.0)]
    assert len(found) == 3 and all(a <= x <= b for (a, b), x in zip(found, dense))


def test_continuation_brackets_every_root_and_the_pole():
    """Following a synthetic ray from Pe = 0.5 to 5 brackets each root and the pole
    in its own step (the pole is rejected later, on the solver, by |h|).  Secant
    steps from the samples' interpolated roots (a first guess only, here within
    7 %) converge to the exact roots to 1e-12."""
    ray = _SyntheticRay()
    scan = follow(ray, 0.5, 5.0, pe_h=1.0)
    found = [(scan.pe[i], scan.pe[i + 1]) for i in brackets(scan.pe, scan.load_ratio, 1.0)]
    assert [a < x < b for (a, b), x in zip(found, (1.0, 2.0, 2.5, 3.0))] == [True] * 4
    assert scan.evaluations == ray.calls and scan.evaluations < 60
    guesses = interpolated_roots(scan.pe, scan.load_ratio, 1.0)

    def h(x):
        return np.exp(2 * x) - ray.load_ratio(np.exp(x), None)
    for x, exact in zip(guesses[:2] + guesses[3:], (1.0, 2.0, 3.0)):
        root, _ = secant(h, x, (h(x + 1e-6) - h(x - 1e-6)) / 2e-6, x - 0.2, x + 0.2)
        assert abs(np.exp(root) - exact) < 1e-12


def test_coupled_contact_has_branch_with_fields():
    """Steel on cast iron, 200 kN/m, 20 m/s, f = 0.35: one valid, converged branch far
    narrower than Hertz; the surface temperatures of the two bodies, from two different
    Green's functions, agree in the contact (perfect thermal contact) to 1e-6 of the
    flash temperature (observed 1.1e-7 at the solver's n = 64: the pointwise residual
    of the heat equation, which test_temperature_mismatch_falls_with_n follows); the
    heat shares add up to f v P."""
    res = contact(problem())
    assert len(res.branches) == 1
    b = res.primary
    assert b.valid and b.converged and b.half_width < res.problem.hertz_half_width
    assert b.temperature_mismatch < 1e-6 * b.flash_temperature
    assert b.heat_cylinder + b.heat_half_plane == pytest.approx(0.35 * 20 * 2e5, rel=1e-14)
    assert b.mean_pressure == pytest.approx(2e5 / (2 * b.half_width), rel=1e-14)


def test_temperature_mismatch_falls_with_n():
    """The two bodies' surface temperatures differ in the contact by the pointwise
    residual of the heat equation, which the projection makes small only as n grows:
    at the steel/cast-iron branch it falls by more than 10 per doubling of n (observed
    2.5e-3, 9.5e-5, 3.0e-6 K at n = 32, 64, 128, against a flash temperature of 881 K)."""
    p = problem()
    d = 1.7648431799916604e-05  # the branch of test_coupled_contact_has_branch_with_fields
    mismatch = [contact_fields(solve(**p.to_dimensionless(d), n=n), length=d, load=p.load,
                               temperature_units=p.temperature_units).temperature_mismatch
                for n in (32, 64, 128)]
    assert mismatch[0] > 10 * mismatch[1] > 100 * mismatch[2]
    assert mismatch[2] < 1e-8 * 881


@pytest.fixture(scope="module")
def moving_source():
    """The Carslaw-Jaeger references (``tests/data/make_moving_source_references.py``)."""
    return data_script("make_moving_source_references")


@pytest.mark.parametrize("case", json.loads(
    (DATA / "moving_source_references.json").read_text())["cases"],
    ids=lambda c: f"speed2={c['speed2']}")
def test_temperature_against_carslaw_jaeger_quadrature(moving_source, case):
    """Each moving body's surface temperature equals an independent adaptive quadrature
    of the Carslaw-Jaeger moving line source, T(x) = (1/(pi K)) int q(xi) exp(-u)
    K0(|u|) dxi, u = v(x - xi)/(2 k) with its own signed speed, over the solution's own
    flux (to 1e-8 relative; stored by the script, the solution checked to be the same
    one to 1e-12): the cylinder's; with the half-plane moving toward +x (section 5b),
    the half-plane's too, over its own incoming temperature.  One point is integrated
    again here."""
    speed2 = case["speed2"]
    sol = moving_source.solution(speed2)
    assert abs(sol.load_ratio / case["load_ratio"] - 1) < 1e-12
    assert abs(sol.sigma_over_delta - case["sigma_over_delta"]) < 1e-12
    p = moving_source.problem(speed2)
    s = np.array(moving_source.POINTS)
    temps = surface_temperatures(sol, s, temperature_units=p.temperature_units)
    for body, stored in zip(moving_source.bodies(speed2), case["temperatures"]):
        assert np.all(np.abs(temps[body] / np.array(stored) - 1) < 1e-8)
    if speed2 == 0.0:
        live = moving_source.moving_source(sol, speed2, s[1], 0)
        assert abs(temps[0][1] / live - 1) < 1e-8


ARGS = ["contact", "--cylinder", "steel", "--half-plane", "cast-iron", "--friction", "0",
        "--lam", "-1", "--json"]


def test_units_on_command_line(capsys):
    """450mm, 200kN/m and 72km/h give the same result as 0.45, 2e5 and 20 in SI."""
    assert main(ARGS + ["--radius", "450mm", "--load", "200kN/m", "--speed", "72km/h"]) == 0
    with_units = json.loads(capsys.readouterr().out)
    assert main(ARGS + ["--radius", "0.45", "--load", "2e5", "--speed", "20"]) == 0
    si = json.loads(capsys.readouterr().out)
    assert with_units["half_width"] == pytest.approx(si["half_width"], rel=1e-14)
    keys = {"half_width", "offset", "a", "b", "peak_pressure", "mean_pressure",
            "hertz_half_width", "hertz_peak_pressure", "pe", "fhpe", "lam", "valid",
            "flash_temperature", "branches"}
    assert keys <= si.keys()


@pytest.mark.parametrize("change,needle", [
    (["--radius", "0"], "radius"),
    (["--radius", "-1mm"], "radius"),
    (["--load", "0"], "load"),
    (["--speed", "-3"], "speed"),
    (["--speed", "3 kg"], "speed"),
    (["--friction", "-0.1"], "friction"),
    (["--cylinder", "stel"], "did you mean"),
    (["--cylinder", "E=0,nu=0.3,alpha=1e-5,K=50,k=1e-5"], "E"),
    (["--cylinder", "E=2e11,nu=0.5,alpha=1e-5,K=50,k=1e-5"], "nu"),
    (["--half-plane", "E=2e11,nu=-1,alpha=1e-5,K=50,k=1e-5"], "nu"),
])
def test_bad_physical_input(capsys, change, needle):
    """Each bad input: exit 2, one line on stderr naming the parameter."""
    base = {"--cylinder": "steel", "--half-plane": "cast-iron", "--radius": "0.45",
            "--load": "2e5", "--speed": "20", "--friction": "0.3", "--lam": "-1"}
    base.update(dict(zip(change[::2], change[1::2])))
    argv = ["contact"] + [x for kv in base.items() for x in kv]
    assert main(argv) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and needle in err[0], err


def test_python_api_validates():
    with pytest.raises(InputError, match="radius"):
        problem(radius=-1.0)
    with pytest.raises(MaterialError, match="did you mean"):
        get_material("copperr")


@pytest.mark.parametrize("lam, width, strict", [(0.5, 69.39e-6, True), (0.9, 349.4e-6, False)])
def test_roots_beyond_fhpe_2_5_are_found(lam, width, strict):
    """Steel on cast iron, 200 kN/m at 72 km/h, f = 0.35: the half-widths that carry
    the load lie at fHPe = 2.85 (lam = 0.5) and 14.2 (lam = 0.9), beyond the
    fHPe = 2.5 where the scan used to stop, and are returned with their validity: the
    second has a positive edge coefficient at the leading edge (strictly invalid) whose
    tensile layer is e^-1258 half-widths wide (valid against the threshold).  A plain
    solve at that half-width gives P_H/P = (Delta/Delta_H)^2 to 1e-6 (the branch's
    error target), and the searched range is reported."""
    p = PhysicalProblem(get_material("steel"), get_material("cast-iron"), 0.45, 2e5, 20.0,
                        0.35, lam, dundurs=False)  # the paper's model, as these were found
    res = contact(p)
    (b,) = [b for b in res.branches if abs(b.half_width / width - 1) < 1e-3]
    v = b.solution.validity
    assert b.valid and v.strictly_valid is strict and res.primary is b
    sol = solve(**p.to_dimensionless(b.half_width))
    assert abs(sol.load_ratio / (b.half_width / p.hertz_half_width) ** 2 - 1) < 1e-6
    assert res.searched[3] > 14.2
    if not strict:
        assert "strictly invalid" in v.reason and v.edge_layer_log_widths[1] < -1000


def test_flash_temperature_and_peak_pressure_are_true_maxima():
    """Steel on cast iron (lam = -1): the flash temperature and the peak pressure are the
    maxima of the closed forms, not of 199 samples: no value on a 4001-point grid of
    the contact exceeds them (to 1e-12 relative), and they exceed the grid's maximum
    by less than the grid can miss (observed: equal to 1e-7)."""
    p = PhysicalProblem(get_material("steel"), get_material("cast-iron"), 0.45, 2e5, 20.0,
                        0.35, -1.0)
    b = contact(p).primary
    s = np.linspace(-1.0, 1.0, 4001)
    t1 = surface_temperatures(b.solution, s, temperature_units=p.temperature_units)[0]
    pr = p.load / b.half_width * b.solution.pressure_at(s)
    for top, dense in ((b.flash_temperature, t1.max()), (b.peak_pressure, pr.max())):
        assert dense <= top * (1 + 1e-12) and top - dense < 1e-6 * abs(top)
