"""Tooth compliance along the face: how far a tooth pair gives under a load spread along the
face, from the exact tooth geometry.

Each member's tooth is cut into transverse slices. A slice is a cantilever of the exact
transverse outline (surfaces.outline: the generated fillet and the flank) from the root
circle to the tip, loaded on its flank along the transverse normal; its compliance per unit
face width (mm²/N: mm of deflection along the load per N/mm of line load) is the
potential-energy sum of Yang & Lin (1987) as written by Chaari, Fakhfakh & Haddar, Eur. J.
Mech. A/Solids 28 (2009) 461-468, eqs (2)-(4): bending ∫ M²/(E'I), shear ∫ 1.2 V²/(G A) and
axial compression ∫ N²/(E'A) over the slice, M, V and N the moment, shear and normal force
of a unit load at each section (E' = E/(1-ν²): a wide tooth is in plane strain); plus the
gear body under the root (analytic.stiffness.foundation_compliance: Sainsot, Velex &
Duverger 2004).

Neighbouring slices hold each other: a tooth is a plate, not a row of springs. The
coupling is a Pasternak (two-parameter) foundation along the face,

    w - λ² w'' = c(z)·q(z),    w' = 0 at free face ends,

c the slice compliance and q the line load (N/mm); its parameters follow from the plate
by Vlasov's variational method (Vlasov & Leont'ev, *Beams, plates and shells on elastic
foundations*, 1966, ch. 1): with the plate deflection w(s, z) = W(z)·φ(s) across the tooth
height (φ the slice's own cantilever deflection shape, 1 at the load), the plate's energy
∫∫ D/2 [(w_ss + w_zz)² - 2(1-ν)(w_ss w_zz - w_sz²)] becomes ∫ [k W² + G_p W'²]/2 dz with
k = ∫ D φ''² ds and G_p = ∫ D [2(1-ν) φ'² - 2ν φ φ''] ds (D = E' t³/12, t the tooth's
thickness at s), so λ = sqrt(G_p/k). A uniform plate of length H loaded at its free edge
gives λ = H·sqrt((2.4 - 3ν)/3) (0.71 H at ν = 0.3). The line's Green's function decays as
exp(-|Δz|/λ)/(2λ) in mid-face; a free end reflects it (the moment-image method of Wellauer
& Seireg, J. Eng. Ind. 82 (1960) 213-222), so a load at the end of a long face deflects the
tooth twice as far as the same load in mid-face: the end softening that misalignment loads.

Across the profile a load at one height bends the whole slice: the cross compliance
C[i, j], the deflection along the normal at radius r_i under a unit line load at r_j, is by
the unit-load method (Maxwell-Betti) ∫ M_i M_j/(E'I) + 1.2 V_i V_j/(GA) + N_i N_j/(E'A)
over the sections below both loads, plus the gear body's bilinear form of Sainsot's fit
(analytic.stiffness.foundation_compliance); its diagonal is the slice compliance above.
A gear's narrow contact band barely needs it; a spline's contact covers the working depth,
where the tooth's rotation under the load is the point. Along the face the plate is taken
as separable: a cell's load goes to (radius × face) nodes by hat functions, which deflect
by C·Q·G (G the Pasternak line's flexibility, per unit slice compliance).

On a grid of contact cells the two members' slices give one symmetric operator u = B·F
(StructureOperator: F the cells' loads, u their deflections along the contact normal),
which the half-space solver adds to its own (pressure.solve_contact, `structure`): rigid
approach, tooth bending and contact deformation close the initial separation in one system.
Units: mm, N, MPa.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from scipy.integrate import cumulative_trapezoid

from ..analytic.stiffness import foundation_compliance

#: the shear correction factor of a rectangular section (Chaari et al. 2009, eq (3))
SHEAR_FACTOR = 1.2
#: integration points along a slice, root to tip
SLICE_POINTS = 400
#: load radii at which a member's slice compliance is tabulated, form circle to tip
TABLE_RADII = 64


@dataclass(frozen=True)
class SliceCompliance:
    """A transverse slice under a unit line load on its flank: compliance per unit face
    width (mm²/N) by part, and the Pasternak coupling length along the face (mm)."""

    bending: float
    shear: float
    axial: float
    foundation: float
    coupling_length: float

    @property
    def total(self) -> float:
        return self.bending + self.shear + self.axial + self.foundation


@dataclass(frozen=True)
class CantileverCompliance:
    """A plane cantilever slice under n unit loads: the (n × n) cross compliances per unit
    width by part (mm²/N; [i, j] the deflection along load i under load j) and each load's
    Vlasov coupling length (n,) (mm)."""

    bending: np.ndarray
    shear: np.ndarray
    axial: np.ndarray
    coupling_length: np.ndarray


def cantilever(s: np.ndarray, half: np.ndarray, load_s, load_y, direction,
               E: float, nu: float) -> CantileverCompliance:
    """Cross compliances and Vlasov coupling lengths of a plane cantilever slice: s (m,) the
    distance from the root section along the tooth's centre line (mm, increasing to the
    tip), half (m,) the half-thickness there (mm); n unit loads at (load_s, load_y) (n,)
    (load_y the distance from the centre line on the loaded side, > 0) along the unit
    directions (n, 2) (d_s, d_y) (d_y < 0: into the tooth); E (MPa), nu. By the unit-load
    method (Maxwell-Betti): [i, j] = ∫ M_i M_j/(E'I) + 1.2 V_i V_j/(GA) + N_i N_j/(E'A)
    over the sections below both loads; the diagonal is Chaari et al.'s eqs (2)-(4). See
    the module for the coupling length."""
    s, half = np.asarray(s, float), np.asarray(half, float)
    load_s, load_y = np.atleast_1d(load_s).astype(float), np.atleast_1d(load_y).astype(float)
    d_s, d_y = np.atleast_2d(np.asarray(direction, float)).T
    E_plane, G = E / (1.0 - nu ** 2), E / (2.0 * (1.0 + nu))
    loaded = s[None, :] <= load_s[:, None]                          # (n loads, m sections)
    moment = np.where(loaded, (load_s[:, None] - s) * d_y[:, None]
                      - (load_y * d_s)[:, None], 0.0)
    area, inertia = 2.0 * half, (2.0 * half) ** 3 / 12.0
    shear_force, normal_force = loaded * d_y[:, None], loaded * d_s[:, None]

    def cross(f, g, stiffness):
        return np.trapezoid(f[:, None, :] * g[None, :, :] / stiffness, s, axis=-1)

    bending = cross(moment, moment, E_plane * inertia)
    shear = cross(shear_force, shear_force, G * area / SHEAR_FACTOR)
    axial = cross(normal_force, normal_force, E_plane * area)
    # each load's deflection shape: w'' = M/(E'I), w(0) = w'(0) = 0
    curvature = moment / (E_plane * inertia)
    slope = cumulative_trapezoid(curvature, s, initial=0.0, axis=-1)
    deflection = cumulative_trapezoid(slope, s, initial=0.0, axis=-1)
    at_load = np.array([np.interp(si, s, w) for si, w in zip(load_s, deflection)])[:, None]
    phi, dphi, ddphi = deflection / at_load, slope / at_load, curvature / at_load
    D = E_plane * inertia
    k = np.trapezoid(D * ddphi ** 2, s, axis=-1)
    G_p = np.trapezoid(D * (2.0 * (1.0 - nu) * dphi ** 2 - 2.0 * nu * phi * ddphi), s, axis=-1)
    return CantileverCompliance(bending, shear, axial, np.sqrt(np.maximum(G_p, 0.0) / k))


class ToothCompliance:
    """The slice compliance of one member's teeth (a cylindrical gear, external or ring),
    tabulated over the load radius from the form circle to the tip: the exact transverse
    outline at mid-face (surfaces.outline), the loads along the involute's normal.
    `matrix` [i, j] (mm²/N per unit face width): the deflection along the normal at
    radii[i] under a unit line load at radii[j]; `table` its diagonal by part.
    bore_radius (mm): the rim's inner radius for the gear body term; None: half the root
    radius (a solid blank on a shaft of half its root diameter). A ring gear takes the body
    term of an external gear of its root circle (h_fi = 2): Sainsot's fit has no rim held
    from outside (an assumption, stated in the result's load_sharing)."""

    def __init__(self, gear, E: float, nu: float, bore_radius: float | None = None):
        from ..surfaces.outline import ToothOutline

        self.gear, self.E, self.nu = gear, E, nu
        outline = ToothOutline(gear)
        (u0, u1), _ = outline.flanks[1].domain
        section = outline.section(np.linspace(u0, u1, 200), 0.0)
        # the side of tooth 0 (on +x at z = 0) that carries the load, in its centre-line
        # frame: s from the root circle toward the tip, y across (the flank at y > 0)
        self._inward = -1.0 if gear.internal else 1.0     # +s along +x, or -x on a ring
        side = np.concatenate([section.flank_plus, section.fillet_plus[1:]])[:, :2]
        if side[:, 1].mean() < 0:
            side = side * np.array([1.0, -1.0])
        root = side[-1]
        self.root_radius = float(np.hypot(*root))
        self.root_half_angle = abs(math.atan2(root[1], self._inward * root[0]))
        self._root_x = float(root[0])
        s_side = self._inward * (side[:, 0] - self._root_x)
        order = np.argsort(s_side)
        s_sorted, half_sorted = s_side[order], side[order, 1]
        keep = np.concatenate([[True], np.diff(s_sorted) > 1e-9])
        self._profile = (s_sorted[keep], half_sorted[keep])
        self.bore_radius = 0.5 * self.root_radius if bore_radius is None else bore_radius
        flank = side[:len(section.flank_plus)]
        radii = np.hypot(*flank.T)
        order = np.argsort(radii)
        self._flank = (radii[order], flank[order])
        self.radii = np.linspace(float(radii.min()), float(radii.max()), TABLE_RADII)
        parts = self.slices(self.radii)
        self.matrix = sum(parts[:4])
        self.table = [SliceCompliance(*(float(p[i, i]) for p in parts[:4]), float(length))
                      for i, length in enumerate(parts[4])]

    def slices(self, radius) -> tuple[np.ndarray, ...]:
        """Bending, shear, axial and gear body cross compliance (n × n, mm²/N per unit
        width) of unit line loads on the flank at the n radii `radius` (mm), each along the
        flank's transverse normal into the tooth, and their coupling lengths (n,) (mm)."""
        radii, points = self._flank
        radius = np.atleast_1d(np.asarray(radius, float))
        k = np.clip(np.searchsorted(radii, radius), 1, len(radii) - 1)
        x, y = (np.interp(radius, radii, points[:, i]) for i in (0, 1))
        tangent = points[k] - points[k - 1]
        normal = np.column_stack([-tangent[:, 1], tangent[:, 0]])
        normal /= np.hypot(*normal.T)[:, None]
        normal[normal[:, 1] > 0] *= -1.0          # into the tooth: toward its centre line
        d_s, d_y = self._inward * normal[:, 0], normal[:, 1]
        load_s = self._inward * (x - self._root_x)
        s_profile, half_profile = self._profile
        s = np.linspace(0.0, float(s_profile[-1]), SLICE_POINTS)
        half = np.interp(s, s_profile, half_profile)
        beam = cantilever(s, half, load_s, y, np.column_stack([d_s, d_y]), self.E, self.nu)
        crossing = load_s + d_s * (y / -d_y)          # the load line meets the centre line
        root_thickness = 2.0 * self.root_radius * math.sin(self.root_half_angle)
        foundation = foundation_compliance(crossing, root_thickness, self.root_half_angle,
                                           self.root_radius / self.bore_radius,
                                           np.arctan2(np.abs(d_s), np.abs(d_y)), self.E)
        return beam.bending, beam.shear, beam.axial, foundation, beam.coupling_length

    def half_thickness(self, radius: float) -> float:
        """The tooth's half-thickness (mm) at `radius` on its flank: the depth to its centre
        line, to which its contact compression is measured (Weber's contact flattening)."""
        radii, points = self._flank
        return float(np.interp(radius, radii, points[:, 1]))

    def at(self, radius) -> tuple[np.ndarray, np.ndarray]:
        """Slice compliance (mm²/N per unit face width) and coupling length (mm) for loads at
        `radius` (mm, array), interpolated in the table (held at its ends)."""
        total = np.array([c.total for c in self.table])
        length = np.array([c.coupling_length for c in self.table])
        r = np.asarray(radius, float)
        return np.interp(r, self.radii, total), np.interp(r, self.radii, length)


class FaceCoupling:
    """The Pasternak line along one member's face, [start, end] (mm, along its axis), on
    `nodes` equally spaced nodes (hat functions): the flexibility G (mm per N, per unit
    slice compliance) taking the nodes' loads Q to their deflections, w = G·Q, from the
    finite-volume form of w - λ² w'' = c·q with free ends: (V - λ²·K)·w = Q, V the nodes'
    widths (half at the ends), K the second difference (zero flux through the ends). Under
    a uniform line load q every node deflects c·q; under a point load it approaches
    the continuous Green's function cosh(z_</λ)·cosh((L - z_>)/λ)/(λ·sinh(L/λ))."""

    def __init__(self, start: float, end: float, coupling_length: float, nodes: int):
        self.nodes = np.linspace(start, end, nodes)
        step = (end - start) / (nodes - 1)
        widths = np.full(nodes, step)
        widths[[0, -1]] = 0.5 * step
        self.widths = widths
        K = (np.diag(np.full(nodes, -2.0)) + np.diag(np.ones(nodes - 1), 1)
             + np.diag(np.ones(nodes - 1), -1))
        K[0, 0] = K[-1, -1] = -1.0
        self.flexibility = np.linalg.inv(np.diag(widths) - coupling_length ** 2 / step * K)


def hats(nodes: np.ndarray, values: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The hat functions on the increasing, equally spaced `nodes` at `values`: each value's
    left node (int) and the share (0..1) its right neighbour takes; the left one takes the
    rest. Values beyond the nodes go to the end nodes."""
    n = len(nodes)
    t = np.clip((np.asarray(values, float) - nodes[0]) / (nodes[-1] - nodes[0]) * (n - 1),
                0.0, n - 1)
    left = np.minimum(np.floor(t).astype(int), n - 2)
    return left, t - left


#: nodes per coupling length along the face, and their fewest and most
NODES_PER_LENGTH, FEWEST_NODES, MOST_NODES = 4.0, 21, 241


class MemberLoading:
    """One member's side of a contact grid: the cells' face positions z (mm, along its axis)
    and load radii (mm), the length of face a cell spans (`extent`, mm), the member's
    profile compliance (`radii` (mm) and `matrix` (mm²/N per unit width) of its
    ToothCompliance, along the contact normal: times the normal's transverse part squared)
    and its face coupling. A cell's load goes to the (radius × face) nodes by hat weights;
    the nodes deflect by matrix·Q·G (profile compliance across, face coupling along), read
    back at the cells with the same weights."""

    def __init__(self, z: np.ndarray, radius: np.ndarray, extent: float, radii: np.ndarray,
                 matrix: np.ndarray, coupling: FaceCoupling):
        self.z, self.radius, self.extent = z, radius, extent
        self.radii, self.matrix, self.coupling = radii, matrix, coupling
        across, across_share = hats(radii, radius)
        along, along_share = hats(coupling.nodes, z)
        used = np.unique(np.concatenate([across, across + 1]))
        self._profile = matrix[np.ix_(used, used)]
        self._shape = (len(used), len(coupling.nodes))
        # each cell's four nodes (row-major in the shape) and its weights on them
        across = np.searchsorted(used, across)
        self._nodes = np.concatenate([(a * self._shape[1] + k)
                                      for a in (across, across + 1)
                                      for k in (along, along + 1)])
        self._weights = np.concatenate([wa * wk
                                        for wa in (1.0 - across_share, across_share)
                                        for wk in (1.0 - along_share, along_share)])
        self._cells = np.tile(np.arange(len(z)), 4)

    def deflection(self, loads: np.ndarray) -> np.ndarray:
        """Deflections (mm) of the cells along the normal under their loads (N)."""
        nodes = np.bincount(self._nodes, self._weights * loads[self._cells],
                            minlength=self._shape[0] * self._shape[1]).reshape(self._shape)
        at_nodes = (self._profile @ nodes @ self.coupling.flexibility).ravel()
        return (at_nodes[self._nodes] * self._weights).reshape(4, -1).sum(axis=0)


class StructureOperator:
    """u = B·p on a contact's grid: both members' teeth bending under the pressure p (MPa on
    the grid's cells of area `cell` mm²), u (mm) along the contact normal. Symmetric and
    positive semi-definite, so the constrained conjugate gradients take it as they take
    the half-space's influence."""

    def __init__(self, members: list[MemberLoading], shape: tuple[int, int], cell: float,
                 active: np.ndarray, reference: tuple):
        self.members, self.shape, self.cell = members, shape, cell
        self.active = np.flatnonzero(active.ravel())
        #: ((depth mm, E MPa, nu) per member): the contact's compression is measured to
        #: the teeth's centre lines (pressure.InfluenceOperator), where the slices' bending
        #: is measured from
        self.reference = reference

    def __call__(self, p: np.ndarray) -> np.ndarray:
        loads = np.asarray(p, float).ravel()[self.active] * self.cell
        u = np.zeros(int(np.prod(self.shape)))
        u[self.active] = sum(m.deflection(loads) for m in self.members)
        return u.reshape(self.shape)

    def coarsened(self, step: int) -> "StructureOperator":
        """The operator on the grid taken every `step`-th cell along both axes (cells
        `step`² times larger), for a coarse first solve."""
        n0, n1 = self.shape
        coarse = np.zeros(self.shape, bool)
        coarse[::step, ::step] = True
        keep = coarse.ravel()[self.active]
        shape = (len(range(0, n0, step)), len(range(0, n1, step)))
        active = np.zeros(self.shape, bool).ravel()
        active[self.active[keep]] = True
        members = [MemberLoading(m.z[keep], m.radius[keep], step * m.extent, m.radii,
                                 m.matrix, m.coupling) for m in self.members]
        return StructureOperator(members, shape, self.cell * step * step,
                                 active.reshape(self.shape)[::step, ::step], self.reference)

    def line_load(self, p: np.ndarray, edges: np.ndarray, member: int = 0) -> np.ndarray:
        """The mean load per unit face width (N/mm) on the strips between `edges` (mm,
        increasing, along the member's axis) under the pressure p (MPa)."""
        m = self.members[member]
        loads = np.asarray(p, float).ravel()[self.active] * self.cell
        # each cell's load spread evenly over the face it spans: the load below each edge
        below = np.clip((np.asarray(edges, float)[:, None] - m.z[None, :]) / m.extent + 0.5,
                        0.0, 1.0) @ loads
        return np.diff(below) / np.diff(edges)


class PairCompliance:
    """The tooth compliance of a pair of cylindrical members along their faces (pinion and
    gear ToothCompliance), applied to a contact's gap field. coupled=False leaves the slices
    independent (a Winkler bed of the same compliance: no coupling, no end softening)."""

    def __init__(self, pinion: ToothCompliance, gear: ToothCompliance, coupled: bool = True):
        self.members = {"pinion": pinion, "gear": gear}
        self.coupled = coupled

    def operator(self, cycle, field) -> StructureOperator:
        """The StructureOperator of a gap field (contact.field.GapField) of a contact
        cycle: the cells on material, each member's face position and radius from the
        field's flank parameters, the coupling length at the cells' mean radius."""
        material = field.material
        members, reference = [], []
        for name, teeth in self.members.items():
            flank = getattr(cycle, name)
            u = field.parameters[f"{name}_u"][material]
            v = field.parameters[f"{name}_v"][material]
            x, y, z = (np.broadcast_to(c, u.shape) for c in flank.point(u, v))
            radius = np.hypot(x, y)
            _, length = teeth.at(radius)
            # an involute helicoid's normal leans by the base helix angle out of the
            # transverse plane: only its transverse part bends the slices
            transverse = math.cos(teeth.gear.base_helix_angle) ** 2
            half = 0.5 * teeth.gear.face_width
            coupling_length = float(np.mean(length)) if self.coupled else 0.0
            nodes = (MOST_NODES if coupling_length == 0.0 else
                     int(np.clip(math.ceil(2 * half / coupling_length * NODES_PER_LENGTH) + 1,
                                 FEWEST_NODES, MOST_NODES)))
            z = np.asarray(z, float)
            members.append(MemberLoading(z, radius, _extent(field, z), teeth.radii,
                                         teeth.matrix * transverse,
                                         FaceCoupling(-half, half, coupling_length, nodes)))
            depth = teeth.half_thickness(float(np.median(radius)))
            reference.append((round(depth, 3), teeth.E, teeth.nu))
        dx, dy = field.spacing
        return StructureOperator(members, material.shape, dx * dy, material, tuple(reference))


def _extent(field, z: np.ndarray) -> float:
    """The length of face (mm) a cell of the field spans, from the face position z of its
    material cells: z fitted as a plane over the cells, |∂z/∂x|·dx + |∂z/∂y|·dy."""
    X, Y = np.meshgrid(field.x, field.y, indexing="ij")
    m = field.material
    A = np.column_stack([X[m], Y[m], np.ones(z.size)])
    (a, b, _), *_ = np.linalg.lstsq(A, z, rcond=None)
    dx, dy = field.spacing
    return float(abs(a) * dx + abs(b) * dy)
