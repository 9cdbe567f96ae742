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


def _jaeger(b, prob, body, s):
    """Jaeger's high-Peclet surface temperature of body 1 or 2 for the computed flux:
    (1/K) sqrt(k/(pi |v|)) times the integral of q over the material upstream of x,
    in contact units f |v1 - v2| P / K sqrt(1/(2 pi |c|)) integral q / sqrt(|r - s|) dr.

    The integral in the representation's variable tau (r = cos T(tau)), where the
    flux's factors are cosine series and 1/sqrt(1 -+ r) dr is smooth: only
    1/sqrt(|tau - tau_s|) is left, integrated by Gauss-Jacobi with 2n nodes (within
    1e-12 of 4n; within 6e-10 of QUADPACK's algebraic-weight rule in r to 1e-8)."""
    from scipy.special import roots_jacobi

    from thermocontact.numerics.moment_engine import stretch, stretch_inverse

    sol = b.solution
    par, rep, eta = sol.parameters, sol.representation, sol.parameters.eta
    tau_s = float(stretch_inverse(np.arccos(s)))
    t_s = float(stretch(tau_s))
    # Body 1 enters at s = +1 (r from s to 1: tau in [0, tau_s]), body 2 at s = -1.
    lo, hi = (0.0, tau_s) if body == 1 else (tau_s, np.pi)
    x, w = roots_jacobi(2 * sol.n, *((-0.5, 0.0) if body == 1 else (0.0, -0.5)))
    tau = lo + 0.5 * (hi - lo) * (1.0 + x)
    t, d = stretch(tau), np.abs(tau - tau_s)
    r = np.cos(t)
    # |r - s| without cancellation: |T(tau) - T(tau_s)| = |d - cos(tau + tau_s) sin d|.
    dt = np.abs(d - np.cos(tau + tau_s) * np.sin(d))
    distance = 2.0 * np.sin(0.5 * (t + t_s)) * np.sin(0.5 * dt)
    dT = 2.0 * np.sin(tau) ** 2
    phi, psi = rep.phi_at(sol.phi, r), rep.psi_at(sol.psi, r)
    if body == 1:  # q1 sqrt(1 - r), smooth; dr/sqrt(1 - r) = sqrt 2 cos(t/2) T' dtau
        K, c = prob.cylinder.K, par.cylinder_scale
        f = 0.5 * ((1 + eta) * (1 - r) * np.sqrt(1 + r) * phi + psi / np.sqrt(1 + r))
        jacobian = np.sqrt(2.0) * np.cos(0.5 * t) * dT
    else:  # moving toward +x: q2 sqrt(1 + r); dr/sqrt(1 + r) = sqrt 2 sin(t/2) T' dtau
        K, c = prob.half_plane.K, par.half_plane_scale
        f = 0.5 * ((1 - eta) * (1 + r) * np.sqrt(1 - r) * phi - psi / np.sqrt(1 - r))
        jacobian = np.sqrt(2.0) * np.sin(0.5 * t) * dT
    integral = np.sqrt(0.5 * (hi - lo)) * (w @ (f * jacobian * np.sqrt(d / distance)))
    unit = prob.friction * prob.sliding_speed * prob.load / K
    return unit * np.sqrt(1.0 / (2.0 * np.pi * abs(c))) * integral


def test_flash_temperatures_of_both_bodies_approach_jaeger():
    """Steel on steel, surfaces through the contact at +30 and -20 m/s (then 4 times
    faster): both bodies' temperature rises, each over its own incoming temperature,
    approach Jaeger's high-Peclet asymptote for the computed flux at the rate 1/c of
    its next term (c = 167 and 664 for the cylinder, -112 and -442 for the half-plane;
    relative to the flash temperature, 7.5e-3 and 1.9e-3, 1.1e-2 and 2.8e-3)."""
    from thermocontact.problem.materials import get_material
    from thermocontact.studies.physical_contact import PhysicalProblem, contact

    steel = get_material("steel")
    errors = []
    for scale in (1.0, 4.0):
        prob = PhysicalProblem(steel, steel, 0.02, 2e5, 30.0 * scale, 0.1, 0.2,
                               speed2=-20.0 * scale)
        b = contact(prob).primary
        s = (b.x[1:-1] - b.offset) / b.half_width
        pick = np.arange(10, s.size - 10, 45)
        t1 = b.temperature_cylinder[1:-1][pick]
        t2 = b.temperature_half_plane[1:-1][pick] - b.half_plane_incoming_temperature
        j1 = np.array([_jaeger(b, prob, 1, x) for x in s[pick]])
        j2 = np.array([_jaeger(b, prob, 2, x) for x in s[pick]])
        flash = b.flash_temperature
        errors.append((np.max(abs(t1 - j1)) / flash, np.max(abs(t2 - j2)) / flash))
        assert b.flash_temperature >= t1.max() > 0.5 * b.flash_temperature
    (e1, e2), (f1, f2) = errors
    assert e1 / f1 > 3.0 and e2 / f2 > 3.0  # first order in 1/c
    assert f1 < 3e-3 and f2 < 4e-3


def test_identical_bodies_at_opposite_speeds_enter_at_one_temperature():
    """With equal and opposite surface speeds, equal shares of the heat (lam = 0) are
    what equal incoming temperatures give: the implied difference vanishes, and the
    contact is centred.  Another partition implies a difference, odd in lam."""
    from thermocontact.problem.materials import get_material
    from thermocontact.studies.physical_contact import PhysicalProblem, contact

    steel = get_material("steel")
    b = contact(PhysicalProblem(steel, steel, 0.02, 2e5, 10.0, 0.3, 0.0, speed2=-10.0)).primary
    assert abs(b.half_plane_incoming_temperature) < 1e-9 * b.flash_temperature
    assert b.flash_temperature_half_plane == pytest.approx(b.flash_temperature, rel=1e-9)
    assert abs(b.offset) < 1e-12 * b.half_width
    b = contact(PhysicalProblem(steel, steel, 0.02, 2e5, 10.0, 0.3, 0.2, speed2=-10.0)).primary
    assert b.half_plane_incoming_temperature > 0.05 * b.flash_temperature
    assert b.heat_cylinder + b.heat_half_plane == pytest.approx(0.3 * 2e5 * 20.0, rel=1e-14)
    # Mirrored with the bodies exchanged, lam -> -lam: the implied difference changes
    # sign, and each body's flash temperature over its own incoming temperature is the
    # other's (to 1e-6 relative, the branch's error target).
    m = contact(PhysicalProblem(steel, steel, 0.02, 2e5, 10.0, 0.3, -0.2, speed2=-10.0)).primary
    assert m.half_plane_incoming_temperature == pytest.approx(
        -b.half_plane_incoming_temperature, rel=1e-6)
    assert m.flash_temperature_half_plane == pytest.approx(b.flash_temperature, rel=1e-6)
    assert m.offset == pytest.approx(-b.offset, rel=1e-6)


def test_contact_command_takes_the_half_planes_speed(capsys):
    import json

    args = ["contact", "--cylinder", "steel", "--half-plane", "steel", "--radius", "20mm",
            "--load", "200kN/m", "--speed", "10", "--friction", "0.1", "--lam", "0"]
    assert main(args + ["--speed2", "-36km/h", "--json"]) == 0
    rec = json.loads(capsys.readouterr().out)
    assert rec["inputs"]["speed2"] == -10.0 and abs(rec["offset"]) < 1e-15
    assert rec["fhpe"] == pytest.approx(2 * rec["pe"] * 0.1 * _H("steel", "steel"), rel=1e-12)
    assert main(args + ["--speed2", "3 kg"]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "speed2" in err[0]


def _H(cyl, half):
    from thermocontact.problem.materials import get_material
    from thermocontact.studies.physical_contact import PhysicalProblem

    return PhysicalProblem(get_material(cyl), get_material(half), 1.0, 1.0, 1.0, 0.1, 0.0).H


@pytest.mark.parametrize("along, start, stop, fixed", [
    ("speed_ratio", -0.5, -0.1, dict(pe=5, fhpe=0.7, K2_over_K1=10, lam=1.0)),
    ("beta_f", 0.0, 0.05, dict(pe=5, fhpe=0.66, K2_over_K1=10, lam=1.0)),
])
def test_boundaries_along_speed_ratio_and_beta_f(along, start, stop, fixed):
    """Fig. 4's case (Pe = 5, K2/K1 = 10, lam = 1) near its boundary fHPe = 0.6654:
    moving the half-plane against the cylinder (R < -0.28) restores the single patch at
    fHPe = 0.7, and a Dundurs term of B = 0.02 removes it at fHPe = 0.66.  Each event
    is the zero of the gap margin of plain solves (opposite signs at +-1e-6)."""
    from thermocontact.studies.boundaries import follow

    path = follow(fixed, along, start, stop, n=32, points=5)
    (e,) = [e for e in path.events if e.inequality == "gap"]
    assert e.edge == "leading"
    before, after = (solve(n=32, **{**fixed, along: e.at + d}).validity.gap_margin
                     for d in (-1e-6, 1e-6))
    assert (before > 0.0) == e.valid_before and before * after < 0.0
    assert e.valid_before and not e.valid_after  # valid below R = -0.28 and B = 0.02


@pytest.mark.parametrize("args, words", [
    (["--along", "speed-ratio", "--from", "0.5", "--to", "1.5", "--fhpe", "0.2",
      "--beta-f", "0.2"], "must not reach 1"),
    (["--along", "fhpe", "--from", "0", "--to", "0.3", "--beta-f", "0.5", "--method", "product"],
     "--beta-f != 0 needs"),
])
def test_paths_refuse_what_no_point_can_solve(args, words, capsys):
    """A path through pure rolling, or with a method that cannot carry the Dundurs
    term's exponents, is refused in one line before any sample (not reported as a path
    of failed samples)."""
    base = ["boundary", "--pe", "5", "--K2-over-K1", "10", "--lam", "0"]
    assert main(base + args) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and words in err[0]
