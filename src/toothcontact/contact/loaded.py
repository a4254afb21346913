"""Loaded contact: the pressure under every contact of the cycle, solved on its own gap field,
with the load shared between the tooth pairs of a mesh position.

Each contact's gap field (field.contact_field: the tangent plane around the contact, masked
where either flank has no material) is solved by the elastic half-space solver
(pressure.solve_contact) for that contact's load; for cylindrical gears the teeth's bending
along the face (compliance.PairCompliance: slices coupled along the face) is part of the same
system, so a pair's approach is its contact deformation and its teeth's bending together.
Pairs in contact at one position share one rigid rotation of the gear: each closes by the
same approach D (its approach measured from its own gap, which includes its separation at
first touch); the loads sum to the normal load. The split is found by modelling each pair as
delta_k(W) = s_k + c_k·W^n_k (n_k = 2/3 and c_k from the rigid analysis's Hertz approach at
first; then c_k calibrated from its last solve and n_k fitted through its last two: a
line contact's approach, and a bending tooth's, grows nearly linearly, a pair that barely
touches steeply), solving the model for D, solving each loaded pair again, until the
loads settle.

The pressure at a sharp face end is singular: the raw peak grows as the grid is refined. The
edge is therefore reported as the pressure averaged over a strip `EDGE_STRIP` wide at the
edge (mm; pressure.ContactSolution.edge_loads), with the share of the load in that strip.
Units: mm, N, MPa.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from .compliance import PairCompliance, StructureOperator
from .field import GapField, contact_fields, pattern_semi_axes
from .local import face_length
from .pressure import ContactSolution, solve_contact

#: width (mm) of the strip at an edge over which the edge pressure is averaged
EDGE_STRIP = 0.1
#: a contact is edge-loaded when its strip-averaged edge pressure exceeds this share of its
#: peak: an ellipse that just reaches an edge averages about 0.1 of its peak over the strip
#: (sqrt(2·0.05/a) for a ≈ 10 mm), one cut by a few tenths of a millimetre well over 0.25
EDGE_LOAD_RATIO = 0.25
#: longest cell (mm) of a loaded contact's grid along a long contact, where the grid's size
#: allows: a third of the edge strip, which then averages over three cells or more
CELL = EDGE_STRIP / 3.0
#: relative change of the pairs' loads at which the shared solve stops
SHARE_TOLERANCE = 0.005
#: with the teeth's bending, the load sharing's rounds solve every COARSE_STEP-th point of
#: the field (4 times fewer cells), and only the final split on the full grid
COARSE_STEP = 2
#: the relative gap error each contact is solved to (pressure.solve_contact), on the full
#: grid and in the load sharing's coarse rounds: on a 30 µm approach, 0.3 nm and 30 nm;
#: the pressures to 1e-5, the split to about 0.2 % of the load (SHARE_TOLERANCE is 0.5 %)
GAP_TOLERANCE, COARSE_TOLERANCE = 1e-5, 1e-3


#: the result keys of a loaded contact (LoadedContact.summary); a row without a solution
#: carries them as None, with bem_status "unloaded" (the other pairs of its position carry
#: the load) or "failed" and the reason in bem_reason
RESULT_KEYS = ("bem_status", "bem_load_N", "bem_p_max_MPa", "edge_loaded", "end_loaded",
               "bem_area_mm2",
               "bem_approach_mm", "bem_grid", "edge_pressure_MPa", "edge_load_fraction",
               "edge_pressure_at", "edge_strip_mm", "bem_raw_peak_MPa", "bem_iterations",
               "bem_relative_error", "bem_reason")


def unsolved(status: str, reason: str | None = None) -> dict:
    """The result keys of a row without a loaded solution (see RESULT_KEYS): "unloaded"
    carries nothing (zero load, pressure and area), "failed" is not known (None)."""
    row = dict.fromkeys(RESULT_KEYS)
    if status == "unloaded":
        row.update(bem_load_N=0.0, bem_p_max_MPa=0.0, bem_area_mm2=0.0, edge_pressure_MPa=0.0,
                   edge_load_fraction=0.0, edge_loaded=False, end_loaded=False)
    return {**row, "bem_status": status, "bem_reason": reason}


@dataclass(frozen=True)
class LoadedContact:
    """One contact's loaded solution: its gap field and the pressure on it."""

    field: GapField
    solution: ContactSolution
    structure: StructureOperator | None = None

    def line_load(self, edges: np.ndarray) -> np.ndarray | None:
        """The contact's mean load per unit face width (N/mm) on the strips of the pinion's
        face between `edges` (mm from mid-face); None without a tooth model."""
        if self.structure is None:
            return None
        return self.structure.line_load(self.solution.pressure_MPa, edges)

    def summary(self) -> dict:
        """The result keys of a loaded contact; the most loaded edge is named by the flank
        edge it is (e.g. "gear_tip", "pinion_end_B"). Where the material runs on to the
        field's border there is no edge (the contact never reaches that border: the solver
        widens the field until it does not); with no flank edge in the field the edge keys
        are zero and edge_pressure_at is "none"."""
        s = self.solution
        named = [(self.edge_name(edge), edge) for axis in (0, 1)
                 for edge in s.edge_loads(axis, EDGE_STRIP)]
        named = [(name, edge) for name, edge in named if not name.startswith("field_")]
        name, worst = max(named, key=lambda item: item[1].edge_pressure_MPa,
                          default=("none", None))
        edge_pressure = worst.edge_pressure_MPa if worst is not None and worst.load_N > 0 else 0.0
        interior = self.interior_peak()
        limit = EDGE_LOAD_RATIO * max(interior, edge_pressure)
        loaded = [n for n, e in named if e.load_N > 0 and e.edge_pressure_MPa > limit]
        return {"bem_status": "solved", "bem_load_N": s.load_N,
                "bem_p_max_MPa": max(interior, edge_pressure),
                "edge_loaded": bool(loaded),
                "end_loaded": any("_end_" in n for n in loaded),
                "bem_area_mm2": s.area_mm2, "bem_approach_mm": s.approach_mm,
                "bem_grid": list(s.pressure_MPa.shape),
                "edge_pressure_MPa": edge_pressure,
                "edge_load_fraction": worst.load_fraction if worst is not None else 0.0,
                "edge_pressure_at": name, "edge_strip_mm": EDGE_STRIP,
                "bem_raw_peak_MPa": s.peak_pressure_MPa, "bem_iterations": s.iterations,
                "bem_relative_error": s.relative_error, "bem_reason": None}

    def edge_name(self, edge) -> str:
        """The flank edge an edge load (pressure.EdgeLoad) is at: the one beyond the last
        material cell of its grid line; named by the field's side ("field_x_low", ...)
        where the material reaches the field's border."""
        material = self.field.material if edge.axis == 0 else self.field.material.T
        line = material[:, edge.line_index]
        cells = np.flatnonzero(line)
        if cells.size:
            outside = cells[0] - 1 if edge.side == "low" else cells[-1] + 1
            if 0 <= outside < line.size:
                index = (outside, edge.line_index) if edge.axis == 0 else (edge.line_index, outside)
                for name, beyond in self.field.beyond.items():
                    if beyond[index]:
                        return name
        return f"field_{'xy'[edge.axis]}_{edge.side}"

    def interior_peak(self) -> float:
        """The largest pressure (MPa) more than EDGE_STRIP from every edge of the material:
        with the strip-averaged edge pressure, the peak that converges as the grid is
        refined (the pressure in a cell at a sharp edge does not)."""
        from scipy.ndimage import distance_transform_edt

        material = self.field.material
        inside = (material if material.all() else
                  distance_transform_edt(material, sampling=self.field.spacing) > EDGE_STRIP)
        p = self.solution.pressure_MPa
        return float(p[inside].max()) if inside.any() else 0.0


def loaded_cycle(cycle, C_E: float, points: int = 128, teeth: PairCompliance | None = None
                 ) -> tuple[list[LoadedContact | None], dict[int, str]]:
    """The loaded solution of every row of a contact.cycle.ContactCycle, loads shared per
    position (None for a pair the others keep unloaded), and the rows whose position could
    not be solved, with the reason (row index -> text; those rows are None too: the other
    positions keep their solutions). `teeth`: the members' tooth compliance along the face,
    None to leave bending out (the pairs then share by their contact approaches alone)."""
    rows = cycle.rows
    out: list[LoadedContact | None] = [None] * len(rows)
    failed: dict[int, str] = {}
    positions: dict[float, list[int]] = {}
    for k, row in enumerate(rows):
        positions.setdefault(row["roll_deg"], []).append(k)
    fields = contact_fields(cycle, range(len(rows)), points, _Pair.MARGIN,   # one batch
                            largest_cell=CELL)
    models: dict[int, tuple[float, float]] = {}     # each tooth pair's last approach model
    for ks in positions.values():
        load = sum(rows[k]["normal_load_N"] for k in ks)
        try:
            pairs = [_Pair(cycle, k, points, 1.0 / C_E, fields[k], teeth) for k in ks]
            solutions = _share(pairs, load, models)
        except (ValueError, RuntimeError) as exc:
            failed.update({k: str(exc) for k in ks})
            continue
        for k, pair, solution in zip(ks, pairs, solutions):
            if solution is not None:
                out[k] = LoadedContact(pair.field, solution, pair.structure)
    return out, failed


class _Pair:
    """One contact to solve: its gap field, widened when the loaded contact reaches the
    field's edge (a cut ellipse spreads away from the cut; a line mostly along itself)."""

    #: the pattern's box enlarged by this much at first
    MARGIN = 1.5

    def __init__(self, cycle, k: int, points: int, E_star: float, field: GapField,
                 teeth: PairCompliance | None):
        self.cycle, self.k, self.points, self.E_star = cycle, k, points, E_star
        self.teeth = teeth
        self.separation = cycle.rows[k]["separation_mm"]
        #: the tooth pair (its index in the cycle) and whether it touches without load
        self.tooth_pair = cycle.rows[k]["pair"]
        self.rigid_contact = cycle.rows[k].get("rigid_contact", True)
        self.semi_axes = self.MARGIN * pattern_semi_axes(cycle, [k])[0]
        #: the largest semi-axis a field needs: the flanks' length along the face, a box
        #: that covers them whole about any point of them
        self.largest = max(float(face_length(getattr(cycle, m), cycle.contact_uv(m, k))[0])
                           for m in ("pinion", "gear"))
        self.growth = (np.array([1.6, 1.6]) if cycle.rows[k]["contact_model"] == "ellipse"
                       else np.array([2.5, 1.3]))
        self._use(field)

    def _use(self, field: GapField) -> None:
        """Solve on `field` from now on (its structure operators built, no solutions yet)."""
        self.field = field
        self.structure = None if self.teeth is None else self.teeth.operator(self.cycle, field)
        self.coarse_structure = (None if self.structure is None
                                 else self.structure.coarsened(COARSE_STEP))
        self.last: ContactSolution | None = None
        self.last_coarse: ContactSolution | None = None

    def hertz_coefficient(self) -> float:
        """c of Hertz's approach law delta = c·W^(2/3) (mm/N^(2/3)) from the rigid
        analysis's approach at the row's load; NaN where it gives none (a line, an area)."""
        row = self.cycle.rows[self.k]
        approach = row.get("approach_mm")
        return approach / row["normal_load_N"] ** (2.0 / 3.0) if approach else math.nan

    def solve(self, load: float, coarse: bool = False) -> ContactSolution:
        """The contact under `load` (N), started from its last solution on this field (the
        load sharing solves each pair a few times at nearby loads). With the teeth's bending
        `coarse` solves on every COARSE_STEP-th point of the field (the load sharing's
        rounds), and the full grid starts from the coarse solution; without it there is one
        grid."""
        coarse = coarse and self.structure is not None
        for _ in range(5):
            try:
                return self._solve(load, coarse)
            except ValueError as exc:
                if "reaches the grid's edge" not in str(exc):
                    raise
            grown = np.minimum(self.semi_axes * self.growth, self.largest)
            if np.array_equal(grown, self.semi_axes):
                break
            self.semi_axes = grown
            self._use(contact_fields(self.cycle, [self.k], self.points, 1.0,
                                     self.semi_axes[None], CELL)[0])
        raise ValueError(f"the loaded contact at roll {self.cycle.rows[self.k]['roll_deg']:.3f} "
                         "deg outgrows its gap field (the surfaces end around it)")

    def _solve(self, load: float, coarse: bool) -> ContactSolution:
        dx, dy = self.field.spacing
        if coarse:
            step = COARSE_STEP
            self.last_coarse = solve_contact(
                self.field.gap[::step, ::step], step * dx, step * dy, load, self.E_star,
                mask=self.field.material[::step, ::step],
                start=None if self.last_coarse is None else self.last_coarse.pressure_MPa,
                dtype=np.float32, structure=self.coarse_structure,
                reference=self.structure.reference, tol=COARSE_TOLERANCE)
            return self.last_coarse
        if self.structure is None or self.last_coarse is None:
            reference = () if self.structure is None else self.structure.reference
            self.last = solve_contact(self.field.gap, dx, dy, load, self.E_star,
                                      mask=self.field.material,
                                      start=None if self.last is None else self.last.pressure_MPa,
                                      dtype=np.float32, structure=self.structure,
                                      reference=reference, tol=GAP_TOLERANCE)
            return self.last
        # the full grid refines the contact under the bending the coupled coarse solve found:
        # the teeth's deflection is smooth along the face, and the coarse and the full
        # grid's pressures carry the same line load
        n0, n1 = self.field.gap.shape
        start = np.repeat(np.repeat(self.last_coarse.pressure_MPa * (load / self.last_coarse.load_N),
                                    COARSE_STEP, axis=0), COARSE_STEP, axis=1)[:n0, :n1]
        start = np.where(self.field.material, start, 0.0)
        bending = self.structure(start)
        self.last = solve_contact(self.field.gap + bending, dx, dy, load, self.E_star,
                                  mask=self.field.material, start=start, dtype=np.float32,
                                  reference=self.structure.reference, tol=GAP_TOLERANCE)
        return self.last


def _share(pairs: list[_Pair], load: float,
           models: dict[int, tuple[float, float]] | None = None) -> list[ContactSolution | None]:
    """Solutions of the pairs of one position under their shares of `load` (see module):
    each pair's approach modelled as s_k + c_k·W^n_k, n_k = 2/3 and c_k from the rigid
    analysis's Hertz approach at first (a pair in contact without one, a line or an area, is
    first solved at the equal split among the pairs in contact to calibrate it; a pair kept
    beyond the approach takes the stiffest of their models), then c_k from its last solution
    and n_k fitted through its last two (0.5 to 3: a line contact grows nearly linearly, a pair that
    barely touches steeply); the model solved for the split, the loaded pairs solved there
    (on the coarse grid where the teeth bend, see _Pair.solve), until the split settles; the
    solutions returned are those at the final split on the full grid, the split corrected
    (up to twice) by the difference of the full grid's approaches from the coarse ones where
    they differ by more than SHARE_TOLERANCE. A pair the model leaves unloaded is not
    solved. `models` (tooth pair -> (c, n)): the pairs' models calibrated at the previous
    position, the first guess where there is one (closer than Hertz's: it holds the teeth's
    bending), updated with this position's."""
    if len(pairs) == 1:
        if pairs[0].structure is not None:
            pairs[0].solve(load, coarse=True)       # the full grid's start
        return [pairs[0].solve(load)]
    count = len(pairs)
    s = np.array([p.separation for p in pairs])
    exponent = np.full(count, 2.0 / 3.0)
    c = np.array([p.hertz_coefficient() for p in pairs])
    models = {} if models is None else models
    keys = [p.tooth_pair for p in pairs]
    for i, key in enumerate(keys):
        if key in models:
            c[i], exponent[i] = models[key]
    at = np.full(count, np.nan)                     # the load of each pair's last solution
    solutions: list[ContactSolution | None] = [None] * count
    touching = np.array([p.rigid_contact for p in pairs])
    for k in np.flatnonzero(~np.isfinite(c) & touching):
        at[k] = load / touching.sum()
        solutions[k] = pairs[k].solve(at[k], coarse=True)
        c[k] = max(solutions[k].approach_mm - s[k], 1e-12) / at[k] ** exponent[k]
    # a pair kept beyond the approach borrows the stiffest model of the pairs in contact: the
    # split loads it only once the position's approach reaches its separation (whatever its
    # own stiffness), and it is then solved and calibrated like the others
    stiffest = np.flatnonzero(touching)[np.argmin((c * load ** exponent)[touching])]
    c[~touching], exponent[~touching] = c[stiffest], exponent[stiffest]
    split = None
    for _ in range(20):
        new = _split(c, exponent, s, load)
        settled = split is not None and np.max(np.abs(new - split)) <= SHARE_TOLERANCE * load
        split = new
        if settled:
            break
        for k in np.flatnonzero(new > 1e-6 * load):
            before, before_at = solutions[k], at[k]
            solutions[k], at[k] = pairs[k].solve(new[k], coarse=True), new[k]
            rise = max(solutions[k].approach_mm - s[k], 1e-12)
            if before is not None and abs(math.log(new[k] / before_at)) > 0.01:
                fitted = (math.log(rise / max(before.approach_mm - s[k], 1e-12))
                          / math.log(new[k] / before_at))
                # the interpolant through its last two solves: a pair that barely touches
                # stiffens fast (fitted up to 2-3); held to 1 it flips the split between two
                exponent[k] = min(max(fitted, 0.5), 3.0)
            c[k] = rise / new[k] ** exponent[k]
    models.update({key: (c[i], exponent[i]) for i, key in enumerate(keys) if np.isfinite(at[i])})

    def on_full_grid(split):
        return [pair.solve(w) if w > 1e-6 * load else None for pair, w in zip(pairs, split)]

    final = on_full_grid(split)
    if pairs[0].structure is None:
        return final
    # the full grid's approach differs a little from the coarse one the split was found on
    # (most at a sharp tip corner, up to a few per cent): the model shifted by that
    # difference gives the full grid's split
    for _ in range(2):
        loaded = np.flatnonzero(split > 1e-6 * load)
        full = np.array([final[k].approach_mm for k in loaded])
        if np.ptp(full) <= SHARE_TOLERANCE * np.mean(full):
            break
        s[loaded] += full - (s[loaded] + c[loaded] * split[loaded] ** exponent[loaded])
        split = _split(c, exponent, s, load)
        final = on_full_grid(split)
    return final


def _split(c: np.ndarray, n: np.ndarray, s: np.ndarray, load: float) -> np.ndarray:
    """Loads W_k >= 0 with s_k + c_k W_k^n_k = D for the loaded pairs and sum W_k = load:
    bisection on D."""

    def load_at(D):       # each pair's load at approach D, at most the whole load
        with np.errstate(divide="ignore", over="ignore"):
            w = (np.maximum(D - s, 0.0) / c) ** (1.0 / n)
        return np.minimum(np.nan_to_num(w, nan=load, posinf=load), load)

    lo, hi = float(np.min(s)), float(np.max(s + c * load ** n))
    for _ in range(60):
        mid = 0.5 * (lo + hi)
        if load_at(mid).sum() < load:
            lo = mid
        else:
            hi = mid
    w = load_at(hi)
    return w * (load / w.sum())
