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

For a layup the modes are roots of ``det M(b)`` off the half-planes' branch cuts (L8,
L15): the rightmost few are seeded by the eigenvalues of the depth discretisation
(:func:`thermocontact.discretisation.tei_depth.layup_modes`) and polished by Newton's
method on the determinant (its logarithmic derivative in closed form, L16), each in the
frame it is nearer to rest in.  The critical
speed comes from a scan that follows the modes in speed with step control, locates
every change of sign and every interior maximum of a mode's growth rate (windows of
growth), and counts the growing modes at every speed by the argument principle
(:func:`speed_scan`, :func:`unstable_count`); a neutral mode, ``b = i omega``, is
polished by Newton's method on ``det M(i omega; V) = 0`` for the two real unknowns
``(V, omega)`` (L10); along a curve of wavelengths, scans at every
:data:`SCAN_EVERY`-th are continued between them (:func:`neutral_curves`), the scans of
every family and wavelength run in lockstep, their evaluations of the dispersion
function answered together (:func:`~thermocontact.execution.lockstep.run_lockstep`).
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass, field, replace

import numpy as np

from ..discretisation.tei_depth import layup_modes
from ..execution.lockstep import run_lockstep
from ..numerics.cache import small_cache
from ..physics.tei_layers import (Layup, dispersion_log_derivatives, dispersion_ratio,
                                  field_group, layup_dispersion, mode_shape)

__all__ = ["Layered", "SpeedScan", "continue_neutral", "continue_step", "continue_steps",
           "first_crossing", "growth_rate", "neutral_curves", "neutral_point", "newton_roots",
           "pattern_frame", "raw_seeds", "speed_scan", "unstable_count"]

#: Chebyshev intervals per body of the depth discretisation that seeds the roots.
SEED_POINTS = 16
#: Seeds polished per evaluation of the modes: the discretisation's rightmost
#: eigenvalues off the half-planes' continuous spectra.
SEEDS = 8
#: Wavenumbers of a critical-speed curve between two scans from the lowest speed.
SCAN_EVERY = 20


def _scale(layup: Layup, m) -> float:
    """``kappa m^2`` of the slowest conductor: the growth rates' scale."""
    return min(b.material.k for b in layup.bodies if b.conducts) * m * m


def newton_roots(log_derivative, x0, scale, iters=25, abandon=None):
    """Newton's method on an analytic function ``f`` given its logarithmic derivative
    ``f'/f`` (vectorised; the step ``-f/f'``); returns the roots and which converged: a step
    below ``1e-13 (|x| + scale)``, one below ``1e-9 (|x| + scale)`` that no longer
    falls (the rounding of the determinant reached), or one below ``1e-7 (|x| + scale)``
    after which quadratic convergence leaves at most ``1e-14 (|x| + scale)``
    (:func:`_settled`).  Each root is iterated only
    until it has converged, or given up (NaN) if its step is still above ``1e-6 (|x| +
    scale)`` after 12 iterations (no quadratic convergence in sight: a seed of the
    continuous spectrum); ``log_derivative(z, active)`` gets the indices of those
    iterated.  ``abandon(x, step, last)``, if given, is asked after each iteration
    with the iterates, the size of each one's latest step and of the one before (0
    for a root converged earlier, inf where there is none): True ends the iteration,
    no root converged (NaN)."""
    x = np.array(x0, dtype=complex)
    scale = np.broadcast_to(np.asarray(scale, dtype=float), x.shape)
    done = np.zeros(x.shape, dtype=bool)
    last = np.full(x.shape, np.inf)
    every = np.arange(x.size)
    for it in range(iters):
        if it == 12:
            x[~done & (last > 1e-6 * (np.abs(x) + scale))] = np.nan
        going = ~done & np.isfinite(x)
        # Every root still going (the usual case): the arrays themselves, not gathered.
        whole = bool(going.all())
        act = every if whole else np.flatnonzero(going)
        if not act.size:
            break
        xa, sa, la = (x, scale, last) if whole else (x[act], scale[act], last[act])
        with np.errstate(invalid="ignore", divide="ignore", over="ignore"):
            step = 1.0 / log_derivative(xa, act)
            step = np.where(np.isfinite(step), step, np.nan)
            xa = xa - step
            size, unit = np.abs(step), np.abs(xa) + sa
            now = ((size <= 1e-13 * unit) | ((size <= 1e-9 * unit) & (size > 0.3 * la))
                   | _settled(size / unit, la / unit))
        if whole:
            x, done = xa, now
        else:
            x[act], done[act] = xa, now
        if abandon is not None:
            step = np.where(done, 0.0, np.inf)
            before = step.copy()
            step[act], before[act] = size, la
            if abandon(x, step, before):
                return np.full(x.shape, np.nan + 0j), np.zeros(x.shape, dtype=bool)
        if whole:
            last = size
        else:
            last[act] = size
    return x, done & np.isfinite(x)


def _settled(step, last):
    """Whether Newton's method has converged after a relative ``step`` (a fraction of
    the unknown's size) that followed one of ``last``: both in the quadratic regime
    (``last <= 1e-3``, ``step <= 1e-7``), where the error after a step is about ``C
    step^2`` with ``C = step/last^2`` measured, so at most ``step^3/last^2 <= 1e-14``
    is left (1e-8 after 1e-4 leaves 1e-16): the iteration that would only see the
    step fall is saved."""
    with np.errstate(invalid="ignore", over="ignore"):
        return (step <= 1e-7) & (last <= 1e-3) & (step ** 3 <= 1e-14 * last ** 2)


@dataclass(frozen=True)
class Layered:
    """One family of modes of a layup.

    Parameters
    ----------
    name : str
        The family's name ("symmetric", "antisymmetric", ...; docs/tei.md).
    layup : Layup
    ask : callable, optional
        ``ask(key, payload)`` of :func:`~thermocontact.execution.lockstep.run_lockstep`:
        the family's evaluations of :meth:`dispersion` and :meth:`dispersion_ratio`
        handed to it, to be answered together with other computations' (None: each
        evaluated at once, as asked).
    """

    name: str
    layup: Layup
    ask: Callable | None = field(default=None, compare=False, repr=False)

    def __post_init__(self):
        # The key of its layup's field group in a batch of requests, made once.
        object.__setattr__(self, "_batch", _group_token(field_group(self.layup)))

    def scale(self, m) -> float:
        return _scale(self.layup, m)

    def continuum(self, m) -> float:
        """The right end of the half-planes' continuous spectrum, ``-kappa m^2``
        (``-inf`` without a half-plane): roots are sought to its right."""
        ks = [b.material.k for b in self.layup.bodies if b.thickness is None and b.conducts]
        return -min(ks) * m * m if ks else -math.inf

    def dispersion(self, b, m, speed):
        """The dispersion function at ``b`` (:func:`~thermocontact.physics.tei_layers.
        layup_dispersion`), ``b``, ``m`` and ``speed`` broadcast."""
        if self.ask is None:
            return layup_dispersion(self.layup, b, m, speed)
        return self.ask(("dispersion", self.layup), (self.layup, b, m, speed))

    def log_derivatives(self, b, m, speed):
        """``[d ln D/db, d ln D/dV]`` of the dispersion function at ``b``, shape of the
        broadcast ``+ (2,)`` (:func:`~thermocontact.physics.tei_layers.
        dispersion_log_derivatives`)."""
        if self.ask is None:
            return dispersion_log_derivatives(self.layup, b, m, speed)
        return self.ask(("log_derivatives", self._batch),
                        (self.layup, b, m, speed))

    def dispersion_ratio(self, b, m, speed):
        """``det M/det M_0`` at ``b`` (:func:`~thermocontact.physics.tei_layers.
        dispersion_ratio`), whose winding counts the growing modes."""
        if self.ask is None:
            return dispersion_ratio(self.layup, b, m, speed)
        return self.ask(("ratio", self._batch),
                        (self.layup, b, m, speed))

    def in_continuum(self, b, m, speed):
        """Whether each ``b`` lies on a half-plane's continuous spectrum (to 1e-2 of its
        distance from ``b + i m U = 0``, and 1e-7 of ``m V``, the discretisation's
        error in the frame at rest where the moving bodies' rows carry ``i m V``): ``b + i m U`` real and below
        ``-kappa m^2/2`` for a half-plane moving at ``U``, where the depth
        discretisation puts a cloud of eigenvalues that are no modes."""
        return self._near_cut(b, m, speed, 0.5, 1e-2, 1e-7)

    def on_cut(self, b, m, speed):
        """Whether each ``b`` lies on a half-plane's branch cut, ``b + i m U`` real
        (to 1e-9 of its size and 1e-13 of ``m V``) and at most ``-kappa m^2``: a point of the
        continuous spectrum, where a root of the determinant on the principal branch
        is no mode."""
        return self._near_cut(b, m, speed, 1.0, 1e-9, 1e-13)

    def _near_cut(self, b, m, speed, edge_factor, tol, slack):
        b = np.asarray(b, dtype=complex)
        out = np.zeros(b.shape, dtype=bool)
        for body in self.layup.bodies:
            if body.thickness is None and body.conducts:
                edge = body.material.k * m * m
                z = b + 1j * m * (speed if body.moving else 0.0)
                out |= (z.real <= -edge_factor * edge) & (
                    np.abs(z.imag) <= tol * (np.abs(z.real) + edge) + slack * m * abs(speed))
        return out

    def modes(self, m, speed, count=SEEDS, seeds=None):
        """The rightmost modes at one wavenumber and speed, 1/s, by decreasing real part:
        depth-discretisation seeds (or ``seeds``) polished by Newton's method in the
        frame each is nearer to rest in.

        A mode is a zero of :meth:`dispersion` off the half-planes' branch cuts (the
        physical sheet, every half-plane's field decaying with depth); its real part
        may lie below the continuous spectrum's ``-kappa m^2`` (a mode at rest on the
        disc, far from the pads' cut in frequency).  Which are found: those seeded by
        the discretisation's ``count`` rightmost eigenvalues off the continuous
        spectra (L14); every growing one is counted by :func:`unstable_count`."""
        m = float(m)
        if seeds is None:
            seeds = raw_seeds(self, m, speed, count=count)
        seeds = np.asarray(seeds, dtype=complex)
        if not seeds.size:
            return np.array([], dtype=complex)
        return _unique(self, m, _polish(self, m, speed, seeds)[0])

    def critical(self, m):
        """The critical speed at ``m`` and the neutral ``b = i omega`` (:func:`first_crossing`)."""
        return first_crossing(self, m)

    def scan(self, m, v_high=1e4, every=False, beyond=1.0):
        """The neutral crossings at ``m`` up to ``beyond`` times the critical speed (or
        ``every`` one up to ``v_high``) and the scan's checks (:func:`speed_scan`)."""
        return speed_scan(self, m, v_high, every=every, beyond=beyond)

    def curve(self, wavenumbers, anchor=None, progress=None):
        """Critical speeds and neutral ``omega`` along sorted wavenumbers
        (:func:`continue_neutral`, from ``anchor = (m, V, omega)`` if given)."""
        return continue_neutral(self, wavenumbers, anchor, progress=progress)

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


@small_cache(64)
def _group_token(group):
    """A token of one :func:`~thermocontact.physics.tei_layers.field_group`, the key by
    which its requests are batched: hashed by identity, not through every body's
    material at every request."""
    return object()


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
    each on its own (each evaluated until it has converged).  A point still stepping
    by a tenth after 12 iterations is given up (not converged): no convergence is in
    sight; so is one at once whose finite derivatives make a singular system.  Where
    the derivatives are not finite (``M`` singular: ``D = 0`` at the point itself)
    it has converged there."""
    m = np.asarray(m, dtype=float)
    newton = _NeutralNewton(family, iters)
    newton.add(m.reshape(-1), np.broadcast_to(speed, m.shape).reshape(-1),
               np.broadcast_to(omega, m.shape).reshape(-1), range(m.size))
    V, w, done = np.empty(m.size), np.empty(m.size), np.zeros(m.size, dtype=bool)
    while True:
        for j, Vj, wj, ok in newton.finished():
            V[j], w[j], done[j] = Vj, wj, ok
        if not newton.size:
            break
        newton.iterate()
    return V.reshape(m.shape), w.reshape(m.shape), done.reshape(m.shape)


class _NeutralNewton:
    """The Newton iterations of :func:`neutral_point` for points that may join at any
    time, each iterated as it would be alone (its own count of iterations): each
    :meth:`iterate` evaluates every point still going in one request."""

    def __init__(self, family, iters=40):
        self.family, self.iters = family, iters
        self.tags = []
        self.m, self.V, self.s, self.sig, self.phi, self.last = (np.empty(0) for _ in range(6))
        self.done, self.stop = np.zeros(0, dtype=bool), np.zeros(0, dtype=bool)
        self.it = np.zeros(0, dtype=int)

    @property
    def size(self):
        return len(self.tags)

    def add(self, m, speed, omega, tags):
        """Points from ``speed`` and ``omega`` at wavenumbers ``m`` (1-D), told by
        :meth:`finished` with their ``tags``."""
        m = np.asarray(m, dtype=float)
        V = np.array(speed, dtype=float)
        w = np.array(omega, dtype=float)
        sig = np.array([self.family.scale(x) for x in m], dtype=float)
        phi = pattern_frame(m, V, w)
        s = (w + phi * m * V) / sig
        n = m.size
        self.tags += list(tags)
        self.m, self.V, self.s, self.sig, self.phi = (
            np.concatenate([x, y]) for x, y in ((self.m, m), (self.V, V), (self.s, s),
                                                (self.sig, sig), (self.phi, phi)))
        self.last = np.concatenate([self.last, np.full(n, np.inf)])
        self.done = np.concatenate([self.done, np.zeros(n, dtype=bool)])
        self.stop = np.concatenate([self.stop, np.zeros(n, dtype=bool)])
        self.it = np.concatenate([self.it, np.zeros(n, dtype=int)])

    def finished(self):
        """The points that have ended, taken out: ``(tag, V, omega, converged)`` each.
        A point ends converged, given up (still stepping by a tenth after 12 iterations:
        no convergence in sight, a guess between branches, the steps held at the
        damping's limits; or a singular system where ``D`` is not 0) or after
        ``iters`` iterations."""
        self.stop |= (self.it == 12) & ~self.done & (self.last > 0.1)
        end = self.done | self.stop | (self.it >= self.iters)
        if not end.any():
            return []
        omega = -self.phi * self.m * self.V + self.sig * self.s
        out = [(self.tags[j], self.V[j], omega[j], bool(self.done[j]))
               for j in np.flatnonzero(end)]
        keep = ~end
        self.tags = [t for t, k in zip(self.tags, keep) if k]
        for name in ("m", "V", "s", "sig", "phi", "last", "done", "stop", "it"):
            setattr(self, name, getattr(self, name)[keep])
        return out

    def iterate(self):
        """One iteration of every point (none ended: :meth:`finished` first)."""
        m, V, s, sig, phi = self.m, self.V, self.s, self.sig, self.phi
        # 1 + (d ln D/dV) sV + (d ln D/ds) sS = 0, two real equations (D divided out).
        L = self.family.log_derivatives(1j * (-phi * m * V + sig * s), m, V)
        with np.errstate(invalid="ignore", divide="ignore", over="ignore"):
            ds = 1j * sig * L[..., 0]
            dv = L[..., 1] - 1j * phi * m * L[..., 0]
            det = dv.real * ds.imag - dv.imag * ds.real
            sV = -ds.imag / det
            sS = dv.imag / det
        # Derivatives not finite: M singular, D = 0 at the point itself (a root to the
        # last bit), no step.  Finite derivatives (D != 0) whose step is not finite (a
        # singular 2 x 2 system): the point given up, not converged.
        ok = np.isfinite(sV) & np.isfinite(sS)
        failed = ~ok & np.isfinite(L).all(axis=-1)
        sV = np.where(ok, sV, 0.0)
        sS = np.where(ok, sS, 0.0)
        # Damped: a step changes the speed by at most a factor 1.5.
        sV = np.clip(sV, -V / 3.0, 0.5 * V)
        sS = np.clip(sS, -2.0 * (1.0 + np.abs(s)), 2.0 * (1.0 + np.abs(s)))
        self.V = V = V + sV
        self.s = s = s + sS
        # Converged: both steps at rounding, small and no longer falling, or small
        # after quadratic convergence (_settled).
        size = np.maximum(np.abs(sV) / V, np.abs(sS) / (1.0 + np.abs(s)) * 1e-2)
        self.done = ((size <= 1e-13) | ((size <= 1e-10) & (size > 0.3 * self.last))
                     | _settled(size, self.last)) & ~failed
        self.stop |= failed
        self.last = size
        self.it = self.it + 1


def raw_seeds(family, m, speed, points=None, count=SEEDS):
    """The depth discretisation's ``count`` rightmost eigenvalues off the half-planes'
    continuous spectra (unpolished; ``points`` per body, default :data:`SEED_POINTS`)."""
    seeds = layup_modes(family.layup, m, speed, SEED_POINTS if points is None else points)
    return seeds[~family.in_continuum(seeds, m, speed)][:count]


def _polish(family, m, speed, b0, reach=None, within=None):
    """Newton's method on the dispersion function from the guesses ``b0``, each in the
    frame it is nearer to rest in (:func:`pattern_frame`: there a mode at rest on a
    body is a number of size ``kappa m^2``, resolved to rounding, not a frequency near
    ``m V``).  Returns the roots (NaN where Newton's method failed, ran farther than
    ``reach`` from its guess, default half the guess in that frame plus ``10 kappa
    m^2``, or ended on a half-plane's branch cut), the frames, and each root's
    ``db/dV`` (:func:`_speed_slope`) from the logarithmic derivatives of the last
    iteration, whose step moved the root by less than its rounding-level tolerance.
    ``within = (r0, floor)``: the speed scan's test of a step, each root to land within
    ``0.2 max(r0, |Re b|) + floor`` of its guess; all NaN as soon as one surely will
    not (its distance from the guess, less twice its latest step, beyond that with
    ``|Re b|`` twice its latest step larger; the steps at least halving, so that less
    than the latest step is left to go), or one is given up."""
    b0 = np.atleast_1d(np.asarray(b0, dtype=complex))
    scale = max(family.scale(m), 1e-300)
    phi = pattern_frame(m, speed, b0.imag)
    shift = 1j * phi * m * speed
    z0 = b0 + shift
    last = np.full(b0.shape + (2,), np.nan, dtype=complex)

    def log_derivative(z, act):
        last[act] = family.log_derivatives(z - shift[act], m, speed)
        return last[act, 0]

    abandon = None
    if within is not None:
        r0, floor = within

        def abandon(z, step, last):
            if np.isnan(z).any():
                return True
            sure = np.isfinite(step) & (step <= 0.5 * last)
            off = np.abs(z - z0) - 2.0 * step
            far = off > 0.2 * np.maximum(r0, np.abs((z - shift).real) + 2.0 * step) + floor
            return bool(np.any(sure & far))

    roots, ok = newton_roots(log_derivative, z0, scale, abandon=abandon)
    lim = 0.5 * np.abs(z0) + 10.0 * scale if reach is None else reach
    b = roots - shift
    good = ok & (np.abs(roots - z0) <= lim) & ~family.on_cut(b, m, speed)
    with np.errstate(invalid="ignore", divide="ignore"):
        slope = np.where(good, -last[:, 1] / last[:, 0], np.nan)
    return np.where(good, b, np.nan), phi, slope


def _seeds_followed(family, m, speed, seeds, b):
    """Which of the discretisation's ``seeds`` are plainly the followed modes ``b``
    (polished, at ``speed``): each alone within :data:`SEED_MATCH` of one of them in
    the same frame (:func:`pattern_frame`), in units of that mode's size there plus
    ``kappa m^2``, and that mode near no other seed.  Two seeds near one mode (a mode
    not followed beside it) are both polished; a seed of a mode not followed is taken
    for a followed one only where that one's own seed is missing."""
    if not (seeds.size and b.size):
        return np.zeros(seeds.shape, dtype=bool)
    band = SEED_MATCH * _frame_size(family, m, speed, b)
    near = ((np.abs(seeds[:, None] - b[None, :]) <= band)
            & (pattern_frame(m, speed, seeds.imag)[:, None] == pattern_frame(m, speed, b.imag)))
    return (near.sum(axis=1) == 1) & (near.sum(axis=0)[np.argmax(near, axis=1)] == 1)


def _frame_size(family, m, speed, b):
    """The size of each ``b`` in the frame it is nearer to rest in, ``|b + i phi m V|``
    (:func:`pattern_frame`), plus ``kappa m^2``: the scale of its rounding and of its
    distance from another root."""
    b = np.asarray(b, dtype=complex)
    return np.abs(b + 1j * pattern_frame(m, speed, b.imag) * m * speed) + family.scale(m)


def _unique(family, m, b):
    """The finite roots ``b``, by decreasing real part, each once."""
    scale = family.scale(m)
    b = np.asarray(b, dtype=complex)
    b = b[np.isfinite(b)]
    out = []
    for r in b[np.argsort(-b.real, kind="stable")]:
        if all(abs(r - x) > 1e-8 * (abs(r) + scale) for x in out):
            out.append(complex(r))
    return np.array(out, dtype=complex)


def _cubic_peak(lo, hi):
    """``ln V`` of the maximum of the cubic in ``ln V`` through the real parts of ``b``
    and of its slope ``d b/d ln V = V db/dV`` at ``lo = (V, b, db/dV)`` (rising) and
    ``hi`` (falling), kept a hundredth of the bracket inside it."""
    ua, ub = math.log(lo[0]), math.log(hi[0])
    H = ub - ua
    fa, fb = lo[1].real, hi[1].real
    da, db = H * lo[0] * lo[2].real, H * hi[0] * hi[2].real     # slopes in t = (u - ua)/H
    # The cubic's slope a t^2 + b t + c: positive at t = 0, negative at 1, one root.
    a = 6.0 * (fa - fb) + 3.0 * (da + db)
    b = -6.0 * (fa - fb) - 4.0 * da - 2.0 * db
    c = da
    if abs(a) <= 1e-12 * (abs(b) + abs(c)):
        t = -c / b
    else:
        sq = math.sqrt(max(b * b - 4.0 * a * c, 0.0))
        # The root without cancellation, then the other from their product c/a.
        r1 = (-b - math.copysign(sq, b)) / (2.0 * a)
        r2 = c / (a * r1) if r1 != 0.0 else -b / a
        t = r1 if 0.0 <= r1 <= 1.0 else r2
    t = min(max(t, 0.01), 0.99) if math.isfinite(t) else 0.5
    return ua + t * H


def _hermite(lo, hi, t):
    """The cubic in ``V`` through ``b`` and ``db/dV`` at ``lo = (V, b, db/dV)`` and ``hi``,
    at ``V = V_lo + t (V_hi - V_lo)``."""
    (va, ba, sa), (vb, bb, sb) = lo, hi
    h = vb - va
    return ((2 * t - 3) * t * t + 1) * ba + ((t - 2) * t + 1) * t * h * sa + (
        (3 - 2 * t) * t * t * bb + (t - 1) * t * t * h * sb)


def _hermite_zero(lo, hi):
    """Where the cubic of :func:`_hermite` has ``Re b = 0`` (``Re b`` of opposite signs at
    ``lo`` and ``hi``), and ``b`` there on it: ``(V, b)``, its zero inside the bracket
    nearest the secant's (the secant's own where rounding leaves none strictly inside,
    or the coefficients are not finite)."""
    (va, ba, sa), (vb, bb, sb) = lo, hi
    h = vb - va
    fa, fb, da, db = ba.real, bb.real, h * sa.real, h * sb.real
    secant = fa / (fa - fb)
    # The cubic's coefficients in t (Hermite's basis expanded), highest first.
    coef = [2 * fa - 2 * fb + da + db, -3 * fa + 3 * fb - 2 * da - db, da, fa]
    with np.errstate(all="ignore"):
        roots = np.roots(coef) if np.all(np.isfinite(coef)) else np.array([])
    inside = [r.real for r in roots if abs(r.imag) <= 1e-12 and 0.0 < r.real < 1.0]
    t = min(inside, key=lambda r: abs(r - secant)) if inside else secant
    return va + t * h, complex(_hermite(lo, hi, t))


def _peak_bound(lo, hi):
    """An upper bound of the largest ``Re b`` of one mode between the speeds of ``lo =
    (V, b, db/dV)`` (``Re b`` rising) and ``hi`` (falling), on the scan's assumption
    that its growth rate changes on no scale of speed far shorter than the step
    control's: ``max(r_lo, r_hi) + PEAK_RISE max(r'_lo, -r'_hi) H``, ``r' = d Re b/d
    ln V`` and ``H`` the bracket's width in ``ln V`` (docs/derivation.md, L15; where
    ``Re b`` is concave on the bracket its maximum is below ``max(r_lo, r_hi) +
    min(r'_lo, -r'_hi) H``); NaN where a value or slope is not finite (no bound: the
    maximum is located)."""
    H = math.log(hi[0]) - math.log(lo[0])
    # np.fmax would drop a NaN; Python's max would keep or drop it by its place.
    values = (lo[1].real, hi[1].real, lo[0] * lo[2].real, -hi[0] * hi[2].real)
    if not all(math.isfinite(v) for v in values):
        return math.nan
    return max(values[:2]) + PEAK_RISE * max(values[2:]) * H


def _speed_slope(family, m, speed, b):
    """``db/dV`` of each root ``b`` at ``speed``: ``-D_V/D_b`` of the dispersion function
    ``D`` (implicit differentiation), in closed form (:meth:`Layered.log_derivatives`)."""
    b = np.asarray(b, dtype=complex)
    L = family.log_derivatives(b, m, speed)
    with np.errstate(invalid="ignore", divide="ignore"):
        return -L[..., 1] / L[..., 0]


def _follow(family, m, v0, b0, slope0, v1, step=False):
    """The root ``b0`` (slope ``slope0`` at ``v0``) at the speed ``v1``: predicted along
    its tangent and polished (NaN where Newton's method fails); the prediction; and
    the root's slope at ``v1`` (:func:`_polish`).  ``step``: a step of the speed scan,
    which is refused unless every root lands within a fifth of ``max(|Re b0|, |Re
    b1|)`` of its prediction: all NaN as soon as one surely will not."""
    pred = b0 + (v1 - v0) * slope0
    scale = family.scale(m)
    reach = 0.5 * np.abs(pred - b0) + 0.5 * np.abs(b0.real) + 10.0 * scale
    within = (np.abs(b0.real), 1e-9 * scale) if step else None
    b1, _, slope1 = _polish(family, m, v1, pred, reach, within)
    return b1, pred, slope1


def unstable_count(family, m, speed, points=48):
    """The number of growing modes at one wavenumber and speed, by the argument
    principle, and whether the count is reliable (L15).

    ``D(b) = det M(b)/det M_0(b)`` (:meth:`Layered.dispersion_ratio`: ``M`` with and
    without the frictional heat) has the modes as zeros,
    no pole in ``Re b >= 0`` (those of ``det M_0`` are free thermal modes, which
    decay) and tends to 1 as ``|b| -> inf`` there; so the number of its zeros in
    ``Re b > 0`` is minus its winding along the imaginary axis, ``-Delta arg D/(2
    pi)`` for ``omega`` from ``-inf`` to ``inf``.  The frequencies: ``points`` per
    decade-spaced side about each body's frame (``0`` and ``-m V``), from ``1e-4``
    times the smallest rate (``kappa m^2``, ``kappa/h^2``, ``m V``) to ``1e6`` times
    the largest (a point closer to the one before it than :data:`COUNT_MERGE` of the
    spacing there left out: far from both frames their points pair up), each step
    refined (cut into about ``|Delta arg|/0.25`` parts a round) until the argument
    changes by less than 0.25.

    Returns
    -------
    (int, bool)
        The count, and whether it is reliable: the steps resolved, the winding an
        integer to 1e-6, ``D`` within 0.05 of 1 at both ends.
    """
    layup = family.layup
    rates = [m * speed] if speed > 0.0 else []
    for body in layup.bodies:
        if body.conducts:
            rates.append(body.material.k * m * m)
            if body.thickness is not None:
                rates.append(body.material.k / body.thickness ** 2)
    lo, hi = min(rates) * 1e-4, max(rates) * 1e6
    side = np.geomspace(lo, hi, points)
    centres = {-m * speed if body.moving else 0.0 for body in layup.bodies}
    w = np.concatenate([c + np.concatenate([-side[::-1], [0.0], side]) for c in centres]
                       + [[-1e3 * hi - m * speed, 1e3 * hi]])
    w = np.unique(w)
    if len(centres) > 1:
        # Far from both frames (|omega| >> m V) their points come in pairs closer than
        # a hundredth of the grid's spacing there: the first of each pair only.
        near = np.min([np.abs(w[1:] - c) for c in centres], axis=0)
        spacing = (side[1] / side[0] - 1.0) * np.maximum(near, lo)
        w = w[np.concatenate([[True], np.diff(w) > COUNT_MERGE * spacing])]

    def ratio(w):
        return family.dispersion_ratio(1j * w, m, speed)

    D = ratio(w)
    resolved = False
    for _ in range(60):
        step = np.angle(D[1:] / D[:-1])
        bad = ~(np.abs(step) <= 0.25)
        if not bad.any():
            resolved = True
            break
        # Each unresolved step cut into about |step|/0.25 parts (2 to 16; a root near
        # the axis turns the argument by about pi however short the step, until it is
        # resolved): a few rounds of evaluations instead of one per halving.
        idx = np.flatnonzero(bad)
        with np.errstate(invalid="ignore"):
            parts = np.clip(np.nan_to_num(np.ceil(np.abs(step[idx]) / 0.25), nan=2.0), 2, 16)
        parts = parts.astype(int)
        at = np.repeat(idx, parts - 1)
        frac = (np.arange(at.size) - np.repeat(np.cumsum(parts - 1) - (parts - 1), parts - 1)
                + 1) / np.repeat(parts, parts - 1)
        new = w[at] + frac * (w[at + 1] - w[at])
        w = np.insert(w, at + 1, new)
        D = np.insert(D, at + 1, ratio(new))
    total = np.sum(np.angle(D[1:] / D[:-1])) + np.angle(D[0]) - np.angle(D[-1])
    n = -total / (2.0 * math.pi)
    count = int(round(n)) if np.isfinite(n) else -1
    ends = abs(D[0] - 1.0) < 0.05 and abs(D[-1] - 1.0) < 0.05
    return count, bool(resolved and ends and abs(n - count) < 1e-6)


#: The count's frequencies: a point closer than this fraction of the grid's spacing
#: (about the nearer frame) to the point before it is left out (:func:`unstable_count`).
COUNT_MERGE = 1e-2
#: The speed scan's steps: at most this factor, at least ``1 + MIN_STEP``.
MAX_RATIO = 4.0
MIN_STEP = 1e-6
#: After an accepted step the next is made larger (by at most 2 in its excess over 1) so
#: that the followed modes are predicted to land within this fraction of their band
#: (the tangent's error growing as the square of the step); never smaller.
STEP_TARGET = 0.7
#: Speeds of a scan between two reseedings from the depth discretisation (a factor).
RESEED = 4.0
#: A reseeding's seed within this fraction of a followed mode's size (in the mode's
#: frame, plus ``kappa m^2``), in that frame and alone there, is taken for that mode and
#: not polished (:func:`_seeds_followed`).
SEED_MATCH = 1e-2
#: An interior maximum of a growth rate is located only where it may reach 0: where
#: rising at this many times the steeper of the slopes at its bracket's ends, over the
#: whole bracket, it would (:func:`_peak_bound`).
PEAK_RISE = 4.0


@dataclass(frozen=True)
class SpeedScan:
    """Every neutral crossing of a family at one wavenumber up to a speed, and what the
    scan that found them checked (:func:`speed_scan`, L15).

    Attributes
    ----------
    crossings : tuple of (float, float, int)
        ``(V, omega, direction)``: the speed, m/s, the neutral frequency, rad/s (the
        crest's speed relative to the counterface is ``-omega/m``), and +1 where a
        mode starts to grow with the speed, -1 where it stops; by speed.
    speeds : int
        Speeds of the scan (grid points accepted).
    counts : int
        Speeds at which the growing modes were counted (argument principle).
    certified : bool
        Every count reliable and equal to the number of growing modes followed.
    maxima : int
        Interior maxima of a mode's growth rate between two speeds (each located
        unless it surely stays below 0, :data:`PEAK_RISE`).
    start, end : float
        The speeds the scan started from (where no mode grows; a mode growing at
        1e-9 m/s, the lowest speed studied, gives that speed as an upper bound of
        the critical speed, ``certified`` False) and reached, m/s.
    """

    crossings: tuple
    speeds: int
    counts: int
    certified: bool
    maxima: int
    start: float
    end: float

    @property
    def first(self):
        """The lowest upward crossing ``(V, omega)``, or None."""
        up = [c for c in self.crossings if c[2] > 0]
        return (up[0][0], up[0][1]) if up else None


def speed_scan(family, m, v_high=1e4, v_low=None, every=False, beyond=1.0):
    """The neutral crossings of a family at wavenumber ``m`` from the lowest speed up
    to ``v_high``: up to ``beyond`` times the first upward one, or ``every`` one; by
    following its rightmost modes in speed (L15).

    From the lowest speed (:meth:`Layered.lowest_speed`, lowered by factors 8 while a
    mode grows there), the modes (:meth:`Layered.modes`) are followed by Newton's
    method from speed to speed, each predicted along its tangent ``db/dV`` (implicit
    differentiation).  A step (a factor at most :data:`MAX_RATIO`) is accepted only if
    every followed mode lands within a fifth of its distance from the imaginary axis
    of its prediction, otherwise halved (in the factor's excess over 1); after an
    accepted step the excess grows by up to 2, less where a mode came near its band's
    edge (:data:`STEP_TARGET`).  On each step, for each mode: a change of sign of
    ``Re b`` is a crossing (Newton's method on the neutral point from the zero of the
    cubic through the step's ends, kept if the mode followed there lands on it; else
    Brent's method on ``Re b(V)``, the mode followed from the nearest point known,
    first); an interior maximum (``dRe b/dV`` positive at the step's start, negative
    at its end) is located where that slope vanishes, unless the values and slopes at
    the step's ends show that it stays below 0 (:data:`PEAK_RISE`; docs/derivation.md,
    L15), and where it reaches 0 it is a window of growth (two crossings).  At every
    accepted speed the growing modes are counted by the argument principle
    (:func:`unstable_count`); where the count exceeds the followed modes that grow,
    and every :data:`RESEED` in speed, the modes are reseeded (the latter polishing
    only the seeds that are not plainly followed modes, :data:`SEED_MATCH`), and a
    new one is followed back over the step.

    Returns
    -------
    SpeedScan
        ``certified`` where every count was reliable and equal to the followed modes
        that grow.  Not excluded: a window inside one step of a mode whose growth rate
        turns twice within it, or of a mode followed at neither end of it (one whose
        seed a reseeding took for a followed mode beside it, that one's own seed
        missing, among them) (docs/derivation.md, L15).
    """
    from scipy.optimize import brentq, minimize_scalar

    m = float(m)
    scale = family.scale(m)
    v = family.lowest_speed(m) if v_low is None else float(v_low)
    while True:
        b = family.modes(m, v)
        n, sure = unstable_count(family, m, v)
        grows = n > 0 or (len(b) and b[0].real > 0.0)
        if not grows or v <= 1e-9:
            break
        v = max(v / 8.0, 1e-9)
    if grows:
        # Growing at the lowest speed studied: that speed, an upper bound.
        w = float(b[0].imag) if len(b) else math.nan
        return SpeedScan(((v, w, 1),), 1, 1, False, 0, v, v)
    start = v
    b = _unique(family, m, b)
    slope = _speed_slope(family, m, v, b)
    crossings, counts, certified, maxima, speeds = [], 1, sure, 0, 1
    ratio, seeded = MAX_RATIO, v

    def growth(ends):
        """b(V) of one mode, followed from the nearest of ``ends``, the points ``(V, b,
        db/dV)`` known on its path (NaN where no follow lands): first predicted by
        the cubic through the nearest known on either side (their values and
        slopes), then along the tangent of each in turn.  ``f(x, True)``: also its
        ``db/dV`` there (:func:`_polish`)."""
        def f(x, with_slope=False):
            r, sl = _along(x)
            return (r, sl) if with_slope else r

        def _along(x):
            below = [e for e in ends if e[0] < x]
            above = [e for e in ends if e[0] > x]
            if below and above:
                lo, hi = max(below, key=lambda e: e[0]), min(above, key=lambda e: e[0])
                t = (x - lo[0]) / (hi[0] - lo[0])
                pred = _hermite(lo, hi, t)
                b0_ = lo[1] if t < 0.5 else hi[1]
                reach = 0.5 * abs(pred - b0_) + 0.5 * abs(b0_.real) + 10.0 * scale
                r, _, sl = _polish(family, m, x, np.array([pred]), reach)
                if np.isfinite(r[0]):
                    return r[0], sl[0]
            for v0, b0_, s0_ in sorted(ends, key=lambda e: abs(math.log(x / e[0]))):
                r, _, sl = _follow(family, m, v0, np.array([b0_]), np.array([s0_]), x)
                if np.isfinite(r[0]):
                    return r[0], sl[0]
            return complex(math.nan), complex(math.nan)
        return f

    def peak(ends):
        """The largest Re b of one mode between the speeds of ``ends`` (the real part of
        its slope positive at the first, negative at the second): where that real
        part vanishes, in ln V to 1e-7, each speed followed from the nearest point
        known on the path.  Each trial speed: the secant of the slope's real part
        through the two latest points if it falls inside the bracket, else the
        maximum of the cubic through the values and slopes at the bracket's ends
        (:func:`_cubic_peak`); if that does not settle in 8 steps, Brent's method on
        the bracket; where a follow fails, bounded maximisation of Re b.  Returns the
        speed, Re b there and the points known; or, as soon as the bracket shows that
        the maximum stays below 0 (:func:`_peak_bound`), NaN, that bound and the
        points known (the maximum not located: no window there)."""
        known = list(ends)

        def slope(x):
            for v0, _, s0_ in known:
                if x == math.log(v0):
                    return s0_.real
            V = math.exp(x)
            r, sl = growth(known)(V, True)
            if not np.isfinite(sl):
                raise FloatingPointError
            known.append((V, r, sl))
            return sl.real

        try:
            lo, hi = ends
            for _ in range(8):
                bound = _peak_bound(lo, hi)
                if bound < 0.0:
                    return math.nan, bound, known
                x = _cubic_peak(lo, hi)
                if len(known) > 3:
                    # The secant of the slope through the two latest points, if inside.
                    (v0, _, s0_), (v1, _, s1_) = known[-2:]
                    u0, u1 = math.log(v0), math.log(v1)
                    d0, d1 = v0 * s0_.real, v1 * s1_.real
                    xs = u1 - d1 * (u1 - u0) / (d1 - d0) if d1 != d0 else math.nan
                    if math.log(lo[0]) < xs < math.log(hi[0]):
                        x = xs
                last = known[-1]
                if len(known) > 2 and abs(x - math.log(last[0])) <= 1e-7:
                    return last[0], last[1].real, known
                d = slope(x)
                if d == 0.0:
                    return known[-1][0], known[-1][1].real, known
                lo, hi = (known[-1], hi) if d > 0.0 else (lo, known[-1])
            # ln V to 1e-7, as the maximisation below: Re b there to rounding.
            top = math.exp(brentq(slope, math.log(lo[0]), math.log(hi[0]),
                                  xtol=1e-7, rtol=1e-15))
            rate = growth(known)(top).real
            if np.isfinite(rate):
                return top, rate, known
        except (FloatingPointError, RuntimeError):
            pass
        f = growth(ends)
        res = minimize_scalar(lambda x: -np.nan_to_num(f(math.exp(x)).real, nan=-np.inf),
                              bounds=(math.log(ends[0][0]), math.log(ends[1][0])),
                              method="bounded", options={"xatol": 1e-7})
        return math.exp(res.x), -res.fun, ends

    def locate(ends, va, vb, direction, step=False):
        f = growth(ends)
        if step:
            # A step's crossing (``ends`` its two ends): the neutral point straight from
            # the cubic through them, kept if it lies inside the step on this mode's
            # path (the mode followed there is it); else Brent's method on Re b(V) first.
            vg, bg = _hermite_zero(ends[0], ends[1])
            V, w, ok = neutral_point(family, m, vg, bg.imag) if np.isfinite(bg) else (
                math.nan, math.nan, False)
            if ok and va < V < vb:
                on = f(float(V))
                if np.isfinite(on) and abs(on - 1j * w) <= 1e-8 * _frame_size(
                        family, m, V, 1j * w):
                    return (float(V), float(w), direction)
        seen = {}                          # b at the speeds Brent's method tried

        def g(x):
            if x not in seen:
                seen[x] = f(x)
            r = seen[x].real
            # Unfollowed: the sign of the nearer end, so that Brent's method stays in
            # the bracket (the neutral point is then polished independently).
            return r if np.isfinite(r) else (-1.0 if (x - va) < (vb - x) else 1.0) * \
                direction * scale
        vc = brentq(g, va, vb, xtol=1e-300, rtol=1e-11, maxiter=200)
        bc = seen[vc] if vc in seen else f(vc)
        w0 = bc.imag if np.isfinite(bc) else ends[0][1].imag * vc / ends[0][0]
        V, w, ok = neutral_point(family, m, vc, w0)
        if ok and abs(V - vc) <= 1e-7 * vc:
            return (float(V), float(w), direction)
        return (float(vc), float(w0), direction)

    def limit():
        up = [c[0] for c in crossings if c[2] > 0]
        return v_high if every or not up else min(v_high, beyond * min(up))

    while v < limit():
        v1 = min(v * ratio, limit())
        if b.size:
            # A step that would be refused ends as soon as that is sure (not at the
            # smallest step, which goes on with the roots as they land).
            b1, pred, s1 = _follow(family, m, v, b, slope, v1, step=ratio - 1.0 > MIN_STEP)
            err = np.abs(b1 - pred)
            tol = 0.2 * np.maximum(np.abs(b.real), np.abs(b1.real)) + 1e-9 * scale
            fine = np.isfinite(b1) & (err <= tol)
            if not fine.all() and ratio - 1.0 > MIN_STEP:
                ratio = 1.0 + 0.5 * (ratio - 1.0)
                continue
            # How much of its band the mode nearest its band's edge used.
            used = float(np.max(err / tol, initial=0.0)) if fine.all() else 1.0
        else:
            b1, s1 = b, slope
            used = 0.0
        # Two modes followed onto one root: the root once.
        keep = np.isfinite(b1)
        for k in range(b1.size):
            if keep[k] and any(keep[j] and abs(b1[k] - b1[j]) <= 1e-8 * (abs(b1[k]) + scale)
                               for j in range(k)):
                keep[k] = False
        b0, s0, b1, s1 = b[keep], slope[keep], b1[keep], s1[keep]
        for k in range(b1.size):
            r0, r1 = b0[k].real, b1[k].real
            if (r0 < 0.0) != (r1 < 0.0):
                ends = [(v, b0[k], s0[k]), (v1, b1[k], s1[k])]
                crossings.append(locate(ends, v, v1, 1 if r1 >= 0.0 else -1, step=True))
            elif r0 < 0.0 and s0[k].real > 0.0 and s1[k].real < 0.0:
                maxima += 1
                top, rate, known = peak([(v, b0[k], s0[k]), (v1, b1[k], s1[k])])
                if rate >= 0.0:
                    crossings.append(locate(known, v, top, 1))
                    crossings.append(locate(known, top, v1, -1))
        # Count the growing modes; reseed from the discretisation where the count
        # exceeds those followed, and every RESEED in speed.
        counts += 1
        n, sure = unstable_count(family, m, v1)
        every_growing_followed = n == int(np.sum(b1.real > 0.0))
        if not every_growing_followed or v1 >= RESEED * seeded:
            seeds = raw_seeds(family, m, v1)
            if every_growing_followed:
                # Every growing mode followed (a reseeding for the modes yet to grow):
                # a seed that is plainly a followed mode's needs no polishing.
                seeds = seeds[~_seeds_followed(family, m, v1, seeds, b1)]
            fresh = [x for x in family.modes(m, v1, seeds=seeds)
                     if all(abs(x - y) > 1e-8 * (abs(x) + scale) for y in b1)]
            if fresh:
                # A mode not followed so far: its value at v, for the step's checks.
                fresh = np.array(fresh)
                fs = _speed_slope(family, m, v1, fresh)
                back = _follow(family, m, v1, fresh, fs, v)[0]
                for k in range(fresh.size):
                    r1 = fresh[k].real
                    if np.isfinite(back[k]) and (back[k].real < 0.0) != (r1 < 0.0):
                        bs = _speed_slope(family, m, v, back[k:k + 1])[0]
                        ends = [(v, back[k], bs), (v1, fresh[k], fs[k])]
                        crossings.append(locate(ends, v, v1, 1 if r1 >= 0.0 else -1,
                                                step=True))
                b1 = np.concatenate([b1, fresh])
                s1 = np.concatenate([s1, fs])
            seeded = v1
        certified &= sure and n == int(np.sum(b1.real > 0.0))
        order = np.argsort(-b1.real, kind="stable")
        b, slope = b1[order], s1[order]
        v = v1
        speeds += 1
        # Not straight back to a step that would be refused (STEP_TARGET).
        grow = 2.0 if used <= STEP_TARGET / 4.0 else max(1.0, math.sqrt(STEP_TARGET / used))
        ratio = min(1.0 + grow * (ratio - 1.0), MAX_RATIO)
    crossings.sort()
    if not every:
        first = [c for c in crossings if c[2] > 0][:1]
        crossings = [c for c in crossings if not first or c[0] <= beyond * first[0][0]]
    return SpeedScan(tuple(crossings), speeds, counts, bool(certified), maxima, start, float(v))


def first_crossing(family, m, v_low=None, v_high=1e4):
    """The lowest speed at which a mode of wavenumber ``m`` grows
    (:func:`speed_scan`), and the neutral growth rate ``b = i omega`` there;
    ``(None, None)`` if none grows below ``v_high``.  A mode growing at 1e-9 m/s, the
    lowest speed studied, gives that speed (an upper bound) and that mode.

    Returns
    -------
    (float, complex) or (None, None)
        The critical speed, m/s, and ``i omega``, 1/s.
    """
    first = speed_scan(family, m, v_high, v_low).first
    return (None, None) if first is None else (first[0], 1j * first[1])


def continue_step(family, m0, point, m1, depth=0):
    """The neutral point at ``m1`` continued from ``point = (V, omega)`` at ``m0``:
    Newton's method from the same speed and frequency in the pattern's frame
    (:func:`neutral_point`), accepted if it converges within a factor 2 of the speed;
    otherwise the interval is halved (in ``ln m``, at most 8 times)."""
    return continue_steps(family, [m0], [point], [m1], depth)[0]


def continue_steps(family, m0, points, m1, depth=0):
    """:func:`continue_step` for several independent steps ``m0[j] -> m1[j]`` from
    ``points[j]``, all iterated together, each at its own pace (:class:`_Continuation`);
    a list of ``(V, omega)`` or None."""
    m0 = np.asarray(m0, dtype=float)
    m1 = np.asarray(m1, dtype=float)
    out = [None] * m0.size
    steps = _Continuation(family)
    for j in range(m0.size):
        steps.start(m0[j], points[j], m1[j], lambda point, j=j: out.__setitem__(j, point),
                    depth)
    while steps.step():
        pass
    return out


class _Continuation:
    """Steps of :func:`continue_step`, any number, each with its halvings, iterated
    together: each first attempt's neutral point by Newton's method
    (:class:`_NeutralNewton`, every point still going in one request), a step that
    fails cut in two (in ``ln m``, at most 8 times) and continued as its own steps; a
    new step may start at any time.  Each step's point is the one it has alone."""

    def __init__(self, family):
        self.family = family
        self.newton = _NeutralNewton(family)

    def start(self, m0, point, m1, then, depth=0):
        """The step ``m0 -> m1`` from ``point = (V, omega)``; ``then(result)`` is told its
        ``(V, omega)``, or None."""
        v0, w0 = point
        # Predicted: the same speed and the same frequency in the pattern's frame, in
        # units of kappa m^2.
        phi = pattern_frame(m0, v0, w0)
        s = (w0 + phi * m0 * v0) / self.family.scale(m0)
        self.newton.add([m1], [v0], [-phi * m1 * v0 + s * self.family.scale(m1)],
                        [(m0, point, m1, depth, then)])

    def step(self):
        """Finish the attempts that have ended (halving those that failed), then one
        iteration of the others; False once none is left."""
        while True:
            ended = self.newton.finished()
            if not ended:
                break
            for (m0, point, m1, depth, then), v, w, ok in ended:
                if ok and 0.5 * point[0] < v < 2.0 * point[0]:
                    then((float(v), float(w)))
                elif depth >= 8:
                    then(None)
                else:
                    mid = math.sqrt(m0 * m1)
                    self.start(m0, point, mid, self._second_half(mid, m1, depth, then),
                               depth + 1)
        if not self.newton.size:
            return False
        self.newton.iterate()
        return True

    def _second_half(self, mid, m1, depth, then):
        def half(point):
            if point is None:
                then(None)
            else:
                self.start(mid, point, m1, then, depth + 1)
        return half


def continue_neutral(family, wavenumbers, anchor=None, scan_every=None, progress=None):
    """The critical speed and neutral ``omega`` along sorted wavenumbers
    (:func:`neutral_curves` of one family).

    Returns
    -------
    (V, omega) : ndarrays
        NaN where no mode grows below the scan's end.
    """
    return neutral_curves([family], wavenumbers, [anchor], scan_every, progress)[0]


def _evaluate(key, payloads):
    """The answers to one kind of request of :meth:`Layered.dispersion`,
    :meth:`Layered.log_derivatives` or :meth:`Layered.dispersion_ratio` (``key = (kind,
    group)``: the layup, or a token of its
    :func:`~thermocontact.physics.tei_layers.field_group`), each payload ``(layup, b,
    m, V)`` broadcast: all their points in one call, each point's value as alone;
    ``("wait", None)``: nothing (a computation waiting for a round to pass)."""
    kind = key[0]
    if kind == "wait":
        return [None] * len(payloads)
    shapes, bs, ms, vs, which, layups = [], [], [], [], [], {}
    for layup, b, m, v in payloads:
        b = np.asarray(b, dtype=complex)
        if np.ndim(m) or np.ndim(v):
            b, m, v = np.broadcast_arrays(b, np.asarray(m, dtype=float),
                                          np.asarray(v, dtype=float))
        shapes.append(b.shape)
        bs.append(b.ravel())
        ms.append(m)
        vs.append(v)
        which.append(layups.setdefault(id(layup), (len(layups), layup))[0])
    sizes = [part.size for part in bs]
    b, m, v = np.concatenate(bs), _spread(ms, sizes), _spread(vs, sizes)
    layups = [lay for _, lay in layups.values()]
    if kind == "dispersion":
        out = layup_dispersion(layups[0], b, m, v)
    else:
        func = dispersion_ratio if kind == "ratio" else dispersion_log_derivatives
        if len(layups) == 1:
            out = func(layups[0], b, m, v)
        else:
            out = func(layups, b, m, v, which=np.repeat(which, sizes))
    ends = np.cumsum(sizes).tolist()
    return [out[end - size:end].reshape(shape + out.shape[1:])
            for end, size, shape in zip(ends, sizes, shapes)]


def _spread(values, sizes):
    """The payloads' ``values`` (each a number, or an array of its points) as one
    array of all the points."""
    if all(np.ndim(x) == 0 for x in values):
        return np.repeat(np.array(values, dtype=float), sizes)
    return np.concatenate([np.full(n, x, dtype=float) if np.ndim(x) == 0 else x.ravel()
                           for x, n in zip(values, sizes)])


def neutral_curves(families, wavenumbers, anchors=None, scan_every=None, progress=None):
    """The critical speed and neutral ``omega`` of each family along sorted wavenumbers
    (L15).

    At every ``scan_every``-th wavenumber (default :data:`SCAN_EVERY`; the first and
    the last included) a scan from the lowest speed (:func:`speed_scan`) finds the
    critical speed; the neutral point found there (and ``anchors[k] = (m, V,
    omega)``, a neutral point of family ``k`` already found by a scan) is continued
    both ways by Newton's method (:func:`continue_step`) to the next scanned
    wavenumber, or until it fails (a fold of the branch, where a window of growth
    closes).  At each wavenumber the lowest of the points reaching it is kept: a
    branch that is the lowest at a scanned wavenumber is followed over both
    neighbouring intervals, so a lower branch is missed only if it is nowhere the
    lowest at a scanned wavenumber.

    The scans of every family and wavenumber, and one computation per family that
    continues its neutral points (:class:`_Continuation`: every step of every chain
    iterated together, each at its own pace, a scan's chains joining as it ends), run
    together
    (:func:`~thermocontact.execution.lockstep.run_lockstep`): each runs until it
    needs the dispersion function (or the count's ratio), and the points all of them
    need are evaluated in one call per family, each as it would be alone; so the
    curves are those of the scans and continuations run one by one (each wavenumber
    keeps the lowest point, whichever reaches it first).  ``progress(done, total)``,
    if given, is told as each scan ends and at the end (the continuations the last of
    ``total``).

    Returns
    -------
    list of (V, omega) : ndarrays
        Per family; NaN where no mode grows below the scan's end.
    """
    ms = np.asarray(wavenumbers, dtype=float)
    n = ms.size
    every = SCAN_EVERY if scan_every is None else scan_every
    scanned = sorted(set(range(0, n, every)) | {n - 1})
    anchors = [None] * len(families) if anchors is None else list(anchors)
    jobs = [(k, j) for k, anchor in enumerate(anchors) for j in scanned
            if anchor is None or ms[j] != anchor[0]]
    total = len(jobs) + 1
    tell = progress or (lambda done, total: None)
    tell(0, total)
    ended = []
    V = [np.full(ms.shape, np.inf) for _ in families]
    W = [np.full(ms.shape, np.nan) for _ in families]

    def keep(k, i, point):
        if point[0] < V[k][i]:
            V[k][i], W[k][i] = point

    # Each family's neutral points, from its scans as they end (and its anchor), are
    # continued by one computation that iterates all their steps together, while the
    # scans still go on: their requests share the scans' rounds.
    starts = [[] for _ in families]
    scanning = [sum(1 for kk, _ in jobs if kk == k) for k in range(len(families))]
    for k, a in enumerate(anchors):
        if a is not None:
            starts[k].append((int(np.searchsorted(ms, a[0])), float(a[0]),
                              (float(a[1]), float(a[2]))))

    def scan(k, j):
        def run(ask):
            vc, b = first_crossing(replace(families[k], ask=ask), ms[j])
            ended.append(j)
            tell(len(ended), total)
            if vc is not None:
                keep(k, j, (vc, b.imag))
                starts[k].append((j + 1, float(ms[j]), (vc, b.imag)))
            scanning[k] -= 1
        return run

    def continuations(k):
        def run(ask):
            steps = _Continuation(replace(families[k], ask=ask))
            while True:
                for start in starts[k]:
                    _chain(steps, ms, start, scanned, V[k], W[k])
                starts[k].clear()
                if not steps.step():
                    if not scanning[k]:
                        return
                    ask(("wait", None), None)        # until a scan of the family ends
        return run

    run_lockstep([scan(k, j) for k, j in jobs]
                 + [continuations(k) for k in range(len(families))], _evaluate)
    for v in V:
        v[~np.isfinite(v)] = np.nan
    tell(total, total)
    return list(zip(V, W))


def _chain(steps, ms, start, scanned, V, W):
    """The neutral point ``start = (k, m0, (V, omega))`` continued up and down the
    wavenumbers ``ms`` (``k`` the first index above ``m0``; a scanned wavenumber's
    own index is ``k - 1``) to the next scanned one, or until a step fails, the
    lowest speed kept in ``V`` and ``W`` at each: its steps started on ``steps``
    (:class:`_Continuation`), each as the one before ends."""
    k, m0, point = start

    def go(order, prev):
        for i in order:
            if ms[i] != m0:
                steps.start(prev[0], prev[1], ms[i], lambda p, i=i: arrived(order, i, p))
                return
            # The start's own wavenumber: its point.
            if point[0] < V[i]:
                V[i], W[i] = point
            prev = (m0, point)

    def arrived(order, i, found):
        if found is None:
            return
        # Another chain's point here already, the same neutral point: that chain has
        # followed this branch on from here (each chain one branch, L15).
        met = _same_point(found, (V[i], W[i]), ms[i])
        if found[0] < V[i]:
            V[i], W[i] = found
        if i not in scanned and not met:
            go(order, (float(ms[i]), found))

    for order in (range(k, ms.size), range(k - 1, -1, -1)):
        go(iter(order), (m0, point))


def _same_point(p, q, m):
    """Whether the neutral points ``p = (V, omega)`` and ``q`` at wavenumber ``m`` are one
    (to 1e-9 of the speed and of ``|omega| + m V``; ``q[0]`` infinite: none)."""
    if not math.isfinite(q[0]):
        return False
    return (abs(p[0] - q[0]) <= 1e-9 * p[0]
            and abs(p[1] - q[1]) <= 1e-9 * (abs(p[1]) + m * p[0]))

