"""Contact by surface separation over the mesh cycle (DESIGN.md principle 3).

At a mesh position the separation of a pinion flank point is the distance, along the pinion
flank's normal, to the gear flank (negative = overlap). The gear is turned back by the
transmission error until the least separation over all tooth pairs is zero; the pinion point
where it is least is the contact point. Units: mm, rad.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..assembly import Frame
from ..surfaces.base import Flank
from .rays import intersect


@dataclass(frozen=True)
class Separation:
    """Separation of pinion flank points (mm, NaN where no gear flank faces them) and where
    their normals meet the gear flank (gear parameters)."""

    s: np.ndarray
    gear_u: np.ndarray
    gear_v: np.ndarray


def separation(pinion: Flank, gear: Flank, pinion_frame: Frame, gear_frame: Frame,
               u: np.ndarray, v: np.ndarray) -> Separation:
    """Separation at pinion parameters (u, v) with both flanks placed by their frames."""
    sample = pinion.evaluate(u, v)
    points = gear_frame.to_local(pinion_frame.to_world(sample.points))
    normals = gear_frame.vectors_to_local(pinion_frame.vectors_to_world(sample.normals))
    u0, v0 = gear.parameters_near(points)
    hits = intersect(gear, points, normals, u0, v0)
    return Separation(np.where(hits.inside, hits.s, np.nan), hits.u, hits.v)


@dataclass(frozen=True)
class ContactPoint:
    """The least separation of one tooth pair: pinion (u, v), gear (u, v), separation (mm)."""

    pinion_u: float
    pinion_v: float
    gear_u: float
    gear_v: float
    s: float


def least_separation(pinion: Flank, gear: Flank, pinion_frame: Frame, gear_frame: Frame,
                     grid: tuple[np.ndarray, np.ndarray], refinements: int = 6) -> ContactPoint | None:
    """The pinion point of least separation (None if the flanks do not face each other).

    The best grid point is refined by fitting a quadratic to the separation on a 5 × 5 patch
    around it and moving to the fitted minimum (kept inside the flank's domain), with the
    patch shrinking each time: a handful of vectorised evaluations instead of a point-by-point
    search."""
    u, v = grid
    field = separation(pinion, gear, pinion_frame, gear_frame, u, v).s
    if not np.isfinite(field).any():
        return None
    i = np.nanargmin(field)
    (u0, u1), (v0, v1) = pinion.domain
    centre = np.array([u.flat[i], v.flat[i]])
    half = np.array([(u1 - u0) / max(u.shape[0] - 1, 1), (v1 - v0) / max(u.shape[1] - 1, 1)])
    best_s = field.flat[i]
    offsets = np.linspace(-1.0, 1.0, 5)
    du, dv = np.meshgrid(offsets, offsets, indexing="ij")
    design = np.stack([np.ones(25), du.ravel(), dv.ravel(), du.ravel() ** 2,
                       (du * dv).ravel(), dv.ravel() ** 2], axis=-1)
    for _ in range(refinements):
        pu = np.clip(centre[0] + half[0] * du, u0, u1)
        pv = np.clip(centre[1] + half[1] * dv, v0, v1)
        values = separation(pinion, gear, pinion_frame, gear_frame, pu, pv).s
        k = np.nanargmin(values)
        candidate = np.array([pu.flat[k], pv.flat[k]])
        ok = np.isfinite(values.ravel())
        if ok.sum() >= 6:
            c, *_ = np.linalg.lstsq(design[ok], values.ravel()[ok], rcond=None)
            hessian = np.array([[2 * c[3], c[4]], [c[4], 2 * c[5]]])
            if np.all(np.linalg.eigvalsh(hessian) > 0):
                step = np.linalg.solve(hessian, -c[1:3])
                vertex = np.clip(centre + np.clip(step, -1.5, 1.5) * half, [u0, v0], [u1, v1])
                candidate = vertex
        trial = separation(pinion, gear, pinion_frame, gear_frame, np.array([candidate[0]]),
                           np.array([candidate[1]])).s[0]
        if np.isfinite(trial) and trial <= min(best_s, np.nanmin(values)):
            centre, best_s = candidate, trial
        elif np.nanmin(values) < best_s:
            centre, best_s = np.array([pu.flat[k], pv.flat[k]]), values.flat[k]
        half = 0.3 * half
    hit = separation(pinion, gear, pinion_frame, gear_frame, np.array([centre[0]]),
                     np.array([centre[1]]))
    return ContactPoint(float(centre[0]), float(centre[1]), float(hit.gear_u[0]),
                        float(hit.gear_v[0]), float(hit.s[0]))


def solve_transmission_error(least, delta0: float = 0.0, tolerance: float = 1e-10,
                             step: float = 1e-5, iterations: int = 30) -> tuple[float, float]:
    """The gear lag delta (rad) at which `least(delta)`, the least separation over all tooth
    pairs (mm), is zero: secant iteration. Returns (delta, least separation there)."""
    d0, s0 = delta0, least(delta0)
    d1 = delta0 + step
    s1 = least(d1)
    for _ in range(iterations):
        if abs(s1) < tolerance:
            break
        slope = (s1 - s0) / (d1 - d0)
        if slope == 0 or not math.isfinite(slope):
            raise RuntimeError("the separation does not change with the gear's rotation")
        d0, s0, d1 = d1, s1, d1 - s1 / slope
        s1 = least(d1)
    return d1, s1
