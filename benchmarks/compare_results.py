"""Compare two runs' result.json files key by key: every bundled case's result unchanged by a
refactor (issue 54), or the differences listed.

    python benchmarks/compare_results.py OUT_BEFORE OUT_AFTER [--rel 1e-9] [--json FILE]

OUT_* are folders as `toothcontact demo --out` writes them (one folder per case, each with
its result.json). Numbers agree when |a - b| <= rel·max(|a|, |b|) + 1e-12; strings, booleans,
nulls and list lengths must be equal; the keys of --ignore (dotted paths; by default the
run's time and the paths of the case file and the bodies it reads, which differ between
any two checkouts) are not compared. With --cheaper-checks (issue 56: a run from before
its cheaper checks against one after) the differences those checks make on purpose are held
to what they state instead (cheaper_checks): a row's stresses below the contact left out
where it cannot decide (the summary's largest still equal), and the positions check's
refined pressure within its 5 % of the doubled one it replaced.
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


#: the positions check's stated tolerance (analyses.contact.POSITIONS_TOLERANCE)
POSITIONS_TOLERANCE = 0.05
#: the row keys of the stresses below a contact (analyses.contact.SUBSURFACE_KEYS)
SUBSURFACE = ("subsurface_shear_max_MPa", "subsurface_shear_depth_mm",
              "subsurface_von_mises_max_MPa", "subsurface_von_mises_depth_mm")


def cheaper_checks(before: dict, after: dict) -> tuple[dict, dict, list[str]]:
    """Issue 56's cheaper checks taken out of two result documents for the key-by-key
    comparison, and what they state checked instead: each row's stresses below the contact
    where the run after left them out (None: not a contact that can decide), the summary's
    subsurface note and count, the positions check (the refined largest pressure within
    POSITIONS_TOLERANCE of the doubled one, or above it: the finer steps found more) and the
    notes of the positions check. Returns the two documents so reduced and the
    differences from what is stated."""
    import copy

    before, after, out = copy.deepcopy(before), copy.deepcopy(after), []
    for row_a, row_b in zip(before.get("positions") or [], after.get("positions") or []):
        if isinstance(row_b, dict) and all(row_b.get(k) is None for k in SUBSURFACE):
            for key in SUBSURFACE:
                row_a.pop(key, None)
                row_b.pop(key, None)
    for doc in (before, after):
        summary = doc.get("summary") or {}
        summary.pop("subsurface_note", None)
        summary.pop("subsurface_contacts", None)
        doc["notes"] = [n for n in doc.get("notes", []) if not n.startswith("positions:")]
    check_a = (before.get("summary") or {}).pop("positions_check", None)
    check_b = (after.get("summary") or {}).pop("positions_check", None)
    if (check_a is None) != (check_b is None):
        out.append("summary.positions_check: only in one run")
    elif check_a is not None and check_a.get("checked"):
        doubled, refined = check_a["doubled_bem_max_p_max_MPa"], check_b["refined_bem_max_p_max_MPa"]
        if refined < (1.0 - POSITIONS_TOLERANCE) * doubled:
            out.append(f"summary.positions_check: refined {refined:.1f} MPa below the doubled "
                       f"{doubled:.1f} by more than {POSITIONS_TOLERANCE:.0%}")
    return before, after, out


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("before", type=Path)
    ap.add_argument("after", type=Path)
    ap.add_argument("--rel", type=float, default=1e-9)
    ap.add_argument("--json", type=Path, help="write the comparison here")
    ap.add_argument("--ignore", nargs="*", default=list(IGNORED), help="dotted keys not compared")
    ap.add_argument("--cheaper-checks", action="store_true",
                    help="hold issue 56's cheaper checks to what they state (cheaper_checks)")
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
        documents, stated = [json.loads(f.read_text()) for f in files], []
        if args.cheaper_checks:
            *documents, stated = cheaper_checks(*documents)
        count, diffs = differences(*documents, args.rel, ignore=tuple(args.ignore))
        diffs += stated
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
