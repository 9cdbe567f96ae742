"""The contact inequalities of a contact set of several zones (derivation section 14).

In every zone the pressure is compressive, and no edge opens a tensile layer wider
than :data:`~thermocontact.analysis.validity.EDGE_LAYER_TOLERANCE` of that zone's
half-width (section 8); outside every zone the gap is open.  The gap in a region
between zones, or beyond the outermost edges, is the integral of the slope
mismatch from the region's edge, every zone's part in closed form
(:func:`~thermocontact.discretisation.operator.outside_operators`).  The discrete
solution's slope mismatch at each edge is a discretisation residual: it is taken
out by the cubic that vanishes at both ends of a region between zones and has
those slopes there (a straight line beyond the outermost edges), so that the gap
near an edge is decided by its ``t^{3/2}`` term, as for the single patch (D20-D21).
"""

from __future__ import annotations

from dataclasses import dataclass, replace

import numpy as np

from ..discretisation.operator import contact_operators, outside_operators
from ..io.results import Result
from ..problem.parameters import Parameters
from .validity import EDGE_LAYER_TOLERANCE, edge_terms, least_of, pressure_samples

__all__ = ["ZoneValidity", "assess_zones", "zone_gap"]

#: Distances from an edge, in that zone's half-widths, where the gap is sampled.
_NEAR = np.geomspace(1e-8, 1e3, 160)


@dataclass(frozen=True, eq=False, repr=False)
class ZoneValidity(Result):
    """Margins of the contact inequalities of a contact set.

    Positions ``X`` in units of the Hertz half-width ``l``; pressures in ``P/l``,
    gaps in ``l^2/R``.

    Attributes
    ----------
    valid : bool
        Every zone's pressure margin, every gap margin and every edge margin >= 0.
    pressure_margin, pressure_margin_at : float
        Least ``p / w(s)`` over every zone (``w = sqrt(1 - s^2)`` in the zone's own
        ``s``) and where.
    gap_margin, gap_margin_at : float
        Least ``g / t^{1 + x}`` outside every zone, ``t`` the distance to the nearer
        edge (in ``l``; ``t_a t_b/(t_a + t_b)`` between two zones) and ``x`` that
        edge's exponent, and where.
    min_pressure, min_gap : float
        Least pressure in the zones and least gap outside (0 at edges).
    edge_margins : tuple of float
        Each zone's ``(trailing, leading)`` edge margins (section 8), flattened.
    edge_log_coefficients : tuple of float
        Each zone's ``(k-, k+)`` of (D22), flattened.
    edge_slope_residuals : tuple of float
        The slope mismatch ``G`` of the discrete solution at every edge, in order.
    strictly_valid : bool
        ``valid`` with no tensile edge layer of any width.
    """

    valid: bool
    pressure_margin: float
    pressure_margin_at: float
    gap_margin: float
    gap_margin_at: float
    min_pressure: float
    min_gap: float
    edge_margins: tuple
    edge_log_coefficients: tuple
    edge_slope_residuals: tuple
    strictly_valid: bool

    def margins(self) -> dict[str, float]:
        return {"pressure": self.pressure_margin, "gap": self.gap_margin,
                "edge": min(self.edge_margins)}

    @property
    def failures(self) -> tuple[str, ...]:
        out = []
        if self.pressure_margin < 0.0:
            out.append(f"pressure margin {self.pressure_margin:.3g} at X = "
                       f"{self.pressure_margin_at:.5g}")
        if self.gap_margin < 0.0:
            out.append(f"gap margin {self.gap_margin:.3g} at X = {self.gap_margin_at:.5g}")
        for k, m in enumerate(self.edge_margins):
            if m < 0.0:
                out.append(f"tensile layer wider than {EDGE_LAYER_TOLERANCE:g} half-widths "
                           f"inside the {'leading' if k % 2 else 'trailing'} edge of zone "
                           f"{k // 2 + 1}")
        return tuple(out)

    @property
    def reason(self) -> str:
        return "valid" if self.valid else "invalid: " + "; ".join(self.failures)

    def _summary(self) -> str:
        return (f"valid={self.valid}, pressure_margin={self.pressure_margin:.3g}, "
                f"gap_margin={self.gap_margin:.3g}, edge_margin={min(self.edge_margins):.3g}")

    def _record(self) -> dict:
        return {"valid": self.valid, "reason": self.reason,
                "strictly_valid": self.strictly_valid,
                "pressure_margin": self.pressure_margin,
                "pressure_margin_at": self.pressure_margin_at,
                "gap_margin": self.gap_margin, "gap_margin_at": self.gap_margin_at,
                "min_pressure": self.min_pressure, "min_gap": self.min_gap,
                "edge_margins": list(self.edge_margins),
                "edge_log_coefficients": list(self.edge_log_coefficients),
                "edge_slope_residuals": list(self.edge_slope_residuals)}


def _zone_par(par, half):
    return replace(par, pe=par.pe * half, fhpe=par.fhpe * half)


def edge_residuals(par: Parameters, rep, edges, phi, psi, profile):
    """The slope mismatch ``G`` (left side minus right side of D14, units of ``l``) at
    every edge ``a_1, b_1, a_2, ...``."""
    centre, half = edges.mean(axis=1), 0.5 * (edges[:, 1] - edges[:, 0])
    X = edges.ravel()
    G = -(2.0 / np.pi) * profile.deriv()(X)
    for j in range(len(edges)):
        s = (X - centre[j]) / half[j]
        s[2 * j:2 * j + 2] = (-1.0, 1.0)  # the zone's own edges, exactly
        C, Tp, Tq = contact_operators(_zone_par(par, half[j]), rep, s, own=False)
        G += C @ phi[j] - par.fhpe * half[j] * (Tp @ phi[j] + Tq @ psi[j])
    return G


def zone_gap(par: Parameters, rep, edges, phi, psi, profile, X, X0, residuals=None):
    """The gap at ``X`` (units ``l^2/R``) in the region outside the zones that holds
    ``X0``, an edge where it vanishes, before the residual's correction.

    ``g(X) = g0(X) - g0(X0) - (pi/2) sum_j Delta_j [I_j(X) - I_j(X0)]`` with ``I_j`` zone
    ``j``'s contact-equation left side integrated from its edge on that side
    (D31a; section 14).
    """
    X = np.atleast_1d(np.asarray(X, dtype=float))
    half = 0.5 * (edges[:, 1] - edges[:, 0])
    J = np.zeros(X.shape)
    for j in range(len(edges)):
        a, b = edges[j]
        if X0 >= b:
            side, t, t0 = 1.0, (X - b) / half[j], (X0 - b) / half[j]
        else:
            side, t, t0 = -1.0, (a - X) / half[j], (a - X0) / half[j]
        C, Tp, Tq, _, _ = outside_operators(_zone_par(par, half[j]), rep, side,
                                            np.concatenate([t, [t0]]))
        v = C @ phi[j] - par.fhpe * half[j] * (Tp @ phi[j] + Tq @ psi[j])
        J += half[j] * (v[:-1] - v[-1])
    return profile(X) - profile(X0) - 0.5 * np.pi * J


def assess_zones(par: Parameters, rep, edges, phi, psi, profile, *, polish=True
                 ) -> ZoneValidity:
    """Evaluate every contact inequality of a contact set (derivation section 14).

    The pressure of each zone as :func:`~thermocontact.analysis.validity.assess` does
    (:func:`~thermocontact.analysis.validity.pressure_samples` samples, the least
    polished); the gap on 160 distances per edge from ``1e-8`` of the zone's half-width
    (``1e-6`` where an edge term exists) to the middle of a region between zones, or
    ``1e3`` half-widths beyond the outermost edges, its least margin polished in
    ``ln t``.
    """
    m = len(edges)
    centre, half = edges.mean(axis=1), 0.5 * (edges[:, 1] - edges[:, 0])
    G = edge_residuals(par, rep, edges, phi, psi, profile)
    k_all, edge_m, bands, layers, exps = [], [], [], [], []
    best_p = (np.inf, 0.0)
    min_p = np.inf
    for j in range(m):
        k_log, exponents, em, _, layer = edge_terms(_zone_par(par, half[j]), rep, phi[j],
                                                     psi[j])
        k_all += list(k_log)
        edge_m += list(em)
        layers.append(np.any(layer))
        band = k_log != 0.0
        bands += list(band)
        exps += list(exponents)
        sp, f = rep.phi_samples(phi[j], pressure_samples(rep.n))
        min_p = min(min_p, float(np.min(rep.pressure_weight(sp) * f)))
        keep = np.ones(sp.size, dtype=bool)
        if band[0]:
            keep &= sp >= -1.0 + EDGE_LAYER_TOLERANCE
        if band[1]:
            keep &= sp <= 1.0 - EDGE_LAYER_TOLERANCE
        at, val = least_of(lambda x, j=j: rep.phi_at(phi[j], x), sp[keep], f[keep],
                         int(np.argmin(f[keep])), polish)
        if val < best_p[0]:
            best_p = (val, float(centre[j] + half[j] * at))

    # Regions outside: left of zone 1, between zones, right of the last.  Each edge
    # adjacent to a region is sampled outward from it (to the middle between zones).
    X_edges = edges.ravel()
    sides = []  # (edge index, direction, anchor X0, region's other end or None)
    sides.append((0, -1.0, X_edges[0], None))
    for k in range(m - 1):
        lo, hi = X_edges[2 * k + 1], X_edges[2 * k + 2]
        sides.append((2 * k + 1, 1.0, lo, hi))
        sides.append((2 * k + 2, -1.0, lo, hi))
    sides.append((2 * m - 1, 1.0, X_edges[-1], None))

    def correction(X, lo, hi):
        # The residual slopes' spurious part: -(pi/2) G (X - e) beyond the outermost
        # edges, the cubic with those end slopes and zero end values between zones.
        if hi is None:
            e = lo
            i = int(np.flatnonzero(X_edges == e)[0])
            return -0.5 * np.pi * G[i] * (X - e)
        i = int(np.flatnonzero(X_edges == lo)[0])
        w = hi - lo
        tau = (X - lo) / w
        m0, m1 = -0.5 * np.pi * G[i], -0.5 * np.pi * G[i + 1]
        return w * (tau * (1.0 - tau) ** 2 * m0 - tau * tau * (1.0 - tau) * m1)

    def gap_at(X, anchor, hi):
        return zone_gap(par, rep, edges, phi, psi, profile, X, anchor) - correction(
            X, anchor, hi)

    best_g = (np.inf, 0.0)
    min_g = 0.0
    for idx, direction, anchor, hi in sides:
        zone = idx // 2
        h = half[zone]
        start = EDGE_LAYER_TOLERANCE if bands[idx] else _NEAR[0]
        reach = 1e3 if hi is None else 0.5 * (hi - anchor) / h
        t = h * np.geomspace(start, reach, _NEAR.size)
        e = X_edges[idx]
        X = e + direction * t
        power = 1.0 + exps[idx]
        other = None if hi is None else (hi - anchor)

        def margin_of(y, e=e, direction=direction, power=power, other=other, anchor=anchor,
                      hi=hi):
            tt = np.exp(np.atleast_1d(y))
            XX = e + direction * tt
            eff = tt if other is None else tt * (other - tt) / other
            return gap_at(XX, anchor, hi) / eff**power

        g = gap_at(X, anchor, hi)
        min_g = min(min_g, float(np.min(g)))
        y = np.log(t)
        ms = margin_of(y)
        i = int(np.argmin(ms))
        y_min, val = least_of(margin_of, y, ms, i, polish)
        if val < best_g[0]:
            best_g = (float(np.squeeze(val)), float(e + direction * np.exp(y_min)))

    edge_m = np.array(edge_m)
    sound = best_p[0] >= 0.0 and best_g[0] >= 0.0
    valid = sound and bool(np.all(edge_m >= 0.0))
    return ZoneValidity(
        valid=bool(valid), pressure_margin=float(best_p[0]), pressure_margin_at=best_p[1],
        gap_margin=best_g[0], gap_margin_at=best_g[1], min_pressure=min_p, min_gap=min_g,
        edge_margins=tuple(float(x) for x in edge_m),
        edge_log_coefficients=tuple(float(x) for x in k_all),
        edge_slope_residuals=tuple(float(x) for x in G),
        strictly_valid=bool(sound and not any(layers)))
