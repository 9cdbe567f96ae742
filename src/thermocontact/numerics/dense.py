"""Certified dense linear solves: the contact systems' linear algebra, with no physics.

A system is solved with its rows equilibrated first (the heat equation's rows next to
an edge grow like n^3 in the graded representation, which would mask the condition
number), by LAPACK's LU called directly (``getrf``, ``gecon``, ``getrs``: the factors of
:func:`scipy.linalg.lu_factor` without its checks and copies), and refused
(:class:`~thermocontact.problem.errors.SolveError`) where its reciprocal condition
number is below :data:`RCOND_MIN`.  A grid line's systems ``A(F) = A0 + F A1`` are
formed and solved as one stack (:func:`solve_stack`), each as alone, their condition
proven from a few anchors where asked (:func:`condition_bounds`, derivation section 6b).
"""

from __future__ import annotations

import math
from collections import deque
from dataclasses import dataclass, replace

import numpy as np
from scipy.linalg.lapack import dgecon, dgesv, dgetrf, dgetri, dgetrs

from ..problem.errors import SolveError
from ..problem.validation import check_choice

__all__ = ["CERTIFIED_RCOND", "ConditionBounds", "GESV_ENTRIES", "RCOND_CHOICES", "RCOND_MIN",
           "STACK_ENTRIES",
           "condition_bounds", "factorise", "ill_conditioned", "log_determinants", "not_finite",
           "not_finite_solution", "row_scales", "solve_equilibrated", "solve_stack"]

#: Systems whose reciprocal 1-norm condition number is below this are refused.
RCOND_MIN = 1e-12

def row_scales(A, axis=1):
    """The reciprocals of the largest magnitudes of ``A``'s rows, reduced over ``axis``
    (1 for a matrix; 1 of a stack of transposed matrices), as ``max(max a, -min a)``:
    no copy of ``A``; a zero row gets ``1/tiny``."""
    return 1.0 / np.maximum(np.maximum(A.max(axis=axis), -A.min(axis=axis)),
                            np.finfo(float).tiny)


#: What ``rcond`` of :func:`solve_stack` (and ``Model.solve_many``) may be.
RCOND_CHOICES = ("estimate", "bound")


def log_determinants(A):
    """``(sign, log|det A|, rcond)`` of each of a stack of square complex matrices
    (shape ``(k, N, N)``; arrays of shape ``(k,)``), by LU of each with its rows and then
    its columns equilibrated (positive real scalings, which leave the phase
    ``sign = det A/|det A|`` unchanged and make the factorisation's backward error small
    in every row and column, not only in the largest), and ``rcond``, the reciprocal
    1-norm condition number of the equilibrated matrix from its inverse (exact to
    rounding where LAPACK's ``gecon`` estimates a lower bound of the inverse's norm).

    The computed ``det`` is that of ``A + E`` with ``|E| <~ N u |A|`` entrywise after
    the scaling, so its phase is off by at most about ``|tr(A^-1 E)| <= N^2 u / rcond``
    radians, times the growth factor of the pivots (derivation S12, *Large n*); an
    exactly singular matrix has ``sign`` 0, ``log|det|`` ``-inf`` and ``rcond`` 0.  The
    stack is scaled, factorised and inverted as one (NumPy's LAPACK loops: two-thirds
    of the cost of a call per matrix of ``getrf`` and ``gecon`` at the stability's sizes,
    43 matrices of 27 x 27 in 2.8 ms against 4.2 ms).
    """
    A = np.asarray(A, dtype=complex)
    mod = np.abs(A)
    r = row_scales(mod, axis=-1)
    mod *= r[:, :, None]
    c = row_scales(mod, axis=-2)
    mod *= c[:, None, :]
    B = A * (r[:, :, None] * c[:, None, :])
    anorm = mod.sum(axis=-2).max(axis=-1)
    sign, logdet = np.linalg.slogdet(B)
    logdet = logdet - np.log(r).sum(axis=-1) - np.log(c).sum(axis=-1)
    rcond = np.zeros(A.shape[0])
    regular = np.flatnonzero(sign != 0)
    try:
        inverse = np.linalg.inv(B[regular])
    except np.linalg.LinAlgError:
        # The same LU's pivots as slogdet's: not reached; rcond 0 (no phase certified)
        # should it be.
        return sign, logdet, rcond
    with np.errstate(over="ignore"):
        rcond[regular] = 1.0 / (anorm[regular] * np.abs(inverse).sum(axis=-2).max(axis=-1))
    return sign, logdet, rcond


def solve_equilibrated(A, b, what="the linear system"):
    """``x`` with ``A x = b`` and the reciprocal condition number, rows equilibrated
    first (the heat equation's rows next to an edge grow like n^3 in the graded
    representation, which would mask the condition number); ``A`` and ``b`` are
    overwritten (``A`` by its factors, in place when it is Fortran-ordered)."""
    scale = row_scales(A)
    A *= scale[:, None]
    b *= scale
    lu, rcond = factorise(A, what, overwrite=True)
    x, _ = dgetrs(*lu, b)
    return x, rcond


def factorise(A, what="the linear system", overwrite=False):
    """LU factors of ``A`` (as :func:`scipy.linalg.lu_factor` returns them) and its
    reciprocal condition number (1-norm); a singular or ill-conditioned ``A`` (below
    :data:`RCOND_MIN`) raises :class:`SolveError`.

    LAPACK's ``getrf`` and ``gecon`` are called directly: the same factors as
    ``lu_factor``'s, without its checks' cost, which a grid line pays per point.
    ``overwrite``: ``A`` may be overwritten by the factors.
    """
    A = np.asarray(A, dtype=float)
    if not np.all(np.isfinite(A)):
        raise not_finite(what)
    # The 1-norm a block of columns at a time: no copy of A (34 MB at n = 1024).
    step = max(1, 2**18 // max(1, A.shape[0]))
    norm = max((np.abs(A[:, i:i + step]).sum(axis=0).max()
                for i in range(0, A.shape[1], step)), default=0.0)
    lu, piv, info = dgetrf(A, overwrite_a=overwrite)
    if info < 0:
        raise SolveError(f"{what} could not be factorised (illegal value in argument "
                         f"{-info} of the LU factorisation)")
    rcond, info = dgecon(lu, norm, norm="1")
    if info != 0 or not np.isfinite(rcond) or rcond < RCOND_MIN:
        raise ill_conditioned(what, rcond)
    return (lu, piv), float(rcond)


def not_finite(what):
    return SolveError(f"{what} could not be factorised (array must not contain infs or NaNs)")


def not_finite_solution(what):
    return SolveError(f"{what}: the linear solve produced non-finite values")


def ill_conditioned(what, rcond):
    return SolveError(f"{what} is singular or ill-conditioned (reciprocal condition "
                      f"number {rcond:.1e} < {RCOND_MIN:.0e}); these parameters have no "
                      f"well-determined solution")


def solve_stack(system, F, what="the linear system",
                rcond="estimate") -> list:
    """:func:`solve_contact_system` of a system without conductance or shared blocks at
    each of several ``F``: per ``F``, ``(x, rcond)`` or the :class:`SolveError`.

    The matrices ``A0 + F A1`` are formed and their rows equilibrated as one stack,
    each entry by the same operations as :meth:`ContactSetSystem.matrix` and
    :func:`solve_equilibrated` apply to it alone; each is then factorised, its
    condition estimated and solved by LAPACK (``getrf``, ``gecon``, ``getrs``), as
    alone.  What is saved is the per-solve work around the linear algebra.

    ``rcond="bound"``: a matrix is not refused where :func:`condition_bounds` proves
    its reciprocal condition number at least :data:`CERTIFIED_RCOND` and its LU has no
    exact zero pivot (then LAPACK's estimate, not below the true number up to rounding,
    would not have refused it either), and its ``rcond`` is that proven lower bound;
    elsewhere it is estimated as above.  The solutions ``x`` and the systems refused are
    the same.
    """
    check_choice("rcond", rcond, RCOND_CHOICES)
    F = np.atleast_1d(np.asarray(F, dtype=float))
    out = []
    anchors = condition_bounds(system.A0, system.A1, F) if rcond == "bound" else None
    # A few matrices at a time, so that a chunk's stack stays in the cache from its
    # forming to its factorisation (the arithmetic is per matrix either way), in a
    # buffer that every chunk reuses; their |entries| for the 1-norms a block of rows
    # at a time (no second matrix of 34 MB at n = 1024).
    k = system.A0.shape[0]
    step = max(1, min(F.size, STACK_ENTRIES // system.A0.size))
    stack = np.empty((step, k, k))
    work = np.empty((step, min(k, max(1, STACK_ENTRIES // (step * k))), k))
    # The transposed matrices once, contiguous, so that every chunk reads them in order;
    # a large one (a chunk of one matrix) through its view, without a copy (34 MB each
    # at n = 1024).
    def transposed(A):
        if A is None:
            return None
        return np.ascontiguousarray(A.T) if A.size <= STACK_ENTRIES else A.T
    A0t, A1t = transposed(system.A0), transposed(system.A1)
    for i in range(0, F.size, step):
        chunk = F[i:i + step]
        out += _solve_chunk(A0t, A1t, system.b, chunk, what, stack[:chunk.size],
                            work[:chunk.size],
                            None if anchors is None else anchors.part(i, i + step))
    return out


#: Matrix entries formed at once by :func:`solve_stack` (1 MB).
STACK_ENTRIES = 2**17
#: Matrices of fewer entries are solved by LAPACK's ``gesv`` (``getrf`` then ``getrs``
#: in one call): OpenBLAS factorises them on one thread whatever its threads, as
#: ``getrf`` alone does; larger ones by ``getrf`` and ``getrs`` apart, so that ``getrf``
#: may use the threads the Python API leaves it (the same factors as before).
GESV_ENTRIES = 10_000
#: A matrix whose reciprocal condition number :func:`condition_bounds` proves at least
#: this (a thousand times :data:`RCOND_MIN`) is not refused, without LAPACK's estimate.
CERTIFIED_RCOND = 1e3 * RCOND_MIN
#: Points of a stack per anchor of :func:`condition_bounds` at least, and per unknown
#: of its systems at least half a point: an anchor (an inverse and a product) costs
#: about what LAPACK's estimates of ``k / 4`` matrices of ``k`` unknowns cost.
POINTS_PER_ANCHOR = 8
#: Anchors of :func:`condition_bounds` per stack at most.
MAX_ANCHORS = 16
#: An anchor of :func:`condition_bounds` covers ``|F - F0| ||C||_1 <= COVERED`` (< 1).
COVERED = 0.9
#: Bound on the relative rounding of a formed, equilibrated entry (``F A1``, ``+ A0``,
#: ``* d``: three roundings of at most 2^-53 each), with room to spare.
FORMING_ROUNDING = 8 * 2.0**-53


@dataclass(frozen=True)
class ConditionBounds:
    """Anchors of a stack ``A(F) = A0 + F A1`` (:func:`condition_bounds`): per ``F``
    the index of the anchor that bounds its condition (-1: none); per anchor its
    ``F0``, row scales ``d0`` (shape ``(anchors, k)``), the bound ``inverse_norm`` on
    ``||A~0^-1||_1`` and ``growth`` on ``||C||_1``, and ``magnitudes``: the 1-norms of
    ``diag(d0) |A0|`` and ``diag(d0) |A1|`` (shape ``(anchors, 2)``)."""

    which: np.ndarray
    F0: np.ndarray
    d0: np.ndarray
    inverse_norm: np.ndarray
    growth: np.ndarray
    magnitudes: np.ndarray

    def part(self, start, stop) -> ConditionBounds:
        """The anchors of the stack's matrices ``start:stop``."""
        return replace(self, which=self.which[start:stop])

    def rcond_bounds(self, F, scale, norms) -> np.ndarray:
        """Lower bounds of the reciprocal 1-norm condition numbers of the equilibrated
        matrices ``diag(scale) A(F)`` as formed in floating point (``norms``: their
        1-norms), NaN where no anchor bounds them (derivation (D6b.2), (D6b.3))."""
        out = np.full(F.size, np.nan)
        ok = self.which >= 0
        if ok.any():
            a = self.which[ok]
            with np.errstate(invalid="ignore", over="ignore", divide="ignore"):
                ratio = self.d0[a] / scale[ok]
                # (D6b.2): the exact matrix's inverse, bounded.
                beta = (self.inverse_norm[a] * ratio.max(axis=1)
                        / (1.0 - np.abs(F[ok] - self.F0[a]) * self.growth[a]))
                # (D6b.3): the formed matrix differs from it by its entries' rounding.
                eta = (FORMING_ROUNDING / ratio.min(axis=1)
                       * (self.magnitudes[a, 0] + np.abs(F[ok]) * self.magnitudes[a, 1]))
                lost = beta * eta
                out[ok] = np.where(lost < 0.5, (1.0 - lost) / (norms[ok] * beta), np.nan)
        return out


def condition_bounds(A0, A1, F) -> ConditionBounds:
    """Anchors that bound the condition of every matrix of a stack ``A(F) = A0 + F A1``,
    each row equilibrated (``d(F)``: the reciprocals of the rows' largest magnitudes,
    as :func:`solve_equilibrated` scales them).

    At an anchor ``F0``, with ``A~0 = diag(d0) A(F0)`` and ``C = A~0^-1 diag(d0) A1``,
    ``diag(d) A(F) = diag(d / d0) A~0 (I + (F - F0) C)`` (D6b.1), so that for
    ``|F - F0| ||C||_1 < 1``::

        ||(diag(d) A(F))^-1||_1 <= ||A~0^-1||_1 max_i(d0_i / d_i) / (1 - |F - F0| ||C||_1)

    (D6b.2), and the matrix as formed in floating point is within its entries'
    rounding of it (D6b.3; derivation section 6b).  An anchor at the middle of the
    ``F`` range covers ``|F - F0| <= COVERED / ||C||_1`` (a bound within a factor
    ``1 - COVERED`` of the anchor's), and the ranges left on either side get one at
    their middles in turn (breadth first); at most one per :data:`POINTS_PER_ANCHOR`
    matrices or per ``k / 2`` matrices of ``k`` unknowns, whichever is fewer, and
    :data:`MAX_ANCHORS` in all (the rest are left to LAPACK's estimate).
    """
    F = np.asarray(F, dtype=float)
    k = A0.shape[0]
    which = np.full(F.size, -1)
    order = np.flatnonzero(np.isfinite(F))
    order = order[np.argsort(F[order], kind="stable")]
    fs = F[order]
    found = []
    tries = min(MAX_ANCHORS, F.size // max(POINTS_PER_ANCHOR, k // 2))
    spans = deque([(0, fs.size)] if fs.size and tries else [])  # sorted F's [i, j) to bound
    # F near the largest floats: spans and reaches that overflow are inf, as meant.
    with np.errstate(over="ignore", invalid="ignore"):
        while spans and tries > 0:
            tries -= 1
            i, j = spans.popleft()
            F0 = fs[i] + 0.5 * (fs[j - 1] - fs[i]) if fs[j - 1] - fs[i] < math.inf else fs[i]
            anchor = _anchor(A0, A1, F0)
            # Singular there: the two sides in turn, without the F equal to F0.
            r = 0.0 if anchor is None else COVERED / anchor[2] if anchor[2] > 0 else math.inf
            lo = int(np.searchsorted(fs, F0 - r, side="left"))
            hi = int(np.searchsorted(fs, F0 + r, side="right"))
            if anchor is not None:
                which[order[lo:hi]] = len(found)
                found.append((F0, *anchor))
            spans += [s for s in ((i, lo), (hi, j)) if s[0] < s[1]]
    if not found:
        return ConditionBounds(which, np.empty(0), np.empty((0, k)), np.empty(0), np.empty(0),
                               np.empty((0, 2)))
    F0s, d0s, inverse_norms, growths, magnitudes = zip(*found)
    return ConditionBounds(which, np.array(F0s), np.array(d0s), np.array(inverse_norms),
                           np.array(growths), np.array(magnitudes))


def _anchor(A0, A1, F0):
    """``(d0, ||A~0^-1||_1, ||C||_1, (||d0 |A0|||_1, ||d0 |A1|||_1))`` of
    :func:`condition_bounds` at ``F0``, the norms bounded for the rounding of ``A~0``
    as formed (D6b.3); None where ``A~0`` is singular, not finite or too ill-conditioned
    for that bound."""
    if not math.isfinite(F0):
        return None
    with np.errstate(invalid="ignore", over="ignore", divide="ignore"):
        A = A0 + F0 * A1 if A1 is not None else A0.copy()
        d0 = row_scales(A)
        A *= d0[:, None]
        if not np.all(np.isfinite(A)):
            return None
        norm = np.abs(A).sum(axis=0).max()
        lu, piv, info = dgetrf(A, overwrite_a=True)
        if info != 0:
            return None
        inverse, info = dgetri(lu, piv, overwrite_lu=True)
        if info != 0:
            return None
        B = np.zeros_like(A0) if A1 is None else d0[:, None] * A1
        magnitudes = (float(np.abs(d0[:, None] * A0).sum(axis=0).max()),
                      float(np.abs(B).sum(axis=0).max()))
        computed = np.abs(inverse).sum(axis=0).max()
        # An anchor that could prove nothing: and its inverse's own rounding (about
        # k 1e-16 / rcond relative) stays far below the factor CERTIFIED_RCOND spares.
        if not 1.0 / (norm * computed) >= CERTIFIED_RCOND:
            return None
        # A~0 exact differs from the one inverted by eta0 in norm at most: its inverse's
        # norm and C's, bounded (D6b.3).
        eta0 = FORMING_ROUNDING * (magnitudes[0] + abs(F0) * magnitudes[1])
        if not computed * eta0 < 0.5:
            return None
        inverse_norm = computed / (1.0 - computed * eta0)
        growth = (np.abs(inverse @ B).sum(axis=0).max()
                  + computed * inverse_norm * eta0 * magnitudes[1])
    if not (math.isfinite(inverse_norm) and math.isfinite(growth)):
        return None
    return d0, float(inverse_norm), float(growth), magnitudes


def _solve_chunk(A0t, A1t, b, F, what, S, work, anchors=None):
    # Each A_i is stored transposed (S[i] = A_i^T), so that S[i].T is in LAPACK's order.
    # A non-finite F makes its matrix non-finite: refused below, at that F only.
    with np.errstate(invalid="ignore", over="ignore"):
        if A1t is None:
            S[...] = A0t[None]
        else:
            np.multiply(A1t[None], F[:, None, None], out=S)
            S += A0t[None]
        # Rows of A_i are columns of S[i]: scaled as in solve_equilibrated.
        scale = row_scales(S, axis=1)
        S *= scale[:, None, :]
        B = b[None, :] * scale
        # Rows of S[i] are columns of A_i: the 1-norm is the largest of their sums.
        sums = np.empty(S.shape[:2])
        rows = work.shape[1]
        for r in range(0, S.shape[1], rows):
            part = S[:, r:r + rows]
            sums[:, r:r + rows] = np.abs(part, out=work[:, :part.shape[1]]).sum(axis=2)
        norms = sums.max(axis=1)
    # Each equilibrated row is at most 1 in magnitude, so a norm is finite exactly when
    # the whole matrix is (an inf or a NaN makes its row's scale and so the row NaN).
    finite = np.isfinite(norms)
    proven = (np.full(F.size, np.nan) if anchors is None
              else anchors.rcond_bounds(F, scale, norms))
    # gesv's factors are getrf's where OpenBLAS factorises on one thread whatever its
    # threads (fewer than GESV_ENTRIES entries); above, getrf may use several, gesv not.
    small = S.shape[1] * S.shape[2] < GESV_ENTRIES
    out, solved = [], []
    for i in range(F.size):
        if not finite[i]:
            out.append(not_finite(what))
            continue
        if small:
            # getrf and getrs in one call (gesv), one call fewer per point; a system
            # then refused by its condition costs one solve.
            lu, piv, x, singular = dgesv(S[i].T, B[i], overwrite_a=True)
        else:
            lu, piv, singular = dgetrf(S[i].T, overwrite_a=True)
        # An exact zero pivot is refused by the estimate (0), as without the bound.
        if proven[i] >= CERTIFIED_RCOND and singular == 0:
            rcond = float(proven[i])
        else:
            rcond, info = dgecon(lu, norms[i], norm="1")
            rcond = float(rcond)
            if info != 0 or not math.isfinite(rcond) or rcond < RCOND_MIN:
                out.append(ill_conditioned(what, rcond))
                continue
        if not small:
            x, _ = dgetrs(lu, piv, B[i])
        out.append((x, rcond))
        solved.append(i)
    if solved:
        # Non-finite solutions, all checked at once.
        ok = np.isfinite(np.concatenate([out[i][0] for i in solved]))
        for i in np.asarray(solved)[~ok.reshape(len(solved), -1).all(axis=1)]:
            out[i] = not_finite_solution(what)
    return out
