"""Quantities in, plain floats out.

Case files carry quantities as text with units ("1.44 in", "3600 lbf", "-50 degC"). This
module is the only place that knows about units: it turns such text into a float in the
core unit of its kind, and says clearly when the text is not a quantity of that kind.

Core units: mm, N, MPa, N*mm, N/mm, rad, 1/mm, mm^2/s, degC, rpm, kg/m^3, 1/MPa, h,
W·s^0.5/(m²·K). Hardness is a number on a named scale (HV, HBW, HRC): parse_hardness.
"""

from __future__ import annotations

import math
import re
from dataclasses import dataclass
from functools import lru_cache


class UnitError(ValueError):
    """A text that is not a quantity of the expected kind (message has no field name)."""


@dataclass(frozen=True)
class Kind:
    """A kind of quantity: its core unit, its pint dimensionality and an example."""

    name: str
    core_unit: str
    dimensionality: str
    example: str
    bare_number_allowed: bool = False
    #: the largest magnitude, in the core unit, that a gear case can mean (beyond it a
    #: number is a typo or an overflow waiting to happen)
    largest: float = math.inf
    #: the smallest magnitude of a quantity that must be positive (a size, a load)
    smallest: float = 0.0


KINDS: dict[str, Kind] = {
    k.name: k
    for k in (
        Kind("length", "mm", "[length]", "'3 mm' or '0.125 in'", largest=1e5, smallest=1e-6),
        Kind("force", "N", "[force]", "'8000 N' or '3600 lbf'", largest=1e8, smallest=1e-6),
        Kind("stress", "MPa", "[pressure]", "'206 GPa' or '30000 ksi'", largest=1e10,
             smallest=1e-3),
        Kind("torque", "N*mm", "[force]*[length]", "'40 N*m' or '478 lbf*in'", largest=1e10,
             smallest=1e-6),
        Kind("stiffness", "N/mm", "[force]/[length]", "'30 N/mm'", largest=1e9, smallest=1e-6),
        Kind("angle", "rad", "", "'20 deg' or '0.35 rad'", largest=2 * math.pi),
        Kind("slope", "rad", "", "'0.0015' (rad), '0.0015 in/in' or '0.1 deg'", True,
             largest=0.1),
        Kind("inverse_length", "1/mm", "1/[length]", "'10 1/in'", largest=100.0, smallest=1e-5),
        Kind("viscosity", "mm**2/s", "[length]**2/[time]", "'220 mm^2/s' or '220 cSt'",
             largest=1e7, smallest=1e-3),
        Kind("temperature", "degC", "[temperature]", "'-50 degC' or '176 degF'", largest=1000.0),
        Kind("rotational_speed", "rpm", "1/[time]", "'3000 rpm' or '314 rad/s'", largest=1e6,
             smallest=1e-6),
        Kind("density", "kg/m**3", "[mass]/[length]**3", "'880 kg/m^3' or '0.88 g/cm^3'",
             largest=1e5, smallest=1e-3),
        Kind("pressure_viscosity", "1/MPa", "1/[pressure]", "'1.8e-8 1/Pa' or '18 1/GPa'",
             largest=1.0, smallest=1e-6),
        Kind("time", "hour", "[time]", "'20000 h' or '2.3 year'", largest=1e7, smallest=1e-6),
        Kind("thermal_contact_coefficient", "W*s**0.5/(m**2*K)",
             "[mass]/[time]**2.5/[temperature]", "'12.7 kW*s^0.5/(m^2*K)'", largest=1e6,
             smallest=1.0),
    )
}

_NUMBER = re.compile(r"^\s*([+-]?(?:inf(?:inity)?|(?:\d+\.?\d*|\.\d+)(?:[eE][+-]?\d+)?))\s*(.*?)\s*$",
                     re.IGNORECASE)
_ANGLE_UNITS = {"radian", "degree", "arcminute", "arcsecond", "milliradian", "microradian",
                "turn", "gradian"}


def split(text: str) -> tuple[float, str] | None:
    """A quantity's text as its number and its unit's text ('' for none), or None where it
    does not start with a number."""
    match = _NUMBER.match(text)
    return None if match is None else (float(match.group(1)), match.group(2))


@lru_cache(maxsize=1)
def registry():
    """The shared pint registry (built on first use: pint is slow to import)."""
    import pint

    return pint.UnitRegistry()


#: torque units as KISSsoft users write them, which pint reads otherwise ("Nm": nanometres)
TORQUE_SHORTHANDS = {"Nm": "N*m", "kNm": "kN*m", "Nmm": "N*mm", "N.m": "N*m", "N·m": "N*m"}


#: a speed names what turns: "1/s" or "Hz" could mean turns or radians per second
ROTATION_UNIT = re.compile(r"rpm|rad|rev|turn|r/min", re.IGNORECASE)


def parse(text: str | float | int, kind: str) -> float:
    """Convert `text` to a float in the core unit of `kind` (see KINDS).

    A bare number is accepted only where its unit is unambiguous (slopes, in rad).
    "inf" (with or without a unit) is accepted for lengths: a flat body's radius.
    """
    spec = KINDS[kind]
    if isinstance(text, bool) or not isinstance(text, (str, int, float)):
        raise UnitError(f"{text!r} is not a quantity; expected {_expected(spec)}")
    if isinstance(text, (int, float)):
        if not spec.bare_number_allowed:
            raise UnitError(f"{text!r} has no unit; expected {_expected(spec)}")
        if math.isnan(text):
            raise UnitError(f"{text!r} is not a number; expected {_expected(spec)}")
        return float(text)
    control = next((ch for ch in text if ord(ch) < 32 or 127 <= ord(ch) < 160), None)
    if control is not None:
        raise UnitError(f"{text!r} holds control character U+{ord(control):04X}")
    parts = split(text)
    if parts is None:
        raise UnitError(f"{text!r} does not start with a number; expected {_expected(spec)}")
    magnitude, unit_text = parts
    if math.isinf(magnitude) and kind != "length":
        raise UnitError(f"{text!r} is infinite; expected a finite {_expected(spec)}")
    if not unit_text:
        if spec.bare_number_allowed or math.isinf(magnitude):
            return magnitude
        raise UnitError(f"{text!r} has no unit; expected {_expected(spec)}")
    ureg = registry()
    if kind == "torque":           # "Nm", "kNm", "Nmm" as gear engineers write them
        unit_text = TORQUE_SHORTHANDS.get(unit_text.strip(), unit_text)
    try:
        unit = ureg.Unit(unit_text.replace("^", "**"))
    except Exception:
        raise UnitError(f"{text!r}: unknown unit {unit_text!r}; expected {_expected(spec)}") from None
    if not _has_dimension(unit, spec):
        raise UnitError(f"{text!r} is not {_expected(spec)}")
    if kind == "rotational_speed" and not ROTATION_UNIT.search(unit_text):
        raise UnitError(f"{text!r} does not say what turns: give rpm, revolution/second or "
                        "rad/s (Hz and 1/s could mean either turns or radians)")
    return float(ureg.Quantity(magnitude, unit).to(spec.core_unit).magnitude)


#: the hardness scales a case may name, and what each is
HARDNESS_SCALES = {"HV": "Vickers", "HBW": "Brinell", "HRC": "Rockwell C"}
_HARDNESS = re.compile(r"^\s*(\d+\.?\d*|\.\d+)\s*([A-Za-z]+)\s*$")


def parse_hardness(text, scales: tuple[str, ...] = ("HV", "HBW")) -> tuple[float, str]:
    """A hardness as (number, scale), e.g. '650 HV' -> (650.0, 'HV'), on one of `scales`
    (HARDNESS_SCALES' keys; a bare number or another scale is refused: scales do not
    convert into each other exactly)."""
    allowed = " or ".join(f"{s} ({HARDNESS_SCALES[s]})" for s in scales)
    match = _HARDNESS.match(text) if isinstance(text, str) else None
    if not match:
        raise UnitError(f"{text!r} is not a hardness; expected a number and its scale, "
                        f"{allowed}, e.g. '{'650' if scales[0] == 'HV' else '32'} {scales[0]}'")
    value, scale = float(match.group(1)), match.group(2).upper()
    if scale not in scales:
        raise UnitError(f"{text!r}: the scale {match.group(2)!r} is not {allowed}")
    if not value > 0:
        raise UnitError(f"{text!r} must be greater than zero")
    return value, scale


def show(value: float, kind: str) -> str:
    """A core-unit value as text with its unit, e.g. '1e+08 N'."""
    unit = KINDS[kind].core_unit.replace("**", "^")
    return f"{value:.6g} {unit}" if unit != "rad" or kind == "angle" else f"{value:.6g} rad"


def _has_dimension(unit, spec: Kind) -> bool:
    ureg = registry()
    if spec.dimensionality:
        return unit.dimensionality == ureg.get_dimensionality(spec.dimensionality)
    if not unit.dimensionless:
        return False
    if spec.name == "angle":
        return any(ureg.get_name(str(u)) in _ANGLE_UNITS for u in unit._units)
    return True


def _expected(spec: Kind) -> str:
    article = "an" if spec.name[0] in "aeiou" else "a"
    return f"{article} {spec.name.replace('_', ' ')} such as {spec.example}"
