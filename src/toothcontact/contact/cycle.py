"""Contact over the mesh cycle of a parallel-axis pair: positions, pairs, ellipses, edges.

At each pinion roll angle over one angular pitch, the gear's lag (transmission error) is
solved so that the least separation over the tooth pairs is zero; every pair whose least
separation is within the approach is in contact. For each of those: the contact point, the
gap fitted in the common tangent plane (and the same from the flanks' curvatures), the Hertz
ellipse under its share of the load, the rigid ellipse at the approach, and the margins to
the edges of both flanks. Load sharing (until loaded contact is solved): the normal load is
split equally among the pairs in contact. Units: mm, N, MPa, rad.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..analytic.hertz import hertz_line, hertz_point
from ..surfaces.base import Flank
from .ellipse import edge_margins
from .local import analytic_gap, fit_gap, tangent_plane
from .search import grid_minimum, refine_minimum, separation, solve_transmission_error

LOAD_SHARING_RULE = "equal split of the normal load among the tooth pairs in contact"
#: allowance (mm) for a pair's grid minimum lying above its true minimum
CELL_GAP = 0.02
#: gap (mm) up to which the fit patch reaches: about half the default approach, where the
#: quartic fit recovers A and B to better than 0.1 % even where the profile curvature varies fast
FIT_GAP = 0.003


@dataclass(frozen=True)
class CycleSettings:
    positions: int = 21
    grid: tuple[int, int] = (25, 41)      # pinion flank grid for the separation search
    approach: float = 0.00632             # mm, Litvin's rigid approach for the pattern
    fit_points: int = 21
    pairs: tuple[int, ...] = (-2, -1, 0, 1, 2)


def parallel_cycle(mesh, pinion: Flank, gear: Flank, normal_load: float,
                   C_E: float, settings: CycleSettings = CycleSettings()) -> list[dict]:
    """One entry per mesh position and tooth pair in contact (see module docstring).

    `mesh` places the driver ("pinion": a pinion or a worm) and the driven member ("gear":
    a gear or a worm wheel): assembly.ParallelMesh or assembly.WormMesh."""
    (u0, u1), (v0, v1) = pinion.domain
    grid = np.meshgrid(np.linspace(u0, u1, settings.grid[0]), np.linspace(v0, v1, settings.grid[1]),
                       indexing="ij")
    pitch = mesh.driver_pitch
    half = ((u1 - u0) / (settings.grid[0] - 1), (v1 - v0) / (settings.grid[1] - 1))
    rows, delta = [], 0.0
    for phi in np.linspace(-0.5 * pitch, 0.5 * pitch, settings.positions):
        frames = {j: mesh.pinion_frame(phi, j) for j in settings.pairs}
        # the whole grid once; the lag is then solved on each pair's best grid points only
        # (turning the gear shifts every separation alike, so the minimum stays among them)
        best = {j: found for j in settings.pairs
                if (found := grid_minimum(pinion, gear, frames[j], mesh.gear_frame(phi, j, delta),
                                          grid)) is not None}
        if not best:
            raise ValueError(f"no tooth pair faces another at roll {math.degrees(phi):.3f} deg")

        def least_at(j, phi, d):
            bu, bv, _ = best[j]
            s = separation(pinion, gear, frames[j], mesh.gear_frame(phi, j, d), bu, bv).s
            return float(np.min(s[np.isfinite(s)])) if np.isfinite(s).any() else math.inf

        def least(d, phi=phi):
            return min(least_at(j, phi, d) for j in best)

        delta, s_grid = solve_transmission_error(least, delta)
        # refine the pairs that may be in contact: the grid minimum can overstate a pair's
        # least separation by about the gap across one grid cell
        lag_shift = {j: least_at(j, phi, delta) for j in best}
        contacts = {j: refine_minimum(pinion, gear, frames[j], mesh.gear_frame(phi, j, delta),
                                      (bu[0], bv[0]), half)
                    for j, (bu, bv, _) in best.items()
                    if lag_shift[j] - s_grid <= settings.approach + CELL_GAP}
        # the lag on the refined minimum (a little below the best grid point)
        slope = _lag_slope(mesh, pinion, gear, phi, delta, contacts)
        s_min = min(cp.s for cp in contacts.values())
        delta -= s_min / slope
        in_contact = {j: cp for j, cp in contacts.items() if cp.s - s_min <= settings.approach}
        share = normal_load / len(in_contact)
        for j, cp in sorted(in_contact.items()):
            rows.append(_pair_result(mesh, pinion, gear, phi, j, delta, cp, share, C_E, settings,
                                     gap=cp.s - s_min))
    return rows


def _lag_slope(mesh, pinion, gear, phi, delta, contacts, step=1e-6) -> float:
    """d(separation)/d(lag) at the contact points (mm/rad)."""
    j, cp = min(contacts.items(), key=lambda item: item[1].s)
    u, v = np.array([cp.pinion_u]), np.array([cp.pinion_v])
    s0 = separation(pinion, gear, mesh.pinion_frame(phi, j), mesh.gear_frame(phi, j, delta), u, v).s[0]
    s1 = separation(pinion, gear, mesh.pinion_frame(phi, j), mesh.gear_frame(phi, j, delta + step),
                    u, v).s[0]
    return (s1 - s0) / step


def _pair_result(mesh, pinion, gear, phi, j, delta, cp, load, C_E, settings, gap) -> dict:
    with np.errstate(all="ignore"):
        return _pair_result_checked(mesh, pinion, gear, phi, j, delta, cp, load, C_E, settings, gap)


def _pair_result_checked(mesh, pinion, gear, phi, j, delta, cp, load, C_E, settings, gap) -> dict:
    pf, gf = mesh.pinion_frame(phi, j), mesh.gear_frame(phi, j, delta)
    p_uv, g_uv = (cp.pinion_u, cp.pinion_v), (cp.gear_u, cp.gear_v)
    plane = tangent_plane(pinion, pf, *p_uv)
    analytic = analytic_gap(pinion, gear, pf, gf, plane, p_uv, g_uv)
    # line contact: the rigid pattern would be longer than the shorter flank's face
    face = min(_face_length(pinion, p_uv), _face_length(gear, g_uv))
    line = analytic.A <= settings.approach / (0.5 * face) ** 2
    extent = (_fit_extent(analytic, pinion, p_uv), math.sqrt(FIT_GAP / analytic.B))
    fit = fit_gap(pinion, gear, pf, gf, plane, p_uv, g_uv, extent, settings.fit_points)
    row = {"roll_deg": math.degrees(phi), "pair": j,
           "contact_radius_pinion_mm": float(np.hypot(*pinion.evaluate(
               np.array([cp.pinion_u]), np.array([cp.pinion_v])).points[0, :2])),
           "face_position_mm": float(pinion.point(np.array(cp.pinion_u), np.array(cp.pinion_v))[2]),
           "separation_mm": gap,
           "A_per_mm": fit.curvature.A, "B_per_mm": fit.curvature.B,
           "A_analytic_per_mm": analytic.A, "B_analytic_per_mm": analytic.B,
           "fit_rms_mm": fit.rms, "transmission_error_urad": delta * 1e6,
           "normal_load_N": load}
    if line:
        contact = hertz_line(load / face, 1.0 / (2.0 * analytic.B), C_E)
        a, b, p0, approach = 0.5 * face, contact.b, contact.p0, float("nan")
        row["line_contact"] = True
    else:
        ellipse = hertz_point(analytic.A, analytic.B, load, C_E)
        a, b, p0, approach = ellipse.a, ellipse.b, ellipse.p0, ellipse.approach
        row["line_contact"] = False
    margins = {}
    if not line:  # a contact line has no ellipse to hold against the edges
        margins = {f"pinion_{k}": v for k, v in edge_margins(pinion, pf, plane, a, b,
                                                             analytic.angle, p_uv).items()}
        margins.update({f"gear_{k}": v for k, v in edge_margins(gear, gf, plane, a, b,
                                                                analytic.angle, g_uv).items()})
    worst = min(margins.values()) if margins else float("nan")
    row.update({"a_mm": a, "b_mm": b, "p_max_MPa": p0, "approach_mm": approach,
                "rigid_a_mm": math.sqrt(settings.approach / analytic.A) if not line else float("inf"),
                "rigid_b_mm": math.sqrt(settings.approach / analytic.B),
                "edge_margin_mm": worst, "edge_contact": bool(worst < 0.0),
                "edge_margins_mm": margins})
    return row


def _fit_extent(gap, flank: Flank, uv) -> float:
    """Half-extent (mm) of the fit patch along e1: where the gap reaches FIT_GAP, at most a
    third of the flank's face length, and at most ten times the patch's width (line contact)."""
    limit = min(_face_length(flank, uv) / 3.0, 10.0 * math.sqrt(FIT_GAP / gap.B))
    return limit if gap.A <= 0 else min(math.sqrt(FIT_GAP / gap.A), limit)


def _face_length(flank: Flank, uv) -> float:
    """Length (mm) of the flank along its v parameter at the point uv."""
    (_, _), (v0, v1) = flank.domain
    speed = np.linalg.norm(flank.evaluate(np.array([uv[0]]), np.array([uv[1]])).r_v[0])
    return float((v1 - v0) * speed)
