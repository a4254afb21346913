"""Independent 3D finite-element reference for surface loading near a free end face.

Linear elastic block on a graded, structured trilinear hexahedral mesh
(`skfem.MeshHex.init_tensor`; scikit-fem gives the mesh and the dof numbering, the
stiffness of the axis-aligned bricks is assembled here in closed form, which is checked
against scikit-fem's own `linear_elasticity` in tests/test_fe_reference.py). Solved with
SuperLU on a geometric nested-dissection ordering. Units: mm, N, MPa.

Geometry: top face z = 0 loaded, bottom z = -H fixed (u = 0), other faces free unless a
function says otherwise. "Free end": the block stops at x = 0 (a quarter-space). "Running
on": the block continues past x = 0 (the half-space-like reference). Loads symmetric about
y = 0 are solved on the half y >= 0 with u_y = 0 on y = 0. Two elastic bodies in contact
(mixed_end_line_load): two such blocks, their contact faces' u_z dofs on matching nodes each
condensed to a compliance, the contact solved on the sum.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
import scipy.sparse as sp
import scipy.sparse.linalg as spl
from skfem import MeshHex

__all__ = [
    "graded_axis", "block_mesh", "stiffness", "love_rectangle_uz",
    "BlockSolver", "SurfaceResult", "PunchResult",
    "surface_displacement", "surface_displacements", "flat_punch_line_load",
    "CylinderResult", "cylinder_end_line_load", "mixed_end_line_load", "best_estimate",
]


# ----------------------------------------------------------------------------- mesh

def graded_axis(lo, hi, fine=(), h_far=None, growth=0.25, breaks=()):
    """Node coordinates on [lo, hi] (mm), element size h(x) = min(h_far, h_k + growth*dist(x,
    [a_k, b_k])) over fine zones (a_k, b_k, h_k); every break (and lo, hi, zone ends) is a node."""
    h_far = float(h_far if h_far is not None else hi - lo)
    zones = [(float(a), float(b), float(h)) for a, b, h in fine]

    def size(x):
        h = np.full_like(x, h_far)
        for a, b, hk in zones:
            d = np.maximum(0.0, np.maximum(a - x, x - b))
            h = np.minimum(h, hk + growth * d)
        return h

    pts = {float(lo), float(hi)}
    pts.update(float(b) for b in breaks if lo <= b <= hi)
    for a, b, _ in zones:
        pts.update(v for v in (a, b) if lo <= v <= hi)
    pts = np.array(sorted(pts))
    out = [pts[:1]]
    for x0, x1 in zip(pts[:-1], pts[1:]):
        if x1 - x0 < 1e-12:
            continue
        s = np.linspace(x0, x1, 4001)
        w = 1.0 / size(s)
        cum = np.concatenate([[0.0], np.cumsum(0.5 * (w[1:] + w[:-1]) * np.diff(s))])
        n = max(1, int(np.ceil(cum[-1] - 1e-6)))
        out.append(np.interp(np.linspace(0, cum[-1], n + 1)[1:], cum, s))
        out[-1][-1] = x1
    return np.concatenate(out)


def block_mesh(x, y, z):
    """Hexahedral mesh of the box spanned by sorted node coordinates x, y, z (mm)."""
    return MeshHex.init_tensor(np.asarray(x, float), np.asarray(y, float), np.asarray(z, float))


# ----------------------------------------------------------------------------- stiffness

def _reference_matrices():
    """Unit-cube trilinear integrals S[a, b, i, j] = int dN_i/dxi_a dN_j/dxi_b (corners c_i)."""
    c = np.array([[i, j, k] for i in (0, 1) for j in (0, 1) for k in (0, 1)], float)
    g = 0.5 + np.array([-1.0, 1.0]) / (2 * np.sqrt(3.0))
    q = np.array([[a, b, d] for a in g for b in g for d in g])  # 8 points, weight 1/8

    def f1(t, ci):  # 1D shape and derivative
        return np.where(ci == 1, t, 1 - t), np.where(ci == 1, 1.0, -1.0)

    dN = np.zeros((len(q), 8, 3))
    for p, xi in enumerate(q):
        for i in range(8):
            v = [f1(xi[a], c[i, a]) for a in range(3)]
            for a in range(3):
                dN[p, i, a] = np.prod([v[b][1] if b == a else v[b][0] for b in range(3)])
    S = np.einsum("pia,pjb->abij", dN, dN) / len(q)
    return c, S


_CORNERS, _S = _reference_matrices()


def stiffness(mesh, E, nu):
    """Global stiffness (N/mm) of trilinear bricks, dof 3*node + component."""
    lam = E * nu / ((1 + nu) * (1 - 2 * nu))
    mu = E / (2 * (1 + nu))
    p, t = mesh.p, mesh.t
    lo = p[:, t].min(axis=1)
    hvec = p[:, t].max(axis=1) - lo                      # (3, ne)
    # local corner pattern of each element node -> index into _CORNERS
    loc = np.rint((p[:, t] - lo[:, None, :]) / hvec[:, None, :]).astype(int)  # (3, 8, ne)
    code = loc[0] * 4 + loc[1] * 2 + loc[2]             # matches _CORNERS ordering
    if not np.all(code == code[:, :1]):
        raise ValueError("elements with differing local node order")
    order = code[:, 0]                                  # local node k is corner order[k]
    S = _S[:, :, order][:, :, :, order]                 # (3,3,8,8) in mesh local order
    vol = np.prod(hvec, axis=0)
    ne = t.shape[1]
    Ke = np.zeros((ne, 8, 3, 8, 3))
    for a in range(3):
        for b in range(3):
            w = vol / (hvec[a] * hvec[b])
            # lambda dN_i/da dN_j/db  at (i, a), (j, b); mu dN_i/da dN_j/db at (i, b), (j, a)
            Ke[:, :, a, :, b] += lam * w[:, None, None] * S[a, b]
            Ke[:, :, b, :, a] += mu * w[:, None, None] * S[a, b]
            if a == b:
                for comp in range(3):
                    Ke[:, :, comp, :, comp] += mu * w[:, None, None] * S[a, a]
    dofs = (3 * t.T[:, :, None] + np.arange(3)).reshape(ne, 24)
    rows = np.repeat(dofs, 24, axis=1).ravel()
    cols = np.tile(dofs, (1, 24)).ravel()
    n = 3 * p.shape[1]
    return sp.csr_matrix((Ke.reshape(ne, 576).ravel(), (rows, cols)), shape=(n, n))


def _nested_dissection(shape, leaf=48):
    """Geometric nested-dissection order of the grid points of an (nx, ny, nz) grid."""
    idx = np.arange(np.prod(shape)).reshape(shape)
    out = []

    def rec(b):
        if b.size <= leaf or min(b.shape) == 0:
            out.append(b.ravel())
            return
        ax = int(np.argmax(b.shape))
        k = b.shape[ax] // 2
        s = [slice(None)] * 3
        s1, s2, s3 = list(s), list(s), list(s)
        s1[ax], s2[ax], s3[ax] = slice(0, k), slice(k + 1, None), k
        rec(b[tuple(s1)])
        rec(b[tuple(s2)])
        out.append(b[tuple(s3)].ravel())

    rec(idx)
    return np.concatenate(out)


# ----------------------------------------------------------------------------- solver

class BlockSolver:
    """Linear elastic box on a tensor mesh (node coordinates x, y, z in mm; E in MPa):
    fixed bottom, optional u_y = 0 on y = 0, u_x = 0 on x = x[0] (sym_x0) or x = x[-1]
    (sym_x1), prescribed u_z on uz_nodes (node ids, or a function of the (nx, ny, nz) grid
    of node ids); factorised once (SuperLU, nested dissection)."""

    def __init__(self, x, y, z, E=210000.0, nu=0.3, sym_y0=True, sym_x0=False,
                 uz_nodes=None, sym_x1=False):
        self.x, self.y, self.z = (np.asarray(v, float) for v in (x, y, z))
        self.mesh = block_mesh(self.x, self.y, self.z)
        p = self.mesh.p
        self.ix = np.searchsorted(self.x, p[0] - 1e-12 * (1 + abs(p[0])))
        self.iy = np.searchsorted(self.y, p[1] - 1e-12 * (1 + abs(p[1])))
        self.iz = np.searchsorted(self.z, p[2] - 1e-12 * (1 + abs(p[2])))
        self.grid = np.empty((len(self.x), len(self.y), len(self.z)), int)
        self.grid[self.ix, self.iy, self.iz] = np.arange(p.shape[1])
        self.K = stiffness(self.mesh, E, nu)
        n = self.K.shape[0]
        fixed = np.zeros(n, bool)
        bottom = self.grid[:, :, 0].ravel()
        for c in range(3):
            fixed[3 * bottom + c] = True
        if sym_y0:
            fixed[3 * self.grid[:, 0, :].ravel() + 1] = True
        if sym_x0:
            fixed[3 * self.grid[0, :, :].ravel()] = True
        if sym_x1:
            fixed[3 * self.grid[-1, :, :].ravel()] = True
        if callable(uz_nodes):
            uz_nodes = uz_nodes(self.grid)
        self.uz_nodes = np.asarray(uz_nodes if uz_nodes is not None else [], int)
        fixed[3 * self.uz_nodes + 2] = True
        self.fixed = fixed
        nd = _nested_dissection(self.grid.shape)
        dof_order = (3 * self.grid.ravel()[nd][:, None] + np.arange(3)).ravel()
        self.free = dof_order[~fixed[dof_order]]
        A = self.K[self.free][:, self.free].tocsc()
        self.n_dofs = A.shape[0]
        self.lu = spl.splu(A, permc_spec="NATURAL", diag_pivot_thresh=0.0,
                           options=dict(SymmetricMode=True))

    def solve(self, f=None, uz_value=0.0):
        """Displacement vector (mm) for nodal forces f (N) and u_z = uz_value on uz_nodes."""
        n = self.K.shape[0]
        u = np.zeros(n)
        u[3 * self.uz_nodes + 2] = uz_value
        rhs = -(self.K @ u)
        if f is not None:
            rhs += f
        u[self.free] = self.lu.solve(rhs[self.free])
        return u

    def top_pressure_load(self, patches, sym_y0=True):
        """Consistent nodal forces (N) of uniform pressures p (MPa, pushing -z) on top
        rectangles (x0, x1, y0, y1, p); patch edges must be mesh lines (on y >= 0 if sym_y0)."""
        f = np.zeros(self.K.shape[0])
        xc = 0.5 * (self.x[1:] + self.x[:-1])
        yc = 0.5 * (self.y[1:] + self.y[:-1])
        hx, hy = np.diff(self.x), np.diff(self.y)
        for x0, x1, y0, y1, pr in patches:
            if sym_y0:
                y0 = max(y0, 0.0)
            for v, arr in ((x0, self.x), (x1, self.x), (y0, self.y), (y1, self.y)):
                if np.min(np.abs(arr - v)) > 1e-9 * (1 + abs(v)):
                    raise ValueError(f"patch edge {v} is not a mesh line")
            ex = np.nonzero((xc > x0) & (xc < x1))[0]
            ey = np.nonzero((yc > y0) & (yc < y1))[0]
            kz = len(self.z) - 1
            for i in ex:
                for j in ey:
                    fz = -pr * hx[i] * hy[j] / 4.0
                    for di in (0, 1):
                        for dj in (0, 1):
                            f[3 * self.grid[i + di, j + dj, kz] + 2] += fz
        return f


# ----------------------------------------------------------------------------- closed form

def _g(X, Y):
    """Antiderivative G with d2G/dXdY = 1/r (r = hypot(X, Y))."""
    X, Y = np.broadcast_arrays(np.asarray(X, float), np.asarray(Y, float))
    r = np.hypot(X, Y)

    def xlog(a, b):  # a * ln(b + r), stable for b < 0, 0 when a == 0
        with np.errstate(divide="ignore", invalid="ignore"):
            val = np.where(b >= 0, np.log(b + r), np.log(a * a / (r - b)))
            return np.where(a == 0, 0.0, a * val)

    return xlog(X, Y) + xlog(Y, X)


def love_rectangle_uz(x, y, rect, p, E, nu):
    """Half-space surface u_z (mm, positive into the body) at (x, y) under uniform pressure p
    (MPa) on rect (x0, x1, y0, y1) (Love 1929): (1 - nu^2) p / (pi E) * int dA / r."""
    x0, x1, y0, y1 = rect
    x, y = np.asarray(x, float), np.asarray(y, float)
    integral = (_g(x1 - x, y1 - y) - _g(x0 - x, y1 - y)
                - _g(x1 - x, y0 - y) + _g(x0 - x, y0 - y))
    return (1 - nu**2) * p / (np.pi * E) * integral


# ----------------------------------------------------------------------------- surface loading

@dataclass
class SurfaceResult:
    """Top-surface u_z (mm, negative = into the body) along y = y_line versus x (mm)."""
    x: np.ndarray
    uz: np.ndarray
    n_dofs: int
    y_line: float = 0.0
    extra: dict = field(default_factory=dict)

    def __call__(self, xq):
        return np.interp(xq, self.x, self.uz)


def _surface_axes(patches_list, end_free, Lx, Ly, H, h, growth, refine, fine_to_end):
    hh = h / refine
    g = growth / np.sqrt(refine)
    xs = [v for pl in patches_list for pt in pl for v in pt[:2]]
    ys = [abs(v) for pl in patches_list for pt in pl for v in pt[2:4]]
    pad = max(ys)
    hi = 0.0 if fine_to_end else min(0.0, max(xs) + pad)
    xb = sorted(set(xs))
    x_half = graded_axis(-Lx, 0.0, [(min(xs) - pad, hi, hh)], h_far=Lx / 4, growth=g,
                         breaks=xb)
    if end_free:
        x = x_half
    else:  # the same nodes mirrored about x = 0: mirror points are nodes
        x = np.concatenate([x_half, -x_half[::-1][1:]])
    y = graded_axis(0.0, Ly, [(0.0, 2 * max(ys), hh)], h_far=Ly / 4, growth=g, breaks=ys)
    z = graded_axis(-H, 0.0, [(0.0, 0.0, hh)], h_far=H / 4, growth=g)
    return x, y, z


def surface_displacements(load_cases, end_free=True, nu=0.3, E=210000.0, Lx=40.0, Ly=40.0,
                          H=40.0, h=0.25, growth=0.25, refine=1.0, fine_to_end=True,
                          top=False, wall=False):
    """Top u_z along y = 0 for several load cases on one factorisation.

    load_cases: list of patch lists, patch = (x0, x1, y0, y1, p) (mm, MPa, symmetric about
    y = 0, x <= 0). Block x in [-Lx, 0] (end_free) or [-Lx, Lx], y in [-Ly, Ly], z in [-H, 0],
    bottom fixed. Element size h/refine (mm) over the patches (padded by their half width,
    in y to twice it) and, if fine_to_end, on to x = 0, growing by growth/sqrt(refine) per mm
    outside; the x nodes of the running-on block mirror those of the free one about x = 0.
    wall (with end_free): u_x = 0 on the end face, a frictionless rigid wall (the exact
    plain mirror, phi = 1). Returns a list of SurfaceResult (with top=True, extra["top"] =
    (x, y, u_z) of the whole top face, y >= 0).
    """
    for pl in load_cases:
        for x0, x1, y0, y1, _ in pl:
            if abs(y0 + y1) > 1e-12:
                raise ValueError("patches must be symmetric about y = 0")
    x, y, z = _surface_axes(load_cases, end_free, Lx, Ly, H, h, growth, refine, fine_to_end)
    s = BlockSolver(x, y, z, E=E, nu=nu, sym_y0=True, sym_x1=bool(end_free and wall))
    line = s.grid[:, 0, -1]
    out = []
    for pl in load_cases:
        u = s.solve(s.top_pressure_load(pl))
        extra = dict(nx=len(x), ny=len(y), nz=len(z))
        if top:
            extra["top"] = (x.copy(), y.copy(), u[3 * s.grid[:, :, -1] + 2])
        out.append(SurfaceResult(x.copy(), u[3 * line + 2], s.n_dofs, extra=extra))
    return out


def surface_displacement(pressure_patches, end_free=True, nu=0.3, E=210000.0, Lx=40.0,
                         Ly=40.0, H=40.0, h=0.25, growth=0.25, refine=1.0, fine_to_end=True):
    """Top u_z (mm) along y = 0 versus x (mm) under uniform pressures on rectangles
    (x0, x1, y0, y1, p) [mm, MPa]; see surface_displacements. Returns a SurfaceResult."""
    return surface_displacements([list(pressure_patches)], end_free, nu, E, Lx, Ly, H, h,
                                 growth, refine, fine_to_end)[0]


# ----------------------------------------------------------------------------- flat punch

@dataclass
class PunchResult:
    """Flat strip punch: nodes x (mm) on [-length, 0], line load q (N/mm, whole width, from
    the nodal reactions over their tributary lengths), q_norm = q / q at x = -length/2, total
    load (N), approach delta (mm), node_force (N, whole width, per x node)."""
    x: np.ndarray
    q: np.ndarray
    q_norm: np.ndarray
    total: float
    delta: float
    n_dofs: int
    node_force: np.ndarray
    q_mid: float

    def end_average(self, c):
        """Mean q over x in [-c, 0] (mm; -c must be a node) divided by q_mid."""
        x, F = self.x, self.node_force
        k = int(np.argmin(np.abs(x + c)))
        if abs(x[k] + c) > 1e-9 * (1 + c):
            raise ValueError(f"-{c} is not a node")
        hl, hr = x[k] - x[k - 1], x[k + 1] - x[k]
        Q = F[k + 1:].sum() + F[k] * hr / (hl + hr)
        return Q / c / self.q_mid


def flat_punch_line_load(a, length, end_free=True, nu=0.3, E=210000.0, delta=1e-3,
                         depth=None, width=None, run_on=None, far_end="run_on", refine=1.0,
                         h_end=None, growth=0.3, ends=(0.05, 0.1, 0.25)):
    """Rigid frictionless flat strip |y| <= a, x in [-length, 0] (mm) pressed delta (mm) into
    the top face (only u_z prescribed on its nodes); bottom z = -depth fixed, y in +-width.

    end_free: the end face x = 0 is free (the block stops there); else the block runs on to
    x = run_on. far_end "run_on": the block runs on past x = -length to -length - run_on;
    "free": the block starts at x = -length with a free face (a slab as long as the strip).
    Defaults depth = width = run_on = 8 * length (end/mid ratios within 0.1 % of 16 *
    length; 2 * length is 5 % off for a free end). Element size h_end = a/16/refine (mm) at
    the strip ends, its edges and the top, growing by growth/sqrt(refine) per mm, at most
    a/4/refine across and a/2/refine along the strip; nodes at x = -c*a for c in ends.
    Symmetric cases are solved on x >= -length/2; y >= 0 always. Returns a PunchResult.
    """
    depth = 8 * length if depth is None else depth
    width = 8 * length if width is None else width
    run_on = 8 * length if run_on is None else run_on
    h0 = (a / 16 if h_end is None else h_end) / refine
    g = growth / np.sqrt(refine)
    h_in = a / 4 / refine
    half = length / 2
    h_far = max(depth, width, run_on) / 4
    # nodes on [-half, run_on] (fine at the punch end x = 0), mirrored about -half
    xr = graded_axis(-half, run_on, [(0.0, 0.0, h0), (-half, 0.0, 2 * h_in)], h_far=h_far,
                     growth=g, breaks=[-c * a for c in ends])
    x_full = np.concatenate([-length - xr[::-1], xr[1:]])
    x_full[np.argmin(np.abs(x_full + half))] = -half
    y = graded_axis(0.0, width, [(a, a, h0), (0.0, a, h_in)], h_far=h_far, growth=g)
    z = graded_axis(-depth, 0.0, [(0.0, 0.0, h0)], h_far=h_far, growth=g)
    symmetric = (far_end == "free") == end_free
    if far_end not in ("free", "run_on"):
        raise ValueError(far_end)
    if symmetric:
        x = xr if not end_free else xr[xr <= 1e-12]
    else:  # free at x = 0, running on past x = -length
        x = x_full[x_full <= 1e-12]
    ix_p = np.nonzero((x <= 1e-12) & (x >= -length - 1e-12))[0]
    iy_p = np.nonzero(y <= a + 1e-12)[0]
    s = BlockSolver(x, y, z, E=E, nu=nu, sym_y0=True, sym_x0=symmetric,
                    uz_nodes=lambda grid: grid[np.ix_(ix_p, iy_p, [-1])][:, :, 0].ravel())
    nodes = s.uz_nodes.reshape(len(ix_p), len(iy_p))
    u = s.solve(uz_value=-delta)
    R = s.K @ u                                        # nodal forces on the body (N)
    F = -R[3 * nodes + 2].sum(axis=1) * 2              # whole width, per x node
    xp = x[ix_p]
    if symmetric:                                      # mirror about x = -half
        F = np.concatenate([F[:0:-1], [2 * F[0]], F[1:]])
        xp = np.concatenate([-length - xp[:0:-1], xp])
    trib = np.empty_like(xp)
    trib[1:-1] = 0.5 * (xp[2:] - xp[:-2])
    trib[0] = 0.5 * (xp[1] - xp[0])
    trib[-1] = 0.5 * (xp[-1] - xp[-2])
    q = F / trib
    q_mid = float(q[np.argmin(np.abs(xp + half))])
    return PunchResult(xp, q, q / q_mid, float(F.sum()), delta, s.n_dofs, F, q_mid)


# ----------------------------------------------------------------------------- cylinder (Hertz)

@dataclass
class CylinderResult:
    """Rigid cylinder on a block (see cylinder_end_line_load), or two blocks in a line
    contact (mixed_end_line_load). Along x: nodes x (mm) on [-length, 0], line load q (N/mm,
    whole width, nodal reactions over their tributary lengths), q_norm = q / q_mid,
    node_force (N, whole width, per x node); q_mid at x = -length/2. Across y (mm, y >= 0,
    the candidate nodes): top-surface pressure p_mid and p_end (MPa, nodal reaction over
    tributary area) at mid-length and at x = 0. b_hertz, p0_hertz: the Hertz half-width and
    peak pressure of the target line load (= q_mid to 1e-7; E* = E / (1 - nu^2) under a
    rigid cylinder, the pair's for two bodies); peak_mid = p_mid[0]; half_width_mid: the
    last y in contact at mid-length. delta: the approach (mm); iterations: constrained-CG
    steps per solve (one solve per face-width load tried); reach: the largest y in contact
    over the face width (below y[-1], the candidates' edge); dofs: the free dofs per body
    where there are two (mixed_end_line_load), n_dofs their sum."""
    x: np.ndarray
    q: np.ndarray
    q_norm: np.ndarray
    node_force: np.ndarray
    q_mid: float
    total: float
    delta: float
    y: np.ndarray
    p_mid: np.ndarray
    p_end: np.ndarray
    b_hertz: float
    p0_hertz: float
    peak_mid: float
    half_width_mid: float
    iterations: list
    n_dofs: int
    n_candidates: int
    reach: float
    dofs: dict = field(default_factory=dict)

    def end_average(self, c):
        """Mean q over x in [-c b, 0] (b = b_hertz; -c b must be a node) over q_mid."""
        return PunchResult.end_average(self, c * self.b_hertz)


def _schur_factor(K, fixed, grid, last):
    """SuperLU factor of K on the free dofs in nested-dissection order with the dofs `last`
    put at the end, and the dense Schur complement S (N/mm) of those dofs (the trailing
    block L_cc U_cc of the factor: diagonal pivots, no permutations). Returns (lu, order, S)."""
    nd = _nested_dissection(grid.shape)
    order = (3 * grid.ravel()[nd][:, None] + np.arange(3)).ravel()
    is_last = np.zeros(K.shape[0], bool)
    is_last[last] = True
    order = np.concatenate([order[~fixed[order] & ~is_last[order]], last])
    A = K[order][:, order].tocsc()
    lu = spl.splu(A, permc_spec="NATURAL", diag_pivot_thresh=0.0,
                  options=dict(SymmetricMode=True))
    m, nc = A.shape[0], len(last)
    if not (np.array_equal(lu.perm_r, np.arange(m)) and np.array_equal(lu.perm_c, np.arange(m))):
        raise RuntimeError("SuperLU permuted the dofs: no Schur complement in the trailing block")
    S = lu.L[m - nc:, m - nc:].toarray() @ lu.U[m - nc:, m - nc:].toarray()
    return lu, order, 0.5 * (S + S.T)


def _signorini_cg(C, gap, W, P, tol=1e-10, max_iter=5000):
    """Frictionless contact on a compliance C (mm/N, dense SPD) of n nodes: forces P >= 0
    (N, pressing) summing to W, approach delta (mm), with d = C P the deflection (mm) and
    the gap s = gap + d - delta >= 0, s = 0 where P > 0. The constrained conjugate gradient
    of Polonsky & Keer (Wear 231 (1999) 206-219): an active-set iteration inside CG (nodes
    whose force turns tensile leave the set, nodes that penetrate join it, CG restarts when
    the set grows). Then the final set is solved exactly (C_AA P_A = delta - gap_A, sum P =
    W) and the complementarity checked: RuntimeError if it fails. Returns (P, delta, steps)."""
    n = len(gap)
    P = np.maximum(np.asarray(P, float), 0.0)
    P *= W / P.sum()
    t = np.zeros(n)
    G_old, restart = 1.0, True
    for it in range(1, max_iter + 1):
        I = P > 0
        g = C @ P + gap
        g -= g[I].mean()
        G = g[I] @ g[I]
        t = np.where(I, g + (0.0 if restart else G / G_old) * t, 0.0)
        G_old = G
        r = C @ t
        r -= r[I].mean()
        tau = (g[I] @ t[I]) / (r[I] @ t[I])
        P_old = P.copy()
        P = np.where(I, P - tau * t, P)
        P[P < 0] = 0.0
        J = ~I & (g < 0)                                        # penetrating, no force yet
        restart = bool(J.any())
        P[J] -= tau * g[J]
        P *= W / P.sum()
        if np.abs(P - P_old).sum() / W < tol:
            break
    else:
        raise RuntimeError(f"constrained CG: no convergence in {max_iter} steps")
    A = np.nonzero(P > 0)[0]                                    # the exact solve on the set
    m = len(A)
    M = np.zeros((m + 1, m + 1))
    M[:m, :m] = C[np.ix_(A, A)]
    M[:m, m] = -1.0
    M[m, :m] = 1.0
    sol = np.linalg.solve(M, np.concatenate([-gap[A], [W]]))
    P = np.zeros(n)
    P[A] = sol[:m]
    delta = sol[m]
    s = gap + C @ P - delta
    if P.min() < -1e-6 * W / m or s.min() < -1e-6 * delta:
        raise RuntimeError(f"contact set not consistent: min force {P.min():.3g} N, "
                           f"min gap {s.min():.3g} mm")
    return np.maximum(P, 0.0), float(delta), it


def _line_axes(b, lo, hi, length, depth, width, run_on, refine, growth, ends, y_reach):
    """Node coordinates (x on [lo, hi], y on [0, width], z on [-depth, 0]; mm) of a block
    under a line contact along x over [-length, 0] of Hertz half-width b (mm): elements of
    b/16/refine along x at x = 0, b/8/refine across the contact (y in [0, 1.5 b]), at the
    top and at x = -length, b/2/refine along the middle, growing by growth/sqrt(refine) per
    mm up to a quarter of the block size; nodes at x = -c b (c in ends), -length/2 and y =
    y_reach b. The nodes on x <= 0 do not depend on hi >= 0 (0 is a break): blocks that
    stop at x = 0 and that run on past it have the same nodes there."""
    h_end, h_c, h_in = b / 16 / refine, b / 8 / refine, b / 4 / refine
    g = growth / np.sqrt(refine)
    h_far = max(depth, width, run_on) / 4
    breaks = [-c * b for c in ends] + [-length / 2]
    zones = [(0.0, 0.0, h_end), (-length, 0.0, 2 * h_in), (-length, -length, h_c)]
    x = graded_axis(lo, hi, zones, h_far=h_far, growth=g, breaks=breaks)
    y = graded_axis(0.0, width, [(0.0, 1.5 * b, h_c)], h_far=h_far, growth=g,
                    breaks=[y_reach * b])
    z = graded_axis(-depth, 0.0, [(0.0, 0.0, h_c)], h_far=h_far, growth=g)
    return x, y, z


def _top_compliance(x, y, z, E, nu, ix, iy, sym_x0=False):
    """The compliance C (mm/N, dense, symmetric) of the top-face u_z dofs of the nodes x[ix]
    x y[iy] (x-major) of a block on the tensor mesh x, y, z (bottom z = z[0] fixed, u_y = 0
    on y = 0, u_x = 0 on x = x[0] if sym_x0, all else free): the inverse of their Schur
    complement (_schur_factor), every other node force-free. Returns (C, dofs)."""
    mesh = block_mesh(x, y, z)
    p = mesh.p
    grid = np.empty((len(x), len(y), len(z)), int)
    grid[np.searchsorted(x, p[0] - 1e-9 * (1 + abs(p[0]))),
         np.searchsorted(y, p[1] - 1e-9 * (1 + abs(p[1]))),
         np.searchsorted(z, p[2] - 1e-9 * (1 + abs(p[2])))] = np.arange(p.shape[1])
    K = stiffness(mesh, E, nu)
    fixed = np.zeros(K.shape[0], bool)
    for c in range(3):
        fixed[3 * grid[:, :, 0].ravel() + c] = True
    fixed[3 * grid[:, 0, :].ravel() + 1] = True                 # y = 0 symmetry
    if sym_x0:
        fixed[3 * grid[0, :, :].ravel()] = True                 # x = x[0] symmetry
    nodes = grid[np.ix_(ix, iy, [len(z) - 1])][:, :, 0]          # (nx_c, ny_c)
    lu, _, S = _schur_factor(K, fixed, grid, 3 * nodes.ravel() + 2)
    dofs = lu.shape[0]
    del lu, K
    C = np.linalg.inv(S)
    return 0.5 * (C + C.T), dofs


def _line_contact(C, x, y, ix, iy, radius, load, length, b, mirrored, tol, outer_max,
                  n_dofs, dofs=None):
    """Frictionless line contact of the gap y^2 / (2 radius) (mm) along x on the candidate
    nodes x[ix] x y[iy] (x-major; y >= 0 solved, x[ix] over [-length, 0], or over [-length/2,
    0] if mirrored about x = -length/2) of the compliance C (mm/N): the set found by the
    constrained conjugate gradient (_signorini_cg) at a load on the face width, solved
    exactly on it and checked, that load rescaled until the line load at x = -length/2 is
    `load` (N/mm, to 1e-7). b: the Hertz half-width of `load` (mm). Returns a CylinderResult
    (see cylinder_end_line_load)."""
    xc, yc = x[ix], y[iy]
    nxc, nyc = len(xc), len(yc)
    half = length / 2
    trib_y = np.empty(nyc)
    trib_y[0] = 0.5 * (y[1] - y[0])
    trib_y[1:] = 0.5 * (y[iy[1:] + 1] - y[iy[1:] - 1])
    trib_x = np.empty(nxc)
    left = np.where(ix > 0, x[np.maximum(ix - 1, 0)], x[ix])
    right = np.where(ix < len(x) - 1, x[np.minimum(ix + 1, len(x) - 1)], x[ix])
    trib_x[:] = 0.5 * (right - left)                            # half at the ends of x
    k_mid = int(np.argmin(np.abs(xc + half)))
    k_end = nxc - 1
    curv = np.tile(yc**2 / (2 * radius), nxc)                   # gap at delta = 0 (mm)
    w_mid = np.zeros(nxc * nyc)                                 # q_mid = w_mid . P (N/mm,
    w_mid[k_mid * nyc:(k_mid + 1) * nyc] = 2.0 / trib_x[k_mid]  # whole width; on the plane
    #                                     x = -length/2: half the force on half the length)

    # the load W on the face width (half of it: y >= 0) that gives q_mid = load
    P0 = np.where(curv <= b**2 / (2 * radius), 1.0, 0.0)       # start: Hertz at mid-length
    W = load * length / 2
    iterations = []
    for _ in range(outer_max):
        P, delta, its = _signorini_cg(C, curv, W, P0 * W / P0.sum(), tol)
        iterations.append(its)
        q = w_mid @ P
        if abs(q / load - 1) < 1e-7:
            break
        W *= load / q
        P0 = P
    else:
        raise RuntimeError(f"mid-length line load {q} N/mm, not {load}, after {outer_max} solves")
    Pg = P.reshape(nxc, nyc)
    if Pg[:, -1].max() > 0:
        raise RuntimeError("the contact reaches the candidates' edge y_reach * b")
    reach = float(yc[np.nonzero(Pg.max(axis=0) > 0)[0].max()])

    F = 2 * Pg.sum(axis=1)                                      # whole width per x node
    pressure = Pg / (trib_x[:, None] * trib_y[None, :])
    q_mid = float(F[k_mid] / trib_x[k_mid])
    xp = xc.copy()
    if mirrored:                                                # mirror about -length/2
        F = np.concatenate([F[:0:-1], [2 * F[0]], F[1:]])
        xp = np.concatenate([-length - xc[:0:-1], xc])
    trib = np.empty_like(xp)
    trib[1:-1] = 0.5 * (xp[2:] - xp[:-2])
    trib[0] = 0.5 * (xp[1] - xp[0])
    trib[-1] = 0.5 * (xp[-1] - xp[-2])
    q = F / trib
    in_mid = np.nonzero(Pg[k_mid] > 0)[0]
    return CylinderResult(
        x=xp, q=q, q_norm=q / q_mid, node_force=F, q_mid=q_mid, total=float(F.sum()),
        delta=float(delta), y=yc, p_mid=pressure[k_mid], p_end=pressure[k_end],
        b_hertz=float(b), p0_hertz=float(2 * load / (np.pi * b)),
        peak_mid=float(pressure[k_mid, 0]), half_width_mid=float(yc[in_mid.max()]),
        iterations=iterations, n_dofs=n_dofs, n_candidates=nxc * nyc, reach=reach,
        dofs=dict(dofs or {}))


def _candidates(x, y, length, b, y_reach):
    """Indices of the contact's candidate nodes: x in [-length, 0], 0 <= y <= y_reach b."""
    ix = np.nonzero((x >= -length - 1e-9 * (1 + length)) & (x <= 1e-12))[0]
    iy = np.nonzero(y <= y_reach * b * (1 + 1e-9))[0]
    return ix, iy


def cylinder_end_line_load(radius=84.0, load=None, length=None, end_free=True, nu=0.3,
                           E=210000.0, depth=None, width=None, run_on=None, refine=1.0,
                           growth=0.3, ends=(0.05, 0.1, 0.25, 0.5), y_reach=2.5,
                           tol=1e-10, outer_max=12):
    """Rigid frictionless cylinder (radius mm, axis along x, x in [-length, 0]) pressed into
    the top face z = 0 of an elastic block (bottom z = -depth fixed, y in +-width), the line
    load at mid-length x = -length/2 brought to `load` (N/mm; default: the load of a Hertz
    half-width b = 1 mm, w = pi E* b^2 / (4 radius), E* = E / (1 - nu^2)).

    end_free: the block's end face x = 0 is free (it ends flush with the cylinder); else the
    block runs on to x = run_on. The block always runs on past x = -length to -length -
    run_on (then the running-on case is symmetric about -length/2 and solved on its half).
    Defaults length = 10 b, depth = width = run_on = 2 * length (b the Hertz half-width).

    Contact (Signorini, frictionless): the candidate nodes are the top nodes with x in
    [-length, 0], 0 <= y <= y_reach * b (y >= 0 solved, u_y = 0 on y = 0). Their u_z-dofs
    are ordered last in one SuperLU factorisation, whose trailing block is their Schur
    complement S (N/mm): the exact stiffness of the block seen from those dofs, every other
    node force-free; its inverse C is their compliance (_top_compliance). The plain
    active-set iteration (u_z = -(delta - y^2 / (2 radius)) prescribed on the nodes in
    contact, the others force-free; those whose reaction pulls leave, those that penetrate
    the cylinder join, all at once) cycles on this dense compliance, so the set is found by
    the constrained conjugate gradient (_signorini_cg: the same moves inside CG) at a given
    load on the face width, then solved exactly on that set and checked (no tensile
    reaction, no penetration). The face-width load is rescaled until the mid-length line
    load is `load` (to 1e-7; _line_contact). RuntimeError if the contact reaches y_reach * b.

    Mesh (_line_axes): element size b/16/refine along x at the end face x = 0, b/8/refine
    across the contact (y in [0, 1.5 b]), at the top and at x = -length, b/2/refine along
    the middle of the cylinder, growing by growth/sqrt(refine) per mm (b = 1 mm by default)
    up to a quarter of the block size; nodes at x = -c b for c in ends. Returns a
    CylinderResult.
    """
    E_star = E / (1 - nu**2)
    load, b, length, depth, width, run_on = _line_defaults(E_star, radius, load, length,
                                                           depth, width, run_on)
    lo, hi = (-length - run_on, 0.0) if end_free else (-length / 2, run_on)
    x, y, z = _line_axes(b, lo, hi, length, depth, width, run_on, refine, growth, ends,
                         y_reach)
    ix, iy = _candidates(x, y, length, b, y_reach)
    C, dofs = _top_compliance(x, y, z, E, nu, ix, iy, sym_x0=not end_free)
    return _line_contact(C, x, y, ix, iy, radius, load, length, b, not end_free, tol,
                         outer_max, dofs)


def _line_defaults(E_star, radius, load, length, depth, width, run_on):
    """A line contact's load (N/mm; default: a Hertz half-width of 1 mm on E_star), its
    half-width b, length (default 10 b) and block sizes (default twice the length), mm."""
    load = np.pi * E_star / (4 * radius) if load is None else float(load)
    b = np.sqrt(4 * load * radius / (np.pi * E_star))
    length = 10 * b if length is None else float(length)
    depth = 2 * length if depth is None else depth
    width = 2 * length if width is None else width
    run_on = 2 * length if run_on is None else run_on
    return load, b, length, depth, width, run_on


def mixed_end_line_load(radius=84.0, load=None, length=None, b_runs_on=True,
                        E_a=98000.0, nu_a=0.35, E_b=210000.0, nu_b=0.3, depth=None,
                        width=None, run_on=None, refine=1.0, growth=0.3,
                        ends=(0.05, 0.1, 0.25, 0.5), y_reach=2.5, tol=1e-10, outer_max=12):
    """Two elastic bodies in a frictionless Hertzian line contact along x over [-length, 0]
    (the gap y^2 / (2 radius) between them, mm): body A (E_a MPa, nu_a) ends at x = 0 with
    a free end face; body B (E_b, nu_b) runs on past x = 0 to x = run_on (b_runs_on: a worm
    set, the wheel's face ending while the worm's thread runs on), or ends flush with A at
    x = 0 (b_runs_on False). Both run on past x = -length to -length - run_on. The line load
    at mid-length x = -length/2 brought to `load` (N/mm; default: the load of a Hertz
    half-width b = 1 mm, w = pi E* b^2 / (4 radius), 1/E* = (1 - nu_a^2)/E_a + (1 -
    nu_b^2)/E_b). Defaults length = 10 b, depth = half width = run_on = 2 * length.

    Each body a block (bottom z = -depth fixed, y in +-width; y >= 0 solved, u_y = 0 on
    y = 0) meshed as cylinder_end_line_load's block (_line_axes, the same y, z nodes for
    both and the same x nodes on x <= 0: the contact faces' nodes match over the region
    where A exists; B's mesh past x = 0 grades out from the end's b/16/refine). Each body's
    top-face u_z dofs of the candidate nodes (x in [-length, 0], 0 <= y <= y_reach b)
    condensed to their Schur complement, inverted to a compliance (_top_compliance); the
    contact, whose nodal forces press both faces equal and opposite, solved on the summed
    compliance C_A + C_B and the rigid gap (_line_contact, as cylinder_end_line_load). B's
    nodes past x = 0 carry no contact. Returns a CylinderResult, its n_dofs both bodies'
    and dofs = {"A": ..., "B": ...}.
    """
    c_a, c_b = (1 - nu_a**2) / E_a, (1 - nu_b**2) / E_b
    E_star = 1 / (c_a + c_b)
    load, b, length, depth, width, run_on = _line_defaults(E_star, radius, load, length,
                                                           depth, width, run_on)
    axes = [_line_axes(b, -length - run_on, hi, length, depth, width, run_on, refine,
                       growth, ends, y_reach) for hi in (0.0, run_on if b_runs_on else 0.0)]
    (xa, y, z), (xb, yb, zb) = axes
    ix, iy = _candidates(xa, y, length, b, y_reach)
    if not (np.array_equal(xb[:len(xa)], xa) and np.array_equal(yb, y)
            and np.array_equal(zb, z)):
        raise RuntimeError("the two bodies' contact faces do not share their nodes")
    C_a, dofs_a = _top_compliance(xa, y, z, E_a, nu_a, ix, iy)
    C_b, dofs_b = _top_compliance(xb, y, z, E_b, nu_b, ix, iy)
    C_a += C_b
    del C_b
    return _line_contact(C_a, xa, y, ix, iy, radius, load, length, b, False, tol, outer_max,
                         dofs_a + dofs_b, dict(A=dofs_a, B=dofs_b))


def best_estimate(fine: dict, big: dict, small: dict) -> dict:
    """A free end's ratios (mean_last) extrapolated to the finest mesh on the largest block:
    the finest mesh at the base block size plus the change from the base size to the
    largest at the coarse mesh (the two converge separately)."""
    return {k: fine[k] + big[k] - small[k] for k in fine}
