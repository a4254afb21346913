"""Writing results: result.json and report.md, each written whole or not at all."""

from __future__ import annotations

import json
import math
import os
import tempfile
from pathlib import Path

from . import __version__


def result_document(name: str, case, raw: dict, result) -> dict:
    """The JSON document of a run: what was asked (units as given) and what was found."""
    return {"case": name, "kind": case.kind, "title": case.title, "source": case.source,
            "assumptions": case.assumptions, "toothcontact_version": __version__,
            "units": "mm, N, MPa, rad unless the key says otherwise",
            "inputs": raw, **result.as_dict()}


def write_run(out_dir: Path, document: dict) -> list[Path]:
    """Write DIR/result.json and DIR/report.md atomically (temporary file, then rename)."""
    texts = {"result.json": json.dumps(_finite(document), indent=2) + "\n",
             "report.md": markdown(document)}
    out_dir.mkdir(parents=True, exist_ok=True)
    return [write_text(out_dir / filename, text) for filename, text in texts.items()]


def write_text(target: Path, text: str) -> Path:
    """Write a text file whole or not at all (temporary file, then rename)."""
    fd, tmp = tempfile.mkstemp(dir=target.parent, prefix=f".{target.name}.", suffix=".tmp")
    try:
        with os.fdopen(fd, "w", encoding="utf-8") as handle:
            handle.write(text)
        os.chmod(tmp, 0o644)
        os.replace(tmp, target)
    except BaseException:
        Path(tmp).unlink(missing_ok=True)
        raise
    return target


def _finite(value):
    """JSON has no infinity: write it as the string "inf"."""
    if isinstance(value, float) and not math.isfinite(value):
        return str(value)
    if isinstance(value, dict):
        return {k: _finite(v) for k, v in value.items()}
    if isinstance(value, (list, tuple)):
        return [_finite(v) for v in value]
    return value


def markdown(document: dict) -> str:
    """A human report: failed checks first, then inputs as given, then the results."""
    lines = [f"# {document['title'] or document['case']}", ""]
    if document["source"]:
        lines += [f"Source: {document['source']}", ""]
    failed = [c for c in document["checks"] if not c["ok"]]
    if failed:
        lines += ["## Failed checks", ""] + [f"- **{c['name']}**: {c['detail']}" for c in failed] + [""]
    if document["assumptions"]:
        lines += ["## Assumptions", ""] + [f"- {a}" for a in document["assumptions"]] + [""]
    lines += ["## Inputs (as given)", "", "```toml", *_toml_lines(document["inputs"]), "```", ""]
    lines += ["## Results", ""]
    skip = {"case", "kind", "title", "source", "assumptions", "toothcontact_version", "units",
            "inputs", "checks", "notes"}
    for key, value in document.items():
        if key in skip:
            continue
        lines += [f"### {key}", "", *_table(value), ""]
    if document["checks"]:
        lines += ["## Checks", "", "| check | result | detail |", "|---|---|---|"]
        lines += [f"| {c['name']} | {'pass' if c['ok'] else '**FAIL**'} | {c['detail']} |"
                  for c in document["checks"]] + [""]
    if document["notes"]:
        lines += ["## Notes", ""] + [f"- {n}" for n in document["notes"]] + [""]
    lines += [f"_toothcontact {document['toothcontact_version']}; {document['units']}._", ""]
    return "\n".join(lines)


def _fmt(value) -> str:
    if isinstance(value, float):
        return f"{value:.6g}"
    return "" if value is None else str(value)


def _table(value) -> list[str]:
    if isinstance(value, dict):
        return ["| quantity | value |", "|---|---|"] + [f"| {k} | {_fmt(v)} |" for k, v in value.items()]
    if isinstance(value, list) and value and isinstance(value[0], dict):
        keys = list(dict.fromkeys(k for row in value for k in row))
        return (["| " + " | ".join(keys) + " |", "|" + "---|" * len(keys)]
                + ["| " + " | ".join(_fmt(row.get(k)) for k in keys) + " |" for row in value])
    return [_fmt(value)]


def _toml_lines(table: dict, prefix: str = "") -> list[str]:
    plain = [f"{k} = {json.dumps(v)}" for k, v in table.items()
             if not isinstance(v, dict) and not (isinstance(v, list) and v and isinstance(v[0], dict))]
    lines = plain
    for k, v in table.items():
        name = f"{prefix}{k}"
        if isinstance(v, dict):
            lines += ["", f"[{name}]", *_toml_lines(v, f"{name}.")]
        elif isinstance(v, list) and v and isinstance(v[0], dict):
            for row in v:
                lines += ["", f"[[{name}]]", *_toml_lines(row, f"{name}.")]
    return lines
