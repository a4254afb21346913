"""Independent 3D finite-element check of the tooth compliance model along the face (issue 27,
item 5c), beside the model (contact.compliance: slice compliance c and Vlasov coupling
length λ from ToothCompliance(gear, E, nu).at(r), the free-ended Pasternak line
contact.structure.FaceCoupling).

FE (tests/fe_tooth.py): the whole gear's exact section (ToothOutline, every tooth, the bore
at half the root radius held), plane strain (quadratic triangles) and extruded over the face
(quadratic tetrahedra, free end faces; scikit-fem, a multifrontal Cholesky). Tooth 0 is
loaded on its flank along the transverse normal at three radii (the pitch radius and 1.5 mm
below and above it) over a patch 0.3 mm up the profile: (a) 1 mm long in mid-face, (b) 1 mm
long touching a face end, (c) a uniform line load over the whole face. E = 206000 MPa,
nu = 0.3. Teeth: the pinion (z = 20, m = 3) and the gear (z = 60, m = 3) of
cases/spur_crowned_20_60.toml, and a z = 17, m = 4 tooth (x = 0, ISO 53 A, b = 30 mm).

Deflections are per unit load, along the load's normal, at the point where the line of
action crosses the tooth's centre line ("centre": the model's reference; the primary
measure), or the patch's work-conjugate mean less the half-space compression to the
half-thickness that the contact solver adds to the model ("surface": Weber's flattening,
influence.InfluenceOperator with a reference depth, plus φ times the mirrored patch at the
end face; sensitive to how finely the indentation is meshed).

Compared (each tooth, radius, mesh):
 (1) c: FE uniform-line-load deflection at mid-face (3D) and plane strain (2D) against c;
 (2) end/mid: the deflection under the end patch over that under the mid-face patch;
 (3) decay: L of A·cosh((b/2 - |z|)/L)/cosh(b/(2L)) fitted to the mid-face load's FE profile
     over |z| >= 3 mm (and 2, 4 mm; plain exponential too), and λ_match, the coupling
     length with which the model's mid-face-patch over uniform-load deflection equals FE's;
 (4) the mid-face patch's deflection, FE against the model c·G;
and, in plane strain on a fine section mesh, the slice compliance split into the teeth alone
(the disc inside the root circle made rigid) and the body, against the model's parts.
The model compared is the corrected one (compliance.SLICE_FACTOR = 0.815 and
COUPLING_PER_ROOT_CHORD = 0.739, fitted by this benchmark on the beam's slices: FE/c was
0.80-0.83 and λ_match 0.72-0.76 S_f), its coupling fading at the free ends over
Reissner's layer (structure.end_layer, from benchmarks/fe_face_load.py; the model's
ratio, 1.87 before it). "model as is" gives its errors; the correction block fits what a
further correction would still take on the line without the end layer (fitted on the
pinion at r = 30 mm, medium mesh; validated on the other radii and the two other teeth,
coarse mesh): c' = κ_c·c, λ' = κ_λ·S_f (S_f the root chord), and an end softening β
(fe_tooth.model_line: flexibility D·G·D, D² = 1 + (β - 1)·(e^(-2 d0/λ') + e^(-2 d1/λ')),
d0, d1 the distances to the face ends), which the model does not take: it softens the
ends under a uniform load too (see compliance).

Run (about 8 minutes on 2 cores, 10 GB of memory at most):

    .venv/bin/python benchmarks/fe_tooth_face.py [--quick]

--quick: the coarse pinion only. Prints the tables and writes benchmarks/fe_tooth_face.json.
"""

from __future__ import annotations

import argparse
import json
import math
import platform
import sys
import time
from pathlib import Path

HERE = Path(__file__).resolve().parent
ROOT = HERE.parent
JSON_OUT = HERE / "fe_tooth_face.json"
sys.path.insert(0, str(ROOT / "tests"))
import fe_tooth as ft  # noqa: E402

PATCHES = ((-0.5, 0.5), (14.0, 15.0))       # mid-face and end patches, b = 30 mm
CALIBRATION = ("pinion", "medium", 1)         # tooth, mesh, site index (r = 30 mm)


def gears():
    from toothcontact.surfaces.involute import CylindricalGear

    pinion, gear = ft.case_gears()
    return {"pinion": pinion, "gear60": gear,
            "z17m4": CylindricalGear(17, 4.0, math.radians(20), 30.0)}


def runs(quick: bool):
    if quick:
        return [("pinion", "coarse")]
    return [("pinion", "coarse"), ("pinion", "medium"), ("gear60", "coarse"),
            ("z17m4", "coarse")]


def dimensions(gear) -> dict:
    from toothcontact.contact.compliance import ToothCompliance

    teeth = ToothCompliance(gear, ft.E_STEEL, ft.NU_STEEL)
    return dict(height=gear.tip_radius - gear.root_radius_value, module=gear.normal_module,
                root_chord=2.0 * teeth.root_radius * math.sin(teeth.root_half_angle),
                rim=gear.root_radius_value - 0.5 * gear.root_radius_value)


def calibrate(site: dict, dims: dict) -> dict:
    """κ_c, κ_λ (of the root chord and of the height) and β from one site's FE (centre)."""
    fe, model = site["fe"], site["model"]
    kappa_c = fe["c_3d_centre"] / model["c"]
    ratio_mid = fe["mid_centre"] / fe["c_3d_centre"]
    lam, beta = fe["lambda_match_centre"], 1.0
    for _ in range(4):                   # λ and β together (β barely moves mid-face)
        beta = ft.matching_end_factor(fe["ratio_centre"], lam, 15.0, PATCHES)
        lam = _lambda_for(ratio_mid, beta)
    return dict(kappa_c=kappa_c, lam=lam, beta=beta,
                kappa_lambda_root_chord=lam / dims["root_chord"],
                kappa_lambda_height=lam / dims["height"])


def _lambda_for(ratio_mid: float, beta: float) -> float:
    from scipy.optimize import brentq

    return float(brentq(lambda L: ft.model_line(1.0, L, -15.0, 15.0, PATCHES,
                                                end_factor=beta)[2][0] - ratio_mid,
                        0.3, 100.0, xtol=1e-6))


def validate(site: dict, dims: dict, cal: dict, by: str) -> dict:
    """The corrected model (c', λ' from `by`, β) at a site against its FE (centre)."""
    fe, model = site["fe"], site["model"]
    c1 = cal["kappa_c"] * model["c"]
    lam1 = cal[f"kappa_lambda_{by}"] * dims[by]
    mid, end = ft.model_line(c1, lam1, -15.0, 15.0, PATCHES, end_factor=cal["beta"])[2]
    return dict(by=by, c=c1, coupling_length=lam1, mid=mid, end=end, ratio=end / mid,
                err_c=c1 / fe["c_3d_centre"] - 1, err_mid=mid / fe["mid_centre"] - 1,
                err_end=end / fe["end_centre"] - 1,
                err_ratio=(end / mid) / fe["ratio_centre"] - 1,
                err_lambda=lam1 / fe["lambda_match_centre"] - 1)


def slice_diagnostic(name: str, gear) -> list[dict]:
    """Plane strain on a fine section mesh (whole gear): the FE slice compliance at the
    three radii, and the teeth alone (the disc inside the root circle made 10⁴ times
    stiffer), against the model's total and its parts (bending + shear + axial: the tooth;
    the Sainsot body term)."""
    from toothcontact.contact.compliance import ToothCompliance

    teeth = ToothCompliance(gear, ft.E_STEEL, ft.NU_STEEL)
    rp = gear.pitch_radius
    radii = (rp - 1.5, rp, rp + 1.5)
    S = ft.section_mesh(gear, radii, 0.05, 0.25 * gear.normal_module / 3.0, 3.0, growth=0.25)
    whole = ft.plane_strain(S)
    alone = ft.plane_strain(S, stiff_below=gear.root_radius_value)
    rows = []
    for i, r in enumerate(radii):
        parts = [float(p[0, 0]) for p in teeth.slices(r)[:4]]
        rows.append(dict(tooth=name, radius=r, dofs=whole["dofs"], model=sum(parts),
                         model_tooth=sum(parts[:3]), model_body=parts[3],
                         fe=whole["centre"][i], fe_tooth=alone["centre"][i],
                         fe_body=whole["centre"][i] - alone["centre"][i]))
    return rows


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--quick", action="store_true")
    args = ap.parse_args()
    t_start = time.perf_counter()
    teeth = gears()
    results = []
    for name, level in runs(args.quick):
        gear = teeth[name]
        rp = gear.pitch_radius
        print(f"{name} (z = {gear.teeth}, m = {gear.normal_module:g}), mesh {level}:", flush=True)
        t0 = time.perf_counter()
        r = ft.face_study(gear, radii=(rp - 1.5, rp, rp + 1.5), **ft.LEVELS[level])
        r.update(name=name, level=level, dimensions=dimensions(gear),
                 seconds=time.perf_counter() - t0)
        print(f"  {r['seconds']:.0f} s", flush=True)
        results.append(r)

    print("\nFE against the model, per unit load (centre: at the tooth's centre line; surface: "
          "patch mean less the half-space\ncompression to the half-thickness). c in mm²/N "
          "(×1e-5), deflections in mm/N (×1e-6), lengths in mm.")
    head = (f"{'tooth':8} {'mesh':6} {'r':>6} {'dofs':>7} | {'c':>5} {'FE3D':>5} {'FE2D':>5} "
            f"{'FE/c':>5} | {'mid':>5} {'FEc':>5} {'FEs':>5} {'mod/FE':>6} | {'ratio':>5} "
            f"{'FEc':>5} {'FEs':>5} | {'λ':>5} {'λmatch':>6} {'L fit':>5} {'L exp':>5}")
    print(head)
    for r in results:
        for s in r["sites"]:
            fe, m, fit = s["fe"], s["model"], s["fits"]["centre_3"]
            print(f"{r['name']:8} {r['level']:6} {s['radius']:6.2f} "
                  f"{r['mesh']['dofs_3d_half']:7d} | "
                  f"{m['c'] * 1e5:5.2f} {fe['c_3d_centre'] * 1e5:5.2f} "
                  f"{fe['c_2d_centre'] * 1e5:5.2f} {fe['c_3d_centre'] / m['c']:5.3f} | "
                  f"{m['mid'] * 1e6:5.2f} {fe['mid_centre'] * 1e6:5.2f} "
                  f"{fe['mid_surface'] * 1e6:5.2f} {m['mid'] / fe['mid_centre']:6.2f} | "
                  f"{m['ratio']:5.2f} {fe['ratio_centre']:5.2f} {fe['ratio_surface']:5.2f} | "
                  f"{m['coupling_length']:5.2f} {fe['lambda_match_centre']:6.2f} "
                  f"{fit['L']:5.2f} {fit['L_exp']:5.2f}")

    # mesh convergence: the pinion's medium mesh against its coarse one
    levels = {r["level"]: r for r in results if r["name"] == "pinion"}
    convergence = []
    if {"coarse", "medium"} <= set(levels):
        print("\nPinion, medium mesh over coarse mesh - 1 (centre measure unless named):")
        keys = ("c_3d_centre", "c_2d_centre", "c_3d_surface", "mid_centre", "mid_surface",
                "end_centre", "ratio_centre", "ratio_surface", "lambda_match_centre")
        print(f"{'r':>6} " + " ".join(f"{k:>14}" for k in keys + ("fit L",)))
        for a, b in zip(levels["coarse"]["sites"], levels["medium"]["sites"]):
            row = {k: b["fe"][k] / a["fe"][k] - 1 for k in keys}
            row["fit L"] = b["fits"]["centre_3"]["L"] / a["fits"]["centre_3"]["L"] - 1
            convergence.append(dict(radius=a["radius"], **row))
            print(f"{a['radius']:6.2f} " + " ".join(f"{v:+14.1%}" for v in row.values()))
    summary = dict(convergence=convergence)
    if not args.quick:
        print("\nSlice compliance, plane strain on a fine section mesh (x1e-5 mm²/N; the model: "
              "the beam's slices, before SLICE_FACTOR; the tooth: the disc inside the root "
              "circle rigid; the body: the rest):")
        print(f"{'tooth':8} {'r':>6} {'dofs':>6} | {'model':>6} {'FE':>6} {'FE/c':>5} | "
              f"{'tooth':>6} {'FE':>6} {'FE/m':>5} | {'body':>6} {'FE':>6} {'FE/m':>5}")
        diagnostic = []
        for name in ("pinion", "gear60", "z17m4"):
            for d in slice_diagnostic(name, teeth[name]):
                diagnostic.append(d)
                print(f"{name:8} {d['radius']:6.2f} {d['dofs']:6d} | {d['model'] * 1e5:6.3f} "
                      f"{d['fe'] * 1e5:6.3f} {d['fe'] / d['model']:5.3f} | "
                      f"{d['model_tooth'] * 1e5:6.3f} {d['fe_tooth'] * 1e5:6.3f} "
                      f"{d['fe_tooth'] / d['model_tooth']:5.3f} | {d['model_body'] * 1e5:6.3f} "
                      f"{d['fe_body'] * 1e5:6.3f} {d['fe_body'] / d['model_body']:5.3f}")
        summary["slice_plane_strain_fine"] = diagnostic
    if not args.quick:
        cal_run = next(r for r in results if (r["name"], r["level"]) == CALIBRATION[:2])
        cal = calibrate(cal_run["sites"][CALIBRATION[2]], cal_run["dimensions"])
        print(f"\nCorrection fitted on the pinion, r = 30 mm, medium mesh: "
              f"c' = {cal['kappa_c']:.3f}·c, λ' = {cal['lam']:.2f} mm "
              f"= {cal['kappa_lambda_root_chord']:.3f}·S_f = {cal['kappa_lambda_height']:.3f}·h, "
              f"end factor β = {cal['beta']:.3f}")
        print(f"{'tooth':8} {'mesh':6} {'r':>6} {'by':>10} | {'λ_match/S_f':>11} "
              f"{'λ_match/h':>9} | {'err c':>6} {'err λ':>6} {'err mid':>7} {'err end':>7} "
              f"{'err ratio':>9} | model as is: {'mid':>6} {'end':>6} {'ratio':>6}")
        checks = []
        for r in results:
            if r["level"] != "coarse":
                continue
            for k, s in enumerate(r["sites"]):
                for by in ("root_chord", "height"):
                    v = validate(s, r["dimensions"], cal, by)
                    fe, m = s["fe"], s["model"]
                    v.update(tooth=r["name"], radius=s["radius"],
                             as_is=dict(err_c=m["c"] / fe["c_3d_centre"] - 1,
                                        err_mid=m["mid"] / fe["mid_centre"] - 1,
                                        err_end=m["end"] / fe["end_centre"] - 1,
                                        err_ratio=m["ratio"] / fe["ratio_centre"] - 1))
                    checks.append(v)
                    print(f"{r['name']:8} {r['level']:6} {s['radius']:6.2f} {by:>10} | "
                          f"{fe['lambda_match_centre'] / r['dimensions']['root_chord']:11.3f} "
                          f"{fe['lambda_match_centre'] / r['dimensions']['height']:9.3f} | "
                          f"{v['err_c']:+6.1%} {v['err_lambda']:+6.1%} {v['err_mid']:+7.1%} "
                          f"{v['err_end']:+7.1%} {v['err_ratio']:+9.1%} | "
                          f"{v['as_is']['err_mid']:+6.0%} {v['as_is']['err_end']:+6.0%} "
                          f"{v['as_is']['err_ratio']:+6.0%}")
        summary.update(calibration=dict(cal, tooth=CALIBRATION[0], mesh=CALIBRATION[1],
                                        radius=cal_run["sites"][CALIBRATION[2]]["radius"]),
                       validation=checks)
    total = time.perf_counter() - t_start
    print(f"\ntotal {total:.0f} s")
    out = dict(benchmark="fe_tooth_face", issue="27 item 5c",
               machine=dict(platform=platform.platform(), python=platform.python_version()),
               E=ft.E_STEEL, nu=ft.NU_STEEL, patches_mm=PATCHES, levels=ft.LEVELS,
               seconds=total, runs=results, **summary)
    JSON_OUT.write_text(json.dumps(out, indent=1, default=float))
    print(f"wrote {JSON_OUT}")


if __name__ == "__main__":
    main()
