"""The load-dependent mesh loss of a cylindrical gear pair: ISO/TR 14179-2's mean
coefficient of friction (Schlenk's, as ISO/TR 14179-2:2001 states it) and Ohlendorf's
gear loss factor H_V (P_loss = P_in·μ·H_V, as ISO/TR 14179-2 uses it)."""

from __future__ import annotations

import math

#: the least sum of the tangential speeds at the pitch point (m/s) for which ISO/TR
#: 14179-2's μ is taken: an assumed bound, not from the standard's text (not at hand), which
#: fits gears running in an elastohydrodynamic film (Schlenk's FZG tests ran at metres per
#: second); μ grows as v_Σ^-0.2 without bound below it (3.5 at 1e-6 rpm), and a slower
#: mesh gives its friction_coefficient instead
SUM_VELOCITY_LEAST = 1.0


def friction_coefficient(line_load: float, sum_velocity: float, radius: float,
                         viscosity: float, roughness: float, X_L: float) -> float:
    """μ = 0.048·(w/(v_Σ·ρ_red))^0.2·η^-0.05·Ra^0.25·X_L (ISO/TR 14179-2): w the transverse
    tangential load per face width (N/mm), v_Σ the sum of the tangential speeds (m/s), ρ_red
    the relative radius of curvature (mm), η the oil's dynamic viscosity (mPa·s), Ra the
    mean of the flanks' roughness (µm), X_L the lubricant factor."""
    return (0.048 * (line_load / (sum_velocity * radius)) ** 0.2 * viscosity ** -0.05
            * roughness ** 0.25 * X_L)


def gear_loss_factor(z1: int, z2: int, base_helix: float, contact_ratio: float,
                     tip_ratio_pinion: float, tip_ratio_gear: float) -> float:
    """Ohlendorf's H_V = π(u + 1)/(z1·u·cos β_b)·(1 - ε_α + ε_1² + ε_2²), u = z2/z1, ε_1
    and ε_2 the parts of the transverse contact ratio ε_α from the pitch point to the
    pinion's and to the gear's tip (load shared equally where two pairs mesh)."""
    u = z2 / z1
    return (math.pi * (u + 1.0) / (z1 * u * math.cos(base_helix))
            * (1.0 - contact_ratio + tip_ratio_pinion ** 2 + tip_ratio_gear ** 2))
