"""How a result's keys and numbers read in the reports: the labels of keys (their words, or
LABELS where the words alone do not say what a key is), the units their suffixes carry,
numbers to four significant digits (a column's figure below the resolution its largest
value is printed to shows as 0), and a figure's span over a case's conditions."""

from __future__ import annotations

import math
import re

#: sections of a document that are not result tables
META = {"case", "kind", "title", "source", "assumptions", "toothcontact_version", "units",
        "inputs", "checks", "notes", "stages", "provenance"}
#: sections that are a chart's curves: drawn in the chart, kept whole in result.json, not
#: tabulated
CHARTS = {"crown_chart", "anti_rattle_curve", "k_chart"}

#: key suffix -> unit shown in a label (longest first)
UNITS = [("_N_per_mm_um", "N/(mm·µm)"), ("_N_per_mm", "N/mm"), ("_m_per_s", "m/s"), ("_sqrt_MPa", "√MPa"),
         ("_mm2_s", "mm²/s"), ("_per_mm", "1/mm"), ("_mm2", "mm²"), ("_urad", "µrad"),
         ("_MPa", "MPa"), ("_Nm", "N·m"), ("_deg", "deg"), ("_rad", "rad"), ("_mm", "mm"),
         ("_um", "µm"), ("_N", "N"), ("_C", "°C"), ("_m_per_s", "m/s"), ("_degC", "°C"),
         ("_K", "K"), ("_W", "W"), ("_mm2_per_s", "mm²/s"), ("_mPa_s", "mPa·s"),
         ("_kg_per_m3", "kg/m³"), ("_per_GPa", "1/GPa")]

#: labels of keys whose words alone do not say what they are
LABELS = {
    "sigma_H_pinion_MPa": "σ_H pinion", "sigma_H_gear_MPa": "σ_H gear",
    "sigma_F_pinion_MPa": "σ_F pinion", "sigma_F_gear_MPa": "σ_F gear",
    "K_v": "dynamic factor K_v", "K_H_beta_rating": "K_Hβ of the rating",
    "K_H_beta_iso_C": "K_Hβ by ISO 6336-1 Method C",
    "tooth_load_factor": "tooth load factor (largest over mean tooth load)",
    "roll_deg": "pinion roll", "pair": "tooth pair", "p_max_MPa": "Hertz peak pressure",
    "max_p_max_MPa": "largest Hertz pressure (equal split)",
    "bem_max_p_max_MPa": "largest loaded pressure", "bem_p_max_MPa": "loaded peak pressure",
    "flank_pressure_max_MPa": "largest loaded pressure on the active flank",
    "flank_p_max_MPa": "active-flank peak pressure",
    "bem_load_N": "loaded share", "bem_area_mm2": "loaded contact area",
    "bem_approach_mm": "loaded approach", "bem_status": "loaded solution",
    "bem_reason": "why not solved", "bem_iterations": "solver iterations",
    "bem_relative_error": "solver residual", "bem_grid": "solver grid",
    "bem_raw_peak_MPa": "largest cell pressure (not a design value)",
    "a_mm": "semi-axis a", "b_mm": "semi-axis b",
    "A_per_mm": "gap coefficient A (half the relative curvature)",
    "B_per_mm": "gap coefficient B (half the relative curvature)",
    "A_analytic_per_mm": "A from the flank curvatures",
    "B_analytic_per_mm": "B from the flank curvatures", "fit_rms_mm": "gap fit rms",
    "transmission_error_urad": "transmission error (unloaded)",
    "loaded_transmission_error_urad": "transmission error (loaded)",
    "transmission_error_peak_to_peak_urad": "transmission error, peak to peak (unloaded)",
    "loaded_transmission_error_peak_to_peak_urad": "transmission error, peak to peak (loaded)",
    "transmission_error_um": "transmission error (unloaded)",
    "loaded_transmission_error_um": "transmission error (loaded)",
    "transmission_error_peak_to_peak_um": "transmission error, peak to peak (unloaded)",
    "loaded_transmission_error_peak_to_peak_um": "transmission error, peak to peak (loaded)",
    "checked": "checked", "method": "method",
    "refined_positions": "positions added between the case's",
    "refinement_levels": "times a step was halved",
    "finest_step_fraction": "finest step (of the case's)",
    "refined_bem_max_p_max_MPa": "largest loaded pressure, positions refined",
    "bem_max_p_max_change_percent": "its change with the positions refined (%)",
    "refined_loaded_transmission_error_peak_to_peak_um":
    "transmission error, peak to peak (loaded), positions refined",
    "refined_failed_contacts": "contacts not solved at the positions added",
    "tolerance_percent": "tolerance (%)", "converged": "largest pressure within the tolerance",
    "transmission_error_converged": "TE peak to peak within 10 % (or 0.1 µm)",
    "transmission_error_arm_mm": "radius at which the transmission error is a length",
    "transmission_error_arm": "transmission error as a length on the",
    "edge_margin_mm": "edge margin", "edge_margins_mm": "edge margins",
    "subsurface_shear_max_MPa": "largest shear (σ1 − σ3)/2 below the surface",
    "root_stress_pinion_MPa": "root stress of the pinion tooth",
    "root_stress_gear_MPa": "root stress of the gear tooth",
    "pinion_root_stress_max_MPa": "largest root stress of the pinion",
    "gear_root_stress_max_MPa": "largest root stress of the gear",
    "load_share": "share of the position's load",
    "te_harmonics_um": "loaded TE harmonics (mesh orders 1, 2, ...)",
    "unloaded_te_harmonics_um": "unloaded TE harmonics (mesh orders 1, 2, ...)",
    "sigma_H_MPa": "contact stress σ_H (ISO 6336-2)",
    "flank_pressure_at": "largest loaded flank pressure at",
    "flank_pressure_to_sigma_H": "largest loaded flank pressure over ISO's σ_H",
    "S_B_note": "scuffing safety S_B",
    "subsurface_shear_depth_mm": "its depth",
    "sliding_velocity_m_per_s": "sliding speed |v1 − v2|",
    "sum_velocity_m_per_s": "sum speed |v1 + v2|",
    "specific_sliding_pinion": "specific sliding (pinion)",
    "specific_sliding_gear": "specific sliding (gear)",
    "friction_coefficient": "friction coefficient μ",
    "film_thickness_central_um": "central film thickness",
    "film_thickness_min_um": "minimum film thickness", "lambda": "specific film λ",
    "flash_temperature_K": "flash temperature", "contact_temperature_degC": "contact temperature",
    "power_loss_W": "power lost in the contact", "lambda_min": "least specific film λ",
    "flash_temperature_max_K": "largest flash temperature",
    "mesh_power_loss_W": "mesh power loss", "mesh_efficiency": "mesh efficiency",
    "subsurface_von_mises_max_MPa": "largest von Mises stress below the surface",
    "subsurface_von_mises_depth_mm": "its depth (von Mises)",
    "subsurface_shear_at": "largest shear below the surface at",
    "contact_radius_pinion_mm": "contact radius on the pinion",
    "face_position_mm": "position along the face", "separation_mm": "separation",
    "E_star_MPa": "E*", "Y_VISC": "viscosity factor Y_VISC", "mu_zm": "mean friction mu_zm",
    "eta_z": "efficiency eta_z (worm driving)", "eta_wheel_driving": "efficiency (wheel driving)",
    "eta_kim": "efficiency by Kim's eq (2)", "eta_total": "total efficiency",
    "I": "AGMA geometry factor I", "Cp_sqrt_MPa": "elastic coefficient Cp",
    "K_D_mm": "K_D", "rho1_mm": "profile radius rho1", "rho2_mm": "profile radius rho2",
    "rho1_lpstc_mm": "pinion profile radius at the LPSTC",
    "K_H_beta": "face load factor K_Hβ of the loaded contact (ISO 6336-1 Method A)",
    "K_H_beta_instantaneous": "K_Hβ at the worst instant",
    "mesh_stiffness_N_per_mm_um": "mesh stiffness c_γα",
    "iso_mesh_stiffness_N_per_mm_um": "mesh stiffness c_γα by ISO 6336-1",
    "single_stiffness_N_per_mm_um": "single-pair stiffness c'",
    "iso_single_stiffness_N_per_mm_um": "single-pair stiffness c' by ISO 6336-1",
    "bem_failed_contacts": "contacts the loaded solver could not answer",
    "max_edge_pressure_MPa": "largest edge pressure", "max_edge_load_fraction":
    "largest share of a contact's load at an edge", "max_end_load_ratio":
    "largest end load ratio", "edge_loaded_contacts": "edge-loaded contacts",
    "end_loaded_contacts": "end-loaded contacts", "edge_load_fraction": "share of the load at the edge",
    "loaded_contacts": "contacts carrying load", "corner_contacts": "corner contacts",
    "corner_contact": "corner contact", "corner_pressure_MPa": "corner contact's pressure",
    "corner_load_N": "corner contact's load", "corner_at": "corner contact at",
    "edge_contacts": "rigid patterns on an edge", "line_contacts": "rigid line patterns",
    "area_contacts": "rigid area patterns",
    "agma_stress_MPa": "AGMA contact stress", "contact_radius_worm_mm": "contact radius on the worm",
    "self_locking": "self-locking", "eta_kim_aligned": "efficiency by Kim's eq (2), shaft aligned",
    "mu": "friction coefficient μ", "mu_aligned": "friction coefficient μ (aligned)",
    "found": "interference found at", "back_flanks": "back flanks touching at",
    "helix_slope_um": "helix slope modification f_Hβ", "twist_um": "flank twist",
    "profile_slope_um": "profile slope modification f_Hα", "root_relief_um": "root relief",
}

#: labels of keys that mean something of their own in one section (a worm efficiency
#: case's anti-rattle spring: seed 001's model with the spring and with the shaft aligned)
SECTION_LABELS = {
    "misalignment": {
        "normal_load_N": "tooth normal load (eq 3)", "spring_force_N": "spring force (eq 20)",
        "misalignment_mm": "misalignment x (eq 21)",
        "preloaded_normal_load_N": "normal load with the spring's preload",
        "pressure_aligned_MPa": "contact pressure, shaft aligned (eq 19)",
        "mu_aligned": "friction μ, shaft aligned",
        "eta_kim_aligned": "efficiency, shaft aligned (eq 2)",
        "pressure_MPa": "contact pressure with the spring (eq 19)",
        "mu": "friction μ with the spring", "eta_kim": "efficiency with the spring (eq 2)"},
    "anti_rattle_spring": {
        "stiffness_N_per_mm": "spring rate k", "d1_mm": "lever d1, mesh to spring",
        "d2_mm": "lever d2, mount to mesh", "mount_moment_Nm": "moment M at the mount",
        "misalignment_at_no_torque_mm": "misalignment at no output torque (eq 21)",
        "aligned_torque_Nm": "output torque where the shaft is aligned (eq 20)",
        "friction_mu_ref": "friction law: μ at the reference pressure",
        "friction_pressure_ref_MPa": "friction law: reference pressure",
        "friction_exponent": "friction law: exponent n (μ = c·p^n)"},
}

#: the members' own names by case kind, for the driver ("pinion") and the driven member
#: ("gear") that the analysis names generically
MEMBER_WORDS = {"worm": (("pinion", "worm"), ("gear", "wheel")),
                "spline": (("pinion", "hub"), ("gear", "sleeve"))}


def in_words(text: str, kind: str) -> str:
    """`text` with the members named as a `kind` names them (a worm set's worm and wheel, a
    spline's hub and sleeve), in words and in edge names (gear_tip -> sleeve_tip)."""
    for member, name in MEMBER_WORDS.get(kind, ()):
        text = re.sub(rf"\b{member}(?=\b|_)", name, text)
    return text

#: significant digits of a figure
DIGITS = 4

#: round-off: a number this close to zero, relative to what it is measured against
ZERO = 1e-8

#: a number this large or larger is written with an exponent (below it, as digits)
LARGE = 1e9

#: edge margins are shown to the micrometre (mm), as the checks give them
MARGIN_RESOLUTION = 1e-3

#: transmission errors are shown to 0.01 µrad (the unloaded TE of conjugate flanks is the
#: contact search's tolerance, a few hundredths)
TE_RESOLUTION = 0.01
#: transmission error as a length (µm): a measuring machine's resolution
TE_UM_RESOLUTION = 0.001


#: the least magnitude a figure of a unit means (below it, float round-off or a value under
#: the model's own resolution: shown as 0): a nanometre, a micro-degree, a kPa, a µN; a gap
#: coefficient (1/mm, half a relative curvature) of 1e-6, a relative radius of 500 m that
#: no crown that can be made reaches (a line contact's fit along its line reads 1e-8 to
#: 2e-7 there)
FLOORS = {"mm": 1e-6, "µm": 1e-3, "1/mm": 1e-6, "µrad": 1e-3, "deg": 1e-6, "rad": 1e-9,
          "MPa": 1e-3, "N": 1e-6, "N/mm": 1e-6, "N·m": 1e-6, "mm²": 1e-9}


def unit_of(key: str) -> str | None:
    """The unit a key's suffix carries (UNITS), or None (a method's letter is no unit:
    K_H_beta_iso_C is ISO's Method C, not a temperature)."""
    if key.endswith("_iso_C"):
        return None
    return next((u for suffix, u in UNITS if key.endswith(suffix)), None)


def floor(key: str) -> float | None:
    """The least magnitude (in the key's unit) a figure of `key` means (FLOORS; a Miner sum's
    1e-9), or None."""
    if key.startswith("miner_sum"):
        return 1e-9
    return FLOORS.get(unit_of(key) or "")


def label(key: str, kind: str = "", section: str = "") -> str:
    """A key's label with its unit: 'face_position_mm' -> 'position along the face [mm]'; in
    a worm set's report (`kind` "worm") the pinion is the worm and the gear the wheel; in
    `section` its SECTION_LABELS first; a spline's hub and sleeve likewise."""
    unit = unit_of(key)
    if key in SECTION_LABELS.get(section, {}):
        words = SECTION_LABELS[section][key]
    elif key in LABELS:
        words = LABELS[key]
    else:
        stem = key[: -len(next(s for s, u in UNITS if key.endswith(s)))] if unit else key
        words = stem.replace("_", " ")
    words = in_words(words, kind)
    return f"{words} [{unit}]" if unit else words


def number(value, scale: float | None = None, resolution: float | None = None,
           least: float | None = None) -> str:
    """A value as text: numbers to four significant digits (in digits up to LARGE: 30000,
    123500) and no finer than `resolution`; a number below `least` in magnitude (its unit's
    floor) is 0;
    beside the largest figure of its kind (`scale`, e.g. its column's largest magnitude) a
    number below half a unit in that figure's last shown digit is 0 (-1.1 to 1.417 mm: a
    misalignment of 6.8e-06 mm shows as 0, as the figures beside it are shown to 0.001 mm);
    None as '', booleans as yes/no, dicts as 'key: value' pairs, an empty list as 'none',
    short lists of names joined, of numbers inline, long ones by their shape and range."""
    if value is None:
        return ""
    if isinstance(value, float) and resolution and math.isfinite(value):
        value = round(value / resolution) * resolution
    if isinstance(value, bool):
        return "yes" if value else "no"
    if isinstance(value, int):
        return str(value)
    if isinstance(value, float):
        if not math.isfinite(value):
            return str(value)
        if value == 0.0 or (scale and abs(value) < 0.5 * last_digit(scale)) or \
                (least and abs(value) < least):
            return "0"
        text = f"{value:.{DIGITS}g}"
        return f"{float(text):.0f}" if "e+" in text and abs(value) < LARGE else text
    if isinstance(value, dict):
        return "; ".join(f"{k}: {number(v)}" for k, v in value.items())
    if isinstance(value, (list, tuple)):
        if not value:
            return "none"
        if all(isinstance(v, str) for v in value):
            return ", ".join(value)
        flat = _flatten(value)
        if len(flat) > 12:
            finite = [v for v in flat if isinstance(v, (int, float)) and not isinstance(v, bool)
                      and math.isfinite(v)]
            shape = " × ".join(str(n) for n in _shape(value))
            low, high = (number(v, least=least) for v in (min(finite), max(finite))) \
                if finite else ("", "")
            span = f", {low} to {high}" if finite else ""
            return f"[{shape} values{span}]"
        return "[" + ", ".join(number(v, least=least) for v in value) + "]"
    return str(value)


def last_digit(value: float) -> float:
    """A unit in the last of the DIGITS significant digits `value` is shown to:
    0.001 for 1.417, 0.01 for 42.5, 1 for 1386."""
    if not (value and math.isfinite(value)):
        return 0.0
    return 10.0 ** (math.floor(math.log10(abs(value))) - DIGITS + 1)


def _flatten(value) -> list:
    if isinstance(value, (list, tuple)):
        return [x for v in value for x in _flatten(v)]
    return [value]


def _shape(value) -> list[int]:
    if isinstance(value, (list, tuple)) and value:
        return [len(value)] + _shape(value[0])
    return []


def span(values: list, unit: str = "") -> str:
    """A figure over a case's conditions: 'low to high unit', one value where they agree
    (as shown), '' where none applies."""
    values = [v for v in values if isinstance(v, (int, float)) and not isinstance(v, bool)
              and math.isfinite(v)]
    if not values:
        return ""
    scale = max(abs(v) for v in values)
    low, high = number(min(values), scale), number(max(values), scale)
    return (low if low == high else f"{low} to {high}") + (f" {unit}" if unit else "")


def over(values: list, unit: str, what: str) -> str:
    """The conditions a figure ranges over: 'over 6 lubricant temperatures, -50 to 70 °C'
    ('at the output torque 10 N·m' where there is one)."""
    count = sum(v is not None for v in values)
    return (f"over {count} {what}s, {span(values, unit)}" if count > 1 else
            f"at the {what} {span(values, unit)}")
