"""The result protocol: every result of the package behaves the same way.

A result is a frozen dataclass that subclasses :class:`Result`, declared with
``@dataclass(frozen=True, eq=False, repr=False)`` so that the protocol's equality and
repr are the ones used.  It then

* pickles (to and from worker processes), its arrays included;
* compares by value: arrays element by element (``np.array_equal``, NaN equal to
  NaN), floats NaN-aware, containers and nested results field by field; ``==`` never
  raises on arrays.  Results are not hashable (they hold arrays);
* has a one-line repr of its key numbers, never its arrays (:meth:`Result._summary`);
* has :meth:`~Result.to_dict`, its JSON record: plain Python types, non-finite numbers
  as None (JSON has none), so that ``json.dumps(result.to_dict(), allow_nan=False)``
  always succeeds;
* where it holds fields over one coordinate (:class:`FieldResult`), has
  :meth:`~FieldResult.to_dataset`, an :class:`xarray.Dataset` of those fields with the
  record's scalars as attributes;
* where it is the answer of a call (an *outcome*: it declares :attr:`Result.STATUSES`),
  has ``status``, one of the documented words of its kind, ``message``, one line on
  how it ended, and ``success``, in the manner of scipy's ``OptimizeResult``; all
  three are in its record;
* declares the units of its quantities in :attr:`Result.UNITS`: one mapping in its
  record (``"units"``) and the CF ``units`` attribute of each variable of its dataset.
"""

from __future__ import annotations

import math
from dataclasses import MISSING, fields, replace
from typing import ClassVar

import numpy as np

__all__ = ["FieldResult", "Result", "dataset_attrs", "plain", "same", "with_units"]


def plain(value):
    """``value`` as plain JSON types: dicts, lists, str, int, float, bool and None.

    NumPy scalars and arrays become Python numbers and lists, tuples become lists,
    results their :meth:`~Result.to_dict`, and NaN and infinities None.

    Raises
    ------
    TypeError
        For anything else (an object has no JSON record of its own).
    """
    if value is None or isinstance(value, (bool, str)):
        return value
    if isinstance(value, np.bool_):
        return bool(value)
    if isinstance(value, (int, np.integer)):
        return int(value)
    if isinstance(value, (float, np.floating)):
        return float(value) if math.isfinite(value) else None
    if isinstance(value, np.ndarray):
        return plain(value.tolist())
    if isinstance(value, (list, tuple)):
        return [plain(v) for v in value]
    if isinstance(value, dict):
        return {(plain(k) if isinstance(k, np.generic) else k): plain(v)
                for k, v in value.items()}
    if isinstance(value, Result):
        return value.to_dict()
    raise TypeError(f"no JSON record for a {type(value).__name__}")


def same(a, b) -> bool:
    """Whether ``a`` and ``b`` are equal by value: arrays element by element (NaN equal
    to NaN), floats NaN-aware, lists, tuples and dicts entry by entry; never raises on
    arrays."""
    if isinstance(a, np.ndarray) or isinstance(b, np.ndarray):
        if not (isinstance(a, np.ndarray) and isinstance(b, np.ndarray)):
            return False
        if a.shape != b.shape or a.dtype.kind != b.dtype.kind:
            return False
        if a.dtype.kind in "fc":
            return bool(np.array_equal(a, b, equal_nan=True))
        if a.dtype.kind == "O":
            return all(same(x, y) for x, y in zip(a.ravel(), b.ravel()))
        return bool(np.array_equal(a, b))
    if isinstance(a, (list, tuple)) or isinstance(b, (list, tuple)):
        return (type(a) is type(b) and len(a) == len(b)
                and all(same(x, y) for x, y in zip(a, b)))
    if isinstance(a, dict) or isinstance(b, dict):
        return (isinstance(a, dict) and isinstance(b, dict) and a.keys() == b.keys()
                and all(same(a[k], b[k]) for k in a))
    if isinstance(a, (float, np.floating)) and isinstance(b, (float, np.floating)):
        return bool(a == b or (math.isnan(a) and math.isnan(b)))
    return bool(a == b)


def _short(value) -> str:
    """A scalar for a repr: floats to 6 digits."""
    if isinstance(value, (float, np.floating)):
        return f"{value:.6g}"
    return repr(value)


#: Per result class, how :meth:`Result.build` makes one (:func:`_plan`).
_PLANS: dict = {}


def _plan(cls):
    """``(field names in order, the same as a set, the fields without a default, the
    defaults)``; None where the class checks its fields (``__post_init__``) or a
    default is made by a factory: the constructor then."""
    try:
        return _PLANS[cls]
    except KeyError:
        pass
    fs = fields(cls)
    plan = None
    if not (hasattr(cls, "__post_init__")
            or any(f.default_factory is not MISSING for f in fs)):
        defaults = {f.name: f.default for f in fs if f.default is not MISSING}
        names = tuple(f.name for f in fs)
        plan = names, frozenset(names), frozenset(names) - defaults.keys(), defaults
    _PLANS[cls] = plan
    return plan


def _made(cls, plan, values: dict):
    """An instance of ``cls`` whose fields are ``values`` (a dict of its own, its names
    checked against ``plan``), the defaults filled in, without the constructor."""
    if len(values) < len(plan[0]):
        values = {**plan[3], **values}
    new = object.__new__(cls)
    object.__setattr__(new, "__dict__", values)
    return new


class Result:
    """The base of every result: value equality, a one-line repr, a JSON record.

    A subclass is a ``@dataclass(frozen=True, eq=False, repr=False)``.  It names its
    key numbers in :meth:`_summary` (default: its scalar fields) and writes its record
    in :meth:`_record` (default: every field); :meth:`to_dict` makes that record
    plain (:func:`plain`).
    """

    __slots__ = ()

    #: The statuses a result of this kind may end with, each with its meaning; None for
    #: a part of a result (a validity, an event, a mode), which has none of its own.
    STATUSES: ClassVar[dict | None] = None
    #: The statuses that are a success (:attr:`success`).
    SUCCESS: ClassVar[frozenset] = frozenset()
    #: The unit of each quantity of the record and the dataset, SI or the reduced unit
    #: of a dimensionless result (``"1"``: a pure number).
    UNITS: ClassVar[dict] = {}

    @property
    def success(self) -> bool:
        """Whether the call that made this result succeeded: its status is one of
        :attr:`SUCCESS`."""
        return self.status in self.SUCCESS

    def _units(self) -> dict:
        """The unit of each quantity: :attr:`UNITS` (a result whose units depend on its
        inputs gives its own)."""
        return dict(self.UNITS)

    def __eq__(self, other):
        if type(other) is not type(self):
            return NotImplemented
        return all(same(getattr(self, f.name), getattr(other, f.name)) for f in fields(self))

    # Equal results may hold different NaNs and arrays: no hash agrees with that.
    __hash__ = None

    def _summary(self) -> str:
        """The key numbers, ``name=value, ...``: by default the scalar fields."""
        return ", ".join(f"{f.name}={_short(getattr(self, f.name))}" for f in fields(self)
                         if f.repr and isinstance(getattr(self, f.name),
                                                  (bool, int, float, str, np.generic,
                                                   type(None))))

    def __repr__(self):
        return f"{type(self).__name__}({self._summary()})"

    def _record(self) -> dict:
        """The record before :func:`plain`: by default every field."""
        return {f.name: getattr(self, f.name) for f in fields(self)}

    def to_dict(self) -> dict:
        """The JSON record: plain Python types, non-finite numbers as None; an outcome's
        ``status``, ``message`` and ``success``, and the ``units`` of its quantities.

        ``json.dumps(result.to_dict(), allow_nan=False)`` always succeeds.
        """
        record = self._record()
        if self.STATUSES is not None:
            record = {**record, "status": self.status, "message": self.message,
                      "success": self.success}
        units = self._units()
        if units:
            record["units"] = units
        return plain(record)

    @classmethod
    def build(cls, **values):
        """``cls(**values)`` without the constructor for a result without
        ``__post_init__`` (the frozen dataclass's ``__init__`` costs a grid line
        microseconds per field and point): the same fields, the defaults filled in."""
        plan = _plan(cls)
        # A field missing or unknown: the constructor's own error.
        if plan is None or not plan[2] <= values.keys() <= plan[1]:
            return cls(**values)
        return _made(cls, plan, values)  # (the call's own dict)

    @classmethod
    def build_each(cls, names, rows) -> list:
        """``[cls.build(**dict(zip(names, row))) for row in rows]``, the names checked
        once (a grid line's results of one kind, each row one result's values)."""
        names = tuple(names)
        plan = _plan(cls)
        if plan is None or not plan[2] <= set(names) <= plan[1] or len(set(names)) < len(names):
            return [cls(**dict(zip(names, row))) for row in rows]
        # A row of another length than the names: build's own way (a missing field's
        # error, a default filled in).
        return [_made(cls, plan, dict(zip(names, row))) if len(row) == len(names)
                else cls.build(**dict(zip(names, row))) for row in rows]

    def replace(self, **changes):
        """A copy with some fields changed: :func:`dataclasses.replace`, or for a result
        without ``__post_init__`` the same object built from the fields directly (the
        constructor's checks cost a grid line tens of microseconds per point)."""
        cls = type(self)
        if hasattr(self, "__post_init__"):
            return replace(self, **changes)
        plan = _plan(cls)
        names = cls.__dataclass_fields__.keys() if plan is None else plan[1]
        if not changes.keys() <= names:
            name = next(name for name in changes if name not in names)
            raise TypeError(f"{cls.__name__} has no field {name!r}")
        if plan is None:  # a default made by a factory: the constructor
            return replace(self, **changes)
        # The fields only (nothing derived from them is carried over): the instance's
        # dict where it holds exactly the fields.
        values = self.__dict__.copy()
        if values.keys() != plan[1]:
            values = {name: values[name] for name in plan[0]}
        values.update(changes)
        return _made(cls, plan, values)


def dataset_attrs(record: dict, skip=()) -> dict:
    """The entries of a record as NetCDF attributes: None as ``"none"``, booleans as 0
    or 1, lists of numbers as float arrays (None as NaN); entries in ``skip``, nested
    records and lists of anything else left out."""
    attrs = {}
    for key, value in record.items():
        if key in skip or isinstance(value, dict):
            continue
        if value is None:
            value = "none"
        elif isinstance(value, bool):
            value = int(value)
        elif isinstance(value, (list, tuple)):
            if not all(v is None or isinstance(v, (int, float)) for v in value):
                continue
            value = np.asarray([np.nan if v is None else v for v in value], dtype=float)
        attrs[key] = value
    return attrs


class FieldResult(Result):
    """A result with fields over one coordinate: :meth:`to_dataset`.

    ``_coordinate`` names the field that holds the coordinate (a 1-d array); every
    other 1-d array field of its length is a variable over it, and the record's scalars
    (:meth:`~Result.to_dict`) are the attributes.
    """

    __slots__ = ()
    #: The field holding the coordinate.
    _coordinate = "x"

    def to_dataset(self):
        """An :class:`xarray.Dataset`: the fields over the coordinate, the record's
        scalars as attributes (:func:`dataset_attrs`)."""
        import xarray as xr

        name = self._coordinate
        coord = np.asarray(getattr(self, name))
        variables = {}
        for f in fields(self):
            value = getattr(self, f.name)
            if (f.name != name and isinstance(value, np.ndarray) and value.ndim == 1
                    and value.shape == coord.shape):
                variables[f.name] = (name, value)
        ds = xr.Dataset(variables, coords={name: (name, coord)},
                        attrs=dataset_attrs(self.to_dict(), skip=(name, *variables)))
        return with_units(ds, self._units())


def with_units(ds, units: dict):
    """``ds`` with the CF ``units`` attribute of each of its variables and coordinates
    named in ``units`` (kept where one is set already)."""
    for key in list(ds.variables):
        if key in units and "units" not in ds[key].attrs:
            ds[key].attrs["units"] = units[key]
    return ds
