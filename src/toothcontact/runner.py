"""Load a case, analyse it, write its outputs: the effects around the pure core."""

from __future__ import annotations

import difflib
import logging
import math
import os
import time
import warnings
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from . import analyses, writing
from . import case as schema
from .extras import missing_extra
from .views import report

log = logging.getLogger(__name__)

_HERE = Path(__file__).resolve().parent


def bundled_cases_dir() -> Path:
    """The bundled case files: inside the installed package (bundled/cases, beside the
    bodies its imported cases read), or `cases/` of a source tree."""
    for candidate in (_HERE / "bundled" / "cases", _HERE.parents[1] / "cases"):
        if candidate.is_dir():
            return candidate
    raise FileNotFoundError("no bundled cases found next to the package")


def bundled_cases() -> list[Path]:
    return sorted(bundled_cases_dir().glob("*.toml"))


def bundled_sweeps() -> list[Path]:
    """The bundled sweep files (the cases folder's sweeps/)."""
    return sorted((bundled_cases_dir() / "sweeps").glob("*.toml"))


def sweep_path(name: str | Path) -> Path:
    """A sweep file: `name` as a path if it is one, else the bundled sweep of that name."""
    path = Path(name)
    if path.is_file():
        return path
    bundled = bundled_cases_dir() / "sweeps" / f"{path.stem}.toml"
    if path.parent == Path(".") and bundled.is_file():
        return bundled
    raise schema.CaseError(f"{name}: no such sweep file, and no bundled sweep of that name "
                           "(`toothcontact cases` lists them)")


def case_path(name: str | Path) -> Path:
    """A case file: `name` as a path if it is one, else the bundled case of that name (with
    or without .toml). Raises CaseError naming both places when neither exists."""
    path = Path(name)
    if path.is_file():
        return path
    bundled = bundled_cases_dir() / (path.name if path.suffix == ".toml" else f"{path.name}.toml")
    if path.parent == Path(".") and bundled.is_file():
        return bundled
    close = difflib.get_close_matches(path.stem, [p.stem for p in bundled_cases()], n=1)
    raise schema.CaseError(f"{name}: no such case file, and no bundled case of that name"
                           + (f"; did you mean {close[0]}?" if close else "")
                           + " (`toothcontact cases` lists them)")


def load_sweep(path: str | Path):
    """Read and validate a sweep file (sweep.spec): the spec, its base case's table (units
    as given; the base validated as a case) and the base case's path. The base is a path
    relative to the sweep file, or a bundled case's name."""
    from pydantic import ValidationError

    from .sweep.sampling import with_class_bands
    from .sweep.spec import SweepSpec

    path = Path(path)
    raw = schema.read_table(path)
    try:
        spec = SweepSpec.model_validate(raw)
    except ValidationError as exc:
        raise schema.CaseError(f"{path}: {schema.describe(exc, SweepSpec)}") from None
    relative = Path(os.path.normpath(path.parent / spec.base))
    try:
        base_path = relative if relative.is_file() else case_path(spec.base)
    except schema.CaseError:
        raise schema.CaseError(f"{path}: base: {schema.shown(spec.base)} is neither a case "
                               "file (relative to the sweep file) nor a bundled case's name "
                               "(`toothcontact cases` lists them)") from None
    if schema.read_table(base_path).get("kind") == "sweep":
        raise schema.CaseError(f"{path}: base: {schema.shown(spec.base)} is a sweep file; give "
                               "a case file or a bundled case's name (a sweep varies one case)")
    _, base = schema.load_case(base_path)
    return with_class_bands(spec, base, base_path.parent, source=str(path)), base, base_path



@dataclass
class Analysis:
    """A case file analysed: the validated case, its raw table (units as given), the
    analyses.Result (with the contact cycle for pictures) and the result document."""

    path: Path
    case: object
    raw: dict
    result: analyses.Result
    document: dict


def analyse_path(path: str | Path) -> Analysis:
    """Load and analyse a case file (raises CaseError, naming the file, on bad input)."""
    path = Path(path)
    case, raw = schema.load_case(path)
    start = time.perf_counter()
    try:
        result = analyses.analyse(case)
    except schema.CaseError as exc:
        raise schema.CaseError(f"{path}: {exc}") from None
    log.info("%s: %s analysis in %.2f s", path.name, case.kind, time.perf_counter() - start)
    return Analysis(path, case, raw, result, report.result_document(
        path.stem, case, raw, result, report.provenance_of(path)))


def analyse_file(path: str | Path) -> dict:
    """Load and analyse a case file; returns the result document (raises CaseError)."""
    return analyse_path(path).document


def analyse_record(path: str | Path):
    """Load and analyse a case file (or a bundled case's name); returns its typed record,
    records.CaseResult (raises CaseError)."""
    from .records import CaseResult

    return CaseResult.from_document(analyse_file(case_path(path)))


def _step(progress: Callable[[str], None] | None, what: str) -> None:
    log.info("%s", what)
    if progress is not None:
        progress(what)


def run_case(path: str | Path, out_dir: str | Path | None = None, pictures: bool = True,
             progress: Callable[[str], None] | None = None, command: str | None = None
             ) -> tuple[dict, list[Path]]:
    """Analyse a case file and write into `out_dir` (default out/<case name>/): result.json,
    report.md, report.html, the plots (views.plots.figures_for) and, with `pictures`, the 3D
    pictures (views.pictures.pictures_for). Nothing is written when the case is bad.

    The folder is all or nothing: everything is written into a staging folder beside it,
    which then replaces it (writing.staging_folder), so a reader sees the previous complete
    run or the new one. A stage that cannot answer (plots, pictures) says so in the
    document's `stages` and leaves the rest standing. `progress(stage)` is called before
    each stage; `command`: the command line that asked for it, for the traceability block."""
    path = case_path(path)
    _step(progress, "analysing")
    run = analyse_path(path)
    document = run.document
    if command:
        document["provenance"]["command"] = command
    target = Path(out_dir) if out_dir is not None else Path("out") / path.stem
    stages = document.setdefault("stages", {})
    with writing.staging_folder(target) as staging:
        _step(progress, "plotting")
        images = _stage(stages, "plots", lambda: _plots(document, staging))
        if not pictures:
            stages["pictures"] = {"status": "skipped", "reason": "--no-pictures"}
        elif not has_pictures(run.case):
            stages["pictures"] = {"status": "skipped", "reason": f"no 3D picture for a "
                                                                f"{run.case.kind} case"}
        else:
            _step(progress, "rendering")
            images += _stage(stages, "pictures", lambda: picture_files(run, staging))
        _step(progress, "writing the reports")
        written = report.write_run(staging, document, images) + images
    return document, [target / p.name for p in written]


def _plots(document: dict, folder: Path) -> list[Path]:
    from .views import plots

    return plots.figures_for(document, folder)


def _stage(stages: dict, name: str, action: Callable[[], list[Path]]) -> list[Path]:
    """Run an output stage; its failure (no OpenGL here, say) is recorded in
    stages[name] and the run goes on without its files."""
    start = time.perf_counter()
    try:
        with warnings.catch_warnings(record=True) as caught:   # the stage's, not stderr's
            warnings.simplefilter("always")
            files = action()
    except Exception as exc:  # noqa: BLE001 - the numbers stand without the pictures
        if os.environ.get("TOOTHCONTACT_DEBUG"):
            raise
        stages[name] = {"status": "failed",
                        "reason": missing_extra(exc) or f"{type(exc).__name__}: {exc}"}
        log.warning("the %s failed: %s", name, stages[name]["reason"])
        log.debug("the %s's failure", name, exc_info=True)
        return []
    stages[name] = {"status": "done", "files": [p.name for p in files]}
    told = sorted({f"{w.category.__name__}: {w.message}" for w in caught})
    if told:      # a library's remark on a drawing (an empty legend, say) stays with it
        stages[name]["warnings"] = told
        log.info("%s: %s", name, "; ".join(told))
    log.info("%s: %d files in %.2f s", name, len(files), time.perf_counter() - start)
    return files


def run_sweep(path: str | Path, out_dir: str | Path | None = None, *,
              scheduler: str | None = None, workers: int | None = None, resume: bool = False,
              positions: bool = False, planned: Callable[[int], None] | None = None,
              on_done: Callable[[dict], None] | None = None) -> tuple[dict, list[Path]]:
    """Run a sweep file (sweep.spec) into OUT_DIR (default out/<sweep>): every sample
    validated first, then analysed on Dask (sweep.run), checkpointed under OUT_DIR/parts;
    then OUT_DIR/samples.parquet (one row per sample), with `positions` also
    OUT_DIR/positions.parquet (each sample's rows per mesh position and pair), with an
    `[optimise]` table the optimisation (sweep.optimise: each design's sweep under
    OUT_DIR/optimise), OUT_DIR/sweep.json (the statistics, sweep.statistics), the figures
    and OUT_DIR/report.html. `planned(n)` hears the number of samples known so far,
    `on_done` each finished record. Returns the statistics and the files written."""
    import shutil

    from .sweep import run as sweep_run
    from .sweep import statistics, store
    from .sweep.optimise import check_statistics, designs, optimise
    from .sweep.sampling import plan

    path = sweep_path(path)
    spec, base, base_path = load_sweep(path)
    with sweep_run.Workers(scheduler, workers) as pool:
        pool.start()          # its workers spawn while the samples are planned and checked
        # a surrogate study plans its loaded samples as it goes; its draws are not cases
        samples = (plan(spec, base, base_path.parent, source=str(path))
                   if spec.method == "monte_carlo" else [])
        if spec.optimise is not None:          # the bounds' corners are cases too, checked now
            design_of = designs(spec.optimise, f"{path}: optimise")
            middle = (None if spec.method == "monte_carlo"       # a surrogate's: one draw
                      else np.full((1, len(spec.tolerance)), 0.5))
            for corner in (0.0, 1.0):
                plan(spec, base, base_path.parent, source=f"{path}: optimise",
                     design=design_of(np.full(len(spec.optimise.variables), corner)),
                     unit_cube=middle)
            # what the objective and constraints name, against the figures the base design
            # reports (one analysis, here, before any output is written)
            record, _ = sweep_run.sample_record(0, {}, schema.load_case(base_path)[0])
            if record["status"] == "ok":
                check_statistics(spec.optimise, record, f"{path}: optimise")
        total = [len(samples)]
        if planned is not None:
            planned(total[0])
        out = Path(out_dir) if out_dir is not None else Path("out") / path.stem
        inputs, grid = [t.field for t in spec.tolerance], [v.field for v in spec.axes]
        classes = {t.field: {"iso1328_class": t.iso1328_class, "tolerance": t.class_tolerance,
                             "distribution": t.distribution,
                             **({"mean": t.mean, "band": t.band} if t.distribution == "normal"
                                else {"low": t.low, "high": t.high})}
                   for t in spec.tolerance if t.iso1328_class is not None}

        def sweep_into(todo, folder, keep_positions):
            rows = sweep_run.run(todo, folder, pool, resume=resume,
                                 positions=keep_positions, on_done=on_done)
            return rows, statistics.summarise(rows, inputs, grid, spec.sampling == "saltelli")

        def evaluate(design, folder, point=None):
            designed = plan(spec, base, base_path.parent, source=f"{path}: optimise",
                            design=design)
            total[0] += len(designed)
            if planned is not None:
                planned(total[0])
            rows, summary = sweep_into(designed, folder, False)
            store.write_table(folder / "samples.parquet", rows)
            return summary, rows

        if spec.method == "surrogate":
            rows, summary = _surrogate_sweep(spec, base, base_path.parent, str(path), pool,
                                             out, positions, resume, on_done, planned)
        else:
            rows, summary = sweep_into(samples, out, positions)
        stats = {"sweep": str(path), "title": spec.title or path.stem, "base": str(base_path),
                 "seed": spec.seed, "sampling": spec.sampling if inputs else "none (a grid)",
                 "method": spec.method, "inputs": inputs, "grid": grid,
                 **({"tolerance_classes": classes} if classes else {}),
                 **({"spectrum": spec.spectrum.model_dump()} if spec.spectrum else {}),
                 **summary}
        if spec.optimise is not None and spec.method == "monte_carlo":
            if not resume:
                shutil.rmtree(out / "optimise", ignore_errors=True)
            stats["optimise"] = optimise(spec.optimise, evaluate, out / "optimise",
                                         where=f"{path}: optimise")
        pool.release()
        written = [store.write_table(out / "samples.parquet", rows)]
        if positions:
            written.append(store.write_table(out / "positions.parquet", store.position_rows(
                out, [r["sample"] for r in rows])))
        written.append(writing.write_text(out / "sweep.json", report.json_text(stats)))
        from .views import sweep_plots

        figures = sweep_plots.sweep_figures(rows, stats, out)
        written += figures + [report.write_sweep_report(out, stats, figures)]
    return stats, written


def _surrogate_sweep(spec, base: dict, folder: Path, source: str, pool, out: Path,
                     positions: bool, resume: bool, on_done, planned) -> tuple[list, dict]:
    """A surrogate study (sweep.surrogate): its loaded samples analysed round by round on
    `pool` into `out` (checkpointed as a Monte Carlo's are), then the sweep's own draws,
    the statistics and the Sobol indices taken on the surrogate. With an [optimise] table
    the design variables are inputs of the surrogate too (uniform over their bounds): the
    optimisation runs on it, the statistics are the best design's, and that design is
    checked by loaded samples into `out`/optimum (surrogate.recheck). The loaded samples'
    records and the statistics, with the surrogate's errors (`surrogate`)."""
    from .contact.edge_loads import END_LOAD_RATIO
    from .sweep import run as sweep_run
    from .sweep import statistics, surrogate
    from .sweep.optimise import design_key, designs, optimise
    from .sweep.sampling import plan, unit_draws
    from .sweep.spec import Surrogate

    settings = spec.surrogate or Surrogate()
    figures = list(settings.figures or surrogate.DEFAULT_FIGURES)
    inputs, grid = [t.field for t in spec.tolerance], [v.field for v in spec.axes]
    variables = [v.field for v in spec.optimise.variables] if spec.optimise else []
    design_of = designs(spec.optimise, f"{source}: optimise") if variables else None
    surrogate.check_figures(figures, spec.optimise, f"{source}: optimise")
    d = len(inputs)

    def planned_at(u, first: int, design: dict | None = None) -> list:
        """The samples at the unit-cube points u (tolerances, then design variables unless
        `design` is given), at every grid point, numbered from `first`."""
        if not variables or design is not None:
            return plan(spec, base, folder, source=f"{source}: surrogate",
                        unit_cube=u[:, :d], first=first, design=design)
        todo: list = []
        for row in u:
            todo += plan(spec, base, folder, source=f"{source}: surrogate",
                         unit_cube=row[None, :d], first=first + len(todo),
                         design=design_of(row[d:]))
        return todo

    analysed: list = []

    def analyse_points(u, first: int) -> list[dict]:
        analysed.extend(planned_at(u, first))
        if planned is not None:
            planned(len(analysed))
        rows = sweep_run.run(analysed, out, pool, resume=resume or first > 0,
                             positions=positions, on_done=on_done)
        return [r for r in rows if r["sample"] >= first]

    found = surrogate.study(analyse_points, d + len(variables), grid, figures, settings,
                            spec.seed, {"max_end_load_ratio": END_LOAD_RATIO})
    shares = None
    if spec.spectrum is not None:       # a level's share: a first-round sample's × its count
        shares = {tuple(r.get(f"input:{g}") for g in grid): r["time_share"] * settings.initial
                  for r in found.records if r["sample"] < settings.initial * len(found.fits)}
    draws = unit_draws(spec)

    def on_surrogate(point=None) -> tuple[dict, list[dict]]:
        """The statistics of the sweep's draws on the surrogate (at a design `point`)."""
        cube = draws if point is None else np.hstack([draws, np.tile(point, (len(draws), 1))])
        records = surrogate.draws_on(found, cube, inputs + variables, grid, shares,
                                     END_LOAD_RATIO)
        return statistics.summarise(records, inputs, grid), records

    best_point = None
    if variables:
        points: dict[str, np.ndarray] = {}

        def evaluate(design: dict, _folder: Path, point: np.ndarray):
            points[design_key(design)] = point
            return on_surrogate(point)

        optimum = optimise(spec.optimise, evaluate, out / "optimise",
                           where=f"{source}: optimise")
        design = optimum["best"]["design"]
        best_point = points[design_key(design)]
        summary, records = on_surrogate(best_point)
        optimum["recheck"] = surrogate.recheck(
            found, lambda u, first: sweep_run.run(planned_at(u, first, design), out / "optimum",
                                                  pool, resume=resume, on_done=on_done),
            best_point, grid, settings, spec.seed)
        summary["optimise"] = optimum
    else:
        summary, records = on_surrogate()
    loaded = statistics.summarise(found.records, inputs, grid)
    summary.update(samples=loaded["samples"], ok=loaded["ok"], failed=loaded["failed"],
                   failures=loaded["failures"], surrogate_draws=len(records),
                   surrogate=surrogate.summary(found, settings, figures))
    if d >= 2:
        summary["sobol"] = surrogate.sobol_on(found, inputs, spec.seed, best_point)
    return found.records, summary


def has_pictures(case) -> bool:
    """Whether a case gets 3D pictures: spur, spline and worm cases (with a load, the
    contact pattern; without, the pair in mesh)."""
    from .views.scene_style import PICTURE_KINDS

    return case.kind in PICTURE_KINDS


def picture_files(run: Analysis, out_dir: Path, position: int | None = None,
                  exaggerate: float = 1.0) -> list[Path]:
    from .views import pictures

    return pictures.pictures_for(run.result, run.case, out_dir, name=run.path.stem,
                                 position=position, exaggerate=exaggerate)


def render_case(path: str | Path, out_dir: str | Path | None = None, position: int | None = None,
                exaggerate: float = 1.0,
                progress: Callable[[str], None] | None = None) -> list[Path]:
    """Analyse a case and write its 3D pictures into `out_dir` (default viz/<case name>/);
    [] without analysing for a kind that has none (analytic kinds, imported meshes)."""
    path = case_path(path)
    case, _ = schema.load_case(path)
    if not has_pictures(case):
        return []
    if exaggerate <= 0 or not math.isfinite(exaggerate):
        raise schema.CaseError(f"--exaggerate: {exaggerate:g} must be a positive number")
    _step(progress, "analysing")
    run = analyse_path(path)
    target = Path(out_dir) if out_dir is not None else Path("viz") / path.stem
    _step(progress, "rendering")
    return picture_files(run, target, position, exaggerate)


def export_case(path: str | Path, out_dir: str | Path | None = None,
                formats: tuple[str, ...] = ("step", "stl")) -> dict:
    """Build the parts of a case as B-spline solids and write them as STEP and/or STL into
    `out_dir` (default geometry/<case>/), with export.json: for each part its flank
    deviation from the exact surface, validity, volume, STEP round trip and STL check."""
    import json

    from . import cad
    from .writing import write_text

    path = case_path(path)
    case, _ = schema.load_case(path)
    if case.kind not in schema.SOLID_KINDS:
        raise schema.CaseError(f"{path}: kind: {case.kind!r} has no solid to export; "
                               f"export works for {', '.join(schema.SOLID_KINDS)}")
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
