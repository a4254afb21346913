"""Backlash: the teeth thinned for a normal backlash j_bn, the backlash of the pair as cut
and placed (ISO 21771), the default of ISO/TR 10064-2, the gear placed on its working flanks,
and the back flanks found when a misalignment uses the backlash up."""

import math

import pytest

from toothcontact import gearset
from toothcontact.analyses import analyse
from toothcontact.case import CaseError, parse_case

PAIR = {"kind": "spur", "teeth": [20, 60], "module": "3 mm", "pressure_angle": "20 deg",
        "face_width": "30 mm"}


def pair_of(**changes):
    return gearset.gear_pair(parse_case({**PAIR, **changes}))


@pytest.mark.parametrize("changes", [
    {"backlash": "0 mm"},
    {"backlash": "0 mm", "helix_angle": "20 deg", "pinion": {"profile_shift": 0.4},
     "gear": {"profile_shift": -0.1}},
    {"backlash": "0 mm", "teeth": [21, -67], "pinion": {"profile_shift": 0.2},
     "gear": {"profile_shift": 0.3}},
], ids=["spur", "helical-shifted", "internal-shifted"])
def test_teeth_as_the_rack_cuts_them_mesh_without_backlash(changes):
    """Unthinned teeth at the centre distance their shifts give: both flanks touch, j_wt = 0
    to 1e-9 mm (the operating tooth thicknesses fill the operating pitch; alpha_w is solved
    to brentq's tolerance)."""
    assert pair_of(**changes).operating_backlash == pytest.approx(0.0, abs=1e-9)


def test_a_given_backlash_is_the_pairs_normal_backlash():
    """Thinning each member by j_bn/(2·cos(alpha_n)·cos(beta)) gives the pair j_bn back
    through the operating tooth thicknesses, spur, helical and internal."""
    for changes in ({}, {"helix_angle": "25 deg"}, {"teeth": [21, -67]}):
        assert pair_of(backlash="0.13 mm", **changes).normal_backlash == pytest.approx(
            0.13, abs=1e-9)


def test_centre_distance_adds_its_own_backlash():
    """Pulling unthinned teeth 10 µm apart opens j_bn = 2·da·sin(alpha_wt)·cos(beta_b) to
    first order (ISO 21771's centre-distance term), within 0.1 %."""
    base = pair_of(backlash="0 mm", helix_angle="15 deg")
    apart = pair_of(backlash="0 mm", helix_angle="15 deg",
                    center_distance=f"{base.center_distance + 0.01} mm")
    expected = 2 * 0.01 * math.sin(base.working_pressure_angle) * math.cos(
        base.pinion.base_helix_angle)
    assert apart.normal_backlash == pytest.approx(expected, rel=1e-3)


def test_default_backlash_is_iso_tr_10064_2():
    """No backlash given: (2/3)(0.06 + 0.0005·a + 0.03·m_n) mm; a = 120 mm, m_n = 3 mm give
    0.14 mm."""
    pair = pair_of()
    assert pair.center_distance == pytest.approx(120.0)
    assert pair.normal_backlash == pytest.approx(0.14, abs=1e-9)


@pytest.mark.parametrize("teeth", [[20, 60], [20, -61]], ids=["external", "internal"])
def test_backlash_leaves_the_working_contact_and_transmission_error_unchanged(teeth):
    """The gear is placed on its working flanks: a crowned helical pair's transmission error
    (1e-6 µrad) and the separations of the pairs in contact (10 nm, the search's own noise)
    are the same with no backlash and with 0.2 mm. (A pair whose least separation lies on a
    form circle may differ: on a ring the thicker shaper cutter moves its form circle.)"""
    raw = {**PAIR, "teeth": teeth, "helix_angle": "15 deg",
           "pinion": {"crown": {"height": "10 um"}}, "load": {"torque": "100 N*m"},
           "analysis": {"positions": 3, "pressure_grid": 0, "interference": False}}
    rows = [analyse(parse_case({**raw, "backlash": b})).as_dict()["positions"]
            for b in ("0 mm", "0.2 mm")]
    assert len(rows[0]) == len(rows[1])
    for tight, loose in zip(*rows):
        assert loose["transmission_error_urad"] == pytest.approx(
            tight["transmission_error_urad"], abs=1e-6)
        if tight["edge_contact_at"] is None:
            assert loose["separation_mm"] == pytest.approx(tight["separation_mm"], abs=1e-5)


def test_a_slope_uses_up_zero_backlash_on_the_back_flanks():
    """A helical pair tilted by 0.44 mrad: without backlash the back flanks touch and the
    checks say so and name the backlash; with the default backlash (222 µm) both are clear."""
    raw = {"kind": "spur", "teeth": [31, 66], "module": "5 mm", "pressure_angle": "25 deg",
           "helix_angle": "10 deg", "face_width": "62.1 mm",
           "misalignment": {"slope": "-0.00044"}, "load": {"torque": "1871 N*m"},
           "analysis": {"positions": 3, "pressure_grid": 0}}
    checks = {}
    for backlash in ("0 mm", None):
        case = parse_case({**raw, "backlash": backlash} if backlash else raw)
        checks[backlash] = {c.name: c for c in analyse(case).checks}
    back = "backlash left under the misalignment (the back flanks clear)"
    assert not checks["0 mm"][back].ok
    assert "backlash 0 µm is used up" in checks["0 mm"][back].detail
    assert checks[None][back].ok and "222.1 µm" in checks[None][back].detail
    assert checks[None]["no tip or root interference of the bodies"].ok


@pytest.mark.parametrize("value", ["-0.1 mm", "2 mm", "0.1"])
def test_bad_backlash_is_refused_naming_the_field(value):
    with pytest.raises((CaseError, ValueError), match="backlash"):
        gearset.gear_pair(parse_case({**PAIR, "backlash": value}))
