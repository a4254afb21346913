"""The gap around a contact point: measured from the separation field, and from curvatures.

Measured: on a grid in the common tangent plane, the lines along the common normal meet the
pinion flank at t_p and the gear flank at t_g; the gap h = t_g - t_p is fitted with
a bivariate quartic polynomial, whose quadratic part, diagonalised, gives A <= B and the
direction of A. Analytic: A and B from both flanks' principal curvatures and
the angle between their principal directions (analytic.hertz.relative_curvature). The two
must agree: that is a test of the whole chain. Units: mm, rad.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..analytic.hertz import RelativeCurvature, relative_curvature
from ..surfaces.base import GUESS_SAMPLES, Flank
from ..surfaces.placement import Frame
from .rays import RayHits, intersect


@dataclass(frozen=True)
class TangentPlanes:
    """For a batch of K contacts: contact point (world), unit normal (out of the pinion),
    and tangent basis e1, e2 (e1 along the pinion's face direction), arrays (K, 3)."""

    point: np.ndarray
    normal: np.ndarray
    e1: np.ndarray
    e2: np.ndarray

    def direction(self, angle: np.ndarray) -> np.ndarray:
        """Unit tangents at `angle` (rad, (K,)) from e1."""
        return np.cos(angle)[:, None] * self.e1 + np.sin(angle)[:, None] * self.e2

    def at(self, x: np.ndarray, y: np.ndarray) -> np.ndarray:
        """World points of the plane coordinates x, y (mm, shape (K, ...))."""
        def lift(vector):
            return vector.reshape(vector.shape[:1] + (1,) * (x.ndim - 1) + (3,))
        return lift(self.point) + x[..., None] * lift(self.e1) + y[..., None] * lift(self.e2)


@dataclass(frozen=True)
class GapFits:
    """Gap h = A x² + B y² in the principal axes of each fit ((K,) arrays A <= B, `angle`
    (rad) from e1 to the A axis); `rms` of the residual (mm); the half-extents of each
    fitted patch (mm, (K, 2))."""

    A: np.ndarray
    B: np.ndarray
    angle: np.ndarray
    rms: np.ndarray
    extent: np.ndarray


def tangent_planes(pinion: Flank, frames: Frame, u: np.ndarray, v: np.ndarray) -> TangentPlanes:
    """The common tangent planes at pinion parameters (u, v) ((K,)), frames stacked (K,)."""
    s = pinion.evaluate(u[:, None], v[:, None], order=1)
    n = frames.vectors_to_world(s.normals)[:, 0]
    face = frames.vectors_to_world(s.r_v)[:, 0]
    e1 = face - np.einsum("ki,ki->k", face, n)[:, None] * n
    e1 /= np.linalg.norm(e1, axis=-1, keepdims=True)
    return TangentPlanes(frames.to_world(s.points)[:, 0], n, e1, np.cross(n, e1))


def heights(flank: Flank, frames: Frame, planes: TangentPlanes, x: np.ndarray, y: np.ndarray,
            guess_u: np.ndarray, guess_v: np.ndarray) -> RayHits:
    """Where the lines along each plane's normal through its points (x, y) (mm, shape
    (K, m)) meet the flank (continued beyond its edges where it exists): hits.s is the
    height t above the plane, hits.inside says whether the flank has material there."""
    local = frames.to_local(planes.at(x, y))
    direction = frames.vectors_to_local(planes.normal[:, None, :])
    hits = intersect(flank, local, direction, *_tangent_start(flank, frames, planes, x, y,
                                                              guess_u, guess_v))
    hits = _continued_from_neighbours(hits, flank, frames, planes, x, y, local, direction)
    return _restarted_near(hits, flank, x, y, local, direction)


#: the Newton steps of a line's restart from its nearest line that met the flank (see
#: _continued_from_neighbours): from there a line that meets the flank converges in a few;
#: a wheel flank's evaluation is costly (its meshing condition solved at every step)
RESTART_STEPS = 8


def _continued_from_neighbours(hits: RayHits, flank: Flank, frames: Frame,
                               planes: TangentPlanes, x, y, local, direction) -> RayHits:
    """The hits with each line whose Newton solve did not converge from the contact's
    tangent map solved again, RESTART_STEPS steps, from its nearest converged line of the
    same plane (that line's parameters moved by the tangent map there). A first-order start
    from the contact point lies far off on a strongly curved or twisted flank (a worm
    wheel's, a few mm from the contact): lines in the middle of a field failed where the
    flank exists, and the field took a false edge there."""
    lost = ~hits.converged & np.isfinite(x) & np.isfinite(y)
    rows, columns, starts = [], [], []
    for k in np.flatnonzero(lost.any(axis=1) & hits.converged.any(axis=1)):
        met = np.flatnonzero(hits.converged[k])
        far = np.flatnonzero(lost[k])
        rows.append(np.full(far.size, k))
        columns.append(far)
        starts.append(met[np.argmin(np.hypot(x[k, far, None] - x[k, met],
                                             y[k, far, None] - y[k, met]), axis=1)])
    if not rows:
        return hits
    k, j, near = (np.concatenate(a) for a in (rows, columns, starts))
    start = _tangent_start(flank, frames[k], planes_at(planes, k), x[k, j][:, None],
                           y[k, j][:, None], hits.u[k, near], hits.v[k, near])
    again = intersect(flank, local[k, j][:, None], direction[k], *start,
                      iterations=RESTART_STEPS)
    found = again.converged[:, 0]
    k, j = k[found], j[found]
    for name in ("u", "v", "s", "converged", "inside"):
        getattr(hits, name)[k, j] = getattr(again, name)[found, 0]
    hits.normal[k, j] = again.normal[found, 0]
    return hits


def _restarted_near(hits: RayHits, flank: Flank, x, y, local, direction) -> RayHits:
    """The hits with each line that neither start met solved again from the flank's own
    nearest sample to the line's plane point (Flank.parameters_near): a line through a tip
    rounding (a radius of 0.1 modules turning a worm wheel's flank by up to 60 deg), started
    from its neighbour's parameters by the tangent map, was thrown off the flank by its
    first Newton step (6 % of the lines through a worm set's flank material failed,
    tests/test_contact_worm.py)."""
    lost = ~hits.converged & np.isfinite(x) & np.isfinite(y)
    if not lost.any():
        return hits
    k, j = np.nonzero(lost)
    points, lines = local[k, j], np.broadcast_to(direction, local.shape)[k, j]
    u0, v0 = flank.parameters_near(points)
    # only lines passing within a cell of that sample's grid (most lost lines miss the
    # flank: beyond a worm wheel's hob reach no surface exists)
    (ua, ub), (va, vb) = flank.domain
    r, r_u, r_v = (np.stack(np.broadcast_arrays(*c), axis=-1)
                   for c in flank.tangents(u0, v0))
    offset = r - points
    off_line = offset - np.sum(offset * lines, axis=-1, keepdims=True) * lines
    cell = (np.linalg.norm(r_u, axis=-1) * (ub - ua)
            + np.linalg.norm(r_v, axis=-1) * (vb - va)) / (GUESS_SAMPLES - 1)
    near = np.linalg.norm(off_line, axis=-1) <= cell
    k, j, points, lines, u0, v0 = k[near], j[near], points[near], lines[near], u0[near], v0[near]
    again = intersect(flank, points, lines, u0, v0)
    found = again.converged
    k, j = k[found], j[found]
    for name in ("u", "v", "s", "converged", "inside"):
        getattr(hits, name)[k, j] = getattr(again, name)[found]
    hits.normal[k, j] = again.normal[found]
    return hits


def _tangent_start(flank: Flank, frames: Frame, planes: TangentPlanes, x, y, guess_u, guess_v):
    """Starting parameters for the lines through plane points (x, y) ((K, m)): the guess
    (one point per plane, (K,)) moved by the flank's tangent map there, projected on the
    plane (first order: Newton then starts one step in)."""
    sample = flank.evaluate(guess_u[:, None], guess_v[:, None], order=1)
    offset = frames.to_world(sample.points)[:, 0] - planes.point
    r_u, r_v = (frames.vectors_to_world(r)[:, 0] for r in (sample.r_u, sample.r_v))
    j11, j12 = np.einsum("ki,ki->k", r_u, planes.e1), np.einsum("ki,ki->k", r_v, planes.e1)
    j21, j22 = np.einsum("ki,ki->k", r_u, planes.e2), np.einsum("ki,ki->k", r_v, planes.e2)
    dx = x - np.einsum("ki,ki->k", offset, planes.e1)[:, None]
    dy = y - np.einsum("ki,ki->k", offset, planes.e2)[:, None]
    det = (j11 * j22 - j12 * j21)[:, None]
    with np.errstate(all="ignore"):
        du = (j22[:, None] * dx - j12[:, None] * dy) / det
        dv = (j11[:, None] * dy - j21[:, None] * dx) / det
    # a flank seen edge-on from the plane (no tangent map) starts at the guess itself
    flat = ~(np.isfinite(du) & np.isfinite(dv))
    return (np.where(flat, guess_u[:, None], guess_u[:, None] + du),
            np.where(flat, guess_v[:, None], guess_v[:, None] + dv))


#: exponents (i, j) of the quartic gap polynomial fitted around a contact point
_POWERS = [(i, k - i) for k in range(5) for i in range(k + 1)]


def fit_gaps(pinion: Flank, gear: Flank, pinion_frames: Frame, gear_frames: Frame,
             planes: TangentPlanes, pinion_uv, gear_uv, extent: np.ndarray, n: int = 21) -> GapFits:
    """Least-squares fit of each contact's gap on an n × n grid of half-extents `extent`
    ((K, 2), mm), each shrunk until the lines of its whole patch meet both surfaces
    (continued beyond the flank edges, where the contact may sit); NaN for a contact where
    a surface ends at the contact itself (a worm wheel's tip edge, beyond which the hob
    generates nothing): no patch around it meets both. The fit carries the cubic
    and quartic terms too, so that the flank's changing curvature does not leak into A and
    B; A and B are the quadratic part, diagonalised."""
    extent = np.array(extent, float)
    unit = np.linspace(-1.0, 1.0, n)
    X, Y = (a.ravel() for a in np.meshgrid(unit, unit, indexing="ij"))
    h = np.full((len(extent), n * n), np.nan)
    todo = np.flatnonzero(np.all(np.isfinite(extent), axis=-1))
    for _ in range(12):
        if todo.size == 0:
            break
        x, y = extent[todo, :1] * X, extent[todo, 1:] * Y
        hp = heights(pinion, pinion_frames[todo], planes_at(planes, todo), x, y,
                     pinion_uv[0][todo], pinion_uv[1][todo])
        hg = heights(gear, gear_frames[todo], planes_at(planes, todo), x, y,
                     gear_uv[0][todo], gear_uv[1][todo])
        met = np.all(hp.converged & hg.converged, axis=-1)
        h[todo[met]] = (hg.s - hp.s)[met]
        extent[todo[~met]] *= 0.7
        todo = todo[~met]
    design = np.stack([X**i * Y**j for i, j in _POWERS], axis=-1)
    coef = h @ np.linalg.pinv(design).T                                  # (K, 15)
    rms = np.sqrt(np.mean((coef @ design.T - h) ** 2, axis=-1))
    c = dict(zip(_POWERS, coef.T))
    ex, ey = extent[:, 0], extent[:, 1]
    quad = np.stack([np.stack([c[(2, 0)] / ex**2, 0.5 * c[(1, 1)] / (ex * ey)], axis=-1),
                     np.stack([0.5 * c[(1, 1)] / (ex * ey), c[(0, 2)] / ey**2], axis=-1)], axis=-2)
    values, vectors = np.linalg.eigh(quad)
    angle = np.arctan2(vectors[:, 1, 0], vectors[:, 0, 0])
    return GapFits(values[:, 0], values[:, 1], angle, rms, extent)


def planes_at(planes: TangentPlanes, index) -> TangentPlanes:
    """The planes of a sub-batch."""
    return TangentPlanes(planes.point[index], planes.normal[index], planes.e1[index], planes.e2[index])


def turned(planes: TangentPlanes, angle: np.ndarray) -> TangentPlanes:
    """The same planes with their bases turned by `angle` (rad, (K,)) from e1 toward e2."""
    e1 = planes.direction(np.asarray(angle, float))
    return TangentPlanes(planes.point, planes.normal, e1, np.cross(planes.normal, e1))


def analytic_gaps(pinion: Flank, gear: Flank, pinion_frames: Frame, gear_frames: Frame,
                  planes: TangentPlanes, pinion_uv, gear_uv) -> list[RelativeCurvature]:
    """A, B and the direction of A from the principal curvatures of both flanks (convex
    positive for each, along its own outward normal), expressed with `angle` from e1."""
    sp = pinion.evaluate(pinion_uv[0][:, None], pinion_uv[1][:, None])
    sg = gear.evaluate(gear_uv[0][:, None], gear_uv[1][:, None])
    kp1, kp2, dp1, _ = (x[:, 0] for x in sp.principal_curvatures())
    kg1, kg2, dg1, _ = (x[:, 0] for x in sg.principal_curvatures())
    dp1 = pinion_frames.vectors_to_world(dp1[:, None])[:, 0]
    dg1 = gear_frames.vectors_to_world(dg1[:, None])[:, 0]
    dot = lambda a, b: np.einsum("ki,ki->k", a, b)  # noqa: E731
    angle_p = np.arctan2(dot(dp1, planes.e2), dot(dp1, planes.e1))
    angle_g = np.arctan2(dot(dg1, planes.e2), dot(dg1, planes.e1))
    out = []
    for k in range(len(angle_p)):
        rc = relative_curvature((float(kp1[k]), float(kp2[k])), (float(kg1[k]), float(kg2[k])),
                                float(angle_g[k] - angle_p[k]), point_contact=False)
        out.append(RelativeCurvature(rc.A, rc.B, float(angle_p[k] + rc.angle)))
    return out


def face_length(flank: Flank, uv) -> np.ndarray:
    """Length (mm) of the flank along its v parameter at the points uv ((K,) arrays)."""
    (_, _), (v0, v1) = flank.domain
    return (v1 - v0) * np.linalg.norm(flank.evaluate(uv[0], uv[1], order=1).r_v, axis=-1)
