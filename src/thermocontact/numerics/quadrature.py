"""Gauss–Chebyshev rules for the two kinds of unknown, and their series.

The pressure is bounded at both contact edges, ``p(r) = sqrt(1 - r^2) phi(r)``; the
heat-flux difference is singular at both, ``q'(r) = psi(r) / sqrt(1 - r^2)``
(derivation section 6).  Each weight function has its own Gauss rule and its own
set of collocation points at which the Cauchy principal value of the rule is exact
(Erdogan, Gupta and Cook 1973).  Nodes are returned in ascending order.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .cache import small_cache

__all__ = [
    "BoundedRule",
    "SingularRule",
    "bounded_rule",
    "singular_rule",
    "u_series_coefficients",
    "u_series_value",
    "t_coefficient_matrix",
    "t_series_coefficients",
    "u_coefficient_matrix",
]


@dataclass(frozen=True)
class BoundedRule:
    """Gauss rule for ``integral sqrt(1 - r^2) phi(r) dr`` over ``[-1, 1]``.

    Attributes
    ----------
    nodes : ndarray, shape (n,)
        ``r_i = cos(pi i / (n + 1))``, the zeros of ``U_n``.
    weights : ndarray, shape (n,)
        ``W_i = pi (1 - r_i^2) / (n + 1)``; they sum to ``pi / 2``.
    collocation : ndarray, shape (n + 1,)
        ``s_k = cos(pi (2k - 1) / (2n + 2))``, the zeros of ``T_{n+1}``, where
        ``sum_i W_i phi(r_i) / (pi (s_k - r_i)) = (1/pi) PV integral
        sqrt(1 - r^2) phi(r) / (s_k - r) dr`` exactly for ``deg phi < 2n + 1``.
    """

    nodes: np.ndarray
    weights: np.ndarray
    collocation: np.ndarray

    @property
    def edge_factor(self):
        """``sqrt(1 - r_i^2)`` at the nodes."""
        return np.sqrt(1.0 - self.nodes**2)


@dataclass(frozen=True)
class SingularRule:
    """Gauss rule for ``integral psi(r) / sqrt(1 - r^2) dr`` over ``[-1, 1]``.

    Attributes
    ----------
    nodes : ndarray, shape (n,)
        ``r_i = cos(pi (2i - 1) / (2n))``, the zeros of ``T_n``.
    weights : ndarray, shape (n,)
        ``pi / n`` each; they sum to ``pi``.
    collocation : ndarray, shape (n - 1,)
        ``s_k = cos(pi k / n)``, the zeros of ``U_{n-1}``, where the rule's
        Cauchy principal value is exact for ``deg psi < 2n``.
    """

    nodes: np.ndarray
    weights: np.ndarray
    collocation: np.ndarray

    @property
    def edge_factor(self):
        """``sqrt(1 - r_i^2)`` at the nodes."""
        return np.sqrt(1.0 - self.nodes**2)


def bounded_rule(n: int) -> BoundedRule:
    """Gauss–Chebyshev rule of the second kind with its collocation points.

    Parameters
    ----------
    n : int
        Number of nodes, ``n >= 1``.

    Returns
    -------
    BoundedRule
    """
    theta = np.pi * np.arange(n, 0, -1) / (n + 1)
    nodes = np.cos(theta)
    weights = np.pi * np.sin(theta) ** 2 / (n + 1)
    colloc = np.cos(np.pi * (2 * np.arange(n + 1, 0, -1) - 1) / (2 * n + 2))
    return BoundedRule(nodes, weights, colloc)


def singular_rule(n: int) -> SingularRule:
    """Gauss–Chebyshev rule of the first kind with its collocation points.

    Parameters
    ----------
    n : int
        Number of nodes, ``n >= 2``.

    Returns
    -------
    SingularRule
    """
    nodes = np.cos(np.pi * (2 * np.arange(n, 0, -1) - 1) / (2 * n))
    weights = np.full(n, np.pi / n)
    colloc = np.cos(np.pi * np.arange(n - 1, 0, -1) / n)
    return SingularRule(nodes, weights, colloc)


@small_cache(32)
def u_coefficient_matrix(n: int):
    """Matrix taking ``phi`` at the U-nodes to its ``U``-coefficients (read-only).

    ``M[j, i] = (2 / (n + 1)) sin(theta_i) sin((j + 1) theta_i)``.
    """
    theta = np.pi * np.arange(n, 0, -1) / (n + 1)
    j = np.arange(1, n + 1)[:, None]
    m = (2.0 / (n + 1)) * np.sin(j * theta[None, :]) * np.sin(theta)[None, :]
    m.flags.writeable = False
    return m


@small_cache(32)
def t_coefficient_matrix(n: int):
    """Matrix taking ``psi`` at the T-nodes to its ``T``-coefficients (read-only).

    ``M[j, i] = (2 - [j = 0]) / n * T_j(r_i)``.
    """
    theta = np.pi * (2 * np.arange(n, 0, -1) - 1) / (2 * n)
    m = (2.0 / n) * np.cos(np.arange(n)[:, None] * theta[None, :])
    m[0] *= 0.5
    m.flags.writeable = False
    return m


def u_series_coefficients(values):
    """Coefficients ``a_j`` of ``phi = sum_j a_j U_j`` from values at the U-nodes.

    Discrete orthogonality of ``U_j`` on the zeros of ``U_n``:
    ``a_j = (2 / (n + 1)) sum_i sin(theta_i) sin((j + 1) theta_i) phi(r_i)``.

    Parameters
    ----------
    values : ndarray, shape (n, ...)
        ``phi`` at :func:`bounded_rule` nodes (ascending).

    Returns
    -------
    ndarray, shape (n, ...)
    """
    values = np.asarray(values, dtype=float)
    return np.tensordot(u_coefficient_matrix(values.shape[0]), values, axes=(1, 0))


def u_series_value(coefficients, s):
    """Evaluate ``sum_j a_j U_j(s)`` by Clenshaw's recurrence (stable on [-1, 1]).

    Parameters
    ----------
    coefficients : ndarray, shape (n,)
        Real (the recurrence runs in place in ``s``'s real arrays).
    s : array_like

    Returns
    -------
    ndarray, shape of ``s``
    """
    s = np.asarray(s, dtype=float)
    two_s = 2.0 * s
    b1 = np.zeros_like(s)
    b2 = np.zeros_like(s)
    for a in coefficients[::-1]:
        # b1 <- (a + 2 s b1) - b2, in that order, in place.
        b = two_s * b1
        b += a
        b -= b2
        b1, b2 = b, b1
    return b1


def t_series_coefficients(values):
    """Coefficients ``b_j`` of ``psi = sum_j b_j T_j`` from values at the T-nodes.

    ``b_j = (2 - [j = 0]) / n * sum_i T_j(r_i) psi(r_i)`` (discrete orthogonality on
    the zeros of ``T_n``).

    Parameters
    ----------
    values : ndarray, shape (n, ...)
        ``psi`` at :func:`singular_rule` nodes (ascending).

    Returns
    -------
    ndarray, shape (n, ...)
    """
    values = np.asarray(values, dtype=float)
    return np.tensordot(t_coefficient_matrix(values.shape[0]), values, axes=(1, 0))
