"""Pseudo-arclength continuation: round a fold, or pass a regular point."""

import numpy as np
import pytest

from thermocontact.numerics.continuation import arclength


def test_finds_the_fold_of_a_parabola():
    """x^2 + t - 1 = 0 from x = -0.9: t grows to the fold at (0, 1), then turns back."""
    def residual(z):
        return np.array([z[0] ** 2 + z[1] - 1.0])

    def jacobian(z, F):
        return np.array([[2.0 * z[0], 1.0]])
    outcome, z = arclength(residual, jacobian, [-0.9, 0.19], until=2.0, ds=0.05)
    assert outcome == "fold"
    assert z[1] == pytest.approx(1.0, abs=1e-4)
    assert z[0] == pytest.approx(0.0, abs=0.05)


def test_passes_where_the_branch_is_regular():
    """A branch without a fold (x^3 + x - t = 0): followed to t = 2 on the solution."""
    def residual(z):
        return np.array([z[0] ** 3 + z[0] - z[1]])

    def jacobian(z, F):
        return np.array([[3.0 * z[0] ** 2 + 1.0, -1.0]])
    outcome, z = arclength(residual, jacobian, [0.0, 0.0], until=2.0, ds=0.1)
    assert outcome == "passed" and z[1] >= 2.0
    assert z[0] ** 3 + z[0] - z[1] == pytest.approx(0.0, abs=1e-10)


# The engine's other pieces, on problems whose answers are known.

import math

from thermocontact.numerics.continuation import (GUESS_AGREEMENT, REJECT, STOP,
                                                 interpolated_root, inverse_interpolation,
                                                 locate, march, secant, sign_changes,
                                                 subdivide, widen)


def test_march_halves_rejected_steps_and_grows_accepted_ones():
    """Steps longer than 0.3 are rejected: from 1, halved twice to 0.25, accepted, grown
    to 0.5, rejected, ... every accepted step is 0.25 (or the last piece), and the march
    ends exactly at the end."""
    accepted = []

    def attempt(t, trial, at_smallest):
        if trial - t > 0.3:
            return REJECT
        accepted.append((t, trial))
        return 2.0
    assert march(attempt, 0.0, 1.1, step=1.0, smallest=1e-3) == 1.1
    assert [b - a for a, b in accepted] == pytest.approx([0.25] * 4 + [0.1])
    assert all(b == a2 for (_, b), (a2, _) in zip(accepted[:-1], accepted[1:]))


def test_march_accepts_at_the_smallest_step_and_keeps_the_largest():
    """A step rejected until it is at its smallest is taken there; growth stops at the
    largest step."""
    widths = []

    def attempt(t, trial, at_smallest):
        if not at_smallest and t < 0.5:
            return REJECT
        widths.append(trial - t)
        return 10.0
    march(attempt, 0.0, 2.0, step=0.4, smallest=0.1, largest=0.3)
    # 0.4 -> 0.2 -> 0.1 (clamped): accepted at 0.1 five times up to t = 0.5, then 0.3.
    assert widths[:5] == pytest.approx([0.1] * 5)
    assert widths[5:-1] == pytest.approx([0.3] * (len(widths) - 6))


def test_march_hands_a_stall_to_its_handler_and_stops_when_asked():
    stalls = []

    def stalled(t):
        stalls.append(t)
        return t + 0.5 if t < 0.6 else None
    # Every natural step fails: the handler moves t by 0.5 until it gives up.
    end = march(lambda t, trial, s: REJECT, 0.0, 2.0, step=lambda t: (2.0 - t) / 8,
                smallest=lambda t: 1e-4 * (2.0 - t), stalled=stalled)
    assert stalls == [0.0, 0.5, 1.0] and end == 1.0
    assert march(lambda t, trial, s: STOP if trial > 0.45 else 1.0, 0.0, 1.0, step=0.1,
                 smallest=0.01) == pytest.approx(0.4)


def test_locate_finds_a_known_root_to_its_tolerance():
    """cos x = x (the Dottie number) and a root at x = 0.3 of a margin that is only a
    step function of x (validity); the bracket holds the root, valid side first."""
    dottie = 0.7390851332151607
    x = locate(lambda x: math.cos(x) - x, 0.0, 1.0, xtol=1e-12)
    assert abs(x - dottie) < 2e-12
    lo, hi = locate(lambda x: math.cos(x) - x, 0.0, 1.0, xtol=1e-6, rtol=1e-6,
                    bracket=True)
    assert lo <= dottie <= hi and hi - lo < 1e-6 * (1 + dottie)
    # A margin that is +1 where valid, -1 past 0.3.
    lo, hi = locate(lambda x: 1.0 if x < 0.3 else -1.0, 0.0, 1.0, xtol=1e-9, rtol=1e-9,
                    bracket=True)
    assert lo < 0.3 <= hi and hi - lo < 1e-9
    with pytest.raises(ValueError):
        locate(lambda x: x + 1.0, 0.0, 1.0, xtol=1e-9)


@pytest.mark.parametrize("offset", [0.0, 3e-13, -3e-13, 5e-12, -5e-12, 0.2, -0.5])
def test_a_first_guess_gives_the_root_brent_gives(offset):
    """locate with a guess: within the tolerance of the root, the root in two new
    evaluations (the guess and one tolerance beyond it); farther, Brent's method on the
    bracket left, to the same tolerance; f never evaluated twice at one point."""
    dottie = 0.7390851332151607
    seen = []

    def f(x):
        seen.append(x)
        return math.cos(x) - x
    x = locate(f, 0.0, 1.0, xtol=1e-12, guess=dottie + offset)
    assert abs(x - dottie) <= 1e-12 + 4 * np.finfo(float).eps * dottie
    assert len(seen) == len(set(seen))
    if abs(offset) < 1e-12:
        assert len(seen) <= 3  # a, the guess and (unless f vanishes there) its neighbour
    plain = []
    locate(lambda x: plain.append(x) or math.cos(x) - x, 0.0, 1.0, xtol=1e-12)
    if abs(offset) < 1e-12:
        assert len(seen) < len(plain)


def test_a_guess_that_cannot_help_is_left_to_brent():
    """A guess outside the bracket, one where f is not finite, one exactly at the root,
    one whose probe is clipped at the bracket's end, ones a few tolerances off (the
    bracket narrowed, then Brent's method): the root, to the tolerance, each time; and
    a root at an end of the bracket is that end, as Brent's method alone returns it."""
    def f(x):
        return math.nan if 0.49 < x < 0.51 else math.tanh(0.6 - x)
    for guess in (-1.0, 0.5, 2.0, 0.6, 0.7, 1.0 - 1e-13, 0.6 + 5e-12, 0.6 - 5e-12):
        assert abs(locate(f, 0.0, 1.0, xtol=1e-12, guess=guess) - 0.6) <= 1e-12 + 1e-15
    for guess in (0.3, 0.5, 0.9):
        assert locate(lambda x: -x, 0.0, 1.0, xtol=1e-9, guess=guess) == 0.0
        assert locate(lambda x: 1.0 - x, 0.0, 1.0, xtol=1e-9, guess=guess) == 1.0


def test_inverse_interpolation_converges_at_fourth_order():
    """The zero of exp(x) - 2 from four samples spaced h about it: exact for a cubic
    inverse, the error falling 16-fold per halving of h (observed order 4); None for
    values that are not monotone or not finite."""
    errors = []
    for h in (0.04, 0.02, 0.01, 0.005):
        xs = math.log(2) + h * np.array([-1.7, -0.7, 0.3, 1.3])
        errors.append(abs(inverse_interpolation(xs, np.exp(xs) - 2.0) - math.log(2)))
    orders = np.log2(np.array(errors[:-1]) / np.array(errors[1:]))
    assert np.all((orders > 3.8) & (orders < 4.2)), orders
    v = np.array([-2.0, -1.0, 0.5, 3.0])
    assert inverse_interpolation(1 + v + 0.1 * v**2 - 0.01 * v**3, v) == pytest.approx(1.0,
                                                                                   abs=1e-15)
    assert inverse_interpolation([0.0, 1.0, 2.0], [-1.0, 1.0, 0.5]) is None
    assert inverse_interpolation([0.0, 1.0], [-1.0, math.nan]) is None
    assert inverse_interpolation([0.0], [-1.0]) is None
    with pytest.raises(ValueError, match="same length"):
        inverse_interpolation([0.0, 1.0], [-1.0, 0.5, 1.0])


def test_an_interpolated_root_is_given_where_its_quadratics_agree():
    """interpolated_root: the cubic where both quadratics through three of its four
    samples agree with it within GUESS_AGREEMENT tolerances (then it is within the
    tolerance: exp(x) - 2 sampled 0.004 apart); None where they do not (0.1 apart),
    and for fewer than four samples."""
    root = math.log(2)
    for h, tol, expected in ((0.004, 1e-9, True), (0.1, 1e-9, False)):
        xs = list(root + h * np.array([-1.6, -0.6, 0.4, 1.4]))
        guess = interpolated_root(xs, [math.exp(x) - 2.0 for x in xs], tol)
        assert (guess is not None) == expected
        if expected:
            assert abs(guess - root) <= tol
    xs = [0.6, 0.7, 0.8]
    assert interpolated_root(xs, [math.exp(x) - 2.0 for x in xs], 1.0) is None
    assert GUESS_AGREEMENT > 1


def test_locate_returns_the_bracket_reached_when_the_margin_cannot_be_evaluated():
    class Refused(Exception):
        pass
    seen = []

    def f(x):
        seen.append(x)
        if len(seen) > 4:
            raise Refused
        return 0.4 - x
    lo, hi = locate(f, 0.0, 1.0, xtol=1e-12, bracket=True, interrupt=(Refused,))
    assert lo <= 0.4 <= hi and {lo, hi} <= set(seen) and hi - lo < 1.0


def test_widen_grows_a_bracket_until_the_sign_changes():
    """From [0.29, 0.31] doubling: the first bracket holding 0.37 is [0.22, 0.38]."""
    a, b = widen(lambda x: x - 0.37, 0.3, 0.01, 0.0, 1.0, factor=2.0, tries=8)
    assert (a, b) == pytest.approx((0.22, 0.38))
    # Cut to [lo, hi], and not beyond `largest` or `tries`.
    assert widen(lambda x: x - 0.37, 0.3, 1.0, 0.1, 0.9, factor=2.0, tries=8) == (0.1, 0.9)
    assert widen(lambda x: x - 0.37, 0.3, 0.01, 0.0, 1.0, factor=2.0, tries=8,
                 largest=0.03) is None
    assert widen(lambda x: x - 0.37, 0.3, 0.01, 0.0, 1.0, factor=2.0, tries=3) is None
    assert widen(lambda x: math.nan, 0.3, 0.01, 0.0, 1.0, factor=2.0, tries=8) is None


def test_subdivide_halves_the_interval_of_a_sign_change():
    """Five halvings of the interval where sign(x - 0.123) changes: width 0.1/32."""
    xs = list(np.linspace(0.0, 1.0, 11))
    values = {x: math.copysign(1.0, x - 0.123) for x in xs}
    out = subdivide(xs, values, lambda x: math.copysign(1.0, x - 0.123),
                    lambda a, b: a != b, lambda a, b: 0.5 * (a + b), times=5)
    assert out == sorted(out) and set(out) == set(values)
    (i,) = sign_changes([values[x] for x in out])
    assert out[i] < 0.123 < out[i + 1] and out[i + 1] - out[i] == pytest.approx(0.1 / 32)
    assert len(out) == 11 + 5
    assert subdivide(xs[::-1], values, None, lambda a, b: False, None, times=5,
                     reverse=True) == xs[::-1]


def test_sign_changes_and_secant():
    assert list(sign_changes([1.0, -1.0, np.nan, -1.0, 2.0, 0.0, -3.0])) == [0, 3]
    x, _ = secant(lambda x: x * x - 2.0, 1.0, 2.0, 0.0, 2.0)
    assert x == pytest.approx(math.sqrt(2.0), abs=1e-13)
    assert secant(lambda x: x * x - 2.0, 1.0, 2.0, 0.0, 1.2) is None  # leaves [lo, hi]
