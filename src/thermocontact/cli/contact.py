"""``thermocontact contact`` and ``thermocontact zones``: a contact in physical units,
and the contact set at one load (:func:`thermocontact.contact`,
:func:`thermocontact.contact_set`)."""

from __future__ import annotations

import json
import os

import click

from .._version import __version__
from ..problem.validation import InputError
from .options import (bulk_temperatures_closure, contact_set_options, far_temperatures,
                      given_here, hertz_unit_options, moving_and_dundurs_options, one_closure,
                      parse_conductance, physical_options, stacked)

__all__ = ["contact_cmd", "zones_cmd"]


def contact_summary(res) -> str:
    prob = res.problem
    lines = [
        f"thermocontact {__version__}: {prob.cylinder.name} cylinder (R = {prob.radius:g} m) "
        + (f"sliding at {prob.speed:g} m/s on {prob.half_plane.name}" if not prob.speed2 else
           f"at {prob.speed:g} m/s on {prob.half_plane.name} at {prob.speed2:g} m/s "
           f"(sliding speed {prob.sliding_speed:g} m/s)"),
        f"  load {prob.load:.4g} N/m, friction {prob.friction:g}, "
        + (f"lambda {prob.lam:g}, " if prob.lam is not None else
           f"bulk temperatures {prob.bulk_temperatures[0]:.5g} K, "
           f"{prob.bulk_temperatures[1]:.5g} K"
           + (f" (sink at {prob.sink_length:.4g} m)" if prob.sink_length is not None else "")
           + ", ")
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
            f"    error estimate {b.error_estimate:.1e}, fields {b.field_error:.1e} "
            f"(n = {b.solution.n}; "
            + ("targets met" if b.converged and b.fields_converged else
               "target NOT met" if b.fields_converged else "fields' target NOT met"
               if b.converged else "targets NOT met") + ")",
        ]
        if b.bulk_temperatures is not None:
            under = ["no limit" if u is None else ("under its limit" if u else "OVER its limit")
                     for u in b.under_limits]
            lines += [
                f"    lambda {b.lam:.6g} (error {b.lam_error:.1e}) from the bulk temperatures",
                f"    peak surface temperature {b.peak_temperatures[0]:.5g} K: cylinder "
                f"{under[0]}, half-plane {under[1]}; flash temperatures "
                f"{b.flash_temperatures[0]:.4g} K and {b.flash_temperatures[1]:.4g} K over "
                f"each body's own",
            ]
        elif b.half_plane_incoming_temperature is not None:
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
    if not res.success:  # why there is no valid, converged branch
        lines.append(f"  {res.message}")
    return "\n".join(lines)


@click.command("zones")
@hertz_unit_options
@stacked(moving_and_dundurs_options())
@click.option("--lam", type=float, default=None,
              help="Heat partition (Q1 - Q2)/(Q1 + Q2), |lam| <= 1e6 as for solve (beyond "
                   "[-1, 1] one body gives heat to the contact); or give --sigma or --theta.")
@click.option("--sigma", type=float, default=None,
              help="Or the offset sigma/Delta of one zone (centre over half-width), with "
                   "--fhpe-hertz > 0: the zone's half-width found by Newton's method.")
@click.option("--theta", type=float, default=None,
              help="Or the far temperatures: theta = pi K2 (T2 - T1)/(f v P), T1 the "
                   "cylinder's incoming temperature, T2 the half-plane's sink's (with "
                   "--sink-distance); lambda is then an output.")
@click.option("--sink-distance", "sink_distance", type=float, default=None,
              help="With --theta: L/l > 1, the distance from the contact at which the "
                   "half-plane is at T2, in Hertz half-widths.")
@click.option("--conductance", default=None,
              help="h0:m, an interface conductance h = h0 (p/p_ref)^m with h0 as the Biot "
                   "number h0 l/K2 at the mean Hertz pressure p_ref = P/(2 l), m >= 0 "
                   "[default: perfect thermal contact].")
@click.option("-n", "n", type=int, default=32, show_default=True,
              help="Unknowns per function per zone, in [8, 256].")
@click.option("--stability", is_flag=True,
              help="Also count the contact set's growing modes (every edge free; rates in "
                   "k2/l^2), as contact --zones --stability.")
@click.option("--json", "as_json", is_flag=True, help="Print one JSON object.")
def zones_cmd(pe_hertz, fhpe_hertz, K2_over_K1, k2_over_k1, delta1_over_delta2, speed_ratio,
              beta_f, lam, sigma, theta, sink_distance, conductance, n, stability, as_json):
    """The contact set at one load: one zone or several, or why there is none.

    Lengths in units of the Hertz half-width l of the load, from the undeformed
    cylinder's lowest point (the leading edge at larger x); loads as fractions of P,
    pressures in units of P/l.
    """
    from ..api import contact_set
    from ..execution.progress import ProgressLine

    # Shown once the command has run 2 s: the share of the path to fHPe_l followed.
    bar = ProgressLine("zones: fHPe_l followed", "%")
    one_closure(lam, sigma, theta)
    res = contact_set(pe_hertz, fhpe_hertz, K2_over_K1, lam=lam, sigma_over_delta=sigma,
                      closure=far_temperatures(theta, sink_distance), k2_over_k1=k2_over_k1,
                      delta1_over_delta2=delta1_over_delta2, speed_ratio=speed_ratio,
                      beta_f=beta_f, n=n,
                      conductance=parse_conductance(conductance, "the Biot number h0 l/K2"),
                      progress=lambda fraction: bar(round(100 * fraction), 100))
    bar.close()
    from .solve import record_of, stability_summary

    record = record_of(res, stability)
    if as_json:
        click.echo(json.dumps(record, allow_nan=False))
        return
    lines = [f"status: {res.status}: {res.message}"]
    if res.answer is not None:
        lines.append(f"  valid: {res.answer.valid} ({res.answer.validity.reason})")
        if lam is None:
            lines.append(f"  lambda {res.answer.lam:.10g}")
        for k, z in enumerate(res.answer.zone_records(), 1):
            lines.append(f"  zone {k}: {z['a']:.6f} < x/l < {z['b']:.6f}, load "
                         f"{z['load']:.6f} P, peak pressure {z['peak_pressure']:.6f} P/l")
    if stability:
        lines.append(stability_summary(record["stability"]))
    click.echo("\n".join(lines))



@click.command("contact")
@physical_options(required=True)
@click.option("--lam", type=float, default=None,
              help="Heat partition (Q1 - Q2)/(Q1 + Q2); or give --bulk-temperatures.")
@click.option("--bulk-temperatures", "bulk_temperatures", default=None,
              help="T1,T2 instead of --lam (K, or 150C,40C): the cylinder's incoming "
                   "temperature and the half-plane's (its incoming one with --speed2, else "
                   "its sink's, with --sink-distance or --layer-thickness); lambda is then "
                   "an output, and each body's absolute peak temperature is judged against "
                   "its material's limit (derivation section 17).")
@click.option("--sink-distance", "sink_distance", default=None,
              help="With --bulk-temperatures, a stationary half-plane: the distance from the "
                   "contact at which it is at T2 (m, or 30mm), beyond the contact.")
@click.option("--layer-thickness", "layer_thickness", default=None,
              help="Or: the half-plane is a layer of this thickness on a sink at T2 (m, or "
                   "20mm; sink distance 4h/pi).")
@click.option("--speed2", default="0", show_default=True,
              help="Speed of the half-plane's surface through the contact (m/s, or with "
                   "units), positive in the cylinder's direction; --speed is then the "
                   "cylinder's surface speed and the heat is made at |speed - speed2|.")
@click.option("--tol", type=float, default=1e-6, show_default=True,
              help="Error target of P_H/P per branch (with --zones not used: contact sets "
                   "are solved with 32 unknowns per function per zone, doubled where the "
                   "path stalls).")
@click.option("--json", "as_json", is_flag=True, help="Print one JSON object.")
@click.option("--stability", is_flag=True,
              help="Also every growing mode of the primary branch linearised at fixed load, "
                   "counted, in 1/s (derivation section 18; seconds); with --zones, of the "
                   "contact set, every edge free (section 18b).")
@click.option("--csv", "csv_file", default=None, help="Write the distributions to this CSV file.")
@click.option("--plot", "plot_file", default=None,
              help="Write pressure and temperatures to this picture (.png, .svg or .pdf).")
@contact_set_options("The contact set at this load, of one zone or several (derivation "
                      "section 14), instead of the single patch's branches.",
                      "omitted: the mean Hertz pressure")
@click.option("--transient", is_flag=True,
              help="The contact in time from switch-on (derivation section 19; as the "
                   "transient command, in SI units): with --lam, --no-dundurs, a stationary "
                   "half-plane, --duration and --out; --plot draws pressure over space and "
                   "time.")
@click.option("--duration", default=None,
              help="With --transient: the time computed (s, or with units: 10ms).")
@click.option("--steps", type=int, default=1000, show_default=True,
              help="With --transient: time steps, 1 to 100000.")
@click.option("--elements", type=int, default=240, show_default=True,
              help="With --transient: equal elements on -3 l < x < 3 l (l the Hertz "
                   "half-width), 8 to 4000.")
@click.option("--out", default=None,
              help="With --transient: the run's NetCDF file (.nc), saved every 30 s while "
                   "it is computed; the same command resumes a partial one.")
def contact_cmd(cylinder, half_plane, materials_file, radius, load, speed, friction, dundurs,
                lam, bulk_temperatures, sink_distance, layer_thickness, speed2, tol, as_json,
                csv_file, plot_file, zones, conductance,
                stability=False, transient=False, duration=None, steps=1000, elements=240,
                out=None):
    """Contact width, pressures and temperatures from materials, load and speed."""
    from ..api import contact
    from ..io.files import check_output_file

    if transient:
        return _contact_transient(cylinder, half_plane, materials_file, radius, load, speed,
                                  friction, dundurs, lam, bulk_temperatures, sink_distance,
                                  layer_thickness, speed2, as_json, csv_file, plot_file, zones,
                                  conductance, stability, duration, steps, elements, out)
    for flag, given in (("--duration", duration is not None), ("--out", out is not None),
                        ("--steps", given_here("steps")), ("--elements", given_here("elements"))):
        if given:
            raise InputError(f"{flag} belongs to --transient", parameters=("transient",))

    # Output paths are checked before the computation, whose result would be lost.
    if csv_file is not None:
        csv_file = check_output_file("--csv", csv_file)
    if plot_file is not None:
        plot_file = check_output_file("--plot", plot_file, suffixes=(".png", ".svg", ".pdf"))
    if (csv_file is not None and plot_file is not None
            and os.path.realpath(csv_file) == os.path.realpath(plot_file)):
        raise InputError(f"--csv and --plot must be different files, got {csv_file!r} twice")
    if zones and (csv_file is not None or plot_file is not None):
        raise InputError("--zones writes no --csv or --plot yet; give --json or neither")
    inputs = dict(radius=radius, load=load, speed=speed, friction=friction, lam=lam,
                  closure=bulk_temperatures_closure(lam, bulk_temperatures, sink_distance,
                                                    layer_thickness),
                  speed2=speed2, dundurs=dundurs is not False, materials=materials_file)
    if conductance is not None and not zones:
        raise InputError("--conductance needs --zones (the single patch assumes perfect "
                         "thermal contact)", parameters=("conductance", "zones"))
    if zones:
        from ..api import contact_set
        from ..execution.progress import ProgressLine

        bar = ProgressLine("contact: fHPe_l followed", "%")
        found = contact_set(cylinder=cylinder, half_plane=half_plane,
                            conductance=parse_conductance(conductance, "in W/(m^2 K)",
                                                          physical=True),
                            progress=bar, **inputs)
        bar.close()
        from .solve import record_of, stability_summary

        record = record_of(found, stability)
        if as_json:
            click.echo(json.dumps(record, allow_nan=False))
            return
        lines = [f"status: {found.status}: {found.message}",
                 f"  Hertz half-width {found.hertz_half_width:.6g} m"]
        for k, z in enumerate(found.zones, 1):
            lines.append(f"  zone {k}: {z['a']:.6g} m < x < {z['b']:.6g} m, load "
                         f"{z['load']:.6g} N/m, peak pressure {z['peak_pressure']:.6g} Pa")
        if found.fields is not None:
            lines.append(f"  flash temperature {found.fields.flash_temperature:.4g} K")
            if found.problem.bulk_temperatures is not None:
                rec = found.to_dict()
                lines.append(f"  lambda {rec['lam']:.6g} from the bulk temperatures; peak "
                             f"surface temperature {rec['peak_temperature']:.5g} K")
        lines.append(f"  valid: {found.valid}")
        if found.applicability is not None:
            lines.append("  theory applicable: yes" if found.applicable else
                         "  theory NOT applicable: " + "; ".join(found.applicability.reasons))
        if stability:
            lines.append(stability_summary(record["stability"]))
        click.echo("\n".join(lines))
        return
    from ..execution.executors import side_process
    from ..execution.progress import ProgressLine

    # The picture's Matplotlib is imported in a second process while the contact is
    # solved: the import alone takes about as long as the solve.
    side = None if plot_file is None else side_process(
        "thermocontact.plotting.curves", "matplotlib.figure", "matplotlib.backends.backend_agg")
    try:
        bar = ProgressLine("contact: half-widths followed", "%")
        res = contact(cylinder, half_plane, progress=bar, tol=tol, **inputs)
        bar.close()
        if csv_file is not None:
            from ..io.tables import write_contact_csv

            write_contact_csv(res, csv_file)
        if plot_file is not None:
            from ..plotting.curves import contact_figure

            if side is None:
                contact_figure(res, plot_file)
            else:
                side.submit(contact_figure, res, plot_file).result()
    finally:
        if side is not None:
            side.shutdown(wait=False, cancel_futures=True)
    from .solve import record_of, stability_summary

    record = record_of(res, stability)
    if as_json:
        click.echo(json.dumps(record, allow_nan=False))
    else:
        click.echo(contact_summary(res)
                   + ("\n" + stability_summary(record["stability"]) if stability else ""))


def _contact_transient(cylinder, half_plane, materials_file, radius, load, speed, friction,
                       dundurs, lam, bulk_temperatures, sink_distance, layer_thickness, speed2,
                       as_json, csv_file, plot_file, zones, conductance, stability, duration,
                       steps, elements, out):
    """``contact --transient``: the run of :func:`thermocontact.contact_transient_spec`."""
    from ..api import contact_transient_spec
    from .transient import check_outputs, run_to_file

    for flag, given in (("--zones", zones), ("--conductance", conductance is not None),
                        ("--stability", stability), ("--csv", csv_file is not None),
                        ("--bulk-temperatures", bulk_temperatures is not None),
                        ("--sink-distance", sink_distance is not None),
                        ("--layer-thickness", layer_thickness is not None)):
        if given:
            raise InputError(f"--transient takes no {flag} (the transient contact holds "
                             f"--lam, with perfect thermal contact)")
    if dundurs is not False:
        raise InputError("--transient has no Dundurs term: give --no-dundurs")
    for flag, value in (("--duration", duration), ("--out", out)):
        if value is None:
            raise InputError(f"--transient needs {flag}")
    out, plot_file, _ = check_outputs(out, plot_file)
    spec, extra = contact_transient_spec(cylinder, half_plane, radius=radius, load=load,
                                         speed=speed, friction=friction, lam=lam,
                                         duration=duration, steps=steps, elements=elements,
                                         speed2=speed2, dundurs=False,
                                         materials=materials_file)
    run_to_file(spec, out, plot_file, None, as_json, extra)
