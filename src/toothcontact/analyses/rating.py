"""What a cylindrical gear pair's loaded contact decides: the tooth root stress of every
contact (rating.root, from its line load along the face and its height), ISO 6336's pitting
and bending ratings with the loaded contact's face load factor (rating.iso6336), and a duty
cycle's damage sums."""

from __future__ import annotations

import math

import numpy as np

from .result import Check, Result

#: face strips each member's line load is summed on for its root stress
ROOT_STRIPS = 40
#: what a duty cycle's level reports of its lubricated contact (None without [operation])
LUBRICATED_LEVEL_KEYS = ("lambda_min", "flash_temperature_max_K", "contact_temperature_max_degC",
                         "mesh_power_loss_W", "mesh_efficiency")


#: a Miner sum below this is no damage to speak of (shown as such, not as its round-off)
LEAST_DAMAGE = 1e-9

def root_sections(case, pair, result: Result) -> None:
    """root_stress_pinion_MPa and root_stress_gear_MPa on every row (the largest along the
    face of the tooth that contact loads; 0 where unloaded, None where not solved or for
    an internal gear), and the largest of each in the summary with where."""
    from ..rating.root import root_stress

    loaded, cycle = result.loaded, result.cycle
    if not loaded:
        return
    overlap = (case.face_width * math.sin(case.helix_angle)
               / (math.pi * case.module_mm))
    members = {"pinion": (pair.pinion, cycle.pinion), "gear": (pair.gear, cycle.gear)}
    models = {name: None if gear.internal else root_stress(
                  gear, math.hypot(gear.base_radius, getattr(flank, "base", flank).form_roll),
                  overlap)
              for name, (gear, flank) in members.items()}
    rows = result.sections["positions"]
    for k, row in enumerate(rows):
        contact = loaded[k]
        for member, (name, (gear, _)) in enumerate(members.items()):
            key = f"root_stress_{name}_MPa"
            if contact is None or models[name] is None:
                row[key] = 0.0 if row["bem_status"] == "unloaded" and models[name] else None
                continue
            row[key] = _largest_root_stress(contact, member, gear, models[name])
    summary = result.sections["summary"]
    for name in members:
        key = f"root_stress_{name}_MPa"
        known = [r for r in rows if r.get(key) is not None]
        if not known:
            continue
        worst = max(known, key=lambda r: r[key])
        summary[f"{name}_root_stress_max_MPa"] = worst[key]
        summary[f"{name}_root_stress_at"] = f"roll {worst['roll_deg']:.2f} deg pair {worst['pair']}"
    summary["root_stress_note"] = (
        "root stress: ISO 6336-3 Method B's nominal bending stress at the critical section "
        "(30° tangents to the generated fillet; a helical gear's virtual spur gear) times "
        "its stress correction Y_S, of each contact's line load on face strips at its own "
        "height, the largest along the face; at the load analysed (K_A, K_v not applied); "
        + ("an internal gear's is not modelled" if pair.gear.internal else
           "against 2D finite elements of the exact tooth within 10 % (tests)"))


def _largest_root_stress(contact, member: int, gear, model) -> float:
    """The largest root stress (MPa) along a member's face (0: the pinion, 1: the gear)
    under one contact: its line load on ROOT_STRIPS face strips (each cell's load spread
    over the face it spans), each strip's at the load-weighted radius of its cells (where
    the tooth model placed them)."""
    face, pressure = contact.faces[member], contact.solution.pressure_MPa
    half = 0.5 * gear.face_width
    edges = np.linspace(-half, half, ROOT_STRIPS + 1)
    line_load = face.line_load(pressure, edges)
    moment = face.line_load(pressure, edges, moment=True)
    on = line_load > 1e-12 * max(float(line_load.max()), 1e-300)
    if not on.any():
        return 0.0
    return float(model.stress(line_load[on], moment[on] / line_load[on]).max())


#: a gear's density where its material gives none (kg/m³): steel's, a cast iron's
DENSITY = {"steel": 7830.0, "cast_iron": 7200.0}


def rated_pair(case, pair):
    """The pair as ISO 6336 rates it (rating.iso6336.RatedPair) and the assumptions made to
    build it (densities not given); raises CaseError naming the field where a material's
    hardness has no ISO 6336-5 row."""
    from ..case import CAST_IRONS, CaseError
    from ..rating.iso6336 import RatedMember, RatedPair

    assumptions, members = [], {}
    cycles = _pinion_cycles(case)
    for name, gear, field in (("pinion", pair.pinion, "material"),
                              ("gear", pair.gear, "gear_material" if case.gear_material
                               else "material")):
        material = getattr(case, field)
        try:
            allowables = {stress: _allowable(material, stress) for stress in ("contact", "bending")}
        except ValueError as exc:
            raise CaseError(f"{field}.{exc}") from None
        density = material.density
        if density is None:
            kind = "cast_iron" if material.treatment in CAST_IRONS else "steel"
            density = DENSITY[kind]
            assumptions.append(f"{name}'s density {density:g} kg/m³ ({kind.replace('_', ' ')}"
                               f"; the dynamic factor's masses)")
        spec = getattr(case, name)
        members[name] = RatedMember(
            gear, material.E, material.nu, density * 1e-9, material.treatment,
            allowables["contact"], allowables["bending"],
            None if spec.roughness_Ra is None else 1e3 * spec.roughness_Ra,
            None if spec.root_roughness_Rz is None else 1e3 * spec.root_roughness_Rz,
            material.yield_strength,
            0.0 if spec.tip_relief is None else 1e3 * spec.tip_relief.amount,
            None if cycles is None else cycles * (1.0 if name == "pinion"
                                                  else pair.pinion.teeth / pair.gear.teeth))
    return RatedPair(members["pinion"], members["gear"], pair.center_distance,
                     pair.working_pressure_angle, pair.transverse_mesh().contact_ratio
                     ), assumptions


def _allowable(material, stress: str):
    """A material's σ_Hlim ("contact") or σ_Flim ("bending"): given, from its hardness and
    quality by ISO 6336-5 Table 1, or None."""
    from ..rating.allowables import allowable
    from ..rating.iso6336 import Allowable

    given = material.sigma_Hlim if stress == "contact" else material.sigma_Flim
    if given is not None:
        return Allowable(given, "given")
    if material.hardness is None:
        return None
    found = allowable(stress, material.treatment, *material.hardness, material.quality,
                      cast=material.cast, alloy=material.alloy,
                      core_hrc=None if material.core_hardness is None
                      else material.core_hardness[0])
    return Allowable(found.value, found.source)


def _pinion_cycles(case) -> float | None:
    """The pinion teeth's load cycles: given, or its life at the case's speed (60·n·L_h)."""
    if case.rating.life is not None:
        return 60.0 * case.operation.pinion_speed * case.rating.life
    return case.rating.pinion_cycles


def _duty(case, pair):
    """ISO's view of how the pair runs (rating.iso6336.Duty): the pinion's torque and speed,
    the oil, the accuracy grade, the mesh misalignment f_ma = |slope|·b and the deflection
    f_sh, the largest less the least of the pinion's deflection over the face (the case's
    and the shafts'), µm."""
    from ..rating.iso6336 import Duty

    width = min(pair.pinion.face_width, pair.gear.face_width)
    torque = (case.load.torque if case.load.torque is not None
              else case.load.tangential_load * pair.operating_pitch_radius)
    deflection = 0.0
    if pair.pinion_deflection is not None:
        drop = pair.pinion_deflection.drop(np.linspace(-0.5 * width, 0.5 * width, 41), width)
        deflection = 1e3 * float(np.ptp(drop))
    r = case.rating
    return Duty(torque, None if case.operation is None else case.operation.pinion_speed,
                None if case.lubricant is None else case.lubricant.viscosity_40,
                r.accuracy_grade, 1e3 * abs(case.misalignment.slope) * width, deflection,
                r.limited_pitting, r.S_Hmin, r.S_Fmin)


def _given_factors(rating) -> dict[str, float]:
    """The factors a [rating] gives, by result key (case.GIVEN_FACTORS)."""
    from ..case import GIVEN_FACTORS

    return {GIVEN_FACTORS[name][0]: getattr(rating, name) for name in GIVEN_FACTORS
            if name in rating.model_fields_set and getattr(rating, name) is not None}


def iso_rating_sections(case, pair, result: Result) -> None:
    """ISO 6336's ratings of the pair (rating.iso6336, Method B with the loaded contact's
    K_Hβ, Method A) into the summary, every factor a key; the `rating` section (each
    figure's symbol, value and source, the factors given, the assumptions); the loaded
    contact's largest flank pressure beside ISO's σ_H; a design check of S_H and of each
    S_F against their least, and of the flank pressure against flank_pressure_limit where
    given."""
    from ..case import GIVEN_FACTORS
    from ..rating.iso6336 import ContactFigures, rate

    summary = result.sections["summary"]
    loaded = summary.get("K_H_beta") is not None
    iso_pair, assumptions = rated_pair(case, pair)
    given = _given_factors(case.rating)
    rating = rate(iso_pair, _duty(case, pair), given, ContactFigures(
        summary.get("K_H_beta"), summary.get("mesh_stiffness_N_per_mm_um")) if loaded
        else ContactFigures())
    rules = case.rating
    assumptions = list(assumptions) + list(rating.assumptions)
    for name, least in (("S_Hmin", rules.S_Hmin), ("S_Fmin", rules.S_Fmin)):
        if name not in rules.model_fields_set:
            assumptions.append(f"{name} = {least:g} (not given)")
    symbols = dict(GIVEN_FACTORS.values())
    summary.update(rating.values())
    summary["rating_factors_given"] = [symbols[key] for key in given]
    _flank_pressure(summary, result)
    result.sections["rating"] = {
        "figures": [{"key": f.key, "symbol": f.symbol, "value": f.value, "source": f.source}
                    for f in rating.figures],
        "factors_given": summary["rating_factors_given"], "assumptions": assumptions,
        "note": "ISO 6336-1/-2/-3:2006 Method B with ISO 6336-5's allowables; K_Hβ the "
                "loaded contact's (ISO 6336-1 Method A) where it was solved, K_Hα ISO's "
                "Method B on the loaded contact's mesh stiffness (its flanks are evenly "
                "spaced: the pitch deviation K_Hα stands for comes from accuracy_grade); "
                "the loaded contact's own largest flank pressure (flank_pressure_max_MPa) "
                "and root stresses (*_root_stress_max_MPa) are local figures beside them, "
                "not ISO's σ_H and σ_F"}
    if summary.get("S_H") is not None:
        result.checks.append(Check(
            "contact safety S_H at least S_Hmin", summary["S_H"] >= rules.S_Hmin,
            f"S_H {summary['S_H']:.3f} (ISO 6336-2: σ_H {summary['sigma_H_MPa']:.0f} MPa "
            "against σ_HP " + " / ".join(
                f"{summary[f'sigma_HP_{m}_MPa']:.0f}" for m in ("pinion", "gear")
                if summary.get(f"sigma_HP_{m}_MPa") is not None)
            + f" MPa), least {rules.S_Hmin:g}"))
    for name in ("pinion", "gear"):
        S_F = summary.get(f"S_F_{name}")
        if S_F is not None:
            result.checks.append(Check(
                f"root safety S_F of the {name} at least S_Fmin", S_F >= rules.S_Fmin,
                f"S_F {S_F:.3f} (ISO 6336-3: σ_F {summary[f'sigma_F_{name}_MPa']:.0f} MPa, "
                f"σ_FP {summary[f'sigma_FP_{name}_MPa']:.0f} MPa), least {rules.S_Fmin:g}"))
    limit = rules.flank_pressure_limit
    if limit is not None and summary.get("flank_pressure_max_MPa") is not None:
        result.checks.append(Check(
            "loaded flank pressure at most the given limit",
            summary["flank_pressure_max_MPa"] <= limit,
            f"{summary['flank_pressure_max_MPa']:.0f} MPa at {summary['flank_pressure_at']}, "
            f"limit {limit:.0f} MPa (rating.flank_pressure_limit; a local figure, not ISO's "
            "S_H)"))


def _flank_pressure(summary: dict, result: Result) -> None:
    """Where the loaded contact's largest flank pressure is (flank_pressure_at) and its ratio
    to ISO's σ_H (flank_pressure_to_sigma_H)."""
    rows = [r for r in result.sections.get("positions", []) if r.get("bem_status") == "solved"]
    if not rows:
        summary.update(flank_pressure_at=None, flank_pressure_to_sigma_H=None)
        return
    top = max(rows, key=lambda r: r["flank_p_max_MPa"])
    summary["flank_pressure_at"] = (f"roll {top['roll_deg']:.2f} deg pair {top['pair']}"
                                    + (", an edge-loaded contact" if top["edge_loaded"] else ""))
    sigma_H = summary.get("sigma_H_MPa")
    summary["flank_pressure_to_sigma_H"] = (summary["flank_pressure_max_MPa"] / sigma_H
                                            if sigma_H else None)


def duty_cycle_sections(case, result: Result, run_level) -> None:
    """A `[[load.spectrum]]`'s levels, each analysed (`run_level(level_case, scratch)` runs
    the contact, the loaded contact and the ratings into a scratch Result; no positions
    check, no subsurface stresses): the `duty_cycle` section with each level's load, cycles,
    ISO's σ_H and σ_F (with the level's own K_v, K_Hβ, K_Hα), the loaded contact's local
    pressures and root stresses and its transmission error (peak to peak and harmonics), and
    Miner's sums D = Σ n_i/N_i of the flanks and the roots against the S-N curves of the
    life factors (ISO 6336-6: Z_NT's and Y_NT's lines, continued past 10¹⁰ cycles with their
    last slope: Miner's elementary rule); the summary's `miner_sum_*` and a design check
    each (D <= 1)."""
    from .. import units
    from ..case import CaseError, LoadSpec
    from ..rating.life import contact_cycles, root_cycles

    levels = case.load.spectrum
    if not levels:
        return
    quiet = case.analysis.model_copy(update={"positions_check": False, "subsurface": False,
                                             "ease_off": False})
    z1, z2 = case.teeth
    materials = {"pinion": case.material, "gear": case.gear_material or case.material}
    level_keys = ("sigma_H_MPa", "sigma_H_pinion_MPa", "sigma_H_gear_MPa",
                  "sigma_F_pinion_MPa", "sigma_F_gear_MPa", "K_v", "K_H_beta_rating",
                  "flank_pressure_max_MPa", "pinion_root_stress_max_MPa",
                  "gear_root_stress_max_MPa", "bem_max_p_max_MPa",
                  "loaded_transmission_error_peak_to_peak_um", "te_harmonics_um",
                  *LUBRICATED_LEVEL_KEYS)
    rows = []
    for i, level in enumerate(levels):
        scratch = Result()
        try:
            run_level(case.model_copy(update={
                "load": LoadSpec.model_construct(tangential_load=level.tangential_load,
                                                 torque=level.torque, spectrum=[]),
                "analysis": quiet}), scratch)
        except CaseError as exc:     # the level's load is what the case got wrong
            given = (f"torque {units.show(level.torque, 'torque')}" if level.torque is not None
                     else f"tangential_load {units.show(level.tangential_load, 'force')}")
            raise CaseError(f"load.spectrum[{i}]: at its {given}: {exc}") from None
        s = scratch.sections["summary"]
        rows.append({"tangential_load_N": s["tangential_load_N"], "pinion_cycles": level.cycles,
                     **{key: s.get(key) for key in level_keys}})
    section = {"levels": rows}
    summary = result.sections["summary"]

    def product(*keys: str) -> float | None:
        values = [summary.get(key) for key in keys]
        return None if None in values else math.prod(values)

    for name, material in materials.items():
        share = 1.0 if name == "pinion" else z1 / abs(z2)
        strengths = {
            "flank": (f"sigma_H_{name}_MPa", product(f"sigma_Hlim_{name}_MPa", "Z_L", "Z_v",
                                                     "Z_R", "Z_W", "Z_X"),
                      lambda f, material=material: contact_cycles(
                          material.treatment, f, case.rating.limited_pitting)),
            "root": (f"sigma_F_{name}_MPa", product(f"sigma_Flim_{name}_MPa", "Y_ST",
                                                    f"Y_delta_rel_T_{name}",
                                                    f"Y_R_rel_T_{name}", f"Y_X_{name}"),
                     lambda f, material=material: root_cycles(material.treatment, f))}
        for kind, (stress_key, strength, cycles_of) in strengths.items():
            key = f"miner_sum_{kind}_{name}"
            if strength is None or any(r[stress_key] is None for r in rows):
                summary[key] = None
                continue
            damage = sum(r["pinion_cycles"] * share / cycles_of(r[stress_key] / strength)
                         for r in rows)
            summary[key] = damage
            result.checks.append(Check(
                f"duty cycle: Miner's sum of the {name}'s {kind} at most 1", damage <= 1.0,
                (f"D = {damage:.3g}" if damage >= LEAST_DAMAGE else "D below 10⁻⁹")
                + f" over {len(rows)} levels"))
    section["note"] = (
        "each level analysed as the case at that load (no positions check, no subsurface "
        "stresses); miner_sum_* = Σ n_i/N_i, n_i the level's load cycles of the member "
        "(the gear's by the ratio), N_i where the S-N curve of ISO 6336-6 (σ_Hlim·Z_NT·Z_L·"
        "Z_v·Z_R·Z_W·Z_X, resp. σ_Flim·Y_ST·Y_NT·Y_δrelT·Y_RrelT·Y_X, over N) meets the "
        "level's ISO σ_H, resp. σ_F; past 10¹⁰ cycles the curves go on with their last slope "
        "(Miner's elementary rule), above the static strength N_i is the static limit's "
        "cycles")
    result.sections["duty_cycle"] = section
