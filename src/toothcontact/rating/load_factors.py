"""Load factors of cylindrical gears by ISO 6336-1:2006: the dynamic factor K_v (Method B),
the transverse load factors K_Hα and K_Fα (Method B), the face load factor K_Hβ for a linear
mesh misalignment (Method C) and the root's K_Fβ from K_Hβ, with the running-in allowances
they take. Each is a closed form of the standard; where the loaded contact supplies a
factor (K_Hβ, the mesh stiffness) ISO calls that Method A (analyses.rating).

Units: mm, µm for deviations and allowances, N, N/mm for line loads, N/(mm·µm) for
stiffness, kg/mm³ for density, rpm, m/s.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

#: the running-in groups of ISO 6336-1 (y_α, y_β): structural and through-hardened steels
#: and pearlitic or bainitic cast irons; grey and ferritic nodular cast irons; surface-
#: hardened and nitrided steels
RUNNING_IN_GROUPS = {"St": "steel", "V": "steel", "GTS": "steel", "GGG": "steel",
                     "GG": "cast_iron", "Eh": "hardened", "IF": "hardened", "NT": "hardened",
                     "NV": "hardened", "NV(nitrocar)": "hardened"}


def _running_in(group: str, amount: float, sigma_Hlim: float, velocity: float,
                rates: tuple[float, float, tuple[float, float], float]) -> float:
    """A running-in allowance (µm) of a deviation `amount` (µm) by ISO 6336-1's pattern:
    rates = (steel's factor over σ_Hlim, grey cast iron's factor, its caps (µm) above 5 and
    above 10 m/s, surface-hardened steel's factor); the steel's cap is 80 µm times its
    factor over σ_Hlim above 5 m/s and half that above 10 m/s, hardened steel's 40 times
    its factor."""
    steel, cast, (cast_cap, cast_fast_cap), hardened = rates
    if group == "hardened":
        return min(hardened * amount, 40.0 * hardened)
    if group == "cast_iron":
        allowance = cast * amount
        return (allowance if velocity <= 5.0
                else min(allowance, cast_cap if velocity <= 10.0 else cast_fast_cap))
    allowance = steel / sigma_Hlim * amount
    if velocity <= 5.0:
        return allowance
    return min(allowance, 80.0 * steel / (1.0 if velocity <= 10.0 else 2.0) / sigma_Hlim)


def profile_running_in(group: str, deviation: float, sigma_Hlim: float,
                       velocity: float) -> float:
    """y_α (µm), the running-in allowance of a base pitch (or profile form) deviation
    (µm) of a material group (RUNNING_IN_GROUPS' values) at the pitch line velocity (m/s)
    (ISO 6336-1:2006, 8.3.3): steels and pearlitic cast irons 160/σ_Hlim·f_pb, at most
    12800/σ_Hlim above 5 m/s and 6400/σ_Hlim above 10 m/s; grey cast iron 0.275·f_pb, at
    most 22 and 11 µm; surface-hardened and nitrided steels 0.075·f_pb, at most 3 µm."""
    return _running_in(group, deviation, sigma_Hlim, velocity, (160.0, 0.275, (22.0, 11.0), 0.075))


def lead_running_in(group: str, misalignment: float, sigma_Hlim: float,
                    velocity: float) -> float:
    """y_β (µm), the running-in allowance of the effective mesh misalignment F_βx (µm)
    (ISO 6336-1:2006, 7.6.3): steels and pearlitic cast irons 320/σ_Hlim·F_βx, at most
    25600/σ_Hlim above 5 m/s and 12800/σ_Hlim above 10 m/s; grey cast iron 0.55·F_βx, at
    most 45 and 22 µm; surface-hardened and nitrided steels 0.15·F_βx, at most 6 µm."""
    return _running_in(group, misalignment, sigma_Hlim, velocity, (320.0, 0.55, (45.0, 22.0), 0.15))


def running_in_tip_relief(sigma_Hlim: float) -> float:
    """C_ay (µm), the tip relief running-in gives a pair without one (ISO 6336-1:2006, 6.5.9):
    (σ_Hlim/97 - 18.45)²/18 + 1.5."""
    return (sigma_Hlim / 97.0 - 18.45) ** 2 / 18.0 + 1.5


def reduced_mass(member_masses: tuple[float, float]) -> float:
    """m_red = m1*·m2*/(m1* + m2*) (kg/mm; ISO 6336-1:2006, 6.5.9), from each member's mass
    per unit face width reduced to its line of action (gear_mass)."""
    m1, m2 = member_masses
    return m1 * m2 / (m1 + m2)


def gear_mass(mean_diameter: float, base_diameter: float, bore_diameter: float,
              density: float) -> float:
    """m* = J*/r_b² (kg/mm): a solid gear's mass moment of inertia per unit face width,
    π·ρ·d_m⁴·(1 - q⁴)/32 with q = d_i/d_m, over its base radius squared (ISO 6336-1:2006,
    6.5.9: d_m = (d_a + d_f)/2; ρ in kg/mm³)."""
    q = bore_diameter / mean_diameter
    return math.pi / 8.0 * (mean_diameter / base_diameter) ** 2 * mean_diameter ** 2 \
        * density * (1.0 - q ** 4)


@dataclass(frozen=True)
class DynamicFactor:
    """K_v by ISO 6336-1 Method B and what it came from: the resonance speed n_E1 (rpm),
    the resonance ratio N = n1/n_E1 and the speed range it falls in."""

    value: float
    resonance_speed: float
    resonance_ratio: float
    regime: str


def dynamic_factor(pinion_teeth: int, pinion_speed: float, mass: float, single: float,
                   mesh: float, total_ratio: float, line_load: float,
                   pitch_deviation: float, profile_deviation: float,
                   tip_relief: float) -> DynamicFactor:
    """K_v (ISO 6336-1:2006 Method B, 6.5): n_E1 = 30000/(π·z1)·sqrt(c_γα/m_red), N = n1/n_E1;
    below N_S (0.85, or 0.5 + 0.35·sqrt(F_t·K_A/b/100) under 100 N/mm) K_v = N·K + 1 with
    K = C_v1·B_p + C_v2·B_f + C_v3·B_k; up to N = 1.15 (main resonance) C_v1·B_p + C_v2·B_f +
    C_v4·B_k + 1; from 1.5 (supercritical) C_v5·B_p + C_v6·B_f + C_v7; linear between 1.15
    and 1.5. B_p = c'·f_pb,eff/(F_t·K_A/b), B_f = c'·f_fα,eff/(F_t·K_A/b),
    B_k = |1 - c'·C_a/(F_t·K_A/b)|. Takes z1, n1 (rpm), m_red (kg/mm), c' and c_γα
    (N/(mm·µm)), ε_γ, the line load F_t·K_A/b (N/mm), the effective (run-in) base pitch
    and profile form deviations and the tip relief C_a (µm)."""
    resonance = 30000.0 / (math.pi * pinion_teeth) * math.sqrt(mesh / mass)
    N = pinion_speed / resonance
    C_v1, C_v5 = 0.32, 0.47
    eps = total_ratio
    if eps <= 2.0:
        C_v2, C_v3, C_v4, C_v6 = 0.34, 0.23, 0.90, 0.47
    else:
        C_v2, C_v3 = 0.57 / (eps - 0.3), 0.096 / (eps - 1.56)
        C_v4, C_v6 = (0.57 - 0.05 * eps) / (eps - 1.44), 0.12 / (eps - 1.74)
    C_v7 = (0.75 if eps <= 1.5 else 0.125 * math.sin(math.pi * (eps - 2.0)) + 0.875
            if eps <= 2.5 else 1.0)
    B_p = single * pitch_deviation / line_load
    B_f = single * profile_deviation / line_load
    B_k = abs(1.0 - single * tip_relief / line_load)
    N_S = 0.85 if line_load >= 100.0 else 0.5 + 0.35 * math.sqrt(line_load / 100.0)
    resonant = C_v1 * B_p + C_v2 * B_f + C_v4 * B_k + 1.0
    supercritical = C_v5 * B_p + C_v6 * B_f + C_v7
    if N <= N_S:
        value, regime = N * (C_v1 * B_p + C_v2 * B_f + C_v3 * B_k) + 1.0, "subcritical"
    elif N <= 1.15:
        value, regime = resonant, "main resonance"
    elif N < 1.5:
        value, regime = (supercritical + (resonant - supercritical) * (1.5 - N) / 0.35,
                         "intermediate")
    else:
        value, regime = supercritical, "supercritical"
    return DynamicFactor(value, resonance, N, regime)


def transverse_load_factors(total_ratio: float, transverse_ratio: float, Z_eps: float,
                            mesh: float, pitch_deviation: float, line_load: float
                            ) -> tuple[float, float]:
    """(K_Hα, K_Fα) by ISO 6336-1:2006 Method B (8.3): for ε_γ <= 2
    ε_γ/2·(0.9 + 0.4·c_γα·(f_pb - y_α)/(F_tH/b)), beyond 0.9 + 0.4·sqrt(2(ε_γ - 1)/ε_γ)·
    c_γα·(f_pb - y_α)/(F_tH/b); K_Hα at most ε_γ/(ε_α·Z_ε²), K_Fα at most ε_γ/(0.25·ε_α +
    0.75), both at least 1. The run-in base pitch deviation f_pb - y_α in µm, the line
    load F_tH/b = F_t·K_A·K_v·K_Hβ/b in N/mm, c_γα in N/(mm·µm)."""
    term = mesh * pitch_deviation / line_load
    eps = total_ratio
    factor = (eps / 2.0 * (0.9 + 0.4 * term) if eps <= 2.0
              else 0.9 + 0.4 * math.sqrt(2.0 * (eps - 1.0) / eps) * term)
    K_H = min(max(factor, 1.0), max(eps / (transverse_ratio * Z_eps ** 2), 1.0))
    K_F = min(max(factor, 1.0), max(eps / (0.25 * transverse_ratio + 0.75), 1.0))
    return K_H, K_F


def face_load_factor(misalignment_um: float, stiffness: float, line_load: float) -> float:
    """K_Hβ of ISO 6336-1:2006 §7.6 (Method C, a linear mesh misalignment) for the effective
    mesh misalignment F_βy (µm) over the face, the mesh stiffness c_γβ (N/(mm·µm)) and the
    mean line load F_m/b (N/mm): 1 + F_βy·c_γβ/(2·F_m/b) while that is at most 2 (the load
    spreads over the whole face), sqrt(2·F_βy·c_γβ/(F_m/b)) beyond (it covers part of it)."""
    ratio = misalignment_um * stiffness / line_load
    return 1.0 + 0.5 * ratio if ratio <= 2.0 else math.sqrt(2.0 * ratio)


def root_face_load_factor(K_H_beta: float, face_width: float, tooth_depth: float) -> float:
    """K_Fβ = K_Hβ^N_F, N_F = (b/h)²/(1 + b/h + (b/h)²) (ISO 6336-1:2006, 7.6.6), b/h the
    face width over the tooth depth (the smaller of the members'), taken at least 3."""
    ratio = max(face_width / tooth_depth, 3.0)
    return K_H_beta ** (ratio ** 2 / (1.0 + ratio + ratio ** 2))
