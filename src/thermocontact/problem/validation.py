"""Validation of inputs, in one place and one wording.

Every check returns the value converted (a float, an int, a name) or raises
:class:`InputError` with one line ``"<name> must be <range>, got <value>"``: the
parameter as the user wrote it and the allowed range, nothing else.  The command
line prints that line and exits with status 2.
"""

from __future__ import annotations

import math
import operator

__all__ = [
    "InputError",
    "check_choice",
    "check_exactly_one",
    "check_finite",
    "check_flag",
    "check_integer",
    "check_nonnegative",
    "check_positive",
    "check_range",
    "check_zero_or_range",
]


class InputError(ValueError):
    """A parameter outside its allowed range; the message names both.

    Parameters
    ----------
    message : str
        One line, naming the parameters as the Python API spells them.
    parameters : tuple of str
        The parameters the message names, so that a front end (the command line)
        can name them as its users spell them (``K2_over_K1`` as ``--K2-over-K1``).
    """

    def __init__(self, message, *, parameters=()):
        super().__init__(message)
        self.parameters = tuple(parameters)

    def __reduce__(self):  # the parameters survive a trip to a worker process
        return (_input_error, (type(self), str(self), self.parameters))


def _input_error(cls, message, parameters):
    return cls(message, parameters=parameters)


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
    if not math.isfinite(x):
        _fail(name, allowed, value)
    return x


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
