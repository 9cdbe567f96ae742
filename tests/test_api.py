"""The public calls: each command is one Python call whose record (or dataset) is
exactly what the command prints (or writes)."""

import json
import pickle

import numpy as np
import pytest

import thermocontact as tc
from thermocontact.cli import main
from thermocontact.problem.validation import InputError
from thermocontact.io.datasets import read_dataset


def _json(capsys, argv):
    assert main(argv) == 0
    return json.loads(capsys.readouterr().out)


def test_public_names_resolve():
    for name in tc.__all__:
        assert getattr(tc, name) is not None, name


def test_axis_validates_itself():
    ax = tc.Axis("load", "1kN/m", "100kN/m", 3, log=True)
    assert np.allclose(ax.values, [1e3, 1e4, 1e5], rtol=1e-15)
    assert ax == pickle.loads(pickle.dumps(ax))
    assert tc.Axis("fhpe", 0, 1, 3.0).count == 3
    for args, words in [(("fhpe", 1, 0, 5), "stop must be greater than start"),
                        (("fhpe", 0, 1, 1), "count must be 2 to 4096"),
                        (("fhpe", 0, 1, 2.5), "count must be an integer"),
                        (("fhpe", 0, 1, 5, True), "log axis must stay positive"),
                        (("fhpe", 0, float("nan"), 5), "finite"),
                        (("load", "1kN", "2kN/m", 5), "N/m"),
                        ((3, 0, 1, 5), "name must be")]:
        with pytest.raises(InputError, match=words) as exc:
            tc.Axis(*args)
        assert "\n" not in str(exc.value)


def test_a_map_checks_its_axes_names():
    with pytest.raises(InputError, match="x parameter must be one of"):
        tc.map_spec(tc.Axis("load", 1, 2, 3), tc.Axis("pe", 1, 2, 3), K2_over_K1=1, lam=0)
    with pytest.raises(InputError, match="y parameter must be one of"):
        tc.map_spec(tc.Axis("load", 1, 2, 3), tc.Axis("pe", 1, 2, 3), cylinder="steel",
                    half_plane="copper", friction=0.1, lam=0, radius=1)
    # "sigma" is the command line's spelling of sigma_over_delta, also in Python.
    spec = tc.map_spec(tc.Axis("sigma", 0, 0.1, 3), tc.Axis("pe", 1, 2, 3), fhpe=0.1,
                       K2_over_K1=1)
    assert spec.x.name == "sigma_over_delta"


def test_boundary_is_the_command(capsys):
    path = tc.boundary(along="fhpe", start=0, stop=1, pe=5, K2_over_K1=10, lam=1, n=16)
    rec = _json(capsys, ["boundary", "--along", "fhpe", "--from", "0", "--to", "1", "--pe",
                         "5", "--K2-over-K1", "10", "--lam", "1", "-n", "16", "--json"])
    assert path.to_dict() == rec
    assert [e["inequality"] for e in rec["events"]]


def test_contact_set_is_the_command(capsys):
    res = tc.contact_set(5.43, 0.3, 10, lam=1, n=16)
    rec = _json(capsys, ["zones", "--pe-hertz", "5.43", "--fhpe-hertz", "0.3",
                         "--K2-over-K1", "10", "--lam", "1", "-n", "16", "--json"])
    assert res.to_dict() == rec
    assert rec["status"] == "solved" and len(rec["zones"]) == 1


def test_parameter_map_is_the_command(tmp_path, capsys):
    ds = tc.parameter_map(x=tc.Axis("fhpe", 0, 0.8, 3), y=tc.Axis("pe", 1, 10, 2, log=True),
                          K2_over_K1=10, lam=1, workers=1)
    out = tmp_path / "m.nc"
    assert main(["map", "--x", "fhpe:0:0.8:3", "--y", "pe:1:10:2:log", "--K2-over-K1", "10",
                 "--lam", "1", "--workers", "1", "--out", str(out)]) == 0
    capsys.readouterr()
    written = read_dataset(out)
    for name in ds.data_vars:
        assert np.array_equal(ds[name].values, written[name].values), name
    assert ds.attrs["manifest"] == written.attrs["manifest"]


def test_operating_map_is_the_command(tmp_path, capsys):
    kw = dict(cylinder="copper", half_plane="steel", radius="10mm", friction=0.2, lam=-1)
    ds = tc.operating_map(tc.Axis("load", "30kN/m", "40kN/m", 2),
                          tc.Axis("speed", 1, 1.5, 2), workers=1, tol=1e-4, **kw)
    out = tmp_path / "op.nc"
    assert main(["map", "--cylinder", "copper", "--half-plane", "steel", "--radius", "10mm",
                 "--friction", "0.2", "--lam", "-1", "--x", "load:3e4:4e4:2",
                 "--y", "speed:1:1.5:2", "--tol", "1e-4", "--workers", "1",
                 "--out", str(out)]) == 0
    # The fields' accuracy said after the summary: the points' largest estimate, and
    # where it meets the target (10 tol).
    est = ds["error_estimate"].values
    assert ds.attrs["field_tol"] == pytest.approx(1e-3)
    assert capsys.readouterr().out.splitlines()[-1] == (
        f"fields' error estimate up to {est.max():.1e} (target 1e-03: met at "
        f"{int((est <= 1e-3).sum())} of 4 points)")
    written = read_dataset(out)
    for name in ds.data_vars:
        a, b = ds[name].values, written[name].values
        assert a.shape == b.shape and np.array_equal(a, b, equal_nan=a.dtype.kind == "f"), name


def test_errors_name_parameters_in_python_and_flags_on_the_command_line(capsys):
    with pytest.raises(InputError, match="^K2_over_K1 must be given") as exc:
        tc.boundary("fhpe", 0, 1, pe=5, lam=1)
    assert exc.value.parameters == ("K2_over_K1",)
    assert main(["boundary", "--along", "fhpe", "--from", "0", "--to", "1", "--pe", "5",
                 "--lam", "1"]) == 2
    assert capsys.readouterr().err == ("error: --K2-over-K1 must be given (it is not the "
                                       "parameter followed)\n")
    with pytest.raises(InputError, match="^give exactly one closure: lam, sigma_over_delta"):
        tc.boundary("fhpe", 0, 1, pe=5, K2_over_K1=1)
    with pytest.raises(InputError, match="^radius must be > 0"):
        tc.contact("steel", "copper", radius=-1, load=1e4, speed=1, friction=0.1, lam=0)
    # A parameter of the other kind of problem is refused, not ignored.
    with pytest.raises(InputError, match="^delta1_over_delta2 belongs to a dimensionless"):
        tc.boundary("load", 1e3, 1e4, cylinder="steel", half_plane="copper", radius=1,
                    speed=1, friction=0.1, lam=0, delta1_over_delta2=2)
    assert main(["boundary", "--along", "load", "--from", "1e3", "--to", "1e4", "--cylinder",
                 "steel", "--half-plane", "copper", "--radius", "1", "--speed", "1",
                 "--friction", "0.1", "--lam", "0", "--delta1-over-delta2", "2"]) == 2
    assert capsys.readouterr().err.startswith("error: --delta1-over-delta2 belongs to a "
                                              "dimensionless path, not to one with --cylinder")
