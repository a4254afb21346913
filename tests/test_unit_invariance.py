"""The same case written in other units gives the same result to round-off, direction labels
included (issue 12): every bundled case rewritten in inch/pound/degree-Fahrenheit units and
in radians, analysed beside the original."""

import math
import re

import numpy as np
import pytest

from toothcontact import units
from toothcontact.analyses import analyse
from toothcontact.case import parse_case
from toothcontact.views.report import result_document
from toothcontact.runner import bundled_cases_dir

from mutations import bundled, small

#: two units of each dimension: a quantity is rewritten in the first, or in the second if
#: it is already given in the first
OTHER = {"[length]": ("inch", "millimeter"), "[force]": ("lbf", "newton"),
         "[mass] / [length] / [time] ** 2": ("psi", "gigapascal"),
         "[length] ** 2 * [mass] / [time] ** 2": ("lbf * inch", "newton * meter"),
         "[mass] / [time] ** 2": ("lbf / inch", "newton / millimeter"),
         "1 / [length]": ("1 / millimeter", "1 / inch"),
         "[length] ** 2 / [time]": ("stokes", "millimeter ** 2 / second"),
         "[temperature]": ("degF", "kelvin"),
         "1 / [time]": ("radian / second", "revolutions_per_minute"),
         "[mass] / [length] ** 3": ("pound / foot ** 3", "kilogram / meter ** 3"),
         "[length] * [time] ** 2 / [mass]": ("1 / psi", "1 / pascal")}
_QUANTITY = re.compile(r"^\s*([+-]?(?:\d+\.?\d*|\.\d+)(?:[eE][+-]?\d+)?)\s*(\S.*)$")

#: relative agreement asked of every number (the solvers stop at 1e-8 relative)
RTOL = 1e-6
#: where a contact sits on a nearly flat gap (a spline's conformal flanks, A ~ 1e-4/mm) is
#: fixed only to sqrt(round-off/A), about 1e-6 mm; the ends of its pattern along the face
#: (an area contact's, where the crown's gap reaches the approach) are interpolated on
#: lines sampled about that point: lengths agree to 1e-4 mm (0.1 µm)
LENGTH_ATOL = 1e-4
#: the loaded contact's pressure grid takes a cell at a flank edge as all or nothing, so
#: a cell centre within round-off of an edge moves its loads by about 1e-4
LOADED_RTOL = 1e-3
LOADED = ("bem_", "flank_p_max", "edge_pressure", "edge_load", "end_load",
          "loaded_", "max_pressure", "max_edge_pressure", "max_edge_load", "max_end_load", "K_H_beta",
          "mesh_stiffness", "single_stiffness", "line_load", "mean_line_load", "load_share",
          "te_harmonics", "subsurface_", "root_stress", "pinion_root_stress",
          "gear_root_stress", "sigma_H", "sigma_F", "S_H", "S_F", "K_F_beta", "K_H_alpha",
          "K_F_alpha", "flank_pressure", "corner_", "recommended_tip_relief", "miner_sum",
          "friction_coefficient",
          "film_thickness", "lambda", "flash_temperature", "contact_temperature", "power_loss",
          "mesh_power_loss", "mesh_efficiency", "bulk_temperature", "S_B", "S_lambda")
#: an edge pressure averages its strip's cells, each taken all or nothing at the edge:
#: on the measured helical pinion's gear tip 3.5e-3 apart
EDGE_RTOL = 1e-2
#: the ease-off map is asked to 0.1 µm: its last radius is the tip circle, where the tip
#: rounding meets the tip land
#: square (its drop's slope is infinite there): a round-off's move of the circle moves the
#: separation sampled on it by up to 0.05 µm
EASE_OFF_TIP_ATOL = 0.1
#: a loaded transmission error's peak to peak is the difference of two loaded TEs of
#: hundreds of µrad, each to LOADED_RTOL: on a helical pair whose TE barely varies
#: (0.23 µrad peak to peak) it is asked to 0.01 µrad
LOADED_TE_ATOL = 1e-2
#: a transmission error of an unmodified, aligned pair is round-off about zero
#: (1e-8 µrad): agreement asked to 1e-6 µrad
TE_ATOL = 1e-6


#: the inputs as typed, and the solver's own account of its iterations (not a result)
UNCOMPARED = ("inputs", "bem_iterations", "bem_relative_error")


def tolerance(where: str) -> tuple[float, float]:
    """(relative, absolute) agreement asked of the number at `where`."""
    key = where.rsplit(".", 1)[-1].split("[")[0]
    if key.endswith("_percent"):          # a change between two loaded figures
        return LOADED_RTOL, 100 * 2 * LOADED_RTOL
    if key.startswith("edge_pressure"):
        return EDGE_RTOL, 1e-9
    if key == "separation_um" and ".ease_off." in where:
        return RTOL, EASE_OFF_TIP_ATOL
    loaded = (key.startswith(LOADED) or ".bem_" in where or ".positions_check." in where
              or ".duty_cycle." in where or ".rating.figures[" in where)
    if key.startswith(("transmission_error", "loaded_transmission_error", "refined_loaded")) \
            and key.endswith("_um"):      # µrad times the arm (mm), µm: below 0.2 of µrad's
        return (LOADED_RTOL, 0.2 * LOADED_TE_ATOL) if loaded else (RTOL, 0.2 * TE_ATOL)
    if loaded:
        return LOADED_RTOL, LOADED_TE_ATOL if key.endswith("_urad") else 1e-9
    if key.endswith("_urad"):
        return RTOL, TE_ATOL
    if key.endswith("_mm") or ".edge_margins_mm" in where:
        return RTOL, LENGTH_ATOL
    return RTOL, 1e-9


def rewritten(text: str) -> str:
    """A quantity's text in the other unit system, to 17 significant digits."""
    match = _QUANTITY.match(text)
    if match is None:
        return text
    ureg = units.registry()
    try:
        unit = ureg.Unit(match.group(2).replace("^", "**"))
    except Exception:
        return text
    quantity = ureg.Quantity(float(match.group(1)), unit)
    if unit.dimensionless:
        if str(unit) in ("degree", "radian"):
            target = "radian" if str(unit) == "degree" else "degree"
            return f"{quantity.to(target).magnitude!r} {'rad' if target == 'radian' else 'deg'}"
        return text
    targets = OTHER.get(str(unit.dimensionality))
    if targets is None:
        return text
    target = targets[1] if ureg.Unit(targets[0]) == unit else targets[0]
    return f"{quantity.to(target).magnitude!r} {target}"


def in_other_units(value):
    if isinstance(value, dict):
        return {k: (v if k in ("title", "source", "assumptions", "kind", "file")
                    else in_other_units(v)) for k, v in value.items()}
    if isinstance(value, list):
        return [in_other_units(v) for v in value]
    if isinstance(value, str):
        return rewritten(value)
    return value


def differences(a, b, where="result"):
    """Places where two result documents differ beyond round-off."""
    if isinstance(a, dict):
        if set(a) != set(b):
            yield f"{where}: keys {sorted(set(a) ^ set(b))}"
            return
        for key in a:
            if key not in UNCOMPARED:
                yield from differences(a[key], b[key], f"{where}.{key}")
    elif isinstance(a, (list, tuple)):
        if len(a) != len(b):
            yield f"{where}: length {len(a)} != {len(b)}"
            return
        if a and all(isinstance(x, (int, float)) and not isinstance(x, bool) for x in a):
            x, y = np.asarray(a, float), np.asarray(b, float)
            scale = np.nanmax(np.abs(x)) if np.isfinite(x).any() else 0.0
            rtol, atol = tolerance(where)
            if not np.allclose(x, y, rtol=rtol, atol=max(atol, rtol * scale), equal_nan=True):
                worst = int(np.nanargmax(np.abs(x - y)))
                yield f"{where}[{worst}]: {x[worst]!r} != {y[worst]!r}"
            return
        for i, (x, y) in enumerate(zip(a, b)):
            yield from differences(x, y, f"{where}[{i}]")
    elif isinstance(a, float) and isinstance(b, (int, float)):
        rtol, atol = tolerance(where)
        if not (math.isclose(a, b, rel_tol=rtol, abs_tol=atol) or (a != a and b != b)):
            yield f"{where}: {a!r} != {b!r}"
    elif isinstance(a, str) and isinstance(b, str):
        if not same_text(a, b):
            yield f"{where}: {a!r} != {b!r}"
    elif a != b:
        yield f"{where}: {a!r} != {b!r}"


_NUMBER = re.compile(r"[-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?")


def same_text(a: str, b: str) -> bool:
    """Texts equal but for the numbers printed in them, which agree to their printed
    precision (1e-3, or one unit of the last digit printed: a loaded figure known to 1e-3
    may round either way) or are both round-off (below 1e-12)."""
    if _NUMBER.sub("#", a) != _NUMBER.sub("#", b):
        return False
    return all(math.isclose(float(x), float(y), rel_tol=1e-3,
                            abs_tol=max(1e-12, 1.0001 * last_digit(x)))
               for x, y in zip(_NUMBER.findall(a), _NUMBER.findall(b)))


def last_digit(text: str) -> float:
    """The value of one unit in the last digit of a printed number ('0.0776': 1e-4)."""
    mantissa, _, exponent = text.lower().partition("e")
    decimals = len(mantissa.partition(".")[2])
    return 10.0 ** (int(exponent or 0) - decimals) if "." in mantissa else \
        10.0 ** int(exponent or 0)


def document(raw: dict) -> dict:
    case = parse_case(raw, base=bundled_cases_dir())
    return result_document("case", case, raw, analyse(case))


CASES = bundled()
#: the cases analysed with the positions check and the stresses below the contacts; the
#: others without them (the check repeats the analysis at midway positions, the stresses
#: read the solved pressure: neither takes a unit of its own, and together they were half
#: of this test's time, 56 s of it on the spline)
WHOLE = ("spur_crowned_20_60", "worm_eps_oversized_hob")


@pytest.mark.parametrize("name", sorted(CASES))
def test_a_case_in_other_units_gives_the_same_result(name):
    raw = small(CASES[name], interference=False)
    if "analysis" in raw:
        raw["analysis"]["positions"] = 3
        if name not in WHOLE and raw["kind"] in ("spur", "spline", "worm", "imported"):
            raw["analysis"].update(positions_check=False, subsurface=False)
    other = in_other_units(raw)
    assert other != raw or name.startswith("hertz_sphere"), "nothing was rewritten"
    found = list(differences(document(raw), document(other)))
    assert not found, "\n".join(found[:12])


def test_the_rewrite_is_a_change_of_units_only():
    """The rewritten quantities parse to the same core values to round-off."""
    assert rewritten("1.44 in").endswith("millimeter")
    number, unit = rewritten("32 1/in").split(" ", 1)
    assert unit == "1 / millimeter" and float(number) == pytest.approx(32 / 25.4, rel=1e-15)
    assert units.parse(rewritten("30 mm"), "length") == pytest.approx(30.0, rel=1e-15)
    assert units.parse(rewritten("-50 degC"), "temperature") == pytest.approx(-50.0, rel=1e-13)
    assert units.parse(rewritten("20 deg"), "angle") == pytest.approx(math.radians(20), rel=1e-15)
    assert units.parse(rewritten("8000 N"), "force") == pytest.approx(8000.0, rel=1e-15)
    assert units.parse(rewritten("206 GPa"), "stress") == pytest.approx(206e3, rel=1e-15)


def test_the_spline_pitch_one_ulp_apart_gives_the_same_pattern():
    """The issue's case: "32 1/in" and "1.2598425196850394 1/mm" (1 ulp apart) moved the
    spline's rigid pattern area by 6 %."""
    raw = small(CASES["spline_crowned_18t"])
    raw["analysis"].update(interference=False, pressure_grid=0)
    other = {**raw, "diametral_pitch": "1.2598425196850394 1/mm"}
    found = list(differences(document(raw), document(other)))
    assert not found, "\n".join(found[:12])
