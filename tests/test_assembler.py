"""One assembler for the single patch and contact sets (derivation section 16)."""

import numpy as np
import pytest

from conftest import assert_ulps
from thermocontact.discretisation.operator import heat_operators, temperature_operators
from thermocontact.discretisation.representations import EdgeGraded
from thermocontact.problem.parameters import Parameters
from thermocontact.problem.validation import InputError
from thermocontact.solvers.single_patch import Model
from thermocontact.solvers.zones import ZoneModel

STENCIL = np.array([1.0, -8.0, 8.0, -1.0])  # fourth-order central difference, times 1/(12 h)


@pytest.mark.parametrize("speed_ratio, beta_f", [(0.5, 0.0), (-0.7, 0.0), (0.0, 0.4),
                                                 (0.3, -0.5)])
def test_one_zone_is_the_single_patch_with_moving_half_plane_and_dundurs(speed_ratio, beta_f):
    """One zone with R != 0 and B != 0 is the single patch at Pe = Pe_l Delta, fHPe =
    fHPe_l Delta: P_H/P = Delta^2 and sigma/Delta to 1e-10 (measured 7e-16)."""
    sol = ZoneModel(10.0, n=16, speed_ratio=speed_ratio, beta_f=beta_f).solve(
        [[-0.9, 0.8]], 5.0, 0.2, 0.3)
    L, sigma = sol.single_patch()
    D = sol.half_widths[0]
    core = Model(5.0 * D, 10.0, speed_ratio=speed_ratio, beta_f=beta_f, n=16).solve_at(
        16, 0.2 * D, lam=0.3)
    assert L == pytest.approx(core.load_ratio, abs=1e-10)
    assert sigma == pytest.approx(core.sigma_over_delta, abs=1e-10)
    assert sol.valid == core.valid
    assert sol.to_dict().get("speed_ratio", 0.0) == speed_ratio


@pytest.mark.parametrize("speed_ratio", [0.0, 0.6, -0.4])
def test_temperature_rows_differentiate_to_the_heat_equation(speed_ratio):
    """d/ds of (D33)'s temperature rows (with the moving half-plane, D33b) is
    -(pi (1 + rho)/2) times the heat operator of (D18)/(D18b)."""
    par = Parameters(3.0, 0.3, 10.0, 4.0, 0.5, speed_ratio)
    rep = EdgeGraded(20)
    rng = np.random.default_rng(6)
    phi, psi = rng.standard_normal(20), rng.standard_normal(20)
    h = 1e-4
    for s0 in (-0.55, 0.3):
        Up, Uq = temperature_operators(par, rep, s0 + h * np.array([-2, -1, 1, 2]))
        deriv = (STENCIL / (12 * h)) @ (Up @ phi + Uq @ psi)
        Hp, Hq = heat_operators(par, rep, np.array([s0]))
        ref = -0.5 * np.pi * (1.0 + par.K2_over_K1) * (Hp @ phi + Hq @ psi)[0]
        assert deriv == pytest.approx(ref, rel=1e-8)


def test_single_patch_with_a_large_conductance_is_perfect_contact():
    """Bi0 -> infinity: the temperature equation (D33) reaches the heat equation
    (D18), the difference in P_H/P falling as 1/Bi0 (to 2e-13 at Bi0 = 1e12)."""
    perfect = Model(5.0, 10.0, n=32).solve_at(32, 0.2, lam=-1)
    changes = []
    for bi in (1e6, 1e9, 1e12):
        sol = Model(5.0, 10.0, n=32, conductance=(bi, 0.0)).solve_at(32, 0.2, lam=-1)
        changes.append(abs(sol.load_ratio - perfect.load_ratio))
    assert changes[-1] < 1e-11
    assert abs(sol.sigma_over_delta - perfect.sigma_over_delta) < 1e-11
    assert changes[1] < 1e-2 * changes[0]


@pytest.mark.parametrize("biot0, m, method", [(3.0, 0.0, "graded"),
                                              (3.0, 1.0, "graded-collocation"),
                                              (0.5, 0.95, "graded-collocation")])
def test_single_patch_conductance_is_one_zone_with_converted_biot(biot0, m, method):
    """The single patch with Bi0 = h0 Delta/K2 (p_ref = P/(2 Delta)) is one zone with
    Bi0_l = Bi0 (P_H/P)^((m - 1)/2) at Pe_l = Pe/Delta (section 16), to 1e-10.  (With
    m != 0 the projected rows weight their points by Bi/(1 + Bi), which depends on
    the length unit: there the two agree to the discretisation error, section 16.)"""
    pe, F, lam = 5.0, 0.3, 0.5
    core = Model(pe, 10.0, n=16, conductance=(biot0, m), method=method).solve_at(
        16, F, lam=lam)
    L = core.load_ratio
    D = np.sqrt(L)
    zone = ZoneModel(10.0, n=16, conductance=(biot0 * L ** ((m - 1) / 2), m),
                     method=method).solve([[-1.0, 1.0]], pe / D, F / D, lam)
    Lz, sigma = zone.single_patch()
    assert Lz == pytest.approx(L, abs=1e-10)
    assert sigma == pytest.approx(core.sigma_over_delta, abs=1e-10)
    # The conductance moves the answer: it is not perfect contact.
    perfect = Model(pe, 10.0, n=16).solve_at(16, F, lam=lam)
    assert abs(perfect.load_ratio - L) > 1e-3


def test_conductance_through_solve_and_the_command_line(capsys):
    import json

    from thermocontact import solve
    from thermocontact.cli import main
    sol = solve(5.0, 0.3, 10.0, lam=0.5, n=16, conductance=(3.0, 0.0))
    ref = Model(5.0, 10.0, n=16, conductance=(3.0, 0.0)).solve_at(16, 0.3, lam=0.5)
    assert sol.load_ratio == ref.load_ratio
    assert sol.error_estimate is not None and sol.error_estimate > 0.0
    assert main(["solve", "--pe", "5", "--fhpe", "0.3", "--K2-over-K1", "10", "--lam", "0.5",
                 "-n", "16", "--conductance", "3:0", "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    assert out["load_ratio"] == ref.load_ratio
    assert (out["conductance_biot0"], out["conductance_exponent"]) == (3.0, 0.0)
    assert sol.to_dataset().attrs["conductance_biot0"] == 3.0
    assert main(["solve", "--pe", "5", "--fhpe", "0.3", "--K2-over-K1", "10", "--lam", "0.5",
                 "--conductance", "0:0"]) != 0
    assert "conductance h0" in capsys.readouterr().err


@pytest.mark.parametrize("speed_ratio, beta_f", [(0.0, 0.0), (0.4, 0.3)])
def test_sigma_closure_of_one_zone_is_the_single_patch(speed_ratio, beta_f):
    """One zone with its offset given: centre/Delta is sigma, and Delta^2 and lam are
    the single patch's at Pe = Pe_l Delta with sigma given (to 1e-10)."""
    zone = ZoneModel(10.0, n=16, speed_ratio=speed_ratio, beta_f=beta_f).solve(
        [[-1.0, 1.0]], 5.0, 0.2, sigma_over_delta=-0.05)
    L, sigma = zone.single_patch()
    assert sigma == pytest.approx(-0.05, abs=1e-13)
    D = zone.half_widths[0]
    core = Model(5.0 * D, 10.0, n=16, speed_ratio=speed_ratio, beta_f=beta_f).solve_at(
        16, 0.2 * D, sigma_over_delta=-0.05)
    assert L == pytest.approx(core.load_ratio, abs=1e-10)
    assert zone.lam == pytest.approx(core.lam, abs=1e-10)


def test_sigma_closure_refused_for_several_zones():
    model = ZoneModel(10.0, n=8)
    with pytest.raises(InputError, match="single zone"):
        model.solve([[-2.6, -1.4], [1.3, 2.7]], 1.0, 0.1, sigma_over_delta=0.0)
    with pytest.raises(InputError, match="exactly one"):
        model.solve([[-1.0, 1.0]], 1.0, 0.1, 0.5, sigma_over_delta=0.0)


def test_zone_error_estimate_is_measured_and_shrinks_with_n():
    """The estimate of refine over n/4, n/2, n: None unless asked for or without a
    coarser level, positive and falling as n doubles."""
    model = ZoneModel(10.0, n=16)
    assert model.solve([[-1.0, 1.0]], 5.0, 0.3, 0.5).error_estimate is None
    assert ZoneModel(10.0, n=4).solve([[-1.0, 1.0]], 5.0, 0.3, 0.5,
                                      estimate=True).error_estimate is None
    sols = [ZoneModel(10.0, n=n).solve([[-1.0, 1.0]], 5.0, 0.3, 0.5, estimate=True)
            for n in (8, 16)]
    est = [sol.error_estimate for sol in sols]
    assert est[0] > 100 * est[1] > 0.0
    assert sols[1].to_dict()["error_estimate"] == est[1]
    # It bounds the error: against n = 32 in Delta^2 and centre/Delta.
    fine = ZoneModel(10.0, n=32).solve(sols[1].edges, 5.0, 0.3, 0.5)
    change = np.subtract(fine.single_patch(), sols[1].single_patch())
    assert np.max(np.abs(change)) < est[1]


@pytest.mark.parametrize("method", ["graded", "galerkin"])
def test_projection_assembled_in_blocks_of_points_is_the_whole(method, monkeypatch):
    """The projected blocks formed a few points at a time (as at large n) equal those
    formed from all 2n points at once, to rounding."""
    from thermocontact.discretisation import system
    from thermocontact.discretisation.methods import METHODS
    from thermocontact.numerics.moment_engine import geometry_cache

    par = Parameters(5.0, 0.0, 10.0, 4.0, 0.7, 0.2)
    whole = METHODS[method].assemble(par, 24)
    held = geometry_cache(24).bytes
    monkeypatch.setattr(system, "ASSEMBLY_ENTRIES", 7 * 24)  # blocks of 7 points
    parts = METHODS[method].assemble(par, 24)
    for name in ("C", "Tp", "Tq", "Hp", "Hq", "const_column", "linear_column"):
        a, b = getattr(whole, name), getattr(parts, name)
        assert a.shape == b.shape
        assert np.max(np.abs(a - b)) <= 1e-14 * np.max(np.abs(a)), name
    assert geometry_cache(24).bytes <= held  # the blocks' point geometry is not kept


def test_the_single_patch_system_shares_its_cached_blocks(monkeypatch):
    """Built from cached blocks at large n, the single patch's system holds them by
    reference, not a copy in A0 and A1, and its matrix at F is the copied assembly's to
    a few ulps (the same sums: conftest.assert_ulps; the threshold lowered to a small n
    here)."""
    from thermocontact.discretisation import system as assembler
    from thermocontact.discretisation.methods import METHODS
    from thermocontact.discretisation.system import contact_set_system

    monkeypatch.setattr(assembler, "SHARED_BLOCKS_N", 32)

    par = Parameters(5.0, 0.2, 10.0)
    blocks = METHODS["graded"].assemble(par, 32)
    rep, edges = blocks.representation, np.array([[-1.0, 1.0]])
    for closure in ({"lam": -1.0}, {"sigma_over_delta": 0.3}):
        shared = contact_set_system(par, edges, rep, "projection", blocks=blocks, **closure)
        copied = contact_set_system(par, edges, rep, "projection", **closure)
        assert shared.A1 is None and copied.A1 is not None
        held = [M for _, _, M, _ in shared.shared]
        assert all(any(M is B for B in (blocks.C, blocks.Tp, blocks.Tq, blocks.Hp, blocks.Hq))
                   for M in held) and len(held) == 5
        for F in (0.0, 0.2, 3.7):
            assert_ulps(shared.matrix(F), copied.matrix(F))
        assert_ulps(shared.b, copied.b)


def test_one_matrix_at_F_and_its_factors_in_place():
    """The system's matrix at F is A0 + F A1 (bitwise: one multiplication and one
    addition, correctly rounded on every CPU), in LAPACK's order; the solve that
    overwrites it by its factors gives the solution of an untouched copy (to the
    rounding of LAPACK's kernels, amplified by the condition: _same_solution)."""
    from scipy.linalg import lu_factor, lu_solve

    from thermocontact.discretisation.system import contact_set_system
    from thermocontact.numerics.dense import factorise, solve_equilibrated

    rep = EdgeGraded(16)
    par = Parameters(5.0, 0.2, 10.0)
    system = contact_set_system(par, np.array([[-1.0, 1.0]]), rep, "projection", lam=-1.0)
    A = system.matrix(0.2)
    A0, A1 = system.parts()
    assert np.array_equal(A, A0 + 0.2 * A1) and A.flags.f_contiguous
    # Rows equilibrated, then factorised in a copy: the same factors, the same solution.
    scale = 1.0 / np.abs(A).max(axis=1)
    expected = lu_solve(lu_factor(A * scale[:, None]), system.b * scale)
    x, rcond = solve_equilibrated(A.copy(order="F"), system.b.copy())
    assert 0 < rcond < 1
    _same_solution(x, expected, rcond)
    # The 1-norm of factorise, formed a block of columns at a time, is numpy's.
    rng = np.random.default_rng(3)
    M = rng.standard_normal((600, 600))
    _, r1 = factorise(M.copy())
    from scipy.linalg.lapack import dgecon

    r2, _ = dgecon(lu_factor(M)[0], np.linalg.norm(M, 1), norm="1")
    assert r1 == pytest.approx(r2, rel=1e-12)


@pytest.mark.parametrize("closure", [{"lam": -1.0}, {"sigma_over_delta": 0.1}])
def test_a_stack_of_systems_is_each_system_solved_alone(closure, monkeypatch):
    """solve_stack (a grid line's systems at many F, formed, equilibrated and solved as
    one stack) gives each F the solution of the plain path (the matrix at F, rows
    equilibrated, LU: _same_solution), and its condition number; an F that makes the
    matrix non-finite is refused at that F only."""
    from thermocontact.discretisation.system import contact_set_system
    from thermocontact.problem.parameters import SolveError
    from thermocontact.numerics.dense import solve_equilibrated, solve_stack

    rep = EdgeGraded(16)
    par = Parameters(5.0, 0.2, 10.0)
    system = contact_set_system(par, np.array([[-1.0, 1.0]]), rep, "projection", **closure)
    F = np.array([0.0, 0.2, 0.55, 3.7, np.inf])
    found = solve_stack(system, F, "the linear system")
    # Formed a few matrices at a time: 40 F in chunks of 3 give what one chunk gives.
    many = np.concatenate([np.linspace(0.0, 0.8, 39), [np.inf]])
    monkeypatch.setattr("thermocontact.numerics.dense.STACK_ENTRIES", 3 * system.A0.size)
    chunked = solve_stack(system, many, "the linear system")
    monkeypatch.undo()
    for a, b in zip(solve_stack(system, many, "the linear system"), chunked):
        if isinstance(a, Exception):
            assert str(a) == str(b)
        else:
            _same_solution(a[0], b[0], b[1])
            assert a[1] == pytest.approx(b[1], rel=1e-12)
    one = solve_stack(system, 0.55, "the linear system")  # a number is a stack of one
    assert len(one) == 1
    _same_solution(one[0][0], found[2][0], found[2][1])
    for f, res in zip(F[:-1], found):
        try:
            x, rcond = solve_equilibrated(system.matrix(f), system.b.copy())
        except SolveError as exc:
            # The offset imposed without heat (F = 0): singular either way.
            assert "sigma_over_delta" in closure and f == 0.0
            assert isinstance(res, SolveError) and str(res) == str(exc)
            continue
        _same_solution(res[0], x, rcond)
        assert res[1] == pytest.approx(rcond, rel=1e-12)
    assert isinstance(found[-1], SolveError) and "infs or NaNs" in str(found[-1])
    # A right side that overflows once its row is equilibrated: refused at that F only.
    from types import SimpleNamespace

    tiny = SimpleNamespace(A0=np.diag([1e-10, 1.0]), A1=np.eye(2), b=np.array([1e300, 1.0]))
    bad, good = solve_stack(tiny, [0.0, 1.0], "the linear system")
    assert isinstance(bad, SolveError) and "non-finite" in str(bad)
    assert np.allclose(good[0], np.linalg.solve(np.diag([1.0 + 1e-10, 2.0]), tiny.b))


def test_refining_cases_each_on_its_own_is_refining_each_alone():
    """refine_each (cases at one n solved together, each stopping at its own n) gives
    every case the levels and estimate that refine gives it alone; a case that fails at
    a level is that case's exception."""
    from types import SimpleNamespace

    from thermocontact.solvers.refinement import refine, refine_each

    # Case k converges like 2^-p_k n^-p_k toward 1 + k; case 3 fails at n = 16.
    orders = [1.0, 2.0, 4.0, 3.0]

    def value(k, n):
        return SimpleNamespace(load_ratio=1.0 + k + (2.0 / n) ** orders[k],
                               sigma_over_delta=0.1 * k, n=n)
    calls = []

    def solve(m, cases):
        calls.append((m, list(cases)))
        return [ValueError("no solution") if (k == 3 and m == 16) else value(k, m)
                for k in cases]
    got = refine_each(solve, [4, 8], 4, tol=1e-4, n_max=1024)
    for k in range(3):
        levels, est = refine(lambda m, k=k: (value(k, m),), [4, 8], tol=1e-4, n_max=1024)
        assert [lv.n for lv in got[k][0]] == [lv[0].n for lv in levels]
        assert got[k][1] == est
    assert isinstance(got[3], ValueError)
    # Each level solved once, for the cases still going.
    assert [m for m, _ in calls] == sorted({m for m, _ in calls})
    assert calls[0] == (4, [0, 1, 2, 3])


@pytest.mark.parametrize("n", [32, 128])
def test_a_stack_solves_as_the_plain_path_on_the_blas_threads(n):
    """Small systems are solved by gesv (getrf then getrs in one call), larger ones by
    getrf and getrs apart, so that getrf may use the BLAS threads the Python API leaves
    it: at n = 32 (66 unknowns) and n = 128 (258), with BLAS on its own threads, the
    stack gives each F the plain path's solution (_same_solution)."""
    from thermocontact.discretisation.system import contact_set_system
    from thermocontact.numerics.dense import GESV_ENTRIES, solve_equilibrated, solve_stack

    system = contact_set_system(Parameters(5.0, 0.2, 10.0), np.array([[-1.0, 1.0]]),
                                EdgeGraded(n), "projection", lam=-1.0)
    assert (system.A0.size < GESV_ENTRIES) == (n == 32)
    F = np.array([0.1, 0.4])
    for f, (x, rcond) in zip(F, solve_stack(system, F, "the linear system")):
        expected, r = solve_equilibrated(system.matrix(f), system.b.copy())
        _same_solution(x, expected, r)
        assert rcond == pytest.approx(r, rel=1e-12)


def _same_solution(x, y, rcond, ulps=8):
    """Two solutions of one system by the same LU on two paths (a stack and each matrix,
    a copy and the original): LAPACK's blocked kernels round by the CPU and the memory's
    alignment, a few ulps of the matrix, which the solve amplifies by at most the
    condition number 1/rcond."""
    x, y = np.asarray(x), np.asarray(y)
    assert x.shape == y.shape
    bound = ulps * np.finfo(float).eps / rcond * np.abs(y).max()
    assert np.abs(x - y).max() <= bound, (np.abs(x - y).max(), bound)


def _true_rcond(A):
    """The reciprocal 1-norm condition number of ``A`` with its rows equilibrated, from
    its inverse."""
    A = A / np.abs(A).max(axis=1)[:, None]
    return 1.0 / (np.linalg.norm(A, 1) * np.linalg.norm(np.linalg.inv(A), 1))


def _same_stacks(a, b):
    """Two solve_stack results: the same solutions (_same_solution), the same refusals."""
    for p, q in zip(a, b, strict=True):
        if isinstance(p, Exception):
            assert isinstance(q, Exception) and str(p) == str(q)
        else:
            _same_solution(p[0], q[0], q[1])


@pytest.mark.parametrize("pe", [0.5, 42.0])
def test_a_line_s_condition_is_proven_from_a_few_anchors(pe, monkeypatch):
    """The benchmark map's lines (K2/K1 = 10, lam = 1, fHPe 0-0.8) at n = 8, 16, 32:
    with rcond="bound" the condition of every matrix is proven from its anchors
    (derivation (D6b.2)) without LAPACK's estimate; the bound never exceeds the true
    reciprocal condition number, is within a factor 20 of it, and the solutions are
    those of the estimate's path (_same_solution)."""
    from thermocontact.discretisation.system import contact_set_system
    from thermocontact.numerics import dense

    F = np.linspace(0.0, 0.8, 200)
    for n in (8, 16, 32):
        system = contact_set_system(Parameters(pe, 0.2, 10.0), np.array([[-1.0, 1.0]]),
                                    EdgeGraded(n), "projection", lam=1.0)
        estimated = dense.solve_stack(system, F)
        calls = []
        monkeypatch.setattr(dense, "dgecon", lambda *a, **k: calls.append(a))
        bounded = dense.solve_stack(system, F, rcond="bound")
        monkeypatch.undo()
        assert calls == []
        _same_stacks(bounded, estimated)
        anchors = dense.condition_bounds(system.A0, system.A1, F)
        assert anchors.F0.size <= 3
        for f, (_, bound) in zip(F, bounded):
            true = _true_rcond(system.A0 + f * system.A1)
            assert true / 20 <= bound <= true * (1 + 1e-9)


def test_a_stack_through_a_singular_matrix_is_refused_as_without_the_bound():
    """A(F) = M (I - F e1 e1^T) is singular at F = 1: the matrices near it are left to
    LAPACK's estimate and refused as without the bound (non-finite F too); every bound
    given is at most the true reciprocal condition number."""
    from types import SimpleNamespace

    from thermocontact.problem.parameters import SolveError
    from thermocontact.numerics.dense import CERTIFIED_RCOND, solve_stack

    rng = np.random.default_rng(1)
    M = rng.standard_normal((6, 6)) + 6 * np.eye(6)
    E = np.zeros((6, 6))
    E[0, 0] = 1.0
    system = SimpleNamespace(A0=M, A1=-M @ E, b=rng.standard_normal(6))
    F = np.concatenate([np.linspace(0.0, 2.0, 81), 1 + np.array([-1e-11, -1e-13, 1e-13, 1e-11]),
                        [np.nan, np.inf]])
    bounded = solve_stack(system, F, rcond="bound")
    estimated = solve_stack(system, F)
    _same_stacks(bounded, estimated)
    refused = [f for f, res in zip(F, bounded) if isinstance(res, SolveError)]
    assert 1.0 in refused and 1 - 1e-13 in refused and 1 + 1e-13 in refused
    assert 1 - 1e-11 not in refused
    # The anchor at F = 1 itself is singular: the sides get theirs.
    proven = [(f, p[1]) for f, p, q in zip(F, bounded, estimated)
              if not isinstance(p, SolveError) and p[1] != q[1]]
    assert len(proven) >= 60 and all(b >= CERTIFIED_RCOND for _, b in proven)
    for f, bound in proven:
        assert bound <= _true_rcond(system.A0 + f * system.A1) * (1 + 1e-9)


def test_condition_bounds_never_exceed_the_true_condition():
    """(D6b.2)-(D6b.3) on 600 random pencils A0 + F A1 (2-9 unknowns, F in [-2, 2], the
    rows of A0 and of A1 scaled apart by up to 1e3 either way, so that the row scales
    d(F) move along F and their ratio to the anchor's matters; every fourth pencil nearly
    singular at F = 0): every bound given is at most the true reciprocal condition
    number, and many are given, where the row scales have moved by more than 2."""
    from thermocontact.numerics.dense import condition_bounds

    rng = np.random.default_rng(2)
    given = moved = 0
    for trial in range(600):
        k = int(rng.integers(2, 10))
        A0 = rng.standard_normal((k, k)) * 10.0 ** rng.uniform(-3, 3, (k, 1))
        A1 = rng.standard_normal((k, k)) * 10.0 ** rng.uniform(-3, 3, (k, 1))
        if trial % 4 == 0:
            A0[-1] = rng.standard_normal(k - 1) @ A0[:-1] * (1 + 1e-9)
        F = np.sort(rng.uniform(-2, 2, 64))
        anchors = condition_bounds(A0, A1, F)
        A = A1[None] * F[:, None, None] + A0[None]
        scale = 1.0 / np.abs(A).max(axis=2)
        Ae = scale[:, :, None] * A
        norms = np.abs(Ae).sum(axis=1).max(axis=1)
        bounds = anchors.rcond_bounds(F, scale, norms)
        ok = np.flatnonzero(np.isfinite(bounds) & (bounds > 0))
        for j in ok:
            true = 1.0 / (norms[j] * np.abs(np.linalg.inv(Ae[j])).sum(axis=0).max())
            assert bounds[j] <= true * (1 + 1e-9), (trial, j)
        given += ok.size
        ratio = anchors.d0[anchors.which[ok]] / scale[ok]
        moved += np.sum(np.maximum(ratio.max(axis=1), 1 / ratio.min(axis=1)) > 2)
    assert given > 5000 and moved > 500


def test_a_matrix_singular_as_formed_is_not_proven():
    """Entries of 1e9 that cancel to 1 in every row: at F1 the matrix as formed in
    floating point is exactly singular, though the exact pencil is not.  The rounding of
    its forming (D6b.3) keeps it from being proven, and it is refused as without the
    bound."""
    from types import SimpleNamespace

    from thermocontact.problem.parameters import SolveError
    from thermocontact.numerics.dense import (CERTIFIED_RCOND, condition_bounds,
                                                    solve_stack)

    p, q, pp, qq = 812547733.3023335, 948606900.4847877, 812547734.3023335, 948606902.4847877
    F1 = 0.44504143799811835
    A1 = np.array([[p, q], [pp, qq]])
    A0 = np.array([[1 - F1 * p, 0.5 - F1 * q], [1 - F1 * pp, 0.5 - F1 * qq]])
    F = F1 + 1e-9 * np.linspace(-1, 1, 16)
    F[8] = F1
    assert (A1 * F1 + A0).tolist() == [[1.0, 0.5], [1.0, 0.5]]
    system = SimpleNamespace(A0=A0, A1=A1, b=np.array([1.0, 2.0]))
    bounded, estimated = solve_stack(system, F, rcond="bound"), solve_stack(system, F)
    _same_stacks(bounded, estimated)
    assert isinstance(bounded[8], SolveError) and "0.0e+00" in str(bounded[8])
    A = A0[None] + F[:, None, None] * A1[None]
    scale = 1.0 / np.abs(A).max(axis=2)
    norms = np.abs(scale[:, :, None] * A).sum(axis=1).max(axis=1)
    assert not np.any(condition_bounds(A0, A1, F).rcond_bounds(F, scale, norms)
                      >= CERTIFIED_RCOND)


def test_an_exact_zero_pivot_is_refused_whatever_the_bound(monkeypatch):
    """The LU's report of an exact zero pivot is refused by LAPACK's estimate (0), as
    without the bound, even if a bound claimed otherwise."""
    from types import SimpleNamespace

    from thermocontact.problem.parameters import SolveError
    from thermocontact.numerics.dense import ConditionBounds, solve_stack

    system = SimpleNamespace(A0=np.eye(3), A1=-np.diag([1.0, 0.0, 0.0]), b=np.ones(3))
    F = np.linspace(0.0, 2.0, 41)  # through F = 1, where A(F) has a zero row
    monkeypatch.setattr(ConditionBounds, "rcond_bounds",
                        lambda self, F, scale, norms: np.ones(F.size))
    bounded = solve_stack(system, F, rcond="bound")
    _same_stacks(bounded, solve_stack(system, F))
    assert isinstance(bounded[20], SolveError) and "0.0e+00" in str(bounded[20])


def test_the_bound_raises_no_warning_the_estimate_does_not():
    """Under warnings as errors, the bound's path runs where the estimate's does: a row
    of 1e-300 beside one of 1e10 in A1, and F at the ends of the floats, where spans
    and reaches overflow."""
    import warnings
    from types import SimpleNamespace

    from thermocontact.numerics.dense import solve_stack

    rng = np.random.default_rng(0)
    A0 = rng.standard_normal((4, 4)) + 4 * np.eye(4)
    A1 = rng.standard_normal((4, 4))
    A0[0] *= 1e-300
    A1[0] = 1e10 * rng.standard_normal(4)
    tiny = SimpleNamespace(A0=A0, A1=A1, b=np.ones(4))
    wide = SimpleNamespace(A0=np.eye(3) + 0.1, A1=np.eye(3), b=np.ones(3))
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        for system, F in ((tiny, np.linspace(-1.0, 1.0, 16)),
                          (wide, np.concatenate([np.full(8, -1.7e308), np.full(8, 1.7e308),
                                                 [0.0]]))):
            _same_stacks(solve_stack(system, F, rcond="bound"), solve_stack(system, F))


def test_the_rows_of_kernels_of_the_points_alone_are_kept(monkeypatch):
    """EdgeGraded's Cauchy and sign rows depend on the points alone: a second assembly
    at another Pe (a map's next line) takes them from the row cache, the same to the
    last bit as formed afresh and read-only; from KEPT_MOMENTS_N they are formed each
    time (no pairs of megabytes kept beside a large solve)."""
    from thermocontact.discretisation import representations
    from thermocontact.numerics import moment_engine
    from thermocontact.numerics.cache import clear_caches

    clear_caches()
    Model(0.7, 10.0).blocks(16)
    calls = []
    moments = moment_engine.moments
    monkeypatch.setattr(moment_engine, "moments",
                        lambda kernel, *a, **k: calls.append(k) or moments(kernel, *a, **k))
    Model(2.3, 10.0).blocks(16)
    assert calls and all(k.get("scale") != 1.0 for k in calls)  # only the Pe kernels
    rep = EdgeGraded(16)
    (s, tau), _ = rep.collocation_points()
    kept = rep.cauchy(s, tau), rep.sign(s, tau)
    clear_caches()
    fresh = rep.cauchy(s, tau), rep.sign(s, tau)
    for a, b in zip(kept, fresh):
        for x, y in zip(a, b):
            assert np.array_equal(x, y) and not x.flags.writeable
    monkeypatch.setattr(representations, "KEPT_MOMENTS_N", 16)
    assert rep.cauchy(s, tau)[0].flags.writeable
