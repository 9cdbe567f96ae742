"""The public face of version 1.0, read off the package itself (not a hand-written list):

* every input of every public call is a name of the one vocabulary
  (thermocontact.problem.vocabulary), so that a quantity has one name and a name one
  unit across the calls;
* every call in ``thermocontact.__all__`` declares what it returns, and every result it
  returns follows the one protocol (io/results.py): frozen, picklable, equal by value, a
  one-line repr, a strict JSON record with ``status`` (one of its kind's documented
  words), ``message``, ``success`` and ``units``, a dataset with CF ``units`` where it
  has fields.
"""

import dataclasses
import inspect
import json
import pickle

import pytest

import thermocontact as tc
from thermocontact.io.results import FieldResult, Result
from thermocontact.problem.vocabulary import DEPRECATED, VOCABULARY

#: What a call may return besides a result: a specification (made by the *_spec calls,
#: to be run by a compute_* call), a map's dataset, nothing.
NOT_RESULTS = {"MapSpec", "OperatingSpec", "TransientSpec", "tuple", "xarray.Dataset", "None",
               "list"}


#: Where the classes a user makes as inputs live (the closures, axes, materials and
#: dimensionless parameters); the others of ``__all__`` are made by the calls (results,
#: specifications, records, methods) from inputs named here.
INPUT_MODULES = ("thermocontact.problem.closure", "thermocontact.problem.axes",
                 "thermocontact.problem.materials", "thermocontact.problem.parameters",
                 "thermocontact.solvers.single_patch")


def _calls():
    """``(name, function)`` of every public call: the functions of ``__all__`` and the
    constructors and public methods of its input classes (Model, Axis, the closures,
    Material, Parameters)."""
    for name in tc.__all__:
        obj = getattr(tc, name)
        if inspect.isfunction(obj):
            yield name, obj
        elif (inspect.isclass(obj) and obj.__module__ in INPUT_MODULES
              and not issubclass(obj, (BaseException, Result))):
            yield name, obj
            for attr, member in vars(obj).items():
                if inspect.isfunction(member) and not attr.startswith("_"):
                    yield f"{name}.{attr}", member


def _inputs(func):
    sig = inspect.signature(func)
    return [p.name for p in sig.parameters.values()
            if p.name not in ("self", "cls") and not p.name.startswith("_")
            and p.kind not in (p.VAR_POSITIONAL, p.VAR_KEYWORD)]


def test_every_input_name_is_in_the_vocabulary():
    """One table of names and units (thermocontact.problem.vocabulary.VOCABULARY): a name
    outside it (a second name for a quantity, ``sigma`` beside ``sigma_over_delta``) or a
    spelling of earlier versions fails here."""
    unknown = {(label, name) for label, func in _calls() for name in _inputs(func)
               if name not in VOCABULARY}
    assert unknown == set()


def test_the_vocabulary_gives_one_unit_and_one_meaning_per_name():
    meanings = [meaning for _, meaning in VOCABULARY.values()]
    assert len(set(meanings)) == len(meanings)  # no quantity under two names
    assert all(isinstance(unit, str) for unit, _ in VOCABULARY.values())
    # A spelling of earlier versions is no name of 1.0 (it is taken through the
    # deprecation layer only), or names there one quantity of one unit only.
    assert {"sigma", "bulk_temperatures"} <= set(DEPRECATED) - set(VOCABULARY)
    assert set(DEPRECATED).isdisjoint({"sigma_over_delta", "closure", "initial"})


def test_the_spellings_of_earlier_versions_still_answer_with_a_warning():
    """sigma=, theta= with sink_distance= (L/Delta), bulk_temperatures= with
    sink_distance= (m), contact(zones=True), transient(start=): the same answer as the
    1.0 spelling, and a DeprecationWarning naming what replaces it."""
    import warnings

    cases = [
        (lambda: tc.solve(5, 0.2, 10, theta=1.0, sink_distance=30.0),
         lambda: tc.solve(5, 0.2, 10, closure=tc.FarTemperatures(1.0, 30.0)), "FarTemperatures"),
        (lambda: tc.map_spec(tc.Axis("fhpe", 0, 0.4, 3), tc.Axis("pe", 1, 2, 2), K2_over_K1=10,
                             sigma=0.1),
         lambda: tc.map_spec(tc.Axis("fhpe", 0, 0.4, 3), tc.Axis("pe", 1, 2, 2), K2_over_K1=10,
                             sigma_over_delta=0.1), "sigma_over_delta"),
        (lambda: tc.transient_spec(2.7, 0.36, 10, lam=1, until=1, steps=5, start="hertz"),
         lambda: tc.transient_spec(2.7, 0.36, 10, lam=1, until=1, steps=5, initial="hertz"),
         "initial"),
    ]
    for old, new, replacement in cases:
        with warnings.catch_warnings(record=True) as seen:
            warnings.simplefilter("always")
            before = old()
        assert any(issubclass(w.category, DeprecationWarning) and replacement in str(w.message)
                   and w.filename == __file__ for w in seen), seen
        with warnings.catch_warnings():
            warnings.simplefilter("error", DeprecationWarning)
            after = new()
        assert (before.manifest() if hasattr(before, "manifest") else before) == (
            after.manifest() if hasattr(after, "manifest") else after)


def test_the_closure_is_one_value_for_every_call():
    """closure=HeatPartition(lam) is lam=; two closures, or one of another kind, are
    refused in one line naming them."""
    kw = dict(cylinder="copper", half_plane="steel", radius="10mm", load="50kN/m",
              speed="2m/s", friction=0.2)
    assert (tc.contact(**kw, closure=tc.HeatPartition(-1)).to_dict()
            == tc.contact(**kw, lam=-1).to_dict())
    with pytest.raises(tc.InputError, match="give exactly one closure, got closure and lam"):
        tc.contact(**kw, lam=-1, closure=tc.HeatPartition(-1))
    with pytest.raises(tc.InputError, match="closure must be HeatPartition or BulkTemperatures"):
        tc.contact(**kw, closure=tc.Offset(0.1))
    with pytest.raises(tc.InputError, match="closure must be given"):
        tc.solve(5, 0.2, 10)


def _returned(func) -> list:
    """The names a call's return annotation gives (``A | B``)."""
    ann = inspect.signature(func).return_annotation
    assert ann is not inspect.Signature.empty, f"{func.__qualname__} declares no return type"
    text = ann if isinstance(ann, str) else getattr(ann, "__name__", str(ann))
    return [part.strip().strip("'\"") for part in text.split("|")]


def _answering_calls():
    """The calls that answer a question: the functions of ``__all__`` and Model.solve
    (a class's other methods return its own parts)."""
    yield from ((label, func) for label, func in _calls()
                if inspect.isfunction(func) and "." not in label)
    yield "Model.solve", tc.Model.solve


def _result_types():
    types = {}
    for label, func in _answering_calls():
        for name in _returned(func):
            if name in NOT_RESULTS:
                continue
            assert name in tc.__all__, f"{label} returns {name}, not a public name"
            types[name] = getattr(tc, name)
    return types


def test_every_call_declares_a_public_result_type():
    types = _result_types()
    assert {"ContactSolution", "PhysicalContact", "ContactSetResult", "Path", "TEIResult",
            "StabilityResult", "TransientRun"} <= set(types)


@pytest.mark.parametrize("name", sorted(_result_types()))
def test_every_result_type_follows_the_protocol(name):
    cls = getattr(tc, name)
    assert issubclass(cls, Result), name
    assert dataclasses.is_dataclass(cls) and cls.__dataclass_params__.frozen, name
    assert cls.__eq__ is Result.__eq__ and cls.__repr__ is Result.__repr__, name
    assert cls.__hash__ is None
    assert isinstance(cls.STATUSES, dict) and cls.STATUSES, name
    assert all(isinstance(k, str) and isinstance(v, str) and v for k, v in cls.STATUSES.items())
    assert cls.SUCCESS and cls.SUCCESS <= set(cls.STATUSES), name
    assert isinstance(cls.UNITS, dict) and cls.UNITS, name


@pytest.fixture(scope="module")
def results():
    """One result of every kind a public call returns, cheaply made."""
    import warnings

    with warnings.catch_warnings():
        warnings.simplefilter("ignore", tc.ConvergenceWarning)
        sol = tc.solve(5, 0.2, 10, lam=-1, n=16)
        made = {
            "ContactSolution": sol,
            "PhysicalContact": tc.contact("copper", "steel", radius="10mm", load="50kN/m",
                                          speed="2m/s", friction=0.2, lam=-1),
            "ContactSetResult": tc.contact_set(5.43, 0.3, 10, lam=1, n=16),
            "PhysicalContactSet": tc.contact_set(cylinder="copper", half_plane="steel",
                                                 radius="10mm", load="50kN/m", speed=2,
                                                 friction=0.2, lam=-1, n=16),
            "Path": tc.boundary("fhpe", 0, 1, pe=5, K2_over_K1=10, lam=1, n=16),
            "TEIResult": tc.tei("steel", "organic-composite-brake-block", 0.4, "50mm",
                                speed=30),
            "TransientRun": tc.transient(2.7, 0.36, 10, lam=1, until=0.2, steps=10,
                                         elements=48),
            "StabilityResult": tc.stability(tc.solve(1.0, 0.3, 1, lam=-1, n=8), n=8),
        }
    return made


def test_the_instances_cover_every_result_type(results):
    assert set(_result_types()) <= set(results)


@pytest.mark.parametrize("name", ["ContactSolution", "PhysicalContact", "ContactSetResult",
                                  "PhysicalContactSet", "Path", "TEIResult", "TransientRun",
                                  "StabilityResult"])
def test_every_result_is_an_outcome_with_a_strict_record(results, name):
    r = results[name]
    assert r.status in type(r).STATUSES, (name, r.status)
    assert isinstance(r.message, str) and r.message, name
    assert isinstance(r.success, bool) and (not r.success or r.status in type(r).SUCCESS)
    rec = r.to_dict()
    assert json.loads(json.dumps(rec, allow_nan=False)) == rec
    assert (rec["status"], rec["message"], rec["success"]) == (r.status, r.message, r.success)
    assert isinstance(rec["units"], dict) and rec["units"]
    assert all(isinstance(u, str) for u in rec["units"].values())
    back = pickle.loads(pickle.dumps(r))
    assert back == r and not (back != r)
    text = repr(r)
    assert text.startswith(type(r).__name__ + "(") and "\n" not in text and len(text) < 300
    if isinstance(r, FieldResult) or hasattr(r, "to_dataset"):
        ds = r.to_dataset()
        for var in ds.variables:
            if var in rec["units"]:
                assert ds[var].attrs.get("units"), (name, var)


def test_every_public_name_is_in_one_group_of_the_reference():
    """The API reference groups the public names (thermocontact.GROUPS): each name of
    ``__all__`` in exactly one group, no other."""
    grouped = [name for names in tc.GROUPS.values() for name in names]
    assert sorted(grouped) == sorted(tc.__all__)
    assert len(grouped) == len(set(grouped))
