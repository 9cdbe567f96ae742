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

from .validation import InputError, check_finite, check_positive, check_range

__all__ = ["SINK_RANGE", "THETA_MAX", "Temperatures", "check_theta", "check_sink_distance",
           "layer_sink_distance", "temperature_closure", "temperature_group"]

#: Sink distances ``L/Delta`` solved: beyond the contact (the law holds for a flux
#: inside the semicircle of radius ``L``) up to where ``ln(L/Delta)`` is still far
#: from swamping the rows' other terms.
SINK_RANGE = (1.0, 1e12)


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
