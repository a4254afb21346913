"""Hertz point and line contact against independent computations and printed cases."""

import math

import numpy as np
import pytest
from scipy.integrate import quad
from scipy.optimize import brentq

from toothcontact.analytic import agma, hertz

STEEL = hertz.compliance(206000.0, 0.3, 206000.0, 0.3)


def displacement_integrals(a, b, p0, C_E):
    """A, B and the approach of an ellipsoidal pressure p0·sqrt(1 - x²/a² - y²/b²) by direct
    quadrature of the potential integral (Johnson §3.6, after Love 1929):
    u(x, y) = (p0·a·b·C_E/2) ∫0^∞ (1 - x²/(a²+w) - y²/(b²+w)) dw / sqrt((a²+w)(b²+w)w).
    No elliptic-integral routine is used, so this is independent of the solver."""
    scale = 0.5 * p0 * a * b * C_E

    def integral(f):
        # substitution w = t² removes the 1/sqrt(w) singularity
        val, _ = quad(lambda t: 2.0 * f(t * t) / math.sqrt((a * a + t * t) * (b * b + t * t)),
                      0, np.inf, epsabs=0, epsrel=1e-12, limit=500)
        return val

    return (scale * integral(lambda w: 1.0 / (a * a + w)),
            scale * integral(lambda w: 1.0 / (b * b + w)),
            scale * integral(lambda w: 1.0))


@pytest.mark.parametrize("ratio", [1.0, 1.0 + 1e-7, 1.5, 4.0, 40.0, 400.0, 1e4])
def test_exact_hertz_matches_independent_quadrature(ratio):
    A, load = 0.02, 1500.0
    c = hertz.hertz_point(A, ratio * A, load, STEEL)
    A_q, B_q, approach_q = displacement_integrals(c.a, c.b, c.p0, STEEL)
    assert c.a >= c.b
    assert A_q == pytest.approx(A, rel=1e-6)
    assert B_q == pytest.approx(ratio * A, rel=1e-6)
    assert approach_q == pytest.approx(c.approach, rel=1e-6)
    assert 2.0 / 3.0 * math.pi * c.a * c.b * c.p0 == pytest.approx(load, rel=1e-12)


@pytest.mark.parametrize("cos_theta", np.linspace(0.0, 0.9999, 23))
def test_roark_form_equals_exact(cos_theta):
    total = 0.2  # sum of the four curvatures, 1/mm
    exact = hertz.hertz_point(0.25 * total * (1 - cos_theta), 0.25 * total * (1 + cos_theta),
                              900.0, STEEL)
    roark = hertz.roark_point(total, cos_theta * total, 900.0, STEEL)
    for field in ("a", "b", "p0", "approach"):
        assert getattr(roark, field) == pytest.approx(getattr(exact, field), rel=1e-6)


# Roark-type coefficients xi (= alpha) and eta (= beta), as printed to 3 significant digits
# in the Schaeffler Technisches Taschenbuch pp. 255-256 (transcribed in the GitHub project
# janwenzel/Dynamic-Contact-Simulation-for-Locating-Bearing-Track-Rollers, Hertz.py).
SCHAEFFLER = [(0.1, 1.07, 0.938), (0.2, 1.15, 0.879), (0.3, 1.24, 0.824), (0.4, 1.35, 0.771),
              (0.5, 1.48, 0.718), (0.6, 1.66, 0.664), (0.7, 1.91, 0.607), (0.8, 2.30, 0.544),
              (0.9, 3.09, 0.461), (0.95, 4.12, 0.396), (0.99, 7.76, 0.287),
              (0.995, 10.15, 0.251), (0.9995, 23.95, 0.163)]


@pytest.mark.parametrize("cos_theta,alpha,beta", SCHAEFFLER)
def test_roark_coefficients_against_printed_table(cos_theta, alpha, beta):
    a, b, _ = hertz.roark_coefficients(cos_theta)
    # the table is printed to three digits and carries a few last-digit slips: 0.5 %
    assert a == pytest.approx(alpha, rel=5e-3)
    assert b == pytest.approx(beta, rel=5e-3)


def test_roark_coefficients_at_the_sphere():
    assert hertz.roark_coefficients(0.0) == pytest.approx((1.0, 1.0, 0.75), rel=1e-12)


def test_sphere_on_rigid_flat_kim_sankar():
    """Kim & Sankar, Introduction to Finite Element Analysis and Design (2009): r = 8 mm,
    F = 60π N, E = 1 GPa, nu = 0.3 on a rigid wall; printed a = 1.010 mm."""
    C_E = hertz.compliance(1000.0, 0.3, 1e12, 0.3)
    c = hertz.hertz_point(1 / 16, 1 / 16, 60 * math.pi, C_E)
    assert abs(c.a - 1.010) <= 0.0005


def test_two_spheres_code_aster_ssnv104():
    """Code_Aster validation SSNV104 (two spheres R = 50 mm, E = 20000 MPa, nu = 0.3, total
    approach 4 mm): printed a = 10 mm and p0 = 2798.3 MPa."""
    C_E = hertz.compliance(20000.0, 0.3, 20000.0, 0.3)
    A = 0.5 * (1 / 50 + 1 / 50)

    def approach_error(load):
        return hertz.hertz_point(A, A, load, C_E).approach - 4.0

    c = hertz.hertz_point(A, A, brentq(approach_error, 1e3, 1e7, xtol=1e-6), C_E)
    assert abs(c.a - 10.0) <= 0.005
    assert abs(c.p0 - 2798.3) <= 0.05


def test_crossed_equal_cylinders_are_a_sphere_on_a_flat():
    """Johnson §4.2: equal cylinders crossed at 90° touch like a sphere of the same radius
    on a flat: a = (3PR/(4E*))^(1/3), p0 = 3P/(2πa²), approach = a²/R."""
    R, P = 10.0, 2000.0
    rc = hertz.relative_curvature((1 / R, 0.0), (1 / R, 0.0), math.pi / 2)
    c = hertz.hertz_point(rc.A, rc.B, P, STEEL)
    a = (3 * P * R * STEEL / 4) ** (1 / 3)
    assert c.a == pytest.approx(a, rel=1e-12)
    assert c.b == pytest.approx(a, rel=1e-12)
    assert c.p0 == pytest.approx(3 * P / (2 * math.pi * a * a), rel=1e-12)
    assert c.approach == pytest.approx(a * a / R, rel=1e-12)


@pytest.mark.parametrize("seed", range(5))
def test_relative_curvature_closed_form_and_direction(seed):
    rng = np.random.default_rng(seed)
    k1, k2 = rng.uniform(0.01, 0.5, 2), rng.uniform(-0.005, 0.3, 2)
    psi = rng.uniform(0, math.pi)
    rc = hertz.relative_curvature(tuple(k1), tuple(k2), psi)
    d1, d2 = k1[0] - k1[1], k2[0] - k2[1]
    assert rc.A + rc.B == pytest.approx(0.5 * (k1.sum() + k2.sum()), rel=1e-12)
    assert rc.B - rc.A == pytest.approx(
        0.5 * math.sqrt(d1 * d1 + d2 * d2 + 2 * d1 * d2 * math.cos(2 * psi)), rel=1e-9)

    def gap_curvature(phi):  # normal curvature of the gap along phi, from both bodies
        body1 = k1[0] * math.cos(phi) ** 2 + k1[1] * math.sin(phi) ** 2
        body2 = k2[0] * math.cos(phi - psi) ** 2 + k2[1] * math.sin(phi - psi) ** 2
        return 0.5 * (body1 + body2)

    assert gap_curvature(rc.angle) == pytest.approx(rc.A, rel=1e-9)
    assert gap_curvature(rc.angle + math.pi / 2) == pytest.approx(rc.B, rel=1e-9)


def test_concave_body_tighter_than_convex_is_rejected():
    with pytest.raises(ValueError, match="do not make point contact"):
        hertz.relative_curvature((1 / 6.0, 1 / 6.0), (-1 / 5.0, -1 / 5.0))


def test_agma_contact_stress_is_hertz_line_contact():
    """Seed 003 eq (3)-(5) is Hertz's cylinder contact with w = Wt/(F·cos phi)."""
    rho1, rho2, phi, d, F, Wt = 11.2, 29.8, math.radians(20), 60.0, 30.0, 8000.0
    I = agma.geometry_factor(rho1, rho2, phi, d, internal=False)
    Sc = agma.contact_stress(agma.elastic_coefficient(STEEL), Wt, d, F, I)
    line = hertz.hertz_line(Wt / (F * math.cos(phi)), 1 / (1 / rho1 + 1 / rho2), STEEL)
    assert Sc == pytest.approx(line.p0, rel=1e-12)


def test_line_contact_half_width_closed_form():
    """Johnson eq 4.45: p0 = 2w/(π b)."""
    line = hertz.hertz_line(250.0, 8.0, STEEL)
    assert line.p0 == pytest.approx(2 * 250.0 / (math.pi * line.b), rel=1e-12)


def test_bundled_ball_in_race_case_against_quadrature():
    """Hamrock's deep-groove bearing (bundled case): the solver's ellipse reproduces the
    gap curvatures of ball and race by independent quadrature."""
    from toothcontact.runner import analyse_file, bundled_cases_dir

    h = analyse_file(bundled_cases_dir() / "hertz_ball_in_race.toml")["hertz"]
    A = 0.5 * (1 / 6.35 - 1 / 6.604)
    B = 0.5 * (1 / 6.35 + 1 / 26.1455)
    assert (h["A_per_mm"], h["B_per_mm"]) == pytest.approx((A, B), rel=1e-12)
    C_E = hertz.compliance(200000.0, 0.3, 200000.0, 0.3)
    A_q, B_q, approach_q = displacement_integrals(h["a_mm"], h["b_mm"], h["p_max_MPa"], C_E)
    assert (A_q, B_q, approach_q) == pytest.approx((A, B, h["approach_mm"]), rel=1e-6)
