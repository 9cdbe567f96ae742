"""The crossing study of docs/zones.md: what exists past the single patch's boundary.

Each path is a growing load at fixed f·H (a ray Pe_l -> (Pe_l, fH Pe_l) in units of
the Hertz half-width l of the load), its fH chosen so that the single patch's
boundary, found by the core along fHPe at the paper's Pe, is crossed.  The single
zone is followed from Hertz's along the ray to 10 % past the boundary; where it fails
the contact sets the failure suggests are tried (thermocontact.studies.contact_sets).
The same rays are then followed to 1.1 and 2 times the boundary's Pe_l with
interface conductances h = C p^m (derivation section 15).  Writes
crossing_study.json and path_*.png beside this file (about 7 minutes on one core; the
paths in parallel with ``--workers N``), keeping each path as it finishes so that an
interrupted study resumes; ``--table`` prints the summary table of docs/zones.md from
the JSON.

    python docs/zones/crossing_study.py [--table | --workers N]
"""

import json
import pathlib
import time

import numpy as np

from thermocontact import Model, __version__
from thermocontact.io.chunks import discard
from thermocontact.io.files import atomic_write
from thermocontact.studies.boundaries import follow
from thermocontact.execution.resumable import run_chunks
from thermocontact.plotting.zones import crossing_figure
from thermocontact.problem.parameters import SolveError
from thermocontact.solvers.zones import ZoneModel
from thermocontact.studies.contact_sets import follow_contact_set, other_starts

#: (name, Pe at the boundary, K2/K1, k2/k1, delta1/delta2, lam)
PATHS = [
    ("a", 5.0, 10.0, 10.0, 1.0, 1.0),
    ("b", 10.0, 100.0, 100.0, 1.0, 1.0),
    ("c", 0.2, 1.0, 1.0, 1.0, 0.5),
    ("d", 5.0, 10.0, 10.0, 2.0, -1.0),
]
N = 24
#: (Bi0, m) of the interface conductances tried on each path: Bi0 = h0 l/K2 at the
#: boundary's load, for a fixed law h = C p^m (so Bi0 grows with the load as
#: l^(1 + m)).
CONDUCTANCES = [(100.0, 0.0), (10.0, 0.0), (1.0, 0.0), (100.0, 1.0), (10.0, 1.0), (1.0, 1.0)]


def first_event(pe, K, k, d, lam):
    """The single patch's first event along fHPe at Pe (the core, derivation section 8)."""
    path = follow({"pe": pe, "K2_over_K1": K, "k2_over_k1": k, "delta1_over_delta2": d,
                   "lam": lam}, "fhpe", 0.0, 4.0)
    return path.events[0]


#: The conductances whose profiles and edges are drawn.
PICTURED = [(10.0, 0.0), (10.0, 1.0)]


def profiles(history, pe_l, fH, K, k, d, lam, cond, fractions, label):
    """The pressure at Pe_l = fraction * pe_l, solved from the nearest step's edges."""
    out = []
    for f in fractions:
        pe = f * pe_l
        near = min(history, key=lambda h: abs(h["pe_hertz"] - pe))
        if abs(near["pe_hertz"] - pe) > 0.3 * pe_l:
            continue
        c = None if cond is None else (cond[0] * f ** (1.0 + cond[1]), cond[1])
        try:
            sol = ZoneModel(K, k2_over_k1=k, delta1_over_delta2=d, n=N, conductance=c).solve(
                np.reshape(near["edges"], (-1, 2)), pe, fH * pe, lam)
        except SolveError:
            continue
        x, p = sol.pressure_samples(101)
        out.append({"label": f"{label}, Pe_l = {f:g} Pe_l*", "x": x.tolist(),
                    "pressure": p.tolist(), "valid": bool(sol.valid)})
    return out


def _rounded(obj):
    """Floats to 7 significant digits (the record's numbers are not more accurate)."""
    if isinstance(obj, float):
        return float(f"{obj:.7g}")
    if isinstance(obj, dict):
        return {k: _rounded(v) for k, v in obj.items()}
    if isinstance(obj, list):
        return [_rounded(v) for v in obj]
    return obj


def study_path(spec):
    """One path's record: the single zone from Hertz's along the ray, the contact sets
    past its event, and the conductances' runs."""
    name, pe, K, k, d, lam = spec
    t0 = time.perf_counter()
    ev = first_event(pe, K, k, d, lam)
    # On a 'load' event P_H/P -> 0: stop just before it.
    f_star = ev.at if ev.inequality != "load" else 0.99 * ev.at
    L = Model(pe, K, k2_over_k1=k, delta1_over_delta2=d).solve(f_star, lam=lam).load_ratio
    fH = f_star / pe
    pe_l = pe / np.sqrt(L)
    lo, hi = 0.2 * pe_l, 1.1 * pe_l
    res = follow_contact_set(lambda t: (lo + t * (hi - lo), fH * (lo + t * (hi - lo))),
                             K, lam=lam, k2_over_k1=k, delta1_over_delta2=d, n=N)
    rec = {"path": name, "pe": pe, "K2_over_K1": K, "k2_over_k1": k,
           "delta1_over_delta2": d, "lam": lam, "n": N,
           "core_event": {"fhpe": ev.at, "inequality": ev.inequality, "load_ratio": L},
           "fH": fH, "pe_hertz_at_core_event": pe_l, "ray": [lo, hi],
           "status": res.status, "message": res.message, "event": res.event,
           "attempts": res.attempts,
           "zones_at_end": None if res.solution is None else res.solution.zone_records(),
           "other_starts": None if res.status != "solved" else other_starts(
               ZoneModel(K, k2_over_k1=k, delta1_over_delta2=d, n=N), res.solution, lam),
           "seconds": round(time.perf_counter() - t0, 1)}
    rec["histories"] = [{"label": "perfect contact", "steps": res.history}]
    rec["profiles"] = profiles(res.history, pe_l, fH, K, k, d, lam, None,
                               (0.4, 0.7, 1.0, 1.1), "perfect")
    rec["with_conductance"] = []
    # Also where perfect contact holds (path d): does a resistance break it?
    for bi, m in CONDUCTANCES:
        t1 = time.perf_counter()
        runs = []
        for end in (1.1, 2.0):
            def pe_at(t, end=end):
                return lo + t * (end * pe_l - lo)
            # A fixed law h = C p^m: at the mean Hertz pressure, which grows as
            # l, Bi0 = h0 l/K2 grows as l^(1 + m), l as Pe_l.
            r = follow_contact_set(
                lambda t, pe_at=pe_at: (pe_at(t), fH * pe_at(t)),
                K, lam=lam, k2_over_k1=k, delta1_over_delta2=d, n=N,
                conductance=lambda t, pe_at=pe_at, bi=bi, m=m: (
                    bi * (pe_at(t) / pe_l) ** (1.0 + m), m))
            runs.append({"pe_hertz_end": end * pe_l, "status": r.status,
                         "other_starts": None if r.status != "solved" else
                         other_starts(ZoneModel(K, k2_over_k1=k, delta1_over_delta2=d,
                                                n=N, conductance=(
                                                    bi * end ** (1.0 + m), m)),
                                      r.solution, lam),
                         "message": r.message, "event": r.event,
                         "zones": None if r.solution is None
                         else r.solution.zone_records()})
        rec["with_conductance"].append({"biot0_at_boundary": bi, "m": m, "runs": runs,
                                        "seconds": round(time.perf_counter() - t1, 1)})
        if (bi, m) in PICTURED:
            label = f"Bi0 = {bi:g}, m = {m:g}"
            rec["histories"].append({"label": label, "steps": r.history})
            rec["profiles"] += profiles(r.history, pe_l, fH, K, k, d, lam, (bi, m),
                                        (1.1, 1.5, 2.0), label)
        print(name, bi, m, [(x["status"], x["event"] and x["event"]["pe_hertz"])
                            for x in runs], flush=True)
    print(json.dumps(rec)[:600], flush=True)
    return rec


def main(workers=1):
    """Every path, each kept in a folder beside this file as it finishes (an
    interrupted study, run again, computes only the paths missing), then the JSON and
    the pictures, each written whole."""
    here = pathlib.Path(__file__).parent
    manifest = {"kind": "thermocontact crossing study", "version": __version__, "n": N,
                "paths": PATHS, "conductances": CONDUCTANCES}
    parts = here / ".crossing_study.parts"
    done = run_chunks(study_path, PATHS, manifest, parts, workers=workers,
                      what="the crossing study")
    out = [done[i] for i in range(len(PATHS))]
    with atomic_write(here / "crossing_study.json") as fh:
        fh.write(json.dumps(_rounded(out)) + "\n")
    for rec in out:
        crossing_figure(rec, str(here / f"path_{rec['path']}.png"))
    discard(parts)




def table(path=None):
    """The summary table of docs/zones.md, from crossing_study.json."""
    path = path or pathlib.Path(__file__).with_name("crossing_study.json")
    rows = ["| path | contact | Pe_l* (core) | single zone fails at Pe_l | status 10 % past |",
            "|---|---|---|---|---|"]
    for rec in json.loads(pathlib.Path(path).read_text()):
        ev = rec["event"]
        rows.append(f"| ({rec['path']}) | perfect | {rec['pe_hertz_at_core_event']:.5f} | "
                    + (f"{ev['pe_hertz']:.5f} ({ev['failure'].split(' at ')[0]} at x/l = "
                       f"{float(ev['failure'].split('X = ')[1]):.4f})" if ev else "—")
                    + f" | {rec['status']} |")
        for c in rec["with_conductance"]:
            outs = []
            for run in c["runs"]:
                e = run["event"]
                outs.append(run["status"] + (f" (fails at {e['pe_hertz']:.4f})" if e else ""))
            rows.append(f"| ({rec['path']}) | Bi0 = {c['biot0_at_boundary']:g}, m = {c['m']:g} | "
                        f"| | 1.1 Pe_l*: {outs[0]}; 2 Pe_l*: {outs[1]} |")
    return "\n".join(rows)


if __name__ == "__main__":
    import sys

    if sys.argv[1:] == ["--table"]:
        print(table())
    elif sys.argv[1:2] == ["--workers"] and len(sys.argv) == 3:
        main(int(sys.argv[2]))
    else:
        main()
