"""The pictures of ``thermocontact tei``: critical speed against wavelength (each
family of modes, and two half-planes of the same materials), against the number of
hot spots round a disc, and the neutral modes through the thickness.
Matplotlib is imported inside the functions only."""

from __future__ import annotations

import math

import numpy as np

from .curves import new_figure, prepare_axes, save_figure

__all__ = ["hot_spots_figure", "modes_figure", "plot_hot_spots", "plot_modes", "plot_tei",
           "tei_figure"]


def plot_tei(result, ax=None, wavelengths=None):
    """Critical speed against wavelength, each family of ``result``, on log axes.

    Speeds above a curve are unstable.  For layers, two half-planes of the same
    materials are drawn dashed (they have no minimum: ``V_c L`` is fixed, H11).  The
    result's wavelength is marked and, with a speed, that speed and its most
    unstable wavelength.

    Parameters
    ----------
    result : thermocontact.studies.tei.TEIResult
    ax : matplotlib.axes.Axes, optional
        Default: the current Axes.
    wavelengths : array_like, optional
        Wavelengths of the curves, m; default: 25 over two decades about the
        result's (half-planes), or 60 over the result's ``wavelength_range``.

    Returns
    -------
    matplotlib.axes.Axes
    """
    ax = prepare_axes(ax)
    wl0 = result.wavelength
    if wavelengths is None:
        if result.wavelength_range is None:
            wavelengths = wl0 * np.logspace(-1.0, 1.0, 25)
        else:
            wavelengths = np.geomspace(*result.wavelength_range, 60)
    wavelengths = np.sort(np.asarray(wavelengths, dtype=float))
    ms = 2.0 * math.pi / wavelengths[::-1]
    tops, bottoms = [], []
    m0 = 2.0 * math.pi / wl0
    for system in result.systems if result.friction > 0.0 else ():
        fam = next((f for f in result.families if f.family == system.name), None)
        # Continued from the family's neutral point at the result's wavelength.
        anchor = (None if fam is None or fam.critical_speed is None
                  else (m0, fam.critical_speed, -fam.migration_speed * m0))
        speeds = system.curve(ms, anchor)[0][::-1]
        if not np.isfinite(speeds).any():
            continue
        label = system.name if system.name != "all" else (
            f"{result.slider} on {result.counterface}, f = {result.friction:g}"
            + ("" if result.dundurs else ", no Dundurs term"))
        line, = ax.loglog(wavelengths, speeds, "-", lw=1.5, label=label)
        tops.append(np.nanmax(speeds))
        bottoms.append(np.nanmin(speeds))
        if fam is not None and fam.minimum_critical_speed is not None:
            ax.loglog([fam.minimum_wavelength], [fam.minimum_critical_speed], "v",
                      color=line.get_color(), ms=5,
                      label=f"minimum {fam.minimum_critical_speed:.3g} m/s")
    if result.half_planes is not None and result.friction > 0.0:
        half = result.half_planes.curve(ms)[0][::-1]
        if np.isfinite(half).any():
            ax.loglog(wavelengths, half, "--", color="0.5", lw=1.0, label="half-planes")
    if not tops:
        ax.text(0.5, 0.5, "stable at all speeds" if result.stable_at_all_speeds
                else "no mode grows below 1e4 m/s", ha="center", transform=ax.transAxes)
    else:
        top, bottom = max(tops) * 3.0, min(bottoms) / 3.0
        ax.set_ylim(bottom, top)
        if len(tops) == 1:
            ax.fill_between(wavelengths, ax.get_lines()[0].get_ydata(), top, alpha=0.12,
                            label="unstable")
        if result.critical_speed is not None:
            ax.loglog([wl0], [result.critical_speed], "o", ms=5,
                      label=f"{wl0:.3g} m: {result.critical_speed:.3g} m/s")
    if result.speed:
        ax.axhline(result.speed, color="0.4", lw=0.8, ls="--",
                   label=f"speed {result.speed:g} m/s")
        if result.most_unstable_wavelength is not None:
            ax.axvline(result.most_unstable_wavelength, color="0.4", lw=0.8, ls=":",
                       label=f"most unstable: {result.most_unstable_wavelength:.3g} m")
    ax.set_xlabel("wavelength (m)")
    ax.set_ylabel("critical speed (m/s)")
    ax.grid(alpha=0.3, which="both")
    ax.legend(fontsize=7)
    return ax


def plot_hot_spots(result, ax=None):
    """Critical speed against the number of hot spots round the disc, each point
    coloured by the family that goes unstable first; the governing ``n`` circled."""
    ax = prepare_axes(ax)
    fams = sorted({h.family for h in result.hot_spots if h.family is not None})
    for fam in fams:
        pts = [(h.n, h.critical_speed) for h in result.hot_spots if h.family == fam]
        ax.semilogy(*zip(*pts), "o", ms=3.5, label=fam)
    if result.governing_hot_spots is not None:
        h = next(x for x in result.hot_spots if x.n == result.governing_hot_spots)
        ax.semilogy([h.n], [h.critical_speed], "o", ms=10, mfc="none", color="k",
                    label=f"governing: n = {h.n}, {h.critical_speed:.3g} m/s")
    ax.set_xlabel(f"number of hot spots n (disc radius {result.disc_radius:g} m)")
    ax.set_ylabel("critical speed (m/s)")
    ax.grid(alpha=0.3, which="both")
    ax.legend(fontsize=7)
    return ax


def plot_modes(result, axes=None, points=41):
    """The neutral mode of each family at the result's wavelength and critical speed
    through the layup: temperature and normal stress (real parts, the crest at
    ``x = 0``; the temperature's largest modulus 1 K).  A symmetric layup is drawn
    as its half (the mid-plane at the top)."""
    if axes is None:
        import matplotlib.pyplot as plt

        axes = plt.gcf().subplots(1, 2, sharey=True)
    m = 2.0 * math.pi / result.wavelength
    for system, fam in zip(result.systems, result.families):
        if fam.critical_speed is None or not hasattr(system, "layup"):
            continue
        b = -1j * fam.migration_speed * m
        shape = system.mode_shape(m, fam.critical_speed, b, points)
        # Crest of the surface temperature at x = 0: a common phase.
        ref = shape[0][1][-1] if len(shape) > 1 else shape[0][1][0]
        phase = np.conj(ref) / abs(ref) if abs(ref) else 1.0
        color = None
        for y, T, u, s in shape:
            line, = axes[0].plot((T * phase).real, y * 1e3, color=color,
                                 label=fam.family if color is None else None)
            color = line.get_color()
            axes[1].plot((s * phase).real / 1e6, y * 1e3, color=color)
    axes[0].set_xlabel("temperature (K)")
    axes[1].set_xlabel("normal stress (MPa per K)")
    axes[0].set_ylabel("y (mm)")
    for ax in axes:
        ax.grid(alpha=0.3)
    axes[0].legend(fontsize=7)
    return axes


def tei_figure(result, path, wavelengths=None):
    """Write :func:`plot_tei` of ``result`` to ``path`` (.png, .svg or .pdf), with
    :func:`plot_hot_spots` beside it when the result has a hot-spot table."""
    if result.hot_spots:
        fig = new_figure(figsize=(11, 4.5))
        ax1, ax2 = fig.subplots(1, 2)
        plot_tei(result, ax=ax1, wavelengths=wavelengths)
        plot_hot_spots(result, ax=ax2)
        fig.subplots_adjust(left=0.07, right=0.98, bottom=0.12, top=0.95, wspace=0.22)
    else:
        fig = new_figure(figsize=(6, 4.5))
        plot_tei(result, ax=fig.subplots(), wavelengths=wavelengths)
        fig.subplots_adjust(left=0.13, right=0.97, bottom=0.12, top=0.95)
    save_figure(fig, path)


def hot_spots_figure(result, path):
    """Write :func:`plot_hot_spots` of ``result`` to ``path``."""
    fig = new_figure(figsize=(6, 4.5))
    plot_hot_spots(result, ax=fig.subplots())
    fig.subplots_adjust(left=0.13, right=0.97, bottom=0.12, top=0.95)
    save_figure(fig, path)


def modes_figure(result, path):
    """Write :func:`plot_modes` of ``result`` to ``path``."""
    fig = new_figure(figsize=(8, 4.5))
    plot_modes(result, axes=fig.subplots(1, 2, sharey=True))
    fig.subplots_adjust(left=0.1, right=0.97, bottom=0.12, top=0.95, wspace=0.08)
    save_figure(fig, path)
