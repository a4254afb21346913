"""Pictures of a contact analysis, rendered off-screen with pyvista (VTK): the contact
pattern on the flank as a paint pattern would show it, the pair in mesh, the pressure map.

- pattern_head_on.png / pattern_perspective.png: the pinion's flank (the worm's, the hub
  tooth's) with the ease-off coloured from 0 to the approach (the paint of a marking
  compound: the CONTACT colour at zero separation, paler up to the approach, grey beyond),
  each contact's Hertz ellipse outlined on the flank, the flank's edges drawn, and every
  edge contact (its ellipse and the edge it crosses) in the WARNING colour;
- pair.png: both bodies in mesh at one position (the teeth built here from the exact flanks,
  in numpy: no CAD kernel), the contact points and ellipses, and the misalignment, which
  may be exaggerated;
- pressure.png: the loaded contact's pressure painted on the flank, the largest over the
  mesh cycle (when the result carries `loaded`), and pressure_peak.png: the pressure of
  every pair at the position of the cycle's largest pressure.

Nothing here opens a window: pyvista.OFF_SCREEN is set, and on a Linux machine without a
display VTK is pointed at EGL. Only this module imports pyvista, and only inside functions.
PNGs are written whole or not at all (temporary file, then rename). Units: mm, µm, MPa.
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np

from .scene import (
    FLANK_BOX,
    MAX_OUTLINES,
    add_edge_labels,
    add_flank_ticks,
    add_texts,
    finish,
    fit_view,
    flank_frame,
    head_on_layout,
    lift_off_flank,
    load_pyvista,
    near_patch,
    new_plotter,
    ordinal,
    picture_title,
    refit_view,
    set_camera,
    stretcher,
    surface_props,
)
from .scene_geometry import (
    Members,
    Patch,
    cut_stretches,
    edge_contacts,
    ellipse_outlines,
    flank_normals,
    flank_patch,
    grid_surface,
    loaded_edges,
    members,
    paint_lut,
    patch_boundary,
    peak_position,
    polyline_mesh,
    pressure_on_flank,
    row_name,
)

#: picture size (pixels)
from .scene_style import (
    CONTACT,
    DRIVEN_BODY,
    DRIVER_BODY,
    INK,
    MEMBER_NAMES,
    NO_PAINT,
    OUTLINE,
    PRESSURE_CMAP,
    WARNING,
)

# ---------------------------------------------------------------------------------------
# the contact pattern


def pattern_scene(result, case=None, name: str = "", view: str = "head-on",
                  bodies: Members | None = None, patch: Patch | None = None):
    """The contact pattern on a tooth flank (the driver's; a worm set's wheel): a pyvista
    Plotter ready to screenshot. view "head-on": orthographic, along the flank's normal at
    the middle of the shown part, tip up; "perspective": from outside, the tip side and
    end A, with the member's teeth around it (`bodies`). Scene coordinates are the member's
    own frame (tooth 0)."""
    pv = load_pyvista()
    cycle = result.cycle
    patch = patch or flank_patch(cycle)
    member, flank = patch.member, patch.flank
    names = MEMBER_NAMES.get(getattr(case, "kind", ""), ("pinion", "gear"))
    owner, mate = (names[0], names[1]) if member == "pinion" else (names[1], names[0])
    approach_um = 1e3 * cycle.settings.approach
    plotter = new_plotter(pv)
    centre, normal, up, across = flank_frame(patch)
    warp, stretch = stretcher(patch, centre, up, across, view)
    plotter._scene_warp = warp
    pts = patch.points.reshape(-1, 3)
    span = float(np.ptp(pts @ across))
    lift = 2e-3 * span

    sep_um = np.where(np.isfinite(patch.separation), 1e3 * patch.separation, np.nan)
    surface = grid_surface(pv, warp(patch.points), {"separation (µm)": sep_um})
    tooth = bodies.tooth(member) if bodies is not None else None
    if view == "perspective" and tooth is not None:
        plotter.add_mesh(tooth, color=DRIVER_BODY if member == "pinion" else DRIVEN_BODY,
                         **surface_props())
        U, V = np.meshgrid(patch.u, patch.v, indexing="ij")
        with np.errstate(all="ignore"):
            n = np.nan_to_num(flank_normals(flank, U, V))
        surface.points = surface.points + 0.5 * lift * n.reshape(-1, 3, order="F")
    plotter._bar_title = (f"least separation over the mesh cycle (µm); paint where it is at "
                          f"most the approach, {approach_um:.2f} µm")
    bar = dict(title=" ", n_labels=5, fmt="%.1f", color=INK,
               position_x=0.17, position_y=0.035, width=0.62, height=0.055, title_font_size=15,
               label_font_size=14, above_label="no paint", vertical=False)
    plotter.add_mesh(surface, scalars="separation (µm)", cmap=paint_lut(pv, approach_um),
                     clim=(0.0, approach_um), above_color=NO_PAINT, nan_color=NO_PAINT,
                     scalar_bar_args=bar, interpolate_before_map=True, **surface_props())

    # the flank's edges; red along the stretch that each crossing ellipse cuts, where the
    # rigid pattern decides (without a loaded contact; its verdicts decide where solved)
    summary = result.sections.get("summary") or {}
    loaded = summary.get("loaded_contacts") is not None
    crossed = {} if loaded else edge_contacts(cycle.rows, row_name(case, member))
    edges = patch_boundary(patch)
    outlines = ellipse_outlines(cycle, member)
    for edge, line in edges.items():
        if len(line) < 2:
            continue
        lifted = warp(lift_off_flank(flank, line, lift))
        plotter.add_mesh(pv.lines_from_points(lifted), color=INK, line_width=2, lighting=False)
        cut = [] if loaded else [
            lifted[i0:i1 + 1] for i0, i1 in cut_stretches(
                cycle.rows, row_name(case, member), edge, line, outlines, 0.01 * span)]
        mesh = polyline_mesh(pv, cut)
        if mesh is not None:
            plotter.add_mesh(mesh, color=WARNING, line_width=7, lighting=False)
    add_edge_labels(plotter, edges, centre, 0.035 * span, set(crossed), warp)
    if view == "head-on":
        add_flank_ticks(plotter, edges, centre, 0.02 * span, warp)

    # the ellipses: every flagged contact's (the loaded contact's edge-loaded ones where it
    # was solved, else the rigid pattern's edge contacts), and of the others every n-th (at
    # most MAX_OUTLINES)
    edge_rows = np.array([bool(r.get("edge_loaded")) if loaded else bool(r["edge_contact"])
                          for r in cycle.rows])
    near = near_patch(patch, outlines) & np.array([r.get("rigid_contact", True)
                                                    for r in cycle.rows])
    plain, cut = np.flatnonzero(~edge_rows & near), np.flatnonzero(edge_rows & near)
    every = max(1, math.ceil(len(plain) / MAX_OUTLINES), math.ceil(len(cut) / MAX_OUTLINES))
    outlined, cut_outlined = np.zeros(len(cycle.rows), bool), np.zeros(len(cycle.rows), bool)
    outlined[plain[::every]] = True
    cut_outlined[cut[::every]] = True
    if len(cut) and not loaded:      # the deepest cut is always drawn
        cut_outlined[min(cut, key=lambda k: cycle.rows[k]["edge_margin_mm"] or 0.0)] = True
    for rows, color, width, opacity in ((outlined, OUTLINE, 1.0, 0.6),
                                        (cut_outlined, WARNING, 2.0, 1.0)):
        lines = [warp(lift_off_flank(flank, outlines[k], 1.5 * lift))
                 for k in np.flatnonzero(rows & near)]
        mesh = polyline_mesh(pv, lines)
        if mesh is not None:
            plotter.add_mesh(mesh, color=color, line_width=width, opacity=opacity,
                             lighting=False)

    positions = len({r["roll_deg"] for r in cycle.rows})
    touching = sum(r.get("rigid_contact", True) for r in cycle.rows)
    what = (f"contact pattern on the {owner}'s flank: "
            + ("looking at it head-on" if view == "head-on" else "perspective"))
    legend = [f"paint: the flank's least separation from the {mate} over the mesh cycle "
              f"({positions} positions)",
              (f"outlines: the Hertz ellipse (a contact line: the line) of each of the "
               f"{touching} contacts" if every == 1 else
               f"outlines: the Hertz ellipse (a contact line: the line) of every "
               f"{ordinal(every)} of the {touching} contacts")
              + (" (red: edge-loaded under load)" if loaded else
                 " (red: edge contacts, the deepest cut always)")]
    if patch.cropped:
        legend.append("the part of the flank near the pattern")
    if stretch > 1.05:
        legend.append(f"NOTE: the profile direction is drawn {stretch:.1f} times its scale "
                      "(a long, shallow flank)")
    warnings = []
    if loaded and summary.get("edge_loaded_contacts"):
        of = f"of {summary['loaded_contacts']} contacts carrying load"
        if summary.get("end_loaded_contacts"):
            warnings.append(f"END LOADING (red): {summary['end_loaded_contacts']} {of}, end "
                            f"load ratio up to {summary['max_end_load_ratio']:.2f}")
        if summary.get("corner_contacts"):
            warnings.append(f"CORNER CONTACT (red): {summary['corner_contacts']} {of}, up to "
                            f"{summary['corner_contact_pressure_max_MPa']:.0f} MPa at "
                            f"{summary['corner_contact_at']}")
    if crossed:
        prefix = row_name(case, member) + "_"
        cutting = sum(any(k.startswith(prefix) and m is not None and m < 0
                          for k, m in (r.get("edge_margins_mm") or {}).items()) for r in cycle.rows)
        warnings.append(f"EDGE CONTACT (red): {cutting} contacts cross the "
                        + ", ".join(f"{e.replace('_', ' ')} ({m:+.3f} mm)" for e, m in crossed.items()))
    other = {} if loaded else edge_contacts(
        cycle.rows, row_name(case, "gear" if member == "pinion" else "pinion"))
    if other:
        warnings.append(f"and the {mate}'s " + ", ".join(
            f"{e.replace('_', ' ')} ({m:+.3f} mm)" for e, m in other.items()))
    add_texts(plotter, picture_title(case, name, what), legend, warnings)

    # the picture holds the flank and the ellipses, these cut off at a third of the flank's
    # size beyond it (an edge contact's ellipse may reach far off the face)
    shown = outlines[near].reshape(-1, 3)
    if len(shown) and view != "head-on":
        lo, hi = pts.min(axis=0), pts.max(axis=0)
        reach = 0.1 * (hi - lo).max()
        shown = np.clip(shown, lo - reach, hi + reach)
        pts = np.concatenate([pts, shown[np.isfinite(shown).all(axis=1)]])
    pts = warp(pts)
    if view == "head-on":
        head_on_layout(plotter, pts, centre, normal, up, stretch)
    else:
        direction = normal + 0.5 * up - 0.8 * across
        target = pts if tooth is None or patch.cropped else np.concatenate(
            [pts, np.asarray(tooth.points)[::5]])
        focus, half = fit_view(target, centre, direction, up, 1.0, FLANK_BOX)
        set_camera(plotter, focus, direction, up, half)
        refit_view(plotter, target, FLANK_BOX)
    return plotter


# ---------------------------------------------------------------------------------------
# the pair in mesh


def position_rows(rows: list[dict], position: int | None) -> tuple[int, list[int]]:
    """The mesh position to show (index into the sorted roll angles; default the one nearest
    roll 0) and the rows (contacts) at it."""
    rolls = sorted({r["roll_deg"] for r in rows})
    if position is None:
        position = int(np.argmin(np.abs(rolls)))
    if not -len(rolls) <= position < len(rolls):
        from ..case import CaseError

        raise CaseError(f"--position: {position} is not a mesh position of the cycle "
                        f"(0 to {len(rolls) - 1})")
    roll = rolls[position]
    return position % len(rolls), [k for k, r in enumerate(rows) if r["roll_deg"] == roll]


def _nominal_mesh(case, parts):
    """The same set without misalignment (frames to measure the misalignment against), from
    the members the analysis generated."""
    from ..surfaces.placement import WormMesh

    if case.kind == "spur":
        return parts.placed()
    if case.kind == "spline":
        from ..gearset import GearPair

        return GearPair(parts.hub, parts.sleeve, parts.hub_modifications,
                        parts.sleeve_modifications, 0.0, case.pressure_angle).placed()
    flank = case.load.flank if getattr(case, "load", None) is not None else "left"
    return WormMesh(parts.wheel[flank])


def _rotation_power(R: np.ndarray, n: float) -> np.ndarray:
    """R^n for a rotation matrix: its axis, n times its angle."""
    from scipy.spatial.transform import Rotation

    return Rotation.from_rotvec(n * Rotation.from_matrix(R).as_rotvec()).as_matrix()


def exaggerated_frame(pinion, gear, pinion0, gear0, factor: float):
    """The driven member's frame with its misalignment relative to the driver multiplied
    by `factor`: the placed frames `pinion`, `gear` are compared with the nominal ones
    `pinion0`, `gear0` at the same roll and lag; the driver stays where it is. Frames of a
    batch of one. (A rigid motion to the power `factor`: its rotation's angle and its
    translation times `factor`, exact for the small motions of a misalignment.)"""
    from ..surfaces.placement import Frame

    def relative(p, g):  # g in p's coordinates
        return p.R[0].T @ g.R[0], p.R[0].T @ (g.origin[0, 0] - p.origin[0, 0])

    R1, t1 = relative(pinion, gear)
    R0, t0 = relative(pinion0, gear0)
    dR = R1 @ R0.T
    dt = t1 - dR @ t0
    Rn = _rotation_power(dR, factor)
    R = pinion.R[0] @ (Rn @ R0)
    origin = pinion.R[0] @ (Rn @ t0 + factor * dt) + pinion.origin[0, 0]
    return Frame(R[None], origin[None, None])


def _placed(body, frame):
    out = body.copy()
    out.points = frame.to_world(np.asarray(body.points)[None])[0]
    if "Normals" in out.point_data:
        out.point_data["Normals"] = frame.vectors_to_world(
            np.asarray(body.point_data["Normals"])[None])[0]
    return out


def _misalignment_text(case) -> str:
    m = getattr(case, "misalignment", None)
    if m is None:
        return ""
    if isinstance(m, (int, float)):
        return f"misalignment {m:.3g} rad" if m else ""
    parts = []
    for key, value in m.model_dump().items():
        if isinstance(value, (int, float)) and not isinstance(value, bool) and value:
            unit = "mm" if any(w in key for w in ("distance", "shift", "mount")) else "rad"
            parts.append(f"{key.replace('_', ' ')} {value:.3g} {unit}")
    return ("misalignment: " + ", ".join(parts)) if parts else ""


def _module_of(case) -> float:
    value = getattr(case, "module_mm", None)
    if value:
        return float(value)
    worm = getattr(case, "worm", None)
    if worm is not None:
        return float(worm.axial_module or worm.normal_module or 2.0)
    return 2.0


def pair_scene(result, case, name: str = "", position: int | None = None,
               exaggerate: float = 1.0, bodies: Members | None = None):
    """Both members in mesh at one position of the cycle (the driven one see-through), the
    contact points and Hertz ellipses there, and the misalignment, multiplied by
    `exaggerate` when asked."""
    pv = load_pyvista()
    cycle = result.cycle
    bodies = bodies or members(pv, case.kind, result.parts)
    index, ks = position_rows(cycle.rows, position)
    # the pairs in contact (pairs kept only for the loaded contact have no ellipse)
    ks = [j for j in ks if cycle.rows[j].get("rigid_contact", True)]
    k = max(ks, key=lambda j: cycle.rows[j]["p_max_MPa"])
    row = cycle.rows[k]
    plotter = new_plotter(pv)
    pinion_frame = cycle.pinion_frames[np.array([k])]
    gear_frame = cycle.gear_frames[np.array([k])]
    if exaggerate != 1.0:
        from ..surfaces.placement import Frame

        mesh0 = _nominal_mesh(case, result.parts)
        phi, delta = math.radians(row["roll_deg"]), row["transmission_error_urad"] * 1e-6
        p0 = Frame.stack([mesh0.pinion_frame(phi, row["pair"])])
        g0 = Frame.stack([mesh0.gear_frame(phi, row["pair"], delta)])
        gear_frame = exaggerated_frame(pinion_frame, gear_frame, p0, g0, exaggerate)
    driver, driven = _placed(bodies.driver, pinion_frame), _placed(bodies.driven, gear_frame)
    plotter.add_mesh(driver, color=DRIVER_BODY, **surface_props())
    plotter.add_mesh(driven, color=DRIVEN_BODY, **surface_props(opacity=0.35))

    m = _module_of(case)
    outlines = ellipse_outlines(cycle, "pinion")
    warn = False
    for j in ks:
        world = cycle.pinion_frames[np.array([j])].to_world(outlines[j][None])[0]
        world = world + 0.01 * m * cycle.planes.normal[j]
        bad = bool(cycle.rows[j]["edge_contact"])
        warn |= bad
        plotter.add_mesh(pv.lines_from_points(world), color=WARNING if bad else CONTACT,
                         line_width=5, lighting=False)
        plotter.add_mesh(pv.Sphere(radius=0.1 * m, center=cycle.planes.point[j]),
                         color=WARNING if bad else CONTACT, smooth_shading=True)
    names = MEMBER_NAMES.get(case.kind, ("pinion", "gear"))
    what = (f"{names[0]} and {names[1]} ({names[1]} see-through) in mesh at roll "
            f"{row['roll_deg']:.2f}°, position {index} of 0-"
            f"{len({r['roll_deg'] for r in cycle.rows}) - 1}")
    legend = [f"{len(ks)} contact(s): dot = contact point, outline = Hertz ellipse "
              f"(largest: a = {row['a_mm']:.2f} mm, b = {row['b_mm']:.3f} mm, "
              f"p = {row['p_max_MPa']:.0f} MPa)"]
    text = _misalignment_text(case)
    if text:
        legend.append(text + (f", shown ×{exaggerate:g}" if exaggerate != 1.0 else ""))
    add_texts(plotter, picture_title(case, name, what), legend,
           ["red: edge contact"] if warn else [])
    scene = np.concatenate([np.asarray(driver.points)[::3], np.asarray(driven.points)[::3]])
    _pair_camera(plotter, case, cycle.planes.point[k], cycle.planes.normal[k],
                 pinion_frame, gear_frame, m, scene)
    return plotter


#: a helical pair's view direction: the contact normal's part to the axis's (see _pair_camera)
HELICAL_OBLIQUE = 1.6


def _pair_camera(plotter, case, focus, normal, pinion_frame, gear_frame, m: float,
                 scene: np.ndarray, oblique: float = 0.35):
    """A view of the mesh through the see-through driven member. Gears and splines: from
    the driver's end B, a little from the driven side; worm sets: along the wheel's axis,
    the worm below and the wheel above. The part of `scene` (points) within reach of the
    focus fills the window below the text."""
    axis = pinion_frame.R[0][:, 2]
    radial = focus - pinion_frame.origin[0, 0]
    radial = radial - axis * np.dot(radial, axis)
    radial /= np.linalg.norm(radial)
    if case.kind == "worm":
        wheel_axis = gear_frame.R[0][:, 2]
        # from the side of the wheel's mid-plane where the contact is: not through the worm
        offset = np.dot(focus - pinion_frame.origin[0, 0], wheel_axis)
        side = 1.0 if (offset if abs(offset) > 1e-6 else np.dot(wheel_axis, normal)) >= 0 else -1.0
        toward = 1.0 if np.dot(axis, normal) >= 0 else -1.0     # the loaded flank's side
        radial = gear_frame.origin[0, 0] - pinion_frame.origin[0, 0]   # toward the wheel
        radial = radial - axis * np.dot(radial, axis)
        radial /= np.linalg.norm(radial)
        direction = side * wheel_axis + 0.3 * radial + 0.3 * toward * axis
        reach, centre = np.inf, focus              # the whole worm and the wheel's sector
    elif case.kind == "spline":                  # the whole end view
        direction = axis + 0.3 * normal + 0.3 * radial
        reach, centre = np.inf, focus
    else:
        # a helical pair's contact lines run across the face: seen from nearer the contact
        # normal, through the driven member, they lie on the flank (from the end they are
        # edge-on)
        if getattr(case, "helix_angle", 0.0):
            oblique = max(oblique, HELICAL_OBLIQUE)
        direction = axis + oblique * normal + 0.25 * radial
        reach = 7.0 * m
        centre = focus
    near = scene[np.linalg.norm(scene - centre, axis=1) < reach]
    near = near if len(near) else scene
    box = (0.02, 0.02, 0.98, 0.86)
    target, half = fit_view(near, centre, direction, radial, 1.02, box)
    set_camera(plotter, target, direction, radial, half)
    refit_view(plotter, near, box, margin=1.04)


def pressure_scene(result, case=None, name: str = "", patch: Patch | None = None,
                   roll: float | None = None):
    """The loaded contact painted on the pattern's flank, head-on: the largest pressure at
    each point over the cycle, or (`roll`, deg) the pressure of every pair at that one
    position. The colour scale is the flank's: it tops out at the largest active-flank
    pressure of the rows shown (flank_p_max_MPa), so that the flank's own pattern spans
    it; what an edge or corner contact presses above it is painted in the warning red
    and named with its value (bem_p_max_MPa, which leaves out the singular cells at a
    sharp edge). Rows without a flank figure take the design pressure's scale."""
    pv = load_pyvista()
    cycle = result.cycle
    patch = patch or flank_patch(cycle)
    flank = patch.flank
    shown_rows = [k for k, r in enumerate(cycle.rows) if roll is None or r["roll_deg"] == roll]
    loaded = [item if k in shown_rows else None for k, item in enumerate(result.loaded or [])]
    points, pressure = pressure_on_flank(cycle, loaded, patch)
    plotter = new_plotter(pv)
    centre, normal, up, across = flank_frame(patch)
    warp, stretch = stretcher(patch, centre, up, across, "head-on")
    plotter._scene_warp = warp
    span = float(np.ptp(patch.points.reshape(-1, 3) @ across))
    lift = 2e-3 * span
    design = [cycle.rows[k]["bem_p_max_MPa"] for k in shown_rows
              if cycle.rows[k].get("bem_p_max_MPa")]
    peak_design = max(design) if design else float(np.percentile(pressure[pressure > 0], 99)) \
        if (pressure > 0).any() else 1.0
    on_flank = [cycle.rows[k]["flank_p_max_MPa"] for k in shown_rows
                if cycle.rows[k].get("flank_p_max_MPa")]
    top = min(max(on_flank), peak_design) if on_flank else peak_design
    above = peak_design > FLANK_SCALE_MARGIN * top
    top = top if above else peak_design
    shown = np.where(pressure > 0, pressure, np.nan)
    surface = grid_surface(pv, warp(points), {"pressure (MPa)": shown})
    plotter._bar_title = ("largest contact pressure over the mesh cycle (MPa)" if roll is None
                          else f"contact pressure at roll {roll:.2f} deg (MPa)")
    bar = dict(title=" ", n_labels=5,
               fmt="%.0f", color=INK, position_x=0.17, position_y=0.035, width=0.62,
               height=0.055, title_font_size=15, label_font_size=14, vertical=False,
               above_label="edge, corner" if above else "above")
    plotter.add_mesh(surface, scalars="pressure (MPa)", cmap=PRESSURE_CMAP, clim=(0.0, top),
                     nan_color=NO_PAINT, above_color=WARNING if above else "#fde725",
                     scalar_bar_args=bar, **surface_props())
    crossed = edge_contacts([cycle.rows[k] for k in shown_rows], row_name(case, patch.member))
    edges = patch_boundary(patch)
    for line in edges.values():
        if len(line) < 2:
            continue
        plotter.add_mesh(pv.lines_from_points(warp(lift_off_flank(flank, line, lift))), color=INK,
                         line_width=2, lighting=False)
    add_edge_labels(plotter, edges, centre, 0.035 * span, set(), warp)
    add_flank_ticks(plotter, edges, centre, 0.02 * span, warp)
    names = MEMBER_NAMES.get(getattr(case, "kind", ""), ("pinion", "gear"))
    owner = names[0] if patch.member == "pinion" else names[1]
    solved = sum(item is not None for item in loaded)
    peak = max((cycle.rows[k].get("bem_raw_peak_MPa") or 0.0 for k in shown_rows), default=0.0)
    legend = [f"the largest pressure at each point over the {solved} loaded contacts of the "
              f"cycle; design peak {peak_design:.0f} MPa" if roll is None else
              f"the {solved} loaded contact{'s' if solved != 1 else ''} at roll {roll:.2f} "
              f"deg, the position of the cycle's largest pressure: peak {peak_design:.0f} MPa"]
    if above:
        legend.append(f"the scale is the flank's (its largest {top:.0f} MPa); red: an edge or "
                      "corner contact above it")
    if stretch > 1.05:
        legend.append(f"NOTE: the profile direction is drawn {stretch:.1f} times its scale")
    if peak > peak_design * 1.001:
        legend.append(f"(cells at a sharp edge reach {peak:.0f} MPa: singular, "
                      "not a design value)")
    edges_loaded = loaded_edges(cycle, shown_rows)
    warnings = []
    if edges_loaded:
        sections = {member: result.sections.get(member) or {} for member in ("pinion", "gear")}
        rounded = ({f"{m}_tip" for m, s in sections.items() if s.get("tip_edge_radius_mm")}
                   | {f"{m}_end_{end}" for m, s in sections.items() if s.get("end_chamfer_mm")
                      for end in "AB"})
        said = dict(zip(("pinion", "gear"), names))         # a spline's hub and sleeve

        def edge_words(edge: str) -> str:
            member, _, rest = edge.partition("_")
            return f"{said.get(member, member)} {rest.replace('_', ' ')}".strip()

        warnings.append("EDGE LOAD: " + ", ".join(
            f"{edge_words(e)} {p:.0f} MPa" + (" on its rounded edge" if e in rounded
                                              else "")
            for e, p in edges_loaded.items())
            + (" (sharp edges averaged over the edge strip)"
               if set(edges_loaded) - rounded else ""))
    if crossed:
        warnings.append("Hertz ellipses cross the " + ", ".join(
            e.replace("_", " ") for e in crossed))
    add_texts(plotter, picture_title(case, name, f"loaded contact on the {owner}'s flank, head-on"
                                       + ("" if roll is None else f", at roll {roll:.2f} deg")),
           legend, warnings)
    head_on_layout(plotter, warp(patch.points.reshape(-1, 3)), centre, normal, up, stretch)
    return plotter


#: a pressure map's scale is the flank's where the design peak (an edge or corner contact)
#: lies more than this factor above the flank's largest pressure; nearer, the design peak's
FLANK_SCALE_MARGIN = 1.05


# ---------------------------------------------------------------------------------------
# a pair without a contact analysis


def geometry_scene(case, parts, name: str = "", bodies: Members | None = None):
    """The members of a spur, spline or worm case without a load (`parts`, as its analysis
    generated them), placed in mesh at roll 0 (nominal, no lag)."""
    pv = load_pyvista()
    from ..surfaces.placement import Frame

    bodies = bodies or members(pv, case.kind, parts)
    mesh = _nominal_mesh(case, parts)
    pf, gf = Frame.stack([mesh.pinion_frame(0.0)]), Frame.stack([mesh.gear_frame(0.0)])
    plotter = new_plotter(pv)
    driver, driven = _placed(bodies.driver, pf), _placed(bodies.driven, gf)
    plotter.add_mesh(driver, color=DRIVER_BODY, **surface_props())
    plotter.add_mesh(driven, color=DRIVEN_BODY, **surface_props(opacity=0.35))
    names = MEMBER_NAMES[case.kind]
    add_texts(plotter, picture_title(case, name, f"{names[0]} and {names[1]} ({names[1]} see-through) "
                                       "in mesh, nominal position"),
           ["geometry only: the case gives no load, so there is no contact analysis"])
    m = _module_of(case)
    if case.kind == "worm":
        focus, normal = np.array([mesh.wheel.worm.reference_radius, 0.0, 0.0]), gf.R[0][:, 2]
    else:
        pitch = parts.operating_pitch_radius if case.kind == "spur" else \
            0.5 * parts.spline.pitch_diameter
        focus, normal = np.array([pitch, 0.0, 0.0]), np.array([0.0, 1.0, 0.0])
    scene = np.concatenate([np.asarray(driver.points)[::3], np.asarray(driven.points)[::3]])
    _pair_camera(plotter, case, focus, normal, pf, gf, m, scene, oblique=0.9)
    return plotter


# ---------------------------------------------------------------------------------------
# dispatch


def pictures_for(result, case, out_dir: str | Path, name: str = "", position: int | None = None,
                 exaggerate: float = 1.0) -> list[Path]:
    """Every picture that applies to a result (analyses.Result of `case`), written into
    `out_dir`: pattern_head_on.png, pattern_perspective.png and pair.png for a contact case
    (spur, spline or worm with a load), pressure.png (the largest over the cycle) and
    pressure_peak.png (at the position of the largest pressure) when the result carries the
    loaded contact; pair.png alone for a spur, spline or worm case without a load or without
    the ease-off ([analysis] ease_off = false); [] for every other kind (analytic kinds,
    imported meshes)."""
    out = Path(out_dir)
    kind = getattr(case, "kind", None)
    cycle = getattr(result, "cycle", None)
    if cycle is None and kind not in MEMBER_NAMES:
        return []
    if cycle is not None:
        position_rows(cycle.rows, position)          # a bad position fails before any write
    pv = load_pyvista()
    bodies = members(pv, kind, result.parts) if kind in MEMBER_NAMES else None
    written = []
    if cycle is None:
        written.append(finish(geometry_scene(case, result.parts, name, bodies),
                               out / "pair.png"))
        return written
    # the pattern and the pressure are painted on the ease-off: none without it
    patch = None if cycle.ease_off is None else flank_patch(cycle)
    if patch is not None:
        for view, filename in (("head-on", "pattern_head_on.png"),
                               ("perspective", "pattern_perspective.png")):
            written.append(finish(pattern_scene(result, case, name, view, bodies, patch),
                                   out / filename))
    if bodies is not None:
        written.append(finish(pair_scene(result, case, name, position, exaggerate, bodies),
                               out / "pair.png"))
    if patch is not None and getattr(result, "loaded", None) and any(
            x is not None for x in result.loaded):
        written.append(finish(pressure_scene(result, case, name, patch), out / "pressure.png"))
        roll = peak_position(cycle.rows)
        if roll is not None:
            written.append(finish(pressure_scene(result, case, name, patch, roll),
                                   out / "pressure_peak.png"))
    return written
