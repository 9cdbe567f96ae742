"""A contact set of several zones linearised with its edges free (docs/derivation.md,
section 18b, S18-S22).

* One zone is the single patch: ``M`` of the set at the rate ``b`` (units ``k2/l^2``)
  equals the single patch's at ``b Delta^2`` but for Flamant's ``ln Delta`` on the load
  (a row operation, S19).
* ``M(0)`` against the Jacobian, by differences in each zone's centre and half-width, of
  the steady contact set's residual at fixed load and heat partition in the
  undifferentiated form (displacement and temperature continuity at points moving with
  each zone, every zone's sources integrated by the moment engine at the other zones'
  points): the cross-zone edges' terms and the zones' common constants against a
  second computation.
* Two zones far apart: ``det M`` of the set over the product of the two zones'
  single-patch determinants grows by ``(2/pi) ln(d2/d1)`` from ``d1`` to ``d2``, its
  sole dependence on the separation ``d`` (the two zones' loads exchanged through
  Flamant's logarithm; every other coupling decays).
* The zones' transient kernels at each other's points, interpolated on Chebyshev
  panels, against their values there (and ``M(b)`` built either way).
"""

from __future__ import annotations

import math
from dataclasses import replace

import numpy as np
import pytest
from numpy.polynomial import Polynomial

from thermocontact import Model
from thermocontact.discretisation.linearised import projections
from thermocontact.discretisation.linearised_set import LinearisedContactSet
from thermocontact.numerics.moment_engine import stretch
from thermocontact.physics.green_functions import cylinder_displacement, cylinder_temperature
from thermocontact.problem.validation import InputError
from thermocontact.solvers.stability import linearised
from thermocontact.solvers.zones import ZoneModel

N = 10


@pytest.fixture(scope="module")
def single():
    return Model(5.0, 10.0, n=N).solve_at(N, 0.2, lam=-1.0)


def _as_zone(sol, centre_over_delta=None):
    """The single patch ``sol`` as one zone in units of the Hertz half-width
    (``Delta = sqrt(P_H/P)``, section 14), at ``centre_over_delta`` (default its own
    offset): ``(parameters, edges, phi, psi)``."""
    h = np.sqrt(sol.load_ratio)
    c = h * (sol.sigma_over_delta if centre_over_delta is None else centre_over_delta)
    par = replace(sol.parameters, pe=sol.parameters.pe / h, fhpe=sol.parameters.fhpe / h)
    return par, np.array([c - h, c + h]), sol.phi / h, sol.psi / h


@pytest.fixture(scope="module")
def single_dundurs():
    return Model(5.0, 10.0, n=N, beta_f=0.6).solve_at(N, 0.2, lam=-1.0)


@pytest.fixture(scope="module")
def single_moving():
    return Model(5.0, 10.0, n=N, speed_ratio=0.5).solve_at(N, 0.2, lam=-1.0)


@pytest.fixture(scope="module")
def single_conductance():
    return Model(5.0, 10.0, n=N, conductance=(10.0, 0.95)).solve_at(N, 0.2, lam=-1.0)


@pytest.mark.parametrize("which", ["single", "single_dundurs", "single_moving",
                                   "single_conductance"])
def test_one_zone_is_the_single_patch(which, request):
    """With and without the Dundurs term (its edge exponents in the representation's
    weight, S15, S26), with the half-plane moving (no temperature constant, S27), and
    with a conductance growing with the pressure, ``Bi0 = 10``, ``m = 0.95`` in the
    single patch's scaling, ``Bi0 Delta^(m - 1)`` in units of ``l`` (D37a, S28)."""
    from thermocontact.problem.conductance import Conductance

    single = request.getfixturevalue(which)
    par, edges, phi, psi = _as_zone(single)
    h = 0.5 * (edges[1] - edges[0])
    cond = single.conductance
    if cond is not None:
        cond = Conductance(cond.biot0 * h ** (cond.exponent - 1.0), cond.exponent)
    zone = LinearisedContactSet(par, single.representation, [edges], phi[None], psi[None],
                                conductance=cond)
    lin = linearised(single)
    _, pd, _ = projections(N)
    wp = single.representation.pressure_rule.weights
    assert zone.size == lin.size
    for b in (0.0, 0.3 + 0.7j, 5.0, 2e-3 + 40j):
        M = np.array(zone.matrix(b), dtype=complex)
        M[:N + 2, :N] -= np.log(h) / np.pi * np.outer(pd.sum(axis=1), wp)
        M1 = lin.matrix(b * h * h)
        assert np.abs(M - M1).max() < 1e-12 * np.abs(M1).max(), b


QUARTIC = Polynomial([0, 0.05]) + (1 / 32) * Polynomial([-4.0, 0, 1]) ** 2


@pytest.fixture(scope="module")
def two_zones():
    """Two zones of a tilted quartic profile with frictional heat (section 14)."""
    return ZoneModel(10.0, n=N, profile=QUARTIC).solve([[-2.6, -1.1], [1.1, 2.6]], 1.0, 0.2,
                                                      0.5)


@pytest.fixture(scope="module")
def two_zones_moving():
    """The same with the half-plane moving (R = 0.5, c2 = 0.5 Pe_l)."""
    return ZoneModel(10.0, n=N, profile=QUARTIC, speed_ratio=0.5).solve(
        [[-2.6, -1.1], [1.1, 2.6]], 1.0, 0.2, 0.5)


@pytest.fixture(scope="module")
def two_zones_conductance():
    """The same with a constant interface conductance, Bi0 = h0 l/K2 = 3."""
    return ZoneModel(10.0, n=N, profile=QUARTIC, conductance=(3.0, 0.0)).solve(
        [[-2.6, -1.1], [1.1, 2.6]], 1.0, 0.2, 0.5)


@pytest.fixture(scope="module")
def two_zones_dundurs():
    """The same with the Dundurs term (beta f = 0.3: edge exponents 0.547 and 0.453)."""
    return ZoneModel(10.0, n=N, profile=QUARTIC, beta_f=0.3).solve(
        [[-2.6, -1.1], [1.1, 2.6]], 1.0, 0.2, 0.5)


def _operator(sol, geometry):
    """The steady contact set's residual in the undifferentiated form at points moving
    with each zone, ``R = A z + r0``, for the zones' centres and half-widths
    ``geometry`` (pairs ``(c_j, Delta_j)``, units of ``l``), ``z`` the unknowns of
    :class:`LinearisedContactSet` but the edges: each zone's ``phi``, ``psi`` times its
    steady half-width, then ``D``.  Every zone's sources by the moment engine at every
    zone's points, kernels in units of ``l`` (Flamant's ``ln|Delta_j u|``, the
    stationary half-plane's ``-ln|Delta_j u|``); each later zone's first temperature
    row less the first's (the common temperature constant) and the first zone's the
    heat partition.  A moving half-plane's kernels are the moving body's with ``c2``
    (S27); its temperature rows are complete, the difference of the incoming
    temperatures a constant left out of ``r0``."""
    par, rep, n, m = sol.parameters, sol.representation, sol.n, sol.zones
    x, pd, pt = projections(n)
    s, aux = rep.projection_points(x)
    eta, rho, d, F = par.eta, par.K2_over_K1, par.delta1_over_delta2, par.fhpe
    wp, wq = rep.pressure_rule.weights, rep.flux_rule.weights
    cl, c2 = par.cylinder_scale, par.half_plane_scale
    size = 2 * n * m + 1
    A = np.zeros((m * (2 * n + 2) + 1, size))
    r0 = np.zeros(A.shape[0])
    rows = []
    for i, (ci, hi) in enumerate(geometry):
        X = ci + hi * s
        disp = np.zeros((2 * n, size))
        temp = np.zeros((2 * n, size))
        for j, (cj, hj) in enumerate(geometry):
            sj = (X - cj) / hj
            a = aux if i == j else None
            ce = cl * hj

            def mom(kernel, scale, log=False):
                return rep.integrate(kernel, sj, scale=scale, logarithmic=log, aux=a)
            cols = slice(2 * n * j, 2 * n * j + 2 * n)

            def heat(M, k):
                ap, aq = (0.5 * (1 + eta), 0.5) if k == 0 else (0.5 * (1 - eta), -0.5)
                return np.hstack([ap * M[0], aq * M[1]])
            lb, _ = mom(lambda u: np.log(np.abs(u)), 1.0, True)
            disp[:, cols.start:cols.start + n] += (lb + np.log(hj) * wp) / np.pi
            if par.free_term:
                # The Dundurs term's -b int H(X - Y) P dY, H's constant half in D.
                step, _ = mom(np.sign, 1.0)
                disp[:, cols.start:cols.start + n] -= 0.5 * par.free_term * step
            w1 = mom(lambda u: cylinder_displacement(ce * u) / cl, ce)
            t1 = mom(lambda u: cylinder_temperature(ce * u), ce, True)
            if c2:
                c2e = c2 * hj
                w2 = mom(lambda u: cylinder_displacement(c2e * u) / abs(c2), abs(c2e))
                t2 = mom(lambda u: cylinder_temperature(c2e * u), abs(c2e), True)
            else:
                w2 = mom(lambda u: -0.5 * hj * np.abs(u), 1.0)
                t2 = mom(lambda u: -np.log(np.abs(u)), 1.0, True)
            disp[:, cols] += 2 * F * (d * heat(w1, 0) + heat(w2, 1))
            temp[:, cols] += rho * heat(t1, 0) - heat(t2, 1)
            if not c2:
                temp[:, cols.start:cols.start + n] -= 0.5 * (1 - eta) * (-np.log(hj)) * wp
                temp[:, cols.start + n:cols.stop] -= -0.5 * (-np.log(hj)) * wq
        cond = sol.conductance
        if cond is not None:
            # The interface's (pi/(2 Bi)) Q at the zone's own points, Q = q/Delta_i in
            # units of l (D33; a constant Bi: linear in the densities).
            assert cond.exponent == 0.0
            at = np.cos(np.multiply.outer(aux, np.arange(n))) @ rep.to_cos
            t = stretch(aux)
            factor = 0.5 * np.pi / (cond.biot0 * hi)
            temp[:, 2 * n * i:2 * n * i + n] += factor * (eta * np.sin(t))[:, None] * at
            temp[:, 2 * n * i + n:2 * n * i + 2 * n] += (factor / np.sin(t))[:, None] * at
        disp[:, -1] = 1.0
        rows.append((pd @ disp, -(2 / np.pi) * (pd @ sol.profile(X)), pt @ temp))
    k = 0
    first = []
    for i, (dp, g, tp) in enumerate(rows):
        A[k:k + n + 2], r0[k:k + n + 2] = dp, g
        k += n + 2
        if i == 0:
            A[k, :-1] = np.concatenate([np.concatenate([wp, np.zeros(n)])] * m)
            r0[k] = -1.0
            k += 1
        first.append(k)
        A[k:k + n] = tp
        k += n
    if c2:
        return A, r0
    A[first[1:]] -= A[first[0]]
    heat2 = np.concatenate([0.5 * (1 - eta) * wp, -0.5 * wq])
    A[first[0]] = -np.sum(pt[0]) * np.append(np.concatenate([heat2] * m), 0.0)
    r0[first[0]] = np.sum(pt[0]) * 0.5 * (1 - sol.lam)
    return A, r0


@pytest.mark.parametrize("which", ["two_zones", "two_zones_dundurs", "two_zones_moving",
                                   "two_zones_conductance"])
def test_M0_is_the_jacobian_of_the_steady_contact_set(which, request):
    """With and without the Dundurs term (S26: its step at the other zones a constant,
    no edges' terms), and with the half-plane moving (S27: at fixed incoming
    temperatures, every temperature row complete)."""
    sol = request.getfixturevalue(which)
    n, m = sol.n, sol.zones
    lin = LinearisedContactSet(sol.parameters, sol.representation, sol.edges, sol.phi,
                               sol.psi, sol.profile, sol.conductance)
    M0 = lin.matrix(0)
    h, c = sol.half_widths, sol.centres
    geometry = list(zip(c, h))
    A, r0 = _operator(sol, geometry)
    z = np.concatenate([np.concatenate([hj * sol.phi[j], hj * sol.psi[j]])
                        for j, hj in enumerate(h)] + [[0.0]])
    # The steady rigid approach: the first zone's displacement rows at rest.
    z[-1] = -(A[0] @ z + r0[0]) / A[0, -1]
    # The steady contact set is the undifferentiated residual's zero, the
    # discretisation's error apart (at n = 10 largest in the temperature's highest
    # projections, 4.5e-3; 3.2e-6 at n = 16, 7.9e-8 at n = 24, derivation S22): the
    # zones' common approach and temperature constant, the profile and the length
    # unit's logarithms are the steady solver's.
    R = A @ z + r0
    temperature = np.r_[n + 3:2 * n + 3, 3 * n + 5:4 * n + 5]
    if sol.parameters.half_plane_scale:
        # The incoming temperatures' difference, the same constant on every zone.
        constant = np.tile(projections(n)[2].sum(axis=1), m)
        R[temperature] -= R[n + 3] / constant[0] * constant
    # The displacement rows' residual, measured: 5.2e-7 at rest, 6.2e-7 with the
    # Dundurs term, 1.3e-6 with the half-plane moving (n = 10).
    assert np.abs(np.delete(R, temperature)).max() < 3e-6
    assert abs(R[3 * n + 5] - R[n + 3]) < 1e-3 and np.abs(R).max() < 1e-2
    # M(0)'s columns: the linear unknowns as A's, each zone's (sig~, del~) by central
    # differences of the residual in c_j/Delta_j and Delta_j/Delta_j.
    J = np.zeros_like(M0)
    lin_cols = [k for j in range(m) for k in range(j * (2 * n + 2) + (j > 0),
                                                  j * (2 * n + 2) + (j > 0) + 2 * n)]
    J[:, lin_cols] = A[:, :-1]
    J[:, 2 * n] = A[:, -1]
    for j in range(m):
        base = 2 * n + 1 if j == 0 else j * (2 * n + 2) + 1 + 2 * n
        for k in range(2):
            step = 1e-5
            cols = []
            for sign in (1, -1):
                g = list(geometry)
                cj, hj = g[j]
                g[j] = (cj + sign * step * h[j], hj) if k == 0 else (cj, hj + sign * step * h[j])
                Ag, rg = _operator(sol, g)
                cols.append(Ag @ z + rg)
            J[:, base + k] = (cols[0] - cols[1]) / (2 * step)
    scale = np.abs(J).max()
    err = np.abs(M0 - J) / scale
    assert err[:, lin_cols].max() < 1e-12
    assert np.delete(err, lin_cols + [2 * n], axis=1).max() < 1e-9


@pytest.mark.parametrize("conductance", [None, (10.0, 0.95)])
def test_two_zones_far_apart_factor_into_their_single_patches(conductance):
    """Two copies of a single patch (heat into the cylinder alone, lam = 1) in the wells
    of the double well ``(X^2 - c^2)^2/(8 c^2)``, whose curvature at each well is the
    cylinder's: ``det M`` of the set over the single patches' ``det M`` grows by
    ``(2/pi) ln 2`` as the separation ``2c`` doubles (S23), to ``O(1/c)``.  With a
    conductance following the pressure, each zone's blocks in its own scaling
    (``Bi0 Delta^(m - 1)`` in units of ``l``, S28) are its single patch's: a factor
    between them would scale the growth."""
    from thermocontact.problem.conductance import Conductance

    sol = Model(5.0, 10.0, n=N, conductance=conductance).solve_at(N, 0.2, lam=1.0)
    par, edges, phi, psi = _as_zone(sol)
    h = 0.5 * (edges[1] - edges[0])
    cond = None if conductance is None else Conductance(
        conductance[0] * h ** (conductance[1] - 1.0), conductance[1])
    b = 0.5 + 1.0j
    sign, single = np.linalg.slogdet(linearised(sol).matrix(b * h * h))
    ratios = []
    for c in (40.0, 80.0, 160.0):
        well = Polynomial([-c * c, 0.0, 1.0]) ** 2 / (8.0 * c * c)
        pair = LinearisedContactSet(par, sol.representation, [edges - c, edges + c],
                                    np.stack([phi, phi]), np.stack([psi, psi]), well,
                                    conductance=cond)
        s, both = np.linalg.slogdet(pair.matrix(b))
        ratios.append(s / sign ** 2 * np.exp(both - 2 * single))
    steps = np.diff(ratios) / (2.0 / np.pi * np.log(2.0))
    # Measured: 1.0047 + 0.0025i, then 0.99896 + 0.0011i (1.0051 + 0.0023i, then
    # 0.99904 + 0.0009i with the conductance).
    assert abs(steps[1] - 1.0) < 2e-3
    assert abs(steps[1] - 1.0) < 0.5 * abs(steps[0] - 1.0)


def test_a_contact_set_s_conductance_reaches_each_zone_in_its_own_scaling(two_zones):
    """``linearised`` of a set solved with an interface conductance (it was refused):
    each zone's block takes ``Bi0 Delta_j^(1 - m)`` (S28, the inverse of D37a)."""
    from thermocontact.problem.conductance import Conductance

    sol = replace(two_zones, conductance=Conductance.of((3.0, 0.5)))
    lin = linearised(sol)
    for zone, h in zip(lin.zones, sol.half_widths):
        assert zone.conductance.exponent == 0.5
        assert zone.conductance.biot0 == pytest.approx(3.0 * np.sqrt(h), rel=1e-15)


def test_stability_of_a_contact_set_solves_it_again_and_counts_in_its_units(two_zones,
                                                                           monkeypatch):
    """``stability(contact set)``: the set solved again at the analysis' ``n`` from its
    edges, linearised with every edge free, rates in ``k2/l^2`` (the count itself is
    the single patch's machinery, S22; a stand-in keeps this fast)."""
    import thermocontact as tc
    import thermocontact.solvers.stability as stability

    seen = {}

    def stand_in(solve_at, rate_unit=None, **region):
        sol = solve_at(N)
        seen.update(sol=sol, lin=linearised(sol), rate_unit=rate_unit, region=region)
        return "verdict"
    monkeypatch.setattr(stability, "stability_of", stand_in)
    assert tc.stability(two_zones, n=N) == "verdict"
    lin = seen["lin"]
    assert isinstance(lin, LinearisedContactSet) and lin.RATE_UNITS == "k2/l^2"
    assert seen["rate_unit"] is None and seen["region"]["n"] == N
    # The modulus bound: the single patch's for the narrowest zone (S24), unless given.
    h = two_zones.half_widths
    assert seen["region"]["modulus_bound"] == pytest.approx(1e6 / h.min() ** 2, rel=1e-15)
    assert 1.5 < h.max() / h.min() and h.min() < 1.0
    tc.stability(two_zones, n=N, modulus_bound=5e3)
    assert seen["region"]["modulus_bound"] == 5e3
    assert np.abs(seen["sol"].edges - two_zones.edges).max() < 1e-12
    assert lin.size == 2 * (2 * N + 2) + 1
    assert list(lin.temperature_rows) == (list(range(N + 3, 2 * N + 3))
                                          + list(range(3 * N + 5, 4 * N + 5)))


def test_contact_zones_stability_adds_the_record(capsys, monkeypatch):
    """``contact --zones --stability`` answers (it was refused): the contact set's
    ``"stability"`` record (stand-ins for the set and its verdict keep it fast)."""
    import json

    import thermocontact.api as api
    from thermocontact.cli import main

    class Found:
        def to_dict(self):
            return {"status": "solved"}
    seen = []

    def verdict(found, progress):
        seen.append(found)
        return replace(single_verdict, eigenvalues=np.array([0.5 + 1j, 0.5 - 1j]))
    from thermocontact.solvers.stability import StabilityResult
    single_verdict = StabilityResult(np.array([]), 2, False, None, 0.5, (1e-3, 1e6),
                                     "argument principle", None, None, None, 40, 12,
                                     units="1/s")
    monkeypatch.setattr(api, "contact_set", lambda **kw: Found())
    monkeypatch.setattr(api, "stability", verdict)
    assert main(["contact", "--cylinder", "steel", "--half-plane", "steel", "--radius",
                 "10mm", "--load", "5kN/m", "--speed", "1m/s", "--friction", "0.3", "--lam",
                 "0", "--no-dundurs", "--zones", "--stability", "--json"]) == 0
    rec = json.loads(capsys.readouterr().out)
    assert isinstance(seen[0], Found) and rec["stability"]["stable"] is False
    assert rec["stability"]["eigenvalues"] == [[0.5, 1.0], [0.5, -1.0]]


def test_zones_stability_adds_the_record(capsys, monkeypatch):
    """``zones --stability`` (the dimensionless command) adds the contact set's
    ``"stability"`` record, in its JSON and its text, as ``contact --zones --stability``
    does (stand-ins keep it fast), with ``--conductance`` too."""
    import json

    import thermocontact.api as api
    from thermocontact.cli import main
    from thermocontact.solvers.stability import StabilityResult

    class Found:
        status, message, answer = "solved", "one zone", None

        def to_dict(self):
            return {"status": "solved"}
    seen = []

    def verdict(found, progress):
        seen.append(found)
        return StabilityResult(np.array([]), 0, True, None, None, (1e-3, 1e6),
                               "argument principle", None, None, None, 40, 12)
    monkeypatch.setattr(api, "contact_set", lambda *a, **kw: Found())
    monkeypatch.setattr(api, "stability", verdict)
    args = ["zones", "--pe-hertz", "1", "--fhpe-hertz", "0.05", "--K2-over-K1", "1",
            "--lam", "1", "--stability"]
    assert main(args + ["--json"]) == 0
    rec = json.loads(capsys.readouterr().out)
    assert isinstance(seen[0], Found) and rec["stability"]["stable"] is True
    assert main(args) == 0
    assert "stable        = True" in capsys.readouterr().out
    # With an interface conductance too (it was refused, S28).
    assert main(args + ["--conductance", "1:0", "--json"]) == 0
    assert json.loads(capsys.readouterr().out)["stability"]["stable"] is True


class _ManyRows:
    """A stand-in linearisation without eigenvalues whose ``2n`` temperature rows fall
    like ``(1 + b/1000)^(-1/2)``: the scaled determinant ``((1 + b)/(1 + b/1000))^n``
    turns its phase by up to ``n pi/2`` and back along the line, as a two-zone contact
    set's does, whose temperature rows settle only at large ``|b|`` (S22)."""

    n, moving, RATE_UNITS = 12, True, "k2/l^2"
    temperature_rows = np.arange(24)

    def matrix(self, b, split=False):
        M = np.eye(25, dtype=complex)
        M[self.temperature_rows, self.temperature_rows] = (1.0 + b / 1000.0) ** -0.5
        return M


@pytest.mark.parametrize("line_step, count", [(4.0, 2), (None, 0)])
def test_the_count_follows_the_phase_of_many_temperature_rows(monkeypatch, line_step,
                                                             count):
    """Two zones' temperature rows, each scaled by ``sqrt(1 + b)``, turn the phase twice
    as fast as a single patch's along the line: the single patch's first steps alias a
    turn (two roots counted where there are none, as at two zones of the quartic at
    fHPe_l = 0, n = 12, where a dense sampling of the contour finds none), steps halved
    per zone do not."""
    import thermocontact.solvers.stability as st

    monkeypatch.setattr(st, "linearised", lambda sol: _ManyRows())
    if line_step is None:
        res = st.stability_of(lambda n: None, n=12, estimate=False)
        assert res.stable is True and res.unstable_modes == 0
    else:
        winding = st.Winding(st.scaled_matrix(_ManyRows()), 1e-3, line_step=line_step)
        assert winding.count(1e6)[0] == count


def test_the_phase_of_a_step_is_the_sum_of_its_eigenvalues_arguments():
    """``step_phase(A, B)`` (S25) against the phase of ``det(A + s(B - A))`` followed on
    a fine grid of ``s``; a step whose eigenvalue turns by pi/4 or more is refused."""
    from thermocontact.solvers.stability import step_phase

    rng = np.random.default_rng(7)
    A = rng.standard_normal((8, 8)) + 1j * rng.standard_normal((8, 8))
    for E in (0.15 * rng.standard_normal((8, 8)), 0.1j * rng.standard_normal((8, 8))):
        B = A @ (np.eye(8) + E)
        s = np.linspace(0.0, 1.0, 2001)
        dets = [np.linalg.det(A + x * (B - A)) for x in s]
        followed = np.unwrap(np.angle(dets))
        assert step_phase(A, B) == pytest.approx(followed[-1] - followed[0], abs=1e-10)
    assert step_phase(A, A @ np.diag(np.r_[np.exp(1j), np.ones(7)])) == np.inf


@pytest.mark.parametrize("line_step", [4.0, 8.0])
def test_steps_by_eigenvalues_do_not_alias_the_turns_of_many_rows(line_step):
    """The aliasing of the many temperature rows (above: the determinant's phase counts
    2 from first steps of 4 units) is gone when each step's phase is the sum of the
    arguments of the eigenvalues of ``A(a)^-1 A(b)`` (S25): 0, from steps of 4 or 8,
    with fewer samples; and the count of known roots is unchanged."""
    import thermocontact.solvers.stability as st
    from test_stability import ROOTS, _known_problem

    winding = st.Winding(st.scaled_matrix(_ManyRows()), 1e-3, line_step=line_step,
                         ratios=True)
    assert winding.count(1e6) == (0, None) and len(winding.values) < 40
    known = st.Winding(_known_problem(ROOTS), 1e-3, ratios=True)
    assert known.count(30.0) == (6, None) and known.count(1e4) == (8, None)
    double = st.Winding(_known_problem([2.0 + 0j, 2.0 + 0j]), 1e-3, ratios=True)
    assert double.count(100.0) == (2, None)
    count, why = st.Winding(_known_problem([1e-3 + 0.5j, 1e-3 - 0.5j]), 1e-3,
                            ratios=True).count(10.0)
    assert count is None and "contour" in why


def test_panel_interpolation_resolves_a_boundary_layer_and_evaluates_a_jump_directly():
    """A boundary layer ``exp(-beta u)`` (``|arg beta| < pi/4``, the transient kernels'
    form) and a logarithm on intervals of either sign, to their tolerance of the
    scale; a jump no panel resolves is evaluated at its points directly."""
    from thermocontact.numerics.interpolation import panel_interpolation

    beta = 40.0 * np.exp(0.6j)
    calls = []

    def f(x):
        calls.append(x.size)
        return np.stack([np.exp(-beta * np.abs(x)), np.log(np.abs(x)),
                         np.where(x > 1.3, 1.0, 0.0)])
    rng = np.random.default_rng(1)
    targets = [rng.uniform(0.01, 3.0, (7, 9)), rng.uniform(-4.0, -0.5, 40)]
    got = panel_interpolation(f, [(0.01, 3.0), (-4.0, -0.5)], targets, tol=1e-14)
    for u, g in zip(targets, got):
        exact = f(u.ravel()).reshape(g.shape)
        scale = np.maximum(1.0, np.abs(exact).reshape(3, -1).max(axis=1))
        # The jump's panels, halved ten times, unresolved: its points evaluated.
        assert np.abs(g - exact).reshape(3, -1).max(axis=1).max() < 1e-13 * scale.max()
    # Fewer evaluations than a graded rule that resolves the layer everywhere would take.
    assert sum(calls) < 3000


def test_the_zones_kernels_interpolated_agree_with_their_values(two_zones):
    """The transient kernels of zone j at zone i's points, interpolated on Chebyshev
    panels of the pair's interval of ``u`` (S21), against their quadrature at every
    point; and ``M(b)`` assembled from either, from the slow rates to the arc."""
    sol = two_zones
    lin = LinearisedContactSet(sol.parameters, sol.representation, sol.edges, sol.phi,
                               sol.psi, sol.profile)

    def direct(b):
        return {pair: lin._kernels(u, b) for pair, (u, _, _) in lin._pairs.items()}
    for b in (2e-3 + 0.02j, 1e-3 + 1e4j):
        fast, slow = lin._cross_kernels(b), direct(b)
        for pair in slow:
            for body_f, body_s in zip(fast[pair], slow[pair]):
                for kf, ks in zip(body_f, body_s):
                    assert np.abs(kf - ks).max() <= 2e-14 * max(1.0, np.abs(ks).max())
        M = lin.matrix(b)
        object.__setattr__(lin, "_cross_kernels", direct)
        M_direct = lin.matrix(b)
        del lin.__dict__["_cross_kernels"]
        assert np.abs(M - M_direct).max() < 1e-14 * np.abs(M_direct).max()


def test_zones_closing_up_take_more_of_the_sources_points(two_zones, monkeypatch):
    """Two zones 1e-6 apart (the second moved next to the first): the cross-zone rule's
    points grow as ``25 delta^(-1/6)`` (S21), and M(b) agrees with the one of four
    times as many points to 1e-10 of its largest entry (measured 2.5e-11; with the
    64 points of well separated zones, 3.4e-4)."""
    from thermocontact.discretisation import linearised_set

    edges = two_zones.edges.copy()
    edges[1] -= edges[1, 0] - edges[0, 1] - 1e-6
    count = linearised_set.source_points(edges, N)
    half = 0.5 * (edges[:, 1] - edges[:, 0])
    assert count == math.ceil(25.0 * (1e-6 / half.max()) ** (-1 / 6)) > 200
    assert linearised_set.source_points(two_zones.edges, N) == 64

    def matrix():
        return LinearisedContactSet(two_zones.parameters, two_zones.representation, edges,
                                    two_zones.phi, two_zones.psi,
                                    two_zones.profile).matrix(0.5 + 1.0j)
    M = matrix()
    monkeypatch.setattr(linearised_set, "source_points", lambda *args: 4 * count)
    reference = matrix()
    assert np.abs(M - reference).max() < 1e-10 * np.abs(reference).max()


def test_a_contact_set_s_M_refuses_rates_left_of_the_imaginary_axis(two_zones):
    """The zones' kernels at each other's points are interpolated only for ``Re b > 0``
    (S21: to the left the interpolant was off by a tenth where its coefficients looked
    resolved): such a rate is refused in one line, ``b = 0`` (the limit) is not."""
    sol = two_zones
    lin = LinearisedContactSet(sol.parameters, sol.representation, sol.edges, sol.phi,
                               sol.psi, sol.profile)
    for b in (-5.0 + 1e-3j, 1e-3j, -1.0):
        with pytest.raises(InputError, match="positive real part"):
            lin.matrix(b)
    assert np.all(np.isfinite(lin.matrix(0)))


def test_at_large_rates_the_zones_couple_only_through_terms_free_of_b(two_zones):
    """S24: at large ``|b|`` zone j's transient fields at zone i's points fall off (its
    temperature like ``exp(-Re sqrt(b) d)`` across the gap, beyond the cylinder's wake
    scale; the half-plane's displacement to its constant ``-2/(pi sqrt b)``, the
    rest like ``|b|^(-3/2)``), so that ``M(b)`` tends to ``M_inf(b)``, each zone's own
    block (its single patch's at ``b Delta_j^2``) coupled by what does not depend on
    ``b``: ``det M / det M_inf -> 1``, and the entries' difference falls at least like
    ``|b|^(-3/2)``."""
    from thermocontact.discretisation.linearised import logarithm_constant

    sol = two_zones
    lin = LinearisedContactSet(sol.parameters, sol.representation, sol.edges, sol.phi,
                               sol.psi, sol.profile)

    def limit(b):
        out = {}
        for pair, (u, _, _) in lin._pairs.items():
            z = np.zeros(u.shape, dtype=complex)
            out[pair] = ((z, z, z, z), (z - 2.0 / (np.pi * np.sqrt(b)),
                                        z - logarithm_constant(b), z, z))
        return out
    ratios, entries = [], []
    for b in 1e3 * np.exp(1j * np.pi / 3), 1e5 * np.exp(1j * np.pi / 3):
        M = lin.matrix(b)
        object.__setattr__(lin, "_cross_kernels", limit)
        M_inf = lin.matrix(b)
        del lin.__dict__["_cross_kernels"]
        s, ld = np.linalg.slogdet(M)
        s_inf, ld_inf = np.linalg.slogdet(M_inf)
        ratios.append(abs(s / s_inf * np.exp(ld - ld_inf) - 1.0))
        entries.append(np.abs(M - M_inf).max() / np.abs(M).max())
    # Measured (n = 10): 3.1e-5 and 1.2e-7; entries 2.1e-4 (the cylinder's wake,
    # Re mu - c = 2.6 at |b| = 1e3) and 1.7e-9.
    assert ratios[1] < 1e-6 and ratios[1] < 1e-2 * ratios[0]
    assert entries[1] < 1e-8


def test_a_fold_is_recorded_for_a_contact_set_as_for_the_single_patch():
    """Next to the fold of the load on the ray K2/K1 = 1, lam = 1, fH = 1 (Pe = 1.22; the
    fold at 1.235) ``det M(0)`` is small and the exponentially slow real root of (S8)
    lies below b_min: the single patch as one zone records both, the root in
    ``k2/l^2`` (``b*/Delta^2``, as ``l(b Delta^2) = l(b) - ln Delta`` moves the ratio
    ``det M_reg(0)/det M(0)`` by ``-ln Delta``: S22), and a fold measure of the same
    size."""
    from thermocontact.solvers.stability import _fold

    sol = Model(1.22, 1.0, n=N).solve_at(N, 1.22, lam=1.0, check_validity=False)
    par, edges, phi, psi = _as_zone(sol)
    h = 0.5 * (edges[1] - edges[0])
    zone = LinearisedContactSet(par, sol.representation, [edges], phi[None], psi[None])
    fold, slow = _fold(linearised(sol))
    fold_set, slow_set = _fold(zone)
    assert slow is not None and slow < 1e-10
    assert slow_set * h * h == pytest.approx(slow, rel=1e-8)
    assert 1.0 / fold_set == pytest.approx(1.0 / fold + np.log(h), rel=1e-8)
    assert fold < 0.1 and fold_set < 0.1
