"""``thermocontact map``: a map over two parameters, dimensionless or in physical units
(:func:`thermocontact.parameter_map`, :func:`thermocontact.operating_map`)."""

from __future__ import annotations

import importlib
import json
import os
import sys

import click

from ..discretisation.methods import DEFAULT_METHOD, METHODS
from ..problem.validation import InputError
from .options import (at_most_one_closure, bulk_temperatures_closure, contact_set_options,
                      far_temperatures,
                      parse_conductance, physical_options, problem_options)

__all__ = ["map_cmd"]


def executor_of(workers, scheduler):
    """The executor of ``--workers``/``--scheduler`` (a Dask client to be closed, or an int)."""
    from ..execution.executors import MAX_WORKERS, connect, cpu_count

    if scheduler is not None:
        if workers is not None:
            raise InputError("give --workers or --scheduler, not both (a cluster has its own)")
        return connect(scheduler)
    if workers is None:
        return cpu_count()
    if not 1 <= workers <= MAX_WORKERS:
        raise InputError(f"--workers must be 1 to {MAX_WORKERS}, got {workers}")
    return workers


def picture_of(out) -> str:
    """The picture written beside the dataset ``out``."""
    return os.path.splitext(out)[0] + ".png"


def announce_cost(spec, workers):
    """A line on standard error before contact sets are searched over a map: they cost
    seconds per point, where the rest of a map costs milliseconds."""
    if not getattr(spec, "zones", False):
        return
    cores = (sum(workers.nthreads().values()) if hasattr(workers, "nthreads")
             else int(workers))
    points = spec.x.count * spec.y.count
    click.echo(f"contact sets at {points} point{'s' * (points != 1)}: about "
               f"{spec.contact_set_cost(1) / points:g} s each on one core, about "
               f"{_duration(spec.contact_set_cost(cores))} on {cores} "
               f"worker{'s' * (cores != 1)}", err=True)


def _duration(seconds: float) -> str:
    if seconds < 120:
        return f"{seconds:.0f} s"
    if seconds < 7200:
        return f"{seconds / 60:.0f} min"
    return f"{seconds / 3600:.1f} h"


def run_map(spec, out, workers, title, command, stability=False):
    """Compute (or resume) a map, write the dataset and its picture, keep nothing else."""
    import time

    import numpy as np

    from ..execution.executors import ExecutionError
    from ..execution.progress import ProgressLine
    from ..plotting.maps import map_figure
    from ..api import compute_map
    from ..io.datasets import parts_folder, read_dataset, write_dataset

    picture = picture_of(out)
    manifest = json.dumps(spec.manifest(), sort_keys=True)
    if os.path.exists(out):
        try:
            done = read_dataset(out)
        except Exception:  # not a map of ours: never overwritten
            done = None
        if done is None or done.attrs.get("manifest") != manifest:
            raise InputError(f"--out {out} exists and holds a different map; remove it or "
                             f"choose another --out")
        if stability and "stable" not in done:
            # The stability is not part of a map's identity: never claim it is there.
            raise InputError(f"--out {out} holds this map without its eigenvalues; remove "
                             f"it or choose another --out for --stability",
                             parameters=("stability",))
        if not os.path.exists(picture):
            map_figure(done, picture, done.attrs.get("picture_field", "load_ratio"), title)
        click.echo(f"{out} is complete (same arguments): nothing to compute")
        return
    parts = parts_folder(out)
    announce_cost(spec, workers)
    bar = ProgressLine("map", "lines")
    t0 = time.perf_counter()
    try:
        ds = compute_map(spec, workers=workers, store=parts, progress=bar, command=command,
                         stability=stability)
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
    write_dataset(ds, out)
    map_figure(ds, picture, ds.attrs.get("picture_field", "load_ratio"), title)
    from ..io.chunks import discard

    discard(parts)  # the dataset holds everything now
    status = np.asarray(ds["status"].values)
    failed = int((status == "failed").sum())
    unconverged = int((status == "not converged").sum())
    events = ds.sizes.get("event", 0)
    click.echo(f"wrote {out} and {picture}: {status.size} points ({int(ds['valid'].sum())} "
               f"valid, {unconverged} not converged, {failed} failed), "
               f"{events} boundary point{'s' * (events != 1)}, "
               f"in {time.perf_counter() - t0:.1f} s")
    if "field_tol" in ds.attrs and "error_estimate" in ds:
        est = np.asarray(ds["error_estimate"].values, dtype=float)
        known = est[np.isfinite(est)]
        if known.size:
            within = int((known <= ds.attrs["field_tol"]).sum())
            click.echo(f"fields' error estimate up to {known.max():.1e} (target "
                       f"{ds.attrs['field_tol']:.0e}: met at {within} of {known.size} points)")
    if "zones_status" in ds:
        zs = np.asarray(ds["zones_status"].values)
        counts = np.asarray(ds["zones_count"].values)[zs == "solved"]
        click.echo(f"contact sets: {int((zs == 'solved').sum())} solved ("
                   + ", ".join(f"{int((counts == c).sum())} of {c} zone{'s' * (c > 1)}"
                               for c in sorted(set(counts.tolist())))
                   + f"), {int((zs == 'no steady solution').sum())} no steady solution, "
                   f"{int((zs == 'not converged').sum())} not converged, "
                   f"{int((zs == 'failed').sum())} failed")


@click.command("map")
@click.option("--x", "x_spec", required=True,
              help="First axis, name:start:stop:count[:log] (e.g. fhpe:0:0.8:41).")
@click.option("--y", "y_spec", required=True,
              help="Second axis, name:start:stop:count[:log] (e.g. pe:0.5:100:31:log).")
@problem_options(required=False)
@click.option("--delta-over-r", "delta_over_r", type=float, default=None,
              help="Half-width over radius > 0: also map whether the theory applies.")
@click.option("--tol", type=float, default=1e-6, show_default=True,
              help="Error target of every point.")
@click.option("--method", type=click.Choice(sorted(METHODS)), default=None,
              help=f"Discretisation method (dimensionless maps) [default: {DEFAULT_METHOD}].")
@click.option("--out", required=True,
              help="Dataset to write: .nc (NetCDF) or .zarr; the picture goes beside it (.png).")
@click.option("--workers", type=int, default=None,
              help="Local worker processes [default: all cores].")
@click.option("--scheduler", default=None,
              help="Run on the Dask cluster whose scheduler is at this address "
                   "(tcp://host:port) instead.")
@physical_options(required=False)
@contact_set_options("Operating maps: also the contact set, of one zone or several, at "
                      "every point (what exists past the single patch's boundary).",
                      "needed unless m = 0")
@click.option("--theta", type=float, default=None,
              help="Dimensionless maps: the far temperatures' group instead of --lam or "
                   "--sigma, as for solve (with --sink-distance as L/Delta), or an axis.")
@click.option("--bulk-temperatures", "bulk_temperatures", default=None,
              help="Operating maps: T1,T2 instead of --lam (K, or 150C,40C), as for contact; "
                   "lambda then varies over the plane and each point is its own contact.")
@click.option("--sink-distance", "sink_distance", default=None,
              help="With --bulk-temperatures, a stationary half-plane: its sink's distance.")
@click.option("--layer-thickness", "layer_thickness", default=None,
              help="Or the thickness of a half-plane layer on its sink (distance 4h/pi).")
@click.option("--stability", is_flag=True,
              help="Dimensionless maps: also stable, unstable_modes and growth_rate at every "
                   "point, from the counted eigenvalues of its steady contact (seconds a "
                   "point).")
def map_cmd(x_spec, y_spec, pe, fhpe, K2_over_K1, k2_over_k1, delta1_over_delta2, speed_ratio,
            beta_f, lam, sigma,
            delta_over_r, tol, method, out, workers, scheduler, cylinder, half_plane,
            materials_file, radius, load, speed, friction, dundurs, zones, conductance,
            theta, bulk_temperatures, sink_distance, layer_thickness, stability=False):
    """The solution over a grid of two parameters, and where it stops being valid.

    Parameters: fhpe, pe, lam, sigma, K2-over-K1, k2-over-k1, delta1-over-delta2,
    speed-ratio, beta-f;
    with --cylinder, load, speed and radius in SI units (an operating map).
    Interrupted, the same command resumes; finished work is kept beside --out.
    """
    from ..api import map_spec
    from ..io.datasets import parts_folder
    from ..io.files import check_output_dir, check_output_file
    from ..problem.axes import Axis

    operating = cylinder is not None or half_plane is not None
    if stability and operating:
        raise InputError("--stability maps dimensionless parameters only (for a physical "
                         "contact, contact --stability)", parameters=("stability",))
    if operating and theta is not None:
        raise InputError("theta belongs to a dimensionless map, not to an operating map",
                         parameters=("theta", "cylinder"))
    at_most_one_closure(lam=lam, sigma=sigma, theta=theta,
                        bulk_temperatures=bulk_temperatures)
    axes = (x_spec.split(":")[0], y_spec.split(":")[0])
    closure = (bulk_temperatures_closure(lam, bulk_temperatures, sink_distance, layer_thickness)
               if operating else far_temperatures(theta, sink_distance, "theta" in axes))
    spec = map_spec(Axis.parse(x_spec, "--x"), Axis.parse(y_spec, "--y"), pe=pe, fhpe=fhpe,
                    K2_over_K1=K2_over_K1, k2_over_k1=k2_over_k1,
                    delta1_over_delta2=delta1_over_delta2,
                    speed_ratio=speed_ratio, beta_f=beta_f, lam=lam, sigma_over_delta=sigma,
                    closure=closure, delta_over_r=delta_over_r, method=method,
                    cylinder=cylinder, half_plane=half_plane, friction=friction,
                    radius=radius, load=load, speed=speed, dundurs=dundurs,
                    materials=materials_file, zones=zones,
                    conductance=parse_conductance(conductance, "in W/(m^2 K)", physical=True),
                    tol=tol)
    fixed = ", ".join(f"{k} = {v:g}" for k, v in spec.fixed.items())
    if operating:
        closure = (f"lambda = {spec.lam:g}" if spec.bulk_temperatures is None else
                   "bulk temperatures " + ", ".join(f"{t:.5g} K" for t in spec.bulk_temperatures)
                   + (f", sink at {spec.reference().sink_length:.3g} m"
                      if spec.reference().sink_length is not None else "")
                   + " (colour: lambda)")
        title = (f"{spec.cylinder.name} on {spec.half_plane.name}, f = {spec.friction:g}, "
                 f"{closure}, {fixed} (SI)\nsingle patch (perfect contact) "
                 f"valid where not shaded; theory not applicable where hatched")
        if spec.zones:
            c = spec.conductance
            title += "\ncontact sets, " + ("perfect contact" if c is None else (
                f"h = {c.h0:g} W/m2K" + (f" (p/{c.p_ref:g} Pa)^{c.exponent:g}"
                                         if c.exponent else "")))
    else:
        title = (f"{fixed}; method {spec.method}, tol {tol:g}\nvalid where not shaded; theory not "
                 f"applicable where hatched")
    if out.lower().endswith(".zarr"):
        out = check_output_dir("--out", out)
        try:
            importlib.import_module("zarr")
        except ImportError:
            raise InputError("--out .zarr needs the zarr package: pip install "
                             "'thermocontact[zarr]', or write .nc") from None
    else:
        out = check_output_file("--out", out, suffixes=(".nc", ".zarr"))
    # Every path is checked before the work whose result it receives.
    check_output_file("--out's picture", picture_of(out))
    check_output_dir("--out's unfinished work", parts_folder(out))
    run_map(spec, out, executor_of(workers, scheduler), title,
             "thermocontact " + " ".join(sys.argv[1:]), stability)
