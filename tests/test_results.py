"""Results and models as a user (and a process pool) handles them: pickling, equality,
a short repr, records and datasets, and a Model that answers like solve()."""

import json
import pickle
import warnings

import numpy as np
import pytest

from thermocontact import ConvergenceWarning, Model, clear_caches, solve
from thermocontact.numerics.cache import BoundedCache, cache_info


@pytest.fixture(scope="module")
def sol():
    return solve(5, 0.2, 10, lam=-1)


def test_solution_pickles_and_compares(sol):
    back = pickle.loads(pickle.dumps(sol))
    assert back == sol and not (back != sol)
    assert back.load_ratio == sol.load_ratio and np.array_equal(back.pressure, sol.pressure)
    # The representation travels as its class and n: the profiles are recomputed.
    assert len(pickle.dumps(sol)) < 4000
    assert back.gap_at([1.5]) == pytest.approx(sol.gap_at([1.5]), rel=1e-15)
    assert sol != sol.replace(lam=0.0)


def test_repr_is_short_and_names_the_result(sol):
    r = repr(sol)
    assert len(r) < 1000 and "load_ratio=0.68671356" in r and "status='converged'" in r


def test_status_message_and_record(sol):
    assert sol.status == "converged" and sol.success and sol.converged
    assert "valid" in sol.message and f"{sol.error_estimate:.1e}" in sol.message
    rec = json.loads(json.dumps(sol.to_dict(), allow_nan=False))
    assert rec["load_ratio"] == sol.load_ratio and rec["reason"] == "valid"
    assert rec["status"] == "converged" and len(rec["pressure"]) == sol.n + 2


def test_dataset_holds_profiles_and_provenance(sol, tmp_path):
    ds = sol.to_dataset()
    assert ds["pressure"].dims == ("s",) and np.array_equal(ds["s"].values, sol.s)
    assert np.array_equal(ds["flux_cylinder"].values, sol.flux_cylinder)
    assert ds.attrs["load_ratio"] == sol.load_ratio and ds.attrs["method"] == "graded"
    # It travels through NetCDF (scipy's writer) unchanged.
    import xarray as xr

    ds.to_netcdf(tmp_path / "sol.nc", engine="scipy")
    back = xr.open_dataset(tmp_path / "sol.nc", engine="scipy")
    assert back.attrs["load_ratio"] == sol.load_ratio
    assert np.array_equal(back["pressure"].values, sol.pressure)
    back.close()
    # The pressure integrates to one (unit load) by the representation's own rule.
    rule = sol.representation.pressure_rule
    assert abs(rule.weights @ sol.phi - 1.0) < 1e-13


def test_model_answers_as_solve_and_pickles():
    model = Model(5, 10)
    a = model.solve(0.2, lam=-1)
    assert a == solve(5, 0.2, 10, lam=-1)
    back = pickle.loads(pickle.dumps(model))
    assert back == model and back.solve(0.3, lam=-1) == model.solve(0.3, lam=-1)
    assert "Model(pe=5" in repr(model)


def test_unconverged_automatic_solve_warns():
    """At Pe = 1000, K2/K1 = 1000 the graded method cannot reach 1e-14 below n = 256."""
    with pytest.warns(ConvergenceWarning, match="error estimate"):
        sol = solve(1000, 0.3, 1000, lam=-1, tol=1e-14)
    assert sol.status == "not converged" and not sol.success
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        solve(5, 0.2, 10, lam=-1, n=16)  # a given n: the status says it, no warning


def test_caches_are_bounded_and_clearable():
    cache = BoundedCache("test cache", 10_000)
    for i in range(5):
        cache.get(i, lambda: np.zeros(400))  # 3200 bytes each
    assert len(cache) == 3 and cache.bytes == 9600
    assert cache.get(4, lambda: None) is not None  # kept: most recent
    big = cache.get("big", lambda: np.zeros(2000))  # over budget: computed, not kept
    assert big.size == 2000 and "big" not in cache._data
    solve(5, 0.2, 10, lam=-1)
    assert cache_info()["assemblies"][0] > 0
    clear_caches()
    assert all(entries == 0 for entries, _, _ in cache_info().values())
    from thermocontact.numerics.moments import panel_rule

    assert panel_rule.cache_info().currsize == 0  # the small tables too
