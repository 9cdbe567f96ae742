"""The discrete system shared by every discretisation method.

Unknowns (derivation section 6): the pressure's bounded factor ``phi`` and the
heat-flux difference's factor ``psi`` at the nodes of a representation
(:mod:`.representations`).  The blocks are

* the contact equation (D14), collocated at ``n + 1`` points ``s_k`` or
  projected on ``n + 1`` functions::

      (C - F Tp) phi - F Tq psi = (2/pi) (L sigma e_0 + L e_1)

  where ``e_0``, ``e_1`` are ``1`` and ``s_k`` (collocation) or their projections;

* the heat equation (D18) at ``n - 1`` points or projections::

      Hp phi + Hq psi = 0

with the load and heat-partition rows ``w_p . phi = 1`` and
``w_q . psi = lam - eta``.  Nothing in the blocks depends on ``F = fHPe``,
``lam`` or ``sigma``, so one assembly serves a whole sweep over them.  The blocks
are plain arrays and a representation (pickled as its class and ``n``), so an
assembly can be sent to another process.

:func:`contact_set_system` places the blocks of every zone of a contact set, and
their terms at each other's points, in one linear system with its closure (the heat
partition or the offset) and, optionally, an interface conductance (derivation
sections 14-16).  The single patch is its one zone in its own scaling: the zone
``(-1, 1)`` with no initial gap, whose two defects are ``L sigma/Delta`` and ``L``.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from dataclasses import replace

from ..numerics.moment_engine import BASES, geometry_cache
from ..problem.closure import Temperatures
from ..problem.parameters import Parameters
from ..problem.validation import InputError, check_sink_given
from .operator import contact_operators, heat_operators, outside_operators, temperature_operators
from .representations import (Representation, projection_columns, projection_nodes,
                              range_projections)

__all__ = ["Blocks", "ContactSetSystem", "assemble",
           "contact_set_system", "equation_points", "temperature_points", "zone_parameters"]

@dataclass(frozen=True, eq=False)
class Blocks:
    """Assembled, ``F``-independent blocks of the discrete equations.

    Attributes
    ----------
    representation : Representation
        How ``phi`` and ``psi`` are carried, evaluated and integrated.
    C, Tp : ndarray, shape (n + 1, n)
        Cauchy and thermal-distortion operators of (D14) on ``phi``.
    Tq : ndarray, shape (n + 1, n)
        Thermal-distortion operator of (D14) on ``psi``.
    Hp, Hq : ndarray, shape (n - 1, n)
        Operators of (D18) on ``phi`` and ``psi``.
    const_column, linear_column : ndarray, shape (n + 1,)
        The right side's ``e_0`` and ``e_1``.
    """

    representation: Representation
    C: np.ndarray
    Tp: np.ndarray
    Tq: np.ndarray
    Hp: np.ndarray
    Hq: np.ndarray
    const_column: np.ndarray
    linear_column: np.ndarray

    @property
    def n(self) -> int:
        return self.representation.n

    def __repr__(self):
        return f"Blocks({self.representation!r})"


def assemble(par: Parameters, rep: Representation, scheme: str) -> Blocks:
    """Assemble the blocks by collocation or by projection on the range spaces.

    Parameters
    ----------
    par : Parameters
        ``fhpe`` is not used.
    rep : Representation
    scheme : {"collocation", "projection"}
        Collocation at the representation's points; or projection of (D14) on
        ``cos(j x)``, ``j <= n``, and of (D18) on ``sin((j + 1) x) sin x``,
        ``j < n - 1``, by the midpoint rule on ``2n`` points in the
        representation's variable ``x`` (:func:`.representations.range_projections`;
        the error is about that of collocation at ``2n``, derivation sections 10
        and 12).

    Returns
    -------
    Blocks
    """
    n = rep.n
    if scheme != "projection":
        (sc, ac, _), (sh, ah, _) = equation_points(rep, scheme)
        C, Tp, Tq = contact_operators(par, rep, sc, ac)
        Hp, Hq = heat_operators(par, rep, sh, ah)
        return Blocks(rep, C, Tp, Tq, Hp, Hq, np.ones(n + 1), sc)
    # The operators at the 2n points, each block of points projected as it is formed:
    # the five 2n x n operators are never held whole (80 MB at n = 1024).
    x = projection_nodes(n)
    s, aux = rep.projection_points(x)
    if x.size * n <= ASSEMBLY_ENTRIES:
        return _projected(par, rep, x, s, aux, x.size)
    # The moment bases of a large n (17 MB at n = 1024) are not kept beside the blocks
    # and the system's matrix: the validity checks form them again.
    with BASES.transient():
        return _projected(par, rep, x, s, aux, ASSEMBLY_BLOCK)


def _projected(par, rep, x, s, aux, step):
    n = rep.n
    total = None
    for i in range(0, x.size, step):
        rows = slice(i, i + step)
        p1, p2 = projection_columns(n, x[rows])
        a = None if aux is None else aux[rows]
        # A block's point geometry serves its kernels only; the 2n points' whole, when
        # one block, may serve another assembly at these points (a sweep).
        with geometry_cache(n).transient(when=step < x.size):
            C, Tp, Tq = contact_operators(par, rep, s[rows], a)
            Hp, Hq = heat_operators(par, rep, s[rows], a)
        pairs = ((p1, C), (p1, Tp), (p1, Tq), (p2, Hp), (p2, Hq))
        if total is None:
            total = [P @ M for P, M in pairs] + [p1.sum(axis=1), p1 @ s[rows]]
        else:
            # Each product added into its block by the BLAS itself (C = A B + C: no
            # temporary of the block's size, 8 MB at n = 1024).
            for t, (P, M) in zip(total, pairs):
                _accumulate(t, P, M)
            total[5] += p1.sum(axis=1)
            total[6] += p1 @ s[rows]
    return Blocks(rep, *total)


def _accumulate(t, P, M):
    """``t += P @ M`` in place: row-major ``t`` is column-major ``t.T``, and
    ``t.T += M.T @ P.T`` is one ``dgemm`` with ``beta = 1`` on views of the three."""
    from scipy.linalg.blas import dgemm

    out = dgemm(1.0, M.T, P.T, beta=1.0, c=t.T, overwrite_c=True)
    if not np.shares_memory(out, t):  # a copy was made (an operand not contiguous)
        t[...] = out.T


#: Points of a block times n: up to n = 256 the 2n points are one block (one point
#: geometry, which the geometry cache keeps for all the block's kernels and for another
#: assembly at these points, a sweep); a larger n takes ASSEMBLY_BLOCK points at a time
#: (arrays of about 2 MB at n = 1024, and a point geometry of 4 MB).
ASSEMBLY_ENTRIES = 2**17
ASSEMBLY_BLOCK = 64


def equation_points(rep: Representation, scheme: str):
    """Where the contact and heat equations are evaluated, and how they are reduced.

    Returns
    -------
    (s, aux, P) for the contact equation, then for the heat equation
        The points, their own coordinate in the representation (``tau``, or None)
        and the projection ``P`` applied to the rows evaluated there (None for
        collocation, whose rows are the equations themselves).
    """
    if scheme == "collocation":
        (sk, ak), (sh, ah) = rep.collocation_points()
        return (sk, ak, None), (sh, ah, None)
    if scheme == "projection":
        x, p1, p2 = range_projections(rep.n)
        s, aux = rep.projection_points(x)
        return (s, aux, p1), (s, aux, p2)
    raise ValueError(f"scheme must be 'collocation' or 'projection', got {scheme!r}")


def zone_parameters(par: Parameters, half: float) -> Parameters:
    """The single-patch parameters of a zone of half-width ``half`` (units of ``l``)."""
    if half == 1.0:
        return par
    return replace(par, pe=par.pe * half, fhpe=par.fhpe * half)


def temperature_points(rep, scheme: str):
    """Where the temperature equation (D33) is evaluated: ``n`` points and the
    reduction (the first ``n`` projections of the contact equation, or collocation at
    ``tau = pi (k - 1/2)/n``)."""
    n = rep.n
    if scheme == "projection":
        x, p1, _ = range_projections(n)
        s, aux = rep.projection_points(x)
        return s, aux, p1[:n]
    tau = np.pi * (np.arange(n, 0, -1) - 0.5) / n
    s, aux = rep.projection_points(tau)
    return s, aux, None


@dataclass(frozen=True, eq=False)
class ContactSetSystem:
    """The linear system of one contact set: ``(A0 + F A1) x = b``.

    The unknowns ``x`` are each zone's ``phi`` (``n`` each), then each zone's
    ``psi``, then the closure's unknowns (each zone's defects ``(mu, nu)`` with the
    heat partition or the far temperatures given; the one zone's ``nu`` with the
    offset given), then (with an interface conductance) the temperature difference's
    constant.  The rows are each zone's contact equation, the load, each zone's heat
    (or temperature) equation, the heat partition (``lam`` given) or the temperature
    row (the far temperatures given, row ``temperature_row`` with a conductance, D41)
    and the returns between zones.  With a
    conductance each zone's temperature rows (D33) depend on the Biot numbers at its
    points (``points``): they are formed by :meth:`matrix` from ``local``.

    ``shared``: blocks of the matrix held by reference rather than copied into ``A0``
    and ``A1`` (the single patch's cached blocks, which would otherwise be held twice):
    ``(rows, columns, M, c)`` adds ``M`` (``c`` None) or ``c F M`` where ``A0`` and
    ``A1`` are zero.  ``A1`` is None when it has no other entries.
    """

    A0: np.ndarray
    A1: np.ndarray | None
    b: np.ndarray
    zones: int
    n: int
    local: tuple = ()
    points: tuple = ()
    closure: str = "lam"
    temperature_row: int | None = None
    shared: tuple = ()

    def parts(self):
        """``A0`` and ``A1`` in full, the shared blocks included (for checks)."""
        A0 = self.A0.copy()
        A1 = np.zeros_like(A0) if self.A1 is None else self.A1.copy()
        for rows, cols, M, c in self.shared:
            if c is None:
                A0[rows, cols] += M
            else:
                A1[rows, cols] += c * M
        return A0, A1

    @property
    def closure_slice(self) -> slice:
        """The closure's unknowns in ``x``."""
        k = 1 if self.closure == "sigma" else 2 * self.zones
        return slice(2 * self.zones * self.n, 2 * self.zones * self.n + k)

    def matrix(self, F, biot=None, scale=None):
        # One new array, in LAPACK's order so that it can be factorised in place.
        if self.A1 is None:
            A = np.array(self.A0, order="F")
        else:
            A = np.multiply(self.A1, F, order="F")
            A += self.A0
        # Each entry gets one term of A0 and one of F A1 in either order: the same sum.
        for rows, cols, M, c in self.shared:
            A[rows, cols] += M if c is None else (c * F) * M
        if not self.local:
            return A
        # The constant's unknown is carried times the largest Bi/(1 + Bi), so that its
        # column stays of order one however small the conductance.
        scale = self.theta_scale(biot) if scale is None else scale
        for (rows, P, U, Lq), bi in zip(self.local, biot):
            # (D33) times Bi/(1 + Bi): the temperature terms weighted by Bi/(1 + Bi),
            # the interface's (pi/2) q by 1/(1 + Bi); either limit stays finite.
            w = 1.0 / (1.0 + bi)
            point_rows = (bi * w)[:, None] * U + (0.5 * np.pi * w)[:, None] * Lq
            point_rows[:, -1] /= scale
            A[rows] = point_rows if P is None else P @ point_rows
        if self.temperature_row is not None:
            # The temperature closure fixes the constant itself (D41), carried as above.
            A[self.temperature_row, -1] = 1.0 / scale
        return A

    @staticmethod
    def theta_scale(biot):
        return max(float(np.max(bi / (1.0 + bi))) for bi in biot)

    def conductance_jacobian(self, x, biot, dbiot, pressure_rows, scale):
        """The derivative of the temperature rows through ``Bi(p)``: ``(D33)`` times
        ``Bi/(1 + Bi)`` changes with ``Bi`` by ``(U x - (pi/2) q)/(1 + Bi)^2`` per
        point, and ``Bi`` with the pressure ``p = pressure_rows @ phi``."""
        J = np.zeros(self.A0.shape)
        n = self.n
        for i, ((rows, P, U, Lq), bi, dbi, R) in enumerate(zip(self.local, biot, dbiot,
                                                               pressure_rows)):
            ux = U[:, :-1] @ x[:-1] + U[:, -1] * x[-1] / scale
            dr = (ux - 0.5 * np.pi * (Lq @ x)) / (1.0 + bi) ** 2 * dbi
            block = dr[:, None] * R
            J[rows, i * n:(i + 1) * n] = block if P is None else P @ block
        return J


def contact_set_system(par: Parameters, edges, rep, scheme: str, *, lam=None,
                       sigma_over_delta=None, temperatures=None, profile=None,
                       conductance=False, blocks=None) -> ContactSetSystem:
    """Assemble the equations of a contact set with given edges (derivation sections
    14 and 16): the one assembler of the single patch and of contact sets.

    Rows: each zone's contact equation (``n + 1``), the load, each zone's heat
    equation (``n - 1``), the heat partition (with ``lam``), and for each gap between
    zones the gap's return (D31a) and the temperature difference's return (D31b).
    With an interface conductance (``conductance=True``, section 15) each zone's heat
    rows are instead ``n`` rows of the temperature equation (D33), whose constant is
    one more unknown, and (D31b) is not needed.  With the heat partition given, each
    zone's right side gains ``(2/pi)(mu_j + nu_j s)``; with the offset given (one
    zone only) ``(2/pi) nu (sigma + s)`` and no partition row (section 16).  With
    the far temperatures given the partition row becomes the temperature row (D41):
    the mean over ``n`` points of zone 0 of the surfaces' temperature difference
    (D33), every zone's sources summed, with each body's far temperature, or with a
    conductance its constant, equal to ``Theta`` (section 17).  Perfect thermal
    contact makes that difference one constant over every zone (the heat rows hold
    it on each zone, the returns (D31b) carry it across each gap), so zone 0's
    points stand for all.

    Parameters
    ----------
    par : Parameters
        ``pe`` and ``fhpe`` in the length unit of ``edges`` (``Pe_l`` and ``fHPe_l``
        for a contact set; ``Pe`` and ``fHPe`` for the single patch, edges (-1, 1)).
    edges : ndarray, shape (m, 2)
    rep : Representation
        An edge-graded one when ``m > 1`` (the kernels between zones are integrated
        from an edge).
    scheme : {"collocation", "projection"}
    lam, sigma_over_delta : float
        The heat partition, or (one zone) the offset ``centre/half``.
    temperatures : Temperatures
        Or the far temperatures, the sink distance in the unit of ``edges``
        (section 17).  Exactly one of the three.
    profile : numpy.polynomial.Polynomial, optional
        The initial gap in units of ``l^2/R`` against ``X``; None: none (the single
        patch in its own scaling, whose ``X^2/2`` is carried by the defects).
    conductance : bool
    blocks : Blocks, optional
        The one zone's own blocks at ``half = 1`` (a cached single-patch assembly).

    Returns
    -------
    ContactSetSystem

    Raises
    ------
    InputError
        The offset given with more than one zone; a sink distance with a moving
        half-plane, or none with a stationary one.
    """
    m, n = len(edges), rep.n
    if sum(c is not None for c in (lam, sigma_over_delta, temperatures)) != 1:
        raise InputError("give exactly one of lam, sigma_over_delta and temperatures",
                         parameters=("lam", "sigma_over_delta", "temperatures"))
    if sigma_over_delta is not None and m != 1:
        raise InputError(f"sigma_over_delta closes a single zone only (section 16), got "
                         f"{m} zones; give lam or temperatures instead",
                         parameters=("sigma_over_delta",))
    if temperatures is not None:
        temperatures = check_temperatures(par, temperatures)
    centre = 0.5 * (edges[:, 0] + edges[:, 1])
    half = 0.5 * (edges[:, 1] - edges[:, 0])
    zpar = [zone_parameters(par, h) for h in half]
    nh = n if conductance else n - 1
    closing = 1 if sigma_over_delta is not None else 2 * m

    def reduce(P, M):
        return M if P is None else P @ M

    # The single patch's cached blocks serve the one zone (-1, 1): then no point is
    # needed unless a temperature equation or a profile asks for them.
    own_cached = blocks is not None and m == 1 and half[0] == 1.0
    if own_cached and not conductance and profile is None:
        sc = sh = ah = p1 = p2 = None
        e0, e1 = blocks.const_column, blocks.linear_column
    else:
        (sc, ac, p1), (sh, ah, p2) = equation_points(rep, scheme)
        if conductance:
            sh, ah, p2 = temperature_points(rep, scheme)
        # The right side's e_0 and e_1 as the single patch forms them.
        e0 = np.ones(n + 1) if p1 is None else p1.sum(axis=1)
        e1 = reduce(p1, sc)
    size = 2 * m * n + closing + int(conductance)
    # The cached blocks of one zone at half = 1 without conductance are shared, not
    # copied, at large n: they alone fill their rows' phi and psi columns, and A1 has
    # nothing else.  Below, copies form the matrix at F faster (once per grid point).
    share = own_cached and not conductance and n >= SHARED_BLOCKS_N
    shared = []
    A0, b = np.zeros((size, size)), np.zeros(size)
    A1 = None if share else np.zeros((size, size))
    phi = [slice(j * n, (j + 1) * n) for j in range(m)]
    psi = [slice((m + j) * n, (m + j + 1) * n) for j in range(m)]
    load = m * (n + 1)
    part = load + 1 + m * nh
    local, points = [], []
    for i in range(m):
        rc = slice(i * (n + 1), (i + 1) * (n + 1))
        rh = slice(load + 1 + i * nh, load + 1 + (i + 1) * nh)
        if sc is not None:
            xc, xh = centre[i] + half[i] * sc, centre[i] + half[i] * sh
        if conductance:
            U = zone_temperature_rows(par, zpar, rep, centre, half, i, sh, ah, size)
        for j in range(m):
            own = i == j
            if own:
                own_blocks = blocks if own_cached else assemble(zpar[j], rep, scheme)
                C, Tp, Tq = own_blocks.C, own_blocks.Tp, own_blocks.Tq
            else:
                s_c = (xc - centre[j]) / half[j]
                C, Tp, Tq = (reduce(p1, M) for M in contact_operators(zpar[j], rep, s_c,
                                                                      own=False))
            if share:
                # -half * T with half = 1: (-F) T is F (-T) to the last bit.
                shared += [(rc, phi[j], C, None), (rc, phi[j], Tp, -1.0),
                           (rc, psi[j], Tq, -1.0), (rh, phi[j], own_blocks.Hp, None),
                           (rh, psi[j], own_blocks.Hq, None)]
                continue
            # Zone j's thermal terms in units of l carry its half-width (section 14).
            A0[rc, phi[j]] = C
            A1[rc, phi[j]] = -half[j] * Tp
            A1[rc, psi[j]] = -half[j] * Tq
            if conductance:
                continue
            if own:
                A0[rh, phi[j]] = own_blocks.Hp
                A0[rh, psi[j]] = own_blocks.Hq
            else:
                Hp, Hq = heat_operators(zpar[j], rep, (xh - centre[j]) / half[j])
                A0[rh, phi[j]] = reduce(p2, Hp)
                A0[rh, psi[j]] = reduce(p2, Hq)
        if conductance:
            U[:, size - 1] = -1.0
            # The interface's (pi/2) q = (pi/2)(q' + eta p) at the zone's own points.
            Lq = np.zeros_like(U)
            Lq[:, phi[i]] = par.eta * rep.pressure_rows(sh, ah)
            Lq[:, psi[i]] = rep.flux_rows(sh, ah)
            local.append((rh, p2, U, Lq))
            points.append((sh, ah))
        if profile is not None:
            b[rc] = (2.0 / np.pi) * reduce(p1, profile.deriv()(xc))
        first = 2 * m * n + (2 * i if sigma_over_delta is None else 0)
        if sigma_over_delta is None:
            A0[rc, first] = -(2.0 / np.pi) * e0
            A0[rc, first + 1] = -(2.0 / np.pi) * e1
        else:
            A0[rc, first] = -(2.0 / np.pi) * (sigma_over_delta * e0 + e1)

    wp, wq = rep.pressure_rule.weights, rep.flux_rule.weights
    b[load] = 1.0
    for j in range(m):
        A0[load, phi[j]] = half[j] * wp
        if lam is not None:
            # (D19) with the load row: sum_j Delta_j w_q . psi_j = lam - eta.
            A0[part, psi[j]] = half[j] * wq
    if lam is not None:
        b[part] = lam - par.eta
    theta_row = None
    if temperatures is not None:
        # (D41): the temperature difference's mean over zone 0's points, less the
        # sink's ln(L/l) times the heat into the half-plane, is Theta; with a
        # conductance, the constant of (D33) less that term.
        if conductance:
            theta_row = part
        else:
            st, at, _ = temperature_points(rep, "collocation")
            U = zone_temperature_rows(par, zpar, rep, centre, half, 0, st, at, size)
            A0[part] = U.mean(axis=0)
        for j in range(m):
            A0[part, phi[j]] -= temperatures.log_sink * half[j] * 0.5 * (1.0 - par.eta) * wp
            A0[part, psi[j]] += temperatures.log_sink * half[j] * 0.5 * wq
        b[part] = temperatures.theta
    for k in range(m - 1):
        lo, hi = edges[k, 1], edges[k + 1, 0]
        rg, rt = part + 1 + k, part + m + k
        for j in range(m):
            C, Tp, Tq, Hp, Hq = region_integral(zpar[j], rep, edges[j], half[j], lo, hi)
            A0[rg, phi[j]] += half[j] * C
            A1[rg, phi[j]] -= half[j] ** 2 * Tp
            A1[rg, psi[j]] -= half[j] ** 2 * Tq
            if not conductance:
                A0[rt, phi[j]] += half[j] * Hp
                A0[rt, psi[j]] += half[j] * Hq
        b[rg] = (2.0 / np.pi) * (profile(hi) - profile(lo))
    closure = ("lam" if lam is not None else "sigma" if sigma_over_delta is not None
               else "temperatures")
    return ContactSetSystem(A0, A1, b, m, n, tuple(local), tuple(points),
                            closure, theta_row, tuple(shared))


#: From this n the single patch's system shares the cached blocks (10 MB at n = 512)
#: instead of copying them into A0 and A1.
SHARED_BLOCKS_N = 512


def zone_temperature_rows(par, zpar, rep, centre, half, i, s, aux, size):
    """The temperature difference (D33) at zone ``i``'s points ``s`` (its own
    coordinate, ``aux`` its representation's), without the constant: rows of
    ``size`` columns on every zone's ``phi`` and ``psi``."""
    n, m = rep.n, len(half)
    U = np.zeros((s.size, size))
    x = centre[i] + half[i] * s
    for j in range(m):
        own = i == j
        s_j = s if own else (x - centre[j]) / half[j]
        # (D33) in units of l: zone j's integrals carry Delta_j, and a stationary
        # half-plane's logarithm ln(Delta_j) times the heat it puts into it.
        Up, Uq = temperature_operators(zpar[j], rep, s_j, aux if own else None)
        lg = 0.0 if par.half_plane_scale else np.log(half[j])
        U[:, j * n:(j + 1) * n] = half[j] * (Up + 0.5 * (1.0 - par.eta) * lg
                                             * rep.pressure_rule.weights[None, :])
        U[:, (m + j) * n:(m + j + 1) * n] = half[j] * (Uq - 0.5 * lg
                                                       * rep.flux_rule.weights[None, :])
    return U


def check_temperatures(par: Parameters, temperatures) -> Temperatures:
    """The closure if it suits the half-plane: a sink distance for a stationary one
    (its logarithm needs a length, D38), none for a moving one (its incoming
    temperature is absolute, section 17)."""
    if not isinstance(temperatures, Temperatures):
        temperatures = Temperatures(*temperatures)
    check_sink_given(temperatures.sink_distance, par.half_plane_scale == 0.0)
    return temperatures


def region_integral(zpar: Parameters, rep, edge_pair, half, lo, hi):
    """Rows of the integrals over ``lo < X < hi`` (outside the zone) of its terms.

    ``integral`` of the zone's contact-equation and heat-equation left sides over
    ``X``, per unit ``ds`` (multiply by ``half`` for ``dX``): the differences of
    :func:`~thermocontact.discretisation.operator.outside_operators` at the two
    ends, measured from the zone's edge on that side.
    """
    a, b = edge_pair
    if lo >= b:
        side, t_lo, t_hi = 1.0, (lo - b) / half, (hi - b) / half
    else:
        side, t_lo, t_hi = -1.0, (a - lo) / half, (a - hi) / half
    ops = outside_operators(zpar, rep, side, np.array([t_lo, t_hi]))
    # From lo to hi: I(t_hi) - I(t_lo) on the right; on the left the integral from
    # the edge outward runs from hi to lo, so the same difference holds with the
    # orientation of I: integral_lo^hi = I(t_hi) - I(t_lo) as well.
    return tuple(M[1] - M[0] for M in ops)
