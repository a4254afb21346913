"""Independent 3D finite-element reference of a spur pair's load distribution along the face
(issue 50 item 6): where one pair carries the whole load, the line load along the face and
the pair's approach under a misalignment, from each member's FE tooth on its body.

Each member: tests/fe_tooth.py's 3D tooth (the exact transverse section, every tooth of the
whole gear on its body, the bore at half the root radius held, free end faces; P2
tetrahedra, the symmetric and antisymmetric halves about mid-face), loaded on its flank at
the contact's radius along the transverse normal (the line of action) by a unit force
spread evenly over a patch `patch` mm up the profile × one face strip, strip by strip. Its
strip compliance A[i, j] (mm/N) is the normal displacement at the tooth's centre line (where
the load's line of action crosses it: no contact compression in it) averaged over strip i
(Gauss points in each z-layer) under the unit force on strip j: a Galerkin (work-conjugate
in the strips' means) compliance of the line load taken constant on each strip.

The pair: the two members' compliances summed, plus each strip's Hertz approach from the
flank to the two centre lines (fe_mesh_stiffness.weber_flattening: the plane-strain
half-plane between the surface at the middle of the Hertz band and the point at the
read-out's depth below it; the band's half-width by hertz_half_width from the flanks'
curvature radii), nonlinear in the strip's line load; the centre-line read-out leaves that
compression out, so it is counted once. The line loads q (N/mm, >= 0) and the rigid approach
δ (mm) solve

    Σ_j A_ij·w_j·q_j + h_i(q_i) + g_i = δ where q_i > 0 (>= δ where q_i = 0),  Σ w_j q_j = F,

w the strips' widths (mm), g the initial gap (the misalignment: slope·(b/2 - z), zero at
end B, z = +b/2) and F the normal load (N), by Newton's method on the active set. Units:
mm, N, MPa.
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass

import numpy as np

import fe_tooth as ft
from fe_mesh_stiffness import hertz_half_width, weber_flattening


def half_face_planes(edges: np.ndarray, layers) -> np.ndarray:
    """The z-planes (mm, z >= 0) of the half face: the strip edges `edges` (from 0 to b/2),
    each strip cut into layers[k] equal layers (an int: the same for every strip)."""
    edges = np.asarray(edges, float)
    layers = np.broadcast_to(np.asarray(layers, int), (len(edges) - 1,))
    planes = [np.linspace(a, b, n + 1)[:-1] for a, b, n in zip(edges[:-1], edges[1:], layers)]
    return np.concatenate(planes + [edges[-1:]])


@dataclass
class MemberCompliance:
    """One member's strip compliance along the whole face: `edges` (mm, -b/2..b/2, the
    strips' edges), `matrix` (mm/N, strips × strips: at the centre line), the read-out
    depth from the flank to the centre line (mm), the mesh's figures, and `surface` (mm/N):
    the loaded patches' mean displacement instead (work-conjugate; it holds the patch's
    own compression, as finely as the mesh resolves the patch)."""

    edges: np.ndarray
    matrix: np.ndarray
    depth: float
    mesh: dict
    surface: np.ndarray | None = None


def member_compliance(gear, radius: float, half_edges: np.ndarray, layers, h_patch: float,
                      h_tooth: float, h_far: float, growth: float, teeth: int | None = None,
                      patch: float = 0.3, E: float = ft.E_STEEL, nu: float = ft.NU_STEEL,
                      gauss: int = 3, log=print) -> MemberCompliance:
    """The strip compliance of `gear`'s tooth loaded at `radius` (mm) on the strips between
    `half_edges` (mm, 0..b/2) and their mirror images; section mesh sizes and body (the
    whole gear, or `teeth` a side) as fe_tooth.section_mesh, `layers` z-layers per strip
    (half_face_planes)."""
    t0 = time.perf_counter()
    S = ft.section_mesh(gear, [radius], h_patch, h_tooth, h_far, teeth=teeth, growth=growth,
                        patch=patch)
    z = half_face_planes(half_edges, layers)
    T = ft.Tooth3D(S, z, E, nu, factorise=False)
    half_edges = np.asarray(half_edges, float)
    strips = list(zip(half_edges[:-1], half_edges[1:]))
    unit = np.column_stack([T.patch_load(0, a, b) for a, b in strips])
    t_factor, nonzeros, u = 0.0, 0, {}
    for kind in ("sym", "anti"):                  # one factor in memory at a time
        t1 = time.perf_counter()
        factor = T.factor(kind)
        t_factor += time.perf_counter() - t1
        nonzeros += factor.nnz
        u[kind] = factor.solve(0.5 * unit)
        del factor
    # strip means at the centre line: Gauss points in each z-layer, weighted by length
    x, w = np.polynomial.legendre.leggauss(gauss)
    points, weights, owner = [], [], []
    for i, (a, b) in enumerate(strips):
        cuts = z[(z >= a - 1e-9) & (z <= b + 1e-9)]
        for lo, hi in zip(cuts[:-1], cuts[1:]):
            points.append(0.5 * (lo + hi) + 0.5 * (hi - lo) * x)
            weights.append(0.5 * (hi - lo) * w / (b - a))
            owner.append(np.full(gauss, i))
    zs, weights, owner = (np.concatenate(v) for v in (points, weights, owner))
    mean = np.zeros((len(strips), len(zs)))
    mean[owner, np.arange(len(zs))] = weights
    site = S.site
    at = np.vstack([np.repeat(site.centre[:, None], len(zs), axis=1), zs[None, :]])
    probe = T.basis.probes(at)
    n = site.normal

    def normal(u):
        v = (probe @ u).reshape(3, len(zs), -1)
        return mean @ (n[0] * v[0] + n[1] * v[1])

    def whole_face(sym, anti):
        """The whole face's strips from the half's: the mirrored half (z < 0, reversed),
        then the half z > 0; sym + anti on the loaded side, sym - anti on the other."""
        flip = slice(None, None, -1)
        near, far = sym + anti, sym - anti
        return np.block([[near[flip, flip], far[flip, :]], [far[:, flip], near]])

    matrix = whole_face(normal(u["sym"]), normal(u["anti"]))
    # the flank's work-conjugate (patch-mean) displacement, a diagnostic of the compression
    surface = whole_face(unit.T @ u["sym"], unit.T @ u["anti"])
    edges = np.concatenate([-half_edges[::-1], half_edges[1:]])
    mesh = dict(S.info, z_planes=len(z), dofs_half=T.dofs, assemble_s=T.timing["assemble"],
                factor_s=t_factor, factor_nonzeros=nonzeros,
                seconds=time.perf_counter() - t0)
    log(f"  z = {gear.teeth} at r = {radius:.3f} mm: {S.info['vertices']} vertices, "
        f"{len(z)} z-planes, {T.dofs} dofs per half, factorised in {t_factor:.0f} s, "
        f"{mesh['seconds']:.0f} s in all")
    return MemberCompliance(edges, matrix, site.depth, mesh, surface)


@dataclass
class PairSolution:
    """The pair's solution: line loads (N/mm) on the strips between `edges` (mm), the rigid
    approach (mm) from first touch, and the normal load (N)."""

    edges: np.ndarray
    line_load: np.ndarray
    approach: float
    load: float

    def on(self, edges: np.ndarray) -> np.ndarray:
        """The mean line loads (N/mm) on the strips between `edges` (mm, within the face):
        the load on this solution's strips (constant on each) integrated over each."""
        below = np.concatenate([[0.0], np.cumsum(self.line_load * np.diff(self.edges))])
        cumulative = np.interp(edges, self.edges, below)
        return np.diff(cumulative) / np.diff(edges)


class PairFaceLoad:
    """Two members' strip compliances (MemberCompliance on the same strips) and the Hertz
    approach of their line contact: curvature radii rho (mm) of the flanks at the contact,
    E (MPa), nu of both."""

    def __init__(self, pinion: MemberCompliance, gear: MemberCompliance, rho: tuple,
                 E: float = ft.E_STEEL, nu: float = ft.NU_STEEL):
        if not np.allclose(pinion.edges, gear.edges):
            raise ValueError("the members' strips differ")
        self.edges, self.widths = pinion.edges, np.diff(pinion.edges)
        self.centres = 0.5 * (self.edges[1:] + self.edges[:-1])
        self.compliance = pinion.matrix + gear.matrix
        self.depths, self.rho, self.E, self.nu = (pinion.depth, gear.depth), rho, E, nu

    def hertz(self, q: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """Each strip's Hertz approach (mm) between the flanks and the two centre lines under
        the line loads q (N/mm) and its derivative (mm²/N): Weber's flattening of each
        member to its read-out depth, K·q·[ln(2d/b) - ν/(2(1 - ν))], K = 2(1 - ν²)/(πE),
        with the half-width b ∝ sqrt(q) (so d/dq adds -K/2 per member)."""
        q = np.maximum(np.asarray(q, float), 1e-12)
        b = np.array([hertz_half_width(v, *self.rho, self.E, self.nu)[0] for v in q])
        h = sum(np.array([weber_flattening(v, bb, d, self.E, self.nu) for v, bb in zip(q, b)])
                for d in self.depths)
        K = 2.0 * (1.0 - self.nu ** 2) / (math.pi * self.E)
        return h, h / q - 0.5 * K * len(self.depths)

    def solve(self, load: float, slope: float) -> PairSolution:
        """Line loads and approach under the normal load `load` (N) with the misalignment
        `slope` (rad in the plane of action, > 0 closing end B at z = +b/2): the initial
        gap slope·(b/2 - z) (or from end A for a negative slope), q >= 0 by an active set
        (the most negative strip dropped, the most overlapping one taken back), Newton's
        method on it for (q, δ)."""
        z, w, A = self.centres, self.widths, self.compliance
        gap = slope * (self.edges[-1] - z) if slope >= 0 else -slope * (z - self.edges[0])
        n = len(z)
        active = np.ones(n, bool)
        q, delta = np.full(n, load / w.sum()), 0.0
        for _ in range(4 * n):
            k = np.flatnonzero(active)
            q[~active] = 0.0
            for _ in range(60):
                h, dh = self.hertz(q)
                residual = np.concatenate([A[k] @ (w * q) + h[k] + gap[k] - delta,
                                           [w @ q - load]])
                J = np.zeros((len(k) + 1, len(k) + 1))
                J[:-1, :-1] = A[np.ix_(k, k)] * w[k] + np.diag(dh[k])
                J[:-1, -1] = -1.0
                J[-1, :-1] = w[k]
                step = np.linalg.solve(J, -residual)
                q[k] += step[:-1]
                delta += step[-1]
                if np.max(np.abs(step[:-1])) < 1e-9 * load / w.sum():
                    break
            if (q[k] < 0).any():
                drop = k[np.argmin(q[k])]
                active[drop] = False
                continue
            clearance = A @ (w * q) + gap - delta           # h(0) = 0 off the contact
            if (clearance[~active] < -1e-12).any():
                active[np.flatnonzero(~active)[np.argmin(clearance[~active])]] = True
                continue
            return PairSolution(self.edges, q.copy(), float(delta), load)
        raise RuntimeError("the active set did not settle")
