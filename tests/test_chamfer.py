"""Chamfered edges: a tip chamfer ([member.tip_edge] chamfer, angle, radius) and face-end
chamfers ([member.end_chamfer] length, angle, radius), each with its edge on the flank
rounded (modify.TipEdge with an angle, modify.EndChamfer): straight at its angle in the
exact flank, its rounded edge's curvature, the loaded contact it carries (converged with
the grid) and the case's checks."""

import copy
import math
import tomllib
from pathlib import Path

import numpy as np
import pytest

from toothcontact import analyses, gearset
from toothcontact.analytic.hertz import compliance
from toothcontact.case import parse_case
from toothcontact.contact.compliance import PairCompliance, tooth_compliance
from toothcontact.contact.loaded import loaded_cycle
from toothcontact.parallel import workers

CASES = Path(__file__).parent.parent / "cases"
FZG = tomllib.loads((CASES / "fzg_c_type.toml").read_text())
SPUR = tomllib.loads((CASES / "spur_crowned_20_60.toml").read_text())
STEEL = compliance(206000.0, 0.3, 206000.0, 0.3)


def chamfered_tips(chamfer="0.4 mm", angle="30 deg", radius="0.3 mm") -> dict:
    raw = copy.deepcopy(FZG)
    raw["pinion"]["tip_edge"] = {"chamfer": chamfer, "angle": angle, "radius": radius}
    return raw


def transverse_points(flank, u: np.ndarray) -> np.ndarray:
    """The flank's points (x, y) in the mid-face section at roll angles u."""
    x, y, _ = flank.point(u, np.zeros_like(u))
    return np.column_stack([x, y])


def test_a_tip_chamfer_is_straight_at_its_angle_from_its_edge_on_the_involute():
    """The FZG pinion chamfered 0.4 mm at 30 deg, its edge rounded 0.3 mm: past the
    rounding the flank is straight (within 0.05 µm of a line over the chamfer: measured
    0.2 µm before the drop's own bend was taken at the chamfer's angle), its line passes
    through the involute's point 0.4 mm along the flank from the tip (the chamfer's edge,
    where the rounding is tangent to both; within 1 µm, measured 0.65 µm on a chamfer
    0.23 mm deep: the edge is placed to first order in the involute's curvature) at 30 deg
    to the involute's tangent there (within 0.3 deg, measured 30.2: the rounding turns 30 deg
    against the involute's tangent where it ends, 0.07 mm past the edge, where the
    involute has turned 0.22 deg further); across the rounding the flank curves
    at 1/0.3 mm (exact derivatives, to 1e-4)."""
    pair = gearset.gear_pair(parse_case(chamfered_tips()))
    gear, edge = pair.pinion, pair.pinion_modifications.tip_edge
    flank = gearset.working_flank(gear, pair.pinion_modifications, 1)
    rb = gear.base_radius
    start, turned = edge.breaks
    sample = flank.evaluate(np.array([start / rb + 1e-6]), np.array([0.0]))
    assert abs(float(sample.normal_curvature(1.0, 0.0)[0])) == pytest.approx(1 / 0.3, rel=1e-4)
    s_tip = math.sqrt(gear.tip_radius**2 - rb**2)
    on_chamfer = transverse_points(flank, np.linspace(turned / rb, s_tip / rb, 40))
    centre = on_chamfer.mean(axis=0)
    _, _, (direction, normal) = np.linalg.svd(on_chamfer - centre)
    assert np.abs((on_chamfer - centre) @ normal).max() < 0.05e-3
    # the chamfer's edge on the involute: 0.4 mm of involute arc back from the tip
    arc_tip = 0.5 * s_tip**2 / rb
    s_edge = math.sqrt(2.0 * rb * (arc_tip - 0.4))
    involute = gear.flank(1, rb)
    near = transverse_points(involute, np.array([s_edge / rb - 1e-6, s_edge / rb]))
    assert abs((near[1] - centre) @ normal) < 1e-3
    tangent = (near[1] - near[0]) / np.linalg.norm(near[1] - near[0])
    assert math.degrees(math.acos(abs(tangent @ direction))) == pytest.approx(30.0, abs=0.3)


def test_an_end_chamfer_drops_its_length_times_its_slope_at_the_end_face():
    """The bundled spur pinion, uncrowned, with 0.8 mm × 45 deg end chamfers, edges rounded
    0.3 mm:
    the flank curves at 1/0.3 mm where the rounding starts, runs straight at 45 deg past
    it (the drop grows 1 mm per mm) and at the end face has dropped 0.8 mm (the chamfer's
    line passes through its edge 0.8 mm from the end): to 1e-9 mm."""
    raw = copy.deepcopy(SPUR)
    raw["pinion"] = {"end_chamfer": {"length": "0.8 mm", "radius": "0.3 mm"}}
    pair = gearset.gear_pair(parse_case(raw))
    chamfer = pair.pinion_modifications.end_chamfer
    flank = gearset.working_flank(pair.pinion, pair.pinion_modifications, 1)
    _, _, start, turned = chamfer.breaks(30.0)
    assert start == pytest.approx(15.0 - 0.8 - 0.3 * math.tan(math.radians(22.5)), rel=1e-12)
    u = np.array([0.5 * sum(flank.domain[0])])
    for v, expected in ((start - 1e-6, 0.0), (start + 1e-6, 1 / 0.3)):
        sample = flank.evaluate(u, np.array([v]))
        assert abs(float(sample.normal_curvature(0.0, 1.0)[0])) == pytest.approx(expected,
                                                                                abs=1e-4 / 0.3)
    assert float(flank.drop(u, np.array([15.0]))[0]) == pytest.approx(0.8, abs=1e-9)
    assert float(flank.drop(u, np.array([-15.0]))[0]) == pytest.approx(0.8, abs=1e-9)
    run = np.array([turned + 0.1, turned + 0.3])
    drops = flank.drop(np.repeat(u, 2), run)
    assert (drops[1] - drops[0]) / 0.2 == pytest.approx(1.0, abs=1e-9)


def test_a_chamfered_face_end_carries_its_edge_load_converged_with_the_grid():
    """An uncrowned spur pair tilted 0.3 mrad toward end B, both members chamfered
    0.8 mm × 45 deg at their face ends (edges rounded 0.3 mm, the default 0.1 m_n): the
    contact's end load sits on the pinion's chamfer's rounded edge (pinion_end_B), end
    loaded. Its edge pressure (the mean over 0.1 × 0.1 mm) is 2090 and 2079 MPa at
    pressure_grid 256 and 384 (measured): within 3 % (128 reads 1934 MPa, 7 % low: cells of
    0.06 mm along the face against a contact 0.05 mm onto the rounding). The load per mm in
    the end's strip is 2.7 times the position's load spread evenly over the face (the end
    load ratio's measure since issue 51; over the contact's own mean along its length in
    contact, the measure before, 4.4: 4.42, 4.35 and 4.32 at 256, 384 and 512; a flush
    sharp end, a quarter-space, carries 1.3 of that: the chamfer puts the edge inside the
    body, which its rounding only softens)."""
    raw = copy.deepcopy(SPUR)
    del raw["pinion"]["crown"]
    raw["misalignment"]["slope"] = "0.0003"
    for member in ("pinion", "gear"):
        raw.setdefault(member, {})["end_chamfer"] = {"length": "0.8 mm"}
    raw["analysis"] = {"positions": 3, "interference": False,
                       "positions_check": False, "pressure_grid": 64}
    case = parse_case(raw)
    result = analyses.analyse(case)
    pair = gearset.gear_pair(case)
    teeth = PairCompliance(tooth_compliance(pair.pinion, 206000.0, 0.3),
                           tooth_compliance(pair.gear, 206000.0, 0.3))
    k = next(i for i, r in enumerate(result.sections["positions"])
             if abs(r["roll_deg"]) < 1e-9 and r["pair"] == 0)
    found = {}
    for grid in (256, 384):
        with workers(1):
            solved, failed = loaded_cycle(result.cycle, STEEL, grid, teeth)
        assert not failed
        found[grid] = solved[k].summary
    for summary in found.values():
        assert summary["edge_pressure_at"] == "pinion_end_B" and summary["end_loaded"]
        assert 2.2 < summary["end_load_ratio"] < 3.3
    assert found[384]["edge_pressure_MPa"] == pytest.approx(found[256]["edge_pressure_MPa"],
                                                             rel=0.03)
    assert found[384]["end_load_ratio"] == pytest.approx(found[256]["end_load_ratio"], rel=0.03)


def test_a_crowned_pair_keeps_its_pattern_off_chamfered_ends_and_says_what_it_analysed():
    """The bundled spur case (4000 mm crown, 0.8 mrad) with tip chamfers on both members
    and end chamfers: no contact is end-loaded (the crown keeps the pattern off the
    chamfers' edges), and the notes and member sections name the chamfers."""
    raw = copy.deepcopy(SPUR)
    raw["pinion"]["tip_edge"] = {"chamfer": "0.3 mm"}
    raw["gear"] = {"tip_edge": {"chamfer": "0.3 mm"}, "end_chamfer": {"length": "0.5 mm"}}
    raw["pinion"]["end_chamfer"] = {"length": "0.8 mm", "angle": "30 deg"}
    raw["analysis"] = {"positions": 5, "interference": False, "positions_check": False}
    result = analyses.analyse(parse_case(raw))
    summary = result.sections["summary"]
    assert summary["end_loaded_contacts"] == 0
    assert result.sections["pinion"]["end_chamfer_mm"] == pytest.approx(0.8)
    assert result.sections["pinion"]["end_chamfer_angle_deg"] == pytest.approx(30.0)
    assert result.sections["gear"]["tip_chamfer_angle_deg"] == pytest.approx(30.0)
    note = next(n for n in result.notes if n.startswith("tip edges:"))
    assert "pinion chamfered 0.3 mm at 30 deg, its edge rounded 0.3 mm" in note
    assert "pinion face ends chamfered 0.8 mm at 30 deg" in note


@pytest.mark.parametrize("member, spec, field", [
    ("tip_edge", {"chamfer": "0.4 mm", "angle": "70 deg"}, "pinion.tip_edge.angle"),
    ("tip_edge", {"chamfer": "6 mm"}, "pinion.tip_edge.chamfer"),
    ("tip_edge", {"chamfer": "0.4 mm", "radius": "0 mm"}, "pinion.tip_edge"),
    ("end_chamfer", {"length": "7 mm"}, "pinion.end_chamfer.length"),
    ("end_chamfer", {"length": "1 mm", "angle": "95 deg"}, "pinion.end_chamfer.angle"),
])
def test_a_chamfer_that_does_not_fit_is_refused_in_one_line(tmp_path, member, spec, field):
    """A tip chamfer turning past the tip land, one that would start below the form circle,
    one with a sharp edge, an end chamfer longer than half the 14 mm face, one past
    90 deg: exit 2, one line naming the field, nothing written."""
    import tomli_w

    import mutations

    raw = copy.deepcopy(FZG)
    raw["pinion"][member] = spec
    assert field in mutations.refused_line(tomli_w.dumps(raw), tmp_path)


def test_the_exported_solid_and_mesh_carry_the_chamfers_exactly():
    """A one-tooth sector of the bundled crowned pinion with 0.8 mm end chamfers and a
    0.3 mm tip chamfer: the B-spline faces (the flank, each end's rounded edge and chamfer
    lofted apart) lie within 0.1 µm of the exact flanks between their fitting points
    (measured 0.04 µm; one loft through all sections rang to 30 mm), the solid is valid
    and lighter than the unchamfered one by about the chamfers' wedges (0.5 · 0.8² mm² on
    each flank's two ends, along its profile; within 20 %), and the collision mesh's flank
    vertices on the end face lie on the exact chamfered flank (within 1 µm; none on the
    unchamfered one)."""
    from toothcontact import cad
    from toothcontact.mesh import gear_mesh
    from toothcontact.surfaces.outline import ToothOutline

    raw = copy.deepcopy(SPUR)
    raw["pinion"]["end_chamfer"] = {"length": "0.8 mm"}
    raw["pinion"]["tip_edge"] = {"chamfer": "0.3 mm"}
    pair = gearset.gear_pair(parse_case(raw))
    body = cad.build_gear(pair.pinion, pair.pinion_modifications, teeth=1)
    assert cad.is_valid(body.solid)
    assert len(body.fit_v) == 5
    assert cad.flank_deviation(body) < 1e-4
    plain = cad.build_gear(pair.pinion, replace_end_chamfer(pair.pinion_modifications), teeth=1)
    flank = gearset.working_flank(pair.pinion, pair.pinion_modifications, 1)
    (u0, u1), _ = flank.domain
    profile = float(np.sum(np.linalg.norm(np.diff(transverse_points(
        flank, np.linspace(u0, u1, 200)), axis=0), axis=1)))
    wedges = 2 * 2 * 0.5 * 0.8**2 * profile
    assert cad.volume(plain.solid) - cad.volume(body.solid) == pytest.approx(wedges, rel=0.2)
    vertices, _ = gear_mesh(ToothOutline(pair.pinion, pair.pinion_modifications), teeth=1)
    at_end = vertices[np.isclose(vertices[:, 2], 15.0)]
    u = np.linspace(u0, u1, 20000)
    curves = {}
    for name, surface in (("chamfered", flank), ("plain", gearset.working_flank(
            pair.pinion, replace_end_chamfer(pair.pinion_modifications), 1))):
        exact = np.stack(surface.point(u, np.full_like(u, 15.0)), -1)
        curves[name] = np.array([np.linalg.norm(exact - p, axis=1).min() for p in at_end])
    assert (curves["chamfered"] < 1e-3).sum() >= 10        # the mesh's flank points there
    assert (curves["plain"] < 1e-3).sum() == 0


def replace_end_chamfer(modifications):
    from dataclasses import replace

    return replace(modifications, end_chamfer=None)
