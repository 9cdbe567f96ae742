"""What kind of end an event of a path is: fold, Hopf or grazing.

The steady contact at an event of :func:`~thermocontact.studies.boundaries.follow` is
linearised at fixed load and its growing modes counted (derivation section 18,
:func:`~thermocontact.solvers.stability.stability_of`): a real eigenvalue of largest real
part with ``Re b >= b_min`` makes the event a ``"fold"`` (a real mode grows, the
branch's real eigenvalue having passed through zero), a complex pair a ``"hopf"`` (an
oscillating mode grows), and none, every mode decaying where validity is lost, a
``"grazing"`` end; ``"unstable"`` where modes were counted but none located,
``"uncertified"`` where the count could not be certified.  :func:`map_stability` gives
each point of a map its verdict, count and largest growth rate.
"""

from __future__ import annotations

from dataclasses import replace
from functools import partial

import numpy as np

from ..discretisation.linearised import check_modelled
from ..execution.executors import run
from ..problem.validation import InputError
from ..solvers.stability import STABILITY_N, stability_of
from .boundaries import Path, closure, model_for

__all__ = ["check_map_stability", "classify", "kind_of", "map_stability", "stability_at"]

#: A map's closures: its points are analysed at the heat partition they imply.
_CLOSURES = ("lam", "sigma_over_delta", "theta", "sink_distance")


def kind_of(result) -> str:
    """``"grazing"``, ``"fold"`` or ``"hopf"`` from a
    :class:`~thermocontact.solvers.stability.StabilityResult`: no eigenvalue in its
    region, or the one of largest real part real or complex; ``"unstable"`` where the
    count is positive but no eigenvalue was located, ``"uncertified"`` where the count
    could not be certified."""
    if result.stable is None:
        return "uncertified"
    if result.stable:
        return "grazing"
    if not len(result.eigenvalues):
        return "unstable"
    lead = result.eigenvalues[0]
    return "fold" if abs(lead.imag) <= 1e-9 * max(1.0, abs(lead)) else "hopf"


def classify(path: Path, *, n=STABILITY_N, progress=None, **region) -> Path:
    """``path`` with each event's ``kind`` (and nothing else changed).

    Parameters
    ----------
    path : Path
        Of a dimensionless problem (:func:`~thermocontact.studies.boundaries.follow`).
    n : int
        Unknowns per function of the stability analysis.
    progress : callable, optional
        ``progress(stage, done, total)`` over the events' evaluations of ``M(b)``
        (:func:`~thermocontact.studies.boundaries.trace`'s form).
    **region
        ``b_min``, ``modulus_bound`` of
        :func:`~thermocontact.solvers.stability.stability_of`.

    Returns
    -------
    Path

    Raises
    ------
    InputError
        A physical path, or a problem the stability analysis does not model.
    """
    if "pe" not in path.fixed and path.along != "pe":
        raise InputError("the kinds of events are computed for dimensionless paths only",
                         parameters=("stability",))
    events = []
    for i, event in enumerate(path.events):
        # The path's fixed inputs hold one closure, never the parameter followed.
        kw = {**path.fixed, path.along: event.at}
        told = None if progress is None else (
            lambda done, total, i=i: progress("kinds of events", i * total + done,
                                              len(path.events) * total))
        events.append(replace(event, kind=kind_of(stability_at(kw, path.method, n=n,
                                                               progress=told, **region))))
    return replace(path, events=tuple(events))


def stability_at(kw: dict, method, *, n=STABILITY_N, progress=None, guesses=(),
                 predictions=(), samples=(), estimate=True, **region):
    """The :class:`~thermocontact.solvers.stability.StabilityResult` of the steady
    single patch of the dimensionless inputs ``kw`` (those of ``solve``, closed by
    ``lam``, ``sigma_over_delta`` or the far temperatures ``theta``), eigenvalues in
    units of ``k2/Delta^2``; ``guesses``, ``predictions`` and ``samples`` (a neighbour's
    eigenvalues, a real one continued from two, and a neighbour's contour samples) and
    ``estimate`` as in
    :func:`~thermocontact.solvers.stability.stability_of`."""
    model = model_for(kw, method=method)

    def solve_at(m):
        return model.solve_at(m, kw["fhpe"], check_validity=False, **closure(kw))
    if guesses is not None and len(guesses):
        region = {**region, "guesses": guesses}
    if len(samples):
        region = {**region, "samples": samples}
    if len(predictions):
        region = {**region, "predictions": predictions}
    if not estimate:
        region = {**region, "estimate": False}
    return stability_of(solve_at, n=n, progress=progress, **region)


def check_map_stability(spec) -> None:
    """Refuse, before the map is computed, a map whose contacts the stability analysis
    does not model: a method other than an edge-graded one
    (:func:`~thermocontact.discretisation.linearised.check_modelled`).

    Raises
    ------
    InputError
    """
    check_modelled(method=spec.method)


def map_stability(ds, spec, *, n=STABILITY_N, workers=1, **region):
    """A dimensionless map with the stability of its solved points.

    Each point not ``"failed"`` is analysed at its own inputs and heat partition
    (the dataset's ``lam``, whatever closed the map: the steady state at that ``lam``
    is the same, and the perturbation leaves the far field unchanged), by
    :func:`stability_at` without the error estimate (which the map does not hold),
    row by row (the points of a row of constant Peclet number share the cylinder's
    kernels; the rows run where ``workers`` says), the eigenvalues of the point before
    it in its row given as guesses to locate its own (the count at the point is the
    certificate).

    Parameters
    ----------
    ds : xarray.Dataset
        Of :func:`~thermocontact.studies.maps.compute_map`.
    spec : MapSpec
        Its specification.
    n : int
        Unknowns per function of the stability analysis.
    workers : int, executor, dask Client or callable
        Where the rows run (:func:`thermocontact.execution.executors.run`): the map's
        own.
    **region
        ``b_min``, ``modulus_bound`` of
        :func:`~thermocontact.solvers.stability.stability_of`.

    Returns
    -------
    xarray.Dataset
        ``ds`` with ``stable`` (1: no eigenvalue in the region, 0: one or more, -1: not
        analysed, -2: the count not certified), ``unstable_modes`` (the count; -1
        where not analysed or not certified) and ``growth_rate`` (the largest real part
        of an eigenvalue located, k2/Delta^2; NaN where none or not analysed).
    """
    dims = (spec.y.name, spec.x.name)
    stable = np.full(ds["valid"].shape, -1, dtype=np.int8)
    modes = np.full(ds["valid"].shape, -1, dtype=np.int32)
    rate = np.full(ds["valid"].shape, np.nan)
    lam = ds["lam"].broadcast_like(ds["valid"]).transpose(*ds["valid"].dims).values
    status = np.asarray(ds["status"].values)
    rows = []
    for j in range(status.shape[0]):
        points = []
        for i in range(status.shape[1]):
            if status[j, i] == "failed":
                continue
            kw = {**spec.fixed, spec.y.name: float(spec.y.values[j]),
                  spec.x.name: float(spec.x.values[i])}
            kw = {k: v for k, v in kw.items() if k not in _CLOSURES}
            kw["lam"] = float(lam[j, i])
            points.append((i, kw))
        rows.append((j, points))
    row_task = partial(_row_stability, method=spec.method, n=n, region=region)
    for j, verdicts in run(row_task, rows, workers=workers):
        for i, verdict, count, growth in verdicts:
            stable[j, i], modes[j, i], rate[j, i] = verdict, count, growth
    out = ds.assign(stable=(dims, stable), unstable_modes=(dims, modes),
                    growth_rate=(dims, rate))
    out["stable"].attrs.update(
        long_name="1 where no eigenvalue of the contact linearised at fixed load has "
                  "Re b >= b_min, 0 where one does, -1 not analysed, -2 not certified",
        flag_values=np.array([-2, -1, 0, 1], dtype=np.int8),
        flag_meanings="not_certified not_analysed unstable stable")
    out["unstable_modes"].attrs.update(
        long_name="eigenvalues with Re b >= b_min counted by the argument principle "
                  "(-1 where not analysed or not certified)")
    out["growth_rate"].attrs.update(
        long_name="largest real part of an eigenvalue located (NaN where none)",
        units="k2/Delta^2")
    return out


def _row_stability(row, *, method, n, region):
    """``[(i, stable, unstable_modes, growth_rate), ...]`` of one row of a map
    (:func:`map_stability`): ``row`` is ``(j, [(i, inputs), ...])``; each point's
    guesses are the eigenvalues of the point before it in the row, and the samples of
    its count those of the row's last point analysed."""
    _, points = row
    out, before, last, single = [], None, None, []
    for i, kw in points:
        extra = {}
        if before is not None:
            # The row's points share the kernels: the samples of the point before cost
            # no kernel's evaluation here.
            extra = {"samples": before.samples,
                     "guesses": before.eigenvalues if last == i - 1 else ()}
        if len(single) == 2 and single[0][0] == i - 2 and single[1][0] == i - 1:
            # One real root at each of the two points before: its logarithm continued
            # linearly, where it moved by less than a factor 1.5.
            (_, b2), (_, b1) = single
            if max(b1 / b2, b2 / b1) < 1.5:
                extra["predictions"] = [b1 * b1 / b2]
        res = stability_at(kw, method, n=n, estimate=False, **region, **extra)
        before, last = res, i
        ev = res.eigenvalues
        real = len(ev) == 1 and ev[0].imag == 0 and res.unstable_modes == 1
        single = (single + [(i, float(ev[0].real))])[-2:] if real else []
        out.append((i, -2 if res.stable is None else int(res.stable),
                    -1 if res.unstable_modes is None else res.unstable_modes,
                    np.nan if res.growth_rate is None else res.growth_rate))
    return out
