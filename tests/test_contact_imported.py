"""Imported bodies: signed distances on triangulations, and the mesh path's contact against
the exact analysis of the same pair."""


import numpy as np
import pytest
import trimesh

from toothcontact import cad, gearset
from toothcontact.analyses import analyse
from toothcontact.case import CaseError, load_case, parse_case
from toothcontact.mesh import TriangleSurface

SPUR = {"kind": "spur", "teeth": [20, 60], "module": "3 mm", "pressure_angle": "20 deg",
        "face_width": "30 mm", "pinion": {"crown": {"radius": "4000 mm"}},
        "misalignment": {"slope": "0.0008"}, "load": {"tangential_load": "8000 N"},
        "analysis": {"positions": 5, "interference": False}}


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
        '[analysis]\npositions = 5\n')
    case, _ = load_case(folder / "case.toml")
    return analyse(spur).sections, analyse(case).sections, folder


def test_mesh_path_agrees_with_the_exact_analysis(both):
    """Every exact contact away from the tip is found on the meshes, at the same place
    (0.1 mm along the face, 0.02 mm in radius), with A within 2 %, B within 15 % (the
    profile curvature spans few facet rows at 2 µm; it converges with the tessellation),
    the peak pressure within 6 % and the transmission error within 2 µrad (about the
    mean)."""
    exact, mesh, _ = both
    te_exact = np.mean([r["transmission_error_urad"] for r in exact["positions"]])
    matched = 0
    for e in exact["positions"]:
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
    pinion-tip corner contacts at the ends of the path included: both paths flag those as
    edge contact at the pinion tip."""
    exact, mesh, _ = both
    corners = 0
    for e in exact["positions"]:
        m = [r for r in mesh["positions"]
             if r["roll_deg"] == pytest.approx(e["roll_deg"]) and r["pair"] == e["pair"]]
        assert m, f"contact at roll {e['roll_deg']} pair {e['pair']} not found on the mesh"
        for edge in ("pinion_tip", "pinion_form", "gear_tip", "gear_form"):
            assert m[0]["edge_margins_mm"][edge] == pytest.approx(e["edge_margins_mm"][edge], abs=0.03)
        if e["edge_margins_mm"]["pinion_tip"] < 0:
            corners += 1
            assert m[0]["edge_contact"] and e["edge_contact"]
            assert min(m[0]["edge_margins_mm"], key=m[0]["edge_margins_mm"].get) == "pinion_tip"
    assert corners == 2


def test_missing_body_file_is_named(both):
    _, _, folder = both
    text = (folder / "case.toml").read_text().replace("gear.stl", "nowhere.stl")
    (folder / "bad.toml").write_text(text)
    with pytest.raises(CaseError, match=r"gear\.file: 'nowhere\.stl': no such file"):
        load_case(folder / "bad.toml")
