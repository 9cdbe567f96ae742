"""A grid line's points solved together (:meth:`Model.solve_many
<thermocontact.solvers.single_patch.Model.solve_many>`): their inputs broadcast, their
levels' validities evaluated a whole n at a time, a coarser level held in a finer one's
representation."""

from __future__ import annotations

import numpy as np

from ..analysis.validity import assess_many
from ..discretisation.system import SHARED_BLOCKS_N
from ..numerics.cache import release_freed_memory
from ..problem.closure import Temperatures
from ..problem.validation import InputError, check_exactly_one, check_numbers
from .result import ContactSolution

__all__ = ["all_as_in", "as_in", "assessed_many", "line_inputs", "line_validities"]


def as_in(sol: ContactSolution, fine: ContactSolution) -> ContactSolution:
    """``sol`` in ``fine``'s representation where that holds it exactly
    (:meth:`~thermocontact.discretisation.representations.Representation.prolong`):
    a coarser level's margins are then evaluated by the finer level's operators, formed
    once for both (its margins the same but for rounding)."""
    return all_as_in([(sol, fine)])[0]


def all_as_in(pairs) -> list:
    """:func:`as_in` of each ``(sol, fine)``: the pairs of one ``(n, fine n)``
    prolonged as one stack (each row summed as alone)."""
    out = [sol for sol, _ in pairs]
    groups = {}
    for i, (sol, fine) in enumerate(pairs):
        if fine.n != sol.n:
            groups.setdefault((sol.representation, fine.representation), []).append(i)
    for (rep, finer), which in groups.items():
        held = rep.prolong(np.array([v for i in which
                                     for v in (out[i].phi, out[i].psi)]), finer)
        if held is None:
            continue
        for k, i in enumerate(which):
            out[i] = out[i].replace(n=finer.n, representation=finer, phi=held[2 * k],
                                    psi=held[2 * k + 1])
    return out


def line_inputs(fhpe, lam, sigma_over_delta, temperatures):
    """A line's points (:meth:`Model.solve_many`): each point's ``fhpe`` and closure
    ``(lam, sigma_over_delta, temperatures)`` (one value broadcast to every point)."""
    closure = check_exactly_one(lam=lam, sigma_over_delta=sigma_over_delta,
                                temperatures=temperatures)
    closures = None
    if closure == "temperatures":
        # One closure (a Temperatures or a tuple (Theta, L/Delta)) or a list of them.
        closures = [t if isinstance(t, Temperatures) else Temperatures(*t)
                    for t in (temperatures if isinstance(temperatures, list)
                              else [temperatures])]
        given = {"fhpe": fhpe}
    else:
        given = {"fhpe": fhpe, closure: lam if closure == "lam" else sigma_over_delta}
    given = {k: check_numbers(k, v) for k, v in given.items()}
    count = max([len(v) for v in given.values()] + ([len(closures)] if closures else []))
    for k, v in given.items():
        if len(v) not in (1, count):
            raise InputError(f"{k} must be one value or {count} (one per point), got "
                             f"{len(v)}", parameters=(k,))
    given = {k: v * count if len(v) == 1 else v for k, v in given.items()}
    if closures is not None:
        given["temperatures"] = closures * count if len(closures) == 1 else closures
    keys = [(given["lam"][i] if closure == "lam" else None,
             given["sigma_over_delta"][i] if closure == "sigma_over_delta" else None,
             given["temperatures"][i] if closure == "temperatures" else None)
            for i in range(count)]
    return given["fhpe"], keys


def line_validities(refined, polish) -> dict:
    """The validity of every point's finest level and of the one before (whose margins'
    change is their error), all points at one n together: ``{(point, n): Validity}``."""
    wanted = {}
    pairs = [(i, sol, levels[-1]) for i, (_, levels, _) in refined.items()
             for sol in levels[-2:]]
    for (i, sol, _), checked in zip(pairs, all_as_in([p[1:] for p in pairs])):
        wanted.setdefault(checked.n, []).append(((i, sol.n), checked))
    validities = {}
    if max(wanted, default=0) >= SHARED_BLOCKS_N:
        release_freed_memory()  # the heap pages the levels' systems left
    # The finest n first: its moment bases, formed again, serve its checks and polish.
    for _, group in sorted(wanted.items(), reverse=True):
        found = assessed_many([sol for _, sol in group], polish=polish)
        validities.update({key: sol.validity for (key, _), sol in zip(group, found)})
    return validities


def assessed_many(sols, polish=True) -> list:
    """Solutions with their contact inequalities evaluated, all together
    (:func:`~thermocontact.analysis.validity.assess_many`: the samples of all formed by
    the same row operators at once), each as
    :func:`~thermocontact.solvers.single_patch.assessed` gives it alone.

    Parameters
    ----------
    sols : sequence of ContactSolution
        Solved without validity, in one representation (one model and ``n``), differing
        only in ``fhpe`` and the closure: a sweep, or a grid line's level.
    polish : bool
        As :func:`~thermocontact.analysis.validity.assess`.

    Returns
    -------
    list of ContactSolution
    """
    if not sols:
        return []
    found = assess_many([sol.parameters for sol in sols], sols[0].representation,
                        np.array([sol.phi for sol in sols]), np.array([sol.psi for sol in sols]),
                        [sol.load_ratio for sol in sols], [sol.sigma_over_delta for sol in sols],
                        [sol.lam for sol in sols], polish=polish)
    return [sol.replace(validity=v) for sol, v in zip(sols, found)]
