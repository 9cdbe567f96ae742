"""The paper's Figures 2-5, and the same figures past the paper's range.

Each figure is a list of sweeps (:mod:`thermocontact.studies.sweeps`); its data go to a CSV
whose header records the parameters, the method, ``n`` and the package version,
and its picture to a PNG and an SVG.  Where the paper is silent the choices are
ours and are listed in ``docs/reproduction.md``.
"""

from __future__ import annotations

import csv
import datetime
import os
from dataclasses import dataclass, field

import numpy as np

from .._version import __version__
from ..physics.reference_solutions import barber_insulated
from ..solvers.single_patch import solve
from ..studies.sweeps import Curve, sweep

__all__ = ["FIGURES", "Figure", "run_figure"]

FHPE = np.linspace(0.0, 0.7, 36)
#: Error target of the figures' sweeps, and the largest n they may use.
TOL = 1e-7
N_MAX = 256
LAM = np.linspace(-1.0, 4.0, 26)


@dataclass(frozen=True)
class Figure:
    """A figure: sweeps sharing axes.

    Attributes
    ----------
    name : str
        File stem.
    title : str
    curves : tuple of (label, fixed, x_name, x)
    y : tuple of str
        Quantities plotted, one panel each: ``load_ratio``, ``sigma_over_delta``
        or ``load`` (``P/P_H``).
    barber : bool
        Add Barber's insulated-cylinder curve.
    distributions : bool
        A picture of pressure and heat flux at a few points instead of curves.
    """

    name: str
    title: str
    curves: tuple
    y: tuple = ("load_ratio",)
    barber: bool = False
    distributions: tuple = field(default=())


def _fhpe_curves(pes, K, lam=-1.0, **extra):
    return tuple((f"Pe = {pe:g}", dict(pe=pe, K2_over_K1=K, lam=lam, **extra), "fhpe", FHPE)
                 for pe in pes)


FIGURES = (
    Figure("fig2", "Fig. 2: K2/K1 = 100, lambda = -1, with Barber's insulated cylinder",
           _fhpe_curves((5, 10), 100.0), barber=True),
    Figure("fig3", "Fig. 3: K2/K1 = 10, lambda = -1",
           _fhpe_curves((1, 2, 5, 10), 10.0), y=("load_ratio", "sigma_over_delta")),
    Figure("fig4", "Fig. 4: K2/K1 = 10, Pe = 5",
           tuple((f"lambda = {lam:g}", dict(pe=5.0, K2_over_K1=10.0, lam=lam), "fhpe", FHPE)
                 for lam in (-1.0, -0.5, 0.0, 0.5, 1.0))),
    Figure("fig5", "Fig. 5: K2/K1 = 10, Pe = 5: load P/P_H against lambda",
           tuple((f"fHPe = {f:g}", dict(pe=5.0, K2_over_K1=10.0, fhpe=f), "lam", LAM)
                 for f in (0.1, 0.2, 0.3, 0.4)), y=("load",)),
    Figure("ext_pe", "Past the paper: K2/K1 = 10, lambda = -1, Pe = 20, 50, 100",
           _fhpe_curves((20, 50, 100), 10.0), y=("load_ratio", "sigma_over_delta")),
    Figure("ext_k1", "Past the paper: K2/K1 = 1, lambda = -1",
           _fhpe_curves((1, 5, 10), 1.0), y=("load_ratio", "sigma_over_delta"), barber=True),
    Figure("ext_k1000", "Past the paper: K2/K1 = 1000, lambda = -1",
           _fhpe_curves((1, 5), 1000.0), y=("load_ratio", "sigma_over_delta"), barber=True),
    Figure("distributions", "Pressure and heat flux at points of Fig. 3 (Pe = 1 and 5)",
           (), distributions=((1.0, 0.2), (1.0, 0.55), (1.0, 0.65), (5.0, 0.3), (5.0, 0.7))),
)


def _header(fig: Figure, curves, extra=()) -> list[str]:
    lines = [
        f"thermocontact {__version__}, {datetime.date.today().isoformat()}",
        fig.title,
    ]
    for c in curves:
        fixed = ", ".join(f"{k}={v:g}" for k, v in c.fixed.items())
        lines.append(f"curve '{c.label}': {fixed}; sweep {c.x_name}; method {c.method}, "
                     f"n {c.n}, error estimate (middle and end of sweep) {c.error_estimate:.1e}")
        for b in c.boundaries:
            kind = "becomes valid" if b.becomes_valid else "stops being valid"
            lines.append(f"  validity boundary: {c.x_name} = {b.x:.9f} ({kind}; "
                         f"{b.margin} margin, at s = {b.at:.4f})")
    lines.extend(extra)
    return lines


def _write_curves_csv(path, fig: Figure, curves, barber=None):
    with open(path, "w", newline="") as fh:
        for line in _header(fig, curves):
            fh.write(f"# {line}\n")
        w = csv.writer(fh)
        w.writerow(["curve", "pe", "K2_over_K1", "k2_over_k1", "delta1_over_delta2", "fhpe",
                    "lam", "load_ratio", "load_over_hertz", "sigma_over_delta", "valid",
                    "pressure_margin", "gap_margin", "n"])
        for c in curves:
            for i in range(c.x.size):
                f = c.x[i] if c.x_name == "fhpe" else c.fixed["fhpe"]
                L = c.load_ratio[i]
                w.writerow([c.label, c.fixed["pe"], c.fixed["K2_over_K1"],
                            c.fixed.get("k2_over_k1", c.fixed["K2_over_K1"]),
                            c.fixed.get("delta1_over_delta2", 1.0), f"{f:.10g}",
                            f"{c.lam[i]:.10g}", f"{L:.12g}", f"{1 / L:.12g}" if L else "inf",
                            f"{c.sigma_over_delta[i]:.12g}", int(c.valid[i]),
                            f"{c.pressure_margin[i]:.6g}", f"{c.gap_margin[i]:.6g}", c.n])
        if barber is not None:
            for f, L in zip(*barber):
                w.writerow(["Barber (insulated cylinder)", "", "", "", 0, f"{f:.10g}", -1,
                            f"{L:.12g}", f"{1 / L:.12g}" if L else "inf", 0, "", "", "", ""])


def run_figure(fig: Figure, out_dir: str) -> list[str]:
    """Compute one figure and write its CSV, PNG and SVG into ``out_dir``.

    Returns
    -------
    list of str
        The files written.
    """
    from ..plotting import curves as plotting

    os.makedirs(out_dir, exist_ok=True)
    stem = os.path.join(out_dir, fig.name)
    if fig.distributions:
        sols = [solve(pe, f, 10.0, lam=-1.0, tol=1e-6) for pe, f in fig.distributions]
        with open(stem + ".csv", "w", newline="") as fh:
            fh.write(f"# thermocontact {__version__}, {datetime.date.today().isoformat()}\n")
            methods = ", ".join(sorted({sol.method for sol in sols}))
            fh.write(f"# {fig.title}; K2/K1 = 10, lambda = -1, method {methods}\n")
            w = csv.writer(fh)
            w.writerow(["pe", "fhpe", "n", "valid", "quantity", "s", "value"])
            for sol in sols:
                p = sol.parameters
                for s_, v in zip(sol.s, sol.pressure):
                    w.writerow([p.pe, p.fhpe, sol.n, int(sol.valid), "pressure", f"{s_:.12g}", f"{v:.12g}"])
                for name, arr in (("flux_cylinder", sol.flux_cylinder),
                                  ("flux_half_plane", sol.flux_half_plane)):
                    for s_, v in zip(sol.flux_s, arr):
                        w.writerow([p.pe, p.fhpe, sol.n, int(sol.valid), name, f"{s_:.12g}", f"{v:.12g}"])
        plotting.distributions_figure(sols, stem, fig.title)
        return [stem + ext for ext in (".csv", ".png", ".svg")]

    curves: list[Curve] = [sweep(label, fixed, x_name, x, tol=TOL, n_max=N_MAX)
                           for label, fixed, x_name, x in fig.curves]
    barber = None
    if fig.barber:
        f = FHPE
        barber = (f, np.array([barber_insulated(x, n=256).load_ratio for x in f]))
    _write_curves_csv(stem + ".csv", fig, curves, barber)
    plotting.curves_figure(curves, stem, fig.title, fig.y, barber)
    return [stem + ext for ext in (".csv", ".png", ".svg")]
