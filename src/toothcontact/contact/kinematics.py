"""How the flanks move where they touch: each member's angular velocity and the velocity of
its material at every contact of a cycle, from the mesh's own placements (its frames
differentiated along the driver's turn), so that misalignment, modifications and the kind of
mesh (parallel pair, worm set) all count. Units: rad/s, m/s, mm."""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

#: the driver's turn (rad) over which the frames are differenced
TURN_STEP = 1e-6


@dataclass(frozen=True)
class ContactMotion:
    """Per contact ((K, 3) arrays, world): the contact point (mm), the unit normal, each
    member's angular velocity (rad/s) and the velocity of its material at the contact point
    (m/s); "pinion" is the driver, "gear" the driven member."""

    point: np.ndarray
    normal: np.ndarray
    omega_pinion: np.ndarray
    omega_gear: np.ndarray
    velocity_pinion: np.ndarray
    velocity_gear: np.ndarray

    def at(self, k: int, points: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """Both members' surface velocities (m/s, (..., 3), tangent to contact k's plane) at
        world `points` (mm, (..., 3)) near contact k: rigid motion v + Ω × (x - p)."""
        arm = (np.asarray(points, float) - self.point[k]) * 1e-3
        n = self.normal[k]
        out = []
        for v, omega in ((self.velocity_pinion[k], self.omega_pinion[k]),
                         (self.velocity_gear[k], self.omega_gear[k])):
            full = v + np.cross(omega, arm)
            out.append(full - (full @ n)[..., None] * n)
        return out[0], out[1]


    def in_plane(self, k: int, axes: tuple[np.ndarray, np.ndarray]) -> np.ndarray:
        """Both members' surface velocities in contact k's tangent plane as affine maps of
        the plane coordinates: (2, 3, 2) coefficients [member, (constant, per mm along
        axes[0], per mm along axes[1]), component along axes[0] / axes[1]] (m/s), for unit
        in-plane `axes` ((3,) each): v = c[0] + x·c[1] + y·c[2]."""
        out = np.empty((2, 3, 2))
        for m, (v, omega) in enumerate(((self.velocity_pinion[k], self.omega_pinion[k]),
                                        (self.velocity_gear[k], self.omega_gear[k]))):
            for j, term in enumerate((v, 1e-3 * np.cross(omega, axes[0]),
                                      1e-3 * np.cross(omega, axes[1]))):
                out[m, j] = term @ axes[0], term @ axes[1]
        return out


def contact_motion(mesh, cycle, driver_speed: float) -> ContactMotion:
    """The motion at every row of `cycle` (contact.cycle.ContactCycle) placed by `mesh`
    (surfaces.placement.ParallelMesh or WormMesh), the driver turning at `driver_speed` (rpm) the way
    the mesh turns it; the gear at its row's transmission error."""
    omega = driver_speed * 2.0 * math.pi / 60.0
    point, normal = cycle.planes.point, cycle.planes.normal
    spins, velocities = {"pinion": [], "gear": []}, {"pinion": [], "gear": []}
    for k, row in enumerate(cycle.rows):
        phi, pair = math.radians(row["roll_deg"]), row["pair"]
        delta = float(cycle.gear_turn[k])
        placements = {"pinion": lambda t, pair=pair: mesh.pinion_frame(t, pair),
                      "gear": lambda t, pair=pair, delta=delta: mesh.gear_frame(t, pair, delta)}
        for name, frame in placements.items():
            here, ahead, behind = frame(phi), frame(phi + TURN_STEP), frame(phi - TURN_STEP)
            dR = (ahead.R - behind.R) / (2.0 * TURN_STEP)
            d_origin = (np.ravel(ahead.origin) - np.ravel(behind.origin)) / (2.0 * TURN_STEP)
            S = dR @ here.R.T             # skew: dR/dφ·Rᵀ = [Ω/ω]×
            spin = np.array([S[2, 1] - S[1, 2], S[0, 2] - S[2, 0], S[1, 0] - S[0, 1]]) * 0.5
            arm = point[k] - np.ravel(here.origin)
            spins[name].append(omega * spin)
            velocities[name].append(omega * 1e-3 * (np.cross(spin, arm) + d_origin))
    return ContactMotion(point, normal, *(np.array(spins[n]).reshape(-1, 3)
                                          for n in ("pinion", "gear")),
                         *(np.array(velocities[n]).reshape(-1, 3) for n in ("pinion", "gear")))
