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

from ..modify import FlankModifications
from .base import Flank
from .generation import GeneratedSide, generate_ring_side, generate_side
from .involute import CylindricalGear
from .modified import ModifiedFlank


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


@dataclass(frozen=True)
class ToothSection:
    """Tooth 0 in the plane z, its pieces in the order the outline runs: fillet_minus
    (root -> form, ending exactly on the flank), flank_minus (form -> tip), the tip arc
    through `tip_middle`, flank_plus (tip -> form), fillet_plus (form -> root); the half
    root arcs on the circle of `root_radius` run from the space centre at the polar angle
    `space_before` and to the one at `space_after`."""

    z: float
    fillet_minus: np.ndarray
    flank_minus: np.ndarray
    tip_middle: tuple[float, float, float]
    flank_plus: np.ndarray
    fillet_plus: np.ndarray
    root_radius: float
    space_before: float
    space_after: float

    def points(self, tip_points: int, root_points: int) -> np.ndarray:
        """The tooth as one polyline from the centre of the space before it to the centre
        of the space after it, the tip arc by `tip_points` points and each half root arc by
        `root_points` (every point once)."""
        z, near = self.z, 0.5 * (self.space_before + self.space_after)
        tip_radius = math.hypot(*self.tip_middle[:2])
        middle = polar_angle(self.tip_middle, near)
        angle = lambda p: polar_angle(p, near)  # noqa: E731
        return np.concatenate([
            arc_points(self.root_radius, self.space_before, angle(self.fillet_minus[0]), z,
                       root_points)[:-1],
            self.fillet_minus, self.flank_minus[1:],
            arc_points(tip_radius, angle(self.flank_minus[-1]), middle, z, tip_points)[1:-1],
            arc_points(tip_radius, middle, angle(self.flank_plus[0]), z, tip_points)[:-1],
            self.flank_plus, self.fillet_plus[1:],
            arc_points(self.root_radius, angle(self.fillet_plus[-1]), self.space_after, z,
                       root_points)[1:]])


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
        """The flanks bend along the face width (a lead crown or an end relief)."""
        m = self.modifications
        return m.lead_crown is not None or m.end_relief is not None

    @property
    def pitch(self) -> float:
        return 2.0 * math.pi / self.gear.teeth

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
        return ToothSection(z, fillet_minus, minus, polar(gear.tip_radius, turn, z), plus[::-1],
                            fillet_plus, float(root), turn - 0.5 * self.pitch,
                            turn + 0.5 * self.pitch)

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
