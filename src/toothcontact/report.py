"""Writing results: result.json, report.md and report.html (self-contained: the pictures
embedded as base64), each written whole or not at all."""

from __future__ import annotations

import base64
import contextlib
import html as _html
import json
import math
import os
import shutil
import tempfile
from pathlib import Path

from . import __version__


def result_document(name: str, case, raw: dict, result) -> dict:
    """The JSON document of a run: what was asked (units as given) and what was found."""
    return {"case": name, "kind": case.kind, "title": case.title, "source": case.source,
            "assumptions": case.assumptions, "toothcontact_version": __version__,
            "units": "mm, N, MPa, rad unless the key says otherwise",
            "inputs": raw, **result.as_dict()}


def write_run(out_dir: Path, document: dict, images=()) -> list[Path]:
    """Write DIR/result.json, DIR/report.md and DIR/report.html atomically (temporary file,
    then rename). `images`: the PNGs of the run (plots and pictures, in DIR), linked from
    report.md and embedded in report.html."""
    out_dir = Path(out_dir)
    images = [Path(p) for p in images]
    texts = {"result.json": json.dumps(_finite(document), indent=2, allow_nan=False) + "\n",
             "report.md": markdown(document, [_relative(p, out_dir) for p in images]),
             "report.html": html(document, images)}
    out_dir.mkdir(parents=True, exist_ok=True)
    return [write_text(out_dir / filename, text) for filename, text in texts.items()]


def _relative(path: Path, folder: Path) -> str:
    try:
        return path.resolve().relative_to(folder.resolve()).as_posix()
    except ValueError:
        return path.as_posix()


#: captions of the pictures and plots, by file name
CAPTIONS = {
    "pattern_head_on.png": "Contact pattern on the flank, head-on: paint up to the approach, "
                           "every contact's Hertz ellipse, edge contact in red",
    "pattern_perspective.png": "Contact pattern on the flank, in perspective",
    "pair.png": "The pair in mesh: contact points and ellipses",
    "pressure.png": "Loaded contact: the largest pressure over the mesh cycle",
    "mesh_cycle.png": "Over the mesh cycle: transmission error, stress, semi-axes, edge margin",
    "ease_off.png": "Ease-off of the flank",
    "crown_design.png": "Crown design chart",
    "worm_efficiency_temperature.png": "Worm-set efficiency against the lubricant temperature",
    "worm_efficiency_torque.png": "Worm-set efficiency against the output torque",
}


def caption(path) -> str:
    name = Path(path).name
    return CAPTIONS.get(name, Path(name).stem.replace("_", " "))


def write_atomic(target: str | Path, write, binary: bool = False) -> Path:
    """Write a file whole or not at all: `write(handle)` fills a temporary file beside
    `target` (opened "wb" if binary, else UTF-8 text), which is then renamed onto it."""
    target = Path(target)
    target.parent.mkdir(parents=True, exist_ok=True)
    fd, tmp = tempfile.mkstemp(dir=target.parent, prefix=f".{target.name}.", suffix=".tmp")
    try:
        with (os.fdopen(fd, "wb") if binary else os.fdopen(fd, "w", encoding="utf-8")) as handle:
            write(handle)
        os.chmod(tmp, 0o644)
        os.replace(tmp, target)
    except BaseException:
        Path(tmp).unlink(missing_ok=True)
        raise
    return target


_STAGING = ".staging"


@contextlib.contextmanager
def staging_folder(target: str | Path):
    """Yield an empty folder beside `target` to write a run into; on success it replaces
    `target` (the old folder is renamed away first, then removed), on any failure it is
    removed and `target` stays as it was. Staging folders that a killed run left behind
    (their process gone) are removed on the way in."""
    target = Path(target).absolute()
    target.parent.mkdir(parents=True, exist_ok=True)
    _remove_abandoned(target)
    staging = Path(tempfile.mkdtemp(dir=target.parent,
                                    prefix=f".{target.name}.{os.getpid()}.", suffix=_STAGING))
    try:
        yield staging
        os.chmod(staging, 0o755)
        retired = None
        if target.exists():
            retired = staging.with_name(staging.name[:-len(_STAGING)] + ".retired")
            os.replace(target, retired)
        os.replace(staging, target)
        if retired is not None:
            shutil.rmtree(retired, ignore_errors=True)
    except BaseException:
        shutil.rmtree(staging, ignore_errors=True)
        raise


def _remove_abandoned(target: Path) -> None:
    for folder in target.parent.glob(f".{target.name}.*.*"):
        if folder.suffix not in (_STAGING, ".retired"):
            continue
        pid = folder.name[len(target.name) + 2:].split(".")[0]
        if pid.isdigit() and not _alive(int(pid)):
            shutil.rmtree(folder, ignore_errors=True)


def _alive(pid: int) -> bool:
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    except PermissionError:
        return True
    return True


def write_text(target: Path, text: str) -> Path:
    """Write a text file whole or not at all (write_atomic)."""
    return write_atomic(target, lambda handle: handle.write(text))


def _finite(value):
    """Strict JSON (RFC 8259) has no NaN or infinity: a number that does not apply is null
    (its entry says why, e.g. by the contact model)."""
    if isinstance(value, float) and not math.isfinite(value):
        return None
    if isinstance(value, dict):
        return {k: _finite(v) for k, v in value.items()}
    if isinstance(value, (list, tuple)):
        return [_finite(v) for v in value]
    return value


def markdown(document: dict, images=()) -> str:
    """A human report: failed checks first, then inputs as given, then the results and the
    pictures (`images`: paths relative to the report)."""
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
    if images:
        lines += ["## Pictures and plots", ""]
        lines += [f"![{caption(p)}]({Path(p).as_posix()})" for p in images] + [""]
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


# ---------------------------------------------------------------------------------------
# HTML: one self-contained file (inline style, images as data: URIs, no script, no link)

_SKIP = {"case", "kind", "title", "source", "assumptions", "toothcontact_version", "units",
         "inputs", "checks", "notes"}

_STYLE = """
body { font: 15px/1.45 system-ui, -apple-system, "Segoe UI", Roboto, sans-serif; color: #1a1a1a;
       max-width: 1240px; margin: 1.5em auto; padding: 0 1em; }
h1 { font-size: 1.6em; margin-bottom: 0.2em; } h2 { margin-top: 1.6em; border-bottom: 1px solid #ddd; }
.meta { color: #555; }
.failed { border: 2px solid #d62728; background: #fdecec; padding: 0.6em 1em; border-radius: 6px; }
.failed h2 { color: #d62728; border: none; margin-top: 0.2em; }
.passed { border: 2px solid #2ca02c; background: #eef8ee; padding: 0.6em 1em; border-radius: 6px; }
table { border-collapse: collapse; margin: 0.5em 0 1em; font-size: 0.9em; }
th, td { border: 1px solid #ccc; padding: 0.2em 0.5em; text-align: left; vertical-align: top; }
th { background: #f3f3f3; } td.num { text-align: right; font-variant-numeric: tabular-nums; }
.scroll { overflow-x: auto; max-height: 32em; overflow-y: auto; }
pre { background: #f6f6f6; padding: 0.8em; overflow-x: auto; }
figure { margin: 1em 0 2em; } figure img { max-width: 100%; border: 1px solid #ddd; }
figcaption { color: #555; font-size: 0.9em; }
.fail { color: #d62728; font-weight: bold; } .pass { color: #2ca02c; }
"""


def html(document: dict, images=()) -> str:
    """The report as one self-contained HTML page: the failed checks at the top, the case's
    and the tool's assumptions, the inputs as given (with their units), the results tables,
    the pictures and plots (`images`: PNG paths, embedded as base64) and every check."""
    e = _html.escape
    title = document.get("title") or document["case"]
    failed = [c for c in document["checks"] if not c["ok"]]
    out = ["<!DOCTYPE html>", '<html lang="en">', "<head>", '<meta charset="utf-8">',
           '<meta name="viewport" content="width=device-width, initial-scale=1">',
           f"<title>{e(title)}</title>", f"<style>{_STYLE}</style>", "</head>", "<body>",
           f"<h1>{e(title)}</h1>",
           f'<p class="meta">case <b>{e(document["case"])}</b> · kind {e(document["kind"])}'
           + (f" · source: {e(document['source'])}" if document.get("source") else "") + "</p>"]
    if failed:
        out += ['<section class="failed" id="failed-checks">',
                f"<h2>Failed checks ({len(failed)} of {len(document['checks'])})</h2>", "<ul>"]
        out += [f"<li><b>{e(c['name'])}</b>: {e(c['detail'])}</li>" for c in failed]
        out += ["</ul>", "</section>"]
    elif document["checks"]:
        out.append(f'<p class="passed">All {len(document["checks"])} checks pass.</p>')
    if document.get("assumptions"):
        out += ["<h2>Assumptions of the case</h2>", "<ul>"]
        out += [f"<li>{e(str(a))}</li>" for a in document["assumptions"]] + ["</ul>"]
    tool = list(document.get("notes") or [])
    rule = (document.get("summary") or {}).get("load_sharing") if isinstance(
        document.get("summary"), dict) else None
    if rule:
        tool.append(f"load sharing: {rule}")
    if tool:
        out += ["<h2>Assumptions the tool made</h2>", "<ul>"]
        out += [f"<li>{e(str(n))}</li>" for n in tool] + ["</ul>"]
    out += ["<h2>Inputs (as given)</h2>",
            f"<pre>{e(chr(10).join(_toml_lines(document['inputs'])))}</pre>"]
    out += ["<h2>Results</h2>", f'<p class="meta">{e(document["units"])}</p>']
    for key, value in document.items():
        if key in _SKIP:
            continue
        out += [f"<h3>{e(key)}</h3>", _html_table(value)]
    if images:
        out.append("<h2>Pictures and plots</h2>")
        for path in images:
            data = base64.b64encode(Path(path).read_bytes()).decode("ascii")
            out += ["<figure>", f'<img alt="{e(caption(path))}" src="data:image/png;base64,{data}">',
                    f"<figcaption>{e(caption(path))} ({e(Path(path).name)})</figcaption>",
                    "</figure>"]
    if document["checks"]:
        out += ["<h2>Checks</h2>", "<table>", "<tr><th>check</th><th>result</th><th>detail</th></tr>"]
        out += [f"<tr><td>{e(c['name'])}</td><td class=\"{'pass' if c['ok'] else 'fail'}\">"
                f"{'pass' if c['ok'] else 'FAIL'}</td><td>{e(c['detail'])}</td></tr>"
                for c in document["checks"]]
        out.append("</table>")
    out += [f'<p class="meta">toothcontact {e(str(document["toothcontact_version"]))}</p>',
            "</body>", "</html>", ""]
    return "\n".join(out)


def _html_value(value) -> str:
    """A cell: numbers formatted, long lists summarised, small dicts as key: value lines."""
    e = _html.escape
    if isinstance(value, dict):
        return "; ".join(f"{e(str(k))}: {_html_value(v)}" for k, v in value.items())
    if isinstance(value, (list, tuple)):
        flat = _flatten(value)
        numbers = [v for v in flat if isinstance(v, (int, float)) and not isinstance(v, bool)]
        if len(flat) > 12:
            shape = " × ".join(str(n) for n in _shape(value))
            if numbers:
                finite = [v for v in numbers if math.isfinite(v)]
                span = f", {_fmt(min(finite))} to {_fmt(max(finite))}" if finite else ""
                return e(f"[{shape} values{span}]")
            return e(f"[{shape} values]")
        return e("[" + ", ".join(_fmt(v) for v in value) + "]") if not any(
            isinstance(v, (list, dict)) for v in value) else "<br>".join(_html_value(v) for v in value)
    return e(_fmt(value))


def _flatten(value) -> list:
    if isinstance(value, (list, tuple)):
        return [x for v in value for x in _flatten(v)]
    return [value]


def _shape(value) -> list[int]:
    if isinstance(value, (list, tuple)) and value:
        return [len(value)] + _shape(value[0])
    return []


def _cell(value) -> str:
    numeric = isinstance(value, (int, float)) and not isinstance(value, bool)
    return f'<td class="num">{_html_value(value)}</td>' if numeric else f"<td>{_html_value(value)}</td>"


def _html_table(value) -> str:
    e = _html.escape
    if isinstance(value, dict):
        rows = "".join(f"<tr><th>{e(str(k))}</th>{_cell(v)}</tr>" for k, v in value.items())
        return f'<div class="scroll"><table>{rows}</table></div>'
    if isinstance(value, list) and value and all(isinstance(r, dict) for r in value):
        keys = list(dict.fromkeys(k for row in value for k in row))
        head = "".join(f"<th>{e(k)}</th>" for k in keys)
        body = "".join("<tr>" + "".join(_cell(row.get(k)) for k in keys) + "</tr>" for row in value)
        return f'<div class="scroll"><table><tr>{head}</tr>{body}</table></div>'
    return f"<p>{_html_value(value)}</p>"
