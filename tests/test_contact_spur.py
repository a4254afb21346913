"""Contact by surface separation on a crowned spur pair, against closed forms."""

import math
from pathlib import Path

import numpy as np
import pytest
from pairs import STEEL, spur_cycle

from toothcontact import gearset
from toothcontact.analytic.hertz import roark_point
from toothcontact.case import parse_case
from toothcontact.contact.cycle import CycleSettings

#: sharp tips: these tests hold the contact against the involute's closed forms (a tip
#: rounding, on by default, has its own: tests/test_tip_edge.py)
SHARP = {"tip_edge": {"radius": "0 mm"}}
CASE = {"kind": "spur", "teeth": [20, 60], "module": "3 mm", "pressure_angle": "20 deg",
        "face_width": "30 mm", "pinion": {"crown": {"radius": "4000 mm"}, **SHARP},
        "gear": SHARP}


def run(case=CASE, slope=0.0, positions=3):
    pair, cycle = spur_cycle(case, slope, positions)
    return pair, cycle.rows


@pytest.fixture(scope="module")
def aligned():
    return run()


def test_fitted_gap_agrees_with_the_flank_curvatures(aligned):
    """A and B from the separation fit within 0.5 % of A and B from both flanks' principal
    curvatures, at every position and pair."""
    _, rows = aligned
    assert len(rows) >= 3
    for r in rows:
        assert r["A_per_mm"] == pytest.approx(r["A_analytic_per_mm"], rel=5e-3)
        assert r["B_per_mm"] == pytest.approx(r["B_analytic_per_mm"], rel=5e-3)


def test_aligned_crowned_spur_touches_mid_face_without_transmission_error(aligned):
    _, rows = aligned
    for r in rows:
        assert r["face_position_mm"] == pytest.approx(0.0, abs=1e-3)
        assert r["A_analytic_per_mm"] == pytest.approx(1 / (2 * 4000.0), rel=1e-6)
        assert abs(r["transmission_error_urad"]) < 0.05


def test_hertz_ellipse_equals_roark_with_the_profile_radii_of_the_contact_point(aligned):
    """Seed 003 eqs (6)-(11) with rho1 = sqrt(r² - rb1²) at the actual contact radius, rho2
    = C·sin(alpha) - rho1, and the crown radius: within 1 %."""
    pair, rows = aligned
    rb1 = pair.pinion.base_radius
    for r in rows:
        rho1 = math.sqrt(r["contact_radius_pinion_mm"] ** 2 - rb1**2)
        rho2 = pair.center_distance * math.sin(pair.working_pressure_angle) - rho1
        curv = [1 / rho1, 1 / rho2, 1 / 4000.0, 0.0]
        roark = roark_point(sum(curv), abs(curv[0] + curv[1] - curv[2] - curv[3]), r["normal_load_N"],
                            STEEL)
        assert r["a_mm"] == pytest.approx(roark.a, rel=0.01)
        assert r["b_mm"] == pytest.approx(roark.b, rel=0.01)
        assert r["p_max_MPa"] == pytest.approx(roark.p0, rel=0.01)


def test_slope_moves_the_contact_by_R_theta_and_then_onto_the_edge():
    _, rows = run(slope=0.001)
    for r in rows:
        assert r["face_position_mm"] == pytest.approx(4000.0 * 0.001, rel=0.01)
    _, rows = run(slope=0.0035)  # R·theta = 14 mm: the ellipse (a ≈ 8.4 mm) runs off end B
    assert all(r["edge_contact"] for r in rows)
    worst = [min(r["edge_margins_mm"], key=r["edge_margins_mm"].get) for r in rows]
    assert all(name.endswith("end_B") for name in worst)


def test_edge_margins_are_lengths_along_the_involute(aligned):
    """The margins to the tip and form circles are lengths along the profile: an involute's
    arc from roll angle t to t' is rb·(t'² - t²)/2, so the margin from the ellipse (reaching
    b across the profile from the contact) to the tip is rb·(t_tip² - t_c²)/2 - b, with t_c
    from the contact radius (the gear's from its roll length along the line of action),
    and likewise to the form circle; to 1e-4 mm."""
    pair, rows = aligned
    flanks = {name: getattr(f, "base", f) for name, f in (   # the involutes under the crown
        ("pinion", gearset.working_flank(pair.pinion, pair.pinion_modifications, 1)),
        ("gear", gearset.working_flank(pair.gear, pair.gear_modifications, -1)))}
    arc = {name: (lambda r, f=f: 0.5 * f.gear.base_radius * (r**2 / f.gear.base_radius**2 - 1))
           for name, f in flanks.items()}
    line_of_action = pair.center_distance * math.sin(pair.working_pressure_angle)
    for r in rows:
        rb1, rb2 = pair.pinion.base_radius, pair.gear.base_radius
        t1 = math.sqrt(r["contact_radius_pinion_mm"] ** 2 / rb1**2 - 1)
        roll = {"pinion": 0.5 * rb1 * t1**2, "gear": 0.5 * (line_of_action - rb1 * t1) ** 2 / rb2}
        for name, f in flanks.items():
            margins = r["edge_margins_mm"]
            assert margins[f"{name}_tip"] == pytest.approx(
                arc[name](f.gear.tip_radius) - roll[name] - r["b_mm"], abs=1e-4)
            assert margins[f"{name}_form"] == pytest.approx(
                roll[name] - arc[name](f.form_radius) - r["b_mm"], abs=1e-4)


def test_rigid_pattern_measured_on_the_separation_field(aligned):
    """The rigid pattern measured on each contact's 201 × 201 separation field at the
    approach delta (wherever no edge cuts it): along the face it spans the crown's closed
    form 2·sqrt(2R·delta - delta²), to one cell of the field (1.25 % of the rigid ellipse's
    box), and across it 2·sqrt(delta/B), to 1.5 cells (the profile curvature changes across
    the pattern); its area is π·a·b of the rigid ellipse to 0.5 % where the gap is
    quadratic over the pattern (fit rms below 1 nm) and to 1 % next to the base circle
    (radius 28.4 mm, rb 28.2 mm), where the profile curvature changes fast."""
    _, rows = aligned
    delta = CycleSettings().approach
    whole = [r for r in rows if not r["rigid_pattern_cut"]]
    assert len(whole) >= 2
    for r in whole:
        along, across = 2 * math.sqrt(2 * 4000.0 * delta - delta**2), 2 * r["rigid_b_mm"]
        assert r["rigid_pattern_along_face_mm"] == pytest.approx(along, abs=0.0125 * along)
        assert r["rigid_pattern_across_face_mm"] == pytest.approx(across, abs=0.019 * across)
        assert r["rigid_pattern_area_mm2"] == pytest.approx(
            math.pi * r["rigid_a_mm"] * r["rigid_b_mm"], rel=5e-3 if r["fit_rms_mm"] < 1e-6 else 0.01)


def test_rigid_pattern_is_cut_at_the_face_end():
    """Under slope 0.0035 the rigid pattern runs from rigid_a before the contact to the first
    face end (the distance the ellipse's edge margins give: a + margin), to one cell, and
    is reported cut."""
    _, rows = run(slope=0.0035)
    for r in rows:
        assert r["rigid_pattern_cut"]
        margins = r["edge_margins_mm"]
        to_end = r["a_mm"] + min(margins["pinion_end_B"], margins["gear_end_B"])
        cell = 2.5 * r["rigid_a_mm"] / 200
        assert r["rigid_pattern_along_face_mm"] == pytest.approx(r["rigid_a_mm"] + to_end, abs=1.5 * cell)


def test_bias_crown_adds_its_centre_shift():
    case = {**CASE, "pinion": {"crown": {"radius": "4000 mm", "center": "2.5 mm"}, **SHARP}}
    _, rows = run(case, slope=0.001)
    for r in rows:
        assert r["face_position_mm"] == pytest.approx(2.5 + 4.0, rel=0.01)


def test_spur_case_reports_positions_and_summary(tmp_path):
    """The bundled crowned spur case: 21 positions, contact R·theta = 3.2 mm toward end B on
    the involute (on the pinion's tip rounding, at the ends of the path, the rounding's
    own surface places it 0.175 mm further), the result keys of the contact issue present,
    and the corner contact at the pinion tip at the ends of the path reported as such."""
    from toothcontact.runner import analyse_file, bundled_cases_dir

    doc = analyse_file(bundled_cases_dir() / "spur_crowned_20_60.toml")
    rows = doc["positions"]
    keys = {"roll_deg", "pair", "contact_radius_pinion_mm", "face_position_mm", "A_per_mm",
            "B_per_mm", "a_mm", "b_mm", "p_max_MPa", "approach_mm", "rigid_a_mm", "rigid_b_mm",
            "edge_margin_mm", "edge_contact", "transmission_error_urad"}
    assert all(keys <= set(r) for r in rows)
    assert len({r["roll_deg"] for r in rows}) == 21
    # the pairs in contact (pairs kept beyond the approach for the loaded contact least
    # apart elsewhere, at a tip corner)
    from toothcontact.case import load_case

    pair = gearset.gear_pair(load_case(bundled_cases_dir() / "spur_crowned_20_60.toml")[0])
    rounding = math.hypot(pair.pinion_modifications.tip_edge.start, pair.pinion.base_radius)
    # the involute more than 0.1 mm below the rounding's start (the three corner contacts at the
    # path's ends lie within 25 µm of it, their point set by the rounding's curve)
    on_involute = [r for r in rows if r["rigid_contact"]
                   and r["contact_radius_pinion_mm"] < rounding - 0.1]
    assert len(on_involute) >= len([r for r in rows if r["rigid_contact"]]) - 3
    assert all(r["face_position_mm"] == pytest.approx(3.2, rel=0.01) for r in on_involute)
    summary = doc["summary"]
    assert summary["worst_face_edge_margin_mm"] > 0
    assert summary["worst_profile_edge"] == "pinion_tip"


def test_ring_gear_pair_crowned_planet():
    """A crowned planet in a ring (internal mesh): the gap fit agrees with the curvatures
    (the ring's flank is concave) and the slope moves the contact by R·theta."""
    case = {"kind": "spur", "teeth": [24, -72], "module": "2 mm", "pressure_angle": "20 deg",
            "face_width": "20 mm", "pinion": {"crown": {"radius": "2500 mm"}, **SHARP},
            "gear": SHARP}
    _, rows = run(case, slope=0.001)
    assert rows
    for r in rows:
        assert r["A_per_mm"] == pytest.approx(r["A_analytic_per_mm"], rel=5e-3)
        assert r["B_per_mm"] == pytest.approx(r["B_analytic_per_mm"], rel=5e-3)
        assert r["face_position_mm"] == pytest.approx(2.5, rel=0.01)


def test_crowned_helical_pair_gap_fit_agrees_with_curvatures():
    case = {"kind": "spur", "teeth": [23, 57], "module": "2.5 mm", "pressure_angle": "20 deg",
            "helix_angle": "20 deg", "face_width": "25 mm",
            "pinion": {"crown": {"height": "12 um", "shape": "parabolic"}, **SHARP},
            "gear": SHARP}
    _, rows = run(case)
    assert rows
    for r in rows:
        assert r["A_per_mm"] == pytest.approx(r["A_analytic_per_mm"], rel=5e-3)
        assert r["B_per_mm"] == pytest.approx(r["B_analytic_per_mm"], rel=5e-3)


@pytest.mark.parametrize("tilt", [0.0, 0.0017])
def test_spline_contact_all_teeth(tilt):
    """Coaxial spline, ratio 1: aligned, every tooth closes its clearance at once and the lag
    is the clearance turned into an angle, (dT/2)·cos(alpha)/rb; tilted, the teeth in the
    plane of the tilt (teeth 0 and 9, half a turn apart, where the tilt only slides the contact
    along the crown) touch and those a quarter turn away (teeth 4-5, 13-14) are farthest."""
    import tomllib

    from toothcontact.analyses import analyse

    raw = tomllib.loads((Path(__file__).parents[1] / "cases" / "spline_crowned_18t.toml").read_text())
    raw.update(misalignment=tilt, analysis={"positions": 1, "grid": [9, 41],
                                                "positions_check": False, "subsurface": False})
    doc = analyse(parse_case(raw)).as_dict()
    rows = doc["positions"]
    gaps = {r["pair"]: r["separation_mm"] for r in rows}
    if tilt == 0.0:
        assert sorted(gaps) == list(range(18))
        assert max(gaps.values()) < 1e-7
        dT, alpha = 0.002 * 25.4, math.radians(30)
        rb = 0.5 * 18 * 25.4 / 32 * math.cos(alpha)
        assert rows[0]["transmission_error_urad"] == pytest.approx(
            0.5 * dT * math.cos(alpha) / rb * 1e6, rel=1e-4)
    else:
        assert gaps[0] < 1e-9 and gaps[9] < 1e-9
        farthest = max(gaps, key=gaps.get)
        assert farthest in (4, 5, 13, 14)
        assert gaps[farthest] > 1e-3  # mm: the clearance there stays open


def test_tip_interference_is_found_when_the_centre_distance_is_too_short():
    """Pulling the gear 1 mm closer drives the tips into the mates' roots: python-fcl on
    the placed bodies reports it, every point on a tip circle (the gear's tip scraping
    the pinion below its active profile, the pinion's tip in the gear's root); at the
    nominal centre distance there is none."""
    from toothcontact.analyses import analyse

    base = {**CASE, "load": {"tangential_load": "8000 N"},
            "analysis": {"positions": 3, "grid": [15, 21], "positions_check": False,
                         "subsurface": False}}
    nominal = analyse(parse_case(base)).as_dict()
    assert nominal["interference"]["found"] == []
    close = analyse(parse_case({**base, "center_distance": "119 mm"})).as_dict()
    assert close["interference"]["found"]
    pair = gearset.gear_pair(parse_case({**base, "center_distance": "119 mm"}))
    for found in close["interference"]["found"]:
        points = np.array(found["points_mm"])
        to_pinion = np.hypot(points[:, 0], points[:, 1])
        to_gear = np.hypot(points[:, 0] - 119.0, points[:, 1])
        # where a tip corner runs into the mate: within 0.1 mm of the pinion's or the
        # gear's tip circle (the crossing of the surfaces lies as deep as the overlap)
        on_tip = (np.isclose(to_pinion, pair.pinion.tip_radius, atol=0.1)
                  | np.isclose(to_gear, pair.gear.tip_radius, atol=0.1))
        assert on_tip.all(), (to_pinion, to_gear)
