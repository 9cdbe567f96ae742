"""The transient contact (derivation section 19): its steady limit, its balance laws,
its short-time limit and its observed order in the time step."""

import numpy as np
import pytest

import thermocontact as tc
from thermocontact.problem.validation import InputError
from thermocontact.solvers.elements import solve_elements
from thermocontact.solvers.transient import TransientSpec, run_transient

#: Below path (a)'s boundary (half its load): one zone, edges on element boundaries.
CASE = dict(pe_hertz=2.7, fhpe_hertz=0.36, K2_over_K1=10.0)


@pytest.mark.parametrize("hold", ["theta", "lam"])
def test_the_steady_state_is_a_fixed_point(hold):
    # Started from the steady element solution on the same elements (held for all
    # t < 0), the steps stay on it: the tables summed over all lags are the steady
    # operators, exactly as the deviation formulation uses them.
    run = tc.transient(**CASE, lam=1.0, until=1.0, steps=40, elements=96, initial="steady",
                       hold=hold)
    steady = solve_elements(TransientSpec(**CASE, lam=1.0, until=1.0, steps=40).parameters(),
                            1.0, domain=(-3.0, 3.0), elements=96)
    assert run.status == "complete"
    assert np.max(np.abs(run.pressure - steady.pressure)) < 1e-11
    assert np.max(np.abs(run.flux - steady.flux)) < 1e-10
    assert np.max(np.abs(run.lam - 1.0)) < 1e-11
    assert np.ptp(run.approach) < 1e-12
    assert np.all(run.scheme == 0)


def test_heat_balance_and_closures_at_every_step():
    run = tc.transient(**CASE, lam=0.3, until=1.0, steps=50, elements=96)
    h = run.h
    # All the frictional work is heat: q1 + q2 = p on every element at every step,
    # the load is P and the partition the one held.
    q1, q2 = 0.5 * (run.pressure + run.flux), 0.5 * (run.pressure - run.flux)
    assert np.max(np.abs(q1 + q2 - run.pressure)) < 1e-15
    assert np.max(np.abs(h * run.pressure.sum(axis=1) - 1.0)) < 1e-12
    assert np.max(np.abs(run.lam[1:] - 0.3)) < 1e-12
    # Off contact no heat crosses; on it, the gap is closed and the pressure compressive.
    off = ~run.in_contact
    assert np.all(run.flux[off] == 0.0)
    assert np.all(run.pressure >= 0.0)
    assert np.all(run.gap[run.scheme == 0] >= -1e-12)
    # The far temperatures held: C is theta at every step.
    run = tc.transient(**CASE, closure=tc.FarTemperatures(0.7), until=0.5, steps=20, elements=96)
    assert np.all(run.temperature_difference[1:] == 0.7)
    on = run.in_contact[-1]
    assert np.max(np.abs((run.theta1[-1] - run.theta2[-1])[on] - 0.7)) < 1e-10


def test_short_times_divide_the_heat_by_the_effusivities():
    # While the heat has conducted a distance sqrt(kappa dt) much shorter than an
    # element and been carried much less than one, each body is a 1-D conductor:
    # equal temperatures give Q1/Q2 = e1/e2 = sqrt(k2/k1)/(K2/K1) (section 19).
    rho, kr = 10.0, 4.0
    e = np.sqrt(kr) / rho
    target = (e - 1.0) / (e + 1.0)
    errors = []
    for dt in (1e-3, 2.5e-4, 6.25e-5):
        run = tc.transient(**{**CASE, "K2_over_K1": rho}, k2_over_k1=kr, closure=tc.FarTemperatures(0.0),
                           until=dt,
                           steps=1, elements=96)
        errors.append(abs(run.lam[1] - target))
    assert errors[0] < 5e-4 and errors[-1] < 2e-6
    assert errors[0] > errors[1] > errors[2]


def test_observed_order_in_the_time_step():
    # A fixed contact set (weak coupling): the rigid approach at t = 0.5 converges at
    # the observed order 1.4, the scheme's 3/2 (the tau^(-1/2) temperature kernel over
    # the last step of a constant flux; derivation section 19).
    D = []
    for steps in (25, 50, 100, 200):
        run = tc.transient(2.7, 0.1, 10.0, lam=1.0, until=0.5, steps=steps, elements=96)
        assert run.zones(-1)[0].size == 1 and np.all(run.scheme == 0)
        D.append(run.approach[-1])
    d = np.abs(np.diff(D))
    orders = np.log2(d[:-1] / d[1:])
    assert np.all((orders > 1.3) & (orders < 1.7)), orders


def test_a_resumed_run_equals_one_run():
    spec = TransientSpec(**CASE, lam=1.0, until=0.6, steps=30, elements=96)
    whole = run_transient(spec)
    k = 12
    part = whole.replace(**{name: getattr(whole, name)[:k + 1] for name in (
        "time", "pressure", "flux", "gap", "theta1", "theta2", "lam", "approach",
        "temperature_difference", "set_iterations", "scheme")}, status="partial")
    again = run_transient(spec, resume=part)
    for name in ("pressure", "flux", "gap", "theta1", "theta2", "approach"):
        assert np.array_equal(getattr(again, name), getattr(whole, name)), name


def test_a_contact_that_leaves_the_window_is_reported():
    # Path (c) past its boundary migrates downstream (docs/transient.md): a window
    # that stops at -2.5 is left, and the run says so and keeps the steps before.
    run = tc.transient(1.439, 4.825, 1.0, lam=0.5, until=4.0, steps=100, elements=88,
                       window=(-2.5, 3.0))
    assert run.status == "stopped" and "window's end" in run.message
    assert 1 < run.time.size < 101


@pytest.mark.parametrize("kw, name", [
    (dict(lam=None), "lam"),
    (dict(theta=0.0), "lam"),
    (dict(steps=0), "steps"),
    (dict(until=-1.0), "until"),
    (dict(window=(0.0, 3.0)), "window"),
    (dict(lam=2.0), "lam"),
    (dict(perturb=0.9), "perturb"),
    (dict(initial="steady", theta=1.0), "initial"),
    (dict(initial="cold"), "initial"),
    (dict(elements=4), "elements"),
    (dict(conductance=(0.0, 1.0)), "conductance"),
    (dict(delta1_over_delta2=2000.0), "delta1_over_delta2"),
    (dict(initial="steady", conductance=(2.0, 0.0)), "conductance"),
    (dict(steps=100_000, elements=4000), "steps x elements"),
    (dict(until=1e9, steps=10), "until/steps"),
])
def test_bad_input_is_refused_naming_the_parameter(kw, name):
    base = dict(CASE, lam=1.0, until=1.0, steps=10)
    with pytest.raises(InputError) as err:
        TransientSpec(**{**base, **kw})
    assert name in str(err.value)


def test_a_stable_contact_relaxes_algebraically_as_its_spectrum_says():
    # Fig. 4's contact at lam = 1, fHPe = 0.3 (Pe = 5, K2/K1 = 10) has no eigenvalue
    # with Re b >= 1e-3 (docs/stability/stability_study.json), and the stationary
    # half-plane's branch point reaches b = 0 (derivation section 18, S8): a kick decays,
    # not exponentially but like the step response's t^(-1/2) tail differentiated,
    # t^(-3/2) (section 19, R3).  The heat partition held, as the steady model does.
    import json
    import pathlib

    rec = json.loads((pathlib.Path(__file__).parents[1] / "docs" / "stability"
                      / "stability_study.json").read_text())["cases"]["fig4 lam=1 fHPe=0.3"]
    assert rec["valid"] and rec["n=12"]["stable"] is True
    assert rec["n=12"]["unstable_modes"] == rec["n=16"]["unstable_modes"] == 0
    s = np.sqrt(rec["load_ratio"])
    run = tc.transient(rec["pe"] / s, rec["fhpe"] / s, 10.0, lam=1.0, until=40.0, steps=200,
                       elements=96, initial="steady", hold="lam", perturb=0.1)
    D = np.abs(run.approach - run.approach[0])
    late = run.time >= 5.0
    slope = np.polyfit(np.log(run.time[late]), np.log(D[late]), 1)[0]
    assert -1.6 < slope < -1.4, slope
    assert D[-1] < 1e-3 * D[1]


def test_the_transient_page_states_its_study():
    # docs/transient.md's table is the study's JSON as the script prints it, and the
    # cycle's period on path (c) converges as the page says: differences falling by
    # about 1.6 per halving of the step (order ~2/3), extrapolated to 2.6 +- 0.05.
    import contextlib
    import importlib.util
    import io
    import pathlib

    root = pathlib.Path(__file__).parents[1]
    spec = importlib.util.spec_from_file_location(
        "transient_study", root / "docs" / "transient" / "transient_study.py")
    study = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(study)
    out = io.StringIO()
    with contextlib.redirect_stdout(out):
        study.table()
    assert out.getvalue() in (root / "docs" / "transient.md").read_text()
    import json

    runs = json.loads(study.OUT.read_text())["runs"]
    periods = [runs[f"c|perfect|{k}"]["period_mean"] for k in ("base", "dt/2", "dt/4", "dt/8")]
    d = np.diff(periods)
    ratios = d[:-1] / d[1:]
    assert np.all((ratios > 1.45) & (ratios < 1.75)), ratios
    limit = periods[-1] + d[-1] / (ratios[-1] - 1.0)
    assert abs(limit - 2.63) < 0.02
    assert runs["c|perfect|h/2"]["period_mean"] == pytest.approx(periods[0], abs=0.02)
    # (a) and (b) stay one zone at every resolution; (c) has two during handovers.
    for name in ("a", "b"):
        assert all(r["zones_max"] == 1 for k, r in runs.items() if k.startswith(name))


def test_a_conductance_that_vanishes_with_the_pressure_is_carried():
    # m = 1.5 makes Bi = Bi0 (2p)^m vanish at the edges faster than 1e-300 allows a
    # power: the resistance is capped, every step stays finite (once it crashed).
    pe = 1.1 * 5.43262
    run = tc.transient(pe, 0.133072 * pe, 10.0, lam=1.0, until=2.0, steps=100, elements=240,
                       conductance=(2.0, 1.5))
    assert run.status == "complete" and np.all(np.isfinite(run.pressure))
    assert np.all(np.isfinite(run.flux)) and np.max(np.abs(run.lam[1:] - 1.0)) < 1e-10


def test_a_run_says_when_its_zones_span_too_few_elements():
    fine = tc.transient(**CASE, lam=1.0, until=0.5, steps=10, elements=120)
    coarse = tc.transient(**CASE, lam=1.0, until=0.5, steps=10, elements=12)
    assert fine.resolution == "resolved" and fine.fewest_elements() >= 30
    assert coarse.fewest_elements() == 4
    assert coarse.resolution.startswith("under-resolved: a zone spans 4 elements")
    assert coarse.to_dict()["resolution"] == coarse.resolution


def test_the_run_ends_on_the_steady_zone_to_its_elements():
    # Switched on from Hertz's, the contact settles on the steady single zone that
    # `zones` computes by another method (edge-graded, edges by Newton's method,
    # section 14): every edge within half an element, the elements' resolution, at
    # two element widths.
    ref = tc.contact_set(**CASE, lam=1.0).answer.zone_records()
    assert len(ref) == 1
    for N in (96, 192):
        run = tc.transient(**CASE, lam=1.0, until=40.0, steps=200, elements=N)
        (a,), (b,) = run.zones(-1)
        assert abs(a - ref[0]["a"]) <= 0.5 * run.h and abs(b - ref[0]["b"]) <= 0.5 * run.h
