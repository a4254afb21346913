"""Contact over the mesh cycle of a parallel-axis pair: positions, pairs, ellipses, edges.

At each pinion roll angle over one angular pitch, the gear's lag (transmission error) is
solved so that the least separation over the tooth pairs is zero; every pair whose least
separation is within the approach is in contact (`rigid_contact`). Pairs farther apart but
within the settings' `reach` are kept too, unloaded (a tooth under load bends by more than
the approach, and a relieved tip or an entering pair then takes its share: the loaded
contact solves them); their load-dependent keys are zero. For each pair kept: the contact point, the
gap fitted in the common tangent plane (and the same from the flanks' curvatures), the
contact model under its share of the load - the Hertz ellipse where the gap is a bowl and
the ellipse fits the face, else the contact line (contact.line) with Hertz's line contact
over the length in contact - the rigid pattern at the approach, and the margins to the
edges of both flanks (negative where the pattern is cut; `edge_contact` when a face end
cuts it). Load sharing (until loaded contact is solved): the normal load is split equally
among the pairs in contact. Units: mm, N, MPa, rad.
"""

from __future__ import annotations

import logging
import math
import time
from dataclasses import dataclass, fields, replace

import numpy as np

from ..analytic.hertz import hertz_line, hertz_point
from ..surfaces.base import Flank
from ..surfaces.placement import Frame
from .ellipse import arc_to_edge, edge_margins
from .field import EaseOff, ease_off
from .line import contact_lines
from .local import TangentPlanes, analytic_gaps, face_length, fit_gaps, planes_at, tangent_planes
from .rigid_pattern import rigid_patterns
from .search import ContactPoints, lowest, refine_minima, separation, solve_transmission_error

log = logging.getLogger(__name__)

LOAD_SHARING_RULE = ("the normal load split among the tooth pairs in contact (rigid_contact): "
                     "by their lengths in contact where all are contact lines (one rigid "
                     "approach, the same stiffness per mm of line), equally otherwise")
#: how many times the separation search's grid is made twice as fine where a position has
#: no point of its pairs facing the other flank (parallel_cycle)
SEARCH_REFINEMENTS = 2
#: allowance (mm) for a pair's grid minimum lying above its true minimum
CELL_GAP = 0.02
#: gap (mm) up to which the fit patch reaches: about half the default approach, where the
#: quartic fit recovers A and B to better than 0.1 % even where the profile curvature varies fast
FIT_GAP = 0.003


#: the load-dependent keys of a row kept beyond the approach: no load, no Hertz contact, no
#: pattern, no edge reached
UNTOUCHED = {"normal_load_N": 0.0, "a_mm": 0.0, "b_mm": 0.0, "p_max_MPa": 0.0,
             "approach_mm": None, "contact_length_mm": 0.0, "edge_margin_mm": None,
             "edge_contact": False, "edge_contact_at": None, "edge_margins_mm": {}}


def mesh_positions(pitch: float, count: int, at: tuple[float, ...] | None = None
                   ) -> np.ndarray:
    """`count` driver roll angles (rad) spread evenly over one pitch (rad), 0 among them,
    or the places `at` (in steps of pitch/count from 0) instead.

    One pitch is periodic, so its two ends are one position: the angles are k·pitch/count
    for k from -(count // 2), each position once. `at` = k + 0.5 for each k puts one midway
    between each two (with them, twice the count)."""
    steps = np.arange(count) - count // 2 if at is None else np.asarray(at, float)
    return pitch * steps / count


@dataclass(frozen=True)
class CycleSettings:
    positions: int = 21
    #: the places analysed instead of the evenly spread positions, in steps of
    #: pitch/positions from roll 0 (mesh_positions); None: the evenly spread ones
    at: tuple[float, ...] | None = None
    grid: tuple[int, int] = (25, 41)      # pinion flank grid for the separation search
    approach: float = 0.00632             # mm, Litvin's rigid approach for the pattern
    fit_points: int = 21
    pairs: tuple[int, ...] = (-2, -1, 0, 1, 2)
    ease_off_grid: tuple[int, int] = (31, 61)   # flank grid of the ease-off map
    #: whose flank the ease-off is mapped on: "pinion" (the driver), or "gear" (the driven
    #: member: a worm wheel's, where a worm gear's pattern is judged)
    ease_off_member: str = "pinion"
    #: whether the ease-off is mapped at all (a sweep's samples leave it: their tables do
    #: not hold it)
    ease_off: bool = True
    field_grid: int = 201     # points per side of each contact's separation field; 0 = none
    #: whether the rows' rigid patterns are measured on those fields (field_grid also sets
    #: how finely a contact line is sampled, which they leave as it is)
    patterns: bool = True
    #: separation (mm) up to which a pair is kept, unloaded, beyond the approach: the
    #: loaded contact's candidates (0: the pairs in contact only)
    reach: float = 0.0


@dataclass(frozen=True)
class ContactCycle:
    """The contact over one mesh cycle: a result row per mesh position and tooth pair in
    contact, and what a closer look needs (pictures, the pressure solver): the flanks, each
    row's placed frames (stacked (K,)) and tangent plane, the direction of each row's A axis
    (rad from e1, the ellipse's long axis or the contact line), the centre of each row's
    pattern in its plane ((K, 2), mm along e1 and e2 from the contact point: a contact
    line's part in contact may lie to one side of it) and the ease-off of the pinion flank
    (None where the settings leave it out)."""

    rows: list[dict]
    pinion: Flank
    gear: Flank
    pinion_frames: Frame
    gear_frames: Frame
    contacts: ContactPoints
    planes: TangentPlanes
    axis_angle: np.ndarray
    pattern_centre: np.ndarray
    ease_off: EaseOff | None
    settings: CycleSettings
    #: per row, the gear's turn from its conjugate place (rad, as its frame turns: the
    #: transmission error before its sign is made a lag)
    gear_turn: np.ndarray
    #: per row, how fast the gear's lag closes the gap at its position (mm/rad, > 0; the
    #: base radius r_b2·cos(beta_b) on a parallel pair): an approach D under load adds
    #: D/turn_slope to the lag
    turn_slope: np.ndarray

    #: per row, the semi-axes (mm, along the A axis and across, about pattern_centre) of the
    #: pattern the row's pair would make under its position's equal share: the rows' Hertz
    #: ellipse or contact line, also for a pair kept beyond the approach (which carries
    #: none); the loaded contact's fields are sized on them
    pattern_semi_axes: np.ndarray
    #: per position (as phis), the least separation (mm) of the facing pairs not kept (inf
    #: where none): a loaded approach beyond it would bring in a pair the cycle left out
    unkept_separation: np.ndarray

    def contact_uv(self, member: str, k: int) -> tuple[np.ndarray, np.ndarray]:
        """Row k's contact point parameters on "pinion" or "gear", as arrays of one."""
        return (np.atleast_1d(getattr(self.contacts, f"{member}_u")[k]),
                np.atleast_1d(getattr(self.contacts, f"{member}_v")[k]))


def parallel_cycle(mesh, pinion: Flank, gear: Flank, normal_load: float,
                   C_E: float, settings: CycleSettings = CycleSettings()) -> ContactCycle:
    """One entry per mesh position and tooth pair in contact (see module docstring).

    `mesh` places the driver ("pinion": a pinion or a worm) and the driven member ("gear":
    a gear or a worm wheel): surfaces.placement.ParallelMesh or WormMesh. The search runs on
    all positions and pairs at once."""
    start = time.perf_counter()
    (u0, u1), (v0, v1) = pinion.domain
    pitch = mesh.driver_pitch
    phis = mesh_positions(pitch, settings.positions, settings.at)
    pairs = np.array(settings.pairs)
    pinion_frames = Frame.stack([[mesh.pinion_frame(phi, j) for j in pairs] for phi in phis])

    def gear_frames(p, j, delta):
        return Frame.stack([mesh.gear_frame(phis[a], pairs[b], d) for a, b, d in zip(p, j, delta)])

    P, J = np.meshgrid(np.arange(len(phis)), np.arange(len(pairs)), indexing="ij")
    P, J = P.ravel(), J.ravel()
    delta = np.zeros(len(phis))
    # the whole grid once (turning the gear shifts every separation alike, so the least ones
    # stay among the best grid points); the lag is then solved on those points only. A
    # grid too coarse for the flank (a long worm's few samples per turn) may put no point
    # of a position's pairs in front of the other flank: it is refined, SEARCH_REFINEMENTS
    # times at most, each time twice as fine along both parameters
    for refinement in range(SEARCH_REFINEMENTS + 1):
        counts = [(n - 1) * 2 ** refinement + 1 for n in settings.grid]
        grid = np.meshgrid(np.linspace(u0, u1, counts[0]), np.linspace(v0, v1, counts[1]),
                           indexing="ij")
        field = separation(pinion, gear, pinion_frames[P, J], gear_frames(P, J, delta[P]),
                           grid[0].ravel(), grid[1].ravel()).s
        best_u, best_v, best_s = lowest(field, *grid)
        facing = np.isfinite(best_s[:, 0])
        lonely = [math.degrees(phis[p]) for p in range(len(phis)) if not facing[P == p].any()]
        if not lonely:
            break
    else:
        raise ValueError(f"no tooth pair faces another at roll {lonely[0]:.3f} deg")
    half = ((u1 - u0) / (counts[0] - 1), (v1 - v0) / (counts[1] - 1))
    P, J, best_u, best_v = P[facing], J[facing], best_u[facing], best_v[facing]
    (ua, ub), (va, vb) = pinion.domain

    def pair_least(delta):
        s = separation(pinion, gear, pinion_frames[P, J], gear_frames(P, J, delta[P]),
                       best_u, best_v).s
        return np.min(np.where(np.isfinite(s), s, np.inf), axis=-1)

    def least(delta):
        out = np.full(len(phis), np.inf)
        np.minimum.at(out, P, pair_least(delta))
        return out

    delta, s_grid = solve_transmission_error(least, delta)
    # refine the pairs that may be in contact: the grid minimum can overstate a pair's
    # least separation by about the gap across one grid cell
    reach = max(settings.approach, settings.reach)
    grid_gaps = pair_least(delta) - s_grid[P]
    near = grid_gaps <= reach + CELL_GAP
    unkept = np.full(len(phis), np.inf)
    np.minimum.at(unkept, P[~near], grid_gaps[~near])
    P, J = P[near], J[near]
    near_pairs = (P, J)
    contacts = refine_minima(pinion, gear, pinion_frames[P, J], gear_frames(P, J, delta[P]),
                             best_u[near, 0], best_v[near, 0], half)
    # the lag on the refined minimum (a little below the best grid point)
    s_min = np.full(len(phis), np.inf)
    np.minimum.at(s_min, P, contacts.s)
    slope = _lag_slope(mesh, pinion, gear, phis, pairs, P, J, delta, contacts)
    delta -= s_min / slope
    gaps = contacts.s - s_min[P]
    keep = np.lexsort((pairs[J], P))
    far = keep[gaps[keep] > reach]
    np.minimum.at(unkept, P[far], gaps[far])
    keep = keep[gaps[keep] <= reach]
    P, J = P[keep], J[keep]
    touching = gaps[keep] <= settings.approach
    share = normal_load / np.bincount(P[touching], minlength=len(phis))[P]
    pf, gf, contacts = pinion_frames[P, J], gear_frames(P, J, delta[P]), _take(contacts, keep)
    with np.errstate(all="ignore"):
        # the transmission error as a lag: positive where the gear trails its conjugate place
        lag = -np.sign(slope[P]) * delta[P]
        rows, planes, angle, centre = _pair_results(pinion, gear, pf, gf, np.degrees(phis[P]), pairs[J],
                                            lag, contacts, gaps[keep], share, C_E, settings)
        _split_by_length(rows, P, touching, normal_load, C_E)
        semi_axes = np.array([[r["a_mm"], r["b_mm"]] for r in rows])
        for row, rigid in zip(rows, touching):
            row["rigid_contact"] = bool(rigid)
            if not rigid:
                row.update(UNTOUCHED)
        ease = (_ease_off(mesh, pinion, gear, phis, pairs, pinion_frames, gear_frames, delta,
                          *near_pairs, settings.ease_off_grid)
                if settings.ease_off and settings.ease_off_member == "pinion" else None)
    cycle = ContactCycle(rows, pinion, gear, pf, gf, contacts, planes, angle, centre, ease,
                         settings, delta[P], np.abs(slope[P]), semi_axes, unkept)
    if settings.ease_off and ease is None:  # the driven member's, from the cycle's placements
        cycle = replace(cycle, ease_off=_driven_ease_off(cycle, settings.ease_off_grid))
    if settings.field_grid and settings.patterns:
        for row, pattern in zip(rows, rigid_patterns(cycle, settings.field_grid)):
            row.update({"rigid_pattern_area_mm2": pattern.area,
                        "rigid_pattern_along_face_mm": pattern.along_face,
                        "rigid_pattern_across_face_mm": pattern.across_face,
                        "rigid_pattern_cut": pattern.cut})
    log.info("contact cycle: %d contacts at %d positions in %.2f s", len(rows), len(phis),
             time.perf_counter() - start)
    return cycle


def _ease_off(mesh, pinion, gear, phis, pairs, pinion_frames, gear_frames, delta, P, J, grid):
    """The pinion flank's ease-off over the pairs near contact at every position (within
    the approach and a grid cell's gap of it: where a flank point's least separation over
    the cycle comes from; the gear at the solved lag, whose final correction is below a
    micrometre and left out)."""
    turns = np.array([mesh.driver_turn(phis[p], pairs[j]) for p, j in zip(P, J)], float)
    return ease_off(pinion, gear, pinion_frames[P, J], gear_frames(P, J, delta[P]), turns, grid)


def _driven_ease_off(cycle: ContactCycle, grid: tuple[int, int]) -> EaseOff:
    """The driven member's (gear's, wheel's) ease-off: the least separation of its tooth-0
    flank from the driver over the placements of the cycle's contacts (field.ease_off with
    the roles swapped; each placement's turn is the angle of the member's frame about its
    own axis). Only the contacts' placements are used: far from the pattern the separation
    is an upper bound; within the approach it is exact."""
    frames = cycle.gear_frames
    axis, x = frames.R[:, :, 2], frames.R[:, :, 0]
    ref = x[0] - axis[0] * np.dot(x[0], axis[0])
    ref /= np.linalg.norm(ref)
    turns = np.arctan2(x @ np.cross(axis[0], ref), x @ ref)
    with np.errstate(all="ignore"):
        return ease_off(cycle.gear, cycle.pinion, frames, cycle.pinion_frames, turns, grid)


def _take(contacts: ContactPoints, index) -> ContactPoints:
    return ContactPoints(*(getattr(contacts, f.name)[index] for f in fields(ContactPoints)))


def _profile_height(flank: Flank, uv) -> np.ndarray:
    """Length (mm) of the flank's profile (its u parameter line, exact arc) through the
    points uv ((K,) arrays)."""
    (u0, u1), _ = flank.domain
    return np.abs(arc_to_edge(flank, "u", np.full(len(uv[0]), u0), u1, np.asarray(uv[1])))


def _known(value) -> float | None:
    """A float for the result, None where it is not known (NaN)."""
    return float(value) if np.isfinite(value) else None


def _lag_slope(mesh, pinion, gear, phis, pairs, P, J, delta, contacts, step=1e-6) -> np.ndarray:
    """d(separation)/d(lag) (mm/rad) at each position's contact point of least separation:
    a central difference, or a one-sided one where the gear turned one way takes the
    contact off the gear flank's edge (a contact on that edge)."""
    s = np.where(np.isfinite(contacts.s), contacts.s, np.inf)
    least = np.array([np.flatnonzero(P == p)[np.argmin(s[P == p])] for p in range(len(phis))])
    u, v = contacts.pinion_u[least, None], contacts.pinion_v[least, None]
    pf = Frame.stack([mesh.pinion_frame(phis[p], pairs[J[k]]) for p, k in enumerate(least)])
    below, here, above = (separation(pinion, gear, pf, Frame.stack(
        [mesh.gear_frame(phis[p], pairs[J[k]], delta[p] + d) for p, k in enumerate(least)]),
        u, v).s[:, 0] for d in (-step, 0.0, step))
    return np.where(np.isfinite(below) & np.isfinite(above), (above - below) / (2.0 * step),
                    np.where(np.isfinite(above), (above - here) / step, (here - below) / step))


def _split_by_length(rows: list[dict], position: np.ndarray, touching: np.ndarray,
                     normal_load: float, C_E: float) -> None:
    """Where every pair in contact at a position is a contact line, the position's normal
    load split among them by their lengths in contact (one rigid approach and the same
    stiffness per mm of line give each the same line load), and their Hertz line contact
    (Johnson eqs 4.45) redone with it; an equal split put the load of a pair touching over
    a few millimetres on it as on one spanning the face (7107 MPa on a final drive)."""
    for p in np.unique(position[touching]):
        ks = np.flatnonzero((position == p) & touching)
        lengths = np.array([rows[k]["contact_length_mm"] for k in ks])
        if (len(ks) < 2 or any(rows[k]["contact_model"] != "line" for k in ks)
                or not lengths.min() > 0.0):
            continue
        for k, length in zip(ks, lengths):
            load = float(normal_load * length / lengths.sum())
            contact = hertz_line(load / length, 0.5 / rows[k]["B_analytic_per_mm"], C_E)
            rows[k].update(normal_load_N=load, b_mm=contact.b, p_max_MPa=contact.p0)


def _pair_results(pinion, gear, pf, gf, roll_deg, pairs, delta, cp: ContactPoints, gaps,
                  loads, C_E, settings):
    """The result rows of K contacts (frames stacked (K,)): the gap fitted and from the
    curvatures, the contact model (a Hertz ellipse, or a contact line: contact.line) with
    its size, pressure and edge margins, and the rigid pattern's size; with the tangent
    planes, the angles of the A axes and the centre of each contact's pattern in its plane
    ((K, 2), mm along e1 and e2: the middle of a contact line's part in contact, 0 for an
    ellipse); a contact line's face_position_mm is its middle's."""
    p_uv, g_uv = (cp.pinion_u, cp.pinion_v), (cp.gear_u, cp.gear_v)
    planes = tangent_planes(pinion, pf, *p_uv)
    analytic = analytic_gaps(pinion, gear, pf, gf, planes, p_uv, g_uv)
    A = np.array([g.A for g in analytic])
    B = np.array([g.B for g in analytic])
    angle = np.array([g.angle for g in analytic])
    face = np.minimum(face_length(pinion, p_uv), face_length(gear, g_uv))
    fit_limit = np.minimum(face_length(pinion, p_uv) / 3.0, 10.0 * np.sqrt(FIT_GAP / B))
    extent = np.stack([np.where(A > 0, np.minimum(np.sqrt(FIT_GAP / A), fit_limit), fit_limit),
                       np.sqrt(FIT_GAP / B)], axis=-1)
    fit = fit_gaps(pinion, gear, pf, gf, planes, p_uv, g_uv, extent, settings.fit_points)
    points = pinion.evaluate(p_uv[0], p_uv[1], order=1).points
    # an ellipse where the gap is a bowl and the loaded ellipse fits the face; else a line;
    # an area where even across the profile the rigid pattern outgrows the flank (conformal
    # flanks: a spline's hub and sleeve share their base circle), crowned or not, measured
    # along the face (a near-flat gap's ellipse axis is ill-conditioned)
    ellipses = [hertz_point(A[k], B[k], loads[k], C_E) if A[k] > 0 else None
                for k in range(len(A))]
    height = np.minimum(_profile_height(pinion, p_uv), _profile_height(gear, g_uv))
    area = B <= settings.approach / (0.5 * height) ** 2
    line = area | np.array([e is None or e.a > 0.5 * f for e, f in zip(ellipses, face)], bool)
    centre = np.zeros((len(A), 2))
    length = np.array([2.0 * e.a if e is not None else 0.0 for e in ellipses])
    width = np.zeros(len(A))
    margins = [dict() for _ in range(len(A))]
    along = np.flatnonzero(line)
    if along.size:
        # an area runs along the face (e1) over the whole profile height
        direction = np.where(area, 0.0, angle)
        across = np.where(area, np.maximum(B, settings.approach / (0.75 * height) ** 2), B)
        lines = contact_lines(pinion, gear, pf[along], gf[along], planes_at(planes, along),
                              (p_uv[0][along], p_uv[1][along]), (g_uv[0][along], g_uv[1][along]),
                              direction[along], gaps[along], across[along], face[along],
                              settings.approach, 2 * max(settings.field_grid, 100) + 1)
        measured = np.isfinite(lines.length)
        # a line whose field cannot be laid (its lines along the common normal miss a
        # flank: a worm wheel's tip corner) is its Hertz ellipse where it has one, else a
        # line over the shorter face
        for k in along[~measured]:
            line[k], area[k] = ellipses[k] is None, False
            length[k] = face[k] if ellipses[k] is None else length[k]
        along, lines_at = along[measured], np.flatnonzero(measured)
        length[along], width[along] = lines.length[lines_at], lines.width[lines_at]
        centre[along] = lines.centre[lines_at]
        angle = np.where(area, 0.0, angle)
        # a contact line's place on the face is its middle (on a flat line, round-off alone
        # puts the least separation anywhere along it)
        middle = planes_at(planes, along).at(centre[along, :1], centre[along, 1:])
        points = points.copy()
        points[along, 2] = pf[along].to_local(middle)[:, 0, 2]
        for k, i in zip(along, lines_at):
            margins[k] = lines.margins[i]
    point = np.flatnonzero(~line)
    found = {}
    for name, flank, frames, uv in (("pinion", pinion, pf, p_uv), ("gear", gear, gf, g_uv)):
        ends = edge_margins(flank, frames[point], planes_at(planes, point),
                            np.array([ellipses[k].a for k in point]),
                            np.array([ellipses[k].b for k in point]), angle[point],
                            uv[0][point], uv[1][point])
        found.update({f"{name}_{edge}": value for edge, value in ends.items()})
    for i, k in enumerate(point):
        margins[k] = {name: float(value[i]) for name, value in found.items()
                      if np.isfinite(value[i])}
    rows = []
    for k in range(len(A)):
        own = margins[k]
        ends = {edge: m for edge, m in own.items() if "_end_" in edge and m < 0.0}
        if area[k]:   # conformal: no Hertz; the rigid pattern at its mean pressure (none
            # where no cell of both flanks is in it: a flank turned onto an edge)
            a, b, approach = 0.5 * length[k], 0.5 * width[k], None
            area_mm2 = length[k] * width[k]
            p0 = loads[k] / area_mm2 if area_mm2 > 0.0 else math.nan
            rigid_a = 0.5 * length[k]
        elif line[k]:
            contact = hertz_line(loads[k] / length[k], 1.0 / (2.0 * B[k]), C_E)
            a, b, p0, approach = 0.5 * length[k], contact.b, contact.p0, None
            rigid_a = 0.5 * length[k]
        else:
            e = ellipses[k]
            a, b, p0, approach = e.a, e.b, e.p0, e.approach
            rigid_a = math.sqrt(settings.approach / A[k])
            # the ellipse's length on the flanks: what a face end cuts off is not in contact
            for side in ("A", "B"):
                length[k] += min([0.0] + [m for edge, m in ends.items()
                                          if edge.endswith(f"_end_{side}")])
            length[k] = max(length[k], 0.0)
        rows.append({
            "roll_deg": float(roll_deg[k]), "pair": int(pairs[k]),
            "contact_radius_pinion_mm": float(np.hypot(*points[k, :2])),
            "face_position_mm": float(points[k, 2]),
            "separation_mm": float(gaps[k]),
            "A_per_mm": _known(fit.A[k]), "B_per_mm": _known(fit.B[k]),
            "A_analytic_per_mm": float(A[k]), "B_analytic_per_mm": float(B[k]),
            "fit_rms_mm": _known(fit.rms[k]), "transmission_error_urad": float(delta[k] * 1e6),
            "normal_load_N": float(loads[k]),
            "contact_model": "area" if area[k] else "line" if line[k] else "ellipse",
            "contact_length_mm": float(length[k]),
            "a_mm": float(a), "b_mm": float(b), "p_max_MPa": float(p0),
            "approach_mm": None if approach is None else float(approach),
            "rigid_a_mm": float(rigid_a), "rigid_b_mm": math.sqrt(settings.approach / B[k]),
            "edge_margin_mm": min(own.values()) if own else None,
            "edge_contact": bool(ends),
            "edge_contact_at": min(ends, key=ends.get) if ends else None,
            "edge_margins_mm": own})
    return rows, planes, angle, centre
