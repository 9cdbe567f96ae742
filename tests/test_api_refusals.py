"""The defects of a hostile round of the Python API and the command line: each refused
in one line before any work, or answered correctly."""

import numpy as np
import pytest
import xarray as xr

import thermocontact as tc
from thermocontact.cli import main
from thermocontact.problem.validation import InputError

#: A transient run of milliseconds.
RUN = dict(until=1, steps=10, elements=16, lam=1)


@pytest.fixture(scope="module")
def short_run():
    return tc.transient(2.7, 0.36, 10, **RUN)


def _one_line(capsys, args, message):
    assert main(args) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and err[0].startswith("error: ") and message in err[0], err


@pytest.mark.parametrize("args", [
    ["boundary", "--along", "fhpe", "--from", "0", "--to", "1", "--pe", "5",
     "--K2-over-K1", "10", "--theta", "1"],
    ["boundary", "--along", "theta", "--from", "0", "--to", "1", "--pe", "5", "--fhpe",
     "0.2", "--K2-over-K1", "10"],
    ["map", "--x", "fhpe:0:1:3", "--y", "pe:1:5:3", "--K2-over-K1", "10", "--theta", "1",
     "--out", "never.nc"],
    ["map", "--x", "theta:0:1:3", "--y", "pe:1:5:3", "--K2-over-K1", "10", "--fhpe", "0.2",
     "--out", "never.nc"],
])
def test_theta_without_a_sink_is_refused_as_solve_refuses_it(capsys, args, tmp_path,
                                                             monkeypatch):
    """A stationary half-plane's far temperatures need its sink: refused in one line
    naming --sink-distance, as solve does, not a path "valid throughout: False" or a
    map whose every point failed (exit 0 before)."""
    monkeypatch.chdir(tmp_path)
    _one_line(capsys, args, "a stationary half-plane needs --sink-distance")
    assert not (tmp_path / "never.nc").exists()


def test_theta_without_a_sink_is_refused_by_the_python_calls():
    fhpe, pe = tc.Axis("fhpe", 0, 1, 3), tc.Axis("pe", 1, 5, 3)
    with pytest.raises(InputError, match="a stationary half-plane needs sink_distance"):
        tc.boundary("fhpe", 0, 1, pe=5, K2_over_K1=10, closure=tc.FarTemperatures(1))
    with pytest.raises(InputError, match="a stationary half-plane needs sink_distance"):
        tc.map_spec(fhpe, pe, K2_over_K1=10, closure=tc.FarTemperatures(1))
    with pytest.raises(InputError, match="sink_distance applies to a stationary half-plane"):
        tc.map_spec(fhpe, pe, K2_over_K1=10, closure=tc.FarTemperatures(1, 3),
                    speed_ratio=0.5)
    # A moving half-plane takes theta alone; a speed ratio that varies leaves it to
    # each point.
    tc.map_spec(fhpe, pe, K2_over_K1=10, closure=tc.FarTemperatures(1), speed_ratio=0.5)
    tc.map_spec(tc.Axis("speed_ratio", -1, -0.5, 2), pe, K2_over_K1=10, fhpe=0.2,
                closure=tc.FarTemperatures(1))


def test_numbers_given_as_strings_are_those_numbers(short_run):
    """tc.transient takes numbers as strings as tc.tei does (a TypeError before): the
    same run."""
    run = tc.transient("2.7", "0.36", "10", until="1", steps=10, elements=16, lam="1",
                       perturb="0")
    assert run.spec == short_run.spec
    assert np.array_equal(run.pressure, short_run.pressure)


@pytest.mark.parametrize("kw, message", [
    (dict(conductance="1:0"), "conductance must be (Bi0, m), two numbers, got '1:0'"),
    (dict(conductance=(1,)), "conductance must be (Bi0, m), two numbers, got (1,)"),
    (dict(conductance=(1, 0, 1)), "conductance must be (Bi0, m), two numbers"),
    (dict(conductance=1), "conductance must be (Bi0, m), two numbers, got 1"),
    (dict(window="-3,3"), "window must be two numbers"),
    (dict(until="x"), "until must be in"),
    (dict(lam="one"), "lam must be in [-1, 1]"),
    (dict(perturb=None), "perturb must be in [-0.5, 0.5]"),
    (dict(steps=True), "steps must be an integer in [1, 100000], got True"),
    (dict(steps=10.5), "steps must be an integer in [1, 100000], got 10.5"),
    (dict(elements=False), "elements must be an integer in [8, 4000], got False"),
    (dict(initial=None), "initial must be one of ['hertz', 'steady']"),
])
def test_a_transient_run_refuses_wrong_types_by_name(kw, message):
    """Tracebacks before (ValueError, TypeError): InputError naming the parameter, and
    a flag is no count (steps=True ran one step)."""
    with pytest.raises(InputError) as err:
        tc.transient(2.7, 0.36, 10, **{**RUN, **kw})
    assert message in str(err.value) and "\n" not in str(err.value)


def test_a_physical_transient_refuses_a_flag_for_its_steps():
    with pytest.raises(InputError, match=r"steps must be an integer in \[1, 100000\], got True"):
        tc.contact_transient("copper", "steel", radius="10mm", load="50kN/m", speed="2m/s",
                             friction=0.2, lam=-1, dundurs=False, duration="1ms", steps=True)


def test_a_run_is_read_from_its_dataset_or_its_file_and_nothing_else(short_run, tmp_path):
    """read_transient of a path (AttributeError before) reads the file; a missing or
    invalid file, None or another object is refused naming ds; compute_transient
    resumes from a dataset as from the run."""
    path = tmp_path / "run.nc"
    short_run.to_dataset().to_netcdf(path)
    assert tc.read_transient(path) == short_run == tc.read_transient(str(path))
    (tmp_path / "bad.nc").write_text("not a dataset")
    for ds, message in ((str(tmp_path / "missing.nc"), "which is no file"),
                        (str(tmp_path / "bad.nc"), "could not be read as a dataset"),
                        (None, "ds must be a transient run's dataset or its file, got None"),
                        (xr.Dataset(), "ds is not a transient run's: it has no 'pe_hertz'"),
                        (xr.Dataset(attrs={"pe_hertz": "x"}), "ds is not a transient run's")):
        with pytest.raises(InputError) as err:
            tc.read_transient(ds)
        assert message in str(err.value) and "\n" not in str(err.value)
    saved = []
    tc.compute_transient(short_run.spec, save=saved.append, save_every=0.0)
    resumed = tc.compute_transient(short_run.spec, resume=saved[3].to_dataset())
    assert np.array_equal(resumed.pressure, short_run.pressure)
    with pytest.raises(InputError, match="resume is not a transient run's"):
        tc.compute_transient(short_run.spec, resume=xr.Dataset())
    with pytest.raises(InputError, match="resume must be a transient run's dataset"):
        tc.compute_transient(short_run.spec, resume=3)


def test_switches_are_booleans():
    """dundurs='no' kept the Dundurs term (a truthy string): a switch is True or False."""
    with pytest.raises(InputError, match="dundurs must be True or False, got 'no'"):
        tc.tei("steel", "cast-iron", 0.3, "50mm", dundurs="no")
    physical = dict(radius="10mm", load="50kN/m", speed="2m/s", friction=0.2, lam=-1)
    with pytest.raises(InputError, match="dundurs must be True or False, got 'no'"):
        tc.contact("copper", "steel", dundurs="no", **physical)
    with pytest.raises(InputError, match="zones must be True or False, got 'yes'"):
        tc.contact("copper", "steel", zones="yes", **physical)
    assert tc.tei("steel", "cast-iron", 0.3, "50mm", dundurs=np.bool_(False)).to_dict() == (
        tc.tei("steel", "cast-iron", 0.3, "50mm", dundurs=False).to_dict())


def test_a_long_run_tells_the_making_of_its_operators():
    """The operators of many steps (the lag tables, a step of lag at a time, in blocks)
    tell their progress before the first step, then the steps theirs from 0 (silent
    for minutes before: 100 000 steps, 4000 elements)."""
    from thermocontact.discretisation.history import TABLES

    TABLES.clear()
    spec = tc.transient_spec(2.7, 0.36, 10, until=20, steps=2000, elements=8, lam=1)
    making, steps = [], []
    tc.compute_transient(spec, preparing=lambda d, t: making.append((d, t)),
                         progress=lambda d, t: steps.append((d, t)) if d < 2 else None)
    done = [d for d, _ in making]
    assert {t for _, t in making} == {2 * 2000 + 3} and making[-1] == (4003, 4003)
    assert done == sorted(done) and len(done) > 4
    assert steps[0] == (0, 2000)


def test_a_run_from_hertz_has_no_partition_before_its_first_step(short_run):
    """At t = 0 no heat has been made: lam and the temperature difference are 0/0, NaN
    in the run and its file, as the docs say; from the first step on, the held lam."""
    assert np.isnan(short_run.lam[0]) and np.isnan(short_run.temperature_difference[0])
    np.testing.assert_allclose(short_run.lam[1:], 1.0, atol=1e-12)
    ds = short_run.to_dataset()
    assert np.isnan(ds["lam"].values[0]) and np.isfinite(ds["lam"].values[1:]).all()
