"""Whether the theory behind a solution applies: small contact, slopes and strains,
temperatures the materials survive.

``valid`` (:mod:`.validity`) says whether a solution satisfies the contact
inequalities of the model.  The model itself (derivation sections 1-5) rests on
half-plane theory: linear elasticity with small strains, surfaces whose slopes are
small, a contact much narrower than the cylinder's radius, and material constants
that hold at the temperatures reached.  This module measures each of those and
says, with the numbers, which assumption a solution violates.

Slopes (derivation D14 in physical units).  The contact equation balances, at
``x = sigma + Delta s``, the surfaces' displacement slopes against the rigid
profile's ``x/R``; multiplied by ``(Delta/R) pi/(2L)`` its terms are slopes:

* elastic, both bodies: ``(1/pi) PV integral p(r)/(s - r) dr``, shared in the
  ratio of the bodies' compliances ``(1 - nu_i)/mu_i`` over their sum ``A``;
* thermal, cylinder: ``F d integral N(c(s - r)) H(s - r) (p + q)(r) dr``;
* thermal, half-plane: ``F integral sgn(s - r) q2(r) dr``, ``q2 = ((1 - eta) p - q')/2``;

and the rigid profile's own slope over the contact is at most
``(|sigma| + Delta)/R``.  Each body's surface slope is bounded by the sum of the
magnitudes of its parts; without the compliances (a dimensionless solve) the
whole elastic part is charged to each body.

Strains.  The peak pressure times each body's compliance ``(1 - nu_i)/mu_i``; in
dimensionless form ``A p_max = p_max pi/(2L) Delta/R`` (with ``p`` in units of
``P/Delta``), charged to each body when the compliances are not known.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..discretisation.operator import distortion_operators
from ..io.results import Result
from .fields import slope_factors, slopes_and_strains

__all__ = ["AMBIENT_TEMPERATURE", "Applicability", "MAX_HALF_WIDTH_OVER_RADIUS",
           "MAX_SLOPE", "MAX_STRAIN", "applicability", "assess", "physical_applicability",
           "surface_slopes"]

#: Half-plane theory replaces the cylinder by a half-plane: the contact must be small
#: against the radius (the curvature's error in the Hertz load is O((Delta/R)^2)).
MAX_HALF_WIDTH_OVER_RADIUS = 0.1
#: Small-slope theory linearises the surfaces' geometry: sin, tan and the slope agree
#: to 0.5 % at 0.1.
MAX_SLOPE = 0.1
#: Linear elasticity with constant moduli: 1 % strain is beyond the elastic limit of
#: every material in the built-in list except elastomers.
MAX_STRAIN = 0.01
#: The temperature that the computed rises (above the cylinder's incoming surface
#: temperature) are added to when compared with a material's limit, K (20 C).
AMBIENT_TEMPERATURE = 293.15


@dataclass(frozen=True, eq=False, repr=False)
class Applicability(Result):
    """Whether the assumptions of the theory hold for one solution.

    Attributes
    ----------
    applicable : bool
        Every measured quantity within its threshold.
    reasons : tuple of str
        One sentence per violated assumption, with the numbers.
    half_width_over_radius : float
    max_slope : tuple of float
        Bound on the largest surface slope of the cylinder and of the half-plane
        over the contact.
    max_strain : tuple of float
        Peak pressure times each body's compliance (the same bound for both when
        the compliances are not known).
    temperature_range : tuple of float or None
        Least and greatest surface temperature over the contact, K (physical
        units only; ambient :data:`AMBIENT_TEMPERATURE` plus the computed rises).
    max_temperature : tuple of float or None
        The materials' limits, K (None where unknown).
    """

    applicable: bool
    reasons: tuple
    half_width_over_radius: float
    max_slope: tuple
    max_strain: tuple
    temperature_range: tuple | None = None
    max_temperature: tuple | None = None

    def _summary(self) -> str:
        return (f"applicable={self.applicable}, reasons={len(self.reasons)}, "
                f"half_width_over_radius={self.half_width_over_radius:.3g}")

    def _record(self) -> dict:
        return {
            "applicable": self.applicable,
            "applicability_reasons": list(self.reasons),
            "half_width_over_radius": self.half_width_over_radius,
            "max_slope": list(self.max_slope),
            "max_strain": list(self.max_strain),
            "temperature_range": (None if self.temperature_range is None
                                  else list(self.temperature_range)),
            "max_temperature": (None if self.max_temperature is None
                                else list(self.max_temperature)),
        }


def surface_slopes(sol, points=201):
    """The slope terms of (D14) over the contact, dimensionless (see the module notes).

    Returns
    -------
    s : ndarray
        Interior points.
    elastic, thermal_cylinder, thermal_half_plane : ndarray
        The terms at ``s`` in the units of (D14); times ``(Delta/R) pi/(2L)`` they
        are slopes.
    """
    par, rep = sol.parameters, sol.representation
    s = np.cos(np.pi * (np.arange(points, 0, -1) - 0.5) / points)
    cb, _ = rep.cauchy(s)
    elastic = (cb @ sol.phi) / np.pi
    F = par.fhpe
    (cyl_b, cyl_s), (hp_b, hp_s) = distortion_operators(par, rep, s)
    thermal_1 = F * (cyl_b @ sol.phi + cyl_s @ sol.psi)
    thermal_2 = F * (hp_b @ sol.phi + hp_s @ sol.psi)
    return s, elastic, thermal_1, thermal_2


def applicability(sol, half_width_over_radius, *, compliance_fractions=None,
                  temperature_rises=None, max_temperature=None) -> Applicability:
    """Measure the theory's assumptions for one solution (:func:`assess`).

    Parameters
    ----------
    sol : ContactSolution
    half_width_over_radius : float
        ``Delta/R``.
    compliance_fractions : pair of float, optional
        ``((1 - nu_1)/mu_1, (1 - nu_2)/mu_2)`` over their sum ``A``; without them
        each body is charged with the whole elastic slope and strain (a bound).
    temperature_rises : array_like, optional
        Surface temperature rises over the contact, K (physical units only).
    max_temperature : pair of float or None, optional
        The cylinder's and the half-plane's limits, K.

    Returns
    -------
    Applicability
    """
    ratio = float(half_width_over_radius)
    frac = (1.0, 1.0) if compliance_fractions is None else tuple(compliance_fractions)
    factors, p_max = slope_factors(sol, frac)
    slope, strain = slopes_and_strains(ratio, abs(sol.sigma_over_delta) + 1.0, sol.load_ratio,
                                       factors, p_max, frac)
    t_range = None
    if temperature_rises is not None:
        rises = np.asarray(temperature_rises, dtype=float)
        rises = rises[np.isfinite(rises)]
        t_range = (float(rises.min()), float(rises.max()))
    return assess(ratio, slope, strain, temperature_rises=t_range,
                  max_temperature=max_temperature)


def assess(half_width_over_radius, max_slope, max_strain, *, temperature_rises=None,
           max_temperature=None, datum=AMBIENT_TEMPERATURE) -> Applicability:
    """Judge the theory's assumptions from their measures: the one judgement of a
    single patch, a contact set and an operating map's point, in one wording.

    Parameters
    ----------
    half_width_over_radius : float
        The contact's half-width (a contact set's: half its extent) over the radius.
    max_slope, max_strain : pair of float
        The cylinder's and the half-plane's (:func:`~.fields.slopes_and_strains`).
    temperature_rises : pair of float, optional
        The least and the greatest surface temperature rise over the contact, K
        (physical units only); added to :data:`AMBIENT_TEMPERATURE`.
    max_temperature : pair of float or None, optional
        The cylinder's and the half-plane's limits, K.
    datum : float
        The temperature the rises are over, K: :data:`AMBIENT_TEMPERATURE`, or the
        cylinder's bulk temperature where it is given (derivation section 17).

    Returns
    -------
    Applicability
    """
    ratio = float(half_width_over_radius)
    slope, strain = tuple(max_slope), tuple(max_strain)
    reasons = []
    if ratio > MAX_HALF_WIDTH_OVER_RADIUS:
        reasons.append(f"half-width/radius {ratio:.3g} > {MAX_HALF_WIDTH_OVER_RADIUS:g}: "
                       f"not a small contact (half-plane theory)")
    for body, value in zip(("cylinder", "half-plane"), slope):
        if not value <= MAX_SLOPE:
            reasons.append(f"{body} surface slope up to {value:.3g} > {MAX_SLOPE:g}: "
                           f"not small slopes")
    for body, value in zip(("cylinder", "half-plane"), strain):
        if not value <= MAX_STRAIN:
            reasons.append(f"{body} strain (peak pressure x compliance) {value:.3g} > "
                           f"{MAX_STRAIN:g}: not small strains")
    t_range = limits = None
    if temperature_rises is not None:
        low, high = (float(t) for t in temperature_rises)
        t_range = (datum + low, datum + high)
        if t_range[0] <= 0.0:
            reasons.append(f"surface temperature down to {t_range[0]:.4g} K (a fall of "
                           f"{-low:.4g} K below {datum:g} K): below "
                           f"absolute zero, the linear heat conduction model does not hold")
        if max_temperature is not None:
            limits = tuple(max_temperature)
            for body, limit in zip(("cylinder", "half-plane"), limits):
                if limit is not None and t_range[1] > limit:
                    reasons.append(f"surface temperature up to {t_range[1]:.4g} K > the "
                                   f"{body} material's limit {limit:.4g} K")
    return Applicability(applicable=not reasons, reasons=tuple(reasons),
                         half_width_over_radius=ratio, max_slope=slope, max_strain=strain,
                         temperature_range=t_range, max_temperature=limits)


def physical_applicability(problem, fields) -> Applicability:
    """Whether the theory applies to a contact of a physical problem: :func:`assess`
    of its fields (:func:`~.fields.contact_fields` in SI units), the one judgement of a
    single patch's branch and of a contact set.

    Parameters
    ----------
    problem : PhysicalProblem
        The radius, the compliances and the materials' temperature limits.
    fields : ContactFields
        In metres, pascals and kelvin.
    """
    slope, strain = fields.slopes_and_strains(problem.radius, problem.compliance_fractions)
    return assess(fields.extent * fields.length / problem.radius, slope, strain,
                  temperature_rises=fields.temperature_range,
                  max_temperature=(problem.cylinder.max_temperature,
                                   problem.half_plane.max_temperature),
                  datum=(AMBIENT_TEMPERATURE if getattr(problem, "bulk_temperatures", None)
                         is None else problem.bulk_temperatures[0]))
