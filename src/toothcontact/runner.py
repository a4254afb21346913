"""Load a case, analyse it, write its outputs: the effects around the pure core."""

from __future__ import annotations

from pathlib import Path

from . import analyses, case as schema, report

_HERE = Path(__file__).resolve().parent


def bundled_cases_dir() -> Path:
    """The bundled case files: inside the installed package, or `cases/` of a source tree."""
    for candidate in (_HERE / "bundled_cases", _HERE.parents[1] / "cases"):
        if candidate.is_dir():
            return candidate
    raise FileNotFoundError("no bundled cases found next to the package")


def bundled_cases() -> list[Path]:
    return sorted(bundled_cases_dir().glob("*.toml"))


def analyse_file(path: str | Path) -> dict:
    """Load and analyse a case file; returns the result document (raises CaseError)."""
    path = Path(path)
    case, raw = schema.load_case(path)
    try:
        result = analyses.analyse(case)
    except schema.CaseError as exc:
        raise schema.CaseError(f"{path}: {exc}") from None
    return report.result_document(path.stem, case, raw, result)


def run_case(path: str | Path, out_dir: str | Path | None = None) -> tuple[dict, list[Path]]:
    """Analyse a case file and write result.json and report.md into `out_dir`
    (default out/<case name>/). Nothing is written when the case is bad."""
    path = Path(path)
    document = analyse_file(path)
    target = Path(out_dir) if out_dir is not None else Path("out") / path.stem
    return document, report.write_run(target, document)
