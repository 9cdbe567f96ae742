"""The far temperatures of the bodies as the closure of the heat partition
(derivation section 17).

Perfect thermal contact makes the surfaces' temperatures equal in the contact; what
fixes the heat partition ``lam`` is each body's temperature far from it: a moving
body's incoming (bulk) temperature, or a stationary half-plane's temperature at a
sink distance ``L`` (the logarithmic law (D38)), or at the cooled back face of a
layer of thickness ``h`` (``L = 4 h/pi``, (D40)).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from .errors import InputError
from .validation import check_finite, check_positive, check_range

__all__ = ["BulkTemperatures", "CLOSURE_LIMIT", "DIMENSIONLESS_CLOSURES", "FarTemperatures",
           "HeatPartition", "Offset", "PHYSICAL_CLOSURES", "SINK_RANGE", "THETA_MAX",
           "Temperatures", "check_closure_range", "check_sink_distance", "check_theta",
           "closure_of", "far_temperatures", "layer_sink_distance", "spelled_closure",
           "temperature_closure", "temperature_group"]

#: Sink distances ``L/Delta`` solved: beyond the contact (the law holds for a flux
#: inside the semicircle of radius ``L``) up to where ``ln(L/Delta)`` is still far
#: from swamping the rows' other terms.
SINK_RANGE = (1.0, 1e12)


#: Bound on |lam| and |sigma/Delta|: far beyond any physical heat partition or offset
#: (the paper's Fig. 5 follows lam beyond +-1 as a formal continuation; a hot body
#: makes |lam| > 1 between bulk temperatures).
CLOSURE_LIMIT = 1e6


def check_closure_range(lam=None, sigma_over_delta=None):
    """``(lam, sigma_over_delta)``, each checked to lie in ``[-CLOSURE_LIMIT,
    CLOSURE_LIMIT]`` where given (None stays None)."""
    return (None if lam is None else check_range("lam", lam, -CLOSURE_LIMIT, CLOSURE_LIMIT),
            None if sigma_over_delta is None
            else check_range("sigma_over_delta", sigma_over_delta, -CLOSURE_LIMIT,
                             CLOSURE_LIMIT))


#: Largest |Theta| given as an input (solve, a dimensionless path's ends, a map's
#: corners): 1e6, as lam's bound; beyond, the products overflow (1e300 made a
#: partition of 5e299).  A Theta derived from physical inputs is not bounded by it.
THETA_MAX = 1e6


def check_theta(theta) -> float:
    """``theta`` given as an input: finite, ``|theta| <= THETA_MAX``."""
    return check_range("theta", theta, -THETA_MAX, THETA_MAX)


@dataclass(frozen=True)
class Temperatures:
    """The temperature closure in dimensionless form (derivation section 17).

    Attributes
    ----------
    theta : float
        ``Theta = pi K2 (T2 - T1)/(f |v1 - v2| P)`` (D39): the half-plane's far
        temperature less the cylinder's incoming one, in units of the temperature
        that the frictional heat per unit length makes in the half-plane.
    sink_distance : float or None
        ``L/l > 0`` (beyond the contact, ``> 1``, where a user gives it): the stationary half-plane's sink distance in the system's length
        unit (the half-width ``Delta`` for the single patch), at which its
        temperature is ``T2`` (D38); None for a half-plane moving through the
        contact, whose incoming temperature is ``T2``.
    """

    theta: float
    sink_distance: float | None = None

    def __post_init__(self):
        # Any finite value: a group derived from physical inputs (a slow, light contact
        # with a sink) may exceed what a user is allowed to give (check_theta).
        object.__setattr__(self, "theta", check_finite("theta", self.theta))
        if self.sink_distance is not None:
            # Any length for the formula; a user's sink beyond the contact is checked
            # where it is given (check_sink_distance).
            object.__setattr__(self, "sink_distance",
                               check_positive("sink_distance", self.sink_distance))

    @property
    def log_sink(self) -> float:
        """``ln(L/l)`` of a stationary half-plane's sink (0 for a moving one)."""
        return 0.0 if self.sink_distance is None else math.log(self.sink_distance)

    def in_unit(self, scale: float) -> Temperatures:
        """The same closure with lengths in units of ``scale`` times today's unit."""
        if self.sink_distance is None:
            return self
        return Temperatures(self.theta, self.sink_distance / scale)


def check_sink_distance(value, name="sink_distance") -> float:
    """A sink distance ``L/Delta`` given for a contact of half-width ``Delta``: in
    :data:`SINK_RANGE`, beyond the contact (the law holds for a flux inside the
    semicircle of radius ``L``, D38)."""
    return check_range(name, value, *SINK_RANGE, open_low=True)


def temperature_closure(theta, sink_distance) -> Temperatures | None:
    """The far temperatures given as ``theta`` and ``sink_distance`` (``L`` over the
    problem's unit of length), each checked as an input; None without ``theta``."""
    if theta is None:
        if sink_distance is not None:
            raise InputError("sink_distance is given with theta only (the temperature "
                             "closure)", parameters=("sink_distance", "theta"))
        return None
    return Temperatures(check_theta(theta), None if sink_distance is None
                        else check_sink_distance(sink_distance))


def temperature_group(T1, T2, K2, friction, sliding_speed, load) -> float:
    """``Theta = pi K2 (T2 - T1)/(f v P)`` (D39), from SI inputs.

    Parameters
    ----------
    T1, T2 : float
        The cylinder's incoming and the half-plane's far (incoming or sink)
        temperature, K.
    K2 : float
        The half-plane's conductivity, W/(m K).
    friction, sliding_speed, load : float
        ``f``, ``|v1 - v2|`` (m/s) and the load per unit length ``P`` (N/m), all > 0.
    """
    return math.pi * K2 * (T2 - T1) / (friction * sliding_speed * load)


def layer_sink_distance(thickness: float) -> float:
    """The sink distance ``L = 4 h/pi`` of a layer of thickness ``h`` on an isothermal
    base (D40): its line source's surface temperature ``(Q/(pi K)) ln coth(pi |x|/(4h))``
    is the sink law's ``(Q/(pi K)) ln(L/|x|)`` to ``O((x/h)^2)``."""
    return 4.0 * thickness / math.pi


# The closure as a value: what fixes the heat partition of a contact, one type for every
# call (``closure=``).  The dimensionless calls take HeatPartition, Offset or
# FarTemperatures; the physical calls HeatPartition or BulkTemperatures.


@dataclass(frozen=True)
class HeatPartition:
    """The heat partition given: ``lam = (Q1 - Q2)/(Q1 + Q2)`` (derivation section 6).

    ``lam`` in [-1, 1] when both bodies take a share of the frictional heat; beyond it
    (to 1e6) one body gives heat through the contact, as a hot body does (the bulk
    temperatures then make ``abs(lam) > 1``).
    """

    lam: float

    def __post_init__(self):
        object.__setattr__(self, "lam", check_closure_range(lam=self.lam)[0])

    def keywords(self) -> dict:
        """The closure as the solvers' keywords."""
        return {"lam": self.lam}


@dataclass(frozen=True)
class Offset:
    """The contact's offset given, ``sigma/Delta`` (its centre from the cylinder's
    initial point of contact, in half-widths, positive toward the leading edge);
    ``lam`` is then an output (the paper's closure, derivation section 6)."""

    sigma_over_delta: float

    def __post_init__(self):
        object.__setattr__(self, "sigma_over_delta",
                           check_closure_range(sigma_over_delta=self.sigma_over_delta)[1])

    def keywords(self) -> dict:
        """The closure as the solvers' keywords."""
        return {"sigma_over_delta": self.sigma_over_delta}


@dataclass(frozen=True)
class FarTemperatures:
    """The far temperatures in dimensionless form (derivation section 17, (D39)):
    ``lam`` an output.

    Attributes
    ----------
    theta : float or None
        ``Theta = pi K2 (T2 - T1)/(f |v1 - v2| P)``, ``|Theta| <= 1e6``; None where a
        path or a map follows it (``along="theta"``, an axis ``theta``).
    sink_distance_over_delta : float or None
        A stationary half-plane's sink distance ``L`` in half-widths (> 1: beyond the
        contact; Hertz's half-width ``l`` for a contact set or a transient run); None
        for a half-plane moving through the contact.
    """

    theta: float | None
    sink_distance_over_delta: float | None = None

    def __post_init__(self):
        if self.theta is not None:
            object.__setattr__(self, "theta", check_theta(self.theta))
        if self.sink_distance_over_delta is not None:
            object.__setattr__(self, "sink_distance_over_delta",
                               check_sink_distance(self.sink_distance_over_delta,
                                                   "sink_distance_over_delta"))

    def keywords(self) -> dict:
        """The closure as the solvers' keywords (``sink_distance`` in the problem's
        unit of length)."""
        return {k: v for k, v in (("theta", self.theta),
                                  ("sink_distance", self.sink_distance_over_delta))
                if v is not None}


@dataclass(frozen=True)
class BulkTemperatures:
    """The bodies' temperatures far from the contact, in physical units (derivation
    section 17): ``lam`` an output.

    Parameters
    ----------
    T1, T2 : float or str
        The cylinder's incoming temperature and the half-plane's far one (its incoming
        temperature when it moves, its sink's when stationary): K, or a string with
        units (``"150C"``, ``"300K"``, ``"100F"``).
    sink_distance : float or str, optional
        A stationary half-plane's distance from the contact at which it is at its
        temperature, m (``"30mm"``).
    layer_thickness : float or str, optional
        Or the thickness of a layer on a sink at that temperature, m (``L = 4h/pi``,
        (D40)).
    """

    T1: float
    T2: float
    sink_distance: float | None = None
    layer_thickness: float | None = None

    def __post_init__(self):
        from .units import parse_quantity, parse_temperature

        for name in ("T1", "T2"):
            object.__setattr__(self, name, parse_temperature(getattr(self, name), name))
        given = [k for k in ("sink_distance", "layer_thickness") if getattr(self, k) is not None]
        if len(given) > 1:
            raise InputError("give at most one of sink_distance and layer_thickness",
                             parameters=tuple(given))
        for name in given:
            object.__setattr__(self, name, check_positive(
                name, parse_quantity(getattr(self, name), "m", name)))

    @property
    def temperatures(self) -> tuple:
        """``(T1, T2)``, K."""
        return (self.T1, self.T2)

    def keywords(self) -> dict:
        """The closure as the physical problem's keywords."""
        return {k: v for k, v in (("bulk_temperatures", self.temperatures),
                                  ("sink_distance", self.sink_distance),
                                  ("layer_thickness", self.layer_thickness))
                if v is not None}



#: The closures of the calls in dimensionless and in physical units.
DIMENSIONLESS_CLOSURES = (HeatPartition, Offset, FarTemperatures)
PHYSICAL_CLOSURES = (HeatPartition, BulkTemperatures)


def closure_of(closure=None, *, kinds=DIMENSIONLESS_CLOSURES, required=True, **spelled):
    """The closure of a call: ``closure``, or the one keyword spelling given.

    Parameters
    ----------
    closure : HeatPartition, Offset, FarTemperatures or BulkTemperatures, optional
        The closure as a value.
    kinds : tuple of type
        The kinds this call accepts.
    required : bool
        Whether a closure must be given (False: a path or map that follows one).
    **spelled
        The call's closure keywords: ``lam``, ``sigma_over_delta`` (each the same as
        its closure type), and the keyword spellings that the closure types replace,
        already turned into a closure by the caller (:func:`deprecated_closure`);
        None where not given.

    Returns
    -------
    closure or None

    Raises
    ------
    InputError
        More than one closure given, none where one is required, or one of another
        kind than the call takes.
    """
    given = [] if closure is None else [("closure", closure)]
    for name, value in spelled.items():
        if value is None:
            continue
        if name == "lam" and not isinstance(value, HeatPartition):
            value = HeatPartition(value)
        elif name == "sigma_over_delta" and not isinstance(value, Offset):
            value = Offset(value)
        given.append((name, value))
    names = [name for name, _ in given]
    accepted = " or ".join(k.__name__ for k in kinds)
    template = [value for _, value in given
                if isinstance(value, FarTemperatures) and value.theta is None]
    if template and (len(given) > 1 or required):
        # The far temperatures' sink without their group: for a path or map that
        # follows theta only.
        raise InputError("sink_distance_over_delta is given with theta only: "
                         "FarTemperatures(theta, sink_distance_over_delta)",
                         parameters=("sink_distance_over_delta", "theta"))
    if len(given) > 1:
        raise InputError(f"give exactly one closure, got {' and '.join(names)} ({accepted})",
                         parameters=tuple(names))
    if not given:
        if required:
            raise InputError(f"closure must be given: {accepted} (or lam="
                             + (", sigma_over_delta=" if Offset in kinds else "") + ")",
                             parameters=("closure", "lam"))
        return None
    name, value = given[0]
    if not isinstance(value, kinds):
        raise InputError(f"{name} must be {accepted}, got {value!r}", parameters=(name,))
    return value


def far_temperatures(temperatures) -> FarTemperatures:
    """The closure of the solvers' ``Temperatures`` (or ``(theta, L/Delta)``) as given to
    ``Model.solve`` before version 1.0."""
    if isinstance(temperatures, Temperatures):
        return FarTemperatures(temperatures.theta, temperatures.sink_distance)
    try:
        theta, sink = temperatures
    except (TypeError, ValueError):
        raise InputError(f"temperatures must be Temperatures or (theta, L/Delta), got "
                         f"{temperatures!r}", parameters=("temperatures",)) from None
    return FarTemperatures(theta, sink)


def spelled_closure(kwargs: dict, physical: bool):
    """The closure that the keyword spellings of versions before 1.0 give, taken out of
    ``kwargs``: ``theta`` with ``sink_distance`` as ``L/Delta`` (``physical`` False), or
    ``bulk_temperatures`` (``"150C,40C"`` or a pair) with ``sink_distance`` or
    ``layer_thickness`` in metres (``physical``).

    Returns
    -------
    closure, names
        The closure (None where none of them was given) and the names found, for the
        caller's DeprecationWarning.
    """
    old = {k: kwargs.pop(k) for k in ("theta", "bulk_temperatures", "sink_distance",
                                      "layer_thickness") if kwargs.get(k) is not None}
    for k in ("theta", "bulk_temperatures", "sink_distance", "layer_thickness"):
        kwargs.pop(k, None)
    if not old:
        return None, []
    if not physical:
        for name in ("bulk_temperatures", "layer_thickness"):
            if name in old:
                raise InputError(f"{name} belongs to a problem in physical units: give "
                                 f"cylinder and half_plane too", parameters=(name,))
        return FarTemperatures(old.get("theta"), old.get("sink_distance")), list(old)
    if "theta" in old:
        raise InputError("theta closes a problem in dimensionless form: here give "
                         "closure=BulkTemperatures(T1, T2, ...)", parameters=("theta",))
    value = old.get("bulk_temperatures")
    if value is None:
        raise InputError(f"{' and '.join(old)} belong to the bulk temperatures: give "
                         f"closure=BulkTemperatures(T1, T2, ...)", parameters=tuple(old))
    parts = value.split(",") if isinstance(value, str) else value
    try:
        t1, t2 = parts
    except (TypeError, ValueError):
        raise InputError(f"bulk_temperatures must be two temperatures, the cylinder's and "
                         f"the half-plane's ('150C,40C'), got {value!r}",
                         parameters=("bulk_temperatures",)) from None
    return (BulkTemperatures(t1, t2, old.get("sink_distance"), old.get("layer_thickness")),
            list(old))
