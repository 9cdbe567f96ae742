"""The stability study of docs/stability.md: every growing mode of steady single patches.

Part 1, the cases: each case (a point of the paper's Figs. 2-5, a ray past a fold, a
crossing path of docs/zones.md approaching its event) analysed by
``thermocontact.stability`` with its defaults (n = 12; eigenvalues with
Re b >= 1e-3 k2/Delta^2 and |b| <= 1e6 counted by the argument principle, located and
confirmed by Newton's method), and at n = 16 for the count's convergence.  Part 2, the
maps: ``parameter_map(..., stability=True)`` over fHPe and Pe for several K2/K1 and
lam, each point valid and stable, valid and unstable, or invalid (the three colours of
stability_map.png).  Writes stability_study.json beside this file, case by case and map
by map (an interrupted study resumes); ``--table`` prints the tables of
docs/stability.md from it, ``--plot`` draws stability_map.png.

    python docs/stability/stability_study.py [--table] [--plot] [--only NAME ...]
"""

import json
import pathlib
import sys
import time
import warnings

import numpy as np

import thermocontact as tc
from thermocontact.io.files import atomic_write

HERE = pathlib.Path(__file__).resolve().parent
OUT = HERE / "stability_study.json"
PICTURE = HERE / "stability_map.png"
LEVELS = (12, 16)

#: (name, Pe, K2/K1, fHPe, lam, delta1/delta2): k2/k1 = K2/K1, as in the paper.
CASES = [
    ("fig4 lam=-1 fHPe=0.3", 5.0, 10.0, 0.3, -1.0, 1.0),
    ("fig4 lam=1 fHPe=0.3", 5.0, 10.0, 0.3, 1.0, 1.0),
    ("fig3 Pe=1 fHPe=0.5", 1.0, 10.0, 0.5, -1.0, 1.0),
    ("fig2 K=1 fHPe=0.3", 5.0, 1.0, 0.3, -1.0, 1.0),
    ("fig5 fHPe=0.3 lam=3", 5.0, 10.0, 0.3, 3.0, 1.0),
    # Past the paper: a ray with a fold (K2/K1 = 1, lam = 1, fH = 1: a fold of the
    # load at Pe = 1.2343) and strong coupling (K2/K1 = 10, lam = 1, fH = 0.5).
    ("ray K=1 fH=1 Pe=1.0", 1.0, 1.0, 1.0, 1.0, 1.0),
    ("ray K=1 fH=1 Pe=1.2", 1.2, 1.0, 1.2, 1.0, 1.0),
    ("ray K=1 fH=1 Pe=1.3", 1.3, 1.0, 1.3, 1.0, 1.0),
    ("ray K=1 fH=1 Pe=1.5", 1.5, 1.0, 1.5, 1.0, 1.0),
    ("ray K=10 fH=0.5 Pe=4.2", 4.2, 10.0, 2.1, 1.0, 1.0),
]
#: The crossing paths (docs/zones.md): the single patch's event at Pe_event,
#: fHPe_event; along the ray fHPe = fH Pe, at fractions of Pe_event.  Path (d) has no
#: event: along fHPe at Pe = 5 to 0.99 of where P_H/P -> 0 (0.640591).
PATHS = [("a", 5.0, 10.0, 0.665362, 1.0), ("c", 0.2, 1.0, 0.670502, 0.5),
         ("b", 10.0, 100.0, 0.331226, 1.0)]
FRACTIONS = (0.9, 1.0)
for name, pe, K, f, lam in PATHS:
    for x in FRACTIONS:
        CASES.append((f"path ({name}) {x:g} Pe*", x * pe, K, x * f, lam, 1.0))
for f in (0.3, 0.5, 0.6, 0.634):
    CASES.append((f"path (d) fHPe={f:g}", 5.0, 10.0, f, -1.0, 2.0))

#: The maps: (name, K2/K1, lam), each over fHPe and Pe.
MAPS = [("K=10 lam=1", 10.0, 1.0), ("K=10 lam=-1", 10.0, -1.0),
        ("K=1 lam=1", 1.0, 1.0), ("K=1 lam=-1", 1.0, -1.0)]
MAP_FHPE = (0.05, 1.0, 8)
MAP_PE = (0.3, 10.0, 8)


def case(pe, K, fhpe, lam, d):
    sol = tc.solve(pe, fhpe, K, lam=lam, delta1_over_delta2=d)
    record = {"pe": pe, "K2_over_K1": K, "fhpe": fhpe, "lam": lam,
              "delta1_over_delta2": d, "load_ratio": sol.load_ratio,
              "sigma_over_delta": sol.sigma_over_delta, "valid": bool(sol.validity.valid)}
    for n in LEVELS:
        t0 = time.time()
        res = tc.stability(sol, n=n)
        record[f"n={n}"] = {**res.to_dict(), "seconds": time.time() - t0}
    return record


def stability_map(K, lam):
    ds = tc.parameter_map(tc.Axis("fhpe", *MAP_FHPE), tc.Axis("pe", *MAP_PE, log=True),
                          K2_over_K1=K, lam=lam, tol=1e-6, stability=True)
    return {"fhpe": ds["fhpe"].values.tolist(), "pe": ds["pe"].values.tolist(),
            "valid": ds["valid"].values.astype(int).tolist(),
            "stable": ds["stable"].values.tolist(),
            "unstable_modes": ds["unstable_modes"].values.tolist(),
            "growth_rate": np.where(np.isfinite(ds["growth_rate"].values),
                                    ds["growth_rate"].values, -1.0).tolist()}


def table(done):
    for name, r in done.get("cases", {}).items():
        a, b = (r[f"n={n}"] for n in LEVELS)
        modes = ", ".join(f"{re:.4g}{im:+.4g}i" for re, im in a["eigenvalues"]) or "none"
        print(f"| {name} | {r['load_ratio']:.4f} | {'yes' if r['valid'] else 'no'} | "
              f"{a['unstable_modes']} ({b['unstable_modes']}) | {modes} | "
              f"{a['fold']:.1e} | {a['seconds']:.1f} |")
    for name, m in done.get("maps", {}).items():
        valid = np.array(m["valid"], bool)
        stable = np.array(m["stable"])
        print(f"{name}: {valid.sum()} valid points, of which {np.sum(valid & (stable == 0))} "
              f"unstable, {np.sum(valid & (stable == -2))} not certified; "
              f"{np.sum(~valid & (stable == 0))} invalid points unstable")


def plot(done):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from matplotlib.colors import ListedColormap

    maps = done["maps"]
    fig, axes = plt.subplots(1, len(maps), figsize=(3.2 * len(maps), 3.4), sharey=True)
    cmap = ListedColormap(["#bbbbbb", "#2a7fbf", "#d7301f", "#ffbf00"])
    for ax, (name, m) in zip(np.atleast_1d(axes), maps.items()):
        valid, stable = np.array(m["valid"], bool), np.array(m["stable"])
        # 0 invalid, 1 valid and stable, 2 valid and unstable, 3 not certified.
        colour = np.where(~valid, 0, np.where(stable == 1, 1, np.where(stable == 0, 2, 3)))
        ax.pcolormesh(m["fhpe"], m["pe"], colour, cmap=cmap, vmin=-0.5, vmax=3.5,
                      shading="nearest")
        ax.set_yscale("log")
        ax.set_title(name, fontsize=9)
        ax.set_xlabel("fHPe")
    np.atleast_1d(axes)[0].set_ylabel("Pe")
    handles = [plt.Rectangle((0, 0), 1, 1, color=cmap(k)) for k in range(4)]
    fig.legend(handles, ["invalid", "valid, stable", "valid, unstable", "not certified"],
               loc="lower center", ncol=4, fontsize=8, frameon=False)
    fig.tight_layout(rect=(0, 0.08, 1, 1))
    fig.savefig(PICTURE, dpi=110)


def save(done):
    # Whole or not at all: an interrupted study resumes from what is done.
    with atomic_write(OUT) as fh:
        fh.write(json.dumps(done, indent=1))


def main(argv):
    warnings.simplefilter("ignore")
    done = json.loads(OUT.read_text()) if OUT.exists() else {}
    done.setdefault("cases", {})
    done.setdefault("maps", {})
    if "--table" in argv:
        return table(done)
    if "--plot" in argv:
        return plot(done)
    only = argv[argv.index("--only") + 1:] if "--only" in argv else None
    for name, pe, K, f, lam, d in CASES:
        if name in done["cases"] or (only and name not in only):
            continue
        done["cases"][name] = case(pe, K, f, lam, d)
        save(done)
        print(name, done["cases"][name]["n=12"]["unstable_modes"], flush=True)
    for name, K, lam in MAPS:
        if name in done["maps"] or (only and name not in only):
            continue
        t0 = time.time()
        done["maps"][name] = {**stability_map(K, lam), "seconds": time.time() - t0}
        save(done)
        print(name, f"{time.time() - t0:.0f} s", flush=True)


if __name__ == "__main__":
    main(sys.argv[1:])
