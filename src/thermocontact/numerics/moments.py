"""The panel machinery of the kernel moments, and the step kernel's closed form.

The moments of a convolution kernel ``K(s - r)`` against the bases of the unknowns
are computed by one engine, :func:`thermocontact.numerics.moment_engine.moments`,
for either coordinate map (the edge-graded variable of derivation section 12 or
``t = arccos r``, section 10).  Its pieces live here: a common rule of equal
panels with ``GAUSS_POINTS``-point Gauss–Legendre each (:func:`panel_rule`); the panel
holding each point and its neighbours, replaced (:func:`near_field`) by an
innermost interval graded toward the point (:func:`levels_for` halvings; its
bases interpolated by :func:`chebyshev_lagrange`) and geometric outer panels
(:func:`outer_panels`).  The kernels of this problem are smooth except at
``r = s`` (a jump, a logarithm, structure on the scale ``1/c`` of the moving
body's kernels), which this integrates to about machine precision.
:func:`sgn_moments` gives the step kernel's moments against the Chebyshev bases
in closed form.
"""

from __future__ import annotations


import numpy as np

from .cache import small_cache

__all__ = ["chebyshev_lagrange", "levels_for", "near_field", "outer_panels", "panel_rule",
           "sgn_moments"]

GAUSS_POINTS = 16


@small_cache(8)
def gauss_legendre(m: int):
    x, w = np.polynomial.legendre.leggauss(m)
    return 0.5 * (x + 1.0), 0.5 * w


@small_cache(64)
def _graded_reference(levels: int = 47):
    """Nodes and weights on ``(0, 1]`` graded toward 0.

    Breakpoints halve from 1 ``levels`` times (47: below ``1e-14``): every panel is
    as far from 0 as it is long, so a pole-like kernel (``c M(c u) - 1/u`` is ``-1/u`` beyond
    ``|u| ~ 1/c``) or a logarithm at 0 costs Gauss–Legendre nothing in accuracy.
    The two outer panels, where the bases may oscillate, get 16 points, the rest 10.
    The last panel ``[0, e]``, ``e = 2^-levels``, is integrated after the
    substitution ``x = e y^6`` by 16-point Gauss–Legendre in ``y``: a logarithm at 0
    becomes ``y^5 ln y``, integrated to about ``3e-12`` of the panel's integral,
    a part ``e |ln e|`` of the whole (section 12: below ``1e-16`` once
    ``levels >= LOG_LEVELS``).
    """
    bps = [0.5**i for i in range(levels + 1)]
    nodes, weights = [], []
    for i, (a, b) in enumerate(zip(bps[1:], bps[:-1])):
        x, w = gauss_legendre(GAUSS_POINTS if i < 2 else 10)
        nodes.append(a + (b - a) * x)
        weights.append((b - a) * w)
    y, w = gauss_legendre(GAUSS_POINTS)
    nodes.append(bps[-1] * y**6)
    weights.append(bps[-1] * 6.0 * y**5 * w)
    return np.concatenate(nodes), np.concatenate(weights)


#: Halvings after which the last panel's rule leaves a logarithm's error below 1e-16.
LOG_LEVELS = 20


@small_cache(16)
def panel_rule(n: int):
    """Common rule on ``[0, pi]`` for ``n`` basis functions: ``m`` equal panels, 16 points each.

    Returns
    -------
    m, h : int, float
        Number and length of the panels (``n/4 + 2``, at least 8: four panels
        per period of the most oscillatory basis function).
    x, w : ndarray
        Nodes and weights.
    panel : ndarray of int
        Panel of each node.
    """
    m = max(8, -(-n // 4) + 2)
    h = np.pi / m
    x, w = gauss_legendre(GAUSS_POINTS)
    nodes = (np.arange(m)[:, None] + x[None, :]).ravel() * h
    return m, h, nodes, np.tile(w, m) * h, np.repeat(np.arange(m), GAUSS_POINTS)


def near_field(x_s, m, h, panel):
    """The panel of each point ``x_s`` and its neighbours, replaced by the graded rule.

    Returns
    -------
    near : ndarray of bool, shape (k, nodes)
        Common-rule nodes to leave out.
    sides : list of (sign, length)
        Lengths of the replaced interval to the left and right of ``x_s``.
    """
    p0 = np.minimum((x_s / h).astype(int), m - 1)
    lo = np.maximum(p0 - 1, 0) * h
    hi = np.minimum(p0 + 2, m) * h
    near = (panel[None, :] >= (p0 - 1)[:, None]) & (panel[None, :] <= (p0 + 1)[:, None])
    return near, [(-1.0, x_s - lo), (1.0, hi - x_s)]


def outer_panels(side, inner, panels=None):
    """``panels`` (default ``_OUTER``) geometric panels of 16 points from ``inner`` to ``side``.

    Returns
    -------
    dist, wq : ndarray, shape (k, 16 panels)
        Distances from the point and weights (0 for a side of zero length).
    """
    panels = _OUTER if panels is None else panels
    xg, wg = gauss_legendre(GAUSS_POINTS)
    ratio = (np.maximum(side, inner) / np.maximum(inner, 1e-300)) ** (1.0 / panels)
    edges = inner[:, None] * ratio[:, None] ** np.arange(panels + 1)[None, :]
    a, b = edges[:, :-1], edges[:, 1:]
    k = len(side)
    dist = (a[:, :, None] + (b - a)[:, :, None] * xg[None, None, :]).reshape(k, -1)
    wq = ((b - a)[:, :, None] * wg[None, None, :]).reshape(k, -1)
    return dist, wq


def levels_for(n: int, scale=None, logarithmic=False) -> int:
    """Halvings of the graded innermost interval (see :func:`kernel_moments`).

    Down to ``1e-3/scale`` (47 without a scale); at least :data:`LOG_LEVELS` for a
    kernel that is ``a + b ln|u|`` below that scale.
    """
    if scale is None:
        return 47
    w_in = 6.0 / (n + 1)
    levels = int(min(47, max(4, np.ceil(np.log2(max(scale * w_in, 1.0) / 1e-3)))))
    return max(levels, LOG_LEVELS) if logarithmic else levels


_P = 20  # interpolation points of the bases across the innermost interval
_OUTER = 3  # panels per side between the innermost interval and the common rule


def chebyshev_lagrange(x, points: int):
    """``l_p(x)`` of ``points`` first-kind Chebyshev points on ``[0, 1]`` (barycentric).

    Returns the points and an array of shape ``x.shape + (points,)``; at a point
    itself the basis is the unit vector.
    """
    theta = np.pi * (np.arange(points) + 0.5) / points
    xc = 0.5 * (1.0 - np.cos(theta))
    lam = (-1.0) ** np.arange(points) * np.sin(theta)
    diff = np.asarray(x, dtype=float)[..., None] - xc
    exact = diff == 0.0
    diff[exact] = 1.0
    terms = lam / diff
    out = terms / terms.sum(axis=-1, keepdims=True)
    hit = exact.any(axis=-1)
    out[hit] = exact[hit]
    return xc, out


@small_cache(64)
def inner_reference(levels: int):
    """Graded rule on (0, 1] and the Lagrange basis of ``_P`` Chebyshev points there.

    Returns ``tau, omega, x, lagrange`` with ``lagrange[q, p] = l_p(tau_q)``.
    """
    tau, om = _graded_reference(levels)
    x, lagrange = chebyshev_lagrange(tau, _P)
    return tau, om, x, lagrange


def sgn_moments(s, n: int):
    """Exact moments of ``sgn(s - r)`` for ``-1 <= s <= 1``.

    With ``t_s = arccos s``:
    ``integral sgn(s - r) sqrt(1-r^2) U_j dr = 2 C_j(t_s) - (pi/2) [j = 0]``,
    ``C_0 = (pi - t_s + sin(2 t_s)/2)/2``,
    ``C_j = -(sin(j t_s)/j - sin((j + 2) t_s)/(j + 2))/2``; and
    ``integral sgn(s - r) T_j / sqrt(1-r^2) dr = 2 D_j(t_s) - pi [j = 0]``,
    ``D_0 = pi - t_s``, ``D_j = -sin(j t_s)/j``.

    Returns
    -------
    bounded, singular : ndarray, shape (k, n)
    """
    ts = np.arccos(np.clip(np.asarray(s, dtype=float), -1.0, 1.0))[:, None]
    j = np.arange(n)[None, :]
    jj = np.where(j > 0, j, 1)
    cb = np.where(j > 0, -0.5 * (np.sin(j * ts) / jj - np.sin((j + 2) * ts) / (j + 2)),
                  0.5 * (np.pi - ts + 0.5 * np.sin(2 * ts)))
    cs = np.where(j > 0, -np.sin(j * ts) / jj, np.pi - ts)
    bounded = 2.0 * cb
    bounded[:, 0] -= 0.5 * np.pi
    singular = 2.0 * cs
    singular[:, 0] -= np.pi
    return bounded, singular
