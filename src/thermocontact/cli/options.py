"""Options shared by several commands, declared once."""

from __future__ import annotations

import click

from ..problem.validation import InputError

__all__ = ["contact_set_options", "given_here", "moving_and_dundurs_options", "one_closure",
           "parse_conductance", "physical_options", "problem_options", "stacked"]


def stacked(options):
    """One decorator applying ``options`` in order (the first listed first in help)."""
    def deco(func):
        for option in reversed(options):
            func = option(func)
        return func
    return deco


def moving_and_dundurs_options(note: str = "") -> tuple:
    """``--speed-ratio`` and ``--beta-f``, the dimensionless model's moving half-plane
    (sections 5b, 16) and Dundurs term (section 5c), for the single patch and contact
    sets alike; ``note`` ends the speed ratio's help."""
    return (
        click.option("--speed-ratio", "speed_ratio", type=float, default=0.0,
                     show_default=True,
                     help="v2/v1: the half-plane's surface speed through the contact over the "
                          "cylinder's, positive in the same direction; 0 is a stationary "
                          "half-plane. Pe is made with v1, fHPe with the sliding speed "
                          "|v1 - v2|." + note),
        click.option("--beta-f", "beta_f", type=float, default=0.0, show_default=True,
                     help="B = beta f, beta = [(1 - 2 nu1)/mu1 - (1 - 2 nu2)/mu2]/A (the "
                          "paper's eq. 10): the Dundurs term -(B/2) p of the contact "
                          "equation; 0 drops it, as the paper does. |B| <= 20; graded "
                          "methods only."),
    )


def problem_options(required: bool):
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
        click.option("--delta1-over-delta2", type=float, default=None,
                     help="Distortivity ratio delta1/delta2 >= 0 (up to 1e6 on paths and "
                          "maps) [default: 1; dimensionless problems only]."),
        *moving_and_dundurs_options(" With --cylinder (boundary, map), --speed is v1."),
        click.option("--lam", type=float, default=None,
                     help="Heat partition (Q1 - Q2)/(Q1 + Q2); give this or --sigma."),
        click.option("--sigma", type=float, default=None,
                     help="Contact offset sigma/Delta; give this or --lam."),
    ]
    return stacked(options)


def physical_options(required: bool):
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
    return stacked(options)


def hertz_unit_options(func):
    """The problem in units of the Hertz half-width ``l`` of the load (``zones``,
    ``transient``): ``--pe-hertz``, ``--fhpe-hertz``, the ratios."""
    options = [
        click.option("--pe-hertz", "pe_hertz", type=float, required=True,
                     help="Pe_l = v l/(2 k2) > 0, l the Hertz half-width of the load."),
        click.option("--fhpe-hertz", "fhpe_hertz", type=float, required=True,
                     help="fHPe_l = f H Pe_l >= 0."),
        click.option("--K2-over-K1", "K2_over_K1", type=float, required=True,
                     help="Conductivity ratio K2/K1 > 0."),
        click.option("--k2-over-k1", "k2_over_k1", type=float, default=None,
                     help="Diffusivity ratio k2/k1 > 0 [default: K2/K1]."),
        click.option("--delta1-over-delta2", type=float, default=1.0, show_default=True,
                     help="Distortivity ratio in [0, 1000] (the materials known span 550)."),
    ]
    return stacked(options)(func)


def contact_set_options(zones_help: str, p_ref_help: str):
    """``--zones`` and ``--conductance`` of the physical commands (``contact``, ``map``),
    which differ only in what the flag adds and what an omitted ``p_ref`` means."""
    zones = click.option("--zones", "zones", is_flag=True, help=zones_help)
    conductance = click.option(
        "--conductance", default=None,
        help="With --zones: h0:m[:p_ref], an interface conductance h = h0 (p/p_ref)^m, h0 "
             "in W/(m^2 K), m >= 0, p_ref in Pa or with units (" + p_ref_help + ") "
             "[default: perfect thermal contact].")
    return lambda func: zones(conductance(func))


def parse_conductance(text, what, physical=False):
    """``"h0:m"`` as ``(h0, m)``, or None; in SI units ``"h0:m[:p_ref]"`` as
    ``(h0, m, p_ref)``, ``p_ref`` in Pa or None."""
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
    from ..problem.units import parse_quantity

    p_ref = parse_quantity(parts[2], "Pa", "conductance p_ref") if len(parts) == 3 else None
    return (*values, p_ref)


def one_closure(lam, sigma, theta):
    """Exactly one of ``--lam``, ``--sigma`` and ``--theta`` (``solve``, ``zones``)."""
    if sum(c is not None for c in (lam, sigma, theta)) != 1:
        raise InputError("give exactly one of lam and sigma (or theta, the far temperatures)",
                         parameters=("lam", "sigma", "theta"))


def given_here(name) -> bool:
    """Whether the option ``name`` was given on this command line, not left at its
    default (an option with a default that another option makes meaningless is
    refused where given, not silently ignored)."""
    from click.core import ParameterSource

    ctx = click.get_current_context(silent=True)
    source = None if ctx is None else ctx.get_parameter_source(name)
    return source not in (None, ParameterSource.DEFAULT)


def at_most_one_closure(**given) -> None:
    """At most one of the closure's flags (a path or a map may follow the closure)."""
    names = [name for name, value in given.items() if value is not None]
    if len(names) > 1:
        raise InputError(f"give at most one of {', '.join(given)}, got {' and '.join(names)}",
                         parameters=tuple(names))


def far_temperatures(theta, sink_distance, may_follow=False):
    """The closure of ``--theta`` and ``--sink-distance`` (a dimensionless command's sink
    distance, in its half-widths), or None where neither is given; ``--sink-distance``
    alone only where the command may follow theta (a path along it, a map over it)."""
    if theta is None and sink_distance is None:
        return None
    if theta is None and not may_follow:
        raise InputError("sink_distance is given with theta only (the far temperatures)",
                         parameters=("sink_distance", "theta"))
    from ..problem.closure import FarTemperatures

    return FarTemperatures(theta, sink_distance)


def bulk_temperatures_closure(lam, temperatures, sink_distance, layer_thickness):
    """The closure of ``--bulk-temperatures`` with ``--sink-distance`` or
    ``--layer-thickness`` (metres, or with units), or None where none is given; exactly
    one of ``--lam`` and ``--bulk-temperatures`` where either is."""
    if temperatures is None:
        for name, value in (("sink_distance", sink_distance),
                            ("layer_thickness", layer_thickness)):
            if value is not None:
                raise InputError(f"give bulk_temperatures, not lam, with {name}" if lam
                                 is not None else f"{name} is given with bulk_temperatures "
                                 f"only", parameters=("bulk_temperatures", "lam", name))
        if lam is None:
            raise InputError("give exactly one of lam and bulk_temperatures",
                             parameters=("lam", "bulk_temperatures"))
        return None
    if lam is not None:
        raise InputError("give exactly one of lam and bulk_temperatures",
                         parameters=("lam", "bulk_temperatures"))
    from ..problem.closure import spelled_closure

    given = {"bulk_temperatures": temperatures, "sink_distance": sink_distance,
             "layer_thickness": layer_thickness}
    return spelled_closure(given, physical=True)[0]
