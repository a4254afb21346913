"""The `toothcontact` console script. Light imports only: the analysis loads on demand."""

from __future__ import annotations

import os
import shlex
from pathlib import Path

import typer

app = typer.Typer(add_completion=False, no_args_is_help=True, rich_markup_mode=None,
                  help="Tooth-contact analysis of gears under misalignment and deflection.")


#: exit codes: 0 done, every design check passed; 1 done, a design check failed (the results
#: are complete); 2 input refused (one line names the field); 3 a bug in toothcontact
EXIT_CHECK_FAILED, EXIT_BAD_INPUT, EXIT_BUG, EXIT_INCOMPLETE = 1, 2, 3, 4


def _fail(message: str, code: int) -> None:
    typer.echo(f"error: {message}", err=True)
    raise typer.Exit(code)


def _say(text: str) -> None:
    """A line of the command's account on stdout, unless --quiet (which sets the package's
    log to errors only, see _logging)."""
    import logging

    if logging.getLogger("toothcontact").isEnabledFor(logging.WARNING):
        typer.echo(text)


#: the log levels of the package's loggers by -v count: warnings, the stages and their
#: times (-v), every step (-vv: a failed stage's traceback among them)
LOG_LEVELS = ("WARNING", "INFO", "DEBUG")


def _logging(verbose: int, quiet: bool) -> None:
    """The package's log (logger "toothcontact") on stderr at the level -v/-q ask for;
    other libraries' loggers are left as they are."""
    import logging

    logger = logging.getLogger("toothcontact")
    logger.setLevel("ERROR" if quiet else LOG_LEVELS[min(verbose, len(LOG_LEVELS) - 1)])
    for old in [h for h in logger.handlers if getattr(h, "toothcontact_cli", False)]:
        logger.removeHandler(old)        # a command run before in this process
    handler = logging.StreamHandler()    # today's stderr
    handler.toothcontact_cli = True
    handler.setFormatter(logging.Formatter("%(levelname)s %(name)s: %(message)s"))
    logger.addHandler(handler)


def _guarded(action):
    """Run `action`; bad input, or a task whose extra is not installed, becomes one line
    and exit 2, never a traceback."""
    from .case import CaseError
    from .extras import missing_extra

    try:
        return action()
    except CaseError as exc:
        _fail(str(exc), EXIT_BAD_INPUT)
    except Exception as exc:  # noqa: BLE001 - the promise is: no traceback for users
        if missing_extra(exc) is not None:
            _fail(missing_extra(exc), EXIT_BAD_INPUT)
        if os.environ.get("TOOTHCONTACT_DEBUG"):
            raise
        _fail(f"internal error: {type(exc).__name__}: {exc} (a bug in toothcontact: please "
              "report it with the case file; TOOTHCONTACT_DEBUG=1 shows the traceback)",
              EXIT_BUG)


class _Progress:
    """A rich progress display on stderr for work that takes more than a moment; silent
    when stderr is not a terminal (pipes, logs, tests). Redrawn at each stage and step,
    with no refresh thread of its own: another thread would keep an analysis from forking
    its workers (toothcontact.parallel)."""

    def __init__(self, total: int | None, label: str):
        from rich.console import Console
        from rich.progress import (
            BarColumn,
            MofNCompleteColumn,
            Progress,
            SpinnerColumn,
            TextColumn,
            TimeElapsedColumn,
            TimeRemainingColumn,
        )

        console = Console(stderr=True)
        columns = [SpinnerColumn(), TextColumn("{task.description}")]
        if total is not None:
            columns += [BarColumn(), MofNCompleteColumn(), TimeRemainingColumn()]
        self._progress = Progress(*columns, TimeElapsedColumn(), console=console,
                                  transient=True, auto_refresh=False,
                                  disable=not console.is_terminal)
        self._task = self._progress.add_task(label, total=total)
        self._label = label

    def __enter__(self):
        self._progress.__enter__()
        return self

    def __exit__(self, *exc):
        return self._progress.__exit__(*exc)

    def stage(self, what: str) -> None:
        self._progress.update(self._task, description=f"{self._label}: {what}", refresh=True)

    def advance(self) -> None:
        self._progress.update(self._task, advance=1, refresh=True)

    def total(self, total: int) -> None:
        """The amount of work, once it is known."""
        self._progress.update(self._task, total=total, refresh=True)


def _wrote(written) -> str:
    return ", ".join(p.name for p in written)


def _version(value: bool) -> None:
    if value:
        from . import __version__

        typer.echo(f"toothcontact {__version__}")
        raise typer.Exit(0)


@app.callback()
def main(version: bool = typer.Option(False, "--version", callback=_version, is_eager=True,
                                      help="print the version and exit"),
         verbose: int = typer.Option(0, "--verbose", "-v", count=True,
                                     help="log the stages and their times to stderr (-vv: "
                                          "every step)"),
         quiet: bool = typer.Option(False, "--quiet", "-q",
                                    help="print errors only; the exit code tells the rest")):
    """Tooth-contact analysis of gears under misalignment and deflection."""
    from .memory import keep_freed_memory

    _logging(verbose, quiet)
    keep_freed_memory()


@app.command()
def run(case: Path = typer.Argument(..., help="case file (TOML), or the name of a bundled "
                                               "case (see `toothcontact cases`)"),
        out: Path | None = typer.Option(None, "--out", help="output folder [out/<case>]"),
        pictures: bool = typer.Option(True, "--pictures/--no-pictures",
                                      help="render the 3D pictures (spur, spline, worm)")):
    """Analyse CASE: writes result.json, report.md, report.html, plots and pictures.

    Exit 0: done; 1: done, but a design check failed; 2: the input was refused; 3: a bug;
    4: done, but a solver could not answer some contacts (the results are incomplete)."""
    from . import runner

    with _Progress(None, case.stem) as progress:
        command = shlex.join(["toothcontact", "run", str(case)]
                             + (["--out", str(out)] if out is not None else [])
                             + ([] if pictures else ["--no-pictures"]))
        document, written = _guarded(lambda: runner.run_case(case, out, pictures, progress.stage,
                                                             command))
    failed = [c for c in document["checks"] if not c["ok"] and c["kind"] == "design"]
    folder = written[0].parent if written else out
    _say(f"{case.stem}: wrote {_wrote(written)} -> {folder}")
    for name, stage in document.get("stages", {}).items():
        if stage["status"] == "failed":
            _say(f"  warning: the {name} could not be made here: {stage['reason']}")
    for check in failed:
        _say(f"  check failed: {check['name']}: {check['detail']}")
    unanswered = [c for c in document["checks"] if not c["ok"] and c["kind"] == "solver"]
    for check in unanswered:
        _say(f"  incomplete: {check['name']}: {check['detail']}")
    for check in document["checks"]:   # the rigid pattern's margins: in the report only
        if not check["ok"] and check["kind"] not in ("design", "solver", "rigid"):
            _say(f"  note ({check['kind']}): {check['name']}: {check['detail']}")
    if unanswered:
        raise typer.Exit(EXIT_INCOMPLETE)
    if failed:
        raise typer.Exit(EXIT_CHECK_FAILED)


@app.command()
def sweep(file: Path = typer.Argument(..., help="sweep file (TOML, kind = \"sweep\") or a "
                                                  "bundled sweep's name"),
          out: Path | None = typer.Option(None, "--out", help="output folder [out/<sweep>]"),
          scheduler: str | None = typer.Option(
              None, "--scheduler", help="an existing Dask scheduler, e.g. tcp://HOST:8786 "
                                        "[a local cluster]"),
          workers: int | None = typer.Option(None, "--workers", min=1,
                                                help="local workers [the machine's cores]"),
          resume: bool = typer.Option(False, "--resume",
                                      help="skip the samples an earlier run of OUT finished"),
          positions: bool = typer.Option(False, "--positions",
                                         help="also positions.parquet: every sample's rows "
                                              "per mesh position and pair")):
    """Run a sweep file on Dask: writes samples.parquet, sweep.json and figures.

    Every sample is validated first, then analysed and checkpointed as it finishes; the
    table has a row per sample, sweep.json the percentiles, the edge-loading probability
    and the sensitivities. Exit 0: done (failed samples are recorded in the table); 1: done,
    but an optimisation found no design that met its constraints; 2: the sweep was
    refused."""
    from . import runner

    failures = []
    with _Progress(0, file.stem) as progress:
        def planned(total):
            progress.total(total)

        def done(record):
            if record["status"] != "ok":
                failures.append(record["sample"])
            progress.stage(f"{len(failures)} failed" if failures else "running")
            progress.advance()

        stats, written = _guarded(lambda: runner.run_sweep(
            file, out, scheduler=scheduler, workers=workers, resume=resume,
            positions=positions, planned=planned, on_done=done))
    _say(f"{file.stem}: {stats['samples']} samples, {stats['ok']} answered, "
         f"{stats['failed']} failed; wrote {_wrote(written)} -> {written[0].parent}")
    best = (stats.get("optimise") or {}).get("best")
    if best is not None and not best["feasible"]:
        _say(f"  no design met the constraints: the best tried, {best['design']}, "
             "breaks one (see the report's optimisation table)")
        raise typer.Exit(EXIT_CHECK_FAILED)


@app.command()
def render(cases: list[Path] = typer.Argument(..., help="case files (TOML)"),
           out: Path | None = typer.Option(None, "--out",
                                              help="output folder; the pictures go to OUT/<case>/ [viz]"),
           position: int | None = typer.Option(None, "--position",
                                                  help="mesh position of the pair picture "
                                                       "(0 = first roll angle) [nearest roll 0]"),
           exaggerate: float = typer.Option(1.0, "--exaggerate",
                                            help="show the misalignment N times larger")):
    """Render each case's 3D pictures off-screen (PNG) into OUT/<case>/.

    The contact pattern on the flank (head-on and in perspective), the pair in mesh and
    the loaded pressure; a case without a load gets the pair in mesh."""
    from . import runner

    with _Progress(len(cases) if len(cases) > 1 else None, "rendering") as progress:
        for case in cases:
            target = (out or Path("viz")) / case.stem
            progress.stage(case.stem)
            written = _guarded(lambda case=case, target=target: runner.render_case(
                case, target, position, exaggerate,
                lambda what: progress.stage(f"{case.stem}: {what}")))
            if written:
                _say(f"{case.stem}: wrote {_wrote(written)} -> {target}")
            else:
                _say(f"{case.stem}: no 3D picture for this kind of case "
                     "(its plots come with `toothcontact run`)")
            progress.advance()


@app.command()
def export(cases: list[Path] = typer.Argument(..., help="case files (TOML)"),
           fmt: str = typer.Option("both", "--format", help="step, stl or both"),
           out: Path | None = typer.Option(None, "--out", help="output folder [geometry/]")):
    """Write the parts of each case as STEP/STL (B-spline solids of the exact flanks)."""
    from . import runner

    formats = {"step": ("step",), "stl": ("stl",), "both": ("step", "stl")}.get(fmt)
    if formats is None:
        _fail(f"--format: {fmt!r} is not one of step, stl, both", EXIT_BAD_INPUT)
    for case in cases:
        target = (out or Path("geometry")) / case.stem
        record = _guarded(lambda case=case, target=target: runner.export_case(case, target,
                                                                            formats))
        for name, part in record["parts"].items():
            _say(f"{case.stem}/{name}: {part['built']}, flank deviation "
                 f"{part['flank_deviation_um']:.3f} µm, valid {part['valid']} -> {target}")


@app.command()
def cases():
    """List the bundled cases and sweeps."""
    from rich.console import Console
    from rich.table import Table

    from . import case as schema
    from . import runner
    from .sweep.sampling import plan

    console = Console(width=200)
    listings = []
    rows = []
    for path in _guarded(runner.bundled_cases):
        info, _ = _guarded(lambda path=path: schema.load_case(path))
        rows.append((path.stem, info.kind, info.title, str(path)))
    listings.append((("name", "kind", "title", "path"), rows,
                     "bundled cases (run one with `toothcontact run NAME`)"))
    rows = []
    for path in _guarded(runner.bundled_sweeps):
        spec, raw, base = _guarded(lambda path=path: runner.load_sweep(path))
        samples = _guarded(lambda spec=spec, raw=raw, base=base: plan(spec, raw, base.parent))
        rows.append((path.stem, str(len(samples)),
                     spec.title or "", str(path)))
    listings.append((("name", "samples", "title", "path"), rows,
                     "bundled sweeps (run one with `toothcontact sweep NAME`)"))
    if not console.is_terminal:        # piped or captured: one tab-separated line per entry
        for _, rows, _ in listings:
            for row in rows:
                typer.echo("\t".join(row))
        return
    for headers, rows, title in listings:
        table = Table(*headers, title=title)
        for row in rows:
            table.add_row(*row)
        console.print(table)


@app.command()
def schema(kind: str = typer.Argument(..., help="a case kind, e.g. spur")):
    """Print the JSON schema of a case kind (for an editor's completion and checks).

    Save it beside your cases, e.g. `toothcontact schema spur > spur.schema.json`, and
    point your editor's TOML support at it (Taplo / Even Better TOML: a `#:schema
    spur.schema.json` first line)."""
    import json

    from .case import KINDS

    if kind not in KINDS:
        _fail(f"kind: {kind!r} is not a known kind; allowed: {', '.join(KINDS)}",
              EXIT_BAD_INPUT)
    typer.echo(json.dumps(KINDS[kind].model_json_schema(), indent=2))


@app.command()
def demo(out: Path = typer.Option(Path("out"), "--out", help="output folder")):
    """Run every bundled case into OUT/<case>/: results, reports, plots, pictures, solids
    (those an extra not installed here would make are listed as such)."""
    from rich.console import Console
    from rich.table import Table

    from . import parallel, runner

    table = Table(title=f"bundled cases -> {out}/<case>/", caption=DEMO_CAPTION,
                  caption_justify="left")
    table.add_column("case", no_wrap=True)
    for header in ("kind", "design checks", "files written", "solids: flank deviation"):
        table.add_column(header)
    paths = _guarded(runner.bundled_cases)
    cores = parallel.machine_cores()
    # cases side by side in forked workers, each on its share of the cores (one at a time
    # where no process can be forked)
    at_once = min(DEMO_CASES_AT_ONCE, cores) if parallel.can_fork() else 1

    def row(i: int):
        with parallel.workers(max(1, cores // at_once)):
            try:
                return _demo_row(paths[i], out)
            except typer.Exit as exc:        # its message is printed: the code comes back
                return exc.exit_code

    with _Progress(len(paths), "demo") as progress:
        progress.stage(f"{len(paths)} cases, {at_once} at a time")
        with parallel.workers(at_once):
            rows = _guarded(lambda: parallel.parallel_map(
                row, len(paths), done=lambda i: progress.advance()))
    for found in rows:
        if isinstance(found, int):
            raise typer.Exit(found)
        table.add_row(*found)
    widest = max((len(p.stem) for p in paths), default=0)
    Console(width=max(110, widest + 90)).print(table)


#: bundled cases `demo` runs side by side at most (each with its share of the cores)
DEMO_CASES_AT_ONCE = 4


def _demo_row(path: Path, out: Path) -> tuple[str, str, str, str, str]:
    """One bundled case run into out/<case>/ and its solids exported: its row of the demo's
    table (case, kind, design checks, files written, solids' flank deviations)."""
    from . import runner
    from .case import SOLID_KINDS
    from .extras import installed

    cad = installed("cad")
    if not cad and path.stem.startswith("imported_"):
        return path.stem, "imported", "", "", "needs the cad extra (STEP input)"
    document, written = _guarded(lambda: runner.run_case(path, out / path.stem))
    design = [c for c in document["checks"] if c["kind"] == "design"]
    failed = sum(not c["ok"] for c in design)
    checks = (f"all {len(design)} pass" if design and not failed else
              f"{failed} of {len(design)} flagged" if design else "none")
    solids = ""
    if document["kind"] in SOLID_KINDS and not cad:
        solids = "needs the cad extra"
    elif document["kind"] in SOLID_KINDS:
        record = _guarded(lambda: runner.export_case(path, out / path.stem))
        solids = ", ".join(
            f"{n} {p['flank_deviation_um']:.2f} µm"
            + (" (above 1 µm)" if p["flank_deviation_um"] > EXPORT_DEVIATION_UM else "")
            for n, p in record["parts"].items())
    pngs = sum(p.suffix == ".png" for p in written)
    return (path.stem, case_kind(document), checks,
            f"{len(written) - pngs} documents, {pngs} PNG", solids)


#: an exported solid's flank strays more than this (µm) from the exact flank: flagged
EXPORT_DEVIATION_UM = 1.0
#: what the demo table's columns mean
DEMO_CAPTION = (
    "kind: the pair as built (spur, helical, ring, spline, worm, ...); design checks: the "
    "report's design checks (edge and end loading, ratings, limits), the method and solver "
    "checks apart; files written: the result and its reports beside the plots and "
    "pictures; solids: each exported STEP part's largest distance from its exact flank "
    "(flagged above 1 µm).")


def case_kind(document: dict) -> str:
    """What a case is, in a gear engineer's words: helical or spur, ring (an internal gear
    pair), spline, worm, or the case kind itself."""
    kind = document["kind"]
    if kind != "spur":
        return kind.replace("_", " ")
    helix = (document.get("pinion") or {}).get("base_helix_angle_deg") or 0.0
    ring = bool((document.get("gear") or {}).get("internal"))
    return ("helical" if abs(helix) > 1e-9 else "spur") + (" ring" if ring else "")
