"""``thermocontact transient``: the contact in time, from switch-on or from a steady
state (:func:`thermocontact.transient`), written to a NetCDF file as it is computed and
resumed from it; also the file of ``contact --transient``."""

from __future__ import annotations

import os

import click

from ..problem.validation import InputError
from .options import far_temperatures, given_here, hertz_unit_options, parse_conductance

__all__ = ["run_to_file", "transient_cmd"]

#: Seconds of computing between two saves of the partial run to --out.
SAVE_EVERY = 30.0


def check_outputs(out, plot=None, gif=None, plot_suffixes=(".png", ".svg", ".pdf")):
    """Every output path checked before any work: ``(out, plot, gif)``."""
    from ..io.files import check_output_file

    out = check_output_file("--out", out, suffixes=(".nc",))
    if plot is not None:
        plot = check_output_file("--plot", plot, suffixes=plot_suffixes)
    if gif is not None:
        gif = check_output_file("--gif", gif, suffixes=(".gif",))
    paths = [(flag, p) for flag, p in (("--out", out), ("--plot", plot), ("--gif", gif))
             if p is not None]
    for i, (fa, a) in enumerate(paths):
        for fb, b in paths[i + 1:]:
            if os.path.realpath(a) == os.path.realpath(b):
                raise InputError(f"{fa} and {fb} must be different files, got {a!r} twice")
    return out, plot, gif


def _same_attrs(attrs, extra) -> bool:
    """Whether a file's attributes hold ``extra`` (a physical run's inputs and units)."""
    import numpy as np

    for key, value in extra.items():
        if key not in attrs:
            return False
        a, b = np.asarray(attrs[key]), np.asarray(value)
        if a.dtype.kind in "fiu" and b.dtype.kind in "fiu":
            if a.shape != b.shape or not np.array_equal(a.astype(float), b.astype(float)):
                return False
        elif str(attrs[key]) != str(value):
            return False
    return True


def _existing(out, spec, extra):
    """The run in ``out`` (None if there is none), refused if other inputs made it."""
    from ..api import read_transient
    from ..io.datasets import read_dataset

    if not os.path.exists(out):
        return None, None
    try:
        ds = read_dataset(out)
        run = read_transient(ds)
    except Exception:  # not a transient run of ours: never overwritten
        run = None
    if run is None or run.spec != spec or not _same_attrs(ds.attrs, extra):
        raise InputError(f"--out {out} exists and holds another run (other inputs or not a "
                         f"transient run); remove it or choose another --out")
    return run, ds


def summary(run, extra, written) -> str:
    """The run's end in a few lines (and in SI units when it has them)."""
    a, b = run.zones(-1)
    steps = run.time.size - 1
    why = f" {run.message}" if run.status == "stopped" else ""
    lines = [f"transient: {run.status}{why}, {steps} of {run.spec.steps} steps to t = "
             f"{run.time[-1]:.6g} l^2/kappa2"
             + (f" = {run.time[-1] * extra['time_unit_s']:.6g} s" if extra else "")
             + f", in {run.seconds:.1f} s of computing",
             "  final zones (x/l): " + (", ".join(f"[{s:.4g}, {e:.4g}]" for s, e in zip(a, b))
                                         or "none")
             + (" = " + ", ".join(f"[{s * extra['length_unit_m'] * 1e3:.4g}, "
                                  f"{e * extra['length_unit_m'] * 1e3:.4g}] mm"
                                  for s, e in zip(a, b)) if extra and a.size else ""),
             f"  lam = {run.lam[-1]:.6g}, approach = {run.approach[-1]:.6g} l^2/R, "
             f"peak pressure = {run.pressure[-1].max():.6g} P/l, "
             f"C = {run.temperature_difference[-1]:.6g} f v P/(pi K2)"]
    if run.resolution != "resolved":
        lines.append(f"  warning: {run.resolution}")
    lines.append("wrote " + ", ".join(written))
    return "\n".join(lines)


def _pictures(ds, plot, gif):
    from ..plotting.transient import animation, space_time

    written = []
    if plot is not None:
        space_time(ds, plot)
        written.append(plot)
    if gif is not None:
        animation(ds, gif)
        written.append(gif)
    return written


def run_to_file(spec, out, plot=None, gif=None, as_json=False, extra=None):
    """Compute the run of ``spec`` into ``out`` (checked paths), saving the partial run
    every :data:`SAVE_EVERY` seconds; resume a partial ``out`` of the same inputs, or
    only draw the pictures of a finished one.  ``extra``: further attributes (the
    physical inputs and units of ``contact --transient``), part of the run's identity."""
    import json

    from ..api import compute_transient
    from ..execution.progress import ProgressLine
    from ..io.datasets import write_dataset

    extra = dict(extra or {})
    # Informative lines go to standard error when standard output is the JSON.
    echo = (lambda text: click.echo(text, err=True)) if as_json else click.echo
    done, ds = _existing(out, spec, extra)
    if done is not None and done.status != "partial":
        state = ("complete" if done.status == "complete"
                 else f"finished ({done.status} {done.message})")
        echo(f"{out} is {state} with the same inputs: nothing to compute")
        written = _pictures(ds, plot, gif)
        if as_json:
            click.echo(json.dumps(done.to_dict(), allow_nan=False))
        elif written:
            echo("wrote " + ", ".join(written))
        return done
    if done is not None:
        echo(f"resuming {out} from step {done.time.size - 1} of {spec.steps}")

    def write(run):
        ds = run.to_dataset()
        ds.attrs.update(extra)
        write_dataset(ds, out)
        return ds

    # Both shown once the command has run 2 s: the operators' making, then the steps.
    making = ProgressLine("transient: operators", "parts")
    bar = ProgressLine("transient", "steps")

    def stepped(done, total):
        making.close()
        bar(done, total)
    try:
        run = compute_transient(spec, resume=done, progress=stepped, save=write,
                                save_every=SAVE_EVERY, preparing=making)
    except KeyboardInterrupt:
        making.close()
        bar.close()
        click.echo("interrupted; rerun the same command to resume", err=True)
        raise click.exceptions.Exit(130) from None
    bar.close()
    ds = write(run)
    written = [out] + _pictures(ds, plot, gif)
    if as_json:
        click.echo(json.dumps(run.to_dict(), allow_nan=False))
    else:
        click.echo(summary(run, extra, written))
    return run


def _window(text):
    try:
        lo, hi = (float(v) for v in text.split(","))
    except ValueError:
        raise InputError(f"--window must be lo,hi with lo < -1 < 1 < hi (units of l), "
                         f"got {text!r}") from None
    return lo, hi


@click.command("transient")
@hertz_unit_options
@click.option("--lam", type=float, default=None,
              help="Heat partition held, in [-1, 1] (or, with --start steady, the steady "
                   "state started from); give this or --theta.")
@click.option("--theta", type=float, default=None,
              help="Far temperatures held, theta = pi K2 (T2 - T1)/(f v P), both bodies "
                   "infinite (--start hertz only); give this or --lam.")
@click.option("--until", type=float, required=True,
              help="Duration > 0, units l^2/kappa2 (kappa2 the half-plane's diffusivity).")
@click.option("--steps", type=int, default=1000, show_default=True,
              help="Time steps, 1 to 100000 (dt = until/steps; first order in dt).")
@click.option("--elements", type=int, default=240, show_default=True,
              help="Equal elements on the window, 8 to 4000.")
@click.option("--window", "window", default="-3,3", show_default=True,
              help="lo,hi: where contact may occur, units l; must contain -1 < x < 1.")
@click.option("--start", type=click.Choice(["hertz", "steady"]), default="hertz",
              show_default=True,
              help="Isothermal bodies under Hertz's pressure, or the steady element "
                   "solution at --lam.")
@click.option("--hold", type=click.Choice(["theta", "lam"]), default="theta",
              show_default=True,
              help="With --start steady: hold that state's far temperatures or its heat "
                   "partition.")
@click.option("--perturb", type=float, default=0.0, show_default=True,
              help="The load is 1 + EPS during the first step, EPS in [-0.5, 0.5].")
@click.option("--conductance", default=None,
              help="Bi0:m, an interface conductance Bi = Bi0 (2 p)^m with Bi0 = h0 l/K2 "
                   "at the mean Hertz pressure, m in [0, 2] [default: perfect thermal "
                   "contact].")
@click.option("--out", required=True,
              help="NetCDF file (.nc) of the run, saved every 30 s while it is computed; "
                   "the same command resumes a partial one.")
@click.option("--plot", "plot_file", default=None,
              help="Write the pressure over space and time to this picture (.png, .svg "
                   "or .pdf).")
@click.option("--gif", "gif_file", default=None,
              help="Write an animation of the pressure and the surface temperatures (.gif).")
@click.option("--json", "as_json", is_flag=True, help="Print one JSON object.")
def transient_cmd(pe_hertz, fhpe_hertz, K2_over_K1, k2_over_k1, delta1_over_delta2, lam, theta,
                  until, steps, elements, window, start, hold, perturb, conductance, out,
                  plot_file, gif_file, as_json):
    """The contact in time: pressure, zones and temperatures from switch-on.

    Lengths in units of the Hertz half-width l of the load, time in l^2/kappa2;
    pressure in P/l, temperature rises in f v P/(pi K2) (derivation section 19).
    Interrupted, the same command resumes from the last save.
    """
    from ..api import transient_spec

    if start != "steady" and given_here("hold"):
        raise InputError("--hold belongs to --start steady (from Hertz's state the "
                         "closure given, --lam or --theta, is held)", parameters=("hold",))
    spec = transient_spec(pe_hertz, fhpe_hertz, K2_over_K1, until=until, steps=steps, lam=lam,
                          closure=far_temperatures(theta, None), k2_over_k1=k2_over_k1,
                          delta1_over_delta2=delta1_over_delta2, elements=elements,
                          window=_window(window), initial=start, hold=hold, perturb=perturb,
                          conductance=parse_conductance(conductance, "the Biot number h0 l/K2"))
    out, plot_file, gif_file = check_outputs(out, plot_file, gif_file)
    run_to_file(spec, out, plot_file, gif_file, as_json)
