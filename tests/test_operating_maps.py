"""Operating maps in physical units: one ray answers the whole load-speed plane."""

import pytest

from thermocontact.problem.materials import get_material
from thermocontact.problem.validation import InputError
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


def test_map_points_equal_contact():
    """Every point of a 2 x 2 map (load 10-40 kN/m, speed 0.3-3 m/s;
    the steel half-plane's surface moving against the copper cylinder's at half its speed,
    R = -1/2, and the Dundurs term of the pair), read off the one ray, equals `contact`
    at that point (speed2 = R v): half-width and offset to 1e-6, peak pressure
    and flash temperature to 1e-5 relative (each side's error target is 1e-6 in P_H/P
    at its own n; the ray is interpolated in ln Pe to degree 5 at 24 samples per
    decade; observed 2.6e-6 on the peak pressure), slopes and strains to 1e-5,
    validity and applicability exactly."""
    s = OperatingSpec(CU, ST, 0.2, -1.0, parse_physical_axis("--x", "load:1e4:4e4:2:log"),
                      parse_physical_axis("--y", "speed:0.3:3:2:log"), {"radius": 0.01},
                      speed_ratio=-0.5)
    assert s.manifest()["speed_ratio"] == -0.5
    ds = compute_operating_map(s, workers=1)
    for j, v in enumerate(ds.speed.values):
        for i, P in enumerate(ds["load"].values):
            ref = contact(PhysicalProblem(CU, ST, 0.01, float(P), float(v), 0.2, -1.0,
                                          speed2=-0.5 * float(v))).primary
            point = ds.isel(speed=j, load=i)
            assert float(point.half_width) == pytest.approx(ref.half_width, rel=1e-6)
            assert float(point.offset) == pytest.approx(ref.offset, rel=1e-6, abs=1e-9 * ref.half_width)
            assert float(point.peak_pressure) == pytest.approx(ref.peak_pressure, rel=1e-5)
            assert float(point.flash_temperature) == pytest.approx(ref.flash_temperature,
                                                                   rel=1e-5)
            assert bool(point.valid) == ref.valid
            # Slopes and strains from the ray's factors against contact's own measure
            # (201 points of the contact; observed 4e-7).
            a = ref.applicability
            for i, body in enumerate(("cylinder", "half_plane")):
                assert float(point[f"max_slope_{body}"]) == pytest.approx(a.max_slope[i],
                                                                        rel=1e-5)
                assert float(point[f"max_strain_{body}"]) == pytest.approx(a.max_strain[i],
                                                                         rel=1e-5)
            assert bool(point.applicable) == ref.applicable


def test_bad_operating_maps_are_refused():
    with pytest.raises(InputError, match="parameter must be one of"):
        parse_physical_axis("--x", "fhpe:0:1:3")
    with pytest.raises(InputError, match="--radius must be given"):
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
