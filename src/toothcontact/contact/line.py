"""Line contact: the contact line along the flanks, how much of it touches, and where the
flanks' edges cut it.

Where the gap around a contact is no bowl small enough for Hertz's ellipse (no crown, or one
so mild that the loaded ellipse would be longer than the face), the contact is a line: along
the direction of least relative curvature (the A axis) the gap stays within the approach of
the contact's separation over a length that may run to the face ends, the tip or the form
circle, or past them. A misalignment tilts the gap along the line, and the contact then
presses on the edge that the tilt closes: beyond it the gap would keep falling.

On a separation field aligned with the line (field.gap_fields: x along the A axis, over two
face lengths either side of the contact, the flanks continued beyond their edges) the rigid
contact line is the set of cells connected to the contact whose gap exceeds the contact's
separation by at most the approach; the part on both flanks' material is in contact, and its
extent along the line is the length in contact. Each edge of both flanks gets a margin (mm,
along the flank, exact arc length from the line's nearest cell to the edge):
- the line stays clear of the edge: its distance to the edge (> 0);
- the line runs on past the edge without pressing on it (the continued gap beyond stays at
  or above the contact's separation): 0, the line reaches the edge (a helical contact line
  ends at the tip and the form circle; an aligned uncrowned pair touches over the whole face);
- the line presses on the edge (the gap beyond it falls below the contact's separation):
  minus the length of the continued line beyond the edge, at most the face length: where it
  runs on farther (no crown turns it) the margin is minus the face length, the pattern would
  have to move by more than the face to clear the edge.
Units: mm.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..surfaces.base import Flank
from ..surfaces.placement import Frame
from .ellipse import arc_to_edge
from .field import FAR, GapField, gap_fields
from .local import TangentPlanes, planes_at
from .rays import intersect

#: the continued gap beyond an edge must fall this far (mm) below the contact's separation
#: for the line to press on the edge: far above the fields' spline error (1e-7 mm, up to
#: 5e-6 mm next to where the surfaces end), far below what a misalignment of 1e-6 rad
#: opens beyond an edge
PRESS = 1e-5
#: points across the line's field: the pattern is about 2·sqrt(approach/B) wide, a tenth of
#: the field's width or more
ACROSS_POINTS = 61


@dataclass(frozen=True)
class ContactLines:
    """The contact lines of K contacts: `length` (K,) in contact (mm); `width` (K,): the
    extent in contact across the line (mm, cells: a conformal contact's area is length ×
    width); `centre` (K, 2): the middle of the part in contact, in the plane coordinates
    (e1, e2) of each contact's tangent plane (mm from the contact point); `margins`: per
    contact, edge name -> margin (mm, see the module docstring)."""

    length: np.ndarray
    width: np.ndarray
    centre: np.ndarray
    margins: list[dict[str, float]]


def contact_lines(pinion: Flank, gear: Flank, pinion_frames: Frame, gear_frames: Frame,
                  planes: TangentPlanes, pinion_uv, gear_uv, angle: np.ndarray,
                  separation: np.ndarray, B: np.ndarray, face: np.ndarray, approach: float,
                  points: int) -> ContactLines:
    """The contact lines of K contacts (frames and planes stacked (K,), parameters, the A
    axis `angle` from e1 (rad), the separation (mm), B (1/mm) and the shorter flank's face
    length (mm), all (K,)), each measured at `approach` (mm) on a field of `points` points
    along the line. A contact whose field cannot be laid (field.gap_samples: its lines
    miss a flank) is not measured: NaN length, width and centre, no margins."""
    along = planes.direction(angle)
    aligned = TangentPlanes(planes.point, planes.normal, along, np.cross(planes.normal, along))
    half = np.stack([2.0 * face, 3.0 * np.sqrt(approach / B)], axis=-1)
    fields = gap_fields(pinion, gear, pinion_frames, gear_frames, aligned, pinion_uv, gear_uv,
                        half, (points, ACROSS_POINTS), missing_ok=True)
    cos, sin = np.cos(angle), np.sin(angle)
    domains = {f"{member}_{name}": limits for member, flank in (("pinion", pinion), ("gear", gear))
               for name, limits in zip(("u", "v"), flank.domain)}
    lengths, widths, centres, margins = [], [], [], []
    for k, field in enumerate(fields):
        if field is None:
            lengths.append(math.nan)
            widths.append(math.nan)
            centres.append((math.nan, math.nan))
            margins.append({})
            continue
        rel = field.gap - separation[k]
        cells, inside = _line_cells(field, rel, approach)
        if inside.any() and rel[inside].min() < 0.0:   # the least gap on the flanks is
            rel = rel - rel[inside].min()              # a little off the contact point
            cells, inside = _line_cells(field, rel, approach)
        # beyond the edges the line decides whether it presses on them: there the gap is
        # solved exactly (the splines may ring next to where a surface ends, e.g. at an
        # involute's cusp on its base circle)
        off = cells & ~field.material
        if off.any():
            rel = rel.copy()
            rel[off] = _exact_gaps(pinion, gear, pinion_frames[k], gear_frames[k],
                                   planes_at(aligned, [k]), field, off) - (field.gap - rel)[off]
            cells, inside = _line_cells(field, rel, approach)
        length, (x, y) = _length(field, rel, inside, approach, domains)
        lengths.append(length)
        across = field.y[np.nonzero(inside)[1]]
        widths.append(float(np.ptp(across)) + field.spacing[1] if across.size else 0.0)
        centres.append((x * cos[k] - y * sin[k], x * sin[k] + y * cos[k]))
        own = {}
        for member, flank in (("pinion", pinion), ("gear", gear)):
            own.update(_edge_margins(field, member, flank, cells, inside, rel, float(face[k])))
        margins.append(own)
    return ContactLines(np.array(lengths), np.array(widths), np.array(centres), margins)


def _exact_gaps(pinion: Flank, gear: Flank, pinion_frame: Frame, gear_frame: Frame,
                plane: TangentPlanes, field: GapField, cells: np.ndarray) -> np.ndarray:
    """The gap (mm) at the given cells of one contact's field, solved exactly (rays.py)
    from the field's own parameters there; NaN where a line does not meet a flank near
    the plane."""
    i, j = np.nonzero(cells)
    world = plane.point + field.x[i, None] * plane.e1 + field.y[j, None] * plane.e2
    heights = []
    for member, flank, frame in (("pinion", pinion, pinion_frame), ("gear", gear, gear_frame)):
        hits = intersect(flank, frame.to_local(world), frame.vectors_to_local(plane.normal),
                         field.parameters[f"{member}_u"][i, j],
                         field.parameters[f"{member}_v"][i, j])
        heights.append(np.where(hits.converged & (np.abs(hits.s) <= FAR), hits.s, np.nan))
    return heights[1] - heights[0]


def _line_cells(field: GapField, rel: np.ndarray, approach: float):
    """The cells of the rigid contact line (`rel`: the gap over the contact's separation; the
    cells connected to the contact within the approach, on the flanks continued beyond their
    edges) and those of them on both flanks' material."""
    from scipy.ndimage import label

    with np.errstate(invalid="ignore"):
        near = np.isfinite(rel) & (rel <= approach)
    labels, _ = label(near)
    centre = (field.gap.shape[0] // 2, field.gap.shape[1] // 2)
    if not near[centre]:  # the contact between cells: the closest cell of the line
        i, j = np.nonzero(near)
        if i.size == 0:
            return near, near
        nearest = np.argmin((i - centre[0]) ** 2 + (j - centre[1]) ** 2)
        centre = (i[nearest], j[nearest])
    cells = labels == labels[centre]
    return cells, cells & field.material


def _length(field: GapField, rel: np.ndarray, inside: np.ndarray, approach: float,
            domains: dict[str, tuple[float, float]]):
    """The length in contact (mm) along the line (x) and the middle of that part (x, y; mm):
    from the first to the last column of the line's cells on material, each end carried to
    where the line's least gap reaches the approach (linear between the columns), or where
    the material ends: where a flank parameter on the line's row (`domains`: each
    parameter's range, by the field's parameter names) reaches its edge; one cell (dx) at
    least."""
    columns = np.flatnonzero(inside.any(axis=1))
    dx, _ = field.spacing
    if columns.size == 0:   # the contact on an edge, no cell of the line on material
        return float(dx), (0.0, 0.0)
    # per column the least gap on material; in the line's end columns a cell on a flank
    # edge counts by its share of material (raised by approach·(1/share - 1)), so that the
    # end moves continuously when an edge runs along a row of cells, as it does beside a
    # conformal contact
    share = field.material_share()
    with np.errstate(invalid="ignore", divide="ignore"):
        on = np.where(inside, rel, np.inf)
        least = np.min(np.where(field.material, rel, np.inf), axis=1)
        smooth = np.min(np.where(share > 0, rel + approach * (1.0 / share - 1.0), np.inf),
                        axis=1)
    ends = []
    for end, outward in ((columns[0], -1), (columns[-1], 1)):
        beyond, row = end + outward, int(np.argmin(on[end]))
        if not 0 <= beyond < len(least):
            ends.append(0.5 * dx)
        elif np.isfinite(least[beyond]) and least[beyond] > smooth[end]:
            ends.append(dx * float(np.clip((approach - smooth[end])
                                           / (least[beyond] - smooth[end]), 0.0, 1.0)))
        else:                   # the material ends: where the first parameter crosses its edge
            fractions = [1.0]
            for name, (low, high) in domains.items():
                a, b = field.parameters[name][end, row], field.parameters[name][beyond, row]
                for limit in (low, high):
                    if (a - limit) * (b - limit) < 0:
                        fractions.append((limit - a) / (b - a))
            ends.append(dx * float(min(fractions)))
    low, high = field.x[columns[0]] - ends[0], field.x[columns[-1]] + ends[1]
    y = float(np.mean(field.y[np.nonzero(inside)[1]]))
    # a line in contact on one column whose least gap there already passes the approach
    # (both ends carried to 0) is as long as the field resolves: a cell, as on an edge
    # (a length of 0 gave its Hertz line an infinite pressure)
    return max(float(high - low), float(dx)), (0.5 * float(low + high), y)


def _edge_margins(field: GapField, member: str, flank: Flank, cells, inside, rel,
                  face: float) -> dict[str, float]:
    """The margins of one flank's four edges (see the module docstring). Beyond a face end
    (v) the line runs on along itself; beyond a profile edge (u: tip, form, root) it lies
    beside its part in contact, in the same columns: only there does it count."""
    rim = np.zeros(cells.shape, bool)
    rim[[0, -1], :] = True                            # the field's ends along the line
    columns = inside.any(axis=1)[:, None]
    out = {}
    for name, other, (low, high) in (("u", "v", flank.domain[0]), ("v", "u", flank.domain[1])):
        value = field.parameters[f"{member}_{name}"]
        fixed = field.parameters[f"{member}_{other}"]
        near = cells if name == "v" else cells & columns
        for key, limit, sign in ((name + "0", low, -1.0), (name + "1", high, 1.0)):
            inward = sign * (limit - value)           # parameter distance inside the edge
            beyond = near & (inward < 0)
            edge = f"{member}_{flank.edges[key]}"
            if not beyond.any():
                if not inside.any():
                    continue
                candidates = inside                   # the line's nearest cell to the edge
            elif rel[beyond].min() >= -PRESS:
                out[edge] = 0.0                       # runs on past the edge, not pressing
                continue
            elif name == "v" and (beyond & rim).any():
                out[edge] = -face                     # runs on farther than the field shows
                continue
            else:
                candidates = beyond                   # the line's farthest cell beyond
            cell = np.unravel_index(np.argmin(np.where(candidates, inward, np.inf)), cells.shape)
            arc = sign * float(arc_to_edge(flank, name, np.array([value[cell]]), limit,
                                           np.array([fixed[cell]]))[0])
            out[edge] = max(arc, -face)
    return out
