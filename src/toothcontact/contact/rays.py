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

#: a ray has converged once its residual is below this (mm): Newton's step from there
#: leaves a residual of about curvature × tolerance², far below a nanometre, so the step
#: is taken and no further evaluation is spent confirming it
TOLERANCE = 1e-7

#: a caller that takes only hits inside the flank's domain (search.separation) abandons a
#: ray whose residual has not halved in this many steps: Newton's iteration converges
#: quadratically once near a root, and a line that misses the flank (a pinion point facing
#: no gear flank, past its tip) cycles instead, with residuals of millimetres to metres, for
#: every step allowed. On the bundled spur, helical, FZG, spline and worm cases no ray that
#: ends inside the domain goes this long without halving it; a quarter to half of the rigid
#: search's ray steps were spent on the cycling ones (tests/test_rays.py)
STALL_STEPS = 4


@dataclass(frozen=True)
class RayHits:
    """Per ray: the flank parameters hit, the distance s along the ray (mm), whether Newton
    converged on the (analytically continued) surface, whether the hit lies inside the
    flank's domain (False: no flank material on that line), and the flank's unit normal
    out of the material there (from the last Newton step, NaN where not converged)."""

    u: np.ndarray
    v: np.ndarray
    s: np.ndarray
    converged: np.ndarray
    inside: np.ndarray
    normal: np.ndarray


def intersect(flank: Flank, points: np.ndarray, directions: np.ndarray, u0: np.ndarray,
              v0: np.ndarray, iterations: int = 30, inside_only: bool = False) -> RayHits:
    """Newton solve of r(u, v) - P - s·n = 0 from the starting parameters (u0, v0).

    points, directions: (..., 3) in the flank's frame; u0, v0: starting guesses (...).
    Each iteration works on the rays still running only (kept packed): a ray stops when its
    residual is below TOLERANCE (converged, after one last step), or when it has no Newton
    step or wanders off; with inside_only (a caller that takes only the hits inside the
    domain) also when its residual has not halved in STALL_STEPS steps."""
    shape = np.broadcast_shapes(np.shape(u0), np.shape(v0), np.shape(points)[:-1],
                                np.shape(directions)[:-1])
    n = int(np.prod(shape))
    u = np.array(np.broadcast_to(u0, shape), float).ravel()
    v = np.array(np.broadcast_to(v0, shape), float).ravel()
    s = np.zeros(n)
    converged = np.zeros(n, bool)
    normal = np.full((n, 3), np.nan)
    (ua, ub), (va, vb) = flank.domain
    reach_u, reach_v = LOST_SPANS * (ub - ua), LOST_SPANS * (vb - va)
    index = np.flatnonzero(np.isfinite(u) & np.isfinite(v))
    # the running rays, packed, vectors by component (first axis): their index, point,
    # direction negated (the Newton matrix's third column) and unknowns
    P = np.broadcast_to(points, shape + (3,)).reshape(-1, 3)[index].T
    m = -np.broadcast_to(directions, shape + (3,)).reshape(-1, 3)[index].T
    pu, pv, ps = u[index], v[index], s[index]
    # each running ray's least squared residual and the steps since it last fell to a quarter
    least, since = np.full(index.size, np.inf), np.zeros(index.size, int)
    for _ in range(iterations):
        if index.size == 0:
            break
        # Newton may probe beyond where the surface exists (a hob's reach): NaN there
        with np.errstate(all="ignore"):
            r, r_u, r_v = flank.tangents(pu, pv)
            y = tuple(P[i] - r[i] - ps * m[i] for i in range(3))       # minus the residual
            residual = dot(y, y)
            last = residual < TOLERANCE * TOLERANCE
            # Newton step: [r_u r_v m]·(du, dv, ds) = y, by Cramer's rule
            a, b, c = cross(r_v, m), cross(m, r_u), cross(r_u, r_v)
            det = dot(r_u, a)
            du, dv, ds = dot(y, a) / det, dot(y, b) / det, dot(y, c) / det
        pu, pv, ps = pu + du, pv + dv, ps + ds
        # a ray along the flank, or a singular point of it (an involute at its base circle),
        # has no Newton step: it ends unconverged, as does one that wanders off
        stepped = (np.abs(det) > 1e-14) & np.isfinite(du) & np.isfinite(dv) & np.isfinite(ds)
        final = last & stepped
        if final.any():
            done = index[final]
            converged[done] = True
            normal[done] = flank.orientation * np.stack(
                [np.broadcast_to(ci, final.shape)[final] for ci in c], axis=-1)
        keep = (stepped & ~last & (pu > ua - reach_u) & (pu < ub + reach_u)
                & (pv > va - reach_v) & (pv < vb + reach_v))
        if inside_only:
            halved = residual < 0.25 * least
            least = np.where(halved, residual, least)
            since = np.where(halved, 0, since + 1)
            keep &= since < STALL_STEPS
        leave = ~keep
        u[index[leave]], v[index[leave]], s[index[leave]] = pu[leave], pv[leave], ps[leave]
        index, P, m = index[keep], P[:, keep], m[:, keep]
        pu, pv, ps = pu[keep], pv[keep], ps[keep]
        least, since = least[keep], since[keep]
    u[index], v[index], s[index] = pu, pv, ps
    slack = 1e-9
    inside = converged & (u >= ua - slack) & (u <= ub + slack) & (v >= va - slack) & (v <= vb + slack)
    with np.errstate(invalid="ignore"):
        normal /= np.linalg.norm(normal, axis=-1, keepdims=True)
    return RayHits(*(x.reshape(shape) for x in (u, v, s, converged, inside)),
                   normal.reshape(shape + (3,)))
