"""Sweeps (issues 15 and 32): the time of one sample, how a sweep scales, what it costs
besides its samples, and what a 1,000-sample study would take, in one run.

1. Per sample: the bundled crowned spur pair (`spur_crowned_20_60`: 21 positions,
   interference on) analysed as a sweep sample runs it (no positions check, no stresses
   below the contacts, no rigid patterns, no ease-off map) on one worker, best of
   `--repeat` in a fresh interpreter (sample_stages.probe) over ROUNDS rounds, with this
   tree's code beside `--against` (25866f5, issue 32's reference) checked out and probed
   in turn; and one design's latency: the case as bundled (positions check and subsurface
   stresses on) on all of the machine's cores, both trees.
2. Scale: a Monte Carlo of the same case (slope normal 0.8 ± 0.3 mrad, crown radius
   uniform 3000-5000 mm, Latin hypercube) on a local Dask cluster of each `--workers`
   count: `--samples` samples and one round (as many samples as workers), both timed
   whole, each in a fresh interpreter as the `sweep` command runs it, so that the rate is the slope between them and the sweep's fixed cost (cluster
   start and close, imports, planning, the last statistics, figures and report) their
   intercept; samples/s, the efficiency against W times one worker's rate and against W
   cores each at part 1's one-core sample time, the tables identical across the counts,
   and the projection of a 1,000-sample study (fixed + 1000 / rate).
3. Alone: W fresh interpreters probing one sample each at once (no Dask), for each
   `--workers` count: what W concurrent samples cost on this machine's shared caches,
   memory bandwidth, clock and (where its cores are hyperthreads) execution units; and W
   pure-Python spins at once, what the machine gives W processes that share nothing.
4. A cluster of separate processes (`dask scheduler` and the largest `--workers` count of
   `dask worker --nthreads 1`, as a deployment runs them): the same Monte Carlo timed as
   in part 2 (the cluster started before the timing, so its fixed cost excludes the start).
5. Faults: a `--killed-samples` sweep on a Dask scheduler and two workers started as
   separate processes (`dask scheduler`, `dask worker`), one worker SIGKILLed once the
   first sample is in: the sweep completes and its table equals a local run's.

Prints a table and writes benchmarks/sweep.json (or `--record`: another machine's);
`--parts` runs some of them and keeps the others' last record (each part records the
commit it measured). `--against` takes a commit or a folder holding that commit's tree (a
machine without the repository's history).

    .venv/bin/python benchmarks/sweep.py [--samples 40] [--workers 1 2] [--repeat 3]
        [--against 25866f5] [--killed-samples 40] [--record benchmarks/sweep.json]
        [--parts per_sample scaling alone cluster killed_worker]
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
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path

from sample_stages import probe as sample_probe
from timing import checked_out, source_path

HERE = Path(__file__).resolve().parent
ROOT = HERE.parent
CASE = "spur_crowned_20_60"
#: the study the projection is for (samples)
STUDY = 1000

#: one design's latency in a fresh interpreter: the bundled case as it is (positions check
#: and subsurface stresses on) on every core of this machine, best of REPEAT: prints JSON
#: {"wall_s"}
LATENCY = """
import json, time, tomllib
from toothcontact.analyses import analyse
from toothcontact.case import parse_case
raw = tomllib.load(open({case!r}, "rb"))
walls = []
for _ in range({repeat}):
    start = time.perf_counter()
    analyse(parse_case(raw))
    walls.append(time.perf_counter() - start)
print(json.dumps({{"wall_s": min(walls)}}))
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


def latency(source: Path, repeat: int) -> float:
    """One design's best wall time (s) with the tree at `source` (a repository root)."""
    code = LATENCY.format(case=str(source / "cases" / f"{CASE}.toml"), repeat=repeat)
    done = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                          env=source_path(source), cwd=source)
    if done.returncode:
        raise SystemExit(f"{source}: {done.stderr.strip().splitlines()[-1]}")
    return json.loads(done.stdout.strip().splitlines()[-1])["wall_s"]


#: rounds of the two trees' sample probes, taken in turn (a shared machine's speed drifts
#: by 10-20 % over minutes: each tree's best is taken over the same minutes)
ROUNDS = 3


def per_sample(repeat: int, against: str) -> dict:
    before, now = [], []
    with checked_out(against) as old:
        for _ in range(ROUNDS):
            before.append(sample_probe(old, repeat))
            now.append(sample_probe(ROOT, repeat))
        before_latency = latency(old, repeat)
    now_latency = latency(ROOT, repeat)
    before_s, now_s = (min(r["wall_s"] for r in runs) for runs in (before, now))
    return {"case": CASE, "against": against, "rounds": ROUNDS,
            "before_s": before_s, "now_s": now_s, "speed_up": before_s / now_s,
            "before_import_s": min(r["import_s"] for r in before),
            "now_import_s": min(r["import_s"] for r in now),
            "before_latency_s": before_latency, "now_latency_s": now_latency,
            "cores": os.cpu_count()}


def sweep_file(folder: Path, samples: int) -> Path:
    folder.mkdir(parents=True, exist_ok=True)
    path = folder / f"mc_{samples}.toml"
    path.write_text(SWEEP.format(base=(ROOT / "cases" / f"{CASE}.toml").as_posix(),
                                 samples=samples))
    return path


def table(written) -> list[dict]:
    import pyarrow.parquet as pq

    return pq.read_table(written[0]).to_pylist()


#: one sweep in a fresh interpreter, as the `sweep` command runs one: a local cluster's
#: workers fork from a server that lives as long as the process that started it, so a sweep
#: after another in one process would find it started
SWEEP_RUN = """
from toothcontact import runner
_, written = runner.run_sweep({path!r}, {out!r}, **{where!r})
print(written[0])
"""


def timed_sweep(path: Path, out: Path, **where) -> tuple[float, list[dict]]:
    """A sweep file run on `workers=` local workers or on a `scheduler=`, in a fresh
    interpreter: its wall time (s, the interpreter's start and imports included) and its
    table."""
    code = SWEEP_RUN.format(path=str(path), out=str(out), where=where)
    start = time.perf_counter()
    done = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                          env=source_path(ROOT))
    wall = time.perf_counter() - start
    if done.returncode:
        raise SystemExit(f"sweep {path}: {done.stderr.strip().splitlines()[-1]}")
    return wall, table([done.stdout.strip().splitlines()[-1]])


def rated(samples: int, count: int, folder: Path, **where) -> tuple[dict, list[dict]]:
    """One round (`count` samples, one per worker) and `samples` samples, each timed whole:
    the rate is the slope between them, the fixed cost their intercept (see the module)."""
    one_round, _ = timed_sweep(sweep_file(folder, count), folder / "round", **where)
    wall, rows = timed_sweep(sweep_file(folder, samples), folder / "all", **where)
    rate = (samples - count) / (wall - one_round)
    fixed = max(one_round - count / rate, 0.0)
    return {"wall_s": wall, "samples_per_s": samples / wall, "rate_samples_per_s": rate,
            "one_round_wall_s": one_round, "fixed_s": fixed, "study_s": fixed + STUDY / rate,
            "ok": sum(r["status"] == "ok" for r in rows)}, rows


def scaling(samples: int, counts: list[int], folder: Path, one_core_s: float | None) -> dict:
    """Each worker count's sweep (see the module); `one_core_s`: one sample's time on one
    core (part 1), against which each count's rate is also judged."""
    out, tables = {}, {}
    for workers in counts:
        out[str(workers)], tables[workers] = rated(samples, workers, folder / str(workers),
                                                   workers=workers)
    single = out.get("1")
    for workers, entry in out.items():
        entry["efficiency"] = (None if single is None else
                               entry["rate_samples_per_s"]
                               / (int(workers) * single["rate_samples_per_s"]))
        entry["one_core_efficiency"] = (None if one_core_s is None else
                                        entry["rate_samples_per_s"] * one_core_s
                                        / int(workers))
    first = tables[counts[0]]
    return {"samples": samples, "study": STUDY, "workers": out,
            "same_table": all(t == first for t in tables.values())}


#: a fixed amount of pure-Python work (no memory traffic, no libraries): prints its wall (s)
SPIN = """
import time
start = time.perf_counter()
total = 0
for i in range(10_000_000):
    total += i * i
print(time.perf_counter() - start)
"""


def spin() -> float:
    """SPIN's wall time (s) in a fresh interpreter."""
    return float(subprocess.run([sys.executable, "-c", SPIN], capture_output=True, text=True,
                                check=True).stdout.split()[-1])


def alone(counts: list[int], repeat: int) -> dict:
    """Each count's W concurrent sample probes (fresh interpreters, one worker each, no
    Dask), and W concurrent spins, the machine's own measure: for each, the mean wall (s)
    and the efficiency, the first count's mean wall over it."""
    out = {}
    for count in counts:
        with ThreadPoolExecutor(count) as pool:
            walls = [r["wall_s"] for r in pool.map(lambda _: sample_probe(ROOT, repeat),
                                                    range(count))]
            spins = list(pool.map(lambda _: spin(), range(count)))
        out[str(count)] = {"mean_wall_s": sum(walls) / count, "walls_s": walls,
                           "spin_mean_wall_s": sum(spins) / count}
    first = out[str(counts[0])]
    for entry in out.values():
        entry["efficiency"] = first["mean_wall_s"] / entry["mean_wall_s"]
        entry["spin_efficiency"] = first["spin_mean_wall_s"] / entry["spin_mean_wall_s"]
    return {"counts": out, "repeat": repeat, "first_count": counts[0]}


def cluster(samples: int, workers: int, folder: Path, one_core_s: float | None) -> dict:
    """The Monte Carlo on a scheduler and `workers` worker processes started beforehand."""
    from toothcontact.sweep.run import separate_processes

    folder.mkdir(parents=True, exist_ok=True)
    with separate_processes(folder, workers) as (where, _):
        entry, rows = rated(samples, workers, folder, scheduler=where)
    _, local = timed_sweep(sweep_file(folder, samples), folder / "local", workers=workers)
    return {**entry, "samples": samples, "workers": workers, "same_table_as_local": rows == local,
            "one_core_efficiency": (None if one_core_s is None else
                                    entry["rate_samples_per_s"] * one_core_s / workers)}


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


PARTS = ("per_sample", "scaling", "alone", "cluster", "killed_worker")


def machine_name() -> str:
    """The processor, its logical cores and (where /proc/cpuinfo says) threads per core."""
    info = Path("/proc/cpuinfo").read_text() if Path("/proc/cpuinfo").exists() else ""
    fields = dict(line.split(":", 1) for line in info.splitlines()[:30] if ":" in line)
    fields = {k.strip(): v.strip() for k, v in fields.items()}
    smt = ""
    if fields.get("siblings") and fields.get("cpu cores"):
        smt = f", {int(fields['siblings']) // int(fields['cpu cores'])} thread(s) per core"
    return (f"{fields.get('model name', platform.machine())}, {os.cpu_count()} logical "
            f"cores{smt}, Python {platform.python_version()}")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--samples", type=int, default=40)
    parser.add_argument("--workers", type=int, nargs="+", default=[1, os.cpu_count() or 1])
    parser.add_argument("--killed-samples", type=int, default=40)
    parser.add_argument("--repeat", type=int, default=3)
    parser.add_argument("--against", default="25866f5")
    parser.add_argument("--parts", nargs="+", choices=PARTS, default=list(PARTS))
    parser.add_argument("--record", type=Path, default=HERE / "sweep.json")
    parser.add_argument("--commit", help="the commit measured (default: git's HEAD; for a "
                                         "tree copied without its repository)")
    args = parser.parse_args()
    counts = sorted(set(args.workers))
    if counts[0] < 1 or args.samples <= counts[-1]:
        raise SystemExit("--workers: counts >= 1, and --samples more than the largest")
    path = args.record
    record = json.loads(path.read_text()) if path.exists() else {}
    record["machine"] = machine_name()
    commit = args.commit or subprocess.run(
        ["git", "-C", str(ROOT), "rev-parse", "--short", "HEAD"], capture_output=True,
        text=True).stdout.strip()
    with tempfile.TemporaryDirectory() as tmp:
        def one_core() -> float | None:
            """One sample's time on one core: part 1's (this run's or the record's), else
            part 3's with one probe alone."""
            alone_one = ((record.get("alone") or {}).get("counts") or {}).get("1") or {}
            return (record.get("per_sample") or {}).get("now_s", alone_one.get("mean_wall_s"))

        runs = {"per_sample": lambda: per_sample(args.repeat, args.against),
                "scaling": lambda: scaling(args.samples, counts, Path(tmp) / "local",
                                           one_core()),
                "alone": lambda: alone(counts, args.repeat),
                "cluster": lambda: cluster(args.samples, counts[-1], Path(tmp) / "cluster",
                                           one_core()),
                "killed_worker": lambda: killed_worker(args.killed_samples, Path(tmp))}
        for part in args.parts:
            record[part] = {**runs[part](), "commit": commit}
    s, sc, a, c, k = (record.get(part) for part in PARTS)
    if s:
        print(f"{CASE} ({s.get('commit', '?')} against {s['against']}) "
              f"{s['against']:>10} {'now':>8} {'speed-up':>9}")
        print(f"{'one sweep sample, one worker':44} {s['before_s']:9.2f}s {s['now_s']:7.2f}s "
              f"{s['speed_up']:8.2f}x")
        print(f"{'import of the analysis path':44} {s['before_import_s']:9.2f}s "
              f"{s['now_import_s']:7.2f}s")
        print(f"{'one design as bundled, ' + str(s['cores']) + ' cores':44} "
              f"{s['before_latency_s']:9.2f}s {s['now_latency_s']:7.2f}s "
              f"{s['before_latency_s'] / s['now_latency_s']:8.2f}x")
    if sc:
        print(f"\n{sc['samples']}-sample Monte Carlo ({sc.get('commit', '?')}): "
              f"{'wall':>8} {'rate/s':>8} {'eff.':>6} {'/core':>6} {'fixed':>7} "
              f"{str(sc['study']) + ' samples':>14}")
        for workers, e in sc["workers"].items():
            eff, core = ("-" if e.get(key) is None else f"{e[key]:.0%}"
                         for key in ("efficiency", "one_core_efficiency"))
            print(f"{workers + ' worker(s)':>40} {e['wall_s']:7.1f}s "
                  f"{e['rate_samples_per_s']:8.3f} {eff:>6} {core:>6} {e['fixed_s']:6.1f}s "
                  f"{e['study_s'] / 60:11.1f} min")
        print("eff.: the rate over W times one worker's; /core: over W cores each as fast "
              "as the per-sample probe's one core")
        print(f"same table on every count: {sc['same_table']}")
    if a:
        print(f"\nconcurrent sample probes, no Dask ({a.get('commit', '?')}): "
              f"{'mean wall':>10} {'efficiency':>11} {'pure-Python spin':>17}")
        for count, e in a["counts"].items():
            print(f"{count + ' at once':>40} {e['mean_wall_s']:9.2f}s {e['efficiency']:10.0%} "
                  f"{e['spin_mean_wall_s']:9.2f}s {e['spin_efficiency']:5.0%}")
    if c:
        core = ("-" if c.get("one_core_efficiency") is None
                else f"{c['one_core_efficiency']:.0%}")
        print(f"\nseparate scheduler and {c['workers']} worker processes "
              f"({c.get('commit', '?')}): {c['wall_s']:.1f}s for {c['samples']}, "
              f"{c['rate_samples_per_s']:.3f}/s, /core {core}, fixed {c['fixed_s']:.1f}s, "
              f"{STUDY} samples {c['study_s'] / 60:.1f} min, same table as local: "
              f"{c['same_table_as_local']}")
    if k:
        print(f"\nseparate scheduler, one of two workers killed after sample "
              f"{k['killed_after_sample']}: {k['answered']}/{k['samples']} answered in "
              f"{k['wall_s']:.1f}s, complete: {k['complete']}, same table as local: "
              f"{k['same_table_as_local']}   ({k.get('commit', '?')})")
    path.write_text(json.dumps(record, indent=2) + "\n")


if __name__ == "__main__":
    main()
