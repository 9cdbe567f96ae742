"""Operating maps in physical units: where, in load, speed and radius, a single patch exists.

For one pair of materials, one friction coefficient and one heat partition, the
dimensionless inputs at a trial half-width ``Delta`` are ``Pe = v Delta/(2 k2)``,
``fHPe = f H Pe`` and the fixed ratios (:class:`~.physical_contact.PhysicalProblem`):
every solution lies on one *ray* ``Pe -> (Pe, f H Pe)``.  The half-widths that carry
a load ``P`` are the roots of ``P_H(Delta) = P (P_H/P)(Pe)``; with
``P_H(Delta) = pi Delta^2/(2 A R)`` and the Hertz half-width
``Delta_H^2 = 2 A R P/pi`` this is ``(Delta/Delta_H)^2 = L(Pe)``, i.e.

    Pe^2 = Pe_H^2 L(Pe),    Pe_H = v Delta_H / (2 k2).

So load, radius and speed enter only through ``Pe_H`` (derivation section 11b, D26):
one continuation along the ray answers every point of a load-speed(-radius) plane.
The ray is sampled geometrically (:data:`RAY_PER_DECADE`), the samples run as chunks
on any executor, validity changes along it are located by Brent's method on the
margins; each grid point's roots are found on a local interpolant of the samples in
``ln Pe`` (degree 5) and its fields read off the same interpolant.
"""

from __future__ import annotations

import json
import math
import os
import warnings
from dataclasses import dataclass

import numpy as np

from .._version import __version__
from ..analysis.applicability import assess
from ..analysis.fields import contact_fields, slopes_and_strains
from ..problem.materials import Material
from ..problem.parameters import ConvergenceWarning, SolveError
from ..problem.physical import PhysicalProblem, hertz_half_width, scan_range
from ..problem.validation import InputError, check_finite, check_nonnegative, check_positive
from .boundaries import estimate_events, locate_events
from .contact_sets import PhysicalConductance, physical_contact_set
from ..execution.resumable import run_chunks
from ..problem.axes import PHYSICAL_UNITS
from .maps import Axis, check_axis_name, parse_axis, prepare_dataset
from .physical_contact import problem_ray
from .ray import Ray
from .ray import interpolated_roots as _interpolated_roots
from .ray import local as _local

__all__ = ["CONTACT_SET_SECONDS", "OperatingSpec", "RAY_PER_DECADE", "compute_operating_map",
           "ray_samples"]

#: Physical axes of an operating map, and their SI units.
AXES = PHYSICAL_UNITS
#: Samples of the ray per decade of Pe, and of one chunk.
RAY_PER_DECADE = 24
RAY_CHUNK = 16


def parse_physical_axis(option, spec) -> Axis:
    """An axis over ``load``, ``speed`` or ``radius`` in SI units."""
    return parse_axis(option, spec, names={k: k for k in AXES})


@dataclass(frozen=True)
class OperatingSpec:
    """An operating map: materials, friction, heat partition, two physical axes.

    Attributes
    ----------
    cylinder, half_plane : Material
    friction, lam : float
    x, y : Axis
        Over ``load`` (N/m), ``speed`` (m/s) or ``radius`` (m), positive.
    fixed : dict
        The third of load, speed, radius (SI).
    tol : float
        Error target of every ray sample.
    dundurs : bool
        Keep the Dundurs term of the two materials (default), as ``contact`` does.
    speed_ratio : float
        ``R = v2/v1``: the half-plane's surface moves at ``R`` times the cylinder's
        (section 5b); the speed axis is the cylinder's surface speed, and the heat is
        made at ``|1 - R|`` times it.  One ray still covers the plane.
    zones : bool
        Also find the contact set, of one zone or several, at every point (section
        14c; a stationary half-plane): past the single patch's boundary it says what
        exists instead.
    conductance : PhysicalConductance, optional
        With ``zones``: an interface conductance (section 15), one law for the whole
        map (so with a reference pressure unless constant).
    bulk_temperatures, sink_distance, layer_thickness : optional
        Instead of ``lam`` (None): the bodies' far temperatures, K, and a stationary
        half-plane's sink, m (:class:`PhysicalProblem`; section 17).  ``lam`` then
        varies over the plane, and each point is its own contact
        (:mod:`.temperature_maps`).
    """

    cylinder: Material
    half_plane: Material
    friction: float
    lam: float
    x: Axis
    y: Axis
    fixed: dict
    tol: float = 1e-6
    dundurs: bool = True
    speed_ratio: float = 0.0
    zones: bool = False
    conductance: PhysicalConductance | None = None
    bulk_temperatures: tuple | None = None
    sink_distance: float | None = None
    layer_thickness: float | None = None

    def __post_init__(self):
        for key in ("x", "y"):
            axis = getattr(self, key)
            if not isinstance(axis, Axis):
                raise InputError(f"{key} must be an Axis, got {axis!r}")
            check_axis_name(key, axis.name, {k: k for k in AXES})
        check_nonnegative("friction", self.friction)
        if self.conductance is not None:
            if not self.zones:
                raise InputError("conductance needs zones (the single patch assumes "
                                 "perfect thermal contact)", parameters=("conductance", "zones"))
            if self.conductance.exponent and self.conductance.p_ref is None:
                raise InputError("conductance must be h0:m:p_ref in an operating map "
                                 "(one law h = h0 (p/p_ref)^m for every load), got no p_ref",
                                 parameters=("conductance",))
        if self.bulk_temperatures is None:
            check_finite("lam", self.lam)
        check_positive("tol", self.tol)
        object.__setattr__(self, "speed_ratio", check_finite("speed_ratio", self.speed_ratio))
        if self.zones and self.speed_ratio:
            raise InputError(f"zones needs a stationary half-plane (speed_ratio 0), got "
                             f"{self.speed_ratio:g}", parameters=("zones", "speed_ratio"))
        if self.x.name == self.y.name:
            raise InputError(f"y must name a parameter other than x's, got "
                             f"{self.y.name!r} twice", parameters=("y", "x"))
        for axis in (self.x, self.y):
            if not axis.start > 0.0:
                raise InputError(f"{'x' if axis is self.x else 'y'} {axis.name} must be "
                                 f"> 0, got {axis.start!r}", parameters=("x" if axis is self.x else "y",))
        third = [k for k in AXES if k not in (self.x.name, self.y.name)][0]
        if self.fixed.get(third) is None:
            raise InputError(f"{third} must be given (it is not an axis)", parameters=(third,))
        object.__setattr__(self, "fixed", {third: check_positive(third, self.fixed[third])})
        # Every corner must be a problem the solver accepts.
        for xv in (self.x.start, self.x.stop):
            for yv in (self.y.start, self.y.stop):
                corner = self.problem(**{self.x.name: xv, self.y.name: yv})
                # The Biot number is monotone in load and radius: corners bound it.
                if self.conductance is not None:
                    self.conductance.biot(corner)

    def problem(self, **values) -> PhysicalProblem:
        kw = {**self.fixed, **values}
        return PhysicalProblem(self.cylinder, self.half_plane, kw["radius"], kw["load"],
                               kw["speed"], self.friction, self.lam,
                               speed2=kw["speed"] * self.speed_ratio, dundurs=self.dundurs,
                               bulk_temperatures=self.bulk_temperatures,
                               sink_distance=self.sink_distance,
                               layer_thickness=self.layer_thickness)

    def grid(self):
        """``(load, speed, radius)`` arrays of shape ``(y.count, x.count)``."""
        yy, xx = np.meshgrid(self.y.values, self.x.values, indexing="ij")
        kw = {self.x.name: xx, self.y.name: yy, **{k: np.full(xx.shape, v)
                                                   for k, v in self.fixed.items()}}
        return kw["load"], kw["speed"], kw["radius"]

    def reference(self) -> PhysicalProblem:
        """The problem at the map's first corner: what every point shares (materials,
        friction, heat partition, speed ratio) is read from it."""
        return self.problem(**{self.x.name: self.x.start, self.y.name: self.y.start})

    @property
    def compliance(self) -> float:
        """``A`` of the materials, 1/Pa (:class:`PhysicalProblem`)."""
        return self.reference().compliance

    def pe_hertz(self, load, speed, radius):
        """``Pe_H = v Delta_H/(2 k2)`` elementwise (:class:`PhysicalProblem`'s, on arrays)."""
        return speed * hertz_half_width(self.compliance, radius, load) / (
            2.0 * self.half_plane.k)

    def ray(self) -> Ray:
        """The dimensionless problems of the whole plane: those of any of its points
        (the ray does not depend on load, speed or radius)."""
        return problem_ray(self.reference())

    @property
    def fh(self) -> float:
        """The ray's slope ``fHPe/Pe``: ``f H |1 - R|``."""
        return self.ray().fh

    def fractions(self) -> tuple:
        """Each body's compliance over their sum ``A``."""
        return self.reference().compliance_fractions

    def contact_set_cost(self, workers: int = 1) -> float:
        """Estimated seconds of the map's contact sets (:func:`contact_set_fields`) on
        ``workers`` cores: one task per line of constant y, each ``x.count`` sets of
        :data:`CONTACT_SET_SECONDS`; 0 without ``zones``."""
        if not self.zones:
            return 0.0
        lines = self.y.count
        rounds = math.ceil(lines / max(1, min(int(workers), lines)))
        return rounds * self.x.count * CONTACT_SET_SECONDS

    def manifest(self) -> dict:
        return {"kind": "thermocontact operating map", "version": __version__,
                "cylinder": self.cylinder.name, "half_plane": self.half_plane.name,
                "friction": self.friction, "lam": self.lam, "x": self.x.spec,
                "y": self.y.spec, "fixed": self.fixed, "tol": self.tol,
                "dundurs": self.dundurs, "speed_ratio": self.speed_ratio,
                # The values, not only the names: a materials file may redefine a name.
                "materials": [_material_values(self.cylinder),
                              _material_values(self.half_plane)],
                "fields": "slopes, strains and temperatures",
                **({} if self.bulk_temperatures is None else {
                    "bulk_temperatures": list(self.bulk_temperatures),
                    "sink_distance": self.sink_distance,
                    "layer_thickness": self.layer_thickness}),
                **({"zones": True, "conductance": None if self.conductance is None else
                    [self.conductance.h0, self.conductance.exponent, self.conductance.p_ref]}
                   if self.zones else {})}


def _material_values(m: Material) -> dict:
    """The numbers of a material that enter a map."""
    return {"E": m.E, "nu": m.nu, "alpha": m.alpha, "K": m.K, "k": m.k,
            "max_temperature": m.max_temperature}


def evaluate_ray(task) -> dict:
    """Solve the ray at the chunk's Péclet numbers: ``P_H/P``, offset, margins, shapes."""
    out = {k: [] for k in ("pe", "load_ratio", "sigma_over_delta", "valid", "peak", "flash",
                           "slope_cylinder", "slope_half_plane", "strain", "temperature_low",
                           "temperature_high", "error_estimate", "n", "status", "reason")}
    for pe in task["pe"]:
        try:
            with warnings.catch_warnings():
                warnings.simplefilter("ignore", ConvergenceWarning)
                ray = task["ray"]
                sol = ray.model(pe, tol=task["tol"]).solve(ray.fh * pe, lam=ray.lam,
                                                           polish=False)
            # The single patch's fields in units of its half-width: pressures of P/Delta,
            # temperatures of f |v1 - v2| P/(pi K1) (D24).
            f = contact_fields(sol, fractions=task["fractions"])
            rec = (sol.load_ratio, sol.sigma_over_delta, int(sol.valid), f.peak_pressure,
                   f.flash_temperature, *f.slope_factors, f.strain_pressure,
                   *f.temperature_range,
                   sol.error_estimate if sol.error_estimate is not None else math.nan, sol.n,
                   sol.status, sol.validity.reason)
        except (SolveError, InputError) as exc:
            nan = math.nan
            rec = (nan, nan, 0, nan, nan, nan, nan, nan, nan, nan, nan, 0, "failed", str(exc))
        for k, v in zip(list(out)[1:], rec):
            out[k].append(v)
        out["pe"].append(pe)
    return out


def ray_samples(spec: OperatingSpec, pe_lo, pe_hi, workers=1, progress=None,
                store_path=None) -> dict:
    """The ray sampled from ``pe_lo`` to ``pe_hi``, and its validity changes (chunks
    kept in ``store_path`` as they finish)."""
    count = max(8, int(math.ceil(RAY_PER_DECADE * math.log10(pe_hi / pe_lo))) + 1)
    pes = np.geomspace(pe_lo, pe_hi, count)
    base = {"ray": spec.ray(), "tol": spec.tol, "fractions": spec.fractions()}
    tasks = [{**base, "pe": [float(p) for p in pes[i:i + RAY_CHUNK]]}
             for i in range(0, count, RAY_CHUNK)]
    manifest = {**spec.manifest(), "pe": [pe_lo, pe_hi, count], "chunk": RAY_CHUNK}
    parts = run_chunks(evaluate_ray, tasks, manifest, store_path, workers=workers,
                       progress=progress)
    ray = {k: np.concatenate([np.asarray(parts[i][k]) for i in range(len(tasks))])
           for k in parts[0]}
    ray["valid"] = ray["valid"].astype(bool)
    # Validity changes along the ray, located on the margins (one n per interval),
    # each with its estimate against n/2 and located again with more unknowns where
    # that exceeds EVENT_RTOL (as a path's events).
    events = []

    def at_n(m, pe):
        return base["ray"].solve_at(pe, m, check_validity=True, polish=False)
    xtol = lambda p, q: 1e-10 * max(abs(p), abs(q))  # noqa: E731
    for i in np.flatnonzero(ray["valid"][:-1] != ray["valid"][1:]):
        if "failed" in (ray["status"][i], ray["status"][i + 1]):
            continue
        n = int(max(ray["n"][i], ray["n"][i + 1]))
        a, b = float(ray["pe"][i]), float(ray["pe"][i + 1])
        try:
            ends = [at_n(n, a), at_n(n, b)]
        except SolveError:
            continue
        found = locate_events(lambda pe, n=n: at_n(n, pe), [a, b], ends,
                              only_validity_changes=True, xtol=xtol)
        events += estimate_events(at_n, found, n, pe_lo, pe_hi, xtol)[0]
    ray["events"] = tuple(events)
    return ray


#: Fields of a map's contact sets (``zones_*``), by point.
ZONE_FIELDS = ("status", "count", "valid", "applicable", "start", "end", "load",
               "peak_pressure", "message", "flash_temperature", "applicability_reasons")


def evaluate_contact_sets(task) -> dict:
    """The contact set at each of the task's points (:func:`physical_contact_set`):
    its status, number of zones, validity, whether the theory applies, the first
    zone's trailing and the last zone's leading edge (m), the load carried (N/m, the
    sum over zones: the imposed load where solved), the peak pressure (Pa), the
    message, the flash temperature (K) and why the theory does not apply (the
    reasons joined by "; ", as the single patch's ``applicability_reasons``).

    Where the single patch is valid (the task's ``starts``, its edges in m, else None)
    the contact set is first sought by Newton's method from its edges, and followed
    from Hertz's zone only if that finds no valid one zone (:func:`physical_contact_set`).
    """
    spec = task["spec"]
    out = {k: [] for k in ZONE_FIELDS}
    starts = task.get("starts") or [None] * len(task["points"])
    for (load, speed, radius), start in zip(task["points"], starts):
        nan = math.nan
        try:
            found = physical_contact_set(spec.problem(load=load, speed=speed, radius=radius),
                                         conductance=spec.conductance, start=start)
            z = found.zones
            row = (found.status, len(z), int(bool(found.valid)), int(found.applicable),
                   z[0]["a"] if z else nan, z[-1]["b"] if z else nan,
                   sum(q["load"] for q in z) if z else nan,
                   max(q["peak_pressure"] for q in z) if z else nan, found.message,
                   found.fields.flash_temperature if found.fields is not None else nan,
                   "; ".join(found.applicability.reasons)
                   if found.applicability is not None else "")
        except (SolveError, InputError) as exc:
            row = ("failed", 0, 0, 0, nan, nan, nan, nan, str(exc), nan, "")
        for k, v in zip(ZONE_FIELDS, row):
            out[k].append(v)
    return out


#: Seconds one contact set takes on one core, measured (steel on copper, R = 10 mm,
#: 2-5 m/s, 100-200 kN/m, with and without a conductance: 4-5 s): the scale of
#: :func:`contact_set_cost`, not a bound.  Where the single patch is valid the set is
#: sought from its edges first (:func:`evaluate_contact_sets`), which costs less.
CONTACT_SET_SECONDS = 5.0


def contact_set_fields(spec: OperatingSpec, workers=1, progress=None, store_path=None,
                       starts=None):
    """``zones_*`` fields over the map (:func:`evaluate_contact_sets`), one task per
    line of constant y, kept in ``store_path`` as they finish; ``starts[i][j]``, the
    edges (m) of a valid single patch at point ``(i, j)`` or None, are tried first.

    Returns
    -------
    dict
        The dataset's variables, ``{"zones_<field>": ((y, x), array)}``.
    """
    per_line = None
    if starts is not None:
        per_line = [{"starts": [None if e is None else tuple(float(v) for v in e)
                                for e in row]} for row in starts]
    found = line_fields(spec, evaluate_contact_sets, "contact sets", ZONE_FIELDS, workers,
                        progress, store_path, per_line=per_line,
                        manifest={"start": "valid single patch" if starts is not None
                                  else None})
    dims = (spec.y.name, spec.x.name)
    return {f"zones_{k}": (dims, v.astype(str) if v.dtype.kind in "UO" else v)
            for k, v in found.items()}


def two_parts(progress, lines):
    """One progress for a map's two parts, its first part's chunks (their count told by
    its own progress; none when resumed), then ``lines`` lines of contact sets: the
    two ``progress(done, total)`` callables."""
    first_total = [0]

    def first(done, total):
        first_total[0] = total
        if progress is not None:
            progress(done, total + lines)

    def second(done, total):
        if progress is not None:
            progress(first_total[0] + done, first_total[0] + total)
    return first, second


def line_fields(spec: OperatingSpec, func, part, names, workers=1, progress=None,
                store_path=None, per_line=None, manifest=None):
    """``func`` over the map's points, one task (``{"spec", "points"}``, updated by
    ``per_line[i]`` where given) per line of constant y, kept in ``store_path`` as
    they finish: ``{name: array (y, x)}``; ``manifest`` adds to the store's
    manifest."""
    load, speed, radius = spec.grid()
    tasks = [{"spec": spec, "points": [(float(load[i, j]), float(speed[i, j]),
                                        float(radius[i, j])) for j in range(load.shape[1])]}
             for i in range(load.shape[0])]
    for task, extra in zip(tasks, per_line or ()):
        task.update(extra)
    manifest = {**spec.manifest(), "part": part, **(manifest or {})}
    parts = run_chunks(func, tasks, manifest, store_path, workers=workers, progress=progress,
                       meanwhile=prepare_dataset)
    return {k: np.array([parts[i][k] for i in range(len(tasks))]) for k in names}


CURVE_POINTS = 201


def _pe_hertz_error(lp, load_ratio, event):
    """The change of ``Pe_H = Pe/sqrt(L)`` over the event's error estimate in ``Pe``
    (the larger of the two sides; L from the ray's interpolant), or NaN."""
    if event.error_estimate is None:
        return math.nan

    def pe_h(pe):
        L = _local(lp, load_ratio, math.log(pe))
        return pe / math.sqrt(L) if L > 0 else math.nan
    err = event.error_estimate
    here = pe_h(event.at)
    return max(abs(pe_h(event.at + err) - here), abs(pe_h(max(event.at - err, 1e-300)) - here))


def boundary_curve(spec: OperatingSpec, pe_h):
    """The curve ``Pe_H = pe_h`` across the map: ``CURVE_POINTS`` values of x and the y
    on the curve (NaN outside the y range).  ``v sqrt(R P) = Pe_H 2 k2 / sqrt(2A/pi)``
    is solved for y exactly."""
    x = (np.geomspace if spec.x.log else np.linspace)(spec.x.start, spec.x.stop, CURVE_POINTS)
    K = pe_h * 2.0 * spec.half_plane.k / math.sqrt(2.0 * spec.compliance / math.pi)
    kw = {spec.x.name: x, **spec.fixed}
    if spec.y.name == "speed":
        y = K / np.sqrt(kw["radius"] * kw["load"])
    elif spec.y.name == "load":
        y = (K / kw["speed"]) ** 2 / kw["radius"]
    else:
        y = (K / kw["speed"]) ** 2 / kw["load"]
    y = np.where((y >= spec.y.start) & (y <= spec.y.stop), y, np.nan)
    return x, y


def compute_operating_map(spec: OperatingSpec, workers=1, progress=None, command=None,
                          store_path=None):
    """The operating map as an :class:`xarray.Dataset` (SI units).

    Returns
    -------
    xarray.Dataset
        Over the two axes: ``half_width``, ``offset``, ``peak_pressure``,
        ``mean_pressure``, ``flash_temperature``, ``load_ratio``, ``pe``, ``fhpe``,
        ``max_slope_*`` and ``max_strain_*`` of the cylinder and the half-plane (as
        ``contact`` measures them), ``valid``, ``applicable`` (size, slopes, strains,
        temperatures: :func:`~thermocontact.analysis.applicability.assess`, as
        ``contact``), ``applicability_reasons`` (joined by "; "), ``branches``,
        ``status``, ``reason``; the boundary
        as values of ``Pe_H`` and as curves in the plane; with ``spec.zones`` the
        contact sets' ``zones_*`` (:func:`evaluate_contact_sets`).
    """
    import xarray as xr

    if spec.bulk_temperatures is not None:
        from .temperature_maps import temperature_map

        return temperature_map(spec, workers, progress, command, store_path)
    load, speed, radius = spec.grid()
    pe_h = spec.pe_hertz(load, speed, radius)
    # The single patch's range (PhysicalProblem.scan_range), in Pe over the whole plane.
    pe_lo, pe_hi = scan_range(pe_h.min(), pe_h.max(), spec.fh)
    ray_progress, zone_progress = two_parts(progress, spec.y.count if spec.zones else 0)
    ray = ray_samples(spec, pe_lo, pe_hi, workers=workers, progress=ray_progress,
                      store_path=store_path)
    lp = np.log(ray["pe"])

    def valid_at(pe):
        # Near an event (within a sample interval on either side; a relocated event
        # may have left the interval it was found in) the event decides; elsewhere
        # the samples either side.
        i = int(np.clip(np.searchsorted(ray["pe"], pe), 1, len(lp) - 1))
        a = ray["pe"][max(i - 2, 0)]
        b = ray["pe"][min(i + 1, len(lp) - 1)]
        near = [e for e in ray["events"] if a <= e.at <= b]
        if near:
            e = min(near, key=lambda e: abs(e.at - pe))
            return bool(e.valid_before) if pe < e.at else bool(e.valid_after)
        return bool(ray["valid"][i - 1]) and bool(ray["valid"][i])

    shape = pe_h.shape
    fields = {k: np.full(shape, np.nan) for k in (
        "half_width", "offset", "peak_pressure", "mean_pressure", "flash_temperature",
        "load_ratio", "pe", "fhpe", "max_slope_cylinder", "max_slope_half_plane",
        "max_strain_cylinder", "max_strain_half_plane")}
    valid = np.zeros(shape, dtype=np.int8)
    applicable = np.zeros(shape, dtype=np.int8)
    branches = np.zeros(shape, dtype=np.int32)
    status = np.full(shape, "solved", dtype=object)
    reason = np.full(shape, "", dtype=object)
    reasons_of = np.full(shape, "", dtype=object)
    # The edges (m) of the single patch where it is valid on the one branch there: the
    # contact sets start from them.
    starts = np.full(shape, None, dtype=object)
    k2, K1 = spec.half_plane.k, spec.cylinder.K
    fractions = spec.fractions()
    limits = (spec.cylinder.max_temperature, spec.half_plane.max_temperature)
    for idx in np.ndindex(shape):
        roots = _interpolated_roots(ray["pe"], ray["load_ratio"], pe_h[idx])
        branches[idx] = len(roots)
        if not roots:
            status[idx] = "no branch"
            reason[idx] = "no half-width carries this load on the searched range"
            continue
        flags = [valid_at(math.exp(r)) for r in roots]
        r = roots[flags.index(True)] if any(flags) else roots[0]
        pe = math.exp(r)
        P, v, R = load[idx], speed[idx], radius[idx]
        d = pe * 2.0 * k2 / v
        Lr = _local(lp, ray["load_ratio"], r)
        fields["half_width"][idx] = d
        # L sigma, not sigma, is smooth along the ray: sigma has a pole where L = 0.
        fields["offset"][idx] = _local(lp, ray["load_ratio"] * ray["sigma_over_delta"],
                                       r) / Lr * d
        fields["peak_pressure"][idx] = P / d * _local(lp, ray["peak"], r)
        fields["mean_pressure"][idx] = P / (2.0 * d)
        # Heat at the sliding speed |1 - R| v (section 5b); temperatures in units of
        # f |1 - R| v P/(pi K1) along the ray.
        unit = spec.friction * v * abs(1.0 - spec.speed_ratio) * P / (np.pi * K1)
        flash = unit * _local(lp, ray["flash"], r)
        fields["flash_temperature"][idx] = flash
        fields["load_ratio"][idx] = Lr
        fields["pe"][idx] = pe
        fields["fhpe"][idx] = spec.fh * pe
        valid[idx] = int(valid_at(pe))
        if valid[idx] and len(roots) == 1:
            starts[idx] = (fields["offset"][idx] - d, fields["offset"][idx] + d)
        # Slopes and strains as contact measures them (thermocontact.analysis.fields),
        # from the ray's per-sample factors.
        sigma = fields["offset"][idx] / d
        slope, strain = slopes_and_strains(
            d / R, abs(sigma) + 1.0, Lr,
            (_local(lp, ray["slope_cylinder"], r), _local(lp, ray["slope_half_plane"], r)),
            _local(lp, ray["strain"], r), fractions)
        for i, body in enumerate(("cylinder", "half_plane")):
            fields[f"max_slope_{body}"][idx] = slope[i]
            fields[f"max_strain_{body}"][idx] = strain[i]
        app = assess(d / R, slope, strain,
                     temperature_rises=(unit * _local(lp, ray["temperature_low"], r),
                                        unit * _local(lp, ray["temperature_high"], r)),
                     max_temperature=limits)
        reasons = app.reasons
        reasons_of[idx] = "; ".join(reasons)
        applicable[idx] = int(not reasons)
        reason[idx] = ("valid" if valid[idx] else "invalid single patch") + (
            "; not applicable: " + "; ".join(reasons) if reasons else "")
    # The existence boundary: Pe_H at the ray's validity changes (each a curve
    # Pe_H = const in the plane).
    bounds = np.array([e.at / math.sqrt(_local(lp, ray["load_ratio"], math.log(e.at)))
                       if _local(lp, ray["load_ratio"], math.log(e.at)) > 0 else np.nan
                       for e in ray["events"]])
    curves = [boundary_curve(spec, b) if np.isfinite(b) else
              (np.full(CURVE_POINTS, np.nan), np.full(CURVE_POINTS, np.nan)) for b in bounds]
    bx = np.array([c[0] for c in curves]).reshape(len(curves), CURVE_POINTS)
    by = np.array([c[1] for c in curves]).reshape(len(curves), CURVE_POINTS)
    dims = (spec.y.name, spec.x.name)
    zones = {}
    if spec.zones:
        zones = contact_set_fields(spec, workers=workers, progress=zone_progress,
                                   store_path=None if store_path is None else
                                   os.path.join(store_path, "contact_sets"),
                                   starts=starts.tolist())
    ds = xr.Dataset(
        {**{k: (dims, v) for k, v in fields.items()},
         "valid": (dims, valid), "applicable": (dims, applicable),
         "branches": (dims, branches), "status": (dims, status.astype(str)),
         "reason": (dims, reason.astype(str)),
         "applicability_reasons": (dims, reasons_of.astype(str)), "pe_hertz": (dims, pe_h),
         "boundary_pe_hertz": ("event", bounds),
         "boundary_pe_hertz_error": ("event", np.array([
             _pe_hertz_error(lp, ray["load_ratio"], e) for e in ray["events"]],
             dtype=float)),
         "boundary_inequality": ("event", np.array([e.inequality for e in ray["events"]],
                                                   dtype=str)),
         "boundary_x": (("event", "curve"), bx), "boundary_y": (("event", "curve"), by),
         "ray_pe": ("ray", ray["pe"]), "ray_load_ratio": ("ray", ray["load_ratio"]),
         "ray_valid": ("ray", ray["valid"].astype(np.int8)), **zones},
        coords={spec.y.name: spec.y.values, spec.x.name: spec.x.values})
    ds.attrs.update({"title": "thermocontact operating map", "thermocontact_version": __version__,
                     "cylinder": spec.cylinder.name, "half_plane": spec.half_plane.name,
                     "friction": spec.friction, "lam": spec.lam, "x": spec.x.spec,
                     "y": spec.y.spec, "tol": spec.tol, "units": "SI",
                     "command": command or "", "chunk_axis": "ray",
                     "manifest": json.dumps(spec.manifest(), sort_keys=True),
                     **{k: v for k, v in spec.fixed.items()}})
    return ds
