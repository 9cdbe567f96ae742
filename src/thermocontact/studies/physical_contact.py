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

from ..analysis.applicability import Applicability, applicability
from ..physics.green_functions import cylinder_temperature
from ..problem.materials import Material, dundurs_beta
from ..problem.parameters import Parameters, SolveError
from ..problem.validation import InputError, check_finite, check_nonnegative, check_positive
from ..numerics.continuation import secant
from ..numerics.extrema import polish_minimum
from ..solvers.result import ContactSolution
from ..solvers.single_patch import DEFAULT_TOL
from .boundaries import EVENT_RTOL, Path, trace
from .ray import Ray, brackets, follow, root, start_of_root

__all__ = ["ALONG", "Branch", "PhysicalContact", "PhysicalProblem", "contact", "follow_along"]

#: The physical inputs a path may follow (SI units), and whether it is sampled
#: geometrically.
ALONG = {"load": True, "speed": True, "radius": True, "friction": False}

#: Half-widths searched: from below fHPe = FHPE_MIN (or half the Hertz half-width)
#: up to MAX_WIDTH Hertz half-widths, whatever fHPe that reaches.  Past fHPe ~ 0.6
#: (Barber's limiting width) P_H/P is negative, and from about 2 the formal solution
#: has poles between which P_H/P turns positive again: such branches exist formally
#: and are reported with their validity (roots were found at fHPe = 2.8 and 14 for
#: steel on cast iron).
FHPE_MIN = 0.05
MAX_WIDTH = 4.0
#: Unknowns per function of the validity checks behind the largest valid load.
VALIDITY_N = 64


@dataclass(frozen=True)
class PhysicalProblem:
    """Inputs in SI units, validated on construction.

    Attributes
    ----------
    cylinder, half_plane : Material
        Body 1 (moving surface) and body 2 (stationary).
    radius : float
        Cylinder radius R, m.
    load : float
        Normal load per unit length P, N/m.
    speed : float
        Speed of the cylinder's surface through the contact v1 > 0, m/s (the sliding
        speed when the half-plane is stationary).
    friction : float
        Coulomb coefficient f >= 0.
    lam : float
        Heat partition (Q1 - Q2)/(Q1 + Q2).
    speed2 : float, optional
        Speed of the half-plane's surface through the contact v2, m/s, positive in
        the cylinder's direction (derivation section 5b); 0, the default, is a
        stationary half-plane.  The frictional heat is ``f p |v1 - v2|``.
    dundurs : bool, optional
        Keep the Dundurs term ``-(beta f/2) p`` with ``beta`` of the two materials
        (default; derivation section 5c), or drop it as the paper does.
    """

    cylinder: Material
    half_plane: Material
    radius: float
    load: float
    speed: float
    friction: float
    lam: float
    speed2: float = 0.0
    dundurs: bool = True

    def __post_init__(self):
        for name in ("cylinder", "half_plane"):
            if not isinstance(getattr(self, name), Material):
                raise InputError(f"{name} must be a Material (see thermocontact.problem.materials."
                                 f"get_material), got {getattr(self, name)!r}")
            getattr(self, name).check_conducts(name)  # K = 0: only the TEI study takes it
        for name in ("radius", "load", "speed"):
            object.__setattr__(self, name, check_positive(name, getattr(self, name)))
        object.__setattr__(self, "friction", check_nonnegative("friction", self.friction))
        object.__setattr__(self, "lam", check_finite("lam", self.lam))
        object.__setattr__(self, "speed2", check_finite("speed2", self.speed2))
        # A derived group out of the solver's range is reported with the inputs it
        # comes from, not only as the dimensionless group.
        dh = self.hertz_half_width
        try:
            if not (np.isfinite(dh) and dh > 0.0):
                raise InputError(f"the Hertz half-width sqrt(2 A R P / pi) is {dh:.3g} m")
            self.parameters(dh)
        except InputError as exc:
            raise InputError(
                f"the inputs are out of the solver's range at the Hertz half-width "
                f"{dh:.3g} m: {exc}; it follows from radius {self.radius:.3g} m, load "
                f"{self.load:.3g} N/m, speed {self.speed:.3g} m/s"
                + (f", speed2 {self.speed2:.3g} m/s" if self.speed2 else "") +
                f", friction {self.friction:g} "
                f"and the materials' E, nu, K and k ({self.cylinder.name}: E = "
                f"{self.cylinder.E:.3g} Pa, k = {self.cylinder.k:.3g} m^2/s; "
                f"{self.half_plane.name}: E = {self.half_plane.E:.3g} Pa, "
                f"k = {self.half_plane.k:.3g} m^2/s)") from None

    @property
    def compliance(self) -> float:
        """``A = (1 - nu1)/mu1 + (1 - nu2)/mu2``, 1/Pa."""
        return self.cylinder.compliance + self.half_plane.compliance

    @property
    def H(self) -> float:
        """``H = k2 delta2 / A``, dimensionless (the paper's eq. 10, corrected; D13)."""
        return self.half_plane.k * self.half_plane.distortivity / self.compliance

    @property
    def hertz_half_width(self) -> float:
        """``Delta_H = sqrt(2 A R P / pi)`` (D2), m."""
        return float(np.sqrt(2.0 * self.compliance * self.radius * self.load / np.pi))

    @property
    def hertz_peak_pressure(self) -> float:
        """``p0 = 2 P / (pi Delta_H)``, Pa."""
        return 2.0 * self.load / (np.pi * self.hertz_half_width)

    @property
    def beta_f(self) -> float:
        """``B = beta f`` of the materials (0 with ``dundurs=False``)."""
        return dundurs_beta(self.cylinder, self.half_plane) * self.friction if self.dundurs else 0.0

    @property
    def speed_ratio(self) -> float:
        """``R = v2/v1``."""
        return self.speed2 / self.speed

    @property
    def sliding_speed(self) -> float:
        """``|v1 - v2|``, m/s: the speed that makes the heat."""
        return abs(self.speed - self.speed2)

    def pe(self, half_width):
        """``Pe = v1 Delta / (2 k2)``."""
        return self.speed * half_width / (2.0 * self.half_plane.k)

    def fhpe(self, half_width):
        """``fHPe = f H |v1 - v2| Delta / (2 k2)`` at half-width ``Delta`` (D13b)."""
        return self.friction * self.H * abs(1.0 - self.speed_ratio) * self.pe(half_width)

    @property
    def pe_hertz(self) -> float:
        """``Pe_H = v Delta_H / (2 k2)``: with the ray, all that load, radius and speed
        decide (D26)."""
        return self.pe(self.hertz_half_width)

    def half_width(self, pe):
        """The half-width at ``Pe``, m."""
        return pe * 2.0 * self.half_plane.k / self.speed

    def ray(self) -> Ray:
        """The dimensionless problems of every trial half-width."""
        c, h = self.cylinder, self.half_plane
        return Ray(h.K / c.K, h.k / c.k, c.distortivity / h.distortivity,
                   self.friction * self.H * abs(1.0 - self.speed_ratio), self.lam,
                   speed_ratio=self.speed_ratio, beta_f=self.beta_f)

    def hertz_load(self, half_width):
        """``P_H = pi Delta^2 / (2 A R)``, N/m."""
        return np.pi * half_width**2 / (2.0 * self.compliance * self.radius)

    def parameters(self, half_width) -> Parameters:
        """Dimensionless parameters at half-width ``Delta``."""
        c, h = self.cylinder, self.half_plane
        return Parameters(self.pe(half_width), self.fhpe(half_width), h.K / c.K, h.k / c.k,
                          c.distortivity / h.distortivity, self.speed_ratio, self.beta_f)

    def to_dimensionless(self, half_width) -> dict:
        """The inputs of :func:`thermocontact.solve` at half-width ``Delta``."""
        p = self.parameters(half_width)
        out = dict(pe=p.pe, fhpe=p.fhpe, K2_over_K1=p.K2_over_K1, k2_over_k1=p.k2_over_k1,
                   delta1_over_delta2=p.delta1_over_delta2, lam=self.lam)
        if p.speed_ratio:
            out["speed_ratio"] = p.speed_ratio
        if p.beta_f:
            out["beta_f"] = p.beta_f
        return out


@dataclass(frozen=True)
class Branch:
    """One half-width that carries the load, with its physical fields.

    Positions ``x`` are measured from the cylinder's initial point of contact,
    positive toward the leading edge (where the cylinder's surface enters).
    Temperatures are rises above the temperature of the cylinder's material as
    it enters the contact; the half-plane's equals the cylinder's in the contact
    (perfect thermal contact).  A stationary half-plane's far-field level is set by
    the bodies' boundary conditions outside this 2-D model; a moving half-plane's
    incoming temperature, over the cylinder's, is the one the heat partition
    implies (``half_plane_incoming_temperature``).
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

    @property
    def flash_temperature_half_plane(self) -> float | None:
        """A moving half-plane's largest surface temperature rise over its own incoming
        temperature (``flash_temperature`` is the cylinder's, the two surfaces being at
        one temperature in the contact); None for a stationary half-plane."""
        if self.half_plane_incoming_temperature is None:
            return None
        return self.flash_temperature - self.half_plane_incoming_temperature

    @property
    def applicable(self) -> bool:
        """Whether the theory applies (:mod:`thermocontact.analysis.applicability`)."""
        return bool(self.applicability is not None and self.applicability.applicable)


@dataclass(frozen=True)
class PhysicalContact:
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
        Why there is no valid branch, when there is none.
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


def _scan_range(prob: PhysicalProblem):
    dh = prob.hertz_half_width
    beta = prob.fhpe(1.0)  # fHPe per metre of half-width
    hi = MAX_WIDTH * dh
    lo = 0.5 * min(dh, FHPE_MIN / beta)
    if not (np.isfinite(lo) and np.isfinite(hi) and 0.0 < lo < hi):
        raise InputError(
            f"the inputs put the contact scale out of range (Hertz half-width {dh:.3g} m, "
            f"fHPe per metre {beta:.3g}): check radius, load, speed, friction and materials")
    return lo, hi


def _cylinder_temperature(prob: PhysicalProblem, sol: ContactSolution, s):
    """The cylinder's surface temperature rise at ``s`` (derivation D8)."""
    return _moving_temperature(prob, sol, s, body=1)


def _moving_temperature(prob: PhysicalProblem, sol: ContactSolution, s, body):
    """A moving body's surface temperature rise over its own incoming temperature at
    ``s``: Carslaw and Jaeger's (D8) over the heat it receives, with its own signed
    kernel scale (the cylinder's ``c``, the half-plane's ``c2``; section 5b)."""
    par = sol.parameters
    c = par.cylinder_scale if body == 1 else par.half_plane_scale
    K = prob.cylinder.K if body == 1 else prob.half_plane.K
    sign = 1.0 if body == 1 else -1.0
    # q1, q2 = ((1 +- eta) p +- q')/2, in units f |v1 - v2| P / Delta.
    ib, iq = sol.representation.integrate(lambda u: cylinder_temperature(c * u), s)
    return (prob.friction * prob.sliding_speed * prob.load / (np.pi * K) * 0.5
            * ((1 + sign * par.eta) * (ib @ sol.phi) + sign * (iq @ sol.psi)))


def _temperatures(prob: PhysicalProblem, sol: ContactSolution, half_width, s):
    """Surface temperature rises of both bodies over the contact (derivation D8, D12),
    the half-plane's level set by continuity with the cylinder in the contact.

    Returns
    -------
    t1, t2 : ndarray
    mismatch : float
        The largest departure of ``t1 - t2`` from its mean over the contact (zero
        for the exact solution: perfect thermal contact).
    incoming : float or None
        For a moving half-plane, its incoming temperature over the cylinder's that the
        heat partition implies (each moving body's rise is over its own incoming
        temperature; section 5b); None for a stationary half-plane, whose level the
        2-D model leaves free.
    """
    rep = sol.representation
    eta = sol.parameters.eta
    t1 = _cylinder_temperature(prob, sol, s)
    if sol.parameters.half_plane_scale:
        t2 = _moving_temperature(prob, sol, s, body=2)
    else:
        # q2 = ((1 - eta) p - q')/2, in units f |v1 - v2| P / Delta.
        lb, lq = rep.integrate(lambda u: np.log(np.abs(u)), s)
        t2 = (-prob.friction * prob.sliding_speed * prob.load / (np.pi * prob.half_plane.K)
              * 0.5 * ((1 - eta) * (lb @ sol.phi) - lq @ sol.psi))
    shift = float(np.mean(t1 - t2))
    t2 = t2 + shift
    return (t1, t2, float(np.max(np.abs(t1 - t2))),
            shift if sol.parameters.half_plane_scale else None)


def _branch(prob: PhysicalProblem, pe, n, tol, estimate) -> Branch:
    """The fields of the solution at ``Pe`` with ``n`` unknowns, whose error estimate
    is ``estimate`` (:func:`~.ray.root`)."""
    half_width = prob.half_width(pe)
    est = estimate
    # The F = 0 path has one exact level (P_H/P = 1 at any n): no error.
    est = 0.0 if prob.friction == 0.0 or prob.fhpe(1.0) == 0.0 else est
    sol = prob.ray().solve_at(pe, n, check_validity=True).replace(error_estimate=est, tol=tol)
    s = np.cos(np.linspace(np.pi, 0.0, 201))
    p = prob.load / half_width * sol.pressure_at(s)
    s_in = s[1:-1]
    t1, t2, mismatch, incoming = _temperatures(prob, sol, half_width, s_in)
    # Peak pressure and flash temperature: the maxima of the closed forms, not of
    # the samples (edges included for the temperature, which is finite there).
    ip = int(np.argmax(p))
    _, neg_peak = polish_minimum(lambda x: -prob.load / half_width * sol.pressure_at(x), s, -p, ip)
    s_t = np.concatenate([[-1.0], s_in, [1.0]])
    t_edges = _cylinder_temperature(prob, sol, [-1.0, 1.0])
    t_all = np.concatenate([t_edges[:1], t1, t_edges[1:]])
    it = int(np.argmax(t_all))
    _, neg_flash = polish_minimum(lambda x: -_cylinder_temperature(prob, sol, x), s_t, -t_all,
                                  it)
    offset = sol.sigma_over_delta * half_width
    lam = sol.lam
    q = prob.friction * prob.sliding_speed * prob.load
    return Branch(
        half_width=float(half_width), offset=float(offset),
        a=float(offset - half_width), b=float(offset + half_width),
        peak_pressure=float(-neg_peak), mean_pressure=prob.load / (2.0 * half_width),
        pe=float(sol.parameters.pe), fhpe=float(sol.parameters.fhpe), lam=float(lam),
        load_ratio=float(sol.load_ratio), valid=bool(sol.valid),
        flash_temperature=float(-neg_flash),
        heat_cylinder=0.5 * q * (1.0 + lam), heat_half_plane=0.5 * q * (1.0 - lam),
        temperature_mismatch=mismatch,
        half_plane_incoming_temperature=incoming,
        error_estimate=float(sol.error_estimate),
        converged=bool(sol.error_estimate <= tol),
        x=offset + half_width * s, pressure=p,
        temperature_cylinder=np.concatenate([[np.nan], t1, [np.nan]]),
        temperature_half_plane=np.concatenate([[np.nan], t2, [np.nan]]),
        solution=sol,
        applicability=applicability(
            sol, half_width / prob.radius,
            compliance_fractions=(prob.cylinder.compliance / prob.compliance,
                                  prob.half_plane.compliance / prob.compliance),
            temperature_rises=np.concatenate([t_all, t2]),
            max_temperature=(prob.cylinder.max_temperature, prob.half_plane.max_temperature)),
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
        lo, hi = _scan_range(prob)
        ray, pe_h = prob.ray(), prob.pe_hertz
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
    if message and largest is not None and np.isfinite(largest):
        message += f"; the largest load with a valid solution is {largest:.4g} N/m"
    searched = None
    if scan is not None:
        searched = (float(lo), float(hi), float(prob.fhpe(lo)), float(prob.fhpe(hi)))
        if message:
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

    ray = prob.ray()
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
        ray, pe_h = prob.ray(), prob.pe_hertz
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
            a, b = _scan_range(prob)
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
    along : {"load", "speed", "radius", "friction"}
    start, stop : float
        SI units; load, speed and radius positive, friction non-negative.
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
        check = check_nonnegative if along == "friction" else check_positive
        check(name, value)
        _moved(problem, along, value)  # validated as a problem
    fixed = {"cylinder": problem.cylinder.name, "half_plane": problem.half_plane.name,
             **{k: getattr(problem, k) for k in ("radius", "load", "speed", "friction", "lam")
                if k != along}}
    if problem.speed2:
        fixed["speed_ratio"] = problem.speed_ratio
    fixed["dundurs"] = problem.dundurs
    return trace(_primary(problem, along), along, fixed, start, stop, tol=tol, rtol=rtol,
                 points=points, log=ALONG[along], n=n, event_rtol=event_rtol,
                 progress=progress)
