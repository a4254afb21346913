"""The lubricated contact of a gear pair or worm set ([operation], [lubricant]): at every
contact the sliding and rolling of the exact flanks as the mesh places them
(contact.kinematics), the oil film (analytic.ehl) against the roughness, the friction, the
flash temperature of the solved pressure (contact.flash) and the power lost; over the
cycle the mesh loss and efficiency, the scuffing and micropitting safeties."""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from .result import Check, Result

#: the columns of a contact line whose line load is below this share of its largest are
#: left out of its film (its ends, where the film grows)
FILM_LOAD_SHARE = 0.05
#: ISO/TS 6336-20's bulk temperature θ_M = θ_oil + BULK_FACTOR·X_S·X_mp·θ_fl,mean (one mesh:
#: X_mp = 1), X_S by how the mesh is lubricated
BULK_FACTOR = 0.47
LUBRICATION_FACTOR = {"splash": 1.2, "spray": 1.0}
#: the ellipticity k = a/b up to which Hamrock & Dowson solved the point contact's film
#: (their formulae's range); a longer ellipse's film is a line contact's, column by column
POINT_FILM_ELLIPTICITY = 8.0
#: the per-contact keys (None where the contact has no loaded solution)
#: an S_B above this is "not limiting" (reported as none, with a note): the contact
#: temperature rises above the oil by less than 1/S_B_NOT_LIMITING of the scuffing margin,
#: so that S_B, which tends to infinity as the flash temperature tends to zero, stays a
#: finite figure of meaning
S_B_NOT_LIMITING = 100.0
LOADED_KEYS = ("friction_coefficient", "film_thickness_central_um", "film_thickness_min_um",
               "lambda", "flash_temperature_K", "contact_temperature_degC", "power_loss_W")


@dataclass(frozen=True)
class LubricatedPair:
    """What the lubricated contact needs of a pair beside its contact: the members' names in
    the results (driver, driven), the driver's speed (rpm), each member's roughness Ra (mm)
    and material (E, ν, thermal_contact_coefficient), the power the mesh passes (W) and
    whether it is the mesh's input (a gear pair's pinion torque) or its output (a worm
    set's wheel torque) and whether ISO/TS 6336-20's bulk temperature estimate applies."""

    names: tuple[str, str]
    speed: float
    roughness: tuple[float, float]
    materials: tuple
    power: float
    input_power: bool
    iso_bulk: bool
    #: the sum of the flanks' tangential speeds at the pitch point (m/s), where ISO/TR
    #: 14179-2's μ may be computed (None: a mesh whose μ is given)
    pitch_sum_velocity: float | None = None


def lubrication_sections(case, running: LubricatedPair, mesh, result: Result) -> None:
    """The lubricated contact's keys on every row, the `lubrication` section (the oil at
    temperature) and the summary's lambda_min, flash_temperature_max_K, mesh_power_loss_W,
    mesh_efficiency and the safeties S_B, S_lambda where their limits are given."""
    if case.operation is None or result.cycle is None:
        return
    from ..analytic import ehl, lubricant
    from ..contact.flash import STEEL_CONTACT_COEFFICIENT
    from ..contact.kinematics import contact_motion

    op, oil = case.operation, case.lubricant
    family = lubricant.FAMILIES[oil.family]
    density_15 = oil.density or family.density_15
    nu = lubricant.kinematic_viscosity(oil.viscosity_40, oil.viscosity_100, op.oil_temperature)
    eta = lubricant.dynamic_viscosity(oil.viscosity_40, oil.viscosity_100, density_15,
                                      op.oil_temperature)
    first, second = running.materials
    fluid = _Fluid(eta=eta, alpha=oil.pressure_viscosity or family.pressure_viscosity,
                   E_reduced=ehl.reduced_modulus(first.E, first.nu, second.E, second.nu),
                   roughness_um=0.5e3 * sum(running.roughness), X_L=family.X_L,
                   friction=oil.friction_coefficient,
                   thermal=tuple(m.thermal_contact_coefficient or STEEL_CONTACT_COEFFICIENT
                                 for m in running.materials))
    cycle = result.cycle
    motion = contact_motion(mesh, cycle, running.speed)
    across = cycle.planes.direction(np.asarray(cycle.axis_angle, float) + 0.5 * math.pi)
    rows = result.sections["positions"]
    loaded = result.loaded or [None] * len(rows)
    for k, row in enumerate(rows):
        row.update(_kinematics(motion, k, running.names))
        if loaded[k] is None:
            known = row.get("bem_status") == "unloaded"
            row.update(dict.fromkeys(LOADED_KEYS), power_loss_W=0.0 if known else None)
            continue
        row.update(_lubricated(cycle, k, row, loaded[k], motion, across[k], fluid))
    _summary(case, running, result, fluid, nu, density_15)


def spur_running(case, pair) -> LubricatedPair:
    """A spur or helical pair's: the pinion drives at [operation] pinion_speed with the
    load's torque."""
    torque = (case.load.torque if case.load.torque is not None
              else case.load.tangential_load * pair.operating_pitch_radius)
    speed = case.operation.pinion_speed
    omega = speed * 2.0 * math.pi / 60.0
    return LubricatedPair(("pinion", "gear"), speed,
                          (case.pinion.roughness_Ra, case.gear.roughness_Ra),
                          (case.material, case.gear_material or case.material),
                          torque * 1e-3 * omega, True, True,
                          2.0 * omega * pair.operating_pitch_radius * 1e-3
                          * math.sin(pair.working_pressure_angle))


def check_friction_range(case, running: LubricatedPair) -> None:
    """Before the contact is solved: a CaseError where ISO/TR 14179-2's μ would be computed
    outside its range (the pitch point's sum speed below mesh_losses.SUM_VELOCITY_LEAST)
    and the case gives no friction_coefficient."""
    from ..analytic.mesh_losses import SUM_VELOCITY_LEAST
    from ..case import CaseError

    v = running.pitch_sum_velocity
    if case.lubricant.friction_coefficient is None and v is not None and v < SUM_VELOCITY_LEAST:
        raise CaseError(f"operation.{running.names[0]}_speed: {running.speed:.4g} rpm runs the "
                        f"flanks at a sum speed of {v:.3g} m/s at the pitch point, below the "
                        f"{SUM_VELOCITY_LEAST:g} m/s ISO/TR 14179-2's friction coefficient is "
                        "taken from here: give lubricant.friction_coefficient")


@dataclass(frozen=True)
class _Fluid:
    """The oil at its temperature and what the friction and film need of the pair: η
    (Pa·s), α (1/MPa), E' (MPa), the flanks' mean roughness (µm), X_L, a fixed μ and the
    flanks' thermal contact coefficients."""

    eta: float
    alpha: float
    E_reduced: float
    roughness_um: float
    X_L: float
    friction: float | None
    #: each member's sqrt(λρc), W·s^0.5/(m²·K)
    thermal: tuple[float, float]


def _kinematics(motion, k: int, names: tuple[str, str]) -> dict:
    """Sliding (|v1 - v2|), sum (|v1 + v2|) speeds (m/s) and each member's specific sliding
    (its slip over its own speed, along its own motion) at contact k's point."""
    v1, v2 = motion.at(k, motion.point[k])
    slide = v1 - v2
    out = {"sliding_velocity_m_per_s": float(np.linalg.norm(slide)),
           "sum_velocity_m_per_s": float(np.linalg.norm(v1 + v2))}
    for name, v, slip in zip(names, (v1, v2), (slide, -slide)):
        speed = float(v @ v)
        out[f"specific_sliding_{name}"] = float(slip @ v) / speed if speed > 0 else None
    return out


def _lubricated(cycle, k: int, row: dict, contact, motion, across: np.ndarray, fluid) -> dict:
    """Friction, film, flash temperature and power lost of one loaded contact, over its
    solved pressure cells (each cell's own sliding speed)."""
    from ..analytic import ehl
    from ..analytic.mesh_losses import friction_coefficient
    from ..contact.flash import flash_temperature

    s, field = contact.solution, contact.field
    planes = cycle.planes
    turn = field.turn
    axis = (math.cos(turn) * planes.e1[k] + math.sin(turn) * planes.e2[k],
            -math.sin(turn) * planes.e1[k] + math.cos(turn) * planes.e2[k])
    X, Y = np.meshgrid(field.x, field.y, indexing="ij")
    plane = motion.in_plane(k, axis)

    def surface(member: int):
        c = plane[member]
        return lambda xf, yf: (c[0, 0] + xf * c[1, 0] + yf * c[2, 0],
                               c[0, 1] + xf * c[1, 1] + yf * c[2, 1])

    (v1x, v1y), (v2x, v2y) = surface(0)(X, Y), surface(1)(X, Y)
    pressure = s.pressure_MPa
    sliding = np.hypot(v1x - v2x, v1y - v2y)
    column_load = pressure.sum(axis=1) * s.dy_mm                  # N/mm along the contact
    v1, v2 = motion.at(k, motion.point[k])
    if not row["B_analytic_per_mm"] > 0.0:
        # no relative radius across the contact (a flank turned onto an edge): neither
        # film nor ISO's μ holds there; a given μ still heats it
        if fluid.friction is None:
            return dict.fromkeys(LOADED_KEYS)
        radius = None
    else:
        radius = 0.5 / row["B_analytic_per_mm"]
    if fluid.friction is not None:
        mu = fluid.friction
    else:
        mu = friction_coefficient(float(column_load.max()), float(np.linalg.norm(v1 + v2)),
                                  radius, fluid.eta * 1e3, fluid.roughness_um, fluid.X_L)
        if not 0.0 < mu < 1.0:
            from ..case import CaseError

            raise CaseError(
                f"lubricant.friction_coefficient: ISO/TR 14179-2's μ comes out {mu:.3g} at "
                f"{_at(row)} (line load {float(column_load.max()):.4g} N/mm, sum speed "
                f"{float(np.linalg.norm(v1 + v2)):.3g} m/s, radius {radius:.4g} mm): outside "
                "(0, 1), its inputs beyond the formula's range; give the friction coefficient")
    power = mu * float(np.sum(pressure * sliding)) * s.dx_mm * s.dy_mm
    flux = mu * pressure * sliding * 1e6
    flash = flash_temperature(flux, field.x, field.y, ((surface(0), fluid.thermal[0]),
                                                      (surface(1), fluid.thermal[1])))
    entraining = 0.5 * ((v1x + v2x) * (across @ axis[0]) + (v1y + v2y) * (across @ axis[1]))
    heat = {"friction_coefficient": mu, "flash_temperature_K": flash, "power_loss_W": power}
    if radius is None:
        return {**heat, "film_thickness_central_um": None, "film_thickness_min_um": None,
                "lambda": None}
    if (row["contact_model"] == "ellipse" and row["A_analytic_per_mm"] > 0
            and row["a_mm"] <= POINT_FILM_ELLIPTICITY * row["b_mm"]):
        u = abs(float(0.5 * (v1 + v2) @ across))
        film = ehl.point_film(fluid.eta, u, radius, 0.5 / row["A_analytic_per_mm"],
                              s.load_N, fluid.E_reduced, fluid.alpha) if u > 0 else None
    else:
        film = _line_film(pressure, column_load, entraining, radius, fluid)
    minimum = 0.0 if film is None else film.minimum_um
    return {**heat, "film_thickness_central_um": 0.0 if film is None else film.central_um,
            "film_thickness_min_um": minimum, "lambda": minimum / fluid.roughness_um}


def _line_film(pressure, column_load, entraining, radius: float, fluid):
    """The thinnest film along a contact line: each column of the field across the line is
    a line contact of its own load per mm and its load-weighted entraining speed; None
    where the oil is not drawn in (no entraining speed)."""
    from ..analytic import ehl

    carrying = column_load >= FILM_LOAD_SHARE * column_load.max()
    weights = pressure[carrying]
    u = np.abs(np.sum(weights * entraining[carrying], axis=1) / weights.sum(axis=1))
    films = [ehl.line_film(fluid.eta, float(speed), radius, float(w), fluid.E_reduced,
                           fluid.alpha)
             for speed, w in zip(u, column_load[carrying]) if speed > 0]
    return min(films, key=lambda f: f.minimum_um) if films else None


def _summary(case, running: LubricatedPair, result: Result, fluid, nu: float,
             density_15: float) -> None:
    """Bulk and contact temperatures, the mesh loss and efficiency, the extremes and the
    safeties (with their design checks) into the summary and the lubrication section."""
    from ..analytic import lubricant

    op, oil = case.operation, case.lubricant
    rows = result.sections["positions"]
    summary = result.sections["summary"]
    solved = [r for r in rows if r["flash_temperature_K"] is not None]
    positions = sorted({r["roll_deg"] for r in rows})
    hottest = [max((r["flash_temperature_K"] for r in solved if r["roll_deg"] == roll),
                   default=0.0) for roll in positions]
    mean_flash = float(np.mean(hottest))
    estimate = (BULK_FACTOR * LUBRICATION_FACTOR[op.lubrication] * mean_flash
                if running.iso_bulk else 0.0)
    bulk = (op.bulk_temperature if op.bulk_temperature is not None
            else op.oil_temperature + estimate)
    for row in rows:
        flash = row["flash_temperature_K"]
        row["contact_temperature_degC"] = None if flash is None else bulk + flash
    losses = [sum(r["power_loss_W"] for r in rows if r["roll_deg"] == roll)
              if all(r["power_loss_W"] is not None for r in rows if r["roll_deg"] == roll)
              else None for roll in positions]
    loss = float(np.mean(losses)) if None not in losses else None
    power = running.power
    result.sections["lubrication"] = {
        "oil_temperature_degC": op.oil_temperature, "kinematic_viscosity_mm2_per_s": nu,
        "viscosity_extrapolated": lubricant.extrapolated(op.oil_temperature),
        "pour_point_degC": (oil.pour_point if oil.pour_point is not None
                            else lubricant.POUR_POINTS[oil.family]),
        "dynamic_viscosity_mPa_s": fluid.eta * 1e3, "density_15_kg_per_m3": density_15,
        "pressure_viscosity_per_GPa": fluid.alpha * 1e3, "family": oil.family,
        "reduced_modulus_MPa": fluid.E_reduced, "mean_roughness_Ra_um": fluid.roughness_um,
        "input_power_W" if running.input_power else "output_power_W": power}
    if not solved:
        return
    filmed = [r for r in solved if r["lambda"] is not None]
    coldest = min(filmed, key=lambda r: r["lambda"]) if filmed else None
    hot = max(solved, key=lambda r: r["flash_temperature_K"])
    contact_max = bulk + hot["flash_temperature_K"]
    summary.update(
        lambda_min=None if coldest is None else coldest["lambda"],
        lambda_min_at=None if coldest is None else _at(coldest),
        film_thickness_min_um=None if coldest is None else coldest["film_thickness_min_um"],
        flash_temperature_max_K=hot["flash_temperature_K"], flash_temperature_at=_at(hot),
        flash_temperature_mean_K=mean_flash, bulk_temperature_degC=bulk,
        contact_temperature_max_degC=contact_max,
        sliding_velocity_max_m_per_s=max(r["sliding_velocity_m_per_s"] for r in rows),
        mesh_power_loss_W=loss,
        mesh_efficiency=None if loss is None else (1.0 - loss / power if running.input_power
                                                   else power / (power + loss)),
        friction_coefficient_mean=float(np.mean([r["friction_coefficient"] for r in solved])))
    theta_S = oil.scuffing_temperature
    rise, margin = contact_max - op.oil_temperature, None
    if theta_S is not None:
        margin = theta_S - op.oil_temperature
    limiting = margin is not None and rise * S_B_NOT_LIMITING > margin
    summary["S_B"] = margin / rise if limiting else None
    if margin is not None and not limiting:
        summary["S_B_note"] = (
            f"not limiting: the hottest contact runs {rise:.3g} K above the oil, under "
            f"1/{S_B_NOT_LIMITING:g} of the scuffing temperature's margin {margin:.4g} K")
    summary["S_lambda"] = (None if oil.permissible_specific_film is None or coldest is None
                           else coldest["lambda"] / oil.permissible_specific_film)
    for key, name, limit in (("S_B", "scuffing", "scuffing_temperature"),
                             ("S_lambda", "micropitting", "permissible_specific_film")):
        if summary[key] is not None:
            result.checks.append(Check(
                f"{name} safety {key} at least 1", summary[key] >= 1.0,
                f"{key} {summary[key]:.2f} ([lubricant] {limit})"))
    if summary.get("S_B_note"):
        result.checks.append(Check("scuffing safety S_B at least 1", True,
                                   f"S_B {summary['S_B_note']}"))
    unfilmed = sum(r.get("bem_status") == "solved" and r["lambda"] is None for r in rows)
    summary["lubrication_note"] = (
        f"the lubricated contact at the {running.names[0]}'s "
        f"{running.speed:g} rpm and {op.oil_temperature:g} °C oil: speeds from the mesh's "
        "own placement of the exact flanks (sliding |v1 - v2| and sum |v1 + v2| of the "
        "tangential speeds at the contact point); friction "
        + ("fixed as given" if fluid.friction is not None else
           "ISO/TR 14179-2's μ at each contact (its largest normal line load, its sum speed "
           "and relative radius, the oil's viscosity, the mean Ra, X_L)")
        + (f"; {unfilmed} contact(s) without a relative radius across them (a flank turned "
           "onto an edge) have no film" + ("" if fluid.friction is not None else
                                           ", no ISO μ and no heat") if unfilmed else "")
        + "; film: Dowson-Higginson's minimum and Dowson-Toyoda's central film of each column "
        "of a contact line or of an ellipse longer than "
        f"{POINT_FILM_ELLIPTICITY:g} times its width (its own load per mm and entraining "
        "speed), Hamrock-Dowson's for a shorter ellipse, isothermal, the oil at the oil "
        "temperature (its viscosity on ASTM D341's line through the two given, "
        + ("extrapolated beyond 40-100 °C" if lubricant.extrapolated(op.oil_temperature)
           else "between them") + "); lambda = h_min / mean Ra; "
        "flash temperature: Blok's, the solved pressure's heat μ·p·v_s crossing into both "
        "flanks (high Peclet number; sqrt(λρc) "
        + ", ".join(f"{t / 1e3:.3g}" for t in fluid.thermal) + " kW·s^0.5/(m²·K)); bulk "
        "temperature "
        + ("as given" if op.bulk_temperature is not None else
           f"θ_oil + {BULK_FACTOR}·X_S·θ_fl,mean (ISO/TS 6336-20, X_S "
           f"{LUBRICATION_FACTOR[op.lubrication]:g})" if running.iso_bulk else
           "the oil's (none given)")
        + "; S_B = (θ_S - θ_oil)/(θ_B,max - θ_oil); S_lambda = lambda_min/λ_GFP; the mesh "
        "loss is the cycle's mean of Σ μ·p·v_s over the contacts' cells, the efficiency "
        + ("1 - loss/input power" if running.input_power else
           "output power/(output power + loss)"))


def _at(row: dict) -> str:
    return f"roll {row['roll_deg']:.2f} deg pair {row['pair']}"
