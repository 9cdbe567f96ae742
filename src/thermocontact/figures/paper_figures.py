"""The paper's Figures 2-5, and the same figures past the paper's range.

Each figure is a list of sweeps (:mod:`thermocontact.studies.sweeps`); its data go to a CSV
whose header records the parameters, the method, ``n`` and the package version,
and its picture to a PNG and an SVG.  Where the paper is silent the choices are
ours and are listed in ``docs/reproduction.md``.
"""

from __future__ import annotations

import os
from dataclasses import dataclass, field

import numpy as np

from ..io.tables import write_table
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
    lines = [fig.title]
    for c in curves:
        fixed = ", ".join(f"{k}={v:g}" for k, v in c.fixed.items())
        lines.append(f"curve '{c.label}': {fixed}; sweep {c.x_name}; method {c.method}, "
                     f"n {c.n}, error estimate (middle and end of sweep) {c.error_estimate:.1e}")
        for b in c.boundaries:
            kind = "becomes valid" if b.valid_after else "stops being valid"
            where = "" if b.position is None else f", at s = {b.position:.4f}"
            lines.append(f"  validity boundary: {c.x_name} = {b.at:.9f} ({kind}; "
                         f"{b.inequality} margin{where})")
    lines.extend(extra)
    return lines


CURVE_COLUMNS = ["curve", "pe", "K2_over_K1", "k2_over_k1", "delta1_over_delta2", "fhpe",
                 "lam", "load_ratio", "load_over_hertz", "sigma_over_delta", "valid",
                 "pressure_margin", "gap_margin", "n"]


def _curve_rows(curves, barber=None):
    for c in curves:
        for i in range(c.x.size):
            f = c.x[i] if c.x_name == "fhpe" else c.fixed["fhpe"]
            L = c.load_ratio[i]
            yield [c.label, c.fixed["pe"], c.fixed["K2_over_K1"],
                   c.fixed.get("k2_over_k1", c.fixed["K2_over_K1"]),
                   c.fixed.get("delta1_over_delta2", 1.0), float(f), float(c.lam[i]),
                   float(L), float(1 / L) if L else "inf", float(c.sigma_over_delta[i]),
                   int(c.valid[i]), float(c.pressure_margin[i]), float(c.gap_margin[i]), c.n]
    if barber is not None:
        for f, L in zip(*barber):
            yield ["Barber (insulated cylinder)", "", "", "", 0, float(f), -1, float(L),
                   float(1 / L) if L else "inf", 0, "", "", "", ""]


def _distribution_rows(sols):
    for sol in sols:
        p = sol.parameters
        head = [p.pe, p.fhpe, sol.n, int(sol.valid)]
        for s_, v in zip(sol.s, sol.pressure):
            yield head + ["pressure", float(s_), float(v)]
        for name, arr in (("flux_cylinder", sol.flux_cylinder),
                          ("flux_half_plane", sol.flux_half_plane)):
            for s_, v in zip(sol.flux_s, arr):
                yield head + [name, float(s_), float(v)]


def run_figure(fig: Figure, out_dir: str, written: list | None = None) -> list[str]:
    """Compute one figure and write its CSV, PNG and SVG into ``out_dir``.

    Each file is written whole (a temporary name, then a rename) and appended to
    ``written`` as soon as it is complete, so that an interrupted caller knows
    which files are.

    Returns
    -------
    list of str
        The files written.
    """
    written = [] if written is None else written
    start = len(written)
    from ..plotting import curves as plotting

    os.makedirs(out_dir, exist_ok=True)
    stem = os.path.join(out_dir, fig.name)
    if fig.distributions:
        sols = [solve(pe, f, 10.0, lam=-1.0, tol=1e-6) for pe, f in fig.distributions]
        methods = ", ".join(sorted({sol.method for sol in sols}))
        write_table(stem + ".csv", [f"{fig.title}; K2/K1 = 10, lambda = -1, method {methods}"],
                    ["pe", "fhpe", "n", "valid", "quantity", "s", "value"],
                    _distribution_rows(sols))
        written.append(stem + ".csv")
        plotting.distributions_figure(sols, stem, fig.title, written=written)
        return written[start:]

    curves: list[Curve] = [sweep(label, fixed, x_name, x, tol=TOL, n_max=N_MAX)
                           for label, fixed, x_name, x in fig.curves]
    barber = None
    if fig.barber:
        f = FHPE
        barber = (f, np.array([barber_insulated(x, n=256).load_ratio for x in f]))
    write_table(stem + ".csv", _header(fig, curves), CURVE_COLUMNS, _curve_rows(curves, barber))
    written.append(stem + ".csv")
    plotting.curves_figure(curves, stem, fig.title, fig.y, barber, written=written)
    return written[start:]
