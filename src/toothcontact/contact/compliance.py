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
TABLE_RADII = 24


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


def cantilever(s: np.ndarray, half: np.ndarray, load_s: float, load_y: float,
               direction: tuple[float, float], E: float, nu: float
               ) -> tuple[float, float, float, float]:
    """Bending, shear and axial compliance (mm²/N per unit width) and the Vlasov coupling
    length (mm) of a plane cantilever slice: s (n,) the distance from the root section
    along the tooth's centre line (mm, increasing to the tip), half (n,) the half-thickness
    there (mm); a unit load at (load_s, load_y) (load_y its distance from the centre line
    on the loaded side, > 0) along the unit `direction` (d_s, d_y) (d_y < 0: into the
    tooth); E (MPa), nu. See the module for the formulas."""
    s, half = np.asarray(s, float), np.asarray(half, float)
    E_plane, G = E / (1.0 - nu ** 2), E / (2.0 * (1.0 + nu))
    d_s, d_y = direction
    loaded = s <= load_s
    moment = np.where(loaded, (load_s - s) * d_y - load_y * d_s, 0.0)
    area, inertia = 2.0 * half, (2.0 * half) ** 3 / 12.0
    bending = np.trapezoid(np.where(loaded, moment ** 2 / (E_plane * inertia), 0.0), s)
    shear = np.trapezoid(np.where(loaded, SHEAR_FACTOR * d_y ** 2 / (G * area), 0.0), s)
    axial = np.trapezoid(np.where(loaded, d_s ** 2 / (E_plane * area), 0.0), s)
    # the slice's deflection shape: w'' = M/(E'I), w(0) = w'(0) = 0
    curvature = moment / (E_plane * inertia)
    slope = cumulative_trapezoid(curvature, s, initial=0.0)
    deflection = cumulative_trapezoid(slope, s, initial=0.0)
    at_load = np.interp(load_s, s, deflection)
    phi, dphi, ddphi = deflection / at_load, slope / at_load, curvature / at_load
    D = E_plane * inertia
    k = np.trapezoid(D * ddphi ** 2, s)
    G_p = np.trapezoid(D * (2.0 * (1.0 - nu) * dphi ** 2 - 2.0 * nu * phi * ddphi), s)
    return float(bending), float(shear), float(axial), math.sqrt(max(G_p, 0.0) / k)


class ToothCompliance:
    """The slice compliance of one member's teeth (a cylindrical gear, external or ring),
    tabulated over the load radius from the form circle to the tip: the exact transverse
    outline at mid-face (surfaces.outline), the load along the involute's normal.
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
        self.table = [self.slice(r) for r in self.radii]

    def slice(self, radius: float) -> SliceCompliance:
        """The slice under a unit line load on the flank at `radius` (mm), along the
        flank's transverse normal into the tooth."""
        radii, points = self._flank
        k = int(np.clip(np.searchsorted(radii, radius), 1, len(radii) - 1))
        x, y = (float(np.interp(radius, radii, points[:, i])) for i in (0, 1))
        tangent = points[k] - points[k - 1]
        normal = np.array([-tangent[1], tangent[0]]) / math.hypot(*tangent)
        if normal[1] > 0:                  # into the tooth: toward its centre line
            normal = -normal
        d_s, d_y = self._inward * normal[0], normal[1]
        load_s = self._inward * (x - self._root_x)
        s_profile, half_profile = self._profile
        s = np.linspace(0.0, float(s_profile[-1]), SLICE_POINTS)
        half = np.interp(s, s_profile, half_profile)
        bending, shear, axial, length = cantilever(s, half, load_s, y, (d_s, d_y),
                                                   self.E, self.nu)
        crossing = load_s + d_s * (y / -d_y)          # the load line meets the centre line
        root_thickness = 2.0 * self.root_radius * math.sin(self.root_half_angle)
        foundation = foundation_compliance(crossing, root_thickness, self.root_half_angle,
                                           self.root_radius / self.bore_radius,
                                           math.atan2(abs(d_s), abs(d_y)), self.E)
        return SliceCompliance(bending, shear, axial, foundation, length)

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

    def weights(self, z: np.ndarray):
        """(nodes × len(z)) sparse hat-function weights of points at face positions z (mm):
        a load at z goes to its two nearest nodes in proportion; a deflection at z is read
        back with the transpose. Points beyond the face go to its end nodes."""
        from scipy.sparse import csr_matrix

        n = len(self.nodes)
        t = np.clip((np.asarray(z, float) - self.nodes[0])
                    / (self.nodes[-1] - self.nodes[0]) * (n - 1), 0.0, n - 1)
        left = np.minimum(np.floor(t).astype(int), n - 2)
        share = t - left
        cols = np.arange(len(t))
        return csr_matrix((np.concatenate([1.0 - share, share]),
                           (np.concatenate([left, left + 1]), np.concatenate([cols, cols]))),
                          shape=(n, len(t)))


#: nodes per coupling length along the face, and their fewest and most
NODES_PER_LENGTH, FEWEST_NODES, MOST_NODES = 4.0, 21, 241


class MemberLoading:
    """One member's side of a contact grid: the cells' face positions z (mm, along its axis)
    and the length of face a cell spans (`extent`, mm), their slice compliance c along the
    contact normal (mm²/N per unit width: the transverse compliance times the normal's
    transverse part squared) and the member's face coupling."""

    def __init__(self, z: np.ndarray, extent: float, compliance: np.ndarray,
                 coupling: FaceCoupling):
        self.z, self.extent, self.compliance, self.coupling = z, extent, compliance, coupling
        self.weights = coupling.weights(z)
        self._scaled = self.weights.multiply(np.sqrt(compliance)[None, :]).tocsr()
        self._scaled_t = self._scaled.T.tocsr()

    def deflection(self, loads: np.ndarray) -> np.ndarray:
        """Deflections (mm) of the cells along the normal under their loads (N)."""
        return self._scaled_t @ (self.coupling.flexibility @ (self._scaled @ loads))


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
        members = [MemberLoading(m.z[keep], step * m.extent, m.compliance[keep], m.coupling)
                   for m in self.members]
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
            compliance, length = teeth.at(radius)
            # an involute helicoid's normal leans by the base helix angle out of the
            # transverse plane: only its transverse part bends the slices
            transverse = math.cos(teeth.gear.base_helix_angle) ** 2
            half = 0.5 * teeth.gear.face_width
            coupling_length = float(np.mean(length)) if self.coupled else 0.0
            nodes = (MOST_NODES if coupling_length == 0.0 else
                     int(np.clip(math.ceil(2 * half / coupling_length * NODES_PER_LENGTH) + 1,
                                 FEWEST_NODES, MOST_NODES)))
            z = np.asarray(z, float)
            members.append(MemberLoading(z, _extent(field, z), compliance * transverse,
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
