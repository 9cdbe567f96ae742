"""The extremum of a smooth function near its least sample, to rounding."""

from __future__ import annotations

import numpy as np

__all__ = ["LOCAL_POINTS", "POLISH_POINTS", "interpolated_minimum", "polish_minimum"]


#: Chebyshev points on which a margin is interpolated between the neighbours of its
#: least sample: the margins are analytic there, and 17 points interpolate them over
#: two sample spacings to about 1e-13 (checked against Brent's method on the closed
#: forms in tests/test_validity.py).
POLISH_POINTS = 17
#: Samples on which :func:`interpolated_minimum` fits its local polynomial.
LOCAL_POINTS = 7


def polish_minimum(f, x, values, i):
    """The least value of ``f`` near the sampled minimum ``values[i]`` at ``x[i]``.

    ``f`` is interpolated on Chebyshev points between the neighbouring samples
    (one vectorised call), the interpolant's least value is found from the roots of
    its derivative, and ``f`` is evaluated there: a margin is the minimum of the
    closed form, not of its samples, so a boundary located where a margin vanishes
    is located to the root finder's tolerance.

    Parameters
    ----------
    f : callable
        Vectorised: ``f(ndarray) -> ndarray``.
    x, values : ndarray
        Increasing samples and ``f`` there.
    i : int
        Index of the least sample.

    Returns
    -------
    x_min, f_min : float
    """
    lo, hi = x[max(i - 1, 0)], x[min(i + 1, len(x) - 1)]
    best = (float(x[i]), float(values[i]))
    if not hi > lo:
        return best
    cheb = np.polynomial.chebyshev.Chebyshev
    k = np.arange(POLISH_POINTS)
    pts = 0.5 * (lo + hi) - 0.5 * (hi - lo) * np.cos(np.pi * (k + 0.5) / POLISH_POINTS)
    if np.unique(pts).size < POLISH_POINTS:
        # Neighbours a few roundings apart (next to an edge, in s): the samples are
        # as fine as floating point resolves; nothing to interpolate.
        return best
    fit = cheb.fit(pts, f(pts), POLISH_POINTS - 1, domain=[lo, hi])
    crit = fit.deriv().roots()
    crit = crit[np.isreal(crit)].real
    crit = crit[(crit > lo) & (crit < hi)]
    cand = np.concatenate([crit, pts])
    at = cand[np.argmin(fit(cand))]
    value = float(f(np.array([at]))[0])
    if np.isfinite(value) and value < best[1]:
        best = (float(at), value)
    return best


def interpolated_minimum(x, values, i, points=LOCAL_POINTS):
    """The least value of the polynomial through the ``points`` samples nearest ``i``.

    No new evaluation of the function: the interpolant of degree ``points - 1``
    on the samples around the least one is minimised between the neighbours of
    ``values[i]`` (on a grid, then by Newton's method on its derivative).  On the
    validity margins' samples it agrees with :func:`polish_minimum` to about 1e-7
    (measured in tests/test_validity.py), at no cost beyond the samples.

    Parameters
    ----------
    x, values : ndarray
        Increasing samples and the function there.
    i : int
        Index of the least sample.
    points : int
        Samples of the stencil (at most ``len(x)``).

    Returns
    -------
    x_min, f_min : float
    """
    best = (float(x[i]), float(values[i]))
    m = min(points, len(x))
    if m < 3:
        return best
    lo = min(max(i - m // 2, 0), len(x) - m)
    xs, fs = x[lo:lo + m], values[lo:lo + m]
    a, b = x[max(i - 1, 0)], x[min(i + 1, len(x) - 1)]
    if not (b > a and np.all(np.isfinite(fs))):
        return best
    # The interpolant in a local variable u (x = x[i] + u h), by its Vandermonde
    # system: microseconds, against a millisecond for numpy.polynomial's fit.
    h = 0.5 * (b - a)
    try:
        c = np.linalg.solve(np.vander((xs - x[i]) / h, m), fs)
    except np.linalg.LinAlgError:
        return best
    ua, ub = (a - x[i]) / h, (b - x[i]) / h
    grid = np.linspace(ua, ub, 33)
    vals = np.polyval(c, grid)
    u = grid[int(np.argmin(vals))]
    d1, d2 = np.polyder(c), np.polyder(c, 2)
    # From a grid point, 1/16 of the interval off at most, Newton's error squares:
    # 4 steps reach rounding.
    for _ in range(4):
        curv = np.polyval(d2, u)
        if not curv > 0.0:
            break
        step = np.polyval(d1, u) / curv
        u = min(max(u - step, ua), ub)
        if abs(step) <= 1e-13:
            break
    value = float(np.polyval(c, u))
    if not value <= vals.min():
        u, value = grid[int(np.argmin(vals))], float(vals.min())
    if np.isfinite(value) and value < best[1]:
        best = (float(x[i] + h * u), value)
    return best
