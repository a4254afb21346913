"""Running a sweep (sweep.run on a local Dask cluster, the `sweep` command): the table and
statistics it writes, the same table whatever the workers, a resumed sweep that recomputes
only what its checkpoints lack, a failed sample recorded beside the others, and a bad sweep
refused before anything runs."""

from __future__ import annotations

import json
import tomllib

import numpy as np
import pyarrow.parquet as pq
import pytest
from typer.testing import CliRunner

from toothcontact import analyses, runner
from toothcontact.case import CaseError, parse_case
from toothcontact.cli import app
from toothcontact.runner import bundled_cases_dir
from toothcontact.sweep.run import sample_record
from toothcontact.sweep.statistics import wilson



def write_sweep(folder, samples=4):
    text = (f'kind = "sweep"\nbase = "spur_crowned_20_60"\nsamples = {samples}\nseed = 5\n'
            '[[tolerance]]\nfield = "misalignment.slope"\ndistribution = "normal"\n'
            'mean = "0.0008"\nstd = "0.0004"\n'
            '[[vary]]\nfield = "analysis.pressure_grid"\nvalues = [0]\n'
            '[[vary]]\nfield = "analysis.interference"\nvalues = [false]\n')
    path = folder / "sweep.toml"
    path.write_text(text)
    return path


@pytest.fixture(scope="module")
def two_workers(tmp_path_factory):
    folder = tmp_path_factory.mktemp("sweep")
    path = write_sweep(folder)
    result = CliRunner().invoke(app, ["sweep", str(path), "--out", str(folder / "out"),
                                      "--workers", "2"])
    assert result.exit_code == 0, result.output
    return folder, path, result


def test_a_sweep_writes_its_table_and_statistics(two_workers):
    """samples.parquet: a row per sample in sample order, the toleranced input in core units
    and the summary's figures; sweep.json: strict JSON with percentiles (P5 <= P50 <= P95
    <= P99), the edge-loading probability inside its Wilson interval, and the sensitivity
    of the largest pressure to the slope (rank correlation, positive)."""
    folder, _, result = two_workers
    table = pq.read_table(folder / "out" / "samples.parquet").to_pylist()
    assert [r["sample"] for r in table] == [0, 1, 2, 3]
    assert all(r["status"] == "ok" for r in table)
    slopes = [r["input:misalignment.slope"] for r in table]
    assert len(set(slopes)) == 4 and all(isinstance(s, float) for s in slopes)
    stats = json.loads((folder / "out" / "sweep.json").read_text())
    p = stats["percentiles"]["max_p_max_MPa"]
    assert p["P5"] <= p["P50"] <= p["P95"] <= p["P99"]
    edge = stats["edge_loading"]
    low, high = edge["interval_95"]
    assert low <= edge["probability"] <= high
    assert stats["sensitivity"]["misalignment.slope"]["max_p_max_MPa"] > 0
    assert "4 samples, 4 answered, 0 failed" in result.output


def test_the_same_seed_gives_the_same_table_whatever_the_workers(two_workers, tmp_path):
    folder, path, _ = two_workers
    _, written = runner.run_sweep(path, tmp_path / "one", workers=1)
    one = pq.read_table(written[0]).to_pylist()
    two = pq.read_table(folder / "out" / "samples.parquet").to_pylist()
    assert one == two


def test_a_resumed_sweep_computes_only_what_its_checkpoints_lack(two_workers, tmp_path):
    """Two of four checkpoints removed (a sweep killed half way): --resume analyses those
    two only, and the table is the whole sweep's again."""
    import shutil

    folder, path, _ = two_workers
    out = tmp_path / "resumed"
    shutil.copytree(folder / "out", out)
    for k in (1, 3):
        (out / "parts" / f"sample_{k:07d}.parquet").unlink()
    done = []
    runner.run_sweep(path, out, workers=1, resume=True, on_done=done.append)
    assert sorted(r["sample"] for r in done) == [1, 3]
    assert (pq.read_table(out / "samples.parquet").to_pylist()
            == pq.read_table(folder / "out" / "samples.parquet").to_pylist())


def test_a_sample_that_fails_is_recorded_with_its_error(monkeypatch):
    """A sample whose analysis fails keeps its number and says why; nothing is raised."""
    def analyse(case):
        raise CaseError("misalignment / load: no contact could be found")

    monkeypatch.setattr(analyses, "analyse", analyse)
    case = parse_case(tomllib.loads((bundled_cases_dir() / "spur_crowned_20_60.toml")
                                    .read_text()))
    record, rows = sample_record(7, {"load.tangential_load": "8000 N"}, case, positions=True)
    assert record["sample"] == 7 and rows == []
    assert record["status"] == "CaseError: misalignment / load: no contact could be found"
    assert record["input:load.tangential_load"] == case.load.tangential_load == 8000.0


def test_a_worker_analyses_the_planned_case_without_parsing_it(two_workers, tmp_path,
                                                              fresh_python):
    """The sweep parses each sample where it plans them; a worker receives the parsed case
    and analyses it as it is: it never imports the units' library (pint and its registry,
    0.5-0.8 s of a worker's first sample)."""
    import pickle

    from toothcontact.runner import load_sweep
    from toothcontact.sweep.sampling import plan

    _, path, _ = two_workers
    spec, base, base_path = load_sweep(path)
    sample = plan(spec, base, base_path.parent)[1]
    (tmp_path / "sample.pickle").write_bytes(pickle.dumps(sample))
    code = f"""
import json, pickle, sys
from toothcontact.sweep.run import sample_record
sample = pickle.loads(open({str(tmp_path / "sample.pickle")!r}, "rb").read())
record, _ = sample_record(sample.sample, sample.inputs, sample.case)
print(json.dumps([record["status"], "pint" in sys.modules, record["max_p_max_MPa"]]))
"""
    status, pint, peak = json.loads(fresh_python(code))
    assert status == "ok" and pint is False
    table = pq.read_table(two_workers[0] / "out" / "samples.parquet").to_pylist()
    assert peak == table[1]["max_p_max_MPa"]


def test_a_bad_sweep_is_refused_before_anything_runs(tmp_path):
    path = tmp_path / "bad.toml"
    path.write_text('kind = "sweep"\nbase = "spur_crowned_20_60"\n[[vary]]\n'
                    'field = "pinion.face_width"\nvalues = ["-3 mm"]\n')
    result = CliRunner().invoke(app, ["sweep", str(path), "--out", str(tmp_path / "out")])
    assert result.exit_code == 2
    assert "pinion.face_width" in result.output and "Traceback" not in result.output
    assert not (tmp_path / "out").exists()


def test_the_wilson_interval():
    """Wilson's score interval: 0 of 10 -> [0, 0.278], 5 of 10 -> [0.237, 0.763] (3 digits,
    z = 1.96); it always holds the observed proportion and is symmetric about one half."""
    assert wilson(0, 10) == pytest.approx([0.0, 0.2775], abs=5e-4)
    assert wilson(5, 10) == pytest.approx([0.2366, 0.7634], abs=5e-4)
    for hits in range(11):
        low, high = wilson(hits, 10)
        assert low <= hits / 10 <= high
    low, high = wilson(7, 10)
    assert wilson(3, 10) == pytest.approx([1 - high, 1 - low], abs=1e-12)


def test_a_sweep_on_a_separate_scheduler_survives_a_killed_worker(tmp_path):
    """A Dask scheduler and two workers started as separate processes (`dask scheduler`,
    `dask worker --no-nanny`); one worker is killed once the first sample is in: the sweep
    still completes, every sample answered, the table the same as a local run's."""
    import signal

    from toothcontact.sweep.run import separate_processes

    with separate_processes(tmp_path) as (where, workers):
        path = write_sweep(tmp_path, samples=6)
        killed = []

        def kill_one(record):
            if not killed:
                workers[0].send_signal(signal.SIGKILL)
                killed.append(record["sample"])

        _, written = runner.run_sweep(path, tmp_path / "out", scheduler=where,
                                      on_done=kill_one)
        assert killed and workers[0].wait(timeout=30) == -signal.SIGKILL
    table = pq.read_table(written[0]).to_pylist()
    assert [r["sample"] for r in table] == list(range(6))
    assert all(r["status"] == "ok" for r in table)
    _, local = runner.run_sweep(path, tmp_path / "local", workers=1)
    assert table == pq.read_table(local[0]).to_pylist()


def test_the_sensitivity_is_taken_within_each_grid_point():
    """A figure that rises with the grid's load and, less, with a toleranced slope: pooled
    over the grid the slope's rank correlation would be weak; within each grid point it is
    1 (and -1 for a figure that falls with it). Percentiles are numpy's."""
    from toothcontact.sweep.statistics import summarise

    slopes = [0.1, 0.4, 0.2, 0.3]
    rows = [{"sample": 4 * g + i, "status": "ok", "input:load": float(load),
             "input:slope": s, "p_MPa": 1000.0 * load + s, "margin_mm": -s}
            for g, load in enumerate((1, 2, 3)) for i, s in enumerate(slopes)]
    stats = summarise(rows, ["slope"], ["load"])
    assert stats["sensitivity"]["slope"] == {"p_MPa": pytest.approx(1.0),
                                             "margin_mm": pytest.approx(-1.0)}
    values = [r["p_MPa"] for r in rows]
    assert stats["percentiles"]["p_MPa"]["P95"] == pytest.approx(np.percentile(values, 95))
    pooled = summarise(rows, ["slope"])["sensitivity"]["slope"]["p_MPa"]
    assert abs(pooled) < 0.5


def test_the_sweep_draws_its_figures(two_workers):
    """The sweep's figures beside its table: the histograms of its figures and, the slope
    being toleranced, the tornado of its rank correlations."""
    folder, _, _ = two_workers
    for name in ("histograms.png", "tornado.png"):
        path = folder / "out" / name
        assert path.is_file() and path.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"


def test_positions_on_request_hold_every_samples_rows(two_workers, tmp_path):
    """--positions, resumed on a sweep run without it: every sample runs again (its rows
    per position were not kept), and positions.parquet holds each sample's rows, as many
    as its own analysis has, tagged with its number, their rigid patterns measured (a
    sample whose rows are not kept skips them), and the samples' figures are the same as
    without them."""
    import shutil

    from toothcontact.analyses import analyse
    from toothcontact.runner import load_sweep
    from toothcontact.sweep.sampling import plan

    folder, path, _ = two_workers
    out = tmp_path / "positions"
    shutil.copytree(folder / "out", out)
    done = []
    runner.run_sweep(path, out, workers=1, resume=True, positions=True, on_done=done.append)
    assert len(done) == 4
    rows = pq.read_table(out / "positions.parquet").to_pylist()
    spec, base, base_path = load_sweep(path)
    first = plan(spec, base, base_path.parent)[0]
    own = analyse(first.case).sections["positions"]
    assert [r["sample"] for r in rows].count(0) == len(own)
    assert sorted({r["sample"] for r in rows}) == [0, 1, 2, 3]
    assert all(r["rigid_pattern_area_mm2"] > 0 for r in rows if r["rigid_contact"])
    assert (pq.read_table(out / "samples.parquet").to_pylist()
            == pq.read_table(folder / "out" / "samples.parquet").to_pylist())


def test_an_optimisation_over_a_spectrum_runs_and_resumes_without_rerunning(tmp_path):
    """A rigid sweep (Hertz only) of 2 draws at 2 spectrum levels, the crown radius sized
    in 3 sweeps: the report, the optimisation figure and every design's table are written,
    the best design is one the optimiser tried and honours the constraint; run again
    with --resume nothing is analysed again and the statistics are the same."""
    path = tmp_path / "optimise.toml"
    path.write_text(
        'kind = "sweep"\nbase = "spur_crowned_20_60"\nsamples = 2\nseed = 3\n'
        '[set]\n"analysis.pressure_grid" = 0\n"analysis.interference" = false\n'
        '"analysis.positions" = 5\n'
        '[spectrum]\nfield = "load.tangential_load"\nlevels = ["4000 N", "8000 N"]\n'
        'shares = [0.75, 0.25]\n'
        '[[tolerance]]\nfield = "misalignment.slope"\ndistribution = "uniform"\n'
        'low = "0.0004"\nhigh = "0.0012"\n'
        '[optimise]\nobjective = "P95 max_p_max_MPa"\nevaluations = 3\n'
        '[[optimise.variable]]\nfield = "pinion.crown.radius"\nlow = "2000 mm"\n'
        'high = "8000 mm"\n'
        '[[optimise.constraint]]\nstatistic = "end_loading"\nmax = 0.5\n')
    stats, written = runner.run_sweep(path, tmp_path / "out", workers=1)
    names = {p.name for p in written}
    assert {"samples.parquet", "sweep.json", "report.html", "optimisation.png"} <= names
    opt = stats["optimise"]
    assert opt["evaluations"] == 3 == len(list((tmp_path / "out" / "optimise").iterdir()))
    assert opt["best"] in opt["history"]
    assert opt["best"]["feasible"] == (opt["best"]["constraints"][0] <= 0.5)
    assert sum(r["time_share"] for r in pq.read_table(written[0]).to_pylist()) == \
        pytest.approx(1.0)
    again = []
    resumed, _ = runner.run_sweep(path, tmp_path / "out", workers=1, resume=True,
                                  on_done=again.append)
    assert again == [] and resumed == stats
