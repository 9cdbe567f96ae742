"""Command line: a thin layer over :func:`thermocontact.solve`.

Errors in the input or the solve are reported on one line of standard error with
exit status 2; nothing here raises a traceback for bad input.
"""

from __future__ import annotations

import json
import os
import sys

import click
import numpy as np

from ._version import __version__
from .discretisation.methods import DEFAULT_METHOD, METHODS
from .problem.parameters import SolveError
from .problem.validation import InputError, check_positive
from .solvers.single_patch import DEFAULT_TOL, solve

__all__ = ["main"]


class _Progress:
    """Refinement progress on standard error, a line per level once a solve has run 2 s."""

    AFTER = 2.0
    #: A level this large takes seconds by itself: announced at once.
    LARGE_N = 512

    def __init__(self):
        import time

        self._clock = time.perf_counter
        self._start = self._clock()

    def __call__(self, n, estimate):
        elapsed = self._clock() - self._start
        if elapsed < self.AFTER and n < self.LARGE_N:
            return
        est = "" if estimate is None else f", error estimate so far {estimate:.1e}"
        click.echo(f"solving at n = {n}{est} ({elapsed:.0f} s elapsed)", err=True)


def _summary(sol) -> str:
    par = sol.parameters
    v = sol.validity
    alpha = par.edge_exponent
    if alpha == 0.5:
        weight, power = "p/sqrt(1-s^2)", "1.5"
    else:  # the Dundurs term's exponents (derivation section 5c)
        weight = f"p/((1-s)^{alpha:.4g} (1+s)^{1 - alpha:.4g})"
        power = f"{1 + (alpha if v.gap_margin_at > 0 else 1 - alpha):.4g}"
    lines = [
        f"thermocontact {__version__}: method {sol.method}, n = {sol.n}",
        f"  Pe = {par.pe:g}, fHPe = {par.fhpe:g}, K2/K1 = {par.K2_over_K1:g}, "
        f"k2/k1 = {par.k2_over_k1:g}, delta1/delta2 = {par.delta1_over_delta2:g}"
        + (f", v2/v1 = {par.speed_ratio:g}" if par.speed_ratio else "")
        + (f", beta f = {par.beta_f:g} (edge exponents {1 - par.edge_exponent:.4g}, "
           f"{par.edge_exponent:.4g})" if par.beta_f else ""),
        f"  {sol.status}: {sol.estimate_message} (n {'chosen' if sol.auto_n else 'given'})",
        f"  P_H/P         = {sol.load_ratio:.10g}",
        f"  lambda        = {sol.lam:.10g}",
        f"  sigma/Delta   = {sol.sigma_over_delta:.10g}",
    ]
    if sol.load_ratio_change is not None:
        lines.append(f"  |P_H/P(2n) - P_H/P(n)| = {sol.load_ratio_change:.2e}")
    lines += [
        f"  valid         = {v.valid}" + ("" if v.reason == "valid" else f"  ({v.reason})"),
        f"  min pressure  = {v.min_pressure:.4g} at s = {v.min_pressure_at:.4f}"
        f"  (margin {weight} = {v.pressure_margin:.4g} at s = {v.pressure_margin_at:.4f})",
        f"  min gap       = {v.min_gap:.4g} Delta^2/R at s = {v.min_gap_at:.4f}"
        f"  (margin g/(|s|-1)^{power} = {v.gap_margin:.4g} at s = {v.gap_margin_at:.4f})",
        f"  load positive = {v.positive_load}",
    ]
    return "\n".join(lines)


@click.group(context_settings={"help_option_names": ["-h", "--help"]})
@click.version_option(__version__, prog_name="thermocontact")
def cli():
    """Thermoelastic sliding contact of a conducting cylinder on a conducting half-plane."""


def _problem_options(required: bool):
    """The dimensionless problem's options, shared by ``solve`` and ``boundary`` (where
    the parameter followed is not given, so none is required)."""
    unless = "" if required else " (unless followed)"
    options = [
        click.option("--pe", type=float, required=required,
                     help=f"Peclet number v Delta/(2 k2) > 0{unless}."),
        click.option("--fhpe", type=float, required=required,
                     help=f"Thermoelastic coupling f H Pe >= 0{unless}."),
        click.option("--K2-over-K1", "K2_over_K1", type=float, required=required,
                     help=f"Conductivity ratio K2/K1 > 0{unless}."),
        click.option("--k2-over-k1", "k2_over_k1", type=float, default=None,
                     help="Diffusivity ratio k2/k1 > 0 [default: K2/K1]."),
        click.option("--delta1-over-delta2", type=float, default=1.0, show_default=True,
                     help="Distortivity ratio delta1/delta2 >= 0."),
        click.option("--speed-ratio", "speed_ratio", type=float, default=0.0,
                     show_default=True,
                     help="v2/v1: the half-plane's surface speed through the contact over the "
                          "cylinder's, positive in the same direction; 0 is a stationary "
                          "half-plane. Pe is made with v1, fHPe with the sliding speed "
                          "|v1 - v2|. With --cylinder (boundary, map), --speed is v1."),
        click.option("--beta-f", "beta_f", type=float, default=0.0, show_default=True,
                     help="B = beta f, beta = [(1 - 2 nu1)/mu1 - (1 - 2 nu2)/mu2]/A (the "
                          "paper's eq. 10): the Dundurs term -(B/2) p of the contact "
                          "equation; 0 drops it, as the paper does. |B| <= 20; graded "
                          "methods only."),
        click.option("--lam", type=float, default=None,
                     help="Heat partition (Q1 - Q2)/(Q1 + Q2); give this or --sigma."),
        click.option("--sigma", type=float, default=None,
                     help="Contact offset sigma/Delta; give this or --lam."),
    ]

    def deco(func):
        for option in reversed(options):
            func = option(func)
        return func
    return deco


def _physical_options(required: bool):
    """The physical problem's options, shared by ``contact`` and, where they select the
    physical variant and the parameter followed or mapped is left out, by ``boundary``
    and ``map``."""
    unless = "" if required else " (physical variant; unless followed or an axis)"
    options = [
        click.option("--cylinder", required=required, default=None,
                     help="Material of the sliding cylinder: a name or "
                          "E=..,nu=..,alpha=..,K=..,k=.." + (
                              "" if required else " (selects the physical variant)")),
        click.option("--half-plane", "half_plane", required=required, default=None,
                     help="Material of the stationary half-plane."),
        click.option("--materials", "materials_file", default=None,
                     help="TOML file adding or overriding materials."),
        click.option("--radius", required=required, default=None,
                     help=f"Cylinder radius (m, or with units: 450mm){unless}."),
        click.option("--load", required=required, default=None,
                     help=f"Load per unit length (N/m, or 200kN/m){unless}."),
        click.option("--speed", required=required, default=None,
                     help=f"Sliding speed (m/s, or 72km/h){unless}."),
        click.option("--friction", type=float, required=required, default=None,
                     help=f"Coefficient of friction >= 0{unless}."),
        click.option("--dundurs/--no-dundurs", default=None,
                     help="Keep (default) or drop, as the paper does, the Dundurs term "
                          "-(beta f/2) p, beta from the two materials' nu and E "
                          "(derivation section 5c)."),
    ]

    def deco(func):
        for option in reversed(options):
            func = option(func)
        return func
    return deco


def _contact_set_options(zones_help: str, p_ref_help: str):
    """``--zones`` and ``--conductance`` of the physical commands (``contact``, ``map``),
    which differ only in what the flag adds and what an omitted ``p_ref`` means."""
    zones = click.option("--zones", "zones", is_flag=True, help=zones_help)
    conductance = click.option(
        "--conductance", default=None,
        help="With --zones: h0:m[:p_ref], an interface conductance h = h0 (p/p_ref)^m, h0 "
             "in W/(m^2 K), m >= 0, p_ref in Pa or with units (" + p_ref_help + ") "
             "[default: perfect thermal contact].")
    return lambda func: zones(conductance(func))


@cli.command("solve")
@_problem_options(required=True)
@click.option("-n", "n", type=int, default=None,
              help="Unknowns per function [default: chosen, doubling over the method's "
                   "range (" + "; ".join(f"{m.name} {m.auto_range[0]}-{m.auto_range[1]}"
                                         for m in METHODS.values()) +
                   ") until the error estimate is below --tol].")
@click.option("--tol", type=float, default=DEFAULT_TOL, show_default=True,
              help="Target of the error estimate when n is chosen.")
@click.option("--method", type=click.Choice(sorted(METHODS)), default=DEFAULT_METHOD,
              show_default=True,
              help="Discretisation: " + "; ".join(f"{m.name}: {m.summary}"
                                                   for m in METHODS.values()) + ".")
@click.option("--check", is_flag=True, help="Also solve with 2n and report the change in P_H/P.")
@click.option("--delta-over-r", "delta_over_r", type=float, default=None,
              help="Half-width over cylinder radius, > 0: also say whether the theory applies "
                   "(small contact, slopes and strains).")
@click.option("--json", "as_json", is_flag=True, help="Print one JSON object.")
def solve_cmd(pe, fhpe, K2_over_K1, k2_over_k1, delta1_over_delta2, speed_ratio, beta_f, lam,
              sigma, n, tol, method, check, delta_over_r, as_json):
    """Solve one case in dimensionless form."""
    if (lam is None) == (sigma is None):
        raise InputError("give exactly one of --lam and --sigma")
    sol = solve(pe, fhpe, K2_over_K1, k2_over_k1=k2_over_k1,
                delta1_over_delta2=delta1_over_delta2, speed_ratio=speed_ratio, beta_f=beta_f,
                lam=lam,
                sigma_over_delta=sigma, n=n, method=method, tol=tol,
                check_convergence=check, progress=_Progress())
    app = None
    if delta_over_r is not None:
        from .analysis.applicability import applicability

        app = applicability(sol, check_positive("delta_over_r", delta_over_r))
    if as_json:
        rec = sol.to_dict()
        if app is not None:
            rec.update(app.to_dict())
        click.echo(json.dumps(rec, allow_nan=False))
    else:
        text = _summary(sol)
        if app is not None:
            text += ("\n  theory applicable: yes" if app.applicable else
                     "\n  theory NOT applicable: " + "; ".join(app.reasons))
        click.echo(text)


@cli.command("boundary")
@click.option("--along", required=True,
              help="The parameter followed: fhpe, pe, lam, sigma, K2-over-K1, k2-over-k1, "
                   "delta1-over-delta2, speed-ratio, beta-f; or, with --cylinder and --half-plane, load, speed, "
                   "radius or friction.")
@click.option("--from", "start", required=True,
              help="Start of the path (physical parameters in SI units or with units).")
@click.option("--to", "stop", required=True, help="End of the path.")
@_problem_options(required=False)
@_physical_options(required=False)
@click.option("--tol", type=float, default=DEFAULT_TOL, show_default=True,
              help="Error target for the choice of n.")
@click.option("-n", "n", type=int, default=None,
              help="Unknowns per function of the whole path (default: chosen by --tol); "
                   "each event's error estimate compares with n/2.")
@click.option("--method", type=click.Choice(sorted(METHODS)), default=DEFAULT_METHOD,
              show_default=True, help="Discretisation method (dimensionless paths).")
@click.option("--json", "as_json", is_flag=True, help="Print one JSON object.")
def boundary_cmd(along, start, stop, pe, fhpe, K2_over_K1, k2_over_k1, delta1_over_delta2,
                 speed_ratio, beta_f, lam, sigma, cylinder, half_plane, materials_file, radius, load, speed,
                 friction, dundurs, tol, n, method, as_json):
    """Every change of validity along one parameter, located to 1e-9 relative."""
    from .studies.boundaries import SPELLINGS as names, follow

    physical = {"cylinder": cylinder, "half_plane": half_plane, "radius": radius,
                "load": load, "speed": speed, "friction": friction, "dundurs": dundurs}
    tol = check_positive("tol", tol)
    bar = _StageProgress(f"boundary along {along}")
    if cylinder is not None or half_plane is not None or along in _PHYSICAL_UNITS:
        path = _physical_path(along, start, stop, physical, materials_file, lam, tol, n,
                              {"pe": pe, "fhpe": fhpe, "K2_over_K1": K2_over_K1,
                               "k2_over_k1": k2_over_k1, "sigma": sigma,
                               "speed_ratio": speed_ratio or None,
                               "beta_f": beta_f or None}, bar)
        method = path.method
    else:
        for name, value in physical.items():
            if value is not None:
                raise InputError(f"--{name.replace('_', '-')} belongs to a physical path: "
                                 f"give --cylinder and --half-plane too")
        if along not in names:
            raise InputError(f"--along must be one of {sorted(names) + sorted(_PHYSICAL_UNITS)}"
                             f", got {along!r}")
        name = names[along]
        given = {"pe": pe, "fhpe": fhpe, "K2_over_K1": K2_over_K1, "k2_over_k1": k2_over_k1,
                 "delta1_over_delta2": delta1_over_delta2,
                 "speed_ratio": speed_ratio or None,  # 0, the default, is left out
                 "beta_f": beta_f or None,
                 "lam": lam, "sigma_over_delta": sigma}
        fixed = {k: v for k, v in given.items() if v is not None and k != name}
        for k, option in (("pe", "--pe"), ("fhpe", "--fhpe"), ("K2_over_K1", "--K2-over-K1")):
            if k != name and k not in fixed:
                raise InputError(f"--{option.lstrip('-')} must be given (it is not the "
                                 f"parameter followed)".replace("----", "--"))
        closures = [k for k in ("lam", "sigma_over_delta") if k in fixed or k == name]
        if len(closures) != 1:
            raise InputError("give exactly one of --lam and --sigma, or follow one of them")
        path = follow(fixed, name, _number("--from", start), _number("--to", stop),
                      method=method, tol=tol, n=n, progress=bar)
    bar.close()
    if as_json:
        click.echo(json.dumps(path.to_dict(), allow_nan=False))
        return
    unit = _PHYSICAL_UNITS.get(along, "")
    click.echo(f"thermocontact {__version__}: along {along} from {path.x[0]:g} to "
               f"{path.x[-1]:g}{' ' + unit if unit else ''} (method {method}, n = {path.n}"
               + (f"; events at n = {path.event_n}" if path.event_n != path.n else "") + ")")
    if not path.events:
        click.echo(f"  no change of validity (valid throughout: {bool(path.valid.all())})")
    for e in path.events:
        where = f" at the {e.edge} edge" if e.edge else ""
        err = ("" if e.error_estimate is None else
               f" (discretisation error estimate {e.error_estimate:.1e})")
        click.echo(f"  {along} = {e.at:.10g}{' ' + unit if unit else ''}{err}: "
                   f"{e.inequality}{where}; valid {e.valid_before} -> {e.valid_after}")


#: Physical parameters a path may follow, and their SI units.
_PHYSICAL_UNITS = {"load": "N/m", "speed": "m/s", "radius": "m", "friction": ""}


def _number(option, text) -> float:
    try:
        return float(text)
    except ValueError:
        raise InputError(f"{option} must be a number, got {text!r}") from None


class _StageProgress:
    """``progress(stage, done, total)``: one :class:`ProgressLine` per stage, shown
    once the command has run 2 s."""

    def __init__(self, label):
        import time

        self.label, self.start, self.line, self.stage = label, time.monotonic(), None, None

    def __call__(self, stage, done, total):
        import time

        from .execution.progress import ProgressLine

        if stage != self.stage:
            self.close()
            delay = max(0.0, 2.0 - (time.monotonic() - self.start))
            self.stage, self.line = stage, ProgressLine(f"{self.label}: {stage}", "steps",
                                                         delay=delay)
        self.line(done, total)

    def close(self):
        if self.line is not None:
            self.line.close()


def _physical_path(along, start, stop, physical, materials_file, lam, tol, n, dimensionless,
                   progress=None):
    """The path of ``boundary`` along a physical parameter."""
    from .problem.materials import get_material, load_materials
    from .problem.units import parse_quantity
    from .studies.physical_contact import PhysicalProblem, follow_along

    if along not in _PHYSICAL_UNITS:
        raise InputError(f"--along must be one of {sorted(_PHYSICAL_UNITS)} with --cylinder, "
                         f"got {along!r}")
    # v2/v1 belongs to both variants: the half-plane's surface at R times the cylinder's.
    speed_ratio = dimensionless.pop("speed_ratio", None) or 0.0
    for name, value in dimensionless.items():
        if value is not None:
            raise InputError(f"--{name.replace('_', '-')} belongs to a dimensionless path, "
                             f"not to one with --cylinder")
    for name in ("cylinder", "half_plane", "radius", "load", "speed", "friction"):
        if name != along and physical[name] is None:
            raise InputError(f"--{name.replace('_', '-')} must be given (it is not the "
                             f"parameter followed)")
    if lam is None:
        raise InputError("--lam must be given")
    if materials_file is not None:
        load_materials(materials_file)
    unit = _PHYSICAL_UNITS[along]
    ends = [parse_quantity(v, unit, o) if unit else _number(o, v)
            for o, v in (("--from", start), ("--to", stop))]
    units = {"radius": "m", "load": "N/m", "speed": "m/s"}
    values = {k: (parse_quantity(physical[k], u, k) if k != along else ends[0])
              for k, u in units.items()}
    friction = ends[0] if along == "friction" else physical["friction"]
    prob = PhysicalProblem(get_material(physical["cylinder"], materials_file),
                           get_material(physical["half_plane"], materials_file),
                           values["radius"], values["load"], values["speed"], friction, lam,
                           speed2=values["speed"] * speed_ratio,
                           dundurs=physical.get("dundurs") is not False)
    return follow_along(prob, along, ends[0], ends[1], tol=tol, n=n, progress=progress)


def _operating_spec(x_spec, y_spec, cylinder, half_plane, materials_file, radius, load,
                    speed, friction, lam, tol, dimensionless, dundurs=None, zones=False,
                    conductance=None):
    from .problem.materials import get_material, load_materials
    from .problem.units import parse_quantity
    from .studies.operating_maps import OperatingSpec, parse_physical_axis

    speed_ratio = dimensionless.pop("speed_ratio", None) or 0.0
    for name, value in dimensionless.items():
        if value is not None:
            raise InputError(f"--{name.replace('_', '-')} belongs to a dimensionless map, "
                             f"not to an operating map (--cylinder)")
    for name, value in (("--cylinder", cylinder), ("--half-plane", half_plane),
                        ("--friction", friction), ("--lam", lam)):
        if value is None:
            raise InputError(f"{name} must be given for an operating map")
    if materials_file is not None:
        load_materials(materials_file)
    units = {"radius": (radius, "m"), "load": (load, "N/m"), "speed": (speed, "m/s")}
    fixed = {k: parse_quantity(v, u, k) for k, (v, u) in units.items() if v is not None}
    x, y = parse_physical_axis("--x", x_spec), parse_physical_axis("--y", y_spec)
    for axis in (x, y):
        if axis.name in fixed:
            raise InputError(f"--{axis.name} must not be given: it is an axis")
    return OperatingSpec(get_material(cylinder, materials_file),
                         get_material(half_plane, materials_file), friction, lam, x, y, fixed,
                         tol=check_positive("tol", tol), dundurs=dundurs is not False,
                         speed_ratio=speed_ratio, zones=zones,
                         conductance=_conductance(conductance, "in W/(m^2 K)", physical=True))


def _workers(workers, scheduler):
    """The executor of ``--workers``/``--scheduler`` (a Dask client to be closed, or an int)."""
    from .execution.executors import MAX_WORKERS, connect, cpu_count

    if scheduler is not None:
        if workers is not None:
            raise InputError("give --workers or --scheduler, not both (a cluster has its own)")
        return connect(scheduler)
    if workers is None:
        return cpu_count()
    if not 1 <= workers <= MAX_WORKERS:
        raise InputError(f"--workers must be 1 to {MAX_WORKERS}, got {workers}")
    return workers


def _run_map(spec, out, workers, title, command):
    """Compute (or resume) a map, write the dataset and its picture, keep nothing else."""
    import time

    from .execution.executors import ExecutionError
    from .execution.progress import ProgressLine
    from .plotting.maps import map_figure
    from .studies.maps import compute_map, parts_folder, read_map, write_map

    picture = os.path.splitext(out)[0] + ".png"
    manifest = json.dumps(spec.manifest(), sort_keys=True)
    if os.path.exists(out):
        try:
            done = read_map(out)
        except Exception:  # not a map of ours: never overwritten
            done = None
        if done is None or done.attrs.get("manifest") != manifest:
            raise InputError(f"--out {out} exists and holds a different map; remove it or "
                             f"choose another --out")
        if not os.path.exists(picture):
            map_figure(done, picture, title=title)
        click.echo(f"{out} is complete (same arguments): nothing to compute")
        return
    parts = parts_folder(out)
    bar = ProgressLine("map", "lines")
    t0 = time.perf_counter()
    try:
        compute = compute_map
        if hasattr(spec, "cylinder"):
            from .studies.operating_maps import compute_operating_map as compute
        ds = compute(spec, workers=workers, store_path=parts, progress=bar, command=command)
    except KeyboardInterrupt:
        bar.close()
        click.echo(f"interrupted: finished lines are kept in {parts}; run the same command "
                   f"to resume", err=True)
        raise click.exceptions.Exit(130)
    except ExecutionError as exc:
        bar.close()
        raise InputError(f"{exc} (kept in {parts})") from None
    finally:
        if hasattr(workers, "close"):
            workers.close()
    bar.close()
    write_map(ds, out)
    map_figure(ds, picture, title=title)
    from .io.chunks import discard

    discard(parts)  # the dataset holds everything now
    status = np.asarray(ds["status"].values)
    failed = int((status == "failed").sum())
    unconverged = int((status == "not converged").sum())
    events = ds.sizes.get("event", 0)
    click.echo(f"wrote {out} and {picture}: {status.size} points ({int(ds['valid'].sum())} "
               f"valid, {unconverged} not converged, {failed} failed), "
               f"{events} boundary point{'s' * (events != 1)}, "
               f"in {time.perf_counter() - t0:.1f} s")
    if "zones_status" in ds:
        zs = np.asarray(ds["zones_status"].values)
        counts = np.asarray(ds["zones_count"].values)[zs == "solved"]
        click.echo(f"contact sets: {int((zs == 'solved').sum())} solved ("
                   + ", ".join(f"{int((counts == c).sum())} of {c} zone{'s' * (c > 1)}"
                               for c in sorted(set(counts.tolist())))
                   + f"), {int((zs == 'no steady solution').sum())} no steady solution, "
                   f"{int((zs == 'not converged').sum())} not converged, "
                   f"{int((zs == 'failed').sum())} failed")


@cli.command("map")
@click.option("--x", "x_spec", required=True,
              help="First axis, name:start:stop:count[:log] (e.g. fhpe:0:0.8:41).")
@click.option("--y", "y_spec", required=True,
              help="Second axis, name:start:stop:count[:log] (e.g. pe:0.5:100:31:log).")
@_problem_options(required=False)
@click.option("--delta-over-r", "delta_over_r", type=float, default=None,
              help="Half-width over radius > 0: also map whether the theory applies.")
@click.option("--tol", type=float, default=1e-6, show_default=True,
              help="Error target of every point.")
@click.option("--method", type=click.Choice(sorted(METHODS)), default=DEFAULT_METHOD,
              show_default=True, help="Discretisation method.")
@click.option("--out", required=True,
              help="Dataset to write: .nc (NetCDF) or .zarr; the picture goes beside it (.png).")
@click.option("--workers", type=int, default=None,
              help="Local worker processes [default: all cores].")
@click.option("--scheduler", default=None,
              help="Run on the Dask cluster whose scheduler is at this address "
                   "(tcp://host:port) instead.")
@_physical_options(required=False)
@_contact_set_options("Operating maps: also the contact set, of one zone or several, at "
                      "every point (what exists past the single patch's boundary).",
                      "needed unless m = 0")
def map_cmd(x_spec, y_spec, pe, fhpe, K2_over_K1, k2_over_k1, delta1_over_delta2, speed_ratio,
            beta_f, lam, sigma,
            delta_over_r, tol, method, out, workers, scheduler, cylinder, half_plane,
            materials_file, radius, load, speed, friction, dundurs, zones, conductance):
    """The solution over a grid of two parameters, and where it stops being valid.

    Parameters: fhpe, pe, lam, sigma, K2-over-K1, k2-over-k1, delta1-over-delta2,
    speed-ratio, beta-f;
    with --cylinder, load, speed and radius in SI units (an operating map).
    Interrupted, the same command resumes; finished work is kept beside --out.
    """
    from .io.files import check_output_dir, check_output_file
    from .studies.maps import MapSpec, parse_axis

    if cylinder is not None or half_plane is not None:
        spec = _operating_spec(x_spec, y_spec, cylinder, half_plane, materials_file, radius,
                               load, speed, friction, lam, tol,
                               dict(pe=pe, fhpe=fhpe, K2_over_K1=K2_over_K1,
                                    k2_over_k1=k2_over_k1, sigma=sigma,
                                    speed_ratio=speed_ratio or None,
                                    beta_f=beta_f or None,
                                    delta_over_r=delta_over_r), dundurs, zones, conductance)
        fixed = ", ".join(f"{k} = {v:g}" for k, v in spec.fixed.items())
        title = (f"{spec.cylinder.name} on {spec.half_plane.name}, f = {spec.friction:g}, "
                 f"lambda = {spec.lam:g}, {fixed} (SI)\nsingle patch (perfect contact) "
                 f"valid where not shaded; theory not applicable where hatched")
        if spec.zones:
            c = spec.conductance
            title += "\ncontact sets, " + ("perfect contact" if c is None else (
                f"h = {c.h0:g} W/m2K" + (f" (p/{c.p_ref:g} Pa)^{c.exponent:g}"
                                         if c.exponent else "")))
    else:
        for name, value in (("--radius", radius), ("--load", load), ("--speed", speed),
                            ("--friction", friction), ("--dundurs", dundurs),
                            ("--zones", zones or None), ("--conductance", conductance)):
            if value is not None:
                raise InputError(f"{name} belongs to an operating map: give --cylinder and "
                                 f"--half-plane too")
        spec = MapSpec(parse_axis("--x", x_spec), parse_axis("--y", y_spec),
                       {"pe": pe, "fhpe": fhpe, "K2_over_K1": K2_over_K1,
                        "k2_over_k1": k2_over_k1, "delta1_over_delta2": delta1_over_delta2,
                        "speed_ratio": speed_ratio or None, "beta_f": beta_f or None,
                        "lam": lam,
                        "sigma_over_delta": sigma},
                       method=method, tol=tol, delta_over_r=delta_over_r)
        fixed = ", ".join(f"{k} = {v:g}" for k, v in spec.fixed.items())
        title = (f"{fixed}; method {method}, tol {tol:g}\nvalid where not shaded; theory not "
                 f"applicable where hatched")
    if out.lower().endswith(".zarr"):
        out = check_output_dir("--out", out)
        try:
            import zarr  # noqa: F401
        except ImportError:
            raise InputError("--out .zarr needs the zarr package: pip install "
                             "'thermocontact[zarr]', or write .nc") from None
    else:
        out = check_output_file("--out", out, suffixes=(".nc", ".zarr"))
    _run_map(spec, out, _workers(workers, scheduler), title,
             "thermocontact " + " ".join(sys.argv[1:]))


@cli.command("reproduce")
@click.option("--out", "out_dir", default="figures", show_default=True,
              help="Folder for the PNG, SVG and CSV files (created if missing).")
@click.option("--only", multiple=True, help="Only these figures (e.g. fig2); repeatable.")
def reproduce_cmd(out_dir, only):
    """Reproduce the paper's Figures 2-5 and extend them past the paper's range."""
    import time

    from .figures.paper_figures import FIGURES, run_figure
    from .io.files import check_output_dir

    names = [f.name for f in FIGURES]
    unknown = [name for name in only if name not in names]
    if unknown:
        raise InputError(f"--only must name figures among {names}, got {unknown[0]!r}")
    out_dir = check_output_dir("--out", out_dir)
    figs = [f for f in FIGURES if not only or f.name in only]
    t0 = time.perf_counter()
    done = []
    try:
        with click.progressbar(figs, label="figures", file=sys.stderr,
                               item_show_func=lambda f: f.name if f else "") as bar:
            for fig in bar:
                run_figure(fig, out_dir, written=done)
    except KeyboardInterrupt:
        # Every file is written whole (renamed when complete): those counted are.
        click.echo(f"interrupted: {len(done)} complete files written to {out_dir}/", err=True)
        raise click.exceptions.Exit(130)
    click.echo(f"wrote {len(done)} files to {out_dir}/ in {time.perf_counter() - t0:.1f} s")


def _contact_summary(res) -> str:
    prob = res.problem
    lines = [
        f"thermocontact {__version__}: {prob.cylinder.name} cylinder (R = {prob.radius:g} m) "
        + (f"sliding at {prob.speed:g} m/s on {prob.half_plane.name}" if not prob.speed2 else
           f"at {prob.speed:g} m/s on {prob.half_plane.name} at {prob.speed2:g} m/s "
           f"(sliding speed {prob.sliding_speed:g} m/s)"),
        f"  load {prob.load:.4g} N/m, friction {prob.friction:g}, lambda {prob.lam:g}, "
        + (f"beta f = {prob.beta_f:.4g} (Dundurs term)" if prob.dundurs
           else "Dundurs term dropped"),
        f"  Hertz: half-width {prob.hertz_half_width:.4g} m, peak pressure "
        f"{prob.hertz_peak_pressure:.4g} Pa",
    ]
    for i, b in enumerate(res.branches):
        tag = "valid" if b.valid else "INVALID"
        star = "*" if b is res.primary else " "
        lines += [
            f" {star}branch {i + 1} ({tag}): half-width {b.half_width:.4g} m, offset "
            f"{b.offset:.4g} m (a = {b.a:.4g}, b = {b.b:.4g})",
            f"    peak pressure {b.peak_pressure:.4g} Pa, mean {b.mean_pressure:.4g} Pa; "
            f"Pe {b.pe:.4g}, fHPe {b.fhpe:.4g}, P_H/P {b.load_ratio:.4g}",
            f"    flash temperature {b.flash_temperature:.4g} K; heat into cylinder "
            f"{b.heat_cylinder:.4g} W/m, half-plane {b.heat_half_plane:.4g} W/m",
            f"    error estimate {b.error_estimate:.1e} (n = {b.solution.n}; target "
            f"{'met' if b.converged else 'NOT met'})",
        ]
        if b.half_plane_incoming_temperature is not None:
            dt = b.half_plane_incoming_temperature
            lines.append(f"    the heat partition implies the half-plane enters {abs(dt):.4g} K "
                         f"{'above' if dt >= 0 else 'below'} the cylinder's temperature; its "
                         f"flash temperature {b.flash_temperature_half_plane:.4g} K over it")
        if b.solution.validity.reason != "valid":
            lines.append(f"    {b.solution.validity.reason}")
        if b.applicable:
            lines.append("    theory applicable: yes")
        else:
            lines.append("    theory NOT applicable: " + "; ".join(b.applicability.reasons))
    if res.message:
        lines.append(f"  {res.message}")
    return "\n".join(lines)


def _conductance(text, what, physical=False):
    """``"h0:m"`` as ``(h0, m)``, or None; in SI units ``"h0:m[:p_ref]"`` as a
    :class:`~.studies.contact_sets.PhysicalConductance`."""
    if text is None:
        return None
    parts = text.split(":")
    form = "h0:m[:p_ref]" if physical else "h0:m"
    try:
        if len(parts) not in ((2, 3) if physical else (2,)):
            raise ValueError
        values = [float(parts[0]), float(parts[1])]
    except ValueError:
        raise InputError(f"--conductance must be {form} (h0 > 0, {what}; exponent m >= 0"
                         + ("; p_ref > 0 in Pa or with units" if physical else "")
                         + f"), got {text!r}") from None
    if not physical:
        return tuple(values)
    from .problem.units import parse_quantity
    from .studies.contact_sets import PhysicalConductance

    p_ref = parse_quantity(parts[2], "Pa", "conductance p_ref") if len(parts) == 3 else None
    return PhysicalConductance(*values, p_ref)


@cli.command("zones")
@click.option("--pe-hertz", "pe_hertz", type=float, required=True,
              help="Pe_l = v l/(2 k2) > 0, l the Hertz half-width of the load.")
@click.option("--fhpe-hertz", "fhpe_hertz", type=float, required=True,
              help="fHPe_l = f H Pe_l >= 0.")
@click.option("--K2-over-K1", "K2_over_K1", type=float, required=True,
              help="Conductivity ratio K2/K1 > 0.")
@click.option("--k2-over-k1", "k2_over_k1", type=float, default=None,
              help="Diffusivity ratio k2/k1 > 0 [default: K2/K1].")
@click.option("--delta1-over-delta2", type=float, default=1.0, show_default=True,
              help="Distortivity ratio >= 0.")
@click.option("--lam", type=float, required=True, help="Heat partition (Q1 - Q2)/(Q1 + Q2).")
@click.option("--conductance", default=None,
              help="h0:m, an interface conductance h = h0 (p/p_ref)^m with h0 as the Biot "
                   "number h0 l/K2 at the mean Hertz pressure p_ref = P/(2 l), m >= 0 "
                   "[default: perfect thermal contact].")
@click.option("-n", "n", type=int, default=32, show_default=True,
              help="Unknowns per function per zone, in [8, 256].")
@click.option("--json", "as_json", is_flag=True, help="Print one JSON object.")
def zones_cmd(pe_hertz, fhpe_hertz, K2_over_K1, k2_over_k1, delta1_over_delta2, lam,
              conductance, n, as_json):
    """The contact set at one load: one zone or several, or why there is none.

    Lengths in units of the Hertz half-width l of the load, from the undeformed
    cylinder's lowest point (the leading edge at larger x); loads as fractions of P,
    pressures in units of P/l.
    """
    from .studies.contact_sets import find_contact_set

    res = find_contact_set(pe_hertz, fhpe_hertz, K2_over_K1, lam=lam, k2_over_k1=k2_over_k1,
                           delta1_over_delta2=delta1_over_delta2, n=n,
                           conductance=_conductance(conductance, "the Biot number h0 l/K2"))
    if as_json:
        click.echo(json.dumps(res.to_dict(), allow_nan=False))
        return
    lines = [f"status: {res.status}: {res.message}"]
    if res.answer is not None:
        lines.append(f"  valid: {res.answer.valid} ({res.answer.validity.reason})")
        for k, z in enumerate(res.answer.zone_records(), 1):
            lines.append(f"  zone {k}: {z['a']:.6f} < x/l < {z['b']:.6f}, load "
                         f"{z['load']:.6f} P, peak pressure {z['peak_pressure']:.6f} P/l")
    click.echo("\n".join(lines))


@cli.command("contact")
@_physical_options(required=True)
@click.option("--lam", type=float, required=True, help="Heat partition (Q1 - Q2)/(Q1 + Q2).")
@click.option("--speed2", default="0", show_default=True,
              help="Speed of the half-plane's surface through the contact (m/s, or with "
                   "units), positive in the cylinder's direction; --speed is then the "
                   "cylinder's surface speed and the heat is made at |speed - speed2|.")
@click.option("--tol", type=float, default=1e-6, show_default=True,
              help="Error target of P_H/P per branch (with --zones not used: contact sets "
                   "are solved with 32 unknowns per function per zone, doubled where the "
                   "path stalls).")
@click.option("--json", "as_json", is_flag=True, help="Print one JSON object.")
@click.option("--csv", "csv_file", default=None, help="Write the distributions to this CSV file.")
@click.option("--plot", "plot_file", default=None,
              help="Write pressure and temperatures to this picture (.png, .svg or .pdf).")
@_contact_set_options("The contact set at this load, of one zone or several (derivation "
                      "section 14), instead of the single patch's branches.",
                      "omitted: the mean Hertz pressure")
def contact_cmd(cylinder, half_plane, materials_file, radius, load, speed, friction, dundurs,
                lam, speed2, tol, as_json, csv_file, plot_file, zones, conductance):
    """Contact width, pressures and temperatures from materials, load and speed."""
    from .io.files import check_output_file
    from .problem.materials import get_material, load_materials
    from .problem.units import parse_quantity
    from .studies.physical_contact import PhysicalProblem, contact

    # Output paths are checked before the computation, whose result would be lost.
    if csv_file is not None:
        csv_file = check_output_file("--csv", csv_file)
    if plot_file is not None:
        plot_file = check_output_file("--plot", plot_file, suffixes=(".png", ".svg", ".pdf"))
    if (csv_file is not None and plot_file is not None
            and os.path.realpath(csv_file) == os.path.realpath(plot_file)):
        raise InputError(f"--csv and --plot must be different files, got {csv_file!r} twice")
    if materials_file is not None:
        load_materials(materials_file)  # read and checked even when both materials are inline
    prob = PhysicalProblem(
        get_material(cylinder, materials_file), get_material(half_plane, materials_file),
        parse_quantity(radius, "m", "radius"), parse_quantity(load, "N/m", "load"),
        parse_quantity(speed, "m/s", "speed"), friction, lam,
        parse_quantity(speed2, "m/s", "speed2"), dundurs=dundurs is not False)
    tol = check_positive("tol", tol)
    if conductance is not None and not zones:
        raise InputError("--conductance needs --zones (the single patch assumes perfect "
                         "thermal contact)")
    if zones:
        if csv_file is not None or plot_file is not None:
            raise InputError("--zones writes no --csv or --plot yet; give --json or neither")
        from .studies.contact_sets import physical_contact_set

        found = physical_contact_set(prob, conductance=_conductance(
            conductance, "in W/(m^2 K)", physical=True))
        if as_json:
            click.echo(json.dumps(found.to_dict(), allow_nan=False))
            return
        lines = [f"status: {found.status}: {found.message}",
                 f"  Hertz half-width {found.hertz_half_width:.6g} m"]
        for k, z in enumerate(found.zones, 1):
            lines.append(f"  zone {k}: {z['a']:.6g} m < x < {z['b']:.6g} m, load "
                         f"{z['load']:.6g} N/m, peak pressure {z['peak_pressure']:.6g} Pa")
        if found.fields is not None:
            lines.append(f"  flash temperature {found.fields.flash_temperature:.4g} K")
        lines.append(f"  valid: {found.valid}")
        if found.applicability is not None:
            lines.append("  theory applicable: yes" if found.applicable else
                         "  theory NOT applicable: " + "; ".join(found.applicability.reasons))
        click.echo("\n".join(lines))
        return
    from .execution.executors import side_process
    from .execution.progress import ProgressLine

    # The picture's Matplotlib is imported in a second process while the contact is
    # solved: the import alone takes about as long as the solve.
    side = None if plot_file is None else side_process(
        "thermocontact.plotting.curves", "matplotlib.figure", "matplotlib.backends.backend_agg")
    try:
        bar = ProgressLine("contact: half-widths followed", "%")
        res = contact(prob, tol=tol, progress=bar)
        bar.close()
        if csv_file is not None:
            _write_contact_csv(res, csv_file)
        if plot_file is not None:
            from .plotting.curves import contact_figure

            if side is None:
                contact_figure(res, plot_file)
            else:
                side.submit(contact_figure, res, plot_file).result()
    finally:
        if side is not None:
            side.shutdown(wait=False, cancel_futures=True)
    if as_json:
        click.echo(json.dumps(res.to_dict(), allow_nan=False))
    else:
        click.echo(_contact_summary(res))


def _write_contact_csv(res, path):
    from .io.tables import write_table

    rows = ([i + 1, int(b.valid)] + [float(v) for v in row]
            for i, b in enumerate(res.branches)
            for row in zip(b.x, b.pressure, b.temperature_cylinder, b.temperature_half_plane))
    write_table(path, ["SI units; temperatures are rises above the cylinder's incoming "
                       "surface temperature"],
                ["branch", "valid", "x", "pressure", "temperature_cylinder",
                 "temperature_half_plane"], rows)


def _refuse_repeated_options(args):
    """An option given twice (``--lam -1 ... --lam 1``) is refused, not silently the last.

    Options declared ``multiple`` (``--only``) may repeat.
    """
    if len(args) < 1 or args[0] not in cli.commands:
        return
    command = cli.commands[args[0]]
    names = {}
    for param in command.params:
        if isinstance(param, click.Option) and not param.multiple:
            for opt in param.opts + param.secondary_opts:
                names[opt] = param.name
    seen = {}
    for token in args[1:]:
        if token == "--":
            break
        opt = token.split("=", 1)[0]
        if opt in names:
            if names[opt] in seen:
                raise InputError(f"{opt} must be given at most once, got it twice "
                                 f"({seen[names[opt]]} and {opt})")
            seen[names[opt]] = opt


def main(argv=None) -> int:
    """Entry point; returns the exit status (0, or 2 for any error)."""
    # The matrices here are small: one BLAS thread is faster than several
    # competing for two cores (measured: 3x on the benchmark).
    from threadpoolctl import threadpool_limits

    import warnings

    def one_line(message, category, *args, **kwargs):
        click.echo(f"warning: {message}", err=True)

    try:
        _refuse_repeated_options(sys.argv[1:] if argv is None else list(argv))
        with threadpool_limits(limits=1, user_api="blas"), warnings.catch_warnings():
            warnings.showwarning = one_line
            rc = cli.main(args=argv, prog_name="thermocontact", standalone_mode=False)
    except click.exceptions.Exit as exc:
        return exc.exit_code
    except click.ClickException as exc:
        click.echo(f"error: {exc.format_message()}", err=True)
        return 2
    except (InputError, SolveError) as exc:
        click.echo(f"error: {exc}", err=True)
        return 2
    except click.exceptions.Abort:
        click.echo("error: aborted", err=True)
        return 130
    except (ValueError, ArithmeticError) as exc:  # e.g. a non-finite number reaching json
        click.echo(f"error: {exc}", err=True)
        return 2
    # Without standalone mode click returns, rather than raises, an Exit's code.
    return rc if isinstance(rc, int) else 0


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
