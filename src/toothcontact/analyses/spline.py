"""The spline kind: an involute spline's geometry and every tooth's contact under an
angular misalignment."""

from __future__ import annotations

import math

from .. import case as schema
from ..analytic import hertz
from ..case import CaseError
from . import contact
from .result import Check, Result


def spline_geometry_case(case: schema.SplineCase) -> Result:
    """Geometry of an involute spline: diameters, the members' shifts, the hub's form circle
    and crown, and the eq 19 crown limit for the clearance."""
    from .. import gearset
    from ..surfaces.generation import generate_side

    try:
        pair = gearset.spline_pair(case)
    except ValueError as exc:
        raise CaseError(str(exc)) from None
    spline, hub, sleeve = pair.spline, pair.hub, pair.sleeve
    generated = generate_side(hub)
    section = {f"{k}_diameter_mm": v for k, v in spline.diameters.items()}
    section.update(pitch_diameter_mm=spline.pitch_diameter, base_diameter_mm=2 * hub.base_radius,
                   hub_profile_shift=hub.profile_shift, sleeve_profile_shift=sleeve.profile_shift,
                   hub_form_diameter_mm=2 * generated.form_radius,
                   normal_clearance_per_side_mm=0.5 * case.clearance * math.cos(case.pressure_angle))
    result = Result(sections={"spline": section}, parts=pair)
    result.checks.append(Check("hub is not undercut", not generated.undercut,
                               f"form diameter {2 * generated.form_radius:.4f} mm"))
    result.checks.append(Check("hub form circle below the sleeve's minor diameter",
                               2 * generated.form_radius < spline.diameters["sleeve_minor"],
                               f"form {2 * generated.form_radius:.4f} mm, sleeve minor "
                               f"{spline.diameters['sleeve_minor']:.4f} mm"))
    if case.crown is not None:
        crown = pair.hub_modifications.lead_crown
        radius = crown.radius_for(case.engaged_length) * math.cos(case.pressure_angle)
        section["crown_radius_mm"] = radius
        section["crown_height_mm"] = float(crown.drop(0.5 * case.engaged_length, case.engaged_length)
                                           / math.cos(case.pressure_angle))
    if case.torque is not None:
        _spline_contact(case, pair, result)
        contact.subsurface_sections(result, case.analysis.subsurface, (case.material.nu,) * 2)
        if case.analysis.positions_check:
            contact.check_positions(result, case.analysis.positions,
                             lambda scratch, at: _spline_contact(contact.refining_case(case),
                                                                 pair, scratch, at))
    return result


def _spline_contact(case: schema.SplineCase, pair, result: Result,
                    at: tuple[float, ...] | None = None) -> None:
    """Every tooth of the spline under the angular misalignment: a coaxial pair of ratio 1
    (surfaces.placement.ParallelMesh with zero centre distance), the sleeve tilted about the normal of
    tooth 0's plane of action; the lag closes the clearance."""
    from ..contact.cycle import parallel_cycle
    from ..gearset import GearPair, working_flank
    from ..surfaces.placement import Misalignment

    coaxial = GearPair(pair.hub, pair.sleeve, pair.hub_modifications, pair.sleeve_modifications,
                       0.0, case.pressure_angle)
    mesh = coaxial.placed(Misalignment(slope=case.misalignment))
    hub = working_flank(pair.hub, pair.hub_modifications, 1)
    sleeve = working_flank(pair.sleeve, pair.sleeve_modifications, mesh.gear_side)
    wt = case.torque / (0.5 * pair.spline.pitch_diameter)
    normal_load = wt / math.cos(case.pressure_angle)
    C_E = hertz.compliance(case.material.E, case.material.nu, case.material.E, case.material.nu)
    a = case.analysis
    try:
        cycle = parallel_cycle(mesh, hub, sleeve, normal_load, C_E,
                              contact.cycle_settings(a, at, pairs=tuple(range(case.teeth))))
    except (ValueError, RuntimeError) as exc:
        raise CaseError(f"misalignment / torque: no contact could be found: {exc}") from None
    contact.contact_sections(cycle, {"tangential_load_N": wt, "normal_load_N": normal_load}, result,
                      (pair.hub.base_radius, "hub's base circle"))
    from ..contact.compliance import PairCompliance, tooth_compliance

    teeth = PairCompliance(tooth_compliance(pair.hub, case.material.E, case.material.nu),
                           tooth_compliance(pair.sleeve, case.material.E, case.material.nu))
    contact.loaded_sections(cycle, C_E, a.pressure_grid, teeth,
                     "tooth bending from the hub's and sleeve's exact transverse slices "
                     "(bending, shear, axial and body compliance across the working depth: a "
                     "load at one height bends the whole tooth; the hub a solid shaft with a "
                     "bore of half its root diameter, the sleeve's body as an external gear's "
                     "of its root circle; corrected to 3D finite elements of a gear) coupled "
                     "along the engaged length as a Pasternak "
                     "line (contact.compliance), solved with the contact in one system", result)
    tooth_loads(cycle.rows, case.teeth, result.sections["summary"])


def tooth_loads(rows: list[dict], teeth: int, summary: dict) -> None:
    """How the load spreads over a spline's teeth, per position (summary["tooth_loads"]: the
    teeth in contact, the largest and the mean tooth load over all `teeth`) and its worst
    (summary["tooth_load_factor"]: the largest tooth load over the mean, a local figure
    like the load distribution factor K_γ of spline design practice, not ISO's); None
    where a position's loaded contact was not solved."""
    by_roll: dict[float, list[float | None]] = {}
    for r in rows:
        by_roll.setdefault(r["roll_deg"], []).append(r.get("bem_load_N"))
    table = []
    for roll, loads in sorted(by_roll.items()):
        if any(v is None for v in loads) or not sum(loads) > 0.0:
            table.append({"roll_deg": roll, "teeth_in_contact": None,
                          "largest_tooth_load_N": None, "mean_tooth_load_N": None,
                          "tooth_load_factor": None})
            continue
        mean = sum(loads) / teeth
        table.append({"roll_deg": roll, "teeth_in_contact": sum(v > 0.0 for v in loads),
                      "largest_tooth_load_N": max(loads), "mean_tooth_load_N": mean,
                      "tooth_load_factor": max(loads) / mean})
    summary["tooth_loads"] = table
    factors = [row["tooth_load_factor"] for row in table]
    summary["tooth_load_factor"] = None if None in factors or not factors else max(factors)
