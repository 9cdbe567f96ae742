"""The extremum of a smooth function near its least sample, to rounding."""

from __future__ import annotations

import numpy as np

__all__ = ["POLISH_POINTS", "polish_minimum"]


#: Chebyshev points on which a margin is interpolated between the neighbours of its
#: least sample: the margins are analytic there, and 17 points interpolate them over
#: two sample spacings to about 1e-13 (checked against Brent's method on the closed
#: forms in tests/test_validity.py).
POLISH_POINTS = 17


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
