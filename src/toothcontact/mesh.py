"""Triangle meshes: interference between positioned bodies (python-fcl), and imported
bodies read as surfaces (surfaces.triangles.TriangleSurface) to measure separation on.

The separation search sees only the two active flanks; a tooth tip digging into the mate's
root, or a neighbouring tooth touching its back flank, is found here instead: the tooth
surfaces of cylindrical gears are meshed straight from their exact sections (`gear_mesh`),
placed by their frames, and collided as BVH models. Units: mm.
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

import numpy as np

from .surfaces.triangles import TriangleSurface


@dataclass(frozen=True)
class Interference:
    """Where two placed meshes overlap: contact points (mm, world) and how many there are."""

    points: np.ndarray

    @property
    def found(self) -> bool:
        return len(self.points) > 0


def gear_mesh(outline, teeth: int | None = None,
              chord: float = 0.01) -> tuple[np.ndarray, np.ndarray]:
    """Triangles (vertices (n, 3), faces (m, 3)) of the tooth surface of a cylindrical gear
    (its `surfaces.outline.ToothOutline`, modifications included): the
    teeth -k..k about tooth 0 (`teeth` = 2k + 1; every tooth when None or not fewer than
    the gear has), stacked from exact transverse sections (surfaces.outline) dense enough
    that no triangle strays more than `chord` (mm) from the surface, half of it along the
    profile and half across: profile points from the sag of a 17-point trial (sag ~ 1/n²),
    arcs and helix steps from the circle's r·dθ²/8, a lead-curved flank at least 9 sections
    and a section where an end relief begins. The surface is open (no end faces, no
    closure of a sector): interference is where two such surfaces cross."""
    from .surfaces.outline import polar_angle
    from .surfaces.placement import rotation

    gear = outline.gear
    flank = outline.flanks[1]
    (u0, u1), (v0, v1) = flank.domain
    trial = np.linspace(u0, u1, 17)
    points = np.stack(flank.point(trial, np.zeros_like(trial)), -1)
    middle = np.stack(flank.point(0.5 * (trial[1:] + trial[:-1]), np.zeros(16)), -1)
    sag = float(np.max(np.linalg.norm(middle - 0.5 * (points[1:] + points[:-1]), axis=-1)))
    half = 0.5 * chord
    u = np.linspace(u0, u1, max(17, int(np.ceil(16 * np.sqrt(sag / half))) + 1))
    u = _within_sag(flank, u, half)

    def steps(radius: float, angle: float) -> int:   # arc points keeping the sag under half
        return max(2, int(np.ceil(abs(angle) / np.sqrt(8.0 * half / radius))) + 1)

    twist = abs(gear.twist_per_length) * gear.face_width
    z = np.linspace(v0, v1, max(9 if outline.curved else 2, steps(gear.tip_radius, twist)))
    z = np.union1d(z, outline.lead_sections())
    first = outline.section(u, 0.0)
    n_tip = steps(gear.tip_radius,
                  polar_angle(first.tip_ends[1]) - polar_angle(first.tip_ends[0]))
    n_root = steps(first.root_radius, polar_angle(first.fillet_minus[0]) - first.space_before)
    edge = outline.modifications.tip_edge     # the rest of a rounding turns up to 45°
    n_rounding = 2 if edge is None or edge.angle is not None else steps(edge.radius, 0.25 * np.pi)

    k = gear.teeth if teeth is None or teeth >= gear.teeth else teeth
    turns = (np.arange(gear.teeth) if k == gear.teeth else np.arange(k) - k // 2) * outline.pitch
    rings = []
    for height in z:
        tooth = outline.section(u, float(height)).points(n_tip, n_root, n_rounding)[:-1]
        rings.append(np.concatenate([tooth @ rotation([0, 0, 1], a).T for a in turns]))
    vertices = np.concatenate(rings)
    n, closed = len(rings[0]), k == gear.teeth
    i = np.arange(n if closed else n - 1)
    j = (i + 1) % n
    quads = [(s * n + i, s * n + j, (s + 1) * n + j, (s + 1) * n + i) for s in range(len(z) - 1)]
    faces = np.concatenate([np.concatenate([np.column_stack([a, b, c]), np.column_stack([a, c, d])])
                            for a, b, c, d in quads])
    return vertices, faces


def _within_sag(flank, u: np.ndarray, half: float) -> np.ndarray:
    """The profile parameters `u` with midpoints added (up to 6 times) where the mid-face
    profile strays more than `half` (mm) from the chord between neighbours (a tip
    rounding's tight curve)."""
    for _ in range(6):
        v = np.zeros_like(u)
        points = np.stack(flank.point(u, v), -1)
        mid = 0.5 * (u[1:] + u[:-1])
        middle = np.stack(flank.point(mid, np.zeros_like(mid)), -1)
        sag = np.linalg.norm(middle - 0.5 * (points[1:] + points[:-1]), axis=-1)
        if not (sag > half).any():
            break
        u = np.union1d(u, mid[sag > half])
    return u


def collision_body(vertices: np.ndarray, faces: np.ndarray):
    """An fcl collision object of a triangle mesh (its BVH built once), to be placed by
    `place` before each query."""
    import fcl

    model = fcl.BVHModel()
    model.beginModel(len(vertices), len(faces))
    model.addSubModel(np.asarray(vertices, float), np.asarray(faces, np.int32))
    model.endModel()
    return fcl.CollisionObject(model, fcl.Transform())


def place(body, R: np.ndarray, origin: np.ndarray):
    """Place a collision body by world = R·local + origin (returns it)."""
    import fcl

    body.setTransform(fcl.Transform(np.asarray(R, float), np.asarray(origin, float)))
    return body


def interference(a, b, max_points: int = 50) -> Interference:
    """Overlap of two placed collision bodies (see `collision_body`, `place`)."""
    import fcl

    request = fcl.CollisionRequest(num_max_contacts=max_points, enable_contact=True)
    result = fcl.CollisionResult()
    fcl.collide(a, b, request, result)
    points = np.array([c.pos for c in result.contacts], float).reshape(-1, 3)
    return Interference(points)


def load_surface(path: str | Path, tolerance: float = 0.002) -> TriangleSurface:
    """An imported body: an STL as it is, or a STEP tessellated to `tolerance` (mm)."""
    import trimesh

    path = Path(path)
    suffix = path.suffix.lower()
    if suffix == ".stl":
        mesh = trimesh.load_mesh(path, file_type="stl")
        return TriangleSurface(mesh.vertices, mesh.faces)
    if suffix in (".step", ".stp"):
        from .cad import read_step, tessellate

        triangles = tessellate(read_step(path), tolerance)
        return TriangleSurface(triangles.vertices, triangles.faces)
    raise ValueError(f"{path.name}: a body must be an .stl, .step or .stp file")
