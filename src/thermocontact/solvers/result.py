"""The result of one solve: small, frozen, picklable, comparable (the result protocol,
:mod:`thermocontact.io.results`)."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .._version import __version__
from ..analysis.applicability import Applicability
from ..analysis.validity import Validity, gap
from ..io.results import FieldResult, dataset_attrs, with_units
from ..problem.parameters import Parameters

__all__ = ["ContactSolution"]


@dataclass(frozen=True, eq=False, repr=False)
class ContactSolution(FieldResult):
    """One solution of the sliding-contact problem, in dimensionless form.

    Positions are ``s = (x - sigma)/Delta``: ``s = +1`` is the leading edge, where
    the cylinder's surface enters the contact.  Pressures are normalised to unit
    integral over the contact and positive in compression; heat fluxes are in
    units of ``f v P / Delta``, so that ``q1 + q2`` is the pressure and the
    integral of ``q = q1 - q2`` is ``lam``.

    Attributes
    ----------
    parameters : Parameters
    method : str
        Discretisation method, a key of
        :data:`~thermocontact.discretisation.methods.METHODS`.
    n : int
        Unknowns per function.
    load_ratio : float
        ``P_H/P``: the Hertz load for the same half-width over the actual load.
    lam : float
        Heat partition ``(Q1 - Q2)/(Q1 + Q2)``.
    sigma_over_delta : float
        Offset of the contact centre from the cylinder's initial point of contact,
        in half-widths, positive toward the leading edge (``+x``).
    phi, psi : ndarray, shape (n,)
        The unknowns at the representation's nodes: ``p/sqrt(1 - s^2)`` and
        ``q' sqrt(1 - s^2)``.
    representation : Representation
        How ``phi`` and ``psi`` are carried and integrated (pickled as its class
        and ``n``).
    validity : Validity or None
        The contact inequalities (None when not evaluated).
    rcond : float
        Reciprocal condition number (1-norm) of the equilibrated linear system:
        LAPACK's estimate; from ``Model.solve_many(..., rcond="bound")`` a proven lower
        bound where one was proven (derivation section 6b).
    error_estimate : float or None
        Estimated relative error of ``P_H/P`` and ``sigma/Delta`` (the larger;
        :func:`~thermocontact.solvers.refinement.error_estimate`).
    tol : float or None
        The error target.
    auto_n : bool
        Whether ``n`` was chosen automatically.
    load_ratio_change : float or None
        ``|P_H/P(2n) - P_H/P(n)|`` when a convergence check was asked for.
    estimate_is_bound : bool
        False for a method whose error estimate does not bound its error (the
        paper's scheme): such a result is never ``converged``.
    applicability : Applicability or None
        Whether the theory's assumptions hold, when judged for a given ``Delta/R``
        (:func:`~thermocontact.analysis.applicability.applicability`); its entries
        then end the record.
    conductance : Conductance or None
        The interface conductance, if any.
    temperatures : Temperatures or None
        The far temperatures when they closed the problem (``lam`` an output,
        derivation section 17).
    lam_error : float or None
        The estimated absolute error of ``lam`` where it is an output of the
        temperatures and was measured (the Richardson estimate of the refinement).
    """

    parameters: Parameters
    method: str
    n: int
    load_ratio: float
    lam: float
    sigma_over_delta: float
    phi: np.ndarray
    psi: np.ndarray
    representation: object
    validity: Validity | None = None
    rcond: float = float("nan")
    error_estimate: float | None = None
    tol: float | None = None
    auto_n: bool = False
    load_ratio_change: float | None = None
    estimate_is_bound: bool = True
    applicability: Applicability | None = None
    conductance: object = None
    temperatures: object = None
    lam_error: float | None = None

    STATUSES = {
        "converged": "the error estimate is within its target (tol)",
        "not converged": "the error estimate exceeds its target at the largest n tried",
        "unreliable estimate": "the method's error estimate is no bound (the paper's "
                               "scheme): not claimed converged",
        "no estimate": "one level only (n < 8 given): no error estimate"}
    SUCCESS = frozenset({"converged"})
    # Lengths in half-widths Delta, pressures normalised to unit load (P/Delta), heat
    # fluxes in units of the frictional heat f v P/Delta, gaps in Delta^2/R; the
    # record's other numbers are pure.
    UNITS = {"s": "Delta", "flux_s": "Delta", "pressure": "P/Delta",
             "flux_difference": "f v P/Delta", "flux_cylinder": "f v P/Delta",
             "flux_half_plane": "f v P/Delta", "min_gap": "Delta^2/R",
             "sink_distance": "Delta"}

    # Status, in the manner of scipy's OptimizeResult.
    @property
    def converged(self) -> bool | None:
        """``error_estimate <= tol`` (None without an estimate)."""
        if self.error_estimate is None or self.tol is None:
            return None
        return bool(self.estimate_is_bound and self.error_estimate <= self.tol)

    @property
    def status(self) -> str:
        """``"converged"``, ``"not converged"``, ``"unreliable estimate"`` (a method whose
        estimate is no bound) or ``"no estimate"`` (``n < 8`` given)."""
        c = self.converged
        if c is None:
            return "no estimate"
        if not self.estimate_is_bound:
            return "unreliable estimate"
        return "converged" if c else "not converged"

    @property
    def success(self) -> bool:
        """Converged (:attr:`SUCCESS`) and valid."""
        return bool(self.converged) and self.validity is not None and self.validity.valid

    @property
    def estimate_message(self) -> str:
        """One line on the error estimate against its target."""
        if self.error_estimate is None:
            return f"no error estimate (n = {self.n} leaves no coarser level)"
        if not self.estimate_is_bound:
            return (f"error estimate {self.error_estimate:.1e} at n = {self.n} is no bound for "
                    f"method {self.method!r}: not claimed converged")
        return (f"error estimate {self.error_estimate:.1e} "
                f"{'<=' if self.converged else '>'} target {self.tol:.0e} at n = {self.n}")

    @property
    def message(self) -> str:
        """One line: the error estimate against its target, and the verdict of validity."""
        head = self.estimate_message
        if self.validity is None:
            return head + "; validity not evaluated"
        tail = ""
        if not self.validity.certain():
            tail = (f" (a margin is within its change since n/2, "
                    f"{self.validity.margin_change:.1e}: its sign is not certain)")
        return f"{head}; {self.validity.reason}{tail}"

    @property
    def valid(self) -> bool:
        """Whether every contact inequality holds (see :class:`Validity`)."""
        if self.validity is None:
            raise ValueError("validity was not evaluated for this solution")
        return self.validity.valid

    # Profiles, from the unknowns.
    @property
    def eta(self) -> float:
        """``(1 - K2/K1)/(1 + K2/K1)``."""
        return self.parameters.eta

    @property
    def s(self):
        """Nodes of the pressure in ``[-1, 1]``, edges included."""
        return np.concatenate([[-1.0], self.representation.pressure_rule.nodes, [1.0]])

    @property
    def pressure(self):
        """The pressure at :attr:`s` (zero at the edges)."""
        pr = self.representation.pressure_rule
        return np.concatenate([[0.0], pr.edge_factor * self.phi, [0.0]])

    @property
    def flux_s(self):
        """Nodes of the heat fluxes (interior: they are singular at the edges)."""
        return self.representation.flux_rule.nodes.copy()

    def _pressure_at_flux_nodes(self):
        pr, fr = self.representation.pressure_rule, self.representation.flux_rule
        if np.array_equal(fr.nodes, pr.nodes):
            return pr.edge_factor * self.phi
        return fr.edge_factor * self.representation.phi_at(self.phi, fr.nodes)

    @property
    def flux_difference(self):
        """``q = q1 - q2 = q' + eta p`` at :attr:`flux_s`."""
        fr = self.representation.flux_rule
        return self.psi / fr.edge_factor + self.eta * self._pressure_at_flux_nodes()

    @property
    def flux_cylinder(self):
        """``q1 = (p + q)/2`` at :attr:`flux_s`."""
        return 0.5 * (self._pressure_at_flux_nodes() + self.flux_difference)

    @property
    def flux_half_plane(self):
        """``q2 = (p - q)/2`` at :attr:`flux_s`."""
        return 0.5 * (self._pressure_at_flux_nodes() - self.flux_difference)

    def pressure_at(self, s):
        """Pressure at ``s`` in ``[-1, 1]``."""
        return self.representation.pressure_at(self.phi, s)

    def flux_difference_at(self, s):
        """Heat-flux difference ``q = q' + eta p`` at ``s`` in ``(-1, 1)``."""
        s = np.asarray(s, dtype=float)
        psi = self.representation.psi_at(self.psi, s)
        return psi / np.sqrt(1.0 - s * s) + self.eta * self.pressure_at(s)

    def gap_at(self, s):
        """Gap at ``|s| >= 1`` in units of ``Delta^2/R`` (derivation D20-D21)."""
        g, _ = gap(self.parameters, self.representation, self.phi, self.psi,
                   self.load_ratio, self.sigma_over_delta, self.lam, s)
        return g

    # Display and records (equality and pickling: :class:`~thermocontact.io.results.Result`).
    def _summary(self):
        p = self.parameters
        v = "?" if self.validity is None else self.validity.valid
        est = "None" if self.error_estimate is None else f"{self.error_estimate:.1e}"
        return (f"pe={p.pe:g}, fhpe={p.fhpe:g}, K2_over_K1={p.K2_over_K1:g}, "
                f"method={self.method!r}, n={self.n}, load_ratio={self.load_ratio:.10g}, "
                f"lam={self.lam:.6g}, sigma_over_delta={self.sigma_over_delta:.6g}, "
                f"valid={v}, error_estimate={est}, status={self.status!r}")

    def _record(self) -> dict:
        """The record of :meth:`to_dict`, the CLI's ``--json``: scalars, validity margins,
        profiles, then the applicability's entries when it was judged (and the units,
        :attr:`UNITS`, which end every record).

        Pressure profile ``s``/``pressure`` is normalised to unit integral (Hertz:
        ``(2/pi) sqrt(1 - s^2)``); gaps are in units of ``Delta^2/R``; positions in
        ``s = (x - sigma)/Delta``.
        """
        par = self.parameters
        rec = {
            "load_ratio": self.load_ratio,
            "lam": self.lam,
            "sigma_over_delta": self.sigma_over_delta,
            "pe": par.pe,
            "fhpe": par.fhpe,
            "K2_over_K1": par.K2_over_K1,
            "k2_over_k1": par.k2_over_k1,
            "delta1_over_delta2": par.delta1_over_delta2,
            "speed_ratio": par.speed_ratio,
            "beta_f": par.beta_f,
            "edge_exponents": [1.0 - par.edge_exponent, par.edge_exponent],
            "n": self.n,
            "method": self.method,
            "status": self.status,
            "message": self.message,
            "success": self.success,
        }
        if self.validity is not None:
            rec.update(self.validity.to_dict())
        rec.update({
            "rcond": self.rcond,
            "load_ratio_change": self.load_ratio_change,
            "error_estimate": self.error_estimate,
            "converged": self.converged,
            "auto_n": self.auto_n,
            "tol": self.tol,
            "s": self.s.tolist(),
            "pressure": self.pressure.tolist(),
            "flux_s": self.flux_s.tolist(),
            "flux_difference": self.flux_difference.tolist(),
            "flux_cylinder": self.flux_cylinder.tolist(),
            "flux_half_plane": self.flux_half_plane.tolist(),
            "version": __version__,
        })
        if self.conductance is not None:
            # Flat scalars, so that the dataset's attributes hold them.
            rec["conductance_biot0"] = self.conductance.biot0
            rec["conductance_exponent"] = self.conductance.exponent
        if self.temperatures is not None:
            rec["theta"] = self.temperatures.theta
            rec["sink_distance"] = self.temperatures.sink_distance
            rec["lam_error"] = self.lam_error
        if self.applicability is not None:
            rec.update(self.applicability.to_dict())
        return rec

    def to_dataset(self):
        """An :class:`xarray.Dataset`: profiles on their coordinates, the rest as attributes.

        Variables ``pressure(s)``, ``flux_difference(flux_s)``, ``flux_cylinder(flux_s)``
        and ``flux_half_plane(flux_s)``; attributes: the inputs, ``load_ratio``,
        ``lam``, ``sigma_over_delta``, the validity margins, the error estimate,
        ``status``, ``message``, the method, ``n`` and the package version.
        """
        import xarray as xr

        profiles = ("s", "pressure", "flux_s", "flux_difference", "flux_cylinder",
                    "flux_half_plane")
        attrs = dataset_attrs(self.to_dict(), skip=profiles)
        return with_units(xr.Dataset(
            {
                "pressure": ("s", self.pressure, {"long_name": "contact pressure",
                                                  "units": "P/Delta"}),
                "flux_difference": ("flux_s", self.flux_difference,
                                    {"long_name": "q1 - q2", "units": "f v P/Delta"}),
                "flux_cylinder": ("flux_s", self.flux_cylinder,
                                  {"long_name": "heat flux into the cylinder",
                                   "units": "f v P/Delta"}),
                "flux_half_plane": ("flux_s", self.flux_half_plane,
                                    {"long_name": "heat flux into the half-plane",
                                     "units": "f v P/Delta"}),
            },
            coords={"s": ("s", self.s, {"long_name": "(x - sigma)/Delta"}),
                    "flux_s": ("flux_s", self.flux_s, {"long_name": "(x - sigma)/Delta"})},
            attrs=attrs,
        ), self._units())
