"""The loaded worm set as made (issue 52): every contact solved where the rigid pattern runs
past an edge, the worm shaft's deflection placed as the deflected worm sits, the mean
Hertzian pressure over the lines as Hertz gives it, the wheel material's limits checked.
Lengths in mm, forces in N."""

import math

import numpy as np
import pytest

from toothcontact import worm_gearset
from toothcontact.analyses.worm import SHAKEDOWN_PER_YIELD, worm_geometry_case
from toothcontact.case import parse_case

SABA = {"kind": "worm", "title": "SABA set",
        "worm": {"form": "ZI", "starts": 1, "normal_module": "1.1 mm", "lead_angle": "4.1 deg",
                 "hand": "right", "pressure_angle": "20 deg", "length": "30 mm"},
        "wheel": {"teeth": 40},
        "wheel_material": {"E": "98 GPa", "nu": 0.35},
        "analysis": {"positions": 3}}


def saba(**changes):
    raw = {key: dict(value) if isinstance(value, dict) else value for key, value in SABA.items()}
    for key, value in changes.items():
        raw.setdefault(key, {}).update(value) if isinstance(value, dict) else raw.update({key: value})
    return parse_case(raw)


def test_a_line_contact_under_a_tiny_torque_solves_every_contact():
    """Seed 000's line-contact set at 0.01 N·m: a pair touching over a few micrometres at
    roll 0 has a rigid pattern (a Hertz ellipse at that load) whose box missed both flanks:
    two of eight contacts were not solved ("no line of the gap field meets both flanks",
    exit 4). The box is now laid again about the contact point, halved, until its lines
    meet the flanks: all solved."""
    result = worm_geometry_case(saba(load={"output_torque": "0.01 N*m"}))
    rows = result.sections["positions"]
    assert [r["bem_status"] for r in rows if r["bem_status"] == "failed"] == []
    assert result.sections["summary"]["bem_failed_contacts"] == 0
    assert all(r["edge_pressure_at"] != "beyond_surface" for r in rows
               if r["bem_status"] == "solved")


def bronze_wheel_set(worm: dict, teeth: int, torque: str, **analysis):
    """A worm set (20 deg, 40 mm long worm) on a bronze wheel of `teeth` under `torque`,
    analysed without the positions check and the subsurface stresses."""
    return parse_case({"kind": "worm",
                       "worm": {"pressure_angle": "20 deg", "length": "40 mm", **worm},
                       "wheel": {"teeth": teeth},
                       "wheel_material": {"E": "98 GPa", "nu": 0.35},
                       "load": {"output_torque": torque},
                       "analysis": {"positions_check": False, "subsurface": False,
                                    **analysis}})


def test_a_four_start_worm_whose_pattern_runs_past_its_tip_solves_every_contact():
    """A 4-start ZI worm at 4 deg lead with a 52-tooth bronze wheel, 60 N·m: its rigid
    pattern reaches 3.97 mm past the worm's tip edge, and the field sized on it missed the
    flank pair (2-3 pairs unsolved at roll ±15 deg). Fitted to the flanks' material: every
    contact solved, none on a false edge."""
    result = worm_geometry_case(bronze_wheel_set(
        {"form": "ZI", "starts": 4, "normal_module": "1.5 mm", "lead_angle": "4 deg"},
        52, "60 N*m", positions=6, pressure_grid=48))
    rows = result.sections["positions"]
    assert {round(r["roll_deg"], 6) for r in rows} >= {-15.0, 15.0}
    assert result.sections["summary"]["bem_failed_contacts"] == 0
    assert all(r["bem_status"] in ("solved", "unloaded") for r in rows)
    assert all(r["edge_pressure_at"] != "beyond_surface" for r in rows
               if r["bem_status"] == "solved")


def test_a_set_whose_contacts_sit_on_the_wheels_tip_corner_is_answered():
    """A thin 1-start ZN worm (m 1 mm, 14.6 deg lead: d1 = 4 mm) on a 50-tooth wheel at
    42 N·m: its contacts sit on the wheel's tip corner, whose default rounding turns the
    flank less than the worm's flank does, so no line along the common normal meets the
    wheel there. The rigid stage had refused the legal case ('no contact could be found',
    exit 2); such a contact is now its Hertz ellipse, its rigid pattern not measured
    (null), and the loaded stage says per contact why it could not solve."""
    result = worm_geometry_case(bronze_wheel_set(
        {"form": "ZN", "starts": 1, "normal_module": "1 mm", "lead_angle": "14.6 deg"},
        50, "42 N*m", positions=3, pressure_grid=32))
    rows = result.sections["positions"]
    assert any(r["rigid_pattern_area_mm2"] is None for r in rows)
    assert all(r["rigid_pattern_area_mm2"] is None or r["rigid_pattern_area_mm2"] > 0.0
               for r in rows if r.get("rigid_contact", True))
    failed = [r for r in rows if r["bem_status"] == "failed"]
    assert all(r["bem_reason"] for r in failed)
    assert all(math.isfinite(r["p_max_MPa"]) for r in rows)


def test_the_worm_shafts_deflection_places_the_worm_as_it_bends():
    """[worm.shaft]: the mesh force on the worm is the frictionless normal force at its pitch
    point (its axial part F_t2 = 2·T2/d2, radial F_n·sin α_n, tangential F_t2·tan γ: the
    textbook split, Niemann/DIN 3975); the misalignment it gives places the wheel relative
    to the worm as the worm, moved and turned by its deflection at the mesh, would sit: the
    wheel's axis and centre in the worm's frame agree to 1e-9 (first order in the
    deflection: the deflection's own square, 1e-9, is what remains)."""
    from toothcontact.analyses import worm as kind
    from toothcontact.analytic import worm_efficiency
    from toothcontact.analyses.result import Result
    from toothcontact.surfaces.placement import Frame, WormMesh, WormMisalignment, rotation

    case = saba(worm={"shaft": {"bearings": ["-40 mm", "40 mm"], "diameter": "8 mm"}},
                load={"output_torque": "4.84 N*m"})
    parts = worm_gearset.worm_set(case)
    worm, wheel = parts.worm["left"], parts.wheel["left"]
    alpha_n, gamma = case.worm.pressure_angle, worm.lead_angle
    F_n = worm_efficiency.normal_tooth_load(4840.0, wheel.reference_radius, gamma, alpha_n)
    result = Result(sections={"summary": {}})
    bent = kind._shaft_bent(case, worm, wheel, F_n, alpha_n, WormMisalignment(), result)
    shaft = result.sections["worm_shaft"]
    force = np.abs(shaft["mesh_force_N"])
    F_t2 = 2 * 4840.0 / (2 * wheel.reference_radius)
    assert force[2] == pytest.approx(F_t2, rel=0.01)
    assert force[0] == pytest.approx(F_n * math.sin(alpha_n), rel=0.01)
    assert force[1] == pytest.approx(F_t2 * math.tan(gamma), rel=0.02)
    assert shaft["deflection_from_wheel_mm"] > 0.0          # pushed away from the wheel
    # the worm moved by its deflection at the mesh (x toward the wheel, y) and turned by
    # its slopes (toward the wheel about y, along the wheel's axis about -x)
    axis_y = WormMesh(wheel).gear_frame(0.0).R[1, 2]
    at = np.array([-shaft["deflection_from_wheel_mm"],
                   shaft["deflection_along_wheel_axis_mm"] * axis_y, 0.0])
    moved = Frame(rotation([0.0, 1.0, 0.0], shaft["slope_toward_wheel_rad"])
                  @ rotation([1.0, 0.0, 0.0], -shaft["slope_along_wheel_axis_rad"]), at)
    straight, placed = WormMesh(wheel), WormMesh(wheel, bent)

    def relative(worm_frame, wheel_frame):
        """The wheel's axis and centre in the worm's frame."""
        return (worm_frame.R.T @ wheel_frame.R[:, 2],
                worm_frame.R.T @ (wheel_frame.origin - worm_frame.origin))

    for phi in (0.0, 0.7):
        turn = rotation([0.0, 0.0, 1.0], phi)
        expected = relative(Frame(moved.R @ turn, moved.origin), straight.gear_frame(phi))
        got = relative(placed.pinion_frame(phi), placed.gear_frame(phi))
        assert np.allclose(got[0], expected[0], atol=1e-8)
        assert np.allclose(got[1], expected[1], atol=1e-8)


def test_the_mean_hertz_pressure_of_a_hertz_line_is_its_peak():
    """(4/π)·load/area, the mean Hertzian pressure over the lines (analyses.worm), on a
    Hertz line contact solved on a half-space (R = 20 mm, 100 N/mm, steel on bronze): its
    peak p0 = sqrt(q·E*/(π·R)) within 2 % on the middle half of the line, q its own line
    load there (the ends, where the half-space runs on past them, carry the end's rise;
    46 cells across the band)."""
    from toothcontact.analytic.hertz import compliance
    from toothcontact.contact.pressure import Grid, solve_shared

    C = compliance(206000.0, 0.3, 98000.0, 0.35)
    E_star = 1.0 / C if C < 1.0 else C
    R, q, length, cell = 20.0, 100.0, 4.0, 0.004
    b = math.sqrt(4 * q * R / (math.pi * E_star))
    y = (np.arange(int(6 * b / cell)) - 0.5 * (int(6 * b / cell) - 1)) * cell
    n = int(length / cell)
    gap = np.broadcast_to(y ** 2 / (2 * R), (n + 2, y.size)).copy()
    mask = np.zeros(gap.shape, bool)
    mask[1:n + 1] = True                      # the line ends inside the grid
    s = solve_shared([Grid(gap, cell, cell, mask, None)], [q * n * cell], E_star, tol=1e-8,
                     max_iter=3000)[0]
    half = s.pressure_MPa[1 + n // 4:1 + 3 * n // 4]
    q_half = half.sum() * cell / half.shape[0]                 # N/mm
    p0 = math.sqrt(q_half * E_star / (math.pi * R))
    mean = 4.0 / math.pi * half.sum() / np.count_nonzero(half > 0.0)
    assert mean == pytest.approx(p0, rel=0.02)
    assert s.pressure_MPa[n // 2].max() == pytest.approx(p0, rel=0.02)


def test_the_wheel_materials_limits_are_checked_and_a_polymer_wheel_says_what_the_model_is():
    """Where the case gives the wheel's yield strength, the largest von Mises stress below
    the contact is held to the shakedown limit it sets (1.29 σ_y: Johnson's p0 = 4k for a
    line contact, in Hertz's stress); a nylon wheel (E 3 GPa) gets the note on what an
    elastic, linear model says of a polymer, and no check is made of its pressures."""
    nylon = worm_geometry_case(saba(wheel_material={"E": "3 GPa", "nu": 0.4,
                                                    "yield_strength": "70 MPa"},
                                    load={"output_torque": "2 N*m"}))
    names = {c.name: c for c in nylon.checks}
    check = names["wheel: the stresses below the contact stay within its shakedown limit"]
    stress = nylon.sections["summary"]["subsurface_von_mises_max_MPa"]
    assert check.ok == (stress <= SHAKEDOWN_PER_YIELD * 70.0)
    assert "1.29 times" in check.detail
    assert any(n.startswith("a polymer wheel (E = 3 GPa)") for n in nylon.notes)
    summary = nylon.sections["summary"]
    assert 0.0 < summary["mean_hertz_pressure_MPa"] <= summary["mean_hertz_pressure_max_MPa"]
    assert summary["wheel_root_shear_MPa"] > 0.0 and "not coded" in summary["wheel_root_shear_method"]
