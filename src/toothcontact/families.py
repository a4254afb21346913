"""Seeded families of realistic designs, and the physical invariants every result must keep.

A tool exact on its own examples must also answer on the user's first design. A family is a
list of case tables (as read from TOML, units as text) drawn by a seeded generator over the
ranges gear engineers use: external and internal spur and helical pairs (12 to 120 teeth,
module 0.5 to 10 mm, 14.5 to 25°, helix 0 to 35°, profile shift -0.5 to +0.8 where the
teeth stay unpointed, crowned or not, slopes of both signs up to one that cuts the pattern),
worm sets of every form (ZA, ZN, ZI, ZK; 1 to 4 starts; both hands and flanks; hob identical
or oversized up to 15 %; centre-distance, shaft-angle and tilt errors) and involute splines
of 30, 37.5 and 45°. `check` lists what a result breaks of the invariants that hold for
every design, whatever its geometry. tests/test_family.py runs a small family in CI;
benchmarks/family.py a large one.
"""

from __future__ import annotations

import math

import numpy as np

#: settings small enough for a family to run in CI (and for the invariants to be the same)
SMALL = {"positions": 3, "grid": [15, 21], "field_grid": 41, "pressure_grid": 32}
#: separation (mm) up to which a pair touches at the solved lag (the others only come within
#: the approach)
TOUCHING = 1e-4


def spur_designs(count: int, seed: int, analysis: dict | None = None) -> list[dict]:
    """`count` parallel-axis pairs: a third internal (ring gears), helix 0 to 35° (half of
    them spur), a crown on half of the pinions, a slope of either sign on most."""
    rng = np.random.default_rng(seed)
    out = []
    while len(out) < count:
        internal = rng.random() < 1 / 3
        z1 = int(rng.integers(12, 41))
        z2 = int(rng.integers(max(z1 + 12, 30), 121)) if internal else int(
            min(120, max(z1, round(z1 * rng.uniform(1.0, 5.0)))))
        module = float(rng.choice([0.5, 0.8, 1.0, 1.5, 2.0, 2.5, 3.0, 4.0, 5.0, 6.0, 8.0, 10.0]))
        alpha = float(rng.choice([14.5, 17.5, 20.0, 20.0, 22.5, 25.0]))
        beta = 0.0 if rng.random() < 0.5 else float(rng.uniform(5.0, 35.0))
        x1 = float(rng.uniform(-0.5, 0.8))
        x2 = float(rng.uniform(-0.3, 0.5))
        if (_pointed(z1, module, alpha, beta, x1)
                or (not internal and _pointed(z2, module, alpha, beta, x2))
                or not 12.0 <= _working_angle(z1, -z2 if internal else z2, alpha, beta,
                                              x1, x2) <= 32.0):
            continue
        face = round(module * float(rng.uniform(6.0, 14.0)), 1)
        case = {"kind": "spur", "title": f"family spur {len(out)}",
                "teeth": [z1, -z2 if internal else z2], "module": f"{module} mm",
                "pressure_angle": f"{alpha} deg", "helix_angle": f"{beta:.2f} deg",
                "hand": str(rng.choice(["right", "left"])), "face_width": f"{face} mm",
                "pinion": {"profile_shift": round(x1, 3)},
                "gear": {"profile_shift": round(x2, 3)},
                "load": {"tangential_load": f"{round(face * float(rng.uniform(50, 400)))} N"},
                "analysis": {**SMALL, "interference": False, **(analysis or {})}}
        crown_um = float(rng.uniform(3.0, 25.0)) if rng.random() < 0.5 else 0.0
        if crown_um:
            case["pinion"]["crown"] = {"height": f"{crown_um:.1f} um"}
        # slopes up to twice what the crown takes (4·drop/face) or up to 1e-3 uncrowned
        limit = 8e-3 * crown_um / face if crown_um else 1e-3
        slope = 0.0 if rng.random() < 0.15 else float(rng.uniform(-1.0, 1.0)) * limit
        case["misalignment"] = {"slope": f"{slope:.6f}"}
        out.append(case)
    return out


def _pointed(z: int, module: float, alpha: float, beta: float, x: float) -> bool:
    """Whether a gear's top land (transverse, at the tip) is under 0.25 m_n: pointed or
    nearly, no design a gear engineer would draw (ISO 21771 tooth thickness at a radius)."""
    a_n, b = math.radians(alpha), math.radians(beta)
    a_t = math.atan(math.tan(a_n) / math.cos(b))
    r = 0.5 * z * module / math.cos(b)
    ra = r + (1.0 + x) * module
    s = module / math.cos(b) * (0.5 * math.pi + 2.0 * x * math.tan(a_n))
    a_a = math.acos(r * math.cos(a_t) / ra)
    inv = lambda a: math.tan(a) - a  # noqa: E731
    land = 2.0 * ra * (s / (2.0 * r) + inv(a_t) - inv(a_a))
    return land < 0.25 * module


def _working_angle(z1: int, z2: int, alpha: float, beta: float, x1: float, x2: float) -> float:
    """The working transverse pressure angle (deg) of a shifted pair (ISO 21771: inv(a_wt) =
    inv(a_t) + 2·tan(a_n)·(x1 ± x2)/(z1 ± z2), the lower sign for a ring, z2 < 0); 0 where
    the shifts leave none. Practice keeps it between about 14 and 30°."""
    from scipy.optimize import brentq

    a_n = math.radians(alpha)
    a_t = math.atan(math.tan(a_n) / math.cos(math.radians(beta)))
    sign = -1.0 if z2 < 0 else 1.0
    inv = lambda a: math.tan(a) - a  # noqa: E731
    target = inv(a_t) + 2.0 * math.tan(a_n) * (x1 + sign * x2) / (z1 + z2)
    if not 0.0 < target < inv(math.radians(60.0)):
        return 0.0
    return math.degrees(brentq(lambda a: inv(a) - target, 1e-6, math.radians(60.0)))


def worm_designs(count: int, seed: int, analysis: dict | None = None) -> list[dict]:
    """`count` worm sets: every form, 1 to 4 starts (lead angles 3 to 34°), both hands and
    loaded flanks, hobs identical or up to 15 % oversized, misalignments on most."""
    rng = np.random.default_rng(seed)
    out = []
    for i in range(count):
        form = ["ZA", "ZN", "ZI", "ZK"][i % 4]
        starts = int(rng.integers(1, 5))
        mn = float(rng.choice([0.5, 1.0, 1.5, 2.0, 2.5, 3.0, 4.0, 5.0, 6.0]))
        # the diameter quotient q = d1/mx of practice (DIN 3976: about 6 to 17) fixes the lead
        quotient = float(rng.uniform(6.0, 17.0))
        gamma = math.degrees(math.atan(starts / quotient))
        z2 = int(rng.integers(20, 81))
        mx = mn / math.cos(math.radians(gamma))
        d1 = quotient * mx
        oversize = 0.0 if rng.random() < 0.35 else float(rng.uniform(0.02, 0.15))
        torque = 0.02 * (mn * z2) ** 2 * float(rng.uniform(0.3, 1.5))   # N·m, ~wheel size²
        case = {"kind": "worm", "title": f"family worm {i}",
                "worm": {"form": form, "starts": starts, "normal_module": f"{mn} mm",
                         "lead_angle": f"{gamma:.2f} deg",
                         "pressure_angle": f"{float(rng.choice([15.0, 20.0, 20.0, 25.0]))} deg",
                         "hand": str(rng.choice(["right", "left"])),
                         "length": f"{round(2.2 * math.sqrt(z2 + 1) * mx + 4 * mx, 1)} mm"},
                "wheel": {"teeth": z2},
                "wheel_material": {"E": "98 GPa", "nu": 0.35},
                "load": {"output_torque": f"{torque:.1f} N*m",
                         "flank": str(rng.choice(["left", "right"]))},
                "analysis": {**SMALL, "grid": [11, 41], **(analysis or {})}}
        if form == "ZK":
            case["worm"]["grinding_wheel_diameter"] = f"{round(float(rng.uniform(8, 25)) * d1)} mm"
        if oversize:
            case["wheel"]["hob_pitch_diameter"] = f"{d1 * (1 + oversize):.4f} mm"
        if rng.random() < 0.7:
            case["misalignment"] = {
                "center_distance_error": f"{float(rng.uniform(-0.02, 0.05)) * mn:.4f} mm",
                "shaft_angle_error": f"{float(rng.uniform(-1e-3, 1e-3)):.6f}",
                "worm_tilt": f"{float(rng.uniform(-1e-3, 1e-3)):.6f}"}
        out.append(case)
    return out


def spline_designs(count: int, seed: int, analysis: dict | None = None) -> list[dict]:
    """`count` crowned or straight involute splines of 30, 37.5 and 45°, tilted."""
    rng = np.random.default_rng(seed)
    out = []
    for i in range(count):
        alpha = [30.0, 37.5, 45.0][i % 3]
        z = int(rng.integers(12, 41))
        module = float(rng.choice([0.5, 0.8, 1.0, 1.25, 1.5, 2.0, 2.5, 3.0]))
        length = round(module * z * float(rng.uniform(0.3, 1.0)), 1)
        thickness = 0.5 * math.pi * module
        clearance = module * float(rng.uniform(0.01, 0.04))
        tilt = float(rng.uniform(0.0, 2e-3))
        case = {"kind": "spline", "title": f"family spline {i}", "teeth": z,
                "module": f"{module} mm", "pressure_angle": f"{alpha} deg",
                # ISO 4156 has a flat root for 30° only
                "root": str(rng.choice(["flat", "fillet"])) if alpha == 30.0 else "fillet",
                "engaged_length": f"{length} mm",
                "tooth_thickness": f"{thickness:.4f} mm", "clearance": f"{clearance:.4f} mm",
                "misalignment": f"{tilt:.6f}",
                "torque": f"{round(0.02 * (module * z) ** 2 * length * float(rng.uniform(0.3, 1.5)), 1)} N*m",
                "analysis": {**SMALL, "positions": 1, "grid": [9, 21], **(analysis or {})}}
        if rng.random() < 0.6:
            case["crown"] = {"height": f"{float(rng.uniform(5.0, 40.0)):.1f} um"}
        out.append(case)
    return out


def check(case: dict, document: dict) -> list[str]:
    """What the result `document` of `case` breaks of the invariants every design keeps:
    strict JSON (no NaN, no infinity, no "nan" text), positive semi-axes, the loads of a
    position summing to the normal load (Hertz split and loaded solution), the contact
    moving toward the end the slope closes, and an uncrowned pair under slope in edge
    contact at that end and not at the other."""
    problems = list(_not_finite(document, "result"))
    rows = document.get("positions") or []
    if case["kind"] in ("spur", "spline", "worm") and not rows:
        problems.append("no contact rows")
    normal = document.get("summary", {}).get("normal_load_N")
    by_position: dict[float, list[dict]] = {}
    for r in rows:
        by_position.setdefault(r["roll_deg"], []).append(r)
        if not (r["a_mm"] > 0 and r["b_mm"] > 0):
            problems.append(f"roll {r['roll_deg']:.3f} pair {r['pair']}: a = {r['a_mm']}, "
                            f"b = {r['b_mm']} must be > 0")
    for roll, group in by_position.items():
        if normal and case["kind"] != "spline":
            split = sum(r["normal_load_N"] for r in group)
            if not math.isclose(split, normal, rel_tol=1e-9):
                problems.append(f"roll {roll:.3f}: Hertz loads sum to {split:.6g} N, not {normal:.6g} N")
            solved = [r for r in group if r.get("bem_status") in ("solved", "unloaded")]
            if solved and len(solved) == len(group):
                carried = sum(r["bem_load_N"] for r in solved)
                if not math.isclose(carried, normal, rel_tol=0.02):
                    problems.append(f"roll {roll:.3f}: loaded solutions carry {carried:.6g} N, "
                                    f"not {normal:.6g} N")
    if case["kind"] == "spur" and rows:
        problems.extend(_slope_invariants(case, rows))
    return problems


def _slope_invariants(case: dict, rows: list[dict]) -> list[str]:
    """A slope moves a crowned pair's contact toward the end it closes (by about R·theta:
    checked where that is over 1 mm) and puts an uncrowned pair's touching contacts in edge
    contact there and not at the other end."""
    slope = float(case.get("misalignment", {}).get("slope", "0"))
    crown = case.get("pinion", {}).get("crown")
    face = float(case["face_width"].split()[0])
    end, other = ("B", "A") if slope > 0 else ("A", "B")
    problems = []
    if crown is not None and slope:
        drop = float(crown["height"].split()[0]) * 1e-3
        shift = slope * face * face / (8.0 * drop)                 # R·theta, R = b²/(8·drop)
        mean = float(np.mean([r["face_position_mm"] for r in rows]))
        if abs(shift) > 1.0 and not mean * shift > 0:
            problems.append(f"slope {slope:g}: the contact's mean face position {mean:.3f} mm "
                            f"does not move toward end {end} (R·theta = {shift:.3f} mm)")
    if crown is None and abs(slope) > 1e-5:
        # the pairs that touch (a pair only within the approach may be a sliver at a corner)
        ends = {r["edge_contact_at"] for r in rows
                if r["edge_contact"] and r["separation_mm"] <= TOUCHING}
        if not any(e.endswith(f"end_{end}") for e in ends):
            problems.append(f"uncrowned, slope {slope:g}: no contact cut by end {end}")
        if any(e.endswith(f"end_{other}") for e in ends):
            problems.append(f"uncrowned, slope {slope:g}: a contact cut by end {other}, the end "
                            "the slope opens")
    return problems


def _not_finite(value, where: str):
    """Places in a document that strict JSON cannot hold or that hide a missing number."""
    if isinstance(value, float) and not math.isfinite(value):
        yield f"{where}: {value}"
    elif isinstance(value, str) and value.lower() in ("nan", "inf", "-inf", "infinity"):
        yield f"{where}: {value!r}"
    elif isinstance(value, dict):
        for key, item in value.items():
            yield from _not_finite(item, f"{where}.{key}")
    elif isinstance(value, (list, tuple)):
        for i, item in enumerate(value):
            yield from _not_finite(item, f"{where}[{i}]")
