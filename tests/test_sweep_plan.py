"""Sweep files and their samples (sweep.spec, sweep.sampling): the same seed gives the same
samples, the samplers keep their distributions (Latin hypercube strata, the normal's mean
and spread, the triangular's median in closed form), grids run in the given units, and
every bad sweep is refused naming the field."""

from __future__ import annotations

import math

import numpy as np
import pytest
from mutations import CASES

from toothcontact.case import CaseError, read_table
from toothcontact.runner import load_sweep
from toothcontact.sweep.sampling import plan
from toothcontact.sweep.spec import SweepSpec

BASE = read_table(CASES / "spur_crowned_20_60.toml")


def sweep(**fields):
    return SweepSpec.model_validate({"kind": "sweep", "base": "spur_crowned_20_60", **fields})


def slopes(samples):
    return np.array([s.inputs["misalignment.slope"] for s in samples])


def test_the_same_seed_gives_the_same_samples_and_each_is_a_valid_case():
    """Every sampler, twice with one seed: the same values; another seed: others. The
    sample numbers run from 0, and each sample's table carries its inputs."""
    for sampling in ("random", "latin_hypercube", "sobol"):
        spec = sweep(samples=16, seed=3, sampling=sampling,
                     tolerance=[{"field": "misalignment.slope", "distribution": "uniform",
                                 "low": "0.0002", "high": "0.0012"}])
        first, again = plan(spec, BASE), plan(spec, BASE)
        assert [s.inputs for s in first] == [s.inputs for s in again]
        other = plan(spec.model_copy(update={"seed": 4}), BASE)
        assert not np.allclose(slopes(first), slopes(other))
        assert [s.sample for s in first] == list(range(16))
        assert all(s.raw["misalignment"]["slope"] == s.inputs["misalignment.slope"]
                   for s in first)


def test_a_latin_hypercube_puts_one_sample_in_each_stratum():
    """n uniform samples on [low, high): exactly one in each of the n equal strata."""
    n = 40
    spec = sweep(samples=n, seed=7, tolerance=[{"field": "misalignment.slope",
                                                "distribution": "uniform",
                                                "low": "0.0", "high": "0.002"}])
    strata = np.floor(slopes(plan(spec, BASE)) / 0.002 * n).astype(int)
    assert sorted(strata) == list(range(n))


def test_the_distributions_keep_their_parameters():
    """Latin hypercube, 4000 samples. Normal: the mean within 0.002σ, the standard
    deviation within 1 %; a ±3σ band gives the same draws as std = band/3. Triangular (low 0, mode
    0.75, high 1 mrad): all inside, the median low + sqrt((high - low)(mode - low)/2)
    within 0.5 %."""
    n = 4000
    normal = {"field": "misalignment.slope", "distribution": "normal", "mean": "0.8 mrad"}
    by_std = slopes(plan(sweep(samples=n, tolerance=[{**normal, "std": "0.3 mrad"}]), BASE))
    by_band = slopes(plan(sweep(samples=n, tolerance=[{**normal, "band": "0.9 mrad"}]), BASE))
    values = np.array([float(v.split()[0]) for v in by_std])            # in mrad, as given
    assert values.mean() == pytest.approx(0.8, abs=0.002 * 0.3)
    assert values.std() == pytest.approx(0.3, rel=0.01)
    assert list(by_std) == list(by_band)
    triangular = slopes(plan(sweep(samples=n, tolerance=[
        {"field": "misalignment.slope", "distribution": "triangular", "low": "0",
         "mode": "0.00075", "high": "0.001"}]), BASE))
    assert triangular.min() >= 0.0 and triangular.max() <= 0.001
    assert np.median(triangular) == pytest.approx(math.sqrt(0.001 * 0.00075 / 2), rel=0.005)


def test_a_grid_runs_from_to_in_steps_in_the_unit_given():
    """Two axes: the first slowest; from/to in the unit of `from` (to given in another unit
    of the same dimension); each grid point repeated `samples` times with the same draws."""
    spec = sweep(samples=2, vary=[
        {"field": "load.tangential_load", "from": "4 kN", "to": "8000 N", "steps": 3},
        {"field": "misalignment.slope", "values": ["0", "0.001"]}],
        tolerance=[{"field": "pinion.crown.radius", "distribution": "uniform",
                    "low": "3000 mm", "high": "5000 mm"}])
    samples = plan(spec, BASE)
    assert len(samples) == 3 * 2 * 2
    loads = [s.inputs["load.tangential_load"] for s in samples]
    assert loads[:4] == ["4.0 kN"] * 4 and loads[-1] == "8.0 kN"
    assert [s.inputs["misalignment.slope"] for s in samples[:4]] == ["0", "0", "0.001", "0.001"]
    crowns = [s.inputs["pinion.crown.radius"] for s in samples]
    assert crowns[0::2] == [crowns[0]] * 6 and crowns[1::2] == [crowns[1]] * 6


@pytest.mark.parametrize("fields, says", [
    ({}, "nothing varies"),
    ({"vary": [{"field": "load.tangential_load", "values": ["1 N"], "steps": 3}]},
     "not both"),
    ({"vary": [{"field": "load.tangential_load", "from": "1 N", "to": "2 N"}]},
     "all of from, to and steps"),
    ({"tolerance": [{"field": "misalignment.slope", "distribution": "normal",
                     "mean": "0.001"}]}, "takes mean, std or band, mean"),
    ({"vary": [{"field": "misalignment.slope", "values": ["0"]}],
      "tolerance": [{"field": "misalignment.slope", "distribution": "uniform", "low": "0",
                     "high": "0.001"}]}, "twice"),
    ({"sampling": "grid"}, "sampling"),
])
def test_a_bad_sweep_is_refused_naming_the_field(tmp_path, fields, says):
    import tomli_w

    path = tmp_path / "sweep.toml"
    path.write_text(tomli_w.dumps({"kind": "sweep", "base": "spur_crowned_20_60", **fields}))
    with pytest.raises(CaseError, match=says):
        load_sweep(path)


@pytest.mark.parametrize("fields, says", [
    ({"vary": [{"field": "pinion.face_width", "values": ["-5 mm"]}]},
     r"sample 0: pinion\.face_width.*set by the sweep"),
    ({"vary": [{"field": "misalignment.slopes", "values": ["0"]}]},
     r"misalignment\.slopes: unknown field"),
    ({"vary": [{"field": "load.tangential_load", "from": "1 kN", "to": "2 mm",
                "steps": 2}]}, r"vary\[0\]\.to: '2 mm' is not in the unit of from"),
    ({"tolerance": [{"field": "misalignment.slope", "distribution": "uniform",
                     "low": "0.001", "high": "0"}]}, "high .* must exceed low"),
])
def test_a_sample_that_is_no_case_is_refused_before_anything_runs(fields, says):
    with pytest.raises(CaseError, match=says):
        plan(sweep(**fields), BASE)


def test_a_sweep_file_finds_its_base_by_name_or_beside_it(tmp_path):
    """`base`: a bundled name, or a case file relative to the sweep file."""
    (tmp_path / "mine.toml").write_text((CASES / "spur_crowned_20_60.toml").read_text())
    for base in ("spur_crowned_20_60", "mine.toml"):
        path = tmp_path / f"sweep_{base.split('.')[0]}.toml"
        path.write_text(f'kind = "sweep"\nbase = "{base}"\n[[vary]]\n'
                        'field = "misalignment.slope"\nvalues = ["0", "0.001"]\n')
        spec, raw, found = load_sweep(path)
        assert raw["kind"] == "spur" and found.is_file()
        assert len(plan(spec, raw, found.parent)) == 2


def test_the_bundled_sweep_is_a_valid_sweep():
    """cases/sweeps/spur_crown_tolerance.toml: its 2 spectrum loads × 12 draws, each a
    valid case, the slope's draws the same at both loads."""
    spec, raw, found = load_sweep(CASES / "sweeps" / "spur_crown_tolerance.toml")
    samples = plan(spec, raw, found.parent)
    assert len(samples) == 24
    assert list(slopes(samples[:12])) == list(slopes(samples[12:]))
