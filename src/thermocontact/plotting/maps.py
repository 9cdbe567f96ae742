"""Pictures of maps: a field over the grid, the invalid region shaded and the
existence boundary drawn where it was located (not where the grid changes).
Matplotlib is imported inside the functions only."""

from __future__ import annotations

import numpy as np

from .curves import prepare_axes, new_figure, save_figure

__all__ = ["map_figure", "plot_map"]

_LABELS = {"fhpe": "fHPe", "pe": "Pe", "lam": r"$\lambda$", "sigma_over_delta": r"$\sigma/\Delta$",
           "K2_over_K1": "$K_2/K_1$", "k2_over_k1": "$k_2/k_1$",
           "delta1_over_delta2": r"$\delta_1/\delta_2$", "speed_ratio": "$v_2/v_1$", "beta_f": r"$\beta f$", "load": "load P (N/m)",
           "speed": "speed v (m/s)", "radius": "radius R (m)", "friction": "friction f",
           "load_ratio": "$P_H/P$", "half_width": "half-width (m)",
           "flash_temperature": "flash temperature (K)", "peak_pressure": "peak pressure (Pa)"}


def _is_log(ds, axis: str) -> bool:
    spec = ds.attrs.get(axis, "")
    return spec.endswith(":log")


def plot_map(ds, field="load_ratio", ax=None):
    """Draw ``field`` of a map dataset, shade where no valid solution is, mark failed
    points and draw the located boundary.

    Parameters
    ----------
    ds : xarray.Dataset
        From :func:`thermocontact.studies.maps.compute_map` (or the operating map).
    field : str
    ax : matplotlib Axes, optional

    Returns
    -------
    Axes
    """
    ax = prepare_axes(ax)
    ydim, xdim = ds[field].dims
    x, y = ds[xdim].values, ds[ydim].values
    z = np.asarray(ds[field].values, dtype=float)
    valid = np.asarray(ds["valid"].values) == 1
    mesh = ax.pcolormesh(x, y, np.where(np.isfinite(z), z, np.nan), shading="nearest",
                         cmap="viridis")
    ax.figure.colorbar(mesh, ax=ax, label=_LABELS.get(field, field))
    # Invalid (but solved) points: a grey veil; failed points: crosses.
    veil = np.where(valid, np.nan, 1.0)
    ax.pcolormesh(x, y, veil, shading="nearest", cmap="Greys", vmin=0.0, vmax=2.5, alpha=0.6)
    # Solved where the theory behind it does not apply (size, slopes, temperatures):
    # hatched, whatever the validity.
    if "applicable" in ds and (np.asarray(ds["applicable"].values) == 0).any():
        outside = np.where(np.asarray(ds["applicable"].values) == 0, 1.0, 0.0)
        ax.contourf(x, y, outside, levels=[0.5, 1.5], colors="none", hatches=["////"])
        ax.contour(x, y, outside, levels=[0.5], colors="white", linewidths=0.8)
    if "zones_status" in ds:
        # Operating maps with contact sets: where one (of any number of zones) is
        # valid, outlined; several zones marked.
        held = ((np.asarray(ds["zones_status"].values) == "solved")
                & (np.asarray(ds["zones_valid"].values) == 1))
        if held.any() and not held.all():
            ax.contour(x, y, held.astype(float), levels=[0.5], colors="tab:red",
                       linestyles="--", linewidths=1.2)
            ax.plot([], [], "--", color="tab:red", label="a valid contact set exists inside")
        else:
            ax.plot([], [], " ", label="a valid contact set exists at "
                    + ("every point" if held.all() else "no point"))
        several = held & (np.asarray(ds["zones_count"].values) > 1)
        if several.any():
            yy, xx = np.meshgrid(y, x, indexing="ij")
            ax.plot(xx[several], yy[several], "+", color="tab:red", ms=4,
                    label="several zones")
    failed = np.asarray(ds["status"].values) == "failed"
    if failed.any():
        yy, xx = np.meshgrid(y, x, indexing="ij")
        ax.plot(xx[failed], yy[failed], "x", color="red", ms=3, label="no solution")
    if ds.sizes.get("event", 0) and ds["boundary_x"].ndim == 2:
        # Operating maps: each boundary is a curve Pe_H = const, drawn exactly.
        for k in range(ds.sizes["event"]):
            if not np.isfinite(ds["boundary_x"].values[k]).any():
                continue  # at Pe_H = infinity: not in the plane
            ax.plot(ds["boundary_x"].values[k], ds["boundary_y"].values[k], "-", color="black",
                    lw=1.2, label=f"boundary: {ds['boundary_inequality'].values[k]}"
                    )
    elif ds.sizes.get("event", 0):
        bx, by = ds["boundary_x"].values, ds["boundary_y"].values
        kinds = [f"{i} ({e})" if e else i for i, e in zip(ds["boundary_inequality"].values,
                                                          ds["boundary_edge"].values)]
        along_x = ds.attrs.get("chunk_axis", "x") == "x"
        for kind in sorted(set(kinds)):
            sel = np.array([k == kind for k in kinds])
            px, py = bx[sel], by[sel]
            order = np.argsort(py if along_x else px)
            ax.plot(px[order], py[order], ".-", color="white", ms=3, lw=1.2)
            ax.plot(px[order], py[order], ".", color="black", ms=2,
                    label=f"boundary: {kind}")
    if ax.get_legend_handles_labels()[1]:
        ax.legend(fontsize=7, loc="best")
    ax.set_xscale("log" if _is_log(ds, "x") else "linear")
    ax.set_yscale("log" if _is_log(ds, "y") else "linear")
    ax.set_xlabel(_LABELS.get(xdim, xdim))
    ax.set_ylabel(_LABELS.get(ydim, ydim))
    return ax


def map_figure(ds, path, field="load_ratio", title=""):
    """Write the map's picture to ``path`` (PNG, SVG or PDF by its extension)."""
    fig = new_figure(figsize=(7, 5.5))
    ax = fig.subplots()
    plot_map(ds, field, ax)
    ax.set_title(title or "valid where not shaded; theory not applicable where hatched",
                 fontsize=8)
    fig.tight_layout()
    save_figure(fig, path)
    return path
