"""``thermocontact reproduce``: the paper's figures and their extensions."""

from __future__ import annotations

import sys

import click

from ..problem.validation import InputError

__all__ = ["reproduce_cmd"]


@click.command("reproduce")
@click.option("--out", "out_dir", default="figures", show_default=True,
              help="Folder for the PNG, SVG and CSV files (created if missing).")
@click.option("--only", multiple=True, help="Only these figures (e.g. fig2); repeatable.")
def reproduce_cmd(out_dir, only):
    """Reproduce the paper's Figures 2-5 and extend them past the paper's range."""
    import time

    from ..figures.paper_figures import FIGURES, run_figure
    from ..io.files import check_output_dir

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
