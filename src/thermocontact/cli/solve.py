"""``thermocontact solve``: one case in dimensionless form (:func:`thermocontact.solve`)."""

from __future__ import annotations

import click

from .._version import __version__
from ..discretisation.methods import DEFAULT_METHOD, DEFAULT_TOL, METHODS
from .options import far_temperatures, one_closure, parse_conductance, problem_options
from .progress import RefinementProgress

__all__ = ["solve_cmd"]


def solve_summary(sol) -> str:
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
        f"  lambda        = {sol.lam:.10g}"
        + ("" if sol.temperatures is None else
           f"  (from theta = {sol.temperatures.theta:g}"
           + ("" if sol.temperatures.sink_distance is None else
              f", L/Delta = {sol.temperatures.sink_distance:g}")
           + ("; error not estimated)" if sol.lam_error is None else
              f"; error {sol.lam_error:.1e})")),
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


@click.command("solve")
@problem_options(required=True)
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
@click.option("--conductance", default=None,
              help="BI0:m, an interface conductance h = h0 (p/p_ref)^m with BI0 the Biot "
                   "number h0 Delta/K2 at the contact's mean pressure p_ref = P/(2 Delta), "
                   "m >= 0 [default: perfect thermal contact].")
@click.option("--theta", type=float, default=None,
              help="The bodies' far temperatures as the closure instead of --lam or --sigma: "
                   "theta = pi K2 (T2 - T1)/(f |v1 - v2| P), T1 the cylinder's incoming "
                   "temperature, T2 the half-plane's (moving) or its sink's (stationary, "
                   "with --sink-distance); lambda is then an output with its error.")
@click.option("--sink-distance", "sink_distance", type=float, default=None,
              help="With --theta and a stationary half-plane: L/Delta > 1, the distance "
                   "from the contact at which the half-plane is at T2 (a layer of thickness "
                   "h on a sink at T2: L = 4h/pi).")
@click.option("--stability", is_flag=True,
              help="Also every growing mode of the contact linearised at fixed load, counted "
                   "(Re b >= 1e-3 k2/Delta^2; derivation section 18; seconds): is it stable?")
@click.option("--json", "as_json", is_flag=True, help="Print one JSON object.")
def solve_cmd(pe, fhpe, K2_over_K1, k2_over_k1, delta1_over_delta2, speed_ratio, beta_f, lam,
              sigma, n, tol, method, check, delta_over_r, conductance, theta, sink_distance,
              stability, as_json):
    """Solve one case in dimensionless form."""
    from ..api import solve

    one_closure(lam, sigma, theta)
    if stability:
        # What the analysis does not model is refused before the solve.
        from ..discretisation.linearised import check_modelled

        check_modelled(method=method)
    sol = solve(pe, fhpe, K2_over_K1, k2_over_k1=k2_over_k1,
                delta1_over_delta2=1.0 if delta1_over_delta2 is None else delta1_over_delta2,
                speed_ratio=speed_ratio, beta_f=beta_f, lam=lam, sigma_over_delta=sigma, n=n,
                closure=far_temperatures(theta, sink_distance),
                method=method, tol=tol, check_convergence=check,
                progress=RefinementProgress(), delta_over_r=delta_over_r,
                conductance=parse_conductance(conductance, "the Biot number h0 Delta/K2"))
    app = sol.applicability
    record = record_of(sol, stability)
    if as_json:
        import json

        click.echo(json.dumps(record, allow_nan=False))
    else:
        text = solve_summary(sol)
        if app is not None:
            text += ("\n  theory applicable: yes" if app.applicable else
                     "\n  theory NOT applicable: " + "; ".join(app.reasons))
        if stability:
            text += "\n" + stability_summary(record["stability"])
        click.echo(text)


def record_of(result, stability=False) -> dict:
    """``result.to_dict()``, with its ``"stability"`` record when asked for
    (:func:`thermocontact.stability`): the JSON of ``solve`` and ``contact``."""
    record = result.to_dict()
    if stability:
        from ..api import stability as eigenvalues
        from ..execution.progress import ProgressLine

        bar = ProgressLine("stability: evaluations of M(b)", "evaluations")
        record["stability"] = eigenvalues(result, progress=bar).to_dict()
        bar.close()
    return record


def stability_summary(record) -> str:
    """The lines of a ``"stability"`` record."""
    r = record["region"]
    found = ", ".join(f"{re:.6g}{im:+.6g}i" for re, im in record["eigenvalues"]) or "none"
    est = record["error_estimate"]
    lines = [f"  stable        = {record['stable']}  ({record['unstable_modes']} eigenvalues "
             f"with Re b >= {r['b_min']:g}, |b| <= {r['modulus_bound']:g} "
             f"{record['units']['eigenvalues']}, by the argument principle)",
             f"  eigenvalues   = {found}"
             + ("" if est is None else f"  (error estimate {est:.2g}: the change from "
                                          f"n = {record['n']} to 3n/2, n/2 above 32)")]
    if record["reason"]:
        lines.append(f"  note          = {record['reason']}")
    if record["slow_root"] is not None:
        unit = record["units"]["eigenvalues"]
        lines.append(f"  slow root     = {record['slow_root']:.3g} {unit} "
                     "(a fold's real root below b_min, not counted)")
    return "\n".join(lines)
