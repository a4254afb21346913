"""The structural operator of a contact grid: how far the teeth give along the contact normal
under the pressure on the grid's cells (u = B·p), from the members' tooth compliance
(contact.compliance: the slices' profile compliance, coupled along the face as a Pasternak
line with free-end layers; a helical tooth's wall), which the pressure solver adds to the
half-space's own (pressure.Grid, `structure`); and where the cells' loads sit along each
member's face, for the line load. Units: mm, N, MPa."""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np

from ..analytic.hats import grid_hats

if TYPE_CHECKING:
    from ..analytic.tooth_wall import ToothWall


class FaceCoupling:
    """The Pasternak line along one member's face, [start, end] (mm, along its axis), on
    `nodes` equally spaced nodes (hat functions): the flexibility G (mm per N, per unit
    slice compliance) taking the nodes' loads Q to their deflections, w = G·Q, from the
    finite-volume form of (λ_e²·w')' = w - c·q with free ends (zero flux through them):
    (V + K)·w = Q, V the nodes' widths (half at the ends), K the links' coupling λ_e²/step
    between neighbours. Without an end layer λ_e = λ: under a uniform line load q every node
    deflects c·q, under a point load it approaches the continuous Green's function
    cosh(z_</λ)·cosh((L - z_>)/λ)/(λ·sinh(L/λ)). end_layer ℓ (mm) > 0: the coupling fades
    to nothing at the free end faces, λ_e² = λ²·(1 - exp(-d0/ℓ))·(1 - exp(-d1/ℓ)) (d0, d1
    the distances to the two ends; each link takes its exact mean), Reissner's free-edge
    layer of a plate's twisting moment (see the module); a uniform load still deflects
    every node by c·q."""

    def __init__(self, start: float, end: float, coupling_length: float, nodes: int,
                 end_layer: float = 0.0):
        self.nodes = np.linspace(start, end, nodes)
        step = (end - start) / (nodes - 1)
        widths = np.full(nodes, step)
        widths[[0, -1]] = 0.5 * step
        self.widths = widths
        links = coupling_length ** 2 / step * end_layer_share(self.nodes, end_layer)
        K = np.diag(np.concatenate([links, [0.0]]) + np.concatenate([[0.0], links]))
        K -= np.diag(links, 1) + np.diag(links, -1)
        self.flexibility = np.linalg.inv(np.diag(widths) + K)


def end_layer_share(nodes: np.ndarray, layer: float) -> np.ndarray:
    """The mean over each link between the increasing `nodes` (mm) of
    (1 - exp(-d0/ℓ))·(1 - exp(-d1/ℓ)), d0 and d1 the distances to the first and the last
    node, ℓ = `layer` (mm; 0: ones): the share of the Pasternak coupling a link keeps near
    free ends (FaceCoupling)."""
    a, b = nodes[:-1], nodes[1:]
    if layer <= 0.0:
        return np.ones(len(a))
    start, end = nodes[0], nodes[-1]

    def mean_exp(d_a, d_b):                  # the mean of exp(-d/ℓ), d linear from d_a to d_b
        return layer * (np.exp(-d_a / layer) - np.exp(-d_b / layer)) / (d_b - d_a)

    return (1.0 - mean_exp(a - start, b - start) - mean_exp(end - b, end - a)
            + math.exp(-(end - start) / layer))


#: nodes per coupling length along the face, and their fewest and most
NODES_PER_LENGTH, FEWEST_NODES, MOST_NODES = 4.0, 21, 241
#: nodes per end layer (FaceCoupling): a 1 mm patch at a 40 mm face's end deflects within
#: 1 % of the converged line's with the nodes half a layer apart
NODES_PER_LAYER = 2.0


def end_layer(half_thickness: float) -> float:
    """The free-end layer ℓ (mm) of a tooth's face coupling (FaceCoupling): Reissner's
    boundary layer of a plate's twisting moment at a free edge, t/sqrt(10) for a plate t
    thick, with t the tooth's thickness at the load, 2 × half_thickness (mm)."""
    return 2.0 * half_thickness / math.sqrt(10.0)


class MemberLoading:
    """One member's side of a contact grid: the cells' face positions z (mm, along its face)
    and load radii (mm), the share of a load along the contact normal that bends the slices
    (`share`, the normal's part in the slice's plane squared), the length of face a cell
    spans (`extent`, mm), the member's profile compliance (`radii` (mm) and `matrix`
    (mm²/N per unit width) of its ToothCompliance) and its face coupling. A cell's load
    (times sqrt(share)) goes to the (radius × face) nodes by hat weights; the nodes deflect
    by matrix·Q·G (profile compliance across, face coupling along), read back at the cells
    with the same weights (times sqrt(share)). With a `wall` (the tooth's ToothWall and the
    cells' heights on it, mm: ToothCompliance.wall_heights) the load's axial part (times
    sqrt(1 - share)) goes likewise to the wall's (height × face) nodes, which deflect by
    its matrix."""

    def __init__(self, z: np.ndarray, radius: np.ndarray, share: np.ndarray, extent: float,
                 radii: np.ndarray, matrix: np.ndarray, coupling: FaceCoupling,
                 root: np.ndarray | None = None, turn: float = 0.0,
                 wall: tuple[ToothWall, np.ndarray] | None = None):
        self.z, self.radius, self.share, self.extent = z, radius, share, extent
        self.radii, self.matrix, self.coupling = radii, matrix, coupling
        #: (cells, 3 + FLEXURE_PER_NODE per flexure node): a unit normal load at each
        #: cell as its tooth's root chord hands it to the gear body, in plane
        #: (ToothCompliance.root_loads) and out of it (flexure_loads); None where the
        #: body's coupling of the teeth is left out
        self.root = root
        #: the turn of the tooth's root chord along the face (rad/mm, counter-clockwise in
        #: the tooth's frame of root_loads): where each flexure node meets the rim
        self.turn = turn
        nodes, weights = grid_hats(radii, coupling.nodes, radius, z)
        # the radial nodes in use: first, first + 1, ... last
        first, last = (int(n) // len(coupling.nodes) for n in (nodes.min(), nodes.max()))
        self.profile = matrix[first:last + 1, first:last + 1]
        self.shape = (len(self.profile), len(coupling.nodes))
        #: each cell's four slice nodes (row-major in the shape; with a wall, then its four
        #: wall nodes: cells × 4 or 8) and its weights on them: the nodes' deflections read
        #: at the cells; their transpose spreads the cells' loads to the nodes
        self.nodes = nodes - first * self.shape[1]
        self.weights = weights * np.sqrt(share)[:, None]
        #: the wall's compliance between the wall nodes the cells load (mm/N), or None
        self.wall = None
        #: the nodes: the slices' (row-major in the shape), then the wall's
        self.size = self.shape[0] * self.shape[1]
        if wall is not None:
            teeth_wall, height = wall
            wall_nodes, wall_weights = teeth_wall.spread(height, z)
            used, index = np.unique(wall_nodes, return_inverse=True)
            self.wall = teeth_wall.matrix[np.ix_(used, used)]
            self.nodes = np.concatenate([self.nodes, self.size + index.reshape(wall_nodes.shape)],
                                        axis=1)
            lean = np.sqrt(np.maximum(1.0 - share, 0.0))      # the load's axial part
            self.weights = np.concatenate([self.weights, wall_weights * lean[:, None]], axis=1)
            self.size += len(used)

    def nodes_deflection(self, node_loads: np.ndarray) -> np.ndarray:
        """The nodes' deflections (mm, flat) under their loads (N, flat): the slices' by
        profile compliance across and face coupling along, then the wall's."""
        slices = self.shape[0] * self.shape[1]
        bent = (self.profile @ node_loads[:slices].reshape(self.shape)
                @ self.coupling.flexibility).ravel()
        return bent if self.wall is None else np.concatenate([bent, self.wall @ node_loads[slices:]])


class StructureOperator:
    """u = B·p on a contact's grid: both members' teeth bending under the pressure p (MPa on
    the grid's cells of area `cell` mm²), u (mm) along the contact normal. Symmetric and
    positive semi-definite, so the constrained conjugate gradients take it as they take
    the half-space's influence."""

    def __init__(self, members: list[MemberLoading], shape: tuple[int, int], cell: float,
                 active: np.ndarray, reference: tuple, gather=None, roots=None):
        from scipy.sparse import csr_matrix

        self.members, self.shape, self.cell = members, shape, cell
        self.active = np.flatnonzero(active.ravel())
        #: ((depth mm, E MPa, nu) per member): the contact's compression is measured to
        #: the teeth's centre lines (influence.InfluenceOperator), where the slices' bending
        #: is measured from
        self.reference = reference
        # both members' node weights on the whole grid (no rows off the material; `gather`
        # where a larger grid's are given): one product each way per application (the
        # spread its transpose, a CSC view made once: as fast as a stored CSR transpose,
        # 0.20 against 0.23 ms on 37,000 cells)
        sizes = [m.size for m in members]
        if gather is None:
            offsets = np.cumsum([0] + sizes[:-1])
            nodes = np.concatenate([m.nodes + o for m, o in zip(members, offsets)], axis=1)
            weights = np.concatenate([m.weights for m in members], axis=1)
            counts = np.zeros(int(np.prod(shape)) + 1, dtype=np.int64)
            counts[self.active + 1] = nodes.shape[1]
            gather = csr_matrix((weights.ravel(), nodes.ravel(), np.cumsum(counts)),
                                shape=(len(counts) - 1, sum(sizes)))
        self._gather, self._spread = gather, gather.T
        self._split = np.cumsum(sizes)[:-1]
        if roots is None and any(m.root is not None for m in members):
            width = max(m.root.shape[1] for m in members if m.root is not None)
            roots = np.zeros((len(self.active), width * len(members)))
            for i, m in enumerate(members):
                if m.root is not None:
                    roots[:, width * i:width * i + m.root.shape[1]] = m.root
        #: the material cells' loads as the teeth's root chords take them ((active cells,
        #: R per member), dense: see MemberLoading.root): the gear bodies' coupling of the
        #: contacts (PairCompliance.body_coupling); None without it
        self.roots = roots

    def window(self, rows: slice, cols: slice) -> StructureOperator:
        """The operator on the part [rows, cols] of the grid (for loads there alone)."""
        return self._part((rows, cols), self.cell)

    def coarsened(self, steps: tuple[int, int]) -> StructureOperator:
        """The operator on the grid taken every steps[0]-th cell along axis 0 and every
        steps[1]-th along axis 1 (cells steps[0]·steps[1] times larger), for a coarse first
        solve."""
        s0, s1 = steps
        return self._part((slice(None, None, s0), slice(None, None, s1)), self.cell * s0 * s1)

    def _part(self, index: tuple[slice, slice], cell: float) -> StructureOperator:
        """The operator on the grid's cells [index], of area `cell` (mm²): the grid's own
        node weights there."""
        cells = np.arange(self.shape[0] * self.shape[1]).reshape(self.shape)[index]
        row = np.full(self.shape[0] * self.shape[1], -1)       # each material cell's root row
        row[self.active] = np.arange(len(self.active))
        rows = row[cells.ravel()]
        return StructureOperator(self.members, cells.shape, cell,
                                 (rows >= 0).reshape(cells.shape), self.reference,
                                 self._gather[cells.ravel()],
                                 None if self.roots is None else self.roots[rows[rows >= 0]])

    def __call__(self, p: np.ndarray) -> np.ndarray:
        loads = self._spread @ (np.asarray(p, float).ravel() * self.cell)
        deflections = np.concatenate([m.nodes_deflection(q) for m, q in
                                      zip(self.members, np.split(loads, self._split))])
        return (self._gather @ deflections).reshape(self.shape)

    def root_resultants(self, p: np.ndarray) -> np.ndarray:
        """(members, R): the loads the pressure p (MPa) on the grid hands each member's
        gear body at its tooth's root chord (N: radial, tangential; N·mm: moment; then per
        flexure node and part N: axial, N·mm: the moments; see MemberLoading.root)."""
        return (np.asarray(p, float).ravel()[self.active] @ self.roots * self.cell).reshape(
            len(self.members), -1)

    def root_deflection(self, moves: np.ndarray) -> np.ndarray:
        """The grid's deflection (mm along the contact normal) where each member's tooth
        root chord moves by `moves` ((members, R): mm, mm, rad in plane; mm, rad, rad per
        flexure node and part) as a rigid body."""
        out = np.zeros(self.shape[0] * self.shape[1])
        out[self.active] = self.roots @ np.asarray(moves, float).ravel()
        return out.reshape(self.shape)

    def face_loads(self) -> tuple[FaceLoad, ...]:
        """Where the grid's cells sit along each member's face and at what load radius (the
        members in order); of a whole grid's operator (a window or a coarsened grid keeps
        the whole grid's members)."""
        material = np.zeros(self.shape[0] * self.shape[1], bool)
        material[self.active] = True
        material = material.reshape(self.shape)
        loads = []
        for m in self.members:
            order = np.argsort(m.z, kind="stable")
            loads.append(FaceLoad(material, order, m.z[order] - 0.5 * m.extent, m.extent,
                                  self.cell, m.radius[order]))
        return tuple(loads)


@dataclass(frozen=True)
class FaceLoad:
    """Where a contact grid's cells sit along a member's face, for the load per unit face
    width under a pressure on the grid. Each cell's load is spread evenly over the length
    of face it spans (`extent`, mm), from its start (its face position less half the
    extent, mm along the member's axis).

    material: the grid's cells on material (the grid's shape);
    order: the material cells (in the grid's order) by increasing start;
    starts: their starts in that order (mm);
    extent: the length of face a cell spans (mm); cell: the cells' area (mm²);
    radius: their load radii on the member's tooth in that order (mm).
    A few arrays: a worker process hands it back with the contact's solution."""

    material: np.ndarray
    order: np.ndarray
    starts: np.ndarray
    extent: float
    cell: float
    radius: np.ndarray

    def line_load(self, p: np.ndarray, edges: np.ndarray, moment: bool = False) -> np.ndarray:
        """The mean load per unit face width (N/mm) on the strips between `edges` (mm,
        increasing, along the member's axis) under the pressure p (MPa) on the grid; with
        `moment`, each cell's load times its load radius (N·mm/mm).

        The load below a point t is the sum of L_i·clip((t - a_i)/w, 0, 1) over the cells
        (L their loads, a their starts, w the extent): t·S0 - S1 over the cells starting
        below t, less the same below t - w, over w (S0, S1 the cumulative sums of L and
        L·a in the order of the starts)."""
        loads = np.asarray(p, float)[self.material][self.order] * self.cell
        if moment:
            loads = loads * self.radius
        S0 = np.concatenate([[0.0], np.cumsum(loads)])
        S1 = np.concatenate([[0.0], np.cumsum(loads * self.starts)])

        def ramp(t):
            k = np.searchsorted(self.starts, t)
            return t * S0[k] - S1[k]

        edges = np.asarray(edges, float)
        below = (ramp(edges) - ramp(edges - self.extent)) / self.extent
        return np.diff(below) / np.diff(edges)
