"""A tip edge broken by a rounding ([member.tip_edge] radius, modify.TipEdge): the flank's
own curvature across the rounding, the contact a rounding carries against Hertz's line
contact on its radius, converged with the cells across it, and the case's checks."""

import copy
import math
import tomllib
from pathlib import Path

import numpy as np
import pytest

from toothcontact import analyses, gearset, member_modifications
from toothcontact.analytic.hertz import compliance, hertz_line
from toothcontact.case import parse_case
from toothcontact.contact import field as field_module
from toothcontact.surfaces.generation import generate_side

#: the analyses here read their own pass's rows and summary: no positions check, no
#: stresses below the contacts
QUIET = {"positions_check": False, "subsurface": False}
FZG = tomllib.loads((Path(__file__).parent.parent / "cases" / "fzg_c_type.toml").read_text())


def rounded(radius="0.45 mm", positions=8) -> dict:
    """The FZG C-type pair with both tips rounded."""
    raw = copy.deepcopy(FZG)
    for member in ("pinion", "gear"):
        raw[member]["tip_edge"] = {"radius": radius}
    raw["analysis"] = {"positions": positions, "interference": False, **QUIET}
    return raw


def test_the_flank_curves_at_the_roundings_radius_where_the_rounding_starts():
    """Across the profile the pinion's flank curves as its involute (1/s, s the roll
    length) up to the rounding's start and at 1/ρ from there (the drop adds the
    difference; exact derivatives): to 1e-6."""
    pair = gearset.gear_pair(parse_case(rounded("0.45 mm")))
    flank = gearset.working_flank(pair.pinion, pair.pinion_modifications, 1)
    edge = pair.pinion_modifications.tip_edge
    start = edge.start / pair.pinion.base_radius                     # roll angle (u)
    for u, expected in ((start - 1e-6, 1.0 / edge.start), (start + 1e-6, 1.0 / 0.45)):
        sample = flank.evaluate(np.array([u]), np.array([0.0]))
        curvature = abs(float(sample.normal_curvature(1.0, 0.0)[0]))
        assert curvature == pytest.approx(expected, rel=1e-4)
    # the rounding starts its tangent length ρ·tan((90° - α_a)/2) before the tip, along the flank
    alpha_a = math.acos(pair.pinion.base_radius / pair.pinion.tip_radius)
    s_tip = math.sqrt(pair.pinion.tip_radius**2 - pair.pinion.base_radius**2)
    arc = (s_tip**2 - edge.start**2) / (2 * pair.pinion.base_radius)
    assert arc == pytest.approx(0.45 * math.tan(0.5 * (0.5 * math.pi - alpha_a)), rel=1e-12)


def test_a_rounded_tip_carries_hertzs_line_contact_on_its_radius_converged(monkeypatch):
    """The FZG pair with 0.45 mm tip roundings: where a pair enters mesh on the pinion's
    rounding (the largest loaded pressure of the cycle), the loaded peak is Hertz's line
    contact of the rounding against the gear's flank with the load the teeth's compliance
    gives that pair over the face (measured 2761 MPa against 2775 MPa: the sharp tip's
    strip-averaged 2385 MPa was a number of the grid), within 3 %, and it does not change
    with twice the cells across the contact (2761, 2762 MPa)."""
    peaks = []
    for fewest in (48, 96):
        monkeypatch.setattr(field_module, "FEWEST_POINTS", fewest)
        result = analyses.analyse(parse_case(rounded()))
        row = max(result.sections["positions"], key=lambda r: r["bem_p_max_MPa"] or 0.0)
        peaks.append(row["bem_p_max_MPa"])
    pair = gearset.gear_pair(parse_case(rounded()))
    assert row["contact_radius_pinion_mm"] > math.hypot(pair.pinion_modifications.tip_edge.start,
                                                        pair.pinion.base_radius)
    rho_gear = (pair.center_distance * math.sin(pair.working_pressure_angle)
                - math.sqrt(row["contact_radius_pinion_mm"]**2 - pair.pinion.base_radius**2))
    hertz = hertz_line(row["bem_load_N"] / 14.0, 0.45 * rho_gear / (0.45 + rho_gear),
                       compliance(206000.0, 0.3, 206000.0, 0.3))
    assert peaks[0] == pytest.approx(hertz.p0, rel=0.03)
    assert peaks[1] == pytest.approx(peaks[0], rel=0.01)


@pytest.mark.parametrize("radius", ["8 mm", "-0.2 mm"])
def test_a_rounding_too_large_or_negative_is_refused_in_one_line(tmp_path, radius):
    """A rounding that would start below the form circle, or a negative radius: exit 2, one
    line naming pinion.tip_edge.radius, nothing written."""
    import tomli_w

    import mutations

    raw = copy.deepcopy(FZG)
    raw["pinion"]["tip_edge"] = {"radius": radius}
    assert "pinion.tip_edge.radius" in mutations.refused_line(tomli_w.dumps(raw), tmp_path)


def test_a_tip_without_a_given_rounding_gets_a_tenth_of_the_module():
    """No [member.tip_edge]: the tips are rounded at 0.1·m_n (0.45 mm on the FZG gear) and
    the result says so (notes, member sections); '0 mm' keeps a sharp edge; a tooth too
    small for 0.1·m_n gets the largest rounding that fits; a spline's tips stay sharp."""
    raw = copy.deepcopy(FZG)
    raw["analysis"] = {"positions": 3, "pressure_grid": 0, "interference": False}
    pair = gearset.gear_pair(parse_case(raw))
    assert pair.pinion_modifications.tip_edge.radius == pytest.approx(0.45)
    assert pair.gear_modifications.tip_edge.radius == pytest.approx(0.45)
    result = analyses.analyse(parse_case(raw))
    assert result.sections["pinion"]["tip_edge_radius_mm"] == pytest.approx(0.45)
    assert any("tip edges: pinion rounded 0.45 mm (default)" in n for n in result.notes)
    raw["pinion"]["tip_edge"] = {"radius": "0 mm"}
    sharp = gearset.gear_pair(parse_case(raw))
    assert sharp.pinion_modifications.tip_edge is None
    assert sharp.gear_modifications.tip_edge.radius == pytest.approx(0.45)
    # a pointed tip (large shift, few teeth): the default shrinks to what fits
    pointed = {"kind": "spur", "teeth": [12, 40], "module": "3 mm", "pressure_angle": "20 deg",
               "face_width": "20 mm", "pinion": {"profile_shift": 0.6}}
    tight = gearset.gear_pair(parse_case(pointed))
    edge = tight.pinion_modifications.tip_edge
    form = generate_side(tight.pinion).form_radius
    largest = member_modifications.largest_tip_edge(tight.pinion, form)
    assert edge is not None and edge.radius == pytest.approx(min(0.3, largest), rel=1e-9)
    spline = tomllib.loads((Path(__file__).parent.parent / "cases"
                            / "spline_crowned_18t.toml").read_text())
    assert gearset.spline_pair(parse_case(spline)).hub_modifications.tip_edge is None


def test_a_sharp_tips_strip_pressure_does_not_depend_on_where_the_grid_cuts_it(monkeypatch):
    """The bundled spline's sharp tips (its contact spans the working depth and ends there):
    with the tip edges snapped to cell boundaries the strip-averaged tip pressure is the
    same on 48 and 51 cells across (measured 336, 336 MPa; before: 303 and 439 MPa) and on
    96 (340 MPa): within 3 %."""
    raw = tomllib.loads((Path(__file__).parent.parent / "cases"
                         / "spline_crowned_18t.toml").read_text())
    raw["analysis"] = {"positions": 1, **QUIET}
    peaks = []
    for grid, fewest in ((128, 48), (192, 48), (128, 96)):
        raw["analysis"]["pressure_grid"] = grid
        monkeypatch.setattr(field_module, "FEWEST_POINTS", fewest)
        result = analyses.analyse(parse_case(raw))
        peaks.append(result.sections["summary"]["max_edge_pressure_MPa"])
    assert peaks[1] == pytest.approx(peaks[0], rel=0.03)
    assert peaks[2] == pytest.approx(peaks[0], rel=0.03)


def test_a_helical_pairs_rounded_tip_corners_converge_with_the_grid():
    """An uncrowned, unrelieved 30 deg helical pair (z = 23/61, m = 3 mm, 300 N/mm) with its
    default 0.3 mm tip roundings: its contact lines run onto the roundings at their ends (a
    corner contact at each tip: what tip relief is for). Each line's field is laid along
    it, so that its cells across are 0.01-0.03 mm, and the splines carry the gap without
    the roundings (field.modification_gap). The largest pressure of every contact (3.3-4.1
    GPa, on the roundings) at the default pressure_grid 128 is the one at 384 within 4 %
    (measured 3.3 % at most; 1.9 % before the gear bodies coupled the pairs' teeth and
    moved load between the corners), at 256 within 6 % (measured 1.6 %; 5.1 % before);
    on fields along the
    face with the gap splined whole it jumped by up to 40 % and a false notch beside a tip
    read 7 GPa."""
    def peaks(grid):
        result = analyses.analyse(parse_case({
            "kind": "spur", "title": "helical corners", "teeth": [23, 61], "module": "3 mm",
            "pressure_angle": "20 deg", "helix_angle": "30 deg", "face_width": "30 mm",
            "misalignment": {"slope": "0"}, "load": {"tangential_load": "9000 N"},
            "analysis": {"positions": 3, "interference": False, **QUIET,
                         "pressure_grid": grid}}))
        return [(r["bem_p_max_MPa"], r["edge_pressure_at"]) for r in result.sections["positions"]
                if r["bem_load_N"]]

    finest = peaks(384)
    assert len(finest) >= 6
    for grid, within in ((128, 0.04), (256, 0.06)):
        found = peaks(grid)
        assert len(found) == len(finest)
        for (p, at), (q, at_finest) in zip(found, finest):
            assert p == pytest.approx(q, rel=within)
            assert at.endswith("_tip") and at == at_finest


def test_the_active_flanks_peak_follows_the_crown_beside_the_corner_contact():
    """The bundled crowned spur pair (no tip relief) at crown radii 2000 and 8000 mm: its
    largest loaded pressure is the gear tip's rounding entering mesh (5841 and 4413 MPa,
    measured), a corner contact that spills past the rounding's start onto the involute.
    flank_p_max_MPa, the active flank's peak more than 0.1 mm inside its edges (the
    rounding's start among them), is the crown's: it falls with a lighter crown and lies
    below the rigid Hertz pressure of its contact by the teeth's bending spreading the
    load (0.88-0.89 of it, measured; asserted 0.8 to 1)."""
    raw = tomllib.loads((Path(__file__).parent.parent / "cases" / "spur_crowned_20_60.toml")
                        .read_text())
    raw["analysis"] = {**raw.get("analysis", {}), **QUIET}
    flank = {}
    for radius in (2000, 8000):
        raw["pinion"]["crown"]["radius"] = f"{radius} mm"
        result = analyses.analyse(parse_case(raw))
        rows = [r for r in result.sections["positions"] if r["bem_load_N"]]
        top = max(rows, key=lambda r: r["bem_p_max_MPa"])
        assert top["edge_pressure_at"] == "gear_tip"
        assert top["bem_p_max_MPa"] > 2.0 * top["flank_p_max_MPa"]
        peak = max(rows, key=lambda r: r["flank_p_max_MPa"])
        assert 0.8 < peak["flank_p_max_MPa"] / peak["p_max_MPa"] < 1.0
        assert result.sections["summary"]["flank_pressure_max_MPa"] == peak["flank_p_max_MPa"]
        flank[radius] = peak["flank_p_max_MPa"]
    assert flank[2000] > 1.2 * flank[8000]
