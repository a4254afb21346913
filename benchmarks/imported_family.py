"""The imported-mesh path on a family of pairs: other generators' STEP files and the tool's
own exports, uncrowned and crowned, aligned and under slope of either sign.

    PYTHONPATH=src .venv/bin/python benchmarks/imported_family.py [--positions 11]

Peer pairs: the STEP sectors in data/peers (py-gearworks, bd_warehouse, cq_gears;
provenance and measured flank deviations in its README), z = 20/60, m = 3 mm, 20 deg,
b = 30 mm. Own pairs: the same pair built by toothcontact.cad (three-tooth sectors, lead
crown R = 4000 mm on the pinion where crowned), written to STEP and read back. Every pair is
tessellated to 2 µm and analysed over one mesh cycle with `kind = "imported"`'s engine
(contact.imported.imported_cycle); the own pairs also on their exact flanks (`kind = "spur"`).

Columns: the transmission error's swing on the meshes and on the exact flanks (own pairs),
the bound the files allow (both bodies' chordal errors plus their flank deviations, as a turn
of the gear at its base radius: an aligned uncrowned pair's swing must stay within it, the
exact answer being flat), the highest peak pressure, the contact models, the edge the
pattern is cut by (if any), and the time of the cycle (tessellation and reading excluded).
Prints a table and writes benchmarks/imported_family.json.
"""

from __future__ import annotations

import argparse
import gzip
import json
import math
import platform
import sys
import tempfile
import time
from pathlib import Path

HERE = Path(__file__).resolve().parent
DATA = HERE.parent / "data" / "peers"
#: largest flank deviation (µm) of each peer file from the exact involute (DATA/README.md)
PEER_DEVIATION_UM = {"pgw_pinion_z20_sector3": 2.34, "pgw_gear_z60_sector3": 0.11,
                     "pgw_pinion_z20_crowned_sector3": 2.34, "bdw_pinion_z20_sector3": 1.89,
                     "bdw_gear_z60_sector3": 0.035, "cqg_pinion_z20_sector3": 4.80,
                     "cqg_gear_z60_sector3": 1.29}
#: peer pairs (label, pinion, gear): both files of a pair span the same z range
PEERS = [("py-gearworks uncrowned", "pgw_pinion_z20_sector3", "pgw_gear_z60_sector3"),
         ("py-gearworks crowned pinion", "pgw_pinion_z20_crowned_sector3", "pgw_gear_z60_sector3"),
         ("bd_warehouse uncrowned", "bdw_pinion_z20_sector3", "bdw_gear_z60_sector3"),
         ("cq_gears uncrowned", "cqg_pinion_z20_sector3", "cqg_gear_z60_sector3")]
SLOPE = 0.0008
TOLERANCE = 0.002


def step_file(name: str, folder: Path) -> Path:
    """A peer STEP of DATA, unpacked into `folder` where it is gzip'd."""
    plain = DATA / f"{name}.step"
    if plain.exists():
        return plain
    path = folder / f"{name}.step"
    path.write_bytes(gzip.decompress((DATA / f"{name}.step.gz").read_bytes()))
    return path


def own_pair(folder: Path, crowned: bool):
    """The tool's own pair as three-tooth STEP sectors in `folder`: (pinion, gear, flank
    deviations in µm, the spur case table)."""
    from toothcontact import cad, gearset
    from toothcontact.case import parse_case

    table = {"kind": "spur", "teeth": [20, 60], "module": "3 mm", "pressure_angle": "20 deg",
             "face_width": "30 mm", "load": {"tangential_load": "8000 N"}}
    if crowned:
        table["pinion"] = {"crown": {"radius": "4000 mm"}}
    pair = gearset.gear_pair(parse_case(table))
    paths, deviation = [], []
    for name, gear, mods in (("pinion", pair.pinion, pair.pinion_modifications),
                             ("gear", pair.gear, pair.gear_modifications)):
        body = cad.build_gear(gear, mods, teeth=3)
        paths.append(cad.write_step(body.solid, folder / f"own_{'crowned' if crowned else 'plain'}_{name}.step"))
        deviation.append(1e3 * cad.flank_deviation(body))
    return paths[0], paths[1], deviation, table


def run(pinion_path, gear_path, deviation_um, slope, positions, pinion_turn, gear_start):
    """One mesh cycle: its rows, cycle time and the files' bound (µrad)."""
    from toothcontact.analytic.hertz import compliance
    from toothcontact.surfaces.placement import Misalignment, ParallelMesh
    from toothcontact.contact.cycle import CycleSettings
    from toothcontact.contact.imported import chordal_error, imported_cycle
    from toothcontact.mesh import load_surface

    pinion, gear = load_surface(pinion_path, TOLERANCE), load_surface(gear_path, TOLERANCE)
    if pinion_turn:
        pinion = pinion.turned(pinion_turn)
    base_radius = 90.0 * math.cos(math.radians(20.0))
    bound = 1e6 * (chordal_error(pinion) + chordal_error(gear) + 1e-3 * sum(deviation_um)) / base_radius
    mesh = ParallelMesh(20, 60, 120.0, math.radians(20.0),
                                  Misalignment(slope=slope), gear_start=gear_start)
    start = time.perf_counter()
    rows = imported_cycle(mesh, pinion, gear, 8000.0 / math.cos(math.radians(20.0)),
                          compliance(206e3, 0.3, 206e3, 0.3), CycleSettings(positions=positions))
    return rows, time.perf_counter() - start, bound


def exact_swing(table: dict, slope: float, positions: int) -> float:
    from toothcontact.analyses import analyse
    from toothcontact.case import parse_case

    case = parse_case({**table, "misalignment": {"slope": str(slope)},
                       "analysis": {"positions": positions, "interference": False}})
    te = [r["transmission_error_urad"] for r in analyse(case).sections["positions"]]
    return max(te) - min(te)


def summary(label, slope, rows, seconds, bound, exact=None) -> dict:
    te = [r["transmission_error_urad"] for r in rows]
    cut = sorted({r["edge_contact_at"] for r in rows if r["edge_contact_at"]})
    return {"case": label, "slope": slope, "positions": len({r["roll_deg"] for r in rows}),
            "te_pp_urad": max(te) - min(te), "te_pp_exact_urad": exact, "bound_urad": bound,
            "max_p_MPa": max(r["p_max_MPa"] for r in rows),
            "models": sorted({r["contact_model"] for r in rows}), "edge_contact": cut,
            "max_contact_radius_mm": max(r["contact_radius_pinion_mm"] for r in rows),
            "seconds": seconds}


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--positions", type=int, default=11)
    args = parser.parse_args()
    records = []
    with tempfile.TemporaryDirectory() as tmp:
        folder = Path(tmp)
        for label, pin, gear in PEERS:
            deviation = [PEER_DEVIATION_UM[pin], PEER_DEVIATION_UM[gear]]
            for slope in (0.0, SLOPE, -SLOPE):
                rows, seconds, bound = run(step_file(pin, folder), step_file(gear, folder),
                                           deviation, slope, args.positions, 0.0, math.pi)
                records.append(summary(label, slope, rows, seconds, bound))
                print(records[-1], flush=True)
        for crowned in (False, True):
            pin, gear, deviation, table = own_pair(folder, crowned)
            for slope in (0.0, SLOPE, -SLOPE):
                # the sectors' tooth 0 sits on +x: teeth -1, 0, 1 meet after these turns
                rows, seconds, bound = run(pin, gear, deviation, slope, args.positions,
                                           -math.radians(18.0), math.radians(174.0))
                records.append(summary(f"toothcontact {'crowned' if crowned else 'uncrowned'}",
                                       slope, rows, seconds, bound,
                                       exact_swing(table, slope, args.positions)))
                print(records[-1], flush=True)
    head = (f"{'case':30s} {'slope':>8s} {'pos':>4s} {'TE p-p':>8s} {'exact':>7s} {'bound':>7s} "
            f"{'max p':>7s} {'model':12s} {'edge contact':24s} {'time':>6s}")
    print(head)
    for r in records:
        exact = "" if r["te_pp_exact_urad"] is None else f"{r['te_pp_exact_urad']:.2f}"
        print(f"{r['case']:30s} {r['slope']:8.4f} {r['positions']:4d} {r['te_pp_urad']:8.2f} "
              f"{exact:>7s} {r['bound_urad']:7.2f} {r['max_p_MPa']:7.0f} "
              f"{'/'.join(r['models']):12s} {','.join(r['edge_contact']) or '-':24s} "
              f"{r['seconds']:5.1f}s")
    print("TE in µrad of the gear; bound: chordal errors + flank deviations at the gear's base "
          "radius; time: the mesh cycle alone")
    (HERE / "imported_family.json").write_text(json.dumps(
        {"python": platform.python_version(), "machine": platform.machine(),
         "tolerance_mm": TOLERANCE, "rows": records}, indent=2) + "\n")


if __name__ == "__main__":
    sys.exit(main())
