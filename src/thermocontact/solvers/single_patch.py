"""Solve the coupled contact and heat equations for one set of parameters.

Two ways to close the problem (derivation section 5):

* ``lam`` given: the unknowns are ``phi``, ``psi``, ``L sigma`` and ``L``.  The
  equations are linear in all of them, so the heat partition is met exactly in one
  solve; ``sigma = (L sigma)/L``.  The partition at which ``L`` vanishes is reached
  by no finite ``sigma`` and is refused.
* ``sigma_over_delta`` given: the unknowns are ``phi``, ``psi`` and ``L``; ``lam``
  follows from the heat flux.  With ``fhpe = 0`` this problem has no bounded
  solution unless ``sigma = 0``, and then ``lam`` is undetermined: refused.
* ``temperatures`` given (the bodies' far temperatures, section 17): the unknowns
  are those of ``lam`` given, the partition row becomes the temperature row (D41),
  and ``lam`` follows from the heat flux.

The system is the one-zone contact set ``(-1, 1)`` in the contact's own scaling,
assembled by :func:`~thermocontact.discretisation.system.contact_set_system` from the
cached blocks (derivation section 16); an interface conductance replaces the heat
equation by the temperature equation (D33).
"""

from __future__ import annotations

import logging
import warnings

import numpy as np

from ..analysis.validity import assess
from ..discretisation.methods import DEFAULT_METHOD, DEFAULT_TOL, METHODS
from ..discretisation.system import (SHARED_BLOCKS_N, Blocks, check_temperatures,
                                     contact_set_system)
from ..numerics.cache import BoundedCache, release_freed_memory
from ..numerics.dense import RCOND_CHOICES, solve_stack
from ..numerics.moment_engine import clear_geometry
from ..problem.closure import (CLOSURE_LIMIT, check_closure_range, closure_of, far_temperatures,
                               temperature_closure)
from ..problem.conductance import Conductance
from ..problem.parameters import ConvergenceWarning, Parameters, SolveError
from ..problem.validation import (InputError, check_callable, check_choice, check_exactly_one,
                                  check_finite, check_flag, check_integer,
                                  check_offset_coupling, check_positive)
from ..problem.vocabulary import deprecated_spellings
from .contact_system import solve_contact_system
from .grid_line import as_in, assessed_many, line_inputs, line_validities
from .refinement import N_RANGE, QUANTITIES, QUANTITIES_WITH_LAM, error_estimate, refine_each
from .result import ContactSolution

__all__ = [
    "DEFAULT_METHOD",
    "DEFAULT_TOL",
    "LIMIT",
    "Model",
    "assessed",
    "check_n",
    "solve",
    "solve_system",
]

log = logging.getLogger("thermocontact")

#: Bound on |lam| and |sigma/Delta|: far beyond any physical heat partition or offset.
LIMIT = CLOSURE_LIMIT

#: Assemblies by method, parameters and n, for every Model of this process.
ASSEMBLIES = BoundedCache("assemblies", 512 * 2**20)


#: The single patch in its own scaling: one zone from -1 to 1 (section 16).
_PATCH = np.array([[-1.0, 1.0]])


def solve_system(par: Parameters, blocks: Blocks, method: str, *, lam=None,
                 sigma_over_delta=None, check_validity=True, polish=True,
                 conductance=None, temperatures=None) -> ContactSolution:
    """Solve the assembled system for one ``fhpe`` and one closure.

    Parameters
    ----------
    par : Parameters
    blocks : Blocks
        From ``METHODS[method](par, n)``; reusable across ``fhpe``, ``lam``,
        ``sigma``.
    method : str
    lam, sigma_over_delta : float
        The heat partition or the offset.
    temperatures : Temperatures or tuple, optional
        Or the far temperatures ``(Theta, L/Delta)`` (derivation section 17); exactly
        one of the three closures.
    check_validity : bool, optional
        Evaluate the contact inequalities (default); without, ``validity`` is
        None (for scans that need only ``P_H/P``).
    polish : bool, optional
        Polish every margin's minimum on the closed forms (default), or only those
        near zero (:func:`~thermocontact.analysis.validity.assess`; maps).
    conductance : Conductance, optional
        An interface conductance with ``Bi0 = h0 Delta/K2`` (derivation section 16);
        default perfect thermal contact.

    Returns
    -------
    ContactSolution

    Raises
    ------
    InputError
        Not exactly one closure; or ``sigma`` given with ``fhpe = 0``.
    SolveError
        A singular or ill-conditioned system, or a ``lam`` (given or implied by the
        temperatures) that no finite ``sigma`` reaches.
    """
    sol = _solve_patch(par, blocks, method, lam, sigma_over_delta, conductance, {},
                       temperatures)
    return assessed(sol, polish=polish) if check_validity else sol


def assessed(sol: ContactSolution, polish=True) -> ContactSolution:
    """``sol`` with its contact inequalities evaluated
    (:func:`~thermocontact.analysis.validity.assess`): as :func:`solve_system` with
    ``check_validity=True`` gives it, for a solution solved without."""
    return assessed_many([sol], polish=polish)[0]


def _solve_patch(par: Parameters, blocks: Blocks, method: str, lam, sigma_over_delta,
                 conductance, systems: dict, temperatures=None) -> ContactSolution:
    """:func:`solve_system` without validity; ``systems`` keeps the assembled systems
    by closure for the next solve with the same blocks (they do not depend on
    ``fhpe``: a grid line assembles its system once per ``n``)."""
    out = _solve_patches([par], blocks, method, [(lam, sigma_over_delta, temperatures)],
                         conductance, systems)[0]
    if isinstance(out, Exception):
        raise out
    return out


def _patch_system(par: Parameters, blocks: Blocks, method: str, closure, conductance,
                  systems: dict):
    """The checked closure ``(lam, sigma, temperatures)`` and its assembled system
    (kept in ``systems`` by closure)."""
    lam, sigma_over_delta, temperatures = closure
    if type(lam) is float and closure in systems:
        # A heat partition checked before (a grid line's points): its checked key (the
        # stored one: 0.0 where this is -0.0).
        key = next(k for k in systems if k == closure)
        return key, systems[key]
    check_exactly_one(lam=lam, sigma_over_delta=sigma_over_delta, temperatures=temperatures)
    lam, sigma_over_delta = check_closure_range(lam, sigma_over_delta)
    if temperatures is not None:
        temperatures = check_temperatures(par, temperatures)
    elif sigma_over_delta is not None:
        check_offset_coupling(par.fhpe)
    # The one zone (-1, 1) without initial gap: its defects (mu, nu) are (L sigma, L).
    key = (lam, sigma_over_delta, temperatures)
    if key not in systems:
        systems[key] = contact_set_system(par, _PATCH, blocks.representation,
                                          METHODS[method].scheme, lam=lam,
                                          sigma_over_delta=sigma_over_delta,
                                          temperatures=temperatures, blocks=blocks,
                                          conductance=conductance is not None)
    return key, systems[key]


def _solve_patches(pars, blocks: Blocks, method: str, closures, conductance,
                   systems: dict, rcond="estimate") -> list:
    """:func:`_solve_patch` of several points of one model (``pars`` equal but for
    ``fhpe``; ``closures`` their ``(lam, sigma, temperatures)``): per point its
    solution or the :class:`InputError` or :class:`SolveError` it raises.  The points
    that share a system are solved as one stack (:func:`solve_stack`), each as
    :func:`solve_contact_system` solves it alone (``rcond``: as :func:`solve_stack`)."""
    out = [None] * len(pars)
    groups = {}
    for i, (par, closure) in enumerate(zip(pars, closures)):
        try:
            key, system = _patch_system(par, blocks, method, closure, conductance, systems)
        except (InputError, SolveError) as exc:
            out[i] = exc
            continue
        groups.setdefault(key, (system, []))[1].append(i)
    for key, (system, rows) in groups.items():
        F = np.array([pars[i].fhpe for i in rows])
        if system.local or system.shared:
            found = []
            for f in F:
                try:
                    found.append(solve_contact_system(system, float(f), blocks.representation,
                                                      [1.0], conductance, "the linear system"))
                except SolveError as exc:
                    found.append(exc)
        else:
            found = solve_stack(system, F, "the linear system", rcond)
        for i, res in zip(rows, found):
            if isinstance(res, Exception):
                out[i] = res
                continue
            try:
                out[i] = _patch_solution(pars[i], blocks, method, key, *res, conductance)
            except SolveError as exc:
                out[i] = exc
    return out


def _patch_solution(par, blocks, method, closure, x, rcond, conductance) -> ContactSolution:
    """The single patch's solution from the unknowns ``x`` of its system."""
    lam, sigma_over_delta, temperatures = closure
    n = blocks.n
    rep = blocks.representation
    pr, fr = rep.pressure_rule, rep.flux_rule
    phi, psi = x[:n], x[n:2 * n]
    if sigma_over_delta is None:
        L_sigma, L = x[2 * n], x[2 * n + 1]
        if lam is None:
            lam = float(fr.weights @ psi + par.eta * (pr.weights @ phi))
        if abs(L) <= 1e-12 * max(1.0, abs(L_sigma)):
            raise SolveError(
                f"lam = {lam:g} is reached by no finite sigma_over_delta (it is the "
                f"limit of lam as sigma_over_delta -> +-infinity); choose another lam"
                + ("" if temperatures is None else " or other temperatures"))
        sigma = L_sigma / L
    else:
        sigma = sigma_over_delta
        L = x[2 * n]
        lam = float(fr.weights @ psi + par.eta * (pr.weights @ phi))
    return ContactSolution.build(
        parameters=par, method=method, n=n, load_ratio=float(L), lam=float(lam),
        sigma_over_delta=float(sigma), phi=phi, psi=psi, representation=rep,
        validity=None, rcond=rcond, conductance=conductance,
        temperatures=temperatures)


def _raising(result):
    """``result``, or raised where it is an exception."""
    if isinstance(result, Exception):
        raise result
    return result


def check_n(n) -> int:
    """``n`` as an int in :data:`~thermocontact.solvers.refinement.N_RANGE`."""
    return check_integer("n", n, *N_RANGE)


def check_method(method) -> str:
    """``method`` if it names a registered method."""
    return check_choice("method", method, METHODS)


class Model:
    """The problem with everything fixed but ``fhpe`` and the closure: solve it many times.

    The assembly depends on ``Pe``, the ratios, the method and ``n`` only
    (derivation section 5), so each :meth:`solve` costs a linear solve once the
    blocks at its ``n`` exist.  Blocks are kept by the model while it lives and
    in a per-process cache bounded in bytes
    (:func:`thermocontact.numerics.cache.clear_caches` empties it); a pickled
    model carries its inputs only.

    Parameters
    ----------
    pe : float
        ``Pe = v Delta / (2 k2) > 0``.
    K2_over_K1 : float
        Conductivity ratio ``> 0``.
    k2_over_k1 : float, optional
        Diffusivity ratio ``> 0``; defaults to ``K2_over_K1``.
    delta1_over_delta2 : float, optional
        Distortivity ratio ``>= 0`` (default 1).
    speed_ratio : float, optional
        ``R = v2/v1``, the half-plane's surface speed through the contact over the
        cylinder's (default 0, the stationary half-plane; derivation section 5b).
    beta_f : float, optional
        ``B = beta f`` of the Dundurs term (default 0, the paper's omission; section 5c).
    conductance : tuple, optional
        ``(Bi0, m)``: an interface conductance ``h = h0 (p/p_ref)^m`` with
        ``Bi0 = h0 Delta/K2`` and ``p_ref = P/(2 Delta)`` (derivation section 16);
        default perfect thermal contact.
    method : str, optional
        A key of :data:`~thermocontact.discretisation.methods.METHODS`.
    n : int, optional
        Unknowns per function, in :data:`~thermocontact.solvers.refinement.N_RANGE`.
        By default ``n`` doubles over the method's automatic range until the
        error estimate is below ``tol``.
    tol : float, optional
        Target of the error estimate (default 1e-8).

    Examples
    --------
    >>> from thermocontact import Model
    >>> model = Model(5, 10)
    >>> [round(model.solve(f, lam=-1).load_ratio, 6) for f in (0.0, 0.2)]
    [1.0, 0.686714]
    """

    def __init__(self, pe, K2_over_K1, *, k2_over_k1=None, delta1_over_delta2=1.0,
                 speed_ratio=0.0, beta_f=0.0, method=DEFAULT_METHOD, n=None,
                 tol=DEFAULT_TOL, conductance=None):
        self.parameters = Parameters(pe, 0.0, K2_over_K1, k2_over_k1, delta1_over_delta2,
                                     speed_ratio, beta_f)
        self.conductance = Conductance.of(conductance)
        self.method = check_method(method)
        self.n = None if n is None else check_n(n)
        self.tol = check_positive("tol", tol)
        self._blocks = {}

    def __getstate__(self):
        return {"parameters": self.parameters, "method": self.method, "n": self.n,
                "tol": self.tol, "conductance": self.conductance}

    def __setstate__(self, state):
        state.setdefault("conductance", None)
        self.__dict__.update(state)
        self._blocks = {}

    def __repr__(self):
        p = self.parameters
        return (f"Model(pe={p.pe:g}, K2_over_K1={p.K2_over_K1:g}, k2_over_k1={p.k2_over_k1:g}, "
                f"delta1_over_delta2={p.delta1_over_delta2:g}, "
                + (f"speed_ratio={p.speed_ratio:g}, " if p.speed_ratio else "")
                + (f"beta_f={p.beta_f:g}, " if p.beta_f else "")
                + (f"conductance=({self.conductance.biot0:g}, {self.conductance.exponent:g}), "
                   if self.conductance is not None else "")
                + f"method={self.method!r}, "
                f"n={self.n}, tol={self.tol:g})")

    def __eq__(self, other):
        if not isinstance(other, Model):
            return NotImplemented
        return self.__getstate__() == other.__getstate__()

    __hash__ = None

    def blocks(self, n: int) -> Blocks:
        """The assembled blocks at ``n``.

        A large level (``n >= 512``) is assembled without the coarser levels' blocks
        beside it (12.5 MB at n = 1024): they are dropped from the model and the cache,
        and a coarser level asked for again is assembled again; so is the point
        geometry kept for assemblies at the coarser levels' points
        (:func:`~thermocontact.numerics.cache.release_freed_memory` too)."""
        if n not in self._blocks:
            if n >= SHARED_BLOCKS_N:
                for m in [m for m in self._blocks if m < n]:
                    del self._blocks[m]
                    ASSEMBLIES.discard(self._assembly_key(m))
                # Nor beside the point geometry the coarser levels' assemblies kept for
                # another assembly at their points (11 MB at n = 256).
                clear_geometry()
                release_freed_memory()
            p = self.parameters
            self._blocks[n] = ASSEMBLIES.get(self._assembly_key(n),
                                             lambda: METHODS[self.method].assemble(p, n))
        return self._blocks[n]

    def _assembly_key(self, n: int):
        p = self.parameters
        return (self.method, p.pe, p.K2_over_K1, p.k2_over_k1, p.delta1_over_delta2,
                p.speed_ratio, p.beta_f, n)

    def parameters_at(self, fhpe) -> Parameters:
        """The full parameters at ``fhpe``."""
        return self.parameters.with_fhpe(fhpe)

    def solve_at(self, n: int, fhpe, *, lam=None, sigma_over_delta=None,
                 check_validity=True, polish=True, temperatures=None) -> ContactSolution:
        """One solve at ``n`` without error estimate."""
        return solve_system(self.parameters_at(fhpe), self.blocks(n), self.method, lam=lam,
                            sigma_over_delta=sigma_over_delta, check_validity=check_validity,
                            polish=polish, conductance=self.conductance,
                            temperatures=temperatures)

    def sizes(self):
        """The first levels of the refinement and the largest ``n``."""
        if self.n is None:
            start, n_max = METHODS[self.method].auto_range
            return [start, 2 * start], n_max
        coarse = [m for m in (self.n // 4, self.n // 2) if m >= N_RANGE[0]]
        return coarse + [self.n], self.n

    @deprecated_spellings(converted=(("temperatures", "closure", far_temperatures),))
    def solve(self, fhpe, *, lam=None, sigma_over_delta=None, closure=None,
              check_convergence=False, progress=None, polish=True,
              _stacklevel=2) -> ContactSolution:
        """Solve at ``fhpe`` with the heat partition, the offset or the far
        temperatures given.

        Parameters
        ----------
        fhpe : float
            ``f H Pe >= 0``.
        lam, sigma_over_delta : float
            The heat partition ``(Q1 - Q2)/(Q1 + Q2)`` or the offset: the same as
            ``closure=HeatPartition(lam)`` and ``closure=Offset(sigma_over_delta)``.
        closure : HeatPartition, Offset or FarTemperatures
            What fixes the heat partition (:mod:`thermocontact.problem.closure`); with
            the far temperatures (derivation section 17) ``lam`` is an output, its error
            estimated with ``P_H/P`` and ``sigma/Delta`` and reported as ``lam_error``.
            Exactly one of ``lam``, ``sigma_over_delta`` and ``closure``.
        check_convergence : bool, optional
            Also solve with ``2n`` (``n/2`` when ``2n`` exceeds the largest ``n``)
            and report the change in ``P_H/P``.
        progress : callable, optional
            ``progress(n, estimate)`` before each level
            (:func:`~thermocontact.solvers.refinement.refine`).
        polish : bool, optional
            Polish every margin's minimum on the closed forms (default), or only
            those near zero (:func:`~thermocontact.analysis.validity.assess`).

        Returns
        -------
        ContactSolution
            With the error estimate from the solutions at ``n``, ``n/2`` and
            ``n/4`` (None when ``n < 8`` leaves no coarser level).  A solution whose
            estimate misses ``tol`` with ``n`` chosen automatically also issues a
            :class:`ConvergenceWarning`.
        """
        # One point: each input one number (solve_many takes sequences).
        given = closure_of(closure, lam=lam, sigma_over_delta=sigma_over_delta).keywords()
        lam, sigma_over_delta = given.get("lam"), given.get("sigma_over_delta")
        temperatures = temperature_closure(given.get("theta"), given.get("sink_distance"))
        fhpe = check_finite("fhpe", fhpe)
        check_flag("check_convergence", check_convergence)
        check_callable("progress", progress)
        sol = self.solve_many([fhpe], lam=None if lam is None else [check_finite("lam", lam)],
                              sigma_over_delta=(None if sigma_over_delta is None else
                                                [check_finite("sigma_over_delta",
                                                              sigma_over_delta)]),
                              temperatures=temperatures, progress=progress, polish=polish,
                              _stacklevel=_stacklevel + 1)[0]
        if isinstance(sol, Exception):
            raise sol
        if check_convergence:
            other = self.solve_at(2 * sol.n if 2 * sol.n <= N_RANGE[1] else sol.n // 2,
                                  fhpe, lam=lam, sigma_over_delta=sigma_over_delta,
                                  temperatures=temperatures, check_validity=False)
            sol = sol.replace(load_ratio_change=abs(other.load_ratio - sol.load_ratio))
        log.debug("solved: %r", sol)
        return sol

    def solve_many(self, fhpe, *, lam=None, sigma_over_delta=None, temperatures=None,
                   polish=True, progress=None, rcond="estimate", _stacklevel=2) -> list:
        """:meth:`solve` at several points of this model: a grid line along ``fhpe``,
        ``lam`` or ``sigma_over_delta``.

        Each point is refined on its own, as :meth:`solve` refines it; the systems
        are assembled once per ``n`` and closure, and the contact inequalities of all
        the points' solutions at one ``n`` are evaluated together
        (:func:`~thermocontact.analysis.validity.assess_many`), to the same numbers.

        Parameters
        ----------
        fhpe : float or sequence of float
            ``f H Pe >= 0``, one value or one per point.
        lam, sigma_over_delta : float or sequence of float
            One value or one per point.
        temperatures : Temperatures or tuple, or a list of them
            Or the far temperatures (:meth:`solve`), one or one per point.  Exactly
            one of the three closures.
        polish : bool, optional
            As :meth:`solve`.
        progress : callable, optional
            As :meth:`solve`, for every point.
        rcond : {"estimate", "bound"}, optional
            Each solution's ``rcond``: LAPACK's estimate, as :meth:`solve` gives it;
            or, cheaper along a line, a lower bound proven from a few anchors
            (:func:`solve_stack`; derivation section 6b), LAPACK's estimate where none
            is proven.  The solutions and the points refused are the same.

        Returns
        -------
        list
            Per point, the :class:`ContactSolution` that :meth:`solve` returns there, or
            the :class:`InputError` or :class:`SolveError` it would raise.
        """
        check_choice("rcond", rcond, RCOND_CHOICES)
        fhpes, keys = line_inputs(fhpe, lam, sigma_over_delta, temperatures)
        far = keys[0][2] is not None
        # lam is an output of the offset and of the temperatures, but its error is
        # estimated only where the temperatures make it (the offset's estimates stay).
        quantities = QUANTITIES if not far else QUANTITIES_WITH_LAM
        sizes, n_max = self.sizes()
        method = METHODS[self.method]
        systems = {}  # by n, the systems by closure
        out = [None] * len(keys)
        pars = {}
        for i, f in enumerate(fhpes):
            try:
                pars[i] = self.parameters_at(f)
            except InputError as exc:
                out[i] = exc
        cases = sorted(pars)

        def solve_level(m, which):
            # Validity only for the solutions returned: the coarser levels feed the
            # error estimate alone.
            points = [cases[j] for j in which]
            blocks = self.blocks(m)
            if m >= SHARED_BLOCKS_N:
                # A large level's system (34 MB at n = 1024) is not formed beside the
                # coarser levels' systems, nor beside the heap pages its assembly freed;
                # a level asked for again forms its system again.
                for k in [k for k in systems if k < m]:
                    del systems[k]
                release_freed_memory()
            return _solve_patches([pars[i] for i in points], blocks, self.method,
                                  [keys[i] for i in points], self.conductance,
                                  systems.setdefault(m, {}), rcond)

        refined = {}
        for j, res in enumerate(refine_each(solve_level, sizes, len(cases),
                                            tol=self.tol if self.n is None else None,
                                            n_max=n_max, p_max=method.order_cap,
                                            progress=progress, quantities=quantities)):
            if isinstance(res, Exception):
                out[cases[j]] = res
            else:
                refined[cases[j]] = (lambda m, j=j: _raising(solve_level(m, [j])[0]), *res)
        # The systems (34 MB at n = 1024, partly resident) are formed again for any
        # further level.
        systems.clear()
        validities = line_validities(refined, polish)
        for i, (at, levels, est) in refined.items():
            try:
                sol = self._finished(at, levels, est, validities, i, quantities, far, polish,
                                     progress)
            except (InputError, SolveError) as exc:
                out[i] = exc
                continue
            if sol.converged is False and self.n is None:
                warnings.warn(f"thermocontact: {sol.message}", ConvergenceWarning,
                              stacklevel=_stacklevel)
            out[i] = sol
        return out

    def _finished(self, at, levels, est, validities, i, quantities, far, polish, progress):
        """A point's solution from its levels: its validity, the margins' change since
        n/2 (refined on, with n chosen, until every margin's sign is beyond it, or n
        reaches its largest), the error estimates."""
        method = METHODS[self.method]
        n_max = self.sizes()[1]

        def validity_of(sol, fine):
            known = validities.get((i, sol.n))
            if known is not None:
                return known
            sol = as_in(sol, fine)
            return assess(sol.parameters, sol.representation, sol.phi, sol.psi,
                          sol.load_ratio, sol.sigma_over_delta, sol.lam, polish=polish)
        fin = levels[-1]
        validity = validity_of(fin, fin)
        if len(levels) > 1:
            while True:
                coarse = validity_of(levels[-2], fin).margins()
                change = max(abs(a - coarse[k]) for k, a in validity.margins().items())
                validity = validity.replace(margin_change=float(change))
                if self.n is not None or validity.certain() or 2 * fin.n > n_max:
                    break
                if progress is not None:
                    progress(2 * fin.n, est)
                levels.append(at(2 * fin.n))
                fin = levels[-1]
                est = error_estimate(levels, quantities, p_max=method.order_cap)
                validity = validity_of(fin, fin)
        lam_error = None
        if far and len(levels) > 1:
            # Absolute: error_estimate is relative to max(|lam|, 0.01).
            lam_error = float(error_estimate(levels, ("lam",), p_max=method.order_cap)
                              * max(abs(fin.lam), 0.01))
        return fin.replace(validity=validity, error_estimate=None if est is None else float(est),
                           auto_n=self.n is None, tol=self.tol,
                           estimate_is_bound=method.estimate_is_bound, lam_error=lam_error)


@deprecated_spellings(closure="dimensionless")
def solve(pe, fhpe, K2_over_K1, *, lam=None, sigma_over_delta=None, closure=None,
          k2_over_k1=None, delta1_over_delta2=1.0, speed_ratio=0.0, beta_f=0.0, n=None,
          method=DEFAULT_METHOD, tol=DEFAULT_TOL, check_convergence=False, progress=None,
          conductance=None, delta_over_r=None) -> ContactSolution:
    """Solve the steady thermoelastic sliding-contact problem.

    ``Model(pe, K2_over_K1, ...).solve(fhpe, ...)``: see :class:`Model` for the
    parameters.

    Parameters
    ----------
    pe, fhpe, K2_over_K1 : float
        ``Pe > 0``, ``f H Pe >= 0`` and the conductivity ratio ``> 0``.
    k2_over_k1, delta1_over_delta2 : float, optional
        Diffusivity (default ``K2_over_K1``) and distortivity (default 1) ratios.
    speed_ratio : float, optional
        ``R = v2/v1`` (default 0, the stationary half-plane).
    beta_f : float, optional
        ``B = beta f`` of the Dundurs term (default 0).
    lam, sigma_over_delta : float
        The heat partition or the contact offset: the same as
        ``closure=HeatPartition(lam)`` and ``closure=Offset(sigma_over_delta)``.
    closure : HeatPartition, Offset or FarTemperatures
        What fixes the heat partition (:mod:`thermocontact.problem.closure`): the
        far temperatures ``FarTemperatures(theta, sink_distance_over_delta)``, the
        group ``Theta = pi K2 (T2 - T1)/(f |v1 - v2| P)`` (D39) with a stationary
        half-plane's sink at ``L/Delta > 1`` (D38; none for a moving half-plane, whose
        ``T2`` is its incoming temperature), make ``lam`` an output with its error
        (``lam_error``; derivation section 17).  Exactly one of ``lam``,
        ``sigma_over_delta`` and ``closure``.
    n : int, optional
        Unknowns per function; by default chosen until the estimate meets ``tol``.
    method : str, optional
        A key of :data:`~thermocontact.discretisation.methods.METHODS`; default
        ``"graded"``.
    tol : float, optional
        Target of the error estimate (default 1e-8).
    check_convergence : bool, optional
        Also solve with ``2n`` and report the change in ``P_H/P``.
    progress : callable, optional
        ``progress(n, estimate)`` before each level of the refinement.
    conductance : tuple, optional
        ``(Bi0, m)`` of an interface conductance, ``Bi0 = h0 Delta/K2`` (section 16);
        default perfect thermal contact.
    delta_over_r : float, optional
        Half-width over the cylinder's radius, > 0: also judge whether the theory
        applies (contact size, slopes, strains; derivation section 11a), recorded as
        the result's ``applicability``.

    Returns
    -------
    ContactSolution

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
    closure = closure_of(closure, lam=lam, sigma_over_delta=sigma_over_delta)
    if delta_over_r is not None:
        delta_over_r = check_positive("delta_over_r", delta_over_r)
    model = Model(pe, K2_over_K1, k2_over_k1=k2_over_k1,
                  delta1_over_delta2=delta1_over_delta2, speed_ratio=speed_ratio, beta_f=beta_f,
                  method=method, n=n, tol=tol, conductance=conductance)
    sol = model.solve(fhpe, closure=closure, check_convergence=check_convergence,
                      progress=progress, _stacklevel=4)
    if delta_over_r is None:
        return sol
    from ..analysis.applicability import applicability

    return sol.replace(applicability=applicability(sol, delta_over_r))
