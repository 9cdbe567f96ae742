"""Contact sets of several zones, each edge an unknown (derivation section 14).

The contact set is a union of intervals ``a_j < X < b_j`` in units of the Hertz
half-width ``l`` of the actual load (``l^2 = 2 P R A / pi``).  On each zone the
contact equation (D14; D31 in units of l) and the heat equation (D18) hold with every
zone's pressure and heat flux acting on it; outside, no heat crosses and the gap is open.  The
load and the heat partition ``lam`` close the problem, and between neighbouring
zones the gap and the temperature difference ``T1 - T2`` return to the values they
have on the zone before (both bodies touch, and perfect thermal contact holds, on
every zone with one rigid approach and one temperature difference).

For given edges the problem is linear.  Each zone's pressure, bounded at both of
its edges, satisfies its ``n + 1`` contact rows only if two numbers vanish, the
defects ``mu_j``, ``nu_j`` of a term ``(2/pi)(mu_j + nu_j s)`` added to its right
side; Newton's method moves the edges until every defect vanishes.  With one zone
this is the single-patch problem with the half-width fixed by the load
(``P_H/P = Delta^2``, ``Pe = Pe_l Delta``, ``fHPe = fHPe_l Delta``,
``sigma/Delta = centre/Delta``), solved by the same blocks.
"""

from __future__ import annotations

from dataclasses import dataclass, field, replace

import numpy as np
from numpy.polynomial import Polynomial

from .._version import __version__
from ..analysis.zone_validity import ZoneValidity, assess_zones
from ..discretisation.methods import DEFAULT_METHOD, METHODS
from ..discretisation.operator import (contact_operators, heat_operators, outside_operators,
                                       temperature_operators)
from ..discretisation.representations import range_projections
from ..discretisation.system import equation_points
from ..io.results import Result
from ..numerics.extrema import polish_minimum
from ..problem.parameters import Parameters, SolveError
from ..problem.validation import InputError, check_range
from .single_patch import solve_equilibrated

__all__ = ["CYLINDER", "ZoneModel", "ZoneSolution", "zone_system"]

#: The cylinder's initial gap, ``X^2/2`` in units of ``l^2/R``.
CYLINDER = Polynomial([0.0, 0.0, 0.5])
#: Newton's stopping test on the largest defect.
DEFECT_TOL = 1e-11


#: Newton steps of the interface conductance's dependence on the pressure.
MAX_PICARD = 50


#: The Biot numbers ``h l/K2`` of an interface conductance that are solved: from
#: nearly insulating to perfect contact to rounding (section 15).
BIOT_RANGE = (1e-12, 1e15)


@dataclass(frozen=True)
class Conductance:
    """An interface conductance ``h = h0 (p / p_ref)^m`` (derivation section 15).

    Attributes
    ----------
    biot0 : float
        ``h0 l / K2 > 0``: the Biot number of the conductance at the reference
        pressure, ``p_ref = P/(2 l)`` (the mean Hertz pressure of the load).
    exponent : float
        ``m >= 0`` (0: a constant conductance; about 0.95 for plastically deformed
        asperities, Cooper, Mikic and Yovanovich 1969).
    """

    biot0: float
    exponent: float = 0.0

    def __post_init__(self):
        object.__setattr__(self, "biot0", check_range("conductance h0", self.biot0,
                                                      *BIOT_RANGE))
        object.__setattr__(self, "exponent", check_range("conductance m", self.exponent, 0.0, 10.0))

    def biot(self, pressure):
        """``Bi = h l/K2`` at pressures ``p l/P`` (clipped at 1e-300 of the reference)."""
        if self.exponent == 0.0:
            return np.full(np.shape(pressure), self.biot0)
        return self.biot0 * np.maximum(2.0 * np.asarray(pressure), 1e-300) ** self.exponent

    def dbiot(self, pressure):
        """``dBi/dp`` (0 where the pressure is clipped)."""
        p2 = 2.0 * np.asarray(pressure)
        live = p2 > 1e-300
        out = np.zeros(np.shape(p2))
        out[live] = 2.0 * self.exponent * self.biot0 * p2[live] ** (self.exponent - 1.0)
        return out


def _edges(edges) -> np.ndarray:
    e = np.asarray(edges, dtype=float)
    if e.ndim == 1:
        e = e.reshape(-1, 2)
    if e.ndim != 2 or e.shape[1] != 2 or e.shape[0] < 1:
        raise InputError("edges must be pairs (a, b) of each zone, e.g. [[-1, 1]]")
    flat = e.ravel()
    if not np.all(np.isfinite(flat)) or np.any(np.diff(flat) <= 0.0):
        raise InputError(f"edges must be finite and increasing, a1 < b1 < a2 < ..., got "
                         f"{flat.tolist()}")
    return e


def zone_parameters(par: Parameters, half: float) -> Parameters:
    """The single-patch parameters of a zone of half-width ``half`` (units of ``l``)."""
    return replace(par, pe=par.pe * half, fhpe=par.fhpe * half)


@dataclass(frozen=True)
class ZoneSystem:
    """The linear system of one contact set: ``(A0 + F A1) x = b``.

    The unknowns ``x`` are each zone's ``phi`` (``n`` each), then each zone's
    ``psi``, then each zone's defects ``(mu, nu)``, then (with an interface
    conductance) the temperature difference's constant.  With a conductance each
    zone's temperature rows (D33) depend on the Biot numbers at its points
    (``points``): they are formed by :meth:`matrix` from ``local``.
    """

    A0: np.ndarray
    A1: np.ndarray
    b: np.ndarray
    zones: int
    n: int
    local: tuple = ()
    points: tuple = ()

    def matrix(self, F, biot=None, scale=None):
        A = self.A0 + F * self.A1
        if not self.local:
            return A
        # The constant's unknown is carried times the largest Bi/(1 + Bi), so that its
        # column stays of order one however small the conductance.
        scale = self.theta_scale(biot) if scale is None else scale
        for (rows, P, U, Lq), bi in zip(self.local, biot):
            # (D33) times Bi/(1 + Bi): the temperature terms weighted by Bi/(1 + Bi),
            # the interface's (pi/2) q by 1/(1 + Bi); either limit stays finite.
            w = 1.0 / (1.0 + bi)
            point_rows = (bi * w)[:, None] * U + (0.5 * np.pi * w)[:, None] * Lq
            point_rows[:, -1] /= scale
            A[rows] = point_rows if P is None else P @ point_rows
        return A

    @staticmethod
    def theta_scale(biot):
        return max(float(np.max(bi / (1.0 + bi))) for bi in biot)

    def conductance_jacobian(self, x, biot, dbiot, pressure_rows, scale):
        """The derivative of the temperature rows through ``Bi(p)``: ``(D33)`` times
        ``Bi/(1 + Bi)`` changes with ``Bi`` by ``(U x - (pi/2) q)/(1 + Bi)^2`` per
        point, and ``Bi`` with the pressure ``p = pressure_rows @ phi``."""
        J = np.zeros_like(self.A0)
        n = self.n
        for i, ((rows, P, U, Lq), bi, dbi, R) in enumerate(zip(self.local, biot, dbiot,
                                                               pressure_rows)):
            ux = U[:, :-1] @ x[:-1] + U[:, -1] * x[-1] / scale
            dr = (ux - 0.5 * np.pi * (Lq @ x)) / (1.0 + bi) ** 2 * dbi
            block = dr[:, None] * R
            J[rows, i * n:(i + 1) * n] = block if P is None else P @ block
        return J


def temperature_points(rep, scheme: str):
    """Where the temperature equation (D33) is evaluated: ``n`` points and the
    reduction (the first ``n`` projections of the contact equation, or collocation at
    ``tau = pi (k - 1/2)/n``)."""
    n = rep.n
    if scheme == "projection":
        x, p1, _ = range_projections(n)
        s, aux = rep.projection_points(x)
        return s, aux, p1[:n]
    tau = np.pi * (np.arange(n, 0, -1) - 0.5) / n
    s, aux = rep.projection_points(tau)
    return s, aux, None


def zone_system(par: Parameters, edges, lam, rep, scheme: str, profile=CYLINDER,
                conductance=False) -> ZoneSystem:
    """Assemble the equations of a contact set with given edges (derivation section 14).

    Rows: each zone's contact equation (``n + 1``), each zone's heat equation
    (``n - 1``), the load, the heat partition, and for each gap between zones the
    gap's return (D31a) and the temperature difference's return (D31b).  With an
    interface conductance (``conductance=True``, section 15) each zone's heat rows
    are instead ``n`` rows of the temperature equation (D33), whose constant is one
    more unknown, and (D31b) is not needed.

    Parameters
    ----------
    par : Parameters
        ``pe = Pe_l`` and ``fhpe = fHPe_l`` in units of the Hertz half-width.
    edges : ndarray, shape (m, 2)
    lam : float
    rep : Representation
        An edge-graded one (the kernels between zones are integrated from an edge).
    scheme : {"collocation", "projection"}
    profile : numpy.polynomial.Polynomial
        The initial gap in units of ``l^2/R`` against ``X`` (default ``X^2/2``).
    conductance : bool
    """
    m, n = len(edges), rep.n
    centre = edges.mean(axis=1)
    half = 0.5 * (edges[:, 1] - edges[:, 0])
    zpar = [zone_parameters(par, h) for h in half]
    (sc, ac, p1), (sh, ah, p2) = equation_points(rep, scheme)
    if conductance:
        sh, ah, p2 = temperature_points(rep, scheme)
    nh = n if conductance else n - 1

    def reduce(P, M):
        return M if P is None else P @ M

    size = 2 * m * n + 2 * m + int(conductance)
    A0, A1, b = np.zeros((size, size)), np.zeros((size, size)), np.zeros(size)
    phi = [slice(j * n, (j + 1) * n) for j in range(m)]
    psi = [slice((m + j) * n, (m + j + 1) * n) for j in range(m)]
    slope = profile.deriv()
    local, points = [], []
    for i in range(m):
        rc = slice(i * (n + 1), (i + 1) * (n + 1))
        rh = slice(m * (n + 1) + i * nh, m * (n + 1) + (i + 1) * nh)
        xc, xh = centre[i] + half[i] * sc, centre[i] + half[i] * sh
        if conductance:
            U = np.zeros((sh.size, size))
        for j in range(m):
            own = i == j
            s_c = sc if own else (xc - centre[j]) / half[j]
            s_h = sh if own else (xh - centre[j]) / half[j]
            C, Tp, Tq = contact_operators(zpar[j], rep, s_c, ac if own else None, own=own)
            # Zone j's thermal terms in units of l carry its half-width (section 14).
            A0[rc, phi[j]] = reduce(p1, C)
            A1[rc, phi[j]] = -half[j] * reduce(p1, Tp)
            A1[rc, psi[j]] = -half[j] * reduce(p1, Tq)
            if conductance:
                # (D33) in units of l: zone j's integrals carry Delta_j, and its
                # logarithm ln(Delta_j) times the heat it puts into the half-plane.
                Up, Uq = temperature_operators(zpar[j], rep, s_h, ah if own else None)
                lg = np.log(half[j])
                U[:, phi[j]] = half[j] * (Up + 0.5 * (1.0 - par.eta) * lg
                                          * rep.pressure_rule.weights[None, :])
                U[:, psi[j]] = half[j] * (Uq - 0.5 * lg * rep.flux_rule.weights[None, :])
            else:
                Hp, Hq = heat_operators(zpar[j], rep, s_h, ah if own else None)
                A0[rh, phi[j]] = reduce(p2, Hp)
                A0[rh, psi[j]] = reduce(p2, Hq)
        if conductance:
            U[:, size - 1] = -1.0
            # The interface's (pi/2) q = (pi/2)(q' + eta p) at the zone's own points.
            Lq = np.zeros_like(U)
            Lq[:, phi[i]] = par.eta * rep.pressure_rows(sh, ah)
            Lq[:, psi[i]] = rep.flux_rows(sh, ah)
            local.append((rh, p2, U, Lq))
            points.append((sh, ah))
        b[rc] = (2.0 / np.pi) * reduce(p1, slope(xc))
        A0[rc, 2 * m * n + 2 * i] = -(2.0 / np.pi) * reduce(p1, np.ones_like(sc))
        A0[rc, 2 * m * n + 2 * i + 1] = -(2.0 / np.pi) * reduce(p1, sc)

    wp, wq = rep.pressure_rule.weights, rep.flux_rule.weights
    load, part = m * (n + 1) + m * nh, m * (n + 1) + m * nh + 1
    for j in range(m):
        A0[load, phi[j]] = half[j] * wp
        A0[part, phi[j]] = half[j] * par.eta * wp
        A0[part, psi[j]] = half[j] * wq
    b[load], b[part] = 1.0, lam
    for k in range(m - 1):
        lo, hi = edges[k, 1], edges[k + 1, 0]
        rg, rt = part + 1 + k, part + m + k
        for j in range(m):
            C, Tp, Tq, Hp, Hq = region_integral(zpar[j], rep, edges[j], half[j], lo, hi)
            A0[rg, phi[j]] += half[j] * C
            A1[rg, phi[j]] -= half[j] ** 2 * Tp
            A1[rg, psi[j]] -= half[j] ** 2 * Tq
            if not conductance:
                A0[rt, phi[j]] += half[j] * Hp
                A0[rt, psi[j]] += half[j] * Hq
        b[rg] = (2.0 / np.pi) * (profile(hi) - profile(lo))
    return ZoneSystem(A0, A1, b, m, n, tuple(local), tuple(points))


def region_integral(zpar: Parameters, rep, edge_pair, half, lo, hi):
    """Rows of the integrals over ``lo < X < hi`` (outside the zone) of its terms.

    ``integral`` of the zone's contact-equation and heat-equation left sides over
    ``X``, per unit ``ds`` (multiply by ``half`` for ``dX``): the differences of
    :func:`~thermocontact.discretisation.operator.outside_operators` at the two
    ends, measured from the zone's edge on that side.
    """
    a, b = edge_pair
    if lo >= b:
        side, t_lo, t_hi = 1.0, (lo - b) / half, (hi - b) / half
    else:
        side, t_lo, t_hi = -1.0, (a - lo) / half, (a - hi) / half
    ops = outside_operators(zpar, rep, side, np.array([t_lo, t_hi]))
    # From lo to hi: I(t_hi) - I(t_lo) on the right; on the left the integral from
    # the edge outward runs from hi to lo, so the same difference holds with the
    # orientation of I: integral_lo^hi = I(t_hi) - I(t_lo) as well.
    return tuple(M[1] - M[0] for M in ops)


def _solve_linear(system: ZoneSystem, F: float, biot=None, scale=None, A=None, b=None):
    A = system.matrix(F, biot, scale) if A is None else A.copy()
    b = system.b.copy() if b is None else b.copy()
    x, rcond = solve_equilibrated(A, b, "the contact set's linear system")
    if not np.all(np.isfinite(x)):
        raise SolveError("the contact set's linear solve produced non-finite values")
    return x, float(rcond)


@dataclass(frozen=True, eq=False, repr=False)
class ZoneSolution(Result):
    """A contact set of one or more zones, in units of the Hertz half-width ``l``.

    Positions ``X = x/l`` from the undeformed cylinder's lowest point, the leading
    edge at larger ``X``; pressures in units of ``P/l`` (unit integral over the
    contact set), heat fluxes in units of ``f v P/l``.

    Attributes
    ----------
    parameters : Parameters
        ``pe = Pe_l``, ``fhpe = fHPe_l``.
    lam : float
    edges : ndarray, shape (m, 2)
        ``(a_j, b_j)`` of each zone, ascending.
    phi, psi : ndarray, shape (m, n)
        Each zone's unknowns at the representation's nodes (in its own ``s``).
    representation : Representation
    method : str
    defect : float
        The largest defect left by Newton's method (zero for the exact edges).
    iterations : int
    rcond : float
    validity : ZoneValidity or None
    profile : Polynomial
    """

    parameters: Parameters
    lam: float
    edges: np.ndarray
    phi: np.ndarray
    psi: np.ndarray
    representation: object
    method: str
    defect: float
    iterations: int
    rcond: float
    validity: ZoneValidity | None = None
    profile: Polynomial = field(default_factory=lambda: CYLINDER)

    @property
    def n(self) -> int:
        return self.representation.n

    @property
    def zones(self) -> int:
        return len(self.edges)

    @property
    def half_widths(self) -> np.ndarray:
        return 0.5 * (self.edges[:, 1] - self.edges[:, 0])

    @property
    def centres(self) -> np.ndarray:
        return self.edges.mean(axis=1)

    @property
    def loads(self) -> np.ndarray:
        """Each zone's share of the load."""
        return self.half_widths * (self.phi @ self.representation.pressure_rule.weights)

    @property
    def heat_partitions(self) -> np.ndarray:
        """Each zone's share of ``lam``: ``integral (q1 - q2) dX`` over it."""
        rep = self.representation
        return self.half_widths * (self.psi @ rep.flux_rule.weights
                                   + self.parameters.eta * (self.phi @ rep.pressure_rule.weights))

    def pressure_at(self, X):
        """The pressure ``p l/P`` at ``X`` (zero outside the zones)."""
        X = np.asarray(X, dtype=float)
        out = np.zeros(X.shape)
        for (a, b), c, h, ph in zip(self.edges, self.centres, self.half_widths, self.phi):
            inside = (X >= a) & (X <= b)
            if np.any(inside):
                out[inside] = self.representation.pressure_at(ph, (X[inside] - c) / h)
        return out

    def pressure_samples(self, count=401):
        """``X`` and the pressure at ``count`` points of each zone (denser toward edges)."""
        rep = self.representation
        xs, ps = [], []
        for c, h, ph in zip(self.centres, self.half_widths, self.phi):
            s, f = rep.phi_samples(ph, count)
            xs.append(c + h * s)
            ps.append(rep.pressure_weight(s) * f)
        return np.concatenate(xs), np.concatenate(ps)

    @property
    def peak_pressures(self) -> np.ndarray:
        """Each zone's largest pressure: the greatest sample, polished on the series."""
        rep, out = self.representation, []
        for ph in self.phi:
            s, f = rep.phi_samples(ph, 401)
            p = rep.pressure_weight(s) * f
            i = int(np.argmax(p))
            _, least = polish_minimum(lambda x, ph=ph: -rep.pressure_at(ph, x), s, -p, i)
            out.append(-least)
        return np.array(out)

    @property
    def valid(self):
        return None if self.validity is None else self.validity.valid

    def single_patch(self):
        """With one zone: ``(P_H/P, sigma/Delta)`` of the equivalent single patch."""
        if self.zones != 1:
            raise ValueError("single_patch: the contact set has more than one zone")
        h, c = self.half_widths[0], self.centres[0]
        return float(h * h), float(c / h)

    def zone_records(self) -> list[dict]:
        return [{"a": float(a), "b": float(b), "load": float(w), "peak_pressure": float(pk)}
                for (a, b), w, pk in zip(self.edges, self.loads, self.peak_pressures)]

    def _record(self) -> dict:
        p = self.parameters
        return {
            "version": __version__,
            "pe_hertz": p.pe, "fhpe_hertz": p.fhpe, "K2_over_K1": p.K2_over_K1,
            "k2_over_k1": p.k2_over_k1, "delta1_over_delta2": p.delta1_over_delta2,
            "beta_f": p.beta_f, "lam": self.lam, "method": self.method, "n": self.n,
            "valid": self.valid,
            "zones": self.zone_records(),
            "defect": self.defect, "iterations": self.iterations,
            "complementarity": None if self.validity is None else self.validity.to_dict(),
        }

    def _summary(self) -> str:
        z = ", ".join(f"[{a:.4g}, {b:.4g}]" for a, b in self.edges)
        return (f"zones={z}, loads={np.round(self.loads, 4).tolist()}, valid={self.valid}, "
                f"n={self.n}")


class ZoneModel:
    """The contact-set problem with the materials' ratios fixed; solve it at any load.

    Parameters
    ----------
    K2_over_K1 : float
    k2_over_k1 : float, optional
        Defaults to ``K2_over_K1``.
    delta1_over_delta2 : float, optional
    beta_f : float, optional
        The Dundurs term (section 5c); the half-plane is stationary.
    method : str, optional
        ``"graded"`` or ``"graded-collocation"``.
    n : int, optional
        Unknowns per function per zone (default 32).
    profile : Polynomial, optional
        The initial gap against ``X`` in units of ``l^2/R`` (default ``X^2/2``, the
        cylinder); e.g. a profile with two minima makes two zones without heat.
    """

    def __init__(self, K2_over_K1, *, k2_over_k1=None, delta1_over_delta2=1.0, beta_f=0.0,
                 method=DEFAULT_METHOD, n=32, profile=CYLINDER, conductance=None):
        self.base = Parameters(1.0, 0.0, K2_over_K1, k2_over_k1, delta1_over_delta2, 0.0,
                               beta_f)
        self.conductance = None if conductance is None else Conductance(*conductance)
        if method not in METHODS or not METHODS[method].edge_exponents:
            raise InputError(f"method must be 'graded' or 'graded-collocation' for contact "
                             f"sets, got {method!r}")
        self.method = method
        self.n = int(n)
        self.profile = profile if isinstance(profile, Polynomial) else Polynomial(profile)

    def parameters(self, pe, fhpe) -> Parameters:
        return replace(self.base, pe=pe, fhpe=fhpe)

    def representation(self):
        m = METHODS[self.method]
        return m.representation(self.n, self.base.edge_exponent)

    def system(self, edges, pe, fhpe, lam) -> ZoneSystem:
        return zone_system(self.parameters(pe, fhpe), _edges(edges), lam,
                           self.representation(), METHODS[self.method].scheme, self.profile,
                           conductance=self.conductance is not None)

    def defects(self, edges, pe, fhpe, lam):
        """The defects ``(mu_1, nu_1, ...)`` and the linear solution at these edges.

        With a pressure-dependent conductance the linear solve is repeated with the
        Biot numbers of the last pressure until the pressure settles (section 15).
        """
        system = self.system(edges, pe, fhpe, lam)
        m, n = system.zones, system.n
        if self.conductance is None:
            x, rcond = _solve_linear(system, fhpe)
            return x[2 * m * n:], x, rcond
        half = 0.5 * np.diff(_edges(edges), axis=1)[:, 0]
        rep = self.representation()
        # The first pressure: the load spread over the zones as Hertz's shape.
        rows = [rep.pressure_rows(sh, ah) for sh, ah in system.points]
        pressure = [(2.0 / (np.pi * half.sum())) * rep.pressure_weight(sh)
                    for sh, _ in system.points]
        cond = self.conductance
        biot = [cond.biot(p) for p in pressure]
        scale = system.theta_scale(biot)
        x, rcond = _solve_linear(system, fhpe, biot, scale)
        if cond.exponent != 0.0:
            # Newton's method on the whole linear system with Bi following the pressure
            # (plain repetition oscillates once the heat couples strongly).
            def residual(x):
                phi = x[:m * n].reshape(m, n)
                p = [r @ f for r, f in zip(rows, phi)]
                bi = [cond.biot(q) for q in p]
                A = system.matrix(fhpe, bi, scale)
                return A @ x - system.b, A, p, bi
            r, A, p, bi = residual(x)
            norm = np.linalg.norm(r)
            step = np.inf
            for _ in range(MAX_PICARD):
                # Converged when the residual is at rounding level or the step is.
                if (norm <= 1e-11 * max(1.0, np.linalg.norm(system.b))
                        or step <= 1e-13 * np.linalg.norm(x)):
                    break
                J = A + system.conductance_jacobian(x, bi, [cond.dbiot(q) for q in p], rows,
                                                    scale)
                dx, rcond = _solve_linear(system, fhpe, A=J, b=-r)
                alpha = 1.0
                while True:
                    trial = residual(x + alpha * dx)
                    if np.linalg.norm(trial[0]) < norm or alpha < 1e-4:
                        break
                    alpha *= 0.5
                x = x + alpha * dx
                step = alpha * np.linalg.norm(dx)
                r, A, p, bi = trial
                norm = np.linalg.norm(r)
            else:
                raise SolveError(f"the interface conductance's pressure did not settle in "
                                 f"{MAX_PICARD} Newton steps")
        return x[2 * m * n:2 * m * n + 2 * m], x, rcond

    def jacobian(self, edges, pe, fhpe, lam, defects=None):
        """Derivatives of the defects with respect to the edges, by differences."""
        e = _edges(edges).ravel()
        d0 = self.defects(e, pe, fhpe, lam)[0] if defects is None else defects
        half = np.repeat(0.5 * (e[1::2] - e[0::2]), 2)
        J = np.empty((d0.size, e.size))
        lengths = np.diff(e)
        for k in range(e.size):
            # A step well inside the zone and the gap either side of the edge.
            near = lengths[max(k - 1, 0):k + 1].min()
            h = min(1e-7 * max(half[k], 1e-3), 1e-3 * near)
            ek = e.copy()
            ek[k] += h
            J[:, k] = (self.defects(ek, pe, fhpe, lam)[0] - d0) / h
        return J

    def solve(self, edges, pe, fhpe, lam, *, max_iter=40, check_validity=True,
              polish=True) -> ZoneSolution:
        """Newton's method on the edges from ``edges`` to zero defects.

        Raises
        ------
        SolveError
            When Newton's method does not converge (the message says how far it got).
        """
        check_range("pe_hertz", pe, 1e-12, 1e6)
        check_range("fhpe_hertz", fhpe, 0.0, 1e6)
        lam = check_range("lam", lam, -1e6, 1e6)
        e = _edges(edges).ravel().copy()
        J = None
        for it in range(max_iter + 1):
            d, x, rcond = self.defects(e, pe, fhpe, lam)
            err = float(np.max(np.abs(d)))
            if err < DEFECT_TOL:
                break
            if it == max_iter:
                raise SolveError(f"the edges did not converge in {max_iter} Newton steps "
                                 f"(largest defect {err:.2e})")
            J = self.jacobian(e, pe, fhpe, lam, d)
            try:
                step = -np.linalg.solve(J, d)
            except np.linalg.LinAlgError:
                raise SolveError("the edges' Newton matrix is singular: a fold or a "
                                 "degenerate contact set") from None
            # Keep the order of the edges: no zone or gap shrinks by more than half.
            lengths = np.diff(e)
            change = np.diff(step)
            with np.errstate(divide="ignore", invalid="ignore"):
                limit = np.where(change < 0.0, -0.5 * lengths / change, np.inf)
            e = e + min(1.0, float(np.min(limit))) * step
            lengths = np.diff(e)
            if np.min(lengths) < 1e-6 * (e[-1] - e[0]):
                k = int(np.argmin(lengths))
                what = (f"zone {k // 2 + 1} shrinks to nothing" if k % 2 == 0 else
                        f"zones {k // 2 + 1} and {k // 2 + 2} merge")
                raise SolveError(f"Newton's method leaves this contact set: {what} "
                                 f"(largest defect {err:.2e})")
        par = self.parameters(pe, fhpe)
        m, n = len(e) // 2, self.n
        edges2 = e.reshape(m, 2)
        phi = x[:m * n].reshape(m, n)
        psi = x[m * n:2 * m * n].reshape(m, n)
        rep = self.representation()
        validity = (assess_zones(par, rep, edges2, phi, psi, self.profile, polish=polish)
                    if check_validity else None)
        return ZoneSolution(par, float(lam), edges2, phi, psi, rep, self.method, err, it,
                            rcond, validity, self.profile)
