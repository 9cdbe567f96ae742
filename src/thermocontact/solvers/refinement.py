"""Refinement in ``n`` and its error estimate: one driver for every caller.

A solve, a sweep's choice of ``n`` and the physical front end's roots all solve at
successive ``n`` (doubling) and estimate the error of the finest solution from
the last three by Richardson's extrapolation with the observed order.  An estimate
is reported only where it was measured: where nothing solved at two levels there is
none (None), and the :class:`Refinement`'s status says why.
"""

from __future__ import annotations

import logging
import math
from dataclasses import dataclass

from ..io.results import Result

__all__ = ["N_RANGE", "P_MAX", "QUANTITIES", "QUANTITIES_WITH_LAM", "Refinement", "error_estimate",
           "refine", "refine_each"]

log = logging.getLogger("thermocontact")

#: Unknowns per function accepted anywhere: at n = 1024 a graded solve takes about a
#: minute and its operators about a gigabyte, beyond which nothing runs in seconds.
N_RANGE = (4, 1024)
#: Largest convergence order the error estimate believes: just above the
#: asymptotic order 4 of the Chebyshev methods (derivation section 10).  The graded
#: methods converge faster once they resolve the edges, but before that (Pe k2/k1
#: large, n small) a sudden drop of the differences must not be read as a high
#: order: the same cap keeps their estimate an upper bound (section 12).
P_MAX = 5.0
#: The quantities whose errors are estimated.
QUANTITIES = ("load_ratio", "sigma_over_delta")
#: And with the heat partition an output of the far temperatures (section 17).
QUANTITIES_WITH_LAM = QUANTITIES + ("lam",)


def _relative(x: float) -> float:
    return max(abs(x), 0.01)


def error_estimate(levels, quantities=QUANTITIES, p_max=P_MAX) -> float:
    """Richardson estimate of the error of the finest of successive solutions.

    For solutions at ``n/4, n/2, n`` with differences ``d1, d2`` in ``P_H/P`` (and
    in ``sigma/Delta``), the observed order is ``p = log2(d1/d2)``, clamped to
    ``[1, 5]`` (1 also when fewer than three levels are given), and the error of
    the finest is ``d2 / (2^p - 1)``.  The cap 5 is just above the product
    method's asymptotic order (about 4, set by the edge terms of derivation
    section 8): a sudden drop of ``d2`` while the discretisation first resolves
    the cylinder's kernels must not be read as a higher order.  The estimate is
    the larger of the quantities' errors, each relative to ``max(|value|, 0.01)``.

    Parameters
    ----------
    levels : sequence of results
        At least two, ``n`` doubling, coarsest first.
    quantities : tuple of str
        The result fields whose errors are estimated.
    p_max : float
        The largest order believed (the method's, :class:`~thermocontact.
        discretisation.methods.Method`).

    Returns
    -------
    float
    """
    est = 0.0
    for attr in quantities:
        v = [getattr(sol, attr) for sol in levels[-3:]]
        d2 = abs(v[-1] - v[-2])
        p = 1.0
        if len(v) == 3:
            d1 = abs(v[1] - v[0])
            if d1 > 0.0 and d2 > 0.0:
                p = min(max(math.log2(d1 / d2), 1.0), p_max)
            elif d2 == 0.0:
                p = p_max
        est = max(est, d2 / (2.0**p - 1.0) / _relative(v[-1]))
    return est


@dataclass(frozen=True, eq=False, repr=False)
class Refinement(Result):
    """The levels of a refinement in ``n`` and the error estimate of the finest.

    It unpacks as ``levels, estimate``.  An estimate is only ever one that was
    measured: where no case has solutions at the finest level and a coarser one of
    the last three, it is None and ``status`` is ``"no estimate"``, ``reason``
    saying why.

    Attributes
    ----------
    levels : tuple of tuple
        The results per level, coarsest first (None where a case has no solution).
    sizes : tuple of int
        ``n`` of each level.
    estimate : float or None
        The largest :func:`error_estimate` over the cases measured at the finest level.
    status : {"converged", "not converged", "estimated", "no estimate"}
        ``estimate <= tol``; above ``tol`` at the largest ``n``; measured without a
        target; or not measured.
    reason : str
        One line: the estimate against its target, or why there is none.
    tol : float or None
        The target.
    """

    levels: tuple
    sizes: tuple
    estimate: float | None
    status: str
    reason: str
    tol: float | None = None

    @property
    def n(self) -> int:
        """``n`` of the finest level."""
        return self.sizes[-1]

    def __iter__(self):
        # ``levels, estimate = refine(...)``; the levels as a list that the caller may
        # extend.
        return iter((list(self.levels), self.estimate))

    def _summary(self) -> str:
        est = "None" if self.estimate is None else f"{self.estimate:.1e}"
        return f"n={self.n}, levels={len(self.levels)}, estimate={est}, status={self.status!r}"

    def _record(self) -> dict:
        """Everything but the levels' results."""
        return {"sizes": list(self.sizes), "estimate": self.estimate, "status": self.status,
                "reason": self.reason, "tol": self.tol}


def _measure(levels, p_max, quantities=QUANTITIES):
    """The largest :func:`error_estimate` over the cases that have a solution at the
    finest level and at a coarser one of the last three (None when none has)."""
    est = None
    for case in zip(*levels):
        sols = [s for s in case[-3:] if s is not None]
        if len(sols) > 1 and case[-1] is not None:
            e = error_estimate(sols, quantities, p_max=p_max)
            est = e if est is None else max(est, e)
    return est


def _done(est, unsolved, n, tol, n_max) -> bool:
    """Whether a refinement stops at ``n``: no target, the target met, ``2n`` beyond
    ``n_max``, or nothing to estimate because nothing solved at ``n``."""
    return (tol is None or (est is not None and est <= tol) or 2 * n > n_max
            or (est is None and unsolved))


def refine(at, sizes, *, tol=None, n_max=None, p_max=P_MAX, progress=None,
           quantities=QUANTITIES) -> Refinement:
    """Solve at ``sizes``, then at doubled ``n`` until the estimate meets ``tol``.

    The doubling also stops where no case has a solution at the finest level: a
    larger ``n`` would be solved in vain, and no estimate is claimed.

    Parameters
    ----------
    at : callable
        ``at(n)`` returns a tuple of results, one per case refined together (a
        sweep refines its probe points together); an entry may be None where
        that case has no solution at this ``n``.
    sizes : sequence of int
        The first levels, increasing by factors of 2.
    tol : float, optional
        Target of the estimate; without it only ``sizes`` are solved.
    n_max : int, optional
        The largest ``n`` (default: the last of ``sizes``).
    p_max : float
        Passed to :func:`error_estimate`.
    progress : callable, optional
        Called as ``progress(n, estimate)`` before each level is solved (``estimate``
        None before the first two), for a caller that shows progress.
    quantities : tuple of str
        Passed to :func:`error_estimate` (``lam`` too where it is an output of the
        far temperatures).

    Returns
    -------
    Refinement
        Unpacks as ``levels, estimate``: the results per level, coarsest first, and
        the largest :func:`error_estimate` over the cases (None where none was
        measured: one level, or no case solved at the finest level and a coarser one).
    """
    sizes = [int(m) for m in sizes]
    n = sizes[-1]
    n_max = n if n_max is None else int(n_max)

    levels = []
    for m in sizes:
        if progress is not None:
            progress(m, None)
        levels.append(at(m))
    while True:
        est = _measure(levels, p_max, quantities) if len(levels) > 1 else None
        log.debug("refinement: n = %d, error estimate %s", n, est)
        unsolved = all(s is None for s in levels[-1])
        if _done(est, unsolved, n, tol, n_max):
            break
        n *= 2
        sizes.append(n)
        if progress is not None:
            progress(n, est)
        levels.append(at(n))
    if est is None:
        status = "no estimate"
        if len(levels) == 1:
            reason = f"no error estimate: one level (n = {n}) leaves no coarser one"
        elif unsolved:
            reason = f"no error estimate: nothing solved at n = {n}"
        else:
            reason = (f"no error estimate: no case solved at n = {n} and at a coarser "
                      f"level of the last three")
    elif tol is None:
        status, reason = "estimated", f"error estimate {est:.1e} at n = {n}"
    elif est <= tol:
        status, reason = "converged", f"error estimate {est:.1e} <= target {tol:.0e} at n = {n}"
    else:
        status = "not converged"
        reason = f"error estimate {est:.1e} > target {tol:.0e} at the largest n = {n}"
    return Refinement(tuple(levels), tuple(sizes), est, status, reason, tol)


def refine_each(solve, sizes, count, *, tol=None, n_max=None, p_max=P_MAX, progress=None,
                quantities=QUANTITIES) -> list:
    """:func:`refine` of ``count`` cases each refined on its own (each stops at its
    own ``n``), the cases that need a level solved together: a grid line's points
    share their systems' assembly and are solved as one stack.

    Each case's levels, estimate and stopping are those :func:`refine` gives it
    alone (same rule, :func:`_done`).

    Parameters
    ----------
    solve : callable
        ``solve(m, cases)`` returns, per case of the list ``cases``, its result at
        ``n = m`` or the exception that ends that case.
    sizes : sequence of int
        The first levels, increasing by factors of 2.
    count : int
        Number of cases.
    tol, n_max, p_max, progress, quantities
        As :func:`refine`; ``progress`` is called for each case.

    Returns
    -------
    list
        Per case, ``(levels, estimate)`` (the results coarsest first, and the estimate
        or None with one level), or the exception that ended it.
    """
    sizes = [int(m) for m in sizes]
    n_max = sizes[-1] if n_max is None else int(n_max)
    levels = {i: [] for i in range(count)}
    out = [None] * count
    active, est = list(range(count)), {}

    def advance(m, cases):
        if progress is not None:
            for i in cases:
                progress(m, est.get(i))
        for i, res in zip(cases, solve(m, cases)):
            if isinstance(res, Exception):
                out[i] = res
            else:
                levels[i].append(res)
        return [i for i in cases if out[i] is None]

    for m in sizes:
        active = advance(m, active)
    n = sizes[-1]
    while active:
        going = []
        for i in active:
            lv = levels[i]
            est[i] = error_estimate(lv[-3:], quantities, p_max=p_max) if len(lv) > 1 else None
            if _done(est[i], False, n, tol, n_max):
                out[i] = (lv, est[i])
            else:
                going.append(i)
        if not going:
            break
        n *= 2
        active = advance(n, going)
    return out
