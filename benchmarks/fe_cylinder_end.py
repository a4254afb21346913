"""3D finite-element reference for a Hertzian line contact at a free end face, beside ours.

Uses tests/fe_reference.py: cylinder_end_line_load (scikit-fem mesh and dofs, trilinear
bricks, SuperLU; the top nodes under the cylinder condensed to their exact Schur complement,
the contact solved on it). A RIGID frictionless cylinder (R = 84 mm, axis along x, length
L = 10b over x in [-L, 0]) pressed into the top face of an elastic block (E = 210000 MPa,
nu = 0.3) to the mid-length line load w of a Hertz half-width b = 1 mm (w = pi E* b^2 /(4R)
= 2157.7 N/mm, p0 = 1373.6 MPa, E* = E/(1 - nu^2)). Two bodies: "free" (the block's end
face x = 0 free: it ends flush with the cylinder) and "run-on" (the block runs on past
x = 0); both run on past the cylinder's other end x = -L. Block depth = half width = run-on
length = size.

Reported: the line load q(x) (N/mm) at the end against mid-length, as the mean over the
last 0.05b, 0.1b, 0.25b and 0.5b and at the last node; the mid-length peak pressure against
Hertz p0. Refinements 1, 1.5, 2 (elements b/8/refine across the contact and at the top,
b/16/refine along x at the end face) at size 2L; the block size at refine 1 for 4L and 8L;
L = 20b at refine 1 (size 2L) as a check of the cylinder's length. Best estimate = finest
mesh at 2L + (8L - 2L at refine 1), as benchmarks/fe_quarter_space.py does.

Ours: toothcontact.contact.pressure.solve_shared on the same problem (a half-space, E*,
the free end as the mirror term FreeEnd with free_end_factor(0.3); the running-on block
without it), the cylinder's load set so that its mid-length line load is w, cells dx along
x and dy across, the same ratios; at L = 10b and 20b.

Run (about 10 minutes on 2 cores; --workers 1 for one process, --quick for refine 1 only):

    .venv/bin/python benchmarks/fe_cylinder_end.py

Prints the tables and writes benchmarks/fe_cylinder_end.json.
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

import numpy as np

HERE = Path(__file__).resolve().parent
ROOT = HERE.parent
JSON_OUT = HERE / "fe_cylinder_end.json"
sys.path.insert(0, str(ROOT / "tests"))
import fe_reference as fr  # noqa: E402

E, NU, R = 210000.0, 0.3, 84.0
E_STAR = E / (1 - NU**2)
B = 1.0                                   # Hertz half-width at mid-length (mm)
W = np.pi * E_STAR * B**2 / (4 * R)       # its line load (N/mm)
P0 = 2 * W / (np.pi * B)
LENGTH = 10 * B
ENDS = (0.05, 0.1, 0.25, 0.5)
REFINES = (1.0, 1.5, 2.0)
SIZE = 2 * LENGTH
SIZES = (4 * LENGTH, 8 * LENGTH)
BODIES = {"free": True, "run-on": False}
OURS_CELLS = ((B / 20, B / 20), (B / 40, B / 40))
OURS_LENGTHS = (LENGTH, 2 * LENGTH)


def _limit_blas():
    try:
        from threadpoolctl import threadpool_limits
        threadpool_limits(1)
    except ImportError:
        pass


def fe_job(body, refine, size, length=LENGTH):
    t = time.perf_counter()
    r = fr.cylinder_end_line_load(R, W, length, end_free=BODIES[body], nu=NU, E=E,
                                  depth=size, width=size, run_on=size, refine=refine,
                                  ends=ENDS)
    keep = r.x >= -length / 2 - 1e-9
    return dict(body=body, refine=refine, size=size, length=length,
                dofs=r.n_dofs, candidates=r.n_candidates,
                seconds=round(time.perf_counter() - t, 1),
                cg_steps=r.iterations, q_mid=r.q_mid, total=r.total, delta=r.delta,
                peak_mid=r.peak_mid, peak_mid_over_p0=r.peak_mid / r.p0_hertz,
                half_width_mid=r.half_width_mid, reach=r.reach,
                last=float(r.q_norm[-1]),
                mean_last={f"{c}b": float(r.end_average(c)) for c in ENDS},
                profile=dict(x=r.x[keep].round(5).tolist(),
                             q_norm=r.q_norm[keep].round(5).tolist()),
                pressure_y=dict(y=r.y.round(5).tolist(), mid=r.p_mid.round(2).tolist(),
                                end=r.p_end.round(2).tolist()))


def ours(end_free, dx, dy, length=LENGTH):
    """Our half-space solver on the cylinder: ratios as for the FE (b = B)."""
    from toothcontact.contact.influence import FreeEnd, free_end_factor
    from toothcontact.contact.pressure import Grid, solve_shared

    t = time.perf_counter()
    nx = int(round(length / dx))
    ny = int(round(6 * B / dy))
    x = -length - 2 * dx + (np.arange(2 * nx + 2) + 0.5) * dx    # -L - 2dx .. +L
    y = -3 * B + (np.arange(ny) + 0.5) * dy
    gap = np.broadcast_to(y**2 / (2 * R), (len(x), ny)).copy()
    mask = np.zeros(gap.shape, bool)
    inside = (x > -length) & (x < 0)
    mask[inside, :] = True
    first_past = int(np.nonzero(x > 0)[0][0])
    ends = (FreeEnd(0, first_past, "high", free_end_factor(NU), length),) if end_free else ()
    load = W * length
    for _ in range(4):                    # the cylinder's load for q_mid = W (to 1e-4)
        s = solve_shared([Grid(gap, dx, dy, mask, None, (), ends)], [load], E_STAR,
                         tol=1e-8, max_iter=2000)[0]
        q = s.pressure_MPa.sum(axis=1) * dy
        xi, qi = x[inside], q[inside]
        mid = float(qi[np.argmin(np.abs(xi + length / 2))])
        if abs(mid / W - 1) < 1e-4:
            break
        load *= W / mid
    return dict(body="free" if end_free else "run-on", length=length, dx=dx, dy=dy,
                seconds=round(time.perf_counter() - t, 1), q_mid=mid,
                peak_mid=float(s.pressure_MPa[inside][np.argmin(np.abs(xi + length / 2))].max()),
                last=float(qi[-1] / mid),
                mean_last={f"{c}b": float(qi[xi > -c * B].mean() / mid) for c in ENDS})


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--workers", type=int, default=min(2, os.cpu_count() or 1))
    parser.add_argument("--out", type=Path, default=JSON_OUT)
    parser.add_argument("--quick", action="store_true", help="refine 1 only, no size checks")
    args = parser.parse_args(argv)
    t0 = time.perf_counter()
    refines = REFINES[:1] if args.quick else REFINES
    jobs = [((b, r, SIZE, LENGTH), (b, r, SIZE, LENGTH)) for r in refines for b in BODIES]
    if not args.quick:
        jobs += [((b, 1.0, s, LENGTH), (b, 1.0, s, LENGTH)) for s in SIZES for b in BODIES]
        jobs += [((b, 1.0, 2 * 2 * LENGTH, 2 * LENGTH), (b, 1.0, 2 * 2 * LENGTH, 2 * LENGTH))
                 for b in BODIES]
    cost = {1.0: 8, 1.5: 40, 2.0: 200}

    def est(key):
        b, r, s, length = key
        return cost[r] * (0.5 if b == "run-on" else 1) * (1 + s / 40) * length / LENGTH

    jobs.sort(key=lambda j: -est(j[0]))
    results = {}
    if args.workers > 1:
        with ProcessPoolExecutor(args.workers, initializer=_limit_blas) as pool:
            futures = {key: pool.submit(fe_job, *a) for key, a in jobs}
            mine = [pool.submit(ours, BODIES[b], dx, dy, length) for length in OURS_LENGTHS
                    for dx, dy in OURS_CELLS for b in BODIES]
            for key, fut in futures.items():
                results[key] = fut.result()
            ours_rows = [f.result() for f in mine]
    else:
        for key, a in jobs:
            results[key] = fe_job(*a)
        ours_rows = [ours(BODIES[b], dx, dy, length) for length in OURS_LENGTHS
                     for dx, dy in OURS_CELLS for b in BODIES]

    def row_text(row):
        return (f"{row['body']:7s} {row['refine']:6.1f} {row['length']:5.0f} {row['size']:5.0f} "
                f"{row['dofs']:7d} {row['seconds']:6.1f} {row['q_mid']:8.1f} "
                f"{row['peak_mid_over_p0']:7.4f} {row['reach']:5.2f} {row['last']:7.3f} "
                + " ".join(f"{row['mean_last'][f'{c}b']:8.4f}" for c in ENDS))

    print(f"Rigid cylinder R = {R} mm on a block, nu = {NU}: b = {B} mm, w = {W:.1f} N/mm, "
          f"p0 = {P0:.1f} MPa; q(end) / q(mid-length)")
    print(f"{'body':7s} {'refine':>6s} {'L':>5s} {'size':>5s} {'dofs':>7s} {'s':>6s} "
          f"{'q_mid':>8s} {'pk/p0':>7s} {'reach':>5s} {'last':>7s} "
          + " ".join(f"{'<' + str(c) + 'b':>8s}" for c in ENDS))
    fe_rows = [results[k] for k, _ in sorted(jobs, key=lambda j: (j[0][3], j[0][2], j[0][1]))]
    for row in fe_rows:
        print(row_text(row))
    best = None
    if not args.quick:
        best = {}
        for b in BODIES:
            best[b] = fr.best_estimate(*(results[key]["mean_last"] for key in (
                (b, max(REFINES), SIZE, LENGTH), (b, 1.0, max(SIZES), LENGTH),
                (b, 1.0, SIZE, LENGTH))))
        print(f"best estimate (refine {max(REFINES)} at size {SIZE:.0f} + size "
              f"{max(SIZES):.0f} - {SIZE:.0f} at refine 1):")
        for b, v in best.items():
            print(f"{b:7s} {'':63s} " + " ".join(f"{v[f'{c}b']:8.4f}" for c in ENDS))
    print("ours (half-space + mirror term for the free end), cells dx x dy (mm):")
    for row in ours_rows:
        print(f"{row['body']:7s} L {row['length']:4.0f} {row['dx']:.4f} x {row['dy']:.4f} "
              f"{row['seconds']:6.1f} s "
              f"q_mid {row['q_mid']:8.1f} peak/p0 {row['peak_mid'] / P0:7.4f} "
              f"last {row['last']:7.3f} "
              + " ".join(f"{row['mean_last'][f'{c}b']:8.4f}" for c in ENDS))

    total = time.perf_counter() - t0
    out = {
        "versions": {"python": platform.python_version(), "numpy": np.__version__,
                     "scikit-fem": __import__("skfem").__version__,
                     "machine": platform.machine(), "cpus": os.cpu_count()},
        "wall_seconds": round(total, 1), "workers": args.workers,
        "units": "mm, N, MPa",
        "setup": (f"rigid frictionless cylinder R = {R}, x in [-L, 0], on a block E = {E}, "
                  f"nu = {NU}; mid-length line load w = {W:.3f} N/mm (Hertz b = {B}, p0 = "
                  f"{P0:.2f}); block depth = half width = run-on length = size, bottom fixed; "
                  "free: end face x = 0 free; run-on: block runs on past x = 0; both run on "
                  "past x = -L. Ratios: mean q over the last c*b over q(-L/2); peak_mid: "
                  "nodal pressure at x = -L/2, y = 0"),
        "fe": fe_rows, "fe_best_estimate_mean_last": best,
        "ours": ours_rows,
    }
    args.out.write_text(json.dumps(out, indent=1) + "\n")
    print(f"\n{total:.0f} s on {args.workers} worker(s); wrote {args.out}")


if __name__ == "__main__":
    main()
