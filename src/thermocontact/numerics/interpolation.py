"""Polynomial interpolation: of samples (the interpolant on the samples nearest a
point, and an estimate of its error: a ray's samples read at any Peclet number), and of
smooth functions on intervals away from their singularities (Chebyshev panels refined
until each panel's last coefficients are negligible: :func:`panel_interpolation`)."""

from __future__ import annotations

import numpy as np

from .moments import chebyshev_lagrange

__all__ = ["PANEL_NODES", "STENCIL", "interpolation_error", "lagrange", "local", "nearest",
           "panel_interpolation"]

#: Samples of a local interpolant (degree 5).
STENCIL = 6


def lagrange(xs, fs, x):
    """The polynomial through the points ``(xs, fs)`` at ``x`` (Lagrange's form)."""
    x = np.asarray(x, dtype=float)
    out = np.zeros_like(x)
    for j, (xj, fj) in enumerate(zip(xs, fs)):
        w = np.ones_like(x)
        for k, xk in enumerate(xs):
            if k != j:
                w = w * (x - xk) / (xj - xk)
        out = out + w * fj
    return out


def nearest(ln_pe, x, stencil=STENCIL) -> slice:
    """The ``stencil`` samples nearest ``x`` (of :func:`local`)."""
    i = int(np.searchsorted(ln_pe, x))
    stencil = min(stencil, len(ln_pe))
    lo = min(max(i - stencil // 2, 0), len(ln_pe) - stencil)
    return slice(lo, lo + stencil)


def local(ln_pe, values, x, stencil=STENCIL):
    """The Lagrange interpolant of ``values`` in ``ln Pe`` at ``x``, on the ``stencil``
    samples nearest ``x``."""
    near = nearest(ln_pe, x, stencil)
    return float(lagrange(ln_pe[near], values[near], x))


def interpolation_error(ln_pe, values, x) -> float:
    """An estimate of the error of :func:`local` at ``x``: its change from the
    interpolant on one sample fewer (the error of the lower degree, an upper estimate
    of its own where the samples resolve the function)."""
    return abs(local(ln_pe, values, x) - local(ln_pe, values, x, STENCIL - 1))


#: First-kind Chebyshev points per panel of :func:`panel_interpolation`.
PANEL_NODES = 16
#: The coefficients of a panel's interpolant whose size is its error estimate (the last
#: three: an odd or an even function's last one alone can vanish).
_TAIL = 3
#: Halvings of a panel before its points are evaluated directly.
_PANEL_DEPTH = 10


def _chebyshev_transform(points):
    """``C`` with ``C @ f`` the Chebyshev coefficients (up to sign) of the interpolant
    of ``f`` at the first-kind points of :func:`~.moments.chebyshev_lagrange`."""
    theta = np.pi * (np.arange(points) + 0.5) / points
    C = (2.0 / points) * np.cos(np.multiply.outer(np.arange(points), theta))
    C[0] *= 0.5
    return C


def panel_interpolation(f, intervals, targets, *, tol, ratio=np.sqrt(2.0)):
    """Values at ``targets`` of a function analytic on ``intervals`` away from ``0``, from
    its Chebyshev interpolants on panels.

    Each interval ``[lo, hi]`` (both of one sign) is cut into panels graded
    geometrically away from ``0`` (ends ``|lo| ratio^k``: the scale of a singularity or
    a boundary layer at ``0``), each interpolated at :data:`PANEL_NODES` first-kind
    Chebyshev points; a panel whose last three Chebyshev coefficients exceed ``tol``
    times the function's scale (``max(1, max |f|)`` over its interval's nodes, each
    component) is halved and interpolated again, up to ten times, beyond which its
    targets are evaluated directly.  ``f`` is called once per round of halving with
    every interval's new nodes together.  The interpolant's error is then about the
    last coefficients' size: ``tol`` of the scale (an absolute tolerance: a component
    exponentially small on an interval is not resolved beyond it).

    Parameters
    ----------
    f : callable
        ``x -> ndarray`` of shape ``(k, x.size)``, vectorised.
    intervals : sequence of (float, float)
        ``lo < hi``, ``0`` outside.
    targets : sequence of ndarray
        Points of each interval.
    tol : float

    Returns
    -------
    list of ndarray
        ``f`` at each interval's targets, shape ``(k,) + targets.shape``.
    """
    C = _chebyshev_transform(PANEL_NODES)
    xc, _ = chebyshev_lagrange(np.zeros(0), PANEL_NODES)
    todo = []
    for j, (lo, hi) in enumerate(intervals):
        near, far = sorted((abs(lo), abs(hi)))
        count = max(1, int(np.ceil(np.log(far / near) / np.log(ratio) - 1e-9)))
        ends = near * ratio ** np.arange(count + 1)
        ends[-1] = far
        ends = np.sign(lo) * ends
        todo += [(j, min(a, b), max(a, b), 0) for a, b in zip(ends[:-1], ends[1:])]
    scale = [None] * len(intervals)
    done, direct = [], []
    while todo:
        x = np.concatenate([a + (b - a) * xc for _, a, b, _ in todo])
        values = np.asarray(f(x))
        values = values.reshape(-1, len(todo), PANEL_NODES)
        for j in range(len(intervals)):
            mine = [k for k, t in enumerate(todo) if t[0] == j]
            if mine:
                top = np.abs(values[:, mine]).max(axis=(1, 2))
                scale[j] = np.maximum(1.0, top if scale[j] is None else
                                      np.maximum(scale[j], top))
        tails = np.abs(np.einsum("mp,kqp->kqm", C[-_TAIL:], values)).max(axis=2)
        refine = []
        for k, (j, a, b, depth) in enumerate(todo):
            if np.all(tails[:, k] <= tol * scale[j]):
                done.append((j, a, b, values[:, k]))
            elif depth < _PANEL_DEPTH:
                m = 0.5 * (a + b)
                refine += [(j, a, m, depth + 1), (j, m, b, depth + 1)]
            else:
                direct.append((j, a, b))
        todo = refine
    out = []
    for j, u in enumerate(targets):
        u = np.asarray(u, dtype=float)
        flat = u.ravel()
        mine = sorted([(a, b, vals) for jj, a, b, vals in done if jj == j]
                      + [(a, b, None) for jj, a, b in direct if jj == j],
                      key=lambda t: t[0])
        starts = np.array([t[0] for t in mine])
        at = np.clip(np.searchsorted(starts, flat, side="right") - 1, 0, len(mine) - 1)
        lo, hi = starts[at], np.array([t[1] for t in mine])[at]
        _, L = chebyshev_lagrange((flat - lo) / (hi - lo), PANEL_NODES)
        resolved = np.array([t[2] is not None for t in mine])
        first = next(t[2] for t in mine if t[2] is not None) if resolved.any() else None
        stack = np.stack([t[2] if t[2] is not None else np.zeros_like(first)
                          for t in mine]) if first is not None else None
        res = None if stack is None else np.einsum("pkn,pn->kp", stack[at], L)
        by_hand = ~resolved[at]
        if np.any(by_hand):
            vals = np.asarray(f(flat[by_hand]))
            if res is None:
                res = np.zeros((vals.shape[0], flat.size), dtype=vals.dtype)
            res[:, by_hand] = vals
        out.append(res.reshape((res.shape[0],) + u.shape))
    return out
