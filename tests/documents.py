"""What every finished run's folder holds, checked the same way wherever a run is made (the
CLI's `run` in test_cli, the installed wheel's `demo` in test_install)."""

import json
from pathlib import Path


def strict_json(text: str):
    """Parse RFC 8259 JSON: NaN, Infinity and -Infinity are refused."""
    def refuse(constant):
        raise ValueError(f"{constant} is not JSON")
    return json.loads(text, parse_constant=refuse)


def complete_run(out: Path) -> dict:
    """The run folder `out` holds a complete result: result.json strict JSON with its kind
    and source, every check saying its kind; report.html opening with its key results;
    report.md a Markdown document. Returns result.json's document."""
    document = strict_json((out / "result.json").read_text())
    assert document["kind"] and document["source"]
    assert all(c["kind"] in ("design", "source", "method", "solver", "rigid")
               for c in document["checks"])
    page = (out / "report.html").read_text()     # the report opens with its key results
    assert page.index('id="key-results"') < page.index('id="design-checks"')
    assert (out / "report.md").read_text().startswith("# ")
    return document
