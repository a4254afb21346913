"""The mesh stiffness and single-pair stiffness of a 20° helical pair: an independent 3D
finite-element reference (issue 50, item 6, last part) for the model's helical mesh
stiffness, which reads +21 % above ISO 6336-1's c_γα
(tests/test_loaded_teeth.py::test_the_mesh_stiffness_of_standard_pairs_is_isos).

Pair: that test's helical pair, so that the reference checks the figure in question:
z = 25/75, m_n = 3 mm, α_n = 20°, β = 15°, b = 20 mm (both members, flush ends), ISO 53
profile A, no profile shift, uncrowned and unmodified, steel (206000 MPa, 0.3), 6000 N
tangential (300 N/mm, F_n = 6611 N), aligned. ε_α = 1.63, ε_β = 0.55: two or three
contact lines carry at every position (no single-pair position: the model reports no c'
for it). The 20 mm face also keeps the FE small: a helical tooth has no mid-face symmetry,
so the whole face is one factorisation, here as long as the spur reference's half face.

FE (tests/fe_pair_helical.py on tests/fe_tooth.py; its docstring has the method): each
member's whole gear (every tooth; the bore at half the root radius held; free end faces),
the exact transverse section screwed along the face, P2 tetrahedra, fine along the whole
active flank of the loaded tooth; unit forces on every contact line's segments (the face's
2 mm strips clipped to the zone of action) along the flank's 3D normal, read at the teeth's
centre lines (on the neighbouring teeth too, by the gears' symmetry: the load one tooth
puts through the body onto the others is in), plus Weber's flattening from the flanks to
the centre lines; each of POSITIONS mesh positions over a base pitch solved for the line
loads and the normal approach under F_n. Mesh stiffness: F_n·cos²β_b/(b·δ) (N/(mm·µm), ISO's
transverse force over transverse deflection per mm of face, as analyses.spur defines
mesh_stiffness_N_per_mm_um), its mean over the positions the c_γα counterpart; c' the
largest single-pair stiffness of one line wholly in the zone carrying F_n alone. Beside
it, "uncoupled": the same with the compliance between different pairs' lines dropped (each
pair's teeth deflect alone, as the model's do), which isolates what the bodies' coupling
of the teeth does.

Variants "light_transverse" and "medium_transverse": the same sections with the load's
axial part dropped (fe_pair_helical.member_compliance, axial=False), what the model's
transverse slices see: with the uncoupled variant they isolate the two load paths the model
lacks (tests/test_helical_stiffness_fe.py; 3 minutes here on 2 cores).

Levels (LEVELS: the section's sizes at the flank / over the loaded tooth / far, their
growth per mm, as fe_face_load's; z-layers; strips): light and light_fine_layers (the
layers halved: the z-convergence), coarse and medium (the section refined: the reference,
medium). Plane strain of the same sections (2D, whole gear, the centre-line compliance at
the mid-zone radius against a converged section) states the section's own convergence.

Sizes (dofs pinion, gear; factor Tflop; peak memory GB per member process, measured on 2
busy cores here, the medium gear's extrapolated): light 58k, 89k (0.11, 0.15; 1.4, 1.7),
light_fine_layers 113k, 175k (0.36, 0.51; 2.6, 3.7), coarse 139k, 217k (1.04, 1.28; 4.2,
5.6), medium 183k, 268k (1.89, about 2.0; 6.4, about 7.5): all eight member processes at
once hold about 35 GB. On one thread here (the two cores 2-5 times oversubscribed by
other work): the coarse pinion 103 s, the light_fine_layers gear 85 s (its factor 42 s:
27 s BLAS, 10 s assembling the fronts); the coarse gear 235 s and the medium pinion 351 s
before the factor's speed-up, at a load of 8-10; from the work and nonzeros, about 160 s
for the medium pinion and 190 s for the medium gear at the lighter load, half of it BLAS.

Run: each member of a level is one process, `--jobs` at a time, sharing `--threads` BLAS
threads by their work (a member keeps one thread if a team is no faster: Factor's
calibration); a member's compliance is kept in --cache. The reference, on a 16-core,
128 GB machine (about 4 minutes expected, 8 at worst; --deadline stops what is left and
keeps the levels done):

    python3 benchmarks/fe_helical_stiffness.py --levels light light_fine_layers coarse \
        medium --threads 16 --jobs 8 --deadline 480 --plane-strain --json OUT.json \
        [--npz OUT.npz]

then here `--levels --model` adds the model's figures to benchmarks/fe_helical_stiffness.json
(about 10 s) and prints the table. Smoke (here, 2 cores, about 5 minutes, 4 GB):
--levels light light_fine_layers --threads 1 --jobs 1. The JSON is written after each
level, so a run stopped early keeps what it finished.
"""

from __future__ import annotations

import argparse
import json
import math
import os
import platform
import subprocess
import sys
import time
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
ROOT = HERE.parent
JSON_OUT = HERE / "fe_helical_stiffness.json"
sys.path.insert(0, str(ROOT / "tests"))
sys.path.insert(0, str(ROOT / "src"))
import fe_pair_helical as fh  # noqa: E402

#: the pair (tests/test_loaded_teeth.py's helical one), its load and the mesh positions
CASE = {"kind": "spur", "title": "helical stiffness reference", "teeth": [25, 75],
        "module": "3 mm", "pressure_angle": "20 deg", "helix_angle": "15 deg",
        "face_width": "20 mm", "misalignment": {"slope": "0.0"},
        "load": {"tangential_load": "6000 N"},
        "analysis": {"positions": 9, "interference": False, "positions_check": False}}
TANGENTIAL_N = 6000.0
POSITIONS = 9
#: section sizes (mm: h_patch along the active flank, h_tooth, h_far; growth per mm),
#: z-layers (mm) and strips (mm)
LEVELS = {
    "tiny": dict(h_patch=0.4, h_tooth=1.5, h_far=30.0, growth=0.8, layer=4.0, strip=4.0),
    "light": dict(h_patch=0.3, h_tooth=1.2, h_far=30.0, growth=0.8, layer=2.0, strip=2.0),
    "light_fine_layers": dict(h_patch=0.3, h_tooth=1.2, h_far=30.0, growth=0.8, layer=1.0,
                              strip=2.0),
    "coarse": dict(h_patch=0.3, h_tooth=0.9, h_far=15.0, growth=0.5, layer=2.0, strip=2.0),
    "medium": dict(h_patch=0.15, h_tooth=0.6, h_far=15.0, growth=0.5, layer=2.0, strip=2.0),
}
#: the same sections with the load's axial part dropped (fe_pair_helical.member_compliance,
#: axial=False): what the model's transverse slices see, which isolates the axial load path
LEVELS.update({f"{level}_transverse": dict(LEVELS[level], axial=False)
               for level in ("light", "medium")})
#: each member's factor work (Tflop: measured for light, light_fine_layers, coarse and the
#: medium pinion, the medium gear's extrapolated): the jobs' order and their BLAS threads
WORK = {("pinion", "tiny"): 0.025, ("gear", "tiny"): 0.033,
        ("pinion", "light"): 0.11, ("gear", "light"): 0.15,
        ("pinion", "light_fine_layers"): 0.36, ("gear", "light_fine_layers"): 0.51,
        ("pinion", "coarse"): 1.04, ("gear", "coarse"): 1.28,
        ("pinion", "medium"): 1.89, ("gear", "medium"): 2.0}
WORK.update({(name, f"{level}_transverse"): WORK[(name, level)]
             for name in ("pinion", "gear") for level in ("light", "medium")})
REFERENCE = "medium"
SMOKE = "light"
MEMBERS = ("pinion", "gear")


def the_pair():
    from toothcontact.case import parse_case
    from toothcontact.gearset import gear_pair

    return gear_pair(parse_case(CASE))


def normal_load(pair) -> float:
    """F_n (N): the tangential force at the pitch circle along the normal."""
    return TANGENTIAL_N / (math.cos(pair.working_pressure_angle)
                           * math.cos(pair.pinion.base_helix_angle))


def geometry(pair, level: str) -> fh.HelicalPairGeometry:
    return fh.pair_geometry(pair, POSITIONS, LEVELS[level]["strip"])


def member_path(cache: Path, name: str, level: str) -> Path:
    return cache / f"{name}_{level}.npz"


def compute_member(pair, name: str, level: str, threads: int, cache: Path) -> None:
    """One member's compliance at one level, into the cache."""
    spec = dict(LEVELS[level])
    spec.pop("strip")
    geo = geometry(pair, level)
    print(f"{name}, {level} ({threads} threads):", flush=True)
    m = fh.member_compliance(geo, name, threads=threads,
                             log=lambda s: print(s, flush=True), **spec)
    try:
        import resource
        m.mesh["max_rss_GB"] = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1e6
    except ImportError:
        pass
    cache.mkdir(parents=True, exist_ok=True)
    tmp = member_path(cache, name, level).with_suffix(".tmp.npz")
    np.savez(tmp, matrix=m.matrix, depth=m.depth, roll=m.roll, surface=m.surface,
             mesh=json.dumps(m.mesh, default=float))
    tmp.replace(member_path(cache, name, level))


def load_member(cache: Path, name: str, level: str) -> fh.MemberHelical:
    d = np.load(member_path(cache, name, level))
    return fh.MemberHelical(d["matrix"], d["depth"], d["roll"], json.loads(str(d["mesh"])),
                            d["surface"])


def level_results(pair, level: str, members: dict) -> dict:
    """The pair's FE results at one level, coupled and uncoupled."""
    geo = geometry(pair, level)
    load = normal_load(pair)
    out = {}
    for variant, coupled in (("coupled", True), ("uncoupled", False)):
        r = fh.HelicalPair(geo, members["pinion"], members["gear"], coupled=coupled).stiffness(load)
        out[variant] = r
    out["mesh"] = {name: m.mesh for name, m in members.items()}
    # Maxwell-Betti: the work-conjugate compliance is symmetric; the centre-line one nearly
    out["asymmetry"] = {name: float(np.abs(m.matrix - m.matrix.T).max() / np.abs(m.matrix).max())
                        for name, m in members.items()}
    return out


def plane_strain_convergence(pair, levels) -> dict:
    """The section's own convergence: plane strain of each level's section (whole gear, the
    bore held), the centre-line compliance (mm²/N) at the zone's middle roll, against a
    converged section (0.03 mm at the flank, 0.15 over the tooth)."""
    import fe_tooth as ft

    geo = geometry(pair, SMOKE)
    out = {}
    for name in MEMBERS:
        flank, rolls, zone = geo.member(name)
        rho = 0.5 * (zone[0] + zone[1])
        radius = math.hypot(flank.base, rho)
        specs = {level: LEVELS[level] for level in levels}
        specs["converged"] = dict(h_patch=0.03, h_tooth=0.15, h_far=15.0, growth=0.3)
        values = {}
        for level, spec in specs.items():
            S = fh.member_section(flank, zone, spec["h_patch"], spec["h_tooth"],
                                  spec["h_far"], spec["growth"], site=radius)
            ps = ft.plane_strain(S)
            values[level] = dict(centre=ps["centre"][0], dofs=ps["dofs"])
        ref = values["converged"]["centre"]
        for level in values:
            values[level]["stiffer_than_converged"] = 1.0 - values[level]["centre"] / ref
        out[name] = dict(radius=radius, levels=values)
    return out


def model_results() -> dict:
    """The model's figures for the pair (toothcontact.analyses.analyse of CASE)."""
    from toothcontact.analyses import analyse
    from toothcontact.case import parse_case

    result = analyse(parse_case(CASE))
    s = result.sections["summary"]
    section = result.sections["load_distribution"]
    return dict(mesh_stiffness=s["mesh_stiffness_N_per_mm_um"],
                single_stiffness=s["single_stiffness_N_per_mm_um"],
                iso_mesh_stiffness=s["iso_mesh_stiffness_N_per_mm_um"],
                iso_single_stiffness=s["iso_single_stiffness_N_per_mm_um"],
                roll_deg=section["roll_deg"], stiffness=section["mesh_stiffness_N_per_mm_um"])


def body_coupling_check(pair, level: str, members: dict) -> dict:
    """The gear bodies' coupling of different teeth, FE against the model's
    (analytic.gear_body.chord_green, as contact.compliance.PairCompliance.body_coupling
    applies it): per member and tooth offset, the mean compliance (µm/kN) between two
    lines on different teeth (the mean normal displacement over one line under a unit
    load spread evenly over the other, both clipped to the zone), the FE's and the
    model's at the lines' mean rolls; and the pair's mesh stiffness with the FE's own
    compliance of each line but the model's between lines (smeared evenly along the
    face, as the model's is), beside the FE's coupled and uncoupled ones."""
    from toothcontact.analytic.gear_body import chord_green
    from toothcontact.contact.compliance import ToothCompliance

    geo = geometry(pair, level)
    width = np.array([s.width for s in geo.segments])
    out: dict = {"offsets": {}}
    swapped = {}
    for name, gear in (("pinion", pair.pinion), ("gear", pair.gear)):
        teeth = ToothCompliance(gear, 206000.0, 0.3)
        m = members[name]
        A = m.matrix.copy()
        share = math.cos(gear.base_helix_angle) ** 2 / geo.face
        pairs = [(I, J, offset) for I, J, offset in line_pairs(geo, name) if offset]
        for I, J, offset in pairs:
            roll_i = float(width[I] @ m.roll[I] / width[I].sum())
            roll_j = float(width[J] @ m.roll[J] / width[J].sum())
            place = int(teeth.roll_sense * np.sign(roll_j - roll_i)) * offset
            g_i, g_j = (teeth.root_loads([math.hypot(gear.base_radius, r)])[0]
                        for r in (roll_i, roll_j))
            A[np.ix_(I, J)] = float(g_i @ chord_green(
                teeth.bore_radius, teeth.root_radius, teeth.root_half_angle, gear.teeth,
                -place, teeth.E, teeth.nu) @ g_j) * share
        fe, model = offset_means(geo, name, m.matrix), offset_means(geo, name, A)
        count = {str(k): sum(o == k for _, _, o in pairs) for k in {o for _, _, o in pairs}}
        out["offsets"][name] = {k: dict(fe_um_per_kN=fe[k], model_um_per_kN=model[k],
                                        line_pairs=count[k]) for k in sorted(count)}
        swapped[name] = fh.MemberHelical(A, m.depth, m.roll, m.mesh, m.surface)
    load = normal_load(pair)
    out["fe_coupled"] = fh.HelicalPair(geo, members["pinion"], members["gear"]).stiffness(
        load)["mesh_stiffness"]
    out["fe_uncoupled"] = fh.HelicalPair(geo, members["pinion"], members["gear"],
                                         coupled=False).stiffness(load)["mesh_stiffness"]
    out["fe_own_lines_model_between"] = fh.HelicalPair(
        geo, swapped["pinion"], swapped["gear"]).stiffness(load)["mesh_stiffness"]
    return out


def model_flexure(pair, level: str) -> dict:
    """The model's out-of-plane compliance between the FE's segments (mm/N, along the
    flank's 3D normal), per member: the body's flexure (ToothCompliance.flexure_loads and
    analytic.gear_body.flexure_green as contact.compliance.PairCompliance.body_coupling
    applies them) and, between segments on one tooth, the tooth's wall under the load's
    axial part (ToothCompliance.wall, as contact.structure.MemberLoading applies it):
    "full" with the load's axial part, "transverse" with it dropped and the read along the
    normal's transverse part (the FE's axial=False counterpart). Each segment at its
    middle (its roll is linear along the face); a segment on a neighbouring tooth turned
    by the FE's own tooth_of."""
    from toothcontact.analytic.gear_body import flexure_green
    from toothcontact.contact.compliance import ToothCompliance

    geo = geometry(pair, level)
    segments = geo.segments
    line = np.array([s.line for s in segments])
    z = np.array([0.5 * (s.z0 + s.z1) for s in segments])
    out = {}
    for name, gear in (("pinion", pair.pinion), ("gear", pair.gear)):
        teeth = ToothCompliance(gear, 206000.0, 0.3)
        flank, rolls, _ = geo.member(name)
        rho = np.array([float(rolls(s.line, zi)) for s, zi in zip(segments, z)])
        points, _, n3, _, _ = flank.at(rho)
        tangential = (points[:, 0] * n3[:, 1] - points[:, 1] * n3[:, 0]) / np.hypot(*points.T)
        mirror = -1.0 if np.median(tangential) > 0.0 else 1.0   # as PairCompliance._root_loads
        radius = np.hypot(flank.base, rho)
        nodes = teeth.flexure_nodes
        parts = teeth.flexure_loads(radius, z, n3[:, 2]).reshape(len(z), len(nodes), -1)
        # per node the loads on (w, ψ_r, ψ_θ): the transverse part's moments, the axial part's
        transverse = np.concatenate([np.zeros(parts.shape[:2] + (1,)), parts[..., :2]], axis=-1)
        loads = {"full": (transverse + parts[..., 2:]).reshape(len(z), -1),
                 "transverse": transverse.reshape(len(z), -1)}
        plate = (teeth.bore_radius, teeth.root_radius, teeth.root_half_angle, gear.teeth,
                 gear.face_width)
        offsets = {}
        for r in range(len(segments)):
            for j in range(len(segments)):
                if (line[r] - line[j]) % geo.positions == 0:
                    offsets[r, j] = flank.tooth_of(float(rolls(line[r], 0.0)
                                                         - rolls(line[j], 0.0)))
        # the flexure between every node of tooth m and every node of tooth 0
        size = 3 * len(nodes)
        greens = {m: flexure_green(*plate, mirror * (m * flank.pitch + flank.twist
                                                     * (nodes[:, None] - nodes[None, :])),
                                   206000.0, 0.3).transpose(0, 2, 1, 3).reshape(size, size)
                  for m in set(offsets.values())}
        # the wall's: each segment's axial part spread to its nodes
        wall = teeth.wall
        nodes_w, weights_w = wall.spread(teeth.wall_heights(radius), z)
        spread = np.zeros((len(z), len(wall.matrix)))
        np.add.at(spread, (np.arange(len(z))[:, None], nodes_w), weights_w * n3[:, 2:3])
        own = spread @ wall.matrix @ spread.T
        matrices = {k: np.zeros((len(segments), len(segments))) for k in loads}
        for (r, j), m in offsets.items():
            for k, L in loads.items():
                matrices[k][r, j] = L[r] @ greens[m] @ L[j]
            if m == 0:
                matrices["full"][r, j] += own[r, j]
        out[name] = matrices
    return out


def line_pairs(geo, name: str):
    """The pairs of contact lines that carry load together (the same position), as the
    segments of each (I, J: index arrays) and how many pitches apart their teeth are on
    member `name` (0: a line with itself)."""
    flank, rolls, _ = geo.member(name)
    line = np.array([s.line for s in geo.segments])
    for i in sorted(set(line)):
        for j in sorted(set(line)):
            if (i - j) % geo.positions == 0:
                yield (np.flatnonzero(line == i), np.flatnonzero(line == j),
                       abs(flank.tooth_of(float(rolls(j, 0.0) - rolls(i, 0.0)))))


def offset_means(geo, name: str, A: np.ndarray) -> dict:
    """The mean compliance (µm/kN) between two lines on teeth `offset` pitches apart (the
    mean normal displacement over one line under a unit load spread evenly over the other,
    both clipped to the zone), over the line pairs of each offset (0: a line on itself)."""
    width = np.array([s.width for s in geo.segments])
    by: dict = {}
    for I, J, offset in line_pairs(geo, name):
        by.setdefault(offset, []).append(
            float(width[I] @ A[np.ix_(I, J)] @ width[J]) / (width[I].sum() * width[J].sum()))
    return {str(k): 1e6 * float(np.mean(v)) for k, v in sorted(by.items())}


def flexure_check(pair, level: str, full: dict, transverse: dict) -> dict:
    """The load's axial path, FE against the model's: per member and tooth offset, what the
    load's axial part adds to the compliance between lines (the FE's `level` less its
    `level`_transverse; the model's body flexure with and without it, model_flexure), and
    the pair's mesh stiffness with the FE's transverse compliances plus the model's axial
    increment, beside the FE's with and without the axial part."""
    geo = geometry(pair, level)
    model = model_flexure(pair, level)
    out: dict = {"offsets": {}}
    swapped = {}
    for name in MEMBERS:
        fe = offset_means(geo, name, full[name].matrix - transverse[name].matrix)
        ours = offset_means(geo, name, model[name]["full"] - model[name]["transverse"])
        out["offsets"][name] = {k: dict(fe_um_per_kN=fe[k], model_um_per_kN=ours[k])
                                for k in fe}
        t = transverse[name]
        swapped[name] = fh.MemberHelical(
            t.matrix + model[name]["full"] - model[name]["transverse"], t.depth, t.roll,
            t.mesh, t.surface)
    load = normal_load(pair)
    stiffness = lambda p, g: fh.HelicalPair(geo, p, g).stiffness(load)["mesh_stiffness"]  # noqa: E731
    out["fe_full"] = stiffness(full["pinion"], full["gear"])
    out["fe_transverse"] = stiffness(transverse["pinion"], transverse["gear"])
    out["fe_transverse_model_axial"] = stiffness(swapped["pinion"], swapped["gear"])
    return out


def thread_shares(jobs: list[tuple[str, str]], threads: int) -> dict:
    """BLAS threads per job: one each, the rest of `threads` in proportion to the jobs'
    factor work (WORK)."""
    total = sum(WORK[job] for job in jobs)
    spare = max(threads - len(jobs), 0)
    return {job: 1 + int(round(spare * WORK[job] / total)) for job in jobs}


def run_jobs(levels, threads: int, jobs: int, cache: Path, deadline: float | None,
             on_level, t0: float, meanwhile=None) -> list[str]:
    """Each member of each level missing from the cache in its own process, `jobs` at a
    time, the biggest first; meanwhile() once they are started; on_level(level) when both
    members of a level are in. Returns the levels left unfinished at the deadline."""
    todo = [(name, level) for level in levels for name in MEMBERS
            if not member_path(cache, name, level).exists()]
    shares = thread_shares(todo, threads) if todo else {}
    todo.sort(key=lambda job: -WORK[job])
    running: dict = {}
    done_levels = set()

    def check_levels():
        for level in levels:
            if level not in done_levels and all(member_path(cache, n, level).exists()
                                                for n in MEMBERS):
                done_levels.add(level)
                on_level(level)

    check_levels()
    while todo or running or meanwhile:
        while todo and len(running) < jobs:
            name, level = todo.pop(0)
            cmd = [sys.executable, str(Path(__file__).resolve()), "--member", name,
                   "--level", level, "--threads", str(shares[(name, level)]),
                   "--cache", str(cache)]
            running[(name, level)] = subprocess.Popen(cmd)
        if meanwhile:
            meanwhile()
            meanwhile = None
        time.sleep(1.0)
        for job, proc in list(running.items()):
            if proc.poll() is not None:
                del running[job]
                if proc.returncode:
                    print(f"{job} failed: {proc.returncode}", flush=True)
        check_levels()
        if deadline is not None and time.perf_counter() - t0 > deadline:
            for job, proc in running.items():
                print(f"deadline: stopping {job}", flush=True)
                proc.kill()
            break
    return [level for level in levels if level not in done_levels]


def table(out: dict) -> None:
    model = out.get("model")
    print(f"\nF_n = {out['normal_load_N']:.0f} N, b = {out['face_mm']:g} mm, {POSITIONS} "
          "positions over a base pitch. Mesh stiffness (N/(mm·µm)) at each position, "
          "its mean (c_γα) and c' (one line wholly in the zone, alone).")
    print(f"{'':27} {'c_γα':>6} {'c_prime':>7}  per position" + " " * 40 + "dofs (pinion, gear)")
    for level, r in out["fe"].items():
        for variant in ("coupled", "uncoupled"):
            v = r[variant]
            mesh = r["mesh"]
            print(f"FE {level:17} {variant[:5]:5} {v['mesh_stiffness']:6.2f} "
                  f"{v['single_stiffness'] or float('nan'):7.2f}  "
                  + " ".join(f"{p['stiffness']:5.2f}" for p in v["positions"])
                  + (f"  {mesh['pinion']['dofs']}, {mesh['gear']['dofs']}"
                     if variant == "coupled" else ""))
    if model:
        print(f"{'model':27} {model['mesh_stiffness']:6.2f} "
              f"{model['single_stiffness'] or float('nan'):7.2f}  "
              + " ".join(f"{v:5.2f}" for v in model["stiffness"] if v is not None))
        print(f"{'ISO 6336-1 (Method B)':27} {model['iso_mesh_stiffness']:6.2f} "
              f"{model['iso_single_stiffness']:7.2f}")
    for level, check in out.get("flexure", {}).items():
        print(f"the load's axial path ({level}): mesh stiffness FE {check['fe_full']:.2f}, "
              f"FE transverse {check['fe_transverse']:.2f}, FE transverse + the model's "
              f"axial increment {check['fe_transverse_model_axial']:.2f}; per tooth offset, "
              "µm/kN (FE, model): " + "; ".join(
                  f"{name} " + ", ".join(f"{k}: {v['fe_um_per_kN']:.3f} {v['model_um_per_kN']:.3f}"
                                         for k, v in offsets.items())
                  for name, offsets in check["offsets"].items()))
    ps = out.get("plane_strain")
    if ps:
        for name, v in ps.items():
            print(f"plane strain, {name} at r = {v['radius']:.2f} mm, stiffer than converged: "
                  + ", ".join(f"{lv} {x['stiffer_than_converged']:+.2%}"
                              for lv, x in v["levels"].items() if lv != "converged"))


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--levels", nargs="*", default=[SMOKE], choices=list(LEVELS),
                    help="the FE levels to compute (none: only --model/--plane-strain "
                         "added to the JSON's levels)")
    ap.add_argument("--threads", type=int, default=os.cpu_count() or 1)
    ap.add_argument("--jobs", type=int, default=2)
    ap.add_argument("--cache", type=Path, default=Path("/tmp/fe_helical"))
    ap.add_argument("--json", type=Path, default=JSON_OUT)
    ap.add_argument("--npz", type=Path, help="also the members' compliances (npz)")
    ap.add_argument("--deadline", type=float, help="seconds: stop the jobs left after it")
    ap.add_argument("--model", action="store_true", help="the model's figures too")
    ap.add_argument("--body-coupling", nargs="*", default=[], choices=list(LEVELS),
                    help="the bodies' coupling of different teeth, FE against the model's, "
                         "on these levels' cached members (body_coupling_check)")
    ap.add_argument("--flexure", nargs="*", default=[], choices=list(LEVELS),
                    help="the load's axial path, FE against the model's body flexure, on "
                         "these levels' cached members and their _transverse variants "
                         "(flexure_check)")
    ap.add_argument("--plane-strain", action="store_true",
                    help="the sections' plane-strain convergence too")
    ap.add_argument("--member", choices=MEMBERS, help=argparse.SUPPRESS)
    ap.add_argument("--level", choices=list(LEVELS), help=argparse.SUPPRESS)
    args = ap.parse_args()
    t0 = time.perf_counter()
    pair = the_pair()
    if args.member:
        compute_member(pair, args.member, args.level, args.threads, args.cache)
        return
    geo = geometry(pair, SMOKE)
    p, g = pair.pinion, pair.gear
    out = dict(benchmark="fe_helical_stiffness", issue="50 item 6", case=CASE,
               machine=dict(platform=platform.platform(), python=platform.python_version(),
                            cpus=os.cpu_count(), threads=args.threads, jobs=args.jobs),
               E=206000.0, nu=0.3, normal_load_N=normal_load(pair), face_mm=geo.face,
               base_helix_deg=math.degrees(p.base_helix_angle),
               transverse_contact_ratio=(geo.zone[1] - geo.zone[0]) / geo.pinion.base_pitch,
               overlap_ratio=geo.face * geo.tan_base_helix / geo.pinion.base_pitch,
               zone_roll_mm=list(geo.zone), base_pitch_mm=geo.pinion.base_pitch,
               positions=POSITIONS, levels={k: LEVELS[k] for k in args.levels},
               reference=REFERENCE, smoke=SMOKE, fe={}, unfinished=[])
    if args.json.exists():                 # levels computed before stay unless redone
        old = json.loads(args.json.read_text())
        out["fe"] = {k: v for k, v in old.get("fe", {}).items() if k not in args.levels}
        out["levels"] = {**{k: LEVELS.get(k, v) for k, v in old.get("levels", {}).items()},
                         **out["levels"]}
        kept = ("model", "plane_strain", "body_coupling", "body_coupling_note", "flexure",
                "transverse_levels_machine")
        for key in kept + ("machine", "seconds") if not args.levels else kept:
            if key in old:
                out[key] = old[key]
        if not args.levels:
            out["unfinished"] = old.get("unfinished", [])

    def write():
        if args.levels or "seconds" not in out:
            out["seconds"] = time.perf_counter() - t0
        out["status"] = (
            f"reference level {REFERENCE!r} in" if REFERENCE in out["fe"] else
            f"SMOKE ONLY, not a reference: levels {sorted(out['fe'])} (the smoke level "
            f"{SMOKE!r} and its check); the reference level {REFERENCE!r} comes from the "
            "16-core run (the module's docstring)")
        args.json.parent.mkdir(parents=True, exist_ok=True)
        args.json.write_text(json.dumps(out, indent=1, default=float))

    def on_level(level):
        members = {name: load_member(args.cache, name, level) for name in MEMBERS}
        out["fe"][level] = level_results(pair, level, members)
        r = out["fe"][level]
        print(f"{level}: c_γα {r['coupled']['mesh_stiffness']:.3f} "
              f"(uncoupled {r['uncoupled']['mesh_stiffness']:.3f}), c' "
              f"{r['coupled']['single_stiffness']:.3f} N/(mm·µm); "
              f"{time.perf_counter() - t0:.0f} s", flush=True)
        write()

    def plane_strain():
        print("plane strain of the sections ...", flush=True)
        out["plane_strain"] = plane_strain_convergence(
            pair, [lv for lv in ("light", "coarse", "medium") if lv in out["levels"]])

    if args.levels:
        unfinished = run_jobs(args.levels, args.threads, args.jobs, args.cache, args.deadline,
                              on_level, t0, plane_strain if args.plane_strain else None)
        out["unfinished"] = unfinished
    elif args.plane_strain:
        plane_strain()
    if args.model:
        out["model"] = model_results()
    for level in args.body_coupling:
        members = {name: load_member(args.cache, name, level) for name in MEMBERS}
        out.setdefault("body_coupling", {})[level] = body_coupling_check(pair, level, members)
    for level in args.flexure:
        full, transverse = ({name: load_member(args.cache, name, lv) for name in MEMBERS}
                            for lv in (level, f"{level}_transverse"))
        out.setdefault("flexure", {})[level] = flexure_check(pair, level, full, transverse)
    write()
    if args.npz:
        arrays = {}
        for level in out["fe"]:
            for name in MEMBERS:
                if member_path(args.cache, name, level).exists():
                    d = np.load(member_path(args.cache, name, level))
                    for key in ("matrix", "depth", "roll", "surface"):
                        arrays[f"{level}/{name}/{key}"] = d[key]
        np.savez_compressed(args.npz, **arrays)
    table(out)
    print(f"\n{time.perf_counter() - t0:.0f} s; wrote {args.json}"
          + (f"; unfinished: {out['unfinished']}" if out["unfinished"] else ""))


if __name__ == "__main__":
    main()
