"""The worm kind: a worm set's geometry (the wheel enveloped by its hob) and the contact of
its loaded flanks, published under the worm's and the wheel's names."""

from __future__ import annotations

import math
import re
from dataclasses import replace

from .. import case as schema
from ..analytic import hertz, worm_efficiency
from ..case import CaseError
from . import contact, lubrication
from .result import Check, Result


def worm_geometry_case(case: schema.WormCase) -> Result:
    """Geometry of a worm set: the worm, the hob and the enveloped wheel's blank (DIN 3975)."""
    from .. import gearset

    try:
        parts = gearset.worm_set(case)
    except ValueError as exc:
        raise CaseError(f"worm / wheel: {exc}") from None
    worm, wheel = parts.worm["left"], parts.wheel["left"]
    hob = wheel.hob
    section = {"form": worm.form, "starts": worm.starts, "hand": worm.hand,
               "axial_module_mm": worm.axial_module, "normal_module_mm": worm.normal_module,
               "lead_mm": worm.lead, "lead_angle_deg": math.degrees(worm.lead_angle),
               "pitch_diameter_mm": worm.pitch_diameter, "tip_diameter_mm": worm.tip_diameter,
               "root_diameter_mm": worm.root_diameter, "form_diameter_mm": 2 * worm.form_radius,
               "length_mm": worm.length}
    if worm.form == "ZI":
        section["base_diameter_mm"] = 2 * worm.base_radius
    result = Result(parts=parts, sections={
        "worm": section,
        "hob": {"pitch_diameter_mm": hob.pitch_diameter,
                "oversized": hob.pitch_diameter != worm.pitch_diameter,
                "length_mm": hob.length,
                "lead_angle_deg": math.degrees(hob.lead_angle),
                "crossing_angle_deg": math.degrees(wheel.crossing_angle),
                "generating_center_distance_mm": wheel.generating_centre_distance},
        "wheel": {"teeth": wheel.teeth, "ratio": wheel.teeth / worm.starts,
                  "pitch_diameter_mm": 2 * wheel.reference_radius,
                  "tip_diameter_mm": wheel.tip_diameter, "root_diameter_mm": wheel.root_diameter,
                  "throat_radius_mm": wheel.throat_radius,
                  "outside_diameter_mm": wheel.outside_diameter, "face_width_mm": wheel.face_width,
                  "center_distance_mm": wheel.centre_distance},
    }, notes=["the wheel flank is the exact envelope of the hob thread (equation of meshing); "
              "the blank follows DIN 3975 guideline proportions", _edges_note(parts.edges)])
    for member, key in (("worm", "worm_tip"), ("wheel", "wheel_tip")):
        edge = parts.edges[key]
        result.sections[member].update(
            tip_edge_radius_mm=None if edge is None else edge["radius_mm"],
            tip_chamfer_mm=None if edge is None else edge.get("chamfer_mm"),
            tip_chamfer_angle_deg=None if edge is None else edge.get("angle_deg"))
    rim = parts.edges["wheel_rim"]
    result.sections["wheel"].update(
        rim_chamfer_mm=None if rim is None else rim["chamfer_mm"],
        rim_chamfer_angle_deg=None if rim is None else rim["angle_deg"],
        rim_chamfer_radius_mm=None if rim is None else rim["radius_mm"])
    result.sections["hob"]["form_diameter_mm"] = 2 * hob.form_radius
    # the wheel's tip torus reaches the worm radius a - d_a2/2 (r_k) in the mid-plane, the
    # hob's radius a0 - d_a2/2 while it cuts: there the flanks must exist
    for name, flank, reach in (("worm", worm, wheel.throat_radius),
                               ("hob", hob, wheel.generating_centre_distance
                                - wheel.tip_diameter / 2)):
        result.checks.append(Check(
            f"{name} flank reaches below the wheel's tip", flank.form_radius <= reach,
            (f"{name} form diameter {2 * flank.form_radius:.3f} mm (no flank inside it)"
             if flank.form_radius > 0.0 else f"the {name} flank exists down to its root (no "
                                             "form circle)")
            + f", the wheel's tip reaches diameter {2 * reach:.3f} mm"))
    if case.load is not None:
        mesh = _worm_contact(case, parts, result)
        contact.subsurface_sections(result, case.analysis.subsurface, (
            case.material.nu, (case.wheel_material or case.material).nu))
        if case.operation is not None:
            lubrication.lubrication_sections(case, _worm_running(case, parts), mesh, result)
        if case.analysis.positions_check:
            contact.check_positions(result, case.analysis.positions,
                             lambda scratch: _worm_contact(contact.midway_case(case), parts,
                                                           scratch, 0.5))
    return result


def _edges_note(edges: dict) -> str:
    """The edges as analysed: each tip's rounding or chamfer, the wheel's rim faces, and
    which are the defaults (an assumption: no standard gives a value)."""
    from ..gearset import WORM_TIP_EDGE_MODULES

    def tip(name: str) -> str:
        edge = edges[f"{name}_tip"]
        if edge is None:
            return f"{name} tip sharp"
        text = (f"{name} tip rounded {edge['radius_mm']:.3g} mm" if "chamfer_mm" not in edge
                else f"{name} tip chamfered {edge['chamfer_mm']:.3g} mm at "
                     f"{edge['angle_deg']:.3g} deg, its edge rounded {edge['radius_mm']:.3g} mm")
        return text + ("" if edge["given"] else " (default)")

    rim = edges["wheel_rim"]
    return ("edges as made: " + ", ".join([tip("worm"), tip("wheel")]) + ", wheel rim faces "
            + ("flush (free ends)" if rim is None else
               f"chamfered {rim['chamfer_mm']:.3g} mm at {rim['angle_deg']:.3g} deg, the edge "
               f"rounded {rim['radius_mm']:.3g} mm")
            + f"; the default rounding, {WORM_TIP_EDGE_MODULES:g} normal modules, is this "
            "tool's assumption: no standard fixes a value and drawings give their own "
            "([worm.tip_edge], [wheel.tip_edge], [wheel.rim_chamfer]; '0 mm' for a sharp tip)")


def _flankless_worm(case: schema.WormCase, worm, wheel) -> str:
    """Why a worm whose flanks start (a ZI worm's base cylinder, a ZK's form limit) above
    the radius the wheel's tips reach cannot be analysed (the tips run where the worm has
    no flank: the contact found would be the flank's lower edge, at any pressure), naming
    the fields that size it: a slender worm of few starts and a steep lead."""
    given = "worm.lead_angle" if case.worm.lead_angle is not None else "worm.pitch_diameter"
    return (f"{given} / worm.starts / worm module: the wheel's tips reach below the flanks "
            f"of this {worm.starts}-start {worm.form} worm of d1 = {worm.pitch_diameter:.4g} mm "
            f"(diameter quotient q = d1/m_x = {worm.pitch_diameter / worm.axial_module:.3g}): "
            f"its flanks start at diameter {2 * worm.form_radius:.4g} mm, above the "
            f"{2 * wheel.throat_radius:.4g} mm the wheel's tips reach; give a larger pitch "
            "diameter (a smaller lead angle) or fewer starts")


def _worm_running(case: schema.WormCase, parts) -> lubrication.LubricatedPair:
    """A worm set's: the worm drives at [operation] worm_speed; the mesh passes the wheel's
    output torque at the wheel's speed; no ISO bulk temperature estimate."""
    speed, wheel = case.operation.worm_speed, parts.wheel[case.load.flank]
    output = (case.load.output_torque * 1e-3 * speed * case.worm.starts / wheel.teeth
              * 2.0 * math.pi / 60.0)
    return lubrication.LubricatedPair(
        ("worm", "wheel"), speed, (case.worm.roughness_Ra, case.wheel.roughness_Ra),
        (case.material, case.wheel_material or case.material), output, False, False)


def _worm_contact(case: schema.WormCase, parts, result: Result, phase: float = 0.0):
    """Contact of the loaded flank pair (`[load] flank`) over one mesh cycle, with seed 001's
    anti-rattle-spring tilt of the worm shaft when a spring is given; the mesh that placed
    it."""
    from ..assembly import WormMesh, WormMisalignment
    from ..contact.cycle import parallel_cycle

    worm, wheel = parts.worm[case.load.flank], parts.wheel[case.load.flank]
    torque = case.load.output_torque
    gamma, Rp = worm.lead_angle, wheel.reference_radius
    alpha_n = case.worm.pressure_angle if case.worm.form != "ZA" else math.atan(
        math.tan(case.worm.pressure_angle) * math.cos(gamma))
    normal_load = worm_efficiency.normal_tooth_load(torque, Rp, gamma, alpha_n)
    m = case.misalignment
    tilt, pivot = m.worm_tilt, m.mount
    loads = {"output_torque_Nm": torque / 1000.0, "normal_load_N": normal_load,
             "loaded_flank": case.load.flank}
    spring = case.anti_rattle_spring
    if spring is not None:
        force = worm_efficiency.anti_rattle_spring_force(torque, spring.mount_moment, spring.d1,
                                                         spring.d2, Rp, alpha_n, gamma)
        x = worm_efficiency.anti_rattle_misalignment(force, spring.stiffness)
        tilt += x / (spring.d1 + spring.d2)
        pivot = -spring.d2
        loads.update(spring_force_N=force, shaft_end_height_mm=x)
        result.notes.append("anti-rattle spring: the worm shaft pivots at its mount, d2 = "
                            f"{spring.d2:g} mm on the -z side of the mesh; the shaft end height "
                            "x (seed 001 eq 21) tilts it by x/(d1 + d2), positive toward the wheel")
    loads["worm_tilt_rad"] = tilt
    if worm.form_radius > wheel.throat_radius:
        raise CaseError(_flankless_worm(case, worm, wheel))
    mesh = WormMesh(wheel, WormMisalignment(m.center_distance_error, m.shaft_angle_error,
                                            m.wheel_axial_shift, tilt, pivot))
    wheel_material = case.wheel_material or case.material
    C_E = hertz.compliance(case.material.E, case.material.nu, wheel_material.E, wheel_material.nu)
    a = case.analysis
    try:
        cycle = parallel_cycle(mesh, worm, wheel, normal_load, C_E,
                              contact.cycle_settings(a, phase, pairs=(-2, -1, 0, 1, 2),
                                              ease_off_grid=(41, 61), ease_off_member="gear"))
    except (ValueError, RuntimeError) as exc:
        raise CaseError(f"misalignment / load: no contact could be found: {exc}") from None
    contact.contact_sections(cycle, loads, result, (wheel.reference_radius, "wheel's reference circle"))
    from ..contact.compliance import PairCompliance, ThreadCompliance, WheelToothCompliance

    teeth = PairCompliance(ThreadCompliance(worm, case.material.E, case.material.nu),
                           WheelToothCompliance(wheel, wheel_material.E, wheel_material.nu))
    contact.loaded_sections(cycle, C_E, a.pressure_grid, teeth,
                     "tooth bending from the wheel tooth's mid-plane section (the enveloped "
                     "flank, continued straight to the root circle; loads placed by their "
                     "height from the throat circle, coupled along the face) and the worm "
                     "thread's axial section in the worm's material (coupled along the "
                     "thread, no end in reach); bending, shear, axial and body compliance "
                     "(contact.compliance), solved with the contact in one system", result)
    _publish_names(result, PUBLISHED_NAMES["worm"])
    return mesh


#: the names a kind's results give the contact engine's driver ("pinion") and driven member
#: ("gear"); a kind not listed keeps those
PUBLISHED_NAMES = {"worm": {"pinion": "worm", "gear": "wheel"}}


#: an edge of a flank as the contact engine names it: member (its driver "pinion", its
#: driven "gear") and edge
_EDGE = re.compile(r"\b(pinion|gear)_(?=(tip|form|root|end_A|end_B)\b)")


def _publish_names(result: Result, names: dict[str, str]) -> None:
    """Results under the names of the parts (a worm set's worm and wheel) where the contact
    engine speaks of its driver and driven member as pinion and gear: the edges in the rows,
    the summary and the check details, and the contact-radius key."""
    def edge(text):
        return _EDGE.sub(lambda m: f"{names[m.group(1)]}_", text) if isinstance(text, str) else text

    for row in result.sections.get("positions", []):
        if "contact_radius_pinion_mm" in row:
            row[f"contact_radius_{names['pinion']}_mm"] = row.pop("contact_radius_pinion_mm")
        for key in ("edge_contact_at", "edge_pressure_at", "corner_at"):
            if key in row:
                row[key] = edge(row[key])
        if isinstance(row.get("edge_margins_mm"), dict):
            row["edge_margins_mm"] = {edge(k): v for k, v in row["edge_margins_mm"].items()}
    summary = result.sections.get("summary", {})
    for key in ("worst_face_edge", "worst_profile_edge", "corner_contact_at"):
        if key in summary:
            summary[key] = edge(summary[key])
    if "ease_off" in result.sections:
        result.sections["ease_off"]["member"] = names[result.sections["ease_off"]["member"]]
    result.checks = [replace(c, detail=edge(c.detail)) for c in result.checks]
