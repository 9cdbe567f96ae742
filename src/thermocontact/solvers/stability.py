"""Eigenvalues of a steady single patch: is it stable?

The contact linearised about a steady solution at fixed load is ``M(b) c = 0``
(:class:`~thermocontact.discretisation.linearised.LinearisedContact`, derivation
section 18), a nonlinear eigenproblem in the rate ``b`` (units ``k2/Delta^2``).  The
verdict is a count: the roots of ``det M`` in the region ``Re b >= b_min``,
``|b| <= R`` (``R`` the modulus bound, the model's range, eq. S11) by the argument
principle on its boundary (:class:`Winding`: the phase of the determinant followed
with steps each confirmed by its midpoint, eq. S12; a contact set's steps from the
eigenvalues of the matrices' ratio, :func:`step_phase`, eq. S25).  Where the count is
positive the roots are located (a single one, real, bracketed on a fixed grid of real
rates and found by the secant method, :func:`_real_root`; several by Beyn's contour
integral on the smallest half-disc holding them all, :func:`beyn`) and each is confirmed
by the secant method or Newton's method on ``det M`` kept on the principal sheet
(:func:`newton`, eq. S13); the error estimate is the change of the eigenvalues between
``n`` and ``3n/2``.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..discretisation.linearised import LinearisedContact, check_modelled
from ..discretisation.linearised_set import LinearisedContactSet
from ..io.results import Result
from ..numerics.continuation import secant
from ..numerics.dense import log_determinants
from ..problem.validation import InputError, check_integer, check_positive
from .zones import ZoneSolution

__all__ = ["B_MIN", "MODULUS_BOUND", "StabilityResult", "Winding", "beyn", "half_disc",
           "linearised", "newton", "scaled_matrix", "stability_of", "step_phase"]

#: Unknowns per function of the stability analysis (its own discretisation).
STABILITY_N = 12
#: The smallest growth rate counted by default, ``k2/Delta^2``: a growth time of a
#: thousand diffusion times across the half-width (a fold's exponentially slow real
#: root, derivation S8, lies far below it).
B_MIN = 1e-3
#: The default modulus bound, ``k2/Delta^2`` (derivation S11): a mode growing faster has
#: a thermal layer thinner than ``Delta/1000``, where the surfaces' roughness and the
#: interface's conductance, not this model, decide.
MODULUS_BOUND = 1e6
#: An eigenvalue that changes by more than this (relative) from n to 3n/2 is said to be
#: unresolved in the record's reason.
UNRESOLVED = 0.1
#: The error estimate's Newton method at the finer n stops at a step below this
#: (relative to ``max(|b|, 1)``; for a complex eigenvalue below this times
#: ``2 |Im b|/max(|b|, 1)`` too, as its conjugate is a root ``2 |Im b|`` away): the change,
#: the sum of its steps, is then that to the finer n's root within about ``C s s'``
#: (``s`` the last step, ``s'`` the one before or ``s`` itself after one step, ``C`` the
#: root's ``|f''/2f'|`` for ``f = det M``, about the inverse of the distance to the nearest
#: other root), a fraction ``C s`` of itself: a thousandth where the roots are apart, one
#: step (two evaluations of ``M``) where the change is below ``1e-3`` (derivation S13).
ESTIMATE_TOL = 1e-3
#: The largest change of the determinant's phase accepted between two samples.
PHASE_STEP = np.pi / 4
#: Below this step of the contour's parameter a sample interval is not refined further:
#: a root on or against the contour, and the count is not certified.
SMALLEST_STEP = 1e-9
#: The largest bound on a sample's phase error (radians: ``N^2 u / rcond`` of the
#: equilibrated ``N x N`` matrix, :func:`~thermocontact.numerics.dense.log_determinants`)
#: with which a count is certified: the phase change along the contour is then off by
#: at most twice that, a third of a root's pi.
PHASE_ERROR_MAX = 0.5
_U = np.finfo(float).eps / 2
#: The line's parameter ``t`` (``b = b_min (1 + i sinh t)``): first steps this long.
_LINE_STEP = 4.0
#: Above this ``n`` the line's first steps are ``_LINE_STEP * _LINE_STEP_N / n``.
_LINE_STEP_N = 16
#: The arc's first steps (of ``theta`` in ``[0, pi/2]``).
_ARC_STEPS = 2

COUNT_METHOD = ("argument principle: the phase of det M(b) (temperature rows times "
                "sqrt(1 + b)) along Re b = b_min and the arc |b| = modulus_bound, each step "
                "confirmed by its midpoint (both halves change it by less than pi/4 and add "
                "up to the whole, or else the sums of the arguments of the eigenvalues of "
                "M(a)^-1 M(b), each below pi/4, do); roots located by the secant method in "
                "a bracket on a grid of real rates (one, real) or Beyn's contour integral "
                "and Newton's method")
#: A contact set's (derivation S25): each step's phase from the eigenvalues of the
#: matrices' ratio.
COUNT_METHOD_STEPS = (
    "argument principle: the phase of det M(b) (temperature rows times sqrt(1 + b)) along "
    "Re b = b_min and the arc |b| = modulus_bound, each step's change the sum of the "
    "arguments of the eigenvalues of M(a)^-1 M(b), each below pi/4, confirmed by its "
    "midpoint (the halves' changes add up to the whole's); roots located by the secant "
    "method in a bracket on a grid of real rates (one, real) or Beyn's contour integral "
    "and Newton's method")


@dataclass(frozen=True, eq=False, repr=False)
class StabilityResult(Result):
    """The eigenvalues of a steady single patch with ``Re b >= b_min``, counted.

    Attributes
    ----------
    eigenvalues : ndarray of complex
        Every eigenvalue located in the region, largest real part first, both members
        of each conjugate pair (``M(conj b) = conj M(b)``); as many as counted unless
        ``reason`` says otherwise.  In units of ``k2/Delta^2``, or 1/s where
        ``rate_unit`` was given.
    unstable_modes : int or None
        The number of eigenvalues in the region by the argument principle (with
        multiplicity); None where the count could not be certified.
    stable : bool or None
        True when the count is 0, False when it is positive, None where it could not
        be certified (``reason``).
    reason : str or None
        Why ``stable`` is None, what was not located, or that an eigenvalue is not
        resolved at ``n`` (its error estimate above 0.1); None otherwise.
    growth_rate : float or None
        The largest real part of an eigenvalue located, None where none.
    region : tuple
        ``(b_min, modulus_bound)`` in the units of the eigenvalues.
    count_method : str
    error_estimate : float or None
        The largest change of an eigenvalue between ``n`` and ``3n/2`` (``n/2`` above
        ``n = 32``), relative to ``max(|b|, 1)``: an estimate of its error at ``n``;
        None where there is none or it was not computed (a map's points).
    fold : float or None
        ``|det M(0)/det M_reg(0)|`` (the two differ in the heat partition's row, S7-S8):
        0 at a fold of the load, where a real root leaves ``b = 0`` exponentially
        slowly; None for a moving half-plane (``b = 0`` is then no branch point).
    slow_root : float or None
        The estimate (S8) of that real root, in the eigenvalues' units, where it lies
        on the principal sheet below ``b_min`` (not counted); None otherwise.
    evaluations : int
        Evaluations of ``M(b)``.
    n : int
    units : str
    samples : tuple of complex
        The rates on the region's boundary where the count evaluated ``M(b)``
        (``k2/Delta^2`` whatever ``units``): a neighbouring contact's count evaluates
        them first, together (:func:`stability_of`); not part of the record.
    """

    eigenvalues: np.ndarray
    unstable_modes: int | None
    stable: bool | None
    reason: str | None
    growth_rate: float | None
    region: tuple
    count_method: str
    error_estimate: float | None
    fold: float | None
    slow_root: float | None
    evaluations: int
    n: int
    units: str = "k2/Delta^2"
    samples: tuple = ()

    STATUSES = {"stable": "no eigenvalue in the region, the count certified",
                "unstable": "eigenvalues in the region (unstable_modes), the count certified",
                "uncertain": "the count could not be certified (message says why): stable "
                             "is None"}
    SUCCESS = frozenset({"stable", "unstable"})
    UNITS = {"eigenvalues": "k2/Delta^2"}

    @property
    def status(self) -> str:
        """One of :attr:`STATUSES`, from ``stable``."""
        return {True: "stable", False: "unstable"}.get(self.stable, "uncertain")

    @property
    def message(self) -> str:
        """The verdict in one line, with its reason where there is one."""
        b_min, bound = self.region
        head = (f"{self.unstable_modes} eigenvalue{'s' * (self.unstable_modes != 1)} with "
                f"Re b >= {b_min:g} and |b| <= {bound:g} {self.units}"
                if self.unstable_modes is not None else "the count was not certified")
        return head + ("" if self.reason is None else f"; {self.reason}")

    def _units(self) -> dict:
        return {name: self.units for name in ("eigenvalues", "growth_rate", "region",
                                              "slow_root")}

    def _summary(self):
        lead = (f"{self.eigenvalues[0]:.4g}" if len(self.eigenvalues) else "none")
        return (f"stable={self.stable}, unstable_modes={self.unstable_modes}, "
                f"largest={lead}, units={self.units!r}")

    def _record(self):
        est = self.error_estimate
        return {"stable": self.stable, "unstable_modes": self.unstable_modes,
                "reason": self.reason,
                "eigenvalues": [[float(b.real), float(b.imag)] for b in self.eigenvalues],
                "growth_rate": self.growth_rate,
                "region": {"b_min": self.region[0], "modulus_bound": self.region[1]},
                "count_method": self.count_method,
                "error_estimate": None if est is None else float(est),
                "fold": None if self.fold is None else float(self.fold),
                "slow_root": self.slow_root,
                "evaluations": int(self.evaluations), "n": self.n}


def linearised(solution) -> LinearisedContact | LinearisedContactSet:
    """The linearised contact about a :class:`~.result.ContactSolution`, or about a
    contact set (:class:`~.zones.ZoneSolution`, its edges free, derivation section
    18b)."""
    check_modelled(method=solution.method)
    if isinstance(solution, ZoneSolution):
        return LinearisedContactSet(solution.parameters, solution.representation,
                                    solution.edges, solution.phi, solution.psi,
                                    solution.profile, solution.conductance)
    return LinearisedContact(solution.parameters, solution.representation, solution.phi,
                             solution.psi, solution.load_ratio, solution.sigma_over_delta,
                             solution.conductance)


class Winding:
    """The phase of a function analytic in ``Re b > 0`` with ``f(conj b) = conj f(b)``,
    followed along the boundary of ``Re b >= b_min``, ``|b| <= R`` (its upper half), and
    the number of its zeros inside (the argument principle).

    ``f = det A(b)`` of a matrix function ``A``; its phase and ``log|f|`` come from
    the LU factors of ``A`` equilibrated, with a bound on the phase's rounding that a
    certified count respects at every sample
    (:func:`~thermocontact.numerics.dense.log_determinants`, :data:`PHASE_ERROR_MAX`).
    The matrices are kept, so that the boundaries of
    several ``R`` share the line's samples and :meth:`contour` can serve Beyn's
    method.

    Parameters
    ----------
    matrix : callable
        ``b -> A(b)``, square.
    b_min : float
    prepare : callable, optional
        ``prepare(points)`` before the samples ``points`` of one round of refinement
        are evaluated by ``matrix`` one by one: for work shared by several (the
        linearised contact's kernel moments, :meth:`LinearisedContact.prepare`).
    line_step : float, optional
        The line's first steps in ``t`` (default :data:`_LINE_STEP`): shorter where
        more rows are scaled by ``sqrt(1 + b)`` (a contact set's, derivation S22),
        whose phase then turns faster along the line.
    many : callable, optional
        ``points -> A``, the matrices at several points stacked (the linearised
        contact's :meth:`LinearisedContact.matrices`): each round's samples evaluated
        together, in place of ``prepare`` and ``matrix`` one by one (the same
        matrices).
    ratios : bool or "refine"
        Follow each step's phase change as :func:`step_phase` does, from the
        eigenvalues of ``A(a)^-1 A(b)`` (a contact set's, derivation S25): a turn of
        the determinant's phase made of many small turns of its factors is then not
        aliased between samples.  ``"refine"``: only for a step the determinant's phase
        at its ends and midpoint does not confirm, before it is cut in two (the single
        patch's: a step confirmed either way is taken, and the eigenvalues, about 1 ms
        a step, are paid only where a round of new rates would be).
    """

    def __init__(self, matrix, b_min, prepare=None, line_step=None, many=None,
                 ratios=False):
        self.matrix, self.b_min, self.prepare = matrix, float(b_min), prepare
        self.line_step = _LINE_STEP if line_step is None else float(line_step)
        self.many = many
        #: Each step's phase change from the eigenvalues of ``A(a)^-1 A(b)``
        #: (:func:`step_phase`) instead of the determinant's phase at its ends: always
        #: (True), or where the determinant's phase does not confirm it ("refine").
        self.ratios = ratios if ratios == "refine" else bool(ratios)
        self.values, self.matrices, self.phase_errors = {}, {}, {}
        #: ``p`` of the factor ``(1 + b)^p`` divided out of ``f`` before its phase is
        #: followed (:meth:`settled`); set by the first :meth:`count`.
        self.power = None

    def evaluate(self, points):
        """Evaluate and keep ``A`` and its determinant at ``points`` not yet kept, together
        where ``many`` was given (otherwise after ``prepare``, one by one, as
        :meth:`at` does on demand)."""
        fresh = [z for z in dict.fromkeys(points) if z not in self.values]
        if not fresh:
            return
        if self.many is None:
            if self.prepare is not None:
                self.prepare(fresh)
            return
        self._keep(fresh, self.many(fresh))

    def _keep(self, points, A):
        """Keep the stack ``A`` at ``points``, the phases and ``log|det|``, and a bound
        on each phase's rounding (``N^2 u / rcond``:
        :func:`~thermocontact.numerics.dense.log_determinants`)."""
        signs, logdets, rconds = log_determinants(A)
        bound = A.shape[-1] ** 2 * _U
        for b, Ab, sign, logdet, rcond in zip(points, A, signs, logdets, rconds):
            self.matrices[b] = Ab
            self.values[b] = (complex(sign), float(logdet))
            self.phase_errors[b] = bound / rcond if rcond > 0 else np.inf

    def at(self, b):
        """``(sign, log|det A(b)|)``, kept (with ``A(b)``)."""
        if b not in self.values:
            self._keep([b], self.matrix(b)[None])
        return self.values[b]

    def settled(self, b):
        """``(phase, log|g(b)|)`` of ``g = f / (1 + b)^p`` (derivation S12).

        ``det M(b)`` grows like a power ``b^p`` for large ``|b|`` (``p`` about ``n/8``
        to ``n/6`` for the single patch: the rows and columns the scaling does not
        settle), and
        its phase turns by about ``p pi/2`` along the line, fastest where ``|b|``
        passes 1: at large ``n`` several turns within one first step, which three
        samples cannot tell from none.  ``(1 + b)^p`` (principal branch) is analytic
        and non-zero in ``Re b > -1`` for every real ``p``, so ``g`` has the zeros of
        ``f`` in the region: the count is the same whatever ``p``, which only removes
        turning that is no root's."""
        sign, logdet = self.at(b)
        if not self.power:
            return sign, logdet
        w = np.log1p(b)
        return sign * np.exp(-1j * self.power * w.imag), logdet - self.power * w.real

    def _measure_power(self, R):
        """``p`` from ``log|f|`` at ``|b| = R`` and ``R/16`` on three rays, ``arg b = 0``,
        about ``pi/4`` and ``3 pi/8`` (through the arc's samples; the median of the three: a root within a few
        millionths of ``R`` on one ray, which makes ``|f|`` there tiny, spoils that
        ray's only; from the real axis alone such a root gave ``p = -4`` where the
        power is about 4, and the count's whole turns aliased); 0 where the region is
        too small to tell."""
        low = max(R / 16.0, self.b_min)
        if low >= 0.5 * R:
            self.power = 0.0
            return
        # The rays through the arc's samples (count), whose values at R are kept.
        edges = self._arc_edges(R)
        angles = (edges[-1], edges[-2], 0.5 * (edges[-3] + edges[-2]))
        rays = [np.exp(1j * angle) for angle in angles]
        points = [complex(r * ray) for ray in rays for r in (R, low)]
        self.evaluate(points)
        logs = [self.at(z)[1] for z in points]
        powers = [(logs[2 * j] - logs[2 * j + 1])
                  / (np.log(abs(1.0 + R * ray)) - np.log(abs(1.0 + low * ray)))
                  for j, ray in enumerate(rays)]
        # A ray with a determinant zero to rounding tells nothing.
        powers = [p for p in powers if np.isfinite(p)]
        self.power = float(np.median(powers)) if powers else 0.0

    def boundary(self, R, points):
        """``(arc, line)``: those of ``points`` on the arc ``|b| = R`` (by angle) and on
        the line ``Re b = b_min``, ``|b| <= R`` (by imaginary part), the upper half of
        the boundary for ``R``."""
        b_min = self.b_min
        line = sorted((b for b in points if b.real == b_min and abs(b) <= R * (1 + 1e-12)),
                      key=lambda b: b.imag)
        arc = sorted((b for b in points if abs(abs(b) - R) <= 1e-12 * R and b.real != b_min),
                     key=lambda b: np.angle(b))
        return arc, line

    def contour(self, R):
        """The samples on the upper half of the boundary for ``R`` (counterclockwise:
        the arc from ``b = R``, then down the line) with trapezoidal weights ``dz``,
        after :meth:`count` for ``R``."""
        arc, line = self.boundary(R, self.values)
        z = np.array(arc + line[::-1], dtype=complex)
        dz = np.zeros_like(z)
        step = np.diff(z)
        dz[:-1] += 0.5 * step
        dz[1:] += 0.5 * step
        return z, dz

    def line(self, t):
        return complex(self.b_min, self.b_min * np.sinh(t))

    def _follow(self, pieces):
        """The phase change of ``f`` along the paths ``point(t)``, ``t`` from ``t0`` to
        ``t1``, of ``pieces`` (tuples ``(point, t0, t1)``), summed.

        Each step is accepted only when its midpoint confirms it: both halves change
        the phase by less than :data:`PHASE_STEP`, their sum agrees with the whole
        step's change (an alias of a whole turn cannot pass both), and the midpoint is
        not a sharp minimum of ``|f|`` (``log|f|`` more than 2 below the chord: a root
        close to the contour); otherwise both halves are examined in the next round.
        Each round's samples are prepared together.  None (and why) where a step falls
        below :data:`SMALLEST_STEP` or ``f`` vanishes."""
        todo = [(point, float(a), float(b)) for point, a, b in pieces]
        total = 0.0
        while todo:
            # In order, once each (the same batch, the same rounding, every run).
            self.evaluate([point(t) for point, a, b in todo for t in (a, 0.5 * (a + b), b)])
            refine = []
            for point, a, b in todo:
                m = 0.5 * (a + b)
                (pa, la), (pm, lm), (pb, lb) = (self.settled(point(t)) for t in (a, m, b))
                if pa == 0 or pm == 0 or pb == 0:
                    return None, (f"det M(b) = 0 to rounding near b = {point(m):.6g}: a "
                                  f"root on the contour, or its phase uncertain (M(b) too "
                                  f"ill-conditioned at this n)")
                worst = max(self.phase_errors[point(t)] for t in (a, m, b))
                if worst > PHASE_ERROR_MAX:
                    return None, (f"the phase of det M(b) is uncertain near b = "
                                  f"{point(m):.6g} (its rounding up to {worst:.2g} rad: M(b) "
                                  f"too ill-conditioned at this n)")
                # Not a sharp minimum of |f| at the midpoint (a root close by).
                smooth = lm >= 0.5 * (la + lb) - 2.0
                confirmed = False
                if self.ratios is not True:
                    first, second = float(np.angle(pm / pa)), float(np.angle(pb / pm))
                    whole = float(np.angle(pb / pa))
                    agree = abs(np.angle(np.exp(1j * (first + second - whole)))) < 0.1
                    confirmed = (smooth and agree and abs(first) < PHASE_STEP
                                 and abs(second) < PHASE_STEP)
                if not confirmed and self.ratios and smooth:
                    # Each eigenvalue's turn bounded instead (step_phase; inf beyond).
                    first, second, whole = (self._step(point(x), point(y)) for x, y in
                                            ((a, m), (m, b), (a, b)))
                    confirmed = abs(first + second - whole) < 0.1
                if confirmed:
                    total += first + second
                    continue
                if abs(b - a) < SMALLEST_STEP:
                    return None, f"a root on or against the contour near b = {point(m):.6g}"
                refine += [(point, a, m), (point, m, b)]
            todo = refine
        return total, None

    def _step(self, x, y):
        """The phase change of ``g`` (:meth:`settled`) from ``x`` to ``y`` by
        :func:`step_phase`, less ``p`` times that of ``1 + b`` (no winding: ``1 + b``
        stays in the right half-plane); ``inf`` where an eigenvalue's argument reaches
        :data:`PHASE_STEP`."""
        change = step_phase(self.matrices[x], self.matrices[y])
        if self.power:
            change -= self.power * float(np.angle(1.0 + y) - np.angle(1.0 + x))
        return change

    def _arc_edges(self, R):
        """The angles of the arc's first steps, from where it meets the line to 0 (one
        expression for :meth:`count` and :meth:`_measure_power`, whose rays must meet
        the arc's samples exactly)."""
        theta0 = float(np.arctan2(np.sqrt(R * R - self.b_min * self.b_min), self.b_min))
        return np.linspace(theta0, 0.0, _ARC_STEPS + 1)

    def count(self, R):
        """``(N, reason)``: the number of zeros of ``f`` in ``Re b >= b_min``,
        ``|b| <= R``, with multiplicity, or ``(None, why)`` where the phase could not
        be followed or the winding is not an integer, or is negative (no analytic
        ``f`` winds so: its phase was lost)."""
        b_min = self.b_min
        if self.power is None:
            self._measure_power(R)
        Y = np.sqrt(R * R - b_min * b_min)
        T = float(np.arcsinh(Y / b_min))
        # The line on a grid common to every R, then to its end at |b| = R.
        grid = np.arange(0.0, T, self.line_step)
        pieces = [(self.line, t0, t1) for t0, t1 in zip(grid, list(grid[1:]) + [T])]
        edges = self._arc_edges(R)
        # The arc starts where the line ends: one sample, not two a rounding apart.
        corner = self.line(T)

        def arc(th):
            return corner if th == edges[0] else R * np.exp(1j * th)
        pieces += [(arc, a, b) for a, b in zip(edges[:-1], edges[1:])]
        change, why = self._follow(pieces)
        if change is None:
            return None, why
        # Upward along the line and back along the arc is the upper half of the
        # boundary traversed clockwise; the lower half adds as much (conjugates).
        winding = -change / np.pi
        N = int(round(winding))
        if abs(winding - N) > 0.05:
            return None, f"the winding {winding:.3f} is not an integer"
        if N < 0:
            # An analytic det M(b) winds zero or more times; a negative winding is a
            # phase lost along the way (whole turns between samples), no count.
            return None, (f"the winding {N} is negative: the phase of det M(b) was lost "
                          f"between its samples")
        return N, None


def step_phase(A, B) -> float:
    """The change of ``arg det`` from ``A`` to ``B`` along ``A + s (B - A)``,
    ``0 <= s <= 1``: the sum of the principal arguments of the eigenvalues ``mu`` of
    ``A^-1 B`` (``det(I + s(A^-1 B - I))`` is the product of ``1 + s(mu - 1)``, each on
    the segment from 1 to ``mu``; derivation S25); ``inf`` where one of them reaches
    :data:`PHASE_STEP` (the step too long to be taken as the matrices' chord)."""
    mu = np.linalg.eigvals(np.linalg.solve(A, B))
    args = np.angle(mu)
    if not np.all(np.abs(args) < PHASE_STEP):
        return np.inf
    return float(args.sum())


def half_disc(b_min, R, *, panels_per_unit=1.0, nodes=8):
    """Quadrature of the upper half of the boundary of ``Re b >= b_min``,
    ``|b| <= R``, counterclockwise: points ``z`` and weights ``dz`` (Gauss-Legendre on
    the arc in ``theta`` and on the line in ``t``, ``b = b_min (1 + i sinh t)``, which
    keeps the branch point ``b = 0`` at a fixed distance ``pi/2`` from the real ``t``
    axis); the lower half is their conjugate, traversed the other way."""
    x, w = np.polynomial.legendre.leggauss(nodes)
    Y = np.sqrt(R * R - b_min * b_min)
    theta0 = float(np.arctan2(Y, b_min))
    T = float(np.arcsinh(Y / b_min))

    def panels(a, b, count):
        edges = np.linspace(a, b, count + 1)
        mid, half = 0.5 * (edges[1:] + edges[:-1]), 0.5 * np.diff(edges)
        return (mid[:, None] + half[:, None] * x).ravel(), (half[:, None] * w).ravel()
    th, wth = panels(0.0, theta0, max(2, int(np.ceil(theta0 / (np.pi / 8)))))
    z_arc, dz_arc = R * np.exp(1j * th), 1j * R * np.exp(1j * th) * wth
    t, wt = panels(T, 0.0, max(2, int(np.ceil(T * panels_per_unit))))
    z_line = b_min * (1.0 + 1j * np.sinh(t))
    dz_line = 1j * b_min * np.cosh(t) * wt    # t descends: the weights are negative
    return np.concatenate([z_arc, z_line]), np.concatenate([dz_arc, dz_line])


def beyn(matrix, contour, *, rank=None, probes=8, tol=1e-5, seed=0, progress=None):
    """Eigenvalues of ``M(b) c = 0`` inside a contour symmetric about the real axis, by
    Beyn's method (Beyn 2012, algorithm 1).

    ``A_k = (1/2 pi i) oint b^k M(b)^{-1} V db`` by the quadrature ``contour`` of the
    upper half (points and weights ``dz``, counterclockwise; :func:`half_disc`), the
    lower half its conjugate (``M(conj b) = conj M(b)``, ``V`` real);
    ``A_0 = V0 S W0^H`` truncated to ``rank`` (or at ``tol`` times the integrand's
    largest norm); the eigenvalues of ``V0^H A_1 W0 S^{-1}``.

    Parameters
    ----------
    matrix : callable
        ``M(b)``, a square complex matrix, analytic inside and near the contour.
    contour : tuple
        ``(z, dz)`` of the upper half.
    rank : int, optional
        The number of eigenvalues inside (the argument principle's count).
    probes : int
        Columns of ``V``: at least the number of eigenvalues inside.
    progress : callable, optional
        ``progress(done, total)`` after each evaluation of ``M``.

    Returns
    -------
    eigenvalues : ndarray
    rank : int
    """
    z, dz = contour
    rng = np.random.default_rng(seed)
    V = None
    A0 = A1 = 0.0
    size = 0.0
    for j, (zj, dzj) in enumerate(zip(z, dz)):
        M = matrix(zj)
        if progress is not None:
            progress(j + 1, len(z))
        if V is None:
            V = rng.standard_normal((M.shape[0], min(probes, M.shape[0])))
        X = np.linalg.solve(M, V) * dzj
        A0 = A0 + X
        A1 = A1 + zj * X
        size = max(size, np.linalg.norm(X, 2) / abs(dzj))
    # The lower half: the conjugates, traversed the other way.
    A0 = (A0 - np.conj(A0)) / (2j * np.pi)
    A1 = (A1 - np.conj(A1)) / (2j * np.pi)
    U, sv, Wh = np.linalg.svd(A0, full_matrices=False)
    k = int(np.sum(sv > tol * max(size, 1e-300))) if rank is None else int(rank)
    if k == 0:
        return np.array([], dtype=complex), 0
    U, sv, W = U[:, :k], sv[:k], Wh[:k].conj().T
    B = U.conj().T @ A1 @ W / sv[None, :]
    return np.linalg.eigvals(B), k


def newton(matrix, b0, *, steps=16, tol=1e-10, h=1e-6, floor=0.0, prepare=None,
           previous=None):
    """An eigenvalue of ``M(b) c = 0`` by Newton's method on ``det M`` from ``b0``.

    ``b <- b - 1/tr(M^{-1} M')`` (the logarithmic derivative of the determinant), with
    ``M'`` the divided difference of ``M`` at the last two iterates (the secant method
    on the matrices: one evaluation of ``M`` a step), and at the first step, or at a
    step that shrinks less than halfway, the forward difference of step ``h |b|``
    toward larger ``Re b`` (on the sheet).  Near a simple root ``b*`` a step is
    ``(b - b*)(1 + O(|b' - b*|))``, ``b'`` the difference's other point, so that a small
    last step confirms a root as Newton's does, and the iterates converge with the
    secant method's order ``(1 + sqrt 5)/2`` (derivation S13).  The iterates stay on the
    principal sheet, ``Re b > floor``: a step that would cross it is halved until it does
    not (the cut ``b <= 0`` of the stationary half-plane's kernels is never reached), and
    a halved step does not end the iteration, however small.  Returns the
    last iterate and its last step as proposed, before any halving (``inf`` where the
    iterates could not stay on the sheet).  ``prepare``, where given, is called with
    the rates of each step before ``matrix`` (:class:`Winding`).  ``previous``, where
    given, is a rate near ``b0`` (an iterate before it) whose ``M`` makes the first
    step's divided difference in place of the forward one.
    """
    b = complex(b0)
    if b.real <= floor:
        # A start off the sheet (an estimate left of the line): moved onto it.
        b = complex(floor + max(abs(floor), 1e-12), b.imag)
    step, before = np.inf, None
    if previous is not None and complex(previous) != b:
        if prepare is not None:
            prepare([complex(previous), b])
        before = (complex(previous), matrix(complex(previous)))

    def forward(b, M):
        e = h * max(abs(b), 1e-300)
        if prepare is not None:
            prepare([b + e])
        return (matrix(b + e) - M) / e
    for _ in range(steps):
        if prepare is not None:
            prepare([b] if before is not None else [b, b + h * max(abs(b), 1e-300)])
        M = matrix(b)
        last = step
        try:
            if before is None:
                step = 1.0 / np.trace(np.linalg.solve(M, forward(b, M)))
            else:
                step = 1.0 / np.trace(np.linalg.solve(M, (M - before[1]) / (b - before[0])))
                if not abs(step) <= 0.5 * abs(last):
                    step = 1.0 / np.trace(np.linalg.solve(M, forward(b, M)))
        except np.linalg.LinAlgError:
            return b, 0.0       # M singular to rounding: b is a root
        if not np.isfinite(step):
            return b, 0.0
        move = step
        for _ in range(60):
            if (b - move).real > floor:
                break
            move *= 0.5
        else:
            return b, np.inf
        before = (b, M)
        b = b - move
        # The step proposed, not the one halved to stay on the sheet, says how close
        # the root is; a halved step has not reached it.
        if move == step and abs(step) <= tol * max(1.0, abs(b)):
            break
    return b, abs(step)


def scaled_matrix(lin, *, many=False):
    """``b -> M(b)`` with its temperature rows times ``sqrt(1 + b)`` (analytic and
    non-zero in ``Re b > 0``: the same eigenvalues; the rows' size and the
    determinant's phase then settle as ``|b|`` grows, where the temperature falls like
    ``b^(-1/2)``, derivation S11, and are unchanged near ``b = 0``).  With ``many``,
    ``rates -> `` the matrices at several non-zero rates stacked
    (:meth:`LinearisedContact.matrices`)."""
    rows = lin.temperature_rows

    def matrices(rates):
        M = lin.matrices(rates)
        M[:, rows] *= np.sqrt(1.0 + np.asarray(rates, dtype=complex))[:, None, None]
        return M

    def matrix(b):
        M = lin.matrix(b)
        M[rows] *= np.sqrt(1.0 + b)
        return M
    return matrices if many else matrix


def _fold(lin):
    """``|det M(0)/det M_reg(0)|`` (0 at a fold of the load, S8) and the slow real root
    of (S8), ``b* = 4 exp(-2 gamma_E) exp(2 det M_reg(0)/det M(0))``, where the ratio is
    negative (its sign decides whether the root is on the principal sheet); None and
    None for a moving half-plane, whose kernels are analytic at ``b = 0``."""
    if getattr(lin, "moving", False):
        return None, None
    reg, _, row = lin.matrix(0, split=True)
    M0 = reg.copy()
    M0[lin.n + 3] = row
    s0, l0 = np.linalg.slogdet(M0)
    s1, l1 = np.linalg.slogdet(reg)
    if s0 == 0:
        return 0.0, None
    if s1 == 0:
        return np.inf, None
    ratio = float(np.real(s1 / s0)) * np.exp(l1 - l0)
    slow = None
    if ratio < 0:
        slow = 4.0 * np.exp(-2.0 * np.euler_gamma) * np.exp(max(2.0 * ratio, -745.0))
    return float(np.exp(l0 - l1)), slow


def _check_region(b_min, modulus_bound):
    b_min = check_positive("b_min", b_min)
    modulus_bound = check_positive("modulus_bound", modulus_bound)
    if not modulus_bound > 10.0 * b_min:
        raise InputError(f"modulus_bound must exceed 10 b_min = {10 * b_min:g}, got "
                         f"{modulus_bound!r}", parameters=("modulus_bound",))
    return b_min, modulus_bound


def stability_of(solve_at, *, n=STABILITY_N, b_min=B_MIN, modulus_bound=MODULUS_BOUND,
                 rate_unit=None, progress=None, guesses=(), predictions=(), samples=(),
                 estimate=True) -> StabilityResult:
    """The eigenvalues of a steady single patch with ``Re b >= b_min``, counted.

    Parameters
    ----------
    solve_at : callable
        ``solve_at(n)``: the steady solution at ``n`` unknowns per function.
    n : int
        The stability analysis' ``n`` (even, from 8 to 64); the error estimate compares
        with ``3n/2`` (``n/2`` above 32).
    b_min : float
        The smallest growth rate counted, ``k2/Delta^2`` (> 0: ``b = 0`` is the branch
        point of the stationary half-plane's kernels).
    modulus_bound : float
        ``R``: the region is ``Re b >= b_min``, ``|b| <= R`` (> 10 b_min; derivation
        S11: a mode beyond it has a thermal layer thinner than ``Delta/sqrt(R)``).
    rate_unit : float, optional
        ``k2/Delta^2`` in 1/s: the eigenvalues and the region are reported in 1/s.
    progress : callable, optional
        ``progress(done, total)`` over the evaluations of ``M(b)`` (``total`` an
        estimate).
    guesses : sequence of complex, optional
        Where the eigenvalues are expected (``k2/Delta^2``): a neighbouring contact's,
        continued along a path or across a map.  A real one starts the bracket of a
        single real eigenvalue on the grid of real rates (:func:`_real_root`);
        otherwise the half-disc of Beyn's method is sought from the one that holds them
        with a margin.  Where they miss, the search is the one
        without them.  They change neither the count (the certificate) nor, beyond
        Newton's tolerance, the eigenvalues.
    predictions : sequence of complex, optional
        A real eigenvalue predicted here (``k2/Delta^2``; extrapolated from two
        neighbours' along a map's row): where one root is counted, its bracket on the
        grid of real rates starts there (before a guess).  It changes neither the
        count nor, beyond the secant method's tolerance, the eigenvalue.
    samples : sequence of complex, optional
        A neighbouring contact's ``samples`` (its result's, ``k2/Delta^2``): those on
        this region's boundary are evaluated first, together, and the count's
        refinement finds them kept (a map's row, whose points share the kernels and
        mostly the samples).  They change neither the count nor the eigenvalues.
    estimate : bool
        Compute the error estimate (the eigenvalues again at ``3n/2``); without it
        ``error_estimate`` is None and the reason does not say whether an eigenvalue
        is resolved (for a map, whose fields do not hold either).

    Returns
    -------
    StabilityResult
    """
    n = check_integer("n", n, 8, 64)
    if n % 2:
        raise InputError(f"n must be an even integer in [8, 64], got {n!r}",
                         parameters=("n",))
    b_min, R = _check_region(b_min, modulus_bound)
    lin = linearised(solve_at(n))
    scaled, scaled_many = scaled_matrix(lin), scaled_matrix(lin, many=True)
    evaluations = [0]
    # The first steps as the single patch's per n temperature rows scaled (a contact
    # set's zones, S22): their phase turns as many times faster along the line; and
    # shorter above n = 16, where what settled() leaves still turns faster with n.
    line_step = (_LINE_STEP * min(1.0, _LINE_STEP_N / n)
                 / max(1, round(len(lin.temperature_rows) / lin.n)))
    expected = int(np.ceil(np.arcsinh(R / b_min) / line_step)) + _ARC_STEPS + 16

    def told(count):
        for _ in range(count):
            evaluations[0] += 1
            if progress is not None:
                progress(evaluations[0], max(expected, evaluations[0]))

    # The rates at which M was evaluated: the error estimate starts from Newton's last.
    taken = []

    def counted(b):
        told(1)
        taken.append(complex(b))
        return scaled(b)

    def counted_many(rates):
        told(len(rates))
        taken.extend(complex(b) for b in rates)
        return scaled_many(rates)

    winding = Winding(counted, b_min, prepare=getattr(lin, "prepare", None),
                      line_step=line_step,
                      many=counted_many if hasattr(lin, "matrices") else None,
                      ratios=_step_control(lin, samples))
    if len(samples):
        winding.evaluate([z for part in winding.boundary(R, map(complex, samples))
                          for z in part])
    N, reason = winding.count(R)
    sampled = tuple(complex(z) for part in winding.boundary(R, winding.values) for z in part)
    found = np.array([], dtype=complex)
    change = None
    if N:
        found, reason = _locate(winding, counted, N, b_min, R, guesses, predictions)
        if found.size and estimate:
            # The error at n: the change to a finer n (the change to n/2 overstates it
            # many times: the eigenvalues converge faster than any fixed order).
            other = linearised(solve_at(2 * ((3 * n // 2 + 1) // 2) if n <= 32 else n // 2))
            # Newton's method there from b, to a step of ESTIMATE_TOL (finer for a pair
            # near the real axis, whose conjugate is the nearest root), from the last
            # two rates taken at n next to b where there are (their kernels' values
            # kept: no new rate for the first step).
            changes = []
            for b in found:
                start, previous = _estimate_start(b, taken)
                tol = ESTIMATE_TOL * (min(1.0, 2.0 * abs(b.imag) / max(1.0, abs(b)))
                                      if b.imag else 1.0)
                root = newton(other.matrix, start, floor=0.5 * b_min, tol=tol,
                              prepare=getattr(other, "prepare", None), previous=previous)[0]
                changes.append(abs(root - b) / max(1.0, abs(b)))
            change = max(changes)
    fold, slow = _fold(lin)
    if slow is not None and slow >= b_min:
        slow = None     # counted, if anywhere
    # Both members of each complex pair, largest real part first.
    full = []
    for b in found:
        full.append(complex(b.real, abs(b.imag)))
        if abs(b.imag) > 1e-9 * max(1.0, abs(b)):
            full.append(complex(b.real, -abs(b.imag)))
    full = np.array(sorted(full, key=lambda b: (-b.real, -b.imag)), dtype=complex)
    if N is not None and len(full) != N:
        reason = reason or f"{len(full)} of the {N} eigenvalues counted were located"
    if change is not None and change > UNRESOLVED:
        reason = ((reason + "; ") if reason else "") + (
            f"an eigenvalue changes by {change:.2g} of itself from n = {n} to a finer n: "
            "not resolved at this n (the count is this n's)")
    units, region = lin.RATE_UNITS, (b_min, R)
    if rate_unit is not None:
        full = full * rate_unit
        region = tuple(x * rate_unit for x in region)
        slow = None if slow is None else slow * rate_unit
        units = "1/s"
    return StabilityResult(
        eigenvalues=full, unstable_modes=N, stable=None if N is None else N == 0,
        reason=reason, growth_rate=float(full.real.max()) if full.size else None,
        region=tuple(float(x) for x in region),
        count_method=COUNT_METHOD_STEPS if winding.ratios is True else COUNT_METHOD,
        error_estimate=change, fold=fold, slow_root=slow,
        evaluations=evaluations[0], n=n, units=units, samples=sampled)


def _estimate_start(b, taken):
    """``(start, previous)`` of the error estimate's Newton method at the finer ``n``
    for the root ``b`` (:func:`newton`): the rate taken at ``n`` nearest ``b`` and the
    next nearest, where both lie within ``1e-6 max(1, |b|)`` of ``b`` and ``1e-12
    max(1, |b|)`` or more apart (the last iterates of the method that confirmed ``b``:
    their divided difference is then as close to ``M'`` as the forward difference of
    step ``1e-6 |b|``, and its rounding below ``1e-4`` of it); otherwise ``(b, None)``
    (the forward difference)."""
    scale = max(1.0, abs(b))
    near = sorted((z for z in set(taken) if abs(z - b) <= 1e-6 * scale),
                  key=lambda z: abs(z - b))
    if len(near) >= 2:
        for z in near[1:]:
            if abs(z - near[0]) >= 1e-12 * scale:
                return near[0], z
    return b, None


#: Real rates per octave of the grid ``b = 2^(k/4)`` on which a single real root is
#: bracketed: the same grid for every contact, so that the points of a map's row, which
#: share the kernels at a rate (:data:`~thermocontact.discretisation.linearised.KERNEL_MOMENTS`),
#: find most of it kept.
_GRID = 4
#: ``2^(j/4)``, ``j = 0 ... 3``: the grid's rates ``2^(k/4)`` as exact binary numbers.
_MANTISSAS = tuple(2.0 ** (j / _GRID) for j in range(_GRID))
#: Grid points of the polynomial interpolating ``det M`` around a bracket (degree 7:
#: its root and slope start the secant method close enough that two steps, one
#: evaluation of ``M`` each, mostly confirm the root; a map's row of 200 points took
#: 3.5 evaluations at new rates a root with 4 points an octave and 8 here, 5.3 with 8 and
#: 4).
_STENCIL = 8


def _real_root(winding, b_min, R, starts=(), *, tol=1e-11):
    """The real root of ``det M`` in ``[b_min, R]``, where its sign changes once (one
    root counted: derivation S13, *Locating the roots*).

    The sign of ``det M`` at the grid's rates ``2^(k/4)`` (exact binary numbers, the same
    on every machine) brackets it: from ``starts[0]`` (the grid point nearest, then steps
    of 1, 2, 4, ... points toward the sign change), else from the whole region, then by
    bisection of the grid's indices (the region's ends ``b_min`` and ``R`` themselves, whose
    signs the count kept, standing for the points beyond them).  The polynomial through
    ``det M`` at the :data:`_STENCIL` grid points around the bracket, in ``x = ln b``,
    gives the estimate (its root in the bracket and the region) and the first slope; the
    secant method on ``det M(e^x)`` from it
    (:func:`~thermocontact.numerics.continuation.secant`, each step one evaluation of
    ``M`` at a new rate, its iterates kept within the stencil and the region) converges
    to the root: its last step, proposed and not evaluated as Newton's method's, is
    ``tol max(1, |ln b|)`` of ``b`` or less.

    Returns
    -------
    root, step, estimate
        The root, a bound on its last step (``|b|``'s) and the polynomial's estimate;
        ``None, inf, estimate`` where the secant method leaves the bracket or does not
        converge; ``None, inf, None`` where the signs at the ends agree, the grid holds
        no point of the region, ``det M`` is not finite at the stencil or the polynomial
        has no root in the bracket.
    """
    first, last = int(np.ceil(_GRID * np.log2(b_min))), int(np.floor(_GRID * np.log2(R)))

    def grid(k):
        return float(np.ldexp(_MANTISSAS[k % _GRID], k // _GRID))

    def rate(k):
        return b_min if k < first else (R if k > last else grid(k))

    def negative(k):
        return float(np.real(winding.at(complex(rate(k), 0.0))[0])) < 0.0
    low, high = first - 1, last + 1
    below = negative(low)
    if first > last or negative(high) == below:
        return None, np.inf, None
    if len(starts):
        k = int(np.clip(np.rint(_GRID * np.log2(starts[0])), first, last))
        up = negative(k) == below
        low, high = (k, high) if up else (low, k)
        step = 1
        while high - low > 1:
            j = k + step if up else k - step
            if not low < j < high:
                break
            same = negative(j) == below
            low, high = (j, high) if same else (low, j)
            if same != up:
                break
            step *= 2
    while high - low > 1:
        mid = (low + high) // 2
        low, high = (mid, high) if negative(mid) == below else (low, mid)
    # The polynomial in x through det M at the grid points around the bracket (beyond
    # the region's ends too: every b > 0 is on the sheet), relative to the largest.
    rates = [grid(k) for k in range(low - _STENCIL // 2 + 1, low + _STENCIL // 2 + 1)]
    winding.evaluate([complex(b, 0.0) for b in rates])     # together: one product
    values = [winding.at(complex(b, 0.0)) for b in rates]
    ref = max(v[1] for v in values)
    f = np.array([float(np.real(sg)) * np.exp(v - ref) for sg, v in values])
    if not np.all(np.isfinite(f)):
        return None, np.inf, None
    x = np.log(rates)
    poly = np.polynomial.Polynomial.fit(x, f, _STENCIL - 1)
    # The bracket within the region, widened by a few ulps (a root on a grid point).
    lo = max(np.log(rate(low)), np.log(b_min))
    hi = min(np.log(rate(high)), np.log(R))
    margin = 8 * np.finfo(float).eps * max(1.0, abs(lo), abs(hi))
    inside = [r.real for r in poly.roots() if abs(r.imag) <= 1e-12
              and lo - margin <= r.real <= hi + margin]
    if not inside:
        return None, np.inf, None
    x0 = min(max(inside[0], lo), hi)
    estimate = float(np.exp(x0))

    def value(x):
        sg, v = winding.at(complex(np.exp(x), 0.0))
        return float(np.real(sg)) * np.exp(np.clip(v - ref, -700.0, 700.0))
    found = secant(value, x0, float(poly.deriv()(x0)), max(x[0], np.log(b_min)),
                   min(x[-1], np.log(R)), xtol=tol, proposed=True)
    if found is None:
        return None, np.inf, estimate
    root = float(np.exp(found[0]))
    return root, root * tol * max(1.0, abs(found[0])), estimate


def _step_control(lin, samples):
    """How the count confirms a step (:class:`Winding`'s ``ratios``): a contact set's
    always by the eigenvalues of ``M(a)^-1 M(b)`` (S25: its many rows' turns alias
    otherwise); a single patch's by its phase, and by the eigenvalues only where the phase
    does not confirm it ("refine": a cut step costs new rates, 5-10 ms each, and the
    eigenvalues about 1 ms a step, three decompositions of 0.3 ms) unless a neighbour's
    samples are given, whose refinements the row's kernels keep: a cut step then costs
    an assembly and a determinant (0.1 ms), and the phase alone is cheaper (a 200 x 200
    map 250 s against 320 s with the eigenvalues)."""
    if isinstance(lin, LinearisedContactSet):
        return True
    return False if len(samples) else "refine"


def _locate(winding, matrix, N, b_min, R, guesses=(), predictions=()):
    """The ``N`` roots counted, with ``Im b >= 0`` (one of each pair).  A single root is
    real (the region is symmetric about the real axis), where ``det M`` changes sign
    between ``b_min`` and ``R``: bracketed on the grid of real rates and found by the
    secant method there (:func:`_real_root`), from a prediction or a real guess (a
    neighbour's root) where one is given; Newton's method from its estimate where the
    secant method does not converge.  Otherwise the smallest half-disc ``|b| <= R_j``
    (``R_j = 4^j``: ``j`` doubled from 1, or from the one that holds the guesses with a
    margin, then bisected, the count growing with the radius) holding all ``N`` by the
    same count (with guesses, the first that holds them); Beyn's method on
    the samples the count took (trapezoidal weights), then on a Gauss-Legendre rule of
    that boundary where Newton's method does not confirm all of them from the first
    estimates.  Newton's method confirms each, kept on the sheet."""
    roots = []

    def confirm(estimates):
        for b in estimates:
            if b.imag < -1e-9 * max(1.0, abs(b)):
                continue    # its conjugate is among them
            root, step = newton(matrix, b, floor=0.5 * b_min, prepare=winding.prepare)
            if not np.isfinite(step) or step > 1e-8 * max(1.0, abs(root)):
                continue
            if root.real < b_min or abs(root) > R:
                continue
            root = (complex(root.real, abs(root.imag)) if abs(root.imag) > 1e-9 *
                    max(1.0, abs(root)) else complex(root.real, 0.0))
            if any(abs(root - q) <= 1e-6 * max(1.0, abs(q)) for q in roots):
                continue
            roots.append(root)

    def located():
        return sum(1 if q.imag == 0 else 2 for q in roots)

    good = [complex(g) for g in guesses if np.isfinite(g) and g.real >= b_min and abs(g) <= R]
    if N == 1:
        # One real root: bracketed on the grid of real rates, from a predicted root
        # (continued from two neighbours along a map's row) or a real guess (a
        # neighbour's root) where one is given.
        starts = [p.real for p in predictions
                  if np.isfinite(p) and b_min <= p.real <= R and p.imag == 0]
        starts += [g.real for g in good if abs(g.imag) <= 1e-9 * abs(g)]
        root, step, estimate = _real_root(winding, b_min, R, starts[:1])
        if root is not None and step <= 1e-8 * max(1.0, root) and b_min <= root <= R:
            roots.append(complex(root, 0.0))
            return np.array(roots, dtype=complex), None
        if estimate is not None:
            confirm([complex(estimate, 0.0)])
            if located() == N:
                return np.array(roots, dtype=complex), None
    top = int(np.ceil(np.log(R) / np.log(4.0)))

    def holds(j):
        r = 4.0 ** j
        return r >= R or (r > 10.0 * b_min and winding.count(r)[0] == N)
    # Doubling j from 1 (most roots lie at small |b|), or from the half-disc that holds
    # the guesses with a margin, then bisection in the bracket.
    low, high = 0, 1
    if good:
        high = int(np.clip(np.ceil(np.log(1.5 * max(abs(g) for g in good)) / np.log(4.0)),
                           1, top))
        if holds(high):
            low = high - 1      # holds: taken, though a smaller one might hold them too
        else:
            low, high = high, min(2 * high, top)
    while high < top and not holds(high):
        low, high = high, min(2 * high, top)
    while high - low > 1:
        mid = (low + high) // 2
        if holds(mid):
            high = mid
        else:
            low = mid
    radius = min(4.0 ** high, R)
    stored = winding.matrices
    confirm(beyn(lambda b: stored[b], winding.contour(radius), rank=N, probes=N + 4)[0])
    if located() < N:
        rule = half_disc(b_min, radius)
        if winding.prepare is not None:
            winding.prepare(list(rule[0]))
        confirm(beyn(matrix, rule, rank=N, probes=N + 4)[0])
    return np.array(roots, dtype=complex), None
