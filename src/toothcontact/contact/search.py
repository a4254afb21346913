"""Contact by surface separation over the mesh cycle (DESIGN.md principle 3).

At a mesh position the separation of a pinion flank point is the distance, along the pinion
flank's normal, to the gear flank (negative = overlap). The gear is turned back by the
transmission error until the least separation over all tooth pairs is zero; the pinion point
where it is least is the contact point. Every function works on a batch: frames stacked
over mesh positions and tooth pairs (assembly.Frame.stack), parameters broadcast against
them. Units: mm, rad.
"""

from __future__ import annotations

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
        facing = (hits.inside & (np.abs(hits.s) <= REACH)
                  & (np.einsum("...i,...i->...", hits.normal, normals) < 0.0))
    return Separation(np.where(facing, hits.s, np.nan), hits.u, hits.v)


@dataclass(frozen=True)
class ContactPoints:
    """The least separation of each of a batch of tooth pairs: pinion (u, v), gear (u, v) and
    the separation (mm), arrays of shape (K,)."""

    pinion_u: np.ndarray
    pinion_v: np.ndarray
    gear_u: np.ndarray
    gear_v: np.ndarray
    s: np.ndarray


def lowest(field: np.ndarray, u: np.ndarray, v: np.ndarray, keep: int = 9):
    """The `keep` points of least separation along the last axis of `field` (NaN = no
    flank facing), as (u, v, s) arrays of shape (..., keep); s is +inf where fewer exist."""
    values = np.where(np.isfinite(field), field, np.inf)
    order = np.argsort(values, axis=-1)[..., :keep]
    u, v = (np.broadcast_to(x.ravel(), field.shape) for x in (u, v))
    return (np.take_along_axis(u, order, -1), np.take_along_axis(v, order, -1),
            np.take_along_axis(values, order, -1))


def refine_minima(pinion: Flank, gear: Flank, pinion_frames: Frame, gear_frames: Frame,
                  start_u: np.ndarray, start_v: np.ndarray, half: tuple[float, float],
                  refinements: int = 6) -> ContactPoints:
    """The pinion points of least separation near (start_u, start_v), for a batch of K pairs
    (frames stacked (K,)): a quadratic is fitted to the separation on a 5 × 5 patch
    (half-sizes `half`) and the patch moves to its minimum (kept inside the flank's domain),
    shrinking each time. The best point seen (patch points and the final fitted minimum)
    is returned for each pair."""
    (u0, u1), (v0, v1) = pinion.domain
    lo, hi = np.array([u0, v0]), np.array([u1, v1])
    centre = np.stack([start_u, start_v], axis=-1).astype(float)          # (K, 2)
    half = np.array(half, float)
    offsets = np.linspace(-1.0, 1.0, 5)
    du, dv = (x.ravel() for x in np.meshgrid(offsets, offsets, indexing="ij"))
    design = np.stack([np.ones(25), du, dv, du**2, du * dv, dv**2], axis=-1)   # (25, 6)
    best_uv, best_s = centre.copy(), np.full(len(centre), np.inf)
    rows = np.arange(len(centre))
    for _ in range(refinements):
        pu = np.clip(centre[:, :1] + half[0] * du, u0, u1)                # (K, 25)
        pv = np.clip(centre[:, 1:] + half[1] * dv, v0, v1)
        values = separation(pinion, gear, pinion_frames, gear_frames, pu, pv).s
        ok = np.isfinite(values)
        k = np.argmin(np.where(ok, values, np.inf), axis=-1)
        better = values[rows, k] < best_s
        best_uv[better] = np.stack([pu[rows, k], pv[rows, k]], axis=-1)[better]
        best_s[better] = values[rows, k][better]
        centre = best_uv.copy()
        # least squares over each patch's finite points: normal equations, batched
        weights = ok.astype(float)
        normal = np.einsum("kn,ni,nj->kij", weights, design, design)
        rhs = np.einsum("kn,ni,kn->ki", weights, design, np.where(ok, values, 0.0))
        fitted = ok.sum(axis=-1) >= 6
        c = np.einsum("kij,kj->ki", np.linalg.pinv(normal[fitted]), rhs[fitted])
        h00, h01, h11 = 2 * c[:, 3], c[:, 4], 2 * c[:, 5]
        det = h00 * h11 - h01 * h01
        convex = (h00 > 0) & (det > 0)
        with np.errstate(all="ignore"):
            step = np.stack([(-h11 * c[:, 1] + h01 * c[:, 2]) / det,
                             (h01 * c[:, 1] - h00 * c[:, 2]) / det], axis=-1)
        step = np.clip(step, -1.5, 1.5)
        patch_centre = np.stack([pu[fitted, 12], pv[fitted, 12]], axis=-1)
        moved = np.clip(patch_centre + step * half, lo, hi)
        index = np.flatnonzero(fitted)[convex]
        centre[index] = moved[convex]
        half = 0.3 * half
    hit = separation(pinion, gear, pinion_frames, gear_frames, centre[:, :1], centre[:, 1:])
    take_centre = np.isfinite(hit.s[:, 0]) & (hit.s[:, 0] <= best_s)
    if not take_centre.all():
        other = separation(pinion, gear, pinion_frames, gear_frames, best_uv[:, :1], best_uv[:, 1:])
        centre = np.where(take_centre[:, None], centre, best_uv)
        hit = Separation(*(np.where(take_centre[:, None], a, b)
                           for a, b in zip((hit.s, hit.gear_u, hit.gear_v),
                                           (other.s, other.gear_u, other.gear_v))))
    return ContactPoints(centre[:, 0], centre[:, 1], hit.gear_u[:, 0], hit.gear_v[:, 0], hit.s[:, 0])


def solve_transmission_error(least, delta0: np.ndarray, tolerance: float = 1e-10,
                             step: float = 1e-5, iterations: int = 30):
    """The gear lags delta (rad, one per mesh position) at which `least(delta)`, the least
    separation over all tooth pairs at each position (mm), is zero: secant iteration on all
    positions at once. Returns (delta, least separation there)."""
    d0 = np.asarray(delta0, float)
    s0 = least(d0)
    d1 = d0 + step
    s1 = least(d1)
    for _ in range(iterations):
        running = np.abs(s1) >= tolerance
        if not running.any():
            break
        with np.errstate(all="ignore"):
            slope = (s1 - s0) / (d1 - d0)
        if not np.all(np.isfinite(slope[running]) & (slope[running] != 0)):
            raise RuntimeError("the separation does not change with the gear's rotation")
        d_next = np.where(running, d1 - s1 / np.where(running, slope, 1.0), d1)
        d0, s0, d1 = np.where(running, d1, d0), np.where(running, s1, s0), d_next
        s1 = np.where(running, least(d1), s1)
    return d1, s1
