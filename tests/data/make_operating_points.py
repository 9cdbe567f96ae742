"""`contact` at 50 random points of an operating map's plane, computed once and stored.

Run ``python tests/data/make_operating_points.py`` to regenerate
``tests/data/operating_points.json`` (about a minute on two cores).  The plane is that
of ``tests/test_operating_maps.py``'s map (copper cylinder, R = 10 mm, on steel whose
surface moves against it at half its speed, f = 0.2, lambda = -1, the Dundurs term
on; load 10-20 kN/m, speed 0.8-2 m/s): its four grid points (the corners), then
points drawn uniformly in log load and log speed from a fixed seed.  Each is solved
by `contact` on its own (its own
continuation along the ray, its own roots refined on the solver, its fields refined
to their target): an independent route to the map's numbers, which are read from
interpolants of the ray's samples.  Stored per point: the inputs, the primary
branch's half-width, offset, peak pressure, flash temperature, slopes, strains,
validity and applicability, and its error estimates.

Also the fields of one sample of the brake block's ray (wheel steel on the organic
block, R = 0.46 m, f = 0.3, lambda = -1: the ray of the brake example of
docs/maps.md), at Pe = 163.77 with n = 256 unknowns per function: the reference of the
fields' error estimate (`refine_fields`) from n = 32, where P_H/P has met 1e-6 and the
fields are 6e-5 off.
"""

from __future__ import annotations

import json
import pathlib
from concurrent.futures import ProcessPoolExecutor

import numpy as np

#: The plane and the points (also read by the test).
PLANE = {"cylinder": "copper", "half_plane": "steel", "radius": 0.01, "friction": 0.2,
         "lam": -1.0, "speed_ratio": -0.5, "load": (1e4, 2e4), "speed": (0.8, 2.0)}
COUNT = 50
SEED = 20261128


def points():
    """The four corners, then COUNT random points."""
    rng = np.random.default_rng(SEED)
    lo, hi = (np.log([PLANE[k][0] for k in ("load", "speed")]),
              np.log([PLANE[k][1] for k in ("load", "speed")]))
    corners = [(PLANE["load"][i], PLANE["speed"][j]) for j in (0, 1) for i in (0, 1)]
    return np.concatenate([np.array(corners), np.exp(lo + (hi - lo) * rng.random((COUNT, 2)))])


def one(point):
    from thermocontact.problem.materials import get_material
    from thermocontact.studies.physical_contact import PhysicalProblem, contact

    load, speed = (float(v) for v in point)
    prob = PhysicalProblem(get_material(PLANE["cylinder"]), get_material(PLANE["half_plane"]),
                           PLANE["radius"], load, speed, PLANE["friction"], PLANE["lam"],
                           speed2=PLANE["speed_ratio"] * speed)
    b = contact(prob).primary
    a = b.applicability
    return {"load": load, "speed": speed, "half_width": b.half_width, "offset": b.offset,
            "peak_pressure": b.peak_pressure, "flash_temperature": b.flash_temperature,
            "max_slope": list(a.max_slope), "max_strain": list(a.max_strain),
            "valid": b.valid, "applicable": b.applicable, "n": b.solution.n,
            "error_estimate": b.error_estimate, "field_error": b.field_error}


#: The brake ray's sample of the fields' reference, and its n.
BRAKE_PE = 163.76933068423324
BRAKE_N = 256


def brake_fields():
    """``{quantity: value}`` of the fields at BRAKE_PE on the brake ray with BRAKE_N
    unknowns per function (dimensionless: pressures of P/Delta, temperatures of
    f v P/(pi K1))."""
    from thermocontact.analysis.fields import contact_fields
    from thermocontact.problem.materials import get_material
    from thermocontact.studies.physical_contact import PhysicalProblem, problem_ray
    from thermocontact.studies.ray import FIELD_QUANTITIES, FieldLevel

    prob = PhysicalProblem(get_material("wheel-steel"),
                           get_material("organic-composite-brake-block"), 0.46, 310e3, 30.0,
                           0.3, -1.0)
    sol = problem_ray(prob).solve_at(BRAKE_PE, BRAKE_N, polish=False)
    level = FieldLevel(sol, contact_fields(sol, fractions=prob.compliance_fractions))
    return {"pe": BRAKE_PE, "n": BRAKE_N,
            "fields": {q: getattr(level, q) for q in FIELD_QUANTITIES}}


def main():
    with ProcessPoolExecutor(2) as pool:
        brake = pool.submit(brake_fields)
        rows = list(pool.map(one, points()))
    out = pathlib.Path(__file__).with_name("operating_points.json")
    out.write_text(json.dumps({"plane": PLANE, "seed": SEED, "corners": rows[:4],
                               "points": rows[4:], "brake_fields": brake.result()},
                              indent=1) + "\n")
    print(f"wrote {out.name}: {len(rows)} points, field errors up to "
          f"{max(r['field_error'] for r in rows):.1e}")


if __name__ == "__main__":
    main()
