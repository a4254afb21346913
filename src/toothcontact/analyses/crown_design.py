"""The crown design kind: seed 003's crown for a spur pair (Wang & El-Bayoumy), its
check, its chart's curves and AGMA's uncrowned stress beside it."""

from __future__ import annotations

import math

from .. import case as schema
from ..analytic import agma, crown, hertz
from ..analytic.spur_mesh import SpurMesh
from ..case import CaseError
from .result import Check, Result


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
    chart = crown.design_chart(design, case.crown == "full", profile_curvature, load, C_E,
                               case.edge_clearance, case.allowable_stress)
    result.sections["crown_chart"] = {
        "theta_rad": chart.theta.tolist(),
        "edge_radius_mm": {end: [r if math.isfinite(r) else None for r in radii.tolist()]
                           for end, radii in chart.edge_radius.items()},
        "stress_radius_mm": chart.stress_radius if math.isfinite(chart.stress_radius) else None,
        "reference_stress_MPa": chart.reference_stress, "reference": chart.reference,
        "design_stress_MPa": chart.design_stress, "slope_A": case.slope_A, "slope_B": slope_B,
        "edge_clearance_mm": case.edge_clearance, "face_width_mm": case.face_width,
        "full": case.crown == "full",
        "note": "seed 003's crown design chart: per total slope theta the edge rule's largest "
                "crown radius at each face end (eq 13) and the stress rule's least radius "
                "(eqs 6-11 against the allowable, or the chosen design's stress)"}
    for end, margin in (("A", design.edge_margin_A), ("B", design.edge_margin_B)):
        result.checks.append(Check(f"contact ellipse inside the face at end {end}",
                                   margin >= -1e-9 * case.face_width,
                                   f"edge margin {margin:.4f} mm (negative = edge loading)"))
    if case.allowable_stress is not None:
        result.checks.append(Check("contact stress within the allowable",
                                   ellipse.p0 <= case.allowable_stress,
                                   f"{ellipse.p0:.1f} MPa against {case.allowable_stress:.1f} MPa"))
    return result
