"""Every public call of the Python API given an argument of a wrong type (None where a
value is needed, a string that is no number, a boolean where a number or a count is
asked, a number where a switch is, a sequence of the wrong length, any other object)
refuses it with an InputError naming it, never another exception (properties with
Hypothesis).

Each call starts from valid, cheap inputs and one of them is replaced; the wrong values
are refused before any work, so the whole file costs a few seconds.  (The stability
analysis's inputs are checked in its own tests.)
"""

import warnings

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

import thermocontact as tc
from thermocontact.problem.materials import get_material
from thermocontact.problem.validation import InputError

# Wrong values by the kind of parameter.  Strings that are no number use characters
# that no unit parser reads either.
_GARBAGE = st.sampled_from([object(), {}, {"a": 1}, [], set(), 1j])
_NOT_A_NUMBER = st.one_of(
    st.sampled_from([True, False, "", "x", "1,5", "nan", "inf", "-inf", "1e999", (), (1.0,),
                     (1.0, 2.0), [3.0], float("nan"), float("inf"), float("-inf")]),
    st.text(alphabet="#@?~^", min_size=1, max_size=4), _GARBAGE)
_NOT_A_COUNT = st.one_of(st.sampled_from([True, False, 1.5, "x", "", "8.5", (8,), float("nan"),
                                          float("inf")]),
                         st.floats(allow_nan=False, allow_infinity=False).filter(
                             lambda v: not v.is_integer()), _GARBAGE)
_NOT_A_SWITCH = st.one_of(st.sampled_from(["yes", "no", "True", "False", "", 1, 0, 2.0,
                                           (True,), [False]]), st.integers(), _GARBAGE)
_NOT_A_PAIR = st.one_of(st.sampled_from(["1:0", "1,0", "x", (), (1.0,), (1.0, 0.0, 1.0),
                                         ("a", "b"), (True, 0.0), (1.0, None), 1.0, True]),
                        st.lists(st.floats(0.1, 2.0), min_size=3, max_size=5).map(tuple),
                        _GARBAGE)
_NOT_A_NAME = st.one_of(st.sampled_from(["", "no-such-thing", 3, 3.5, True, ("graded",)]),
                        st.text(alphabet="#@?~^", min_size=1, max_size=6), _GARBAGE)
_NOT_A_CALLABLE = st.one_of(st.sampled_from([3, "x", True, (1,), 0.5]), _GARBAGE)
_NOT_AN_AXIS = st.one_of(st.sampled_from(["fhpe:0:1:3", ("fhpe", 0, 1, 3), 3, True, "x"]),
                         _GARBAGE)
_NOT_TEMPERATURES = st.one_of(st.sampled_from(["x", "20C", "20C,30C,40C", "20C,", (1.0,),
                                               (1.0, 2.0, 3.0), ("a", "b"), (True, 300.0),
                                               300.0, True]), _GARBAGE)

_NOT_TEXT = st.one_of(st.sampled_from([None, 3, 2.5, True, ("fhpe",)]), _GARBAGE)
_NOT_WORKERS = st.one_of(st.sampled_from(["x", "", True, 2.5, (2,)]), _GARBAGE)

WRONG = {"number": _NOT_A_NUMBER, "text": _NOT_TEXT, "workers": _NOT_WORKERS, "count": _NOT_A_COUNT, "switch": _NOT_A_SWITCH,
         "pair": _NOT_A_PAIR, "name": _NOT_A_NAME, "callable": _NOT_A_CALLABLE,
         "axis": _NOT_AN_AXIS, "temperatures": _NOT_TEMPERATURES,
         "object": st.one_of(st.sampled_from([3, "x", True, 2.5]), _GARBAGE)}

COPPER, STEEL = get_material("copper"), get_material("steel")
FHPE, PE = tc.Axis("fhpe", 0, 0.5, 2), tc.Axis("pe", 1, 5, 2)
PHYSICAL = dict(cylinder="copper", half_plane="steel", radius="10mm", load="50kN/m",
                speed="2m/s", friction=0.2)
RUN = dict(pe_hertz=2.7, fhpe_hertz=0.36, K2_over_K1=10, until=0.1, steps=2, elements=8,
           lam=1)
DIMENSIONLESS = {k: "number" for k in ("pe", "fhpe", "K2_over_K1", "k2_over_k1",
                                        "delta1_over_delta2", "speed_ratio", "beta_f", "lam",
                                        "theta", "sink_distance")}
QUANTITIES = {k: "number" for k in ("radius", "load", "speed", "friction", "lam")}
SINKS = {"sink_distance": "number", "layer_thickness": "number"}
TRANSIENT = {**{k: "number" for k in ("pe_hertz", "fhpe_hertz", "K2_over_K1", "until", "lam",
                                       "theta", "k2_over_k1", "delta1_over_delta2",
                                       "perturb")},
             "steps": "count", "elements": "count", "window": "pair", "initial": "name",
             "hold": "name", "conductance": "pair"}


def _spec():
    return tc.transient_spec(**RUN)


def _dataset():
    return tc.transient(**RUN).to_dataset()


#: name: (call, valid inputs, {parameter: kind of its wrong values}).
CALLS = {
    "solve": (tc.solve, dict(pe=5, fhpe=0.2, K2_over_K1=10, lam=1, n=8),
              {**DIMENSIONLESS, "sigma_over_delta": "number", "tol": "number",
               "delta_over_r": "number", "n": "count", "method": "name",
               "check_convergence": "switch", "progress": "callable", "conductance": "pair"}),
    "Model": (tc.Model, dict(pe=5, K2_over_K1=10, n=8),
              {**{k: "number" for k in ("pe", "K2_over_K1", "k2_over_k1", "delta1_over_delta2",
                                         "speed_ratio", "beta_f", "tol")},
               "n": "count", "method": "name", "conductance": "pair"}),
    "Parameters": (tc.Parameters, dict(pe=5, fhpe=0.2, K2_over_K1=10),
                   {k: "number" for k in ("pe", "fhpe", "K2_over_K1", "k2_over_k1",
                                          "delta1_over_delta2", "speed_ratio", "beta_f")}),
    "Axis": (tc.Axis, dict(name="fhpe", start=0, stop=1, count=3),
             {"name": "text", "start": "number", "stop": "number", "count": "count",
              "log": "switch"}),
    "Material": (tc.Material, dict(name="m", E=2e11, nu=0.3, alpha=1e-5, K=50, k=1e-5),
                 {**{k: "number" for k in ("E", "nu", "alpha", "K", "k",
                                           "max_temperature")}}),
    "PhysicalProblem": (tc.PhysicalProblem,
                        dict(cylinder=COPPER, half_plane=STEEL, radius=0.01, load=5e4,
                             speed=2, friction=0.2, lam=-1),
                        {**{k: "number" for k in ("radius", "load", "speed", "friction",
                                                  "lam", "speed2")},
                         "cylinder": "object", "half_plane": "object", "dundurs": "switch"}),
    "contact": (tc.contact, dict(PHYSICAL, lam=-1),
                {**QUANTITIES, **SINKS, "speed2": "number", "cylinder": "name",
                 "half_plane": "name", "tol": "number",
                 "dundurs": "switch", "zones": "switch", "materials": "name",
                 "progress": "callable", "bulk_temperatures": "temperatures",
                 "closure": "object"}),
    "contact_set": (tc.contact_set, dict(pe_hertz=5.43, fhpe_hertz=0.0, K2_over_K1=10, lam=1,
                                         n=8),
                    {**{k: "number" for k in ("pe_hertz", "fhpe_hertz", "K2_over_K1", "lam",
                                              "k2_over_k1", "delta1_over_delta2",
                                              "sigma_over_delta", "theta",
                                              "sink_distance")},
                     "n": "count", "conductance": "pair", "progress": "callable",
                     "closure": "object"}),
    "boundary": (tc.boundary, dict(along="fhpe", start=0, stop=0.1, pe=5, K2_over_K1=10,
                                   lam=1, n=8),
                 {**DIMENSIONLESS, "along": "name", "start": "number", "stop": "number",
                  "sigma": "number", "sigma_over_delta": "number", "closure": "object",
                  "tol": "number", "n": "count", "method": "name", "progress": "callable"}),
    "map_spec": (tc.map_spec, dict(x=FHPE, y=PE, K2_over_K1=10, lam=1),
                 {**DIMENSIONLESS, "x": "axis", "y": "axis", "sigma": "number",
                  "sigma_over_delta": "number", "closure": "object",
                  "delta_over_r": "number", "tol": "number", "method": "name"}),
    "parameter_map": (tc.parameter_map, dict(x=FHPE, y=PE, K2_over_K1=10, lam=1),
                      {**DIMENSIONLESS, "x": "axis", "y": "axis", "tol": "number",
                       "method": "name", "progress": "callable", "workers": "workers"}),
    "operating_map": (tc.operating_map,
                      dict(x=tc.Axis("speed", 1, 2, 2), y=tc.Axis("load", 1e4, 2e4, 2),
                           cylinder="copper", half_plane="steel", friction=0.2, lam=-1,
                           radius="10mm"),
                      {**QUANTITIES, **SINKS, "speed_ratio": "number", "x": "axis",
                       "y": "axis", "cylinder": "name", "half_plane": "name", "tol": "number",
                       "dundurs": "switch",
                       "zones": "switch", "progress": "callable", "workers": "workers",
                       "bulk_temperatures": "temperatures", "closure": "object"}),
    "compute_map": (lambda **kw: tc.compute_map(**kw),
                    dict(spec=tc.map_spec(FHPE, PE, K2_over_K1=10, lam=1)),
                    {"spec": "object", "progress": "callable", "workers": "workers"}),
    "tei": (tc.tei, dict(slider="steel", counterface="cast-iron", friction=0.3,
                         wavelength="50mm"),
            {"slider": "name", "counterface": "name", "friction": "number",
             "wavelength": "number", "speed": "number", "dundurs": "switch",
             "materials": "name"}),
    "transient_spec": (tc.transient_spec, RUN, {**TRANSIENT, "closure": "object"}),
    "TransientSpec": (tc.TransientSpec, RUN, TRANSIENT),
    "transient": (tc.transient, RUN, {**TRANSIENT, "closure": "object", "progress": "callable",
                                      "save": "callable",
                                      "preparing": "callable", "resume": "object"}),
    "compute_transient": (lambda **kw: tc.compute_transient(**kw), dict(spec=_spec()),
                          {"spec": "object", "resume": "object", "progress": "callable",
                           "save": "callable", "save_every": "number",
                           "preparing": "callable"}),
    "read_transient": (tc.read_transient, dict(ds=_dataset()), {"ds": "object"}),
    "contact_transient_spec": (
        tc.contact_transient_spec, dict(PHYSICAL, lam=-1, dundurs=False, duration="1ms",
                                        steps=5, elements=16),
        {**QUANTITIES, "duration": "number", "steps": "count", "elements": "count",
         "window": "pair", "dundurs": "switch", "cylinder": "name", "half_plane": "name"}),
    "contact_transient": (
        tc.contact_transient, dict(PHYSICAL, lam=-1, dundurs=False, duration="1ms",
                                   steps=5, elements=16),
        {**QUANTITIES, "duration": "number", "steps": "count", "elements": "count",
         "window": "pair", "dundurs": "switch", "progress": "callable",
         "preparing": "callable"}),
}


@pytest.mark.parametrize("name", sorted(CALLS))
@settings(max_examples=40, deadline=None, derandomize=True, database=None,
          suppress_health_check=[HealthCheck.too_slow])
@given(data=st.data())
def test_a_wrong_type_is_an_input_error(name, data):
    call, valid, kinds = CALLS[name]
    parameter = data.draw(st.sampled_from(sorted(kinds)), label="parameter")
    value = data.draw(WRONG[kinds[parameter]], label="value")
    try:
        with warnings.catch_warnings():
            # The spellings before 1.0 (sigma=) are checked too; their warning is
            # tests/test_public_face.py's.
            warnings.simplefilter("ignore", DeprecationWarning)
            call(**{**valid, parameter: value})
    except InputError as exc:
        assert "\n" not in str(exc)
        return
    except Exception as exc:  # the defect this test is for
        pytest.fail(f"{name}({parameter}={value!r}) raised {type(exc).__name__}: {exc}")
    pytest.fail(f"{name}({parameter}={value!r}) was accepted")
