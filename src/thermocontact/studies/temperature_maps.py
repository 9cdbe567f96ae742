"""Operating maps at fixed bulk temperatures: the heat partition varies over the plane.

With ``lam`` given, load, speed and radius enter only through the Hertz Peclet number
and one ray answers a whole plane (:mod:`.operating_maps`, derivation section 11b).
With the bodies' far temperatures given instead (section 17) the closure's group
``Theta = pi K2 (T2 - T1)/(f |v1 - v2| P)`` and the sink's ``v1 L/(2 k2)`` depend on
load and speed themselves: each point is its own ray, and is answered by
:func:`~.physical_contact.contact` (its branches, ``lam`` with its error, the
absolute peak temperatures against the materials' limits), one task per line of
constant y.
"""

from __future__ import annotations

import json
import math

import numpy as np

from .._version import __version__
from ..problem.parameters import SolveError
from ..problem.validation import InputError
from .operating_maps import contact_set_fields, in_parts, line_fields
from .physical_contact import contact
from .ray import FIELD_TOL_FACTOR

__all__ = ["TEMPERATURE_FIELDS", "temperature_map"]

#: Numbers of each point's primary branch (NaN without one), then flags and words.
NUMBERS = ("lam", "lam_error", "half_width", "offset", "peak_pressure", "flash_temperature",
           "peak_temperature", "flash_temperature_half_plane", "load_ratio", "pe", "fhpe",
           "error_estimate")
FLAGS = ("valid", "applicable", "under_limit_cylinder", "under_limit_half_plane", "branches")
WORDS = ("status", "reason", "applicability_reasons")
TEMPERATURE_FIELDS = NUMBERS + FLAGS + WORDS


def evaluate_line(task) -> dict:
    """The contact at each of the task's points (:func:`~.physical_contact.contact`).

    ``under_limit_*`` is 1 below the material's limit, 0 above it, -1 for a material
    without one; ``status`` is ``"solved"``, ``"no branch"`` or ``"failed"``."""
    spec = task["spec"]
    out = {k: [] for k in TEMPERATURE_FIELDS}
    for load, speed, radius in task["points"]:
        row = dict.fromkeys(NUMBERS, math.nan)
        row.update(dict.fromkeys(FLAGS, 0), status="solved", reason="",
                   applicability_reasons="")
        try:
            res = contact(spec.problem(load=load, speed=speed, radius=radius), tol=spec.tol)
            b = res.primary
            row["branches"] = len(res.branches)
            if b is None:
                row.update(status="no branch", reason=res.message)
            else:
                row.update(lam=b.lam, lam_error=b.lam_error, half_width=b.half_width,
                           offset=b.offset, peak_pressure=b.peak_pressure,
                           flash_temperature=b.flash_temperature,
                           peak_temperature=b.peak_temperatures[0],
                           flash_temperature_half_plane=b.flash_temperatures[1],
                           load_ratio=b.load_ratio, pe=b.pe, fhpe=b.fhpe,
                           # The solution's estimate (P_H/P, sigma/Delta, lam) and its
                           # fields' (Branch.field_error), relative.
                           error_estimate=max(b.error_estimate, b.field_error),
                           valid=int(b.valid), applicable=int(b.applicable),
                           under_limit_cylinder=_flag(b.under_limits[0]),
                           under_limit_half_plane=_flag(b.under_limits[1]),
                           reason=b.solution.validity.reason,
                           applicability_reasons="; ".join(b.applicability.reasons))
        except (SolveError, InputError) as exc:
            row.update(status="failed", reason=str(exc))
        for k in TEMPERATURE_FIELDS:
            out[k].append(row[k])
    return out


def _flag(under):
    return -1 if under is None else int(under)


def temperature_map(spec, workers=1, progress=None, command=None, store_path=None):
    """The operating map of ``spec`` (an
    :class:`~thermocontact.studies.operating_maps.OperatingSpec` with bulk
    temperatures) as an :class:`xarray.Dataset` in SI units: over the two axes the
    primary branch's :data:`TEMPERATURE_FIELDS` (``lam`` the partition the
    temperatures imply, ``peak_temperature`` both surfaces' greatest absolute
    temperature, K; ``error_estimate`` the larger of the branch's relative estimates,
    its solution's and its fields', whose target is the attribute ``field_tol``), the
    Hertz Peclet number and the closure's group ``theta``; with ``spec.zones`` the
    contact sets' ``zones_*`` (:func:`~.operating_maps.evaluate_contact_sets`, the
    temperatures their closure too), each sought first from the valid primary branch's
    edges."""
    import os

    import xarray as xr

    load, speed, radius = spec.grid()
    line_progress, zone_progress = in_parts(progress, 1, spec.y.count if spec.zones else 0)
    found = line_fields(spec, evaluate_line, "bulk temperatures", TEMPERATURE_FIELDS, workers,
                        line_progress, store_path)
    dims = (spec.y.name, spec.x.name)
    data = {k: (dims, v.astype(str) if k in WORDS else v) for k, v in found.items()}
    if spec.zones:
        valid = found["valid"] == 1
        starts = np.where(valid, found["offset"] - found["half_width"], np.nan), np.where(
            valid, found["offset"] + found["half_width"], np.nan)
        data.update(contact_set_fields(
            spec, workers=workers, progress=zone_progress,
            store_path=None if store_path is None else os.path.join(store_path,
                                                                    "contact_sets"),
            starts=[[None if not v else (a, b) for v, a, b in zip(*row)]
                    for row in zip(valid, *starts)]))
    theta = np.vectorize(lambda P, v, R: spec.problem(load=P, speed=v, radius=R).theta)(
        load, speed, radius)
    ds = xr.Dataset({**data, "pe_hertz": (dims, spec.pe_hertz(load, speed, radius)),
                     "theta": (dims, theta)},
                    coords={spec.y.name: spec.y.values, spec.x.name: spec.x.values})
    ref = spec.reference()
    ds.attrs.update({"title": "thermocontact operating map at fixed bulk temperatures",
                     "thermocontact_version": __version__, "cylinder": spec.cylinder.name,
                     "half_plane": spec.half_plane.name, "friction": spec.friction,
                     "bulk_temperatures": list(ref.bulk_temperatures),
                     "sink_distance": -1.0 if ref.sink_length is None else ref.sink_length,
                     "x": spec.x.spec, "y": spec.y.spec, "tol": spec.tol,
                     "field_tol": FIELD_TOL_FACTOR * spec.tol, "units": "SI",
                     "command": command or "", "chunk_axis": "y", "picture_field": "lam",
                     "manifest": json.dumps(spec.manifest(), sort_keys=True),
                     **{k: v for k, v in spec.fixed.items()}})
    return ds
