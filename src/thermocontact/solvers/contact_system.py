"""The contact system solved: an assembled contact set's linear system at one ``fHPe``,
with an interface conductance's dependence on the pressure by Newton's method
(derivation sections 15 and 16).  Used by the single patch and the contact sets alike.
"""

from __future__ import annotations

import numpy as np

from ..discretisation.system import ContactSetSystem
from ..numerics.dense import not_finite_solution, solve_equilibrated
from ..problem.errors import NotConvergedError

__all__ = ["MAX_PICARD", "solve_contact_system"]

#: Newton steps of the interface conductance's dependence on the pressure.
MAX_PICARD = 50


def _solve_linear(system: ContactSetSystem, F: float, biot=None, scale=None, A=None,
                  b=None, what="the contact set's linear system"):
    A = system.matrix(F, biot, scale) if A is None else A.copy(order="F")
    b = system.b.copy() if b is None else b.copy()
    x, rcond = solve_equilibrated(A, b, what)
    if not np.all(np.isfinite(x)):
        raise not_finite_solution(what)
    return x, float(rcond)


def solve_contact_system(system: ContactSetSystem, F: float, rep, half, conductance=None,
                         what="the contact set's linear system"):
    """``x`` and the reciprocal condition number of an assembled contact set at
    ``F`` (:func:`~thermocontact.discretisation.system.contact_set_system`).

    With an interface conductance (section 15) whose Biot numbers follow the
    pressure (``m != 0``), Newton's method on the whole linear system with that
    dependence in its Jacobian, from the load spread over the zones as Hertz's shape
    (plain repetition with the last pressure oscillates once the heat couples
    strongly).

    Parameters
    ----------
    system : ContactSetSystem
    F : float
        ``fHPe`` in the system's length unit.
    rep : Representation
    half : array_like
        The zones' half-widths in the system's length unit.
    conductance : Conductance, optional
        Required when the system was assembled with one.
    what : str
        The system's name in messages.

    Raises
    ------
    SolveError
        A singular system, or the conductance's pressure unsettled after
        :data:`MAX_PICARD` Newton steps.
    """
    if not system.local:
        return _solve_linear(system, F, what=what)
    m, n = system.zones, system.n
    # The first pressure: the load spread over the zones as Hertz's shape.
    rows = [rep.pressure_rows(sh, ah) for sh, ah in system.points]
    pressure = [(2.0 / (np.pi * np.sum(half))) * rep.pressure_weight(sh)
                for sh, _ in system.points]
    cond = conductance
    biot = [cond.biot(p) for p in pressure]
    scale = system.theta_scale(biot)
    x, rcond = _solve_linear(system, F, biot, scale, what=what)
    if cond.exponent == 0.0:
        return x, rcond

    def residual(x):
        phi = x[:m * n].reshape(m, n)
        p = [r @ f for r, f in zip(rows, phi)]
        bi = [cond.biot(q) for q in p]
        A = system.matrix(F, bi, scale)
        return A @ x - system.b, A, p, bi
    r, A, p, bi = residual(x)
    norm = np.linalg.norm(r)
    step = np.inf
    for _ in range(MAX_PICARD):
        # Converged when the residual is at rounding level or the step is.
        if (norm <= 1e-11 * max(1.0, np.linalg.norm(system.b))
                or step <= 1e-13 * np.linalg.norm(x)):
            if not np.isfinite(x).all():
                raise not_finite_solution(what)
            return x, rcond
        J = A + system.conductance_jacobian(x, bi, [cond.dbiot(q) for q in p], rows, scale)
        dx, rcond = _solve_linear(system, F, A=J, b=-r, what=what)
        alpha = 1.0
        while True:
            trial = residual(x + alpha * dx)
            if np.linalg.norm(trial[0]) < norm or alpha < 1e-4:
                break
            alpha *= 0.5
        x = x + alpha * dx
        step = alpha * np.linalg.norm(dx)
        r, A, p, bi = trial
        norm = np.linalg.norm(r)
    raise NotConvergedError(f"the interface conductance's pressure did not settle in "
                     f"{MAX_PICARD} Newton steps")
