"""A worm set from its case: the worm's flanks (ZA, ZN, ZI, ZK), the hob and the wheel it
envelopes, and their edges as made (tip roundings or chamfers, the wheel's rim chamfers).
Units: mm, rad."""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from .case import TipEdgeSpec, WormCase
from .member_modifications import DEFAULT_TIP_EDGE_MODULES, end_chamfer
from .surfaces.broken import BrokenEdgeFlank, BrokenWormFlank, ProfileEdgeBreak
from .surfaces.wheel import BlankError, WormWheelFlank
from .surfaces.worm import WormFlank


@dataclass(frozen=True)
class WormSet:
    """Worm flanks and wheel flanks of a worm set, by side ("left", "right"), as made: their
    tip edges and the wheel's face ends broken (surfaces.broken); `edges` says how (the
    radii and chamfers, mm and deg, for the result's assumptions)."""

    worm: dict[str, BrokenWormFlank]
    wheel: dict[str, BrokenEdgeFlank]
    edges: dict = field(default_factory=dict)


#: a hob lengthened to cut the whole wheel face is this much longer than its generating zone
HOB_LENGTH_MARGIN = 1.05
#: the worm's and the wheel's tip edges are rounded by this many normal modules unless the
#: case says otherwise: the involute gears' default (DEFAULT_TIP_EDGE_MODULES); no standard
#: gives one (../shared/references/worm-tip-geometry.md)
WORM_TIP_EDGE_MODULES = DEFAULT_TIP_EDGE_MODULES


def _wheel(hob, w, worm) -> WormWheelFlank:
    return WormWheelFlank(hob, w.teeth, worm=worm, profile_shift=w.profile_shift,
                          face_width=w.face_width, align_hob_thread=w.align_hob_thread)


def worm_set(case: WormCase) -> WormSet:
    """The worm of a case and its wheel, enveloped by the hob (the worm itself or an
    oversized hob with the worm's axial module, hence its lead; sharp, as a hob's cutting
    edges are), both as made: tip edges and the wheel's face ends broken as the case says
    (worm_edges)."""
    spec = case.worm
    common = dict(form=spec.form, starts=spec.starts, length=spec.length, hand=spec.hand,
                  pressure_angle=spec.pressure_angle, wheel_diameter=spec.grinding_wheel_diameter)
    mx, d1 = spec.axial_module_and_pitch_diameter()
    worm = {side: WormFlank(axial_module=mx, pitch_diameter=d1, side=side, **common)
            for side in ("left", "right")}
    w = case.wheel
    hob_d1 = w.hob_pitch_diameter or d1
    extra = 4.0 * math.pi * mx * spec.starts  # an oversized hob is this much longer
    wheel = {}
    for side in ("left", "right"):
        hob = worm[side] if hob_d1 == d1 else WormFlank(
            axial_module=mx, pitch_diameter=hob_d1, side=side,
            **{**common, "length": spec.length + extra})
        try:
            try:
                wheel[side] = _wheel(hob, w, worm[side])
            except BlankError as exc:
                if exc.parameter != "hob_length":
                    raise
                # a hob is a tool of its own: as long as the wheel's face needs, even where
                # the worm it copies is shorter (the worm then meshes over its own length)
                longer = WormFlank(axial_module=mx, pitch_diameter=hob_d1, side=side,
                                   **{**common, "length": HOB_LENGTH_MARGIN * exc.needed})
                wheel[side] = _wheel(longer, w, worm[side])
        except BlankError as exc:
            given = "" if w.face_width is not None else " (the default)"
            raise ValueError(f"wheel.face_width{given}: {exc}") from None
    return worm_edges(case, worm, wheel)


def worm_edges(case: WormCase, worm: dict[str, WormFlank], wheel: dict[str, WormWheelFlank]
               ) -> WormSet:
    """The worm set as made: each worm flank's tip edge ([worm.tip_edge]) and each wheel
    flank's tip edge on its throat ([wheel.tip_edge]) broken by a rounding (default
    WORM_TIP_EDGE_MODULES normal modules, '0 mm' sharp) or a rounded chamfer, the wheel's
    face ends by [wheel.rim_chamfer] (default none: flush, free ends)."""
    mn = worm["left"].normal_module
    broken_worm, broken_wheel, edges = {}, {}, {}
    for side in ("left", "right"):
        tip = _tip_break(worm[side], "u1", case.worm.tip_edge, mn, "worm.tip_edge",
                         _radial(worm[side]))
        broken_worm[side] = BrokenWormFlank(worm[side], tip)
        flank = wheel[side]
        ends = end_chamfer(case.wheel.rim_chamfer, mn, flank.face_width, "wheel.rim_chamfer")
        tip = _tip_break(flank, "u0", case.wheel.tip_edge, mn, "wheel.tip_edge",
                         _throat(flank))
        broken_wheel[side] = BrokenEdgeFlank(flank, tip, ends, flank.face_width)
        if side == "left":
            edges = {"worm_tip": _edge_record(case.worm.tip_edge, broken_worm[side].tip),
                     "wheel_tip": _edge_record(case.wheel.tip_edge, broken_wheel[side].tip),
                     "wheel_rim": None if ends is None else {
                         "chamfer_mm": ends.length, "angle_deg": math.degrees(ends.angle),
                         "radius_mm": ends.radius}}
    return WormSet(broken_worm, broken_wheel, edges)


def _tip_break(flank, edge: str, spec: TipEdgeSpec | None, normal_module: float, field: str,
               across) -> ProfileEdgeBreak | None:
    """The break of a worm's or a wheel's tip edge (`edge` of its domain) by the case's
    `spec` at `field`: a rounding of its radius or WORM_TIP_EDGE_MODULES normal modules
    ('0 mm': sharp, None), or a chamfer with its edge rounded; `across` (flank, u, v) -> the
    outward unit normal of the surface across the edge (the tip's) at the flank's point."""
    radius = WORM_TIP_EDGE_MODULES * normal_module if spec is None or spec.radius is None \
        else spec.radius
    if radius == 0.0:
        return None
    (u0, u1), (v0, v1) = flank.domain
    u, v = np.array(u1 if edge == "u1" else u0), np.array(0.5 * (v0 + v1))
    sample = flank.evaluate(u, v)
    turn = math.acos(float(np.clip(np.dot(sample.normals, across(sample.points)), -1.0, 1.0)))
    chamfer = None if spec is None else spec.chamfer
    try:
        return ProfileEdgeBreak.across(flank, edge, radius, turn, chamfer,
                                       None if chamfer is None else spec.angle)
    except ValueError as exc:
        raise ValueError(f"{field}: {exc}") from None


def _radial(worm: WormFlank):
    """The worm's tip cylinder's outward normal at a point (mm): radial."""
    return lambda point: np.array([point[0], point[1], 0.0]) / math.hypot(point[0], point[1])


def _throat(wheel: WormWheelFlank):
    """The wheel's tip surface's outward normal at a point of its tip edge: the throat
    torus's (its tube about the circle of the centre distance a in the mid-plane), toward
    that circle."""
    def normal(point):
        radial = np.array([point[0], point[1], 0.0]) / math.hypot(point[0], point[1])
        towards = wheel.centre_distance * radial - point
        return towards / np.linalg.norm(towards)
    return normal


def _edge_record(spec: TipEdgeSpec | None, tip: ProfileEdgeBreak | None) -> dict | None:
    """A tip edge break as the results state it (mm, deg), None for a sharp edge."""
    if tip is None:
        return None
    out = {"radius_mm": tip.radius, "given": spec is not None and spec.radius is not None}
    if tip.chamfered:
        out.update(chamfer_mm=spec.chamfer, angle_deg=math.degrees(tip.angle))
    return out
