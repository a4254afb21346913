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
from ..assembly import Frame
from ..surfaces.base import Flank
from .rays import intersect


@dataclass(frozen=True)
class TangentPlane:
    """Contact point (world), unit normal (out of the pinion), and tangent basis e1, e2
    (e1 along the pinion's face direction)."""

    point: np.ndarray
    normal: np.ndarray
    e1: np.ndarray
    e2: np.ndarray

    def direction(self, angle: float) -> np.ndarray:
        return np.cos(angle) * self.e1 + np.sin(angle) * self.e2


@dataclass(frozen=True)
class GapFit:
    """Gap h = A x² + B y² in the principal axes of the fit; `angle` (rad) from e1 to the A
    axis; `rms` of the residual (mm); the half-extents of the fitted patch (mm)."""

    curvature: RelativeCurvature
    rms: float
    extent: tuple[float, float]


def tangent_plane(pinion: Flank, frame: Frame, u: float, v: float) -> TangentPlane:
    s = pinion.evaluate(np.array([u]), np.array([v]))
    n = frame.vectors_to_world(s.normals[0])
    face = frame.vectors_to_world(s.r_v[0])
    e1 = face - np.dot(face, n) * n
    e1 /= np.linalg.norm(e1)
    return TangentPlane(frame.to_world(s.points[0]), n, e1, np.cross(n, e1))


def heights(flank: Flank, frame: Frame, plane: TangentPlane, x: np.ndarray, y: np.ndarray,
            guess: tuple[float, float]):
    """Distance t along the plane's normal from the plane point (x, y) to the flank, and
    whether the line meets the flank's surface (continued beyond its edges where it exists)."""
    points = plane.point + x[..., None] * plane.e1 + y[..., None] * plane.e2
    local = frame.to_local(points)
    direction = np.broadcast_to(frame.vectors_to_local(plane.normal), local.shape)
    hits = intersect(flank, local, direction, np.full(x.shape, guess[0]), np.full(x.shape, guess[1]))
    return hits.s, hits.converged


def fit_gap(pinion: Flank, gear: Flank, pinion_frame: Frame, gear_frame: Frame,
            plane: TangentPlane, pinion_uv, gear_uv, extent: tuple[float, float],
            n: int = 21) -> GapFit:
    """Least-squares fit of the gap on an n × n grid of half-extents `extent`, shrunk until
    the lines of the whole patch meet both surfaces (continued beyond the flank edges, where
    the contact may sit). The fit carries the cubic and quartic terms too, so that the
    flank's changing curvature does not leak into A and B; A and B are the quadratic part,
    diagonalised."""
    for _ in range(12):
        x, y = np.meshgrid(np.linspace(-extent[0], extent[0], n),
                           np.linspace(-extent[1], extent[1], n), indexing="ij")
        tp, in_p = heights(pinion, pinion_frame, plane, x, y, pinion_uv)
        tg, in_g = heights(gear, gear_frame, plane, x, y, gear_uv)
        if np.all(in_p & in_g):
            break
        extent = (0.7 * extent[0], 0.7 * extent[1])
    else:
        raise ValueError("the gap cannot be fitted here: the surfaces end (base circle)")
    h = (tg - tp).ravel()
    X, Y = x.ravel() / extent[0], y.ravel() / extent[1]
    powers = [(i, k - i) for k in range(5) for i in range(k + 1)]
    design = np.stack([X**i * Y**j for i, j in powers], axis=-1)
    coef, *_ = np.linalg.lstsq(design, h, rcond=None)
    rms = float(np.sqrt(np.mean((design @ coef - h) ** 2)))
    c = dict(zip(powers, coef))
    quad = np.array([[c[(2, 0)] / extent[0] ** 2, 0.5 * c[(1, 1)] / (extent[0] * extent[1])],
                     [0.5 * c[(1, 1)] / (extent[0] * extent[1]), c[(0, 2)] / extent[1] ** 2]])
    values, vectors = np.linalg.eigh(quad)
    angle = float(np.arctan2(vectors[1, 0], vectors[0, 0]))
    return GapFit(RelativeCurvature(A=float(values[0]), B=float(values[1]), angle=angle), rms,
                  extent)


def analytic_gap(pinion: Flank, gear: Flank, pinion_frame: Frame, gear_frame: Frame,
                 plane: TangentPlane, pinion_uv, gear_uv) -> RelativeCurvature:
    """A, B and the direction of A from the principal curvatures of both flanks (convex
    positive for each, along its own outward normal), expressed with `angle` from e1."""
    sp = pinion.evaluate(np.array([pinion_uv[0]]), np.array([pinion_uv[1]]))
    sg = gear.evaluate(np.array([gear_uv[0]]), np.array([gear_uv[1]]))
    kp1, kp2, dp1, _ = (np.asarray(x)[0] for x in sp.principal_curvatures())
    kg1, kg2, dg1, _ = (np.asarray(x)[0] for x in sg.principal_curvatures())
    dp1 = pinion_frame.vectors_to_world(dp1)
    dg1 = gear_frame.vectors_to_world(dg1)
    angle_p = np.arctan2(np.dot(dp1, plane.e2), np.dot(dp1, plane.e1))
    angle_g = np.arctan2(np.dot(dg1, plane.e2), np.dot(dg1, plane.e1))
    rc = relative_curvature((float(kp1), float(kp2)), (float(kg1), float(kg2)),
                            float(angle_g - angle_p), point_contact=False)
    return RelativeCurvature(rc.A, rc.B, float(angle_p + rc.angle))
