"""Where lines meet a flank: the vectorised ray-surface intersection behind every separation.

For points P with directions n (both in the flank's own frame) find (u, v, s) with
r(u, v) = P + s·n by Newton's method on all points at once; s is the signed distance along
n to the flank. Units: mm, rad.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..surfaces.base import Flank, cross, dot

#: a ray whose parameters wander this many domain spans beyond the flank has met no part of
#: it worth following (another branch of a long surface, or none): it stops, unconverged
LOST_SPANS = 5.0


@dataclass(frozen=True)
class RayHits:
    """Per ray: the flank parameters hit, the distance s along the ray (mm), whether Newton
    converged on the (analytically continued) surface, and whether the hit lies inside the
    flank's domain (False: no flank material on that line)."""

    u: np.ndarray
    v: np.ndarray
    s: np.ndarray
    converged: np.ndarray
    inside: np.ndarray


def intersect(flank: Flank, points: np.ndarray, directions: np.ndarray, u0: np.ndarray,
              v0: np.ndarray, iterations: int = 30, tolerance: float = 1e-11) -> RayHits:
    """Newton solve of r(u, v) - P - s·n = 0 from the starting parameters (u0, v0).

    points, directions: (..., 3) in the flank's frame; u0, v0: starting guesses (...).
    Each iteration works on the rays still running only: a ray stops when its residual is
    below `tolerance` (converged), or when it has no Newton step or wanders off."""
    shape = np.broadcast_shapes(np.shape(u0), np.shape(v0), np.shape(points)[:-1],
                                np.shape(directions)[:-1])
    P = np.broadcast_to(points, shape + (3,)).reshape(-1, 3)
    D = np.broadcast_to(directions, shape + (3,)).reshape(-1, 3)
    u = np.array(np.broadcast_to(u0, shape), float).ravel()
    v = np.array(np.broadcast_to(v0, shape), float).ravel()
    s = np.zeros(u.shape)
    converged = np.zeros(u.shape, bool)
    (ua, ub), (va, vb) = flank.domain
    reach_u, reach_v = LOST_SPANS * (ub - ua), LOST_SPANS * (vb - va)
    active = np.flatnonzero(np.isfinite(u) & np.isfinite(v))
    for _ in range(iterations):
        if active.size == 0:
            break
        sample = flank.evaluate(u[active], v[active], order=1)
        residual = sample.points - P[active] - s[active, None] * D[active]
        done = np.linalg.norm(residual, axis=-1) < tolerance
        converged[active[done]] = True
        # Newton step: [r_u r_v -n]·(du, dv, ds) = -residual, by Cramer's rule
        ru, rv, n = sample.r_u, sample.r_v, -D[active]
        rv_n = cross(rv, n)
        det = dot(ru, rv_n)
        # a ray along the flank, or a singular point of it (an involute at its base circle),
        # has no Newton step: it ends unconverged
        running = ~done & (np.abs(det) > 1e-14) & np.isfinite(residual).all(axis=-1)
        ru, rv, n, rv_n, det = ru[running], rv[running], n[running], rv_n[running], det[running]
        y = -residual[running]
        step = np.stack([dot(y, rv_n), dot(ru, cross(y, n)), dot(ru, cross(rv, y))],
                        axis=-1) / det[:, None]
        active = active[running]
        u[active] += step[:, 0]
        v[active] += step[:, 1]
        s[active] += step[:, 2]
        on = (np.isfinite(step).all(axis=-1) & (u[active] > ua - reach_u) & (u[active] < ub + reach_u)
              & (v[active] > va - reach_v) & (v[active] < vb + reach_v))
        active = active[on]
    slack = 1e-9
    inside = converged & (u >= ua - slack) & (u <= ub + slack) & (v >= va - slack) & (v <= vb + slack)
    return RayHits(*(x.reshape(shape) for x in (u, v, s, converged, inside)))
