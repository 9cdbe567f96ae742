"""The validity boundary along fHPe by the path follower at the boundary points of
tests/test_maps.py's small map, computed once and stored.

Run ``python tests/data/make_boundary_paths.py`` to regenerate
``tests/data/boundary_paths.json`` (a few seconds).  The map is ``fhpe:0:0.8:9`` by
``pe:1:10:3:log`` at K2/K1 = 10, lam = 1; its boundary points are those on its lines
and those traced between them where the boundary bends.  For each point checked (every
one on a line, and the first three in every fifth between them: :func:`picked`) the
follower (:func:`thermocontact.studies.boundaries.follow`: its own n and samples, to
1e-6) is run along fHPe from 0 to 0.8 at the point's Pe; stored are that Pe and the
positions where the follower finds validity change.
"""

from __future__ import annotations

import json
import pathlib

import numpy as np

from thermocontact.io.files import atomic_write
from thermocontact.studies.boundaries import follow
from thermocontact.studies.maps import MapSpec, compute_map, parse_axis

OUT = pathlib.Path(__file__).resolve().parent / "boundary_paths.json"
#: The map of tests/test_maps.py (its X, Y and FIXED).
X, Y = "fhpe:0:0.8:9", "pe:1:10:3:log"
FIXED = {"K2_over_K1": 10.0, "lam": 1.0}


def picked(ds):
    """The indices of the boundary points checked: every one on a line, and every fifth
    of those between the lines, the first three."""
    between = ds.boundary_between_lines.values == 1
    return np.concatenate([np.flatnonzero(~between), np.flatnonzero(between)[::5][:3]])


def main():
    ds = compute_map(MapSpec(parse_axis("--x", X), parse_axis("--y", Y), dict(FIXED)),
                     workers=1)
    points = []
    for i in picked(ds):
        pe = float(ds.boundary_y.values[i])
        path = follow({"pe": pe, **FIXED}, "fhpe", 0.0, 0.8, tol=1e-6)
        points.append({"pe": pe, "map_fhpe": float(ds.boundary_x.values[i]),
                       "events": [e.at for e in path.events
                                  if e.valid_before != e.valid_after]})
        print(points[-1], flush=True)
    record = {"x": X, "y": Y, "fixed": FIXED, "points": points}
    with atomic_write(OUT) as fh:
        fh.write(json.dumps(record, indent=1) + "\n")


if __name__ == "__main__":
    main()
