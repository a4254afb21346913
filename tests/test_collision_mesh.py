"""The collision meshes of cylindrical gears (mesh.gear_mesh), against the B-spline solids
built independently from the same exact sections (cad.build_gear: OCP interpolation and
loft)."""

import numpy as np
import pytest

from toothcontact import cad, gearset
from toothcontact.case import parse_case
from toothcontact.mesh import gear_mesh
from toothcontact.surfaces.outline import ToothOutline

CHORD = 0.01  # mm


def _shell_distance(solid, points: np.ndarray) -> np.ndarray:
    """Distance (mm) of each point to the boundary of an OCP solid."""
    from OCP.BRepBuilderAPI import BRepBuilderAPI_MakeVertex
    from OCP.BRepExtrema import BRepExtrema_DistShapeShape
    from OCP.gp import gp_Pnt
    from OCP.TopAbs import TopAbs_SHELL
    from OCP.TopExp import TopExp_Explorer

    shell = TopExp_Explorer(solid, TopAbs_SHELL).Current()
    return np.array([BRepExtrema_DistShapeShape(
        BRepBuilderAPI_MakeVertex(gp_Pnt(*map(float, p))).Vertex(), shell).Value() for p in points])


@pytest.mark.parametrize("raw", [
    {"kind": "spur", "teeth": [17, 40], "module": "5 mm", "pressure_angle": "20 deg",
     "helix_angle": "20 deg", "face_width": "50 mm", "load": {"torque": "500 N*m"}},
    {"kind": "spur", "teeth": [14, 40], "module": "2 mm", "pressure_angle": "20 deg",
     "face_width": "20 mm", "pinion": {"crown": {"height": "30 um"}},
     "load": {"torque": "50 N*m"}},
], ids=["helical", "undercut-crowned"])
def test_gear_mesh_lies_on_the_solid_within_its_chord(raw):
    """Three teeth of the pinion: every vertex on the B-spline solid's boundary within its
    own fitting error between its sections and fitting points (5 µm), every triangle's centroid within 1.2 × CHORD of it (the sags
    across and along the face add), and the mesh spans the teeth (tip to root circle)."""
    pair = gearset.gear_pair(parse_case(raw))
    gear, mods = pair.pinion, pair.pinion_modifications
    vertices, faces = gear_mesh(ToothOutline(gear, mods), 3, CHORD)
    body = cad.build_gear(gear, mods, teeth=3)
    turn = 2.0 * np.pi / gear.teeth     # the solid's sector runs from tooth 0, the mesh's from -1
    c, s = np.cos(turn), np.sin(turn)
    to_solid = np.array([[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]])
    rng = np.random.default_rng(7)
    at_vertices = _shell_distance(body.solid, vertices[rng.choice(len(vertices), 80)] @ to_solid.T)
    centroids = vertices[faces[rng.choice(len(faces), 200)]].mean(axis=1)
    at_centroids = _shell_distance(body.solid, centroids @ to_solid.T)
    assert at_vertices.max() < 5e-3
    assert at_centroids.max() < 1.2 * CHORD
    assert at_centroids.max() > 0.1 * CHORD           # the chords are not denser than asked
    radii = np.hypot(vertices[:, 0], vertices[:, 1])
    assert radii.max() == pytest.approx(gear.tip_radius, abs=1e-9)
    # the root circle, less the 30 µm crown at the face ends (a crown moves the whole side)
    assert radii.min() == pytest.approx(gear.root_radius_value, abs=0.035)
    assert len(faces) < 20000
