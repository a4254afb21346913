"""What a report shows, read from a result document (no recomputation, no case parsing):
the key results that decide the design, the design checks apart from the source-data and
method checks, the inputs as given, and the results as tables with human labels, units and
numbers rounded to four significant digits (a column's figure below the resolution its
largest value is printed to shows as 0). The templates (templates/report.*.j2) lay it
out as Markdown and as one self-contained HTML page."""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass, field

from .labels import (
    CHARTS,
    MARGIN_RESOLUTION,
    META,
    TE_RESOLUTION,
    TE_UM_RESOLUTION,
    ZERO,
    floor,
    in_words,
    label,
    number,
    over,
    span,
    unit_of,
)


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
    is shown collapsed, and one of many rows or columns is written beside the reports as
    the CSV file `csv` (report.md links it instead of repeating it; report.html keeps it,
    sortable). `brief`: report.md
    names it and points to report.html instead of repeating it (the summary's every
    figure, which the key results already pick from)."""

    title: str
    headers: list[str]
    rows: list[list[str]]
    numeric: list[bool]
    collapsed: bool = False
    note: str = ""
    csv: str = ""
    brief: bool = False


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
    #: the long definitions, once each, at the end: (what it defines, the text)
    glossary: list[tuple[str, str]] = field(default_factory=list)

    @property
    def failed(self) -> list[CheckLine]:
        return [c for c in self.design_checks if not c.ok]

    @property
    def disagreements(self) -> list[CheckLine]:
        """The source and method checks that disagree (shown, not flagged)."""
        return [c for c in self.other_checks if not c.ok]


#: a table of more rows than this is shown collapsed
COLLAPSE_ROWS = 12
#: a table of more columns than this (or more rows than COLLAPSE_ROWS) is written as a CSV
#: file beside the reports, which report.md links instead of repeating (a duty cycle's
#: levels: 20 columns, 1.3 kB of FZG's report.md)
WIDE_COLUMNS = 12
#: a table's note longer than this (characters) is a definition: it goes to the glossary
GLOSSARY_NOTE = 300


def view(document: dict) -> ReportView:
    """The report of a result document."""
    checks = [CheckLine(c["name"], bool(c["ok"]), c["detail"], c.get("kind", "design"))
              for c in document.get("checks", [])]
    summary = document.get("summary") if isinstance(document.get("summary"), dict) else {}
    rating = document.get("rating") if isinstance(document.get("rating"), dict) else {}
    rated = {f["key"] for f in rating.get("figures", [])}
    tables = [t for key, value in document.items() if key not in META | CHARTS | {"rating"}
              for t in _tables(key, {k: v for k, v in value.items() if k not in rated
                                     and not _is_note(k) and k != "load_sharing"}
                               if key == "summary" else value, document["kind"])]
    if rating:
        tables.insert(0, rating_table(rating))
    entries = [(label(k).removesuffix(" note"), str(v)) for k, v in summary.items()
               if (k == "load_sharing" or _is_note(k)) and v]
    entries += [(t.title, t.note) for t in tables if len(t.note) > GLOSSARY_NOTE]
    glossary = list(dict.fromkeys(entries))            # each text once, in order
    seen = {text for _, text in glossary}
    tables = [t if t.note not in seen else dataclasses.replace(t, note="see the glossary")
              for t in tables]
    # the summary's own table: every figure, the key results' source (report.html has it)
    tables = [dataclasses.replace(t, brief=True) if t.title == "summary" and summary else t
              for t in tables]
    stages = [(name, stage.get("reason", "")) for name, stage in
              (document.get("stages") or {}).items() if stage.get("status") == "failed"]
    kind = document["kind"]

    def words(text: str) -> str:
        return in_words(text, kind)

    checks = [CheckLine(words(c.name), c.ok, words(c.detail), c.kind) for c in checks]
    tables = [dataclasses.replace(t, rows=[[words(cell) for cell in row] for row in t.rows],
                                  note=words(t.note)) for t in tables]
    return ReportView(
        title=document.get("title") or document["case"], case=document["case"],
        kind=document["kind"], source=document.get("source") or "",
        version=str(document.get("toothcontact_version", "")), units=document.get("units", ""),
        key_results=[KeyResult(words(k.label), words(k.value), words(k.where), k.bad)
                     for k in key_results(document)],
        design_checks=[c for c in checks if c.kind == "design"],
        other_checks=[c for c in checks if c.kind != "design"],
        assumptions=[str(a) for a in document.get("assumptions") or []]
        + [f"rating: {a}" for a in rating.get("assumptions", [])],
        tool_notes=[words(n) for n in document.get("notes") or []],
        glossary=[(words(name), words(text)) for name, text in glossary],
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
    rows = [[f["symbol"], number(f["value"]), unit_of(f["key"]) or "", f["source"]]
            for f in rating["figures"]]
    given = rating.get("factors_given") or []
    return Table("ISO 6336 rating", ["figure", "value", "unit", "source"], rows,
                 [False, True, False, False],
                 note=rating.get("note", "") + ("; given in the case: " + ", ".join(given)
                                                 if given else ""))


def _is_note(key: str) -> bool:
    """A section's explanation (its `note`, a summary's `..._note`): text under the table."""
    return key == "note" or key.endswith("_note")


def note_of(section: dict) -> str:
    """A section's explanations (its `note`, a summary's `..._note`s) as one text."""
    return "; ".join(f"{number(v)}" for k, v in section.items() if _is_note(k))


def _tables(key: str, value, kind: str) -> list[Table]:
    """A document section as a table: a dict as quantity/value rows (those that do not
    apply, None, left out), a list of dicts as one row each (a column that applies to no
    row left out)."""
    title = key.replace("_", " ")
    if isinstance(value, dict):
        def nested(v) -> bool:          # a table of its own: a dict, or a list of dicts
            return isinstance(v, dict) or (isinstance(v, list) and bool(v)
                                           and all(isinstance(r, dict) for r in v))

        plain = {k: v for k, v in value.items() if not _is_note(k)
                 and k not in ("load_sharing",) and v is not None and not nested(v)}
        # a table within the section (the summary's positions check, a duty cycle's levels)
        # follows as its own
        inner = [t for k, v in value.items() if nested(v)
                 for t in _tables(f"{title} {k}" if isinstance(v, list) else k, v, kind)]
        if not plain:
            if inner and note_of(value):
                inner[0] = dataclasses.replace(inner[0], note=note_of(value))
            return inner
        note = note_of(value)
        rows = [[label(k, kind, key), number(v, least=floor(k))] for k, v in plain.items()]
        return [Table(title, ["quantity", "value"], rows, [False, True], note=note)] + inner
    if isinstance(value, list) and value and all(isinstance(r, dict) for r in value):
        keys = [k for k in dict.fromkeys(k for row in value for k in row)
                if any(row.get(k) is not None for row in value)]
        scale = {k: max((abs(r[k]) for r in value if isinstance(r.get(k), float)
                         and math.isfinite(r[k])), default=0.0) for k in keys}
        rows = [[number(r.get(k), scale[k], least=floor(k)) for k in keys] for r in value]
        numeric = [all(isinstance(r.get(k), (int, float)) and not isinstance(r.get(k), bool)
                       for r in value if r.get(k) is not None) for k in keys]
        long = len(value) > COLLAPSE_ROWS
        wide = len(keys) > WIDE_COLUMNS
        return [Table(title, [label(k, kind, key) for k in keys], rows, numeric,
                      collapsed=long,
                      csv=f"{key.replace(' ', '_')}.csv" if long or wide else "")]
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
    if summary and summary.get("tooth_load_factor") is not None:
        worst = max(summary["tooth_loads"], key=lambda r: r["tooth_load_factor"])
        out.append(KeyResult(
            "tooth load factor (largest over mean tooth load)",
            number(summary["tooth_load_factor"]),
            f"{number(worst['largest_tooth_load_N'])} N against a mean of "
            f"{number(worst['mean_tooth_load_N'])} N over all teeth at roll "
            f"{number(worst['roll_deg'], resolution=0.01)} deg; "
            f"{worst['teeth_in_contact']} teeth in contact"))
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
            "largest loaded pressure with the positions refined",
            f"{number(check['refined_bem_max_p_max_MPa'])} MPa "
            f"({check['bem_max_p_max_change_percent']:+.1f} %)",
            f"the case's {check['positions']} positions and {check['refined_positions']} "
            "between them where the pressure's peak or the transmission error's extremes "
            f"can hide (steps down to 1/{round(1 / check['finest_step_fraction'])})",
            not check["converged"]))
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
    fitted = stats.get("surrogate")
    errors = (fitted or {}).get("rmse")
    tables = [_percentile_table("percentiles over the samples" if fitted is None else
                                f"percentiles over {stats['surrogate_draws']} draws on the "
                                "surrogate", stats.get("percentiles", {}), errors)]
    if fitted:
        tables.append(Table(
            "the surrogate and its error",
            ["figure", "leave-one-out RMS error", "of the figure's range", "range"],
            [[label(k), number(fitted["rmse"][k]), f"{100 * e:.1f} %",
              number(fitted["ranges"][k])] for k, e in fitted["errors"].items()],
            [False, True, True, True],
            note=f"{fitted['model']}; {fitted['loaded_samples']} loaded samples per grid "
                 f"point in {fitted['rounds']} round(s) ({fitted['design']}); "
                 + ("every figure settled: within" if fitted["converged"] else
                    f"not every figure settled (the budget, {fitted['max_samples']} samples, "
                    "is spent): within")
                 + f" the tolerance, {100 * fitted['tolerance']:g} % of its range, or, the "
                 "largest end load ratio, no draw's side of 1 in doubt; the error is a "
                 "point's: a percentile drawn on the surrogate, an average over the draws, "
                 "is surer"))
    weighted = stats.get("time_weighted")
    if weighted:
        spectrum = stats["spectrum"]
        tables.append(Table("load spectrum", ["level", "share of the time"],
                            [[str(level), number(share)] for level, share
                             in zip(spectrum["levels"], spectrum["shares"])], [False, True],
                            note=f"{spectrum['field']}: each sample weighted by its level's "
                                 "share over the draws"))
        tables.append(_percentile_table("percentiles over the operating time",
                                        weighted["percentiles"], errors))
    from ..sweep.statistics import LEAST_DRAWS

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
            [[str(h["evaluation"])] + [_as_set(h["design"][n]) for n in names]
             + [number(h["objective"])] + [number(g) for g in h["constraints"]]
             + [number(h["feasible"])] for h in opt["history"]],
            [True] + [False] * len(names) + [True] * (1 + len(constraints)) + [False],
            collapsed=len(opt["history"]) > COLLAPSE_ROWS,
            note=f"{opt['method']}: {opt['message']}"))
    return SweepView(
        title=stats.get("title") or stats["sweep"], sweep=stats["sweep"], base=stats["base"],
        sampling=stats["sampling"] + (f", {stats['surrogate_draws']} draws taken on a "
                                      "surrogate of the loaded samples"
                                      if stats.get("surrogate") else ""),
        seed=stats["seed"], samples=stats["samples"],
        ok=stats["ok"], failed=stats["failed"], version=version,
        key_results=_sweep_key_results(stats), tables=tables,
        failures=[(str(n), e) for n, e in stats.get("failures", {}).items()])


def _as_set(text) -> str:
    """A design variable's value as a sweep set it ("5496.008337120669 mm") to four
    significant digits with its unit ("5496 mm"); anything else as it is."""
    head, _, unit = str(text).partition(" ")
    try:
        return f"{number(float(head))} {unit}".strip()
    except ValueError:
        return str(text)


def _percentile_table(title: str, percentiles: dict, errors: dict | None = None) -> Table:
    """Each figure's percentiles; with a surrogate's `errors` (figure -> its leave-one-out
    RMS error) that error beside them (a figure not studied shows none)."""
    names = ["P5", "P50", "P95", "P99"]
    extra = ["surrogate error (±)"] if errors else []
    return Table(title, ["figure"] + names + extra,
                 [[label(k)] + [number(q.get(n)) for n in names]
                  + ([number(errors[k]) if k in errors else "–"] if errors else [])
                  for k, q in percentiles.items()], [False] + [True] * (len(names) + len(extra)))


def _sweep_key_results(stats: dict) -> list[KeyResult]:
    out = []
    fitted = stats.get("surrogate")
    for key in ("bem_max_p_max_MPa", "loaded_transmission_error_peak_to_peak_urad",
                "max_p_max_MPa"):
        q = stats.get("percentiles", {}).get(key)
        if q:
            error = (fitted or {}).get("rmse", {}).get(key)
            out.append(KeyResult(f"{label(key)}, P95", number(q["P95"]),
                                 f"P50 {number(q['P50'])}, P99 {number(q['P99'])}"
                                 + ("" if error is None else
                                    f"; on the surrogate, ± {number(error)}")))
    if fitted:     # the largest loaded pressure's, else the worst figure's
        shown = ("bem_max_p_max_MPa" if "bem_max_p_max_MPa" in fitted["errors"]
                 else max(fitted["errors"], key=fitted["errors"].get))
        out.append(KeyResult("surrogate error", f"{100 * fitted['errors'][shown]:.1f} %",
                             f"of the range of {label(shown)} (leave-one-out RMS), "
                             f"{fitted['loaded_samples']} loaded samples per grid point"
                             + ("" if fitted["converged"] else "; not every figure within "
                                "the tolerance"), bad=not fitted["converged"]))
    for flag, what in (("edge_loading", "edge loading (any flank edge)"),
                       ("end_loading", "loading at a face end"),
                       ("corner_contact", "a corner contact (tip, root or form edge)")):
        edge = stats.get(flag)
        if edge and edge.get("probability") is not None:
            low, high = edge["interval_95"]
            out.append(KeyResult(f"probability of {what}", f"{edge['probability']:.1%}",
                                 f"95 % interval {low:.1%} to {high:.1%} over "
                                 f"{edge['samples']} "
                                 + ("draws on the surrogate (its error not counted)"
                                    if fitted else "samples"),
                                 bad=edge["probability"] > 0))
        weighted = (stats.get("time_weighted") or {}).get(flag)
        if weighted:
            out.append(KeyResult(f"share of the time: {what}", f"{weighted['time_share']:.1%}",
                                 "over the load spectrum", bad=weighted["time_share"] > 0))
    opt = stats.get("optimise")
    if opt:
        best, recheck = opt["best"], opt.get("recheck")
        out.append(KeyResult(f"optimum: {opt['objective']}", number(best["objective"]),
                             ", ".join(f"{k} = {_as_set(v)}" for k, v in best["design"].items())
                             + ("" if best["feasible"] else " (no feasible design found)"),
                             bad=not best["feasible"]))
        if recheck:
            worst = max(recheck["errors"], key=recheck["errors"].get)
            out.append(KeyResult(
                "optimum re-checked by the loaded contact",
                f"{100 * recheck['errors'][worst]:.1f} %",
                f"RMS difference of {recheck['samples']} loaded samples from the surrogate, "
                f"over the range of {label(worst)} (its stated error "
                f"{100 * recheck['stated_errors'][worst]:.1f} %)",
                bad=not recheck["agrees"]))
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

