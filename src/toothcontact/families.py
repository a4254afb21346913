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
    """`count` parallel-axis pairs as practice draws them: a quarter internal (ring gears),
    pinion 12 to 40 teeth and gear up to 120, module 0.5 to 10 mm (log-uniform), helix 0 to
    35° (half of them spur), shifts -0.5 to +0.8 on the pinion and -0.3 to +0.5 on the gear,
    face width 6 to 14 modules, a crown on half of the pinions (drop 3 to 25 µm), a slope of
    either sign on most (up to twice what the crown takes, or 1e-3 uncrowned) and a
    tangential load of 50 to 400 N per mm of face. Designs no engineer would draw are drawn
    again: pointed tips (top land under 0.25 m), a working pressure angle outside 12 to
    32°, a ring's tip circle inside its base circle."""
    rng = np.random.default_rng(seed)
    out = []
    while len(out) < count:
        internal = rng.random() < 0.25
        z1 = int(rng.integers(12, 41))
        z2 = int(rng.integers(z1 + 12, 121)) if internal else int(
            min(120, max(z1, round(z1 * rng.uniform(1.0, 5.0)))))
        module = round(float(np.exp(rng.uniform(math.log(0.5), math.log(10.0)))), 3)
        alpha = float(rng.choice([14.5, 17.5, 20.0, 20.0, 22.5, 25.0]))
        beta = 0.0 if rng.random() < 0.5 else float(rng.uniform(5.0, 35.0))
        x1 = float(rng.uniform(-0.5, 0.8))
        x2 = float(rng.uniform(-0.3, 0.5))
        working = _working_angle(z1, -z2 if internal else z2, alpha, beta, x1, x2)
        if (_pointed(z1, module, alpha, beta, x1)
                or (not internal and _pointed(z2, module, alpha, beta, x2))
                or (internal and _ring_tip_inside_base(z2, module, alpha, beta, x2))
                or not 12.0 <= working <= 32.0
                or _tip_below_form(z1, -z2 if internal else z2, module, alpha, beta, x1, x2,
                                   working)):
            continue
        face = round(module * float(rng.uniform(6.0, 14.0)), 2)
        case = {"kind": "spur", "title": f"family spur {len(out)}",
                "teeth": [z1, -z2 if internal else z2], "module": f"{module} mm",
                "pressure_angle": f"{alpha} deg", "helix_angle": f"{beta:.2f} deg",
                "hand": str(rng.choice(["right", "left"])), "face_width": f"{face} mm",
                "pinion": {"profile_shift": round(x1, 3)},
                "gear": {"profile_shift": round(x2, 3)},
                "load": {"tangential_load": f"{round(face * float(rng.uniform(50, 400)))} N"},
                "analysis": {**SMALL, "interference": False, **(analysis or {})},
                "export": {"teeth": 3}}
        crown_um = float(rng.uniform(3.0, 25.0)) if rng.random() < 0.5 else 0.0
        if crown_um:
            case["pinion"]["crown"] = {"height": f"{crown_um:.1f} um"}
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


def _tip_below_form(z1: int, z2: int, module: float, alpha: float, beta: float, x1: float,
                    x2: float, working: float) -> bool:
    """Whether the mate's tip reaches below the pinion's form circle (or, external, the
    pinion's tip below the gear's): the tip then works on the fillet, not the involute
    (tip interference). Along the line of action from the pinion's base tangency point the
    mate's tip lies at a·sin(a_w) ∓ sqrt(r_a2² - r_b2²) (the lower sign internal), and a
    rack-cut flank's form point at r·sin(a_t) - (h - x·m)/sin(a_t), h the rack's straight
    flank below its reference line, (1.25 - 0.38·(1 - sin a_n))·m (ISO 53 A)."""
    a_n = math.radians(alpha)
    a_t = math.atan(math.tan(a_n) / math.cos(math.radians(beta)))
    a_w = math.radians(working)
    h = (1.25 - 0.38 * (1.0 - math.sin(a_n))) * module
    r1, r2 = (0.5 * abs(z) * module / math.cos(math.radians(beta)) for z in (z1, z2))
    internal = z2 < 0
    centre = (r2 - r1 if internal else r2 + r1) * math.cos(a_t) / math.cos(a_w)
    line = centre * math.sin(a_w)

    def form(r, x):
        return r * math.sin(a_t) - (h - x * module) / math.sin(a_t)

    def reach(r, x, ring=False):   # a tip's distance from its base tangency point
        tip = r - (1.0 - x) * module if ring else r + (1.0 + x) * module
        return math.sqrt(max(tip * tip - (r * math.cos(a_t)) ** 2, 0.0))

    if internal:
        return reach(r2, x2, ring=True) - line < form(r1, x1)
    return (line - reach(r2, x2) < form(r1, x1)) or (line - reach(r1, x1) < form(r2, x2))


def _ring_tip_inside_base(z: int, module: float, alpha: float, beta: float, x: float) -> bool:
    """Whether a ring gear's tip circle, r - (1 - x)·m, lies inside its base circle (the
    involute does not reach it)."""
    a_t = math.atan(math.tan(math.radians(alpha)) / math.cos(math.radians(beta)))
    r = 0.5 * z * module / math.cos(math.radians(beta))
    return r - (1.0 - x) * module < r * math.cos(a_t)


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


#: worm and wheel materials: steel, and a tin bronze (CuSn12Ni2-C-GZ, ISO/TR 14521 Table 3
#: order of magnitude)
STEEL = {"E": "206 GPa", "nu": 0.3}
BRONZE = {"E": "98 GPa", "nu": 0.35}


def worm_designs(count: int, seed: int, analysis: dict | None = None) -> list[dict]:
    """`count` loaded worm sets, the forms ZA, ZN, ZI, ZK in turn: 1 to 4 starts, lead
    angle 3 to 25° with the diameter quotient q = d1/mx in [5, 20], normal module 0.5 to
    6 mm (log-uniform), 20 to 80 wheel teeth, pressure angle 15 to 25°, either hand and
    loaded flank, a hob identical to the worm (40 %) or 2 to 15 % oversized (a quarter of
    these tilted to the worm's thread), centre-distance, shaft-angle and worm-tilt errors,
    a steel worm on a bronze (70 %) or steel wheel. The worm is long enough for the wheel:
    1.25 times the chord of the wheel's tip circle at the worm's tip cylinder plus one lead.
    The output torque loads the wheel's teeth with 10 to 40 N per mm of face width per mm
    of module."""
    rng = np.random.default_rng(seed)
    forms = ("ZA", "ZN", "ZI", "ZK")
    out = []
    for i in range(count):
        form = forms[i % 4]
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
        worm = {"form": form, "starts": starts, "normal_module": f"{mn:.4f} mm",
                "lead_angle": f"{lead:.3f} deg", "hand": str(rng.choice(["right", "left"])),
                "pressure_angle": f"{rng.uniform(15.0, 25.0):.2f} deg",
                "length": f"{1.25 * chord + starts * math.pi * mx:.2f} mm"}
        if form == "ZK":
            worm["grinding_wheel_diameter"] = f"{rng.uniform(100.0, 400.0):.0f} mm"
        wheel = {"teeth": teeth}
        if rng.random() > 0.4:
            wheel["hob_pitch_diameter"] = f"{2 * r1 * rng.uniform(1.02, 1.15):.4f} mm"
            wheel["align_hob_thread"] = bool(rng.random() < 0.25)
        face = 2 * math.sqrt((r1 + mx) ** 2 - r1 ** 2)
        torque = rng.uniform(10.0, 40.0) * face * mn * teeth * mx / 2 / 1000.0  # N·m
        out.append({
            "kind": "worm", "title": f"family worm {i} ({form} z1={starts} z2={teeth} "
                                     f"mn={mn:.3g} lead={lead:.1f})",
            "worm": worm, "wheel": wheel,
            "material": STEEL, "wheel_material": BRONZE if rng.random() < 0.7 else STEEL,
            "misalignment": {
                "center_distance_error": f"{rng.uniform(-0.02, 0.02) * mn:.5f} mm",
                "shaft_angle_error": f"{rng.uniform(-5e-4, 5e-4):.6f}",
                "worm_tilt": f"{rng.uniform(-5e-4, 5e-4):.6f}"},
            "load": {"output_torque": f"{torque:.4g} N*m",
                     "flank": str(rng.choice(["left", "right"]))},
            "analysis": {**SMALL, "grid": [11, 41], **(analysis or {})}})
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
    strict JSON (no NaN, no infinity, no "nan" text), positive semi-axes (none, and no
    load, on a pair kept beyond the approach for the loaded contact), the loads of a
    position summing to the normal load (Hertz split and loaded solution), a loaded peak
    that is the larger of the active flank's and the edge's, the contact
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
        if not r.get("rigid_contact", True):    # kept for the loaded contact only: no Hertz
            if r["a_mm"] or r["b_mm"] or r["normal_load_N"]:
                problems.append(f"roll {r['roll_deg']:.3f} pair {r['pair']}: not in contact "
                                f"but a = {r['a_mm']}, b = {r['b_mm']}, "
                                f"{r['normal_load_N']} N")
        elif not (r["a_mm"] > 0 and r["b_mm"] > 0):
            problems.append(f"roll {r['roll_deg']:.3f} pair {r['pair']}: a = {r['a_mm']}, "
                            f"b = {r['b_mm']} must be > 0")
        if r.get("bem_status") == "solved" and not math.isclose(
                r["bem_p_max_MPa"], max(r["flank_p_max_MPa"], r["edge_pressure_MPa"])):
            problems.append(f"roll {r['roll_deg']:.3f} pair {r['pair']}: bem_p_max_MPa "
                            f"{r['bem_p_max_MPa']} is not the larger of the active flank's "
                            f"{r['flank_p_max_MPa']} and the edge's {r['edge_pressure_MPa']}")
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
    touching = [r for r in rows if r.get("rigid_contact", True)]
    if case["kind"] == "spur" and touching:
        problems.extend(_slope_invariants(case, touching))
    return problems


def _slope_invariants(case: dict, rows: list[dict]) -> list[str]:
    """(rows: the pairs in contact) A slope moves a crowned pair's contact toward the end it
    closes (by about R·theta: checked where that is over 1 mm) and puts an uncrowned pair's
    touching contacts in edge contact there (where one runs clear of the tips by a module)
    and not at the other end."""
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
        # along the face, not at a tip or form corner (tip interference is another story)
        touching = [r for r in rows if r["separation_mm"] <= TOUCHING and not any(
            m < 0.0 and "_end_" not in edge for edge, m in r["edge_margins_mm"].items())]
        if not touching:
            return problems
        ends = {r["edge_contact_at"] for r in touching if r["edge_contact"]}
        # a helical line that runs onto a tip rounding ends there, short of the face end
        module = float(case["module"].split()[0])
        along = [r for r in touching if all(m > module for edge, m in
                                            r["edge_margins_mm"].items() if edge.endswith("_tip"))]
        if along and not any(e.endswith(f"end_{end}") for e in ends):
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
