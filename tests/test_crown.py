"""Crown design (seed 003) against the geometry of a circular crown and the paper's Example 1."""

import math

import numpy as np
import pytest

from toothcontact.analytic import crown, hertz

INCH, LBF, PSI = 25.4, 4.4482216152605, 0.00689475729
STEEL_PSI = hertz.compliance(30e6 * PSI, 0.3, 30e6 * PSI, 0.3)


def test_radius_from_drop_is_the_circle_through_three_points():
    """Eq (12) against the circumradius of the points (-L, -drop), (0, 0), (L, -drop)."""
    drop, L = 0.012, 15.0
    p, q, r = np.array([-L, -drop]), np.array([0.0, 0.0]), np.array([L, -drop])
    sides = [np.linalg.norm(q - p), np.linalg.norm(r - q), np.linalg.norm(p - r)]
    u, v = q - p, r - p
    area = 0.5 * abs(u[0] * v[1] - u[1] * v[0])
    assert crown.radius_from_drop(drop, L) == pytest.approx(np.prod(sides) / (4 * area), rel=1e-9)
    assert crown.drop_from_radius(crown.radius_from_drop(drop, L), L) == pytest.approx(drop, rel=1e-9)


def test_example_1_is_reproduced_when_a_is_053_in():
    """Seed 003 Example 1: F = 1.44 in, slopes 0.0019 / 0.00074, Wt = 3600 lbf; with a
    profile curvature that makes a ≈ 0.53 in, the bias design gives R ≈ 143 in, c ≈ 0.64 in."""
    load = crown.normal_load(3600 * LBF, math.radians(25))
    profile = 1 / (0.155 * INCH) - 1 / (3.0 * INCH)  # internal mesh, assumed radii
    design = crown.design_crown(1.44 * INCH, 0.0019, 0.00074, profile, load, STEEL_PSI)
    assert design.contact.semi_axis_face / INCH == pytest.approx(0.53, abs=0.005)
    assert design.radius / INCH == pytest.approx(143, abs=1.0)
    assert design.center_from_B / INCH == pytest.approx(0.64, abs=0.01)
    # both ends at their limit: eq (13) with zero margin
    assert design.edge_margin_A == pytest.approx(0.0, abs=1e-9)
    assert design.edge_margin_B == pytest.approx(0.0, abs=1e-9)


def test_full_crown_meets_the_edge_rule_at_half_face():
    load, profile = crown.normal_load(8000.0, math.radians(20)), 1 / 11.2 + 1 / 29.8
    design = crown.design_crown(30.0, 0.0012, 0.0012, profile, load, hertz.compliance(206e3, .3, 206e3, .3))
    assert design.center_from_B == pytest.approx(15.0, rel=1e-12)
    assert design.radius * 0.0012 + design.contact.semi_axis_face == pytest.approx(15.0, rel=1e-9)


def test_a_crown_20_percent_flatter_than_designed_edge_loads():
    C_E = hertz.compliance(206e3, .3, 206e3, .3)
    load, profile = crown.normal_load(8000.0, math.radians(20)), 1 / 11.2 + 1 / 29.8
    design = crown.design_crown(30.0, 0.0015, 0.0003, profile, load, C_E)
    flatter = crown.check_crown(1.2 * design.radius, design.center_from_B, 30.0, 0.0015, 0.0003,
                                profile, load, C_E)
    assert flatter.edge_margin_A < 0 and flatter.edge_margin_B < 0
    rounder = crown.check_crown(0.8 * design.radius, design.center_from_B, 30.0, 0.0015, 0.0003,
                                profile, load, C_E)
    assert rounder.edge_margin_A > 0 and rounder.edge_margin_B > 0
    assert rounder.contact.ellipse.p0 > design.contact.ellipse.p0


def test_crowned_contact_semi_axis_along_face_is_the_long_axis_for_flat_crowns():
    C_E = hertz.compliance(206e3, .3, 206e3, .3)
    flat = crown.crowned_contact(5000.0, 0.12, 9000.0, C_E)
    assert flat.semi_axis_face == pytest.approx(flat.ellipse.a, rel=1e-12)
    tight = crown.crowned_contact(2.0, 0.12, 9000.0, C_E)  # crown more curved than the profile
    assert tight.semi_axis_face == pytest.approx(tight.ellipse.b, rel=1e-12)
