"""Pictures, rendered off-screen: the paint shows where the contact is computed to be, edge
contact turns the warning colour on (and only then), every picture is written whole."""

import math
from dataclasses import replace
from pathlib import Path
from types import SimpleNamespace

import numpy as np
import pytest
from matplotlib.colors import rgb_to_hsv, to_rgb
from typer.testing import CliRunner

from toothcontact import analyses
from toothcontact.views import pictures, scene, scene_geometry, scene_style, style
from toothcontact.surfaces.placement import Frame, rotation
from toothcontact.case import parse_case
from toothcontact.cli import app


def spur_case(slope: float):
    """The bundled crowned spur pair, three positions, no interference or loaded solve (fast);
    a tip relief keeps the first and last contacts off the tip edge."""
    return parse_case({
        "kind": "spur", "title": "render test", "teeth": [20, 60], "module": "3 mm",
        "pressure_angle": "20 deg", "face_width": "30 mm",
        "pinion": {"crown": {"radius": "4000 mm"},
                   "tip_relief": {"amount": "20 um", "start_diameter": "64 mm"}},
        "misalignment": {"slope": str(slope)}, "load": {"tangential_load": "8000 N"},
        "analysis": {"positions": 3, "interference": False, "pressure_grid": 0}})


@pytest.fixture(scope="module")
def aligned():
    case = spur_case(0.0)
    return case, analyses.analyse(case)


@pytest.fixture(scope="module")
def tilted():
    case = spur_case(0.004)
    return case, analyses.analyse(case)


def hsv(image: np.ndarray) -> np.ndarray:
    return rgb_to_hsv(image.astype(float) / 255.0)


def hue_distance(h: np.ndarray, target: float) -> np.ndarray:
    d = np.abs(h - target)
    return np.minimum(d, 1.0 - d)


CONTACT_HUE = float(rgb_to_hsv(np.array(to_rgb(scene_style.CONTACT)))[0])
WARNING_HUE = float(rgb_to_hsv(np.array(to_rgb(scene_style.WARNING)))[0])


def is_contact_colour(pixels: np.ndarray) -> np.ndarray:
    """The paint at (nearly) zero separation: the CONTACT hue, saturated, shaded by the
    lights but not washed out."""
    h = hsv(pixels)
    return (hue_distance(h[..., 0], CONTACT_HUE) < 0.04) & (h[..., 1] > 0.6) & (h[..., 2] > 0.25)


def is_warning_colour(pixels: np.ndarray) -> np.ndarray:
    h = hsv(pixels)
    return (hue_distance(h[..., 0], WARNING_HUE) < 0.03) & (h[..., 1] > 0.55) & (h[..., 2] > 0.45)


def window(image: np.ndarray, pixel, half: int = 3) -> np.ndarray:
    c, r = (int(round(x)) for x in pixel)
    return image[max(r - half, 0):r + half + 1, max(c - half, 0):c + half + 1]


def test_the_warning_colour_is_the_plots_warning_colour():
    assert scene_style.WARNING == style.WARNING


def test_pattern_is_not_blank_and_paints_where_the_contact_is(aligned):
    case, result = aligned
    cycle = result.cycle
    plotter = pictures.pattern_scene(result, case, "test", "head-on")
    image = scene.screenshot(plotter)
    assert image.shape == (scene_style.WINDOW[1], scene_style.WINDOW[0], 3)
    colours = np.unique(image.reshape(-1, 3), axis=0)
    assert len(colours) > 500                                    # not blank
    # every contact point of the cycle, projected by the plotter's camera, is painted in the
    # contact colour (tooth 0's flank: each row's point carried by its own pinion frame)
    for k in range(len(cycle.rows)):
        local = cycle.pinion_frames[np.array([k])].to_local(cycle.planes.point[[k]])
        pixel = scene.project(plotter, local)[0]
        assert 0 <= pixel[0] < image.shape[1] and 0 <= pixel[1] < image.shape[0]
        assert is_contact_colour(window(image, pixel)).mean() > 0.5, (k, pixel)
    # the face ends, where the crown opens the gap beyond the approach, are not painted
    (u0, u1), (v0, v1) = cycle.pinion.domain
    for v in (v0 + 0.03 * (v1 - v0), v1 - 0.03 * (v1 - v0)):
        end = np.stack(cycle.pinion.point(np.array([0.5 * (u0 + u1)]), np.array([v])), axis=-1)
        pixel = scene.project(plotter, end)[0]
        assert not is_contact_colour(window(image, pixel)).any()
    plotter.close()
    # without edge contact nothing is in the warning colour
    assert not any(r["edge_contact"] for r in cycle.rows)
    assert is_warning_colour(image).sum() == 0


def test_pressure_at_the_position_of_the_largest_pressure(aligned):
    """Beside the envelope over the cycle, the pressure at one position: the position whose
    loaded contact holds the largest design pressure (its rows' bem_p_max_MPa), only its
    pairs painted: the map's peak is that position's and it covers a part of the envelope's
    painted area."""
    case, result = aligned
    cycle = result.cycle
    rows = [dict(r, bem_p_max_MPa=r["p_max_MPa"]) for r in cycle.rows]
    roll = scene_geometry.peak_position(rows)
    assert roll == max(rows, key=lambda r: r["p_max_MPa"])["roll_deg"]
    cycle = replace(cycle, rows=rows)
    loaded = SimpleNamespace(cycle=cycle, loaded=synthetic_loaded(cycle))
    patch = scene_geometry.flank_patch(cycle)
    at_roll = [item if r["roll_deg"] == roll else None for item, r in zip(loaded.loaded, rows)]
    _, envelope = scene_geometry.pressure_on_flank(cycle, loaded.loaded, patch)
    _, one = scene_geometry.pressure_on_flank(cycle, at_roll, patch)
    here = max(r["p_max_MPa"] for r in rows if r["roll_deg"] == roll)
    assert one.max() == pytest.approx(here, rel=0.05)
    assert 0 < (one > 0).sum() < 0.5 * (envelope > 0).sum()
    plotter = pictures.pressure_scene(loaded, case, "test", patch, roll)
    image = scene.screenshot(plotter)
    plotter.close()
    assert len(np.unique(image.reshape(-1, 3), axis=0)) > 300
    assert scene_geometry.peak_position([{"roll_deg": 0.0, "bem_p_max_MPa": None}]) is None


def test_a_cut_ellipse_is_drawn_along_the_edge_not_past_it(tilted):
    """Under a 4 mrad slope every ellipse crosses end B: its outline runs along the flank's
    edge there (every point on the flank: inside its face to 1 µm), and it reaches that
    edge (the cut shows)."""
    case, result = tilted
    outlines = scene_geometry.ellipse_outlines(result.cycle)
    half = 0.5 * case.face_width
    assert np.isfinite(outlines).all()
    assert np.abs(outlines[..., 2]).max() <= half + 1e-3
    assert all(np.abs(line[:, 2]).max() > half - 1e-3 for line in outlines)


def test_edge_contact_turns_the_warning_colour_on_at_its_edge(tilted):
    case, result = tilted
    cycle = result.cycle
    assert all(r["edge_margins_mm"].get("pinion_end_B", 0.0) < 0 for r in cycle.rows)
    plotter = pictures.pattern_scene(result, case, "test", "head-on")
    image = scene.screenshot(plotter)
    warning = is_warning_colour(image)
    assert warning.sum() > 500
    # and it is at end B: the warning pixels near the end B edge's projection
    (u0, u1), (v0, v1) = cycle.pinion.domain
    u = np.linspace(u0, u1, 9)
    edge_b = np.stack(cycle.pinion.point(u, np.full_like(u, v1)), axis=-1)
    edge_a = np.stack(cycle.pinion.point(u, np.full_like(u, v0)), axis=-1)
    at_b = scene.project(plotter, edge_b)
    at_a = scene.project(plotter, edge_a)
    plotter.close()
    assert sum(is_warning_colour(window(image, p, 4)).any() for p in at_b) >= 2
    assert not any(is_warning_colour(window(image, p, 4)).any() for p in at_a)
    # the red lies on end B's side of the flank (an ellipse reaches beyond the edge)
    top, bottom = np.concatenate([at_a[:, 1], at_b[:, 1]]).min(), np.concatenate(
        [at_a[:, 1], at_b[:, 1]]).max()
    _, cols = np.nonzero(warning[int(top) - 40:int(bottom) + 40])
    middle = 0.5 * (at_a[:, 0].mean() + at_b[:, 0].mean())
    toward_b = np.sign(at_b[:, 0].mean() - middle)
    assert np.mean(np.sign(cols - middle) == toward_b) > 0.95


def synthetic_loaded(cycle, n: int = 48):
    """A loaded solution per row as the loaded-contact module gives it: a Hertz pressure
    field on a grid of the row's tangent plane (x along e1, y along e2)."""
    out = []
    for k, row in enumerate(cycle.rows):
        a, b, angle = row["a_mm"], row["b_mm"], float(cycle.axis_angle[k])
        x = np.linspace(-1.3 * a, 1.3 * a, n)
        y = np.linspace(-1.3 * b, 1.3 * b, n)
        X, Y = np.meshgrid(x, y, indexing="ij")
        xa = X * math.cos(angle) + Y * math.sin(angle)
        yb = -X * math.sin(angle) + Y * math.cos(angle)
        p = row["p_max_MPa"] * np.sqrt(np.clip(1 - (xa / a) ** 2 - (yb / b) ** 2, 0, None))
        out.append(SimpleNamespace(field=SimpleNamespace(x=x, y=y, material=np.ones_like(p, bool),
                                                            turn=0.0),
                                   solution=SimpleNamespace(pressure_MPa=p)))
    return out


def test_pressure_map_from_the_loaded_contact(aligned):
    case, result = aligned
    cycle = result.cycle
    loaded = SimpleNamespace(cycle=cycle, loaded=synthetic_loaded(cycle))
    patch = scene_geometry.flank_patch(cycle)
    _, pressure = scene_geometry.pressure_on_flank(cycle, loaded.loaded, patch)
    assert pressure.max() == pytest.approx(max(r["p_max_MPa"] for r in cycle.rows), rel=0.05)
    plotter = pictures.pressure_scene(loaded, case, "test", patch)
    image = scene.screenshot(plotter)
    top_hue = float(rgb_to_hsv(np.array(to_rgb("#fde725")))[0])       # viridis' top
    k = int(np.argmax([r["p_max_MPa"] for r in cycle.rows]))
    local = cycle.pinion_frames[np.array([k])].to_local(cycle.planes.point[[k]])
    h = hsv(window(image, scene.project(plotter, local)[0], 2))
    plotter.close()
    assert (hue_distance(h[..., 0], top_hue) < 0.06).mean() > 0.5


def test_the_pressure_maps_scale_is_the_flanks(aligned):
    """The colour scale tops out at the flank's largest pressure (flank_p_max_MPa), so the
    flank's own pattern spans it: where an edge or corner contact's design pressure
    (bem_p_max_MPa) lies above it (here the peak row's, 1/0.6 of the flank's largest), its
    cells are the warning red; within 5 % of it the scale is the design peak's and nothing
    is red (the aligned pair has no edge contact)."""
    case, result = aligned
    top = max(r["p_max_MPa"] for r in result.cycle.rows)
    k = int(np.argmax([r["p_max_MPa"] for r in result.cycle.rows]))
    for flank_share, red in ((0.6, True), (0.98, False)):
        rows = [dict(r, bem_p_max_MPa=r["p_max_MPa"], flank_p_max_MPa=flank_share * top)
                for r in result.cycle.rows]
        cycle = replace(result.cycle, rows=rows)
        loaded = SimpleNamespace(cycle=cycle, loaded=synthetic_loaded(cycle))
        patch = scene_geometry.flank_patch(cycle)
        plotter = pictures.pressure_scene(loaded, case, "test", patch)
        image = scene.screenshot(plotter)
        local = cycle.pinion_frames[np.array([k])].to_local(cycle.planes.point[[k]])
        at_peak = window(image, scene.project(plotter, local)[0], 2)
        plotter.close()
        if red:
            assert is_warning_colour(at_peak).mean() > 0.5
        else:
            assert is_warning_colour(image).sum() == 0


def test_a_flank_map_carries_its_face_positions_and_diameters():
    """add_flank_ticks labels the form edge with round face positions (mm from mid-face) and
    end B with round diameters, the last with its unit, none where the edge's own name
    stands (its middle 30 %), each off the edge away from the flank's centre."""
    labels = []
    plotter = SimpleNamespace(add_point_labels=lambda point, text, **_: labels.append(
        (point[0], text[0])))
    t = np.linspace(0.0, 1.0, 61)
    form = np.column_stack([np.full_like(t, 34.0), np.zeros_like(t), -7.0 + 14.0 * t])
    end_b = np.column_stack([34.0 + 7.0 * t, np.zeros_like(t), np.full_like(t, 7.0)])
    centre = np.array([37.5, 0.0, 0.0])
    scene.add_flank_ticks(plotter, {"form": form, "end_B": end_b, "tip": form + [7, 0, 0]},
                          centre, 1.0)
    texts = [text for _, text in labels]
    assert texts == ["-6", "-3", "3", "6 mm", "d 69", "d 72", "d 78", "d 81 mm"]
    # off their edges, away from the centre: below the form edge (radius 34), beyond end B
    assert all(point[0] < 34.0 for point, text in labels if not text.startswith("d "))
    assert all(point[2] > 7.0 for point, text in labels if text.startswith("d "))


def test_pictures_of_a_contact_case_are_written_whole(aligned, tmp_path):
    case, result = aligned
    result = SimpleNamespace(cycle=result.cycle, loaded=synthetic_loaded(result.cycle),
                             parts=result.parts, sections=result.sections)
    written = pictures.pictures_for(result, case, tmp_path, name="test", exaggerate=20.0)
    assert [p.name for p in written] == ["pattern_head_on.png", "pattern_perspective.png",
                                         "pair.png", "pressure.png"]
    assert sorted(p.name for p in tmp_path.iterdir()) == sorted(p.name for p in written)
    from PIL import Image

    for path in written:
        image = np.asarray(Image.open(path).convert("RGB"))
        # the head-on pictures are cut off below their colour bar (the frame filled)
        assert image.shape[1:] == (scene_style.WINDOW[0], 3)
        assert 0.4 * scene_style.WINDOW[1] < image.shape[0] <= scene_style.WINDOW[1]
        assert len(np.unique(image.reshape(-1, 3), axis=0)) > 300, path.name
        # the bottom rows hold the colour bar's labels, not an empty band
        assert len(np.unique(image[-int(0.15 * scene_style.WINDOW[1]):].reshape(-1, 3), axis=0)) > 20


def test_a_bad_position_fails_before_anything_is_written(aligned, tmp_path):
    from toothcontact.case import CaseError

    case, result = aligned
    with pytest.raises(CaseError, match="--position"):
        pictures.pictures_for(result, case, tmp_path / "out", position=7)
    assert not (tmp_path / "out").exists()


def test_exaggerated_misalignment_multiplies_the_relative_motion():
    nominal_p = Frame.stack([Frame(rotation([0, 0, 1], 0.3), np.zeros(3))])
    nominal_g = Frame.stack([Frame(rotation([0, 0, 1], -0.1), np.array([100.0, 0, 0]))])
    tilt = rotation([0, 1, 0], 0.001)
    placed_g = Frame.stack([Frame(tilt @ nominal_g.R[0], tilt @ nominal_g.origin[0, 0]
                                  + np.array([0.02, 0, 0]))])
    same = pictures.exaggerated_frame(nominal_p, placed_g, nominal_p, nominal_g, 1.0)
    assert np.allclose(same.R, placed_g.R) and np.allclose(same.origin, placed_g.origin)
    ten = pictures.exaggerated_frame(nominal_p, placed_g, nominal_p, nominal_g, 10.0)
    relative = ten.R[0] @ nominal_g.R[0].T
    angle = math.acos((np.trace(relative) - 1) / 2)
    assert angle == pytest.approx(0.01, rel=1e-9)


def test_render_command(tmp_path):
    runner = CliRunner()
    cases = Path(__file__).parents[1] / "cases"
    result = runner.invoke(app, ["render", str(cases / "hertz_sphere_on_flat.toml"),
                                 "--out", str(tmp_path)])
    assert result.exit_code == 0 and "no 3D picture" in result.output
    assert not (tmp_path / "hertz_sphere_on_flat").exists()
    result = runner.invoke(app, ["render", str(cases / "worm_saba_set.toml"),
                                 "--out", str(tmp_path)])
    assert result.exit_code == 0, result.output
    assert [p.name for p in (tmp_path / "worm_saba_set").iterdir()] == ["pair.png"]
    result = runner.invoke(app, ["render", str(cases / "spur_crowned_20_60.toml"), "--out",
                                 str(tmp_path), "--exaggerate", "-1"])
    assert result.exit_code == 2 and "--exaggerate" in result.output


@pytest.mark.parametrize("half", [0.3, 2.0, 10.0, 47.0])
def test_the_scale_bar_is_a_round_length_drawn_to_scale(half):
    """A head-on picture's mm bar: 1, 2 or 5 × 10^k mm, between a fifteenth and a sixth of
    the window's width, and on the screen exactly that long (its ends projected through
    the camera: pixels per mm = window height / (2·half) in an orthographic view)."""
    pv = scene.load_pyvista()
    plotter = scene.new_plotter(pv)
    focus, normal, up = np.zeros(3), np.array([0.0, 0.0, 1.0]), np.array([0.0, 1.0, 0.0])
    scene.set_camera(plotter, focus, normal, up, half, parallel=True)
    before = len(plotter.renderer.actors)
    length = scene._scale_bar(plotter, focus, normal, up, half)
    width = 2.0 * half * scene_style.WINDOW[0] / scene_style.WINDOW[1]
    mantissa = length / 10.0 ** math.floor(math.log10(length))
    assert round(mantissa, 9) in (1.0, 2.0, 5.0)
    assert width / 15.0 < length <= width / 6.0
    bar = list(plotter.renderer.actors.values())[before].GetMapper().GetInput()
    ends = scene.project(plotter, np.asarray(bar.points))
    assert abs(ends[1, 0] - ends[0, 0]) == pytest.approx(
        length * scene_style.WINDOW[1] / (2.0 * half), rel=0.01)
    plotter.close()


def test_the_colour_bars_title_stands_clear_of_its_tick_labels(aligned):
    """VTK drew a horizontal colour bar's title over its tick labels (issue 28): the bar
    carries no title of its own, and the title is a text above the bar's box, below the
    scale bar's height."""
    case, result = aligned
    plotter = pictures.pattern_scene(result, case, "test", "head-on")
    scene._bar_title(plotter)
    bar = plotter.scalar_bar
    assert not bar.GetTitle().strip()
    x, y = bar.GetPosition()
    _, height = bar.GetPosition2()
    texts = [a for a in plotter.renderer.actors.values()
             if hasattr(a, "GetInput") and isinstance(a.GetInput(), str)
             and a.GetInput().startswith("least separation over the mesh cycle")]
    assert len(texts) == 1
    coordinate = texts[0].GetPositionCoordinate()
    tx, ty = coordinate.GetValue()[:2]
    assert tx == pytest.approx(x) and ty > y + height
    plotter.close()


def test_a_helical_pair_is_seen_across_its_contact_lines(tmp_path):
    """A 20 deg helical pair's contact line, 20 mm long on the flank, drawn in pair.png
    seen from nearer the contact normal than the axis: on the screen it spans more than
    300 px (measured 495 px; seen from the end, mostly along the axis, 161 px)."""
    case = parse_case({"kind": "spur", "title": "helical view", "teeth": [23, 57],
                       "module": "2.5 mm", "pressure_angle": "20 deg", "helix_angle": "20 deg",
                       "face_width": "25 mm", "pinion": {"crown": {"radius": "8000 mm"}},
                       "load": {"tangential_load": "6000 N"},
                       "analysis": {"positions": 1, "interference": False, "pressure_grid": 0,
                                    "positions_check": False}})
    result = analyses.analyse(case)
    plotter = pictures.pair_scene(result, case, "test")
    cycle = result.cycle
    k = max(range(len(cycle.rows)), key=lambda j: cycle.rows[j]["p_max_MPa"])
    outline = cycle.pinion_frames[np.array([k])].to_world(scene_geometry.ellipse_outlines(cycle)[k][None])[0]
    pixels = scene.project(plotter, outline)
    axis = cycle.pinion_frames.R[k][:, 2]
    looking = np.asarray(plotter.camera.direction)
    plotter.close()
    assert cycle.rows[k]["a_mm"] > 9.0
    assert np.ptp(pixels, axis=0).max() > 300
    assert abs(np.dot(looking, axis)) < math.cos(math.radians(45))


def test_without_the_ease_off_only_the_pair_is_drawn(aligned, tmp_path):
    """[analysis] ease_off = false: the pattern and the pressure are painted on the ease-off,
    which the analysis did not map; the pair at its position is drawn, and nothing else."""
    import dataclasses

    case, result = aligned
    result = SimpleNamespace(cycle=dataclasses.replace(result.cycle, ease_off=None),
                             loaded=synthetic_loaded(result.cycle), parts=result.parts,
                             sections=result.sections)
    written = pictures.pictures_for(result, case, tmp_path, name="test")
    assert [p.name for p in written] == ["pair.png"]
    assert sorted(p.name for p in tmp_path.iterdir()) == ["pair.png"]
