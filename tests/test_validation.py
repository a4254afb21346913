"""Bad input gets one line naming the field, exit 2 and nothing written; legal input a
complete strict-JSON result (issue 12: each input the fuzz found, as a test)."""

import copy
import math
import tomllib

import pytest
import tomli_w
from documents import strict_json
from typer.testing import CliRunner

from toothcontact.cli import app
from toothcontact.runner import bundled_cases_dir

SMALL = {"positions": 3, "grid": [9, 15], "field_grid": 41, "pressure_grid": 32,
         "interference": False, "positions_check": False}


def bundled(name: str) -> dict:
    return tomllib.loads((bundled_cases_dir() / f"{name}.toml").read_text())


def edited(name: str, changes: dict, small: bool = True) -> dict:
    """A bundled case with dotted-path `changes` (value None deletes)."""
    raw = copy.deepcopy(bundled(name))
    if small and raw["kind"] in ("spur", "spline", "worm"):
        raw["analysis"] = {**SMALL, **raw.get("analysis", {}), **{
            k: v for k, v in SMALL.items() if k != "positions"}}
    for path, value in changes.items():
        *parents, last = path.split(".")
        table = raw
        for key in parents:
            table = table.setdefault(key, {})
        if value is None:
            table.pop(last, None)
        else:
            table[last] = value
    return raw


def run(raw: dict, tmp_path):
    case = tmp_path / "case.toml"
    case.write_text(tomli_w.dumps(raw))
    out = tmp_path / "out"
    result = CliRunner().invoke(app, ["run", str(case), "--out", str(out), "--no-pictures"])
    return result, out


HELICAL = {"kind": "spur", "teeth": [27, 71], "module": "2.5 mm", "pressure_angle": "20 deg",
           "helix_angle": "15 deg", "face_width": "40 mm", "load": {"torque": "300 N*m"},
           "analysis": SMALL}

REFUSED = [
    ("hertz_ball_in_race", {"body1.radii": ["0 mm", "6.35 mm"]}, "body1.radii[0]"),
    ("hertz_ball_in_race", {"body1.radii": ["1e-400 mm", "6.35 mm"]}, "body1.radii[0]"),
    ("hertz_ball_in_race", {"load": "1e300 N"}, "load: '1e300 N'"),
    ("hertz_ball_in_race", {"body2.E": "1e-300 MPa"}, "body2.E"),
    ("crown_spur_metric_bias", {"slope_A": "1"}, "slope_A: '1'"),
    ("crown_example3_sector_check", {"radius": "1e-9 in"}, "radius"),
    ("crown_example3_sector_check", {"radius": "0.3 in"}, "radius / center_from_B / face_width"),
    ("crown_spur_metric_bias", {"edge_clearance": "20 mm"}, "edge_clearance / face_width"),
    ("spur_crowned_20_60", {"pinion.crown.radius": "4 mm"}, "pinion.crown.radius: 4 mm"),
    ("spline_crowned_18t", {"crown.radius": "5 mm"}, "crown.radius: 5 mm"),
    ("spline_crowned_18t", {"tooth_thickness": "0.049 mm"}, "tooth_thickness: 0.049 mm"),
    ("spur_crowned_20_60", {"analysis.grid": [0, 0]}, "analysis.grid"),
    ("spur_crowned_20_60", {"analysis.grid": [1, 1]}, "analysis.grid"),
    ("spur_crowned_20_60", {"analysis.grid": [3, 1000000]}, "analysis.grid"),
    ("spur_crowned_20_60", {"teeth": [5, 60]}, "pinion.profile_shift"),
    ("worm_kim_steering_ars", {"mu_zm": 20}, "mu_zm"),
    ("spur_crowned_20_60", {"pinion.profile_shift": 1.5}, "pinion.profile_shift: 1.5"),
    ("spur_crowned_20_60", {"pinion.profile_shift": -1.5}, "pinion.profile_shift"),
    ("spur_crowned_20_60", {"misalignment.slope": math.nan}, "misalignment.slope"),
    ("spur_crowned_20_60", {"misalignment.slope": math.inf}, "misalignment.slope"),
    ("spur_crowned_20_60", {"pinion.crown.radius": "1e200 mm"}, "pinion.crown.radius"),
    ("spur_crowned_20_60", {"module": "1e300 mm"}, "module"),
    ("spur_crowned_20_60", {"center_distance": "1e-3 mm"}, "center_distance"),
    ("worm_eps_oversized_hob", {"worm.length": "1e300 mm"}, "worm.length"),
    ("worm_eps_oversized_hob", {"worm.pressure_angle": "0.02 deg"}, "worm.pressure_angle"),
    ("worm_eps_oversized_hob", {"misalignment.worm_tilt": math.nan},
     "misalignment.worm_tilt"),
    ("imported_peer_uncrowned_20_60", {"base_helix_angle": "90 deg"}, "base_helix_angle"),
    ("imported_peer_uncrowned_20_60", {"center_distance": "1e-3 mm"}, "center_distance"),
]


@pytest.mark.parametrize("name,changes,field", REFUSED,
                         ids=[f"{n}:{'/'.join(c)}={list(c.values())[0]}" for n, c, _ in REFUSED])
def test_refused_with_one_line_naming_the_field(tmp_path, name, changes, field):
    raw = edited(name, changes)
    if raw["kind"] == "imported":
        for member in ("pinion", "gear"):
            raw[member]["file"] = str((bundled_cases_dir() / raw[member]["file"]).resolve())
    result, out = run(raw, tmp_path)
    lines = result.output.strip().splitlines()
    assert result.exit_code == 2, result.output
    assert len(lines) == 1 and field in lines[0], result.output
    assert not out.exists()


def test_conditions_out_of_their_physical_range(tmp_path):
    """Below absolute zero, an efficiency above 1, a friction above 1: refused."""
    for changes, field in (({"temperature": "-500 degF"}, "temperature"),
                           ({"eta_spindle": 5.0}, "eta_spindle")):
        raw = {"kind": "worm_efficiency", "starts": 1, "teeth": 40, "normal_module": "2 mm",
               "lead_angle": "5 deg", "normal_pressure_angle": "20 deg",
               "din3996": {"mu_0T": 0.047},
               "conditions": [{"temperature": "40 degC", "viscosity": "220 mm^2/s",
                               **changes}]}
        result, _ = run(raw, tmp_path)
        assert result.exit_code == 2 and f"conditions[0].{field}" in result.output, \
            result.output


def test_a_helical_pair_pulled_apart_is_refused_not_given_a_negative_contact_ratio(tmp_path):
    """Standard centre 127.0 mm; at 137 mm the tips no longer reach across the line of
    action (its contact ratio was written as -1.48)."""
    result, out = run({**HELICAL, "center_distance": "137.3 mm"}, tmp_path)
    assert result.exit_code == 2, result.output
    assert result.output.startswith("error: ") and "center_distance" in result.output
    assert not out.exists()


def test_a_tiny_load_on_a_worm_set_is_answered(tmp_path):
    """1e-9 N·m on the wheel (a broadcast error before): a complete strict-JSON result. The
    loaded contact, nanometres across, may find no line of its field meeting both flanks:
    then its rows say why and the run exits 4 (incomplete), never with a traceback."""
    raw = edited("worm_eps_oversized_hob", {"load.output_torque": "1e-9 N*m"})
    result, out = run(raw, tmp_path)
    assert result.exit_code in (0, 1, 4), result.output
    document = strict_json((out / "result.json").read_text())
    assert document["positions"]


def test_a_crown_radius_as_large_as_allowed_gives_finite_tiny_drops(tmp_path):
    """A 1e9 mm crown over a 30 mm face drops 15²/(2e9) = 1.125e-7 mm at each end (the
    closed form; R - sqrt(R² - L²) lost it to cancellation)."""
    raw = edited("spur_crowned_20_60", {"pinion.crown.radius": "1e9 mm", "load": None})
    result, out = run(raw, tmp_path)
    assert result.exit_code in (0, 1), result.output
    pinion = strict_json((out / "result.json").read_text())["pinion"]
    for end in "AB":
        assert pinion[f"crown_drop_{end}_mm"] == pytest.approx(15.0 ** 2 / 2e9, rel=1e-9)


def imported_with(tmp_path, member: str, path) -> dict:
    raw = bundled("imported_peer_uncrowned_20_60")
    for name in ("pinion", "gear"):
        raw[name]["file"] = str((bundled_cases_dir() / raw[name]["file"]).resolve())
    raw[member]["file"] = str(path)
    raw["analysis"] = {"positions": 3}
    return raw


HEADER_ONLY_STEP = """ISO-10303-21;
HEADER;
FILE_DESCRIPTION(('empty'),'2;1');
FILE_NAME('empty.step','2026-01-01T00:00:00',(''),(''),'','','');
FILE_SCHEMA(('AUTOMOTIVE_DESIGN { 1 0 10303 214 1 1 1 1 }'));
ENDSEC;
DATA;
ENDSEC;
END-ISO-10303-21;
"""


def test_a_step_file_without_a_body_is_named(tmp_path):
    step = tmp_path / "empty.step"
    step.write_text(HEADER_ONLY_STEP)
    result, out = run(imported_with(tmp_path, "pinion", step), tmp_path)
    assert result.exit_code == 2, result.output
    assert "pinion.file" in result.output and "holds no solid" in result.output, result.output
    assert not out.exists()


@pytest.mark.parametrize("shape", ["box", "cylinder"])
def test_a_body_that_is_not_a_gear_is_named(tmp_path, shape):
    from OCP.BRepPrimAPI import BRepPrimAPI_MakeBox, BRepPrimAPI_MakeCylinder
    from OCP.gp import gp_Pnt

    from toothcontact import cad

    solid = (BRepPrimAPI_MakeBox(gp_Pnt(-30, -30, 0), 60, 60, 30).Shape() if shape == "box"
             else BRepPrimAPI_MakeCylinder(33.0, 30.0).Shape())
    step = cad.write_step(solid, tmp_path / f"{shape}.step")
    result, out = run(imported_with(tmp_path, "pinion", step), tmp_path)
    assert result.exit_code == 2, result.output
    assert "pinion.teeth" in result.output and "no gear of 20 teeth" in result.output
    assert not out.exists()


def test_an_imported_tooth_count_that_the_body_does_not_show_is_named(tmp_path):
    """A 20-tooth pinion declared with 40 teeth (a TE of 52,000 µrad before)."""
    raw = imported_with(tmp_path, "gear", bundled("imported_peer_uncrowned_20_60")["gear"]["file"])
    raw["gear"]["file"] = str((bundled_cases_dir() / raw["gear"]["file"]).resolve())
    raw["pinion"]["teeth"] = 40
    result, out = run(raw, tmp_path)
    assert result.exit_code == 2 and "pinion.teeth: 40" in result.output, result.output


def test_a_partial_analysis_table_keeps_the_kinds_own_defaults():
    """A spline with only `pressure_grid` given keeps its 3 positions and 9 × 41 grid (it
    fell back to the generic 21 positions: 378 contacts, over a minute); a worm set its
    11 × 121 grid."""
    from toothcontact.case import parse_case

    spline = parse_case(edited("spline_crowned_18t", {"analysis": {"pressure_grid": 64}},
                               small=False))
    assert (spline.analysis.positions, spline.analysis.grid) == (3, (9, 41))
    assert spline.analysis.pressure_grid == 64
    worm = parse_case(edited("worm_saba_set", {"analysis": {"positions": 3}}, small=False))
    assert (worm.analysis.positions, worm.analysis.grid) == (3, (11, 121))
