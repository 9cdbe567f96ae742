"""The stability of a steady single patch (docs/derivation.md, section 18, S1-S9).

* ``M(0)`` against the Jacobian, by central differences in the centre and half-width, of
  the steady problem's residual at fixed load and heat partition (displacement and
  temperature continuity at points moving with the contact, kernels of the dilated
  contact assembled anew): the edges' columns, derived from the Green's functions'
  derivatives, against a second computation.
* ``M(b) -> M(0)`` as ``b -> 0``, like ``sqrt(b)`` (T11), with the stationary half-plane's
  diverging temperature constant ``l(b)`` (T6) apart; ``M(conj b) = conj M(b)``.
* ``det M(0)`` vanishes where the load along a ray of growing load has a fold, located
  by Brent's method on the steady solver's load.
* The kernels' tabulated moments against the moment engine's.
* The count by the argument principle, Beyn's method and Newton's method on a nonlinear
  eigenproblem with known eigenvalues; on the contact, the count against the roots
  Beyn's method finds inside a different contour.
"""

from __future__ import annotations

import json
import pathlib
import pickle

import numpy as np
import pytest
from scipy.optimize import brentq

from conftest import assert_ulps
from thermocontact import BulkTemperatures, Model, StabilityResult
from thermocontact.discretisation.linearised import LinearisedContact, projections
from thermocontact.numerics.moment_engine import stretch
from thermocontact.physics.green_functions import cylinder_displacement, cylinder_temperature
from thermocontact.problem.validation import InputError
from thermocontact.solvers.stability import (Winding, beyn, half_disc, linearised, newton,
                                             stability_of)


def _steady(pe, K, fhpe, lam, n):
    return Model(pe, K, n=n).solve_at(n, fhpe, lam=lam)


def _residual(sol, z):
    """The steady residual at fixed load and heat partition (stationary half-plane) or
    fixed incoming temperatures (moving half-plane) in the undifferentiated form, at
    points moving with the contact: ``z = (phi, psi, D, sigma/Delta0, Delta/Delta0)``,
    lengths in units of the solution's half-width ``Delta0``.  A dilation by
    ``Delta/Delta0`` is the contact at ``Pe Delta/Delta0`` (section 16)."""
    par, rep, n = sol.parameters, sol.representation, sol.n
    x, pd, pt = projections(n)
    s, aux = rep.projection_points(x)
    eta, rho, d, F = par.eta, par.K2_over_K1, par.delta1_over_delta2, par.fhpe
    wp, wq = rep.pressure_rule.weights, rep.flux_rule.weights
    phi, psi, D, sg, dl = z[:n], z[n:2 * n], z[2 * n], z[2 * n + 1], z[2 * n + 2]
    ce = par.cylinder_scale * dl
    c2 = par.half_plane_scale * dl

    def moments(kernel, scale, log=False):
        return rep.integrate(kernel, s, scale=scale, logarithmic=log, aux=aux)

    def q1(m):
        return 0.5 * (1 + eta) * m[0] @ phi + 0.5 * m[1] @ psi

    def q2(m):
        return 0.5 * (1 - eta) * m[0] @ phi - 0.5 * m[1] @ psi
    lb, _ = moments(lambda u: np.log(np.abs(u)), 1.0, True)
    # The Dundurs term -b p(s) of the slope equation, integrated: -b int H(s - r) p dr
    # (its constant half enters D; scale-invariant: no dependence on sigma or Delta).
    sign_b, _ = moments(np.sign, 1.0)
    w1 = moments(lambda u: cylinder_displacement(ce * u) / ce, ce)
    w2 = (moments(lambda u: cylinder_displacement(c2 * u) / abs(c2), max(1.0, abs(c2)))
          if c2 else moments(lambda u: -0.5 * np.abs(u), 1.0))
    # Flamant's ln|Delta (s - r)| = ln|s - r| + ln(Delta/Delta0) in units of Delta0.
    disp = (lb @ phi / np.pi - 0.5 * par.free_term * (sign_b @ phi)
            + np.log(dl) / np.pi * (wp @ phi)
            + 2 * F * dl * (d * q1(w1) + q2(w2)) + D
            - (sol.load_ratio / np.pi) * (sg + dl * s) ** 2)
    t1 = moments(lambda u: cylinder_temperature(ce * u), ce, True)
    t2 = (moments(lambda u: cylinder_temperature(c2 * u), max(1.0, abs(c2)), True) if c2
          else moments(lambda u: -np.log(np.abs(u)), 1.0, True))
    temp = rho * q1(t1) - q2(t2)
    if sol.conductance is not None:
        # The interface's (pi/(2 Bi)) q (D33) at the points, the flux scaled by
        # 1/Delta and the pressure's reference fixed: p/p_ref = 2 p / (Delta/Delta0).
        at = np.cos(np.multiply.outer(aux, np.arange(n))) @ rep.to_cos
        t = stretch(aux)                  # s = cos t, without cancellation at the edges
        sin_t = np.sin(t)
        # p = w(s) phi with the Dundurs term's edge exponents: w = (1 - s)^a (1 + s)^(1 - a).
        p_at = (2 * np.sin(t / 2) ** 2) ** rep.alpha * (2 * np.cos(t / 2) ** 2) ** (
            1 - rep.alpha) * (at @ phi)
        q_at = eta * p_at + (at @ psi) / sin_t
        temp = temp + 0.5 * np.pi * q_at / (dl * sol.conductance.biot(p_at / dl))
    out = np.concatenate([pd @ disp, [wp @ phi - 1.0], pt @ temp])
    if not c2:
        # The stationary half-plane's temperature has a free constant: its first
        # projection is replaced by the heat partition (heat into the half-plane).
        out[n + 3] = -np.sum(pt[0]) * (0.5 * (1 - eta) * wp @ phi - 0.5 * wq @ psi)
    return out


@pytest.mark.parametrize("pe, K, fhpe, lam, d, R, B, conductance", [
    (5.0, 10.0, 0.2, -1.0, 1.0, 0.0, 0.0, None),
    (2.0, 1.0, 0.5, 0.5, 0.0, 0.0, 0.0, None),
    (1.0, 3.0, 0.4, 0.0, 2.0, 0.0, 0.0, None),
    (2.0, 3.0, 0.3, 0.2, 1.0, 0.5, 0.0, None),
    (2.0, 3.0, 0.3, 0.2, 0.5, -0.7, 0.0, None),
    (5.0, 10.0, 0.2, -1.0, 1.0, 0.0, 0.6, None),
    (2.0, 3.0, 0.3, 0.2, 0.5, 0.4, -0.8, None),
    (5.0, 10.0, 0.2, -1.0, 1.0, 0.0, 0.0, (3.0, 0.0)),
    (2.0, 1.0, 0.5, 0.5, 0.0, 0.0, 0.0, (0.5, 0.0)),
    (1.0, 3.0, 0.4, 0.0, 2.0, 0.0, 0.0, (3.0, 1.0)),
    (2.0, 3.0, 0.3, 0.2, 0.5, -0.7, 0.0, (10.0, 0.95)),
    # Every model at once.
    (2.0, 3.0, 0.3, 0.2, 0.5, 0.4, -0.8, (3.0, 1.0))])
def test_M0_is_the_jacobian_of_the_steady_problem(pe, K, fhpe, lam, d, R, B, conductance):
    """Also for a moving half-plane (R = v2/v1 != 0: its steady kernels, the
    temperature complete, no partition row; derivation S14), with the Dundurs term
    (beta f = B, the edge exponents it makes carried by the representation, S15) and
    with an interface conductance (Bi0, m), constant or following the pressure (S16),
    and with all three."""
    n = 10
    sol = Model(pe, K, delta1_over_delta2=d, speed_ratio=R, beta_f=B, n=n,
                conductance=conductance).solve_at(n, fhpe, lam=lam)
    M0 = linearised(sol).matrix(0)
    z0 = np.concatenate([sol.phi, sol.psi, [0.0, sol.sigma_over_delta, 1.0]])
    J = np.empty_like(M0)
    # The residual is linear in phi, psi and D, unless the conductance follows the
    # pressure (then phi's columns are differences too).
    nonlinear = n if conductance is not None and conductance[1] else 0
    for k in range(z0.size):
        h = 1e-5 if k > 2 * n or k < nonlinear else 1.0
        e = np.zeros_like(z0)
        e[k] = h
        J[:, k] = (_residual(sol, z0 + e) - _residual(sol, z0 - e)) / (2 * h)
    scale = np.abs(J).max()
    # The edges' columns differ from the differences by the steady residual's
    # derivative (the discretisation error) and the differences' error.
    assert np.abs(M0[:, nonlinear:2 * n + 1] - J[:, nonlinear:2 * n + 1]).max() < 1e-13 * scale
    assert np.abs(M0[:, :nonlinear] - J[:, :nonlinear]).max(initial=0.0) < 1e-8 * scale
    assert np.abs(M0[:, 2 * n + 1:] - J[:, 2 * n + 1:]).max() < 1e-8 * scale


def test_M_tends_to_M0_like_sqrt_b():
    sol = _steady(1.0, 1.0, 0.3, -1.0, 6)
    lin = linearised(sol)
    reg0, _, row0 = lin.matrix(0, split=True)
    errors = []
    for b in (1e-6, 1e-8):
        reg, ell, row = lin.matrix(b, split=True)
        assert ell == pytest.approx(-np.log(np.sqrt(b) / 2) - np.euler_gamma, rel=1e-14)
        np.testing.assert_array_equal(row, row0)
        errors.append(np.abs(reg - reg0).max() / np.abs(reg0).max())
    # The stationary half-plane's displacement converges like sqrt(b) (T11).
    assert errors[0] < 1e-3
    assert errors[0] / errors[1] == pytest.approx(10.0, rel=0.05)
    # And the whole: the diverging constant on the temperature's first projection.
    M = lin.matrix(1e-8)
    np.testing.assert_allclose(M, reg + ell * np.outer(np.eye(M.shape[0])[sol.n + 3], row),
                               rtol=0, atol=1e-15 * np.abs(M).max())


def _fold_function(K, lam, fH, n):
    # Along a ray of growing load at fixed f H: Pe_l = Pe/sqrt(P_H/P) (units of the
    # load's Hertz half-width, docs/zones.md); its derivative in Pe vanishes at a fold.
    def pe_l(pe):
        return pe / np.sqrt(_steady(pe, K, fH * pe, lam, n).load_ratio)

    def slope(pe):
        h = 1e-5 * pe
        return (pe_l(pe + h) - pe_l(pe - h)) / (2 * h)
    return slope


def test_det_M0_vanishes_at_the_fold_of_the_load():
    K, lam, fH, n = 1.0, 1.0, 1.0, 24
    fold = brentq(_fold_function(K, lam, fH, n), 1.2, 1.27, xtol=1e-11)

    def det(pe):
        sign, logdet = np.linalg.slogdet(linearised(_steady(pe, K, fH * pe, lam, n)).matrix(0))
        return sign * np.exp(logdet - 30.0)
    singular = brentq(det, 1.2, 1.27, xtol=1e-11)
    # The two discretisations (slope and heat-flux form, displacement and temperature
    # form) agree there to 2e-3, 1e-4, 6e-6, 2e-9, 9e-11 at n = 8, 12, 16, 24, 32.
    assert singular == pytest.approx(fold, rel=1e-8)


def _known_problem(roots):
    """``M(b) = (b - A)(1 + 0.6 C/(b + 3))`` with real ``A`` whose eigenvalues are
    ``roots`` (closed under conjugation) and real ``C`` of unit norm:
    ``M(conj b) = conj M(b)``, and the second factor is regular and invertible for
    ``Re b > -2.4``."""
    rng = np.random.default_rng(3)
    blocks = []
    for r in roots:
        if r.imag > 0:
            blocks.append(np.array([[r.real, r.imag], [-r.imag, r.real]]))
        elif r.imag == 0:
            blocks.append(np.array([[r.real]]))
    size = sum(len(b) for b in blocks)
    J = np.zeros((size, size))
    k = 0
    for b in blocks:
        J[k:k + len(b), k:k + len(b)] = b
        k += len(b)
    Q = rng.standard_normal((size, size))
    A = Q @ J @ np.linalg.inv(Q)
    C = rng.standard_normal((size, size))
    C /= np.linalg.norm(C, 2)
    return lambda b: (b * np.eye(size) - A) @ (np.eye(size) + 0.6 * C / (b + 3.0))


class _Stand:
    """A stand-in for the linearised contact: the known problem, its last row taken
    for the temperature's (``n = size - 4``), the same at every ``n``."""

    moving = False
    RATE_UNITS = "k2/Delta^2"

    def __init__(self, roots):
        self._M = _known_problem(roots)
        self.n = self._M(1.0).shape[0] - 4
        self.temperature_rows = np.arange(self.n + 3, self.n + 4)

    def matrix(self, b, split=False):
        M = self._M(b)
        return (M, 0.0, M[self.n + 3].copy()) if split else M

    def matrices(self, rates):
        return np.stack([self._M(b) for b in rates])


ROOTS = [1.5 + 2.0j, 1.5 - 2.0j, 0.7 + 0j, -1.0 + 0j, 4.0 + 0.5j, 4.0 - 0.5j, 12.0 + 0j,
         2e-4 + 0j, 0.3 + 40.0j, 0.3 - 40.0j]


def _order(r):
    return (round(r.real, 6), round(r.imag, 6))


def test_the_argument_principle_counts_known_roots():
    """The winding of ``det M`` along Re b = b_min and the arc |b| = R counts the roots
    of the known problem in the region, with multiplicity, and none outside it: the
    pair at 0.3 +- 40i only once R passes 40, the root at 2e-4 never (below b_min),
    -1 never (left of the line)."""
    winding = Winding(_known_problem(ROOTS), 1e-3)
    assert winding.count(30.0) == (6, None)
    assert winding.count(1e4) == (8, None)
    assert Winding(_known_problem(ROOTS), 1e-4).count(1e4) == (9, None)
    # A double root counts twice.
    assert Winding(_known_problem([2.0 + 0j, 2.0 + 0j]), 1e-3).count(100.0) == (2, None)


def test_a_negative_winding_is_no_count():
    """det M(b) is analytic in the region, so its winding is a count of roots, never
    negative: a negative one (a phase lost between samples: n = 48 at Pe = fHPe = 1.5,
    K2/K1 = 1, lam = 1, past the fold, gave -2 before the power was divided out) is
    refused, not reported as a count.  Here
    a function with a double pole inside winds -2."""
    def pole(b):
        return np.array([[1.0 / (b - 1.0) ** 2]])
    count, why = Winding(pole, 1e-3).count(10.0)
    assert count is None and "negative" in why


@pytest.mark.parametrize("k", [0, 16, 40])
def test_a_power_of_b_turning_the_phase_is_divided_out(k):
    """det M(b) growing like b^k turns its phase by about k pi/2 along the line, several
    turns within one first step at large k: followed as it is, the count of the three
    roots of (1 + b)^k (b - 0.3 -+ 40i)(b - 2)/(b + 3)^3 is lost at k = 16 (the winding
    -5); with the measured power (1 + b)^p divided out (the same zeros, derivation S12)
    it is 3 at every k, from the same 48 evaluations (two of them the power's, on three
    rays; the corner where the arc meets the line one sample)."""
    def f(b):
        b = complex(b)
        return np.array([[np.exp(k * np.log1p(b)) * (b - (0.3 + 40j)) * (b - (0.3 - 40j))
                          * (b - 2.0) / (b + 3.0) ** 3]])
    winding = Winding(f, 1e-3)
    assert winding.count(1e6) == (3, None)
    assert winding.power == pytest.approx(k, abs=1e-3)
    assert len(winding.values) == 48
    if k == 16:
        raw = Winding(f, 1e-3)
        raw.power = 0.0
        assert raw.count(1e6)[0] is None


@pytest.mark.parametrize("R, expected", [(999980.0, 0), (1e6, 1), (1000020.0, 2)])
def test_roots_next_to_the_arc_do_not_spoil_the_measured_power(R, expected):
    """Two real roots within 1e-5 of ``R`` (999990 and 1000010) make ``|det M(R)|``
    tiny: the power measured on the real axis alone came out about -4 (the matrix's is
    about 4), the phase then turned like ``b^8`` and the count aliased to 2, 3, 4 where
    the region holds 0, 1, 2, certified.  The median of three rays' powers is not
    spoiled by one: the right counts, and the power the one without the roots."""
    roots = [999990.0 + 0j, 1000010.0 + 0j, -1.0 + 0j, -0.5 + 3j, -0.5 - 3j, -2.0 + 0j]
    for mode in (False, "refine"):
        winding = Winding(_known_problem(roots), 1e-3, ratios=mode)
        assert winding.count(R) == (expected, None)
        assert winding.power > 3.0


def test_the_determinant_equilibrated_and_its_phase_bounded():
    """``log_determinants`` of badly scaled complex matrices (rows and columns scaled by
    e^+-20) equals slogdet's phase and logarithm (to 1e-13 and 1e-12 of its size), and
    its rcond is that of the equilibrated matrix by its singular value decomposition (the
    inverse V S^-1 U^H) to 1e-8; an exactly singular matrix gives a zero phase and
    rcond 0."""
    from thermocontact.numerics.dense import log_determinants, row_scales

    rng = np.random.default_rng(3)
    for N in (3, 17, 40):
        stack = rng.normal(size=(3, N, N)) + 1j * rng.normal(size=(3, N, N))
        stack *= (np.exp(rng.uniform(-20, 20, (3, N, 1)))
                  * np.exp(rng.uniform(-20, 20, (3, 1, N))))
        for A, sign, logdet, rcond in zip(stack, *log_determinants(stack)):
            s0, l0 = np.linalg.slogdet(A)
            assert abs(sign - s0) < 1e-13 and abs(logdet - l0) < 1e-12 * abs(l0)
            r = row_scales(np.abs(A))
            B = A * r[:, None]
            B = B * row_scales(np.abs(B), axis=0)[None, :]
            U, sv, Vh = np.linalg.svd(B)
            inverse = (Vh.conj().T / sv) @ U.conj().T
            exact = 1.0 / (np.abs(B).sum(axis=0).max() * np.abs(inverse).sum(axis=0).max())
            assert rcond == pytest.approx(exact, rel=1e-8)
    singular = log_determinants(np.stack([np.ones((3, 3)), np.eye(3)]).astype(complex))
    assert singular[0][0] == 0 and singular[2][0] == 0 and singular[2][1] == 1.0


def test_a_phase_rounding_cannot_certify_a_count():
    """``det [[1, 1], [1, 1 + e (b + 1)]] = e (b + 1)`` has no root in the region, but at
    e = 1e-17 its phase is rounding (the bound N^2 u / rcond above PHASE_ERROR_MAX): no
    count, and the reason says so; at e = 1e-3 the count is 0."""
    def matrix(e):
        return lambda b: np.array([[1.0, 1.0], [1.0, 1.0 + e * (b + 1.0)]], dtype=complex)
    assert Winding(matrix(1e-3), 1e-3).count(100.0) == (0, None)
    count, why = Winding(matrix(1e-17), 1e-3).count(100.0)
    assert count is None and "uncertain" in why


def test_a_root_on_the_contour_is_not_counted_but_said():
    winding = Winding(_known_problem([1e-3 + 0.5j, 1e-3 - 0.5j]), 1e-3)
    count, why = winding.count(10.0)
    assert count is None and "contour" in why


def test_beyn_and_newton_find_known_eigenvalues():
    M = _known_problem(ROOTS)
    found, rank = beyn(M, half_disc(1e-3, 8.0), rank=5, probes=8)
    assert rank == 5
    inside = sorted([r for r in ROOTS if r.real >= 1e-3 and abs(r) <= 8.0], key=_order)
    np.testing.assert_allclose(sorted(found, key=_order), inside, atol=1e-8)
    for r in inside:
        b, step = newton(M, r + 0.05 - 0.03j)
        assert abs(b - r) < 1e-12


def test_newton_takes_one_evaluation_a_step():
    """Newton's method with the secant of the matrices (derivation S13): M and its forward
    difference at the first step, then one evaluation of M a step; from 0.06 away each
    simple root of a known problem to 1e-13 in at most six evaluations (central differences
    kept while the steps shrank tenfold took seven or eight), the last step proposed below
    Newton's tolerance."""
    M = _known_problem(ROOTS)
    for r in (1.5 + 2.0j, 0.7 + 0j, 4.0 + 0.5j, 12.0 + 0j, 0.3 + 40.0j):
        rates = []

        def counted(b):
            rates.append(b)
            return M(b)
        b, step = newton(counted, r + 0.05 - 0.03j)
        assert abs(b - r) < 1e-13 * abs(r) and step < 1e-10 * abs(r)
        assert len(rates) <= 6 and len(set(rates)) == len(rates)


def test_newton_from_two_earlier_iterates():
    """With ``previous``, the first step's divided difference is taken between it and
    the start (the error estimate's, from the last two iterates at n whose kernels are
    kept): no forward difference, the same root as from the start alone."""
    M = _known_problem(ROOTS)
    for r in (1.5 + 2.0j, 0.7 + 0j, 12.0 + 0j):
        rates = []

        def counted(b):
            rates.append(b)
            return M(b)
        start, before = r + 3e-4 - 2e-4j, r + 3e-4 - 2e-4j + 1e-7
        b, step = newton(counted, start, previous=before, tol=1e-3)
        assert rates == [before, start]
        ref, _ = newton(M, start, tol=1e-3)
        assert abs(b - ref) < 1e-9 * abs(r) and abs(b - r) < 1e-6 * abs(r)


def test_the_estimate_starts_from_the_last_iterates():
    """The error estimate's start (:func:`_estimate_start`): the two rates taken nearest
    the root, within 1e-6 of it and at least 1e-12 apart; otherwise the root itself and
    the forward difference."""
    from thermocontact.solvers.stability import _estimate_start

    b = 0.8 + 1.4j
    taken = [2.0 + 1j, b + 1e-3, b + 5e-7, b + 2e-10, b + 2e-10, b - 1e-14]
    assert _estimate_start(b, taken) == (b - 1e-14, b + 2e-10)
    assert _estimate_start(b, [b + 1e-3, b + 5e-7]) == (b, None)
    assert _estimate_start(b, [b + 1e-14, b + 2e-14, b + 1e-3]) == (b, None)


def test_kept_kernel_values_are_those_formed():
    """A body's kernel values kept per scale and rate (the error estimate's M at 3n/2
    takes those of the rates taken at n) are those formed, in the order asked, kept or
    not, and each rate is kept once."""
    from thermocontact.discretisation.linearised import (KERNEL_VALUES, _body_values,
                                                         _kept_values)

    rates = [1e-3 + 0.5j, 2.0 + 0j, 40.0 + 3.0j]
    for c in (0.0, 1.5):
        KERNEL_VALUES.clear()
        formed = _body_values(c, rates)
        first = _kept_values(c, rates[1:])
        both = _kept_values(c, rates[::-1])
        # A pass over other rates forms each rate's on its own rules (to rounding).
        tol = dict(rtol=1e-14, atol=1e-14 * np.abs(formed).max())
        np.testing.assert_allclose(first, formed[:, 4:], **tol)
        np.testing.assert_allclose(
            both, np.concatenate([formed[:, 8:], formed[:, 4:8], formed[:, :4]], axis=1), **tol)
        assert len(KERNEL_VALUES) == 3
        # A budget of one rate: those kept before are dropped while others are kept.
        budget = KERNEL_VALUES.max_bytes
        try:
            KERNEL_VALUES.clear()
            KERNEL_VALUES.max_bytes = formed[:, :4].nbytes
            _kept_values(c, rates[:1])
            small = _kept_values(c, rates)
        finally:
            KERNEL_VALUES.max_bytes = budget
        np.testing.assert_allclose(small, formed, **tol)
        assert len(KERNEL_VALUES) == 1


def test_newton_stays_on_the_sheet():
    """A Newton step that would cross ``Re b = floor`` (the cut of the stationary
    half-plane's kernels lies beyond it) is halved: the iterates stay right of it, and
    an iteration that cannot stay says so (step inf) instead of evaluating ``M`` there."""
    M = _known_problem([-1.0 + 0.1j, -1.0 - 0.1j])

    def guarded(b):
        assert b.real > 1e-3, b
        return M(b)
    b, step = newton(guarded, 0.05 + 0.1j, floor=1e-3)
    assert b.real > 1e-3 and not step < 1e-8
    # A halved step, however small its proposal, does not end the iteration: with the
    # root at 4e-4 left of the floor 5e-4, the iterates from 1.2e-3 go on to the floor
    # (the change 7e-4 of the 8e-4 to the root, where stopping at the first halved
    # step of a tolerance 1e-3 left half of it).
    M = _known_problem([4e-4 + 0j, 3.0 + 1.0j, 3.0 - 1.0j])
    b, step = newton(M, 1.2e-3 + 0j, floor=5e-4, tol=1e-3)
    assert 5e-4 < b.real < 5e-4 + 1e-8 and step == pytest.approx(1e-4, rel=1e-3)


def test_the_contour_tells_its_progress(monkeypatch):
    """stability_of tells each evaluation of M; classify tells them over all its
    events as one stage."""
    import thermocontact.solvers.stability as st
    from thermocontact.studies import event_kinds
    from thermocontact.studies.boundaries import Event, Path

    told = []
    monkeypatch.setattr(st, "linearised", lambda sol: _Stand(ROOTS[:2]))
    res = st.stability_of(lambda n: n, n=12, modulus_bound=100.0,
                          progress=lambda done, total: told.append((done, total)))
    assert [d for d, _ in told] == list(range(1, res.evaluations + 1))
    assert all(d <= t for d, t in told)
    assert res.unstable_modes == 2 and res.evaluations > 10

    events = tuple(Event(at=a, inequality="gap", edge="leading", valid_before=True,
                         valid_after=False) for a in (0.2, 0.3))
    path = Path(along="fhpe", fixed={"pe": 1.0, "K2_over_K1": 1.0, "lam": 0.5},
                x=np.array([0.0, 1.0]), valid=np.array([True, False]), events=events, n=8,
                method="graded", error_estimate=float("nan"))

    def stand_in(solve_at, n, progress=None, **region):
        for j in (1, 2, 3):
            progress(j, 3)
        return _result([])
    monkeypatch.setattr(event_kinds, "stability_of", stand_in)
    stages = []
    event_kinds.classify(path, progress=lambda *a: stages.append(a))
    assert stages == [("kinds of events", k, 6) for k in range(1, 7)]


def test_stability_refuses_what_it_does_not_model():
    sol = Model(5.0, 10.0, method="product", n=8).solve_at(8, 0.2, lam=0.0)
    with pytest.raises(InputError, match="method"):
        linearised(sol)


def _verdict(eigenvalues, stable="counted", count="located", reason=None):
    eigenvalues = np.array(eigenvalues, dtype=complex)
    count = len(eigenvalues) if count == "located" else count
    return StabilityResult(
        eigenvalues=eigenvalues, unstable_modes=count,
        stable=(count == 0) if stable == "counted" else stable, reason=reason,
        growth_rate=float(eigenvalues.real.max()) if eigenvalues.size else None,
        region=(1e-3, 1e4), count_method="argument principle", error_estimate=None,
        fold=0.1, slow_root=None, evaluations=40, n=8)


def test_stability_result_record():
    res = _verdict([1.0 + 2.0j, 1.0 - 2.0j])
    record = json.loads(json.dumps(res.to_dict(), allow_nan=False))
    assert record["stable"] is False and record["unstable_modes"] == 2
    assert record["eigenvalues"] == [[1.0, 2.0], [1.0, -2.0]]
    assert record["growth_rate"] == 1.0
    assert record["region"] == {"b_min": 1e-3, "modulus_bound": 1e4}
    uncertified = _verdict([], stable=None, count=None, reason="a root on the contour")
    record = json.loads(json.dumps(uncertified.to_dict(), allow_nan=False))
    assert record["stable"] is None and record["unstable_modes"] is None
    assert record["reason"] == "a root on the contour"
    assert pickle.loads(pickle.dumps(res)) == res
    assert "stable=False" in repr(res)


def test_LinearisedContact_size():
    sol = _steady(5.0, 10.0, 0.2, -1.0, 6)
    lin = LinearisedContact(sol.parameters, sol.representation, sol.phi, sol.psi,
                            sol.load_ratio, sol.sigma_over_delta)
    assert lin.matrix(0).shape == (lin.size, lin.size) == (15, 15)


def test_solve_command_adds_the_stability_record(capsys, monkeypatch):
    """``solve --stability``: the record of :func:`thermocontact.stability` of the very
    solution printed, under ``"stability"`` (the eigenvalues themselves are tested
    above; here a stand-in keeps the command fast)."""
    import thermocontact.api as api
    from thermocontact.cli import main

    seen = []

    def stand_in(sol, progress):
        # The command shows the contour's progress (a second a point).
        progress(1, 1)
        seen.append(sol)
        return _verdict([0.5 + 1.0j, 0.5 - 1.0j])
    monkeypatch.setattr(api, "stability", stand_in)
    args = ["solve", "--pe", "1", "--fhpe", "0.3", "--K2-over-K1", "1", "--lam", "-1",
            "-n", "16", "--stability"]
    assert main(args + ["--json"]) == 0
    rec = json.loads(capsys.readouterr().out)
    assert rec["stability"]["stable"] is False
    assert rec["stability"]["eigenvalues"] == [[0.5, 1.0], [0.5, -1.0]]
    assert seen[0].load_ratio == rec["load_ratio"]
    assert main(args) == 0
    assert "stable        = False" in capsys.readouterr().out


def _result(eigenvalues):
    return _verdict(eigenvalues)


def test_kinds_of_events(monkeypatch):
    """Each event's kind from the eigenvalues of the steady contact at the event itself
    (a stand-in for the eigenvalues; the solution it is given is checked), and the
    record carries ``kind`` only where it was computed."""
    from thermocontact.studies import event_kinds
    from thermocontact.studies.boundaries import Event, Path

    assert event_kinds.kind_of(_result([])) == "grazing"
    assert event_kinds.kind_of(_result([0.3, 0.1 + 2j, 0.1 - 2j])) == "fold"
    assert event_kinds.kind_of(_result([0.3 + 1j, 0.3 - 1j, 0.2])) == "hopf"
    assert event_kinds.kind_of(_verdict([], stable=False, count=2)) == "unstable"
    assert event_kinds.kind_of(_verdict([], stable=None, count=None)) == "uncertified"
    events = tuple(Event(at=a, inequality="gap", edge="leading", valid_before=True,
                         valid_after=False) for a in (0.2, 0.3, 0.4))
    path = Path(along="fhpe", fixed={"pe": 1.0, "K2_over_K1": 1.0, "lam": 0.5},
                x=np.array([0.0, 1.0]), valid=np.array([True, False]), events=events, n=8,
                method="graded", error_estimate=float("nan"))
    answers = iter([_result([]), _result([0.5]), _result([0.1 + 1j, 0.1 - 1j])])
    seen = []

    def stand_in(solve_at, n, **region):
        seen.append(solve_at(n))
        return next(answers)
    monkeypatch.setattr(event_kinds, "stability_of", stand_in)
    out = event_kinds.classify(path)
    assert [e.kind for e in out.events] == ["grazing", "fold", "hopf"]
    assert [s.parameters.fhpe for s in seen] == [0.2, 0.3, 0.4]
    assert all(s.lam == pytest.approx(0.5, abs=1e-12) for s in seen)
    assert "kind" not in path.to_dict()["events"][0]
    assert out.to_dict()["events"][1]["kind"] == "fold"


def _convergence():
    """The stored eigenvalue of the growing pair at n = 8 ... 32
    (tests/data/make_stability_convergence.py)."""
    path = pathlib.Path(__file__).parent / "data" / "stability_convergence.json"
    data = json.loads(path.read_text())
    return data["case"], data["levels"]


def test_a_growing_pair_past_a_fold():
    """Past the fold of the ray K2/K1 = 1, lam = 1, fH = 1 (Pe = 1.5) the stored pair
    (docs/stability.md) makes M singular at n = 8, a simple root confirmed by a step of
    Newton's method on det M (below 1e-10 of |b|), and its conjugate too:
    M(conj b) = conj M(b); at n = 12 the stored eigenvalue, 5e-2 away, is a root there."""
    case, levels = _convergence()
    assert case == {"pe": 1.5, "K2_over_K1": 1.0, "fhpe": 1.5, "lam": 1.0}
    at = {r["n"]: complex(*r["b"]) for r in levels}
    lin = linearised(_steady(1.5, 1.0, 1.5, 1.0, 8))
    b = at[8]
    M = lin.matrix(b)
    sv = np.linalg.svd(M, compute_uv=False)
    assert sv[-1] < 1e-13 * sv[0] and sv[-2] > 1e-8 * sv[0]
    root, step = newton(lambda z: M if z == b else lin.matrix(z), b, steps=1)
    assert step < 1e-10 * abs(b) and abs(root - b) < 1e-10 * abs(b)
    assert_ulps(lin.matrix(np.conj(b)), np.conj(M))  # a symmetry, to the rounding
    assert abs(at[12] - b) > 1e-2
    sv = np.linalg.svd(linearised(_steady(1.5, 1.0, 1.5, 1.0, 12)).matrix(at[12]),
                       compute_uv=False)
    assert sv[-1] < 1e-13 * sv[0]


def test_the_growing_pair_converges_in_n():
    """The stored eigenvalue at n = 8, 12, 16, 20, 24 against n = 32: the change falls
    at every step at an observed algebraic order above 10 (10.1, 13.1, 15.0, 11.3:
    faster than any fixed order, as the steady solution's, derivation section 12), to
    below 1e-7 at n = 24; at every n the stored root is a simple root (smallest singular
    value of M below 1e-17 of the largest, the next above 1e-10) where Newton's last
    step was below 1e-12."""
    _, levels = _convergence()
    n = np.array([r["n"] for r in levels], dtype=float)
    assert n.tolist() == [8, 12, 16, 20, 24, 32]
    b = np.array([complex(*r["b"]) for r in levels])
    change = np.abs(b[:-1] - b[-1]) / np.abs(b[-1])
    order = np.log(change[:-1] / change[1:]) / np.log(n[1:-1] / n[:-2])
    assert np.all(order > 10.0)
    assert change[-1] < 1e-7 and change[0] > 1e-2
    for r in levels:
        assert r["smallest_singular_value"] < 1e-17 and r["second_singular_value"] > 1e-10
        assert r["newton_step"] < 1e-12


@pytest.mark.parametrize("closure", [
    dict(lam=-1), dict(closure=BulkTemperatures("60C", "20C", sink_distance="30mm"))])
def test_physical_contact_rates_in_per_second(monkeypatch, closure):
    """``stability(contact(...))`` analyses the primary branch at its own Pe, fHPe and
    lam (the one the bulk temperatures imply, where they close the problem) and
    reports in 1/s: the unit k2/Delta^2 of the half-plane's diffusivity and the branch's
    half-width; with the Dundurs term (on by default) at the pair's beta f."""
    import thermocontact as tc
    import thermocontact.solvers.stability as st

    kwargs = dict(cylinder="copper", half_plane="steel", radius="10mm", load="50kN/m",
                  speed="2m/s", friction=0.2, **closure)
    res = tc.contact(**kwargs)
    branch = res.primary
    seen = {}

    def stand_in(solve_at, rate_unit=None, **region):
        seen["solution"], seen["unit"] = solve_at(32), rate_unit
        return _result([])
    monkeypatch.setattr(st, "stability_of", stand_in)
    tc.stability(res)
    assert seen["unit"] == pytest.approx(res.problem.half_plane.k / branch.half_width ** 2,
                                         rel=1e-14)
    assert seen["solution"].parameters.pe == pytest.approx(branch.pe, rel=1e-14)
    assert seen["solution"].parameters.fhpe == pytest.approx(branch.fhpe, rel=1e-14)
    assert seen["solution"].load_ratio == pytest.approx(branch.load_ratio, rel=1e-8)
    assert seen["solution"].lam == pytest.approx(branch.lam, rel=1e-12)
    assert seen["solution"].parameters.beta_f == res.problem.beta_f != 0.0


def test_stability_of_orders_pairs_and_estimates(monkeypatch):
    """The driver on known problems standing in for ``M(b)`` at ``n`` and ``3n/2``: the
    count of the region's roots, both members of each pair, largest real part first,
    only what lies in the region, the change to ``3n/2`` as the error estimate, and
    rates in 1/s with ``rate_unit``."""
    import thermocontact.solvers.stability as st

    fine = ROOTS
    coarse = [r + 2e-2 for r in fine]
    monkeypatch.setattr(st, "linearised", lambda n: _Stand(fine if n == 12 else coarse))
    res = st.stability_of(lambda n: n, n=12, modulus_bound=30.0)
    expected = [12.0, 4.0 + 0.5j, 4.0 - 0.5j, 1.5 + 2.0j, 1.5 - 2.0j, 0.7]
    assert res.unstable_modes == 6 and res.stable is False and res.reason is None
    np.testing.assert_allclose(res.eigenvalues, expected, atol=1e-9)
    assert res.growth_rate == pytest.approx(12.0, abs=1e-9)
    # The root 0.7 moves by 2e-2, relative to max(|b|, 1) = 1: Newton's method at 3n/2
    # runs to a step below ESTIMATE_TOL, the change then within C s s' of the move.
    assert res.error_estimate == pytest.approx(2e-2, rel=1e-5)
    # A move below ESTIMATE_TOL is one step: within C s of itself, C ~ 1 here (S13).
    small = [r + 5e-4 for r in fine]
    monkeypatch.setattr(st, "linearised", lambda n: _Stand(fine if n == 12 else small))
    one = st.stability_of(lambda n: n, n=12, modulus_bound=30.0)
    assert one.error_estimate == pytest.approx(5e-4, rel=2e-3)
    monkeypatch.setattr(st, "linearised", lambda n: _Stand(fine if n == 12 else coarse))
    per_second = st.stability_of(lambda n: n, n=12, modulus_bound=30.0, rate_unit=2.0)
    np.testing.assert_allclose(per_second.eigenvalues, 2.0 * res.eigenvalues, rtol=1e-12)
    assert per_second.units == "1/s" and per_second.region == (2e-3, 60.0)
    # With the pair at 0.3 +- 40i inside: eight, the pair located too.
    wide = st.stability_of(lambda n: n, n=12, modulus_bound=100.0)
    assert wide.unstable_modes == 8 and len(wide.eigenvalues) == 8
    for bad in (dict(b_min=0.0), dict(modulus_bound=1e-3), dict(n=13), dict(n="12")):
        with pytest.raises(InputError):
            st.stability_of(lambda n: n, **bad)


@pytest.mark.parametrize("roots, guesses", [
    ([40.0 + 0j], [25.0]),                        # one real root: the bracket narrowed
    ([40.0 + 0j], [3e-3, 9e5]),                    # guesses far off, at the region's ends
    ([1.5 + 2.0j, 1.5 - 2.0j, 0.7 + 0j], [1.45 + 2.1j, 0.72]),   # Newton from each
    ([1.5 + 2.0j, 1.5 - 2.0j, 0.7 + 0j], [30.0 + 1j, -4.0]),     # useless: Beyn's method
])
def test_a_neighbours_eigenvalues_change_nothing_but_the_work(monkeypatch, roots, guesses):
    """``stability_of(..., guesses=...)`` (a neighbour's eigenvalues, continued across a
    map): the same count and the same eigenvalues (to Newton's tolerance) as without
    them, whether the guesses are close, far or outside the region; where a single real
    root's guess is close, fewer evaluations of M (its bracket on the grid of real rates
    started there).  The same with a neighbour's contour samples (``samples``) and a
    predicted real root (``predictions``: the bracket started there where one root is
    counted)."""
    import thermocontact.solvers.stability as st

    monkeypatch.setattr(st, "linearised", lambda n: _Stand(roots))
    plain = st.stability_of(lambda n: n, n=12, modulus_bound=1e3)
    guessed = st.stability_of(lambda n: n, n=12, modulus_bound=1e3, guesses=guesses)
    assert plain.unstable_modes == guessed.unstable_modes == len(roots)
    assert plain.reason is None and guessed.reason is None
    np.testing.assert_allclose(guessed.eigenvalues, plain.eigenvalues, rtol=1e-9)
    np.testing.assert_allclose(sorted(guessed.eigenvalues, key=_order),
                               sorted(roots, key=_order), rtol=1e-9)
    if len(roots) == 1 and abs(guesses[0] - roots[0]) < 0.5 * abs(roots[0]):
        assert guessed.evaluations < plain.evaluations
    # A neighbour's contour samples (here the same contact's), evaluated first: the
    # same count and eigenvalues, on the neighbour's samples and those the phase alone
    # adds (with samples a step is confirmed by the phase only: its refinements kept).
    seeded = st.stability_of(lambda n: n, n=12, modulus_bound=1e3, guesses=guesses,
                             samples=plain.samples)
    assert seeded.unstable_modes == plain.unstable_modes and seeded.reason is None
    # To Newton's tolerance: the phase alone samples more, so Beyn's estimates differ.
    np.testing.assert_allclose(seeded.eigenvalues, guessed.eigenvalues, rtol=1e-9)
    again = st.stability_of(lambda n: n, n=12, modulus_bound=1e3, guesses=guesses,
                            samples=seeded.samples)
    assert sorted(again.samples, key=_order) == sorted(seeded.samples, key=_order)
    # A real root predicted close by: its bracket started there, fewer evaluations; one
    # predicted off the sheet or far away changes nothing but the work.
    for predictions in ([0.97 * roots[-1].real], [-3.0], [9e5]):
        predicted = st.stability_of(lambda n: n, n=12, modulus_bound=1e3,
                                    predictions=predictions)
        assert predicted.unstable_modes == plain.unstable_modes
        np.testing.assert_allclose(predicted.eigenvalues, plain.eigenvalues, rtol=1e-9)
    if len(roots) == 1:
        close = st.stability_of(lambda n: n, n=12, modulus_bound=1e3,
                                predictions=[0.97 * roots[0].real])
        assert close.evaluations < plain.evaluations


@pytest.mark.parametrize("root, below", [(1.05e-3, None), (1.05e-3, 9.9e-4), (0.9, None),
                                         (40.0, None), (3.3e4, None), (9.7e5, None),
                                         (9.99e5, 1.0005e6)])
def test_a_single_real_root_is_found_on_the_grid_by_the_secant_method(monkeypatch, root,
                                                                       below):
    """One root in the region, real, next to ``b_min`` and to ``R`` too, between the
    region's end and the grid's first point (other roots left of the line, and where
    given one just outside the region, ``below``): bracketed on the grid of real rates
    and found by the secant method from the polynomial's estimate (Newton's method, the
    fallback, never called: the root outside is not taken) to rounding, with or without
    a start; a close start (a neighbour's root or a prediction) costs fewer evaluations
    of M than none, a far one changes nothing but the work."""
    import thermocontact.solvers.stability as st

    roots = [complex(root), -1.0 + 0j, -0.5 + 3j, -0.5 - 3j, -2.0 + 0j]
    if below is not None:
        roots.append(complex(below))
    monkeypatch.setattr(st, "linearised", lambda n: _Stand(roots))

    def no_newton(*args, **kwargs):
        raise AssertionError("Newton's method called")
    monkeypatch.setattr(st, "newton", no_newton)
    plain = st.stability_of(lambda n: n, n=12, estimate=False)
    for start in (dict(), dict(guesses=[root * (1.15 if root < 1 else 0.8)]),
                  dict(predictions=[root * (1.02 if root < 1 else 0.98)]),
                  dict(guesses=[2e-3 if root > 0.1 else 5e5])):
        res = st.stability_of(lambda n: n, n=12, estimate=False, **start)
        assert res.unstable_modes == 1 and res.reason is None
        assert abs(res.eigenvalues[0] - root) <= 1e-12 * max(1.0, root)
        if start and abs(next(iter(start.values()))[0] / root - 1) < 0.25:
            assert res.evaluations < plain.evaluations


def test_map_gains_stable_and_growth_rate(tmp_path, capsys, monkeypatch):
    """``parameter_map(..., stability=True)`` (a 2 x 2 map, the smallest): each point
    analysed at its own inputs and at the map's heat partition there (the solution
    given to the eigensolver, at the map's n, is the map's own); ``stable`` and
    ``growth_rate`` from the stand-in's eigenvalues (largest real part, NaN where none);
    ``map --stability`` passes the flag on, and an operating map is refused in one line."""
    import thermocontact as tc
    import thermocontact.cli.maps as cli_maps
    from thermocontact.cli import main
    from thermocontact.studies import event_kinds

    answers = iter([_result([]), _result([0.25 + 1j, 0.25 - 1j, 0.75]), _result([0.5]),
                    _verdict([], stable=None, count=None, reason="a root on the contour")])
    seen = []

    def stand_in(solve_at, n, **region):
        seen.append(solve_at)
        return next(answers)
    monkeypatch.setattr(event_kinds, "stability_of", stand_in)
    ds = tc.parameter_map(tc.Axis("fhpe", 0.2, 0.3, 2), tc.Axis("pe", 1.0, 1.2, 2),
                          K2_over_K1=10, lam=0.5, tol=1e-4, stability=True)
    # Each point's solve at the map's n: the map's own solution.
    seen = [solve_at(n) for solve_at, n in zip(seen, ds["n"].values.ravel())]
    assert ds["stable"].values.tolist() == [[1, 0], [0, -2]]
    assert ds["unstable_modes"].values.tolist() == [[0, 3], [1, -1]]
    rate = ds["growth_rate"].values
    assert np.isnan(rate[[0, 1], [0, 1]]).all() and rate[0, 1] == 0.75 and rate[1, 0] == 0.5
    assert ds["growth_rate"].attrs["units"] == "k2/Delta^2"
    assert [(s.parameters.pe, s.parameters.fhpe) for s in seen] == [
        (1.0, 0.2), (1.0, 0.3), (1.2, 0.2), (1.2, 0.3)]
    assert all(s.parameters.K2_over_K1 == 10.0 and s.lam == 0.5 for s in seen)
    np.testing.assert_allclose([s.load_ratio for s in seen], ds["load_ratio"].values.ravel(),
                               rtol=1e-10)
    np.testing.assert_allclose([s.sigma_over_delta for s in seen],
                               ds["sigma_over_delta"].values.ravel(), rtol=1e-10)
    runs = []
    monkeypatch.setattr(cli_maps, "run_map", lambda *args: runs.append(args))
    assert main(["map", "--x", "fhpe:0.2:0.3:2", "--y", "pe:1:1.2:2", "--K2-over-K1", "10",
                 "--lam", "0.5", "--out", str(tmp_path / "m.nc"), "--stability"]) == 0
    assert runs[0][-1] is True
    capsys.readouterr()
    assert main(["map", "--x", "load:1e4:1e5:2", "--y", "speed:1:2:2", "--cylinder", "copper",
                 "--half-plane", "steel", "--radius", "10mm", "--friction", "0.2",
                 "--lam", "-1", "--out", str(tmp_path / "o.nc"), "--stability"]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "--stability maps dimensionless parameters only" in err[0]
    # What the analysis does not model is refused before the map is computed.
    import thermocontact.studies.maps as maps

    def not_computed(*args, **kw):
        raise AssertionError("the map was computed")
    monkeypatch.setattr(maps, "compute_map", not_computed)
    for kw, words in ((dict(method="galerkin"), "edge-graded method"),):
        with pytest.raises(InputError, match=words):
            tc.parameter_map(tc.Axis("fhpe", 0.2, 0.3, 2), tc.Axis("pe", 1.0, 1.2, 2),
                             K2_over_K1=10, lam=0.5, stability=True, **kw)
    with pytest.raises(InputError, match="dimensionless parameters only"):
        tc.compute_map(tc.map_spec(tc.Axis("load", 1e4, 1e5, 2), tc.Axis("speed", 1, 2, 2),
                                   cylinder="copper", half_plane="steel", friction=0.2,
                                   radius=0.01, lam=-1), stability=True)


def test_half_plane_waves_shorter_than_the_contact_decay():
    """docs/stability.md, modes short against the contact: at the copper-steel contact
    (50 kN/m, 2 m/s, f = 0.2, lam = -1, no Dundurs term: Delta = 77.6 um and fHPe =
    0.159 from ``contact``) the sliding half-planes grow at m Delta = 0.01, above the
    critical wavelength, and not at m Delta >= 0.1 (no discrete mode from 0.3); the
    critical wavelength in half-widths, L_c/Delta = Gamma/fHPe, has Gamma = C f H/(2 k2)
    = 92.6 with C = V_c L the pair's constant, the same at two wavelengths."""
    import math

    from thermocontact.physics.tei import SlidingPair
    from thermocontact.problem.materials import get_material
    from thermocontact.studies.tei import critical_speed, growth_rate

    pair = SlidingPair(get_material("copper"), get_material("steel"), 0.2, dundurs=False)
    delta, fhpe, speed = 7.763386328106788e-05, 0.15929446878466574, 2.0
    unit = get_material("steel").k / delta ** 2
    assert 0 < growth_rate(pair, 0.01 / delta, speed) / unit < 1e-3
    assert -0.1 < growth_rate(pair, 0.1 / delta, speed) / unit < -0.01
    for m_delta in (0.3, 1.0, 10.0):
        assert growth_rate(pair, m_delta / delta, speed) == -math.inf
    gamma = [critical_speed(pair, 2 * math.pi / L)[0] * L * fhpe / (speed * delta)
             for L in (0.02, 0.05)]
    assert gamma == pytest.approx([92.6, 92.6], rel=1e-3)


def test_kinds_of_events_on_a_path_closed_by_the_far_temperatures(monkeypatch):
    """A path closed by the far temperatures (theta, L/Delta) is analysed at the steady
    contact those temperatures make: the solution handed to the eigensolver is the one
    of ``solve(..., closure=FarTemperatures(theta, L/Delta))`` at the event."""
    from thermocontact import FarTemperatures, solve
    from thermocontact.studies import event_kinds
    from thermocontact.studies.boundaries import Event, Path

    fixed = {"pe": 5.0, "K2_over_K1": 10.0, "theta": 1.0, "sink_distance": 30.0}
    event = Event(at=0.2, inequality="gap", edge="leading", valid_before=True,
                  valid_after=False)
    path = Path(along="fhpe", fixed=fixed, x=np.array([0.0, 1.0]),
                valid=np.array([True, False]), events=(event,), n=8, method="graded",
                error_estimate=float("nan"))
    seen = []

    def stand_in(solve_at, n, **region):
        seen.append(solve_at(32))
        return _result([])
    monkeypatch.setattr(event_kinds, "stability_of", stand_in)
    assert event_kinds.classify(path).events[0].kind == "grazing"
    direct = solve(5.0, 0.2, 10.0, closure=FarTemperatures(1.0, 30.0), n=32)
    assert seen[0].lam == pytest.approx(direct.lam, abs=1e-12)
    assert seen[0].load_ratio == pytest.approx(direct.load_ratio, rel=1e-12)


def test_a_finished_map_without_its_stability_is_not_passed_off_as_analysed(tmp_path,
                                                                             capsys):
    """``map --stability`` on the ``--out`` of the same map computed without it: refused
    in one line (it once said "nothing to compute" and exited 0 without the fields)."""
    from thermocontact.cli import main

    args = ["map", "--x", "fhpe:0.2:0.3:2", "--y", "pe:1:1.2:2", "--K2-over-K1", "10",
            "--lam", "0.5", "--tol", "1e-4", "--out", str(tmp_path / "m.nc")]
    assert main(args) == 0
    capsys.readouterr()
    assert main(args + ["--stability"]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "without its eigenvalues" in err[0] and "--stability" in err[0]
    assert main(args) == 0
    assert "nothing to compute" in capsys.readouterr().out


# --- The verdict on real contacts (shared: each a few seconds) ------------------------

@pytest.fixture(scope="module")
def growing_pair():
    """The steady contact past the fold (Pe = fHPe = 1.5, K2/K1 = 1, lam = 1) at n = 12,
    its linearised contact and its verdict with the defaults."""
    sol = _steady(1.5, 1.0, 1.5, 1.0, 12)
    return sol, linearised(sol), stability_of(lambda m: _steady(1.5, 1.0, 1.5, 1.0, m))


def test_the_growing_pair_is_counted_and_located(growing_pair):
    """The pair the ellipse of Re b in [0.5, 10], |Im b| <= 10 once missed
    (docs/stability.md): counted (2 eigenvalues with Re b >= 1e-3, |b| <= 1e6), located
    and confirmed at the stored n = 12 root (tests/data/stability_convergence.json) to
    1e-9; not stable."""
    _, levels = _convergence()
    stored = complex(*[r["b"] for r in levels if r["n"] == 12][0])
    _, _, res = growing_pair
    assert res.stable is False and res.unstable_modes == 2 and res.reason is None
    np.testing.assert_allclose(res.eigenvalues, [stored, np.conj(stored)], rtol=1e-9)
    assert res.growth_rate == pytest.approx(stored.real, rel=1e-9)
    assert res.region == (1e-3, 1e6)


def test_the_count_against_beyn_on_another_contour(growing_pair):
    """A second method: the rank of Beyn's zeroth moment (its singular values, not the
    winding) on a different contour, the boundary of Re b >= 0.2, |b| <= 3, finds two
    eigenvalues, Newton's method takes them to the verdict's; the winding on that
    contour counts two as well."""
    _, lin, res = growing_pair
    found, rank = beyn(lin.matrix, half_disc(0.2, 3.0, nodes=6, panels_per_unit=0.5),
                       probes=6, tol=1e-6)
    assert rank == 2
    polished = sorted((newton(lin.matrix, b, floor=0.1)[0] for b in found), key=_order)
    np.testing.assert_allclose(polished, sorted(res.eigenvalues, key=_order), rtol=1e-9)
    assert Winding(lin.matrix, 0.2).count(3.0) == (2, None)


@pytest.fixture(scope="module")
def fig4_contact():
    """A valid steady contact of the paper's Fig. 4 (Pe = 5, fHPe = 0.2, K2/K1 = 10,
    lam = -1) at n = 12 and its verdict."""
    model = Model(5.0, 10.0)

    def solve_at(m):
        return model.solve_at(m, 0.2, lam=-1.0, check_validity=False)
    return model.solve_at(12, 0.2, lam=-1.0), stability_of(solve_at)


def test_steps_confirmed_by_the_eigenvalues_where_the_phase_does_not(growing_pair,
                                                                     fig4_contact):
    """The single patch's count confirms a step by the eigenvalues of ``M(a)^-1 M(b)``
    (S25) where the determinant's phase at its ends and midpoint does not, before
    cutting it (``ratios="refine"``): past the fold and at Fig. 4's contact the same
    counts as by the phase alone (2 and 0) on fewer samples of M."""
    from thermocontact.solvers.stability import Winding, scaled_matrix

    sol, lin, res = growing_pair
    assert res.unstable_modes == 2 and "eigenvalues of M(a)^-1 M(b)" in res.count_method
    contacts = [lin, linearised(fig4_contact[0])]
    for contact, expected in zip(contacts, (2, 0)):
        counts = {}
        for mode in (False, "refine"):
            winding = Winding(scaled_matrix(contact), 1e-3,
                              many=scaled_matrix(contact, many=True), ratios=mode)
            counts[mode] = (winding.count(1e6), len(winding.values))
        assert counts[False][0] == counts["refine"][0] == (expected, None)
        assert counts["refine"][1] < counts[False][1]


def test_a_stack_of_rates_is_kept_and_found_again(growing_pair):
    """``LinearisedContact.matrices`` keeps the moments of a stack of rates
    (``STACKED_MOMENTS``): the same rates give the same matrices from the kept stack as
    from each rate's own moments, and another contact's cylinder (another Peclet
    number) finds no stack of the first's."""
    from thermocontact.discretisation.linearised import STACKED_MOMENTS

    sol, lin, res = growing_pair
    rates = [complex(b) for b in res.samples[:6]]
    first = lin.matrices(rates)
    kept = len(STACKED_MOMENTS)
    again = lin.matrices(rates)
    assert len(STACKED_MOMENTS) == kept
    np.testing.assert_array_equal(again, first)
    one = np.stack([lin.matrix(b) for b in rates])
    np.testing.assert_allclose(first, one, rtol=0, atol=1e-12 * np.abs(one).max())
    other = linearised(_steady(1.6, 1.0, 1.5, 1.0, 12))
    other.matrices(rates)
    assert len(STACKED_MOMENTS) == kept + 1


def test_a_valid_contact_of_the_paper_is_stable(fig4_contact):
    """No eigenvalue with Re b >= 1e-3 anywhere within |b| <= 1e6; Beyn's rank on the
    boundary of Re b >= 0.05, |b| <= 4 is 0 too (the second method)."""
    sol, res = fig4_contact
    assert sol.validity.valid
    assert res.stable is True and res.unstable_modes == 0 and res.reason is None
    assert len(res.eigenvalues) == 0 and res.growth_rate is None
    _, rank = beyn(linearised(sol).matrix, half_disc(0.05, 4.0, nodes=6, panels_per_unit=0.5),
                   probes=6, tol=1e-6)
    assert rank == 0


def test_no_eigenvalue_approaches_beyond_the_modulus_bound(fig4_contact, growing_pair):
    """Past the default bound (derivation S11) these two contacts have no eigenvalue near:
    along rays at arg b = 0, 0.3 pi, 0.49 pi the temperature-scaled M(b) keeps its
    smallest singular value within a factor 10 of its value at |b| = 1e6 out to 1e8."""
    for lin in (linearised(fig4_contact[0]), growing_pair[1]):
        n = lin.n
        for angle in (0.0, 0.3 * np.pi, 0.49 * np.pi):
            smallest = []
            for modulus in (1e6, 1e7, 1e8):
                b = modulus * np.exp(1j * angle)
                M = lin.matrix(b)
                M[n + 3:] *= np.sqrt(1.0 + b)
                smallest.append(np.linalg.svd(M, compute_uv=False)[-1])
            assert min(smallest) > 0.1 * smallest[0] > 0.0


def test_stability_refuses_what_is_not_a_steady_single_patch():
    """``stability(None)``, a string or a dict: one InputError naming ``solution``
    (they were tracebacks)."""
    import thermocontact as tc

    for bad in (None, "x", {"pe": 1.0}):
        with pytest.raises(InputError, match="solution must be") as err:
            tc.stability(bad)
        assert err.value.parameters == ("solution",)


def test_stability_flags_are_booleans(monkeypatch):
    """``parameter_map(..., stability='yes')`` and ``boundary(..., stability='yes')``
    are refused before any work (they started the analysis); True and False pass."""
    import thermocontact as tc
    import thermocontact.studies.maps as maps

    def not_computed(*args, **kw):
        raise AssertionError("the map was computed")
    monkeypatch.setattr(maps, "compute_map", not_computed)
    for value in ("yes", 1, None):
        with pytest.raises(InputError, match="stability must be True or False") as err:
            tc.parameter_map(tc.Axis("fhpe", 0.2, 0.3, 2), tc.Axis("pe", 1.0, 1.2, 2),
                             K2_over_K1=10, lam=0.5, stability=value)
        assert err.value.parameters == ("stability",)
        with pytest.raises(InputError, match="stability must be True or False"):
            tc.boundary("fhpe", 0, 1, pe=5, K2_over_K1=10, lam=1, stability=value)
    with pytest.raises(AssertionError, match="computed"):
        tc.parameter_map(tc.Axis("fhpe", 0.2, 0.3, 2), tc.Axis("pe", 1.0, 1.2, 2),
                         K2_over_K1=10, lam=0.5, stability=np.bool_(False))


def test_solve_stability_with_another_method_is_refused_before_the_solve(capsys,
                                                                        monkeypatch):
    """``solve --stability --method paper`` (and ``galerkin``): one line, exit 2,
    nothing solved (it solved for 17 s, then printed a warning and an error)."""
    import thermocontact.api as api
    from thermocontact.cli import main

    def not_solved(*args, **kw):
        raise AssertionError("solved")
    monkeypatch.setattr(api, "solve", not_solved)
    base = ["solve", "--pe", "1.5", "--fhpe", "1.5", "--K2-over-K1", "1", "--lam", "1",
            "--stability"]
    for extra, words in ((["--method", "paper"], "edge-graded --method"),
                         (["--method", "galerkin"], "edge-graded --method")):
        assert main(base + extra) == 2
        captured = capsys.readouterr()
        err = captured.err.strip().splitlines()
        assert len(err) == 1 and words in err[0], err
        assert captured.out == ""


def test_the_moving_half_plane_reduces_to_the_stationary_one(growing_pair):
    """Rolling-sliding (derivation S14): at R = +-1e-12 the pair past the fold is the
    stationary half-plane's to 1e-10, although the steady offset jumps there (D14c) and
    the half-plane's kernels are a moving body's, without the stationary one's constants
    and partition row (the same eigenvalues: the constants are a rigid displacement and
    a rotation, absorbed by D~ and sigma~)."""
    _, _, res = growing_pair
    root = res.eigenvalues[0]
    for R in (1e-12, -1e-12):
        lin = linearised(Model(1.5, 1.0, speed_ratio=R).solve_at(12, 1.5, lam=1.0,
                                                                 check_validity=False))
        assert lin.moving
        b, step = newton(lin.matrix, root, floor=1e-4)
        assert step < 1e-10 and abs(b - root) < 1e-10 * abs(root)


@pytest.mark.parametrize("c, b", [(0.0, 1e-3 + 1e-2j), (5.0, 2.0 + 3.0j), (50.0, 1.0 + 1.0j),
                                  (0.0, 1e4j), (0.0, 1e-3 + 600j)])
def test_tabulated_moments_are_the_moment_engines(c, b):
    """The kernel table (moments as a fixed linear map of the kernel's values at fixed
    nodes, derivation S9) against the moment engine, for the transient slope difference,
    temperature and gradient of a body at (c, b), both weights, n = 8: to 1e-13 of the
    largest entry (4e-12 at b = 1e4 i, a layer of 1/100).  The stationary half-plane's
    (c = 0) also from its values at the coarse nodes (panels of ratio 2), and its
    displacement less its constant: to the same tolerances (3.6e-12 at b = 1e-3 + 600i;
    on the count's line Re b = 1e-3 and arc |b| = 1e6 at most 4.8e-12, near b = 220i,
    between its samples 5.5e-12, and 1.3e-14 for |b| < 30, derivation S9)."""
    from thermocontact.numerics.tabulated_moments import kernel_nodes, kernel_table
    from thermocontact.physics import transient_green_functions as tk
    from thermocontact.physics.green_functions import moving_slope

    rep = _steady(1.0, 1.0, 0.3, -1.0, 8).representation
    x, _, _ = projections(8)
    s, tau = rep.projection_points(x)
    table = kernel_table(tau, 8, rep.to_cos)
    nodes = [kernel_nodes()] + ([kernel_nodes(coarse=True)] if c == 0 else [])
    scale = max(1.0, c, abs(np.sqrt(b)))
    slope0 = (lambda v: moving_slope(v, c)) if c else (lambda v: 0.5 * np.sign(v))
    kernels = [(lambda v: tk.transient_slope(v, c, b) - slope0(v), False),
               (lambda v: tk.transient_temperature(v, c, b), True),
               (lambda v: tk.transient_temperature_gradient_regular(v, c, b), True)]
    if c == 0:
        kernels.append((lambda v: tk.transient_displacement(v, c, b)
                        - 2.0 / (np.pi * np.sqrt(b)), False))
    tol = 1e-13 if abs(b) < 100 else 1e-11
    for kernel, log in kernels:
        engine = rep.integrate(kernel, s, scale=scale, logarithmic=log, aux=tau)
        for u in nodes:
            tabled = table.moments(kernel(u))
            for w in range(2):
                assert np.abs(tabled[w] - engine[w]).max() < tol * np.abs(engine[w]).max()
    # The assembly's values: the coarse nodes for the stationary half-plane alone (a
    # moving body's wake needs the fine ones, S9).
    from thermocontact.discretisation.linearised import _body_values
    assert _body_values(c, b).shape[0] == nodes[-1].size == (
        kernel_nodes(coarse=True) if c == 0 else kernel_nodes()).size


def test_a_valid_contact_with_a_fast_mode_at_its_edges():
    """Path (a) at fHPe = 0.65 (Pe = 5, K2/K1 = 10, lam = 1; valid): the count finds
    one real eigenvalue near 2e4 k2/Delta^2 (derivation S11, docs/stability.md), stored
    by tests/data/make_edge_mode.py with its values at n = 8 ... 48.  The stored root at
    n = 12 makes M singular (a simple root); the values converge in n (the change against
    n = 48: 4.7e-2, 3.2e-3, 1.8e-3, 1.3e-4 at n = 12, 16, 24, 32): a mode of the
    equations, not of the discretisation."""
    path = pathlib.Path(__file__).parent / "data" / "edge_mode.json"
    data = json.loads(path.read_text())
    assert data["valid"] and data["verdict"]["unstable_modes"] == 1
    assert data["verdict"]["stable"] is False and data["verdict"]["region"]["modulus_bound"] == 1e6
    levels = {r["n"]: r for r in data["levels"]}
    b12 = complex(levels[12]["b"], levels[12]["imag"])
    assert data["verdict"]["eigenvalues"][0] == pytest.approx([b12.real, 0.0], rel=1e-9)
    lin = linearised(Model(5.0, 10.0).solve_at(12, 0.65, lam=1.0, check_validity=False))
    sv = np.linalg.svd(lin.matrix(b12), compute_uv=False)
    assert sv[-1] < 1e-15 * sv[0] and sv[-2] > 1e-9 * sv[0]
    b = np.array([levels[n]["b"] for n in sorted(levels)])
    change = np.abs(b[:-1] - b[-1]) / b[-1]
    assert change[1] > 1e-2 and change[-1] < 2e-4 and change[-2] < 2e-3
    assert all(r["imag"] == 0.0 and r["smallest_singular_value"] < 1e-17 for r in levels.values())


def test_the_api_states_the_solvers_defaults():
    """``stability``'s defaults, shown in its signature, are the solver's constants (the
    modulus bound's, None, is the single patch's MODULUS_BOUND or a contact set's, S24:
    tests/test_stability_zones.py)."""
    import inspect

    import thermocontact as tc
    from thermocontact.solvers import stability as st

    params = inspect.signature(tc.stability).parameters
    assert params["b_min"].default == st.B_MIN
    assert params["modulus_bound"].default is None
    assert params["n"].default == st.STABILITY_N


def test_the_dundurs_term_reduces_to_none(growing_pair):
    """The Dundurs term (derivation S15): at beta f = +-1e-10 the pair past the fold is
    the one without it to 1e-10 (3.3e-11 measured; 3.3e-7 at 1e-6: continuous in the
    term), the edge exponents and the representation's weight changed with it."""
    _, _, res = growing_pair
    root = res.eigenvalues[0]
    for B in (1e-10, -1e-10):
        lin = linearised(Model(1.5, 1.0, beta_f=B).solve_at(12, 1.5, lam=1.0,
                                                            check_validity=False))
        assert lin.representation.alpha != 0.5
        b, step = newton(lin.matrix, root, floor=1e-4)
        assert step < 1e-9 and abs(b - root) < 1e-10 * abs(root)


def test_an_interface_conductance_removes_the_fast_edge_mode():
    """The edge mode of path (a) at fHPe = 0.65 (tests/data/edge_mode.json: 2.0e4 at
    n = 12 with perfect contact) lives where the perfect contact makes the flux singular
    (derivation S11, S16): a weak resistance moves it (Bi = 1e3: 2.08e4), a Biot number of
    10 (a bounded flux at the edges) leaves no eigenvalue with Re b >= 1e-3 and
    |b| <= 1e6."""
    import thermocontact as tc

    weak = tc.stability(tc.solve(5, 0.65, 10, lam=1, conductance=(1e3, 0.0)))
    assert weak.unstable_modes == 1 and weak.stable is False
    assert weak.eigenvalues[0].imag == 0.0
    assert weak.eigenvalues[0].real == pytest.approx(2.0773e4, rel=1e-4)
    resisting = tc.stability(tc.solve(5, 0.65, 10, lam=1, conductance=(10.0, 0.0)))
    assert resisting.stable is True and resisting.unstable_modes == 0
