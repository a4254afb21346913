"""Flank modifications as gear engineers order them (issue 29): helix slope f_Hβ, profile
slope f_Hα, root relief and twist, each against what the involute geometry says
independently of the contact engine: the drop at a contact point is the transmission error
a rigid pair shows there, a crown's contact moves to where a linear drop tilts its
parabola's minimum (-R·k), and a helix slope of the misalignment's gap across the face
brings the loaded pattern back to the aligned one."""

import math
from pathlib import Path

import numpy as np
import pytest

from toothcontact import cad, gearset
from toothcontact.analyses import analyse
from toothcontact.case import CaseError, parse_case
from toothcontact.surfaces.modify import FlankModifications, RootRelief, Topography, Twist
from toothcontact.surfaces.involute import CylindricalGear

FACE = 30.0


def spur(pinion: dict, slope: float = 0.0, positions: int = 12, grid: int = 0) -> dict:
    """The 20/60 spur pair, m = 3 mm, b = 30 mm, 6000 N, with the pinion's modifications."""
    return {"kind": "spur", "teeth": [20, 60], "module": "3 mm", "pressure_angle": "20 deg",
            "face_width": f"{FACE} mm", "pinion": pinion,
            "misalignment": {"slope": str(slope)}, "load": {"tangential_load": "6000 N"},
            "analysis": {"positions": positions, "interference": False, "pressure_grid": grid,
                         "positions_check": False}}


def profile_ends(raw: dict) -> tuple[float, float, float]:
    """The pinion's base radius and the roll lengths (mm) of its form circle and tip."""
    pair = gearset.gear_pair(parse_case(raw))
    flank = gearset.working_flank(pair.pinion, pair.pinion_modifications, 1)
    return pair.pinion.base_radius, flank.base.form_roll, flank.base.tip_roll


def roll_length(row: dict, rb: float) -> float:
    return math.sqrt(row["contact_radius_pinion_mm"] ** 2 - rb ** 2)


def test_a_profile_slope_is_the_transmission_error_it_puts_at_each_contact():
    """A rigid, unloaded pair's transmission error (the gear's lag as a length on its base
    circle) is the material the pinion's profile slope removed at the point in contact:
    f_Hα·(s - s_mid)/(s_tip - s_form) at its roll length s, where two pairs touch the
    lesser of theirs. Measured within 0.016 µm of a 10 µm slope where one pair touches,
    0.054 µm where the pair low on the pinion takes the contact: second order in f_Hα (4
    times that at 20 µm), the slope turning the normal by f_Hα/(s_tip - s_form) = 0.7 mrad
    so that the gear's contact moves along its involute to meet it; asked to 0.06 µm."""
    raw = spur({"profile_slope": {"amount": "10 um"}})
    rb, s_form, s_tip = profile_ends(raw)
    rows = analyse(parse_case(raw)).sections["positions"]

    def drop_um(row):
        return 10.0 * (roll_length(row, rb) - 0.5 * (s_form + s_tip)) / (s_tip - s_form)

    for roll in sorted({r["roll_deg"] for r in rows}):
        here = [r for r in rows if r["roll_deg"] == roll]
        assert here[0]["transmission_error_um"] == pytest.approx(min(map(drop_um, here)),
                                                                 abs=0.06)


@pytest.mark.parametrize("field, amount, expected", [
    ("helix_slope", "12 um", "helix"), ("twist", "12 um", "twist")])
def test_a_linear_drop_moves_a_crowned_contact_by_minus_R_k(field, amount, expected):
    """On a crowned pinion (R = 4000 mm) a drop growing by k per mm of face moves the
    contact's minimum of w²/(2R) + k·w to w = -R·k: a helix slope f_Hβ by -R·f_Hβ/b at every
    position (-1.6 mm here), a twist S by -R·S·(s - s_mid)/((s_tip - s_form)·b), the tip
    contacts one way and the root's the other (the diagonal pattern of a twisted flank):
    each contact on the involute within 0.02 mm of the closed form (a corner contact at a
    tip's rounding is placed on the search grid's face positions, 0.75 mm apart)."""
    R, f = 4000.0, 0.012
    plain = spur({"crown": {"radius": f"{R} mm"}})
    modified = spur({"crown": {"radius": f"{R} mm"}, field: {"amount": amount}})
    rb, s_form, s_tip = profile_ends(plain)
    before = analyse(parse_case(plain)).sections["positions"]
    after = analyse(parse_case(modified)).sections["positions"]
    shifts = []
    for a, b in zip(before, after):
        assert (a["roll_deg"], a["pair"]) == (b["roll_deg"], b["pair"])
        if min(b["edge_margins_mm"].get(tip, math.inf) for tip in ("pinion_tip", "gear_tip")) < 0.1:
            continue                    # at a tip's rounding (within 0.1 mm of its start)
        if expected == "helix":
            k = f / FACE
        else:
            k = f * (roll_length(b, rb) - 0.5 * (s_form + s_tip)) / ((s_tip - s_form) * FACE)
        moved = b["face_position_mm"] - a["face_position_mm"]
        assert moved == pytest.approx(-R * k, abs=0.02)
        shifts.append(moved)
    if expected == "twist":
        assert min(shifts) < -0.5 and max(shifts) > 0.5


def test_a_helix_slope_of_the_misalignments_gap_restores_the_aligned_contact():
    """An uncrowned pair tilted 0.3 mrad (+ closes end B: 9 µm across the 30 mm face) loads
    end B (K_Hβ up); the pinion's helix slope f_Hβ = +θ·b = 9 µm, removing that much at end B
    relative to end A, brings the loaded contact back to the aligned pair's: K_Hβ and the
    largest line load within 2 %. The opposite sign doubles the tilt."""
    theta = 0.0003
    f = f"{theta * FACE * 1e3:.6g} um"

    def loaded(pinion, slope):
        result = analyse(parse_case(spur(pinion, slope, positions=4, grid=64)))
        return result.sections["summary"], result.sections["load_distribution"]

    aligned, aligned_lines = loaded({}, 0.0)
    tilted, _ = loaded({}, theta)
    corrected, corrected_lines = loaded({"helix_slope": {"amount": f}}, theta)
    doubled, _ = loaded({"helix_slope": {"amount": f"-{f}"}}, theta)
    assert tilted["K_H_beta"] > aligned["K_H_beta"] + 0.1
    assert corrected["K_H_beta"] == pytest.approx(aligned["K_H_beta"], rel=0.02)
    assert np.max(corrected_lines["line_load_N_per_mm"]) == pytest.approx(
        np.max(aligned_lines["line_load_N_per_mm"]), rel=0.02)
    assert doubled["K_H_beta"] > tilted["K_H_beta"] + 0.1


def test_a_linear_relief_start_is_blended_with_its_slope():
    """modify.relief_ramp: the blend joins none and the line with their values and slopes
    (C1: the drop's first derivative continuous, so the loaded pressure at a relief's start
    converges with the grid); outside the blend it is the line, at the relief's end the
    amount; a blend of 0 is the kink; a parabolic relief has none."""
    from toothcontact.surfaces.modify import relief_ramp

    h = 0.1
    xs = np.linspace(-0.3, 1.0, 1301)
    ys = relief_ramp(xs, "linear", 2 * h)
    slope = np.gradient(ys, xs)
    # the slope grows by at most the blend's curvature 1/(2h) per step (a kink: 0.5)
    assert np.max(np.abs(np.diff(slope))) <= 1.01 * (xs[1] - xs[0]) / (2 * h)
    assert ys[xs <= -h] == pytest.approx(0.0) and ys[-1] == pytest.approx(1.0)
    assert np.allclose(ys[xs >= h], xs[xs >= h])
    assert relief_ramp(np.array([0.0, 0.05]), "linear", 0.0) == pytest.approx([0.0, 0.05])
    assert relief_ramp(np.array([-0.05, 0.5]), "parabolic", 2 * h) == pytest.approx([0.0, 0.25])


def test_a_root_relief_removes_its_amount_at_the_form_circle_and_nothing_above_its_start():
    """The root relief's drop: its amount at the form circle, linear (or parabolic) to its
    start, none from there to the tip but for the start's blend (0.2 of its length by
    default: amount·0.2/8 at the start itself, none 0.1 of the length past it); the case
    refuses a start off the flank or above the tip relief's start, naming the field."""
    raw = spur({"root_relief": {"amount": "15 um", "start_diameter": "58 mm"}})
    pair = gearset.gear_pair(parse_case(raw))
    flank = gearset.working_flank(pair.pinion, pair.pinion_modifications, 1)
    start = pair.pinion_modifications.root_relief.start
    length = start - flank.base.form_roll
    s = np.array([flank.base.form_roll, 0.5 * (flank.base.form_roll + start), start,
                  start + 0.1 * length, flank.base.tip_roll - 2.0])
    drop = pair.pinion_modifications.root_relief.drop(s, flank.base.form_roll)
    assert drop == pytest.approx([0.015, 0.0075, 0.015 * 0.2 / 8, 0.0, 0.0], abs=1e-12)
    for pinion, says in (
            ({"root_relief": {"amount": "15 um", "start_diameter": "40 mm"}},
             "pinion.root_relief.start_diameter: 40 mm must lie between the base diameter"),
            ({"root_relief": {"amount": "15 um", "start_diameter": "62 mm"},
              "tip_relief": {"amount": "10 um", "start_diameter": "61 mm"}},
             "pinion.root_relief.start_diameter: 62 mm must lie between the form circle and "
             "the tip relief's start")):
        with pytest.raises(ValueError, match=says):
            gearset.gear_pair(parse_case(spur(pinion)))


def test_the_solid_follows_a_twisted_root_relieved_measured_flank():
    """The STEP solid's B-spline flanks of a helical pinion with a twist, a root relief and
    a measured topography (a 5 × 4 grid of bumps of ±3 µm) pass within 1 µm of the exact
    modified flank (the relief's start is a break of the profile the loft fits around)."""
    gear = CylindricalGear(23, 2.5, math.radians(20), 25.0, helix_angle=math.radians(20),
                           profile_shift=0.2)
    start = float(gear.base_radius * gear.roll_angle(0.5 * 58.5))
    rolls = [float(gear.base_radius * gear.roll_angle(0.5 * d)) for d in (58, 60.5, 63, 65.5)]
    bumps = 0.003 * np.sin(np.add.outer(np.linspace(0, 3, 5), np.linspace(0, 2, 4)))
    mods = FlankModifications(root_relief=RootRelief(0.010, start), twist=Twist(0.012),
                              topography=Topography(np.linspace(-12.5, 12.5, 5), rolls, bumps))
    assert start in mods.profile_breaks
    body = cad.build_gear(gear, mods, teeth=3)
    assert cad.is_valid(body.solid)
    assert cad.flank_deviation(body) < 1e-3


def test_the_modifications_are_toleranced_in_a_sweep():
    """[[tolerance]] field = "pinion.helix_slope.amount" (and the profile slope's, the
    twist's) draws the amount per sample: each sample's case carries its draw, in the
    band's unit (µm), inside the band."""
    from mutations import CASES

    from toothcontact.case import read_table
    from toothcontact.sweep.sampling import plan
    from toothcontact.sweep.spec import SweepSpec

    tolerances = [{"field": f"pinion.{name}.amount", "distribution": "uniform",
                   "low": "-8 um", "high": "8 um"}
                  for name in ("helix_slope", "profile_slope", "twist")]
    spec = SweepSpec.model_validate({"kind": "sweep", "base": "spur_crowned_20_60",
                                     "samples": 6, "tolerance": tolerances})
    samples = plan(spec, read_table(CASES / "spur_crowned_20_60.toml"))
    assert len(samples) == 6
    for sample in samples:
        mods = gearset.gear_pair(parse_case(sample.raw)).pinion_modifications
        for name, part in (("helix_slope", mods.helix_slope), ("profile_slope", mods.profile_slope),
                           ("twist", mods.twist)):
            assert -0.008 <= part.amount <= 0.008
            assert sample.inputs[f"pinion.{name}.amount"].endswith("µm")


def crown_grid(R: float, faces: int = 13, diameters=(58.0, 60.0, 62.0, 64.0, 66.0)) -> dict:
    """A topography that samples a circular lead crown of radius R (its drop
    R - sqrt(R² - w²), in µm) on `faces` face positions across the 30 mm face."""
    face = np.linspace(-0.5 * FACE, 0.5 * FACE, faces)
    rows = [[1e3 * (R - math.sqrt(R * R - w * w))] * len(diameters) for w in face]
    return {"face": [f"{w:.6g} mm" for w in face], "diameter": [f"{d} mm" for d in diameters],
            "deviation_um": rows}


def test_a_topography_sampling_a_crown_is_that_crowns_contact():
    """A measured grid of 13 face positions × 5 diameters that samples a circular crown of
    R = 4000 mm, on a pinion tilted 0.3 mrad: every contact's Hertz pressure, semi-axes and
    face position within 1 % (0.02 mm) of the crown's own (the spline is exact for a
    parabola and a circle this flat differs from one by 1e-10 mm)."""
    R = 4000.0
    crowned = analyse(parse_case(spur({"crown": {"radius": f"{R} mm"}}, 0.0003)))
    measured = analyse(parse_case(spur({"topography": crown_grid(R)}, 0.0003)))
    a, b = crowned.sections["positions"], measured.sections["positions"]
    assert [(r["roll_deg"], r["pair"]) for r in a] == [(r["roll_deg"], r["pair"]) for r in b]
    for x, y in zip(a, b):
        for key in ("p_max_MPa", "a_mm", "b_mm"):
            assert y[key] == pytest.approx(x[key], rel=0.01)
        assert y["face_position_mm"] == pytest.approx(x["face_position_mm"], abs=0.02)


def test_a_topography_file_is_the_inline_grid(tmp_path):
    """The CSV layout of the README (a label cell and the diameters, then a face position and
    its deviations per row) gives the grid written inline; a bad cell, a ragged row, a
    diameter below the base circle or a file beside the inline grid are refused naming the
    field."""
    grid = crown_grid(4000.0, faces=5)
    lines = ["face_mm/diameter_mm," + ",".join(d.split()[0] for d in grid["diameter"])]
    lines += [f"{w.split()[0]}," + ",".join(f"{v:.9g}" for v in row)
              for w, row in zip(grid["face"], grid["deviation_um"])]
    (tmp_path / "k.csv").write_text("\n".join(lines) + "\n")
    from toothcontact.case import load_case
    import tomli_w

    case_file = tmp_path / "case.toml"
    case_file.write_text(tomli_w.dumps(spur({"topography": {"file": "k.csv"}})))
    from_file = gearset.gear_pair(load_case(case_file)[0]).pinion_modifications.topography
    inline = gearset.gear_pair(parse_case(spur({"topography": grid}))).pinion_modifications.topography
    assert np.allclose(from_file.deviation, inline.deviation, atol=1e-12)
    assert np.allclose(from_file.face, inline.face) and np.allclose(from_file.roll, inline.roll)

    import mutations

    (tmp_path / "bad.csv").write_text(lines[0] + "\n" + lines[1] + "\n-3,1,x,1,1,1\n")
    bad = dict(grid, deviation_um=[row[:-1] for row in grid["deviation_um"]])
    low = dict(grid, diameter=["50 mm", "60 mm", "62 mm", "64 mm", "66 mm"])
    for topography, says in (({"file": "bad.csv"}, "row 3, column 3: 'x' is not a number"),
                             (bad, "deviation_um: 5 rows of [4] numbers"),
                             (low, "pinion.topography.diameter: 50 mm must lie above the base"),
                             (dict(grid, file="k.csv"), "give the grid inline or as a file")):
        line = mutations.refused_line(tomli_w.dumps(spur({"topography": topography})), tmp_path)
        assert "pinion.topography" in line and says in line, line


def measured_surface(w, d):
    """A flank deviation (µm) over face position w and diameter d (mm): a lead crown, a
    profile crown, a helix slope and a twist: polynomial of degree two in each direction."""
    return w * w / 30.0 + 0.4 * (d - 62.0) ** 2 - 0.1 * w + 0.06 * w * (d - 62.0)


def k_chart(face=(-12.0, 0.0, 12.0), diameters=(59.0, 62.0, 65.0)) -> dict:
    """Three profile traces and three lead traces of measured_surface, as a gear measuring
    machine reports them."""
    profile_d = np.linspace(57.5, 66.5, 10)
    lead_w = np.linspace(-15.0, 15.0, 13)
    return {"profile_face": [f"{w} mm" for w in face],
            "profile_diameter": [f"{d:.6g} mm" for d in profile_d],
            "profile_um": [[measured_surface(w, d) for d in profile_d] for w in face],
            "lead_diameter": [f"{d} mm" for d in diameters],
            "lead_face": [f"{w:.6g} mm" for w in lead_w],
            "lead_um": [[measured_surface(w, d) for w in lead_w] for d in diameters]}


def test_a_k_chart_is_the_surface_its_traces_were_measured_on():
    """Gordon's interpolation of three profile and three lead traces (cubic-spline cardinal
    blends) passes through every trace and, for a surface of degree two in each direction
    (crowns, slope, twist), is that surface everywhere: the grid within 0.002 µm of it
    (measured 0.0009 µm: the blend runs in roll length, in which a quadratic in the
    diameter is not one), and the contacts of the pair as with the surface given as a dense
    grid (pressures within 0.1 %, TE within 0.005 µm). Traces
    that disagree where they cross are averaged there, with a note; a K-chart beside a grid
    is refused."""
    from toothcontact.surfaces.modify import k_chart_grid

    spec = k_chart()
    pair = gearset.gear_pair(parse_case(spur({"k_chart": spec})))
    topo = pair.pinion_modifications.topography
    lead_w = np.linspace(-15.0, 15.0, 13)
    profile_d = np.linspace(57.5, 66.5, 10)
    truth = np.array([[measured_surface(w, d) for d in profile_d] for w in lead_w])
    assert np.allclose(topo.face, lead_w) and np.abs(1e3 * topo.deviation - truth).max() < 0.002
    dense_w, dense_d = np.linspace(-15, 15, 31), np.linspace(57.5, 66.5, 19)
    dense = {"face": [f"{w:.6g} mm" for w in dense_w],
             "diameter": [f"{d:.6g} mm" for d in dense_d],
             "deviation_um": [[measured_surface(w, d) for d in dense_d] for w in dense_w]}
    charted = analyse(parse_case(spur({"k_chart": spec}, 0.0002))).sections["positions"]
    gridded = analyse(parse_case(spur({"topography": dense}, 0.0002))).sections["positions"]
    for x, y in zip(charted, gridded):
        assert (x["roll_deg"], x["pair"]) == (y["roll_deg"], y["pair"])
        assert x["p_max_MPa"] == pytest.approx(y["p_max_MPa"], rel=1e-3)
        assert x["transmission_error_um"] == pytest.approx(y["transmission_error_um"], abs=0.005)

    shifted = dict(spec, lead_um=[[v + 2.0 for v in row] for row in spec["lead_um"]])
    with pytest.warns(UserWarning, match=r"pinion.k_chart: the profile and lead traces differ "
                                         r"by up to 2.00 µm where they cross"):
        gearset.gear_pair(parse_case(spur({"k_chart": shifted})))
    grid, worst = k_chart_grid([0.0], [1.0, 2.0], [[0.0, 0.0]], [1.5], [-1.0, 1.0], [[2.0, 2.0]])
    assert worst == pytest.approx(2.0) and np.allclose(grid, 1.0)     # the mean where they cross
    with pytest.raises(CaseError, match="^case: pinion: topography / k_chart: give the measured "
                                        "flank one way"):
        parse_case(spur({"k_chart": spec, "topography": dense}))


def test_the_bundled_measured_flank_is_its_generators_grid(tmp_path):
    """cases/helical_measured_topography.csv is what data/measured's generator writes (crown,
    profile slope, twist, tip relief and seeded noise), and the case reads it as the
    pinion's topography: each grid value at its face position and roll length (µm -> mm)."""
    import importlib.util
    from pathlib import Path

    from mutations import CASES

    from toothcontact.case import load_case

    root = Path(__file__).resolve().parents[1]
    spec = importlib.util.spec_from_file_location(
        "generator", root / "data" / "measured" / "helical_pinion_topography.py")
    generator = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(generator)
    generator.write(tmp_path / "grid.csv")
    shipped = CASES / "helical_measured_topography.csv"
    assert (tmp_path / "grid.csv").read_text() == shipped.read_text()
    pair = gearset.gear_pair(load_case(CASES / "helical_measured_topography.toml")[0])
    grid = pair.pinion_modifications.topography
    rb = pair.pinion.base_radius
    assert np.allclose(grid.face, generator.FACE)
    assert np.allclose(grid.roll, np.sqrt((generator.DIAMETER / 2) ** 2 - rb ** 2), atol=1e-9)
    assert np.allclose(grid.deviation, np.round(generator.deviation_um(), 2) * 1e-3, atol=1e-12)


def test_the_k_chart_traces_are_the_modifications_as_made():
    """member_modifications.k_chart_traces on the bundled crowned pair: the pinion's lead
    trace is its circular crown, R - sqrt(R² - z²) (R = 4000 mm) to 1e-9 mm at every face
    position, the uncrowned gear's lead flat; the profile trace runs from the form to the
    tip diameter, zero below the tip edge's start and rising on the rounding."""
    import math

    from toothcontact.case import load_case
    from toothcontact.member_modifications import k_chart_traces

    case, _ = load_case(Path(__file__).parents[1] / "cases" / "spur_crowned_20_60.toml")
    pair = gearset.gear_pair(case)
    pinion = k_chart_traces(pair.pinion_modifications, pair.pinion)
    gear = k_chart_traces(pair.gear_modifications, pair.gear)
    for z, drop in zip(pinion["lead_face_mm"], pinion["lead_um"]):
        assert drop == pytest.approx(1e3 * (4000.0 - math.sqrt(4000.0 ** 2 - z ** 2)), abs=1e-6)
    assert max(map(abs, gear["lead_um"])) < 1e-9
    d = np.asarray(pinion["profile_diameter_mm"])
    assert d[-1] == pytest.approx(2 * pair.pinion.tip_radius, abs=1e-9) and d[0] < d[-1]
    profile = np.asarray(pinion["profile_um"])
    assert profile[d < d[-1] - 1.0].max() == 0.0 and profile[-1] > 10.0
