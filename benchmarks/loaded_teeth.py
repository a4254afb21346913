"""The loaded contact beside an earlier commit's, on the bundled spur cases, in one run: the
loaded stage's time (analyses.contact.loaded_sections, the load sharing and every pressure solve)
and the whole analysis without the interference check, best of `--repeat`. The earlier
code is taken from git (`git archive`) and run in a subprocess of this run. Prints a table
and writes benchmarks/<out>: loaded_teeth.json records the tooth bending along the face
(issue 14) beside the code it replaced (a7404bb); loaded_free_ends.json the free face ends
and snapped fields (issue 27) beside 25866f5.

    .venv/bin/python benchmarks/loaded_teeth.py [--repeat 3] [--before a7404bb] [--out F]
"""

from __future__ import annotations

import argparse
import json
import platform
import subprocess
import sys
import tempfile
from pathlib import Path

HERE = Path(__file__).resolve().parent
ROOT = HERE.parent
CASES = ("spur_crowned_20_60", "helical_offcentre_crown_tip_relief")

#: runs inside the interpreter for one source tree: prints JSON {case: [stage s, total s]}
PROBE = r"""
import json, sys, time
from pathlib import Path
from toothcontact import analyses
from toothcontact.case import load_case
try:                                   # the analyses package (one module per kind)
    from toothcontact.analyses import contact as owner
    name = "loaded_sections"
except ImportError:                    # before it: one module
    owner, name = analyses, "_loaded_sections"
stage = []
inner = getattr(owner, name)
def timed(*args, **kwargs):
    start = time.perf_counter()
    try:
        return inner(*args, **kwargs)
    finally:
        stage.append(time.perf_counter() - start)
setattr(owner, name, timed)
out = {}
for name in sys.argv[2:]:
    case = load_case(Path(sys.argv[1]) / f"{name}.toml")[0]
    case = case.model_copy(update={"analysis": case.analysis.model_copy(
        update={"interference": False})})
    best = None
    for _ in range(REPEAT):
        stage.clear()
        start = time.perf_counter()
        analyses.analyse(case)
        run = (stage[-1], time.perf_counter() - start)
        best = run if best is None or run[0] < best[0] else best
    out[name] = best
print(json.dumps(out))
"""


def probe(source: Path, repeat: int) -> dict:
    """{case: (loaded stage s, analysis s)} with the package at `source` (a src folder)."""
    code = PROBE.replace("REPEAT", str(repeat))
    env = {"PYTHONPATH": str(source), "PATH": "/usr/bin:/bin"}
    done = subprocess.run([sys.executable, "-c", code, str(ROOT / "cases"), *CASES],
                          capture_output=True, text=True, env=env, check=True)
    return json.loads(done.stdout.strip().splitlines()[-1])


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeat", type=int, default=3)
    parser.add_argument("--before", default="a7404bb")
    parser.add_argument("--out", default="loaded_teeth.json")
    args = parser.parse_args()
    with tempfile.TemporaryDirectory() as tmp:
        archive = subprocess.run(["git", "-C", str(ROOT), "archive", args.before, "src"],
                                 capture_output=True, check=True).stdout
        subprocess.run(["tar", "-x", "-C", tmp], input=archive, check=True)
        before = probe(Path(tmp) / "src", args.repeat)
    now = probe(ROOT / "src", args.repeat)
    rows = [{"case": name, "before_loaded_s": before[name][0], "now_loaded_s": now[name][0],
             "loaded_ratio": now[name][0] / before[name][0],
             "before_analysis_s": before[name][1], "now_analysis_s": now[name][1]}
            for name in CASES]
    print(f"{'case':34s} {'loaded before':>14s} {'loaded now':>11s} {'ratio':>6s} "
          f"{'analysis before':>16s} {'now':>6s}")
    for r in rows:
        print(f"{r['case']:34s} {r['before_loaded_s']:14.2f} {r['now_loaded_s']:11.2f} "
              f"{r['loaded_ratio']:6.2f} {r['before_analysis_s']:16.2f} {r['now_analysis_s']:6.2f}")
    record = {"before": args.before, "repeat": args.repeat, "machine": platform.platform(),
              "python": platform.python_version(), "rows": rows}
    (HERE / args.out).write_text(json.dumps(record, indent=2) + "\n")


if __name__ == "__main__":
    main()
