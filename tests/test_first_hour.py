"""A new user's first hour (issue 28): what the fuzzer and a first session found, each
refused in one line naming the field (exit 2, nothing written) or read as meant."""

import pytest
from typer.testing import CliRunner

import mutations
from test_cli import GOOD_HERTZ

from toothcontact.cli import app
from toothcontact.units import parse

HERTZ = GOOD_HERTZ

SLENDER_WORM = """kind = "worm"
[worm]
form = "ZI"
starts = 1
normal_module = "1 mm"
lead_angle = "{lead}"
pressure_angle = "20 deg"
length = "20 mm"
[wheel]
teeth = 30
[load]
output_torque = "5 N*m"
flank = "left"
"""


def refused(tmp_path, text: str) -> str:
    return mutations.refused_line(text, tmp_path)


def test_a_kind_that_is_not_a_name_is_refused(tmp_path):
    """kind = ["spur"] ended in "internal error: TypeError: unhashable type" (exit 3)."""
    line = refused(tmp_path, HERTZ.replace('kind = "hertz"', 'kind = ["spur"]'))
    assert "kind: ['spur'] is not a known kind; allowed: hertz" in line


@pytest.mark.parametrize("where", ["load", "assumptions"])
def test_arrays_nested_thousands_deep_are_refused(tmp_path, where):
    """Arrays nested 5,000 deep (a value, or inside assumptions) ended in "internal error:
    RecursionError" (exit 3)."""
    deep = "[" * 5000 + "1" + "]" * 5000
    text = (HERTZ.replace('load = "1000 N"', f"load = {deep}") if where == "load"
            else f"assumptions = {deep}\n" + HERTZ)
    assert "nested more than 16 deep" in refused(tmp_path, text)


def test_a_huge_value_is_not_echoed_whole(tmp_path):
    """A 10 MB number and a unit thousands of characters long were echoed whole into the
    message: it shows 60 characters and says how long the value was."""
    line = refused(tmp_path, HERTZ.replace('"1000 N"', '"1' + "0" * 10**6 + ' N"'))
    assert len(line) < 400 and "(1000005 characters)" in line and "load" in line
    line = refused(tmp_path, HERTZ.replace('"1000 N"', '"1000 ' + "N*" * 3000 + 'N"'))
    assert len(line) < 400 and "load" in line


def test_a_key_given_twice_is_named(tmp_path):
    """A duplicate key was refused as "Cannot overwrite a value (at line 2, column 14)"
    without naming it."""
    line = refused(tmp_path, HERTZ.replace('load = "1000 N"', 'load = "1000 N"\nload = "2 kN"'))
    assert "'load' is given twice" in line


def test_a_sweeps_missing_base_names_the_field(tmp_path):
    """A sweep whose base is neither a file nor a bundled case said "no such case file"
    without naming `base`."""
    sweep = tmp_path / "sweep.toml"
    sweep.write_text('kind = "sweep"\nbase = "no_such_case"\nsamples = 4\n'
                     '[[tolerance]]\nfield = "load"\ndistribution = "uniform"\n'
                     'low = "900 N"\nhigh = "1100 N"\n')
    result = CliRunner().invoke(app, ["sweep", str(sweep), "--out", str(tmp_path / "out")])
    assert result.exit_code == 2, result.output
    assert "base: 'no_such_case' is neither a case file" in result.output


@pytest.mark.parametrize("lead, q", [("17.1 deg", "3.25"), ("14 deg", "4.01")])
def test_a_slender_worm_says_why_it_has_no_contact(tmp_path, lead, q):
    """A single-start ZI worm, m_n = 1 mm, lead angle 17.1 deg (d1 3.4 mm), ended in "no
    line of the gap field meets both flanks", and at 14 deg answered 343,845 MPa without a
    word: its base cylinder, where a ZI flank starts, lies above the diameter the wheel's
    tips reach, so they run where the worm has no flank and the contact found is the
    flank's lower edge. Both are refused before the contact is sought (it was refused only
    where the search happened to fail at a position), naming the lead angle, the starts
    and the diameter quotient."""
    line = refused(tmp_path, SLENDER_WORM.format(lead=lead))
    assert "worm.lead_angle / worm.starts" in line
    assert f"diameter quotient q = d1/m_x = {q}" in line
    assert "the wheel's tips reach below the flanks" in line


def test_newton_metres_as_gear_engineers_write_them():
    """"180 Nm" was read by pint as nanometres and refused where a torque is expected."""
    assert parse("180 Nm", "torque") == pytest.approx(180e3)        # N·mm
    assert parse("1.2 kNm", "torque") == pytest.approx(1.2e6)
    assert parse("500 Nmm", "torque") == pytest.approx(500.0)
    assert parse("180 N m", "torque") == pytest.approx(180e3)
    with pytest.raises(ValueError):
        parse("3 Nm", "length")                # still nanometres' refusal where a length is


def test_the_case_listing_off_a_terminal_is_one_line_per_entry():
    """`toothcontact cases` piped or captured printed a box table that folded long paths;
    off a terminal it prints one tab-separated line per case: name, kind, title, path."""
    result = CliRunner().invoke(app, ["cases"])
    assert result.exit_code == 0
    lines = result.output.splitlines()
    spur = next(line for line in lines if line.startswith("spur_crowned_20_60\t"))
    name, kind, _, path = spur.split("\t")
    assert kind == "spur" and path.endswith("spur_crowned_20_60.toml")
    assert not any(c in result.output for c in "┃│━")


def test_a_mistyped_case_name_gets_a_suggestion(tmp_path):
    result = CliRunner().invoke(app, ["run", "spur_crowned_20_06", "--out", str(tmp_path / "o")])
    assert result.exit_code == 2
    assert "did you mean spur_crowned_20_60?" in result.output
