"""A half-plane moving through the contact (derivation section 5b): the stationary
case unchanged, its limit v2 -> 0 explained, the exchange of the two bodies and the
symmetric rolling-sliding pair exact."""

import numpy as np
import pytest

from thermocontact import solve
from thermocontact.cli import main
from thermocontact.problem.validation import InputError

#: The stationary half-plane's results before the moving half-plane existed (the same
#: commands at the previous commit): (case, P_H/P, sigma/Delta, gap margin, pressure margin).
STATIONARY = [
    (dict(pe=5, fhpe=0.3, K2_over_K1=10, lam=0.2),
     0.7702815883830534, -0.08373355638053542, 0.893582438592473, 0.47253673991684686),
    (dict(pe=2, fhpe=0.2, K2_over_K1=3, k2_over_k1=0.5, delta1_over_delta2=2.0, lam=0.5, n=64),
     0.703990215342052, -0.32792211052641684, 1.0190492196599552, 0.580381229419742),
]


@pytest.mark.parametrize("case,L,sigma,gap,pressure", STATIONARY)
def test_speed_ratio_zero_is_the_stationary_half_plane(case, L, sigma, gap, pressure):
    sol = solve(speed_ratio=0.0, **case)
    assert abs(sol.load_ratio - L) < 1e-10 and abs(sol.sigma_over_delta - sigma) < 1e-10
    assert abs(sol.validity.gap_margin - gap) < 1e-10
    assert abs(sol.validity.pressure_margin - pressure) < 1e-10


@pytest.mark.parametrize("sign", [1.0, -1.0])
def test_slow_half_plane_is_the_stationary_one_rotated(sign):
    """As v2 -> 0+- the moving kernels tend to the stationary ones up to the rigid
    rotation -+1/2 of the half-plane's slope kernel, which moves the offset by
    -+ pi F (1 - lam)/(4L) (D14c) and nothing else; the heat kernel's change is
    O(c2 ln c2), 3e-11 at R = 1e-12."""
    case = dict(pe=5, fhpe=0.3, K2_over_K1=10, lam=0.2)
    still = solve(**case)
    slow = solve(speed_ratio=sign * 1e-12, **case)
    L = still.load_ratio
    assert abs(slow.load_ratio - L) < 1e-10
    shift = -sign * np.pi * 0.3 * (1.0 - 0.2) / (4.0 * L)
    assert abs(slow.sigma_over_delta - (still.sigma_over_delta + shift)) < 1e-10
    assert abs(slow.validity.gap_margin - still.validity.gap_margin) < 1e-9
    s = np.linspace(-0.99, 0.99, 9)
    rep = still.representation
    assert np.max(abs(rep.pressure_at(slow.phi, s) - rep.pressure_at(still.phi, s))) < 1e-9


@pytest.mark.parametrize("d", [1.0, 0.5])
def test_exchanging_the_bodies_mirrors_the_solution(d):
    """(body 1, body 2, Pe, R < 0, lam) mirrored in x with the bodies exchanged is
    (body 2, body 1, |R| Pe k2/k1, 1/R, 1/rho, k1/k2, 1/d, F d, -lam): same P_H/P,
    opposite offset, mirrored pressure.  It maps the moving half-plane's kernels
    onto the cylinder's in the contact equation, the heat equation and the gap."""
    pe, F, rho, kappa, R, lam = 2.0, 0.4, 3.0, 2.0, -0.5, 0.3
    a = solve(pe, F, rho, k2_over_k1=kappa, delta1_over_delta2=d, speed_ratio=R, lam=lam, n=128)
    b = solve(abs(R) * pe * kappa, F * d, 1 / rho, k2_over_k1=1 / kappa,
              delta1_over_delta2=1 / d, speed_ratio=1 / R, lam=-lam, n=128)
    assert abs(a.load_ratio - b.load_ratio) < 1e-12
    assert abs(a.sigma_over_delta + b.sigma_over_delta) < 1e-12
    s = np.linspace(-0.99, 0.99, 9)
    assert np.max(abs(a.representation.pressure_at(a.phi, s)
                      - b.representation.pressure_at(b.phi, -s))) < 1e-10
    assert abs(a.validity.gap_margin - b.validity.gap_margin) < 1e-9
    # The thermal terms matter here: without them the comparison would be Hertz's.
    assert abs(a.load_ratio - 1.0) > 0.1 and abs(a.sigma_over_delta) > 0.01


def test_identical_bodies_at_opposite_speeds_are_symmetric():
    """Two identical bodies whose surfaces move through the contact at equal and
    opposite speeds, sharing the heat equally: the contact is centred and its
    pressure even, to rounding."""
    sol = solve(3.0, 0.5, 1.0, speed_ratio=-1.0, lam=0.0)
    assert abs(sol.sigma_over_delta) < 1e-14
    s = np.linspace(-0.99, 0.99, 9)
    p = sol.representation.pressure_at(sol.phi, s)
    assert np.max(abs(p - p[::-1])) < 1e-12
    assert sol.load_ratio < 0.9 and sol.validity.valid


def test_pure_rolling_makes_no_heat():
    """R = 1 with F > 0 is refused; with F = 0 it is Hertz's contact."""
    with pytest.raises(InputError, match="speed_ratio 1 is pure rolling"):
        solve(5, 0.2, 10, speed_ratio=1.0, lam=0.0)
    sol = solve(5, 0.0, 10, speed_ratio=1.0, lam=0.0)
    assert abs(sol.load_ratio - 1.0) < 1e-12 and abs(sol.sigma_over_delta) < 1e-12


def test_command_line_speed_ratio(capsys):
    import json

    args = ["solve", "--pe", "5", "--fhpe", "0.3", "--K2-over-K1", "10", "--lam", "0.2"]
    assert main(args + ["--speed-ratio", "-0.5", "--json"]) == 0
    rec = json.loads(capsys.readouterr().out)
    assert rec["speed_ratio"] == -0.5
    assert abs(rec["load_ratio"] - solve(5, 0.3, 10, speed_ratio=-0.5, lam=0.2).load_ratio) < 1e-14
    for bad in ("1", "nan", "x"):
        assert main(args + ["--speed-ratio", bad]) == 2
        err = capsys.readouterr().err.strip().splitlines()
        assert len(err) == 1 and "speed" in err[0] and "Traceback" not in err[0]
