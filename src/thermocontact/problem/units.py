"""Reading physical quantities, with or without units, into SI floats.

The engineering front end accepts inputs such as ``"200 kN/m"``, ``"72 km/h"`` or
``"450mm"`` as well as plain numbers.  :func:`parse_quantity` turns any of them into
a float in a stated SI unit.  Plain numbers (and plain-number strings) are taken to
be in that SI unit already.  A unit written in the SI symbols of mechanics and heat
(m, g, s, min, h, N, Pa, J, W, K with the prefixes p to T, joined by ``/``, ``*``,
spaces and integer powers) is read by a small table here; anything else by `pint`_,
whose import and registry take one to two seconds, as long as a whole solve: the
table keeps them out of a command like ``contact --load 310kN/m``, and a test checks
it against pint.

.. _pint: https://pint.readthedocs.io
"""

from __future__ import annotations

import numbers
import re
from functools import lru_cache

from .validation import InputError, check_finite

__all__ = ["parse_quantity", "parse_temperature"]


#: SI symbols: (scale to SI, exponents of m, kg, s, K).
_SYMBOLS = {
    "m": (1.0, (1, 0, 0, 0)), "g": (1e-3, (0, 1, 0, 0)), "s": (1.0, (0, 0, 1, 0)),
    "min": (60.0, (0, 0, 1, 0)), "h": (3600.0, (0, 0, 1, 0)), "K": (1.0, (0, 0, 0, 1)),
    "N": (1.0, (1, 1, -2, 0)), "Pa": (1.0, (-1, 1, -2, 0)), "J": (1.0, (2, 1, -2, 0)),
    "W": (1.0, (2, 1, -3, 0)),
}
_PREFIXES = {"p": 1e-12, "n": 1e-9, "u": 1e-6, "\u00b5": 1e-6, "\u03bc": 1e-6, "m": 1e-3,
             "c": 1e-2, "k": 1e3, "M": 1e6, "G": 1e9, "T": 1e12}
_NUMBER = re.compile(r"^[+-]?(\d+\.?\d*|\.\d+)([eE][+-]?\d+)?")
_FACTOR = re.compile(r"^([A-Za-z\u00b5\u03bc]+)(?:(?:\^|\*\*)([+-]?\d+))?$")


def _si(unit: str):
    """``(scale, exponents)`` of a product of SI symbols, or None if not one.

    ``"kN/m"``, ``"W/m/K"``, ``"m^2/s"``, ``"1/K"``; division binds to the next
    factor only, as in pint.
    """
    text = unit.replace(" / ", "/").replace("/ ", "/").replace(" /", "/")
    tokens = re.split(r"((?<!\*)\*(?!\*)|/|\s+)", text.strip())
    scale, dims, sign = 1.0, [0, 0, 0, 0], 1
    pending = None  # an operator not yet followed by a factor
    for token in tokens:
        if not token or token.isspace():
            continue
        if token in ("*", "/"):
            if pending is not None:  # "m / / s", "*/m": pint refuses them
                return None
            pending = token
            sign = -1 if token == "/" else 1
            continue
        pending = None
        if token == "1":
            sign = 1
            continue
        match = _FACTOR.match(token)
        if match is None:
            return None
        name, power = match.group(1), int(match.group(2) or 1)
        if name in _SYMBOLS:
            factor, exps = _SYMBOLS[name]
        elif name[:1] in _PREFIXES and name[1:] in _SYMBOLS:
            factor, exps = _SYMBOLS[name[1:]]
            factor *= _PREFIXES[name[:1]]
        else:
            return None
        scale *= factor ** (sign * power)
        dims = [d + sign * power * e for d, e in zip(dims, exps)]
        sign = 1
    if pending is not None:  # a trailing operator
        return None
    return scale, tuple(dims)


def _read_si(text: str, unit: str):
    """``text`` in ``unit`` if both are numbers and SI symbols, else None; a
    dimension mismatch is the string ``"mismatch"``."""
    match = _NUMBER.match(text)
    if match is None:
        return None
    have, want = _si(text[match.end():]), _si(unit)
    if have is None or want is None:
        return None
    if have[1] != want[1]:
        return "mismatch"
    return float(match.group(0)) * have[0] / want[0]


@lru_cache(maxsize=1)
def _registry():
    """The shared pint unit registry, built on first use."""
    import pint

    return pint.UnitRegistry()


def _finite(name: str, x: float, value) -> float:
    # The message shows the value as the user wrote it, not as converted.
    try:
        return check_finite(name, x)
    except InputError:
        raise InputError(f"{name} must be a finite real number, got {value!r}") from None


def parse_quantity(value, unit: str, name: str) -> float:
    """Return ``value`` expressed in the SI unit ``unit``, as a float.

    Parameters
    ----------
    value : float, int, str or pint.Quantity
        A real number (taken to be in ``unit`` already), a string holding a
        plain number (likewise), or a string with a number and a unit, such as
        ``"200kN/m"``, ``"72 km/h"``, ``"450mm"`` or ``"12e-6 1/K"``.  A pint
        quantity is converted directly.
    unit : str
        The SI unit of the result in pint's notation, e.g. ``"N/m"``, ``"m/s"``,
        ``"m"``, ``"Pa"``, ``"1/K"``, ``"W/m/K"``, ``"m^2/s"``; ``""`` for a
        dimensionless number.
    name : str
        The parameter's name, used in error messages.

    Returns
    -------
    float
        The finite value in ``unit``.  Its sign is not checked.

    Raises
    ------
    InputError
        If the value cannot be read, has dimensions other than those of
        ``unit``, or is not finite.  The message is one line, e.g.
        ``"v: cannot read '72 kg' as a quantity in m/s"``.

    Examples
    --------
    >>> parse_quantity("72 km/h", "m/s", "v")
    20.0
    >>> parse_quantity(2e5, "N/m", "P")
    200000.0
    """
    shown = unit if unit else "dimensionless units"
    if isinstance(value, bool):
        raise InputError(f"{name}: cannot read {value!r} as a quantity in {shown}")
    if isinstance(value, numbers.Real):
        return _finite(name, float(value), value)
    if isinstance(value, str):
        text = value.strip()
        try:
            x = float(text)
        except ValueError:
            pass
        else:
            return _finite(name, x, value)
        if not text:
            raise InputError(f"{name}: cannot read {value!r} as a quantity in {shown}")
        x = _read_si(text, unit)
        if x == "mismatch":
            raise InputError(f"{name}: cannot read {value!r} as a quantity in {shown}")
        if x is not None:
            return _finite(name, x, value)
        ureg = _registry()
        try:
            quantity = ureg.Quantity(text)
        except Exception:  # pint raises many kinds for unparsable text
            raise InputError(
                f"{name}: cannot read {value!r} as a quantity in {shown}"
            ) from None
    elif hasattr(value, "to") and hasattr(value, "magnitude"):
        quantity = value  # a pint quantity from the caller's own registry
    else:
        raise InputError(f"{name}: cannot read {value!r} as a quantity in {shown}")
    try:
        x = float(quantity.to(unit if unit else "dimensionless").magnitude)
    except Exception:  # DimensionalityError, offset units, non-scalar values
        raise InputError(
            f"{name}: cannot read {str(value)!r} as a quantity in {shown}"
        ) from None
    return _finite(name, x, value)


#: Temperature units: (scale, offset) to kelvin, T_K = scale * value + offset.
_TEMPERATURE_UNITS = {"": (1.0, 0.0), "K": (1.0, 0.0), "C": (1.0, 273.15),
                      "\u00b0C": (1.0, 273.15), "degC": (1.0, 273.15),
                      "F": (5.0 / 9.0, 273.15 - 32.0 * 5.0 / 9.0),
                      "\u00b0F": (5.0 / 9.0, 273.15 - 32.0 * 5.0 / 9.0),
                      "degF": (5.0 / 9.0, 273.15 - 32.0 * 5.0 / 9.0)}


def parse_temperature(value, name: str) -> float:
    """An absolute temperature in kelvin from a number (K) or a string with ``K``,
    ``C`` (``degC``, ``°C``) or ``F``: ``"150C"`` is 423.15 K.  Temperatures below
    0 K are refused (one line naming ``name``)."""
    if isinstance(value, numbers.Real) and not isinstance(value, bool):
        kelvin = float(value)
    else:
        text = str(value).strip()
        match = _NUMBER.match(text)
        unit = text[match.end():].strip() if match is not None else None
        if match is None or unit not in _TEMPERATURE_UNITS:
            raise InputError(f"{name}: cannot read {value!r} as a temperature (K, C or F: "
                             f"'150C', '300K')", parameters=(name,))
        scale, offset = _TEMPERATURE_UNITS[unit]
        kelvin = scale * float(match.group(0)) + offset
    kelvin = _finite(name, kelvin, value)
    if kelvin < 0.0:
        raise InputError(f"{name} must be >= 0 K, got {value!r} ({kelvin:.6g} K)",
                         parameters=(name,))
    return kelvin
