"""The optional parts of the install: a task whose extra is missing says which extra to
install (exit 2, one line), a run without the pictures' extra writes everything else and
says why in its document (the core install itself is measured by benchmarks/install_size.py
in a fresh virtual environment)."""

import json
import sys

import pytest
from typer.testing import CliRunner

from toothcontact.cli import app
from toothcontact.extras import installed, missing_extra


def hide(monkeypatch, top: str) -> None:
    """Make `top` and its submodules unimportable in this process (a missing extra)."""
    for name in [m for m in sys.modules if m == top or m.startswith(f"{top}.")]:
        monkeypatch.setitem(sys.modules, name, None)
    monkeypatch.setitem(sys.modules, top, None)


def test_a_missing_module_names_its_extra():
    assert "pip install 'toothcontact[cad]'" in missing_extra(ModuleNotFoundError(
        "No module named 'OCP'", name="OCP.STEPControl"))
    assert "[sweep]" in missing_extra(ModuleNotFoundError("x", name="distributed"))
    assert missing_extra(ModuleNotFoundError("x", name="numpy")) is None
    assert missing_extra(ValueError("x")) is None
    assert installed("cad") and installed("viz") and installed("sweep")


def test_an_imported_step_case_without_the_cad_extra_says_so(monkeypatch, tmp_path):
    hide(monkeypatch, "OCP")
    result = CliRunner().invoke(app, ["run", "imported_spur_crowned_20_60", "--out",
                                      str(tmp_path / "out"), "--no-pictures"])
    assert result.exit_code == 2, result.output
    lines = result.output.strip().splitlines()
    assert len(lines) == 1 and "needs the cad extra" in lines[0]
    assert not (tmp_path / "out").exists()


def test_a_run_without_the_viz_extra_writes_all_but_the_pictures(monkeypatch, tmp_path):
    hide(monkeypatch, "pyvista")
    out = tmp_path / "out"
    result = CliRunner().invoke(app, ["run", "worm_saba_set", "--out", str(out)])
    assert result.exit_code == 0, result.output
    assert "pip install 'toothcontact[viz]'" in result.output
    document = json.loads((out / "result.json").read_text())
    assert "viz extra" in document["stages"]["pictures"]["reason"]
    assert (out / "report.html").is_file() and not list(out.glob("pattern_*.png"))


@pytest.mark.parametrize("command", [["export", "cases/spur_crowned_20_60.toml"],
                                     ["sweep", "spur_crown_robustness"]])
def test_export_and_sweep_without_their_extras_say_which(monkeypatch, tmp_path, command):
    hide(monkeypatch, "OCP")
    hide(monkeypatch, "distributed")
    hide(monkeypatch, "dask")
    from pathlib import Path

    root = Path(__file__).parent.parent
    args = [str(root / command[1]) if command[1].startswith("cases/") else command[1]]
    result = CliRunner().invoke(app, [command[0], *args, "--out", str(tmp_path / "out")])
    assert result.exit_code == 2, result.output
    assert "extra" in result.output and "pip install 'toothcontact[" in result.output
