"""Worm set teeth bending (contact.compliance: WheelToothCompliance, ThreadCompliance):
the slices against independent geometry (the involute a straight-sided worm generates in
the wheel's mid-plane, the straight axial profile of a ZA thread, the blank's tip torus)
and the loaded contact's extra approach against the bounds of a Pasternak line."""

from __future__ import annotations

import math
import tomllib

import numpy as np
import pytest
from mutations import CASES

from toothcontact import worm_gearset
from toothcontact.analyses import analyse, contact
from toothcontact.case import parse_case
from toothcontact.contact.compliance import (ThreadCompliance, ToothCompliance,
                                             WheelToothCompliance)
from toothcontact.surfaces.involute import CylindricalGear


def eps_case(**analysis):
    with open(CASES / "worm_eps_oversized_hob.toml", "rb") as f:
        raw = tomllib.load(f)
    raw.setdefault("analysis", {}).update(analysis)
    return parse_case(raw)


@pytest.fixture(scope="module")
def worm_set():
    case = eps_case()
    parts = worm_gearset.worm_set(case)
    flank = case.load.flank
    wheel_material = case.wheel_material or case.material
    worm, wheel = parts.worm[flank], parts.wheel[flank]
    return (case, worm, wheel, ThreadCompliance(worm, case.material.E, case.material.nu),
            WheelToothCompliance(wheel, wheel_material.E, wheel_material.nu))


class BeamToothCompliance(ToothCompliance):
    """A gear's slices as the beam gives them, without the finite-element correction."""

    corrected = False


def test_the_wheel_slice_is_the_involute_a_za_worm_generates(worm_set):
    """A ZA worm's axial section is a straight rack of the axial pressure angle α_x, so
    the wheel's mid-plane section is the involute of a helical gear of z2 teeth, transverse
    module m_x and pressure angle α_x, helix angle γ: the slice's half-thickness on the
    flank equals that gear's within 1 µm. Below the flank (the hob tip's generated edge)
    the slice is continued straight to the root circle, thinner than the rack-generated
    fillet, so its compliance lies above the gear's, by less than 25 % (measured 4 % at the
    root to 18 % at the tip). Both slices as the beam gives them: a wheel tooth is not
    corrected to finite elements (compliance.SLICE_FACTOR), so the gear's is taken
    uncorrected too."""
    case, worm, wheel, _, teeth = worm_set
    assert worm.form == "ZA"
    gamma, alpha_x = worm.lead_angle, case.worm.pressure_angle
    gear = CylindricalGear(wheel.teeth, worm.axial_module * math.cos(gamma),
                           math.atan(math.tan(alpha_x) * math.cos(gamma)), wheel.face_width,
                           helix_angle=gamma, profile_shift=wheel.profile_shift)
    equivalent = BeamToothCompliance(gear, teeth.E, teeth.nu)
    radii = np.linspace(max(teeth.radii[0], equivalent.radii[0]),
                        min(teeth.radii[-1], equivalent.radii[-1]), 7)
    for r in radii:
        assert teeth.half_thickness(r) == pytest.approx(equivalent.half_thickness(r), abs=1e-3)
    ratio = teeth.at(radii)[0] / equivalent.at(radii)[0]
    assert np.all((ratio > 1.0) & (ratio < 1.25)), ratio


def test_the_thread_slice_is_the_za_axial_profile(worm_set):
    """A ZA thread's axial section is straight: half-thickness s_x/2 - (r - r1)·tan α_x,
    s_x = π·m_x/2 (1e-9 mm). Steel thread against bronze wheel: at mid-depth the thread
    gives less than half as much as the wheel tooth; both profile matrices positive
    definite."""
    case, worm, wheel, thread, teeth = worm_set
    alpha_x, r1 = case.worm.pressure_angle, worm.reference_radius
    for r in np.linspace(thread.radii[0], thread.radii[-1], 5):
        expected = math.pi * worm.axial_module / 4 - (r - r1) * math.tan(alpha_x)
        assert thread.half_thickness(r) == pytest.approx(expected, abs=1e-9)
    middle_thread = 0.5 * (thread.radii[0] + thread.radii[-1])
    meets = wheel.centre_distance - middle_thread            # the wheel's radius facing it
    assert thread.at(middle_thread)[0] < 0.5 * teeth.at(meets)[0]
    for t in (thread, teeth):
        assert np.linalg.eigvalsh(t.matrix).min() > 0


def test_a_point_on_the_wheel_tip_loads_the_slice_at_its_tip(worm_set):
    """The blank's tip is a torus of tube radius a - r_a2 about the throat circle, and the
    wheel flank's tip edge (u = 0) runs just beyond it (the flank keeps a thin strip of
    envelope past the blank, under 0.1 mm): at every axial position the edge maps to the
    mid-plane tip radius r_a2 within that strip, although its distance from the wheel axis
    varies by more than 0.5 mm over the face; the mid-plane maps to itself (1e-9 mm). The
    tip's rounding takes its drop off the edge (its radius falls by at most that)."""
    _, _, wheel, _, teeth = worm_set
    half = 0.5 * wheel.face_width
    v = np.linspace(-0.6 * half, 0.6 * half, 7)
    radius, face, share = teeth.coordinates(wheel, np.zeros_like(v), v)
    tip = 0.5 * wheel.tip_diameter
    rounded = float(wheel.normal_drop(np.array(0.0), np.array(0.0)))
    assert np.all((radius > tip - rounded) & (radius < tip + 0.1)), radius - tip
    x, y, _ = wheel.point(np.zeros_like(v), v)
    assert np.ptp(np.hypot(x, y)) > 0.5
    assert np.allclose(face, v, atol=1e-9)
    assert np.all((share > 0.8) & (share <= 1.0))
    u = np.linspace(0.1, 0.9, 5)
    x, y, _ = wheel.point(u, np.zeros_like(u))
    assert np.allclose(teeth.coordinates(wheel, u, np.zeros_like(u))[0], np.hypot(x, y),
                       atol=1e-9)


def test_the_bending_adds_what_a_pasternak_line_allows():
    """The loaded worm set's approach with the teeth bending, less the half-space's alone,
    against the bounds of a Pasternak line (free ends, compliance c, coupling length λ,
    face b) under a load F spread over part of it: at most c·F/(2λ) (the Green's
    function's peak, a point load far from the ends; a free end doubles it, so 2·c·F/(2λ)
    with the wheel's largest c and smallest λ over the working depth), at least c·F/b
    (Cauchy-Schwarz with the uniform load, which deflects every slice by c·q; the wheel's
    smallest c, the thread's long line adding more)."""
    case = eps_case(positions=3)
    bent = analyse(case).sections["positions"]
    original = contact.loaded_sections
    try:
        contact.loaded_sections = lambda cycle, C_E, grid, teeth, text, result: original(
            cycle, C_E, grid, None, text, result)
        rigid = analyse(case).sections["positions"]
    finally:
        contact.loaded_sections = original
    parts = worm_gearset.worm_set(case)
    worm, wheel = parts.worm[case.load.flank], parts.wheel[case.load.flank]
    material = case.wheel_material or case.material
    teeth = WheelToothCompliance(wheel, material.E, material.nu)
    thread = ThreadCompliance(worm, case.material.E, case.material.nu)
    c_min = min(c.total for c in teeth.table)
    most = sum(max(c.total / c.coupling_length for c in t.table) for t in (teeth, thread))
    for with_bending, without in zip(bent, rigid):
        F = with_bending["bem_load_N"]
        if not F:
            continue
        extra = with_bending["bem_approach_mm"] - without["bem_approach_mm"]
        assert c_min * F / wheel.face_width < extra < most * F, (extra, F)
