"""The load distribution along the face where one pair carries: the model against an
independent 3D finite-element reference (issue 50, item 6).

Pair: benchmarks/cases/spur_uncrowned_25_75.toml, z = 25/75, m = 3 mm, α = 20°, ISO 53
profile A, both members 40 mm wide (flush ends), uncrowned, steel (206000 MPa, 0.3),
6000 N tangential (F_n = 6385 N); misalignment slopes 0 (the single-pair stiffness),
0.22 and 0.9 mrad in the plane of action (closing end B, z = +20 mm). Position: the
model's sampled single-pair position (11 positions over a pitch: roll -3.93°, pinion
contact radius 37.432 mm, ρ1 = 12.62 mm inside the single-contact zone 11.11-13.64 mm of
the line of action, 0.26 mm from its middle); the gear's contact radius from the line of
action (112.57 mm).

FE (tests/fe_pair_face.py on tests/fe_tooth.py): each member's tooth on its whole gear
(every tooth; the bore at half the root radius held; free end faces), P2 tetrahedra,
loaded at its contact radius along the line of action by unit forces on face strips
(0.3 mm up the profile); strip compliances read at the teeth's centre lines, summed, plus
the Hertz approach from the flanks to the centre lines (Weber's plane-strain flattening,
nonlinear in the line load), solved with the misalignment's gap for non-negative line
loads and the approach. Strips: the model's 20 strips of 1.99 mm (load_distribution's,
between 0.1 mm from each face end), the last one at each end in four, and the 0.1 mm end
slivers (28 strips; the "fine strips" level halves each). The line loads are compared on
the model's strips; K_Hβ is the largest over the mean F_n/b on them, as the model's
position K_H_beta; the single-pair stiffness is F_n/(b·δ) of the aligned pair (δ the
approach, µm; the model's single_stiffness_N_per_mm_um).

Mesh levels (section sizes in mm at the load patch, over the loaded tooth, far; growth per
mm): coarse 0.3/0.9/15/0.5 and medium 0.15/0.6/15/0.5, one z-layer per strip; light
0.3/1.2/30/0.8 on the strips and on the strips halved (light_fine_strips: 1 mm in mid-face,
0.25 mm over the last 2 mm), which isolates the strips' (and z-layers') own convergence.
Plane strain of the same sections (whole gear, centre line) puts the medium one 0.6 % and
the coarse one 1.3 % stiffer than a converged one (0.03 mm at the patch, 0.15 mm over the
tooth). The reference is the medium level. Also: the tooling's sectors (3 teeth a side,
the cut faces held) instead of the whole gears, and the plane-strain FE of the whole pair
in contact (tests/fe_mesh_stiffness.py, refine 1 and 2) for the single-pair stiffness.

Model: toothcontact.analyses.analyse of the case at each slope, as it stands, and as it
stood before the free-end layer (structure.end_layer returning 0: the Pasternak line's
free ends w' = 0) and uncoupled (a Winkler bed), for the cause of the end rise.

Not here: the same reference for a helical pair (issue 50 item 6's 20° pair, whose mesh
stiffness the model puts 18 % above ISO's c_γα). Its tooth is the section turned along the
face (the prisms leaning by β at the pitch circle, fine for P2 tetrahedra on 2 mm layers),
but it has no mid-face symmetry (a helical tooth's symmetry, a half-turn about a radial
axis, swaps its flanks), so the whole face goes into one factor (twice the planes), and a
contact line crosses the active flank from root to tip (b·tan β_b = 13.6 mm of roll on
b = 40 mm), so every strip is loaded at its own radius (a load site each, the patch's fine
elements along the whole active flank) with the normal's axial part (sin β_b) as well, and
read along the 3D normal; the mesh stiffness loads 3-4 lines on neighbouring teeth at once
(ε_γ ≈ 3.1: the teeth ±1, ±2 meshed as finely, or tooth 0 loaded alone and read on them by
the gear's symmetry). From this benchmark's factors (nonzeros growing as dofs^1.3-1.6):
about 0.7 million dofs and 12 GB for the pinion's factor, 1 million and 16 GB for the
gear's, 25-35 GB at the peak and 10-30 minutes a factor on one core, per mesh level; beyond
the 2 cores and 10 GB this benchmark keeps to.

Run (about 15 minutes on 2 cores, 8 GB of memory at most; each member and level is kept in
--cache and computed once, --member/--level computes one into it and stops):

    .venv/bin/python benchmarks/fe_face_load.py [--cache DIR] [--levels coarse medium ...]

Prints the tables and writes benchmarks/fe_face_load.json.
"""

from __future__ import annotations

import argparse
import json
import math
import platform
import sys
import time
import tomllib
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
ROOT = HERE.parent
CASE = HERE / "cases" / "spur_uncrowned_25_75.toml"
JSON_OUT = HERE / "fe_face_load.json"
sys.path.insert(0, str(ROOT / "tests"))
import fe_pair_face as fl  # noqa: E402
import fe_tooth as ft  # noqa: E402

SLOPES = (0.0, 0.00022, 0.0009)
#: section sizes (mm: h_patch, h_tooth, h_far, growth), strips split in `split`, sectors
LEVELS = {
    "coarse": dict(h_patch=0.3, h_tooth=0.9, h_far=15.0, growth=0.5, split=1, teeth=None),
    "medium": dict(h_patch=0.15, h_tooth=0.6, h_far=15.0, growth=0.5, split=1, teeth=None),
    "light": dict(h_patch=0.3, h_tooth=1.2, h_far=30.0, growth=0.8, split=1, teeth=None),
    "light_fine_strips": dict(h_patch=0.3, h_tooth=1.2, h_far=30.0, growth=0.8, split=2,
                              teeth=None),
    "sectors": dict(h_patch=0.3, h_tooth=0.9, h_far=15.0, growth=0.5, split=1, teeth=3),
}
REFERENCE = "medium"
#: the model's position: one of 11 over a pitch, roll -3.93 deg, and its pinion contact
#: radius (mm; main checks it against the model's run)
POSITIONS, ROLL, PINION_RADIUS = 11, -3.927, 37.4316


def case(slope: float, positions: int = POSITIONS) -> dict:
    """The case's table with the misalignment `slope` (rad) and `positions` over a pitch,
    the interference and the positions check off."""
    raw = tomllib.loads(CASE.read_text())
    raw["misalignment"]["slope"] = f"{slope}"
    raw["analysis"] = {"positions": positions, "interference": False, "positions_check": False}
    return raw


def model_strips() -> np.ndarray:
    """The model's load_distribution strips (mm): 20 between 0.1 mm from each face end."""
    from toothcontact.analyses.spur import FACE_STRIPS
    from toothcontact.contact.edge_loads import EDGE_STRIP

    end = 20.0 - EDGE_STRIP
    return np.linspace(-end, end, FACE_STRIPS + 1)


def half_edges(split: int) -> np.ndarray:
    """The FE's strip edges on the half face (mm): the model's strips, the last in four,
    the 0.1 mm sliver; every strip cut in `split`."""
    model = model_strips()
    half = model[model >= -1e-9]
    edges = np.concatenate([half[:-1], np.linspace(half[-2], half[-1], 5)[1:], [20.0]])
    edges = np.unique(np.round(edges, 9))
    fine = [np.linspace(a, b, split + 1)[:-1] for a, b in zip(edges[:-1], edges[1:])]
    return np.concatenate(fine + [edges[-1:]])


def contact_radii(pair, r1: float) -> tuple[float, float, tuple[float, float]]:
    """The gear's contact radius (mm) on the line of action with the pinion's at r1, and
    the flanks' curvature radii there (mm)."""
    rb1, rb2 = pair.pinion.base_radius, pair.gear.base_radius
    rho1 = math.sqrt(r1 ** 2 - rb1 ** 2)
    rho2 = (rb1 + rb2) * math.tan(pair.working_pressure_angle) - rho1
    return r1, math.hypot(rb2, rho2), (rho1, rho2)


def member(name: str, level: str, cache: Path, pair, radius: float) -> fl.MemberCompliance:
    """One member's strip compliance at one level, from the cache or computed into it."""
    path = cache / f"{name}_{level}.npz"
    if path.exists():
        d = np.load(path, allow_pickle=True)
        return fl.MemberCompliance(d["edges"], d["matrix"], float(d["depth"]),
                                   d["mesh"].item(), d["surface"])
    spec = dict(LEVELS[level])
    split, teeth = spec.pop("split"), spec.pop("teeth")
    gear = getattr(pair, name)
    print(f"{name}, {level}:", flush=True)
    m = fl.member_compliance(gear, radius, half_edges(split), 1, teeth=teeth, **spec)
    cache.mkdir(parents=True, exist_ok=True)
    np.savez(path, edges=m.edges, matrix=m.matrix, depth=m.depth, mesh=np.array(m.mesh),
             surface=m.surface)
    return m


def fe_results(pinion, gear, rho, load: float) -> dict:
    """The pair's FE solutions at SLOPES: K_Hβ, line loads on the model's strips and on the
    FE's, the approach and the single-pair stiffness."""
    pair = fl.PairFaceLoad(pinion, gear, rho)
    strips = model_strips()
    out = {}
    for slope in SLOPES:
        s = pair.solve(load, slope)
        line = s.on(strips)
        out[f"{slope:g}"] = dict(
            K_H_beta=float(line.max() / (load / 40.0)), line_load=line.tolist(),
            fe_strips=s.edges.tolist(), fe_line_load=s.line_load.tolist(),
            approach_um=1e3 * s.approach,
            stiffness=load / 40.0 / (1e3 * s.approach))
    return out


def model_results(variant: str) -> dict:
    """The model at SLOPES at ROLL: its line loads, K_H_beta and stiffness; `variant`:
    'as is', 'no end layer' (compliance.end_layer 0) or 'uncoupled' (Winkler)."""
    from unittest import mock

    from toothcontact.analyses import analyse
    from toothcontact.case import parse_case
    from toothcontact.contact import compliance

    patches = {"no end layer": [mock.patch.object(compliance, "end_layer", lambda t: 0.0)],
               "uncoupled": [mock.patch.object(compliance.PairCompliance, "__init__",
                                               _uncoupled)],
               "as is": []}[variant]
    out = {}
    for p in patches:
        p.start()
    try:
        for slope in SLOPES:
            result = analyse(parse_case(case(slope)))
            section = result.sections["load_distribution"]
            k = int(np.argmin(np.abs(np.asarray(section["roll_deg"]) - ROLL)))
            out[f"{slope:g}"] = dict(
                roll_deg=section["roll_deg"][k], K_H_beta=section["K_H_beta"][k],
                line_load=section["line_load_N_per_mm"][k],
                stiffness=section["mesh_stiffness_N_per_mm_um"][k])
        summary = result.sections["summary"]
        out["iso_single_stiffness"] = summary["iso_single_stiffness_N_per_mm_um"]
        rows = [r for r in result.sections["positions"] if r["roll_deg"] == section["roll_deg"][k]]
        out["pinion_radius"] = rows[0]["contact_radius_pinion_mm"]
    finally:
        for p in patches:
            p.stop()
    return out


def _uncoupled(self, pinion, gear, coupled=True):
    self.members, self.coupled = {"pinion": pinion, "gear": gear}, False


def plane_strain_stiffness(pair, r1: float) -> dict:
    """The single-pair stiffness (N/(mm·µm)) of the plane-strain FE of the whole pair in
    contact (tests/fe_mesh_stiffness.py) at the pinion radius r1, 150 N/mm tangential, by
    refine level."""
    import fe_mesh_stiffness as fm

    return {f"refine {refine:g}": fm.mesh_stiffness(r1, refine=refine, pair=pair,
                                                    tangential_line_load=150.0).stiffness
            for refine in (1.0, 2.0)}


def end_rise(line, centres) -> dict:
    """The last two strips at end B over the line fitted to the strips centred in
    [0, 12] mm (the loaded middle at both slopes), less 1."""
    line, centres = np.asarray(line), np.asarray(centres)
    middle = (centres > 0) & (centres < 12)
    slope, level = np.polyfit(centres[middle], line[middle], 1)
    trend = level + slope * centres
    return dict(slope_N_per_mm2=float(slope), last=float(line[-1] / trend[-1] - 1),
                second=float(line[-2] / trend[-2] - 1))


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--cache", type=Path, default=Path("/tmp/fe_face_load"))
    ap.add_argument("--levels", nargs="+", default=list(LEVELS))
    ap.add_argument("--member", choices=("pinion", "gear"))
    ap.add_argument("--level", choices=list(LEVELS))
    args = ap.parse_args()
    from toothcontact.case import parse_case
    from toothcontact.gearset import gear_pair

    t0 = time.perf_counter()
    pair = gear_pair(parse_case(case(0.0)))
    r1, r2, rho = contact_radii(pair, PINION_RADIUS)
    radii = {"pinion": r1, "gear": r2}
    if args.member:
        member(args.member, args.level, args.cache, pair, radii[args.member])
        return
    load = 6000.0 / math.cos(pair.working_pressure_angle)
    centres = 0.5 * (model_strips()[1:] + model_strips()[:-1])
    fe = {}
    for level in args.levels:
        members = [member(name, level, args.cache, pair, radii[name]) for name in radii]
        fe[level] = dict(results=fe_results(*members, rho, load),
                         mesh={name: m.mesh for name, m in zip(radii, members)})
    model = {variant: model_results(variant) for variant in ("as is", "no end layer",
                                                             "uncoupled")}
    plane_strain = plane_strain_stiffness(pair, r1)
    assert abs(model["as is"]["pinion_radius"] - r1) < 1e-3, model["as is"]["pinion_radius"]

    print(f"\nAt roll {ROLL} deg (pinion r = {r1:.3f} mm, gear r = {r2:.3f} mm), F_n = "
          f"{load:.0f} N, b = 40 mm. K_Hβ at 0.22 and 0.9 mrad; c' (N/(mm·µm)) aligned; "
          "the end rise: the last strip over the mid-face trend.")
    print(f"{'':24} {'K 0.22':>7} {'K 0.9':>7} {'c_prime':>7} {'rise .22':>8} {'rise .9':>8} "
          f"{'slope .9':>8}  dofs (pinion, gear per half)")
    rows = [(f"FE {level}", fe[level]["results"], fe[level]["mesh"]) for level in fe]
    rows += [(f"model {variant}", model[variant], None) for variant in model]
    for name, r, mesh in rows:
        rises = [end_rise(r[f"{s:g}"]["line_load"], centres) for s in SLOPES[1:]]
        stiffness = r["0"]["stiffness"]
        print(f"{name:24} {r['0.00022']['K_H_beta']:7.3f} {r['0.0009']['K_H_beta']:7.3f} "
              f"{stiffness:7.2f} {rises[0]['last']:+8.1%} {rises[1]['last']:+8.1%} "
              f"{rises[1]['slope_N_per_mm2']:8.2f}  "
              + (f"{mesh['pinion']['dofs_half']}, {mesh['gear']['dofs_half']}" if mesh else ""))
    print("plane-strain FE of the pair in contact (refine 1, 2): "
          + ", ".join(f"{v:.2f}" for v in plane_strain.values()) + " N/(mm·µm); ISO c' "
          f"{model['as is']['iso_single_stiffness']:.2f}")
    ref = fe[REFERENCE]["results"]
    print(f"\nLine loads (N/mm) on the model's strips, FE {REFERENCE} against the model as is "
          "(and before the end layer):")
    for s in SLOPES[1:]:
        key = f"{s:g}"
        print(f"slope {s * 1e3:g} mrad")
        print("  z    " + " ".join(f"{z:6.1f}" for z in centres))
        for name, r in (("FE", ref), ("model", model["as is"]),
                        ("before", model["no end layer"])):
            print(f"  {name:6}" + " ".join(f"{v:6.0f}" for v in r[key]["line_load"]))
    out = dict(benchmark="fe_face_load", issue="50 item 6", case=str(CASE.relative_to(ROOT)),
               machine=dict(platform=platform.platform(), python=platform.python_version()),
               E=ft.E_STEEL, nu=ft.NU_STEEL, normal_load_N=load, face_mm=40.0,
               roll_deg=ROLL, positions=POSITIONS, radii_mm=[r1, r2], curvature_mm=list(rho),
               slopes=list(SLOPES), strips_mm=model_strips().tolist(),
               levels=LEVELS, reference=REFERENCE, fe=fe, model=model,
               plane_strain_pair_stiffness=plane_strain,
               seconds=time.perf_counter() - t0)
    JSON_OUT.write_text(json.dumps(out, indent=1, default=float))
    print(f"\n{time.perf_counter() - t0:.0f} s; wrote {JSON_OUT}")


if __name__ == "__main__":
    main()
