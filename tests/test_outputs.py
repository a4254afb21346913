"""A run's output folder is all or nothing (issue 12): a reader sees the previous complete
run or the new complete one, never a mix and never a temporary file; a stage that cannot
answer says so in its own entry and the other stages' files stand."""

import json
import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest

from toothcontact import runner
from toothcontact.views import report
from toothcontact.runner import bundled_cases_dir

HERTZ = bundled_cases_dir() / "hertz_sphere_on_flat.toml"
CROWN = bundled_cases_dir() / "crown_spur_metric_bias.toml"


def listing(folder: Path) -> dict[str, bytes]:
    return {p.name: p.read_bytes() for p in sorted(folder.iterdir())}


def no_leftovers(folder: Path) -> bool:
    return not [p for p in folder.parent.iterdir() if p.name.startswith(".")]


def test_a_run_that_fails_while_writing_leaves_the_previous_run(tmp_path, monkeypatch):
    out = tmp_path / "out"
    runner.run_case(HERTZ, out, pictures=False)
    before = listing(out)

    def broken(*args, **kwargs):
        raise OSError("disk full")

    monkeypatch.setattr(report, "write_run", broken)
    with pytest.raises(OSError):
        runner.run_case(CROWN, out, pictures=False)
    assert listing(out) == before and no_leftovers(out)


def test_a_new_run_replaces_the_old_folder_whole(tmp_path):
    out = tmp_path / "out"
    runner.run_case(CROWN, out, pictures=False)
    (out / "stale.png").write_bytes(b"from another input")
    runner.run_case(HERTZ, out, pictures=False)
    assert "stale.png" not in listing(out)
    assert json.loads((out / "result.json").read_text())["kind"] == "hertz"
    assert no_leftovers(out)


def test_a_plot_that_fails_is_its_own_entry(tmp_path, monkeypatch):
    from toothcontact.views import plots

    def broken(*args, **kwargs):
        raise RuntimeError("no fonts")

    monkeypatch.setattr(plots, "figures_for", broken)
    document, written = runner.run_case(CROWN, tmp_path / "out", pictures=False)
    assert document["stages"]["plots"] == {"status": "failed",
                                           "reason": "RuntimeError: no fonts"}
    assert document["stages"]["pictures"]["status"] == "skipped"
    saved = json.loads((tmp_path / "out" / "result.json").read_text())
    assert saved["stages"]["plots"]["status"] == "failed" and saved["crown"]
    assert sorted(p.name for p in written) == ["report.html", "report.md", "result.json"]


def test_a_killed_run_leaves_the_previous_run_and_the_next_run_cleans_up(tmp_path):
    """Kill -9 a run while it writes (its pictures take seconds): the folder still holds
    the previous run, whole; the staging folder it left is removed by the next run."""
    out = tmp_path / "out"
    runner.run_case(HERTZ, out, pictures=False)
    before = listing(out)
    case = bundled_cases_dir() / "spur_crowned_20_60.toml"
    process = subprocess.Popen([sys.executable, "-m", "toothcontact", "run", str(case),
                                "--out", str(out)], stdout=subprocess.DEVNULL,
                               stderr=subprocess.DEVNULL)
    deadline = time.time() + 120
    while time.time() < deadline and process.poll() is None:
        staged = [p for p in tmp_path.iterdir() if p.name.endswith(".staging")]
        if staged and any(staged[0].iterdir()):
            break
        time.sleep(0.05)
    assert process.poll() is None, "the run ended before it could be killed"
    os.kill(process.pid, signal.SIGKILL)
    process.wait()
    assert listing(out) == before
    runner.run_case(HERTZ, out, pictures=False)
    assert no_leftovers(out)


def test_a_defaulted_material_is_stated_in_the_result():
    """The default steel (E = 206 GPa) and a mate's material taken from the member's are
    named in the notes, which the report lists; a given material is not."""
    from toothcontact.analyses import analyse
    from toothcontact.case import parse_case

    raw = {"kind": "spur", "teeth": [20, 60], "module": "3 mm", "pressure_angle": "20 deg",
           "face_width": "30 mm"}
    notes = analyse(parse_case(raw)).notes
    assert "material: none given, so steel: E = 206 GPa, nu = 0.3" in notes
    assert "gear_material: none given, so the same as material" in notes
    given = analyse(parse_case({**raw, "material": {"E": "210 GPa", "nu": 0.29},
                                "gear_material": {"E": "100 GPa", "nu": 0.3}})).notes
    assert not any("none given" in n for n in given)
