"""Writing results: result.json, report.md and report.html (self-contained: the pictures
embedded as base64), each written whole or not at all."""

from __future__ import annotations

import base64
import contextlib
import json
import math
import os
import re
import shutil
import tempfile
from pathlib import Path

from . import __version__
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

    return {"run_at_utc": datetime.datetime.now(datetime.timezone.utc).isoformat(
                timespec="seconds"),
            "case_file": str(path), "case_sha256": hashlib.sha256(path.read_bytes()).hexdigest()}


def write_run(out_dir: Path, document: dict, images=()) -> list[Path]:
    """Write DIR/result.json, DIR/report.md and DIR/report.html atomically (temporary file,
    then rename). `images`: the PNGs of the run (plots and pictures, in DIR), linked from
    report.md and embedded in report.html."""
    out_dir = Path(out_dir)
    images = [Path(p) for p in images]
    texts = {"result.json": json_text(document),
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
    no script, the PNGs `images` embedded as base64)."""
    pictures = [{"caption": caption(p), "name": Path(p).name,
                 "data": base64.b64encode(Path(p).read_bytes()).decode("ascii")}
                for p in images]
    return _template("report.html.j2").render(v=view(document), images=pictures)


def write_sweep_report(out_dir: Path, stats: dict, images=()) -> Path:
    """A sweep's report as one self-contained HTML page (templates/sweep.html.j2, in the
    style of a case's report; report_view.sweep_view) with its figures embedded:
    OUT_DIR/report.html."""
    from . import __version__
    from .report_view import sweep_view

    pictures = [{"name": Path(p).name,
                 "data": base64.b64encode(Path(p).read_bytes()).decode("ascii")}
                for p in images]
    text = _template("sweep.html.j2").render(v=sweep_view(stats, __version__),
                                              images=pictures)
    return write_text(Path(out_dir) / "report.html", text)


def _template(name: str):
    import jinja2

    environment = jinja2.Environment(
        loader=jinja2.PackageLoader("toothcontact", "templates"),
        autoescape=jinja2.select_autoescape(["html.j2"]), trim_blocks=name.endswith("html.j2"),
        lstrip_blocks=True, keep_trailing_newline=True, undefined=jinja2.StrictUndefined)
    environment.filters["cell"] = lambda text: str(text).replace("|", "\\|").replace("\n", " ")
    return environment.get_template(name)
