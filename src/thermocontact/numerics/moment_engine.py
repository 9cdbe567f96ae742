"""The one moment engine: every integral of the unknowns, Cauchy ones included, as a
moment of the kernel, on the edge-graded or the identity coordinate map.

With ``r = cos t`` and ``t = T(tau) = tau - sin(2 tau)/2`` (a map of ``[0, pi]``
onto itself with ``T ~ (2/3) tau^3`` at both ends) the unknowns are expanded as

    phi(r) = p(r) / sqrt(1 - r^2) = sum_j a_j cos(j tau),
    psi(r) = q'(r) sqrt(1 - r^2) = sum_j b_j cos(j tau),

and carried by their values at ``tau_i = pi (i - 1/2) / n``.  The edge terms of
derivation section 8, ``|t|^3 ln|t|`` in ``phi`` and ``t^2 ln|t|`` in ``psi``,
become ``tau^9 ln tau`` and ``tau^6 ln tau``, and a boundary layer of width ``w``
in ``t`` one of width ``(3 w / 2)^(1/3)`` in ``tau``: where a Chebyshev series
converges at order 4 and must resolve ``sqrt(2 / c)`` at the edges, the cosine
series in ``tau`` converges much faster and resolves ``(2 / c)^(1/6)``
(derivation section 12).

No integral of these bases is known in closed form, the Cauchy ones included:
every operator is a moment computed by :func:`moments`, the construction of
:mod:`thermocontact.numerics.moments` carried over from ``t`` to ``tau``.
"""

from __future__ import annotations


import numpy as np

from . import moments as _moments
from .cache import BoundedCache, small_cache
from .moments import (LOG_LEVELS, gauss_legendre, inner_reference, chebyshev_lagrange,
                      levels_for, near_field, outer_panels, panel_rule)

__all__ = [
    "CoordinateMap",
    "GEOMETRY",
    "GRADED",
    "SMALL_GEOMETRY",
    "IDENTITY",
    "bounded_weight",
    "chebyshev_moments",
    "clear_geometry",
    "geometry_cache",
    "graded_map",
    "pressure_weight",
    "cosine_value",
    "moments",
    "nodes",
    "singular_weight",
    "stretch",
    "stretch_inverse",
    "tau_of",
]

#: ``(x - sin x)/x^3 = sum_k (-1)^k x^(2k) / (2k + 3)!``, ``k <= 6``: below 1e-18 relative
#: truncation for ``|x| < 1/2``.
_X_MINUS_SIN = [(-1.0) ** k / float(np.prod(np.arange(1, 2 * k + 4))) for k in range(7)]


def _x_minus_sin(x):
    """``x - sin x``, by its Taylor series for ``|x| < 1/2`` (no cancellation)."""
    x = np.asarray(x, dtype=float)
    small = np.abs(x) < 0.5
    if small.all():
        xs, out = x, None
    else:
        out = x - np.sin(x)
        if not small.any():
            return out
        xs = x[small]
    x2 = xs * xs
    series = np.full(xs.shape, _X_MINUS_SIN[-1])
    for c in _X_MINUS_SIN[-2::-1]:  # Horner in x^2
        series *= x2
        series += c
    series *= x2 * xs
    if out is None:
        return series
    out[small] = series
    return out


def stretch(tau):
    """``t = T(tau) = tau - sin(2 tau)/2`` on ``[0, pi]`` (odd about 0 and pi)."""
    tau = np.asarray(tau, dtype=float)
    near = np.minimum(tau, np.pi - tau)
    half = 0.5 * _x_minus_sin(2.0 * near)
    return np.where(tau <= 0.5 * np.pi, half, np.pi - half)


def stretch_derivative(tau):
    """``T'(tau) = 2 sin^2 tau``."""
    return 2.0 * np.sin(np.asarray(tau, dtype=float)) ** 2


def stretch_increment(tau, d):
    """``T(tau + d) - T(tau)`` without cancellation for small ``d``.

    ``d - cos(2 tau + d) sin d = 2 d sin^2(tau + d/2) + cos(2 tau + d) (d - sin d)``.
    """
    return 2.0 * d * np.sin(tau + 0.5 * d) ** 2 + np.cos(2.0 * tau + d) * _x_minus_sin(d)


def stretch_inverse(t):
    """``tau`` with ``T(tau) = t``, ``t`` in ``[0, pi]``, by Newton's method.

    Each point's iteration stops at the first step of at most ``1e-15`` (the step taken),
    all points' steps at once; NaN where ``t`` is NaN."""
    t = np.asarray(t, dtype=float)
    near = np.minimum(t, np.pi - t)
    out = np.zeros_like(near)
    pos = near > 0.0
    if np.any(pos):
        x = near[pos]
        # T <= (2/3) tau^3 gives a start at or below the root; T is increasing and
        # convex on [0, pi/2], so the iterates converge from above after one step.
        y = np.minimum(np.cbrt(1.5 * x), 0.5 * np.pi)
        live = np.arange(y.size)
        # Monotone and quadratic from there: a few steps (100 a bound never reached).
        for _ in range(100):
            yl, xl = y[live], x[live]
            step = (0.5 * _x_minus_sin(2.0 * yl) - xl) / (2.0 * np.sin(yl) ** 2)
            y[live] = yl - step
            live = live[np.abs(step) > 1e-15]
            if live.size == 0:
                break
        out[pos] = y
    return np.where(t <= 0.5 * np.pi, out, np.where(np.isnan(t), np.nan, np.pi - out))


def tau_of(s):
    """``tau`` of points ``s`` (clipped to ``[-1, 1]``)."""
    return stretch_inverse(np.arccos(np.clip(np.asarray(s, dtype=float), -1.0, 1.0)))


def nodes(n: int):
    """``tau_i = pi (i - 1/2) / n``, descending, so that ``r = cos T(tau)`` ascends."""
    return np.pi * (np.arange(n, 0, -1) - 0.5) / n


def cosine_value(coefficients, tau):
    """``sum_j a_j cos(j tau)``, by Clenshaw's recurrence in ``cos tau``."""
    return np.polynomial.chebyshev.chebval(np.cos(np.asarray(tau, dtype=float)), coefficients)


def bounded_weight(tau, alpha=0.5):
    """``w(cos T) sin T T'``, so that ``p(r) dr = phi W dtau`` with ``p = w phi``
    (:func:`pressure_weight`; ``sin^2 T T'`` for ``alpha = 1/2``)."""
    return _pressure_factor(stretch(tau), alpha) * stretch_derivative(tau)


def pressure_weight(s, alpha=0.5):
    """``w(s) = (1 - s)^alpha (1 + s)^(1 - alpha)`` on ``[-1, 1]``: the pressure's edge
    behaviour, ``sqrt(1 - s^2)`` for ``alpha = 1/2`` (derivation sections 6 and 5c)."""
    s = np.clip(np.asarray(s, dtype=float), -1.0, 1.0)
    if alpha == 0.5:
        return np.sqrt(1.0 - s * s)
    return (1.0 - s) ** alpha * (1.0 + s) ** (1.0 - alpha)


def _pressure_factor(t, alpha):
    """``w(cos t) sin t``, formed from ``1 - cos t = 2 sin^2(t/2)`` and
    ``1 + cos t = 2 cos^2(t/2)`` without cancellation next to either edge."""
    t = np.asarray(t, dtype=float)
    if alpha == 0.5:
        return np.sin(t) ** 2
    a, c = np.abs(np.sin(0.5 * t)), np.abs(np.cos(0.5 * t))
    return 2.0 * a ** (2.0 * alpha) * c ** (2.0 - 2.0 * alpha) * np.sin(t)


def singular_weight(tau):
    """``T'(tau)``, so that ``q'(r) dr = psi W dtau``."""
    return stretch_derivative(tau)


class CoordinateMap:
    """A variable ``x`` on ``[0, pi]`` with ``r = cos T(x)``, and the unknowns' weights.

    The moments are integrals over ``x`` of ``K(s - cos T(x))`` times a weight times
    ``cos(j x)``.  The edge-graded map (:data:`GRADED`, section 12) has
    ``T(x) = x - sin(2x)/2`` and the weights ``sin^2 T T'`` (pressure) and ``T'``
    (flux); the identity (:data:`IDENTITY`, ``x = t = arccos r``) with weight 1 gives
    the Chebyshev moments of section 10 (:func:`chebyshev_moments`).  A graded map
    whose pressure has the edge exponent ``alpha`` (:func:`graded_map`) has the
    weight ``w(cos T) sin T T'`` (:func:`pressure_weight`) and, as its ``base``, the
    map of the same stretch with ``alpha = 1/2``: the point geometry, which does not
    depend on ``alpha``, is the base's.
    """

    def __init__(self, name, T, dT, increment, inverse, pressure_factor, alpha=0.5,
                 base=None):
        self.name = name
        self.T, self.dT, self.increment, self.inverse = T, dT, increment, inverse
        #: ``w(cos T) sin T`` for the graded pressure weight (``sin^2 T`` when
        #: ``alpha = 1/2``), 1 for the identity map.
        self.pressure_factor = pressure_factor
        #: The pressure's edge exponent at ``s = 1``.
        self.alpha = alpha
        self._base = base

    @property
    def base(self):
        """The map of the same stretch with ``alpha = 1/2`` (itself when it is one)."""
        return self if self._base is None else self._base

    def weights(self, x):
        """The pressure's and the flux's weight at ``x``."""
        dT = self.dT(x)
        return self.pressure_factor(self.T(x)) * dT, dT

    def __repr__(self):
        return f"CoordinateMap({self.name!r})"


GRADED = CoordinateMap("graded", stretch, stretch_derivative, stretch_increment,
                       stretch_inverse, lambda t: np.sin(t) ** 2)


@small_cache(16)
def graded_map(alpha=0.5) -> CoordinateMap:
    """The edge-graded map whose pressure weight has the edge exponents ``alpha`` at
    ``s = 1`` and ``1 - alpha`` at ``s = -1`` (:func:`pressure_weight`; the Dundurs
    term's exponents, derivation section 5c); :data:`GRADED` for ``alpha = 1/2``."""
    if alpha == 0.5:
        return GRADED
    return CoordinateMap(f"graded alpha={alpha!r}", stretch, stretch_derivative,
                         stretch_increment, stretch_inverse,
                         lambda t: _pressure_factor(t, alpha), alpha=alpha, base=GRADED)
IDENTITY = CoordinateMap("identity", lambda x: np.asarray(x, dtype=float),
                         lambda x: np.ones_like(np.asarray(x, dtype=float)),
                         lambda x, d: np.broadcast_to(d, np.broadcast_shapes(np.shape(x), np.shape(d))).astype(float),
                         lambda t: np.asarray(t, dtype=float), lambda t: np.ones_like(t))


@small_cache(32)
def weight_integrals(n: int, alpha=0.5):
    """``integral_0^pi W(tau) cos(j tau) dtau`` for both weights, ``j < n``.

    The weights are even and ``pi``-periodic, entire for ``alpha = 1/2``, so the
    midpoint rule on ``max(256, 4n)`` points is exact to rounding; otherwise the
    pressure weight behaves as ``tau^(6 alpha + 5)`` at ``tau = 0`` (and
    ``6 (1 - alpha) + 5`` at ``pi``), where the rule's error is ``O(m^-(6 alpha + 6))``:
    below 1e-14 from ``m = 256`` for every ``alpha`` in ``(0, 1)``.

    Returns
    -------
    bounded, singular : ndarray, shape (n,)
    """
    m = max(256, 4 * n)
    tq = np.pi * (np.arange(m) + 0.5) / m
    wb, ws = bounded_weight(tq, alpha), singular_weight(tq)
    bounded, singular = np.empty(n), np.empty(n)
    # The (n, 4n) table of cos(j tau) a block of j at a time (4 MB; 32 MB whole at
    # n = 1024), each block formed in place.
    step = max(1, 2**19 // m)
    for j in range(0, n, step):
        basis = np.multiply.outer(np.arange(j, min(j + step, n)), tq)
        np.cos(basis, out=basis)
        basis *= np.pi / m
        bounded[j:j + step], singular[j:j + step] = basis @ wb, basis @ ws
    return bounded, singular


#: The bases ``cos(j tau)`` at the first half of the common rule's nodes, per n (17 MB at
#: n = 1024, 4 MB at 512): bounded in bytes, so that a refinement to n = 1024 does not
#: keep the coarser levels' bases beside the finest one's; a level visited again forms
#: them again.
BASES = BoundedCache("moment bases", 40 * 2**20)


def _common(n: int, cmap=None):
    """Common panel rule in ``x``, the bases and weights at its nodes (the bases and
    nodes those of ``cmap``'s stretch, whatever its ``alpha``)."""
    cmap = GRADED if cmap is None else cmap

    def build():
        m, h, tau, _, panel = panel_rule(n)
        # The rule is symmetric about pi/2 (node N - 1 - k is pi - tau_k), and
        # cos(j (pi - tau)) = (-1)^j cos(j tau): the bases at the first half's nodes
        # serve both halves (17 MB at n = 1024), even and odd j apart (_far_product).
        half = np.multiply.outer(tau[:tau.size // 2], np.arange(n))
        np.cos(half, out=half)  # in place
        g = (np.ascontiguousarray(half[:, 0::2]), np.ascontiguousarray(half[:, 1::2]))
        del half
        r = np.cos(cmap.base.T(tau))
        return m, h, r, g, panel

    def weights():
        _, _, tau, wt, _ = panel_rule(n)
        return np.stack(cmap.weights(tau)) * wt[None, :]
    # The bases for every alpha; the weights, shape (2, nodes), of this one.
    return (BASES.get((n, cmap.base.name), build)
            + (BASES.get((n, cmap.name, "weights"), weights),))


def _far_product(values, bases, out):
    """``out = values @ cos(j tau)`` over the common rule's nodes (``values`` of shape
    (k, N)), from the bases at the first half of the nodes (:func:`_common`): node
    ``N - 1 - i`` mirrors node ``i``, so the even ``j`` take the sum of the two halves'
    values and the odd ``j`` their difference.  Half the products of the full table."""
    even, odd = bases
    h = even.shape[0]
    first, mirrored = values[:, :h], values[:, ::-1][:, :h]
    out[:, 0::2] = (first + mirrored) @ even
    out[:, 1::2] = (first - mirrored) @ odd


def _u(s, tau_s, t_s, d, wq, cmap):
    """``s - cos T(tau_s + d)`` without cancellation next to ``tau_s``, and the weights.

    Returns ``(u, e)`` with ``e = u - (s - clip(s))``, the part measured from the
    nearer edge for points outside ``[-1, 1]``, formed separately; inside, ``(u,)``,
    ``u`` being ``e`` (unless ``e`` holds a ``-0.0``, which ``0 + e`` makes ``+0.0``):
    ``e`` is the last; and both weights of ``cmap`` (the point geometry's: ``alpha = 1/2``)
    at ``tau_s + d`` times ``wq``, shape ``(2,) + d.shape``, with
    ``T(tau_s + d) = t_s + dT`` (an absolute error of rounding, all a weight needs).
    ``e = cos t_s - cos T(tau_s + d)``: with the weights' ratio ``sin^2 T``, what
    the weights of another ``alpha`` are formed from (:func:`_edge_power`).
    """
    dt = cmap.increment(tau_s[:, None], d)
    half = t_s[:, None] + 0.5 * dt
    e = 2.0 * np.sin(half) * np.sin(0.5 * dt)
    singular = cmap.dT(tau_s[:, None] + d) * wq
    bounded = cmap.pressure_factor(half + 0.5 * dt) * singular
    past = _past_edge(s)[:, None]
    if past.any() or np.any(np.signbit(e) & (e == 0.0)):
        return (past + e, e), np.stack([bounded, singular])
    return (e,), np.stack([bounded, singular])


def _past_edge(s):
    """``s - clip(s)``: how far each point lies beyond the nearer edge (0 inside)."""
    return s - np.clip(s, -1.0, 1.0)


#: Geometric panels of 16 points between the innermost interval and ``h`` on a full side.
_FIXED_OUTER = 2
#: Geometric panels of 16 points from ``h`` to the end of a full side (at most ``2h``).
_OWN = 2
#: Interpolation points of the bases on ``[h, 2h]``: ``cos(j delta)``, ``j < n``, spans
#: less than two periods there; 30 Chebyshev points interpolate it to 1e-14.
_OWN_P = 30


class _Side:
    """One side of the replaced interval around every point ``tau_s``.

    A side at least one panel ``h`` long (``full``) is integrated by the innermost
    interval ``[0, w]``, graded, with the bases interpolated on 20 points,
    ``_FIXED_OUTER`` geometric panels from ``w`` to ``h`` and ``_OWN`` from ``h`` to
    the side's end (at most ``2h``), whose bases are interpolated on ``_OWN_P``
    Chebyshev points of ``[h, 2h]``.  All rows then carry the bases at the same
    offsets ``delta`` from ``tau_s``, which enter as
    ``cos(j (tau_s + delta)) = cos(j tau_s) cos(j delta) - sin(j tau_s) sin(j delta)``:
    two matrix products for all rows.  A shorter side (next to an edge, or of
    zero length at or beyond it) is graded and paneled row by row.
    """

    #: For a side moved from a point at an edge (:meth:`moved`): that point's key (its
    #: geometry is the cache's, not held here, where the cache would count it again),
    #: whose innermost interval the moved side's is.
    template = None

    def __init__(self, geo, sign, side, n, h, w):
        self.sign = sign
        self.full = side >= h
        # Sides of zero length (points at or beyond an edge) contribute nothing.
        self.rows = np.flatnonzero(self.full), np.flatnonzero(~self.full & (side > 0.0))
        self.inner = np.where(self.full, w, np.minimum(side, w))
        # Whether any point has this side; without one the moments skip it.
        self.live = bool(self.rows[0].size or self.rows[1].size)
        if not self.live:
            return  # no rule to form
        # The panels' points: the same rule as the common panels (moments._GL).
        xg, wg = gauss_legendre(_moments.GAUSS_POINTS)
        # Offsets and weights of the outer panels: fixed ones then the row's own.
        edges = w * (h / w) ** (np.arange(_FIXED_OUTER + 1) / _FIXED_OUTER)
        fixed = (edges[:-1, None] + np.diff(edges)[:, None] * xg).ravel()
        fixed_w = (np.diff(edges)[:, None] * wg).ravel()
        k = len(side)
        own, own_w = outer_panels(np.maximum(side, h), np.full(k, h), _OWN)
        xc, self.own_lagrange = chebyshev_lagrange((own[self.rows[0]] - h) / h, _OWN_P)
        dist = np.concatenate([np.broadcast_to(fixed, (k, fixed.size)), own], axis=1)
        wq = np.concatenate([np.broadcast_to(fixed_w, (k, fixed.size)), own_w], axis=1)
        dist_s, wq_s = outer_panels(side, self.inner, _FIXED_OUTER + _OWN)
        full = self.full[:, None]
        dist, wq = np.where(full, dist, dist_s), np.where(full, wq, wq_s)
        d = sign * dist
        self.outer_u, self.outer_w = _u(geo.s, geo.tau_s, geo.t_s, d, wq, geo.cmap)
        self.outer_live = wq > 0.0
        self.n_fixed = fixed.size
        # Rows paneled row by row: cosines and sines of their offsets, formed directly,
        # so that, as on the full sides, both sides of a point share the factors
        # cos(j tau_s), sin(j tau_s) and the principal value's cancellation between
        # the sides is not disturbed by a recurrence's phase error next to an edge.
        short = self.rows[1]
        xp = inner_reference(LOG_LEVELS)[2]  # the innermost interval's 20 points on [0, 1]
        phase = np.concatenate([sign * self.inner[short, None] * xp, d[short]], axis=1)
        phase = phase[..., None] * np.arange(n)
        self.short_cos, self.short_sin = np.cos(phase), np.sin(phase)
        offsets = sign * np.concatenate([w * xp, fixed, h * (1.0 + xc)])
        j = np.arange(n)
        self.fixed_cos = np.cos(np.outer(offsets, j))
        self.fixed_sin = np.sin(np.outer(offsets, j))

    def moved(self, offset, template):
        """This side of one point at an edge, for points ``offset = s - clip(s)``
        beyond it (:meth:`_Geometry.moved`): every row the point's, the distances
        ``u = offset + e`` formed as :func:`_u` forms them."""
        k = offset.size
        new = object.__new__(_Side)
        new.sign, new.live, new.template = self.sign, self.live, template
        new.full, new.inner = _rows(self.full, k), _rows(self.inner, k)
        new.rows = tuple(np.arange(k) if r.size else r for r in self.rows)
        if not self.live:
            return new
        e = self.outer_u[-1]
        new.outer_u = (offset[:, None] + e, _rows(e, k))
        new.outer_w = np.broadcast_to(self.outer_w, (2, k) + self.outer_w.shape[2:])
        new.outer_live, new.n_fixed = _rows(self.outer_live, k), self.n_fixed
        new.own_lagrange = _rows(self.own_lagrange, k if self.rows[0].size else 0)
        new.short_cos = _rows(self.short_cos, k if self.rows[1].size else 0)
        new.short_sin = _rows(self.short_sin, k if self.rows[1].size else 0)
        new.fixed_cos, new.fixed_sin = self.fixed_cos, self.fixed_sin
        return new

    def inner_parts(self, geo, levels):
        """Graded innermost interval: ``u``, live mask, weights, Lagrange matrix (kept
        in the geometry cache as entries of their own, so that it counts them)."""
        ref_tau, om, _, lagr = inner_reference(levels)
        d = self.sign * self.inner[:, None] * ref_tau[None, :]
        wq = self.inner[:, None] * om[None, :]
        u, wts = _u(geo.s, geo.tau_s, geo.t_s, d, wq, geo.cmap)
        return u, wq > 0.0, wts, lagr


class _Geometry:
    """Everything about a set of points that does not depend on the kernel."""

    def __init__(self, s, n, tau, cmap):
        m, h, r, g, panel, wts = _common(n, cmap)
        self.s, self.n, self.cmap = s, n, cmap
        if tau is None:
            self.t_s = np.arccos(np.clip(s, -1.0, 1.0))
            self.tau_s = cmap.inverse(self.t_s)
        else:
            self.tau_s = tau
            self.t_s = cmap.T(tau)
        self.near, sides = near_field(self.tau_s, m, h, panel)
        self.far_u = s[:, None] - r[None, :]
        clipped = np.clip(s, -1.0, 1.0)
        # Inside [-1, 1] the distances from the edge are the distances themselves.
        self.far_e = (self.far_u if np.array_equal(clipped, s)
                      else clipped[:, None] - r[None, :])
        j = np.arange(n)
        self.cos_s = np.cos(np.outer(self.tau_s, j))
        self.sin_s = np.sin(np.outer(self.tau_s, j))
        w = min(6.0 / (n + 1), h)
        self.sides = [_Side(self, sign, side, n, h, w) for sign, side in sides]

    def moved(self, s, key):
        """This geometry of one point at an edge (``key`` its key), for points ``s`` at
        or beyond that edge: their ``tau_s`` is the edge's, so everything but the
        distances ``s - r`` is the point's row, repeated (read-only views), and the
        distances are the point's plus ``s - clip(s)``, as :func:`_u` forms them: the
        same numbers as a geometry of its own, without its sines and cosines (a
        polished gap margin's points)."""
        k = s.size
        new = object.__new__(_Geometry)
        new.s, new.n, new.cmap = s, self.n, self.cmap
        new.t_s, new.tau_s = _rows(self.t_s, k), _rows(self.tau_s, k)
        new.near = _rows(self.near, k)
        new.far_u = s[:, None] - _common(self.n, self.cmap)[2][None, :]
        new.far_e = _rows(self.far_e, k)
        new.cos_s, new.sin_s = _rows(self.cos_s, k), _rows(self.sin_s, k)
        new.sides = [side.moved(_past_edge(s), key) for side in self.sides]
        return new


def _rows(a, k):
    """``a``'s first row repeated ``k`` times (a read-only view)."""
    return np.broadcast_to(a[:1], (k,) + a.shape[1:])


#: The point geometry of the moments, shared by the kernels of one assembly, at
#: ``n > SMALL_GEOMETRY_N`` (:func:`geometry_cache`).
GEOMETRY = BoundedCache("graded geometry", 32 * 2**20)
#: The same at ``n <= SMALL_GEOMETRY_N``, under a budget of its own.  A contact
#: evaluates the same points at every level of its refinement and for every ``Pe``
#: (its fields' samples and slope points, its assemblies' collocation points): about
#: 57 MB at levels 8 to 64.  A least-recently-used cache smaller than that cycle keeps
#: none of it from one call to the next, so the small levels get the room the cycle
#: needs, and the large levels keep the budget (and the peak memory) they had.
SMALL_GEOMETRY = BoundedCache("graded geometry, n <= 64", 64 * 2**20)
SMALL_GEOMETRY_N = 64


def clear_geometry() -> None:
    """Forget the point geometry at every ``n`` (a first call's cost)."""
    GEOMETRY.clear()
    SMALL_GEOMETRY.clear()


def geometry_cache(n: int) -> BoundedCache:
    """The cache of the point geometry at ``n`` (:data:`GEOMETRY` or
    :data:`SMALL_GEOMETRY`)."""
    return SMALL_GEOMETRY if n <= SMALL_GEOMETRY_N else GEOMETRY
#: Rows times common-rule nodes per block of points: the moments of more points are
#: computed block by block, so that the geometry and the kernel's values (arrays of
#: that size, a few of them at once) stay near 4 MB each whatever n.
BLOCK_ENTRIES = 2**19
#: Entries of the far field's kernel values evaluated at once (columns of a block).
KERNEL_ENTRIES = 2**16
#: Fewest rows in a block: the validity checks' kernels carry their points' own
#: distances as arrays of up to a few hundred rows.
MIN_BLOCK = 256


def _geometry(key: bytes, n: int, tau_key: bytes | None, cmap) -> _Geometry:
    def build():
        s = np.frombuffer(key, dtype=float)
        if tau_key is not None:
            return _Geometry(s, n, np.frombuffer(tau_key, dtype=float), cmap)
        edge = 1.0 if np.all(s >= 1.0) else -1.0 if np.all(s <= -1.0) else None
        if s.size == 0 or edge is None or (s.size == 1 and s[0] == edge):
            return _Geometry(s, n, None, cmap)
        # Points beyond one edge: the edge's own geometry, moved (kept, for the next).
        at_edge = np.array([edge]).tobytes()
        return _geometry(at_edge, n, None, cmap).moved(s, at_edge)
    return geometry_cache(n).get((key, n, tau_key, cmap.name), build)


def _inner_parts(geo: _Geometry, index: int, levels, key: bytes, tau_key: bytes | None):
    """The innermost interval of the side ``index`` of ``geo`` (:meth:`_Side.inner_parts`;
    a moved side's from its edge point's, as :meth:`_Side.moved`)."""
    side = geo.sides[index]

    def build():
        if side.template is None:
            return side.inner_parts(geo, levels)
        edge_key = side.template
        edge_geo = _geometry(edge_key, geo.n, None, geo.cmap)
        u, live, wq, lagr = _inner_parts(edge_geo, index, levels, edge_key, None)
        e = u[-1]
        k = geo.s.size
        return ((_past_edge(geo.s)[:, None] + e, _rows(e, k)), _rows(live, k),
                np.broadcast_to(wq, (2, k) + wq.shape[2:]), lagr)
    return geometry_cache(geo.n).get((key, geo.n, tau_key, geo.cmap.name, index, levels),
                                     build)


def _edge_power(bounded, singular, cos_t, alpha):
    """The pressure's weight ``w(cos t) sin t T' wq`` of the edge exponent ``alpha``
    (:func:`pressure_weight`) from the point geometry's ``bounded = sin^2 t T' wq``
    (``alpha = 1/2``), ``singular = T' wq`` and ``cos t``.

    ``w(cos t) sin t = sin^2 t tan(t/2)^(2 alpha - 1)``, and with
    ``q = sin^2 t / (1 + |cos t|)^2``, ``tan^2(t/2)`` is ``q`` where ``cos t >= 0``
    and ``1/q`` where ``cos t < 0``: ``sin^2 t``, the weights' ratio, is relative to
    rounding, and ``1 + |cos t| >= 1`` needs ``cos t`` to rounding only, so that the
    power keeps its relative accuracy next to either edge.  Zero where ``bounded``
    is (an edge, a node of zero weight).
    """
    with np.errstate(divide="ignore", invalid="ignore"):
        q = np.divide(bounded, singular)
        a = np.abs(cos_t)
        a += 1.0
        a *= a
        q /= a
        out = np.power(q, alpha - 0.5, out=q)
        np.reciprocal(out, out=out, where=cos_t < 0.0)
        out *= bounded
    np.copyto(out, 0.0, where=bounded == 0.0)
    return out


def _pressure_weights(geo: _Geometry, key: bytes, tau_key: bytes | None, levels, parts,
                      alpha):
    """The pressure's weights of the edge exponent ``alpha`` on the live sides' nodes of
    ``geo`` (whose own are those of ``alpha = 1/2``): per live side, the innermost
    interval's and the outer panels' (:func:`_edge_power`), kept beside the geometry
    in its cache (a moved geometry's from its edge point's, as :func:`_inner_parts`).
    ``parts``: the live sides' innermost intervals, by index."""
    def build():
        edge_key = geo.sides[0].template
        if edge_key is not None:
            edge_geo = _geometry(edge_key, geo.n, None, geo.cmap)
            edge_parts = {index: _inner_parts(edge_geo, index, levels, edge_key, None)
                          for index in parts}
            k = geo.s.size
            return [tuple(_rows(w, k) for w in pair) for pair in _pressure_weights(
                edge_geo, edge_key, None, levels, edge_parts, alpha)]
        cos_t = np.cos(geo.t_s)[:, None]
        out = []
        for index, (u, _, wq, _) in parts.items():
            side = geo.sides[index]
            out.append((_edge_power(wq[0], wq[1], cos_t - u[-1], alpha),
                        _edge_power(side.outer_w[0], side.outer_w[1],
                                    cos_t - side.outer_u[-1], alpha)))
        return out
    return geometry_cache(geo.n).get((key, geo.n, tau_key, geo.cmap.name, levels, alpha),
                                     build)


def _weighted(values, weights, halves):
    """``values`` times each of ``halves``' ``weights`` (0 the pressure's, 1 the
    flux's; each of ``values``' shape, or a view broadcast to it), stacked along a first
    axis, each product formed in its place."""
    out = np.empty((len(halves),) + values.shape,
                   dtype=np.result_type(values.dtype, weights[0].dtype))
    for i, h in enumerate(halves):
        np.multiply(values, weights[h], out=out[i])
    return out


def _kernel_values(kernel, far, near):
    """The kernel's values on the far field's nodes ``far`` and on each array of the
    sides' nodes ``near``: ``(values on far, [values on each of near])``.

    Called once on all of them side by side where they are few (KERNEL_ENTRIES): a
    kernel's fixed cost, its masks and temporaries, paid once, each value the same as
    alone (kernels are elementwise in ``u``, their rows' own parameters broadcast along
    the rows).  A kernel whose values depend on the array it is given says so
    (``elementwise = False``: the transient kernels' quadrature takes its depth per
    block of points) and is called on each part apart; so is every kernel on a large
    far field, a few of its columns at a time, so that a kernel's temporaries (ten or
    more arrays of the block's size for the Bessel kernels) stay small."""
    if (getattr(kernel, "elementwise", True)
            and far.size + sum(u.size for u in near) <= KERNEL_ENTRIES):
        values = kernel(np.concatenate([far, *near], axis=1))
        edges = np.cumsum([far.shape[1]] + [u.shape[1] for u in near])
        kf, *rest = np.split(values, edges[:-1], axis=1)
        return kf, rest
    if far.size <= KERNEL_ENTRIES:
        kf = kernel(far)
    else:
        step = max(1, KERNEL_ENTRIES // far.shape[0])
        kf = None
        for c in range(0, far.shape[1], step):
            part = kernel(np.ascontiguousarray(far[:, c:c + step]))
            if kf is None:  # real or complex, as the kernel's values are
                kf = np.empty(far.shape, dtype=part.dtype)
            kf[:, c:c + step] = part
    return kf, [kernel(u) for u in near]


def moments(kernel, s, n: int, scale=None, cauchy=False, tau=None, from_edge=False,
            logarithmic=False, cmap=GRADED, pressure=True, flux=True):
    """Moments of a convolution kernel against the graded bases.

    ``B[k, j] = integral_0^pi K(s_k - cos T(tau)) sin^2 T(tau) T'(tau) cos(j tau) dtau``
    and ``S[k, j] = integral_0^pi K(s_k - cos T(tau)) T'(tau) cos(j tau) dtau``: the
    integrals of ``K(s_k - r)`` against the pressure and the heat-flux difference
    whose factors ``phi``, ``psi`` are ``cos(j tau)`` (the pressure's weight
    ``w(cos T) sin T T'`` in place of ``sin^2 T T'`` for a map of another edge
    exponent, :func:`graded_map`).

    Parameters
    ----------
    kernel : callable
        Vectorised ``K(u)``, ``u = s - r``, called with arrays whose rows belong to
        the points; may jump, be logarithmically singular or vary on any scale at
        ``u = 0``, or be ``1/u`` (``cauchy=True``).
    s : array_like, shape (k,)
        Points inside or outside ``[-1, 1]``.
    n : int
        Number of basis functions.
    scale : float, optional
        For a kernel smooth on either side of ``u = 0`` with structure on the
        scale ``1/scale`` only: the grading toward ``tau_s`` stops at
        ``1e-3/scale`` instead of ``2^-47`` of the interval (a logarithm needs the
        latter).  ``scale=1`` suits a jump or a pole.
    logarithmic : bool
        With ``scale``: the kernel is ``a(u) + b(u) ln|u|`` with ``a``, ``b``
        smooth on that scale (grading at least ``LOG_LEVELS`` halvings deep).
    cauchy : bool
        ``K`` has a simple pole at ``u = 0`` whose principal value is wanted.
    tau : array_like, optional
        ``tau`` of interior points ``s = cos T(tau)``: points within ``1e-16`` of
        an edge keep their position, which ``s`` alone would round away.
    from_edge : bool
        Call the kernel with ``e = u - (s - clip(s))`` instead of ``u``: for points
        outside ``[-1, 1]``, ``u`` less the distance past the edge, formed without
        that subtraction (``1 - r`` right of the contact, ``-(1 + r)`` left of it).
    cmap : CoordinateMap
        The map and the weights: :data:`GRADED`, :func:`graded_map` of the pressure's
        edge exponent, or :data:`IDENTITY`.
    pressure, flux : bool
        Whether to compute the bounded (pressure's) and the singular (flux's) moments:
        one alone costs the kernel's values and half the products.

    Returns
    -------
    bounded, singular : ndarray, shape (k, n)
        Each None where not asked for.

    Notes
    -----
    The construction of :func:`thermocontact.numerics.moments.kernel_moments` in ``tau``:
    a common 16-point Gauss–Legendre panel rule; around ``tau_s`` three panels
    replaced, per side, by an innermost interval of width ``w = min(6/(n + 1), h)``
    graded toward ``tau_s`` (bases interpolated on 20 points there) and geometric
    panels to the side's end (:class:`_Side`: at offsets shared by all rows where the
    side is a panel ``h`` long or more).  For a principal value, with
    ``1/u ~ 1/(D (tau - tau_s))``,
    ``D = sin t_s T'(tau_s)``, the two graded sides of lengths ``a`` and ``b`` are
    the same rule scaled, so their divergent parts cancel and the principal value
    of the omitted central interval, ``W(tau_s) cos(j tau_s) ln(b/a) / D``, is
    added (derivation section 12).  The geometry of the points (everything but the
    pressure's weight) is the same for every edge exponent ``alpha`` and kept once;
    another ``alpha``'s pressure weights on its graded nodes are formed from it
    (:func:`_edge_power`) and kept beside it.
    """
    s = np.ascontiguousarray(np.atleast_1d(np.asarray(s, dtype=float)))
    m, h, r, g, panel, wts = _common(n, cmap)
    rows = max(1, BLOCK_ENTRIES // r.size)
    if s.size > rows and s.size > MIN_BLOCK:
        # Block by block (kernels are elementwise in u, or carry at most MIN_BLOCK
        # rows of their own, as the validity checks' do).
        rows = max(rows, MIN_BLOCK)
        parts = [moments(kernel, s[i:i + rows], n, scale=scale, cauchy=cauchy,
                         tau=None if tau is None else np.asarray(tau)[i:i + rows],
                         from_edge=from_edge, logarithmic=logarithmic, cmap=cmap,
                         pressure=pressure, flux=flux)
                 for i in range(0, s.size, rows)]
        return tuple(None if parts[0][h] is None else np.concatenate([p[h] for p in parts])
                     for h in (0, 1))
    halves = [h for h, asked in ((0, pressure), (1, flux)) if asked]
    tau_key = None if tau is None else np.ascontiguousarray(tau, dtype=float).tobytes()
    key = s.tobytes()
    geo = _geometry(key, n, tau_key, cmap.base)
    pick = -1 if from_edge else 0  # e, or u (the same where only e is held)
    levels = levels_for(n, scale, logarithmic)
    far = geo.far_e if from_edge else geo.far_u
    live = [(index, side) for index, side in enumerate(geo.sides) if side.live]
    parts = {index: _inner_parts(geo, index, levels, key, tau_key) for index, _ in live}
    # Per live side, the innermost interval's and the outer panels' weights, each a
    # pair (pressure, flux): the geometry's, or with another alpha's pressure weights.
    side_weights = [(parts[index][2], side.outer_w) for index, side in live]
    if pressure and cmap.alpha != 0.5:
        side_weights = [((b_in, w_in[1]), (b_out, w_out[1])) for (w_in, w_out), (b_in, b_out)
                        in zip(side_weights, _pressure_weights(geo, key, tau_key, levels,
                                                               parts, cmap.alpha))]
    # The graded sides' nodes (innermost interval, then outer panels, per side).
    near = [u for index, side in live for u in (parts[index][0][pick], side.outer_u[pick])]
    with np.errstate(divide="ignore", invalid="ignore"):
        kf, near_values = _kernel_values(kernel, far, near)
    kf[geo.near] = 0.0
    # The weights' products into one array, through one temporary.
    out = np.empty((len(halves), kf.shape[0], n), dtype=np.result_type(kf, g[0]))
    weighted = np.empty_like(kf, dtype=np.result_type(kf, wts))
    for i, h in enumerate(halves):
        np.multiply(kf, wts[h], out=weighted)
        _far_product(weighted, g, out[i])
    del weighted
    # A side without points (every point at or beyond its edge: a block of the gap's
    # points) has nothing to integrate and no kernel values.
    for k, ((index, side), (w_in, w_out)) in enumerate(zip(live, side_weights)):
        full, short = side.rows
        _, inside, _, lagr = parts[index]
        # Rows of a side of zero length (points at or beyond an edge) hold dummies.
        inner = _weighted(np.where(inside, near_values[2 * k], 0.0), w_in, halves) @ lagr
        outer = _weighted(np.where(side.outer_live, near_values[2 * k + 1], 0.0), w_out,
                          halves)
        if full.size:
            nf = side.n_fixed
            own = np.matmul(outer[:, full, None, nf:], side.own_lagrange)[:, :, 0]
            v = np.concatenate([inner[:, full], outer[:, full, :nf], own], axis=2)
            out[:, full] += (geo.cos_s[full] * (v @ side.fixed_cos)
                             - geo.sin_s[full] * (v @ side.fixed_sin))
        if short.size:
            v = np.concatenate([inner[:, short], outer[:, short]], axis=2)
            if len(halves) == 1:
                # A row's product (the BLAS's vector times matrix) is not the same
                # numbers as the same row's in a product of two: one half alone takes
                # its place beside a zero other half.
                both = np.zeros((2,) + v.shape[1:], dtype=v.dtype)
                both[halves[0]] = v[0]
                v = both
            v = v.transpose(1, 0, 2)
            c = np.matmul(v, side.short_cos).transpose(1, 0, 2)[halves]
            sn = np.matmul(v, side.short_sin).transpose(1, 0, 2)[halves]
            out[:, short] += geo.cos_s[short] * c - geo.sin_s[short] * sn
    if cauchy:
        a_in, b_in = (side.inner for side in geo.sides)
        interior = (a_in > 0.0) & (b_in > 0.0) & (geo.tau_s > 0.0) & (geo.tau_s < np.pi)
        if np.any(interior):
            ts = geo.tau_s[interior]
            log_ratio = np.log(b_in[interior] / a_in[interior]) / (
                np.sin(geo.t_s[interior]) * cmap.dT(ts))
            basis = np.cos(np.arange(n)[None, :] * ts[:, None])
            w = cmap.weights(ts)
            for i, h in enumerate(halves):
                out[i][interior] += (w[h] * log_ratio)[:, None] * basis
    moments_of = [None, None]
    for i, h in enumerate(halves):
        moments_of[h] = out[i]
    return tuple(moments_of)


def chebyshev_moments(kernel, s, n: int, scale=None, logarithmic=False):
    """Moments of ``K(s - r)`` against ``sqrt(1 - r^2) U_j`` and ``T_j / sqrt(1 - r^2)``.

    ``B[k, j] = integral_0^pi K(s_k - cos t) sin t sin((j + 1) t) dt`` and
    ``S[k, j] = integral_0^pi K(s_k - cos t) cos(j t) dt``, ``j < n`` (derivation
    section 10): :func:`moments` with the identity map and weight 1, since
    ``sin t sin((j + 1) t) = (cos(j t) - cos((j + 2) t)) / 2``.

    Returns
    -------
    bounded, singular : ndarray, shape (len(s), n)
    """
    _, c = moments(kernel, s, n + 2, scale=scale, logarithmic=logarithmic, cmap=IDENTITY)
    return 0.5 * (c[:, :n] - c[:, 2:]), c[:, :n].copy()
