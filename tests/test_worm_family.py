"""A seeded family of realistic worm sets (toothcontact.families: three of each form, either
hand, identical or oversized and tilted hobs) through the geometry of their cases, held to
invariants checked independently of the generation formulas: the wheel flank is the
envelope of the hob (every point a placed hob point, the equation of meshing holds there, with
the kinematics rebuilt in test_worm_wheel), the wheel teeth have a positive thickness and
leave a positive space, and the flank normals point out of the tooth. Lengths in mm."""

import math

import numpy as np
import pytest
from scipy.optimize import brentq

from test_worm_wheel import dot, envelope_residuals
from toothcontact import families, worm_gearset
from toothcontact.case import parse_case

FAMILY = families.worm_designs(12, seed=2024)


@pytest.fixture(scope="module", params=range(len(FAMILY)),
                ids=[d["title"] for d in FAMILY])
def worm_set(request):
    raw = FAMILY[request.param]
    return raw, worm_gearset.worm_set(parse_case(raw))


def test_the_family_covers_the_ranges():
    """Every form, both hands, both loaded flanks, identical, oversized and tilted hobs."""
    assert {d["worm"]["form"] for d in FAMILY} == {"ZA", "ZN", "ZI", "ZK"}
    assert {d["worm"]["hand"] for d in FAMILY} == {"left", "right"}
    assert {d["load"]["flank"] for d in FAMILY} == {"left", "right"}
    hobs = [d["wheel"] for d in FAMILY]
    assert any("hob_pitch_diameter" not in h for h in hobs)
    assert any(h.get("align_hob_thread") for h in hobs)
    assert any("hob_pitch_diameter" in h and not h["align_hob_thread"] for h in hobs)


def test_the_wheel_flank_is_the_envelope_of_the_hob(worm_set):
    """On a 7 × 7 grid over each flank's whole domain: the wheel point is the hob point
    r_h(u_h, v_h) turned by the generating angle phi1 and placed by the rebuilt machine motion
    (1e-8 mm), and there the hob normal is square to the relative velocity v12 = e_z × X -
    (z1/z2)·k2 × (X - C) (|n·v12|/|v12| < 1e-8). The envelope is the wheel as generated,
    before its tip edge is broken (test_worm_edges holds the rounding)."""
    _, parts = worm_set
    for wheel in parts.wheel.values():
        P, rebuilt, residual, _ = envelope_residuals(wheel.base, *wheel.grid(7, 7))
        assert np.all(np.isfinite(P))
        np.testing.assert_allclose(rebuilt, P, atol=1e-8)
        assert residual.max() < 1e-8


def polar_angle_at_radius(flank, radius, v):
    """Polar angle (rad) of the flank's point of the given radius in the section z2 = v,
    found from `point` alone (brentq on the depth parameter)."""
    f = lambda u: math.hypot(*np.stack(flank.point(np.array(u), np.array(v)))[:2]) - radius  # noqa: E731
    u = brentq(f, 0.0, 1.0, xtol=1e-13)
    x, y, _ = flank.point(np.array(u), np.array(v))
    return math.atan2(float(y), float(x))


def test_wheel_teeth_have_thickness_and_space(worm_set):
    """In five sections across the face and at three radii between the root and tip edges
    (common to both flanks), tooth 0's two flanks bound a positive thickness and leave a
    positive space to the next tooth: 0 < theta_plus - theta_minus < 2 pi/z2."""
    _, parts = worm_set
    left, right = parts.wheel["left"], parts.wheel["right"]
    pitch = 2 * math.pi / left.teeth
    for v in np.linspace(-0.45, 0.45, 5) * left.face_width:
        ends = [np.hypot(*np.stack(f.point(np.array([0.0, 1.0]), np.array([v, v])))[:2])
                for f in (left, right)]  # (tip-edge, root-edge) radii of each flank
        lo, hi = max(e.min() for e in ends), min(e.max() for e in ends)
        for radius in np.linspace(lo, hi, 5)[1:-1]:
            a, b = sorted(polar_angle_at_radius(f, radius, v) for f in (left, right))
            assert 0 < b - a < pitch


def test_wheel_normals_point_out_of_the_tooth(worm_set):
    """Each flank's unit normal is the normalised r_u × r_v (finite differences, up to its
    orientation sign, 1e-5) and points away from tooth 0's centre line, toward increasing
    polar angle on the flank at the larger angle (n·e_theta > 0) and the other way on the
    other flank."""
    _, parts = worm_set
    left, right = parts.wheel["left"], parts.wheel["right"]
    order = sorted((left, right), key=lambda f: polar_angle_at_radius(
        f, f.reference_radius, 0.0))
    for flank, sign in zip(order, (-1.0, 1.0)):
        u, v = np.meshgrid(np.linspace(0.05, 0.95, 5),
                           np.linspace(-0.45, 0.45, 5) * flank.face_width, indexing="ij")
        s = flank.evaluate(u, v)
        h = 1e-6
        du = (np.stack(flank.point(u + h, v), -1) - np.stack(flank.point(u - h, v), -1)) / (2 * h)
        dv = (np.stack(flank.point(u, v + h), -1) - np.stack(flank.point(u, v - h), -1)) / (2 * h)
        cross = np.cross(du, dv)
        cross /= np.linalg.norm(cross, axis=-1, keepdims=True)
        np.testing.assert_allclose(np.abs(dot(cross, s.normals)), 1.0, atol=1e-5)
        theta = np.arctan2(s.points[..., 1], s.points[..., 0])
        e_theta = np.stack([-np.sin(theta), np.cos(theta), np.zeros_like(theta)], -1)
        assert np.all(sign * dot(s.normals, e_theta) > 0)


def test_worm_flanks_start_on_their_form_circle(worm_set):
    """The worm flank's domain starts at the root, or 1e-4 of the depth outside the form
    circle when that lies above the root; its points and their first and second derivatives
    are finite over the whole domain (edges included) and, for a ZI worm, the form radius is
    the base radius r1·cos(atan(tan(alpha_n)/sin(gamma)))."""
    raw, parts = worm_set
    for worm in parts.worm.values():
        (u0, u1), _ = worm.domain
        root, form = worm.root_diameter / 2, worm.form_radius
        assert u0 == (root if form <= root else form + 1e-4 * (u1 - form))
        s = worm.evaluate(*worm.grid(101, 5))
        for array in (s.points, s.r_u, s.r_v, s.r_uu, s.r_uv, s.r_vv):
            assert np.all(np.isfinite(array))
        if worm.form == "ZI":
            alpha_t = math.atan(math.tan(worm.pressure_angle) / math.sin(worm.lead_angle))
            assert worm.form_radius == pytest.approx(
                worm.reference_radius * math.cos(alpha_t), rel=1e-12)
