"""Random worm sets as a new user writes them (the before-stop check's recipe: ZA/ZN/ZI/ZK,
1-4 starts, m_n 1-2.5 mm, lead 3-20 deg, 25-60 wheel teeth of bronze, 5-60 N·m, the hob the
worm itself), run by the CLI at its default settings here and at a named commit in the same
run: per design the largest loaded pressure (bem_max_p_max_MPa), the largest on the active
flanks (flank_pressure_max_MPa), the rigid Hertz peak (max_p_max_MPa) they are read against,
the contacts that failed and the wall time. A loaded peak tens of times the Hertz one is a
model artifact (before 0985342: false gap dips beside the wheel's face ends).

    .venv/bin/python benchmarks/worm_peaks.py [--designs 20] [--seed 2026] [--against f702aea]

Prints a table and writes benchmarks/worm_peaks.json."""

from __future__ import annotations

import argparse
import json
import random
import subprocess
import sys
import tempfile
import time
from pathlib import Path

from timing import ROOT, checked_out, source_path

KEYS = ("bem_max_p_max_MPa", "flank_pressure_max_MPa", "max_p_max_MPa", "bem_failed_contacts")


def designs(count: int, seed: int) -> list[str]:
    """`count` worm cases (TOML text) drawn as the before-stop check draws them."""
    rng = random.Random(seed)
    out = []
    for _ in range(count):
        out.append(
            f'kind = "worm"\n[worm]\nform = "{rng.choice(["ZA", "ZN", "ZI", "ZK"])}"\n'
            f'starts = {rng.randint(1, 4)}\nnormal_module = "{rng.choice([1, 1.5, 2, 2.5])} mm"\n'
            f'lead_angle = "{rng.uniform(3, 20):.1f} deg"\npressure_angle = "20 deg"\n'
            f'hand = "{rng.choice(["right", "left"])}"\nlength = "40 mm"\n[wheel]\n'
            f'teeth = {rng.randint(25, 60)}\n[wheel_material]\nE = "98 GPa"\nnu = 0.35\n'
            f'[load]\noutput_torque = "{rng.randint(5, 60)} N*m"\n')
    return out


def run(tree: Path, text: str, folder: Path) -> dict:
    """One design by the CLI of the tree at `tree` (its src on the path): the summary's
    KEYS, the exit code and the wall time (s)."""
    case = folder / "design.toml"
    case.write_text(text)
    env = source_path(tree)
    start = time.perf_counter()
    done = subprocess.run([sys.executable, "-m", "toothcontact", "run", str(case), "--out",
                           str(folder / "out"), "--no-pictures"], env=env,
                          capture_output=True, text=True)
    wall = time.perf_counter() - start
    record = {"exit": done.returncode, "wall_s": round(wall, 2)}
    result = folder / "out" / "result.json"
    if result.exists():
        summary = json.loads(result.read_text())["summary"]
        record.update({key: summary.get(key) for key in KEYS})
    return record


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--designs", type=int, default=20)
    parser.add_argument("--seed", type=int, default=2026)
    parser.add_argument("--against", default="f702aea")
    args = parser.parse_args()
    texts = designs(args.designs, args.seed)
    rows = []
    with checked_out(args.against) as old, tempfile.TemporaryDirectory() as scratch:
        for k, text in enumerate(texts):
            row = {"design": text}
            for label, tree in ((args.against, old), ("this tree", ROOT)):
                folder = Path(scratch) / f"{k}-{label.replace(' ', '_')}"
                folder.mkdir()
                row[label] = run(tree, text, folder)
            rows.append(row)
            _print_row(k, text, row, args.against)
    summary = {}
    for label in (args.against, "this tree"):
        peaks = [r[label].get("bem_max_p_max_MPa") or 0.0 for r in rows]
        ratios = [(r[label].get("bem_max_p_max_MPa") or 0.0) / r[label]["max_p_max_MPa"]
                  for r in rows if r[label].get("max_p_max_MPa")]
        summary[label] = {
            "largest_loaded_peak_MPa": max(peaks),
            "designs_above_10_GPa": sum(p > 1e4 for p in peaks),
            "largest_peak_over_hertz": max(ratios) if ratios else None,
            "failed_contacts": sum(r[label].get("bem_failed_contacts") or 0 for r in rows),
            "not_answered": sum(r[label]["exit"] not in (0, 1) for r in rows),
            "wall_s": round(sum(r[label]["wall_s"] for r in rows), 1)}
    print()
    for label, s in summary.items():
        print(f"{label:>10}: " + ", ".join(f"{k} {v:.4g}" if isinstance(v, float) else f"{k} {v}"
                                           for k, v in s.items()))
    (Path(__file__).with_suffix(".json")).write_text(json.dumps(
        {"against": args.against, "seed": args.seed, "summary": summary, "designs": rows},
        indent=1))


def _print_row(k: int, text: str, row: dict, against: str) -> None:
    head = " ".join(line.split(" = ")[1].strip('"') for line in text.splitlines()
                    if line.startswith(("form", "starts", "normal_module", "teeth",
                                        "output_torque")))
    cells = []
    for label in (against, "this tree"):
        r = row[label]
        cells.append(f"{r.get('bem_max_p_max_MPa') or 0:8.0f} {r.get('flank_pressure_max_MPa') or 0:7.0f} "
                     f"{r.get('max_p_max_MPa') or 0:6.0f} {r.get('bem_failed_contacts') or 0:2} "
                     f"{r['wall_s']:5.1f}")
    if k == 0:
        print(f"{'':3} {'design':32} | {'at ' + against:31} | {'this tree':31}")
        print(f"{'':3} {'':32} | {'loaded':>8} {'flank':>7} {'Hertz':>6} {'F':>2} {'s':>5} "
              f"| {'loaded':>8} {'flank':>7} {'Hertz':>6} {'F':>2} {'s':>5}")
    print(f"{k:3} {head:32} | {cells[0]} | {cells[1]}")


if __name__ == "__main__":
    main()
