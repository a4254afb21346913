"""Tooth bending strength of cylindrical gears: the factors and stresses of ISO 6336-3:2006
Method B. The nominal root stress σ_F0 = F_t/(b·m_n)·Y_F·Y_S·Y_β·Y_B·Y_DT, the root stress
σ_F = σ_F0·K_A·K_v·K_Fβ·K_Fα, and the permissible σ_FP = σ_Flim·Y_ST·Y_NT·Y_δrelT·Y_RrelT·
Y_X / S_Fmin.

Y_F and Y_S are ISO's at the outer point of single pair contact of the virtual spur gear
(d_en), with the critical section (30° tangents) found on the exact fillet the basic rack
generates (rating.root: within 0.05 % of ISO's closed form of that trochoid, tested).
Units: mm, N, MPa (N/mm²), µm for roughness.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..surfaces.involute import CylindricalGear
from .root import critical_section, load_arm, stress_correction, virtual_spur_gear


@dataclass(frozen=True)
class FormFactors:
    """ISO 6336-3 Method B's tooth form factor Y_F and stress correction factor Y_S of a
    gear loaded at the outer point of single pair contact, with what they come from: the
    critical section's chord s_Fn and fillet radius ρ_F, the bending arm h_Fe (mm), the
    load's angle α_Fen (rad) and the virtual gear's d_en (mm)."""

    Y_F: float
    Y_S: float
    s_Fn: float
    rho_F: float
    h_Fe: float
    alpha_Fen: float
    d_en: float


def form_factors(gear: CylindricalGear, transverse_ratio: float) -> FormFactors:
    """Y_F = 6·(h_Fe/m_n)·cos α_Fen / ((s_Fn/m_n)²·cos α_n) and Y_S = (1.2 + 0.13·L)·
    q_s^(1/(1.21 + 2.3/L)), L = s_Fn/h_Fe, q_s = s_Fn/(2ρ_F) (ISO 6336-3:2006 Method B) of
    an external gear in a pair of transverse contact ratio ε_α: the load at the virtual
    gear's outer point of single pair contact, ε_αn = ε_α/cos²β_b and
    d_en = 2·sqrt((sqrt(r_an² - r_bn²) - p_bn·(ε_αn - 1))² + r_bn²)."""
    virtual = virtual_spur_gear(gear)
    section = critical_section(virtual)
    m, alpha = gear.normal_module, gear.pressure_angle
    ratio_n = transverse_ratio / math.cos(gear.base_helix_angle) ** 2
    r_bn = virtual.base_radius
    roll = (math.sqrt(virtual.tip_radius ** 2 - r_bn ** 2)
            - math.pi * m * math.cos(alpha) * (ratio_n - 1.0))
    (h_F,), (cos_alpha,) = load_arm(virtual, section, [roll])
    Y_F = 6.0 * (h_F / m) * cos_alpha / ((section.s_Fn / m) ** 2 * math.cos(alpha))
    Y_S = float(stress_correction(section.s_Fn, h_F, section.rho_F))
    return FormFactors(float(Y_F), Y_S, section.s_Fn, section.rho_F, float(h_F),
                       math.acos(cos_alpha), 2.0 * math.hypot(roll, r_bn))


def deep_tooth_factor(transverse_ratio_n: float, accuracy_grade: int | None) -> float:
    """Y_DT (ISO 6336-3:2006): 1, but for gears of ISO accuracy 4 or finer with ε_αn above
    2.05: 2.366 - 0.666·ε_αn up to 2.5, 0.7 beyond."""
    if accuracy_grade is None or accuracy_grade > 4 or transverse_ratio_n <= 2.05:
        return 1.0
    return 2.366 - 0.666 * transverse_ratio_n if transverse_ratio_n <= 2.5 else 0.7


def nominal_root_stress(tangential_load: float, face_width: float, normal_module: float,
                        *factors: float) -> float:
    """σ_F0 = F_t/(b·m_n)·Y_F·Y_S·Y_β·Y_B·Y_DT (MPa; ISO 6336-3:2006 Method B), F_t at the
    reference circle (N), b the member's face width (mm)."""
    return tangential_load / (face_width * normal_module) * math.prod(factors)


#: ISO 6336-3:2006 Table 3: the slip-layer thickness ρ' (mm) of Y_δrelT by material group;
#: structural steels by their yield stress σ_S and through-hardened steels and pearlitic
#: cast irons by their 0.2 % proof stress (MPa), interpolated linearly between the rows
SLIP_LAYER_FIXED = {"Eh": 0.0030, "IF": 0.0030, "NT": 0.1005, "NV": 0.1005,
                    "NV(nitrocar)": 0.1005}
SLIP_LAYER_BY_STRENGTH = {"St": ((300.0, 0.0833), (400.0, 0.0445)),
                          "V": ((500.0, 0.0281), (600.0, 0.0194), (800.0, 0.0064),
                                (1000.0, 0.0014))}
SLIP_LAYER_BY_STRENGTH["GTS"] = SLIP_LAYER_BY_STRENGTH["GGG"] = SLIP_LAYER_BY_STRENGTH["V"]
#: grey cast iron's (by its tensile strength, 150-300 MPa: 0.3124-0.3095 mm, taken as the
#: stronger's)
SLIP_LAYER_FIXED["GG"] = 0.3095
#: the relative stress gradient of the reference test gear (q_sT = 2.5), 1/mm
GRADIENT_REFERENCE = 1.2


def notch_sensitivity_factor(group: str, notch: float, strength: float | None) -> float | None:
    """Y_δrelT = (1 + sqrt(ρ'·χ*))/(1 + sqrt(ρ'·χ*_T)) (ISO 6336-3:2006 Method B), χ* =
    (1 + 2·q_s)/5 the relative stress gradient (1/mm) of the notch parameter q_s, χ*_T =
    1.2 the reference test gear's; ρ' by material group (Table 3), None where it needs a
    yield or proof stress not given."""
    if group in SLIP_LAYER_FIXED:
        rho = SLIP_LAYER_FIXED[group]
    elif strength is None:
        return None
    else:
        points = SLIP_LAYER_BY_STRENGTH[group]
        rho = float(np.interp(strength, [s for s, _ in points], [r for _, r in points]))
    gradient = (1.0 + 2.0 * notch) / 5.0
    return (1.0 + math.sqrt(rho * gradient)) / (1.0 + math.sqrt(rho * GRADIENT_REFERENCE))


def relative_surface_factor(group: str, roughness_Rz: float | None) -> float | None:
    """Y_RrelT (ISO 6336-3:2006 Method B) of the root's roughness R_z (µm): below 1 µm 1.120
    (through-hardened, pearlitic cast iron, case- and induction-hardened), 1.070 (structural
    steel), 1.025 (grey and ferritic cast iron, nitrided); up to 40 µm 1.674 - 0.529·
    (R_z + 1)^0.1, 5.306 - 4.203·(R_z + 1)^0.01, 4.299 - 3.259·(R_z + 1)^0.0058 for the same
    groups. None where no root roughness is given."""
    if roughness_Rz is None:
        return None
    kind = ("structural" if group == "St" else
            "soft" if group in ("GG", "NT", "NV", "NV(nitrocar)") else "hard")
    if roughness_Rz < 1.0:
        return {"hard": 1.120, "structural": 1.070, "soft": 1.025}[kind]
    r = min(roughness_Rz, 40.0) + 1.0
    return {"hard": 1.674 - 0.529 * r ** 0.1, "structural": 5.306 - 4.203 * r ** 0.01,
            "soft": 4.299 - 3.259 * r ** 0.0058}[kind]


def size_factor(group: str, module: float) -> float:
    """Y_X for long life (ISO 6336-3:2006 Method B) of the normal module (mm): 1 up to 5 mm;
    structural and through-hardened steels and pearlitic cast irons 1.03 - 0.006·m_n (0.85
    from 30 mm), surface-hardened and nitrided steels 1.05 - 0.01·m_n (0.8 from 25 mm), grey
    and ferritic cast iron 1.075 - 0.015·m_n (0.7 from 25 mm)."""
    if module <= 5.0:
        return 1.0
    if group in ("Eh", "IF", "NT", "NV", "NV(nitrocar)"):
        return max(1.05 - 0.01 * module, 0.8)
    if group == "GG":
        return max(1.075 - 0.015 * module, 0.7)
    return max(1.03 - 0.006 * module, 0.85)


def material_factors(group: str, form: FormFactors, strength: float | None,
                     root_roughness_Rz: float | None, module: float):
    """The root's strength factors of a member of material `group` (ISO 6336-5
    abbreviations): (key, ISO symbol, value or None for the neutral 1, its source, why it
    would be 1) for Y_δrelT, Y_RrelT and Y_X."""
    q_s = form.s_Fn / (2.0 * form.rho_F)
    return (
        ("Y_delta_rel_T", "Y_δrelT", notch_sensitivity_factor(group, q_s, strength),
         f"ISO 6336-3 Method B (relative notch sensitivity, q_s {q_s:.3f})",
         "no yield or proof stress given (material yield_strength)"),
        ("Y_R_rel_T", "Y_RrelT", relative_surface_factor(group, root_roughness_Rz),
         "ISO 6336-3 Method B (relative surface factor of the root's Rz)",
         "no root roughness given (root_roughness_Rz; the reference test gear's Rz is "
         "about 10 µm)"),
        ("Y_X", "Y_X", size_factor(group, module),
         "ISO 6336-3 Method B (size factor, long life)", ""))
