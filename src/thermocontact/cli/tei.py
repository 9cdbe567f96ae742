"""``thermocontact tei``: thermoelastic instability of sliding half-planes, of a brake
disc of finite thickness between pads, of pads on backing plates and of clutch packs
(:func:`thermocontact.tei`)."""

from __future__ import annotations

import json

import click

from ..problem.errors import InputError
from .progress import StageProgress

__all__ = ["report_lines", "tei_cmd"]


@click.command("tei")
@click.option("--slider", required=True,
              help="Material of the sliding body (a disc; a clutch's friction-disc core): a "
                   "name or E=..,nu=..,alpha=..,K=..,k=.. (K=0: a non-conductor).")
@click.option("--counterface", required=True,
              help="Material of the body it slides on (the pads; a clutch's facings).")
@click.option("--friction", required=True,
              help="Coefficient of friction: 0, or 1e-6 to 10.")
@click.option("--wavelength", required=True,
              help="Wavelength of the perturbation, 1 nm to 1 km (m, or with units: "
                   "50mm).")
@click.option("--speed", default=None,
              help="Sliding speed: 0, or 1e-9 to 1e4 m/s (m/s, or with units): also every "
                   "growing mode at that speed and the most unstable wavelength.")
@click.option("--dundurs/--no-dundurs", default=True,
              help="Keep (default) or drop the Dundurs term beta f (derivation section 5c): "
                   "in layers, the friction traction's elastic effect.")
@click.option("--slider-thickness", default=None,
              help="The disc's full thickness (a length); absent: a half-plane.")
@click.option("--faces", type=click.IntRange(1, 2), default=2, show_default=True,
              help="2: both faces rub on identical counterfaces (symmetric and antisymmetric "
                   "families); 1: the other face free and insulated.")
@click.option("--counterface-thickness", default=None,
              help="The pads' (a clutch's facings') thickness; absent: half-planes.")
@click.option("--backing", type=click.Choice(["slip-insulated", "bonded-insulated",
                                              "slip-isothermal"]),
              default="slip-insulated", show_default=True,
              help="The pad layers' rigid backing plate.")
@click.option("--separator", default=None,
              help="A clutch pack: the separator plates' MATERIAL:THICKNESS (steel:2mm); the "
                   "slider is the friction disc's core, the counterface its facings.")
@click.option("--plane-stress", is_flag=True,
              help="Plane stress instead of plane strain.")
@click.option("--disc-radius", default=None,
              help="Disc radius R: the critical speed of n hot spots (wavelength 2 pi R/n).")
@click.option("--hot-spots", default=None,
              help="N1:N2, the hot-spot numbers of the table (default 1:60).")
@click.option("--stop", "stop", default=None,
              help="V0:DECEL: a stop from V0 m/s at DECEL m/s^2: each hot-spot number's "
                   "amplification (needs --disc-radius).")
@click.option("--stop-history", default=None,
              help="Instead of --stop: a CSV file of time (s) and speed (m/s).")
@click.option("--stop-threshold", type=float, default=None,
              help="The amplification that marks a hot-spot number unstable over the stop "
                   "(default e^5).")
@click.option("--materials", "materials_file", default=None,
              help="TOML file adding or overriding materials.")
@click.option("--json", "as_json", is_flag=True, help="Print one JSON object.")
@click.option("--plot", "plot_file", default=None,
              help="Write the critical speed against the wavelength (each family, and the "
                   "half-planes) to this picture (.png, .svg or .pdf); with --disc-radius, "
                   "also against the number of hot spots.")
@click.option("--plot-modes", "modes_file", default=None,
              help="Write the neutral modes' temperature and stress through the thickness "
                   "to this picture (layers only).")
def tei_cmd(slider, counterface, friction, wavelength, speed, dundurs, slider_thickness, faces,
            counterface_thickness, backing, separator, plane_stress, disc_radius, hot_spots,
            stop, stop_history, stop_threshold, materials_file, as_json, plot_file,
            modes_file):
    """Thermoelastic instability of sliding bodies: critical speeds and modes of
    half-planes, brake discs between pads, pads on backing plates and clutch packs."""
    from ..api import tei
    from ..io.files import check_output_file

    if plot_file is not None:
        plot_file = check_output_file("--plot", plot_file, suffixes=(".png", ".svg", ".pdf"))
    if modes_file is not None:
        modes_file = check_output_file("--plot-modes", modes_file,
                                       suffixes=(".png", ".svg", ".pdf"))
        if slider_thickness is None and counterface_thickness is None:
            raise InputError("--plot-modes needs a layer (--slider-thickness or "
                             "--counterface-thickness)")
    # Layers take seconds to minutes: each stage's progress once the command has run 2 s.
    progress = StageProgress("tei")
    try:
        res = tei(slider, counterface, friction, wavelength, speed=speed, dundurs=dundurs,
                  materials=materials_file, slider_thickness=slider_thickness, faces=faces,
                  counterface_thickness=counterface_thickness, backing=backing,
                  separator=separator, plane_stress=plane_stress, disc_radius=disc_radius,
                  hot_spots=hot_spots, brake_stop=stop, stop_history=stop_history,
                  stop_threshold=stop_threshold, progress=progress)
    finally:
        progress.close()
    if plot_file is not None:
        from ..plotting.tei import tei_figure

        tei_figure(res, plot_file)
    if modes_file is not None:
        from ..plotting.tei import modes_figure

        modes_figure(res, modes_file)
    if as_json:
        click.echo(json.dumps(res.to_dict(), allow_nan=False))
        return
    click.echo("\n".join(report_lines(res)))


def _speed(v):
    return "none below 1e4 m/s" if v is None else f"{v:.6g} m/s"


def report_lines(res):
    """The command's text report of a :class:`~thermocontact.studies.tei.TEIResult`,
    line by line."""
    geometry = []
    if res.separator is not None:
        geometry.append(f"clutch pack: core {res.slider_thickness:.6g} m, facings "
                        f"{res.counterface_thickness:.6g} m, separators {res.separator} "
                        f"{res.separator_thickness:.6g} m")
    else:
        if res.slider_thickness is not None:
            geometry.append(f"disc {res.slider_thickness:.6g} m, {res.faces} "
                            f"face{'s' if res.faces == 2 else ''} rubbing")
        if res.counterface_thickness is not None:
            geometry.append(f"pads {res.counterface_thickness:.6g} m on a {res.backing} "
                            f"backing")
    lines = [f"{res.slider} sliding on {res.counterface}, f = {res.friction:g}, wavelength "
             f"{res.wavelength:.6g} m" + (f", beta = {res.beta:.4g}" if res.dundurs
                                         else ", no Dundurs term")
             + ("" if res.plane == "strain" else ", plane stress")]
    if geometry:
        lines.append("  " + "; ".join(geometry))
    if res.critical_speed is None:
        lines.append("  stable at all speeds" if res.stable_at_all_speeds else
                     "  no mode grows below 1e4 m/s (stability beyond not established)")
    else:
        lines.append(f"  critical speed  {res.critical_speed:.6g} m/s (the neutral mode "
                     f"migrates at {res.migration_speed:.6g} m/s relative to the counterface)")
    if len(res.families) > 1 or res.families and res.families[0].minimum_critical_speed:
        for fam in res.families:
            low = ("" if fam.minimum_critical_speed is None else
                   f"; minimum {fam.minimum_critical_speed:.6g} m/s at wavelength "
                   f"{fam.minimum_wavelength:.6g} m"
                   + (" (the end of the range searched: not an interior minimum)"
                      if fam.minimum_at_range_end else ""))
            lines.append(f"    {fam.family}: {_speed(fam.critical_speed)}{low}")
            windows = [(a["speed"], b["speed"]) for a, b in zip(fam.crossings, fam.crossings[1:])
                       if a["direction"] > 0 > b["direction"]]
            for lo, hi in windows:
                lines.append(f"      grows on {lo:.6g} < V < {hi:.6g} m/s, below the critical "
                             f"speed of the branch above")
            if fam.certified is False:
                lines.append("      (the speed scan's count of growing modes did not confirm "
                             "the modes followed: see docs/tei.md)")
    if res.speed is not None:
        lines.append(f"  at {res.speed:.6g} m/s: {len(res.modes)} "
                     f"mode{'' if len(res.modes) == 1 else 's'}, the fastest growing first")
        for k, mode in enumerate(res.modes, 1):
            fam = "" if mode.family == "all" else f" ({mode.family})"
            lines.append(f"    {k}: growth rate {mode.growth_rate:.6g} 1/s, frequency "
                         f"{mode.frequency:.6g} Hz, migration speed {mode.migration_speed:.6g} m/s"
                         + fam)
        if res.most_unstable_wavelength is not None:
            lines.append(f"  most unstable wavelength {res.most_unstable_wavelength:.6g} m "
                         f"(growth rate {res.most_unstable_growth_rate:.6g} 1/s)")
    if res.hot_spots:
        lines.append(f"  hot spots round a disc of radius {res.disc_radius:.6g} m "
                     f"(governing n = {res.governing_hot_spots}):")
        lines.append("     n   wavelength (m)   critical speed (m/s)   family")
        for h in res.hot_spots:
            v = "-" if h.critical_speed is None else f"{h.critical_speed:.6g}"
            lines.append(f"  {h.n:4d}   {h.wavelength:14.6g}   {v:>20}   {h.family or '-'}")
    if res.stop is not None:
        st = res.stop
        i = int(st.log_amplification.argmax())
        first = ("no hot-spot number exceeds it" if st.first_unstable is None else
                 f"first exceeded by n = {st.first_unstable['n']} at "
                 f"{st.first_unstable['speed']:.6g} m/s")
        lines.append(f"  stop from {st.history.speeds[0]:.6g} m/s in "
                     f"{st.history.times[-1]:.6g} s: largest log amplification "
                     f"{st.log_amplification[i]:.6g} (n = {int(st.n[i])}); threshold "
                     f"{st.threshold:.6g}: {first}")
    return lines
