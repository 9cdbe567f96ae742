"""The contact problem linearised about a steady single patch: ``M(b) c = 0``.

A perturbation growing as ``exp(b t)`` of a steady single patch at fixed load
(derivation section 18, eqs. S1-S9).  The pressure and the heat-flux difference are
carried in the contact's moving coordinate ``r = (xi - sigma(t))/Delta(t)`` by the
steady representation (``phi``, ``psi``); the edges move with the centre's and the
half-width's perturbations, whose effect on the fields at a fixed point is the
derivative of each Green's function acting on the steady densities: the
inverse-square-root terms of a moving edge enter through it, integrably.  The equations
are the undifferentiated ones, displacement (S3) and temperature (S4) continuity, at
points moving with the contact (whose steady terms remove the Cauchy kernel from the
edges' terms), ``u = s - r``:

* displacement, projected on ``cos(j tau)``, ``j <= n + 1``:
  ``(1/pi) int ln|u| p~ + 2F sum_i d_i int W_i q~_i + D~ + del~/pi
  - (2L/pi)(sig~ + del~ s)(sigma/Delta + s)
  + 2F sum_i d_i int {(S_i - S_i0)(sig~ + del~ r) - del~ u S_i0} q0_i = 0`` (S3, S5, S6);
* temperature, projected on ``cos(j tau)``, ``j < n``:
  ``sum_i +-[int T_i q~_i + int {(G_i - G_i0)(sig~ + del~ r) - del~ u G_i0} q0_i] = 0``
  (``rho`` for the cylinder, ``-1`` for the half-plane; S4, S6);
* the load: ``w_p . phi~ = 0``.

``W``, ``S``, ``T``, ``G`` are each body's transient displacement, slope, temperature
and gradient kernels (:mod:`thermocontact.physics.transient_green_functions`) with
``b`` the rate in units of ``k2/Delta^2``; at ``b = 0`` the steady kernels
(:mod:`thermocontact.physics.green_functions`).  The moments of every kernel are a
fixed linear map of its values at fixed nodes, built once per ``n``
(:mod:`thermocontact.numerics.tabulated_moments`; the same moments as the moment
engine's, which the tests compare): the kernels' values and their product with the
table are the only work per ``b``, and each body's moments are kept for the next
contact (the half-plane's depend on ``b`` alone, the cylinder's on ``b`` and ``Pe``).
Unknowns, in this order: ``phi~`` (n),
``psi~`` (n), the rigid approach ``D~``, ``sig~ = sigma~/Delta`` and
``del~ = Delta~/Delta``.

With ``edges="held"`` the same unknowns describe the contact whose edges stay where
they are (eq. S17, the linearisation of the transient's elements, whose contact set
holds under a small perturbation): the pressure's two inverse-square-root terms at the
fixed edges are ``-d/dr[(sig~ + del~ r) p0]``, their frictional heat goes into both
bodies as the pressure's does, and the heat-flux difference is ``psi~`` alone, so the
steady flux's singularity stays at the fixed edges.  Its columns ``sig~``, ``del~`` are
each kernel's moments on ``g = sqrt(1 - r^2) d/dr[(sig~ + del~ r) p0]``, equations at
fixed points.
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import cached_property

import numpy as np

from ..numerics.cache import BoundedCache, small_cache
from ..numerics.moment_engine import graded_map, nodes, stretch
from ..numerics.tabulated_moments import kernel_nodes, kernel_table
from ..physics.green_functions import (cylinder_displacement, cylinder_temperature,
                                       cylinder_temperature_gradient_regular, moving_slope)
from ..physics.transient_green_functions import (transient_displacement_and_slope,
                                                 transient_temperature_and_gradient_regular)
from ..problem.parameters import Parameters
from ..problem.validation import InputError
from .representations import EdgeGraded

__all__ = ["LinearisedContact", "check_modelled", "logarithm_constant", "projections"]


def check_modelled(*, method="graded") -> None:
    """Refuse, in one line naming the parameter, what the linearised contact does not
    model (before any work): a method other than an edge-graded one.

    Raises
    ------
    InputError
    """
    from .methods import METHODS

    if method not in METHODS or not METHODS[method].edge_exponents:
        raise InputError("stability needs an edge-graded method (graded, "
                         f"graded-collocation), got {method!r}", parameters=("method",))


def logarithm_constant(b):
    """``l(b) = -ln(sqrt(b)/2) - gamma_E``: the stationary half-plane's temperature
    ``K0(sqrt(b)|u|) = -ln|u| + l(b) + O(b u^2 ln)`` (derivation eq. T6), principal
    branch."""
    return -np.log(np.sqrt(complex(b)) / 2.0) - np.euler_gamma


def projections(n: int):
    """Points ``tau`` (``2n`` midpoints, descending in ``s``) and the projections on
    ``cos(j tau)``: ``n + 2`` rows for the displacement, ``n`` for the temperature."""
    m = 2 * n
    x = np.pi * (np.arange(m, 0, -1) - 0.5) / m
    p = (np.pi / m) * np.cos(np.arange(n + 2)[:, None] * x[None, :])
    return x, p, p[:n]


@dataclass(frozen=True, eq=False)
class LinearisedContact:
    """The linearised single patch about one steady solution (derivation section 18).

    Attributes
    ----------
    parameters : Parameters
        The steady solution's (the half-plane stationary or moving, S14; the Dundurs
        term or none, S15).
    representation : Representation
        An edge-graded one (the steady solution's).
    phi, psi : ndarray, shape (n,)
        The steady solution's factors.
    load_ratio, sigma_over_delta : float
        Its ``L = P_H/P`` and offset.
    conductance : Conductance, optional
        Its interface conductance (Biot number at the contact's scale, derivation
        S16); None for perfect thermal contact.
    edges : {"free", "held"}
        ``"free"``: the edges move (S5, S6), the stability of the steady contact;
        ``"held"``: they stay where they are (S17), the linearisation of a contact
        set held fixed (the transient's elements under a small perturbation), for a
        stationary half-plane without the Dundurs term and with perfect thermal
        contact.
    """

    parameters: Parameters
    representation: object
    phi: np.ndarray
    psi: np.ndarray
    load_ratio: float
    sigma_over_delta: float
    conductance: object = None
    edges: str = "free"

    def __post_init__(self):
        check_modelled(method="graded" if isinstance(self.representation, EdgeGraded)
                       else type(self.representation).__name__)
        if self.edges not in ("free", "held"):
            raise InputError(f"edges must be 'free' or 'held', got {self.edges!r}",
                             parameters=("edges",))
        par = self.parameters
        if self.edges == "held" and (par.half_plane_scale or par.free_term
                                     or self.conductance is not None):
            raise InputError("edges='held' is modelled for a stationary half-plane without "
                             "the Dundurs term and with perfect thermal contact (the "
                             "transient's model)", parameters=("edges",))

    @property
    def n(self) -> int:
        return self.representation.n

    @property
    def size(self) -> int:
        return 2 * self.n + 3

    #: The unit of the rate ``b``.
    RATE_UNITS = "k2/Delta^2"

    @property
    def temperature_rows(self) -> np.ndarray:
        """The rows of :meth:`matrix` that are the temperature's (S4)."""
        return np.arange(self.n + 3, self.size)

    @property
    def moving(self) -> bool:
        """Whether the half-plane moves through the contact (``c2 = R Pe != 0``): its
        kernels are then those of a moving body, ``b = 0`` is not a branch point and
        its temperature has no free constant (derivation S14)."""
        return self.parameters.half_plane_scale != 0.0

    @cached_property
    def _fixed(self):
        """What does not depend on ``b``: the points, the kernel table, Flamant's
        block and the steady kernels' edge terms (S5, S6)."""
        par, rep, n = self.parameters, self.representation, self.n
        x, pd, pt = projections(n)
        s, aux = rep.projection_points(x)
        table = kernel_table(aux, n, rep.to_cos, graded_map(rep.alpha))
        u = kernel_nodes()
        c, c2 = par.cylinder_scale, par.half_plane_scale

        def steady():
            # Flamant's logarithm with the Dundurs term's -b H(u) (its constant half goes
            # to D~; scale-invariant, it has no edges' terms, S15); u S_0 and
            # u (G_0 - 1/u) of each body, the stationary half-plane's G_0 being 1/u.
            values = np.stack([np.log(np.abs(u)) / np.pi - 0.5 * par.free_term * np.sign(u),
                               u * moving_slope(u, c),
                               u * moving_slope(u, c2) if c2 else 0.5 * np.abs(u),
                               u * cylinder_temperature_gradient_regular(u, c),
                               u * cylinder_temperature_gradient_regular(u, c2) if c2
                               else np.zeros_like(u)], axis=1)
            return _frozen([table.moments(values)])
        # Kept with the transient kernels' moments: the points of a map's row (one
        # Peclet number) share them.
        mom, = KERNEL_MOMENTS.get((table.key, "steady", float(c), float(c2),
                                   float(par.free_term)), steady)
        return dict(pd=pd, pt=pt, s=s, table=table, u=u, flamant=mom[0][..., 0],
                    flamant_flux=mom[1][..., 0],
                    uS0=(mom[..., 1], mom[..., 2]),
                    uG0=(mom[..., 3], mom[..., 4] if c2 else None),
                    interface=self._interface(aux), held=self._held_sources())

    def _held_sources(self):
        """``g = sqrt(1 - r^2) d/dr[(sig~ + del~ r) p0]`` at the nodes, shape (n, 2): the
        columns ``sig~``, ``del~`` of the pressure's edge terms with the edges held
        (S17), as flux-type nodal values (``g/sqrt(1 - r^2)`` is the density).  With
        ``r = cos T(tau)``, ``p0 = sin T phi0(tau)`` and ``dr/dtau = -sin T T'``,
        ``sin T d/dr = -(1/T') d/dtau``, ``T' = 2 sin^2 tau``: smooth and even in
        ``tau``.  None with the edges free."""
        if self.edges != "held":
            return None
        n = self.n
        tau = nodes(n)                                     # r ascending
        t = stretch(tau)
        sin_t, cos_t = np.sin(t), np.cos(t)
        j = np.arange(n)
        slope = -(np.sin(np.multiply.outer(tau, j)) * j) @ (self.representation.to_cos
                                                            @ self.phi)
        tail = sin_t * slope / (2.0 * np.sin(tau) ** 2)    # sin T phi0'(tau) / T'
        return np.stack([-cos_t * self.phi - tail,
                         -(cos_t ** 2 - sin_t ** 2) * self.phi - cos_t * tail], axis=1)

    def _interface(self, tau):
        """The interface's term of the temperature rows at the points ``tau`` (S16),
        shape (points, 2n + 3), or None for perfect thermal contact: with
        ``I = (pi/(2 Bi)) q`` (D33), ``Bi = Bi0 (p/p_ref)^m``, ``q = q' + eta p`` in the
        contact's moving coordinates and the flux scaled by ``1/Delta(t)``,
        ``I~ = (pi/(2 Bi)) (q~ - del~ q0 - m q0 (p~/p0 - del~))``."""
        cond = self.conductance
        if cond is None:
            return None
        par, rep, n = self.parameters, self.representation, self.n
        # Nodal values to values at the points (the cosine series in tau).
        at = np.cos(np.multiply.outer(tau, np.arange(n))) @ rep.to_cos
        t = stretch(tau)
        weight = 2.0 * np.sin(0.5 * t) ** (2.0 * rep.alpha) * np.cos(0.5 * t) ** (
            2.0 - 2.0 * rep.alpha)                       # w(s) = (1 - s)^a (1 + s)^(1 - a)
        inverse_sin = 1.0 / np.sin(t)                    # q' = psi/sqrt(1 - s^2)
        p0 = weight * (at @ self.phi)
        q0 = par.eta * p0 + inverse_sin * (at @ self.psi)
        factor = 0.5 * np.pi / cond.biot(p0)
        m = cond.exponent
        out = np.zeros((tau.size, self.size))
        out[:, :n] = (factor * weight * (par.eta - (m * q0 / p0 if m else 0.0)))[:, None] * at
        out[:, n:2 * n] = (factor * inverse_sin)[:, None] * at
        out[:, 2 * n + 2] = -(1.0 - m) * factor * q0
        return out

    def kernel_values(self, b):
        """The kernels that depend on ``b`` at the table's nodes, shape (nodes, 8):
        per body (cylinder, half-plane) ``W``, ``T``, ``S_b - S_0``, ``G_b - G_0``
        (``G`` less ``1/u``), each body's rate ``b k2/k_i``; the stationary
        half-plane's displacement and temperature less their diverging constants
        ``2/(pi sqrt b)`` and ``l(b)`` (T11, T6).  At ``b = 0`` the steady kernels
        (the differences 0)."""
        par = self.parameters
        u, c, c2 = self._fixed["u"], par.cylinder_scale, par.half_plane_scale
        if b == 0:
            out = np.zeros((u.size, 8))
            for k, scale in ((0, c), (4, c2)):
                if scale:
                    out[:, k] = cylinder_displacement(scale * u) / abs(scale)
                    out[:, k + 1] = cylinder_temperature(scale * u)
            if not c2:
                out[:, 4] = -0.5 * np.abs(u)
                out[:, 5] = -np.log(np.abs(u))
            return out
        b = complex(b)
        return np.concatenate([_body_values(c, b / par.k2_over_k1, coarse=False),
                               _body_values(c2, b, coarse=False)], axis=1)

    def kernel_moments(self, b):
        """``(bounded, singular)`` moments of :meth:`kernel_values` at the table's
        points, each shape ``(points, n, 8)``, the stationary half-plane's from its values
        at the coarse nodes (:func:`_body_values`).  Each body's are kept per process by its
        scale and rate (:data:`KERNEL_MOMENTS`): a map's points share the half-plane's
        (they depend on ``b`` alone) and a line's points at one Peclet number the
        cylinder's."""
        table = self._fixed["table"]
        if b == 0:
            par = self.parameters
            key = (table.key, float(par.cylinder_scale), float(par.half_plane_scale), 0.0)
            return KERNEL_MOMENTS.get(key, lambda: _frozen(table.moments(self.kernel_values(0))))
        both = [_body_moments(table, c, rate) for c, rate in self._bodies(complex(b))]
        return tuple(np.concatenate([m[w] for m in both], axis=-1) for w in range(2))

    def _bodies(self, b):
        """Each body's scale and rate at ``b``: the cylinder's ``b k2/k1``."""
        par = self.parameters
        return ((par.cylinder_scale, b / par.k2_over_k1), (par.half_plane_scale, b))

    def prepare(self, rates) -> None:
        """Compute and keep the moments (:meth:`kernel_moments`) at several rates at
        once: the kernels' values at each rate not yet kept, and one product of the
        table with all of them (the table, 11 MB at n = 12, read once instead of once
        a rate)."""
        table = self._fixed["table"]
        for body in range(2):
            todo = {}
            for b in rates:
                if b != 0:
                    c, rate = self._bodies(complex(b))[body]
                    key = (table.key, float(c), complex(rate))
                    if key not in KERNEL_MOMENTS and key not in todo:
                        todo[key] = (c, rate)
            if not todo:
                continue
            # One body's scale, its rates' kernels in one pass (those not kept).
            c = next(iter(todo.values()))[0]
            values = _kept_values(c, [rate for _, rate in todo.values()])
            bounded, singular = table.moments(values)
            for j, key in enumerate(todo):
                part = _frozen(np.array(m[..., 4 * j:4 * j + 4]) for m in (bounded, singular))
                KERNEL_MOMENTS.get(key, lambda part=part: part)

    def matrix(self, b, *, split=False, values=None):
        """``M(b)``, complex, shape ``(2n + 3, 2n + 3)`` (eqs. S3-S8).

        Parameters
        ----------
        b : complex
            The rate in units of ``k2/Delta^2`` (``Delta`` the steady half-width), off
            the cut ``b < 0``; ``b = 0`` gives the limit (S8): the stationary
            half-plane's temperature constant ``l(b)`` (T6) replaced by the heat
            partition row.
        split : bool
            Return ``(M_reg, ell, row)`` with ``M = M_reg + ell * outer(e, row)``,
            ``e`` the temperature's first projection: the part regular as ``b -> 0``
            and the diverging constant of the stationary half-plane's temperature.
        values : ndarray, optional
            :meth:`kernel_values` at ``b``, where already computed (otherwise the
            moments kept by :meth:`kernel_moments`).

        Returns
        -------
        ndarray, or tuple with ``split``
        """
        if values is None:
            bounded, singular = self.kernel_moments(b)
        else:
            bounded, singular = self._fixed["table"].moments(values)
        rows, ell, row = self._assemble(bounded[None], singular[None], [b])
        rows = rows[0]
        if split:
            return rows, ell[0], row
        n = self.n
        if b == 0 and not self.moving:
            rows[n + 3] = row
        elif b != 0:
            rows[n + 3] += ell[0] * row
        return rows

    def matrices(self, rates):
        """``M(b)`` at several non-zero rates at once, shape ``(len(rates), 2n + 3,
        2n + 3)``: :meth:`matrix` of each (the same assembly, on a stack), their kernel
        moments prepared together (:meth:`prepare`)."""
        rates = [complex(b) for b in rates]
        if any(b == 0 for b in rates):
            raise InputError("matrices: the rates must be non-zero (matrix(0) is the limit "
                             "b -> 0)", parameters=("rates",))
        table = self._fixed["table"]
        par = self.parameters
        key = (table.key, float(par.cylinder_scale), float(par.half_plane_scale),
               float(par.k2_over_k1), tuple(rates))

        def stacked():
            self.prepare(rates)
            # Each body's moments stacked over the rates, the bodies side by side.
            bodies = [[_body_moments(table, *self._bodies(b)[body]) for b in rates]
                      for body in range(2)]
            return _frozen(np.concatenate([np.stack([m[w] for m in kept]) for kept in bodies],
                                          axis=-1) for w in range(2))
        bounded, singular = STACKED_MOMENTS.get(key, stacked)
        rows, ell, row = self._assemble(bounded, singular, rates)
        rows[:, self.n + 3] += ell[:, None] * row
        return rows

    def _assemble(self, bounded, singular, rates):
        """``(M_reg, ell, row)`` of :meth:`matrix` (``split``) at each of ``rates``,
        all zero or none, from their kernel moments stacked on a first axis: shapes
        ``(rates, 2n + 3, 2n + 3)``, ``(rates,)`` and ``(2n + 3,)``."""
        par, rep, n = self.parameters, self.representation, self.n
        fixed = self._fixed
        pd, pt, s = fixed["pd"], fixed["pt"], fixed["s"]
        nonzero = rates[0] != 0
        ell = np.array([0.0 if b == 0 or self.moving else logarithm_constant(b)
                        for b in rates])
        eta, rho, d, F = par.eta, par.K2_over_K1, par.delta1_over_delta2, par.fhpe
        phi0, psi0 = self.phi, self.psi
        L0, sig0 = self.load_ratio, self.sigma_over_delta
        r = rep.pressure_rule.nodes
        wp, wq = rep.pressure_rule.weights, rep.flux_rule.weights
        # Each body's heat from (phi, psi): q1 = ((1 + eta) p + q')/2,
        # q2 = ((1 - eta) p - q')/2.
        share = ((0.5 * (1.0 + eta), 0.5), (0.5 * (1.0 - eta), -0.5))

        def mom(body, k):
            return bounded[..., 4 * body + k], singular[..., 4 * body + k]

        def on_heat(m, i):
            (ap, aq), (Mb, Ms) = share[i], m
            return np.concatenate([ap * Mb, aq * Ms], axis=-1)

        def steady_heat(m, i, weight=1.0):
            # int K q0_i dr for the steady heat times ``weight`` at the nodes.
            (ap, aq), (Mb, Ms) = share[i], m
            return ap * (Mb @ (weight * phi0)) + aq * (Ms @ (weight * psi0))

        dtype = bounded.dtype
        count = bounded.shape[0]

        def edges(diff, u_steady, i):
            # The columns (sig~, del~) of int (K_b - K_0)(u)(sig~ + del~ r) q0_i
            # - del~ int u K_0(u) q0_i (S6).
            out = np.zeros((count, s.size, 2), dtype=dtype)
            if nonzero:
                out[..., 0] = steady_heat(diff, i)
                out[..., 1] = steady_heat(diff, i, r)
            if u_steady is not None:
                out[..., 1] -= steady_heat(u_steady, i)
            return out

        size = self.size
        disp = np.zeros((count, s.size, size), dtype=dtype)
        temp = np.zeros((count, s.size, size), dtype=dtype)
        cols = slice(0, 2 * n)
        # Elastic (Flamant, and the Dundurs term) on phi~; the edges' elastic and
        # profile terms (S5).
        disp[..., :n] += fixed["flamant"]
        disp[..., 2 * n] = 1.0
        disp[..., 2 * n + 1] = -(2.0 * L0 / np.pi) * (sig0 + s)
        disp[..., 2 * n + 2] = 1.0 / np.pi - (2.0 * L0 / np.pi) * s * (sig0 + s)
        # Each body's thermal displacement (factor 2 F d_i) and its edges' terms.
        uS0 = [(m[0], m[1]) for m in fixed["uS0"]]
        for i, weight in enumerate((d, 1.0)):
            if weight == 0.0:
                continue
            f = 2.0 * F * weight
            disp[..., cols] += f * on_heat(mom(i, 0), i)
            disp[..., 2 * n + 1:] += f * edges(mom(i, 2), uS0[i], i)
        # Temperatures: rho times body 1's minus body 2's (S4), u G_0 = 1 + u (G_0 - 1/u).
        uG0 = [None if m is None else (m[0], m[1]) for m in fixed["uG0"]]
        for i, sign in enumerate((rho, -1.0)):
            temp[..., cols] += sign * on_heat(mom(i, 1), i)
            e = edges(mom(i, 3), uG0[i], i)
            e[..., 1] -= share[i][0] * (wp @ phi0) + share[i][1] * (wq @ psi0)
            temp[..., 2 * n + 1:] += sign * e
        if fixed["interface"] is not None:
            temp += fixed["interface"]
        if fixed["held"] is not None:
            # The edges held (S17): the pressure's edge terms -d/dr[(sig~ + del~ r) p0],
            # each kernel's flux-type moments on g, at fixed points; its heat shared as
            # the pressure's.
            g = fixed["held"]
            disp[..., 2 * n + 1:] = -fixed["flamant_flux"] @ g
            temp[..., 2 * n + 1:] = 0.0
            for i, (weight, sign) in enumerate(zip((d, 1.0), (rho, -1.0))):
                disp[..., 2 * n + 1:] -= 2.0 * F * weight * share[i][0] * (mom(i, 0)[1] @ g)
                temp[..., 2 * n + 1:] -= sign * share[i][0] * (mom(i, 1)[1] @ g)
        rows = np.zeros((count, size, size), dtype=dtype)
        rows[:, :n + 2] = pd @ disp
        rows[:, n + 2, :n] = rep.pressure_rule.weights
        rows[:, n + 3:] = pt @ temp
        # -l(b) int q2~ dr, a constant: on the temperature's first projection only (the
        # stationary half-plane's; a moving one's temperature has no free constant).
        row = -np.sum(pt[0]) * np.concatenate([share[1][0] * wp, share[1][1] * wq, np.zeros(3)])
        if self.moving:
            row = np.zeros_like(row)
        return rows, ell, row


#: Each body's kernel moments per table, scale and rate, kept per process: a map's
#: points share the half-plane's (its kernels depend on ``b`` alone) and a line's
#: points at one Peclet number the cylinder's (37 kB an entry at n = 12); and the steady
#: kernels' moments of M(0), per table and the bodies' scales.
KERNEL_MOMENTS = BoundedCache("transient kernel moments", 64 * 2**20)


#: The moments of :meth:`LinearisedContact.matrices` stacked over its rates, kept per
#: table, scales and rates: the next point of a map's row evaluates its neighbour's
#: contour samples first, the same rates (some 43, 6 MB at n = 12, formed once).
STACKED_MOMENTS = BoundedCache("stacked kernel moments", 16 * 2**20)


#: Each body's kernel values at the nodes (:func:`_body_values`) per scale and rate,
#: kept per process: they do not depend on ``n``, so that the error estimate's ``M(b)``
#: at ``3n/2`` takes those of the rates Newton's method took at ``n`` (151 kB an entry
#: for a moving body, 76 kB for the stationary half-plane).
KERNEL_VALUES = BoundedCache("transient kernel values", 32 * 2**20)


def _body_moments(table, c, b):
    """The moments (:meth:`~thermocontact.numerics.tabulated_moments.KernelTable.moments`)
    of one body's :func:`_body_values`, kept in :data:`KERNEL_MOMENTS`."""
    return KERNEL_MOMENTS.get((table.key, float(c), complex(b)),
                              lambda: _frozen(table.moments(_kept_values(c, [b]))))


def _kept_values(c, rates):
    """:func:`_body_values` of one body at ``rates``, shape (nodes, 4 len(rates)): each
    rate's kept in :data:`KERNEL_VALUES`, those not kept formed in one pass."""
    keys = [(float(c), complex(b)) for b in rates]
    todo = list(dict.fromkeys(k[1] for k in keys if k not in KERNEL_VALUES))
    fresh = {}
    if todo:
        values = _body_values(c, todo)
        for j, b in enumerate(todo):
            fresh[b], = _frozen([np.array(values[:, 4 * j:4 * j + 4])])
            KERNEL_VALUES.get((float(c), b), lambda part=fresh[b]: part)

    def kept(key):
        # One kept before may have been dropped by those just kept: formed again.
        return fresh[key[1]] if key[1] in fresh else KERNEL_VALUES.get(
            key, lambda: _frozen([_body_values(key[0], [key[1]])])[0])
    return np.concatenate([kept(k) for k in keys], axis=1)


def _frozen(arrays):
    """``arrays`` as a tuple of read-only arrays (kept in a cache: shared, never
    written)."""
    out = tuple(arrays)
    for m in out:
        m.setflags(write=False)
    return out


@small_cache(8)
def _steady_slope_and_gradient(c, size):
    """A moving body's steady slope ``S_0`` and regular gradient ``G_0 - 1/u`` at the
    ``size`` nodes of :func:`~thermocontact.numerics.tabulated_moments.kernel_nodes`
    (the table's or the coarse ones), formed once per scale: every rate's differences
    take them (:func:`_body_values`)."""
    u = kernel_nodes(coarse=size != kernel_nodes().size)
    return _frozen([moving_slope(u, c), cylinder_temperature_gradient_regular(u, c)])


def _body_values(c, rates, coarse=None):
    """``W``, ``T``, ``S_b - S_0``, ``G_b - G_0`` of one body (section "Transient
    kernels") at :func:`~thermocontact.numerics.tabulated_moments.kernel_nodes` at each
    of ``rates`` (one rate or several), shape (nodes, 4 len(rates)), the rates' four
    columns in turn (``W`` and ``S`` of all the rates in one pass); for ``c = 0`` less
    the constants
    ``2/(pi sqrt b)`` and ``l(b)``.  The stationary half-plane's (``c = 0``) at the
    coarse nodes unless ``coarse`` is False: its kernels, layers of ``sqrt(b)`` alone,
    need only the panels of ratio 2 (derivation S9)."""
    u = kernel_nodes(coarse=c == 0.0 if coarse is None else coarse)
    rates = [complex(b) for b in np.atleast_1d(rates)]
    W, S = transient_displacement_and_slope(u, c, rates)
    out = np.empty((u.size, 4 * len(rates)), dtype=complex)
    if c != 0.0:
        S0, G0 = _steady_slope_and_gradient(c, u.size)
    for j, b in enumerate(rates):
        T, dG = transient_temperature_and_gradient_regular(u, c, b)
        if c == 0.0:
            out[:, 4 * j] = W[j] - 2.0 / (np.pi * np.sqrt(b))
            out[:, 4 * j + 1] = T - logarithm_constant(b)
            out[:, 4 * j + 2] = S[j] - 0.5 * np.sign(u)
            out[:, 4 * j + 3] = dG
        else:
            out[:, 4 * j] = W[j]
            out[:, 4 * j + 1] = T
            out[:, 4 * j + 2] = S[j] - S0
            out[:, 4 * j + 3] = dG - G0
    return out
