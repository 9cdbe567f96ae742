"""The far temperatures as the closure of the heat partition (derivation section 17):
lam an output, the limits of the closure, the sink law's constant and the layer."""

import numpy as np
import pytest
from scipy.integrate import quad
from scipy.special import sici

from thermocontact import BulkTemperatures, FarTemperatures, solve
from thermocontact.analysis.fields import contact_fields
from thermocontact.problem.closure import Temperatures, layer_sink_distance
from thermocontact.problem.validation import InputError
from thermocontact.solvers.single_patch import Model


@pytest.mark.parametrize("kw, temperatures", [
    (dict(), (0.5, 10.0)),
    (dict(), (-2.0, 3.0)),
    (dict(speed_ratio=-0.5, delta1_over_delta2=0.5), (0.3, None)),
    (dict(beta_f=0.4), (1.0, 30.0)),
    (dict(conductance=(3.0, 0.0)), (0.5, 10.0)),
    (dict(conductance=(3.0, 1.0)), (0.5, 10.0)),
])
def test_the_closures_lam_fed_back_gives_the_same_solution(kw, temperatures):
    """The temperature row replaces the partition row only: the solution with the
    far temperatures, solved again with its own lam given, is the same to 1e-10
    (measured 1e-16 to 2e-14; the pressure's factor to 1e-12)."""
    model = Model(5.0, 10.0, n=32, **kw)
    a = model.solve_at(32, 0.2, temperatures=temperatures)
    b = model.solve_at(32, 0.2, lam=a.lam)
    assert abs(a.load_ratio - b.load_ratio) < 1e-10
    assert abs(a.sigma_over_delta - b.sigma_over_delta) < 1e-10
    assert np.max(np.abs(a.phi - b.phi)) < 1e-10
    assert np.max(np.abs(a.psi - b.psi)) < 1e-10
    assert a.validity.valid == b.validity.valid
    # The closure moves lam: the thermal terms matter here.
    assert abs(a.lam - model.solve_at(32, 0.2, temperatures=(temperatures[0] + 1.0,
                                                             temperatures[1])).lam) > 0.05


def test_lam_comes_back_with_its_estimate():
    """Solved with n chosen, lam carries the Richardson estimate of the refinement,
    which bounds its change to n = 128, and the record says so."""
    sol = solve(5, 0.2, 10, closure=FarTemperatures(1.0, 30), tol=1e-6)
    fine = solve(5, 0.2, 10, closure=FarTemperatures(1.0, 30), n=128)
    assert sol.lam_error is not None and sol.lam_error > 0
    assert abs(sol.lam - fine.lam) <= sol.lam_error
    rec = sol.to_dict()
    assert rec["theta"] == 1.0 and rec["sink_distance"] == 30.0
    assert rec["lam_error"] == sol.lam_error
    # With lam given there is no lam_error, and the record is today's.
    assert "lam_error" not in solve(5, 0.2, 10, lam=sol.lam).to_dict()


def test_high_peclet_split_is_the_effusivity_law():
    """Both surfaces moving the same way at high Peclet numbers with equal incoming
    temperatures: q1/q2 -> e1 sqrt(v1)/(e2 sqrt(v2)), e = sqrt(K rho c) (Jaeger's
    T = (1/K) sqrt(k/(pi v)) integral q/sqrt(xi - x) on both sides), i.e.
    q1/q2 = (K1/K2) sqrt(k2/k1) / sqrt(R).  The error falls as Pe^-2 (observed order
    1.96, 1.98, 1.99 from Pe = 10 to 80)."""
    rho, kappa, R = 2.0, 1.0, 0.5
    ratio = np.sqrt(kappa / R) / rho
    limit = (ratio - 1.0) / (ratio + 1.0)
    errors = [abs(solve(pe, 0.0, rho, k2_over_k1=kappa, speed_ratio=R, closure=FarTemperatures(0.0), n=64).lam
                  - limit) for pe in (10.0, 20.0, 40.0, 80.0)]
    orders = np.log2(np.array(errors[:-1]) / np.array(errors[1:]))
    assert np.all((orders > 1.9) & (orders < 2.1))
    assert errors[-1] < 5e-6


def test_exchanging_the_bodies_exchanges_the_temperatures():
    """(body 1, body 2, Pe, R < 0, Theta) mirrored with the bodies exchanged
    (section 5b) is (body 2, body 1, |R| Pe k2/k1, 1/R, 1/rho, k1/k2, 1/d, F d) with
    Theta' = pi K1 (T1 - T2)/(f v P) = -Theta/rho: lam' = -lam, the same P_H/P, the
    opposite offset."""
    pe, F, rho, kappa, R, d, theta = 2.0, 0.4, 3.0, 2.0, -0.5, 0.5, 0.7
    a = solve(pe, F, rho, k2_over_k1=kappa, delta1_over_delta2=d, speed_ratio=R,
              closure=FarTemperatures(theta), n=64)
    b = solve(abs(R) * pe * kappa, F * d, 1 / rho, k2_over_k1=1 / kappa,
              delta1_over_delta2=1 / d, speed_ratio=1 / R,
              closure=FarTemperatures(-theta / rho), n=64)
    assert abs(a.lam + b.lam) < 1e-11
    assert abs(a.load_ratio - b.load_ratio) < 1e-11
    assert abs(a.sigma_over_delta + b.sigma_over_delta) < 1e-11
    assert abs(a.lam) > 0.05 and abs(a.load_ratio - 1.0) > 0.1


@pytest.mark.parametrize("kw, temperatures", [
    (dict(pe=5.0, fhpe=0.2, K2_over_K1=10.0), (0.5, 10.0)),
    (dict(pe=3.0, fhpe=0.3, K2_over_K1=0.5, k2_over_k1=2.0, speed_ratio=-0.7), (-0.4, None)),
])
def test_the_surfaces_meet_at_the_far_temperatures(kw, temperatures):
    """The fields' evaluator (201 points, independent of the row's n-point mean) finds
    each body's level where the closure put it: a moving half-plane's incoming
    temperature over the cylinder's is T2 - T1, i.e. Theta K1/K2 in the cylinder's
    units; a stationary one's temperature at the sink (D38) is T2, i.e. the level
    that perfect contact gives its logarithm is Theta + ln(L/Delta) (1 - lam)/2 in
    its units.  To 1e-7 at n = 64."""
    sol = solve(**kw, closure=FarTemperatures(temperatures[0], temperatures[1]), n=64)
    rho = sol.parameters.K2_over_K1
    f = contact_fields(sol)                       # units f v P/(pi K1)
    if temperatures[1] is None:
        assert f.half_plane_incoming_temperature == pytest.approx(temperatures[0] / rho,
                                                                  abs=1e-7)
    else:
        # The level of T2 (as shifted by the evaluator) over its logarithm's, in units
        # of f v P/(pi K2): the evaluator's mean of T1 - T2, times rho.
        level = rho * np.nanmean(f.temperature_half_plane - _log_rise(sol))
        expected = temperatures[0] + np.log(temperatures[1]) * 0.5 * (1.0 - sol.lam)
        assert level == pytest.approx(expected, abs=1e-7)


def _log_rise(sol):
    """The stationary half-plane's -integral q2 ln|s - r| dr at the evaluator's points,
    in units of f v P/(pi K1) (its own unit over rho), NaN at the edges."""
    from thermocontact.analysis.fields import SAMPLES, surface_temperatures
    s = np.cos(np.linspace(np.pi, 0.0, SAMPLES))[1:-1]
    _, t2 = surface_temperatures(sol, s)
    return np.concatenate([[np.nan], t2, [np.nan]])


# The sink law (D38) and the layer (D40), against independent quadrature.

def _half_disc(q, a, L, x):
    """The exact surface temperature (times pi K) at x of a half-disc of radius L held
    at 0 on its arc, insulated on its flat face but for the flux q on |xi| < a:
    the full disc's Green's function with the source doubled (the flat face a
    symmetry line), integral q(xi) ln(|L^2 - x xi|/(L |x - xi|)) dxi."""
    f = lambda xi: q(xi) * np.log(abs(L * L - x * xi) / (L * abs(x - xi)))
    return quad(f, -a, x, limit=200, epsabs=1e-13)[0] + quad(f, x, a, limit=200, epsabs=1e-13)[0]


FLUXES = {
    # Q = 1 on |xi| < 1, and the law's constant C(x) = pi K T(x)/Q - ln(L/a) (D38a).
    "uniform": (lambda xi: 0.5 * np.ones_like(xi),
                lambda x: 1.0 - 0.5 * ((1 + x) * np.log1p(x) + (1 - x) * np.log1p(-x))),
    "semi-elliptic": (lambda xi: (2 / np.pi) * np.sqrt(np.maximum(1 - xi * xi, 0.0)),
                      lambda x: 0.5 + np.log(2.0) - x * x),
}


@pytest.mark.parametrize("name", FLUXES)
def test_the_sink_laws_constant_against_quadrature(name):
    """A flux of total Q on |x| < a into a stationary half-plane whose temperature at
    distance L is T2: T - T2 = (Q/(pi K)) (ln(L/a) + C(x/a)) by the law (D38), C(0) =
    1 (uniform) and 1/2 + ln 2 (semi-elliptic).  The exact half-disc of radius L
    (its arc at T2, checked) is the law at the centre to rounding and elsewhere to
    (x^2/(2 L^4)) integral q xi^2 for these symmetric fluxes (observed order 4.0 at
    x = a/2; an asymmetric flux's first moment gives O((a/L)^2))."""
    q, constant = FLUXES[name]
    errors = []
    for L in (4.0, 8.0, 16.0):
        assert _half_disc(q, 1.0, L, 0.0) == pytest.approx(np.log(L) + constant(0.0),
                                                           abs=1e-12)
        exact = _half_disc(q, 1.0, L, 0.5)
        errors.append(abs(exact - (np.log(L) + constant(0.5))))
        second = quad(lambda xi: q(xi) * xi * xi, -1.0, 1.0)[0]
        assert errors[-1] == pytest.approx(0.25 * second / (2 * L**4), rel=0.02)
        # The arc at T2: the field at |z| = L, by the same quadrature.
        z = L * np.exp(-0.7j)
        arc = quad(lambda xi: q(xi) * np.log(abs(L * L - np.conj(z) * xi) / (L * abs(z - xi))),
                   -1.0, 1.0)[0]
        assert abs(arc) < 1e-12
    orders = np.log2(np.array(errors[:-1]) / np.array(errors[1:]))
    assert np.all(np.abs(orders - 4.0) < 0.05)
    # The law's own form by quadrature: integral q ln(L/|x - xi|) at x = 0.3.
    law = sum(quad(lambda xi: q(xi) * np.log(16.0 / abs(0.3 - xi)), lo, hi)[0]
              for lo, hi in ((-1.0, 0.3), (0.3, 1.0)))
    assert law == pytest.approx(np.log(16.0) + constant(0.3), abs=1e-10)


def test_the_layer_is_the_sink_law_with_l_4h_over_pi():
    """A layer of thickness h on an isothermal base: the line source's surface
    temperature, the inverse transform of Q tanh(|k| h)/(K |k|), is (Q/(pi K))
    ln coth(pi |x|/(4h)) (quadrature of the transform to 1e-9), and a flux on |x| < a
    has the sink law's temperature with L = 4h/pi to O((a/h)^2) (observed order 2)."""
    h = 3.0
    for x in (0.3, 1.0, 2.5):
        # integral_0^inf tanh(k h) cos(k x)/k dk = head (k < 1) + the exponentially
        # small tail of (tanh(k h) - 1) + integral_1^inf cos(k x)/k dk = -Ci(x).
        head = quad(lambda k: np.tanh(k * h) / k * np.cos(k * x) if k > 0 else h, 0.0, 1.0,
                    epsabs=1e-13)[0]
        tail = quad(lambda k: (np.tanh(k * h) - 1.0) / k, 1.0, 40.0, weight="cos", wvar=x,
                    epsabs=1e-13)[0]
        transform = head + tail - sici(x)[1]
        assert transform == pytest.approx(np.log(1.0 / np.tanh(np.pi * x / (4 * h))), abs=1e-9)
    errors = []
    q = FLUXES["semi-elliptic"][0]
    for h in (4.0, 8.0, 16.0):
        layer = quad(lambda xi: q(xi) * np.log(1 / np.tanh(np.pi * abs(xi) / (4 * h))),
                     -1.0, 0.0)[0] * 2
        law = np.log(layer_sink_distance(h)) + FLUXES["semi-elliptic"][1](0.0)
        errors.append(abs(layer - law))
    orders = np.log2(np.array(errors[:-1]) / np.array(errors[1:]))
    assert np.all(np.abs(orders - 2.0) < 0.05)
    assert layer_sink_distance(np.pi / 4) == pytest.approx(1.0, abs=1e-15)


@pytest.mark.parametrize("kw, message", [
    (lambda: dict(closure=FarTemperatures(0.0, 1.0)),
     r"sink_distance_over_delta must be in \(1, 1e\+12\]"),
    (lambda: dict(closure=FarTemperatures(0.0)), "stationary half-plane needs sink_distance"),
    (lambda: dict(closure=FarTemperatures(0.0, 5.0), speed_ratio=-0.5),
     "stationary half-plane only"),
    (lambda: dict(closure=FarTemperatures(0.0, 5.0), lam=0.2), "exactly one closure"),
    (lambda: dict(closure=FarTemperatures(None, 5.0)), "is given with theta only"),
    (lambda: dict(closure=FarTemperatures(float("nan"), 5.0)), "theta must be"),
])
def test_bad_closures_are_refused_in_one_line(kw, message):
    """A bad closure is refused in one line, where the value is made or where it is
    solved."""
    with pytest.raises(InputError, match=message) as err:
        solve(5, 0.2, 10, n=16, **kw())
    assert "\n" not in str(err.value)


def test_temperatures_record():
    t = Temperatures(0.5, 20.0)
    assert t.in_unit(2.0) == Temperatures(0.5, 10.0)
    assert t.log_sink == pytest.approx(np.log(20.0), abs=1e-15)
    assert Temperatures(0.5).log_sink == 0.0


def test_solve_command_takes_the_temperatures(capsys):
    """``solve --theta --sink-distance`` is the Python call; a closure given twice is
    refused in one line naming the flags."""
    import json

    from thermocontact.cli import main

    args = ["solve", "--pe", "5", "--fhpe", "0.2", "--K2-over-K1", "10", "-n", "16"]
    assert main(args + ["--theta", "1", "--sink-distance", "30", "--json"]) == 0
    rec = json.loads(capsys.readouterr().out)
    sol = solve(5, 0.2, 10, closure=FarTemperatures(1.0, 30.0), n=16)
    assert rec["lam"] == sol.lam and rec["sink_distance"] == 30.0
    assert main(args + ["--theta", "1", "--sink-distance", "30", "--lam", "0.2"]) == 2
    err = capsys.readouterr().err.strip()
    assert err == ("error: give exactly one of --lam and --sigma (or --theta, the far "
                   "temperatures)")


# The physical front end (derivation section 17; `contact --bulk-temperatures`).

COPPER_ON_STEEL = dict(radius="10mm", load="50kN/m", speed="2m/s", friction=0.2)


@pytest.mark.parametrize("closure", [
    dict(closure=BulkTemperatures("20C", "20C"), speed2="-1m/s"),
    dict(closure=BulkTemperatures("80C", "20C", sink_distance="1mm"))])
def test_contact_with_bulk_temperatures_fed_back_as_lam(closure):
    """The contact found with the bulk temperatures is the one found with its lam
    given, to 1e-10 (measured 2e-16); a moving half-plane's incoming temperature,
    found independently by the fields' evaluator, is T2 - T1 = 0 to 1e-9 K (measured
    2e-12 K, against a flash temperature of 37 K); the absolute peaks are the
    cylinder's bulk temperature plus the flash temperature."""
    import thermocontact as tc

    res = tc.contact("copper", "steel", **COPPER_ON_STEEL, **closure)
    b = res.primary
    again = tc.contact("copper", "steel", **COPPER_ON_STEEL, lam=b.lam,
                       speed2=closure.get("speed2", 0)).primary
    assert again.half_width == pytest.approx(b.half_width, rel=1e-10)
    assert again.offset == pytest.approx(b.offset, rel=1e-10)
    assert 0 < b.lam_error < 1e-8
    t1, t2 = res.problem.bulk_temperatures
    assert b.peak_temperatures == (t1 + b.flash_temperature,) * 2
    assert b.flash_temperatures[1] == pytest.approx(t1 + b.flash_temperature - t2, abs=1e-12)
    assert b.under_limits == (True, True)
    rec = res.to_dict()
    assert rec["lam"] == b.lam and rec["peak_temperatures"] == list(b.peak_temperatures)
    if "speed2" in closure:
        assert abs(b.half_plane_incoming_temperature) < 1e-9
        assert b.flash_temperature > 30


def test_theta_by_hand_and_the_layer_is_its_sink():
    """Theta = pi K2 (T2 - T1)/(f |v1 - v2| P) from the SI inputs, and a layer of
    thickness h is the sink at 4h/pi."""
    from thermocontact.problem.materials import get_material
    from thermocontact.problem.physical import PhysicalProblem

    cu, st = get_material("copper"), get_material("steel")
    p = PhysicalProblem(cu, st, 0.01, 5e4, 2.0, 0.2, None, bulk_temperatures=(353.15, 293.15),
                        layer_thickness=1e-3)
    assert p.theta == pytest.approx(np.pi * st.K * (-60.0) / (0.2 * 2.0 * 5e4), rel=1e-14)
    assert p.sink_length == pytest.approx(4e-3 / np.pi, rel=1e-15)
    q = PhysicalProblem(cu, st, 0.01, 5e4, 2.0, 0.2, None, bulk_temperatures=(353.15, 293.15),
                        sink_distance=4e-3 / np.pi)
    assert p.temperatures(1e-4) == q.temperatures(1e-4)
    far = q.to_dimensionless(1e-4)["closure"]
    assert far.sink_distance_over_delta == pytest.approx(40 / np.pi, rel=1e-14)


@pytest.mark.parametrize("args, message", [
    (["--lam", "1", "--bulk-temperatures", "20C,20C", "--sink-distance", "30mm"],
     "give exactly one of --lam and --bulk-temperatures"),
    (["--bulk-temperatures", "-300C,20C", "--sink-distance", "30mm"],
     "--bulk-temperatures must be >= 0 K"),
    (["--bulk-temperatures", "20C,20C", "--sink-distance", "0.01mm"],
     "--sink-distance must put the sink beyond the contact"),
    (["--bulk-temperatures", "20C,20C"], "needs --sink-distance or --layer-thickness"),
    (["--bulk-temperatures", "20C,20C", "--sink-distance", "3mm", "--layer-thickness", "2mm"],
     "give at most one of --sink-distance and --layer-thickness"),
    (["--bulk-temperatures", "20C,20C", "--speed2", "1", "--sink-distance", "3mm"],
     "--sink-distance applies to a stationary half-plane only"),
    (["--lam", "1", "--layer-thickness", "3mm"], "not --lam, with --layer-thickness"),
])
def test_contact_refuses_bad_closures_in_one_line(capsys, args, message):
    from thermocontact.cli import main

    base = ["contact", "--cylinder", "copper", "--half-plane", "steel", "--radius", "10mm",
            "--load", "50kN/m", "--speed", "2m/s", "--friction", "0.2"]
    assert main(base + args) == 2
    err = capsys.readouterr().err.strip()
    assert err.startswith("error: ") and message in err and "\n" not in err


@pytest.mark.parametrize("name", ["electrical_contact.md", "brake_block.md"])
def test_examples_with_the_bulk_temperatures_print_what_they_show(name, capsys, tmp_path,
                                                                  monkeypatch):
    """Each worked example's command with --bulk-temperatures prints its block (the gear
    example's is its first command, which tests/test_examples.py runs)."""
    import pathlib
    import re
    import shlex

    from thermocontact.cli import main

    text = (pathlib.Path(__file__).parent.parent / "docs" / "examples" / name).read_text()
    blocks = re.findall(r"```console\n((?:(?!```).)*)```\n\n```\n((?:(?!```).)*)```", text, re.S)
    (command, shown), = [(c, o) for c, o in blocks if "--bulk-temperatures" in c]
    monkeypatch.chdir(tmp_path)  # a --plot file goes there
    assert main(shlex.split(command.replace("\\\n", " ").strip()[2:])[1:]) == 0
    assert capsys.readouterr().out == shown


def test_operating_map_at_fixed_bulk_temperatures_is_contact_at_its_points():
    """Each point of the map is the contact at its load and speed: lam (which varies
    over the plane, of either sign), the half-width and the error estimate equal, the
    peak temperature the cylinder's bulk temperature plus the flash temperature."""
    import thermocontact as tc

    kw = dict(cylinder="copper", half_plane="steel", friction=0.2, radius="10mm",
              closure=BulkTemperatures("80C", "20C", sink_distance="2mm"))
    ds = tc.operating_map(tc.Axis("load", 2e4, 2e5, 2, log=True), tc.Axis("speed", 1, 4, 2),
                          **kw)
    lam = ds["lam"].values
    assert lam.min() < 0 < lam.max() and np.all(ds["valid"].values == 1)
    res = tc.contact(load=float(ds["load"][1]), speed=float(ds["speed"][0]), **kw).primary
    assert ds["lam"].values[0, 1] == res.lam
    assert ds["half_width"].values[0, 1] == res.half_width
    # Each point's estimate is its contact's: the solution's and the fields', within
    # the fields' target.
    assert ds["error_estimate"].values[0, 1] == max(res.error_estimate, res.field_error)
    assert np.all(ds["error_estimate"].values <= ds.attrs["field_tol"])
    assert np.allclose(ds["peak_temperature"].values,
                       353.15 + ds["flash_temperature"].values, rtol=0, atol=1e-9)
    assert ds.attrs["picture_field"] == "lam"


def test_paths_move_the_temperature_difference_and_the_sink():
    """A physical path along the sink distance or T2 - T1 (the cylinder's T1 kept)
    follows the branch of the moved problem: its solution is the dimensionless solve
    with that problem's Theta and L/Delta at the same Pe, and a farther sink or a
    hotter half-plane sends more of the heat into the cylinder (lam grows)."""
    from thermocontact.problem.materials import get_material
    from thermocontact.problem.physical import PhysicalProblem
    from thermocontact.studies.physical_contact import _moved, _primary

    p = PhysicalProblem(get_material("copper"), get_material("steel"), 0.01, 5e4, 2.0, 0.2,
                        None, bulk_temperatures=(353.15, 293.15), sink_distance=2e-3)
    q = _moved(p, "temperature_difference", 10.0)
    assert q.bulk_temperatures == (353.15, 363.15) and q.sink_distance == 2e-3
    for along, values in (("sink_distance", (2e-3, 4e-3)), ("temperature_difference",
                                                             (-60.0, 10.0))):
        at = _primary(p, along)
        sols = [at(16, v) for v in values]
        assert sols[1].lam > sols[0].lam + 0.01
        moved = _moved(p, along, values[1])
        pe = sols[1].parameters.pe
        ref = solve(**moved.to_dimensionless(moved.half_width(pe)), n=16)
        assert abs(ref.lam - sols[1].lam) < 1e-12
        assert abs(ref.load_ratio - sols[1].load_ratio) < 1e-12
    with pytest.raises(InputError, match="needs bulk_temperatures"):
        _moved(PhysicalProblem(get_material("copper"), get_material("steel"), 0.01, 5e4, 2.0,
                               0.2, 0.5), "sink_distance", 1e-3)


def test_a_path_along_theta_meets_the_path_along_lam():
    """The gap event along Theta (sink at 10 half-widths) is where the solution's lam
    is the gap event along lam: the same solution, closed two ways (1e-8; measured
    1e-15 at n = 32)."""
    import thermocontact as tc

    kw = dict(pe=5, fhpe=0.7, K2_over_K1=10, n=16)
    lam = [tc.solve(5, 0.7, 10, closure=FarTemperatures(t, 10), n=16).lam for t in (0.0, 1.0)]
    ends = [(target - lam[0]) / (lam[1] - lam[0]) for target in (0.0, 1.0)]
    along_lam = tc.boundary("lam", 0, 1, **kw).events
    along_theta = tc.boundary("theta", *ends, closure=FarTemperatures(None, 10), **kw).events
    assert [e.inequality for e in along_lam] == [e.inequality for e in along_theta] == ["gap"]
    at = tc.solve(5, 0.7, 10, closure=FarTemperatures(along_theta[0].at, 10), n=16).lam
    assert abs(at - along_lam[0].at) < 1e-8


def test_a_dimensionless_map_over_theta_is_solve_at_its_points():
    """Theta as a map's axis (or fixed) with the sink distance L/Delta: each point is
    the solve with that closure; Theta with lam is a closure given twice."""
    import thermocontact as tc

    ds = tc.parameter_map(tc.Axis("fhpe", 0, 0.4, 2), tc.Axis("theta", 0, 1, 2), pe=5,
                          K2_over_K1=10, closure=FarTemperatures(None, 10))
    ref = solve(5, 0.4, 10, closure=FarTemperatures(1.0, 10), tol=1e-6)
    assert abs(ds["lam"].values[1, 1] - ref.lam) < 1e-8
    assert abs(ds["load_ratio"].values[1, 1] - ref.load_ratio) < 1e-8
    with pytest.raises(InputError, match="exactly one of lam and sigma \\(or theta\\)"):
        tc.parameter_map(tc.Axis("fhpe", 0, 0.4, 2), tc.Axis("theta", 0, 1, 2), pe=5,
                         K2_over_K1=10, lam=1.0)
