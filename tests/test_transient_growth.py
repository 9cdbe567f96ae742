"""The transient against the eigenvalues: its small perturbations are the steps on a
contact set held fixed, and these grow at the eigenvalue of the contact with its edges
held (derivation S17), which the stability analysis computes; not at the edges-free one."""

import dataclasses
import json

import numpy as np
import pytest

from conftest import DATA, data_script
import thermocontact as tc
from thermocontact.problem.validation import InputError
from thermocontact.solvers.stability import linearised, newton
from thermocontact.solvers.transient import TransientSpec, held_set_steps

RECORD = json.loads((DATA / "transient_growth.json").read_text())
MAKE = data_script("make_transient_growth")


@pytest.fixture(scope="module")
def past_the_fold():
    case = RECORD["case"]
    return tc.solve(case["pe"], case["fhpe"], case["K2_over_K1"], lam=case["lam"])


@pytest.mark.parametrize("hold", ["theta", "lam"])
def test_a_small_kick_is_the_steps_on_the_held_set(hold):
    # Below path (a)'s boundary (test_transient.py's case): a kick of 1e-4 of the load
    # keeps every element's contact, and the run is the steady state plus the steps on
    # the held set, to the rounding of the differences.
    kw = dict(pe_hertz=2.7, fhpe_hertz=0.36, K2_over_K1=10.0, lam=1.0, until=2.0, steps=40,
              elements=96, initial="steady", hold=hold, perturb=1e-4)
    run = tc.transient(**kw)
    held = run.pressure[0] > 0.0
    assert run.status == "complete" and np.all((run.pressure > 0.0) == held)
    _, p, q, D = held_set_steps(TransientSpec(**kw), held)
    for got, want in ((run.pressure[1:] - run.pressure[0], p),
                      (run.flux[1:] - run.flux[0], q),
                      (run.approach[1:] - run.approach[0], D)):
        assert np.max(np.abs(got - want)) < 1e-8 * np.max(np.abs(want))


def test_the_transient_grows_at_the_eigenvalue_with_the_edges_held(past_the_fold):
    sol, rec = past_the_fold, RECORD
    assert not sol.validity.valid          # no steady state of the elements there
    L = sol.load_ratio
    assert abs(L - rec["load_ratio"]) < 1e-10
    # The held eigenvalue at n = 12 is the stored one (Newton's method from n = 16's);
    # the stored n = 24 one is converged to 1e-6.
    stored = {e: [complex(*r["b"]) for r in rec["eigenvalues"][e]] for e in ("held", "free")}
    case = rec["case"]
    at_12 = tc.Model(case["pe"], case["K2_over_K1"]).solve_at(12, case["fhpe"], lam=case["lam"],
                                                              check_validity=False)
    lin = dataclasses.replace(linearised(at_12), edges="held")
    held, step = newton(lin.matrix, stored["held"][1], floor=1e-4, steps=10, tol=1e-12)
    assert step < 1e-10
    assert abs(held - stored["held"][0]) < 1e-8
    assert abs(stored["held"][1] - stored["held"][2]) < 1e-6
    levels = {(r["m"], r["steps"]): complex(*r["b_l"]) for r in rec["levels"]}
    # A run of the stored series, again: its rate to 1e-6.
    spec, active = MAKE.held_set_case(sol, 32, 500)
    t, _, _, D = held_set_steps(spec, active)
    rate, rest = MAKE.pencil_rate(t, D)
    assert abs(rate - levels[32, 500]) < 1e-6 * abs(rate)
    assert rest < 0.02                     # a complex pair is what grows
    # First order in the step (m = 32) and in the element (dt = 0.01), each difference
    # falling by 1.6 to 2.8 per halving; extrapolated with the observed ratios.
    def tail(a, b, c):
        ratio = abs(b - a) / abs(c - b)
        assert 1.6 < ratio < 2.8, ratio
        return (c - b) / (ratio - 1.0)
    in_dt = [levels[32, s] for s in (1000, 2000, 4000)]
    in_h = [levels[m, 1000] for m in (32, 64, 128)]
    limit = in_dt[-1] + tail(*in_dt) + (in_h[-1] - in_h[0]) + tail(*in_h)
    eigenvalue = stored["held"][2] / L     # in l^2/kappa2
    assert abs(limit - eigenvalue) < 1e-2 * abs(eigenvalue), (limit, eigenvalue)
    # The edges-free pair is not what the transient sees.
    assert abs(limit - stored["free"][2] / L) > 0.3 * abs(eigenvalue)


def test_held_edges_only_in_the_transients_model(past_the_fold):
    lin = linearised(past_the_fold)
    with pytest.raises(InputError, match="edges"):
        dataclasses.replace(lin, edges="sliding")
    for change in (dict(speed_ratio=0.4), dict(beta_f=0.3)):
        with pytest.raises(InputError, match="edges='held'"):
            dataclasses.replace(lin, edges="held",
                                parameters=dataclasses.replace(lin.parameters, **change))
