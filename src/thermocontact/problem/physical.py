"""The contact problem in physical units: materials, radius, load, speeds, friction.

The inputs in SI units and what follows from them alone (derivation sections 5, 11b):
the compliance ``A``, Hertz's half-width and peak pressure, the dimensionless groups
at any trial half-width ``Delta`` (``Pe = v1 Delta/(2 k2)``, ``fHPe = f H |v1 - v2|
Delta/(2 k2)``, the materials' ratios, ``beta f``), the Hertz Peclet number ``Pe_H``
and the half-widths searched for the ones that carry the load.  The single patch's
branches, the contact sets and the operating maps all start from this one problem.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .closure import FarTemperatures, Temperatures, layer_sink_distance, temperature_group
from .materials import Material, dundurs_beta
from .parameters import Parameters
from .validation import InputError, check_finite, check_flag, check_nonnegative, check_positive

__all__ = ["FHPE_MIN", "MAX_WIDTH", "PhysicalProblem", "hertz_half_width", "scan_range"]

#: Half-widths searched: from below fHPe = FHPE_MIN (or half the Hertz half-width)
#: up to MAX_WIDTH Hertz half-widths, whatever fHPe that reaches.  Past fHPe ~ 0.6
#: (Barber's limiting width) P_H/P is negative, and from about 2 the formal solution
#: has poles between which P_H/P turns positive again: such branches exist formally
#: and are reported with their validity (roots were found at fHPe = 2.8 and 14 for
#: steel on cast iron).
FHPE_MIN = 0.05
MAX_WIDTH = 4.0


def hertz_half_width(compliance, radius, load):
    """``Delta_H = sqrt(2 A R P / pi)`` (D2), m; elementwise on arrays.

    Parameters
    ----------
    compliance : float
        ``A``, 1/Pa.
    radius, load : float or ndarray
        ``R`` (m) and ``P`` (N/m).
    """
    return np.sqrt(2.0 * compliance * radius * load / np.pi)


def scan_range(hertz_lo, hertz_hi, fhpe_per_unit):
    """The range searched for the half-widths that carry a load, in any unit of
    length (metres, or the Peclet number ``Pe`` along a ray).

    From half the least Hertz half-width, or half the width where ``fHPe =``
    :data:`FHPE_MIN` if that is less, to :data:`MAX_WIDTH` times the greatest.

    Parameters
    ----------
    hertz_lo, hertz_hi : float
        The least and the greatest Hertz half-width (equal for one problem).
    fhpe_per_unit : float
        ``fHPe`` per unit of length (``>= 0``; 0: no thermal coupling).

    Returns
    -------
    lo, hi : float
    """
    low = FHPE_MIN / fhpe_per_unit if fhpe_per_unit > 0 else hertz_lo
    return 0.5 * min(hertz_lo, low), MAX_WIDTH * hertz_hi


@dataclass(frozen=True)
class PhysicalProblem:
    """Inputs in SI units, validated on construction.

    Attributes
    ----------
    cylinder, half_plane : Material
        Body 1 (moving surface) and body 2 (stationary).
    radius : float
        Cylinder radius R, m.
    load : float
        Normal load per unit length P, N/m.
    speed : float
        Speed of the cylinder's surface through the contact v1 > 0, m/s (the sliding
        speed when the half-plane is stationary).
    friction : float
        Coulomb coefficient f >= 0.
    lam : float or None
        Heat partition (Q1 - Q2)/(Q1 + Q2); or None with ``bulk_temperatures``.
    speed2 : float, optional
        Speed of the half-plane's surface through the contact v2, m/s, positive in
        the cylinder's direction (derivation section 5b); 0, the default, is a
        stationary half-plane.  The frictional heat is ``f p |v1 - v2|``.
    dundurs : bool, optional
        Keep the Dundurs term ``-(beta f/2) p`` with ``beta`` of the two materials
        (default; derivation section 5c), or drop it as the paper does.
    bulk_temperatures : pair of float, optional
        Instead of ``lam`` (derivation section 17): the cylinder's incoming
        temperature and the half-plane's (its incoming one when it moves, its sink's
        when stationary), K; ``lam`` is then an output.
    sink_distance : float, optional
        With ``bulk_temperatures`` and a stationary half-plane: the distance L from
        the contact at which the half-plane is at its temperature, m (D38), larger
        than the Hertz half-width.
    layer_thickness : float, optional
        Or the thickness h of a half-plane layer on a sink at its temperature, m:
        ``L = 4 h/pi`` (D40).
    """

    cylinder: Material
    half_plane: Material
    radius: float
    load: float
    speed: float
    friction: float
    lam: float | None
    speed2: float = 0.0
    dundurs: bool = True
    bulk_temperatures: tuple | None = None
    sink_distance: float | None = None
    layer_thickness: float | None = None

    def __post_init__(self):
        for name in ("cylinder", "half_plane"):
            if not isinstance(getattr(self, name), Material):
                raise InputError(f"{name} must be a Material (see thermocontact.problem.materials."
                                 f"get_material), got {getattr(self, name)!r}")
            getattr(self, name).check_conducts(name)  # K = 0: only the TEI study takes it
        for name in ("radius", "load", "speed"):
            object.__setattr__(self, name, check_positive(name, getattr(self, name)))
        object.__setattr__(self, "friction", check_nonnegative("friction", self.friction))
        object.__setattr__(self, "speed2", check_finite("speed2", self.speed2))
        object.__setattr__(self, "dundurs", check_flag("dundurs", self.dundurs))
        self._check_closure()
        # A derived group out of the solver's range is reported with the inputs it
        # comes from, not only as the dimensionless group.
        dh = self.hertz_half_width
        try:
            if not (np.isfinite(dh) and dh > 0.0):
                raise InputError(f"the Hertz half-width sqrt(2 A R P / pi) is {dh:.3g} m")
            self.parameters(dh)
        except InputError as exc:
            raise InputError(
                f"the inputs are out of the solver's range at the Hertz half-width "
                f"{dh:.3g} m: {exc}; it follows from radius {self.radius:.3g} m, load "
                f"{self.load:.3g} N/m, speed {self.speed:.3g} m/s"
                + (f", speed2 {self.speed2:.3g} m/s" if self.speed2 else "") +
                f", friction {self.friction:g} "
                f"and the materials' E, nu, K and k ({self.cylinder.name}: E = "
                f"{self.cylinder.E:.3g} Pa, k = {self.cylinder.k:.3g} m^2/s; "
                f"{self.half_plane.name}: E = {self.half_plane.E:.3g} Pa, "
                f"k = {self.half_plane.k:.3g} m^2/s)") from None

    def _check_closure(self):
        """Exactly one closure: ``lam``, or the bulk temperatures with (stationary
        half-plane) one sink, larger than the contact (section 17)."""
        names = ("lam", "bulk_temperatures")
        if (self.lam is None) == (self.bulk_temperatures is None):
            raise InputError("give exactly one of lam and bulk_temperatures", parameters=names)
        sinks = {k: getattr(self, k) for k in ("sink_distance", "layer_thickness")
                 if getattr(self, k) is not None}
        if self.lam is not None:
            object.__setattr__(self, "lam", check_finite("lam", self.lam))
            if sinks:
                raise InputError(f"give bulk_temperatures, not lam, with "
                                 f"{' and '.join(sinks)}", parameters=tuple(sinks) + names)
            return
        try:
            t1, t2 = self.bulk_temperatures
        except (TypeError, ValueError):
            raise InputError(f"bulk_temperatures must be two temperatures (the cylinder's, "
                             f"the half-plane's), got {self.bulk_temperatures!r}",
                             parameters=("bulk_temperatures",)) from None
        temps = tuple(check_finite("bulk_temperatures", t) for t in (t1, t2))
        if min(temps) < 0.0:
            raise InputError(f"bulk_temperatures must be >= 0 K, got {temps}",
                             parameters=("bulk_temperatures",))
        object.__setattr__(self, "bulk_temperatures", temps)
        if self.friction == 0.0 or self.speed == self.speed2:
            raise InputError("bulk_temperatures need frictional heat (friction > 0 and "
                             "speed2 != speed): give lam", parameters=("bulk_temperatures",
                                                                       "friction"))
        if len(sinks) > 1:
            raise InputError("give at most one of sink_distance and layer_thickness",
                             parameters=tuple(sinks))
        if self.speed2 != 0.0:
            if sinks:
                raise InputError(f"{next(iter(sinks))} applies to a stationary half-plane "
                                 f"only (a moving one's temperature is its incoming one)",
                                 parameters=tuple(sinks) + ("speed2",))
            return
        if not sinks:
            raise InputError("a stationary half-plane needs sink_distance or "
                             "layer_thickness with bulk_temperatures",
                             parameters=("sink_distance", "layer_thickness",
                                         "bulk_temperatures"))
        name, value = next(iter(sinks.items()))
        object.__setattr__(self, name, check_positive(name, value))
        dh = self.hertz_half_width
        if self.sink_length <= dh:
            raise InputError(f"{name} must put the sink beyond the contact: L = "
                             f"{self.sink_length:.3g} m is not larger than the Hertz "
                             f"half-width {dh:.3g} m", parameters=(name,))

    @property
    def sink_length(self) -> float | None:
        """The stationary half-plane's sink distance L, m (``4 h/pi`` for a layer, D40);
        None without one."""
        if self.layer_thickness is not None:
            return layer_sink_distance(self.layer_thickness)
        return self.sink_distance

    @property
    def theta(self) -> float | None:
        """``Theta = pi K2 (T2 - T1)/(f |v1 - v2| P)`` of the bulk temperatures (D39)."""
        if self.bulk_temperatures is None:
            return None
        t1, t2 = self.bulk_temperatures
        return temperature_group(t1, t2, self.half_plane.K, self.friction,
                                 self.sliding_speed, self.load)

    @property
    def sink_pe(self) -> float | None:
        """``v1 L/(2 k2)``: the sink distance as a Peclet number, so that
        ``L/Delta = sink_pe/Pe`` at every trial half-width (section 17)."""
        L = self.sink_length
        return None if L is None else self.pe(L)

    def temperatures(self, half_width) -> Temperatures | None:
        """The temperature closure at half-width ``Delta`` (None with ``lam``)."""
        if self.bulk_temperatures is None:
            return None
        L = self.sink_length
        return Temperatures(self.theta, None if L is None else L / half_width)

    @property
    def compliance(self) -> float:
        """``A = (1 - nu1)/mu1 + (1 - nu2)/mu2``, 1/Pa."""
        return self.cylinder.compliance + self.half_plane.compliance

    @property
    def H(self) -> float:
        """``H = k2 delta2 / A``, dimensionless (the paper's eq. 10, corrected; D13)."""
        return self.half_plane.k * self.half_plane.distortivity / self.compliance

    @property
    def hertz_half_width(self) -> float:
        """``Delta_H = sqrt(2 A R P / pi)`` (D2), m."""
        return float(hertz_half_width(self.compliance, self.radius, self.load))

    @property
    def hertz_peak_pressure(self) -> float:
        """``p0 = 2 P / (pi Delta_H)``, Pa."""
        return 2.0 * self.load / (np.pi * self.hertz_half_width)

    @property
    def beta_f(self) -> float:
        """``B = beta f`` of the materials (0 with ``dundurs=False``)."""
        return dundurs_beta(self.cylinder, self.half_plane) * self.friction if self.dundurs else 0.0

    @property
    def speed_ratio(self) -> float:
        """``R = v2/v1``."""
        return self.speed2 / self.speed

    @property
    def sliding_speed(self) -> float:
        """``|v1 - v2|``, m/s: the speed that makes the heat."""
        return abs(self.speed - self.speed2)

    def pe(self, half_width):
        """``Pe = v1 Delta / (2 k2)``."""
        return self.speed * half_width / (2.0 * self.half_plane.k)

    def fhpe(self, half_width):
        """``fHPe = f H |v1 - v2| Delta / (2 k2)`` at half-width ``Delta`` (D13b)."""
        return self.friction * self.H * abs(1.0 - self.speed_ratio) * self.pe(half_width)

    @property
    def pe_hertz(self) -> float:
        """``Pe_H = v Delta_H / (2 k2)``: with the ray, all that load, radius and speed
        decide (D26)."""
        return self.pe(self.hertz_half_width)

    def half_width(self, pe):
        """The half-width at ``Pe``, m."""
        return pe * 2.0 * self.half_plane.k / self.speed

    def ray_parameters(self) -> dict:
        """The dimensionless groups that every trial half-width shares (the inputs of
        :class:`thermocontact.studies.ray.Ray`): the materials' ratios, the ray's slope
        ``fHPe/Pe = f H |1 - v2/v1|``, ``lam``, ``v2/v1`` and ``beta f``."""
        c, h = self.cylinder, self.half_plane
        return dict(K2_over_K1=h.K / c.K, k2_over_k1=h.k / c.k,
                    delta1_over_delta2=c.distortivity / h.distortivity,
                    fh=self.friction * self.H * abs(1.0 - self.speed_ratio), lam=self.lam,
                    speed_ratio=self.speed_ratio, beta_f=self.beta_f,
                    **({} if self.lam is not None else
                       dict(theta=self.theta, sink_pe=self.sink_pe)))

    @property
    def compliance_fractions(self) -> tuple:
        """Each body's compliance ``(1 - nu_i)/mu_i`` over their sum ``A``."""
        return (self.cylinder.compliance / self.compliance,
                self.half_plane.compliance / self.compliance)

    @property
    def temperature_units(self) -> tuple:
        """``f |v1 - v2| P/(pi K1)`` and ``f |v1 - v2| P/(pi K2)``, K: the units of each
        body's surface temperature rise (derivation D8, D12, D24)."""
        q = self.friction * self.sliding_speed * self.load
        return q / (np.pi * self.cylinder.K), q / (np.pi * self.half_plane.K)

    def scan_range(self) -> tuple:
        """The half-widths searched for the ones that carry the load, m
        (:func:`scan_range`)."""
        dh = self.hertz_half_width
        per_metre = self.fhpe(1.0)  # fHPe per metre of half-width
        lo, hi = scan_range(dh, dh, per_metre)
        if not (np.isfinite(lo) and np.isfinite(hi) and 0.0 < lo < hi):
            raise InputError(
                f"the inputs put the contact scale out of range (Hertz half-width {dh:.3g} m, "
                f"fHPe per metre {per_metre:.3g}): check radius, load, speed, friction and "
                f"materials")
        return lo, hi

    def hertz_load(self, half_width):
        """``P_H = pi Delta^2 / (2 A R)``, N/m."""
        return np.pi * half_width**2 / (2.0 * self.compliance * self.radius)

    def parameters(self, half_width) -> Parameters:
        """Dimensionless parameters at half-width ``Delta``."""
        c, h = self.cylinder, self.half_plane
        return Parameters(self.pe(half_width), self.fhpe(half_width), h.K / c.K, h.k / c.k,
                          c.distortivity / h.distortivity, self.speed_ratio, self.beta_f)

    def to_dimensionless(self, half_width) -> dict:
        """The inputs of :func:`thermocontact.solve` at half-width ``Delta`` (with bulk
        temperatures the closure ``FarTemperatures(Theta, L/Delta)`` of (D39))."""
        p = self.parameters(half_width)
        out = dict(pe=p.pe, fhpe=p.fhpe, K2_over_K1=p.K2_over_K1, k2_over_k1=p.k2_over_k1,
                   delta1_over_delta2=p.delta1_over_delta2)
        if self.lam is not None:
            out["lam"] = self.lam
        else:
            t = self.temperatures(half_width)
            out["closure"] = FarTemperatures(t.theta, t.sink_distance)
        if p.speed_ratio:
            out["speed_ratio"] = p.speed_ratio
        if p.beta_f:
            out["beta_f"] = p.beta_f
        return out
