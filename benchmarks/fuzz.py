"""Input fuzz (issues 12 and 53): mutated bundled cases through `toothcontact run`, and
mutated bundled sweeps read and planned as `toothcontact sweep` does before any sample
runs, each outcome held to the promise (exit 2 with one line naming a field and nothing
written, or a complete folder with a strict-JSON result of physical figures and no
library warning; never another exit code, never a traceback). A share of the mutations
aims at issue 53's inputs (tests/mutations.py: NAMED, ADDITIONS, SWEEP_ADDITIONS), some of
which must be refused and some answered.

    .venv/bin/python benchmarks/fuzz.py [--count 1200] [--seed 12] [--timeout 60]

Prints a table of outcomes by class and writes benchmarks/fuzz.json with every broken
promise."""

from __future__ import annotations

import argparse
import collections
import json
import platform
import random
import signal
import sys
import tempfile
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "tests"))
import mutations  # noqa: E402

#: the share of the mutated inputs that are sweeps (only planned: a sweep's samples are
#: cases, which the rest exercises)
SWEEPS = 0.1
class _Timeout(BaseException):
    pass


def _alarm(signum, frame):
    raise _Timeout()


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--count", type=int, default=1200)
    parser.add_argument("--seed", type=int, default=12)
    parser.add_argument("--timeout", type=int, default=60, help="seconds per run")
    parser.add_argument("--out", type=Path, default=Path(__file__).with_name("fuzz.json"))
    args = parser.parse_args()
    rng = random.Random(args.seed)
    cases, sweeps = mutations.bundled(), mutations.bundled_sweeps()
    signal.signal(signal.SIGALRM, _alarm)
    counts = collections.Counter()
    broken, slowest, unnamed = [], [], []
    started = time.perf_counter()
    with tempfile.TemporaryDirectory(prefix="fuzz_") as scratch:
        folder = Path(scratch)
        for i in range(args.count):
            sweep = rng.random() < SWEEPS
            if sweep:
                name = rng.choice(sorted(sweeps))
                what, path, raw = mutations.mutate_sweep(sweeps[name], rng)
            else:
                name = rng.choice(sorted(cases))
                what, path, raw = mutations.mutate(mutations.small(cases[name]), rng)
            out_dir = folder / f"out{i}"
            t0 = time.perf_counter()
            signal.alarm(args.timeout)
            try:
                if sweep:
                    code, output = mutations.plan_sweep(raw, folder, f"s{i}")
                    problem = None if code in (0, 2) else f"exit {code}: {output[:300]}"
                else:
                    case_path = mutations.write_case(raw, folder, f"m{i}", name)
                    code, output = mutations.run_cli(case_path, out_dir)
                    problem = mutations.verdict(code, output, out_dir)
            except _Timeout:
                code, output, problem = -1, "", f"still running after {args.timeout} s"
            finally:
                signal.alarm(0)
            seconds = time.perf_counter() - t0
            field = ".".join(map(str, path))
            slowest.append((seconds, name, field, what))
            kind = mutations.classify(code, problem, what)
            outcome = "broken" if kind else {2: "refused", 0: "answered",
                                             1: "answered, check failed",
                                             4: "answered, a stage incomplete"}.get(code,
                                                                                    "broken")
            counts[outcome] += 1
            counts["sweeps" if sweep else "cases"] += 1
            counts["aimed at issue 53"] += what in mutations.MUST_REFUSE | mutations.MUST_ANSWER \
                or any(what == w for w, *_ in mutations.ADDITIONS) \
                or any(what == w for options in mutations.NAMED.values() for w, _ in options)
            if code == 2 and not kind:
                key = next((str(k) for k in reversed(path) if isinstance(k, str)), "")
                named = key in output or "missing" in output and key.split(".")[0] in output
                counts["refused, naming the mutated field"] += bool(named)
                if not named:
                    unnamed.append({"case": name, "field": field, "mutation": what,
                                    "message": output.strip()[-300:]})
            if kind:
                counts[kind] += 1
                broken.append({"case": name, "field": field, "mutation": what, "exit": code,
                               "class": kind, "problem": problem or kind,
                               "message": output.strip()[-300:]})
                print(f"[{i}] {name} {field} ({what}): {kind}: {problem or ''}", flush=True)
    wall = time.perf_counter() - started
    slowest.sort(reverse=True)
    print(f"\n{args.count} mutated inputs, seed {args.seed}, {wall:.0f} s")
    for outcome in ("cases", "sweeps", "aimed at issue 53", "refused",
                    "refused, naming the mutated field", "answered", "answered, check failed",
                    "answered, a stage incomplete", "broken", *mutations.CLASSES):
        print(f"  {outcome:34s} {counts[outcome]:5d}")
    record = {"python": platform.python_version(), "machine": platform.machine(),
              "count": args.count, "seed": args.seed, "timeout_s": args.timeout,
              "wall_s": wall, "outcomes": dict(counts),
              "slowest": [{"seconds": s, "case": c, "field": f, "mutation": w}
                          for s, c, f, w in slowest[:10]],
              "broken": broken, "refused_naming_another_field": unnamed}
    args.out.write_text(json.dumps(record, indent=2) + "\n")


if __name__ == "__main__":
    main()
