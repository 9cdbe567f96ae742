"""Thermoelastic instability of sliding half-planes: critical speed, modes, the most
unstable wavelength (``thermocontact tei``).

The dispersion relation and its root search are :mod:`thermocontact.physics.tei`;
the derivation is the section "Thermoelastic instability of sliding half-planes" of
``docs/derivation.md`` (H1-H12).  For two half-planes the wavelength enters only
through the Péclet number ``V/(kappa m)``, so the critical speed is proportional to
the wavenumber (H11): longer waves go unstable first, and at a given speed the growth
rate has a maximum over the wavelength.

Examples
--------
>>> from thermocontact.problem.materials import get_material
>>> from thermocontact.studies.tei import analyse
>>> r = analyse(get_material("steel"), get_material("organic-composite-brake-block"), 0.4, 0.05)
>>> round(r.critical_speed, 4), r.stable_at_all_speeds
(55.3725, False)
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np
from scipy.optimize import brentq, minimize_scalar

from ..io.results import Result
from ..physics.tei import SlidingPair, high_speed_unstable, modes, speed_lower_bound
from ..problem.validation import check_range, check_zero_or_range

__all__ = ["FRICTION_RANGE", "SPEED_RANGE", "TEIMode", "TEIResult", "WAVELENGTH_RANGE",
           "analyse", "critical_speed", "critical_speeds", "growth_rate",
           "most_unstable_wavelength", "tei_modes"]

#: Speeds scanned per factor 2 above the lower bound (H9) before Brent's method.
_PER_OCTAVE = 4
#: Without a crossing up to this multiple of the lower bound, the high-speed limit
#: (H10) decides; where it says unstable, the scan goes on to ``_LAST_FACTOR``.
_SCAN_FACTOR = 1e6
_LAST_FACTOR = 1e15
#: Wavelengths studied, m: a nanometre to a kilometre (beyond, the dimensionless
#: groups of the dispersion relation overflow or underflow).
WAVELENGTH_RANGE = (1e-9, 1e3)
#: Sliding speeds studied besides 0, m/s: below, the growth rates underflow and the
#: most unstable wavelength is not resolved; above, no machine slides.
SPEED_RANGE = (1e-9, 1e4)
#: Coefficients of friction besides 0 (no frictional heat): below, the critical speed
#: overflows; above, no pair of materials slides.
FRICTION_RANGE = (1e-6, 10.0)



@dataclass(frozen=True, eq=False, repr=False)
class TEIMode(Result):
    """One mode ``exp(b t + i m x)`` of the sliding half-planes.

    Attributes
    ----------
    growth_rate : float
        ``Re b``, 1/s; positive for a growing mode.
    frequency : float
        Rate at which the pattern's crests pass a fixed point of the counterface,
        ``migration_speed / wavelength``, Hz, signed as ``migration_speed``.
    migration_speed : float
        The pattern's speed relative to the counterface, m/s, positive in the
        direction the slider moves (``V`` for a pattern fixed on the slider).
    """

    growth_rate: float
    frequency: float
    migration_speed: float


def _mode(b: complex, wavenumber: float) -> TEIMode:
    # The slider moves toward +x in the frame of the dispersion relation (U = +V).
    speed = -b.imag / wavenumber
    return TEIMode(float(b.real), float(speed * wavenumber / (2.0 * math.pi)), float(speed))


@dataclass(frozen=True, eq=False, repr=False)
class TEIResult(Result):
    """The thermoelastic stability of two sliding half-planes at one wavelength.

    Attributes
    ----------
    slider, counterface : str
        The materials' names.
    friction : float
    wavelength : float
        ``L = 2 pi / m``, m.
    dundurs : bool
        Whether the Dundurs term ``beta f`` was kept.
    beta : float
        ``beta`` of the pair, slider as body 1 (0 when dropped).
    critical_speed : float or None
        The lowest sliding speed at which a mode of this wavelength grows, m/s;
        None when none does at any speed.
    stable_at_all_speeds : bool
    migration_speed : float or None
        The neutral mode's speed relative to the counterface at the critical
        speed, m/s, positive in the slider's direction.
    speed : float or None
        The sliding speed of ``modes``, m/s, if one was given.
    modes : tuple of TEIMode
        At ``speed``: every mode of this wavelength, the fastest growing first.
    most_unstable_wavelength : float or None
        At ``speed``: the wavelength of largest growth rate, m (None if every
        wavelength is stable at every speed, or without friction or speed).
    most_unstable_growth_rate : float or None
        Its growth rate, 1/s.
    pair : SlidingPair
        The problem itself (materials, friction, Dundurs term), for further studies
        such as the critical speed at other wavelengths.
    """

    slider: str
    counterface: str
    friction: float
    wavelength: float
    dundurs: bool
    beta: float
    critical_speed: float | None
    stable_at_all_speeds: bool
    migration_speed: float | None
    speed: float | None = None
    modes: tuple = field(default=())
    most_unstable_wavelength: float | None = None
    most_unstable_growth_rate: float | None = None
    pair: SlidingPair | None = field(default=None, repr=False)

    def _summary(self) -> str:
        vc = ("stable_at_all_speeds=True" if self.critical_speed is None
              else f"critical_speed={self.critical_speed:.6g}")
        at = "" if self.speed is None else f", speed={self.speed:.6g}, modes={len(self.modes)}"
        return (f"{self.slider} on {self.counterface}, friction={self.friction:g}, "
                f"wavelength={self.wavelength:.6g}, {vc}{at}")

    def _record(self) -> dict:
        """The JSON record of ``thermocontact tei``: the inputs, the critical speed and,
        with a speed, the modes and the most unstable wavelength."""
        out = {"slider": self.slider, "counterface": self.counterface,
               "friction": self.friction, "wavelength": self.wavelength,
               "dundurs": self.dundurs, "beta": self.beta,
               "critical_speed": self.critical_speed,
               "stable_at_all_speeds": self.stable_at_all_speeds,
               "migration_speed": self.migration_speed}
        if self.speed is not None:
            out.update(speed=self.speed, modes=list(self.modes),
                       most_unstable_wavelength=self.most_unstable_wavelength,
                       most_unstable_growth_rate=self.most_unstable_growth_rate)
        return out


def growth_rate(pair: SlidingPair, wavenumber: float, speed: float) -> float:
    """The largest ``Re b`` of the modes, 1/s; ``-inf`` where there is no mode (every
    disturbance then decays with the continuous spectrum, ``Re b <= -kappa m^2``)."""
    b = modes(pair, wavenumber, speed)
    return float(b[0].real) if b.size else -math.inf


def critical_speed(pair: SlidingPair, wavenumber: float):
    """The lowest speed at which a mode of wavenumber ``m`` grows, and that mode.

    No mode grows below the bound (H9); the speeds above it are scanned
    geometrically until the largest growth rate changes sign, which Brent's method
    then locates to 1e-13 relative.  Without a sign change up to 1e6 times the
    bound, the high-speed limit (H10) decides between a later crossing and
    stability at every speed.

    Returns
    -------
    (float, TEIMode) or (None, None)
        The critical speed, m/s, and the neutral mode there.
    """
    low = speed_lower_bound(pair, wavenumber)
    if not math.isfinite(low):
        return None, None
    floor = -max(pair.slider.k, pair.counterface.k) * wavenumber**2  # no mode: decays

    def sigma(v):
        s = growth_rate(pair, wavenumber, v)
        return s if math.isfinite(s) else floor

    ratio = 2.0 ** (1.0 / _PER_OCTAVE)
    v_prev, v = 0.5 * low, 0.5 * low  # sigma < 0 below the bound
    last = _SCAN_FACTOR
    while True:
        v *= ratio
        if sigma(v) > 0.0:
            break
        v_prev = v
        if v > last * low:
            if last == _LAST_FACTOR or not high_speed_unstable(pair):
                return None, None
            last = _LAST_FACTOR
    vc = brentq(sigma, v_prev, v, xtol=1e-300, rtol=1e-13, maxiter=200)
    b = modes(pair, wavenumber, vc)
    return float(vc), _mode(b[0], wavenumber)


def critical_speeds(pair: SlidingPair, wavelengths) -> np.ndarray:
    """Critical speed at each wavelength, m/s (``nan`` where stable at all speeds).

    The wavelength enters the dispersion relation only through ``V/(kappa m)``
    (H11), so one critical speed gives them all: ``V_c(L) = V_c(L0) L0/L``.
    """
    wl = np.atleast_1d(np.asarray(wavelengths, dtype=float))
    wl0 = float(np.exp(np.mean(np.log(wl))))
    vc, _ = critical_speed(pair, 2.0 * math.pi / wl0)
    return np.full(wl.shape, math.nan) if vc is None else vc * wl0 / wl


def tei_modes(pair: SlidingPair, wavenumber: float, speed: float) -> tuple:
    """Every mode at ``speed``, fastest growing first, as :class:`TEIMode`."""
    return tuple(_mode(b, wavenumber) for b in modes(pair, wavenumber, speed))


def most_unstable_wavelength(pair: SlidingPair, speed: float, wavenumber: float,
                             critical=None):
    """The wavelength of largest growth rate at ``speed``, and that rate.

    The critical speed is ``P_c kappa m`` (H11), so every wavenumber above
    ``m_c = speed/(P_c kappa)`` is stable; the growth rate vanishes as ``m -> 0``
    too (it is ``O(V m)``, H10).  The maximum is bracketed on 60 wavenumbers
    spaced in ``ln m`` over five decades below ``m_c`` and refined by Brent's method.

    ``critical``, the critical speed at ``wavenumber`` if known (m/s), saves its
    search.

    Returns
    -------
    (float, float) or (None, None)
        Wavelength, m, and growth rate, 1/s.
    """
    if speed <= 0.0:
        return None, None
    vc = critical if critical is not None else critical_speed(pair, wavenumber)[0]
    if vc is None:
        return None, None
    m_c = wavenumber * speed / vc
    logs = np.linspace(math.log(m_c) - 5.0 * math.log(10.0), math.log(m_c), 61)[:-1]
    rates = np.array([growth_rate(pair, math.exp(x), speed) for x in logs])
    i = int(np.argmax(rates))
    if i == 0:  # still growing toward long waves: not bracketed (not expected, H10)
        return 2.0 * math.pi / math.exp(logs[0]), float(rates[0])
    hi = logs[i + 1] if i + 1 < logs.size else math.log(m_c)
    res = minimize_scalar(lambda x: -growth_rate(pair, math.exp(x), speed),
                          bracket=(logs[i - 1], logs[i], hi), tol=1e-10)
    return 2.0 * math.pi / math.exp(res.x), float(-res.fun)


def analyse(slider, counterface, friction, wavelength, speed=None, dundurs=True) -> TEIResult:
    """The critical speed at one wavelength and, at a speed, the modes and the most
    unstable wavelength: the study behind :func:`thermocontact.tei`.

    Parameters
    ----------
    slider, counterface : Material
        As for :class:`~thermocontact.physics.tei.SlidingPair`.
    friction : float
        ``f``: 0 or in :data:`FRICTION_RANGE`.
    wavelength : float
        ``L`` in :data:`WAVELENGTH_RANGE`, m.
    speed : float, optional
        Sliding speed ``V``: 0 or in :data:`SPEED_RANGE`, m/s.
    dundurs : bool, optional
        Keep the Dundurs term (default).

    Returns
    -------
    TEIResult
    """
    friction = check_zero_or_range("friction", friction, *FRICTION_RANGE)
    wl = check_range("wavelength", wavelength, *WAVELENGTH_RANGE)
    pair = SlidingPair(slider, counterface, friction, dundurs=dundurs)
    m = 2.0 * math.pi / wl
    vc, neutral = critical_speed(pair, m)
    extra = {}
    if speed is not None:
        v = check_zero_or_range("speed", speed, *SPEED_RANGE)
        mw, rate = (None, None) if vc is None else most_unstable_wavelength(pair, v, m, vc)
        extra = dict(speed=v, modes=tei_modes(pair, m, v) if v > 0.0 else (),
                     most_unstable_wavelength=mw, most_unstable_growth_rate=rate)
    return TEIResult(pair.slider.name, pair.counterface.name, pair.friction, wl, pair.dundurs,
                     pair.beta, vc, vc is None,
                     None if neutral is None else neutral.migration_speed, **extra, pair=pair)
