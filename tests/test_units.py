"""Quantities with units in, core units out."""

import pytest

from toothcontact.units import UnitError, parse


@pytest.mark.parametrize("text,kind,expected", [
    ("1.44 in", "length", 36.576), ("12 um", "length", 0.012), ("inf", "length", float("inf")),
    ("3600 lbf", "force", 3600 * 4.4482216152605), ("206 GPa", "stress", 206000.0),
    ("30000 ksi", "stress", 30000 * 6.89475729), ("478 lbf*in", "torque", 478 * 4.4482216152605 * 25.4),
    ("40 N*m", "torque", 40000.0), ("20 deg", "angle", 0.3490658503988659),
    ("0.0019", "slope", 0.0019), (0.0019, "slope", 0.0019), ("0.0019 in/in", "slope", 0.0019),
    ("8 mrad", "slope", 0.008), ("10 1/in", "inverse_length", 10 / 25.4),
    ("-50 degC", "temperature", -50.0), ("-58 degF", "temperature", -50.0),
    ("30000 mm^2/s", "viscosity", 30000.0), ("220 cSt", "viscosity", 220.0),
    ("30 N/mm", "stiffness", 30.0),
])
def test_parse_to_core_units(text, kind, expected):
    assert parse(text, kind) == pytest.approx(expected, rel=1e-9)


@pytest.mark.parametrize("text,kind,fragment", [
    ("3 kg", "length", "is not a length"), ("20", "angle", "has no unit"),
    ("20 mm/mm", "angle", "is not an angle"), ("abc", "length", "does not start with a number"),
    ("3 furlongz", "length", "unknown unit"), (30.0, "length", "has no unit"),
    ("inf N", "force", "infinite"), (True, "length", "not a quantity"),
])
def test_bad_quantities_say_what_is_expected(text, kind, fragment):
    with pytest.raises(UnitError, match=fragment):
        parse(text, kind)
