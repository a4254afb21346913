"""Crowned splines: Dudley's rule and stress, seed 003 eq (19) against a tilted-tooth check."""

import math

import pytest

from toothcontact.analytic import hertz, spline

INCH, LBF, PSI = 25.4, 4.4482216152605, 0.00689475729


def test_dudley_stress_reduces_to_2290_for_steel():
    """Dudley: sigma = 2290·sqrt(2T/(D·N·h·r1)) psi for steel (E = 30e6 psi, nu = 0.3)."""
    T, D, N, h, r1 = 478.0, 0.5625, 18, 0.028, 71.6  # lbf·in, in
    C_E = hertz.compliance(30e6 * PSI, 0.3, 30e6 * PSI, 0.3)
    ours = spline.dudley_contact_stress(T * LBF * INCH, D * INCH, N, h * INCH, r1 * INCH, C_E)
    dudley = 2290 * math.sqrt(2 * T / (D * N * h * r1)) * PSI
    assert ours == pytest.approx(dudley, rel=5e-4)  # 2290 is sqrt(E*/π) rounded to 4 digits


def test_dudley_crown_drop_matches_the_circle():
    """C1 = (A/2)·tan(theta) and r1 = A²/(8·C1): the circle of radius r1 drops C1 over A/2
    (to second order in C1/A, the parabolic approximation Dudley makes)."""
    A, theta = 12.7, math.radians(0.1)
    C1, r1 = spline.dudley_crown(A, theta)
    exact_drop = r1 - math.sqrt(r1**2 - (A / 2) ** 2)
    assert exact_drop == pytest.approx(C1, rel=2 * C1 / A)


@pytest.mark.parametrize("theta_deg", [0.05, 0.1, 0.5, 2.0])
def test_eq19_radius_closes_the_clearance_exactly(theta_deg):
    """At the eq (19) radius the tilted crowned tooth touches the space walls (zero
    clearance), found by rotating the flank arc numerically; 1 % flatter does not fit."""
    T, dT, theta = 0.049 * INCH, 0.002 * INCH, math.radians(theta_deg)
    R = spline.max_crown_radius_for_fit(T, dT, theta)
    long_enough = 2 * R * math.sin(theta)
    assert spline.tilted_tooth_clearance(R, T, dT, theta, long_enough) == pytest.approx(0.0, abs=1e-9)
    assert spline.tilted_tooth_clearance(1.01 * R, T, dT, theta, long_enough) < -1e-7
    assert spline.tilted_tooth_clearance(0.99 * R, T, dT, theta, long_enough) > 1e-7


def test_the_tooth_load_factor_is_the_largest_tooth_load_over_the_mean():
    """analyses.spline.tooth_loads on hand numbers: two positions of a 4-tooth spline, the
    first with loads 30, 10, 0, 0 N (2 teeth in contact, mean 10 N over all 4 teeth,
    factor 3), the second 10 N each (factor 1); a position whose solve failed leaves the
    figures None."""
    from toothcontact.analyses.spline import tooth_loads

    rows = [{"roll_deg": r, "bem_load_N": v} for r, loads in ((-1.0, (30.0, 10.0, 0.0, 0.0)),
                                                             (1.0, (10.0,) * 4))
            for v in loads]
    summary = {}
    tooth_loads(rows, 4, summary)
    first, second = summary["tooth_loads"]
    assert (first["teeth_in_contact"], first["mean_tooth_load_N"],
            first["largest_tooth_load_N"], first["tooth_load_factor"]) == (2, 10.0, 30.0, 3.0)
    assert second["tooth_load_factor"] == 1.0
    assert summary["tooth_load_factor"] == 3.0
    rows[0]["bem_load_N"] = None
    tooth_loads(rows, 4, summary)
    assert summary["tooth_loads"][0]["tooth_load_factor"] is None
    assert summary["tooth_load_factor"] is None
