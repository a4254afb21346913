"""Involute flanks and their modifications against closed forms."""

import math

import numpy as np
import pytest
from scipy.optimize import brentq

from toothcontact.surfaces.modify import EndRelief, FlankModifications, LeadCrown, ProfileCrown, TipRelief
from toothcontact.surfaces.generation import generate_side
from toothcontact.surfaces.involute import CylindricalGear
from toothcontact.surfaces.modified import ModifiedFlank

GEARS = {
    "spur": CylindricalGear(20, 3.0, math.radians(20), 30.0),
    "helical RH": CylindricalGear(23, 2.5, math.radians(20), 25.0, helix_angle=math.radians(20)),
    "helical LH shifted": CylindricalGear(31, 2.0, math.radians(25), 20.0,
                                          helix_angle=math.radians(12), hand="left", profile_shift=0.3),
    "ring": CylindricalGear(60, 3.0, math.radians(20), 30.0, internal=True),
    "helical ring": CylindricalGear(71, 2.0, math.radians(20), 20.0, helix_angle=math.radians(15),
                                    internal=True),
}


def active_grid(flank, nu=9, nv=5):
    (u0, u1), (v0, v1) = flank.domain
    return np.meshgrid(np.linspace(u0 + 0.02 * (u1 - u0), u1, nu), np.linspace(v0, v1, nv), indexing="ij")


@pytest.mark.parametrize("name", GEARS)
@pytest.mark.parametrize("side", [1, -1])
def test_profile_radius_of_curvature_is_sqrt_r2_minus_rb2(name, side):
    """Transverse radius of curvature of an involute = sqrt(r² - rb²); on the helicoid the
    profile-normal principal curvature is cos(beta_b)/sqrt(r² - rb²), the other zero
    (Litvin & Fuentes §14.3). Sign: convex (+) outside, concave (-) on a ring gear."""
    gear = GEARS[name]
    flank = gear.flank(side)
    s = flank.evaluate(*active_grid(flank))
    rho = np.sqrt(np.sum(s.points[..., :2] ** 2, axis=-1) - gear.base_radius**2)
    k1, k2, _, _ = s.principal_curvatures()
    curved, straight = (k1, k2) if gear.internal else (k2, k1)
    sign = -1.0 if gear.internal else 1.0
    np.testing.assert_allclose(curved * rho, sign * math.cos(gear.base_helix_angle), rtol=1e-9)
    np.testing.assert_allclose(straight, 0.0, atol=1e-12)
    # transverse section: curvature of the z = const curve is 1/rho (planar curve in z)
    transverse = s.r_u[..., 0] * s.r_uu[..., 1] - s.r_u[..., 1] * s.r_uu[..., 0]
    speed = np.linalg.norm(s.r_u[..., :2], axis=-1)
    np.testing.assert_allclose(np.abs(transverse) / speed**3 * rho, 1.0, rtol=1e-9)


@pytest.mark.parametrize("name", GEARS)
def test_closed_form_normal_matches_cross_product(name):
    flank = GEARS[name].flank(1)
    u, v = active_grid(flank)
    n = np.stack(flank.unit_normal(u, v), axis=-1)
    np.testing.assert_allclose(n, flank.evaluate(u, v).normals, atol=1e-13)


@pytest.mark.parametrize("name", GEARS)
def test_normals_leave_the_tooth(name):
    """Both flank normals point away from tooth 0's centre line (angularly)."""
    for side in (1, -1):
        flank = GEARS[name].flank(side)
        s = flank.evaluate(*active_grid(flank, 3, 3))
        angular = np.stack([-s.points[..., 1], s.points[..., 0]], axis=-1)
        assert np.all(side * np.einsum("...i,...i", s.normals[..., :2], angular) > 0)


@pytest.mark.parametrize("name", GEARS)
def test_base_pitch_between_adjacent_teeth(name):
    """The normal line of a flank point meets the same-side flank of the next tooth one
    transverse base pitch further on (measured in the transverse plane), to 1e-9 mm."""
    gear = GEARS[name]
    flank = gear.flank(1)
    (u0, u1), _ = flank.domain
    t0 = u0 + 0.3 * (u1 - u0)
    p = np.array(flank.transverse_point(t0))
    nx, ny, _ = flank.unit_normal(t0, 0.0)
    n = np.array([nx, ny]) / math.hypot(nx, ny)
    found = []
    for step in (2 * math.pi / gear.teeth, -2 * math.pi / gear.teeth):
        rot = np.array([[math.cos(step), -math.sin(step)], [math.sin(step), math.cos(step)]])

        def off_line(t, rot=rot):  # signed distance of the other tooth's point from the line
            d = rot @ np.array(flank.transverse_point(t)) - p
            return d[0] * n[1] - d[1] * n[0]

        ts = np.linspace(0.0, u1 + 1.0, 400)
        vals = np.array([off_line(t) for t in ts])
        for i in np.flatnonzero(np.sign(vals[:-1]) != np.sign(vals[1:])):
            t1 = brentq(off_line, ts[i], ts[i + 1], xtol=1e-15)
            found.append(np.linalg.norm(rot @ np.array(flank.transverse_point(t1)) - p))
    # the nearest same-side flank along the normal lies one base pitch away
    assert min(found) == pytest.approx(gear.base_pitch, abs=1e-9)


def test_rack_generated_involute_and_fillet_join():
    """The rack's straight flank generates the exact involute; the generated fillet ends on
    the root circle and meets the involute at the form circle (continuous, tangent)."""
    gear = GEARS["helical RH"]
    side = generate_side(gear)
    assert not side.undercut
    r_end = np.hypot(*side.fillet[-1])
    assert r_end == pytest.approx(side.form_radius, rel=1e-12)
    assert np.hypot(*side.fillet[0]) == pytest.approx(gear.root_radius_value, rel=1e-12)
    flank = gear.flank(1, side.form_radius)
    start = np.array(flank.transverse_point(flank.domain[0][0]))
    np.testing.assert_allclose(side.fillet[-1], start, atol=1e-9)
    fillet_dir = side.fillet[-1] - side.fillet[-2]
    fillet_dir /= np.linalg.norm(fillet_dir)
    flank_dir = np.array(flank.transverse_point(flank.domain[0][0] + 1e-6)) - start
    flank_dir /= np.linalg.norm(flank_dir)
    assert np.dot(fillet_dir, flank_dir) > 0.999


@pytest.mark.parametrize("z,x,expected", [(12, 0.0, True), (12, 0.3, False), (17, 0.0, True),
                                          (18, 0.0, False), (14, 0.2, False)])
def test_undercut_limit(z, x, expected):
    """Classical limit: no undercut while x >= x_min = h* - z·sin²(alpha)/2, with h* the
    depth of the rack's straight flank below its reference line, h_fP* - rho_fP*(1 - sin a)."""
    gear = CylindricalGear(z, 2.0, math.radians(20), 10.0, profile_shift=x)
    h_rack = gear.dedendum - gear.root_radius * (1 - math.sin(math.radians(20)))
    x_min = h_rack - z * math.sin(math.radians(20)) ** 2 / 2
    assert (x < x_min) == expected
    assert generate_side(gear).undercut == expected


def rack_margin(gear, P, phi):
    """How deep (mm, > 0 inside) the transverse point P of the gear lies in the generating
    rack tooth at the rolling position phi (array): the gear turned by phi, the rack moved by
    r·phi along its pitch line. The rack is rebuilt here from ISO 53 in the transverse
    section: flanks at alpha_t, tooth pi·m_t/2 thick on its reference line (r + x·m from the
    gear axis, centred on the space after tooth 0), tip at the dedendum, and its tip rounding
    an ellipse (rho deep, rho/cos(beta) along the pitch line) tangent to the tip line and
    the flank."""
    r, m, mt = gear.pitch_radius, gear.normal_module, gear.transverse_module
    alpha, beta = gear.transverse_pressure_angle, gear.helix_angle
    rho, ry = gear.root_radius * m, gear.root_radius * m / math.cos(beta)
    x_ref = r + gear.profile_shift * m
    x_tip = x_ref - gear.dedendum * m
    c, s = np.cos(phi), np.sin(phi)
    X = c * P[0] - s * P[1]
    d = np.abs(s * P[0] + c * P[1] - r * phi - 0.5 * math.pi * mt)
    w = 0.25 * math.pi * mt - (x_ref - X) * math.tan(alpha)  # half-thickness at X
    x_c = x_tip + rho
    d_c = 0.25 * math.pi * mt - (x_ref - x_c) * math.tan(alpha) - math.hypot(
        rho * math.tan(alpha), ry)  # the ellipse's centre: tangent to the flank line
    flank = (w - d) * math.cos(alpha)
    tip = X - x_tip
    q = np.hypot((X - x_c) / rho, (d - d_c) / ry)
    corner = np.where((X < x_c) & (d > d_c), (1.0 - q) * rho, np.inf)
    return np.minimum(np.minimum(flank, tip), corner)


def form_radius_by_rolling(gear):
    """The form radius found by rolling the rack past the involute: the largest radius at
    which some rack position cuts into the involute's point (depth > 1e-10 mm; the best of
    50001 positions in ±1.5 rad, refined by a bounded scalar search), by bisection
    between the base and tip circles. The involute's polar angle at radius R is
    s/(2r) + inv(alpha_t) - inv(acos(rb/R)) (ISO 21771)."""
    from scipy.optimize import minimize_scalar

    rb = gear.base_radius
    half = gear.tooth_thickness / (2 * gear.pitch_radius)
    inv = lambda a: math.tan(a) - a  # noqa: E731
    phis = np.linspace(-1.5, 1.5, 50001)

    def cut(R):
        theta = half + inv(gear.transverse_pressure_angle) - inv(math.acos(rb / R))
        P = R * np.array([math.cos(theta), math.sin(theta)])
        depth = rack_margin(gear, P, phis)
        k = int(np.argmax(depth))
        best = minimize_scalar(lambda f: -float(rack_margin(gear, P, np.array([f]))[0]),
                               bounds=(phis[max(k - 1, 0)], phis[min(k + 1, phis.size - 1)]),
                               method="bounded", options={"xatol": 1e-14})
        return max(depth[k], -best.fun) > 1e-10

    lo, hi = rb * (1 + 1e-12), gear.tip_radius
    assert cut(lo) and not cut(hi)
    for _ in range(45):
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if cut(mid) else (lo, mid)
    return 0.5 * (lo + hi)


@pytest.mark.parametrize("gear", [
    CylindricalGear(14, 2.0, math.radians(20), 20.0),
    CylindricalGear(10, 3.0, math.radians(20), 20.0, profile_shift=0.1),
    CylindricalGear(12, 1.5, math.radians(20), 15.0, helix_angle=math.radians(25)),
    CylindricalGear(13, 2.0, math.radians(14.5), 15.0, profile_shift=0.3),
], ids=["z14", "z10 x0.1", "helical z12", "z13 14.5deg"])
def test_undercut_form_radius_by_rolling_the_rack(gear):
    """On an undercut gear the generated root cuts into the involute above the base circle;
    the form radius (where the involute begins) is where rolling the rack past the involute
    stops cutting into it (`form_radius_by_rolling`, 1e-6 mm). The fillet ends there on the
    involute and starts on the root circle (1e-9 mm)."""
    side = generate_side(gear)
    assert side.undercut and side.form_radius > gear.base_radius
    assert side.form_radius == pytest.approx(form_radius_by_rolling(gear), abs=1e-6)
    flank = gear.flank(1, side.form_radius)
    np.testing.assert_allclose(side.fillet[-1], flank.transverse_point(flank.domain[0][0]),
                               atol=1e-9)
    assert np.hypot(*side.fillet[0]) == pytest.approx(gear.root_radius_value, abs=1e-9)


# --- modifications -----------------------------------------------------------------------

SPUR = GEARS["spur"]


@pytest.mark.parametrize("shape", ["circular", "parabolic"])
@pytest.mark.parametrize("name", ["spur", "helical RH"])
def test_lead_crown_drop_at_face_ends_equals_height(shape, name):
    """Measured independently: the distance from the crowned end point to the unmodified
    flank along its normal, in the transverse plane (ISO 21771)."""
    gear = GEARS[name]
    base = gear.flank(1, generate_side(gear).form_radius)
    crowned = ModifiedFlank(base, FlankModifications(lead_crown=LeadCrown(height=0.012, shape=shape)))
    (u0, u1), (v0, v1) = base.domain
    u = np.array([0.5 * (u0 + u1)] * 3)
    v = np.array([v0, 0.0, v1])
    moved = crowned.evaluate(u, v).points - base.evaluate(u, v).points
    n = base.evaluate(u, v).normals
    # transverse amount: component along the transverse projection of the normal
    nt = n[:, :2] / np.linalg.norm(n[:, :2], axis=-1, keepdims=True)
    transverse_drop = -np.einsum("ij,ij->i", moved[:, :2], nt)
    np.testing.assert_allclose(transverse_drop, [0.012 * math.cos(gear.base_helix_angle) ** 2, 0.0,
                                                 0.012 * math.cos(gear.base_helix_angle) ** 2],
                               atol=1e-12)


@pytest.mark.parametrize("shape", ["circular", "parabolic"])
@pytest.mark.parametrize("center", [0.0, 6.0])
def test_lead_crown_curvature_at_its_centre_is_one_over_R(shape, center):
    base = SPUR.flank(1, generate_side(SPUR).form_radius)
    crown = LeadCrown(radius=4000.0, shape=shape, center=center)
    crowned = ModifiedFlank(base, FlankModifications(lead_crown=crown))
    (u0, u1), _ = base.domain
    s = crowned.evaluate(np.array([0.5 * (u0 + u1)]), np.array([center]))
    assert s.normal_curvature(0.0, 1.0)[0] == pytest.approx(1 / 4000.0, rel=1e-9)
    assert crowned.drop(np.array([0.5 * (u0 + u1)]), np.array([center]))[0] == pytest.approx(0.0, abs=1e-15)


def test_crown_height_and_radius_agree_with_seed_eq12():
    L, h = 15.0, 0.012
    assert LeadCrown(height=h).radius_for(2 * L) == pytest.approx((h * h + L * L) / (2 * h), rel=1e-15)
    c = LeadCrown(radius=(h * h + L * L) / (2 * h))
    assert c.drop(np.array([L]), 2 * L)[0] == pytest.approx(h, rel=1e-9)


def test_profile_crown_tip_relief_and_end_relief_amounts():
    base = SPUR.flank(1, generate_side(SPUR).form_radius)
    s_form, s_tip = base.form_roll, base.tip_roll
    start = s_form + 0.7 * (s_tip - s_form)
    mods = FlankModifications(profile_crown=ProfileCrown(0.004),
                              tip_relief=TipRelief(0.010, start, "parabolic"),
                              end_relief=EndRelief(0.008, 3.0, "linear"))
    F = SPUR.face_width
    w = np.array([0.0, 0.0, 0.0, 0.5 * F, 0.5 * F - 1.5, 0.5 * F - 3.0])
    s = np.array([s_form, 0.5 * (s_form + s_tip), s_tip, 0.5 * (s_form + s_tip),
                  0.5 * (s_form + s_tip), 0.5 * (s_form + s_tip)])
    drop = mods.drop(w, s, F, s_form, s_tip)
    # the end relief's start blended (modify.RELIEF_BLEND, 0.2 of its length): 0.2/8 of the
    # amount there
    np.testing.assert_allclose(drop, [0.004, 0.0, 0.004 + 0.010, 0.008, 0.004, 0.008 * 0.2 / 8],
                               atol=1e-12)


@pytest.mark.parametrize("name", ["ring", "helical ring"])
def test_shaper_cut_ring_fillet_joins_the_involute(name):
    """The shaper cutter's flank generates the ring's exact involute (checked on cutter
    involute points through the same Willis solve), and its tip rounding a fillet from the
    root circle to the form circle, tangent to the flank there."""
    import math as m

    from toothcontact.surfaces.generation import _shaped, generate_ring_side, shaper_cutter_teeth

    gear = GEARS[name]
    side = generate_ring_side(gear)
    assert np.hypot(*side.fillet[0]) == pytest.approx(gear.root_radius_value, rel=1e-12)
    flank = gear.flank(1, side.form_radius)
    form_end = np.array(flank.transverse_point(flank.domain[0][1]))
    np.testing.assert_allclose(side.fillet[-1], form_end, atol=1e-9)
    n_flank = np.array(flank.unit_normal(flank.domain[0][1], 0.0))[:2]
    n_flank /= np.linalg.norm(n_flank)
    assert np.dot(side.fillet_normals[-1], n_flank) == pytest.approx(1.0, abs=1e-9)
    # cutter involute points generate points on the ring's involute (same base circle)
    zc = shaper_cutter_teeth(gear.teeth)
    mt, a = gear.transverse_module, gear.transverse_pressure_angle
    rc, r2 = 0.5 * zc * mt, gear.pitch_radius
    rbc = rc * m.cos(a)
    psi = (m.pi * mt - gear.tooth_thickness) / (2 * rc) + m.tan(a) - a
    t = np.linspace(0.3, 0.5, 5)
    ang = psi - t
    pts = rbc * np.stack([np.cos(ang) - t * np.sin(ang), np.sin(ang) + t * np.cos(ang)], -1)
    nrm = np.stack([np.sin(ang), -np.cos(ang)], -1)  # out of the cutter tooth (side +1)
    ring_pts, _ = _shaped(pts, nrm, r2 - rc, r2, rc)
    r = np.hypot(ring_pts[:, 0], ring_pts[:, 1])
    alpha = np.arccos(gear.base_radius / r)
    polar = np.arctan2(ring_pts[:, 1], ring_pts[:, 0])
    # the space centred on 0: its + side is the ring tooth's side -1 flank at +pi/z
    expected = m.pi / gear.teeth - (gear.base_half_angle + (np.tan(alpha) - alpha))
    np.testing.assert_allclose(polar, expected, atol=1e-12)


def test_a_ring_whose_default_cutter_would_be_pointed_is_cut_by_a_larger_one():
    """A 38-tooth 25° ring (x = 0.168, helix 11.39°): the default 12-tooth shaper cutter's
    tooth, as thick as the ring's space, ends in a point; the next cutter with a tip land
    cuts it, its fillet ends on the ring's form circle between its tip and root; a cutter
    tip too short for the rack's rounding gets a smaller one; a ring whose space no cutter
    fills is refused naming gear.profile_shift."""
    import math

    from toothcontact.surfaces.generation import (_shaper_cutter, generate_ring_side,
                                                  shaper_cutter_teeth)
    from toothcontact.surfaces.involute import CylindricalGear

    ring = CylindricalGear(38, 5.672, math.radians(25.0), 48.0, helix_angle=math.radians(11.39),
                           profile_shift=0.168, internal=True)
    default = shaper_cutter_teeth(38)
    assert _shaper_cutter(ring, default) is None
    side = generate_ring_side(ring)
    assert side.cutter_teeth > default and _shaper_cutter(ring, side.cutter_teeth) is not None
    assert ring.tip_radius < side.form_radius < ring.root_radius_value
    deep = CylindricalGear(38, 5.672, math.radians(25.0), 48.0, profile_shift=-1.5,
                           internal=True)   # a short cutter tip: the rounding shrinks to fit
    assert deep.tip_radius < generate_ring_side(deep).form_radius < deep.root_radius_value
    pointed = CylindricalGear(38, 5.672, math.radians(25.0), 48.0, profile_shift=1.0,
                              internal=True)
    with pytest.raises(ValueError, match="gear.profile_shift"):
        generate_ring_side(pointed)
