"""How a method represents the unknowns and integrates kernels against them.

The pressure is ``p(r) = sqrt(1 - r^2) phi(r)`` and the heat-flux difference's
singular part ``q'(r) = psi(r) / sqrt(1 - r^2)`` (derivation section 6).  A
representation carries ``phi`` and ``psi`` by their values at ``n`` nodes and
provides

* the rules ``integral p dr = w_p . phi`` and ``integral q' dr = w_q . psi``;
* the row operators ``integral K(s - r) p(r) dr = I_p(s) . phi`` and
  ``integral K(s - r) q'(r) dr = I_q(s) . psi`` for any kernel, the principal
  value of ``1/u`` and the step ``sgn u`` (the moments every operator of the
  contact and heat equations is made of, :mod:`.operator`);
* the points where the equations are collocated, and the projections on the
  equations' range spaces;
* ``phi``, ``psi`` anywhere, and the Hilbert transform of the pressure at and
  beyond the edges (the Cauchy part of the gap, derivation D20-D21).

Three representations:

* :class:`ChebyshevSampled`: the paper's, ``phi`` a ``U``-series and ``psi`` a
  ``T``-series, every kernel sampled at the Gauss–Chebyshev nodes (section 6;
  low algebraic order);
* :class:`Chebyshev`: the same series, every kernel integrated exactly against
  them (section 10: closed forms for ``1/u`` and ``sgn``, moments to rounding by
  :func:`~thermocontact.numerics.moment_engine.chebyshev_moments` otherwise);
* :class:`EdgeGraded`: cosine series in the edge-graded variable ``tau`` (section
  12), every integral a moment by
  :func:`~thermocontact.numerics.moment_engine.moments`.

A representation is identified by its class and ``n``: it pickles as that pair,
and what it computes is kept in per-process caches bounded in bytes
(:mod:`thermocontact.numerics.cache`).
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import cached_property

import numpy as np

from ..numerics import moment_engine as graded
from ..numerics.batched import stacked
from ..numerics.cache import BoundedCache, small_cache
from ..numerics.moments import sgn_moments
from ..numerics.quadrature import (bounded_rule, singular_rule, t_coefficient_matrix,
                                   t_series_coefficients, u_coefficient_matrix,
                                   u_series_coefficients, u_series_value)

__all__ = ["Chebyshev", "ChebyshevSampled", "EdgeGraded", "NodeRule", "Representation",
           "projection_columns", "projection_nodes", "range_projections"]

#: Row operators that depend only on a representation and a set of points (the
#: validity checks and the temperatures evaluate the same points again and again).
ROWS = BoundedCache("row operators", 128 * 2**20)
#: :class:`EdgeGraded` keeps its Cauchy and sign rows below this ``n`` (a map's lines
#: reach 128 at most; at 256 the three pairs of an assembly would hold 6 MB beside the
#: solve at 1024 whose levels are 256 and 512, which is to stay below 200 MB).
KEPT_MOMENTS_N = 256


def _log_abs(u):
    """``ln|u|``, the kernel of :meth:`Representation.logarithm`."""
    return np.log(np.abs(u))


#: How :meth:`Representation.logarithm` integrates its kernel.
_LOGARITHMIC = {"scale": 1.0, "logarithmic": True}


def _reciprocal(u):
    """``1/u``, the kernel of :meth:`EdgeGraded.cauchy` (its principal value)."""
    return 1.0 / u


def _read_only(arrays):
    """``arrays`` (a tuple), each made read-only: shared from a cache."""
    for a in arrays:
        a.flags.writeable = False
    return arrays


@dataclass(frozen=True)
class NodeRule:
    """Nodes of one unknown and the weights of its integral over ``[-1, 1]``.

    Attributes
    ----------
    nodes : ndarray, shape (n,)
        Ascending.
    weights : ndarray, shape (n,)
        ``integral p dr = weights @ phi`` (pressure) or
        ``integral q' dr = weights @ psi`` (flux).
    edge_factor : ndarray, shape (n,)
        ``sqrt(1 - r_i^2)``, formed without cancellation next to an edge.
    """

    nodes: np.ndarray
    weights: np.ndarray
    edge_factor: np.ndarray


#: Largest table of sample cosines (points times n) kept in :data:`ROWS`.
SAMPLE_TABLE_ENTRIES = 2**20

#: Quadrature points per unknown of the Galerkin projections.
OVERSAMPLING = 2


@small_cache(16)
def range_projections(n: int):
    """Points and projections of the two equations on their range spaces.

    On ``m = 2n`` midpoints ``x_k = pi (k - 1/2)/m`` (descending), the rows
    ``(pi/m) cos(j x_k)``, ``j <= n``, project a function of ``x`` on ``cos(j x)``
    (the contact equation: ``T_j`` with weight ``1/sqrt(1-s^2)`` when ``s = cos x``),
    and ``(pi/m) sin((j + 1) x_k) sin x_k``, ``j <= n - 2``, on
    ``sin((j + 1) x) sin x`` (the heat equation: ``U_j`` with weight
    ``sqrt(1-s^2)``).  The Chebyshev representations take ``x = t = arccos s``,
    the edge-graded one ``x = tau`` (derivation sections 10 and 12).

    Returns
    -------
    x : ndarray, shape (m,)
    p1 : ndarray, shape (n + 1, m)
    p2 : ndarray, shape (n - 1, m)
    """
    x = projection_nodes(n)
    p1, p2 = projection_columns(n, x)
    for a in (x, p1, p2):
        a.flags.writeable = False
    return x, p1, p2


def projection_nodes(n: int):
    """The ``2n`` midpoints ``x_k = pi (k - 1/2)/(2n)``, descending, of
    :func:`range_projections`."""
    m = OVERSAMPLING * n
    return np.pi * (np.arange(m, 0, -1) - 0.5) / m


def projection_columns(n: int, x):
    """The columns of :func:`range_projections`' ``p1`` and ``p2`` at some of its
    nodes ``x`` (element by element the same numbers), so that a large projection can
    be formed a block of points at a time."""
    w = np.pi / (OVERSAMPLING * n)
    p1 = w * np.cos(np.arange(n + 1)[:, None] * x[None, :])
    p2 = w * np.sin((np.arange(n - 1)[:, None] + 1) * x[None, :]) * np.sin(x)[None, :]
    return p1, p2


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


def _key(points) -> bytes:
    return np.ascontiguousarray(points, dtype=float).tobytes()


class Representation:
    """Interface and shared behaviour; see the module docstring.

    Parameters
    ----------
    n : int
        Unknowns per function.
    """

    #: Short name used in records.
    name = ""
    #: Edge exponent of the pressure at ``s = 1`` (``1 - alpha`` at ``s = -1``):
    #: ``p = w phi`` with ``w = (1 - s)^alpha (1 + s)^(1 - alpha)``.
    alpha = 0.5

    def __init__(self, n: int):
        self.n = int(n)

    # Identity: class, n (and the edge exponent where it is not 1/2).  Everything
    # else is recomputed or cached per process.
    def _identity(self):
        return (self.n,) if self.alpha == 0.5 else (self.n, self.alpha)

    def __reduce__(self):
        return (type(self), self._identity())

    def __eq__(self, other):
        return type(self) is type(other) and self._identity() == other._identity()

    def __hash__(self):
        return hash((type(self).__name__,) + self._identity())

    def __repr__(self):
        extra = "" if self.alpha == 0.5 else f", alpha={self.alpha!r}"
        return f"{type(self).__name__}(n={self.n}{extra})"

    def logarithm(self, s, aux=None):
        """Row operators ``(I_p, I_q)`` of ``integral ln|s - r| (p, q')(r) dr``: a
        stationary half-plane's surface temperature kernel (D12), the same for every
        ``Pe``."""
        return self.integrate(_log_abs, np.asarray(s, dtype=float), aux=aux, **_LOGARITHMIC)

    def prolong(self, values, finer):
        """``finer``'s nodal values (m, finer.n) of the functions whose nodal values here
        are the rows of ``values`` (m, n) (``phi`` or ``psi``), or None where the finer
        representation does not hold them exactly (derivation section 12)."""
        return None

    def rows(self, key, build, exponent=True):
        """A row operator of this representation, cached under ``key`` (with
        ``exponent=False``, one that is the same for every edge exponent)."""
        return ROWS.get(self._rows_key(key, exponent), build)

    def _rows_key(self, key, exponent=True):
        """``key`` in :data:`ROWS`: with this representation's identity, or without its
        edge exponent (``exponent=False``: a row operator of the flux, the same for
        every exponent)."""
        identity = self._identity() if exponent else (self.n,)
        return (type(self).__name__,) + identity + tuple(key)

    # Quantities every representation derives the same way.
    def pressure_weight(self, s):
        """``w(s) = (1 - s)^alpha (1 + s)^(1 - alpha)``, ``sqrt(1 - s^2)`` when
        ``alpha = 1/2``: ``p = w phi``."""
        return graded.pressure_weight(s, self.alpha)

    def pressure_at(self, phi, s):
        """``p(s) = w(s) phi(s)`` on ``[-1, 1]``."""
        s = np.asarray(s, dtype=float)
        return self.pressure_weight(s) * self.phi_at(phi, s)

    def pressure_matrix(self, s):
        """The matrix ``M`` with ``M @ phi = p(s)``, cached for the points ``s``
        (fixed points where many solutions are evaluated)."""
        s = np.asarray(s, dtype=float)
        return self.rows(("pressure", s.tobytes()), lambda: self._pressure_matrix(s))

    def _pressure_matrix(self, s):
        return np.column_stack([self.pressure_at(e, s) for e in np.eye(self.n)])

    def pressure_rows(self, s, aux=None):
        """``M`` with ``M @ phi = p(s)`` (``aux``, the points' own coordinate, unused)."""
        return self.pressure_matrix(s)

    def phi_samples_many(self, phi, count):
        """:meth:`phi_samples` of each row of ``phi`` (m, n): the points and an array
        (m, count)."""
        rows = [self.phi_samples(f, count) for f in phi]
        return rows[0][0], np.stack([f for _, f in rows])

    # The checks of a grid line evaluate many solutions at once: each row of ``phi``
    # (m, n) as the single evaluation gives it.
    def psi_edges_many(self, psi):
        """:meth:`psi_edges` of each row of ``psi`` (m, n): shape (m, 2)."""
        return np.array([self.psi_edges(f) for f in psi]).reshape(-1, 2)

    def cauchy_edges_many(self, phi):
        """:meth:`cauchy_edges` of each row of ``phi`` (m, n): shape (m, 2)."""
        return np.array([self.cauchy_edges(f) for f in phi]).reshape(-1, 2)

    def cauchy_outside_many(self, phi, tt, right: bool):
        """:meth:`cauchy_outside` of each row of ``phi`` (m, n): shape (m, tt.size)."""
        return np.array([self.cauchy_outside(f, tt, right) for f in phi]).reshape(
            len(phi), np.size(tt))


class _ChebyshevSeries(Representation):
    """``phi`` as a ``U``-series, ``psi`` as a ``T``-series (derivation section 6)."""

    @cached_property
    def pressure_rule(self) -> NodeRule:
        r = bounded_rule(self.n)
        return NodeRule(r.nodes, r.weights, r.edge_factor)

    @cached_property
    def flux_rule(self) -> NodeRule:
        r = singular_rule(self.n)
        return NodeRule(r.nodes, r.weights, r.edge_factor)

    def collocation_points(self):
        """Contact equation at the zeros of ``T_{n+1}``, heat equation at those of
        ``U_{n-1}``: where the Gauss rules' principal values are exact.

        Returns
        -------
        (s_contact, aux_contact), (s_heat, aux_heat)
        """
        return (bounded_rule(self.n).collocation, None), (singular_rule(self.n).collocation, None)

    def projection_points(self, x):
        """``s = cos x`` of the projections' points ``x = t``."""
        return np.cos(x), None

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

    def cauchy_edges(self, phi):
        """``(1/pi) integral p(r)/(s - r) dr`` at ``s = -1`` and ``s = 1``.

        ``(1/pi) integral sqrt(1-r^2) U_j(r)/(s - r) dr = T_{j+1}(s)``: ``(-1)^{j+1}``
        and 1 at the edges.
        """
        a = u_series_coefficients(phi)
        sign = np.where(np.arange(a.size) % 2 == 0, -1.0, 1.0)
        return float((sign * a).sum()), float(a.sum())

    def cauchy_outside(self, phi, tt, right: bool):
        """``integral_1^{1+tt} H(y) dy`` (right) or ``integral_{-1-tt}^{-1} H(y) dy`` (left).

        ``H(y) = (1/pi) integral p(r)/(y - r) dr``, in closed form term by term.
        """
        a = u_series_coefficients(phi)
        m = np.arange(1, a.size + 1)
        if right:
            return _cauchy_outside_integral(m, tt) @ a
        sign_m = np.where(m % 2 == 1, -1.0, 1.0)
        return _cauchy_outside_integral(m, tt) @ (sign_m * a)


class Chebyshev(_ChebyshevSeries):
    """Chebyshev series, every kernel integrated exactly against them (section 10)."""

    name = "chebyshev"

    def _maps(self):
        return u_coefficient_matrix(self.n), t_coefficient_matrix(self.n)

    def integrate(self, kernel, s, *, scale=None, logarithmic=False, aux=None):
        """Row operators ``(I_p, I_q)`` of ``integral K(s - r) (p, q')(r) dr``.

        By :func:`~thermocontact.numerics.moment_engine.chebyshev_moments`; ``scale`` and
        ``logarithmic`` describe the kernel as there.

        Returns
        -------
        ndarray, shape (k, n), twice
        """
        b, t = graded.chebyshev_moments(kernel, np.asarray(s, dtype=float), self.n, scale=scale,
                              logarithmic=logarithmic)
        to_u, to_t = self._maps()
        return b @ to_u, t @ to_t

    def cauchy(self, s, aux=None):
        """Principal values of ``integral (p, q')(r) / (s - r) dr``, ``|s| < 1``.

        ``PV integral sqrt(1-r^2) U_j/(s - r) dr = pi T_{j+1}(s)`` and
        ``PV integral T_j/(sqrt(1-r^2)(s - r)) dr = -pi U_{j-1}(s)``.
        """
        th = np.arccos(np.asarray(s, dtype=float))[:, None]
        j = np.arange(self.n)[None, :]
        cb = np.pi * np.cos((j + 1) * th)
        cs = -np.pi * np.sin(j * th) / np.sin(th)
        to_u, to_t = self._maps()
        return cb @ to_u, cs @ to_t

    def sign(self, s, aux=None):
        """``integral sgn(s - r) (p, q')(r) dr`` in closed form (``sgn_moments``)."""
        b, t = sgn_moments(np.asarray(s, dtype=float), self.n)
        to_u, to_t = self._maps()
        return b @ to_u, t @ to_t


class ChebyshevSampled(_ChebyshevSeries):
    """The paper's scheme: Chebyshev series, kernels sampled at the nodes (section 6).

    The Cauchy kernel's Gauss sum is exact at the collocation points; the step
    kernels and the logarithm of the cylinder's temperature gradient are not,
    which limits the convergence to low algebraic order.
    """

    name = "chebyshev-sampled"

    def integrate(self, kernel, s, *, scale=None, logarithmic=False, aux=None):
        s = np.asarray(s, dtype=float)[:, None]
        pr, fr = bounded_rule(self.n), singular_rule(self.n)
        return (pr.weights[None, :] * kernel(s - pr.nodes[None, :]),
                fr.weights[None, :] * kernel(s - fr.nodes[None, :]))

    def cauchy(self, s, aux=None):
        return self.integrate(lambda u: 1.0 / u, s)

    def sign(self, s, aux=None):
        return self.integrate(np.sign, s)


class EdgeGraded(Representation):
    """Cosine series in the edge-graded variable ``tau`` (derivation section 12).

    ``r = cos T(tau)``, ``T(tau) = tau - sin(2 tau)/2``; the unknowns are carried by
    their values at ``tau_i = pi (i - 1/2)/n``.  Every integral, the Cauchy ones
    included, is a moment by :func:`~thermocontact.numerics.moment_engine.moments`.
    """

    name = "edge-graded"

    def __init__(self, n: int, alpha=0.5):
        super().__init__(n)
        # The pressure's edge exponents (section 5c): 1/2 at both edges unless the
        # Dundurs term makes them alpha and 1 - alpha.
        self.alpha = float(alpha)
        if not 0.0 < self.alpha < 1.0:
            raise ValueError(f"alpha must lie in (0, 1), got {alpha!r}")
        self._cmap = graded.graded_map(self.alpha)

    @property
    def to_cos(self):
        """Matrix taking nodal values to cosine coefficients in ``tau`` (read-only)."""
        return t_coefficient_matrix(self.n)

    def _rule(self, which):
        t = graded.stretch(graded.nodes(self.n))
        r, sin_t = np.cos(t), np.sin(t)
        wb, ws = graded.weight_integrals(self.n, self.alpha)
        w = (wb if which == 0 else ws) @ self.to_cos
        if which == 0 and self.alpha != 0.5:
            # w(cos t) from the half-angles, without cancellation next to an edge.
            a, c = np.sin(0.5 * t), np.cos(0.5 * t)
            sin_t = 2.0 * a ** (2.0 * self.alpha) * c ** (2.0 - 2.0 * self.alpha)
        return NodeRule(r, w, sin_t)

    @cached_property
    def pressure_rule(self) -> NodeRule:
        return self._rule(0)

    @cached_property
    def flux_rule(self) -> NodeRule:
        return self._rule(1)

    def collocation_points(self):
        """Contact equation at ``tau = pi (k - 1/2)/(n + 1)``, heat equation at
        ``tau = pi k / n``: the analogues in ``tau`` of the zeros of ``T_{n+1}`` and
        ``U_{n-1}``.  Each point comes with its ``tau`` (``aux``)."""
        def points(m, shift):
            k = np.arange(m, 0, -1) if shift else np.arange(m - 1, 0, -1)
            tau = np.pi * (k - shift) / m
            return np.cos(graded.stretch(tau)), tau
        return points(self.n + 1, 0.5), points(self.n, 0.0)

    def projection_points(self, x):
        """``s = cos T(x)`` of the projections' points ``x = tau``, and ``tau``."""
        return np.cos(graded.stretch(x)), x

    def integrate(self, kernel, s, *, scale=None, logarithmic=False, aux=None,
                  from_edge=False):
        """Row operators ``(I_p, I_q)``; ``aux`` is the points' ``tau`` (keeps points
        within rounding of an edge apart from it), ``from_edge`` as in
        :func:`~thermocontact.numerics.moment_engine.moments`."""
        return self._moments(kernel, s, aux, scale=scale, logarithmic=logarithmic,
                             from_edge=from_edge)

    def _moments(self, kernel, s, aux, pressure=True, flux=True, **how):
        """:meth:`integrate`'s row operators, the pressure's and the flux's each only
        where asked for (None otherwise); ``how`` as
        :func:`~thermocontact.numerics.moment_engine.moments` takes it."""
        b, q = graded.moments(kernel, np.asarray(s, dtype=float), self.n, tau=aux,
                              cmap=self._cmap, pressure=pressure, flux=flux, **how)
        to_cos = self.to_cos
        return (None if b is None else b @ to_cos, None if q is None else q @ to_cos)

    def prolong(self, values, finer):
        """A cosine series of ``n`` terms in ``tau`` is one of any ``m >= n`` terms: its
        values at ``finer``'s nodes are the series summed there (Clenshaw's recurrence,
        no matrix), exact but for rounding (an edge-graded ``finer`` of the same
        exponent and ``m >= n``; else None)."""
        if type(finer) is not type(self) or finer.alpha != self.alpha or finer.n < self.n:
            return None
        coefficients = stacked(self.to_cos, values).T  # (n, m), each row as alone
        return graded.cosine_value(coefficients, graded.nodes(finer.n))  # (m, finer.n)

    def cauchy(self, s, aux=None):
        return self._kept("cauchy", s, aux, _reciprocal, scale=1.0, cauchy=True)

    def sign(self, s, aux=None):
        return self._kept("sign", s, aux, np.sign, scale=1.0)

    def logarithm(self, s, aux=None):
        return self._kept("logarithm", s, aux, _log_abs, **_LOGARITHMIC)

    def _kept(self, name, s, aux, kernel, **how):
        """The row operators of a kernel that depends on the points alone (``1/u``,
        ``sgn u``, ``ln|u|``), read-only, kept in the row-operator cache below
        :data:`KEPT_MOMENTS_N`: a map's lines assemble them at the same points for every
        ``Pe`` (a fifth of an assembly's time).

        The flux's rows are kept apart from the pressure's and without the edge
        exponent: a contact of another friction (another exponent, with the Dundurs
        term) forms the pressure's rows alone."""
        s = np.asarray(s, dtype=float)
        if self.n >= KEPT_MOMENTS_N:
            return self._moments(kernel, s, aux, **how)
        points = (s.tobytes(), None if aux is None else np.asarray(aux, float).tobytes())
        keys = (self._rows_key((name, "pressure") + points),
                self._rows_key((name, "flux") + points, exponent=False))
        held = [ROWS.find(key) for key in keys]
        missing = [h is None for h in held]
        if any(missing):
            made = self._moments(kernel, s, aux, *missing, **how)
            held = [h if h is not None else ROWS.get(key, lambda m=m: _read_only((m,))[0])
                    for h, key, m in zip(held, keys, made)]
        return tuple(held)

    def phi_at(self, phi, s):
        return graded.cosine_value(self.to_cos @ phi, graded.tau_of(s))

    def phi_samples(self, phi, count):
        """``count`` points equally spaced in ``tau`` (edges included) and ``phi`` there.

        Denser toward the edges than Chebyshev points, and no ``tau`` is inverted.
        """
        s, values = self.phi_samples_many(np.asarray(phi, dtype=float)[None, :], count)
        return s, values[0]

    def phi_samples_many(self, phi, count):
        """:meth:`phi_samples` of each row of ``phi`` (m, n): the points and an array
        (m, count), the cosine series summed at the samples by a table of
        ``cos(j tau_k)``, the rows as stacked products
        (:func:`~thermocontact.numerics.batched.stacked`: the same whatever their
        number).  The table is kept for reuse up to 2^20 entries (count 2049 up to
        n = 256); a larger one (17 MB at n = 1024) is formed a block of samples at a
        time and not kept."""
        tau = np.linspace(np.pi, 0.0, count)
        coefficients = stacked(self.to_cos, phi)

        def table(k):
            cosines = np.multiply.outer(tau[k], np.arange(self.n))
            return np.cos(cosines, out=cosines)  # in place
        if count * self.n <= SAMPLE_TABLE_ENTRIES:
            cosines = self.rows(("phi_samples", count), lambda: table(slice(None)),
                                exponent=False)
            return np.cos(graded.stretch(tau)), stacked(cosines, coefficients)
        step = max(1, SAMPLE_TABLE_ENTRIES // (8 * self.n))
        values = np.concatenate([stacked(table(slice(i, i + step)), coefficients)
                                 for i in range(0, count, step)], axis=1)
        return np.cos(graded.stretch(tau)), values

    def _pressure_matrix(self, s):
        # phi(s) = sum_j (to_cos @ phi)_j cos(j tau(s)): one inversion of tau for all j.
        return (self.pressure_weight(s)[:, None]
                * graded.cosine_value(self.to_cos, graded.tau_of(s)).T)

    def pressure_rows(self, s, aux=None):
        """``M`` with ``M @ phi = p(s)``; with ``aux``, the points' ``tau``, no ``tau`` is
        inverted (the free term of the contact equation at its own points)."""
        if aux is None:
            return self.pressure_matrix(s)
        basis = np.cos(np.outer(np.asarray(aux, dtype=float), np.arange(self.n)))
        return self.pressure_weight(s)[:, None] * (basis @ self.to_cos)

    def psi_at(self, psi, s):
        return graded.cosine_value(self.to_cos @ psi, graded.tau_of(s))

    def flux_rows(self, s, aux):
        """``M`` with ``M @ psi = q'(s) = psi(s)/sqrt(1 - s^2)`` at interior points given
        with their ``tau`` (``aux``): no ``tau`` inverted, ``sqrt(1 - s^2) = sin T(tau)``."""
        aux = np.asarray(aux, dtype=float)
        basis = np.cos(np.outer(aux, np.arange(self.n)))
        return (basis @ self.to_cos) / np.sin(graded.stretch(aux))[:, None]

    def psi_edges(self, psi):
        return self.psi_edges_many(np.asarray(psi, dtype=float)[None, :])[0]

    def psi_edges_many(self, psi):
        # psi(tau = pi) and psi(0): the cosine series' alternating and plain sums.
        edges = self.rows(("psi edges",), lambda: np.vstack(
            [(-1.0) ** np.arange(self.n), np.ones(self.n)]) @ self.to_cos, exponent=False)
        return stacked(edges, psi)

    def _pressure_row(self, key, kernel, points, from_edge=False):
        points = np.asarray(points, dtype=float)

        def build():
            b, _ = self._moments(kernel, points, None, flux=False, scale=1.0,
                                 from_edge=from_edge)
            return b / np.pi
        return self.rows((key, _key(points)), build)

    def cauchy_edges(self, phi):
        v = self.cauchy_edges_many(np.asarray(phi, dtype=float)[None, :])[0]
        return float(v[0]), float(v[1])

    def cauchy_edges_many(self, phi):
        # p ~ sqrt(1 -+ r) at the edge, so p/(s - r) is integrable there.
        return stacked(self._pressure_row("edges", lambda u: 1.0 / u, [-1.0, 1.0]), phi)

    def cauchy_outside(self, phi, tt, right: bool):
        return self.cauchy_outside_many(np.asarray(phi, dtype=float)[None, :], tt, right)[0]

    def cauchy_outside_many(self, phi, tt, right: bool):
        # integral of (1/pi) p(r)/(y - r) over y: (1/pi) integral p(r) ln(...) dr,
        # with the kernel of e = 1 - r (right) or -(1 + r) (left), never of u - tt.
        # In tau the kernels are smooth but at the edge itself, where the weight
        # vanishes like tau^8: no grading beyond that of a unit scale is needed.
        tt = np.asarray(tt, dtype=float)
        col = tt[:, None]
        if right:  # ln((1 - r + tt)/(1 - r))
            row = self._pressure_row("right", lambda e: np.log1p(col / e), 1.0 + tt,
                                     from_edge=True)
            return stacked(row, phi)
        # -ln((1 + r + tt)/(1 + r))
        row = self._pressure_row("left", lambda e: np.log1p(col / -e), -1.0 - tt,
                                 from_edge=True)
        return -stacked(row, phi)
