"""The contact ellipse held against the flank's edges (docs/DESIGN.md principle 4).

The ellipse lies in the common tangent plane; each of its boundary points is carried onto a
flank along the common normal, and its parameters are compared with the flank's domain.
The margin to an edge is the least distance (mm, along the flank) from the ellipse to that
edge: the length of the parameter line from each carried boundary point to the edge (the
transverse profile for a tip or form edge, the face line for a face end), integrated
exactly; a negative margin means the ellipse is cut by the edge: edge loading.
"""

from __future__ import annotations

import numpy as np

from ..surfaces.base import Flank
from ..surfaces.placement import Frame
from .local import TangentPlanes
from .rays import intersect


def edge_margins(flank: Flank, frames: Frame, planes: TangentPlanes, a: np.ndarray,
                 b: np.ndarray, angle: np.ndarray, guess_u: np.ndarray, guess_v: np.ndarray,
                 samples: int = 72) -> dict[str, np.ndarray]:
    """Margins (mm) from K ellipses (semi-axes a along `angle` from e1, b across; (K,)
    arrays, frames stacked (K,)) to each of the flank's edges, named as in flank.edges;
    "beyond_surface" is -b where part of the ellipse lies where the flank surface does not
    exist (outside the region a hob generated), where its normal line meets the flank more
    than 0.5 mm from the tangent plane, or more than a domain's span beyond an edge, and
    NaN where the whole ellipse lies on the surface."""
    theta = np.linspace(0.0, 2.0 * np.pi, samples, endpoint=False)
    da = planes.direction(angle)
    db = np.cross(planes.normal, da)
    direction = frames.vectors_to_local(planes.normal[:, None, :])
    u = np.repeat(np.asarray(guess_u, float)[:, None], samples, axis=1)
    v = np.repeat(np.asarray(guess_v, float)[:, None], samples, axis=1)
    along = a[:, None, None] * np.cos(theta)[:, None] * da[:, None, :]
    across = b[:, None, None] * np.sin(theta)[:, None] * db[:, None, :]
    # march out from the contact point, each step starting where the last one landed, so
    # that the hits follow the flank here and not a far branch of a long surface
    for fraction in (0.25, 0.5, 0.75, 1.0):
        points = planes.point[:, None, :] + fraction * (along + across)
        hits = intersect(flank, frames.to_local(points), direction, u, v, iterations=40)
        u = np.where(hits.converged, hits.u, u)
        v = np.where(hits.converged, hits.v, v)
    (u0, u1), (v0, v1) = flank.domain
    u, v = np.nan_to_num(hits.u), np.nan_to_num(hits.v)
    margins = {
        flank.edges["u0"]: -arc_to_edge(flank, "u", u, u0, v),
        flank.edges["u1"]: arc_to_edge(flank, "u", u, u1, v),
        flank.edges["v0"]: -arc_to_edge(flank, "v", v, v0, u),
        flank.edges["v1"]: arc_to_edge(flank, "v", v, v1, u),
    }
    # a hit far off the tangent plane, or parameters more than a domain's span beyond its
    # edges, is another part of a long (continued) surface, not the flank here
    du, dv = u1 - u0, v1 - v0
    on = (hits.converged & np.isfinite(hits.u) & (np.abs(hits.s) < 0.5)
          & (hits.u > u0 - du) & (hits.u < u1 + du) & (hits.v > v0 - dv) & (hits.v < v1 + dv))
    out = {name: np.where(on.any(axis=-1), np.min(np.where(on, value, np.inf), axis=-1), -b)
           for name, value in margins.items()}
    out["beyond_surface"] = np.where(on.all(axis=-1), np.nan, -b)
    return out


#: Gauss-Legendre nodes and weights on [-1, 1] for the arc lengths along parameter lines
_NODES, _WEIGHTS = np.polynomial.legendre.leggauss(6)


#: beyond its edges a surface continued stands in for the flank where its speed stays
#: within this factor of the edge's (an involute past its tip); elsewhere (a generated
#: wheel past its face end and root, where the continuation grows without bound) the
#: edge's speed does
CONTINUATION_SPEED = 2.0


def arc_to_edge(flank: Flank, name: str, start: np.ndarray, end: float, other: np.ndarray) -> np.ndarray:
    """Signed length (mm) along the flank's `name` ("u" or "v") parameter line from `start`
    to the edge at `end`, the other parameter held at `other` (clamped to the flank's
    domain: a point beyond two edges at once is measured from the flank's nearest line):
    the integral of the line's speed, by 6-point Gauss-Legendre (the speed is smooth; an
    involute's is linear in its roll angle). Past the edge the surface continued stands in
    (see CONTINUATION_SPEED); where the surface does not exist on part of the line (beyond
    a hob's reach), the speed at the edge's side of the domain stands in for it."""
    (u0, u1), (v0, v1) = flank.domain
    low, high = (u0, u1) if name == "u" else (v0, v1)
    other = np.clip(other, *((v0, v1) if name == "u" else (u0, u1)))

    def speed_at(s, o):
        sample = flank.evaluate(*((s, o) if name == "u" else (o, s)), order=1)
        return np.linalg.norm(sample.r_u if name == "u" else sample.r_v, axis=-1)

    mid, half = 0.5 * (start + end), 0.5 * (end - start)
    t = mid[..., None] + half[..., None] * _NODES
    with np.errstate(all="ignore"):
        speed = speed_at(t, np.broadcast_to(other[..., None], t.shape))
        edge = speed_at(np.clip(start, low, high), other)[..., None]
    beyond = (t < low) | (t > high)
    speed = np.where(np.isfinite(speed) & ~(beyond & (speed > CONTINUATION_SPEED * edge)),
                     speed, edge)
    return half * (speed @ _WEIGHTS)
