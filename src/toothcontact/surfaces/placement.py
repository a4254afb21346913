"""Where the gears sit: rigid frames of a pair in mesh, with misalignment, from numbers
(the layout), so that the contact engine below needs no case or gear set.

World frame of a parallel-axis pair: the pinion turns about the z axis through the origin,
its tooth 0 on +x at roll angle 0; the gear's centre lies on the x axis (at +a for an
external gear, at -a for a ring), so the pitch point is on +x. The pinion drives turning
counter-clockwise (+phi1): its flank side +1 meets the gear. Units: mm, rad.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from functools import cached_property

import numpy as np


def rotation(axis, angle: float) -> np.ndarray:
    """Rotation matrix about a unit `axis` by `angle` (Rodrigues)."""
    k = np.asarray(axis, float)
    k = k / np.linalg.norm(k)
    K = np.array([[0, -k[2], k[1]], [k[2], 0, -k[0]], [-k[1], k[0], 0]])
    return np.eye(3) + math.sin(angle) * K + (1 - math.cos(angle)) * K @ K


@dataclass(frozen=True)
class Frame:
    """world = R·local + origin. A stack of frames (R of shape (..., 3, 3), origin of shape
    (..., 1, 3)) maps points (..., n, 3) frame by frame; see `stack`."""

    R: np.ndarray
    origin: np.ndarray

    @classmethod
    def stack(cls, frames) -> Frame:
        """Frames in a nested list (shape S) as one stacked frame of batch shape S."""
        R = np.array([f.R for f in np.ravel(frames)])
        origin = np.array([f.origin for f in np.ravel(frames)])
        shape = np.shape(frames)
        return cls(R.reshape(shape + (3, 3)), origin.reshape(shape + (1, 3)))

    def __getitem__(self, index) -> Frame:
        """The stacked frames at `index` (batch axes only)."""
        return Frame(self.R[index], self.origin[index])

    def to_world(self, p):
        return p @ np.swapaxes(self.R, -1, -2) + self.origin

    def vectors_to_world(self, n):
        return n @ np.swapaxes(self.R, -1, -2)

    def to_local(self, p):
        return (p - self.origin) @ self.R

    def vectors_to_local(self, n):
        return n @ self.R


@dataclass(frozen=True)
class Misalignment:
    """Misalignment of the gear relative to the pinion.

    slope: tilt of the gear axis in the plane of action (rad), positive closing the gap at
    end B (z > 0); slope_normal: tilt normal to the plane of action (rad), about the line of
    action; center_distance_error (mm, positive = farther apart); axial_shift of the gear
    along its axis (mm). Tilts turn about the gear axis's mid-face point."""

    slope: float = 0.0
    slope_normal: float = 0.0
    center_distance_error: float = 0.0
    axial_shift: float = 0.0


class ParallelMesh:
    """A spur/helical pair (or a coaxial spline) in mesh: the frames of both members at any
    pinion angle, from the pair's layout: tooth counts, centre distance (mm; 0 for a
    coaxial spline), working pressure angle (rad, for the plane of action the slopes refer
    to), the gear's angle at phi1 = 0 and the pinion's (rad). gearset.GearPair.placed
    gives them for a designed pair; an imported pair's come from its case."""

    def __init__(self, pinion_teeth: int, gear_teeth: int, centre_distance: float,
                 working_pressure_angle: float, misalignment: Misalignment = Misalignment(),
                 internal: bool = False, gear_start: float = 0.0, pinion_start: float = 0.0):
        self.misalignment = misalignment
        self.pinion_start = pinion_start
        self.pinion_teeth, self.gear_teeth, self.internal = pinion_teeth, gear_teeth, internal
        self.ratio = pinion_teeth / gear_teeth
        a = centre_distance + misalignment.center_distance_error
        self.center = np.array([-a if internal else a, 0.0, misalignment.axial_shift])
        self.gear_start = gear_start
        self.gear_side = -1 if internal else 1
        # line of action at the pitch point: the normal of pinion flank side +1 there (it faces
        # +y and, as the tooth narrows toward its tip, leans outward by the pressure angle)
        alpha = working_pressure_angle
        self.line_of_action = np.array([math.sin(alpha), math.cos(alpha), 0.0])
        self.plane_normal = np.cross(self.line_of_action, [0.0, 0.0, 1.0])
        self._tilt = self._tilt_rotation()

    @property
    def driver_pitch(self) -> float:
        """The pinion's angular pitch (rad): one mesh cycle."""
        return 2.0 * math.pi / self.pinion_teeth

    def driver_turn(self, phi1, tooth):
        """The pinion's turn (rad) at which its tooth 0 stands where tooth `tooth` stands at
        phi1: its own flank's place in the cycle."""
        return phi1 + tooth * 2.0 * math.pi / self.pinion_teeth

    def pinion_frame(self, phi1: float, tooth: int = 0) -> Frame:
        return Frame(rotation([0, 0, 1], self.pinion_start + self.driver_turn(phi1, tooth)),
                     np.zeros(3))

    def gear_frame(self, phi1: float, tooth: int = 0, delta: float = 0.0) -> Frame:
        """The gear's frame when the pinion has turned phi1 and the gear lags by delta (rad,
        the transmission error: positive = gear behind its ideal position)."""
        sense = 1.0 if self.internal else -1.0
        angle = (self.gear_start + sense * (phi1 * self.ratio - delta)
                 + sense * tooth * 2.0 * math.pi / self.gear_teeth)
        return Frame(self._tilt @ rotation([0, 0, 1], angle), self.center)

    def _tilt_rotation(self) -> np.ndarray:
        """Tilts about axes through the gear's mid-face point. A rotation by +slope about
        k = L × e_z (L: line of action, the pinion flank's normal at the pitch point) moves a
        gear point at height z by -slope·z along L, i.e. toward the pinion at end B (z > 0),
        for an external and a ring gear alike."""
        m = self.misalignment
        return rotation(self.plane_normal, m.slope) @ rotation(self.line_of_action, m.slope_normal)


@dataclass(frozen=True)
class WormMisalignment:
    """Misalignment of a worm set: centre_distance_error (mm, + = apart), shaft_angle_error
    (rad, crossing angle 90° + error), wheel_axial_shift (mm, along the wheel axis), and a
    tilt of the worm shaft (rad) about its mount, a pivot `pivot` mm along the worm axis from
    the mesh (negative: on the -z side), in the plane of the worm axis and the centre line
    (positive: the far end of the shaft moves toward the wheel) - seed 001's anti-rattle-
    spring misalignment (eqs 20-21)."""

    centre_distance_error: float = 0.0
    shaft_angle_error: float = 0.0
    wheel_axial_shift: float = 0.0
    worm_tilt: float = 0.0
    pivot: float = 0.0


class WormMesh:
    """A worm and its wheel in mesh. World = the housing: the worm turns by phi1 about z (its
    axis), the wheel centre lies on +x; the wheel is placed by its own generating kinematics
    (surfaces.wheel.wheel_from_hob) at the set's centre distance and crossing angle plus the
    misalignment; wheel tooth j is tooth 0 turned by j pitches, and the wheel lags by delta
    (transmission error)."""

    def __init__(self, wheel_flank, misalignment: WormMisalignment = WormMisalignment()):
        self.wheel, self.misalignment = wheel_flank, misalignment
        self.centre_distance = wheel_flank.centre_distance + misalignment.centre_distance_error
        self.crossing_angle = 0.5 * math.pi + misalignment.shaft_angle_error
        # the shaft tilt: about the y axis through the pivot (0, 0, pivot); a positive tilt
        # moves the shaft's end at z > pivot toward +x (the wheel)
        pivot = np.array([0.0, 0.0, misalignment.pivot])
        tilt = rotation([0.0, 1.0, 0.0], misalignment.worm_tilt)
        self._tilt = Frame(tilt, pivot - tilt @ pivot)

    @property
    def driver_pitch(self) -> float:
        """The worm's turn per wheel tooth (rad): one mesh cycle."""
        return 2.0 * math.pi / self.wheel.worm.starts

    def pinion_frame(self, phi1: float, tooth: int = 0) -> Frame:
        """The worm's frame, turned to the thread start that meets wheel tooth `tooth`: the
        flank is one start's thread, start k is that thread turned by 2πk/starts, and a
        turn of one start's pitch brings the next wheel tooth into start 0's place."""
        turn = rotation([0.0, 0.0, 1.0], self.driver_turn(phi1, tooth))
        return Frame(self._tilt.R @ turn, self._tilt.origin)

    def driver_turn(self, phi1, tooth):
        """The worm's turn (rad) with the start that meets wheel tooth `tooth` at phi1 in
        start 0's place: the thread's own place in the cycle."""
        start = np.mod(self._start_step * np.asarray(tooth), self.wheel.worm.starts)
        return phi1 + 2.0 * math.pi * start / self.wheel.worm.starts

    @cached_property
    def _start_step(self) -> int:
        """+1 when a turn of the worm by one start's pitch carries wheel tooth j to tooth
        j + 1's place (start k then meets tooth k), else -1."""
        ahead = self.gear_frame(self.driver_pitch, 0).R
        return 1 if np.allclose(ahead, self.gear_frame(0.0, 1).R, atol=1e-9) else -1

    def gear_frame(self, phi1: float, tooth: int = 0, delta: float = 0.0) -> Frame:
        M = self.wheel.wheel_from_hob(phi1, centre_distance=self.centre_distance,
                                      crossing_angle=self.crossing_angle)
        # wheel-attached -> worm-attached (M inverse) -> housing (the worm's turn)
        turn = rotation([0, 0, 1], 2.0 * math.pi * tooth / self.wheel.teeth - delta)
        shift = np.array([0.0, 0.0, self.misalignment.wheel_axial_shift])
        worm_turn = rotation([0.0, 0.0, 1.0], phi1)
        R = worm_turn @ M[:3, :3].T @ turn
        origin = worm_turn @ (M[:3, :3].T @ (shift - M[:3, 3]))
        return Frame(R, origin)
