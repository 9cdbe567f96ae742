"""The discrete system shared by every discretisation method, and their registry.

Unknowns (derivation section 6): the pressure's bounded factor ``phi`` at the
nodes of a :class:`~thermocontact.quadrature.BoundedRule` and the heat-flux
difference's factor ``psi`` at the nodes of a
:class:`~thermocontact.quadrature.SingularRule`.  A method supplies the blocks of

* the contact equation (D14) at ``n + 1`` points ``s_k``::

      (C - F Tp) phi - F Tq psi = (2/pi) (L sigma + L s_k)

* the heat equation (D18) at ``n - 1`` points ``s'_k``::

      Hp phi + Hq psi = 0

with the load and heat-partition rows ``w_p . phi = 1`` and
``w_q . psi = lam - eta``.  Nothing in the blocks depends on ``F = fHPe``,
``lam`` or ``sigma``, so one assembly serves a whole sweep over them.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Callable

import numpy as np

from .representations import CHEBYSHEV
from ..problem.parameters import Parameters
from ..numerics.quadrature import BoundedRule, SingularRule

__all__ = ["AUTO_RANGE", "Blocks", "METHODS", "register"]


@dataclass(frozen=True)
class Blocks:
    """Assembled, ``F``-independent blocks of the discrete equations.

    Attributes
    ----------
    n : int
        Unknowns per function.
    pressure_rule, flux_rule : BoundedRule, SingularRule
        Node sets of ``phi`` and ``psi``.
    contact_points : ndarray, shape (n + 1,)
        Where the contact equation is enforced.
    C, Tp : ndarray, shape (n + 1, n)
        Cauchy and thermal-distortion operators on ``phi``.
    Tq : ndarray, shape (n + 1, n)
        Thermal-distortion operator on ``psi``.
    Hp, Hq : ndarray, shape (n - 1, n)
        Heat-equation operators on ``phi`` and ``psi``.
    integrate : callable
        ``integrate(kernel, s, scale=None) -> (Ib, Is)``, row operators with
        ``integral K(s - r) p(r) dr = Ib @ phi`` and
        ``integral K(s - r) q'(r) dr = Is @ psi`` for any kernel, computed the
        method's way (used by the validity checks); ``kernel`` receives arrays
        whose rows belong to the points ``s``.
    """

    n: int
    pressure_rule: BoundedRule
    flux_rule: SingularRule
    contact_points: np.ndarray
    C: np.ndarray
    Tp: np.ndarray
    Tq: np.ndarray
    Hp: np.ndarray
    Hq: np.ndarray
    integrate: Callable = field(repr=False, compare=False)
    #: The contact equation's columns for ``L sigma`` and ``L`` (times -2/pi):
    #: by default 1 and ``s_k`` at the collocation points; a projection method
    #: gives their projections.
    const_column: np.ndarray | None = field(default=None, repr=False, compare=False)
    linear_column: np.ndarray | None = field(default=None, repr=False, compare=False)
    #: Row operators of the validity checks, which depend only on the blocks.
    cache: dict = field(default_factory=dict, repr=False, compare=False)
    #: Representation of ``phi`` and ``psi`` (:mod:`thermocontact.bases`).
    basis: object = field(default=CHEBYSHEV, repr=False, compare=False)


Assembler = Callable[[Parameters, int], Blocks]

METHODS: dict[str, Assembler] = {}
#: Per method, the first and the largest ``n`` of the solver's automatic doubling.
AUTO_RANGE: dict[str, tuple[int, int]] = {}


def register(name: str, auto_range: tuple[int, int] = (16, 1024)):
    """Add an assembler to :data:`METHODS` under ``name``, with its automatic ``n`` range."""

    def deco(func: Assembler) -> Assembler:
        METHODS[name] = func
        AUTO_RANGE[name] = auto_range
        return func

    return deco
