"""Convergence of the half-space contact solver on gap fields of the contact cycle.

Solves every stored gap field (`.npz` with gap, dx, dy, load, E_star, mask; see
tests/data/fields/README.md) with contact.pressure.solve_contact at its defaults (tol 1e-8,
max_iter 500, Hertz or interference start, float64) and tabulates per field: shape, dx/dy,
iterations, wall time (best of --repeat, the influence operator built afresh each time, as
the cycle does for each field), final relative gap error and the outcome: "converged",
"edge" (the contact reaches the grid's edge: the caller widens the field) or "failed"
(with the solver's message).

With --baseline REV the solver of that git revision (its contact/pressure.py, imported
beside the package) runs on the same fields in the same process, for a before/after table.
With --dump CASE.toml DIR it instead analyses the case and stores every field the loaded
contact hands to the solver in DIR (CASE_000.npz, ...; the gap in float64), to gather more.

Each directory or glob given to --fields is one set; a set of at most --max-rows fields is
recorded field by field, a larger one by its summary (counts, mean and largest iterations,
total time, largest error) and the fields on which either solver failed.

Run (a few seconds for the stored fields; minutes for a thousand with a baseline):

    .venv/bin/python benchmarks/solver_convergence.py
    .venv/bin/python benchmarks/solver_convergence.py --dump cases/spur_crowned_20_60.toml \\
        /tmp/fields
    .venv/bin/python benchmarks/solver_convergence.py --baseline 8744259 \\
        --fields tests/data/fields /tmp/fields

Prints the tables and writes benchmarks/solver_convergence.json.
"""

from __future__ import annotations

import argparse
import glob
import importlib.util
import itertools
import json
import os
import platform
import subprocess
import sys
import tempfile
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
ROOT = HERE.parent
JSON_OUT = HERE / "solver_convergence.json"
try:
    import toothcontact  # noqa: F401
except ImportError:
    sys.path.insert(0, str(ROOT / "src"))

sys.path.insert(0, str(HERE))
from timing import timed  # noqa: E402
from toothcontact.contact import pressure  # noqa: E402


def baseline_solver(rev: str):
    """contact/pressure.py of git revision `rev`, imported as a sibling module of the
    package's (its relative imports resolve to the package as it is now)."""
    source = subprocess.run(["git", "-C", str(ROOT), "show",
                             f"{rev}:src/toothcontact/contact/pressure.py"],
                            check=True, capture_output=True, text=True).stdout
    path = Path(tempfile.mkdtemp()) / "pressure_baseline.py"
    path.write_text(source)
    name = "toothcontact.contact._pressure_baseline"
    spec = importlib.util.spec_from_file_location(name, path)
    module = importlib.util.module_from_spec(spec)
    sys.modules[name] = module
    spec.loader.exec_module(module)
    return module


def dump(case_file: Path, out: Path) -> int:
    """Analyse the case, storing each field that contact.loaded hands to solve_contact in
    `out` as <case>_<index>.npz; the number stored."""
    from toothcontact import analyses
    from toothcontact.case import load_case
    from toothcontact.contact import loaded

    out.mkdir(parents=True, exist_ok=True)
    count, solve = itertools.count(), loaded.solve_contact

    def recording(gap, dx, dy, load, E_star, mask=None, **options):
        material = np.ones(np.shape(gap), dtype=bool) if mask is None else mask
        np.savez_compressed(out / f"{case_file.stem}_{next(count):03d}.npz", gap=gap,
                            mask=material, dx=dx, dy=dy, load=load, E_star=E_star)
        return solve(gap, dx, dy, load, E_star, mask=mask, **options)

    loaded.solve_contact = recording
    try:
        analyses.analyse(load_case(case_file)[0])
    except Exception as exc:                       # the fields stored until then are kept
        print(f"{case_file.name}: the analysis stopped: {exc}")
    finally:
        loaded.solve_contact = solve
    return next(count)


def field_files(pattern: str) -> list[Path]:
    path = Path(pattern)
    if path.is_dir():
        return sorted(path.glob("*.npz"))
    return sorted(Path(p) for p in glob.glob(pattern))


def solve(solver, field, repeat: int) -> dict:
    """One solver on one field: iterations, time_s, relative_error, status, message."""
    def run():
        solver.influence_operator.cache_clear()
        try:
            return solver.solve_contact(field["gap"], field["dx"], field["dy"], field["load"],
                                        field["E_star"], mask=field["mask"])
        except (ValueError, RuntimeError) as exc:
            return exc

    t, result = timed(run, repeat)
    if isinstance(result, Exception):
        edge = isinstance(result, ValueError) and "grid's edge" in str(result)
        return {"status": "edge" if edge else "failed", "iterations": None, "time_s": t,
                "relative_error": None, "message": str(result)}
    return {"status": "converged", "iterations": result.iterations, "time_s": t,
            "relative_error": result.relative_error, "message": None}


def load_field(path: Path) -> dict:
    with np.load(path) as f:
        field = {"gap": f["gap"], "mask": f["mask"].astype(bool)}
        field.update({k: float(f[k]) for k in ("dx", "dy", "load", "E_star")})
    return field


def summary(rows: list[dict], key: str) -> dict:
    results = [r[key] for r in rows]
    its = [r["iterations"] for r in results if r["status"] == "converged"]
    errors = [r["relative_error"] for r in results if r["status"] == "converged"]
    return {
        "fields": len(results),
        "converged": len(its),
        "edge": sum(r["status"] == "edge" for r in results),
        "failed": sum(r["status"] == "failed" for r in results),
        "iterations_mean": float(np.mean(its)) if its else None,
        "iterations_max": max(its) if its else None,
        "time_total_s": float(sum(r["time_s"] for r in results)),
        "relative_error_max": max(errors) if errors else None,
    }


def table(headers, rows):
    widths = [max(len(str(c)) for c in col) for col in zip(headers, *rows)]
    line = lambda cells: "  ".join(str(c).rjust(w) for c, w in zip(cells, widths))  # noqa: E731
    return "\n".join([line(headers), line(["-" * w for w in widths])] + [line(r) for r in rows])


def cells(result: dict) -> list[str]:
    if result["status"] == "converged":
        return [str(result["iterations"]), f"{result['time_s'] * 1e3:.1f}",
                f"{result['relative_error']:.1e}", "converged"]
    return ["-", f"{result['time_s'] * 1e3:.1f}", "-", result["status"]]


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--fields", nargs="+", default=[str(ROOT / "tests" / "data" / "fields")],
                        help="directories of .npz fields, or globs; each one set")
    parser.add_argument("--baseline", metavar="REV", help="also run this git revision's solver")
    parser.add_argument("--repeat", type=int, default=3, help="best of, per field and solver")
    parser.add_argument("--max-rows", type=int, default=50,
                        help="record a set field by field up to this many fields")
    parser.add_argument("--out", type=Path, default=JSON_OUT)
    parser.add_argument("--dump", nargs=2, type=Path, metavar=("CASE", "DIR"),
                        help="only store the fields of CASE's analysis in DIR")
    args = parser.parse_args(argv)
    if args.dump:
        print(f"stored {dump(*args.dump)} fields in {args.dump[1]}")
        return

    solvers = {"current": pressure}
    if args.baseline:
        solvers["baseline"] = baseline_solver(args.baseline)
    sets = []
    for pattern in args.fields:
        files = field_files(pattern)
        rows = []
        for path in files:
            field = load_field(path)
            row = {"field": path.stem, "shape": list(field["gap"].shape),
                   "dx_mm": field["dx"], "dy_mm": field["dy"],
                   "dx_over_dy": field["dx"] / field["dy"], "load_N": field["load"],
                   "material_cells": int(field["mask"].sum())}
            for key, solver in solvers.items():
                row[key] = solve(solver, field, args.repeat)
            rows.append(row)
            print(f"  {path.stem}: " + ", ".join(
                f"{key} {row[key]['status']} ({row[key]['iterations']})" for key in solvers),
                flush=True)
        recorded = rows if len(rows) <= args.max_rows else [
            r for r in rows if any(r[key]["status"] == "failed" for key in solvers)]
        sets.append({"fields": pattern, "count": len(rows),
                     "summary": {key: summary(rows, key) for key in solvers},
                     "rows_recorded": "all" if len(rows) <= args.max_rows
                     else "fields on which a solver failed",
                     "rows": recorded})

        headers = ["field", "shape", "dx/dy", "it", "ms", "error", "outcome"]
        if args.baseline:
            headers += ["base it", "base ms", "base error", "base outcome"]
        print(f"\n{pattern}: {len(rows)} fields" + ("" if recorded is rows
                                                    else f", {len(recorded)} shown"))
        print(table(headers, [
            [r["field"], "×".join(map(str, r["shape"])), f"{r['dx_over_dy']:.1f}"]
            + sum((cells(r[key]) for key in solvers), []) for r in recorded]))
        for key in solvers:
            s = sets[-1]["summary"][key]
            print(f"{key}: {s['converged']} converged, {s['edge']} edge, {s['failed']} failed;"
                  f" iterations mean {s['iterations_mean'] or 0:.1f}, max {s['iterations_max']};"
                  f" {s['time_total_s']:.2f} s in all")
        print()

    out = {
        "versions": {"python": platform.python_version(), "numpy": np.__version__,
                     "machine": platform.machine(), "cpus": os.cpu_count()},
        "solver": {"tol": 1e-8, "max_iter": 500, "start": "default (warm)", "dtype": "float64",
                   "timing": "best of --repeat wall times, the influence operator built "
                             "afresh for each (as the cycle does per field)"},
        "baseline_revision": args.baseline,
        "sets": sets,
    }
    tmp = args.out.with_suffix(".json.tmp")
    tmp.write_text(json.dumps(out, indent=2) + "\n")
    tmp.replace(args.out)
    print(f"wrote {args.out}")


if __name__ == "__main__":
    main()
