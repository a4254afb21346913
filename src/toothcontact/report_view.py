"""What a report shows, read from a result document (no recomputation, no case parsing):
the key results that decide the design, the design checks apart from the source-data and
method checks, the inputs as given, and the results as tables with human labels, units and
numbers rounded to four significant digits (a column's figure below the resolution its
largest value is printed to shows as 0). The templates (templates/report.*.j2) lay it
out as Markdown and as one self-contained HTML page."""

from __future__ import annotations

import math
import re
from dataclasses import dataclass, field

#: sections of a document that are not result tables
META = {"case", "kind", "title", "source", "assumptions", "toothcontact_version", "units",
        "inputs", "checks", "notes", "stages", "provenance"}
#: sections that are a chart's curves: drawn in the chart, kept whole in result.json, not
#: tabulated
CHARTS = {"crown_chart", "anti_rattle_curve"}

#: key suffix -> unit shown in a label (longest first)
UNITS = [("_N_per_mm_um", "N/(mm·µm)"), ("_N_per_mm", "N/mm"), ("_m_per_s", "m/s"), ("_sqrt_MPa", "√MPa"),
         ("_mm2_s", "mm²/s"), ("_per_mm", "1/mm"), ("_mm2", "mm²"), ("_urad", "µrad"),
         ("_MPa", "MPa"), ("_Nm", "N·m"), ("_deg", "deg"), ("_rad", "rad"), ("_mm", "mm"),
         ("_um", "µm"), ("_N", "N"), ("_C", "°C"), ("_m_per_s", "m/s"), ("_degC", "°C"),
         ("_K", "K"), ("_W", "W"), ("_mm2_per_s", "mm²/s"), ("_mPa_s", "mPa·s"),
         ("_kg_per_m3", "kg/m³"), ("_per_GPa", "1/GPa")]

#: labels of keys whose words alone do not say what they are
LABELS = {
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
    "doubled_positions": "positions, doubled", "checked": "checked",
    "doubled_bem_max_p_max_MPa": "largest loaded pressure, twice the positions",
    "bem_max_p_max_change_percent": "its change with twice the positions (%)",
    "doubled_loaded_transmission_error_peak_to_peak_um":
    "transmission error, peak to peak (loaded), twice the positions",
    "doubled_failed_contacts": "contacts not solved at the positions between",
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

#: the members' names in a worm set's labels
WORM_MEMBERS = (("pinion", "worm"), ("gear", "wheel"))

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


def label(key: str, kind: str = "", section: str = "") -> str:
    """A key's label with its unit: 'face_position_mm' -> 'position along the face [mm]'; in
    a worm set's report (`kind` "worm") the pinion is the worm and the gear the wheel; in
    `section` its SECTION_LABELS first."""
    unit = next((u for suffix, u in UNITS if key.endswith(suffix)), None)
    if key in SECTION_LABELS.get(section, {}):
        words = SECTION_LABELS[section][key]
    elif key in LABELS:
        words = LABELS[key]
    else:
        stem = key[: -len(next(s for s, u in UNITS if key.endswith(s)))] if unit else key
        words = stem.replace("_", " ")
    if kind == "worm":
        for member, name in WORM_MEMBERS:
            words = re.sub(rf"\b{member}\b", name, words)
    return f"{words} [{unit}]" if unit else words


def number(value, scale: float | None = None, resolution: float | None = None) -> str:
    """A value as text: numbers to four significant digits (in digits up to LARGE: 30000,
    123500) and no finer than `resolution`;
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
        if value == 0.0 or (scale and abs(value) < 0.5 * last_digit(scale)):
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
            span = f", {number(min(finite))} to {number(max(finite))}" if finite else ""
            return f"[{shape} values{span}]"
        return "[" + ", ".join(number(v) for v in value) + "]"
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


@dataclass(frozen=True)
class KeyResult:
    """One figure that decides the design: what it is, its value with unit, and where."""

    label: str
    value: str
    where: str = ""
    bad: bool = False


@dataclass(frozen=True)
class Table:
    """A results table: `rows` of cells (text), `numeric` per column; a table of many rows
    is shown collapsed."""

    title: str
    headers: list[str]
    rows: list[list[str]]
    numeric: list[bool]
    collapsed: bool = False
    note: str = ""


@dataclass(frozen=True)
class CheckLine:
    name: str
    ok: bool
    detail: str
    kind: str


@dataclass
class ReportView:
    title: str
    case: str
    kind: str
    source: str
    version: str
    units: str
    key_results: list[KeyResult]
    design_checks: list[CheckLine]
    other_checks: list[CheckLine]
    assumptions: list[str]
    tool_notes: list[str]
    inputs: str
    tables: list[Table]
    stages: list[tuple[str, str]] = field(default_factory=list)
    provenance: list[tuple[str, str]] = field(default_factory=list)

    @property
    def failed(self) -> list[CheckLine]:
        return [c for c in self.design_checks if not c.ok]

    @property
    def disagreements(self) -> list[CheckLine]:
        """The source and method checks that disagree (shown, not flagged)."""
        return [c for c in self.other_checks if not c.ok]


#: a table of more rows than this is shown collapsed
COLLAPSE_ROWS = 12


def view(document: dict) -> ReportView:
    """The report of a result document."""
    checks = [CheckLine(c["name"], bool(c["ok"]), c["detail"], c.get("kind", "design"))
              for c in document.get("checks", [])]
    summary = document.get("summary") if isinstance(document.get("summary"), dict) else {}
    tool = list(document.get("notes") or [])
    for key in ("load_sharing", "transmission_error_note", "edge_pressure_note"):
        if summary.get(key):
            tool.append(summary[key])
    rating = document.get("rating") if isinstance(document.get("rating"), dict) else {}
    rated = {f["key"] for f in rating.get("figures", [])}
    tables = [t for key, value in document.items() if key not in META | CHARTS | {"rating"}
              for t in _tables(key, {k: v for k, v in value.items() if k not in rated}
                               if key == "summary" else value, document["kind"])]
    if rating:
        tables.insert(0, rating_table(rating))
    stages = [(name, stage.get("reason", "")) for name, stage in
              (document.get("stages") or {}).items() if stage.get("status") == "failed"]
    return ReportView(
        title=document.get("title") or document["case"], case=document["case"],
        kind=document["kind"], source=document.get("source") or "",
        version=str(document.get("toothcontact_version", "")), units=document.get("units", ""),
        key_results=key_results(document),
        design_checks=[c for c in checks if c.kind == "design"],
        other_checks=[c for c in checks if c.kind != "design"],
        assumptions=[str(a) for a in document.get("assumptions") or []]
        + [f"rating: {a}" for a in rating.get("assumptions", [])], tool_notes=tool,
        inputs="\n".join(toml_lines(document.get("inputs") or {})), tables=tables,
        stages=stages, provenance=provenance(document))


#: the traceability block's lines: (label, the document's provenance key)
PROVENANCE = (("run at (UTC)", "run_at_utc"), ("case file", "case_file"),
              ("case file SHA-256", "case_sha256"), ("command", "command"))


def provenance(document: dict) -> list[tuple[str, str]]:
    """What made the document: the tool's version, when, from which case file (its hash)
    and by which command, as far as the document says."""
    given = document.get("provenance") or {}
    return ([("toothcontact", str(document.get("toothcontact_version", "")))]
            + [(name, str(given[key])) for name, key in PROVENANCE if given.get(key)])


def rating_table(rating: dict) -> Table:
    """ISO 6336's rating as one table: each figure's symbol, value and source, the factors
    the case gave named so."""
    def unit(key: str) -> str:
        return next((u for suffix, u in UNITS if key.endswith(suffix)), "")

    rows = [[f["symbol"], number(f["value"]), unit(f["key"]), f["source"]]
            for f in rating["figures"]]
    given = rating.get("factors_given") or []
    return Table("ISO 6336 rating", ["figure", "value", "unit", "source"], rows,
                 [False, True, False, False],
                 note=rating.get("note", "") + ("; given in the case: " + ", ".join(given)
                                                 if given else ""))


def _is_note(key: str) -> bool:
    """A section's explanation (its `note`, a summary's `..._note`): text under the table."""
    return key == "note" or key.endswith("_note")


def _tables(key: str, value, kind: str) -> list[Table]:
    """A document section as a table: a dict as quantity/value rows (those that do not
    apply, None, left out), a list of dicts as one row each (a column that applies to no
    row left out)."""
    title = key.replace("_", " ")
    if isinstance(value, dict):
        plain = {k: v for k, v in value.items() if not _is_note(k)
                 and k not in ("load_sharing",) and v is not None and not isinstance(v, dict)}
        # a table within the section (the summary's positions check) follows as its own
        inner = [t for k, v in value.items() if isinstance(v, dict) for t in _tables(k, v, kind)]
        if not plain:
            return inner
        note = "; ".join(f"{number(v)}" for k, v in value.items() if _is_note(k))
        rows = [[label(k, kind, key), number(v)] for k, v in plain.items()]
        return [Table(title, ["quantity", "value"], rows, [False, True], note=note)] + inner
    if isinstance(value, list) and value and all(isinstance(r, dict) for r in value):
        keys = [k for k in dict.fromkeys(k for row in value for k in row)
                if any(row.get(k) is not None for row in value)]
        scale = {k: max((abs(r[k]) for r in value if isinstance(r.get(k), float)
                         and math.isfinite(r[k])), default=0.0) for k in keys}
        rows = [[number(r.get(k), scale[k]) for k in keys] for r in value]
        numeric = [all(isinstance(r.get(k), (int, float)) and not isinstance(r.get(k), bool)
                       for r in value if r.get(k) is not None) for k in keys]
        return [Table(title, [label(k, kind, key) for k in keys], rows, numeric,
                      collapsed=len(value) > COLLAPSE_ROWS)]
    return []


# ---------------------------------------------------------------------------------------
# key results


def key_results(document: dict) -> list[KeyResult]:
    """The figures that decide the design, by what the document holds: the loaded contact
    and its pattern (contact kinds), the crown (crown design), the efficiency (worm sets),
    the ellipse (Hertz)."""
    out: list[KeyResult] = []
    summary = document.get("summary") if isinstance(document.get("summary"), dict) else None
    if summary:
        driven = "wheel" if document["kind"] == "worm" else "gear"
        out += _contact_figures(summary, document.get("positions") or [], driven)
    if summary and summary.get("K_H_beta") is not None:
        out.append(KeyResult("face load factor K_Hβ (loaded contact)", number(summary["K_H_beta"]),
                             "ISO 6336-1 Method A: the cycle's largest over mean line load; "
                             f"worst instant {number(summary.get('K_H_beta_instantaneous'))}"
                             + (f"; ISO's Method C {number(summary['K_H_beta_iso_C'])}"
                                if summary.get("K_H_beta_iso_C") is not None else "")))
    if summary and summary.get("mesh_stiffness_N_per_mm_um") is not None:
        out.append(KeyResult("mesh stiffness c_γα", f"{number(summary['mesh_stiffness_N_per_mm_um'])}"
                             " N/(mm·µm)",
                             f"ISO 6336-1 {number(summary.get('iso_mesh_stiffness_N_per_mm_um'))}"
                             + (f"; single pair {number(summary['single_stiffness_N_per_mm_um'])}"
                                if summary.get("single_stiffness_N_per_mm_um") is not None else "")
                             + f"; ISO c' {number(summary.get('iso_single_stiffness_N_per_mm_um'))}"))
    mesh = document.get("mesh") or {}
    if "normal_backlash_mm" in mesh:
        out.append(KeyResult("normal backlash", f"{number(mesh['normal_backlash_mm'] * 1e3)} µm",
                             f"centre distance {number(mesh['center_distance_mm'])} mm"))
    if "transverse_contact_ratio" in mesh:
        out.append(KeyResult("contact ratio", number(mesh["transverse_contact_ratio"]),
                             f"overlap ratio {number(mesh['overlap_ratio'])}"))
    wheel, worm = document.get("wheel"), document.get("worm")
    if isinstance(wheel, dict) and "center_distance_mm" in wheel and isinstance(worm, dict):
        out.append(KeyResult("ratio", f"{number(wheel['ratio'])}",
                             f"{worm['starts']}-start {worm['form']} worm, {wheel['teeth']} "
                             "wheel teeth"))
        out.append(KeyResult("centre distance", f"{number(wheel['center_distance_mm'])} mm",
                             f"lead angle {number(worm['lead_angle_deg'])} deg, wheel face "
                             f"width {number(wheel['face_width_mm'])} mm"))
    crown = document.get("crown")
    if isinstance(crown, dict):
        out.append(KeyResult("crown radius", f"{number(crown['radius_mm'])} mm",
                             f"centre {number(crown.get('center_from_B_mm'))} mm from end B; "
                             f"drop {number(crown['drop_A_mm'] * 1e3)} µm at A, "
                             f"{number(crown['drop_B_mm'] * 1e3)} µm at B"))
    contact = document.get("contact")
    if isinstance(contact, dict) and "stress_MPa" in contact:
        out.append(KeyResult("contact stress", f"{number(contact['stress_MPa'])} MPa",
                             f"ellipse {number(contact['a_mm'])} × {number(contact['b_mm'])} mm"))
        margins = [contact[k] for k in ("edge_margin_A_mm", "edge_margin_B_mm") if k in contact]
        if margins:
            shown = number(min(margins), resolution=ZERO * contact["a_mm"])
            out.append(KeyResult("least margin to the face ends", f"{shown} mm",
                                 "the ellipse just reaches the end" if shown == "0" else
                                 "negative: a face end cuts the ellipse", min(margins) < -1e-6))
    hertz = document.get("hertz")
    if isinstance(hertz, dict):
        out.append(KeyResult("peak pressure", f"{number(hertz['p_max_MPa'])} MPa",
                             f"ellipse a = {number(hertz['a_mm'])} mm, b = {number(hertz['b_mm'])} "
                             f"mm; approach {number(hertz['approach_mm'] * 1e3)} µm"))
    spline = document.get("spline")
    if isinstance(spline, dict) and "contact_stress_MPa" in spline:      # a crown design
        out.append(KeyResult("crown radius", f"{number(spline['crown_radius_mm'])} mm",
                             f"height {number(spline['crown_height_mm'] * 1e3)} µm; the "
                             f"tilted tooth fits up to {number(spline['crown_radius_fit_max_mm'])} mm"))
        out.append(KeyResult("contact stress", f"{number(spline['contact_stress_MPa'])} MPa",
                             f"tooth load {number(spline['tooth_load_N'])} N"))
    if document["kind"] == "worm_efficiency":
        out += _anti_rattle_figures(document.get("misalignment") or [],
                                    document.get("anti_rattle_spring") or {})
        out += _efficiency_figures(document.get("efficiency") or [])
    return out


def _contact_figures(summary: dict, rows: list[dict], driven: str) -> list[KeyResult]:
    out = []
    solved = [r for r in rows if r.get("bem_status") == "solved"]
    if summary.get("bem_max_p_max_MPa") is not None and solved:
        top = max(solved, key=lambda r: r["bem_p_max_MPa"])
        where = f"roll {number(top['roll_deg'])} deg, pair {top['pair']}"
        if top.get("edge_loaded"):
            where += f", edge-loaded at {top.get('edge_pressure_at')}"
        out.append(KeyResult("largest loaded contact pressure",
                             f"{number(summary['bem_max_p_max_MPa'])} MPa", where,
                             bool(top.get("edge_loaded"))))
        if summary.get("loaded_contacts") is not None:
            of = f" of {summary['loaded_contacts']}"
            ends, corners = summary["end_loaded_contacts"], summary["corner_contacts"]
            out.append(KeyResult("end-loaded contacts", f"{ends}{of}",
                                 "a face end loaded above the contact's mean load per mm; "
                                 f"largest end load ratio {number(summary['max_end_load_ratio'])}",
                                 ends > 0))
            out.append(KeyResult("corner contacts", f"{corners}{of}",
                                 "a tip, root or form edge pressed harder than the flank"
                                 + (f": {number(summary['corner_contact_pressure_max_MPa'])} "
                                    f"MPa at {summary['corner_contact_at']}" if corners else ""),
                                 corners > 0))
    elif summary.get("max_p_max_MPa") is not None:
        out.append(KeyResult("largest Hertz pressure", f"{number(summary['max_p_max_MPa'])} MPa",
                             "equal load split, no loaded solution"))
    for what, key, edge in (("face ends", "worst_face_edge_margin_mm", "worst_face_edge"),
                            ("tip and form", "worst_profile_edge_margin_mm", "worst_profile_edge")):
        if summary.get(key) is not None:
            out.append(KeyResult(f"worst edge margin ({what})",
                                 f"{number(summary[key], resolution=MARGIN_RESOLUTION)} mm",
                                 f"at {summary.get(edge)} (negative: the pattern is cut)",
                                 summary[key] < 0))
    span = summary.get("face_position_range_mm")
    if span:
        ends = [number(v, resolution=MARGIN_RESOLUTION) for v in span]
        value = f"{ends[0]} mm" if ends[0] == ends[1] else f"{ends[0]} to {ends[1]} mm"
        out.append(KeyResult("pattern centre on the face", value,
                             "from mid-face, toward end B positive"))
    for label_, key in (("transmission error, peak to peak (unloaded)",
                         "transmission_error_peak_to_peak"),
                        ("transmission error, peak to peak (loaded)",
                         "loaded_transmission_error_peak_to_peak")):
        if summary.get(f"{key}_urad") is not None:
            length = summary.get(f"{key}_um")
            value = f"{number(summary[f'{key}_urad'], resolution=TE_RESOLUTION)} µrad"
            if length is not None:
                value = f"{number(length, resolution=TE_UM_RESOLUTION)} µm ({value})"
            out.append(KeyResult(label_, value, f"the {driven}'s lag"
                                 + (f", as a length on the {summary['transmission_error_arm']}"
                                    if length is not None else "")))
    for name in ("pinion", "gear"):
        if summary.get(f"{name}_root_stress_max_MPa") is not None:
            out.append(KeyResult(
                f"largest root stress ({name})",
                f"{number(summary[f'{name}_root_stress_max_MPa'])} MPa",
                f"at {summary[f'{name}_root_stress_at']} (ISO 6336-3's section and Y_S, "
                "each contact's own line load)"))
    out.extend(_rating_results(summary))
    sums = {k: v for k, v in summary.items() if k.startswith("miner_sum_") and v is not None}
    if sums:
        worst = max(sums, key=sums.get)
        kind, member = worst.removeprefix("miner_sum_").split("_")
        out.append(KeyResult("duty cycle: largest Miner's sum", number(sums[worst]),
                             f"the {member}'s {kind}, on ISO 6336-6's S-N curves",
                             sums[worst] > 1.0))
    if summary.get("te_harmonics_um"):
        out.append(KeyResult(
            "transmission error harmonics (loaded)",
            ", ".join(f"{number(v, resolution=TE_UM_RESOLUTION)}" for v in
                      summary["te_harmonics_um"][:3]) + " µm",
            "amplitudes of mesh orders 1, 2, 3"))
    if summary.get("subsurface_shear_max_MPa") is not None:
        out.append(KeyResult(
            "largest shear below the surface",
            f"{number(summary['subsurface_shear_max_MPa'])} MPa at "
            f"{number(summary['subsurface_shear_depth_mm'] * 1e3)} µm deep",
            f"(σ1 − σ3)/2 at {summary['subsurface_shear_at']}; von Mises "
            f"{number(summary['subsurface_von_mises_max_MPa'])} MPa at "
            f"{number(summary['subsurface_von_mises_depth_mm'] * 1e3)} µm"))
    out.extend(_lubrication_results(summary))
    check = summary.get("positions_check") or {}
    if check.get("checked"):
        out.append(KeyResult(
            "largest loaded pressure with twice the positions",
            f"{number(check['doubled_bem_max_p_max_MPa'])} MPa "
            f"({check['bem_max_p_max_change_percent']:+.1f} %)",
            f"{check['doubled_positions']} positions: the case's {check['positions']} and one "
            "midway between each two", not check["converged"]))
    return out


def _rating_results(summary: dict) -> list[KeyResult]:
    """ISO 6336's safety factors, and the loaded contact's largest flank pressure beside ISO's
    σ_H, where the case was rated."""
    if "sigma_H0_MPa" not in summary:
        return []
    out = []
    S_H = summary.get("S_H")
    permissible = " / ".join(number(summary[f"sigma_HP_{m}_MPa"]) for m in ("pinion", "gear")
                             if summary.get(f"sigma_HP_{m}_MPa") is not None)
    out.append(KeyResult("contact safety S_H (ISO 6336-2)", "—" if S_H is None else number(S_H),
                         "not computed: no σ_Hlim, nor hardness and quality" if S_H is None else
                         f"σ_H {number(summary['sigma_H_MPa'])} MPa (σ_H0 "
                         f"{number(summary['sigma_H0_MPa'])}, K_Hβ "
                         f"{number(summary['K_H_beta_rating'])}) against σ_HP {permissible} MPa",
                         S_H is not None and S_H < 1.0))
    for name in ("pinion", "gear"):
        S_F, stress = summary.get(f"S_F_{name}"), summary.get(f"sigma_F_{name}_MPa")
        if stress is None:
            continue
        out.append(KeyResult(f"root safety S_F of the {name} (ISO 6336-3)",
                             "—" if S_F is None else number(S_F),
                             f"σ_F {number(stress)} MPa"
                             + ("; not computed: no σ_Flim, nor hardness and quality"
                                if S_F is None else
                                f" against σ_FP {number(summary[f'sigma_FP_{name}_MPa'])} MPa"),
                             S_F is not None and S_F < 1.0))
    if summary.get("flank_pressure_max_MPa") is not None:
        ratio = summary.get("flank_pressure_to_sigma_H")
        out.append(KeyResult("largest loaded flank pressure (local)",
                             f"{number(summary['flank_pressure_max_MPa'])} MPa",
                             f"at {summary.get('flank_pressure_at')}"
                             + (f"; {number(ratio)} × ISO's σ_H" if ratio else "")))
    return out


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


def _efficiency_figures(rows: list[dict]) -> list[KeyResult]:
    """A worm set's efficiency over its lubricant conditions (temperatures), or at the
    case's one constant friction."""
    if not rows:
        return []
    temperatures = [r.get("temperature_C") for r in rows]
    at = (over(temperatures, "°C", "lubricant temperature")
          if any(t is not None for t in temperatures) else
          f"at the case's constant friction μ_zm {span([r.get('mu_zm') for r in rows])}")
    out = []
    for key, what in (("eta_z", "efficiency eta_z (worm driving, DIN 3996)"),
                      ("eta_kim", "efficiency by Kim's eq (2)"),
                      ("eta_total", "total efficiency")):
        value = span([r.get(key) for r in rows])
        if value:
            out.append(KeyResult(what, value, at))
    locking = [r.get("self_locking") for r in rows if "self_locking" in r]
    if locking:
        some = [number(t) for t, lock in zip(temperatures, locking) if lock and t is not None]
        out.append(KeyResult("self-locking (wheel driving)", "yes" if all(locking) else
                             "no" if not any(locking) else "at some conditions",
                             f"at {', '.join(some)} °C of {at.removeprefix('over ')}"
                             if some and not all(locking) else at))
    return out


def _anti_rattle_figures(rows: list[dict], spring: dict) -> list[KeyResult]:
    """Seed 001's anti-rattle spring over the case's output torques: the efficiency with the
    spring and with the shaft aligned, the spring force, the misalignment and the torque
    where it vanishes, and the contact pressure and friction where [contact] was given."""
    if not rows:
        return []
    torques = [r["output_torque_Nm"] for r in rows]
    at = over(torques, "N·m", "output torque")
    out = []
    # no torque, nothing transmitted: the efficiency of those rows is 0, not a figure
    driven = [r for r in rows if r["output_torque_Nm"] > 0 and r.get("eta_kim") is not None]
    if driven:
        aligned = [r.get("eta_kim_aligned") for r in driven]
        loss = max(driven, key=lambda r: r["eta_kim_aligned"] - r["eta_kim"])
        out.append(KeyResult(
            "efficiency with the spring (eq 2, μ from eq 19's pressure)",
            span([r["eta_kim"] for r in driven]),
            over([r["output_torque_Nm"] for r in driven], "N·m", "output torque")
            + f"; shaft aligned {span(aligned)}; the largest loss to the spring "
              f"{number(loss['eta_kim_aligned'] - loss['eta_kim'])} at "
              f"{number(loss['output_torque_Nm'])} N·m"
            + ("; nothing transmitted at 0 N·m" if len(driven) < len(rows) else "")))
    out.append(KeyResult("anti-rattle spring force (eq 20)",
                         span([r["spring_force_N"] for r in rows], "N"),
                         at + (f"; spring rate {number(spring['stiffness_N_per_mm'])} N/mm"
                               if "stiffness_N_per_mm" in spring else "")))
    out.append(KeyResult("worm-shaft misalignment (eq 21)",
                         span([r["misalignment_mm"] for r in rows], "mm"),
                         at + "; the shaft's height at the spring, negative: pressed down"))
    aligned_at = spring.get("aligned_torque_Nm")
    if aligned_at is not None:
        out.append(KeyResult("output torque where the shaft is aligned",
                             f"{number(aligned_at)} N·m" if aligned_at >= 0 else "none",
                             ("eq (20): no spring force, so no misalignment (eq 21); "
                              if aligned_at >= 0 else
                              f"eq (20) has no spring force only at {number(aligned_at)} N·m; ")
                             + f"{number(spring['misalignment_at_no_torque_mm'])} mm at no "
                               "torque"))
    if any(r.get("pressure_MPa") is not None for r in rows):
        pressed = [r["pressure_MPa"] for r in rows if r["pressure_MPa"] > 0]
        aligned = [r["pressure_aligned_MPa"] for r in rows if r["pressure_aligned_MPa"] > 0]
        out.append(KeyResult("contact pressure with the spring (eq 19)", span(pressed, "MPa"),
                             f"{at}; shaft aligned {span(aligned, 'MPa')}"))
        law = (f"μ = {number(spring['friction_mu_ref'])}·(p / "
               f"{number(spring['friction_pressure_ref_MPa'])} MPa)^"
               f"{number(spring['friction_exponent'])}; " if "friction_mu_ref" in spring else "")
        aligned_mu = span([r.get("mu_aligned") for r in rows])
        out.append(KeyResult("friction coefficient μ with the spring",
                             span([r.get("mu") for r in rows]),
                             f"{law}{at}; shaft aligned {aligned_mu}"))
    return out


# ---------------------------------------------------------------------------------------
# inputs as given


def toml_lines(table: dict, prefix: str = "") -> list[str]:
    """The case's inputs as TOML text: plain keys first, then each sub-table (a table that
    holds only sub-tables gets no header of its own)."""
    import json

    lines = [f"{k} = {json.dumps(v, ensure_ascii=False)}" for k, v in table.items()
             if not isinstance(v, dict) and not (isinstance(v, list) and v and isinstance(v[0], dict))]
    for k, v in table.items():
        name = f"{prefix}{k}"
        if isinstance(v, dict):
            inner = toml_lines(v, f"{name}.")
            has_plain = any(not isinstance(x, dict) for x in v.values())
            lines += (["", f"[{name}]"] if has_plain else []) + inner
        elif isinstance(v, list) and v and isinstance(v[0], dict):
            for row in v:
                lines += ["", f"[[{name}]]", *toml_lines(row, f"{name}.")]
    return lines


# ---------------------------------------------------------------------------------------
# a sweep's report


@dataclass
class SweepView:
    """What a sweep's report shows, read from its statistics (sweep.json)."""

    title: str
    sweep: str
    base: str
    sampling: str
    seed: int
    samples: int
    ok: int
    failed: int
    version: str
    key_results: list[KeyResult]
    tables: list[Table]
    failures: list[tuple[str, str]]


def sweep_view(stats: dict, version: str) -> SweepView:
    """The report of a sweep's statistics: the figures that decide (P95 of the largest
    loaded pressure, the edge-loading probability, the optimum), then the percentiles,
    sensitivities, spectrum and optimisation as tables."""
    tables = [_percentile_table("percentiles over the samples", stats.get("percentiles", {}))]
    weighted = stats.get("time_weighted")
    if weighted:
        spectrum = stats["spectrum"]
        tables.append(Table("load spectrum", ["level", "share of the time"],
                            [[str(level), number(share)] for level, share
                             in zip(spectrum["levels"], spectrum["shares"])], [False, True],
                            note=f"{spectrum['field']}: each sample weighted by its level's "
                                 "share over the draws"))
        tables.append(_percentile_table("percentiles over the operating time",
                                        weighted["percentiles"]))
    from .sweep.statistics import LEAST_DRAWS

    sensitivity = stats.get("sensitivity", {})
    intervals = stats.get("sensitivity_interval", {})
    figures = sorted({k for ranks in sensitivity.values() for k in ranks})
    draws = stats.get("sensitivity_draws")

    def rank(field: str, key: str) -> str:
        rho, interval = sensitivity[field].get(key), intervals.get(field, {}).get(key)
        if rho is None:
            return "–"
        return number(rho) + (f" ({number(interval[0])} to {number(interval[1])})"
                              if interval else "")

    if figures:
        tables.append(Table("sensitivity: Spearman rank correlation (95 % interval)",
                            ["toleranced input"] + [label(k) for k in figures],
                            [[field] + [rank(field, k) for k in figures]
                             for field in sensitivity],
                            [False] + [True] * len(figures),
                            note="within each grid point, averaged over the grid"
                                 + (f"; {draws} draws per grid point" if draws else "")
                                 + (f"; too few draws for an interval ({LEAST_DRAWS} or more)"
                                    if draws is not None and draws < LEAST_DRAWS else "")))
    sobol = stats.get("sobol")
    if sobol:
        rows = [[field, label(k), number(i["S1"]), number(i["S1_conf"]), number(i["ST"]),
                 number(i["ST_conf"])]
                for field, per in sobol["indices"].items() for k, i in per.items()]
        tables.append(Table("Sobol indices (Saltelli's design, SALib)",
                            ["toleranced input", "figure", "first order S1", "± (95 %)",
                             "total ST", "± (95 %)"], rows,
                            [False, False, True, True, True, True],
                            collapsed=len(rows) > COLLAPSE_ROWS,
                            note=f"over {sobol['grid_points']} of {sobol['of']} grid points "
                                 "(those whose every sample answered), averaged"))
    opt = stats.get("optimise")
    if opt:
        names = [v["field"] for v in opt["variables"]]
        constraints = [c["statistic"] for c in opt["constraints"]]
        tables.append(Table(
            "optimisation: every design tried",
            ["evaluation"] + names + [opt["objective"]] + [f"{c} (≤ {o['max']:g})" for c, o
                                                           in zip(constraints,
                                                                  opt["constraints"])]
            + ["feasible"],
            [[str(h["evaluation"])] + [str(h["design"][n]) for n in names]
             + [number(h["objective"])] + [number(g) for g in h["constraints"]]
             + [number(h["feasible"])] for h in opt["history"]],
            [True] + [False] * len(names) + [True] * (1 + len(constraints)) + [False],
            collapsed=len(opt["history"]) > COLLAPSE_ROWS,
            note=f"{opt['method']}: {opt['message']}"))
    return SweepView(
        title=stats.get("title") or stats["sweep"], sweep=stats["sweep"], base=stats["base"],
        sampling=stats["sampling"], seed=stats["seed"], samples=stats["samples"],
        ok=stats["ok"], failed=stats["failed"], version=version,
        key_results=_sweep_key_results(stats), tables=tables,
        failures=[(str(n), e) for n, e in stats.get("failures", {}).items()])


def _percentile_table(title: str, percentiles: dict) -> Table:
    names = ["P5", "P50", "P95", "P99"]
    return Table(title, ["figure"] + names,
                 [[label(k)] + [number(q.get(n)) for n in names]
                  for k, q in percentiles.items()], [False] + [True] * len(names))


def _sweep_key_results(stats: dict) -> list[KeyResult]:
    out = []
    for key in ("bem_max_p_max_MPa", "loaded_transmission_error_peak_to_peak_urad",
                "max_p_max_MPa"):
        q = stats.get("percentiles", {}).get(key)
        if q:
            out.append(KeyResult(f"{label(key)}, P95", number(q["P95"]),
                                 f"P50 {number(q['P50'])}, P99 {number(q['P99'])}"))
    for flag, what in (("edge_loading", "edge loading (any flank edge)"),
                       ("end_loading", "loading at a face end"),
                       ("corner_contact", "a corner contact (tip, root or form edge)")):
        edge = stats.get(flag)
        if edge and edge.get("probability") is not None:
            low, high = edge["interval_95"]
            out.append(KeyResult(f"probability of {what}", f"{edge['probability']:.1%}",
                                 f"95 % interval {low:.1%} to {high:.1%} over "
                                 f"{edge['samples']} samples", bad=edge["probability"] > 0))
        weighted = (stats.get("time_weighted") or {}).get(flag)
        if weighted:
            out.append(KeyResult(f"share of the time: {what}", f"{weighted['time_share']:.1%}",
                                 "over the load spectrum", bad=weighted["time_share"] > 0))
    opt = stats.get("optimise")
    if opt:
        best = opt["best"]
        out.append(KeyResult(f"optimum: {opt['objective']}", number(best["objective"]),
                             ", ".join(f"{k} = {v}" for k, v in best["design"].items())
                             + ("" if best["feasible"] else " (no feasible design found)"),
                             bad=not best["feasible"]))
    return out


def _lubrication_results(summary: dict) -> list[KeyResult]:
    """The lubricated contact's key results (analyses.lubrication), where it was analysed."""
    if summary.get("lambda_min") is None:
        return []
    out = [KeyResult("least specific film λ", number(summary["lambda_min"]),
                     f"h_min {number(summary['film_thickness_min_um'])} µm over the mean Ra, "
                     f"at {summary['lambda_min_at']}"),
           KeyResult("largest flash temperature",
                     f"{number(summary['flash_temperature_max_K'])} K",
                     f"at {summary['flash_temperature_at']}; contact temperature "
                     f"{number(summary['contact_temperature_max_degC'])} °C on a bulk "
                     f"{number(summary['bulk_temperature_degC'])} °C")]
    if summary.get("mesh_power_loss_W") is not None:
        out.append(KeyResult("mesh power loss", f"{number(summary['mesh_power_loss_W'])} W",
                             f"mesh efficiency {100 * summary['mesh_efficiency']:.2f} %, mean "
                             f"μ {number(summary['friction_coefficient_mean'])}"))
    for key, label_, needs in (("S_B", "scuffing safety S_B", "scuffing_temperature"),
                               ("S_lambda", "micropitting safety S_λ",
                                "permissible_specific_film")):
        value, note = summary.get(key), summary.get(f"{key}_note")
        out.append(KeyResult(label_, "—" if value is None else number(value),
                             note or (f"not computed: no [lubricant] {needs}" if value is None
                                      else f"against the [lubricant] {needs}"),
                             value is not None and value < 1.0))
    return out

