"""A helical tooth's own give under the axial part of its load: the tooth as a wall in its
radial-axial plane.

An involute helicoid's normal leans out of the transverse plane by the base helix angle
β_b, so sin β_b of each normal load pushes the tooth along the gear's axis. The transverse
slices (contact.compliance) carry the load's part in their plane, the gear body's flexure
(gear_body.flexure_green) the axial part from the root circle down; above the root the
tooth shears along its face like a wall. Its mid-surface, the height s along its centre
line from the root circle by the face position z, is taken in plane stress (the flanks are
free), as thick as the tooth at s (the slice's outline, 2·half(s)), held at the root
circle (the body's own move is the flexure's), free at the tip and at both face ends, and
loaded along z.

Solved by finite elements (scikit-fem: quadratic triangles, FE_REFINEMENT per node
spacing each way), its compliance is kept between loads spread by hat functions over a
grid of nodes (`heights` × `face`, about HEIGHT_SPANS spans over the tooth's height, as
many mm apart along the face): what a contact's cells hand it (contact.compliance,
MemberLoading) as they hand the slices their loads. The spread stands for the local part a
thin wall leaves out (its point load's logarithm), which the contact's half-space holds: on
the helical reference pair the mesh stiffness moves 0.15 % when the spread goes from 0.15
to 1.2 mm.

Checked against the closed form of a long wall in shear (a load q per mm spread along the
face at height s₀ moves the wall's middle by q·∫₀^s₀ ds/(G·t(s)), G the shear modulus)
and, on the helical reference pair of benchmarks/fe_helical_stiffness.py, against the 3D
FE's compliance under the load's axial part less its transverse part and the body's
flexure (tests/test_tooth_wall.py). Units: mm, N, MPa.
"""

from __future__ import annotations

import math

import numpy as np

from .hats import grid_hats

#: node spans over the tooth's height (root circle to tip along the centre line); the face's
#: nodes are as far apart
HEIGHT_SPANS = 6
#: finite elements (quadratic triangles, two per square) per node spacing each way: the
#: reference pair's wall compliance moves 0.3 % from 2 to 4
FE_REFINEMENT = 1
#: load cases per solve (bounds the memory of the dense right-hand sides)
SOLVE_COLUMNS = 256


class ToothWall:
    """The wall compliance of one tooth: `matrix` [i, j] (mm/N), the mean axial
    displacement under node i's hat of a unit axial force spread by node j's hat, nodes
    row-major over (`heights` (mm from the root circle along the centre line) ×
    `face` (mm from mid-face)).

    height: the tooth's profile as heights along its centre line (mm, increasing from 0 at
    the root circle to the tip) and `half` its half-thickness there (mm); face_width (mm);
    E (MPa), nu: the material."""

    def __init__(self, height: np.ndarray, half: np.ndarray, face_width: float, E: float,
                 nu: float, refinement: int = FE_REFINEMENT):
        from scipy.sparse import coo_matrix, diags
        from scipy.sparse.linalg import splu
        from skfem import Basis, BilinearForm, ElementTriP2, ElementVector, MeshTri, asm
        from skfem.helpers import ddot, dot, sym_grad, trace

        top = float(height[-1])
        spacing = top / HEIGHT_SPANS
        spans = max(1, math.ceil(face_width / spacing - 1e-9))
        self.heights = np.linspace(0.0, top, HEIGHT_SPANS + 1)
        self.face = np.linspace(-0.5 * face_width, 0.5 * face_width, spans + 1)
        mesh = MeshTri.init_tensor(_refined(self.face, refinement),
                                   _refined(self.heights, refinement))
        basis = Basis(mesh, ElementVector(ElementTriP2()))
        mu = E / (2.0 * (1.0 + nu))
        plane_stress_lambda = E * nu / (1.0 - nu ** 2)

        @BilinearForm
        def stiffness(u, v, w):
            t = 2.0 * np.interp(w.x[1], height, half)
            eu, ev = sym_grad(u), sym_grad(v)
            return t * (plane_stress_lambda * trace(eu) * trace(ev) + 2.0 * mu * ddot(eu, ev))

        @BilinearForm
        def mass(u, v, w):
            return dot(u, v)

        along, _ = basis.split_indices()          # the dofs of the displacement along z
        # each node's hat at the along-face dofs (quadratic triangles hold a bilinear hat
        # exactly, each triangle inside one node span), times the mass matrix: the nodal
        # forces of a load spread by the hat, scaled to a unit total
        nodes, weights = self.spread(basis.doflocs[1, along], basis.doflocs[0, along])
        hats = coo_matrix((weights.ravel(), (np.repeat(along, 4), nodes.ravel())),
                          shape=(basis.N, self.heights.size * self.face.size)).tocsc()
        forces = asm(mass, basis) @ hats
        forces = forces @ diags(1.0 / np.asarray(forces[along].sum(axis=0)).ravel())
        held = basis.get_dofs(lambda x: np.isclose(x[1], 0.0)).all()
        free = np.setdiff1d(np.arange(basis.N), held)
        forces = forces[free].tocsc()
        solve = splu(asm(stiffness, basis)[free][:, free].tocsc()).solve
        G = np.zeros((forces.shape[1], forces.shape[1]))
        for start in range(0, forces.shape[1], SOLVE_COLUMNS):
            block = slice(start, start + SOLVE_COLUMNS)
            G[:, block] = (forces.T @ solve(forces[:, block].toarray()))
        self.matrix = 0.5 * (G + G.T)

    def spread(self, height: np.ndarray, z: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """Loads at the heights (mm from the root circle along the centre line) and face
        positions z (mm from mid-face) on the wall's nodes: each load's four nodes (index in
        `matrix`, (n, 4)) and its weights on them ((n, 4), summing to 1)."""
        return grid_hats(self.heights, self.face, height, z)


def _refined(nodes: np.ndarray, refinement: int) -> np.ndarray:
    """Equally spaced nodes with `refinement` spans in each of theirs."""
    return np.linspace(nodes[0], nodes[-1], (len(nodes) - 1) * refinement + 1)

