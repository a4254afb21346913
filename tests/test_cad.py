"""B-spline solids against the exact flanks and independent volume estimates."""

import json
import math

import numpy as np
import pytest

from toothcontact import cad
from toothcontact.surfaces.modify import FlankModifications, LeadCrown, TipRelief
from toothcontact.surfaces.generation import generate_ring_side, generate_side
from toothcontact.surfaces.involute import CylindricalGear


def transverse_area(gear: CylindricalGear, samples: int = 40) -> float:
    """Shoelace area of a densely sampled exact transverse outline (no OCC involved); the
    fillet by `samples` generated points."""
    pitch = 2 * math.pi / gear.teeth
    outline = []
    side = generate_ring_side(gear) if gear.internal else generate_side(gear, samples=samples)
    flank = {s: gear.flank(s, side.form_radius) for s in (1, -1)}
    t = np.linspace(*flank[1].domain[0], 400)
    if gear.internal:
        t = t[::-1]  # from the form end to the tip
    fil_m = side.fillet * [1, -1]
    minus = np.stack(flank[-1].transverse_point(t), -1)
    plus = np.stack(flank[1].transverse_point(t[::-1]), -1)
    tip = _arc(gear.tip_radius, math.atan2(*minus[-1][::-1]), math.atan2(*plus[0][::-1]))
    fil_p = side.fillet[::-1]
    root = _arc(gear.root_radius_value, math.atan2(*fil_p[-1][::-1]),
                math.atan2(*fil_m[0][::-1]) + pitch)
    tooth = np.concatenate([fil_m, minus, tip, plus, fil_p, root])
    for k in range(gear.teeth):
        c, s = math.cos(k * pitch), math.sin(k * pitch)
        outline.append(tooth @ np.array([[c, s], [-s, c]]))
    xy = np.concatenate(outline)
    x, y = xy[:, 0], xy[:, 1]
    return 0.5 * abs(np.dot(x, np.roll(y, -1)) - np.dot(y, np.roll(x, -1)))


def _arc(radius, a0, a1, n=400):
    a = np.linspace(a0, a1, n)
    return radius * np.stack([np.cos(a), np.sin(a)], -1)


@pytest.mark.parametrize("gear", [
    CylindricalGear(20, 3.0, math.radians(20), 30.0),
    CylindricalGear(23, 2.5, math.radians(20), 25.0, helix_angle=math.radians(20), profile_shift=0.2),
], ids=["spur", "helical"])
def test_full_gear_solid_volume_flanks_and_files(gear, tmp_path):
    body = cad.build_gear(gear)
    assert cad.is_valid(body.solid)
    # a helix only turns the transverse section: volume = area × face width (dense outline: 1e-5)
    assert cad.volume(body.solid) == pytest.approx(transverse_area(gear) * gear.face_width, rel=1e-5)
    assert cad.flank_deviation(body) < 1e-3  # 1 µm, measured between the fitting points
    step = cad.write_step(body.solid, tmp_path / "g.step")
    again = cad.read_step(step)
    assert cad.is_valid(again)
    assert cad.volume(again) == pytest.approx(cad.volume(body.solid), rel=1e-9)
    mesh = cad.tessellate(body.solid, 0.01)
    assert mesh.is_watertight
    assert mesh.volume == pytest.approx(cad.volume(body.solid), rel=1e-3)


def test_undercut_pinion_is_built_with_its_trochoid_and_form_circle():
    """A 14-tooth 20° pinion without shift is undercut: its solid is valid, says so, and its
    transverse section (z = 0) is the generated root up to the form circle and the involute
    from it: dense exact points of both lie on the solid's boundary within 1 µm (40 points
    carry the fillet's B-spline, 17 the flank's), the flank faces within 1 µm between their
    fitting points, and the volume is the dense exact outline's area times the face width
    (1e-4: the fillet's B-spline bulges by up to 1 µm between its points)."""
    from OCP.BRepBuilderAPI import BRepBuilderAPI_MakeVertex
    from OCP.BRepExtrema import BRepExtrema_DistShapeShape
    from OCP.TopAbs import TopAbs_SHELL
    from OCP.TopExp import TopExp_Explorer
    from OCP.gp import gp_Pnt

    gear = CylindricalGear(14, 2.0, math.radians(20), 20.0)
    body = cad.build_gear(gear, teeth=3)
    assert cad.is_valid(body.solid)
    assert any("undercut" in note for note in body.notes)
    assert cad.flank_deviation(body) < 1e-3
    dense = generate_side(gear, samples=400)
    assert dense.undercut and dense.form_radius > gear.base_radius
    flank = gear.flank(1, dense.form_radius)
    exact = np.concatenate([dense.fillet, np.stack(flank.transverse_point(
        np.linspace(*flank.domain[0], 200)), -1)])
    shell = TopExp_Explorer(body.solid, TopAbs_SHELL).Current()
    worst = max(BRepExtrema_DistShapeShape(BRepBuilderAPI_MakeVertex(
        gp_Pnt(float(x), float(y), 0.0)).Vertex(), shell).Value() for x, y in exact)
    assert worst < 1e-3
    whole = cad.build_gear(gear)
    reference = transverse_area(gear, samples=4000) * gear.face_width
    assert cad.volume(whole.solid) == pytest.approx(reference, rel=1e-4)


def test_ring_gear_is_rim_minus_toothed_hole():
    ring = CylindricalGear(60, 3.0, math.radians(20), 20.0, internal=True)
    body = cad.build_gear(ring)
    assert cad.is_valid(body.solid)
    outer = ring.root_radius_value + cad.RING_RIM_MODULES * ring.normal_module
    expected = (math.pi * outer**2 - transverse_area(ring)) * ring.face_width
    assert cad.volume(body.solid) == pytest.approx(expected, rel=1e-5)
    assert cad.flank_deviation(body) < 1e-3


def test_modified_sector_follows_the_exact_modified_flank():
    """Bias crown and tip relief on a helical pinion: the B-spline faces pass within 1 µm
    of the exact modified flank between the fitting points."""
    gear = CylindricalGear(23, 2.5, math.radians(20), 25.0, helix_angle=math.radians(20), profile_shift=0.2)
    start = float(gear.base_radius * gear.roll_angle(0.5 * 65.0))
    mods = FlankModifications(lead_crown=LeadCrown(height=0.012, shape="parabolic", center=3.0),
                              tip_relief=TipRelief(0.010, start))
    body = cad.build_gear(gear, mods, teeth=3)
    assert cad.is_valid(body.solid)
    assert cad.flank_deviation(body) < 1e-3
    plain = cad.build_gear(gear, teeth=3)
    removed = cad.volume(plain.solid) - cad.volume(body.solid)
    assert removed > 0  # crowning removes material


def test_export_command_writes_checked_parts(tmp_path):
    from typer.testing import CliRunner

    from toothcontact.cli import app
    from toothcontact.runner import bundled_cases_dir

    case = bundled_cases_dir() / "spur_crowned_20_60.toml"
    result = CliRunner().invoke(app, ["export", str(case), "--out", str(tmp_path)])
    assert result.exit_code == 0, result.output
    record = json.loads((tmp_path / case.stem / "export.json").read_text())
    for name in ("pinion", "gear"):
        part = record["parts"][name]
        assert part["valid"] and part["stl_watertight"]
        assert part["flank_deviation_um"] < 1.0
        assert part["step_reread_volume_mm3"] == pytest.approx(part["volume_mm3"], rel=1e-9)
        assert (tmp_path / case.stem / f"{name}.step").stat().st_size > 0


def test_export_refuses_a_kind_without_solids(tmp_path):
    from typer.testing import CliRunner

    from toothcontact.cli import app
    from toothcontact.runner import bundled_cases_dir

    case = bundled_cases_dir() / "hertz_crossed_cylinders.toml"
    result = CliRunner().invoke(app, ["export", str(case), "--out", str(tmp_path)])
    assert result.exit_code == 2 and "has no solid to export" in result.output
    assert not any(tmp_path.iterdir())
