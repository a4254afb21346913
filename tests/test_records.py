"""The Python API's typed records (records.py): a case's result as its summary and its
positions, each a table a study stacks, beside the document they come from."""

import json

import pandas
import pytest

from toothcontact import runner
from toothcontact.records import CaseResult


@pytest.fixture(scope="module")
def relieved():
    return runner.analyse_record("spur_relieved_20_60")


def test_the_record_holds_what_result_json_holds(relieved):
    document = relieved.document
    assert relieved.case == "spur_relieved_20_60" and relieved.kind == "spur"
    assert dict(relieved.summary) == document["summary"]
    assert list(relieved.positions) == document["positions"]
    assert len(relieved.checks) == len(document["checks"])
    assert relieved.passed == all(c["ok"] for c in document["checks"] if c["kind"] == "design")
    assert relieved.passed        # the bundled design that passes its checks
    json.dumps(document, allow_nan=False)


def test_positions_and_summary_as_dataframes(relieved):
    """A row per position and pair, a column per key, nested margins one column per edge;
    the summary one row indexed by the case, and summaries of cases stack into a table."""
    positions = relieved.positions.to_dataframe()
    assert isinstance(positions, pandas.DataFrame) and len(positions) == len(relieved.positions)
    assert {"roll_deg", "pair", "bem_p_max_MPa", "edge_margins_mm.pinion_tip"} <= set(positions)
    first = relieved.positions.rows[0]
    assert positions["edge_margins_mm.pinion_tip"].iloc[0] == first["edge_margins_mm"]["pinion_tip"]
    summary = relieved.summary.to_dataframe()
    assert list(summary.index) == ["spur_relieved_20_60"]
    assert summary.loc["spur_relieved_20_60", "bem_max_p_max_MPa"] == \
        relieved.summary["bem_max_p_max_MPa"]
    assert "positions_check.refined_bem_max_p_max_MPa" in summary
    other = CaseResult.from_document(dict(relieved.document, case="again"))
    stacked = pandas.concat([relieved.summary.to_dataframe(), other.summary.to_dataframe()])
    assert list(stacked.index) == ["spur_relieved_20_60", "again"]


def test_a_result_without_positions_is_a_record_too():
    """A Hertz case: a summary-less result has an empty summary and no positions."""
    result = runner.analyse_record("hertz_sphere_on_flat")
    assert result.kind == "hertz" and len(result.positions) == 0
    assert result.positions.to_dataframe().empty
