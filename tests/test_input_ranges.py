"""Inputs held to where their formulas hold (issue 53): each class of a third fuzzer's
findings, on the bundled FZG pair (lubricated, rated, with a duty cycle) and the bundled
sweeps. Internal errors are gone (ASTM D341's line past its range, a contact without a
relative radius, a file name too long, a flank turned onto an edge); implausible figures
are refused or bounded with a note (cold oil below its pour point, S_B's temperatures,
ISO/TR 14179-2's μ at a crawl, S_B as the flash temperature vanishes); bad input is refused
naming the field (counts that are not finite, switches for numbers, control characters,
NaN constraints); the legal inputs are answered (a sweep's tolerance in degC, a large pair
whose loaded mesh keeps a pair far apart); refusals name what the user wrote (the CSV's
file, row and column, the spectrum level, the tolerance's key, a sweep for a base, the
nearest figures). Most are parse-level; a few run a small analysis."""

import math
import tomllib
from pathlib import Path

import numpy as np
import pytest
import tomli_w

import mutations
from toothcontact.case import CaseError, parse_case

FZG = tomllib.loads((mutations.CASES / "fzg_c_type.toml").read_text(encoding="utf-8"))
#: the smallest analysis that solves the loaded contact
QUICK = {"positions": 3, "positions_check": False, "subsurface": False,
         "interference": False, "pressure_grid": 48, "field_grid": 41, "grid": [9, 15]}


def fzg(**tables) -> dict:
    """The bundled FZG pair's table with fields set: the members', [operation]'s,
    [lubricant]'s and [rating]'s merged into its own, any other replacing it (None
    removing it)."""
    raw = {**FZG, "analysis": dict(QUICK)}
    for key, value in tables.items():
        merged = key in ("pinion", "gear", "operation", "lubricant", "rating") and value
        raw[key] = {**raw[key], **value} if merged else value
    return {key: value for key, value in raw.items() if value is not None}


def refused(raw: dict, says: str, base=None) -> str:
    with pytest.raises(CaseError) as error:
        parse_case(raw, base=base)
    assert says in str(error.value), str(error.value)
    return str(error.value)


# -- internal errors gone ---------------------------------------------------------------

def test_astm_d341s_line_holds_only_over_its_range():
    """Walther's log log(ν + 0.7) has no value below ν = 0.3 mm²/s and overflows far below
    any pour point: viscosities under 2 mm²/s (D341's range for the offset 0.7 alone) are
    refused by name, and the line gives inf, not an OverflowError, at 1 K."""
    from toothcontact.analytic.lubricant import kinematic_viscosity

    assert kinematic_viscosity(100.0, 11.0, -272.15) == math.inf
    assert kinematic_viscosity(100.0, 11.0, 40.0) == pytest.approx(100.0)
    refused(fzg(lubricant={"viscosity_40": "0.3 mm^2/s", "viscosity_100": "0.1 mm^2/s"}),
            "viscosity_40: 0.3 mm^2/s must be at least 2 mm^2/s")


@pytest.mark.parametrize("oil", ["-200 degC", "-273 degC", "1 K", "-459 degF", "-90 degC",
                                 "-55 degC"])
def test_oil_below_its_pour_point_is_refused(oil):
    refused(fzg(operation={"oil_temperature": oil}),
            "operation.oil_temperature: ")
    line = refused(fzg(operation={"oil_temperature": oil}), "pour point -15 degC")
    assert "the mineral family's default" in line


def test_a_given_pour_point_and_a_hot_oil():
    """A lubricant's own pour point replaces the family's; an oil so hot that D341's line
    thins it below 2 mm²/s is refused; at the pour point the case is read."""
    parse_case(fzg(operation={"oil_temperature": "-25 degC"},
                   lubricant={"pour_point": "-27 degC"}))
    refused(fzg(operation={"oil_temperature": "-30 degC"}, lubricant={"pour_point": "-27 degC"}),
            "the lubricant.pour_point given")
    refused(fzg(operation={"oil_temperature": "300 degC"}),
            "operation.oil_temperature: 300 degC gives the oil a viscosity of 0.9951")
    parse_case(fzg(operation={"oil_temperature": "-15 degC"}))


@pytest.mark.parametrize("table, amount, says", [
    ("helix_slope", "1 m", "turns the flank by up to 71.4 rad"),
    ("helix_slope", "500 mm", "turns the flank by up to 35.7 rad"),
    ("profile_slope", "50 mm", "turns the flank by up to 2.27 rad"),
    ("crown", None, "turns the flank by up to 0.612 rad"),
    ("profile_slope", "0.5 mm", "reaches ±0.25 mm over the flank, beyond 0.05 of the normal "
                                "module (0.225 mm)"),
    ("profile_slope", "2 mm", "reaches ±1 mm"), ("twist", "1 mm", "reaches ±0.25 mm"),
    ("twist", "-1 mm", "reaches ±0.25 mm")])
def test_a_modification_larger_than_a_deviation_is_refused(table, amount, says):
    """A modification that turns the flank by more than 0.1 rad (the misalignment's limit),
    or a slope or twist reaching beyond 0.05 normal modules: the helix slope's 1 m over a 14
    mm face divided by zero in the rating before, a profile slope of 0.5 mm in the film, a
    2 mm one and a twist of 1 mm failed in the loaded contact."""
    from toothcontact import gearset

    spec = {"height": "2 mm"} if amount is None else {"amount": amount}
    case = parse_case(fzg(pinion={table: spec}))
    with pytest.raises(ValueError, match=f"pinion.{table}: its drop"):
        gearset.gear_pair(case)
    with pytest.raises(ValueError) as error:
        gearset.gear_pair(case)
    assert says in str(error.value)


@pytest.mark.parametrize("length", [300, 5000])
def test_a_file_name_too_long_is_refused_by_name(length):
    raw = fzg(pinion={"topography": {"file": "x" * (length - 4) + ".csv"}})
    line = refused(raw, "pinion.topography: file: 'xxxx")
    assert f"({length + 2} characters): a file name has at most 255 bytes" in line
    assert len(line) < 200


def quick_run(raw: dict, tmp_path, code: int | None = None) -> dict:
    """`toothcontact run` on the table: its result (the run must keep the promise: a
    complete folder, strict JSON, physical figures, no library warning; exit 0 or 1, or
    `code`)."""
    import json

    tmp_path.mkdir(parents=True, exist_ok=True)
    case = mutations.write_case(raw, tmp_path, "case", "fzg_c_type")
    exit_code, output = mutations.run_cli(case, tmp_path / "out")
    assert mutations.verdict(exit_code, output, tmp_path / "out") is None, output
    assert exit_code in ((0, 1) if code is None else (code,)), output
    return json.loads((tmp_path / "out" / "result.json").read_text())


def test_a_flank_turned_onto_an_edge_is_answered(tmp_path):
    """A 0.45 mm profile slope (the most 0.05 modules allow) turns the pinion's flank onto
    the gear's tip edge: a contact without a relative radius across it (B = 0) had divided
    by zero in the film; now it carries no film and, with ISO's μ, no heat, and the note
    says how many. On the 20/60 pair a 0.3 mm slope puts whole positions off both flanks'
    material: the run is answered with that stage incomplete, saying why in the tool's
    words (it had been 'cannot convert float NaN to integer')."""
    result = quick_run(fzg(pinion={"profile_slope": {"amount": "0.45 mm"}},
                           load={"torque": "200 N*m", "spectrum": []}), tmp_path / "a")
    rows = result["positions"]
    flat = [r for r in rows if r["B_analytic_per_mm"] <= 0 and r["bem_status"] == "solved"]
    assert flat and all(r["lambda"] is None and r["friction_coefficient"] is None
                        for r in flat)
    assert "without a relative radius across them" in result["summary"]["lubrication_note"]
    raw = {**mutations.bundled()["spur_crowned_20_60"], "analysis": dict(QUICK)}
    raw["pinion"] = {**raw["pinion"], "profile_slope": {"amount": "0.3 mm"}}
    result = quick_run(raw, tmp_path / "b", code=4)
    reasons = {r["bem_reason"] for r in result["positions"] if r["bem_status"] == "failed"}
    assert reasons and all(r.startswith("no contact of the position lies on both flanks' "
                                        "material") for r in reasons)
    assert result["summary"]["max_p_max_MPa"] < 1e5


# -- implausible figures refused or bounded ----------------------------------------------

@pytest.mark.parametrize("change, says", [
    ({"lubricant": {"scuffing_temperature": "80 degC"}},
     "lubricant.scuffing_temperature: 80 degC must exceed the oil temperature 90 degC"),
    ({"lubricant": {"scuffing_temperature": "90 degC"}},
     "lubricant.scuffing_temperature: 90 degC must exceed"),
    ({"operation": {"bulk_temperature": "-100 degC"}},
     "operation.bulk_temperature: -100 degC must be at least the oil temperature 90 degC"),
])
def test_s_b_s_temperatures_lie_above_the_oil(change, says):
    refused(fzg(**change), says)


def test_a_worm_sets_bulk_lies_above_its_oil():
    raw = tomllib.loads((mutations.CASES / "worm_eps_oversized_hob.toml").read_text())
    raw["operation"] = {**raw["operation"], "bulk_temperature": "-100 degC"}
    refused(raw, "operation.bulk_temperature: -100 degC must be at least the oil temperature")


def test_iso_tr_14179_2s_friction_at_a_crawl_needs_a_given_one():
    """At 1e-6 rpm ISO/TR 14179-2's μ came out 3.5 and the efficiency 0.39: below the sum
    speed it is taken from, a case gives its friction coefficient, refused before the
    contact is solved; a computed μ is held in (0, 1)."""
    from toothcontact.analyses import analyse
    from toothcontact.analytic.mesh_losses import SUM_VELOCITY_LEAST, friction_coefficient

    with pytest.raises(CaseError, match="operation.pinion_speed: 1e-06 rpm runs the flanks at "
                                        "a sum speed of 2.93e-09 m/s"):
        analyse(parse_case(fzg(operation={"pinion_speed": "1e-6 rpm"})))
    assert 0 < friction_coefficient(400.0, SUM_VELOCITY_LEAST, 10.0, 10.0, 0.3, 1.0) < 1


def test_the_flash_temperature_of_a_vanishing_friction_vanishes():
    """A flux of 1e-288 W/m² (μ = 1e-300) made the heat's mean direction's norm underflow to
    zero and the flash temperature infinite; it is linear in the flux."""
    from toothcontact.contact.flash import flash_temperature

    x = np.linspace(-1.0, 1.0, 41)
    flux = np.outer(np.maximum(1 - x ** 2, 0), np.ones(41)) * 1e9
    bodies = ((lambda X, Y: (5.0 + 0 * X, 0 * Y), 12e3), (lambda X, Y: (3.0 + 0 * X, 0 * Y), 12e3))
    hot = flash_temperature(flux, x, x, bodies)
    cold = flash_temperature(flux * 1e-300, x, x, bodies)
    assert math.isfinite(cold) and cold == pytest.approx(hot * 1e-300, rel=1e-9)


def test_s_b_is_not_limiting_where_the_flash_vanishes(tmp_path):
    """A friction of 1e-300 with θ_S 300 °C: S_B tends to infinity (the flash temperature to
    zero); it had read 0.00 and failed its check. Now it is none with a note, the check
    passes; an oil at -10 °C (below D341's 40-100 °C) is noted as extrapolated."""
    result = quick_run(fzg(lubricant={"friction_coefficient": 1e-300,
                                      "scuffing_temperature": "300 degC"},
                           operation={"oil_temperature": "-10 degC"},
                           load={"torque": "200 N*m", "spectrum": []}), tmp_path)
    summary = result["summary"]
    assert summary["S_B"] is None and summary["S_B_note"].startswith("not limiting")
    assert summary["flash_temperature_max_K"] == pytest.approx(0.0, abs=1e-200)
    check = next(c for c in result["checks"] if c["name"] == "scuffing safety S_B at least 1")
    assert check["ok"]
    assert result["lubrication"]["viscosity_extrapolated"]
    assert "extrapolated beyond 40-100 °C" in summary["lubrication_note"]


# -- bad input refused naming the field --------------------------------------------------

@pytest.mark.parametrize("change, says", [
    ({"load": {"torque": "200 N*m", "spectrum": [{"torque": "120 N*m", "cycles": math.inf}]}},
     "load.spectrum[0].cycles: inf: Input should be a finite number"),
    ({"load": {"torque": "200 N*m", "spectrum": [{"torque": "120 N*m", "cycles": 2.5}]}},
     "load.spectrum[0].cycles: 2.5 is no whole number of cycles"),
    ({"rating": {"pinion_cycles": math.inf}}, "rating.pinion_cycles: inf"),
    ({"rating": {"pinion_cycles": math.nan}}, "rating.pinion_cycles: nan"),
    ({"load": {"torque": "200\x00 N*m"}}, "load.torque: '200\\x00 N*m' holds control character "
                                          "U+0000"),
])
def test_counts_are_finite_and_whole_and_quantities_printable(change, says):
    refused(fzg(**change), says)


@pytest.mark.parametrize("table, key", [
    ("rating", "application_factor"), ("rating", "dynamic_factor"), ("rating", "S_Hmin"),
    ("rating", "pinion_cycles"), ("lubricant", "permissible_specific_film"),
    ("pinion", "profile_shift")])
def test_a_switch_is_never_a_number(table, key):
    refused(fzg(**{table: {key: True}}),
            f"{table}.{key}: True is a switch (true or false) where a number")


def test_a_switch_in_a_list_or_a_spectrum_level():
    refused(fzg(teeth=[True, 24]), "teeth: [True, 24] holds a switch")
    refused(fzg(load={"torque": "200 N*m", "spectrum": [{"torque": "120 N*m", "cycles": True}]}),
            "load.spectrum[0].cycles: True is a switch")


# -- sweeps: legal offset units, bad input refused, refusals that name -------------------

def sweep_file(tmp_path, name: str, **changes) -> Path:
    raw = {**mutations.bundled_sweeps()[name], **changes}
    path = tmp_path / f"{name}.toml"
    path.write_text(tomli_w.dumps({k: v for k, v in raw.items() if v is not None}))
    return path


def planned(path):
    from toothcontact.runner import load_sweep
    from toothcontact.sweep.sampling import plan

    spec, base, base_path = load_sweep(path)
    return plan(spec, base, base_path.parent, source=str(path))


def test_a_tolerance_in_degc_is_read_as_a_temperature(tmp_path):
    """'80 degC' was 'not a number with a unit' (pint's Quantity reads an offset unit only
    apart from its number); its spread of '5 degC' is 5 K, not -268 degC."""
    samples = planned(sweep_file(tmp_path, "spur_crown_tolerance", base="fzg_c_type",
                                 optimise=None, spectrum=None, tolerance=[
                                     {"field": "operation.oil_temperature",
                                      "distribution": "normal", "mean": "80 degC",
                                      "std": "5 degC"},
                                     {"field": "lubricant.scuffing_temperature",
                                      "distribution": "uniform", "low": "300 degF",
                                      "high": "450 K"}]))
    oil = np.array([s.case.operation.oil_temperature for s in samples])
    scuffing = np.array([s.case.lubricant.scuffing_temperature for s in samples])
    assert 60 < oil.min() and oil.max() < 100 and 1 < oil.std() < 10
    assert (148.8 < scuffing).all() and (scuffing < 176.9).all()


@pytest.mark.parametrize("name, change, says", [
    ("helical_quality_class", lambda r: r["tolerance"][0].update(iso1328_class=True),
     "tolerance[0].iso1328_class: True is a switch"),
    ("spur_crown_tolerance", lambda r: r["optimise"]["constraint"][0].update(max=math.nan),
     "optimise.constraint[0].max: nan: Input should be a finite number"),
    ("spur_crown_tolerance", lambda r: r["tolerance"][0].update(std="0"),
     "tolerance[0].std: '0' must be greater than zero (the normal's spread)"),
    ("helical_quality_class", lambda r: r["tolerance"][2].update(low="nan"),
     "tolerance[2].low: 'nan' is not a number with a unit"),
    ("helical_quality_class", lambda r: r["tolerance"][2].update(high="inf"),
     "tolerance[2].high: 'inf' is not a finite number"),
    ("helical_quality_class", lambda r: r["tolerance"][0].update(mean="nan um"),
     "tolerance[0] (pinion.helix_slope.amount).mean: 'nan um'"),
    ("spur_crown_tolerance", lambda r: r.update(
        base=str(mutations.CASES / "sweeps" / "spur_harris_map.toml")),
     "base: '/"),
])
def test_a_bad_sweep_is_refused_naming_what_was_written(tmp_path, name, change, says):
    raw = mutations.bundled_sweeps()[name]
    change(raw)
    path = tmp_path / "sweep.toml"
    path.write_text(tomli_w.dumps(raw))
    with pytest.raises(CaseError) as error:
        planned(path)
    assert says in str(error.value), str(error.value)
    if "base" in says:
        assert "is a sweep file; give a case file" in str(error.value)


def test_an_unknown_objective_names_at_most_a_dozen_figures():
    from toothcontact.sweep.optimise import NEAREST, check_statistics
    from toothcontact.sweep.spec import Optimise

    spec = Optimise.model_validate({"variable": [{"field": "a", "low": "1 mm", "high": "2 mm"}],
                                    "objective": "P95 bem_max_p_max_mpa"})
    figures = {f"figure_{i}_MPa": 1.0 for i in range(80)} | {"bem_max_p_max_MPa": 1.0}
    with pytest.raises(CaseError) as error:
        check_statistics(spec, figures, "optimise")
    message = str(error.value)
    assert "'bem_max_p_max_mpa' is not a figure" in message
    assert "the nearest of the 81 figures: bem_max_p_max_MPa" in message
    assert message.count("figure_") <= NEAREST and len(message) < 600


# -- refusals that name what the user wrote ---------------------------------------------

def csv_refusal(tmp_path, name: str) -> str:
    raw = tomllib.loads((mutations.CASES / "helical_measured_topography.toml").read_text())
    raw["pinion"]["topography"]["file"] = name
    mutations.write_case(raw, tmp_path, "case", "helical_measured_topography")
    return refused(raw, f"pinion.topography: file: {name}", base=tmp_path)


@pytest.mark.parametrize("name, says", [
    ("bad_nan.csv", "row 4, column 1: 'nan' is not a finite number"),
    ("bad_ragged.csv", "row 5: 7 deviations after the face position; the header gives 9"),
    ("bad_latin1.csv", "not UTF-8 text (byte 0xe4 at position 2); save the CSV as UTF-8"),
])
def test_a_topography_csvs_problem_names_its_file_row_and_column(tmp_path, name, says):
    assert says in csv_refusal(tmp_path, name)


def test_a_spectrum_level_that_fails_is_named():
    """A level whose contact cannot be found is refused naming the level and its load
    (it was the main load's 'misalignment / load' line)."""
    from toothcontact.analyses import rating
    from toothcontact.analyses.result import Result

    case = parse_case(fzg())

    def run_level(level, scratch):
        raise CaseError("misalignment / load: no contact could be found: no line")

    with pytest.raises(CaseError, match=r"load.spectrum\[0\]: at its torque 120000 N\*mm: "
                                        "misalignment / load: no contact could be found"):
        rating.duty_cycle_sections(case, Result(), run_level)


# -- the large legal pair -----------------------------------------------------------------

def test_a_large_pairs_loaded_mesh_keeps_a_pair_far_apart():
    """The FZG pair scaled to m = 40 mm and a 400 mm face at 1e6 N: the loaded contact
    keeps tooth pairs up to 3 single-pair approaches apart (1.1 mm), and one stood 0.66
    mm off at a position of 21: its contact line's field took no hit farther than 0.5 mm
    from the plane and met no flank, so the case was refused ('no contact could be found').
    The field now follows a flank that stands off by its own height at the contact."""
    from toothcontact import gearset
    from toothcontact.analyses.spur import contact_cycle
    from toothcontact.contact.field import FAR

    raw = fzg(module="40 mm", face_width="400 mm", load={"tangential_load": "1e6 N"},
              analysis={**QUICK, "positions": 21})
    for member in ("pinion", "gear"):
        raw[member] = {k: v for k, v in raw[member].items() if k != "tip_diameter"}
    raw.pop("center_distance")
    case = parse_case(raw)
    _, cycle, _ = contact_cycle(case, gearset.gear_pair(case))
    far = [r for r in cycle.rows if r["separation_mm"] > FAR]
    assert far and not any(r["rigid_contact"] for r in far)
