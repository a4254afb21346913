"""A member's shaft under the mesh force: bending between its two bearings and torsion over
the face, as a displacement of its flank toward the mate along the face.

The shaft is an Euler-Bernoulli beam along the member's axis z (mm from mid-face, + toward
end B) on two simple supports (the bearings; a pinion may overhang them), of one diameter
or of stepped sections, the gear body being one of them. The mesh force is spread over the
face at the operating pitch point, evenly or as the loaded contact's line load gives it:
its transverse part bends the shaft along itself, its axial part (a helix) at the pitch
radius adds a bending couple. With the
internal moment M(z) (the moment of everything beyond z, reactions included) the beam
obeys E·I·u_x'' = M_y and E·I·u_y'' = -M_x (I = π d⁴/64), u = 0 at both bearings: the
bending of a statically determinate beam, integrated twice on a fine grid. The torque enters
(or leaves) the body at one face end and is handed to the mesh along the face, so
the body twists by φ(z) = ∫ T(ζ)/(G·J) dζ (J = π d⁴/32, G = E/2(1+ν)): the face end away
from the torque's side turns back against the load, its flank away from the mate by
r_b·φ. Both are read along the flank's transverse normal at the pitch point (the line of
action), positive toward the mate, relative to mid-face (the shaft's displacement there
moves the whole member): the deflection field modify.Deflection takes.
Units: mm, N, MPa, rad.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from scipy.integrate import cumulative_trapezoid

#: points of the beam's grid
POINTS = 4001


@dataclass(frozen=True)
class Shaft:
    """A shaft: `bearings` (two positions, mm from mid-face), `sections` ((start, end,
    diameter) mm, covering the bearings and the face), E (MPa), nu, the face end the
    torque comes in or goes out at (`torque_side`, "A" or "B") and the bearings' radial
    stiffness (`bearing_stiffness`, N/mm each; None: rigid)."""

    bearings: tuple[float, float]
    sections: tuple[tuple[float, float, float], ...]
    E: float
    nu: float
    torque_side: str = "A"
    bearing_stiffness: tuple[float, float] | None = None

    def diameter(self, z: np.ndarray) -> np.ndarray:
        """The diameter (mm) at axial positions z (the section that holds each; the later
        one where two meet)."""
        out = np.full(np.shape(z), np.nan)
        for start, end, d in self.sections:
            out = np.where((z >= start) & (z <= end), d, out)
        return out


@dataclass(frozen=True)
class ShaftDeflection:
    """A shaft's deflection over the face: face positions (mm), the flank's displacement
    toward the mate (mm) from bending and from torsion, and each one's slope over the face
    (rad, least squares; positive closes end B like misalignment.slope)."""

    face: np.ndarray
    bending: np.ndarray
    torsion: np.ndarray

    @property
    def bending_slope(self) -> float:
        return float(np.polyfit(self.face, self.bending, 1)[0])

    @property
    def torsion_slope(self) -> float:
        return float(np.polyfit(self.face, self.torsion, 1)[0])

    @property
    def total(self) -> np.ndarray:
        return self.bending + self.torsion


def beam_deflection(shaft: Shaft, z: np.ndarray, force: np.ndarray, couple: np.ndarray
                    ) -> np.ndarray:
    """Deflection (z.size, 2) (mm, x and y) of the shaft on its bearings under loads on the
    grid z (mm, increasing, spanning the bearings): force (z.size, 2) N in x and y and
    couple (z.size, 2) N·mm about x and y, each the load of its grid point."""
    z = np.asarray(z, float)
    z1, z2 = shaft.bearings
    # reactions: the forces and their moments about y (from x forces) and x (from y) vanish
    reactions = np.zeros((2, 2))
    total = force.sum(axis=0)
    turning = np.array([(z * force[:, 0]).sum() + couple[:, 1].sum(),      # about y
                        (z * force[:, 1]).sum() - couple[:, 0].sum()])     # about -x
    A = np.array([[1.0, 1.0], [z1, z2]])
    for axis in (0, 1):
        reactions[:, axis] = np.linalg.solve(A, [-total[axis], -turning[axis]])
    loads = force.copy()
    for k, at in enumerate((z1, z2)):
        i = int(np.argmin(np.abs(z - at)))
        loads[i] += reactions[k]
    # the moment of everything beyond z: sum over ζ > z of (ζ - z)·F_x about y, and
    # -(ζ - z)·F_y about x, plus the couples beyond z
    beyond_force = np.cumsum(loads[::-1], axis=0)[::-1]
    beyond_moment = np.cumsum((loads * z[:, None])[::-1], axis=0)[::-1]
    beyond_couple = np.cumsum(couple[::-1], axis=0)[::-1]
    shift = lambda a: np.concatenate([a[1:], np.zeros((1, 2))])     # noqa: E731 strictly beyond
    arm = shift(beyond_moment) - z[:, None] * shift(beyond_force)   # Σ (ζ - z) F
    M_y = arm[:, 0] + shift(beyond_couple)[:, 1]
    M_x = -arm[:, 1] + shift(beyond_couple)[:, 0]
    inertia = math.pi * shaft.diameter(z) ** 4 / 64.0
    curvature = np.stack([M_y, -M_x], axis=-1) / (shaft.E * inertia)[:, None]
    slope = cumulative_trapezoid(curvature, z, initial=0.0, axis=0)
    u = cumulative_trapezoid(slope, z, initial=0.0, axis=0)
    # a line through the bearings: u(z_k) = the bearing's own give, -R_k/k_k (0 if rigid)
    give = (np.zeros((2, 2)) if shaft.bearing_stiffness is None else
            -reactions / np.asarray(shaft.bearing_stiffness, float)[:, None])
    at = np.array([[np.interp(b, z, u[:, axis]) for axis in (0, 1)] for b in (z1, z2)]) - give
    gradient = (at[1] - at[0]) / (z2 - z1)
    return u - at[0] - np.outer(z - z1, gradient)


def face_share(z: np.ndarray, face_width: float,
               line_load: tuple[np.ndarray, np.ndarray] | None = None) -> np.ndarray:
    """Each grid point's share ((z.size,), summing to 1) of the mesh force along the face:
    even over the face, or as `line_load` (face positions mm, N/mm) gives it, interpolated
    (held beyond its ends)."""
    half = 0.5 * face_width
    on_face = ((z >= -half) & (z <= half)).astype(float)
    if line_load is not None:
        on_face *= np.interp(z, *line_load)
    return on_face / on_face.sum()


def twist(shaft: Shaft, z: np.ndarray, face_width: float, torque: float,
          line_load: tuple[np.ndarray, np.ndarray] | None = None) -> np.ndarray:
    """The body's twist (rad) at face positions z (mm), from the face end at the torque's
    side, under `torque` (N·mm) handed to the mesh along the face evenly or as `line_load`
    (see face_share): the torque still carried at ζ falls from `torque` at that end to 0 at
    the other as the mesh takes it."""
    half = 0.5 * face_width
    s = np.linspace(-half, half, POINTS)
    from_side = (s + half) if shaft.torque_side == "A" else (half - s)
    order = np.argsort(from_side)
    taken = np.empty(POINTS)
    taken[order] = np.cumsum(face_share(s, face_width, line_load)[order])
    carried = torque * (1.0 - taken)
    G = shaft.E / (2.0 * (1.0 + shaft.nu))
    J = math.pi * shaft.diameter(s) ** 4 / 32.0
    rate = carried / (G * J)
    angle = cumulative_trapezoid(rate[order], from_side[order], initial=0.0)
    return np.interp(half + np.asarray(z) if shaft.torque_side == "A" else half - np.asarray(z),
                     from_side[order], angle)


def shaft_deflection(shaft: Shaft, face_width: float, axis_to_pitch: np.ndarray,
                     force: np.ndarray, line_of_action: np.ndarray, base_radius: float,
                     torque: float, points: int = 41,
                     line_load: tuple[np.ndarray, np.ndarray] | None = None) -> ShaftDeflection:
    """The flank's displacement toward the mate over the face (`points` positions) of a
    member whose shaft carries the mesh force `force` (N, 3-vector on this member, spread
    over the face at the pitch point, `axis_to_pitch` (2,) mm from its axis, evenly or as
    `line_load` gives it: see face_share), `line_of_action`: the unit transverse normal of
    its working flank there (pointing to the mate), base radius (mm) and transmitted torque
    (N·mm)."""
    half = 0.5 * face_width
    z1, z2 = shaft.bearings
    lo, hi = min(z1, z2, -half), max(z1, z2, half)
    z = np.linspace(lo, hi, POINTS)
    share = face_share(z, face_width, line_load)
    loads = np.outer(share, force[:2])
    rx, ry = axis_to_pitch
    moment = np.array([ry * force[2], -rx * force[2]])        # (r × F_z ẑ) about x and y
    couple = np.outer(share, moment)
    u = beam_deflection(shaft, z, loads, couple)
    face = np.linspace(-half, half, points | 1)        # odd: a point at mid-face
    toward = np.array([np.interp(face, z, u[:, axis]) for axis in (0, 1)]).T @ line_of_action[:2]
    phi = twist(shaft, face, face_width, torque, line_load)
    # relative to mid-face: the shaft's displacement there moves the whole member (the
    # centre distance, the lag), the rest bends and twists its flank along the face
    middle = len(face) // 2
    return ShaftDeflection(face, toward - toward[middle], -base_radius * (phi - phi[middle]))
