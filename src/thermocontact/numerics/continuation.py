"""Pseudo-arclength continuation of ``F(x, t) = 0`` past the points where ``t`` stalls.

Natural continuation in ``t`` fails where the branch turns back (a fold: ``dt/ds``
changes sign along the arclength ``s``); pseudo-arclength continuation (Keller) goes
round it, with ``z = (x, t)`` as the unknown and the tangent as the direction: each
step predicts ``z + ds tau`` and corrects by Newton's method on
``F(z) = 0, tau . (z - z_predicted) = 0``.
"""

from __future__ import annotations

import numpy as np

__all__ = ["arclength"]


def _tangent(J, previous=None):
    """The unit null vector of ``J`` (``k`` by ``k + 1``), along ``previous`` or with
    ``dt/ds > 0``."""
    v = np.linalg.svd(J)[2][-1]
    if previous is not None:
        return v if v @ previous > 0.0 else -v
    return v if v[-1] > 0.0 else -v


def arclength(residual, jacobian, z0, *, until, ds=0.02, steps=200, tol=1e-10,
              newton=12):
    """Follow ``residual(z) = 0`` from ``z0`` toward larger ``t = z[-1]``.

    Parameters
    ----------
    residual : callable
        ``z -> F``, ``k`` values for ``k + 1`` unknowns.
    jacobian : callable
        ``(z, F(z)) -> dF/dz``, ``k`` by ``k + 1``.
    z0 : ndarray
        A solution.
    until : float
        Stop once ``t`` reaches it.
    ds, steps, tol, newton : float, int
        Step length (halved where Newton's method fails), most steps, tolerance on
        the largest residual, most Newton steps per correction.

    Returns
    -------
    outcome : {"passed", "fold", "failed"}
    z : ndarray
        The solution at ``t >= until`` (passed); the fold's estimate, with ``t`` the
        largest of the parabola through the two points that bracket it and their
        slopes ``dt/ds`` (fold, error O(ds^3)); the last solution (failed).
    """
    z = np.asarray(z0, dtype=float).copy()
    F = residual(z)
    tau = _tangent(jacobian(z, F))
    for _ in range(steps):
        zp = z + ds * tau
        zn = zp.copy()
        for _ in range(newton):
            F = residual(zn)
            if np.max(np.abs(F)) < tol:
                break
            system = np.vstack([jacobian(zn, F), tau])
            zn = zn - np.linalg.solve(system, np.append(F, tau @ (zn - zp)))
        else:
            ds *= 0.5
            if ds < 1e-8:
                return "failed", z
            continue
        new_tau = _tangent(jacobian(zn, F), tau)
        if new_tau[-1] * tau[-1] < 0.0:
            # dt/ds goes from a > 0 to b < 0 over the step: t(s) is a parabola with its
            # top at s* = ds a/(a - b) from z.
            a, b = tau[-1], new_tau[-1]
            s_star = ds * a / (a - b)
            fold = z + s_star * tau
            fold[-1] = z[-1] + 0.5 * a * s_star
            return "fold", fold
        z, tau = zn, new_tau
        if z[-1] >= until:
            return "passed", z
    return "failed", z
