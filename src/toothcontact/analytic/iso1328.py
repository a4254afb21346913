"""Flank tolerances of a cylindrical involute gear by its flank tolerance class (µm).

Source: ISO 1328-1:2013, *Cylindrical gears — ISO system of flank tolerance
classification — Part 1*, clause 5: the class-5 values of Formulae (5)-(12) times the step
factor √2 per class, (√2)^(A-5) (5.2.2), each rounded by 5.2.3 (over 10 µm to the whole
µm, 5 to 10 µm to 0.5 µm, under 5 µm to 0.1 µm); the totals (9) and (12) from the
unrounded slope and form values. The formulae hold within the standard's scope (clause 1:
5 ≤ z ≤ 1000, 5 mm ≤ d ≤ 15 000 mm, 0.5 mm ≤ m_n ≤ 70 mm, 4 mm ≤ b ≤ 1200 mm, β ≤ 45°)
and "shall not be extrapolated beyond these limits", so a gear outside it is refused. The
2013 edition gives formulae where the 1995 edition printed tables; its classes 1-11 are
not the 1995 grades 0-12.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

#: the flank tolerance classes of ISO 1328-1:2013
CLASSES = range(1, 12)

#: the scope of the formulae (clause 1): name -> (low, high, unit)
SCOPE = {"teeth": (5, 1000, ""), "reference_diameter": (5.0, 15000.0, "mm"),
         "normal_module": (0.5, 70.0, "mm"), "face_width": (4.0, 1200.0, "mm"),
         "helix_angle": (0.0, 45.0, "deg")}


@dataclass(frozen=True)
class FlankTolerances:
    """One gear's flank tolerances (µm), rounded as the standard rounds them."""

    tolerance_class: int
    single_pitch: float          # f_pT, Formula (5)
    cumulative_pitch: float      # F_pT, (6)
    profile_slope: float         # f_HαT, (7)
    profile_form: float          # f_fαT, (8)
    profile_total: float         # F_αT, (9)
    helix_slope: float           # f_HβT, (10)
    helix_form: float            # f_fβT, (11)
    helix_total: float           # F_βT, (12)


def rounded(value_um: float) -> float:
    """A tolerance rounded by ISO 1328-1:2013, 5.2.3 (halves away from zero)."""
    step = 1.0 if value_um > 10.0 else 0.5 if value_um >= 5.0 else 0.1
    return round(math.floor(value_um / step + 0.5) * step, 1)


def out_of_scope(teeth: int, reference_diameter: float, normal_module: float,
                 face_width: float, helix_angle: float) -> list[str]:
    """What lies outside the formulae's scope (mm, rad), each as 'name = value (range)'."""
    given = {"teeth": teeth, "reference_diameter": reference_diameter,
             "normal_module": normal_module, "face_width": face_width,
             "helix_angle": abs(math.degrees(helix_angle))}
    return [f"{name} = {given[name]:.4g}{' ' + unit if unit else ''} (ISO 1328-1:2013 "
            f"takes {low:g} to {high:g}{' ' + unit if unit else ''})"
            for name, (low, high, unit) in SCOPE.items()
            if not low <= given[name] <= high * (1 + 1e-12)]


def flank_tolerances(tolerance_class: int, reference_diameter: float, normal_module: float,
                     face_width: float) -> FlankTolerances:
    """The tolerances of class A (1-11) of a gear of reference diameter d, normal module
    m_n and face width b (mm): ISO 1328-1:2013 Formulae (5)-(12), rounded (5.2.3)."""
    if tolerance_class not in CLASSES:
        raise ValueError(f"flank tolerance class {tolerance_class!r}: ISO 1328-1:2013 has "
                         "classes 1 to 11")
    d, m, b = reference_diameter, normal_module, face_width
    step = math.sqrt(2.0) ** (tolerance_class - 5)
    f_H_alpha = (0.4 * m + 0.001 * d + 4.0) * step
    f_f_alpha = (0.55 * m + 5.0) * step
    f_H_beta = (0.05 * math.sqrt(d) + 0.35 * math.sqrt(b) + 4.0) * step
    f_f_beta = (0.07 * math.sqrt(d) + 0.45 * math.sqrt(b) + 4.0) * step
    return FlankTolerances(
        tolerance_class=tolerance_class,
        single_pitch=rounded((0.001 * d + 0.4 * m + 5.0) * step),
        cumulative_pitch=rounded((0.002 * d + 0.55 * math.sqrt(d) + 0.7 * m + 12.0) * step),
        profile_slope=rounded(f_H_alpha), profile_form=rounded(f_f_alpha),
        profile_total=rounded(math.hypot(f_H_alpha, f_f_alpha)),
        helix_slope=rounded(f_H_beta), helix_form=rounded(f_f_beta),
        helix_total=rounded(math.hypot(f_H_beta, f_f_beta)))
