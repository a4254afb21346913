"""Sweeps (issue 15): the time of one sample and how a sweep scales, in one run.

1. Per sample: the full loaded spur case (bundled `spur_crowned_20_60`: 21 positions, 128²
   pressure grid, interference on) with this tree's code beside the first release's
   (commit 8744259, taken from git and run in a subprocess of this run), best of
   `--repeat`, each as it runs by default on this machine (the first release's transforms
   on every core, this tree's positions in forked processes), and this tree's on one core
   (what a sweep worker gets on a machine it fills); and the physical limit of the solves,
   the time spent inside the FFT library (pocketfft's transforms, by cProfile, on one
   core).
2. Scale: a `--samples` Monte Carlo of the same case (slope normal 0.8 ± 0.3 mrad, crown
   radius uniform 3000-5000 mm, Latin hypercube) on a local Dask cluster of 1 and of 2
   workers: wall time, samples per second, speed-up; the two tables must be identical.
3. Faults: a `--killed-samples` sweep on a Dask scheduler and two workers started as
   separate processes (`dask scheduler`, `dask worker`), one worker SIGKILLed once the
   first sample is in: the sweep completes and its table equals a local run's.

Prints a table and writes benchmarks/sweep.json; `--parts` runs some of the three and keeps
the others' last record (each part records the commit it measured).

    .venv/bin/python benchmarks/sweep.py [--samples 200] [--killed-samples 40] [--repeat 3]
                                         [--parts per_sample scaling killed_worker]
"""

from __future__ import annotations

import argparse
import json
import os
import platform
import signal
import subprocess
import sys
import tempfile
import time
from pathlib import Path

HERE = Path(__file__).resolve().parent
ROOT = HERE.parent
CASE = "spur_crowned_20_60"
FIRST_RELEASE = "8744259"

#: runs inside the interpreter for one source tree: prints JSON {best_s, one_worker_s,
#: fft_s}: the best time as the tree runs by default (the first release: its transforms on
#: every core; now: the positions on every core, in forked processes), on one worker where
#: the tree can be told (None for the first release), and the time inside the FFT library
#: on one worker (cProfile sees only the thread it runs in)
PROBE = r"""
import cProfile, contextlib, json, pstats, sys, time
from pathlib import Path
from toothcontact import analyses
from toothcontact.case import load_case
try:
    from toothcontact.parallel import workers
except ImportError:
    workers = None
case = load_case(Path(sys.argv[1]) / "CASE.toml")[0]

def best(context):
    found = None
    for _ in range(REPEAT):
        with context():
            start = time.perf_counter()
            analyses.analyse(case)
            found = min(found or 1e9, time.perf_counter() - start)
    return found

one = (lambda: workers(1)) if workers else contextlib.nullcontext
profile = cProfile.Profile()
with one():
    profile.runcall(analyses.analyse, case)
stats = pstats.Stats(profile).stats
fft = sum(tt for (path, _, name), (_, _, tt, _, _) in stats.items()
          if "pocketfft" in path or name.startswith("<built-in method scipy.fft._pocketfft"))
print(json.dumps({"best_s": best(contextlib.nullcontext),
                  "one_worker_s": best(one) if workers else None, "fft_s": fft}))
"""

SWEEP = """kind = "sweep"
title = "benchmark: slope and crown radius toleranced"
base = "{base}"
samples = {samples}
seed = 1
sampling = "latin_hypercube"
[[tolerance]]
field = "misalignment.slope"
distribution = "normal"
mean = "0.0008"
std = "0.0003"
[[tolerance]]
field = "pinion.crown.radius"
distribution = "uniform"
low = "3000 mm"
high = "5000 mm"
"""


def probe(source: Path, cases: Path, repeat: int) -> dict:
    """{best_s, fft_s} of the bundled case with the package at `source` (a src folder)."""
    code = PROBE.replace("REPEAT", str(repeat)).replace("CASE", CASE)
    env = {"PYTHONPATH": str(source), "PATH": "/usr/bin:/bin"}
    done = subprocess.run([sys.executable, "-c", code, str(cases)], capture_output=True,
                          text=True, env=env, check=True)
    return json.loads(done.stdout.strip().splitlines()[-1])


def per_sample(repeat: int) -> dict:
    with tempfile.TemporaryDirectory() as tmp:
        archive = subprocess.run(["git", "-C", str(ROOT), "archive", FIRST_RELEASE, "src",
                                  "cases"], capture_output=True, check=True).stdout
        subprocess.run(["tar", "-x", "-C", tmp], input=archive, check=True)
        before = probe(Path(tmp) / "src", Path(tmp) / "cases", repeat)
    now = probe(ROOT / "src", ROOT / "cases", repeat)
    return {"case": CASE, "first_release": FIRST_RELEASE, "before_s": before["best_s"],
            "now_s": now["best_s"], "speed_up": before["best_s"] / now["best_s"],
            "now_one_worker_s": now["one_worker_s"],
            "one_worker_speed_up": before["best_s"] / now["one_worker_s"],
            "now_fft_s": now["fft_s"], "now_fft_share": now["fft_s"] / now["one_worker_s"]}


def sweep_file(folder: Path, samples: int) -> Path:
    path = folder / f"mc_{samples}.toml"
    path.write_text(SWEEP.format(base=(ROOT / "cases" / f"{CASE}.toml").as_posix(),
                                 samples=samples))
    return path


def table(written) -> list[dict]:
    import pyarrow.parquet as pq

    return pq.read_table(written[0]).to_pylist()


def scaling(samples: int, folder: Path) -> dict:
    from toothcontact import runner

    path = sweep_file(folder, samples)
    out, tables = {}, {}
    for workers in (1, 2):
        start = time.perf_counter()
        _, written = runner.run_sweep(path, folder / f"workers_{workers}", workers=workers)
        wall = time.perf_counter() - start
        tables[workers] = table(written)
        out[workers] = {"wall_s": wall, "samples_per_s": samples / wall,
                        "ok": sum(r["status"] == "ok" for r in tables[workers])}
    return {"samples": samples, "one_worker": out[1], "two_workers": out[2],
            "speed_up": out[1]["wall_s"] / out[2]["wall_s"],
            "same_table": tables[1] == tables[2]}


def killed_worker(samples: int, folder: Path) -> dict:
    from toothcontact import runner
    from toothcontact.sweep.run import separate_processes

    path = sweep_file(folder, samples)
    with separate_processes(folder) as (where, workers):
        killed = []

        def kill_one(record):
            if not killed:
                workers[0].send_signal(signal.SIGKILL)
                killed.append(record["sample"])

        start = time.perf_counter()
        _, written = runner.run_sweep(path, folder / "scheduler", scheduler=where,
                                      on_done=kill_one)
        wall = time.perf_counter() - start
        remote = table(written)
    _, local = runner.run_sweep(path, folder / "local", workers=2)
    return {"samples": samples, "wall_s": wall, "killed_after_sample": killed[0],
            "answered": sum(r["status"] == "ok" for r in remote),
            "complete": [r["sample"] for r in remote] == list(range(samples)),
            "same_table_as_local": remote == table(local)}


PARTS = ("per_sample", "scaling", "killed_worker")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--samples", type=int, default=200)
    parser.add_argument("--killed-samples", type=int, default=40)
    parser.add_argument("--repeat", type=int, default=3)
    parser.add_argument("--parts", nargs="+", choices=PARTS, default=list(PARTS))
    args = parser.parse_args()
    path = HERE / "sweep.json"
    record = json.loads(path.read_text()) if path.exists() else {}
    record["machine"] = (f"{platform.machine()}, {os.cpu_count()} cores, Python "
                         f"{platform.python_version()}")
    commit = subprocess.run(["git", "-C", str(ROOT), "rev-parse", "--short", "HEAD"],
                            capture_output=True, text=True).stdout.strip()
    with tempfile.TemporaryDirectory() as tmp:
        runs = {"per_sample": lambda: per_sample(args.repeat),
                "scaling": lambda: scaling(args.samples, Path(tmp)),
                "killed_worker": lambda: killed_worker(args.killed_samples, Path(tmp))}
        for part in args.parts:
            record[part] = {**runs[part](), "commit": commit}
    s, sc, k = (record.get(part) for part in PARTS)
    if s:
        print(f"{'per sample (' + CASE + ')':44} {'first release':>14} {'now':>8} {'speed-up':>9}")
        print(f"{'full loaded analysis, interference on':44} {s['before_s']:13.2f}s "
              f"{s['now_s']:7.2f}s {s['speed_up']:8.2f}x   ({s.get('commit', '?')})")
        if s.get("now_one_worker_s"):
            print(f"{'  on one core (a sweep worker)':44} {'':14} "
                  f"{s['now_one_worker_s']:7.2f}s {s['one_worker_speed_up']:8.2f}x")
        print(f"{'  of which inside the FFT library (limit)':44} {'':14} {s['now_fft_s']:7.2f}s "
              f"({s['now_fft_share']:.0%} of one core's)")
    if sc:
        print(f"\n{sc['samples']}-sample Monte Carlo {'wall':>10} {'samples/s':>10}"
              f"   ({sc.get('commit', '?')})")
        for name in ("one_worker", "two_workers"):
            print(f"{name.replace('_', ' '):24} {sc[name]['wall_s']:9.1f}s "
                  f"{sc[name]['samples_per_s']:10.3f}")
        print(f"speed-up {sc['speed_up']:.2f}x, same table: {sc['same_table']}")
    if k:
        print(f"\nseparate scheduler, one of two workers killed after sample "
              f"{k['killed_after_sample']}: {k['answered']}/{k['samples']} answered in "
              f"{k['wall_s']:.1f}s, complete: {k['complete']}, same table as local: "
              f"{k['same_table_as_local']}   ({k.get('commit', '?')})")
    path.write_text(json.dumps(record, indent=2) + "\n")


if __name__ == "__main__":
    main()
