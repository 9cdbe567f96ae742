"""The existence boundary fHPe*(Pe) for K2/K1 = 1, 10, 100 and lambda = -1, 0, 1.

Run: ``python docs/maps/existence_boundaries.py`` (about two minutes on two cores).
Each case is the map

    thermocontact map --x fhpe:0:2:41 --y pe:0.1:100:13:log --K2-over-K1 K --lam L

(k2/k1 = K2/K1, delta1 = delta2) and the table gives, per Pe, the first fHPe along the
grid line where the single patch stops being valid (located by Brent's method to 1e-9
relative), with the inequality that fails; '>2' where it stays valid up to fHPe = 2.
"""

from __future__ import annotations

import numpy as np

from thermocontact.studies.maps import MapSpec, compute_map, parse_axis


def main():
    pes = parse_axis("--y", "pe:0.1:100:13:log").values
    rows = {}
    for K in (1.0, 10.0, 100.0):
        for lam in (-1.0, 0.0, 1.0):
            spec = MapSpec(parse_axis("--x", "fhpe:0:2:41"), parse_axis("--y", "pe:0.1:100:13:log"),
                           {"K2_over_K1": K, "lam": lam})
            ds = compute_map(spec, workers=None)
            col = []
            for pe in pes:
                sel = (ds.boundary_y.values == pe) & (ds.boundary_valid_before.values == 1)
                if sel.any():
                    k = np.flatnonzero(sel)[np.argmin(ds.boundary_x.values[sel])]
                    col.append(f"{ds.boundary_x.values[k]:.4f} {ds.boundary_inequality.values[k]}")
                else:
                    col.append(">2" if ds.valid.sel(pe=pe).values[0] else "none valid")
            rows[(K, lam)] = col
    keys = list(rows)
    print("| Pe | " + " | ".join(f"K2/K1={int(K)}, λ={lam:g}" for K, lam in keys) + " |")
    print("|---" * (len(keys) + 1) + "|")
    for i, pe in enumerate(pes):
        print(f"| {pe:.3g} | " + " | ".join(rows[k][i] for k in keys) + " |")


if __name__ == "__main__":
    main()
