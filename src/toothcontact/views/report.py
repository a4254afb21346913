"""Writing results: result.json, report.md and report.html (self-contained: the pictures
embedded as base64), each written whole or not at all."""

from __future__ import annotations

import base64
import json
import math
import re
from pathlib import Path

from .. import __version__
from ..writing import write_text
from .report_view import view


def result_document(name: str, case, raw: dict, result, provenance: dict | None = None
                    ) -> dict:
    """The JSON document of a run: what was asked (units as given), what was found, and
    what made it (`provenance`: run_at_utc, case_file, case_sha256, command)."""
    return {"case": name, "kind": case.kind, "title": case.title, "source": case.source,
            "assumptions": case.assumptions, "toothcontact_version": __version__,
            "provenance": provenance or {},
            "units": "mm, N, MPa, rad unless the key says otherwise",
            "inputs": raw, **result.as_dict()}


def provenance_of(path: Path) -> dict:
    """When and from which case file (path and SHA-256 of its bytes) a run was made."""
    import datetime
    import hashlib

    return {"run_at_utc": datetime.datetime.now(datetime.UTC).isoformat(
                timespec="seconds"),
            "case_file": str(path), "case_sha256": hashlib.sha256(path.read_bytes()).hexdigest()}


def write_run(out_dir: Path, document: dict, images=()) -> list[Path]:
    """Write DIR/result.json, DIR/report.md, DIR/report.html and each long table's CSV
    (DIR/positions.csv, ...) atomically (temporary file, then rename). `images`: the PNGs of
    the run (plots and pictures, in DIR), linked from report.md and embedded in
    report.html."""
    out_dir = Path(out_dir)
    images = [Path(p) for p in images]
    texts = {"result.json": json_text(document),
             "report.md": markdown(document, [_relative(p, out_dir) for p in images]),
             "report.html": html(document, images),
             **{t.csv: csv_text(t) for t in view(document).tables if t.csv}}
    out_dir.mkdir(parents=True, exist_ok=True)
    return [write_text(out_dir / filename, text) for filename, text in texts.items()]


def csv_text(table) -> str:
    """A report table as CSV: its labelled headers (units in brackets), then its rows as the
    reports show them (four significant digits, round-off as 0)."""
    import csv
    import io

    buffer = io.StringIO()
    writer = csv.writer(buffer, lineterminator="\n")
    writer.writerow(table.headers)
    writer.writerows(table.rows)
    return buffer.getvalue()


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
    "pressure_peak.png": "Loaded contact at the position of the largest pressure",
    "mesh_cycle.png": "Over the mesh cycle: transmission error, stress, semi-axes, edge margin",
    "mesh_loads.png": "Over the mesh cycle: load sharing, mesh stiffness, transmission error "
                      "harmonics, the largest shear below each contact",
    "lubrication.png": "The lubricated contact over the mesh cycle: sliding and sum speeds, "
                       "specific film λ, flash temperature, power lost",
    "ease_off.png": "Ease-off of the flank",
    "k_chart.png": "K-chart: each member's profile and lead traces as made",
    "path_of_contact.png": "Flank pressure along the path of contact against ISO's σ_H",
    "crown_design.png": "Crown design chart",
    "worm_efficiency_temperature.png": "Worm-set efficiency against the lubricant temperature",
    "worm_efficiency_torque.png": "Worm-set efficiency against the output torque",
}


def caption(path) -> str:
    name = Path(path).name
    return CAPTIONS.get(name, Path(name).stem.replace("_", " "))


def json_text(document) -> str:
    """A document as strict JSON text (a number that does not apply is null)."""
    return json.dumps(_finite(document), indent=2, allow_nan=False) + "\n"


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
    """The report as Markdown (templates/report.md.j2; see report_view): key results,
    design checks, the pictures (`images`: paths relative to the report), the results
    tables, source and method checks, assumptions and the inputs as given."""
    pictures = [{"caption": caption(p), "path": Path(p).as_posix(), "name": Path(p).name}
                for p in images]
    text = _template("report.md.j2").render(v=view(document), images=pictures)
    return re.sub(r"\n{3,}", "\n\n", text)


def html(document: dict, images=()) -> str:
    """The report as one self-contained HTML page (templates/report.html.j2: inline style,
    an inline script that sorts the result tables by a clicked column, the PNGs `images`
    embedded as base64; nothing fetched)."""
    pictures = [{"caption": caption(p), "name": Path(p).name,
                 "data": base64.b64encode(Path(p).read_bytes()).decode("ascii")}
                for p in images]
    return _template("report.html.j2").render(v=view(document), images=pictures)


def write_sweep_report(out_dir: Path, stats: dict, images=()) -> Path:
    """A sweep's report as one self-contained HTML page (templates/sweep.html.j2, in the
    style of a case's report; report_view.sweep_view) with its figures embedded:
    OUT_DIR/report.html."""
    from .. import __version__
    from .report_view import sweep_view

    pictures = [{"name": Path(p).name,
                 "data": base64.b64encode(Path(p).read_bytes()).decode("ascii")}
                for p in images]
    text = _template("sweep.html.j2").render(v=sweep_view(stats, __version__),
                                              images=pictures)
    return write_text(Path(out_dir) / "report.html", text)


#: a table cell of a numeric column this long or shorter is a number with its unit, kept on
#: one line and aligned right; a longer one is text and wraps
NUMBER_CHARS = 24


def _template(name: str):
    import jinja2

    environment = jinja2.Environment(
        loader=jinja2.PackageLoader("toothcontact", "templates"),
        autoescape=jinja2.select_autoescape(["html.j2"]), trim_blocks=name.endswith("html.j2"),
        lstrip_blocks=True, keep_trailing_newline=True, undefined=jinja2.StrictUndefined)
    environment.filters["cell"] = lambda text: str(text).replace("|", "\\|").replace("\n", " ")
    environment.globals["NUMBER_CHARS"] = NUMBER_CHARS
    return environment.get_template(name)
