"""Reading quantities with and without units into SI floats."""

import math

import pytest

from thermocontact.problem.validation import InputError
from thermocontact.problem.units import parse_quantity


@pytest.mark.parametrize(
    ("value", "unit", "expected"),
    [
        ("200kN/m", "N/m", 2e5),
        ("200 kN/m", "N/m", 2e5),
        ("72km/h", "m/s", 20.0),
        ("72 km/h", "m/s", 20.0),
        ("450mm", "m", 0.45),
        ("0.45 m", "m", 0.45),
        ("210 GPa", "Pa", 2.1e11),
        ("12e-6 1/K", "1/K", 1.2e-5),
        ("12 ppm/K", "1/K", 1.2e-5),
        ("50 W/m/K", "W/m/K", 50.0),
        ("5 mm^2/s", "m^2/s", 5e-6),
        ("0.3", "", 0.3),
        ("2e5", "N/m", 2e5),
        ("  2e5 ", "N/m", 2e5),
        ("-3.5", "m", -3.5),  # sign is the caller's business
    ],
)
def test_strings(value, unit, expected):
    assert parse_quantity(value, unit, "x") == pytest.approx(expected, rel=1e-12)


@pytest.mark.parametrize("value", [2e5, 7, -1.5, 0.0])
def test_numbers_pass_through(value):
    result = parse_quantity(value, "N/m", "P")
    assert result == value and isinstance(result, float)


def test_pint_quantity():
    import pint

    q = pint.UnitRegistry().Quantity(3, "mm")
    assert parse_quantity(q, "m", "a") == pytest.approx(3e-3)


def test_dimension_mismatch():
    with pytest.raises(InputError) as err:
        parse_quantity("72 kg", "m/s", "v")
    assert str(err.value) == "v: cannot read '72 kg' as a quantity in m/s"


@pytest.mark.parametrize("value", ["garbage", "2 +", "", "   ", "m/s/", "12 apples"])
def test_garbage(value):
    with pytest.raises(InputError, match=r"^speed: cannot read .* as a quantity in m/s$"):
        parse_quantity(value, "m/s", "speed")


@pytest.mark.parametrize("value", [math.inf, -math.inf, math.nan, "inf", "nan", "inf m/s"])
def test_non_finite(value):
    with pytest.raises(InputError, match="^v"):
        parse_quantity(value, "m/s", "v")


@pytest.mark.parametrize("value", [None, True, [1.0], object()])
def test_wrong_type(value):
    with pytest.raises(InputError, match="^v: cannot read"):
        parse_quantity(value, "m/s", "v")


def test_messages_are_one_line():
    for value in ["72 kg", "2 +", "inf"]:
        with pytest.raises(InputError) as err:
            parse_quantity(value, "m/s", "v")
        assert "\n" not in str(err.value)


SI_CASES = [
    ("450mm", "m"), ("72 km/h", "m/s"), ("200kN/m", "N/m"), ("3 m / s", "m/s"),
    ("12e-6 1/K", "1/K"), ("50 W/m/K", "W/m/K"), ("1.2e-5 m^2/s", "m^2/s"),
    ("1.2e-5 m**2/s", "m^2/s"), ("2 N/mm", "N/m"), ("0.5 ms", "s"), ("10 min", "s"),
    ("1 h", "s"), ("30 GPa", "Pa"), ("3 mPa", "Pa"), (".5 um", "m"), ("2 N*m/m", "N"),
    ("2 N m / m", "N"), ("3e2 mm/min", "m/s"), ("7 kg/m^3", "kg/m^3"),
    ("1 W/m^2", "kg/s^3"), ("4 cm^-1", "1/m"), ("8 MN/m", "N/m"), ("1 kJ/kg/K", "J/kg/K"),
]


@pytest.mark.parametrize(("value", "unit"), SI_CASES)
def test_si_table_agrees_with_pint(value, unit):
    """Units read by the SI table (no pint) equal pint's reading to rounding, and the
    table does read each of these (it is what keeps pint out of a command line)."""
    from thermocontact.problem.units import _read_si, _registry

    fast = _read_si(value, unit)
    assert isinstance(fast, float)
    assert fast == pytest.approx(_registry().Quantity(value).to(unit).magnitude, rel=1e-14)


@pytest.mark.parametrize(("value", "unit"), [("5 mph", "m/s"), ("1 inch", "m"),
                                             ("20 degC", "K"), ("5 m/", "m"), ("2 (N/m)", "N/m")])
def test_other_units_are_left_to_pint(value, unit):
    """What the table does not know is pint's to read (or to refuse)."""
    from thermocontact.problem.units import _read_si

    assert _read_si(value, unit) is None


def _si_expressions():
    from hypothesis import strategies as st

    symbols = st.sampled_from(["m", "g", "s", "min", "h", "K", "N", "Pa", "J", "W"])
    prefixes = st.sampled_from(["", "p", "n", "u", "m", "c", "k", "M", "G"])
    powers = st.sampled_from(["", "^2", "^-1", "**3", "^3"])
    factor = st.tuples(prefixes, symbols, powers).map(lambda t: "".join(t))
    joins = st.sampled_from(["/", "*", " ", " / "])
    return st.tuples(st.floats(1e-3, 1e3), factor,
                     st.lists(st.tuples(joins, factor), max_size=3))


def test_si_table_agrees_with_pint_on_generated_units():
    """Products and quotients of the table's symbols with prefixes and powers, as the
    table reads them and as pint does (converted to the SI base units of their own
    dimension), agree to 1e-12; what the table does not read, pint must be asked."""
    from hypothesis import given, settings

    from thermocontact.problem.units import _read_si, _registry, _si

    ureg = _registry()

    @settings(max_examples=150, deadline=None)
    @given(_si_expressions())
    def check(case):
        number, first, rest = case
        unit = first + "".join(j + f for j, f in rest)
        text = f"{number!r} {unit}"
        q = ureg.Quantity(text).to_base_units()
        base = {"meter": 0, "kilogram": 1, "second": 2, "kelvin": 3}
        dims = [0, 0, 0, 0]
        for name, power in q.unit_items():
            dims[base[name]] += power
        have = _si(unit)
        assert have is not None, unit
        assert tuple(dims) == have[1], unit
        si_unit = "*".join(f"{k}^{p}" for k, p in zip(("m", "kg", "s", "K"), have[1]) if p) or ""
        value = _read_si(text, si_unit) if si_unit else None
        if value is not None:
            assert value == pytest.approx(q.magnitude, rel=1e-12), text
    check()
