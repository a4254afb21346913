"""Worm thread flanks ZA, ZN, ZI, ZK: each form's defining property checked from the points
and normals alone (root finding on `point`, finite differences, an independently built
grinding wheel), not by re-running the module's formulas. Lengths in mm, angles in rad."""

import math

import numpy as np
import pytest
from scipy.optimize import brentq

from toothcontact.surfaces.worm import WormFlank

ALPHA = math.radians(20.0)
GAMMA_SEED = math.radians(4.1)
WORMS = {  # seed worm set: z1 = 1, mn = 1.1 mm, gamma = 4.1°; and a 2-start worm
    "seed_z1": dict(starts=1, axial_module=1.1 / math.cos(GAMMA_SEED),
                    pitch_diameter=1 * 1.1 / math.cos(GAMMA_SEED) / math.tan(GAMMA_SEED),
                    length=25.0),
    "z2_mx1.75": dict(starts=2, axial_module=1.75, pitch_diameter=20.0, length=30.0),
}
FORMS = ("ZA", "ZN", "ZI", "ZK")


def make(form, worm="z2_mx1.75", hand="right", side="left", **kwargs):
    return WormFlank(form, hand=hand, side=side, pressure_angle=ALPHA, **WORMS[worm], **kwargs)


def xyz(flank, u, v):
    return np.stack(np.broadcast_arrays(*flank.point(np.asarray(u, float),
                                                     np.asarray(v, float))), axis=-1)


def roots(fun, lo, hi, n=6001, max_jump=np.inf):
    """All sign changes of a vectorised scalar function on [lo, hi], refined by brentq."""
    t = np.linspace(lo, hi, n)
    g = fun(t)
    idx = np.nonzero((np.sign(g[:-1]) != np.sign(g[1:])) & (np.abs(g[:-1]) < max_jump)
                     & (np.abs(g[1:]) < max_jump))[0]
    scalar = lambda s: float(fun(np.array([s]))[0])  # noqa: E731
    return [brentq(scalar, t[i], t[i + 1], xtol=1e-15, rtol=1e-15) for i in idx]


def axial_z(flank, r, theta, z_near):
    """z where the flank's points of radius r cross the half-plane at polar angle theta,
    the crossing nearest z_near: found from `point` alone (scan in v, then brentq)."""
    v0, v1 = flank.domain[1]

    def angle_error(v):
        p = xyz(flank, r, v)
        return np.angle(np.exp(1j * (np.arctan2(p[..., 1], p[..., 0]) - theta)))

    zs = [xyz(flank, r, v)[2] for v in roots(angle_error, v0 - 7, v1 + 7, max_jump=1.0)]
    return min(zs, key=lambda z: abs(z - z_near))


def screw(points, phi, p):
    """Rotate by phi about z and translate by p·phi along z (p in mm/rad)."""
    c, s = math.cos(phi), math.sin(phi)
    x, y, z = np.moveaxis(points, -1, 0)
    return np.stack([c * x - s * y, s * x + c * y, z + p * phi], axis=-1)


def flanks_all():
    return [(f, w, h) for f in FORMS for w in WORMS for h in ("right", "left")]


# --- parameterisation contract ------------------------------------------------------------
@pytest.mark.parametrize("form,worm,hand", flanks_all())
def test_parameterisation_and_worm_data(form, worm, hand):
    """u = radius, z = p·v, the domain ends are the planes z = ±L/2 and the root (or form)
    and tip cylinders; lead, lead angle and p from the DIN 3975 definitions (1e-12)."""
    w = WORMS[worm]
    fl = make(form, worm, hand)
    mx, d1, z1 = w["axial_module"], w["pitch_diameter"], w["starts"]
    assert fl.lead == pytest.approx(z1 * math.pi * mx, rel=1e-14)
    assert fl.axial_pitch == pytest.approx(math.pi * mx, rel=1e-14)
    assert math.tan(fl.lead_angle) == pytest.approx(z1 * mx / d1, rel=1e-14)
    sign = 1 if hand == "right" else -1
    assert fl.screw_parameter == pytest.approx(sign * fl.lead / (2 * math.pi), rel=1e-14)
    (u0, u1), (v0, v1) = fl.domain
    root, tip = (d1 - 2.4 * mx) / 2, (d1 + 2 * mx) / 2
    start = root if fl.form_radius <= root else fl.form_radius + 1e-4 * (tip - fl.form_radius)
    assert (u0, u1) == pytest.approx((start, tip), rel=1e-14)
    u, v = fl.grid(5, 7)
    p = xyz(fl, u, v)
    np.testing.assert_allclose(np.hypot(p[..., 0], p[..., 1]), u, rtol=1e-13)
    np.testing.assert_allclose(p[..., 2], fl.screw_parameter * v, rtol=1e-14)
    z_v0 = fl.screw_parameter * v0
    assert z_v0 == pytest.approx(-w["length"] / 2 if fl.edges["v0"] == "end_A" else w["length"] / 2)
    assert fl.edges["u0"] == ("form" if fl.form_radius > root else "root")
    assert fl.edges["u1"] == "tip"
    assert {fl.edges["v0"], fl.edges["v1"]} == {"end_A", "end_B"}


def test_from_lead_angle_seed_worm():
    fl = WormFlank.from_lead_angle("ZI", 1, GAMMA_SEED, normal_module=1.1, length=25.0)
    assert fl.lead_angle == pytest.approx(GAMMA_SEED, rel=1e-14)
    assert fl.normal_module == pytest.approx(1.1, rel=1e-14)
    assert fl.pitch_diameter == pytest.approx(WORMS["seed_z1"]["pitch_diameter"], rel=1e-14)
    with pytest.raises(ValueError):
        WormFlank("ZX", 1, 1.0, 10.0, length=5.0)


# --- 1. ZA ---------------------------------------------------------------------------------
@pytest.mark.parametrize("worm", WORMS)
@pytest.mark.parametrize("side", ["left", "right"])
def test_za_axial_section_is_a_straight_line_at_alpha_x(worm, side):
    """Points of the flank in the axial half-plane at polar angle 0.7 rad: line residual
    < 1e-9 mm, inclination to the radial direction = alpha_x (1e-12 rad)."""
    fl = make("ZA", worm, side=side)
    r = np.linspace(*fl.domain[0], 9)
    z = np.array([axial_z(fl, ri, 0.7, fl.screw_parameter * 0.7) for ri in r])
    A = np.stack([np.ones_like(r), r], axis=1)
    coef, *_ = np.linalg.lstsq(A, z, rcond=None)
    assert np.abs(A @ coef - z).max() < 1e-9
    assert math.atan(coef[1]) == pytest.approx(ALPHA if side == "left" else -ALPHA, abs=1e-12)


# --- 2. ZN ---------------------------------------------------------------------------------
@pytest.mark.parametrize("worm", WORMS)
@pytest.mark.parametrize("hand", ["right", "left"])
def test_zn_normal_section_of_the_space_is_straight(worm, hand):
    """DIN 3975 normal section of the thread space: the plane through the radial line at the
    middle Q of the space on the reference cylinder (d_m1 = d1), normal to the reference helix
    through Q. Both flanks bounding the space (left flank of the thread at z = 0, right flank
    of the previous thread = right flank shifted by -px) cut it in straight lines (residual
    < 1e-9 mm) at ±alpha_n to the radial line (1e-12 rad), symmetric about it (1e-12 mm)."""
    left, right = make("ZN", worm, hand, "left"), make("ZN", worm, hand, "right")
    r1, p, px = left.reference_radius, left.screw_parameter, left.axial_pitch
    zq = 0.5 * (axial_z(left, r1, 0.0, 0.0) + axial_z(right, r1, 0.0, 0.0) - px)
    Q = np.array([r1, 0.0, zq])
    N = np.array([0.0, r1, p]) / math.hypot(r1, p)  # normal to the helix tangent (0, r1, p)
    t = np.cross([1.0, 0.0, 0.0], N)
    for flank, shift, sign in ((left, 0.0, 1), (right, -px, -1)):
        pts = []
        for u in np.linspace(*left.domain[0], 9):
            def g(v):
                return (xyz(flank, u, v) + [0, 0, shift] - Q) @ N
            v0, v1 = flank.domain[1]
            cands = [xyz(flank, u, v) + [0, 0, shift] for v in roots(g, v0, v1)]
            pts.append(min(cands, key=lambda c: np.linalg.norm(c - Q)))
        pts = np.array(pts) - Q
        xi, eta = pts[:, 0], pts @ t
        np.testing.assert_allclose(pts @ N, 0.0, atol=1e-12)
        A = np.stack([np.ones_like(xi), xi], axis=1)
        coef, *_ = np.linalg.lstsq(A, eta, rcond=None)
        assert np.abs(A @ coef - eta).max() < 1e-9
        assert sign * math.atan(coef[1]) == pytest.approx(ALPHA, abs=1e-12)
        if sign == 1:
            eta_left = coef[0]
        else:
            assert coef[0] == pytest.approx(-eta_left, abs=1e-12)


# --- 3. ZI ---------------------------------------------------------------------------------
@pytest.mark.parametrize("worm", WORMS)
@pytest.mark.parametrize("hand", ["right", "left"])
@pytest.mark.parametrize("side", ["left", "right"])
def test_zi_is_an_involute_helicoid(worm, hand, side):
    """Every normal line touches the base cylinder (distance to the axis = r_b, 1e-9 mm);
    r_b agrees with cos(gamma_b) = cos(gamma)·cos(alpha_n), tan(gamma_b) = |p|/r_b (1e-12);
    the normal profile angle at d1, asin(|n·e_r|), is alpha_n (1e-12 rad)."""
    fl = make("ZI", worm, hand, side)
    gamma_b = math.acos(math.cos(fl.lead_angle) * math.cos(ALPHA))
    assert fl.base_radius == pytest.approx(abs(fl.screw_parameter) / math.tan(gamma_b), rel=1e-12)
    u, v = fl.grid(7, 9)
    s = fl.evaluate(u, v)
    P, n = s.points, s.normals
    ez_x_n = np.cross([0.0, 0.0, 1.0], n)
    dist = np.abs(np.einsum("...i,...i", P, ez_x_n)) / np.linalg.norm(ez_x_n, axis=-1)
    np.testing.assert_allclose(dist, fl.base_radius, atol=1e-9)
    s1 = fl.evaluate(np.full(5, fl.reference_radius), np.linspace(-3, 3, 5))
    e_r = s1.points / fl.reference_radius * [1, 1, 0]
    np.testing.assert_allclose(np.arcsin(np.abs(np.einsum("...i,...i", s1.normals, e_r))),
                               ALPHA, atol=1e-12)


# --- 4. all forms --------------------------------------------------------------------------
@pytest.mark.parametrize("form,worm,hand", flanks_all())
def test_helical_symmetry(form, worm, hand):
    """Points screwed by phi (rotation phi, translation p·phi = ±lead·phi/2pi) lie on the
    flank again: their z equals the flank's z in their own axial half-plane (1e-9 mm)."""
    fl = make(form, worm, hand)
    u, v = fl.grid(4, 3)
    P = xyz(fl, u, v * 0.5).reshape(-1, 3)
    for phi in (0.37, -2.9):
        for q in screw(P, phi, fl.screw_parameter):
            r, th = math.hypot(q[0], q[1]), math.atan2(q[1], q[0])
            assert axial_z(fl, r, th, q[2]) == pytest.approx(q[2], abs=1e-9)


@pytest.mark.parametrize("form,worm,hand", flanks_all())
def test_axial_thickness_at_d1(form, worm, hand):
    """Left and right flank of the thread at z = 0 in the axial planes at 0 and 1.1 rad:
    thickness pi·mx/2 at d1 (1e-9 mm); at polar angle 0 the thread is centred on z = 0."""
    left, right = make(form, worm, hand, "left"), make(form, worm, hand, "right")
    r1, s = left.reference_radius, math.pi * left.axial_module / 2
    for th in (0.0, 1.1):
        zl = axial_z(left, r1, th, left.screw_parameter * th)
        zr = axial_z(right, r1, th, zl + s)
        assert zr - zl == pytest.approx(s, abs=1e-9)
        if th == 0.0:
            assert zl + zr == pytest.approx(0.0, abs=1e-9)


def fd_curvatures(fl, u, v, h=2e-3):
    """Principal curvatures from fourth-order central differences of the points (step h in
    mm and rad) and the shape operator I^-1 II (independent of FlankSample); the normal is
    (r_u × r_v)/|r_u × r_v| of the differences."""
    P = lambda i, j: xyz(fl, u + i * h, v + j * h)  # noqa: E731
    w1 = {-2: 1 / 12, -1: -8 / 12, 1: 8 / 12, 2: -1 / 12}  # d/dx, times 1/h
    w2 = {-2: -1 / 12, -1: 16 / 12, 0: -30 / 12, 1: 16 / 12, 2: -1 / 12}  # d²/dx², times 1/h²
    ru = sum(w * P(i, 0) for i, w in w1.items()) / h
    rv = sum(w * P(0, j) for j, w in w1.items()) / h
    ruu = sum(w * P(i, 0) for i, w in w2.items()) / h**2
    rvv = sum(w * P(0, j) for j, w in w2.items()) / h**2
    ruv = sum(wi * wj * P(i, j) for i, wi in w1.items() for j, wj in w1.items()) / h**2
    n = np.cross(ru, rv)
    n /= np.linalg.norm(n, axis=-1, keepdims=True)
    d = lambda a, b: np.einsum("...i,...i", a, b)  # noqa: E731
    I = np.stack([d(ru, ru), d(ru, rv), d(ru, rv), d(rv, rv)], -1).reshape(-1, 2, 2)
    II = -np.stack([d(ruu, n), d(ruv, n), d(ruv, n), d(rvv, n)], -1).reshape(-1, 2, 2)
    k = np.sort(np.linalg.eigvals(np.linalg.solve(I, II)).real, axis=-1)
    return n.reshape(-1, 3), k


@pytest.mark.parametrize("form,worm,hand", flanks_all())
@pytest.mark.parametrize("side", ["left", "right"])
def test_curvature_and_normals(form, worm, hand, side):
    """Principal curvatures of FlankSample = those of a fourth-order difference fit (h = 2e-3;
    rtol 1e-5, atol 1e-6 of the largest |k|); normals along ±(r_u × r_v) of the differences
    (1e-8), and pointing out of the material: n_z < 0 on the left flank, > 0 on the right,
    and a step of 0.05 mm along +n lands in the thread space, along -n inside the thread."""
    fl = make(form, worm, hand, side)
    (u0, u1), _ = fl.domain
    u, v = np.meshgrid(np.linspace(u0 + 0.05, u1 - 0.05, 5), np.linspace(-3.0, 3.0, 4),
                       indexing="ij")
    s = fl.evaluate(u, v)
    k1, k2, _, _ = s.principal_curvatures()
    n_fd, k_fd = fd_curvatures(fl, u, v)
    sign = np.sign(np.einsum("...i,...i", n_fd, s.normals.reshape(-1, 3)))
    assert np.all(sign == sign[0])
    np.testing.assert_allclose(s.normals.reshape(-1, 3), sign[0] * n_fd, atol=1e-8)
    k_fd = sign[0] * k_fd[:, ::-1] if sign[0] < 0 else k_fd
    scale = np.abs(k_fd).max()
    np.testing.assert_allclose(k1.ravel(), k_fd[:, 0], rtol=1e-5, atol=1e-6 * scale)
    np.testing.assert_allclose(k2.ravel(), k_fd[:, 1], rtol=1e-5, atol=1e-6 * scale)
    nz = s.normals[..., 2]
    assert np.all(nz < 0) if side == "left" else np.all(nz > 0)
    # out of the material, checked against both flanks of the thread (points only)
    other = make(form, worm, hand, "right" if side == "left" else "left")
    lf, rf = (fl, other) if side == "left" else (other, fl)
    thick = math.pi * fl.axial_module / 2
    for P, n in zip(s.points[::2, ::3].reshape(-1, 3), s.normals[::2, ::3].reshape(-1, 3)):
        for step, inside in ((0.05, False), (-0.05, True)):
            X = P + step * n
            r, th = math.hypot(X[0], X[1]), math.atan2(X[1], X[0])
            zl = axial_z(lf, r, th, X[2] - (0 if side == "left" else thick))
            zr = axial_z(rf, r, th, zl + thick)
            assert (zl < X[2] < zr) == inside


# --- 5. ZK ---------------------------------------------------------------------------------
def cone_distance_and_normal(wheel_centre, axis, rw, alpha0, zeta_ref, X):
    """Signed distance of X from the cone side zeta = zeta_ref + (rw - rho)·tan(alpha0) and
    the cone's unit normal at the foot point (built here from the DIN 3975 wheel)."""
    w = X - wheel_centre
    zeta = w @ axis
    radial = w - zeta * axis
    rho = np.linalg.norm(radial)
    e_rho = radial / rho
    tau = math.tan(alpha0)
    dist = (zeta + tau * rho - zeta_ref - rw * tau) / math.hypot(1.0, tau)
    normal = (tau * e_rho + axis) / math.hypot(1.0, tau)
    return dist, normal


@pytest.mark.parametrize("worm", WORMS)
@pytest.mark.parametrize("hand", ["right", "left"])
@pytest.mark.parametrize("side", ["left", "right"])
def test_zk_is_the_envelope_of_the_grinding_wheel(worm, hand, side, wheel_diameter=250.0):
    """The wheel: centre distance D/2 + d1/2, axis square to the common perpendicular (x) and
    to the reference helix at the space centre (crossing angle = lead angle), centre at the
    space centre (1e-12). For every worm point there is a screw position of the worm in which
    its normal line meets the wheel axis; there the point lies on the cone (|distance| < 1e-9
    mm), the normals coincide (1e-9) and the meshing equation n·v12 = 0 holds (< 1e-10 mm/rad,
    v12 = e_z × r + p e_z)."""
    fl = make("ZK", worm, hand, side, wheel_diameter=wheel_diameter)
    other = make("ZK", worm, hand, "right" if side == "left" else "left",
                 wheel_diameter=wheel_diameter)
    wheel = fl.grinding_wheel
    r1, p, px = fl.reference_radius, fl.screw_parameter, fl.axial_pitch
    zl = axial_z(fl if side == "left" else other, r1, 0.0, 0.0)
    zr = axial_z(other if side == "left" else fl, r1, 0.0, 0.0)
    zq = 0.5 * (zl + zr - px) if side == "left" else 0.5 * (zl + px + zr)
    C, k = wheel.centre, wheel.axis
    assert wheel.centre_distance == pytest.approx(fl.wheel_diameter / 2 + r1, rel=1e-14)
    np.testing.assert_allclose(C, [fl.wheel_diameter / 2 + r1, 0.0, zq], atol=1e-12)
    assert np.linalg.norm(k) == pytest.approx(1.0, rel=1e-14) and abs(k[0]) < 1e-15
    assert math.acos(abs(k[2])) == pytest.approx(fl.lead_angle, abs=1e-13)
    assert k @ np.array([0.0, r1, p]) == pytest.approx(0.0, abs=1e-12)
    assert wheel.radius == fl.wheel_diameter / 2 and wheel.profile_angle == ALPHA

    u, v = fl.grid(6, 5)
    s = fl.evaluate(u, v)
    for W, n in zip(s.points.reshape(-1, 3), s.normals.reshape(-1, 3)):
        # screw positions with the point near the wheel: polar angle within ±0.6 rad of 0
        th_w = math.atan2(W[1], W[0])
        phi0 = th_w + 2 * math.pi * round((W[2] - zq - p * th_w) / (2 * math.pi * p))

        def moved(phi):
            return screw(W, -phi, p), screw(n, -phi, 0.0)

        def h(phis):
            out = []
            for phi in phis:
                X, m = moved(phi)
                out.append((X - C) @ np.cross(m, k))
            return np.array(out)

        found = []
        for phi in roots(h, phi0 - 0.6, phi0 + 0.6, n=241):
            X, m = moved(phi)
            dist, nc = cone_distance_and_normal(C, k, wheel.radius, wheel.profile_angle,
                                                wheel.half_width, X)
            found.append((abs(dist), X, m, nc))
        assert len(found) == 1  # one wheel position within ±0.6 rad
        dist, X, m, nc = found[0]
        assert dist < 1e-9
        assert np.linalg.norm(np.cross(m, nc)) < 1e-9
        v12 = np.array([-X[1], X[0], p])
        assert abs(nc @ v12) < 1e-10


@pytest.mark.parametrize("wheel_diameter", [30.0, 3000.0])
@pytest.mark.parametrize("hand", ["right", "left"])
def test_zk_envelope_with_a_small_or_large_grinding_wheel(wheel_diameter, hand):
    """The contact line's branch (psi near 0 of A cos psi + B sin psi = D, B < 0 for either
    hand) holds for a grinding wheel of 1.5 worm diameters and of 150: the same envelope
    checks as for the default 250 mm wheel."""
    test_zk_is_the_envelope_of_the_grinding_wheel("z2_mx1.75", hand, "left", wheel_diameter)


def ground_boundary(fl, r, phis=np.linspace(-1.6, 1.6, 6401)):
    """z (mm) of the left flank at radius r in the axial half-plane y = 0, x > 0 as the
    grinding wheel leaves it, found without the contact line: the wheel is the solid
    |zeta| + tan(alpha0)·rho <= half_width + radius·tan(alpha0), rho <= a - r_f (its tip
    grinds the root cylinder), built from `grinding_wheel` alone. For each screw position phi
    of the worm the line (r cos phi, r sin phi, t) meets this convex solid in an interval
    (golden-section search for a point inside, bisection for its upper end); the flank is
    the highest upper end screwed back, max(t - p·phi)."""
    W = fl.grinding_wheel
    C, k, tau = W.centre, W.axis, math.tan(W.profile_angle)
    c, rho_t, p = W.half_width + W.radius * tau, W.centre_distance - fl.root_diameter / 2, \
        fl.screw_parameter

    def g(t):  # <= 0 inside the wheel, convex along each line
        w = np.stack([r * np.cos(phis), r * np.sin(phis), t], -1) - C
        zeta = w @ k
        rho = np.sqrt(np.maximum((w * w).sum(-1) - zeta ** 2, 0.0))
        return np.maximum(np.abs(zeta) + tau * rho - c, rho - rho_t)

    lo, hi = np.full_like(phis, C[2] - 20.0), np.full_like(phis, C[2] + 20.0)
    golden = (math.sqrt(5) - 1) / 2
    for _ in range(90):
        a, b = hi - golden * (hi - lo), lo + golden * (hi - lo)
        left = g(a) < g(b)
        hi, lo = np.where(left, b, hi), np.where(left, lo, a)
    inside = 0.5 * (lo + hi)
    ok = g(inside) < 0
    lo, hi = inside, inside + 40.0
    for _ in range(70):
        mid = 0.5 * (lo + hi)
        out = g(mid) > 0
        hi, lo = np.where(out, mid, hi), np.where(out, lo, mid)
    return float(np.max(np.where(ok, lo - p * phis, -np.inf)))


@pytest.mark.parametrize("starts,q,hand", [(4, 5.0, "right"), (1, 10.0, "left"), (2, 6.0, "right")])
def test_zk_form_radius_is_where_the_ground_boundary_leaves_the_flank(starts, q, hand):
    """Above the form radius the flank's axial profile is the boundary the wheel grinds
    (`ground_boundary`, < 2e-6 mm); 0.01 mx below it the ground boundary leaves the
    profile's continuation (> 2e-5 mm) or the continuation does not exist. Designs: a
    4-start worm with q = 5 (26.6°; the wheel's tip edge cuts into the flank, 0.87 mx above
    the root), a 1-start q = 10 worm (the wheel's tip corner rounds the root, 0.013 mx) and
    a 2-start q = 6 worm (the contact line turns back, 0.27 mx)."""
    mx = 2.0
    fl = WormFlank("ZK", starts, mx, q * mx, length=40.0, hand=hand, pressure_angle=ALPHA)
    left = fl if hand == "right" else WormFlank("ZK", starts, mx, q * mx, length=40.0,
                                                pressure_angle=ALPHA)
    form = fl.form_radius
    assert form > fl.root_diameter / 2
    assert fl.domain[0][0] == pytest.approx(form + 1e-4 * (fl.tip_diameter / 2 - form), rel=1e-15)
    assert form == pytest.approx(left.form_radius, rel=1e-12)  # the hand is a mirror image
    for r in (form + 0.001 * mx, form + 0.05 * mx, fl.reference_radius):
        assert abs(ground_boundary(left, r) - float(left.axial_profile(np.array(r)))) < 2e-6
    below = form - 0.01 * mx
    profile = float(left.axial_profile(np.array(below)))
    assert math.isnan(profile) or abs(ground_boundary(left, below) - profile) > 2e-5


def test_zk_profile_is_nan_where_there_is_no_contact_line():
    """Far outside the worm (radii a contact search may probe: -1e8 ... 5e9 mm, or 0.1 mm)
    the ZK profile is NaN, as a point, a jet and a third-order Taylor number; inside the
    domain it is finite everywhere."""
    from toothcontact.surfaces.jet import Jet

    fl = make("ZK", "z2_mx1.75")
    wild = np.array([-1e8, 0.1, 1e6, 5e9])
    assert np.all(np.isnan(fl.axial_profile(wild)))
    u, v = Jet.variables(wild, np.zeros(4))
    assert np.all(np.isnan(value_of(fl.point(u, v)[0])))
    r = np.linspace(*fl.domain[0], 101)
    assert np.all(np.isfinite(fl.axial_profile(r)))


def value_of(x):
    return np.asarray(getattr(x, "f", x), float)


# --- 6. hand -------------------------------------------------------------------------------
@pytest.mark.parametrize("form", FORMS)
@pytest.mark.parametrize("worm", WORMS)
@pytest.mark.parametrize("side", ["left", "right"])
def test_left_hand_is_the_mirror_image(form, worm, side):
    """Mirror y -> -y: the left-hand flank meets the half-plane at -theta where the right-hand
    flank meets the one at theta (1e-9 mm); at mirrored points (u, -v) the left-hand normals
    are the mirrored right-hand normals (1e-12), still out of the material."""
    rh, lh = make(form, worm, "right", side), make(form, worm, "left", side)
    for r in np.linspace(*rh.domain[0], 3):
        for th in (0.3, -2.0):
            z = axial_z(rh, r, th, 1.0)
            assert axial_z(lh, r, -th, z) == pytest.approx(z, abs=1e-9)
    u, v = rh.grid(4, 5)
    a, b = rh.evaluate(u, v), lh.evaluate(u, -v)
    M = np.array([1.0, -1.0, 1.0])
    np.testing.assert_allclose(b.points, a.points * M, atol=1e-12)
    np.testing.assert_allclose(b.normals, a.normals * M, atol=1e-12)
    for ka, kb in zip(a.principal_curvatures()[:2], b.principal_curvatures()[:2]):
        np.testing.assert_allclose(kb, ka, rtol=1e-10, atol=1e-12)
