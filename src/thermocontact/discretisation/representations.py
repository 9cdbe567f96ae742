"""How a method represents the unknowns: evaluation and the Cauchy integrals outside.

The solver and the validity checks need, from a discrete solution ``phi, psi``
(nodal values), the factors ``phi(s)``, ``psi(s)`` anywhere in ``[-1, 1]``, the
Hilbert transform of the pressure at the edges and its integral beyond them (the
Cauchy part of the gap, derivation D20-D21).  :class:`ChebyshevBasis` does this in
closed form for the polynomial representation of derivation section 6;
:class:`GradedBasis` by moments for the representation of section 12.
"""

from __future__ import annotations

import numpy as np

from ..numerics import edge_graded as graded
from ..numerics.quadrature import t_series_coefficients, u_series_coefficients, u_series_value

__all__ = ["ChebyshevBasis", "GradedBasis", "CHEBYSHEV"]


def _cauchy_outside_integral(m, tt):
    """``I_m = integral_1^{1+tt} w(y)^m dy`` with ``w = y - sqrt(y^2 - 1)``, ``tt >= 0``.

    ``w^m = (1/pi) integral sqrt(1 - r^2) U_{m-1}(r) / (y - r) dr`` for ``y > 1``;
    with ``y = cosh u``: ``I_m = (1/2) integral_0^U (e^{-(m-1)u} - e^{-(m+1)u}) du``.
    The distance ``tt`` past the edge is the argument, not ``1 + tt``, so that
    ``U = arccosh(1 + tt)`` keeps full relative accuracy next to the edge.

    Parameters
    ----------
    m : ndarray of int, shape (k,)
    tt : ndarray, shape (j,)

    Returns
    -------
    ndarray, shape (j, k)
    """
    u = np.log1p(tt + np.sqrt(tt * (tt + 2.0)))[:, None]
    m = np.asarray(m)[None, :]
    mm1 = np.where(m > 1, m - 1, 1)
    first = np.where(m > 1, -np.expm1(-mm1 * u) / mm1, u)
    second = -np.expm1(-(m + 1) * u) / (m + 1)
    return 0.5 * (first - second)


class ChebyshevBasis:
    """``phi`` as a ``U``-series, ``psi`` as a ``T``-series (derivation section 6)."""

    def phi_at(self, phi, s):
        """``phi(s)``, ``-1 <= s <= 1``."""
        return u_series_value(u_series_coefficients(phi), np.asarray(s, dtype=float))

    def phi_samples(self, phi, count):
        """``count`` Chebyshev points ``s`` of ``[-1, 1]`` (edges included) and ``phi(s)``."""
        s = np.cos(np.linspace(np.pi, 0.0, count))
        return s, self.phi_at(phi, s)

    def psi_at(self, psi, s):
        """``psi(s)``, ``-1 <= s <= 1``."""
        return np.polynomial.chebyshev.chebval(np.asarray(s, dtype=float),
                                               t_series_coefficients(psi))

    def psi_edges(self, psi):
        """``(psi(-1), psi(1))``."""
        b = t_series_coefficients(psi)
        return np.array([np.sum(b * (-1.0) ** np.arange(b.size)), np.sum(b)])

    def cauchy_edges(self, blocks, phi):
        """``(1/pi) integral p(r)/(s - r) dr`` at ``s = -1`` and ``s = 1``.

        ``(1/pi) integral sqrt(1-r^2) U_j(r)/(s - r) dr = T_{j+1}(s)``: ``(-1)^{j+1}``
        and 1 at the edges.
        """
        a = u_series_coefficients(phi)
        sign = np.where(np.arange(a.size) % 2 == 0, -1.0, 1.0)
        return float((sign * a).sum()), float(a.sum())

    def cauchy_outside(self, blocks, phi, tt, right: bool):
        """``integral_1^{1+tt} H(y) dy`` (right) or ``integral_{-1-tt}^{-1} H(y) dy`` (left).

        ``H(y) = (1/pi) integral p(r)/(y - r) dr``, in closed form term by term.
        """
        a = u_series_coefficients(phi)
        m = np.arange(1, a.size + 1)
        if right:
            return _cauchy_outside_integral(m, tt) @ a
        sign_m = np.where(m % 2 == 1, -1.0, 1.0)
        return _cauchy_outside_integral(m, tt) @ (sign_m * a)


CHEBYSHEV = ChebyshevBasis()


class GradedBasis:
    """``phi`` and ``psi`` as cosine series in ``tau`` (derivation section 12)."""

    def __init__(self, n: int):
        self.n = n
        self.to_cos = graded.coefficient_matrix(n)

    def phi_at(self, phi, s):
        return graded.cosine_value(self.to_cos @ phi, graded.tau_of(s))

    def phi_samples(self, phi, count):
        """``count`` points equally spaced in ``tau`` (edges included) and ``phi`` there.

        Denser toward the edges than Chebyshev points, and no ``tau`` is inverted.
        """
        tau = np.linspace(np.pi, 0.0, count)
        return np.cos(graded.stretch(tau)), graded.cosine_value(self.to_cos @ phi, tau)

    def psi_at(self, psi, s):
        return graded.cosine_value(self.to_cos @ psi, graded.tau_of(s))

    def psi_edges(self, psi):
        b = self.to_cos @ psi
        return np.array([np.sum(b * (-1.0) ** np.arange(b.size)), np.sum(b)])

    def _row(self, blocks, key, kernel, points, scale=None, from_edge=False):
        key = ("graded", key, np.asarray(points, dtype=float).tobytes())
        if key not in blocks.cache:
            b, _ = graded.moments(kernel, points, self.n, scale=scale, from_edge=from_edge)
            blocks.cache[key] = (b @ self.to_cos) / np.pi
        return blocks.cache[key]

    def cauchy_edges(self, blocks, phi):
        # p ~ sqrt(1 -+ r) at the edge, so p/(s - r) is integrable there.
        row = self._row(blocks, "edges", lambda u: 1.0 / u, np.array([-1.0, 1.0]), scale=1.0)
        v = row @ phi
        return float(v[0]), float(v[1])

    def cauchy_outside(self, blocks, phi, tt, right: bool):
        # integral of (1/pi) p(r)/(y - r) over y: (1/pi) integral p(r) ln(...) dr,
        # with the kernel of e = 1 - r (right) or -(1 + r) (left), never of u - tt.
        tt = np.asarray(tt, dtype=float)
        col = tt[:, None]
        # In tau the kernels are smooth but at the edge itself, where the weight
        # vanishes like tau^8: no grading beyond that of a unit scale is needed.
        if right:  # ln((1 - r + tt)/(1 - r))
            row = self._row(blocks, "right", lambda e: np.log1p(col / e), 1.0 + tt,
                            scale=1.0, from_edge=True)
            return row @ phi
        # -ln((1 + r + tt)/(1 + r))
        row = self._row(blocks, "left", lambda e: np.log1p(col / -e), -1.0 - tt,
                        scale=1.0, from_edge=True)
        return -(row @ phi)
