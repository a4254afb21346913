"""The Hertz kind: the contact ellipse of two bodies (exact and Roark's form)."""

from __future__ import annotations

import math

from .. import case as schema
from ..analytic import hertz
from ..case import CaseError
from .result import Check, Result


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
                      "largest relative difference "
                      + (f"{agree:.1e}" if agree >= 1e-12 else "below 10⁻¹² (round-off)")
                      + " (limit 1e-6)", "method")],
    )
