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
from ..problem.conductance import PhysicalConductance
from .contact_sets import physical_contact_set
from ..execution.resumable import run_chunks
from ..problem.axes import PHYSICAL_UNITS
from .maps import Axis, check_axis_name, parse_axis, prepare_dataset
from .physical_contact import problem_ray
from ..numerics.interpolation import interpolation_error, nearest
from ..numerics.interpolation import local as _local
from .ray import FIELD_TOL_FACTOR, Ray, refine_fields
from .ray import interpolated_roots as _interpolated_roots

__all__ = ["CONTACT_SET_SECONDS", "OperatingSpec", "RAY_PER_DECADE", "compute_operating_map",
           "operating_point", "operating_ray", "ray_samples", "sample_fields"]

#: Physical axes of an operating map, and their SI units.
AXES = PHYSICAL_UNITS
#: Samples of the ray per decade of Pe, and of one chunk.
RAY_PER_DECADE = 24
RAY_CHUNK = 16
#: Ray samples per chunk of their fields (each a refinement, up to n = 256: seconds).
FIELD_CHUNK = 2


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
        14c): past the single patch's boundary it says what exists instead.
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
                "fields": "refined to their own target",
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
    """Solve the ray at the chunk's Péclet numbers: ``P_H/P``, offset, validity, error
    estimate and ``n`` (the fields come later, where a point needs them:
    :func:`evaluate_fields`)."""
    out = {k: [] for k in ("pe", "load_ratio", "sigma_over_delta", "valid", "error_estimate",
                           "n", "status", "reason")}
    ray = task["ray"]
    for pe in task["pe"]:
        try:
            with warnings.catch_warnings():
                warnings.simplefilter("ignore", ConvergenceWarning)
                sol = ray.model(pe, tol=task["tol"]).solve(ray.fh * pe, lam=ray.lam,
                                                           polish=False)
            rec = (sol.load_ratio, sol.sigma_over_delta, int(sol.valid),
                   sol.error_estimate if sol.error_estimate is not None else math.nan, sol.n,
                   sol.status, sol.validity.reason)
        except (SolveError, InputError) as exc:
            nan = math.nan
            rec = (nan, nan, 0, nan, 0, "failed", str(exc))
        for k, v in zip(list(out)[1:], rec):
            out[k].append(v)
        out["pe"].append(pe)
    return out


#: A ray sample's fields (:func:`evaluate_fields`), in units of its half-width:
#: pressures of P/Delta, temperatures of f |v1 - v2| P/(pi K1) (D24).
SAMPLE_FIELDS = ("peak", "flash", "slope_cylinder", "slope_half_plane", "strain",
                 "temperature_low", "temperature_high", "field_error", "field_n")


def evaluate_fields(task) -> dict:
    """The fields of the chunk's ray samples (``task["samples"]``: ``(Pe, n)``, ``n``
    where ``P_H/P`` met the target), each refined until they meet their target
    (:func:`~.ray.refine_fields`): :data:`SAMPLE_FIELDS`.  A point read between samples
    adds the interpolation's error (:func:`operating_point`'s estimate)."""
    out = {k: [] for k in SAMPLE_FIELDS}
    ray = task["ray"]
    for pe, n in task["samples"]:
        try:
            with warnings.catch_warnings():
                warnings.simplefilter("ignore", ConvergenceWarning)
                fine = refine_fields(
                    lambda m, pe=pe: ray.solve_at(pe, m, polish=False), n,
                    lambda s: contact_fields(s, fractions=task["fractions"]),
                    task["tol"], method=ray.method)
            level = fine.levels[-1][0]
            f = level.fields
            rec = (f.peak_pressure, f.flash_temperature, *f.slope_factors, f.strain_pressure,
                   *f.temperature_range, math.nan if fine.estimate is None else fine.estimate,
                   level.solution.n)
        except (SolveError, InputError):
            rec = (math.nan,) * (len(SAMPLE_FIELDS) - 1) + (0,)
        for k, v in zip(SAMPLE_FIELDS, rec):
            out[k].append(v)
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


def needed_samples(ray, pe_h_lo, pe_h_hi) -> np.ndarray:
    """Indices of the ray samples that the points of ``Pe_H`` in ``[pe_h_lo, pe_h_hi]``
    read their fields from: the stencils
    (:data:`~thermocontact.numerics.interpolation.STENCIL`, and the next smaller
    of the interpolation's estimate) of every interval where ``Pe^2 - Pe_H^2 L`` changes
    sign for some ``Pe_H`` of the range (where :func:`~.ray.interpolated_roots` looks).

    Each sample's sign changes once in ``u = Pe_H^2``, at ``Pe^2/L``; an interval's
    pair of signs is constant between those two values, so it is tested at the range's
    ends and at those values that lie inside it.
    """
    pe, L = np.asarray(ray["pe"]), np.asarray(ray["load_ratio"])
    g = pe**2
    with np.errstate(divide="ignore", invalid="ignore"):
        turn = np.where(L > 0, g / L, np.nan)
    lo, hi = pe_h_lo**2, pe_h_hi**2
    tests = [np.full(pe.size - 1, lo), np.full(pe.size - 1, hi)]
    for t in (turn[:-1], turn[1:]):
        tests.append(np.where((t >= lo) & (t <= hi), t, lo))
    changes = np.zeros(pe.size - 1, dtype=bool)
    for u in tests:
        a, b = g[:-1] - u * L[:-1], g[1:] - u * L[1:]
        changes |= np.isfinite(a) & np.isfinite(b) & (a * b <= 0)
    needed = np.zeros(pe.size, dtype=bool)
    for i in np.flatnonzero(changes):
        # A root inside the interval reads the STENCIL samples nearest it (and the
        # next smaller stencil, among them): i - 2 to i + 3 for STENCIL = 6.
        needed[nearest(np.log(pe), 0.5 * (np.log(pe[i]) + np.log(pe[i + 1])))] = True
    return np.flatnonzero(needed)


def sample_fields(spec: OperatingSpec, ray: dict, pe_h_lo, pe_h_hi, workers=1,
                  progress=None, store_path=None) -> dict:
    """``ray`` with :data:`SAMPLE_FIELDS` at the samples the points of ``Pe_H`` in
    ``[pe_h_lo, pe_h_hi]`` need (:func:`needed_samples`; NaN elsewhere), computed in
    chunks kept in ``store_path`` as they finish."""
    idx = [int(i) for i in needed_samples(ray, pe_h_lo, pe_h_hi)
           if ray["status"][i] != "failed"]
    base = {"ray": spec.ray(), "tol": spec.tol, "fractions": spec.fractions()}
    tasks = [{**base, "samples": [(float(ray["pe"][i]), int(ray["n"][i]))
                                  for i in idx[k:k + FIELD_CHUNK]]}
             for k in range(0, len(idx), FIELD_CHUNK)]
    manifest = {**spec.manifest(), "part": "fields", "samples": [
        [float(ray["pe"][i]), int(ray["n"][i])] for i in idx], "chunk": FIELD_CHUNK}
    parts = run_chunks(evaluate_fields, tasks, manifest, store_path, workers=workers,
                       progress=progress, meanwhile=prepare_dataset)
    out = dict(ray)
    for k in SAMPLE_FIELDS:
        column = np.full(len(ray["pe"]), 0 if k == "field_n" else np.nan)
        if idx:
            column[idx] = np.concatenate([np.asarray(parts[j][k], dtype=float)
                                          for j in range(len(tasks))])
        out[k] = column
    return out


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


def in_parts(progress, count, lines):
    """One progress for a map's parts: ``count`` parts of chunks (each part's count told
    by its own progress; none when resumed), then ``lines`` lines of contact sets: the
    ``count + 1`` ``progress(done, total)`` callables."""
    totals = [0] * count

    def part(k):
        def tell(done, total):
            totals[k] = total
            if progress is not None:
                before = sum(totals[:k])
                progress(before + done, before + total + lines)
        return tell

    def last(done, total):
        if progress is not None:
            before = sum(totals)
            progress(before + done, before + total)
    return [part(k) for k in range(count)] + [last]


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


def operating_ray(spec: OperatingSpec, workers=1, progress=None, store_path=None,
                  fields_progress=None) -> dict:
    """The ray of the map's plane (:func:`ray_samples` over the single patch's range of
    every point, :meth:`PhysicalProblem.scan_range`) with the fields its points read
    (:func:`sample_fields` over the plane's range of ``Pe_H``), the fields' chunks kept
    in ``store_path``'s folder ``fields``: what :func:`operating_point` reads any point
    of the plane from."""
    load, speed, radius = spec.grid()
    pe_h = spec.pe_hertz(load, speed, radius)
    pe_lo, pe_hi = scan_range(pe_h.min(), pe_h.max(), spec.fh)
    ray = ray_samples(spec, pe_lo, pe_hi, workers=workers, progress=progress,
                      store_path=store_path)
    return sample_fields(spec, ray, pe_h.min(), pe_h.max(), workers=workers,
                         progress=fields_progress, store_path=None if store_path is None
                         else os.path.join(store_path, "fields"))


#: A point's numbers (:func:`operating_point`), the dataset's variables of the same names.
POINT_FIELDS = ("half_width", "offset", "peak_pressure", "mean_pressure", "flash_temperature",
                "load_ratio", "pe", "fhpe", "max_slope_cylinder", "max_slope_half_plane",
                "max_strain_cylinder", "max_strain_half_plane", "error_estimate")


def valid_at(ray: dict, pe) -> bool:
    """The ray's validity at ``Pe``: near an event (within a sample interval on either
    side; a relocated event may have left the interval it was found in) the event's,
    elsewhere that of the samples either side."""
    lp = ray["pe"]
    i = int(np.clip(np.searchsorted(lp, pe), 1, len(lp) - 1))
    a, b = lp[max(i - 2, 0)], lp[min(i + 1, len(lp) - 1)]
    near = [e for e in ray["events"] if a <= e.at <= b]
    if near:
        e = min(near, key=lambda e: abs(e.at - pe))
        return bool(e.valid_before) if pe < e.at else bool(e.valid_after)
    return bool(ray["valid"][i - 1]) and bool(ray["valid"][i])


def _read(lp, values, x, sample_error):
    """The interpolant of ``values`` at ``x`` and the estimate of its relative error:
    the interpolation's
    (:func:`~thermocontact.numerics.interpolation.interpolation_error`) and the largest of the
    stencil's samples' own (relative to ``max(|value|, 0.01)``, as the refinement's)."""
    v = _local(lp, values, x)
    own = np.max(sample_error[nearest(lp, x)])
    return v, interpolation_error(lp, values, x) / max(abs(v), 0.01) + own


def operating_point(spec: OperatingSpec, ray: dict, load, speed, radius) -> dict:
    """One point of the operating map from the ray's samples (:func:`ray_samples`, with
    :func:`sample_fields` over a ``Pe_H`` range holding the point's).

    Returns
    -------
    dict
        ``branches``, ``status`` (``solved`` or ``no branch``) and ``reason``; where
        solved, :data:`POINT_FIELDS` in SI units, ``valid``, ``applicable``,
        ``applicability_reasons`` (joined by "; ") and ``start`` (the edges, m, of a
        valid single patch on the one branch there, else None).  ``error_estimate``
        is the estimated relative error of the half-width, the offset (relative to
        the larger of itself and the half-width), the peak pressure, the flash
        temperature and the slopes and strains: the interpolations' estimates, the
        stencils' samples' own (their ``P_H/P`` and fields' refinements), and their
        effect through the root of D26, added.
    """
    pe_h = float(spec.pe_hertz(load, speed, radius))
    lp = np.log(ray["pe"])
    roots = _interpolated_roots(ray["pe"], ray["load_ratio"], pe_h)
    out = {"branches": len(roots), "status": "solved"}
    if not roots:
        return {**out, "status": "no branch",
                "reason": "no half-width carries this load on the searched range"}
    flags = [valid_at(ray, math.exp(r)) for r in roots]
    r = roots[flags.index(True)] if any(flags) else roots[0]
    pe = math.exp(r)
    k2, K1 = spec.half_plane.k, spec.cylinder.K
    d = pe * 2.0 * k2 / speed
    L, e_l = _read(lp, ray["load_ratio"], r, ray["error_estimate"])
    # The root's error in ln Pe from that of L: h = Pe_H^2 L - Pe^2 moves by
    # Pe_H^2 dL, at the slope dh/dx = Pe_H^2 L' - 2 Pe^2.
    step = 1e-4
    slope = pe_h**2 * (_local(lp, ray["load_ratio"], r + step)
                       - _local(lp, ray["load_ratio"], r - step)) / (2 * step) - 2 * pe**2
    dx = pe_h**2 * e_l * max(abs(L), 0.01) / max(abs(slope), 1e-300)
    # L sigma, not sigma, is smooth along the ray: sigma has a pole where L = 0.
    ls, e_ls = _read(lp, ray["load_ratio"] * ray["sigma_over_delta"], r, ray["error_estimate"])
    offset = ls / L * d
    e_offset = e_ls * max(abs(ls), 0.01) / max(abs(ls), abs(L)) + 2 * dx

    def read(name):
        v, e = _read(lp, ray[name], r, ray["field_error"])
        shift = abs(_local(lp, ray[name], r + dx) - v) / max(abs(v), 0.01)
        return v, e + shift
    (peak, e_peak), (flash, e_flash), (slope_c, e_c), (slope_h, e_h), (strain, e_s) = (
        read(k) for k in ("peak", "flash", "slope_cylinder", "slope_half_plane", "strain"))
    # Heat at the sliding speed |1 - R| v (section 5b); temperatures in units of
    # f |1 - R| v P/(pi K1) along the ray.
    unit = spec.friction * speed * abs(1.0 - spec.speed_ratio) * load / (np.pi * K1)
    # Slopes and strains as contact measures them (thermocontact.analysis.fields), from
    # the ray's per-sample factors.
    slopes, strains = slopes_and_strains(d / radius, abs(offset / d) + 1.0, L,
                                         (slope_c, slope_h), strain, spec.fractions())
    app = assess(d / radius, slopes, strains,
                 temperature_rises=(unit * _local(lp, ray["temperature_low"], r),
                                    unit * _local(lp, ray["temperature_high"], r)),
                 max_temperature=(spec.cylinder.max_temperature,
                                  spec.half_plane.max_temperature))
    valid = valid_at(ray, pe)
    reasons = app.reasons
    return {**out, "half_width": d, "offset": offset, "peak_pressure": load / d * peak,
            "mean_pressure": load / (2.0 * d), "flash_temperature": unit * flash,
            "load_ratio": L, "pe": pe, "fhpe": spec.fh * pe,
            "max_slope_cylinder": slopes[0], "max_slope_half_plane": slopes[1],
            "max_strain_cylinder": strains[0], "max_strain_half_plane": strains[1],
            # Slopes scale as d/L = d^-1 at the root (L = (Pe/Pe_H)^2), and with the
            # offset (the rigid profile's reach).
            "error_estimate": max(dx, e_offset, e_peak, e_flash, e_s,
                                  max(e_c, e_h) + 3 * dx + e_offset),
            "valid": int(valid), "applicable": int(not reasons),
            "applicability_reasons": "; ".join(reasons),
            "reason": ("valid" if valid else "invalid single patch") + (
                "; not applicable: " + "; ".join(reasons) if reasons else ""),
            "start": (offset - d, offset + d) if valid and len(roots) == 1 else None}


def compute_operating_map(spec: OperatingSpec, workers=1, progress=None, command=None,
                          store_path=None):
    """The operating map as an :class:`xarray.Dataset` (SI units).

    Returns
    -------
    xarray.Dataset
        Over the two axes: ``half_width``, ``offset``, ``peak_pressure``,
        ``mean_pressure``, ``flash_temperature``, ``load_ratio``, ``pe``, ``fhpe``,
        ``max_slope_*`` and ``max_strain_*`` of the cylinder and the half-plane (as
        ``contact`` measures them), ``error_estimate`` (of those fields, relative:
        :func:`operating_point`; the attribute ``field_tol`` is its target,
        :data:`~.ray.FIELD_TOL_FACTOR` times ``tol``), ``valid``, ``applicable`` (size, slopes, strains,
        temperatures: :func:`~thermocontact.analysis.applicability.assess`, as
        ``contact``), ``applicability_reasons`` (joined by "; "), ``branches``,
        ``status``, ``reason``; the boundary
        as values of ``Pe_H`` and as curves in the plane; with ``spec.zones`` the
        contact sets' ``zones_*`` (:func:`evaluate_contact_sets`).
    """
    import xarray as xr

    if spec.bulk_temperatures is not None:
        raise InputError("a map at fixed bulk temperatures is each point's own contact: "
                         "temperature_maps.temperature_map", parameters=("spec",))
    load, speed, radius = spec.grid()
    pe_h = spec.pe_hertz(load, speed, radius)
    # One progress for the parts: the ray's chunks, its fields', then the contact sets'.
    ray_progress, fields_progress, zone_progress = in_parts(
        progress, 2, spec.y.count if spec.zones else 0)
    ray = operating_ray(spec, workers, ray_progress, store_path, fields_progress)
    lp = np.log(ray["pe"])
    shape = pe_h.shape
    fields = {k: np.full(shape, np.nan) for k in POINT_FIELDS}
    valid = np.zeros(shape, dtype=np.int8)
    applicable = np.zeros(shape, dtype=np.int8)
    branches = np.zeros(shape, dtype=np.int32)
    status = np.full(shape, "solved", dtype=object)
    reason = np.full(shape, "", dtype=object)
    reasons_of = np.full(shape, "", dtype=object)
    # The edges (m) of the single patch where it is valid on the one branch there: the
    # contact sets start from them.
    starts = np.full(shape, None, dtype=object)
    for idx in np.ndindex(shape):
        point = operating_point(spec, ray, load[idx], speed[idx], radius[idx])
        branches[idx] = point["branches"]
        status[idx], reason[idx] = point["status"], point["reason"]
        if point["status"] != "solved":
            continue
        for k in POINT_FIELDS:
            fields[k][idx] = point[k]
        valid[idx], applicable[idx] = point["valid"], point["applicable"]
        reasons_of[idx] = point["applicability_reasons"]
        starts[idx] = point["start"]
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
                     "y": spec.y.spec, "tol": spec.tol, "field_tol": FIELD_TOL_FACTOR * spec.tol,
                     "units": "SI",
                     "command": command or "", "chunk_axis": "ray",
                     "manifest": json.dumps(spec.manifest(), sort_keys=True),
                     **{k: v for k, v in spec.fixed.items()}})
    return ds
