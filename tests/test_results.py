"""Results and models as a user (and a process pool) handles them: pickling, equality,
a short repr, records and datasets (the result protocol, for every result class), the
commands' JSON as the results' records, and a Model that answers like solve()."""

import contextlib
import dataclasses
import io
import json
import pickle
import warnings

import numpy as np
import pytest

from thermocontact import ConvergenceWarning, Model, clear_caches, solve
from thermocontact.io.results import FieldResult, Result, plain, same
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


# The result protocol (thermocontact.io.results), for every result of the package.


def _results():
    """One small instance of every result class, built from cheap solves (those of the
    commands below with their arguments, BLAS on one thread as they run)."""
    from thermocontact.analysis.applicability import applicability
    from thermocontact.physics.reference_solutions import barber_insulated
    from thermocontact.problem.parameters import Parameters
    from thermocontact.solvers.elements import solve_elements
    from thermocontact.solvers.refinement import refine
    from thermocontact.studies.boundaries import follow
    from thermocontact.studies.contact_sets import find_contact_set
    from thermocontact.studies.ray import Ray, follow as follow_ray
    from thermocontact.studies.sweeps import sweep

    sol = solve(5, 0.2, 10, lam=-1)
    fixed = dict(pe=5.0, K2_over_K1=10.0, lam=1.0)  # as the CLI's
    path = follow(fixed, "fhpe", 0.0, 2.0, n=16)
    sets = find_contact_set(5.43, 0.5, 10, lam=-1, n=16)
    return {
        "ContactSolution": sol,
        "Validity": sol.validity,
        "Applicability": applicability(sol, 0.01),
        "Curve": sweep("c", dict(pe=5, K2_over_K1=10, lam=-1), "fhpe",
                       np.linspace(0.0, 0.3, 4), n=16),
        "Path": path,
        "Event": path.events[0],
        "RayScan": follow_ray(Ray(10.0, 10.0, 1.0, 0.1, -1.0), 1.0, 10.0, n=8),
        "ContactSetResult": sets,
        "ZoneSolution": sets.answer,
        "ZoneValidity": sets.answer.validity,
        "ElementSolution": solve_elements(Parameters(1.0, 0.0, 10.0), 0.0, elements=100),
        "BarberSolution": barber_insulated(0.3, n=16),
        "Refinement": refine(lambda m: (solve(5, 0.2, 10, lam=-1, n=m),), [8, 16, 32]),
    }


@pytest.fixture(scope="module")
def results():
    return _one_thread(_results)


NAMES = ["ContactSolution", "Validity", "Applicability", "Curve", "Path", "Event", "RayScan",
         "ContactSetResult", "ZoneSolution", "ZoneValidity", "ElementSolution",
         "BarberSolution", "Refinement"]


def _changed(r):
    """``r`` with one field changed: an array (by one element) where it has one."""
    for f in dataclasses.fields(r):
        v = getattr(r, f.name)
        if isinstance(v, np.ndarray) and v.size and v.dtype.kind in "fb":
            w = v.copy()
            w.flat[0] = (not w.flat[0]) if v.dtype.kind == "b" else w.flat[0] + 1.0
            return dataclasses.replace(r, **{f.name: w})
    for f in dataclasses.fields(r):
        v = getattr(r, f.name)
        if isinstance(v, float) and not isinstance(v, bool):
            return dataclasses.replace(r, **{f.name: v + 1.0})
    raise AssertionError(f"{type(r).__name__}: no field to change")


def test_every_result_class_follows_the_protocol():
    """Frozen dataclasses whose equality and repr are the protocol's."""
    import importlib

    classes = {}
    for module in ("analysis.applicability", "analysis.validity", "analysis.zone_validity",
                   "physics.reference_solutions", "solvers.elements", "solvers.refinement",
                   "solvers.result", "solvers.zones", "studies.boundaries",
                   "studies.contact_sets", "studies.ray", "studies.sweeps"):
        mod = importlib.import_module(f"thermocontact.{module}")
        classes.update({k: v for k, v in vars(mod).items()
                        if isinstance(v, type) and issubclass(v, Result)
                        and v not in (Result, FieldResult)})
    assert set(NAMES) <= set(classes)
    for name, cls in classes.items():
        assert dataclasses.is_dataclass(cls) and cls.__dataclass_params__.frozen, name
        assert cls.__eq__ is Result.__eq__ and cls.__repr__ is Result.__repr__, name
        assert cls.__hash__ is None, name


@pytest.mark.parametrize("name", NAMES)
def test_result_pickles_compares_and_records(results, name):
    r = results[name]
    back = pickle.loads(pickle.dumps(r))
    assert back == r and not (back != r)
    other = _changed(r)
    assert (other == r) is False and other != r
    text = repr(r)
    assert text.startswith(name + "(") and "\n" not in text and len(text) < 200, text
    rec = r.to_dict()
    assert json.loads(json.dumps(rec, allow_nan=False)) == rec
    if isinstance(r, FieldResult):
        ds = r.to_dataset()
        assert ds.sizes and all(len(v.dims) == 1 for v in ds.data_vars.values())
        assert all(not isinstance(v, (dict, list)) for v in ds.attrs.values())


def test_field_datasets_hold_the_arrays(results):
    """The generic dataset of a result with fields over one coordinate."""
    curve = results["Curve"]
    ds = curve.to_dataset()
    assert np.array_equal(ds["x"].values, curve.x)
    assert np.array_equal(ds["load_ratio"].values, curve.load_ratio, equal_nan=True)
    assert ds.attrs["n"] == 16 and ds.attrs["error_estimate"] == "none"
    scan = results["RayScan"]
    assert np.array_equal(scan.to_dataset()["load_ratio"].values, scan.load_ratio)
    path = results["Path"]
    assert np.array_equal(path.to_dataset()["valid"].values, path.valid)


def test_equality_is_nan_aware_and_never_raises():
    """NaN equals NaN in arrays and scalars; arrays of different shape, or an array
    against a number, are simply different."""
    a = np.array([1.0, np.nan])
    assert same(a, a.copy()) and same(float("nan"), float("nan"))
    assert not same(a, np.array([1.0])) and not same(a, 1.0) and not same([a], (a,))
    assert same({"x": [a, None]}, {"x": [a.copy(), None]})
    assert plain({"a": np.float64(np.inf), "b": (np.int64(2), np.nan), "c": a}) == {
        "a": None, "b": [2, None], "c": [1.0, None]}
    with pytest.raises(TypeError, match="no JSON record"):
        plain(object())


def _cli_json(args):
    from thermocontact.cli import main

    out = io.StringIO()
    with contextlib.redirect_stdout(out):
        assert main(args + ["--json"]) == 0
    return json.loads(out.getvalue())


def _one_thread(func):
    """``func()`` with BLAS on one thread, as the command runs (same rounding)."""
    from threadpoolctl import threadpool_limits

    with threadpool_limits(limits=1, user_api="blas"):
        return func()


def test_solve_json_is_the_record(results):
    from thermocontact.analysis.applicability import applicability

    args = ["solve", "--pe", "5", "--fhpe", "0.2", "--K2-over-K1", "10", "--lam", "-1"]
    sol = results["ContactSolution"]
    assert _cli_json(args) == sol.to_dict()
    judged = sol.replace(applicability=applicability(sol, 0.01))
    rec = _cli_json(args + ["--delta-over-r", "0.01"])
    assert rec == judged.to_dict() and "applicable" in rec
    # Its entries end the record, before the units (which every record ends with).
    keys, plain_keys = list(rec), list(sol.to_dict())
    assert keys[-1] == plain_keys[-1] == "units"
    assert keys[: len(plain_keys) - 1] == plain_keys[:-1]


def test_boundary_json_is_the_record(results):
    path = results["Path"]
    assert _cli_json(["boundary", "--along", "fhpe", "--from", "0", "--to", "2", "--pe", "5",
                      "--K2-over-K1", "10", "--lam", "1", "-n", "16"]) == path.to_dict()


def test_zones_json_is_the_record(results):
    res = results["ContactSetResult"]
    rec = _cli_json(["zones", "--pe-hertz", "5.43", "--fhpe-hertz", "0.5", "--K2-over-K1",
                     "10", "--lam", "-1", "-n", "16"])
    assert rec == res.to_dict() and rec["status"] == "solved"


def test_the_geometry_cache_counts_everything_it_holds():
    """The moment engine's point geometry and the innermost intervals it adds per kernel
    are counted by the cache that holds them: its bytes are those of its entries."""
    from thermocontact.numerics.cache import nbytes
    from thermocontact.numerics.moment_engine import GEOMETRY, SMALL_GEOMETRY

    clear_caches()
    solve(5, 0.2, 10, lam=-1, n=32)
    assert len(SMALL_GEOMETRY) > 0 and len(GEOMETRY) == 0  # levels 8 to 32: the small n
    solve(5, 0.2, 10, lam=-1, n=128)
    assert len(GEOMETRY) > 0
    for cache in (GEOMETRY, SMALL_GEOMETRY):
        assert cache.bytes == sum(nbytes(v) for v in cache._data.values())
        assert cache.bytes <= cache.max_bytes
    # A broadcast view (a geometry moved from an edge point's) holds its distinct
    # entries only.
    row = np.arange(6.0)
    assert nbytes(np.broadcast_to(row, (1000, 6))) == row.nbytes
    assert nbytes(np.broadcast_to(row[:, None], (6, 7))) == row.nbytes
    assert nbytes(np.zeros((0, 3))) == 0 and nbytes(np.zeros((4, 3))) == 96


def test_transient_entries_are_dropped_and_the_others_kept():
    cache = BoundedCache("transient test cache", 10_000)
    cache.get("kept", lambda: np.zeros(100))
    with cache.transient():
        inside = cache.get("inside", lambda: np.zeros(100))
        assert cache.get("inside", lambda: None) is inside  # reused within the block
        assert cache.get("kept", lambda: None) is not None
    assert "inside" not in cache._data and "kept" in cache._data
    assert len(cache) == 1 and cache.bytes == 800


def test_replace_is_the_dataclass_replace(sol):
    """Result.replace (the fields copied directly where no __post_init__ checks them)
    gives what dataclasses.replace gives, leaves the original alone and refuses an
    unknown field."""
    import dataclasses

    changed = sol.replace(load_ratio=0.5, error_estimate=1e-3)
    assert changed == dataclasses.replace(sol, load_ratio=0.5, error_estimate=1e-3)
    assert changed.load_ratio == 0.5 and sol.load_ratio != 0.5
    assert type(changed) is type(sol) and changed.validity is sol.validity
    with pytest.raises(TypeError, match="no field 'loads'"):
        sol.replace(loads=1.0)
    # A result with a default made by a factory is replaced by the constructor, its
    # unknown fields refused alike.
    import dataclasses as dc

    from thermocontact.io.results import Result

    @dc.dataclass(frozen=True, eq=False, repr=False)
    class Listed(Result):
        a: float
        items: list = dc.field(default_factory=list)
    listed = Listed(1.0).replace(a=2.0)
    assert listed == Listed(2.0) and listed.items == []
    with pytest.raises(TypeError, match="Listed has no field 'b'"):
        Listed(1.0).replace(b=2.0)


def test_build_is_the_constructor(sol):
    """Result.build (no constructor where no __post_init__ checks the fields) gives what
    the constructor gives, defaults included, pickles alike, and leaves a missing or
    unknown field to the constructor's own error."""
    import dataclasses
    import pickle

    from thermocontact.analysis.validity import Validity

    values = {f.name: getattr(sol, f.name) for f in dataclasses.fields(sol)
              if f.name not in ("error_estimate", "tol")}
    built = type(sol).build(**values)
    assert built == type(sol)(**values) and type(built) is type(sol)
    assert built.error_estimate is None and pickle.loads(pickle.dumps(built)) == built
    v = {f.name: getattr(sol.validity, f.name) for f in dataclasses.fields(sol.validity)
         if f.default is dataclasses.MISSING}
    assert Validity.build(**v) == Validity(**v)
    with pytest.raises(TypeError):
        Validity.build(**{k: x for k, x in v.items() if k != "valid"})
    with pytest.raises(TypeError):
        Validity.build(**v, loads=1.0)


def test_replace_carries_the_fields_only():
    """A result whose dict also holds something derived (a cached property) is
    replaced with its fields only, as the dataclass replace makes it; one without
    such entries keeps its dict's fields exactly."""
    import dataclasses as dc
    import functools

    from thermocontact.io.results import Result

    @dc.dataclass(frozen=True, eq=False, repr=False)
    class Cached(Result):
        a: float
        b: float = 2.0

        @functools.cached_property
        def total(self):
            return self.a + self.b

    c = Cached(1.0)
    assert c.total == 3.0 and "total" in vars(c)
    changed = c.replace(a=5.0)
    assert vars(changed) == {"a": 5.0, "b": 2.0} and changed.total == 7.0
    assert vars(Cached(1.0).replace(b=4.0)) == {"a": 1.0, "b": 4.0}
    # As many entries as fields but not the fields: copied field by field (a field
    # missing is the copy's own error, as it always was).
    odd = Cached(1.0)
    assert odd.total == 3.0
    object.__getattribute__(odd, "__dict__").pop("b")
    with pytest.raises(KeyError):
        odd.replace(a=5.0)


def test_build_each_is_build_per_row(sol):
    """Result.build_each gives per row what build gives, defaults included; a name
    missing or unknown goes to the constructor's own error, a repeated one is the
    last value's (as in a dict)."""
    import dataclasses

    from thermocontact.analysis.validity import Validity

    v = {f.name: getattr(sol.validity, f.name) for f in dataclasses.fields(sol.validity)
         if f.default is dataclasses.MISSING}
    rows = [tuple(v.values()), tuple(v.values())]
    built = Validity.build_each(v.keys(), rows)
    assert built == [Validity.build(**v)] * 2 and built[0] is not built[1]
    full = {f.name: getattr(sol.validity, f.name) for f in dataclasses.fields(sol.validity)}
    assert Validity.build_each(full, [tuple(full.values())]) == [sol.validity]
    assert Validity.build_each(v, []) == []
    with pytest.raises(TypeError):
        Validity.build_each([k for k in v if k != "valid"], [tuple(v.values())[1:]])
    with pytest.raises(TypeError):
        Validity.build_each([*v, "loads"], [(*v.values(), 1.0)])
    flipped = Validity.build_each([*v, "valid"], [(*v.values(), not v["valid"])])
    assert flipped == [Validity.build(**{**v, "valid": not v["valid"]})]
    # A row shorter than the names is build's: a missing field refused, a missing
    # default filled in.
    with pytest.raises(TypeError):
        Validity.build_each(v, [tuple(v.values())[:-1]])
    last = list(full)[-1]
    short = Validity.build_each(full, [tuple(full.values())[:-1]])[0]
    assert short == Validity.build(**{k: x for k, x in full.items() if k != last})
    assert short.replace(valid=True).valid is True
