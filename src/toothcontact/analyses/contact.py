"""What every contact kind (spur, spline, worm, imported) reports from its contact cycle: the
positions and summary, the loaded contact, the loaded transmission error and the
positions check."""

from __future__ import annotations

import logging
import math
import time

import numpy as np

from .. import case as schema
from ..case import CaseError
from .result import Check, Result

log = logging.getLogger(__name__)


def cycle_settings(a: schema.AnalysisSpec, at: tuple[float, ...] | None = None,
                   **kind_settings):
    """The contact cycle's settings from a case's [analysis] table, at the places `at` (in
    steps of the positions' spacing from roll 0; None: the case's positions;
    contact.cycle.mesh_positions)."""
    from ..contact.cycle import CycleSettings

    return CycleSettings(a.positions, at, a.grid, a.approach, field_grid=a.field_grid,
                         patterns=a.rigid_patterns is not False,
                         ease_off=a.ease_off is not False, **kind_settings)


#: the largest loaded pressure may move by this much (fraction) with the positions refined
#: before the result says that the case needs more
POSITIONS_TOLERANCE = 0.05
#: the loaded transmission error's peak to peak may move by this fraction, or by
#: TE_POSITIONS_FLOOR µm if more, with the positions refined before the result says so
TE_POSITIONS_TOLERANCE, TE_POSITIONS_FLOOR = 0.10, 0.1
#: the positions check halves a step this many times at most (to 1/8 of the case's step)
REFINEMENT_LEVELS = 3


def refining_case(case: schema.CaseInfo) -> schema.CaseInfo:
    """The case as check_positions' refining passes run it: without the rigid patterns and
    the ease-off (a row's keys and a map the check does not read, which leave the loaded
    contact as it is)."""
    return case.model_copy(update={"analysis": case.analysis.model_copy(update={
        "rigid_patterns": False, "ease_off": False})})


def _per_position(rows: list[dict]) -> list[tuple[float | None, float | None]]:
    """(largest loaded pressure MPa, loaded transmission error µm) of each position of a
    pass's rows, in roll order; None where the position's pairs were not solved (its
    transmission error also where its loaded contact left it unknown)."""
    positions: dict[float, list[dict]] = {}
    for row in rows:
        positions.setdefault(row["roll_deg"], []).append(row)
    out = []
    for roll in sorted(positions):
        answered = [r for r in positions[roll] if r["bem_status"] != "failed"]
        out.append((max((r["bem_p_max_MPa"] or 0.0 for r in answered), default=None)
                    if answered else None,
                    positions[roll][0].get("loaded_transmission_error_um")))
    return out


def _to_refine(known: dict[float, tuple], count: int, width: float,
               most: int | None = None) -> list[float]:
    """The midpoints of the intervals `width` steps wide between the places analysed
    (`known`: step -> (pressure, TE); the cycle is periodic over `count` steps) that can hide
    a larger figure: one end within POSITIONS_TOLERANCE of the largest pressure, the
    pressure changing by more than twice that across it (an edge contact starting
    between), or one end at the transmission error's highest or lowest (where they differ
    by more than TE_POSITIONS_FLOOR); at most `most`, those nearest the largest pressure
    first, then the largest jumps, then the TE's extremes. Intervals with an end not
    solved are left."""
    steps = sorted(known)
    pressures = [known[k][0] for k in steps if known[k][0] is not None]
    errors = [known[k][1] for k in steps if known[k][1] is not None]
    if not pressures:
        return []
    top = max(pressures)
    extremes = ({max(errors), min(errors)} if errors and max(errors) - min(errors)
                > TE_POSITIONS_FLOOR else set())
    found = []
    for a, b in zip(steps, steps[1:] + [steps[0] + count]):
        (pa, ta), (pb, tb) = known[a], known[b if b in known else b - count]
        if b - a != width or pa is None or pb is None:
            continue
        reasons = (max(pa, pb) >= (1.0 - POSITIONS_TOLERANCE) * top,
                   abs(pa - pb) >= 2.0 * POSITIONS_TOLERANCE * top,
                   ta in extremes or tb in extremes)
        if any(reasons):
            found.append((reasons, max(pa, pb), abs(pa - pb), a + 0.5 * width))
    found.sort(key=lambda f: (f[0], f[1] if f[0][0] else f[2]), reverse=True)
    return sorted(f[3] for f in found[:most])


def _envelope(known: dict[float, tuple]) -> tuple[float, float | None]:
    """The largest pressure (MPa) and the transmission error's peak to peak (µm; None
    where a place's is unknown) over the places analysed."""
    pressures = [p for p, _ in known.values() if p is not None]
    errors = [t for _, t in known.values()]
    spread = None if None in errors else max(errors) - min(errors)
    return max(pressures), spread


def check_positions(result: Result, positions: int, refine) -> None:
    """summary["positions_check"]: the largest loaded pressure and the loaded transmission
    error's peak to peak at the case's positions, and with the positions refined by
    adaptive bisection where those figures can hide (_to_refine: about the pressure's peak,
    across its jumps and about the transmission error's extremes), a step halved up to
    REFINEMENT_LEVELS times, stopping when a level moves neither figure by more than its
    tolerance or as many positions as the case's were added (the cost of doubling them; a
    pass for one place is not worth its contact cycle); `refine(scratch, at)` runs the
    contact and the loaded contact at the places `at` (steps from roll 0) into a scratch
    Result. A note where the pressure moves by more
    than POSITIONS_TOLERANCE (`converged` false), or the peak to peak by more than
    TE_POSITIONS_TOLERANCE (`transmission_error_converged` false). Nothing where no loaded
    contact was solved."""
    summary = result.sections.get("summary") or {}
    here = summary.get("bem_max_p_max_MPa")
    if here is None:
        return
    start = time.perf_counter()
    first = _per_position(result.sections["positions"])
    known = dict(zip((float(k - positions // 2) for k in range(len(first))), first))
    spread = summary.get("loaded_transmission_error_peak_to_peak_um")
    width, added, failed, levels = 1.0, 0, 0, 0
    while levels < REFINEMENT_LEVELS and positions - added >= (2 if levels else 1):
        at = _to_refine(known, positions, width, positions - added)
        if not at:
            break
        before = _envelope(known)
        scratch = Result()
        try:
            refine(scratch, tuple(at))
        except CaseError as exc:
            summary["positions_check"] = {"positions": positions, "checked": False,
                                          "reason": str(exc)}
            return
        found = _per_position(scratch.sections["positions"])
        if len(found) != len(at):       # a place without a pair: not comparable
            break
        known.update(zip(at, found))
        added, levels, width = added + len(at), levels + 1, 0.5 * width
        failed += scratch.sections["summary"].get("bem_failed_contacts", 0)
        after = _envelope(known)
        if (after[0] <= (1.0 + POSITIONS_TOLERANCE) * before[0]
                and (None in (after[1], before[1]) or after[1] - before[1]
                     <= max(TE_POSITIONS_TOLERANCE * before[1], TE_POSITIONS_FLOOR))):
            break
    best, refined = _envelope(known)
    refined = None if spread is None else refined
    check = {"positions": positions, "checked": True, "method": "adaptive bisection",
             "refined_positions": added, "refinement_levels": levels,
             "finest_step_fraction": width,
             "bem_max_p_max_MPa": here, "refined_bem_max_p_max_MPa": best,
             "bem_max_p_max_change_percent": 100.0 * (best - here) / here,
             "loaded_transmission_error_peak_to_peak_um": spread,
             "refined_loaded_transmission_error_peak_to_peak_um": refined,
             "refined_failed_contacts": failed,
             "tolerance_percent": 100.0 * POSITIONS_TOLERANCE,
             "converged": best <= (1.0 + POSITIONS_TOLERANCE) * here,
             "transmission_error_converged": None if refined is None else
             refined - spread <= max(TE_POSITIONS_TOLERANCE * spread, TE_POSITIONS_FLOOR)}
    summary["positions_check"] = check
    log.info("positions check: largest loaded pressure %.0f MPa at %d positions, %.0f MPa "
             "with %d more (%+.1f %%, steps down to 1/%d), in %.2f s", here, positions, best,
             added, check["bem_max_p_max_change_percent"], round(1 / width),
             time.perf_counter() - start)
    more = f"give [analysis] positions = {positions * max(2, round(1 / width))} or more"
    if not check["converged"]:
        result.notes.append(
            f"positions: the largest loaded pressure rises from {here:.0f} to {best:.0f} MPa "
            f"(+{check['bem_max_p_max_change_percent']:.1f} %) with the positions refined "
            f"between the case's {positions} (to 1/{round(1 / width)} of their step where it "
            f"can hide); the peak falls between the case's positions: {more}")
    if check["transmission_error_converged"] is False:
        result.notes.append(
            f"positions: the loaded transmission error's peak to peak grows from {spread:.3g} "
            f"to {refined:.3g} µm with the positions refined between the case's "
            f"{positions}: its extremes fall between the case's positions: {more} for the "
            "transmission error")


#: the mesh orders whose amplitudes a transmission error's Fourier series reports (as many
#: as its positions resolve: orders below half their number)
TE_ORDERS = 5


def mesh_harmonics(values: list[float]) -> list[float]:
    """The amplitudes of mesh orders 1, 2, ... of a transmission error sampled at n positions
    spread evenly over one mesh cycle (contact.cycle.mesh_positions), in its unit: 2|X_k|/n
    of its discrete Fourier transform X, for k below n/2 (the order n/2 is not resolved),
    at most TE_ORDERS."""
    x = np.asarray(values, float)
    n = len(x)
    orders = min(TE_ORDERS, (n - 1) // 2)
    return (2.0 * np.abs(np.fft.rfft(x)[1:orders + 1]) / n).tolist()


def _loaded_transmission_error(cycle, summary: dict) -> None:
    """loaded_transmission_error_urad on every row of a position whose loaded contact was
    solved: the unloaded one plus D/turn_slope, D (mm) the position's common approach (a
    loaded pair's approach: its contact deformation and, where modelled, its teeth's
    bending), and its peak to peak in the summary. None where the position has no solved
    pair."""
    positions: dict[float, list[int]] = {}
    for k, row in enumerate(cycle.rows):
        positions.setdefault(row["roll_deg"], []).append(k)
    values, arm = [], summary["transmission_error_arm_mm"]
    for ks in positions.values():
        solved = [k for k in ks if cycle.rows[k]["bem_status"] == "solved"]
        te = None
        if solved:
            k = max(solved, key=lambda j: cycle.rows[j]["bem_load_N"])
            row, slope = cycle.rows[k], float(cycle.turn_slope[k])
            if math.isfinite(slope) and slope > 0.0:
                te = row["transmission_error_urad"] + 1e6 * row["bem_approach_mm"] / slope
                values.append(te)
        for k in ks:
            cycle.rows[k]["loaded_transmission_error_urad"] = te
            cycle.rows[k]["loaded_transmission_error_um"] = None if te is None else 1e-3 * arm * te
    complete = len(values) == len(positions)
    spread = max(values) - min(values) if complete else None
    summary["loaded_transmission_error_peak_to_peak_urad"] = spread
    summary["loaded_transmission_error_peak_to_peak_um"] = (
        None if spread is None else 1e-3 * arm * spread)
    by_roll = [cycle.rows[ks[0]]["loaded_transmission_error_um"]
               for _, ks in sorted(positions.items())]
    summary["te_harmonics_um"] = mesh_harmonics(by_roll) if complete else None
    summary["transmission_error_note"] = (
        "transmission errors are the gear's (a worm set's wheel's) rotation from where "
        "conjugate flanks would hold it, in µrad, positive where it lags behind, and that "
        f"rotation as a length (µm) on the {summary['transmission_error_arm']} "
        f"(r = {arm:.3f} mm); the loaded one adds the turn that closes the position's common "
        "approach D (half-space contact and, where modelled, tooth bending): "
        "D/r_b2·cos(beta_b) on a parallel pair")


def loaded_sections(cycle, C_E: float, grid: int, teeth, bending: str,
                     result: Result) -> None:
    """The loaded contact of every row (contact.loaded): bem_* and edge keys on each row
    (bem_status "solved", "unloaded" or "failed" with bem_reason: a position the solver
    cannot answer says so in its own rows and the others keep theirs), their worst in the
    summary, and the checks that every contact was solved, none end-loaded and none a
    corner contact (_edge_verdicts)."""
    if not grid:
        return
    from ..contact.edge_loads import unsolved
    from ..contact.loaded import loaded_cycle

    rows = cycle.rows
    start = time.perf_counter()
    try:
        loaded, failed = loaded_cycle(cycle, C_E, grid, teeth)
    except (ValueError, RuntimeError) as exc:   # no gap field to solve on: the stage fails
        loaded, failed = [None] * len(rows), {k: str(exc) for k in range(len(rows))}
    log.info("loaded contact: %d contacts at %d positions, %d not solved, in %.2f s",
             len(rows), len({r["roll_deg"] for r in rows}), len(failed),
             time.perf_counter() - start)
    for k in sorted(failed)[:1]:
        log.warning("loaded contact not solved at roll %.3f deg: %s", rows[k]["roll_deg"],
                    failed[k])
    result.loaded = loaded
    for k, (row, contact) in enumerate(zip(rows, loaded)):
        row.update(unsolved("failed", failed[k]) if k in failed else
                   unsolved("unloaded") if contact is None else contact.summary)
    totals: dict[float, float | None] = {}
    for row in rows:       # a position with a pair not solved has no known total
        known = totals.get(row["roll_deg"], 0.0)
        totals[row["roll_deg"]] = (None if known is None or row["bem_load_N"] is None
                                   else known + row["bem_load_N"])
    for row in rows:       # each pair's share of its position's load (None: not known)
        total = totals[row["roll_deg"]]
        row["load_share"] = row["bem_load_N"] / total if total else None
    summary = result.sections["summary"]
    summary.update(
        load_sharing="one rigid rotation for all pairs of a position; each pair's approach "
                     f"from its half-space solution; {bending}",
        bem_failed_contacts=len(failed))
    _loaded_transmission_error(cycle, summary)
    _reach_check(cycle, result)
    result.checks.append(Check(
        "loaded contact solved at every contact", not failed,
        f"{len(failed)} of {len(rows)} contacts not solved"
        + (f", first at roll {rows[min(failed)]['roll_deg']:.2f} deg: {failed[min(failed)]}"
           if failed else ""), kind="solver"))
    answered = [r for r in rows if r["bem_status"] != "failed"]
    if not answered:
        return
    summary.update(bem_max_p_max_MPa=max(r["bem_p_max_MPa"] for r in answered),
                   flank_pressure_max_MPa=max(r["flank_p_max_MPa"] for r in answered),
                   max_edge_pressure_MPa=max(r["edge_pressure_MPa"] for r in answered),
                   max_edge_load_fraction=max(r["edge_load_fraction"] for r in answered))
    _edge_verdicts(cycle, rows, summary, result)
    for check in result.checks:     # the loaded contact decides; the rigid margins stay figures
        if check.name.startswith(RIGID_PATTERN_CHECK):
            check.kind = "rigid"


def _edge_verdicts(cycle, rows: list[dict], summary: dict, result: Result) -> None:
    """The loaded contact's edge figures over the contacts that carry load, counted once
    for the summary, the checks and the report: edge-loaded (either kind), end-loaded at a
    face end (end_load_ratio above END_LOAD_RATIO; the largest ratio over the contacts
    judged, those carrying EDGE_LEAST_SHARE of their position's load), and corner contacts
    (a tip, root or form edge pressed harder than the flank); a design check of each
    kind."""
    from ..contact.edge_loads import EDGE_LEAST_SHARE, EDGE_STRIP, END_LOAD_RATIO, edge_breaks

    carrying = [r for r in rows if r["bem_status"] == "solved"]
    judged = [r for r in carrying if (r.get("load_share") or 0.0) >= EDGE_LEAST_SHARE]
    ends = [r for r in carrying if r["end_loaded"]]
    corners = [r for r in carrying if r["corner_contact"]]
    breaks = edge_breaks(cycle)
    rounded = ({f"{member}_tip" for member in breaks.roundings}
               | {f"{member}_end_{end}" for member in breaks.chamfers for end in "AB"})
    worst_end = max(judged, key=lambda r: r["end_load_ratio"], default=None)
    worst_corner = max(corners, key=lambda r: r["corner_pressure_MPa"], default=None)
    summary.update(
        loaded_contacts=len(carrying),
        edge_loaded_contacts=sum(bool(r["edge_loaded"]) for r in carrying),
        end_loaded_contacts=len(ends),
        max_end_load_ratio=0.0 if worst_end is None else worst_end["end_load_ratio"],
        corner_contacts=len(corners),
        corner_contact_pressure_max_MPa=(0.0 if worst_corner is None
                                         else worst_corner["corner_pressure_MPa"]),
        corner_contact_load_max_N=max((r["corner_load_N"] for r in corners), default=0.0),
        corner_contact_at=(None if worst_corner is None else
                           f"roll {worst_corner['roll_deg']:.2f} deg pair {worst_corner['pair']} "
                           f"({worst_corner['corner_at']})"),
        edge_pressure_note=_edge_note(breaks.curved))
    count = f"of {len(carrying)} contacts carrying load"
    result.checks.append(Check(
        "loaded contact: no end loading at the face ends", not ends,
        f"{len(ends)} {count} end-loaded; largest end load ratio "
        + ("0" if worst_end is None else
           f"{worst_end['end_load_ratio']:.2f} at roll {worst_end['roll_deg']:.2f} deg pair "
           f"{worst_end['pair']}") + f" (end-loaded above {END_LOAD_RATIO:g})"
        + ("; a lead crown, or a worm wheel cut by an oversized hob, keeps the load off the "
           "face ends" if ends else "")))
    result.checks.append(Check(
        "loaded contact: no corner contact at a tip, root or form edge", not corners,
        f"{len(corners)} {count} on an edge of the profile"
        + ("" if worst_corner is None else
           f"; highest {worst_corner['corner_pressure_MPa']:.0f} MPa "
           + ("on the rounded edge" if worst_corner["corner_at"] in rounded
              else f"averaged over {EDGE_STRIP} mm")
           + f" ({worst_corner['corner_at']}) carrying {worst_corner['corner_load_N']:.0f} N "
           f"at roll {worst_corner['roll_deg']:.2f} deg pair {worst_corner['pair']}, "
           + (f"the flank's peak there {worst_corner['flank_p_max_MPa']:.0f} MPa; "
              if worst_corner["flank_p_max_MPa"] > 0.0 else
              "a contact wholly on the edge (none of it on the flank); ")
           + ("a larger rounding or a chamfer of the tip edge, or a hob oversize that keeps "
              "the pattern off it, relieves it" if breaks.curved else
              "tip relief removes it (summary recommended_tip_relief where the kind gives "
              "one)"))))


def _edge_note(curved: bool) -> str:
    """What the edge figures mean (the summary's edge_pressure_note); `curved`: a worm
    set's contact lines, crossing the edges, judged by their line load."""
    from ..contact.edge_loads import (
        CORNER_REACH,
        EDGE_LEAST_SHARE,
        EDGE_NEIGHBOURHOOD,
        EDGE_PRESSURE_RATIO,
        EDGE_STRIP,
        END_LOAD_RATIO,
    )

    pressures = (f"edge_pressure_MPa is the pressure averaged over a {EDGE_STRIP} mm strip at "
                 "a sharp edge, the largest on the rounding at a rounded tip (a smooth "
                 "surface: Hertz on its radius); flank_p_max_MPa the active flank's peak more "
                 f"than {EDGE_STRIP} mm inside its edges, off the tip roundings"
                 + ("" if curved else " and off a corner contact's whole footprint (the "
                    "flank within its half-width of the rounding)")
                 + "; bem_p_max_MPa the larger of edge and flank: both converge as the grid "
                 "is refined; bem_raw_peak_MPa, the largest cell pressure, grows without bound "
                 "at a sharp edge and is not a design value; free face ends are "
                 "quarter-spaces (mirror-pressure correction). ")
    if curved:
        verdicts = ("The contact lines curve and cross the edges: each edge is judged by the "
                    f"line load in the {EDGE_STRIP} mm strip at it (its rounding included) "
                    f"over the line's mean over the next {EDGE_NEIGHBOURHOOD:g} mm inward (the "
                    "edge's own effect, not the line's trend), the line followed by the "
                    "load's centroids "
                    "(end_load_ratio at the face ends, edge_load_ratio at the tip, root and "
                    "form edges). Of the contacts that carry load (loaded_contacts), one is "
                    f"end_loaded when its end_load_ratio exceeds {END_LOAD_RATIO:g}, a "
                    f"corner_contact when its edge_load_ratio exceeds {END_LOAD_RATIO:g} or "
                    f"its load lies within {CORNER_REACH:g} mm of a tip, root or form edge "
                    "alone (corner_pressure_MPa, corner_load_N at that edge), edge_loaded when "
                    "either")
    else:
        verdicts = ("Of the contacts that carry load (loaded_contacts), one is end_loaded "
                    "when its load per mm of face in the strip at a face end exceeds "
                    f"{END_LOAD_RATIO:g} times its mean over its length in contact "
                    "(end_load_ratio: what a lead crown is for), a corner_contact when a tip, "
                    f"root or form edge presses harder than {EDGE_PRESSURE_RATIO:g} times its "
                    "flank's peak (a tip entering mesh on its rounding: what tip relief is "
                    "for; corner_pressure_MPa, corner_load_N on its footprint), edge_loaded "
                    "when either")
    return (pressures + verdicts + f"; contacts carrying under {EDGE_LEAST_SHARE:.0%} of their "
            "position's load are judged by neither")


#: the per-contact keys of the stresses below it (subsurface_sections)
SUBSURFACE_KEYS = ("subsurface_shear_max_MPa", "subsurface_shear_depth_mm",
                   "subsurface_von_mises_max_MPa", "subsurface_von_mises_depth_mm")
#: the contacts whose stresses below can decide: this many largest by each of
#: DECIDING_FIGURES, and every edge-loaded one (deciding_contacts)
DECIDING_EACH = 3
DECIDING_FIGURES = ("bem_p_max_MPa", "flank_p_max_MPa", "bem_raw_peak_MPa", "bem_load_N")


def deciding_contacts(rows: list[dict], solved: list[int]) -> list[int]:
    """The solved contacts (indices into `rows`) whose stresses below can be the cycle's
    largest: the DECIDING_EACH largest by each of DECIDING_FIGURES (peak pressures, the
    largest cell pressure, the load) and every edge-loaded one (a corner or end-loaded
    contact puts its largest stress near the surface, whatever its load). On the bundled
    cases no other contact's shear or von Mises maximum exceeds theirs (tests)."""
    chosen = {k for k in solved if rows[k].get("edge_loaded")}
    for figure in DECIDING_FIGURES:
        chosen.update(sorted(solved, key=lambda k: -(rows[k].get(figure) or 0.0))
                      [:DECIDING_EACH])
    return sorted(chosen)


def subsurface_sections(result: Result, wanted: bool | str | None,
                        poisson: tuple[float, float]) -> None:
    """The stresses below the loaded contacts that can decide (deciding_contacts; every
    solved one where `wanted` is "all"), in the body of each Poisson's ratio (the larger
    where they differ; contact.subsurface): per row the largest principal shear
    (σ1 - σ3)/2 and von Mises stress and their depths (None for a contact not computed or
    without a loaded solution), and the largest over the cycle in the summary with how
    many contacts were computed. `wanted`: the case's `[analysis] subsurface` (None: yes,
    the deciding contacts)."""
    if wanted is False or not result.loaded:
        return
    from ..contact.subsurface import peak
    from ..parallel import parallel_map

    rows = result.sections["positions"]
    solved = [k for k, contact in enumerate(result.loaded) if contact is not None]
    every = wanted == "all"
    if not every:
        solved = deciding_contacts(rows, solved)
    ratios = sorted(set(poisson))

    def task(i: int):
        s = result.loaded[solved[i]].solution
        peaks = [peak(s.pressure_MPa, s.dx_mm, s.dy_mm, nu) for nu in ratios]
        return max((p for p in peaks if p is not None), key=lambda p: p.shear_MPa,
                   default=None)

    start = time.perf_counter()
    found = dict(zip(solved, parallel_map(task, len(solved))))
    log.info("stresses below %d contacts in %.2f s", len(solved), time.perf_counter() - start)
    for k, row in enumerate(rows):
        p = found.get(k)
        row.update(dict(zip(SUBSURFACE_KEYS, (None,) * 4)) if p is None else {
            "subsurface_shear_max_MPa": p.shear_MPa, "subsurface_shear_depth_mm": p.shear_depth_mm,
            "subsurface_von_mises_max_MPa": p.von_mises_MPa,
            "subsurface_von_mises_depth_mm": p.von_mises_depth_mm})
    answered = [r for r in rows if r["subsurface_shear_max_MPa"] is not None]
    if not answered:
        return
    worst = max(answered, key=lambda r: r["subsurface_shear_max_MPa"])
    worst_vm = max(answered, key=lambda r: r["subsurface_von_mises_max_MPa"])
    result.sections["summary"].update(
        subsurface_shear_max_MPa=worst["subsurface_shear_max_MPa"],
        subsurface_shear_depth_mm=worst["subsurface_shear_depth_mm"],
        subsurface_shear_at=f"roll {worst['roll_deg']:.2f} deg pair {worst['pair']}",
        subsurface_von_mises_max_MPa=worst_vm["subsurface_von_mises_max_MPa"],
        subsurface_von_mises_depth_mm=worst_vm["subsurface_von_mises_depth_mm"],
        subsurface_contacts=len(answered),
        subsurface_note=("the stresses below every loaded contact" if every else
                         "the stresses below the loaded contacts that can decide (the "
                         f"{DECIDING_EACH} largest by peak pressure, flank pressure, cell "
                         "pressure and load, and every edge-loaded one: "
                         "subsurface_contacts; the other rows' are not computed)")
                        + " in an elastic half-space "
                        "under its solved pressure (frictionless; Boussinesq's point load "
                        "summed over the pressure cells by FFT): subsurface_shear_max_MPa the "
                        "largest principal shear (σ1 - σ3)/2 and its depth, "
                        "subsurface_von_mises_max_MPa the largest von Mises stress and its "
                        "depth; a smooth contact's lies near 0.3 of its peak pressure, 0.5-0.8 "
                        "of its half-width deep (Hertz); a sharp edge's pressure puts a larger "
                        "one near the surface"
                        + (f"; in the body of the larger (Poisson's ratios {ratios[0]:g} and "
                           f"{ratios[1]:g})" if len(ratios) > 1 else ""))


def _reach_check(cycle, result: Result) -> None:
    """Where pairs were kept beyond the approach for the loaded contact (the cycle's reach),
    a check that no position's loaded approach D reaches a pair the cycle left out (its
    least separation on the search grid): that pair's share would be missing."""
    if not cycle.settings.reach:
        return
    rolls = sorted({r["roll_deg"] for r in cycle.rows})
    short = []
    for roll, unkept in zip(rolls, cycle.unkept_separation):
        approach = max((r["bem_approach_mm"] for r in cycle.rows
                        if r["roll_deg"] == roll and r["bem_status"] == "solved"), default=0.0)
        if approach >= unkept:
            short.append((roll, approach, unkept))
    reach_um = 1e3 * cycle.settings.reach
    result.checks.append(Check(
        "loaded contact: every tooth pair the load brings in was considered", not short,
        f"pairs within {reach_um:.1f} µm of contact were considered"
        + (f"; at roll {short[0][0]:.2f} deg the loaded approach {1e3 * short[0][1]:.1f} µm "
           f"reaches a pair {1e3 * short[0][2]:.1f} µm apart that was not: its share is "
           "missing" if short else "")))


#: the rigid pattern's edge checks: design checks where no loaded contact was solved, else
#: (kind "rigid") figures beside the loaded contact's end-loading and corner verdicts (a
#: helical contact line always reaches the face ends; a rigid ellipse's margin cannot say
#: whether its end carries load)
RIGID_PATTERN_CHECK = "contact pattern clear of the edges"


def contact_sections(cycle, loads: dict, result: Result, arm: tuple[float, str]) -> None:
    """positions, summary, ease-off and the edge checks of a contact cycle: a
    contact.cycle.ContactCycle (kept whole in result.cycle for pictures and the pressure
    solver), or the rows of an imported pair. `arm` is the radius (mm) at which the gear's
    lag is read as a length (transmission_error_um) and what that radius is."""
    from ..contact.cycle import LOAD_SHARING_RULE

    rows = cycle if isinstance(cycle, list) else cycle.rows
    for row in rows:
        row["transmission_error_um"] = 1e-3 * arm[0] * row["transmission_error_urad"]
    if not isinstance(cycle, list):
        result.cycle = cycle
    ease = None if isinstance(cycle, list) else cycle.ease_off
    if ease is not None:
        result.sections["ease_off"] = {
            "face_mm": ease.face_mm.round(4).tolist(), "radius_mm": ease.radius_mm.round(4).tolist(),
            "separation_um": [[None if not np.isfinite(s) else round(float(s) * 1e3, 3)
                               for s in line] for line in ease.separation],
            "approach_um": cycle.settings.approach * 1e3,
            "member": cycle.settings.ease_off_member}
    result.sections["positions"] = rows
    # every row of a position has its lag: the unloaded TE per position, in roll order
    per_position = {r["roll_deg"]: r["transmission_error_um"] for r in rows}
    # the rigid analysis's figures: pairs kept beyond the approach for the loaded contact
    # (rigid_contact false) touch nowhere
    rows = [r for r in rows if r.get("rigid_contact", True)]
    te = [r["transmission_error_urad"] for r in rows]
    summary = {**loads, "max_p_max_MPa": max((r["p_max_MPa"] for r in rows
                                              if math.isfinite(r["p_max_MPa"])), default=None),
               "transmission_error_peak_to_peak_urad": max(te) - min(te),
               "transmission_error_peak_to_peak_um": 1e-3 * arm[0] * (max(te) - min(te)),
               "unloaded_te_harmonics_um": mesh_harmonics(
                   [per_position[roll] for roll in sorted(per_position)]),
               "transmission_error_arm_mm": arm[0], "transmission_error_arm": arm[1],
               "face_position_range_mm": [min(r["face_position_mm"] for r in rows),
                                          max(r["face_position_mm"] for r in rows)],
               "line_contacts": sum(r["contact_model"] == "line" for r in rows),
               "area_contacts": sum(r["contact_model"] == "area" for r in rows),
               "edge_contacts": sum(r["edge_contact"] for r in rows),
               "load_sharing": LOAD_SHARING_RULE}
    for kind, label in (("face", "at the face ends (edge loading)"),
                        ("profile", "at the tip and form edges (corner contact)")):
        label = f"{RIGID_PATTERN_CHECK} {label}"
        candidates = [(v, k, r["roll_deg"]) for r in rows for k, v in r["edge_margins_mm"].items()
                      if ("end_" in k) == (kind == "face")]
        if not candidates:
            continue
        margin, edge, roll = min(candidates)
        summary[f"worst_{kind}_edge_margin_mm"], summary[f"worst_{kind}_edge"] = margin, edge
        result.checks.append(Check(label, margin >= 0,
                                   f"worst margin {margin:.3f} mm ({edge}) at roll {roll:.2f} deg"))
    result.sections["summary"] = summary
