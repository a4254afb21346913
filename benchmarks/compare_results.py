"""Compare two runs' result.json files key by key: every bundled case's result unchanged by a
refactor (issue 54), or the differences listed.

    python benchmarks/compare_results.py OUT_BEFORE OUT_AFTER [--rel 1e-9] [--json FILE]

OUT_* are folders as `toothcontact demo --out` writes them (one folder per case, each with
its result.json). Numbers agree when |a - b| <= rel·max(|a|, |b|) + 1e-12; strings, booleans,
nulls and list lengths must be equal; the keys of --ignore (dotted paths; by default the
run's time and the paths of the case file and the bodies it reads, which differ between
any two checkouts) are not compared.
Prints a table (case, values compared, differing) and
the first differences; exit 1 where any case differs or is missing from either run.
"""

from __future__ import annotations

import argparse
import json
import math
import sys
from pathlib import Path


#: what differs between any two runs of the same case (dotted paths)
IGNORED = ("provenance.run_at_utc", "provenance.case_file", "bodies.pinion.file",
           "bodies.gear.file")


def differences(a, b, rel: float, path: str = "", ignore=IGNORED) -> tuple[int, list[str]]:
    """(values compared, differences as 'path: a != b') between two JSON values."""
    if isinstance(a, dict) and isinstance(b, dict):
        count, out = 0, []
        for key in sorted(set(a) | set(b)):
            where = f"{path}.{key}" if path else str(key)
            if where in ignore:
                continue
            if key not in a or key not in b:
                out.append(f"{where}: only in {'after' if key not in a else 'before'}")
                continue
            n, d = differences(a[key], b[key], rel, where, ignore)
            count, out = count + n, out + d
        return count, out
    if isinstance(a, list) and isinstance(b, list):
        if len(a) != len(b):
            return 1, [f"{path}: {len(a)} items != {len(b)}"]
        count, out = 0, []
        for k, (x, y) in enumerate(zip(a, b)):
            n, d = differences(x, y, rel, f"{path}[{k}]", ignore)
            count, out = count + n, out + d
        return count, out
    numbers = (int, float)
    if isinstance(a, numbers) and isinstance(b, numbers) and not isinstance(a, bool) \
            and not isinstance(b, bool):
        same = a == b or (math.isfinite(a) and math.isfinite(b)
                          and abs(a - b) <= rel * max(abs(a), abs(b)) + 1e-12)
        return 1, [] if same else [f"{path}: {a!r} != {b!r}"]
    return 1, [] if a == b else [f"{path}: {a!r} != {b!r}"]


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("before", type=Path)
    ap.add_argument("after", type=Path)
    ap.add_argument("--rel", type=float, default=1e-9)
    ap.add_argument("--json", type=Path, help="write the comparison here")
    ap.add_argument("--ignore", nargs="*", default=list(IGNORED), help="dotted keys not compared")
    args = ap.parse_args()
    cases = sorted({p.parent.name for run in (args.before, args.after)
                    for p in run.glob("*/result.json")})
    report, failed = {}, False
    print(f"{'case':45} {'compared':>9} {'differing':>9}")
    for case in cases:
        files = [run / case / "result.json" for run in (args.before, args.after)]
        if not all(f.exists() for f in files):
            report[case] = dict(missing=[str(f) for f in files if not f.exists()])
            print(f"{case:45} {'missing in ' + str([f.parent.parent for f in files if not f.exists()]):>19}")
            failed = True
            continue
        count, diffs = differences(*(json.loads(f.read_text()) for f in files), args.rel,
                                   ignore=tuple(args.ignore))
        report[case] = dict(compared=count, differing=len(diffs), first=diffs[:20])
        failed |= bool(diffs)
        print(f"{case:45} {count:9d} {len(diffs):9d}")
        for line in diffs[:5]:
            print(f"    {line}")
    if args.json:
        args.json.write_text(json.dumps(dict(rel=args.rel, cases=report), indent=1))
    return 1 if failed or not cases else 0


if __name__ == "__main__":
    sys.exit(main())
