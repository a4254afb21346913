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


#: farthest separation (mm) taken as the two flanks facing each other; beyond it the normal
#: line has met another part of the (long) mating surface, not the flank opposite
REACH = 2.0


def separation(pinion: Flank, gear: Flank, pinion_frame: Frame, gear_frame: Frame,
               u: np.ndarray, v: np.ndarray) -> Separation:
    """Separation at pinion parameters (u, v) with both flanks placed by their frames.

    NaN where the normal line meets no gear flank inside its domain, meets it from behind
    (the two normals must oppose), or farther than REACH."""
    with np.errstate(all="ignore"):  # probes beyond a surface's existence give NaN there
        sample = pinion.evaluate(u, v, order=1)
        points = gear_frame.to_local(pinion_frame.to_world(sample.points))
        normals = gear_frame.vectors_to_local(pinion_frame.vectors_to_world(sample.normals))
        u0, v0 = gear.parameters_near(points)
        hits = intersect(gear, points, normals, u0, v0)
        facing = hits.inside & (np.abs(hits.s) <= REACH)
        if facing.any():
            mate = gear.evaluate(np.where(facing, hits.u, gear.domain[0][0]),
                                 np.where(facing, hits.v, gear.domain[1][0]), order=1).normals
            facing &= np.einsum("...i,...i->...", mate, normals) < 0.0
    return Separation(np.where(facing, hits.s, np.nan), hits.u, hits.v)


@dataclass(frozen=True)
class ContactPoint:
    """The least separation of one tooth pair: pinion (u, v), gear (u, v), separation (mm)."""

    pinion_u: float
    pinion_v: float
    gear_u: float
    gear_v: float
    s: float


def grid_minimum(pinion: Flank, gear: Flank, pinion_frame: Frame, gear_frame: Frame,
                 grid: tuple[np.ndarray, np.ndarray], keep: int = 9):
    """The `keep` pinion grid points of least separation, as (u, v, s) arrays (None when the
    flanks do not face each other)."""
    u, v = grid
    field = separation(pinion, gear, pinion_frame, gear_frame, u, v).s.ravel()
    finite = np.flatnonzero(np.isfinite(field))
    if finite.size == 0:
        return None
    best = finite[np.argsort(field[finite])[:keep]]
    return u.ravel()[best], v.ravel()[best], field[best]


def refine_minimum(pinion: Flank, gear: Flank, pinion_frame: Frame, gear_frame: Frame,
                   start: tuple[float, float], half: tuple[float, float],
                   refinements: int = 6) -> ContactPoint:
    """The pinion point of least separation near `start`: a quadratic is fitted to the
    separation on a 5 × 5 patch (half-sizes `half`) and the patch moves to its minimum (kept
    inside the flank's domain), shrinking each time: a handful of vectorised evaluations.
    The best point seen (patch points and the final fitted minimum) is returned."""
    (u0, u1), (v0, v1) = pinion.domain
    centre, half = np.array(start, float), np.array(half, float)
    offsets = np.linspace(-1.0, 1.0, 5)
    du, dv = np.meshgrid(offsets, offsets, indexing="ij")
    du, dv = du.ravel(), dv.ravel()
    design = np.stack([np.ones(25), du, dv, du**2, du * dv, dv**2], axis=-1)
    best_uv, best_s = centre.copy(), np.inf
    for _ in range(refinements):
        pu = np.clip(centre[0] + half[0] * du, u0, u1)
        pv = np.clip(centre[1] + half[1] * dv, v0, v1)
        values = separation(pinion, gear, pinion_frame, gear_frame, pu, pv).s
        ok = np.isfinite(values)
        if not ok.any():
            break
        k = np.nanargmin(values)
        if values[k] < best_s:
            best_uv, best_s = np.array([pu[k], pv[k]]), values[k]
        centre = best_uv
        if ok.sum() >= 6:
            c, *_ = np.linalg.lstsq(design[ok], values[ok], rcond=None)
            hessian = np.array([[2 * c[3], c[4]], [c[4], 2 * c[5]]])
            if np.all(np.linalg.eigvalsh(hessian) > 0):
                step = np.clip(np.linalg.solve(hessian, -c[1:3]), -1.5, 1.5)
                patch_centre = np.array([pu[12], pv[12]])
                centre = np.clip(patch_centre + step * half, [u0, v0], [u1, v1])
        half = 0.3 * half
    hit = separation(pinion, gear, pinion_frame, gear_frame, centre[:1], centre[1:])
    if not (np.isfinite(hit.s[0]) and hit.s[0] <= best_s):
        hit = separation(pinion, gear, pinion_frame, gear_frame, best_uv[:1], best_uv[1:])
        centre = best_uv
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
