"""Line contact (contact.line): uncrowned pairs aligned and under slope, against closed forms.

An uncrowned spur pair tilted by theta in the plane of action opens a gap that grows
linearly along the face, theta per mm: the rigid contact line runs from the end the slope
closes over delta/theta (delta the approach), and presses on that end (edge contact). Aligned,
it spans the face and presses on no edge. Hertz's line contact with the load over the length
in contact gives the pressure (Johnson eq 4.45 with the profile radii of the contact point).
"""

import math

import numpy as np

import pytest
from pairs import STEEL, spur_cycle

from toothcontact.analytic.hertz import hertz_line
from toothcontact.contact.cycle import CycleSettings

SPUR = {"kind": "spur", "teeth": [20, 60], "module": "3 mm", "pressure_angle": "20 deg",
        "face_width": "30 mm"}
DELTA = CycleSettings().approach


def cycle(case=SPUR, slope=0.0, positions=3):
    return spur_cycle(case, slope, positions)


@pytest.mark.parametrize("slope, end", [(0.0005, "B"), (-0.0008, "A")])
def test_slope_cuts_the_contact_line_at_the_end_it_closes(slope, end):
    """Length in contact delta/|theta| to 0.5 %, the contact on the end the slope closes
    (to 0.05 mm, where the tilted gear's end stands), the line pressing on that end (margin
    minus the face length: no crown turns it) and clear of the other end by the face less
    the line (to 0.5 mm: the tilted gear's end stands up to 0.05 mm off the pinion's),
    Hertz's line contact over the length in contact to 0.1 %."""
    pair, cyc = cycle(slope=slope)
    sign = 1.0 if end == "B" else -1.0
    other = "A" if end == "B" else "B"
    rb1 = pair.pinion.base_radius
    for r in cyc.rows:
        assert r["contact_model"] == "line"
        length = DELTA / abs(slope)
        assert r["contact_length_mm"] == pytest.approx(length, rel=5e-3)
        # the line's middle: half its length inside the closed end
        assert sign * r["face_position_mm"] == pytest.approx(15.0 - 0.5 * length, abs=0.1)
        assert r["edge_contact"] and r["edge_contact_at"].endswith(f"end_{end}")
        margins = r["edge_margins_mm"]
        assert min(margins[f"pinion_end_{end}"], margins[f"gear_end_{end}"]) == -30.0
        assert margins[f"pinion_end_{other}"] == pytest.approx(30.0 - length, abs=0.5)
        rho1 = math.sqrt(r["contact_radius_pinion_mm"] ** 2 - rb1**2)
        rho2 = pair.center_distance * math.sin(pair.working_pressure_angle) - rho1
        exact = hertz_line(r["normal_load_N"] / r["contact_length_mm"],
                           rho1 * rho2 / (rho1 + rho2), STEEL)
        assert r["p_max_MPa"] == pytest.approx(exact.p0, rel=1e-3)
        assert r["b_mm"] == pytest.approx(exact.b, rel=1e-3)
        assert r["approach_mm"] is None


def test_slope_moves_the_line_toward_the_end_it_closes():
    """The middle of the part in contact (the row's face position) lies half its length
    inside the end the slope closes (e1 runs along the face toward end B), where the least
    separation is: the contact point plus the pattern's centre."""
    _, cyc = cycle(slope=0.0005)
    contact = cyc.pinion.evaluate(np.asarray(cyc.contacts.pinion_u),
                                  np.asarray(cyc.contacts.pinion_v), order=1).points[:, 2]
    for k, r in enumerate(cyc.rows):
        assert r["face_position_mm"] == pytest.approx(15.0 - 0.5 * r["contact_length_mm"],
                                                      abs=0.1)
        assert contact[k] == pytest.approx(15.0, abs=0.05)
        assert contact[k] + cyc.pattern_centre[k][0] == pytest.approx(r["face_position_mm"],
                                                                      abs=0.05)


def test_aligned_uncrowned_pair_touches_over_the_whole_face_without_edge_contact():
    """Aligned: the line spans the face (30 mm to 0.5 %) and reaches both ends without
    pressing on them (margins 0), so no edge contact."""
    _, cyc = cycle()
    for r in cyc.rows:
        assert r["contact_model"] == "line"
        assert r["contact_length_mm"] == pytest.approx(30.0, rel=5e-3)
        assert not r["edge_contact"]
        for end in ("A", "B"):
            assert r["edge_margins_mm"][f"pinion_end_{end}"] == 0.0


def test_crown_too_mild_for_the_face_is_a_line():
    """A 1 µm crown: the loaded ellipse would be longer than the face, so the contact is a
    line; with a slope that throws the crown's vertex off the face it presses on that end."""
    case = {**SPUR, "pinion": {"crown": {"height": "1 um"}}}
    _, aligned = cycle(case)
    assert all(r["contact_model"] == "line" and not r["edge_contact"] for r in aligned.rows)
    _, tilted = cycle(case, slope=0.001)
    assert all(r["edge_contact_at"].endswith("end_B") for r in tilted.rows)


def test_helical_uncrowned_lines_end_at_the_tip_and_form_without_edge_contact():
    """An aligned uncrowned helical pair: the contact lines run obliquely across the flank
    and end at the tip and form circles, where they reach the edge (margin 0) without
    pressing on it; no row is cut by a face end."""
    case = {**SPUR, "teeth": [27, 71], "module": "2.5 mm", "helix_angle": "15 deg",
            "face_width": "40 mm"}
    _, cyc = cycle(case)
    assert cyc.rows
    for r in cyc.rows:
        assert r["contact_model"] == "line"
        assert not r["edge_contact"]
        assert min(r["edge_margins_mm"].values()) >= 0.0


def test_contact_lines_of_one_position_share_its_load_by_their_lengths():
    """An aligned uncrowned helical pair: the lines in contact at one position run across
    the flank over different lengths; under one rigid approach each carries the same load
    per mm, so the normal load is split by their lengths (an equal split put a short line's
    load on it as on a long one's), and each row's Hertz line contact is that load over its
    length."""
    sharp = {"tip_edge": {"radius": "0 mm"}}    # a rounded tip's contact is no line
    case = {**SPUR, "teeth": [27, 71], "module": "2.5 mm", "helix_angle": "15 deg",
            "face_width": "40 mm", "pinion": sharp, "gear": sharp}
    _, cyc = cycle(case, positions=5)
    rows = [r for r in cyc.rows if r["rigid_contact"]]
    total = sum(r["normal_load_N"] for r in rows if r["roll_deg"] == rows[0]["roll_deg"])
    shared = 0
    for roll in {r["roll_deg"] for r in rows}:
        here = [r for r in rows if r["roll_deg"] == roll]
        assert math.fsum(r["normal_load_N"] for r in here) == pytest.approx(total, rel=1e-12)
        if len(here) < 2:
            continue
        lengths = [r["contact_length_mm"] for r in here]
        assert max(lengths) > 1.2 * min(lengths)
        shared += 1
        for r in here:
            assert r["normal_load_N"] / r["contact_length_mm"] == pytest.approx(
                total / sum(lengths), rel=1e-12)
            exact = hertz_line(r["normal_load_N"] / r["contact_length_mm"],
                               0.5 / r["B_analytic_per_mm"], STEEL)
            assert r["p_max_MPa"] == pytest.approx(exact.p0, rel=1e-12)
    assert shared >= 3


def test_a_line_resolved_to_one_column_on_an_edge_is_one_cell_long():
    """A line whose only column in contact lies on a flank edge, where the cells' share of
    material raises its least gap past the approach, carried both ends to nothing: a
    length of 0, and its Hertz line an infinite pressure (a before-stop worm set's pair at
    a wheel tip). It is given the field's resolution along the line, one cell."""
    from types import SimpleNamespace

    from toothcontact.contact.line import _length

    approach, dx = 1e-3, 0.25
    rel = np.full((9, 5), 2e-2)
    rel[4, 2] = 0.0                                  # the contact, on one column
    inside = rel <= approach
    share = np.ones_like(rel)
    share[4] = 0.1                                   # that column on the edge
    field = SimpleNamespace(x=dx * np.arange(9), y=0.1 * np.arange(5), spacing=(dx, 0.1),
                            material=np.ones_like(rel, bool), parameters={},
                            material_share=lambda: share)
    length, (x, _) = _length(field, rel, inside, approach, {})
    assert length == dx and x == pytest.approx(4 * dx)
    share[4] = 1.0                                   # off the edge: ends carried as before
    rel[rel > 0] = 1.5e-3
    length, _ = _length(field, rel, inside, approach, {})
    assert length == pytest.approx(2 * dx * approach / 1.5e-3)
