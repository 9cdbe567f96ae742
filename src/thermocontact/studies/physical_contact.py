"""The problem in physical units: materials, radius, load, speed and friction in;
contact width, offset, pressures and temperatures out, for every solution branch.

For a trial half-width ``Delta`` the dimensionless groups follow from the inputs
(derivation section 5): ``Pe = v Delta / (2 k2)``, ``fHPe = f H Pe`` with
``H = k2 delta2 / A``, and the solver gives ``P_H/P``; the load that half-width
carries is ``P = P_H(Delta) / (P_H/P)`` with the Hertz load
``P_H = pi Delta^2 / (2 A R)`` (D2).  The half-widths that carry the given load are
the roots of ``h(Delta) = P_H(Delta)/P - (P_H/P)(Delta)``, which, unlike
``P(Delta)``, stays finite where ``P_H/P`` passes through zero.  ``h`` need not be
monotone: it is followed along the half-widths by continuation with step control
(every trial half-width is a point of the problem's :class:`~.ray.Ray`), and every
sign change is refined on the solver (:func:`~.ray.root`).
"""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass, field

import numpy as np

from .._version import __version__
from ..analysis.applicability import Applicability, physical_applicability
from ..analysis.fields import contact_fields
from ..io.results import Result
from ..problem.parameters import SolveError
from ..problem.physical import FHPE_MIN, MAX_WIDTH, PhysicalProblem
from ..problem.validation import InputError, check_finite, check_nonnegative, check_positive
from ..numerics.continuation import secant
from ..solvers.result import ContactSolution
from ..solvers.single_patch import DEFAULT_TOL, assessed
from .boundaries import EVENT_RTOL, Path, trace
from .ray import FIELD_TOL_FACTOR, Ray, brackets, follow, refine_fields, root, start_of_root

__all__ = ["ALONG", "Branch", "FHPE_MIN", "MAX_WIDTH", "PhysicalContact", "PhysicalProblem",
           "contact", "follow_along", "problem_ray"]

#: The physical inputs a path may follow (SI units), and whether it is sampled
#: geometrically.
ALONG = {"load": True, "speed": True, "radius": True, "friction": False,
         # With the bulk temperatures (derivation section 17): T2 - T1 (K), the
         # cylinder's T1 kept, and a stationary half-plane's sink distance (m).
         "temperature_difference": False, "sink_distance": True}

#: Unknowns per function of the validity checks behind the largest valid load.
VALIDITY_N = 64


def problem_ray(problem: PhysicalProblem) -> Ray:
    """The dimensionless problems of every trial half-width of ``problem``
    (:meth:`~thermocontact.problem.physical.PhysicalProblem.ray_parameters`)."""
    return Ray(**problem.ray_parameters())


#: The units of a physical contact's quantities (SI; temperatures are rises above the
#: cylinder's incoming surface temperature, except the absolute peak temperatures).
SI_UNITS = {
    "half_width": "m", "offset": "m", "a": "m", "b": "m", "x": "m",
    "peak_pressure": "Pa", "mean_pressure": "Pa", "pressure": "Pa",
    "flash_temperature": "K", "flash_temperature_half_plane": "K",
    "temperature_cylinder": "K", "temperature_half_plane": "K",
    "temperature_mismatch": "K", "half_plane_incoming_temperature": "K",
    "peak_temperatures": "K", "flash_temperatures": "K", "bulk_temperatures": "K",
    "heat_cylinder": "W/m", "heat_half_plane": "W/m",
    "hertz_half_width": "m", "hertz_peak_pressure": "Pa", "largest_valid_load": "N/m",
    "radius": "m", "load": "N/m", "speed": "m/s", "speed2": "m/s",
    "sink_distance": "m", "layer_thickness": "m",
    "half_width_min": "m", "half_width_max": "m"}


@dataclass(frozen=True, eq=False, repr=False)
class Branch(Result):
    """One half-width that carries the load, with its physical fields.

    Positions ``x`` are measured from the cylinder's initial point of contact,
    positive toward the leading edge (where the cylinder's surface enters).
    Temperatures are rises above the temperature of the cylinder's material as
    it enters the contact; the half-plane's equals the cylinder's in the contact
    (perfect thermal contact).  A stationary half-plane's far-field level is set by
    the bodies' boundary conditions outside this 2-D model; a moving half-plane's
    incoming temperature, over the cylinder's, is the one the heat partition
    implies (``half_plane_incoming_temperature``).

    With the bulk temperatures given (derivation section 17), ``lam`` is the
    partition they imply, ``lam_error`` its estimated error (at most the branch's
    relative estimate times ``max(|lam|, 0.01)``), and the absolute temperatures are
    reported: ``peak_temperatures`` (each body's greatest surface temperature, the
    cylinder's bulk temperature plus the flash temperature: the surfaces are at one
    temperature in the contact, where both peak), ``flash_temperatures`` (each body's
    rise over its own bulk or sink temperature) and ``under_limits`` (each peak below
    its material's ``max_temperature``; None where the material has none).

    ``error_estimate`` is that of ``P_H/P`` and ``sigma/Delta`` (target ``tol``);
    ``field_error`` that of the fields, relative: the peak pressure, the flash
    temperature and the slopes' and strain's factors, local values that converge
    more slowly in ``n``, refined from the branch's ``n`` to their own target
    (:data:`~thermocontact.studies.ray.FIELD_TOL_FACTOR` ``tol``,
    :func:`~thermocontact.studies.ray.refine_fields`; the solution is then that of
    the finer ``n``), 0 for Hertz's contact (exact at any ``n``).
    """

    half_width: float
    offset: float
    a: float
    b: float
    peak_pressure: float
    mean_pressure: float
    pe: float
    fhpe: float
    lam: float
    load_ratio: float
    valid: bool
    flash_temperature: float
    heat_cylinder: float
    heat_half_plane: float
    temperature_mismatch: float
    half_plane_incoming_temperature: float | None
    error_estimate: float
    converged: bool
    x: np.ndarray = field(repr=False)
    pressure: np.ndarray = field(repr=False)
    temperature_cylinder: np.ndarray = field(repr=False)
    temperature_half_plane: np.ndarray = field(repr=False)
    solution: ContactSolution = field(repr=False)
    applicability: Applicability | None = field(default=None, repr=False)
    lam_error: float | None = None
    bulk_temperatures: tuple | None = None
    temperature_limits: tuple | None = None
    field_error: float | None = None

    @property
    def peak_temperatures(self) -> tuple | None:
        """Each body's greatest absolute surface temperature, K (bulk temperatures
        given), else None."""
        if self.bulk_temperatures is None:
            return None
        peak = self.bulk_temperatures[0] + self.flash_temperature
        return (peak, peak)

    @property
    def flash_temperatures(self) -> tuple | None:
        """Each body's greatest surface temperature over its own bulk (or sink)
        temperature, K (bulk temperatures given), else None."""
        if self.bulk_temperatures is None:
            return None
        t1, t2 = self.bulk_temperatures
        return (self.flash_temperature, t1 + self.flash_temperature - t2)

    @property
    def under_limits(self) -> tuple | None:
        """Whether each body's peak stays below its material's limit (None for a
        material without one), bulk temperatures given; else None."""
        if self.bulk_temperatures is None:
            return None
        return tuple(None if limit is None else bool(peak < limit)
                     for peak, limit in zip(self.peak_temperatures, self.temperature_limits))

    @property
    def flash_temperature_half_plane(self) -> float | None:
        """A moving half-plane's largest surface temperature rise over its own incoming
        temperature (``flash_temperature`` is the cylinder's, the two surfaces being at
        one temperature in the contact); None for a stationary half-plane."""
        if self.half_plane_incoming_temperature is None:
            return None
        return self.flash_temperature - self.half_plane_incoming_temperature

    @property
    def fields_converged(self) -> bool:
        """Whether ``field_error`` meets its target (``FIELD_TOL_FACTOR`` times the
        solution's ``tol``)."""
        return bool(self.field_error is not None
                    and self.field_error <= FIELD_TOL_FACTOR * self.solution.tol)

    @property
    def applicable(self) -> bool:
        """Whether the theory applies (:mod:`thermocontact.analysis.applicability`)."""
        return bool(self.applicability is not None and self.applicability.applicable)

    UNITS = SI_UNITS

    def _record(self) -> dict:
        """The branch's JSON record (SI units; without the distributions)."""
        v = self.solution.validity
        return {
            "half_width": self.half_width, "offset": self.offset, "a": self.a, "b": self.b,
            "peak_pressure": self.peak_pressure, "mean_pressure": self.mean_pressure,
            "pe": self.pe, "fhpe": self.fhpe, "lam": self.lam, "load_ratio": self.load_ratio,
            "valid": self.valid, "flash_temperature": self.flash_temperature,
            "heat_cylinder": self.heat_cylinder, "heat_half_plane": self.heat_half_plane,
            "temperature_mismatch": self.temperature_mismatch,
            "half_plane_incoming_temperature": self.half_plane_incoming_temperature,
            "flash_temperature_half_plane": self.flash_temperature_half_plane,
            "n": self.solution.n, "error_estimate": self.error_estimate,
            "converged": self.converged, "field_error": self.field_error,
            "min_pressure_margin": v.pressure_margin, "min_gap_margin": v.gap_margin,
            "reason": v.reason, "strictly_valid": v.strictly_valid,
            "applicable": self.applicable,
            "applicability_reasons": list(self.applicability.reasons),
            **({} if self.bulk_temperatures is None else {
                "lam_error": self.lam_error,
                "peak_temperatures": list(self.peak_temperatures),
                "flash_temperatures": list(self.flash_temperatures),
                "under_limits": list(self.under_limits)}),
        }

    def _units(self) -> dict:
        return {}  # the contact's record carries them once

    def _summary(self) -> str:
        return (f"half_width={self.half_width:.6g} m, offset={self.offset:.6g} m, "
                f"peak_pressure={self.peak_pressure:.6g} Pa, flash_temperature="
                f"{self.flash_temperature:.6g} K, valid={self.valid}, "
                f"applicable={self.applicable}")


@dataclass(frozen=True, eq=False, repr=False)
class PhysicalContact(Result):
    """All solution branches of one physical problem.

    Attributes
    ----------
    problem : PhysicalProblem
    branches : tuple of Branch
        In order of increasing half-width.
    primary : Branch or None
        The first valid branch from small half-widths (the one reached by loading
        from zero), else the first branch.
    message : str
        How the search ended: the valid branch found, or why there is none.
    largest_valid_load : float or None
        When no branch is valid: the largest load over the scanned half-widths
        whose solution is valid, N/m (None if there is none; ``inf`` when valid
        solutions reach the limiting width, where the load grows without bound).
    searched : tuple of float or None
        The half-widths searched for roots, m, and the fHPe they span:
        ``(Delta_lo, Delta_hi, fhpe_lo, fhpe_hi)`` (None without thermal coupling).
    """

    problem: PhysicalProblem
    branches: tuple
    primary: Branch | None
    message: str
    largest_valid_load: float | None
    searched: tuple | None = None

    STATUSES = {
        "solved": "a valid branch carries the load, its error estimate within its target",
        "not converged": "a valid branch carries the load, its error estimate beyond its "
                         "target",
        "invalid": "every half-width that carries the load violates a contact inequality: "
                   "no single-patch contact exists",
        "no solution": "no half-width carries the load"}
    SUCCESS = frozenset({"solved"})
    UNITS = SI_UNITS

    @property
    def status(self) -> str:
        """One of :attr:`STATUSES`."""
        if not self.branches:
            return "no solution"
        if not self.primary.valid:
            return "invalid"
        return "solved" if self.primary.converged else "not converged"

    def _summary(self) -> str:
        p = self.problem
        prim = self.primary
        return (f"{p.cylinder.name} on {p.half_plane.name}, load={p.load:.6g} N/m, "
                f"status={self.status!r}, branches={len(self.branches)}"
                + ("" if prim is None else f", half_width={prim.half_width:.6g} m, "
                   f"valid={prim.valid}, applicable={prim.applicable}"))

    def _record(self) -> dict:
        """The JSON record of the contact (SI units): the primary branch's numbers at
        the top level, every branch under ``branches``, the inputs."""
        prob = self.problem
        prim = self.primary
        rec = {key: (getattr(prim, key) if prim is not None else None) for key in (
            "half_width", "offset", "a", "b", "peak_pressure", "mean_pressure", "pe", "fhpe",
            "flash_temperature", "heat_cylinder", "heat_half_plane")}
        rec.update({
            "hertz_half_width": prob.hertz_half_width,
            "hertz_peak_pressure": prob.hertz_peak_pressure,
            "lam": prob.lam if prob.lam is not None else (
                prim.lam if prim is not None else None),
            "valid": bool(prim is not None and prim.valid),
            "applicable": bool(prim is not None and prim.applicable),
            "applicability_reasons": (list(prim.applicability.reasons) if prim is not None
                                      else []),
            "error_estimate": prim.error_estimate if prim is not None else None,
            "converged": prim.converged if prim is not None else None,
            "message": self.message,
            "largest_valid_load": self.largest_valid_load,
            "searched": (None if self.searched is None else dict(zip(
                ("half_width_min", "half_width_max", "fhpe_min", "fhpe_max"), self.searched))),
            "branches": [b.to_dict() for b in self.branches],
            "inputs": {
                "cylinder": prob.cylinder.name, "half_plane": prob.half_plane.name,
                "radius": prob.radius, "load": prob.load, "speed": prob.speed,
                "speed2": prob.speed2, "friction": prob.friction, "lam": prob.lam,
                "dundurs": prob.dundurs,
                **({} if prob.bulk_temperatures is None else {
                    "bulk_temperatures": list(prob.bulk_temperatures),
                    "sink_distance": prob.sink_distance,
                    "layer_thickness": prob.layer_thickness}),
            },
            "beta_f": prob.beta_f,
            "version": __version__,
        })
        if prob.bulk_temperatures is not None:
            rec.update({key: (prim.to_dict()[key] if prim is not None else None) for key in (
                "lam_error", "peak_temperatures", "flash_temperatures", "under_limits")})
            rec["theta"] = prob.theta
        if rec["largest_valid_load"] is not None and not np.isfinite(rec["largest_valid_load"]):
            rec["largest_valid_load"] = "unbounded"
        return rec


def _branch(prob: PhysicalProblem, pe, n, tol, estimate) -> Branch:
    """The fields of the solution at ``Pe`` with ``n`` unknowns, whose error estimate
    is ``estimate`` (:func:`~.ray.root`)."""
    half_width = prob.half_width(pe)
    # The F = 0 path has one exact level (P_H/P = 1 at any n): no error.
    hertz = prob.friction == 0.0 or prob.fhpe(1.0) == 0.0
    est = 0.0 if hertz else estimate
    ray = problem_ray(prob)

    def fields_of(s):
        return contact_fields(s, length=half_width, load=prob.load,
                              temperature_units=prob.temperature_units,
                              fractions=prob.compliance_fractions)
    if hertz:  # Hertz's contact: exact at any n
        sol = ray.solve_at(pe, n, check_validity=True)
        f, field_error = fields_of(sol), 0.0
    else:
        # The fields (local values) to their own target, from n on (ray.refine_fields);
        # the contact inequalities of the finest level alone, the one reported.
        fine = refine_fields(lambda m: ray.solve_at(pe, m), n, fields_of, tol,
                             method=ray.method)
        sol, f = assessed(fine.levels[-1][0].solution), fine.levels[-1][0].fields
        field_error = fine.estimate
    sol = sol.replace(error_estimate=est, tol=tol)
    offset = sol.sigma_over_delta * half_width
    lam = sol.lam
    q = prob.friction * prob.sliding_speed * prob.load
    return Branch(
        half_width=float(half_width), offset=float(offset),
        a=float(offset - half_width), b=float(offset + half_width),
        peak_pressure=f.peak_pressure, mean_pressure=f.mean_pressure,
        pe=float(sol.parameters.pe), fhpe=float(sol.parameters.fhpe), lam=float(lam),
        load_ratio=float(sol.load_ratio), valid=bool(sol.valid),
        flash_temperature=f.flash_temperature,
        heat_cylinder=0.5 * q * (1.0 + lam), heat_half_plane=0.5 * q * (1.0 - lam),
        temperature_mismatch=f.temperature_mismatch,
        half_plane_incoming_temperature=f.half_plane_incoming_temperature,
        error_estimate=float(sol.error_estimate),
        converged=bool(sol.error_estimate <= tol),
        field_error=None if field_error is None else float(field_error),
        x=f.x, pressure=f.pressure,
        temperature_cylinder=f.temperature_cylinder,
        temperature_half_plane=f.temperature_half_plane,
        solution=sol,
        applicability=physical_applicability(prob, f),
        **({} if prob.bulk_temperatures is None else dict(
            lam_error=float(est * max(abs(lam), 0.01)),
            bulk_temperatures=prob.bulk_temperatures,
            temperature_limits=(prob.cylinder.max_temperature,
                                prob.half_plane.max_temperature))),
    )


def contact(problem: PhysicalProblem, tol=1e-6, progress=None) -> PhysicalContact:
    """Find every half-width that carries the load, with validity and physical fields.

    Parameters
    ----------
    problem : PhysicalProblem
    tol : float
        Error target of ``P_H/P`` in each branch's final solve (default 1e-6).
    progress : callable, optional
        ``progress(done, 100)`` while the half-widths are followed
        (:func:`~.ray.follow`).

    Returns
    -------
    PhysicalContact
    """
    prob = problem
    tol = check_positive("tol", tol)
    if prob.friction == 0.0 or prob.fhpe(1.0) == 0.0:
        # No thermal coupling: the Hertz contact, exactly (P_H/P = 1 at any n).
        roots = [(prob.pe_hertz, 16, 0.0)]
        scan = None
    else:
        lo, hi = prob.scan_range()
        ray, pe_h = problem_ray(prob), prob.pe_hertz
        scan = follow(ray, prob.pe(lo), prob.pe(hi), pe_h=pe_h, progress=progress)
        roots = []
        for i in brackets(scan.pe, scan.load_ratio, pe_h):
            try:
                r = root(ray, pe_h, scan, i, tol)
            except SolveError:  # the closure singular at a level: as at the limit
                r = (None, None, None)
            if r is not None:
                roots.append(r)
    branches, singular = [], 0
    for pe, n, estimate in roots:
        try:
            if pe is None:
                raise SolveError("singular at a level of the refinement")
            branches.append(_branch(prob, pe, n, tol, estimate))
        except SolveError:
            # Only at the limiting width, where P_H/P = 0 and the offset is infinite.
            singular += 1
    branches = tuple(branches)
    valid = [b for b in branches if b.valid]
    primary = valid[0] if valid else (branches[0] if branches else None)
    largest = None
    if not valid:
        largest = _largest_valid_load(prob, scan) if scan is not None else float("inf")
    message = ""
    if not branches and singular:
        message = ("the load is carried only at the limiting contact width, where P_H/P = 0 "
                   "and the offset is infinite (P_H is negligible against the load: check "
                   "the radius and the load)")
    elif not branches:
        message = ("no half-width carries this load: it exceeds every load that a single "
                   "contact patch can carry at this speed")
    elif not valid:
        message = ("every solution violates a contact inequality (tensile pressure, "
                   "interpenetration or negative load): no single-patch contact exists")
    if valid:
        k = branches.index(primary) + 1
        message = (f"a valid single patch carries the load (branch {k} of {len(branches)}, "
                   f"half-width {primary.half_width:.4g} m)")
        if not primary.converged:
            message += (f"; its error estimate {primary.error_estimate:.1e} is beyond the "
                        f"target {tol:.0e}")
    if message and largest is not None and np.isfinite(largest):
        message += f"; the largest load with a valid solution is {largest:.4g} N/m"
    searched = None
    if scan is not None:
        searched = (float(lo), float(hi), float(prob.fhpe(lo)), float(prob.fhpe(hi)))
        if message and not valid:
            message += (f" (half-widths searched: {searched[0]:.3g} to {searched[1]:.3g} m, "
                        f"fHPe {searched[2]:.3g} to {searched[3]:.3g})")
    return PhysicalContact(prob, branches, primary, message, largest, searched)


def _largest_valid_load(prob, scan):
    """Largest load carried by a valid solution over the followed half-widths.

    Each sample with ``L > 0`` is assessed (one with tension inside the tolerated edge
    layers is invalid without the full assessment); between a valid sample and an
    invalid neighbour the validity change is located by Brent's method on the margins
    (:func:`~.boundaries.locate_events`); its load, ``P_H(Delta)/L``, is a candidate
    with the valid samples'.  All at ``n =`` :data:`VALIDITY_N`, not the scan's 16:
    with delta1 != delta2 the margins converge algebraically (derivation section 8),
    and at n = 16 even the order of the events can differ.  Valid within 1 % of the limiting width
    (``L -> 0``), where the load grows without bound, it is ``inf``.
    """
    from .boundaries import locate_events

    ray = problem_ray(prob)
    pe, L = scan.pe, scan.load_ratio
    inside = np.cos(np.linspace(np.pi, 0.0, 257))[1:-1]  # 7.5e-5 from the edges

    n = VALIDITY_N

    def at(p):
        return ray.solve_at(p, n, check_validity=True, polish=False)

    valid = np.zeros(pe.size, dtype=bool)
    for i in np.flatnonzero(L > 0):
        try:
            sol = ray.solve_at(pe[i], n)
            # Tension inside the tolerated edge layers is invalid for certain.
            valid[i] = bool(np.min(sol.pressure_at(inside)) >= 0.0 and at(pe[i]).valid)
        except SolveError:
            continue
    candidates = [(pe[i], L[i]) for i in np.flatnonzero(valid)]
    for i in np.flatnonzero(valid[:-1] != valid[1:]):
        try:
            ends = [at(pe[i]), at(pe[i + 1])]
            events = locate_events(at, [pe[i], pe[i + 1]], ends, only_validity_changes=True,
                                   xtol=lambda a, b: 1e-10 * max(a, b))
            candidates += [(e.at, at(e.at).load_ratio) for e in events]
        except SolveError:
            continue
    candidates = [(p, l) for p, l in candidates if l > 0]
    if not candidates:
        return None
    if min(l for _, l in candidates) < 0.01:
        return float("inf")
    return float(max(prob.load * (p / prob.pe_hertz) ** 2 / l for p, l in candidates))


def _primary(problem: PhysicalProblem, along: str):
    """``at(n, x)``: the first branch (least half-width) of ``problem`` with ``along``
    set to ``x``, solved with ``n`` unknowns; None where there is none.

    Its ``Pe`` solves D26 at that ``n`` by secant steps in ``ln Pe`` from the nearest
    root found so far, moved by the change of ``ln Pe_H`` (exact where ``P_H/P`` does
    not change); a point farther than a factor 1.5 in ``Pe_H`` (or friction) from
    every root found is first bracketed by a scan of its ray (:func:`~.ray.follow`).
    """
    found = []  # (x, Pe_H, ln Pe, slope of h there)

    def at(n, x):
        prob = _moved(problem, along, x)
        ray, pe_h = problem_ray(prob), prob.pe_hertz
        if ray.fh == 0.0:
            return ray.solve_at(pe_h, n, check_validity=True)

        def h(y):
            return math.exp(2 * y) / pe_h**2 - ray.load_ratio(math.exp(y), n)
        def distance(root):
            # In ln Pe_H; along the friction also in ln f (the ray itself moves).
            far = abs(math.log(root[1] / pe_h))
            if along == "friction":
                far = max(far, abs(math.log(max(root[0], 1e-300) / max(x, 1e-300))))
            return far
        near = min(found, key=distance, default=None)
        step = None
        if near is not None and distance(near) < math.log(1.5):
            y = near[2] + math.log(pe_h / near[1])
            step = secant(h, y, near[3], y - 1.0, y + 1.0, xtol=1e-13)
        if step is None:
            # No root found so far near enough, or the steps from it failed: bracket
            # the first root on the ray (poles, where |h| stays large, skipped).
            a, b = prob.scan_range()
            scan = follow(ray, prob.pe(a), prob.pe(b), pe_h=pe_h)
            for i in brackets(scan.pe, scan.load_ratio, pe_h):
                lo, hi = math.log(scan.pe[i]), math.log(scan.pe[i + 1])
                y, slope = start_of_root(scan, pe_h, i)
                step = secant(h, y, slope, lo, hi, xtol=1e-13)
                if step is not None and abs(h(step[0])) <= 1e-6:
                    break
                step = None
        if step is None:
            return None
        y, slope = step
        found.append((x, pe_h, y, slope))
        try:
            return ray.solve_at(math.exp(y), n, check_validity=True)
        except SolveError:
            return None
    return at


def _moved(problem: PhysicalProblem, along: str, value) -> PhysicalProblem:
    """``problem`` with ``along`` at ``value``; along the speed both surfaces' speeds
    scale together (the ratio v2/v1, and so the ray, is kept)."""
    if along == "speed":
        return dataclasses.replace(problem, speed=value, speed2=value * problem.speed_ratio)
    if along in ("temperature_difference", "sink_distance") and problem.bulk_temperatures is None:
        raise InputError(f"a path along {along} needs bulk_temperatures (not lam)",
                         parameters=("along", "bulk_temperatures"))
    if along == "temperature_difference":
        t1 = problem.bulk_temperatures[0]
        return dataclasses.replace(problem, bulk_temperatures=(t1, t1 + value))
    if along == "sink_distance":
        return dataclasses.replace(problem, sink_distance=value, layer_thickness=None)
    return dataclasses.replace(problem, **{along: value})


def follow_along(problem: PhysicalProblem, along: str, start, stop, *, tol=DEFAULT_TOL,
                 rtol=1e-9, points=17, n=None, event_rtol=EVENT_RTOL, progress=None) -> Path:
    """Follow the contact of ``problem`` along load, speed, radius or friction and
    locate every change of validity (:func:`~.boundaries.trace`).

    The solution followed is the first branch, of least half-width (the one reached
    by loading from zero).  Its dimensionless margins are those of the solution at
    each point; events are located by Brent's method on them to ``rtol`` relative in
    the physical parameter.

    Parameters
    ----------
    problem : PhysicalProblem
        The fixed inputs (its value of ``along`` is replaced; along the speed, with a
        moving half-plane, both speeds scale together).
    along : {"load", "speed", "radius", "friction", "temperature_difference", "sink_distance"}
        The last two with the bulk temperatures (derivation section 17): the
        half-plane's far temperature less the cylinder's (K, the cylinder's kept), a
        stationary half-plane's sink distance (m).
    start, stop : float
        SI units; load, speed, radius and sink distance positive, friction
        non-negative, the temperature difference any.
    tol, rtol, points, n, event_rtol, progress
        As in :func:`~.boundaries.follow`.

    Returns
    -------
    Path
        ``fixed`` holds the other inputs (materials by name, SI units).
    """
    from ..problem.validation import check_choice

    along = check_choice("along", along, tuple(ALONG))
    for name, value in (("start", start), ("stop", stop)):
        check = {"friction": check_nonnegative, "temperature_difference": check_finite}.get(
            along, check_positive)
        check(name, value)
        _moved(problem, along, value)  # validated as a problem
    fixed = {"cylinder": problem.cylinder.name, "half_plane": problem.half_plane.name,
             **{k: getattr(problem, k) for k in ("radius", "load", "speed", "friction", "lam")
                if k != along}}
    if problem.bulk_temperatures is not None:
        del fixed["lam"]
        if along == "temperature_difference":
            fixed["cylinder_temperature"] = problem.bulk_temperatures[0]
        else:
            fixed["bulk_temperatures"] = list(problem.bulk_temperatures)
        if along != "sink_distance" and problem.sink_length is not None:
            fixed["sink_distance"] = problem.sink_length
    if problem.speed2:
        fixed["speed_ratio"] = problem.speed_ratio
    fixed["dundurs"] = problem.dundurs
    return trace(_primary(problem, along), along, fixed, start, stop, tol=tol, rtol=rtol,
                 points=points, log=ALONG[along], n=n, event_rtol=event_rtol,
                 progress=progress)
