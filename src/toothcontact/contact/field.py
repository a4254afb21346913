"""Separation fields: the pinion flank's ease-off over the mesh cycle, and the gap around one
contact in its tangent plane.

Ease-off: at every mesh position (every tooth pair near contact, the gear at its solved
lag) the separation of a grid of pinion flank points from the gear flank; the least over the
cycle at each point is what a paint pattern shows: zero along the path of contact, and the
gap a marking compound must bridge elsewhere.

Gap field: around a contact, on a grid in the common tangent plane (x along e1, the pinion's
face direction; y along e2), the distance along the common normal from the pinion flank to
the gear flank, and where both flanks have material. The lines are solved exactly (rays.py)
on a `samples` × `samples` grid and carried to the requested grid by bicubic splines of the
gap and of both flanks' parameters: the surfaces are smooth, so the splines are exact to far
below a micrometre (tested), and the flank edges, from the interpolated parameters, fall
where they lie. Units: mm.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..assembly import Frame
from ..surfaces.base import Flank
from .local import TangentPlanes, heights, planes_at
from .search import separation


@dataclass(frozen=True)
class EaseOff:
    """Least separation (mm, NaN where no gear flank faces the point) of the pinion flank's
    grid points over the cycle: parameters u (nu,), v (nv,), the grid's points (nu, nv, 3)
    in the pinion's own frame, and the separation (nu, nv)."""

    u: np.ndarray
    v: np.ndarray
    points: np.ndarray
    separation: np.ndarray

    @property
    def face_mm(self) -> np.ndarray:
        """Face position of each v line (mm, along the axis, from mid-face)."""
        return self.points[:, :, 2].mean(axis=0)

    @property
    def radius_mm(self) -> np.ndarray:
        """Radius of each u line (mm, mean over the face)."""
        return np.hypot(self.points[..., 0], self.points[..., 1]).mean(axis=1)


def ease_off(pinion: Flank, gear: Flank, pinion_frames: Frame, gear_frames: Frame,
             turns: np.ndarray, grid: tuple[int, int]) -> EaseOff:
    """The ease-off of the pinion flank over the cycle, from K placements of it against the
    gear (frames stacked (K,), the gear at its solved lag), placement k putting the flank
    where the pinion's turn `turns[k]` (rad) puts it.

    At each grid point the separation is least where the flank passes the path of contact;
    between placements it is a parabola in the turn (the point runs along the flank at a
    steady rate, and the gap grows with the square of its distance from the contact), so
    the least is taken at the vertex through the lowest placement and its two neighbours."""
    u, v = pinion.grid(*grid)
    s = separation(pinion, gear, pinion_frames, gear_frames, u.ravel(), v.ravel()).s
    s = np.where(np.isfinite(s), s, np.inf)
    # the least over placements at the same turn (other pairs of the same position)
    order = np.argsort(turns, kind="stable")
    turns, s = turns[order], s[order]
    unique, first = np.unique(np.round(turns, 12), return_index=True)
    s = np.minimum.reduceat(s, first, axis=0)
    least = np.min(s, axis=0)
    m = np.argmin(s, axis=0)
    inner = (m > 0) & (m < len(unique) - 1)
    idx = np.clip(m, 1, max(len(unique) - 2, 1))
    if len(unique) >= 3:
        cols = np.arange(s.shape[1])
        t0, t1, t2 = unique[idx - 1], unique[idx], unique[idx + 1]
        s0, s1, s2 = s[idx - 1, cols], s[idx, cols], s[idx + 1, cols]
        with np.errstate(all="ignore"):
            # vertex of the parabola through three points (t_i, s_i)
            d01, d12 = (s1 - s0) / (t1 - t0), (s2 - s1) / (t2 - t1)
            curvature = (d12 - d01) / (t2 - t0)
            t_min = 0.5 * (t0 + t1) - d01 / (2.0 * curvature)
            vertex = s0 + d01 * (t_min - t0) + curvature * (t_min - t0) * (t_min - t1)
        ok = inner & np.isfinite(vertex) & (curvature > 0) & (t_min >= t0) & (t_min <= t2)
        least = np.where(ok, np.minimum(vertex, least), least)
    points = np.stack(pinion.point(u, v), axis=-1)
    return EaseOff(u[:, 0], v[0], points,
                   np.where(np.isfinite(least), least, np.nan).reshape(u.shape))


@dataclass(frozen=True)
class GapField:
    """The gap around one contact on an (nx, ny) grid of its tangent plane: x (nx,) along e1
    and y (ny,) along e2 (mm, from the contact point); gap (mm, NaN where a surface does not
    exist), and `material`: both flanks have material on the line (inside their domains)."""

    x: np.ndarray
    y: np.ndarray
    gap: np.ndarray
    material: np.ndarray

    @property
    def spacing(self) -> tuple[float, float]:
        return float(self.x[1] - self.x[0]), float(self.y[1] - self.y[0])


def gap_field(pinion: Flank, gear: Flank, pinion_frame: Frame, gear_frame: Frame,
              plane: TangentPlanes, pinion_uv, gear_uv, half: tuple[float, float],
              shape: tuple[int, int], samples: int = 41) -> GapField:
    """The gap field of one contact (frames and plane of a batch of one) over
    [-half[0], half[0]] × [-half[1], half[1]] mm on `shape` points."""
    from scipy.interpolate import RectBivariateSpline

    xs, ys = np.linspace(-half[0], half[0], samples), np.linspace(-half[1], half[1], samples)
    X, Y = (a.reshape(1, -1) for a in np.meshgrid(xs, ys, indexing="ij"))
    hp = heights(pinion, pinion_frame, plane, X, Y, *(np.atleast_1d(w) for w in pinion_uv))
    hg = heights(gear, gear_frame, plane, X, Y, *(np.atleast_1d(w) for w in gear_uv))
    met = (hp.converged & hg.converged).reshape(samples, samples)
    if not met.any():
        raise ValueError("no line of the gap field meets both flanks")
    nearest = _nearest_met(met)
    x, y = np.linspace(-half[0], half[0], shape[0]), np.linspace(-half[1], half[1], shape[1])

    def spline(values):
        filled = values.reshape(samples, samples)[nearest]
        return RectBivariateSpline(xs, ys, filled, kx=3, ky=3)(x, y)

    gap = spline(hg.s - hp.s)
    inside = np.ones(gap.shape, bool)
    for flank, hits in ((pinion, hp), (gear, hg)):
        (u0, u1), (v0, v1) = flank.domain
        u, v = spline(hits.u), spline(hits.v)
        inside &= (u >= u0) & (u <= u1) & (v >= v0) & (v <= v1)
    # a fine point whose nearest sample did not meet both surfaces has no surface to speak of
    ix = np.rint((x + half[0]) / (2 * half[0]) * (samples - 1)).astype(int)
    iy = np.rint((y + half[1]) / (2 * half[1]) * (samples - 1)).astype(int)
    exists = met[np.ix_(ix, iy)]
    return GapField(x, y, np.where(exists, gap, np.nan), inside & exists)


def _nearest_met(met: np.ndarray):
    """Index arrays taking each sample to its nearest sample where both lines met."""
    from scipy.ndimage import distance_transform_edt

    if met.all():
        return tuple(np.indices(met.shape))
    _, index = distance_transform_edt(~met, return_indices=True)
    return tuple(index)


def contact_field(cycle, k: int, shape: tuple[int, int], margin: float = 1.3) -> GapField:
    """The gap field of row k of a contact cycle, over the bounding box of its Hertz ellipse
    (or of the line of contact) enlarged by `margin`."""
    row = cycle.rows[k]
    a, b, angle = row["a_mm"], row["b_mm"], float(cycle.axis_angle[k])
    half = (margin * float(np.hypot(a * np.cos(angle), b * np.sin(angle))),
            margin * float(np.hypot(a * np.sin(angle), b * np.cos(angle))))
    index = np.array([k])
    return gap_field(cycle.pinion, cycle.gear, cycle.pinion_frames[index], cycle.gear_frames[index],
                     planes_at(cycle.planes, index), cycle.contact_uv("pinion", k),
                     cycle.contact_uv("gear", k), half, shape)
