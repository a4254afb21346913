"""What a solved contact says about the flanks' edges: its result keys (summarise), the load
in the strip at a face end against the contact's mean (end_load_ratio), the pressure at a
tip, root or form edge against the flank's own peak, corner contacts, a tip rounding's own
contact, and where the flanks' edges and kinks lie (edge_breaks).

The pressure at a sharp face end is singular: the raw peak grows as the grid is refined. The
edge is therefore reported as the pressure averaged over a strip `EDGE_STRIP` wide at the
edge (mm; pressure.ContactSolution.edge_loads), with the share of the load in that strip.
A rounded tip (surfaces.modify.TipEdge) is a smooth surface: its edge is the rounding
itself, its pressure the largest on it (Hertz on the rounding's radius), apart from the
active flank's. Units: mm, N, MPa.
"""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass

import numpy as np

from .field import GapField, is_face_end
from .pressure import ContactSolution, EdgeLoad
from .structure import FaceLoad

#: width (mm) of the strip at an edge over which the edge pressure is averaged
EDGE_STRIP = 0.1
#: a contact is end-loaded when its load per mm of face in the strip at a face end exceeds
#: END_LOAD_RATIO times its mean load per mm of face over its length in contact: the end
#: carries more than its share, as under a crown too mild for the misalignment or an
#: uncrowned face tilted onto its end. Two members ending flush and aligned carry
#: 0.7-0.8 of the mean at their free ends (3D finite elements, tests/test_free_end.py):
#: not end-loaded; a pattern cut at its middle by the end carries 1.3-1.5.
END_LOAD_RATIO = 1.0
#: a contact is edge-loaded at a tip, root or form edge when its pressure averaged over the
#: strip there exceeds EDGE_PRESSURE_RATIO times its peak more than EDGE_STRIP inside every
#: edge: the edge raises the pressure (a corner contact), not a contact that merely
#: reaches it while relieved
EDGE_PRESSURE_RATIO = 1.0
#: a contact carrying less than this share of its position's load is judged by neither
#: criterion (a pair just touching at a corner, a few newtons of thousands: its ratios say
#: nothing about the design; its pressure stays in bem_p_max_MPa)
EDGE_LEAST_SHARE = 0.02

#: the result keys of a loaded contact (LoadedContact.summary); a row without a solution
#: carries them as None, with bem_status "unloaded" (the other pairs of its position carry
#: the load) or "failed" and the reason in bem_reason
RESULT_KEYS = ("bem_status", "bem_load_N", "bem_p_max_MPa", "flank_p_max_MPa", "edge_loaded",
               "end_loaded", "corner_contact", "corner_pressure_MPa", "corner_load_N",
               "corner_at", "end_load_ratio", "edge_load_ratio", "bem_area_mm2",
               "bem_approach_mm", "bem_grid", "edge_pressure_MPa", "edge_load_fraction",
               "edge_pressure_at", "edge_strip_mm", "bem_raw_peak_MPa", "bem_iterations",
               "bem_relative_error", "bem_reason")


def unsolved(status: str, reason: str | None = None) -> dict:
    """The result keys of a row without a loaded solution (see RESULT_KEYS): "unloaded"
    carries nothing (zero load, pressure and area), "failed" is not known (None)."""
    row = dict.fromkeys(RESULT_KEYS)
    if status == "unloaded":
        row.update(bem_load_N=0.0, bem_p_max_MPa=0.0, flank_p_max_MPa=0.0, bem_area_mm2=0.0,
                   edge_pressure_MPa=0.0,
                   edge_load_fraction=0.0, edge_loaded=False, end_loaded=False,
                   corner_contact=False, corner_pressure_MPa=0.0, corner_load_N=0.0,
                   end_load_ratio=0.0, edge_load_ratio=None)
    return {**row, "bem_status": status, "bem_reason": reason}


@dataclass(frozen=True)
class LoadedContact:
    """One contact's loaded solution: its gap field, the pressure on it, its result keys
    (`summary`: see :func:`summarise`, computed where the contact was solved) and where its
    cells sit along each member's face and at what load radius (the driver's, then the
    driven member's; empty without a tooth model)."""

    field: GapField
    solution: ContactSolution
    summary: dict
    faces: tuple[FaceLoad, ...] = ()

    def line_load(self, edges: np.ndarray) -> np.ndarray | None:
        """The contact's mean load per unit face width (N/mm) on the strips of the pinion's
        face between `edges` (mm from mid-face); None without a tooth model."""
        if not self.faces:
            return None
        return self.faces[0].line_load(self.solution.pressure_MPa, edges)


def summarise(field: GapField, s: ContactSolution, position_load: float | None = None,
              breaks: EdgeBreaks | None = None) -> dict:
    """The result keys of a loaded contact (RESULT_KEYS); the most loaded edge is named by
    the flank edge it is (e.g. "gear_tip", "pinion_end_B"). Where the material runs on to
    the field's border there is no edge (the contact never reaches that border: the solver
    widens the field until it does not); with no flank edge in the field the edge keys are
    zero and edge_pressure_at is "none". end_load_ratio: the largest over the face ends of
    the load per mm of face in the end's strip over the contact's mean (END_LOAD_RATIO);
    edge_loaded: end-loaded, or a tip, root or form edge pressed harder than the contact's
    interior (EDGE_PRESSURE_RATIO); neither for a contact carrying less than
    EDGE_LEAST_SHARE of `position_load` (N; None: the contact's own load). `breaks` (the
    members' tip roundings and chamfers, and their face-end chamfers): a broken tip's edge
    is its rounding (or the chamfer's rounded edge) itself, its pressure the largest on it
    (a smooth surface's, converged on the grid), not a strip's at the tip circle; a
    chamfered face end's likewise, its end load ratio taken over the last EDGE_STRIP of
    the flank before the chamfer's rounded edge and that edge; the interior peak
    (flank_p_max_MPa) is the active flank's more than EDGE_STRIP inside its edges, the
    roundings' starts among them: what a lead crown sizes, apart from the edges' pressures
    (a corner contact on a rounding spills past its start onto the involute)."""
    breaks = breaks or EdgeBreaks()
    if breaks.curved:
        return _summarise_crossed(field, s, position_load, breaks)
    on_break = {**tip_roundings(field, breaks.roundings),
                **chamfered_ends(field, breaks.chamfers)}
    # a chamfered end's edge load: on its rounded edge and the last strip of flank before it
    at_break = {**on_break, **chamfered_ends(field, breaks.chamfers, EDGE_STRIP)}
    # a tip, root or form edge named before a face end: a contact along a tip presses the
    # face ends' strips as hard where it reaches them
    rounded = [(n, _rounding_load(field, n, on, s, patch=is_face_end(n)))
               for n, on in at_break.items()]
    named = sorted([(n, e) for n, e in flank_edges(field, s) if n not in on_break]
                   + [(n, e) for n, e in rounded if e.load_N > 0],
                   key=lambda item: is_face_end(item[0]))
    highest = max((e.edge_pressure_MPa for _, e in named), default=0.0)
    name, worst = next(((n, e) for n, e in named if e.edge_pressure_MPa >= (1 - 1e-3) * highest),
                       ("none", None))
    edge_pressure = worst.edge_pressure_MPa if worst is not None and worst.load_N > 0 else 0.0
    footprints = corner_footprints(field, s, tip_roundings(field, breaks.roundings))
    interior = _interior_peak(field, s, list(on_break.values()) + list(footprints.values()))
    end_ratio = max((end_load_ratio(
        field, s, member, end, breaks.chamfers.get(member),
        None if member not in breaks.faces else (position_load or s.load_N) / breaks.faces[member])
        for member in ("pinion", "gear") for end in "AB"), default=0.0)
    profile = [(n, e) for n, e in named if not is_face_end(n) and e.load_N > 0
               and e.edge_pressure_MPa > EDGE_PRESSURE_RATIO * interior]
    judged = s.load_N >= EDGE_LEAST_SHARE * (position_load or s.load_N)
    end_loaded = bool(judged and end_ratio > END_LOAD_RATIO)
    profile = profile if judged else []
    corner, corner_edge = max(profile, key=lambda item: item[1].edge_pressure_MPa,
                              default=("none", None))
    corner_load = (0.0 if corner_edge is None else
                   float(s.pressure_MPa[footprints[corner]].sum()) * s.dx_mm * s.dy_mm
                   if corner in footprints else corner_edge.load_N)
    return {"bem_status": "solved", "bem_load_N": s.load_N,
            "bem_p_max_MPa": max(interior, edge_pressure), "flank_p_max_MPa": interior,
            "edge_loaded": bool(profile) or end_loaded,
            "end_loaded": end_loaded, "corner_contact": bool(profile),
            "corner_pressure_MPa": 0.0 if corner_edge is None else corner_edge.edge_pressure_MPa,
            "corner_load_N": corner_load, "corner_at": corner,
            "end_load_ratio": float(end_ratio), "edge_load_ratio": None,
            "bem_area_mm2": s.area_mm2, "bem_approach_mm": s.approach_mm,
            "bem_grid": list(s.pressure_MPa.shape),
            "edge_pressure_MPa": edge_pressure,
            "edge_load_fraction": worst.load_fraction if worst is not None else 0.0,
            "edge_pressure_at": name, "edge_strip_mm": EDGE_STRIP,
            "bem_raw_peak_MPa": s.peak_pressure_MPa, "bem_iterations": s.iterations,
            "bem_relative_error": s.relative_error, "bem_reason": None}


#: a contact whose load lies within this distance (mm) of a tip, root or form edge of a
#: curved line's flank (or on its rounding) touches there alone: a corner contact
CORNER_REACH = 2.0 * EDGE_STRIP


def _summarise_crossed(field: GapField, s: ContactSolution, position_load: float | None,
                       breaks: EdgeBreaks) -> dict:
    """summarise for contact lines that curve and cross the flanks' edges (a worm set's,
    breaks.curved): each edge is judged by its load share, the line load in the strip at
    the edge (its rounding or chamfer included) over the line's mean (line_load_ratio): a
    face end's is its end_load_ratio, end-loaded above END_LOAD_RATIO; a tip, root or form
    edge pressed above that ratio, or a contact lying within CORNER_REACH of such an edge
    alone (a pair touching only there), is a corner contact. The pressures keep their
    meanings: the edge's (a rounding's resolved peak, a sharp edge's strip mean), the
    flank's more than EDGE_STRIP inside its edges and off the roundings."""
    edges = crossed_edges(field, breaks)
    rounded = {**tip_roundings(field, breaks.roundings), **chamfered_ends(field, breaks.chamfers)}
    loads = {name: _rounding_load(field, name, on, s, patch=is_face_end(name))
             for name, on in rounded.items()}
    for name, edge in flank_edges(field, s):
        if name in edges and name not in loads:
            loads[name] = edge
    ratios = {name: line_load_ratio(field, s, mask) for name, mask in edges.items()}
    interior = _interior_peak(field, s, list(rounded.values()))
    judged = s.load_N >= EDGE_LEAST_SHARE * (position_load or s.load_N)
    ends = {n: r for n, (r, _) in ratios.items() if is_face_end(n)}
    profile = {n: r for n, (r, _) in ratios.items() if not is_face_end(n)}
    alone = [n for n, (_, reach) in ratios.items()
             if not is_face_end(n) and reach < CORNER_REACH]
    end_ratio = max(ends.values(), default=0.0)
    overloaded = [n for n, r in profile.items() if r > END_LOAD_RATIO]
    corner_edges = sorted(set(alone + overloaded), key=lambda n: -profile.get(n, 0.0))
    corner = corner_edges[0] if judged and corner_edges else "none"
    end_loaded = bool(judged and end_ratio > END_LOAD_RATIO)
    worst = max(((n, e) for n, e in loads.items() if e.load_N > 0),
                key=lambda item: item[1].edge_pressure_MPa, default=("none", None))
    edge_pressure = 0.0 if worst[1] is None else worst[1].edge_pressure_MPa
    corner_load = loads[corner] if corner in loads else None
    return {"bem_status": "solved", "bem_load_N": s.load_N,
            "bem_p_max_MPa": max(interior, edge_pressure), "flank_p_max_MPa": interior,
            "edge_loaded": end_loaded or corner != "none", "end_loaded": end_loaded,
            "corner_contact": corner != "none",
            "corner_pressure_MPa": 0.0 if corner_load is None else corner_load.edge_pressure_MPa,
            "corner_load_N": 0.0 if corner_load is None else corner_load.load_N,
            "corner_at": corner, "end_load_ratio": float(end_ratio),
            "edge_load_ratio": float(max(profile.values(), default=0.0)),
            "bem_area_mm2": s.area_mm2, "bem_approach_mm": s.approach_mm,
            "bem_grid": list(s.pressure_MPa.shape),
            "edge_pressure_MPa": edge_pressure,
            "edge_load_fraction": 0.0 if worst[1] is None else worst[1].load_fraction,
            "edge_pressure_at": worst[0], "edge_strip_mm": EDGE_STRIP,
            "bem_raw_peak_MPa": s.peak_pressure_MPa, "bem_iterations": s.iterations,
            "bem_relative_error": s.relative_error, "bem_reason": None}


def crossed_edges(field: GapField, breaks: EdgeBreaks) -> dict[str, np.ndarray]:
    """The flank edges in a field as the cells beyond each ("gear_tip" -> bool mask): those
    the field crosses (field.beyond, less where a surface does not exist), a broken edge's
    rounding or chamfer added to its own (tip_roundings, chamfered_ends)."""
    edges = {name: beyond.copy() for name, beyond in field.beyond.items()
             if name != "beyond_surface"}
    for name, on in {**tip_roundings(field, breaks.roundings),
                     **chamfered_ends(field, breaks.chamfers)}.items():
        edges[name] = edges[name] | on if name in edges else on.copy()
    return {name: mask for name, mask in edges.items() if mask.any()}


#: an edge's line load is judged against the line's over this length (mm) inside the
#: strip at it (line_load_ratio)
EDGE_NEIGHBOURHOOD = 1.0


def line_load_ratio(field: GapField, s: ContactSolution, edge: np.ndarray
                    ) -> tuple[float, float]:
    """(ratio, reach): a contact's line load in the strip within EDGE_STRIP of an edge (two
    cells where they are longer: `edge` the cells beyond it, or on its rounding, themselves
    in the strip) over the line's mean over the next EDGE_NEIGHBOURHOOD inward (over the
    whole line where it is shorter), and the farthest its load lies from the edge (mm; 0
    for none). The line is followed through strips of that width by distance from the
    edge: its length in each is
    the distance between the load's centroids in the strips beside it (half of each; a
    straight line's segment in the strip, whatever its angle to the edge, and a curved
    line's chord), or, where the load lies in fewer than three strips, its loaded cells'
    extent along their principal axis. Judged against its neighbourhood, the ratio is the
    edge's own effect (a sharp edge raising the load, a free end or a rounding relieving
    it), not the line's trend: a worm wheel's line running from near its root at the face
    ends to near its tip mid-face carries twice its mean at the ends, the teeth stiffer
    there, with no edge effect at all."""
    from scipy.ndimage import distance_transform_edt

    loaded = s.pressure_MPa > 0.0
    if not loaded.any():
        return 0.0, 0.0
    # a strip of at least two cells: an oblique end's staircase decides nothing finer
    width = max(EDGE_STRIP, 2.0 * max(field.spacing))
    distance = distance_transform_edt(~edge, sampling=field.spacing)[loaded]
    strips = np.floor(distance / width).astype(int)
    weights = s.pressure_MPa[loaded]
    X, Y = np.meshgrid(field.x, field.y, indexing="ij")
    points = np.stack([X[loaded], Y[loaded]], axis=-1)
    reach = float(distance.max())
    if strips.min() > 0:
        return 0.0, reach
    used = np.unique(strips)
    load = np.array([weights[strips == k].sum() for k in used])
    if len(used) < 3:
        lengths = np.array([_principal_extent(points[strips == k], field.spacing)
                            for k in used])
    else:
        centroid = np.array([np.average(points[strips == k], axis=0,
                                        weights=weights[strips == k]) for k in used])
        step = np.linalg.norm(np.diff(centroid, axis=0), axis=1)
        lengths = 0.5 * (np.concatenate([step, step[-1:]]) + np.concatenate([step[:1], step]))
    lengths = np.maximum(lengths, min(field.spacing))
    near = (used > 0) & (used <= max(round(EDGE_NEIGHBOURHOOD / width), 1))
    if not near.any():
        near = np.ones_like(near)
    return float((load[0] / lengths[0]) / (load[near].sum() / lengths[near].sum())), reach


def _principal_extent(points: np.ndarray, spacing) -> float:
    """The extent (mm) of cell centres `points` (n, 2) along their principal axis, a cell
    added."""
    if len(points) < 2:
        return float(min(spacing))
    centred = points - points.mean(axis=0)
    _, vectors = np.linalg.eigh(centred.T @ centred)
    along = centred @ vectors[:, -1]
    return float(np.ptp(along)) + float(min(spacing))


def corner_footprints(field: GapField, s: ContactSolution, roundings: dict[str, np.ndarray]
                      ) -> dict[str, np.ndarray]:
    """Each loaded tip rounding's footprint ("gear_tip" -> bool mask): the rounding and the
    contact's cells within twice its band width of it (its loaded width across its longer
    axis, the median over its lines; at least EDGE_STRIP): a corner contact on the rounding
    presses the involute beside it over its own width, a pair entering mesh early along a
    band next to the rounding (premature contact off the path of contact, issue 51); the
    flank's own pressure lies beyond."""
    from scipy.ndimage import distance_transform_edt

    out = {}
    loaded = field.material & (s.pressure_MPa > 0.0)
    if not loaded.any():
        return out
    across = 1 if loaded.shape[0] >= loaded.shape[1] else 0
    counts = loaded.sum(axis=across)
    band = float(np.median(counts[counts > 0])) * field.spacing[across]
    for name, on in roundings.items():
        if not (on & loaded).any():
            continue
        near = distance_transform_edt(~on, sampling=field.spacing) <= max(2.0 * band,
                                                                           EDGE_STRIP)
        out[name] = field.material & (on | (near & loaded))
    return out


def tip_roundings(field: GapField, roundings: dict[str, tuple[float, float]]
                  ) -> dict[str, np.ndarray]:
    """The cells on each member's tip edge rounding ("pinion_tip" -> bool mask): its roll
    angle u beyond the rounding's start (`roundings`: member -> (start, +1 or -1 toward the
    tip)), on material."""
    return {f"{member}_tip": field.material & ((field.parameters[f"{member}_u"] - start)
                                                * toward > 0.0)
            for member, (start, toward) in roundings.items()}


def _rounding_load(field: GapField, name: str, on: np.ndarray, s: ContactSolution,
                   patch: bool = False) -> EdgeLoad:
    """A broken edge's load (on `on`) as an edge load: its load and share, its largest pressure
    more than EDGE_STRIP from the material's other edges (where it meets a face end, the
    end's strip measures the corner: a sharp edge's pressure there does not converge); with
    `patch`, the largest mean over EDGE_STRIP × EDGE_STRIP of material (an end chamfer's
    rounded edge runs along a line field's long cells, which do not resolve its peak)."""
    from scipy.ndimage import uniform_filter

    p = np.where(on, s.pressure_MPa, 0.0)
    load = float(p.sum()) * s.dx_mm * s.dy_mm
    if patch:
        size = [max(1, round(EDGE_STRIP / step)) for step in field.spacing]
        held = uniform_filter(field.material.astype(float), size, mode="constant")
        mean = uniform_filter(np.where(field.material, s.pressure_MPa, 0.0), size,
                              mode="constant")
        p = np.where(on, np.divide(mean, held, out=np.zeros_like(mean), where=held > 0), 0.0)
    beyond_tip = field.beyond.get(name, np.zeros_like(on))
    inner = np.where(_inside_strip(field.material | beyond_tip, p > 0.0, field.spacing), p, 0.0)
    peak = float(inner.max()) if inner.size else 0.0
    return EdgeLoad(1, "high", 0.0, peak, float(s.pressure_MPa[on].max()) if on.any() else 0.0,
                    load, load / s.load_N if s.load_N else 0.0,
                    int(np.unravel_index(inner.argmax(), inner.shape)[0]))


@dataclass(frozen=True)
class EdgeBreaks:
    """The broken edges of a cycle's flanks: `roundings` (member -> (the roll angle where
    its tip edge's rounding starts, +1 or -1 toward the tip)) and `chamfers` (member -> the
    face position, mm from mid-face either way, where its end chamfer's rounded edge
    starts); and where each member's modifications bend its flank (`kinks`: member ->
    (roll angles, rad, of its profile_breaks; face positions, mm, of its lead_breaks)):
    relief starts, roundings' and chamfers' ends."""

    roundings: dict = dataclasses.field(default_factory=dict)
    chamfers: dict = dataclasses.field(default_factory=dict)
    kinks: dict = dataclasses.field(default_factory=dict)
    #: member -> its face width (mm): a face end's load per mm is judged against its
    #: position's load spread over it
    faces: dict = dataclasses.field(default_factory=dict)
    #: whether the contact lines curve and cross the edges (a worm set's): its edges are
    #: judged by the line load along the line (line_load_ratio), not per mm of face
    curved: bool = False


def edge_breaks(cycle) -> EdgeBreaks:
    """The tip roundings (or chamfers) and end chamfers of a cycle's members (those
    without one left out), from each flank's own breaks (Flank.breaks)."""
    roundings, chamfers, kinks, faces = {}, {}, {}, {}
    for member in ("pinion", "gear"):
        flank = getattr(cycle, member)
        gear = getattr(getattr(flank, "base", flank), "gear", None)
        if isinstance(getattr(gear, "face_width", None), float):
            faces[member] = gear.face_width
        broken = flank.breaks()
        if broken.rounding is not None:
            roundings[member] = broken.rounding
        if broken.chamfer is not None:
            chamfers[member] = broken.chamfer
        if broken.profile_kinks or broken.lead_kinks:
            kinks[member] = (np.array(broken.profile_kinks), np.array(broken.lead_kinks))
    return EdgeBreaks(roundings, chamfers, kinks, faces, curved_lines(cycle))


def chamfered_ends(field: GapField, chamfers: dict[str, float], before: float = 0.0
                   ) -> dict[str, np.ndarray]:
    """The cells on each member's end chamfers' rounded edges and beyond, and `before` (mm)
    ahead of them ("pinion_end_B" -> bool mask), on material (`chamfers`: member -> where
    the rounding starts, mm from mid-face either way)."""
    return {f"{member}_end_{end}": field.material & (sign * field.parameters[f"{member}_v"]
                                                     > start - before)
            for member, start in chamfers.items() for end, sign in (("A", -1.0), ("B", 1.0))}


def end_load_ratio(field: GapField, s: ContactSolution, member: str, end: str,
                   chamfer: float | None = None, mean: float | None = None) -> float:
    """A face end's load ratio (END_LOAD_RATIO): the load per mm of face in the last
    EDGE_STRIP of the member's flank before its end `end` ("A" or "B") over `mean` (N per mm
    of face: its position's load over the face width, the share the end would carry of an
    even spread), or without one over the contact's mean load per mm of face over its extent
    in contact; 0 where the end is not in the field. With a `chamfer` (where its rounded
    edge starts, mm from mid-face either way) the strip is the last EDGE_STRIP before that
    start, and the stretch of the contact beyond it, on the rounded edge (the stretch its
    loaded cells cover wholly: within a cell, where the contact ends is not known), is added
    to the strip's width.

    Distances along the face are the member's own (its face coordinate's distance from the
    end over that coordinate's gradient in the field's plane, mm), whatever the field's
    axes: a field laid along a helical contact line, or a worm wheel's, whose material
    boundary on one side of the grid mixes face end, tip and root. Each cell counts by its
    share in the strip (as GapField.share), so that the measure does not jump as the end
    crosses cell centres; a sharp end's strip is as wide as its cells' area over the
    material's length along the end (taken on the next strip inward): where a staircase end
    leaves whole cells past the end, the solver's body, made of those cells, runs on past
    it too."""
    name = f"{member}_end_{end}"
    loaded = s.pressure_MPa > 0.0
    if (chamfer is None and name not in field.inside) or not loaded.any():
        return 0.0
    dx, dy = field.spacing
    sign = 1.0 if end == "B" else -1.0
    # the face coordinate's distance inside the end (or the chamfer's start), in its units
    within = (chamfer - sign * field.parameters[f"{member}_v"] if chamfer is not None
              else field.inside[name])
    # the contact's extent along the face: from its loaded cell nearest the end to the one
    # farthest from it, each cell whole
    cells = np.flatnonzero(loaded)
    values = within.ravel()[cells]
    extremes = np.unravel_index(cells[[values.argmin(), values.argmax()]], within.shape)
    (nearest, farthest), (reach_in, reach_out), slope = _face_distance(within, extremes, (dx, dy))
    if nearest - reach_in >= EDGE_STRIP:            # no loaded cell reaches the strip
        return 0.0
    extent = float((farthest + reach_out) - (nearest - reach_in))
    on_edge = max(-float(nearest + reach_in), 0.0)   # the loaded cells wholly on a rounding
    # the cells the strip and the band inward of it may hold: within three strips and a
    # cell of the end (in the coordinate's units, at twice its gradient at the contact)
    reaches = 2.0 * float(slope.max()) * (3.0 * EDGE_STRIP + dx + dy)
    near = np.nonzero(field.material & (within < reaches))
    if not near[0].size:
        return 0.0
    distance, reach, _ = _face_distance(within, near, (dx, dy))
    # where the other member's face ends first, the strip starts at its end (the material's)
    start = max(float((distance - reach).min()), 0.0)
    if start >= EDGE_STRIP:
        return 0.0

    def before(limit: float) -> np.ndarray:     # each cell's share at distances below limit
        return np.clip(0.5 + (start + limit - distance)
                       / np.where(reach > 0.0, 2.0 * reach, 1.0), 0.0, 1.0)

    strip = before(EDGE_STRIP)
    if chamfer is not None:       # and the stretch of the rounding loaded cells cover wholly
        width = EDGE_STRIP + on_edge
    else:
        along_end = float((before(2.0 * EDGE_STRIP) - strip).sum()) * dx * dy / EDGE_STRIP
        width = float(strip.sum()) * dx * dy / along_end if along_end > 0.0 else 0.0
    if width <= 0.0:
        return 0.0
    load = float((s.pressure_MPa[near] * strip).sum()) * dx * dy
    return (load / width) / (mean or s.load_N / max(extent, EDGE_STRIP))


def _face_distance(within: np.ndarray, cells: tuple[np.ndarray, np.ndarray],
                   spacing: tuple[float, float]) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """At `cells` (index arrays) of a field, a coordinate's distance (mm in the field's
    plane) from where `within` (its value less its bound) is zero, half a cell's extent
    along it (mm) and its gradient's size (its units per mm): `within` over that gradient
    (central differences; one-sided at the field's borders)."""
    gradient = []
    for axis, step in enumerate(spacing):
        index = cells[axis]
        ahead = np.minimum(index + 1, within.shape[axis] - 1)
        behind = np.maximum(index - 1, 0)
        forward, backward = list(cells), list(cells)
        forward[axis], backward[axis] = ahead, behind
        gradient.append((within[tuple(forward)] - within[tuple(backward)])
                        / (np.maximum(ahead - behind, 1) * step))
    slope = np.hypot(*gradient)
    slope = np.where(slope > 0.0, slope, 1.0)
    reach = 0.5 * (np.abs(gradient[0]) * spacing[0] + np.abs(gradient[1]) * spacing[1]) / slope
    return within[cells] / slope, reach, slope


def flank_edges(field: GapField, s: ContactSolution) -> list[tuple[str, EdgeLoad]]:
    """The loads at the flank edges in a contact's field (pressure.EdgeLoad over the
    EDGE_STRIP, each named by the flank edge it is at; the field's own borders left out)."""
    named = [(_edge_name(field, edge), edge) for axis in (0, 1)
             for edge in s.edge_loads(axis, EDGE_STRIP)]
    return [(name, edge) for name, edge in named if not name.startswith("field_")]


def _edge_name(field: GapField, edge: EdgeLoad) -> str:
    """The flank edge an edge load (pressure.EdgeLoad) is at: the one beyond the last
    material cell of its grid line; named by the field's side ("field_x_low", ...) where
    the material reaches the field's border."""
    material = field.material if edge.axis == 0 else field.material.T
    line = material[:, edge.line_index]
    cells = np.flatnonzero(line)
    if cells.size:
        outside = cells[0] - 1 if edge.side == "low" else cells[-1] + 1
        if 0 <= outside < line.size:
            index = (outside, edge.line_index) if edge.axis == 0 else (edge.line_index, outside)
            for name, beyond in field.beyond.items():
                if beyond[index]:
                    return name
    return f"field_{'xy'[edge.axis]}_{edge.side}"


def _interior_peak(field: GapField, s: ContactSolution, roundings=()) -> float:
    """The largest pressure (MPa) on the active flank more than EDGE_STRIP inside its edges:
    those of the material and of the cells left out (`roundings`: bool masks of the tip
    roundings, the chamfers' edges and the corner contacts' footprints). With the edge
    pressures, the peak that converges as the grid is refined (the pressure in a cell at a
    sharp edge does not)."""
    active = field.material.copy()
    for on in roundings:
        active &= ~on
    p = s.pressure_MPa
    inside = _inside_strip(active, active & (p > 0.0), field.spacing)
    return float(p[inside].max()) if inside.any() else 0.0


def _inside_strip(keep: np.ndarray, cells: np.ndarray, spacing) -> np.ndarray:
    """The `cells` (bool grid) more than EDGE_STRIP from every cell outside `keep` (bool
    grid, cells dx × dy mm): the distance transform on the box about them only, widened by
    more than the strip (no cell farther out can be within it)."""
    from scipy.ndimage import distance_transform_edt

    out = np.zeros_like(cells)
    if not cells.any():
        return out
    box = []
    for axis, step in enumerate(spacing):
        index = np.flatnonzero(cells.any(axis=1 - axis))
        margin = int(math.ceil(EDGE_STRIP / step)) + 1
        box.append(slice(max(int(index[0]) - margin, 0), int(index[-1]) + 1 + margin))
    box = tuple(box)
    near = keep[box]
    far = (np.ones_like(near) if near.all() else
           distance_transform_edt(near, sampling=spacing) > EDGE_STRIP)
    out[box] = far & cells[box]
    return out


def near_crossing(field: GapField, breaks: EdgeBreaks, loaded: np.ndarray, reach: float
                  ) -> bool:
    """Whether `loaded` cells lie within `reach` (mm) of where a line of the field along
    its longer axis crosses an edge of the material or a kink of either flank's
    modifications (`breaks.kinks`: a relief's start, a rounding, a chamfer). A spur
    pair's tip rounding runs along its contact line: no line crosses it."""
    from scipy.ndimage import maximum_filter1d

    region = (~field.material).astype(np.int64)
    for member, (rolls, faces) in breaks.kinks.items():
        region = region * (len(rolls) + 1) + np.searchsorted(
            rolls, field.parameters[f"{member}_u"])
        region = region * (len(faces) + 1) + np.searchsorted(
            faces, field.parameters[f"{member}_v"])
    axis = 0 if region.shape[0] >= region.shape[1] else 1
    if axis == 1:                           # lines along the longer axis as rows
        region, loaded = region.T, loaded.T
    change = region[1:] != region[:-1]
    crossing = np.zeros(region.shape, np.uint8)
    crossing[1:] |= change
    crossing[:-1] |= change
    cells = 2 * math.ceil(reach / field.spacing[axis]) + 1
    near = maximum_filter1d(crossing, cells, axis=0, mode="constant")
    return bool((near.view(bool) & loaded).any())


def curved_lines(cycle) -> bool:
    """Whether a cycle's contact lines curve (a worm set's): their fields, laid square to
    the face rather than along a line, are fitted to the flanks' material (a pattern that
    runs past an edge would size them past it, field.gap_samples)."""
    return not all(getattr(flank, "straight_contact_lines", False)
                   for flank in (cycle.pinion, cycle.gear))
