"""The ray of a physical problem: every trial half-width of one pair of materials.

For one pair of materials, one friction coefficient and one heat partition, a trial
half-width ``Delta`` fixes ``Pe = v Delta/(2 k2)`` and ``fHPe = f H Pe``, the ratios
being the materials': every dimensionless problem lies on the *ray*
``Pe -> (Pe, f H Pe)``.  A load ``P`` is carried where (derivation section 11b, D26)

    Pe^2 = Pe_H^2 L(Pe),    Pe_H = v Delta_H/(2 k2),    L = P_H/P,

so load, radius and speed enter only through ``Pe_H``.  :func:`follow` traces ``L``
along the ray by continuation in ``ln Pe`` with step control;
:func:`interpolated_roots` finds the roots of D26 on a local interpolant of samples;
:func:`root` refines one root on the solver itself.  ``thermocontact contact``
(one ``Pe_H``) and the operating maps (every ``Pe_H`` of a plane) share them.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..discretisation.methods import DEFAULT_METHOD, METHODS
from ..io.results import FieldResult
from ..numerics.interpolation import lagrange, local
from ..numerics.continuation import REJECT, locate, march, secant, sign_changes
from ..problem.parameters import SolveError
from ..problem.closure import Temperatures
from ..solvers.refinement import (N_RANGE, QUANTITIES, QUANTITIES_WITH_LAM, Refinement,
                                  refine)
from ..solvers.single_patch import DEFAULT_TOL, Model

__all__ = ["FIELD_P_MAX", "FIELD_QUANTITIES", "FIELD_TOL_FACTOR", "FieldLevel", "Ray",
           "RayScan", "follow", "interpolated_roots", "refine_fields", "root",
           "start_of_root"]

#: Unknowns per function of the continuation: enough to bracket the roots of D26,
#: which :func:`root` then refines at the resolution that meets the error target.
SCAN_N = 16
#: Steps of the continuation in ln Pe: the first, the largest and the smallest.
STEP_FIRST = math.log(10.0) / 4
STEP_MAX = math.log(10.0) / 2
STEP_MIN = math.log(10.0) / 256
#: A step is accepted when the quadratic extrapolation of the last three samples
#: predicts ``L`` to this fraction of ``max(1, |L|)``, or (following one load) to
#: SIGN_MARGIN of the distance ``|L - (Pe/Pe_H)^2|`` from a root of D26.
PREDICTOR_TOL = 0.02
SIGN_MARGIN = 0.25
#: Points per step where the parabola of ``L`` is checked for hidden roots.
SUBSTEPS = 16
#: The fields' error target over the solution's: a contact's fields (the peak
#: pressure, the flash temperature, the slope factors and the strain's pressure) are
#: local values and converge more slowly in ``n`` than ``P_H/P`` and ``sigma/Delta``
#: (at n = 32, 6e-5 against 2e-9 on the brake block's ray), so they are refined on
#: their own to ``FIELD_TOL_FACTOR tol``.
FIELD_TOL_FACTOR = 10.0
#: The fields' quantities (:class:`FieldLevel`'s attributes) and the largest order
#: their Richardson estimate believes: measured, their errors fall by factors of 6 to
#: 24 per doubling of ``n`` (orders 2.6 to 4.6), irregularly (a factor of 4 once), so
#: an order of at most 2 keeps the estimate above the error.
FIELD_QUANTITIES = ("peak_pressure", "flash_temperature", "slope_cylinder",
                    "slope_half_plane", "strain_pressure")
FIELD_P_MAX = 2.0


@dataclass(frozen=True)
class Ray:
    """The dimensionless problems of one material pair, friction and heat partition.

    Attributes
    ----------
    K2_over_K1, k2_over_k1, delta1_over_delta2 : float
        The materials' ratios.
    fh : float
        ``f H``, the ray's slope ``fHPe/Pe``.
    lam : float
        Heat partition.
    method : str
    speed_ratio : float
        ``R = v2/v1`` (0: a stationary half-plane); ``fh`` is then
        ``f H |1 - R|``.
    beta_f : float
        ``B = beta f`` of the Dundurs term (section 5c).
    theta, sink_pe : float or None
        The far temperatures instead of ``lam`` (None; section 17): ``Theta`` (D39),
        the same at every trial half-width of one load, and a stationary half-plane's
        sink distance as ``v1 L/(2 k2)``, so that ``L/Delta = sink_pe/Pe``.
    """

    K2_over_K1: float
    k2_over_k1: float
    delta1_over_delta2: float
    fh: float
    lam: float
    method: str = DEFAULT_METHOD
    speed_ratio: float = 0.0
    beta_f: float = 0.0
    theta: float | None = None
    sink_pe: float | None = None

    def model(self, pe, tol=DEFAULT_TOL, n=None) -> Model:
        """The :class:`Model` at ``Pe``."""
        return Model(pe, self.K2_over_K1, k2_over_k1=self.k2_over_k1,
                     delta1_over_delta2=self.delta1_over_delta2,
                     speed_ratio=self.speed_ratio, beta_f=self.beta_f, method=self.method, n=n,
                     tol=tol)

    def solve_at(self, pe, n, check_validity=False, polish=True):
        """The solution at ``Pe`` with ``n`` unknowns per function."""
        return self.model(pe).solve_at(n, self.fh * pe, lam=self.lam,
                                       check_validity=check_validity, polish=polish,
                                       temperatures=self.temperatures(pe))

    def temperatures(self, pe):
        """The far temperatures at ``Pe`` (None with ``lam`` given)."""
        if self.theta is None:
            return None
        return Temperatures(self.theta, None if self.sink_pe is None else self.sink_pe / pe)

    def load_ratio(self, pe, n) -> float:
        """``L = P_H/P`` at ``Pe`` (0 where the closure is singular, ``L = 0`` exactly)."""
        try:
            return float(self.solve_at(pe, n).load_ratio)
        except SolveError:
            return 0.0


@dataclass(frozen=True, eq=False, repr=False)
class RayScan(FieldResult):
    """``L`` along the ray, from :func:`follow` (a result, :mod:`thermocontact.io.results`:
    its dataset holds ``load_ratio`` over ``pe``).

    Attributes
    ----------
    pe, load_ratio : ndarray
        The accepted samples, increasing in ``Pe``.
    n : int
        Unknowns per function of every sample.
    evaluations : int
        Solves made, rejected steps included.
    """

    pe: np.ndarray
    load_ratio: np.ndarray
    n: int
    evaluations: int
    _coordinate = "pe"

    def _summary(self) -> str:
        return (f"Pe {self.pe[0]:.4g} to {self.pe[-1]:.4g}, {self.pe.size} samples, "
                f"n={self.n}, evaluations={self.evaluations}")


@dataclass(frozen=True)
class FieldLevel:
    """A solution and its fields (:func:`~thermocontact.analysis.fields.contact_fields`)
    at one ``n``: a level of :func:`refine_fields`, its :data:`FIELD_QUANTITIES` as
    attributes."""

    solution: object
    fields: object

    @property
    def peak_pressure(self) -> float:
        return self.fields.peak_pressure

    @property
    def flash_temperature(self) -> float:
        return self.fields.flash_temperature

    @property
    def slope_cylinder(self) -> float:
        return self.fields.slope_factors[0]

    @property
    def slope_half_plane(self) -> float:
        return self.fields.slope_factors[1]

    @property
    def strain_pressure(self) -> float:
        return self.fields.strain_pressure


def refine_fields(solve_at, n, fields_of, tol, n_max=None, method=DEFAULT_METHOD) -> Refinement:
    """A solution's fields to ``FIELD_TOL_FACTOR tol``: from ``n`` (where ``P_H/P``
    met ``tol``) and ``n/2``, ``n`` doubled until the Richardson estimate of every
    field of :data:`FIELD_QUANTITIES` (relative, orders up to :data:`FIELD_P_MAX`)
    meets the target, or up to the method's largest automatic ``n``.

    Parameters
    ----------
    solve_at : callable
        ``solve_at(m)``: the solution with ``m`` unknowns per function.
    n : int
    fields_of : callable
        ``fields_of(solution)``: its :class:`~thermocontact.analysis.fields.ContactFields`.
    tol : float
        The solution's error target.
    n_max : int, optional
        Default: the method's automatic range's end.

    Returns
    -------
    Refinement
        Its levels' finest (one :class:`FieldLevel`) holds the solution and fields
        reported; ``estimate`` is the fields' (None where ``n`` has no coarser level).
    """
    n_max = max(int(n), METHODS[method].auto_range[1] if n_max is None else int(n_max))
    sizes = [m for m in (int(n) // 2, int(n)) if m >= N_RANGE[0]]

    def at(m):
        sol = solve_at(m)
        return (FieldLevel(sol, fields_of(sol)),)
    return refine(at, sizes, tol=FIELD_TOL_FACTOR * tol, n_max=n_max, p_max=FIELD_P_MAX,
                  quantities=FIELD_QUANTITIES)


def follow(ray: Ray, pe_lo, pe_hi, n=SCAN_N, pe_h=None, progress=None) -> RayScan:
    """Trace ``L`` from ``pe_lo`` to ``pe_hi`` by continuation in ``ln Pe``.

    Each step is predicted by the quadratic through the last three samples; it is
    accepted when the solve agrees to ``PREDICTOR_TOL max(1, |L|)`` (or, given
    ``pe_h``, to ``SIGN_MARGIN |L - (Pe/Pe_H)^2|``: far from a root of D26 only the
    sign of that difference matters) and then grows (by at most 2, as the error's
    cube root: the predictor is third order), and is halved otherwise, between
    :data:`STEP_MIN` and :data:`STEP_MAX`
    (:func:`~thermocontact.numerics.continuation.march`).  Given ``pe_h``, a step is halved too
    where ``h = L - (Pe/Pe_H)^2``, with ``L`` on the parabola through the last two
    samples and the new one, changes sign more than once inside it, so that pairs of
    roots (near a fold of the load) do not hide in one step.  Near a pole of ``L`` (past fHPe ~ 2)
    the step falls to its smallest and the pole is crossed.

    Parameters
    ----------
    ray : Ray
    pe_lo, pe_hi : float
        ``0 < pe_lo < pe_hi``.
    n : int
    pe_h : float, optional
        Follow for the one load of this ``Pe_H``.
    progress : callable, optional
        ``progress(done, 100)``: the percentage of ``ln Pe`` covered.

    Returns
    -------
    RayScan
    """
    x_lo, x_hi = math.log(pe_lo), math.log(pe_hi)
    xs, fs = [x_lo], [ray.load_ratio(pe_lo, n)]
    evaluations = 1

    def attempt(_, x, at_smallest):
        nonlocal evaluations
        f = ray.load_ratio(math.exp(x), n)
        evaluations += 1
        if pe_h is not None and len(xs) >= 2 and not at_smallest:
            # Between the samples, h = L - (Pe/Pe_H)^2 with L on the parabola through
            # the last two samples and this one (the term (Pe/Pe_H)^2 is exact): more
            # than one sign change of it inside the step, two roots could hide there.
            u = np.linspace(xs[-1], x, SUBSTEPS + 1)
            h = lagrange(xs[-2:] + [x], fs[-2:] + [f], u) - np.exp(2 * u) / pe_h**2
            if np.count_nonzero(np.diff(np.sign(h)) != 0) > 1:
                return REJECT
        growth = 1.0
        if len(xs) >= 3:
            predicted = float(lagrange(xs[-3:], fs[-3:], x))
            allowed = PREDICTOR_TOL * max(1.0, abs(f))
            if pe_h is not None:
                allowed = max(allowed, SIGN_MARGIN * abs(f - math.exp(2 * x) / pe_h**2))
            error = abs(f - predicted) / allowed
            if error > 1.0 and not at_smallest:
                return REJECT
            growth = min(2.0, 0.9 / max(error, 1e-3) ** (1 / 3))
        xs.append(x)
        fs.append(f)
        if progress is not None:
            progress(round(100 * (x - x_lo) / (x_hi - x_lo)), 100)
        return growth

    march(attempt, x_lo, x_hi, step=STEP_FIRST, smallest=STEP_MIN, largest=STEP_MAX)
    return RayScan(np.exp(xs), np.array(fs), n, evaluations)


def brackets(pe, load_ratio, pe_h):
    """Indices ``i`` where ``Pe^2 - Pe_H^2 L`` changes sign between samples ``i`` and
    ``i + 1`` (both finite)."""
    return sign_changes(np.asarray(pe) ** 2 - pe_h**2 * np.asarray(load_ratio))


def interpolated_roots(pe, load_ratio, pe_h):
    """The roots ``ln Pe`` of D26 on the local interpolants of the samples (those
    with :data:`~thermocontact.numerics.interpolation.STENCIL` finite samples around
    them)."""
    lp = np.log(pe)
    L = np.asarray(load_ratio)
    ok = np.isfinite(L)
    roots = []
    for i in brackets(pe, L, pe_h):
        if not np.all(ok[max(i - 3, 0):i + 4]):
            continue

        def h(x):
            return pe_h**2 * local(lp, L, x) - math.exp(2 * x)
        roots.append(locate(h, lp[i], lp[i + 1], xtol=1e-14))
    return roots


def start_of_root(scan: RayScan, pe_h, i):
    """``(ln Pe, slope of h)`` at the root of D26 on the local interpolant of the
    samples ``i`` and ``i + 1`` of ``scan`` (secant steps from linear interpolation)."""
    lp = np.log(scan.pe)
    a, b = float(lp[i]), float(lp[i + 1])

    def interpolant(x):
        return math.exp(2 * x) / pe_h**2 - local(lp, scan.load_ratio, x)

    ha, hb = interpolant(a), interpolant(b)
    x0, slope = a - ha * (b - a) / (hb - ha), (hb - ha) / (b - a)
    return secant(interpolant, x0, slope, a, b) or (x0, slope)


def root(ray: Ray, pe_h, scan: RayScan, i, tol, pole_tol=1e-6):
    """The root of D26 between samples ``i`` and ``i + 1`` of ``scan``, at the
    resolution that meets ``tol``.

    At the scan's ``n``: secant steps from the root of the samples' local
    interpolant (itself found by secant steps from linear interpolation) along its
    slope (Brent's method if they leave the bracket); a sign
    change across a pole of ``L``, where ``|h|`` stays above ``pole_tol``, is no
    root.  There ``n`` doubles over the method's automatic range until the
    Richardson estimate of ``P_H/P`` and ``sigma/Delta`` meets ``tol``; at that ``n``
    secant steps converge from the first root along its slope (one or two
    assemblies), ``h = (Pe/Pe_H)^2 - L`` changing there by the discretisation error
    only.

    Returns
    -------
    (pe, n, estimate) or None
        None for a pole.  ``estimate`` is that of the levels at the first root
        (``Pe`` within the first root's error, about 1e-7 relative, of the last).
    """
    def h(x, n):
        return math.exp(2 * x) / pe_h**2 - ray.load_ratio(math.exp(x), n)

    a, b = math.log(scan.pe[i]), math.log(scan.pe[i + 1])
    x0, slope = start_of_root(scan, pe_h, i)
    # To 1e-8 only: the steps at the final n start from here along this slope.
    found = secant(lambda x: h(x, scan.n), x0, slope, a, b, xtol=1e-8)
    if found is None:
        x = locate(lambda y: h(y, scan.n), a, b, xtol=1e-12)
    else:
        x, slope = found
    if abs(h(x, scan.n)) > pole_tol:
        return None
    start, n_max = METHODS[ray.method].auto_range
    levels, estimate = refine(lambda m: (ray.solve_at(math.exp(x), m),),
                              [start, 2 * start, 4 * start], tol=tol, n_max=n_max,
                              quantities=QUANTITIES if ray.theta is None else QUANTITIES_WITH_LAM)
    fine = levels[-1][0]
    n = fine.n
    width = max(b - a, 1e-9)
    found = secant(lambda y: h(y, n), x, slope, x - width, x + width,
                    h0=math.exp(2 * x) / pe_h**2 - fine.load_ratio)
    if found is not None:
        x = found[0]
    return math.exp(x), n, (math.inf if estimate is None else estimate)
