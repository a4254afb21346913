"""From a validated case to its result: one function per analytic case kind.

Each returns a `Result`: named sections of numbers (keys carry their unit), the checks a
reviewer must see (edge loading, stress over a limit, a source's inconsistency) and notes.
Pure functions: nothing here reads or writes files.
"""

from __future__ import annotations

import functools
import math
import re
import warnings
from dataclasses import dataclass, field, replace
from pathlib import Path

import numpy as np

from . import case as schema
from .analytic import agma, crown, hertz, spline, worm_efficiency
from .analytic.stiffness import face_load_factor, mesh_stiffness, single_stiffness
from .analytic.spur_mesh import SpurMesh
from .case import CaseError


@dataclass
class Check:
    """A pass/fail statement about the result. kind "design": about the design (a failed one
    is flagged at the top of the report and exits the run with 1); "source": whether a
    source's own printed numbers agree with each other (a misprint is the source's, not the
    design's); "method": a self-check of the method (two routes to the same number);
    "solver": whether a solver answered everywhere (a failed one leaves the results
    incomplete: its rows say why, and the run exits with 4)."""

    name: str
    ok: bool
    detail: str
    kind: str = "design"

    def as_dict(self) -> dict:
        return {"name": self.name, "ok": bool(self.ok), "detail": self.detail, "kind": self.kind}


@dataclass
class Result:
    """What an analysis found: sections, checks and notes go to result.json; `cycle` (a
    contact.cycle.ContactCycle, for contact cases) and `loaded` (contact.loaded.LoadedContact
    or None per cycle row) stay in memory for the pictures."""

    sections: dict = field(default_factory=dict)
    checks: list[Check] = field(default_factory=list)
    notes: list[str] = field(default_factory=list)
    cycle: object = None
    loaded: list | None = None

    def as_dict(self) -> dict:
        return {**self.sections, "checks": [c.as_dict() for c in self.checks],
                "notes": self.notes}


def analyse(case: schema.CaseInfo) -> Result:
    """Run the analysis of the case's kind; bad geometry becomes a CaseError."""
    runner = {
        "hertz": hertz_case,
        "crown_design": crown_design_case,
        "worm_efficiency": worm_efficiency_case,
        "spline_crown": spline_crown_case,
        "spur": spur_geometry_case,
        "spline": spline_geometry_case,
        "worm": worm_geometry_case,
        "imported": imported_case,
    }[case.kind]
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        result = runner(case)
    # the analyses' own warnings are notes for the reader; a numerical library's runtime
    # warnings (an overflow inside a guarded step) are not
    result.notes.extend(str(w.message) for w in caught if issubclass(w.category, UserWarning))
    result.notes.extend(_defaulted_materials(case))
    return result


def _defaulted_materials(case: schema.CaseInfo) -> list[str]:
    """Notes naming the materials the case left to their defaults (steel; the mate's)."""
    given = case.model_fields_set
    notes = []
    if "material" in type(case).model_fields and "material" not in given:
        m = case.material
        whose = " (the worm's)" if case.kind == "worm" else ""
        notes.append(f"material{whose}: none given, so steel: E = {m.E / 1e3:g} GPa, "
                     f"nu = {m.nu:g}")
    for mate in ("gear_material", "wheel_material", "sleeve_material"):
        if mate in type(case).model_fields and getattr(case, mate) is None:
            notes.append(f"{mate}: none given, so the same as material")
    return notes


def _ellipse(contact: hertz.PointContact) -> dict:
    return {"a_mm": contact.a, "b_mm": contact.b, "p_max_MPa": contact.p0,
            "approach_mm": contact.approach, "A_per_mm": contact.A, "B_per_mm": contact.B}


def hertz_case(case: schema.HertzCase) -> Result:
    """General two-body point contact: exact Hertz, with Roark's form beside it."""
    C_E = hertz.compliance(case.body1.E, case.body1.nu, case.body2.E, case.body2.nu)
    k1 = hertz.curvatures_from_radii(case.body1.radii)
    k2 = hertz.curvatures_from_radii(case.body2.radii)
    try:
        rc = hertz.relative_curvature(k1, k2, case.angle)
    except ValueError as exc:
        raise CaseError(f"body1.radii / body2.radii: {exc}") from None
    exact = hertz.hertz_point(rc.A, rc.B, case.load, C_E)
    total = 2.0 * (rc.A + rc.B)
    roark = hertz.roark_point(total, 2.0 * (rc.B - rc.A), case.load, C_E)
    alpha, beta, lam = hertz.roark_coefficients((rc.B - rc.A) / (rc.A + rc.B))
    agree = max(abs(roark.a / exact.a - 1), abs(roark.b / exact.b - 1), abs(roark.p0 / exact.p0 - 1))
    return Result(
        sections={
            "hertz": {**_ellipse(exact), "mean_pressure_MPa": exact.mean_pressure,
                      "a_direction_deg": math.degrees(rc.angle), "E_star_MPa": 1.0 / C_E},
            "roark": {"cos_theta": (rc.B - rc.A) / (rc.A + rc.B), "alpha": alpha, "beta": beta,
                      "lambda": lam, "K_D_mm": 1.5 / total, "a_mm": roark.a, "b_mm": roark.b,
                      "stress_MPa": roark.p0, "approach_mm": roark.approach},
        },
        checks=[Check("Roark's alpha/beta form equals the exact Hertz solution", agree < 1e-6,
                      f"largest relative difference {agree:.1e} (limit 1e-6)", "method")],
    )


def spur_mesh(case: schema.CrownDesignCase) -> SpurMesh:
    """The spur pair of a crown-design case, with the defaults stated in the README."""
    m = case.module_mm
    z1, z2 = case.teeth
    r1, r2 = 0.5 * m * z1, 0.5 * m * abs(z2)
    internal = z2 < 0
    mesh = SpurMesh(
        z1=z1, z2=z2, module=m, pressure_angle=case.pressure_angle,
        center_distance=case.center_distance or (r2 - r1 if internal else r2 + r1),
        outside_radius_pinion=case.outside_radius_pinion or r1 + m,
        outside_radius_gear=case.outside_radius_gear or (r2 - m if internal else r2 + m))
    try:
        mesh.check()
    except ValueError as exc:
        raise CaseError(f"teeth / module / pressure_angle / outside radii: {exc}") from None
    return mesh


def crown_design_case(case: schema.CrownDesignCase) -> Result:
    """Wang & El-Bayoumy's crown design (seed 003): full or bias crown, or check a given one."""
    mesh = spur_mesh(case)
    gear_material = case.gear_material or case.material
    C_E = hertz.compliance(case.material.E, case.material.nu, gear_material.E, gear_material.nu)
    if case.profile_radii is not None:
        rho1, rho2 = case.profile_radii
    else:
        rho1 = mesh.lpstc()
        rho2 = mesh.gear_radius_of_curvature(rho1)
    if mesh.internal and rho2 <= rho1:
        raise CaseError(f"profile_radii: the internal gear's concave radius {rho2:.4g} mm must "
                        f"exceed the pinion's {rho1:.4g} mm")
    profile_curvature = 1.0 / rho1 + (-1.0 if mesh.internal else 1.0) / rho2
    load = crown.normal_load(case.tangential_load, case.pressure_angle)
    slope_B = case.slope_A if case.crown == "full" else case.slope_B
    if case.radius is None:
        if case.slope_A + slope_B <= 0:
            raise CaseError(f"slope_A + slope_B: {case.slope_A + slope_B:.4g} rad must be > 0 "
                            "for the contact to move; the crown would be flat")
        try:
            design = crown.design_crown(case.face_width, case.slope_A, slope_B,
                                        profile_curvature, load, C_E, case.edge_clearance)
        except crown.CrownDesignError as exc:
            raise CaseError(f"{exc.fields}: {exc}") from None
        fields = "slope_A / slope_B / face_width"
    else:
        center = case.center_from_B if case.center_from_B is not None else 0.5 * case.face_width
        if case.crown == "bias" and case.center_from_B is None:
            raise CaseError("center_from_B: missing; checking a bias crown needs its centre")
        if not 0 <= center <= case.face_width:
            raise CaseError(f"center_from_B: {center:.4g} mm must lie on the face, 0 to "
                            f"{case.face_width:.4g} mm")
        design = crown.check_crown(case.radius, center, case.face_width, case.slope_A, slope_B,
                                   profile_curvature, load, C_E)
        fields = "radius / center_from_B / face_width"
    reach = max(design.center_from_B, case.face_width - design.center_from_B)
    if not (0 <= design.center_from_B <= case.face_width and design.radius > reach):
        raise CaseError(f"{fields}: the crown (radius {design.radius:.4g} mm, centre "
                        f"{design.center_from_B:.4g} mm from end B) must be centred on the "
                        f"{case.face_width:.4g} mm face with a radius above {reach:.4g} mm, the "
                        "farthest face end from its centre; slopes this large (or a radius this "
                        "small) are beyond what a lead crown can take")
    ellipse = design.contact.ellipse
    d = mesh.operating_pitch_diameter
    I = agma.geometry_factor(rho1, rho2, case.pressure_angle, d, mesh.internal)
    Cp = agma.elastic_coefficient(C_E)
    result = Result(sections={
        "crown": {"mode": "design" if case.radius is None else "check",
                  "radius_mm": design.radius, "center_from_B_mm": design.center_from_B,
                  "drop_A_mm": design.drop_A, "drop_B_mm": design.drop_B},
        "contact": {"a_mm": ellipse.a, "b_mm": ellipse.b, "stress_MPa": ellipse.p0,
                    "semi_axis_along_face_mm": design.contact.semi_axis_face,
                    "rho1_mm": rho1, "rho2_mm": rho2, "normal_load_N": load,
                    "approach_mm": ellipse.approach,
                    "edge_margin_A_mm": design.edge_margin_A,
                    "edge_margin_B_mm": design.edge_margin_B},
        "mesh": {"pitch_diameter_mm": d, "center_distance_mm": mesh.center_distance,
                 "base_pitch_mm": mesh.base_pitch, "contact_ratio": mesh.contact_ratio},
        "uncrowned": {"agma_stress_MPa": agma.contact_stress(Cp, case.tangential_load, d,
                                                             case.face_width, I),
                      "I": I, "Cp_sqrt_MPa": Cp},
    })
    for end, margin in (("A", design.edge_margin_A), ("B", design.edge_margin_B)):
        result.checks.append(Check(f"contact ellipse inside the face at end {end}",
                                   margin >= -1e-9 * case.face_width,
                                   f"edge margin {margin:.4f} mm (negative = edge loading)"))
    if case.allowable_stress is not None:
        result.checks.append(Check("contact stress within the allowable",
                                   ellipse.p0 <= case.allowable_stress,
                                   f"{ellipse.p0:.1f} MPa against {case.allowable_stress:.1f} MPa"))
    return result


def worm_efficiency_case(case: schema.WormEfficiencyCase) -> Result:
    """Tooth efficiency of a worm set over lubricant conditions (seeds 000 and 001)."""
    if case.lead_angle is not None:
        gamma = case.lead_angle
    else:
        try:
            gamma = worm_efficiency.lead_angle_from_pitch_diameter(
                case.starts, case.normal_module, case.worm_pitch_diameter)
        except ValueError as exc:
            raise CaseError(f"worm_pitch_diameter: {exc}") from None
    alpha_n = case.normal_pressure_angle
    result = Result()
    rows = []
    for i, cond in enumerate(case.conditions or [None]):
        if cond is None:
            Y_VISC, mu = 1.0, case.mu_zm if case.mu_zm is not None else worm_efficiency.mean_friction(
                **case.din3996.model_dump())
        else:
            Y_VISC = worm_efficiency.viscosity_factor(cond.viscosity)
            mu = worm_efficiency.mean_friction(**case.din3996.model_dump(), Y_VISC=Y_VISC)
        eta_z = worm_efficiency.efficiency_worm_driving(gamma, mu)
        eta_back = worm_efficiency.efficiency_wheel_driving(gamma, mu)
        row = {"temperature_C": cond.temperature if cond else None,
               "viscosity_mm2_s": cond.viscosity if cond else None,
               "Y_VISC": Y_VISC, "mu_zm": mu, "eta_z": eta_z,
               "eta_wheel_driving": max(eta_back, 0.0), "self_locking": eta_back <= 0.0,
               "eta_kim": worm_efficiency.efficiency_kim(gamma, alpha_n, mu)}
        if cond is not None:
            if cond.eta_spindle is not None:
                row["eta_total"] = eta_z * cond.eta_spindle
            result.checks.extend(_published_checks(cond, eta_z, gamma))
        rows.append(row)
    result.sections["efficiency"] = rows
    result.sections["worm"] = {"lead_angle_deg": math.degrees(gamma),
                               "axial_module_mm": case.normal_module / math.cos(gamma),
                               "wheel_pitch_radius_mm": _wheel_pitch_radius(case, gamma)}
    if case.anti_rattle_spring is not None:
        result.sections["misalignment"] = _anti_rattle_rows(case, gamma)
    return result


def _wheel_pitch_radius(case: schema.WormEfficiencyCase, gamma: float) -> float:
    return 0.5 * case.teeth * case.normal_module / math.cos(gamma)


def _published_checks(cond: schema.Condition, eta_z: float, gamma: float) -> list[Check]:
    """Compare a condition with the values its source prints (seed 000 Table 3.5-1 style)."""
    at = f"at {cond.temperature:g} °C"
    checks = []
    if cond.published_eta_z is not None:
        checks.append(Check(f"eta_z {at} matches the published value", abs(eta_z - cond.published_eta_z) <= 0.01,
                            f"computed {eta_z:.3f}, published {cond.published_eta_z:.3f} (tolerance 0.01)",
                            "source"))
        if cond.published_mu_zm is not None:
            own = worm_efficiency.efficiency_worm_driving(gamma, cond.published_mu_zm)
            checks.append(Check(f"published eta_z {at} follows from the published mu_zm",
                                abs(own - cond.published_eta_z) <= 0.005,
                                f"eta_z(mu_zm={cond.published_mu_zm}) = {own:.4f}, published "
                                f"{cond.published_eta_z:.3f} (tolerance 0.005)", "source"))
    if None not in (cond.published_eta_total, cond.published_eta_z, cond.eta_spindle):
        product = cond.published_eta_z * cond.eta_spindle
        checks.append(Check(f"published eta_tot {at} equals eta_z·eta_spindle",
                            abs(product - cond.published_eta_total) <= 0.01,
                            f"{cond.published_eta_z:.3f} × {cond.eta_spindle:.3f} = {product:.3f}, "
                            f"published {cond.published_eta_total:.3f} (tolerance 0.01): "
                            + ("consistent" if abs(product - cond.published_eta_total) <= 0.01
                               else "the source's column is inconsistent"), "source"))
    return checks


def _anti_rattle_rows(case: schema.WormEfficiencyCase, gamma: float) -> list[dict]:
    """Seed 001 eqs (3), (20), (21) per output torque; with [contact], eq (19)'s pressure
    with and without the spring's preload, the friction law and eq (2)'s efficiency."""
    spring, alpha = case.anti_rattle_spring, case.normal_pressure_angle
    Rp = _wheel_pitch_radius(case, gamma)
    kim = case.contact
    if kim is not None:
        rp = 0.5 * case.worm_pitch_diameter
        # a ZI worm's base cylinder: cos(gamma_b) = cos(alpha_n)·cos(gamma), r_b = r·tan(gamma)/tan(gamma_b)
        base = rp * math.tan(gamma) / math.tan(math.acos(math.cos(alpha) * math.cos(gamma)))
        try:
            radii = worm_efficiency.kim_curvature_radii(rp, base, 0.5 * kim.hob_pitch_diameter,
                                                         gamma, Rp, alpha)
        except ValueError as exc:
            raise CaseError(f"contact: {exc}") from None
        C_E = hertz.compliance(kim.worm.E, kim.worm.nu, kim.wheel.E, kim.wheel.nu)
    rows = []
    for torque in spring.output_torques:
        force = worm_efficiency.anti_rattle_spring_force(
            torque, spring.mount_moment, spring.d1, spring.d2, Rp, alpha, gamma)
        Fn = worm_efficiency.normal_tooth_load(torque, Rp, gamma, alpha)
        row = {"output_torque_Nm": torque / 1000.0, "normal_load_N": Fn, "spring_force_N": force,
               "misalignment_mm": worm_efficiency.anti_rattle_misalignment(force, spring.stiffness)}
        if kim is not None:
            total = worm_efficiency.preloaded_normal_force(Fn, force, spring.d1, spring.d2, alpha)
            law = kim.friction
            for suffix, F in (("_aligned", Fn), ("", total)):
                p = worm_efficiency.kim_contact_pressure(F, radii, C_E) if F > 0 else 0.0
                # no load, no pressure: the power law gives no friction (null) and the
                # set transmits nothing (efficiency 0)
                mu = worm_efficiency.friction_power_law(p, law.mu_ref, law.pressure_ref,
                                                        law.exponent) if p > 0 else None
                row[f"pressure{suffix}_MPa"], row[f"mu{suffix}"] = p, mu
                row[f"eta_kim{suffix}"] = (worm_efficiency.efficiency_kim_preloaded(
                    gamma, alpha, mu, Fn, F) if p > 0 else 0.0)
            row["preloaded_normal_load_N"] = total
        rows.append(row)
    return rows


def spline_crown_case(case: schema.SplineCrownCase) -> Result:
    """Dudley's crowned spline with seed 003's fit limit (eq 19)."""
    theta = case.misalignment
    height, radius = spline.dudley_crown(case.engaged_length, theta)
    sleeve = case.sleeve_material or case.material
    C_E = hertz.compliance(case.material.E, case.material.nu, sleeve.E, sleeve.nu)
    D = case.pitch_diameter_mm
    stress = spline.dudley_contact_stress(case.torque, D, case.teeth, case.working_depth, radius, C_E)
    r_max = spline.max_crown_radius_for_fit(case.tooth_thickness, case.clearance, theta)
    clearance = spline.tilted_tooth_clearance(radius, case.tooth_thickness, case.clearance, theta,
                                              0.5 * case.engaged_length)
    result = Result(sections={"spline": {
        "crown_radius_mm": radius, "crown_height_mm": height, "contact_stress_MPa": stress,
        "crown_radius_fit_max_mm": r_max, "tooth_load_N": 2.0 * case.torque / (D * case.teeth),
        "fit_clearance_mm": clearance, "pitch_diameter_mm": D,
        "fit_max_touch_from_center_mm": r_max * math.sin(theta)}})
    result.checks.append(Check("the tilted crowned tooth fits the space (crown radius <= eq 19 limit)",
                               radius <= r_max and clearance >= 0,
                               f"crown radius {radius:.1f} mm, eq 19 limit {r_max:.1f} mm, "
                               f"clearance left {clearance * 1000:.2f} µm"))
    if r_max * math.sin(theta) > 0.5 * case.engaged_length:
        result.notes.append("eq 19 assumes the tilted tooth touches at R·sin(theta) = "
                            f"{r_max * math.sin(theta):.3f} mm from the crown centre, beyond half "
                            f"the engaged length ({0.5 * case.engaged_length:.3f} mm); on this "
                            "length a larger radius would still fit")
    return result


def spur_geometry_case(case: schema.SpurCase) -> Result:
    """Geometry of a spur/helical pair: both gears' circles, form and undercut, the mesh."""
    from . import gearset
    from .surfaces.generation import generate_side

    try:
        pair = gearset.gear_pair(case)
        mesh = pair.transverse_mesh()
    except ValueError as exc:
        raise CaseError(str(exc)) from None
    result = Result(notes=["crown and relief amounts are measured along the flank normal in the "
                           "transverse plane (ISO 21771); on a helical flank the normal "
                           "displacement is that amount times cos(beta_b)"])
    result.notes.append(_tip_edge_note(case, pair))
    for name, gear, mods in (("pinion", pair.pinion, pair.pinion_modifications),
                             ("gear", pair.gear, pair.gear_modifications)):
        section = {"teeth": gear.teeth, "internal": gear.internal,
                   "transverse_module_mm": gear.transverse_module,
                   "transverse_pressure_angle_deg": math.degrees(gear.transverse_pressure_angle),
                   "base_helix_angle_deg": math.degrees(gear.base_helix_angle),
                   "hand": gear.hand if gear.helix_angle else None,
                   "pitch_diameter_mm": 2 * gear.pitch_radius, "base_diameter_mm": 2 * gear.base_radius,
                   "tip_diameter_mm": 2 * gear.tip_radius, "root_diameter_mm": 2 * gear.root_radius_value,
                   "tooth_thickness_mm": gear.tooth_thickness,
                   "tip_edge_radius_mm": None if mods.tip_edge is None else mods.tip_edge.radius,
                   "tip_chamfer_angle_deg": (None if mods.tip_edge is None
                                             or mods.tip_edge.angle is None
                                             else math.degrees(mods.tip_edge.angle)),
                   "end_chamfer_mm": (None if mods.end_chamfer is None
                                      else mods.end_chamfer.length),
                   "end_chamfer_angle_deg": (None if mods.end_chamfer is None
                                             else math.degrees(mods.end_chamfer.angle))}
        if not gear.internal:
            generated = generate_side(gear)
            section["form_diameter_mm"] = 2 * generated.form_radius
            section["undercut"] = generated.undercut
            result.checks.append(Check(f"{name} is not undercut", not generated.undercut,
                                       f"form diameter {2 * generated.form_radius:.3f} mm, base "
                                       f"diameter {2 * gear.base_radius:.3f} mm"))
        if mods.lead_crown is not None:
            R = mods.lead_crown.radius_for(gear.face_width)
            section["crown_radius_mm"] = R
            for end, w in (("A", -0.5 * gear.face_width), ("B", 0.5 * gear.face_width)):
                section[f"crown_drop_{end}_mm"] = float(mods.lead_crown.drop(w, gear.face_width))
        result.sections[name] = section
    result.sections["mesh"] = {
        "center_distance_mm": pair.center_distance,
        "working_pressure_angle_deg": math.degrees(pair.working_pressure_angle),
        "transverse_contact_ratio": mesh.contact_ratio, "overlap_ratio": pair.overlap_ratio,
        "transverse_base_pitch_mm": mesh.base_pitch,
        "rho1_lpstc_mm": mesh.lpstc(),
        "normal_backlash_mm": pair.normal_backlash,
        "transverse_backlash_mm": pair.operating_backlash,
        "backlash_note": "j_bn along the contact normal and j_wt on the operating pitch "
                         "circles (ISO 21771), from the teeth thinned for the case's backlash "
                         "(half on each member; " + (
                             "ISO/TR 10064-2's least recommended (2/3)(0.06 + 0.0005·a + "
                             "0.03·m_n) mm, as none was given" if case.backlash is None else
                             "as given") + ") at the centre distance; the gear is placed "
                         "on the working flanks, the backlash on the back ones"}
    result.checks.append(Check("transverse contact ratio above 1", mesh.contact_ratio > 1.0,
                               f"{mesh.contact_ratio:.3f}"))
    edge = pair.path_limits()
    start, end = pair.active_path()
    result.sections["mesh"]["usable_contact_ratio"] = (end - start) / mesh.base_pitch
    reach = {"gear tip below the pinion's form circle": edge["pinion_form"] - edge["gear_tip"],
             "pinion tip below the gear's form circle": edge["pinion_tip"] - edge["gear_form"]}
    result.checks.append(Check(
        "tips work on the mating involutes (no tip interference)",
        max(reach.values()) <= 1e-9,
        "; ".join(f"{what} by {d:.3f} mm along the line of action" for what, d in reach.items()
                  if d > 1e-9) or "both tips meet the mates' involutes above their form circles"))
    clearance = gearset.tip_clearances(pair.pinion, pair.gear, pair.center_distance)
    result.sections["mesh"].update({f"{name}_tip_clearance_mm": c for name, c in clearance.items()})
    result.checks.append(Check("tips clear the mating root circles",
                               min(clearance.values()) >= 0.0,
                               ", ".join(f"{name} tip {c:.3f} mm" for name, c in clearance.items())))
    if case.load is not None:
        _spur_contact(case, pair, result)
    return result


def _cycle_settings(a: schema.AnalysisSpec, **kind_settings):
    """The contact cycle's settings from a case's [analysis] table."""
    from .contact.cycle import CycleSettings

    return CycleSettings(a.positions, a.grid, a.approach, field_grid=a.field_grid, **kind_settings)


#: with a shaft the contact is analysed again, the shafts loaded by the loaded contact's
#: line load, until their deflection under it differs by less than SHAFT_TOLERANCE (mm)
#: anywhere on the face from the one analysed: at most SHAFT_PASSES analyses in all; each
#: new pass applies SHAFT_RELAXATION of the step toward the line load found (a stiff mesh
#: answers a micrometre of deflection with a large shift of its load, and the full step can
#: swing between the face ends)
SHAFT_TOLERANCE, SHAFT_PASSES, SHAFT_RELAXATION = 0.5e-3, 4, 0.5


def _spur_contact(case: schema.SpurCase, pair, result: Result) -> None:
    """Contact by surface separation over the mesh cycle (contact.cycle) and the loaded
    contact; with a [member.shaft], repeated with the shafts carrying the loaded contact's
    line load (its mean over the cycle; the first pass spreads it evenly) until the shafts'
    deflection settles (SHAFT_TOLERANCE, SHAFT_RELAXATION): each pass starts from the
    geometry's sections and checks."""
    from .gearset import gear_pair

    checks, sections = list(result.checks), dict(result.sections)
    changes, applied = [], None
    for attempt in range(SHAFT_PASSES):
        result.checks, result.sections = list(checks), dict(sections)
        _contact_pass(case, pair, result)
        distribution = result.sections.get("load_distribution")
        if not pair.shafts or distribution is None:
            return
        face = np.asarray(distribution["face_mm"])
        found = np.mean(distribution["line_load_N_per_mm"], axis=0)
        loaded = gear_pair(case, (face, found))
        changes.append(max(float(np.max(np.abs(loaded.shafts[name].total - shaft.total)))
                           for name, shaft in pair.shafts.items()))
        if changes[-1] <= SHAFT_TOLERANCE or attempt == SHAFT_PASSES - 1:
            break
        before = np.full(face.shape, found.mean()) if applied is None else applied
        applied = before + SHAFT_RELAXATION * (found - before)
        pair = gear_pair(case, (face, applied))
    result.sections["shaft"]["passes"] = len(changes)
    result.sections["shaft"]["changes_um"] = [1e3 * c for c in changes]
    result.checks.append(Check(
        "shaft deflection settled with the loaded line load", changes[-1] <= SHAFT_TOLERANCE,
        f"{len(changes)} pass(es); the shafts' deflection under the loaded line load differs "
        f"by {1e3 * changes[-1]:.2f} µm from the one analysed (settled below "
        f"{1e3 * SHAFT_TOLERANCE:g} µm)"))


def _tip_edge_note(case: schema.SpurCase, pair) -> str:
    """The tip edges and end chamfers as analysed: each member's rounding or chamfer, and
    where it is the default."""
    from .gearset import DEFAULT_TIP_EDGE_MODULES

    parts = []
    for name, mods in (("pinion", pair.pinion_modifications), ("gear", pair.gear_modifications)):
        edge, spec = mods.tip_edge, getattr(case, name).tip_edge
        if edge is None:
            text = "sharp"
        elif edge.angle is None:
            text = f"rounded {edge.radius:.3g} mm"
        else:
            text = (f"chamfered {spec.chamfer:.3g} mm at {math.degrees(edge.angle):.3g} deg, "
                    f"its edge rounded {edge.radius:.3g} mm")
        parts.append(f"{name} {text}" + ("" if spec is not None else " (default)"))
        chamfer = mods.end_chamfer
        if chamfer is not None:
            parts.append(f"{name} face ends chamfered {chamfer.length:.3g} mm at "
                         f"{math.degrees(chamfer.angle):.3g} deg, their edges rounded "
                         f"{chamfer.radius:.3g} mm (the edge pressure there resolved from "
                         "pressure_grid 256)")
    return ("tip edges: " + ", ".join(parts) + f"; the default is {DEFAULT_TIP_EDGE_MODULES:g} "
            "normal modules, or the largest rounding that fits the tooth ([member.tip_edge] "
            "radius; '0 mm' for a sharp edge)")


def _contact_pass(case: schema.SpurCase, pair, result: Result) -> None:
    """One analysis of the contact (cycle, loaded contact, load distribution, interference)
    with the pair's deflection as it stands."""
    from .assembly import Misalignment, ParallelMesh
    from .contact.cycle import parallel_cycle
    from .gearset import working_flank

    m = case.misalignment
    mesh = ParallelMesh(pair, Misalignment(m.slope, m.slope_normal, m.center_distance_error,
                                           m.axial_shift))

    pinion = working_flank(pair.pinion, pair.pinion_loaded_modifications, 1)
    gear = working_flank(pair.gear, pair.gear_modifications, mesh.gear_side)
    wt = case.load.tangential_load or case.load.torque / pair.operating_pitch_radius
    normal_load = wt / (math.cos(pair.working_pressure_angle) * math.cos(pair.pinion.base_helix_angle))
    gear_material = case.gear_material or case.material
    C_E = hertz.compliance(case.material.E, case.material.nu, gear_material.E, gear_material.nu)
    a = case.analysis
    reach = (_loaded_reach(pair, normal_load, case.material.E, gear_material.E)
             if a.pressure_grid else 0.0)
    try:
        cycle = parallel_cycle(mesh, pinion, gear, normal_load, C_E,
                              _cycle_settings(a, reach=reach))
    except (ValueError, RuntimeError) as exc:
        raise CaseError(f"misalignment / load: no contact could be found: {exc}") from None
    _contact_sections(cycle, {"tangential_load_N": wt, "normal_load_N": normal_load}, result)
    if pair.shafts:
        _shaft_sections(pair, result)
    from .contact.compliance import PairCompliance, tooth_compliance

    teeth = PairCompliance(tooth_compliance(pair.pinion, case.material.E, case.material.nu),
                           tooth_compliance(pair.gear, gear_material.E, gear_material.nu))
    _loaded_sections(cycle, C_E, a.pressure_grid, teeth,
                     "tooth bending from each member's exact transverse slices (bending, shear, "
                     "axial and gear body compliance, solid blanks with a bore of half the root "
                     "diameter" + ("; the ring gear's body as an external gear's of its root "
                                   "circle" if pair.gear.internal else "") + ", corrected to 3D finite "
                     "elements of the whole gear) coupled along the face as a Pasternak line "
                     "(contact.compliance), solved with the contact in one system", result)
    _load_distribution(case, pair, result)
    if case.analysis.interference:
        _spur_interference(mesh, pair, cycle, result)


#: the separation (as a multiple of ISO's single-pair approach under the whole load) up
#: to which a pair is kept for the loaded contact: the tooth pairs a loaded mesh may bring in
LOADED_REACH = 3.0


def _loaded_reach(pair, normal_load: float, E_pinion: float, E_gear: float) -> float:
    """The separation (mm) within which tooth pairs are candidates for the loaded contact:
    LOADED_REACH times the normal approach of one pair carrying the whole normal load with
    ISO 6336-1's single stiffness c' (Method B, scaled by E/E_steel as ISO does):
    F_n·cos²β_b/(b·c')."""
    from .analytic.stiffness import E_STEEL

    c = single_stiffness(pair.pinion.teeth, -pair.gear.teeth if pair.gear.internal
                         else pair.gear.teeth, pair.pinion.profile_shift,
                         pair.gear.profile_shift, pair.pinion.helix_angle)
    c *= 2.0 * E_pinion * E_gear / (E_pinion + E_gear) / E_STEEL
    width = min(pair.pinion.face_width, pair.gear.face_width)
    approach_um = normal_load * math.cos(pair.pinion.base_helix_angle) ** 2 / (width * c)
    return LOADED_REACH * approach_um * 1e-3


def _shaft_sections(pair, result: Result) -> None:
    """The shafts' deflections over the face (shaft.py; already in the pinion's deflection
    the contact used): per member the displacement of its flank toward the mate from
    bending and from torsion, relative to mid-face, and in the summary their slopes summed
    over the members (positive closing end B, like misalignment.slope)."""
    result.sections["shaft"] = {
        name: {"face_mm": s.face.round(4).tolist(),
               "bending_um": (s.bending * 1e3).round(4).tolist(),
               "torsion_um": (s.torsion * 1e3).round(4).tolist(),
               "bending_slope_rad": s.bending_slope, "torsion_slope_rad": s.torsion_slope}
        for name, s in pair.shafts.items()}
    result.sections["summary"].update(
        shaft_bending_slope_rad=sum(s.bending_slope for s in pair.shafts.values()),
        shaft_torsion_slope_rad=sum(s.torsion_slope for s in pair.shafts.values()),
        shaft_note="the shafts' bending between their bearings and the bodies' twist over the "
                   "face under the mesh force, toward the mate along the line of action, "
                   "relative to mid-face; added to the pinion's deflection before the contact "
                   "is searched: first with the force spread evenly over the face, then "
                   "(passes) as the loaded contact's mean line load over the cycle spreads it, "
                   "until the deflection changes by less than "
                   f"{1e3 * SHAFT_TOLERANCE:g} µm (changes_um: after each pass, the "
                   "largest change the loaded line load makes)")


#: a collision point counts as interference when it lies this close (mm) to a member's tip
#: or root circle, or beyond them; between them, on the involute flanks, it is the contact
#: (working flanks) or the backlash used up (back flanks)
INTERFERENCE_BAND = 0.05


#: chordal tolerance (mm) of the meshes the bodies are collided as: a fifth of the band
INTERFERENCE_MESH = 0.01


@functools.lru_cache(maxsize=16)
def _collision_teeth(gear, modifications, teeth: int):
    """A member's `teeth` tooth surfaces as a collision body (chords within
    INTERFERENCE_MESH) and its band of working radii (form to tip circle, mm): built once
    per process for the same teeth (a sweep's worker reuses them; each query places the
    body afresh)."""
    from .mesh import collision_body, gear_mesh
    from .surfaces.outline import ToothOutline

    outline = ToothOutline(gear, modifications)
    return (collision_body(*gear_mesh(outline, teeth, INTERFERENCE_MESH)),
            tuple(sorted((outline.generated.form_radius, gear.tip_radius))))


def _spur_interference(mesh, pair, cycle, result: Result) -> None:
    """Tip and root interference of the placed bodies (python-fcl) at every mesh position:
    tooth surfaces (mesh.gear_mesh, chords within INTERFERENCE_MESH) of the teeth in contact
    over the cycle and one more on each side (a tooth entering mesh), their BVHs built once
    and placed at each position (_collision_teeth)."""
    from .mesh import interference, place

    rows = cycle.rows
    reach = max(abs(r["pair"]) for r in rows) + 1     # the teeth in contact, and one more
    bodies, bands = {}, {}
    for name, gear, mods in (("pinion", pair.pinion, pair.pinion_modifications),
                             ("gear", pair.gear, pair.gear_modifications)):
        bodies[name], bands[name] = _collision_teeth(gear, mods, 2 * reach + 1)
    found, back = [], []
    for roll in sorted({r["roll_deg"] for r in rows}):
        lag = next(float(cycle.gear_turn[k]) for k, r in enumerate(rows) if r["roll_deg"] == roll)
        phi = math.radians(roll)
        frames = {"pinion": mesh.pinion_frame(phi), "gear": mesh.gear_frame(phi, 0, lag)}
        hit = interference(*(place(bodies[n], frames[n].R, frames[n].origin)
                             for n in ("pinion", "gear")))
        if not hit.found:
            continue
        on_flanks = np.ones(len(hit.points), bool)
        for name, frame in frames.items():
            r = np.hypot(*frame.to_local(hit.points)[:, :2].T)
            lo, hi = bands[name]
            on_flanks &= (r > lo + INTERFERENCE_BAND) & (r < hi - INTERFERENCE_BAND)
        if not on_flanks.all():
            found.append({"roll_deg": roll,
                          "points_mm": hit.points[~on_flanks][:5].round(4).tolist()})
        coast = on_flanks & (_pinion_side(frames["pinion"], pair.pinion, hit.points) < 0)
        if coast.any():
            back.append({"roll_deg": roll, "points_mm": hit.points[coast][:5].round(4).tolist()})
    result.sections["interference"] = {
        "checked_positions": len({r["roll_deg"] for r in rows}), "band_mm": INTERFERENCE_BAND,
        "found": found, "back_flanks": back}
    backlash = f"the normal backlash {round(pair.normal_backlash * 1e3, 1) + 0.0:g} µm"
    result.checks.append(Check("no tip or root interference of the bodies", not found,
                               f"{len(found)} positions with interference"
                               + (f", first at roll {found[0]['roll_deg']:.2f} deg near "
                                  f"{found[0]['points_mm'][0]} mm" if found else "")
                               + (f"; the back flanks touch too ({backlash} is used up): the "
                                  "tips run into the mates' back flanks" if found and back
                                  else "")))
    result.checks.append(Check(
        "backlash left under the misalignment (the back flanks clear)", not back,
        (f"the back flanks touch at {len(back)} positions, first at roll "
         f"{back[0]['roll_deg']:.2f} deg near {back[0]['points_mm'][0]} mm: {backlash} is used "
         "up (case field backlash)") if back else f"{backlash} clears at every position"))


def _pinion_side(frame, pinion, points: np.ndarray) -> np.ndarray:
    """+1 where a world point lies on the working (+1) half of its nearest pinion tooth or
    the space beside it, -1 on the coast half."""
    local = frame.to_local(points)
    angle = np.arctan2(local[:, 1], local[:, 0]) - pinion.twist_per_length * local[:, 2]
    pitch = 2.0 * math.pi / pinion.teeth
    return np.where((angle + 0.5 * pitch) % pitch - 0.5 * pitch >= 0.0, 1, -1)


def _loaded_transmission_error(cycle, summary: dict) -> None:
    """loaded_transmission_error_urad on every row of a position whose loaded contact was
    solved: the unloaded one plus D/turn_slope, D (mm) the position's common approach (a
    loaded pair's approach: its contact deformation and, where modelled, its teeth's
    bending), and its peak to peak in the summary. None where the position has no solved
    pair."""
    positions: dict[float, list[int]] = {}
    for k, row in enumerate(cycle.rows):
        positions.setdefault(row["roll_deg"], []).append(k)
    values = []
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
    summary["loaded_transmission_error_peak_to_peak_urad"] = (
        max(values) - min(values) if len(values) == len(positions) else None)
    summary["transmission_error_note"] = (
        "transmission errors are the gear's (a worm set's wheel's) rotation from where "
        "conjugate flanks would hold it, in µrad, positive where it lags behind; the loaded "
        "one adds the turn that closes the position's common approach D (half-space contact "
        "and, where modelled, tooth bending): D/r_b2·cos(beta_b) on a parallel pair")


def _loaded_sections(cycle, C_E: float, grid: int, teeth, bending: str,
                     result: Result) -> None:
    """The loaded contact of every row (contact.loaded): bem_* and edge keys on each row
    (bem_status "solved", "unloaded" or "failed" with bem_reason: a position the solver
    cannot answer says so in its own rows and the others keep theirs), their worst in the
    summary, and the checks that every contact was solved and none is edge-loaded."""
    if not grid:
        return
    from .contact.loaded import (EDGE_PRESSURE_RATIO, EDGE_STRIP, END_LOAD_RATIO,
                                 edge_breaks, loaded_cycle, unsolved)

    rows = cycle.rows
    try:
        loaded, failed = loaded_cycle(cycle, C_E, grid, teeth)
    except (ValueError, RuntimeError) as exc:   # no gap field to solve on: the stage fails
        loaded, failed = [None] * len(rows), {k: str(exc) for k in range(len(rows))}
    result.loaded = loaded
    for k, (row, contact) in enumerate(zip(rows, loaded)):
        row.update(unsolved("failed", failed[k]) if k in failed else
                   unsolved("unloaded") if contact is None else contact.summary)
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
    edged = [r for r in answered if r["edge_loaded"]]
    breaks = edge_breaks(cycle)
    rounded = ({f"{member}_tip" for member in breaks.roundings}
               | {f"{member}_end_{end}" for member in breaks.chamfers for end in "AB"})
    candidates = edged or answered
    highest = max(r["edge_pressure_MPa"] for r in candidates)
    # the first of those within 0.1 % (a spline's teeth all press alike, to the pressure
    # grid's resolution of their edges)
    worst = next(r for r in candidates if r["edge_pressure_MPa"] >= (1 - 1e-3) * highest)
    summary.update(
        bem_max_p_max_MPa=max(r["bem_p_max_MPa"] for r in answered),
        max_flank_p_max_MPa=max(r["flank_p_max_MPa"] for r in answered),
        max_edge_pressure_MPa=max(r["edge_pressure_MPa"] for r in answered),
        max_edge_load_fraction=max(r["edge_load_fraction"] for r in answered),
        edge_loaded_contacts=len(edged),
        end_loaded_contacts=sum(bool(r["end_loaded"]) for r in answered),
        max_end_load_ratio=max(r["end_load_ratio"] for r in answered),
        edge_pressure_note=f"edge_pressure_MPa is the pressure averaged over a {EDGE_STRIP} mm "
                           "strip at a sharp edge, the largest on the rounding at a rounded tip "
                           "(a smooth surface: Hertz on its radius), flank_p_max_MPa the "
                           f"active flank's peak more than {EDGE_STRIP} mm inside its edges "
                           "(a tip rounding's start among them: what a lead crown sizes), and "
                           "bem_p_max_MPa the larger of the two: both converge as the "
                           "grid is refined; bem_raw_peak_MPa, the largest cell pressure, grows "
                           "without bound at a sharp edge and is not a design value; free face "
                           "ends are quarter-spaces (mirror-pressure correction); a contact is "
                           "end_loaded when its load per mm of face in the strip at a face end "
                           f"exceeds {END_LOAD_RATIO:g} times its mean over its length in contact "
                           "(end_load_ratio: what a lead crown is for), edge_loaded when "
                           "end-loaded or when the pressure at a tip, root or form edge exceeds "
                           f"{EDGE_PRESSURE_RATIO:g} times the contact's interior peak")
    result.checks.append(Check(
        "loaded contact: no edge load", not edged,
        f"{len(edged)} of {len(answered)} contacts edge-loaded; highest edge pressure "
        f"{worst['edge_pressure_MPa']:.0f} MPa "
        + ("on the rounded edge" if worst["edge_pressure_at"] in rounded
           else f"averaged over {EDGE_STRIP} mm")
        + f" ({worst['edge_pressure_at']}), "
        f"{worst['edge_pressure_MPa'] / max(worst['bem_p_max_MPa'], 1e-300):.2f} of the "
        f"contact's peak {worst['bem_p_max_MPa']:.0f} MPa, at roll {worst['roll_deg']:.2f} deg "
        f"pair {worst['pair']}; largest end load ratio "
        f"{max(r['end_load_ratio'] for r in answered):.2f} (end-loaded above "
        f"{END_LOAD_RATIO:g})"))


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


#: strips across the face the line loads of a position are summed on: the load
#: distribution at the scale of the face. They leave out the EDGE_STRIP at each face end:
#: a sharp end's pressure peak there is the edge pressure's business, not K_H_beta's
FACE_STRIPS = 20


def _load_distribution(case: schema.SpurCase, pair, result: Result) -> None:
    """The mesh's load along the face from the loaded contacts (their line loads, all pairs
    of a position summed on one face grid of the pinion) and what follows from it, beside
    ISO 6336-1's figures for the same pair:
    - load_distribution: face_mm, and per position roll_deg, line_load_N_per_mm, K_H_beta
      (that position's largest line load over W/b), and mean_line_load_N_per_mm (the
      line load averaged over the mesh cycle's positions);
    - summary: K_H_beta, ISO 6336-1's face load factor: the largest over the face of the
      line load averaged over the mesh cycle, over the mean W/b (b the common face width);
      the contact lines' sweep across the face within the cycle, which ISO assigns to
      K_H_alpha, averages out; K_H_beta_instantaneous, the largest over the cycle of a
      position's largest line load over W/b, beside it;
      mesh_stiffness_N_per_mm_um, the mean over the cycle of W/(D - s_min)/b·cos²β_b (D the
      position's loaded approach, s_min its least unloaded separation; the cos²β_b makes it
      ISO's transverse force over transverse deflection), the model's counterpart of c_γα; single_stiffness_N_per_mm_um, the largest of it at positions
      with one loaded pair (c'); the ISO values c' and c_γα (Method B) and ISO's K_H_beta
      for the case's slope over the face with the model's stiffness (Method C, linear mesh
      misalignment: no crown, no running-in) beside them.
    Nothing is added when no position was solved (or the loaded contact was not asked for)."""
    cycle, loaded = result.cycle, result.loaded
    if loaded is None:
        return
    rows = cycle.rows
    positions: dict[float, list[int]] = {}
    for k, row in enumerate(rows):
        positions.setdefault(row["roll_deg"], []).append(k)
    width = min(pair.pinion.face_width, pair.gear.face_width)
    transverse = math.cos(pair.pinion.base_helix_angle) ** 2
    from .contact.loaded import EDGE_STRIP

    end = 0.5 * pair.pinion.face_width - EDGE_STRIP
    edges = np.linspace(-end, end, FACE_STRIPS + 1)
    rolls, lines, loads, factors, stiffness, single = [], [], [], [], [], []
    for roll, ks in positions.items():
        solved = [k for k in ks if loaded[k] is not None]
        if not solved or any(rows[k]["bem_status"] == "failed" for k in ks):
            continue
        line = sum(loaded[k].line_load(edges) for k in solved)
        load = sum(loaded[k].solution.load_N for k in solved)
        rolls.append(roll)
        lines.append(line)
        loads.append(load)
        factors.append(float(line.max() / (load / width)))
        lead = max(solved, key=lambda k: loaded[k].solution.load_N)
        closing = loaded[lead].solution.approach_mm - min(rows[k]["separation_mm"] for k in ks)
        if closing > 0:     # ISO's c: the transverse force over the transverse deflection
            stiffness.append(load / closing / width * 1e-3 * transverse)
            if len(solved) == 1:
                single.append(stiffness[-1])
    if not rolls:
        return
    # the positions divide one mesh cycle evenly: their mean is the cycle's mean
    mean_line = np.mean(lines, axis=0)
    result.sections["load_distribution"] = {
        "face_mm": (0.5 * (edges[1:] + edges[:-1])).round(4).tolist(), "roll_deg": rolls,
        "line_load_N_per_mm": [line.round(3).tolist() for line in lines],
        "mean_line_load_N_per_mm": mean_line.round(3).tolist(),
        "K_H_beta": factors,
        "note": f"line loads along the pinion's face (N/mm of face, along the contact normal) "
                f"on {FACE_STRIPS} strips between {EDGE_STRIP} mm from each face end (the edge "
                "pressure covers those), face_mm their centres, all tooth pairs of a position "
                f"summed; K_H_beta is the largest over the mean W/b on b = {width:g} mm, "
                "at each position; mean_line_load_N_per_mm their mean over the cycle"}
    summary = result.sections["summary"]
    iso_single = single_stiffness(pair.pinion.teeth, -pair.gear.teeth if pair.gear.internal
                                  else pair.gear.teeth, pair.pinion.profile_shift,
                                  pair.gear.profile_shift, case.helix_angle)
    iso_mesh = mesh_stiffness(iso_single, pair.transverse_mesh().contact_ratio)
    model_mesh = float(np.mean(stiffness)) if stiffness else None
    slope = (case.misalignment.slope + summary.get("shaft_bending_slope_rad", 0.0)
             + summary.get("shaft_torsion_slope_rad", 0.0))
    summary.update(
        K_H_beta=float(mean_line.max() / (np.mean(loads) / width)),
        K_H_beta_instantaneous=max(factors),
        mesh_stiffness_N_per_mm_um=model_mesh,
        single_stiffness_N_per_mm_um=max(single) if single else None,
        iso_single_stiffness_N_per_mm_um=iso_single,
        iso_mesh_stiffness_N_per_mm_um=iso_mesh,
        iso_K_H_beta_linear=(face_load_factor(abs(slope) * width * 1e3,
                                              0.85 * model_mesh,
                                              summary["tangential_load_N"] / width)
                             if model_mesh else None),
        stiffness_note="mesh_stiffness_N_per_mm_um is the model's mean secant stiffness over "
                       "the cycle per mm of face (ISO's c_γα counterpart), "
                       "single_stiffness_N_per_mm_um its largest with one pair in contact "
                       "(c'); iso_* are ISO 6336-1 Method B for solid blanks; "
                       "iso_K_H_beta_linear is ISO 6336-1 Method C for the case's slope (plus "
                       "the shafts' slopes) as a linear mesh misalignment over b with c_γβ = "
                       "0.85 of the model's mesh stiffness, and ignores crowns and running-in")


def _contact_sections(cycle, loads: dict, result: Result) -> None:
    """positions, summary, ease-off and the edge checks of a contact cycle: a
    contact.cycle.ContactCycle (kept whole in result.cycle for pictures and the pressure
    solver), or the rows of an imported pair."""
    from .contact.cycle import LOAD_SHARING_RULE

    rows = cycle if isinstance(cycle, list) else cycle.rows
    if not isinstance(cycle, list):
        ease = cycle.ease_off
        result.cycle = cycle
        result.sections["ease_off"] = {
            "face_mm": ease.face_mm.round(4).tolist(), "radius_mm": ease.radius_mm.round(4).tolist(),
            "separation_um": [[None if not np.isfinite(s) else round(float(s) * 1e3, 3)
                               for s in line] for line in ease.separation],
            "approach_um": cycle.settings.approach * 1e3,
            "member": cycle.settings.ease_off_member}
    result.sections["positions"] = rows
    # the rigid analysis's figures: pairs kept beyond the approach for the loaded contact
    # (rigid_contact false) touch nowhere
    rows = [r for r in rows if r.get("rigid_contact", True)]
    te = [r["transmission_error_urad"] for r in rows]
    summary = {**loads, "max_p_max_MPa": max(r["p_max_MPa"] for r in rows),
               "transmission_error_peak_to_peak_urad": max(te) - min(te),
               "face_position_range_mm": [min(r["face_position_mm"] for r in rows),
                                          max(r["face_position_mm"] for r in rows)],
               "line_contacts": sum(r["contact_model"] == "line" for r in rows),
               "area_contacts": sum(r["contact_model"] == "area" for r in rows),
               "edge_contacts": sum(r["edge_contact"] for r in rows),
               "load_sharing": LOAD_SHARING_RULE}
    for kind, label in (("face", "at the face ends (edge loading)"),
                        ("profile", "at the tip and form edges (corner contact)")):
        candidates = [(v, k, r["roll_deg"]) for r in rows for k, v in r["edge_margins_mm"].items()
                      if ("end_" in k) == (kind == "face")]
        if not candidates:
            continue
        margin, edge, roll = min(candidates)
        summary[f"worst_{kind}_edge_margin_mm"], summary[f"worst_{kind}_edge"] = margin, edge
        result.checks.append(Check(f"contact pattern clear of the edges {label}", margin >= 0,
                                   f"worst margin {margin:.3f} mm ({edge}) at roll {roll:.2f} deg"))
    result.sections["summary"] = summary


def spline_geometry_case(case: schema.SplineCase) -> Result:
    """Geometry of an involute spline: diameters, the members' shifts, the hub's form circle
    and crown, and the eq 19 crown limit for the clearance."""
    from . import gearset
    from .surfaces.generation import generate_side

    try:
        pair = gearset.spline_pair(case)
    except ValueError as exc:
        raise CaseError(str(exc)) from None
    spline, hub, sleeve = pair.spline, pair.hub, pair.sleeve
    generated = generate_side(hub)
    section = {f"{k}_diameter_mm": v for k, v in spline.diameters.items()}
    section.update(pitch_diameter_mm=spline.pitch_diameter, base_diameter_mm=2 * hub.base_radius,
                   hub_profile_shift=hub.profile_shift, sleeve_profile_shift=sleeve.profile_shift,
                   hub_form_diameter_mm=2 * generated.form_radius,
                   normal_clearance_per_side_mm=0.5 * case.clearance * math.cos(case.pressure_angle))
    result = Result(sections={"spline": section})
    result.checks.append(Check("hub is not undercut", not generated.undercut,
                               f"form diameter {2 * generated.form_radius:.4f} mm"))
    result.checks.append(Check("hub form circle below the sleeve's minor diameter",
                               2 * generated.form_radius < spline.diameters["sleeve_minor"],
                               f"form {2 * generated.form_radius:.4f} mm, sleeve minor "
                               f"{spline.diameters['sleeve_minor']:.4f} mm"))
    if case.crown is not None:
        crown = pair.hub_modifications.lead_crown
        radius = crown.radius_for(case.engaged_length) * math.cos(case.pressure_angle)
        section["crown_radius_mm"] = radius
        section["crown_height_mm"] = float(crown.drop(0.5 * case.engaged_length, case.engaged_length)
                                           / math.cos(case.pressure_angle))
    if case.torque is not None:
        _spline_contact(case, pair, result)
    return result


def _spline_contact(case: schema.SplineCase, pair, result: Result) -> None:
    """Every tooth of the spline under the angular misalignment: a coaxial pair of ratio 1
    (assembly.ParallelMesh with zero centre distance), the sleeve tilted about the normal of
    tooth 0's plane of action; the lag closes the clearance."""
    from .assembly import Misalignment, ParallelMesh
    from .contact.cycle import parallel_cycle
    from .gearset import GearPair, working_flank

    coaxial = GearPair(pair.hub, pair.sleeve, pair.hub_modifications, pair.sleeve_modifications,
                       0.0, case.pressure_angle)
    mesh = ParallelMesh(coaxial, Misalignment(slope=case.misalignment))
    hub = working_flank(pair.hub, pair.hub_modifications, 1)
    sleeve = working_flank(pair.sleeve, pair.sleeve_modifications, mesh.gear_side)
    wt = case.torque / (0.5 * pair.spline.pitch_diameter)
    normal_load = wt / math.cos(case.pressure_angle)
    C_E = hertz.compliance(case.material.E, case.material.nu, case.material.E, case.material.nu)
    a = case.analysis
    try:
        cycle = parallel_cycle(mesh, hub, sleeve, normal_load, C_E,
                              _cycle_settings(a, pairs=tuple(range(case.teeth))))
    except (ValueError, RuntimeError) as exc:
        raise CaseError(f"misalignment / torque: no contact could be found: {exc}") from None
    _contact_sections(cycle, {"tangential_load_N": wt, "normal_load_N": normal_load}, result)
    from .contact.compliance import PairCompliance, tooth_compliance

    teeth = PairCompliance(tooth_compliance(pair.hub, case.material.E, case.material.nu),
                           tooth_compliance(pair.sleeve, case.material.E, case.material.nu))
    _loaded_sections(cycle, C_E, a.pressure_grid, teeth,
                     "tooth bending from the hub's and sleeve's exact transverse slices "
                     "(bending, shear, axial and body compliance across the working depth: a "
                     "load at one height bends the whole tooth; the hub a solid shaft with a "
                     "bore of half its root diameter, the sleeve's body as an external gear's "
                     "of its root circle; corrected to 3D finite elements of a gear) coupled "
                     "along the engaged length as a Pasternak "
                     "line (contact.compliance), solved with the contact in one system", result)
    per_position = {}
    for r in cycle.rows:
        per_position.setdefault(r["roll_deg"], []).append(r["pair"])
    result.sections["summary"]["teeth_in_contact"] = {f"{k:.3f}": v for k, v in per_position.items()}


def worm_geometry_case(case: schema.WormCase) -> Result:
    """Geometry of a worm set: the worm, the hob and the enveloped wheel's blank (DIN 3975)."""
    from . import gearset

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
    result = Result(sections={
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
              "the blank follows DIN 3975 guideline proportions"])
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
        _worm_contact(case, parts, result)
    return result


def _flankless_worm(case: schema.WormCase, worm, wheel) -> str:
    """Why no contact was found on a worm whose flanks start (a ZI worm's base cylinder, a
    ZK's form limit) above the radius the wheel's tips reach, naming the fields that size
    it: a slender worm of few starts and a steep lead."""
    given = "worm.lead_angle" if case.worm.lead_angle is not None else "worm.pitch_diameter"
    return (f"{given} / worm.starts / worm module: no contact could be found on a "
            f"{worm.starts}-start {worm.form} worm of d1 = {worm.pitch_diameter:.4g} mm "
            f"(diameter quotient q = d1/m_x = {worm.pitch_diameter / worm.axial_module:.3g}): "
            f"its flanks start at diameter {2 * worm.form_radius:.4g} mm, above the "
            f"{2 * wheel.throat_radius:.4g} mm the wheel's tips reach; give a larger pitch "
            "diameter (a smaller lead angle) or fewer starts")


def _worm_contact(case: schema.WormCase, parts, result: Result) -> None:
    """Contact of the loaded flank pair (`[load] flank`) over one mesh cycle, with seed 001's
    anti-rattle-spring tilt of the worm shaft when a spring is given."""
    from .assembly import WormMesh, WormMisalignment
    from .contact.cycle import parallel_cycle

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
    mesh = WormMesh(wheel, WormMisalignment(m.center_distance_error, m.shaft_angle_error,
                                            m.wheel_axial_shift, tilt, pivot))
    wheel_material = case.wheel_material or case.material
    C_E = hertz.compliance(case.material.E, case.material.nu, wheel_material.E, wheel_material.nu)
    a = case.analysis
    try:
        cycle = parallel_cycle(mesh, worm, wheel, normal_load, C_E,
                              _cycle_settings(a, pairs=(-2, -1, 0, 1, 2),
                                              ease_off_grid=(41, 61), ease_off_member="gear"))
    except (ValueError, RuntimeError) as exc:
        if worm.form_radius > wheel.throat_radius:
            raise CaseError(_flankless_worm(case, worm, wheel)) from None
        raise CaseError(f"misalignment / load: no contact could be found: {exc}") from None
    _contact_sections(cycle, loads, result)
    from .contact.compliance import PairCompliance, ThreadCompliance, WheelToothCompliance

    teeth = PairCompliance(ThreadCompliance(worm, case.material.E, case.material.nu),
                           WheelToothCompliance(wheel, wheel_material.E, wheel_material.nu))
    _loaded_sections(cycle, C_E, a.pressure_grid, teeth,
                     "tooth bending from the wheel tooth's mid-plane section (the enveloped "
                     "flank, continued straight to the root circle; loads placed by their "
                     "height from the throat circle, coupled along the face) and the worm "
                     "thread's axial section in the worm's material (coupled along the "
                     "thread, no end in reach); bending, shear, axial and body compliance "
                     "(contact.compliance), solved with the contact in one system", result)
    _publish_names(result, PUBLISHED_NAMES["worm"])


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
        for key in ("edge_contact_at", "edge_pressure_at"):
            if key in row:
                row[key] = edge(row[key])
        if isinstance(row.get("edge_margins_mm"), dict):
            row["edge_margins_mm"] = {edge(k): v for k, v in row["edge_margins_mm"].items()}
    summary = result.sections.get("summary", {})
    for key in ("worst_face_edge", "worst_profile_edge"):
        if key in summary:
            summary[key] = edge(summary[key])
    if "ease_off" in result.sections:
        result.sections["ease_off"]["member"] = names[result.sections["ease_off"]["member"]]
    result.checks = [replace(c, detail=edge(c.detail)) for c in result.checks]


def imported_case(case: schema.ImportedCase) -> Result:
    """A pair from the user's STL/STEP bodies: contact over the mesh cycle on the meshes
    (contact.imported). Reads the two body files (named and checked by the case)."""
    from .assembly import Misalignment, ParallelMesh
    from .contact.imported import chordal_error, imported_cycle, teeth_per_turn
    from .mesh import load_surface

    bodies = {}
    for name in ("pinion", "gear"):
        spec = getattr(case, name)
        try:
            bodies[name] = load_surface(spec.file, case.step_tolerance)
        except ValueError as exc:
            raise CaseError(f"{name}.file: {exc}") from None
        found = teeth_per_turn(bodies[name])
        if not abs(found - spec.teeth) < 0.25:
            seen = (f"its tooth tips are {360.0 / found:.3f} deg apart ({found:.2f} teeth a "
                    "turn)" if math.isfinite(found) else "it shows fewer than two tooth tips "
                    "about its z axis")
            raise CaseError(f"{name}.teeth: {spec.teeth}, but {Path(spec.file).name} is no "
                            f"gear of {spec.teeth} teeth about its z axis: {seen}; give the "
                            "body's tooth count, and a file whose z axis is the gear's axis")
    tips = {name: float(np.hypot(body.vertices[:, 0], body.vertices[:, 1]).max())
            for name, body in bodies.items()}
    if not max(tips.values()) < case.center_distance < sum(tips.values()):
        raise CaseError(f"center_distance: {case.center_distance:.4g} mm: the bodies' tip radii "
                        f"are {tips['pinion']:.4g} and {tips['gear']:.4g} mm, so their teeth "
                        f"can only mesh between {max(tips.values()):.4g} and "
                        f"{sum(tips.values()):.4g} mm")
    if case.pinion_phase:
        bodies["pinion"] = bodies["pinion"].turned(case.pinion_phase)
    z1, z2 = case.pinion.teeth, case.gear.teeth
    m = case.misalignment
    mesh = ParallelMesh.of_layout(z1, z2, case.center_distance, case.pressure_angle,
                                  Misalignment(m.slope, m.slope_normal, m.center_distance_error,
                                               m.axial_shift), gear_start=case.gear_phase)
    pitch_radius = case.center_distance * z1 / (z1 + z2)
    wt = case.load.tangential_load or case.load.torque / pitch_radius
    normal_load = wt / (math.cos(case.pressure_angle) * math.cos(case.base_helix_angle))
    gear_material = case.gear_material or case.material
    C_E = hertz.compliance(case.material.E, case.material.nu, gear_material.E, gear_material.nu)
    a = case.analysis
    try:
        rows = imported_cycle(mesh, bodies["pinion"], bodies["gear"], normal_load, C_E,
                              _cycle_settings(a), tuple(None if b.form_diameter is None else
                                                        0.5 * b.form_diameter
                                                        for b in (case.pinion, case.gear)))
    except ValueError as exc:
        raise CaseError(f"pinion / gear: no contact could be found: {exc}") from None
    chordal = {name: chordal_error(body) for name, body in bodies.items()}
    result = Result(sections={"bodies": {
        name: {"file": getattr(case, name).file, "teeth": getattr(case, name).teeth,
               "triangles": len(body.faces), "chordal_error_um": 1e3 * chordal[name],
               "watertight": bool(body.mesh.is_watertight)}
        for name, body in bodies.items()}})
    unchecked = [name for name in ("pinion", "gear") if getattr(case, name).form_diameter is None]
    result.notes.append("imported bodies: contact on the smooth surfaces the facets stand for "
                        "(Phong tessellation through normals fitted to the facets), by transverse "
                        "sections of the pinion's driving flanks; tips at each body's largest "
                        "radius" + (f"; form edge not checked for the {' and '.join(unchecked)} "
                                    "(give form_diameter)" if unchecked else ""))
    _contact_sections(rows, {"tangential_load_N": wt, "normal_load_N": normal_load}, result)
    # what the facets allow: their chordal errors as a turn of the gear at its base radius
    base_radius = case.center_distance * z2 / (z1 + z2) * math.cos(case.pressure_angle)
    result.sections["summary"]["transmission_error_facet_bound_urad"] = \
        1e6 * (chordal["pinion"] + chordal["gear"]) / base_radius
    return result
