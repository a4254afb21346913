"""Separation fields of a crowned spur pair: the ease-off over the cycle and the gap around a
contact, against exact ray solves and the crown's closed form."""

import math

import numpy as np
import pytest
from pairs import spur_cycle

from toothcontact.contact.field import contact_field
from toothcontact.contact.local import heights, planes_at

CROWN_RADIUS, FACE = 4000.0, 30.0
CASE = {"kind": "spur", "teeth": [20, 60], "module": "3 mm", "pressure_angle": "20 deg",
        "face_width": f"{FACE} mm", "pinion": {"crown": {"radius": f"{CROWN_RADIUS} mm"},
                                                "tip_edge": {"radius": "0 mm"}},
        "gear": {"tip_edge": {"radius": "0 mm"}}}   # sharp: the involute's closed forms


def cycle(slope=0.0, positions=3):
    return spur_cycle(CASE, slope, positions)[1]


@pytest.fixture(scope="module")
def aligned():
    return cycle()


def test_ease_off_across_the_face_is_the_crown_drop(aligned):
    """Aligned and crowned on the pinion only: along every profile line the separation a
    distance z from mid-face exceeds that at mid-face by the crown's drop z²/(2R) (circular
    crown, to 0.5 %), wherever the line is in contact at mid-face (the lines one grid step
    inside the face ends: at the very ends the crowned flank's normal leaves the gear's
    face)."""
    ease = aligned.ease_off
    mid = int(np.argmin(np.abs(ease.v)))
    touching = np.flatnonzero(ease.separation[:, mid] < 1e-4)
    assert touching.size >= 5
    for end in (1, -2):
        drop = ease.v[end] ** 2 / (2.0 * CROWN_RADIUS)
        rise = ease.separation[touching, end] - ease.separation[touching, mid]
        assert rise == pytest.approx(np.full(touching.size, drop), rel=5e-3)


def test_gap_field_matches_exact_ray_solves(aligned):
    """The spline-carried gap on a 256 × 256 grid equals the exact ray solve at random grid
    points to 1e-4 µm, and near the contact its even part (the mean over the point and its
    reflection through the contact: the profile curvature's change along the profile, a
    cubic term, cancels) is A x² + B y² of the fit, to 1 % up to a 2 µm gap."""
    rng = np.random.default_rng(1)
    for k in (0, len(aligned.rows) - 1):
        field = contact_field(aligned, k, (256, 256))
        i, j = rng.integers(0, 256, 300), rng.integers(0, 256, 300)
        x, y = field.x[i][None], field.y[j][None]
        index = np.array([k])
        hp = heights(aligned.pinion, aligned.pinion_frames[index], planes_at(aligned.planes, index),
                     x, y, *aligned.contact_uv("pinion", k))
        hg = heights(aligned.gear, aligned.gear_frames[index], planes_at(aligned.planes, index),
                     x, y, *aligned.contact_uv("gear", k))
        assert np.max(np.abs((hg.s - hp.s)[0] - field.gap[i, j])) < 1e-7
        row, angle = aligned.rows[k], aligned.axis_angle[k]
        X, Y = np.meshgrid(field.x, field.y, indexing="ij")
        xa = X * math.cos(angle) + Y * math.sin(angle)
        ya = -X * math.sin(angle) + Y * math.cos(angle)
        quadratic = row["A_per_mm"] * xa**2 + row["B_per_mm"] * ya**2
        near = quadratic < 0.002
        even = 0.5 * (field.gap + field.gap[::-1, ::-1])[near] - row["separation_mm"]
        assert np.all(np.abs(even - quadratic[near]) <= 0.01 * quadratic[near] + 1e-6)


def test_gap_field_material_ends_at_the_face_end():
    """Under a slope that pushes the contact to end B the field's material stops where the
    first of the two flanks ends (the tilted gear's end B stands back from the pinion's):
    at a + margin along e1 (the face direction of a spur flank) from the contact, the
    margins measured independently by marching the ellipse onto the flanks, to one cell."""
    tilted = cycle(slope=0.004, positions=1)
    k = 0
    row = tilted.rows[k]
    assert row["edge_contact"]
    field = contact_field(tilted, k, (256, 256))
    line = field.material[:, 128]
    last = field.x[np.flatnonzero(line)[-1]]
    dx, _ = field.spacing
    margins = row["edge_margins_mm"]
    end = row["a_mm"] + min(margins["pinion_end_B"], margins["gear_end_B"])
    assert last == pytest.approx(end, abs=dx)
    assert margins["gear_end_B"] < margins["pinion_end_B"]
    assert not line[-1] and line[0]


def test_gap_field_next_to_the_base_circle_stays_on_the_flank():
    """At roll -2 deg pair -1 touches low on the pinion, whose field runs down to the
    involute's cusp on the base circle; past it the lines meet the other branch of the
    surface (converged, but no part of the flank). Those samples are left out (the
    parameter map folds there), so the gap over the material is never below the contact's
    separation (before: -8.7 µm next to the fold) and equals exact ray solves at random
    material points to 0.01 µm (to 1e-4 µm away from the fold)."""
    nine = cycle(positions=9)
    k = next(i for i, r in enumerate(nine.rows) if r["roll_deg"] == pytest.approx(-2.0) and r["pair"] == -1)
    field = contact_field(nine, k, (201, 201), 1.5)
    assert 0.6 < field.material.mean() < 0.9        # the form circle crosses the field
    assert np.min(field.gap[field.material]) >= nine.rows[k]["separation_mm"] - 1e-9
    ii, jj = np.nonzero(field.material)
    pick = np.random.default_rng(2).integers(0, ii.size, 400)
    i, j = ii[pick], jj[pick]
    index = np.array([k])
    exact = [heights(flank, frames[index], planes_at(nine.planes, index), field.x[i][None],
                     field.y[j][None], *nine.contact_uv(member, k)).s[0]
             for member, flank, frames in (("pinion", nine.pinion, nine.pinion_frames),
                                           ("gear", nine.gear, nine.gear_frames))]
    assert np.max(np.abs(exact[1] - exact[0] - field.gap[i, j])) < 1e-5


HELICAL = {"kind": "spur", "teeth": [23, 61], "module": "3 mm", "pressure_angle": "20 deg",
           "helix_angle": "30 deg", "face_width": "30 mm"}     # tips rounded by default


def test_a_turned_field_at_a_rounded_helical_tip_is_the_exact_gap():
    """An uncrowned 30 deg helical pair with its default tip roundings (0.3 mm): each
    contact line's field laid along the line (contact_fields' along_pattern, turned by
    10-20 deg from the face direction), 128 × 48 points. Where the flanks lie within 50 µm
    of each other, the field's gap is the exact ray solve at its points to 1 % + 0.01 µm
    (measured 0.8 % at most), and to 0.1 µm where they lie within 10 µm (measured 0.05
    µm), next to the roundings too. The splines carry the gap less the modifications,
    which are put back from the interpolated parameters (field.modification_gap): splined
    whole, a rounding's start, narrower than the samples' spacing, rang in them (a false
    notch of 16 µm beside a helical tip, 7 GPa on it)."""
    from toothcontact.contact.field import contact_fields, field_turns
    from toothcontact.contact.local import turned

    helical = spur_cycle(HELICAL, 0.0, 3)[1]
    rows = np.arange(len(helical.rows))
    turns = field_turns(helical, rows)
    assert np.all(np.abs(np.degrees(turns)) > 5.0)
    fields = contact_fields(helical, rows, (128, 48), along_pattern=True)
    near_tips = 0
    for k, field in zip(rows, fields):
        assert field.turn == turns[k]
        close = np.isfinite(field.gap) & (field.gap < 0.05)
        i, j = np.nonzero(close)
        index = np.array([k])
        planes = turned(planes_at(helical.planes, index), turns[index])
        x, y = field.x[i][None], field.y[j][None]
        hp = heights(helical.pinion, helical.pinion_frames[index], planes, x, y,
                     *helical.contact_uv("pinion", k))
        hg = heights(helical.gear, helical.gear_frames[index], planes, x, y,
                     *helical.contact_uv("gear", k))
        exact = (hg.s - hp.s)[0]
        error = np.abs(exact - field.gap[i, j])
        assert np.all(error <= 0.01 * exact + 1e-5)
        assert np.all(error[exact < 0.01] < 1e-4)
        near_tips += sum(int((np.abs(v[i, j]) < 0.05).sum()) for name, v in field.inside.items()
                         if name.endswith("_tip"))
    assert near_tips > 100                  # the comparison reaches the roundings
