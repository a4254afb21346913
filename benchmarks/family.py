"""A large family of realistic designs, run end to end: the failure count (target 0), the
time per design and the loaded-contact solver's convergence on the cycle's real gap fields
(iterations and final error per contact). Prints a table and writes
benchmarks/family.json.

    .venv/bin/python benchmarks/family.py [--spur N] [--worm N] [--spline N] [--seed S]
        [--workers W] [--defaults]

The designs come from toothcontact.families (the generator the CI family test draws a
small sample from); every design must answer without an exception and keep the invariants
of families.check. By default each runs at the family's small settings (3 positions, 32²
pressure grid); --defaults runs the tool's own default settings instead (slow).
"""

from __future__ import annotations

import argparse
import json
import math
import platform
import time
from concurrent.futures import ProcessPoolExecutor
from pathlib import Path

HERE = Path(__file__).resolve().parent


def run_one(raw: dict) -> dict:
    """One design: its outcome, time and the loaded contacts' iterations and errors."""
    from toothcontact import families
    from toothcontact.analyses import analyse
    from toothcontact.case import CaseError, parse_case
    from toothcontact.views.report import result_document

    start = time.perf_counter()
    record = {"title": raw["title"], "kind": raw["kind"], "design": raw}
    try:
        case = parse_case(raw)
        document = result_document("family", case, raw, analyse(case))
        json.dumps(document, allow_nan=False)
        problems = families.check(raw, document)
        record["outcome"] = "ok" if not problems else "invariant"
        record["problems"] = problems
        rows = document.get("positions") or []
        record["contacts"] = len(rows)
        record["solver"] = [{"status": r.get("bem_status"), "iterations": r.get("bem_iterations"),
                             "relative_error": r.get("bem_relative_error")} for r in rows
                            if r.get("bem_status")]
    except CaseError as exc:
        record["outcome"], record["problems"] = "refused", [str(exc)]
    except Exception as exc:   # noqa: BLE001 - every exception a real design triggers is a bug
        record["outcome"], record["problems"] = "exception", [f"{type(exc).__name__}: {exc}"]
    record["seconds"] = time.perf_counter() - start
    return record


def main() -> None:
    from toothcontact import families

    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--spur", type=int, default=300)
    parser.add_argument("--worm", type=int, default=120)
    parser.add_argument("--spline", type=int, default=90)
    parser.add_argument("--seed", type=int, default=2026)
    parser.add_argument("--workers", type=int, default=2)
    parser.add_argument("--defaults", action="store_true",
                        help="run each design at the tool's default settings")
    args = parser.parse_args()
    designs = (families.spur_designs(args.spur, args.seed)
               + families.worm_designs(args.worm, args.seed + 1)
               + families.spline_designs(args.spline, args.seed + 2))
    if args.defaults:
        for raw in designs:
            del raw["analysis"]
    start = time.perf_counter()
    with ProcessPoolExecutor(args.workers) as pool:
        records = list(pool.map(run_one, designs, chunksize=4))
    wall = time.perf_counter() - start

    rows = []
    for kind in ("spur", "worm", "spline"):
        mine = [r for r in records if r["kind"] == kind]
        if not mine:
            continue
        solver = [s for r in mine for s in r.get("solver", [])]
        solved = [s for s in solver if s["status"] == "solved"]
        iterations = sorted(s["iterations"] for s in solved)
        rows.append({
            "kind": kind, "designs": len(mine),
            "ok": sum(r["outcome"] == "ok" for r in mine),
            "refused": sum(r["outcome"] == "refused" for r in mine),
            "invariant_broken": sum(r["outcome"] == "invariant" for r in mine),
            "exceptions": sum(r["outcome"] == "exception" for r in mine),
            "median_s": _percentile(sorted(r["seconds"] for r in mine), 50),
            "max_s": max(r["seconds"] for r in mine),
            "contacts_loaded": len(solver),
            "solver_failed": sum(s["status"] == "failed" for s in solver),
            "iterations_median": _percentile(iterations, 50),
            "iterations_p95": _percentile(iterations, 95),
            "iterations_max": iterations[-1] if iterations else None,
            "worst_relative_error": max((s["relative_error"] for s in solved), default=None)})
    header = ("kind", "designs", "ok", "refused", "invariant_broken", "exceptions", "median_s",
              "max_s", "contacts_loaded", "solver_failed", "iterations_median",
              "iterations_p95", "iterations_max", "worst_relative_error")
    print(" ".join(f"{h:>12}" for h in header))
    for row in rows:
        print(" ".join(f"{_fmt(row[h]):>12}" for h in header))
    failures = [r for r in records if r["outcome"] != "ok"]
    for r in failures:
        print(f"- {r['title']} ({r['outcome']}): {r['problems'][0][:300]}")
    print(f"{len(failures)} of {len(records)} designs failed; {wall:.0f} s on {args.workers} workers")
    out = {"machine": platform.platform(), "python": platform.python_version(),
           "seed": args.seed, "settings": "defaults" if args.defaults else families.SMALL,
           "wall_s": wall, "table": rows, "failures": failures}
    (HERE / "family.json").write_text(json.dumps(out, indent=1) + "\n")


def _percentile(values: list, q: float):
    if not values:
        return None
    return values[min(len(values) - 1, int(math.ceil(q / 100 * len(values))) - 1)]


def _fmt(value) -> str:
    if value is None:
        return "-"
    if isinstance(value, float):
        return f"{value:.3g}"
    return str(value)


if __name__ == "__main__":
    main()
