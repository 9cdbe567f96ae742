"""The refinement driver reports only the estimates it measured, and a sweep's choice
of n keeps to the method's automatic range."""

import types

import numpy as np
import pytest

from thermocontact.discretisation.methods import METHODS
from thermocontact.problem.parameters import SolveError
from thermocontact.solvers.refinement import Refinement, error_estimate, refine
from thermocontact.studies import sweeps


def level(n, value=1.0):
    """A stand-in solution whose load ratio converges like 1/n^2."""
    return types.SimpleNamespace(load_ratio=value + 1.0 / n**2, sigma_over_delta=0.0)


def test_nothing_solved_is_no_estimate():
    """No case solves: no estimate (not 0), a status saying why, and no doubling in vain."""
    done = refine(lambda m: (None, None), [4, 8, 16], tol=1e-6, n_max=1024)
    assert isinstance(done, Refinement)
    assert done.estimate is None and done.status == "no estimate"
    assert "nothing solved at n = 16" in done.reason
    assert done.sizes == (4, 8, 16) and done.n == 16
    levels, est = done  # unpacks as before
    assert est is None and isinstance(levels, list) and len(levels) == 3


def test_estimate_from_the_cases_that_solved():
    """A case without solutions is left out; the estimate is the other case's own."""
    done = refine(lambda m: (level(m), None), [4, 8, 16])
    sols = [lv[0] for lv in done.levels]
    assert done.estimate == error_estimate(sols) > 0.0
    assert done.status == "estimated"


def test_doubles_until_an_estimate_is_measured():
    """Solved first at n = 16: no estimate there, so the next level is solved and the
    estimate is that of n = 16 against n = 32 (order 1 assumed with two solutions)."""
    seen = []

    def at(m):
        seen.append(m)
        return (level(m) if m >= 16 else None,)

    done = refine(at, [4, 8, 16], tol=1.0, n_max=64)
    assert seen == [4, 8, 16, 32] and done.status == "converged"
    assert done.estimate == pytest.approx((1 / 16**2 - 1 / 32**2) / (1 + 1 / 32**2))


def test_not_converged_and_single_level():
    done = refine(lambda m: (level(m),), [4, 8, 16], tol=1e-30, n_max=64)
    assert done.status == "not converged" and done.n == 64 and done.estimate > 1e-30
    one = refine(lambda m: (level(m),), [16])
    assert one.estimate is None and one.status == "no estimate" and "one level" in one.reason
    import json

    json.dumps(done.to_dict(), allow_nan=False)
    assert "levels" not in done.to_dict() and len(repr(done)) < 200


class _Model:
    """A stand-in model: records the n solved, never converges (or never solves)."""

    def __init__(self, solves=True):
        self.seen, self.solves = [], solves

    def solve_at(self, n, fhpe, check_validity=False, **closure):
        self.seen.append(n)
        if not self.solves:
            raise SolveError("singular")
        return types.SimpleNamespace(load_ratio=1.0 + 1.0 / n, sigma_over_delta=0.0)


@pytest.fixture
def model(monkeypatch):
    def install(solves=True):
        m = _Model(solves)
        monkeypatch.setattr(sweeps, "model_for", lambda fixed, method: m)
        return m
    return install


def test_choose_n_without_solutions_reports_no_estimate(model):
    model(solves=False)
    n, est = sweeps.choose_n(dict(pe=5, K2_over_K1=10, lam=-1), "fhpe", (0.3, 0.7))
    assert est is None and n == 4 * METHODS["graded"].auto_range[0]


@pytest.mark.parametrize("method", ["graded", "galerkin"])
def test_choose_n_keeps_to_the_methods_range(model, method):
    lo, hi = METHODS[method].auto_range
    m = model()
    n, est = sweeps.choose_n(dict(pe=5, K2_over_K1=10, lam=-1), "fhpe", (0.7,), tol=1e-30,
                             method=method)
    assert min(m.seen) == lo and max(m.seen) == hi == n and est > 1e-30
    m = model()
    n, _ = sweeps.choose_n(dict(pe=5, K2_over_K1=10, lam=-1), "fhpe", (0.7,), tol=1e-30,
                           method=method, n_max=8 * lo)
    assert max(m.seen) == n == 8 * lo


def test_choose_n_of_a_figure_curve_as_before():
    """Fig. 3's Pe = 5 curve: n = 32 and the estimate that its CSV header states."""
    n, est = sweeps.choose_n(dict(pe=5.0, K2_over_K1=10.0, lam=-1.0), "fhpe", (0.36, 0.7),
                             tol=1e-7, n_max=256)
    assert n == 32 and est == pytest.approx(4.1588759786595196e-08, rel=1e-6)


def test_sweep_with_n_given_claims_no_estimate():
    c = sweeps.sweep("c", dict(pe=5, K2_over_K1=10, lam=-1), "fhpe", np.linspace(0, 0.3, 3),
                     n=16)
    assert c.error_estimate is None and c.to_dict()["error_estimate"] is None
