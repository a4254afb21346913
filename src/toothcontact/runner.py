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


from .cad.parts import SOLID_KINDS as GEOMETRY_KINDS  # noqa: E402 - OCP loads lazily


def export_case(path: str | Path, out_dir: str | Path | None = None,
                formats: tuple[str, ...] = ("step", "stl")) -> dict:
    """Build the parts of a case as B-spline solids and write them as STEP and/or STL into
    `out_dir` (default geometry/<case>/), with export.json: for each part its flank
    deviation from the exact surface, validity, volume, STEP round trip and STL check."""
    import json

    from . import cad
    from .report import write_text

    path = Path(path)
    case, _ = schema.load_case(path)
    if case.kind not in GEOMETRY_KINDS:
        raise schema.CaseError(f"{path}: kind: {case.kind!r} has no solid to export; "
                               f"export works for {', '.join(GEOMETRY_KINDS)}")
    try:
        bodies = cad.build_parts(case)
    except ValueError as exc:
        raise schema.CaseError(f"{path}: {exc}") from None
    target = Path(out_dir) if out_dir is not None else Path("geometry") / path.stem
    target.mkdir(parents=True, exist_ok=True)
    record = {"case": path.stem, "parts": {}}
    for name, body in bodies.items():
        entry = {"built": body.description, "valid": cad.is_valid(body.solid),
                 "volume_mm3": cad.volume(body.solid),
                 "flank_deviation_um": 1000.0 * body.flank_deviation(),
                 "notes": getattr(body, "notes", [])}
        if "step" in formats:
            step = cad.write_step(body.solid, target / f"{name}.step")
            entry["step"] = step.name
            entry["step_reread_volume_mm3"] = cad.volume(cad.read_step(step))
        if "stl" in formats:
            mesh = cad.tessellate(body.solid, case.export.stl_tolerance)
            stl = cad.write_mesh(mesh, target / f"{name}.stl")
            entry.update(stl=stl.name, stl_triangles=len(mesh.faces),
                         stl_watertight=bool(mesh.is_watertight),
                         stl_tolerance_mm=case.export.stl_tolerance)
        record["parts"][name] = entry
    write_text(target / "export.json", json.dumps(record, indent=2) + "\n")
    return record
