"""Independent 2D finite-element reference for the mesh stiffness of a spur pair.

Method. Both gears of an aligned spur pair in one transverse section, plane strain, linear
elastic (E, nu; steel 206000 MPa, 0.3 by default), as whole gears: every tooth's exact
transverse outline (toothcontact.surfaces.outline.ToothOutline: the involute flanks, the
rack-generated fillets, the root and tip arcs; the teeth thinned for the pair's backlash as
toothcontact.gearset.gear_pair makes them) and the rim down to a bore of radius r_bore
(half the root radius by default, the project's solid blank on a shaft), the bore tied
rigidly to the gear's centre. The gear's bore is held; the pinion's turns by theta_1 as a
rigid ring. A body whose bore is rigidly tied turns as a rigid body plus its bore-held
elastic field, and a rigid turn moves every point of an involute flank by r_b·theta along
its normal, so the contact is solved on the two bore-held bodies with the rigid approach
delta = r_b1·theta_1 along the line of action.

Contact: frictionless (Signorini), between the two loaded flanks only. The pressure is
piecewise linear (hat functions) on a uniform grid of spacing h_p = b_H/(4·refine) along
the common tangent at the initial contact point P, over |s| <= 2.5 b_H (b_H the Hertz
half-width of the flanks' curvatures at P); it acts along each flank's outward facet
normal. Both flanks' boundary nodes there sit at exactly s = k·h_p/2 (two elements per
grid step, MESH_PER_GRID), so the hats' kinks fall on facet ends and the facet quadrature
is exact (with kinks inside facets the pressure came out 10-30 % noisy). Each body's
compliance on that grid, C_i = B_i^T K_i^-1 B_i (B_i the consistent nodal forces of the unit
hat loads; B_i^T u is the hat-weighted mean indentation), is exact for the discretised body;
the gap at delta = 0 is the exact distance between the flanks along the line of action. The
constrained conjugate gradient of tests/fe_reference.py (_signorini_cg: Polonsky & Keer,
then an exact solve on the contact set and a check of complementarity) finds the pressure
for the given normal line load F_n (N/mm) and the approach delta (mm). Mesh stiffness per
unit face c = F_n/delta, reported in N/(mm·um). The pair's other teeth are meshed but not
in contact: the neighbouring pairs' separation is measured (µm) on the exact outlines,
before the load and after it (first order: the gap less the relative displacement of the
two closest points along their joining line, the pinion's rigid turn included); a
position is a single-pair one when it stays open.

Library and mesh: scikit-fem (MeshTri, ElementTriP2: quadratic triangles; the linear
elasticity form with the 3D Lamé constants, which in 2D is plane strain), SciPy's SuperLU
for the bore-held stiffness (factorised once per body). The mesh is made here, without a
mesher package: the exact outline (a dense polyline: flanks at 1500 involute points, the
fillets by a cubic spline through the generated ones, arcs every 0.01 mm or finer) is
resampled by a size function h(x) = min(h_max, min_k(h_k + g·dist(x, feature_k))), with
the features the contact band (|s| <= 1.5 b_H on both flanks, h_c = h_p/2), the loaded
tooth and its two neighbours (outline, h_t = 0.25/refine), the outlines of the teeth
within three of it (h_o = 0.6/refine), every other tooth's outline (H_OUTLINE = 0.6 mm),
and h_max elsewhere (2 mm pinion, 4 mm gear), g = 0.25; the inside is filled by
a quadtree of cell size <= h(centre); points too near a boundary segment (inside its
diametral circle, or within 0.6 h of a boundary node) are dropped so every boundary segment
is a Delaunay edge; scipy's Delaunay triangulates, and the regions the boundary walls
enclose are kept by a point-in-tooth test. The triangulation is checked to contain every
boundary segment. `refine` scales h_p, h_c, h_t and h_o down (and g by 1/sqrt(refine)).
At refine 1, 2, 4 the pair has about 0.14, 0.25 and 0.51 million dofs (the mesh
stiffness of the 20/60 pair moves by 0.1 % from 1 to 4; halving h_max, lowering g to 0.15,
widening the grid to 3.5 b_H or coarsening it to b_H/4 at refine 2 moved it by < 0.05 %).

Units: mm, N, MPa; loads per unit face width (N/mm); stiffness N/(mm·µm).
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass, field

import numpy as np
import scipy.sparse.linalg as spl
from matplotlib.path import Path
from scipy.interpolate import CubicSpline
from scipy.sparse import coo_matrix
from scipy.sparse.csgraph import connected_components
from scipy.spatial import Delaunay, cKDTree

E_STEEL, NU_STEEL = 206000.0, 0.3
#: the element size (mm) on the outline of the teeth beyond the loaded ones' neighbours
H_OUTLINE = 0.6
#: contact elements per pressure-grid step (a pressure grid no finer than the mesh keeps
#: the hat pressures from oscillating)
MESH_PER_GRID = 2.0

__all__ = [
    "E_STEEL", "NU_STEEL", "spur_pair", "tooth_outline", "gear_outline", "Placement",
    "place", "mesh_domain", "ElasticBody", "hat_operator", "MeshStiffness",
    "mesh_stiffness", "hertz_half_width", "weber_flattening", "annulus_mesh",
    "annulus_torsion", "cantilever_deflection", "disc_pair_contact",
]


# ----------------------------------------------------------------------------- geometry

def spur_pair(teeth=(20, 60), module=3.0, face=20.0, pressure_angle=20.0):
    """The project's aligned, uncrowned spur pair (ISO 53 profile A rack, default
    backlash thinning) as toothcontact.gearset.GearPair."""
    from toothcontact.case import parse_case
    from toothcontact.gearset import gear_pair

    case = parse_case({
        "kind": "spur", "title": "fe mesh stiffness", "teeth": list(teeth),
        "module": f"{module} mm", "pressure_angle": f"{pressure_angle} deg",
        "helix_angle": "0 deg", "face_width": f"{face} mm"})
    return gear_pair(case)


def _arc(radius, a0, a1, step):
    n = max(2, int(math.ceil(abs(a1 - a0) * radius / step)) + 1)
    a = np.linspace(a0, a1, n)
    return radius * np.column_stack([np.cos(a), np.sin(a)])


def _spline(points, count):
    """`count` points on a cubic spline through `points` (chord-length parameter)."""
    d = np.concatenate([[0.0], np.cumsum(np.hypot(*np.diff(points, axis=0).T))])
    return CubicSpline(d, points, axis=0)(np.linspace(0.0, d[-1], count))


def tooth_outline(gear, flank_points=1500, fillet_points=400, arc_step=0.01):
    """Tooth 0 of an external gear in its own frame (centre at the origin, tooth on +x), as
    a dense polyline from the centre of the space before it to the centre of the space
    after it: (points (n, 2) mm, piece (n,) int: 0 root arc, 1 fillet -, 2 flank -, 3 tip,
    4 flank + (side +1: faces increasing polar angle), 5 fillet +, 6 root arc)."""
    from toothcontact.surfaces.outline import ToothOutline

    if gear.internal:
        raise ValueError("external gears only")
    outline = ToothOutline(gear)
    (u0, u1), _ = outline.flanks[1].domain
    u = np.sqrt(np.linspace(u0 ** 2, u1 ** 2, flank_points))   # even in arc length
    sec = outline.section(u, 0.0)
    fm = _spline(sec.fillet_minus[:, :2], fillet_points)
    fp = _spline(sec.fillet_plus[:, :2], fillet_points)
    km, kp = sec.flank_minus[:, :2], sec.flank_plus[:, :2]
    ang = lambda p: math.atan2(p[1], p[0])  # noqa: E731
    rr, ra = sec.root_radius, gear.tip_radius
    root0 = _arc(rr, sec.space_before, ang(fm[0]), arc_step)
    tip = _arc(ra, ang(km[-1]), ang(kp[0]), arc_step)
    root1 = _arc(rr, ang(fp[-1]), sec.space_after, arc_step)
    pieces = [root0[:-1], fm, km[1:], tip[1:-1], kp, fp[1:], root1[1:]]
    return (np.concatenate(pieces),
            np.concatenate([np.full(len(p), i) for i, p in enumerate(pieces)]))


def _rot(a):
    c, s = math.cos(a), math.sin(a)
    return np.array([[c, -s], [s, c]])


def gear_outline(gear, rotation, centre, **kw):
    """The whole gear's outline, closed, counter-clockwise, placed: turned by `rotation`
    (rad) about its centre, then moved to `centre`: (points (n, 2), tooth (n,) its tooth,
    piece (n,) as tooth_outline)."""
    pts, piece = tooth_outline(gear, **kw)
    pts, piece = pts[:-1], piece[:-1]
    pitch = 2 * math.pi / gear.teeth
    out = [pts @ _rot(rotation + k * pitch).T for k in range(gear.teeth)]
    tooth = np.repeat(np.arange(gear.teeth), len(pts))
    tooth = np.where(tooth > gear.teeth // 2, tooth - gear.teeth, tooth)   # -z/2 .. z/2
    return (np.concatenate(out) + np.asarray(centre, float), tooth,
            np.tile(piece, gear.teeth))


@dataclass
class Placement:
    """Where the pair sits with its tooth 0 pair in contact at pinion radius r1: pinion at
    the origin turned by phi1, gear at (a, 0) turned by phi2 (rad); P the contact point,
    n the line of action's direction (the pinion's flank normal, out of the pinion), t
    the tangent (n turned by -90°); rho1, rho2 the flanks' radii of curvature at P (mm)."""
    r1: float
    phi1: float
    phi2: float
    P: np.ndarray
    n: np.ndarray
    t: np.ndarray
    rho1: float
    rho2: float
    centre2: np.ndarray


def place(pair, r1):
    """The placement of pair (GearPair) at the pinion contact radius r1 (mm): the pinion
    drives turning counter-clockwise on its flank side +1, the gear turns clockwise and is
    loaded on its side +1. The line of action touches the pinion's base circle at polar
    angle -alpha_w and runs along (sin alpha_w, cos alpha_w)."""
    p, g = pair.pinion, pair.gear
    aw, a = pair.working_pressure_angle, pair.center_distance
    rb1, rb2 = p.base_radius, g.base_radius
    rho1 = math.sqrt(r1 ** 2 - rb1 ** 2)
    length = a * math.sin(aw)                      # T1T2
    rho2 = length - rho1
    a0 = -aw
    phi1 = a0 - p.base_half_angle + rho1 / rb1
    phi2 = math.pi - aw - g.base_half_angle + rho2 / rb2
    n = np.array([math.sin(aw), math.cos(aw)])
    T1 = rb1 * np.array([math.cos(a0), math.sin(a0)])
    return Placement(r1, phi1, phi2, T1 + rho1 * n, n, np.array([n[1], -n[0]]), rho1, rho2,
                     np.array([a, 0.0]))


def hertz_half_width(load, rho1, rho2, E, nu):
    """Hertz half-width b (mm) and peak pressure p0 (MPa) of two equal elastic cylinders
    (radii rho1, rho2 mm) under a line load (N/mm), plane strain: b = sqrt(4 F R/(pi E*)),
    1/R = 1/rho1 + 1/rho2, E* = E/(2(1 - nu²))."""
    R = 1.0 / (1.0 / rho1 + 1.0 / rho2)
    E_star = E / (2.0 * (1.0 - nu ** 2))
    b = math.sqrt(4.0 * load * R / (math.pi * E_star))
    return b, 2.0 * load / (math.pi * b)


# ----------------------------------------------------------------------------- mesher

def _resample(points, closed, breaks, size):
    """Nodes along a dense polyline at the local size h(x): each piece between consecutive
    `breaks` (indices, kept as nodes) gets ceil(∫ds/h) equal steps in ∫ds/h."""
    pts = np.vstack([points, points[:1]]) if closed else points
    h = size(pts)
    ds = np.hypot(*np.diff(pts, axis=0).T)
    cum = np.concatenate([[0.0], np.cumsum(ds / (0.5 * (h[1:] + h[:-1])))])
    b = sorted(set(int(i) for i in breaks) | ({0} if closed else {0, len(pts) - 1}))
    if closed:
        b = b + [len(pts) - 1]
    out = []
    for i0, i1 in zip(b[:-1], b[1:]):
        m = max(1, int(math.ceil(cum[i1] - cum[i0] - 1e-9)))
        target = np.linspace(cum[i0], cum[i1], m + 1)[:-1]
        k = np.clip(np.searchsorted(cum, target, side="right") - 1, i0, i1 - 1)
        f = ((target - cum[k]) / np.maximum(cum[k + 1] - cum[k], 1e-300))[:, None]
        out.append(pts[k] + f * (pts[k + 1] - pts[k]))
    if not closed:
        out.append(pts[-1:])
    return np.concatenate(out)


def _splice(loop, dense, P, t, s_values):
    """The closed loop of boundary nodes with those near P (along the tangent t, within the
    span of s_values) replaced by the points of the dense outline at exactly those
    tangential coordinates s = (x - P)·t: the pressure grid's hats then change slope only
    at facet ends (so the facet quadrature integrates them exactly)."""
    n = np.array([-t[1], t[0]])
    s_max = float(np.max(np.abs(s_values)))
    step = float(np.min(np.diff(np.sort(s_values))))

    def near(x, extra):
        return (np.abs((x - P) @ t) <= s_max + extra) & (np.abs((x - P) @ n) < 0.2)

    on = near(loop, 0.5 * step)
    if not on.any():
        raise ValueError("no boundary nodes near P")
    shift = int(np.argmin(on)) if on[0] else 0
    loop, on = np.roll(loop, -shift, axis=0), np.roll(on, -shift)
    idx = np.nonzero(on)[0]
    if idx[-1] - idx[0] + 1 != len(idx):
        raise ValueError("the nodes near P are not one run of the loop")
    d = dense[near(dense, 2 * step)]
    s_d = (d - P) @ t
    o = np.argsort(s_d)
    s_new = np.sort(np.asarray(s_values, float))
    if ((loop[idx[-1]] - loop[idx[0]]) @ t) < 0:
        s_new = s_new[::-1]
    pts = np.column_stack([np.interp(s_new, s_d[o], d[o, 0]), np.interp(s_new, s_d[o], d[o, 1])])
    return np.vstack([loop[:idx[0]], pts, loop[idx[-1] + 1:]])


def _quadtree(lo, hi, size, h_max):
    """Cell centres of a quadtree over the box [lo, hi] whose cells are no larger than
    h(centre)."""
    nx = np.maximum(1, np.ceil((hi - lo) / h_max).astype(int))
    s = float(np.max((hi - lo) / nx))
    gx = lo[0] + s * (np.arange(nx[0]) + 0.5)
    gy = lo[1] + s * (np.arange(nx[1]) + 0.5)
    c = np.column_stack([a.ravel() for a in np.meshgrid(gx, gy, indexing="ij")])
    out = []
    offsets = np.array([[-1, -1], [-1, 1], [1, -1], [1, 1]]) * 0.25
    while len(c):
        split = s > size(c)
        out.append(c[~split])
        c = (c[split][:, None, :] + offsets[None] * s).reshape(-1, 2)
        s *= 0.5
    return np.concatenate(out)


@dataclass
class Domain:
    """A meshed planar domain: nodes p (n, 2), triangles t (m, 3) counter-clockwise, the
    boundary nodes' indices by loop (outline first, then holes) and the minimum angle."""
    p: np.ndarray
    t: np.ndarray
    loops: list
    min_angle_deg: float


def mesh_domain(loops, inside, size, h_max):
    """Triangulate the domain bounded by closed `loops` (each an array of boundary nodes,
    already resampled), `inside(x)` its point test (bool per point), `size(x)` the element
    size (mm). Returns a Domain; RuntimeError if a boundary segment is not an edge."""
    bnd = np.concatenate(loops)
    nb = len(bnd)
    seg = []
    start = 0
    for loop in loops:
        i = np.arange(start, start + len(loop))
        seg.append(np.column_stack([i, np.roll(i, -1)]))
        start += len(loop)
    seg = np.concatenate(seg)
    lo, hi = bnd.min(axis=0), bnd.max(axis=0)
    cand = _quadtree(lo, hi, size, h_max)
    cand = cand[inside(cand)]
    hc = size(cand)
    tree_b = cKDTree(bnd)
    d, _ = tree_b.query(cand)
    keep = d > 0.6 * hc
    mid = 0.5 * (bnd[seg[:, 0]] + bnd[seg[:, 1]])
    half = 0.5 * np.hypot(*(bnd[seg[:, 1]] - bnd[seg[:, 0]]).T)
    tree_c = cKDTree(cand)
    for idx in tree_c.query_ball_point(mid, 1.2 * half + 1e-12):
        keep[idx] = False
    pts = np.vstack([bnd, cand[keep]])
    tri = Delaunay(pts).simplices
    # walls: the boundary segments; every one must be a triangulation edge
    edges = np.sort(np.concatenate([tri[:, [0, 1]], tri[:, [1, 2]], tri[:, [2, 0]]]), axis=1)
    key = edges[:, 0].astype(np.int64) * len(pts) + edges[:, 1]
    wall_key = np.sort(seg, axis=1)
    wall_key = wall_key[:, 0].astype(np.int64) * len(pts) + wall_key[:, 1]
    missing = ~np.isin(wall_key, key)
    if missing.any():
        raise RuntimeError(f"{int(missing.sum())} boundary segments not in the triangulation")
    # regions between the walls: triangles joined across non-wall edges
    m = len(tri)
    owner = np.tile(np.arange(m), 3)
    order = np.argsort(key, kind="stable")
    ks, os_ = key[order], owner[order]
    same = ks[1:] == ks[:-1]
    a, b = os_[:-1][same], os_[1:][same]
    inner = ~np.isin(ks[:-1][same], wall_key)
    graph = coo_matrix((np.ones(int(inner.sum())), (a[inner], b[inner])), shape=(m, m))
    _, label = connected_components(graph, directed=False)
    cen = pts[tri].mean(axis=1)
    # each region by the majority of its triangles' centroid tests
    ins = inside(cen).astype(float)
    votes = np.bincount(label, weights=ins) / np.bincount(label)
    tri = tri[votes[label] > 0.5]
    # counter-clockwise, drop unused nodes
    e1, e2 = pts[tri[:, 1]] - pts[tri[:, 0]], pts[tri[:, 2]] - pts[tri[:, 0]]
    flip = e1[:, 0] * e2[:, 1] - e1[:, 1] * e2[:, 0] < 0
    tri[flip] = tri[flip][:, [0, 2, 1]]
    used = np.unique(tri)
    if not np.isin(np.arange(nb), used).all():
        raise RuntimeError("boundary nodes left out of the mesh")
    remap = np.full(len(pts), -1)
    remap[used] = np.arange(len(used))
    p, t = pts[used], remap[tri]
    loops_idx, start = [], 0
    for loop in loops:
        loops_idx.append(remap[np.arange(start, start + len(loop))])
        start += len(loop)
    return Domain(p, t, loops_idx, _min_angle(p, t))


def _min_angle(p, t):
    v = p[t]
    ang = []
    for i in range(3):
        a, b, c = v[:, i], v[:, (i + 1) % 3], v[:, (i + 2) % 3]
        u, w = b - a, c - a
        cosang = (u * w).sum(1) / (np.hypot(*u.T) * np.hypot(*w.T))
        ang.append(np.degrees(np.arccos(np.clip(cosang, -1, 1))))
    return float(np.min(ang))


def _size_function(features, growth, h_max):
    """h(x) = min(h_max, min_k(h_k + growth·dist(x, points_k))) for features (points, h_k)."""
    trees = [(cKDTree(np.asarray(pts)), float(h)) for pts, h in features if len(pts)]

    def size(x):
        h = np.full(len(x), float(h_max))
        for tree, hk in trees:
            d, _ = tree.query(x)
            h = np.minimum(h, hk + growth * d)
        return h
    return size


# ----------------------------------------------------------------------------- FE body

class ElasticBody:
    """Plane-strain P2 body on a Domain with every dof whose location satisfies `fixed(x)`
    (x (2, n) mm) held; K factorised once (SuperLU)."""

    def __init__(self, domain, fixed, E, nu):
        from skfem import Basis, ElementTriP2, ElementVector, MeshTri, asm
        from skfem.models.elasticity import lame_parameters, linear_elasticity

        self.domain = domain
        self.mesh = MeshTri(domain.p.T.copy(), domain.t.T.copy())
        self.element = ElementVector(ElementTriP2())
        self.basis = Basis(self.mesh, self.element, intorder=4)
        self.K = asm(linear_elasticity(*lame_parameters(E, nu)), self.basis).tocsr()
        held = np.nonzero(fixed(self.basis.doflocs))[0]
        self.free = np.setdiff1d(np.arange(self.K.shape[0]), held)
        self.n_dofs = len(self.free)
        t0 = time.perf_counter()
        self.lu = spl.splu(self.K[self.free][:, self.free].tocsc(),
                           permc_spec="MMD_AT_PLUS_A")
        self.factor_s = time.perf_counter() - t0

    @staticmethod
    def within(centre, radius):
        """The dof test of a disc: |x - centre| <= radius (1 + 1e-9)."""
        c = np.asarray(centre, float)[:, None]
        return lambda x: np.hypot(*(x - c)) <= radius * (1.0 + 1e-9)

    def release(self):
        """Drop the factorisation (its memory); solve no longer works."""
        self.lu = None

    def solve(self, F):
        """Displacements (all dofs) under nodal forces F (columns allowed)."""
        F = np.asarray(F, float)
        u = np.zeros(F.shape)
        u[self.free] = self.lu.solve(F[self.free])
        return u

    def vertex_displacement(self, u):
        """(n_vertices, 2) displacements at the mesh vertices."""
        return u[self.basis.nodal_dofs].T


def hat_operator(body, P, t, s_nodes, reach):
    """B (n_dofs × M): the consistent nodal forces of unit hat loads along the boundary
    near P: load j is a pressure phi_j(s)/h (MPa per N/mm) along the facets' inward normal,
    phi_j the hat of node s_nodes[j] (s the coordinate along t from P, spacing h), on the
    boundary facets within `reach` mm of P. B^T u is then each hat's mean indentation."""
    from skfem import FacetBasis, LinearForm, asm

    mesh = body.mesh
    facets = mesh.boundary_facets()
    mid = mesh.p[:, mesh.facets[:, facets]].mean(axis=1).T
    near = np.hypot(*(mid - P).T) < reach
    fb = FacetBasis(mesh, body.element, facets=facets[near], intorder=12)
    h = s_nodes[1] - s_nodes[0]
    cols = []
    for sj in s_nodes:
        @LinearForm
        def load(v, w, sj=sj):
            s = (w.x[0] - P[0]) * t[0] + (w.x[1] - P[1]) * t[1]
            phi = np.maximum(0.0, 1.0 - np.abs(s - sj) / h) / h
            return -phi * (w.n[0] * v[0] + w.n[1] * v[1])
        cols.append(asm(load, fb))
    return np.column_stack(cols)


# ----------------------------------------------------------------------------- the pair

@dataclass
class MeshStiffness:
    """One FE solution of the pair at pinion contact radius r1 (mm)."""
    r1: float
    refine: float
    normal_load: float            # F_n, N/mm
    delta_um: float               # approach along the line of action (µm)
    stiffness: float              # F_n/delta, N/(mm·µm)
    half_width: float             # contact half-width (mm), from the pressure's extent
    peak_pressure: float          # MPa
    hertz_b: float
    hertz_p0: float
    neighbour_gap_um: dict        # pair (-1 entering, +1 leaving) -> (before, after) µm
    h_contact: float              # element size at the contact (mm)
    h_tooth: float                # on the loaded teeth (mm)
    h_grid: float                 # the pressure grid's step (mm)
    dofs: dict
    elements: dict
    min_angle_deg: dict
    seconds: float
    extra: dict = field(default_factory=dict)

    @property
    def single_pair(self) -> bool:
        return all(after > 0 for _, after in self.neighbour_gap_um.values())


def _inside_gear(gear, rotation, centre, bore):
    """Point test of the placed gear: inside its tooth-0 wedge after reduction by the
    angular pitch, outside the bore."""
    pts, _ = tooth_outline(gear, flank_points=300, fillet_points=100, arc_step=0.05)
    wedge = Path(np.vstack([pts, [[0.0, 0.0]]]))
    pitch = 2 * math.pi / gear.teeth

    def inside(x):
        y = (np.asarray(x) - centre) @ _rot(-rotation).T
        r = np.hypot(*y.T)
        th = np.arctan2(y[:, 1], y[:, 0])
        th = (th + 0.5 * pitch) % pitch - 0.5 * pitch
        q = r[:, None] * np.column_stack([np.cos(th), np.sin(th)])
        return (r > bore) & wedge.contains_points(q)
    return inside


def _gear_domain(gear, rotation, centre, bore, loaded, contact, refine, growth, h_max):
    """Mesh of a placed gear; contact = (P, t, s_values): the boundary nodes near P sit at
    exactly those tangential coordinates (_splice), the band |s| <= 1.5 b_H meshed at their
    spacing. Returns (Domain, bore node indices, dense outline, tooth, piece, size)."""
    dense, tooth, piece = gear_outline(gear, rotation, centre)
    P, t, s_values = contact
    h_t, h_o = 0.25 / refine, 0.6 / refine
    s = (dense - P) @ t
    hgt = (dense - P) @ np.array([-t[1], t[0]])
    band = dense[(np.abs(s) <= 0.6 * np.max(np.abs(s_values))) & (np.abs(hgt) < 0.05)
                 & (tooth == 0)]
    hc = float(np.min(np.diff(np.sort(s_values))))
    loaded_pts = dense[np.isin(tooth, loaded)]
    near_pts = dense[np.abs(tooth) <= max(abs(k) for k in loaded) + 2]
    features = [(band, hc), (loaded_pts, h_t), (near_pts[::2], h_o), (dense[::4], H_OUTLINE)]
    size = _size_function(features, growth, h_max)
    # tip corners and the ends of the fillets/flanks as breaks
    breaks = np.nonzero(piece != np.roll(piece, 1))[0]
    outer = _splice(_resample(dense, True, breaks, size), dense, P, t, s_values)
    n_bore = max(24, int(math.ceil(2 * math.pi * bore / min(h_max, 0.5 * bore))))
    a = np.linspace(0, 2 * math.pi, n_bore, endpoint=False)
    hole = centre + bore * np.column_stack([np.cos(-a), np.sin(-a)])   # clockwise
    inside = _inside_gear(gear, rotation, centre, bore)
    domain = mesh_domain([outer, hole], inside, size, h_max)
    return domain, domain.loops[1], dense, tooth, piece, size


def _closest(points, tree_pts, poly):
    """For each point, the distance (mm) to the polyline `poly` near its nearest vertex and
    the unit vector toward it, and the nearest vertex index."""
    d, j = tree_pts.query(points)
    best = np.full(len(points), np.inf)
    vec = np.zeros((len(points), 2))
    for k0 in (-1, 0):
        a = poly[np.clip(j + k0, 0, len(poly) - 1)]
        b = poly[np.clip(j + k0 + 1, 0, len(poly) - 1)]
        ab = b - a
        L2 = np.maximum((ab * ab).sum(1), 1e-300)
        f = np.clip(((points - a) * ab).sum(1) / L2, 0, 1)
        q = a + f[:, None] * ab
        dist = np.hypot(*(q - points).T)
        better = dist < best
        best[better] = dist[better]
        vec[better] = (q - points)[better] / np.maximum(dist[better], 1e-300)[:, None]
    return best, vec, j


def weber_flattening(load, b, depth, E, nu):
    """Weber's contact flattening (mm) of one body: the approach between the surface at the
    middle of a Hertz line contact (half-width b mm, load N/mm) and the point at `depth`
    (mm) below it, on a plane-strain half-plane:
    2F(1 - nu²)/(pi E)·[ln(2d/b) - nu/(2(1 - nu))]. It is the infinitely long limit of the
    project's half-space compression measured to a reference depth (Boussinesq's
    displacement at depth, Johnson eq 3.21b, integrated along the line)."""
    return 2.0 * load * (1.0 - nu ** 2) / (math.pi * E) * (
        math.log(2.0 * depth / b) - nu / (2.0 * (1.0 - nu)))


def mesh_stiffness(r1, refine=1.0, pair=None, tangential_line_load=300.0, E=E_STEEL,
                   nu=NU_STEEL, bore_ratio=0.5, growth=0.25, h_max=(2.0, 4.0),
                   grid_per_b=None, reach_b=2.5, breakdown=False):
    """The single-pair mesh stiffness of `pair` (default spur_pair()) at pinion contact
    radius r1 (mm) under the tangential line load (N/mm at the pinion's operating pitch
    circle), by the FE described in the module. refine: 1, 2, 4... (pressure grid
    b_H/(4·refine), contact elements half that, loaded teeth 0.25/refine mm, the teeth
    within three of them 0.6/refine mm, P2); bore radius bore_ratio × root radius (0.5: the
    project's default); h_max the largest element (mm) in the pinion and the gear.

    breakdown: also split each body's indentation at the contact's middle (µm, into the
    body along the line of action) into its structure, the displacement of the point at
    the depth of the tooth's half-thickness below the contact (the depth the project
    measures its contact compression to, toothcontact.contact.compliance.ToothCompliance.
    half_thickness), and its contact part (the rest); and the structure into the tooth
    (the same body clamped on its root circle: every dof inside it held) and the gear
    body (the rest), all under the pair's contact pressure. Returns a MeshStiffness."""
    t_start = time.perf_counter()
    pair = spur_pair() if pair is None else pair
    p, g = pair.pinion, pair.gear
    pl = place(pair, r1)
    F_n = tangential_line_load * pair.operating_pitch_radius / p.base_radius
    b_H, p0_H = hertz_half_width(F_n, pl.rho1, pl.rho2, E, nu)
    grid_per_b = 4.0 * refine if grid_per_b is None else grid_per_b
    h_p = b_H / grid_per_b
    m = int(math.ceil(reach_b * b_H / h_p))
    s_nodes = h_p * np.arange(-m, m + 1)
    g_growth = growth / math.sqrt(refine)
    members = {"pinion": (p, pl.phi1, np.zeros(2), h_max[0], -1.0),
               "gear": (g, pl.phi2, pl.centre2, h_max[1], 1.0)}
    bodies, dense = {}, {}
    fine = h_p / MESH_PER_GRID
    k_fine = int(round(s_nodes[-1] / fine))
    s_fine = fine * np.arange(-k_fine, k_fine + 1)
    C = np.zeros((len(s_nodes), len(s_nodes)))
    Bs, Xs = {}, {}
    reach = reach_b * b_H + 0.2
    for name, (gear, rot, centre, hm, _) in members.items():
        bore = bore_ratio * gear.root_radius_value
        domain, _, d_out, d_tooth, d_piece, _ = _gear_domain(
            gear, rot, centre, bore, [-1, 0, 1], (pl.P, pl.t, s_fine), refine, g_growth, hm)
        body = ElasticBody(domain, ElasticBody.within(centre, bore), E, nu)
        dense[name] = (d_out, d_tooth, d_piece)
        # each hat load's displacements (dofs × M), kept; the factorisation let go
        B = hat_operator(body, pl.P, pl.t, s_nodes, reach)
        Bs[name], Xs[name] = B, body.solve(B)
        C += B.T @ Xs[name]
        body.release()
        bodies[name] = body
    # the gap at delta = 0 along n, from the exact outlines (pinion below, gear above)
    gap0 = np.zeros(len(s_nodes))
    for name, (*_, side) in members.items():
        out, tooth, piece = dense[name]
        on = (tooth == 0) & (piece == 4)
        s = (out[on] - pl.P) @ pl.t
        hgt = (out[on] - pl.P) @ pl.n
        o = np.argsort(s)
        gap0 += side * np.interp(s_nodes, s[o], hgt[o])
    C = 0.5 * (C + C.T)
    from fe_reference import _signorini_cg
    P0 = np.where(np.abs(s_nodes) <= b_H, 1.0, 0.0)
    P, delta, _ = _signorini_cg(C, gap0 - gap0.min(), F_n, P0 * F_n / P0.sum())
    delta += gap0.min()
    pressure = P / h_p
    touching = np.nonzero(P > 0)[0]
    half_width = 0.5 * (s_nodes[touching[-1]] - s_nodes[touching[0]] + 2 * h_p)
    U = {name: Xs[name] @ P for name in bodies}
    del Xs
    # the neighbouring pairs' separation before and after the load
    u = {name: bodies[name].vertex_displacement(U[name]) for name in bodies}
    theta1 = delta / p.base_radius
    gaps = {}
    g_out, _, _ = dense["gear"]
    gear_tree = cKDTree(g_out)
    gv_tree = cKDTree(bodies["gear"].mesh.p.T)
    pv_tree = cKDTree(bodies["pinion"].mesh.p.T)
    p_out, p_tooth, _ = dense["pinion"]
    for k in (-1, 1):
        pts = p_out[p_tooth == k]
        dist, vec, j = _closest(pts, gear_tree, g_out)
        near = dist < 0.5
        pts, dist, vec, j = pts[near], dist[near], vec[near], j[near]
        if not len(dist):
            gaps[k] = (math.inf, math.inf)
            continue
        up = u["pinion"][pv_tree.query(pts)[1]] + theta1 * np.column_stack([-pts[:, 1],
                                                                              pts[:, 0]])
        ug = u["gear"][gv_tree.query(g_out[j])[1]]
        after = dist - ((up - ug) * vec).sum(1)
        gaps[k] = (float(dist.min() * 1e3), float(after.min() * 1e3))
    extra = {"s_nodes": s_nodes, "pressure": pressure, "gap0": gap0, "placement": pl}
    if breakdown:
        from toothcontact.contact.compliance import ToothCompliance

        middle = int(np.argmin(np.abs(s_nodes)))
        parts = {}
        for name, (gear, rot, centre, hm, side) in members.items():
            body, B = bodies[name], Bs[name]
            radius = float(np.hypot(*(pl.P - centre)))
            depth = ToothCompliance(gear, E, nu).half_thickness(radius)
            into = side * pl.n                       # into the body along the line of action
            point = (pl.P + depth * into)[:, None]
            probe = body.basis.probes(point)
            at_depth = lambda U_: float(into @ (probe @ U_))  # noqa: E731
            surface = float((B.T @ U[name])[middle])
            clamped = ElasticBody(body.domain, ElasticBody.within(
                centre, gear.root_radius_value), E, nu)
            tooth = at_depth(clamped.solve(B @ P))
            clamped.release()
            structure = at_depth(U[name])
            parts[name] = {"radius_mm": radius, "depth_mm": float(depth),
                           "indentation_um": surface * 1e3,
                           "structure_um": structure * 1e3,
                           "tooth_um": tooth * 1e3,
                           "body_um": (structure - tooth) * 1e3,
                           "contact_um": (surface - structure) * 1e3,
                           "weber_um": weber_flattening(F_n, b_H, depth, E, nu) * 1e3}
        extra["breakdown"] = parts
    return MeshStiffness(
        r1=float(r1), refine=float(refine), normal_load=float(F_n),
        delta_um=float(delta * 1e3), stiffness=float(F_n / delta * 1e-3),
        half_width=float(half_width), peak_pressure=float(pressure.max()),
        hertz_b=float(b_H), hertz_p0=float(p0_H), neighbour_gap_um=gaps,
        h_contact=float(fine), h_tooth=0.25 / refine, h_grid=float(h_p),
        dofs={k: b.n_dofs for k, b in bodies.items()},
        elements={k: int(b.domain.t.shape[0]) for k, b in bodies.items()},
        min_angle_deg={k: b.domain.min_angle_deg for k, b in bodies.items()},
        seconds=time.perf_counter() - t_start, extra=extra)


# ----------------------------------------------------------------------------- closed forms

def _circle(centre, radius, size, clockwise=False, step=0.002):
    """A circle's boundary nodes at the local size (counter-clockwise unless clockwise)."""
    n = max(64, int(math.ceil(2 * math.pi * radius / step)))
    a = np.linspace(0.0, 2 * math.pi, n, endpoint=False)
    a = -a if clockwise else a
    dense = np.asarray(centre, float) + radius * np.column_stack([np.cos(a), np.sin(a)])
    return _resample(dense, True, [0], size)


def annulus_mesh(a, R, h, refine=1.0):
    """An annulus a < r < R about the origin at element size h/refine: (Domain)."""
    hh = h / refine
    size = lambda x: np.full(len(x), hh)  # noqa: E731

    def inside(x):
        r = np.hypot(*np.asarray(x).T)
        return (r > a) & (r < R)
    return mesh_domain([_circle((0, 0), R, size), _circle((0, 0), a, size, True)],
                       inside, size, hh)


def annulus_torsion(a=10.0, R=30.0, refine=1.0, E=E_STEEL, nu=NU_STEEL, torque=1000.0):
    """An annulus held on its bore r = a, twisted by a uniform shear traction on r = R of
    torque `torque` (N·mm per mm): the FE mean circumferential displacement of the rim
    against the exact u_theta(R) = tau R³/(2 mu)·(1/a² - 1/R²), tau = T/(2 pi R²) (µm)."""
    from skfem import FacetBasis, Functional, LinearForm, asm

    dom = annulus_mesh(a, R, 0.1 * (R - a), refine)
    body = ElasticBody(dom, ElasticBody.within((0.0, 0.0), a), E, nu)
    mesh = body.mesh
    facets = mesh.boundary_facets()
    mid = mesh.p[:, mesh.facets[:, facets]].mean(axis=1)
    outer = facets[np.hypot(*mid) > 0.5 * (a + R)]
    fb = FacetBasis(mesh, body.element, facets=outer, intorder=6)
    tau = torque / (2 * math.pi * R ** 2)

    @LinearForm
    def shear(v, w):
        r = np.sqrt(w.x[0] ** 2 + w.x[1] ** 2)
        return tau * (-w.x[1] * v[0] + w.x[0] * v[1]) / r

    u = body.solve(asm(shear, fb))

    @Functional
    def turn(w):
        r = np.sqrt(w.x[0] ** 2 + w.x[1] ** 2)
        return (-w.x[1] * w["u"][0] + w.x[0] * w["u"][1]) / r

    fe = asm(turn, fb, u=fb.interpolate(u)) / (2 * math.pi * R)
    mu = E / (2 * (1 + nu))
    exact = tau * R ** 3 / (2 * mu) * (1 / a ** 2 - 1 / R ** 2)
    return fe * 1e3, exact * 1e3


def cantilever_deflection(length=32.0, depth=4.0, refine=1.0, E=E_STEEL, nu=NU_STEEL,
                          load=100.0):
    """A plane-strain cantilever strip [0, L] × [-c, c] (c = depth/2) clamped on x = 0 (every
    dof there held), loaded on its free end by a parabolic shear traction of resultant
    `load` (N per mm of width): the FE deflection of the end's centre against Timoshenko's
    beam P L³/(3 E' I) + 1.2 P L/(G A) (E' = E/(1 - nu²), I = depth³/12, A = depth; µm)."""
    from skfem import FacetBasis, LinearForm, asm

    c, L = 0.5 * depth, length
    hh = depth / 8 / refine
    size = lambda x: np.full(len(x), hh)  # noqa: E731
    corners = np.array([[0, -c], [L, -c], [L, c], [0, c], [0, -c]], float)
    dense = np.concatenate([np.linspace(corners[i], corners[i + 1], 2001)[:-1]
                            for i in range(4)])
    loop = _resample(dense, True, [0, 2000, 4000, 6000], size)
    inside = lambda x: ((x[:, 0] > 0) & (x[:, 0] < L) & (np.abs(x[:, 1]) < c))  # noqa: E731
    dom = mesh_domain([loop], inside, size, hh)
    body = ElasticBody(dom, lambda x: x[0] <= 1e-9 * L, E, nu)
    mesh = body.mesh
    facets = mesh.boundary_facets()
    mid = mesh.p[:, mesh.facets[:, facets]].mean(axis=1)
    end = facets[mid[0] > L * (1 - 1e-9)]
    fb = FacetBasis(mesh, body.element, facets=end, intorder=6)

    @LinearForm
    def shear(v, w):
        return -0.75 * load / c * (1 - (w.x[1] / c) ** 2) * v[1]

    u = body.solve(asm(shear, fb))
    tip = body.basis.probes(np.array([[L * (1 - 1e-9)], [0.0]]))
    fe = -float((tip @ u)[1])
    E_plane, G = E / (1 - nu ** 2), E / (2 * (1 + nu))
    beam = load * L ** 3 / (3 * E_plane * depth ** 3 / 12) + 1.2 * load * L / (G * depth)
    return fe * 1e3, beam * 1e3


def disc_pair_contact(R1=20.0, R2=60.0, load=300.0, refine=1.0, depth=2.0, E=E_STEEL,
                      nu=NU_STEEL, reach_b=2.5):
    """Two discs (radii R1, R2 mm, bores R/4 held) touching at the origin, pressed together
    by the normal line load `load` (N/mm), solved as the gear pair is (hat pressures on the
    common tangent, each disc's FE compliance, _signorini_cg). Returns a dict: the FE
    contact half-width (mm, the pressure's extent) and peak pressure (MPa) beside Hertz's,
    the pressure's rms departure from Hertz's ellipse over the peak, and for each disc its
    contact part (µm: the indentation at the middle less the displacement of the point
    `depth` mm below it) beside Weber's flattening."""
    from fe_reference import _signorini_cg

    b, p0 = hertz_half_width(load, R1, R2, E, nu)
    h_p = b / (4.0 * refine)
    m = int(math.ceil(reach_b * b / h_p))
    s_nodes = h_p * np.arange(-m, m + 1)
    n, t = np.array([1.0, 0.0]), np.array([0.0, 1.0])
    P0 = np.zeros(2)
    C = np.zeros((len(s_nodes), len(s_nodes)))
    bodies = []
    for R, side in ((R1, -1.0), (R2, 1.0)):
        centre = np.array([side * R, 0.0])
        band = np.column_stack([np.zeros(21), np.linspace(-1.5 * b, 1.5 * b, 21)])
        size = _size_function([(band, h_p / MESH_PER_GRID),
                               (np.array([[0.0, 0.0]]), 0.25 / refine)],
                              0.25 / math.sqrt(refine), R / 8)
        outer = _circle(centre, R, size, step=min(0.002, h_p / 4))
        fine = h_p / MESH_PER_GRID
        k = int(round(s_nodes[-1] / fine))
        dense_arc = centre + R * np.column_stack([
            -side * np.cos(np.linspace(-0.1, 0.1, 20001)), np.sin(np.linspace(-0.1, 0.1, 20001))])
        outer = _splice(outer, dense_arc, P0, t, fine * np.arange(-k, k + 1))
        bore = _circle(centre, R / 4, size, True)
        inside = lambda x, c=centre, R=R: ((np.hypot(*(np.asarray(x) - c).T) < R)  # noqa: E731
                                           & (np.hypot(*(np.asarray(x) - c).T) > R / 4))
        dom = mesh_domain([outer, bore], inside, size, R / 8)
        body = ElasticBody(dom, ElasticBody.within(centre, R / 4), E, nu)
        B = hat_operator(body, P0, t, s_nodes, reach_b * b + 0.2)
        C += B.T @ body.solve(B)
        bodies.append((body, B, side, R))
    C = 0.5 * (C + C.T)
    gap = (R1 - np.sqrt(R1 ** 2 - s_nodes ** 2)) + (R2 - np.sqrt(R2 ** 2 - s_nodes ** 2))
    start = np.where(np.abs(s_nodes) <= b, 1.0, 0.0)
    P, delta, _ = _signorini_cg(C, gap, load, start * load / start.sum())
    p = P / h_p
    on = np.nonzero(P > 0)[0]
    ellipse = p0 * np.sqrt(np.clip(1 - (s_nodes / b) ** 2, 0, None))
    out = {"b_fe": 0.5 * (s_nodes[on[-1]] - s_nodes[on[0]] + 2 * h_p), "b_hertz": b,
           "p0_fe": float(p.max()), "p0_hertz": p0,
           "rms_over_p0": float(np.sqrt(np.mean((p - ellipse)[np.abs(s_nodes) <= b] ** 2)) / p0),
           "delta_um": delta * 1e3, "weber_um": weber_flattening(load, b, depth, E, nu) * 1e3}
    middle = int(np.argmin(np.abs(s_nodes)))
    for k, (body, B, side, R) in enumerate(bodies):
        u = body.solve(B @ P)
        into = side * n
        probe = body.basis.probes((depth * into)[:, None])
        out[f"contact_um_{k + 1}"] = ((B.T @ u)[middle] - float(into @ (probe @ u))) * 1e3
    return out
