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
