"""Contact by surface separation over the mesh cycle (docs/DESIGN.md principle 3).

At a mesh position the separation of a pinion flank point is the distance, along the pinion
flank's normal, to the gear flank (negative = overlap). The gear is turned back by the
transmission error until the least separation over all tooth pairs is zero; the pinion point
where it is least is the contact point. Every function works on a batch: frames stacked
over mesh positions and tooth pairs (surfaces.placement.Frame.stack), parameters broadcast against
them. Units: mm, rad.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..surfaces.base import Flank
from ..surfaces.placement import Frame
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
        hits = intersect(gear, points, normals, u0, v0, inside_only=True)
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
    (half-sizes `half`) and the patch moves to its least point in the flank's domain (on an
    edge where the separation falls toward it), shrinking each time. The best point seen
    (patch points and the final fitted minimum) is returned for each pair."""
    (u0, u1), (v0, v1) = pinion.domain
    lo, hi = np.array([u0, v0]), np.array([u1, v1])
    centre = np.stack([start_u, start_v], axis=-1).astype(float)          # (K, 2)
    half = np.array(half, float)
    offsets = np.linspace(-1.0, 1.0, 5)
    du, dv = (x.ravel() for x in np.meshgrid(offsets, offsets, indexing="ij"))
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
        # least squares over each patch's finite points (at their places after the clip to
        # the domain, in half-sizes from the patch centre): normal equations, batched
        x, y = (pu - centre[:, :1]) / half[0], (pv - centre[:, 1:]) / half[1]
        design = np.stack([np.ones_like(x), x, y, x * x, x * y, y * y], axis=-1)  # (K, 25, 6)
        weights = ok.astype(float)
        normal = np.einsum("kn,kni,knj->kij", weights, design, design)
        rhs = np.einsum("kn,kni,kn->ki", weights, design, np.where(ok, values, 0.0))
        fitted = np.flatnonzero(ok.sum(axis=-1) >= 6)
        c = np.einsum("kij,kj->ki", np.linalg.pinv(normal[fitted]), rhs[fitted])
        # the fitted quadratic's least point in the domain, within 1.5 half-sizes
        low = np.maximum((lo - centre[fitted]) / half, -1.5)
        high = np.minimum((hi - centre[fitted]) / half, 1.5)
        moved = np.clip(centre[fitted] + _box_minimum(c, low, high) * half, lo, hi)
        centre = best_uv.copy()
        centre[fitted] = moved
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


def _box_minimum(c: np.ndarray, low: np.ndarray, high: np.ndarray) -> np.ndarray:
    """The least point (K, 2) of the quadratics c0 + c1 x + c2 y + c3 x² + c4 xy + c5 y²
    (c: (K, 6)) in the boxes low <= (x, y) <= high ((K, 2)): the least of the candidates a
    box-constrained minimum can be - the free minimum (where convex and inside), each side's
    one-dimensional minimum (clipped to the side) and the corners. A separation that falls
    toward a flank edge (no crown, or a slope beyond the crown) has its contact on the edge."""
    def value(x, y):
        return c[:, 1] * x + c[:, 2] * y + c[:, 3] * x * x + c[:, 4] * x * y + c[:, 5] * y * y

    candidates = []
    det = 4.0 * c[:, 3] * c[:, 5] - c[:, 4] ** 2
    with np.errstate(all="ignore"):
        free = np.stack([(c[:, 4] * c[:, 2] - 2.0 * c[:, 5] * c[:, 1]) / det,
                         (c[:, 4] * c[:, 1] - 2.0 * c[:, 3] * c[:, 2]) / det], axis=-1)
        convex = (c[:, 3] > 0) & (det > 0) & np.all((free >= low) & (free <= high), axis=-1)
        candidates.append(np.where(convex[:, None], free, np.nan))
        for axis in (0, 1):          # sides x = bound (y free) and y = bound (x free)
            other = 1 - axis
            curvature = c[:, 3 + 2 * other]
            for bound in (low[:, axis], high[:, axis]):
                linear = c[:, 1 + other] + c[:, 4] * bound
                t = np.clip(np.where(curvature > 0, -linear / (2.0 * curvature), low[:, other]),
                            low[:, other], high[:, other])
                point = np.empty_like(free)
                point[:, axis], point[:, other] = bound, t
                candidates.append(point)
    for x in (low[:, 0], high[:, 0]):
        for y in (low[:, 1], high[:, 1]):
            candidates.append(np.stack([x, y], axis=-1))
    points = np.stack(candidates, axis=1)                                  # (K, n, 2)
    with np.errstate(invalid="ignore"):
        scores = np.stack([value(p[:, 0], p[:, 1]) for p in np.moveaxis(points, 1, 0)], axis=-1)
    scores = np.where(np.isfinite(scores), scores, np.inf)
    return points[np.arange(len(c)), np.argmin(scores, axis=-1)]


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
