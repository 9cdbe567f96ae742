"""The names of the public calls' inputs, each with its one unit and meaning.

One quantity, one name, one unit, across every call: a physical quantity in SI units
(strings with units accepted where it is given), a dimensionless one under a name that
says its scale (``sigma_over_delta``, ``sink_distance_over_delta``).  The table is the
reference the API's signatures are checked against (``tests/test_vocabulary.py``) and
the docs' list of names (docs/results.md).

Units: an SI unit; ``"1"`` a pure number; a reduced unit of a dimensionless problem
(``"Delta"`` the contact's half-width, ``"l"`` Hertz's half-width of the load,
``"l^2/kappa2"`` its diffusion time); ``""`` for what has no unit (a name, a choice,
a flag, a count, a function, a file).
"""

from __future__ import annotations

__all__ = ["DEPRECATED", "VOCABULARY", "deprecated_spellings"]

#: name -> (unit, meaning).
VOCABULARY = {
    # The problem in dimensionless form (derivation section 5).
    "pe": ("1", "Peclet number v Delta/(2 k2) of the contact's half-width"),
    "fhpe": ("1", "frictional heating f H Pe, H = k2 delta2/A"),
    "pe_hertz": ("1", "Peclet number v l/(2 k2) of Hertz's half-width l"),
    "fhpe_hertz": ("1", "frictional heating f H Pe_l of Hertz's half-width"),
    "K2_over_K1": ("1", "conductivity ratio, half-plane over cylinder"),
    "k2_over_k1": ("1", "diffusivity ratio, half-plane over cylinder"),
    "delta1_over_delta2": ("1", "distortivity ratio, cylinder over half-plane"),
    "speed_ratio": ("1", "the half-plane's surface speed over the cylinder's, v2/v1"),
    "beta_f": ("1", "Dundurs constant times friction (section 5c)"),
    "delta_over_r": ("1", "half-width over radius, for the applicability"),
    # The closure (problem/closure.py).
    "closure": ("", "what fixes the heat partition: HeatPartition, Offset, "
                    "FarTemperatures or BulkTemperatures"),
    "lam": ("1", "heat partition (Q1 - Q2)/(Q1 + Q2)"),
    "sigma_over_delta": ("1", "offset of the contact's centre, in half-widths"),
    "theta": ("1", "far temperatures' group pi K2 (T2 - T1)/(f |v1 - v2| P)"),
    "sink_distance_over_delta": ("1", "a stationary half-plane's sink distance, in "
                                      "half-widths"),
    "T1": ("K", "the cylinder's incoming temperature"),
    "T2": ("K", "the half-plane's far temperature (incoming, or its sink's)"),
    "sink_distance": ("m", "a stationary half-plane's distance to its sink"),
    "layer_thickness": ("m", "thickness of a layer on a sink (L = 4h/pi)"),
    "conductance": ("", "interface conductance h(p): (Bi0, m) dimensionless, "
                        "(h0 W/(m^2 K), m[, p_ref Pa]) physical"),
    "temperatures": ("", "the far temperatures in the solvers' own form, Temperatures(theta, "
                         "L over the length unit), one or one per point (Model's methods)"),
    # The problem in physical units.
    "cylinder": ("", "the cylinder's material: a name, an inline definition, a Material"),
    "half_plane": ("", "the half-plane's material"),
    "slider": ("", "the sliding body's material (TEI)"),
    "counterface": ("", "the counterface's material (TEI)"),
    "materials": ("", "a TOML file of further materials"),
    "radius": ("m", "the cylinder's radius R"),
    "load": ("N/m", "load per unit length P"),
    "speed": ("m/s", "sliding speed: the cylinder's surface through the contact"),
    "speed2": ("m/s", "the half-plane's surface speed"),
    "friction": ("1", "Coulomb coefficient f"),
    "dundurs": ("", "keep the Dundurs term of the friction traction (flag)"),
    "wavelength": ("m", "a perturbation's wavelength (TEI)"),
    "slider_thickness": ("m", "a brake disc's full thickness (TEI; none: a half-plane)"),
    "faces": ("", "the disc's faces that rub: 2 or 1"),
    "counterface_thickness": ("m", "the pads' (or facings') thickness on their backing"),
    "backing": ("", "the pads' backing plate: slip-insulated, bonded-insulated or "
                    "slip-isothermal"),
    "separator": ("", "a clutch pack's separator plates, material:thickness"),
    "plane_stress": ("", "plane stress instead of plane strain (flag)"),
    "disc_radius": ("m", "a disc's radius, for the hot spots round it"),
    "hot_spots": ("", "the numbers of hot spots round the disc, N1:N2"),
    "brake_stop": ("", "a brake stop V0:DECEL, m/s and m/s^2"),
    "stop_history": ("", "a CSV file of time (s) and speed (m/s) of a stop"),
    "stop_threshold": ("1", "the amplification over a stop that marks a hot-spot number"),
    "duration": ("s", "time computed by a transient contact"),
    "temperature_difference": ("K", "T2 - T1, followed by a physical path"),
    # Materials (problem/materials.py).
    "name": ("", "a name (a material's, an axis's parameter)"),
    "E": ("Pa", "Young's modulus"),
    "nu": ("1", "Poisson's ratio"),
    "alpha": ("1/K", "linear thermal expansion coefficient"),
    "K": ("W/m/K", "thermal conductivity"),
    "k": ("m^2/s", "thermal diffusivity"),
    "max_temperature": ("K", "the material's highest tolerated temperature"),
    "max_temperature_source": ("", "where max_temperature comes from"),
    "source": ("", "where the material's values come from"),
    "note": ("", "a note on the material"),
    "role": ("", "the body's role, as a message names it"),
    # Paths, maps and their axes.
    "along": ("", "the parameter a path follows"),
    "start": ("", "a range's first value, in the unit of its parameter"),
    "stop": ("", "a range's last value, in the unit of its parameter"),
    "count": ("", "number of points of an axis"),
    "log": ("", "geometric spacing (flag)"),
    "x": ("", "a map's first axis (Axis)"),
    "y": ("", "a map's second axis (Axis)"),
    "zones": ("", "contact sets of several zones too (flag)"),
    "spec": ("", "a specification made by map_spec or transient_spec"),
    "stability": ("", "eigenvalues of the steady contact too (flag)"),
    # The transient contact, in units of Hertz's half-width l.
    "until": ("l^2/kappa2", "duration of a dimensionless transient run"),
    "steps": ("", "time steps"),
    "elements": ("", "boundary elements"),
    "window": ("l", "where contact may occur, (lo, hi)"),
    "initial": ("", "the transient's initial state: 'hertz' or 'steady'"),
    "hold": ("", "what a transient from a steady state holds: 'theta' or 'lam'"),
    "perturb": ("1", "relative load step during the first time step"),
    "resume": ("", "a partial run to go on from"),
    "save": ("", "called with a partial run now and then"),
    "save_every": ("s", "seconds of computing between saves"),
    "ds": ("", "a dataset written by to_dataset"),
    # Stability of the steady contact.
    "solution": ("", "a steady contact (ContactSolution or PhysicalContact)"),
    "b_min": ("k2/Delta^2", "the least growth rate of the eigenvalues counted"),
    "modulus_bound": ("k2/Delta^2", "the largest |b| of the eigenvalues counted"),
    # Discretisation and execution.
    "method": ("", "discretisation method (METHODS)"),
    "n": ("", "unknowns per function"),
    "tol": ("1", "relative error target"),
    "check_convergence": ("", "solve again at 2n and report the change (flag)"),
    "polish": ("", "polish the validity margins' extrema (flag)"),
    "rcond": ("", "how a grid line's condition numbers are found"),
    "progress": ("", "a function told of the progress"),
    "preparing": ("", "a function told of the progress of the operators' making"),
    "check_validity": ("", "evaluate the contact inequalities too (flag)"),
    "workers": ("", "where the work runs: processes, an executor, a Dask client"),
    "store": ("", "a folder keeping finished work"),
    "command": ("", "the command line recorded in a map's attributes"),
}

#: The names of earlier versions that a call still takes for one minor version, with a
#: DeprecationWarning, and what replaces them.
DEPRECATED = {
    "sigma": "sigma_over_delta",
    "theta": "closure=FarTemperatures(theta, sink_distance_over_delta)",
    "sink_distance": "closure=FarTemperatures(...) (as L/Delta) or "
                     "closure=BulkTemperatures(..., sink_distance=...) (m)",
    "bulk_temperatures": "closure=BulkTemperatures(T1, T2, ...)",
    "layer_thickness": "closure=BulkTemperatures(T1, T2, layer_thickness=...)",
    "temperatures": "closure=FarTemperatures(...)",
    "start": "initial (of a transient run)",
    "zones": "contact_set(...) (of contact)",
    "re_min": "b_min (of stability: every eigenvalue above it counted)",
    "re_max": "nothing (stability counts every eigenvalue up to modulus_bound)",
    "im_max": "nothing (stability counts every eigenvalue up to modulus_bound)",
    "points": "nothing (stability's contour is followed adaptively)",
}


def deprecated_spellings(*, renamed=(), closure=None, physical=None, converted=(),
                         retired=()):
    """A public call that still takes the spellings of versions before 1.0, each with a
    :class:`DeprecationWarning` naming what replaces it (:data:`DEPRECATED`).

    Parameters
    ----------
    renamed : sequence of (str, str)
        ``(old, new)`` keyword names.
    converted : sequence of (str, str, callable)
        ``(old, new, convert)``: ``new=convert(old value)``.
    retired : sequence of str
        Keywords that 1.0 no longer needs: taken and ignored.
    closure : {"dimensionless", "physical", "either"}, optional
        The call's closure keywords of earlier versions (``theta``, ``sink_distance``,
        ``bulk_temperatures``, ``layer_thickness``) become its ``closure=``
        (:func:`~thermocontact.problem.closure.spelled_closure`); ``"either"``: which
        kind ``physical(args, kwargs)`` tells.

    The call's own signature (``inspect.signature`` of the decorated function) holds the
    names of 1.0 only.
    """
    import functools
    import warnings

    def wrap(func):
        @functools.wraps(func)
        def call(*args, **kwargs):
            from .closure import spelled_closure
            from .errors import InputError

            used = []
            for old, new in renamed:
                if old in kwargs:
                    if new in kwargs:
                        raise InputError(f"give {new}, not both {old} and {new}",
                                         parameters=(new,))
                    kwargs[new] = kwargs.pop(old)
                    used.append(f"{old}= ({new}=)")
            for old in retired:
                if old in kwargs:
                    kwargs.pop(old)
                    used.append(f"{old}= (no longer needed: ignored)")
            for old, new, convert in converted:
                if kwargs.get(old) is not None:
                    if kwargs.get(new) is not None:
                        raise InputError(f"give {new}, not both {old} and {new}",
                                         parameters=(new,))
                    kwargs[new] = convert(kwargs.pop(old))
                    used.append(f"{old}= ({new}=)")
                kwargs.pop(old, None)
            if closure is not None:
                kind = (physical(args, kwargs) if closure == "either"
                        else closure == "physical")
                found, names = spelled_closure(kwargs, kind)
                if found is not None:
                    if kwargs.get("closure") is not None:
                        raise InputError(f"give closure alone, not with {', '.join(names)}",
                                         parameters=("closure", *names))
                    kwargs["closure"] = found
                    used.append(", ".join(f"{n}=" for n in names)
                                + f" (closure={type(found).__name__}(...))")
            if used:
                warnings.warn(f"{func.__name__}: {'; '.join(used)}: the spelling of versions "
                              f"before 1.0, taken until 1.1 (CHANGELOG.md)",
                              DeprecationWarning, stacklevel=2)
            return func(*args, **kwargs)
        return call
    return wrap
