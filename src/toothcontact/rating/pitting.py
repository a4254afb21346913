"""Surface durability (pitting) of cylindrical gears: the factors and stresses of ISO
6336-2:2006 Method B, each a closed form of the standard (named in its docstring), checked
against ISO/TR 6336-30:2017 Example 1's printed values (tests/test_iso_rating.py).

The nominal contact stress at the pitch point σ_H0 = Z_H·Z_E·Z_ε·Z_β·sqrt(F_t/(d1·b)·(u+1)/u),
the contact stress of each member σ_H = Z_B (pinion) or Z_D (gear) times σ_H0 times
sqrt(K_A·K_v·K_Hβ·K_Hα), and the permissible stress σ_HP = σ_Hlim·Z_NT·Z_L·Z_v·Z_R·Z_W·Z_X /
S_Hmin. u = z2/z1 is negative for an internal gear. Units: mm, N, MPa (N/mm²), rad, m/s,
mm²/s.
"""

from __future__ import annotations

import math


def zone_factor(base_helix: float, transverse_pressure: float, working_pressure: float) -> float:
    """Z_H = sqrt(2·cos β_b·cos α_wt / (cos²α_t·sin α_wt)) (ISO 6336-2:2006, zone factor)."""
    return math.sqrt(2.0 * math.cos(base_helix) * math.cos(working_pressure)
                     / (math.cos(transverse_pressure) ** 2 * math.sin(working_pressure)))


def elasticity_factor(E1: float, nu1: float, E2: float, nu2: float) -> float:
    """Z_E = sqrt(1/(π·((1-ν1²)/E1 + (1-ν2²)/E2))) (sqrt(MPa); ISO 6336-2:2006, elasticity
    factor): 189.8 for steel on steel."""
    return math.sqrt(1.0 / (math.pi * ((1.0 - nu1 ** 2) / E1 + (1.0 - nu2 ** 2) / E2)))


def contact_ratio_factor(transverse: float, overlap: float) -> float:
    """Z_ε (ISO 6336-2:2006, contact ratio factor) of the transverse and overlap ratios:
    sqrt((4-ε_α)/3·(1-ε_β) + ε_β/ε_α) for ε_β < 1 (spur: ε_β = 0), sqrt(1/ε_α) beyond."""
    if overlap >= 1.0:
        return math.sqrt(1.0 / transverse)
    return math.sqrt((4.0 - transverse) / 3.0 * (1.0 - overlap) + overlap / transverse)


def helix_angle_factor(helix: float) -> float:
    """Z_β = 1/sqrt(cos β) (ISO 6336-2:2006, helix angle factor; the TR's 1.01944 at 15.8°)."""
    return 1.0 / math.sqrt(math.cos(helix))


def single_pair_factors(z1: int, z2: int, tip_diameters: tuple[float, float],
                        base_diameters: tuple[float, float], working_pressure: float,
                        transverse_ratio: float, overlap: float) -> tuple[float, float]:
    """(Z_B, Z_D): the single pair tooth contact factors of pinion and gear (ISO 6336-2:2006),
    which carry σ_H0 at the pitch point to the inner points of single pair contact B and D
    of a spur pair: M1 = tan α_wt / sqrt([sqrt(d_a1²/d_b1² - 1) - 2π/z1]·[sqrt(d_a2²/d_b2²
    - 1) - (ε_α - 1)·2π/z2]) and M2 alike with the members swapped; Z_B = M1, Z_D = M2 where
    above 1 (else 1) for ε_β = 0, 1 for ε_β >= 1, M - ε_β·(M - 1) (at least 1) between.
    z2 < 0: an internal gear, whose Z_D is 1."""
    (da1, da2), (db1, db2) = tip_diameters, base_diameters
    a1 = math.sqrt((da1 / db1) ** 2 - 1.0)
    a2 = math.sqrt((da2 / db2) ** 2 - 1.0)
    step = transverse_ratio - 1.0
    M1 = math.tan(working_pressure) / math.sqrt(
        (a1 - 2.0 * math.pi / z1) * (a2 - step * 2.0 * math.pi / abs(z2)))
    M2 = math.tan(working_pressure) / math.sqrt(
        (a2 - 2.0 * math.pi / abs(z2)) * (a1 - step * 2.0 * math.pi / z1))

    def factor(M: float) -> float:
        if overlap >= 1.0:
            return 1.0
        return max(1.0, M - overlap * (M - 1.0))

    return factor(M1), 1.0 if z2 < 0 else factor(M2)


def _c_ZL(sigma_Hlim: float) -> float:
    """C_ZL = 0.08·(σ_Hlim - 850)/350 + 0.83, σ_Hlim held to 850-1200 MPa (ISO 6336-2:2006)."""
    return 0.08 * (min(max(sigma_Hlim, 850.0), 1200.0) - 850.0) / 350.0 + 0.83


def lubricant_factor(sigma_Hlim: float, viscosity_40: float) -> float:
    """Z_L = C_ZL + 4·(1 - C_ZL)/(1.2 + 134/ν40)² (ISO 6336-2:2006, lubricant factor; ν40 the
    oil's kinematic viscosity at 40 °C, mm²/s; σ_Hlim the softer member's)."""
    c = _c_ZL(sigma_Hlim)
    return c + 4.0 * (1.0 - c) / (1.2 + 134.0 / viscosity_40) ** 2


def velocity_factor(sigma_Hlim: float, velocity: float) -> float:
    """Z_v = C_Zv + 2·(1 - C_Zv)/sqrt(0.8 + 32/v), C_Zv = C_ZL + 0.02 (ISO 6336-2:2006,
    velocity factor; v the pitch line velocity, m/s)."""
    c = _c_ZL(sigma_Hlim) + 0.02
    return c + 2.0 * (1.0 - c) / math.sqrt(0.8 + 32.0 / velocity)


#: ISO 6336-2's mean peak-to-valley roughness R_z of a flank given by its Ra (µm): R_z = 6·Ra,
#: the relation ISO/TR 6336-30 Example 1 uses (Ra 1.0 µm -> its Z_R = 0.96599)
RZ_PER_RA = 6.0


def roughness_factor(sigma_Hlim: float, roughness_Rz: tuple[float, float],
                     relative_radius: float) -> float:
    """Z_R = (3/R_z10)^C_ZR (ISO 6336-2:2006, roughness factor): R_z10 = R_z·(10/ρ_red)^(1/3)
    the mean R_z of the flanks (µm) scaled to a relative radius of curvature of 10 mm
    (ρ_red at the pitch point, mm), C_ZR = 0.32 - 0.0002·σ_Hlim with σ_Hlim held to 850-1200
    MPa."""
    Rz10 = 0.5 * sum(roughness_Rz) * (10.0 / relative_radius) ** (1.0 / 3.0)
    c = 0.32 - 0.0002 * min(max(sigma_Hlim, 850.0), 1200.0)
    return (3.0 / Rz10) ** c


def pitch_point_relative_radius(base_diameters: tuple[float, float], working_pressure: float,
                                internal: bool) -> float:
    """ρ_red = ρ1·ρ2/(ρ1 ± ρ2) at the pitch point, ρ = d_b·tan α_wt / 2 (mm; a ring gear's
    concave flank subtracts)."""
    rho1, rho2 = (0.5 * d * math.tan(working_pressure) for d in base_diameters)
    return rho1 * rho2 / (rho2 - rho1 if internal else rho1 + rho2)


def nominal_contact_stress(Z_H: float, Z_E: float, Z_eps: float, Z_beta: float,
                           tangential_load: float, pinion_diameter: float, face_width: float,
                           ratio: float) -> float:
    """σ_H0 = Z_H·Z_E·Z_ε·Z_β·sqrt(F_t/(d1·b)·(u+1)/u) (MPa; ISO 6336-2:2006): F_t the
    nominal tangential load at the reference circle (N), d1 the pinion's reference
    diameter, b the common face width (mm), u = z2/z1 (negative for an internal gear)."""
    return Z_H * Z_E * Z_eps * Z_beta * math.sqrt(
        tangential_load / (pinion_diameter * face_width) * (ratio + 1.0) / ratio)
