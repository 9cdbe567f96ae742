"""Operating maps in physical units: one ray answers the whole load-speed plane."""

import numpy as np
import pytest

from thermocontact.problem.materials import get_material
from thermocontact.problem.validation import InputError
from thermocontact.problem.conductance import PhysicalConductance
from thermocontact.studies.operating_maps import (OperatingSpec, compute_operating_map,
                                                  parse_physical_axis)
from thermocontact.studies.physical_contact import PhysicalProblem, contact

CU, ST = get_material("copper"), get_material("steel")


def spec(x="load:1e3:1e5:2:log", y="speed:0.1:10:2:log", **kw):
    return OperatingSpec(CU, ST, 0.2, -1.0, parse_physical_axis("--x", x),
                         parse_physical_axis("--y", y), {"radius": 0.01, **kw})


def test_load_speed_and_radius_enter_only_through_pe_hertz():
    """Two problems with the same v sqrt(R P) (load x4, speed /2, and radius x4, speed /2)
    have the same dimensionless solution: equal Pe, fHPe and P_H/P of the primary
    branch, half-widths in the ratio of their Hertz half-widths."""
    base = PhysicalProblem(CU, ST, 0.01, 1e4, 2.0, 0.2, -1.0)
    for other in (PhysicalProblem(CU, ST, 0.01, 4e4, 1.0, 0.2, -1.0),
                  PhysicalProblem(CU, ST, 0.04, 1e4, 1.0, 0.2, -1.0)):
        a, b = contact(base).primary, contact(other).primary
        assert b.pe == pytest.approx(a.pe, rel=1e-9)
        assert b.fhpe == pytest.approx(a.fhpe, rel=1e-9)
        assert b.load_ratio == pytest.approx(a.load_ratio, rel=1e-9)
        ratio = other.hertz_half_width / base.hertz_half_width
        assert b.half_width / a.half_width == pytest.approx(ratio, rel=1e-9)


#: The map of the tests below: copper on steel, the steel's surface moving against the
#: copper's at half its speed (R = -1/2), the Dundurs term of the pair; the plane of
#: tests/data/make_operating_points.py.
PLANE = ("load:1e4:2e4:2:log", "speed:0.8:2:2:log")


@pytest.fixture(scope="session")
def small_map(tmp_path_factory):
    """``(spec, dataset, ray)``: the 2 x 2 map of :data:`PLANE`, and its ray (with the
    fields of the plane's points) read back from the map's chunks."""
    from thermocontact.studies.operating_maps import operating_ray

    s = OperatingSpec(CU, ST, 0.2, -1.0, parse_physical_axis("--x", PLANE[0]),
                      parse_physical_axis("--y", PLANE[1]), {"radius": 0.01},
                      speed_ratio=-0.5)
    parts = tmp_path_factory.mktemp("small_map") / "parts"
    ds = compute_operating_map(s, workers=1, store_path=parts)
    return s, ds, operating_ray(s, store_path=parts)


def _stored_contacts() -> dict:
    """`contact` at the map's corners and at 50 random points of its plane
    (tests/data/make_operating_points.py)."""
    import json
    import pathlib

    return json.loads((pathlib.Path(__file__).parent / "data" /
                       "operating_points.json").read_text())


def _equals_contact(point, ref, field_tol):
    """A map's point against `contact` there: half-width and offset to 1e-6, the fields
    to ``field_tol`` relative and within the two sides' estimates, validity and
    applicability exactly.  Returns the largest relative difference of the fields."""
    assert point["half_width"] == pytest.approx(ref["half_width"], rel=1e-6)
    assert point["offset"] == pytest.approx(ref["offset"], rel=1e-6,
                                            abs=1e-9 * ref["half_width"])
    worst = 0.0
    for ours, theirs in ((point["peak_pressure"], ref["peak_pressure"]),
                         (point["flash_temperature"], ref["flash_temperature"]),
                         (point["max_slope_cylinder"], ref["max_slope"][0]),
                         (point["max_slope_half_plane"], ref["max_slope"][1]),
                         (point["max_strain_cylinder"], ref["max_strain"][0]),
                         (point["max_strain_half_plane"], ref["max_strain"][1])):
        error = abs(ours / theirs - 1.0)
        assert error <= field_tol
        assert error <= point["error_estimate"] + ref["field_error"]
        worst = max(worst, error)
    # The samples meet the target and the interpolation adds little here: each point's
    # own estimate meets it too (observed up to 5.6e-6; the errors up to 7.1e-7).
    assert point["error_estimate"] <= field_tol
    assert bool(point["valid"]) == ref["valid"]
    assert bool(point["applicable"]) == ref["applicable"]
    return worst


def test_map_points_equal_contact(small_map):
    """Every point of a 2 x 2 map (load 10-20 kN/m, speed 0.8-2 m/s; the steel
    half-plane's surface moving against the copper cylinder's at half its speed,
    R = -1/2, and the Dundurs term of the pair), read off the one ray, equals `contact`
    at that point (speed2 = R v; stored by tests/data/make_operating_points.py):
    half-width and offset to 1e-6, peak pressure, flash temperature, slopes and strains
    to the fields' target 1e-5 relative (both sides refine their fields to 10 tol,
    tol = 1e-6; the ray is interpolated in ln Pe to degree 5 at 24 samples per decade)
    and within the sum of the two sides' estimates (each below the target), validity
    and applicability exactly."""
    from thermocontact.studies.operating_maps import POINT_FIELDS

    s, ds, _ = small_map
    assert s.manifest()["speed_ratio"] == -0.5
    field_tol = ds.attrs["field_tol"]
    assert field_tol == pytest.approx(1e-5)
    data = _stored_contacts()
    assert data["plane"]["speed_ratio"] == -0.5
    for ref in data["corners"]:
        point = ds.sel(load=ref["load"], speed=ref["speed"])
        _equals_contact({k: float(point[k]) for k in POINT_FIELDS + ("valid", "applicable")},
                        ref, field_tol)


def test_random_points_of_a_map_equal_contact(small_map):
    """50 points drawn at random over the map's plane (log-uniform in load and speed),
    each read off the map's ray as the map reads its grid points
    (:func:`operating_point`), against `contact` at that point, solved on its own
    (stored by tests/data/make_operating_points.py): as the grid's points above.  The
    map's error is within the sum of the two sides' estimates, each below the target
    1e-5."""
    from thermocontact.studies.operating_maps import operating_point

    s, ds, ray = small_map
    data = _stored_contacts()
    assert data["plane"]["load"] == [s.x.start, s.x.stop]
    assert data["plane"]["speed"] == [s.y.start, s.y.stop]
    assert len(data["points"]) == 50
    field_tol = ds.attrs["field_tol"]
    worst = 0.0
    for ref in data["points"]:
        p = operating_point(s, ray, ref["load"], ref["speed"], 0.01)
        assert p["status"] == "solved" and p["branches"] == 1
        assert ref["field_error"] <= field_tol
        worst = max(worst, _equals_contact(p, ref, field_tol))
    assert worst > 0.0  # two routes, not one number twice


def test_fields_refined_to_their_target_from_where_the_load_ratio_met_its_own():
    """The brake block's ray (wheel steel on the organic block, lambda = -1) at
    Pe = 163.77, where P_H/P meets 1e-6 at n = 32 but the fields are 6e-5 off: refined
    from n = 32 (:func:`refine_fields`), the fields' estimate meets the target 1e-5 and
    is above each field's error against n = 256 (stored by
    tests/data/make_operating_points.py; that reference's own error is about 1e-7)."""
    from thermocontact.analysis.fields import contact_fields
    from thermocontact.studies.physical_contact import problem_ray
    from thermocontact.studies.ray import FIELD_QUANTITIES, refine_fields

    ref = _stored_contacts()["brake_fields"]
    prob = PhysicalProblem(get_material("wheel-steel"),
                           get_material("organic-composite-brake-block"), 0.46, 310e3, 30.0,
                           0.3, -1.0)
    ray = problem_ray(prob)
    fine = refine_fields(lambda m: ray.solve_at(ref["pe"], m, polish=False), 32,
                         lambda sol: contact_fields(sol, fractions=prob.compliance_fractions),
                         1e-6)
    assert fine.status == "converged" and fine.estimate <= 1e-5 and fine.n > 32
    level = fine.levels[-1][0]
    errors = [abs(getattr(level, q) / ref["fields"][q] - 1.0) for q in FIELD_QUANTITIES]
    assert max(errors) <= fine.estimate
    # At n = 32 alone (where P_H/P met its target) they were beyond it.
    coarse = fine.levels[1][0]
    assert coarse.solution.n == 32
    assert max(abs(getattr(coarse, q) / ref["fields"][q] - 1.0)
               for q in FIELD_QUANTITIES) > 1e-5


def test_bad_operating_maps_are_refused():
    with pytest.raises(InputError, match="parameter must be one of"):
        parse_physical_axis("--x", "fhpe:0:1:3")
    with pytest.raises(InputError, match="radius must be given"):
        OperatingSpec(CU, ST, 0.2, -1.0, parse_physical_axis("--x", "load:1:2:3"),
                      parse_physical_axis("--y", "speed:1:2:3"), {})
    with pytest.raises(InputError, match="load must be > 0"):
        spec(x="load:-1:2:3")


def test_manifest_holds_the_materials_values():
    """A materials file may redefine a name: the manifest carries the values, so a map
    made with other properties under the same name is refused, not resumed."""
    import dataclasses

    soft = dataclasses.replace(CU, E=60e9)
    assert spec().manifest() != OperatingSpec(
        soft, ST, 0.2, -1.0, parse_physical_axis("--x", "load:1e3:1e5:2:log"),
        parse_physical_axis("--y", "speed:0.1:10:2:log"), {"radius": 0.01}).manifest()


#: Steel on copper, lambda = 1, R = 10 mm: every point of ``zones_map`` a valid single
#: patch of one zone; the heavier load strains the copper beyond 1 %.
STEEL_ON_COPPER = ["--cylinder", "steel", "--half-plane", "copper", "--friction", "0.3",
                   "--lam", "1", "--radius", "0.01"]


@pytest.fixture(scope="module")
def zones_map(tmp_path_factory):
    """``map STEEL_ON_COPPER --x speed:2:5:2 --y load:1e5:2e5:2 --zones`` (the operating
    map and its contact sets, as the command computes it), once for this module, with
    its chunks kept."""
    s = OperatingSpec(ST, CU, 0.3, 1.0, parse_physical_axis("--x", "speed:2:5:2"),
                      parse_physical_axis("--y", "load:1e5:2e5:2"), {"radius": 0.01},
                      zones=True)
    parts = tmp_path_factory.mktemp("zones_map") / "parts"
    return s, compute_operating_map(s, store_path=parts), parts


def test_contact_sets_over_a_map_equal_the_single_patch_where_it_is_valid(zones_map):
    """With --zones every point also gets its contact set, followed from Hertz's zone in
    the friction heat at the point's load (an independent route: the map's single patch
    comes from the one ray in Pe, interpolated). Where the single patch is valid (steel on
    copper, lambda = 1, Pe_H 1.1-3.8), the contact set is that one zone: edges to 1e-8 of
    the half-width (observed 5e-10), peak pressure to 1e-4 relative (the contact set's at
    its n = 32, the map's refined to 1e-5), the whole load. The
    contact sets are kept beside the ray's chunks and a second run reads them back."""
    s, ds, parts = zones_map
    assert (ds.valid.values == 1).all()
    assert (ds.zones_status.values == "solved").all() and (ds.zones_count.values == 1).all()
    assert (ds.zones_valid.values == 1).all()
    # The heavier load strains the copper beyond 1 %: both say so (the map's only
    # reason here; both measure strain as peak pressure x compliance).
    assert ds.applicable.values.tolist() == [[1, 1], [0, 0]]
    assert (ds.zones_applicable.values == ds.applicable.values).all()
    d = ds.half_width.values
    np.testing.assert_allclose(ds.zones_start.values, (ds.offset - ds.half_width).values,
                               rtol=0, atol=1e-8 * d.min())
    np.testing.assert_allclose(ds.zones_end.values, (ds.offset + ds.half_width).values,
                               rtol=0, atol=1e-8 * d.min())
    # The contact set's peak pressure is that of its own n = 32 per zone, not refined
    # further; the map's fields are refined to 1e-5 (observed apart: 5.4e-5).
    np.testing.assert_allclose(ds.zones_peak_pressure.values, ds.peak_pressure.values,
                               rtol=1e-4)
    np.testing.assert_allclose(ds.zones_load.values, ds["load"].values[:, None] + 0 * d,
                               rtol=1e-12)
    assert sorted(p.name for p in (parts / "contact_sets").iterdir()) == [
        "chunk-000000.json", "chunk-000001.json", "manifest.json"]
    assert compute_operating_map(s, store_path=parts).identical(ds)


def test_one_point_one_answer_from_every_command(zones_map, capsys):
    """The same operating point (steel on copper, 200 kN/m at 2 m/s, the map's corner)
    through `contact`, `contact --zones` (one zone), the operating map and `map --zones`:
    the same `applicable`, the same reasons (here the copper's strain, one judgement in
    one wording) and the same flash temperature: the contact set's to 1e-8 (its own
    solve, n = 32 per zone, to 1e-4 of the single patch's refined fields), the map's to
    1e-5, the fields' target of both. The contact set's slopes and strains equal the
    map's to 1e-5 as well."""
    import json

    from thermocontact.cli import main

    _, ds, _ = zones_map
    point = ["--load", "2e5", "--speed", "2", "--json"]
    args = STEEL_ON_COPPER
    assert main(["contact", *args, *point]) == 0
    patch = json.loads(capsys.readouterr().out)
    assert main(["contact", *args, *point, "--zones"]) == 0
    zones = json.loads(capsys.readouterr().out)
    here = ds.sel(load=2e5, speed=2.0)
    assert len(zones["zones"]) == 1 and zones["status"] == "solved"
    # The map's contact set comes from the valid single patch's edges by Newton's
    # method, `contact --zones` follows it from Hertz's zone: the same zone.
    assert "single patch" in str(here.zones_message.values)
    assert "Hertz" in zones["message"]
    d = float(here.half_width)
    assert float(here.zones_start) == pytest.approx(zones["zones"][0]["a"], rel=0, abs=1e-8 * d)
    assert float(here.zones_end) == pytest.approx(zones["zones"][0]["b"], rel=0, abs=1e-8 * d)
    reasons = patch["applicability_reasons"]
    assert reasons and "half-plane strain" in reasons[0]  # not vacuous
    for applicable, why in (
            (zones["applicable"], zones["applicability_reasons"]),
            (zones["theory_applicable"], zones["theory_reasons"]),
            (bool(here.applicable), str(here.applicability_reasons.values).split("; ")),
            (bool(here.zones_applicable),
             str(here.zones_applicability_reasons.values).split("; "))):
        assert applicable is patch["applicable"] is False
        assert why == reasons
    assert str(here.reason.values) == "valid; not applicable: " + "; ".join(reasons)
    flash = patch["flash_temperature"]
    assert zones["flash_temperature"] == pytest.approx(float(here.zones_flash_temperature),
                                                       rel=1e-8)
    # The contact set's fields are those of its n = 32 per zone, not refined further;
    # the single patch's and the map's are refined to 1e-5.
    assert zones["flash_temperature"] == pytest.approx(flash, rel=1e-4)
    assert float(here.flash_temperature) == pytest.approx(flash, rel=1e-5)
    for i, body in enumerate(("cylinder", "half_plane")):
        # (The contact set's at its n = 32 again: observed 1.7e-5 apart.)
        assert zones["max_slope"][i] == pytest.approx(float(here[f"max_slope_{body}"]),
                                                      rel=1e-4)
        assert zones["max_strain"][i] == pytest.approx(float(here[f"max_strain_{body}"]),
                                                       rel=1e-4)


def test_contact_set_with_a_conductance_starts_from_the_single_patch(zones_map):
    """With a conductance, Newton's method from a valid single patch's edges (the map's,
    interpolated along its ray) finds the conductance's own zone: its defects vanish with
    the conductance (to 1e-12) and not without it, and it is the zone that `contact
    --zones --conductance 5e6:0.95:2GPa` follows from Hertz's at this point (steel on
    copper, 200 kN/m at 2 m/s; that command's edges, to 1e-8 of the half-width)."""
    from thermocontact.solvers.zones import ZoneModel
    from thermocontact.studies.contact_sets import physical_contact_set

    _, ds, _ = zones_map
    here = ds.sel(load=2e5, speed=2.0)
    p = PhysicalProblem(ST, CU, 0.01, 2e5, 2.0, 0.3, 1.0)
    cond = PhysicalConductance(5e6, 0.95, 2e9)
    start = (float(here.offset - here.half_width), float(here.offset + here.half_width))
    found = physical_contact_set(p, conductance=cond, start=start)
    assert found.status == "solved" and "single patch" in found.message
    (zone,) = found.zones
    d = float(here.half_width)
    # `contact --zones` with this conductance, followed from Hertz's zone (n = 32).
    assert zone["a"] == pytest.approx(-0.0001846707351433056, rel=0, abs=1e-8 * d)
    assert zone["b"] == pytest.approx(0.00015998892555344637, rel=0, abs=1e-8 * d)
    assert abs(zone["a"] - start[0]) > 1e-3 * d  # the conductance moved it
    ell, g = p.hertz_half_width, p.ray_parameters()
    edges = np.array([[zone["a"], zone["b"]]]) / ell
    for biot, small in ((cond.biot(p), True), (None, False)):
        model = ZoneModel(g["K2_over_K1"], k2_over_k1=g["k2_over_k1"],
                          delta1_over_delta2=g["delta1_over_delta2"], beta_f=g["beta_f"],
                          n=32, conductance=biot)
        defects = model.defects(edges, p.pe_hertz, p.fhpe(ell), 1.0)[0]
        assert bool(np.max(np.abs(defects)) < 1e-12) is small


def test_contact_set_options_of_a_map_are_checked():
    """A conductance needs the contact sets, and one law for every load (a reference
    pressure unless constant); a moving half-plane's contact sets are taken."""
    ax = parse_physical_axis("--x", "speed:2:5:2"), parse_physical_axis("--y", "load:1e5:2e5:2")
    with pytest.raises(InputError, match="conductance needs zones"):
        OperatingSpec(ST, CU, 0.3, 1.0, *ax, {"radius": 0.01},
                      conductance=PhysicalConductance(1e5, 0.0))
    with pytest.raises(InputError, match="h0:m:p_ref"):
        OperatingSpec(ST, CU, 0.3, 1.0, *ax, {"radius": 0.01}, zones=True,
                      conductance=PhysicalConductance(1e5, 1.0))
    assert OperatingSpec(ST, CU, 0.3, 1.0, *ax, {"radius": 0.01}, zones=True,
                         speed_ratio=-0.5).problem(load=1e5, speed=2.0).speed2 == -1.0
    OperatingSpec(ST, CU, 0.3, 1.0, *ax, {"radius": 0.01}, zones=True,
                  conductance=PhysicalConductance(1e5, 0.0))


def test_physical_conductance_in_biot_numbers():
    """h = h0 (p/p_ref)^m at the mean Hertz pressure P/(2 l), times l/K2: with p_ref that
    pressure it is h0 l/K2 whatever m; doubling p_ref divides it by 2^m; m = 0 ignores
    p_ref."""
    prob = PhysicalProblem(ST, CU, 0.01, 1e5, 3.0, 0.3, 1.0)
    ell, p_mean = prob.hertz_half_width, prob.load / (2 * prob.hertz_half_width)
    bi = 2e5 * ell / CU.K
    assert PhysicalConductance(2e5, 0.95).biot(prob) == (pytest.approx(bi, rel=1e-15), 0.95)
    assert PhysicalConductance(2e5, 0.95, p_mean).biot(prob)[0] == pytest.approx(bi, rel=1e-14)
    assert PhysicalConductance(2e5, 0.95, 2 * p_mean).biot(prob)[0] == pytest.approx(
        bi / 2 ** 0.95, rel=1e-14)
    assert PhysicalConductance(2e5, 0.0, 1.0).biot(prob)[0] == pytest.approx(bi, rel=1e-15)
    for bad in ((0.0, 1.0), (1e5, -1.0), (1e5, 1.0, 0.0), (float("nan"), 1.0)):
        with pytest.raises(InputError, match="conductance"):
            PhysicalConductance(*bad)


@pytest.mark.parametrize("extra,needle", [
    (["--conductance", "1e5:1"], "--conductance needs --zones"),
    (["--zones", "--conductance", "1e5:0.95"], "h0:m:p_ref"),
    (["--zones", "--conductance", "1e5:0.95:-2GPa"], "conductance p_ref must be"),
    (["--zones", "--conductance", "1e5"], "--conductance must be h0:m[:p_ref]"),
])
def test_map_contact_set_options_refused_in_one_line(capsys, tmp_path, extra, needle):
    from thermocontact.cli import main

    argv = ["map", "--cylinder", "steel", "--half-plane", "copper", "--friction", "0.3",
            "--lam", "1", "--radius", "0.01", "--x", "speed:2:5:2", "--y", "load:1e5:2e5:2",
            "--out", str(tmp_path / "m.nc")] + extra
    assert main(argv) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and needle in err[0]
    assert not (tmp_path / "m.nc").exists()


def test_dimensionless_map_has_no_contact_sets(capsys, tmp_path):
    from thermocontact.cli import main

    assert main(["map", "--x", "fhpe:0:0.5:2", "--y", "pe:1:5:2", "--K2-over-K1", "10",
                 "--lam", "0", "--zones", "--out", str(tmp_path / "m.nc")]) == 2
    assert "--zones belongs to an operating map" in capsys.readouterr().err


def test_contact_sets_cost_announced_before_the_work(capsys, tmp_path, monkeypatch):
    """`map --zones` says on standard error, before any work, what the contact sets cost:
    points x seconds per set, in rounds of one line per worker."""
    import thermocontact.api as api
    from thermocontact.cli import main
    from thermocontact.studies.operating_maps import CONTACT_SET_SECONDS

    ax = parse_physical_axis("--x", "speed:2:5:3"), parse_physical_axis("--y", "load:1e5:2e5:2")
    s = OperatingSpec(ST, CU, 0.3, 1.0, *ax, {"radius": 0.01}, zones=True)
    assert s.contact_set_cost(1) == 6 * CONTACT_SET_SECONDS
    assert s.contact_set_cost(2) == s.contact_set_cost(8) == 3 * CONTACT_SET_SECONDS
    assert OperatingSpec(ST, CU, 0.3, 1.0, *ax, {"radius": 0.01}).contact_set_cost(1) == 0
    seen = []

    def stop(*args, **kwargs):
        seen.append(capsys.readouterr().err)
        raise KeyboardInterrupt
    monkeypatch.setattr(api, "compute_map", stop)
    argv = ["map", *STEEL_ON_COPPER, "--x", "speed:2:5:3", "--y", "load:1e5:2e5:2",
            "--workers", "2", "--out", str(tmp_path / "m.nc")]
    assert main(argv + ["--zones"]) == 130
    assert seen[0].startswith(f"contact sets at 6 points: about {CONTACT_SET_SECONDS:g} s "
                              f"each on one core, about "
                              f"{3 * CONTACT_SET_SECONDS:.0f} s on 2 workers\n"), seen
    assert main(argv) == 130 and "contact sets" not in seen[1]
