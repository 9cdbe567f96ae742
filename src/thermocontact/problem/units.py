"""Reading physical quantities, with or without units, into SI floats.

The engineering front end accepts inputs such as ``"200 kN/m"``, ``"72 km/h"`` or
``"450mm"`` as well as plain numbers.  :func:`parse_quantity` turns any of them into
a float in a stated SI unit.  Plain numbers (and plain-number strings) are taken to
be in that SI unit already; anything else is parsed with `pint`_, which is imported
only when a unit actually has to be read, because building its unit registry takes a
noticeable fraction of a second.

.. _pint: https://pint.readthedocs.io
"""

from __future__ import annotations

import numbers
from functools import lru_cache

from .validation import InputError, check_finite

__all__ = ["parse_quantity"]


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
