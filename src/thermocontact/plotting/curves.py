"""Pictures.  Matplotlib is imported here only, inside the functions."""

from __future__ import annotations

import os

import numpy as np

from ..io.files import atomic_write

__all__ = ["contact_figure", "curves_figure", "distributions_figure", "plot_curve"]

_YLABEL = {
    "load_ratio": "$P_H/P$",
    "sigma_over_delta": r"$\sigma/\Delta$",
    "load": "$P/P_H$",
}


def _pyplot():
    # No backend is chosen here: without a display matplotlib falls back to Agg.
    import matplotlib.pyplot as plt

    return plt


def _save(fig, path, written=None):
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
    plt = _pyplot()
    if ax is None:
        ax = plt.gca()
    x = curve.x
    v = _values(curve, y)
    # Insert the boundary points so that the solid and dashed parts meet there.
    xs, vs, ok = list(x), list(v), list(curve.valid)
    for b in curve.boundaries:
        yb = np.interp(b.x, x, v)
        i = int(np.searchsorted(xs, b.x))
        xs[i:i] = [b.x, b.x]
        vs[i:i] = [yb, yb]
        ok[i:i] = [not b.becomes_valid, b.becomes_valid]
    xs, vs, ok = np.array(xs), np.array(vs), np.array(ok)
    line, = ax.plot(xs, np.where(ok, vs, np.nan), label=curve.label, **kwargs)
    ax.plot(xs, np.where(~ok, vs, np.nan), "--", color=line.get_color(), lw=1)
    for b in curve.boundaries:
        ax.plot([b.x], [np.interp(b.x, x, v)], "x", color=line.get_color(), ms=8, mew=2)
    ax.set_xlabel("fHPe" if curve.x_name == "fhpe" else r"$\lambda$")
    ax.set_ylabel(_YLABEL[y])
    return ax


def curves_figure(curves, stem, title, ys=("load_ratio",), barber=None, written=None):
    """Write ``stem.png`` and ``stem.svg``: one panel per quantity in ``ys``."""
    plt = _pyplot()
    fig, axes = plt.subplots(1, len(ys), figsize=(5.5 * len(ys), 4.2), squeeze=False)
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
        _save(fig, stem + ext, written)
    plt.close(fig)


def distributions_figure(sols, stem, title, written=None):
    """Write ``stem.png``/``.svg``: pressures (top) and heat fluxes (bottom)."""
    plt = _pyplot()
    fig, (ax1, ax2) = plt.subplots(2, 1, figsize=(7, 7), sharex=True)
    for sol in sols:
        p = sol.parameters
        tag = f"Pe = {p.pe:g}, fHPe = {p.fhpe:g} ({'valid' if sol.valid else 'invalid'})"
        line, = ax1.plot(sol.s, sol.pressure, "-" if sol.valid else "--", label=tag)
        ax2.plot(sol.flux_s, sol.flux_half_plane, "-" if sol.valid else "--", color=line.get_color())
        ax2.plot(sol.flux_s, sol.flux_cylinder, ":", color=line.get_color())
    s = np.linspace(-1, 1, 201)
    ax1.plot(s, 2 / np.pi * np.sqrt(1 - s * s), "k--", lw=0.8, label="Hertz")
    ax1.set_ylabel("pressure $p\\Delta/P$")
    ax1.legend(fontsize=7)
    ax2.set_ylim(-1.5, 2.5)
    ax2.set_xlabel("$s = (x - \\sigma)/\\Delta$  (leading edge at +1)")
    ax2.set_ylabel("heat flux, units $fvP/\\Delta$\n(solid: half-plane, dotted: cylinder)")
    for ax in (ax1, ax2):
        ax.grid(alpha=0.3)
    fig.suptitle(title, fontsize=9)
    fig.tight_layout()
    for ext in (".png", ".svg"):
        _save(fig, stem + ext, written)
    plt.close(fig)


def contact_figure(res, path):
    """Pressure (Hertz dashed) and surface temperatures against x for each branch."""
    plt = _pyplot()
    prob = res.problem
    fig, (ax1, ax2) = plt.subplots(2, 1, figsize=(7, 6.5), sharex=True)
    dh = prob.hertz_half_width
    x = np.linspace(-dh, dh, 301)
    ax1.plot(1e3 * x, 1e-6 * prob.hertz_peak_pressure * np.sqrt(np.clip(1 - (x / dh) ** 2, 0, None)),
             "k--", lw=1, label="Hertz")
    for i, b in enumerate(res.branches):
        tag = f"branch {i + 1} ({'valid' if b.valid else 'invalid'})"
        line, = ax1.plot(1e3 * b.x, 1e-6 * b.pressure, label=tag)
        ax2.plot(1e3 * b.x, b.temperature_cylinder, color=line.get_color(),
                 label=f"{tag}: cylinder = half-plane in contact")
    ax1.set_ylabel("pressure, MPa")
    ax2.set_ylabel("surface temperature rise, K")
    ax2.set_xlabel("x, mm (cylinder surface moves toward -x)")
    for ax in (ax1, ax2):
        ax.grid(alpha=0.3)
        ax.legend(fontsize=7)
    fig.suptitle(f"{prob.cylinder.name} on {prob.half_plane.name}: R = {prob.radius:g} m, "
                 f"P = {prob.load:.3g} N/m, v = {prob.speed:g} m/s, f = {prob.friction:g}, "
                 f"lambda = {prob.lam:g}", fontsize=8)
    fig.tight_layout()
    _save(fig, path)
    plt.close(fig)
