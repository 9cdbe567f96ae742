"""An interface conductance ``h = h0 (p/p_ref)^m`` between the bodies (derivation
section 15): in dimensionless form (a Biot number) and in SI units."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .errors import InputError
from .validation import check_pair, check_range

__all__ = ["BIOT_RANGE", "Conductance", "PhysicalConductance"]


#: The Biot numbers ``h l/K2`` of an interface conductance that are solved: from
#: nearly insulating to perfect contact to rounding (section 15).
BIOT_RANGE = (1e-12, 1e15)


@dataclass(frozen=True)
class Conductance:
    """An interface conductance ``h = h0 (p / p_ref)^m`` (derivation sections 15, 16).

    Attributes
    ----------
    biot0 : float
        ``h0 l / K2 > 0``: the Biot number of the conductance at the reference
        pressure ``p_ref = P/(2 l)``, ``l`` the length unit (the Hertz half-width of
        the load for a contact set, the contact's half-width ``Delta`` for the single
        patch, section 16).
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

    @classmethod
    def of(cls, value):
        """``value`` (None, a Conductance or ``(Bi0, m)``) as a Conductance or None."""
        if value is None or isinstance(value, cls):
            return value
        return cls(*check_pair("conductance", value, "(Bi0, m), two numbers"))

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


@dataclass(frozen=True)
class PhysicalConductance:
    """An interface conductance ``h = h0 (p/p_ref)^m`` in SI units (section 15).

    Attributes
    ----------
    h0 : float
        W/(m^2 K) at ``p_ref``, > 0.
    exponent : float
        ``m`` in [0, 10].
    p_ref : float or None
        Pa; None: the mean Hertz pressure ``P/(2 l)`` of each load (a law that then
        changes with the load, so that a map, whose loads differ, needs a ``p_ref``
        unless ``m = 0``).
    """

    h0: float
    exponent: float = 0.0
    p_ref: float | None = None

    def __post_init__(self):
        object.__setattr__(self, "h0", check_range("conductance h0", self.h0, 0.0, 1e300,
                                                   open_low=True))
        object.__setattr__(self, "exponent", check_range("conductance m", self.exponent,
                                                         0.0, 10.0))
        if self.p_ref is not None:
            object.__setattr__(self, "p_ref", check_range(
                "conductance p_ref", self.p_ref, 0.0, 1e300, open_low=True))

    def biot(self, problem) -> tuple[float, float]:
        """``(Bi0, m)`` of :class:`Conductance` for
        ``problem``: ``Bi0 = h(P/(2 l)) l/K2``."""
        ell = problem.hertz_half_width
        with np.errstate(over="ignore", under="ignore"):
            factor = ell / problem.half_plane.K  # Bi0 / h0
            if self.p_ref is not None and self.exponent:
                factor *= (problem.load / (2.0 * ell) / self.p_ref) ** self.exponent
            bi = self.h0 * factor
        lo, hi = BIOT_RANGE
        if not (np.isfinite(factor) and factor > 0.0):
            raise InputError(f"conductance p_ref = {self.p_ref:g} Pa makes h at the mean "
                             f"Hertz pressure {'infinite' if factor > 0 else 'zero'}: "
                             f"give a p_ref near the contact pressures")
        if not lo <= bi <= hi:
            raise InputError(f"conductance h0 = {self.h0:g} W/(m^2 K) gives a Biot number "
                             f"h l/K2 = {bi:.3g} at load {problem.load:g} N/m, outside "
                             f"[{lo:g}, {hi:g}]: h0 must be in [{lo / factor:.3g}, "
                             f"{hi / factor:.3g}] W/(m^2 K) here" + (
                                 f" with p_ref = {self.p_ref:g} Pa, m = {self.exponent:g}"
                                 if self.p_ref is not None and self.exponent else ""))
        return bi, self.exponent
