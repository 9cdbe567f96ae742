"""What kind of end an event of a path is: fold, Hopf or grazing.

The steady contact at an event of :func:`~thermocontact.studies.boundaries.follow` is
linearised at fixed load and its eigenvalues found (derivation section 18,
:func:`~thermocontact.solvers.stability.stability_of`): a real eigenvalue of largest real
part in the right half-plane makes the event a ``"fold"`` (a real mode grows, the
branch's real eigenvalue having passed through zero), a complex pair a ``"hopf"`` (an
oscillating mode grows), and none, every mode decaying where validity is lost, a
``"grazing"`` end.
"""

from __future__ import annotations

from dataclasses import replace

from ..problem.validation import InputError
from ..solvers.stability import STABILITY_N, stability_of
from .boundaries import Path, model_for

__all__ = ["classify", "kind_of"]


def kind_of(result) -> str:
    """``"grazing"``, ``"fold"`` or ``"hopf"`` from a
    :class:`~thermocontact.solvers.stability.StabilityResult`: no eigenvalue in its
    region, or the one of largest real part real or complex."""
    if result.stable or not len(result.eigenvalues):
        return "grazing"
    lead = result.eigenvalues[0]
    return "fold" if abs(lead.imag) <= 1e-9 * max(1.0, abs(lead)) else "hopf"


def classify(path: Path, *, n=STABILITY_N, **region) -> Path:
    """``path`` with each event's ``kind`` (and nothing else changed).

    Parameters
    ----------
    path : Path
        Of a dimensionless problem (:func:`~thermocontact.studies.boundaries.follow`).
    n : int
        Unknowns per function of the stability analysis.
    **region
        ``re_min``, ``re_max``, ``im_max``, ``points`` of
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
    for event in path.events:
        # The path's fixed inputs hold one closure, never the parameter followed.
        kw = {**path.fixed, path.along: event.at}
        model = model_for(kw, method=path.method)

        def solve_at(m, kw=kw, model=model):
            return model.solve_at(m, kw["fhpe"], lam=kw.get("lam"),
                                  sigma_over_delta=kw.get("sigma_over_delta"),
                                  check_validity=False)
        events.append(replace(event, kind=kind_of(stability_of(solve_at, n=n, **region))))
    return replace(path, events=tuple(events))
