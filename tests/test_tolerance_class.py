"""Flank tolerance classes (ISO 1328-1:2013, analytic.iso1328) and their use in a sweep:
the formulae of 5.3 evaluated by hand for the bundled automotive helical pinion, the
rounding of 5.2.3, the step factor √2 per class of 5.2.2, the standard's scope, and a
[[tolerance]] whose band a class sets."""

import math

import numpy as np
import pytest
from mutations import CASES

from toothcontact.analytic.iso1328 import flank_tolerances, out_of_scope, rounded
from toothcontact.case import CaseError, read_table
from toothcontact.runner import load_sweep
from toothcontact.sweep.sampling import plan, with_class_bands
from toothcontact.sweep.spec import SweepSpec

#: the bundled helical_measured_topography pinion: z = 27, m_n = 2.25 mm, β = 27°, b = 20 mm
D, MN, B = 27 * 2.25 / math.cos(math.radians(27.0)), 2.25, 20.0


@pytest.mark.parametrize("tolerance_class, f_H_beta, f_H_alpha, f_pT, F_beta", [
    # by hand, class 5: f_HβT = 0.05·√68.181 + 0.35·√20 + 4 = 5.978 -> 6.0 (5 to 10 µm:
    # to 0.5 µm); f_HαT = 0.4·2.25 + 0.001·68.181 + 4 = 4.968 -> 5.0 (under 5: to 0.1 µm);
    # f_pT = 0.001·68.181 + 0.4·2.25 + 5 = 5.968 -> 6.0; F_βT = hypot(5.978, f_fβT =
    # 0.07·√68.181 + 0.45·√20 + 4 = 6.590) = 8.898 -> 9.0
    (5, 6.0, 5.0, 6.0, 9.0),
    # class 6 (×√2): 8.454 -> 8.5, 7.026 -> 7.0, 8.440 -> 8.5, 12.583 -> 13
    (6, 8.5, 7.0, 8.5, 13.0),
    # class 7 (×2): 11.956 -> 12 (over 10 µm: whole µm), 9.936 -> 10.0, 11.936 -> 12, 17.796 -> 18
    (7, 12.0, 10.0, 12.0, 18.0),
    # class 3 (×1/2): 2.989 -> 3.0, 2.484 -> 2.5, 2.984 -> 3.0, 4.449 -> 4.4
    (3, 3.0, 2.5, 3.0, 4.4),
])
def test_the_class_tolerances_are_the_standards_formulae(tolerance_class, f_H_beta, f_H_alpha,
                                                          f_pT, F_beta):
    t = flank_tolerances(tolerance_class, D, MN, B)
    assert (t.helix_slope, t.profile_slope, t.single_pitch, t.helix_total) \
        == (f_H_beta, f_H_alpha, f_pT, F_beta)


def test_rounding_and_the_step_between_classes():
    """5.2.3: over 10 µm to the whole µm, 5-10 µm to 0.5 µm, under 5 µm to 0.1 µm; 5.2.2: two
    classes apart the unrounded tolerances differ by 2 exactly (seen where rounding is
    exact: a large gear whose class-9 value is a whole number of µm to within 0.5)."""
    assert [rounded(v) for v in (10.6, 10.4, 9.74, 9.76, 5.2, 4.96, 4.94, 0.25)] \
        == [11.0, 10.0, 9.5, 10.0, 5.0, 5.0, 4.9, 0.3]
    for A in range(1, 10):
        low, high = flank_tolerances(A, 400.0, 8.0, 100.0), flank_tolerances(A + 2, 400.0, 8.0, 100.0)
        ratio = high.cumulative_pitch / low.cumulative_pitch
        assert ratio == pytest.approx(2.0, rel=0.05 if low.cumulative_pitch > 10 else 0.1)


def test_the_scope_is_the_standards():
    assert out_of_scope(27, D, MN, B, math.radians(27.0)) == []
    beyond = out_of_scope(4, 3.0, 0.3, 2.0, math.radians(50.0))
    assert [b.split(" =")[0] for b in beyond] == ["teeth", "reference_diameter",
                                                  "normal_module", "face_width", "helix_angle"]
    with pytest.raises(ValueError, match="classes 1 to 11"):
        flank_tolerances(12, D, MN, B)


def classed_sweep(tolerance: dict, base: str = "helical_measured_topography") -> SweepSpec:
    return SweepSpec.model_validate({"kind": "sweep", "base": base, "samples": 64,
                                     "tolerance": [tolerance]})


def test_a_class_sets_the_band_a_sweep_draws():
    """pinion.helix_slope.amount with iso1328_class = 6: a normal of ±3σ = f_HβT = 8.5 µm
    about 0 (64 Latin hypercube draws: 4000 draws' spread would be 8.5/3; the draws lie
    within ±3.1σ); the gear's profile slope uniform over ±f_HαT of the gear (z = 38: d =
    95.95 mm, f_HαT = 0.4·2.25 + 0.096 + 4 = 4.996 -> 5.0, times √2 = 7.07 -> 7.0 µm)."""
    base = read_table(CASES / "helical_measured_topography.toml")
    spec = with_class_bands(classed_sweep({"field": "pinion.helix_slope.amount",
                                           "distribution": "normal", "iso1328_class": 6}),
                            base, CASES)
    (t,) = spec.tolerance
    assert (t.mean, t.band) == ("0.0 um", "8.5 um")
    draws = np.array([float(s.inputs["pinion.helix_slope.amount"].split()[0])
                      for s in plan(spec, base, CASES)])
    assert np.all(np.abs(draws) <= 3.1 * 8.5 / 3) and draws.std() == pytest.approx(8.5 / 3, rel=0.1)
    spec = with_class_bands(classed_sweep({"field": "gear.profile_slope.amount",
                                           "distribution": "uniform", "iso1328_class": 6,
                                           "mean": "0.002 mm"}), base, CASES)
    assert (spec.tolerance[0].low, spec.tolerance[0].high) == ("-5.0 um", "9.0 um")


def test_a_class_is_refused_where_it_sets_no_band(tmp_path):
    """A class on a field it has no tolerance for, beside a band, or on a gear beyond the
    standard's scope: refused naming the field, before anything runs."""
    import tomli_w

    for tolerance, base, says in (
            ({"field": "pinion.twist.amount", "distribution": "normal", "iso1328_class": 6},
             "helical_measured_topography", "iso1328_class sets the band of"),
            ({"field": "pinion.helix_slope.amount", "distribution": "normal", "band": "5 um",
              "iso1328_class": 6}, "helical_measured_topography", "the class gives it"),
            ({"field": "pinion.helix_slope.amount", "distribution": "normal",
              "iso1328_class": 6}, "spur_crowned_20_60", None)):
        path = tmp_path / "sweep.toml"
        path.write_text(tomli_w.dumps({"kind": "sweep", "base": base, "samples": 4,
                                       "tolerance": [tolerance]}))
        if says is None:     # in scope: z = 20, m = 3 mm, b = 30 mm: f_HβT = (0.05·√60 +
            # 0.35·√30 + 4)·√2 = 8.916 -> 9.0 µm
            assert load_sweep(path)[0].tolerance[0].band == "9.0 um"
            continue
        with pytest.raises(CaseError, match=says):
            load_sweep(path)
    small = read_table(CASES / "spur_crowned_20_60.toml") | {"face_width": "3 mm"}
    with pytest.raises(CaseError, match=r"tolerance\[0\].*face_width = 3 mm \(ISO 1328-1:2013 "
                                        r"takes 4 to 1200 mm\)"):
        with_class_bands(classed_sweep({"field": "pinion.helix_slope.amount",
                                        "distribution": "normal", "iso1328_class": 6}),
                         small, CASES)
