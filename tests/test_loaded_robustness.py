"""A loaded contact the solver cannot answer says why in its own rows, and every view of the
run (plots, pictures, reports) is still made from the values it leaves null."""

import json

import pytest

from toothcontact import runner
from toothcontact.contact import loaded

CASE = """kind = "spur"
title = "robustness: a loaded solve that fails"
teeth = [20, 60]
module = "3 mm"
pressure_angle = "20 deg"
face_width = "30 mm"
[pinion.crown]
radius = "4000 mm"
[load]
tangential_load = "8000 N"
[analysis]
positions = 3
interference = false
field_grid = 41
pressure_grid = 24
"""

REASON = "the conjugate-gradient step broke down (forced by the test)"


def strict(text: str):
    """The document parsed as strict JSON (RFC 8259: no NaN or Infinity)."""
    def refuse(constant):
        raise ValueError(f"{constant} in result.json")
    return json.loads(text, parse_constant=refuse)


@pytest.mark.parametrize("failing", ["every position", "one position"])
def test_a_failed_loaded_solve_leaves_a_complete_run(tmp_path, monkeypatch, failing):
    solve, once = loaded.solve_shared, tmp_path / "failed_once"

    def broken(grids, *args, **kwargs):
        if failing == "one position":
            try:
                once.open("x").close()       # created by one call of all the workers'
            except FileExistsError:
                return solve(grids, *args, **kwargs)
        raise RuntimeError(REASON)

    monkeypatch.setattr(loaded, "solve_shared", broken)   # the forked workers inherit it
    case = tmp_path / "failing.toml"
    case.write_text(CASE)
    document, written = runner.run_case(case, tmp_path / "out")
    result = strict((tmp_path / "out" / "result.json").read_text())
    assert result == strict(json.dumps(document))
    rows = result["positions"]
    failed = [r for r in rows if r["bem_status"] == "failed"]
    assert failed and all(REASON in r["bem_reason"] for r in failed)
    assert all(r["bem_p_max_MPa"] is None for r in failed)
    if failing == "every position":
        assert len(failed) == len(rows)
        assert all(r["loaded_transmission_error_urad"] is None for r in rows)
    else:
        assert any(r["bem_status"] == "solved" for r in rows)
    check = next(c for c in result["checks"] if c["name"] == "loaded contact solved at every "
                                                           "contact")
    assert not check["ok"] and REASON in check["detail"]
    stages = result["stages"]
    assert stages["plots"]["status"] == "done", stages["plots"]
    pictures = stages["pictures"]         # or failed for want of OpenGL, not for the nulls
    assert pictures["status"] == "done" or not pictures["reason"].startswith(
        ("TypeError", "ValueError", "KeyError", "AttributeError", "IndexError")), pictures
    names = {p.name for p in written}
    assert {"result.json", "report.md", "report.html"} <= names
    assert REASON in (tmp_path / "out" / "report.md").read_text()
