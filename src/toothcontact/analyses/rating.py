"""What a cylindrical gear pair's loaded contact decides: the tooth root stress of every
contact (rating.root, from its line load along the face and its height) and the safety
factors against the materials' allowable stress numbers (ISO 6336-2 and -3, the life
factors of rating.life)."""

from __future__ import annotations

import math

import numpy as np

from .result import Check, Result

#: face strips each member's line load is summed on for its root stress
ROOT_STRIPS = 40
#: what a duty cycle's level reports of its lubricated contact (None without [operation])
LUBRICATED_LEVEL_KEYS = ("lambda_min", "flash_temperature_max_K", "contact_temperature_max_degC",
                         "mesh_power_loss_W", "mesh_efficiency")
#: ISO 6336-3's stress correction factor of the reference test gear (σ_FE = σ_Flim·Y_ST)
Y_ST = 2.0


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


def safety_sections(case, pair, result: Result) -> None:
    """S_H (the least of the members'), S_H_pinion, S_H_gear, S_F_pinion and S_F_gear in
    the summary, with the permissible stresses and life factors; None with the reason in
    safety_note where a member's allowable is not given; a design check of each against
    its least (case.rating)."""
    from ..rating.life import contact_life_factor, root_life_factor

    summary = result.sections["summary"]
    solved = [r for r in result.sections.get("positions", []) if r.get("bem_status") == "solved"]
    if not solved:
        return
    # σ_H: the largest active-flank pressure (flank_p_max leaves out the strips at the
    # edges and the tip roundings, whose pressure has its own check) of every contact: an
    # edge-loaded one's flank carries its load too (leaving those out judged an unrelieved
    # helical pair, its every loaded contact on a gear tip's corner, by a 39 MPa contact)
    top = max(solved, key=lambda r: r["flank_p_max_MPa"])
    rating = case.rating
    load_factor = rating.application_factor * rating.dynamic_factor
    z1, z2 = case.teeth
    cycles = {"pinion": rating.pinion_cycles,
              "gear": None if rating.pinion_cycles is None
              else rating.pinion_cycles * z1 / abs(z2)}
    materials = {"pinion": case.material, "gear": case.gear_material or case.material}
    sigma_H = top["flank_p_max_MPa"] * math.sqrt(load_factor)
    notes, contact = [], {}
    for name, material in materials.items():
        n = cycles[name]
        if material.sigma_Hlim is None:
            summary[f"S_H_{name}"] = None
            notes.append(f"no sigma_Hlim for the {name}'s material: no S_H")
        else:
            Z_NT = 1.0 if n is None else contact_life_factor(material.treatment, n,
                                                              rating.limited_pitting)
            permissible = material.sigma_Hlim * Z_NT * rating.lubrication_factor
            contact[name] = permissible / sigma_H
            summary.update({f"Z_NT_{name}": Z_NT, f"sigma_HP_{name}_MPa": permissible,
                            f"S_H_{name}": contact[name]})
        stress = summary.get(f"{name}_root_stress_max_MPa")
        if material.sigma_Flim is None or stress is None:
            summary[f"S_F_{name}"] = None
            notes.append(f"no sigma_Flim for the {name}'s material: no S_F" if stress is not None
                         else f"no root stress for the {name}: no S_F")
            continue
        Y_NT = 1.0 if n is None else root_life_factor(material.treatment, n)
        permissible = material.sigma_Flim * Y_ST * Y_NT
        summary.update({f"Y_NT_{name}": Y_NT, f"sigma_FP_{name}_MPa": permissible,
                        f"S_F_{name}": permissible / (stress * load_factor) if stress > 0
                        else None})
    summary["S_H"] = min(contact.values()) if contact else None
    summary["sigma_H_MPa"] = sigma_H
    summary["sigma_H_at"] = (f"roll {top['roll_deg']:.2f} deg pair {top['pair']}"
                             + (", an edge-loaded contact" if top["edge_loaded"] else ""))
    summary["safety_note"] = (
        "S_H = σ_Hlim·Z_NT·(Z_L·Z_v·Z_R) / σ_H, σ_H the largest loaded pressure on the active "
        "flank, more than 0.1 mm inside its edges and off the tip roundings (an edge's "
        "pressure has its own check), times "
        "sqrt(K_A·K_v) (ISO 6336-2; Z_W = Z_X = 1); S_F = σ_Flim·Y_ST·Y_NT / "
        "(σ_F·K_A·K_v), σ_F the largest root stress (ISO 6336-3; Y_ST = 2, Y_δrelT = Y_RrelT = "
        "Y_X = 1); life factors for "
        + ("the endurance limit (no load cycles given)" if cycles["pinion"] is None else
           f"{cycles['pinion']:.3g} pinion and {cycles['gear']:.3g} gear load cycles")
        + (f"; K_A·K_v = {load_factor:g}" if load_factor != 1.0 else "")
        + ("; " + "; ".join(notes) if notes else ""))
    if contact:
        result.checks.append(Check(
            "contact safety S_H at least S_Hmin", summary["S_H"] >= rating.S_Hmin,
            f"S_H {summary['S_H']:.3f} (σ_H {sigma_H:.0f} MPa against σ_HP "
            + " / ".join(f"{summary[f'sigma_HP_{m}_MPa']:.0f}" for m in contact)
            + f" MPa), least {rating.S_Hmin:g}"))
    for name in materials:
        S_F = summary.get(f"S_F_{name}")
        if S_F is not None:
            result.checks.append(Check(
                f"root safety S_F of the {name} at least S_Fmin", S_F >= rating.S_Fmin,
                f"S_F {S_F:.3f} (σ_F {summary[f'{name}_root_stress_max_MPa']:.0f} MPa at "
                f"{summary[f'{name}_root_stress_at']}, σ_FP "
                f"{summary[f'sigma_FP_{name}_MPa']:.0f} MPa), least {rating.S_Fmin:g}"))


def duty_cycle_sections(case, result: Result, run_level) -> None:
    """A `[[load.spectrum]]`'s levels, each analysed (`run_level(level_case, scratch)` runs
    the contact, the loaded contact and the ratings into a scratch Result; no positions
    check, no subsurface stresses): the `duty_cycle` section with each level's load, cycles,
    σ_H, root stresses and transmission error (peak to peak and harmonics), and Miner's sums
    D = Σ n_i/N_i of the flanks and the roots against the S-N curves of the life factors
    (ISO 6336-6: Z_NT's and Y_NT's lines, continued past 10¹⁰ cycles with their last slope:
    Miner's elementary rule); the summary's `miner_sum_*` and a design check each (D <= 1)."""
    from ..case import LoadSpec
    from ..rating.life import contact_cycles, root_cycles

    levels = case.load.spectrum
    if not levels:
        return
    rating = case.rating
    load_factor = rating.application_factor * rating.dynamic_factor
    quiet = case.analysis.model_copy(update={"positions_check": False, "subsurface": False,
                                             "ease_off": False})
    z1, z2 = case.teeth
    materials = {"pinion": case.material, "gear": case.gear_material or case.material}
    rows = []
    for level in levels:
        scratch = Result()
        run_level(case.model_copy(update={
            "load": LoadSpec.model_construct(tangential_load=level.tangential_load,
                                             torque=level.torque, spectrum=[]),
            "analysis": quiet}), scratch)
        s = scratch.sections["summary"]
        rows.append({"tangential_load_N": s["tangential_load_N"], "pinion_cycles": level.cycles,
                     "sigma_H_MPa": s.get("sigma_H_MPa"),
                     "pinion_root_stress_max_MPa": s.get("pinion_root_stress_max_MPa"),
                     "gear_root_stress_max_MPa": s.get("gear_root_stress_max_MPa"),
                     "bem_max_p_max_MPa": s.get("bem_max_p_max_MPa"),
                     "loaded_transmission_error_peak_to_peak_um":
                         s.get("loaded_transmission_error_peak_to_peak_um"),
                     "te_harmonics_um": s.get("te_harmonics_um"),
                     **{key: s.get(key) for key in LUBRICATED_LEVEL_KEYS}})
    section = {"levels": rows}
    summary = result.sections["summary"]
    for name, material in materials.items():
        share = 1.0 if name == "pinion" else z1 / abs(z2)
        for kind, allowable, stress_key, cycles_of in (
                ("flank", material.sigma_Hlim, "sigma_H_MPa",
                 lambda f: contact_cycles(material.treatment, f, rating.limited_pitting)),
                ("root", None if material.sigma_Flim is None else Y_ST * material.sigma_Flim,
                 f"{name}_root_stress_max_MPa",
                 lambda f: root_cycles(material.treatment, f))):
            key = f"miner_sum_{kind}_{name}"
            if allowable is None or any(r[stress_key] is None for r in rows):
                summary[key] = None
                continue
            scale = math.sqrt(load_factor) if kind == "flank" else load_factor
            damage = sum(r["pinion_cycles"] * share
                         / cycles_of(r[stress_key] * scale
                                     / (allowable * (rating.lubrication_factor
                                                     if kind == "flank" else 1.0)))
                         for r in rows)
            summary[key] = damage
            result.checks.append(Check(
                f"duty cycle: Miner's sum of the {name}'s {kind} at most 1", damage <= 1.0,
                f"D = {damage:.3g} over {len(rows)} levels"))
    section["note"] = (
        "each level analysed as the case at that load (no positions check, no subsurface "
        "stresses); miner_sum_* = Σ n_i/N_i, n_i the level's load cycles of the member "
        "(the gear's by the ratio), N_i where the S-N curve of ISO 6336-6 (σ_Hlim·Z_NT·Z_L·Z_v·"
        "Z_R, resp. σ_Flim·Y_ST·Y_NT, over N) meets the level's σ_H·sqrt(K_A·K_v), resp. "
        "σ_F·K_A·K_v; past 10¹⁰ cycles the curves go on with their last slope (Miner's "
        "elementary rule), above the static strength N_i is the static limit's cycles")
    result.sections["duty_cycle"] = section
