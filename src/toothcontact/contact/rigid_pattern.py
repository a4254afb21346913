"""The rigid contact pattern: where the unloaded flanks, placed at a contact, lie within a
chosen approach of each other (Litvin's 0.00632 mm by default), measured on the contact's
gap field: the pattern's extent along and across the contact and where it meets the flanks'
edges. Units: mm.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .field import GapField, contact_fields
from .local import face_length


@dataclass(frozen=True)
class RigidPattern:
    """One contact's rigid pattern measured on its separation field: the cells where the gap
    exceeds the contact's least separation by at most the approach, on both flanks'
    material. area (mm²); along_face and across_face (mm): its extents along e1 (the
    pinion's face direction) and e2 in the tangent plane, cell centres plus one cell;
    cut: a flank edge bounds it (a pattern cell next to no material). All None where no
    field on both flanks could be laid about the contact (UNMEASURED)."""

    area: float | None
    along_face: float | None
    across_face: float | None
    cut: bool | None


#: the rigid pattern of a contact about which no field meets both flanks (a worm wheel's
#: tip corner, whose rounding does not turn as far as the worm's flank)
UNMEASURED = RigidPattern(None, None, None, None)


def rigid_patterns(cycle, points: int, margin: float = 1.25, growths: int = 3) -> list[RigidPattern]:
    """The rigid pattern of every row of a contact cycle, each on a `points` × `points`
    separation field over the box of its rigid ellipse (both axes capped at the shorter
    member's face length: a worm's nearly conformal flanks make ellipses of metres)
    enlarged by `margin`; a field the pattern reaches the side of is enlarged 1.6
    times, up to `growths` times (where a grown batch cannot be followed on the flanks, each
    row is measured on the field it had). All rows' fields are solved in one batch. A row
    kept beyond the approach (rigid_contact false) has no pattern (zero); one about which
    no field meets both flanks is UNMEASURED."""
    from scipy.ndimage import binary_dilation

    rows, approach = cycle.rows, cycle.settings.approach
    # the shorter of the two members' faces (a worm's thread runs on for turns; the wheel's
    # face bounds its contact lines)
    face = np.minimum(*(face_length(getattr(cycle, m), (
        np.asarray(getattr(cycle.contacts, f"{m}_u")),
        np.asarray(getattr(cycle.contacts, f"{m}_v")))) for m in ("pinion", "gear")))
    # a contact line's box spans the face both ways: its part in contact may lie to one side
    semi_axes = np.array([[f if r["contact_model"] != "ellipse" else min(r["rigid_a_mm"], f),
                           min(r["rigid_b_mm"], f)] for r, f in zip(rows, face)])
    margins = np.full(len(rows), float(margin))
    out: list[RigidPattern | None] = [None if r.get("rigid_contact", True)
                                      else RigidPattern(0.0, 0.0, 0.0, False) for r in rows]
    todo = np.array([k for k in range(len(rows)) if out[k] is None], int)
    previous: dict[int, GapField] = {}
    for attempt in range(growths + 1):
        try:
            solved = contact_fields(cycle, todo, (points, points), margins[todo],
                                    semi_axes[todo], missing_ok=True)
        except ValueError:
            if attempt == 0:
                raise
            # a field grown past where its flanks can be followed (a worm's far turns):
            # each row keeps the field it had
            solved = [previous[k] for k in todo]
            attempt = growths
        for k, field in zip(todo, solved):
            if field is None:                    # no field on both flanks: not measured
                out[k] = UNMEASURED
                continue
            previous[k] = field
            below = rows[k]["separation_mm"] + approach - field.gap
            pattern = field.material & (below >= 0)
            rim = np.zeros(pattern.shape, bool)
            rim[[0, -1], :] = rim[:, [0, -1]] = True
            if (pattern & rim).any() and attempt < growths:
                continue
            share = np.minimum(field.material_share(), field.share(below))
            out[k] = _measure(field, share,
                              bool((pattern & binary_dilation(~field.material)).any()))
        todo = np.array([k for k in todo if out[k] is None], int)
        margins[todo] *= 1.6
        if todo.size == 0:
            break
    return out


def _measure(field: GapField, share: np.ndarray, cut: bool) -> RigidPattern:
    """Area and extents of a pattern given as each cell's share in it (0 to 1): the area
    the sum of the shares, an extent the sum over the grid lines across it of each line's
    largest share (for a pattern of whole cells: its cells, and its rows and columns)."""
    dx, dy = field.spacing
    return RigidPattern(float(share.sum() * dx * dy), float(share.max(axis=1).sum() * dx),
                        float(share.max(axis=0).sum() * dy), cut)
