"""Where one sweep sample's time goes (issue 32): the bundled spur pair analysed as a sweep
sample runs it (`spur_crowned_20_60`, no positions check, no subsurface stresses, no rigid
patterns, no ease-off map, one worker), its stages timed by cProfile's cumulative time, here and at a named
commit (25866f5, the issue's reference) in the same run, each in a fresh interpreter; the
best of N wall times beside them, and the import of the analysis path.

    .venv/bin/python benchmarks/sample_stages.py [--against 25866f5] [--repeat 3]

Prints a table and writes benchmarks/sample_stages.json."""

from __future__ import annotations

import argparse
import json
import subprocess
import sys
from pathlib import Path

from timing import checked_out, source_path

ROOT = Path(__file__).resolve().parent.parent
CASE = ROOT / "cases" / "spur_crowned_20_60.toml"

#: the stages: (name, file suffix, function) whose cumulative time is read; a function
#: "a|b" is either (the first found): contact_fields laid the loaded contacts' fields in
#: one call until FieldSamples split the lines solved (contact_samples) from the splines
#: (FieldSamples.field), so at 25866f5 the first row holds both
STAGES = [
    ("case parsed", "toothcontact/case.py", "parse_case"),
    ("rigid contact cycle (search, fits, patterns)", "contact/cycle.py", "parallel_cycle"),
    ("  of it: rigid patterns", "contact/field.py", "rigid_patterns"),
    ("gap fields of the loaded contacts: lines solved", "contact/field.py",
     "contact_fields|contact_samples"),
    ("  laid on cells from their lines (splines)", "contact/field.py", "field"),
    ("tooth operators and free ends per field", "contact/loaded.py", "_use"),
    ("pressure solves", "contact/pressure.py", "solve_shared"),
    ("  of it: FFT convolutions", "contact/pressure.py", "_convolve"),
    ("loaded contact, all positions", "contact/loaded.py", "loaded_cycle"),
    ("load distribution", "analyses/spur.py", "_load_distribution"),
    ("interference (collision meshes)", "analyses/spur.py", "_spur_interference"),
    ("root stresses", "analyses/rating.py", "root_sections"),
    ("analysis, all stages", "toothcontact/analyses", "analyse"),
]

#: one sample's analysis in a fresh interpreter: prints JSON {wall_s (best of REPEAT),
#: stages {name: cumulative s or None}, import_s}
PROBE = """
import time
start = time.perf_counter()
import cProfile, json, pstats, tomllib
from toothcontact.analyses import analyse
from toothcontact.case import parse_case
from toothcontact.parallel import workers
import_s = time.perf_counter() - start
raw = tomllib.load(open({case!r}, "rb"))
raw.setdefault("analysis", {{}}).update(positions_check=False, subsurface=False,
                                        rigid_patterns=False, ease_off=False)
while True:                  # a tree before some of these settings: without them
    try:
        parse_case(raw)
        break
    except Exception as exc:
        named = [key for key in list(raw["analysis"]) if key in str(exc)]
        if not named:
            raise
        raw["analysis"].pop(named[0])
walls = []
with workers(1):
    for _ in range({repeat}):
        start = time.perf_counter()
        analyse(parse_case(raw))
        walls.append(time.perf_counter() - start)
    profile = cProfile.Profile()
    profile.runcall(lambda: analyse(parse_case(raw)))
stats = pstats.Stats(profile).stats
stages = {{}}
for name, suffix, function in {stages!r}:
    found = None
    for one in function.split("|"):
        times = [ct for (path, _, fn), (_, _, _, ct, _) in stats.items()
                 if (path.endswith(suffix) or path.endswith(suffix + ".py")
                     or path.endswith(suffix + "/__init__.py")) and fn == one]
        if times:
            found = max(times)
            break
    stages[name] = found
print(json.dumps({{"wall_s": min(walls), "stages": stages, "import_s": import_s}}))
"""


def probe(source: Path, repeat: int) -> dict:
    code = PROBE.format(case=str(CASE), repeat=repeat, stages=STAGES)
    env = source_path(source)
    done = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                          env=env, cwd=source)
    if done.returncode:
        raise SystemExit(f"{source}: {done.stderr.strip().splitlines()[-1]}")
    return json.loads(done.stdout.strip().splitlines()[-1])


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--against", default="25866f5")
    parser.add_argument("--repeat", type=int, default=3)
    args = parser.parse_args()
    commit = subprocess.run(["git", "rev-parse", "--short", "HEAD"], cwd=ROOT,
                            capture_output=True, text=True, check=True).stdout.strip()
    with checked_out(args.against) as old:
        before = probe(old, args.repeat)
    now = probe(ROOT, args.repeat)
    print(f"one sweep sample of {CASE.stem} on one worker: {commit} against {args.against}")
    print(f"{'stage':48s} {args.against:>10s} {commit:>10s}")
    for name, *_ in STAGES:
        cells = [f"{r['stages'][name]:10.2f}" if r["stages"][name] is not None else
                 f"{'-':>10s}" for r in (before, now)]
        print(f"{name:48s} {cells[0]} {cells[1]}")
    print(f"{'wall time, best of ' + str(args.repeat) + ' (s)':48s} {before['wall_s']:10.2f} "
          f"{now['wall_s']:10.2f}")
    print(f"{'import of the analysis path (s)':48s} {before['import_s']:10.2f} "
          f"{now['import_s']:10.2f}")
    record = {"case": CASE.stem, "commit": commit, "against": args.against,
              "repeat": args.repeat, "before": before, "now": now,
              "note": "stage times are cProfile's cumulative seconds in one profiled run "
                      "(the profiler adds about 15 %); wall times unprofiled"}
    (ROOT / "benchmarks" / "sample_stages.json").write_text(json.dumps(record, indent=1) + "\n")


if __name__ == "__main__":
    main()
