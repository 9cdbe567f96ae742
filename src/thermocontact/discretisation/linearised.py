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
(:mod:`thermocontact.physics.green_functions`).  Every kernel goes through the one
moment engine, as the steady blocks do.  Unknowns, in this order: ``phi~`` (n),
``psi~`` (n), the rigid approach ``D~``, ``sig~ = sigma~/Delta`` and
``del~ = Delta~/Delta``.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..physics.green_functions import (cylinder_displacement, cylinder_slope,
                                       cylinder_temperature,
                                       cylinder_temperature_gradient_regular)
from ..physics.transient_green_functions import (transient_displacement_and_slope,
                                                 transient_temperature,
                                                 transient_temperature_gradient_regular)
from ..problem.parameters import Parameters
from ..problem.validation import InputError
from .representations import EdgeGraded

__all__ = ["LinearisedContact", "logarithm_constant", "projections"]


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
        The steady solution's (stationary half-plane, no Dundurs term).
    representation : Representation
        An edge-graded one (the steady solution's).
    phi, psi : ndarray, shape (n,)
        The steady solution's factors.
    load_ratio, sigma_over_delta : float
        Its ``L = P_H/P`` and offset.
    """

    parameters: Parameters
    representation: object
    phi: np.ndarray
    psi: np.ndarray
    load_ratio: float
    sigma_over_delta: float

    def __post_init__(self):
        par = self.parameters
        if par.half_plane_scale:
            raise InputError("stability: speed_ratio must be 0 (the stationary half-plane); "
                             f"got {par.speed_ratio!r}", parameters=("speed_ratio",))
        if par.free_term:
            raise InputError(f"stability: beta_f must be 0, got {par.beta_f!r}",
                             parameters=("beta_f",))
        if not isinstance(self.representation, EdgeGraded):
            raise InputError("stability needs an edge-graded method (graded, "
                             "graded-collocation)", parameters=("method",))

    @property
    def n(self) -> int:
        return self.representation.n

    @property
    def size(self) -> int:
        return 2 * self.n + 3

    def _kernels(self, b):
        """Per body: the unknowns' kernels ``W``, ``T`` and the edges' kernels
        ``S_b - S_0``, ``G_b - G_0`` (None at ``b = 0``), ``u S_0``, ``u G_0 - 1``,
        with the scale of each body; and ``l(b)``."""
        par = self.parameters
        c = par.cylinder_scale
        steady1 = dict(uS0=lambda u: u * cylinder_slope(c * u),
                       uG0=lambda u: u * cylinder_temperature_gradient_regular(u, c))
        # The stationary half-plane: S_0 = sgn(u)/2, G_0 = 1/u exactly.
        steady2 = dict(uS0=lambda u: 0.5 * np.abs(u), uG0=None)
        if b == 0:
            # Its displacement's and temperature's diverging constants taken out (T6,
            # T11); the temperature's returns as the partition row (S8).
            cyl = dict(W=lambda u: cylinder_displacement(c * u) / c,
                       T=lambda u: cylinder_temperature(c * u), dS=None, dG=None, **steady1)
            half = dict(W=lambda u: -0.5 * np.abs(u), T=lambda u: -np.log(np.abs(u)),
                        dS=None, dG=None, **steady2)
            return (cyl, c), (half, 1.0), 0.0
        b1 = b / par.k2_over_k1
        ell = logarithm_constant(b)
        w0 = 2.0 / (np.pi * np.sqrt(complex(b)))
        ws1, ws2 = _shared(c, b1), _shared(0.0, b)
        cyl = dict(W=_blockwise(lambda u: ws1(u)[0]),
                   T=lambda u: transient_temperature(u, c, b1),
                   dS=_blockwise(lambda u: ws1(u)[1] - cylinder_slope(c * u)),
                   dG=lambda u: (transient_temperature_gradient_regular(u, c, b1)
                                 - cylinder_temperature_gradient_regular(u, c)), **steady1)
        half = dict(W=_blockwise(lambda u: ws2(u)[0] - w0),
                    T=lambda u: transient_temperature(u, 0.0, b) - ell,
                    dS=_blockwise(lambda u: ws2(u)[1] - 0.5 * np.sign(u)),
                    dG=lambda u: transient_temperature_gradient_regular(u, 0.0, b), **steady2)
        return ((cyl, max(1.0, c, abs(np.sqrt(complex(b1))))),
                (half, max(1.0, abs(np.sqrt(complex(b))))), ell)

    def matrix(self, b, *, split=False):
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

        Returns
        -------
        ndarray, or tuple with ``split``
        """
        par, rep, n = self.parameters, self.representation, self.n
        x, pd, pt = projections(n)
        s, aux = rep.projection_points(x)
        (k1, sc1), (k2, sc2), ell = self._kernels(b)
        eta, rho, d, F = par.eta, par.K2_over_K1, par.delta1_over_delta2, par.fhpe
        phi0, psi0 = self.phi, self.psi
        L0, sig0 = self.load_ratio, self.sigma_over_delta
        r = rep.pressure_rule.nodes
        wp, wq = rep.pressure_rule.weights, rep.flux_rule.weights
        # Each body's heat from (phi, psi): q1 = ((1 + eta) p + q')/2,
        # q2 = ((1 - eta) p - q')/2.
        share = ((0.5 * (1.0 + eta), 0.5), (0.5 * (1.0 - eta), -0.5))

        def integrate(kernel, scale, logarithmic=False):
            return rep.integrate(kernel, s, scale=scale, logarithmic=logarithmic, aux=aux)

        def on_heat(mom, i):
            (ap, aq), (Mb, Ms) = share[i], mom
            return np.hstack([ap * Mb, aq * Ms])

        def steady_heat(mom, i, weight=1.0):
            # int K q0_i dr for the steady heat times ``weight`` at the nodes.
            (ap, aq), (Mb, Ms) = share[i], mom
            return ap * (Mb @ (weight * phi0)) + aq * (Ms @ (weight * psi0))

        def edges(diff, u_steady, i, scale, logarithmic):
            # The columns (sig~, del~) of int (K_b - K_0)(u)(sig~ + del~ r) q0_i
            # - del~ int u K_0(u) q0_i (S6).
            out = np.zeros((s.size, 2), dtype=complex if b != 0 else float)
            if diff is not None:
                mom = integrate(diff, scale, logarithmic)
                out[:, 0] = steady_heat(mom, i)
                out[:, 1] = steady_heat(mom, i, r)
            if u_steady is not None:
                out[:, 1] -= steady_heat(integrate(u_steady, scale, logarithmic), i)
            return out

        size = self.size
        dtype = complex if b != 0 else float
        disp = np.zeros((s.size, size), dtype=dtype)
        temp = np.zeros((s.size, size), dtype=dtype)
        cols = slice(0, 2 * n)
        # Elastic (Flamant) on phi~; the edges' elastic and profile terms (S5).
        lb, _ = integrate(lambda u: np.log(np.abs(u)), 1.0, True)
        disp[:, :n] += lb / np.pi
        disp[:, 2 * n] = 1.0
        disp[:, 2 * n + 1] = -(2.0 * L0 / np.pi) * (sig0 + s)
        disp[:, 2 * n + 2] = 1.0 / np.pi - (2.0 * L0 / np.pi) * s * (sig0 + s)
        # Each body's thermal displacement (factor 2 F d_i) and its edges' terms.
        for i, (k, scale, weight) in enumerate(((k1, sc1, d), (k2, sc2, 1.0))):
            if weight == 0.0:
                continue
            f = 2.0 * F * weight
            disp[:, cols] += f * on_heat(integrate(k["W"], scale), i)
            disp[:, 2 * n + 1:] += f * edges(k["dS"], k["uS0"], i, scale, False)
        # Temperatures: rho times body 1's minus body 2's (S4), u G_0 = 1 + u (G_0 - 1/u).
        for i, (k, scale, sign) in enumerate(((k1, sc1, rho), (k2, sc2, -1.0))):
            temp[:, cols] += sign * on_heat(integrate(k["T"], scale, True), i)
            e = edges(k["dG"], k["uG0"], i, scale, True)
            e[:, 1] -= share[i][0] * (wp @ phi0) + share[i][1] * (wq @ psi0)
            temp[:, 2 * n + 1:] += sign * e
        rows = np.zeros((size, size), dtype=dtype)
        rows[:n + 2] = pd @ disp
        rows[n + 2, :n] = rep.pressure_rule.weights
        rows[n + 3:] = pt @ temp
        # -l(b) int q2~ dr, a constant: on the temperature's first projection only.
        row = -np.sum(pt[0]) * np.concatenate([share[1][0] * wp, share[1][1] * wq, np.zeros(3)])
        if split:
            return rows, ell, row
        if b == 0:
            rows[n + 3] = row
        else:
            rows[n + 3] += ell * row
        return rows


def _blockwise(kernel):
    """``kernel``, marked as one whose values depend on the array it is given (the
    transient distortion's quadrature in ``phi`` takes its depth and panels per block
    of points): the moments evaluate it on each part of their nodes apart
    (:func:`~thermocontact.numerics.moment_engine.moments`), as they always have."""
    kernel.elementwise = False
    return kernel


def _shared(c, b):
    """``u -> (W(u), S(u))`` of one body, each array of ``u`` computed once: the moment
    engine asks for ``W`` and then ``S`` at the same arguments (same points, scale)."""
    memo = {}

    def both(u):
        key = (u.shape, hash(u.tobytes()))
        if key not in memo:
            memo[key] = transient_displacement_and_slope(u, c, b)
        return memo[key]
    return both
