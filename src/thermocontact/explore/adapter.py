"""Every call of the explorer into the library, in this one module.

The page speaks the keyword names of :func:`thermocontact.contact` (its query string's
keys are those names, its fields hold the strings a user types, ``"10mm"``,
``"50kN/m"``); this module turns them into the public calls (:func:`~thermocontact.contact`,
:func:`~thermocontact.map_spec` and :func:`~thermocontact.compute_map`,
:func:`~thermocontact.tei`, :func:`~thermocontact.contact_transient`) and their
results into the plain JSON the page draws.  Nothing here computes physics: every
number shown is a result's record value (``to_dict()``), tagged with its key, so that
a renamed keyword or record key changes this module and nothing else of the explorer.

A *state* is a dict of the page's field names to strings (absent or empty: not
given).  A *view* is a dict of plain JSON: ``numbers`` (each with the record key it
comes from, its full-precision ``repr`` and a short text), ``curves``, ``verdicts``
and ``code``.
"""

from __future__ import annotations

import functools
import json
import math
import os
import shlex

import numpy as np

from .. import api
from ..io.datasets import write_dataset
from ..io.results import plain
from ..io.tables import write_contact_csv
from ..physics.reference_solutions import hertz_pressure
from ..problem.axes import Axis
from ..problem.closure import spelled_closure
from ..problem.errors import Error, SolveError
from ..problem.materials import get_material, list_materials, material_aliases
from ..problem.units import parse_quantity
from ..problem.validation import InputError

__all__ = ["DEFAULTS", "EXPECTED", "FIELDS", "UserError", "code_for", "contact_csv",
           "contact_record", "contact_view", "explain", "job_key", "parse_state", "record_value",
           "run_job", "setup", "tei_view"]

#: The single contact's fields: the keyword names of :func:`thermocontact.contact`, with
#: the page's defaults (the README's copper-on-steel contact) and their SI units
#: (``None``: not a quantity with a unit).
POINT = {
    "cylinder": ("copper", None), "half_plane": ("steel", None),
    "radius": ("10mm", "m"), "load": ("50kN/m", "N/m"), "speed": ("2m/s", "m/s"),
    "speed2": ("0", "m/s"), "friction": ("0.2", None), "lam": ("-1", None),
    "bulk_temperatures": ("", None), "sink_distance": ("", "m"),
    "layer_thickness": ("", "m"), "dundurs": ("true", None),
}
#: The other tabs' fields: the map's axes (``x``, ``y`` of
#: :func:`thermocontact.operating_map`, written as ``name:start:stop:count:log`` in SI
#: units), the TEI's wavelength (:func:`thermocontact.tei`) and the transient run's
#: duration, steps and elements (:func:`thermocontact.contact_transient`; an empty
#: duration is :data:`TRANSIENT_UNITS` times ``l^2/kappa2``).
EXTRA = {
    "x": ("load:1000:1000000:21:log", None), "y": ("speed:0.1:50:21:log", None),
    "wavelength": ("50mm", "m"),
    "duration": ("", "s"), "steps": ("200", None), "elements": ("120", None),
}
DEFAULTS = {k: v for k, (v, _) in {**POINT, **EXTRA}.items()}
FIELDS = tuple(DEFAULTS)
#: The longest text a field takes (a material defined inline is the longest).
MAX_LENGTH = 200
#: An empty transient duration: this many ``l^2/kappa2``.
TRANSIENT_UNITS = 3.0
#: Frames of the transient's space-time picture sent to the page, at most.
FRAMES = 150
#: Wavelengths of the TEI curve (each a call of :func:`thermocontact.tei`), over
#: ``TEI_DECADES`` either side of the wavelength chosen.
TEI_POINTS, TEI_DECADES = 9, 2.0

#: The numbers the contact tab shows: record key (a path into ``to_dict()``), label,
#: unit shown and its factor from SI.
CONTACT_NUMBERS = (
    ("half_width", "half-width Δ", "mm", 1e3),
    ("offset", "offset", "mm", 1e3),
    ("a", "trailing edge a", "mm", 1e3),
    ("b", "leading edge b", "mm", 1e3),
    ("peak_pressure", "peak pressure", "MPa", 1e-6),
    ("mean_pressure", "mean pressure", "MPa", 1e-6),
    ("hertz_half_width", "Hertz half-width", "mm", 1e3),
    ("hertz_peak_pressure", "Hertz peak pressure", "MPa", 1e-6),
    ("flash_temperature", "flash temperature", "K", 1.0),
    ("lam", "heat partition λ", "", 1.0),
    ("lam_error", "error of λ", "", 1.0),
    ("peak_temperatures[0]", "peak temperature", "K", 1.0),
    ("flash_temperatures[1]", "half-plane's flash temperature", "K", 1.0),
    ("heat_cylinder", "heat into the cylinder", "W/m", 1.0),
    ("heat_half_plane", "heat into the half-plane", "W/m", 1.0),
    ("pe", "Péclet number Pe", "", 1.0),
    ("fhpe", "coupling fHPe", "", 1.0),
    ("error_estimate", "error estimate of P_H/P", "", 1.0),
)
#: Numbers of the primary branch, from ``branches[i]`` of the record: its validity
#: margins, and a moving half-plane's temperatures.
BRANCH_NUMBERS = (
    ("min_pressure_margin", "least pressure margin", "", 1.0),
    ("min_gap_margin", "least gap margin", "", 1.0),
    # A moving half-plane, lam given: its incoming temperature the partition implies.
    ("half_plane_incoming_temperature", "half-plane's incoming temperature over the "
                                        "cylinder's", "K", 1.0),
    ("flash_temperature_half_plane", "half-plane's flash temperature", "K", 1.0),
)
TEI_NUMBERS = (
    ("critical_speed", "critical speed", "m/s", 1.0),
    ("migration_speed", "migration speed", "m/s", 1.0),
    ("speed", "sliding speed", "m/s", 1.0),
    ("modes[0].growth_rate", "growth rate", "1/s", 1.0),
    ("most_unstable_wavelength", "most unstable wavelength", "mm", 1e3),
    ("most_unstable_growth_rate", "its growth rate", "1/s", 1.0),
)


#: The library's errors of bad input or of no solution: the page's words, never a
#: traceback (:func:`explain`).
EXPECTED = (InputError, SolveError)


class UserError(Error):
    """What the page tells a user about bad input: a message per field and one for all.

    Attributes
    ----------
    fields : dict
        Field name -> one-line message naming it.
    message : str
        One line for the whole request.
    """

    def __init__(self, message, fields=None):
        super().__init__(message)
        self.message = message
        self.fields = dict(fields or {})

    def to_dict(self) -> dict:
        return {"message": self.message, "fields": self.fields}


def explain(exc: BaseException, fields=FIELDS) -> UserError:
    """The page's words for an error: an :class:`~thermocontact.InputError` next to the
    fields it names; a solve that failed as one line; anything else as one line naming
    its kind, never a traceback."""
    if isinstance(exc, UserError):
        return exc
    if isinstance(exc, InputError):
        named = [p for p in getattr(exc, "parameters", ()) if p in fields]
        return UserError(str(exc), {p: str(exc) for p in named})
    if isinstance(exc, SolveError):
        return UserError(f"no solution: {exc}")
    return UserError(f"the computation failed ({type(exc).__name__}: {exc})")


def parse_state(query) -> dict:
    """The page's state from a query (a mapping of names to strings, or to lists of
    them as :func:`urllib.parse.parse_qs` gives): known fields only, stripped;
    refused in one line per field when too long or given twice."""
    state, errors = {}, {}
    for name, value in query.items():
        if name not in DEFAULTS and name != "tab":
            continue  # the page's own keys (a tab) or a stranger's: not inputs
        if isinstance(value, (list, tuple)):
            if len(value) != 1:
                errors[name] = f"{name} must be given once, got {len(value)} values"
                continue
            value = value[0]
        text = str(value).strip()
        if len(text) > MAX_LENGTH:
            errors[name] = f"{name} must be at most {MAX_LENGTH} characters"
            continue
        state[name] = text
    if errors:
        raise UserError("; ".join(errors.values()), errors)
    return state


def _given(state, name):
    """The field's text, or None when empty or absent."""
    text = state.get(name, "")
    return text if text != "" else None


def _number(state, name, kind=float):
    text = _given(state, name)
    if text is None:
        return None
    try:
        value = kind(text)
    except ValueError:
        what = "a number" if kind is float else "an integer"
        raise InputError(f"{name} must be {what}, got {text!r}", parameters=(name,)) from None
    if kind is float and not math.isfinite(value):
        raise InputError(f"{name} must be finite, got {text!r}", parameters=(name,))
    return value


def _switch(state, name):
    text = (_given(state, name) or DEFAULTS[name]).lower()
    if text not in ("true", "false", "1", "0", "yes", "no"):
        raise InputError(f"{name} must be true or false, got {text!r}", parameters=(name,))
    return text in ("true", "1", "yes")


#: The fields :func:`thermocontact.contact` needs.
REQUIRED = ("cylinder", "half_plane", "radius", "load", "speed", "friction")


def contact_kwargs(state) -> dict:
    """The keyword arguments of :func:`thermocontact.contact` for ``state``, each field
    read on its own first so that an error is shown next to the field it is in."""
    closure = "lam" in state or "bulk_temperatures" in state
    # Absent keys take the defaults; the closure's only when neither is given.
    state = {**{k: v for k, (v, _) in POINT.items() if closure is False or k != "lam"},
             **state}
    errors, kw = {}, {}
    for name, (_, unit) in POINT.items():
        try:
            if name in REQUIRED and _given(state, name) is None:
                raise InputError(f"{name} must be given", parameters=(name,))
            if name in ("cylinder", "half_plane"):
                text = _given(state, name)
                try:
                    get_material(text)
                except InputError as exc:
                    raise InputError(f"{name}: {exc}", parameters=(name,)) from None
                kw[name] = text
            elif name in ("friction", "lam"):
                value = _number(state, name)
                if value is not None:
                    kw[name] = value
            elif name == "dundurs":
                kw[name] = _switch(state, name)
            elif _given(state, name) is not None:
                text = _given(state, name)
                if unit is not None and name != "bulk_temperatures":
                    parse_quantity(text, unit, name)  # read alone, to name the field
                kw[name] = text
        except InputError as exc:
            errors[name] = str(exc)
    if errors:
        raise UserError("; ".join(errors.values()), errors)
    return kw


def _call(func, *args, **kwargs):
    """A library call whose errors reach the page as :class:`UserError`."""
    try:
        return func(*args, **kwargs)
    except (InputError, SolveError) as exc:
        raise explain(exc) from None


def contact_of(state):
    """The :class:`~thermocontact.PhysicalContact` of ``state`` (the last
    :data:`CACHED` kept: the tabs, the code and the downloads of one point share it)."""
    return _contact(tuple(sorted(contact_kwargs(state).items())))


#: Contacts kept by :func:`contact_of`.
CACHED = 64


@functools.lru_cache(maxsize=CACHED)
def _contact(items):
    return _call(api.contact, **library_keywords(dict(items)))


def library_keywords(kw) -> dict:
    """The page's fields (the command line's words: ``bulk_temperatures`` with
    ``sink_distance`` or ``layer_thickness``) as the library's keywords: the bulk
    temperatures as ``closure=BulkTemperatures(...)``."""
    kw = dict(kw)
    given = {k: kw.pop(k) for k in TEMPERATURES if k in kw}
    if given:
        try:
            kw["closure"] = spelled_closure(given, physical=True)[0]
        except InputError as exc:
            raise explain(exc) from None
    return kw


def record_value(record, path):
    """``record`` (a result's ``to_dict()``) at ``path``, a record key as the page's
    ``data-quantity`` writes it (``"flash_temperature"``, ``"peak_temperatures[0]"``,
    ``"branches[0].min_gap_margin"``); None where it has no such entry."""
    value = record
    for part in path.replace("]", "").replace("[", ".").split("."):
        if isinstance(value, list):
            index = int(part)
            value = value[index] if index < len(value) else None
        elif isinstance(value, dict):
            value = value.get(part)
        else:
            return None
        if value is None:
            return None
    return value


def _shown(record, table, prefix="", always=()):
    """The numbers of ``table`` (key, label, unit, factor) as the page shows them: each
    its record key (``prefix`` + key), its ``repr`` (what a test or a screen reader
    reads) and a short text; those absent from ``record`` left out, but for
    ``always`` (shown as absent)."""
    out = []
    for key, label, unit, factor in table:
        value = record_value(record, prefix + key)
        if value is None and key not in always:
            continue
        if value is None or isinstance(value, str):
            text = "—" if value is None else value
        else:
            text = f"{value * factor:.5g}" + (f" {unit}" if unit else "")
        out.append({"key": prefix + key, "label": label, "value": repr(value), "text": text})
    return out


#: The closure by the bulk temperatures: its fields (instead of ``lam``).
TEMPERATURES = ("bulk_temperatures", "sink_distance", "layer_thickness")


def setup() -> dict:
    """What the page needs first: its fields (the contact's, the closure by temperatures
    among them, the other tabs', those always written in its URL) and their defaults,
    and the materials of the library's table (names and aliases)."""
    return {"point": list(POINT), "temperatures": list(TEMPERATURES), "extra": list(EXTRA),
            "always": [*REQUIRED, "lam", *TEMPERATURES], "defaults": DEFAULTS,
            "names": [m.name for m in list_materials()], "aliases": material_aliases()}


def contact_view(state) -> dict:
    """What the contact tab shows for ``state``: numbers, curves, verdicts, code."""
    res = contact_of(state)
    rec = res.to_dict()
    prim = res.primary
    numbers = _shown(rec, CONTACT_NUMBERS, always=("half_width", "flash_temperature"))
    index = res.branches.index(prim) if prim is not None else None
    if index is not None:
        numbers += _shown(rec, BRANCH_NUMBERS, prefix=f"branches[{index}].")
    prob = res.problem
    # Hertz's pressure (the frictionless, isothermal contact) for comparison.
    ell = prob.hertz_half_width
    xh = ell * np.cos(np.linspace(np.pi, 0.0, 121))
    curves = {"hertz_x": xh, "hertz_pressure": prob.load / ell * hertz_pressure(xh / ell)}
    absolute = prob.bulk_temperatures is not None
    if prim is not None:
        base = prob.bulk_temperatures[0] if absolute else 0.0
        curves.update(x=prim.x, pressure=prim.pressure,
                      temperature_cylinder=base + prim.temperature_cylinder,
                      temperature_half_plane=base + prim.temperature_half_plane)
    branch = rec["branches"][index] if index is not None else {}
    verdicts = {
        "valid": {"key": "valid", "value": repr(rec["valid"]),
                  "reason": branch.get("reason", "")},
        "applicable": {"key": "applicable", "value": repr(rec["applicable"]),
                       "reasons": rec["applicability_reasons"]},
        "converged": {"key": "converged", "value": repr(rec["converged"])},
        "branches": len(res.branches),
        "message": rec["message"],
        "under_limits": rec.get("under_limits"),
        "temperatures": "temperature, K" if absolute else "temperature rise, K",
    }
    return {"numbers": numbers, "curves": plain(curves), "verdicts": verdicts,
            "code": code_for(state, "contact"), "inputs": rec["inputs"]}


def contact_record(state) -> str:
    """The point's JSON record (:meth:`PhysicalContact.to_dict`), as downloaded."""
    return json.dumps(plain(contact_of(state).to_dict()), allow_nan=False, indent=1)


def contact_csv(state, folder) -> bytes:
    """The point's distributions as the command line's ``--csv`` writes them, made in
    ``folder`` (the server's temporary folder) and read back."""
    res = contact_of(state)
    path = os.path.join(folder, f"point-{os.getpid()}-{id(res)}.csv")
    try:
        write_contact_csv(res, path)
        with open(path, "rb") as fh:
            return fh.read()
    finally:
        if os.path.exists(path):
            os.remove(path)


# -- copy as code -------------------------------------------------------------------

#: The command line's flag of each keyword (``half_plane`` -> ``--half-plane``).
def _flag(name):
    return "--" + name.replace("_", "-")


def _python_value(name, value):
    return repr(float(value)) if name in ("friction", "lam") else repr(value)


def code_for(state, tab="contact") -> dict:
    """The command and the Python call that reproduce what ``tab`` shows."""
    kw = contact_kwargs(state)
    dundurs = kw.pop("dundurs", True)
    if tab == "transient":
        dundurs = False
    cyl, half = kw.pop("cylinder"), kw.pop("half_plane")
    speed2 = kw.get("speed2")
    if speed2 is not None and parse_quantity(speed2, "m/s", "speed2") == 0.0:
        kw.pop("speed2")
    args = [f"--cylinder {shlex.quote(cyl)}", f"--half-plane {shlex.quote(half)}"]
    # A value that starts with a minus is joined to its flag (--lam=-1).
    args += [f"{_flag(k)}{'=' if str(v).startswith('-') else ' '}{shlex.quote(str(v))}"
             for k, v in kw.items()]
    if not dundurs:
        args.append("--no-dundurs")
    pyargs = [f"{k}={_python_value(k, v)}" for k, v in kw.items() if k not in TEMPERATURES]
    if "bulk_temperatures" in kw:
        t1, t2 = kw["bulk_temperatures"].split(",")
        sinks = "".join(f", {k}={kw[k]!r}" for k in TEMPERATURES[1:] if k in kw)
        pyargs.append(f"closure=tc.BulkTemperatures({t1.strip()!r}, {t2.strip()!r}{sinks})")
    if not dundurs:
        pyargs.append("dundurs=False")
    head = f"{cyl!r}, {half!r}, "
    if tab == "map":
        spec = map_spec_of(state)  # every input of the map checked, each named
        x, y = spec.x, spec.y
        axes = [a.name for a in (x, y)]
        args = [a for a in args if a.split()[0].split("=")[0] not in
                [_flag(n) for n in axes + ["speed2"]]]
        fixed = {k: v for k, v in kw.items() if k not in axes and k != "speed2"}
        command = ("thermocontact map " + " ".join(args)
                   + f" --x {x.spec} --y {y.spec} --out map.nc")
        ratio = _speed_ratio(state)
        if ratio:
            command += f" --speed-ratio {ratio!r}"
        fixed_args = [a for a in pyargs if a.split("=")[0] in fixed or a.startswith("closure=")]
        python = (f"tc.operating_map(tc.Axis.parse({x.spec!r}), tc.Axis.parse({y.spec!r}), "
                  f"cylinder={cyl!r}, half_plane={half!r}, "
                  + ", ".join(a for a in fixed_args if not a.startswith("dundurs="))
                  + (f", speed_ratio={ratio!r}" if ratio else "")
                  + ("" if dundurs else ", dundurs=False") + ")")
    elif tab == "tei":
        wavelength = state.get("wavelength") or DEFAULTS["wavelength"]
        speed = _sliding_speed(state)
        command = (f"thermocontact tei --slider {shlex.quote(cyl)} --counterface "
                   f"{shlex.quote(half)} --friction {kw['friction']!r} --wavelength "
                   f"{shlex.quote(wavelength)} --speed {speed!r}"
                   + ("" if dundurs else " --no-dundurs"))
        python = (f"tc.tei({head}{kw['friction']!r}, {wavelength!r}, speed={speed!r}"
                  + ("" if dundurs else ", dundurs=False") + ")")
    elif tab == "transient":
        extra = transient_kwargs(state)
        command = ("thermocontact contact " + " ".join(args) + " --transient"
                   + f" --duration {shlex.quote(extra['duration'])} --steps {extra['steps']}"
                   + f" --elements {extra['elements']} --out transient.nc")
        python = (f"tc.contact_transient({head}" + ", ".join(pyargs)
                  + ", " + ", ".join(f"{k}={v!r}" for k, v in extra.items()) + ")")
    else:
        command = "thermocontact contact " + " ".join(args)
        python = f"tc.contact({head}" + ", ".join(pyargs) + ")"
    return {"command": command, "python": "import thermocontact as tc\n" + python}


# -- the map, the TEI and the transient -----------------------------------------------

def _speed_ratio(state) -> float:
    """v2/v1 of the point, the map's constant speed ratio."""
    prob = contact_of(state).problem
    return prob.speed2 / prob.speed if prob.speed2 else 0.0


def _sliding_speed(state) -> float:
    return contact_of(state).problem.sliding_speed


def map_spec_of(state):
    """The :func:`thermocontact.map_spec` of the map over ``x`` and ``y`` around the
    point of ``state`` (its other inputs kept)."""
    kw = contact_kwargs(state)
    try:
        axes = [Axis.parse(state.get(k) or DEFAULTS[k], k) for k in ("x", "y")]
    except InputError as exc:
        raise explain(exc) from None
    for name, axis in zip(("x", "y"), axes):
        if axis.name not in ("load", "speed", "radius"):
            raise UserError(f"{name} must be an axis over load, speed or radius, got "
                            f"{axis.name!r}", {name: f"{name} must be over load, speed or "
                                                     f"radius, got {axis.name!r}"})
    if axes[0].name == axes[1].name:
        raise UserError("x and y must be over different parameters",
                        {"y": "y must be over another parameter than x"})
    ratio = _speed_ratio(state)
    kw.pop("speed2", None)
    for axis in axes:
        kw.pop(axis.name)
    return _call(api.map_spec, axes[0], axes[1], speed_ratio=ratio, **library_keywords(kw))


def map_view(ds) -> dict:
    """The map's dataset as the page draws it: axes, each point's verdict, the
    existence boundary's curves."""
    x, y = ds.attrs["x"].split(":")[0], ds.attrs["y"].split(":")[0]
    valid = np.asarray(ds["valid"].values, dtype=int)
    applicable = np.asarray(ds["applicable"].values, dtype=int)
    branches = np.asarray(ds["branches"].values, dtype=int)
    # 0 no branch, 1 invalid, 2 valid but the theory does not apply, 3 valid.
    verdict = np.where(branches == 0, 0, np.where(valid == 0, 1, 2 + applicable))
    # A map at fixed bulk temperatures (each point its own contact) draws no curves.
    curves = {k: ds[k].values if k in ds else [] for k in ("boundary_x", "boundary_y")}
    return plain({
        "x": {"name": x, "values": ds[x].values}, "y": {"name": y, "values": ds[y].values},
        "verdict": verdict, **curves, "reasons": np.asarray(ds["reason"].values).tolist(),
    })


def tei_view(state) -> dict:
    """The TEI tab: :func:`thermocontact.tei` of the cylinder sliding over the
    half-plane at the point's sliding speed, at the wavelength chosen, and the
    critical speed at wavelengths either side (each its own call)."""
    kw = contact_kwargs(state)
    text = _given(state, "wavelength") or DEFAULTS["wavelength"]
    try:
        wavelength = parse_quantity(text, "m", "wavelength")
    except InputError as exc:
        raise UserError(str(exc), {"wavelength": str(exc)}) from None
    speed = _sliding_speed(state)
    args = (kw["cylinder"], kw["half_plane"], kw["friction"])
    res = _call(api.tei, *args, text, speed=speed, dundurs=kw["dundurs"])
    rec = res.to_dict()
    grid = wavelength * np.logspace(-TEI_DECADES, TEI_DECADES, TEI_POINTS)
    grid = grid[(grid >= 1e-9) & (grid <= 1e3)]
    curve = [_call(api.tei, *args, float(w), dundurs=kw["dundurs"]).critical_speed
             for w in grid]
    return {"numbers": _shown(rec, TEI_NUMBERS, always=[k for k, *_ in TEI_NUMBERS]),
            "curves": plain({"wavelength": grid, "critical_speed": curve,
                             "point": [wavelength, speed]}),
            "verdicts": {"stable_at_all_speeds": rec["stable_at_all_speeds"],
                         "unstable": (rec["critical_speed"] is not None
                                      and speed > rec["critical_speed"])},
            "code": code_for(state, "tei")}


def transient_kwargs(state) -> dict:
    """The run's ``duration``, ``steps`` and ``elements`` (:func:`contact_transient`);
    an empty duration is :data:`TRANSIENT_UNITS` times ``l^2/kappa2``."""
    errors, kw = {}, {}
    for name in ("steps", "elements"):
        try:
            kw[name] = _number({name: _given(state, name) or DEFAULTS[name]}, name, int)
        except InputError as exc:
            errors[name] = str(exc)
    duration = _given(state, "duration")
    if duration is None:
        prob = contact_of(state).problem
        # The unit of time of contact_transient_spec, l^2/kappa2.
        duration = f"{TRANSIENT_UNITS * prob.hertz_half_width ** 2 / prob.half_plane.k:.4g}s"
    else:
        try:
            parse_quantity(duration, "s", "duration")
        except InputError as exc:
            errors["duration"] = str(exc)
    if errors:
        raise UserError("; ".join(errors.values()), errors)
    kw["duration"] = duration
    return kw


def transient_call(state) -> dict:
    """The keyword arguments of :func:`thermocontact.contact_transient_spec` for
    ``state``: the point's, without the Dundurs term (the transient run has none) and
    the sink (its half-plane is infinite), and the run's."""
    kw = contact_kwargs(state)
    kw.pop("sink_distance", None)
    kw.pop("layer_thickness", None)
    kw.setdefault("lam", None)
    kw["dundurs"] = False
    return {**kw, **transient_kwargs(state)}


def job_key(kind, state) -> str:
    """What identifies the result of a background job, every input checked first (so
    that an error is shown at once, before a process starts): a map's manifest, a
    transient run's inputs."""
    if kind == "map":
        return json.dumps(map_spec_of(state).manifest(), sort_keys=True, default=str)
    if kind == "transient":
        kw = transient_call(state)
        _call(api.contact_transient_spec, **library_keywords(kw))
        return json.dumps(kw, sort_keys=True, default=str)
    raise UserError(f"no background job {kind!r}: map or transient")


def transient_view(ds) -> dict:
    """The run as the page plays it: SI time, position and pressure, the surfaces'
    temperatures, at most :data:`FRAMES` frames."""
    a = ds.attrs
    step = max(1, math.ceil(ds.sizes["time"] / FRAMES))
    frames = ds.isel(time=slice(None, None, step))
    time = frames["time"].values * a["time_unit_s"]
    # Temperatures of the run are in units of f v P/(pi K2) (temperature_unit_K).
    return plain({
        "time": time, "time_repr": [repr(float(t)) for t in time],
        "x": ds["x"].values * a["length_unit_m"],
        "pressure": frames["pressure"].values * a["pressure_unit_Pa"],
        "temperature_cylinder": frames["temperature1"].values * a["temperature_unit_K"],
        "temperature_half_plane": frames["temperature2"].values * a["temperature_unit_K"],
        "status": a["status"],
    })


def job_context():
    """The ``multiprocessing`` context of the explorer's jobs: processes forked by a
    clean server process that has imported the library and this module once (never
    forked from the server, whose threads may hold locks), ``spawn`` where there is no
    fork server (:func:`~thermocontact.execution.executors.process_context`)."""
    from ..execution.executors import process_context

    return process_context(fork=False, preload=[__name__])


def run_job(kind, state, folder, progress):
    """A background job, in its own process: the map (``kind="map"``) or the transient
    run (``"transient"``) of ``state``; writes ``<kind>.nc`` and ``view.json`` in
    ``folder``, or ``error.json`` with the page's words.  ``progress`` is a shared array
    ``[done, total]``."""
    import signal

    from ..execution.executors import one_blas_thread

    # Ctrl-C in the server's terminal reaches every process of its group: the server
    # ends the jobs itself, so a job does not answer it with a traceback of its own.
    signal.signal(signal.SIGINT, signal.SIG_IGN)

    def tell(done, total):
        progress[0], progress[1] = float(done), float(total)

    try:
        with one_blas_thread():
            if kind == "map":
                spec = map_spec_of(state)
                ds = _call(api.compute_map, spec, progress=tell,
                           command=code_for(state, "map")["command"])
                view = map_view(ds)
            else:
                kw = transient_call(state)
                kw.pop("bulk_temperatures", None)  # refused by job_key
                ds = _call(api.contact_transient, **kw, progress=tell)
                view = transient_view(ds)
        write_dataset(ds, os.path.join(folder, f"{kind}.nc"))
        name, content = "view.json", view
    except Exception as exc:  # the page's words, never a traceback
        name, content = "error.json", explain(exc).to_dict()
    tmp = os.path.join(folder, name + ".part")
    with open(tmp, "w") as fh:
        json.dump(content, fh, allow_nan=False)
    os.replace(tmp, os.path.join(folder, name))
