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

What each solved contact says about the flanks' edges is contact.edge_loads'. A contact
that spans too few cells across its field is solved again on a narrower one
(_Pair.narrow). Units: mm, N, MPa.
"""

from __future__ import annotations

import math

import numpy as np

from ..parallel import parallel_map
from .compliance import PairCompliance
from .edge_loads import (
    EDGE_STRIP,
    EdgeBreaks,
    LoadedContact,
    curved_lines,
    edge_breaks,
    near_crossing,
    summarise,
    tip_roundings,
)
from .field import LOADED_FAR, FieldSamples, GapField, contact_samples, pattern_semi_axes
from .influence import FreeEnd, ObliqueFreeEnd, free_end_factor
from .local import face_length
from .pressure import (
    ContactSolution,
    Grid,
    GridEdgeError,
    solve_shared,
)

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
        #: the field's box ((2, 2) mm in its plane) once it is grown or narrowed onto the
        #: contact (see grow, narrow); None while it lies about the pattern
        self.box: np.ndarray | None = None
        #: whether its field was narrowed (once per pair)
        self.narrowed = False
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
        # the field as laid, in its own axes: the pattern's semi-axes turned by its axis
        # angle laid a slanted line's field as wide across as its length's slant, so that
        # growing the semi-axis across by the growth barely widened it (a worm wheel's
        # contact at a tip chamfer took six solves before its field grew, and ran out of
        # the position's tries: "outgrows its gap fields")
        f = self.field
        box = self.box if self.box is not None else np.array([[f.x[0], f.x[-1]],
                                                               [f.y[0], f.y[-1]]], float)
        middle, half = box.mean(axis=1), 0.5 * np.ptp(box, axis=1)
        grown = np.minimum(half * np.where(axes, self.growth, 1.0), self.largest)
        if np.array_equal(grown, half):
            raise self._outgrown()
        self._narrowed(np.stack([middle - grown, middle + grown], axis=1))

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
        if solution is None or self.narrowed:
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
            self.narrowed = True
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
    """The free end faces (influence.FreeEnd) of both members that cross a contact's field
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
    """Each member's free-end weight: its φ (influence.free_end_factor of its Poisson's
    ratio) times its share (1 - ν²)/E of the composite compliance (steel's φ and equal
    shares without a tooth model)."""
    if teeth is None:
        return {"pinion": 0.5 * free_end_factor(0.3), "gear": 0.5 * free_end_factor(0.3)}
    c = {name: (1.0 - t.nu ** 2) / t.E for name, t in teeth.members.items()}
    return {name: free_end_factor(teeth.members[name].nu) * value / sum(c.values())
            for name, value in c.items()}


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


def _body_coupling(pairs: list[_Pair]) -> np.ndarray | None:
    """The gear bodies' coupling of the pairs' teeth (PairCompliance.body_coupling), or
    None without a tooth model."""
    teeth = pairs[0].teeth
    if teeth is None:
        return None
    return teeth.body_coupling([p.structure for p in pairs],
                               [int(p.cycle.rows[p.k]["pair"]) for p in pairs])


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
            body = _body_coupling(pairs)
            if pairs[0].structure is not None:
                coarse = _precise_enough([p.grid(coarse=True) for p in pairs], loads, E_star,
                                         tol=COARSE_TOLERANCE, body=body)
                sharpened = [p.sharpen(s, p.steps) for p, s in zip(pairs, coarse)]   # every one
                if any(sharpened):
                    continue
                starts = [p.refined(s) for p, s in zip(pairs, coarse)]
                loads = np.array([0.0 if s is None else s.load_N for s in coarse])
            solutions = _precise_enough([p.grid() for p in pairs], loads, E_star,
                                        starts=starts, tol=GAP_TOLERANCE, body=body)
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
