"""Contact sets take every closure of the single patch (derivation sections 16, 17): the
heat partition over solve's range, the offset, the far temperatures with a sink or a
moving half-plane, and the bulk temperatures in physical units; one zone is the single
patch under each of them."""

import json

import numpy as np
import pytest
from numpy.polynomial import Polynomial

from thermocontact.cli import main
from thermocontact.solvers.single_patch import Model
from thermocontact.solvers.zones import ZoneModel

#: Copper on steel with a hot cylinder (and a sink: lam = -63.4), far outside [-1, 1]
#: (the cylinder gives heat to the contact).
HOT = ["--cylinder", "copper", "--half-plane", "steel", "--radius", "10mm", "--load",
       "10kN/m", "--speed", "0.2m/s", "--friction", "0.1", "--bulk-temperatures",
       "200C,20C", "--json"]


@pytest.mark.parametrize("model, closure", [
    ({}, {"lam": -0.3}),
    # Beyond [-1, 1]: the formal continuation solve takes, and a hot body's partition.
    ({}, {"lam": 2.0}),
    ({}, {"lam": -63.0}),
    ({}, {"sigma_over_delta": -0.05}),
    ({}, {"temperatures": (0.5, 10.0)}),
    ({"delta1_over_delta2": 0.5}, {"temperatures": (-2.0, 3.0)}),
    # A moving half-plane: Theta alone (its far temperature is its incoming one).
    ({"speed_ratio": -0.5}, {"temperatures": (0.3, None)}),
    # An interface conductance: its constant closed by the temperatures (D41).
    ({"conductance": (3.0, 0.0)}, {"temperatures": (0.5, 10.0)}),
])
def test_one_zone_is_the_single_patch_under_every_closure(model, closure):
    """One zone in units of the Hertz half-width l is the single patch at
    Pe = Pe_l Delta, fHPe = fHPe_l Delta with the same closure (the sink distance L/l
    becoming L/Delta, a conductance's Biot number h0 l/K2 becoming h0 Delta/K2):
    P_H/P = Delta^2, sigma/Delta, lam and the validity to 1e-8 (the same blocks:
    measured 1e-15)."""
    pe_l, f_l = 5.0, 0.1
    sol = ZoneModel(10.0, n=32, **model).solve([[-1.0, 1.0]], pe_l, f_l, **closure)
    L, sigma = sol.single_patch()
    D = sol.half_widths[0]
    if "temperatures" in closure:
        theta, sink = closure["temperatures"]
        closure = {"temperatures": (theta, None if sink is None else sink / D)}
    if "conductance" in model:
        model = dict(model, conductance=(model["conductance"][0] * D, 0.0))
    core = Model(pe_l * D, 10.0, n=32, **model).solve_at(32, f_l * D, **closure)
    assert abs(L - core.load_ratio) < 1e-8
    assert abs(sigma - core.sigma_over_delta) < 1e-8
    assert abs(sol.lam - core.lam) < 1e-8
    assert sol.valid == core.validity.valid
    if "lam" not in closure:  # an output that the closure moved
        assert sol.to_dict()["lam"] == sol.lam and abs(sol.lam) > 0.05


def test_two_zones_held_at_their_far_temperatures():
    """Two zones (the quartic profile, with heat) closed by the far temperatures: the
    fields' evaluator, by its own quadrature at points of both zones, finds the
    surfaces meeting where the closure puts them, rho (T1 - T2 rises) -
    ln(L/l)(1 - lam)/2 = Theta, to 1e-6 (measured 5e-8 at n = 32); solved again with
    the partition it gives, the same edges."""
    from thermocontact.analysis.fields import surface_temperatures

    prof = (1 / 32) * Polynomial([-4.0, 0, 1]) ** 2
    model = ZoneModel(10.0, n=32, profile=prof)
    theta, sink = 0.7, 20.0
    sol = model.solve([[-2.6, -1.1], [1.1, 2.6]], 3.0, 0.2, temperatures=(theta, sink))
    assert sol.zones == 2 and sol.valid
    assert sol.lam == pytest.approx(sol.heat_partitions.sum(), abs=1e-14)
    s = np.cos(np.linspace(0.2, np.pi - 0.2, 9))
    for zone in (0, 1):
        t1, t2 = surface_temperatures(sol, s, zone=zone)
        level = 10.0 * (t1 - t2) - np.log(sink) * 0.5 * (1.0 - sol.lam)
        np.testing.assert_allclose(level, theta, atol=1e-6)
    back = model.solve(sol.edges, 3.0, 0.2, lam=sol.lam, check_validity=False)
    np.testing.assert_allclose(back.edges, sol.edges, atol=1e-9)


def test_zones_command_takes_every_closure(capsys):
    """`zones --lam 2` (refused before as outside [-1, 1]), `--sigma`, `--theta` with
    `--sink-distance`, and `--theta` alone for a moving half-plane with the Dundurs
    term (`--speed-ratio`, `--beta-f`: absent before) answer, each the single patch at
    the same n; what solve refuses is refused in one line naming the flags."""
    base = ["zones", "--pe-hertz", "5.43", "--fhpe-hertz", "0.3", "--K2-over-K1", "10",
            "-n", "16", "--json"]
    moving = ["--theta", "0.3", "--speed-ratio", "-0.5", "--beta-f", "0.1"]
    for closure in (["--lam", "2"], ["--sigma", "-0.05"],
                    ["--theta", "0.5", "--sink-distance", "10"], moving):
        assert main(base + closure) == 0
        rec = json.loads(capsys.readouterr().out)
        assert rec["status"] == "solved" and rec["valid"] is True
        (zone,) = rec["zones"]
        D = 0.5 * (zone["b"] - zone["a"])
        kw = ({"lam": 2.0} if closure[0] == "--lam" else
              {"sigma_over_delta": -0.05} if closure[0] == "--sigma" else
              {"temperatures": (0.3, None)} if closure is moving else
              {"temperatures": (0.5, 10.0 / D)})
        model = {"speed_ratio": -0.5, "beta_f": 0.1} if closure is moving else {}
        core = Model(5.43 * D, 10.0, n=16, **model).solve_at(16, 0.3 * D, **kw)
        assert D * D == pytest.approx(core.load_ratio, abs=1e-8)
        assert rec["lam"] == pytest.approx(core.lam, abs=1e-8)
    for args, message in (
            (["--theta", "0.5"], "a stationary half-plane needs --sink-distance"),
            (["--sink-distance", "10", "--lam", "1"], "--sink-distance is given with "
             "--theta only"),
            (["--lam", "1e7"], "--lam must be in [-1e+06, 1e+06], got 10000000.0"),
            (["--lam", "1", "--theta", "1"], "give exactly one of --lam and --sigma"),
            (["--theta", "2e6", "--sink-distance", "10"], "--theta must be in [-1e+06, 1e+06]"),
            (["--lam", "1", "--speed-ratio", "1"], "--speed-ratio 1 is pure rolling, which "
             "makes no frictional heat: --fhpe-hertz must be 0 there, got 0.3")):
        assert main(base + args) == 2
        err = capsys.readouterr().err.strip().splitlines()
        assert len(err) == 1 and message in err[0], err
    assert main(["zones", "--pe-hertz", "5", "--fhpe-hertz", "0", "--K2-over-K1", "10",
                 "--sigma", "0.1"]) == 2
    assert "--sigma cannot be imposed when --fhpe-hertz = 0" in capsys.readouterr().err


def test_contact_zones_with_bulk_temperatures_is_the_single_patch(capsys):
    """`contact --zones --bulk-temperatures ... --sink-distance` (refused before) for a
    hot copper cylinder on steel, whose partition is -63: the one valid zone (n = 32)
    equals the single patch's branch (its fields refined to their own target, from
    n = 32) to 1e-8 in its edges, lam and the peak temperature."""
    args = HOT + ["--sink-distance", "2mm"]
    assert main(["contact"] + args) == 0
    (branch,) = json.loads(capsys.readouterr().out)["branches"]
    assert main(["contact", "--zones"] + args) == 0
    rec = json.loads(capsys.readouterr().out)
    assert rec["status"] == "solved" and rec["valid"] is True
    assert rec["dimensionless"]["n"] == 32 and branch["n"] >= 32
    (zone,) = rec["zones"]
    ell = rec["hertz_half_width"]
    assert abs(zone["a"] - branch["a"]) < 1e-8 * ell
    assert abs(zone["b"] - branch["b"]) < 1e-8 * ell
    assert rec["lam"] == pytest.approx(branch["lam"], abs=1e-8) and rec["lam"] < -60
    assert rec["peak_temperature"] == pytest.approx(branch["peak_temperatures"][0], abs=1e-6)
    assert rec["bulk_temperatures"] == pytest.approx([473.15, 293.15], abs=1e-12)


def test_contact_zones_of_a_moving_half_plane_hold_its_model(capsys, monkeypatch):
    """`contact --zones --speed2` (refused before): the contact set is sought with the
    single patch's dimensionless groups, the speed ratio v2/v1 and the Dundurs term
    among them, and the incoming temperatures without a sink (the solve itself is the
    zone model's, checked against the single patch with a moving half-plane in
    `test_zones_command_takes_every_closure`; a stand-in here)."""
    from thermocontact.studies import contact_sets
    from thermocontact.studies.physical_contact import PhysicalProblem

    seen = {}

    def stand_in(*args, **kwargs):
        seen.update(kwargs, args=args)
        raise contact_sets.SolveError("stand-in")
    monkeypatch.setattr(contact_sets, "find_contact_set", stand_in)
    assert main(["contact", "--zones", "--speed2=-0.1m/s"] + HOT) == 2
    assert "stand-in" in capsys.readouterr().err
    from thermocontact.problem.materials import get_material
    problem = PhysicalProblem(get_material("copper"), get_material("steel"), 0.01, 1e4, 0.2,
                              0.1, None, speed2=-0.1, bulk_temperatures=(473.15, 293.15))
    groups = problem.ray_parameters()
    assert seen["speed_ratio"] == -0.5 == groups["speed_ratio"]
    assert seen["beta_f"] == groups["beta_f"] != 0.0
    assert seen["temperatures"].sink_distance is None
    assert seen["args"][:3] == (problem.pe_hertz, problem.fhpe(problem.hertz_half_width),
                                groups["K2_over_K1"])


def test_a_formal_partition_far_out_ends_within_the_budget(monkeypatch):
    """lam = 1e6, the end of solve's range (at which the path ran for minutes before the
    budget): answered, "not converged" within the evaluations allowed, the progress
    told at each of them."""
    from thermocontact import contact_set
    from thermocontact.studies import contact_sets

    monkeypatch.setattr(contact_sets, "MAX_EVALUATIONS", 40)
    told = []
    res = contact_set(5.43, 0.5, 10, lam=1e6, n=8, progress=told.append)
    assert res.status == "not converged" and res.answer is None
    assert res.message.startswith("stopped after 40 evaluations")
    assert len(told) >= 39


def test_a_map_at_fixed_bulk_temperatures_has_its_contact_sets():
    """`map --zones --bulk-temperatures` (refused before): each point's contact set is
    closed by the temperatures too; where the single patch is valid, the one zone is
    it, edges to 1e-8 of the half-width."""
    import thermocontact as tc

    ds = tc.operating_map(tc.Axis("speed", 0.2, 2.0, 2), tc.Axis("load", 1e4, 5e4, 2),
                          cylinder="copper", half_plane="steel", radius="10mm",
                          friction=0.1, closure=tc.BulkTemperatures("200C", "20C", sink_distance="2mm"),
                          zones=True)
    assert (ds["valid"] == 1).all() and (ds["zones_status"] == "solved").all()
    assert (ds["zones_count"] == 1).all()
    width = ds["half_width"].values
    np.testing.assert_allclose(ds["zones_start"], ds["offset"] - width, atol=1e-8 * width.max())
    np.testing.assert_allclose(ds["zones_end"], ds["offset"] + width, atol=1e-8 * width.max())
    assert float(ds["lam"].min()) < -60  # the hot cylinder's partition at 10 kN/m, 0.2 m/s
