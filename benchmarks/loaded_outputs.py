"""What the loaded contact's new outputs cost (issue 30): the bundled relieved spur pair's
analysis (no positions check) here with the stresses below the contacts, here without
them, and at a named commit before them, each the best of N fresh interpreters on one
worker; and the subsurface peak of one contact alone: a 30 mm line contact's 980 × 14
cells and a circular contact's 128 × 128.

    .venv/bin/python benchmarks/loaded_outputs.py [--against REV] [--repeat N]

Prints a table and writes benchmarks/loaded_outputs.json."""

from __future__ import annotations

import argparse
import json
import os
import subprocess
import sys
from pathlib import Path

from timing import checked_out, source_path

ROOT = Path(__file__).resolve().parent.parent
CASE = ROOT / "cases" / "spur_relieved_20_60.toml"

#: an analysis of CASE on one worker, its wall time printed; {subsurface} set or left out
ANALYSIS = """
import time, tomllib
from toothcontact.case import parse_case
from toothcontact.analyses import analyse
from toothcontact.parallel import workers
raw = tomllib.load(open({case!r}, "rb"))
raw.setdefault("analysis", {{}}).update(positions_check=False{subsurface})
case = parse_case(raw)
with workers(1):
    start = time.perf_counter()
    analyse(case)
print(time.perf_counter() - start)
"""

#: one contact's subsurface peak, its wall time printed (the best of 5 after a first call)
PEAK = """
import time
import numpy as np
from toothcontact.contact.subsurface import peak
x = np.linspace(-1.3, 1.3, {across})
if {line}:
    p = np.repeat(np.sqrt(np.clip(1 - x * x, 0, None))[None, :], 980, axis=0) * 2000.0
    d = (30.0 / 980, 0.26 / {across})          # 30 mm long, 0.2 mm wide
else:
    X, Y = np.meshgrid(x, x, indexing="ij")
    p = np.sqrt(np.clip(1 - X * X - Y * Y, 0, None)) * 2000.0
    d = (2.6 / {across},) * 2
peak(p, *d, 0.3)
times = []
for _ in range(5):
    start = time.perf_counter()
    peak(p, *d, 0.3)
    times.append(time.perf_counter() - start)
print(min(times))
"""


def best_of(code: str, src: Path, repeat: int) -> float:
    """The least time (s) a fresh interpreter on `src` prints for `code`, of `repeat`."""
    env = {**source_path(src.parent), "OMP_NUM_THREADS": "1"}
    return min(float(subprocess.run([sys.executable, "-c", code], env=env, check=True,
                                    capture_output=True, text=True, cwd=src.parent)
                     .stdout.split()[-1]) for _ in range(repeat))


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--against", default="ec6e1e2", help="a commit before the outputs")
    parser.add_argument("--repeat", type=int, default=3)
    args = parser.parse_args()
    src = ROOT / "src"
    rows = []
    with checked_out(args.against) as old:
        for name, code, where in (
                ("analysis, subsurface stresses", ANALYSIS.format(case=str(CASE),
                                                                  subsurface=""), src),
                ("analysis, no subsurface stresses", ANALYSIS.format(
                    case=str(CASE), subsurface=", subsurface=False"), src),
                (f"analysis at {args.against}", ANALYSIS.format(case=str(CASE),
                                                                 subsurface=""),
                 old / "src")):
            rows.append({"step": name, "seconds": best_of(code, where, args.repeat)})
    for name, across, line in (("one line contact, 980 x 14 cells", 14, True),
                               ("one circular contact, 128 x 128 cells", 128, False)):
        rows.append({"step": name, "seconds": best_of(
            PEAK.format(across=across, line=line), src, args.repeat)})
    print(f"{'step':44s} {'s':>8s}")
    for row in rows:
        print(f"{row['step']:44s} {row['seconds']:8.3f}")
    (ROOT / "benchmarks" / "loaded_outputs.json").write_text(json.dumps(
        {"case": CASE.name, "against": args.against, "repeat": args.repeat,
         "machine_cores": os.cpu_count(), "rows": rows}, indent=2) + "\n")


if __name__ == "__main__":
    main()
