"""The transient contact: from switch-on to the steady state, or to what follows it.

Derivation section 19.  The load ``P`` is applied and sliding starts at ``t = 0``; the
pressure, the heat fluxes into both bodies and the contact set (any number of zones)
evolve.  The elastic response is quasi-static; the heat conducts.  Elements of width
``h`` on a fixed window carry, over each step ``dt``, a constant pressure and heat
flux; every lag of the history acts through the element-and-step integrals of the
impulse responses (:mod:`thermocontact.discretisation.history`), summed by an online
FFT convolution in ``O(L log^2 L)`` for ``L`` steps.  Each step is a contact problem
of the steady elements' form (section 14b) solved by an active set from the last
step's, with the history on its right side (eq. R9).

Units: lengths in the Hertz half-width ``l`` of the load, time in ``l^2/kappa2``,
pressure in ``P/l``, heat flux in ``f v P/l``, temperatures in ``f v P/(pi K2)``.

Closures (the far field):

* ``lam``: the heat partition held, the far temperature difference ``C(t)`` free, as
  the steady model does;
* ``theta``: the far temperatures held, ``C = theta`` (derivation section 17's
  ``Theta``), both half-planes infinite, ``lam(t)`` an output.  Started from a steady
  state, the temperatures are those of that state (the closure of
  :mod:`thermocontact.solvers.stability`, section 18).
"""

from __future__ import annotations

import time as _time
from dataclasses import dataclass, field, fields

import numpy as np

from ..discretisation.element_operators import steady_element_operators
from ..discretisation.history import HeatHistory, transient_element_operators
from ..io.results import Result, dataset_attrs
from ..problem.errors import NotConvergedError
from ..problem.parameters import DISTORTIVITY_RATIO_MAX, Parameters, SolveError
from ..problem.validation import (InputError, check_choice, check_finite, check_integer,
                                  check_nonnegative, check_pair, check_positive, check_range)
from .active_set import chattering, next_set
from .elements import contact_runs, solve_elements, solve_on_set

__all__ = ["TransientRun", "TransientSpec", "held_set_steps", "longest_step", "read_run",
           "run_transient", "zones_of"]

#: Most steps x elements of a run: its history (the inputs' and outputs' transforms, in
#: complex spatial modes) and its fields stay within a few hundred MB.
MAX_STEP_ELEMENTS = 3_000_000
#: Time steps and elements of a run.
STEPS_RANGE = (1, 100_000)
ELEMENTS_RANGE = (8, 4000)
#: Most half-widths the cylinder's surface may move in one step: beyond, a step resolves
#: nothing of the convected heat and its tables' panels (a quarter of a pulse's width
#: each) grow without bound.
MAX_SHIFT = 100.0
#: Shortest run, l^2/kappa2: a millionth of a millionth of the time heat takes to
#: cross the contact (shorter steps underflow their squares: 1e-300 divided by zero).
UNTIL_MIN = 1e-12
#: Fewest elements a zone should span for its pressure to be carried (below, a run's
#: ``resolution`` says so).
RESOLVED_ELEMENTS = 8
#: Largest interface resistance pi/(2 Bi) of a step's rows: where the pressure (and
#: with m > 0 the conductance) vanishes, q is held at zero to 1e-12 of the row's scale.
RESISTANCE_MAX = 1e12
#: The active set of one step: changes all at once, then one at a time (the worst
#: first) if that cycles; at most this many solves.
_MAX_SET_ITERATIONS = 400
#: The implicit step's active set: at most this many solves before it settles or
#: gives way to the IMEX step.
_COUPLED_ITERATIONS = 12
#: Passes of Bi = Bi0 (2p)^m on a set's own pressure (m > 0).
_BI_PASSES = 20


def longest_step(pe_hertz) -> float:
    """The longest time step at ``Pe_l``, l^2/kappa2: the cylinder's surface moves
    :data:`MAX_SHIFT` half-widths in it."""
    return MAX_SHIFT / (2.0 * pe_hertz)


@dataclass(frozen=True)
class TransientSpec:
    """What a transient run computes (every input; the dataset's attributes).

    Attributes
    ----------
    pe_hertz, fhpe_hertz, K2_over_K1, k2_over_k1, delta1_over_delta2 : float
        The problem in units of ``l`` (as ``zones``): ``Pe_l = v l/(2 k2)``,
        ``F_l = f H Pe_l``.
    lam, theta : float or None
        The closure: exactly one with ``initial = "hertz"``; with ``initial = "steady"``
        ``lam`` picks the steady state and ``hold`` says what is then held.
    until : float
        Duration, units ``l^2/kappa2``, at least :data:`UNTIL_MIN`.
    steps : int
        Number of time steps (``dt = until/steps``).
    elements : int
        Elements on the window.
    window : (float, float)
        Where contact may occur, units ``l``.
    initial : {"hertz", "steady"}
    hold : {"theta", "lam"}
        With ``initial = "steady"``: the far temperatures (default) or the heat partition.
    perturb : float
        The load is ``1 + perturb`` during the first step.
    conductance : (float, float) or None
        ``(Bi0, m)``: interface conductance ``Bi = Bi0 (2 p)^m`` (section 15).
    """

    pe_hertz: float
    fhpe_hertz: float
    K2_over_K1: float
    until: float
    steps: int
    k2_over_k1: float | None = None
    delta1_over_delta2: float = 1.0
    lam: float | None = None
    theta: float | None = None
    elements: int = 240
    window: tuple = (-3.0, 3.0)
    initial: str = "hertz"
    hold: str = "theta"
    perturb: float = 0.0
    conductance: tuple | None = None

    def __post_init__(self):
        # Every input converted as it is checked (a number given as a string is that
        # number; a flag or a string that is no number is refused).
        def fix(name, value):
            object.__setattr__(self, name, value)
        fix("pe_hertz", check_positive("pe_hertz", self.pe_hertz))
        fix("fhpe_hertz", check_nonnegative("fhpe_hertz", self.fhpe_hertz))
        fix("K2_over_K1", check_positive("K2_over_K1", self.K2_over_K1))
        if self.k2_over_k1 is not None:
            fix("k2_over_k1", check_positive("k2_over_k1", self.k2_over_k1))
        fix("delta1_over_delta2", check_range("delta1_over_delta2", self.delta1_over_delta2,
                                              0.0, DISTORTIVITY_RATIO_MAX))
        fix("until", check_range("until", self.until, UNTIL_MIN, float("inf")))
        fix("steps", check_integer("steps", self.steps, *STEPS_RANGE))
        fix("elements", check_integer("elements", self.elements, *ELEMENTS_RANGE))
        if self.steps * self.elements > MAX_STEP_ELEMENTS:
            raise InputError(f"steps x elements must be at most {MAX_STEP_ELEMENTS:.0e} (the "
                             f"history's memory), got {self.steps} x {self.elements}",
                             parameters=("steps", "elements"))
        shift = 2.0 * self.pe_hertz * self.until / self.steps
        if shift > MAX_SHIFT:
            raise InputError(f"until/steps must be at most {longest_step(self.pe_hertz):.4g} "
                             f"l^2/kappa2 at this Pe_l: the cylinder's surface would move "
                             f"{shift:.4g} half-widths in one step (at most {MAX_SHIFT:g}); give "
                             f"more steps", parameters=("until", "steps"))
        lo, hi = check_pair("window", self.window, "two numbers lo < -1 and hi > 1")
        fix("window", (lo, hi))
        if not (lo < -1.0 and hi > 1.0):
            raise InputError(f"window must contain the Hertz contact -1 < x < 1, got "
                             f"({lo!r}, {hi!r})", parameters=("window",))
        if hi - lo > self.elements:
            # Elements wider than a half-width: Hertz's contact on fewer than two of
            # them (a window of 1e300 leaves it on none: a singular contact set).
            raise InputError(f"window must be at most {self.elements} half-widths wide "
                             f"with {self.elements} elements (each at most one, two across "
                             f"Hertz's contact), got ({lo!r}, {hi!r})", parameters=("window",))
        check_choice("initial", self.initial, ("hertz", "steady"))
        check_choice("hold", self.hold, ("theta", "lam"))
        if self.initial == "hertz" and (self.lam is None) == (self.theta is None):
            raise InputError("give one closure: lam (the heat partition held) or theta (the "
                             "far temperatures held)", parameters=("lam", "theta"))
        if self.initial == "steady" and (self.lam is None or self.theta is not None):
            raise InputError("initial='steady' takes lam (which steady state) and no theta",
                             parameters=("lam", "theta", "initial"))
        if self.lam is not None:
            fix("lam", check_range("lam", self.lam, -1.0, 1.0))
        if self.theta is not None:
            fix("theta", check_finite("theta", self.theta))
        fix("perturb", check_range("perturb", self.perturb, -0.5, 0.5))
        if self.conductance is not None and self.initial == "steady":
            raise InputError("initial='steady' takes no conductance: the steady element "
                             "solution is one of perfect thermal contact",
                             parameters=("conductance", "initial"))
        if self.conductance is not None:
            Bi0, m = check_pair("conductance", self.conductance, "(Bi0, m), two numbers")
            check_positive("conductance", Bi0)
            if not 0.0 <= m <= 2.0:
                raise InputError(f"conductance exponent m must lie in [0, 2], got {m!r}",
                                 parameters=("conductance",))
            fix("conductance", (Bi0, m))
        self.parameters()

    @property
    def dt(self) -> float:
        return self.until / self.steps

    def parameters(self) -> Parameters:
        return Parameters(self.pe_hertz, self.fhpe_hertz, self.K2_over_K1, self.k2_over_k1,
                          self.delta1_over_delta2)

    def grid(self):
        lo, hi = self.window
        h = (hi - lo) / self.elements
        return lo + h * (np.arange(self.elements) + 0.5), h


def zones_of(active, X, h):
    """``(start, end)`` of each run of contact elements (edges to half an element)."""
    starts, stops = contact_runs(active)
    return X[starts] - 0.5 * h, X[stops - 1] + 0.5 * h


@dataclass(frozen=True, eq=False, repr=False)
class TransientRun(Result):
    """A transient run: fields over time and the elements' centres.

    Attributes
    ----------
    spec : TransientSpec
    time : ndarray, shape (T,)
        ``t_n = n dt``, units ``l^2/kappa2``; ``T - 1`` steps computed.
    x : ndarray, shape (N,)
        Element centres, units ``l``.
    pressure, flux, gap, theta1, theta2 : ndarray, shape (T, N)
        ``p`` (``P/l``), ``q = q1 - q2`` (``f v P/l``), the gap (``l^2/R``) and each
        surface's temperature rise (``f v P/(pi K2)``) at the end of each step.
    lam, approach, temperature_difference : ndarray, shape (T,)
        The heat partition, the rigid approach and ``C = theta1 - theta2`` on contact.
        From Hertz's start ``lam`` and ``C`` are NaN at ``t = 0``: no heat has been
        made yet (sliding starts at ``t = 0``), so the partition ``sum q/sum p`` of the
        heat is 0/0 and the surfaces' temperatures have no difference to report; from
        the first step on they are the step's.  From a steady start they are that
        state's.
    status : {"complete", "partial", "stopped"}
        The run to its end, a resumable part of it, or a run that stopped early
        (:attr:`STATUSES`; ``message`` says why).
    set_iterations : ndarray of int, shape (T,)
        Linear solves of each step's active sets.
    scheme : ndarray of int, shape (T,)
        How each step was solved: 0 implicit (R9), 2 implicit with its contact set
        settled at an edge that lies inside an element, 1 IMEX (R10, R11) where the
        implicit step has no settled contact set on these elements.
    """

    spec: TransientSpec
    time: np.ndarray
    x: np.ndarray
    pressure: np.ndarray
    flux: np.ndarray
    gap: np.ndarray
    theta1: np.ndarray
    theta2: np.ndarray
    lam: np.ndarray
    approach: np.ndarray
    temperature_difference: np.ndarray
    set_iterations: np.ndarray
    scheme: np.ndarray
    status: str = "complete"
    seconds: float = 0.0
    message: str = ""

    STATUSES = {"complete": "every step computed",
                "partial": "the steps up to an interruption or a save, resumable",
                "stopped": "the run stopped early (the contact reached the window's end, "
                           "or a step has no settled contact set): message says where and why"}
    SUCCESS = frozenset({"complete"})
    UNITS = {"time": "l^2/kappa2", "x": "l", "zones": "l", "window": "l",
             "pressure": "P/l", "peak_pressure": "P/l", "flux": "f v P/l", "gap": "l^2/R",
             "temperature1": "f v P/(pi K2)", "temperature2": "f v P/(pi K2)",
             "temperature_difference": "f v P/(pi K2)", "approach": "l^2/R", "seconds": "s"}

    def _summary(self) -> str:
        a, b = self.zones(-1)
        z = ", ".join(f"[{s:.4g}, {e:.4g}]" for s, e in zip(a, b))
        return (f"t={self.time[-1]:.4g}, steps={self.time.size - 1}, zones={z}, "
                f"lam={self.lam[-1]:.6g}, status={self.status}")

    @property
    def in_contact(self) -> np.ndarray:
        return self.pressure > 0.0

    @property
    def h(self) -> float:
        return float(self.x[1] - self.x[0])

    def fewest_elements(self, share: float = 0.1) -> int:
        """The fewest elements spanned by a zone carrying at least ``share`` of the load,
        at any step after the first (0: none).  A zone just formed or about to open
        carries less and spans a few elements by nature."""
        fewest = 0
        h = self.h
        for p in self.pressure[1:]:
            for a, b in zip(*contact_runs(p > 0.0)):
                if h * p[a:b].sum() >= share and (fewest == 0 or b - a < fewest):
                    fewest = int(b - a)
        return fewest

    @property
    def resolution(self) -> str:
        """``"resolved"``, or why the elements are too coarse: a zone carrying a tenth of
        the load on fewer than :data:`RESOLVED_ELEMENTS` elements has its pressure on
        too few constants."""
        k = self.fewest_elements()
        if k >= RESOLVED_ELEMENTS or k == 0:
            return "resolved"
        return (f"under-resolved: a zone spans {k} element{'s' if k > 1 else ''} (fewer than "
                f"{RESOLVED_ELEMENTS}); give more elements or a narrower window")

    def zones(self, n):
        """Zones ``(starts, ends)`` at step ``n`` (to half an element)."""
        return zones_of(self.in_contact[n], self.x, self.h)

    def zone_table(self):
        """``zones_count(time)``, ``zone_start``/``zone_end(time, zone)`` (NaN-padded)."""
        all_zones = [self.zones(n) for n in range(self.time.size)]
        count = np.array([z[0].size for z in all_zones])
        width = max(1, int(count.max()))
        start = np.full((self.time.size, width), np.nan)
        end = np.full((self.time.size, width), np.nan)
        for n, (a, b) in enumerate(all_zones):
            start[n, :a.size], end[n, :b.size] = a, b
        return count, start, end

    def _record(self) -> dict:
        a, b = self.zones(-1)
        return {"spec": self.spec.__dict__, "time": float(self.time[-1]),
                "steps": int(self.time.size - 1), "status": self.status,
                "message": self.message,
                "zones": [[float(s), float(e)] for s, e in zip(a, b)],
                "lam": float(self.lam[-1]), "approach": float(self.approach[-1]),
                "temperature_difference": float(self.temperature_difference[-1]),
                "peak_pressure": float(self.pressure[-1].max()), "seconds": self.seconds,
                "resolution": self.resolution}

    def to_dataset(self):
        """The run as an :class:`xarray.Dataset` (coordinates ``time``, ``x``, ``zone``)."""
        import xarray as xr

        count, start, end = self.zone_table()
        tx = ("time", "x")
        ds = xr.Dataset(
            {"pressure": (tx, self.pressure, {"units": "P/l"}),
             "flux": (tx, self.flux, {"units": "f v P/l", "long_name": "q1 - q2"}),
             "in_contact": (tx, self.in_contact.astype(np.int8)),
             "gap": (tx, self.gap, {"units": "l^2/R"}),
             "temperature1": (tx, self.theta1, {"units": "f v P/(pi K2)",
                                                "long_name": "cylinder surface temperature rise"}),
             "temperature2": (tx, self.theta2, {"units": "f v P/(pi K2)",
                                                "long_name": "half-plane surface temperature rise"}),
             "lam": ("time", self.lam),
             "approach": ("time", self.approach, {"units": "l^2/R"}),
             "temperature_difference": ("time", self.temperature_difference,
                                        {"units": "f v P/(pi K2)"}),
             "set_iterations": ("time", self.set_iterations),
             "scheme": ("time", self.scheme, {"long_name": "0 implicit, 1 IMEX, 2 settled"}),
             "zones_count": ("time", count),
             "zone_start": (("time", "zone"), start, {"units": "l"}),
             "zone_end": (("time", "zone"), end, {"units": "l"})},
            coords={"time": ("time", self.time, {"units": "l^2/kappa2"}),
                    "x": ("x", self.x, {"units": "l"})})
        attrs = {k: v for k, v in self.spec.__dict__.items() if k not in ("window", "conductance")}
        attrs["window"] = list(self.spec.window)
        if self.spec.conductance is not None:
            attrs["conductance"] = list(self.spec.conductance)
        ds.attrs.update(dataset_attrs(attrs))
        ds.attrs["window"] = list(self.spec.window)
        ds.attrs["status"] = self.status
        ds.attrs["message"] = self.message
        ds.attrs["seconds"] = self.seconds
        return ds

    @classmethod
    def from_dataset(cls, ds) -> TransientRun:
        """The run that :meth:`to_dataset` wrote, from that dataset (or its file read back).

        The inverse of :meth:`to_dataset`: the inputs (``"none"`` back to None, the
        window and the conductance as tuples, steps and elements as integers), the
        fields, the status and the seconds; other attributes are ignored.  A partial
        run read so is what :func:`run_transient` resumes.

        Raises
        ------
        InputError
            The dataset is not a transient run's (an input or a field is missing).
        """
        attrs = ds.attrs

        def optional(key):
            value = attrs.get(key, "none")
            return None if isinstance(value, str) and value == "none" else float(value)

        try:
            spec = TransientSpec(
                pe_hertz=float(attrs["pe_hertz"]), fhpe_hertz=float(attrs["fhpe_hertz"]),
                K2_over_K1=float(attrs["K2_over_K1"]), until=float(attrs["until"]),
                steps=int(attrs["steps"]), k2_over_k1=optional("k2_over_k1"),
                delta1_over_delta2=float(attrs["delta1_over_delta2"]),
                lam=optional("lam"), theta=optional("theta"), elements=int(attrs["elements"]),
                window=tuple(float(w) for w in np.ravel(attrs["window"])),
                # (A file of versions before 1.0 names the initial state "start".)
                initial=str(attrs.get("initial", attrs.get("start"))),
                hold=str(attrs["hold"]),
                perturb=float(attrs["perturb"]),
                conductance=(tuple(float(c) for c in np.ravel(attrs["conductance"]))
                             if "conductance" in attrs else None))

            # Every array field from its variable (the temperatures renamed), so that
            # a field added to the run is read back without a change here.
            renamed = {"theta1": "temperature1", "theta2": "temperature2"}
            arrays = {}
            for f in fields(cls):
                if f.name not in ("spec", "status", "seconds", "message"):
                    v = np.asarray(ds[renamed.get(f.name, f.name)].values)
                    arrays[f.name] = v.astype(int if v.dtype.kind in "iub" else float)
            status, message = str(attrs["status"]), str(attrs.get("message", ""))
            if status.startswith("stopped at step"):  # a file of versions before 1.0
                status, message = "stopped", status[len("stopped "):]
            return cls(spec=spec, status=status, seconds=float(attrs["seconds"]),
                       message=message, **arrays)
        except KeyError as exc:
            raise InputError(f"the dataset is not a transient run's: it has no {exc}",
                             parameters=("ds",)) from None
        except (TypeError, ValueError) as exc:
            raise InputError(f"the dataset is not a transient run's: {exc}",
                             parameters=("ds",)) from None


def read_run(source, name: str = "ds") -> TransientRun:
    """The run of a dataset that :meth:`TransientRun.to_dataset` wrote, given as the
    dataset or as its file (``.nc``); anything else, a file that is missing or not a
    dataset, or a dataset not of a run, is refused naming ``name``."""
    import os

    import xarray as xr

    if isinstance(source, (str, os.PathLike)):
        from ..io.datasets import read_dataset

        if not os.path.isfile(source):
            raise InputError(f"{name} must be a transient run's dataset or its file, got "
                             f"{os.fspath(source)!r}, which is no file", parameters=(name,))
        try:
            source = read_dataset(source)
        except Exception as exc:  # any reader's failure: not a dataset it knows
            raise InputError(f"{name}: {os.fspath(source)!r} could not be read as a dataset "
                             f"({type(exc).__name__}: {exc})".splitlines()[0],
                             parameters=(name,)) from None
    if not isinstance(source, xr.Dataset):
        raise InputError(f"{name} must be a transient run's dataset or its file, got "
                         f"{source!r}"[:200], parameters=(name,))
    try:
        return TransientRun.from_dataset(source)
    except InputError as exc:
        raise InputError(str(exc).replace("the dataset", f"{name}", 1),
                         parameters=(name,)) from None


@dataclass
class _State:
    """Everything a step needs from the steps before it."""

    pressure: list = field(default_factory=list)
    flux: list = field(default_factory=list)
    gap: list = field(default_factory=list)
    theta1: list = field(default_factory=list)
    theta2: list = field(default_factory=list)
    lam: list = field(default_factory=list)
    approach: list = field(default_factory=list)
    difference: list = field(default_factory=list)
    iterations: list = field(default_factory=list)
    scheme: list = field(default_factory=list)

    def append(self, p, q, g, t1, t2, lam, D, C, it):
        for name, v in zip(("pressure", "flux", "gap", "theta1", "theta2", "lam", "approach",
                            "difference", "iterations"), (p, q, g, t1, t2, lam, D, C, it)):
            getattr(self, name).append(v)


def _hertz(X, h):
    """Hertz's pressure ``(2/pi) sqrt(1 - X^2)`` as element averages (load 1)."""
    def prim(x):
        x = np.clip(x, -1.0, 1.0)
        return (x * np.sqrt(1.0 - x * x) + np.arcsin(x)) / np.pi
    return (prim(X + 0.5 * h) - prim(X - 0.5 * h)) / h


def _solve_set(ops, g_known, t_known, h, active, load, closure, resistance_of, p):
    """(R9) on one active set; with a pressure-dependent conductance, Bi from the
    solution's own pressure (a few passes from ``p``).  Raises SolveError where the
    solution is not finite."""
    for _ in range(_BI_PASSES if resistance_of.nonlinear else 1):
        p_old = p
        try:
            p, q, gap, D, C = solve_on_set(ops.Gp, ops.Gq, ops.Tp, ops.Tq, g_known, t_known, h,
                                           active, load=load, resistance=resistance_of(p),
                                           **closure)
        except np.linalg.LinAlgError:
            raise SolveError("a singular contact set at this step") from None
        if not (np.all(np.isfinite(p)) and np.all(np.isfinite(q))):
            raise SolveError("no finite solution on this contact set")
        if resistance_of.nonlinear and np.max(np.abs(p - p_old)) <= 1e-12 * np.max(p):
            break
    return p, q, gap, D, C


def _coupled(ops, g_known, t_known, h, active, load, closure, resistance_of, p_start, tol):
    """The implicit step (eq. R9): contact and heat together on an active set, all
    changes at once, else the worst first.

    The thermal coupling makes the step's matrix non-symmetric, and an element at a
    zone's end can be tensile in contact and interpenetrate out of it (the edge lies
    inside it).  Such a cycle, toggling only elements at the zones' ends, settles on
    the state without tension that interpenetrates least, as the steady elements do
    (section 14b); ``chatter`` counts its toggled elements.  So does a set that has
    not settled after ``_COUPLED_ITERATIONS`` solves.
    """
    seen = {}
    one_at_a_time = False
    for it in range(1, _COUPLED_ITERATIONS + 1):
        p, q, gap, D, C = _solve_set(ops, g_known, t_known, h, active, load, closure,
                                     resistance_of, p_start)
        p_start = p
        tension = active & (p < -tol)
        overlap = ~active & (gap < -tol)
        if not tension.any() and not overlap.any():
            return p, q, gap, D, C, it, 0
        seen[active.tobytes()] = (p, q, gap, D, C, active)
        new, one_at_a_time, cycled = next_set(active, p, gap, tension, overlap, seen,
                                               one_at_a_time)
        if cycled:
            return _settle(seen, it, tol)
        if not new.any():
            raise SolveError("every element left contact")
        active = new
    return _settle(seen, it, tol)


def _settle(seen, it, tol):
    """A cycle of the active set: the state without tension that interpenetrates least,
    if it has settled (:func:`~.active_set.chattering`)."""
    toggled = chattering([v[5] for v in seen.values()])
    calm = [v for v in seen.values() if np.all(v[0][v[5]] >= -tol)]
    if toggled is None or not calm:
        raise NotConvergedError("the active set cycles: no settled contact set at this step")
    p, q, gap, D, C, _ = min(calm, key=lambda v: -np.min(np.where(v[5], 0.0, v[2])))
    return p, q, gap, D, C, it, int(toggled.size)


def _contact(flamant, g_known, h, active, load, tol):
    """The step's elastic contact (eq. R10): ``g_known + flamant p - D >= 0``, ``p >= 0``,
    complementary, ``h sum p = load``, by an active set from the last step's.

    Flamant's operator is positive definite on loads of zero sum, so this is a convex
    problem: all changes at once, then the worst one at a time should that cycle.
    """
    seen = set()
    one_at_a_time = False
    N = flamant.shape[0]
    for it in range(1, _MAX_SET_ITERATIONS + 1):
        idx = np.flatnonzero(active)
        k = idx.size
        A = np.empty((k + 1, k + 1))
        A[:k, :k] = flamant[np.ix_(idx, idx)]
        A[:k, k] = -1.0
        A[k, :k] = h
        A[k, k] = 0.0
        b = np.concatenate([-g_known[idx], [load]])
        try:
            x = np.linalg.solve(A, b)
        except np.linalg.LinAlgError:
            raise SolveError("a singular contact set at this step") from None
        p = np.zeros(N)
        p[idx] = x[:k]
        gap = g_known + flamant @ p - x[k]
        gap[idx] = 0.0
        tension = active & (p < -tol)
        overlap = ~active & (gap < -tol)
        if not tension.any() and not overlap.any():
            return p, gap, x[k], active, it
        seen.add(active.tobytes())
        new, one_at_a_time, cycled = next_set(active, p, gap, tension, overlap, seen,
                                               one_at_a_time)
        if cycled:
            raise NotConvergedError("the active set cycles: no settled contact set at this step")
        if not new.any():
            raise SolveError("every element left contact")
        active = new
    raise NotConvergedError(f"the active set did not settle in {_MAX_SET_ITERATIONS} solves")


def _partition(ops, p, t_known, h, active, closure, resistance):
    """The step's heat (eq. R11): ``t_known + Tp p + (Tq + diag(resistance)) q = C`` on
    the contact, with the closure ``h sum q = lam h sum p`` (``C`` unknown) or
    ``C = theta``; ``q = 0`` off contact."""
    idx = np.flatnonzero(active)
    k = idx.size
    free = "lam" in closure
    A = np.zeros((k + free, k + free))
    A[:k, :k] = ops.Tq[np.ix_(idx, idx)]
    if resistance is not None:
        A[np.arange(k), np.arange(k)] += resistance[idx]
    b = -t_known[idx] - ops.Tp[np.ix_(idx, idx)] @ p[idx]
    if free:
        A[:k, k] = -1.0
        A[k, :k] = h
        b = np.concatenate([b, [closure["lam"] * h * p[idx].sum()]])
    else:
        b = b + closure["theta"]
    x = np.linalg.solve(A, b)
    q = np.zeros(p.size)
    q[idx] = x[:k]
    return q, (x[k] if free else closure["theta"])


class _Resistance:
    """``pi/(2 Bi)`` per element, ``Bi = Bi0 (2 p)^m`` (section 15; None: perfect)."""

    def __init__(self, conductance, N):
        self.conductance = conductance
        self.nonlinear = conductance is not None and conductance[1] != 0.0
        self.N = N

    def __call__(self, p):
        if self.conductance is None:
            return None
        Bi0, m = self.conductance
        # Where m > 0 makes Bi vanish with the pressure the row says q = 0 (section 15):
        # a resistance of RESISTANCE_MAX does so to rounding and stays finite.
        with np.errstate(divide="ignore", over="ignore"):
            r = np.pi / (2.0 * Bi0 * (2.0 * np.maximum(p, 0.0)) ** m)
        return np.minimum(r, RESISTANCE_MAX)


def run_transient(spec: TransientSpec, *, resume: TransientRun | None = None, progress=None,
                  save=None, save_every: float = 30.0, preparing=None) -> TransientRun:
    """Run the transient contact (derivation section 19).

    Parameters
    ----------
    spec : TransientSpec
    resume : TransientRun, optional
        A partial run of the same ``spec``: its steps are replayed into the history (no
        solves) and the run goes on from its last.
    progress : callable, optional
        ``progress(done, total)`` before the first step (``done`` of a resumed run)
        and after each step.
    save : callable, optional
        ``save(partial_run)`` at most every ``save_every`` seconds, never after the
        last step (the run returned is the whole one).
    preparing : callable, optional
        ``preparing(done, total)`` while the operators are made, before any step:
        over both bodies' lag tables, a step of lag at a time, then the step's own
        matrices (a long run's or a fine one's take minutes).

    Returns
    -------
    TransientRun
        ``status`` says why a run stopped early: the contact reached the window's end,
        or no contact set settled (then the run holds every step before).

    Raises
    ------
    SolveError
        When the steady start state does not exist on these elements.
    """
    from ..execution.executors import one_blas_thread

    # The step's matrices are small: one BLAS thread is faster than several competing
    # for the cores (path (a)'s 1000 steps: 7 s against 214 s on a loaded 2-core machine).
    with one_blas_thread():
        return _run(spec, resume, progress, save, save_every, preparing)


def _run(spec, resume, progress, save, save_every, preparing=None):
    t0 = _time.perf_counter()
    run = _Stepper(spec, preparing)
    done = 0 if resume is None else run.replay(resume)
    seconds = (resume.seconds if resume is not None else 0.0) - t0
    status, message = "complete", "every step computed"
    last_save = _time.perf_counter()
    if progress is not None:
        progress(done, spec.steps)
    for n in range(done + 1, spec.steps + 1):
        stopped = run.step(n)
        if stopped is not None:
            status, message = "stopped", stopped
            break
        if progress is not None:
            progress(n, spec.steps)
        if save is not None and _time.perf_counter() - last_save > save_every and n < spec.steps:
            save(run.result("partial", f"the first {n} of {spec.steps} steps, resumable",
                            seconds + _time.perf_counter()))
            last_save = _time.perf_counter()
    return run.result(status, message, seconds + _time.perf_counter())


def held_set_steps(spec: TransientSpec, active) -> tuple:
    """The steps linearised on a contact set held fixed: a small perturbation of a steady
    state whose contact elements stay in contact and the others out.

    Each step (eq. R9) is then linear in what the steps before it left, and the steady
    state drops out of the perturbation's steps: they are the steps of a run from rest
    (no profile, no steady heat) on the elements ``active``, kicked by the load
    ``spec.perturb`` during the first step, the closure held at its steady value
    (``hold="theta"``: the far temperatures; ``"lam"``: the partition, its heat
    ``lam`` times the kick).  A run of :func:`run_transient` from that steady state with
    a kick small enough to keep the set is the steady state plus these steps (tested);
    no sign is asked of the perturbation, so the set may be one no steady state of the
    elements has (an invalid single patch): the edges held there are the
    linearisation of derivation S17.

    Parameters
    ----------
    spec : TransientSpec
        ``initial="steady"``: the problem, the elements, the steps, the kick
        (``perturb``) and what is held.
    active : array of bool, shape (elements,)
        The contact set held.

    Returns
    -------
    time : ndarray, shape (steps,)
        The end of each step, ``l^2/kappa2``.
    pressure, flux : ndarray, shape (steps, elements)
        The perturbation's pressure and ``q1 - q2`` at each step.
    approach : ndarray, shape (steps,)
        The perturbation's rigid approach.
    """
    if spec.initial != "steady":
        raise InputError("held_set_steps perturbs a steady state: give initial='steady'",
                         parameters=("initial",))
    X, h = spec.grid()
    active = np.asarray(active, dtype=bool)
    if active.shape != X.shape or not active.any():
        raise InputError(f"active must be {X.size} flags with at least one set, got "
                         f"shape {active.shape}", parameters=("active",))
    tops = transient_element_operators(spec.parameters(), X, h, spec.dt, spec.steps)
    ops, history = tops.current, HeatHistory(tops)
    p, q, D = (np.zeros((spec.steps, X.size)), np.zeros((spec.steps, X.size)),
               np.zeros(spec.steps))
    for n in range(1, spec.steps + 1):
        y1, y2 = history.known(n)
        load = spec.perturb if n == 1 else 0.0
        closure = {"lam": spec.lam} if spec.hold == "lam" else {"theta": 0.0}
        p[n - 1], q[n - 1], _, D[n - 1], _ = solve_on_set(
            ops.Gp, ops.Gq, ops.Tp, ops.Tq, y1[0] + y2[0], y1[1] - y2[1], h, active,
            load=load, **closure)
        history.push(0.5 * (p[n - 1] + q[n - 1]), 0.5 * (p[n - 1] - q[n - 1]))
    return spec.dt * np.arange(1, spec.steps + 1), p, q, D


class _Stepper:
    """A transient run in the making: its operators and its start (:meth:`__init__`),
    the steps of a partial run taken as they are (:meth:`replay`), one step at a time
    (:meth:`step`), the run so far (:meth:`result`)."""

    #: The active sets' tolerance on the pressure and the gap.
    TOL = 1e-12

    def __init__(self, spec, preparing=None):
        self.spec = spec
        self.par = spec.parameters()
        self.X, self.h = spec.grid()
        N = self.X.size
        tops = transient_element_operators(self.par, self.X, self.h, spec.dt, spec.steps,
                                           preparing)
        self.ops, self.history = tops.current, HeatHistory(tops)
        self.g0 = 0.5 * self.X * self.X
        self.base_gap, self.base_t1, self.base_t2 = np.zeros(N), np.zeros(N), np.zeros(N)
        self.q1s, self.q2s = np.zeros(N), np.zeros(N)
        self.state = _State()
        if spec.initial == "hertz":
            self._start_hertz()
        else:
            self._start_steady()
        self.resistance = _Resistance(spec.conductance, N)
        self.q1_last, self.q2_last = self.q1s, self.q2s

    def _start_hertz(self):
        """Isothermal bodies under Hertz's pressure, the closure given held."""
        spec, ops, N = self.spec, self.ops, self.X.size
        self.closure = {"lam": spec.lam} if spec.lam is not None else {"theta": spec.theta}
        p0 = _hertz(self.X, self.h)
        self.active = p0 > 0.0
        zero = np.zeros(N)
        # Hertz's contact before any heat: the approach that closes it on average.
        elastic = self.g0 + ops.flamant @ p0
        D0 = float(np.mean(elastic[self.active]))
        self.state.append(p0, zero, np.where(self.active, 0.0, elastic - D0), zero, zero,
                          np.nan, D0, np.nan, 0)
        self.state.scheme.append(0)

    def _start_steady(self):
        """The steady element solution at ``lam`` on these elements, its far
        temperatures (or its heat partition) held."""
        spec, ops, par, X, h = self.spec, self.ops, self.par, self.X, self.h
        steady = solve_elements(par, spec.lam, domain=spec.window, elements=X.size)
        sops = steady_element_operators(par, X, h)
        ps, qs = steady.pressure, steady.flux
        q1s, q2s = 0.5 * (ps + qs), 0.5 * (ps - qs)
        self.q1s, self.q2s = q1s, q2s
        # The steady fields held for all time, less what the step's own lag adds back.
        self.base_gap = (sops.gap1 @ q1s + sops.gap2 @ q2s) - (ops.gap1 @ q1s + ops.gap2 @ q2s)
        self.base_t1 = sops.theta1 @ q1s - ops.theta1 @ q1s
        self.base_t2 = sops.theta2 @ q2s - ops.theta2 @ q2s
        self.active = steady.active.copy()
        t1, t2 = sops.theta1 @ q1s, sops.theta2 @ q2s
        # The steady state's own temperature difference on its contact.
        C = float(np.mean((t1 - t2)[self.active]))
        D = float(np.mean((self.g0 + sops.Gp @ ps + sops.Gq @ qs)[self.active]))
        self.state.append(ps, qs, steady.gap, t1, t2, spec.lam, D, C, steady.iterations)
        self.state.scheme.append(0)
        self.closure = {"lam": spec.lam} if spec.hold == "lam" else {"theta": C}

    def replay(self, resume) -> int:
        """Take the steps of the partial run ``resume`` as they are (its heat into the
        histories, its states): the run goes on from its last, as if uninterrupted.
        Returns the steps taken."""
        if resume.spec != self.spec:
            raise InputError("the partial run was computed with other inputs",
                             parameters=("resume",))
        done = resume.time.size - 1
        for n in range(1, done + 1):
            self.history.skip(n)
            p, q = resume.pressure[n], resume.flux[n]
            self.history.push(0.5 * (p + q) - self.q1s, 0.5 * (p - q) - self.q2s)
        self.state = _State()
        for n in range(done + 1):
            self.state.append(resume.pressure[n], resume.flux[n], resume.gap[n],
                              resume.theta1[n], resume.theta2[n], resume.lam[n],
                              resume.approach[n], resume.temperature_difference[n],
                              int(resume.set_iterations[n]))
            self.state.scheme.append(int(resume.scheme[n]))
        self.active = resume.pressure[done] > 0.0
        if done:
            p, q = resume.pressure[done], resume.flux[done]
            self.q1_last, self.q2_last = 0.5 * (p + q), 0.5 * (p - q)
        return done

    def step(self, n) -> str | None:
        """Step ``n``: its state appended; or where and why the run stops (the state
        not appended)."""
        spec, ops, h = self.spec, self.ops, self.h
        X, tol = self.X, self.TOL
        y1, y2 = self.history.known(n)
        gap_known = self.g0 + self.base_gap + y1[0] + y2[0]
        t1_known = self.base_t1 + y1[1]
        t2_known = self.base_t2 + y2[1]
        load = 1.0 + spec.perturb if n == 1 else 1.0
        # First the step with its own thermal bulge from the last step's heat (IMEX,
        # eq. R10): the contact is then elastic, a convex problem with one solution.
        # Then the implicit step (R9) from its contact set, which the IMEX one replaces
        # where the implicit one has no settled contact set on these elements.
        bulge = ops.gap1 @ self.q1_last + ops.gap2 @ self.q2_last
        try:
            p, gap, D, active, it = _contact(ops.flamant, gap_known + bulge, h, self.active,
                                             load, tol)
        except SolveError as exc:
            return f"at step {n}: {exc}"
        try:
            q, C = _partition(ops, p, t1_known - t2_known, h, active, self.closure,
                              self.resistance(p))
        except np.linalg.LinAlgError:
            return f"at step {n}: the heat on the contact set is singular"
        scheme = 1
        try:
            p, q, gap, D, C, more, chatter = _coupled(ops, gap_known, t1_known - t2_known, h,
                                                      active, load, self.closure,
                                                      self.resistance, p, tol)
            it += more
            scheme = 0 if chatter == 0 else 2
        except SolveError:
            # The IMEX state's gap with its own heat (R9's left side; it may be negative
            # where the explicit bulge let the surfaces overlap).
            gap = (gap_known + ops.gap1 @ (0.5 * (p + q)) + ops.gap2 @ (0.5 * (p - q))
                   + ops.flamant @ p - D)
            gap[active] = 0.0
        active = p > 0.0
        self.active = active
        if (active[0] or active[-1]) and n == 1:
            # Before any step there is no heat to report (a partition of 0/0): the window
            # is refused, as an input.
            raise InputError(f"window must hold the contact through the first step, got "
                             f"{spec.window!r}: the contact reached an end of it at once "
                             f"(x = {X[0] if active[0] else X[-1]:.4g}); widen it or give "
                             f"more elements", parameters=("window",))
        if active[0] or active[-1]:
            return (f"at step {n}: the contact reached the window's end "
                    f"(x = {X[0] if active[0] else X[-1]:.4g}); give a wider window")
        q1, q2 = 0.5 * (p + q), 0.5 * (p - q)
        self.q1_last, self.q2_last = q1, q2
        self.history.push(q1 - self.q1s, q2 - self.q2s)
        t1 = t1_known + ops.theta1 @ q1
        t2 = t2_known + ops.theta2 @ q2
        lam = float(np.sum(q) / np.sum(p))
        self.state.append(p, q, gap, t1, t2, lam, D, C, it)
        self.state.scheme.append(scheme)
        return None

    def result(self, status, message, seconds) -> TransientRun:
        """The run so far."""
        state = self.state
        return TransientRun(self.spec, self.spec.dt * np.arange(len(state.pressure)), self.X,
                            np.array(state.pressure), np.array(state.flux), np.array(state.gap),
                            np.array(state.theta1), np.array(state.theta2),
                            np.array(state.lam, dtype=float),
                            np.array(state.approach, dtype=float),
                            np.array(state.difference, dtype=float),
                            np.array(state.iterations, dtype=int),
                            np.array(state.scheme, dtype=int), status, seconds, message)
