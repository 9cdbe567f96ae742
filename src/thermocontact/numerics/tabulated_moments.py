"""Moments of kernels known by their values at fixed nodes: a linear map built once.

The linearised contact (derivation section 18) integrates the same few kernels against
the same bases at the same points for every rate ``b``; only the kernels change.  Each
kernel is replaced by its interpolant on panels graded geometrically toward ``u = 0``
on either side (:data:`SMALLEST` ``<= |u| <=`` :data:`LARGEST`, ratio :data:`RATIO`,
:data:`NODES` Chebyshev points each), so that its moments are a fixed linear map of its
values at those nodes:

    B[k, i] = integral_0^pi K(s_k - cos T(tau)) W(tau) phi_i(tau) dtau
            = sum_m K(u_m) A[k, i, m],

``phi_i`` the nodal basis of the graded representation (cosine series in ``tau``),
``W`` the pressure's or the flux's weight (:func:`~.moment_engine.moments`).  The map
``A`` (:class:`KernelTable`) is product integration: on each panel the Lagrange
polynomials of the nodes are integrated against the weighted bases by Gauss-Legendre
in ``tau``, on the ``tau``-interval the panel covers, located without cancellation
next to ``tau_k`` (offsets ``delta = tau - tau_k``, as the moment engine forms
them), one matrix product per point and panel; a cell small against its distance from
the contact's edges (most of those next to ``u = 0``) by an 8-point product rule in the
panel's own variable instead (:func:`_tiny_cells`, derivation S9: its error below
rounding).  Below :data:`SMALLEST` the kernel is
its fit ``a + b ln|u| + c u + d u ln|u|`` on the first panel's nodes, the bases
integrated against those four functions on pieces halving toward ``u = 0`` and mapped
to the nodes after.  A kernel that is smooth on either side of ``u = 0`` on every
scale down to :data:`SMALLEST`, with at most a jump or a logarithm at ``0`` (the
transient kernels of derivation eqs. T3-T10, each side's interpolant then converging
geometrically), is integrated to about 1e-13 of its size.  A kernel that is a layer
``exp(-beta u)``, ``|arg beta| <= pi/4`` (the stationary half-plane's), may be given at
the nodes of every second panel instead (:data:`COARSE_RATIO`), through the map
composed with each coarse panel's interpolant (:attr:`KernelTable.coarse`; at most
5.5e-12 for Re b > 0, derivation S9).  The kernels' values are the only work per ``b``.
"""

from __future__ import annotations

import numpy as np

from .cache import BoundedCache, small_cache
from .moment_engine import GRADED, stretch, stretch_inverse

__all__ = ["COARSE_RATIO", "KernelTable", "NODES", "RATIO", "kernel_nodes", "kernel_table"]

#: Chebyshev points per panel (degree 15 interpolation).
NODES = 16
#: Ratio of consecutive panels' ends: ``|u|`` in ``[h, RATIO h]``.  A kernel
#: ``exp(-beta u)`` (a boundary layer of the transient kernels, ``|arg beta| <= pi/4``)
#: is interpolated to 1e-14 of its size at ``u = 0`` on every panel with this ratio.
#: Not 2 (half the nodes): a moving body's wake has ``D = b/(rho + |c| s)``, whose
#: argument reaches ``arg b`` (``pi/2`` on the imaginary axis), a barely damped
#: oscillation of wavenumber about ``|b|/(2|c|)`` where ``c^2 >~ |b|``, which panels of
#: ratio 2 resolve only to 6e-7 at ``c = 50, b = 3000i`` and 2e-4 at ``c = 200,
#: b = 10^4 i`` (this ratio: 1e-10 and 1e-7; derivation S9).
RATIO = np.sqrt(2.0)
#: The stationary half-plane's panels: every second edge of :data:`RATIO`'s (ratio 2,
#: half the nodes).  Its kernels have ``D = rho = sqrt(b)``: boundary layers
#: ``exp(-beta u)``, ``|arg beta| <= pi/4``, with a logarithm or a jump at ``u = 0``,
#: which panels of ratio 2 interpolate to about 1e-11 of their size (derivation S9,
#: *Panels of ratio 2 for the stationary half-plane*); a moving body's wake is not such
#: a layer and keeps :data:`RATIO`.
COARSE_RATIO = RATIO * RATIO
#: The panels span ``SMALLEST <= |u| <= LARGEST`` (points in ``[-1, 1]``); below
#: ``SMALLEST`` the kernel is ``a + b ln|u| + c u + d u ln|u|`` to ``O(u^2 ln u)``.
SMALLEST, LARGEST = 2.0 ** -36, 2.0
#: The innermost interval's pieces, halving toward ``u = 0`` (the rest, below
#: ``2^-60`` of it in ``tau``, is left out).
_INNER_HALVINGS = 60
#: Gauss-Legendre points per piece in ``tau`` and the longest piece.
_GAUSS = 24
#: Gauss-Legendre points per piece of the innermost interval (``[d/2, d]``: a logarithm
#: whose singularity lies ``d/2`` away, integrated to ``(3 + sqrt 8)^-24 = 4e-19`` of itself).
_INNER_GAUSS = 12
_PIECE = 0.125

#: The tables kept per process (16 MB at n = 12, 62 MB at n = 24, the coarse map included).
TABLES = BoundedCache("kernel tables", 128 * 2**20)


def _panels(coarse=False):
    """The panels' edges in ``|u|``, ascending; with ``coarse`` every second one
    (:data:`COARSE_RATIO`: the panels an even number)."""
    count = int(np.ceil(np.log(LARGEST / SMALLEST) / np.log(RATIO)))
    count += count % 2
    edges = SMALLEST * RATIO ** np.arange(count + 1)
    edges[-1] = max(edges[-1], LARGEST)
    return edges[::2] if coarse else edges


def _chebyshev():
    """The Chebyshev points of a panel, descending in ``[-1, 1]``."""
    return np.cos(np.pi * (np.arange(NODES) + 0.5) / NODES)


@small_cache(4)
def kernel_nodes(coarse=False):
    """The nodes ``u`` (ascending: the negative side's, then the positive side's) at
    which a kernel's values are given to :meth:`KernelTable.moments`; with ``coarse``
    those of the panels of ratio :data:`COARSE_RATIO` (the stationary half-plane's)."""
    edges = _panels(coarse)
    x = _chebyshev()
    mid, half = 0.5 * (edges[1:] + edges[:-1]), 0.5 * (edges[1:] - edges[:-1])
    pos = np.sort((mid[:, None] + half[:, None] * x[None, :]).ravel())
    out = np.concatenate([-pos[::-1], pos])
    out.setflags(write=False)       # kept: shared by every caller
    return out


def _lagrange(xq, x):
    """Values at ``xq`` (any shape, in [-1, 1]) of the Lagrange polynomials of the
    Chebyshev nodes ``x``, shape ``xq.shape + (len(x),)``: the Chebyshev series of each
    (its coefficients the inverse of the nodes' Vandermonde matrix) summed at ``xq``."""
    cheb = np.polynomial.chebyshev
    return cheb.chebvander(xq, x.size - 1) @ np.linalg.inv(cheb.chebvander(x, x.size - 1))


def _offset_u(tau_k, t_k, d, cmap):
    """``u = s_k - cos T(tau_k + d)`` without cancellation for small ``d``."""
    dt = cmap.increment(tau_k, d)
    return 2.0 * np.sin(t_k + 0.5 * dt) * np.sin(0.5 * dt)


def _offsets(tau_k, t_k, s_k, a, side, cmap):
    """The offsets ``d`` with ``u(tau_k + d) = side * a`` (``a > 0``), by Newton's
    method from the direct inversion; ``side = +1`` has ``d > 0`` (``r < s_k``)."""
    one_minus = 2.0 * np.sin(0.5 * t_k) ** 2 + side * a       # 1 - r
    one_plus = 2.0 * np.cos(0.5 * t_k) ** 2 - side * a        # 1 + r
    t = np.where(one_minus <= one_plus,
                 2.0 * np.arcsin(np.sqrt(np.clip(0.5 * one_minus, 0.0, 1.0))),
                 np.pi - 2.0 * np.arcsin(np.sqrt(np.clip(0.5 * one_plus, 0.0, 1.0))))
    d = stretch_inverse(t) - tau_k
    for _ in range(4):
        slope = np.sin(cmap.T(tau_k + d)) * cmap.dT(tau_k + d)
        step = (_offset_u(tau_k, t_k, d, cmap) - side * a) / np.where(slope > 0.0, slope, 1.0)
        d = d - np.where(slope > 0.0, step, 0.0)
    return d


class KernelTable:
    """The linear map from a kernel's values at :func:`kernel_nodes` to its moments
    at points ``s_k = cos T(tau_k)`` inside the contact (module docstring).

    Parameters
    ----------
    tau : ndarray, shape (k,)
        The points' ``tau`` in ``(0, pi)``.
    n : int
        Basis functions (nodal values at the graded nodes: the moments returned are
        those of :meth:`~thermocontact.discretisation.representations.EdgeGraded.integrate`).
    to_cos : ndarray, shape (n, n)
        Nodal values to cosine coefficients in ``tau``.
    cmap : CoordinateMap
        The graded map with the pressure's weight.
    """

    def __init__(self, tau, n, to_cos, cmap=GRADED):
        tau_k = np.asarray(tau, dtype=float)
        #: What the table depends on besides ``to_cos`` (which follows from ``n`` and
        #: ``cmap``): a key for what is computed with it.
        self.key = (np.ascontiguousarray(tau_k).tobytes(), int(n), cmap.name)
        t_k = stretch(tau_k)
        s_k = np.cos(t_k)
        edges = _panels()
        xc = _chebyshev()
        npan = edges.size - 1
        # The innermost interval |u| < edges[0]: the kernel there is
        # a + b ln|u| + c u + d u ln|u| + O(u^2 ln|u|), fitted to the first panel's
        # nodes (least squares): a row of weights on those nodes per function.
        first = 0.5 * (edges[0] + edges[1]) + 0.5 * (edges[1] - edges[0]) * xc
        fit = np.linalg.pinv(_inner_basis(first))           # (4, NODES)
        gx, gw = np.polynomial.legendre.leggauss(_GAUSS)
        ix, iw = np.polynomial.legendre.leggauss(_INNER_GAUSS)
        to_cos = np.asarray(to_cos)
        # (side, point, panel, weight, n, node): each side's panels outward from u = 0,
        # each panel's nodes in the Chebyshev points' (descending) order; a cell's
        # entries contiguous, laid out as the map once at the end.
        cells = np.zeros((2, tau_k.size, npan, 2, n, NODES))
        for at_side, side in enumerate((-1.0, 1.0)):
            # The offsets of each panel's ends, cut at the contact's edge.
            end = np.where(side > 0, np.pi - tau_k, -tau_k)
            reach = np.where(side > 0, 1.0 + s_k, 1.0 - s_k)
            a = np.minimum(edges[None, :], reach[:, None])
            d = _offsets(tau_k[:, None], t_k[:, None], s_k[:, None], a, side, cmap)
            d = np.where(a >= reach[:, None], end[:, None], d)
            lo, hi = d[:, :-1], d[:, 1:]
            live = np.abs(hi - lo) > 0.0
            # The cells small against their distance from the edges (tau = 0, pi) and
            # against 1/n, whole (not cut at the contact's edge): on the rule of
            # _tiny_rule, the rest by Gauss-Legendre in tau.
            near = np.minimum(tau_k[:, None] + np.minimum(lo, hi),
                              np.pi - tau_k[:, None] - np.maximum(lo, hi))
            tiny = live & (a[:, 1:] < reach[:, None]) & (
                np.abs(hi - lo) <= np.minimum(2.0 * near, 4.0 / n) / _TINY_RHO)
            if np.any(tiny):
                k_t, p_t = np.nonzero(tiny)
                cells[at_side, k_t, p_t] = _tiny_cells(
                    tau_k[k_t], t_k[k_t], edges[p_t], edges[p_t + 1], lo[tiny], hi[tiny],
                    side, to_cos, cmap)
            live &= ~tiny
            k_idx, p_idx = np.nonzero(live)
            lo, hi = lo[live], hi[live]
            # Each (point, panel) cell's interval in pieces of at most _PIECE, in order.
            pieces = np.maximum(1, np.ceil(np.abs(hi - lo) / _PIECE).astype(int))
            rep = np.repeat(np.arange(lo.size), pieces)
            within = np.arange(rep.size) - np.repeat(np.cumsum(pieces) - pieces, pieces)
            width = (hi - lo)[rep] / pieces[rep]
            nodes = (lo[rep] + within * width)[:, None] + 0.5 * width[:, None] * (gx + 1.0)
            kk, q = k_idx[rep], p_idx[rep]
            u = np.abs(_offset_u(tau_k[kk][:, None], t_k[kk][:, None], nodes, cmap))
            mid, half = 0.5 * (edges[q + 1] + edges[q]), 0.5 * (edges[q + 1] - edges[q])
            lag = _lagrange(np.clip((u - mid[:, None]) / half[:, None], -1.0, 1.0), xc)
            basis, weights = _basis(tau_k[kk][:, None] + nodes, to_cos, cmap)
            weights *= 0.5 * np.abs(width)[:, None] * gw
            lag = weights[..., None] * lag                  # (2, I, G, NODES)
            # Per cell, its pieces' nodes in one product (n x G m) @ (G m x NODES), the
            # cells of m pieces stacked.
            first = np.cumsum(pieces) - pieces
            for m in np.unique(pieces):
                these = np.flatnonzero(pieces == m)
                at = (first[these][:, None] + np.arange(m)).ravel()
                cell = np.matmul(basis[at].reshape(these.size, m * _GAUSS, n).transpose(0, 2, 1),
                                 lag[:, at].reshape(2, these.size, m * _GAUSS, NODES))
                cells[at_side, k_idx[these], p_idx[these]] = cell.transpose(1, 0, 2, 3)
            # The innermost interval [0, d0] in pieces halving toward 0: the kernel there
            # is the fit on the first panel, so that the bases are integrated against
            # its four functions, mapped to the first panel's nodes after.
            d0 = d[:, 0]
            halvings = 2.0 ** -np.arange(_INNER_HALVINGS + 1)
            ilo = (d0[:, None] * halvings[1:])[..., None]
            ihi = (d0[:, None] * halvings[:-1])[..., None]
            inodes = (ilo + 0.5 * (ihi - ilo) * (ix + 1.0)).reshape(tau_k.size, -1)
            basis, weights = _basis(tau_k[:, None] + inodes, to_cos, cmap)
            weights *= (0.5 * np.abs(ihi - ilo) * iw).reshape(tau_k.size, -1)
            four = _inner_basis(np.abs(_offset_u(tau_k[:, None], t_k[:, None], inodes, cmap)))
            inner = np.matmul(basis.transpose(0, 2, 1), weights[..., None] * four)
            cells[at_side, :, 0] += (inner @ fit).transpose(1, 0, 2, 3)
        # Ascending u: the negative side's panels inward, its nodes in descending |u|;
        # the positive side's outward, its nodes in ascending |u|.
        table = np.empty((2, tau_k.size, n, 2, npan, NODES))
        table[:, :, :, 0] = cells[0, :, ::-1].transpose(2, 0, 3, 1, 4)
        table[:, :, :, 1] = cells[1, ..., ::-1].transpose(2, 0, 3, 1, 4)
        #: The map, shape ``(2, k, n, nodes)``: nodal values to moments.
        self.matrix = table.reshape(2, tau_k.size, n, -1)
        #: The map from values at the coarse nodes (:func:`kernel_nodes`, ``coarse``):
        #: each coarse panel's interpolant is a polynomial of the same degree on each of
        #: its two halves, which their own interpolants reproduce, so that its moments are
        #: the map's on its values at the halves' nodes.
        self.coarse = _coarsened(self.matrix)
        self.shape = (tau_k.size, n)

    def moments(self, values):
        """``(bounded, singular)`` moments, each shape ``(k, n)`` (or with the extra
        trailing axes of ``values``), of the kernels whose values at
        :func:`kernel_nodes` are ``values`` (shape ``(nodes,)`` or ``(nodes, m)``): at
        its nodes or at its coarse ones (:attr:`coarse`), told apart by their number."""
        values = np.asarray(values)
        by_nodes = {m.shape[-1]: m for m in (self.matrix, self.coarse)}
        if values.shape[0] not in by_nodes:
            raise ValueError(f"values at {values.shape[0]} nodes: the table's are "
                             f"{sorted(by_nodes)} (kernel_nodes, coarse or not)")
        table = by_nodes[values.shape[0]].reshape(2 * self.shape[0] * self.shape[1], -1)
        if np.iscomplexobj(values):
            # A real product on the real and imaginary parts side by side (half the
            # work of the complex one).
            flat = np.ascontiguousarray(values.reshape(values.shape[0], -1))
            out = (table @ flat.view(float)).view(complex)
        else:
            out = table @ values.reshape(values.shape[0], -1)
        return out.reshape((2,) + self.shape + values.shape[1:])


#: Points of the rule of a small cell (:func:`_tiny_cells`) and the least ratio of the
#: cell's distance from the edges (and of ``2/n``) to its half-width in ``tau``.  In the
#: rule's variable (affine in ``u``, and ``u - u_edge ~ tau^6`` next to an edge) the
#: edges, where the integrand's only singularities lie, are then at a Bernstein
#: parameter of 76 or more (measured, n = 12 to 64), so that the interpolation error is
#: about ``4 e 8 rho^-M / (rho - 1) = 1e-15`` of the integrand's size at most (derivation
#: S9; measured 3.8e-16 of a point's row of the table at most).
_TINY_POINTS = 8
_TINY_RHO = 200.0
#: Newton's steps for the offsets of those points.
_TINY_NEWTON = 3


@small_cache(2)
def _tiny_rule():
    """The Chebyshev points ``x_m`` (first kind) of :data:`_TINY_POINTS` and the
    matrix ``Q[m, j] = integral_-1^1 l_m(x) L_j(x) dx``, ``l_m`` their Lagrange
    polynomials and ``L_j`` those of a panel's nodes (:func:`_chebyshev`): exact by
    Gauss-Legendre (the product has degree ``_TINY_POINTS + NODES - 2``)."""
    m = _TINY_POINTS
    x = np.cos(np.pi * (np.arange(m) + 0.5) / m)
    gx, gw = np.polynomial.legendre.leggauss((m + NODES) // 2 + 1)
    q = (_lagrange(gx, x) * gw[:, None]).T @ _lagrange(gx, _chebyshev())
    x.setflags(write=False)
    q.setflags(write=False)
    return x, q


def _tiny_cells(tau_k, t_k, low, high, lo, hi, side, to_cos, cmap):
    """The table's entries of cells small against their distance from the edges, the
    cells' ``|u|`` from ``low`` to ``high`` and their offsets from ``lo`` to ``hi``:
    shape ``(cells, 2, n, NODES)``, the nodes in the Chebyshev points' (descending)
    order.

    In ``x``, the panel's variable (``|u| = mid + half x``), a cell's moments are
    ``integral_-1^1 F(x) L_j(x) dx`` with ``F = phi_i W |dtau/dx|``,
    ``|dtau/dx| = half/(sin T T')``: ``F`` interpolated on the points of
    :func:`_tiny_rule` and integrated against the panel's Lagrange polynomials exactly
    (``Q``).  ``F`` is
    analytic about the cell (its singularities are at the edges ``tau = 0, pi`` alone:
    the map's ``sin T T'`` vanishes nowhere else), so that the rule's error is that of
    interpolation on a Bernstein ellipse of parameter :data:`_TINY_RHO` or more.  The
    points' offsets by Newton's method on ``u(tau_k + d)`` from the line through the
    ends' (off by about ``(delta/distance) delta``, ``delta`` the half-width, at most
    ``delta/200``: three steps square that relative error three times, below
    rounding)."""
    x, q = _tiny_rule()
    mid, half = 0.5 * (high + low), 0.5 * (high - low)
    a = (mid[:, None] + half[:, None] * x) * side
    tau_k, t_k = tau_k[:, None], t_k[:, None]
    d = 0.5 * (hi + lo)[:, None] + 0.5 * (hi - lo)[:, None] * x
    for _ in range(_TINY_NEWTON):
        slope = np.sin(cmap.T(tau_k + d)) * cmap.dT(tau_k + d)
        d = d - (_offset_u(tau_k, t_k, d, cmap) - a) / slope
    tau = tau_k + d
    basis, weights = _basis(tau, to_cos, cmap)
    jacobian = half[:, None] / (np.sin(cmap.T(tau)) * cmap.dT(tau))
    f = basis[:, None] * (weights * jacobian).transpose(1, 0, 2)[..., None]
    return np.matmul(f.transpose(0, 1, 3, 2), q)           # (cells, 2, n, NODES)


def _coarsened(matrix):
    """``matrix`` (the last axis the nodes of :func:`kernel_nodes`) acting on values at
    the coarse nodes: each coarse panel's values interpolated to its two halves' nodes
    (one ``(2 NODES, NODES)`` map, the same for every panel: the panels are similar)."""
    xc = np.sort(_chebyshev())
    fine = _panels()[:3] / _panels()[0]                 # [1, sqrt 2, 2]
    mid, half = 0.5 * (fine[1:] + fine[:-1]), 0.5 * np.diff(fine)
    # The halves' nodes (ascending |u|) in the coarse panel's [-1, 1].
    x = ((mid[:, None] + half[:, None] * xc) - 1.5 * fine[0]).ravel() / (0.5 * fine[0])
    refine = _lagrange(x, xc)                           # (2 NODES, NODES)
    side = matrix.shape[-1] // 2
    # Each side's pairs of panels: one product a side (the negative side's nodes descend
    # in |u|, and so does the map's order there) on a view of the map, no copy.
    pairs = matrix.reshape(-1, 2, side // (2 * NODES), 2 * NODES)
    out = np.matmul(pairs, np.stack([refine[::-1, ::-1], refine]))
    return out.reshape(matrix.shape[:-1] + (side,))


def _basis(tau, to_cos, cmap):
    """The representation's nodal bases at ``tau`` (any shape; its cosine series
    through ``to_cos``), shape ``tau.shape + (n,)``, and the pressure's and the flux's
    weights there, shape ``(2,) + tau.shape``.  ``cos(j tau) = T_j(cos tau)`` by the
    Chebyshev recurrence (a tenth of the cosines' cost):
    its rounding grows to ``j^2 eps/2`` only next to ``tau = 0, pi``, where the weights
    vanish (the tables within 1.5e-15 of those of the cosines at n = 64)."""
    n = to_cos.shape[0]
    basis = np.polynomial.chebyshev.chebvander(np.cos(tau), n - 1) @ to_cos
    return basis, np.stack(cmap.weights(tau))


def _inner_basis(u):
    """``1, ln u, u, u ln u`` at ``u > 0``, shape ``u.shape + (4,)``."""
    lg = np.log(u)
    return np.stack([np.ones_like(u), lg, u, u * lg], axis=-1)


def kernel_table(tau, n, to_cos, cmap=GRADED) -> KernelTable:
    """The :class:`KernelTable` of points ``tau``, ``n`` and ``cmap``, kept per process."""
    tau = np.ascontiguousarray(tau, dtype=float)
    key = (tau.tobytes(), n, cmap.name)
    return TABLES.get(key, lambda: KernelTable(tau, n, to_cos, cmap))
