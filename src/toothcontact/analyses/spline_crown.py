"""The spline crown kind: the crown of an involute spline for a misalignment (seed 002)."""

from __future__ import annotations

import math

from .. import case as schema
from ..analytic import hertz, spline
from .result import Check, Result


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
