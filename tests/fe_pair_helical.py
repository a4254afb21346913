"""Independent 3D finite-element reference of a helical pair's mesh stiffness and single-pair
stiffness (issue 50 item 6): each member's helical tooth on its whole gear, loaded along
its contact lines, and the pair's load sharing between the lines in contact.

Each member: tests/fe_tooth.py's tooth (the exact transverse section of ToothOutline, the
whole gear on its bore at half the root radius, free end faces, P2 tetrahedra), the section
screwed along the face (each z-plane turned by CylindricalGear.twist_per_length·z: the
prisms lean by the helix) over the whole face, which has no mid-face symmetry: one
factorisation (Tooth3D with z from -b/2 to b/2). The section's elements are fine
(h_patch) along the whole active flank of tooth 0's flank_plus, which carries every load.

Contact lines. On the involute helicoid a contact line is straight on the plane of action,
inclined at β_b: in the member's own (turning) section frame its roll (the distance along
the transverse line of action from the base circle, ρ = sqrt(r² - r_b²)) runs
ρ(z) = ρ0 + σ·tan β_b·z, σ = ±1 from the twist's sense and the flank's (flank_lines). The
pair's roll distances add up to the transverse line of action between the base circles,
ρ1 + ρ2 = (r_b1 + r_b2)·tan α_wt, at every z; the gear's twist is taken opposite the
pinion's (external pair: opposite hands) so that its σ is minus the pinion's. The line
carries load where the pinion's roll lies in the zone of action, between the start of its
active profile (the gear's tip) and its own tip. Mesh positions: M evenly over a base
pitch p_bt; at position p the lines of the pairs k in contact have pinion rolls
ρ_ref + (p + k·M)·p_bt/M: line index i = p + k·M, all on one grid.

Loads and read-outs (mm/N). Tooth 0 of each member is loaded by each line's segments in
turn (the face's strips clipped to the zone, a sliver under 0.3 of a strip joined to its
neighbour): a unit force along the flank's 3D normal into the tooth (its axial part
sin β_b included: the facets' own normals), spread over the segment along the line and
across the profile by a cos² bell `bell` mm wide (in involute arc length), normalised by
the same quadrature. A segment's displacement is read where the contact point's transverse
normal crosses the tooth's centre line in its z-plane (as the spur reference reads "at the
centre line": no contact compression in it), along the 3D normal, averaged over the
segment (Gauss points). That point lies d·cos β_b below the flank's tangent plane (d the
transverse depth), right under the same contact line (shifted along it by d·sin β_b), so
the contact's compression is Weber's plane-strain flattening to that depth, counted once
for each member: the line load per mm of contact line q·cos β_b (q per mm of face), the
Hertz half-width from the normal curvature radii ρ/cos β_b. A line on tooth k of the pair
grid is tooth 0's line read on the neighbour that carries it (the gear's rotational
symmetry: tooth_of), so the compliance between pairs' lines (through the rim and body)
is in.

The pair at a position: the members' compliances summed over the segments of its lines,
plus the Hertz approach, solved for non-negative segment line loads q (N/mm of face) and
the one normal approach δ (a rigid turn closes every contact point of every line by the
same normal distance; no modifications: no initial gaps on the lines) under the normal
load F_n. Mesh stiffness at the position: ISO's transverse force over transverse
deflection per mm of face, F_n·cos²β_b/(b·δ) (as analyses.spur._load_distribution defines
mesh_stiffness_N_per_mm_um); the mesh stiffness c_γα its mean over the positions (one
cycle). Single-pair stiffness c': one pair alone under F_n, its line wholly in the zone of
action (whole face), the same F_n·cos²β_b/(b·δ); its largest over the positions (ISO's
"maximum stiffness of one tooth pair"). Not here: contact off the zone of action (a tip
edge reaching past the path of contact under load: the model's "corner contacts").
Units: mm, N, MPa.
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass, field

import numpy as np

import fe_tooth as ft
from fe_mesh_stiffness import hertz_half_width, weber_flattening


# ----------------------------------------------------------------------------- geometry

@dataclass
class FlankGeometry:
    """A member's loaded flank (flank_plus of tooth 0, z = 0 section): the polyline (tip ->
    form), each point's roll ρ (mm) and involute arc length ρ²/(2 r_b); the twist (rad/mm),
    the base radius, the sense σ of the contact line's roll along z in the turning frame,
    and the sense s_a of the base tangent point's polar angle along the roll (a tooth m
    pitches further carries the roll -s_a·m·p_bt on a fixed line of action)."""

    gear: object
    twist: float
    section: object
    flank: np.ndarray
    roll: np.ndarray
    base: float
    sigma: int
    s_a: int
    tan_base_helix: float

    @property
    def pitch(self) -> float:
        return 2.0 * math.pi / self.gear.teeth

    @property
    def base_pitch(self) -> float:
        return self.base * self.pitch

    @property
    def roll_range(self) -> tuple[float, float]:
        return float(self.roll.min()), float(self.roll.max())

    def tooth_of(self, shift: float) -> int:
        """The tooth (0: the loaded one, +1 the next at +pitch) that carries a contact line
        whose roll is `shift` (mm, a whole number of base pitches) from tooth 0's on a fixed
        line of action."""
        m = -self.s_a * shift / self.base_pitch
        if abs(m - round(m)) > 1e-6:
            raise ValueError(f"a roll shift of {shift} mm is not a whole base pitch")
        return int(round(m))

    def at(self, rho: np.ndarray):
        """At the rolls rho (mm, in the section frame): the flank points (k, 2), the unit
        transverse normals into the tooth (k, 2), the 3D unit normals into the tooth of the
        helicoid (k, 3), the points where the transverse normal crosses the centre line
        y = 0 (k, 2) and the transverse depth to them (k,)."""
        rho = np.atleast_1d(np.asarray(rho, float))
        order = np.argsort(self.roll)
        r_sorted = self.roll[order]
        s = np.concatenate([[0.0], np.cumsum(np.hypot(*np.diff(self.flank, axis=0).T))])
        at = np.interp(rho, r_sorted, s[order])
        pts = np.column_stack([np.interp(at, s, self.flank[:, i]) for i in (0, 1)])
        d = 0.01
        ahead = np.column_stack([np.interp(at + d, s, self.flank[:, i]) for i in (0, 1)])
        back = np.column_stack([np.interp(at - d, s, self.flank[:, i]) for i in (0, 1)])
        tangent = ahead - back
        tangent /= np.hypot(*tangent.T)[:, None]
        normal = np.column_stack([tangent[:, 1], -tangent[:, 0]])
        normal[normal[:, 1] > 0] *= -1.0                   # into the tooth (toward y = 0)
        # the helicoid X(s, z) = R(twist·z)·c(s) + z·e_z: X_s x X_z = (τ_y, -τ_x, κ τ·c)
        axial = self.twist * np.einsum("ij,ij->i", tangent, pts)
        sign = np.sign(np.einsum("ij,ij->i", normal, np.column_stack([tangent[:, 1],
                                                                       -tangent[:, 0]])))
        n3 = np.column_stack([normal, sign * axial])
        n3 /= np.linalg.norm(n3, axis=1)[:, None]
        depth = pts[:, 1] / -normal[:, 1]
        return pts, normal, n3, pts + depth[:, None] * normal, depth


def flank_geometry(gear, twist: float, samples: int = 2000) -> FlankGeometry:
    """The loaded flank of `gear` turning at `twist` rad/mm (its sign free: a mirror image
    of the gear carries the same load on its other flank)."""
    section = ft.tooth_section(gear, samples)
    flank = section.flank_plus[:, :2].copy()
    rb = gear.base_radius
    r = np.hypot(*flank.T)
    roll = np.sqrt(np.maximum(r ** 2 - rb ** 2, 0.0))
    # the base tangent point of each point's normal line: its polar angle along the roll
    mid = len(flank) // 2
    angles = []
    for k in (mid - 50, mid + 50):
        p = flank[k]
        tangent = flank[k + 1] - flank[k - 1]
        normal = np.array([tangent[1], -tangent[0]]) / np.hypot(*tangent)
        for a in (math.atan2(p[1], p[0]) + s * math.acos(rb / r[k]) for s in (1, -1)):
            foot = rb * np.array([math.cos(a), math.sin(a)])
            arm = p - foot
            if abs(arm[0] * normal[1] - arm[1] * normal[0]) < 1e-3 * np.hypot(*arm):
                angles.append(a)
                break
    s_a = int(np.sign((angles[1] - angles[0]) / (roll[mid + 50] - roll[mid - 50])))
    sigma = -int(np.sign(twist)) * s_a if twist else 0
    return FlankGeometry(gear, float(twist), section, flank, roll, rb, sigma, s_a,
                         abs(twist) * rb)


@dataclass
class Segment:
    """Part of contact line `line` (grid index) over z in [z0, z1] (mm), inside the zone."""

    line: int
    z0: float
    z1: float

    @property
    def width(self) -> float:
        return self.z1 - self.z0


@dataclass
class HelicalPairGeometry:
    """The pair's contact lines: pinion and gear flanks, the transverse line of action
    between the base circles (mm), the pinion's zone of action in roll, the face (mm), the
    grid of lines (pinion roll at z = 0 of line i: rho_ref + i·p_bt/M), the strips."""

    pinion: FlankGeometry
    gear: FlankGeometry
    action: float
    zone: tuple[float, float]
    face: float
    positions: int
    rho_ref: float
    strips: np.ndarray
    lines: list[int] = field(default_factory=list)
    segments: list[Segment] = field(default_factory=list)

    @property
    def tan_base_helix(self) -> float:
        return self.pinion.tan_base_helix

    @property
    def cos_base_helix(self) -> float:
        return 1.0 / math.sqrt(1.0 + self.tan_base_helix ** 2)

    def rho0(self, line: int) -> float:
        """The pinion's roll (mm) of `line` at z = 0."""
        return self.rho_ref + line * self.pinion.base_pitch / self.positions

    def pinion_roll(self, line: int, z) -> np.ndarray:
        return self.rho0(line) + self.pinion.sigma * self.tan_base_helix * np.asarray(z, float)

    def gear_roll(self, line: int, z) -> np.ndarray:
        return self.action - self.pinion_roll(line, z)

    def member(self, name: str):
        """The member's flank, its roll function (line, z) -> mm, its zone of action in
        roll (mm)."""
        if name == "pinion":
            return self.pinion, self.pinion_roll, self.zone
        return self.gear, self.gear_roll, (self.action - self.zone[1], self.action - self.zone[0])

    def in_zone(self, line: int) -> tuple[float, float] | None:
        """The z-interval (mm) of `line` inside the zone of action (and the face)."""
        t = self.pinion.sigma * self.tan_base_helix
        if t == 0.0:                                     # spur: the line stands still
            inside = self.zone[0] <= self.rho0(line) <= self.zone[1]
            return (-0.5 * self.face, 0.5 * self.face) if inside else None
        a, b = sorted(((self.zone[0] - self.rho0(line)) / t, (self.zone[1] - self.rho0(line)) / t))
        a, b = max(a, -0.5 * self.face), min(b, 0.5 * self.face)
        return (a, b) if b > a + 1e-9 else None

    def whole(self, line: int) -> bool:
        """The line lies in the zone over the whole face."""
        span = self.in_zone(line)
        return span is not None and span[0] <= -0.5 * self.face + 1e-9 \
            and span[1] >= 0.5 * self.face - 1e-9

    def position_lines(self, p: int) -> list[int]:
        return [i for i in self.lines if (i - p) % self.positions == 0]

    def position_segments(self, p: int) -> np.ndarray:
        keep = set(self.position_lines(p))
        return np.array([k for k, s in enumerate(self.segments) if s.line in keep], int)


def pair_geometry(pair, positions: int, strip: float, twist_sign: float = 1.0,
                  samples: int = 2000, rho_ref: float | None = None) -> HelicalPairGeometry:
    """The contact lines of `pair` (gearset.GearPair, helical, external; a spur pair's lines
    stand along the face): `positions` mesh positions over a base pitch, the face cut in
    strips `strip` mm wide (from -b/2; a whole number of them), the segments of every line
    that touches the zone; line 0's pinion roll at z = 0 rho_ref (mm; default the zone's
    middle)."""
    p, g = pair.pinion, pair.gear
    kp = twist_sign * math.tan(p.helix_angle) / p.pitch_radius
    kg = -twist_sign * math.tan(g.helix_angle) / g.pitch_radius
    fp, fg = flank_geometry(p, kp, samples), flank_geometry(g, kg, samples)
    if fp.sigma != -fg.sigma:
        raise ValueError("the gear's contact line does not follow the pinion's")
    action = (p.base_radius + g.base_radius) * math.tan(pair.working_pressure_angle)
    face = min(p.face_width, g.face_width)
    lo = max(action - fg.roll_range[1], fp.roll_range[0])
    hi = min(fp.roll_range[1], action - fg.roll_range[0])
    n = int(round(face / strip))
    strips = np.linspace(-0.5 * face, 0.5 * face, n + 1)
    geo = HelicalPairGeometry(fp, fg, action, (lo, hi), face, positions,
                              0.5 * (lo + hi) if rho_ref is None else rho_ref, strips)
    reach = 0.5 * face * geo.tan_base_helix + 1e-9
    step = fp.base_pitch / positions
    first = int(math.floor((lo - reach - geo.rho_ref) / step)) - 1
    last = int(math.ceil((hi + reach - geo.rho_ref) / step)) + 1
    for i in range(first, last + 1):
        span = geo.in_zone(i)
        if span is None:
            continue
        pieces = []
        for a, b in zip(strips[:-1], strips[1:]):
            a2, b2 = max(a, span[0]), min(b, span[1])
            if b2 > a2 + 1e-9:
                pieces.append([a2, b2])
        # a sliver under 0.3 of a strip joins its neighbour
        if len(pieces) > 1 and pieces[0][1] - pieces[0][0] < 0.3 * strip:
            pieces[1][0] = pieces.pop(0)[0]
        if len(pieces) > 1 and pieces[-1][1] - pieces[-1][0] < 0.3 * strip:
            pieces[-2][1] = pieces.pop()[1]
        if pieces and pieces[0][1] - pieces[0][0] < 1e-3:
            continue
        geo.lines.append(i)
        geo.segments += [Segment(i, a, b) for a, b in pieces]
    return geo


# ----------------------------------------------------------------------------- one member

@dataclass
class MemberHelical:
    """One member's compliance between the segments (pair-geometry order): matrix[r, c]
    (mm/N) the normal displacement at segment r's centre-line points (its mean) under a
    unit force on segment c, where both belong to lines of one position (else 0); each
    segment's mean transverse depth to the centre line (mm) and mean roll (mm) in the
    member's frame; the mesh's figures and timings."""

    matrix: np.ndarray
    depth: np.ndarray
    roll: np.ndarray
    mesh: dict
    surface: np.ndarray | None = None


def bell(s: np.ndarray, width: float) -> np.ndarray:
    """cos²(π s/width) on |s| < width/2, else 0."""
    return np.where(np.abs(s) < 0.5 * width, np.cos(math.pi * s / width) ** 2, 0.0)


def member_section(flank: FlankGeometry, zone: tuple[float, float], h_patch: float,
                   h_tooth: float, h_far: float, growth: float, margin: float = 0.8,
                   site: float | None = None):
    """The section mesh: fine (h_patch) along tooth 0's flank_plus over the rolls `zone`
    (mm, this member's) and `margin` mm of arc beyond, its load patch (tag patch0) over
    the same stretch (to the tip corner if it comes within half an element of it); or,
    `site` (mm), a 0.3 mm patch at that radius (on the same refined section: the plane-strain
    checks)."""
    gear = flank.gear
    s = np.concatenate([[0.0], np.cumsum(np.hypot(*np.diff(flank.flank, axis=0).T))])
    order = np.argsort(flank.roll)
    arc = np.interp(np.array(zone), flank.roll[order], s[order])      # from the tip
    top = float(arc.min()) - margin
    top = 0.0 if top < 0.5 * h_patch else top             # up to the tip corner
    bottom = min(float(arc.max()) + margin, s[-1] - 0.05)
    centre = 0.5 * (top + bottom)
    radius = float(np.hypot(*[np.interp(centre, s, flank.flank[:, i]) for i in (0, 1)]))
    dense = np.column_stack([np.interp(np.linspace(top - margin, bottom + margin, 200), s,
                                       flank.flank[:, i]) for i in (0, 1)])
    if site is not None:
        return ft.section_mesh(gear, [site], h_patch, h_tooth, h_far, growth=growth,
                               patch=0.3, refine=dense)
    return ft.section_mesh(gear, [radius], h_patch, h_tooth, h_far, growth=growth,
                           patch=bottom - top, refine=dense)


def member_compliance(geo: HelicalPairGeometry, name: str, h_patch: float,
                      h_tooth: float, h_far: float, growth: float, layer: float,
                      bell_width: float = 0.6, gauss: int = 3, threads: int = 1,
                      E: float = ft.E_STEEL, nu: float = ft.NU_STEEL, intorder: int = 6,
                      axial: bool = True, log=print) -> MemberHelical:
    """One member's ("pinion" or "gear") compliance between geo's segments. Section sizes
    as fe_tooth.section_mesh (h_patch along the whole active flank), z-planes every
    `layer` mm at most with the strips' edges among them, the whole face; `threads` BLAS
    threads for the factor's large fronts; the load's bell `bell_width` mm across the
    profile, integrated at `intorder` on the facets; `gauss` points per layer for the
    read-outs. axial=False drops the load's axial part (sin β_b of it) and reads the
    displacement along the normal's transverse part only: what a model of transverse
    slices sees (a diagnostic of the axial load path through the tooth and the body)."""
    from skfem import FacetBasis, LinearForm, asm

    t0 = time.perf_counter()
    flank, rolls, zone = geo.member(name)
    S = member_section(flank, zone, h_patch, h_tooth, h_far, growth)
    t_section = time.perf_counter() - t0
    z = np.concatenate([np.linspace(a, b, max(1, int(math.ceil((b - a) / layer - 1e-9))) + 1)[:-1]
                        for a, b in zip(geo.strips[:-1], geo.strips[1:])] + [geo.strips[-1:]])
    T = ft.Tooth3D(S, z, E, nu, factorise=False, twist=flank.twist, threads=threads)
    t_assemble = time.perf_counter() - t0 - t_section
    # loads: every segment, over tooth 0's active flank facets
    sel = T.facets[T.facet_tags == "patch0"]
    fb = FacetBasis(T.mesh, T.element, facets=sel, intorder=intorder)
    x = np.asarray(fb.global_coordinates())                 # (3, facets, points)
    rb = flank.base
    rho_x = np.sqrt(np.maximum(x[0] ** 2 + x[1] ** 2 - rb ** 2, 0.0))
    s_x = rho_x ** 2 / (2.0 * rb)
    dx = fb.dx

    @LinearForm
    def traction(v, w):
        return -(w.n[0] * v[0] + w.n[1] * v[1] + axial * w.n[2] * v[2]) * w.g

    cols = []
    for seg in geo.segments:
        rho_c = rolls(seg.line, x[2])
        g = bell(s_x - rho_c ** 2 / (2.0 * rb), bell_width)
        g = g * ((x[2] >= seg.z0) & (x[2] <= seg.z1))
        area = float(np.sum(g * dx))
        if area <= 0.0:
            raise ValueError(f"segment {seg} misses the mesh's patch")
        cols.append(asm(traction, fb, g=g / area))
    F = np.column_stack(cols)
    t1 = time.perf_counter()
    factor = T.factor("full")
    t_factor = time.perf_counter() - t1
    t1 = time.perf_counter()
    U = factor.solve(F)
    t_solve = time.perf_counter() - t1
    factor_info = dict(nonzeros=factor.nnz, flops=factor.flops,
                       peak_front_bytes=factor.peak_front_bytes,
                       update_bytes_peak=factor.update_bytes_peak, timing=factor.timing,
                       threads_used=factor.threads_used, calibration=factor.calibration)
    del factor
    surface = F.T @ U                                       # work-conjugate, a diagnostic
    # read-outs: each segment's centre-line points on the tooth that carries its line
    xg, wg = np.polynomial.legendre.leggauss(gauss)
    nseg = len(geo.segments)
    depth, roll = np.zeros(nseg), np.zeros(nseg)
    matrix = np.zeros((nseg, nseg))
    line_of = np.array([s.line for s in geo.segments])
    for r, seg in enumerate(geo.segments):
        cuts = z[(z > seg.z0 + 1e-9) & (z < seg.z1 - 1e-9)]
        edges = np.concatenate([[seg.z0], cuts, [seg.z1]])
        spans = list(zip(edges[:-1], edges[1:]))
        zq = np.concatenate([0.5 * (a + b) + 0.5 * (b - a) * xg for a, b in spans])
        wq = np.concatenate([0.5 * (b - a) * wg for a, b in spans]) / seg.width
        rho = rolls(seg.line, zq)
        _, _, n3, centre, d = flank.at(rho)
        depth[r], roll[r] = wq @ d, wq @ rho
        same = np.flatnonzero((line_of - seg.line) % geo.positions == 0)
        for line in np.unique(line_of[same]):
            m = flank.tooth_of(float(rolls(seg.line, 0.0) - rolls(int(line), 0.0)))
            turn = m * flank.pitch + flank.twist * zq
            c, s = np.cos(turn), np.sin(turn)
            P = np.vstack([c * centre[:, 0] - s * centre[:, 1],
                           s * centre[:, 0] + c * centre[:, 1], zq])
            N = np.vstack([c * n3[:, 0] - s * n3[:, 1], s * n3[:, 0] + c * n3[:, 1],
                           axial * n3[:, 2]])
            probe = T.basis.probes(P)
            loads = np.flatnonzero(line_of == line)
            vals = (probe @ U[:, loads]).reshape(3, len(zq), len(loads))
            matrix[r, loads] = wq @ np.einsum("ik,ikj->kj", N, vals)
    mesh = dict(S.info, z_planes=len(z), layer=layer, dofs=T.dofs, segments=nseg,
                section_s=t_section, assemble_s=t_assemble, factor_s=t_factor,
                solve_s=t_solve, threads=threads, factor=factor_info,
                seconds=time.perf_counter() - t0)
    log(f"  z = {flank.gear.teeth}: {S.info['vertices']} vertices, {len(z)} z-planes, "
        f"{T.dofs} dofs, {nseg} load cases; factor {t_factor:.0f} s "
        f"({factor_info['nonzeros'] / 1e6:.0f} M nonzeros), solves {t_solve:.0f} s, "
        f"{mesh['seconds']:.0f} s in all")
    return MemberHelical(matrix, depth, roll, mesh, surface)


# ----------------------------------------------------------------------------- the pair

def solve_contact(A: np.ndarray, w: np.ndarray, hertz, load: float,
                  gap: np.ndarray | None = None):
    """Line loads q (>= 0, per mm of face) and the approach δ of
    Σ_j A_ij·w_j·q_j + h_i(q_i) + g_i = δ where q_i > 0 (>= δ where q_i = 0), Σ w q = load:
    hertz(q) -> (h, dh/dq); an active set with Newton's method on it (fe_pair_face)."""
    n = len(w)
    gap = np.zeros(n) if gap is None else gap
    active = np.ones(n, bool)
    q, delta = np.full(n, load / w.sum()), 0.0
    for _ in range(4 * n + 4):
        k = np.flatnonzero(active)
        q[~active] = 0.0
        for _ in range(60):
            h, dh = hertz(q)
            residual = np.concatenate([A[k] @ (w * q) + h[k] + gap[k] - delta, [w @ q - load]])
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
            active[k[np.argmin(q[k])]] = False
            continue
        clearance = A @ (w * q) + gap - delta
        if (clearance[~active] < -1e-12).any():
            active[np.flatnonzero(~active)[np.argmin(clearance[~active])]] = True
            continue
        return q.copy(), float(delta)
    raise RuntimeError("the active set did not settle")


class HelicalPair:
    """Both members' compliances on geo's segments and the Hertz approach of the lines;
    coupled=False drops the compliance between different lines (the teeth of different
    pairs then deflect apart, as if the bodies did not carry one tooth's load to the
    others)."""

    def __init__(self, geo: HelicalPairGeometry, pinion: MemberHelical, gear: MemberHelical,
                 E: float = ft.E_STEEL, nu: float = ft.NU_STEEL, coupled: bool = True):
        self.geo, self.E, self.nu = geo, E, nu
        self.compliance = pinion.matrix + gear.matrix
        if not coupled:     # a diagnostic: each line's teeth alone, no load through the body
            lines = np.array([s.line for s in geo.segments])
            self.compliance = np.where(lines[:, None] == lines[None, :], self.compliance, 0.0)
        self.widths = np.array([s.width for s in geo.segments])
        c = geo.cos_base_helix
        self.depths = (pinion.depth * c, gear.depth * c)        # below the tangent plane
        self.rho_n = (pinion.roll / c, gear.roll / c)           # normal curvature radii

    def hertz(self, idx: np.ndarray):
        """The Hertz approach function of the segments idx: q (N/mm of face) -> (h, dh/dq)."""
        c = self.geo.cos_base_helix
        K = 2.0 * (1.0 - self.nu ** 2) / (math.pi * self.E)
        r1, r2 = self.rho_n[0][idx], self.rho_n[1][idx]
        d1, d2 = self.depths[0][idx], self.depths[1][idx]

        def f(q):
            line = np.maximum(np.asarray(q, float), 1e-12) * c   # per mm of contact line
            b = np.array([hertz_half_width(v, a, bb, self.E, self.nu)[0]
                          for v, a, bb in zip(line, r1, r2)])
            h = np.array([weber_flattening(v, bh, da, self.E, self.nu)
                          + weber_flattening(v, bh, db, self.E, self.nu)
                          for v, bh, da, db in zip(line, b, d1, d2)])
            return h, c * (h / line - K)
        return f

    def solve(self, idx: np.ndarray, load: float):
        """Line loads (N/mm of face) on the segments idx and the approach (mm) under the
        normal load (N)."""
        A = self.compliance[np.ix_(idx, idx)]
        return solve_contact(A, self.widths[idx], self.hertz(idx), load)

    def stiffness(self, load: float) -> dict:
        """Per position: the mesh stiffness F_n·cos²β_b/(b·δ) (N/(mm·µm)), the approach
        (µm), the pairs' lines and their loads (N); the mean (c_γα); per line wholly in the
        zone, its single-pair stiffness under the whole load; their largest (c')."""
        geo, c2 = self.geo, self.geo.cos_base_helix ** 2
        positions = []
        for p in range(geo.positions):
            idx = geo.position_segments(p)
            q, delta = self.solve(idx, load)
            lines = [geo.segments[k].line for k in idx]
            loads = {int(i): float(sum(w * v for w, v, j in zip(self.widths[idx], q, lines)
                                       if j == i)) for i in sorted(set(lines))}
            positions.append(dict(
                position=p, rho0_pair0=geo.rho0(p), approach_um=1e3 * delta,
                stiffness=load * c2 / (geo.face * 1e3 * delta), line_loads_N=loads,
                segments=[[geo.segments[k].line, geo.segments[k].z0, geo.segments[k].z1,
                           float(v)] for k, v in zip(idx, q)]))
        single = {}
        for i in geo.lines:
            if geo.whole(i):
                idx = np.array([k for k, s in enumerate(geo.segments) if s.line == i])
                q, delta = self.solve(idx, load)
                single[int(i)] = dict(rho0=geo.rho0(i), approach_um=1e3 * delta,
                                      stiffness=load * c2 / (geo.face * 1e3 * delta),
                                      K_H_beta=float(q.max() / (load / geo.face)))
        mesh = float(np.mean([p["stiffness"] for p in positions]))
        return dict(positions=positions, mesh_stiffness=mesh, single=single,
                    single_stiffness=max(v["stiffness"] for v in single.values())
                    if single else None)
