"""Line-of-action geometry of spur meshes, checked by coordinates in the transverse plane."""

import math

import pytest

from toothcontact.analytic import agma
from toothcontact.analytic.spur_mesh import SpurMesh


def mesh(z1=20, z2=60, m=3.0, phi=20.0):
    r1, r2 = m * z1 / 2, m * abs(z2) / 2
    internal = z2 < 0
    return SpurMesh(z1, z2, m, math.radians(phi), r2 - r1 if internal else r2 + r1, r1 + m,
                    r2 - m if internal else r2 + m)


@pytest.mark.parametrize("z2", [60, -60])
def test_start_of_contact_lies_on_the_gear_tip(z2):
    """Place T1, T2 and the point C1 along the line of action in coordinates: the point must
    be at the gear's tip radius from the gear centre and at sqrt(rb1² + C1²) from the pinion's."""
    g = mesh(z2=z2)
    phi = g.pressure_angle
    t = (math.cos(phi), math.sin(phi))  # line-of-action direction
    n = (-math.sin(phi), math.cos(phi))  # towards the pinion centre from T1
    pinion = (g.base_radius_pinion * n[0], g.base_radius_pinion * n[1])
    s = g.start_of_contact
    point = (s * t[0], s * t[1])  # T1 at the origin
    # the gear centre: on the line through the pitch point, at the centre distance
    # external: T2 ahead of T1 on the line, gear centre on the far side of the line;
    # internal: T2 behind T1, gear centre on the pinion's side
    side = -1.0 if g.internal else 1.0
    T2 = (side * g.line_of_action_length * t[0], side * g.line_of_action_length * t[1])
    gear = (T2[0] - side * g.base_radius_gear * n[0], T2[1] - side * g.base_radius_gear * n[1])
    assert math.dist(pinion, gear) == pytest.approx(g.center_distance, rel=1e-12)
    assert math.dist(gear, point) == pytest.approx(g.outside_radius_gear, rel=1e-12)
    assert math.dist(pinion, point) == pytest.approx(math.hypot(g.base_radius_pinion, s), rel=1e-12)


@pytest.mark.parametrize("z2", [60, -60])
def test_lpstc_is_where_the_pair_ahead_leaves_the_pinion_tip(z2):
    """Seed 003 eq (1) against a count of the pairs in contact: just above the LPSTC one
    pair carries the load, just below it two do (pairs one base pitch apart on the line)."""
    g = mesh(z2=z2)
    assert g.lpstc() == pytest.approx(math.sqrt(g.outside_radius_pinion**2 - g.base_radius_pinion**2)
                                      - 2 * math.pi * g.base_radius_pinion / g.z1, rel=1e-15)

    def pairs_in_contact(s):
        return sum(g.start_of_contact <= s + k * g.base_pitch <= g.end_of_contact
                   for k in range(-3, 4))

    eps = 1e-9
    assert pairs_in_contact(g.lpstc() - eps) == 2
    assert pairs_in_contact(g.lpstc() + eps) == 1
    assert pairs_in_contact(g.hpstc() - eps) == 1
    assert pairs_in_contact(g.hpstc() + eps) == 2
    assert 1.0 < g.contact_ratio < 2.0


def test_base_pitch_equals_circular_pitch_times_cos_phi():
    g = mesh()
    assert g.base_pitch == pytest.approx(math.pi * 3.0 * math.cos(math.radians(20)), rel=1e-12)


@pytest.mark.parametrize("z2,sign", [(60, 1), (-60, -1)])
def test_geometry_factor_at_pitch_point_closed_form(z2, sign):
    """At the pitch point I = cos·sin/2 · u/(u ± 1) (AGMA 2001, spur, m_N = 1)."""
    g = mesh(z2=z2)
    phi = g.pressure_angle
    d = g.operating_pitch_diameter
    rho1 = 0.5 * d * math.sin(phi)
    rho2 = g.gear_radius_of_curvature(rho1)
    u = abs(z2) / g.z1
    I = agma.geometry_factor(rho1, rho2, phi, d, g.internal)
    assert I == pytest.approx(math.cos(phi) * math.sin(phi) / 2 * u / (u + sign), rel=1e-12)


def test_interference_is_reported():
    g = mesh(z1=12, z2=120)
    with pytest.raises(ValueError, match="interference"):
        g.check()
