"""Imported bodies: signed distances on triangulations, and the mesh path's contact against
the exact analysis of the same pair."""


import gzip
import math
from pathlib import Path

import numpy as np
import pytest
import trimesh

from toothcontact import cad, gearset
from toothcontact.analyses import analyse
from toothcontact.analytic.hertz import compliance, hertz_line
from toothcontact.surfaces.placement import Misalignment, ParallelMesh
from toothcontact.case import CaseError, load_case, parse_case
from toothcontact.contact.cycle import CycleSettings
from toothcontact.contact.imported import chordal_error, imported_cycle
from toothcontact.mesh import load_surface
from toothcontact.surfaces.triangles import TriangleSurface

# unthinned teeth (no backlash): the files' teeth stand where the exact analysis puts them
# (a thinned pinion is turned forward by its thinning there, not in the files)
SPUR = {"kind": "spur", "teeth": [20, 60], "module": "3 mm", "pressure_angle": "20 deg",
        "face_width": "30 mm", "backlash": "0 mm",
        # sharp tips: the facets' path reads a rounding as flank up to the tip circle
        "pinion": {"crown": {"radius": "4000 mm"}, "tip_edge": {"radius": "0 mm"}},
        "gear": {"tip_edge": {"radius": "0 mm"}},
        "misalignment": {"slope": "0.0008"}, "load": {"tangential_load": "8000 N"},
        "analysis": {"positions": 4, "interference": False, "positions_check": False}}


def brute_force(mesh: trimesh.Trimesh, points: np.ndarray) -> np.ndarray:
    """Unsigned distance to the closest of all triangles (independent of the sampling)."""
    out = []
    for p in points:
        c = trimesh.triangles.closest_point(mesh.triangles, np.repeat(p[None], len(mesh.faces), 0))
        out.append(np.linalg.norm(c - p, axis=1).min())
    return np.array(out)


def test_signed_distance_is_exact_on_long_thin_facets():
    """A box 100 × 1 × 1 mm of 12 sliver triangles: the distance equals the box's closed
    form to 1e-12 mm, inside negative, everywhere within it."""
    box = trimesh.creation.box(extents=[100.0, 1.0, 1.0])
    surface = TriangleSurface(box.vertices, box.faces)
    q = np.random.default_rng(2).uniform([-51, -1, -1], [51, 1, 1], (3000, 3))
    d, _, _ = surface.signed_distance(q)
    half = np.array([50.0, 0.5, 0.5])
    inside = np.all(np.abs(q) <= half, axis=1)
    outside = np.linalg.norm(np.maximum(np.abs(q) - half, 0.0), axis=1)
    depth = -np.min(half - np.abs(q), axis=1)
    assert np.max(np.abs(d - np.where(inside, depth, outside))) < 1e-12


def test_signed_distance_matches_brute_force_on_a_gear_sector():
    """An uncrowned gear sector tessellated to 10 µm (long facets across the face): near
    its surface the distance equals the closest of all triangles; along a tooth's middle the
    sign changes at the tip circle, beyond which the distance is r - r_tip (the tip land's
    facets stand within the 10 µm chordal tolerance of the circle)."""
    pair = gearset.gear_pair(parse_case({**SPUR, "pinion": {}}))
    mesh = cad.tessellate(cad.build_gear(pair.gear, teeth=3).solid, 0.01)
    surface = TriangleSurface(mesh.vertices, mesh.faces)
    rng = np.random.default_rng(3)
    near = mesh.sample(400, return_index=False) + rng.normal(scale=0.2, size=(400, 3))
    d, _, _ = surface.signed_distance(near)
    assert np.max(np.abs(np.abs(d) - brute_force(mesh, near))) < 1e-9
    # along the middle of tooth 0 (on the +x axis): inside below the tip radius
    r = np.linspace(85.0, 95.0, 41)
    d, _, _ = surface.signed_distance(np.stack([r, 0 * r, 0 * r], -1))
    tip = pair.gear.tip_radius
    assert np.all((d < 0) == (r < tip))
    assert d[r > tip] == pytest.approx(r[r > tip] - tip, abs=0.01)


@pytest.fixture(scope="module")
def both(tmp_path_factory):
    """The same crowned, misaligned pair: exact, and from STL files of five-tooth sectors
    (2 µm chordal tolerance) through an `imported` case."""
    folder = tmp_path_factory.mktemp("imported")
    spur = parse_case(SPUR)
    pair = gearset.gear_pair(spur)
    for name, gear, mods in (("pinion", pair.pinion, pair.pinion_modifications),
                             ("gear", pair.gear, pair.gear_modifications)):
        cad.write_mesh(cad.tessellate(cad.build_gear(gear, mods, teeth=5).solid, 0.002),
                       folder / f"{name}.stl")
    (folder / "case.toml").write_text(
        'kind = "imported"\n'
        'pinion = { file = "pinion.stl", teeth = 20, form_diameter = "56.46 mm" }\n'
        'gear = { file = "gear.stl", teeth = 60, form_diameter = "174.78 mm" }\n'
        'center_distance = "120 mm"\n'
        'pinion_phase = "-36 deg"\n'       # teeth 0..4 -> -2..2
        'gear_phase = "168 deg"\n'         # 180 deg - two gear pitches
        '[misalignment]\nslope = "0.0008"\n'
        '[load]\ntangential_load = "8000 N"\n'
        '[analysis]\npositions = 4\n')
    case, _ = load_case(folder / "case.toml")
    return analyse(spur).sections, analyse(case).sections, folder


def touching(sections) -> list[dict]:
    """The exact analysis's pairs in contact (the pairs it keeps beyond the approach for
    its loaded contact have no Hertz contact; the mesh path keeps none)."""
    return [r for r in sections["positions"] if r["rigid_contact"]]


def test_mesh_path_agrees_with_the_exact_analysis(both):
    """Every exact contact away from the tip is found on the meshes, at the same place
    (0.1 mm along the face, 0.02 mm in radius), with A within 2 %, B within 15 % (the
    profile curvature spans few facet rows at 2 µm; it converges with the tessellation),
    the peak pressure within 6 % and the transmission error within 2 µrad (about the
    mean)."""
    exact, mesh, _ = both
    te_exact = np.mean([r["transmission_error_urad"] for r in touching(exact)])
    matched = 0
    for e in touching(exact):
        if e["edge_margins_mm"]["pinion_tip"] < 0.5:   # a tip corner: no bowl to fit A, B
            continue
        m = [r for r in mesh["positions"]
             if r["roll_deg"] == pytest.approx(e["roll_deg"]) and r["pair"] == e["pair"]]
        assert m, f"contact at roll {e['roll_deg']} pair {e['pair']} not found on the mesh"
        r = m[0]
        matched += 1
        assert r["face_position_mm"] == pytest.approx(e["face_position_mm"], abs=0.1)
        assert r["contact_radius_pinion_mm"] == pytest.approx(e["contact_radius_pinion_mm"], abs=0.02)
        assert r["A_per_mm"] == pytest.approx(e["A_per_mm"], rel=0.02)
        assert r["B_per_mm"] == pytest.approx(e["B_per_mm"], rel=0.15)
        assert r["p_max_MPa"] == pytest.approx(e["p_max_MPa"], rel=0.06)
        assert r["transmission_error_urad"] == pytest.approx(
            e["transmission_error_urad"] - te_exact, abs=2.0)
    assert matched >= 5


def test_mesh_path_holds_the_ellipse_against_tips_and_form_circles(both):
    """The margins to both bodies' tip circles (the meshes' largest radii) and form circles
    (the case's form diameters), walked along the meshes' transverse profiles, equal the
    exact analysis's (lengths along the involutes) within 0.03 mm at every contact, the
    pinion-tip corner contact at the end of the path included (roll -p/2, the cycle's one
    end: the positions hold it once): both paths put their least margin there, negative (a
    tip cuts the ellipse; edge_contact names face ends)."""
    exact, mesh, _ = both
    corners = 0
    for e in touching(exact):
        m = [r for r in mesh["positions"]
             if r["roll_deg"] == pytest.approx(e["roll_deg"]) and r["pair"] == e["pair"]]
        assert m, f"contact at roll {e['roll_deg']} pair {e['pair']} not found on the mesh"
        for edge in ("pinion_tip", "pinion_form", "gear_tip", "gear_form"):
            assert m[0]["edge_margins_mm"][edge] == pytest.approx(e["edge_margins_mm"][edge], abs=0.03)
        if e["edge_margins_mm"]["pinion_tip"] < 0:
            corners += 1
            assert m[0]["edge_margin_mm"] < 0 and not m[0]["edge_contact"]
            assert min(m[0]["edge_margins_mm"], key=m[0]["edge_margins_mm"].get) == "pinion_tip"
    assert corners == 1


def test_missing_body_file_is_named(both):
    _, _, folder = both
    text = (folder / "case.toml").read_text().replace("gear.stl", "nowhere.stl")
    (folder / "bad.toml").write_text(text)
    with pytest.raises(CaseError, match=r"gear\.file: 'nowhere\.stl': no such file"):
        load_case(folder / "bad.toml")


# --- pairs from other gear generators (data/peers, see its README) -----------------

DATA = Path(__file__).parents[1] / "data" / "peers"
#: the files' largest flank deviation from the exact involute (µm, data/peers/README)
DEVIATION_UM = {"pgw_pinion_z20_sector3.step": 2.34, "pgw_gear_z60_sector3.step": 0.11,
                "pgw_pinion_z20_crowned_sector3.step": 2.34, "pgw_gear_z60_full.step.gz": 0.11}
#: the gear's base radius (mm) of every pair here: z = 60, m = 3 mm, 20 deg
GEAR_BASE_RADIUS = 90.0 * math.cos(math.radians(20.0))
C_E = compliance(206e3, 0.3, 206e3, 0.3)


def body(name: str, folder: Path, tolerance: float) -> TriangleSurface:
    """A body of data/peers tessellated to `tolerance` (mm); .gz unpacked first."""
    path = DATA / name
    if name.endswith(".gz"):
        path = folder / name[:-3]
        path.write_bytes(gzip.decompress((DATA / name).read_bytes()))
    return load_surface(path, tolerance)


def peer_cycle(pinion, gear, slope=0.0, positions=3, turn=0.0):
    """The mesh path on a pair of data/peers (tooth 0 of both on +x, faces 0..30)."""
    mesh = ParallelMesh(20, 60, 120.0, math.radians(20.0), Misalignment(slope=slope),
                                  gear_start=math.pi)
    return imported_cycle(mesh, pinion.turned(turn) if turn else pinion, gear, 8513.4, C_E,
                          CycleSettings(positions=positions))


def facet_bound(pinion, gear, names=()) -> float:
    """The transmission error's swing (µrad) the files allow: both bodies' chordal errors
    and the files' flank deviations, as a turn of the gear at its base radius."""
    error = chordal_error(pinion) + chordal_error(gear) + 1e-3 * sum(DEVIATION_UM[n] for n in names)
    return 1e6 * error / GEAR_BASE_RADIUS


def finite_rows(rows):
    """No NaN or inf anywhere in the rows (None only for what does not apply)."""
    for row in rows:
        for key, value in row.items():
            values = value.values() if isinstance(value, dict) else [value]
            for v in values:
                assert v is None or isinstance(v, (str, bool)) or math.isfinite(v), (key, v)


@pytest.fixture(scope="module")
def peer(tmp_path_factory):
    folder = tmp_path_factory.mktemp("peer")
    return {name: body(name, folder, 0.005) for name in
            ("pgw_pinion_z20_sector3.step", "pgw_gear_z60_sector3.step",
             "pgw_pinion_z20_crowned_sector3.step", "pgw_gear_z60_full.step.gz")}


def test_uncrowned_misaligned_pair_is_a_line_cut_by_the_face_end(peer):
    """Another generator's uncrowned pair under 0.0008 rad slope: the gap falls linearly
    along the face (no bowl), so every contact is a line from the face end it closes at,
    as long as the approach over the slope (6.32 µm / 0.0008 = 7.9 mm), loaded as a Hertz
    line over that length, with no approach; its margin at that end is minus the face width
    (nothing turns the gap beyond it), every other edge's finite; nothing NaN or inf."""
    rows = peer_cycle(peer["pgw_pinion_z20_sector3.step"], peer["pgw_gear_z60_sector3.step"],
                      slope=0.0008)
    finite_rows(rows)
    assert len(rows) >= 3
    for r in rows:
        assert r["contact_model"] == "line" and r["approach_mm"] is None
        assert r["contact_length_mm"] == pytest.approx(0.00632 / 0.0008, rel=0.05)
        assert r["rigid_a_mm"] == pytest.approx(0.5 * r["contact_length_mm"])
        assert r["edge_contact"] and r["edge_contact_at"] in ("pinion_end_B", "gear_end_B")
        assert r["edge_margins_mm"][r["edge_contact_at"]] == pytest.approx(-30.0, abs=0.1)
        assert r["edge_margins_mm"]["pinion_end_A"] > 20.0
        line = hertz_line(r["normal_load_N"] / r["contact_length_mm"], 0.5 / r["B_per_mm"], C_E)
        assert r["p_max_MPa"] == pytest.approx(line.p0) and r["b_mm"] == pytest.approx(line.b)
        assert 30.0 - r["contact_length_mm"] / 2 == pytest.approx(r["face_position_mm"], abs=0.1)


def test_crowned_bowl_beyond_the_edge_reports_the_extent_cut_off(peer):
    """A crown of 4000 mm (A = 1.25e-4 /mm) under 0.004 rad slope: the bowl's least lies
    slope / 2A = 16 mm from mid-face, d = 1 mm beyond end B, so the contact is a line cut by
    that end; continued beyond it, the gap stays within the approach of its value at the
    end for sqrt(d² + approach / A) = 7.2 mm past the least: about 8 mm cut off (the margin;
    not the face width), the line in the face about 6 mm long. Checked against the bowl's
    own A (the fit over the face)."""
    rows = peer_cycle(peer["pgw_pinion_z20_crowned_sector3.step"],
                      peer["pgw_gear_z60_sector3.step"], slope=0.004)
    finite_rows(rows)
    for r in rows:
        assert r["contact_model"] == "line" and r["edge_contact"]
        A = r["A_per_mm"]
        assert A == pytest.approx(1.25e-4, rel=0.1)
        least = 15.0 + 0.004 / (2.0 * A)                    # beyond the face (0 .. 30 mm)
        end = 30.0 - (30.0 - r["face_position_mm"] - 0.5 * r["contact_length_mm"])
        beyond = least - end
        assert 0 < beyond < 2
        reach = math.sqrt(beyond ** 2 + 0.00632 / A)
        assert r["edge_margins_mm"][r["edge_contact_at"]] == pytest.approx(-(beyond + reach), abs=0.3)
        assert r["contact_length_mm"] == pytest.approx(reach - beyond, abs=0.3)


def test_crowned_aligned_pair_is_an_ellipse_inside_the_face(peer):
    """The same crown aligned: a bowl centred on the face, an ellipse (Hertz point
    contact) with the crown's A, clear of both face ends by what its rigid pattern leaves."""
    rows = peer_cycle(peer["pgw_pinion_z20_crowned_sector3.step"], peer["pgw_gear_z60_sector3.step"])
    finite_rows(rows)
    for r in rows:
        assert r["contact_model"] == "ellipse" and r["approach_mm"] > 0
        assert r["face_position_mm"] == pytest.approx(15.0, abs=0.3)
        assert r["A_per_mm"] == pytest.approx(1.25e-4, rel=0.1)
        assert r["contact_length_mm"] == pytest.approx(2 * r["rigid_a_mm"], rel=0.05)
        assert r["edge_margins_mm"]["pinion_end_A"] > 0 and r["edge_margins_mm"]["pinion_end_B"] > 0
        assert not r["edge_contact"] and r["edge_contact_at"] is None


def test_no_contact_outside_the_bodies(peer):
    """Contacts lie on the pinion's flank: never beyond its tip circle (the largest radius
    of the file, to its facets' chordal error), never off its face; the contacts at the
    ends of the path that reach the tip have their least margin there, negative. (The old
    fit put its bowl's vertex off the flank, beyond the tip.)"""
    pinion = peer["pgw_pinion_z20_crowned_sector3.step"]
    tip = float(np.max(np.hypot(pinion.vertices[:, 0], pinion.vertices[:, 1])))
    # the whole gear, the pinion turned 1 deg on, at the cycle's end (roll -9 deg, half a
    # pitch): its leaving tooth (1) meets the gear with its tip corner
    rows = peer_cycle(pinion, peer["pgw_gear_z60_full.step.gz"], slope=0.0008, positions=2,
                      turn=math.radians(1.0))
    rows = [r for r in rows if r["roll_deg"] == pytest.approx(-9.0)]
    corners = 0
    for r in rows:
        assert r["contact_radius_pinion_mm"] <= tip + chordal_error(pinion)
        assert 0.0 <= r["face_position_mm"] <= 30.0
        if r["edge_margins_mm"]["pinion_tip"] < 0:
            corners += 1
            assert r["edge_margin_mm"] < 0 and r["contact_radius_pinion_mm"] > tip - 0.5
    assert corners >= 1


def test_peer_pair_transmission_error_within_what_the_files_allow(peer):
    """Another generator's uncrowned pair, aligned: the exact answer is flat, so the swing
    is the files' own: within their chordal errors and flank deviations (README) as a turn
    of the gear at its base radius (here about 60 µrad at 5 µm facets; the swing, 15 µrad,
    is the shape of the pinion file's 2.3 µm profile error)."""
    pinion, gear = peer["pgw_pinion_z20_sector3.step"], peer["pgw_gear_z60_sector3.step"]
    rows = peer_cycle(pinion, gear, positions=5)
    te = [r["transmission_error_urad"] for r in rows]
    assert max(te) - min(te) <= facet_bound(pinion, gear, ("pgw_pinion_z20_sector3.step",
                                                           "pgw_gear_z60_sector3.step"))


@pytest.fixture(scope="module")
def uncrowned_own():
    """The tool's own uncrowned pair as three-tooth sectors (2 µm facets) and the exact
    analysis of the same pair."""
    spur = parse_case({**SPUR, "pinion": {}, "misalignment": {}})
    pair = gearset.gear_pair(spur)
    meshes = [cad.tessellate(cad.build_gear(g, teeth=3).solid, 0.002) for g in (pair.pinion, pair.gear)]
    bodies = [TriangleSurface(m.vertices, m.faces) for m in meshes]
    return bodies, analyse(spur).sections


def test_own_pair_transmission_error_flat_as_the_exact_one(uncrowned_own):
    """The tool's own uncrowned pair (flanks within 0.03 µm of the involute), aligned: the
    exact analysis is flat, and the meshes' swing stays within the facets' bound (their
    chordal errors as a turn of the gear at its base radius, 23 µrad at 2 µm) - the old
    vertex-to-facet lag solve swung 11.7 µrad where 1-2 were due."""
    (pinion, gear), exact = uncrowned_own
    te_exact = [r["transmission_error_urad"] for r in exact["positions"]]
    assert max(te_exact) - min(te_exact) < 0.1
    mesh = ParallelMesh(20, 60, 120.0, math.radians(20.0), gear_start=math.pi - math.radians(6.0))
    rows = imported_cycle(mesh, pinion.turned(-math.radians(18.0)), gear, 8513.4, C_E,
                          CycleSettings(positions=5))
    finite_rows(rows)
    te = [r["transmission_error_urad"] for r in rows]
    assert max(te) - min(te) <= facet_bound(pinion, gear)
    assert all(r["contact_model"] == "line" and r["contact_length_mm"] == pytest.approx(30.0, abs=0.1)
               for r in rows)


def test_full_gear_step_from_another_generator(peer):
    """A whole 60-tooth gear STEP (not a sector) against the pinion sector: the same line
    contacts as the sector, at the same transmission error within the facets' bound."""
    full = peer["pgw_gear_z60_full.step.gz"]
    rows = peer_cycle(peer["pgw_pinion_z20_sector3.step"], full, slope=0.0008)
    sector = peer_cycle(peer["pgw_pinion_z20_sector3.step"], peer["pgw_gear_z60_sector3.step"],
                        slope=0.0008)
    whole = {(r["roll_deg"], r["pair"]): r for r in rows}
    # the whole gear has the teeth a sector lacks (a pinion tip corner at the path's end)
    assert set(whole) >= {(r["roll_deg"], r["pair"]) for r in sector}
    finite_rows(rows)
    for b in sector:
        a = whole[(b["roll_deg"], b["pair"])]
        assert a["contact_model"] == b["contact_model"] == "line"
        assert a["contact_length_mm"] == pytest.approx(b["contact_length_mm"], abs=0.2)
        assert a["transmission_error_urad"] == pytest.approx(b["transmission_error_urad"],
                                                             abs=facet_bound(full, full))


def test_peer_pair_as_stl_reads_as_its_step(peer, tmp_path):
    """The same facets written as binary STL (single precision) and read back give the
    same contacts: the STL path is the STEP path without the tessellation."""
    names = ("pgw_pinion_z20_sector3.step", "pgw_gear_z60_sector3.step")
    stl = []
    for name in names:
        path = tmp_path / name.replace(".step", ".stl")
        cad.write_mesh(peer[name].mesh, path)
        stl.append(load_surface(path))
    rows = peer_cycle(*stl, slope=0.0008, positions=2)
    step = peer_cycle(*(peer[n] for n in names), slope=0.0008, positions=2)
    assert [(r["roll_deg"], r["pair"]) for r in rows] == [(r["roll_deg"], r["pair"]) for r in step]
    for a, b in zip(rows, step):
        assert a["transmission_error_urad"] == pytest.approx(b["transmission_error_urad"], abs=0.5)
        assert a["contact_length_mm"] == pytest.approx(b["contact_length_mm"], abs=0.05)
        assert a["edge_contact_at"] == b["edge_contact_at"]


def peer_case(folder: Path, **changes) -> Path:
    """An imported case of the py-gearworks pair in `folder`, with `changes` to its table."""
    table = {"kind": "imported",
             "pinion": {"file": str(DATA / "pgw_pinion_z20_sector3.step"), "teeth": 20},
             "gear": {"file": str(DATA / "pgw_gear_z60_sector3.step"), "teeth": 60},
             "center_distance": "120 mm", "step_tolerance": "10 um",
             "load": {"tangential_load": "8000 N"}, "analysis": {"positions": 2}}
    for key, value in changes.items():
        if isinstance(value, dict):
            table[key] = {**table.get(key, {}), **value}
        else:
            table[key] = value
    return parse_case(table, base=folder)


@pytest.mark.parametrize("changes, message", [
    ({"gear": {"teeth": 59}}, (r"gear\.teeth: 59, but pgw_gear_z60_sector3\.step is no gear of "
                               r"59 teeth .* 6\.000 deg apart \(60\.00 teeth a turn\)")),
    ({"center_distance": "140 mm"}, r"center_distance: 140 mm: the bodies' tip radii are 33 "
                                    r"and 93 mm, so their teeth can only mesh between 93 and "
                                    r"126 mm"),
    ({"center_distance": "125.9 mm"}, r"the gear never closes on the pinion over two pitches"),
    ({"center_distance": "112 mm"}, r"the bodies overlap at every gear angle over two pitches"),
    ({"misalignment": {"axial_shift": "40 mm"}}, r"the bodies' faces do not overlap along the axis"),
])
def test_a_pair_that_cannot_be_analysed_is_told_why(tmp_path, changes, message):
    """One message naming the real cause (never the tessellation)."""
    with pytest.raises(CaseError, match=message) as caught:
        analyse(peer_case(tmp_path, **changes))
    assert "tessellation" not in str(caught.value)
