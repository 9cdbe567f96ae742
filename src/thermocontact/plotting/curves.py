"""Pictures.  Matplotlib is imported here only, inside the functions.

The ``plot_*`` functions draw one result on an Axes (``ax=None``: the current
one) and return it; they neither solve nor choose a backend.  The ``*new_figure``
functions compose them on a :class:`matplotlib.figure.Figure` (no pyplot state)
and save it whole to a file.
"""

from __future__ import annotations

import os

import numpy as np

from ..io.files import atomic_write

__all__ = ["contact_figure", "curves_figure", "distributions_figure", "plot_branch",
           "plot_curve", "plot_distributions"]

_YLABEL = {
    "load_ratio": "$P_H/P$",
    "sigma_over_delta": r"$\sigma/\Delta$",
    "load": "$P/P_H$",
}


def prepare_axes(ax):
    if ax is None:
        import matplotlib.pyplot as plt

        ax = plt.gca()
    return ax


def _stacked(axes):
    """``axes``, or two new stacked Axes of the current figure."""
    if axes is None:
        import matplotlib.pyplot as plt

        axes = plt.gcf().subplots(2, 1, sharex=True)
    return axes


def new_figure(**kwargs):
    # A Figure of its own, outside pyplot: no backend, nothing left open.
    from matplotlib.figure import Figure

    return Figure(**kwargs)


def save_figure(fig, path, written=None):
    """Save ``fig`` whole (a temporary file, renamed when complete); note it in ``written``."""
    fmt = os.path.splitext(path)[1].lstrip(".").lower()
    with atomic_write(path, "wb") as fh:
        fig.savefig(fh, format=fmt, dpi=130)
    if written is not None:
        written.append(path)


def _values(curve, y):
    if y == "load":
        with np.errstate(divide="ignore"):
            return 1.0 / curve.load_ratio
    return getattr(curve, y)


def plot_curve(curve, y="load_ratio", ax=None, **kwargs):
    """Plot one sweep: valid part solid, invalid part dashed, boundaries marked.

    Parameters
    ----------
    curve : Curve
    y : str
        ``load_ratio``, ``sigma_over_delta`` or ``load``.
    ax : matplotlib Axes, optional
    **kwargs
        Passed to the solid line.

    Returns
    -------
    matplotlib Axes
    """
    ax = prepare_axes(ax)
    x = curve.x
    v = _values(curve, y)
    # Insert the boundary points so that the solid and dashed parts meet there.
    xs, vs, ok = list(x), list(v), list(curve.valid)
    for b in curve.boundaries:
        yb = np.interp(b.at, x, v)
        i = int(np.searchsorted(xs, b.at))
        xs[i:i] = [b.at, b.at]
        vs[i:i] = [yb, yb]
        ok[i:i] = [b.valid_before, b.valid_after]
    xs, vs, ok = np.array(xs), np.array(vs), np.array(ok)
    line, = ax.plot(xs, np.where(ok, vs, np.nan), label=curve.label, **kwargs)
    ax.plot(xs, np.where(~ok, vs, np.nan), "--", color=line.get_color(), lw=1)
    for b in curve.boundaries:
        ax.plot([b.at], [np.interp(b.at, x, v)], "x", color=line.get_color(), ms=8, mew=2)
    ax.set_xlabel("fHPe" if curve.x_name == "fhpe" else r"$\lambda$")
    ax.set_ylabel(_YLABEL[y])
    return ax


def curves_figure(curves, stem, title, ys=("load_ratio",), barber=None, written=None):
    """Write ``stem.png`` and ``stem.svg``: one panel per quantity in ``ys``."""
    fig = new_figure(figsize=(5.5 * len(ys), 4.2))
    axes = fig.subplots(1, len(ys), squeeze=False)
    for ax, y in zip(axes[0], ys):
        for c in curves:
            plot_curve(c, y, ax)
        if barber is not None and y == "load_ratio":
            ax.plot(barber[0], barber[1], "k:", lw=1.5, label="Barber (insulated cylinder)")
        if y in ("load_ratio", "load"):
            ax.axhline(1.0, color="0.6", lw=0.8)
            ax.axhline(0.0, color="0.6", lw=0.8)
            ax.set_ylim(bottom=-0.2 if y == "load_ratio" else None)
        if y == "load":
            ax.set_ylim(0.0, 4.0)
        if y == "sigma_over_delta":
            # sigma/Delta diverges where P_H/P -> 0 (the limiting contact width).
            ax.set_ylim(-1.0, 0.25)
        ax.grid(alpha=0.3)
    axes[0][0].legend(fontsize=8)
    fig.suptitle(title + "\n(solid: valid; dashed: invalid; x: where validity changes)", fontsize=9)
    fig.tight_layout()
    for ext in (".png", ".svg"):
        save_figure(fig, stem + ext, written)


def plot_distributions(sol, axes=None):
    """Pressure (top) and heat fluxes (bottom) of one solution against ``s``.

    Parameters
    ----------
    sol : ContactSolution
    axes : pair of Axes, optional
        Default: two new stacked Axes of the current figure.

    Returns
    -------
    (Axes, Axes)
    """
    ax1, ax2 = _stacked(axes)
    p = sol.parameters
    tag = f"Pe = {p.pe:g}, fHPe = {p.fhpe:g} ({'valid' if sol.valid else 'invalid'})"
    style = "-" if sol.valid else "--"
    line, = ax1.plot(sol.s, sol.pressure, style, label=tag)
    ax2.plot(sol.flux_s, sol.flux_half_plane, style, color=line.get_color())
    ax2.plot(sol.flux_s, sol.flux_cylinder, ":", color=line.get_color())
    ax1.set_ylabel("pressure $p\\Delta/P$")
    ax2.set_xlabel("$s = (x - \\sigma)/\\Delta$  (leading edge at +1)")
    ax2.set_ylabel("heat flux, units $fvP/\\Delta$\n(solid: half-plane, dotted: cylinder)")
    return ax1, ax2


def distributions_figure(sols, stem, title, written=None):
    """Write ``stem.png``/``.svg``: pressures (top) and heat fluxes (bottom)."""
    fig = new_figure(figsize=(7, 7))
    axes = fig.subplots(2, 1, sharex=True)
    for sol in sols:
        plot_distributions(sol, axes)
    ax1, ax2 = axes
    s = np.linspace(-1, 1, 201)
    ax1.plot(s, 2 / np.pi * np.sqrt(1 - s * s), "k--", lw=0.8, label="Hertz")
    ax1.legend(fontsize=7)
    ax2.set_ylim(-1.5, 2.5)
    for ax in axes:
        ax.grid(alpha=0.3)
    fig.suptitle(title, fontsize=9)
    fig.tight_layout()
    for ext in (".png", ".svg"):
        save_figure(fig, stem + ext, written)


def plot_branch(branch, problem, axes=None, label=None):
    """Pressure and surface temperatures of one branch in its own coordinates.

    The abscissa is ``s = (x - offset)/Delta`` of the branch, so a branch far
    narrower than Hertz's is drawn as clearly as a wide one; the pressure is in
    units of the Hertz peak pressure ``p0`` of the load; the temperature is the
    surfaces' rise above the cylinder's incoming temperature, K, or their absolute
    temperature where the bulk temperatures were given.

    Parameters
    ----------
    branch : Branch
    problem : PhysicalProblem
    axes : pair of Axes, optional
    label : str, optional

    Returns
    -------
    (Axes, Axes)
    """
    ax1, ax2 = _stacked(axes)
    s = (branch.x - branch.offset) / branch.half_width
    tag = label or (f"half-width {branch.half_width:.3g} m, offset {branch.offset:.3g} m "
                    f"({'valid' if branch.valid else 'invalid'})")
    line, = ax1.plot(s, branch.pressure / problem.hertz_peak_pressure,
                     "-" if branch.valid else "--", label=tag)
    # With the bulk temperatures given, the surfaces' absolute temperature (the
    # cylinder's incoming one plus the rise); else the rise above it.
    base = 0.0 if branch.bulk_temperatures is None else branch.bulk_temperatures[0]
    ax2.plot(s, base + branch.temperature_cylinder, color=line.get_color())
    # Plain-text labels: mathtext's parser would double the picture's cost.
    ax1.set_ylabel("pressure / Hertz peak p₀")
    ax2.set_ylabel(("surface temperature rise, K" if branch.bulk_temperatures is None
                    else "surface temperature, K") + "\n(both surfaces, in contact)")
    ax2.set_xlabel("(x − offset)/Δ of each branch "
                   "(cylinder surface moves toward -x)")
    return ax1, ax2


def contact_figure(res, path):
    """Write every branch of a physical contact, each in its own coordinates, to ``path``."""
    prob = res.problem
    fig = new_figure(figsize=(7, 6.5))
    axes = fig.subplots(2, 1, sharex=True)
    for i, b in enumerate(res.branches):
        plot_branch(b, prob, axes, label=f"branch {i + 1}: half-width {b.half_width:.3g} m "
                                         f"({'valid' if b.valid else 'invalid'})")
    if res.branches:
        axes[0].legend(fontsize=7)
    else:
        axes[0].text(0.5, 0.5, "no half-width carries this load", ha="center",
                     transform=axes[0].transAxes)
    for ax in axes:
        ax.grid(alpha=0.3)
    closure = (f"lambda = {prob.lam:g}" if prob.lam is not None else
               f"lambda = {res.primary.lam:.4g} from the bulk temperatures "
               f"{prob.bulk_temperatures[0]:.5g} K, {prob.bulk_temperatures[1]:.5g} K"
               if res.primary is not None else "bulk temperatures given")
    fig.suptitle(f"{prob.cylinder.name} on {prob.half_plane.name}: R = {prob.radius:g} m, "
                 f"P = {prob.load:.3g} N/m, v = {prob.speed:g} m/s, f = {prob.friction:g}"
                 f"\n{closure}; Hertz: half-width {prob.hertz_half_width:.3g} m, "
                 f"p0 = {prob.hertz_peak_pressure:.3g} Pa", fontsize=8)
    # Fixed margins, wide enough for the two-line labels (tested): tight_layout would
    # draw the figure once more to measure it.
    fig.subplots_adjust(left=0.15, right=0.97, bottom=0.08, top=0.9, hspace=0.08)
    save_figure(fig, path)
