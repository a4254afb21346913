"""report.md read as a Markdown viewer reads it (markdown-it-py, CommonMark with GFM
tables): every table of a bundled case's report whole (its header and every row, no row
left as a paragraph of raw pipes), labels and units from the table of quantities (no unit
words left in a label, no raw Python lists), the members named as the kind names them, and
the traceability block (version, time, case file and its SHA-256, command)."""

import hashlib
import json
import tomllib
from pathlib import Path

import pytest
import tomli_w
from markdown_it import MarkdownIt
from typer.testing import CliRunner

from toothcontact.cli import app
from toothcontact.views.labels import label, number

CASES = Path(__file__).parent.parent / "cases"

#: bundled cases of every kind, run with few positions and no pictures
QUICK = {"hertz_ball_in_race": None, "crown_example1_planet_bias": None,
         "spline_crown_torque_tube": None, "worm_saba_set": None,
         "worm_kim_steering_ars": None,
         "spur_crowned_20_60": {"positions": 3, "pressure_grid": 64},
         "worm_eps_oversized_hob": {"positions": 3, "pressure_grid": 64}}


@pytest.fixture(scope="module")
def reports(tmp_path_factory) -> dict[str, tuple[str, dict, Path]]:
    """Each quick case's report.md text, result document and case file."""
    folder = tmp_path_factory.mktemp("reports")
    out = {}
    for name, analysis in QUICK.items():
        raw = tomllib.loads((CASES / f"{name}.toml").read_text())
        if analysis:
            raw["analysis"] = {**raw.get("analysis", {}), **analysis}
        case = folder / f"{name}.toml"
        case.write_text(tomli_w.dumps(raw))
        target = folder / name
        result = CliRunner().invoke(app, ["run", str(case), "--out", str(target),
                                          "--no-pictures"])
        assert result.exit_code in (0, 1), result.output
        out[name] = ((target / "report.md").read_text(),
                     json.loads((target / "result.json").read_text()), case)
    return out


def parsed_tables(text: str) -> list[dict]:
    """The tables a GFM viewer finds: their source lines, header cells and body rows."""
    tokens = MarkdownIt("commonmark").enable("table").parse(text)
    tables, current = [], None
    for token in tokens:
        if token.type == "table_open":
            current = {"lines": range(*token.map), "headers": [], "rows": []}
        elif token.type == "tr_open" and current is not None:
            current["rows"].append([])
        elif token.type == "inline" and current is not None and current["rows"]:
            current["rows"][-1].append(token.content)
        elif token.type == "table_close":
            current["headers"] = current["rows"].pop(0)
            tables.append(current)
            current = None
    return tables


@pytest.mark.parametrize("name", list(QUICK))
def test_every_table_of_a_bundled_report_reads_whole(reports, name):
    """Every line of report.md that starts with a pipe lies inside a table the parser
    found, and every table has a header and at least one row with as many cells (a blank
    line after the header row split each result table into a header-only table and a
    paragraph of raw pipes)."""
    text = reports[name][0]
    tables = parsed_tables(text)
    assert tables
    covered = {line for t in tables for line in t["lines"]}
    piped = [i for i, line in enumerate(text.splitlines()) if line.startswith("|")]
    assert [i for i in piped if i not in covered] == []
    for table in tables:
        assert table["rows"], table["headers"]
        assert all(len(row) == len(table["headers"]) for row in table["rows"])


@pytest.mark.parametrize("name", list(QUICK))
def test_labels_carry_their_units_and_no_raw_lists(reports, name):
    """No label of a report reads a unit as words ("N per mm", "N [1/mm]"), a symbol as
    spaced letters ("K H beta") or the solver's internal name ("bem failed"), no cell
    shows a Python list ("[]", "['...']"); a worm set's report names the worm and the
    wheel, never the pinion or the gear."""
    text = reports[name][0]
    for table in parsed_tables(text):
        labels = table["headers"] + [row[0] for row in table["rows"]]
        cells = labels + [c for row in table["rows"] for c in row[1:]]
        for cell in labels:
            for words in (" per mm", "N [1/mm]", "K H beta", "bem "):
                assert words not in cell, (words, cell)
        for cell in cells:
            for words in ("[]", "['"):
                assert words not in cell, (words, cell)
        if name.startswith("worm"):
            assert not any("pinion" in h or " gear" in h for h in table["headers"])


def test_a_report_says_what_made_it(reports):
    """The traceability block: the tool's version, when (UTC), the case file and the
    SHA-256 of its bytes, and the command, in report.md and in result.json."""
    text, document, case = reports["spur_crowned_20_60"]
    sha = hashlib.sha256(case.read_bytes()).hexdigest()
    provenance = document["provenance"]
    assert provenance["case_sha256"] == sha and provenance["case_file"] == str(case)
    assert provenance["command"].startswith("toothcontact run ")
    block = text.split("## Traceability", 1)[1]
    assert f"case file SHA-256: {sha}" in block
    assert f"toothcontact: {document['toothcontact_version']}" in block
    assert "run at (UTC): 20" in block and "command: toothcontact run" in block


def test_numbers_keep_the_digits_that_mean_something():
    """A margin to the micrometre and a transmission error to 0.01 µrad (the unloaded TE
    of conjugate flanks is the search's tolerance: 0.01676 µrad shows as 0.02), an empty
    list as 'none', names joined; a worm set's labels name its members."""
    assert number(-0.20722, resolution=1e-3) == "-0.207"
    assert number(0.01676, resolution=0.01) == "0.02"
    assert number([]) == "none" and number(["pinion_tip", "gear_tip"]) == "pinion_tip, gear_tip"
    assert label("mesh_stiffness_N_per_mm_um") == "mesh stiffness c_γα [N/(mm·µm)]"
    assert label("line_load_N_per_mm") == "line load [N/mm]"
    assert label("K_H_beta") == "face load factor K_Hβ of the loaded contact (ISO 6336-1 Method A)"
    assert label("roll_deg", "worm") == "worm roll [deg]"
    assert label("contact_radius_pinion_mm", "worm") == "contact radius on the worm [mm]"
