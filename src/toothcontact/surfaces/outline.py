"""A cylindrical gear's tooth in a transverse section, as exact points.

One tooth runs from the centre of the space before it to the centre of the space after it:
half root arc, fillet, flank, tip arc, flank, fillet, half root arc. The flanks carry the
gear's modifications (a modification moves a point off its section along the normal, so
the axial parameter is corrected until the point lies in the plane); the generated fillet
(by the rack, or by a shaper cutter on a ring; on an undercut gear the trochoid that cuts
into the involute, up to the form circle) turns with the helix and moves with the flank's
form end. The B-spline solids (cad.gear) and the collision meshes (mesh.gear_mesh) are both
made from these sections. Units: mm, rad; gear centre at the origin, tooth 0 on +x.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from functools import cached_property

import numpy as np

from .base import Flank
from .generation import GeneratedSide, generate_ring_side, generate_side
from .involute import CylindricalGear
from .modified import ModifiedFlank
from .modify import FlankModifications


def polar(radius: float, angle: float, z: float) -> tuple[float, float, float]:
    """The point at `radius` and polar `angle` in the plane z."""
    return radius * math.cos(angle), radius * math.sin(angle), z


def arc_points(radius: float, start: float, end: float, z: float, count: int) -> np.ndarray:
    """`count` points on the circle of `radius` from polar angle `start` to `end`."""
    angles = np.linspace(start, end, count)
    return np.column_stack([radius * np.cos(angles), radius * np.sin(angles),
                            np.full(count, z)])


def polar_angle(point, near: float = 0.0) -> float:
    """The polar angle (rad) of a point, taken within half a turn of `near`."""
    angle = math.atan2(point[1], point[0]) - near
    return near + math.atan2(math.sin(angle), math.cos(angle))


def arc_through(start: np.ndarray, middle: np.ndarray, end: np.ndarray, count: int
                ) -> np.ndarray:
    """`count` points on the circular arc from `start` through `middle` to `end` (points
    in one plane z, (3,) each)."""
    (ax, ay), (bx, by), (cx, cy) = start[:2], middle[:2], end[:2]
    d = 2.0 * (ax * (by - cy) + bx * (cy - ay) + cx * (ay - by))
    ux = ((ax**2 + ay**2) * (by - cy) + (bx**2 + by**2) * (cy - ay) + (cx**2 + cy**2) * (ay - by)) / d
    uy = ((ax**2 + ay**2) * (cx - bx) + (bx**2 + by**2) * (ax - cx) + (cx**2 + cy**2) * (bx - ax)) / d
    a0, am, a1 = (math.atan2(p[1] - uy, p[0] - ux) for p in (start, middle, end))
    # counter-clockwise where the middle comes before the end that way, else clockwise
    sweep = (a1 - a0) % (2.0 * math.pi)
    if (am - a0) % (2.0 * math.pi) > sweep:
        sweep -= 2.0 * math.pi
    radius = math.hypot(ax - ux, ay - uy)
    angles = a0 + np.linspace(0.0, sweep, count)
    return np.column_stack([ux + radius * np.cos(angles), uy + radius * np.sin(angles),
                            np.full(count, start[2])])


@dataclass(frozen=True)
class ToothSection:
    """Tooth 0 in the plane z, its pieces in the order the outline runs: fillet_minus
    (root -> form, ending exactly on the flank), flank_minus (form -> tip), the rest of the
    minus tip rounding (`rounding_minus`: start, middle, end of its arc, from the flank's
    end onto the tip circle; None on a sharp tip), the tip arc through `tip_middle`, the
    plus rounding (`rounding_plus`: from the tip circle to the flank's end), flank_plus
    (tip -> form), fillet_plus (form -> root); the half root arcs on the circle of
    `root_radius` run from the space centre at the polar angle `space_before` and to the
    one at `space_after`."""

    z: float
    fillet_minus: np.ndarray
    flank_minus: np.ndarray
    tip_middle: tuple[float, float, float]
    flank_plus: np.ndarray
    fillet_plus: np.ndarray
    root_radius: float
    space_before: float
    space_after: float
    rounding_minus: np.ndarray | None = None
    rounding_plus: np.ndarray | None = None

    @property
    def tip_ends(self) -> tuple[np.ndarray, np.ndarray]:
        """Where the tip arc starts and ends: the flanks' ends, or the roundings' on the tip
        circle."""
        if self.rounding_minus is None:
            return self.flank_minus[-1], self.flank_plus[0]
        return self.rounding_minus[-1], self.rounding_plus[0]

    def points(self, tip_points: int, root_points: int, rounding_points: int = 5
               ) -> np.ndarray:
        """The tooth as one polyline from the centre of the space before it to the centre
        of the space after it, the tip arc by `tip_points` points, each half root arc by
        `root_points` and the rest of each tip rounding by `rounding_points` (every point
        once)."""
        z, near = self.z, 0.5 * (self.space_before + self.space_after)
        tip_radius = math.hypot(*self.tip_middle[:2])
        middle = polar_angle(self.tip_middle, near)
        angle = lambda p: polar_angle(p, near)  # noqa: E731
        tip_start, tip_end = self.tip_ends
        minus, plus = (np.empty((0, 3)),) * 2
        if self.rounding_minus is not None:
            minus = arc_through(*self.rounding_minus, rounding_points)[1:]
            plus = arc_through(*self.rounding_plus, rounding_points)[:-1]
        return np.concatenate([
            arc_points(self.root_radius, self.space_before, angle(self.fillet_minus[0]), z,
                       root_points)[:-1],
            self.fillet_minus, self.flank_minus[1:], minus,
            arc_points(tip_radius, angle(tip_start), middle, z, tip_points)[1:-1],
            arc_points(tip_radius, middle, angle(tip_end), z, tip_points)[:-1], plus,
            self.flank_plus, self.fillet_plus[1:],
            arc_points(self.root_radius, angle(self.fillet_plus[-1]), self.space_after, z,
                       root_points)[1:]])


#: the flank length (mm) of the profile points' spacing next to a profile break, doubling
#: away from it up to the even spacing: a cubic through a curvature jump strays by about
#: the jump times this spacing squared (a 0.3 mm tip rounding: 24 µm on the even points)
BREAK_SPACING = 0.01


def profile_points(u0: float, u1: float, points: int, breaks, base_radius: float
                   ) -> np.ndarray:
    """Roll angles (rad) of a profile's points: `points` evenly from u0 to u1, and around
    each break (roll angles, where the modified profile's slope or curvature jumps) points
    from BREAK_SPACING of flank length, doubling away from it (base_radius in mm)."""
    even = np.linspace(u0, u1, points)
    step = abs(u1 - u0) / (points - 1)
    fit = [even]
    for b in breaks:
        if not min(u0, u1) < b < max(u0, u1):
            continue
        # the flank's length per roll angle at the break is its roll length r_b·|u|
        h = BREAK_SPACING / (base_radius * max(abs(b), 1e-3))
        offsets = h * 2.0 ** np.arange(int(np.log2(max(step / h, 1.0))) + 1)
        fit.append(b + np.concatenate([[0.0], offsets, -offsets]))
    u = np.unique(np.concatenate(fit))
    u = u[(u >= min(u0, u1)) & (u <= max(u0, u1))]
    keep = np.concatenate([[True], np.diff(u) > 1e-9])
    return u[keep] if u0 < u1 else u[keep][::-1]


class ToothOutline:
    """The teeth of a gear with `modifications` on both flanks, section by section."""

    def __init__(self, gear: CylindricalGear, modifications: FlankModifications | None = None):
        self.gear = gear
        self.modifications = modifications or FlankModifications()
        self.generated: GeneratedSide = (generate_ring_side(gear) if gear.internal
                                         else generate_side(gear))
        self.flanks: dict[int, Flank] = {
            side: self._apply(gear.flank(side, self.generated.form_radius)) for side in (1, -1)}

    def _apply(self, flank: Flank) -> Flank:
        return flank if self.modifications.empty else ModifiedFlank(flank, self.modifications)

    @cached_property
    def curved(self) -> bool:
        """The flanks bend along the face width (a lead crown, an end relief or chamfer)."""
        m = self.modifications
        return m.lead_crown is not None or m.end_relief is not None or m.end_chamfer is not None

    def lead_sections(self) -> np.ndarray:
        """Face positions (mm) a section must lie at besides evenly spaced ones: the lead's
        breaks (modify.FlankModifications.lead_breaks), and along an end chamfer's edge
        rounding five more, so that a mesh or a loft follows its turn."""
        m, width = self.modifications, self.gear.face_width
        out = np.array(m.lead_breaks(width))
        if m.end_chamfer is not None:
            start, end = m.end_chamfer.breaks(width)[2:]
            turn = np.linspace(start, end, 7)[1:-1]
            out = np.union1d(out, np.concatenate([-turn, turn]))
        return out

    @property
    def pitch(self) -> float:
        return 2.0 * math.pi / self.gear.teeth

    def profile_parameters(self, points: int) -> np.ndarray:
        """The flanks' roll angles (rad) for sections: `points` evenly over the profile and
        closing in on the breaks of its modifications (profile_points)."""
        (u0, u1), _ = self.flanks[1].domain
        base = self.gear.base_radius
        return profile_points(u0, u1, points,
                              [b / base for b in self.modifications.profile_breaks], base)

    def section(self, u: np.ndarray, z: float) -> ToothSection:
        """Tooth 0 in the plane z, the flanks at the profile parameters u."""
        gear = self.gear
        forward = slice(None, None, -1) if gear.internal else slice(None)   # a ring's u runs from the tip
        minus = self._flank_section(self.flanks[-1], u, z)[forward]
        plus = self._flank_section(self.flanks[1], u, z)[forward]
        fillet_minus = self._fillet_section(-1, z, minus[0])
        fillet_plus = self._fillet_section(1, z, plus[0])[::-1]
        turn = gear.twist_per_length * z
        root = 0.5 * (np.hypot(*fillet_minus[0, :2]) + np.hypot(*fillet_plus[-1, :2]))
        tip_middle = polar(gear.tip_radius, turn, z)
        roundings = (None, None)
        edge = self.modifications.tip_edge
        if edge is not None and edge.angle is None:     # a chamfer runs on to the tip land
            roundings = tuple(self._rest_of_rounding(side, z, np.array(tip_middle))
                              for side in (-1, 1))
        return ToothSection(z, fillet_minus, minus, tip_middle, plus[::-1],
                            fillet_plus, float(root), turn - 0.5 * self.pitch,
                            turn + 0.5 * self.pitch, roundings[0],
                            None if roundings[1] is None else roundings[1][::-1])

    def _rest_of_rounding(self, side: int, z: float, tip_middle: np.ndarray) -> np.ndarray:
        """The part of a tip edge rounding (modify.TipEdge) past the flank's end, from the
        flank's end at the tip onto the tip circle, in the plane z: (start, middle, end) of
        the circular arc tangent to the flank there and to the tip circle (its radius
        ρ' = (r_a² - |P|²)/(2(P·n ± r_a)), P the flank's end and n its normal into the
        tooth: the rounding's radius to the flank drop's second order)."""
        gear, flank = self.gear, self.flanks[side]
        (u0, u1), _ = flank.domain
        tip, inward = (u0, 1.0) if gear.internal else (u1, -1.0)
        near_tip = self._flank_section(flank, np.array([tip + inward * 1e-6, tip]), z)
        end = near_tip[1]
        tangent = (end - near_tip[0])[:2]
        tangent /= np.hypot(*tangent)
        normal = np.array([-tangent[1], tangent[0]])
        if normal @ (tip_middle[:2] - end[:2]) < 0.0:
            normal = -normal
        sense = -1.0 if gear.internal else 1.0
        r_a, point = gear.tip_radius, end[:2]
        radius = (r_a**2 - point @ point) / (2.0 * (point @ normal + sense * r_a))
        centre = point + radius * normal
        touch = centre * r_a / np.hypot(*centre)
        bisector = (point - centre) + (touch - centre)
        middle = centre + radius * bisector / np.hypot(*bisector)
        return np.array([[*point, z], [*middle, z], [*touch, z]])

    @staticmethod
    def _flank_section(flank: Flank, u: np.ndarray, z: float) -> np.ndarray:
        v = np.full_like(u, z)
        for _ in range(4):
            pts = np.stack(flank.point(u, v), axis=-1)
            v = v - (pts[:, 2] - z)
        pts = np.stack(flank.point(u, v), axis=-1)
        pts[:, 2] = z
        return pts

    def _fillet_section(self, side: int, z: float, flank_start: np.ndarray) -> np.ndarray:
        """The generated fillet of `side` in the plane z (root -> form): turned with the
        helix and displaced like the flank's form end (a lead crown moves the whole tooth
        side), ending exactly on the flank's first point."""
        gear, generated, flank = self.gear, self.generated, self.flanks[side]
        mirror = np.array([1.0, side])
        turn = gear.twist_per_length * z
        c, s = math.cos(turn), math.sin(turn)
        rotation = np.array([[c, s], [-s, c]])
        pts = (generated.fillet * mirror) @ rotation
        if isinstance(flank, ModifiedFlank):
            (u0, u1), _ = flank.domain
            form_end = u1 if gear.internal else u0
            drop = float(np.asarray(flank.drop(np.array([form_end]), np.array([z])))[0])
            normals = (generated.fillet_normals * mirror) @ rotation
            pts = pts - drop * math.cos(gear.base_helix_angle) * normals
        pts = np.column_stack([pts, np.full(len(pts), z)])
        pts[-1] = flank_start
        return pts
