"""Triangle meshes: interference between positioned bodies (python-fcl), and imported
bodies as surfaces to measure separation on.

The separation search sees only the two active flanks; a tooth tip digging into the mate's
root, or a neighbouring tooth touching its back flank, is found here instead: the bodies are
tessellated from their B-spline solids, placed by their frames, and collided as BVH models.

An imported body (a user's STL, or STEP tessellated here) is a `TriangleSurface`: the signed
distance of any point to it is the distance to its closest triangle (negative inside), the
triangle found among the k nearest of points sampled over every triangle at least as
densely as the typical edge (so long, thin triangles are found as readily as small ones).
Units: mm.
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import cached_property
from pathlib import Path

import numpy as np


@dataclass(frozen=True)
class Interference:
    """Where two placed meshes overlap: contact points (mm, world) and how many there are."""

    points: np.ndarray

    @property
    def found(self) -> bool:
        return len(self.points) > 0


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


class TriangleSurface:
    """A closed triangle mesh (vertices (n, 3), faces (m, 3), outward winding) to measure
    signed distances to."""

    def __init__(self, vertices: np.ndarray, faces: np.ndarray):
        import trimesh

        self.mesh = trimesh.Trimesh(np.asarray(vertices, float), np.asarray(faces, np.int64),
                                    process=True)
        if len(self.mesh.faces) == 0:
            raise ValueError("the mesh has no triangles")
        self.vertices, self.faces = self.mesh.vertices, self.mesh.faces
        self.triangles = self.mesh.triangles

    def turned(self, angle: float) -> "TriangleSurface":
        """The surface turned about its z axis by `angle` (rad)."""
        c, s = np.cos(angle), np.sin(angle)
        return TriangleSurface(self.vertices @ np.array([[c, s, 0.0], [-s, c, 0.0], [0.0, 0.0, 1.0]]),
                               self.faces)

    @cached_property
    def _samples(self):
        """A KD-tree of points over every triangle and the triangle of each point, and the
        farthest any point of a triangle lies from its nearest sample (mm). Each triangle
        is covered by a grid of cells h × h along and across its longest edge (h: the side
        of a square of the mean triangle area), one sample per cell, moved onto the
        triangle: a long thin facet gets a row of samples along it, a small one one."""
        import trimesh

        tri = self.triangles
        h = float(np.sqrt(2.0 * self.mesh.area / len(tri)))
        edges = np.roll(tri, -1, axis=1) - tri                        # edge k: vertex k -> k+1
        lengths = np.linalg.norm(edges, axis=-1)
        k = np.argmax(lengths, axis=1)
        rows = np.arange(len(tri))
        origin, along = tri[rows, k], edges[rows, k]
        long = lengths[rows, k]
        along = along / long[:, None]
        apex = tri[rows, (k + 2) % 3] - origin
        across = apex - np.einsum("ij,ij->i", apex, along)[:, None] * along
        width = np.linalg.norm(across, axis=-1)
        across = across / np.maximum(width, 1e-300)[:, None]
        nu = np.clip(np.ceil(long / h), 1, 4096).astype(int)
        nv = np.clip(np.ceil(width / h), 1, 4096).astype(int)
        points, owner = [], []
        for a, b in {(int(x), int(y)) for x, y in zip(nu, nv)}:
            which = np.flatnonzero((nu == a) & (nv == b))
            i, j = (g.ravel() for g in np.meshgrid((np.arange(a) + 0.5) / a,
                                                   (np.arange(b) + 0.5) / b, indexing="ij"))
            grid = (origin[which, None, :] + (i[None, :, None] * long[which, None, None]) * along[which, None, :]
                    + (j[None, :, None] * width[which, None, None]) * across[which, None, :])
            grid = trimesh.triangles.closest_point(np.repeat(tri[which], len(i), axis=0),
                                                   grid.reshape(-1, 3))
            points.append(grid)
            owner.append(np.repeat(which, len(i)))
        from scipy.spatial import cKDTree

        points, owner = np.concatenate(points), np.concatenate(owner)
        # the sampling radius: the farthest a corner or an edge's midpoint lies from its own
        # triangle's nearest sample (the points of a triangle farthest from the samples)
        probes = np.concatenate([tri, 0.5 * (tri + np.roll(tri, -1, axis=1))], axis=1)
        order = np.argsort(owner, kind="stable")
        first = np.searchsorted(owner[order], np.arange(len(tri)))
        count = np.bincount(owner, minlength=len(tri))
        radius = 0.0
        for c in np.unique(count):
            which = np.flatnonzero(count == c)
            own = points[order[first[which, None] + np.arange(c)]]           # (t, c, 3)
            gap = np.linalg.norm(probes[:, None, :, :][which] - own[:, :, None, :], axis=-1)
            radius = max(radius, float(gap.min(axis=1).max()))
        return cKDTree(points), owner, 1.05 * radius

    @cached_property
    def _edge_normals(self) -> np.ndarray:
        """Pseudo-normal of every unique edge: the sum of its two faces' normals."""
        mesh = self.mesh
        normals = np.zeros((len(mesh.edges_unique), 3))
        np.add.at(normals, mesh.faces_unique_edges.ravel(), np.repeat(mesh.face_normals, 3, axis=0))
        return normals

    def signed_distance(self, points: np.ndarray, k: int = 16, exact_within: float = np.inf):
        """(distance, closest point) of each point (..., 3): the distance to the surface,
        negative inside the body; exact for points within `exact_within` (mm) of it, and
        for points farther an upper bound of the distance (the nearest of k candidates). The sign is that of (point - closest) against the face
        normal, or, where the closest point is on an edge or a vertex, against the edge's or
        the vertex's angle-weighted pseudo-normal (Bærentzen & Aanæs, IEEE TVCG 11(3), 2005):
        a face normal alone misjudges points off sharp edges."""

        flat = np.asarray(points, float).reshape(-1, 3)
        distance, nearest, face = self._closest(flat, np.arange(len(flat)), k, exact_within)
        normal = self._pseudo_normals(face, nearest)
        sign = np.where(np.einsum("ij,ij->i", flat - nearest, normal) < 0.0, -1.0, 1.0)
        shape = np.shape(points)[:-1]
        return (sign * distance).reshape(shape), nearest.reshape(shape + (3,))

    def closest(self, points: np.ndarray, k: int = 16) -> tuple[np.ndarray, np.ndarray]:
        """The closest point on the surface to each point (n, 3), and the normal of the
        facet it lies on."""
        points = np.asarray(points, float).reshape(-1, 3)
        _, nearest, face = self._closest(points, np.arange(len(points)), k, np.inf)
        return nearest, self.mesh.face_normals[face]

    def _closest(self, points: np.ndarray, which: np.ndarray, k: int, exact_within: float):
        """Distance, closest point and face for points[which]: the best of the triangles of
        the k nearest samples, and again with 4k for the points whose k-th sample lies
        nearer than their distance plus the sampling radius (a closer triangle may hide
        there): exact."""
        import trimesh

        tree, owner, radius = self._samples
        k = min(k, tree.n)
        p = points[which]
        reach, index = tree.query(p, k=k, workers=-1)
        reach, index = reach.reshape(len(p), k), index.reshape(len(p), k)
        candidates = owner[index]
        repeated = np.repeat(p, k, axis=0)
        closest = trimesh.triangles.closest_point(self.triangles[candidates.ravel()], repeated)
        distance = np.linalg.norm(closest - repeated, axis=-1).reshape(-1, k)
        best = np.argmin(distance, axis=1)
        rows = np.arange(len(p))
        out = (distance[rows, best], closest.reshape(-1, k, 3)[rows, best], candidates[rows, best])
        unsure = (reach[:, -1] < out[0] + radius) & (out[0] < exact_within)
        if unsure.any() and k < tree.n:
            again = self._closest(p, np.flatnonzero(unsure), 4 * k, exact_within)
            for arr, new in zip(out, again):
                arr[unsure] = new
        return out

    def _pseudo_normals(self, face: np.ndarray, point: np.ndarray) -> np.ndarray:
        """The normal to judge the side by, at points on the given faces."""
        import trimesh

        mesh = self.mesh
        bary = trimesh.triangles.points_to_barycentric(self.triangles[face], point)
        zero = bary < 1e-9
        normal = mesh.face_normals[face].copy()
        on_edge = zero.sum(axis=1) == 1
        if on_edge.any():
            opposite = np.argmax(zero[on_edge], axis=1)           # the vertex off the edge
            edge = mesh.faces_unique_edges[face[on_edge], (opposite + 1) % 3]
            normal[on_edge] = self._edge_normals[edge]
        at_vertex = zero.sum(axis=1) >= 2
        if at_vertex.any():
            corner = np.argmin(zero[at_vertex], axis=1)           # the one nonzero weight
            normal[at_vertex] = mesh.vertex_normals[mesh.faces[face[at_vertex], corner]]
        return normal


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
