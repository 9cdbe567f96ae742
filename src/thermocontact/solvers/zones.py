"""Contact sets of several zones, each edge an unknown (derivation section 14).

The contact set is a union of intervals ``a_j < X < b_j`` in units of the Hertz
half-width ``l`` of the actual load (``l^2 = 2 P R A / pi``).  On each zone the
contact equation (D14; D31 in units of l) and the heat equation (D18) hold with every
zone's pressure and heat flux acting on it; outside, no heat crosses and the gap is open.  The
load and the heat partition ``lam`` (or the bodies' far temperatures, section 17) close
the problem, and between neighbouring zones the gap and the temperature difference
``T1 - T2`` return to the values they have on the zone before (both bodies touch, and
perfect thermal contact holds, on every zone with one rigid approach and one
temperature difference).

For given edges the problem is linear.  Each zone's pressure, bounded at both of
its edges, satisfies its ``n + 1`` contact rows only if two numbers vanish, the
defects ``mu_j``, ``nu_j`` of a term ``(2/pi)(mu_j + nu_j s)`` added to its right
side; Newton's method moves the edges until every defect vanishes.  With one zone
this is the single-patch problem with the half-width fixed by the load
(``P_H/P = Delta^2``, ``Pe = Pe_l Delta``, ``fHPe = fHPe_l Delta``,
``sigma/Delta = centre/Delta``), solved by the same blocks; one zone may instead be
closed by its offset, the half-width then found by Newton's method.  Every closure of
the single patch closes a contact set: ``lam`` in the single patch's range (a formal
continuation beyond [-1, 1] included), the offset (one zone), the far temperatures.
The system is assembled by
:func:`~thermocontact.discretisation.system.contact_set_system`, the single patch's
too (derivation section 16), with the moving half-plane, the Dundurs term and an
interface conductance.
"""

from __future__ import annotations

from dataclasses import dataclass, field, replace

import numpy as np
from numpy.polynomial import Polynomial

from .._version import __version__
from ..analysis.zone_validity import ZoneValidity, assess_zones
from ..discretisation.methods import DEFAULT_METHOD, METHODS
from ..discretisation.system import (ContactSetSystem,
                                     check_temperatures, contact_set_system, zone_parameters)
from ..io.results import Result
from ..numerics.extrema import polish_minimum
from ..problem.closure import Temperatures, check_closure_range
from ..problem.conductance import Conductance
from ..problem.errors import NotConvergedError
from ..problem.parameters import Parameters, SolveError
from ..problem.validation import (InputError, check_exactly_one, check_offset_coupling,
                                  check_range)
from .contact_system import solve_contact_system
from .refinement import N_RANGE, refine

__all__ = ["CYLINDER", "ZoneModel", "ZoneSolution",
           "zone_parameters", "zone_system"]

#: The cylinder's initial gap, ``X^2/2`` in units of ``l^2/R``.
CYLINDER = Polynomial([0.0, 0.0, 0.5])
#: Newton's stopping test on the largest defect.
DEFECT_TOL = 1e-11


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


#: The system of a contact set (:class:`~thermocontact.discretisation.system.
#: ContactSetSystem`), under the name it had.
ZoneSystem = ContactSetSystem


def zone_system(par: Parameters, edges, lam, rep, scheme: str, profile=CYLINDER,
                conductance=False, *, sigma_over_delta=None,
                temperatures=None) -> ContactSetSystem:
    """The contact set's equations in units of the Hertz half-width (section 14):
    :func:`~thermocontact.discretisation.system.contact_set_system` with the profile
    ``profile`` (default the cylinder's ``X^2/2``) and ``lam``, the far
    ``temperatures`` (sink distance ``L/l``) or, for one zone, ``sigma_over_delta``."""
    return contact_set_system(par, _edges(edges), rep, scheme, lam=lam,
                              sigma_over_delta=sigma_over_delta, temperatures=temperatures,
                              profile=profile, conductance=conductance)


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
        The heat partition: given, or the output of the offset or the temperatures.
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
    error_estimate : float or None
        Measured by :meth:`ZoneModel.error_estimate` (``solve(..., estimate=True)``);
        None when not measured.
    temperatures : Temperatures or None
        The far temperatures that closed the set (``Theta`` and the sink distance
        ``L/l``, section 17); None when ``lam`` or the offset did.
    conductance : Conductance or None
        The interface conductance it was solved with (section 15); None for perfect
        thermal contact.
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
    error_estimate: float | None = None
    temperatures: Temperatures | None = None
    conductance: Conductance | None = None

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
            **({} if self.temperatures is None else
               {"theta": self.temperatures.theta,
                "sink_distance": self.temperatures.sink_distance}),
            **({"speed_ratio": p.speed_ratio} if p.speed_ratio else {}),
            **({"error_estimate": self.error_estimate}
               if self.error_estimate is not None else {}),
            "valid": self.valid,
            "zones": self.zone_records(),
            "defect": self.defect, "iterations": self.iterations,
            "complementarity": None if self.validity is None else self.validity.to_dict(),
        }

    def _summary(self) -> str:
        z = ", ".join(f"[{a:.4g}, {b:.4g}]" for a, b in self.edges)
        return (f"zones={z}, loads={np.round(self.loads, 4).tolist()}, valid={self.valid}, "
                f"n={self.n}")


@dataclass(frozen=True)
class ZoneMeasure:
    """A zone's single-patch equivalents, the quantities whose change with ``n``
    estimates a contact set's error: ``load_ratio = Delta_j^2`` and
    ``sigma_over_delta = centre_j/Delta_j`` (for one zone the single patch's
    ``P_H/P`` and ``sigma/Delta``, section 14)."""

    load_ratio: float
    sigma_over_delta: float


def zone_measures(sol: ZoneSolution) -> tuple:
    """Each zone's :class:`ZoneMeasure`, the cases refined together."""
    return tuple(ZoneMeasure(float(h * h), float(c / h))
                 for h, c in zip(sol.half_widths, sol.centres))


#: The Peclet number and the coupling of a contact set, in units of the Hertz
#: half-width: checked at each solve and, for a followed path, at its target.
PE_HERTZ_RANGE = (1e-12, 1e6)
FHPE_HERTZ_RANGE = (0.0, 1e6)


class ZoneModel:
    """The contact-set problem with the materials' ratios fixed; solve it at any load.

    Parameters
    ----------
    K2_over_K1 : float
    k2_over_k1 : float, optional
        Defaults to ``K2_over_K1``.
    delta1_over_delta2 : float, optional
    beta_f : float, optional
        The Dundurs term (section 5c).
    method : str, optional
        ``"graded"`` or ``"graded-collocation"``.
    n : int, optional
        Unknowns per function per zone (default 32).
    profile : Polynomial, optional
        The initial gap against ``X`` in units of ``l^2/R`` (default ``X^2/2``, the
        cylinder); e.g. a profile with two minima makes two zones without heat.
    conductance : tuple, optional
        ``(Bi0, m)`` of an interface conductance, ``Bi0 = h0 l/K2`` (section 15).
    speed_ratio : float, optional
        ``R = v2/v1``: the half-plane moving through the contact (default 0, the
        stationary half-plane; sections 5b and 16).
    """

    def __init__(self, K2_over_K1, *, k2_over_k1=None, delta1_over_delta2=1.0, beta_f=0.0,
                 method=DEFAULT_METHOD, n=32, profile=CYLINDER, conductance=None,
                 speed_ratio=0.0):
        self.base = Parameters(1.0, 0.0, K2_over_K1, k2_over_k1, delta1_over_delta2,
                               speed_ratio, beta_f)
        self.conductance = Conductance.of(conductance)
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

    def system(self, edges, pe, fhpe, lam=None, *, sigma_over_delta=None,
               temperatures=None) -> ContactSetSystem:
        return zone_system(self.parameters(pe, fhpe), edges, lam, self.representation(),
                           METHODS[self.method].scheme, self.profile,
                           conductance=self.conductance is not None,
                           sigma_over_delta=sigma_over_delta, temperatures=temperatures)

    def defects(self, edges, pe, fhpe, lam=None, *, sigma_over_delta=None,
                temperatures=None):
        """The defects and the linear solution at these edges: ``(mu_1, nu_1, ...)``
        with ``lam`` or ``temperatures`` given, ``(nu,)`` with ``sigma_over_delta``
        (section 16).

        With a pressure-dependent conductance the Biot numbers follow the pressure
        (section 15, :func:`~thermocontact.solvers.contact_system.solve_contact_system`).
        """
        system = self.system(edges, pe, fhpe, lam, sigma_over_delta=sigma_over_delta,
                             temperatures=temperatures)
        half = 0.5 * np.diff(_edges(edges), axis=1)[:, 0]
        x, rcond = solve_contact_system(system, fhpe, self.representation(), half,
                                        self.conductance)
        return x[system.closure_slice], x, rcond

    def jacobian(self, edges, pe, fhpe, lam=None, defects=None, *, temperatures=None):
        """Derivatives of the defects with respect to the edges, by differences
        (``lam`` or ``temperatures`` given)."""
        e = _edges(edges).ravel()
        d0 = (self.defects(e, pe, fhpe, lam, temperatures=temperatures)[0]
              if defects is None else defects)
        half = np.repeat(0.5 * (e[1::2] - e[0::2]), 2)
        J = np.empty((d0.size, e.size))
        lengths = np.diff(e)
        for k in range(e.size):
            # A step well inside the zone and the gap either side of the edge.
            near = lengths[max(k - 1, 0):k + 1].min()
            h = min(1e-7 * max(half[k], 1e-3), 1e-3 * near)
            ek = e.copy()
            ek[k] += h
            J[:, k] = (self.defects(ek, pe, fhpe, lam, temperatures=temperatures)[0]
                       - d0) / h
        return J

    def solve(self, edges, pe, fhpe, lam=None, *, sigma_over_delta=None, temperatures=None,
              max_iter=40, check_validity=True, polish=True,
              estimate=False) -> ZoneSolution:
        """Newton's method on the edges from ``edges`` to zero defects.

        Parameters
        ----------
        edges : array_like, shape (m, 2)
            The start.
        pe, fhpe : float
            ``Pe_l > 0`` and ``fHPe_l >= 0``.
        lam, sigma_over_delta : float
            The heat partition (``|lam| <= 1e6``, as the single patch's: beyond
            [-1, 1] a formal continuation of the closure), or (one zone) the offset
            ``centre/half-width``, whose zone is ``((sigma - 1) Delta, (sigma + 1) Delta)``
            with ``Delta`` found by Newton's method (section 16).
        temperatures : Temperatures or (float, float or None)
            Or the far temperatures ``(Theta, L/l)``, the sink distance in units of
            ``l`` (a stationary half-plane; None for a moving one): ``lam`` is then
            an output (section 17).  Exactly one of the three closures.
        max_iter : int, optional
        check_validity, polish : bool, optional
            As :meth:`~thermocontact.solvers.single_patch.Model.solve`.
        estimate : bool, optional
            Also solve at ``n/2`` and ``n/4`` from the solution's edges and record the
            error estimate of :func:`~thermocontact.solvers.refinement.refine` on each
            zone's ``Delta_j^2`` and ``centre_j/Delta_j`` (None when ``n/2`` is below
            the smallest ``n``); without, ``error_estimate`` is None (not measured).

        Raises
        ------
        SolveError
            When Newton's method does not converge (the message says how far it got).
        """
        check_exactly_one(lam=lam, sigma_over_delta=sigma_over_delta,
                          temperatures=temperatures)
        check_range("pe_hertz", pe, *PE_HERTZ_RANGE)
        check_range("fhpe_hertz", fhpe, *FHPE_HERTZ_RANGE)
        lam, sigma = check_closure_range(lam, sigma_over_delta)
        if temperatures is not None:
            temperatures = check_temperatures(self.base, temperatures)
        if sigma is None:
            e, x, rcond, err, it = self._newton_edges(edges, pe, fhpe, lam, max_iter,
                                                      temperatures)
        else:
            check_offset_coupling(fhpe, "fhpe_hertz")
            e, x, rcond, err, it = self._newton_half(edges, pe, fhpe, sigma, max_iter)
        par = self.parameters(pe, fhpe)
        m, n = len(e) // 2, self.n
        edges2 = e.reshape(m, 2)
        phi = x[:m * n].reshape(m, n)
        psi = x[m * n:2 * m * n].reshape(m, n)
        rep = self.representation()
        validity = (assess_zones(par, rep, edges2, phi, psi, self.profile, polish=polish)
                    if check_validity else None)
        sol = ZoneSolution(par, 0.0 if lam is None else lam, edges2, phi, psi, rep,
                           self.method, err, it, rcond, validity, self.profile,
                           temperatures=temperatures, conductance=self.conductance)
        if lam is None:
            # The offset's or the temperatures' partition: the zones' shares summed (D19).
            sol = replace(sol, lam=float(np.sum(sol.heat_partitions)))
        if estimate:
            sol = replace(sol, error_estimate=self.error_estimate(
                sol, sigma_over_delta=sigma, max_iter=max_iter))
        return sol

    def at_n(self, n) -> "ZoneModel":
        """The same model with ``n`` unknowns per function per zone."""
        other = object.__new__(ZoneModel)
        other.__dict__.update(self.__dict__)
        other.n = int(n)
        return other

    def error_estimate(self, sol: ZoneSolution, *, sigma_over_delta=None, max_iter=40):
        """The error estimate of ``sol`` from the solutions at ``n/4``, ``n/2`` and
        ``n`` (:func:`~thermocontact.solvers.refinement.refine`, each zone's
        :class:`ZoneMeasure` a case), or None when ``n/2`` is below the smallest ``n``.
        """
        sizes = [k for k in (sol.n // 4, sol.n // 2) if k >= N_RANGE[0]] + [sol.n]
        if len(sizes) < 2:
            return None
        closure = ({"sigma_over_delta": sigma_over_delta} if sigma_over_delta is not None
                   else {"temperatures": sol.temperatures} if sol.temperatures is not None
                   else {"lam": sol.lam})

        def at(k):
            if k == sol.n:
                return zone_measures(sol)
            coarse = self.at_n(k).solve(sol.edges, sol.parameters.pe, sol.parameters.fhpe,
                                        max_iter=max_iter, check_validity=False, **closure)
            if coarse.zones != sol.zones:
                raise SolveError("the error estimate's coarser solution has another "
                                 "number of zones")
            return zone_measures(coarse)
        _, est = refine(at, sizes, p_max=METHODS[self.method].order_cap)
        return None if est is None else float(est)

    def _newton_edges(self, edges, pe, fhpe, lam, max_iter, temperatures=None):
        e = _edges(edges).ravel().copy()
        J = None
        for it in range(max_iter + 1):
            d, x, rcond = self.defects(e, pe, fhpe, lam, temperatures=temperatures)
            err = float(np.max(np.abs(d)))
            if err < DEFECT_TOL:
                break
            if it == max_iter:
                raise NotConvergedError(f"the edges did not converge in {max_iter} Newton steps "
                                 f"(largest defect {err:.2e})")
            J = self.jacobian(e, pe, fhpe, lam, d, temperatures=temperatures)
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
        return e, x, rcond, err, it

    def _newton_half(self, edges, pe, fhpe, sigma, max_iter):
        """Newton's method on the one zone's half-width ``Delta`` with its centre at
        ``sigma Delta``, to ``nu = 0`` (section 16)."""
        start = _edges(edges)
        if len(start) != 1:
            raise InputError(f"sigma_over_delta closes a single zone only (section 16), "
                             f"got {len(start)} zones; give lam instead",
                             parameters=("sigma_over_delta",))
        half = 0.5 * float(start[0, 1] - start[0, 0])

        def at(h):
            e = np.array([(sigma - 1.0) * h, (sigma + 1.0) * h])
            d, x, rcond = self.defects(e, pe, fhpe, sigma_over_delta=sigma)
            return e, float(d[0]), x, rcond
        for it in range(max_iter + 1):
            e, d, x, rcond = at(half)
            err = abs(d)
            if err < DEFECT_TOL:
                return e, x, rcond, err, it
            if it == max_iter:
                break
            h = 1e-7 * half
            slope = (at(half + h)[1] - d) / h
            if slope == 0.0 or not np.isfinite(slope):
                raise SolveError("the half-width's Newton step is singular")
            # Keep the zone: it shrinks by at most half a step.
            half = max(half - d / slope, 0.5 * half)
        raise NotConvergedError(f"the half-width did not converge in {max_iter} Newton steps "
                         f"(defect {err:.2e})")
