"""The discrete system shared by every discretisation method.

Unknowns (derivation section 6): the pressure's bounded factor ``phi`` and the
heat-flux difference's factor ``psi`` at the nodes of a representation
(:mod:`.representations`).  The blocks are

* the contact equation (D14), collocated at ``n + 1`` points ``s_k`` or
  projected on ``n + 1`` functions::

      (C - F Tp) phi - F Tq psi = (2/pi) (L sigma e_0 + L e_1)

  where ``e_0``, ``e_1`` are ``1`` and ``s_k`` (collocation) or their projections;

* the heat equation (D18) at ``n - 1`` points or projections::

      Hp phi + Hq psi = 0

with the load and heat-partition rows ``w_p . phi = 1`` and
``w_q . psi = lam - eta``.  Nothing in the blocks depends on ``F = fHPe``,
``lam`` or ``sigma``, so one assembly serves a whole sweep over them.  The blocks
are plain arrays and a representation (pickled as its class and ``n``), so an
assembly can be sent to another process.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..problem.parameters import Parameters
from .operator import contact_operators, heat_operators
from .representations import Representation, range_projections

__all__ = ["Blocks", "assemble", "equation_points"]


@dataclass(frozen=True, eq=False)
class Blocks:
    """Assembled, ``F``-independent blocks of the discrete equations.

    Attributes
    ----------
    representation : Representation
        How ``phi`` and ``psi`` are carried, evaluated and integrated.
    C, Tp : ndarray, shape (n + 1, n)
        Cauchy and thermal-distortion operators of (D14) on ``phi``.
    Tq : ndarray, shape (n + 1, n)
        Thermal-distortion operator of (D14) on ``psi``.
    Hp, Hq : ndarray, shape (n - 1, n)
        Operators of (D18) on ``phi`` and ``psi``.
    const_column, linear_column : ndarray, shape (n + 1,)
        The right side's ``e_0`` and ``e_1``.
    """

    representation: Representation
    C: np.ndarray
    Tp: np.ndarray
    Tq: np.ndarray
    Hp: np.ndarray
    Hq: np.ndarray
    const_column: np.ndarray
    linear_column: np.ndarray

    @property
    def n(self) -> int:
        return self.representation.n

    def __repr__(self):
        return f"Blocks({self.representation!r})"


def assemble(par: Parameters, rep: Representation, scheme: str) -> Blocks:
    """Assemble the blocks by collocation or by projection on the range spaces.

    Parameters
    ----------
    par : Parameters
        ``fhpe`` is not used.
    rep : Representation
    scheme : {"collocation", "projection"}
        Collocation at the representation's points; or projection of (D14) on
        ``cos(j x)``, ``j <= n``, and of (D18) on ``sin((j + 1) x) sin x``,
        ``j < n - 1``, by the midpoint rule on ``2n`` points in the
        representation's variable ``x`` (:func:`.representations.range_projections`;
        the error is about that of collocation at ``2n``, derivation sections 10
        and 12).

    Returns
    -------
    Blocks
    """
    n = rep.n
    (sc, ac, p1), (sh, ah, p2) = equation_points(rep, scheme)
    C, Tp, Tq = contact_operators(par, rep, sc, ac)
    Hp, Hq = heat_operators(par, rep, sh, ah)
    if p1 is None:
        return Blocks(rep, C, Tp, Tq, Hp, Hq, np.ones(n + 1), sc)
    return Blocks(rep, p1 @ C, p1 @ Tp, p1 @ Tq, p2 @ Hp, p2 @ Hq, p1.sum(axis=1), p1 @ sc)


def equation_points(rep: Representation, scheme: str):
    """Where the contact and heat equations are evaluated, and how they are reduced.

    Returns
    -------
    (s, aux, P) for the contact equation, then for the heat equation
        The points, their own coordinate in the representation (``tau``, or None)
        and the projection ``P`` applied to the rows evaluated there (None for
        collocation, whose rows are the equations themselves).
    """
    if scheme == "collocation":
        (sk, ak), (sh, ah) = rep.collocation_points()
        return (sk, ak, None), (sh, ah, None)
    if scheme == "projection":
        x, p1, p2 = range_projections(rep.n)
        s, aux = rep.projection_points(x)
        return (s, aux, p1), (s, aux, p2)
    raise ValueError(f"scheme must be 'collocation' or 'projection', got {scheme!r}")
