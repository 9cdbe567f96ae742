"""Which contact set carries a load: from Hertz's zone, followed in fHPe (section 14c).

At ``fHPe_l = 0`` the contact set is Hertz's zone ``[-1, 1]``.  It is followed with
step control in ``fHPe_l`` at fixed ``Pe_l``, every inequality checked at every
step.  Where one fails, the event is located on the least margin and the contact sets
that the failure suggests are tried at the target: a zone where the gap closed
(nucleation), the zone split where the pressure vanished, and the second method's
contact set (:mod:`thermocontact.solvers.elements`).  The answer is the first
valid set, or the evidence that none of them is.

Every closure of the single patch closes the contact set: the heat partition ``lam``
(over the single patch's range, a formal continuation beyond [-1, 1] included) or the
far temperatures (section 17) held along the path; the offset, which closes one zone
only and has no Hertzian start (at ``fHPe_l = 0`` it leaves ``lam`` undetermined),
by Newton's method on the zone's half-width at the point itself.  Time is bounded by
a budget of evaluations, each one telling the progress.
"""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass, field, replace

import numpy as np

from ..analysis.applicability import Applicability, physical_applicability
from ..analysis.fields import ContactFields, contact_fields
from ..discretisation.system import check_temperatures
from ..io.results import Result
from ..numerics.continuation import REJECT, STOP, arclength, locate, march
from ..problem.parameters import (C_MAX, C_MIN, DISTORTIVITY_RATIO_MAX, SolveError,
                                  check_moving_half_plane)
from ..problem.validation import InputError, check_exactly_one, check_positive, check_range
from ..solvers.elements import solve_elements
from ..problem.closure import check_closure_range
from ..problem.conductance import PhysicalConductance
from ..solvers.zones import FHPE_HERTZ_RANGE, PE_HERTZ_RANGE, ZoneModel, ZoneSolution

__all__ = ["ContactSetResult", "PhysicalContactSet", "find_contact_set",
           "follow_contact_set", "other_starts", "physical_contact_set"]

#: Relative width to which the event of the first failing inequality is located.
EVENT_TOL = 1e-4


@dataclass(frozen=True, eq=False, repr=False)
class ContactSetResult(Result):
    """The answer for one load: a contact set, or why there is none.

    A result (:mod:`thermocontact.io.results`); its record is the JSON of
    ``thermocontact zones``.

    Attributes
    ----------
    status : {"solved", "no steady solution", "not converged"}
    message : str
    solution : ZoneSolution or None
        The valid contact set (``solved``), else the last one found: invalid, or at an
        earlier point of the path (``reached < 1``).
    event : dict or None
        Where the single zone followed from Hertz's first fails: ``fhpe_hertz``,
        the failing inequality and where.
    attempts : list of dict
        The other contact sets tried and what became of them.
    history : list of dict
        Every accepted step of the continuation: ``t``, ``pe_hertz``, ``fhpe_hertz``,
        ``edges``, ``valid`` (the single zone, past the event too).
    folds : list of dict
        Where the branch followed turns back (pseudo-arclength continuation,
        :func:`~thermocontact.numerics.continuation.arclength`).
    reached : float
        The path parameter of ``solution`` (1 at the point asked for).
    """

    status: str
    message: str
    solution: ZoneSolution | None
    event: dict | None = None
    attempts: list = field(default_factory=list)
    history: list = field(default_factory=list)
    folds: list = field(default_factory=list)
    reached: float = 1.0

    STATUSES = {"solved": "the contact set at the point asked for, valid or not (valid says)",
                "no steady solution": "the branch followed from Hertz's zone folds back, and "
                                      "no other contact set tried holds: none exists there",
                "not converged": "the path stopped short of the point asked for (its steps, "
                                 "or the budget of evaluations, ran out); the last contact "
                                 "set followed is kept"}
    SUCCESS = frozenset({"solved"})
    # Lengths in Hertz's half-width l of the load, loads in units of the load P.
    UNITS = {"a": "l", "b": "l", "centre": "l", "half_width": "l", "load": "P",
             "peak_pressure": "P/l", "pe_hertz": "1", "fhpe_hertz": "1"}

    @property
    def answer(self) -> ZoneSolution | None:
        """The contact set at the point asked for (valid or not), or None where the
        path stopped short of it: a set found earlier on the path says nothing about
        validity there."""
        return self.solution if self.reached >= 1.0 else None

    def _summary(self) -> str:
        sol = self.answer
        zones = "None" if sol is None else ", ".join(f"[{a:.4g}, {b:.4g}]" for a, b in sol.edges)
        return (f"status={self.status!r}, zones={zones}, "
                f"valid={None if sol is None else sol.valid}, reached={self.reached:.6g}")

    def _record(self) -> dict:
        sol = self.answer
        rec = {"status": self.status, "message": self.message,
               "valid": None if sol is None else sol.valid,
               "zones": [] if sol is None else sol.zone_records(),
               "complementarity": (None if sol is None or sol.validity is None
                                   else sol.validity.to_dict()),
               "event": self.event, "attempts": self.attempts, "folds": self.folds}
        if sol is not None:
            rec["n"] = sol.n
            rec["defect"] = sol.defect
            # Given, or the output of the offset or the far temperatures.
            rec["lam"] = sol.lam
        elif self.solution is not None:
            rec["last_followed"] = {"t": self.reached,
                                    "zones": self.solution.zone_records(),
                                    "valid": self.solution.valid}
        return rec


def _point(where: dict) -> str:
    """A point of a path, ``{"pe_hertz": .., "fhpe_hertz": ..}``, for a message."""
    return f"Pe_l = {where['pe_hertz']:.6g}, fHPe_l = {where['fhpe_hertz']:.6g}"


def _first_failure(sol: ZoneSolution) -> str:
    return sol.validity.failures[0] if sol.validity.failures else "valid"


def find_contact_set(pe_hertz, fhpe_hertz, K2_over_K1, *, lam=None, k2_over_k1=None,
                     delta1_over_delta2=1.0, beta_f=0.0, conductance=None, speed_ratio=0.0,
                     n=32, progress=None, start=None, sigma_over_delta=None,
                     temperatures=None) -> ContactSetResult:
    """The contact set at ``Pe_l``, ``fHPe_l`` (units of the Hertz half-width ``l``),
    followed from Hertz's zone along ``fHPe_l`` at fixed ``Pe_l``.

    Parameters
    ----------
    pe_hertz, fhpe_hertz : float
        ``Pe_l = v l/(2 k2) > 0`` and ``fHPe_l >= 0``.
    K2_over_K1, k2_over_k1, delta1_over_delta2 : float
    lam : float
        The heat partition held, ``|lam| <= 1e6`` (as the single patch's).
    temperatures : Temperatures or (float, float or None), optional
        Or the far temperatures held, ``(Theta, L/l)`` with the sink distance in units
        of ``l`` (section 17): ``lam`` is then an output.
    sigma_over_delta : float, optional
        Or the offset ``centre/half-width`` of one zone (section 16): no path from
        Hertz's zone (at ``fHPe_l = 0`` the offset leaves ``lam`` undetermined), but
        Newton's method on the zone's half-width from Hertz's at the point itself.
        Exactly one of the three closures.
    beta_f : float, optional
        The Dundurs term (section 5c); the second method is then not tried.
    conductance : (float, float), optional
        ``(Bi0, m)``: an interface conductance ``h = h0 (p/p_ref)^m`` with
        ``Bi0 = h0 l/K2`` and ``p_ref = P/(2 l)`` (derivation section 15); default
        perfect thermal contact.  The second method is then not tried.
    speed_ratio : float, optional
        ``R = v2/v1``: the half-plane moving through the contact (default 0, the
        stationary half-plane; sections 5b and 16).  The second method is then not
        tried.
    n : int
        Unknowns per function per zone; where the path cannot be followed with them,
        followed again with twice as many (once; the message says so).
    progress : callable, optional
        ``progress(fraction)`` as the continuation advances.
    start : (float, float), optional
        The edges of one zone (units of ``l``), a valid single patch's: where
        Newton's method from them finds a valid contact set of one zone, that is
        the answer, and nothing is followed (:func:`follow_contact_set`).
    """
    check_exactly_one(lam=lam, sigma_over_delta=sigma_over_delta, temperatures=temperatures)
    # The target's own values named (a step toward it would name a fraction of it).
    pe = check_range("pe_hertz", pe_hertz, *PE_HERTZ_RANGE)
    target = check_range("fhpe_hertz", fhpe_hertz, *FHPE_HERTZ_RANGE)
    # The cylinder's kernel scale at this Peclet number (the zone model's own check
    # knows no Peclet number yet).
    k = check_positive("k2_over_k1", K2_over_K1 if k2_over_k1 is None else k2_over_k1)
    if not C_MIN <= pe * k <= C_MAX:
        raise InputError(f"pe_hertz * k2_over_k1 (the cylinder's kernel scale) must be in "
                         f"[{C_MIN:.0e}, {C_MAX:.0e}], got {pe * k:.3g} (pe_hertz = {pe:.3g}, "
                         f"k2_over_k1 = {k:.3g})", parameters=("pe_hertz", "k2_over_k1"))
    speed_ratio = check_moving_half_plane(speed_ratio, pe, target,
                                          names=("pe_hertz", "fhpe_hertz"))

    materials = dict(k2_over_k1=k2_over_k1, delta1_over_delta2=delta1_over_delta2,
                     beta_f=beta_f, conductance=conductance, speed_ratio=speed_ratio)
    if sigma_over_delta is not None:
        return _offset_contact_set(pe, target, K2_over_K1, sigma_over_delta, n=n,
                                   progress=progress, **materials)
    budgets = []

    def attempt(n_, start=None):
        # Each resolution its own budget: the finer one is not starved by the first.
        budgets.append(_Budget(MAX_EVALUATIONS))
        return follow_contact_set(lambda t: (pe, t * target), K2_over_K1, lam=lam,
                                  temperatures=temperatures, n=n_, progress=progress,
                                  start=start, budget=budgets[-1], **materials)
    res = attempt(n, start)
    # (A first attempt that spent its budget is not tried again: the path is one its
    # steps cannot resolve, at any n.)
    if res.status == "not converged" and 2 * int(n) <= 256 and budgets[0].left > 0:
        # An under-resolved zone (narrow, or at a high Peclet number) can stall the
        # continuation where a finer one passes.
        again = attempt(2 * int(n))
        return replace(again, message=f"{again.message} (with n = {2 * int(n)}: with n = "
                                      f"{int(n)}, {res.message})")
    return res


#: Largest correction of any edge's predicted position in one continuation step, in
#: half-widths of the smallest zone.
MAX_EDGE_MOVE = 0.25
#: Most steps (accepted or not) of one stretch of continuation: a path that needs more
#: (far past the boundary, at a large distortivity ratio) ends where it got to, so
#: that every contact set is answered in bounded time.
MAX_STEPS = 150
#: Most evaluations of the contact set's defects (an assembly and a linear solve each,
#: about 25 ms at n = 32 on this project's machine) for one contact set, both
#: resolutions together: a path whose steps, fractions of it, cannot resolve it (an
#: fHPe_l of 1e6, where the single zone fails near 5) ends where it got to, in bounded
#: time.  Following to fHPe_l = 10 takes about 400.
MAX_EVALUATIONS = 2000


class _BudgetSpent(Exception):
    """The evaluations a contact set is allowed are spent."""


class _Budget:
    """Evaluations left; ``tick()`` after each (the progress of a run whose steps are
    all refused still moves)."""

    def __init__(self, limit, tick=None):
        self.limit, self.left, self.tick = int(limit), int(limit), tick

    def draw(self):
        if self.left <= 0:
            raise _BudgetSpent
        self.left -= 1
        if self.tick is not None:
            self.tick()


class _Budgeted(ZoneModel):
    """A :class:`ZoneModel` whose every evaluation of the defects (in Newton's method,
    its Jacobian's differences and the arclength continuation alike) draws on a
    budget."""

    def __init__(self, budget, *args, **kwargs):
        super().__init__(*args, **kwargs)
        self._budget = budget

    def defects(self, *args, **kwargs):
        self._budget.draw()
        return super().defects(*args, **kwargs)


def follow_contact_set(path, K2_over_K1, *, lam=None, k2_over_k1=None,
                       delta1_over_delta2=1.0, beta_f=0.0, conductance=None, speed_ratio=0.0,
                       n=32, progress=None, start=None, budget=MAX_EVALUATIONS,
                       temperatures=None) -> ContactSetResult:
    """Follow the contact set along ``t -> (Pe_l, fHPe_l) = path(t)``, ``0 <= t <= 1``.

    At ``t = 0`` the contact is taken to be Hertz's zone (``fHPe_l`` small there);
    ``conductance`` may be a function of ``t`` returning ``(Bi0, m)``.  The closure
    held along the path: ``lam`` (``|lam| <= 1e6``) or the far ``temperatures``
    (``(Theta, L/l)``, section 17).  Each step
    starts from the edges extrapolated through the last two solutions; it is halved
    where Newton's method fails or an edge lands farther than
    :data:`MAX_EDGE_MOVE` of the smallest zone's half-width from that prediction (so
    that no step jumps to another branch), and grown by half where it succeeds
    (:func:`~thermocontact.numerics.continuation.march`); below 1e-4 of what remains,
    pseudo-arclength continuation passes the point or locates a fold
    (:func:`~thermocontact.numerics.continuation.arclength`).  Where an inequality
    fails, the event is located on the least margin to :data:`EVENT_TOL` by Brent's
    method (:func:`~thermocontact.numerics.continuation.locate`).  Events carry ``t``,
    ``pe_hertz`` and ``fhpe_hertz``.

    Given ``start``, the edges ``(a, b)`` of one zone at ``t = 1`` (a valid single
    patch's), Newton's method from them comes first: where it converges to a valid
    contact set of one zone, that is the answer ("solved") and nothing is followed
    (a valid one-zone set at the point is the single patch, section 16; with an
    interface conductance the single patch's edges are a start only, the set being
    that of the conductance).  Otherwise the path is followed as without.

    At most ``budget`` evaluations of the defects are made (:data:`MAX_EVALUATIONS`,
    for each resolution of :func:`find_contact_set`): where they are spent, the answer
    is "not converged", with the last solution followed and where it was, and the
    event and the contact sets tried if they were found.
    """
    check_exactly_one(lam=lam, temperatures=temperatures)
    check_range("delta1_over_delta2", delta1_over_delta2, 0.0, DISTORTIVITY_RATIO_MAX)
    if not 8 <= int(n) <= 256:
        raise InputError(f"n must be in [8, 256], got {n!r}")
    follower = _Follower(path, K2_over_K1, lam, temperatures, progress,
                         budget if isinstance(budget, _Budget) else _Budget(budget),
                         k2_over_k1=k2_over_k1, delta1_over_delta2=delta1_over_delta2,
                         beta_f=beta_f, conductance=conductance, speed_ratio=speed_ratio,
                         n=int(n))
    return follower.result(start)


class _Follower:
    """The contact set followed along a path (:func:`follow_contact_set`): the solves
    along it (:meth:`at`), the steps (:meth:`follow`, :meth:`around`), the event where
    the single zone fails (:meth:`event_of`) and the contact sets tried there
    (:meth:`tried`); what was found so far kept where the budget ends."""

    def __init__(self, path, K2_over_K1, lam, temperatures, progress, budget, **materials):
        self.path, self.K2_over_K1, self.materials = path, K2_over_K1, materials
        self.progress, self.budget = progress, budget
        # The last solution followed and its t: the answer where the budget is spent.
        self.latest = [None, 0.0]
        if progress is not None:
            budget.tick = lambda: progress(self.latest[1])
        self.model = self.model_at(0.0)
        # The closure held, checked as the solver checks it (lam's range; a sink
        # distance for a stationary half-plane, none for a moving one).
        if lam is not None:
            self.closure = {"lam": check_closure_range(lam)[0]}
        else:
            self.closure = {"temperatures": check_temperatures(self.model.base, temperatures)}
        self.history, self.folds, self.budget_steps = [], [], []
        # The event and the contact sets tried, once found: kept where the budget ends.
        self.event, self.attempts = None, []

    def model_at(self, t):
        # A conductance may change along the path (a law h = C p^m has a Biot number
        # at the mean Hertz pressure that grows with the load).
        cond = self.materials["conductance"]
        return _Budgeted(self.budget, self.K2_over_K1,
                         **{**self.materials, "conductance": cond(t) if callable(cond) else cond})

    def at(self, edges, t, polish=False, max_iter=40):
        pe, F = self.path(t)
        return self.model_at(t).solve(edges, pe, F, polish=polish, max_iter=max_iter,
                                      **self.closure)

    def where(self, t):
        pe, F = self.path(t)
        return {"t": t, "pe_hertz": pe, "fhpe_hertz": F}

    def follow(self, sol, t, to, stop_when_invalid):
        """From ``sol`` at ``t`` toward ``to`` (steps from an eighth of what remains,
        halved on failure, grown by half on success); stops at the first invalid
        solution if asked.  Returns the last solution, its t, and the t where it
        failed."""
        last = None  # the previous (t, edges), for the secant predictor
        failed_at = None
        steps = 0

        def attempt(t, trial, _):
            nonlocal sol, last, failed_at, steps
            steps += 1
            if steps > MAX_STEPS:
                self.budget_steps.append(self.where(t))
                return STOP
            guess = sol.edges
            if last is not None and last[1].shape == sol.edges.shape:
                guess = sol.edges + (trial - t) / (t - last[0]) * (sol.edges - last[1])
            try:
                # From the predicted edges a step converges in a few Newton steps, or
                # is too long; the correction, not the move, is limited (a zone may
                # travel many of its widths along a path).
                new = self.at(guess, trial, max_iter=12)
            except SolveError:
                return REJECT
            if new.zones != sol.zones or float(np.max(np.abs(new.edges - guess))) > (
                    MAX_EDGE_MOVE * float(np.min(sol.half_widths))):
                return REJECT
            if stop_when_invalid and not new.valid:
                failed_at = trial
                return STOP
            last = (t, sol.edges)
            sol = new
            self.latest[:] = [sol, trial]
            self.history.append(dict(self.where(trial), edges=sol.edges.ravel().tolist(),
                                     valid=bool(sol.valid)))
            if self.progress is not None:
                self.progress(trial)
            return 1.5

        def stalled(t):
            # Natural steps stall: round the point by pseudo-arclength, which passes it
            # or finds the branch turning back (a fold).
            nonlocal sol, last
            outcome, z = self.around(sol, t, min(to, t + 0.02 * (to - t)))
            if outcome == "passed":
                try:
                    sol = self.at(z[:-1].reshape(-1, 2), z[-1])
                except SolveError:
                    return None
                last = None
                self.latest[:] = [sol, float(z[-1])]
                return float(z[-1])
            if outcome == "fold":
                self.folds.append(dict(self.where(float(z[-1])), edges=z[:-1].tolist()))
            return None

        t = march(attempt, t, to, step=lambda t: (to - t) / 8.0,
                  smallest=lambda t: 1e-4 * (to - t), stalled=stalled)
        return sol, t, failed_at

    def around(self, sol, t, until):
        """Pseudo-arclength from ``sol`` at ``t``: ``("passed" | "fold" | ..., z)``."""
        def residual(z):
            pe, F = self.path(z[-1])
            return self.model_at(z[-1]).defects(z[:-1], pe, F, **self.closure)[0]

        def jacobian(z, F0):
            pe, F = self.path(z[-1])
            h = 1e-7 * max(1.0, abs(z[-1]))
            return np.column_stack([self.model_at(z[-1]).jacobian(z[:-1], pe, F, defects=F0,
                                                                  **self.closure),
                                    (residual(np.append(z[:-1], z[-1] + h)) - F0) / h])
        try:
            return arclength(residual, jacobian, np.append(sol.edges.ravel(), t),
                             until=until, ds=0.02 * float(np.min(sol.half_widths)))
        except (SolveError, InputError, np.linalg.LinAlgError):
            return "failed", None

    def result(self, start) -> ContactSetResult:
        """The answer; where the budget of evaluations ends, what was found so far."""
        try:
            return self.followed(start)
        except _BudgetSpent:
            sol, reached = self.latest
            return ContactSetResult(
                "not converged", f"stopped after {self.budget.limit} evaluations of the "
                f"contact set's defects, the most allowed, with the single zone followed to "
                f"{_point(self.where(reached))}", sol, self.event, self.attempts,
                history=self.history, folds=self.folds, reached=reached)

    def followed(self, start) -> ContactSetResult:
        """Newton's method from ``start`` (a valid single patch's edges) first; else the
        single zone followed from Hertz's, and past the event where it fails the other
        contact sets tried."""
        if start is not None:
            try:
                found = self.at(np.asarray(start, dtype=float).reshape(1, 2), 1.0, polish=True)
            except (SolveError, InputError):
                found = None
            if found is not None and found.zones == 1 and found.valid:
                return ContactSetResult("solved", "one zone, by Newton's method from the valid "
                                        "single patch's edges", found)
        self.latest[0] = self.at(np.array([[-1.0, 1.0]]), 0.0)
        sol, t, failed_at = self.follow(self.latest[0], 0.0, 1.0, True)
        if failed_at is None and t < 1.0:
            return self.stopped(sol, t)
        if failed_at is None:
            final = self.at(sol.edges, 1.0, polish=True)
            if final.valid:
                return ContactSetResult("solved", "one zone, followed from Hertz's", final,
                                        history=self.history)
            failed_at = 1.0
        lo_sol, bad, hi = self.event_of(sol, t, failed_at)
        # The single zone itself at the end (followed on past the event).
        single, reached, _ = self.follow(bad, hi, 1.0, False)
        single = self.at(single.edges, reached, polish=True)
        if reached < 1.0:
            self.event["single_zone_followed_to"] = self.where(reached)
        return self.tried(single, reached, hi)

    def stopped(self, sol, t) -> ContactSetResult:
        """The single zone followed short of the point, and why."""
        history, where = self.history, self.where
        if self.budget_steps:
            return ContactSetResult(
                "not converged", f"the single zone was followed to {_point(where(t))} in "
                f"{MAX_STEPS} steps, the most allowed, and no further", sol,
                history=history, reached=t)
        if self.folds:
            return ContactSetResult(
                "no steady solution", f"the single zone's branch folds back at "
                f"{_point(self.folds[-1])}: beyond it, along this path, it has no "
                f"continuation", sol, history=history, folds=self.folds, reached=t)
        return ContactSetResult(
            "not converged", f"the single zone could not be followed past "
            f"{_point(where(t))} (Newton's method fails, or jumps, for every step)", sol,
            history=history, reached=t)

    def event_of(self, sol, t, failed_at):
        """The event between the last valid ``t`` and the first invalid one, located on
        the least margin (continuous where the verdict changes, sections 7-8; >= 0
        exactly where valid), each solve starting from the valid solution nearest it:
        the solutions either side and the event's ``t``."""
        solved = {t: sol}

        def margin(t_):
            if t_ not in solved:
                start = max((x for x in solved if solved[x].valid), default=t)
                solved[t_] = self.at(solved[start].edges, t_)
            return min(solved[t_].validity.margins().values())
        try:
            lo, hi = locate(margin, t, failed_at, xtol=EVENT_TOL * 1e-9, rtol=EVENT_TOL,
                            bracket=True, interrupt=(SolveError,))
        except ValueError:  # no sign change between the ends: the event at the invalid one
            lo, hi = t, failed_at
        lo_sol = solved[lo]
        bad = self.at(lo_sol.edges, hi, polish=True)
        self.event = dict(self.where(hi), failure=_first_failure(bad),
                          edges=bad.edges.ravel().tolist())
        # The history passes the event where it was located.
        for s_ev, t_ev in ((lo_sol, lo), (bad, hi)):
            self.history.append(dict(self.where(t_ev), edges=s_ev.edges.ravel().tolist(),
                                     valid=bool(s_ev.valid)))
        return lo_sol, bad, hi

    def tried(self, single, reached, hi) -> ContactSetResult:
        """The contact sets the failed single zone suggests, and the second method's,
        tried at ``reached``: the first valid one, or why there is none."""
        event, attempts, where = self.event, self.attempts, self.where
        guesses = _suggested_sets(single)
        (a, b), = single.edges
        h = 0.5 * (b - a)
        try:
            if (self.materials["beta_f"] or self.materials["conductance"] is not None
                    or self.materials["speed_ratio"]):
                raise SolveError("not tried: the second method has neither the Dundurs term "
                                 "nor a moving half-plane nor a conductance")
            pe, F = self.path(reached)
            # (With the temperatures, at the single zone's partition: its contact set
            # is a start for Newton's method, which then holds the temperatures.)
            el = solve_elements(self.model.parameters(pe, F), single.lam,
                                domain=(a - 1.5 * h, b + 1.5 * h), elements=400)
            guesses.append(("the second method's contact set", el.zones.tolist()))
            attempts.append({"tried": "second method (400 elements)",
                             "zones": el.zones.ravel().tolist(), "chatter": el.chatter})
        except SolveError as exc:
            attempts.append({"tried": "second method (400 elements)", "result": str(exc)})
        for name, guess in guesses:
            try:
                # A contact set that holds converges in a few steps from these guesses.
                s2 = self.at(np.array(guess, dtype=float), reached, polish=True, max_iter=15)
            except (SolveError, InputError) as exc:
                attempts.append({"tried": name, "from": np.ravel(guess).tolist(),
                                 "result": f"no convergence ({exc})"})
                continue
            attempts.append({"tried": name, "from": np.ravel(guess).tolist(),
                             "edges": s2.edges.ravel().tolist(),
                             "loads": s2.loads.tolist(),
                             "result": s2.validity.reason})
            if s2.valid:
                status = "solved" if reached >= 1.0 else "not converged"
                return ContactSetResult(
                    status, f"{s2.zones} zones ({name}) at {_point(where(reached))}; the single "
                    f"zone fails beyond {_point(where(hi))}", s2, event, attempts,
                    self.history, self.folds, reached)
        end = where(reached)
        return ContactSetResult(
            "no steady solution",
            f"the single zone followed from Hertz's fails beyond fHPe_l = "
            f"{event['fhpe_hertz']:.6g} (Pe_l = {event['pe_hertz']:.6g}; "
            f"{event['failure']}), and none of the {len(guesses)} other contact sets tried "
            f"is valid at fHPe_l = {end['fhpe_hertz']:.6g} (see attempts)"
            + ("" if reached >= 1.0 else "; the single zone itself could be followed only "
               "that far, where it is returned"), single, event, attempts, self.history,
            self.folds, reached)


def _offset_contact_set(pe, fhpe, K2_over_K1, sigma_over_delta, *, n, progress,
                        **materials) -> ContactSetResult:
    """The one zone of offset ``sigma_over_delta`` at ``(Pe_l, fHPe_l)``: Newton's
    method on its half-width from Hertz's (section 16), within the budget of
    :data:`MAX_EVALUATIONS` evaluations, each telling the progress.  The offset closes
    one zone only: where that zone is not valid, no contact set holds at this offset
    (of those Newton's method reaches)."""
    if not 8 <= int(n) <= 256:
        raise InputError(f"n must be in [8, 256], got {n!r}", parameters=("n",))
    sigma = check_closure_range(sigma_over_delta=sigma_over_delta)[1]
    budget = _Budget(MAX_EVALUATIONS, None if progress is None else lambda: progress(0.0))
    cond = materials.pop("conductance")
    model = _Budgeted(budget, K2_over_K1, n=int(n), conductance=cond, **materials)
    try:
        sol = model.solve([[sigma - 1.0, sigma + 1.0]], pe, fhpe, sigma_over_delta=sigma)
    except SolveError as exc:
        return ContactSetResult("not converged", f"the zone of offset sigma/Delta = "
                                f"{sigma:g} was not found from Hertz's half-width: {exc}",
                                None, reached=0.0)
    except _BudgetSpent:
        return ContactSetResult("not converged", f"stopped after {budget.limit} evaluations "
                                f"of the zone's defect, the most allowed", None, reached=0.0)
    if progress is not None:
        progress(1.0)
    where = _point({"pe_hertz": pe, "fhpe_hertz": fhpe})
    if sol.valid:
        return ContactSetResult("solved", f"one zone of offset sigma/Delta = {sigma:g} at "
                                f"{where}, by Newton's method on its half-width", sol)
    return ContactSetResult(
        "no steady solution", f"the zone of offset sigma/Delta = {sigma:g} at {where} is "
        f"not valid ({_first_failure(sol)}); an offset closes one zone only", sol)


def _suggested_sets(single: ZoneSolution) -> list[tuple[str, list]]:
    """The contact sets that the failure of one zone suggests, ``(name, edges)``: a
    zone where the gap closed, or the zone split where the pressure vanished (each
    with new half-widths 1e-3 and 1e-2 of the zone's)."""
    v = single.validity
    guesses = []
    (a, b), = single.edges
    h = 0.5 * (b - a)
    if v.gap_margin < 0.0:
        X0 = v.gap_margin_at
        for w in (1e-3, 1e-2):
            width = w * h
            if X0 > b:
                gap = X0 - b
                guesses.append(("zone where the gap closed",
                                [[a, b], [X0 - min(width, 0.5 * gap), X0 + width]]))
            else:
                gap = a - X0
                guesses.append(("zone where the gap closed",
                                [[X0 - width, X0 + min(width, 0.5 * gap)], [a, b]]))
    # (A pressure failing at an edge moves that edge: only an interior one splits.)
    if v.pressure_margin < 0.0 and a + 0.05 * h < v.pressure_margin_at < b - 0.05 * h:
        Xp = v.pressure_margin_at
        for w in (1e-3, 1e-2):
            guesses.append(("zone split where the pressure vanished",
                            [[a, Xp - w * h], [Xp + w * h, b]]))
    return guesses


def other_starts(model: ZoneModel, sol: ZoneSolution, lam) -> list[dict]:
    """Newton's method from other contact sets at the same load: is the answer unique?

    Starts: Hertz's zone; the zone widened and narrowed by a fifth; split at its
    centre into two zones; shifted by a quarter of its width either way.  Each outcome:
    the edges reached, whether valid, and whether they are the given solution's (to
    1e-8 of ``l``), or why Newton's method failed.
    """
    pe, F = sol.parameters.pe, sol.parameters.fhpe
    (a, b) = sol.edges[0, 0], sol.edges[-1, 1]
    c, h = 0.5 * (a + b), 0.5 * (b - a)
    starts = {"Hertz's zone": [[-1.0, 1.0]], "widened": [[c - 1.2 * h, c + 1.2 * h]],
              "narrowed": [[c - 0.8 * h, c + 0.8 * h]],
              "split in two": [[a, c - 0.05 * h], [c + 0.05 * h, b]],
              "shifted upstream": [[a + 0.25 * h, b + 0.25 * h]],
              "shifted downstream": [[a - 0.25 * h, b - 0.25 * h]]}
    out = []
    for name, start in starts.items():
        try:
            other = model.solve(start, pe, F, lam, max_iter=20)
        except (SolveError, InputError) as exc:
            out.append({"start": name, "result": f"no convergence ({exc})"})
            continue
        same = other.zones == sol.zones and bool(
            np.max(np.abs(other.edges - sol.edges)) < 1e-8)
        out.append({"start": name, "edges": other.edges.ravel().tolist(),
                    "valid": bool(other.valid), "same": same})
    return out


def _physical(conductance) -> PhysicalConductance:
    if isinstance(conductance, PhysicalConductance):
        return conductance
    return PhysicalConductance(*conductance)


@dataclass(frozen=True, eq=False, repr=False)
class PhysicalContactSet(ContactSetResult):
    """The contact set of a physical problem, in SI units (:func:`physical_contact_set`):
    the dimensionless answer (:class:`ContactSetResult`, units of the Hertz half-width)
    and the problem's fields and applicability.

    Attributes
    ----------
    problem : PhysicalProblem
    conductance : PhysicalConductance or None
    fields : ContactFields or None
        Pressure, both surfaces' temperatures, slopes and strains of the contact set
        at the point asked for (:func:`~thermocontact.analysis.fields.contact_fields`,
        SI units); None where there is none.
    applicability : Applicability or None
        Whether the theory applies
        (:func:`~thermocontact.analysis.applicability.physical_applicability`, as for
        a single patch); None without a contact set.
    """

    problem: object = None
    conductance: PhysicalConductance | None = None
    fields: ContactFields | None = None
    applicability: Applicability | None = None

    UNITS = {"a": "m", "b": "m", "load": "N/m", "peak_pressure": "Pa", "mean_pressure": "Pa",
             "flash_temperature": "K", "temperature_mismatch": "K", "peak_temperature": "K",
             "bulk_temperatures": "K", "hertz_half_width": "m"}

    @classmethod
    def of(cls, result: ContactSetResult, problem, conductance=None, fields=None,
           applicability=None) -> PhysicalContactSet:
        """The dimensionless ``result`` with its problem in SI units."""
        return cls(**{f.name: getattr(result, f.name) for f in dataclasses.fields(result)},
                   problem=problem, conductance=conductance, fields=fields,
                   applicability=applicability)

    @property
    def result(self) -> ContactSetResult:
        """The answer in units of the Hertz half-width."""
        return ContactSetResult(**{f.name: getattr(self, f.name)
                                   for f in dataclasses.fields(ContactSetResult)})

    @property
    def valid(self):
        """Whether the contact set satisfies every inequality (None without one)."""
        sol = self.answer
        return None if sol is None else sol.valid

    @property
    def applicable(self) -> bool:
        return bool(self.applicability is not None and self.applicability.applicable)

    @property
    def hertz_half_width(self) -> float:
        return self.problem.hertz_half_width

    @property
    def zones(self) -> list:
        """Each zone's ``a``, ``b`` (m, from the undeformed cylinder's lowest point, the
        leading edge at larger x), ``load`` (N/m) and ``peak_pressure`` (Pa)."""
        ell, P = self.problem.hertz_half_width, self.problem.load
        sol = self.answer
        return [{"a": z["a"] * ell, "b": z["b"] * ell, "load": z["load"] * P,
                 "peak_pressure": z["peak_pressure"] * P / ell}
                for z in ([] if sol is None else sol.zone_records())]

    def _record(self) -> dict:
        """The JSON record of ``contact --zones`` (the dimensionless answer under
        ``"dimensionless"``)."""
        app, f = self.applicability, self.fields
        rec = {"status": self.status, "message": self.message, "valid": self.valid,
               "theory_applicable": self.applicable,
               "theory_reasons": [] if app is None else list(app.reasons),
               "theory_checked": ["contact size against the radius", "slopes", "strains",
                                  "temperatures"],
               "hertz_half_width": self.hertz_half_width, "zones": self.zones,
               "dimensionless": self.result.to_dict()}
        if f is not None:
            rec.update({
                "peak_pressure": f.peak_pressure, "mean_pressure": f.mean_pressure,
                "flash_temperature": f.flash_temperature,
                "temperature_mismatch": (f.temperature_mismatch
                                         if np.isfinite(f.temperature_mismatch) else None)})
            if self.problem.bulk_temperatures is not None:
                # lam an output; the surfaces' absolute peak, the cylinder's incoming
                # temperature plus its flash temperature (section 17).
                rec.update({"lam": self.answer.lam,
                            "bulk_temperatures": list(self.problem.bulk_temperatures),
                            "peak_temperature": (self.problem.bulk_temperatures[0]
                                                 + f.flash_temperature)})
        if app is not None:
            rec.update(app.to_dict())
        return rec

    def _summary(self) -> str:
        z = ", ".join(f"[{q['a']:.4g}, {q['b']:.4g}] m" for q in self.zones)
        return (f"status={self.status!r}, zones={z or 'none'}, valid={self.valid}, "
                f"applicable={self.applicable}")


def physical_contact_set(problem, *, conductance=None, n=32,
                         progress=None, start=None) -> PhysicalContactSet:
    """:func:`find_contact_set` for a problem in SI units, the answer in SI units.

    Parameters
    ----------
    problem : PhysicalProblem
        Closed by ``lam`` or by the bulk temperatures (``lam`` then an output,
        section 17: a stationary half-plane's with a sink, a moving one's with its
        incoming temperature).
    conductance : PhysicalConductance or tuple, optional
        ``(h0, m[, p_ref])``: an interface conductance ``h = h0 (p/p_ref)^m``, ``h0``
        in W/(m^2 K), ``p_ref`` in Pa (default: the mean Hertz pressure ``P/(2 l)``).
    start : (float, float), optional
        The edges (m, as :attr:`PhysicalContactSet.zones`) of a valid single patch
        at this point, tried first (:func:`find_contact_set`).

    Returns
    -------
    PhysicalContactSet
        With the fields of the contact set (pressure, both surfaces' temperatures
        from the zones' heat fluxes, slopes, strains) and whether the theory applies.
    """
    ell = problem.hertz_half_width
    groups = problem.ray_parameters()
    conductance = None if conductance is None else _physical(conductance)
    res = find_contact_set(problem.pe_hertz, problem.fhpe(ell), groups["K2_over_K1"],
                           lam=problem.lam, temperatures=problem.temperatures(ell),
                           k2_over_k1=groups["k2_over_k1"],
                           delta1_over_delta2=groups["delta1_over_delta2"],
                           beta_f=groups["beta_f"], speed_ratio=groups["speed_ratio"],
                           n=n, progress=progress,
                           conductance=None if conductance is None else
                           conductance.biot(problem),
                           start=None if start is None else np.asarray(start) / ell)
    fields = app = None
    if res.answer is not None:
        fields = contact_fields(res.answer, length=ell, load=problem.load,
                                temperature_units=problem.temperature_units,
                                fractions=problem.compliance_fractions,
                                perfect_contact=conductance is None)
        app = physical_applicability(problem, fields)
    return PhysicalContactSet.of(res, problem, conductance, fields, app)
