"""Start-up times of the command line and the analysis path, here and at a named commit, in
one run: `toothcontact --help`, importing the analysis path (toothcontact.analyses), and
reading one case (the unit registry and the schema's first use) and analysing the Hertz
sphere-on-flat case, each the best of N fresh interpreters.

    .venv/bin/python benchmarks/startup.py [--against REV] [--repeat N]

The commit beside it is checked out with `git worktree` into a temporary folder and run on
this environment (PYTHONPATH=its src). Prints a table and writes benchmarks/startup.json."""

from __future__ import annotations

import argparse
import json
import subprocess
import sys
from pathlib import Path

from timing import checked_out, source_path

ROOT = Path(__file__).resolve().parent.parent

#: what is timed, each a fresh interpreter's whole run (s)
STEPS = {
    "--help": ["-m", "toothcontact", "--help"],
    "import toothcontact.analyses": ["-c", "import toothcontact.analyses"],
    "import, read and analyse a Hertz case": [
        "-c", "from toothcontact import runner; "
              "runner.analyse_file(runner.bundled_cases_dir() / 'hertz_sphere_on_flat.toml')"],
}


def best_of(args: list[str], src: Path, repeat: int) -> float:
    """The least wall time (s) of `repeat` fresh interpreters running `args` on `src`."""
    import time

    env = source_path(src.parent)
    times = []
    for _ in range(repeat):
        start = time.perf_counter()
        subprocess.run([sys.executable, *args], env=env, check=True, capture_output=True,
                       cwd=src.parent)
        times.append(time.perf_counter() - start)
    return min(times)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--against", default="52d87ba", help="the commit beside this one")
    parser.add_argument("--repeat", type=int, default=7)
    args = parser.parse_args()
    rows = []
    with checked_out(args.against) as old:
        for name, step in STEPS.items():
            rows.append({"step": name,
                         "here_s": best_of(step, ROOT / "src", args.repeat),
                         f"{args.against}_s": best_of(step, old / "src", args.repeat)})
    print(f"{'step':42s} {'here (s)':>9s} {args.against + ' (s)':>12s}")
    for row in rows:
        print(f"{row['step']:42s} {row['here_s']:9.3f} {row[args.against + '_s']:12.3f}")
    out = Path(__file__).with_suffix(".json")
    out.write_text(json.dumps({"against": args.against, "repeat": args.repeat,
                               "python": sys.version.split()[0], "rows": rows}, indent=2) + "\n")
    print(f"wrote {out}")


if __name__ == "__main__":
    main()
