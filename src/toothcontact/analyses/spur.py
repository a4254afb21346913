"""The spur kind (spur and helical pairs, external and internal): geometry, the contact over
the mesh cycle and the loaded contact with the teeth bending, shafts, load distribution
and interference."""

from __future__ import annotations

import functools
import math

import numpy as np

from .. import case as schema
from ..analytic import hertz
from ..analytic.stiffness import single_stiffness
from ..case import CaseError
from . import contact, lubrication, rating
from .result import Check, Result


def spur_geometry_case(case: schema.SpurCase) -> Result:
    """Geometry of a spur/helical pair: both gears' circles, form and undercut, the mesh."""
    from .. import gearset
    from ..member_modifications import k_chart_traces
    from ..surfaces.generation import generate_side

    try:
        pair = gearset.gear_pair(case)
        mesh = pair.transverse_mesh()
    except ValueError as exc:
        raise CaseError(str(exc)) from None
    result = Result(notes=["crown and relief amounts are measured along the flank normal in the "
                           "transverse plane (ISO 21771); on a helical flank the normal "
                           "displacement is that amount times cos(beta_b)"], parts=pair)
    result.notes.append(_tip_edge_note(case, pair))
    blended = [f"{name}.{kind}" for name in ("pinion", "gear") for kind in
               ("tip_relief", "root_relief", "end_relief")
               if getattr(getattr(case, name), kind) is not None
               and getattr(getattr(case, name), kind).shape == "linear"
               and getattr(getattr(case, name), kind).blend is None]
    if blended:
        from ..surfaces.modify import RELIEF_BLEND

        result.notes.append(f"relief starts: {', '.join(blended)} blended over "
                            f"{RELIEF_BLEND:g} of the relief's length (the default; a ground "
                            "relief's transition: a kink's loaded pressure would not converge; "
                            "field blend)")
    for name, gear, mods in (("pinion", pair.pinion, pair.pinion_modifications),
                             ("gear", pair.gear, pair.gear_modifications)):
        section = {"teeth": gear.teeth, "internal": gear.internal,
                   "transverse_module_mm": gear.transverse_module,
                   "transverse_pressure_angle_deg": math.degrees(gear.transverse_pressure_angle),
                   "base_helix_angle_deg": math.degrees(gear.base_helix_angle),
                   "hand": gear.hand if gear.helix_angle else None,
                   "pitch_diameter_mm": 2 * gear.pitch_radius, "base_diameter_mm": 2 * gear.base_radius,
                   "tip_diameter_mm": 2 * gear.tip_radius, "root_diameter_mm": 2 * gear.root_radius_value,
                   "tooth_thickness_mm": gear.tooth_thickness,
                   "tip_edge_radius_mm": None if mods.tip_edge is None else mods.tip_edge.radius,
                   "tip_chamfer_angle_deg": (None if mods.tip_edge is None
                                             or mods.tip_edge.angle is None
                                             else math.degrees(mods.tip_edge.angle)),
                   "end_chamfer_mm": (None if mods.end_chamfer is None
                                      else mods.end_chamfer.length),
                   "end_chamfer_angle_deg": (None if mods.end_chamfer is None
                                             else math.degrees(mods.end_chamfer.angle)),
                   **{f"{kind}_um": None if getattr(mods, kind) is None
                      else 1e3 * getattr(mods, kind).amount
                      for kind in ("helix_slope", "profile_slope", "twist", "root_relief")}}
        if not gear.internal:
            generated = generate_side(gear)
            section["form_diameter_mm"] = 2 * generated.form_radius
            section["undercut"] = generated.undercut
            result.checks.append(Check(f"{name} is not undercut", not generated.undercut,
                                       f"form diameter {2 * generated.form_radius:.3f} mm, base "
                                       f"diameter {2 * gear.base_radius:.3f} mm"))
        if mods.lead_crown is not None:
            R = mods.lead_crown.radius_for(gear.face_width)
            section["crown_radius_mm"] = R
            for end, w in (("A", -0.5 * gear.face_width), ("B", 0.5 * gear.face_width)):
                section[f"crown_drop_{end}_mm"] = float(mods.lead_crown.drop(w, gear.face_width))
        result.sections[name] = section
    result.sections["k_chart"] = {
        name: k_chart_traces(mods, gear) for name, gear, mods in (
            ("pinion", pair.pinion, pair.pinion_modifications),
            ("gear", pair.gear, pair.gear_modifications))}
    result.sections["mesh"] = {
        "center_distance_mm": pair.center_distance,
        "working_pressure_angle_deg": math.degrees(pair.working_pressure_angle),
        "transverse_contact_ratio": mesh.contact_ratio, "overlap_ratio": pair.overlap_ratio,
        "transverse_base_pitch_mm": mesh.base_pitch,
        "rho1_lpstc_mm": mesh.lpstc(),
        "normal_backlash_mm": pair.normal_backlash,
        "transverse_backlash_mm": pair.operating_backlash,
        "backlash_note": "j_bn along the contact normal and j_wt on the operating pitch "
                         "circles (ISO 21771), from the teeth thinned for the case's backlash "
                         "(half on each member; " + (
                             "ISO/TR 10064-2's least recommended (2/3)(0.06 + 0.0005·a + "
                             "0.03·m_n) mm, as none was given" if case.backlash is None else
                             "as given") + ") at the centre distance; the gear is placed "
                         "on the working flanks, the backlash on the back ones"}
    result.checks.append(Check("transverse contact ratio above 1", mesh.contact_ratio > 1.0,
                               f"{mesh.contact_ratio:.3f}"))
    edge = pair.path_limits()
    start, end = pair.active_path()
    result.sections["mesh"]["usable_contact_ratio"] = (end - start) / mesh.base_pitch
    reach = {"gear tip below the pinion's form circle": edge["pinion_form"] - edge["gear_tip"],
             "pinion tip below the gear's form circle": edge["pinion_tip"] - edge["gear_form"]}
    result.checks.append(Check(
        "tips work on the mating involutes (no tip interference)",
        max(reach.values()) <= 1e-9,
        "; ".join(f"{what} by {d:.3f} mm along the line of action" for what, d in reach.items()
                  if d > 1e-9) or "both tips meet the mates' involutes above their form circles"))
    clearance = gearset.tip_clearances(pair.pinion, pair.gear, pair.center_distance)
    result.sections["mesh"].update({f"{name}_tip_clearance_mm": c for name, c in clearance.items()})
    result.checks.append(Check("tips clear the mating root circles",
                               min(clearance.values()) >= 0.0,
                               ", ".join(f"{name} tip {c:.3f} mm" for name, c in clearance.items())))
    if case.load is not None:
        rating.rated_pair(case, pair)      # a material without ISO 6336-5 row fails first
        if case.operation is not None:     # and a friction outside its formula's range
            lubrication.check_friction_range(case, lubrication.spur_running(case, pair))
        _spur_contact(case, pair, result)
        rating.duty_cycle_sections(
            case, result, lambda level, scratch: _spur_contact(level, gearset.gear_pair(level),
                                                               scratch))
    return result


#: with a shaft the contact is analysed again, the shafts loaded by the loaded contact's
#: line load, until their deflection under it differs by less than SHAFT_TOLERANCE (mm)
#: anywhere on the face from the one analysed: at most SHAFT_PASSES analyses in all; each
#: new pass applies SHAFT_RELAXATION of the step toward the line load found (a stiff mesh
#: answers a micrometre of deflection with a large shift of its load, and the full step can
#: swing between the face ends)
SHAFT_TOLERANCE, SHAFT_PASSES, SHAFT_RELAXATION = 0.5e-3, 4, 0.5


def _spur_contact(case: schema.SpurCase, pair, result: Result) -> None:
    """Contact by surface separation over the mesh cycle (contact.cycle) and the loaded
    contact; with a [member.shaft], repeated with the shafts carrying the loaded contact's
    line load (its mean over the cycle; the first pass spreads it evenly) until the shafts'
    deflection settles (SHAFT_TOLERANCE, SHAFT_RELAXATION): each pass starts from the
    geometry's sections and checks."""
    from ..gearset import gear_pair

    checks, sections = list(result.checks), dict(result.sections)
    changes, applied = [], None
    for attempt in range(SHAFT_PASSES):
        result.checks, result.sections = list(checks), dict(sections)
        mesh = _contact_pass(case, pair, result)
        distribution = result.sections.get("load_distribution")
        if not pair.shafts or distribution is None:
            break
        face = np.asarray(distribution["face_mm"])
        found = np.mean(distribution["line_load_N_per_mm"], axis=0)
        loaded = gear_pair(case, (face, found))
        changes.append(max(float(np.max(np.abs(loaded.shafts[name].total - shaft.total)))
                           for name, shaft in pair.shafts.items()))
        if changes[-1] <= SHAFT_TOLERANCE or attempt == SHAFT_PASSES - 1:
            break
        before = np.full(face.shape, found.mean()) if applied is None else applied
        applied = before + SHAFT_RELAXATION * (found - before)
        pair = gear_pair(case, (face, applied))
    gear_material = case.gear_material or case.material
    contact.subsurface_sections(result, case.analysis.subsurface,
                                (case.material.nu, gear_material.nu))
    rating.root_sections(case, pair, result)
    rating.iso_rating_sections(case, pair, result)
    if case.operation is not None:
        lubrication.lubrication_sections(case, lubrication.spur_running(case, pair), mesh,
                                         result)
    if case.analysis.positions_check:
        contact.check_positions(result, case.analysis.positions,
                         lambda scratch, at: _loaded_pass(contact.refining_case(case), pair,
                                                           scratch, at))
    if not pair.shafts or not changes:
        return
    result.sections["shaft"]["passes"] = len(changes)
    result.sections["shaft"]["changes_um"] = [1e3 * c for c in changes]
    result.checks.append(Check(
        "shaft deflection settled with the loaded line load", changes[-1] <= SHAFT_TOLERANCE,
        f"{len(changes)} pass(es); the shafts' deflection under the loaded line load differs "
        f"by {1e3 * changes[-1]:.2f} µm from the one analysed (settled below "
        f"{1e3 * SHAFT_TOLERANCE:g} µm)"))


#: the recommended tip relief's amount over the mesh's largest loaded approach: the relief
#: must clear the deflected tip with some to spare, as the relieved mesh shares its load
#: over fewer pairs near the tips and deflects a little more
RELIEF_MARGIN = 1.2


def _recommended_tip_relief(pair, result: Result) -> None:
    """summary recommended_tip_relief: per member of an external pair, the linear tip relief
    that keeps its tip off the mate under this load (Sigg's long relief, as ISO/TR 6336-30
    and ISO 6336-1's C_a take it: the amount the loaded teeth deflect, here the mesh's
    largest loaded approach D - s over the cycle along the contact normal (D a position's
    common approach, s its least unloaded separation) times RELIEF_MARGIN, transverse (over
    cos β_b); starting where the double contact at that tip begins: the pinion's at its
    highest point of single contact D = A + p_b, the gear's at the pinion's lowest, B =
    E - p_b), and the case lines that apply it."""
    rows, loaded = result.cycle.rows, result.loaded
    if loaded is None or pair.internal:
        return
    closing = []
    for roll in {r["roll_deg"] for r in rows}:
        ks = [k for k, r in enumerate(rows) if r["roll_deg"] == roll]
        solved = [k for k in ks if loaded[k] is not None]
        if solved:
            lead = max(solved, key=lambda k: loaded[k].solution.load_N)
            closing.append(loaded[lead].solution.approach_mm
                           - min(rows[k]["separation_mm"] for k in ks))
    if not closing:
        return
    amount = RELIEF_MARGIN * max(closing) / math.cos(pair.pinion.base_helix_angle)
    mesh = pair.transverse_mesh()
    path = pair.center_distance * math.sin(pair.working_pressure_angle)
    starts = {"pinion": math.hypot(pair.pinion.base_radius,
                                   mesh.start_of_contact + mesh.base_pitch),
              "gear": math.hypot(pair.gear.base_radius,
                                 path - (mesh.end_of_contact - mesh.base_pitch))}
    relief = {name: {"amount_um": round(1e3 * amount, 1),
                     "start_diameter_mm": round(2.0 * radius, 3)}
              for name, radius in starts.items()}
    summary = result.sections["summary"]
    summary["recommended_tip_relief"] = relief
    summary["recommended_tip_relief_case"] = "\n".join(
        f"[{name}.tip_relief]\namount = \"{r['amount_um']:g} um\"\n"
        f"start_diameter = \"{r['start_diameter_mm']:g} mm\"\nshape = \"linear\""
        for name, r in relief.items())
    summary["recommended_tip_relief_note"] = (
        "linear tip relief that keeps each tip off its mate under this load: the amount the "
        f"loaded mesh deflects (its largest approach over the cycle, {1e3 * max(closing):.1f} "
        f"µm along the contact normal) times {RELIEF_MARGIN:g}, transverse; from where the "
        "double contact at that tip begins (Sigg's long relief: the pinion's highest and "
        "lowest points of single contact); the blend at its start as the case's default")


def _tip_edge_note(case: schema.SpurCase, pair) -> str:
    """The tip edges and end chamfers as analysed: each member's rounding or chamfer, and
    where it is the default."""
    from ..member_modifications import DEFAULT_TIP_EDGE_MODULES

    parts = []
    for name, mods in (("pinion", pair.pinion_modifications), ("gear", pair.gear_modifications)):
        edge, spec = mods.tip_edge, getattr(case, name).tip_edge
        if edge is None:
            text = "sharp"
        elif edge.angle is None:
            text = f"rounded {edge.radius:.3g} mm"
        else:
            text = (f"chamfered {spec.chamfer:.3g} mm at {math.degrees(edge.angle):.3g} deg, "
                    f"its edge rounded {edge.radius:.3g} mm")
        parts.append(f"{name} {text}" + ("" if spec is not None else " (default)"))
        chamfer = mods.end_chamfer
        if chamfer is not None:
            parts.append(f"{name} face ends chamfered {chamfer.length:.3g} mm at "
                         f"{math.degrees(chamfer.angle):.3g} deg, their edges rounded "
                         f"{chamfer.radius:.3g} mm (the edge pressure there resolved from "
                         "pressure_grid 256)")
    return ("tip edges: " + ", ".join(parts) + f"; the default is {DEFAULT_TIP_EDGE_MODULES:g} "
            "normal modules, or the largest rounding that fits the tooth ([member.tip_edge] "
            "radius; '0 mm' for a sharp edge)")


def _contact_pass(case: schema.SpurCase, pair, result: Result):
    """One analysis of the contact (cycle, loaded contact, load distribution, interference)
    with the pair's deflection as it stands; the mesh that placed it."""
    mesh, cycle = _loaded_pass(case, pair, result)
    if pair.shafts:
        _shaft_sections(pair, result)
    _load_distribution(pair, result)
    _recommended_tip_relief(pair, result)
    if case.analysis.interference:
        _spur_interference(mesh, pair, cycle, result)
    return mesh


def _loaded_pass(case: schema.SpurCase, pair, result: Result,
                 at: tuple[float, ...] | None = None):
    """The contact cycle and its loaded contact (at the places `at`, in steps of the
    positions' spacing; None: the case's positions) into `result`; the mesh and the
    cycle."""
    mesh, cycle, (wt, normal_load, C_E) = contact_cycle(case, pair, at)
    contact.contact_sections(cycle, {"tangential_load_N": wt, "normal_load_N": normal_load}, result,
                      (pair.gear.base_radius, "gear's base circle (along the transverse line "
                                              "of action)"))
    from ..contact.compliance import PairCompliance, tooth_compliance

    gear_material = case.gear_material or case.material
    a = case.analysis
    teeth = PairCompliance(tooth_compliance(pair.pinion, case.material.E, case.material.nu),
                           tooth_compliance(pair.gear, gear_material.E, gear_material.nu),
                           bodies=True)
    contact.loaded_sections(cycle, C_E, a.pressure_grid, teeth,
                     "tooth bending from each member's exact transverse slices (bending, shear, "
                     "axial and gear body compliance, solid blanks with a bore of half the root "
                     "diameter" + ("; the ring gear's body as an external gear's of its root "
                                   "circle" if pair.gear.internal else "") + ", corrected to 3D finite "
                     "elements of the whole gear) coupled along the face as a Pasternak line "
                     "(contact.compliance), solved with the contact in one system; the teeth of "
                     "different pairs coupled through the " + ("pinion's body" if pair.gear.internal
                                                                else "gear bodies")
                     + " (a rim held at that bore, as thick as the face: in plane stress, "
                     "and bending out of its plane as a Mindlin plate under the loads' axial "
                     "part and their face positions, the tooth's own chord too: "
                     "analytic.gear_body)" + ("; each helical tooth shearing along its face as "
                                              "a wall under its loads' axial part (plane "
                                              "stress, held at the root circle: "
                                              "analytic.tooth_wall)"
                                              if pair.pinion.twist_per_length else ""),
                     result)
    return mesh, cycle


def contact_cycle(case: schema.SpurCase, pair, at: tuple[float, ...] | None = None):
    """The pair's contact cycle under the case's load and misalignment (at the places `at`,
    in steps of the positions' spacing; None: the case's positions), with the tooth pairs
    the loaded contact may bring in: the mesh, the cycle and (tangential load N, normal
    load N, the pair's Hertz compliance C_E)."""
    from ..contact.cycle import parallel_cycle
    from ..gearset import working_flank
    from ..surfaces.placement import Misalignment

    m = case.misalignment
    mesh = pair.placed(Misalignment(m.slope, m.slope_normal, m.center_distance_error,
                                           m.axial_shift))

    pinion = working_flank(pair.pinion, pair.pinion_loaded_modifications, 1)
    gear = working_flank(pair.gear, pair.gear_modifications, mesh.gear_side)
    wt = case.load.tangential_load or case.load.torque / pair.operating_pitch_radius
    normal_load = wt / (math.cos(pair.working_pressure_angle) * math.cos(pair.pinion.base_helix_angle))
    gear_material = case.gear_material or case.material
    C_E = hertz.compliance(case.material.E, case.material.nu, gear_material.E, gear_material.nu)
    a = case.analysis
    reach = (_loaded_reach(pair, normal_load, case.material.E, gear_material.E)
             if a.pressure_grid else 0.0)
    try:
        cycle = parallel_cycle(mesh, pinion, gear, normal_load, C_E,
                              contact.cycle_settings(a, at, reach=reach))
    except (ValueError, RuntimeError) as exc:
        raise CaseError(f"misalignment / load: no contact could be found: {exc}") from None
    return mesh, cycle, (wt, normal_load, C_E)


#: the separation (as a multiple of ISO's single-pair approach under the whole load) up
#: to which a pair is kept for the loaded contact: the tooth pairs a loaded mesh may bring in
LOADED_REACH = 3.0


def _loaded_reach(pair, normal_load: float, E_pinion: float, E_gear: float) -> float:
    """The separation (mm) within which tooth pairs are candidates for the loaded contact:
    LOADED_REACH times the normal approach of one pair carrying the whole normal load with
    ISO 6336-1's single stiffness c' (Method B, scaled by E/E_steel as ISO does):
    F_n·cos²β_b/(b·c')."""
    from ..analytic.stiffness import E_STEEL

    p = pair.pinion
    c = single_stiffness(p.teeth, -pair.gear.teeth if pair.gear.internal else pair.gear.teeth,
                         p.profile_shift, pair.gear.profile_shift, p.helix_angle,
                         p.pressure_angle, p.dedendum)
    c *= 2.0 * E_pinion * E_gear / (E_pinion + E_gear) / E_STEEL
    width = min(pair.pinion.face_width, pair.gear.face_width)
    approach_um = normal_load * math.cos(pair.pinion.base_helix_angle) ** 2 / (width * c)
    return LOADED_REACH * approach_um * 1e-3


def _shaft_sections(pair, result: Result) -> None:
    """The shafts' deflections over the face (shaft.py; already in the pinion's deflection
    the contact used): per member the displacement of its flank toward the mate from
    bending and from torsion, relative to mid-face, and in the summary their slopes summed
    over the members (positive closing end B, like misalignment.slope)."""
    result.sections["shaft"] = {
        name: {"face_mm": s.face.round(4).tolist(),
               "bending_um": (s.bending * 1e3).round(4).tolist(),
               "torsion_um": (s.torsion * 1e3).round(4).tolist(),
               "bending_slope_rad": s.bending_slope, "torsion_slope_rad": s.torsion_slope}
        for name, s in pair.shafts.items()}
    result.sections["summary"].update(
        shaft_bending_slope_rad=sum(s.bending_slope for s in pair.shafts.values()),
        shaft_torsion_slope_rad=sum(s.torsion_slope for s in pair.shafts.values()),
        shaft_note="the shafts' bending between their bearings and the bodies' twist over the "
                   "face under the mesh force, toward the mate along the line of action, "
                   "relative to mid-face; added to the pinion's deflection before the contact "
                   "is searched: first with the force spread evenly over the face, then "
                   "(passes) as the loaded contact's mean line load over the cycle spreads it, "
                   "until the deflection changes by less than "
                   f"{1e3 * SHAFT_TOLERANCE:g} µm (changes_um: after each pass, the "
                   "largest change the loaded line load makes)")


#: a collision point counts as interference when it lies this close (mm) to a member's tip
#: or root circle, or beyond them; between them, on the involute flanks, it is the contact
#: (working flanks) or the backlash used up (back flanks)
INTERFERENCE_BAND = 0.05


#: chordal tolerance (mm) of the meshes the bodies are collided as: a fifth of the band
INTERFERENCE_MESH = 0.01


@functools.lru_cache(maxsize=16)
def _collision_teeth(gear, modifications, teeth: int):
    """A member's `teeth` tooth surfaces as a collision body (chords within
    INTERFERENCE_MESH) and its band of working radii (form to tip circle, mm): built once
    per process for the same teeth (a sweep's worker reuses them; each query places the
    body afresh)."""
    from ..mesh import collision_body, gear_mesh
    from ..surfaces.outline import ToothOutline

    outline = ToothOutline(gear, modifications)
    return (collision_body(*gear_mesh(outline, teeth, INTERFERENCE_MESH)),
            tuple(sorted((outline.generated.form_radius, gear.tip_radius))))


def _spur_interference(mesh, pair, cycle, result: Result) -> None:
    """Tip and root interference of the placed bodies (python-fcl) at every mesh position:
    tooth surfaces (mesh.gear_mesh, chords within INTERFERENCE_MESH) of the teeth in contact
    over the cycle and one more on each side (a tooth entering mesh), their BVHs built once
    and placed at each position (_collision_teeth)."""
    from ..mesh import interference, place

    rows = cycle.rows
    reach = max(abs(r["pair"]) for r in rows) + 1     # the teeth in contact, and one more
    bodies, bands = {}, {}
    for name, gear, mods in (("pinion", pair.pinion, pair.pinion_modifications),
                             ("gear", pair.gear, pair.gear_modifications)):
        bodies[name], bands[name] = _collision_teeth(gear, mods, 2 * reach + 1)
    found, back = [], []
    for roll in sorted({r["roll_deg"] for r in rows}):
        lag = next(float(cycle.gear_turn[k]) for k, r in enumerate(rows) if r["roll_deg"] == roll)
        phi = math.radians(roll)
        frames = {"pinion": mesh.pinion_frame(phi), "gear": mesh.gear_frame(phi, 0, lag)}
        hit = interference(*(place(bodies[n], frames[n].R, frames[n].origin)
                             for n in ("pinion", "gear")))
        if not hit.found:
            continue
        on_flanks = np.ones(len(hit.points), bool)
        for name, frame in frames.items():
            r = np.hypot(*frame.to_local(hit.points)[:, :2].T)
            lo, hi = bands[name]
            on_flanks &= (r > lo + INTERFERENCE_BAND) & (r < hi - INTERFERENCE_BAND)
        if not on_flanks.all():
            found.append({"roll_deg": roll,
                          "points_mm": hit.points[~on_flanks][:5].round(4).tolist()})
        coast = on_flanks & (_pinion_side(frames["pinion"], pair.pinion, hit.points) < 0)
        if coast.any():
            back.append({"roll_deg": roll, "points_mm": hit.points[coast][:5].round(4).tolist()})
    result.sections["interference"] = {
        "checked_positions": len({r["roll_deg"] for r in rows}), "band_mm": INTERFERENCE_BAND,
        "found": found, "back_flanks": back}
    backlash = f"the normal backlash {round(pair.normal_backlash * 1e3, 1) + 0.0:g} µm"
    result.checks.append(Check("no tip or root interference of the bodies", not found,
                               f"{len(found)} positions with interference"
                               + (f", first at roll {found[0]['roll_deg']:.2f} deg near "
                                  f"{found[0]['points_mm'][0]} mm" if found else "")
                               + (f"; the back flanks touch too ({backlash} is used up): the "
                                  "tips run into the mates' back flanks" if found and back
                                  else "")))
    result.checks.append(Check(
        "backlash left under the misalignment (the back flanks clear)", not back,
        (f"the back flanks touch at {len(back)} positions, first at roll "
         f"{back[0]['roll_deg']:.2f} deg near {back[0]['points_mm'][0]} mm: {backlash} is used "
         "up (case field backlash)") if back else f"{backlash} clears at every position"))


def _pinion_side(frame, pinion, points: np.ndarray) -> np.ndarray:
    """+1 where a world point lies on the working (+1) half of its nearest pinion tooth or
    the space beside it, -1 on the coast half."""
    local = frame.to_local(points)
    angle = np.arctan2(local[:, 1], local[:, 0]) - pinion.twist_per_length * local[:, 2]
    pitch = 2.0 * math.pi / pinion.teeth
    return np.where((angle + 0.5 * pitch) % pitch - 0.5 * pitch >= 0.0, 1, -1)


#: strips across the face the line loads of a position are summed on: the load
#: distribution at the scale of the face. They leave out the EDGE_STRIP at each face end:
#: a sharp end's pressure peak there is the edge pressure's business, not K_H_beta's
FACE_STRIPS = 20


def _load_distribution(pair, result: Result) -> None:
    """The mesh's load along the face from the loaded contacts (their line loads, all pairs
    of a position summed on one face grid of the pinion) and what follows from it, beside
    ISO 6336-1's figures for the same pair:
    - load_distribution: face_mm, and per position roll_deg, line_load_N_per_mm, K_H_beta
      (that position's largest line load over W/b), and mean_line_load_N_per_mm (the
      line load averaged over the mesh cycle's positions);
    - summary: K_H_beta, ISO 6336-1's face load factor by Method A: the largest over the
      face of the line load averaged over the mesh cycle, over the mean W/b (b the common
      face width); the contact lines' sweep across the face within the cycle, which ISO
      assigns to K_H_alpha, averages out; K_H_beta_instantaneous, the largest over the cycle
      of a position's largest line load over W/b, beside it;
      mesh_stiffness_N_per_mm_um, the mean over the cycle of W/(D - s_min)/b·cos²β_b (D the
      position's loaded approach, s_min its least unloaded separation; the cos²β_b makes it
      ISO's transverse force over transverse deflection), the model's counterpart of c_γα;
      single_stiffness_N_per_mm_um, the largest of it at positions with one loaded pair
      (c'). ISO's c', c_γα and Method C's K_Hβ are the rating's (rating.iso6336).
    Nothing is added when no position was solved (or the loaded contact was not asked for)."""
    cycle, loaded = result.cycle, result.loaded
    if loaded is None:
        return
    rows = cycle.rows
    positions: dict[float, list[int]] = {}
    for k, row in enumerate(rows):
        positions.setdefault(row["roll_deg"], []).append(k)
    width = min(pair.pinion.face_width, pair.gear.face_width)
    transverse = math.cos(pair.pinion.base_helix_angle) ** 2
    from ..contact.edge_loads import EDGE_STRIP

    end = 0.5 * pair.pinion.face_width - EDGE_STRIP
    edges = np.linspace(-end, end, FACE_STRIPS + 1)
    rolls, lines, loads, factors, stiffness, single = [], [], [], [], [], []
    per_position = []
    for roll, ks in positions.items():
        solved = [k for k in ks if loaded[k] is not None]
        if not solved or any(rows[k]["bem_status"] == "failed" for k in ks):
            continue
        line = sum(loaded[k].line_load(edges) for k in solved)
        load = sum(loaded[k].solution.load_N for k in solved)
        rolls.append(roll)
        lines.append(line)
        loads.append(load)
        factors.append(float(line.max() / (load / width)))
        lead = max(solved, key=lambda k: loaded[k].solution.load_N)
        closing = loaded[lead].solution.approach_mm - min(rows[k]["separation_mm"] for k in ks)
        per_position.append(None)
        if closing > 0:     # ISO's c: the transverse force over the transverse deflection
            stiffness.append(load / closing / width * 1e-3 * transverse)
            per_position[-1] = stiffness[-1]
            if len(solved) == 1:
                single.append(stiffness[-1])
    if not rolls:
        return
    # the positions divide one mesh cycle evenly: their mean is the cycle's mean
    mean_line = np.mean(lines, axis=0)
    result.sections["load_distribution"] = {
        "face_mm": (0.5 * (edges[1:] + edges[:-1])).round(4).tolist(), "roll_deg": rolls,
        "line_load_N_per_mm": [line.round(3).tolist() for line in lines],
        "mean_line_load_N_per_mm": mean_line.round(3).tolist(),
        "K_H_beta": factors,
        "mesh_stiffness_N_per_mm_um": per_position,
        "note": f"line loads along the pinion's face (N/mm of face, along the contact normal) "
                f"on {FACE_STRIPS} strips between {EDGE_STRIP} mm from each face end (the edge "
                "pressure covers those), face_mm their centres, all tooth pairs of a position "
                f"summed; K_H_beta is the largest over the mean W/b on b = {width:g} mm, "
                "at each position; mean_line_load_N_per_mm their mean over the cycle; "
                "mesh_stiffness_N_per_mm_um the position's secant mesh stiffness (see the "
                "summary's stiffness_note)"}
    result.sections["summary"].update(
        K_H_beta=float(mean_line.max() / (np.mean(loads) / width)),
        K_H_beta_instantaneous=max(factors),
        mesh_stiffness_N_per_mm_um=float(np.mean(stiffness)) if stiffness else None,
        single_stiffness_N_per_mm_um=max(single) if single else None,
        stiffness_note="mesh_stiffness_N_per_mm_um is the model's mean secant stiffness over "
                       "the cycle per mm of face (ISO's c_γα counterpart), "
                       "single_stiffness_N_per_mm_um its largest with one pair in contact "
                       "(c'); iso_* are ISO 6336-1 Method B for solid blanks; K_H_beta is "
                       "ISO 6336-1 Method A (the cycle's largest over mean line load), "
                       "K_H_beta_instantaneous the worst single position's, K_H_beta_iso_C "
                       "ISO's Method C for the case's misalignment and deflection with ISO's "
                       "own c_γβ (the rating's section)")
