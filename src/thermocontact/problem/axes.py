"""One axis of a grid of parameters, validated on construction.

A map (:func:`thermocontact.parameter_map`, :func:`thermocontact.operating_map`) is
a grid ``x × y`` of two axes.  An axis is ``count`` values from ``start`` to
``stop``, evenly spaced or, with ``log``, geometrically.  The physical axes
``load`` (N/m), ``speed`` (m/s) and ``radius`` (m) accept their ends as numbers in
SI units or as strings with units (``"10kN/m"``).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .units import parse_quantity
from .validation import InputError, check_finite

__all__ = ["Axis", "MAX_AXIS_POINTS", "PHYSICAL_UNITS"]

#: Most points on one axis.
MAX_AXIS_POINTS = 4096
#: The physical axes and their SI units; every other axis is dimensionless.
PHYSICAL_UNITS = {"load": "N/m", "speed": "m/s", "radius": "m"}


def _end(label: str, which: str, name: str, value) -> float:
    unit = PHYSICAL_UNITS.get(name)
    if unit is not None:
        return parse_quantity(value, unit, f"{label} {which}")
    return check_finite(f"{label} {which}", value)


def checked_axis(label: str, name, start, stop, count, log=False) -> tuple:
    """``(name, start, stop, count, log)`` converted and checked, or :class:`InputError`
    naming ``label`` (``"x"``, ``"--x"``): a range that is reversed or empty, fewer
    than 2 or more than :data:`MAX_AXIS_POINTS` points, a log axis that does not stay
    positive."""
    if not isinstance(name, str) or not name:
        raise InputError(f"{label} name must be a parameter's name, got {name!r}")
    start, stop = _end(label, "start", name, start), _end(label, "stop", name, stop)
    if not stop > start:
        raise InputError(f"{label} stop must be greater than start, got start {start!r}, "
                         f"stop {stop!r}")
    if isinstance(count, bool) or not isinstance(count, (int, np.integer)):
        if isinstance(count, float) and count.is_integer():
            count = int(count)
        else:
            raise InputError(f"{label} count must be an integer, got {count!r}")
    if not 2 <= count <= MAX_AXIS_POINTS:
        raise InputError(f"{label} count must be 2 to {MAX_AXIS_POINTS}, got {count}")
    if not isinstance(log, (bool, np.bool_)):
        raise InputError(f"{label} log must be True or False, got {log!r}")
    if log and not start > 0.0:
        raise InputError(f"{label} log axis must stay positive (start > 0), got start "
                         f"{start!r}")
    return name, start, stop, int(count), bool(log)


@dataclass(frozen=True)
class Axis:
    """One axis of a map: ``count`` values from ``start`` to ``stop``.

    Parameters
    ----------
    name : str
        The parameter: a dimensionless one (``"fhpe"``, ``"pe"``, ``"lam"``,
        ``"sigma"``, ``"K2_over_K1"``, ...) for :func:`thermocontact.parameter_map`,
        or ``"load"`` (N/m), ``"speed"`` (m/s) or ``"radius"`` (m) for
        :func:`thermocontact.operating_map`; the map checks that it is one of its own.
    start, stop : float or str
        The ends, ``stop > start``; a physical axis's may carry units (``"10mm"``).
    count : int
        Number of values, 2 to :data:`MAX_AXIS_POINTS`.
    log : bool
        Geometric spacing (then ``start > 0``).

    Raises
    ------
    InputError
        One line naming the field and its allowed range.

    Examples
    --------
    >>> Axis("fhpe", 0, 0.8, 5).values
    array([0. , 0.2, 0.4, 0.6, 0.8])
    >>> Axis("load", "1kN/m", "100kN/m", 3, log=True).values
    array([  1000.,  10000., 100000.])
    """

    name: str
    start: float
    stop: float
    count: int
    log: bool = False

    def __post_init__(self):
        label = f"Axis {self.name!r}" if isinstance(self.name, str) else "Axis"
        fields = checked_axis(label, self.name, self.start, self.stop, self.count, self.log)
        for key, value in zip(("name", "start", "stop", "count", "log"), fields):
            object.__setattr__(self, key, value)

    @property
    def values(self) -> np.ndarray:
        """The axis's values, shape ``(count,)``."""
        if self.log:
            return np.geomspace(self.start, self.stop, self.count)
        return np.linspace(self.start, self.stop, self.count)

    @property
    def spec(self) -> str:
        """The axis as written on the command line (``name:start:stop:count[:log]``)."""
        return (f"{self.name}:{self.start!r}:{self.stop!r}:{self.count}"
                + (":log" if self.log else ""))

    @classmethod
    def parse(cls, text, label: str = "axis") -> "Axis":
        """An axis from its command-line form ``name:start:stop:count[:log]``.

        The name is not checked here (the map that takes the axis checks it);
        errors name ``label`` (``"--x"``).

        Examples
        --------
        >>> Axis.parse("pe:1:100:3:log").values
        array([  1.,  10., 100.])
        """
        form = "name:start:stop:count[:log]"
        if not isinstance(text, str):
            raise InputError(f"{label} must be {form}, got {text!r}", parameters=(label,))
        parts = text.split(":")
        if len(parts) not in (4, 5):
            raise InputError(f"{label} must be {form}, got {text!r}", parameters=(label,))
        try:
            start, stop = float(parts[1]), float(parts[2])
        except ValueError:
            raise InputError(f"{label} start and stop must be numbers, got {text!r}",
                             parameters=(label,)) from None
        try:
            count = int(parts[3])
        except ValueError:
            raise InputError(f"{label} count must be an integer, got {parts[3]!r}",
                             parameters=(label,)) from None
        if len(parts) == 5 and parts[4].strip() != "log":
            raise InputError(f"{label} fifth field must be 'log', got {parts[4]!r}",
                             parameters=(label,))
        name, start, stop, count, log = checked_axis(label, parts[0].strip(), start, stop,
                                                      count, len(parts) == 5)
        return cls(name, start, stop, count, log)

    def renamed(self, name: str) -> "Axis":
        """The same values under another spelling of the parameter."""
        return Axis(name, self.start, self.stop, self.count, self.log)
