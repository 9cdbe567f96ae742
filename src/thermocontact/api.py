"""The public calls: one per command of the command line.

Each function here is what a command does, from Python: it takes the command's
inputs as keyword arguments (physical quantities as SI numbers or as strings with
units, ``"10mm"``, ``"50kN/m"``), checks them, composes the studies beneath and
returns a result whose ``to_dict()`` is the command's JSON (or, for a map, the
:class:`xarray.Dataset` the command writes).  Errors name the parameters as spelled
here; the command line maps them to its flags.

=================================  ===========================================
command                            call
=================================  ===========================================
``thermocontact solve``            :func:`thermocontact.solve`, :class:`thermocontact.Model`
``thermocontact contact``          :func:`contact`
``thermocontact contact --zones``  :func:`contact_set` in physical units
``thermocontact zones``            :func:`contact_set`
``thermocontact boundary``         :func:`boundary`
``thermocontact map``              :func:`parameter_map`, :func:`operating_map`
``thermocontact transient``        :func:`transient` (:func:`transient_spec`,
                                   :func:`compute_transient`, :func:`read_transient`)
``contact ... --transient``        :func:`contact_transient` (:func:`contact_transient_spec`)
=================================  ===========================================
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from .discretisation.methods import DEFAULT_METHOD, DEFAULT_TOL, METHODS
from .problem.axes import Axis
from .problem.closure import (DIMENSIONLESS_CLOSURES, PHYSICAL_CLOSURES, BulkTemperatures,
                              FarTemperatures, HeatPartition, Offset, check_sink_distance,
                              closure_of, temperature_closure)
from .problem.validation import (InputError, check_callable, check_choice, check_flag,
                                 check_integer, check_nonnegative, check_pair, check_positive,
                                 check_sink_given)
from .problem.vocabulary import deprecated_spellings
from .solvers.single_patch import Model, solve

if TYPE_CHECKING:  # the results' types, named in the calls' annotations
    import xarray

    from .solvers.stability import StabilityResult
    from .solvers.transient import TransientRun, TransientSpec
    from .studies.boundaries import Path
    from .studies.contact_sets import ContactSetResult
    from .studies.maps import MapSpec
    from .studies.operating_maps import OperatingSpec
    from .studies.physical_contact import PhysicalContact
    from .studies.tei import TEIResult

__all__ = ["Axis", "BulkTemperatures", "FarTemperatures", "HeatPartition", "Model", "Offset",
           "boundary", "compute_map", "compute_transient", "contact", "contact_set",
           "contact_transient", "contact_transient_spec", "map_spec", "operating_map",
           "parameter_map", "read_transient", "solve", "stability", "tei", "transient",
           "transient_spec"]

#: Physical parameters a path may follow, and their SI units ("" is dimensionless).
PHYSICAL_ALONG = {"load": "N/m", "speed": "m/s", "radius": "m", "friction": "",
                  "temperature_difference": "K", "sink_distance": "m"}


def _materials(cylinder, half_plane, materials, names=("cylinder", "half_plane")):
    """Both bodies as :class:`~thermocontact.problem.materials.Material`; names and
    inline specifications are looked up (with ``materials``, a TOML file, first).
    Anything else is refused naming its parameter (``names``)."""
    from .problem.materials import Material, get_material, load_materials

    for name, m in zip(names, (cylinder, half_plane)):
        if not isinstance(m, (str, Material)):
            raise InputError(f"{name} must be a material name, an inline definition "
                             f"'E=..,nu=..,alpha=..,K=..,k=..' or a Material, got {m!r}",
                             parameters=(name,))
    if materials is not None:
        load_materials(materials)  # read and checked even when both bodies are inline
    return tuple(m if isinstance(m, Material) else get_material(m, materials)
                 for m in (cylinder, half_plane))


def _quantity(name, value, unit):
    from .problem.units import parse_quantity

    if value is None:
        return None
    return parse_quantity(value, unit, name)


def _physical_problem(cylinder, half_plane, radius, load, speed, friction, closure: dict,
                      speed2=0.0, dundurs=True, materials=None):
    """The problem in SI units; ``closure``: ``lam``, or ``bulk_temperatures`` with
    ``sink_distance`` or ``layer_thickness`` (:func:`_physical_closure`)."""
    from .studies.physical_contact import PhysicalProblem

    cyl, half = _materials(cylinder, half_plane, materials)
    return PhysicalProblem(cyl, half, _quantity("radius", radius, "m"),
                           _quantity("load", load, "N/m"), _quantity("speed", speed, "m/s"),
                           friction, closure.get("lam"), _quantity("speed2", speed2, "m/s"),
                           dundurs=check_flag("dundurs", dundurs),
                           bulk_temperatures=closure.get("bulk_temperatures"),
                           sink_distance=closure.get("sink_distance"),
                           layer_thickness=closure.get("layer_thickness"))


def _physical_conductance(conductance):
    """``None``, a :class:`~thermocontact.studies.contact_sets.PhysicalConductance` or
    ``(h0, m[, p_ref])`` with ``p_ref`` in Pa or with units."""
    from .problem.conductance import PhysicalConductance

    if conductance is None or isinstance(conductance, PhysicalConductance):
        return conductance
    try:
        h0, m, *rest = conductance
    except (TypeError, ValueError):
        raise InputError(f"conductance must be (h0, m[, p_ref]) with h0 in W/(m^2 K), "
                         f"got {conductance!r}", parameters=("conductance",)) from None
    if len(rest) > 1:
        raise InputError(f"conductance must be (h0, m[, p_ref]), got {conductance!r}",
                         parameters=("conductance",))
    p_ref = _quantity("conductance p_ref", rest[0], "Pa") if rest else None
    return PhysicalConductance(h0, m, p_ref)


def _contact_set_moved(func):
    """``contact(..., zones=True[, conductance=...])`` of earlier versions:
    :func:`contact_set` with the same inputs, and a DeprecationWarning."""
    import functools
    import warnings

    @functools.wraps(func)
    def call(*args, **kwargs):
        if "zones" not in kwargs and "conductance" not in kwargs:
            return func(*args, **kwargs)
        zones = check_flag("zones", kwargs.pop("zones", False))
        conductance = kwargs.pop("conductance", None)
        if not zones:
            if conductance is not None:
                raise InputError("conductance needs a contact set (contact_set): the single "
                                 "patch assumes perfect thermal contact",
                                 parameters=("conductance",))
            return func(*args, **kwargs)
        warnings.warn("contact: zones=True (and conductance=): the spelling of versions "
                      "before 1.0, taken until 1.1; call contact_set(cylinder=...) "
                      "(CHANGELOG.md)", DeprecationWarning, stacklevel=2)
        kwargs.pop("tol", None)  # the single patch's target
        names = ("cylinder", "half_plane")
        kwargs.update(zip(names, args))
        return contact_set(conductance=conductance, **kwargs)
    return call


@_contact_set_moved
@deprecated_spellings(closure="physical")
def contact(cylinder, half_plane, *, radius, load, speed, friction, lam=None, closure=None,
            speed2=0.0, dundurs=True, materials=None, tol=1e-6,
            progress=None) -> PhysicalContact:
    """The contact of a cylinder on a half-plane from materials, load and speed.

    ``thermocontact contact`` from Python: every half-width that carries the load as a
    single contact patch (its branches, the one of least half-width first), with its
    pressure, temperatures, validity and whether the theory applies.  The contact set
    of one zone or several is :func:`contact_set`.

    Parameters
    ----------
    cylinder, half_plane : str or Material
        A name from the materials table (``"steel"``, ``"copper"``), an inline
        ``"E=..,nu=..,alpha=..,K=..,k=.."``, or a
        :class:`~thermocontact.problem.materials.Material`.
    radius : float or str
        Cylinder radius R, m (or with units, ``"10mm"``).
    load : float or str
        Load per unit length P, N/m (``"50kN/m"``).
    speed : float or str
        The cylinder's surface speed through the contact v1 > 0, m/s (``"72km/h"``).
    friction : float
        Coefficient of friction f >= 0.
    lam : float, optional
        Heat partition (Q1 - Q2)/(Q1 + Q2): the same as ``closure=HeatPartition(lam)``.
    closure : HeatPartition or BulkTemperatures
        What fixes the heat partition (:mod:`thermocontact.problem.closure`):
        :class:`~thermocontact.HeatPartition`, or the bodies' far temperatures
        :class:`~thermocontact.BulkTemperatures` (``lam`` then an output with its
        error, each body's absolute peak temperature judged against its material's
        limit; derivation section 17).  Exactly one of ``lam`` and ``closure``.
    speed2 : float or str
        The half-plane's surface speed v2, m/s, positive in the cylinder's direction;
        0 (default) is a stationary half-plane.  The heat is made at ``|v1 - v2|``.
    dundurs : bool
        Keep the Dundurs term ``-(beta f/2) p`` (default; derivation section 5c).
    materials : str or path, optional
        A TOML file adding or overriding materials.
    tol : float
        Error target of P_H/P per branch.
    progress : callable, optional
        ``progress(done, total)`` while the half-widths are followed.

    Returns
    -------
    PhysicalContact
        ``to_dict()`` is the JSON of ``thermocontact contact ... --json``.

    Examples
    --------
    >>> import thermocontact as tc
    >>> res = tc.contact("copper", "steel", radius="10mm", load="50kN/m", speed="2m/s",
    ...                  friction=0.2, lam=-1)
    >>> round(res.primary.half_width * 1e3, 4)  # mm
    0.0776
    """
    problem = _physical_problem(cylinder, half_plane, radius, load, speed, friction,
                                _physical_closure(closure, lam), speed2, dundurs, materials)
    tol = check_positive("tol", tol)
    check_callable("progress", progress)
    from .studies.physical_contact import contact as contact_of

    return contact_of(problem, tol=tol, progress=progress)


def _physical_closure(closure, lam, required=True) -> dict:
    """The closure of a call in physical units, as the physical problem's keywords
    (``lam``, or ``bulk_temperatures`` with ``sink_distance`` or ``layer_thickness``)."""
    found = closure_of(closure, lam=lam, kinds=PHYSICAL_CLOSURES, required=required)
    return {} if found is None else found.keywords()


def _dimensionless_closure(closure, lam, sigma_over_delta, required=True) -> dict:
    """The closure of a call in dimensionless form, as the solvers' keywords (``lam``,
    ``sigma_over_delta``, or ``theta`` with ``sink_distance`` in the problem's unit of
    length)."""
    found = closure_of(closure, lam=lam, sigma_over_delta=sigma_over_delta,
                       kinds=DIMENSIONLESS_CLOSURES, required=required)
    return {} if found is None else found.keywords()


def _physical_contact_set(args, kwargs) -> bool:
    """Whether a call to :func:`contact_set` is in physical units."""
    return any(kwargs.get(k) is not None for k in ("cylinder", "half_plane"))


@deprecated_spellings(closure="either", physical=_physical_contact_set)
def contact_set(pe_hertz=None, fhpe_hertz=None, K2_over_K1=None, *, lam=None,
                sigma_over_delta=None, closure=None, k2_over_k1=None,
                delta1_over_delta2=1.0, speed_ratio=None, beta_f=None, cylinder=None,
                half_plane=None, radius=None,
                load=None, speed=None, friction=None, speed2=0.0, dundurs=True,
                materials=None, conductance=None, n=32, progress=None) -> ContactSetResult:
    """The contact set at one load: one zone or several, or why there is none.

    ``thermocontact zones`` (dimensionless) and ``thermocontact contact --zones``
    (physical) from Python (derivation section 14).  Dimensionless: lengths in units of
    the Hertz half-width ``l`` of the load, from the undeformed cylinder's lowest point;
    loads as fractions of P; pressures in P/l.  Physical: the inputs of
    :func:`contact`, the answer in SI units as well.

    Parameters
    ----------
    pe_hertz : float
        ``Pe_l = v l/(2 k2) > 0`` (dimensionless).
    fhpe_hertz : float
        ``fHPe_l = f H Pe_l >= 0`` (dimensionless).
    K2_over_K1 : float
        Conductivity ratio > 0 (dimensionless).
    lam : float, optional
        Heat partition (Q1 - Q2)/(Q1 + Q2), ``|lam| <= 1e6`` as for :func:`solve`
        (beyond [-1, 1] a formal continuation: one body gives heat to the contact, as a
        hot body does between unequal far temperatures): ``closure=HeatPartition(lam)``.
    sigma_over_delta : float, optional
        Or the offset ``centre/half-width`` of one zone (section 16; ``fhpe_hertz > 0``):
        ``closure=Offset(sigma_over_delta)`` (dimensionless).
    closure : HeatPartition, Offset, FarTemperatures or BulkTemperatures
        What fixes the heat partition (:mod:`thermocontact.problem.closure`):
        dimensionless, :class:`~thermocontact.FarTemperatures` with its sink distance in
        units of ``l`` (D38); physical, :class:`~thermocontact.BulkTemperatures`.
        ``lam`` is then an output.  Exactly one of ``lam``, ``sigma_over_delta`` and
        ``closure``.
    k2_over_k1 : float, optional
        Diffusivity ratio > 0 (default ``K2_over_K1``; dimensionless).
    delta1_over_delta2 : float
        Distortivity ratio >= 0 (dimensionless).
    speed_ratio : float, optional
        ``R = v2/v1``, the half-plane's surface speed over the cylinder's (default 0;
        dimensionless; sections 5b and 16), as for :func:`solve`.
    beta_f : float, optional
        The Dundurs term's ``beta f`` (default 0; dimensionless; section 5c), as for
        :func:`solve`.
    cylinder, half_plane, radius, load, speed, friction, speed2, dundurs, materials
        The problem in physical units, as for :func:`contact` (``speed2`` the
        half-plane's surface speed, m/s; ``dundurs`` the term from the materials).
    conductance : tuple, optional
        An interface conductance ``h = h0 (p/p_ref)^m`` (section 15); default perfect
        thermal contact.  Dimensionless ``(Bi0, m)``: the Biot number
        ``Bi0 = h0 l/K2`` at the mean Hertz pressure ``p_ref = P/(2 l)``; physical
        ``(h0, m[, p_ref])``, ``h0`` in W/(m^2 K), ``p_ref`` in Pa (default the mean
        Hertz pressure), or a PhysicalConductance.
    n : int
        Unknowns per function per zone, 8 to 256.
    progress : callable, optional
        As the continuation advances (each evaluation of the defects tells it: a run
        bounded by its budget of evaluations): dimensionless ``progress(fraction)``;
        physical ``progress(percent, 100)``.

    Returns
    -------
    ContactSetResult
        ``status`` (``"solved"``, ``"no steady solution"`` or ``"not converged"``),
        ``message``, ``answer``; ``to_dict()`` is the JSON of ``thermocontact zones``.
        Physical: a :class:`~thermocontact.PhysicalContactSet`, the same result with
        the problem, the fields and the applicability in SI units (the JSON of
        ``thermocontact contact --zones``).

    Examples
    --------
    >>> import thermocontact as tc
    >>> res = tc.contact_set(5.43, 0.3, 10, lam=1)
    >>> res.status, len(res.answer.zone_records())
    ('solved', 1)
    """
    check_callable("progress", progress)
    n = check_integer("n", n, 8, 256)
    physical = {"cylinder": cylinder, "half_plane": half_plane, "radius": radius,
                "load": load, "speed": speed, "friction": friction}
    if cylinder is not None or half_plane is not None:
        for name, value in (("pe_hertz", pe_hertz), ("fhpe_hertz", fhpe_hertz),
                            ("K2_over_K1", K2_over_K1), ("sigma_over_delta", sigma_over_delta),
                            ("k2_over_k1", k2_over_k1)):
            if value is not None:
                raise InputError(f"{name} belongs to a dimensionless contact set, not to one "
                                 f"with cylinder", parameters=(name, "cylinder"))
        for name, value in (("delta1_over_delta2", None if delta1_over_delta2 == 1.0
                             else delta1_over_delta2), ("speed_ratio", speed_ratio),
                            ("beta_f", beta_f)):
            if value is not None:
                raise InputError(f"{name} belongs to a dimensionless contact set: the "
                                 f"physical problem gives it (speed2, dundurs, the materials)",
                                 parameters=(name,))
        for name, value in physical.items():
            if value is None:
                raise InputError(f"{name} must be given for a contact set in physical units",
                                 parameters=(name,))
        from .studies.contact_sets import physical_contact_set

        problem = _physical_problem(cylinder, half_plane, radius, load, speed, friction,
                                    _physical_closure(closure, lam), speed2, dundurs,
                                    materials)
        return physical_contact_set(
            problem, conductance=_physical_conductance(conductance), n=n,
            progress=None if progress is None else (
                lambda fraction: progress(round(100 * fraction), 100)))
    for name, value in {**physical, "speed2": speed2 or None, "materials": materials,
                        "dundurs": None if dundurs is True else dundurs}.items():
        if value is not None:
            raise InputError(f"{name} belongs to a contact set in physical units: give "
                             f"cylinder and half_plane too", parameters=(name, "cylinder"))
    for name, value in (("pe_hertz", pe_hertz), ("fhpe_hertz", fhpe_hertz),
                        ("K2_over_K1", K2_over_K1)):
        if value is None:
            raise InputError(f"{name} must be given (or the problem in physical units: "
                             f"cylinder, half_plane, ...)", parameters=(name,))
    from .studies.contact_sets import find_contact_set

    given = _dimensionless_closure(closure, lam, sigma_over_delta)
    return find_contact_set(pe_hertz, fhpe_hertz, K2_over_K1, lam=given.get("lam"),
                            sigma_over_delta=given.get("sigma_over_delta"),
                            temperatures=temperature_closure(given.get("theta"),
                                                             given.get("sink_distance")),
                            k2_over_k1=k2_over_k1,
                            delta1_over_delta2=delta1_over_delta2,
                            speed_ratio=_zero_absent("speed_ratio", speed_ratio) or 0.0,
                            beta_f=_zero_absent("beta_f", beta_f) or 0.0, n=n,
                            conductance=None if conductance is None else check_pair(
                                "conductance", conductance, "(Bi0, m), two numbers"),
                            progress=progress)


def _physical_path_call(args, kwargs) -> bool:
    """Whether a call to :func:`boundary` follows a physical path."""
    along = args[0] if args else kwargs.get("along")
    return (any(kwargs.get(k) is not None for k in ("cylinder", "half_plane"))
            or (isinstance(along, str) and along.replace("-", "_") in PHYSICAL_ALONG))


def _closure_parts(closure, lam, sigma_over_delta) -> dict:
    """The closure of a path or map (of any kind, checked where it is used, or none: one
    of its parts followed) as keywords: ``lam``, ``sigma_over_delta``, ``theta`` and
    ``sink_distance`` (``L/Delta``), or the bulk temperatures in SI units."""
    found = closure_of(closure, lam=lam, sigma_over_delta=sigma_over_delta,
                       kinds=DIMENSIONLESS_CLOSURES + PHYSICAL_CLOSURES, required=False)
    return {} if found is None else found.keywords()


@deprecated_spellings(renamed=(("sigma", "sigma_over_delta"),), closure="either",
                      physical=_physical_path_call)
def boundary(along, start, stop, *, pe=None, fhpe=None, K2_over_K1=None, k2_over_k1=None,
             delta1_over_delta2=None, speed_ratio=None, beta_f=None, lam=None,
             sigma_over_delta=None, closure=None, cylinder=None, half_plane=None,
             radius=None, load=None, speed=None, friction=None, dundurs=None,
             materials=None, method=None, tol=DEFAULT_TOL, n=None, progress=None,
             stability=False) -> Path:
    """Every sign change of a contact inequality's margin along one parameter, and
    where solutions stop or start existing, located to 1e-9 relative.

    ``thermocontact boundary`` from Python.  Events chain (each one's ``valid_before``
    is the previous one's ``valid_after``); ``Event.changes_validity`` is False for a
    margin that changes sign where another inequality already fails.  Dimensionless: give the problem as for
    :func:`thermocontact.solve` less the parameter followed.  Physical: give
    ``cylinder`` and ``half_plane`` and the others of :func:`contact` less the one
    followed (``load``, ``speed``, ``radius`` or ``friction``); the branch of least
    half-width is followed.

    Parameters
    ----------
    along : str
        Dimensionless: ``"fhpe"``, ``"pe"``, ``"lam"``, ``"sigma_over_delta"``,
        ``"theta"``, ``"K2_over_K1"``, ``"k2_over_k1"``, ``"delta1_over_delta2"``,
        ``"speed_ratio"``, ``"beta_f"`` (hyphens accepted for underscores; ``"sigma"``
        for ``"sigma_over_delta"``, as on the command line); physical: ``"load"``
        (N/m), ``"speed"`` (m/s), ``"radius"`` (m), ``"friction"``, and with
        :class:`~thermocontact.BulkTemperatures` ``"temperature_difference"`` (T2 - T1
        in K, T1 kept) and ``"sink_distance"`` (m) (derivation section 17).
    start, stop : float or str
        The path's ends (physical ones in SI units or with units).
    pe, fhpe, K2_over_K1, k2_over_k1, delta1_over_delta2, speed_ratio, beta_f : float
        The dimensionless problem (:func:`thermocontact.solve`); ``speed_ratio`` also
        with the physical one (the half-plane's surface at that multiple of the
        cylinder's speed).
    lam, sigma_over_delta, closure
        The closure, exactly one unless it is followed, as for :func:`solve`
        (dimensionless) or :func:`contact` (physical: ``lam`` or
        :class:`~thermocontact.BulkTemperatures`).  Following ``theta``:
        ``closure=FarTemperatures(None, sink_distance_over_delta)`` gives the sink.
    cylinder, half_plane, radius, load, speed, friction, dundurs, materials
        The physical problem, as for :func:`contact`.
    method : str, optional
        Discretisation method of a dimensionless path (default ``"graded"``); a
        physical path refuses it.
    tol : float
        Error target for the choice of ``n``.
    n : int, optional
        Unknowns per function of the whole path instead of the choice by ``tol``.
    progress : callable, optional
        ``progress(stage, done, total)``.
    stability : bool, optional
        Also each event's ``kind``, ``"fold"``, ``"hopf"``, ``"grazing"`` (or
        ``"unstable"``, ``"uncertified"``), from the eigenvalues of the steady contact
        there (:func:`stability`; dimensionless paths; seconds per event).

    Returns
    -------
    Path
        ``x``, ``valid``, the margins and ``events``; ``to_dict()`` is the JSON of
        ``thermocontact boundary``.

    Examples
    --------
    >>> import thermocontact as tc
    >>> path = tc.boundary("fhpe", 0, 1, pe=5, K2_over_K1=10, lam=1)
    >>> [round(e.at, 4) for e in path.events]
    [0.6654, 0.702]
    """
    tol = check_positive("tol", tol)
    check_callable("progress", progress)
    parts = _closure_parts(closure, lam, sigma_over_delta)
    lam, sigma, theta = (parts.get(k) for k in ("lam", "sigma_over_delta", "theta"))
    stability = check_flag("stability", stability)
    physical = {"cylinder": cylinder, "half_plane": half_plane, "radius": radius,
                "load": load, "speed": speed, "friction": friction, "dundurs": dundurs,
                "materials": materials, "bulk_temperatures": parts.get("bulk_temperatures"),
                "sink_distance": parts.get("sink_distance"),
                "layer_thickness": parts.get("layer_thickness")}
    from .studies.boundaries import SPELLINGS

    if not isinstance(along, str):
        raise InputError(f"along must be one of {sorted(SPELLINGS) + sorted(PHYSICAL_ALONG)}"
                         f", got {along!r}", parameters=("along",))
    along_name = along.replace("-", "_")
    if cylinder is not None or half_plane is not None or along_name in PHYSICAL_ALONG:
        dimensionless = {"pe": pe, "fhpe": fhpe, "K2_over_K1": K2_over_K1,
                         "k2_over_k1": k2_over_k1, "delta1_over_delta2": delta1_over_delta2,
                         "beta_f": _zero_absent("beta_f", beta_f),
                         "sigma_over_delta": sigma, "method": method, "theta": theta}
        if stability:
            raise InputError("the kinds of events (stability) are computed for "
                             "dimensionless paths only", parameters=("stability",))
        return _physical_path(along_name, start, stop, physical, lam,
                              _zero_absent("speed_ratio", speed_ratio) or 0.0,
                              dimensionless, tol, n, progress)
    from .studies.boundaries import follow
    from .studies.maps import NAMES

    method = DEFAULT_METHOD if method is None else check_choice("method", method, METHODS)
    # A dimensionless path's sink distance is L/Delta, of its far temperatures (section 17).
    dimensionless_sink = None
    if isinstance(closure, FarTemperatures):
        dimensionless_sink, physical["sink_distance"] = physical["sink_distance"], None
    for name, value in physical.items():
        if value is not None:
            raise InputError(f"{name} belongs to a physical path: give cylinder and "
                             f"half_plane too", parameters=(name, "cylinder", "half_plane"))
    if along_name not in NAMES:
        raise InputError(f"along must be one of {sorted(SPELLINGS) + sorted(PHYSICAL_ALONG)}"
                         f", got {along!r}", parameters=("along",))
    name = NAMES[along_name]
    given = {"pe": pe, "fhpe": fhpe, "K2_over_K1": K2_over_K1, "k2_over_k1": k2_over_k1,
             "delta1_over_delta2": delta1_over_delta2,
             # 0, the default, is left out
             "speed_ratio": _zero_absent("speed_ratio", speed_ratio),
             "beta_f": _zero_absent("beta_f", beta_f), "lam": lam, "sigma_over_delta": sigma,
             "theta": theta, "sink_distance": None if dimensionless_sink is None else
             check_sink_distance(_number("sink_distance", dimensionless_sink))}
    if given[name] is not None:
        raise InputError(f"{name} must not be given: it is the parameter followed",
                         parameters=(name,))
    fixed = {k: v for k, v in given.items() if v is not None and k != name}
    for k in ("pe", "fhpe", "K2_over_K1"):
        if k != name and k not in fixed:
            raise InputError(f"{k} must be given (it is not the parameter followed)",
                             parameters=(k,))
    closures = [k for k in ("lam", "sigma_over_delta", "theta") if k in fixed or k == name]
    if len(closures) != 1:
        raise InputError("give exactly one closure: lam, sigma_over_delta or closure (or "
                         "follow one of lam, sigma_over_delta and theta)",
                         parameters=("lam", "sigma_over_delta", "closure"))
    _check_sink(fixed, closures[0], (name,))
    path = follow(fixed, name, _number("start", start), _number("stop", stop),
                  method=method, tol=tol, n=n, progress=progress)
    if not stability:
        return path
    from .studies.event_kinds import classify

    return classify(path, progress=progress)


def _zero_absent(name, value):
    """A parameter whose default 0 means "not given" (``speed_ratio``, ``beta_f``): None
    for None or 0, else the number checked."""
    if value is None:
        return None
    return _number(name, value) or None


def _number(name, value) -> float:
    from .problem.validation import check_finite

    if isinstance(value, str):
        try:
            number = float(value)
        except ValueError:
            raise InputError(f"{name} must be a number, got {value!r}",
                             parameters=(name,)) from None
        # A number written with a non-zero digit that rounds to 0 (1e-400) underflowed.
        if number == 0.0 and any(c in "123456789" for c in value.lower().split("e")[0]):
            raise InputError(f"{name} must be 0 or at least 5e-324 in magnitude, "
                             f"got {value!r}, which rounds to 0",
                             parameters=(name,))
        value = number
    return check_finite(name, value)


def _physical_path(along, start, stop, physical, lam, speed_ratio, dimensionless, tol, n,
                   progress):
    """The path of :func:`boundary` along a physical parameter."""
    from .studies.physical_contact import follow_along

    if along not in PHYSICAL_ALONG:
        raise InputError(f"along must be one of {sorted(PHYSICAL_ALONG)} with cylinder, "
                         f"got {along!r}", parameters=("along", "cylinder"))
    for name in ("cylinder", "half_plane"):
        if physical[name] is None:
            raise InputError(f"{name} must be given: along {along} the path is physical",
                             parameters=(name,))
    for name, value in dimensionless.items():
        if value is not None:
            raise InputError(f"{name} belongs to a dimensionless path, not to one with "
                             f"cylinder", parameters=(name, "cylinder"))
    for name in ("cylinder", "half_plane", "radius", "load", "speed", "friction"):
        if name != along and physical[name] is None:
            raise InputError(f"{name} must be given (it is not the parameter followed)",
                             parameters=(name,))
    # (Along the temperature difference the bulk temperatures are given: the
    # cylinder's is kept.)
    if physical.get(along) is not None:
        raise InputError(f"{along} must not be given: it is the parameter followed",
                         parameters=(along,))
    if (lam is None) == (physical["bulk_temperatures"] is None):
        raise InputError("give one closure: lam or closure=BulkTemperatures(...)",
                         parameters=("lam", "closure"))
    unit = PHYSICAL_ALONG[along]
    ends = [_quantity(o, v, unit) if unit else _number(o, v)
            for o, v in (("start", start), ("stop", stop))]
    values = {k: (ends[0] if k == along else physical[k])
              for k in ("radius", "load", "speed", "friction")}
    speed = _quantity("speed", values["speed"], "m/s")
    # Along the sink distance the path's start stands for it.
    sink = ends[0] if along == "sink_distance" else physical["sink_distance"]
    closure = {"lam": lam} if lam is not None else {
        "bulk_temperatures": physical["bulk_temperatures"], "sink_distance": sink,
        "layer_thickness": physical["layer_thickness"]}
    prob = _physical_problem(physical["cylinder"], physical["half_plane"], values["radius"],
                             values["load"], speed, values["friction"], closure,
                             speed2=speed * speed_ratio,
                             dundurs=(True if physical["dundurs"] is None
                                      else physical["dundurs"]),
                             materials=physical["materials"])
    return follow_along(prob, along, ends[0], ends[1], tol=tol, n=n, progress=progress)


@deprecated_spellings(renamed=(("sigma", "sigma_over_delta"),), closure="dimensionless")
def parameter_map(x, y, *, pe=None, fhpe=None, K2_over_K1=None, k2_over_k1=None,
                  delta1_over_delta2=None, speed_ratio=None, beta_f=None, lam=None,
                  sigma_over_delta=None, closure=None, delta_over_r=None,
                  method=DEFAULT_METHOD, tol=1e-6, workers=1, store=None, progress=None,
                  command=None, stability=False) -> xarray.Dataset:
    """The single patch over a grid of two dimensionless parameters.

    ``thermocontact map`` from Python: every point solved to ``tol``, and where
    validity changes located on every grid line by Brent's method (to 1e-9 along the
    line) and traced between the lines where it bends.

    Parameters
    ----------
    x, y : Axis
        Over two of ``fhpe``, ``pe``, ``lam``, ``sigma_over_delta``, ``K2_over_K1``,
        ``k2_over_k1``, ``delta1_over_delta2``, ``speed_ratio``, ``beta_f``, ``theta``.
    pe, fhpe, K2_over_K1, k2_over_k1, delta1_over_delta2, speed_ratio, beta_f : float
        The other inputs, as for :func:`thermocontact.solve`.
    lam, sigma_over_delta, closure
        The closure, as for :func:`thermocontact.solve`: exactly one, unless an axis is
        one of ``lam``, ``sigma_over_delta`` and ``theta`` (an axis ``theta`` with
        ``closure=FarTemperatures(None, sink_distance_over_delta)`` for its sink).
    delta_over_r : float, optional
        Half-width over radius: also map whether the theory applies.
    method : str
    tol : float
        Error target of every point.
    workers : int, executor, dask Client or callable
        Where the grid lines run (:func:`thermocontact.execution.executors.run`);
        default in this process.
    store : str or path, optional
        A folder keeping finished grid lines: an interrupted call given the same
        ``store`` resumes (and refuses a store of another map).
    progress : callable, optional
        ``progress(done, total)`` in grid lines.
    command : str, optional
        Recorded in the dataset's attributes.
    stability : bool, optional
        Also ``stable``, ``unstable_modes`` and ``growth_rate`` at every solved point,
        from the eigenvalues of its steady contact (:func:`stability` with its
        defaults, at the point's heat partition; seconds a point, in this process).

    Returns
    -------
    xarray.Dataset
        As written by ``thermocontact map --out``.

    Examples
    --------
    >>> import thermocontact as tc
    >>> ds = tc.parameter_map(tc.Axis("fhpe", 0, 0.8, 3), tc.Axis("pe", 1, 10, 2, log=True),
    ...                       K2_over_K1=10, lam=1)
    >>> ds["valid"].shape
    (2, 3)
    """
    stability = check_flag("stability", stability)
    spec = map_spec(x, y, pe=pe, fhpe=fhpe, K2_over_K1=K2_over_K1, k2_over_k1=k2_over_k1,
                    delta1_over_delta2=delta1_over_delta2, speed_ratio=speed_ratio,
                    beta_f=beta_f, lam=lam, sigma_over_delta=sigma_over_delta,
                    closure=closure, delta_over_r=delta_over_r, method=method, tol=tol)
    return compute_map(spec, workers=workers, store=store, progress=progress, command=command,
                       stability=stability)


@deprecated_spellings(closure="physical")
def operating_map(x, y, *, cylinder, half_plane, friction, lam=None, closure=None,
                  radius=None, load=None, speed=None, speed_ratio=0.0, dundurs=True,
                  materials=None, tol=1e-6, zones=False, conductance=None, workers=1,
                  store=None, progress=None, command=None) -> xarray.Dataset:
    """The contact of one material pair over a grid of load, speed or radius.

    ``thermocontact map --cylinder ... --half-plane ...`` from Python.  Load,
    radius and speed enter only through the Hertz Péclet number, so one ray of
    dimensionless solutions answers the whole plane.

    Parameters
    ----------
    x, y : Axis
        Two of ``load`` (N/m), ``speed`` (m/s) and ``radius`` (m); ends may carry
        units (``Axis("load", "1kN/m", "1MN/m", 41, log=True)``).
    cylinder, half_plane, friction, dundurs, materials
        As for :func:`contact`.
    lam, closure
        The closure, as for :func:`contact`: with
        :class:`~thermocontact.BulkTemperatures` ``lam`` varies over the plane and each
        point is solved as its own contact (derivation section 17); the dataset holds
        ``lam``, ``lam_error``, ``peak_temperature`` (absolute, K) and whether each body
        stays under its material's limit.
    radius, load, speed : float or str
        The third of them, the one that is not an axis.
    speed_ratio : float
        v2/v1: the half-plane's surface speed over the cylinder's (0, stationary).
    tol : float
        Error target of every sample of the ray.
    zones : bool
        Also the contact set at every point.
    conductance : (h0, m, p_ref) or PhysicalConductance, optional
        With ``zones``: one interface conductance law for the whole map.
    workers, store, progress, command
        As for :func:`parameter_map`.

    Returns
    -------
    xarray.Dataset
        As written by ``thermocontact map --cylinder ... --out``.
    """
    spec = map_spec(x, y, cylinder=cylinder, half_plane=half_plane, friction=friction,
                    lam=lam, closure=closure, radius=radius, load=load, speed=speed,
                    speed_ratio=speed_ratio, dundurs=dundurs, materials=materials, tol=tol,
                    zones=zones, conductance=conductance)
    return compute_map(spec, workers=workers, store=store, progress=progress, command=command)


def _physical_map_call(args, kwargs) -> bool:
    """Whether a call to :func:`map_spec` makes an operating map."""
    return any(kwargs.get(k) is not None for k in ("cylinder", "half_plane"))


@deprecated_spellings(renamed=(("sigma", "sigma_over_delta"),), closure="either",
                      physical=_physical_map_call)
def map_spec(x, y, *, pe=None, fhpe=None, K2_over_K1=None, k2_over_k1=None,
             delta1_over_delta2=None, speed_ratio=None, beta_f=None, lam=None,
             sigma_over_delta=None, closure=None, delta_over_r=None, method=None,
             cylinder=None, half_plane=None, friction=None, radius=None, load=None,
             speed=None, dundurs=None, materials=None, zones=False, conductance=None,
             tol=1e-6) -> MapSpec | OperatingSpec:
    """What identifies a map, every input checked, nothing computed.

    With ``cylinder`` and ``half_plane``, the
    :class:`~thermocontact.studies.operating_maps.OperatingSpec` of
    :func:`operating_map`; otherwise the :class:`~thermocontact.studies.maps.MapSpec`
    of :func:`parameter_map`.  Its ``manifest()`` tells whether a stored map (or a
    store of finished grid lines) belongs to the same inputs.  The parameters are
    those of the two functions; an input of the other kind of map is refused.

    Returns
    -------
    MapSpec or OperatingSpec
    """
    parts = _closure_parts(closure, lam, sigma_over_delta)
    lam, sigma, theta = (parts.get(k) for k in ("lam", "sigma_over_delta", "theta"))
    bulk_temperatures = parts.get("bulk_temperatures")
    sink_distance, layer_thickness = parts.get("sink_distance"), parts.get("layer_thickness")
    dimensionless = {"pe": pe, "fhpe": fhpe, "K2_over_K1": K2_over_K1,
                     "k2_over_k1": k2_over_k1, "delta1_over_delta2": delta1_over_delta2,
                     "beta_f": _zero_absent("beta_f", beta_f), "sigma_over_delta": sigma,
                     "delta_over_r": delta_over_r, "theta": theta}
    # The far temperatures' sink distance is L/Delta (section 17).
    dimensionless_sink = None
    if isinstance(closure, FarTemperatures):
        dimensionless_sink, sink_distance = sink_distance, None
    physical = {"radius": radius, "load": load, "speed": speed, "friction": friction,
                "dundurs": dundurs, "materials": materials, "zones": zones or None,
                "conductance": conductance, "bulk_temperatures": bulk_temperatures,
                "sink_distance": sink_distance, "layer_thickness": layer_thickness}
    if cylinder is None and half_plane is None:
        from .studies.maps import NAMES, MapSpec

        for name, value in physical.items():
            if value is not None:
                raise InputError(f"{name} belongs to an operating map: give cylinder and "
                                 f"half_plane too", parameters=(name, "cylinder", "half_plane"))
        fixed = {"pe": pe, "fhpe": fhpe, "K2_over_K1": K2_over_K1, "k2_over_k1": k2_over_k1,
                 "delta1_over_delta2": delta1_over_delta2,
                 "speed_ratio": _zero_absent("speed_ratio", speed_ratio),
                 "beta_f": _zero_absent("beta_f", beta_f),
                 "lam": lam, "sigma_over_delta": sigma, "theta": theta,
                 "sink_distance": None if dimensionless_sink is None else
                 check_sink_distance(_number("sink_distance", dimensionless_sink))}
        _refuse_axis_values((x, y), fixed, NAMES)
        _check_sink(fixed, "theta" if fixed.get("theta") is not None else None,
                    tuple(NAMES.get(getattr(a, "name", None)) for a in (x, y)))
        return MapSpec(x, y, fixed, method=DEFAULT_METHOD if method is None else method,
                       tol=tol, delta_over_r=delta_over_r)
    from .studies.operating_maps import OperatingSpec

    # The operating map derives the distortivity ratio from the materials and solves
    # with the default method: either given is refused rather than ignored.
    dimensionless["method"] = method
    for name, value in dimensionless.items():
        if value is not None:
            raise InputError(f"{name} belongs to a dimensionless map, not to an operating "
                             f"map (cylinder)", parameters=(name, "cylinder"))
    for name, value in (("cylinder", cylinder), ("half_plane", half_plane),
                        ("friction", friction)):
        if value is None:
            raise InputError(f"{name} must be given for an operating map", parameters=(name,))
    if (lam is None) == (bulk_temperatures is None):
        raise InputError("give one closure for an operating map: lam or "
                         "closure=BulkTemperatures(...)", parameters=("lam", "closure"))
    cyl, half = _materials(cylinder, half_plane, materials)
    units = {"radius": (radius, "m"), "load": (load, "N/m"), "speed": (speed, "m/s")}
    fixed = {k: _quantity(k, v, u) for k, (v, u) in units.items() if v is not None}
    _refuse_axis_values((x, y), fixed)
    return OperatingSpec(cyl, half, friction, lam, x, y, fixed,
                         tol=check_positive("tol", tol),
                         dundurs=True if dundurs is None else check_flag("dundurs", dundurs),
                         speed_ratio=_zero_absent("speed_ratio", speed_ratio) or 0.0,
                         zones=check_flag("zones", zones),
                         conductance=_physical_conductance(conductance),
                         bulk_temperatures=bulk_temperatures, sink_distance=sink_distance,
                         layer_thickness=layer_thickness)


def _check_sink(fixed, closure, varied):
    """A dimensionless path's or map's far temperatures (``closure`` ``"theta"``, given
    or ``varied``) with their sink where the half-plane is stationary and none where
    it moves, before any point is solved (``speed_ratio`` varied: each point says)."""
    # (A sink distance without theta is a physical input, refused as such.)
    if "theta" in varied:
        closure = "theta"
    others = [k for k in ("lam", "sigma_over_delta") if fixed.get(k) is not None or k in varied]
    # (A closure given twice is refused as such, where the closures are counted.)
    if closure == "theta" and not others and "speed_ratio" not in varied:
        check_sink_given(fixed.get("sink_distance"), not fixed.get("speed_ratio"))


def _refuse_axis_values(axes, given, names=None):
    """A value given for a parameter that is an axis is refused, not silently replaced
    by the axis (``names``: spellings of an axis name to the parameter's)."""
    for axis in axes:
        if isinstance(axis, Axis):
            name = (names or {}).get(axis.name, axis.name)
            if given.get(name) is not None:
                raise InputError(f"{name} must not be given: it is an axis",
                                 parameters=(name,))


def compute_map(spec, *, workers=1, store=None, progress=None, command=None,
                stability=False) -> xarray.Dataset:
    """The map that a :func:`map_spec` describes, as an :class:`xarray.Dataset`.

    :func:`parameter_map` and :func:`operating_map` are this call on their
    specification; the command line makes the specification first (to check its
    inputs and its output file before any work) and then calls this.

    Parameters
    ----------
    spec : MapSpec or OperatingSpec
    workers, store, progress, command, stability
        As for :func:`parameter_map` (``stability``: dimensionless maps only).

    Returns
    -------
    xarray.Dataset
    """
    from .studies.event_kinds import check_map_stability, map_stability
    from .studies.maps import MapSpec
    from .studies.maps import compute_map as dimensionless
    from .studies.operating_maps import OperatingSpec, compute_operating_map

    check_callable("progress", progress)
    if not isinstance(spec, (MapSpec, OperatingSpec)):
        raise InputError(f"spec must be a map's specification (map_spec), got {spec!r}",
                         parameters=("spec",))

    stability = check_flag("stability", stability)
    if stability and not isinstance(spec, MapSpec):
        raise InputError("stability: maps of dimensionless parameters only (for a physical "
                         "contact, stability() of the contact)", parameters=("stability",))
    if stability:
        check_map_stability(spec)
    if isinstance(spec, MapSpec):
        ds = dimensionless(spec, workers=workers, store_path=store, progress=progress,
                           command=command)
        return map_stability(ds, spec, workers=workers) if stability else ds
    if spec.bulk_temperatures is not None:
        # Each point its own contact at the temperatures (section 17).
        from .studies.temperature_maps import temperature_map

        return temperature_map(spec, workers, progress, command, store)
    return compute_operating_map(spec, workers=workers, progress=progress, command=command,
                                 store_path=store)


#: Lengths of layers and radii, m: a nanometre to a kilometre, as the wavelength.
_LENGTH_RANGE = (1e-9, 1e3)


def _length(name, value):
    from .problem.validation import check_range

    if value is None:
        return None
    try:
        x = _quantity(name, value, "m")
    except InputError as exc:       # the message names the parameter: so does the error
        raise InputError(str(exc), parameters=(name,)) from None
    return check_range(name, x, *_LENGTH_RANGE)


def _pair_of(name, value, kind):
    """``"a:b"`` or a pair, as two strings or numbers."""
    parts = value.split(":") if isinstance(value, str) else value
    try:
        a, b = parts
    except (TypeError, ValueError):
        raise InputError(f"{name} must be {kind}, got {value!r}", parameters=(name,)) from None
    return a, b


def _hot_spots(value):
    from .problem.validation import check_integer

    n1, n2 = _pair_of("hot_spots", value, "N1:N2, integers 1 <= N1 <= N2")
    try:
        n1, n2 = (int(x) if isinstance(x, str) and x.strip().isdigit() else x for x in (n1, n2))
        n1 = check_integer("hot_spots", n1, 1, 10000)
        n2 = check_integer("hot_spots", n2, 1, 10000)
    except InputError:
        raise InputError(f"hot_spots must be N1:N2, integers 1 <= N1 <= N2 <= 10000, got "
                         f"{value!r}", parameters=("hot_spots",)) from None
    if n2 < n1:
        raise InputError(f"hot_spots must be N1:N2 with N1 <= N2 (not empty), got {value!r}",
                         parameters=("hot_spots",))
    return n1, n2


def _separator(value, materials):
    from .problem.materials import Material, get_material

    if value is None:
        return None, None
    if isinstance(value, str):
        name, sep, thick = value.rpartition(":")
        if not sep:
            raise InputError(f"separator must be MATERIAL:THICKNESS (e.g. steel:2mm), got "
                             f"{value!r}", parameters=("separator",))
    else:
        name, thick = _pair_of("separator", value, "(material, thickness)")
    mat = name if isinstance(name, Material) else get_material(name, materials)
    return mat, _length("separator", thick)


def tei(slider, counterface, friction, wavelength, speed=None, dundurs=True, materials=None,
        *, slider_thickness=None, faces=2, counterface_thickness=None,
        backing="slip-insulated", separator=None, plane_stress=False, disc_radius=None,
        hot_spots=None, brake_stop=None, stop_history=None,
        stop_threshold=None, progress=None) -> TEIResult:
    """Thermoelastic instability of sliding bodies (``thermocontact tei``): two
    half-planes, a brake disc of finite thickness between pads, pads as layers on a
    backing plate, a clutch pack.

    The critical speed of every family of modes at one wavelength, the neutral mode's
    migration speed, each family's minimum over the wavelength; at a given speed,
    every growing mode and the most unstable wavelength; with a disc radius, the
    critical speed per number of hot spots; with a stop, each hot-spot number's
    amplification (docs/derivation.md, "Thermoelastic instability of sliding
    half-planes" and "Thermoelastic instability of layers").

    Parameters
    ----------
    slider, counterface : str or Material
        The sliding body (the disc; a clutch's friction-disc core) and the one it
        slides on (the pads; a clutch's facing): names, inline definitions
        ``"E=..,nu=..,alpha=..,K=..,k=.."`` or Materials.  ``K = 0`` is a
        non-conductor; not both.
    friction : float
        Coulomb coefficient ``f``: 0, or 1e-6 to 10
        (:data:`~thermocontact.physics.tei.FRICTION_RANGE`).
    wavelength : float or str
        ``L`` of the perturbation, 1 nm to 1 km
        (:data:`~thermocontact.physics.tei.WAVELENGTH_RANGE`), m or with units
        (``"50mm"``).
    speed : float or str, optional
        Sliding speed ``V``: 0, or 1e-9 to 1e4 m/s
        (:data:`~thermocontact.physics.tei.SPEED_RANGE`), m/s or with units: adds the
        modes at that speed and the most unstable wavelength.
    dundurs : bool, optional
        Keep the Dundurs term ``beta f`` (default), as ``contact`` does: in layers, the
        friction traction's elastic effect.
    materials : str or os.PathLike, optional
        A TOML file of further materials.
    slider_thickness : float or str, optional
        The disc's full thickness ``d`` (1 nm to 1 km); absent: a half-plane.
    faces : {2, 1}, optional
        2 (default): both faces rub on identical counterfaces, the modes split into
        the families symmetric and antisymmetric about the mid-plane; 1: the other
        face free and insulated.
    counterface_thickness : float or str, optional
        The pads' (a clutch's facings') thickness; absent: half-planes.
    backing : str, optional
        The pad layers' rigid backing plate: "slip-insulated" (default: the pad free
        to slip on it, no heat through it), "bonded-insulated" or "slip-isothermal".
    separator : str or (material, thickness), optional
        A clutch pack: the separator plates' material and thickness
        (``"steel:2mm"``); the friction disc's core is the slider
        (``slider_thickness``), its facings the counterface
        (``counterface_thickness``).
    plane_stress : bool, optional
        Plane stress instead of plane strain (thin discs).
    disc_radius : float or str, optional
        ``R``: adds the critical speed of ``n`` hot spots round the disc, wavelength
        ``2 pi R/n``, for ``hot_spots``.
    hot_spots : str or (int, int), optional
        ``"N1:N2"`` (default ``"1:60"`` with a radius).
    brake_stop : str or (float, float), optional
        ``"V0:DECEL"``: a stop from ``V0`` (m/s) at a constant deceleration (m/s^2),
        with ``disc_radius``: each hot-spot number's amplification.
    stop_history : str or os.PathLike, optional
        Instead of ``brake_stop``: a CSV file of time (s) and speed (m/s).
    stop_threshold : float, optional
        The amplification that marks a hot-spot number unstable over the stop
        (default ``e^5``).
    progress : callable, optional
        ``progress(stage, done, total)``: the analysis's stages (each family's
        critical speed, its curve over the wavelength, the hot-spot curves, the stop),
        each counted in scans from the lowest speed; layers take seconds to minutes.

    Returns
    -------
    TEIResult
        Its ``to_dict()`` is the command's JSON.

    Raises
    ------
    InputError
        Any input outside its range (a wavelength, speed, friction, a thickness that
        is not a positive length, an empty or non-integer hot-spot range, a stop
        that ends above its start, a non-conducting disc on non-conducting pads, an
        unknown material); the message is one line naming the parameter.  Raised
        before any computation.
    """
    from .problem.validation import check_choice, check_flag, check_integer

    s, c = _materials(slider, counterface, materials, names=("slider", "counterface"))
    dundurs = check_flag("dundurs", dundurs)
    check_callable("progress", progress)
    plane = "stress" if check_flag("plane_stress", plane_stress) else "strain"
    wl = _quantity("wavelength", wavelength, "m")
    v = _quantity("speed", speed, "m/s")
    d = _length("slider_thickness", slider_thickness)
    faces = check_integer("faces", faces, 1, 2)
    h = _length("counterface_thickness", counterface_thickness)
    from .studies.tei import BACKINGS

    backing = check_choice("backing", backing, BACKINGS)
    sep, sep_t = _separator(separator, materials)
    if sep is not None and (d is None or h is None):
        raise InputError("separator (a clutch pack) needs slider_thickness (the friction "
                         "disc's core) and counterface_thickness (its facings)",
                         parameters=("separator", "slider_thickness", "counterface_thickness"))
    radius = _length("disc_radius", disc_radius)
    if hot_spots is not None and radius is None:
        raise InputError("hot_spots needs disc_radius", parameters=("hot_spots", "disc_radius"))
    spots = None if radius is None else _hot_spots("1:60" if hot_spots is None else hot_spots)
    history = None
    if brake_stop is not None or stop_history is not None:
        from .studies.brake_stop import stop_history as make_history

        if radius is None:
            raise InputError("brake_stop needs disc_radius (its amplification is per number "
                             "of hot spots)", parameters=("brake_stop", "disc_radius"))
        history = make_history(brake_stop, stop_history, stop_threshold)
    from .execution.executors import one_blas_thread
    from .studies.tei import analyse, check_geometry

    # The problem statement checked whole before any work (two non-conductors
    # sliding on each other refused).
    check_geometry(s, c, slider_thickness=d, faces=faces, counterface_thickness=h,
                   backing=backing, separator=sep, separator_thickness=sep_t)
    # Small matrices: one BLAS thread is faster than several competing for the cores.
    with one_blas_thread():
        return analyse(s, c, friction, wl, speed=v, dundurs=dundurs, plane=plane,
                       slider_thickness=d, faces=faces, counterface_thickness=h,
                       backing=backing, separator=sep, separator_thickness=sep_t,
                       disc_radius=radius, hot_spots=spots, stop=history,
                       progress=progress)


@deprecated_spellings(renamed=(("re_min", "b_min"),),
                      retired=("re_max", "im_max", "points"))
def stability(solution, *, n=12, b_min=1e-3, modulus_bound=None,
              progress=None) -> StabilityResult:
    """Every growing mode of a steady single patch, counted: is it stable?

    The contact linearised about a steady solution at fixed load, its edges free, for a
    perturbation growing as ``exp(b t)`` (docs/derivation.md, section 18):
    ``M(b) c = 0``.  The eigenvalues with ``Re b >= b_min`` and ``|b| <= modulus_bound``
    (the region the model holds in, S11) are counted by the
    argument principle on the boundary of that region, located by Beyn's contour
    integral and confirmed by Newton's method; ``stable`` is True only where the
    count is 0, None (with the reason) where the count could not be certified.  A
    stationary or a moving half-plane, with or without the Dundurs term and an
    interface conductance.  A contact set of one or more zones (:func:`contact_set`),
    every edge free (section 18b): likewise.

    Parameters
    ----------
    solution : ContactSolution, PhysicalContact or ContactSetResult
        From :func:`solve` (edge-graded methods; eigenvalues in units of
        ``k2/Delta^2``), from :func:`contact` (its primary branch; eigenvalues in
        1/s) or from :func:`contact_set` (the set at the point asked for, solved with
        perfect thermal contact; eigenvalues, ``b_min`` and ``modulus_bound`` in units
        of ``k2/l^2``, ``l`` the Hertz half-width, or in 1/s for a physical one).
    n : int, optional
        Unknowns per function of the analysis (default 12, even, from 8 to 64; the
        steady solution is solved again at ``n``, and at ``3n/2`` for the error
        estimate where eigenvalues are found).
    b_min : float, optional
        The smallest growth rate counted, ``k2/Delta^2`` (> 0: ``b = 0`` is the
        branch point of the stationary half-plane's kernels; a fold's exponentially
        slow real root lies below the default, and the record estimates it).
    modulus_bound : float, optional
        ``|b|`` beyond which no eigenvalue is sought, ``k2/Delta^2`` (> 10 b_min): a
        mode beyond it has a thermal layer thinner than ``Delta/sqrt(modulus_bound)``
        (``Delta/1000`` by default, ``10^6``), where the model no longer holds (S11).
        For a contact set, in ``k2/l^2``, by default ``10^6/Delta_min^2``, ``Delta_min``
        its narrowest zone's half-width in units of ``l``: beyond it the thermal layer
        is thinner than a thousandth of every zone's half-width (S24).
    progress : callable, optional
        ``progress(done, total)`` over the evaluations of ``M(b)`` (``total`` an
        estimate).

    Returns
    -------
    StabilityResult
        ``to_dict()`` is the ``"stability"`` record of ``solve --stability`` and
        ``contact --stability``.

    Raises
    ------
    InputError
        A solution of neither kind, a Chebyshev method, a physical contact without a
        branch, a contact set not found at the point asked for, or a region out of
        range.

    Examples
    --------
    >>> import thermocontact as tc
    >>> res = tc.stability(tc.solve(2, 0.3, 1, lam=-1), n=8)
    >>> res.stable, res.unstable_modes
    (True, 0)
    """
    from .discretisation.linearised import check_modelled
    from .solvers.result import ContactSolution
    from .solvers.stability import MODULUS_BOUND, stability_of
    from .solvers.zones import ZoneSolution
    from .studies.contact_sets import ContactSetResult
    from .studies.physical_contact import PhysicalContact

    rate_unit = None
    if isinstance(solution, (ContactSetResult, ZoneSolution)):
        return _contact_set_stability(solution, n=n, b_min=b_min,
                                      modulus_bound=modulus_bound, progress=progress)
    if modulus_bound is None:
        modulus_bound = MODULUS_BOUND
    if isinstance(solution, PhysicalContact):
        # A physical contact: its primary branch, rates in 1/s (k2/Delta^2).
        branch = solution.primary
        if branch is None:
            raise InputError("stability: the contact has no branch to analyse",
                             parameters=("solution",))
        kw = solution.problem.to_dimensionless(branch.half_width)
        # With the bulk temperatures the branch's partition is the one they imply; the
        # perturbation leaves the far field unchanged, so the steady state is the same.
        kw["lam"] = branch.lam
        rate_unit = solution.problem.half_plane.k / branch.half_width ** 2
        method, conductance = DEFAULT_METHOD, None
    elif isinstance(solution, ContactSolution):
        p = solution.parameters
        kw = dict(pe=p.pe, fhpe=p.fhpe, K2_over_K1=p.K2_over_K1, k2_over_k1=p.k2_over_k1,
                  delta1_over_delta2=p.delta1_over_delta2, speed_ratio=p.speed_ratio,
                  beta_f=p.beta_f, lam=solution.lam)
        method = solution.method
        check_modelled(method=method)
        cond = solution.conductance
        conductance = None if cond is None else (cond.biot0, cond.exponent)
    else:
        raise InputError("solution must be a steady single patch of solve() or contact() "
                         f"or a contact set of contact_set(), got "
                         f"{type(solution).__name__}", parameters=("solution",))
    model = Model(kw["pe"], kw["K2_over_K1"], k2_over_k1=kw["k2_over_k1"],
                  delta1_over_delta2=kw["delta1_over_delta2"],
                  speed_ratio=kw.get("speed_ratio", 0.0), beta_f=kw.get("beta_f", 0.0),
                  method=method, conductance=conductance)

    def solve_at(m):
        return model.solve_at(m, kw["fhpe"], lam=kw["lam"], check_validity=False)
    return stability_of(solve_at, n=n, b_min=b_min, modulus_bound=modulus_bound,
                        rate_unit=rate_unit, progress=progress)


def _contact_set_stability(found, **region) -> StabilityResult:
    """:func:`stability` of a contact set (derivation section 18b): each zone's edges
    free, the eigenvalues in units of ``k2/l^2`` (``l`` the Hertz half-width), or 1/s
    for a physical one.  The set is solved again at the analysis' ``n`` from its edges,
    with its heat partition (the far temperatures' output, where they closed it: the
    perturbation leaves the far field unchanged)."""
    from .discretisation.linearised_set import modulus_bound as set_bound
    from .solvers.stability import MODULUS_BOUND, stability_of
    from .solvers.zones import ZoneModel, ZoneSolution
    from .studies.contact_sets import PhysicalContactSet

    rate_unit = None
    sol = found
    if not isinstance(found, ZoneSolution):
        sol = found.answer
        if sol is None:
            raise InputError(f"stability: no contact set at the point asked for "
                             f"({found.status}: {found.message})", parameters=("solution",))
    if region["modulus_bound"] is None:
        region["modulus_bound"] = set_bound(sol.half_widths, MODULUS_BOUND)
    if isinstance(found, PhysicalContactSet):
        rate_unit = found.problem.half_plane.k / found.hertz_half_width ** 2
    par = sol.parameters
    model = ZoneModel(par.K2_over_K1, k2_over_k1=par.k2_over_k1,
                      delta1_over_delta2=par.delta1_over_delta2, beta_f=par.beta_f,
                      method=sol.method, profile=sol.profile, speed_ratio=par.speed_ratio,
                      conductance=sol.conductance)

    def solve_at(m):
        return model.at_n(m).solve(sol.edges, par.pe, par.fhpe, lam=sol.lam,
                                   check_validity=False)
    return stability_of(solve_at, rate_unit=rate_unit, **region)


def _transient_closure(closure, lam) -> dict:
    """A transient run's closure as its specification's ``lam`` and ``theta`` (its far
    temperatures, both bodies infinite: no sink); how many are given, and whether the
    initial state takes them, the specification checks (TransientSpec)."""
    if closure is None:
        return {"lam": lam}
    if not isinstance(closure, (HeatPartition, FarTemperatures)) or closure.keywords().keys() & (
            {"lam"} if lam is not None else set()):
        closure_of(closure, lam=lam, kinds=(HeatPartition, FarTemperatures))
    if isinstance(closure, FarTemperatures) and (closure.sink_distance_over_delta is not None
                                                 or closure.theta is None):
        raise InputError("a transient run's far temperatures are FarTemperatures(theta) "
                         "alone: both bodies are infinite (no sink)", parameters=("closure",))
    return {"lam": lam, **closure.keywords()}


@deprecated_spellings(renamed=(("start", "initial"),), closure="dimensionless")
def transient_spec(pe_hertz, fhpe_hertz, K2_over_K1, *, until, steps, lam=None, closure=None,
                   k2_over_k1=None, delta1_over_delta2=1.0, elements=240, window=(-3.0, 3.0),
                   initial="hertz", hold="theta", perturb=0.0,
                   conductance=None) -> TransientSpec:
    """The inputs of a transient run, checked (:func:`transient` without the run).

    The command line makes the specification first, to compare it with a partial run
    on disk and to check its output files, before any work; :func:`compute_transient`
    then runs it.  Parameters as for :func:`transient`.

    Returns
    -------
    TransientSpec
    """
    from .solvers.transient import TransientSpec

    # Every input checked and converted by the specification itself.
    given = _transient_closure(closure, lam)
    return TransientSpec(pe_hertz=pe_hertz, fhpe_hertz=fhpe_hertz, K2_over_K1=K2_over_K1,
                         until=until, steps=steps, k2_over_k1=k2_over_k1,
                         delta1_over_delta2=delta1_over_delta2, lam=given.get("lam"),
                         theta=given.get("theta"), elements=elements, window=window,
                         initial=initial, hold=hold, perturb=perturb, conductance=conductance)


def compute_transient(spec, *, resume=None, progress=None, save=None, save_every=30.0,
                      preparing=None) -> TransientRun:
    """The transient run that a :func:`transient_spec` (or :func:`contact_transient_spec`)
    describes.

    Parameters
    ----------
    spec : TransientSpec
    resume : TransientRun, xarray.Dataset or path, optional
        A partial run of the same ``spec`` (``status == "partial"``, e.g. read back
        by :func:`read_transient`, or its dataset or file): its steps are taken as
        they are and the run goes on from its last; the steps computed are the same
        as without the interruption.
    progress : callable, optional
        ``progress(done, total)`` before the first step and after each step.
    save : callable, optional
        ``save(partial_run)`` at most every ``save_every`` seconds of computing.
    save_every : float
        Seconds.
    preparing : callable, optional
        ``preparing(done, total)`` while the operators are made, before any step (the
        lag tables a step of lag at a time: minutes for 100 000 steps or 4000
        elements).

    Returns
    -------
    TransientRun
    """
    from .solvers.transient import TransientRun, TransientSpec, read_run, run_transient

    if not isinstance(spec, TransientSpec):
        raise InputError(f"spec must be a transient run's specification (transient_spec), "
                         f"got {spec!r}", parameters=("spec",))
    if resume is not None and not isinstance(resume, TransientRun):
        resume = read_run(resume, "resume")
    for name, value in (("progress", progress), ("save", save), ("preparing", preparing)):
        check_callable(name, value)
    save_every = check_nonnegative("save_every", save_every)
    return run_transient(spec, resume=resume, progress=progress, save=save,
                         save_every=save_every, preparing=preparing)


def read_transient(ds) -> TransientRun:
    """The :class:`~thermocontact.TransientRun` of a dataset that ``to_dataset`` wrote.

    Parameters
    ----------
    ds : xarray.Dataset or path
        A transient run's dataset, or its file (``.nc``): its attributes are the
        inputs, ``status`` and ``seconds``; any others (those of
        :func:`contact_transient`) are left out.  Anything else, or a file that is
        missing or not a run's, is refused (:class:`InputError` naming ``ds``).

    Returns
    -------
    TransientRun
        Equal to the run that wrote the dataset.
    """
    from .solvers.transient import read_run

    return read_run(ds)


@deprecated_spellings(renamed=(("start", "initial"),), closure="dimensionless")
def transient(pe_hertz, fhpe_hertz, K2_over_K1, *, until, steps, lam=None, closure=None,
              k2_over_k1=None, delta1_over_delta2=1.0, elements=240, window=(-3.0, 3.0),
              initial="hertz", hold="theta", perturb=0.0, conductance=None, progress=None,
              resume=None, save=None, preparing=None) -> TransientRun:
    """The transient contact from switch-on (or from a steady state), in time.

    ``thermocontact transient`` from Python (docs/derivation.md, section 19).  Lengths
    in units of the Hertz half-width ``l`` of the load (as :func:`contact_set`), time
    in ``l^2/kappa2``; pressure in ``P/l``, heat flux in ``f v P/l``, temperature rises
    in ``f v P/(pi K2)``.  A stationary half-plane without the Dundurs term.

    Parameters
    ----------
    pe_hertz, fhpe_hertz, K2_over_K1 : float
        ``Pe_l = v l/(2 k2) > 0``, ``fHPe_l >= 0``, the conductivity ratio ``> 0``.
    until : float
        Duration ``> 0``, units ``l^2/kappa2``.
    steps : int
        Time steps, 1 to 100 000 (``dt = until/steps``; the scheme is first order in
        ``dt``).
    lam, closure : optional
        The far field: ``lam`` (``closure=HeatPartition(lam)``) holds the heat partition
        (in [-1, 1]) and lets the far temperature difference adjust, as the steady model
        does; ``closure=FarTemperatures(theta)`` holds the far temperatures,
        ``theta = pi K2 (T2 - T1)/(f v P)`` (section 17), with both bodies infinite (no
        sink).  With ``initial="steady"``, ``lam`` names the steady state.
    k2_over_k1, delta1_over_delta2 : float, optional
        Diffusivity ratio (default ``K2_over_K1``) and distortivity ratio (default 1).
    elements : int
        Equal elements on ``window`` (8 to 4000).
    window : (float, float)
        Where contact may occur, units ``l``; must contain ``(-1, 1)``.
    initial : {"hertz", "steady"}
        Isothermal bodies under Hertz's pressure, or the steady element solution at
        ``lam`` on the same elements.
    hold : {"theta", "lam"}
        From a steady start: hold that state's far temperatures (the closure of
        :func:`stability`) or its heat partition.
    perturb : float
        The load is ``1 + perturb`` during the first step (in [-0.5, 0.5]).
    conductance : (float, float), optional
        ``(Bi0, m)``: interface conductance ``Bi = Bi0 (2 p)^m`` (section 15).
    progress : callable, optional
        ``progress(done, total)`` before the first step and after each step.
    resume : TransientRun, optional
        A partial run of the same inputs to continue (or its dataset or file).
    save : callable, optional
        ``save(partial_run)`` every 30 s of computing.
    preparing : callable, optional
        ``preparing(done, total)`` while the operators are made, before any step
        (:func:`compute_transient`).

    Returns
    -------
    TransientRun
        ``to_dataset()`` is the file of ``thermocontact transient``.

    Examples
    --------
    >>> import thermocontact as tc
    >>> run = tc.transient(2.7, 0.36, 10, lam=1, until=1.0, steps=50, elements=120)
    >>> run.status, run.zones(-1)[0].size
    ('complete', 1)
    """
    spec = transient_spec(pe_hertz, fhpe_hertz, K2_over_K1, until=until, steps=steps, lam=lam,
                          closure=closure, k2_over_k1=k2_over_k1,
                          delta1_over_delta2=delta1_over_delta2, elements=elements,
                          window=window, initial=initial, hold=hold, perturb=perturb,
                          conductance=conductance)
    return compute_transient(spec, resume=resume, progress=progress, save=save,
                             preparing=preparing)


@deprecated_spellings(closure="physical")
def contact_transient_spec(cylinder, half_plane, *, radius, load, speed, friction, lam=None,
                           closure=None, duration, steps=1000, elements=240,
                           window=(-3.0, 3.0), speed2=0.0, dundurs=True,
                           materials=None) -> tuple:
    """The transient run of a contact in SI units: its specification and units.

    The physical problem of :func:`contact` in the units of the transient run
    (:func:`transient`), as the contact set of :func:`contact` with ``zones`` maps it:
    lengths in the Hertz half-width ``l`` of the load, ``Pe_l = v l/(2 k2)``,
    ``fHPe_l = f H Pe_l`` and the materials' ratios; time in ``l^2/k2`` (``k2`` the
    half-plane's diffusivity).

    Parameters
    ----------
    cylinder, half_plane, radius, load, speed, friction, materials
        As for :func:`contact`.
    lam, closure
        The heat partition held, in [-1, 1]: ``lam`` or ``closure=HeatPartition(lam)``
        (:class:`~thermocontact.BulkTemperatures` are not a closure of the transient
        run: they set a sink the run's infinite half-plane lacks).
    duration : float or str
        Time computed, s (or with units, ``"10ms"``).
    steps, elements, window
        As for :func:`transient` (``window`` in units of ``l``).
    speed2 : float or str
        Must be 0: the transient run has a stationary half-plane.
    dundurs : bool
        The transient run has no Dundurs term: ``False``, or materials and friction
        whose ``beta f`` is 0.

    Returns
    -------
    spec : TransientSpec
    attrs : dict
        The physical inputs and the units, the dataset's further attributes:
        ``length_unit_m`` (``l``), ``time_unit_s`` (``l^2/k2``), ``duration_s``,
        ``cylinder``, ``half_plane``, ``radius_m``, ``load_N_per_m``,
        ``speed_m_per_s``, ``friction``, ``pressure_unit_Pa`` (``P/l``) and
        ``temperature_unit_K`` (``f v P/(pi K2)``).
    """
    found = closure_of(closure, lam=lam, kinds=PHYSICAL_CLOSURES)
    if not isinstance(found, HeatPartition):
        raise InputError("the transient contact holds lam, not bulk temperatures (they set a "
                         "sink the transient half-plane lacks): give lam",
                         parameters=("closure", "lam"))
    if _quantity("speed2", speed2, "m/s"):
        raise InputError("the transient contact needs a stationary half-plane (speed2 = 0)",
                         parameters=("speed2",))
    problem = _physical_problem(cylinder, half_plane, radius, load, speed, friction,
                                found.keywords(), 0.0, dundurs, materials)
    if problem.beta_f:
        raise InputError("the transient contact has no Dundurs term: give dundurs=False",
                         parameters=("dundurs",))
    ell = problem.hertz_half_width
    time_unit = ell ** 2 / problem.half_plane.k
    duration = check_positive("duration", _quantity("duration", duration, "s"))
    groups = problem.ray_parameters()
    from .solvers.transient import MAX_SHIFT, STEPS_RANGE, UNTIL_MIN, longest_step

    steps = check_integer("steps", steps, *STEPS_RANGE)
    # The duration's bounds in seconds, as the dimensionless run would refuse them.
    if duration < UNTIL_MIN * time_unit:
        raise InputError(f"duration must be at least {UNTIL_MIN * time_unit:.4g} s here "
                         f"(1e-12 of l^2/kappa2), got {duration:.4g} s",
                         parameters=("duration",))
    longest = longest_step(problem.pe_hertz) * time_unit
    if duration / steps > longest:
        raise InputError(f"duration/steps must be at most {longest:.4g} s at this "
                         f"speed: the cylinder's surface would move "
                         f"{MAX_SHIFT * duration / steps / longest:.4g} half-widths in "
                         f"one step (at most {MAX_SHIFT:g}); give more steps",
                         parameters=("duration", "steps"))
    spec = transient_spec(problem.pe_hertz, problem.fhpe(ell), groups["K2_over_K1"],
                          until=duration / time_unit, steps=steps, lam=problem.lam,
                          k2_over_k1=groups["k2_over_k1"],
                          delta1_over_delta2=groups["delta1_over_delta2"], elements=elements,
                          window=window)
    attrs = {"length_unit_m": ell, "time_unit_s": time_unit, "duration_s": duration,
             "cylinder": problem.cylinder.name, "half_plane": problem.half_plane.name,
             "radius_m": problem.radius, "load_N_per_m": problem.load,
             "speed_m_per_s": problem.speed, "friction": problem.friction,
             "pressure_unit_Pa": problem.load / ell,
             "temperature_unit_K": problem.temperature_units[1]}
    return spec, attrs


def contact_transient(cylinder, half_plane, *, radius, load, speed, friction, lam=None,
                      closure=None, duration, steps=1000, elements=240, window=(-3.0, 3.0),
                      speed2=0.0, dundurs=True, materials=None, progress=None,
                      preparing=None) -> xarray.Dataset:
    """The transient contact of a cylinder on a half-plane in SI units, from switch-on.

    ``thermocontact contact ... --transient`` from Python: :func:`contact_transient_spec`
    run by :func:`compute_transient`, from Hertz's contact of isothermal bodies, the
    heat partition ``lam`` held.

    Parameters
    ----------
    cylinder, half_plane, radius, load, speed, friction, lam, closure, duration, steps, elements, window, speed2, dundurs, materials
        As for :func:`contact_transient_spec`.
    progress : callable, optional
        ``progress(done, total)`` before the first step and after each step.
    preparing : callable, optional
        ``preparing(done, total)`` while the operators are made (:func:`compute_transient`).

    Returns
    -------
    xarray.Dataset
        The run's dataset (:meth:`TransientRun.to_dataset`, dimensionless fields)
        with the physical inputs and units as further attributes: the file of
        ``thermocontact contact ... --transient --out``.

    Examples
    --------
    >>> import thermocontact as tc
    >>> ds = tc.contact_transient("copper", "steel", radius="10mm", load="50kN/m",
    ...                           speed="2m/s", friction=0.2, lam=-1, dundurs=False,
    ...                           duration="1ms", steps=20, elements=64)
    >>> ds.attrs["status"], round(float(ds.attrs["time_unit_s"]) * 1e3, 3)  # ms
    ('complete', 0.436)
    """
    spec, attrs = contact_transient_spec(cylinder, half_plane, radius=radius, load=load,
                                         speed=speed, friction=friction, lam=lam,
                                         closure=closure, duration=duration, steps=steps, elements=elements,
                                         window=window, speed2=speed2, dundurs=dundurs,
                                         materials=materials)
    ds = compute_transient(spec, progress=progress, preparing=preparing).to_dataset()
    ds.attrs.update(attrs)
    return ds
