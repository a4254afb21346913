"""Loaded contact: the pressure under every contact of the cycle, solved on its own gap field,
with the load shared between the tooth pairs of a mesh position.

Each contact's gap field (field.contact_field: the tangent plane around the contact, masked
where either flank has no material) is solved by the elastic half-space solver
(pressure.solve_shared, with the other contacts of its position); for cylindrical gears the
teeth's bending along the face (compliance.PairCompliance: slices coupled along the face) is
part of the same system, so a pair's approach is its contact deformation and its teeth's
bending together.
Pairs in contact at one position share one rigid rotation of the gear: each closes by the
same approach D (its approach measured from its own gap, which includes its separation at
first touch); the loads sum to the normal load. All pairs of a position are therefore one
contact problem (pressure.solve_shared: their grids one block-diagonal system with one
approach and one load), solved once: the split of the load follows from it as the contact
set does. With the teeth's bending it is solved first on coarser grids (`coarse_steps`: a
line contact's field keeps every cell across it), then on the full grids from that solution,
the bending part of the system on both (holding the coarse solve's bending fixed on the
full grid instead, as an earlier version did, left the bundled helical pair's largest
pressure 23 % high: the full grid moves load toward relieved tips and between the pairs,
and the bending must follow).

The pressure at a sharp face end is singular: the raw peak grows as the grid is refined. The
edge is therefore reported as the pressure averaged over a strip `EDGE_STRIP` wide at the
edge (mm; pressure.ContactSolution.edge_loads), with the share of the load in that strip.
A rounded tip (modify.TipEdge) is a smooth surface: its edge is the rounding itself, its
pressure the largest on it (Hertz on the rounding's radius), apart from the active flank's.
A contact that spans too few cells across its field is solved again on a narrower one
(_Pair.narrow). Units: mm, N, MPa.
"""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass

import numpy as np

from ..parallel import parallel_map
from .compliance import FaceLoad, PairCompliance
from .field import LOADED_FAR, FieldSamples, GapField, contact_samples, is_face_end, pattern_semi_axes
from .local import face_length
from .pressure import (
    ContactSolution,
    EdgeLoad,
    FreeEnd,
    Grid,
    GridEdgeError,
    ObliqueFreeEnd,
    free_end_factor,
    solve_shared,
)

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
#: longest cell (mm) of a loaded contact's grid along a long contact, where the grid's size
#: allows: a third of the edge strip, which then averages over three cells or more
CELL = EDGE_STRIP / 3.0
#: the longest cell (mm) along a contact whose pattern stays CLEAR_REACH (mm) or more from
#: where a line along it crosses an edge of the material or a kink of a modification (a
#: relief's start, a tip rounding, an end chamfer): there the pressure changes over the
#: contact's own length, not across an edge strip or a kink the line crosses. Nor may it
#: lie on a tip rounding: a corner contact's largest shear lies 0.01-0.02 mm deep, where
#: the stresses below cells 0.067 mm long moved 1-4 % from those below 0.033 mm
#: (subsurface.peak resolves what the cells hold, not the pressure between them). A
#: contact whose loaded pressure comes nearer or onto one (on its coarse solve, or on the
#: full one) is solved again on CELL (_Pair.sharpen).
CLEAR_CELL, CLEAR_REACH = 2.0 * CELL, 1.0
#: a loaded contact spanning fewer than RESOLVE_CELLS cells along an axis of its field is
#: solved again on a field narrowed to NARROW_SPAN times its extent there (_Pair.narrow)
RESOLVE_CELLS, NARROW_SPAN = 10, 3.0
#: ... where that box is at most NARROW_GAIN of the field's side (an oblique line that
#: spans the field is left as it is)
NARROW_GAIN = 0.5
#: with the teeth's bending, a position is solved first on coarser grids, then on the full
#: grids from there. A line contact's field (LINE_ASPECT or more times as many cells along
#: one axis as along the other) keeps every cell across the line, where the pressure rises
#: over a few cells, and every LINE_STEP-th along it, where the pressure changes over the
#: face: the full solve starts close to its answer (the bundled spur case: 209 full-grid
#: steps and 0.39 s of coarse solves, against 269 and 0.59 s from every second cell both
#: ways). Other fields keep every COARSE_STEP-th cell both ways.
COARSE_STEP, LINE_STEP, LINE_ASPECT = 2, 8, 4
#: the relative gap error a position is solved to (pressure.solve_shared), on the full
#: grids and in the coarse first solve: on a 30 µm approach, 0.3 nm and 30 nm
GAP_TOLERANCE, COARSE_TOLERANCE = 1e-5, 1e-3


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


def loaded_cycle(cycle, C_E: float, points: int = 128, teeth: PairCompliance | None = None
                 ) -> tuple[list[LoadedContact | None], dict[int, str]]:
    """The loaded solution of every row of a contact.cycle.ContactCycle, loads shared per
    position (None for a pair the others keep unloaded), and the rows whose position could
    not be solved, with the reason (row index -> text; those rows are None too: the other
    positions keep their solutions). `teeth`: the members' tooth compliance along the face,
    None to leave bending out (the pairs then share by their contact approaches alone).
    The positions are solved on the machine's cores (parallel.parallel_map), each on its
    own: the result does not depend on their number."""
    rows = cycle.rows
    out: list[LoadedContact | None] = [None] * len(rows)
    failed: dict[int, str] = {}
    positions: dict[float, list[int]] = {}
    for k, row in enumerate(rows):
        positions.setdefault(row["roll_deg"], []).append(k)
    every = np.arange(len(rows))
    reaches, patterns = field_reach(cycle, every), pattern_semi_axes(cycle, every)
    # a contact with no pattern of its own (no relative curvature across it: a flank
    # turned onto an edge) has no semi-axes, NaN or 0: its field covers the reach
    patterns = np.fmin(np.where(patterns > 0.0, patterns, np.nan), reaches[:, None])
    samples = contact_samples(cycle, every, _Pair.MARGIN, patterns,     # one batch
                              far=LOADED_FAR, along_pattern=True, fit=curved_lines(cycle))
    fields = [s.field(points, CELL, snap=True) for s in samples]
    groups = list(positions.values())
    breaks = edge_breaks(cycle)

    def position(index: int):
        """A position's (field, faces, solution, summary) per pair (the field where it was
        widened, else None; the solution and summary None for a pair that carries no
        load), or the reason it could not be solved."""
        ks = groups[index]
        load = sum(rows[k]["normal_load_N"] for k in ks)
        # a pair whose field holds no material of both flanks carries nothing there (its
        # field has no cell to solve on): one kept beyond the approach, or a rigid contact
        # off the flanks' edges (a flank turned onto its mate's edge, touching beyond the
        # form circle)
        solvable = [k for k in ks if fields[k].material.any()]
        if not solvable:
            edges = sorted({name for k in ks for name, cells in fields[k].beyond.items()
                            if cells.any()})
            return ("no contact of the position lies on both flanks' material (its fields "
                    f"lie beyond {', '.join(edges) or 'the flanks'})")
        try:
            pairs = [_Pair(cycle, k, points, samples[k], fields[k], teeth, reaches[k],
                           patterns[k], breaks) for k in solvable]
            solutions = dict(zip(solvable, zip(pairs, _share(pairs, load, 1.0 / C_E))))
        except (ValueError, RuntimeError) as exc:
            return str(exc)
        return [(None if pair.field is fields[k] else pair.field,
                 () if pair.structure is None or solution is None
                 else pair.structure.face_loads(), solution,
                 None if solution is None else summarise(pair.field, solution, load, breaks))
                if k in solutions else (None, None, None, None)
                for k, (pair, solution) in ((k, solutions.get(k, (None, None))) for k in ks)]

    for ks, answer in zip(groups, parallel_map(position, len(groups))):
        if isinstance(answer, str):
            failed.update(dict.fromkeys(ks, answer))
            continue
        for k, (field, faces, solution, summary) in zip(ks, answer):
            if solution is not None:
                out[k] = LoadedContact(fields[k] if field is None else field, solution,
                                       summary, faces)
    return out, failed


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


class _Pair:
    """One contact to solve: its gap field, widened when the loaded contact reaches the
    field's edge (a cut ellipse spreads away from the cut; a line mostly along itself), its
    cells along the contact CLEAR_CELL long until the contact comes near an edge."""

    #: the pattern's box enlarged by this much at first
    MARGIN = 1.5
    #: the widest field's semi-axis over the flanks' length along the face
    REACH = 1.05

    def __init__(self, cycle, k: int, points: int, samples: FieldSamples, field: GapField,
                 teeth: PairCompliance | None, reach: float, pattern: np.ndarray,
                 breaks: EdgeBreaks):
        """Row k of the cycle on its first `field` (of its `samples`, on cells of CELL at
        most: laid again on CLEAR_CELL where its pattern is clear); `reach` (mm) its
        field_reach, `pattern` (mm, (2,)) its pattern_semi_axes, `breaks` its flanks' broken
        edges and kinks."""
        self.cycle, self.k, self.points, self.teeth = cycle, k, points, teeth
        self.breaks = breaks
        #: the exact samples of the gap over the field's box (a field on other cells over
        #: the same box is carried from them; a box grown or narrowed is solved afresh)
        self.samples: FieldSamples | None = samples
        #: the longest cell of its fields (mm): CLEAR_CELL where its pattern (its field's
        #: middle, 1/MARGIN of it both ways) stays clear of the crossings (near_crossing)
        #: and off the tip roundings, else CELL
        self.cell = CELL
        #: whether the pair touches without load (else it is kept beyond the approach)
        self.rigid_contact = cycle.rows[k].get("rigid_contact", True)
        #: the largest semi-axis a field needs (see field_reach)
        self.largest = float(reach)
        self.semi_axes = self.MARGIN * np.minimum(pattern, self.largest)
        # a contact line grows fastest along the face; on a field laid along it (turned)
        # 2.5 overshot (73 mm about a 35 mm helical line: cells of 0.07 mm along it);
        # across it a field widens only where the contact reached those edges (a worm
        # set's curved line leaving its straight field sideways): by 2 a step (by 1.3,
        # twice the position's solves of 1.3 times the cells, at equal pressures)
        self.growth = (np.array([1.6, 1.6]) if cycle.rows[k]["contact_model"] == "ellipse"
                       else np.array([1.6 if field.turn else 2.5, 2.0]))
        #: the field's box ((2, 2) mm in the plane) once it is narrowed onto the contact
        #: (see narrow); None while it lies about the pattern
        self.box: np.ndarray | None = None
        # its pattern: the field's middle, 1/MARGIN of it both ways
        n0, n1 = field.gap.shape
        middle = np.zeros((n0, n1), bool)
        rim = 0.5 * (1.0 - 1.0 / self.MARGIN)
        middle[int(rim * n0):n0 - int(rim * n0), int(rim * n1):n1 - int(rim * n1)] = True
        axis = 0 if n0 >= n1 else 1
        if field.spacing[axis] < 0.95 * CELL or not self._clear(
                field, middle & field.material, CLEAR_REACH):
            self._use(field)
            return
        self.cell = CLEAR_CELL
        self._use(self._field())

    def _use(self, field: GapField) -> None:
        """Solve on `field` from now on (its structure operators and free ends built)."""
        self.field = field
        self.steps = coarse_steps(field.material)
        self.structure = None if self.teeth is None else self.teeth.operator(self.cycle, field)
        self.coarse_structure = (None if self.structure is None
                                 else self.structure.coarsened(self.steps))
        reference = () if self.structure is None else self.structure.reference
        self.free_ends = free_ends(field, _member_ends(self.teeth), reference)

    def grow(self, axes: tuple[bool, bool]) -> None:
        """Widen the field along the axes whose edges the loaded contact reached (`axes`:
        across x, across y; pressure.GridEdgeError), ValueError where it already covers the
        flanks. Only along those: a worm set's curved contact line leaves a straight field
        sideways, and widening its length with its width (2.5 and 1.3 times a step) bent
        the line further out of it each time, up to fields 90 mm long on 4 mm samples."""
        if self.box is not None:
            middle, half = self.box.mean(axis=1), 0.5 * np.ptp(self.box, axis=1)
            grown = np.minimum(half * np.where(axes, self.growth.max(), 1.0), self.largest)
            if np.array_equal(grown, half):
                raise self._outgrown()
            self._narrowed(np.stack([middle - grown, middle + grown], axis=1))
            return
        grown = np.minimum(self.semi_axes * np.where(axes, self.growth, 1.0), self.largest)
        if np.array_equal(grown, self.semi_axes):
            raise self._outgrown()
        self.semi_axes, self.samples = grown, None
        self._use(self._field())

    def _field(self) -> GapField:
        """The field over the pair's box (or its semi-axes about its pattern while it has
        none), on cells of `cell` at most."""
        if self.samples is None:
            where = (dict(margin=1.0, semi_axes=self.semi_axes[None]) if self.box is None
                     else dict(boxes=self.box[None]))
            self.samples = contact_samples(self.cycle, [self.k], far=LOADED_FAR,
                                           along_pattern=True, fit=curved_lines(self.cycle),
                                           **where)[0]
        return self.samples.field(self.points, self.cell, snap=True)

    def sharpen(self, solution: ContactSolution | None, steps: tuple[int, int] = (1, 1)
                ) -> bool:
        """Put a field of CLEAR_CELL back on cells of CELL where the loaded contact
        (`solution`, on every `steps`-th cell of the field) comes within CLEAR_REACH of a
        crossing (near_crossing) or onto a tip rounding after all; whether its field
        changed (the position is then solved again)."""
        f = self.field
        axis = 0 if f.gap.shape[0] >= f.gap.shape[1] else 1
        if solution is None or self.cell == CELL:
            return False
        loaded = np.zeros(f.gap.shape, bool)
        loaded[::steps[0], ::steps[1]] = solution.pressure_MPa > 0.0
        # a coarse solve's loaded cell stands for the cells up to the next one it keeps
        reach = CLEAR_REACH + (steps[axis] - 1) * f.spacing[axis]
        if self._clear(f, loaded, reach):
            return False
        self.cell = CELL
        field = self._field()
        if field.gap.shape == f.gap.shape:      # held to its most points either way
            return False
        self._use(field)
        return True

    def _clear(self, field: GapField, loaded: np.ndarray, reach: float) -> bool:
        """Whether the `loaded` cells of `field` stay `reach` (mm) or more from every
        crossing along its lines (near_crossing) and off the tip roundings."""
        return not near_crossing(field, self.breaks, loaded, reach) and not any(
            (loaded & on).any() for on in tip_roundings(field, self.breaks.roundings).values())

    def _outgrown(self) -> ValueError:
        return ValueError(f"the loaded contact at roll {self.cycle.rows[self.k]['roll_deg']:.3f} "
                          "deg outgrows its gap field (the surfaces end around it)")

    def narrow(self, solution: ContactSolution | None) -> bool:
        """Narrow the field onto a contact that spans fewer than RESOLVE_CELLS cells on every
        line along an axis (a pair kept beyond the approach, sized on its far field, that
        closes at one spot; a contact at a tip rounding's start): along that axis the box
        becomes NARROW_SPAN times the contact's extent about it; whether it was narrowed
        (once per pair: the position is then solved again)."""
        if solution is None or self.box is not None:
            return False
        touched = solution.pressure_MPa > 0.0
        if not touched.any():
            return False
        f = self.field
        box = np.array([[f.x[0], f.x[-1]], [f.y[0], f.y[-1]]], float)
        changed = False
        for axis, coordinate in enumerate((f.x, f.y)):
            # the contact's widest run of cells on a line along the axis
            if touched.sum(axis=axis).max() >= RESOLVE_CELLS:
                continue
            cells = np.flatnonzero(touched.any(axis=1 - axis))
            step = f.spacing[axis]
            low, high = coordinate[cells[0]] - 0.5 * step, coordinate[cells[-1]] + 0.5 * step
            half = 0.5 * NARROW_SPAN * (high - low)
            if half > 0.5 * NARROW_GAIN * np.ptp(box[axis]):
                continue            # a contact lying across the field: narrowing gains little
            box[axis] = 0.5 * (low + high) + np.array([-half, half])
            changed = True
        if changed:
            self._narrowed(box)
        return changed

    def _narrowed(self, box: np.ndarray) -> None:
        """Solve on the field over `box` ((2, 2) mm in the plane) from now on."""
        self.box, self.samples = box, None
        self._use(self._field())

    def grid(self, coarse: bool = False) -> Grid:
        """The field as the solver's grid, with the teeth's bending where there is a tooth
        model; coarse: every `steps`-th point along each axis."""
        f, (dx, dy) = self.field, self.field.spacing
        reference = () if self.structure is None else self.structure.reference
        if coarse:
            s0, s1 = self.steps
            # the coarse solve only starts the full one: its ends stay half-spaces
            return Grid(f.gap[::s0, ::s1], s0 * dx, s1 * dy, f.material[::s0, ::s1],
                        self.coarse_structure, reference)
        return Grid(f.gap, dx, dy, f.material, self.structure, reference, self.free_ends)

    def refined(self, coarse: ContactSolution | None) -> np.ndarray | None:
        """The coarse solution's pressure interpolated (bilinearly) on the full grid, the
        full solve's start; None for none."""
        if coarse is None:
            return None
        from scipy.ndimage import map_coordinates

        (n0, n1), (s0, s1) = self.field.gap.shape, self.steps
        at = np.meshgrid(np.arange(n0) / s0, np.arange(n1) / s1, indexing="ij")
        p = map_coordinates(coarse.pressure_MPa, at, order=1, mode="nearest")
        return np.where(self.field.material, p, 0.0)


#: a free end's mirror term acts within this many reference depths of the end (the
#: compression measured to a depth fades within a few depths: Boussinesq's d²/ρ³; the FZG
#: C-type gear's end-to-mid pressure is 0.762 with 1 depth, 0.757 with 2, and was the same
#: to 1e-3 from 2 to 6 depths)
FREE_END_REACH = 1.0
#: an end face is taken as crossing the grid along one axis where its normal lies within
#: this angle (deg) of that axis (a spur face end is square to the face direction x; a
#: misalignment turns it by a fraction of a degree); beyond it, obliquely (a helical face
#: end on a field laid along the helix or along a contact line: pressure.ObliqueFreeEnd)
FREE_END_ANGLE = 1.0


def free_ends(field: GapField, weights: dict[str, float], reference: tuple
              ) -> tuple[FreeEnd, ...]:
    """The free end faces (pressure.FreeEnd) of both members that cross a contact's field
    where its compression is measured to the teeth's reference depths (`reference`, the
    tooth model's): each member's face ends ("pinion_end_A", ...) where the field reaches
    past them, the mirror weighted by `weights` (per member: its φ times its share of the
    composite compliance, see _member_ends), acting within FREE_END_REACH reference depths of the
    end. An end oblique to both axes by more than FREE_END_ANGLE is left as a half-space;
    so is every end without a reference (half-spaces that run on: Hertz's idealisation,
    whose approach is measured from infinity, where a mirror's far field would shift it)."""
    if not reference:
        return ()
    reach = FREE_END_REACH * max(depth for depth, _, _ in reference)
    spacing = field.spacing
    ends = []
    for name, beyond in field.beyond.items():
        member, _, edge = name.partition("_")
        if edge not in ("end_A", "end_B") or member not in weights:
            continue
        gx, gy = (np.median(g[field.material]) for g in
                  np.gradient(np.nan_to_num(field.inside[name]), *spacing))
        angle = math.degrees(math.atan2(min(abs(gx), abs(gy)), max(abs(gx), abs(gy))))
        if angle > FREE_END_ANGLE:
            ends.append(_oblique_end(field, name, weights[member], reach))
            continue
        axis = 0 if abs(gx) >= abs(gy) else 1
        outside = beyond if axis == 0 else beyond.T
        lines = outside.any(axis=0) & (~outside).any(axis=0)
        if not lines.any():
            continue
        low = (gx if axis == 0 else gy) > 0          # material on the high side of the end
        cells = outside[:, lines]
        index = (np.argmin(cells, axis=0) if low
                 else cells.shape[0] - np.argmin(cells[::-1], axis=0))
        # the outermost line's end: no material cell lies beyond the mirror plane (one left
        # outside it would carry a half-space's end spike)
        ends.append(FreeEnd(axis, int(index.min() if low else index.max()),
                            "low" if low else "high", weights[member], reach))
    return _merged(ends)


def _oblique_end(field: GapField, name: str, weight: float, reach: float) -> ObliqueFreeEnd:
    """The face end `name` crossing the field obliquely as a straight line: its `inside`
    field (the flank's face parameter's distance from the end) fitted by a plane over the
    cells within `reach` mm of the end, scaled to mm; moved out, where the fit leaves a
    material cell beyond it, to that cell's centre (no material cell without its mirror)."""
    dx, dy = field.spacing
    inside = field.inside[name]
    I, J = np.meshgrid(np.arange(inside.shape[0]), np.arange(inside.shape[1]), indexing="ij")
    finite = np.isfinite(inside)
    gx, gy = (np.median(g[finite]) for g in np.gradient(np.nan_to_num(inside), dx, dy))
    near = finite & (np.abs(inside) < reach * math.hypot(gx, gy))
    if near.sum() < 3:
        near = finite
    (alpha, beta, gamma), *_ = np.linalg.lstsq(
        np.column_stack([I[near], J[near], np.ones(near.sum())]), inside[near], rcond=None)
    scale = math.hypot(alpha / dx, beta / dy)
    a, b, c = alpha / scale, beta / scale, gamma / scale
    on = field.material & near
    if on.any():
        c += max(0.0, -float(np.min(a * I[on] + b * J[on] + c)))
    return ObliqueFreeEnd(a, b, c, weight, reach)


def _merged(ends: list) -> tuple:
    """The ends with those of both members that lie within a cell of each other (flush
    ends) taken as one, at the outer of the two, their weights summed: one mirror
    convolution instead of two (square ends on the same axis and side; oblique ends whose
    normals agree within FREE_END_ANGLE)."""
    out: list = []
    for end in ends:
        twin = next((k for k, o in enumerate(out) if _flush(o, end)), None)
        if twin is None:
            out.append(end)
            continue
        o = out[twin]
        reach, weight = max(o.reach_mm, end.reach_mm), o.weight + end.weight
        if isinstance(o, FreeEnd):
            index = min(o.index, end.index) if o.side == "low" else max(o.index, end.index)
            out[twin] = FreeEnd(o.axis, index, o.side, weight, reach)
        else:
            out[twin] = ObliqueFreeEnd(o.a, o.b, max(o.c, end.c), weight, reach)
    return tuple(out)


def _flush(one, other) -> bool:
    """Whether two free ends are the same end face of the two members (within a cell)."""
    if isinstance(one, FreeEnd) and isinstance(other, FreeEnd):
        return ((one.axis, one.side) == (other.axis, other.side)
                and abs(one.index - other.index) <= 1)
    if isinstance(one, ObliqueFreeEnd) and isinstance(other, ObliqueFreeEnd):
        turn = math.degrees(math.acos(min(1.0, (one.a * other.a + one.b * other.b)
                                          / math.hypot(one.a, one.b) / math.hypot(other.a, other.b))))
        return turn <= FREE_END_ANGLE and abs(one.c - other.c) <= math.hypot(one.a, one.b)
    return False


def _member_ends(teeth: PairCompliance | None) -> dict[str, float]:
    """Each member's free-end weight: its φ (pressure.free_end_factor of its Poisson's
    ratio) times its share (1 - ν²)/E of the composite compliance (steel's φ and equal
    shares without a tooth model)."""
    if teeth is None:
        return {"pinion": 0.5 * free_end_factor(0.3), "gear": 0.5 * free_end_factor(0.3)}
    c = {name: (1.0 - t.nu ** 2) / t.E for name, t in teeth.members.items()}
    return {name: free_end_factor(teeth.members[name].nu) * value / sum(c.values())
            for name, value in c.items()}


def curved_lines(cycle) -> bool:
    """Whether a cycle's contact lines curve (a worm set's): their fields, laid square to
    the face rather than along a line, are fitted to the flanks' material (a pattern that
    runs past an edge would size them past it, field.gap_samples)."""
    return not all(getattr(flank, "straight_contact_lines", False)
                   for flank in (cycle.pinion, cycle.gear))


def field_reach(cycle, rows) -> np.ndarray:
    """The largest semi-axis (mm, (K,)) a loaded-contact field of the given rows needs: the
    flanks' length along the face (a box that covers them whole about any point of them)
    and a little more (_Pair.REACH), so that the flanks end inside it even about a point at
    one end. The patterns the fields are sized on are held to it: a pair kept beyond the
    approach at a point of nearly no relative curvature has a pattern (its Hertz line at
    the position's share) of hundreds of metres, whose grid's cells, of kilometres,
    stalled the shared solve of its position."""
    rows = np.atleast_1d(np.asarray(rows, int))
    return _Pair.REACH * np.max([face_length(getattr(cycle, m), (
        np.asarray(getattr(cycle.contacts, f"{m}_u"))[rows],
        np.asarray(getattr(cycle.contacts, f"{m}_v"))[rows])) for m in ("pinion", "gear")],
        axis=0)


def coarse_steps(material: np.ndarray) -> tuple[int, int]:
    """The steps along each axis of a field (its material mask) to its coarse grid (see
    COARSE_STEP); every cell where the steps would pass over all of its material (a far
    pair's field holding a sliver of both flanks)."""
    n0, n1 = material.shape
    steps = ((LINE_STEP, 1) if n0 >= LINE_ASPECT * n1 else
             (1, LINE_STEP) if n1 >= LINE_ASPECT * n0 else (COARSE_STEP, COARSE_STEP))
    return steps if material[::steps[0], ::steps[1]].any() else (1, 1)


def _widened(pairs: list[_Pair], wide: tuple[list, list[GapField]]
             ) -> list[ContactSolution | None]:
    """The solutions before the narrowing, each pair back on the field it was found on
    (`wide`: the solutions and the fields; a narrowed field the solver could not close, or
    whose contact outgrew it)."""
    solutions, fields = wide
    for pair, field in zip(pairs, fields):
        if pair.field is not field:
            pair._use(field)
    return solutions


def _precise_enough(grids: list[Grid], loads, E_star: float, **options
                    ) -> list[ContactSolution | None]:
    """pressure.solve_shared in single precision (half the FFT work), and again in double
    where single precision's round-off stalls the iteration (RuntimeError: measured at
    roll 8 deg of an aligned 20/60 spur pair, a gap error of 0.035 after 500 steps, which
    double precision closes)."""
    try:
        return solve_shared(grids, loads, E_star, dtype=np.float32, **options)
    except RuntimeError:
        return solve_shared(grids, loads, E_star, dtype=np.float64, **options)


def _share(pairs: list[_Pair], load: float, E_star: float) -> list[ContactSolution | None]:
    """Solutions of the pairs of one position (see module) under `load` (N) together,
    composite modulus E_star (MPa): one shared solve (pressure.solve_shared) started from
    the rigid analysis's split (the load equally among the pairs in contact; the others
    take load once the approach reaches them), first on the coarse grids where the teeth
    bend; the pairs whose contacts reach their fields' edges get wider fields (all at once),
    one that spans too few cells a narrower one about it (_Pair.narrow), and the position
    is solved again (where the narrowed fields cannot be solved, the solutions before
    stand). None for a pair that carries no load."""
    touching = [p.rigid_contact for p in pairs]
    if not any(touching):
        touching = [True] * len(pairs)
    loads = np.array(touching, float) * (load / sum(touching))
    # the solutions before a narrowing and their fields: kept where the narrowed fields
    # cannot be solved
    wide: tuple[list, list[GapField]] | None = None
    for _ in range(7 * len(pairs) + 1):
        try:
            starts = None
            if pairs[0].structure is not None:
                coarse = _precise_enough([p.grid(coarse=True) for p in pairs], loads, E_star,
                                         tol=COARSE_TOLERANCE)
                sharpened = [p.sharpen(s, p.steps) for p, s in zip(pairs, coarse)]   # every one
                if any(sharpened):
                    continue
                starts = [p.refined(s) for p, s in zip(pairs, coarse)]
                loads = np.array([0.0 if s is None else s.load_N for s in coarse])
            solutions = _precise_enough([p.grid() for p in pairs], loads, E_star,
                                        starts=starts, tol=GAP_TOLERANCE)
        except GridEdgeError as exc:
            # every field that can widen does (one by one, a spline's 18 fields took 18
            # solves of their position); one already covering its flanks may have reached
            # its edge only because another was too small: the position fails where none
            # can widen
            outgrown = []
            for grid, axes in exc.reached.items():
                try:
                    pairs[grid].grow(axes)
                except ValueError as error:
                    outgrown.append(error)
            if len(outgrown) == len(exc.reached):
                if wide is None:
                    raise outgrown[0] from exc
                return _widened(pairs, wide)
            continue
        except RuntimeError:
            if wide is None:
                raise
            return _widened(pairs, wide)
        sharpened = [pair.sharpen(s) for pair, s in zip(pairs, solutions)]       # every one
        if any(sharpened):
            continue
        found_on = [pair.field for pair in pairs]
        narrowed = [pair.narrow(s) for pair, s in zip(pairs, solutions)]
        if not any(narrowed):
            return solutions
        wide = (solutions, found_on)
        loads = np.array([0.0 if s is None else s.load_N for s in solutions])
    raise ValueError(f"the loaded contact at roll {pairs[0].cycle.rows[pairs[0].k]['roll_deg']:.3f} "
                     "deg outgrows its gap fields")
