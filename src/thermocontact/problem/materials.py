"""Material properties in SI units: a built-in database, user files, inline definitions.

A :class:`Material` holds the room-temperature properties the thermoelastic
contact problem needs: Young's modulus ``E``, Poisson's ratio ``nu``, the linear
expansion coefficient ``alpha``, the conductivity ``K`` and the diffusivity ``k``.
From them it derives the plane-strain distortivity ``delta = alpha (1 + nu)/K`` and
the plane-strain compliance ``(1 - nu)/mu`` that enter the dimensionless groups.

Materials come from

* the built-in file ``thermocontact/data/materials.toml`` (values and sources are
  listed there; :func:`list_materials` returns them),
* an optional user TOML file of the same layout, which adds or overrides entries,
* an inline definition such as ``"E=210e9,nu=0.3,alpha=12e-6,K=50,k=1.4e-5"``.

File layout: one table per material, named in lower case with hyphens, with keys
``E`` (Pa), ``nu``, ``alpha`` (1/K), ``K`` (W/m/K) and either ``k`` (m^2/s) or
``rho`` (kg/m^3) and ``c`` (J/kg/K), plus optional ``source`` and ``note`` strings.
Numbers are SI; strings with units (``E = "210 GPa"``) are converted with
:func:`thermocontact.problem.units.parse_quantity`.  An ``[aliases]`` table maps extra names
to material names, e.g. ``steel = "carbon-steel"``.

Examples
--------
>>> from thermocontact.problem.materials import get_material
>>> get_material("steel").name
'carbon-steel'
>>> round(get_material("E=210 GPa, nu=0.3, alpha=12e-6, K=50, k=1.4e-5").mu / 1e9, 2)
80.77
"""

from __future__ import annotations

import difflib
import math
import os
import re
import sys
from collections.abc import Mapping
from dataclasses import dataclass, field
from functools import lru_cache
from importlib.resources import files
from pathlib import Path

from .validation import (InputError, check_finite, check_nonnegative, check_positive,
                         check_range)
from .units import parse_quantity

if sys.version_info >= (3, 11):
    import tomllib
else:  # pragma: no cover - exercised on Python 3.10 only
    import tomli as tomllib

__all__ = [
    "Material",
    "MaterialError",
    "dundurs_beta",
    "get_material",
    "list_materials",
    "load_materials",
    "material_aliases",
]


class MaterialError(InputError):
    """A material that cannot be found, read or accepted; the message is one line."""


# SI unit of each numeric key, in the notation of :func:`parse_quantity`.
_UNITS = {
    "E": "Pa",
    "nu": "",
    "alpha": "1/K",
    "K": "W/m/K",
    "k": "m^2/s",
    "rho": "kg/m^3",
    "c": "J/kg/K",
    "max_temperature": "K",
}
_TEXT_KEYS = ("source", "note", "max_temperature_source")
_REQUIRED = ("E", "nu", "alpha", "K")
_NEED = "need E, nu, alpha, K and either k or rho and c"
_INLINE_EXAMPLE = "E=210e9,nu=0.3,alpha=12e-6,K=50,k=1.4e-5"


def _number(material: str, param: str, value) -> float:
    return _checked(material, check_finite, param, value)


def _positive(material: str, param: str, value) -> float:
    return _checked(material, check_positive, param, value)


def _nonnegative(material: str, param: str, value) -> float:
    return _checked(material, check_nonnegative, param, value)


def _checked(material, check, param, value) -> float:
    """The one wording of :mod:`.validation`, prefixed with the material's name."""
    try:
        return check(param, value)
    except InputError as exc:
        raise MaterialError(f"material '{material}': {exc}") from None


@dataclass(frozen=True)
class Material:
    """Room-temperature properties of an isotropic, elastic, heat-conducting solid.

    Parameters
    ----------
    name : str
        Name used in messages and reports.
    E : float
        Young's modulus, Pa; finite and > 0.
    nu : float
        Poisson's ratio, ``-1 < nu < 0.5``.
    alpha : float
        Coefficient of linear thermal expansion, 1/K; finite and > 0.
    K : float
        Thermal conductivity, W/m/K; finite and >= 0.  ``K = 0`` is a non-conductor
        (the limit ``K -> 0`` at a fixed heat capacity): no heat enters it and it
        does not distort thermally; only the sliding half-planes' instability
        (``thermocontact tei``) accepts one.
    k : float
        Thermal diffusivity ``K/(rho c)``, m^2/s; finite and > 0 (>= 0, and not
        used, when ``K = 0``).
    source : str, optional
        Where the values come from.
    note : str, optional
        Caveats, e.g. the scatter of a class of materials.
    max_temperature : float, optional
        Highest surface temperature the material survives as the material it is
        (melting, decomposition, oxidation or a phase change), K; None if unknown.
    max_temperature_source : str, optional
        Where that limit comes from.

    Raises
    ------
    MaterialError
        If a property is outside its range; the message names the material, the
        property and the allowed range.
    """

    name: str
    E: float
    nu: float
    alpha: float
    K: float
    k: float
    source: str = field(default="", repr=False)
    note: str = field(default="", repr=False)
    max_temperature: float | None = field(default=None, repr=False)
    max_temperature_source: str = field(default="", repr=False)

    def __post_init__(self):
        name = str(self.name)
        object.__setattr__(self, "name", name)
        object.__setattr__(self, "E", _positive(name, "E", self.E))
        nu = _checked(name, lambda p, v: check_range(p, v, -1.0, 0.5, open_low=True,
                                                     open_high=True), "nu", self.nu)
        object.__setattr__(self, "nu", nu)
        object.__setattr__(self, "alpha", _positive(name, "alpha", self.alpha))
        object.__setattr__(self, "K", _checked(name, check_nonnegative, "K", self.K))
        object.__setattr__(self, "k", (_positive if self.K > 0.0 else _nonnegative)(
            name, "k", self.k))
        object.__setattr__(self, "source", str(self.source))
        object.__setattr__(self, "note", str(self.note))
        if self.max_temperature is not None:
            object.__setattr__(self, "max_temperature",
                               _positive(name, "max_temperature", self.max_temperature))
        object.__setattr__(self, "max_temperature_source", str(self.max_temperature_source))

    @property
    def mu(self) -> float:
        """Shear modulus ``E / (2 (1 + nu))``, Pa."""
        return self.E / (2.0 * (1.0 + self.nu))

    @property
    def compliance(self) -> float:
        """Plane-strain compliance ``(1 - nu)/mu = 2 (1 - nu**2)/E``, 1/Pa."""
        return 2.0 * (1.0 - self.nu**2) / self.E

    @property
    def distortivity(self) -> float:
        """Plane-strain distortivity ``delta = alpha (1 + nu)/K``, m/W (``inf`` for a
        non-conductor, which takes no heat: its distortion ``delta q`` is 0)."""
        return self.alpha * (1.0 + self.nu) / self.K if self.K > 0.0 else math.inf

    @property
    def heat_capacity(self) -> float:
        """Volumetric heat capacity ``rho c = K/k``, J/m^3/K (nan when ``k = 0``)."""
        return self.K / self.k if self.k > 0.0 else math.nan

    @property
    def conducts(self) -> bool:
        """``K > 0``: heat enters the body."""
        return self.K > 0.0

    def check_conducts(self, role: str) -> "Material":
        """This material, or a one-line :class:`MaterialError` naming ``role`` if it is
        a non-conductor (``K = 0``), which the steady contact cannot carry."""
        if not self.conducts:
            raise MaterialError(f"{role} must conduct heat (K > 0), got material "
                                f"'{self.name}' with K = 0 (a non-conductor: only "
                                f"'thermocontact tei' accepts one)", parameters=(role,))
        return self


def _normalize(name: str) -> str:
    """Case-insensitive key of a material name; ``_`` and spaces count as ``-``."""
    return re.sub(r"[\s_]+", "-", name.strip().lower())


def _build(name: str, table: Mapping, where: str) -> Material:
    """A :class:`Material` from a mapping of keys to numbers or unit strings."""
    allowed = (*_UNITS, *_TEXT_KEYS)
    for key in table:
        if key not in allowed:
            raise MaterialError(
                f"{where}: unknown key '{key}'; allowed: {', '.join(allowed)}"
            )
    for key in _REQUIRED:
        if key not in table:
            raise MaterialError(f"{where}: missing key '{key}' ({_NEED})")
    has_k = "k" in table
    if has_k and ("rho" in table or "c" in table):
        raise MaterialError(f"{where}: give either k or rho and c, not both")
    if not has_k:
        if "rho" not in table and "c" not in table:
            raise MaterialError(f"{where}: missing key 'k' (or 'rho' and 'c'; {_NEED})")
        for key in ("rho", "c"):
            if key not in table:
                raise MaterialError(f"{where}: missing key '{key}' ({_NEED})")

    values = {}
    for key, unit in _UNITS.items():
        if key in table:
            try:
                values[key] = parse_quantity(table[key], unit, f"material '{name}': {key}")
            except MaterialError:
                raise
            except InputError as exc:
                raise MaterialError(str(exc)) from None
    if not has_k:
        rho = _positive(name, "rho", values["rho"])
        c = _positive(name, "c", values["c"])
        values["k"] = values["K"] / (rho * c)  # K itself is checked by Material
    text = {}
    for key in _TEXT_KEYS:
        if key in table:
            if not isinstance(table[key], str):
                raise MaterialError(f"{where}: {key} must be a string, got {table[key]!r}")
            text[key] = table[key]
    return Material(
        name=name,
        E=values["E"],
        nu=values["nu"],
        alpha=values["alpha"],
        K=values["K"],
        k=values["k"],
        max_temperature=values.get("max_temperature"),
        **text,
    )


def _read_toml(text: str, where: str) -> dict:
    try:
        return tomllib.loads(text)
    except tomllib.TOMLDecodeError as exc:
        message = " ".join(str(exc).split())
        raise MaterialError(f"{where}: invalid TOML: {message}") from None


def _parse_catalogue(data: Mapping, where: str):
    """Materials and aliases (both keyed by normalized names) of a parsed file."""
    materials: dict[str, Material] = {}
    aliases: dict[str, str] = {}
    for key, value in data.items():
        if key == "aliases":
            if not isinstance(value, Mapping):
                raise MaterialError(f"{where}: [aliases] must be a table")
            for alias, target in value.items():
                if not isinstance(target, str):
                    raise MaterialError(
                        f"{where}: alias '{alias}' must name a material, got {target!r}"
                    )
                aliases[_normalize(alias)] = _normalize(target)
            continue
        if not isinstance(value, Mapping):
            raise MaterialError(
                f"{where}: entry '{key}' must be a table of material properties"
            )
        name = _normalize(key)
        if not name:
            raise MaterialError(f"{where}: empty material name")
        if name in materials:
            raise MaterialError(f"{where}: material '{name}' is defined twice")
        materials[name] = _build(name, value, f"{where}: material '{name}'")
    return materials, aliases


@lru_cache(maxsize=1)
def _builtin():
    text = files("thermocontact").joinpath("data").joinpath("materials.toml").read_text(
        encoding="utf-8"
    )
    where = "built-in materials"
    return _parse_catalogue(_read_toml(text, where), where)


def _catalogue(user_file=None):
    """Merged materials and resolved aliases (alias -> material name)."""
    builtin_materials, builtin_aliases = _builtin()
    materials = dict(builtin_materials)
    aliases = dict(builtin_aliases)
    if user_file is not None:
        if not isinstance(user_file, (str, os.PathLike)):
            raise MaterialError(f"materials must be the path of a TOML file, got "
                                f"{user_file!r}", parameters=("materials",))
        path = Path(os.fspath(user_file))
        where = f"materials file '{path.name}'"
        try:
            text = path.read_text(encoding="utf-8")
        except FileNotFoundError:
            raise MaterialError(f"materials file '{path}': not found") from None
        except (OSError, UnicodeDecodeError) as exc:
            raise MaterialError(
                f"materials file '{path}': cannot read ({type(exc).__name__})"
            ) from None
        user_materials, user_aliases = _parse_catalogue(_read_toml(text, where), where)
        for name in user_materials:
            aliases.pop(name, None)  # a material defined by the user beats an alias
        materials.update(user_materials)
        for alias in user_aliases:
            if alias in materials:
                raise MaterialError(
                    f"{where}: alias '{alias}' is also the name of a material"
                )
        aliases.update(user_aliases)
    resolved: dict[str, str] = {}
    for alias in aliases:
        seen = [alias]
        target = aliases[alias]
        while target in aliases:
            if target in seen:
                raise MaterialError(
                    f"alias '{alias}' is circular: {' -> '.join(seen + [target])}"
                )
            seen.append(target)
            target = aliases[target]
        if target not in materials:
            raise MaterialError(f"alias '{alias}' refers to unknown material '{target}'")
        resolved[alias] = target
    return materials, resolved


def load_materials(user_file=None) -> dict[str, Material]:
    """All known materials, keyed by lower-case name and by alias.

    Parameters
    ----------
    user_file : str or os.PathLike, optional
        A TOML file in the built-in file's layout; its materials are added to
        the built-in ones or replace those of the same name, and its
        ``[aliases]`` are added.

    Returns
    -------
    dict of str to Material
        Material names first, then aliases; an alias maps to the same
        :class:`Material` as the name it stands for.

    Raises
    ------
    MaterialError
        If a file cannot be read or holds an invalid material or alias.
    """
    materials, aliases = _catalogue(user_file)
    result = dict(materials)
    for alias, target in aliases.items():
        result[alias] = materials[target]
    return result


def material_aliases(user_file=None) -> dict[str, str]:
    """Aliases and the material names they stand for.

    Parameters
    ----------
    user_file : str or os.PathLike, optional
        As for :func:`load_materials`.

    Returns
    -------
    dict of str to str
    """
    return dict(_catalogue(user_file)[1])


def list_materials(user_file=None) -> list[Material]:
    """The known materials (without aliases), sorted by name.

    Parameters
    ----------
    user_file : str or os.PathLike, optional
        As for :func:`load_materials`.

    Returns
    -------
    list of Material
    """
    materials, _ = _catalogue(user_file)
    return [materials[name] for name in sorted(materials)]


def _parse_inline(spec: str) -> Material:
    """A material from ``"key=value,key=value,..."``; see :func:`get_material`."""
    where = "inline material"
    table: dict[str, str] = {}
    name = "inline"
    for part in spec.split(","):
        part = part.strip()
        if not part:
            continue
        key, sep, value = part.partition("=")
        key, value = key.strip(), value.strip()
        if not sep or not key:
            raise MaterialError(f"{where}: expected key=value, got '{part}'")
        if not value:
            raise MaterialError(f"{where}: no value for key '{key}'")
        if key == "name":
            name = value
            continue
        if key not in _UNITS:
            raise MaterialError(
                f"{where}: unknown key '{key}'; allowed: {', '.join(_UNITS)}, name"
            )
        if key in table:
            raise MaterialError(f"{where}: key '{key}' given twice")
        table[key] = value
    return _build(name, table, where)


def dundurs_beta(cylinder: Material, half_plane: Material) -> float:
    """The paper's ``beta = [(1 - 2 nu1)/mu1 - (1 - 2 nu2)/mu2] / A`` (its eq. 10;
    in magnitude twice Dundurs' second constant), ``A = (1 - nu1)/mu1 + (1 - nu2)/mu2``; in
    ``[-1, 1]``, 0 for a pair of one material (derivation section 5c)."""
    num = (1.0 - 2.0 * cylinder.nu) / cylinder.mu - (1.0 - 2.0 * half_plane.nu) / half_plane.mu
    return num / ((1.0 - cylinder.nu) / cylinder.mu + (1.0 - half_plane.nu) / half_plane.mu)


def get_material(spec, user_file=None) -> Material:
    """Look up a material by name or build it from an inline definition.

    Parameters
    ----------
    spec : str or Material
        A material name or alias (case-insensitive; ``_`` and spaces count as
        ``-``), or an inline definition of comma-separated ``key=value`` pairs:
        ``E``, ``nu``, ``alpha``, ``K`` and either ``k`` or ``rho`` and ``c``,
        optionally ``name``, e.g. ``"E=210e9, nu=0.3, alpha=12e-6, K=50,
        k=1.4e-5"``.  Keys are case-sensitive (``K`` is the conductivity,
        ``k`` the diffusivity).  Plain numbers are SI; values may carry units,
        e.g. ``E=210 GPa``.  A :class:`Material` is returned unchanged.
    user_file : str or os.PathLike, optional
        Extra materials, as for :func:`load_materials`.

    Returns
    -------
    Material

    Raises
    ------
    MaterialError
        For an unknown name (the message suggests the closest known names), a
        malformed inline definition (the message names the missing or bad key),
        or properties out of range.
    """
    if isinstance(spec, Material):
        return spec
    if not isinstance(spec, str):
        raise MaterialError(
            f"material must be a name or an inline definition, got {spec!r}"
        )
    if "=" in spec:
        return _parse_inline(spec)
    key = _normalize(spec)
    if not key:
        raise MaterialError(
            f"material: empty name; give a name or an inline definition such as "
            f"{_INLINE_EXAMPLE}"
        )
    materials, aliases = _catalogue(user_file)
    if key in materials:
        return materials[key]
    if key in aliases:
        return materials[aliases[key]]
    names = sorted({*materials, *aliases})
    close = [n for n in names if key in n]
    close += [
        n for n in difflib.get_close_matches(key, names, n=3, cutoff=0.6) if n not in close
    ]
    if close:
        raise MaterialError(
            f"unknown material '{spec.strip()}'; did you mean: {', '.join(close[:5])}"
        )
    raise MaterialError(
        f"unknown material '{spec.strip()}'; known: {', '.join(names)} "
        f"(or give an inline definition such as {_INLINE_EXAMPLE})"
    )
