"""Mutated case files for the input fuzz (issue 12): a bundled case's raw table with one field
deleted, given a bad number, a wrong unit, a wrong type or an unknown neighbour, run through
the command line as a user would, and the outcome held to the promise: exit 2 with one line
naming a field and nothing written, or a complete folder with a strict-JSON result.

A share of the mutations aims at the inputs a third fuzzer found (issue 53): values past the
range a formula holds in (ASTM D341's viscosities and the oil's pour point, ISO/TR
14179-2's speeds, S_B's temperatures, a modification against its flank), counts that are
not finite, switches for numbers, control characters, file names and CSV files, and the
sweep files' tolerances and constraints; an answer is held to physical figures too
(implausible).

Used by tests/test_fuzz.py (hypothesis, small budget) and benchmarks/fuzz.py (large)."""

from __future__ import annotations

import copy
import json
import math
import random
import re
import tomllib
import warnings
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


#: issue 53's inputs by the key they are given to: (what, value)
NAMED = {
    "viscosity_40": [("a viscosity below ASTM D341's range", "0.3 mm^2/s")],
    "viscosity_100": [("a viscosity below ASTM D341's range", "1e-3 mm^2/s")],
    "oil_temperature": [(f"oil at {t}", t) for t in ("-200 degC", "-273 degC", "1 K",
                                                     "-459 degF", "-90 degC", "-55 degC",
                                                     "300 degC")],
    "bulk_temperature": [("a bulk far below the oil", "-100 degC")],
    "scuffing_temperature": [("a scuffing temperature at room temperature", "20 degC")],
    "pinion_speed": [("the slowest speed allowed", "1e-6 rpm")],
    "worm_speed": [("the slowest speed allowed, its μ given", "1e-6 rpm")],
    "friction_coefficient": [("a vanishing friction", 1e-300)],
    "cycles": [("infinite cycles", math.inf), ("a switch for cycles", True)],
    "pinion_cycles": [("infinite cycles", math.inf), ("a switch for cycles", True)],
    "file": [("a 300-character file name", "x" * 296 + ".csv"),
             ("a 5000-character file name", "x" * 5000),
             ("a CSV with a nan face position", "bad_nan.csv"),
             ("a CSV with a short row", "bad_ragged.csv"),
             ("a CSV that is not UTF-8", "bad_latin1.csv")],
    "iso1328_class": [("a switch for a class", True)],
    "max": [("nan for a constraint", math.nan)],
    "mean": [("nan for a mean", "nan um")],
    "std": [("a zero spread", "0 um")],
}
#: issue 53's tables added to a case where `applies(raw)`: (what, applies, path, value); an
#: empty path sets several fields at once
ADDITIONS = [
    *[(f"a helix slope of {a}", lambda r: r.get("kind") == "spur", ("pinion", "helix_slope"),
       {"amount": a}) for a in ("1 m", "500 mm")],
    *[(f"a profile slope of {a}", lambda r: r.get("kind") == "spur",
       ("pinion", "profile_slope"), {"amount": a}) for a in ("0.5 mm", "1 mm", "2 mm", "50 mm")],
    *[(f"a twist of {a}", lambda r: r.get("kind") == "spur", ("pinion", "twist"),
       {"amount": a}) for a in ("1 mm", "-1 mm")],
    ("a scuffing temperature below the oil's", lambda r: "lubricant" in r,
     ("lubricant", "scuffing_temperature"), "-10 degC"),
    ("a bulk far below the oil", lambda r: "operation" in r,
     ("operation", "bulk_temperature"), "-100 degC"),
    *[(f"a switch for {key}", lambda r: r.get("kind") == "spur", ("rating", key), True)
      for key in ("application_factor", "dynamic_factor", "S_Hmin")],
    ("a switch for permissible_specific_film", lambda r: "lubricant" in r,
     ("lubricant", "permissible_specific_film"), True),
    ("a vanishing friction with a scuffing temperature",
     lambda r: r.get("kind") == "spur" and "lubricant" in r, ("lubricant",),
     {"friction_coefficient": 1e-300, "scuffing_temperature": "300 degC"}),
    ("a spectrum level of 1e6 N*m", lambda r: r.get("kind") == "spur" and "load" in r,
     ("load", "spectrum"), [{"torque": "1e6 N*m", "cycles": 1e6}]),
    ("a large legal pair (m 40 mm, 400 mm face, 2e6 N)",
     lambda r: r.get("kind") == "spur" and "load" in r and "center_distance" not in r
     and not any("tip_relief" in r.get(m, {}) or "shaft" in r.get(m, {})
                 or "tip_diameter" in r.get(m, {}) for m in ("pinion", "gear")), (),
     {"module": "40 mm", "face_width": "400 mm", "load": {"tangential_load": "2e6 N"}}),
]
#: what of NAMED's and ADDITIONS' a case must refuse (bad input), and must answer (legal)
MUST_REFUSE = {what for key, options in NAMED.items() if key not in ("friction_coefficient",
                                                                     "worm_speed")
               for what, _ in options} - {
    "oil at 300 degC"} | {     # refused where it thins the oil below 2 mm²/s, not always
    "a helix slope of 1 m", "a helix slope of 500 mm", "a profile slope of 50 mm",
    "a profile slope of 1 mm", "a profile slope of 2 mm",
    "a scuffing temperature below the oil's", "a switch for a number", "a control character",
    "a sweep for a base", "a bulk far below the oil", "a switch for application_factor",
    "a switch for dynamic_factor", "a switch for S_Hmin",
    "a switch for permissible_specific_film"}
MUST_ANSWER = {"a vanishing friction", "a vanishing friction with a scuffing temperature",
               "a large legal pair (m 40 mm, 400 mm face, 2e6 N)",
               "a tolerance in degC on an oiled base"}
#: the bad CSV files a mutated topography may name, written beside the case (write_case)
BAD_CSV = ("bad_nan.csv", "bad_ragged.csv", "bad_latin1.csv")


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


def _get(table, path):
    for key in path:
        if not isinstance(table, (dict, list)):
            return None
        try:
            table = table[key]
        except (KeyError, IndexError):
            return None
    return table


def changed(table: dict, path: tuple, value=None, delete: bool = False,
            create: bool = False) -> dict:
    """A copy of `table` with the entry at `path` replaced by `value` (or deleted); create:
    the tables on the way made where missing."""
    out = copy.deepcopy(table)
    if create:
        node = out
        for key in path[:-1]:
            node = node.setdefault(key, {}) if isinstance(node, dict) else node[key]
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
        return ([(f"integer {v}", v) for v in BAD_INTEGERS] + [("a float for an integer", 2.5)]
                + [("a switch for a number", True)])
    if isinstance(value, float):
        return [(f"number {v}", v) for v in BAD_FLOATS] + [("a switch for a number", True)]
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
        options += [("a control character", f"{value[:1]}\x00{value[1:]}")]
        return options
    if isinstance(value, list):
        options = [("an empty list", [])]
        if value:
            options += [("one element fewer", value[:-1]), ("one element more", value + value[-1:])]
        return options
    if isinstance(value, dict):
        return [("a string for a table", "bogus")]
    return []


#: the share of mutations drawn from issue 53's inputs (NAMED, ADDITIONS)
AIMED = 0.3


def aimed(raw: dict) -> list[tuple[str, tuple, object]]:
    """Issue 53's mutations that apply to the table `raw`: (what, path, value)."""
    out = [(what, path, value) for path, _ in leaves(raw)
           if isinstance(path[-1], str) and path[-1] in NAMED for what, value in NAMED[path[-1]]]
    out += [(what, path, value) for what, applies, path, value in ADDITIONS if applies(raw)]
    return out


def mutate(raw: dict, rng: random.Random) -> tuple[str, tuple, dict]:
    """One random mutation of the table `raw` (a case or a sweep): (what was done, the path,
    the table)."""
    targeted = aimed(raw)
    if targeted and rng.random() < AIMED:
        what, path, value = rng.choice(targeted)
        if not path:                                    # several fields at once
            out = copy.deepcopy(raw)
            out.update(copy.deepcopy(value))
            return what, tuple(value), out
        if isinstance(value, dict) and isinstance(_get(raw, path), dict):
            value = {**_get(raw, path), **value}
        return what, path, changed(raw, path, copy.deepcopy(value), create=True)
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
    """Write `raw` as TOML into `folder`; paths to files (imported bodies, topographies)
    that the bundled cases ship made absolute against their folder, and the bad CSV files
    a mutation names (BAD_CSV) written beside it."""
    raw = copy.deepcopy(raw)
    for member in ("pinion", "gear"):
        body = raw.get(member)
        for table in (body, body.get("topography") if isinstance(body, dict) else None):
            if not isinstance(table, dict) or not isinstance(table.get("file"), str):
                continue
            if table["file"] in BAD_CSV:
                _write_bad_csv(folder / table["file"])
            elif len(table["file"]) < 200 and (CASES / table["file"]).is_file():
                table["file"] = str((CASES / table["file"]).resolve())
    path = folder / f"{name}.toml"
    path.write_text(tomli_w.dumps(raw), encoding="utf-8")
    return path


def _write_bad_csv(path: Path) -> None:
    """One of BAD_CSV: the shipped topography with a nan face position, a short row, or
    saved in Latin-1 with a non-ASCII label."""
    lines = (CASES / "helical_measured_topography.csv").read_text(encoding="utf-8").splitlines()
    if path.name == "bad_nan.csv":
        lines[3] = "nan" + lines[3][lines[3].index(","):]
        path.write_text("\n".join(lines) + "\n", encoding="utf-8")
    elif path.name == "bad_ragged.csv":
        lines[4] = lines[4].rsplit(",", 2)[0]
        path.write_text("\n".join(lines) + "\n", encoding="utf-8")
    else:
        path.write_bytes(("\n".join(lines).replace("face mm", "Fläche mm") + "\n")
                         .encode("latin-1"))


def bundled_sweeps() -> dict[str, dict]:
    """Every bundled sweep's raw table, by name, its base made absolute."""
    out = {}
    for p in sorted((CASES / "sweeps").glob("*.toml")):
        raw = tomllib.loads(p.read_text(encoding="utf-8"))
        base = (p.parent / raw["base"]).resolve()
        raw["base"] = str(base) if base.is_file() else raw["base"]
        out[p.stem] = raw
    return out


#: issue 53's sweep mutations beside NAMED's: (what, path, value)
SWEEP_ADDITIONS = [
    ("a tolerance in degC on an oiled base", (), {
        "base": "fzg_c_type", "vary": [], "set": {}, "optimise": None, "spectrum": None,
        "tolerance": [
            {"field": "operation.oil_temperature", "distribution": "normal",
             "mean": "80 degC", "std": "5 degC"}]}),
    ("a sweep for a base", ("base",), str(CASES / "sweeps" / "spur_crown_tolerance.toml")),
]


def mutate_sweep(raw: dict, rng: random.Random) -> tuple[str, tuple, dict]:
    """One mutation of a sweep's table: issue 53's (SWEEP_ADDITIONS) or mutate's."""
    if rng.random() < 0.25:
        what, path, value = rng.choice(SWEEP_ADDITIONS)
        if not path:
            out = {k: v for k, v in {**copy.deepcopy(raw), **value}.items() if v is not None}
            return what, tuple(value), out
        return what, path, changed(raw, path, value)
    return mutate(raw, rng)


def plan_sweep(raw: dict, folder: Path, name: str) -> tuple[int, str]:
    """Write a sweep's table into `folder` and read and plan it as `toothcontact sweep`
    does before any sample runs (runner.load_sweep, sampling.plan, the optimiser's
    bounds): (2, "error: ...") where it is refused, (0, "") where planned, (3, the error)
    for anything else."""
    from toothcontact.case import CaseError
    from toothcontact.runner import load_sweep
    from toothcontact.sweep.optimise import designs
    from toothcontact.sweep.sampling import plan

    path = folder / f"{name}.toml"
    path.write_text(tomli_w.dumps(raw), encoding="utf-8")
    try:
        spec, base, base_path = load_sweep(path)
        plan(spec, base, base_path.parent, source=str(path))
        if spec.optimise is not None:
            designs(spec.optimise)
    except CaseError as exc:
        return 2, f"error: {exc}"
    except Exception as exc:  # noqa: BLE001 - what the fuzz is for
        return 3, f"{type(exc).__name__}: {exc}"
    return 0, ""


def verdict(code: int, output: str, out_dir: Path) -> str | None:
    """None if the run kept the promise, else what went wrong: exit 2 with one error line
    and nothing written, or exit 0, 1 or 4 (a stage that cannot answer, saying why in the
    tool's words) with a complete folder, a strict-JSON result of plausible figures and no
    library warning."""
    lines = [line for line in output.strip().splitlines() if line.strip()]
    if code == 2:
        if len(lines) != 1 or not lines[0].startswith("error: "):
            return f"exit 2 without one error line: {output[:300]!r}"
        if out_dir.exists() and any(out_dir.iterdir()):
            return "exit 2 but files written"
        return None
    if code not in (0, 1, 4):
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
    told = re.search(r"\b\w*Warning: .*", output)
    if told:
        return f"a library warning reached the output: {told.group(0)[:200]!r}"
    document = json.loads((out_dir / "result.json").read_text(encoding="utf-8"))
    if code == 4:     # a stage that cannot answer says why, in words of the tool's own
        reasons = [r.get("bem_reason") or "" for r in document.get("positions") or []]
        python = next((r for r in reasons if PYTHON_ERROR.search(r)), None)
        if python:
            return f"exit 4 for a Python error: {python[:200]}"
    return implausible(document)


#: the words of Python's and numpy's own errors: a stage's reason in them is an internal
#: error passed off as an answer (issue 53: "cannot convert float NaN to integer")
PYTHON_ERROR = re.compile(r"cannot convert|division by zero|out of range|out of bounds|"
                          r"has no attribute|not subscriptable|math domain|NoneType|"
                          r"could not broadcast|unsupported operand|must be real number|"
                          r"zero-size array|object is not|invalid literal")


#: the classes a broken promise falls in, as issue 53 counts them
CLASSES = ("internal error", "implausible figure", "library warning", "bad input accepted",
           "legal input refused", "other")


def classify(code: int, problem: str | None, what: str) -> str | None:
    """The class (CLASSES) of a run's broken promise (its exit code, verdict's problem and
    the mutation's description), or None where it kept it."""
    if problem is None:
        if code in (0, 1, 4) and what in MUST_REFUSE:
            return "bad input accepted"
        if code == 2 and what in MUST_ANSWER:
            return "legal input refused"
        return None
    if problem.startswith("implausible"):
        return "implausible figure"
    if "warning" in problem:
        return "library warning"
    if problem.startswith(("exit 3", "exit 4 for a Python error", "still running")):
        return "internal error"
    return "other"


#: a figure of an answer outside these bounds is implausible (issue 53): (key, low, high),
#: the summary's and, for the rows' keys, every row's
PLAUSIBLE = [("friction_coefficient", 0.0, 1.0), ("friction_coefficient_mean", 0.0, 1.0),
             ("mesh_efficiency", 0.0, 1.0), ("S_B", 0.0, math.inf),
             ("S_lambda", 0.0, math.inf), ("S_H", 0.0, math.inf),
             # an EHL film of gear teeth is microns: 100 µm is no elastohydrodynamic film
             ("film_thickness_min_um", 0.0, 100.0), ("film_thickness_central_um", 0.0, 100.0),
             # 100 GPa is no contact pressure of steel
             ("max_p_max_MPa", 0.0, 1e5), ("p_max_MPa", 0.0, 1e5)]


def implausible(document: dict) -> str | None:
    """None if every figure of a result lies within PLAUSIBLE, else the first that does
    not, named."""
    summary = document.get("summary") or {}
    rows = (document.get("sections") or {}).get("positions") or document.get("positions") or []
    for key, low, high in PLAUSIBLE:
        for where, values in (("summary", [summary.get(key)]),
                              ("positions", [r.get(key) for r in rows if isinstance(r, dict)])):
            for value in values:
                if isinstance(value, (int, float)) and not isinstance(value, bool) \
                        and not low <= value <= high:
                    return f"implausible figure: {where} {key} = {value:.4g}"
    return None


def run_cli(case_path: Path, out_dir: Path) -> tuple[int, str]:
    """`toothcontact run CASE --out DIR --no-pictures` in this process: (exit code, output)."""
    from typer.testing import CliRunner

    from toothcontact.cli import app

    with warnings.catch_warnings(record=True) as caught:      # each run's, not once a process
        warnings.simplefilter("always")
        result = CliRunner().invoke(app, ["run", str(case_path), "--out", str(out_dir),
                                          "--no-pictures"])
    if result.exception is not None and not isinstance(result.exception, SystemExit):
        return 3, f"{type(result.exception).__name__}: {result.exception}"
    told = "".join(f"{w.category.__name__}: {w.message}\n" for w in caught)
    return result.exit_code, result.output + told


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
