"""Maps of the single-patch solution over a grid of two parameters.

A map evaluates :meth:`Model.solve <thermocontact.solvers.single_patch.Model.solve>`
at every point of a grid ``x × y`` of two dimensionless parameters, the others
fixed, and locates where validity changes along the grid's lines.  The work is
cut into chunks, one grid line each, along the axis that keeps the assembly
(``fhpe``, ``lam`` or ``sigma_over_delta``; derivation section 5) when there is
one: a chunk costs one assembly per resolution and a linear solve per point.
Chunks run wherever :func:`thermocontact.execution.executors.run` sends them and
are kept on disk as they finish (:class:`~thermocontact.io.chunks.ChunkStore`), so
an interrupted map resumes where it stopped and ends identical to an
uninterrupted one.

The existence boundary is located on every grid line by Brent's method on the
margin that changes sign (:func:`~.boundaries.locate_events`), to ``rtol``
relative along the line: its position along that axis does not depend on the
grid's spacing.
"""

from __future__ import annotations

import json
import math
import warnings
from dataclasses import dataclass, field

import numpy as np

from .._version import __version__
from ..discretisation.methods import DEFAULT_METHOD, METHODS
from ..execution.resumable import run_chunks
from ..numerics.continuation import interpolated_root, locate, widen
from ..problem.parameters import ConvergenceWarning, SolveError
from ..problem.axes import MAX_AXIS_POINTS, Axis
from ..problem.validation import (InputError, check_choice, check_finite, check_positive)
from .boundaries import (ALONG, SPELLINGS, check_problem, closure, locate_events, model_for,
                         validity_margins)

__all__ = ["Axis", "MAX_AXIS_POINTS", "MapSpec", "compute_map", "evaluate_chunk", "parse_axis",
           "prepare_dataset"]

#: Parameter names a dimensionless map accepts: the command line's and Python's.
NAMES = {**SPELLINGS, **{name: name for name in ALONG}}
#: Axes along which the assembly is kept: a grid line along one is one chunk.
CHEAP = ("fhpe", "lam", "sigma_over_delta")
#: Most points in a map (and MAX_AXIS_POINTS on one axis).
MAX_POINTS = 1_000_000
#: Default error target of a map's solutions.
MAP_TOL = 1e-6
#: Relative tolerance of the boundary along a grid line.
BOUNDARY_RTOL = 1e-9
#: Between grid lines the boundary is traced further where it bends: a segment whose
#: middle deviates from the straight line by more than CURVE_TOL of the chunk axis's
#: span (in its own scale, log or linear) gets a point on the line halfway, located
#: like the grid lines' own, at most CURVE_DEPTH times over.
CURVE_TOL = 1e-3
CURVE_DEPTH = 3
#: Fields of each point, in the dataset's order.
FIELDS = ("load_ratio", "sigma_over_delta", "lam", "valid", "applicable", "pressure_margin",
          "gap_margin", "edge_margin", "error_estimate", "n", "status", "reason")


def parse_axis(option: str, spec, names=NAMES) -> Axis:
    """An :class:`Axis` from ``name:start:stop:count[:log]`` (:meth:`Axis.parse`), its
    name one of ``names`` (a spelling of the command line's taken to Python's).

    Raises
    ------
    InputError
        Naming ``option``: an unknown parameter, values that are not numbers, a
        reversed or empty range, fewer than 2 or more than :data:`MAX_AXIS_POINTS`
        points, a log axis that does not stay positive, or a bad fifth field.
    """
    if isinstance(spec, str):
        check_axis_name(option, spec.split(":", 1)[0].strip(), names)
    axis = Axis.parse(spec, option)
    return axis.renamed(names[axis.name])


def check_axis_name(option: str, name, names=NAMES) -> str:
    """``name`` if it is one of ``names``, else :class:`InputError` naming ``option``."""
    if name not in names:
        allowed = sorted({k for k in names if "_" not in k} or names)
        raise InputError(f"{option} parameter must be one of {', '.join(allowed)}, got {name!r}",
                         parameters=(option,))
    return name


@dataclass(frozen=True)
class MapSpec:
    """A dimensionless map: two axes, the fixed inputs, the method and the target.

    Parameters
    ----------
    x, y : Axis
    fixed : dict
        The other inputs of :func:`~thermocontact.solvers.single_patch.solve`
        (``pe``, ``fhpe``, ``K2_over_K1``, optionally ``k2_over_k1`` and
        ``delta1_over_delta2`` and ``speed_ratio``, and ``lam`` or
        ``sigma_over_delta`` unless an axis is one of them).
    method : str
    tol : float
        Error target of every point.
    delta_over_r : float, optional
        Half-width over radius, for the theory's applicability (not assessed without).
    """

    x: Axis
    y: Axis
    fixed: dict
    method: str = DEFAULT_METHOD
    tol: float = MAP_TOL
    delta_over_r: float | None = None
    chunk_points: int = field(default=256, repr=False)

    def __post_init__(self):
        for key in ("x", "y"):
            axis = getattr(self, key)
            if not isinstance(axis, Axis):
                raise InputError(f"{key} must be an Axis, got {axis!r}")
            name = NAMES[check_axis_name(key, axis.name)]
            if name != axis.name:  # "sigma" -> "sigma_over_delta"
                object.__setattr__(self, key, axis.renamed(name))
        if self.x.name == self.y.name:
            raise InputError(f"y must name a parameter other than x's, got "
                             f"{self.y.name!r} twice", parameters=("y", "x"))
        if self.x.count * self.y.count > MAX_POINTS:
            raise InputError(f"the grid must have at most {MAX_POINTS} points, got "
                             f"{self.x.count} x {self.y.count}")
        check_choice("method", self.method, METHODS)
        check_positive("tol", self.tol)
        if self.delta_over_r is not None:
            check_positive("delta_over_r", self.delta_over_r)
        axes = {self.x.name, self.y.name}
        fixed = {k: v for k, v in self.fixed.items() if v is not None and k not in axes}
        fixed = {k: check_finite(k, v) for k, v in fixed.items()}
        for k in ("pe", "fhpe", "K2_over_K1"):
            if k not in axes and k not in fixed:
                raise InputError(f"{k} must be given (it is not an axis)", parameters=(k,))
        closures = [k for k in ("lam", "sigma_over_delta", "theta") if k in fixed or k in axes]
        if len(closures) != 1:
            raise InputError("give exactly one of lam and sigma (or theta), or make one of "
                             "them an axis", parameters=("lam", "sigma", "theta"))
        if "sink_distance" in fixed and closures != ["theta"]:
            raise InputError("sink_distance is given with theta only (section 17)",
                             parameters=("sink_distance", "theta"))
        object.__setattr__(self, "fixed", fixed)
        # Every parameter's range is an interval: the grid's corners check them all.
        for xv in (self.x.start, self.x.stop):
            for yv in (self.y.start, self.y.stop):
                kw = {**fixed, self.x.name: xv, self.y.name: yv}
                check_problem(kw, self.method)

    @property
    def inner(self) -> str:
        """``"x"`` or ``"y"``: the axis each chunk runs along."""
        return "y" if self.y.name in CHEAP and self.x.name not in CHEAP else "x"

    def tasks(self) -> list[dict]:
        """The chunks: grid lines along :attr:`inner`, each cut into pieces of at most
        ``chunk_points`` points."""
        inner, outer = (self.x, self.y) if self.inner == "x" else (self.y, self.x)
        values = inner.values
        pieces = max(1, math.ceil(values.size / self.chunk_points))
        cuts = np.array_split(np.arange(values.size), pieces)
        out = []
        for j, v in enumerate(outer.values):
            for cut in cuts:
                out.append({"fixed": {**self.fixed, outer.name: float(v)}, "name": inner.name,
                            "values": [float(u) for u in values[cut]], "outer": j,
                            "start": int(cut[0]), "method": self.method, "tol": self.tol,
                            "delta_over_r": self.delta_over_r})
        return out

    def manifest(self) -> dict:
        """What identifies the map: equal manifests, equal maps."""
        return {"kind": "thermocontact map", "version": __version__, "x": self.x.spec,
                "y": self.y.spec, "fixed": self.fixed, "method": self.method, "tol": self.tol,
                "delta_over_r": self.delta_over_r, "chunk_points": self.chunk_points}


def _record(sol, delta_over_r) -> dict:
    v = sol.validity
    applicable = -1
    if delta_over_r is not None:
        from ..analysis.applicability import applicability

        applicable = int(applicability(sol, delta_over_r).applicable)
    reason = v.reason
    if not v.certain():
        reason += (f" (a margin is within its change since n/2, {v.margin_change:.1e}: its "
                   f"sign is not certain)")
    return {"load_ratio": sol.load_ratio, "sigma_over_delta": sol.sigma_over_delta,
            "lam": sol.lam, "valid": int(v.valid), "applicable": applicable,
            "pressure_margin": v.pressure_margin, "gap_margin": v.gap_margin,
            "edge_margin": min(v.edge_margins),
            "error_estimate": (float("nan") if sol.error_estimate is None
                               else sol.error_estimate),
            "n": sol.n, "status": sol.status, "reason": reason}


def _failed(exc) -> dict:
    nan = float("nan")
    return {"load_ratio": nan, "sigma_over_delta": nan, "lam": nan, "valid": 0,
            "applicable": -1, "pressure_margin": nan, "gap_margin": nan, "edge_margin": nan,
            "error_estimate": nan, "n": 0, "status": "failed", "reason": str(exc)}


def evaluate_chunk(task: dict) -> dict:
    """Solve the points of one chunk and locate the changes of validity between them.

    Returns
    -------
    dict
        ``{field: list}`` for every field of :data:`FIELDS`, and ``events``: the
        changes of validity along the chunk, each ``{"at", "inequality", "edge",
        "valid_before", "valid_after", "position"}``.
    """
    fixed, name, values = task["fixed"], task["name"], task["values"]
    method, tol = task["method"], task["tol"]
    out = {k: [] for k in FIELDS}
    with warnings.catch_warnings():
        # The status records it.
        warnings.simplefilter("ignore", ConvergenceWarning)
        if name in CHEAP:
            # One model along the line: its points solved together (Model.solve_many).
            try:
                found = model_for(fixed, method, tol).solve_many(
                    list(values) if name == "fhpe" else fixed["fhpe"], polish=False,
                    # The map keeps no rcond: proven well-conditioned is enough (the
                    # same points are refused).
                    rcond="bound",
                    **({name: list(values)} if name in ("lam", "sigma_over_delta")
                       else closure(fixed)))
            except (SolveError, InputError) as exc:
                found = [exc] * len(values)
        else:
            found = []
            for value in values:
                kw = {**fixed, name: float(value)}
                try:
                    found.append(model_for(kw, method, tol).solve(kw["fhpe"], polish=False,
                                                                  **closure(kw)))
                except (SolveError, InputError) as exc:
                    found.append(exc)
    sols = []
    for sol in found:
        if isinstance(sol, Exception):
            sol, rec = None, _failed(sol)
        else:
            rec = _record(sol, task["delta_over_r"])
        sols.append(sol)
        for k in FIELDS:
            out[k].append(rec[k])
    out["events"] = _events(fixed, name, values, sols, method, tol)
    return out


def _events(fixed, name, values, sols, method, tol):
    """Changes of validity between neighbouring solved points
    (:func:`~.boundaries.locate_events`)."""
    def xtol(p, q):
        return BOUNDARY_RTOL * max(abs(p), abs(q), 1e-300)

    events = []
    for i, (a, b, sa, sb) in enumerate(zip(values[:-1], values[1:], sols[:-1], sols[1:])):
        if sa is None or sb is None or sa.valid == sb.valid:
            continue
        n = max(sa.n, sb.n)

        def at(x, n=n):
            kw = {**fixed, name: float(x)}
            try:
                return model_for(kw, method, tol).solve_at(n, kw["fhpe"], polish=False,
                                                        **closure(kw))
            except InputError:
                return None
        # A point solved at the event's n is its end as solve_at gives it (the margins
        # are the same numbers: the map's points are solved without polish).
        ends = [s if s.n == n else at(x) for s, x in ((sa, a), (sb, b))]
        if ends[0] is None or ends[1] is None:
            continue
        # Brent's method starts from the ends without solving there again: at(x) is
        # what they are (a line's points depend on nothing but their own x and n).
        known = {a: ends[0], b: ends[1]}
        # Brent's first point: the margin's zero interpolated through the ends and the
        # samples beyond them solved at the same n (about h^4 off), where it is likely
        # within the tolerance (then two solves instead of three or four).
        samples = {i - 1: sols[i - 1] if i > 0 else None, i: ends[0], i + 1: ends[1],
                   i + 2: sols[i + 2] if i + 2 < len(sols) else None}
        around = [(values[j], s) for j, s in samples.items() if s is not None and s.n == n]

        def guesses(p, q, k, around=around):
            return interpolated_root([x for x, _ in around],
                                     [validity_margins(s)[k] for _, s in around], xtol(p, q))
        found = locate_events(lambda x: known[x] if x in known else at(x), [a, b], ends,
                              only_validity_changes=True, xtol=xtol, guesses=guesses)
        events += [e.to_dict() for e in found]
    return events


def _between_lines(spec: MapSpec, boundary, n_grid):
    """Points of the boundary between grid lines where it bends (:data:`CURVE_TOL`).

    Boundary points are grouped by inequality, edge and direction; where a group has
    one point on each of three neighbouring lines and the middle one is off the chord
    of the outer two by more than ``CURVE_TOL`` of the chunk axis's span, each of the
    two segments gets a point on the line halfway between its lines, located by
    Brent's method on that inequality's margin near the chord (at the larger ``n`` of
    the two lines), and so on to ``CURVE_DEPTH`` levels.  The tolerance compares
    positions in the axes' own scales (log or linear).
    """
    inner, outer = (spec.x, spec.y) if spec.inner == "x" else (spec.y, spec.x)
    fwd_i = (lambda v: math.log(v)) if inner.log else float
    inv_i = math.exp if inner.log else float
    fwd_o = (lambda v: math.log(v)) if outer.log else float
    inv_o = math.exp if outer.log else float
    span = abs(fwd_i(inner.stop) - fwd_i(inner.start))
    lo_i, hi_i = sorted((fwd_i(inner.start), fwd_i(inner.stop)))
    n_lines = np.asarray(n_grid, dtype=float)
    n_lines = np.nanmax(np.where(n_lines > 0, n_lines, np.nan), axis=1 if spec.inner == "x" else 0)
    outer_index = {float(v): j for j, v in enumerate(outer.values)}
    groups = {}
    for b in boundary:
        u, v = (b[0], b[1]) if spec.inner == "x" else (b[1], b[0])
        groups.setdefault(b[2:6], {}).setdefault(outer_index[float(v)], []).append(u)
    added = []

    def bend(key, ua, va, ub, vb, n, depth):
        vm, up = 0.5 * (va + vb), 0.5 * (ua + ub)
        fixed = {**spec.fixed, outer.name: inv_o(vm)}

        def margin(u):
            kw = {**fixed, inner.name: inv_i(u)}
            try:
                sol = model_for(kw, spec.method, spec.tol).solve_at(
                    n, kw["fhpe"], polish=False, **closure(kw))
            except (SolveError, InputError):
                return math.nan
            return {"load": sol.load_ratio, **sol.validity.margins()}[key[0]]
        found = widen(margin, up, max(abs(ua - ub), span / 1000), lo_i, hi_i, factor=2.0,
                      tries=8)
        if found is None:
            return
        a, b = found
        try:
            um = locate(margin, a, b, xtol=BOUNDARY_RTOL * max(abs(a), abs(b), 1e-300))
        except (ValueError, RuntimeError):
            return
        x = inv_i(um)
        point = (x, inv_o(vm)) if spec.inner == "x" else (inv_o(vm), x)
        added.append((*point, *key, 1))
        if depth < CURVE_DEPTH and abs(um - up) > CURVE_TOL * span:
            bend(key, ua, va, um, vm, n, depth + 1)
            bend(key, um, vm, ub, vb, n, depth + 1)

    for key, lines in groups.items():
        single = {j: fwd_i(us[0]) for j, us in lines.items() if len(us) == 1}
        marked = set()
        for j in single:
            if j - 1 in single and j + 1 in single:
                v0, v1, v2 = (fwd_o(outer.values[k]) for k in (j - 1, j, j + 1))
                u0, u1, u2 = single[j - 1], single[j], single[j + 1]
                chord = u0 + (u2 - u0) * (v1 - v0) / (v2 - v0)
                if abs(u1 - chord) > CURVE_TOL * span:
                    marked |= {j - 1, j}
        for j in sorted(marked):
            n = int(max(n_lines[j], n_lines[j + 1]))
            bend(key, single[j], fwd_o(outer.values[j]), single[j + 1],
                   fwd_o(outer.values[j + 1]), n, 1)
    return added


def _dataset(spec: MapSpec, chunks: dict, command: str | None):
    """The map as an :class:`xarray.Dataset` from its chunks (by task index)."""
    import xarray as xr

    xs, ys = spec.x.values, spec.y.values
    shape = (ys.size, xs.size)
    data = {k: np.empty(shape, dtype=object) for k in FIELDS}
    boundary = []
    for i, task in enumerate(spec.tasks()):
        chunk = chunks[i]
        j, k0 = task["outer"], task["start"]
        idx = np.arange(k0, k0 + len(task["values"]))
        for k in FIELDS:
            col = np.empty(len(chunk[k]), dtype=object)
            col[:] = chunk[k]
            if spec.inner == "x":
                data[k][j, idx] = col
            else:
                data[k][idx, j] = col
        outer_value = task["fixed"][(spec.y if spec.inner == "x" else spec.x).name]
        for e in chunk["events"]:
            xy = (e["at"], outer_value) if spec.inner == "x" else (outer_value, e["at"])
            boundary.append((*xy, e["inequality"], e["edge"] or "", int(e["valid_before"]),
                             int(e["valid_after"]), 0))
    boundary += _between_lines(spec, boundary, data["n"])
    dtypes = {"valid": np.int8, "applicable": np.int8, "n": np.int32, "status": str,
              "reason": str}
    dims = (spec.y.name, spec.x.name)
    # A closure on an axis (lam, sigma_over_delta) is that axis's coordinate: the field
    # of the same name would repeat it, and xarray refuses a name in both.
    variables = {k: (dims, data[k].astype(dtypes.get(k, float))) for k in FIELDS
                 if k not in dims}
    variables["boundary_x"] = ("event", np.array([b[0] for b in boundary], dtype=float))
    variables["boundary_y"] = ("event", np.array([b[1] for b in boundary], dtype=float))
    variables["boundary_inequality"] = ("event", np.array([b[2] for b in boundary], dtype=str))
    variables["boundary_edge"] = ("event", np.array([b[3] for b in boundary], dtype=str))
    variables["boundary_valid_before"] = ("event", np.array([b[4] for b in boundary],
                                                             dtype=np.int8))
    variables["boundary_valid_after"] = ("event", np.array([b[5] for b in boundary],
                                                            dtype=np.int8))
    variables["boundary_between_lines"] = ("event", np.array([b[6] for b in boundary],
                                                             dtype=np.int8))
    ds = xr.Dataset(variables, coords={spec.y.name: ys, spec.x.name: xs})
    ds = _describe(ds, spec, command)
    return ds


_DESCRIPTIONS = {
    "load_ratio": "P_H/P: Hertz load of the contact's half-width over the load",
    "sigma_over_delta": "contact offset sigma/Delta",
    "lam": "heat partition (Q1 - Q2)/(Q1 + Q2)",
    "valid": "1 where every contact inequality holds",
    "applicable": "1 where the theory applies, 0 where not, -1 not assessed (no delta_over_r)",
    "pressure_margin": "least p/sqrt(1 - s^2) over the contact, or p/((1 - s)^alpha "
                       "(1 + s)^(1 - alpha)) with the Dundurs term (< 0: tensile)",
    "gap_margin": "least g/(|s| - 1)^1.5 outside the contact, or ^(1 + the edge's "
                  "exponent) with the Dundurs term (< 0: interpenetration)",
    "edge_margin": "least edge-layer margin (derivation sections 8 and 5c; < 0: tensile "
                   "layer wider than 1e-6 half-widths)",
    "error_estimate": "estimated error of P_H/P and sigma/Delta",
    "n": "unknowns per function",
    "status": "converged, not converged, or failed",
    "reason": "the validity verdict, or why the point failed",
    "boundary_x": "x of the changes of validity, located to 1e-9 relative along the chunk axis",
    "boundary_y": "y of the changes of validity",
    "boundary_inequality": "the inequality whose margin changes sign",
    "boundary_edge": "where it fails: leading, trailing, or empty (the load)",
    "boundary_valid_before": "validity before the change, along the chunk axis",
    "boundary_valid_after": "validity after the change",
    "boundary_between_lines": "1 for points traced between grid lines where the boundary "
                              "bends (CURVE_TOL), located like those on the lines",
}


def _describe(ds, spec: MapSpec, command):
    for k, text in _DESCRIPTIONS.items():
        if k in ds:
            ds[k].attrs["long_name"] = text
    ds["boundary_x"].attrs["parameter"] = spec.x.name
    ds["boundary_y"].attrs["parameter"] = spec.y.name
    ds["applicable"].attrs.update(flag_values=np.array([-1, 0, 1], dtype=np.int8),
                                  flag_meanings="not_assessed not_applicable applicable")
    ds.attrs.update({
        "title": "thermocontact map of the single-patch solution",
        "thermocontact_version": __version__,
        "method": spec.method,
        "tol": spec.tol,
        "x": spec.x.spec,
        "y": spec.y.spec,
        "chunk_axis": spec.inner,
        "boundary_rtol": BOUNDARY_RTOL,
        "command": command or "",
        "manifest": json.dumps(spec.manifest(), sort_keys=True),
    })
    for k, v in spec.fixed.items():
        ds.attrs[k] = v
    if spec.delta_over_r is not None:
        ds.attrs["delta_over_r"] = spec.delta_over_r
    return ds


def compute_map(spec: MapSpec, *, workers=1, store_path=None, progress=None, command=None):
    """Evaluate a map, keeping finished chunks in ``store_path`` (resumed if present).

    Parameters
    ----------
    spec : MapSpec
    workers : int, None, executor, dask Client or callable
        Where the chunks run (:func:`thermocontact.execution.executors.run`).
    store_path : str, optional
        Folder of the finished chunks; without one nothing is kept on disk.
    progress : callable, optional
        ``progress(done, total)`` in chunks.
    command : str, optional
        Recorded in the dataset's attributes.

    Returns
    -------
    xarray.Dataset
    """
    chunks = run_chunks(evaluate_chunk, spec.tasks(), spec.manifest(), store_path,
                        workers=workers, progress=progress, meanwhile=prepare_dataset)
    return _dataset(spec, chunks, command)


def prepare_dataset():
    """Import xarray and make a first dataset: the first costs about a second (xarray
    imports dask, where installed, to recognise its arrays), which a run with workers
    elsewhere spends while they compute (:func:`~thermocontact.execution.resumable.
    run_chunks`)."""
    import xarray as xr

    xr.Dataset({"a": ("x", np.zeros(1))}, coords={"x": [0.0]})
