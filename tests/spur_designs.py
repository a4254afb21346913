"""A seeded generator of spur and helical pair case tables (issue 11), for tests and for
running a family through the geometry and the export path:

    PYTHONPATH=src python tests/spur_designs.py [COUNT] [SEED]

runs COUNT designs (default 60, seed 5) through `analyses.analyse(parse_case(...))` (geometry
only) and `cad.build_parts` (the solids `export` writes, three-tooth sectors of external
gears) and prints one line per design and a summary.

Ranges: external (75 %) and internal pairs; pinion 12-60 teeth, gear up to 120; module
0.5-10 mm (log-uniform); pressure angle 14.5-25°; spur (half) or helical up to 35°; profile
shifts -0.5..+0.8 on both members (the ring's too); face width 6-15 modules; a lead crown on
the pinion (half of them). Some of these designs cannot be made (pointed teeth, a tip past
the mating root); they must be refused with a message naming the field, never fail inside.
"""

from __future__ import annotations

import math

import numpy as np


def spur_design(rng: np.random.Generator, *, load: bool = False) -> dict:
    """One case table (as read from TOML) of a spur or helical pair, drawn from `rng`."""
    internal = rng.random() < 0.25
    z1 = int(rng.integers(12, 61))
    z2 = int(rng.integers(z1 + 10, 121)) if internal else int(rng.integers(z1, 121))
    module = float(np.exp(rng.uniform(math.log(0.5), math.log(10.0))))
    helix = 0.0 if rng.random() < 0.5 else float(rng.uniform(5.0, 35.0))
    raw = {
        "kind": "spur",
        "teeth": [z1, -z2 if internal else z2],
        "module": f"{module:.4f} mm",
        "pressure_angle": f"{rng.uniform(14.5, 25.0):.2f} deg",
        "helix_angle": f"{helix:.2f} deg",
        "face_width": f"{rng.uniform(6.0, 15.0) * module:.3f} mm",
        "pinion": {"profile_shift": round(float(rng.uniform(-0.5, 0.8)), 3)},
        "gear": {"profile_shift": round(float(rng.uniform(-0.5, 0.8)), 3)},
        "export": {"teeth": 3},
    }
    if rng.random() < 0.5:
        raw["pinion"]["crown"] = {"height": f"{rng.uniform(2.0, 10.0) * module:.2f} um"}
    raw["title"] = (f"generated {'internal' if internal else 'external'} {z1}/{z2} "
                    f"m={module:.3g} a={raw['pressure_angle']} b={helix:.1f} "
                    f"x={raw['pinion']['profile_shift']}/{raw['gear']['profile_shift']}")
    if load:
        raw["load"] = {"tangential_load": f"{rng.uniform(20.0, 80.0) * module * float(raw['face_width'].split()[0]):.4g} N"}
        raw["analysis"] = {"positions": 3, "pressure_grid": 32, "field_grid": 41}
    return raw


def spur_family(seed: int, count: int, **kwargs) -> list[dict]:
    rng = np.random.default_rng(seed)
    return [spur_design(rng, **kwargs) for _ in range(count)]


def _run(count: int, seed: int) -> None:
    import time
    import traceback

    from toothcontact import cad
    from toothcontact.analyses import analyse
    from toothcontact.case import CaseError, parse_case

    outcomes = {}
    for i, raw in enumerate(spur_family(seed, count)):
        start = time.perf_counter()
        try:
            case = parse_case(raw)
            result = analyse(case)
            try:
                bodies = cad.build_parts(case)
            except ValueError as exc:  # what export turns into exit 2
                raise CaseError(f"export: {exc}") from None
            bad = [n for n, b in bodies.items() if not cad.is_valid(b.solid)]
            failed = [c.name for c in result.checks if not c.ok]
            outcome = ("ran" + (f"; INVALID SOLID {bad}" if bad else "")
                       + (f"; failed checks: {'; '.join(failed)}" if failed else ""))
            key = "invalid" if bad else "ran"
        except CaseError as exc:
            outcome, key = f"refused: {exc}", "refused"
        except Exception as exc:  # noqa: BLE001 - the point is to see every failure
            where = traceback.extract_tb(exc.__traceback__)[-1]
            outcome = (f"ERROR {type(exc).__name__}: {exc} "
                       f"[{where.filename.split('src/')[-1]}:{where.lineno}]")
            key = "error"
        outcomes[key] = outcomes.get(key, 0) + 1
        print(f"{i:3d} {time.perf_counter() - start:6.1f}s {raw['title']}: {outcome}", flush=True)
    print(f"{count} designs (seed {seed}): " + ", ".join(f"{k} {v}" for k, v in outcomes.items()))


if __name__ == "__main__":
    import sys

    _run(int(sys.argv[1]) if len(sys.argv) > 1 else 60, int(sys.argv[2]) if len(sys.argv) > 2 else 5)
