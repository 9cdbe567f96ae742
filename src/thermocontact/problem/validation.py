"""Validation of inputs, in one place and one wording.

Every check returns the value converted (a float, an int, a name) or raises
:class:`InputError` with one line ``"<name> must be <range>, got <value>"``: the
parameter as the user wrote it and the allowed range, nothing else.  The command
line prints that line and exits with status 2.
"""

from __future__ import annotations

import math
import operator

from .errors import InputError

__all__ = [
    "InputError",
    "check_callable",
    "check_choice",
    "check_exactly_one",
    "check_finite",
    "check_flag",
    "check_integer",
    "check_nonnegative",
    "check_numbers",
    "check_offset_coupling",
    "check_pair",
    "check_positive",
    "check_range",
    "check_sink_given",
    "check_zero_or_range",
]


def _fail(name: str, allowed: str, value):
    raise InputError(f"{name} must be {allowed}, got {value!r}", parameters=(name,))


def _real(name: str, value, allowed: str) -> float:
    """``value`` as a finite float (``-0.0`` becomes ``0.0``), else the full range in the message."""
    if isinstance(value, bool):
        _fail(name, allowed, value)
    try:
        x = float(value) + 0.0
    except (TypeError, ValueError):
        _fail(name, allowed, value)
    if not math.isfinite(x) or (x == 0.0 and isinstance(value, str) and _underflows(value)):
        _fail(name, allowed, value)
    return x


def _underflows(text: str) -> bool:
    """Whether a number written as text is not 0 but rounds to 0.0 (``"1e-400"``)."""
    from decimal import Decimal, InvalidOperation

    try:
        return Decimal(text.strip()) != 0
    except InvalidOperation:
        return False


def check_flag(name: str, value) -> bool:
    """``value`` if it is a bool (NumPy's too): a flag is not any truthy value."""
    if isinstance(value, bool) or type(value).__name__ == "bool_":
        return bool(value)
    _fail(name, "True or False", value)


def check_finite(name: str, value) -> float:
    """``value`` as a finite float."""
    return _real(name, value, "a finite real number")


def check_positive(name: str, value) -> float:
    """``value`` as a float, finite and ``> 0``."""
    x = _real(name, value, "> 0 (finite)")
    if x <= 0.0:
        _fail(name, "> 0 (finite)", value)
    return x


def check_nonnegative(name: str, value) -> float:
    """``value`` as a float, finite and ``>= 0``."""
    x = _real(name, value, ">= 0 (finite)")
    if x < 0.0:
        _fail(name, ">= 0 (finite)", value)
    return x


def check_range(name: str, value, low: float, high: float, *, open_low=False,
                open_high=False) -> float:
    """``value`` as a float in ``[low, high]`` (an end excluded when ``open_*``)."""
    allowed = f"in {'(' if open_low else '['}{low:g}, {high:g}{')' if open_high else ']'}"
    x = _real(name, value, allowed)
    if (x < low or x > high or (open_low and x == low) or (open_high and x == high)):
        _fail(name, allowed, value)
    return x


def check_zero_or_range(name: str, value, low: float, high: float) -> float:
    """``value`` as a float, 0 or in ``[low, high]`` (0 the case apart: no friction, no
    sliding)."""
    allowed = f"0 or in [{low:g}, {high:g}]"
    x = _real(name, value, allowed)
    if x != 0.0 and not low <= x <= high:
        _fail(name, allowed, value)
    return x


def check_integer(name: str, value, low: int, high: int | None = None) -> int:
    """``value`` as an int in ``[low, high]`` (a float with an integral value is accepted)."""
    allowed = f"an integer in [{low}, {high}]" if high is not None else f"an integer >= {low}"
    if isinstance(value, bool):
        _fail(name, allowed, value)
    if isinstance(value, float) and value.is_integer():
        value = int(value)
    try:
        n = operator.index(value)
    except TypeError:
        _fail(name, allowed, value)
    if n < low or (high is not None and n > high):
        _fail(name, allowed, value)
    return int(n)


def check_flag(name: str, value) -> bool:
    """``value`` if it is a boolean (``True`` or ``False``; NumPy's too): a flag is not
    any truthy value."""
    kind = type(value)
    if isinstance(value, bool) or (kind.__module__ == "numpy" and kind.__name__ in ("bool",
                                                                                   "bool_")):
        return bool(value)
    _fail(name, "True or False", value)


def check_choice(name: str, value, choices) -> str:
    """``value`` if it is one of ``choices``."""
    choices = sorted(choices)
    if not isinstance(value, str) or value not in choices:
        _fail(name, f"one of {choices}", value)
    return value


def check_exactly_one(**named) -> str:
    """The name of the one argument that is not None, or :class:`InputError`."""
    given = [k for k, v in named.items() if v is not None]
    if len(given) != 1:
        raise InputError(f"give exactly one of {' and '.join(named)}", parameters=tuple(named))
    return given[0]


def check_offset_coupling(fhpe, fhpe_name: str = "fhpe") -> None:
    """The offset closes a contact only with thermal coupling (``fhpe > 0``): without,
    the contact is Hertzian, a bounded solution needs ``sigma_over_delta = 0`` and then
    ``lam`` is undetermined."""
    if fhpe == 0.0:
        raise InputError(
            f"sigma_over_delta cannot be imposed when {fhpe_name} = 0: without thermal "
            f"coupling the contact is Hertzian, a bounded solution needs "
            f"sigma_over_delta = 0 and then lam is undetermined; give lam instead",
            parameters=("sigma_over_delta", fhpe_name))


def check_sink_given(sink_distance, stationary: bool) -> None:
    """The far temperatures' sink: given for a stationary half-plane (its logarithm
    needs a length, D38), not for a moving one (its incoming temperature is absolute,
    section 17)."""
    if not stationary and sink_distance is not None:
        raise InputError("sink_distance applies to a stationary half-plane only: a moving "
                         "half-plane's far temperature is its incoming one",
                         parameters=("sink_distance",))
    if stationary and sink_distance is None:
        raise InputError("a stationary half-plane needs sink_distance (> 1, in half-widths) "
                         "with the temperatures", parameters=("sink_distance",))


def check_pair(name: str, value, allowed: str = "two numbers") -> tuple[float, float]:
    """``value`` as two finite floats: a sequence of two numbers (not a string, whose
    characters are not numbers even when they spell them)."""
    if isinstance(value, (str, bytes)):
        _fail(name, allowed, value)
    try:
        a, b = value
    except (TypeError, ValueError):
        _fail(name, allowed, value)
    return _real(name, a, allowed), _real(name, b, allowed)


def check_flag(name: str, value) -> bool:
    """``value`` if it is a boolean (``numpy.bool_`` too): a switch is on or off, never
    a string or a number that happens to be truthy (``"no"`` is not False)."""
    kind = type(value)
    if isinstance(value, bool) or (kind.__module__ == "numpy"
                                   and kind.__name__ in ("bool", "bool_")):
        return bool(value)
    _fail(name, "True or False", value)


def check_callable(name: str, value):
    """``value`` if it is None or can be called (a progress or a save): refused before
    any work, not where the work first reports."""
    if value is not None and not callable(value):
        _fail(name, "None or a callable", value)
    return value


def check_numbers(name: str, value) -> list[float]:
    """``value``, a number or a flat sequence of them, as a list of finite floats."""
    if isinstance(value, (str, bytes)) or not hasattr(value, "__len__"):
        return [check_finite(name, value)]
    try:
        items = list(value)
    except TypeError:
        _fail(name, "a number or a sequence of numbers", value)
    if not items:
        _fail(name, "a number or a sequence of numbers", value)
    return [check_finite(name, v) for v in items]
