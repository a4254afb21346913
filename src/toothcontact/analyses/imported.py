"""The imported kind: contact over the mesh cycle on the user's STL/STEP bodies."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np

from .. import case as schema
from ..analytic import hertz
from ..case import CaseError
from . import contact
from .result import Result


def imported_case(case: schema.ImportedCase) -> Result:
    """A pair from the user's STL/STEP bodies: contact over the mesh cycle on the meshes
    (contact.imported). Reads the two body files (named and checked by the case)."""
    from ..contact.imported import chordal_error, imported_cycle, teeth_per_turn
    from ..mesh import load_surface
    from ..surfaces.placement import Misalignment, ParallelMesh

    bodies = {}
    for name in ("pinion", "gear"):
        spec = getattr(case, name)
        try:
            bodies[name] = load_surface(spec.file, case.step_tolerance)
        except ValueError as exc:
            raise CaseError(f"{name}.file: {exc}") from None
        found = teeth_per_turn(bodies[name])
        if not abs(found - spec.teeth) < 0.25:
            seen = (f"its tooth tips are {360.0 / found:.3f} deg apart ({found:.2f} teeth a "
                    "turn)" if math.isfinite(found) else "it shows fewer than two tooth tips "
                    "about its z axis")
            raise CaseError(f"{name}.teeth: {spec.teeth}, but {Path(spec.file).name} is no "
                            f"gear of {spec.teeth} teeth about its z axis: {seen}; give the "
                            "body's tooth count, and a file whose z axis is the gear's axis")
    tips = {name: float(np.hypot(body.vertices[:, 0], body.vertices[:, 1]).max())
            for name, body in bodies.items()}
    if not max(tips.values()) < case.center_distance < sum(tips.values()):
        raise CaseError(f"center_distance: {case.center_distance:.4g} mm: the bodies' tip radii "
                        f"are {tips['pinion']:.4g} and {tips['gear']:.4g} mm, so their teeth "
                        f"can only mesh between {max(tips.values()):.4g} and "
                        f"{sum(tips.values()):.4g} mm")
    if case.pinion_phase:
        bodies["pinion"] = bodies["pinion"].turned(case.pinion_phase)
    z1, z2 = case.pinion.teeth, case.gear.teeth
    m = case.misalignment
    mesh = ParallelMesh(z1, z2, case.center_distance, case.pressure_angle,
                        Misalignment(m.slope, m.slope_normal, m.center_distance_error,
                                     m.axial_shift), gear_start=case.gear_phase)
    pitch_radius = case.center_distance * z1 / (z1 + z2)
    wt = case.load.tangential_load or case.load.torque / pitch_radius
    normal_load = wt / (math.cos(case.pressure_angle) * math.cos(case.base_helix_angle))
    gear_material = case.gear_material or case.material
    C_E = hertz.compliance(case.material.E, case.material.nu, gear_material.E, gear_material.nu)
    a = case.analysis
    try:
        rows = imported_cycle(mesh, bodies["pinion"], bodies["gear"], normal_load, C_E,
                              contact.cycle_settings(a), tuple(None if b.form_diameter is None else
                                                        0.5 * b.form_diameter
                                                        for b in (case.pinion, case.gear)))
    except ValueError as exc:
        raise CaseError(f"pinion / gear: no contact could be found: {exc}") from None
    chordal = {name: chordal_error(body) for name, body in bodies.items()}
    result = Result(sections={"bodies": {
        name: {"file": getattr(case, name).file, "teeth": getattr(case, name).teeth,
               "triangles": len(body.faces), "chordal_error_um": 1e3 * chordal[name],
               "watertight": bool(body.mesh.is_watertight)}
        for name, body in bodies.items()}})
    unchecked = [name for name in ("pinion", "gear") if getattr(case, name).form_diameter is None]
    result.notes.append("imported bodies: contact on the smooth surfaces the facets stand for "
                        "(Phong tessellation through normals fitted to the facets), by transverse "
                        "sections of the pinion's driving flanks; tips at each body's largest "
                        "radius" + (f"; form edge not checked for the {' and '.join(unchecked)} "
                                    "(give form_diameter)" if unchecked else ""))
    # what the facets allow: their chordal errors as a turn of the gear at its base radius
    base_radius = case.center_distance * z2 / (z1 + z2) * math.cos(case.pressure_angle)
    contact.contact_sections(rows, {"tangential_load_N": wt, "normal_load_N": normal_load}, result,
                      (base_radius, "gear's base circle (along the transverse line of action)"))
    result.sections["summary"]["transmission_error_facet_bound_urad"] = \
        1e6 * (chordal["pinion"] + chordal["gear"]) / base_radius
    return result
