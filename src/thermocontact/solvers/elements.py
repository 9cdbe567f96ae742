"""A second method for contact sets: elements, undifferentiated Green's functions, active set.

Independent of the main method's representations and moments (derivation section
14b): the line ``Xmin < X < Xmax`` (units of the Hertz half-width ``l``) is cut into
equal elements carrying constant pressure ``p_k`` and heat-flux difference ``q_k``;
every element integral of a Green's function is exact (closed-form antiderivatives):

* Flamant: the gap gains ``-(1/2) integral p(Y) ln|X - Y| dY``;
* the cylinder's thermal bulge ``-(pi/2) F (d/c) integral E(c(X - Y)) (p + q) dY``
  (D5; ``integral exp(-v) I0(v) dv = v exp(-v) (I0 + I1)``);
* the stationary half-plane's ``+(pi/2) F integral |X - Y|/2 (p - q) dY`` (D4);
* the temperatures: ``rho integral q1 exp(-u) K0(|u|) dY + integral q2 ln|X - Y| dY``
  is the same constant on every contact element (D8, D12; ``u = c (X - Y)``,
  ``integral exp(-v) K0(v) dv = v exp(-v) (K0 - K1)`` for ``v > 0``).

The contact set is found by the active-set iteration of unilateral contact: solve
with the elements in contact, drop the element in the greatest tension or add the one
that interpenetrates most, until none does.  Collocation at the elements' centres; the edges are known to
half an element, the loads to ``O(h)``.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..discretisation.element_operators import steady_element_operators
from ..io.results import FieldResult
from ..problem.errors import NotConvergedError
from ..problem.parameters import Parameters
from .active_set import chattering, next_set

__all__ = ["ElementSolution", "contact_runs", "solve_elements", "solve_on_set"]


@dataclass(frozen=True, eq=False, repr=False)
class ElementSolution(FieldResult):
    """The second method's contact set.

    Attributes
    ----------
    centres : ndarray
        Element centres ``X_k``.
    h : float
        Element width.
    pressure, flux : ndarray
        ``p_k`` (units ``P/l``) and ``q_k`` (units ``f v P/l``), zero off contact.
    gap : ndarray
        The gap at the centres (units ``l^2/R``), zero on contact.
    active : ndarray of bool
    iterations : int
    chatter : int
        Elements at the zones' ends that the active set toggled without settling
        (0 when it settled): the edges are known to that many elements.
    """

    centres: np.ndarray
    h: float
    pressure: np.ndarray
    flux: np.ndarray
    gap: np.ndarray
    active: np.ndarray
    iterations: int
    chatter: int = 0
    _coordinate = "centres"

    def _summary(self) -> str:
        z = ", ".join(f"[{a:.4g}, {b:.4g}]" for a, b in self.zones)
        return (f"zones={z}, elements={self.centres.size}, h={self.h:.3g}, "
                f"iterations={self.iterations}, chatter={self.chatter}")

    @property
    def zones(self) -> np.ndarray:
        """``(a, b)`` of each run of contact elements (to half an element)."""
        starts, stops = contact_runs(self.active)
        h = self.h
        return np.column_stack([self.centres[starts] - 0.5 * h,
                                self.centres[stops - 1] + 0.5 * h])

    @property
    def loads(self) -> np.ndarray:
        starts, stops = contact_runs(self.active)
        return np.array([self.h * self.pressure[a:b].sum() for a, b in zip(starts, stops)])


def contact_runs(active):
    """``(starts, stops)``: the index ranges ``[start, stop)`` of each run of contact
    elements in ``active`` (one zone each)."""
    on = np.diff(np.concatenate([[0], np.asarray(active, dtype=np.int8), [0]]))
    return np.flatnonzero(on == 1), np.flatnonzero(on == -1)


def solve_elements(par: Parameters, lam, *, profile=None, domain=(-2.5, 2.5), elements=800,
                   max_iter=2000) -> ElementSolution:
    """Solve the contact-set problem by elements and an active set (section 14b).

    Parameters
    ----------
    par : Parameters
        ``pe = Pe_l``, ``fhpe = fHPe_l`` in units of ``l``; a stationary half-plane
        and no Dundurs term.
    lam : float
    profile : callable, optional
        Initial gap ``g0(X)`` in units of ``l^2/R`` (default ``X^2/2``).
    domain : (float, float)
        Where contact may occur.
    elements : int

    Raises
    ------
    SolveError
        When the active set does not settle (it cycles) in ``max_iter`` iterations.
    """
    if par.half_plane_scale or par.free_term:
        raise ValueError("solve_elements: a stationary half-plane without the Dundurs term")
    lo, hi = domain
    h = (hi - lo) / elements
    X = lo + h * (np.arange(elements) + 0.5)
    g0 = 0.5 * X * X if profile is None else np.asarray(profile(X), dtype=float)
    ops = steady_element_operators(par, X, h)
    Gp, Gq, Tp, Tq = ops.Gp, ops.Gq, ops.Tp, ops.Tq

    def solve_set(active):
        p, q, gap, _, _ = solve_on_set(Gp, Gq, Tp, Tq, g0, np.zeros(elements), h, active,
                                       lam=lam)
        return p, q, gap

    # Start from where the initial gap is within 1/2 of its least value (the Hertz
    # contact of the cylinder).
    active = g0 <= np.min(g0) + 0.5
    history = []
    for it in range(1, max_iter + 1):
        p, q, gap = solve_set(active)
        # One change at a time, the worst violation first: all at once makes the
        # edges chatter where the heat flux's edge singularity is under-resolved.
        tension = np.where(active, p, 0.0)
        overlap = np.where(active, 0.0, gap)
        if tension.min() >= 0.0 and overlap.min() >= 0.0:
            return ElementSolution(X, h, p, q, gap, active, it)
        history.append(active.tobytes())
        new, _, cycled = next_set(active, p, gap, tension < 0.0, overlap < 0.0, history, True)
        if cycled:
            # A cycle.  If it toggles only elements at the ends of the zones, the
            # edges are settled to within them: return the state of the cycle with
            # no tension, and how many elements chatter.
            key = new.tobytes()
            states = [np.frombuffer(k, dtype=bool) for k in history[history.index(key):]]
            toggled = chattering(states)
            if toggled is not None:
                for state in states:
                    p, q, gap = solve_set(state)
                    if np.all(p[state] >= 0.0):
                        return ElementSolution(X, h, p, q, gap, state.copy(), it, toggled.size)
            raise NotConvergedError(f"the active set cycles after {it} iterations: no settled "
                             f"contact set on {elements} elements")
        active = new
    raise NotConvergedError(f"the active set did not settle in {max_iter} iterations")


def solve_on_set(Gp, Gq, Tp, Tq, g_known, t_known, h, active, *, load=1.0, lam=None,
                 theta=None, resistance=None):
    """Pressure and heat on a given set of contact elements (section 14b, eq. R9).

    Solves, on the elements in ``active``, ``g_known + Gp p + Gq q - D = 0`` (contact),
    ``t_known + Tp p + (Tq + diag(resistance)) q = C`` (equal temperatures, or the
    interface conductance's jump), ``h sum p = load`` and one closure: ``lam`` (then
    ``h sum q = lam h sum p`` and ``C`` is unknown) or ``theta`` (``C = theta``, the far
    temperatures').  ``resistance`` is ``pi/(2 Bi)`` per element (None: perfect contact).

    Returns
    -------
    p, q, gap : ndarray
        On every element (zero off contact; the gap zero on it).
    approach, C : float
    """
    if (lam is None) == (theta is None):
        raise ValueError("solve_on_set: give one of lam and theta")
    N = Gp.shape[0]
    idx = np.flatnonzero(active)
    k = idx.size
    free = lam is not None
    size = 2 * k + 1 + free
    A = np.zeros((size, size))
    b = np.zeros(size)
    sub = np.ix_(idx, idx)
    A[:k, :k] = Gp[sub]
    A[:k, k:2 * k] = Gq[sub]
    A[:k, 2 * k] = -1.0
    b[:k] = -g_known[idx]
    A[k:2 * k, :k] = Tp[sub]
    A[k:2 * k, k:2 * k] = Tq[sub]
    if resistance is not None:
        A[k + np.arange(k), k + np.arange(k)] += resistance[idx]
    b[k:2 * k] = -t_known[idx]
    if free:
        A[k:2 * k, 2 * k + 1] = -1.0
        A[2 * k + 1, k:2 * k] = h
        A[2 * k + 1, :k] = -lam * h
    else:
        b[k:2 * k] += theta
    A[2 * k, :k] = h
    b[2 * k] = load
    x = np.linalg.solve(A, b)
    p = np.zeros(N)
    q = np.zeros(N)
    p[idx], q[idx] = x[:k], x[k:2 * k]
    gap = g_known + Gp @ p + Gq @ q - x[2 * k]
    gap[idx] = 0.0
    return p, q, gap, x[2 * k], (x[2 * k + 1] if free else theta)
