"""Independent finite-element reference of a spur gear tooth's deflection along its face.

Method: linear elasticity of the gear's exact transverse section (toothcontact.surfaces.outline
.ToothOutline: generated fillet, flank, tip arc; the case's thinning included), meshed here
in 2D with unstructured triangles (a DistMesh-type spring smoother, Persson & Strang, SIAM
Rev. 46 (2004) 329-345, on fixed boundary points; scipy's Delaunay), then

* 2D: plane strain, quadratic triangles (scikit-fem ElementTriP2), or
* 3D: the section extruded over the face on graded z-layers, each prism split into three
  tetrahedra by the global vertex order (conforming across prisms), quadratic tetrahedra
  (scikit-fem ElementTetP2, 10 nodes).

Body: the whole gear (teeth=None, the default: every tooth, the far ones on coarse
elements), or `teeth` teeth on each side of the loaded tooth 0 (on +x) with the rim under
them and the sector's two radial cut faces held (much too stiff for this body: plane strain
gives 0.64/0.71/0.76 of the whole gear's compliance for 1/2/3 teeth a side on the 20-tooth
pinion); the bore (radius `bore`, default half the root radius: the compliance model's
"solid blank on a shaft of half its root diameter") held. Free end faces z = ±b/2 (3D).

Load: a uniform traction along the flank's transverse normal (into the tooth) at each load
radius on tooth 0's flank_plus (y > 0), over a patch `patch` mm along the profile (its two
ends are mesh nodes) × a z-interval (whose ends are mesh planes). Read-outs (mm, per unit
load): the work-conjugate (patch-mean) normal displacement, the normal displacement at the
point where the load's line of action crosses the tooth's centre line (y = 0; "to the centre
line", the compliance model's reference), and along the face the flank point's and the
centre-line point's normal displacement at every z-plane. Half-space helpers give the
compression from the surface to the half-thickness that the contact solver adds to the
model (Weber's flattening), to compare surface read-outs.

Solver: a multifrontal Cholesky (dense fronts by LAPACK/BLAS, one thread: OpenBLAS's threaded
potrf is 10-100x slower on 2 cores) on a geometric nested-dissection order; 3D: the
symmetric and the antisymmetric halves about mid-face (z >= 0 with u_z = 0, resp.
u_x = u_y = 0, on z = 0) factorised apart, any load split into the two. Checked against
beam theory and a direct SuperLU solve in tests/test_fe_tooth.py.

Mesh levels (LEVELS) and the comparison with contact.compliance: face_study, run by
benchmarks/fe_tooth_face.py. Units: mm, N, MPa.
"""

from __future__ import annotations

import math
import time
import tomllib
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np
import scipy.sparse as sp
from matplotlib.path import Path as MplPath
from scipy.spatial import Delaunay, cKDTree

ROOT = Path(__file__).resolve().parents[1]
E_STEEL, NU_STEEL = 206000.0, 0.3


# ----------------------------------------------------------------------------- geometry

def case_gears(case: str = "spur_crowned_20_60.toml"):
    """(pinion, gear) CylindricalGears of a bundled spur case, as the analyses build them."""
    from toothcontact.case import parse_case
    from toothcontact.gearset import gear_pair

    with open(ROOT / "cases" / case, "rb") as fh:
        pair = gear_pair(parse_case(tomllib.load(fh)))
    return pair.pinion, pair.gear


@dataclass(frozen=True)
class LoadSite:
    """Tooth 0's loaded flank (flank_plus, y > 0) at the load radius: the point (mm), the unit
    transverse normal into the tooth, the patch's two ends on the flank (mm) and the point
    where the line of action crosses the centre line y = 0, its distance from the flank
    point (mm), the half-thickness at the radius (mm)."""

    radius: float
    point: np.ndarray
    normal: np.ndarray
    patch_ends: np.ndarray
    centre: np.ndarray
    depth: float
    half_thickness: float


def tooth_section(gear, samples: int = 400):
    """The exact section of tooth 0 at z = 0 (ToothOutline.section)."""
    from toothcontact.surfaces.outline import ToothOutline

    outline = ToothOutline(gear)
    (u0, u1), _ = outline.flanks[1].domain
    return outline.section(np.linspace(u0, u1, samples), 0.0)


def load_site(gear, radius: float, patch: float, section=None) -> LoadSite:
    """The load on flank_plus of tooth 0 at `radius`, a patch `patch` mm long along the
    profile centred there."""
    section = section or tooth_section(gear)
    flank = section.flank_plus[:, :2]                      # tip -> form
    s = np.concatenate([[0.0], np.cumsum(np.hypot(*np.diff(flank, axis=0).T))])
    r = np.hypot(*flank.T)
    at = float(np.interp(-radius, -r, s))                  # r falls along the polyline
    point = np.array([np.interp(at, s, flank[:, i]) for i in (0, 1)])
    ends = np.array([[np.interp(a, s, flank[:, i]) for i in (0, 1)]
                     for a in (at - 0.5 * patch, at + 0.5 * patch)])
    tangent = ends[1] - ends[0]
    normal = np.array([tangent[1], -tangent[0]]) / np.hypot(*tangent)
    if normal[1] > 0:
        normal = -normal                                   # into the tooth (toward y = 0)
    depth = point[1] / -normal[1]
    return LoadSite(radius, point, normal, ends, point + depth * normal, float(depth),
                    float(point[1]))


def _resample(poly: np.ndarray, size, required: list[int]) -> tuple[np.ndarray, np.ndarray]:
    """Points along the open polyline `poly` (its ends and the vertices `required` kept),
    spaced by the size function; returns the points and, per point, the index of the
    required vertex it is (-1 if none)."""
    cut = sorted(set([0, len(poly) - 1] + list(required)))
    out, mark = [], []
    for a, b in zip(cut[:-1], cut[1:]):
        piece = poly[a:b + 1]
        seg = np.hypot(*np.diff(piece, axis=0).T)
        s = np.concatenate([[0.0], np.cumsum(seg)])
        dense = np.linspace(0.0, s[-1], max(int(s[-1] / 0.005), 8))
        xy = np.column_stack([np.interp(dense, s, piece[:, i]) for i in (0, 1)])
        w = 1.0 / size(xy)
        cum = np.concatenate([[0.0], np.cumsum(0.5 * (w[1:] + w[:-1]) * np.diff(dense))])
        n = max(1, int(math.ceil(cum[-1] - 1e-9)))
        at = np.interp(np.linspace(0.0, cum[-1], n + 1), cum, dense)
        pts = np.column_stack([np.interp(at, s, piece[:, i]) for i in (0, 1)])
        pts[0], pts[-1] = piece[0], piece[-1]
        out.append(pts[:-1])
        mark.append(np.concatenate([[a], np.full(n - 1, -1)]))
    out.append(poly[-1:])
    mark.append(np.array([len(poly) - 1]))
    return np.concatenate(out), np.concatenate(mark)


@dataclass
class Section:
    """A meshed transverse section: points p (2, n) mm, triangles t (3, m), boundary edges
    (2, k) with their tags (k,) ('free', 'bore', 'cut', 'patch0', 'patch1', ...: the load
    patch at sites[i]), the bore radius (mm)."""

    p: np.ndarray
    t: np.ndarray
    edges: np.ndarray
    tags: np.ndarray
    sites: list
    bore: float
    info: dict = field(default_factory=dict)

    @property
    def site(self) -> LoadSite:
        return self.sites[0]


def _rotate(xy: np.ndarray, angle: float) -> np.ndarray:
    c, s = math.cos(angle), math.sin(angle)
    return xy @ np.array([[c, s], [-s, c]])


def section_mesh(gear, radii, h_patch: float, h_tooth: float, h_far: float,
                 teeth: int | None = None, patch: float = 0.3, bore: float | None = None,
                 growth: float = 0.25, iterations: int = 60, seed: int = 0,
                 refine: np.ndarray | None = None) -> Section:
    """Triangles of the gear section: tooth 0 loaded at each of `radii` (a patch `patch` mm
    along the profile, boundary nodes at its ends), `teeth` neighbours on each side with the
    rim under them (radial cut lines tagged 'cut'), or the whole gear (None); the bore
    (default half the root radius). Element size (mm): h_patch at the load points growing
    by `growth` per mm, h_tooth over the loaded tooth and its root, growing by `growth` per
    mm away from it, at most h_far; refine (k, 2): more points (mm) where the size is
    h_patch (a whole flank's contact zone)."""
    section = tooth_section(gear)
    radii = [float(r) for r in np.atleast_1d(radii)]
    sites = [load_site(gear, r, patch, section) for r in radii]
    pitch = 2.0 * math.pi / gear.teeth
    root = section.root_radius
    bore = 0.5 * gear.root_radius_value if bore is None else bore
    centre = np.array([0.5 * (root + gear.tip_radius), 0.0])
    reach = 0.5 * (gear.tip_radius - root) + 0.5 * root * pitch
    points = np.array([st.point for st in sites])
    if refine is not None:
        points = np.vstack([points, np.asarray(refine, float).reshape(-1, 2)])
    near_tree = cKDTree(points)

    def size(xy):
        xy = np.atleast_2d(xy)
        near = near_tree.query(xy)[0]
        h = np.minimum(h_patch + growth * near,
                       h_tooth + growth * np.maximum(np.hypot(*(xy - centre).T) - reach, 0.0))
        return np.minimum(h, h_far)

    one = section.points(24, 24)[:, :2].copy()
    flank = section.flank_plus[:, :2]
    # tooth 0's polyline with the tip corners and the patch ends as vertices
    k_tip = [int(np.argmin(np.hypot(*(one - c).T))) for c in
             (section.flank_minus[-1, :2], section.flank_plus[0, :2])]
    k0 = int(np.argmin(np.hypot(*(one - flank[0]).T)))
    seg = one[k0:k0 + len(flank)]
    ends = []
    for st in sites:
        pair = []
        for e in st.patch_ends:
            k = k0 + int(np.argmin(np.hypot(*(seg - e).T)))
            one[k] = e
            pair.append(k)
        ends.append(sorted(pair))
    if len({k for pair in ends for k in pair}) != 2 * len(ends):
        raise ValueError("load patches overlap")
    order = list(range(-(gear.teeth // 2), gear.teeth - gear.teeth // 2)) if teeth is None \
        else list(range(-teeth, teeth + 1))
    step = len(one) - 1
    base0 = order.index(0) * step
    poly = np.vstack([_rotate(one, k * pitch)[:-1] for k in order]
                     + [_rotate(one, order[-1] * pitch)[-1:]])
    req = [j * step + k for j, tooth in enumerate(order) for k in k_tip]
    req += [base0 + k for pair in ends for k in pair]
    if teeth is None:
        pts, mark = _resample(poly, size, req)
        pts, mark = pts[:-1], mark[:-1]                    # closed: the last is the first
        tags = np.full(len(pts), "free", dtype=object)
        nb = max(12, int(math.ceil(2.0 * math.pi * bore / float(size(np.array([[bore, 0.0]]))[0]))))
        ang = np.linspace(0.0, 2.0 * math.pi, nb, endpoint=False)
        hole = np.column_stack([bore * np.cos(ang), bore * np.sin(ang)])
        loops = [(pts, tags, mark), (hole, np.full(nb, "bore", dtype=object), np.full(nb, -1))]
    else:
        half = (teeth + 0.5) * pitch
        # outline (space centre at -half to +half), cut line down, bore arc, cut line up
        top, mark = _resample(poly, size, req)
        a = np.array([bore * math.cos(half), bore * math.sin(half)])
        cut1, _ = _resample(np.array([top[-1], a]), size, [])
        ang = np.linspace(half, -half, 400)
        arc = np.column_stack([bore * np.cos(ang), bore * np.sin(ang)])
        arc_pts, _ = _resample(arc, size, [])
        cut2, _ = _resample(np.array([arc[-1], top[0]]), size, [])
        pts = np.vstack([top, cut1[1:], arc_pts[1:], cut2[1:-1]])
        tags = np.array(["free"] * (len(top) - 1) + ["cut"] * (len(cut1) - 1)
                        + ["bore"] * (len(arc_pts) - 1) + ["cut"] * (len(cut2) - 1), dtype=object)
        mark = np.concatenate([mark, np.full(len(pts) - len(top), -1)])
        loops = [(pts, tags, mark)]
    boundary, edge_tags, offset = [], [], 0
    for pts, tags, mark in loops:
        idx = np.arange(len(pts)) + offset
        tg = np.array(tags, dtype=object)
        for i, pair in enumerate(ends):
            where = [np.flatnonzero(mark == base0 + k) for k in pair]
            if all(len(w) for w in where):
                lo, hi = sorted(int(w[0]) for w in where)
                tg[lo:hi] = f"patch{i}"
        boundary.append(np.vstack([idx, np.roll(idx, -1)]))
        edge_tags.append(tg)
        offset += len(pts)
    fixed = np.vstack([lp[0] for lp in loops])
    p, t = _distmesh(fixed, [lp[0] for lp in loops], size, iterations, seed)
    tags = np.concatenate(edge_tags).astype(str)
    assert all(np.any(tags == f"patch{i}") for i in range(len(sites)))
    return Section(p, t, np.hstack(boundary), tags, sites, bore,
                   dict(h_patch=h_patch, h_tooth=h_tooth, h_far=h_far, growth=growth,
                        teeth=teeth, vertices=int(p.shape[1]), triangles=int(t.shape[1]),
                        min_angle=mesh_quality(p, t)))


def rectangle_section(length: float, thickness: float, h: float, seed: int = 0) -> Section:
    """A plate strip's section for checks against beam theory: x in [0, length] (held at
    x = 0, tag 'bore'), y in [-thickness/2, thickness/2], triangles of size h; its load
    site 0 the end x = length (tag 'patch0'), loaded along -y (a shear load on the end), the
    read-out point (length, 0) just inside."""
    def side(a, b, n):
        return a + np.linspace(0.0, 1.0, n, endpoint=False)[:, None] * (np.asarray(b) - a)

    L, t = float(length), float(thickness)
    nl, nt = max(2, int(math.ceil(L / h))), max(2, int(math.ceil(t / h)))
    corners = [np.array(c, float) for c in ((0.0, -t / 2), (L, -t / 2), (L, t / 2), (0.0, t / 2))]
    loop = np.vstack([side(corners[0], corners[1], nl), side(corners[1], corners[2], nt),
                      side(corners[2], corners[3], nl), side(corners[3], corners[0], nt)])
    tags = np.array(["free"] * nl + ["patch0"] * nt + ["free"] * nl + ["bore"] * nt)
    p, tri = _distmesh(loop, [loop], lambda xy: np.full(len(np.atleast_2d(xy)), h), 40, seed)
    idx = np.arange(len(loop))
    site = LoadSite(L, np.array([L, 0.0]), np.array([0.0, -1.0]),
                    np.array([[L, -t / 2], [L, t / 2]]), np.array([L - 1e-7, 0.0]), 0.0, t / 2)
    return Section(p, tri, np.vstack([idx, np.roll(idx, -1)]), tags, [site], 0.0,
                   dict(vertices=int(p.shape[1]), triangles=int(tri.shape[1])))


def _distmesh(fixed: np.ndarray, loops: list[np.ndarray], size, iterations: int, seed: int):
    """Triangulate the region inside loops[0] and outside the other loops: the fixed
    boundary points kept, interior points placed by the size function and relaxed as a
    truss (DistMesh), Delaunay triangles whose centroid lies inside kept."""
    rng = np.random.default_rng(seed)
    paths = [MplPath(np.vstack([lp, lp[:1]])) for lp in loops]
    dense = []
    for lp in loops:
        closed = np.vstack([lp, lp[:1]])
        seg = np.hypot(*np.diff(closed, axis=0).T)
        for a, b, L in zip(closed[:-1], closed[1:], seg):
            k = max(2, int(L / 0.01))
            dense.append(a + np.linspace(0.0, 1.0, k, endpoint=False)[:, None] * (b - a))
    tree = cKDTree(np.vstack(dense))

    def inside(xy):
        ok = paths[0].contains_points(xy)
        for pth in paths[1:]:
            ok &= ~pth.contains_points(xy)
        return ok

    def distance(xy):                                      # > 0 inside
        d, _ = tree.query(xy)
        return np.where(inside(xy), d, -d)

    lo, hi = fixed.min(axis=0), fixed.max(axis=0)
    h_min = float(size(fixed).min())
    # candidates on a jittered grid at the local size: a coarse grid refined by halving
    pts = []
    h = float(size(fixed).max()) * 2
    cells = [np.array([[x, y] for x in np.arange(lo[0], hi[0] + h, h)
                       for y in np.arange(lo[1], hi[1] + h, h)])]
    level = h
    grid = cells[0]
    while True:
        hs = size(grid)
        keep = hs >= level * 0.999
        pts.append(grid[keep])
        if level < h_min * 0.99 or not np.any(~keep):
            break
        rest = grid[~keep]
        level *= 0.5
        offs = np.array([[-1, -1], [-1, 1], [1, -1], [1, 1]]) * (0.5 * level)
        grid = (rest[:, None, :] + offs[None]).reshape(-1, 2)
    q = np.vstack(pts)
    q = q + rng.uniform(-0.1, 0.1, q.shape) * size(q)[:, None]
    q = q[distance(q) > 0.5 * size(q)]
    nf = len(fixed)
    p = np.vstack([fixed, q])
    for it in range(iterations):
        t = Delaunay(p).simplices
        cen = p[t].mean(axis=1)
        t = t[inside(cen)]
        bars = np.unique(np.sort(np.vstack([t[:, [0, 1]], t[:, [1, 2]], t[:, [0, 2]]]),
                                 axis=1), axis=0)
        vec = p[bars[:, 0]] - p[bars[:, 1]]
        L = np.hypot(*vec.T)
        hb = size(0.5 * (p[bars[:, 0]] + p[bars[:, 1]]))
        L0 = hb * 1.2 * math.sqrt(np.sum(L ** 2) / np.sum(hb ** 2))
        F = np.maximum(L0 - L, 0.0)
        Fv = (F / L)[:, None] * vec
        tot = np.zeros_like(p)
        np.add.at(tot, bars[:, 0], Fv)
        np.add.at(tot, bars[:, 1], -Fv)
        tot[:nf] = 0.0
        p = p + 0.2 * tot
        # interior points kept a third of the local size inside the boundary
        mov = p[nf:]
        d = distance(mov)
        hs = size(mov)
        near = d < 0.35 * hs
        if np.any(near):
            _, j = tree.query(mov[near])
            foot = tree.data[j]
            dirn = np.where(d[near][:, None] > 0, mov[near] - foot, foot - mov[near])
            nrm = np.hypot(*dirn.T)[:, None]
            dirn = dirn / np.maximum(nrm, 1e-12)
            mov[near] = foot + dirn * (0.35 * hs[near])[:, None]
            # a point pushed outside again (a thin place): drop it
            bad = np.zeros(len(mov), bool)
            bad[np.flatnonzero(near)] = distance(mov[near]) < 0.2 * hs[near]
            mov = mov[~bad]
        p = np.vstack([p[:nf], mov])
    t = Delaunay(p).simplices
    t = t[inside(p[t].mean(axis=1))]
    # orient counter-clockwise, drop unused points
    a = p[t[:, 1]] - p[t[:, 0]]
    b = p[t[:, 2]] - p[t[:, 0]]
    cw = a[:, 0] * b[:, 1] - a[:, 1] * b[:, 0] < 0
    t[cw] = t[cw][:, [0, 2, 1]]
    used = np.unique(t)
    assert np.all(used[:nf] == np.arange(nf)), "a boundary point fell out of the mesh"
    remap = np.full(len(p), -1)
    remap[used] = np.arange(len(used))
    p, t = p[used], remap[t]
    # every boundary segment must be a triangle edge
    bnd = set()
    for lp_start, lp in zip(np.cumsum([0] + [len(x) for x in loops[:-1]]), loops):
        idx = np.arange(len(lp)) + lp_start
        for i, j in zip(idx, np.roll(idx, -1)):
            bnd.add((min(i, j), max(i, j)))
    tri_edges = set(map(tuple, np.sort(np.vstack([t[:, [0, 1]], t[:, [1, 2]],
                                                  t[:, [0, 2]]]), axis=1).tolist()))
    missing = bnd - tri_edges
    assert not missing, f"{len(missing)} boundary segments not recovered"
    return p.T.copy(), t.T.copy()


def mesh_quality(p: np.ndarray, t: np.ndarray) -> float:
    """The smallest angle (deg) of the triangles."""
    P = p.T[t.T]
    ang = []
    for k in range(3):
        a = P[:, (k + 1) % 3] - P[:, k]
        b = P[:, (k + 2) % 3] - P[:, k]
        c = np.sum(a * b, axis=1) / (np.hypot(*a.T) * np.hypot(*b.T))
        ang.append(np.degrees(np.arccos(np.clip(c, -1, 1))))
    return float(np.min(ang))


# ----------------------------------------------------------------------------- half-space

def _gauss(n: int, a: float, b: float):
    x, w = np.polynomial.legendre.leggauss(n)
    return 0.5 * (a + b) + 0.5 * (b - a) * x, 0.5 * (b - a) * w


def halfspace_strip(width: float, depth: float, E: float, nu: float) -> float:
    """Plane strain: a unit line load (N/mm) spread evenly over a strip `width` (mm) wide on
    a half-space; the strip's mean surface displacement less the mean displacement at
    `depth` (mm) below its points (mm per N/mm): Weber's contact flattening to a depth, as
    the contact solver measures the compression (influence.InfluenceOperator, `reference`).
    Boussinesq's point force integrated along the infinite line (the differences converge),
    then over the strip (the mean of ln|x - x'| over it is ln(width) - 3/2)."""
    G = E / (2.0 * (1.0 + nu))
    x, w = _gauss(64, 0.0, width)
    dx = x[:, None] - x[None, :]
    ww = w[:, None] * w[None, :] / width ** 2
    mean_ln_depth = float(np.sum(ww * 0.5 * np.log(dx ** 2 + depth ** 2)))
    mean_d2 = float(np.sum(ww * depth ** 2 / (dx ** 2 + depth ** 2)))
    return (4.0 * (1.0 - nu) * (mean_ln_depth - math.log(width) + 1.5)
            - 2.0 * mean_d2) / (4.0 * math.pi * G)


def _primitive(a, b):
    """∫_0^a ∫_0^b ds dt / sqrt(s² + t²) (signed a, b)."""
    a, b = np.asarray(a, float), np.asarray(b, float)
    A, B = np.abs(a), np.abs(b)
    with np.errstate(divide="ignore", invalid="ignore"):
        v = np.where(A > 0, A * np.arcsinh(B / np.where(A > 0, A, 1.0)), 0.0) + \
            np.where(B > 0, B * np.arcsinh(A / np.where(B > 0, B, 1.0)), 0.0)
    return np.sign(a) * np.sign(b) * v


def halfspace_patch(width: float, length: float, depth: float, E: float, nu: float,
                    offset: float = 0.0) -> float:
    """A unit force (N) spread evenly over a width × length (mm) rectangle on a half-space;
    at the receiving rectangle of the same size `offset` mm away along `length` (0: the
    loaded one), its mean surface displacement less the mean displacement at `depth` (mm)
    below its points (mm per N), as influence.InfluenceOperator with a reference depth
    measures the compression: Love's rectangle (Boussinesq integrated) at the surface,
    Boussinesq by Gauss quadrature at depth."""
    G = E / (2.0 * (1.0 + nu))
    p = 1.0 / (width * length)
    xs, wx = _gauss(40, 0.0, width)
    ys, wy = _gauss(40, offset, offset + length)
    X, Y = np.meshgrid(xs, ys, indexing="ij")
    W = wx[:, None] * wy[None, :] / (width * length)
    I = (_primitive(width - X, length - Y) - _primitive(-X, length - Y)
         - _primitive(width - X, -Y) + _primitive(-X, -Y))
    surface = float(np.sum(W * I)) * p / (2.0 * math.pi * G) * (1.0 - nu)
    xs2, wx2 = _gauss(16, 0.0, width)
    ys2, wy2 = _gauss(16, 0.0, length)
    S = np.stack(np.meshgrid(xs2, ys2, indexing="ij"), -1).reshape(-1, 2)
    Ws = (wx2[:, None] * wy2[None, :]).ravel() * p
    R = np.sqrt((X.ravel()[:, None] - S[None, :, 0]) ** 2
                + (Y.ravel()[:, None] - S[None, :, 1]) ** 2 + depth ** 2)
    at_depth = ((2.0 * (1.0 - nu) / R + depth ** 2 / R ** 3) @ Ws) / (4.0 * math.pi * G)
    return surface - float(W.ravel() @ at_depth)


# ----------------------------------------------------------------------------- 2D

def _facet_index(facets: np.ndarray, pairs: np.ndarray) -> np.ndarray:
    """Indices into a mesh's facets (2, nf) of the vertex pairs (2, k)."""
    lookup = {tuple(f): i for i, f in enumerate(np.sort(facets, axis=0).T.tolist())}
    return np.array([lookup[tuple(e)] for e in np.sort(pairs, axis=0).T.tolist()], int)


def plane_strain(S: Section, E: float = E_STEEL, nu: float = NU_STEEL,
                 stiff_below: float | None = None) -> dict:
    """The section in plane strain (ElementTriP2), bore (and cut lines) held, under a unit
    line load (1 N per mm of face) on each site's patch in turn: per site the patch-mean
    normal displacement `surface` and the normal displacement where the line of action
    crosses the centre line, `centre` (mm per N/mm = mm²/N); the dofs. stiff_below (mm):
    the triangles whose centroid lies inside that radius 10⁴ times stiffer (a rigid body
    under the teeth: the teeth alone, held at that circle)."""
    from skfem import (
        Basis,
        BilinearForm,
        ElementTriP0,
        ElementTriP2,
        ElementVector,
        FacetBasis,
        Functional,
        LinearForm,
        MeshTri,
        asm,
        condense,
        solve,
    )
    from skfem.helpers import ddot, sym_grad, trace
    from skfem.models.elasticity import lame_parameters, linear_elasticity

    mesh = MeshTri(S.p, S.t)
    e = ElementVector(ElementTriP2())
    basis = Basis(mesh, e, intorder=4)
    if stiff_below is None:
        K = asm(linear_elasticity(*lame_parameters(E, nu)), basis)
    else:
        lam_, mu_ = lame_parameters(E, nu)
        centroid = np.hypot(*S.p[:, S.t].mean(axis=1))
        p0 = basis.with_element(ElementTriP0())
        scale = p0.zeros() + 1.0
        scale[centroid < stiff_below] = 1e4

        @BilinearForm
        def form(u, v, w):
            eps_u, eps_v = sym_grad(u), sym_grad(v)
            return w.s * (lam_ * trace(eps_u) * trace(eps_v) + 2.0 * mu_ * ddot(eps_u, eps_v))

        K = asm(form, basis, s=p0.interpolate(scale))
    held = _facet_index(mesh.facets, S.edges[:, np.isin(S.tags, ["bore", "cut"])])
    D = basis.get_dofs(facets=held).all()
    surface, centre = [], []
    for i, site in enumerate(S.sites):
        patch = _facet_index(mesh.facets, S.edges[:, S.tags == f"patch{i}"])
        fb = FacetBasis(mesh, e, facets=patch, intorder=6)
        area = float(asm(Functional(lambda w: 1.0 + 0.0 * w.x[0]), fb))
        n = site.normal

        @LinearForm
        def traction(v, w):
            return (n[0] * v[0] + n[1] * v[1]) / area

        f = asm(traction, fb)
        u = solve(*condense(K, f, D=D))
        surface.append(float(f @ u))
        centre.append(float(n @ (basis.probes(site.centre[:, None]) @ u)))
    return dict(surface=surface, centre=centre, dofs=int(K.shape[0]))


# ----------------------------------------------------------------------------- 3D

def graded(lo: float, hi: float, fine: list[tuple[float, float, float]], coarse: float,
           growth: float = 0.3, breaks=()) -> np.ndarray:
    """Node coordinates on [lo, hi] (mm): element size min(coarse, h_k + growth·distance
    to [a_k, b_k]) over the fine zones (a_k, b_k, h_k); lo, hi, the zones' ends and
    `breaks` are nodes."""
    def size(x):
        h = np.full_like(x, coarse)
        for a, b, hk in fine:
            h = np.minimum(h, hk + growth * np.maximum(0.0, np.maximum(a - x, x - b)))
        return h

    pts = sorted({lo, hi, *[v for a, b, _ in fine for v in (a, b) if lo <= v <= hi],
                  *[v for v in breaks if lo <= v <= hi]})
    out = [np.array([pts[0]])]
    for a, b in zip(pts[:-1], pts[1:]):
        s = np.linspace(a, b, 2001)
        w = 1.0 / size(s)
        cum = np.concatenate([[0.0], np.cumsum(0.5 * (w[1:] + w[:-1]) * np.diff(s))])
        n = max(1, int(math.ceil(cum[-1] - 1e-6)))
        x = np.interp(np.linspace(0.0, cum[-1], n + 1), cum, s)[1:]
        x[-1] = b
        out.append(x)
    return np.concatenate(out)


def extrude(p2: np.ndarray, t2: np.ndarray, z: np.ndarray, twist: float = 0.0):
    """MeshTet of the triangles (p2 (2, n), t2 (3, m)) extruded over the z-planes: each
    prism cut into three tetrahedra by its vertices' global order (the quad faces' diagonals
    then agree between neighbours). Vertex k of plane j is j·n + k. twist (rad/mm): plane
    z's section turned by twist·z about the axis (a helical gear's teeth: the section
    screwed along the face, CylindricalGear.twist_per_length)."""
    from skfem import MeshTet

    n, nz = p2.shape[1], len(z)
    p = np.vstack([np.tile(p2, nz), np.repeat(z, n)[None, :]])
    if twist:
        turn = twist * p[2]
        c, s = np.cos(turn), np.sin(turn)
        p[:2] = np.vstack([c * p[0] - s * p[1], s * p[0] + c * p[1]])
    t = np.sort(t2, axis=0)                            # a < b < c by global index
    tets = []
    for j in range(nz - 1):
        a0, b0, c0 = t + j * n
        a1, b1, c1 = t + (j + 1) * n
        tets += [np.vstack([a0, b0, c0, c1]), np.vstack([a0, b0, b1, c1]),
                 np.vstack([a0, a1, b1, c1])]
    t3 = np.hstack(tets)
    # positive orientation
    P = p.T[t3.T]
    vol = np.einsum("ij,ij->i", np.cross(P[:, 1] - P[:, 0], P[:, 2] - P[:, 0]), P[:, 3] - P[:, 0])
    t3[:, vol < 0] = t3[[0, 2, 1, 3]][:, vol < 0]
    return MeshTet(p, t3)


def nested_dissection(coords: np.ndarray, graph: sp.csr_matrix, leaf: int = 48):
    """Geometric nested dissection of a graph (vertex coordinates coords (d, n)): split at
    the median of the longest extent, the split's side adjacent to the other the separator,
    recursively. Returns the blocks (vertex arrays) in post-order (each separator after its
    two halves) and each block's parent (-1: the root)."""
    graph = sp.csr_matrix(graph)
    blocks, parent = [], []

    # candidate cuts: planes normal to x, y, z and the two diagonals of x-y, and radial
    # half-planes (the polar angle about the gear's axis, its branch on the far side)
    feats = np.vstack([coords, (coords[0] + coords[1]) / math.sqrt(2),
                       (coords[0] - coords[1]) / math.sqrt(2),
                       np.arctan2(coords[1], coords[0])])

    def rec(idx) -> int:
        if len(idx) > leaf:
            sub = graph[idx][:, idx]
            proj = feats[:, idx]
            best = None
            qs = np.linspace(0.3, 0.7, 9) if len(idx) > 20 * leaf else [0.5]
            for p in proj:
                for q in qs:
                    left = p <= np.quantile(p, q)
                    if left.all() or not left.any():
                        continue
                    sep = left & ((sub @ (~left).astype(float)) > 0)
                    nl, nr = int(np.sum(left & ~sep)), int(np.sum(~left))
                    score = sep.sum() / max(nl * nr, 1)
                    if best is None or score < best[0]:
                        best = (score, left, sep)
            if best is not None:
                _, left, sep = best
                kids = [rec(idx[left & ~sep]) if np.any(left & ~sep) else -1,
                        rec(idx[~left])]
                blocks.append(idx[sep])
                parent.append(-1)
                me = len(blocks) - 1
                for k in kids:
                    if k >= 0:
                        parent[k] = me
                return me
        blocks.append(idx)
        parent.append(-1)
        return len(blocks) - 1

    rec(np.arange(coords.shape[1]))
    return blocks, np.array(parent)


class Factor:
    """Cholesky factor of K on its free dofs: a multifrontal factorisation (dense fronts by
    LAPACK/BLAS) on a geometric nested-dissection order of the nodes (a node's components
    together). `solve` takes loads on all dofs and gives u on all dofs (held ones 0).

    threads: BLAS threads for the fronts of at least `big` rows (and the solves' blocks of
    at least `big` rows); smaller ones, and everything on 1 thread, run single-threaded
    (OpenBLAS's threaded potrf runs 10-100x slower than its one thread on 2 busy cores,
    and a thread team costs more than a small front's work). calibrate: first time a
    front-sized Cholesky and update (1500 rows) on one thread and on `threads`, and keep
    one thread unless the team is at least 1.3 times as fast (a busy machine);
    `threads_used` says which. `peak_front_bytes`: the largest front (a dense matrix) met;
    `update_bytes_peak`: the most memory the pending update matrices held at once."""

    def __init__(self, K: sp.csr_matrix, free: np.ndarray, coords: np.ndarray,
                 threads: int = 1, big: int = 1200, calibrate: bool = True):
        self.threads, self.big = int(threads), int(big)
        self.calibration = self._calibrate() if calibrate and self.threads > 1 else {}
        if self.calibration and self.calibration["speedup"] < 1.3:
            self.threads = 1
        self.threads_used = self.threads
        with self._limit(1):
            self._factor(K, free, coords)

    def _calibrate(self, n: int = 1500) -> dict:
        """Seconds of a Cholesky, a triangular solve and a symmetric update of n rows on
        one BLAS thread and on `threads` (the best of two tries each)."""
        from scipy.linalg import cholesky, solve_triangular
        from scipy.linalg.blas import dsyrk

        rng = np.random.default_rng(0)
        with self._limit(1):
            M = rng.standard_normal((n, n))
            A = M @ M.T + n * np.eye(n)
        B = np.asfortranarray(rng.standard_normal((n, n)))
        seconds = {}
        for t in (1, self.threads):
            best = math.inf
            for _ in range(2):
                with self._limit(t):
                    t0 = time.perf_counter()
                    L = cholesky(A, lower=True, check_finite=False)
                    X = np.asfortranarray(solve_triangular(L, B, lower=True,
                                                           check_finite=False).T)
                    dsyrk(-1.0, X, beta=1.0, c=np.asfortranarray(A), lower=1)
                    best = min(best, time.perf_counter() - t0)
            seconds[t] = best
        return dict(one=seconds[1], team=seconds[self.threads],
                    speedup=seconds[1] / seconds[self.threads])

    def _limit(self, n: int):
        """BLAS on n threads within the block (one scan of the loaded libraries per
        factor: threadpool_limits rescans them each time, 4 ms)."""
        if getattr(self, "_controller", None) is None:
            from threadpoolctl import ThreadpoolController

            self._controller = ThreadpoolController()
        return self._controller.limit(limits=n, user_api="blas")

    def _factor(self, K, free, coords):
        from contextlib import nullcontext

        from scipy.linalg import cholesky
        from scipy.linalg.blas import dsyrk, dtrsm

        self.free = free
        A = K[free][:, free].tocsr()
        loc, node = np.unique(np.round(coords[:, free], 9), axis=1, return_inverse=True)
        node = node.ravel()
        P = sp.csr_matrix((np.ones(len(free)), (np.arange(len(free)), node)),
                          shape=(len(free), loc.shape[1]))
        G = (P.T @ (abs(A) @ P)).tocsr()
        t0 = time.perf_counter()
        blocks, parent = nested_dissection(loc, G)
        t_order = time.perf_counter() - t0
        # dofs block by block: the permutation and each block's range
        dofs_of_node = np.argsort(node, kind="stable")
        starts = np.searchsorted(node[dofs_of_node], np.arange(loc.shape[1]))
        counts = np.bincount(node, minlength=loc.shape[1])
        perm, ranges, at = [], [], 0
        for blk in blocks:
            d = np.concatenate([np.zeros(0, np.int64)] + [
                dofs_of_node[starts[k]:starts[k] + counts[k]] for k in blk])
            perm.append(d)
            ranges.append((at, at + len(d)))
            at += len(d)
        self.perm = np.concatenate(perm)
        Ap = A[self.perm][:, self.perm].tocsr()
        Ap.sort_indices()
        n = Ap.shape[0]
        children = [[] for _ in blocks]
        for k, p in enumerate(parent):
            if p >= 0:
                children[p].append(k)
        lookup = np.full(n, -1, dtype=np.int64)
        self.L, updates, self.flops = [], {}, 0.0
        self.peak_front_bytes, self.update_bytes_peak, pending = 0, 0, 0
        dense = dense_big = flops_big = extend = 0.0
        for s, (a, b) in enumerate(ranges):
            rows = Ap[a:b]
            cols = rows.indices
            later = cols[cols >= b]
            bset = [later] + [updates[c][0][updates[c][0] >= b] for c in children[s]]
            B = np.unique(np.concatenate(bset)) if bset else np.zeros(0, int)
            k = b - a
            idx = np.concatenate([np.arange(a, b), B])
            lookup[idx] = np.arange(len(idx))
            # the front, its lower triangle only (Fortran order for BLAS)
            t_extend = time.perf_counter()
            F = np.zeros((len(idx), len(idx)), order="F")
            self.peak_front_bytes = max(self.peak_front_bytes, F.nbytes)
            r = np.repeat(np.arange(k), np.diff(rows.indptr))
            keep = cols >= a
            lc = lookup[cols[keep]]
            F[np.maximum(r[keep], lc), np.minimum(r[keep], lc)] = rows.data[keep]
            for c in children[s]:
                Bc, Uc = updates.pop(c)
                pending -= Uc.nbytes
                li = lookup[Bc]
                for j in range(len(li)):                 # lower triangle, column by column
                    column = F[:, li[j]]
                    column[li[j:]] += Uc[j:, j]
                del Uc
            extend += time.perf_counter() - t_extend
            lookup[idx] = -1
            if k == 0:
                if len(B):
                    updates[s] = (B, F)
                    pending += F.nbytes
                continue
            t_dense = time.perf_counter()
            team = self.threads > 1 and len(idx) >= self.big
            with self._limit(self.threads) if team else nullcontext():
                Lss = cholesky(F[:k, :k], lower=True, check_finite=False)
                # Lbs·Lssᵀ = F_bs, on the right in place (one copy of F_bs, Fortran order)
                Lbs = dtrsm(1.0, Lss, np.asfortranarray(F[k:, :k]), side=1, lower=1,
                            trans_a=1, overwrite_b=1)
                if len(B):
                    Ub = np.asfortranarray(F[k:, k:])
                    del F
                    Ub = dsyrk(-1.0, Lbs, beta=1.0, c=Ub, lower=1, overwrite_c=1)
                    updates[s] = (B, Ub)
                    pending += Ub.nbytes
            dense += time.perf_counter() - t_dense
            if len(idx) >= self.big:
                dense_big += time.perf_counter() - t_dense
                flops_big += k ** 3 / 3 + k * k * len(B) + k * len(B) ** 2
            self.update_bytes_peak = max(self.update_bytes_peak, pending)
            self.L.append((a, b, Lss, B, Lbs))
            self.flops += k ** 3 / 3 + k * k * len(B) + k * len(B) ** 2
            F = None
        self.n = n
        # seconds: the ordering, the dense kernels (and those of the fronts of `big` rows
        # and more, which run on `threads`), the fronts' assembly (extend-add), all of it;
        # the big fronts' flops
        self.timing = dict(order=t_order, dense=dense, dense_big=dense_big, extend=extend,
                           total=time.perf_counter() - t0, flops_big=flops_big)
        self.nnz = int(sum(l[2].size / 2 + l[4].size for l in self.L))

    def solve(self, f: np.ndarray) -> np.ndarray:
        with self._limit(1):
            return self._solve(f)

    def _solve(self, f: np.ndarray) -> np.ndarray:
        from contextlib import nullcontext

        from scipy.linalg import solve_triangular

        f = np.asarray(f, float)
        X = f[self.free][self.perm].copy()
        one = X.ndim == 1
        if one:
            X = X[:, None]
        many = self.threads > 1 and X.shape[1] > 8

        def limit(a, b, B):
            return self._limit(self.threads) if many and b - a + len(B) >= self.big \
                else nullcontext()

        for a, b, Lss, B, Lbs in self.L:
            with limit(a, b, B):
                xs = solve_triangular(Lss, X[a:b], lower=True, check_finite=False)
                X[a:b] = xs
                if len(B):
                    X[B] -= Lbs @ xs
        for a, b, Lss, B, Lbs in reversed(self.L):
            with limit(a, b, B):
                rhs = X[a:b] - Lbs.T @ X[B] if len(B) else X[a:b]
                X[a:b] = solve_triangular(Lss, rhs, lower=True, trans="T",
                                          check_finite=False)
        u = np.zeros(f.shape if not one else f.shape + (1,))
        tmp = np.empty_like(X)
        tmp[self.perm] = X
        u[self.free] = tmp
        return u[:, 0] if one else u


class Tooth3D:
    """The section extruded over z in [0, b/2] (z = 0 mid-face, z-planes `z`), quadratic
    tetrahedra; factorised twice: symmetric about mid-face (u_z = 0 on z = 0) and
    antisymmetric (u_x = u_y = 0 there). Bore (and cut faces) held; z = b/2 free.
    factorise=False: `factors` stays empty and `factor(kind)` factorises one half on demand
    (one factor in memory at a time on a large body).

    The whole face instead (z-planes from -b/2 to b/2: z[0] < 0; a helical tooth, `twist`
    rad/mm, has no mid-face symmetry): both end faces free, one factor, kind "full".
    threads: the factors' BLAS threads for their large fronts (Factor)."""

    def __init__(self, S: Section, z: np.ndarray, E: float = E_STEEL, nu: float = NU_STEEL,
                 factorise: bool = True, twist: float = 0.0, threads: int = 1):
        import time

        from skfem import Basis, ElementTetP2, ElementVector, asm
        from skfem.models.elasticity import lame_parameters, linear_elasticity

        t0 = time.perf_counter()
        self.S, self.z, self.E, self.nu = S, np.asarray(z, float), E, nu
        self.twist, self.threads = float(twist), int(threads)
        self.whole = bool(self.z[0] < -1e-9)
        if twist and not self.whole:
            raise ValueError("a twisted tooth has no mid-face symmetry: give the whole face")
        self.mesh = extrude(S.p, S.t, self.z, twist)
        self.element = ElementVector(ElementTetP2())
        self.basis = Basis(self.mesh, self.element, intorder=2)
        self.K = asm(linear_elasticity(*lame_parameters(E, nu)), self.basis).tocsr()
        t1 = time.perf_counter()
        n2 = S.p.shape[1]
        # boundary facets: 2D edge tag and z-range
        bf = self.mesh.boundary_facets()
        fv = self.mesh.facets[:, bf]
        v2 = fv % n2
        zs = self.mesh.p[2, fv]
        tag_of = {tuple(e): tg for e, tg in zip(np.sort(S.edges, axis=0).T.tolist(), S.tags)}
        tags = np.full(len(bf), "end", dtype=object)
        for k in range(len(bf)):
            u = sorted(set(v2[:, k].tolist()))
            if len(u) == 2:
                tags[k] = tag_of.get(tuple(u), "free")
        self.facets, self.facet_tags = bf, tags.astype(str)
        self.facet_z = (zs.min(axis=0), zs.max(axis=0))
        held = bf[np.isin(self.facet_tags, ["bore", "cut"])]
        held_dofs = self.basis.get_dofs(facets=held).all()
        mid = bf[(self.facet_tags == "end") & (zs.max(axis=0) < 1e-9)]
        mid_dofs = self.basis.get_dofs(facets=mid)
        comp = {name: mid_dofs.all(name) for name in ("u^1", "u^2", "u^3")}
        nd = self.K.shape[0]
        self.dofs = nd
        self._free = {}
        halves = (("sym", comp["u^3"]), ("anti", np.concatenate([comp["u^1"], comp["u^2"]])))
        for kind, extra in ((("full", np.zeros(0, np.int64)),) if self.whole else halves):
            fixed = np.zeros(nd, bool)
            fixed[held_dofs] = True
            fixed[extra] = True
            self._free[kind] = np.flatnonzero(~fixed)
        self.factors = {kind: self.factor(kind) for kind in self._free} if factorise else {}
        t2 = time.perf_counter()
        self.timing = dict(assemble=t1 - t0, factor=t2 - t1)

    def factor(self, kind: str) -> Factor:
        """The Cholesky factor of the half `kind` ("sym" or "anti"; "full": the whole
        face)."""
        return Factor(self.K, self._free[kind], self.basis.doflocs, self.threads)

    def patch_load(self, site: int, z0: float, z1: float) -> np.ndarray:
        """Consistent nodal loads (N) of a unit force spread evenly over site `site`'s patch
        facets with z in [z0, z1] (mesh planes), along its normal."""
        from skfem import FacetBasis, Functional, LinearForm, asm

        lo, hi = self.facet_z
        sel = self.facets[(self.facet_tags == f"patch{site}") & (lo >= z0 - 1e-9)
                          & (hi <= z1 + 1e-9)]
        fb = FacetBasis(self.mesh, self.element, facets=sel, intorder=4)
        area = float(asm(Functional(lambda w: 1.0 + 0.0 * w.x[0]), fb))
        n = self.S.sites[site].normal

        @LinearForm
        def traction(v, w):
            return (n[0] * v[0] + n[1] * v[1]) / area

        return asm(traction, fb)

    def normal_at(self, u: np.ndarray, xy: np.ndarray, site: int = 0) -> np.ndarray:
        """Displacement of u along site `site`'s normal at the point xy (mm) of every
        z-plane (rows; u (n,) or (n, k))."""
        zz = np.clip(self.z, self.z[0] + 1e-7, self.z[-1] - 1e-7)
        pts = np.vstack([np.tile(np.asarray(xy, float)[:, None], (1, len(zz))), zz])
        vals = self.basis.probes(pts) @ u
        vals = vals.reshape((3, len(zz)) + np.shape(u)[1:])
        n = self.S.sites[site].normal
        return n[0] * vals[0] + n[1] * vals[1]


# ----------------------------------------------------------------------------- the study

def model_line(c: float, length: float, start: float, end: float, patches, nodes: int = 481,
               end_factor: float = 1.0, end_layer: float = 0.0):
    """The compliance model's face line (contact.compliance.FaceCoupling, free ends, its end
    layer `end_layer` mm) under a unit force spread evenly over each patch (z0, z1) in turn:
    its node positions, the deflections (nodes × patches, mm per N, slice compliance c
    mm²/N) and each patch's work-conjugate (load-weighted mean) deflection (mm per N).
    end_factor β != 1: an end softening proposed before the end layer, the flexibility
    D·G·D with D = diag(sqrt(f)),
    f(z) = 1 + (β - 1)·(exp(-2(z - start)/λ) + exp(-2(end - z)/λ)) (symmetric, as the
    contact solver needs; over half a coupling length from each end, so that mid-face
    keeps G)."""
    from toothcontact.analytic.hats import hats
    from toothcontact.contact.structure import FaceCoupling

    line = FaceCoupling(start, end, length, nodes, end_layer)
    G = line.flexibility
    if end_factor != 1.0:
        z = line.nodes
        f = 1.0 + (end_factor - 1.0) * (np.exp(-2.0 * (z - start) / length)
                                        + np.exp(-2.0 * (end - z) / length))
        d = np.sqrt(f)
        G = d[:, None] * G * d[None, :]
    Q = np.zeros((nodes, len(patches)))
    for j, (z0, z1) in enumerate(patches):
        zs = np.linspace(z0, z1, 4001)
        w = np.full(len(zs), 1.0 / len(zs))
        left, share = hats(line.nodes, zs)
        np.add.at(Q[:, j], left, w * (1.0 - share))
        np.add.at(Q[:, j], left + 1, w * share)
    W = c * G @ Q
    return line.nodes, W, np.einsum("ij,ij->j", Q, W)


def matching_end_factor(ratio: float, length: float, half: float, patches) -> float:
    """The end factor β (model_line) whose line, coupling length `length` on [-half, half],
    deflects under the end patch (patches[1]) `ratio` times as far as under the mid-face one
    (patches[0])."""
    from scipy.optimize import brentq

    def f(beta):
        at = model_line(1.0, length, -half, half, patches, end_factor=beta)[2]
        return at[1] / at[0] - ratio

    return float(brentq(f, 0.2, 20.0, xtol=1e-6))


def matching_length(ratio: float, half: float, patch) -> float:
    """The coupling length λ (mm) whose face line (free ends on [-half, half]) deflects
    `ratio` (1/mm) times the slice compliance under a unit force on `patch` (its
    work-conjugate mean), i.e. the λ that makes the model's point-load deflection over its
    uniform-load one equal the FE's."""
    from scipy.optimize import brentq

    def f(lam):
        return model_line(1.0, lam, -half, half, [patch])[2][0] - ratio

    return float(brentq(f, 0.05, 200.0, xtol=1e-6))


def fit_decay(z: np.ndarray, w: np.ndarray, half: float, start: float, stop: float | None = None):
    """The decay length L (mm) and amplitude A (mm/N) of w(z) ≈ A·cosh((half - |z|)/L)/
    cosh(half/L) (the free-ended Pasternak line's Green's function for a load at z = 0)
    fitted by least squares over start <= |z| <= stop (default: the face end), its rms
    residual over the peak; and the plain exponential's length from a log-linear fit over
    the same points."""
    from scipy.optimize import curve_fit

    z, w = np.abs(np.asarray(z, float)), np.asarray(w, float)
    stop = half if stop is None else stop
    m = (z >= start - 1e-9) & (z <= stop + 1e-9)
    scale = float(w[m].max())

    def shape(x, A, L):
        return A * np.cosh((half - x) / L) / np.cosh(half / L)

    slope = np.polyfit(z[m], np.log(w[m]), 1)[0]
    (A, L), _ = curve_fit(shape, z[m], w[m] / scale, p0=(2.0, -1.0 / slope))
    rms = float(np.sqrt(np.mean((shape(z[m], A, L) - w[m] / scale) ** 2)))
    return dict(L=float(L), A=float(A * scale), L_exp=float(-1.0 / slope), rms=rms,
                points=int(m.sum()))


#: mesh levels of face_study (mm): section sizes at the patch, over the loaded tooth, far;
#: their growth per mm; z-layers at the patches and elsewhere
LEVELS = {
    "coarse": dict(h_patch=0.3, h_tooth=1.2, h_far=6.0, growth=0.4, hz_fine=0.5, hz_coarse=3.0),
    "medium": dict(h_patch=0.15, h_tooth=0.9, h_far=5.0, growth=0.35, hz_fine=0.25,
                   hz_coarse=2.0),
}


def face_study(gear, radii=(30.0,), h_patch=0.3, h_tooth=1.2, h_far=6.0, growth=0.4,
               hz_fine=0.5, hz_coarse=3.0, patch=(0.3, 1.0), fit_from=(2.0, 3.0, 4.0),
               E: float = E_STEEL, nu: float = NU_STEEL, log=print) -> dict:
    """FE (2D plane strain of the whole gear, and 3D) against the compliance model for
    `gear`, tooth 0 loaded on its flank at each of `radii`: a uniform line load over the
    face, a patch (patch[0] mm up the profile × patch[1] mm along the face) in mid-face and
    one touching a face end. Deflections are per unit load, along the load's transverse
    normal: 'centre' the point where the line of action crosses the tooth's centre line (the
    model's reference), 'surface' the patch's work-conjugate mean less the half-space
    compression from the surface to the half-thickness (Weber's flattening, which the
    contact solver adds to the model: halfspace_strip / halfspace_patch, at the end face
    plus φ times the mirrored patch's, influence.free_end_factor). See
    benchmarks/fe_tooth_face.py for the reported quantities."""
    import time

    from toothcontact.contact.compliance import ToothCompliance
    from toothcontact.contact.influence import free_end_factor
    from toothcontact.contact.structure import end_layer

    t0 = time.perf_counter()
    width, length = patch
    half = 0.5 * gear.face_width
    S = section_mesh(gear, radii, h_patch, h_tooth, h_far, growth=growth, patch=width)
    t_mesh = time.perf_counter() - t0
    ps = plane_strain(S, E, nu)
    t_2d = time.perf_counter() - t0 - t_mesh
    z = graded(0.0, half, [(0.0, 0.5 * length, hz_fine), (half - length, half, hz_fine)],
               hz_coarse, 0.3, breaks=(half - 0.5 * length,))
    T = Tooth3D(S, z, E, nu)
    log(f"  mesh: {S.info['vertices']} vertices, {S.info['triangles']} triangles "
        f"(min angle {S.info['min_angle']:.1f} deg), {len(z)} z-planes on half the face; "
        f"2D {ps['dofs']} dofs; 3D {T.dofs} dofs per half, assembly "
        f"{T.timing['assemble']:.0f} s, two factorisations {T.timing['factor']:.0f} s")
    teeth = ToothCompliance(gear, E, nu)
    zz = np.concatenate([-z[::-1][:-1], z])                    # the whole face
    k_mid, k_end = len(z) - 1, len(z) - 1 + int(np.argmin(np.abs(z - (half - 0.5 * length))))
    mid_patch, end_patch = (-0.5 * length, 0.5 * length), (half - length, half)
    phi = free_end_factor(nu)
    out = dict(gear=dict(teeth=gear.teeth, module=gear.normal_module,
                         face_width=gear.face_width, root_radius=gear.root_radius_value,
                         tip_radius=gear.tip_radius, bore=S.bore),
               mesh=dict(S.info, z_planes=len(z), dofs_2d=ps["dofs"], dofs_3d_half=T.dofs,
                         assemble_s=T.timing["assemble"], factor_s=T.timing["factor"],
                         mesh_s=t_mesh, plane_strain_s=t_2d),
               patch=dict(profile=width, face=length), sites=[])
    # every site's loads in one solve per factor; every read-out point in one probe
    loads = []
    for i in range(len(S.sites)):
        loads.append((T.patch_load(i, 0.0, half) * half,          # 1 N/mm over the face
                      T.patch_load(i, 0.0, 0.5 * length),         # 1 N on the half patch
                      T.patch_load(i, half - length, half)))      # 1 N on the end patch
    us = T.factors["sym"].solve(np.column_stack(
        [col for f_line, unit_mid, unit_end in loads
         for col in (f_line, 0.5 * unit_mid, 0.5 * unit_end)]))
    ua = T.factors["anti"].solve(np.column_stack([0.5 * unit_end for *_, unit_end in loads]))
    xy = [p for site in S.sites for p in
          (site.centre, site.patch_ends.mean(axis=0) + 1e-6 * site.normal)]  # flank: on the chord
    zc = np.clip(z, 1e-7, half - 1e-7)
    probe = T.basis.probes(np.vstack([np.repeat(np.array(xy).T, len(z), axis=1),
                                      np.tile(zc, len(xy))]))
    values = (probe @ np.hstack([us, ua])).reshape(3, len(xy), len(z), -1)
    for i, site in enumerate(S.sites):
        unit_mid, unit_end = loads[i][1], loads[i][2]
        u_line, u_mid = us[:, 3 * i], us[:, 3 * i + 1]
        u_end = us[:, 3 * i + 2] + ua[:, i]
        n = site.normal
        rows = {}
        for j, name in enumerate(("centre", "flank")):
            v = n[0] * values[0, 2 * i + j] + n[1] * values[1, 2 * i + j]   # (z, columns)
            s_line, s_mid, s_end = v[:, 3 * i], v[:, 3 * i + 1], v[:, 3 * i + 2]
            a_end = v[:, us.shape[1] + i]
            rows[name] = dict(line=np.concatenate([s_line[::-1][:-1], s_line]),
                              mid=np.concatenate([s_mid[::-1][:-1], s_mid]),
                              end=np.concatenate([(s_end - a_end)[::-1][:-1], s_end + a_end]))
        c, lam = (float(v) for v in teeth.at(site.radius))
        depth = teeth.half_thickness(site.radius)
        hs_strip = halfspace_strip(width, depth, E, nu)
        hs_patch = halfspace_patch(width, length, depth, E, nu)
        hs_end = hs_patch + phi * halfspace_patch(width, length, depth, E, nu, offset=length)
        layer = end_layer(depth)
        nodes, W, at = model_line(c, lam, -half, half, [mid_patch, end_patch], end_layer=layer)
        fe = dict(
            c_2d_centre=ps["centre"][i], c_2d_surface=ps["surface"][i] - hs_strip,
            c_3d_centre=float(rows["centre"]["line"][k_mid]),
            c_3d_surface=float(unit_mid @ u_line) - hs_strip,
            mid_centre=float(rows["centre"]["mid"][k_mid]),
            mid_surface=float(unit_mid @ u_mid) - hs_patch,
            mid_surface_raw=float(unit_mid @ u_mid),
            end_centre=float(rows["centre"]["end"][k_end]),
            end_surface=float(unit_end @ u_end) - hs_end,
            end_surface_raw=float(unit_end @ u_end))
        for m in ("centre", "surface"):
            fe[f"ratio_{m}"] = fe[f"end_{m}"] / fe[f"mid_{m}"]
            # the coupling length that gives the FE's point-over-line deflection, and the
            # model's end ratio with it
            try:
                lam_m = matching_length(fe[f"mid_{m}"] / fe[f"c_3d_{m}"], half, mid_patch)
                r_m = model_line(1.0, lam_m, -half, half, [mid_patch, end_patch])[2]
                fe[f"lambda_match_{m}"], fe[f"model_ratio_at_match_{m}"] = lam_m, r_m[1] / r_m[0]
            except ValueError:
                fe[f"lambda_match_{m}"] = fe[f"model_ratio_at_match_{m}"] = float("nan")
        fits = {f"{name}_{a:g}": fit_decay(z, rows[name]["mid"][k_mid:], half, a)
                for name in ("centre", "flank") for a in fit_from}
        model = dict(c=c, coupling_length=lam, end_layer=layer, parts=dict(
            zip(("bending", "shear", "axial", "foundation"),
                (float(p[0, 0]) for p in teeth.slices(site.radius)[:4]))),
            half_thickness=depth, mid=float(at[0]), end=float(at[1]),
            ratio=float(at[1] / at[0]), halfspace_strip=hs_strip, halfspace_patch=hs_patch,
            halfspace_patch_end=hs_end, free_end_factor=phi,
            profile_mid=np.interp(zz, nodes, W[:, 0]).tolist(),
            profile_end=np.interp(zz, nodes, W[:, 1]).tolist())
        out["sites"].append(dict(
            radius=site.radius, height=site.radius - gear.root_radius_value,
            centre_depth=site.depth, fe=fe, fits=fits, model=model, z=zz.tolist(),
            profiles={k: {kk: vv.tolist() for kk, vv in v.items()} for k, v in rows.items()}))
    out["seconds"] = time.perf_counter() - t0
    return out
