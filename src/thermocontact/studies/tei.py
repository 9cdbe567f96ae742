"""Thermoelastic instability of sliding bodies: critical speed, modes, the most
unstable wavelength (``thermocontact tei``), for two half-planes and for every layup of
layers (brake discs, pads, clutch packs; :mod:`thermocontact.studies.tei_layers`),
each family's minimum over the wavelength and the hot-spot table.

The half-planes' dispersion relation and its root search are
:mod:`thermocontact.physics.tei`; the derivation is the section "Thermoelastic
instability of sliding half-planes" of ``docs/derivation.md`` (H1-H12), and for layers
"Thermoelastic instability of layers" (L1-L14).  For two half-planes the wavelength enters only
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
from ..physics.tei_layers import BACKINGS
from ..physics.tei import (FRICTION_RANGE, SPEED_RANGE, WAVELENGTH_RANGE, SlidingPair,
                           high_speed_limit, high_speed_roots, modes, speed_lower_bound)
from ..problem.validation import check_range, check_zero_or_range

__all__ = ["BACKINGS", "FRICTION_RANGE", "HalfPlanes", "HotSpot", "SPEED_RANGE", "TEIFamily", "TEIMode",
           "TEIResult", "WAVELENGTH_RANGE", "analyse", "critical_speed", "critical_speeds",
           "check_geometry", "family_minimum", "growth_rate", "hot_spot_table", "most_unstable_wavelength",
           "stable_at_all_speeds", "tei_modes"]

#: Speeds scanned per factor 2 above the lower bound (H9) before Brent's method.
_PER_OCTAVE = 4
#: Without a crossing up to this multiple of the lower bound, the high-speed limit
#: (H10) decides; where it says unstable, the scan goes on to ``_LAST_FACTOR``.
_SCAN_FACTOR = 1e6
_LAST_FACTOR = 1e15


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
    family : str
        The family of modes it belongs to ("all" where the layup has no symmetry
        to split them; docs/tei.md).
    """

    growth_rate: float
    frequency: float
    migration_speed: float
    family: str = "all"


def _mode(b: complex, wavenumber: float, family: str = "all") -> TEIMode:
    # The slider moves toward +x in the frame of the dispersion relation (U = +V).
    speed = -b.imag / wavenumber
    return TEIMode(float(b.real), float(speed * wavenumber / (2.0 * math.pi)), float(speed),
                   family)


@dataclass(frozen=True, eq=False, repr=False)
class TEIFamily(Result):
    """One family of modes: its critical speed at the wavelength asked for and its
    minimum over the wavelength.

    Attributes
    ----------
    family : str
        "antisymmetric" or "symmetric" about a disc's mid-plane, a clutch pack's
        families (:data:`~thermocontact.physics.tei_layers.CLUTCH_FAMILIES`), or
        "all".
    critical_speed : float or None
        m/s, at the result's wavelength; None where no mode of the family grows
        below :data:`SPEED_RANGE`'s end (or, for half-planes, at any speed).
    migration_speed : float or None
        The neutral mode's speed relative to the counterface, m/s, positive in the
        slider's direction.
    minimum_critical_speed : float or None
        The lowest critical speed over the wavelengths of ``wavelength_range``, m/s
        (None for two half-planes, whose critical speed falls as ``1/L`` without
        end).
    minimum_wavelength : float or None
        The wavelength where it occurs, m.
    minimum_at_range_end : bool or None
        True where the least critical speed found lies at an end of
        ``wavelength_range``: the minimum is then not interior, and may lie beyond
        the range (None without a minimum).
    crossings : tuple of dict
        Layers: every neutral crossing of the family at the result's wavelength up to
        :data:`CROSSINGS_BEYOND` times its critical speed, by speed (``speed``, m/s;
        ``migration_speed``, m/s; ``direction``, +1 where a mode starts to grow with
        the speed, -1 where it stops): the critical speed is the first +1, and a
        window of growth that closes again shows as a +1 followed by a -1
        (docs/tei.md).
    certified : bool or None
        Layers: the speed scan's check (L15): at each of its speeds the growing modes
        counted by the argument principle are those followed.  None for half-planes
        (their modes are all found by a polynomial root search).
    """

    family: str
    critical_speed: float | None
    migration_speed: float | None
    minimum_critical_speed: float | None = None
    minimum_wavelength: float | None = None
    minimum_at_range_end: bool | None = None
    crossings: tuple = field(default=())
    certified: bool | None = None


@dataclass(frozen=True, eq=False, repr=False)
class HotSpot(Result):
    """The critical speed of ``n`` hot spots round a disc (wavelength ``2 pi R/n``), m/s,
    and the family that goes unstable first."""

    n: int
    wavelength: float
    critical_speed: float | None
    family: str | None


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
        wavelength is stable at every speed, or without friction or speed, or for
        layers without a ``wavelength_range``).
    most_unstable_growth_rate : float or None
        Its growth rate, 1/s.
    plane : str
        "strain" or "stress".
    slider_thickness, counterface_thickness, separator_thickness : float or None
        The disc's full thickness, the pads' (or facings') thickness and the
        separator plates' thickness, m; None for half-planes.
    faces : int
        Faces of the disc that rub: 2 (between identical pads) or 1.
    backing : str or None
        The pad layers' backing plate.
    separator : str or None
        The separator plates' material (a clutch pack).
    families : tuple of TEIFamily
        Every family of modes; ``critical_speed`` above is the lowest of theirs.
    wavelength_range : tuple of float or None
        The wavelengths over which the families' minima were sought, m: from the
        thinnest layer to 200 times the thickest (or 2 pi R), within
        :data:`WAVELENGTH_RANGE`; None for half-planes, and for layers thicker than
        its longest wavelength divided by 200 (no minimum is then sought).
    disc_radius : float or None
        ``R``, m, of ``hot_spots``.
    hot_spots : tuple of HotSpot
        ``n = N1 ... N2`` round the disc.
    governing_hot_spots : int or None
        The ``n`` of lowest critical speed.
    stop : BrakeStop or None
        The amplification of each hot-spot number over a stop.
    pair : SlidingPair
        The problem itself (materials, friction, Dundurs term), for further studies
        such as the critical speed at other wavelengths.
    systems : tuple
        The families as studied (:class:`HalfPlanes` or
        :class:`~thermocontact.studies.tei_layers.Layered`), for pictures and
        further studies.
    half_planes : HalfPlanes or None
        For layers: two half-planes of the same materials, the reference line of
        the pictures.
    """

    slider: str
    counterface: str
    friction: float
    wavelength: float
    dundurs: bool
    beta: float
    critical_speed: float | None
    stable_at_all_speeds: bool | None
    migration_speed: float | None
    speed: float | None = None
    modes: tuple = field(default=())
    most_unstable_wavelength: float | None = None
    most_unstable_growth_rate: float | None = None
    plane: str = "strain"
    slider_thickness: float | None = None
    faces: int = 2
    counterface_thickness: float | None = None
    backing: str | None = None
    separator: str | None = None
    separator_thickness: float | None = None
    families: tuple = field(default=())
    wavelength_range: tuple | None = None
    disc_radius: float | None = None
    hot_spots: tuple = field(default=())
    governing_hot_spots: int | None = None
    stop: object = None
    pair: SlidingPair | None = field(default=None, repr=False)
    systems: tuple = field(default=(), repr=False)
    half_planes: object = field(default=None, repr=False)

    STATUSES = {"solved": "a mode of this wavelength grows above the critical speed found",
                "stable at all speeds": "no mode of this wavelength grows at any speed "
                                        "(proven from the high-speed limit, H10)",
                "no critical speed found": "no mode grows at the speeds searched; beyond "
                                           "them stability is not proven (message says "
                                           "how far)"}
    SUCCESS = frozenset({"solved", "stable at all speeds"})
    UNITS = {"wavelength": "m", "critical_speed": "m/s", "migration_speed": "m/s",
             "speed": "m/s", "growth_rate": "1/s", "frequency": "Hz",
             "most_unstable_wavelength": "m", "most_unstable_growth_rate": "1/s",
             "minimum_critical_speed": "m/s", "minimum_wavelength": "m",
             "wavelength_range": "m", "slider_thickness": "m", "counterface_thickness": "m",
             "separator_thickness": "m", "disc_radius": "m", "log_amplification": "1",
             "threshold": "1"}

    @property
    def status(self) -> str:
        """One of :attr:`STATUSES`."""
        if self.critical_speed is not None:
            return "solved"
        return "stable at all speeds" if self.stable_at_all_speeds else "no critical speed found"

    @property
    def message(self) -> str:
        """How the search ended, in one line."""
        if self.critical_speed is not None:
            return (f"critical speed {self.critical_speed:.6g} m/s at wavelength "
                    f"{self.wavelength:.6g} m (the lowest of {max(1, len(self.families))} "
                    f"famil{'ies' if len(self.families) > 1 else 'y'})")
        if self.stable_at_all_speeds:
            return (f"no mode of wavelength {self.wavelength:.6g} m grows at any speed "
                    f"(the high-speed limit decides)")
        return (f"no mode of wavelength {self.wavelength:.6g} m grows below "
                f"{SPEED_RANGE[1]:g} m/s, the speeds searched")

    def _summary(self) -> str:
        vc = (f"stable_at_all_speeds={self.stable_at_all_speeds}" if self.critical_speed is None
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
               "migration_speed": self.migration_speed,
               "plane": self.plane, "slider_thickness": self.slider_thickness,
               "faces": self.faces, "counterface_thickness": self.counterface_thickness,
               "backing": self.backing, "separator": self.separator,
               "separator_thickness": self.separator_thickness,
               "families": list(self.families),
               "wavelength_range": (None if self.wavelength_range is None
                                    else list(self.wavelength_range))}
        if self.speed is not None:
            out.update(speed=self.speed, modes=list(self.modes),
                       most_unstable_wavelength=self.most_unstable_wavelength,
                       most_unstable_growth_rate=self.most_unstable_growth_rate)
        if self.disc_radius is not None:
            out.update(disc_radius=self.disc_radius, hot_spots=list(self.hot_spots),
                       governing_hot_spots=self.governing_hot_spots)
        if self.stop is not None:
            out.update(stop=self.stop)
        return out


def growth_rate(pair: SlidingPair, wavenumber: float, speed: float) -> float:
    """The largest ``Re b`` of the modes, 1/s; ``-inf`` where there is no mode (every
    disturbance then decays with the continuous spectrum, ``Re b <= -kappa m^2``)."""
    b = modes(pair, wavenumber, speed)
    return float(b[0].real) if b.size else -math.inf


def _asymptotic(pair: SlidingPair, wavenumber: float, speed: float) -> bool:
    """Whether the modes at ``speed`` are those of the high-speed limit (H10): every
    ``b/(V m)`` within 1e-3 of a root ``X`` of :func:`high_speed_roots`."""
    X = high_speed_roots(pair)
    b = modes(pair, wavenumber, speed) / (speed * wavenumber)
    return bool(X.size) and all(np.min(np.abs(X - x)) <= 1e-3 * max(1.0, abs(x)) for x in b)


def critical_speed(pair: SlidingPair, wavenumber: float):
    """The lowest speed at which a mode of wavenumber ``m`` grows, and that mode.

    No mode grows below the bound (H9); the speeds above it are scanned
    geometrically until the largest growth rate changes sign, which Brent's method
    then locates to 1e-13 relative.  Without a sign change up to 1e6 times the
    bound, the high-speed limit (H10) decides: where a mode grows there, the scan
    goes on (to 1e15 times the bound).

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
            if last == _LAST_FACTOR or high_speed_limit(pair) != "grows":
                return None, None
            last = _LAST_FACTOR
    vc = brentq(sigma, v_prev, v, xtol=1e-300, rtol=1e-13, maxiter=200)
    b = modes(pair, wavenumber, vc)
    return float(vc), _mode(b[0], wavenumber)


def stable_at_all_speeds(pair: SlidingPair, wavenumber: float):
    """For a wavelength with no critical speed up to the scan's end: True where that
    is proven, None where it is not claimed.

    Proven: no mode grows below the bound (H9); the scan finds none up to 1e6 (or
    1e15) times it; and beyond, either every root of the high-speed limit decays
    (H10), with the modes at the scan's end already those of the limit (each
    ``b/(V m)`` within 1e-3 of a root), or the bodies are of one material, whose
    threshold (H11b) is exact.  Otherwise (a limit neutral at leading order between
    dissimilar bodies, or a scan that has not reached the limit) no claim is made.
    """
    if pair.friction == 0.0 or not math.isfinite(speed_lower_bound(pair, wavenumber)):
        return True     # no frictional heat, or no body distorts: nothing can grow
    limit = high_speed_limit(pair)
    one = pair.slider.E == pair.counterface.E and pair.slider.nu == pair.counterface.nu and (
        pair.slider.alpha == pair.counterface.alpha and pair.slider.K == pair.counterface.K
        and pair.slider.k == pair.counterface.k)
    if limit == "neutral" and one:
        return True
    if limit != "decays":
        return None
    low = speed_lower_bound(pair, wavenumber)
    return True if any(_asymptotic(pair, wavenumber, f * low)
                       for f in (_SCAN_FACTOR, _LAST_FACTOR)) else None


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
                          bounds=(logs[i - 1], hi), method="bounded", options={"xatol": 1e-10})
    return 2.0 * math.pi / math.exp(res.x), float(-res.fun)


@dataclass(frozen=True)
class HalfPlanes:
    """Two sliding half-planes as a family of modes, with the interface of
    :class:`~thermocontact.studies.tei_layers.Layered`: every mode by the polynomial
    root search (H8), critical speeds by (H9-H11)."""

    name: str
    pair: SlidingPair

    def scale(self, m) -> float:
        return min(b.k for b in self.pair.bodies if b.K > 0.0) * m * m

    def modes(self, m, speed, count=None):
        b = modes(self.pair, m, speed)
        return b if count is None else b[:count]

    def dispersion(self, b, m, speed):
        from ..physics.tei import dispersion

        return dispersion(self.pair, b, m, speed)

    def critical(self, m):
        vc, mode = critical_speed(self.pair, m)
        return (None, None) if vc is None else (vc, -1j * mode.migration_speed * m)

    def curve(self, wavenumbers, anchor=None, progress=None):
        """Exact: only ``V/(kappa m)`` enters (H11), ``V_c`` and the neutral
        frequency in units of ``kappa m^2`` are fixed multiples (one critical speed at
        most: ``progress`` is not told)."""
        ms = np.asarray(wavenumbers, dtype=float)
        if anchor is not None:
            m0, vc, w = anchor
            return vc * ms / m0, w * (ms / m0) ** 2
        m0 = float(np.exp(np.mean(np.log(ms))))
        vc, b = self.critical(m0)
        if vc is None:
            return np.full(ms.shape, np.nan), np.full(ms.shape, np.nan)
        return vc * ms / m0, b.imag * (ms / m0) ** 2


def _systems(pair, layups_):
    from .tei_layers import Layered

    if not layups_:
        return (HalfPlanes("all", pair),)
    return tuple(Layered(name, lay) for name, lay in layups_.items())


def _wavelength_range(thicknesses, radius):
    """Where a layup's families' minima are sought, m: from the thinnest layer's
    thickness (shorter waves see half-planes, whose critical speed rises as 1/L) to
    the disc's circumference (one hot spot) or 200 times the thickest layer; None where
    that is empty within :data:`WAVELENGTH_RANGE`."""
    lo = min(thicknesses)
    hi = 2.0 * math.pi * radius if radius is not None else 200.0 * max(thicknesses)
    lo, hi = max(lo, WAVELENGTH_RANGE[0]), min(hi, WAVELENGTH_RANGE[1])
    # Layers thicker than the longest wavelength studied: no range (they are half-planes
    # at every wavelength of it).
    return (lo, hi) if lo < hi else None


#: Wavelengths of the curve on which each family's minimum is bracketed.
MINIMUM_POINTS = 40
#: A layered family's neutral crossings are recorded up to this multiple of its
#: critical speed (a window of growth below it shows as a pair).
CROSSINGS_BEYOND = 3.0


def family_minimum(system, wl_range, points=MINIMUM_POINTS, anchor=None, progress=None):
    """The lowest critical speed over ``wl_range`` and its wavelength, (m/s, m, at the
    end): the curve on ``points`` wavelengths (:meth:`curve`; for layers
    :func:`~thermocontact.studies.tei_layers.continue_neutral`, scans from the lowest
    speed continued between them), its least point refined by bounded minimisation in
    ``ln m`` between its neighbours (each point a neutral point continued from the
    least).  ``at the end`` is True where the least point is an end of the range (not
    refined: the minimum may lie beyond).  ``(None, None, None)`` where the family is
    stable throughout.  ``progress(done, total)``: the curve's (:meth:`curve`)."""
    from scipy.optimize import minimize_scalar

    from .tei_layers import continue_step

    ms = np.geomspace(2.0 * math.pi / wl_range[1], 2.0 * math.pi / wl_range[0], points)
    V, W = system.curve(ms, anchor, progress=progress)
    if not np.isfinite(V).any():
        return None, None, None
    i = int(np.nanargmin(V))
    if i in (0, points - 1):
        return float(V[i]), float(2.0 * math.pi / ms[i]), True
    if not (np.isfinite(V[i - 1]) and np.isfinite(V[i + 1])):
        return float(V[i]), float(2.0 * math.pi / ms[i]), False
    start = (float(ms[i]), (float(V[i]), float(W[i])))

    def vc(x):
        p = continue_step(system, start[0], start[1], math.exp(x))
        return math.inf if p is None else p[0]

    res = minimize_scalar(vc, bounds=(math.log(ms[i - 1]), math.log(ms[i + 1])),
                          method="bounded", options={"xatol": 1e-10})
    if not res.fun <= V[i]:
        return float(V[i]), float(2.0 * math.pi / ms[i]), False
    # The refinement may end on an end of the range (the least point its neighbour).
    end = min(abs(res.x - math.log(ms[0])), abs(res.x - math.log(ms[-1]))) < 1e-6
    return float(res.fun), float(2.0 * math.pi / math.exp(res.x)), bool(end)


def hot_spot_table(systems, radius, n1, n2, anchors=None, progress=None):
    """``HotSpot`` for ``n = n1 ... n2`` round a disc of radius ``radius``, and the
    governing ``n`` (lowest critical speed; None if none goes unstable).
    ``anchors``: a neutral point ``(m, V, omega)`` of each family, or None;
    ``progress(stage, done, total)``: the layered families' curves, their scans run
    together (:func:`~thermocontact.studies.tei_layers.neutral_curves`), as the stage
    "hot spots"; each other family's curve as its own stage."""
    from .tei_layers import Layered, neutral_curves

    ns = np.arange(n1, n2 + 1)
    ms = ns / radius                                  # m = 2 pi/(2 pi R/n)
    anchors = anchors or [None] * len(systems)
    # The layered families' curves together (their scans batched), the others' each.
    layered = [k for k, s in enumerate(systems) if isinstance(s, Layered)]
    curves = dict(zip(layered, neutral_curves([systems[k] for k in layered], ms,
                                              [anchors[k] for k in layered],
                                              progress=_stage(progress, "hot spots"))))
    speeds = np.array([curves[k][0] if k in curves else system.curve(
                           ms, anchors[k], _stage(progress, f"{system.name}: hot spots"))[0]
                       for k, system in enumerate(systems)])
    table = []
    for k, n in enumerate(ns):
        col = speeds[:, k]
        j = int(np.nanargmin(col)) if np.isfinite(col).any() else None
        table.append(HotSpot(int(n), float(2.0 * math.pi * radius / n),
                             None if j is None else float(col[j]),
                             None if j is None else systems[j].name))
    finite = [h for h in table if h.critical_speed is not None]
    governing = min(finite, key=lambda h: h.critical_speed).n if finite else None
    return tuple(table), governing


def _growing(system, m, speed):
    """At ``speed``: every growing mode of a family, or its least stable if none grows."""
    b = system.modes(m, speed)
    grow = b[b.real > 0.0]
    return grow if grow.size else b[:1]


def _most_unstable(systems, speed, wl_range):
    """Over the layups' wavelengths: the largest growth rate at ``speed`` and its
    wavelength, from 24 wavelengths refined by Brent's method in ``ln m``."""
    from scipy.optimize import minimize_scalar

    ms = np.geomspace(2.0 * math.pi / wl_range[1], 2.0 * math.pi / wl_range[0], 24)
    best = (-math.inf, None, None)
    for system in systems:
        rates = np.array([_rate(system, m, speed) for m in ms])
        i = int(np.argmax(rates))
        if rates[i] > best[0]:
            best = (rates[i], i, system)
    rate, i, system = best
    if system is None or rate <= 0.0:
        return None, None
    if i in (0, ms.size - 1):
        return float(2.0 * math.pi / ms[i]), float(rate)
    res = minimize_scalar(lambda x: -_rate(system, math.exp(x), speed),
                          bounds=(math.log(ms[i - 1]), math.log(ms[i + 1])), method="bounded",
                          options={"xatol": 1e-8})
    return float(2.0 * math.pi / math.exp(res.x)), float(-res.fun)


def _rate(system, m, speed):
    b = system.modes(m, speed)
    return float(b[0].real) if len(b) else -math.inf


def _stage(progress, stage):
    """``progress(stage, done, total)`` as ``tell(done, total)`` for one stage (a no-op
    without ``progress``)."""
    if progress is None:
        return lambda done, total: None
    return lambda done, total: progress(stage, done, total)


def check_geometry(slider, counterface, **geometry):
    """The layups of a geometry built, so that their checks run before any work
    (:func:`~thermocontact.physics.tei_layers.layups`); two half-planes: the pair's."""
    from ..physics.tei_layers import layups

    if not layups(slider, counterface, 0.0, **geometry):
        SlidingPair(slider, counterface, 0.0)


def analyse(slider, counterface, friction, wavelength, speed=None, dundurs=True, *,
            plane="strain", slider_thickness=None, faces=2, counterface_thickness=None,
            backing="slip-insulated", separator=None, separator_thickness=None,
            disc_radius=None, hot_spots=None, stop=None, progress=None) -> TEIResult:
    """The critical speed of every family at one wavelength, its minimum over the
    wavelength, and at a speed the modes and the most unstable wavelength; with a
    disc radius, the hot-spot table; with a stop, its amplifications: the study
    behind :func:`thermocontact.tei`.

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
    plane : {"strain", "stress"}
    slider_thickness, faces, counterface_thickness, backing, separator,
    separator_thickness
        The geometry (:func:`~thermocontact.physics.tei_layers.layups`; lengths in m,
        already checked).
    disc_radius : float, optional
        ``R``, m, with ``hot_spots = (n1, n2)``.
    stop : StopHistory, optional
        A speed history (:func:`thermocontact.studies.brake_stop.stop_history`), with
        ``disc_radius`` and ``hot_spots``: each hot-spot number's amplification.
    progress : callable, optional
        ``progress(stage, done, total)``: each family's scan, its curve over the
        wavelength, the families' hot-spot curves (one stage), and the stop (a
        layup's analysis takes seconds to minutes).

    Returns
    -------
    TEIResult
    """
    from ..physics.tei_layers import layups, plane_stress_material

    friction = check_zero_or_range("friction", friction, *FRICTION_RANGE)
    wl = check_range("wavelength", wavelength, *WAVELENGTH_RANGE)
    v = None if speed is None else check_zero_or_range("speed", speed, *SPEED_RANGE)
    pair = SlidingPair(slider, counterface, friction, dundurs=dundurs)
    if plane == "stress":
        pair = SlidingPair(plane_stress_material(slider), plane_stress_material(counterface),
                           friction, dundurs=dundurs)
    lay = layups(slider, counterface, friction, dundurs=dundurs, plane=plane,
                 slider_thickness=slider_thickness, faces=faces,
                 counterface_thickness=counterface_thickness, backing=backing,
                 separator=separator, separator_thickness=separator_thickness)
    systems = _systems(pair, lay)
    thick = [t for t in (slider_thickness, counterface_thickness, separator_thickness)
             if t is not None]
    wl_range = _wavelength_range(thick, disc_radius) if thick else None
    m = 2.0 * math.pi / wl
    fams, anchors = [], []
    for system in systems:
        if friction == 0.0:
            fams.append(TEIFamily(system.name, None, None))
            anchors.append(None)
            continue
        tell = _stage(progress, f"{system.name}: critical speed")
        tell(0, 1)
        scan = system.scan(m, beyond=CROSSINGS_BEYOND) if lay else None
        tell(1, 1)
        if scan is None:
            vc, b = system.critical(m)
        else:
            vc, b = (None, None) if scan.first is None else (scan.first[0], 1j * scan.first[1])
        anchor = None if vc is None else (m, vc, b.imag)
        curve_told = _stage(progress, f"{system.name}: minimum over the wavelength")
        low, at, end = ((None, None, None) if wl_range is None
                        else family_minimum(system, wl_range, anchor=anchor,
                                            progress=curve_told))
        crossings = () if scan is None else tuple(
            {"speed": c[0], "migration_speed": -c[1] / m, "direction": c[2]}
            for c in scan.crossings)
        fams.append(TEIFamily(system.name, vc, None if vc is None else -b.imag / m, low, at,
                              end, crossings, None if scan is None else scan.certified))
        anchors.append(anchor)
    found = [f for f in fams if f.critical_speed is not None]
    first = min(found, key=lambda f: f.critical_speed) if found else None
    if first is not None:
        stable = False
    elif friction == 0.0:
        stable = True
    elif lay:
        stable = None          # a layup: stable below the scan's end, nothing claimed beyond
    else:
        stable = stable_at_all_speeds(pair, m)
    extra = {}
    if v is not None:
        mw = rate = None
        if v > 0.0 and first is not None:
            if lay:
                mw, rate = ((None, None) if wl_range is None
                            else _most_unstable(systems, v, wl_range))
            else:
                mw, rate = most_unstable_wavelength(pair, v, m, first.critical_speed)
        found_modes = []
        if v > 0.0 and friction > 0.0:
            for system in systems:
                bs = system.modes(m, v) if not lay else _growing(system, m, v)
                found_modes.extend(_mode(complex(b), m, system.name) for b in bs)
        elif v > 0.0 and not lay:
            found_modes = list(tei_modes(pair, m, v))
        found_modes.sort(key=lambda x: -x.growth_rate)
        extra = dict(speed=v, modes=tuple(found_modes), most_unstable_wavelength=mw,
                     most_unstable_growth_rate=rate)
    if disc_radius is not None and friction > 0.0:
        table, governing = hot_spot_table(systems, disc_radius, *hot_spots, anchors=anchors,
                                          progress=progress)
        extra.update(disc_radius=disc_radius, hot_spots=table, governing_hot_spots=governing)
    elif disc_radius is not None:
        extra.update(disc_radius=disc_radius)
    if stop is not None:
        from .brake_stop import stop_amplification

        tell = _stage(progress, "the stop's growth rates")
        tell(0, 1)
        extra.update(stop=stop_amplification(systems, disc_radius, hot_spots, stop))
        tell(1, 1)
    return TEIResult(pair.slider.name, pair.counterface.name, pair.friction, wl, pair.dundurs,
                     pair.beta, None if first is None else first.critical_speed, stable,
                     None if first is None else first.migration_speed, **extra,
                     plane=plane, slider_thickness=slider_thickness,
                     faces=faces if slider_thickness is not None else 2,
                     counterface_thickness=counterface_thickness,
                     backing=backing if counterface_thickness is not None else None,
                     separator=None if separator is None else separator.name,
                     separator_thickness=separator_thickness, families=tuple(fams),
                     wavelength_range=wl_range, pair=pair, systems=systems,
                     half_planes=HalfPlanes("half-planes", pair) if lay else None)
