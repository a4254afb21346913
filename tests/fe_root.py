"""Independent finite-element reference of the tooth root stress: the whole gear's exact
transverse section (tests/fe_tooth.py: generated fillets, flanks, tip arcs; bore held) in
plane strain with quadratic triangles (scikit-fem), a unit line load (1 N per mm of face)
along the flank's transverse normal on a short patch at the load radius, and the
tangential stress along the loaded side's root fillet (the surface's only stress: a free
surface carries no normal or shear stress), read from the displacement's gradient just
inside the surface. Shares nothing with rating.root but the gear's outline."""

from __future__ import annotations


import numpy as np
from fe_tooth import E_STEEL, NU_STEEL, _facet_index, section_mesh, tooth_section

#: how far inside the surface (mm) the stress is read, and the step of the difference
INSIDE, STEP = 2e-3, 5e-4


def fillet_stress(gear, radius: float, h_tooth: float = 0.15, h_patch: float = 0.1,
                  h_far: float = 3.0, patch: float = 0.2) -> dict:
    """The tangential stress (MPa per N/mm of line load) along the loaded side's fillet
    (fillet_plus of tooth 0, from the form circle to the root): 'points' (n, 2) mm, 'arc'
    (n,) mm from the form end, 'inclination' (n,) deg of the tangent to the centre line,
    'stress' (n,) MPa; and the mesh's size."""
    from skfem import (Basis, ElementTriP2, ElementVector, FacetBasis, Functional,
                       LinearForm, MeshTri, asm, condense, solve)
    from skfem.models.elasticity import lame_parameters, linear_elasticity

    S = section_mesh(gear, [radius], h_patch, h_tooth, h_far, patch=patch, growth=0.2)
    mesh = MeshTri(S.p, S.t)
    e = ElementVector(ElementTriP2())
    basis = Basis(mesh, e, intorder=4)
    lam, mu = lame_parameters(E_STEEL, NU_STEEL)
    K = asm(linear_elasticity(lam, mu), basis)
    held = _facet_index(mesh.facets, S.edges[:, S.tags == "bore"])
    D = basis.get_dofs(facets=held).all()
    patch_facets = _facet_index(mesh.facets, S.edges[:, S.tags == "patch0"])
    fb = FacetBasis(mesh, e, facets=patch_facets, intorder=6)
    length = float(asm(Functional(lambda w: 1.0 + 0.0 * w.x[0]), fb))
    n = S.sites[0].normal

    @LinearForm
    def traction(v, w):
        return (n[0] * v[0] + n[1] * v[1]) / length

    u = solve(*condense(K, asm(traction, fb), D=D))
    section = tooth_section(gear, samples=400)
    fillet = section.fillet_plus[:, :2]                    # form -> root
    tangent = np.gradient(fillet, axis=0)
    tangent /= np.hypot(*tangent.T)[:, None]
    # into the material: on side +1's fillet the tooth and rim lie toward -y
    into = np.column_stack([tangent[:, 1], -tangent[:, 0]])
    into[into[:, 1] > 0] *= -1.0
    at = fillet[1:-1] + INSIDE * into[1:-1]
    offsets = np.array([[STEP, 0.0], [-STEP, 0.0], [0.0, STEP], [0.0, -STEP]])
    probes = (at[:, None, :] + offsets[None, :, :]).reshape(-1, 2).T
    ux, uy = (v.reshape(-1, 4) for v in _probe(basis, probes, u))
    exx = (ux[:, 0] - ux[:, 1]) / (2 * STEP)
    eyy = (uy[:, 2] - uy[:, 3]) / (2 * STEP)
    exy = 0.5 * ((ux[:, 2] - ux[:, 3]) + (uy[:, 0] - uy[:, 1])) / (2 * STEP)
    sxx = lam * (exx + eyy) + 2 * mu * exx
    syy = lam * (exx + eyy) + 2 * mu * eyy
    sxy = 2 * mu * exy
    t = tangent[1:-1]
    stress = t[:, 0] ** 2 * sxx + t[:, 1] ** 2 * syy + 2 * t[:, 0] * t[:, 1] * sxy
    arc = np.concatenate([[0.0], np.cumsum(np.hypot(*np.diff(fillet, axis=0).T))])[1:-1]
    normals = np.column_stack([-tangent[:, 1], tangent[:, 0]])
    inclination = np.degrees(np.arctan2(np.abs(normals[:, 0]), np.abs(normals[:, 1])))[1:-1]
    return dict(points=fillet[1:-1], arc=arc, inclination=inclination,
                stress=stress, vertices=int(S.p.shape[1]))


def _probe(basis, points: np.ndarray, u: np.ndarray):
    """The displacement components (ux, uy) at points (2, n)."""
    values = basis.probes(points) @ u
    return values[:points.shape[1]], values[points.shape[1]:]
