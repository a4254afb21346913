"""3D finite-element reference for a MIXED free end (a worm set's), beside ours.

The worm wheel's face ends while the worm's thread runs on past it: two elastic bodies in a
frictionless Hertzian line contact along x over [-L, 0] (L = 10b), the gap y^2/(2R) between
them (R = 84 mm, the mid-length line load w that gives a Hertz half-width b = 1 mm on the
pair's E*: w = pi E* b^2/(4R) = 703.7 N/mm, p0 = 448.0 MPa). Body A (the wheel, bronze
E = 98000 MPa, nu = 0.35) ends at x = 0 with a free end face; body B (the worm, steel
E = 210000 MPa, nu = 0.3):

  mixed  B runs on past x = 0 (by the block size);
  flush  B ends at x = 0 too (both end faces free);
  A-rigid  body A alone under a rigid cylinder (tests/fe_reference.py
           cylinder_end_line_load, nu = 0.35; the diagnostic of the flush case).

Uses tests/fe_reference.py: mixed_end_line_load (scikit-fem mesh and dofs, trilinear
bricks, SuperLU; each body a block whose contact-face u_z dofs on the same x-y nodes are
condensed to their exact Schur complement; the contact solved on C_A + C_B and the rigid
gap). Both blocks run on past x = -L; block depth = half width = run-on length = size.

Reported: the line load q(x) (N/mm) at A's end against mid-length, as the mean over the
last 0.05b, 0.1b, 0.25b and 0.5b and at the last node; the mid-length peak pressure
against Hertz p0. Refinements 1, 1.5, 2 (elements b/8/refine across the contact and at the
top, b/16/refine along x at the end face) at size 2L; the block size at refine 1 for 4L
and 8L; L = 20b at refine 1 (size 2L, mixed) as a check of the contact's length; the same for
A-rigid. Best estimate = finest mesh at 2L + (8L - 2L at refine 1), as
benchmarks/fe_cylinder_end.py.

Ours: toothcontact.contact.pressure.solve_shared on the same problem (a half-space with
the pair's E*, the load set so that the mid-length line load is w, cells dx x dy): mixed,
ONE FreeEnd at x = 0 weighted as loaded._member_ends weights body A (phi(0.35) times A's
share of the composite compliance; B runs on: no mirror); flush, both members' ends merged
as loaded._merged does (one FreeEnd, the weights summed); A-rigid, phi(0.35) on E_A*.

Also (why ours misses where it does): ours with the mirror's reach varied (5b, 10b = L,
untapered), and the end weight that would match the FE at each c (a scan of weights).

Run (about 40 minutes on 2 loaded cores, one worker; --quick: refine 1 only):

    PYTHONPATH=src .venv/bin/python benchmarks/fe_mixed_end.py

Prints the tables and writes benchmarks/fe_mixed_end.json.
"""

from __future__ import annotations

import argparse
import json
import os
import platform
import sys
import time
from pathlib import Path
from types import SimpleNamespace

import numpy as np

HERE = Path(__file__).resolve().parent
ROOT = HERE.parent
JSON_OUT = HERE / "fe_mixed_end.json"
sys.path.insert(0, str(ROOT / "tests"))
sys.path.insert(0, str(ROOT / "src"))
import fe_reference as fr  # noqa: E402

E_A, NU_A = 98000.0, 0.35                 # the wheel: bronze, ends at x = 0
E_B, NU_B = 210000.0, 0.3                 # the worm: steel, runs on (or ends flush)
R = 84.0
C_A, C_B = (1 - NU_A**2) / E_A, (1 - NU_B**2) / E_B
E_STAR = 1 / (C_A + C_B)
B = 1.0                                   # Hertz half-width at mid-length (mm)
W = np.pi * E_STAR * B**2 / (4 * R)       # its line load (N/mm)
P0 = 2 * W / (np.pi * B)
LENGTH = 10 * B
ENDS = (0.05, 0.1, 0.25, 0.5)
REFINES = (1.0, 1.5, 2.0)
SIZE = 2 * LENGTH
SIZES = (4 * LENGTH, 8 * LENGTH)
BODIES = ("mixed", "flush")
ALL = BODIES + ("A-rigid",)
OURS_CELLS = ((B / 20, B / 20), (B / 40, B / 40))


def _limit_blas():
    try:
        from threadpoolctl import threadpool_limits
        threadpool_limits(1)
    except ImportError:
        pass


def member_weights():
    """loaded._member_ends for the pair: {"A": phi(0.35) s_A, "B": phi(0.3) s_B}."""
    from toothcontact.contact.loaded import _member_ends

    members = {"A": SimpleNamespace(E=E_A, nu=NU_A), "B": SimpleNamespace(E=E_B, nu=NU_B)}
    return _member_ends(SimpleNamespace(members=members))


def fe_job(body, refine, size, length=LENGTH):
    t = time.perf_counter()
    kw = dict(depth=size, width=size, run_on=size, refine=refine, ends=ENDS)
    if body == "A-rigid":
        load = np.pi * E_A / (1 - NU_A**2) * B**2 / (4 * R)
        r = fr.cylinder_end_line_load(R, load, length, end_free=True, nu=NU_A, E=E_A, **kw)
    else:
        r = fr.mixed_end_line_load(R, W, length, b_runs_on=body == "mixed", E_a=E_A,
                                   nu_a=NU_A, E_b=E_B, nu_b=NU_B, **kw)
    keep = r.x >= -length / 2 - 1e-9
    return dict(body=body, refine=refine, size=size, length=length,
                dofs=r.n_dofs, dofs_by_body=r.dofs or {"A": r.n_dofs},
                candidates=r.n_candidates, seconds=round(time.perf_counter() - t, 1),
                cg_steps=r.iterations, q_mid=r.q_mid, total=r.total, delta=r.delta,
                peak_mid=r.peak_mid, peak_mid_over_p0=r.peak_mid / r.p0_hertz,
                half_width_mid=r.half_width_mid, reach=r.reach,
                last=float(r.q_norm[-1]),
                mean_last={f"{c}b": float(r.end_average(c)) for c in ENDS},
                profile=dict(x=r.x[keep].round(5).tolist(),
                             q_norm=r.q_norm[keep].round(5).tolist()),
                pressure_y=dict(y=r.y.round(5).tolist(), mid=r.p_mid.round(2).tolist(),
                                end=r.p_end.round(2).tolist()))


def ours(body, dx, dy, length=LENGTH, weight=None, reach=None):
    """Our half-space solver on the same contact: ratios as for the FE (b = B). The mirror
    acts within reach (mm; default `length`, as benchmarks/fe_cylinder_end.py: taper 1 to
    mid-length, a cosine to 0 at the contact's far end; 4 length: untapered over the
    contact); weight: the end's weight instead of the members' (the weight scan)."""
    from toothcontact.contact.loaded import _merged
    from toothcontact.contact.influence import FreeEnd, free_end_factor
    from toothcontact.contact.pressure import Grid, solve_shared

    t = time.perf_counter()
    weights = member_weights()
    if body == "A-rigid":
        e_star, load_mid, names = E_A / (1 - NU_A**2), np.pi * E_A / (1 - NU_A**2) / (4 * R), ()
    else:
        e_star, load_mid, names = E_STAR, W, ("A",) if body == "mixed" else ("A", "B")
    nx = int(round(length / dx))
    ny = int(round(6 * B / dy))
    x = -length - 2 * dx + (np.arange(2 * nx + 2) + 0.5) * dx    # -L - 2dx .. +L
    y = -3 * B + (np.arange(ny) + 0.5) * dy
    gap = np.broadcast_to(y**2 / (2 * R), (len(x), ny)).copy()
    mask = np.zeros(gap.shape, bool)
    inside = (x > -length) & (x < 0)
    mask[inside, :] = True
    first_past = int(np.nonzero(x > 0)[0][0])
    reach = length if reach is None else reach
    if weight is not None:
        ends = (FreeEnd(0, first_past, "high", weight, reach),)
    elif body == "A-rigid":
        ends = (FreeEnd(0, first_past, "high", free_end_factor(NU_A), reach),)
    else:
        ends = _merged([FreeEnd(0, first_past, "high", weights[n], reach) for n in names])
    load = load_mid * length
    for _ in range(6):                    # the contact's load for q_mid = w (to 1e-4)
        s = solve_shared([Grid(gap, dx, dy, mask, None, (), ends)], [load], e_star,
                         tol=1e-8, max_iter=2000)[0]
        q = s.pressure_MPa.sum(axis=1) * dy
        xi, qi = x[inside], q[inside]
        mid = float(qi[np.argmin(np.abs(xi + length / 2))])
        if abs(mid / load_mid - 1) < 1e-4:
            break
        load *= load_mid / mid
    return dict(body=body, length=length, dx=dx, dy=dy, E_star=e_star, reach=reach,
                end_weights=[e.weight for e in ends],
                seconds=round(time.perf_counter() - t, 1), q_mid=mid,
                peak_mid_over_p0=float(s.pressure_MPa[inside][np.argmin(
                    np.abs(xi + length / 2))].max()) / (2 * load_mid / np.pi / B),
                last=float(qi[-1] / mid),
                mean_last={f"{c}b": float(qi[xi > -c * B].mean() / mid) for c in ENDS})


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--out", type=Path, default=JSON_OUT)
    parser.add_argument("--quick", action="store_true", help="refine 1 only, no size checks")
    parser.add_argument("--cache", type=Path, default=None,
                        help="folder keeping each FE job's row (a rerun takes them from it)")
    args = parser.parse_args(argv)
    _limit_blas()
    t0 = time.perf_counter()
    refines = REFINES[:1] if args.quick else REFINES
    jobs = [(b, r, SIZE, LENGTH) for b in ALL for r in refines]
    if not args.quick:
        jobs += [(b, 1.0, s, LENGTH) for b in ALL for s in SIZES]
        jobs += [("mixed", 1.0, 2 * 2 * LENGTH, 2 * LENGTH)]

    def row_text(row):
        return (f"{row['body']:7s} {row['refine']:6.1f} {row['length']:5.0f} {row['size']:5.0f} "
                f"{row['dofs']:7d} {row['candidates']:5d} {row['seconds']:6.1f} "
                f"{row['q_mid']:8.1f} {row['peak_mid_over_p0']:7.4f} {row['reach']:5.2f} "
                f"{row['last']:7.3f} "
                + " ".join(f"{row['mean_last'][f'{c}b']:8.4f}" for c in ENDS))

    print(f"Bronze A (E {E_A:.0f}, nu {NU_A}) ends at x = 0; steel B (E {E_B:.0f}, nu {NU_B}); "
          f"R = {R} mm: E* = {E_STAR:.1f} MPa, b = {B} mm, w = {W:.1f} N/mm, "
          f"p0 = {P0:.1f} MPa; q(end) / q(mid-length)")
    head = (f"{'body':7s} {'refine':>6s} {'L':>5s} {'size':>5s} {'dofs':>7s} {'cand':>5s} "
            f"{'s':>6s} {'q_mid':>8s} {'pk/p0':>7s} {'reach':>5s} {'last':>7s} "
            + " ".join(f"{'<' + str(c) + 'b':>8s}" for c in ENDS))
    print(head, flush=True)
    jobs.sort(key=lambda k: (k[1], k[3], k[2]))     # the cheap ones first
    results = {}
    for key in jobs:
        kept = args.cache / ("_".join(map(str, key)) + ".json") if args.cache else None
        if kept is not None and kept.exists():
            results[key] = json.loads(kept.read_text())
        else:
            results[key] = fe_job(*key)
            if kept is not None:
                kept.parent.mkdir(parents=True, exist_ok=True)
                kept.write_text(json.dumps(results[key]))
        print(row_text(results[key]), flush=True)
    fe_rows = [results[k] for k in sorted(jobs, key=lambda k: (k[0], k[3], k[2], k[1]))]
    best = None
    if not args.quick:
        best = {}
        for b in ALL:
            best[b] = fr.best_estimate(*(results[key]["mean_last"] for key in (
                (b, max(REFINES), SIZE, LENGTH), (b, 1.0, max(SIZES), LENGTH),
                (b, 1.0, SIZE, LENGTH))))
        print(f"best estimate (refine {max(REFINES)} at size {SIZE:.0f} + size "
              f"{max(SIZES):.0f} - {SIZE:.0f} at refine 1):")
        for b, v in best.items():
            print(f"{b:7s} {'':69s} " + " ".join(f"{v[f'{c}b']:8.4f}" for c in ENDS))
    ours_rows = [ours(b, dx, dy) for b in ALL for dx, dy in OURS_CELLS]
    ours_rows += [ours("mixed", dx, dy, 2 * LENGTH) for dx, dy in OURS_CELLS]
    print("ours (half-space + mirror term, weights as loaded._member_ends), cells dx x dy (mm):")
    for row in ours_rows:
        print(f"{row['body']:7s} L {row['length']:4.0f} {row['dx']:.4f} x {row['dy']:.4f} "
              f"{row['seconds']:6.1f} s weight {sum(row['end_weights']):.4f} "
              f"q_mid {row['q_mid']:8.1f} pk/p0 {row['peak_mid_over_p0']:7.4f} "
              f"last {row['last']:7.3f} "
              + " ".join(f"{row['mean_last'][f'{c}b']:8.4f}" for c in ENDS))
    # why: the mirror's reach (its taper) on the half-space, and the end weight that would
    # match the FE at each c (no one weight matches all: the mirror's shape, not its weight)
    cell = OURS_CELLS[0][0]
    reach_rows = [ours(b, cell, cell, reach=r) for b in BODIES
                  for r in (LENGTH / 2, LENGTH, 4 * LENGTH)]
    print(f"ours against the mirror's reach (cells {cell}): reach 5b, 10b (= L, the rows "
          "above), 40b (untapered over the contact)")
    for row in reach_rows:
        print(f"{row['body']:7s} reach {row['reach']:5.1f} "
              + " ".join(f"{row['mean_last'][f'{c}b']:8.4f}" for c in ENDS))
    from toothcontact.contact.influence import free_end_factor

    weights = member_weights()
    scan_weights = np.round(np.arange(0.6, 2.01, 0.1), 2)
    scan = {b: [ours(b, cell, cell, weight=float(w))["mean_last"] for w in scan_weights]
            for b in ALL}
    matching = {}
    if best is not None:
        print(f"the end weight that would match the FE best estimate (cells {cell}; ours "
              f"falls with the weight; the members': mixed {weights['A']:.3f}, flush "
              f"{weights['A'] + weights['B']:.3f}, A-rigid phi(0.35) = {free_end_factor(NU_A)}):")
        for b in ALL:
            matching[b] = {}
            for c in ENDS:
                k = f"{c}b"
                ratios = np.array([m[k] for m in scan[b]])
                inside = ratios.min() <= best[b][k] <= ratios.max()
                matching[b][k] = (float(np.interp(best[b][k], ratios[::-1], scan_weights[::-1]))
                                  if inside else None)
            print(f"{b:7s} " + " ".join(
                f"{c}b {matching[b][f'{c}b']:6.3f}" if matching[b][f"{c}b"] is not None
                else f"{c}b {'n/a':>6s}" for c in ENDS))

    compare = {}
    if best is not None:
        print("ours (cells b/40, L = 10b) against the FE best estimate, relative difference:")
        for b in ALL:
            mine = next(r for r in ours_rows if r["body"] == b and r["dx"] == OURS_CELLS[-1][0]
                        and r["length"] == LENGTH)
            compare[b] = {k: mine["mean_last"][k] / best[b][k] - 1 for k in best[b]}
            print(f"{b:7s} " + " ".join(f"{c}b {compare[b][f'{c}b']:+7.1%}" for c in ENDS))

    total = time.perf_counter() - t0
    out = {
        "versions": {"python": platform.python_version(), "numpy": np.__version__,
                     "scipy": __import__("scipy").__version__,
                     "scikit-fem": __import__("skfem").__version__,
                     "machine": platform.machine(), "cpus": os.cpu_count()},
        "wall_seconds": round(total, 1), "workers": 1,
        "units": "mm, N, MPa",
        "setup": (f"two elastic blocks in a frictionless line contact along x in [-L, 0], gap "
                  f"y^2/(2R), R = {R}: A (E = {E_A}, nu = {NU_A}) ends at x = 0 with a free "
                  f"end face; B (E = {E_B}, nu = {NU_B}) runs on past x = 0 (mixed) or ends "
                  f"there too (flush); A-rigid: A under a rigid cylinder (its own E*, b = 1). "
                  f"Pair E* = {E_STAR:.2f}; mid-length line load w = {W:.3f} N/mm (Hertz b = "
                  f"{B}, p0 = {P0:.2f}); block depth = half width = run-on length = size, "
                  "bottom fixed; both blocks run on past x = -L. Ratios: mean q over the last "
                  "c*b over q(-L/2); peak_mid: nodal pressure at x = -L/2, y = 0"),
        "member_weights": member_weights(),
        "fe": fe_rows, "fe_best_estimate_mean_last": best,
        "ours": ours_rows, "ours_b40_vs_fe_best": compare,
        "ours_reach": reach_rows,
        "ours_weight_scan": {"cells": cell, "weights": scan_weights.tolist(),
                             "mean_last": scan, "weight_matching_fe_best": matching},
    }
    args.out.write_text(json.dumps(out, indent=1) + "\n")
    print(f"\n{total:.0f} s on 1 worker; wrote {args.out}")


if __name__ == "__main__":
    main()
