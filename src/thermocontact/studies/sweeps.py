"""Sweeps of one parameter with one assembly, and where validity is lost along them.

Along a sweep in ``fhpe`` or ``lam`` the discrete blocks do not change, so each
point costs one linear solve (derivation section 5).  The point where a curve
stops being valid is located by Brent's method on the margin that changes sign
(:func:`validity_margins`), not by sampling.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy.optimize import brentq

from ..discretisation.methods import DEFAULT_METHOD
from ..problem.parameters import SolveError
from ..problem.validation import InputError
from ..solvers.refinement import refine
from ..solvers.result import ContactSolution
from ..solvers.single_patch import Model

__all__ = ["Boundary", "Curve", "choose_n", "sweep", "validity_margins"]

#: Names of the margins; each is >= 0 exactly when its inequality holds.
MARGINS = ("load", "pressure", "gap", "edge")


def validity_margins(sol: ContactSolution) -> dict[str, float]:
    """The signed margins of the contact inequalities of one solution.

    ``load``: ``P_H/P``, and those of :meth:`Validity.margins
    <thermocontact.analysis.validity.Validity.margins>`.  ``sol.valid`` holds
    exactly when all are >= 0.
    """
    return {"load": sol.load_ratio, **sol.validity.margins()}


@dataclass(frozen=True)
class Boundary:
    """Where a curve changes validity.

    Attributes
    ----------
    x : float
        Value of the swept parameter, to ``xtol``.
    margin : str
        Which inequality: ``load``, ``pressure``, ``gap`` or ``edge``.
    at : float
        Where it fails (``s``) just past the boundary.
    becomes_valid : bool
        Whether the curve turns valid (rather than invalid) as ``x`` increases.
    """

    x: float
    margin: str
    at: float
    becomes_valid: bool


@dataclass(frozen=True)
class Curve:
    """One sweep: fixed parameters, the swept one, and the solutions' key values.

    Attributes
    ----------
    label : str
    fixed : dict
        The fixed inputs of :func:`~thermocontact.solvers.single_patch.solve`.
    x_name : str
        ``"fhpe"`` or ``"lam"``.
    x, load_ratio, sigma_over_delta, lam, valid, pressure_margin, gap_margin : ndarray
    boundaries : tuple of Boundary
    n : int
    method : str
    error_estimate : float
        The larger of the error estimates at the middle and the end of the sweep.
    solutions : tuple of ContactSolution
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
    error_estimate: float
    solutions: tuple = ()


def _model(fixed: dict, method: str, n=None) -> Model:
    return Model(fixed["pe"], fixed["K2_over_K1"], k2_over_k1=fixed.get("k2_over_k1"),
                 delta1_over_delta2=fixed.get("delta1_over_delta2", 1.0), method=method, n=n)


def _closure(kw: dict) -> dict:
    return {k: kw[k] for k in ("lam", "sigma_over_delta") if k in kw}


def choose_n(fixed: dict, x_name: str, x_end, tol=1e-6, method=DEFAULT_METHOD,
             n_max=None) -> tuple[int, float]:
    """Smallest ``n`` (doubling from 16) whose error estimate at the points
    ``x_end`` is below ``tol``, or ``n_max``.

    The points are refined together (:func:`~thermocontact.solvers.refinement.refine`
    from the levels 4, 8, 16); a point without a solution at some ``n`` is left out
    of the estimate there.

    Returns
    -------
    n, error_estimate
    """
    model = _model(fixed, method)
    points = [{**fixed, x_name: float(x)} for x in np.atleast_1d(x_end)]

    def at(m):
        out = []
        for kw in points:
            try:
                out.append(model.solve_at(m, kw["fhpe"], check_validity=False, **_closure(kw)))
            except SolveError:
                out.append(None)
        return tuple(out)

    levels, est = refine(at, [4, 8, 16], tol=tol, n_max=2**30 if n_max is None else n_max)
    n = 16 * 2 ** (len(levels) - 3)
    return n, est


def _solver(fixed: dict, x_name: str, n: int, method: str):
    model = _model(fixed, method)

    def at(x):
        kw = {**fixed, x_name: x}
        return model.solve_at(n, kw["fhpe"], **_closure(kw))

    return at


def _boundaries(at, x, sols, xtol):
    """Brent's method on each margin that changes sign between neighbouring points."""
    out = []
    margins = [validity_margins(s) if s is not None else None for s in sols]
    for i in range(len(x) - 1):
        a, b = margins[i], margins[i + 1]
        if a is None or b is None or sols[i].valid == sols[i + 1].valid:
            continue
        roots = []
        for name in MARGINS:
            if (a[name] >= 0) == (b[name] >= 0):
                continue
            # The gap and pressure margins scale with 1/L and are not continuous
            # through L = 0: only the load margin is sought across it.
            if name != "load" and (a["load"] <= 0 or b["load"] <= 0):
                continue

            def f(xx, name=name):
                try:
                    return validity_margins(at(xx))[name]
                except SolveError:
                    # Only where P_H/P vanishes (sigma infinite): the load
                    # margin's root itself.
                    if name == "load":
                        return 0.0
                    raise

            try:
                root = brentq(f, x[i], x[i + 1], xtol=xtol)
            except (ValueError, SolveError):
                continue
            roots.append((root, name))
        if not roots:
            continue
        root, name = min(roots)
        # Sample the invalid side just past the root to say where it fails.
        past = at(min(root + 10 * xtol, x[i + 1]) if sols[i].valid else
                  max(root - 10 * xtol, x[i]))
        v = past.validity
        where = {"load": 0.0, "pressure": v.pressure_margin_at, "gap": v.gap_margin_at,
                 "edge": 1.0 if v.edge_margins[1] <= v.edge_margins[0] else -1.0}
        out.append(Boundary(float(root), name, float(where[name]),
                            becomes_valid=bool(sols[i + 1].valid)))
    return tuple(out)


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
    est = float("nan")
    if n is None:
        probe = (x[x.size // 2], x[-1])
        n, est = choose_n(fixed, x_name, probe, tol=tol, method=method, n_max=n_max)
    at = _solver(fixed, x_name, n, method)
    sols = []
    for xi in x:
        try:
            sols.append(at(xi))
        except SolveError:
            sols.append(None)
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
        boundaries=_boundaries(at, x, sols, xtol) if ok else (),
        n=n,
        method=method,
        error_estimate=est,
        solutions=tuple(sols) if keep_solutions else (),
    )
