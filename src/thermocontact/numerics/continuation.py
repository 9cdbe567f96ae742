"""The continuation engine: step control, event location, bracket widening, folds.

Every path of the studies is followed by the pieces here, which know nothing of
contacts: they take callables.

- :func:`march` advances a parameter ``t`` from ``start`` to ``stop`` with step
  control: a step the caller rejects is shrunk (halved), an accepted one grown by the
  factor the caller returns, between a smallest and a largest step; at the smallest
  step it is either accepted regardless or handed to a stall handler.
- :func:`subdivide` halves the intervals of a sampling where the caller suspects
  more than the samples show.
- :func:`locate` is the one locator of a sign change of a margin ``f`` on a
  bracket ``[a, b]``: Brent's method (``scipy.optimize.brentq``), to
  ``|x - x*| <= xtol + rtol |x*|``; optionally it returns the bracket of evaluated
  points either side of the root.  :func:`sign_changes` lists the intervals of a
  sampling where a margin changes sign.
- :func:`widen` widens a bracket about a point until a margin changes sign across it.
- :func:`secant` refines a root from a point and a slope (no bracket).
- :func:`arclength`: pseudo-arclength continuation of ``F(x, t) = 0`` past the
  points where ``t`` stalls.  Natural continuation in ``t`` fails where the branch
  turns back (a fold: ``dt/ds`` changes sign along the arclength ``s``);
  pseudo-arclength continuation (Keller) goes round it, with ``z = (x, t)`` as the
  unknown and the tangent as the direction: each step predicts ``z + ds tau`` and
  corrects by Newton's method on ``F(z) = 0, tau . (z - z_predicted) = 0``.
"""

from __future__ import annotations

import math

import numpy as np

__all__ = ["GUESS_AGREEMENT", "REJECT", "RTOL", "STOP", "arclength", "interpolated_root",
           "inverse_interpolation", "locate", "march", "secant", "sign_changes", "subdivide",
           "widen"]

#: Brent's default relative tolerance (four machine epsilons, scipy's own default).
RTOL = 4 * np.finfo(float).eps
#: What a step of :func:`march` returns to be rejected (the step shrinks and is tried
#: again), or to end the march where it is.
REJECT = None
STOP = "stop"


def _value(x, t):
    """``x(t)`` for a callable, else ``x``."""
    return x(t) if callable(x) else x


def march(attempt, start, stop, *, step, smallest, largest=math.inf, shrink=0.5,
          stalled=None):
    """Advance ``t`` from ``start`` to ``stop > start`` with step control.

    The next trial point is ``min(stop, t + step)``.  ``attempt(t, trial,
    at_smallest)`` decides:

    - a growth factor ``g > 0``: the trial is accepted (``t = trial``) and the step
      becomes ``g step``, kept within ``[smallest, largest]`` (only below ``largest``
      with ``stalled``);
    - :data:`REJECT`: the step becomes ``shrink step``.  Below ``smallest``, without
      ``stalled``, it is set to ``smallest`` (where ``attempt`` is told
      ``at_smallest`` and should accept); with ``stalled``, ``stalled(t)`` returns the
      point to go on from (the step restarting at ``step``), or None to end;
    - :data:`STOP`: the march ends at ``t``.

    Parameters
    ----------
    attempt : callable
        ``attempt(t, trial, at_smallest) -> float, REJECT or STOP``.
    start, stop : float
    step, smallest : float or callable
        The first step and the smallest; a callable is evaluated at the current ``t``
        (a step relative to what remains, say).
    largest : float
    shrink : float
        Factor of a rejected step, in ``(0, 1)``.
    stalled : callable, optional
        ``stalled(t) -> float or None``: where the step falls below ``smallest``.

    Returns
    -------
    float
        Where the march ended: ``stop``, or short of it (``STOP``, or ``stalled``
        returning None).
    """
    t = start
    h = _value(step, t)
    while t < stop:
        low = _value(smallest, t)
        trial = min(stop, t + h)
        # The step at its smallest (to rounding) cannot be shrunk further.
        outcome = attempt(t, trial, h <= low * (1 + 1e-9))
        if outcome is STOP:
            return t
        if outcome is REJECT:
            h *= shrink
            if h < low:
                if stalled is None:
                    h = low
                    continue
                t_next = stalled(t)
                if t_next is None:
                    return t
                t, h = t_next, _value(step, t_next)
            continue
        t = trial
        h *= outcome
        if stalled is None:
            h = max(h, _value(smallest, t))
        h = min(h, largest)
    return t


def subdivide(xs, values, evaluate, suspicious, middle, *, times, reverse=False,
              progress=None):
    """Halve the intervals of a sampling where ``suspicious``, ``times`` times at most.

    Parameters
    ----------
    xs : sequence of float
        The samples, in order (decreasing with ``reverse``).
    values : dict
        ``{x: value}`` of the samples; the new samples' are added to it.
    evaluate : callable
        ``x -> value``.
    suspicious : callable
        ``(value_a, value_b) -> bool``: halve ``(a, b)``.
    middle : callable
        ``(a, b) -> x`` inside the interval.
    progress : callable, optional
        ``progress(done, total)`` per new sample of a round.

    Returns
    -------
    list of float
        The samples, in order.
    """
    xs = list(xs)
    for _ in range(times):
        new = [middle(a, b) for a, b in zip(xs[:-1], xs[1:])
               if suspicious(values[a], values[b])]
        if not new:
            break
        for i, x in enumerate(new):
            values[x] = evaluate(x)
            if progress is not None:
                progress(i + 1, len(new))
        xs = sorted(set(xs) | set(new), reverse=reverse)
    return xs


def sign_changes(values) -> np.ndarray:
    """Indices ``i`` where ``values`` changes sign, strictly, between ``i`` and
    ``i + 1`` (both finite)."""
    g = np.asarray(values, dtype=float)
    ok = np.isfinite(g)
    return np.flatnonzero(ok[:-1] & ok[1:] & (np.sign(g[:-1]) * np.sign(g[1:]) < 0))


def locate(f, a, b, *, xtol, rtol=RTOL, bracket=False, interrupt=(), guess=None):
    """The sign change of ``f`` on ``[a, b]`` by Brent's method.

    Parameters
    ----------
    f : callable
        ``x -> float``, of opposite signs at ``a`` and ``b``.
    a, b : float
        ``a < b``.
    xtol, rtol : float
        The root is located to ``xtol + rtol |x|`` (scipy's ``brentq``).
    bracket : bool
        Return the evaluated points either side of the root instead.
    interrupt : tuple of exception types
        With ``bracket``: an evaluation of ``f`` that raises one of these ends the
        search with the bracket reached so far (as does a search that does not
        converge).
    guess : float, optional
        Without ``bracket``: a point of ``(a, b)`` believed within the tolerance of
        the root (an interpolation of samples beyond the bracket).  ``f`` is evaluated
        there and one tolerance beyond it, on the side of the sign change: where the
        sign changes between the two, the root is their secant point (two evaluations
        of ``f``); else Brent's method continues on the bracket they leave.

    Returns
    -------
    float, or (float, float) with ``bracket``
        The root; or ``(x_a, x_b)``, the evaluated points nearest each other where
        ``f >= 0`` is as at ``a`` and as at ``b`` (``x_a`` on ``a``'s side).

    Raises
    ------
    ValueError
        ``f(a)`` and ``f(b)`` have the same sign.
    RuntimeError
        No convergence in 100 iterations (without ``bracket``).
    """
    from scipy.optimize import brentq  # here: scipy.optimize is slow to import

    if not bracket:
        if guess is not None and a < guess < b:
            known = {}

            def f(x, f=f):  # Brent starts from the ends: each evaluated once
                if x not in known:
                    known[x] = f(x)
                return known[x]
            found = _near_guess(f, a, b, guess, xtol + rtol * abs(guess))
            if not isinstance(found, tuple):
                return found
            a, b = found
        return float(brentq(f, a, b, xtol=xtol, rtol=rtol))
    seen = {}

    def g(x):
        seen[x] = v = f(x)
        return v
    try:
        root = float(brentq(g, a, b, xtol=xtol, rtol=rtol))
    except (RuntimeError, *interrupt):
        root = None
    if a not in seen or b not in seen:
        return a, b
    side_a = seen[a] >= 0
    xs = sorted(seen)
    changes = [(p, q) for p, q in zip(xs[:-1], xs[1:]) if (seen[p] >= 0) != (seen[q] >= 0)]
    if root is not None:
        # Brent's last bracket: the root and its neighbour across the sign change.
        changes = [c for c in changes if root in c] or changes
        changes.sort(key=lambda c: c[1] - c[0])
    if not changes:
        return a, b
    p, q = changes[0]
    return (p, q) if (seen[p] >= 0) == side_a else (q, p)


def inverse_interpolation(xs, values):
    """Where the polynomial through the points ``(values[i], xs[i])`` (``x`` as a
    function of the value) gives value 0: a root's estimate from samples around it
    (Neville's scheme); None unless at least two values are given, all finite and
    strictly monotone (then ``x`` is a function of the value)."""
    xs, values = [float(x) for x in xs], [float(v) for v in values]
    if len(xs) != len(values):
        raise ValueError(f"xs and values must have the same length, got {len(xs)} and "
                         f"{len(values)}")
    steps = np.diff(values)
    if (len(values) < 2 or not all(map(math.isfinite, values + xs))
            or not (np.all(steps > 0.0) or np.all(steps < 0.0))):
        return None
    p = list(xs)
    for level in range(1, len(p)):
        for i in range(len(p) - level):
            lo, hi = values[i], values[i + level]
            p[i] = (hi * p[i] - lo * p[i + 1]) / (hi - lo)
    return p[0] if math.isfinite(p[0]) else None


#: :func:`interpolated_root` trusts the cubic where both quadratics through three of its
#: four points are within this many tolerances of it: its error was 2-4 % of their
#: distance on the events of the benchmark map's lines at 41, 100 and 200 samples.
GUESS_AGREEMENT = 20.0


def interpolated_root(xs, values, tol):
    """A root's estimate from four samples around it (:func:`inverse_interpolation`,
    a cubic in the value) where it is likely within ``tol`` of the root: the two
    quadratics through its first and last three samples agree with it within
    :data:`GUESS_AGREEMENT` tolerances (on a coarser sampling they do not, and a first
    guess that misses costs more than it saves); else None."""
    if len(xs) != 4:
        return None
    cubic = inverse_interpolation(xs, values)
    if cubic is None:
        return None
    for part in (slice(0, 3), slice(1, 4)):
        quadratic = inverse_interpolation(xs[part], values[part])
        if quadratic is None or not abs(cubic - quadratic) <= GUESS_AGREEMENT * tol:
            return None
    return cubic


def _near_guess(f, a, b, guess, tol):
    """:func:`locate`'s first steps from ``guess``: the root (float) where ``f`` changes
    sign between ``guess`` and the point ``tol`` beyond it toward the sign change, else
    the bracket ``(a, b)`` narrowed by those evaluations (a tuple)."""
    fa, fg = f(a), f(guess)
    if fa == 0.0:
        return float(a)  # as Brent's method returns it
    if fg == 0.0:
        return float(guess)
    if not (math.isfinite(fa) and math.isfinite(fg)):
        return a, b
    toward_b = (fg > 0.0) == (fa > 0.0)
    probe = min(guess + tol, b) if toward_b else max(guess - tol, a)
    fp = f(probe)
    if fp == 0.0:
        return float(probe)
    if math.isfinite(fp) and (fp > 0.0) != (fg > 0.0):
        # The secant point of the two, within their interval (at most tol wide).
        x = guess - fg * (probe - guess) / (fp - fg)
        return float(min(max(x, min(guess, probe)), max(guess, probe)))
    if not math.isfinite(fp):
        return (guess, b) if toward_b else (a, guess)
    return (probe, b) if toward_b else (a, probe)


def widen(f, center, width, lo, hi, *, factor, tries, largest=math.inf):
    """A bracket ``[a, b]`` about ``center`` across which ``f`` changes sign.

    ``[center - width, center + width]``, cut to ``[lo, hi]``, is widened by
    ``factor`` until ``f`` is finite at both ends with ``f >= 0`` at one only, at most
    ``tries`` times, and not once ``width`` exceeds ``largest``.

    Returns
    -------
    (a, b) or None
    """
    for _ in range(tries):
        a, b = max(center - width, lo), min(center + width, hi)
        fa, fb = f(a), f(b)
        if np.isfinite(fa) and np.isfinite(fb) and (fa >= 0) != (fb >= 0):
            return a, b
        if width > largest:
            return None
        width *= factor
    return None


def secant(h, x0, slope, lo, hi, h0=None, xtol=1e-13, proposed=False):
    """The root of ``h`` by secant steps from ``x0``, the first along ``slope``.

    Returns ``(x, slope)`` at the last point evaluated (its ``h`` known to the
    caller's solver), or None when a step leaves ``[lo, hi]`` or 30 do not converge.
    With ``proposed``, the point a step below ``xtol`` proposes is returned without
    evaluating it (as Newton's method's last step: one evaluation fewer where each is
    costly).
    """
    h0 = h(x0) if h0 is None else h0
    for _ in range(30):
        if slope == 0.0 or not math.isfinite(slope):
            return None
        x1 = x0 - h0 / slope
        if not lo <= x1 <= hi:
            return None
        if proposed and abs(x1 - x0) <= xtol * max(1.0, abs(x1)):
            return x1, slope
        h1 = h(x1)
        if abs(x1 - x0) <= xtol * max(1.0, abs(x1)):
            return x1, slope
        if h1 != h0:
            slope = (h1 - h0) / (x1 - x0)
        x0, h0 = x1, h1
    return None


def _tangent(J, previous=None):
    """The unit null vector of ``J`` (``k`` by ``k + 1``), along ``previous`` or with
    ``dt/ds > 0``."""
    v = np.linalg.svd(J)[2][-1]
    if previous is not None:
        return v if v @ previous > 0.0 else -v
    return v if v[-1] > 0.0 else -v


def arclength(residual, jacobian, z0, *, until, ds=0.02, steps=200, tol=1e-10,
              newton=12):
    """Follow ``residual(z) = 0`` from ``z0`` toward larger ``t = z[-1]``.

    Parameters
    ----------
    residual : callable
        ``z -> F``, ``k`` values for ``k + 1`` unknowns.
    jacobian : callable
        ``(z, F(z)) -> dF/dz``, ``k`` by ``k + 1``.
    z0 : ndarray
        A solution.
    until : float
        Stop once ``t`` reaches it.
    ds, steps, tol, newton : float, int
        Step length (halved where Newton's method fails), most steps, tolerance on
        the largest residual, most Newton steps per correction.

    Returns
    -------
    outcome : {"passed", "fold", "failed"}
    z : ndarray
        The solution at ``t >= until`` (passed); the fold's estimate, with ``t`` the
        largest of the parabola through the two points that bracket it and their
        slopes ``dt/ds`` (fold, error O(ds^3)); the last solution (failed).
    """
    z = np.asarray(z0, dtype=float).copy()
    F = residual(z)
    tau = _tangent(jacobian(z, F))
    for _ in range(steps):
        zp = z + ds * tau
        zn = zp.copy()
        for _ in range(newton):
            F = residual(zn)
            if np.max(np.abs(F)) < tol:
                break
            system = np.vstack([jacobian(zn, F), tau])
            zn = zn - np.linalg.solve(system, np.append(F, tau @ (zn - zp)))
        else:
            ds *= 0.5
            if ds < 1e-8:
                return "failed", z
            continue
        new_tau = _tangent(jacobian(zn, F), tau)
        if new_tau[-1] * tau[-1] < 0.0:
            # dt/ds goes from a > 0 to b < 0 over the step: t(s) is a parabola with its
            # top at s* = ds a/(a - b) from z.
            a, b = tau[-1], new_tau[-1]
            s_star = ds * a / (a - b)
            fold = z + s_star * tau
            fold[-1] = z[-1] + 0.5 * a * s_star
            return "fold", fold
        z, tau = zn, new_tau
        if z[-1] >= until:
            return "passed", z
    return "failed", z
