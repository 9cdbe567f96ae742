"""The transient study of docs/transient.md: what happens past the boundary in time.

On the crossing paths (a)-(c) of docs/zones.md, at 1.1 times the boundary's Pe_l (the
load 21 % past it, where no steady contact set was found on (a)-(c)), the contact is
switched on from Hertz's (isothermal bodies, the heat partition held as the steady
model holds it) and run to t = 20 l^2/kappa2 in 1000 steps; with perfect thermal
contact and with an interface conductance Bi = 10 (2p) (m = 1).  Each run is repeated
with half the time step, with perfect contact also with half the element width, and on
the path that cycles with a quarter (and, perfect, an eighth) of the time step, as its convergence evidence.  Writes
transient_study.json and path_*.png beside this file (the base runs' datasets in
runs/), keeping each run as it finishes
so that an interrupted study resumes; ``--table`` prints the summary of
docs/transient.md from the JSON.  About 5 minutes on one core.

    python docs/transient/transient_study.py [--table]
"""

import json
import pathlib
import sys
import time

import numpy as np

import thermocontact as tc
from thermocontact import __version__
from thermocontact.io.datasets import write_dataset
from thermocontact.io.files import atomic_write

HERE = pathlib.Path(__file__).parent
OUT = HERE / "transient_study.json"
#: The base runs' datasets, for the pictures (not kept in the repository).
RUNS = HERE / "runs"
#: (name, Pe_l at 1.1 of the boundary, fH, K2/K1 = k2/k1, lam, window, elements);
#: Pe_l* and fH from docs/zones.md.
PATHS = [
    ("a", 1.1 * 5.43262, 0.133072, 10.0, 1.0, (-3.0, 3.0), 240),
    ("b", 1.1 * 10.51460, 0.033123, 100.0, 1.0, (-3.0, 3.0), 240),
    ("c", 1.1 * 1.30840, 3.352512, 1.0, 0.5, (-8.0, 3.0), 320),
]
UNTIL = 20.0
STEPS = 1000
CONDUCTANCES = [None, (10.0, 1.0)]
#: (label, steps factor, elements factor): the run and its refinements.
LEVELS = [("base", 1, 1), ("dt/2", 2, 1), ("h/2", 1, 2), ("dt/4", 4, 1), ("dt/8", 8, 1)]


def summary(run):
    """The late behaviour (t >= until/2) of a run."""
    t = run.time
    late = t >= 0.5 * t[-1]
    p, x, h = run.pressure, run.x, run.h
    centroid = (p * x).sum(axis=1) / p.sum(axis=1)
    count, start, end = run.zone_table()
    c = centroid[late] - centroid[late].mean()
    up = np.flatnonzero((c[:-1] < 0) & (c[1:] >= 0))
    periods = np.diff(t[late][up])
    single = late & (count == 1)
    return {
        "status": run.status, "seconds": run.seconds, "steps": int(t.size - 1),
        "elements": int(x.size), "h": h,
        "zones_max": int(count[late].max()), "share_several": float(np.mean(count[late] > 1)),
        "centroid_min": float(centroid[late].min()), "centroid_max": float(centroid[late].max()),
        "period_mean": float(periods.mean()) if periods.size > 1 else None,
        "period_spread": float(np.ptp(periods)) if periods.size > 1 else None,
        "cycles": int(periods.size),
        "trailing": [float(np.nanmin(start[single, 0])), float(np.nanmax(start[single, 0]))]
        if single.any() else None,
        "leading": [float(np.nanmin(end[single, 0])), float(np.nanmax(end[single, 0]))]
        if single.any() else None,
        "peak_pressure": [float(p[late].max(axis=1).min()), float(p[late].max(axis=1).max())],
        "implicit_share": float(np.mean(run.scheme[1:] != 1)),
    }


def key(name, cond, label):
    return f"{name}|{'perfect' if cond is None else '%g:%g' % cond}|{label}"


def compute():
    results = json.loads(OUT.read_text())["runs"] if OUT.exists() else {}
    for name, pe, fH, K, lam, window, elements in PATHS:
        for cond in CONDUCTANCES:
            for label, fs, fe in LEVELS:
                if ((label in ("dt/4", "dt/8") and name != "c")
                        or (label in ("h/2", "dt/8") and cond is not None)):
                    continue
                k = key(name, cond, label)
                if k in results:
                    continue
                t0 = time.time()
                run = tc.transient(pe, fH * pe, K, lam=lam, until=UNTIL, steps=STEPS * fs,
                                   elements=elements * fe, window=window, conductance=cond)
                results[k] = summary(run)
                print(f"{k}: {time.time() - t0:.0f} s, {run}", flush=True)
                if label == "base":
                    RUNS.mkdir(exist_ok=True)
                    write_dataset(run.to_dataset(), RUNS / f"{name}{_tag(cond)}.nc")
                with atomic_write(OUT) as f:
                    json.dump({"version": __version__, "until": UNTIL, "runs": results}, f,
                              indent=1)


def _tag(cond):
    return "" if cond is None else "_conductance"


def pictures():
    """The space-time pictures of the base runs (from the runs' files)."""
    import xarray as xr

    from thermocontact.plotting.transient import animation, space_time

    for name, *_ in PATHS:
        for cond in CONDUCTANCES:
            path = RUNS / f"{name}{_tag(cond)}.nc"
            if path.exists():
                with xr.open_dataset(path) as ds:
                    ds = ds.load()
                space_time(ds, HERE / f"path_{name}{_tag(cond)}.png")
                if name == "c" and cond is None:
                    # The cycle, from t = 14: about three periods.
                    animation(ds.sel(time=slice(14.0, None)), HERE / "path_c.gif", frames=120)


def table():
    runs = json.loads(OUT.read_text())["runs"]
    print("| path | contact | run | zones (max) | centroid x/l | period | leading edge | "
          "peak p | s |")
    print("|---|---|---|---|---|---|---|---|---|")
    for k, r in runs.items():
        name, cond, label = k.split("|")
        # A cycle: the centroid moves by more than four elements, periodically.
        moving = r["centroid_max"] - r["centroid_min"] > 4 * r["h"]
        per = "—" if r["period_mean"] is None or r["cycles"] < 3 or not moving else (
            f"{r['period_mean']:.3f} ± {r['period_spread'] / 2:.3f}")
        lead = "—" if r["leading"] is None else f"{r['leading'][0]:.3f} … {r['leading'][1]:.3f}"
        print(f"| ({name}) | {cond} | {label} | {r['zones_max']} | "
              f"{r['centroid_min']:.3f} … {r['centroid_max']:.3f} | {per} | {lead} | "
              f"{r['peak_pressure'][0]:.3f} … {r['peak_pressure'][1]:.3f} | {r['seconds']:.0f} |")


if __name__ == "__main__":
    if "--table" in sys.argv:
        table()
    else:
        compute()
        pictures()
