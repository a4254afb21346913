"""The worm solid against its exact flanks and an independent volume."""

import math

import numpy as np
import pytest

from toothcontact import cad
from toothcontact.surfaces.worm import WormFlank


@pytest.fixture(scope="module")
def saba_worm():
    """Seed 000's worm (z1 = 1, mn = 1.1 mm, lead angle 4.1°), ZI, 20 mm long."""
    kw = dict(form="ZI", starts=1, lead_angle=math.radians(4.1), normal_module=1.1, length=20.0)
    left = WormFlank.from_lead_angle(side="left", **kw)
    right = WormFlank.from_lead_angle(side="right", **kw)
    return cad.build_worm(left, right)


@pytest.fixture(scope="module")
def undercut_worm():
    """A ZK worm whose flanks start on a form circle 0.27 mx above the root (2 starts,
    mx = 2 mm, q = 6, lead angle 18.4°), 10 mm long."""
    kw = dict(form="ZK", starts=2, axial_module=2.0, pitch_diameter=12.0, length=10.0)
    left, right = (WormFlank(side=side, **kw) for side in ("left", "right"))
    assert left.form_radius > left.root_diameter / 2 + 0.5
    return cad.build_worm(left, right)


@pytest.mark.parametrize("name", ["saba_worm", "undercut_worm"])
def test_worm_solid_is_valid_and_has_the_screw_volume(name, request):
    """Volume = core + thread; the thread fills, at each radius r, the fraction w(r)/p_x of
    every circle (w: axial thread width from the exact axial profiles; below a form circle
    the width there), so V = π·r_f²·L + (L/p_x)·∫ 2π·r·w(r) dr (numerical quadrature,
    1e-7; 1e-6 for the ZK worm, whose profile, curved more, the 17 interpolation points
    follow to 0.04 µm: 8e-7 of the volume)."""
    body = request.getfixturevalue(name)
    left, right = body.flanks["left"], body.flanks["right"]
    rf, (r0, ra) = left.root_diameter / 2, left.domain[0]
    r = np.linspace(rf, ra, 8001)
    profile = np.maximum(r, r0)
    w = right.axial_profile(profile) - left.axial_profile(profile)
    expected = math.pi * rf**2 * left.length + left.length / left.axial_pitch * np.trapezoid(
        2 * math.pi * r * w, r)
    assert cad.is_valid(body.solid)
    assert cad.volume(body.solid) == pytest.approx(expected, rel=1e-7 if name == "saba_worm"
                                                   else 1e-6)


@pytest.mark.parametrize("name", ["saba_worm", "undercut_worm"])
def test_worm_faces_lie_on_the_exact_flanks(name, request):
    assert cad.worm_flank_deviation(request.getfixturevalue(name)) < 1e-4  # 0.1 µm


def test_the_deviation_measure_sees_an_offset():
    """The measure is not blind: points moved 2 µm off the flank along its normal measure
    2 µm from the faces."""
    from OCP.BRepBuilderAPI import BRepBuilderAPI_MakeVertex
    from OCP.BRepExtrema import BRepExtrema_DistShapeShape
    from OCP.TopAbs import TopAbs_SHELL
    from OCP.TopExp import TopExp_Explorer
    from OCP.gp import gp_Pnt

    kw = dict(form="ZA", starts=1, lead_angle=math.radians(6.0), normal_module=1.5, length=12.0)
    left = WormFlank.from_lead_angle(side="left", **kw)
    body = cad.build_worm(left, WormFlank.from_lead_angle(side="right", **kw))
    shell = TopExp_Explorer(body.solid, TopAbs_SHELL).Current()
    (u0, u1), _ = left.domain
    s = left.evaluate(np.linspace(u0 + 0.3, u1 - 0.3, 5), np.zeros(5))
    for p, n in zip(s.points + 0.002 * s.normals, s.normals):
        vertex = BRepBuilderAPI_MakeVertex(gp_Pnt(*map(float, p))).Vertex()
        assert BRepExtrema_DistShapeShape(vertex, shell).Value() == pytest.approx(0.002, abs=1e-6)


def test_worm_set_export_worm_and_enveloped_wheel(tmp_path):
    """Seed 000's worm set: both solids valid, both flank families within 1 µm of the exact
    surfaces (the wheel's: the envelope), STEP round trip and watertight STL."""
    import json

    from toothcontact.runner import bundled_cases_dir, export_case

    record = export_case(bundled_cases_dir() / "worm_saba_set.toml", tmp_path)
    assert record == json.loads((tmp_path / "export.json").read_text())
    for name in ("worm", "wheel"):
        part = record["parts"][name]
        assert part["valid"] and part["stl_watertight"], name
        assert part["flank_deviation_um"] < 1.0, name
        assert part["step_reread_volume_mm3"] == pytest.approx(part["volume_mm3"], rel=1e-9)
