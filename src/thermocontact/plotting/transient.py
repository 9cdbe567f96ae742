"""Pictures of a transient run (derivation section 19): the pressure over space and
time with the zones' edges, and an animation of the pressure and both surfaces'
temperatures.  Matplotlib is imported inside the functions only."""

from __future__ import annotations

import numpy as np

from ..io.files import atomic_path
from .curves import new_figure, save_figure

__all__ = ["animation", "space_time"]


def _scales(ds):
    """x and time scales and their labels: SI (mm, s) when the run carries its units
    (``contact --transient``), else the run's own units."""
    ell, tau = ds.attrs.get("length_unit_m"), ds.attrs.get("time_unit_s")
    if ell is not None and tau is not None:
        return float(ell) * 1e3, float(tau), "x (mm)", "time (s)"
    return 1.0, 1.0, "x / l", "time (l^2/kappa2)"


def space_time(ds, path) -> None:
    """The pressure over ``x`` (across) and time (up) as an image, the zones' edges as
    lines.

    Parameters
    ----------
    ds : xarray.Dataset
        A transient run's dataset (:meth:`~thermocontact.TransientRun.to_dataset`).
    path : str
        ``.png``, ``.svg`` or ``.pdf``.
    """
    xs, ts, xlabel, tlabel = _scales(ds)
    x = np.asarray(ds["x"].values) * xs
    t = np.asarray(ds["time"].values) * ts
    p = np.asarray(ds["pressure"].values)
    fig = new_figure(figsize=(7, 5))
    ax = fig.subplots()
    # Element edges across, step ends up: each cell is an element over a step.
    h = x[1] - x[0]
    xe = np.concatenate([x - 0.5 * h, [x[-1] + 0.5 * h]])
    dt = t[1] - t[0] if t.size > 1 else 1.0
    te = np.concatenate([[t[0] - 0.5 * dt], 0.5 * (t[1:] + t[:-1]), [t[-1] + 0.5 * dt]])
    mesh = ax.pcolormesh(xe, te, p, cmap="viridis", shading="flat")
    fig.colorbar(mesh, ax=ax, label="pressure p l / P")
    start = np.asarray(ds["zone_start"].values) * xs
    end = np.asarray(ds["zone_end"].values) * xs
    for k in range(start.shape[1]):
        label = "zone edges" if k == 0 else None
        ax.plot(start[:, k], t, color="w", lw=0.8, label=label)
        ax.plot(end[:, k], t, color="w", lw=0.8)
    ax.set_xlabel(xlabel)
    ax.set_ylabel(tlabel)
    ax.set_title(f"pressure over space and time ({ds.attrs.get('status', '')})", fontsize=9)
    ax.legend(loc="upper right", fontsize=7)
    fig.tight_layout()
    save_figure(fig, path)


def animation(ds, path, frames=100) -> None:
    """A GIF of the pressure and both surfaces' temperature rises against ``x``, time in
    the title: at most ``frames`` frames, one every few steps, the last step always.

    Parameters
    ----------
    ds : xarray.Dataset
        A transient run's dataset.
    path : str
        ``.gif``, written whole.
    frames : int
        Most frames (>= 1).
    """
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from PIL import Image

    xs, ts, xlabel, tlabel = _scales(ds)
    x = np.asarray(ds["x"].values) * xs
    t = np.asarray(ds["time"].values) * ts
    p = np.asarray(ds["pressure"].values)
    t1 = np.asarray(ds["temperature1"].values)
    t2 = np.asarray(ds["temperature2"].values)
    every = max(1, -(-t.size // max(1, int(frames))))
    shown = list(range(0, t.size, every))
    if shown[-1] != t.size - 1:
        shown.append(t.size - 1)
    fig = new_figure(figsize=(6, 5), dpi=80)
    canvas = FigureCanvasAgg(fig)
    top, bottom = fig.subplots(2, 1, sharex=True)
    (pline,) = top.plot(x, p[0], color="k", animated=True)
    top.set_ylim(0.0, 1.05 * max(float(p.max()), 1e-12))
    top.set_ylabel("pressure p l / P")
    (l1,) = bottom.plot(x, t1[0], color="C3", label="cylinder", animated=True)
    (l2,) = bottom.plot(x, t2[0], color="C0", label="half-plane", animated=True)
    lo = float(min(t1.min(), t2.min()))
    hi = float(max(t1.max(), t2.max()))
    pad = 0.05 * (hi - lo) or 1.0
    bottom.set_ylim(lo - pad, hi + pad)
    bottom.set_xlabel(xlabel)
    bottom.set_ylabel("temperature rise, f v P/(pi K2)")
    bottom.legend(fontsize=7, loc="upper right")
    title = fig.suptitle("", animated=True)
    unit = tlabel.split(" ", 1)[1].strip("()")
    # The axes drawn once; each frame redraws only the curves and the title (blitting:
    # a whole redraw a frame costs ten times more).
    canvas.draw()
    background = canvas.copy_from_bbox(fig.bbox)
    images = []
    for n in shown:
        canvas.restore_region(background)
        pline.set_ydata(p[n])
        l1.set_ydata(t1[n])
        l2.set_ydata(t2[n])
        title.set_text(f"time {t[n]:.4g} {unit} (step {n} of {t.size - 1})")
        for artist in (pline, l1, l2, title):
            fig.draw_artist(artist)
        images.append(Image.fromarray(np.asarray(canvas.buffer_rgba())).convert("RGB"))
    # One palette for every frame (the colours do not change): quantized once.
    palette = images[0].quantize(colors=256, method=Image.Quantize.FASTOCTREE)
    images = [im.quantize(palette=palette, dither=Image.Dither.NONE) for im in images]
    with atomic_path(path) as tmp:
        images[0].save(tmp, format="GIF", save_all=True, append_images=images[1:],
                       duration=100, loop=0)
