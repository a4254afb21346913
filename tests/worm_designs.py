"""A seeded generator of realistic worm-set case tables (issue 11), for tests and for running
a family end to end:

    PYTHONPATH=src python tests/worm_designs.py [COUNT] [SEED]

runs COUNT designs (default 40, seed 11) through `analyses.analyse(parse_case(...))` with a
load at small settings and prints one line per design and a summary.

Ranges: ZA, ZN, ZI, ZK; 1-4 starts; normal module 0.5-6 mm (log-uniform); lead angle 3-25°
with the diameter factor q = d1/mx in [5, 20]; wheel teeth 20-80; pressure angle 15-25°; either
hand and either loaded flank; a hob identical to the worm (40 %) or 2-15 % oversized (a
quarter of these tilted to the worm's thread); centre-distance, shaft-angle and worm-tilt
errors; a steel worm on a bronze (70 %) or steel wheel. The worm is long enough for the wheel:
1.25 times the chord of the wheel's tip circle at the worm's tip cylinder plus one lead. The
output torque loads the wheel's teeth with 10-40 N per mm of face width per mm of module.
"""

from __future__ import annotations

import math

import numpy as np

FORMS = ("ZA", "ZN", "ZI", "ZK")
STEEL = {"E": "206 GPa", "nu": 0.3}
BRONZE = {"E": "98 GPa", "nu": 0.35}  # CuSn12Ni2-C-GZ, ISO/TR 14521 Table 3 order of magnitude


def worm_design(rng: np.random.Generator, form: str | None = None, *,
                analysis: dict | None = None) -> dict:
    """One case table (as read from TOML) of a loaded worm set, drawn from `rng`."""
    form = form or str(rng.choice(FORMS))
    while True:
        starts = int(rng.integers(1, 5))
        lead = float(rng.uniform(3.0, 25.0))
        q = starts / math.tan(math.radians(lead))
        if 5.0 <= q <= 20.0:
            break
    mn = float(np.exp(rng.uniform(math.log(0.5), math.log(6.0))))
    teeth = int(rng.integers(20, 81))
    mx = mn / math.cos(math.radians(lead))
    r1, a = q * mx / 2, q * mx / 2 + teeth * mx / 2
    chord = 2 * math.sqrt((teeth * mx / 2 + mx) ** 2 - (a - r1 - mx) ** 2)
    length = 1.25 * chord + starts * math.pi * mx
    worm = {"form": form, "starts": starts, "normal_module": f"{mn:.4f} mm",
            "lead_angle": f"{lead:.3f} deg", "hand": str(rng.choice(["right", "left"])),
            "pressure_angle": f"{rng.uniform(15.0, 25.0):.2f} deg", "length": f"{length:.2f} mm"}
    if form == "ZK":
        worm["grinding_wheel_diameter"] = f"{rng.uniform(100.0, 400.0):.0f} mm"
    wheel = {"teeth": teeth}
    if rng.random() > 0.4:
        wheel["hob_pitch_diameter"] = f"{2 * r1 * rng.uniform(1.02, 1.15):.4f} mm"
        wheel["align_hob_thread"] = bool(rng.random() < 0.25)
    face = 2 * math.sqrt((r1 + mx) ** 2 - r1 ** 2)
    torque = rng.uniform(10.0, 40.0) * face * mn * teeth * mx / 2 / 1000.0  # N·m
    return {
        "kind": "worm",
        "title": f"generated {form} z1={starts} z2={teeth} mn={mn:.3g} lead={lead:.1f}",
        "worm": worm, "wheel": wheel,
        "material": STEEL, "wheel_material": BRONZE if rng.random() < 0.7 else STEEL,
        "misalignment": {
            "center_distance_error": f"{rng.uniform(-0.02, 0.02) * mn:.5f} mm",
            "shaft_angle_error": f"{rng.uniform(-5e-4, 5e-4):.6f}",
            "worm_tilt": f"{rng.uniform(-5e-4, 5e-4):.6f}"},
        "load": {"output_torque": f"{torque:.4g} N*m",
                 "flank": str(rng.choice(["left", "right"]))},
        "analysis": analysis if analysis is not None else {
            "positions": 3, "pressure_grid": 32, "field_grid": 41},
    }


def worm_family(seed: int, count: int, forms=FORMS, **kwargs) -> list[dict]:
    """`count` designs, the forms taken in turn, from one seeded generator."""
    rng = np.random.default_rng(seed)
    return [worm_design(rng, forms[i % len(forms)], **kwargs) for i in range(count)]


def _run(count: int, seed: int) -> None:
    import time
    import traceback

    from toothcontact.analyses import analyse
    from toothcontact.case import CaseError, parse_case

    outcomes = {}
    for i, raw in enumerate(worm_family(seed, count)):
        start = time.perf_counter()
        try:
            result = analyse(parse_case(raw))
            failed = [c.name for c in result.checks if not c.ok]
            outcome = "ran" + (f"; failed checks: {'; '.join(failed)}" if failed else "")
            key = "ran"
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

    _run(int(sys.argv[1]) if len(sys.argv) > 1 else 40, int(sys.argv[2]) if len(sys.argv) > 2 else 11)
