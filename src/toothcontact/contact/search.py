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
from scipy.optimize import minimize

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
                     grid: tuple[np.ndarray, np.ndarray]) -> ContactPoint | None:
    """The pinion point of least separation: the best grid point, refined by a bounded
    quasi-Newton search on the smooth separation (None if the flanks do not face)."""
    u, v = grid
    field = separation(pinion, gear, pinion_frame, gear_frame, u, v).s
    if not np.isfinite(field).any():
        return None
    i = np.nanargmin(field)
    start = np.array([u.flat[i], v.flat[i]])

    def s_at(x):
        value = separation(pinion, gear, pinion_frame, gear_frame, np.array([x[0]]),
                           np.array([x[1]])).s[0]
        return value if np.isfinite(value) else 1e3

    (u0, u1), (v0, v1) = pinion.domain
    scale = np.array([u1 - u0, v1 - v0])
    best = minimize(lambda y: s_at(start + y * scale), np.zeros(2), method="L-BFGS-B",
                    bounds=[((u0 - start[0]) / scale[0], (u1 - start[0]) / scale[0]),
                            ((v0 - start[1]) / scale[1], (v1 - start[1]) / scale[1])],
                    options={"ftol": 1e-15, "gtol": 1e-12, "eps": 1e-7})
    x = start + best.x * scale
    if not best.fun <= field.flat[i]:
        x = start
    hit = separation(pinion, gear, pinion_frame, gear_frame, np.array([x[0]]), np.array([x[1]]))
    return ContactPoint(float(x[0]), float(x[1]), float(hit.gear_u[0]), float(hit.gear_v[0]),
                        float(hit.s[0]))


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
