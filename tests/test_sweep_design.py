"""Load spectra, Sobol indices and modification sizing on the sweep engine (sweep.spec,
sweep.sampling, sweep.statistics, sweep.optimise) and a sweep's figures and report, without
running analyses: each against a closed form (time-weighted percentiles as repeated draws,
the Sobol indices of a linear model, a constrained optimum of a smooth model)."""

from __future__ import annotations

import json
import math
import re
from pathlib import Path

import numpy as np
import pytest
from mutations import CASES

from toothcontact.case import CaseError, read_table
from toothcontact.runner import load_sweep
from toothcontact.sweep import optimise as optimiser
from toothcontact.sweep.sampling import plan, saltelli_design
from toothcontact.sweep.spec import Optimise, SweepSpec
from toothcontact.sweep.statistics import summarise, weighted_percentile

BASE = read_table(CASES / "spur_crowned_20_60.toml")
SLOPE = {"field": "misalignment.slope", "distribution": "uniform", "low": "0",
         "high": "0.001"}
CENTRE = {"field": "pinion.crown.center", "distribution": "uniform", "low": "-2 mm",
          "high": "2 mm"}


def sweep(**fields):
    return SweepSpec.model_validate({"kind": "sweep", "base": "spur_crowned_20_60", **fields})


def test_a_load_spectrum_is_the_first_grid_axis_and_its_samples_share_the_time():
    """Three levels × 4 draws: the levels slowest, each sample's time share its level's
    share over the draws, the shares summing to 1."""
    spec = sweep(samples=4, tolerance=[SLOPE],
                 spectrum={"field": "load.tangential_load",
                           "levels": ["2000 N", "4000 N", "8000 N"], "shares": [0.5, 0.3, 0.2]})
    samples = plan(spec, BASE)
    assert [s.inputs["load.tangential_load"] for s in samples[::4]] == ["2000 N", "4000 N",
                                                                         "8000 N"]
    assert [s.time_share for s in samples[::4]] == [0.125, 0.075, 0.05]
    assert math.fsum(s.time_share for s in samples) == pytest.approx(1.0, abs=1e-12)


@pytest.mark.parametrize("fields, says", [
    ({"spectrum": {"field": "load.torque", "levels": ["1 N*m", "2 N*m"], "shares": [1.0]}},
     "1 shares for 2 levels"),
    ({"spectrum": {"field": "load.torque", "levels": ["1 N*m", "2 N*m"],
                   "shares": [0.5, 0.6]}}, "sum to 1"),
    ({"sampling": "saltelli", "tolerance": [SLOPE]}, "two or more"),
    ({"tolerance": [SLOPE], "optimise": {"objective": "P97 bem_max_p_max_MPa",
                                         "variable": [{"field": "pinion.crown.radius",
                                                       "low": "2 m", "high": "8 m"}]}},
     "not a statistic"),
    ({"tolerance": [SLOPE], "optimise": {
        "objective": "P95 bem_max_p_max_MPa", "variable": [
            {"field": "misalignment.slope", "low": "0", "high": "0.001"}]}}, "twice"),
])
def test_a_bad_spectrum_sampling_or_optimisation_is_refused_naming_it(tmp_path, fields, says):
    import tomli_w

    path = tmp_path / "sweep.toml"
    path.write_text(tomli_w.dumps({"kind": "sweep", "base": "spur_crowned_20_60", **fields}))
    with pytest.raises(CaseError, match=says):
        load_sweep(path)


def test_saltellis_design_has_n_times_inputs_plus_two_draws_at_each_grid_point():
    spec = sweep(samples=8, sampling="saltelli", tolerance=[SLOPE, CENTRE],
                 vary=[{"field": "load.tangential_load", "values": ["4000 N", "8000 N"]}])
    samples = plan(spec, BASE)
    assert len(samples) == 2 * 8 * (2 + 2)
    first = [s.inputs["misalignment.slope"] for s in samples[:32]]
    assert first == [s.inputs["misalignment.slope"] for s in samples[32:]]


def rows_of(inputs: np.ndarray, y: np.ndarray, fields: list[str], **extra) -> list[dict]:
    return [{"sample": k, "status": "ok", **{f"input:{f}": float(x) for f, x in
                                              zip(fields, point)}, "figure": float(v), **extra}
            for k, (point, v) in enumerate(zip(inputs, y))]


def test_sobol_indices_of_a_linear_model_match_the_closed_form():
    """y = 3 x1 + x2 on the unit square (Saltelli's design, 1024 base points): S1 = ST =
    9/10 and 1/10 (independent inputs, no interaction), within 0.03."""
    fields = ["a", "b"]
    x = saltelli_design(1024, 2, seed=1)
    stats = summarise(rows_of(x, 3 * x[:, 0] + x[:, 1], fields), fields, saltelli=True)
    for field, share in zip(fields, (0.9, 0.1)):
        index = stats["sobol"]["indices"][field]["figure"]
        assert index["S1"] == pytest.approx(share, abs=0.03)
        assert index["ST"] == pytest.approx(share, abs=0.03)


def test_time_weighted_statistics_equal_repeated_draws():
    """Weights 3:1 on two load levels give the percentiles of the values repeated 3:1, and
    the time share edge-loaded is the weighted share."""
    values = np.arange(20.0)
    weights = np.where(values < 10, 0.075, 0.025)           # 10 draws per level: sum 1
    repeated = np.concatenate([np.repeat(values[:10], 3), values[10:]])
    for q in (5, 50, 95, 99):
        assert weighted_percentile(values, weights, q) == np.percentile(
            repeated, q, method="inverted_cdf")
    rows = [{"sample": k, "status": "ok", "figure": v, "time_share": w,
             "end_loaded_contacts": float(v >= 15)} for k, (v, w) in
            enumerate(zip(values, weights))]
    stats = summarise(rows, [])
    assert stats["time_weighted"]["end_loading"]["time_share"] == pytest.approx(5 * 0.025)
    assert stats["end_loading"]["probability"] == pytest.approx(5 / 20)


def test_the_optimiser_finds_a_constrained_optimum(tmp_path):
    """A smooth model of a crown radius r (mm): objective (r - 6000)², constraint
    r/8000 <= 0.5: the optimum r = 4000 within 1 %, feasible, every design in the history
    and the design's text in the unit of `low`."""
    spec = Optimise.model_validate({
        "objective": "P95 figure", "evaluations": 40,
        "variable": [{"field": "pinion.crown.radius", "low": "2 m", "high": "8000 mm"}],
        "constraint": [{"statistic": "P50 ratio", "max": 0.5}]})

    def evaluate(design, folder, point):
        r = float(design["pinion.crown.radius"].split()[0]) * 1000.0      # given in m
        assert point[0] == pytest.approx((r - 2000.0) / 6000.0)
        stats = {"ok": 1, "failed": 0, "percentiles": {"figure": {"P95": (r - 6000) ** 2},
                                                       "ratio": {"P50": r / 8000}}}
        return stats, [{"status": "ok"}]

    out = optimiser.optimise(spec, evaluate, tmp_path)
    best = out["best"]
    assert best["feasible"] and best["design"]["pinion.crown.radius"].endswith(" m")
    assert float(best["design"]["pinion.crown.radius"].split()[0]) == pytest.approx(4.0,
                                                                                     rel=0.01)
    assert out["evaluations"] == len(out["history"]) <= 40


def test_an_objective_naming_a_figure_the_samples_lack_is_refused():
    stats = {"ok": 1, "failed": 0, "percentiles": {"bem_max_p_max_MPa": {"P95": 1.0}}}
    with pytest.raises(CaseError, match="'bem_max_p_mx_MPa' is not a figure.*bem_max_p_max"):
        optimiser.statistic("P95 bem_max_p_mx_MPa", stats, [{"status": "ok"}], "optimise")


def grid_rows():
    """A synthetic crown × slope × load × relief grid: the pressure rises with slope and
    falls with crown, end-loaded where slope > crown/4000 mrad; TE falls with relief."""
    rows, k = [], 0
    for crown in (2000.0, 4000.0, 6000.0):
        for slope in (0.0, 0.0005, 0.001):
            for load in (4000.0, 8000.0):
                for relief in (0.0, 0.02):
                    rows.append({
                        "sample": k, "status": "ok", "input:pinion.crown.radius": crown,
                        "input:misalignment.slope": slope, "input:load.tangential_load": load,
                        "input:pinion.tip_relief.amount": relief,
                        "bem_max_p_max_MPa": 1000 + 1e6 * slope - 0.05 * crown,
                        "loaded_transmission_error_peak_to_peak_urad": 50 + load / 100
                        - 1000 * relief, "end_loaded_contacts": float(slope * 4e6 > crown)})
                    k += 1
    return rows


def test_the_figures_and_report_of_a_grid_sweep(tmp_path):
    """From the table and statistics alone: the robustness map, the Harris map, the
    response and the optimisation; the report names the key results and embeds each."""
    from toothcontact.views import report, sweep_plots

    rows = grid_rows()
    fields = ["pinion.crown.radius", "misalignment.slope", "load.tangential_load",
              "pinion.tip_relief.amount"]
    stats = {"sweep": "grid.toml", "title": "grid", "base": "base.toml", "seed": 0,
             "sampling": "latin_hypercube", "inputs": [], "grid": fields,
             **summarise(rows, [], fields)}
    stats["optimise"] = {"objective": "P95 bem_max_p_max_MPa", "constraints": [
        {"statistic": "end_loading", "max": 0.05}], "variables": [
        {"field": "pinion.crown.radius", "low": "2 m", "high": "8 m"}],
        "method": "COBYQA", "message": "done", "evaluations": 2, "feasible_found": True,
        "history": [{"evaluation": i, "design": {"pinion.crown.radius": f"{r} m"},
                     "objective": o, "constraints": [c], "feasible": c <= 0.05}
                    for i, (r, o, c) in enumerate([(5.0, 900.0, 0.0), (6.5, 850.0, 0.2)])]}
    stats["optimise"]["best"] = stats["optimise"]["history"][0]
    figures = sweep_plots.sweep_figures(rows, stats, tmp_path)
    names = [p.name for p in figures]
    assert names == ["histograms.png", "response.png", "map.png", "harris.png",
                     "optimisation.png"]
    assert all(p.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n" for p in figures)
    page = report.write_sweep_report(tmp_path, stats, figures).read_text()
    assert "probability of loading at a face end" in page and "optimum" in page
    assert page.count("data:image/png;base64,") == len(figures)
    json.dumps(stats, allow_nan=False)


def test_the_bundled_sweeps_are_valid_sweeps():
    """Every sweep in cases/sweeps plans into valid cases; the crown study has a spectrum,
    tolerances and an optimisation."""
    found = sorted((CASES / "sweeps").glob("*.toml"))
    assert len(found) >= 3
    for path in found:
        spec, raw, where = load_sweep(path)
        assert plan(spec, raw, where.parent)
    spec, _, _ = load_sweep(CASES / "sweeps" / "spur_crown_tolerance.toml")
    assert spec.spectrum and spec.tolerance and spec.optimise


def test_an_optimisation_bound_that_is_no_case_is_refused_before_anything_runs(tmp_path):
    """A design variable's low bound that no case takes (a negative crown radius): refused
    at once, naming the field and the value, with no output written."""
    from toothcontact import runner

    path = tmp_path / "sweep.toml"
    path.write_text('kind = "sweep"\nbase = "spur_crowned_20_60"\n[[tolerance]]\n'
                    'field = "misalignment.slope"\ndistribution = "uniform"\nlow = "0"\n'
                    'high = "0.001"\n[optimise]\nobjective = "P95 max_p_max_MPa"\n'
                    '[[optimise.variable]]\nfield = "pinion.crown.radius"\nlow = "-5 mm"\n'
                    'high = "8000 mm"\n')
    with pytest.raises(CaseError, match=r"pinion\.crown\.radius.*-5\.0 mm"):
        runner.run_sweep(path, tmp_path / "out")
    assert not (tmp_path / "out").exists()


@pytest.mark.parametrize("objective, base, named", [
    ("P95 a_mm", "hertz_sphere_on_flat", "'a_mm' is not a figure the base design reports"),
    ("edge_loading", "hertz_sphere_on_flat", "'edge_loading': the base design reports no edge"),
])
def test_an_objective_the_samples_cannot_answer_is_refused_before_anything_runs(
        tmp_path, objective, base, named):
    """An objective naming a figure the base design's analysis does not report (a Hertz
    contact has no a_mm in its summary, and no edge counts): refused after the one analysis
    of the base design, naming optimise.objective and what the design does report, before
    any sample runs or any output is written (it was refused only after every sample)."""
    from toothcontact import runner

    path = tmp_path / "sweep.toml"
    path.write_text(f'kind = "sweep"\nbase = "{base}"\n[[tolerance]]\n'
                    'field = "load"\ndistribution = "uniform"\nlow = "90 N"\nhigh = "110 N"\n'
                    f'[optimise]\nobjective = "{objective}"\n[[optimise.variable]]\n'
                    'field = "body1.E"\nlow = "0.8 GPa"\nhigh = "1.2 GPa"\n')
    with pytest.raises(CaseError, match=r"optimise\.objective: " + re.escape(named)):
        runner.run_sweep(path, tmp_path / "out")
    assert not (tmp_path / "out").exists()


def test_a_rank_correlations_interval_covers_the_true_one_95_times_in_100():
    """Fisher's z with Bonett & Wright's variance: over 1500 samples of 30 draws from a
    bivariate normal of correlation 0.6 (Spearman's rho (6/π)·asin(r/2) = 0.582), the 95 %
    interval covers the population's rho in 93-97 % of them; under 10 draws there is none."""
    from scipy.stats import spearmanr

    from toothcontact.sweep.statistics import spearman_interval

    rng = np.random.default_rng(7)
    r, n = 0.6, 30
    truth = 6 / math.pi * math.asin(r / 2)
    covered = 0
    for _ in range(1500):
        x = rng.standard_normal(n)
        y = r * x + math.sqrt(1 - r * r) * rng.standard_normal(n)
        low, high = spearman_interval(float(spearmanr(x, y).statistic), n)
        covered += low <= truth <= high
    assert 0.93 <= covered / 1500 <= 0.97
    assert spearman_interval(1.0, 4) is None and spearman_interval(0.3, 9) is None
    assert spearman_interval(0.5, 30) == pytest.approx([0.148, 0.740], abs=1e-3)


def spectrum_rows():
    """Two load levels, 70 % and 30 % of the time, 20 draws each: the pressure's humps at
    1000 and 1500 MPa, rising with the slope drawn."""
    rng = np.random.default_rng(3)
    rows = []
    for level, (load, share, base) in enumerate([(4000.0, 0.7, 1000.0), (8000.0, 0.3, 1500.0)]):
        for i in range(20):
            slope = float(rng.uniform(0.0, 0.001))
            rows.append({"sample": 20 * level + i, "status": "ok", "time_share": share / 20,
                         "input:load.tangential_load": load, "input:misalignment.slope": slope,
                         "bem_max_p_max_MPa": base + 1e5 * slope})
    return rows


def test_sweep_figures_show_each_load_level_and_how_sure_a_rank_is(tmp_path, monkeypatch):
    """Under a spectrum the histogram has one histogram and median per load level, named
    by its level and time share, beside the percentiles over the operating time; the
    tornado's bar carries its 95 % interval and the draws it rests on; an optimisation that
    met no constraint stars no design as the best and says so; axes read as words."""
    from toothcontact.views import style, sweep_plots

    rows = spectrum_rows()
    stats = {"title": "spectrum", "inputs": ["misalignment.slope"],
             "grid": ["load.tangential_load"],
             "spectrum": {"field": "load.tangential_load", "levels": ["4000 N", "8000 N"],
                          "shares": [0.7, 0.3]},
             **summarise(rows, ["misalignment.slope"], ["load.tangential_load"])}
    interval = stats["sensitivity_interval"]["misalignment.slope"]["bem_max_p_max_MPa"]
    assert stats["sensitivity_draws"] == 20 and interval[0] > 0.9
    stats["optimise"] = {"objective": "P95 bem_max_p_max_MPa", "constraints": [
        {"statistic": "end_loading", "max": 0.05}], "variables": [
        {"field": "pinion.crown.radius", "low": "2 m", "high": "8 m"}], "evaluations": 2,
        "history": [{"evaluation": i, "design": {"pinion.crown.radius": f"{r} m"},
                     "objective": o, "constraints": [0.2], "feasible": False}
                    for i, (r, o) in enumerate([(5.0, 900.0), (6.5, 850.0)])]}
    stats["optimise"]["best"] = stats["optimise"]["history"][1]
    seen = {}
    saved = style.save

    def keep(fig, path):
        seen[Path(path).name] = (
            [t.get_text() for legend in fig.legends + [a.get_legend() for a in fig.axes
                                                      if a.get_legend()] for t in legend.get_texts()],
            [a.get_xlabel() for a in fig.axes] + [a.get_ylabel() for a in fig.axes],
            [len(c.get_children()) for a in fig.axes for c in a.containers])
        return saved(fig, path)

    monkeypatch.setattr(style, "save", keep)
    sweep_plots.sweep_figures(rows, stats, tmp_path)
    texts, labels, _ = seen["histograms.png"]
    assert "load.tangential_load = 4000 N (70% of the time)" in texts
    assert "load.tangential_load = 8000 N (30% of the time)" in texts
    assert "P50 over the operating time" in texts
    texts, labels, _ = seen["tornado.png"]
    assert any("20 draws per point, 95 % intervals" in " ".join(t.split()) for t in labels)
    texts, labels, _ = seen["optimisation.png"]
    assert "best tried: no design met the constraints" in texts
    assert "best feasible design" not in texts
    assert "P95 of the largest loaded pressure (MPa)" in labels
