"""The materials database, user files and inline material definitions."""

import dataclasses
import math

import pytest

from thermocontact.problem.materials import (
    Material,
    MaterialError,
    get_material,
    list_materials,
    load_materials,
    material_aliases,
)
from thermocontact.problem.validation import InputError

BUILTIN = [
    "carbon-steel",
    "wheel-steel",
    "grey-cast-iron",
    "aluminium-alloy",
    "copper",
    "bronze",
    "organic-composite-brake-block",
    "sintered-brake-material",
    "carbon-carbon",
    "alumina",
    "paper-based-clutch-facing",
    "sintered-bronze-facing",
]

STEEL = "E=210e9,nu=0.3,alpha=12e-6,K=50,k=1.4e-5"


def test_material_error_is_input_error():
    assert issubclass(MaterialError, InputError)
    assert issubclass(MaterialError, ValueError)


def test_every_builtin_loads_and_validates():
    materials = load_materials()
    names = [m.name for m in list_materials()]
    assert sorted(BUILTIN) == names
    for name in BUILTIN:
        m = materials[name]
        assert m.name == name
        for value in (m.E, m.alpha, m.K, m.k):
            assert math.isfinite(value) and value > 0
        assert -1 < m.nu < 0.5
        assert m.source.strip()
        # Re-validating the stored values must succeed.
        assert dataclasses.replace(m) == m


def test_builtin_values_are_room_temperature_plausible():
    for m in list_materials():
        # Paper-based clutch facings, porous and oil-filled, are the softest: 0.3 GPa.
        assert (1e9 if m.name != "paper-based-clutch-facing" else 1e8) <= m.E <= 500e9, m.name
        assert 0.1 <= m.nu <= 0.4, m.name
        assert 1e-6 <= m.alpha <= 5e-5, m.name
        assert 0.1 <= m.K <= 500, m.name
        assert 1e-7 <= m.k <= 2e-4, m.name
        assert 1e6 <= m.heat_capacity <= 5e6, m.name  # rho c of solids


def test_wide_scatter_classes_say_so():
    for name in ("organic-composite-brake-block", "sintered-brake-material", "carbon-carbon",
                 "paper-based-clutch-facing", "sintered-bronze-facing"):
        assert get_material(name).note, name


def test_derived_quantities_carbon_steel():
    # E = 205 GPa, nu = 0.29, alpha = 11.7e-6 /K, K = 60.5 W/m/K,
    # rho = 7854 kg/m^3, c = 434 J/kg/K (values of the built-in file).
    m = get_material("carbon-steel")
    assert (m.E, m.nu, m.alpha, m.K) == (205e9, 0.29, 11.7e-6, 60.5)
    assert m.k == pytest.approx(60.5 / 3_408_636, rel=1e-12)  # rho c = 3 408 636
    assert m.k == pytest.approx(1.774904e-5, rel=1e-6)
    assert m.mu == pytest.approx(79.457364e9, rel=1e-7)  # 205e9 / 2.58
    assert m.compliance == pytest.approx(8.9356098e-12, rel=1e-7)  # 2 * 0.9159 / 205e9
    assert m.compliance == pytest.approx((1 - m.nu) / m.mu, rel=1e-14)
    assert m.distortivity == pytest.approx(2.4947107e-7, rel=1e-7)  # 15.093e-6 / 60.5
    assert m.heat_capacity == pytest.approx(3_408_636, rel=1e-12)


def test_aliases():
    assert get_material("steel") == get_material("carbon-steel")
    assert get_material("steel").name == "carbon-steel"
    assert get_material("cast-iron").name == "grey-cast-iron"
    materials = load_materials()
    assert materials["steel"] is materials["carbon-steel"]
    assert material_aliases() == {"steel": "carbon-steel", "cast-iron": "grey-cast-iron"}
    assert "steel" not in [m.name for m in list_materials()]


@pytest.mark.parametrize("spec", ["Carbon-Steel", "  STEEL ", "carbon_steel", "carbon steel"])
def test_names_are_case_insensitive(spec):
    assert get_material(spec).name == "carbon-steel"


def test_material_passes_through():
    m = get_material("copper")
    assert get_material(m) is m


USER_FILE = """
[carbon-steel]            # override a built-in material
E = "200 GPa"
nu = 0.3
alpha = 12e-6
K = 50
k = 1.3e-5
source = "test data"

[Titanium-6Al-4V]         # add one; the name is normalized to lower case
E = 114e9
nu = 0.34
alpha = "8.6 ppm/K"
K = 6.7
rho = 4430
c = 526

[aliases]
ti64 = "titanium-6al-4v"
mild-steel = "steel"      # aliases may point at aliases
"""


@pytest.fixture
def user_file(tmp_path):
    path = tmp_path / "my_materials.toml"
    path.write_text(USER_FILE, encoding="utf-8")
    return path


def test_user_file_overrides_and_adds(user_file):
    materials = load_materials(user_file)
    steel = materials["carbon-steel"]
    assert (steel.E, steel.nu, steel.K, steel.k) == (200e9, 0.3, 50.0, 1.3e-5)
    assert steel.source == "test data"
    assert materials["steel"] is steel
    assert materials["mild-steel"] is steel
    ti = get_material("TI64", user_file=str(user_file))
    assert ti.name == "titanium-6al-4v"
    assert ti.alpha == pytest.approx(8.6e-6)
    assert ti.k == pytest.approx(6.7 / (4430 * 526))
    assert len(list_materials(user_file)) == len(BUILTIN) + 1
    # The built-in database is unaffected.
    assert get_material("carbon-steel").E == 205e9


def test_user_material_replaces_alias(tmp_path):
    path = tmp_path / "m.toml"
    path.write_text("[steel]\nE=1e9\nnu=0.2\nalpha=1e-5\nK=1\nk=1e-6\n", encoding="utf-8")
    assert get_material("steel", path).E == 1e9
    assert "steel" not in material_aliases(path)


@pytest.mark.parametrize(
    ("text", "fragment"),
    [
        ("[x]\nE=1e9\nnu=0.2\nalpha=1e-5\nK=1\n", "missing key 'k'"),
        ("[x]\nE=1e9\nnu=0.2\nalpha=1e-5\nK=1\nrho=1000\n", "missing key 'c'"),
        ("[x]\nE=1e9\nnu=0.2\nK=1\nk=1e-6\n", "missing key 'alpha'"),
        ("[x]\nE=1e9\nnu=0.2\nalpha=1e-5\nK=1\nk=1e-6\nalpa=1\n", "unknown key 'alpa'"),
        ("[x]\nE=1e9\nnu=0.2\nalpha=1e-5\nK=1\nk=1e-6\nrho=1\nc=1\n", "either k or rho"),
        ("[x]\nE=-1e9\nnu=0.2\nalpha=1e-5\nK=1\nk=1e-6\n", "E must be > 0"),
        ("[x]\nE='1 kg'\nnu=0.2\nalpha=1e-5\nK=1\nk=1e-6\n", "E: cannot read"),
        ("[x]\nE=1e9\nnu=0.2\nalpha=1e-5\nK=1\nrho=-1\nc=1\n", "rho must be > 0"),
        ("[x]\nE=1e9\nnu=0.2\nalpha=1e-5\nK=1\nk=1e-6\nsource=3\n", "source must be a string"),
        ("x = 3\n", "entry 'x' must be a table"),
        ("[x\n", "invalid TOML"),
        ("[aliases]\na = 'nothing'\n", "alias 'a' refers to unknown material 'nothing'"),
        ("[aliases]\na = 'b'\nb = 'a'\n", "circular"),
        ("[aliases]\ncopper = 'alumina'\n", "alias 'copper' is also the name of a material"),
    ],
)
def test_bad_user_file(tmp_path, text, fragment):
    path = tmp_path / "bad.toml"
    path.write_text(text, encoding="utf-8")
    with pytest.raises(MaterialError) as err:
        load_materials(path)
    assert fragment in str(err.value)
    assert "\n" not in str(err.value)


def test_missing_user_file(tmp_path):
    with pytest.raises(MaterialError, match="not found"):
        load_materials(tmp_path / "absent.toml")


def test_inline_with_diffusivity():
    m = get_material(STEEL)
    assert (m.E, m.nu, m.alpha, m.K, m.k) == (210e9, 0.3, 12e-6, 50.0, 1.4e-5)
    assert m.name == "inline"


def test_inline_with_rho_c_units_and_spaces():
    m = get_material(" E = 210 GPa , nu=0.3, alpha=12e-6 1/K, K=50 W/m/K, rho=7800, c=450 J/kg/K ")
    assert m.E == pytest.approx(210e9)
    assert m.alpha == pytest.approx(12e-6)
    assert m.k == pytest.approx(50 / (7800 * 450))


def test_inline_name():
    assert get_material(STEEL + ",name=my steel").name == "my steel"


@pytest.mark.parametrize(
    ("spec", "param"),
    [
        ("E=0,nu=0.3,alpha=12e-6,K=50,k=1.4e-5", "E must be > 0"),
        ("E=-210e9,nu=0.3,alpha=12e-6,K=50,k=1.4e-5", "E must be > 0"),
        ("E=inf,nu=0.3,alpha=12e-6,K=50,k=1.4e-5", "E must be a finite real number"),
        ("E=210e9,nu=0.5,alpha=12e-6,K=50,k=1.4e-5", "nu must be in (-1, 0.5)"),
        ("E=210e9,nu=-1,alpha=12e-6,K=50,k=1.4e-5", "nu must be in (-1, 0.5)"),
        ("E=210e9,nu=0.3,alpha=-12e-6,K=50,k=1.4e-5", "alpha must be > 0"),
        ("E=210e9,nu=0.3,alpha=12e-6,K=-1,k=1.4e-5", "K must be >= 0"),
        ("E=210e9,nu=0.3,alpha=12e-6,K=50,k=-1", "k must be > 0"),
        ("E=210e9,nu=0.3,alpha=12e-6,K=50,rho=0,c=450", "rho must be > 0"),
    ],
)
def test_inline_out_of_range(spec, param):
    with pytest.raises(MaterialError) as err:
        get_material(spec)
    message = str(err.value)
    assert param in message
    assert message.startswith("material 'inline': ")
    assert "\n" not in message


@pytest.mark.parametrize(
    ("kwargs", "param"),
    [
        ({"E": 0.0}, "E must be > 0"),
        ({"E": math.nan}, "E must be > 0 (finite)"),
        ({"E": "abc"}, "E must be > 0 (finite)"),
        ({"nu": 0.5}, "nu must be in (-1, 0.5)"),
        ({"nu": -1.0}, "nu must be in (-1, 0.5)"),
        ({"alpha": -1e-6}, "alpha must be > 0"),
        ({"K": -1.0}, "K must be >= 0"),
        ({"k": 0.0}, "k must be > 0"),
    ],
)
def test_constructor_validation(kwargs, param):
    base = {"name": "test", "E": 1e9, "nu": 0.3, "alpha": 1e-5, "K": 1.0, "k": 1e-6}
    with pytest.raises(MaterialError) as err:
        Material(**{**base, **kwargs})
    assert str(err.value).startswith(f"material 'test': {param}")


@pytest.mark.parametrize(
    ("spec", "fragment"),
    [
        ("E=210e9,nu=0.3,alpha=12e-6,K=50", "missing key 'k'"),
        ("E=210e9,nu=0.3,K=50,k=1.4e-5", "missing key 'alpha'"),
        ("E=210e9,nu=0.3,alpha=12e-6,K=50,rho=7800", "missing key 'c'"),
        ("E=210e9,nu=0.3,alpha=12e-6,K=50,k=1.4e-5,rho=7800,c=450", "either k or rho"),
        ("E=210e9,nu=0.3,alpha=12e-6,K=50,k=1.4e-5,G=80e9", "unknown key 'G'"),
        ("E=210e9,E=200e9,nu=0.3,alpha=12e-6,K=50,k=1.4e-5", "key 'E' given twice"),
        ("E=210e9,nu,alpha=12e-6,K=50,k=1.4e-5", "expected key=value, got 'nu'"),
        ("E=,nu=0.3,alpha=12e-6,K=50,k=1.4e-5", "no value for key 'E'"),
        ("E=210 kg,nu=0.3,alpha=12e-6,K=50,k=1.4e-5", "E: cannot read '210 kg' as a quantity in Pa"),
        ("E=210e9,nu=0.3,alpha=12e-6,K=fifty,k=1.4e-5", "K: cannot read 'fifty'"),
    ],
)
def test_malformed_inline(spec, fragment):
    with pytest.raises(MaterialError) as err:
        get_material(spec)
    assert fragment in str(err.value)
    assert "\n" not in str(err.value)


def test_unknown_material_suggests():
    with pytest.raises(MaterialError) as err:
        get_material("stel")
    assert str(err.value).startswith("unknown material 'stel'; did you mean: steel")


def test_unknown_material_substring_suggests():
    with pytest.raises(MaterialError) as err:
        get_material("iron")
    message = str(err.value)
    assert "cast-iron" in message and "grey-cast-iron" in message


def test_unknown_material_lists_known():
    with pytest.raises(MaterialError) as err:
        get_material("unobtainium")
    message = str(err.value)
    assert message.startswith("unknown material 'unobtainium'; known: ")
    assert all(name in message for name in BUILTIN)


@pytest.mark.parametrize("spec", ["", "   ", 3.0, None])
def test_bad_spec(spec):
    with pytest.raises(MaterialError, match="material"):
        get_material(spec)
