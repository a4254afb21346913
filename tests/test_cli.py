"""The console script as a user meets it: bundled cases run, bad input gets one line."""

import json
from pathlib import Path

import pytest
from typer.testing import CliRunner

from toothcontact.cli import app
from toothcontact.runner import bundled_cases

runner = CliRunner()


def strict_json(text: str):
    """Parse RFC 8259 JSON: NaN, Infinity and -Infinity are refused."""
    def refuse(constant):
        raise ValueError(f"{constant} is not JSON")
    return json.loads(text, parse_constant=refuse)


@pytest.mark.parametrize("case", bundled_cases(), ids=lambda p: p.stem)
def test_every_bundled_case_runs(case, tmp_path):
    """Exit 0, or 1 exactly when a design check failed (a source's inconsistent numbers are
    a note, not a failed design); result.json is strict JSON; every check says its kind.
    Without the 3D pictures: the demo renders every bundled case's (test_install) and
    test_render looks at them."""
    out = tmp_path / "out"
    result = runner.invoke(app, ["run", str(case), "--out", str(out), "--no-pictures"])
    assert result.exit_code in (0, 1), result.output
    document = strict_json((out / "result.json").read_text())
    assert all(c["kind"] in ("design", "source", "method", "solver") for c in document["checks"])
    page = (out / "report.html").read_text()     # the report opens with its key results
    assert page.index('id="key-results"') < page.index('id="design-checks"')
    failed = [c for c in document["checks"] if not c["ok"] and c["kind"] == "design"]
    assert result.exit_code == (1 if failed else 0)
    assert document["kind"] and document["source"]
    assert (out / "report.md").read_text().startswith("# ")
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
