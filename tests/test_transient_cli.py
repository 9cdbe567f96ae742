"""``thermocontact transient`` and ``contact --transient``: the file, its round trip, the
resume after an interrupt, the pictures and one-line errors for bad input."""

import dataclasses

import numpy as np
import pytest
import xarray as xr

import thermocontact as tc
from thermocontact.cli import main
from thermocontact.io.datasets import read_dataset, write_dataset
from thermocontact.problem.materials import get_material
from thermocontact.problem.physical import PhysicalProblem

ARGS = ["transient", "--pe-hertz", "2.7", "--fhpe-hertz", "0.36", "--K2-over-K1", "10",
        "--until", "0.5", "--steps", "40", "--elements", "96"]
VARIABLES = {"pressure", "flux", "in_contact", "gap", "temperature1", "temperature2", "lam",
             "approach", "temperature_difference", "set_iterations", "zones_count",
             "zone_start", "zone_end"}


@pytest.fixture(scope="module")
def complete(tmp_path_factory):
    """One uninterrupted run of the command, with both pictures: (file, picture, gif)."""
    folder = tmp_path_factory.mktemp("complete")
    out, png, gif = folder / "run.nc", folder / "st.png", folder / "anim.gif"
    assert main(ARGS + ["--lam", "1", "--out", str(out), "--plot", str(png),
                        "--gif", str(gif)]) == 0
    return out, png, gif


def test_file_holds_every_variable_and_the_inputs(complete):
    """Every variable over (time, x); the inputs as attributes; the load carried at every
    step (sum p h = 1, the equilibrium the pressure must satisfy) and t_n = n dt."""
    ds = read_dataset(complete[0])
    assert VARIABLES <= set(ds.data_vars)
    assert ds["pressure"].dims == ("time", "x") and ds.sizes["time"] == 41
    assert ds.sizes["x"] == 96
    attrs = ds.attrs
    assert (attrs["pe_hertz"], attrs["fhpe_hertz"], attrs["K2_over_K1"]) == (2.7, 0.36, 10.0)
    assert (attrs["until"], attrs["steps"], attrs["elements"], attrs["lam"]) == (0.5, 40, 96, 1)
    assert attrs["theta"] == "none" and attrs["k2_over_k1"] == "none"
    assert list(attrs["window"]) == [-3.0, 3.0] and attrs["initial"] == "hertz"
    assert attrs["status"] == "complete"
    h = 6.0 / 96
    np.testing.assert_allclose(ds["pressure"].values.sum(axis=1) * h, 1.0, rtol=1e-12)
    np.testing.assert_array_equal(ds["time"].values, 0.5 / 40 * np.arange(41))
    np.testing.assert_array_equal(ds["in_contact"].values, ds["pressure"].values > 0)


def test_pictures_are_png_and_gif(complete):
    _, png, gif = complete
    assert png.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    assert gif.read_bytes()[:6] == b"GIF89a"
    from PIL import Image

    with Image.open(gif) as im:
        assert im.n_frames == 41  # one frame a step: 41 states, fewer than 100 frames


@pytest.mark.parametrize("kw", [
    dict(lam=1.0),
    dict(closure=tc.FarTemperatures(0.5), k2_over_k1=3.0, conductance=(2.0, 0.5), window=(-2.5, 3.0), perturb=0.1),
], ids=["lam", "theta-conductance"])
def test_from_dataset_round_trip(tmp_path, kw):
    """Written to NetCDF and read back, the run equals itself: every field, and the spec
    with its None values, window and conductance tuples and integer steps."""
    run = tc.transient(2.7, 0.36, 10, until=0.25, steps=12, elements=48, **kw)
    write_dataset(run.to_dataset(), tmp_path / "r.nc")
    back = tc.read_transient(read_dataset(tmp_path / "r.nc"))
    assert back == run
    assert type(back.spec.steps) is int and type(back.spec.elements) is int
    assert type(back.spec.window) is tuple
    assert back.spec.lam == kw.get("lam") and back.spec.theta == (0.5 if "closure" in kw else None)
    assert back.spec.conductance == kw.get("conductance")


def _identical_but_seconds(a, b):
    a, b = read_dataset(a), read_dataset(b)
    a.attrs["seconds"] = b.attrs["seconds"] = 0.0
    xr.testing.assert_identical(a, b)


def test_interrupt_leaves_a_partial_file_that_resumes_exactly(complete, tmp_path, monkeypatch,
                                                              capsys):
    """Ctrl-C at step 25 (partial saved after every step): exit 130, the file holds the
    24 steps before, status partial; the same command resumes from step 24 and writes a
    file identical to the uninterrupted run's."""
    from thermocontact.cli import transient as command
    from thermocontact.execution.progress import ProgressLine

    out = tmp_path / "run.nc"

    def interrupt(self, done, total):
        if done == 25:
            raise KeyboardInterrupt

    with monkeypatch.context() as m:
        m.setattr(command, "SAVE_EVERY", 0.0)
        m.setattr(ProgressLine, "__call__", interrupt)
        assert main(ARGS + ["--lam", "1", "--out", str(out)]) == 130
    err = capsys.readouterr().err
    assert err.strip().splitlines()[-1] == "interrupted; rerun the same command to resume"
    partial = read_dataset(out)
    assert partial.attrs["status"] == "partial" and partial.sizes["time"] == 25
    assert main(ARGS + ["--lam", "1", "--out", str(out)]) == 0
    assert f"resuming {out} from step 24 of 40" in capsys.readouterr().out
    _identical_but_seconds(out, complete[0])


def test_resumed_from_a_sliced_run(complete, tmp_path, capsys):
    """A partial run made by slicing the complete one's arrays resumes to the same file."""
    run = tc.read_transient(read_dataset(complete[0]))
    steps = run.time.size
    cut = {f.name: getattr(run, f.name)[:11] for f in dataclasses.fields(run)
           if f.name != "x" and isinstance(getattr(run, f.name), np.ndarray)
           and getattr(run, f.name).shape[0] == steps}
    out = tmp_path / "run.nc"
    write_dataset(run.replace(status="partial", **cut).to_dataset(), out)
    assert main(ARGS + ["--lam", "1", "--out", str(out)]) == 0
    assert "from step 10 of 40" in capsys.readouterr().out
    _identical_but_seconds(out, complete[0])


def test_complete_file_draws_only_the_pictures(complete, tmp_path, capsys):
    out = tmp_path / "run.nc"
    out.write_bytes(complete[0].read_bytes())
    png = tmp_path / "again.png"
    assert main(ARGS + ["--lam", "1", "--out", str(out), "--plot", str(png)]) == 0
    assert "is complete" in capsys.readouterr().out
    assert png.read_bytes()[:4] == b"\x89PNG"
    assert out.read_bytes() == complete[0].read_bytes()


def _one_line_error(capsys, args, *flags):
    assert main(args) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and err[0].startswith("error: "), err
    for flag in flags:
        assert flag in err[0], err[0]


def test_other_inputs_are_refused(complete, tmp_path, capsys):
    out = tmp_path / "run.nc"
    out.write_bytes(complete[0].read_bytes())
    _one_line_error(capsys, ARGS + ["--lam", "0.5", "--out", str(out)], "--out")
    assert out.read_bytes() == complete[0].read_bytes()


@pytest.mark.parametrize("extra, flags", [
    ([], ("--lam", "--theta")),
    (["--lam", "1", "--theta", "0"], ("--lam", "--theta")),
    (["--lam", "1", "--steps", "0"], ("--steps", "[1, 100000]")),
    (["--lam", "1", "--until", "-1"], ("--until",)),
    (["--lam", "1", "--window", "0,1"], ("--window",)),
    (["--lam", "1", "--window", "a,b"], ("--window",)),
    (["--lam", "1", "--start", "steady", "--theta", "0"], ("--theta", "--start")),
    (["--lam", "2"], ("--lam", "[-1, 1]")),
    (["--lam", "1", "--conductance", "1"], ("--conductance",)),
    # Elements wider than a half-width (Hertz's contact on none: a singular set).
    (["--lam", "1", "--window=-1e300,1e300"], ("--window", "half-widths wide")),
    # The contact at an end of the window at once: no step, no heat to report.
    (["--lam", "1", "--elements", "16", "--window=-1.01,1.01"],
     ("--window", "through the first step")),
    (["--lam", "0", "--hold", "lam"], ("--hold", "--start steady")),
    # Steps whose squares underflow (a division by zero, warned).
    (["--lam", "1", "--until", "1e-300"], ("--until", "[1e-12, inf]")),
], ids=["no-closure", "both-closures", "steps", "until", "window", "window-text",
        "steady-theta", "lam-range", "conductance", "window-wide", "window-tight", "hold",
        "until-tiny"])
def test_bad_input_is_one_line(tmp_path, capsys, extra, flags):
    # The given flag replaces the one of ARGS (a flag given twice is refused).
    given = {extra[i] for i in range(0, len(extra), 2)}
    base = [a for i, a in enumerate(ARGS) if not (a in given or ARGS[i - 1] in given)]
    _one_line_error(capsys, base + extra + ["--out", str(tmp_path / "r.nc")], *flags)
    assert not (tmp_path / "r.nc").exists()


@pytest.mark.parametrize("paths, flag", [
    (["--out", "{tmp}"], "--out"),
    (["--out", "{tmp}/r.txt"], "--out"),
    (["--out", "{tmp}/missing/r.nc"], "--out"),
    (["--out", "{tmp}/r.nc", "--gif", "{tmp}/a.png"], "--gif"),
    (["--out", "{tmp}/r.nc", "--plot", "{tmp}/a.gif"], "--plot"),
], ids=["folder", "suffix", "missing-folder", "gif-suffix", "plot-suffix"])
def test_unwritable_outputs_are_refused_first(tmp_path, capsys, paths, flag):
    _one_line_error(capsys, ARGS + ["--lam", "1"] + [p.format(tmp=tmp_path) for p in paths],
                    flag)


CONTACT = ["contact", "--cylinder", "copper", "--half-plane", "steel", "--radius", "10mm",
           "--load", "50kN/m", "--speed", "2m/s", "--friction", "0.2", "--lam", "-1",
           "--transient", "--duration", "1ms", "--steps", "20", "--elements", "64"]


def test_contact_transient_maps_the_physical_problem(tmp_path, capsys):
    """The file's dimensionless inputs are those of the PhysicalProblem (Pe_l, fHPe_l,
    the ratios of the materials' K, k and distortivity), time in l^2/k2 of steel."""
    out = tmp_path / "c.nc"
    assert main(CONTACT + ["--no-dundurs", "--out", str(out)]) == 0
    assert "s of computing" in capsys.readouterr().out
    cu, st = get_material("copper"), get_material("steel")
    problem = PhysicalProblem(cu, st, 0.01, 5e4, 2.0, 0.2, -1.0, dundurs=False)
    ell = problem.hertz_half_width
    ds = read_dataset(out)
    a = ds.attrs
    assert a["pe_hertz"] == pytest.approx(2.0 * ell / (2 * st.k), rel=1e-14)
    assert a["fhpe_hertz"] == pytest.approx(0.2 * problem.H * a["pe_hertz"], rel=1e-14)
    assert a["K2_over_K1"] == pytest.approx(st.K / cu.K, rel=1e-14)
    assert a["k2_over_k1"] == pytest.approx(st.k / cu.k, rel=1e-14)
    assert a["delta1_over_delta2"] == pytest.approx(cu.distortivity / st.distortivity, rel=1e-14)
    assert a["length_unit_m"] == pytest.approx(ell, rel=1e-14)
    assert a["time_unit_s"] == pytest.approx(ell ** 2 / st.k, rel=1e-14)
    assert ds["time"].values[-1] * a["time_unit_s"] == pytest.approx(1e-3, rel=1e-12)
    assert (a["cylinder"], a["half_plane"], a["friction"]) == ("copper", st.name, 0.2)
    assert a["status"] == "complete" and a["lam"] == -1.0
    # Rerun: the same inputs, complete.
    assert main(CONTACT + ["--no-dundurs", "--out", str(out)]) == 0
    assert "is complete" in capsys.readouterr().out


@pytest.mark.parametrize("extra, flags", [
    (["--out", "{tmp}/c.nc"], ("--no-dundurs",)),
    (["--no-dundurs", "--out", "{tmp}/c.nc", "--speed2", "1"], ("--speed2",)),
    (["--no-dundurs", "--out", "{tmp}/c.nc", "--zones"], ("--zones",)),
    (["--no-dundurs"], ("--out",)),
    (["--no-dundurs", "--out", "{tmp}/c.nc", "--duration", "-1s"], ("--duration",)),
    # In seconds, as given (not the dimensionless run's until in l^2/kappa2).
    (["--no-dundurs", "--out", "{tmp}/c.nc", "--duration", "1e300s"],
     ("--duration/--steps must be at most", " s at this speed", "--steps")),
    (["--no-dundurs", "--out", "{tmp}/c.nc", "--duration", "1e-30s"],
     ("--duration must be at least", "got 1e-30 s")),
], ids=["dundurs", "speed2", "zones", "no-out", "duration", "duration-long",
        "duration-short"])
def test_contact_transient_refusals(tmp_path, capsys, extra, flags):
    args = [a for a in CONTACT if a not in ("--duration", "1ms")] if "--duration" in extra \
        else CONTACT
    _one_line_error(capsys, args + [e.format(tmp=tmp_path) for e in extra], *flags)


def test_contact_transient_refuses_bulk_temperatures(tmp_path, capsys):
    args = [a for a in CONTACT if a not in ("--lam", "-1")]
    _one_line_error(capsys, args + ["--no-dundurs", "--out", str(tmp_path / "c.nc"),
                                    "--bulk-temperatures", "80C,20C", "--sink-distance",
                                    "2mm"], "--bulk-temperatures")
