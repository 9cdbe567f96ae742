"""``thermocontact boundary``: every sign change of a margin along one parameter, and
where solutions stop existing (:func:`thermocontact.boundary`)."""

from __future__ import annotations

import json

import click

from .._version import __version__
from ..discretisation.methods import DEFAULT_METHOD, DEFAULT_TOL, METHODS
from ..problem.errors import InputError
from .options import (at_most_one_closure, bulk_temperatures_closure, far_temperatures,
                      physical_options,
                      problem_options)
from .progress import StageProgress

__all__ = ["boundary_cmd"]


@click.command("boundary")
@click.option("--along", required=True,
              help="The parameter followed: fhpe, pe, lam, sigma, K2-over-K1, k2-over-k1, "
                   "delta1-over-delta2, speed-ratio, beta-f, theta; or, with --cylinder and --half-plane, load, speed, "
                   "radius or friction; with --bulk-temperatures also temperature-difference "
                   "(T2 - T1 in K, T1 kept) or sink-distance.")
@click.option("--from", "start", required=True,
              help="Start of the path (physical parameters in SI units or with units).")
@click.option("--to", "stop", required=True, help="End of the path.")
@problem_options(required=False)
@physical_options(required=False)
@click.option("--tol", type=float, default=DEFAULT_TOL, show_default=True,
              help="Error target for the choice of n.")
@click.option("-n", "n", type=int, default=None,
              help="Unknowns per function of the whole path (default: chosen by --tol); "
                   "each event's error estimate compares with n/2.")
@click.option("--method", type=click.Choice(sorted(METHODS)), default=None,
              help=f"Discretisation method (dimensionless paths) [default: {DEFAULT_METHOD}].")
@click.option("--theta", type=float, default=None,
              help="Dimensionless paths: the far temperatures' group instead of --lam or "
                   "--sigma, as for solve (or follow it: --along theta).")
@click.option("--bulk-temperatures", "bulk_temperatures", default=None,
              help="Physical paths: T1,T2 instead of --lam, as for contact.")
@click.option("--sink-distance", "sink_distance", default=None,
              help="With --bulk-temperatures, a stationary half-plane: its sink's distance "
                   "(m, or 30mm); with --theta: L/Delta > 1.")
@click.option("--layer-thickness", "layer_thickness", default=None,
              help="Or the thickness of a half-plane layer on its sink.")
@click.option("--stability", is_flag=True,
              help="Also each event's kind: fold, hopf or grazing, from the counted "
                   "eigenvalues of the steady contact there (dimensionless paths; seconds per "
                   "event).")
@click.option("--json", "as_json", is_flag=True, help="Print one JSON object.")
def boundary_cmd(along, start, stop, pe, fhpe, K2_over_K1, k2_over_k1, delta1_over_delta2,
                 speed_ratio, beta_f, lam, sigma, cylinder, half_plane, materials_file, radius, load, speed,
                 friction, dundurs, tol, n, method, theta, bulk_temperatures, sink_distance,
                 layer_thickness, stability, as_json):
    """Every sign change of a contact inequality's margin along one parameter, and
    where solutions stop or start existing, located to 1e-9 relative.

    Events chain (each starts from the validity the previous one left); one that
    does not change validity (a margin changing sign where another inequality
    already fails) is listed as such ("changes_validity": false in --json).
    """
    from ..api import PHYSICAL_ALONG, boundary

    bar = StageProgress(f"boundary along {along}")
    physical = (cylinder is not None or half_plane is not None
                or along.replace("-", "_") in PHYSICAL_ALONG)
    at_most_one_closure(lam=lam, sigma=sigma, theta=theta,
                        bulk_temperatures=bulk_temperatures)
    # (A physical path without its bodies is refused by the call, naming them first.)
    closure = (None if physical and (cylinder is None or half_plane is None)
               else bulk_temperatures_closure(lam, bulk_temperatures, sink_distance,
                                              layer_thickness)
               if physical else far_temperatures(theta, sink_distance,
                                                 along.replace("-", "_") == "theta"))
    if physical and theta is not None:
        raise InputError("theta belongs to a dimensionless path, not to one with cylinder",
                         parameters=("theta", "cylinder"))
    path = boundary(along, start, stop, pe=pe, fhpe=fhpe, K2_over_K1=K2_over_K1,
                    k2_over_k1=k2_over_k1, delta1_over_delta2=delta1_over_delta2,
                    speed_ratio=speed_ratio, beta_f=beta_f, lam=lam, sigma_over_delta=sigma,
                    closure=closure, cylinder=cylinder, half_plane=half_plane,
                    radius=radius, load=load, speed=speed, friction=friction,
                    dundurs=dundurs, materials=materials_file, method=method, tol=tol, n=n,
                    progress=bar, stability=stability)
    method = path.method
    bar.close()
    if as_json:
        click.echo(json.dumps(path.to_dict(), allow_nan=False))
        return
    unit = PHYSICAL_ALONG.get(along.replace("-", "_"), "")
    click.echo(f"thermocontact {__version__}: along {along} from {path.x[0]:g} to "
               f"{path.x[-1]:g}{' ' + unit if unit else ''} (method {method}, n = {path.n}"
               + (f"; events at n = {path.event_n}" if path.event_n != path.n else "") + ")")
    if not path.events:
        click.echo(f"  no change of validity (valid throughout: {bool(path.valid.all())})")
    for e in path.events:
        where = f" at the {e.edge} edge" if e.edge else ""
        err = ("" if e.error_estimate is None else
               f" (discretisation error estimate {e.error_estimate:.1e})")
        if e.inequality in ("solution_ends", "solution_begins"):
            # The solver's refusals begin there: no solution, or none well-determined
            # (a system too ill-conditioned to trust), as solve would say at that point.
            what = ("the last point solved: the solver refuses past it"
                    if e.inequality == "solution_ends" else
                    "the first point solved: the solver refuses before it")
        else:
            what = e.inequality + where
        change = (f"valid {e.valid_before} -> {e.valid_after}" if e.changes_validity else
                  f"validity unchanged ({e.valid_before})")
        click.echo(f"  {along} = {e.at:.10g}{' ' + unit if unit else ''}{err}: "
                   f"{what}; {change}" + (f"; {e.kind}" if e.kind else ""))
