"""The crossing study of docs/zones.md: what exists past the single patch's boundary.

Each path is a growing load at fixed f·H (a ray Pe_l -> (Pe_l, fH Pe_l) in units of
the Hertz half-width l of the load), its fH chosen so that the single patch's
boundary, found by the core along fHPe at the paper's Pe, is crossed.  The single
zone is followed from Hertz's along the ray to 10 % past the boundary; where it fails
the contact sets the failure suggests are tried (thermocontact.studies.contact_sets).
Writes crossing_study.json beside this file.

    python docs/zones/crossing_study.py
"""

import json
import pathlib
import time

import numpy as np

from thermocontact import Model
from thermocontact.studies.boundaries import follow
from thermocontact.studies.contact_sets import follow_contact_set

#: (name, Pe at the boundary, K2/K1, k2/k1, delta1/delta2, lam)
PATHS = [
    ("a", 5.0, 10.0, 10.0, 1.0, 1.0),
    ("b", 10.0, 100.0, 100.0, 1.0, 1.0),
    ("c", 0.2, 1.0, 1.0, 1.0, 0.5),
    ("d", 5.0, 10.0, 10.0, 2.0, -1.0),
]
N = 24


def first_event(pe, K, k, d, lam):
    """The single patch's first event along fHPe at Pe (the core, derivation section 8)."""
    path = follow({"pe": pe, "K2_over_K1": K, "k2_over_k1": k, "delta1_over_delta2": d,
                   "lam": lam}, "fhpe", 0.0, 4.0)
    return path.events[0]


def main():
    out = []
    for name, pe, K, k, d, lam in PATHS:
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
               "seconds": round(time.perf_counter() - t0, 1)}
        print(json.dumps(rec)[:600], flush=True)
        out.append(rec)
    path = pathlib.Path(__file__).with_name("crossing_study.json")
    path.write_text(json.dumps(out, indent=1) + "\n")


if __name__ == "__main__":
    main()
