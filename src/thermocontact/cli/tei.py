"""``thermocontact tei``: thermoelastic instability of two sliding half-planes
(:func:`thermocontact.tei`)."""

from __future__ import annotations

import json

import click

__all__ = ["tei_cmd"]


@click.command("tei")
@click.option("--slider", required=True,
              help="Material of the sliding half-plane: a name or E=..,nu=..,alpha=..,K=..,k=.. "
                   "(K=0: a non-conductor).")
@click.option("--counterface", required=True, help="Material of the half-plane it slides over.")
@click.option("--friction", type=float, required=True,
              help="Coefficient of friction: 0, or 1e-6 to 10.")
@click.option("--wavelength", required=True,
              help="Wavelength of the perturbation, 1 nm to 1 km (m, or with units: "
                   "50mm).")
@click.option("--speed", default=None,
              help="Sliding speed: 0, or 1e-9 to 1e4 m/s (m/s, or with units): also the "
                   "modes at that speed and the most unstable wavelength.")
@click.option("--dundurs/--no-dundurs", default=True,
              help="Keep (default) or drop the Dundurs term beta f (derivation section 5c).")
@click.option("--materials", "materials_file", default=None,
              help="TOML file adding or overriding materials.")
@click.option("--json", "as_json", is_flag=True, help="Print one JSON object.")
@click.option("--plot", "plot_file", default=None,
              help="Write the critical speed against the wavelength to this picture "
                   "(.png, .svg or .pdf).")
def tei_cmd(slider, counterface, friction, wavelength, speed, dundurs, materials_file, as_json,
            plot_file):
    """Thermoelastic instability of two sliding half-planes: critical speed and modes."""
    from ..api import tei

    if plot_file is not None:
        from ..io.files import check_output_file

        plot_file = check_output_file("--plot", plot_file, suffixes=(".png", ".svg", ".pdf"))
    res = tei(slider, counterface, friction, wavelength, speed=speed, dundurs=dundurs,
              materials=materials_file)
    if plot_file is not None:
        from ..plotting.tei import tei_figure

        tei_figure(res, plot_file)
    if as_json:
        click.echo(json.dumps(res.to_dict(), allow_nan=False))
        return
    lines = [f"{res.slider} sliding on {res.counterface}, f = {res.friction:g}, wavelength "
             f"{res.wavelength:.6g} m" + (f", beta = {res.beta:.4g}" if res.dundurs
                                         else ", no Dundurs term")]
    if res.critical_speed is None:
        lines.append("  stable at all speeds")
    else:
        lines.append(f"  critical speed  {res.critical_speed:.6g} m/s (the neutral mode "
                     f"migrates at {res.migration_speed:.6g} m/s relative to the counterface)")
    if res.speed is not None:
        lines.append(f"  at {res.speed:.6g} m/s: {len(res.modes)} "
                     f"mode{'' if len(res.modes) == 1 else 's'}, the fastest growing first")
        for k, mode in enumerate(res.modes, 1):
            lines.append(f"    {k}: growth rate {mode.growth_rate:.6g} 1/s, frequency "
                         f"{mode.frequency:.6g} Hz, migration speed {mode.migration_speed:.6g} m/s")
        if res.most_unstable_wavelength is not None:
            lines.append(f"  most unstable wavelength {res.most_unstable_wavelength:.6g} m "
                         f"(growth rate {res.most_unstable_growth_rate:.6g} 1/s)")
    click.echo("\n".join(lines))
