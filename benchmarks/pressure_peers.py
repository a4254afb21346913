"""Elastic half-space contact: toothcontact.contact.pressure against ContactMechanics.

Both solvers, in one process, solve the same Hertz problem: gap h = A·x² + B·y²
(A = 0.02 /mm, B/A = 1, 4, 40, 400), W = 2500 N, steel on steel (E* = 115385 MPa), on
256² and 512² grids spanning ±1.4 × the Hertz semi-axes along each axis. ContactMechanics
(Pastewka group, MIT) runs its non-periodic FreeFFTElasticHalfSpace with the Polonsky-Keer
constrained conjugate gradients (make_system(...).minimize_proxy(external_force=W)),
once at its default tolerances and once with pentol = 1e-8 × the Hertz approach, which is
the accuracy our solver is run at (relative gap error 1e-8). Reported per case: wall time
(best of --repeat, setup included: the peer builds its substrate, we start with an empty
influence-operator cache; our time with the operator cached is given too), iterations,
max |p_ours - p_peer| / p0, the speed ratio peer/ours, and both solutions' errors against
exact Hertz (analytic.hertz). Ours runs in float64 with the Hertz warm start (the default),
in float32, and from a uniform start ("cold").

Then the edge-loading convergence: a Hertz ellipse (A = 0.01, B = 0.1 /mm, W = 2000 N)
centred 0.6 a from x = 0 and cut by a face end at x = 1.125 a (the mask's edge) on grids
of 64 to 512 cells across: the pressure averaged over the 0.1 mm strip at the face end
(edge_pressure_MPa) converges, the raw peak of the edge cells grows like n^(1/2).

Prints the tables and writes benchmarks/pressure_peers.json. Peer code is only installed
and called, never copied into the project.

Setup (a separate venv, so that the project's .venv stays as it is; the peer's wheels
pull muGrid, NuMPI and SurfaceTopography; toothcontact's pressure solver needs only numpy
and scipy, so the script puts the repository's src/ on sys.path):

    python3.11 -m venv /tmp/bem-peers-venv
    /tmp/bem-peers-venv/bin/pip install ContactMechanics==1.8.3

Run (about 3 min on 2 cores, most of it the peer at 512²):

    /tmp/bem-peers-venv/bin/python benchmarks/pressure_peers.py
    /tmp/bem-peers-venv/bin/python benchmarks/pressure_peers.py --ratios 4 --grids 256

Without ContactMechanics (e.g. `.venv/bin/python benchmarks/pressure_peers.py`) only our
solver runs; the peer's fields are null and the table says the peer is missing.
"""

from __future__ import annotations

import argparse
import json
import math
import os
import platform
import sys
import warnings
from importlib import metadata
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
JSON_OUT = HERE / "pressure_peers.json"
try:
    import toothcontact  # noqa: F401
except ImportError:
    sys.path.insert(0, str(HERE.parent / "src"))

sys.path.insert(0, str(HERE))
sys.path.insert(0, str(HERE.parent / "tests"))
from test_pressure import E_STAR as TEST_E_STAR, TRUNCATED, truncated_gap  # noqa: E402 - the tests' problem
from timing import timed  # noqa: E402
from toothcontact.analytic import hertz  # noqa: E402
from toothcontact.contact import pressure as P  # noqa: E402

E_STAR = 1.0 / hertz.compliance(210000.0, 0.3, 210000.0, 0.3)
A_HERTZ, LOAD = 0.02, 2500.0
MARGIN = 1.4                       # grid half-extent over the Hertz semi-axis, per axis
TOL = 1e-8                         # our relative gap error; the peer's pentol = TOL·approach
STRIP = 0.1                        # mm, edge strip width


def versions() -> dict:
    out = {"python": platform.python_version(), "machine": platform.machine(),
           "cpus": os.cpu_count()}
    for dist in ("ContactMechanics", "muGrid", "NuMPI", "SurfaceTopography", "numpy",
                 "scipy"):
        try:
            out[dist] = metadata.version(dist)
        except metadata.PackageNotFoundError:
            out[dist] = None
    return out


def hertz_problem(ratio: float, n: int):
    exact = hertz.hertz_point(A_HERTZ, ratio * A_HERTZ, LOAD, 1.0 / E_STAR)
    lx, ly = 2 * MARGIN * exact.a, 2 * MARGIN * exact.b
    dx, dy = lx / n, ly / n
    x = (np.arange(n) - (n - 1) / 2) * dx
    y = (np.arange(n) - (n - 1) / 2) * dy
    X, Y = np.meshgrid(x, y, indexing="ij")
    return A_HERTZ * X**2 + ratio * A_HERTZ * Y**2, dx, dy, exact


def gap_error(h, p, dx, dy):
    """Our relative gap error of any pressure field (rms gap residual in contact, largest
    penetration outside, over the largest displacement), by our influence operator."""
    u = P.influence_operator(h.shape, dx, dy)(p) / E_STAR
    contact = p > 0
    g = h + u
    residual = g - g[contact].mean()
    pen = max(0.0, -float(residual[~contact].min(initial=0.0)))
    return max(math.sqrt(float(np.mean(residual[contact] ** 2))), pen) / float(u.max())


def run_ours(h, dx, dy, exact, repeat, **options):
    def cold():
        P.influence_operator.cache_clear()
        return P.solve_contact(h, dx, dy, LOAD, E_STAR, tol=TOL, **options)

    t_cold, sol = timed(cold, repeat)
    t_cached, _ = timed(lambda: P.solve_contact(h, dx, dy, LOAD, E_STAR, tol=TOL,
                                                  **options), repeat)
    return {
        "time_s": t_cold, "time_cached_operator_s": t_cached,
        "iterations": sol.iterations, "relative_gap_error": sol.relative_error,
        "peak_error_rel": sol.peak_pressure_MPa / exact.p0 - 1,
        "approach_error_rel": sol.approach_mm / exact.approach - 1,
    }, sol.pressure_MPa


def run_peer(h, dx, dy, exact, repeat, pentol):
    import ContactMechanics as CM
    from SurfaceTopography import Topography

    n0, n1 = h.shape
    sizes = (n0 * dx, n1 * dy)

    def solve():
        substrate = CM.FreeFFTElasticHalfSpace((n0, n1), E_STAR, sizes)
        # the peer presses a rigid surface of heights -h onto the substrate
        system = CM.make_system(Topography(-h, physical_sizes=sizes, periodic=False),
                                substrate=substrate)
        result = system.minimize_proxy(external_force=LOAD, pentol=pentol)
        if not result.success:
            raise RuntimeError(f"ContactMechanics: {result.message}")
        return result

    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        t, result = timed(solve, repeat)
    p = result.jac / (dx * dy)
    return {
        "time_s": t, "iterations": int(result.nit), "pentol_mm": pentol,
        "relative_gap_error": gap_error(h, p, dx, dy),
        "peak_error_rel": float(p.max()) / exact.p0 - 1,
        "approach_error_rel": float(result.offset) / exact.approach - 1,
    }, p


def hertz_rows(ratios, grids, repeat, peer_ok):
    rows = []
    for ratio in ratios:
        for n in grids:
            h, dx, dy, exact = hertz_problem(ratio, n)
            row = {"B_over_A": ratio, "grid": n, "dx_mm": dx, "dy_mm": dy,
                   "hertz": {"a_mm": exact.a, "b_mm": exact.b, "p0_MPa": exact.p0,
                             "approach_mm": exact.approach}}
            ours, p_ours = run_ours(h, dx, dy, exact, repeat)
            row["ours"] = ours
            row["ours_float32"], _ = run_ours(h, dx, dy, exact, repeat, dtype=np.float32)
            row["ours_cold_start"], _ = run_ours(h, dx, dy, exact, max(1, repeat - 1),
                                                 warm_start=False)
            for key, pentol in (("peer", TOL * exact.approach), ("peer_default_tol", None)):
                if not peer_ok:
                    row[key] = None
                    continue
                peer_repeat = 1 if n >= 512 else repeat
                peer, p_peer = run_peer(h, dx, dy, exact, peer_repeat, pentol)
                peer["max_abs_dp_over_p0"] = float(np.abs(p_peer - p_ours).max()) / exact.p0
                peer["speedup_vs_ours"] = peer["time_s"] / ours["time_s"]
                peer["speedup_vs_ours_float32"] = peer["time_s"] / row["ours_float32"]["time_s"]
                peer["speedup_vs_ours_cold_start"] = (peer["time_s"]
                                                      / row["ours_cold_start"]["time_s"])
                row[key] = peer
            rows.append(row)
            print(f"  B/A = {ratio:g}, {n}²: ours {ours['time_s']:.3f} s"
                  + (f", peer {row['peer']['time_s']:.2f} s" if row["peer"] else ""),
                  flush=True)
    return rows


def edge_rows(grids):
    """The truncated ellipse of the tests (tests/test_pressure.py) at each grid size."""
    A, B, load = TRUNCATED["A"], TRUNCATED["B"], TRUNCATED["load"]
    rows = []
    for n in grids:
        h, dx, dy, mask, exact = truncated_gap(n)
        P.influence_operator.cache_clear()
        t, sol = timed(lambda: P.solve_contact(h, dx, dy, load, TEST_E_STAR, mask=mask), 1)
        _, end = sol.edge_loads(axis=0, width_mm=STRIP)
        rows.append({"cells_across": n, "dx_mm": dx, "dy_mm": dy, "time_s": t,
                     "iterations": sol.iterations,
                     "edge_pressure_MPa": end.edge_pressure_MPa,
                     "raw_edge_peak_MPa": end.raw_peak_MPa,
                     "strip_load_fraction": end.load_fraction,
                     "peak_pressure_MPa": sol.peak_pressure_MPa})
    for coarse, fine in zip(rows, rows[1:]):
        fine["edge_pressure_change"] = fine["edge_pressure_MPa"] / coarse["edge_pressure_MPa"] - 1
        fine["raw_peak_ratio"] = fine["raw_edge_peak_MPa"] / coarse["raw_edge_peak_MPa"]
    return {"problem": {"A_per_mm": A, "B_per_mm": B, "load_N": load, "E_star_MPa": TEST_E_STAR,
                        "hertz_a_mm": exact.a, "hertz_b_mm": exact.b, "hertz_p0_MPa": exact.p0,
                        "centre_x_mm": 0.6 * exact.a, "face_end_x_mm": 1.125 * exact.a,
                        "grid_x_mm": [-1.5 * exact.a, 1.5 * exact.a],
                        "grid_y_mm": [-2 * exact.b, 2 * exact.b], "strip_mm": STRIP},
            "rows": rows}


def table(headers, rows):
    widths = [max(len(str(c)) for c in col) for col in zip(headers, *rows)]
    line = lambda cells: "  ".join(str(c).rjust(w) for c, w in zip(cells, widths))  # noqa: E731
    return "\n".join([line(headers), line(["-" * w for w in widths])] + [line(r) for r in rows])


def fmt(value, spec):
    return "n/a" if value is None else format(value, spec)


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--ratios", type=float, nargs="+", default=[1.0, 4.0, 40.0, 400.0])
    parser.add_argument("--grids", type=int, nargs="+", default=[256, 512])
    parser.add_argument("--edge-grids", type=int, nargs="+", default=[64, 128, 256, 512])
    parser.add_argument("--repeat", type=int, default=3, help="best of (peer: 1 at 512²)")
    parser.add_argument("--out", type=Path, default=JSON_OUT)
    args = parser.parse_args(argv)

    try:
        import ContactMechanics  # noqa: F401
        peer_ok, peer_note = True, None
    except ImportError as error:
        peer_ok, peer_note = False, f"ContactMechanics not importable: {error}"
        print(f"peer missing: {peer_note}; running our solver only")

    print("Hertz problems:")
    rows = hertz_rows(args.ratios, args.grids, args.repeat, peer_ok)
    print("Edge-loading convergence:")
    edges = edge_rows(args.edge_grids)

    out = {
        "versions": versions(),
        "peer_note": peer_note,
        "hertz_problem": {"A_per_mm": A_HERTZ, "load_N": LOAD, "E_star_MPa": E_STAR,
                          "grid_half_extent_over_semi_axis": MARGIN, "tol": TOL,
                          "timing": "best of --repeat wall times; time_s includes building "
                                    "the influence operator (ours) / the substrate (peer)"},
        "hertz": rows,
        "edge_convergence": edges,
    }
    tmp = args.out.with_suffix(".json.tmp")
    tmp.write_text(json.dumps(out, indent=2) + "\n")
    tmp.replace(args.out)

    headers = ["B/A", "grid", "ours s (it)", "f32 s", "cold s (it)", "peer s (it)",
               "peer/ours", "peer/f32", "peer/cold", "max|dp|/p0", "peer dflt s (it)",
               "dflt/ours", "max|dp|/p0 dflt", "ours p0 err", "peer p0 err"]
    body = []
    for r in rows:
        o, peer, dflt = r["ours"], r["peer"], r["peer_default_tol"]
        body.append([
            f"{r['B_over_A']:g}", f"{r['grid']}²",
            f"{o['time_s']:.3f} ({o['iterations']})",
            f"{r['ours_float32']['time_s']:.3f}",
            f"{r['ours_cold_start']['time_s']:.3f} ({r['ours_cold_start']['iterations']})",
            f"{peer['time_s']:.2f} ({peer['iterations']})" if peer else "missing",
            fmt(peer and peer["speedup_vs_ours"], ".1f"),
            fmt(peer and peer["speedup_vs_ours_float32"], ".1f"),
            fmt(peer and peer["speedup_vs_ours_cold_start"], ".1f"),
            fmt(peer and peer["max_abs_dp_over_p0"], ".1e"),
            f"{dflt['time_s']:.2f} ({dflt['iterations']})" if dflt else "missing",
            fmt(dflt and dflt["speedup_vs_ours"], ".1f"),
            fmt(dflt and dflt["max_abs_dp_over_p0"], ".1e"),
            f"{o['peak_error_rel']:+.1e}",
            fmt(peer and peer["peak_error_rel"], "+.1e"),
        ])
    print()
    print(f"Hertz, W = {LOAD:g} N, A = {A_HERTZ} /mm, E* = {E_STAR:.0f} MPa; ours at relative "
          f"gap error {TOL:g}, peer at pentol = {TOL:g}·approach and at its defaults (dflt)")
    print(table(headers, body))
    print()
    print(f"Truncated ellipse, edge pressure averaged over {STRIP} mm at the face end")
    print(table(["cells", "dx mm", "edge MPa", "change", "raw peak MPa", "x prev",
                 "strip load", "it", "s"],
                [[e["cells_across"], f"{e['dx_mm']:.4f}", f"{e['edge_pressure_MPa']:.1f}",
                  fmt(e.get("edge_pressure_change"), "+.2%"), f"{e['raw_edge_peak_MPa']:.0f}",
                  fmt(e.get("raw_peak_ratio"), ".3f"), f"{e['strip_load_fraction']:.2%}",
                  e["iterations"], f"{e['time_s']:.2f}"] for e in edges["rows"]]))
    print(f"\nwrote {args.out}")


if __name__ == "__main__":
    main()
