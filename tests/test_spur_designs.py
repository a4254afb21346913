"""Spur and helical designs across the legal ranges (issue 11): a seeded family through the
geometry, held to relations computed here from the reported circles; an undercut pinion run
loaded end to end; and designs that cannot be made refused with the field named."""

import math

import pytest

from toothcontact import cad, families, gearset
from toothcontact.analyses import analyse
from toothcontact.case import CaseError, parse_case
from toothcontact.surfaces.generation import generate_side

# the family's designs without their loads: the geometry and the solids
FAMILY = [{k: v for k, v in raw.items() if k not in ("load", "misalignment")}
          for raw in families.spur_designs(16, seed=5)]


def inv(a):
    return math.tan(a) - a


@pytest.mark.parametrize("raw", FAMILY, ids=[d["title"] for d in FAMILY])
def test_family_geometry_is_consistent(raw):
    """Every generated pair's geometry runs. From the reported numbers: both tips clear the
    mating root circle at the centre distance; every tooth keeps a positive thickness on its
    tip circle, 2·r_a·(s/d ± inv(alpha_t) ∓ inv(acos(r_b/r_a))) (ISO 21771); the form
    circle of an external gear lies between its base and tip circles; the centre distance
    follows from the working pressure angle, a = |r_b2 ± r_b1|/cos(alpha_w)."""
    result = analyse(parse_case(raw))
    p, g, mesh = (result.sections[k] for k in ("pinion", "gear", "mesh"))
    a, internal = mesh["center_distance_mm"], g["internal"]
    if internal:
        assert g["root_diameter_mm"] / 2 - a - p["tip_diameter_mm"] / 2 >= 0
        assert g["tip_diameter_mm"] / 2 - a - p["root_diameter_mm"] / 2 >= 0
    else:
        assert a - p["tip_diameter_mm"] / 2 - g["root_diameter_mm"] / 2 >= 0
        assert a - g["tip_diameter_mm"] / 2 - p["root_diameter_mm"] / 2 >= 0
    alpha_t = math.radians(p["transverse_pressure_angle_deg"])
    for member in (p, g):
        ra, rb, r = (member[f"{k}_diameter_mm"] / 2 for k in ("tip", "base", "pitch"))
        sign = -1.0 if member["internal"] else 1.0
        s_a = 2 * ra * (member["tooth_thickness_mm"] / (2 * r)
                        + sign * (inv(alpha_t) - inv(math.acos(rb / ra))))
        assert s_a > 0
        if not member["internal"]:
            assert rb <= member["form_diameter_mm"] / 2 < ra
    rb1, rb2 = p["base_diameter_mm"] / 2, g["base_diameter_mm"] / 2
    assert a == pytest.approx(abs(rb2 - rb1 if internal else rb2 + rb1)
                              / math.cos(math.radians(mesh["working_pressure_angle_deg"])),
                              rel=1e-12)


def test_family_solids_of_external_pairs_are_valid():
    """The export path (three-tooth sectors) gives valid solids for the external pairs of
    the family, undercut pinions and high pressure angles included."""
    external = [raw for raw in FAMILY if raw["teeth"][1] > 0][:4]
    assert any(float(raw["pressure_angle"].split()[0]) > 23 for raw in external)  # 0.38 does not fit
    for raw in external:
        for body in cad.build_parts(parse_case(raw)).values():
            assert cad.is_valid(body.solid)


def test_undercut_pinion_runs_loaded_end_to_end():
    """A 14-tooth 20° pinion without shift, loaded: analysed, not refused. It is flagged as
    undercut, its form diameter is the one generated (above the base circle), the bodies
    (built with the undercut root) show no tip or root interference, and every mesh position
    has a contact."""
    raw = {"kind": "spur", "teeth": [14, 40], "module": "2 mm", "pressure_angle": "20 deg",
           "face_width": "20 mm", "load": {"torque": "50 N*m"},
           "analysis": {"positions": 3, "pressure_grid": 32, "field_grid": 41}}
    case = parse_case(raw)
    result = analyse(case)
    pinion = result.sections["pinion"]
    side = generate_side(gearset.gear_pair(case).pinion)
    assert pinion["undercut"] is True
    assert pinion["form_diameter_mm"] == pytest.approx(2 * side.form_radius, rel=1e-12)
    assert pinion["form_diameter_mm"] > pinion["base_diameter_mm"]
    assert result.sections["interference"]["found"] == []
    assert len(result.sections["interference"]) and len(result.cycle.rows) >= 3
    assert not next(c for c in result.checks if c.name == "pinion is not undercut").ok


BASE = {"kind": "spur", "module": "2 mm", "pressure_angle": "20 deg", "face_width": "20 mm"}


@pytest.mark.parametrize("raw,field", [
    ({**BASE, "teeth": [12, 40], "pinion": {"profile_shift": 1.2}}, "pinion.profile_shift"),
    ({**BASE, "teeth": [12, 13], "pinion": {"profile_shift": 0.8},
      "gear": {"profile_shift": 0.8}}, "pinion.profile_shift"),
    ({**BASE, "teeth": [20, -40], "pinion": {"profile_shift": 0.8},
      "gear": {"profile_shift": -0.3}}, "pinion.profile_shift / gear.profile_shift"),
    ({**BASE, "teeth": [20, 40], "pressure_angle": "25 deg", "rack": {"root_radius": 0.45}},
     "rack.root_radius"),
    ({**BASE, "teeth": [20, 40], "center_distance": "50 mm"}, "center_distance"),
])
def test_impossible_designs_name_the_field(raw, field):
    """Pointed teeth, a tip past the mating root at the zero-backlash centre distance, no
    working pressure angle, a rack tip rounding that does not fit, a centre distance inside
    the base circles: one CaseError naming the field, never an internal error."""
    with pytest.raises(CaseError, match=field.replace(".", r"\.")):
        analyse(parse_case(raw))


def test_a_given_centre_distance_that_drives_a_tip_past_the_root_is_reported():
    """A centre distance from the case is an assembly to analyse, not a design to refuse: a
    tip past the mating root is a failed check with the clearances (a - r_a1 - r_f2 and
    a - r_a2 - r_f1, computed here)."""
    raw = {**BASE, "teeth": [20, 40], "pinion": {"profile_shift": 0.8},
           "gear": {"profile_shift": 0.8}, "center_distance": "61 mm"}
    result = analyse(parse_case(raw))
    p, g, mesh = (result.sections[k] for k in ("pinion", "gear", "mesh"))
    expected = 61.0 - p["tip_diameter_mm"] / 2 - g["root_diameter_mm"] / 2
    assert mesh["pinion_tip_clearance_mm"] == pytest.approx(expected, rel=1e-12)
    assert expected < 0
    assert not next(c for c in result.checks if c.name == "tips clear the mating root circles").ok


def test_default_rack_rounding_fits_a_high_pressure_angle():
    """At 25° ISO 53's tip rounding 0.38·m_n overlaps itself on the rack's tip (largest
    (pi/4 - 1.25·tan 25°)·cos 25°/(1 - sin 25°) = 0.318); the default becomes 95 % of it and
    the gear's solid is valid; a rounding given explicitly is kept."""
    raw = {**BASE, "teeth": [20, 40], "pressure_angle": "25 deg"}
    largest = (math.pi / 4 - 1.25 * math.tan(math.radians(25))) * math.cos(
        math.radians(25)) / (1 - math.sin(math.radians(25)))
    pair = gearset.gear_pair(parse_case(raw))
    assert pair.pinion.root_radius == pytest.approx(0.95 * largest, rel=1e-12)
    assert cad.is_valid(cad.build_gear(pair.pinion, teeth=3).solid)
    given = gearset.gear_pair(parse_case({**raw, "rack": {"root_radius": 0.3}}))
    assert given.pinion.root_radius == 0.3
