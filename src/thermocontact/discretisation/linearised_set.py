"""A contact set of several zones linearised about a steady solution: ``M(b) c = 0``.

Every zone's edges move (derivation section 18b, eqs. S18-S28): zone ``j``, of centre
``c_j`` and half-width ``Delta_j`` (units of the Hertz half-width ``l``), carries its
pressure and heat-flux difference in its own moving coordinate as the single patch
does (:class:`~.linearised.LinearisedContact`, section 18), with the unknowns
``phi~_j``, ``psi~_j``, ``sig~_j = c~_j/Delta_j``, ``del~_j = Delta~_j/Delta_j``; the rigid
approach ``D~`` is shared.  Each zone's own block is the single patch's ``M`` of its
equivalents (``Pe_j = Pe_l Delta_j``, ``fHPe_j = fHPe_l Delta_j``, ``P_H/P = Delta_j^2``,
``sigma/Delta = c_j/Delta_j``) at its own rate ``b Delta_j^2``, its densities carried
times ``Delta_j`` (unit integral for one zone), with two terms of the common length
unit (S19): Flamant's ``(1/pi) ln Delta_j int p~_j`` and the stationary half-plane's
``-ln Delta_j int q~_2j``, and the profile's slope where it is not the cylinder's
(S20).  Zone ``j``'s terms at zone ``i``'s points (S21) are its sources' fields,
``int K(w) q~_j`` with ``w = c_i + Delta_i s - c_j - Delta_j r``, and the edges' terms
``int [K_0'(w) X~_i(s) - K_b'(w) Y~_j(r)] q0_j``, ``X~_i = Delta_i(sig~_i + del~_i s)``,
``Y~_j = Delta_j(sig~_j + del~_j r)``: the source's edges move, and so do the points;
at separated arguments every kernel is smooth, and its integral against the source
zone's interpolant is the midpoint rule in ``tau`` (as the steady solver's product
integration), the transient kernels interpolated on Chebyshev panels of the pair's
interval of ``w``; the Dundurs term's step is a constant there (S26).  The load row is
the sum of the zones', and the stationary half-plane's temperature constant ``l(b)``
multiplies the whole perturbed heat into it on every zone (S22): with each later zone's
first temperature row less the first zone's, it stands on the first zone's alone, as
the single patch's does, and ``M(0)`` is the Jacobian of the steady contact set at fixed
load and fixed ``lam``.

Unknowns, in this order: the first zone's ``phi~``, ``psi~``, ``D~``, ``sig~``,
``del~``, then each later zone's ``phi~``, ``psi~``, ``sig~``, ``del~``
(``m (2n + 2) + 1``); rows: the first zone's displacement (``n + 2``), the load and
its temperature (``n``), then each later zone's displacement and temperature.  One
zone is the single patch, its rows and unknowns in its order.

Modelled: a stationary or a moving half-plane (S27: no temperature constant, every
temperature row complete), with or without the Dundurs term (S26), with perfect
thermal contact or an interface conductance (S28: local, each zone's block with its
own Biot number).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from functools import cached_property

import numpy as np
from numpy.polynomial import Polynomial

from ..numerics.interpolation import panel_interpolation
from ..numerics.moment_engine import bounded_weight, singular_weight, stretch
from ..physics.green_functions import (cylinder_displacement, cylinder_temperature,
                                       cylinder_temperature_gradient_regular, moving_slope)
from ..physics.transient_green_functions import (transient_displacement_and_slope,
                                                 transient_temperature,
                                                 transient_temperature_gradient_regular)
from ..problem.conductance import Conductance
from ..problem.parameters import Parameters
from ..problem.validation import InputError
from .linearised import LinearisedContact, logarithm_constant, projections
from .system import zone_parameters

__all__ = ["LinearisedContactSet", "modulus_bound", "source_points"]

#: The zones' transient kernels at each other's points are interpolated to this, of
#: their scale (:meth:`LinearisedContactSet._cross_kernels`): ten times the rounding
#: of their quadrature's values (the last Chebyshev coefficients of a resolved panel
#: are that rounding, up to 3e-15 of the kernel's size).
CROSS_TOLERANCE = 1e-14

#: The cylinder's initial gap ``X^2/2`` (units ``l^2/R``), the default profile.
CYLINDER_GAP = Polynomial([0.0, 0.0, 0.5])


def _steady_fields(u, scale):
    """A body's steady slope ``S_0`` and temperature gradient ``G_0`` (with its Cauchy
    part ``1/u``) at ``u`` for its signed scale (derivation D4, D7, D14b; at rest
    ``sgn(u)/2`` and ``1/u``)."""
    if scale:
        return moving_slope(u, scale), 1.0 / u + cylinder_temperature_gradient_regular(u, scale)
    return 0.5 * np.sign(u), 1.0 / u


def modulus_bound(half_widths, single) -> float:
    """A contact set's modulus bound in ``k2/l^2`` from the single patch's ``single``
    (``k2/Delta^2``): ``single / Delta_min^2``, ``Delta_min`` the narrowest zone's
    half-width in units of ``l`` (derivation S24: at large ``|b|`` the zones couple
    through terms that do not depend on ``b``, each zone's block is its single
    patch's at ``b Delta_j^2``, and beyond this bound every zone's thermal layer is
    thinner than ``Delta_j/sqrt(single)``).  One zone: the single patch's bound."""
    return float(single) / float(np.min(half_widths)) ** 2


#: The sources' rule's points at the narrowest gap ``delta`` (in the adjacent zones'
#: larger half-width) are at least ``SOURCE_RATE * delta^(-1/6)`` (S21), and at most
#: :data:`MAX_SOURCE_POINTS`.
SOURCE_RATE = 25.0
MAX_SOURCE_POINTS = 4096


def source_points(edges, n, alpha=0.5) -> int:
    """The points ``N`` of the cross-zone integrals' midpoint rule in ``tau`` (S21):
    ``max(64, 4n)`` (``max(256, 4n)`` with the Dundurs term's edge exponents), and
    where zones close up ``25 delta^(-1/6)``, ``delta`` the narrowest gap over the
    larger of its two zones' half-widths.  A kernel singular ``delta`` beyond an edge
    is analytic in a strip of half-width about ``(9 delta/2)^(1/6)/2`` in ``tau``, so
    the rule's error falls like ``exp(-1.3 N delta^(1/6))`` (measured from
    ``delta = 1e-3`` to ``1e-5``): ``25 delta^(-1/6)`` takes it below 1e-14.  M(b)
    then agrees with eight times as many points to 1e-14, 1e-12 and 3e-11 of its
    largest entry at gaps of 1e-3, 1e-5 and 1e-6 to 1e-8 (with 64 points: 2e-12,
    7e-6, 3e-4 and 2e-2; the near-singular kernels' own values limit it then; with the
    Dundurs term, 2e-10 at 1e-8).  At most :data:`MAX_SOURCE_POINTS` (``delta`` about
    5e-14)."""
    edges = np.asarray(edges, dtype=float).reshape(-1, 2)
    count = max(64 if alpha == 0.5 else 256, 4 * int(n))
    if len(edges) > 1:
        half = 0.5 * (edges[:, 1] - edges[:, 0])
        gaps = (edges[1:, 0] - edges[:-1, 1]) / np.maximum(half[1:], half[:-1])
        count = max(count, math.ceil(SOURCE_RATE * float(np.min(gaps)) ** (-1.0 / 6.0)))
    return min(count, MAX_SOURCE_POINTS)


@dataclass(frozen=True, eq=False)
class LinearisedContactSet:
    """A steady contact set linearised with its edges free (derivation section 18b).

    Attributes
    ----------
    parameters : Parameters
        ``pe = Pe_l`` and ``fhpe = fHPe_l``, in units of the Hertz half-width ``l``
        (the half-plane's ``c2 = R Pe_l``, the Dundurs term's ``free_term`` as they
        are).
    representation : Representation
        An edge-graded one (the steady solution's).
    edges : ndarray, shape (m, 2)
        ``(a_j, b_j)`` of each zone, ascending, units of ``l``.
    phi, psi : ndarray, shape (m, n)
        Each zone's steady factors in units of ``P/l`` and ``f v P/l``
        (:class:`~thermocontact.solvers.zones.ZoneSolution`'s).
    profile : Polynomial, optional
        The initial gap against ``X`` in units of ``l^2/R`` (default ``X^2/2``).
    conductance : Conductance, optional
        An interface conductance, ``Bi0 = h0 l/K2`` at ``p_ref = P/(2 l)``
        (:class:`~thermocontact.solvers.zones.ZoneSolution`'s); None for perfect
        thermal contact (S28).
    """

    parameters: Parameters
    representation: object
    edges: np.ndarray
    phi: np.ndarray
    psi: np.ndarray
    profile: Polynomial = field(default_factory=lambda: CYLINDER_GAP)
    conductance: Conductance | None = None

    def __post_init__(self):
        par = self.parameters
        edges = np.asarray(self.edges, dtype=float).reshape(-1, 2)
        if np.any(np.diff(edges.ravel()) <= 0.0):
            raise InputError("edges must be increasing, a1 < b1 < a2 < ...",
                             parameters=("edges",))
        object.__setattr__(self, "edges", edges)

    @property
    def n(self) -> int:
        return self.representation.n

    @property
    def size(self) -> int:
        return len(self.edges) * (2 * self.n + 2) + 1

    #: The unit of the rate ``b``.
    RATE_UNITS = "k2/l^2"

    @property
    def temperature_rows(self) -> np.ndarray:
        """The rows of :meth:`matrix` that are the temperature's, every zone's."""
        n, m = self.n, len(self.edges)
        starts = [n + 3] + [2 * n + 3 + k * (2 * n + 2) + n + 2 for k in range(m - 1)]
        return np.concatenate([np.arange(s, s + n) for s in starts])

    @cached_property
    def _geometry(self):
        """Each zone's half-width and centre (units of ``l``)."""
        a, b = self.edges.T
        return 0.5 * (b - a), 0.5 * (a + b)

    @property
    def moving(self) -> bool:
        """Whether the half-plane moves (``c2 = R Pe_l != 0``): no temperature constant,
        ``b = 0`` no branch point (S27); at rest, the constant of S22."""
        return self.parameters.half_plane_scale != 0.0

    @cached_property
    def zones(self) -> tuple:
        """Each zone's single patch (:class:`~.linearised.LinearisedContact`): its
        equivalents, its densities times ``Delta_j`` (S19)."""
        out = []
        cond = self.conductance
        for h, c, ph, ps in zip(*self._geometry, self.phi, self.psi):
            # The conductance in the zone's own scaling (S28, the inverse of D37a):
            # Bi0_j = Bi0 Delta_j^(1 - m).
            own = None if cond is None else Conductance(
                cond.biot0 * float(h) ** (1.0 - cond.exponent), cond.exponent)
            out.append(LinearisedContact(zone_parameters(self.parameters, float(h)),
                                         self.representation, h * np.asarray(ph),
                                         h * np.asarray(ps), float(h * h), float(c / h),
                                         own))
        return tuple(out)

    @cached_property
    def _layout(self):
        """Where each zone's block of ``2n + 3`` rows and unknowns goes: the later
        zones' ``D~`` columns join the first's, their load rows the first's."""
        n, m = self.n, len(self.edges)
        B = 2 * n + 3
        rows = [i * B + n + 2 for i in range(1, m)]
        cols = [j * B + 2 * n for j in range(1, m)]
        keep_rows = np.setdiff1d(np.arange(m * B), rows)
        keep_cols = np.setdiff1d(np.arange(m * B), cols)
        # The first temperature row of each zone, in the folded rows.
        first = np.searchsorted(keep_rows, [i * B + n + 3 for i in range(m)])
        return B, rows, cols, keep_rows, keep_cols, first

    @cached_property
    def _sources(self):
        """The rule of the cross-zone integrals (S21): ``r = cos T(tau)`` at ``N``
        midpoints in ``tau``, the pressure's and the flux difference's weights
        ``(pi/N) w(cos T) sin T T'`` (``sin^2 T T'`` without the Dundurs term) and
        ``(pi/N) T'`` (``p dr`` and ``q' dr`` in ``tau``), and the cosine series taking
        nodal values there: the moments of the zone's interpolant of its density
        against the kernel, as the steady solver's product integration forms them, to
        the midpoint rule's error: exponentially small in ``N = max(64, 4n)`` for
        the weights of ``alpha = 1/2``, smooth and periodic; ``O(N^-(6 alpha + 6))``
        with the Dundurs term's edge exponents (``tau^(6 alpha + 5)`` at the edge,
        :func:`~thermocontact.numerics.moment_engine.weight_integrals`), below 1e-14
        with ``N = max(256, 4n)``; more where zones close up
        (:func:`source_points`)."""
        rep, n = self.representation, self.n
        alpha = getattr(rep, "alpha", 0.5)
        count = source_points(self.edges, n, alpha)
        tau = np.pi * (np.arange(count) + 0.5) / count
        series = np.cos(np.multiply.outer(tau, np.arange(n))) @ rep.to_cos
        step = np.pi / count
        return (np.cos(stretch(tau)), step * bounded_weight(tau, alpha),
                step * singular_weight(tau), series)

    @cached_property
    def _points(self):
        """The projections and their points ``s`` in each zone's own coordinate."""
        x, pd, pt = projections(self.n)
        s, _ = self.representation.projection_points(x)
        return pd, pt, s

    def matrix(self, b, *, split=False):
        """``M(b)``, complex, shape ``(m (2n + 2) + 1,)`` square (eqs. S18-S28).

        Parameters
        ----------
        b : complex
            The rate in units of ``k2/l^2``, ``Re b > 0`` (the zones' kernels at each
            other's points are interpolated there, S21; to the left of the imaginary
            axis they are not resolved and are refused); ``b = 0`` gives the limit (S8,
            S22): the first zone's first temperature row is the heat partition's (a
            moving half-plane's, S27: every temperature row complete).
        split : bool
            Return ``(M_reg, ell, row)`` with ``M = M_reg + ell * outer(e, row)``, ``e``
            the first zone's first temperature row, as
            :meth:`~.linearised.LinearisedContact.matrix`.

        Returns
        -------
        ndarray, or tuple with ``split``
        """
        if b != 0 and not complex(b).real > 0.0:
            raise InputError(f"b must have a positive real part (or be 0) for a contact "
                             f"set's M(b), got {b!r}", parameters=("b",))
        n, m = self.n, len(self.edges)
        B, load_rows, d_cols, keep_rows, keep_cols, first = self._layout
        pd, pt, s = self._points
        h, c = self._geometry
        full = np.zeros((m * B, m * B), dtype=complex)
        w = np.zeros(m * B, dtype=complex)
        moving = self.moving
        ell = 0.0 if b == 0 or moving else logarithm_constant(b)
        for i, zone in enumerate(self.zones):
            block = slice(i * B, (i + 1) * B)
            reg, _, row = zone.matrix(self._zone_rate(b, i), split=True)
            reg = np.array(reg, dtype=complex)
            # The common length unit (S19): Flamant's ln Delta_i int p~_i, the
            # stationary half-plane's l(b Delta_i^2) - l(b) = -ln Delta_i (a moving
            # one's temperature is scale-free, S27: row = 0).
            lnh = np.log(h[i])
            wp = zone.representation.pressure_rule.weights
            reg[:n + 2, :n] += (lnh / np.pi) * np.outer(pd.sum(axis=1), wp)
            reg[n + 3] -= lnh * row
            # Flamant's edges' term (1/pi) del~ int p0 (S5), the zone's load for the
            # single patch's 1.
            reg[:n + 2, 2 * n + 2] += pd.sum(axis=1) * (wp @ zone.phi - 1.0) / np.pi
            # The profile's slope where it is not the cylinder's X (S20).
            X = c[i] + h[i] * s
            extra = -(2.0 / np.pi) * h[i] * (self.profile.deriv()(X) - X)
            reg[:n + 2, 2 * n + 1] += pd @ extra
            reg[:n + 2, 2 * n + 2] += pd @ (extra * s)
            full[block, block] = reg
            w[block] = row
        full += self._cross_constant
        for pair, kernels in self._cross_kernels(b).items():
            self._cross(full, *pair, kernels)
        # Fold the shared approach and the one load row (S22).
        for r in load_rows:
            full[n + 2] += full[r]
        for k in d_cols:
            full[:, 2 * n] += full[:, k]
        M = full[np.ix_(keep_rows, keep_cols)]
        w = w[keep_cols]
        if moving:
            # No temperature constant (S27): every temperature row complete.
            if split:
                return M, 0.0, np.zeros_like(w)
            return M.real if b == 0 else M
        # l(b) on every zone's first temperature row: on the first zone's alone.
        M[first[1:]] -= M[first[0]]
        if split:
            return M, ell, w
        if b == 0:
            M[first[0]] = w
            return M.real
        else:
            M[first[0]] += ell * w
        return M

    @cached_property
    def _pairs(self) -> dict:
        """For each zone ``j`` at each other zone ``i``'s points (S21), what does not
        depend on ``b``: the separated arguments ``u`` (points by sources), the steady
        densities at the sources (the pressure's ``P0`` and each body's heat ``q0``)."""
        s = self._points[2]
        h, c = self._geometry
        r, wp, wq, series = self._sources
        out = {}
        for i in range(len(h)):
            for j in range(len(h)):
                if i == j:
                    continue
                zone = self.zones[j]
                P0, psi0 = wp * (series @ zone.phi), series @ zone.psi
                u = (c[i] + h[i] * s)[:, None] - (c[j] + h[j] * r)[None, :]
                out[i, j] = u, P0, [ap * P0 + aq * wq * psi0
                                    for _, _, ap, aq in self._weights()]
        return out

    def _weights(self):
        """Each body's ``(f, sign, share of p, share of q')``: its thermal displacement's
        factor ``2 F d_k`` and its temperature's sign (S3-S4)."""
        par = self.parameters
        eta, rho, d, F = par.eta, par.K2_over_K1, par.delta1_over_delta2, par.fhpe
        return ((2.0 * F * d, rho, 0.5 * (1.0 + eta), 0.5),
                (2.0 * F, -1.0, 0.5 * (1.0 - eta), -0.5))

    @cached_property
    def _cross_constant(self) -> np.ndarray:
        """The zones' terms at each other's points that do not depend on ``b`` (S18,
        S21): Flamant's logarithm and its edges' terms, and each body's steady slope
        and temperature gradient at the receiver's moving points (``K_0' X~_i``)."""
        n, m = self.n, len(self.edges)
        B = 2 * n + 3
        pd, pt, s = self._points
        h, _ = self._geometry
        r, wp, _, series = self._sources
        par = self.parameters
        full = np.zeros((m * B, m * B))
        for (i, j), (u, P0, q0) in self._pairs.items():
            R = slice(i * B, i * B + n + 2)
            T = slice(i * B + n + 3, (i + 1) * B)
            own = slice(i * B + 2 * n + 1, i * B + 2 * n + 3)      # sig~_i, del~_i
            edge = slice(j * B + 2 * n + 1, j * B + 2 * n + 3)     # sig~_j, del~_j
            # Flamant's logarithm with the Dundurs term's step (S26), and the
            # logarithm's derivative 1/w (no rate; the step's vanishes off w = 0).
            flamant = np.log(np.abs(u)) / np.pi - 0.5 * par.free_term * np.sign(u)
            full[R, j * B:j * B + n] += pd @ ((flamant * wp) @ series)
            K = 1.0 / (np.pi * u)
            full[R, own] += pd @ self._moved_points(K, P0, i)
            full[R, edge] += pd @ self._moved_sources(K, P0, j)
            S0, G0 = zip(*(_steady_fields(u, scale) for scale in self._scales))
            # W' = -S, T' = -G: the steady fields at the moved points.
            for (f, sign, _, _), q, S, G in zip(self._weights(), q0, S0, G0):
                full[R, own] += f * (pd @ self._moved_points(-S, q, i))
                full[T, own] += sign * (pt @ self._moved_points(-G, q, i))
        return full

    def _moved_points(self, K, q0, i):
        """``int K(w) X~_i q0`` (S18): the receiver's columns ``sig~_i``, ``del~_i``."""
        a = K @ q0
        return self._geometry[0][i] * np.stack([a, a * self._points[2]], axis=1)

    def _moved_sources(self, K, q0, j):
        """``-int K(w) Y~_j q0`` (S18): the source's columns ``sig~_j``, ``del~_j``."""
        r = self._sources[0]
        return -self._geometry[0][j] * np.stack([K @ q0, K @ (r * q0)], axis=1)

    def _cross(self, full, i, j, kernels):
        """Zone ``j``'s terms at zone ``i``'s points that depend on ``b`` (S18, S21),
        added into ``full``: each body's ``W`` and ``T`` on the perturbed sources, its
        ``S_b`` and ``G_b`` on the moved sources (``kernels``, at the pair's ``u``)."""
        n = self.n
        B = 2 * n + 3
        pd, pt, s = self._points
        r, wp, wq, series = self._sources
        _, _, q0 = self._pairs[i, j]
        R = slice(i * B, i * B + n + 2)
        T = slice(i * B + n + 3, (i + 1) * B)
        src = slice(j * B, j * B + 2 * n)                      # phi~_j, psi~_j
        edge = slice(j * B + 2 * n + 1, j * B + 2 * n + 3)     # sig~_j, del~_j
        for (f, sign, ap, aq), q, (W, Tb, Sb, Gb) in zip(self._weights(), q0, kernels):
            if f:
                full[R, src] += f * (pd @ np.hstack([ap * (W * wp) @ series,
                                                     aq * (W * wq) @ series]))
                full[R, edge] += f * (pd @ self._moved_sources(-Sb, q, j))
            full[T, src] += sign * (pt @ np.hstack([ap * (Tb * wp) @ series,
                                                    aq * (Tb * wq) @ series]))
            full[T, edge] += sign * (pt @ self._moved_sources(-Gb, q, j))

    def _cross_kernels(self, b) -> dict:
        """Each body's ``(W, T, S_b, G_b)`` at each pair's ``u`` (S21): the steady kernels
        at ``b = 0``; otherwise the transient ones (:meth:`_kernels`), interpolated on
        Chebyshev panels of each pair's interval of ``u`` to :data:`CROSS_TOLERANCE`
        (:func:`~thermocontact.numerics.interpolation.panel_interpolation`: a few dozen
        evaluations where the pair has ``N (n + 12)``)."""
        pairs = self._pairs
        if b == 0:
            return {pair: self._kernels(u, 0) for pair, (u, _, _) in pairs.items()}

        def f(x):
            return np.concatenate(self._kernels(x, b, constants=False))
        us = [u for u, _, _ in pairs.values()]
        values = panel_interpolation(f, [(u.min(), u.max()) for u in us], us,
                                     tol=CROSS_TOLERANCE)
        # The half-plane's constants at rest, taken off the values interpolated (the
        # kernels' scale, not theirs, sets the tolerance).
        W0, T0 = ((0.0, 0.0) if self.moving else
                  (2.0 / (np.pi * np.sqrt(complex(b))), logarithm_constant(complex(b))))
        return {pair: (v[:4], (v[4] - W0, v[5] - T0, v[6], v[7]))
                for pair, v in zip(pairs, values)}

    @property
    def _scales(self):
        """Each body's signed scale in units of ``l``: the cylinder's ``c_l``, the
        half-plane's ``c2 = R Pe_l`` (0 at rest)."""
        return self.parameters.cylinder_scale, self.parameters.half_plane_scale

    def _kernels(self, u, b, constants=True):
        """Each body's ``(W, T, S_b, G_b)`` at the separated arguments ``u`` (units of
        ``l``), the cylinder's with ``c_l`` and rate ``b k2/k1``, the half-plane's with
        ``c2`` and rate ``b``: at rest less the constants ``2/(pi sqrt b)`` and
        ``l(b)`` (S7, S21; not without ``constants``), moving as they are (S27); at
        ``b = 0`` the steady kernels."""
        par = self.parameters
        out = []
        for scale, rate in zip(self._scales, (b / par.k2_over_k1, b)):
            if b == 0:
                S, G = _steady_fields(u, scale)
                if scale:
                    W, T = cylinder_displacement(scale * u) / abs(scale), \
                        cylinder_temperature(scale * u)
                else:
                    W, T = -0.5 * np.abs(u), -np.log(np.abs(u))
                out.append((W, T, S, G))
                continue
            rate = complex(rate)
            flat = np.ravel(u)
            W, S = transient_displacement_and_slope(flat, scale, rate)
            T = transient_temperature(flat, scale, rate)
            G = transient_temperature_gradient_regular(flat, scale, rate) + 1.0 / flat
            if scale == 0.0 and constants:
                W = W - 2.0 / (np.pi * np.sqrt(rate))
                T = T - logarithm_constant(rate)
            out.append(tuple(np.reshape(v, np.shape(u)) for v in (W, T, S, G)))
        return out

    def _zone_rate(self, b, j):
        """Zone ``j``'s own rate ``b Delta_j^2`` (one expression, so that what
        :meth:`prepare` keeps is what :meth:`matrix` asks for, to the last bit)."""
        return b * self._geometry[0][j] ** 2

    def prepare(self, rates) -> None:
        """Each zone's :meth:`~.linearised.LinearisedContact.prepare` at its own rates
        ``b Delta_j^2``."""
        for j, zone in enumerate(self.zones):
            zone.prepare([self._zone_rate(b, j) for b in rates])
