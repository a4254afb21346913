"""B-spline solids of cylindrical gears and splines from their exact flanks.

A cylindrical gear is lofted through transverse sections (see `loft`): in each section the
tooth outline is the exact (modified) flank, the generated root fillet (by the rack, or by a
shaper cutter for a ring; on an undercut gear the trochoid that cuts into the involute, up to
the form circle where they meet) and the tip and root arcs. `loft.flank_deviation` measures how far the flank faces stray from the exact
surface between the fitting points.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..modify import FlankModifications
from ..surfaces.base import Flank
from ..surfaces.generation import generate_ring_side, generate_side
from ..surfaces.involute import CylindricalGear
from ..surfaces.modified import ModifiedFlank
from .loft import (LoftedBody, arc, chord_parameters, generated_face, half_root_arc,
                   interpolated, loft, patterned_wire, polar, sector_closure)

#: radial thickness of a ring gear's rim below its root circle, in normal modules
RING_RIM_MODULES = 3.0


@dataclass
class GearBody(LoftedBody):
    """A built gear (flanks keyed by side +1/-1)."""

    gear: CylindricalGear | None = None


def build_gear(gear: CylindricalGear, modifications: FlankModifications | None = None,
               profile_points: int = 17, sections: int | None = None,
               teeth: int | None = None) -> GearBody:
    """B-spline solid of a cylindrical gear with `modifications` on both flanks: the whole
    gear, or a sector of `teeth` teeth (external gears)."""
    mods = modifications or FlankModifications()
    notes = []
    if gear.internal:
        generated = generate_ring_side(gear)
        notes.append(f"ring gear: root fillet cut by a {generated.cutter_teeth}-tooth "
                     "shaper cutter")
    else:
        generated = generate_side(gear)
        if generated.undercut:
            notes.append(f"undercut by its rack: the generated root cuts into the involute, "
                         f"which starts on the form circle d = {2 * generated.form_radius:.4f} mm")
    flanks = {side: _apply(gear.flank(side, generated.form_radius), mods) for side in (1, -1)}
    if sections is None:
        twist = abs(gear.twist_per_length) * gear.face_width
        curved = mods.lead_crown is not None or mods.end_relief is not None
        sections = max(7 if curved else 2, int(math.ceil(twist / 0.04)) + 1)
    (u0, u1), (v0, v1) = flanks[1].domain
    fit_u = np.linspace(u0, u1, profile_points)
    fit_v = np.linspace(v0, v1, sections)

    params = {"flank": chord_parameters(np.stack(
                  gear.flank(1, generated.form_radius).transverse_point(fit_u), -1)),
              "fillet": chord_parameters(generated.fillet)}
    wires, flank_index = [], {}
    for z in fit_v:
        wire, flank_index = _section_wire(gear, flanks, generated, params, fit_u, float(z),
                                          teeth or gear.teeth)
        wires.append(wire)
    maker = loft(wires, ruled=sections == 2)
    faces = {side: generated_face(maker, (wires[0], i)) for side, i in flank_index.items()}
    solid = maker.Shape()
    if gear.internal:
        solid = _ring_from_hole(gear, solid)
    return GearBody(solid, flanks, faces, fit_u, fit_v, gear.teeth, teeth or gear.teeth, notes,
                    gear=gear)


def _apply(flank: Flank, mods: FlankModifications) -> Flank:
    return flank if mods.empty else ModifiedFlank(flank, mods)


def _flank_section(flank: Flank, u: np.ndarray, z: float) -> np.ndarray:
    """Points of the flank in the plane z (a modification moves points off their section
    along the normal: the axial parameter is corrected until the point lies in the plane)."""
    v = np.full_like(u, z)
    for _ in range(4):
        pts = np.stack(flank.point(u, v), axis=-1)
        v = v - (pts[:, 2] - z)
    pts = np.stack(flank.point(u, v), axis=-1)
    pts[:, 2] = z
    return pts


def _fillet_section(gear: CylindricalGear, flank: Flank, generated, side: int, z: float,
                    flank_start: np.ndarray) -> np.ndarray:
    """The generated fillet of `side` in the plane z: rotated with the helix and displaced
    like the flank's form end (a lead crown moves the whole tooth side), ending exactly on
    the flank's first point."""
    mirror = np.array([1.0, side])
    turn = gear.twist_per_length * z
    c, s = math.cos(turn), math.sin(turn)
    rotation = np.array([[c, s], [-s, c]])
    pts = (generated.fillet * mirror) @ rotation
    if isinstance(flank, ModifiedFlank):
        (u0, u1), _ = flank.domain
        form_end = u1 if gear.internal else u0
        drop = float(np.asarray(flank.drop(np.array([form_end]), np.array([z])))[0])
        normals = (generated.fillet_normals * mirror) @ rotation
        pts = pts - drop * math.cos(gear.base_helix_angle) * normals
    pts = np.column_stack([pts, np.full(len(pts), z)])
    pts[-1] = flank_start
    return pts


def _section_wire(gear: CylindricalGear, flanks: dict, generated, params: dict, u: np.ndarray,
                  z: float, teeth: int):
    """The closed outline at height z of all teeth (or of a sector of `teeth` teeth closed
    toward the axis), and the positions of tooth 0's flank edges in it (side -> index).

    Each tooth runs from the centre of the space before it to the centre of the space after
    it: half root arc, fillet, flank, tip arc, flank, fillet, half root arc."""
    # each flank from its form end to its tip (u runs from the tip on a ring)
    forward = slice(None, None, -1) if gear.internal else slice(None)
    minus = _flank_section(flanks[-1], u, z)[forward]
    plus = _flank_section(flanks[1], u, z)[forward]
    f = params["flank"][forward]
    f = 1.0 - f if gear.internal else f
    g = params["fillet"]
    turn = gear.twist_per_length * z
    pitch = 2.0 * math.pi / gear.teeth
    fil_minus = _fillet_section(gear, flanks[-1], generated, -1, z, minus[0])     # root -> form
    fil_plus = _fillet_section(gear, flanks[1], generated, 1, z, plus[0])[::-1]   # form -> root
    side_minus = [interpolated(fil_minus, g), interpolated(minus, f)]
    tip = arc(minus[-1], polar(gear.tip_radius, turn, z), plus[-1])
    side_plus = [interpolated(plus[::-1], 1.0 - f[::-1]), interpolated(fil_plus, 1.0 - g[::-1])]
    start, end = fil_minus[0], fil_plus[-1]
    root = 0.5 * (np.hypot(*start[:2]) + np.hypot(*end[:2]))
    space_before, space_after = turn - 0.5 * pitch, turn + 0.5 * pitch
    edges = [half_root_arc(root, space_before, start, z), *side_minus, tip, *side_plus,
             half_root_arc(root, space_after, end, z, reverse=True)]
    flank_edges = {-1: len(side_minus), 1: len(side_minus) + 2}

    if teeth < gear.teeth and gear.internal:
        raise ValueError("a ring gear is built whole, not as a sector")
    closure = (sector_closure(root, root - 2.0 * gear.normal_module, space_before,
                              space_before + teeth * pitch, z) if teeth < gear.teeth else [])
    return patterned_wire(edges, teeth, pitch, closure), flank_edges


def _ring_from_hole(gear: CylindricalGear, hole):
    """A ring gear: a rim cylinder with the toothed hole cut out."""
    from OCP.BRepAlgoAPI import BRepAlgoAPI_Cut
    from OCP.BRepPrimAPI import BRepPrimAPI_MakeCylinder
    from OCP.gp import gp_Ax2, gp_Dir, gp_Pnt

    outer = gear.root_radius_value + RING_RIM_MODULES * gear.normal_module
    rim = BRepPrimAPI_MakeCylinder(gp_Ax2(gp_Pnt(0, 0, -0.5 * gear.face_width), gp_Dir(0, 0, 1)),
                                   outer, gear.face_width).Shape()
    cut = BRepAlgoAPI_Cut(rim, hole)
    cut.Build()
    return cut.Shape()
