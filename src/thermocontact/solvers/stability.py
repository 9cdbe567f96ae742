"""Eigenvalues of a steady single patch: is it stable?

The contact linearised about a steady solution at fixed load is ``M(b) c = 0``
(:class:`~thermocontact.discretisation.linearised.LinearisedContact`, derivation
section 18), a nonlinear eigenproblem in the rate ``b`` (units ``k2/Delta^2``).  Its
eigenvalues in a region of the right half-plane are found by Beyn's contour-integral
method (:func:`beyn`) and each is checked by Newton's method on ``det M`` (the trace
formula, :func:`newton`), the second method; the error estimate is the change of the
eigenvalues between ``n`` and ``n/2``.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..discretisation.linearised import LinearisedContact
from ..io.results import Result
from ..problem.validation import InputError, check_integer, check_positive

__all__ = ["StabilityResult", "beyn", "inside", "linearised", "newton", "stability_of"]

#: Unknowns per function of the stability analysis (its own discretisation: the cost
#: of ``M(b)`` grows with ``n`` and with the number of contour points).
STABILITY_N = 12


@dataclass(frozen=True, eq=False, repr=False)
class StabilityResult(Result):
    """The eigenvalues of a steady single patch in a region of the right half-plane.

    Attributes
    ----------
    eigenvalues : ndarray of complex
        Largest real part first; one of each conjugate pair with its partner
        (``M(conj b) = conj M(b)``).  In units of ``k2/Delta^2``, or 1/s where
        ``rate_unit`` (``k2/Delta^2`` in 1/s) was given.
    stable : bool
        No eigenvalue in the region (``Re b > re_min``, ``|b|`` within the
        ellipse ``region``).
    error_estimate : float or None
        The largest change of an eigenvalue between ``n`` and ``n/2`` (relative to
        ``max(|b|, 1)``), None where there is none to compare.
    newton_change : float or None
        The largest change when Newton's method polishes Beyn's estimates (the second
        method), relative as above.
    region : tuple
        ``(re_min, re_max, im_max)`` of the ellipse searched, in the units of the
        eigenvalues.
    n : int
    units : str
    """

    eigenvalues: np.ndarray
    stable: bool
    error_estimate: float | None
    newton_change: float | None
    region: tuple
    n: int
    units: str = "k2/Delta^2"

    def _summary(self):
        lead = (f"{self.eigenvalues[0]:.4g}" if len(self.eigenvalues) else "none")
        return f"stable={self.stable}, largest={lead}, units={self.units!r}"

    def _record(self):
        est = self.error_estimate
        return {"stable": bool(self.stable),
                "eigenvalues": [[float(b.real), float(b.imag)] for b in self.eigenvalues],
                "error_estimate": None if est is None else float(est),
                "newton_change": (None if self.newton_change is None
                                  else float(self.newton_change)),
                "region": {"re_min": self.region[0], "re_max": self.region[1],
                           "im_max": self.region[2]},
                "n": self.n, "units": self.units}


def linearised(solution) -> LinearisedContact:
    """The linearised contact about a :class:`~.result.ContactSolution`."""
    if solution.conductance is not None:
        raise InputError("stability: an interface conductance is not supported; solve "
                         "with perfect thermal contact", parameters=("conductance",))
    return LinearisedContact(solution.parameters, solution.representation, solution.phi,
                             solution.psi, solution.load_ratio, solution.sigma_over_delta)


def ellipse(re_min, re_max, im_max, points):
    """Contour points in the upper half (``theta`` in ``(0, pi)``) of the ellipse with
    real extent ``[re_min, re_max]`` and imaginary extent ``[-im_max, im_max]``, and
    ``dz/dtheta`` there; the lower half is their conjugate."""
    centre, a = 0.5 * (re_min + re_max), 0.5 * (re_max - re_min)
    theta = 2.0 * np.pi * (np.arange(points // 2) + 0.5) / points
    return centre + a * np.cos(theta) + 1j * im_max * np.sin(theta), \
        -a * np.sin(theta) + 1j * im_max * np.cos(theta)


def beyn(matrix, region, *, points=32, probes=8, tol=1e-5, seed=0, progress=None):
    """Eigenvalues of ``M(b) c = 0`` inside an ellipse by Beyn's method (Beyn 2012,
    algorithm 1).

    ``A_k = (1/2 pi i) oint b^k M(b)^{-1} V db`` by the trapezoidal rule on the ellipse
    (exponentially convergent for ``M`` analytic in a neighbourhood of it), with a
    real probe ``V`` so that the lower half of the contour is the conjugate of the
    upper; ``A_0 = V0 S W0^H`` truncated at ``tol`` times the integrand's largest norm;
    the eigenvalues are those of ``V0^H A_1 W0 S^{-1}`` that lie inside.

    Parameters
    ----------
    matrix : callable
        ``M(b)``, a square complex matrix, analytic inside and near the ellipse.
    region : tuple
        ``(re_min, re_max, im_max)``.
    points : int
        Contour points (even; ``points/2`` evaluations of ``M``).
    progress : callable, optional
        ``progress(done, total)`` after each evaluation of ``M``.
    probes : int
        Columns of ``V``: at least the number of eigenvalues inside.

    Returns
    -------
    eigenvalues : ndarray
    rank : int
        The rank of ``A_0`` found (``== probes`` means there may be more).
    """
    z, dz = ellipse(*region, points)
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
        size = max(size, np.linalg.norm(X, 2))
    # The lower half: conjugates (M(conj b) = conj M(b), V real).
    scale = (2.0 * np.pi / points) / (2j * np.pi)
    A0 = scale * (A0 - np.conj(A0))
    A1 = scale * (A1 - np.conj(A1))
    U, sv, Wh = np.linalg.svd(A0, full_matrices=False)
    # Against the integrand's own size: with no eigenvalue inside, A_0 is quadrature
    # error only (a branch point near the contour makes it converge slowly).
    k = int(np.sum(sv > tol * max(size, 1e-300)))
    if k == 0:
        return np.array([], dtype=complex), 0
    U, sv, W = U[:, :k], sv[:k], Wh[:k].conj().T
    B = U.conj().T @ A1 @ W / sv[None, :]
    lam = np.linalg.eigvals(B)
    return lam[inside(lam, region)], k


def inside(b, region):
    """Whether ``b`` lies inside the ellipse ``region = (re_min, re_max, im_max)``."""
    centre, a = 0.5 * (region[0] + region[1]), 0.5 * (region[1] - region[0])
    return ((np.real(b) - centre) / a) ** 2 + (np.imag(b) / region[2]) ** 2 < 1.0


def newton(matrix, b0, *, steps=8, tol=1e-10, h=1e-6):
    """An eigenvalue of ``M(b) c = 0`` by Newton's method on ``det M`` from ``b0``.

    ``b <- b - 1/tr(M^{-1} M')`` (the logarithmic derivative of the determinant), with
    ``M'`` by central differences of step ``h max(1, |b|)``.  Returns the last
    iterate and its last step.
    """
    b = complex(b0)
    step = np.inf
    for _ in range(steps):
        e = h * max(1.0, abs(b))
        M = matrix(b)
        dM = (matrix(b + e) - matrix(b - e)) / (2.0 * e)
        step = 1.0 / np.trace(np.linalg.solve(M, dM))
        b = b - step
        if abs(step) <= tol * max(1.0, abs(b)):
            break
    return b, abs(step)


def stability_of(solve_at, *, n=STABILITY_N, re_min=0.5, re_max=10.0, im_max=10.0,
                 points=32, rate_unit=None, polish=True, progress=None) -> StabilityResult:
    """Eigenvalues of largest real part of a steady single patch in an ellipse.

    Parameters
    ----------
    solve_at : callable
        ``solve_at(n)``: the steady solution at ``n`` unknowns per function.
    n : int
        The stability analysis' ``n`` (even, >= 8); the error estimate compares
        with ``n/2``.
    re_min, re_max, im_max : float
        The ellipse searched, in units of ``k2/Delta^2``: ``re_min > 0`` keeps it off
        the branch point ``b = 0`` of the stationary half-plane's kernels, whose
        distance from the contour sets the trapezoidal rule's convergence (about
        ``exp(-0.45 points)`` of the integrand's size for the default ellipse).
    points : int
        Contour points.
    rate_unit : float, optional
        ``k2/Delta^2`` in 1/s: the eigenvalues and the region are reported in 1/s.
    polish : bool
        Check each eigenvalue by Newton's method (the second method).
    progress : callable, optional
        ``progress(done, total)`` over the contour points (the analysis' cost).

    Returns
    -------
    StabilityResult
    """
    n = check_integer("stability n", n, 8, 64)
    re_min = check_positive("stability re_min", re_min)
    if not re_max > re_min:
        raise InputError(f"stability re_max must exceed re_min = {re_min:g}, got {re_max!r}",
                         parameters=("re_max",))
    im_max = check_positive("stability im_max", im_max)
    points = 2 * check_integer("stability points", points // 2, 4, 256)
    region = (re_min, re_max, im_max)
    lin = linearised(solve_at(n))
    found, _ = beyn(lin.matrix, region, points=points, progress=progress)
    found = found[found.imag >= -1e-12 * np.maximum(1.0, np.abs(found))]
    change = None
    if polish and found.size:
        # The second method: Newton's from each estimate; an estimate it does not
        # confirm (no convergence, or a root outside the region) is dropped.
        kept, changes = [], []
        for b in found:
            p, step = newton(lin.matrix, b)
            if step <= 1e-8 * max(1.0, abs(p)) and inside(p, region):
                kept.append(p)
                changes.append(abs(p - b) / max(1.0, abs(p)))
        change = max(changes) if changes else None
        found = np.array(kept, dtype=complex)
    estimate = None
    if found.size:
        coarse = linearised(solve_at(n // 2))
        estimate = max(abs(newton(coarse.matrix, b)[0] - b) / max(1.0, abs(b)) for b in found)
    # Both members of each complex pair, largest real part first.
    full = []
    for b in found:
        full.append(complex(b.real, abs(b.imag)))
        if abs(b.imag) > 1e-12 * max(1.0, abs(b)):
            full.append(complex(b.real, -abs(b.imag)))
    full = np.array(sorted(full, key=lambda b: (-b.real, -b.imag)), dtype=complex)
    units = "k2/Delta^2"
    if rate_unit is not None:
        full = full * rate_unit
        region = tuple(x * rate_unit for x in region)
        units = "1/s"
    return StabilityResult(eigenvalues=full, stable=not bool(np.any(full.real > 0.0)),
                           error_estimate=estimate, newton_change=change,
                           region=tuple(float(x) for x in region), n=n, units=units)
