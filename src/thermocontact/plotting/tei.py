"""The picture of ``thermocontact tei``: critical speed against wavelength.
Matplotlib is imported inside the functions only."""

from __future__ import annotations

import numpy as np

from .curves import new_figure, prepare_axes, save_figure

__all__ = ["plot_tei", "tei_figure"]


def plot_tei(result, ax=None, wavelengths=None):
    """Critical speed against wavelength for the pair of ``result``, on log axes.

    Speeds above the curve are unstable.  The wavelength of ``result`` is marked
    and, if it has a speed, that speed and its most unstable wavelength.

    Parameters
    ----------
    result : thermocontact.studies.tei.TEIResult
    ax : matplotlib.axes.Axes, optional
        Default: the current Axes.
    wavelengths : array_like, optional
        Wavelengths of the curve, m; default 25 over two decades about the result's.

    Returns
    -------
    matplotlib.axes.Axes
    """
    ax = prepare_axes(ax)
    wl0 = result.wavelength
    if wavelengths is None:
        wavelengths = wl0 * np.logspace(-1.0, 1.0, 25)
    wavelengths = np.sort(np.asarray(wavelengths, dtype=float))
    # Only V/(kappa m) enters (derivation, H11): V_c L is the same at every wavelength.
    vc = result.critical_speed
    speeds = np.full(wavelengths.shape, np.nan) if vc is None else vc * wl0 / wavelengths
    label = (f"{result.slider} on {result.counterface}, f = {result.friction:g}"
             + ("" if result.dundurs else ", no Dundurs term"))
    if np.all(np.isnan(speeds)):
        ax.text(0.5, 0.5, "stable at all speeds", ha="center", transform=ax.transAxes)
    else:
        ax.loglog(wavelengths, speeds, "-", lw=1.5, label=label)
        top = np.nanmax(speeds) * 3.0
        ax.fill_between(wavelengths, speeds, top, alpha=0.12, label="unstable")
        ax.set_ylim(np.nanmin(speeds) / 3.0, top)
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


def tei_figure(result, path, wavelengths=None):
    """Write :func:`plot_tei` of ``result`` to ``path`` (.png, .svg or .pdf)."""
    fig = new_figure(figsize=(6, 4.5))
    plot_tei(result, ax=fig.subplots(), wavelengths=wavelengths)
    fig.subplots_adjust(left=0.13, right=0.97, bottom=0.12, top=0.95)
    save_figure(fig, path)
