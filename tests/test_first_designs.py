"""Ordinary designs a new user tried first, which the first release failed on (issue 11),
each run at the tool's default settings and checked for the physics it must show."""

import json

import pytest

from toothcontact import families
from toothcontact.analyses import analyse
from toothcontact.case import parse_case
from toothcontact.views.report import result_document
from toothcontact.runner import bundled_cases_dir


def run(raw: dict) -> dict:
    case = parse_case(raw)
    document = result_document("first", case, raw, analyse(case))
    json.dumps(document, allow_nan=False)
    assert families.check({"title": "first", **raw}, document) == []
    return document


def solved_everywhere(document: dict) -> bool:
    return all(r["bem_status"] in ("solved", "unloaded") for r in document["positions"])


def test_uncrowned_pair_under_slope_is_edge_contact_at_the_end_it_closes():
    """z = 20/60, m = 3 mm, b = 30 mm, no crown, slope 0.0005, 8000 N: every contact is a
    line cut by end B, touching over delta/theta = 12.6 mm, and the loaded contact finds
    the edge load there."""
    doc = run({"kind": "spur", "teeth": [20, 60], "module": "3 mm", "pressure_angle": "20 deg",
               "face_width": "30 mm", "misalignment": {"slope": "0.0005"},
               "load": {"tangential_load": "8000 N"}})
    rows = doc["positions"]
    touching = [r for r in rows if r["separation_mm"] < 1e-4]
    assert touching and all(r["contact_model"] == "line" for r in rows)
    for r in touching:
        assert r["edge_contact"] and r["edge_contact_at"].endswith("end_B")
        assert r["contact_length_mm"] == pytest.approx(0.00632 / 0.0005, rel=0.01)
        assert r["a_mm"] < 15.0
    assert solved_everywhere(doc)
    assert any(r["edge_loaded"] and r["edge_pressure_at"].endswith("end_B") for r in rows)


def test_ordinary_helical_pair_is_solved_at_every_contact():
    """z = 27/71, mn 2.5 mm, 20°, beta 15°, b 40 mm, 12 µm crown, slope 0.0004, 300 N·m."""
    doc = run({"kind": "spur", "teeth": [27, 71], "module": "2.5 mm",
               "pressure_angle": "20 deg", "helix_angle": "15 deg", "face_width": "40 mm",
               "pinion": {"crown": {"height": "12 um"}}, "misalignment": {"slope": "0.0004"},
               "load": {"torque": "300 N*m"}})
    assert solved_everywhere(doc)
    assert doc["summary"]["bem_failed_contacts"] == 0


def test_seed_000_worm_set_loaded():
    """The SABA worm set with 20 N·m on the wheel: a line contact (hob identical to the
    worm) solved at every contact, without transmission error. Its tips rounded as made
    (0.1 m_n): a pair whose least separation lies on a rounding is a point contact there
    (its relative radius across at most the rounding's)."""
    import tomllib

    raw = tomllib.loads((bundled_cases_dir() / "worm_saba_set.toml").read_text())
    raw["load"] = {"output_torque": "20 N*m"}
    doc = run(raw)
    rounding = max(doc[m]["tip_edge_radius_mm"] for m in ("worm", "wheel"))
    rows = doc["positions"]
    assert all(r["contact_model"] == "line" or 0.5 / r["B_analytic_per_mm"] <= rounding
               for r in rows)
    assert sum(r["contact_model"] == "line" for r in rows) >= 0.8 * len(rows)
    assert solved_everywhere(doc)
    assert doc["summary"]["transmission_error_peak_to_peak_urad"] < 1.0


def test_loaded_zk_worm_with_an_oversized_hob():
    """A ZK worm (2 starts, z2 = 45, mn = 2 mm, d1 = 24 mm, 5 % oversized hob, 40 N·m):
    point contact, found and solved at every position, on either flank and hand."""
    for hand, flank in (("right", "left"), ("left", "right")):
        doc = run({"kind": "worm",
                   "worm": {"form": "ZK", "starts": 2, "normal_module": "2 mm",
                            "pitch_diameter": "24 mm", "pressure_angle": "20 deg",
                            "hand": hand, "length": "40 mm"},
                   "wheel": {"teeth": 45, "hob_pitch_diameter": "25.2 mm"},
                   "load": {"output_torque": "40 N*m", "flank": flank}})
        assert doc["positions"] and solved_everywhere(doc)
        assert all(r["contact_model"] == "ellipse" for r in doc["positions"])


def test_default_worm_wheel_blank_fits_a_one_start_worm():
    """A one-start ZA worm, mn = 1 mm, lead angle 8.6°, wheel z2 = 28, all else default:
    the default wheel face width fits the default blank (it was refused)."""
    doc = run({"kind": "worm",
               "worm": {"form": "ZA", "starts": 1, "normal_module": "1 mm",
                        "lead_angle": "8.6 deg", "pressure_angle": "20 deg",
                        "length": "30 mm"},
               "wheel": {"teeth": 28}, "load": {"output_torque": "5 N*m"}})
    wheel = doc["wheel"]
    assert 0 < wheel["face_width_mm"] < 2 * wheel["throat_radius_mm"] + 2.0
    assert doc["positions"] and solved_everywhere(doc)


def test_undercut_pinion_is_analysed_and_flagged():
    """A 14-tooth 20° pinion without profile shift is slightly undercut: it is analysed
    (active profile from its form circle, above the base circle) and the undercut flagged."""
    doc = run({"kind": "spur", "teeth": [14, 40], "module": "2 mm", "pressure_angle": "20 deg",
               "face_width": "20 mm", "load": {"torque": "50 N*m"}})
    pinion = doc["pinion"]
    assert pinion["undercut"] and pinion["form_diameter_mm"] > pinion["base_diameter_mm"]
    assert any(c["name"] == "pinion is not undercut" and not c["ok"] for c in doc["checks"])
    assert doc["positions"] and solved_everywhere(doc)
    radius = 0.5 * pinion["form_diameter_mm"]
    assert min(r["contact_radius_pinion_mm"] for r in doc["positions"]) >= radius - 1e-6
