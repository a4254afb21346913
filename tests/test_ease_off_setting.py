"""[analysis] ease_off: the ease-off map is a run's picture and section; a sweep's sample
and the positions check's second pass leave it, at the same figures."""

import copy

from toothcontact import analyses
from toothcontact.analyses.contact import refining_case
from toothcontact.case import parse_case
from toothcontact.sweep.run import sample_record

RAW = {"kind": "spur", "title": "ease-off", "teeth": [20, 60], "module": "3 mm",
       "pressure_angle": "20 deg", "face_width": "20 mm",
       "pinion": {"crown": {"radius": "4000 mm"}}, "misalignment": {"slope": "0.0005"},
       "load": {"tangential_load": "8000 N"},
       "analysis": {"positions": 3, "interference": False, "pressure_grid": 48,
                    "positions_check": False, "subsurface": False}}


def with_analysis(**settings) -> dict:
    raw = copy.deepcopy(RAW)
    raw["analysis"].update(settings)
    return raw


def test_leaving_the_ease_off_out_leaves_every_other_section_as_it_is():
    mapped = analyses.analyse(parse_case(with_analysis())).sections
    left = analyses.analyse(parse_case(with_analysis(ease_off=False))).sections
    assert len(mapped["ease_off"]["separation_um"]) == 31      # the pinion's 31 × 61 grid
    assert "ease_off" not in left
    assert {k: v for k, v in mapped.items() if k != "ease_off"} == left


def test_a_sweep_sample_leaves_the_ease_off_unless_its_case_asks(monkeypatch):
    seen = []
    real = analyses.analyse

    def analyse(case):
        seen.append(case.analysis.ease_off)
        return real(case)

    monkeypatch.setattr(analyses, "analyse", analyse)
    plain, _ = sample_record(0, {}, parse_case(with_analysis()))
    asked, _ = sample_record(1, {}, parse_case(with_analysis(ease_off=True)))
    assert seen == [False, True]
    assert plain["status"] == asked["status"] == "ok"
    assert {k: v for k, v in plain.items() if k != "sample"} == {
        k: v for k, v in asked.items() if k != "sample"}


def test_the_positions_checks_second_pass_leaves_the_ease_off():
    case = parse_case(with_analysis())
    assert case.analysis.ease_off is None            # a run maps it
    assert refining_case(case).analysis.ease_off is False
