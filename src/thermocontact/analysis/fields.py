"""The fields of a contact: pressure, both surfaces' temperatures, slopes and strains.

One evaluator for every kind of contact: a single patch
(:class:`~thermocontact.solvers.result.ContactSolution`), a contact set of several
zones (:class:`~thermocontact.solvers.zones.ZoneSolution`) and a sample of an
operating map's ray.  A contact is a list of zones, each with its centre and
half-width in a unit of length ``ell`` (the half-width ``Delta`` of a single patch,
whose centre is its offset ``sigma/Delta``; the Hertz half-width ``l`` of a contact
set), its pressure ``p`` in units of ``P/ell`` and its heat-flux difference ``q'``
carried by ``(phi, psi)`` in its own coordinate ``s``.  Every field at a point is
the sum of every zone's integral.

Temperatures (derivation D8, D12; section 5b for a moving half-plane).  The
cylinder's surface temperature rise over its incoming temperature is

    T1(x) = (1/(pi K1)) integral q1(xi) exp(-u) K0(|u|) dxi,  u = v1 (x - xi)/(2 k1),

with ``q1 = ((1 + eta) p + q')/2`` in units ``f |v1 - v2| P/ell``: on zone ``j``,
``T1 = (f |v1 - v2| P/(pi K1)) h_j integral q1_j(r) T(c_j (s_j - r)) dr`` with
``T(u) = exp(-u) K0(|u|)``, ``c_j = Pe_ell h_j k2/k1`` and ``s_j`` the point in the
zone's coordinate.  A stationary half-plane's is
``T2 = -(f |v1 - v2| P/(pi K2)) h_j integral q2_j(r) (ln|s_j - r| + ln h_j) dr``,
``q2 = ((1 - eta) p - q')/2``, up to a constant that the 2-D model leaves free: it
is set by perfect thermal contact, the mean of ``T1 - T2`` over the contact being
zero.  A half-plane moving through the contact has the cylinder's kernel with its
own signed scale ``c2`` and its rise over its own incoming temperature; that
temperature over the cylinder's is the same constant (the heat partition implies
it).  The flash temperature is the greatest of ``T1``: the maximum of the closed
form near the greatest sample (:func:`~thermocontact.numerics.extrema.polish_minimum`),
the edges included.

Slopes and strains (:mod:`.applicability`, module notes): the terms of (D14) at the
interior points, per body the largest ``fraction |elastic| + |thermal|``; times
``(ell/R) pi/(2 L)`` (``L = P_H/P`` in units of ``ell``: ``(Delta/l)^2`` for a single
patch, 1 for a contact set) they are slopes, and the rigid profile adds
``max|x|/R``.  The strain is each body's compliance times the greatest pressure on
the same points.
"""

from __future__ import annotations

from dataclasses import dataclass, field, fields, replace

import numpy as np

from ..discretisation.operator import distortion_operators, temperature_kernels
from ..numerics.extrema import polish_minimum
from ..numerics.moment_engine import geometry_cache

__all__ = ["ContactFields", "SAMPLES", "Zone", "contact_fields", "slope_factors",
           "slopes_and_strains", "surface_temperatures", "zones_of"]

#: Points per zone at which pressure and temperatures are sampled (``s = -cos(theta)``,
#: equally spaced in ``theta``, edges included).
SAMPLES = 201
#: Gauss-Chebyshev points per zone of the slopes and strains.
SLOPE_POINTS = 201


@dataclass(frozen=True, eq=False)
class Zone:
    """One zone of a contact: its ``centre`` and ``half`` width in units of ``ell``,
    its unknowns ``phi``, ``psi`` and the single-patch parameters of its own
    half-width (``Pe`` and ``fHPe`` times ``half``)."""

    centre: float
    half: float
    phi: np.ndarray
    psi: np.ndarray
    parameters: object


def zones_of(sol):
    """The zones of a single patch or of a contact set, and ``L = P_H/P`` in units of
    their length (``(Delta/l)^2`` for a single patch, 1 for a contact set).

    Returns
    -------
    zones : tuple of Zone
    representation : Representation
    eta : float
    load_ratio : float
    """
    par = sol.parameters
    if np.ndim(sol.phi) == 1:  # a single patch: one zone, in units of its half-width
        zone = Zone(float(sol.sigma_over_delta), 1.0, sol.phi, sol.psi, par)
        return (zone,), sol.representation, par.eta, float(sol.load_ratio)
    zones = tuple(Zone(float(c), float(h), ph, ps, replace(par, pe=par.pe * h, fhpe=par.fhpe * h))
                  for c, h, ph, ps in zip(sol.edges.mean(axis=1),
                                          0.5 * (sol.edges[:, 1] - sol.edges[:, 0]),
                                          sol.phi, sol.psi))
    return zones, sol.representation, par.eta, 1.0


def _local(zone: Zone, other: Zone, s):
    """``s`` of ``other``'s points in ``zone``'s coordinate (unchanged for its own)."""
    if zone is other:
        return s
    return (other.centre + other.half * s - zone.centre) / zone.half


def _temperatures(zones, rep, eta, units, at, s, half_plane=True):
    """Both bodies' surface temperature rises at points ``s`` of zone ``at``, before
    the half-plane's level is set: the sums over zones of (D8) and (D12) in units
    ``units`` (``f |v1 - v2| P/(pi K_i)``), by the kernels' one quadrature
    (:func:`~thermocontact.discretisation.operator.temperature_kernels`); the
    half-plane's None with ``half_plane=False``."""
    t1 = t2 = 0.0
    for z in zones:
        u = _local(z, at, s)
        (tb, tq), hp = temperature_kernels(z.parameters, rep, u, half_plane=half_plane)
        # q1, q2 = ((1 +- eta) p +- q')/2, each body with its own signed kernel scale.
        a = units[0] * 0.5 * ((1 + eta) * (tb @ z.phi) + tq @ z.psi)
        t1 = t1 + (a if z.half == 1.0 else z.half * a)
        if not half_plane:
            continue
        hb, hq = hp
        if z.parameters.half_plane_scale:
            b = units[1] * 0.5 * ((1 - eta) * (hb @ z.phi) - hq @ z.psi)
        else:
            if z.half != 1.0:
                # ln|x - xi| in units of ell: ln h_j more per unit of heat.
                lg = np.log(z.half)
                hb = hb + lg * rep.pressure_rule.weights[None, :]
                hq = hq + lg * rep.flux_rule.weights[None, :]
            b = -units[1] * 0.5 * ((1 - eta) * (hb @ z.phi) - hq @ z.psi)
        t2 = t2 + (b if z.half == 1.0 else z.half * b)
    return t1, (t2 if half_plane else None)


def surface_temperatures(sol, s, *, zone=0, temperature_units=None):
    """Both bodies' surface temperature rises at points ``s`` of one zone (D8, D12).

    Parameters
    ----------
    sol : ContactSolution or ZoneSolution
    s : array_like
        Points in the zone's own coordinate (``[-1, 1]`` over the zone).
    zone : int
        Which zone (0 for a single patch).
    temperature_units : pair of float, optional
        As in :func:`contact_fields`.

    Returns
    -------
    t1, t2 : ndarray
        The cylinder's rise over its incoming temperature; the half-plane's before
        its level is set: a moving half-plane's rise over its own incoming
        temperature, a stationary one's up to a constant.
    """
    zones, rep, eta, _ = zones_of(sol)
    if temperature_units is None:
        temperature_units = (1.0, 1.0 / sol.parameters.K2_over_K1)
    s = np.atleast_1d(np.asarray(s, dtype=float))
    at = zones[zone]
    return _temperatures(zones, rep, eta, temperature_units, at, s)


def slopes_and_strains(length_over_radius, reach, load_ratio, slope_factors, strain_pressure,
                       fractions=(1.0, 1.0)):
    """Each body's largest surface slope and its strain (:mod:`.applicability`).

    ``slope_i = reach ell/R + (ell/R) pi/(2|L|) F_i`` and
    ``strain_i = fraction_i p_max (ell/R) pi/(2|L|)`` (D14 in physical units).

    Parameters
    ----------
    length_over_radius : float
        ``ell/R``.
    reach : float
        The largest ``|x|`` over the contact, units of ``ell`` (``|sigma| + 1`` for a
        single patch).
    load_ratio : float
        ``L = P_H/P`` in units of ``ell``.
    slope_factors : pair of float
        ``F_i``: the largest ``fraction_i |elastic| + |thermal_i|`` of (D14).
    strain_pressure : float
        ``p_max``, units ``P/ell``.
    fractions : pair of float
        Each body's compliance over ``A``.

    Returns
    -------
    max_slope, max_strain : pair of float, twice
    """
    ratio = float(length_over_radius)
    L = load_ratio
    scale = ratio * np.pi / (2.0 * abs(L)) if L != 0.0 else np.inf
    rigid = reach * ratio
    slope = (float(rigid + scale * slope_factors[0]), float(rigid + scale * slope_factors[1]))
    strain = (float(fractions[0] * strain_pressure * scale),
              float(fractions[1] * strain_pressure * scale))
    return slope, strain


@dataclass(frozen=True, eq=False)
class ContactFields:
    """A contact's surface fields in the units it was evaluated in.

    With ``length`` in m, ``load`` in N/m and temperature units in K (as
    :func:`contact_fields` is called for a physical problem): positions in m,
    pressures in Pa, temperature rises in K over the cylinder's incoming surface
    temperature.

    Attributes
    ----------
    x, pressure : ndarray
        :data:`SAMPLES` points per zone, edges included, zone after zone.
    temperature_cylinder, temperature_half_plane : ndarray
        At the same points (NaN at the edges, where the series are not evaluated).
    peak_pressure, mean_pressure : float
        The greatest pressure (of the closed form) and the load over the contact's
        length.
    flash_temperature : float
        The cylinder's greatest surface temperature rise (of the closed form, the
        edges included).
    temperature_mismatch : float
        The largest departure of ``T1 - T2`` from its mean over the contact (zero
        for the exact solution: perfect thermal contact).
    half_plane_incoming_temperature : float or None
        A moving half-plane's incoming temperature over the cylinder's, which the
        heat partition implies; None for a stationary half-plane.
    temperature_range : pair of float
        The least and the greatest surface temperature rise of either body over the
        contact.
    reach : float
        The largest ``|x|`` over the contact, units of ``length``.
    extent : float
        Half the distance from the first zone's trailing edge to the last zone's
        leading edge, units of ``length``.
    load_ratio : float
        ``L = P_H/P`` in units of ``length``.
    slope_factors : pair of float
        Per body, the largest ``fraction |elastic| + |thermal|`` of (D14).
    strain_pressure : float
        The greatest pressure on the slopes' points, units ``load/length``.
    length : float
        The unit of length the fields were evaluated in.
    """

    x: np.ndarray = field(repr=False)
    pressure: np.ndarray = field(repr=False)
    temperature_cylinder: np.ndarray = field(repr=False)
    temperature_half_plane: np.ndarray = field(repr=False)
    peak_pressure: float
    mean_pressure: float
    flash_temperature: float
    temperature_mismatch: float
    half_plane_incoming_temperature: float | None
    temperature_range: tuple
    reach: float
    extent: float
    load_ratio: float
    slope_factors: tuple
    strain_pressure: float
    length: float = 1.0

    @property
    def flash_temperature_half_plane(self) -> float | None:
        """A moving half-plane's greatest rise over its own incoming temperature (the
        surfaces being at one temperature in the contact); None if stationary."""
        if self.half_plane_incoming_temperature is None:
            return None
        return self.flash_temperature - self.half_plane_incoming_temperature

    def slopes_and_strains(self, radius, fractions=(1.0, 1.0)):
        """Each body's largest slope and strain for a cylinder of ``radius`` (units of
        ``length``, as :func:`slopes_and_strains`)."""
        return slopes_and_strains(self.length / radius, self.reach, self.load_ratio,
                                  self.slope_factors, self.strain_pressure, fractions)

    def __eq__(self, other):
        if type(other) is not type(self):
            return NotImplemented
        return all(np.array_equal(getattr(self, f.name), getattr(other, f.name), equal_nan=True)
                   if isinstance(getattr(self, f.name), np.ndarray)
                   else getattr(self, f.name) == getattr(other, f.name) for f in fields(self))

    __hash__ = None


def contact_fields(sol, *, length=1.0, load=1.0, temperature_units=None,
                   fractions=(1.0, 1.0), perfect_contact=True) -> ContactFields:
    """Evaluate a contact's fields (see the module notes).

    Parameters
    ----------
    sol : ContactSolution or ZoneSolution
        Anything with ``parameters``, ``representation``, ``phi`` and ``psi``: one
        zone (1-D ``phi``, with ``sigma_over_delta`` and ``load_ratio``) or several
        (2-D ``phi``, with ``edges``).
    length : float
        The solution's unit of length in the unit wanted (m: ``Delta``, or ``l``).
    load : float
        The load in the unit wanted (N/m); pressures come in ``load/length``.
    temperature_units : pair of float, optional
        ``f |v1 - v2| P/(pi K1)`` and ``f |v1 - v2| P/(pi K2)`` (K); default
        ``(1, K1/K2)``: temperatures in units of ``f |v1 - v2| P/(pi K1)``.
    fractions : pair of float
        Each body's compliance ``(1 - nu_i)/mu_i`` over their sum, for the slope
        factors (default: the whole elastic part charged to each body, a bound).
    perfect_contact : bool
        Whether both surfaces are at one temperature in the contact (default), which
        sets a stationary half-plane's level.  Across an interface conductance they
        are not, and the half-plane's temperatures are NaN (its level is not set):
        the temperature range is then the cylinder's.

    Returns
    -------
    ContactFields
    """
    zones, rep, eta, L = zones_of(sol)
    par = sol.parameters
    if temperature_units is None:
        temperature_units = (1.0, 1.0 / par.K2_over_K1)
    u1, u2 = temperature_units
    moving = bool(par.half_plane_scale)
    s = np.cos(np.linspace(np.pi, 0.0, SAMPLES))
    s_in = s[1:-1]
    unit_p = load / length
    xs, ps, t1s, t2s, t1_all = [], [], [], [], []
    peak = -np.inf
    for z in zones:
        p = unit_p * rep.pressure_at(z.phi, s)
        xs.append(z.centre * length + (z.half * length) * s)
        ps.append(p)
        ip = int(np.argmax(p))
        _, neg_peak = polish_minimum(lambda x, z=z: -unit_p * rep.pressure_at(z.phi, x), s, -p, ip)
        peak = max(peak, -neg_peak)
        t1, t2 = _temperatures(zones, rep, eta, (u1, u2), z, s_in)
        t1s.append(t1)
        t2s.append(t2)
        t_edges = _temperatures(zones, rep, eta, (u1, u2), z, np.array([-1.0, 1.0]),
                                half_plane=False)[0]
        t1_all.append(np.concatenate([t_edges[:1], t1s[-1], t_edges[1:]]))
    t1, t2 = np.concatenate(t1s), np.concatenate(t2s)
    if perfect_contact:
        shift = float(np.mean(t1 - t2))
        t2 = t2 + shift
        mismatch = float(np.max(np.abs(t1 - t2)))
    else:
        t2 = np.full_like(t2, np.nan)
        shift = mismatch = float("nan")
    # The flash temperature: the greatest sample, polished on the closed form in its zone.
    best = max(range(len(zones)), key=lambda j: np.max(t1_all[j]))
    t_all = t1_all[best]
    it = int(np.argmax(t_all))
    s_t = np.concatenate([[-1.0], s_in, [1.0]])
    zb = zones[best]
    # Its points are this solution's alone: their moments' geometry is not kept.
    with geometry_cache(rep.n).transient():
        _, neg_flash = polish_minimum(
            lambda x: -_temperatures(zones, rep, eta, (u1, u2), zb, np.asarray(x, dtype=float),
                                     half_plane=False)[0],
            s_t, -t_all, it)
    rises = np.concatenate([*t1_all, t2])
    rises = rises[np.isfinite(rises)]
    nan = np.array([np.nan])
    n_in = s_in.size
    t2_zones = [t2[k * n_in:(k + 1) * n_in] for k in range(len(zones))]
    factors, strain_p = _slope_factors(zones, rep, par, fractions)
    edges = [(z.centre - z.half, z.centre + z.half) for z in zones]
    # A single patch's |sigma| + 1, formed as the applicability has always formed it.
    reach = (abs(zones[0].centre) + 1.0 if len(zones) == 1 and zones[0].half == 1.0
             else max(max(abs(a), abs(b)) for a, b in edges))
    extent = zones[0].half if len(zones) == 1 else 0.5 * (edges[-1][1] - edges[0][0])
    width = sum(2.0 * z.half for z in zones)
    return ContactFields(
        x=np.concatenate(xs), pressure=np.concatenate(ps),
        temperature_cylinder=np.concatenate([np.concatenate([nan, t, nan]) for t in t1s]),
        temperature_half_plane=np.concatenate([np.concatenate([nan, t, nan])
                                               for t in t2_zones]),
        peak_pressure=float(peak), mean_pressure=load / (width * length),
        flash_temperature=float(-neg_flash), temperature_mismatch=mismatch,
        half_plane_incoming_temperature=shift if moving else None,
        temperature_range=(float(rises.min()), float(rises.max())),
        reach=float(reach), extent=float(extent), load_ratio=float(L),
        slope_factors=factors, strain_pressure=strain_p, length=float(length))


def slope_factors(sol, fractions=(1.0, 1.0)):
    """Per body the largest ``fraction |elastic| + |thermal|`` of (D14) over the
    contact, and the greatest pressure on the same points (units ``P/ell``), of a
    single patch or a contact set (:func:`slopes_and_strains` makes them slopes and
    strains)."""
    zones, rep, _, _ = zones_of(sol)
    return _slope_factors(zones, rep, sol.parameters, fractions)


def _slope_factors(zones, rep, par, fractions):
    """Per body the largest ``fraction |elastic| + |thermal|`` of (D14) over every
    zone's Gauss-Chebyshev points, and the greatest pressure there (units of ``ell``:
    zone ``j``'s thermal terms carry ``h_j``, section 14)."""
    m = SLOPE_POINTS
    s = np.cos(np.pi * (np.arange(m, 0, -1) - 0.5) / m)
    f1 = f2 = p_max = -np.inf
    for at in zones:
        elastic = t1 = t2 = 0.0
        for z in zones:
            u = _local(z, at, s)
            cb, _ = rep.cauchy(u)
            (cyl_b, cyl_s), (hp_b, hp_s) = distortion_operators(z.parameters, rep, u)
            # In units of l zone j's thermal terms carry h_j: fHPe_l h_j is its own fHPe.
            F = z.parameters.fhpe
            e = (cb @ z.phi) / np.pi
            a = F * (cyl_b @ z.phi + cyl_s @ z.psi)
            b = F * (hp_b @ z.phi + hp_s @ z.psi)
            elastic, t1, t2 = elastic + e, t1 + a, t2 + b
        f1 = max(f1, float(np.max(fractions[0] * np.abs(elastic) + np.abs(t1))))
        f2 = max(f2, float(np.max(fractions[1] * np.abs(elastic) + np.abs(t2))))
        p_max = max(p_max, float(np.max(rep.pressure_at(at.phi, s))))
    return (f1, f2), p_max
