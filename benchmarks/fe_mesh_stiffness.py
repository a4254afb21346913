"""The single-pair mesh stiffness of an aligned spur pair: the project against a 2D FE of
the two teeth in series with their contact (issue 27, item 5d).

Pair: 20/60 teeth, m = 3 mm, alpha = 20 deg, ISO 53 profile A, uncrowned, aligned, 20 mm
face, the project's default backlash thinning and steel (E = 206000 MPa, nu = 0.3), solid
blanks with a bore of half the root radius; 300 N/mm tangential at the pinion's pitch
circle (F_n = 319.25 N/mm).

Project: toothcontact.analyses.analyse with 13 positions over a pitch (rolls -9, -7.5, ...
9 deg), which puts positions at roll -4.5 deg (the pitch point, pinion contact radius
30 mm) and -6 deg (29.756 mm, inside the single-pair zone, the leaving pair 29 um open);
the stiffness of a position is its load over its approach per mm of face (as
tests/test_loaded_teeth.py's position_stiffness). Its 2D limit: the same run on faces of
20 and 160 mm (end effects), and its parts in 2D: each member's slice compliance
(ToothCompliance: bending, shear, axial, Sainsot's body) times F_n, plus Weber's
flattening to the tooth's half-thickness (the plane-strain limit of the project's
half-space compression measured to that depth).

FE: tests/fe_mesh_stiffness.py (scikit-fem, P2 plane strain, both whole gears, the bores
tied rigidly, frictionless Signorini contact on the loaded flanks) at refine 1, 2, 4
(contact elements b_H/8, b_H/16, b_H/32 against the Hertz half-width b_H = 0.166 mm;
loaded teeth 0.25, 0.125, 0.0625 mm; the teeth within three 0.6, 0.3, 0.15 mm; 0.14, 0.25,
0.51 million dofs), and at refine 2 with the largest elements halved, a slower grading
and a wider pressure grid (the pitch point), with its
breakdown of each member's indentation into tooth (clamped on its root circle), gear body
and contact (to the half-thickness depth). Also the FE's checks against closed forms: a
rigid-bore annulus in torsion, a slender cantilever (Timoshenko), two discs in Hertz
contact (half-width, peak, Weber's flattening).

Run (5 minutes on 2 idle cores, 9 beside other jobs; --quick: refine 1 and 2 only):

    .venv/bin/python benchmarks/fe_mesh_stiffness.py

Prints the tables and writes benchmarks/fe_mesh_stiffness.json.
"""

from __future__ import annotations

import argparse
import json
import os
import platform
import sys
import time
from concurrent.futures import ProcessPoolExecutor
from pathlib import Path

# one BLAS thread per process: two workers on two cores, spinning BLAS threads slowed
# them several times over
os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")
os.environ.setdefault("OMP_NUM_THREADS", "1")

import numpy as np  # noqa: E402

HERE = Path(__file__).resolve().parent
ROOT = HERE.parent
JSON_OUT = HERE / "fe_mesh_stiffness.json"
sys.path.insert(0, str(ROOT / "tests"))
import fe_mesh_stiffness as fm  # noqa: E402

LINE_LOAD = 300.0          # N/mm tangential
FACE = 20.0
ROLLS = (-4.5, -6.0)       # deg: the pitch point and one more single-pair position
POSITIONS = 13
REFINES = (1.0, 2.0, 4.0)
#: other mesh and grid settings at the pitch point, refine 2: largest elements halved,
#: slower grading, a wider pressure grid
SENSITIVITY = ({"h_max": (1.0, 2.0)}, {"growth": 0.15}, {"reach_b": 3.5})


def project_run(face=FACE, positions=POSITIONS):
    from toothcontact.analyses import analyse
    from toothcontact.case import parse_case

    return analyse(parse_case({
        "kind": "spur", "title": "stiffness check", "teeth": [20, 60], "module": "3 mm",
        "pressure_angle": "20 deg", "helix_angle": "0 deg", "face_width": f"{face} mm",
        "misalignment": {"slope": "0"}, "load": {"tangential_load": f"{LINE_LOAD * face} N"},
        "analysis": {"positions": positions, "interference": False}}))


def project_positions(result, face=FACE):
    """Per roll (deg, rounded to 1e-6): stiffness N/(mm·µm), the lead pair's pinion contact
    radius (mm), the loaded pairs and the other pairs' separations (µm)."""
    rows = result.sections["positions"]
    out = {}
    for roll in sorted({r["roll_deg"] for r in rows}):
        pairs = [r for r in rows if r["roll_deg"] == roll]
        lead = max(pairs, key=lambda r: r["bem_load_N"])
        closing = lead["bem_approach_mm"] - min(r["separation_mm"] for r in pairs)
        load = sum(r["bem_load_N"] for r in pairs)
        out[round(roll, 6)] = {
            "stiffness": load / closing / face * 1e-3,
            "approach_um": closing * 1e3,
            "r1_mm": lead["contact_radius_pinion_mm"],
            "loaded_pairs": sum(r["bem_load_N"] > 0 for r in pairs),
            "other_separation_um": {int(r["pair"]): r["separation_mm"] * 1e3
                                    for r in pairs if r is not lead}}
    return out


def project_parts(r1):
    """The project's model in 2D at pinion radius r1: each member's slice compliance parts
    times F_n (µm) and Weber's flattening to its half-thickness (µm)."""
    from toothcontact.contact.compliance import ToothCompliance

    pair = fm.spur_pair()
    pl = fm.place(pair, r1)
    F_n = LINE_LOAD * pair.operating_pitch_radius / pair.pinion.base_radius
    b, _ = fm.hertz_half_width(F_n, pl.rho1, pl.rho2, fm.E_STEEL, fm.NU_STEEL)
    out, total = {}, 0.0
    for name, gear, radius in (("pinion", pair.pinion, r1),
                               ("gear", pair.gear, float(np.hypot(*(pl.P - pl.centre2))))):
        tc = ToothCompliance(gear, fm.E_STEEL, fm.NU_STEEL)
        bending, shear, axial, body, _ = (np.ravel(x)[0] for x in tc.slices(radius))
        depth = tc.half_thickness(radius)
        weber = fm.weber_flattening(F_n, b, depth, fm.E_STEEL, fm.NU_STEEL)
        parts = {"bending_um": bending * F_n * 1e3, "shear_um": shear * F_n * 1e3,
                 "axial_um": axial * F_n * 1e3, "tooth_um": (bending + shear + axial) * F_n * 1e3,
                 "body_um": body * F_n * 1e3, "contact_um": weber * 1e3,
                 "depth_mm": depth, "radius_mm": radius}
        parts["indentation_um"] = parts["tooth_um"] + parts["body_um"] + parts["contact_um"]
        total += parts["indentation_um"]
        out[name] = parts
    out["approach_um"] = total
    out["stiffness"] = F_n / total
    return out


def fe_case(args):
    r1, refine, options = args
    options = dict(options)
    res = fm.mesh_stiffness(r1, refine=refine, tangential_line_load=LINE_LOAD,
                            breakdown=not options, **options)
    d = {k: v for k, v in res.__dict__.items() if k != "extra"}
    d["neighbour_gap_um"] = {str(k): v for k, v in d["neighbour_gap_um"].items()}
    d["single_pair"] = res.single_pair
    d["breakdown"] = res.extra.get("breakdown")
    d["options"] = options
    return d


def closed_forms():
    out = {}
    for refine in (1.0, 2.0):
        fe, exact = fm.annulus_torsion(refine=refine)
        out[f"annulus_torsion_refine_{refine:g}"] = {"fe_um": fe, "exact_um": exact,
                                                      "error": fe / exact - 1}
        fe, beam = fm.cantilever_deflection(refine=refine)
        out[f"cantilever_refine_{refine:g}"] = {"fe_um": fe, "timoshenko_um": beam,
                                                "error": fe / beam - 1}
        d = fm.disc_pair_contact(refine=refine)
        out[f"hertz_discs_refine_{refine:g}"] = {k: float(v) for k, v in d.items()}
    return out


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--quick", action="store_true", help="refine 1 and 2 only")
    ap.add_argument("--workers", type=int, default=2)
    ap.add_argument("--out", type=Path, default=JSON_OUT)
    args = ap.parse_args(argv)
    t0 = time.perf_counter()
    refines = REFINES[:2] if args.quick else REFINES

    result = project_run()
    summary = result.sections["summary"]
    positions = project_positions(result)
    wide = project_positions(project_run(face=160.0), face=160.0)
    project = {}
    for roll in ROLLS:
        row = positions[round(roll, 6)]
        if row["loaded_pairs"] != 1:
            raise RuntimeError(f"roll {roll}: {row['loaded_pairs']} pairs loaded")
        project[roll] = dict(row, stiffness_face_160=wide[round(roll, 6)]["stiffness"],
                             model_2d=project_parts(row["r1_mm"]))
    print(f"project ({time.perf_counter() - t0:.0f} s): single_stiffness "
          f"{summary['single_stiffness_N_per_mm_um']:.3f}, ISO c' "
          f"{summary['iso_single_stiffness_N_per_mm_um']:.3f} N/(mm·µm)", flush=True)

    jobs = [(project[roll]["r1_mm"], refine, ()) for refine in refines for roll in ROLLS]
    pitch = project[ROLLS[0]]["r1_mm"]
    jobs += [(pitch, 2.0, tuple(o.items())) for o in SENSITIVITY]
    jobs.sort(key=lambda j: -j[1])                   # the longest first
    with ProcessPoolExecutor(max(1, args.workers)) as pool:
        done = dict(zip(jobs, pool.map(fe_case, jobs)))
    fe = {(r1, refine): d for (r1, refine, o), d in done.items() if not o}
    sensitivity = [d for (r1, refine, o), d in done.items() if o]
    checks = closed_forms()

    rows = []
    print("\nroll  r1 mm   refine  h_c mm   h_t mm  dofs (pinion+gear)  FE c  project c  "
          "project/FE-1  neighbour gap after (µm)  FE s")
    for roll in ROLLS:
        pr = project[roll]
        for refine in refines:
            f = fe[(pr["r1_mm"], refine)]
            dev = pr["stiffness"] / f["stiffness"] - 1
            gap = min(a for _, a in f["neighbour_gap_um"].values())
            print(f"{roll:5.2f} {pr['r1_mm']:7.4f} {refine:5.0f} {f['h_contact']:9.4f} "
                  f"{f['h_tooth']:7.4f} {sum(f['dofs'].values()):12d} {f['stiffness']:10.3f} "
                  f"{pr['stiffness']:8.3f} {100 * dev:+9.1f} % {gap:14.1f} {f['seconds']:12.0f}")
            rows.append({"roll_deg": roll, "refine": refine, "fe": f,
                         "project_stiffness": pr["stiffness"], "project_over_fe": dev})
    print("\nbreakdown at the finest mesh (µm, into each member along the line of action): "
          "FE | project's model in 2D")
    finest = max(refines)
    for roll in ROLLS:
        f = fe[(project[roll]["r1_mm"], finest)]["breakdown"]
        m = project[roll]["model_2d"]
        for name in ("pinion", "gear"):
            print(f"{roll:5.2f} {name:6s} tooth {f[name]['tooth_um']:6.2f} | "
                  f"{m[name]['tooth_um']:6.2f}   body {f[name]['body_um']:6.2f} | "
                  f"{m[name]['body_um']:6.2f}   contact {f[name]['contact_um']:6.2f} | "
                  f"{m[name]['contact_um']:6.2f}")
        fa = fe[(project[roll]['r1_mm'], finest)]["delta_um"]
        print(f"{roll:5.2f} approach FE {fa:.2f} µm | project 2D {m['approach_um']:.2f} µm | "
              f"project (20 mm face) {project[roll]['approach_um']:.2f} µm")
    print(f"\nat roll {ROLLS[0]} deg, refine 2, other mesh and grid settings: "
          f"(the default {fe[(pitch, 2.0)]['stiffness']:.4f})")
    for d in sensitivity:
        print(f"  {d['options']}: {d['stiffness']:.4f} N/(mm·µm), "
              f"{sum(d['dofs'].values())} dofs")
    print("\nclosed forms:")
    for k, v in checks.items():
        print(f"  {k}: " + ", ".join(f"{a} {b:.4g}" for a, b in v.items()))

    out = {
        "description": __doc__.split("\n\n")[0],
        "pair": {"teeth": [20, 60], "module_mm": 3.0, "pressure_angle_deg": 20.0,
                 "face_mm": FACE, "tangential_line_load_N_per_mm": LINE_LOAD,
                 "E_MPa": fm.E_STEEL, "nu": fm.NU_STEEL, "bore": "half the root radius"},
        "project_summary": {k: summary[k] for k in ("single_stiffness_N_per_mm_um",
                                                     "iso_single_stiffness_N_per_mm_um",
                                                     "mesh_stiffness_N_per_mm_um",
                                                     "iso_mesh_stiffness_N_per_mm_um")},
        "project": {str(k): v for k, v in project.items()},
        "fe": rows,
        "fe_sensitivity_roll_-4.5_refine_2": sensitivity,
        "closed_forms": checks,
        "seconds": time.perf_counter() - t0,
        "versions": {"python": platform.python_version(), "numpy": np.__version__,
                     "machine": platform.machine(), "cpus": os.cpu_count()},
    }
    args.out.write_text(json.dumps(out, indent=1, default=float) + "\n")
    print(f"\nwrote {args.out} ({out['seconds']:.0f} s)")


if __name__ == "__main__":
    main()
