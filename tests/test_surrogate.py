"""Tolerance studies on a surrogate (sweep.surrogate, `method = "surrogate"`): the
interpolant and its leave-one-out error against functions whose values are known, the
samples added where that error is largest, the statistics drawn on it against the same
draws of the function itself, the sweep file's table, and a surrogate sweep run end to end.
The loaded reference (a 400-sample full Monte Carlo of the bundled spur_crown_tolerance) is
benchmarks/surrogate_study.py's."""

from __future__ import annotations

import json
import re

import numpy as np
import pyarrow.parquet as pq
import pytest

from toothcontact.case import CaseError
from toothcontact.sweep import surrogate
from toothcontact.sweep.spec import Surrogate, SweepSpec


def smooth(u: np.ndarray) -> np.ndarray:
    """A largest pressure (MPa) over two toleranced inputs: a slope's square and a crown
    position's wave."""
    return 1000.0 + 300.0 * u[:, 0] ** 2 + 100.0 * np.sin(3.0 * u[:, 1])


def kinked(u: np.ndarray) -> np.ndarray:
    """A figure that switches between two contacts (a flank and a corner): the larger of
    two planes."""
    return np.maximum(1000.0 + 200.0 * u[:, 0], 1150.0 + 150.0 * u[:, 1] - 100.0 * u[:, 0])


def test_the_interpolant_and_its_leave_one_out_error_on_a_smooth_figure():
    """30 Latin-hypercube points of a smooth figure: the interpolant's RMS error on 2000
    random points of the cube (its corners beyond the design's reach included) is within
    2 % of the range, and its leave-one-out error (what the study reports) is no smaller
    than half that true error and no larger than three times it (measured: 1.24 % true,
    1.27 % leave-one-out; at 20 and 50 points the leave-one-out error was 1.0-2.6 times
    the true one on this and the kinked figure: it errs on the safe side)."""
    u = surrogate.latin_hypercube(30, 2, seed=3)
    f = surrogate.fit(u, smooth(u))
    test = np.random.default_rng(0).random((2000, 2))
    true = float(np.sqrt(np.mean((f.model(test) - smooth(test)) ** 2))) / np.ptp(smooth(u))
    assert true < 0.02
    assert true / 2 <= f.error <= 3 * true
    assert f.rmse == pytest.approx(f.error * f.spread)
    assert np.allclose(f.model(u), smooth(u))          # it interpolates its samples


def test_each_sample_counts_by_its_share_of_the_cube():
    """20 Latin-hypercube points and 20 more crowded into one corner (as the rounds add
    them where a figure bends): the shares sum to 1 and the crowded points' are under a
    fifth of the others' on average, so the error over the cube does not count that
    corner's residuals twenty times."""
    rng = np.random.default_rng(5)
    u = np.vstack([surrogate.latin_hypercube(20, 2, seed=1), 0.25 * rng.random((20, 2))])
    f = surrogate.fit(u, kinked(u))
    assert f.weights.sum() == pytest.approx(1.0)
    assert f.weights[20:].mean() < 0.2 * f.weights[:20].mean()
    assert f.rmse == pytest.approx(float(np.sqrt(np.sum(f.weights * f.residuals ** 2))))


def test_a_figure_judged_by_a_threshold_is_settled_by_the_side_its_draws_fall():
    """A figure whose error is 10 % of its range but whose values stay far below its
    threshold is settled (every draw's side is sure); the same against a threshold inside
    its range is not."""
    u = surrogate.latin_hypercube(12, 2, seed=3)
    f = surrogate.fit(u, 0.3 * kinked(u) / 1300.0)        # 0.23 to 0.31
    assert f.error > 0.03
    assert surrogate.settled(f, 1.0, 0.03)
    assert not surrogate.settled(f, 0.27, 0.03)
    assert not surrogate.settled(f, None, 0.03)


def test_the_study_adds_samples_where_the_error_is_largest_until_the_tolerance():
    """A kinked figure at two grid points (the second 1.5 times the first): the first 12
    points leave it above 3 %; rounds of 8 points, each where the leave-one-out error is
    largest, bring it within 3 % before the budget of 80; the records are numbered on
    through the rounds, grid point by grid point, as the sweep analyses them."""
    calls = []

    def analyse_points(u, first):
        calls.append((len(u), first))
        out = []
        for g, scale in enumerate((1.0, 1.5)):
            values = scale * kinked(u)
            out += [{"sample": first + g * len(u) + i, "status": "ok", "input:load": scale,
                     "p": float(v)} for i, v in enumerate(values)]
        return out

    settings = Surrogate(initial=12, batch=8, max_samples=80, tolerance=0.03)
    found = surrogate.study(analyse_points, 2, ["load"], ["p"], settings, seed=1)
    errors = [fits["p"].error for fits in found.fits.values()]
    assert len(found.fits) == 2 and max(errors) <= 0.03
    assert found.rounds > 1 and len(found.u) == 12 + 8 * (found.rounds - 1) <= 80
    assert calls[0] == (12, 0) and calls[1] == (8, 24)
    assert sorted(r["sample"] for r in found.records) == list(range(2 * len(found.u)))
    first_round = surrogate._fits(found.u[:12], found.records[:24], ["load"], ["p"])
    assert max(f["p"].error for f in first_round.values()) > 0.03


def test_the_new_samples_go_where_the_residual_is():
    """With every design point's weight 0 but one, the new points lie nearest that one
    (its share of the cube), spread apart, not on top of each other."""
    u = surrogate.latin_hypercube(16, 2, seed=2)
    weights = np.zeros(16)
    weights[5] = 1.0
    new = surrogate.next_points(u, weights, 3, seed=4)
    nearest = np.linalg.norm(new[:, None, :] - u[None, :, :], axis=2).argmin(axis=1)
    assert list(nearest) == [5, 5, 5]
    apart = np.linalg.norm(new[:, None, :] - new[None, :, :], axis=2)
    assert apart[np.triu_indices(3, 1)].min() > 0.01


def test_the_statistics_on_the_surrogate_are_the_functions_within_its_stated_error():
    """P50 and P95 of the kinked figure over 4000 draws, on the surrogate against the
    function itself at the same draws: within the surrogate's stated leave-one-out error
    (or 0.5 % of the range, if larger); the probability that it exceeds a threshold (as the
    end-loaded share is had from max_end_load_ratio) within 2 points; the draws' records
    carry the inputs as CDF values and the time share of their level."""

    def analyse_points(u, first):
        return [{"sample": first + i, "status": "ok", "max_end_load_ratio": float(v / 1100.0),
                 "bem_max_p_max_MPa": float(v)} for i, v in enumerate(kinked(u))]

    settings = Surrogate(initial=20, batch=8, max_samples=60, tolerance=0.02)
    figures = ["bem_max_p_max_MPa", "max_end_load_ratio"]
    found = surrogate.study(analyse_points, 2, [], figures, settings, seed=7)
    draws = np.random.default_rng(11).random((4000, 2))
    records = surrogate.draws_on(found, draws, ["slope", "centre"], [], {(): 0.3}, 1.0)
    on = np.array([r["bem_max_p_max_MPa"] for r in records])
    exact = kinked(draws)
    stated = found.fits[()]["bem_max_p_max_MPa"].rmse
    for q in (50, 95):
        assert abs(np.percentile(on, q) - np.percentile(exact, q)) <= max(
            stated, 0.005 * np.ptp(exact))
    share = np.mean([r["end_loaded_contacts"] for r in records])
    assert share == pytest.approx(np.mean(exact / 1100.0 > 1.0), abs=0.02)
    assert records[3]["input:centre"] == draws[3, 1]
    assert records[0]["time_share"] == pytest.approx(0.3 / 4000)
    summary = surrogate.summary(found, settings, figures)
    assert summary["converged"] and summary["loaded_samples"] == len(found.u)
    assert set(summary["errors"]) == set(figures)


def test_a_figure_the_samples_do_not_report_is_named():
    def analyse_points(u, first):
        return [{"sample": first + i, "status": "ok", "bem_max_p_max_MPa": 1.0}
                for i in range(len(u))]

    with pytest.raises(CaseError, match="'sigma_H' is not a figure the samples report"):
        surrogate.study(analyse_points, 2, [], ["sigma_H"], Surrogate(initial=6), seed=0)


BASE = {"kind": "sweep", "base": "spur_crowned_20_60", "samples": 100,
        "tolerance": [{"field": "misalignment.slope", "distribution": "normal",
                       "mean": "0.0008", "std": "0.0003"}]}


@pytest.mark.parametrize("changes, message", [
    ({"method": "surrogate", "tolerance": [], "vary": [{"field": "load.torque",
                                                         "values": ["1 N*m"]}]},
     "'surrogate' fits the \\[\\[tolerance\\]\\] inputs"),
    ({"surrogate": {"initial": 10}}, "read only with method = 'surrogate'"),
    ({"method": "surrogate", "surrogate": {"initial": 30, "max_samples": 20}},
     "max_samples \\(20\\) must be at least initial \\(30\\)"),
    ({"method": "kriging"}, "method"),
])
def test_a_surrogate_sweep_file_is_checked(changes, message):
    with pytest.raises(ValueError, match=message):
        SweepSpec.model_validate({**BASE, **changes})


def test_an_optimisation_on_a_surrogate_names_what_it_cannot_draw():
    from toothcontact.sweep.spec import Optimise

    spec = Optimise.model_validate({
        "objective": "P95 bem_max_p_max_MPa",
        "variable": [{"field": "pinion.crown.radius", "low": "1 m", "high": "2 m"}],
        "constraint": [{"statistic": "edge_loading", "max": 0.1}]})
    with pytest.raises(CaseError, match="constraint\\[0\\].statistic: 'edge_loading' is not drawn"):
        surrogate.check_figures(list(surrogate.DEFAULT_FIGURES), spec)
    spec = spec.model_copy(update={"constraints": [], "objective": "P50 sigma_H_MPa"})
    with pytest.raises(CaseError, match="needs 'sigma_H_MPa' among the surrogate's figures"):
        surrogate.check_figures(list(surrogate.DEFAULT_FIGURES), spec)


def test_a_surrogate_sweep_runs_end_to_end(tmp_path):
    """A coarse spur pair (5 positions, a 48-cell grid) with its slope and crown position
    toleranced, over a two-level spectrum, its crown radius sized for P95 of the largest
    loaded pressure: 8 loaded samples a level, then 4 a round to 16 (a tolerance of 1 %
    that the budget stops first); samples.parquet holds the 32 loaded samples, sweep.json
    the statistics over the 500 draws on the surrogate at the optimum, its error per
    figure, the Sobol indices on it, the time-weighted figures, the optimisation's history
    on the surrogate and the optimum re-checked by 8 loaded samples a level; the report
    shows the error beside the percentiles."""
    from toothcontact import runner

    text = """kind = "sweep"
base = "spur_crowned_20_60"
samples = 500
seed = 3
method = "surrogate"
[surrogate]
initial = 8
batch = 4
max_samples = 16
tolerance = 0.01
[set]
"analysis.positions" = 5
"analysis.pressure_grid" = 48
"analysis.interference" = false
[spectrum]
field = "load.tangential_load"
levels = ["4000 N", "8000 N"]
shares = [0.7, 0.3]
[[tolerance]]
field = "misalignment.slope"
distribution = "normal"
mean = "0.0008"
std = "0.0003"
[[tolerance]]
field = "pinion.crown.center"
distribution = "uniform"
low = "-1.5 mm"
high = "1.5 mm"
[optimise]
objective = "P95 bem_max_p_max_MPa"
evaluations = 8
[[optimise.variable]]
field = "pinion.crown.radius"
low = "1500 mm"
high = "20000 mm"
"""
    path = tmp_path / "study.toml"
    path.write_text(text)
    stats, written = runner.run_sweep(path, tmp_path / "out", workers=2)
    table = pq.read_table(tmp_path / "out" / "samples.parquet").to_pylist()
    assert len(table) == 32 and all(r["status"] == "ok" for r in table)
    saved = json.loads((tmp_path / "out" / "sweep.json").read_text())
    fitted = saved["surrogate"]
    assert saved["method"] == "surrogate" and saved["surrogate_draws"] == 1000
    assert fitted["loaded_samples"] == 16 and fitted["rounds"] == 3 and fitted["grid_points"] == 2
    assert set(fitted["errors"]) == {"bem_max_p_max_MPa", "max_end_load_ratio"}
    assert saved["samples"] == 32 and saved["ok"] == 32
    p = saved["percentiles"]["bem_max_p_max_MPa"]
    assert p["P5"] <= p["P50"] <= p["P95"] <= p["P99"]
    loaded = [r["bem_max_p_max_MPa"] for r in table]
    assert min(loaded) - 3 * fitted["rmse"]["bem_max_p_max_MPa"] <= p["P50"] <= max(loaded)
    assert "end_loading" in saved["time_weighted"]
    assert set(saved["sobol"]["indices"]) == {"misalignment.slope", "pinion.crown.center"}
    html = (tmp_path / "out" / "report.html").read_text()
    assert "surrogate error (±)" in html and "the surrogate and its error" in html
    assert "1000 draws taken on a surrogate of the loaded samples" in html
    assert not re.search(r"\d\.\d{7,} mm", html)      # a design's radius as set, rounded
    assert stats["surrogate"]["converged"] is False
    opt = saved["optimise"]
    assert 1 <= opt["evaluations"] <= 8 and opt["best"]["design"]["pinion.crown.radius"]
    recheck = opt["recheck"]
    assert recheck["samples"] == 8 and recheck["ok"] == 16
    assert set(recheck["errors"]) == set(fitted["errors"])
    assert len(list((tmp_path / "out" / "optimum").glob("*/sample_*.parquet"))) == 16
    assert "optimum re-checked by the loaded contact" in html


def test_on_the_stored_monte_carlo_the_surrogate_finds_its_percentiles():
    """The bundled spur_crown_tolerance's 400-sample Monte Carlo at full load (8000 N), as
    benchmarks/surrogate_study.py stored it (each sample's toleranced inputs and loaded
    figures): the study played on it, its design the stored samples (20 first, then 8 a
    round, each the one farthest from the design weighted by its nearest point's residual,
    as next_points picks) until the largest loaded pressure is settled at 3 %. Over all
    400 samples the surrogate's P50 and P95 are the Monte Carlo's within twice its stated
    RMS error (measured: settled at 28 samples, 0.2 and 0.8 MPa off on a range of 184 MPa,
    stated 2.1 MPa). The stated error is the pointwise one at the samples and is
    optimistic for a point it did not see (6.2 MPa there, which holds the loaded figure's
    own scatter between neighbouring samples; 0.3-1.0 times over three starts and both
    loads), so it is held to a quarter of that: a percentile, an average over the draws, is
    far surer than any one point."""
    import pathlib

    from scipy import stats

    stored = json.loads((pathlib.Path(__file__).parent.parent / "benchmarks" /
                         "surrogate_reference.json").read_text())
    records = [r for r in stored["spur_crown_tolerance/400"]["records"]
               if r["input:load.tangential_load"] == 8000.0]
    u = np.array([[stats.norm.cdf(r["input:misalignment.slope"], 0.0008, 0.0003),
                   (r["input:pinion.crown.center"] + 1.5) / 3.0] for r in records])
    y = np.array([r["bem_max_p_max_MPa"] for r in records])
    chosen = list(range(20))
    while True:
        f = surrogate.fit(u[chosen], y[chosen])
        rest = np.setdiff1d(np.arange(len(y)), chosen)
        if surrogate.settled(f, None, 0.03) or len(chosen) >= 120:
            break
        distance = np.linalg.norm(u[rest][:, None] - u[chosen][None], axis=2)
        nearest = distance.argmin(axis=1)
        score = distance[np.arange(len(rest)), nearest] * np.abs(f.residuals)[nearest]
        chosen += list(rest[np.argsort(-score)[:8]])
    on = f(u)
    for q in (50, 95):
        assert abs(np.percentile(on, q) - np.percentile(y, q)) <= 2.0 * f.rmse
    true = float(np.sqrt(np.mean((f(u[rest]) - y[rest]) ** 2)))
    assert f.rmse >= 0.25 * true
