"""Shaft deflection (shaft.py) against closed-form beam and torsion results, and its way
into a gear pair's analysis."""

from __future__ import annotations

import math

import numpy as np
import pytest

from toothcontact.analyses import analyse
from toothcontact.case import CaseError, parse_case
from toothcontact.gearset import gear_pair
from toothcontact.shaft import Shaft, beam_deflection, shaft_deflection, twist

E, NU, D = 206000.0, 0.3, 30.0
EI = E * math.pi * D ** 4 / 64


def grid(lo, hi, n=8001):
    return np.linspace(lo, hi, n)


def point(z, at, value, axis=0):
    loads = np.zeros((z.size, 2))
    loads[int(np.argmin(np.abs(z - at))), axis] = value
    return loads


def test_a_point_load_between_the_bearings():
    """P at a from the left bearing of a span L (b = L - a): deflection under the load
    P·a²·b²/(3·E·I·L) along the load, in both planes (0.1 %)."""
    L, a, P = 120.0, 40.0, 5000.0
    shaft = Shaft((0.0, L), ((0.0, L, D),), E, NU)
    z = grid(0.0, L)
    for axis in (0, 1):
        u = beam_deflection(shaft, z, point(z, a, P, axis), np.zeros((z.size, 2)))
        expected = P * a ** 2 * (L - a) ** 2 / (3 * EI * L)
        assert np.interp(a, z, u[:, axis]) == pytest.approx(expected, rel=1e-3)
        assert np.allclose(u[:, 1 - axis], 0.0, atol=1e-12)


def test_yielding_bearings_move_the_shaft_by_their_reactions():
    """Bearings of radial stiffness k1, k2 under P at a from the first of a span L: each
    gives R_k/k_k along the load (R1 = P·b/L, R2 = P·a/L), so the deflection under the load
    is the rigid-bearing one plus the line through those, P·a²·b²/(3EIL) + (R1/k1)·b/L +
    (R2/k2)·a/L, and beyond the span the line carries on (0.1 %)."""
    L, a, P, k1, k2 = 120.0, 40.0, 5000.0, 2.0e5, 5.0e5
    b = L - a
    z = grid(0.0, L + 30.0)
    soft = Shaft((0.0, L), ((0.0, L + 30.0, D),), E, NU, "A", (k1, k2))
    u = beam_deflection(soft, z, point(z, a, P), np.zeros((z.size, 2)))[:, 0]
    R1, R2 = P * b / L, P * a / L
    expected = P * a ** 2 * b ** 2 / (3 * EI * L) + R1 / k1 * b / L + R2 / k2 * a / L
    assert np.interp(a, z, u) == pytest.approx(expected, rel=1e-3)
    assert np.interp(0.0, z, u) == pytest.approx(R1 / k1, rel=1e-3)
    assert np.interp(L, z, u) == pytest.approx(R2 / k2, rel=1e-3)
    rigid = beam_deflection(Shaft((0.0, L), ((0.0, L + 30.0, D),), E, NU), z, point(z, a, P),
                            np.zeros((z.size, 2)))[:, 0]
    line = R1 / k1 + (z - 0.0) * (R2 / k2 - R1 / k1) / L
    assert np.allclose(u - rigid, line, rtol=0.0, atol=1e-3 * np.abs(line).max())


def test_the_case_takes_one_bearing_stiffness_for_both_or_one_each():
    """`bearing_stiffness` in units: one value serves both bearings; three are refused."""
    one = gear_pair(parse_case(case({"bearings": ["-60 mm", "60 mm"], "diameter": "30 mm",
                                     "bearing_stiffness": ["400 N/um"]})))
    both = gear_pair(parse_case(case({"bearings": ["-60 mm", "60 mm"], "diameter": "30 mm",
                                      "bearing_stiffness": ["400 N/um", "400000 N/mm"]})))
    assert one.shafts["pinion"].bending == pytest.approx(both.shafts["pinion"].bending)
    with pytest.raises(CaseError, match="bearing_stiffness"):
        parse_case(case({"bearings": ["-60 mm", "60 mm"], "diameter": "30 mm",
                         "bearing_stiffness": ["1 N/um"] * 3}))


def test_a_uniform_load_over_the_span_and_an_overhung_load():
    """Uniform q over the span: 5qL⁴/(384EI) at mid-span; P on an overhang c beyond the
    right bearing: P·c²·(L + c)/(3EI) at its end (0.1 %)."""
    L, q = 120.0, 50.0
    shaft = Shaft((0.0, L), ((0.0, L, D),), E, NU)
    z = grid(0.0, L)
    loads = np.zeros((z.size, 2))
    loads[:, 0] = q * L / z.size
    u = beam_deflection(shaft, z, loads, np.zeros((z.size, 2)))
    assert np.interp(L / 2, z, u[:, 0]) == pytest.approx(5 * q * L ** 4 / (384 * EI), rel=1e-3)
    c, P = 40.0, 3000.0
    shaft = Shaft((0.0, L), ((0.0, L + c, D),), E, NU)
    z = grid(0.0, L + c)
    u = beam_deflection(shaft, z, point(z, L + c, P), np.zeros((z.size, 2)))
    assert u[-1, 0] == pytest.approx(P * c ** 2 * (L + c) / (3 * EI), rel=1e-3)


def test_a_couple_is_a_pair_of_forces():
    """A couple M about y at z0 deflects the shaft as two opposite forces ±M/e in x a
    distance e apart do (1 %), and a couple at a bearing turns that end by M·L/(3EI)."""
    L, M, z0, e = 120.0, 2.0e5, 50.0, 1.0
    shaft = Shaft((0.0, L), ((0.0, L, D),), E, NU)
    z = grid(0.0, L)
    couple = np.zeros((z.size, 2))
    couple[int(np.argmin(np.abs(z - z0))), 1] = M
    by_couple = beam_deflection(shaft, z, np.zeros((z.size, 2)), couple)
    pair = point(z, z0 + e / 2, M / e) + point(z, z0 - e / 2, -M / e)
    by_forces = beam_deflection(shaft, z, pair, np.zeros((z.size, 2)))
    assert np.max(np.abs(by_couple[:, 0] - by_forces[:, 0])) < 0.01 * np.max(np.abs(by_forces))
    couple[:] = 0.0
    couple[0, 1] = M
    u = beam_deflection(shaft, z, np.zeros((z.size, 2)), couple)
    slope = (u[1, 0] - u[0, 0]) / (z[1] - z[0])
    assert abs(slope) == pytest.approx(M * L / (3 * EI), rel=2e-3)


def test_the_body_twists_by_half_the_torque_over_the_face():
    """A torque handed evenly to the mesh along the face: the twist across the face is
    T·b/(2·G·J) (0.1 %), growing away from the torque's side."""
    b, T = 30.0, 2.4e5
    G, J = E / (2 * (1 + NU)), math.pi * D ** 4 / 32
    for side, sign in (("A", 1.0), ("B", -1.0)):
        shaft = Shaft((-60.0, 60.0), ((-60.0, 60.0, D),), E, NU, side)
        phi = twist(shaft, np.array([-b / 2, b / 2]), b, T)
        assert sign * (phi[1] - phi[0]) == pytest.approx(T * b / (2 * G * J), rel=1e-3)


def case(shaft: dict, **extra):
    return {"kind": "spur", "teeth": [20, 60], "module": "3 mm", "pressure_angle": "20 deg",
            "face_width": "30 mm", "pinion": {"crown": {"radius": "4000 mm"}, "shaft": shaft},
            "load": {"tangential_load": "8000 N"},
            "analysis": {"positions": 3, "interference": False,
                         "positions_check": False, "pressure_grid": 48}, **extra}


def test_a_pinion_shaft_under_an_even_load():
    """The pair's first estimate (the mesh force spread evenly over the face): a symmetric
    layout bends the pinion symmetrically (no bending slope; the face ends closer to the
    gear than mid-face, by the closed form of a beam under the face's load spread evenly,
    2 %), and the torque coming in at end A twists end B away: the torsion slope
    T·b/(2GJ)·r_b over b, as a least-squares slope of the quadratic twist (5 %)."""
    shaft = gear_pair(parse_case(case({"bearings": ["-60 mm", "60 mm"],
                                       "diameter": "30 mm"}))).shafts["pinion"]
    assert abs(shaft.bending_slope) < 1e-12
    F = 8000.0 / math.cos(math.radians(20))
    L, b, q = 120.0, 30.0, F / 30.0
    # mid-span minus 15 mm from it, for a load q over the middle b of a span L
    x = np.linspace(0.0, L, 12001)
    loads = np.where(np.abs(x - L / 2) <= b / 2, q * (x[1] - x[0]), 0.0)
    u = beam_deflection(Shaft((0.0, L), ((0.0, L, 30.0),), E, NU), x,
                        np.column_stack([loads, np.zeros_like(x)]), np.zeros((x.size, 2)))[:, 0]
    expected = np.interp(L / 2, x, u) - np.interp(L / 2 + b / 2, x, u)
    assert shaft.bending[-1] == pytest.approx(expected, rel=0.02)
    G, J = E / (2 * (1 + NU)), math.pi * 30.0 ** 4 / 32
    r_b = 30.0 * math.cos(math.radians(20))
    across = 8000.0 * 30.0 * b / (2 * G * J) * r_b
    assert shaft.torsion_slope < 0
    assert -shaft.torsion_slope * b == pytest.approx(across, rel=0.05)


def test_a_pinion_shaft_enters_the_analysis_as_its_deflection():
    """The analysis adds the shaft's deflection (under its final line load) to the pinion's
    and reports it: the summary's slopes are the section's."""
    result = analyse(parse_case(case({"bearings": ["-60 mm", "60 mm"], "diameter": "30 mm"})))
    section, summary = result.sections["shaft"]["pinion"], result.sections["summary"]
    assert summary["shaft_bending_slope_rad"] == section["bending_slope_rad"]
    assert summary["shaft_torsion_slope_rad"] == section["torsion_slope_rad"]
    assert section["bending_um"][-1] > 0 and section["bending_um"][0] > 0   # the ends closer


@pytest.mark.parametrize("shaft, field", [
    ({"bearings": ["-60 mm", "60 mm"]}, "diameter"),
    ({"bearings": ["-60 mm", "-60 mm"], "diameter": "30 mm"}, "bearings"),
    ({"bearings": ["-60 mm", "60 mm"], "sections": [["-60 mm", "0 mm", "30 mm"]]}, "sections"),
])
def test_a_shaft_that_cannot_be_built_is_refused(shaft, field):
    with pytest.raises(CaseError, match=field):
        analyse(parse_case(case(shaft)))


def test_a_line_load_rising_along_the_face():
    """Bearings at the face ends, the line load rising linearly from 0 at end A to q0 at
    end B (shaft_deflection with line_load): the deflection relative to mid-face follows
    the closed form y(x) = q0·x·(7L⁴ - 10L²x² + 3x⁴)/(360·E·I·L) (x from end A), to 0.5 % of
    its largest; the torque coming in at end A is taken as ζ² (ζ the distance from A over
    b), so the face twists by T·b·(2/3)/(G·J) (0.1 %)."""
    L, q0, T = 60.0, 400.0, 2.4e5
    shaft = Shaft((-L / 2, L / 2), ((-L / 2, L / 2, D),), E, NU, "A")
    face = np.linspace(-L / 2, L / 2, 13)
    line_load = (face, q0 * (face + L / 2) / L)
    force = np.array([q0 * L / 2, 0.0, 0.0])
    found = shaft_deflection(shaft, L, np.zeros(2), force, np.array([1.0, 0.0, 0.0]), 1.0,
                             T, points=61, line_load=line_load)
    x = found.face + L / 2
    y = q0 * x * (7 * L ** 4 - 10 * L ** 2 * x ** 2 + 3 * x ** 4) / (360 * EI * L)
    expected = y - y[len(y) // 2]
    assert np.max(np.abs(found.bending - expected)) < 5e-3 * np.max(np.abs(expected))
    G, J = E / (2 * (1 + NU)), math.pi * D ** 4 / 32
    phi = twist(shaft, np.array([-L / 2, L / 2]), L, T, line_load)
    assert phi[1] - phi[0] == pytest.approx(T * L * (2 / 3) / (G * J), rel=1e-3)


def test_the_shaft_settles_under_the_loaded_line_load():
    """A slender overhung pinion shaft under an uncrowned pair: the load piles up at one
    end, so the shaft's deflection under the loaded contact's line load differs from the
    even spread's by more than the tolerance; the analysis repeats, half a step at a time,
    until it settles (within 0.5 µm; measured 3.3, 2.6, 0.62, 0.31 µm over 4 passes) and
    says how many passes it took."""
    raw = case({"bearings": ["-120 mm", "20 mm"], "diameter": "24 mm"})
    del raw["pinion"]["crown"]
    result = analyse(parse_case(raw))
    section = result.sections["shaft"]
    assert section["passes"] >= 2
    assert section["changes_um"][0] > 0.5 >= section["changes_um"][-1]
    check = next(c for c in result.checks if c.name.startswith("shaft deflection settled"))
    assert check.ok


def test_a_centred_solid_pinion_against_iso_6336_f_sh():
    """ISO 6336-1:2006 §7.6 (Method C): the misalignment from the pinion's deformation,
    f_sh = F_m/b · 0.023 · [|B* + K'·l·s/d1²·(d1/d_sh)⁴ - 0.3| + 0.3] · (b/d1)² µm (B* = 1
    for a spur or single helical pair). A pinion centred between its bearings (s = 0) has
    no K' term: f_sh = 0.023·F_m·b/d1². Its 0.7 share (1 - 0.3) is the pinion body's twist
    over the face under the torque handed on evenly, 4·F_m·b/(π·G·d1²) = 0.0161 F_m·b/d1²
    with G = 79 200 MPa (0.7 · 0.023 = 0.0161); the 0.3 the standard adds for bending,
    which a centred pinion's symmetric deflection does not tilt. The model's solid pinion
    (shaft diameter d1) twists across the face by ISO's share times cos α (the model
    measures along the line of action, ISO at the reference circle) within 1 % (ISO's
    constant has two digits), and its bending has no slope."""
    F_t, b, d1 = 8000.0, 30.0, 60.0
    pair = gear_pair(parse_case(case({"bearings": ["-60 mm", "60 mm"], "diameter": "60 mm"})))
    shaft = pair.shafts["pinion"]
    f_sh = F_t / b * 0.023 * (abs(1.0 - 0.3) + 0.3) * (b / d1) ** 2          # µm
    torsion_share = 0.7 * f_sh * math.cos(pair.working_pressure_angle)
    assert -shaft.torsion_slope * b * 1e3 == pytest.approx(torsion_share, rel=0.01)
    assert abs(shaft.bending_slope) < 1e-12
