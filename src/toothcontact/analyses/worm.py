"""The worm kind: a worm set's geometry (the wheel enveloped by its hob) and the contact of
its loaded flanks, published under the worm's and the wheel's names."""

from __future__ import annotations

import math
import re
from dataclasses import replace

import numpy as np

from .. import case as schema
from ..analytic import hertz, worm_efficiency
from ..case import CaseError
from . import contact, lubrication
from .result import Check, Result


def worm_geometry_case(case: schema.WormCase) -> Result:
    """Geometry of a worm set: the worm, the hob and the enveloped wheel's blank (DIN 3975)."""
    from .. import worm_gearset

    try:
        parts = worm_gearset.worm_set(case)
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
        _wheel_figures(case, parts.wheel[case.load.flank], result)
        _wheel_limits(case.wheel_material or case.material, result)
        if case.analysis.positions_check:
            contact.check_positions(result, case.analysis.positions,
                             lambda scratch, at: _worm_contact(contact.refining_case(case),
                                                               parts, scratch, at))
    return result


#: the wheel's face is cut into this many strips for its teeth's line loads (_wheel_figures)
FACE_STRIPS = 40
#: a wheel softer than this (MPa) is a polymer's: the note on what an elastic model says
POLYMER_MODULUS = 10000.0


def _wheel_figures(case: schema.WormCase, wheel, result: Result) -> None:
    """What DIN 3996 / ISO/TS 14521 build on that the loaded contact gives, each with its
    method (the standards' own formulas were not at hand: ../shared/references/
    worm-din3996.md; nothing here is theirs): the mean Hertzian pressure over the contact
    lines, (4/π)·load/loaded area of each position's contacts (a semi-elliptical pressure
    across a line has its peak 4/π times its mean), averaged over the positions; and the
    wheel's root shear, the largest over the contacts and the face of the tooth's line load
    (wheel.faces, N/mm, in FACE_STRIPS strips) in the slice's plane, its transverse part
    cos α_n, over the root chord S_f of the mid-plane slice (compliance.WheelToothCompliance):
    the nominal shear of the root section, slice by slice."""
    from ..contact.compliance import WheelToothCompliance

    rows, loaded = result.sections.get("positions", []), result.loaded or []
    solved = [(row, c) for row, c in zip(rows, loaded) if c is not None]
    if not solved:
        return
    by_roll: dict[float, list] = {}
    for row, c in solved:
        by_roll.setdefault(row["roll_deg"], []).append(c)
    means = [4.0 / math.pi * sum(c.solution.load_N for c in cs)
             / sum(c.solution.area_mm2 for c in cs) for cs in by_roll.values()
             if sum(c.solution.area_mm2 for c in cs) > 0.0]
    summary = result.sections["summary"]
    summary.update(mean_hertz_pressure_MPa=float(np.mean(means)),
                   mean_hertz_pressure_max_MPa=float(np.max(means)),
                   mean_hertz_pressure_method="(4/pi)·load/loaded area of each position's "
                   "contacts (a semi-elliptical pressure across each line), averaged over the "
                   "positions: the loaded contact's mean Hertzian pressure over its lines, not "
                   "DIN 3996's formula (not at hand)")
    faces = [c.faces[1] for _, c in solved if len(c.faces) > 1]
    if not faces:
        return
    chord = WheelToothCompliance(wheel, 1.0, 0.3).root_chord
    half = 0.5 * wheel.face_width
    edges = np.linspace(-half, half, FACE_STRIPS + 1)
    line = max(float(np.max(face.line_load(c.solution.pressure_MPa, edges)))
               for (_, c), face in zip([sc for sc in solved if len(sc[1].faces) > 1], faces))
    alpha_n = case.worm.pressure_angle
    summary.update(wheel_root_chord_mm=chord, wheel_line_load_max_N_per_mm=line,
                   wheel_root_shear_MPa=line * math.cos(alpha_n) / chord,
                   wheel_root_shear_method="the largest line load on a wheel tooth (over the "
                   f"contacts, in {FACE_STRIPS} strips of the face) times cos(alpha_n), over "
                   "the root chord of the mid-plane slice: the root section's nominal shear, "
                   "slice by slice; DIN 3996's tau_F and its factors not coded (not at hand)")


#: the elastic von Mises stress below a line contact at its shakedown limit, over the yield
#: strength: Johnson, Contact Mechanics (1985) §9.3, repeated rolling of a line contact
#: (frictionless, kinematic hardening) shakes down for p0 <= 4k, k = σ_y/√3 the shear
#: yield stress; Hertz's von Mises peak below a line contact is 0.557·p0 (ν = 0.3, at 0.70 b):
#: 0.557·4/√3 = 1.29. First yield (p0 = 3.1k) would fail every bronze wheel at its rating;
#: beyond shakedown the flank flows on with every pass
SHAKEDOWN_PER_YIELD = 0.557 * 4.0 / math.sqrt(3.0)


def _wheel_limits(material, result: Result) -> None:
    """Checks against the wheel material's limits where the case gives them: the stresses
    below the contact (the largest von Mises stress of the elastic solution) against the
    shakedown limit its yield strength sets (SHAKEDOWN_PER_YIELD), the contact temperature
    (bulk plus flash) against its temperature limit; for a wheel softer than POLYMER_MODULUS
    a note on what the elastic model can and cannot say of a polymer."""
    summary = result.sections.get("summary", {})
    stressed = [r for r in result.sections.get("positions", [])
                if r.get("subsurface_von_mises_max_MPa") is not None]
    if material.yield_strength is not None and stressed:
        worst = max(stressed, key=lambda r: r["subsurface_von_mises_max_MPa"])
        stress = worst["subsurface_von_mises_max_MPa"]
        limit = SHAKEDOWN_PER_YIELD * material.yield_strength
        result.checks.append(Check(
            "wheel: the stresses below the contact stay within its shakedown limit",
            stress <= limit,
            f"von Mises {stress:.0f} MPa {worst['subsurface_von_mises_depth_mm']:.3g} mm below "
            f"the flank at roll {worst['roll_deg']:.2f} deg pair {worst['pair']} against "
            f"{limit:.0f} MPa, {SHAKEDOWN_PER_YIELD:.2f} times the wheel material's yield "
            f"strength {material.yield_strength:.0f} MPa: a line contact's shakedown limit "
            "p0 = 4k (Johnson 1985, §9.3) in the elastic solution's stress; above it the flank "
            "flows on with every pass"))
    hottest = summary.get("contact_temperature_max_degC")
    if material.temperature_limit is not None and hottest is not None:
        limit = material.temperature_limit                   # degC, as cases read it
        result.checks.append(Check(
            "wheel: the contact temperature stays below its limit", hottest <= limit,
            f"bulk plus flash {hottest:.0f} °C against the wheel material's {limit:.0f} °C"))
    if material.E < POLYMER_MODULUS:
        result.notes.append(
            f"a polymer wheel (E = {material.E / 1000:.3g} GPa): the contact is solved "
            "elastic, linear and at one modulus, so its pressures, areas and load sharing "
            "hold for short loading at the temperature that modulus belongs to; a polymer "
            "creeps, its modulus falls with temperature and moisture, and it is rated by its "
            "own allowables (e.g. VDI 2736 for plastic gears), not by a steel's or a bronze's "
            "pressure or yield: the pressures here are figures to hold against those, and no "
            "check is made of them")


def _edges_note(edges: dict) -> str:
    """The edges as analysed: each tip's rounding or chamfer, the wheel's rim faces, and
    which are the defaults (an assumption: no standard gives a value)."""
    from ..worm_gearset import WORM_TIP_EDGE_MODULES

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


def _worm_contact(case: schema.WormCase, parts, result: Result,
                  at: tuple[float, ...] | None = None):
    """Contact of the loaded flank pair (`[load] flank`) over one mesh cycle, with seed 001's
    anti-rattle-spring tilt of the worm shaft when a spring is given; the mesh that placed
    it."""
    from ..contact.cycle import parallel_cycle
    from ..surfaces.placement import WormMesh, WormMisalignment

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
    misalignment = WormMisalignment(m.center_distance_error, m.shaft_angle_error,
                                    m.wheel_axial_shift, tilt, pivot)
    if case.worm.shaft is not None:
        misalignment = _shaft_bent(case, worm, wheel, normal_load, alpha_n, misalignment,
                                   result)
    mesh = WormMesh(wheel, misalignment)
    wheel_material = case.wheel_material or case.material
    C_E = hertz.compliance(case.material.E, case.material.nu, wheel_material.E, wheel_material.nu)
    a = case.analysis
    try:
        cycle = parallel_cycle(mesh, worm, wheel, normal_load, C_E,
                              contact.cycle_settings(a, at, pairs=(-2, -1, 0, 1, 2),
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


def _shaft_bent(case: schema.WormCase, worm, wheel, normal_load: float, alpha_n: float,
                misalignment, result: Result):
    """The worm set's misalignment with the worm shaft's deflection at the mesh added
    (`[worm.shaft]`): the shaft (shaft.beam_deflection, a beam on its two bearings) under
    the mesh's normal force, frictionless, at the worm's pitch point facing the wheel, spread
    evenly along the worm axis over the wheel's face width, its axial part at the pitch
    radius a bending couple. The worm's move at the mesh away from the wheel opens the
    centre distance, its move along the wheel's axis shifts the wheel axially, its slope
    toward the wheel tilts it about the mesh and its slope along the wheel's axis turns the
    crossing angle. The `worm_shaft` section says how much; DIN 3996's limit on the
    deflection is not coded (its formula was not at hand: the references hold only that
    the standard bounds it)."""
    from ..gearset import shaft_of
    from ..shaft import POINTS, beam_deflection
    from ..surfaces.placement import WormMesh, WormMisalignment

    half = 0.5 * wheel.face_width
    try:
        shaft = shaft_of(case.worm.shaft, case.material, half, "worm.shaft")
    except ValueError as exc:
        raise CaseError(str(exc)) from None
    # the loaded flank's outward normal at its pitch point facing the wheel (+x, z near 0)
    r1 = worm.reference_radius
    v = float(worm.axial_profile(np.array(r1))) / worm.screw_parameter
    normal = worm.evaluate(np.array(r1), np.array(v)).normals
    force = -normal_load * normal                      # the wheel presses into the thread
    z1, z2 = shaft.bearings
    z = np.linspace(min(z1, z2, -half), max(z1, z2, half), POINTS)
    share = ((z >= -half) & (z <= half)).astype(float)
    share /= share.sum()
    loads = np.outer(share, force[:2])
    couple = np.outer(share, [0.0, -r1 * force[2]])    # (r1 x̂) × F_z ẑ about x and y
    u = beam_deflection(shaft, z, loads, couple)
    slope = np.gradient(u, z, axis=0)
    at = [float(np.interp(0.0, z, u[:, i])) for i in (0, 1)]
    tilt = [float(np.interp(0.0, z, slope[:, i])) for i in (0, 1)]
    # the wheel's axis in the housing (WormMesh's world: worm axis z, wheel centre on +x)
    axis = WormMesh(wheel).gear_frame(0.0).R[:, 2]
    m = misalignment
    worm_tilt = m.worm_tilt + tilt[0]
    pivot = m.worm_tilt * m.pivot / worm_tilt if worm_tilt else 0.0
    bent = WormMisalignment(m.centre_distance_error - at[0],
                            m.shaft_angle_error - tilt[1] * float(axis[1]),
                            m.wheel_axial_shift - at[1] * float(axis[1]), worm_tilt, pivot)
    result.sections["worm_shaft"] = {
        "deflection_mm": math.hypot(*at), "deflection_from_wheel_mm": -at[0],
        "deflection_along_wheel_axis_mm": at[1] * float(axis[1]),
        "slope_toward_wheel_rad": tilt[0], "slope_along_wheel_axis_rad": tilt[1],
        "mesh_force_N": [float(f) for f in force],
        "method": "Euler-Bernoulli beam on the case's two bearings (shaft.beam_deflection) "
                  "under the frictionless normal force at the worm's pitch point, spread "
                  "over the wheel's face width along the worm, its axial part a couple at "
                  "the pitch radius; DIN 3996's deflection limit not coded (not at hand)"}
    result.notes.append(
        f"worm shaft: {1000 * math.hypot(*at):.3g} um at the mesh under the mesh force "
        f"({1000 * -at[0]:.3g} um away from the wheel, a slope of {1e3 * tilt[0]:.3g} mrad "
        "toward it): the contact is solved with the worm so placed")
    return bent


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
