"""The command line's own surface: help that shows its defaults, the case schema per kind
for editors, a sweep whose optimisation found no feasible design exits 1, and importing
the package leaves the process's allocator alone."""

import json
import subprocess
import sys

from typer.testing import CliRunner

from toothcontact.cli import app


def test_run_help_shows_the_default_output_folder():
    """`run --help` lost "[out/<case>]" (read as rich markup)."""
    result = CliRunner().invoke(app, ["run", "--help"])
    assert result.exit_code == 0
    assert "[out/<case>]" in result.output


def test_the_schema_of_a_kind_is_json_with_its_fields():
    result = CliRunner().invoke(app, ["schema", "spur"])
    assert result.exit_code == 0
    schema = json.loads(result.output)
    assert {"teeth", "module", "face_width", "pinion", "load"} <= set(schema["properties"])
    assert "end_chamfer" in json.dumps(schema)
    bad = CliRunner().invoke(app, ["schema", "spurr"])
    assert bad.exit_code == 2 and "kind: 'spurr' is not a known kind" in bad.output


def test_a_sweep_without_a_feasible_design_exits_1(monkeypatch, tmp_path):
    """An optimisation whose every design broke a constraint exited 0 as if it had found
    one: exit 1, and the line says so."""
    from toothcontact import runner

    stats = {"samples": 4, "ok": 4, "failed": 0,
             "optimise": {"objective": "P95 bem_max_p_max_MPa",
                          "best": {"feasible": False, "objective": 5000.0,
                                   "design": {"pinion.crown.radius": "4000 mm"}}}}
    folder = tmp_path / "out"
    folder.mkdir()
    monkeypatch.setattr(runner, "run_sweep",
                        lambda *a, **k: (stats, [folder / "sweep.json"]))
    result = CliRunner().invoke(app, ["sweep", "spur_crown_tolerance", "--out", str(folder)])
    assert result.exit_code == 1, result.output
    assert "no design met the constraints" in result.output


def test_importing_the_package_leaves_mallopt_alone():
    """Importing toothcontact changed glibc's malloc thresholds for the whole process: the
    command line and a sweep's samples set them, a host program importing the package
    does not (M_MMAP_THRESHOLD read back through mallinfo is not available, so the call
    itself is watched)."""
    code = ("import ctypes, toothcontact.memory as m\n"
            "called = []\n"
            "m.keep_freed_memory = lambda: called.append(1)\n"
            "import importlib, toothcontact\n"
            "importlib.reload(toothcontact)\n"
            "import toothcontact.analyses\n"
            "print(len(called))\n")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                         check=True)
    assert out.stdout.strip() == "0"


def test_verbose_logs_the_stages_and_quiet_prints_nothing(tmp_path):
    """-v logs each stage and its time to stderr through the package's loggers; -q prints
    nothing but errors (the exit code tells the rest); a bad case still gets its line."""
    def toothcontact(*args):
        return subprocess.run([sys.executable, "-m", "toothcontact", *args],
                              capture_output=True, text=True, timeout=300, cwd=tmp_path)

    loud = toothcontact("-v", "run", "hertz_sphere_on_flat", "--out", "loud")
    assert loud.returncode == 0
    assert "INFO toothcontact.runner: hertz_sphere_on_flat.toml: hertz analysis in" in loud.stderr
    assert "INFO toothcontact.runner: writing the reports" in loud.stderr
    assert "wrote result.json" in loud.stdout
    quiet = toothcontact("-q", "run", "hertz_sphere_on_flat", "--out", "quiet")
    assert quiet.returncode == 0 and quiet.stdout == "" and quiet.stderr == ""
    assert (tmp_path / "quiet" / "result.json").is_file()
    plain = toothcontact("run", "hertz_sphere_on_flat", "--out", "plain")
    assert "INFO" not in plain.stderr and "wrote result.json" in plain.stdout
    bad = toothcontact("-q", "run", "no_such_case")
    assert bad.returncode == 2 and bad.stderr.startswith("error: no_such_case")
