"""Thermoelastic instability of brake discs, pads on backing plates and clutch packs:
the modes of each family, critical speeds against the wavelength and their minimum.

A *family* is one layup of :mod:`thermocontact.physics.tei_layers` whose modes are
studied together: a disc rubbing on both faces between identical pads splits into
the modes symmetric and antisymmetric about its mid-plane (each a half-disc with the
mid-plane's conditions), a clutch pack into four families (docs/tei.md).  Two
half-planes are the family of :mod:`thermocontact.physics.tei`, whose polynomial
root search finds every mode; the same interface serves both
(:class:`thermocontact.studies.tei.HalfPlanes`, :class:`Layered`), so that every study
works for every geometry.

For a layup the modes are roots of ``det M(b)`` (L8): the rightmost few are seeded by
the eigenvalues of the depth discretisation
(:func:`thermocontact.discretisation.tei_depth.layup_modes`) and polished by Newton's
method on the determinant.  A neutral mode, ``b = i omega`` at the critical speed, is
found by Newton's method on ``det M(i omega; V) = 0`` for the two real unknowns
``(V, omega)`` (L10); along a curve of wavelengths it is continued from the last one.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..discretisation.tei_depth import layup_modes
from ..physics.tei_layers import Layup, layup_dispersion, mode_shape

__all__ = ["Layered", "continue_neutral", "continue_step", "first_crossing", "growth_rate",
           "neutral_point", "newton_roots", "pattern_frame", "raw_seeds"]

#: Chebyshev intervals per body of the depth discretisation that seeds the roots.
SEED_POINTS = 16
#: Chebyshev intervals per body of the scan for the first crossing (signs only; the
#: crossing is then polished by Newton's method).
SCAN_POINTS = 16
#: Seeds polished per evaluation of the modes.
SEEDS = 4
#: Speeds per factor 2 of the scan for the first crossing.
PER_OCTAVE = 2


def _scale(layup: Layup, m) -> float:
    """``kappa m^2`` of the slowest conductor: the growth rates' scale."""
    return min(b.material.k for b in layup.bodies if b.conducts) * m * m


def newton_roots(func, x0, scale, iters=25):
    """Newton's method on an analytic ``func`` (vectorised), the derivative by central
    differences of step ``1e-6 scale``; returns the roots and which converged: a step
    below ``1e-13 (|x| + scale)``, or one below ``1e-9 (|x| + scale)`` that no longer
    falls (the rounding of the determinant reached).  Each root is iterated only
    until it has converged; ``func(z, active)`` gets the indices of those iterated."""
    x = np.array(x0, dtype=complex)
    scale = np.broadcast_to(np.asarray(scale, dtype=float), x.shape)
    done = np.zeros(x.shape, dtype=bool)
    last = np.full(x.shape, np.inf)
    for _ in range(iters):
        act = np.flatnonzero(~done & np.isfinite(x))
        if not act.size:
            break
        xa, h = x[act], 1e-6 * scale[act]
        f = func(np.stack([xa, xa + h, xa - h]), act)
        d = (f[1] - f[2]) / (2.0 * h)
        with np.errstate(invalid="ignore", divide="ignore"):
            step = f[0] / d
        step = np.where(np.isfinite(step), step, np.nan)
        x[act] = xa - step
        size, unit = np.abs(step), np.abs(x[act]) + scale[act]
        done[act] = (size <= 1e-13 * unit) | ((size <= 1e-9 * unit) & (size > 0.3 * last[act]))
        last[act] = size
    return x, done & np.isfinite(x)


@dataclass(frozen=True)
class Layered:
    """One family of modes of a layup.

    Parameters
    ----------
    name : str
        The family's name ("symmetric", "antisymmetric", ...; docs/tei.md).
    layup : Layup
    """

    name: str
    layup: Layup

    def scale(self, m) -> float:
        return _scale(self.layup, m)

    def continuum(self, m) -> float:
        """The right end of the half-planes' continuous spectrum, ``-kappa m^2``
        (``-inf`` without a half-plane): roots are sought to its right."""
        ks = [b.material.k for b in self.layup.bodies if b.thickness is None and b.conducts]
        return -min(ks) * m * m if ks else -math.inf

    def dispersion(self, b, m, speed):
        return layup_dispersion(self.layup, b, m, speed)

    def in_continuum(self, b, m, speed):
        """Whether each ``b`` lies on a half-plane's continuous spectrum (to 1e-3 of its
        scale): ``b + i m U`` real and below ``-kappa m^2/2`` for a half-plane moving
        at ``U``, where the depth discretisation puts a cloud of eigenvalues that are
        no modes."""
        b = np.asarray(b, dtype=complex)
        out = np.zeros(b.shape, dtype=bool)
        for body in self.layup.bodies:
            if body.thickness is None and body.conducts:
                edge = body.material.k * m * m
                z = b + 1j * m * (speed if body.moving else 0.0)
                out |= (z.real < -0.5 * edge) & (np.abs(z.imag) <= 1e-3 * (np.abs(z.real) + edge))
        return out

    def modes(self, m, speed, count=SEEDS, seeds=None):
        """The rightmost modes at one wavenumber and speed, 1/s, by decreasing real part:
        depth-discretisation seeds (or ``seeds``) polished by Newton's method."""
        m = float(m)
        if seeds is None:
            seeds = raw_seeds(self, m, speed)[:count]
        if not len(seeds):
            return np.array([], dtype=complex)
        scale = max(self.scale(m), 1e-300)
        roots, ok = newton_roots(lambda z, _: self.dispersion(z, m, speed), seeds, scale)
        # A root far from its seed is none of the discretisation's: Newton's method
        # has run off to where the determinant underflows.
        near = np.abs(roots - seeds) <= 0.5 * np.abs(seeds) + 10.0 * scale
        roots = roots[ok & near & (roots.real > self.continuum(m))]
        out = []
        for r in roots[np.argsort(-roots.real, kind="stable")]:
            if all(abs(r - x) > 1e-8 * (abs(r) + scale) for x in out):
                out.append(complex(r))
        return np.array(out, dtype=complex)

    def critical(self, m):
        """The critical speed at ``m`` and the neutral ``b = i omega`` (:func:`first_crossing`)."""
        return first_crossing(self, m)

    def curve(self, wavenumbers, anchor=None):
        """Critical speeds and neutral ``omega`` along sorted wavenumbers
        (:func:`continue_neutral`, from ``anchor = (m, V, omega)`` if given)."""
        return continue_neutral(self, wavenumbers, anchor)

    def mode_shape(self, m, speed, b, points=41):
        """The mode ``b`` through the layup
        (:func:`~thermocontact.physics.tei_layers.mode_shape`)."""
        return mode_shape(self.layup, b, m, speed, points)

    def lowest_speed(self, m) -> float:
        """Where the scan for the first crossing starts, m/s: the frictional heat's
        coefficient ``2 mu a f V/(K m)`` (the references' scales) is 1e-4 there.
        At least 1e-9 m/s."""
        mu, a, K = self.layup.references()
        return max(1e-9, 1e-4 * K * m / (2.0 * mu * a * max(self.layup.friction, 1e-300)))


def growth_rate(family, m, speed) -> float:
    """The largest ``Re b`` of the family's modes, 1/s (``-inf`` without a mode)."""
    b = family.modes(m, speed)
    return float(b[0].real) if len(b) else -math.inf


def pattern_frame(m, V, omega):
    """1 if the pattern is nearer to rest on the moving bodies than on the bodies at
    rest, else 0: the frame in which a neutral mode's frequency is measured."""
    return np.where(np.abs(omega + m * V) < np.abs(omega), 1.0, 0.0)


def neutral_point(family, m, speed, omega, iters=40):
    """``(V, omega, converged)`` with ``D(i omega; V) = 0`` near a guess, by Newton's
    method on two real unknowns (L10).

    A neutral mode fixed on a body is sharply defined in ``omega``: within
    ``kappa m^2`` of ``-m U`` of that body.  The unknowns are therefore ``V`` and
    the frequency in the frame of the bodies the pattern is nearer to rest on,
    ``s = (omega + phi m V)/(kappa m^2)`` (``phi`` 1 for the moving bodies, 0 for
    those at rest), which Newton's method varies independently.  ``m`` may be an
    array (with ``speed`` and ``omega`` of its shape): the points are solved together,
    each on its own."""
    m = np.asarray(m, dtype=float)
    V = np.array(np.broadcast_to(speed, m.shape), dtype=float)
    w = np.array(np.broadcast_to(omega, m.shape), dtype=float)
    sig = (np.vectorize(family.scale)(m) if m.ndim else np.asarray(family.scale(float(m))))
    phi = pattern_frame(m, V, w)
    s = (w + phi * m * V) / sig
    done = np.zeros(m.shape, dtype=bool)
    last = np.full(m.shape, np.inf)

    def omega_of(V, s):
        return -phi * m * V + sig * s

    for _ in range(iters):
        hs = 1e-6 * (1.0 + np.abs(s))
        hv = 1e-7 * V
        f = family.dispersion(1j * np.stack([omega_of(V, s), omega_of(V, s + hs),
                                             omega_of(V, s - hs), omega_of(V + hv, s)]),
                              np.stack([m] * 4), np.stack([V, V, V, V + hv]))
        ds = (f[1] - f[2]) / (2.0 * hs)
        dv = (f[3] - f[0]) / hv
        det = dv.real * ds.imag - dv.imag * ds.real
        with np.errstate(invalid="ignore", divide="ignore"):
            sV = (-f[0].real * ds.imag + f[0].imag * ds.real) / det
            sS = (-dv.real * f[0].imag + dv.imag * f[0].real) / det
        sV = np.where(done | ~np.isfinite(sV), 0.0, sV)
        sS = np.where(done | ~np.isfinite(sS), 0.0, sS)
        # Damped: a step changes the speed by at most a factor 1.5.
        sV = np.clip(sV, -V / 3.0, 0.5 * V)
        sS = np.clip(sS, -2.0 * (1.0 + np.abs(s)), 2.0 * (1.0 + np.abs(s)))
        V = V + sV
        s = s + sS
        # Converged: both steps at rounding, or small and no longer falling.
        size = np.maximum(np.abs(sV) / V, np.abs(sS) / (1.0 + np.abs(s)) * 1e-2)
        done |= (size <= 1e-13) | ((size <= 1e-10) & (size > 0.3 * last))
        last = np.where(done, last, size)
        if done.all():
            break
    return V, omega_of(V, s), done


def raw_seeds(family, m, speed, points=None):
    """The depth discretisation's rightmost eigenvalues off the half-planes' continuous
    spectra (unpolished; ``points`` per body, default :data:`SEED_POINTS`)."""
    seeds = layup_modes(family.layup, m, speed, SEED_POINTS if points is None else points)
    return seeds[~family.in_continuum(seeds, m, speed)][:SEEDS]


def first_crossing(family, m, v_low=None, v_high=1e4):
    """The lowest speed at which a mode of wavenumber ``m`` grows, from a scan
    upward (:data:`PER_OCTAVE` speeds per factor 2, one where every mode decays at
    least at ``kappa m^2``; the depth discretisation's eigenvalues at
    :data:`SCAN_POINTS`) located by Newton's method on the neutral point; ``(None, None)`` if
    none grows below ``v_high``.

    Where a mode grows at the scan's start, the start moves down (by factors 8) until
    none does; a mode growing at 1e-9 m/s, the lowest speed studied, gives that speed
    (an upper bound) and that mode.

    Returns
    -------
    (float, complex) or (None, None)
        The critical speed, m/s, and the neutral growth rate ``b = i omega``, 1/s.
    """
    v = family.lowest_speed(m) if v_low is None else v_low
    fine = 2.0 ** (1.0 / PER_OCTAVE)
    ratio = fine
    prev = None
    # A mode growing at the scan's start: the start moves down until none does.
    while True:
        b = raw_seeds(family, m, v, SCAN_POINTS)
        if not (len(b) and family.modes(m, v, seeds=b[:SEEDS]).real.max(initial=-1.0) > 0.0):
            break
        if v <= 1e-9:           # growing at the lowest speed studied: an upper bound
            return v, complex(family.modes(m, v, seeds=b[:SEEDS])[0])
        v = max(v / 8.0, 1e-9)
    while v <= v_high * ratio:
        b = raw_seeds(family, m, v, SCAN_POINTS)
        if len(b) and b[0].real > 0.0:
            b = family.modes(m, v, seeds=b)      # polished
        if len(b) and b[0].real > 0.0:
            if prev is None:    # growing where the start found none: locate from below
                v0, b0 = v / fine, None
            else:
                v0, b0 = prev
            # Interpolate in ln V where Re b crosses 0, and the frequency in the
            # pattern's frame (neutral_point), then Newton.
            b1 = complex(b[0])
            t = 0.5 if b0 is None else -b0.real / (b1.real - b0.real)
            vg = v0 * (v / v0) ** t
            phi = float(pattern_frame(m, v, b1.imag))
            s1 = b1.imag + phi * m * v
            s0 = s1 if b0 is None else b0.imag + phi * m * v0
            V, w, ok = neutral_point(family, m, vg, -phi * m * vg + s0 + t * (s1 - s0))
            if ok and v0 / fine <= V <= v * fine:
                return float(V), 1j * float(w)
            return _brent_crossing(family, m, v0, v)
        prev = (v, complex(b[0]) if len(b) else None)
        # Octaves where every mode decays at least at kappa m^2 are crossed in one step.
        ratio = 2.0 if not len(b) or b[0].real < -family.scale(m) else fine
        v *= ratio
    return None, None


def _brent_crossing(family, m, v0, v1):
    from scipy.optimize import brentq

    vc = brentq(lambda v: growth_rate(family, m, v), v0, v1, rtol=1e-13)
    b = family.modes(m, vc)
    return float(vc), complex(b[0])


def continue_step(family, m0, point, m1, depth=0):
    """The neutral point at ``m1`` continued from ``point = (V, omega)`` at ``m0``:
    Newton's method from the same speed and frequency in the pattern's frame
    (:func:`neutral_point`), accepted if it converges within a factor 2 of the speed;
    otherwise the interval is halved (in ``ln m``, at most 8 times)."""
    v0, w0 = point
    # Predicted: the same speed and the same frequency in the pattern's frame, in
    # units of kappa m^2.
    phi = float(pattern_frame(m0, v0, w0))
    s = (w0 + phi * m0 * v0) / family.scale(m0)
    v, w, ok = neutral_point(family, m1, v0, -phi * m1 * v0 + s * family.scale(m1))
    if ok and 0.5 * v0 < v < 2.0 * v0:
        return float(v), float(w)
    if depth >= 8:
        return None
    mid = math.sqrt(m0 * m1)
    half = continue_step(family, m0, point, mid, depth + 1)
    return None if half is None else continue_step(family, mid, half, m1, depth + 1)


def continue_neutral(family, wavenumbers, anchor=None, check_every=20):
    """The critical speed and neutral ``omega`` along sorted wavenumbers, continued.

    From ``anchor = (m, V, omega)``, a neutral point already found, outward both
    ways; without one, from a scan (:func:`first_crossing`) at the first
    wavenumber.  Each next point comes from Newton's method on the neutral point
    started from the last (:func:`continue_step`, halving the step where it fails).
    Every ``check_every`` points the modes at ``0.999 V`` are checked to decay: where
    one grows, another branch crosses lower, and a scan (:func:`first_crossing`) takes
    over, as it does wherever the continuation fails.

    Returns
    -------
    (V, omega) : ndarrays
        NaN where no mode grows below the scan's end.
    """
    ms = np.asarray(wavenumbers, dtype=float)
    V = np.full(ms.shape, np.nan)
    W = np.full(ms.shape, np.nan)
    if anchor is None:
        _walk(family, ms, range(ms.size), None, V, W, check_every)
    else:
        k = int(np.searchsorted(ms, anchor[0]))
        start = (float(anchor[0]), (float(anchor[1]), float(anchor[2])))
        _walk(family, ms, range(k, ms.size), start, V, W, check_every)
        _walk(family, ms, range(k - 1, -1, -1), start, V, W, check_every)
    return V, W


def _walk(family, ms, order, prev, V, W, check_every):
    for count, i in enumerate(order):
        m = ms[i]
        found = None
        if prev is not None:
            found = prev[1] if prev[0] == m else continue_step(family, prev[0], prev[1], m)
            if found is not None and count % check_every == check_every - 1 and growth_rate(
                    family, m, 0.999 * found[0]) > 0.0:
                found = None
        if found is None:
            vc, b = first_crossing(family, m)
            found = None if vc is None else (vc, b.imag)
        if found is None:
            prev = None
            continue
        V[i], W[i] = found
        prev = (float(m), found)
