"""Where lines meet a flank: the vectorised ray-surface intersection behind every separation.

For points P with directions n (both in the flank's own frame) find (u, v, s) with
r(u, v) = P + s·n by Newton's method on all points at once; s is the signed distance along
n to the flank. Units: mm, rad.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..surfaces.base import Flank


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

    points, directions: (..., 3) in the flank's frame; u0, v0: starting guesses (...)."""
    u, v = np.array(u0, float, copy=True), np.array(v0, float, copy=True)
    s = np.zeros(u.shape)
    converged = np.zeros(u.shape, bool)
    for _ in range(iterations):
        sample = flank.evaluate(u, v, order=1)
        residual = sample.points - points - s[..., None] * directions
        jac = np.stack([sample.r_u, sample.r_v, -directions], axis=-1)
        # a ray along the flank, or a singular point of it (an involute at its base circle),
        # has no Newton step: park it (identity) and let it end unconverged
        singular = ~(np.abs(np.linalg.det(jac)) > 1e-14)
        jac = np.where(singular[..., None, None], np.eye(3), jac)
        step = np.linalg.solve(jac, -residual[..., None])[..., 0]
        step = np.where(np.isfinite(step) & ~singular[..., None], step, 0.0)
        u, v, s = u + step[..., 0], v + step[..., 1], s + step[..., 2]
        converged = np.linalg.norm(residual, axis=-1) < tolerance
        if np.all(converged | ~np.isfinite(residual).all(axis=-1)):
            break
    (ua, ub), (va, vb) = flank.domain
    slack = 1e-9
    inside = converged & (u >= ua - slack) & (u <= ub + slack) & (v >= va - slack) & (v <= vb + slack)
    return RayHits(u, v, s, converged, inside)
