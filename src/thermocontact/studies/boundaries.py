"""Where validity changes along any one parameter: events located to 1e-9.

A solution is followed along one of the dimensionless parameters (``fhpe``,
``pe``, ``lam``, ``sigma_over_delta``, ``K2_over_K1``, ``k2_over_k1``,
``delta1_over_delta2``, ``speed_ratio``, ``beta_f``) from ``start`` to ``stop``.  The resolution ``n`` is chosen
once, by the refinement driver at the path's ends and middle; the path is sampled
with step control (an interval is halved while a margin comes closer to zero than
its change across the interval, so that a margin that dips below zero and back
within one step is not missed), and every sign change of a margin (the load ratio,
the pressure, the gap, the edge layers; :meth:`Validity.margins
<thermocontact.analysis.validity.Validity.margins>`) is located by Brent's method on
that margin to ``rtol`` relative in the parameter.  Where solutions stop (or start)
existing, the last solved and the first failed sample are brought together by
bisection to the same tolerance (in ``asinh`` of the parameter, so that a path of any
length needs few solves) and the place is an event of its own kind, ``"solution_ends"`` or ``"solution_begins"``.
Events chain: each one's ``valid_before`` is the previous one's ``valid_after``; a
margin that changes sign where another inequality already fails is an event that
does not change validity (:attr:`Event.changes_validity`).
"""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass

import numpy as np

from ..discretisation.methods import DEFAULT_METHOD, METHODS
from ..io.results import FieldResult, Result
from ..numerics.continuation import locate, subdivide, widen
from ..problem.closure import Temperatures, check_theta
from ..problem.parameters import DISTORTIVITY_RATIO_LIMIT, SolveError
from ..problem.validation import (InputError, check_choice, check_finite, check_integer,
                                  check_range)
from ..solvers.refinement import refine
from ..problem.closure import check_closure_range
from ..solvers.single_patch import DEFAULT_TOL, Model

__all__ = ["ALONG", "Event", "Path", "SPELLINGS", "NO_SOLUTION", "check_problem", "closure",
           "estimate_events", "follow", "locate_events", "model_for", "trace", "validity_margins"]

#: The parameters a path may follow.
ALONG = ("fhpe", "pe", "lam", "sigma_over_delta", "K2_over_K1", "k2_over_k1",
         "delta1_over_delta2", "speed_ratio", "beta_f", "theta")
#: The command line's spellings of :data:`ALONG`.
SPELLINGS = {"fhpe": "fhpe", "pe": "pe", "lam": "lam", "sigma": "sigma_over_delta",
             "K2-over-K1": "K2_over_K1", "k2-over-k1": "k2_over_k1",
             "delta1-over-delta2": "delta1_over_delta2", "speed-ratio": "speed_ratio",
             "beta-f": "beta_f", "theta": "theta"}
#: Margins, each >= 0 exactly when its inequality holds.
MARGINS = ("load", "pressure", "gap", "edge")
#: The events where solutions stop, and where they start, existing along a path.
NO_SOLUTION = ("solution_ends", "solution_begins")
#: The most bisections of the interval between a solved and a failed sample.
MAX_BISECTIONS = 200
#: An event's error estimate (against n/2) is brought below this fraction of its
#: value (or of a thousandth of the path) by doubling n for the events alone, when n is
#: chosen automatically.
EVENT_RTOL = 1e-2
#: Initial samples of a path, and the most halvings of one interval.
START_POINTS = 33
MAX_HALVINGS = 5


@dataclass(frozen=True, eq=False, repr=False)
class Event(Result):
    """A sign change of a margin along a path, or where solutions stop existing.

    Attributes
    ----------
    at : float
        The parameter's value, to ``rtol`` relative.
    inequality : {"load", "pressure", "gap", "edge", "solution_ends", "solution_begins"}
        The inequality whose margin changes sign; ``"solution_ends"``
        (``"solution_begins"``): ``at`` is the last (first) point solved, to ``rtol``,
        with none just after (before) it along the path, where ``valid`` is False: the
        solver refuses there, for want of a solution or of a well-determined one (a
        system too ill-conditioned to trust, as :meth:`Model.solve
        <thermocontact.solvers.single_patch.Model.solve>` says at such a point).
    edge : {"leading", "trailing"} or None
        Where it fails (None for the load).
    valid_before, valid_after : bool
        Validity just before and just after ``at`` along the path's direction.
    position : float or None
        ``s = (x - sigma)/Delta`` where the margin is least just past the event (None
        for the load).
    error_estimate : float or None
        The event's distance from where the same margin changes sign with half the
        unknowns: the discretisation's share of its error (``at`` itself is located
        to ``rtol``).  None where it could not be bracketed at ``n/2``.
    kind : {"fold", "hopf", "grazing", "unstable", "uncertified"} or None
        From the counted eigenvalues of the steady contact at the event
        (:func:`thermocontact.studies.event_kinds.classify`); None where not asked for
        (and then left out of the record).
    """

    at: float
    inequality: str
    edge: str | None
    valid_before: bool
    valid_after: bool
    position: float | None = None
    error_estimate: float | None = None
    kind: str | None = None

    @property
    def changes_validity(self) -> bool:
        """Whether validity differs either side (False: a margin changes sign where
        another inequality already fails)."""
        return self.valid_before != self.valid_after

    def _record(self) -> dict:
        record = {**super()._record(), "changes_validity": self.changes_validity}
        if self.kind is None:
            del record["kind"]
        return record


@dataclass(frozen=True, eq=False, repr=False)
class Path(FieldResult):
    """The samples of a path and its events.

    ``n`` is that of the samples; ``event_n`` that of the events' final location
    (larger where their estimates asked for it, :data:`EVENT_RTOL`).
    ``error_estimate`` is that of the refinement that chose ``n`` (NaN where nothing
    was measured, None in the record).  The record (the command's JSON) holds the
    events, not the samples; the dataset holds ``valid`` over the samples ``x``.
    """

    along: str
    fixed: dict
    x: np.ndarray
    valid: np.ndarray
    events: tuple
    n: int
    method: str
    error_estimate: float
    event_n: int | None = None
    status: str = "solved"
    message: str = ""

    STATUSES = {
        "solved": "the path followed from start to stop, its events located; the error "
                  "estimate of its n within the target",
        "not converged": "the error estimate of the largest n tried is beyond the target",
        "no estimate": "no error estimate (nothing solved at two levels)",
        "no solution": "no point of the path has a solution"}
    SUCCESS = frozenset({"solved"})
    # Where a margin is least past an event, in the contact's half-widths; the samples
    # and the events' places are the parameter followed, in its own unit (_units).
    UNITS = {"position": "Delta"}

    def _units(self) -> dict:
        from ..problem.vocabulary import VOCABULARY

        unit = VOCABULARY.get(self.along, ("1",))[0] or "1"
        return {**self.UNITS, "x": unit, "at": unit}

    def _summary(self) -> str:
        return (f"along={self.along!r}, from {self.x[0]:g} to {self.x[-1]:g}, "
                f"events={[e.inequality for e in self.events]}, status={self.status!r}, "
                f"n={self.n}, event_n={self.event_n}")

    def _record(self) -> dict:
        return {"along": self.along, "fixed": self.fixed, "n": self.n, "method": self.method,
                "error_estimate": self.error_estimate, "event_n": self.event_n,
                "events": [e.to_dict() for e in self.events]}


def _inputs(fixed: dict, along: str, x: float) -> dict:
    kw = {**fixed, along: x}
    # The parameter followed replaces whichever closure was given (section 17's theta
    # with its sink distance among them).
    if along in ("lam", "sigma_over_delta", "theta"):
        for k in ("lam", "sigma_over_delta", "theta"):
            if k != along:
                kw.pop(k, None)
        if along != "theta":
            kw.pop("sink_distance", None)
    return kw


def model_for(kw: dict, method=DEFAULT_METHOD, tol=DEFAULT_TOL, n=None) -> Model:
    """The :class:`Model` of the inputs ``kw`` (those of ``solve``; ``fhpe`` and the
    closure are the solve's)."""
    return Model(kw["pe"], kw["K2_over_K1"], k2_over_k1=kw.get("k2_over_k1"),
                 delta1_over_delta2=kw.get("delta1_over_delta2", 1.0),
                 speed_ratio=kw.get("speed_ratio", 0.0), beta_f=kw.get("beta_f", 0.0),
                 method=method, n=n, tol=tol)


def check_problem(kw: dict, method=DEFAULT_METHOD) -> None:
    """Refuse, in one error, inputs ``kw`` (those of ``solve``) that are out of range or
    that ``method`` cannot represent (the Dundurs term's exponents), the heat partition,
    offset or far temperatures' group included."""
    METHODS[method].check(model_for(kw, method).parameters_at(kw.get("fhpe", 0.0)))
    check_closure_range(kw.get("lam"), kw.get("sigma_over_delta"))
    if "delta1_over_delta2" in kw:
        check_range("delta1_over_delta2", kw["delta1_over_delta2"], 0.0,
                    DISTORTIVITY_RATIO_LIMIT)
    if "theta" in kw:
        check_theta(kw["theta"])


def closure(kw: dict) -> dict:
    """``lam`` or ``sigma_over_delta`` of the inputs ``kw``, as given; or the far
    temperatures of ``theta`` and ``sink_distance`` (``L/Delta``; section 17)."""
    if "theta" in kw:
        return {"temperatures": Temperatures(kw["theta"], kw.get("sink_distance"))}
    return {k: kw[k] for k in ("lam", "sigma_over_delta") if k in kw}


def _solver(fixed, along, method):
    """``at(n, x)``: the solution at ``x`` with ``n`` unknowns (None where there is none)."""
    def at(n, x):
        kw = _inputs(fixed, along, x)
        try:
            return model_for(kw, method, n=n).solve_at(n, kw["fhpe"], **closure(kw))
        except (SolveError, InputError):
            return None
    return at


def validity_margins(sol) -> dict[str, float]:
    """The signed margins of the contact inequalities of one solution (None for None).

    ``load``: ``P_H/P``, and those of :meth:`Validity.margins
    <thermocontact.analysis.validity.Validity.margins>`; ``sol.valid`` holds exactly
    when all are >= 0.
    """
    return None if sol is None else {"load": sol.load_ratio, **sol.validity.margins()}


def _where(sol, inequality):
    """The position ``s`` and the edge where ``inequality`` is least (None for the load)."""
    v = sol.validity
    at = {"load": None, "pressure": v.pressure_margin_at, "gap": v.gap_margin_at,
          "edge": 1.0 if v.edge_margins[1] <= v.edge_margins[0] else -1.0}[inequality]
    return (None, None) if at is None else (float(at), "leading" if at > 0 else "trailing")


def locate_events(at, xs, sols, *, xtol, only_validity_changes=False, guesses=None):
    """Every sign change of a margin between neighbouring samples
    (:func:`~thermocontact.numerics.continuation.locate`: Brent's method).

    Parameters
    ----------
    at : callable
        ``at(x)``: the solution at ``x``; None, or a :class:`SolveError`, where there
        is none.
    xs, sols : sequences
        The samples, in the path's order, and their solutions (None allowed).
    xtol : callable
        ``xtol(a, b)``: the events' tolerance on the interval ``(a, b)``.
    only_validity_changes : bool
        Keep, per interval, only the first event, and only where the samples'
        validity differs (a figure's boundaries).
    guesses : callable, optional
        ``guesses(a, b, margin)``: a first point for Brent's method on ``(a, b)``
        (:func:`~thermocontact.numerics.continuation.locate`'s ``guess``), or None.

    Returns
    -------
    tuple of Event
    """
    events = []
    for a, b, sa, sb in zip(xs[:-1], xs[1:], sols[:-1], sols[1:]):
        ma, mb = validity_margins(sa), validity_margins(sb)
        if ma is None or mb is None or (only_validity_changes and sa.valid == sb.valid):
            continue
        found = []
        for k in MARGINS:
            if (ma[k] >= 0) == (mb[k] >= 0):
                continue
            # The margins other than the load's scale with 1/L: not continuous
            # through L = 0.
            if k != "load" and (ma["load"] <= 0 or mb["load"] <= 0):
                continue
            seen = {}  # Brent's points: x -> (solution, margin)

            def f(x, k=k, seen=seen):
                try:
                    sol = at(x)
                except SolveError:
                    sol = None
                m = validity_margins(sol)
                if m is None:
                    # Refused only where P_H/P vanishes (sigma infinite): the load
                    # margin's root itself.
                    return 0.0 if k == "load" else np.nan
                seen[x] = (sol, m[k])
                return m[k]
            try:
                root = locate(f, min(a, b), max(a, b), xtol=xtol(a, b),
                              guess=None if guesses is None else guesses(a, b, k))
            except (ValueError, RuntimeError):
                continue
            found.append((abs(root - a), root, k, seen))
        found.sort(key=lambda event: event[:3])
        # Events chain: each starts from the validity the previous one left.
        before = bool(sa.valid)
        for _, root, k, seen in found[:1] if only_validity_changes else found:
            step = 10 * xtol(a, b) * np.sign(b - a)
            past = None
            if abs(step) < abs(b - a):
                past = _just_past(seen, root, step, mb[k] >= 0)
                if past is None:
                    try:
                        past = at(root + step)
                    except SolveError:
                        past = None
            past = past if past is not None else sb
            position, edge = _where(past, k)
            events.append(Event(float(root), k, edge, before, bool(past.valid), position))
            before = bool(past.valid)
    return tuple(events)


def _just_past(seen, root, step, after):
    """The solution just past an event at ``root`` among Brent's own points ``seen``
    (``x -> (solution, margin)``): the one nearest the root, from the root itself up to
    ``step`` beyond it, whose margin has the sign it has after the event
    (``after``: ``>= 0``); None without one.  Brent's method ends with the root and a
    point on the other side of the sign change within its tolerance, so that the
    validity after the event is read without another solve."""
    near = [(abs(x - root), sol) for x, (sol, margin) in seen.items()
            if (margin >= 0) == after and 0.0 <= (x - root) * np.sign(step) <= abs(step)]
    return min(near, key=lambda pair: pair[0])[1] if near else None


def _asinh_spaced(start, stop, points):
    """``points`` samples from ``start`` to ``stop``, evenly in ``asinh x`` (the ends
    exact)."""
    t = np.linspace(np.arcsinh(start), np.arcsinh(stop), points)
    return [float(start), *map(float, np.sinh(t[1:-1])), float(stop)]


def _existence_events(at, xs, sols, xtol):
    """Where solutions stop or start existing between neighbouring samples: the solved
    and the failed sample brought within ``xtol`` of each other by bisection in
    ``asinh x`` (linear near 0, logarithmic far from it: about 40 halvings from
    1e300 to 1e-9 relative).  The bisection's solved points join ``sols``.

    Returns
    -------
    xs : list of float
        The ends of each bracket, the solved and the failed, to join the samples.
    events : list of Event
        ``"solution"`` events at the last solved points.
    """
    new, events = [], []
    for a, b in zip(xs[:-1], xs[1:]):
        if (sols[a] is None) == (sols[b] is None):
            continue
        ok, bad = (a, b) if sols[a] is not None else (b, a)
        for _ in range(MAX_BISECTIONS):
            if abs(bad - ok) <= xtol(ok, bad):
                break
            mid = float(np.sinh(0.5 * (np.arcsinh(ok) + np.arcsinh(bad))))
            if not min(ok, bad) < mid < max(ok, bad):
                break  # the floating-point numbers between them are exhausted
            try:
                sol = at(mid)
            except SolveError:
                sol = None
            if sol is None:
                bad = mid
            else:
                ok, sols[mid] = mid, sol
        # Both ends of the bracket join the samples: a second pass finds it resolved.
        sols.setdefault(bad, None)
        new += [ok, bad]
        valid = bool(sols[ok].valid)
        stops = sols[a] is not None  # solutions stop existing (else they start)
        events.append(Event(float(ok), NO_SOLUTION[0 if stops else 1], None,
                            valid if stops else False,
                            False if stops else valid))
    return new, events


def _relocated(at, event, lo, hi, xtol, within=None):
    """The sign change of the event's margin under ``at`` nearest ``event.at``
    (brackets widened by 4 from 1e-4 of ``max(|at|, 1e-3 (hi - lo))`` to a tenth of the
    path, and never past ``within``, the event's own stretch of the path), or None."""
    def f(x):
        try:
            m = validity_margins(at(x))
        except SolveError:
            m = None
        return np.nan if m is None else m[event.inequality]

    width = max(abs(event.at), 1e-3 * (hi - lo), 1e-300) * 1e-4
    a, b = (lo, hi) if within is None else within
    found = widen(f, event.at, width, a, b, factor=4.0, tries=12, largest=0.1 * (hi - lo))
    if found is None:
        return None
    try:
        return locate(f, *found, xtol=xtol(*found))
    except (ValueError, RuntimeError):
        return None


def estimate_events(at, events, n, start, stop, xtol, *, event_rtol=EVENT_RTOL, n_max=256,
                    progress=None, samples=None):
    """Each event with its error estimate, located again with more unknowns where
    that estimate asks for it.

    The estimate is the event's distance from the same margin's sign change under
    ``at(n // 2, x)``.  Where the margins converge slowly (delta1 != delta2,
    derivation section 8) it can exceed ``event_rtol`` of the event's value (or of a
    thousandth of the path): the events alone are then located again with doubled
    ``n`` (up to ``n_max``; ``event_rtol=None``: never), each new estimate being the
    move.

    Parameters
    ----------
    at : callable
        ``at(n, x)``: the solution at ``x`` with ``n`` unknowns (None where none).
    events : sequence of Event
        Located at ``n``.
    start, stop : float
        The path's ends (the events stay between them).
    xtol : callable
        The events' tolerance, as in :func:`locate_events`.
    samples : sequence of float, optional
        The samples between which the events were located: each event is then located
        again only within its own stretch of the path, from the sample after the
        previous event of the same margin to the sample before the next one, so that
        on a long path another event's sign change is never taken for it (its estimate
        is None where its margin has none there).

    Returns
    -------
    events : list of Event
        In the path's order.
    n : int
        That of their final location.
    """
    report = progress or (lambda stage, done, total: None)
    start, stop = float(start), float(stop)
    lo, hi = min(start, stop), max(start, stop)
    span = hi - lo
    grid = None if samples is None else np.unique(np.asarray(samples, dtype=float))

    def stretch(e, among):
        """From the sample after the previous event of e's margin to the sample before
        the next (the path's ends where there is none), or None without samples."""
        if grid is None:
            return None
        same = [o.at for o in among if o.inequality == e.inequality and o.at != e.at]
        below = max((x for x in same if x < e.at), default=None)
        above = min((x for x in same if x > e.at), default=None)
        a = lo if below is None else float(grid[min(np.searchsorted(grid, below, "right"),
                                                      grid.size - 1)])
        b = hi if above is None else float(grid[max(np.searchsorted(grid, above) - 1, 0)])
        # Two events of one margin between the same samples: split their interval.
        a = a if a <= e.at else 0.5 * (below + e.at)
        b = b if b >= e.at else 0.5 * (above + e.at)
        return a, b

    out = []
    for i, e in enumerate(events):
        x = _relocated(lambda y: at(n // 2, y), e, lo, hi, xtol, stretch(e, events))
        out.append(dataclasses.replace(e, error_estimate=None if x is None else abs(x - e.at)))
        report(f"events' estimates (n = {n // 2})", i + 1, len(events))

    def too_large(e):
        # An event that cannot be bracketed with fewer unknowns is not escalated.
        return (e.error_estimate is not None
                and e.error_estimate > event_rtol * max(abs(e.at), 1e-3 * span))
    while event_rtol is not None and n * 2 <= n_max and any(too_large(e) for e in out):
        n *= 2
        moved = []
        for i, e in enumerate(out):
            # All events move to the new n (so that event_n is every event's n).
            x = _relocated(lambda y: at(n, y), e, lo, hi, xtol, stretch(e, out))
            moved.append(e if x is None else dataclasses.replace(
                e, at=x, error_estimate=abs(x - e.at)))
            report(f"events located again (n = {n})", i + 1, len(out))
        out = sorted(moved, key=lambda e: e.at, reverse=stop < start)
    return out, n


def follow(fixed: dict, along: str, start, stop, *, method=DEFAULT_METHOD, tol=DEFAULT_TOL,
           rtol=1e-9, points=START_POINTS, n=None, event_rtol=EVENT_RTOL,
           progress=None) -> Path:
    """Follow a solution along one parameter and locate every change of validity.

    Parameters
    ----------
    fixed : dict
        The other inputs of :func:`~thermocontact.solvers.single_patch.solve`
        (``pe``, ``fhpe``, ``K2_over_K1``, optionally ``k2_over_k1``,
        ``delta1_over_delta2``, and ``lam`` or ``sigma_over_delta``).
    along : str
        One of :data:`ALONG`.
    start, stop : float
        The path's ends (either order).
    method : str
    tol : float
        Error target of ``P_H/P`` and ``sigma/Delta`` for the choice of ``n``.
    rtol : float
        Relative tolerance of the events in the parameter.
    points : int
        Initial samples (at least 3).
    n : int, optional
        Unknowns per function of the whole path, instead of the choice by ``tol``
        (each event's error estimate compares with ``n/2``).
    event_rtol : float
        With ``n`` chosen by ``tol``: each event is located again with doubled ``n``
        until its error estimate is below this fraction of its value.
    progress : callable, optional
        ``progress(stage, done, total)`` (:func:`trace`).

    Returns
    -------
    Path
    """
    along = check_choice("along", along, ALONG)
    start, stop = check_finite("start", start), check_finite("stop", stop)
    if along == "speed_ratio" and min(start, stop) <= 1.0 <= max(start, stop) and (
            fixed.get("beta_f", 0.0) or fixed.get("fhpe", 0.0)):
        # Pure rolling makes no frictional heat, and the friction (with the Dundurs
        # term) reverses there: with either, R = 1 is no point of the path, at an end
        # or inside it alike (without them the solution is continuous through it).
        raise InputError("a path along speed_ratio must not reach 1 with fhpe or beta_f "
                         "!= 0: pure rolling makes no frictional heat and reverses the "
                         "friction; follow each side of 1 on its own",
                         parameters=("start", "stop"))
    # The path's ends are problems the method accepts (every parameter's range is an
    # interval, so the ends check them all): a refusal is one error, not a failed sample.
    for x in (start, stop):
        check_problem({**fixed, along: x}, method)
    return trace(_solver(fixed, along, method), along, dict(fixed), start, stop,
                 method=method, tol=tol, rtol=rtol, points=points, n=n, event_rtol=event_rtol,
                 progress=progress)


def trace(at, along: str, fixed: dict, start, stop, *, method=DEFAULT_METHOD, tol=DEFAULT_TOL,
          rtol=1e-9, points=START_POINTS, log=False, n=None, event_rtol=EVENT_RTOL,
          progress=None) -> Path:
    """:func:`follow` on any solver: ``at(n, x)`` gives the solution at ``x`` with ``n``
    unknowns (None where there is none); ``along`` and ``fixed`` are recorded.  With
    ``log`` (both ends positive) the samples and their halvings are geometric;
    ``progress(stage, done, total)`` is told of each sample and event."""
    report = progress or (lambda stage, done, total: None)
    start, stop = check_finite("start", start), check_finite("stop", stop)
    if start == stop:
        raise InputError(f"stop must differ from start, got {stop!r} twice",
                         parameters=("start", "stop"))
    points = check_integer("points", points, 3, 10_000)
    log = bool(log and start > 0 and stop > 0)

    def middle(a, b):
        return float(np.sqrt(a * b)) if log else 0.5 * (a + b)
    # One n for the whole path, refined until the estimate meets tol at its ends and
    # middle (so that the margins vary smoothly along it).
    probes = [start, middle(start, stop), stop]
    lo, n_max = METHODS[method].auto_range
    auto = n is None
    xtol = lambda a, b: rtol * max(abs(a), abs(b), 1e-300)  # noqa: E731
    xs = list((np.geomspace if log else np.linspace)(start, stop, points))
    if auto and any(at(lo, x) is None for x in probes):
        # n is chosen where solutions exist: the ends and middle of the solved part,
        # found with the fewest unknowns.
        coarse = {x: at(lo, x) for x in xs}
        if all(v is None for v in coarse.values()):
            xs = _asinh_spaced(start, stop, points)
            coarse = {x: at(lo, x) for x in xs}
        edges, _ = _existence_events(lambda x: at(lo, x), xs, coarse, xtol)
        solved = [x for x in sorted(set(xs) | set(edges), reverse=stop < start)
                  if coarse[x] is not None]
        if solved:
            probes = [solved[0], middle(solved[0], solved[-1]), solved[-1]]
    if n is None:
        levels, est = refine(lambda m: tuple(at(m, x) for x in probes), [lo, 2 * lo, 4 * lo],
                             tol=tol, n_max=n_max, p_max=METHODS[method].order_cap)
        n = lo * 2 ** (len(levels) - 1)
    else:
        n = check_integer("n", n, 8, 1024)
        _, est = refine(lambda m: tuple(at(m, x) for x in probes), [n // 4, n // 2, n],
                        p_max=METHODS[method].order_cap)

    sols = {}
    for i, x in enumerate(xs):
        sols[x] = at(n, x)
        report("samples", i + 1, len(xs))
    if all(v is None for v in sols.values()):
        # Solutions may exist in a stretch narrower than the samples' spacing (near 0
        # of a path to 1e300): sampled again, evenly in asinh x.
        xs = _asinh_spaced(start, stop, points)
        for i, x in enumerate(xs):
            sols[x] = sols[x] if x in sols else at(n, x)
            report("samples (asinh)", i + 1, len(xs))

    def suspicious(sa, sb):
        ma, mb = validity_margins(sa), validity_margins(sb)
        if ma is None or mb is None:
            return False
        return any(min(abs(ma[k]), abs(mb[k])) < abs(ma[k] - mb[k]) for k in MARGINS)

    # Where solutions stop existing is resolved first, so that the margins' sign
    # changes next to it are bracketed by solved samples.
    edges, existence = _existence_events(lambda x: at(n, x), xs, sols, xtol)
    xs = sorted(set(xs) | set(edges), reverse=stop < start)
    # The interval from an edge to its solved neighbour may span many decades (a path
    # to 1e300): sampled again, evenly in asinh x, so that the events in it are
    # bracketed to their own scale.
    for edge in [x for x in edges if sols[x] is not None]:
        i = xs.index(edge)
        for other in [xs[j] for j in (i - 1, i + 1)
                      if 0 <= j < len(xs) and sols[xs[j]] is not None]:
            for t in np.linspace(np.arcsinh(other), np.arcsinh(edge), points)[1:-1]:
                x = float(np.sinh(t))
                if x not in sols:
                    sols[x] = at(n, x)
                    xs.append(x)
    xs = sorted(set(xs), reverse=stop < start)
    xs = subdivide(xs, sols, lambda x: at(n, x), suspicious, middle, times=MAX_HALVINGS,
                   reverse=stop < start,
                   progress=lambda done, total: report("samples halved", done, total))
    # Again for a halving that failed (the brackets resolved above give the same events).
    edges, more = _existence_events(lambda x: at(n, x), xs, sols, xtol)
    xs = sorted(set(xs) | set(edges), reverse=stop < start)
    existence = list({e.at: e for e in [*existence, *more]}.values())

    events = locate_events(lambda x: at(n, x), xs, [sols[x] for x in xs], xtol=xtol)
    # The events' brackets are widened within the solved part of the path.
    solved = [x for x in xs if sols[x] is not None] or [start, stop]
    events, event_n = estimate_events(at, events, n, solved[0], solved[-1], xtol,
                                      event_rtol=event_rtol if auto else None, n_max=n_max,
                                      progress=report, samples=xs)
    # The solution events are located at n alone (no margin to compare at n/2).
    events = sorted([*events, *existence], key=lambda e: e.at, reverse=stop < start)
    xs_arr = np.array(xs)
    valid = np.array([bool(sols[x] is not None and sols[x].valid) for x in xs])
    status, message = _path_status(sols, events, est, tol if auto else None, n)
    return Path(along, fixed, xs_arr, valid, tuple(events), n, method,
                float(est) if est is not None else float("nan"), event_n, status, message)


def _path_status(sols, events, est, tol, n):
    """The status and message of a path (:attr:`Path.STATUSES`)."""
    found = f"{len(events)} event{'s' * (len(events) != 1)} located"
    if all(v is None for v in sols.values()):
        return "no solution", "no point of the path has a solution"
    if est is None:
        return "no estimate", f"{found}; no error estimate at n = {n}"
    if tol is None or est <= tol:
        return "solved", (f"{found}; error estimate {est:.1e}"
                          + ("" if tol is None else f" <= target {tol:.0e}") + f" at n = {n}")
    return "not converged", f"{found}; error estimate {est:.1e} > target {tol:.0e} at n = {n}"
