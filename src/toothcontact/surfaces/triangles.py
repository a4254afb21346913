"""An imported body (a user's STL, or STEP tessellated by mesh.load_surface) as a surface to
measure separation on: a `TriangleSurface`. The signed distance of any point to it is the
distance to its closest triangle (negative inside), the triangle found among the k nearest
of points sampled over every triangle at least as densely as the typical edge (so long,
thin triangles are found as readily as small ones).
The facets are chords of the smooth surface they stand for and lie up to the chordal error
inside or outside it; the smooth surface is put back by Phong tessellation with shape factor
1/2 (Boubekeur & Alexa, ACM TOG 27(5), 2008): a point p on a facet goes to
p + 1/2·Σ w_i ((P_i - p)·n_i) n_i (w_i its barycentric weights, P_i the corners, n_i the
surface normals there), which is exact to second order (a quadric through the corners with
those normals), so distances to it carry the facets' third-order error only, not their sag.
The corner normals come from a cubic fitted to each vertex's neighbours on the same side of
every crease (facets meeting at more than SMOOTH_ANGLE are different faces of the body: a
tooth's flank and its tip land, an end face). Units: mm.
"""

from __future__ import annotations

from functools import cached_property

import numpy as np

#: facets meeting at more than this (rad) are on two faces of the body, across a crease
SMOOTH_ANGLE = np.radians(20.0)


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

    def turned(self, angle: float) -> TriangleSurface:
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
            grid = (origin[which, None, :]
                    + (i[None, :, None] * long[which, None, None]) * along[which, None, :]
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

    def signed_distance(self, points: np.ndarray, k: int = 16, exact_within: float = np.inf,
                        smooth: bool = False):
        """(distance, closest point, its facet) of each point (..., 3): the distance to the facets
        (`smooth`: to the smooth surface they stand for, see the module docstring), negative
        inside the body; exact for points within `exact_within` (mm) of it, and for points
        farther an upper bound of the distance (the nearest of k candidates). The sign is
        that of (point - closest) against the face normal, or, where the closest point is on
        an edge or a vertex, against the edge's or the vertex's angle-weighted pseudo-normal
        (Bærentzen & Aanæs, IEEE TVCG 11(3), 2005): a face normal alone misjudges points off
        sharp edges. A point within the facets' sag of the smooth surface takes its side of
        that surface (against the normal interpolated there)."""

        flat = np.asarray(points, float).reshape(-1, 3)
        distance, nearest, face = self._closest(flat, np.arange(len(flat)), k, exact_within)
        normal = self._pseudo_normals(face, nearest)
        sign = np.where(np.einsum("ij,ij->i", flat - nearest, normal) < 0.0, -1.0, 1.0)
        if smooth:
            lifted, smooth_normal = self.lift(face, nearest)
            offset = flat - lifted
            close = distance <= 2.0 * np.linalg.norm(lifted - nearest, axis=-1)
            sign[close] = np.where(np.einsum("ij,ij->i", offset[close], smooth_normal[close])
                                   < 0.0, -1.0, 1.0)
            distance, nearest = np.linalg.norm(offset, axis=-1), lifted
        shape = np.shape(points)[:-1]
        return (sign * distance).reshape(shape), nearest.reshape(shape + (3,)), face.reshape(shape)

    @cached_property
    def parts(self) -> np.ndarray:
        """(m,): the face of the body each facet belongs to (a label): facets connected
        across edges of less than SMOOTH_ANGLE."""
        from scipy.sparse import coo_matrix
        from scipy.sparse.csgraph import connected_components

        mesh, m = self.mesh, len(self.faces)
        pairs = mesh.face_adjacency[mesh.face_adjacency_angles < SMOOTH_ANGLE]
        graph = coo_matrix((np.ones(len(pairs)), (pairs[:, 0], pairs[:, 1])), shape=(m, m))
        return connected_components(graph, directed=False)[1]

    @cached_property
    def _slots(self):
        """The vertices as seen from each face of the body (a vertex on a crease is one slot
        per side): the slot of every facet corner (m, 3), each slot's vertex, and the slots'
        adjacency (sparse, along the facets' edges, within one face of the body)."""
        from scipy.sparse import coo_matrix

        part, m = self.parts, len(self.faces)
        key = self.faces.astype(np.int64) * (int(part.max()) + 1) + part[:, None]
        _, slot = np.unique(key.ravel(), return_inverse=True)
        slot = slot.reshape(m, 3)
        count = int(slot.max()) + 1
        vertex = np.zeros(count, np.int64)
        vertex[slot.ravel()] = self.faces.ravel()
        a, b = slot.ravel(), np.roll(slot, -1, axis=1).ravel()
        adjacency = coo_matrix((np.ones(2 * len(a)), (np.concatenate([a, b]), np.concatenate([b, a]))),
                               shape=(count, count)).tocsr()
        adjacency.data[:] = 1.0
        return slot, vertex, adjacency

    @cached_property
    def _slot_normals(self) -> np.ndarray:
        """Each slot's normal as far as known: the angle-weighted mean of its facets'
        normals (refined on demand by corner_normals)."""
        slot, _, adjacency = self._slots
        weighted = (self.mesh.face_normals[:, None, :] * self.mesh.face_angles[:, :, None]).reshape(-1, 3)
        sums = np.stack([np.bincount(slot.ravel(), weighted[:, i], minlength=adjacency.shape[0])
                         for i in range(3)], axis=-1)
        return sums / np.linalg.norm(sums, axis=-1, keepdims=True)

    @cached_property
    def _fitted(self) -> np.ndarray:
        return np.zeros(self._slots[2].shape[0], bool)

    def corner_normals(self, faces: np.ndarray) -> np.ndarray:
        """(n, 3, 3): the surface normal at the corners of the given facets, from a cubic
        fitted by least squares to the neighbours (two rings of edges, within the same face
        of the body) of each corner's vertex: exact to second order on either side of a
        crease and on uneven facets, where the angle-weighted mean of the facets' normals
        round a vertex is not (it is the normal half a facet inward at a crease). Computed
        for the corners asked for, and kept."""
        slot = self._slots[0][faces]
        need = np.unique(slot[~self._fitted[slot]])
        if need.size:
            self._fit_normals(need)
        return self._slot_normals[slot]

    def _fit_normals(self, which: np.ndarray) -> None:
        """Fit a cubic h(x, y) = d x + e y + (quadratic) + (cubic) over each slot's two-ring
        (x, y in the tangent plane of its angle-weighted normal, h along it; the cubic terms
        keep a curvature that changes across the ring, as where a flank meets its fillet,
        from tilting the fit; each neighbour weighs 1 / (0.1 + its distance²), distances in
        the ring's mean distance: the nearer rings tell the slope at the vertex best); the
        normal is then that one tilted by the gradient (d, e); the least-norm fit where the
        neighbours leave terms open."""
        _, vertex, adjacency = self._slots
        normals = self._slot_normals
        near = adjacency[which]
        ring = ((near + near @ adjacency) > 0).tocoo()
        centre, other = which[ring.row], ring.col
        keep = other != centre
        owner, centre, other = ring.row[keep], centre[keep], other[keep]
        n = normals[centre]
        helper = np.where(np.abs(n[:, 0:1]) < 0.9, [[1.0, 0.0, 0.0]], [[0.0, 1.0, 0.0]])
        t1 = np.cross(n, helper)
        t1 /= np.linalg.norm(t1, axis=-1, keepdims=True)
        t2 = np.cross(n, t1)
        rel = self.vertices[vertex[other]] - self.vertices[vertex[centre]]
        size = np.bincount(owner, np.linalg.norm(rel, axis=-1), minlength=len(which))
        size /= np.maximum(np.bincount(owner, minlength=len(which)), 1)
        scale = np.maximum(size, 1e-12)[owner]
        x, y = (rel * t1).sum(-1) / scale, (rel * t2).sum(-1) / scale
        h = (rel * n).sum(-1) / scale
        phi = np.stack([x, y, x * x, x * y, y * y, x ** 3, x * x * y, x * y * y, y ** 3], -1)
        terms = phi.shape[1]
        weight = 1.0 / (x * x + y * y + 0.1)
        M = np.zeros((len(which), terms, terms))
        r = np.zeros((len(which), terms))
        for i in range(terms):
            r[:, i] = np.bincount(owner, weight * phi[:, i] * h, minlength=len(which))
            for j in range(i, terms):
                M[:, i, j] = M[:, j, i] = np.bincount(owner, weight * phi[:, i] * phi[:, j],
                                                      minlength=len(which))
        # equilibrated (the terms' sizes differ by the facets' aspect ratio)
        D = np.sqrt(np.maximum(np.einsum("ijj->ij", M), 1e-300))
        M, r = M / D[:, :, None] / D[:, None, :], r / D
        # least norm where the neighbours leave a term open (a ruled flank's strips: only
        # two positions along the face, so x and x² are one term there)
        ok = np.bincount(owner, minlength=len(which)) >= 3
        fitted = normals[which].copy()
        if ok.any():
            coef = np.einsum("ijk,ik->ij", np.linalg.pinv(M[ok], rcond=1e-9), r[ok]) / D[ok]
            first = np.searchsorted(owner, np.flatnonzero(ok))
            n0, a1, a2 = normals[which[ok]], t1[first], t2[first]
            tilted = n0 - coef[:, 0:1] * a1 - coef[:, 1:2] * a2
            fitted[ok] = tilted / np.linalg.norm(tilted, axis=-1, keepdims=True)
        normals[which] = fitted
        self._fitted[which] = True

    def lift(self, face: np.ndarray, point: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """Points (n, 3) on the given facets (n,) put onto the smooth surface (Phong
        tessellation, shape factor 1/2), and the unit normal interpolated there."""
        import trimesh

        corners, normals = self.triangles[face], self.corner_normals(face)
        bary = trimesh.triangles.points_to_barycentric(corners, point)
        return self.lift_barycentric(corners, normals, bary)

    @staticmethod
    def lift_barycentric(corners: np.ndarray, normals: np.ndarray, bary: np.ndarray):
        """The Phong lift of the points with barycentric weights `bary` (n, 3) on facets
        with `corners` and corner `normals` (n, 3, 3), and the unit normal there."""
        point = np.einsum("ij,ijk->ik", bary, corners)
        height = np.einsum("ijk,ijk->ij", corners - point[:, None, :], normals)
        lifted = point + 0.5 * np.einsum("ij,ij,ijk->ik", bary, height, normals)
        normal = np.einsum("ij,ijk->ik", bary, normals)
        return lifted, normal / np.linalg.norm(normal, axis=-1, keepdims=True)

    def closest(self, points: np.ndarray, k: int = 16) -> tuple[np.ndarray, np.ndarray]:
        """The closest point on the surface to each point (n, 3), and the normal of the
        facet it lies on."""
        points = np.asarray(points, float).reshape(-1, 3)
        _, nearest, face = self._closest(points, np.arange(len(points)), k, np.inf)
        return nearest, self.mesh.face_normals[face]

    def sections(self, faces: np.ndarray, heights: np.ndarray):
        """Where the planes z = heights (sorted, mm) cut the edges of the given facets, on the
        smooth surface: (points (n, 3), unit normals (n, 3), index of each point's plane
        (n,)), one point per edge and plane (an edge lying in a plane is left out)."""
        tri, normals = self.triangles[faces], self.corner_normals(faces)
        start, end = np.array([0, 1, 2]), np.array([1, 2, 0])
        vertex = self.faces[faces]
        # each edge once: the first facet that has it
        key = np.sort(np.stack([vertex[:, start], vertex[:, end]], -1), axis=-1).reshape(-1, 2)
        code, first = np.unique(key[:, 0].astype(np.int64) * len(self.vertices) + key[:, 1],
                                return_index=True)
        facet, corner = np.divmod(first, 3)
        a, b = tri[facet, corner], tri[facet, (corner + 1) % 3]
        low, high = np.minimum(a[:, 2], b[:, 2]), np.maximum(a[:, 2], b[:, 2])
        lo, hi = np.searchsorted(heights, low, "left"), np.searchsorted(heights, high, "left")
        count = hi - lo
        edge = np.repeat(np.arange(len(first)), count)
        plane = np.repeat(lo - np.cumsum(count) + count, count) + np.arange(len(edge))
        facet, corner = facet[edge], corner[edge]
        t = (heights[plane] - a[edge, 2]) / (b[edge, 2] - a[edge, 2])
        bary = np.zeros((len(edge), 3))
        rows = np.arange(len(edge))
        bary[rows, corner] = 1.0 - t
        bary[rows, (corner + 1) % 3] = t
        points, normal = self.lift_barycentric(tri[facet], normals[facet], bary)
        # on a crease two faces of the body meet, each lifting the edge along its own
        # normal: the crease's point is the one at both faces' heights (each face's lift
        # along its normal), off the chord square to it
        codes, across = self._crease_edges
        at = np.minimum(np.searchsorted(codes, code[edge]), len(codes) - 1)
        on = np.flatnonzero(codes[at] == code[edge])
        if on.size:
            other = np.where(across[at[on], 0] == faces[facet[on]], across[at[on], 1],
                             across[at[on], 0])
            chord = np.einsum("ij,ijk->ik", bary[on], tri[facet[on]])
            ends = np.stack([self.faces[faces[facet[on]], corner[on]],
                             self.faces[faces[facet[on]], (corner[on] + 1) % 3]], -1)
            mine = np.stack([1.0 - t[on], t[on]], -1)
            theirs = np.zeros((on.size, 3))
            for k in range(3):
                for e in range(2):
                    theirs[:, k] += np.where(self.faces[other, k] == ends[:, e], mine[:, e], 0.0)
            lifted_b, normal_b = self.lift_barycentric(self.triangles[other],
                                                       self.corner_normals(other), theirs)
            normal_a = normal[on]
            h_a = np.einsum("ij,ij->i", points[on] - chord, normal_a)
            h_b = np.einsum("ij,ij->i", lifted_b - chord, normal_b)
            c = np.einsum("ij,ij->i", normal_a, normal_b)
            a = (h_a - c * h_b) / (1.0 - c * c)
            b = (h_b - c * h_a) / (1.0 - c * c)
            points[on] = chord + a[:, None] * normal_a + b[:, None] * normal_b
        return points, normal, plane

    @cached_property
    def _crease_edges(self) -> tuple[np.ndarray, np.ndarray]:
        """The edges between two faces of the body (facets at SMOOTH_ANGLE or more): their
        codes (v_low * n + v_high, sorted) and the two facets of each."""
        mesh, n = self.mesh, len(self.vertices)
        sharp = mesh.face_adjacency_angles >= SMOOTH_ANGLE
        pairs = np.sort(mesh.face_adjacency_edges[sharp], axis=1).astype(np.int64)
        codes = pairs[:, 0] * n + pairs[:, 1]
        order = np.argsort(codes)
        return codes[order], mesh.face_adjacency[sharp][order]

    def _closest(self, points: np.ndarray, which: np.ndarray, k: int, exact_within: float):
        """Distance, closest point and face for points[which]: the best of the triangles of
        the k nearest samples, and again with 4k for the points whose k-th sample lies
        nearer than their distance plus the sampling radius (a closer triangle may hide
        there): exact."""
        import trimesh

        tree, owner, radius = self._samples
        k = min(k, tree.n)
        p = points[which]
        # threads pay off on large queries only (starting them costs more on small ones)
        reach, index = tree.query(p, k=k, workers=-1 if len(p) > 20000 else 1)
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
