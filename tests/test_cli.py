"""The console script as a user meets it: bundled cases run, bad input gets one line."""

from pathlib import Path

import pytest
from documents import complete_run
from typer.testing import CliRunner

from toothcontact.cli import app
from toothcontact.runner import bundled_cases

runner = CliRunner()


#: the bundled cases `run` is tested on here: each kind's (the spur kind's lightest), the
#: worm set with a load, the imported pair; the installed `demo` runs every bundled case
#: and checks each folder the same way (test_install), so the heavy spur variants (the FZG
#: pair, the measured topography, the shaft, ...) are not run twice in CI
RUN_CASES = ("spur_crowned_20_60", "spline_crowned_18t", "spline_crown_torque_tube",
             "worm_eps_oversized_hob", "worm_saba_set", "worm_kim_steering_ars",
             "imported_spur_crowned_20_60", "hertz_sphere_on_flat", "crown_example1_planet_bias")


def test_the_run_cases_are_bundled_and_cover_every_kind():
    """RUN_CASES names bundled cases, one of each kind among them."""
    import tomllib

    bundled = {p.stem: tomllib.loads(p.read_text())["kind"] for p in bundled_cases()}
    assert set(RUN_CASES) <= set(bundled)
    assert {bundled[name] for name in RUN_CASES} == set(bundled.values())


@pytest.mark.parametrize("case", [p for p in bundled_cases() if p.stem in RUN_CASES],
                         ids=lambda p: p.stem)
def test_a_bundled_case_runs(case, tmp_path):
    """Exit 0, or 1 exactly when a design check failed (a source's inconsistent numbers are
    a note, not a failed design); the folder complete (documents.complete_run) and nothing
    else written. Without the 3D pictures: the demo renders every bundled case's
    (test_install) and test_render looks at them."""
    out = tmp_path / "out"
    result = runner.invoke(app, ["run", str(case), "--out", str(out), "--no-pictures"])
    assert result.exit_code in (0, 1), result.output
    document = complete_run(out)
    failed = [c for c in document["checks"] if not c["ok"] and c["kind"] == "design"]
    assert result.exit_code == (1 if failed else 0)
    assert [p.name for p in tmp_path.iterdir()] == ["out"]


def test_cases_lists_the_bundled_cases():
    result = runner.invoke(app, ["cases"])
    assert result.exit_code == 0
    assert all(c.stem in result.output for c in bundled_cases())


GOOD_HERTZ = """kind = "hertz"
load = "1000 N"
[body1]
radii = ["12.7 mm", "12.7 mm"]
E = "206 GPa"
nu = 0.3
[body2]
radii = ["inf", "inf"]
E = "206 GPa"
nu = 0.3
"""


@pytest.mark.parametrize("text,field", [
    (GOOD_HERTZ.replace('load = "1000 N"\n', ""), "load: missing"),
    (GOOD_HERTZ.replace('"1000 N"', '"1000 mm"'), "load: '1000 mm' is not a force"),
    (GOOD_HERTZ.replace('"1000 N"', '"-1000 N"'), "load: '-1000 N' must be greater than zero"),
    (GOOD_HERTZ.replace('"1000 N"', '"lots"'), "load: 'lots' does not start with a number"),
    (GOOD_HERTZ.replace('"hertz"', '"bevel"'), "kind: 'bevel' is not a known kind"),
    (GOOD_HERTZ.replace('nu = 0.3\n[body2]', 'nu = 0.7\n[body2]'), "body1.nu: 0.7"),
    (GOOD_HERTZ.replace('"inf", "inf"', '"-10 mm", "-10 mm"'), "body1.radii / body2.radii"),
    (GOOD_HERTZ.replace('load =', 'lode = "1 N"\nload ='), "lode: unknown field"),
    (GOOD_HERTZ.replace('[body1]', '[body1'), "not valid TOML"),
])
def test_bad_input_gets_one_line_naming_the_field(tmp_path, text, field):
    case = tmp_path / "bad.toml"
    case.write_text(text)
    out = tmp_path / "out"
    result = runner.invoke(app, ["run", str(case), "--out", str(out)])
    assert result.exit_code == 2
    lines = result.output.strip().splitlines()
    assert len(lines) == 1 and field in lines[0], result.output
    assert "Traceback" not in result.output
    assert not out.exists()


def test_negative_face_width_in_a_crown_case(tmp_path):
    case = tmp_path / "crown.toml"
    source = (Path(__file__).parents[1] / "cases" / "crown_spur_metric_bias.toml").read_text()
    case.write_text(source.replace('"30 mm"', '"-30 mm"'))
    result = runner.invoke(app, ["run", str(case), "--out", str(tmp_path / "o")])
    assert result.exit_code == 2
    assert "face_width: '-30 mm' must be greater than zero" in result.output


def test_missing_case_file(tmp_path):
    result = runner.invoke(app, ["run", str(tmp_path / "nope.toml")])
    assert result.exit_code == 2 and "no such case file" in result.output


def test_impossible_geometry_names_the_file_and_fields(tmp_path):
    case = tmp_path / "crown.toml"
    source = (Path(__file__).parents[1] / "cases" / "crown_spur_metric_bias.toml").read_text()
    case.write_text(source.replace("teeth = [20, 60]", "teeth = [12, 120]"))
    result = runner.invoke(app, ["run", str(case), "--out", str(tmp_path / "o")])
    assert result.exit_code == 2
    assert "crown.toml: teeth / module / pressure_angle / outside radii:" in result.output
    assert "interference" in result.output


def test_help_does_not_import_the_heavy_stack(fresh_python):
    code = ("import sys; from toothcontact.cli import app\n"
            "try:\n    app(['--help'])\nexcept SystemExit:\n    pass\n"
            "heavy = {'cadquery', 'pyvista', 'vtk', 'OCP', 'scipy', 'pint', 'matplotlib'}\n"
            "print(sorted(heavy & set(sys.modules)))")
    assert fresh_python(code) == "[]"


def test_the_demo_names_a_pairs_kind_as_built():
    """The demo table's kind: helical or spur from the base helix angle, ring for an
    internal gear, the case kind in words otherwise."""
    from toothcontact.cli import case_kind

    def spur(helix, internal=None):
        return {"kind": "spur", "pinion": {"base_helix_angle_deg": helix},
                "gear": {"internal": internal}}

    assert case_kind(spur(0.0)) == "spur"
    assert case_kind(spur(18.75)) == "helical"
    assert case_kind(spur(0.0, True)) == "spur ring"
    assert case_kind(spur(-14.1, True)) == "helical ring"
    assert case_kind({"kind": "worm_efficiency"}) == "worm efficiency"
    assert case_kind({"kind": "spline"}) == "spline"
