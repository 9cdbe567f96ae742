"""A brake stop: how much each number of hot spots grows while the speed falls.

The speed falls from ``V0`` to its end along a history ``V(t)`` (a constant
deceleration, or a CSV file of time and speed), the load constant.  With the
coefficients frozen at each instant (the growth rate ``b(V)`` of the mode at the
speed of that instant, the mode's shape following the speed), the perturbation of
``n`` hot spots round a disc of radius ``R`` (wavenumber ``m = n/R``) is amplified by

    ``A_n = exp(int Re b(V(t); m) dt)``   (derivation, L13),

``b`` the largest growth rate of the families at that speed.  The approximation
needs the speed to change little over a growth time, ``|dV/dt| / V << |Re b|``; it is
checked against a time integration of the linearised equations discretised in depth
(``tests/test_tei_layers.py``).  For each ``n`` the rightmost modes are followed
down the speeds by Newton's method (all ``n`` together) from the family's rightmost
modes at the top speed (depth-discretisation seeds, polished), reseeded every 16th
speed.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from ..io.results import Result
from ..physics.tei import SPEED_RANGE
from ..problem.validation import InputError, check_range

__all__ = ["BrakeStop", "StopHistory", "growth_table", "stop_amplification", "stop_history"]

#: Speeds (Chebyshev points of the stop's range) at which the growth rates are
#: computed and interpolated.
SPEEDS = 48
#: The default amplification that marks a hot-spot number unstable, ``e^5``.
DEFAULT_THRESHOLD = math.exp(5.0)


@dataclass(frozen=True, eq=False, repr=False)
class StopHistory(Result):
    """A speed history: ``times`` (s, increasing from 0) and ``speeds`` (m/s, the last
    no higher than the first), and the amplification ``threshold``."""

    times: np.ndarray
    speeds: np.ndarray
    threshold: float

    def _record(self) -> dict:
        return {"duration": float(self.times[-1]), "initial_speed": float(self.speeds[0]),
                "final_speed": float(self.speeds[-1]), "threshold": self.threshold}


def stop_history(stop=None, path=None, threshold=None) -> StopHistory:
    """The history of ``stop = "V0:DECEL"`` (or a pair), or of a CSV file ``path`` of
    time (s) and speed (m/s), checked: one line each for a speed outside
    ``(0, 1e4]`` m/s, a deceleration that is not positive, times that do not
    increase, a stop that ends above its start."""

    if (stop is None) == (path is None):
        raise InputError("give exactly one of brake_stop and stop_history",
                         parameters=("brake_stop", "stop_history"))
    thr = DEFAULT_THRESHOLD if threshold is None else check_range(
        "stop_threshold", threshold, 1.0, 1e300, open_low=True)
    if stop is not None:
        parts = stop.split(":") if isinstance(stop, str) else stop
        try:
            v0, decel = parts
        except (TypeError, ValueError):
            raise InputError(f"brake_stop must be V0:DECEL (m/s and m/s^2), got {stop!r}",
                             parameters=("brake_stop",)) from None
        v0 = check_range("brake_stop", v0, SPEED_RANGE[0], SPEED_RANGE[1])
        decel = check_range("brake_stop", decel, 1e-9, 1e6)
        t = np.linspace(0.0, v0 / decel, 2)
        return StopHistory(t, v0 - decel * t, thr)
    try:
        data = np.loadtxt(path, delimiter=",", ndmin=2, comments="#")
    except ValueError:
        try:
            data = np.loadtxt(path, delimiter=",", ndmin=2, comments="#", skiprows=1)
        except (ValueError, OSError) as exc:
            raise InputError(f"stop_history: cannot read {path}: {exc}",
                             parameters=("stop_history",)) from None
    except OSError as exc:
        raise InputError(f"stop_history: cannot read {path}: {exc}",
                         parameters=("stop_history",)) from None
    if data.shape[1] != 2 or data.shape[0] < 2 or not np.isfinite(data).all():
        raise InputError(f"stop_history must be a CSV of two columns, time (s) and speed "
                         f"(m/s), at least two rows, got shape {data.shape}",
                         parameters=("stop_history",))
    t, v = data[:, 0] - data[0, 0], data[:, 1]
    if np.any(np.diff(t) <= 0.0):
        raise InputError("stop_history: the times must increase", parameters=("stop_history",))
    if np.any(v < 0.0) or np.any(v > SPEED_RANGE[1]) or v[0] <= 0.0:
        raise InputError(f"stop_history: speeds must be in [0, {SPEED_RANGE[1]:g}] m/s and "
                         f"the first > 0", parameters=("stop_history",))
    if v[-1] > v[0]:
        raise InputError(f"stop_history: a stop must not end above its start ({v[-1]:g} > "
                         f"{v[0]:g} m/s)", parameters=("stop_history",))
    return StopHistory(t, v, thr)


@dataclass(frozen=True, eq=False, repr=False)
class BrakeStop(Result):
    """Each hot-spot number's amplification over a stop (L13).

    Attributes
    ----------
    n : ndarray of int
    log_amplification : ndarray
        ``int Re b dt`` over the stop, per ``n``.
    threshold : float
        The amplification that marks an ``n`` unstable.
    first_unstable : dict or None
        ``{"n", "speed"}``: the hot-spot number whose running amplification first
        exceeds ``threshold`` during the stop, and the speed then, m/s.
    history : StopHistory
    """

    n: np.ndarray
    log_amplification: np.ndarray
    threshold: float
    first_unstable: dict | None
    history: StopHistory = field(repr=False)

    def _summary(self) -> str:
        i = int(np.argmax(self.log_amplification))
        return (f"largest log amplification {self.log_amplification[i]:.4g} at n = "
                f"{int(self.n[i])}, first_unstable={self.first_unstable}")

    def _record(self) -> dict:
        return {"amplification": [{"n": int(k), "log_amplification": float(a)}
                                  for k, a in zip(self.n, self.log_amplification)],
                "first_unstable": self.first_unstable, "threshold": self.threshold,
                "history": self.history.to_dict()}


def _track(system, ms, speeds):
    """The largest growth rate of a layered family at each wavenumber (axis 1) and
    speed (axis 0): the rightmost modes followed by Newton's method on the
    dispersion function from speed to speed, all wavenumbers at once, each
    predicted in the frame it is nearer to rest in (its frequency there kept); a
    root that lands farther than the step from its prediction is dropped, and the
    depth discretisation reseeds (all wavenumbers polished together) every 16th
    speed."""
    from .tei_layers import newton_roots, pattern_frame, raw_seeds

    out = np.full((speeds.size, ms.size), -np.inf)
    tracked = None
    prev_v = None
    scale1 = np.array([system.scale(m) for m in ms])
    for i, v in enumerate(speeds):
        if tracked is not None:
            # Predict: a pattern at rest on the moving bodies moves with the speed.
            phi = pattern_frame(ms[:, None], prev_v, tracked.imag)
            tracked = tracked - 1j * phi * ms[:, None] * (v - prev_v)
        if i % 16 == 0:
            seeds = [system.modes(m, v)[:2] for m in ms]
            fresh = np.array([np.pad(s_, (0, 2 - len(s_)), constant_values=np.nan)
                              for s_ in seeds])
            tracked = fresh if tracked is None else np.concatenate([tracked, fresh], axis=1)
        mm = np.broadcast_to(ms[:, None], tracked.shape)
        scale = np.broadcast_to(scale1[:, None], tracked.shape)
        good = np.isfinite(tracked)
        mg = mm[good]
        roots, ok = newton_roots(lambda z, act: system.log_derivatives(z, mg[act], v)[..., 0],
                                 tracked[good], scale[good])
        near = np.abs(roots - tracked[good]) <= (0.2 * np.abs(tracked[good].real) + 10.0
                                                  * scale[good] + mm[good] * abs(v - (
                                                      prev_v if prev_v is not None else v)))
        new = np.full(tracked.shape, np.nan, dtype=complex)
        new[good] = np.where(ok & near, roots, np.nan)
        # Drop duplicates (two tracks on one root) and keep at most 4 per wavenumber.
        for j in range(new.shape[0]):
            row = new[j]
            keep = []
            for x in row[np.isfinite(row)][np.argsort(-row[np.isfinite(row)].real)]:
                if all(abs(x - y) > 1e-8 * (abs(x) + scale1[j]) for y in keep):
                    keep.append(x)
            row[:] = np.nan
            row[:len(keep[:4])] = keep[:4]
        tracked = new[:, :4] if new.shape[1] > 4 else new
        with np.errstate(invalid="ignore"):
            out[i] = np.max(np.where(np.isfinite(tracked), tracked.real, -np.inf), axis=1)
        prev_v = v
    return out


def growth_table(systems, ms, speeds):
    """The largest growth rate over the families, 1/s, at each speed (rows) and
    wavenumber (columns)."""
    rows = []
    for system in systems:
        if hasattr(system, "layup"):
            rows.append(_track(system, ms, speeds))
        else:
            rows.append(np.array([[_rate(system, m, v) for m in ms] for v in speeds]))
    return np.max(np.array(rows), axis=0)


def _rate(system, m, v):
    b = system.modes(m, v)
    return float(b[0].real) if len(b) else -math.inf


def stop_amplification(systems, radius, hot_spots, history: StopHistory) -> BrakeStop:
    """Each hot-spot number's frozen-coefficient amplification over the stop (L13).

    The growth rates are computed at :data:`SPEEDS` Chebyshev points of the stop's
    speed range and interpolated (a polynomial in the speed: they are smooth in it),
    then integrated along the history by the trapezoidal rule on 2000 instants
    (the history's own instants included)."""
    n = np.arange(hot_spots[0], hot_spots[1] + 1)
    ms = n / radius
    v_hi, v_lo = float(np.max(history.speeds)), float(np.min(history.speeds))
    v_lo = max(v_lo, 1e-6 * v_hi)
    k = np.arange(SPEEDS)
    nodes = 0.5 * (v_hi + v_lo) + 0.5 * (v_hi - v_lo) * np.cos(np.pi * k / (SPEEDS - 1))
    table = growth_table(systems, ms, nodes)                  # (speeds, n)
    table = np.where(np.isfinite(table), table, np.nan)
    # Chebyshev interpolation in the speed, per n.
    from numpy.polynomial import chebyshev as C

    x_nodes = (2.0 * nodes - (v_hi + v_lo)) / (v_hi - v_lo)
    fill = np.where(np.isnan(table), np.nanmin(table, axis=0, initial=0.0), table)
    coef = C.chebfit(x_nodes, fill, SPEEDS - 1)
    t = np.union1d(np.linspace(history.times[0], history.times[-1], 2000), history.times)
    v = np.clip(np.interp(t, history.times, history.speeds), v_lo, v_hi)
    rates = C.chebval((2.0 * v - (v_hi + v_lo)) / (v_hi - v_lo), coef)   # (n, t)
    running = np.concatenate([np.zeros((n.size, 1)),
                              np.cumsum(0.5 * (rates[:, 1:] + rates[:, :-1]) * np.diff(t),
                                        axis=1)], axis=1)
    limit = math.log(history.threshold)
    first = None
    over = running > limit
    if over.any():
        j = int(np.min(np.where(over.any(axis=0))[0]))
        i = int(np.argmax(running[:, j]))
        first = {"n": int(n[i]), "speed": float(v[j])}
    return BrakeStop(n, running[:, -1], history.threshold, first, history)
