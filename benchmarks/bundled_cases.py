"""Each bundled case's analysis time, here and at a named commit in the same run: what a
user waits for on `toothcontact run` (before reports and pictures) and most of what the
demo and the test suite pay for (issue 54 item 6, issue 56).

    .venv/bin/python benchmarks/bundled_cases.py [--against REV] [--cases NAME ...]

Each case is analysed in a fresh interpreter on one worker (toothcontact.parallel.workers(1)),
its source tree first on PYTHONPATH; the wall time of analyse(load_case(path)) is the best of
--repeat. Prints a table and writes benchmarks/bundled_cases.json."""

from __future__ import annotations

import argparse
import json
import platform
import subprocess
import sys
from pathlib import Path

from timing import checked_out, source_path

ROOT = Path(__file__).resolve().parent.parent
JSON_OUT = Path(__file__).with_suffix(".json")

PROBE = """
import json, time
from toothcontact.analyses import analyse
from toothcontact.case import load_case
from toothcontact.parallel import workers
best = float("inf")
with workers(1):
    for _ in range({repeat}):
        start = time.perf_counter()
        analyse(load_case({path!r})[0])
        best = min(best, time.perf_counter() - start)
print(json.dumps(best))
"""


def case_time(tree: Path, path: Path, repeat: int) -> float | None:
    """The best wall time (s) of the case's analysis with `tree`'s source; None if it fails."""
    done = subprocess.run([sys.executable, "-c", PROBE.format(path=str(path), repeat=repeat)],
                          env=source_path(tree), capture_output=True, text=True, cwd=tree)
    return json.loads(done.stdout.strip().splitlines()[-1]) if done.returncode == 0 else None


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--against", default="HEAD~1", help="the commit (or a tree) to compare")
    ap.add_argument("--cases", nargs="*", help="bundled case names (default: all)")
    ap.add_argument("--repeat", type=int, default=1)
    ap.add_argument("--json", type=Path, default=JSON_OUT)
    args = ap.parse_args()
    paths = sorted((ROOT / "cases").glob("*.toml"))
    if args.cases:
        paths = [p for p in paths if p.stem in args.cases]
    rows = {}
    with checked_out(args.against) as old:
        for path in paths:
            rows[path.stem] = {"here_s": case_time(ROOT, path, args.repeat),
                               "against_s": case_time(old, path, args.repeat)}
            r = rows[path.stem]
            print(f"{path.stem:40} {r['here_s'] or float('nan'):8.2f} "
                  f"{r['against_s'] or float('nan'):8.2f}", flush=True)
    here = sum(r["here_s"] or 0.0 for r in rows.values())
    against = sum(r["against_s"] or 0.0 for r in rows.values())
    print(f"{'all cases':40} {here:8.2f} {against:8.2f}  (here, {args.against})")
    args.json.write_text(json.dumps(dict(
        benchmark="bundled_cases", against=args.against, repeat=args.repeat,
        machine=dict(platform=platform.platform(), python=platform.python_version()),
        cases=rows, total_here_s=here, total_against_s=against), indent=1))


if __name__ == "__main__":
    main()
