"""A family of realistic designs no test was tuned to (toothcontact.families), each run end
to end at small settings: it must answer without an exception and keep the physical
invariants (families.check). benchmarks/family.py runs a larger family."""

import json

import pytest

from toothcontact import families
from toothcontact.analyses import analyse
from toothcontact.case import parse_case
from toothcontact.views.report import result_document

#: without the positions check (a second pass of the same stages at midway positions, 40 %
#: of this test's time); benchmarks/family.py runs its 510 designs with it
QUIET = {"positions_check": False}
SPUR = families.spur_designs(36, seed=11, analysis=QUIET)
SPLINE = families.spline_designs(9, seed=12, analysis=QUIET)


def run(raw: dict) -> dict:
    case = parse_case(raw)
    document = result_document("family", case, raw, analyse(case))
    json.dumps(document, allow_nan=False)       # strict JSON
    return document


@pytest.mark.parametrize("raw", SPUR + SPLINE, ids=lambda raw: raw["title"])
def test_design_answers_and_keeps_the_invariants(raw):
    assert families.check(raw, run(raw)) == []


def test_the_family_spans_the_design_space():
    """The generated family holds what the issue asks for: external and ring pairs, spur and
    helical up to 35°, shifts from -0.5 to +0.8, crowned and uncrowned, slopes of both signs,
    splines of 30, 37.5 and 45°."""
    many = families.spur_designs(300, seed=1)
    assert any(d["teeth"][1] < 0 for d in many) and any(d["teeth"][1] > 0 for d in many)
    helix = [float(d["helix_angle"].split()[0]) for d in many]
    assert min(helix) == 0.0 and max(helix) > 30.0
    shifts = [d["pinion"]["profile_shift"] for d in many]
    assert min(shifts) < -0.4 and max(shifts) > 0.7
    assert any("crown" in d["pinion"] for d in many) and any("crown" not in d["pinion"] for d in many)
    slopes = [float(d["misalignment"]["slope"]) for d in many]
    assert min(slopes) < 0 < max(slopes)
    angles = {float(d["pressure_angle"].split()[0]) for d in families.spline_designs(9, seed=1)}
    assert angles == {30.0, 37.5, 45.0}
