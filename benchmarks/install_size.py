"""The core install's size and what it runs (issue 28): a fresh virtual environment gets
`pip install <checkout>` (no extras: numpy, scipy, pydantic, pint, typer, rich, matplotlib,
trimesh, python-fcl, jinja2, threadpoolctl), its size is measured per package, and every
bundled case runs in it with --no-pictures (the imported cases read STEP: they must say
they need the cad extra, exit 2). Beside it, the same for '[all]' if --all is given.

    python benchmarks/install_size.py [--all] [--out install_size.json]

Needs network access to PyPI (or a pip cache). Prints a table; writes JSON."""

from __future__ import annotations

import argparse
import json
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]

#: what the issue asks of the core install (MB)
CORE_TARGET_MB = 400


def size_mb(path: Path) -> float:
    return sum(p.stat().st_size for p in path.rglob("*") if p.is_file() and not p.is_symlink()) / 1e6


def install(folder: Path, spec: str) -> tuple[Path, float]:
    """A fresh venv in `folder` with `spec` installed: (its bin folder, seconds)."""
    subprocess.run([sys.executable, "-m", "venv", str(folder)], check=True)
    t0 = time.perf_counter()
    subprocess.run([str(folder / "bin" / "pip"), "install", "-q", spec], check=True)
    return folder / "bin", time.perf_counter() - t0


def packages(folder: Path) -> dict[str, float]:
    site = next(folder.glob("lib/python*/site-packages"))
    sizes = {p.name: size_mb(p) if p.is_dir() else p.stat().st_size / 1e6 for p in site.iterdir()}
    return dict(sorted(sizes.items(), key=lambda kv: -kv[1]))


def run_cases(bin_folder: Path, out: Path) -> dict[str, int]:
    codes = {}
    for case in sorted((ROOT / "cases").glob("*.toml")):
        done = subprocess.run([str(bin_folder / "toothcontact"), "run", str(case), "--out",
                               str(out / case.stem), "--no-pictures"],
                              capture_output=True, text=True)
        codes[case.stem] = done.returncode
    return codes


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--all", action="store_true", help="measure '[all]' as well")
    parser.add_argument("--out", default=str(Path(__file__).with_name("install_size.json")))
    args = parser.parse_args()
    record = {}
    with tempfile.TemporaryDirectory() as tmp:
        for name, spec in [("core", str(ROOT))] + ([("all", f"{ROOT}[all]")] if args.all else []):
            folder = Path(tmp) / name
            bin_folder, seconds = install(folder, spec)
            codes = run_cases(bin_folder, Path(tmp) / f"{name}-out")
            sizes = packages(folder)
            record[name] = {"venv_MB": size_mb(folder), "install_s": seconds,
                            "largest_packages_MB": dict(list(sizes.items())[:12]),
                            "exit_codes": codes}
    core = record["core"]
    print(f"{'install':8} {'venv MB':>9} {'install s':>10}  cases answered (exit 0/1) / refused (2)")
    for name, r in record.items():
        answered = sum(c in (0, 1) for c in r["exit_codes"].values())
        refused = [k for k, c in r["exit_codes"].items() if c == 2]
        print(f"{name:8} {r['venv_MB']:9.0f} {r['install_s']:10.1f}  {answered} / {len(refused)} "
              f"({', '.join(refused)})")
    print(f"core target: under {CORE_TARGET_MB} MB; largest packages: "
          + ", ".join(f"{k} {v:.0f}" for k, v in list(core["largest_packages_MB"].items())[:6]))
    others = {k: c for k, c in core["exit_codes"].items() if c not in (0, 1)
              and not k.startswith("imported_")}
    record["core_runs_every_kind"] = not others
    Path(args.out).write_text(json.dumps(record, indent=2) + "\n")


if __name__ == "__main__":
    main()
