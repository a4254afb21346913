"""Figures (plots.py): each writes a PNG of the stated size that shows what it claims.

Pixel checks read the written PNG: a blank or missing element changes the colours found."""

import json

import numpy as np
import pytest
from matplotlib import colormaps
from matplotlib.colors import to_rgb
from PIL import Image
from scipy import ndimage

from toothcontact import analyses, case as schema, runner
from toothcontact.views import design_charts, plots, report, style

WIDTH = 1020  # 8.5 in at 120 dpi


def _result(name: str, tmp_path, **changes) -> dict:
    """A bundled case (with `changes` to its raw table) analysed and read back from the
    result.json that `report.write_run` writes."""
    raw = dict(schema.load_case(runner.bundled_cases_dir() / f"{name}.toml")[1], **changes)
    case = schema.parse_case(raw)
    document = report.result_document(name, case, raw, analyses.analyse(case))
    out = tmp_path / f"result_{name}"
    report.write_run(out, document)
    return json.loads((out / "result.json").read_text())


def _rgb(path, size) -> np.ndarray:
    image = Image.open(path)
    assert image.format == "PNG" and image.size == size
    return np.asarray(image.convert("RGB")).astype(np.int32)


def _near(rgb: np.ndarray, colour, tol: float = 40.0) -> np.ndarray:
    target = np.round(255.0 * np.array(colour if isinstance(colour, tuple)
                                       else to_rgb(colour))[:3]).astype(int)
    return ((rgb - target) ** 2).sum(axis=-1) < tol * tol


def _reddish(rgb: np.ndarray) -> np.ndarray:
    """Pixels of the warning red, also where a thin line blends it with the background."""
    r, g, b = np.moveaxis(rgb, -1, 0)
    return (r > 150) & (r - np.maximum(g, b) > 70)


def _distinct(rgb: np.ndarray) -> int:
    return len(np.unique((rgb[..., 0] << 16) | (rgb[..., 1] << 8) | rgb[..., 2]))


# --------------------------------------------------------------------------- mesh cycle


def _cycle(edge: bool, kind: str = "spur") -> dict:
    """A small mesh cycle with the keys of result['positions']: two pairs, pair 1 leaving
    after the sixth position, one line-contact row (b None, margin "nan")."""
    rows = []
    for i, roll in enumerate(np.linspace(-9.0, 9.0, 11)):
        for pair in (0, 1) if i < 6 else (0,):
            line = pair == 1 and i == 2
            margin = 0.8 - 0.1 * i + 0.5 * pair if edge else 0.3 + 0.1 * i
            rows.append({"roll_deg": float(roll), "pair": pair,
                         "transmission_error_urad": -15.0 + 0.01 * (i % 4),
                         "p_max_MPa": 1200.0 + 50 * i + 100 * pair,
                         "a_mm": 6.35 if line else 8.0 + 0.1 * i, "b_mm": None if line else 0.2,
                         "edge_margin_mm": "nan" if line else margin,
                         "edge_contact": (not line) and margin < 0,
                         "contact_model": "line" if line else "ellipse",
                         "edge_margins_mm": {} if line else {"pinion_tip": margin,
                                                             "gear_end_A": 3.0}})
    return {"case": "synthetic", "kind": kind, "title": "synthetic cycle", "positions": rows}


def test_mesh_cycle_draws_edge_contact_in_red_only_when_there_is_some(tmp_path):
    edged = _cycle(edge=True)
    assert any(r["edge_contact"] for r in edged["positions"])
    rgb = _rgb(plots.mesh_cycle(edged, tmp_path / "edge.png"), (WIDTH, 888))
    assert _distinct(rgb) > 300
    assert _reddish(rgb).sum() > 50

    clear = _cycle(edge=False)
    assert not any(r["edge_contact"] for r in clear["positions"])
    rgb = _rgb(plots.mesh_cycle(clear, tmp_path / "clear.png"), (WIDTH, 888))
    assert _distinct(rgb) > 300
    assert _reddish(rgb).sum() == 0
    # every series colour is drawn (two pairs)
    for colour in style.SERIES[:2]:
        assert _near(rgb, colour, 20).sum() > 200


def test_mesh_cycle_of_a_spline_runs_over_the_tooth_index(tmp_path):
    """kind 'spline': one series per position over the teeth (three positions here)."""
    rows = [{"roll_deg": roll, "pair": tooth, "transmission_error_urad": 3039.2 + 0.1 * (roll == 0),
             "p_max_MPa": 30.0 + 40.0 * (tooth % 9 == 0) + roll, "a_mm": 2.0 + 0.05 * roll,
             "b_mm": 0.8, "edge_margin_mm": -1.6 + 0.01 * roll if tooth % 9 == 0 else "nan",
             "edge_contact": tooth % 9 == 0,
             "contact_model": "line" if tooth % 9 else "ellipse"}
            for roll in (-10.0, 0.0, 10.0) for tooth in range(18)]
    result = {"case": "spline", "kind": "spline", "positions": rows}
    rgb = _rgb(plots.mesh_cycle(result, tmp_path / "spline.png"), (WIDTH, 888))
    for colour in style.SERIES[:3]:
        assert _near(rgb, colour, 20).sum() > 200
    assert _reddish(rgb).sum() > 50
    with pytest.raises(ValueError, match="positions"):
        plots.mesh_cycle({"kind": "spur"}, tmp_path / "none.png")


# --------------------------------------------------------------------------- ease-off


def _field(x0: float, y0: float):
    x, y = np.linspace(-10.0, 10.0, 41), np.linspace(20.0, 30.0, 31)
    X, Y = np.meshgrid(x, y)
    return x, y, 0.5 * (X - x0) ** 2 + 1.0 * (Y - y0) ** 2


def test_ease_off_map_puts_the_lowest_colour_at_the_fields_minimum(tmp_path):
    """Two fields, mirror images of each other (same values, same colour bar): the pixels
    of the colour map's lowest colour that one image has and the other lacks sit where
    each field has its minimum (right and low vs left and high)."""
    size = (WIDTH, 624)
    low = colormaps["viridis"](0.0)[:3]
    masks = []
    for x0, y0 in ((5.0, 22.5), (-5.0, 27.5)):
        x, y, z = _field(x0, y0)
        rgb = _rgb(plots.ease_off_map(x, y, z, tmp_path / f"e{x0}.png"), size)
        assert _distinct(rgb) > 200
        masks.append(_near(rgb, low, 25))
    (r1, c1), (r2, c2) = [np.argwhere(a & ~b).mean(axis=0) for a, b in
                          ((masks[0], masks[1]), (masks[1], masks[0]))]
    assert c1 - c2 > 0.3 * size[0]  # x0 = +5 mm lies right of x0 = -5 mm
    assert r1 - r2 > 0.2 * size[1]  # radius 22.5 mm lies below 27.5 mm


def test_ease_off_contours_leave_the_flat_bottom_alone(tmp_path, monkeypatch):
    """A field flat at its least separation (a conjugate patch, its round-off ±0.01 µm)
    rising to 100 µm: no contour level within 2 % of the range above the least, so the
    flat bottom's noise draws no islands; the levels above it are drawn and labelled."""
    x, y = np.linspace(-10.0, 10.0, 41), np.linspace(20.0, 30.0, 31)
    X, _ = np.meshgrid(x, y)
    noise = 0.01 * np.random.default_rng(1).standard_normal(X.shape)
    z = np.maximum(np.abs(X) - 4.0, 0.0) ** 2 + noise
    levels = []
    saved = style.save

    def keep(fig, path):
        levels.extend(float(v) for c in fig.axes[0].collections if hasattr(c, "levels")
                      for v in c.levels)
        return saved(fig, path)

    monkeypatch.setattr(style, "save", keep)
    plots.ease_off_map(x, y, z, tmp_path / "flat.png")
    lo, hi = z.min(), z.max()
    assert levels and min(levels) > lo + 0.02 * (hi - lo)


def test_ease_off_map_blank_where_no_flank_and_the_approach_contour(tmp_path):
    size = (WIDTH, 624)
    x, y, z = _field(0.0, 25.0)
    plain = _rgb(plots.ease_off_map(x, y, z, tmp_path / "plain.png"), size)
    assert _reddish(plain).sum() == 0
    contoured = _rgb(plots.ease_off_map(x, y, z, tmp_path / "approach.png", approach_um=6.3),
                     size)
    assert _reddish(contoured).sum() > 200
    holed = z.copy()
    holed[y > 28.0, :] = np.nan  # beyond the tip: no flank
    blank = _rgb(plots.ease_off_map(x, y, holed, tmp_path / "holed.png"), size)
    white = [(rgb > 250).all(axis=-1).sum() for rgb in (plain, blank)]
    assert white[1] - white[0] > 45000  # a fifth of the axes, about 90000 px
    with pytest.raises(ValueError, match="shape"):
        plots.ease_off_map(x, y, z.T, tmp_path / "bad.png")


# --------------------------------------------------------------------------- crown design


def _axes_rows(rgb: np.ndarray) -> tuple[int, int]:
    """First and last row of the axes frame (rows that are mostly dark: the spines)."""
    dark = (rgb < 90).all(axis=-1).sum(axis=1)
    rows = np.nonzero(dark > 0.5 * rgb.shape[1])[0]
    return int(rows.min()), int(rows.max())


def _row_of(mask: np.ndarray, columns) -> float:
    hits = np.concatenate([np.nonzero(mask[:, c])[0] for c in columns])
    assert len(hits), "curve not found near the design"
    return float(np.median(hits))


def _design_between_curves(path, result) -> list[tuple[float, float, float]]:
    """For each design marker: (edge-rule row, marker row, stress-rule row), read off the
    image in the columns beside the marker (rows grow downward: larger R = smaller row)."""
    rgb = _rgb(path, (WIDTH, 672))
    top, bottom = _axes_rows(rgb)
    inside = np.zeros(rgb.shape[:2], bool)
    inside[top + 2:bottom - 1, :] = True
    labels, count = ndimage.label(_near(rgb, style.DESIGN, 30) & inside)
    blobs = sorted(ndimage.center_of_mass(np.ones_like(labels), labels, range(1, count + 1)),
                   key=lambda rc: rc[1])
    blobs = [b for b in blobs if (labels == labels[int(b[0]), int(b[1])]).sum() > 30]
    ends = ["A"] if result["inputs"]["crown"] == "full" else ["B", "A"]  # slope_B < slope_A
    assert len(blobs) == len(ends)
    found = []
    for (row, col), end in zip(blobs, ends):
        col = round(col)
        beside = [*range(col - 24, col - 14), *range(col + 15, col + 25)]
        colour = style.SERIES[0] if end == "A" else style.SERIES[2]
        edge = _row_of(_near(rgb, colour, 25) & inside, beside)
        stress = _row_of(_near(rgb, style.SERIES[1], 25) & inside, range(col - 60, col + 60))
        found.append((edge, row, stress))
    return found


def test_crown_chart_marks_a_passing_design_between_the_edge_and_stress_rules(tmp_path):
    result = _result("crown_spur_metric_bias", tmp_path, allowable_stress="2000 MPa")
    assert all(c["ok"] for c in result["checks"])
    path = design_charts.crown_design_chart(result, tmp_path / "crown.png")
    rgb = _rgb(path, (WIDTH, 672))
    assert _distinct(rgb) > 300
    for edge, marker, stress in _design_between_curves(path, result):
        assert abs(marker - edge) < 5  # designed: on the edge rule at its end's slope
        assert stress - marker > 10  # and well above the stress rule (lower radius bound)

    curves = design_charts.crown_design_curves(result)
    R = result["crown"]["radius_mm"]
    for end, slope in (("A", curves["slope_A"]), ("B", curves["slope_B"])):
        assert np.interp(slope, curves["theta"], curves["edge_radius_mm"][end]) == \
            pytest.approx(R, rel=2e-3)
    assert curves["reference"] == "allowable" and curves["stress_radius_mm"] < R


def test_crown_chart_without_an_allowable_uses_the_designs_stress(tmp_path):
    """Example 1 has no allowable stress: the reference line runs through the design."""
    result = _result("crown_example1_planet_bias", tmp_path)
    path = design_charts.crown_design_chart(result, tmp_path / "crown.png")
    for edge, marker, stress in _design_between_curves(path, result):
        assert abs(marker - edge) < 5 and abs(marker - stress) < 5
    curves = design_charts.crown_design_curves(result)
    assert curves["reference"] == "design"
    assert curves["reference_stress_MPa"] == pytest.approx(result["contact"]["stress_MPa"],
                                                           rel=1e-9)


# --------------------------------------------------------------------------- worm sets


def test_worm_efficiency_over_temperature(tmp_path):
    result = _result("worm_saba_flap_actuator", tmp_path)
    rgb = _rgb(design_charts.worm_efficiency_vs_temperature(result, tmp_path / "t.png"), (WIDTH, 792))
    assert _distinct(rgb) > 300
    for colour in style.SERIES[:2]:  # eta_total and eta_z: lines and published points
        assert _near(rgb, colour, 20).sum() > 500
    with pytest.raises(ValueError, match="temperature"):
        design_charts.worm_efficiency_vs_temperature({"efficiency": [{"temperature_C": None}]},
                                             tmp_path / "none.png")


def test_worm_efficiency_over_torque_follows_the_results_rows(tmp_path):
    result = _result("worm_kim_steering_ars", tmp_path)
    curves = design_charts.worm_torque_curves(result)
    rows = result["misalignment"]
    torque = [r["output_torque_Nm"] for r in rows]
    for key in ("misalignment_mm", "spring_force_N", "normal_load_N"):
        assert np.interp(torque, curves["output_torque_Nm"], curves[key]) == pytest.approx(
            [r[key] for r in rows], abs=2e-3 * np.ptp(curves[key]))
    zero = np.interp(0.0, curves["misalignment_mm"], curves["output_torque_Nm"])
    assert zero == pytest.approx(19.67, abs=0.01)  # seed 001: aligned at 19.67 N·m
    assert curves["eta_aligned"] == pytest.approx(result["efficiency"][0]["eta_kim"], rel=1e-12)
    rgb = _rgb(design_charts.worm_efficiency_vs_torque(result, tmp_path / "q.png"), (WIDTH, 888))
    assert _distinct(rgb) > 300


# --------------------------------------------------------------------------- dispatch, files


def test_figures_for_writes_what_applies_and_nothing_else(tmp_path):
    cases = {"hertz_sphere_on_flat": [], "spline_crown_torque_tube": [],
             "crown_example2_offset_gear": ["crown_design.png"],
             "worm_saba_flap_actuator": ["worm_efficiency_temperature.png"],
             "worm_kim_steering_ars": ["worm_efficiency_torque.png"]}
    for name, expected in cases.items():
        out = tmp_path / name
        written = plots.figures_for(_result(name, tmp_path), out)
        assert [p.name for p in written] == expected
        assert sorted(p.name for p in out.iterdir()) == expected if expected else not out.exists()
    x, y, z = _field(0.0, 25.0)
    cycle = dict(_cycle(edge=True), ease_off={"face_mm": x.tolist(), "radius_mm": y.tolist(),
                                              "separation_um": z.tolist(), "approach_um": 6.3})
    written = plots.figures_for(cycle, tmp_path / "cycle")
    assert [p.name for p in written] == ["mesh_cycle.png", "ease_off.png"]
    assert sorted(p.name for p in (tmp_path / "cycle").iterdir()) == ["ease_off.png",
                                                                       "mesh_cycle.png"]


def test_a_failed_write_leaves_no_file(tmp_path, monkeypatch):
    from matplotlib.figure import Figure

    def broken(self, *args, **kwargs):
        raise RuntimeError("disk full")

    monkeypatch.setattr(Figure, "savefig", broken)
    x, y, z = _field(0.0, 25.0)
    with pytest.raises(RuntimeError, match="disk full"):
        plots.ease_off_map(x, y, z, tmp_path / "map.png")
    assert list(tmp_path.iterdir()) == []


def test_plots_never_load_pyplot(fresh_python):
    """The object API only: no pyplot state, no display backend."""
    code = ("import sys, numpy as np; from toothcontact.views import plots; "
            "import tempfile, pathlib;"
            "d = pathlib.Path(tempfile.mkdtemp());"
            "plots.ease_off_map([0, 1], [0, 1], np.eye(2), d / 'm.png');"
            "print('matplotlib.pyplot' in sys.modules)")
    assert fresh_python(code) == "False"


def test_the_k_chart_and_the_path_of_contact_are_drawn_from_the_result(tmp_path):
    """k_chart.png from a result's k_chart section (both members, profile and lead) and
    path_of_contact.png from its positions' flank pressures and the rating's σ_H: written
    at the figures' width, and by figures_for for a spur pair that has them."""
    trace = {"profile_diameter_mm": [56.0, 60.0, 66.0], "profile_um": [0.0, 0.0, 30.0],
             "lead_face_mm": [-15.0, 0.0, 15.0], "lead_um": [28.1, 0.0, 28.1],
             "lead_diameter_mm": 59.4}
    rows = [{"roll_deg": r, "pair": p, "contact_radius_pinion_mm": 29.0 + r + 3 * p,
             "flank_p_max_MPa": 1200.0 + 10 * r, "transmission_error_urad": 0.1 * r}
            for r in (-2.0, 0.0, 2.0) for p in (0, 1)]
    result = {"kind": "spur", "case": "c", "title": "t", "k_chart": {"pinion": trace,
                                                                     "gear": trace},
              "positions": rows,
              "rating": {"figures": [{"key": "sigma_H_MPa", "value": 1300.0},
                                     {"key": "sigma_H0_MPa", "value": 1100.0}]}}
    for draw, name in ((plots.k_chart, "k.png"), (plots.path_of_contact, "p.png")):
        path = draw(result, tmp_path / name)
        assert Image.open(path).size[0] == WIDTH
    names = {p.name for p in plots.figures_for(result, tmp_path / "all")}
    assert {"k_chart.png", "path_of_contact.png"} <= names
