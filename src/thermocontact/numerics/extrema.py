"""The extremum of a smooth function near its least sample, to rounding."""

from __future__ import annotations

import numpy as np

__all__ = ["LOCAL_POINTS", "POLISH_POINTS", "interpolated_minima", "interpolated_minimum",
           "polish_minimum"]


#: Chebyshev points on which a margin is interpolated between the neighbours of its
#: least sample: the margins are analytic there, and 17 points interpolate them over
#: two sample spacings to about 1e-13 (checked against Brent's method on the closed
#: forms in tests/test_validity.py).
POLISH_POINTS = 17
#: Samples on which :func:`interpolated_minimum` fits its local polynomial.
LOCAL_POINTS = 7


def _interpolation_matrix(count):
    """The matrix taking a function's values at the ``count`` Chebyshev points of the
    first kind, ascending (``-cos(pi (k + 1/2)/count)``), to the coefficients of its
    interpolant in the Chebyshev polynomials ``T_0 ... T_{count-1}``: the discrete
    orthogonality ``c_j = (2/count) sum_k f_k T_j(x_k)``, ``c_0`` halved."""
    k = np.arange(count)
    x = -np.cos(np.pi * (k + 0.5) / count)
    matrix = (2.0 / count) * np.polynomial.chebyshev.chebvander(x, count - 1).T
    matrix[0] *= 0.5
    return x, matrix


_POLISH_NODES, _POLISH_MATRIX = _interpolation_matrix(POLISH_POINTS)


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
        The sample's own where ``f`` is not finite at every interpolation point.
    """
    lo, hi = x[max(i - 1, 0)], x[min(i + 1, len(x) - 1)]
    best = (float(x[i]), float(values[i]))
    if not hi > lo:
        return best
    mid, half = 0.5 * (lo + hi), 0.5 * (hi - lo)
    pts = mid + half * _POLISH_NODES
    if np.any(pts[1:] == pts[:-1]):
        # Neighbours a few roundings apart (next to an edge, in s): the samples are
        # as fine as floating point resolves; nothing to interpolate.
        return best
    # The interpolant in the interval's own variable t (x = mid + half t), its
    # coefficients by the points' discrete orthogonality; the critical points are
    # the roots of its derivative inside, the candidates those and the points.
    cheb = np.polynomial.chebyshev
    on_pts = f(pts)
    if not np.all(np.isfinite(on_pts)):
        # A closed form undefined between the samples: nothing to interpolate; the
        # sampled minimum stands.
        return best
    c = _POLISH_MATRIX @ on_pts
    crit = cheb.chebroots(cheb.chebder(c))
    crit = crit[np.isreal(crit)].real
    crit = crit[(crit > -1.0) & (crit < 1.0)]
    k = int(np.argmin(cheb.chebval(np.concatenate([crit, _POLISH_NODES]), c)))
    at = mid + half * crit[k] if k < crit.size else pts[k - crit.size]
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
    at, value = interpolated_minima(x, np.asarray(values, dtype=float)[None, :], [i], points)
    return float(at[0]), float(value[0])


def _horner(c, u):
    """``np.polyval`` of each row of coefficients ``c`` (m, k) at the rows of ``u``
    (m, ...), the same operations in the same order."""
    u = np.asarray(u, dtype=float)
    y = np.zeros_like(u)
    shape = (c.shape[0],) + (1,) * (u.ndim - 1)
    for k in range(c.shape[1]):
        y = y * u + c[:, k].reshape(shape)
    return y


def interpolated_minima(x, values, i, points=LOCAL_POINTS):
    """:func:`interpolated_minimum` of several functions sampled at the same ``x``.

    Parameters
    ----------
    x : ndarray, shape (N,)
        Increasing samples, shared.
    values : ndarray, shape (m, N)
        The functions there, one per row.
    i : sequence of int, length m
        Index of each row's least sample.
    points : int

    Returns
    -------
    x_min, f_min : ndarray, shape (m,)
        Each row's as :func:`interpolated_minimum` finds it (the same operations,
        made on all rows at once).
    """
    x = np.asarray(x, dtype=float)
    values = np.asarray(values, dtype=float)
    i = np.asarray(i, dtype=int)
    rows = np.arange(values.shape[0])
    best_x, best_f = x[i].copy(), values[rows, i].copy()
    m = min(points, len(x))
    if m < 3 or rows.size == 0:
        return best_x, best_f
    lo = np.minimum(np.maximum(i - m // 2, 0), len(x) - m)
    stencil = lo[:, None] + np.arange(m)
    xs, fs = x[stencil], values[rows[:, None], stencil]
    a, b = x[np.maximum(i - 1, 0)], x[np.minimum(i + 1, len(x) - 1)]
    ok = (b > a) & np.all(np.isfinite(fs), axis=1)
    if not np.any(ok):
        return best_x, best_f
    rows, i, xs, fs, a, b = rows[ok], i[ok], xs[ok], fs[ok], a[ok], b[ok]
    # The interpolant in a local variable u (x = x[i] + u h), by its Vandermonde
    # system (np.vander's powers, by running products): microseconds per row.
    h = 0.5 * (b - a)
    t = (xs - x[i][:, None]) / h[:, None]
    vander = np.empty((t.shape[0], m, m))
    vander[:, :, m - 1] = 1.0
    vander[:, :, m - 2] = t
    np.multiply.accumulate(np.repeat(t[:, :, None], m - 1, axis=2), axis=2,
                           out=vander[:, :, m - 2::-1])
    try:
        c = np.linalg.solve(vander, fs[:, :, None])[:, :, 0]
    except np.linalg.LinAlgError:
        # A singular stencil: each row alone, the singular ones keeping their sample.
        for r, k in zip(rows, i):
            bx, bf = interpolated_minima(x, values[r:r + 1], [k], points)
            best_x[r], best_f[r] = bx[0], bf[0]
        return best_x, best_f
    ua, ub = (a - x[i]) / h, (b - x[i]) / h
    grid = np.linspace(ua, ub, 33, axis=1)
    vals = _horner(c, grid)
    k0 = np.argmin(vals, axis=1)
    first = grid[np.arange(grid.shape[0]), k0]
    u = first.copy()
    d1 = c[:, :-1] * np.arange(m - 1, 0, -1)
    d2 = d1[:, :-1] * np.arange(m - 2, 0, -1)
    # From a grid point, 1/16 of the interval off at most, Newton's error squares:
    # 4 steps reach rounding.
    active = np.ones(u.size, dtype=bool)
    for _ in range(4):
        curv = _horner(d2, u)
        active &= curv > 0.0
        if not np.any(active):
            break
        with np.errstate(divide="ignore", invalid="ignore"):
            step = _horner(d1, u) / curv
        u = np.where(active, np.minimum(np.maximum(u - step, ua), ub), u)
        active &= ~(np.abs(step) <= 1e-13)
    value = _horner(c, u)
    least = vals.min(axis=1)
    fallback = ~(value <= least)
    u = np.where(fallback, first, u)
    value = np.where(fallback, least, value)
    better = np.isfinite(value) & (value < best_f[rows])
    best_x[rows[better]] = x[i[better]] + h[better] * u[better]
    best_f[rows[better]] = value[better]
    return best_x, best_f
