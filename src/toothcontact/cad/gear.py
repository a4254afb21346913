"""B-spline solids of cylindrical gears and splines from their exact flanks.

A cylindrical gear is lofted through transverse sections (see `loft`) of its exact tooth
outline (surfaces.outline: the modified flanks, the generated root fillets, the tip and root
arcs). `loft.flank_deviation` measures how far the flank faces stray from the exact surface
between the fitting points.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..surfaces.involute import CylindricalGear
from ..surfaces.modify import FlankModifications
from ..surfaces.outline import ToothOutline
from .loft import (
    LoftedBody,
    arc,
    chord_parameters,
    fused,
    generated_face,
    half_root_arc,
    interpolated,
    loft,
    patterned_wire,
    sector_closure,
)

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
    outline = ToothOutline(gear, modifications)
    generated = outline.generated
    notes = []
    if gear.internal:
        notes.append(f"ring gear: root fillet cut by a {generated.cutter_teeth}-tooth "
                     "shaper cutter")
    elif generated.undercut:
        notes.append(f"undercut by its rack: the generated root cuts into the involute, "
                     f"which starts on the form circle d = {2 * generated.form_radius:.4f} mm")
    (u0, u1), (v0, v1) = outline.flanks[1].domain
    fit_u = outline.profile_parameters(profile_points)
    params = {"flank": chord_parameters(np.stack(
                  gear.flank(1, generated.form_radius).transverse_point(fit_u), -1)),
              "fillet": chord_parameters(generated.fillet)}
    solids, faces, fit_v = [], {1: (), -1: ()}, ()
    for z in _lead_segments(outline, sections):
        wires = []
        for height in z:
            wire, flank_index = _section_wire(outline, params, fit_u, float(height),
                                              teeth or gear.teeth)
            wires.append(wire)
        maker = loft(wires, ruled=len(z) == 2)
        for side, i in flank_index.items():
            faces[side] += (generated_face(maker, (wires[0], i)),)
        solids.append(maker.Shape())
        fit_v += (z,)
    solid = fused(solids)
    if gear.internal:
        solid = _ring_from_hole(gear, solid)
    return GearBody(solid, outline.flanks, faces, fit_u, fit_v, gear.teeth, teeth or gear.teeth,
                    notes, gear=gear)


def _lead_segments(outline: ToothOutline, sections: int | None) -> list[np.ndarray]:
    """The face width's sections (mm) for lofting, one array per segment between the
    lead's breaks (an end relief's or chamfer's start: one B-spline face per segment, so
    the loft's splines do not ring across a jump in the lead's slope or curvature):
    `sections` over the face (default: 7 on a bent lead, 2 on a straight one, or one per
    0.04 rad of helical twist); with breaks, each segment as densely, at least 5 sections
    where its lead bends (2 where it is straight: ruled), 7 on a chamfer's rounded edge."""
    gear, m = outline.gear, outline.modifications
    (_, _), (v0, v1) = outline.flanks[1].domain
    twist_rate = abs(gear.twist_per_length)
    if sections is None:
        sections = max(7 if outline.curved else 2,
                       int(math.ceil(twist_rate * gear.face_width / 0.04)) + 1)
    breaks = [b for b in m.lead_breaks(gear.face_width) if v0 < b < v1]
    if not breaks:
        return [np.linspace(v0, v1, sections)]
    bounds = [v0, *breaks, v1]
    spacing = (v1 - v0) / max(sections - 1, 1)
    straight = (m.lead_crown is None and twist_rate == 0.0
                and (m.end_relief is None or m.end_relief.shape == "linear"))
    rounded = []
    if m.end_chamfer is not None:
        _, _, start, end = m.end_chamfer.breaks(gear.face_width)
        rounded = [(start, end), (-end, -start)]
    out = []
    for low, high in zip(bounds[:-1], bounds[1:]):
        count = max(int(math.ceil((high - low) / spacing - 1e-9)) + 1, 2 if straight else 5)
        if any(math.isclose(low, a) and math.isclose(high, b) for a, b in rounded):
            count = 7
        out.append(np.linspace(low, high, count))
    return out


def _section_wire(outline: ToothOutline, params: dict, u: np.ndarray, z: float, teeth: int):
    """The closed outline at height z of all teeth (or of a sector of `teeth` teeth closed
    toward the axis), and the positions of tooth 0's flank edges in it (side -> index)."""
    gear = outline.gear
    section = outline.section(u, z)
    f = params["flank"][::-1] if gear.internal else params["flank"]
    f = 1.0 - f if gear.internal else f
    g = params["fillet"]
    side_minus = [interpolated(section.fillet_minus, g), interpolated(section.flank_minus, f)]
    start, end = section.tip_ends
    tip = [arc(start, section.tip_middle, end)]
    if section.rounding_minus is not None:
        tip = [arc(*section.rounding_minus), *tip, arc(*section.rounding_plus)]
    side_plus = [interpolated(section.flank_plus, 1.0 - f[::-1]),
                 interpolated(section.fillet_plus, 1.0 - g[::-1])]
    root = section.root_radius
    edges = [half_root_arc(root, section.space_before, section.fillet_minus[0], z), *side_minus,
             *tip, *side_plus,
             half_root_arc(root, section.space_after, section.fillet_plus[-1], z, reverse=True)]
    flank_edges = {-1: len(side_minus), 1: len(side_minus) + len(tip) + 1}

    if teeth < gear.teeth and gear.internal:
        raise ValueError("a ring gear is built whole, not as a sector")
    closure = (sector_closure(root, root - 2.0 * gear.normal_module, section.space_before,
                              section.space_before + teeth * outline.pitch, z)
               if teeth < gear.teeth else [])
    return patterned_wire(edges, teeth, outline.pitch, closure), flank_edges


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
