"""Worm-set blank defaults that agree with each other (issue 11): every legal set of required
fields gives a valid wheel, checked against relations computed here from the worm's and the
blank's diameters; designs that cannot be made get one message naming the field."""

import itertools
import math

import numpy as np
import pytest

from toothcontact import worm_gearset
from toothcontact.analyses import analyse
from toothcontact.case import CaseError, parse_case

FORMS = ("ZA", "ZN", "ZI", "ZK")
#: the analyses here read the contact's own rows and summary: without the positions check
#: and the stresses below the contacts (another pass and a stage they do not read)
QUIET = {"positions_check": False, "subsurface": False}


def worm_case(form, starts, lead_deg, teeth, module, length=None, **wheel):
    """A worm case with only the required fields (and `wheel` extras). The default length
    covers the mesh: 1.25 times the chord of the wheel's tip circle at the worm's tip
    cylinder, plus one lead."""
    mx = module / math.cos(math.radians(lead_deg))
    r1 = starts * mx / math.tan(math.radians(lead_deg)) / 2
    if length is None:
        a, ra2 = r1 + teeth * mx / 2, teeth * mx / 2 + mx
        length = 1.25 * 2 * math.sqrt(ra2 ** 2 - (a - r1 - mx) ** 2) + starts * math.pi * mx
    return {"kind": "worm",
            "worm": {"form": form, "starts": starts, "normal_module": f"{module} mm",
                     "lead_angle": f"{lead_deg} deg", "pressure_angle": "20 deg",
                     "length": f"{length:.3f} mm"},
            "wheel": {"teeth": teeth, **wheel}}


GRID = [(form, z1, lead, z2, module)
        for (form, z1, lead), z2, module in zip(
            itertools.product(FORMS, (1, 2, 4), (3.0, 22.0)),
            itertools.cycle((20, 45, 80, 31)), itertools.cycle((0.5, 2.0, 6.0)))]


@pytest.mark.parametrize("form,starts,lead,teeth,module", GRID)
def test_defaults_give_a_valid_wheel(form, starts, lead, teeth, module):
    """With only the required fields: b2 = 2·sqrt(r_a1² - r1²) (Mott's chord; narrower, but
    not below half of it, where the hob's tip stops generating the root on its mid-face
    contact: large lead angles), inside the worm's reach 2·sqrt(r_a1² - (a - d_e2/2)²);
    d_a2 <= d_e2 < 2a, r_k = a - d_a2/2 > 0; the
    wheel flank exists over its whole domain (no NaN on a 9 × 9 grid), lies on the face
    planes at v = ±b2/2, and mostly inside the blank (the rest a thin strip past its tip)."""
    case = parse_case(worm_case(form, starts, lead, teeth, module))
    parts = worm_gearset.worm_set(case)
    for side in ("left", "right"):
        worm, wheel = parts.worm[side], parts.wheel[side]
        r1, ra1 = worm.pitch_diameter / 2, worm.tip_diameter / 2
        a, de2 = wheel.centre_distance, wheel.outside_diameter
        chord = 2 * math.sqrt(ra1 ** 2 - r1 ** 2)
        assert 0.5 * chord < wheel.face_width <= chord * (1 + 1e-12)
        if lead < 20:
            assert wheel.face_width == pytest.approx(chord, rel=1e-12)
        assert 0 < wheel.face_width < 2 * math.sqrt(ra1 ** 2 - (a - de2 / 2) ** 2)
        assert wheel.tip_diameter <= de2 < 2 * a
        assert wheel.throat_radius == pytest.approx(a - wheel.tip_diameter / 2, rel=1e-12)
        assert wheel.throat_radius > 0
        u, v = wheel.grid(9, 9)
        P = np.stack(wheel.point(u, v), axis=-1)
        assert np.all(np.isfinite(P))
        np.testing.assert_allclose(P[:, 0, 2], -wheel.face_width / 2, atol=1e-9)
        assert wheel.inside_blank(P).mean() > 0.85


def test_small_worm_diameter_factor_seed_case():
    """The issue's case: a 1-start ZA worm, mn = 1 mm, lead angle 8.6° (q = 6.6), z2 = 28,
    was refused ("face width 5.581 mm must lie in (0, 2 r_k = 4.665 mm)"); its geometry now
    runs, with Mott's face width wider than the throat (its faces cut the outside cylinder)."""
    raw = worm_case("ZA", 1, 8.6, 28, 1.0, length=30.0)
    result = analyse(parse_case(raw))
    wheel = result.sections["wheel"]
    assert wheel["face_width_mm"] == pytest.approx(5.581, abs=1e-3)
    assert wheel["face_width_mm"] > 2 * wheel["throat_radius_mm"]


@pytest.mark.parametrize("raw,field", [
    (worm_case("ZA", 1, 25.0, 40, 2.0), "worm.lead_angle"),  # d1 inside the thread depth
    (worm_case("ZI", 2, 10.0, 40, 2.0, hob_pitch_diameter="20 mm"), "wheel.hob_pitch_diameter"),
    (worm_case("ZA", 1, 5.0, 40, 2.0, face_width="40 mm"), "wheel.face_width"),
])
def test_impossible_designs_name_the_field(raw, field):
    """Designs that cannot be made end in one CaseError (exit 2 upstream) that names the
    field, never in an internal error."""
    with pytest.raises(CaseError, match=field.replace(".", r"\.")):
        analyse(parse_case(raw))


def test_margins_beyond_two_edges_at_once_stay_the_size_of_the_ellipse():
    """A 2-start ZA worm (m 2 mm, 18.6°, 60 mm long) on a 60-tooth wheel: at roll 0 one
    ellipse runs past the wheel's face end and root at once, where the wheel's surface
    continued beyond both edges is no flank (its speed grows without bound). Its margins
    were -107 mm (a wheel tooth 4.5 mm deep); measured from the flank's nearest line, at
    the edge's speed beyond it, every margin of every contact is now no more negative than
    the contact's own length across the pattern (2 × the rigid semi-axis)."""
    raw = {**worm_case("ZA", 2, 18.6, 60, 2.0, length=60.0),
           "wheel_material": {"E": "98 GPa", "nu": 0.35}, "load": {"output_torque": "49 N*m"},
           "analysis": QUIET}
    rows = analyse(parse_case(raw)).sections["positions"]
    for r in rows:
        reach = 2.0 * max(r["rigid_a_mm"] or 0.0, r["a_mm"] or 0.0)
        assert all(m >= -reach for m in r["edge_margins_mm"].values()), (r["roll_deg"], r["pair"])


def test_a_worm_shorter_than_the_wheels_generating_zone_is_cut_by_a_longer_hob():
    """The hob is a tool of its own: where the worm is shorter than the zone that generates
    the wheel's face, the hob (the worm's thread) is lengthened to cover it, 5 % over, and
    the wheel it cuts is the very wheel a long worm cuts as its own hob (the envelope
    depends on the thread, not the hob's length): the same points to 1e-9 mm. An 8 mm
    worm (one lead of 6.3 mm and a little) then meshes over its own length: its end
    carries the load, and the analysis says so instead of refusing the design."""
    short, long = (worm_gearset.worm_set(parse_case(worm_case("ZI", 1, 5.0, 40, 2.0, length=n)))
                   for n in (8.0, 60.0))
    for side in ("left", "right"):
        cut, reference = short.wheel[side], long.wheel[side]
        low, high = cut.generating_zone
        assert cut.hob.length == pytest.approx(1.05 * 2 * max(-low, high), rel=1e-9)
        assert cut.hob.length > 8.0 and reference.hob is long.worm[side].base
        u, v = cut.grid(9, 9)
        assert np.abs(cut.evaluate(u, v).points - reference.evaluate(u, v).points).max() < 1e-9
    raw = {**worm_case("ZI", 1, 5.0, 40, 2.0, length=8.0), "load": {"output_torque": "20 N*m"},
           "analysis": QUIET}
    summary = analyse(parse_case(raw)).sections["summary"]
    assert summary["worst_face_edge"].startswith("worm_end")
    assert summary["worst_face_edge_margin_mm"] < 0 and summary["edge_loaded_contacts"] > 0
