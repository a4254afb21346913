"""Mutated case files for the input fuzz (issue 12): a bundled case's raw table with one field
deleted, given a bad number, a wrong unit, a wrong type or an unknown neighbour, run through
the command line as a user would, and the outcome held to the promise: exit 2 with one line
naming a field and nothing written, or a complete folder with a strict-JSON result.

Used by tests/test_fuzz.py (hypothesis, small budget) and benchmarks/fuzz.py (large)."""

from __future__ import annotations

import copy
import random
import re
import tomllib
from pathlib import Path

import tomli_w
from documents import strict_json

CASES = Path(__file__).resolve().parents[1] / "cases"

#: analysis settings small enough for hundreds of runs; a mutation may still change them
SMALL = {"positions": 3, "grid": [9, 15], "field_grid": 41, "pressure_grid": 32}

_QUANTITY = re.compile(r"^\s*([+-]?[\d.]+(?:[eE][+-]?\d+)?|[+-]?inf)\s*(\S.*)?$", re.I)
BAD_MAGNITUDES = ["0", "-1", "-3.5", "1e-400", "1e-9", "1e300", "nan", "inf"]
WRONG_UNITS = ["s", "kg", "furlong", "degC", "N", "mm", "deg", "bogus_unit"]
BAD_INTEGERS = [0, -3, 1, 2, 4, 10 ** 6]
BAD_FLOATS = [float("nan"), float("inf"), -1.0, 0.0, 5.0, 1e300, 1.5, -1.5]


def bundled() -> dict[str, dict]:
    """Every bundled case's raw table, by name."""
    return {p.stem: tomllib.loads(p.read_text(encoding="utf-8"))
            for p in sorted(CASES.glob("*.toml"))}


def leaves(table, path=()):
    """(path, value) of every scalar, list and table below `table`, tables included."""
    out = []
    items = table.items() if isinstance(table, dict) else enumerate(table)
    for key, value in items:
        here = path + (key,)
        out.append((here, value))
        if isinstance(value, (dict, list)):
            out.extend(leaves(value, here))
    return out


def _parent(table, path):
    for key in path[:-1]:
        table = table[key]
    return table


def changed(table: dict, path: tuple, value=None, delete: bool = False) -> dict:
    """A copy of `table` with the entry at `path` replaced by `value` (or deleted)."""
    out = copy.deepcopy(table)
    parent = _parent(out, path)
    if delete:
        del parent[path[-1]]
    else:
        parent[path[-1]] = value
    return out


def _value_mutations(value, rng: random.Random) -> list[tuple[str, object]]:
    if isinstance(value, bool):
        return [("a string for a switch", "yes")]
    if isinstance(value, int):
        return [(f"integer {v}", v) for v in BAD_INTEGERS] + [("a float for an integer", 2.5)]
    if isinstance(value, float):
        return [(f"number {v}", v) for v in BAD_FLOATS]
    if isinstance(value, str):
        match = _QUANTITY.match(value)
        try:
            x = float(match.group(1)) if match else None
        except ValueError:
            x = None
        if x is None:
            return [("an unknown choice", "bogus")]
        number, unit = match.group(1), match.group(2) or ""
        options = [(f"magnitude {m}", f"{m} {unit}".strip()) for m in BAD_MAGNITUDES]
        options += [(f"unit {u}", f"{number} {u}") for u in WRONG_UNITS]
        options += [("no unit", number), ("a bare number", x)]
        options += [(f"scaled {s:g}", f"{x * s:.6g} {unit}".strip()) for s in (1e3, 1e-3)]
        return options
    if isinstance(value, list):
        options = [("an empty list", [])]
        if value:
            options += [("one element fewer", value[:-1]), ("one element more", value + value[-1:])]
        return options
    if isinstance(value, dict):
        return [("a string for a table", "bogus")]
    return []


def mutate(raw: dict, rng: random.Random) -> tuple[str, tuple, dict]:
    """One random mutation of the case table `raw`: (what was done, the path, the table)."""
    candidates = [(p, v) for p, v in leaves(raw)
                  if p[0] not in ("title", "source", "assumptions", "kind")]
    path, value = rng.choice(candidates)
    roll = rng.random()
    if roll < 0.12:
        return "deleted", path, changed(raw, path, delete=True)
    if roll < 0.16:
        target = _parent(raw, path) if len(path) > 1 else raw
        if isinstance(target, dict):
            where = path[:-1] + ("colour",)
            return "an unknown field", where, changed(raw, where, "red")
    options = _value_mutations(value, rng)
    if not options:
        return "deleted", path, changed(raw, path, delete=True)
    what, new = rng.choice(options)
    return what, path, changed(raw, path, new)


def small(raw: dict, interference: bool = True) -> dict:
    """The case with small analysis settings (kept where the case sets its own), with or
    without the bodies' collision check."""
    out = copy.deepcopy(raw)
    if out.get("kind") in ("spur", "spline", "worm", "imported"):
        analysis = out.setdefault("analysis", {})
        for key, value in {**SMALL, "interference": interference}.items():
            analysis.setdefault(key, value)
    return out


def write_case(raw: dict, folder: Path, name: str, source: str) -> Path:
    """Write `raw` as TOML into `folder`; paths to files (imported bodies) made absolute
    against the bundled case `source`'s folder."""
    raw = copy.deepcopy(raw)
    for member in ("pinion", "gear"):
        body = raw.get(member)
        if raw.get("kind") == "imported" and isinstance(body, dict) \
                and isinstance(body.get("file"), str):
            body["file"] = str((CASES / body["file"]).resolve())
    path = folder / f"{name}.toml"
    path.write_text(tomli_w.dumps(raw), encoding="utf-8")
    return path


def verdict(code: int, output: str, out_dir: Path) -> str | None:
    """None if the run kept the promise, else what went wrong."""
    lines = [line for line in output.strip().splitlines() if line.strip()]
    if code == 2:
        if len(lines) != 1 or not lines[0].startswith("error: "):
            return f"exit 2 without one error line: {output[:300]!r}"
        if out_dir.exists() and any(out_dir.iterdir()):
            return "exit 2 but files written"
        return None
    if code not in (0, 1):
        return f"exit {code}: {(lines or [''])[-1][:300]}"
    names = sorted(p.name for p in out_dir.iterdir()) if out_dir.is_dir() else []
    for required in ("result.json", "report.md", "report.html"):
        if required not in names:
            return f"exit {code} but {required} missing ({names})"
    if any(n.endswith(".tmp") or n.startswith(".") for n in names):
        return f"temporary files left: {names}"
    try:
        strict_json((out_dir / "result.json").read_text(encoding="utf-8"))
    except ValueError as exc:
        return f"result.json: {exc}"
    return None


def run_cli(case_path: Path, out_dir: Path) -> tuple[int, str]:
    """`toothcontact run CASE --out DIR --no-pictures` in this process: (exit code, output)."""
    from typer.testing import CliRunner

    from toothcontact.cli import app

    result = CliRunner().invoke(app, ["run", str(case_path), "--out", str(out_dir),
                                      "--no-pictures"])
    if result.exception is not None and not isinstance(result.exception, SystemExit):
        return 3, f"{type(result.exception).__name__}: {result.exception}"
    return result.exit_code, result.output


def refused_line(case_text: str, folder: Path) -> str:
    """Run a case text through `toothcontact run`: it must exit 2 with one line and write
    nothing; that line."""
    from typer.testing import CliRunner

    from toothcontact.cli import app

    case = folder / "case.toml"
    case.write_text(case_text)
    out = folder / "out"
    result = CliRunner().invoke(app, ["run", str(case), "--out", str(out), "--no-pictures"])
    assert result.exit_code == 2, result.output
    lines = result.output.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("error: "), lines
    assert not out.exists()
    return lines[0]
