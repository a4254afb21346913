"""A normal (not editable) install works anywhere (issue 13): the wheel is built, installed
into a fresh virtual environment (its dependencies borrowed from this one), and `demo` runs
every bundled case from an empty folder, the imported cases reading their packaged bodies."""

import json
import re
import subprocess
import sys
import sysconfig
from pathlib import Path

import pytest
from documents import complete_run

from toothcontact.runner import bundled_cases

ROOT = Path(__file__).resolve().parents[1]


@pytest.fixture(scope="module")
def installed(tmp_path_factory) -> Path:
    """The bin folder of a fresh venv holding the built wheel."""
    folder = tmp_path_factory.mktemp("install")
    subprocess.run([sys.executable, "-m", "pip", "wheel", "-q", "--no-deps", "-w",
                    str(folder / "dist"), str(ROOT)], check=True)
    wheel, = (folder / "dist").glob("toothcontact-*.whl")
    venv = folder / "venv"
    subprocess.run([sys.executable, "-m", "venv", "--without-pip", str(venv)], check=True)
    python = venv / "bin" / "python"
    purelib = subprocess.run([str(python), "-c", "import sysconfig; "
                              "print(sysconfig.get_paths()['purelib'])"],
                             check=True, capture_output=True, text=True).stdout.strip()
    # the dependencies of this environment, without its editable toothcontact (a path
    # listed in a .pth file is added to sys.path, but the .pth files there are not run)
    Path(purelib, "borrowed.pth").write_text(sysconfig.get_paths()["purelib"] + "\n")
    subprocess.run([sys.executable, "-m", "pip", "--python", str(python), "install", "-q",
                    "--no-deps", "--no-index", str(wheel)], check=True)
    return venv / "bin"


def test_the_installed_tool_is_the_wheel(installed, tmp_path):
    where = subprocess.run([str(installed / "python"), "-c",
                            "import toothcontact; print(toothcontact.__file__)"],
                           cwd=tmp_path, check=True, capture_output=True, text=True).stdout
    assert str(ROOT) not in where and "site-packages" in where
    assert (Path(where.strip()).parent / "py.typed").exists()      # typed (PEP 561)
    version = subprocess.run([str(installed / "toothcontact"), "--version"], cwd=tmp_path,
                             check=True, capture_output=True, text=True).stdout
    assert version.startswith("toothcontact ")


def test_cases_lists_the_packaged_cases_and_run_takes_a_name(installed, tmp_path):
    listed = subprocess.run([str(installed / "toothcontact"), "cases"], cwd=tmp_path,
                            check=True, capture_output=True, text=True).stdout
    assert "imported_peer_uncrowned_20_60" in listed and "bundled" in listed
    done = subprocess.run([str(installed / "toothcontact"), "run", "hertz_sphere_on_flat",
                           "--out", "mine"], cwd=tmp_path, capture_output=True, text=True)
    assert done.returncode == 0, done.stderr
    assert json.loads((tmp_path / "mine" / "result.json").read_text())["kind"] == "hertz"


def test_demo_runs_every_bundled_case_from_an_empty_folder(installed, tmp_path):
    """Every bundled case's folder complete (documents.complete_run: strict JSON, checks
    with their kinds, both reports): test_cli runs only some of them through `run`."""
    done = subprocess.run([str(installed / "toothcontact"), "demo", "--out", "out"],
                          cwd=tmp_path, capture_output=True, text=True)
    assert done.returncode == 0, done.stderr[-2000:]
    cases = sorted(p.name for p in (tmp_path / "out").iterdir())
    assert cases == sorted(p.stem for p in bundled_cases())
    for case in cases:
        complete_run(tmp_path / "out" / case)
    # the table names every case whole (it can be pasted into `run`) and its kind as built
    rows = {line.split("│")[1].strip(): [c.strip() for c in line.split("│")[2:]]
            for line in done.stdout.splitlines() if line.count("│") >= 5}
    assert set(cases) <= set(rows)
    assert rows["helical_offcentre_crown_tip_relief"][0] == "helical"
    assert rows["spur_crowned_20_60"][0] == "spur"
    assert rows["fzg_c_type"][1].startswith(("all ", "1 of", "2 of"))
    # no printed figure carries float round-off (issue 55): no number of 1e-7 or below,
    # in any bundled report
    noise = re.compile(r"(?<![\w.])-?\d(?:\.\d+)?e-(?:0[7-9]|[1-9]\d)\b")
    for case in cases:
        for name in ("report.md", "report.html"):
            text = (tmp_path / "out" / case / name).read_text(encoding="utf-8")
            text = re.sub(r"data:image/png;base64,[^\"]+", "", text)
            assert not noise.findall(text), (case, name, noise.findall(text)[:5])
    # a design review's document (issue 55): FZG's report.md under 20 kB (19.5 kB; 33.4 kB
    # before its summary table, glossary texts and inputs stayed in report.html), its
    # positions and its duty cycle's levels in CSV files beside it
    fzg = tmp_path / "out" / "fzg_c_type"
    assert (fzg / "report.md").stat().st_size < 20_000
    for table in ("positions.csv", "duty_cycle_levels.csv"):
        assert table in (fzg / "report.md").read_text(encoding="utf-8")
        assert (fzg / table).stat().st_size > 0
