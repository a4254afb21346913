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

A worm set's members are sliced in their own planes: the wheel tooth in its mid-plane,
its loads placed by their height from the throat circle (WheelToothCompliance), the worm
thread in its axial section, coupled along the thread (ThreadCompliance).

The reduced model is corrected to 3D finite elements of whole gears (tests/fe_tooth.py:
scikit-fem, quadratic tetrahedra, the gear on a bore of r_f/2, free end faces;
benchmarks/fe_tooth_face.py), which it missed by more than 10 %: the slice compliance came
out 20-24 % above the FE's under a load uniform along the face (0.815 of it on the
20-tooth pinion: the beam's shear term of a short tooth and Sainsot's body are soft), the
deflection decays along the face over twice Vlasov's λ, and a load at a face end deflects
2.36 times the mid-face one, which a Pasternak line cannot give (at most 2). A cylindrical
gear's (or spline's) teeth therefore take SLICE_FACTOR times the slice compliance and a
coupling length COUPLING_PER_ROOT_CHORD times the root chord S_f (the decay length scales
with it: 0.732, 0.720 and 0.755 S_f on three teeth), fitted on the 20-tooth pinion of
spur_crowned_20_60 at its pitch radius and checked on a z = 17, m = 4 tooth and the
60-tooth gear, not fitted (c within 3 %, λ within 3 % at the pitch radius, 13 % on the
60-tooth gear 1.5 mm above it).

At a free face end the coupling fades (contact.structure: end_layer, FaceCoupling): the
line's coupling is the plate's twisting stiffness, and a plate's twisting moment vanishes at
a free edge within Reissner's boundary layer, of decay length t/sqrt(10) for a plate t
thick (E. Reissner, J.
Appl. Mech. 12 (1945) A69-A77: the edge-zone equation ψ - (t²/10)∇²ψ = 0), t here the
tooth's thickness at the load. With w' = 0 at its ends instead, the line was too stiff at an
end under a load that varies along the face: held to a tilt (a misalignment) it needs the
end forces ±λ²w'/c, which loaded the end strips too much (the end rise of issue 50 item 6:
with uncoupled slices the load is linear to the end, and the half-space's free-end mirror
takes 2 % off the end instead), and a load at the end deflected the tooth at most twice the
mid-face one, the FE's 2.16-2.39 (benchmarks/fe_tooth_face.py). The layer that gives the
line (FE's slice compliance, the model's λ) FE's deflection under a load on a 0.5 mm strip
0.1 mm from the end came out 1.7 mm on the 25-tooth pinion, 1.45 mm on the 75-tooth gear of
benchmarks/fe_face_load.py, Reissner's 1.48 and 1.45 mm; the model takes Reissner's, not a
fit. With it a 1 mm patch at a face end deflects the tooth 2.07-2.31 times the mid-face one
(1.84-1.87 before; FE 2.16-2.39), within 10 % of FE's deflection at 9 of the 12 sites of
benchmarks/fe_tooth_face.py (three teeth at three radii: -20 % to +8 %, -28 % to -11 %
before; the shortfall grows toward the tip, where the tooth and so its layer are thinner), a
uniform load still deflects the face evenly (the FE's ends 0.97-0.99 of mid-face), and where
one pair of the 25/75 pair carries the whole load, the strip at the loaded end B carries
FE's line load within 1.2 % at 0.22 and 0.9 mrad (-0.1 % and +3.3 % before), K_Hβ FE's
within 1.0 % (likewise), the other strips within 10 % but for the two where FE's contact
ends mid-face at 0.9 mrad: the model's contact runs on about 0.7 mm further, which no single
coupling length follows (tests/test_face_load_fe.py).

A plane-strain FE of the whole 20/60 pair in contact (tests/fe_mesh_stiffness.py) found the
uncorrected single-pair stiffness 11.5 % below its own (the teeth and bodies 18 % too
soft, the contact 8 % too stiff), the corrected one 3.5 % above it; on the 25/75 pair the
corrected one is 2.9 % above the 3D FE's (benchmarks/fe_face_load.py). Worm wheels and
threads keep the uncorrected model (no FE of them yet) and no end layer.

On a grid of contact cells the two members' slices (and a helical tooth's wall,
analytic.tooth_wall) give one symmetric operator u = B·F (contact.structure.
StructureOperator: F the cells' loads, u their deflections along the contact normal), which
the half-space solver adds to its own (pressure.Grid, `structure`): rigid approach, tooth
bending and contact deformation close the initial separation in one system.
Units: mm, N, MPa.
"""

from __future__ import annotations

import functools
import math
from dataclasses import dataclass

import numpy as np
from scipy.integrate import cumulative_trapezoid

from ..analytic.gear_body import chord_green, flexure_green
from ..analytic.hats import hats
from ..analytic.stiffness import foundation_compliance
from ..analytic.tooth_wall import ToothWall
from .structure import (
    FEWEST_NODES,
    MOST_NODES,
    NODES_PER_LAYER,
    NODES_PER_LENGTH,
    FaceCoupling,
    MemberLoading,
    StructureOperator,
    end_layer,
)

#: the shear correction factor of a rectangular section (Chaari et al. 2009, eq (3))
SHEAR_FACTOR = 1.2
#: integration points along a slice, root to tip
SLICE_POINTS = 400
#: load radii at which a member's slice compliance is tabulated, form circle to tip
TABLE_RADII = 64
#: ... and its root loads (ToothCompliance.root_loads), which the gear bodies' coupling
#: reads at every cell of a contact's field
ROOT_TABLE_RADII = 256
#: a tooth's loads on its gear body's flexure per flexure node (ToothCompliance.
#: flexure_loads): the transverse part's two moments, the axial part's force and moments
FLEXURE_PER_NODE = 5
#: the finite-element correction of a gear tooth (see the module): the slice compliance's
#: factor and the coupling length per root chord
SLICE_FACTOR, COUPLING_PER_ROOT_CHORD = 0.815, 0.739


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
    from outside (an assumption, stated in the result's load_sharing). `corrected`: the
    finite-element correction (see the module) applies to these teeth."""

    corrected = True

    def __init__(self, gear, E: float, nu: float, bore_radius: float | None = None):
        from ..surfaces.outline import ToothOutline

        self.gear = gear
        outline = ToothOutline(gear)
        (u0, u1), _ = outline.flanks[1].domain
        section = outline.section(np.linspace(u0, u1, 200), 0.0)
        # the side of tooth 0 (on +x at z = 0) that carries the load: flank, then fillet
        side = np.concatenate([section.flank_plus, section.fillet_plus[1:]])[:, :2]
        side = side * np.array([1.0, np.sign(side[:, 1].mean())])
        root = side[-1]
        inward = -1.0 if gear.internal else 1.0     # the centre line along +x, or -x on a ring
        self._tabulate(side, len(section.flank_plus), inward, np.hypot(*side.T),
                       float(np.hypot(*root)), abs(math.atan2(root[1], inward * root[0])),
                       bore_radius, E, nu)

    def _tabulate(self, side: np.ndarray, flank_points: int, inward: float,
                  radius: np.ndarray, root_radius: float, root_half_angle: float,
                  bore_radius: float | None, E: float, nu: float) -> None:
        """The table from the slice's loaded side: `side` (n, 2) mm from the tip (first) to
        the root (last) in a plane whose x runs along the tooth's centre line (outward, or
        inward on a ring: `inward` -1) and y across it (the flank at y > 0), its first
        `flank_points` the flank, `radius` (n,) each point's load radius (mm); the root's
        radius (mm) and the half angle its chord subtends (rad) for the body term."""
        self.E, self.nu = E, nu
        self._inward = inward
        self.root_radius, self.root_half_angle = root_radius, root_half_angle
        self._root_x = float(side[-1, 0])
        s_side = inward * (side[:, 0] - self._root_x)
        order = np.argsort(s_side)
        s_sorted, half_sorted = s_side[order], side[order, 1]
        keep = np.concatenate([[True], np.diff(s_sorted) > 1e-9])
        self._profile = (s_sorted[keep], half_sorted[keep])
        self.bore_radius = 0.5 * root_radius if bore_radius is None else bore_radius
        flank, radii = side[:flank_points], radius[:flank_points]
        order = np.argsort(radii)
        self._flank = (radii[order], flank[order])
        self.radii = np.linspace(float(radii.min()), float(radii.max()), TABLE_RADII)
        parts = self.slices(self.radii)
        factor = SLICE_FACTOR if self.corrected else 1.0
        lengths = (np.full(TABLE_RADII, COUPLING_PER_ROOT_CHORD * self.root_chord)
                   if self.corrected else parts[4])
        self.matrix = factor * sum(parts[:4])
        self.table = [SliceCompliance(*(factor * float(p[i, i]) for p in parts[:4]),
                                      float(length)) for i, length in enumerate(lengths)]

    @property
    def root_chord(self) -> float:
        """The tooth's root chord S_f (mm): 2·r_f·sin of the root's half angle."""
        return 2.0 * self.root_radius * math.sin(self.root_half_angle)

    def coordinates(self, flank, u: np.ndarray, v: np.ndarray
                    ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """Where the flank points (u, v) load the teeth: the load radius on the slice (mm),
        the position along the face (mm) and the share of a load along the flank's normal
        that bends the slice (the normal's part in the slice's plane, squared): an involute
        helicoid's normal leans by the base helix angle out of the transverse plane."""
        x, y, z = (np.broadcast_to(c, np.shape(u)) for c in flank.point(u, v))
        share = math.cos(self.gear.base_helix_angle) ** 2
        return np.hypot(x, y), np.asarray(z, float), np.full(np.shape(u), share)

    def face_span(self, face: np.ndarray, coupling_length: float) -> tuple[float, float]:
        """The ends (mm) of the face the slices are coupled along: the gear's face."""
        half = 0.5 * self.gear.face_width
        return -half, half

    def slices(self, radius) -> tuple[np.ndarray, ...]:
        """Bending, shear, axial and gear body cross compliance (n × n, mm²/N per unit
        width) of unit line loads on the flank at the n radii `radius` (mm), each along the
        flank's transverse normal into the tooth, and their coupling lengths (n,) (mm)."""
        radius = np.atleast_1d(np.asarray(radius, float))
        x, y, normal = self._on_flank(radius)
        d_s, d_y = self._inward * normal[:, 0], normal[:, 1]
        load_s = self._inward * (x - self._root_x)
        s_profile, half_profile = self._profile
        s = np.linspace(0.0, float(s_profile[-1]), SLICE_POINTS)
        half = np.interp(s, s_profile, half_profile)
        beam = cantilever(s, half, load_s, y, np.column_stack([d_s, d_y]), self.E, self.nu)
        crossing = load_s + d_s * (y / -d_y)          # the load line meets the centre line
        foundation = foundation_compliance(crossing, self.root_chord, self.root_half_angle,
                                           self.root_radius / self.bore_radius,
                                           np.arctan2(np.abs(d_s), np.abs(d_y)), self.E)
        return beam.bending, beam.shear, beam.axial, foundation, beam.coupling_length

    def _on_flank(self, radius: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """The flank points at `radius` (mm, (n,)) in the slice's plane (x along the tooth's
        centre line, y across it, the flank at y > 0) and the flank's unit normal there into
        the tooth ((n, 2): toward its centre line)."""
        radii, points = self._flank
        k = np.clip(np.searchsorted(radii, radius), 1, len(radii) - 1)
        x, y = (np.interp(radius, radii, points[:, i]) for i in (0, 1))
        tangent = points[k] - points[k - 1]
        normal = np.column_stack([-tangent[:, 1], tangent[:, 0]])
        normal /= np.hypot(*normal.T)[:, None]
        normal[normal[:, 1] > 0] *= -1.0          # into the tooth: toward its centre line
        return x, y, normal

    def root_loads(self, radius) -> np.ndarray:
        """(n, 3): a unit load along the flank's normal into the tooth at each of the n radii
        (mm) as the tooth's root chord hands it to the gear body: the radial force, the
        tangential force and the moment (mm) about the chord's middle, in the tooth's frame
        (its centre line on +x, the loaded flank at y > 0; gear_body.chord_green's kinds).
        An external gear's teeth only (a ring's body is held outside). Interpolated in a
        table over the flank (ROOT_TABLE_RADII radii: a field's thousands of cells read
        it, the flank's polyline once)."""
        return self._from_root_table(radius, (0, 1, 2))

    def _from_root_table(self, radius, columns) -> np.ndarray:
        """The root table's `columns` (see _root_table) at the radii (mm), (n, columns)."""
        radii, table = self._root_table
        radius = np.atleast_1d(np.asarray(radius, float))
        return np.column_stack([np.interp(radius, radii, table[:, i]) for i in columns])

    @functools.cached_property
    def _root_table(self) -> tuple[np.ndarray, np.ndarray]:
        """root_loads at ROOT_TABLE_RADII radii over the flank and the flank's point there:
        (radii (mm), (n, 5): the normal's two components, the moment (mm), x and y (mm))."""
        flank_radii, _ = self._flank
        radii = np.linspace(flank_radii[0], flank_radii[-1], ROOT_TABLE_RADII)
        x, y, d = self._on_flank(radii)
        moment = (x - self.root_radius) * d[:, 1] - y * d[:, 0]
        return radii, np.column_stack([d[:, 0], d[:, 1], moment, x, y])

    @functools.cached_property
    def flexure_nodes(self) -> np.ndarray:
        """The face positions (mm from mid-face) of the nodes at which a tooth's root hands
        its load to the body's flexure (gear_body.flexure_green), a cell's load shared
        between its two nodes by hat functions (so that the body's move is continuous along
        the face): a helical tooth's root chord turns along the face, so the nodes are as
        far apart as it turns by the chord's half angle, both face ends among them (a spur
        tooth: one node at mid-face). On the helical reference pair the mesh stiffness
        moves 0.02 % from half that spacing, 0.2 % at twice it."""
        face = self.gear.face_width
        spans = math.ceil(abs(self.gear.twist_per_length) * face / self.root_half_angle - 1e-9)
        return np.zeros(1) if spans == 0 else np.linspace(-0.5 * face, 0.5 * face, spans + 1)

    def flexure_loads(self, radius, z, axial) -> np.ndarray:
        """(n, FLEXURE_PER_NODE per flexure node): a unit load along the flank's 3D normal
        into the tooth at each of the n radii (mm) and face positions z (mm from mid-face),
        of axial part `axial` (along the gear's axis), as the tooth's root chord hands it to
        the body's flexure, shared between the columns of the cell's two flexure nodes (hat
        functions along the face). At each node first the transverse part's moments about
        the rim's tangent and its radius, z·F_r and z·F_t (N·mm; work-conjugate to ψ_r and
        ψ_θ), then the axial part's force F_z (N) and moments -(x - r_f)·F_z and -y·F_z ((x,
        y) the load point in the tooth's frame of root_loads, r_f the root radius):
        PairCompliance.body_coupling leaves the transverse part out on the tooth's own chord,
        where the slices' finite-element correction already holds the body's flexure under
        it."""
        radius = np.atleast_1d(np.asarray(radius, float))
        z = np.broadcast_to(np.asarray(z, float), radius.shape)
        axial = np.broadcast_to(np.asarray(axial, float), radius.shape)
        d_x, d_y, _, x, y = self._from_root_table(radius, range(5)).T
        transverse = z * np.sqrt(np.maximum(1.0 - axial ** 2, 0.0))
        loads = np.column_stack([d_x * transverse, d_y * transverse, axial,
                                 -(x - self.root_radius) * axial, -y * axial])
        nodes = self.flexure_nodes
        if len(nodes) == 1:
            return loads
        out = np.zeros((len(radius), len(nodes), FLEXURE_PER_NODE))
        rows = np.arange(len(radius))
        left, share = hats(nodes, z)
        out[rows, left] = (1.0 - share)[:, None] * loads
        out[rows, left + 1] = share[:, None] * loads
        return out.reshape(len(radius), -1)

    @functools.cached_property
    def roll_sense(self) -> float:
        """+1 where the tooth one pitch counter-clockwise (in the tooth's frame of
        root_loads) meets a fixed line of action further from the base circle than this
        tooth does, else -1: which neighbour carries the contact ahead on the path."""
        radii, points = self._flank
        for start in (0.25, 0.75):
            r0 = radii[0] + start * (radii[-1] - radii[0])
            x, y, d = self._on_flank(np.array([r0]))
            for sense in (1.0, -1.0):
                turn = sense * 2.0 * math.pi / self.gear.teeth
                c, s = math.cos(turn), math.sin(turn)
                turned = points @ np.array([[c, s], [-s, c]])
                # the turned flank's crossing of the line through (x, y) along d
                across = (turned[:, 0] - x[0]) * d[0, 1] - (turned[:, 1] - y[0]) * d[0, 0]
                k = np.flatnonzero(np.sign(across[:-1]) != np.sign(across[1:]))
                if len(k):
                    t = across[k[0]] / (across[k[0]] - across[k[0] + 1])
                    crossing = np.hypot(*(turned[k[0]] + t * (turned[k[0] + 1] - turned[k[0]])))
                    return sense if crossing > r0 else -sense
        raise ValueError("no neighbouring tooth's flank meets the line of action: "
                         "its flank spans less than a base pitch")

    @functools.cached_property
    def wall(self) -> ToothWall | None:
        """The tooth's own give under the axial part of its loads (analytic.tooth_wall): a
        helical tooth's; None on a spur tooth, whose loads have no axial part."""
        if not self.gear.twist_per_length:
            return None
        height, half = self._profile
        return ToothWall(height, half, self.gear.face_width, self.E, self.nu)

    def wall_heights(self, radius) -> np.ndarray:
        """The heights (mm) along the tooth's centre line from the root circle of the flank
        points at the radii (mm): where their loads meet the wall."""
        return self._inward * (self._from_root_table(radius, (3,))[:, 0] - self._root_x)

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


@functools.lru_cache(maxsize=16)
def tooth_compliance(gear, E: float, nu: float) -> ToothCompliance:
    """A gear's ToothCompliance, built once per process for the same teeth and material (a
    sweep's worker reuses it for every sample that leaves the teeth as they are; the table
    is read, never changed)."""
    return ToothCompliance(gear, E, nu)


class WheelToothCompliance(ToothCompliance):
    """A worm wheel's teeth (surfaces.wheel.WormWheelFlank). The slice is the tooth's
    mid-plane section (the enveloped flank at z2 = 0, tooth 0 centred on +x2), continued
    along its last tangent from the hob tip's generated edge to the root circle (a
    straight continuation, thinner than the generated fillet: a little softer). The
    blank's tip and root are tori about the throat circle (radius a, the centre distance,
    in the mid-plane), so a tooth's height is measured from that circle: a point at wheel
    radius r and axial position z loads the slice at a - sqrt((a - r)² + z²); along the
    face the slices couple along z over the face width. The body term is an external
    gear's of the throat root circle (Sainsot), the bore half the root radius unless given.
    Not corrected to finite elements (see the module); the load's part out of the slice's
    plane is left out (no wall: analytic.tooth_wall is a cylindrical gear's tooth)."""

    corrected = False
    wall = None

    def __init__(self, wheel, E: float, nu: float, bore_radius: float | None = None):
        self.wheel = wheel
        u = np.linspace(0.0, 1.0, 200)
        x, y, _ = wheel.point(u, np.zeros_like(u))           # tip (u = 0) to root edge
        flank = np.column_stack([x, y])
        flank = flank * np.array([1.0, np.sign(flank[:, 1].mean())])
        root_radius = 0.5 * wheel.root_diameter
        last, before = flank[-1], flank[-2]
        direction = (last - before) / np.hypot(*(last - before))
        # the nearer t > 0 with |last + t·direction| = root radius
        b, c = float(last @ direction), float(last @ last) - root_radius ** 2
        reach = -b - math.sqrt(max(b * b - c, 0.0))
        fillet = last + np.linspace(0.0, reach, 12)[1:, None] * direction
        side = np.concatenate([flank, fillet])
        root = side[-1]
        self._tabulate(side, len(flank), 1.0, np.hypot(*side.T), root_radius,
                       abs(math.atan2(root[1], root[0])), bore_radius, E, nu)

    def coordinates(self, flank, u, v):
        """The load radius from the throat circle, the axial position and the normal's part
        in the transverse plane squared (see ToothCompliance.coordinates)."""
        sample = flank.evaluate(np.asarray(u, float), np.asarray(v, float), order=1)
        x, y, z = np.moveaxis(sample.points, -1, 0)
        a = self.wheel.centre_distance
        radius = a - np.sqrt((a - np.hypot(x, y)) ** 2 + z ** 2)
        return radius, z, 1.0 - sample.normals[..., 2] ** 2

    def face_span(self, face, coupling_length):
        half = 0.5 * self.wheel.face_width
        return -half, half


#: the part of a worm thread's depth above its root cylinder its table leaves out
THREAD_CLEARANCE = 0.1
#: how far (in coupling lengths) a worm thread's slices are coupled beyond a contact's
#: cells on either side: the thread runs on for turns, so no free end is in reach
THREAD_REACH = 8.0


class ThreadCompliance(ToothCompliance):
    """A worm's thread (surfaces.worm.WormFlank). The slice is its axial section: the
    thread between its flanks in a plane through the worm axis (the flank's axial profile,
    held below the form radius), a cantilever from the root cylinder to the tip, loaded at
    its radius from the axis. Along the thread the slices couple as a Pasternak line with
    no end in reach (THREAD_REACH coupling lengths beyond the contact), the position along
    it being the arc of the thread at the reference radius, r1·θ/cos γ. The body term is
    Sainsot's for a gear of the root radius whose root chord is the thread's axial root
    thickness (the worm's core as the body), the bore half the root radius (a solid
    worm) unless given. Not corrected to finite elements (see the module); no wall (as the
    wheel's)."""

    corrected = False
    wall = None

    def __init__(self, worm, E: float, nu: float, bore_radius: float | None = None):
        self.worm = worm
        root_radius, tip_radius = 0.5 * worm.root_diameter, 0.5 * worm.tip_diameter
        r = np.linspace(tip_radius, root_radius, 200)
        half = np.abs(worm.axial_profile(np.maximum(r, worm.form_radius)))
        side = np.column_stack([r, half])
        # loads from the form radius, or from a tenth of the depth above the root (the
        # mate's tip stays clear of the root cylinder; a load on the root bends nothing)
        lowest = max(worm.form_radius, root_radius + THREAD_CLEARANCE * (tip_radius - root_radius))
        on_flank = int(np.count_nonzero(r >= lowest))
        self._tabulate(side, on_flank, 1.0, r, root_radius,
                       math.asin(min(half[-1] / root_radius, 1.0)), bore_radius, E, nu)

    def coordinates(self, flank, u, v):
        """The radius from the worm axis, the arc along the thread and the normal's part in
        the axial plane squared (see ToothCompliance.coordinates)."""
        sample = flank.evaluate(np.asarray(u, float), np.asarray(v, float), order=1)
        x, y, _ = np.moveaxis(sample.points, -1, 0)
        theta = np.arctan2(y, x)
        middle = float(np.median(theta))
        theta = middle + (theta - middle + math.pi) % (2.0 * math.pi) - math.pi
        normal = sample.normals
        across = -np.sin(theta) * normal[..., 0] + np.cos(theta) * normal[..., 1]
        worm = self.worm
        return (np.hypot(x, y), worm.reference_radius * theta / math.cos(worm.lead_angle),
                1.0 - across ** 2)

    def face_span(self, face, coupling_length):
        reach = THREAD_REACH * coupling_length
        return float(np.min(face)) - reach, float(np.max(face)) + reach


class PairCompliance:
    """The tooth compliance of a pair of members along their faces (the driver's and the
    driven member's ToothCompliance, or a worm's ThreadCompliance and its wheel's
    WheelToothCompliance), applied to a contact's gap field. coupled=False leaves the
    slices independent (a Winkler bed of the same compliance: no coupling, no end
    softening)."""

    def __init__(self, pinion: ToothCompliance, gear: ToothCompliance, coupled: bool = True,
                 bodies: bool = False):
        self.members = {"pinion": pinion, "gear": gear}
        self.coupled = coupled
        #: the members whose gear bodies couple the teeth of different contacts
        #: (body_coupling): with `bodies`, an external cylindrical gear's (a ring's rim is
        #: held from outside, which the annulus held at its bore is not; worm sets and
        #: splines keep their teeth apart)
        self.bodies = {name: bodies and type(teeth) is ToothCompliance
                       and not teeth.gear.internal for name, teeth in self.members.items()}

    def operator(self, cycle, field) -> StructureOperator:
        """The StructureOperator of a gap field (contact.field.GapField) of a contact
        cycle: the cells on material, each member's face position, load radius and share
        from the field's flank parameters, the coupling length at the cells' mean radius."""
        material = field.material
        members, reference = [], []
        for name, teeth in self.members.items():
            flank = getattr(cycle, name)
            u = field.parameters[f"{name}_u"][material]
            v = field.parameters[f"{name}_v"][material]
            radius, face, share = teeth.coordinates(flank, u, v)
            _, length = teeth.at(radius)
            coupling_length = float(np.mean(length)) if self.coupled else 0.0
            start, end = teeth.face_span(face, float(np.mean(length)))
            depth = teeth.half_thickness(float(np.median(radius)))
            layer = end_layer(depth) if teeth.corrected else 0.0
            spacing = coupling_length / NODES_PER_LENGTH
            if layer > 0.0:
                spacing = min(spacing, layer / NODES_PER_LAYER)
            nodes = (MOST_NODES if coupling_length == 0.0 else
                     int(np.clip(math.ceil((end - start) / spacing) + 1, FEWEST_NODES,
                                 MOST_NODES)))
            root, turn = self._root_loads(teeth, flank, u, v, radius, face, share) \
                if self.bodies[name] else (None, 0.0)
            wall = None if teeth.wall is None else (teeth.wall, teeth.wall_heights(radius))
            members.append(MemberLoading(face, radius, share, _extent(field, face),
                                         teeth.radii, teeth.matrix,
                                         FaceCoupling(start, end, coupling_length, nodes, layer),
                                         root, turn, wall))
            reference.append((round(depth, 3), teeth.E, teeth.nu))
        dx, dy = field.spacing
        return StructureOperator(members, material.shape, dx * dy, material, tuple(reference))

    @staticmethod
    def _root_loads(teeth: ToothCompliance, flank, u, v, radius, face, share
                    ) -> tuple[np.ndarray, float]:
        """The cells' unit normal loads as their tooth's root chord hands them to the gear
        body (MemberLoading.root: in plane, then out of plane) and the chord's turn along
        the face (rad/mm) in the tooth's frame of root_loads. The load's axial part is an
        involute helicoid's, sin β_b, its sense and the side of the tooth the flank is on
        from the flank's own normal at the cells' middle (the tooth's frame has the loaded
        flank counter-clockwise of the centre line: a mirror image of the gear where the
        flank is clockwise of it)."""
        middle = int(np.argsort(radius)[len(radius) // 2])
        sample = flank.evaluate(u[middle:middle + 1], v[middle:middle + 1], order=1)
        load = -sample.normals[0]                               # into the tooth
        x, y = sample.points[0, :2]
        mirror = -1.0 if x * load[1] - y * load[0] > 0.0 else 1.0
        axial = math.copysign(math.sin(teeth.gear.base_helix_angle), load[2]) \
            if teeth.gear.twist_per_length else 0.0
        root = np.hstack([teeth.root_loads(radius) * np.sqrt(share)[:, None],
                          teeth.flexure_loads(radius, face, np.full(len(radius), axial))])
        return root, mirror * teeth.gear.twist_per_length

    def body_coupling(self, structures: list[StructureOperator], pairs: list[int]
                      ) -> np.ndarray | None:
        """The gear bodies' coupling of the contacts of one position (their grids'
        `structures`, the tooth pair of each, as the cycle's rows number them): C[k, l, i]
        (R × R) turns the root loads member i's tooth takes from contact l
        (StructureOperator.root_resultants) into the moves of its tooth at contact k (mm,
        rad: root_deflection). In plane gear_body.chord_green over the face width (the rim
        in generalized plane stress), zero for k = l (a tooth's own body is in its slice
        compliance); out of plane gear_body.flexure_green between the teeth's flexure
        nodes, on its own tooth under the load's axial part only (the slices' finite-
        element correction, fitted on whole gears under loads along the face, holds the
        body's flexure under the transverse part). None where no member couples."""
        names = [name for name, on in self.bodies.items() if on]
        if not names:
            return None
        K = len(structures)
        width = structures[0].roots.shape[1] // len(self.members)
        C = np.zeros((K, K, len(self.members), width, width))
        for i, (name, teeth) in enumerate(self.members.items()):
            if not self.bodies[name]:
                continue
            rb = teeth.gear.base_radius
            rolls = [float(np.mean(np.sqrt(np.maximum(s.members[i].radius ** 2 - rb ** 2,
                                                        0.0)))) for s in structures]
            gear = teeth.gear
            nodes = teeth.flexure_nodes
            turn = structures[0].members[i].turn
            plate = (teeth.bore_radius, teeth.root_radius, teeth.root_half_angle, gear.teeth,
                     gear.face_width)
            for k in range(K):
                for l in range(K):
                    # tooth k's place from tooth l (pitches, counter-clockwise in the
                    # tooth's frame): the one whose contact lies further along the path
                    # is the neighbour of roll_sense
                    place = (teeth.roll_sense * math.copysign(1.0, rolls[k] - rolls[l])
                             * abs(pairs[k] - pairs[l]))
                    if pairs[k] != pairs[l]:
                        C[k, l, i, :3, :3] = chord_green(
                            teeth.bore_radius, teeth.root_radius, teeth.root_half_angle,
                            gear.teeth, int(place), teeth.E, teeth.nu) / gear.face_width
                    G = flexure_green(*plate, 2.0 * math.pi * place / gear.teeth
                                      + turn * (nodes[:, None] - nodes[None, :]),
                                      teeth.E, teeth.nu)            # (node, node, 3, 3)
                    # each node's transverse part (ψ_r, ψ_θ), then its axial part (w, ψ_r, ψ_θ)
                    block = np.zeros((len(nodes), FLEXURE_PER_NODE, len(nodes), FLEXURE_PER_NODE))
                    if pairs[k] != pairs[l]:
                        block[:, :2, :, :2] = G[:, :, 1:, 1:].transpose(0, 2, 1, 3)
                    block[:, :2, :, 2:] = G[:, :, 1:, :].transpose(0, 2, 1, 3)
                    block[:, 2:, :, :2] = G[:, :, :, 1:].transpose(0, 2, 1, 3)
                    block[:, 2:, :, 2:] = G.transpose(0, 2, 1, 3)
                    size = len(nodes) * FLEXURE_PER_NODE
                    C[k, l, i, 3:3 + size, 3:3 + size] = block.reshape(size, size)
        return C


def _extent(field, z: np.ndarray) -> float:
    """The length of face (mm) a cell of the field spans, from the face position z of its
    material cells: z fitted as a plane over the cells, |∂z/∂x|·dx + |∂z/∂y|·dy."""
    X, Y = np.meshgrid(field.x, field.y, indexing="ij")
    m = field.material
    # least squares by its normal equations about the means (2 × 2)
    A = np.stack([X[m] - X[m].mean(), Y[m] - Y[m].mean()])
    a, b = np.linalg.solve(A @ A.T, A @ (z - z.mean()))
    dx, dy = field.spacing
    return float(abs(a) * dx + abs(b) * dy)
