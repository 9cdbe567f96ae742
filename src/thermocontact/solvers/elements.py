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
from scipy.special import i0e, i1e, k0e, k1e

from ..io.results import FieldResult
from ..problem.parameters import Parameters, SolveError

__all__ = ["ElementSolution", "solve_elements"]


def _log_integral(u):
    """Antiderivative of ``ln|u|``: ``u ln|u| - u`` (0 at ``u = 0``)."""
    a = np.abs(u)
    with np.errstate(divide="ignore", invalid="ignore"):
        out = u * np.log(np.where(a > 0.0, a, 1.0)) - u
    return out


def _displacement_integral(v):
    """Antiderivative of ``E(v)`` (``exp(-v) I0(v)``, 1 for ``v <= 0``), 0 at 0."""
    vp = np.maximum(v, 0.0)
    return np.where(v > 0.0, vp * (i0e(vp) + i1e(vp)), v)


def _temperature_integral(v):
    """Antiderivative of ``exp(-v) K0(|v|)``: ``-1`` at ``v = 0``, continuous."""
    a = np.abs(v)
    with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
        ahead = a * np.exp(-2.0 * a) * (k0e(a) - k1e(a))
        behind = -a * (k0e(a) + k1e(a))
    out = np.where(v > 0.0, ahead, behind)
    return np.where(a == 0.0, -1.0, out)


def _element_matrix(antiderivative, X, Y, h, scale=1.0):
    """``M[i, k] = integral over element k of K(scale (X_i - Y))`` by the antiderivative."""
    u = X[:, None] - Y[None, :]
    return (antiderivative(scale * (u + 0.5 * h)) - antiderivative(scale * (u - 0.5 * h))) / scale


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
        on = np.concatenate([[False], self.active, [False]]).astype(int)
        starts = np.flatnonzero(np.diff(on) == 1)
        ends = np.flatnonzero(np.diff(on) == -1) - 1
        h = self.h
        return np.column_stack([self.centres[starts] - 0.5 * h, self.centres[ends] + 0.5 * h])

    @property
    def loads(self) -> np.ndarray:
        on = np.concatenate([[False], self.active, [False]]).astype(int)
        starts = np.flatnonzero(np.diff(on) == 1)
        ends = np.flatnonzero(np.diff(on) == -1)
        return np.array([self.h * self.pressure[a:b].sum() for a, b in zip(starts, ends)])


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
    F, c, d, rho, eta = par.fhpe, par.cylinder_scale, par.delta1_over_delta2, par.K2_over_K1, 0.0
    del eta
    flamant = -0.5 * _element_matrix(_log_integral, X, X, h)
    cyl = -(0.5 * np.pi) * F * (d / c) * _element_matrix(_displacement_integral, X, X, h, c)
    half = (0.5 * np.pi) * F * _element_matrix(lambda u: 0.25 * u * np.abs(u), X, X, h)
    # Gap response to (p, q): p acts through all three, q = q1 - q2 through the bulges.
    Gp = flamant + cyl + half
    Gq = cyl - half
    temp_cyl = rho * _element_matrix(_temperature_integral, X, X, h, c)
    temp_hp = _element_matrix(_log_integral, X, X, h)
    # rho T(q1) + L(q2) with q1 = (p + q)/2, q2 = (p - q)/2.
    Tp = 0.5 * (temp_cyl + temp_hp)
    Tq = 0.5 * (temp_cyl - temp_hp)

    def solve_set(active):
        idx = np.flatnonzero(active)
        k = idx.size
        # Unknowns: p (k), q (k), the approach, the temperature difference.
        A = np.zeros((2 * k + 2, 2 * k + 2))
        b = np.zeros(2 * k + 2)
        A[:k, :k] = Gp[np.ix_(idx, idx)]
        A[:k, k:2 * k] = Gq[np.ix_(idx, idx)]
        A[:k, 2 * k] = -1.0
        b[:k] = -g0[idx]
        A[k:2 * k, :k] = Tp[np.ix_(idx, idx)]
        A[k:2 * k, k:2 * k] = Tq[np.ix_(idx, idx)]
        A[k:2 * k, 2 * k + 1] = -1.0
        A[2 * k, :k] = h
        b[2 * k] = 1.0
        A[2 * k + 1, k:2 * k] = h
        b[2 * k + 1] = lam
        x = np.linalg.solve(A, b)
        p = np.zeros(elements)
        q = np.zeros(elements)
        p[idx], q[idx] = x[:k], x[k:2 * k]
        gap = g0 + Gp @ p + Gq @ q - x[2 * k]
        gap[idx] = 0.0
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
        new = active.copy()
        if tension.min() < 0.0:
            new[int(np.argmin(tension))] = False
        else:
            new[int(np.argmin(overlap))] = True
        key = new.tobytes()
        if key in history:
            # A cycle.  If it toggles only elements at the ends of the zones, the
            # edges are settled to within them: return the state of the cycle with
            # no tension, and how many elements chatter.
            states = [np.frombuffer(k, dtype=bool) for k in history[history.index(key):]]
            every = np.logical_and.reduce(states)
            toggled = np.flatnonzero(np.logical_or.reduce(states) & ~every)
            ends = np.flatnonzero(np.diff(np.concatenate([[0], every.astype(int), [0]])))
            # Within two elements of an end of the zones that every state shares.
            if toggled.size and np.all(np.min(np.abs(toggled[:, None] - ends[None, :] + 0.5),
                                              axis=1) <= 2.5):
                for state in states:
                    p, q, gap = solve_set(state)
                    if np.all(p[state] >= 0.0):
                        return ElementSolution(X, h, p, q, gap, state.copy(), it, toggled.size)
            raise SolveError(f"the active set cycles after {it} iterations: no settled "
                             f"contact set on {elements} elements")
        active = new
    raise SolveError(f"the active set did not settle in {max_iter} iterations")
