"""Sweeps of one parameter with one assembly, and where validity is lost along them.

Along a sweep in ``fhpe`` or ``lam`` the discrete blocks do not change, so each
point costs one linear solve (derivation section 5).  The point where a curve
stops being valid is located by Brent's method on the margin that changes sign
(:func:`~.boundaries.validity_margins`), not by sampling.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..discretisation.methods import DEFAULT_METHOD, METHODS
from ..io.results import FieldResult
from ..problem.parameters import SolveError
from ..problem.validation import InputError
from ..solvers.grid_line import assessed_many
from ..solvers.refinement import refine
from .boundaries import closure, locate_events, model_for

__all__ = ["Curve", "choose_n", "sweep"]

@dataclass(frozen=True, eq=False, repr=False)
class Curve(FieldResult):
    """One sweep: fixed parameters, the swept one, and the solutions' key values.

    A result (:mod:`thermocontact.io.results`): its dataset holds the arrays over
    ``x``; its record every field but the solutions.

    Attributes
    ----------
    label : str
    fixed : dict
        The fixed inputs of :func:`~thermocontact.solvers.single_patch.solve`.
    x_name : str
        ``"fhpe"`` or ``"lam"``.
    x, load_ratio, sigma_over_delta, lam, valid, pressure_margin, gap_margin : ndarray
    boundaries : tuple of Event
        Where validity changes (:func:`~.boundaries.locate_events`).
    n : int
    method : str
    error_estimate : float or None
        The larger of the error estimates at the middle and the end of the sweep
        (None with ``n`` given, or where nothing solved there: none was measured).
    solutions : tuple of ContactSolution
        Every solution, when kept (``keep_solutions``).
    """

    label: str
    fixed: dict
    x_name: str
    x: np.ndarray
    load_ratio: np.ndarray
    sigma_over_delta: np.ndarray
    lam: np.ndarray
    valid: np.ndarray
    pressure_margin: np.ndarray
    gap_margin: np.ndarray
    boundaries: tuple
    n: int
    method: str
    error_estimate: float | None
    solutions: tuple = ()

    def _summary(self) -> str:
        est = "None" if self.error_estimate is None else f"{self.error_estimate:.1e}"
        return (f"{self.label!r}, {self.x_name} from {self.x[0]:g} to {self.x[-1]:g} "
                f"({self.x.size} points), valid {int(np.count_nonzero(self.valid))}, "
                f"boundaries {len(self.boundaries)}, method={self.method!r}, n={self.n}, "
                f"error_estimate={est}")

    def _record(self) -> dict:
        rec = super()._record()
        del rec["solutions"]
        return rec


def choose_n(fixed: dict, x_name: str, x_end, tol=1e-6, method=DEFAULT_METHOD,
             n_max=None) -> tuple[int, float | None]:
    """Smallest ``n`` of the method's automatic range whose error estimate at the points
    ``x_end`` is below ``tol``, or the largest.

    The points are refined together (:func:`~thermocontact.solvers.refinement.refine`)
    from the levels ``lo, 2 lo, 4 lo`` up to ``hi`` (``lo, hi`` the method's
    :attr:`~thermocontact.discretisation.methods.Method.auto_range`; ``n_max`` may
    lower ``hi``), the estimate believing the method's order cap; a point without a
    solution at some ``n`` is left out of the estimate there.

    Returns
    -------
    n : int
    error_estimate : float or None
        None where no point solved at ``n`` and a coarser level (nothing was measured).
    """
    lo, hi = METHODS[method].auto_range
    hi = hi if n_max is None else min(hi, int(n_max))
    model = model_for(fixed, method)
    points = [{**fixed, x_name: float(x)} for x in np.atleast_1d(x_end)]

    def at(m):
        out = []
        for kw in points:
            try:
                out.append(model.solve_at(m, kw["fhpe"], check_validity=False, **closure(kw)))
            except SolveError:
                out.append(None)
        return tuple(out)

    done = refine(at, [lo, 2 * lo, 4 * lo], tol=tol, n_max=hi, p_max=METHODS[method].order_cap)
    return done.n, done.estimate


def _solver(fixed: dict, x_name: str, n: int, method: str):
    model = model_for(fixed, method)

    def at(x, check_validity=True):
        kw = {**fixed, x_name: x}
        return model.solve_at(n, kw["fhpe"], check_validity=check_validity, **closure(kw))

    return at


def sweep(label: str, fixed: dict, x_name: str, x, *, n=None, method=DEFAULT_METHOD,
          tol=1e-6, n_max=None, xtol=1e-9, keep_solutions=False) -> Curve:
    """Solve along ``x`` with one assembly and locate the validity boundaries.

    Parameters
    ----------
    label : str
    fixed : dict
        Inputs of :func:`~thermocontact.solvers.single_patch.solve` other than ``x_name``
        (``pe``, ``K2_over_K1``, optionally ``k2_over_k1``, ``delta1_over_delta2``,
        and ``lam`` or ``fhpe``).
    x_name : {"fhpe", "lam"}
    x : array_like
        Increasing values.
    n : int, optional
        Default: chosen by :func:`choose_n` at the sweep's end for ``tol``, at most
        ``n_max``.
    method : str
    tol : float
        Error target for the choice of ``n``.
    xtol : float
        Tolerance of the boundaries in ``x``.
    keep_solutions : bool
        Keep every solution in the curve (for distribution plots).

    Returns
    -------
    Curve
    """
    if x_name not in ("fhpe", "lam"):
        raise InputError(f"x_name must be 'fhpe' or 'lam', got {x_name!r}")
    x = np.asarray(x, dtype=float)
    est = None
    if n is None:
        probe = (x[x.size // 2], x[-1])
        n, est = choose_n(fixed, x_name, probe, tol=tol, method=method, n_max=n_max)
    at = _solver(fixed, x_name, n, method)
    # Every point solved first, then all their contact inequalities evaluated together
    # (one representation: the samples formed by the same row operators at once).
    sols = []
    for xi in x:
        try:
            sols.append(at(xi, check_validity=False))
        except SolveError:
            sols.append(None)
    checked = iter(assessed_many([s for s in sols if s is not None]))
    sols = [None if s is None else next(checked) for s in sols]
    ok = [s for s in sols if s is not None]
    nan = float("nan")

    def col(f):
        return np.array([f(s) if s is not None else nan for s in sols])

    return Curve(
        label=label,
        fixed=dict(fixed),
        x_name=x_name,
        x=x,
        load_ratio=col(lambda s: s.load_ratio),
        sigma_over_delta=col(lambda s: s.sigma_over_delta),
        lam=col(lambda s: s.lam),
        valid=np.array([bool(s.valid) if s is not None else False for s in sols]),
        pressure_margin=col(lambda s: s.validity.pressure_margin),
        gap_margin=col(lambda s: s.validity.gap_margin),
        boundaries=(locate_events(at, list(x), sols, xtol=lambda a, b: xtol,
                                  only_validity_changes=True) if ok else ()),
        n=n,
        method=method,
        error_estimate=est,
        solutions=tuple(sols) if keep_solutions else (),
    )
