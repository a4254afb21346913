"""Gear sets from their cases: a parallel-axis pair (both gears, modifications, mesh), an
involute spline (hub and sleeve) and a worm set (worm and hob-enveloped wheel).

Sources: ISO 21771:2007 for the working pressure angle of a shifted pair,
inv(alpha_wt) = inv(alpha_t) + 2·tan(alpha_n)·(x1 ± x2)/(z1 ± z2), the centre distance
a = (r2 ± r1)·cos(alpha_t)/cos(alpha_wt) and the overlap ratio b·sin(beta)/(π·m_n).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field, replace

import numpy as np

from .analytic.spur_mesh import SpurMesh
from .case import SplineCase, SpurCase
from .member_modifications import check_crown_span, modifications, tip_edge, tip_thickness
from .surfaces.involute import CylindricalGear, inv
from .surfaces.modify import (
    Deflection,
    FlankModifications,
    LeadCrown,
)
from .surfaces.placement import Misalignment, ParallelMesh
from .surfaces.spline import InvoluteSpline


@dataclass(frozen=True)
class GearPair:
    pinion: CylindricalGear
    gear: CylindricalGear
    pinion_modifications: FlankModifications
    gear_modifications: FlankModifications
    center_distance: float
    working_pressure_angle: float
    pinion_deflection: Deflection | None = None
    #: the members' shafts' deflections over the face (shaft.ShaftDeflection by member
    #: name), already in pinion_deflection
    shafts: dict = field(default_factory=dict)

    @property
    def internal(self) -> bool:
        return self.gear.internal

    @property
    def pinion_loaded_modifications(self) -> FlankModifications:
        """The pinion's modifications with its deflection added (for the loaded contact)."""
        return replace(self.pinion_modifications, deflection=self.pinion_deflection)

    @property
    def operating_pitch_radius(self) -> float:
        """Pinion operating pitch radius a/(u ± 1) (mm)."""
        u = self.gear.teeth / self.pinion.teeth
        return self.center_distance / (u - 1.0 if self.internal else u + 1.0)

    @property
    def operating_backlash(self) -> float:
        """j_wt (mm): the transverse circular backlash on the operating pitch circles, from
        the teeth as cut (thinning included) at the centre distance: the operating pitch
        less both tooth thicknesses there, s_w = 2·r_w·psi(r_w), psi(r) = psi_b -+ inv(alpha)
        (ISO 21771: 0 for unthinned teeth at the centre distance their shifts give)."""
        alpha_w = self.working_pressure_angle
        r_w1 = self.operating_pitch_radius
        r_w2 = r_w1 * self.gear.teeth / self.pinion.teeth
        sign = 1.0 if self.internal else -1.0           # a ring's tooth widens outward
        s_w1 = 2.0 * r_w1 * (self.pinion.base_half_angle - inv(alpha_w))
        s_w2 = 2.0 * r_w2 * (self.gear.base_half_angle + sign * inv(alpha_w))
        return 2.0 * math.pi * r_w1 / self.pinion.teeth - s_w1 - s_w2

    @property
    def normal_backlash(self) -> float:
        """j_bn (mm): the backlash along the contact normal, j_wt·cos(alpha_wt)·cos(beta_b)
        (ISO 21771)."""
        return (self.operating_backlash * math.cos(self.working_pressure_angle)
                * math.cos(self.pinion.base_helix_angle))

    def placed(self, misalignment: Misalignment = Misalignment()) -> ParallelMesh:
        """The pair in mesh (surfaces.placement.ParallelMesh) with `misalignment`: gear tooth
        0 beside the space that holds pinion tooth 0, on the driven side; a thinned pinion
        turned forward by its thinning (its working flank where the rack's would be), the
        gear by the rest of half the backlash (the whole backlash on the back flanks); a
        coaxial spline keeps its clearance centred: closing it is its lag."""
        g = self.gear
        pitch = 2.0 * math.pi / g.teeth
        forward, close = 0.0, 0.0
        if self.center_distance > 0.0:
            p = self.pinion
            forward = 0.5 * p.thinning / p.pitch_radius
            r_w1 = self.operating_pitch_radius
            close = (0.5 * self.operating_backlash - r_w1 * forward) / (r_w1 * g.teeth / p.teeth)
        start = 0.5 * pitch - close if g.internal else math.pi - 0.5 * pitch + close
        return ParallelMesh(self.pinion.teeth, g.teeth, self.center_distance,
                            self.working_pressure_angle, misalignment, g.internal, start,
                            forward)

    def transverse_mesh(self) -> SpurMesh:
        """The transverse line-of-action geometry (contact ratio, LPSTC, ...)."""
        p, g = self.pinion, self.gear
        return SpurMesh(z1=p.teeth, z2=-g.teeth if g.internal else g.teeth,
                        module=p.transverse_module, pressure_angle=self.working_pressure_angle,
                        center_distance=self.center_distance, outside_radius_pinion=p.tip_radius,
                        outside_radius_gear=g.tip_radius)

    @property
    def overlap_ratio(self) -> float:
        face = min(self.pinion.face_width, self.gear.face_width)
        return face * math.sin(self.pinion.helix_angle) / (math.pi * self.pinion.normal_module)

    def path_limits(self) -> dict[str, float]:
        """Where each edge of the flanks lies on the transverse line of action, in mm from
        the pinion's base tangency point T1: the pinion's form and tip circles, the gear's
        tip and form circles (the forms those the generating cutters leave; a circle inside
        its base circle lies at its base tangency point)."""
        from .surfaces.generation import generate_ring_side, generate_side

        p, g = self.pinion, self.gear
        T1T2 = self.center_distance * math.sin(self.working_pressure_angle)

        def along(gear, radius):       # from the member's own tangency point
            return math.sqrt(max(radius * radius - gear.base_radius ** 2, 0.0))

        pinion_form = along(p, generate_side(p).form_radius)
        if g.internal:                 # T2 beyond T1: the gear point lies at s + T1T2 from T2
            to_s = lambda d: d - T1T2  # noqa: E731
            gear_form = along(g, generate_ring_side(g).form_radius)
        else:                          # T2 ahead of T1: at T1T2 - s from T2
            to_s = lambda d: T1T2 - d  # noqa: E731
            gear_form = along(g, generate_side(g).form_radius)
        return {"pinion_form": pinion_form, "pinion_tip": along(p, p.tip_radius),
                "gear_tip": to_s(along(g, g.tip_radius)), "gear_form": to_s(gear_form),
                "gear_base": T1T2 if not g.internal else math.inf}

    def active_path(self, forms: bool = True) -> tuple[float, float]:
        """(start, end) of the contact path (mm from T1) where both flanks are involutes
        between their form (with `forms`; else base) and tip circles; start >= end: the
        flanks never meet there."""
        edge = self.path_limits()
        lower = ("pinion_form", "gear_tip") if forms else ("gear_tip",)
        upper = ("pinion_tip", "gear_form", "gear_base") if forms else ("pinion_tip", "gear_base")
        return (max(0.0, *(edge[k] for k in lower)), min(edge[k] for k in upper))


def working_flank(gear: CylindricalGear, modifications: FlankModifications, side: int):
    """The active flank of tooth 0 on `side`: from the generated form circle (rack or shaper
    cutter) to the tip, with its modifications."""
    from .surfaces.generation import generate_ring_side, generate_side
    from .surfaces.modified import ModifiedFlank

    generated = generate_ring_side(gear) if gear.internal else generate_side(gear)
    flank = gear.flank(side, generated.form_radius)
    return flank if modifications.empty else ModifiedFlank(flank, modifications)


def rack_root_radius(case: SpurCase) -> float:
    """The rack's tip-rounding coefficient rho_fP/m_n: the case's, or by default ISO 53's
    0.38, lowered to 95 % of the largest rounding the rack's tip land takes (at pressure
    angles above about 23°, where ISO 53's 0.38 does not fit; as the shaper cutter of a ring,
    `generation.generate_ring_side`). A rounding tangent to the flank (at alpha_n) and to the
    tip line takes (1 - sin(alpha_n))/cos(alpha_n)·rho of the tip's half-width
    pi/4 - h_fP·tan(alpha_n) (in modules, normal section)."""
    rack, alpha = case.rack, case.pressure_angle
    land = math.pi / 4 - rack.dedendum * math.tan(alpha)
    if land <= 0:
        raise ValueError(f"rack.dedendum: {rack.dedendum:g} makes the rack's teeth pointed at "
                         f"{math.degrees(alpha):.4g} deg: it must be below "
                         f"{math.pi / 4 / math.tan(alpha):.4g}")
    largest = land * math.cos(alpha) / (1 - math.sin(alpha))
    if "root_radius" not in rack.model_fields_set:
        return min(rack.root_radius, 0.95 * largest)
    if rack.root_radius > largest:
        raise ValueError(f"rack.root_radius: {rack.root_radius:g} does not fit the rack's tip "
                         f"at {math.degrees(alpha):.4g} deg with dedendum {rack.dedendum:g}: "
                         f"at most {largest:.4g}")
    return rack.root_radius


def gear_pair(case: SpurCase, line_load=None) -> GearPair:
    """The case's pair: members, modifications, centre distance, and the pinion's deflection
    with the shafts' (their mesh force spread evenly over the face, or as `line_load`
    ((face positions mm, N/mm)) gives it: the loaded contact's, see analyses)."""
    from scipy.optimize import brentq

    z1, z2 = case.teeth
    internal = z2 < 0
    common = dict(normal_module=case.module_mm, pressure_angle=case.pressure_angle,
                  helix_angle=case.helix_angle, addendum=case.rack.addendum,
                  dedendum=case.rack.dedendum, root_radius=rack_root_radius(case))
    other_hand = case.hand if internal else ("left" if case.hand == "right" else "right")
    pinion = CylindricalGear(z1, face_width=case.pinion.face_width or case.face_width,
                             hand=case.hand, profile_shift=case.pinion.profile_shift,
                             tip_diameter=case.pinion.tip_diameter, **common)
    gear = CylindricalGear(abs(z2), face_width=case.gear.face_width or case.face_width,
                           hand=other_hand, profile_shift=case.gear.profile_shift,
                           internal=internal, tip_diameter=case.gear.tip_diameter, **common)
    alpha_t = pinion.transverse_pressure_angle
    sign = -1.0 if internal else 1.0
    x_sum = case.pinion.profile_shift + sign * case.gear.profile_shift
    involute_w = inv(alpha_t) + 2.0 * math.tan(case.pressure_angle) * x_sum / (z1 + sign * abs(z2))
    r_sum = gear.pitch_radius + sign * pinion.pitch_radius
    if case.center_distance is not None:
        center = case.center_distance
        if not abs(r_sum) * math.cos(alpha_t) < center:
            raise ValueError(f"center_distance: {center:.4g} mm must exceed the base-circle "
                             f"{'difference' if internal else 'sum'} "
                             f"{abs(r_sum) * math.cos(alpha_t):.4g} mm")
        alpha_w = math.acos(abs(r_sum) * math.cos(alpha_t) / center)
    else:
        if not 0 < involute_w < inv(math.radians(70)):
            shifts = "x1 - x2" if internal else "x1 + x2"
            raise ValueError(
                f"pinion.profile_shift / gear.profile_shift: {shifts} = {x_sum:.4g} gives no "
                f"working pressure angle in (0, 70) deg (inv(alpha_w) = {involute_w:.4g})")
        alpha_w = brentq(lambda a: inv(a) - involute_w, 1e-9, math.radians(70))
        center = abs(r_sum) * math.cos(alpha_t) / math.cos(alpha_w)
    thinning = _thinning(case, center, pinion)
    pinion, gear = replace(pinion, thinning=thinning), replace(gear, thinning=thinning)
    check_tip_diameters(pinion, gear)
    check_proportions(pinion, gear, center if case.center_distance is None else None)
    d = case.deflection
    deflection = None if d is None else Deflection(d.slope, d.bending, tuple(d.table))
    shafts = _shafts(case, pinion, gear, center, alpha_w, line_load)
    if shafts:
        deflection = _with_shafts(deflection, shafts, pinion.face_width)
    pair = GearPair(pinion, gear, modifications(case.pinion, pinion, "pinion"),
                    modifications(case.gear, gear, "gear"), center, alpha_w, deflection, shafts)
    tips = "".join(f" / {name}.tip_diameter" for name in ("pinion", "gear")
                   if getattr(case, name).tip_diameter is not None)
    check_mesh(pair, ("center_distance" if case.center_distance is not None else
                      "teeth / pinion.profile_shift / gear.profile_shift / rack.addendum") + tips)
    return pair


def recommended_backlash(center_distance: float, normal_module: float) -> float:
    """j_bn,min (mm): the least normal backlash ISO/TR 10064-2:1996 recommends for steel
    gears in a steel housing, (2/3)·(0.06 + 0.0005·a + 0.03·m_n), a and m_n in mm (also
    AGMA 2002-B88 without the 2/3)."""
    return 2.0 / 3.0 * (0.06 + 0.0005 * center_distance + 0.03 * normal_module)


#: the largest normal backlash a pair is analysed with, × m_n
MAX_BACKLASH = 0.5


def _thinning(case: SpurCase, center: float, pinion: CylindricalGear) -> float:
    """Each member's transverse thinning on the reference circle (mm) for the case's normal
    backlash (default `recommended_backlash`), half of it on each: j_bn = cos(alpha_n)·
    cos(beta)·(ds_t1 + ds_t2) (ISO 21771, at the centre distance)."""
    j_bn = (recommended_backlash(center, case.module_mm) if case.backlash is None
            else case.backlash)
    if not 0.0 <= j_bn <= MAX_BACKLASH * case.module_mm:
        raise ValueError(f"backlash: {j_bn:.4g} mm normal backlash; allowed 0 to "
                         f"{MAX_BACKLASH} × module = {MAX_BACKLASH * case.module_mm:.4g} mm")
    return j_bn / (2.0 * math.cos(pinion.pressure_angle) * math.cos(pinion.helix_angle))


def check_mesh(pair: GearPair, fields: str) -> None:
    """Refuse a pair that does not mesh: the involutes between form and tip circles never
    meet on the line of action, or the tips leave less than one base pitch of it with the
    overlap (total contact ratio ISO 21771 ε_γ = ε_α + ε_β below 1). A tip reaching below
    the mate's form circle is analysed and flagged, not refused. `fields`: what sets it."""
    at = f"at the centre distance {pair.center_distance:.4g} mm"
    start, end = pair.active_path()
    if not end > start:
        raise ValueError(f"{fields}: the flanks never meet on their involutes {at}: between "
                         f"form and tip circles they share no part of the line of action "
                         f"(from {start:.4g} to {end:.4g} mm from the pinion's base point)")
    start, end = pair.active_path(forms=False)
    ratio, overlap = (end - start) / pair.transverse_mesh().base_pitch, pair.overlap_ratio
    if ratio + overlap < 1.0:
        raise ValueError(f"{fields}: the mesh is interrupted {at}: the tips leave "
                         f"{max(end - start, 0.0):.4g} mm of the line of action, a contact "
                         f"ratio of {ratio:.3f} + overlap {overlap:.3f} = "
                         f"{ratio + overlap:.3f}, below 1 (a pair leaves before the next "
                         "engages)")


#: the thinnest top land a pair is analysed with, × m_n: a thinner tip is a knife edge
#: (design practice asks 0.2 to 0.4·m_n, the upper end for case-hardened gears)
MIN_TOP_LAND = 0.1




def shaft_of(spec, material, half: float, field: str):
    """The shaft (shaft.Shaft) a case's [member.shaft] `spec` describes, in the member's
    `material` where it gives no E and ν; its sections must hold the bearings and the
    loaded stretch ±`half` (mm) about the mesh; `field` names it in the message."""
    from .shaft import Shaft

    sections = (tuple(spec.sections) if spec.sections else
                ((min(*spec.bearings, -2.0 * half), max(*spec.bearings, 2.0 * half),
                  spec.diameter),))
    stiffness = spec.bearing_stiffness
    shaft = Shaft(tuple(spec.bearings), sections, spec.E or material.E,
                  spec.nu if spec.nu is not None else material.nu, spec.torque_side,
                  (tuple(stiffness) * 2)[:2] if stiffness else None)
    span = np.linspace(min(*spec.bearings, -half), max(*spec.bearings, half), 201)
    if np.isnan(shaft.diameter(span)).any():
        gap = float(span[np.isnan(shaft.diameter(span))][0])
        raise ValueError(f"{field}.sections: no section holds z = {gap:.4g} mm; they must "
                         "cover the bearings and the face")
    return shaft


def _shafts(case, pinion: CylindricalGear, gear: CylindricalGear, center: float,
            alpha_w: float, line_load=None) -> dict:
    """The shaft deflection (shaft.ShaftDeflection) of each member with a [member.shaft],
    under the case's load (none without a load): the normal force at the operating pitch
    point, on the pinion against its working flank's normal (the line of action, toward the
    gear, and the helix's axial part), on the gear the opposite, spread evenly over the face
    or as `line_load` ((face positions mm on the pinion, N/mm)) gives it; each read along
    its own flank's normal toward the mate."""
    from .shaft import shaft_deflection

    specs = {name: getattr(case, name).shaft for name in ("pinion", "gear")}
    if case.load is None or not any(specs.values()):
        return {}
    material = {"pinion": case.material, "gear": case.gear_material or case.material}
    r_w1 = center / (gear.teeth / pinion.teeth + (-1.0 if gear.internal else 1.0))
    F_t = case.load.tangential_load or case.load.torque / r_w1
    F_bt = F_t / math.cos(alpha_w)
    line = np.array([math.sin(alpha_w), math.cos(alpha_w), 0.0])     # ParallelMesh's
    (u0, _), _ = pinion.flank(1).domain
    n_z = float(pinion.flank(1).unit_normal(np.array([u0]), np.array([0.0]))[2][0])
    force = -F_bt * (line + np.array([0.0, 0.0, n_z / math.cos(pinion.base_helix_angle)]))
    out = {}
    for name, spec in specs.items():
        if spec is None:
            continue
        member = pinion if name == "pinion" else gear
        if member.internal:
            raise ValueError(f"{name}.shaft: a ring gear has no shaft here (its rim is held "
                             "by its housing)")
        shaft = shaft_of(spec, material[name], 0.5 * member.face_width, f"{name}.shaft")
        sign = 1.0 if name == "pinion" else -1.0
        r_w = r_w1 if name == "pinion" else r_w1 * gear.teeth / pinion.teeth
        to_pitch = np.array([sign * r_w, 0.0])
        out[name] = shaft_deflection(shaft, member.face_width, to_pitch, sign * force,
                                     sign * line, member.base_radius, F_t * r_w,
                                     line_load=line_load)
    return out


def _with_shafts(deflection: Deflection | None, shafts: dict, face_width: float) -> Deflection:
    """The pinion's deflection with the shafts' displacements toward the mate added (the
    gear's read on the pinion's face positions: parallel axes, mid-faces together)."""
    face = np.linspace(-0.5 * face_width, 0.5 * face_width, 41)
    total = sum(np.interp(face, s.face, s.total) for s in shafts.values())
    if deflection is not None and deflection.table:
        positions, values = np.array(deflection.table, float).T
        order = np.argsort(positions)
        total = total + np.interp(face, positions[order], values[order])
    base = deflection or Deflection()
    return Deflection(base.slope, base.bending, tuple(zip(face.tolist(), total.tolist())))


def check_proportions(pinion: CylindricalGear, gear: CylindricalGear,
                      center: float | None) -> None:
    """Refuse a pair that cannot be made, naming the field: teeth pointed at the tip (no
    thickness left), a ring's tip inside its base circle (no involute there), or a tip that
    reaches past the mating member's root circle at the zero-backlash centre distance
    `center` (None: a centre distance given by the case, where a tip past the root is
    interference to report, not a design to refuse)."""
    for name, member in (("pinion", pinion), ("gear", gear)):
        s_a = tip_thickness(member)
        kind = "ring" if member.internal else f"{member.teeth}-tooth {name}"
        if math.isnan(s_a):
            least = (member.base_radius - member.pitch_radius) / member.normal_module \
                + member.addendum
            raise ValueError(f"{name}.profile_shift: {member.profile_shift:g} puts the {kind}'s "
                             f"tip circle (d_a = {2 * member.tip_radius:.4g} mm) inside its base "
                             f"circle (d_b = {2 * member.base_radius:.4g} mm): allowed from "
                             f"{least:.3g}")
        if not s_a >= MIN_TOP_LAND * member.normal_module:
            raise ValueError(f"{name}.profile_shift: {member.profile_shift:g} makes the {kind}'s "
                             f"teeth pointed (top land {s_a:.3g} mm on the tip circle d_a = "
                             f"{2 * member.tip_radius:.4g} mm, below {MIN_TOP_LAND:g}·m_n = "
                             f"{MIN_TOP_LAND * member.normal_module:.3g} mm): allowed up to "
                             f"{_pointed_shift(member):.3g}")
    if center is None:
        return
    members = {"pinion": pinion, "gear": gear}
    for name, gap in tip_clearances(pinion, gear, center).items():
        other = "gear" if name == "pinion" else "pinion"
        member = members[name]
        if gap < 0 and member.tip_diameter is not None:    # a ring's tip must grow, a gear's shrink
            limit = member.tip_diameter + (2.0 if member.internal else -2.0) * abs(gap)
            raise ValueError(f"{name}.tip_diameter: {member.tip_diameter:.4g} mm "
                             f"puts the {name}'s tip circle {-gap:.3g} mm past the {other}'s "
                             f"root circle at the zero-backlash centre distance {center:.4g} mm: "
                             f"allowed {'from' if member.internal else 'up to'} {limit:.4g} mm, "
                             "or give a center_distance")
        if gap < 0:
            raise ValueError(f"{name}.profile_shift: {members[name].profile_shift:g} "
                             f"puts the {name}'s tip circle {-gap:.3g} mm past the {other}'s "
                             f"root circle at the zero-backlash centre distance {center:.4g} mm: "
                             f"lower the shift, or give a center_distance")


def tip_diameter_range(gear: CylindricalGear) -> tuple[float, float, str, str]:
    """The tip diameters (mm) the member can be made with, (low, high, why low, why high):
    an external gear's tip circle lies above its form circle (where the generated involute
    begins) and at most where the top land falls to MIN_TOP_LAND·m_n; a ring's (its inner
    diameter) lies below its form circle (where the shaper-cut involute ends toward the
    root) and at least on its base circle and where its top land (the tooth thins inward)
    is MIN_TOP_LAND·m_n."""
    from scipy.optimize import brentq

    from .surfaces.generation import generate_ring_side, generate_side

    land = MIN_TOP_LAND * gear.normal_module
    pointed = f"a top land of {MIN_TOP_LAND:g}·m_n = {land:.3g} mm"
    rb = gear.base_radius

    def excess(r):          # top land less the least, at tip radius r
        return tip_thickness(replace(gear, tip_diameter=2.0 * r)) - land

    if gear.internal:       # the tooth thins inward: pointed toward the base circle
        form = generate_ring_side(gear).form_radius
        if excess(rb) >= 0:
            return 2 * rb, 2 * form, "the base diameter", "the form diameter"
        low = brentq(excess, rb, form) if excess(form) > 0 else form
        return 2 * low, 2 * form, pointed, "the form diameter"
    form = max(generate_side(gear).form_radius, rb)
    high = form * 1.01 + gear.normal_module
    while excess(high) > 0:
        high += gear.normal_module
    top = brentq(excess, form, high) if excess(form) > 0 else form
    return 2 * form, 2 * top, "the form diameter", pointed


def check_tip_diameters(pinion: CylindricalGear, gear: CylindricalGear) -> None:
    """Refuse a given tip diameter (`tip_diameter`) the member cannot be made with
    (tip_diameter_range): the message names the field, the value and the allowed range."""
    for name, member in (("pinion", pinion), ("gear", gear)):
        d = member.tip_diameter
        if d is None:
            continue
        low, high, why_low, why_high = tip_diameter_range(member)
        if member.internal:
            if not low < d < high:
                raise ValueError(
                    f"{name}.tip_diameter: {d:.4g} mm (the ring's inner diameter) must lie "
                    f"above {low:.4g} mm ({why_low}) and below {high:.4g} mm ({why_high} of "
                    f"the {member.teeth}-tooth ring); allowed ({low:.4g}, {high:.4g}) mm")
        elif not low < d <= high:
            kind = f"{member.teeth}-tooth {name}"
            raise ValueError(
                f"{name}.tip_diameter: {d:.4g} mm must lie above {low:.4g} mm ({why_low} of "
                f"the {kind}) and at most {high:.4g} mm ({why_high}); allowed "
                f"({low:.4g}, {high:.4g}] mm")


def tip_clearances(pinion: CylindricalGear, gear: CylindricalGear,
                   center: float) -> dict[str, float]:
    """Radial clearance (mm) between each member's tip circle and the mating root circle at
    the centre distance, keyed by the member whose tip it is; negative: the tip reaches past
    the root."""
    if gear.internal:
        return {"pinion": gear.root_radius_value - center - pinion.tip_radius,
                "gear": gear.tip_radius - center - pinion.root_radius_value}
    return {"pinion": center - pinion.tip_radius - gear.root_radius_value,
            "gear": center - gear.tip_radius - pinion.root_radius_value}


def _pointed_shift(gear: CylindricalGear) -> float:
    """The profile shift at which the gear's top land falls to MIN_TOP_LAND·m_n (bisection
    on x)."""
    lo, hi = -1.5, gear.profile_shift
    for _ in range(60):
        mid = 0.5 * (lo + hi)
        s_a = tip_thickness(replace(gear, profile_shift=mid))
        lo, hi = (mid, hi) if s_a >= MIN_TOP_LAND * gear.normal_module else (lo, mid)
    return lo




@dataclass(frozen=True)
class SplinePair:
    """Hub (external) and sleeve (internal) of a spline, and their modifications (the hub's
    crown, both members' tip edges)."""

    spline: InvoluteSpline
    hub: CylindricalGear
    sleeve: CylindricalGear
    hub_modifications: FlankModifications
    sleeve_modifications: FlankModifications


#: a spline's teeth are sharp unless the case rounds them: its contact spans the working
#: depth and ends at the tips, where a rounding's start is a jump in curvature whose pressure
#: peak lies within micrometres of it, finer than any grid across the depth (the bundled
#: 18-tooth spline with 0.08 mm roundings: 1981, 2412 and 3058 MPa on 48, 96 and 128 cells
#: across), while a sharp tip's pressure averaged over the edge strip converges (336 and
#: 340 MPa on 48 and 96)
SPLINE_TIP_EDGE_MODULES = 0.0


def spline_pair(case: SplineCase) -> SplinePair:
    """The spline of a case. Its crown is given in the tooth-thickness direction (seed 003,
    Dudley); on the flank normal in the transverse plane that is the drop times
    cos(alpha), so the flank's crown radius is R / cos(alpha)."""
    spline = InvoluteSpline(case.teeth, case.module_mm, case.pressure_angle, case.tooth_thickness,
                            case.clearance, case.engaged_length, case.root)
    crown = None
    if case.crown is not None:
        check_crown_span(case.crown, case.engaged_length, "crown")
        c, scale = case.crown, 1.0 / math.cos(case.pressure_angle)
        crown = LeadCrown(None if c.radius is None else c.radius * scale,
                          None if c.height is None else c.height / scale, c.shape, c.center)
    try:
        hub, sleeve = spline.hub(), spline.sleeve()
    except ValueError as exc:
        raise ValueError(f"teeth / module / pressure_angle / tooth_thickness / clearance: the "
                         f"spline's teeth cannot be built from these proportions ({exc})") from None
    return SplinePair(spline, hub, sleeve,
                      FlankModifications(lead_crown=crown, tip_edge=tip_edge(
                          case.tip_edge, hub, "tip_edge", SPLINE_TIP_EDGE_MODULES)),
                      FlankModifications(tip_edge=tip_edge(
                          case.tip_edge, sleeve, "tip_edge", SPLINE_TIP_EDGE_MODULES)))
