"""Local polynomial interpolation of samples: the interpolant on the samples nearest a
point, and an estimate of its error (a ray's samples read at any Peclet number)."""

from __future__ import annotations

import numpy as np

__all__ = ["STENCIL", "interpolation_error", "lagrange", "local", "nearest"]

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
