"""Solve the coupled contact and heat equations for one set of parameters.

Two ways to close the problem (derivation section 5):

* ``lam`` given: the unknowns are ``phi``, ``psi``, ``L sigma`` and ``L``.  The
  equations are linear in all of them, so the heat partition is met exactly in one
  solve; ``sigma = (L sigma)/L``.  The partition at which ``L`` vanishes is reached
  by no finite ``sigma`` and is refused.
* ``sigma_over_delta`` given: the unknowns are ``phi``, ``psi`` and ``L``; ``lam``
  follows from the heat flux.  With ``fhpe = 0`` this problem has no bounded
  solution unless ``sigma = 0``, and then ``lam`` is undetermined: refused.
"""

from __future__ import annotations

from dataclasses import dataclass, field, replace
from functools import lru_cache

import numpy as np
from scipy.linalg import LinAlgError, lu_factor, lu_solve
from scipy.linalg.lapack import dgecon

from ..discretisation.system import AUTO_RANGE, METHODS, Blocks
from ..problem.parameters import InputError, Parameters, SolveError, check_finite, check_positive
from ..analysis.validity import Validity, assess, gap

__all__ = [
    "ContactSolution",
    "DEFAULT_METHOD",
    "DEFAULT_TOL",
    "N_AUTO_MAX",
    "N_RANGE",
    "RCOND_MIN",
    "error_estimate",
    "solve",
    "solve_blocks",
]

#: Default method and error target.
DEFAULT_METHOD = "graded"
DEFAULT_TOL = 1e-8
N_RANGE = (4, 2048)
#: Automatic choice of n doubles from N_AUTO_START up to N_AUTO_MAX (the
#: Chebyshev and paper methods; each method's range is in ``assembly.AUTO_RANGE``).
N_AUTO_START = 16
N_AUTO_MAX = 1024
#: Bound on |lam| and |sigma/Delta|: far beyond any physical heat partition or offset.
LIMIT = 1e6
#: Largest convergence order the error estimate believes: just above the
#: asymptotic order 4 of the Chebyshev methods (derivation section 10).  The graded
#: methods converge faster once they resolve the edges, but before that (Pe k2/k1
#: large, n small) a sudden drop of the differences must not be read as a high
#: order: the same cap keeps their estimate an upper bound (section 12).
P_MAX = 5.0
#: Systems whose reciprocal 1-norm condition number is below this are refused.
RCOND_MIN = 1e-12


@dataclass(frozen=True)
class ContactSolution:
    """One solution of the sliding-contact problem, in dimensionless form.

    Attributes
    ----------
    parameters : Parameters
    method : str
        Discretisation method, a key of :data:`~thermocontact.assembly.METHODS`.
    n : int
        Unknowns per function.
    load_ratio : float
        ``P_H/P``: the Hertz load for the same half-width over the actual load.
    lam : float
        Heat partition ``(Q1 - Q2)/(Q1 + Q2)``.
    sigma_over_delta : float
        Offset of the contact centre from the cylinder's initial point of contact,
        in half-widths, positive toward the leading edge (``+x``).
    eta : float
        ``(1 - K2/K1)/(1 + K2/K1)``.
    s, pressure : ndarray
        Nodes in ``[-1, 1]`` (edges included) and the contact pressure there,
        normalised to unit integral and positive in compression.
    flux_s : ndarray
        Nodes of the heat-flux distributions (interior; they are singular at the
        edges).
    flux_difference, flux_cylinder, flux_half_plane : ndarray
        ``q = q1 - q2``, ``q1`` and ``q2`` at ``flux_s``, in units of
        ``f v P / Delta`` so that ``q1 + q2`` is the pressure and the integral of
        ``q`` is ``lam``.
    validity : Validity
    rcond : float
        Reciprocal condition number (1-norm) of the linear system.
    load_ratio_change : float or None
        ``|P_H/P(2n) - P_H/P(n)|`` when a convergence check was asked for.
    error_estimate : float or None
        Estimated relative error of ``P_H/P`` and ``sigma/Delta`` (the larger),
        see :func:`error_estimate`.
    converged : bool or None
        ``error_estimate <= tol``.
    auto_n : bool
        Whether ``n`` was chosen automatically.
    tol : float or None
        The error target.
    """

    parameters: Parameters
    method: str
    n: int
    load_ratio: float
    lam: float
    sigma_over_delta: float
    eta: float
    s: np.ndarray
    pressure: np.ndarray
    flux_s: np.ndarray
    flux_difference: np.ndarray
    flux_cylinder: np.ndarray
    flux_half_plane: np.ndarray
    validity: Validity
    rcond: float
    load_ratio_change: float | None = None
    error_estimate: float | None = None
    converged: bool | None = None
    auto_n: bool = False
    tol: float | None = None
    blocks: Blocks = field(default=None, repr=False, compare=False)
    phi: np.ndarray = field(default=None, repr=False, compare=False)
    psi: np.ndarray = field(default=None, repr=False, compare=False)

    @property
    def valid(self) -> bool:
        """Whether every contact inequality holds (see :class:`Validity`)."""
        if self.validity is None:
            raise ValueError("validity was not evaluated for this solution")
        return self.validity.valid

    def pressure_at(self, s):
        """Pressure at ``s`` in ``[-1, 1]`` from the ``U``-series of ``phi``."""
        s = np.asarray(s, dtype=float)
        return np.sqrt(np.clip(1.0 - s * s, 0.0, None)) * self.blocks.basis.phi_at(self.phi, s)

    def flux_difference_at(self, s):
        """Heat-flux difference ``q = q' + eta p`` at ``s`` in ``(-1, 1)``."""
        s = np.asarray(s, dtype=float)
        psi = self.blocks.basis.psi_at(self.psi, s)
        return psi / np.sqrt(1.0 - s * s) + self.eta * self.pressure_at(s)

    def gap_at(self, s):
        """Gap at ``|s| >= 1`` in units of ``Delta^2/R`` (derivation D20-D21)."""
        g, _ = gap(self.parameters, self.blocks, self.phi, self.psi, self.load_ratio,
                   self.sigma_over_delta, self.lam, s)
        return g


def _factor(A):
    try:
        lu = lu_factor(A, check_finite=True)
    except (LinAlgError, ValueError) as exc:
        raise SolveError(f"the linear system could not be factorised ({exc})") from None
    rcond, info = dgecon(lu[0], np.linalg.norm(A, 1), norm="1")
    if info != 0 or not np.isfinite(rcond) or rcond < RCOND_MIN:
        raise SolveError(
            f"the linear system is singular or ill-conditioned (reciprocal condition "
            f"number {rcond:.1e} < {RCOND_MIN:.0e}); these parameters have no "
            f"well-determined solution"
        )
    return lu, float(rcond)


def solve_blocks(par: Parameters, blocks: Blocks, method: str, *, lam=None,
                 sigma_over_delta=None, check_validity=True) -> ContactSolution:
    """Solve the assembled system for one ``fhpe`` and one of ``lam``/``sigma``.

    Parameters
    ----------
    par : Parameters
    blocks : Blocks
        From ``METHODS[method](par, n)``; reusable across ``fhpe``, ``lam``,
        ``sigma``.
    method : str
    lam, sigma_over_delta : float
        Exactly one of them.
    check_validity : bool, optional
        Evaluate the contact inequalities (default); without, ``validity`` is
        None (for scans that need only ``P_H/P``).

    Returns
    -------
    ContactSolution

    Raises
    ------
    InputError
        Both or neither of ``lam`` and ``sigma_over_delta``; or ``sigma`` given
        with ``fhpe = 0``.
    SolveError
        A singular or ill-conditioned system, or a ``lam`` that no finite
        ``sigma`` reaches.
    """
    if (lam is None) == (sigma_over_delta is None):
        raise InputError("give exactly one of lam and sigma_over_delta")
    n = blocks.n
    F = par.fhpe
    pr, fr = blocks.pressure_rule, blocks.flux_rule
    eta = par.eta
    sk = blocks.contact_points if blocks.linear_column is None else blocks.linear_column
    one = np.ones(n + 1) if blocks.const_column is None else blocks.const_column
    np1, nm1 = n + 1, n - 1
    two_pi = 2.0 / np.pi

    if lam is not None:
        lam = check_finite("lam", lam)
        if abs(lam) > LIMIT:
            raise InputError(f"lam must be in [-{LIMIT:.0e}, {LIMIT:.0e}], got {lam!r}")
        size = 2 * n + 2
    else:
        sigma = check_finite("sigma_over_delta", sigma_over_delta)
        if abs(sigma) > LIMIT:
            raise InputError(f"sigma_over_delta must be in [-{LIMIT:.0e}, {LIMIT:.0e}], got {sigma!r}")
        if F == 0.0:
            raise InputError(
                "sigma_over_delta cannot be imposed when fhpe = 0: without thermal "
                "coupling the contact is Hertzian, a bounded solution needs "
                "sigma_over_delta = 0 and then lam is undetermined; give lam instead"
            )
        size = 2 * n + 1

    A = np.zeros((size, size))
    b = np.zeros(size)
    A[:np1, :n] = blocks.C - F * blocks.Tp
    A[:np1, n:2 * n] = -F * blocks.Tq
    A[np1, :n] = pr.weights
    b[np1] = 1.0
    A[np1 + 1:np1 + 1 + nm1, :n] = blocks.Hp
    A[np1 + 1:np1 + 1 + nm1, n:2 * n] = blocks.Hq
    if lam is not None:
        A[2 * n + 1, n:2 * n] = fr.weights
        b[2 * n + 1] = lam - eta
        A[:np1, 2 * n] = -two_pi * one
        A[:np1, 2 * n + 1] = -two_pi * sk
    else:
        A[:np1, 2 * n] = -two_pi * (sigma * one + sk)

    # Equilibrate the rows: the heat equation's rows next to an edge grow like
    # n^3 in the graded representation, which would mask the condition number.
    scale = 1.0 / np.maximum(np.abs(A).max(axis=1), np.finfo(float).tiny)
    A *= scale[:, None]
    b *= scale
    lu, rcond = _factor(A)
    x = lu_solve(lu, b)
    phi, psi = x[:n], x[n:2 * n]
    if lam is not None:
        L_sigma, L = x[2 * n], x[2 * n + 1]
        if abs(L) <= 1e-12 * max(1.0, abs(L_sigma)):
            raise SolveError(
                f"lam = {lam:g} is reached by no finite sigma_over_delta (it is the "
                f"limit of lam as sigma_over_delta -> +-infinity); choose another lam"
            )
        sigma = L_sigma / L
    else:
        L = x[2 * n]
        lam = float(fr.weights @ psi + eta * (pr.weights @ phi))
    if not np.all(np.isfinite(x)):
        raise SolveError("the linear solve produced non-finite values")

    validity = assess(par, blocks, phi, psi, L, sigma, lam) if check_validity else None
    p_nodes = pr.edge_factor * phi
    if fr.nodes is pr.nodes:
        p_at_flux = p_nodes
    else:
        p_at_flux = fr.edge_factor * blocks.basis.phi_at(phi, fr.nodes)
    q = psi / fr.edge_factor + eta * p_at_flux
    return ContactSolution(
        parameters=par,
        method=method,
        n=n,
        load_ratio=float(L),
        lam=float(lam),
        sigma_over_delta=float(sigma),
        eta=eta,
        s=np.concatenate([[-1.0], pr.nodes, [1.0]]),
        pressure=np.concatenate([[0.0], p_nodes, [0.0]]),
        flux_s=fr.nodes.copy(),
        flux_difference=q,
        flux_cylinder=0.5 * (p_at_flux + q),
        flux_half_plane=0.5 * (p_at_flux - q),
        validity=validity,
        rcond=rcond,
        blocks=blocks,
        phi=phi,
        psi=psi,
    )


def check_n(n) -> int:
    """Return ``n`` as an int, or raise :class:`InputError` outside :data:`N_RANGE`."""
    lo, hi = N_RANGE
    if isinstance(n, bool) or not isinstance(n, (int, np.integer)):
        if isinstance(n, float) and n.is_integer():
            n = int(n)
        else:
            raise InputError(f"n must be an integer in [{lo}, {hi}], got {n!r}")
    if not lo <= n <= hi:
        raise InputError(f"n must be an integer in [{lo}, {hi}], got {n!r}")
    return int(n)


@lru_cache(maxsize=8)
def _assembled(method: str, pe: float, K: float, k: float, d: float, n: int) -> Blocks:
    """Assembly depends on neither fHPe, lam nor sigma: keep the last few for sweeps."""
    return METHODS[method](Parameters(pe, 0.0, K, k, d), n)


def _blocks(par: Parameters, method: str, n: int) -> Blocks:
    return _assembled(method, par.pe, par.K2_over_K1, par.k2_over_k1,
                      par.delta1_over_delta2, n)


def _relative(x: float) -> float:
    return max(abs(x), 0.01)


def error_estimate(levels, quantities=("load_ratio", "sigma_over_delta")) -> float:
    """Richardson estimate of the error of the finest of successive solutions.

    For solutions at ``n/4, n/2, n`` with differences ``d1, d2`` in ``P_H/P`` (and
    in ``sigma/Delta``), the observed order is ``p = log2(d1/d2)``, clamped to
    ``[1, 5]`` (1 also when fewer than three levels are given), and the error of
    the finest is ``d2 / (2^p - 1)``.  The cap 5 is just above the product
    method's asymptotic order (about 4, set by the edge terms of derivation
    section 8): a sudden drop of ``d2`` while the discretisation first resolves
    the cylinder's kernels must not be read as a higher order.  The estimate is the larger of the two
    quantities' errors, each relative to ``max(|value|, 0.01)``.

    Parameters
    ----------
    levels : sequence of ContactSolution
        At least two, ``n`` doubling, coarsest first.
    quantities : tuple of str
        The result fields whose errors are estimated.

    Returns
    -------
    float
    """
    est = 0.0
    for attr in quantities:
        v = [getattr(sol, attr) for sol in levels[-3:]]
        d2 = abs(v[-1] - v[-2])
        p = 1.0
        if len(v) == 3:
            d1 = abs(v[1] - v[0])
            if d1 > 0.0 and d2 > 0.0:
                p = float(np.clip(np.log2(d1 / d2), 1.0, P_MAX))
            elif d2 == 0.0:
                p = P_MAX
        est = max(est, d2 / (2.0**p - 1.0) / _relative(v[-1]))
    return est


def solve(pe, fhpe, K2_over_K1, *, k2_over_k1=None, delta1_over_delta2=1.0,
          lam=None, sigma_over_delta=None, n=None, method=DEFAULT_METHOD,
          tol=DEFAULT_TOL, check_convergence=False) -> ContactSolution:
    """Solve the steady thermoelastic sliding-contact problem.

    Parameters
    ----------
    pe : float
        ``Pe = v Delta / (2 k2) > 0``.
    fhpe : float
        ``f H Pe >= 0``.
    K2_over_K1 : float
        Conductivity ratio ``> 0``.
    k2_over_k1 : float, optional
        Diffusivity ratio ``> 0``; defaults to ``K2_over_K1``.
    delta1_over_delta2 : float, optional
        Distortivity ratio ``>= 0`` (default 1).
    lam, sigma_over_delta : float
        Exactly one: the heat partition ``(Q1 - Q2)/(Q1 + Q2)`` or the contact
        offset.
    n : int, optional
        Unknowns per function, in :data:`N_RANGE`.  By default it is chosen: ``n``
        doubles from 8 to at most 256 (graded methods) or from 16 to at most
        :data:`N_AUTO_MAX` (the others) until :func:`error_estimate` is below ``tol``
        (the largest ``n`` reached without it is reported by ``converged = False``).
    method : str, optional
        A key of :data:`~thermocontact.assembly.METHODS`: ``"graded"`` (default:
        cosine series in the edge-graded variable, every integral a moment, each
        equation projected), ``"graded-collocation"`` (the same, collocated),
        ``"galerkin"`` and ``"product"`` (Chebyshev series with exact kernel
        moments, projected or collocated) or ``"paper"`` (the paper's
        collocation, kernels sampled at nodes).
    tol : float, optional
        Target of the error estimate when ``n`` is chosen (default 1e-8).
    check_convergence : bool, optional
        Also solve with ``2n`` (``n/2`` when ``2n`` exceeds the largest ``n``) and
        report the change in ``P_H/P``.

    Returns
    -------
    ContactSolution
        With ``error_estimate`` from the solutions at ``n``, ``n/2`` and ``n/4``
        (None when ``n < 8`` leaves no coarser level).

    Raises
    ------
    InputError
        A parameter out of range (the message names it and the range).
    SolveError
        No well-determined solution of the discrete problem.

    Examples
    --------
    >>> from thermocontact import solve
    >>> round(solve(5, 0.0, 10, lam=-1).load_ratio, 12)
    1.0
    """
    par = Parameters(pe, fhpe, K2_over_K1, k2_over_k1, delta1_over_delta2)
    if not isinstance(method, str) or method not in METHODS:
        raise InputError(f"method must be one of {sorted(METHODS)}, got {method!r}")
    if (lam is None) == (sigma_over_delta is None):
        raise InputError("give exactly one of lam and sigma_over_delta")
    tol = check_positive("tol", tol)
    auto = n is None
    if not auto:
        n = check_n(n)

    def at(m):
        # Validity only for the solution returned: the coarser levels feed the
        # error estimate alone.
        return solve_blocks(par, _blocks(par, method, m), method, lam=lam,
                            sigma_over_delta=sigma_over_delta, check_validity=False)

    if auto:
        start, n_max = AUTO_RANGE[method]
        levels = [at(start), at(2 * start)]
        while True:
            est = error_estimate(levels)
            if est <= tol or levels[-1].n >= n_max:
                break
            levels.append(at(2 * levels[-1].n))
    else:
        coarse = [m for m in (n // 4, n // 2) if m >= N_RANGE[0]]
        levels = [at(m) for m in coarse] + [at(n)]
        est = error_estimate(levels) if len(levels) > 1 else None
    fin = levels[-1]
    validity = assess(par, fin.blocks, fin.phi, fin.psi, fin.load_ratio,
                      fin.sigma_over_delta, fin.lam)
    sol = replace(fin, validity=validity,
                  error_estimate=None if est is None else float(est),
                  converged=None if est is None else bool(est <= tol), auto_n=auto, tol=tol)
    if check_convergence:
        # Against 2n, or against n/2 when 2n is beyond the largest n.
        other = at(2 * sol.n if 2 * sol.n <= N_RANGE[1] else sol.n // 2)
        sol = replace(sol, load_ratio_change=abs(other.load_ratio - sol.load_ratio))
    return sol
