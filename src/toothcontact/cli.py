"""The `toothcontact` console script. Light imports only: the analysis loads on demand."""

from __future__ import annotations

import os
from pathlib import Path
from typing import Optional

import typer

app = typer.Typer(add_completion=False, no_args_is_help=True,
                  help="Tooth-contact analysis of gears under misalignment and deflection.")


def _fail(message: str, code: int) -> None:
    typer.echo(f"error: {message}", err=True)
    raise typer.Exit(code)


def _guarded(action):
    """Run `action`; bad input becomes one line and exit 2, never a traceback."""
    from .case import CaseError

    try:
        return action()
    except CaseError as exc:
        _fail(str(exc), 2)
    except Exception as exc:  # noqa: BLE001 - the promise is: no traceback for users
        if os.environ.get("TOOTHCONTACT_DEBUG"):
            raise
        _fail(f"internal error: {type(exc).__name__}: {exc} "
              "(set TOOTHCONTACT_DEBUG=1 to see the traceback)", 3)


@app.command()
def run(case: Path = typer.Argument(..., help="case file (TOML)"),
        out: Optional[Path] = typer.Option(None, "--out", help="output folder [out/<case>]")):
    """Analyse CASE: writes result.json and report.md."""
    from . import runner

    document, written = _guarded(lambda: runner.run_case(case, out))
    failed = [c for c in document["checks"] if not c["ok"]]
    typer.echo(f"{case.stem}: wrote {', '.join(str(p) for p in written)}")
    for check in failed:
        typer.echo(f"  check failed: {check['name']}: {check['detail']}")


@app.command()
def export(cases: list[Path] = typer.Argument(..., help="case files (TOML)"),
           fmt: str = typer.Option("both", "--format", help="step, stl or both"),
           out: Optional[Path] = typer.Option(None, "--out", help="output folder [geometry/]")):
    """Write the parts of each case as STEP/STL (B-spline solids of the exact flanks)."""
    from . import runner

    formats = {"step": ("step",), "stl": ("stl",), "both": ("step", "stl")}.get(fmt)
    if formats is None:
        _fail(f"--format: {fmt!r} is not one of step, stl, both", 2)
    for case in cases:
        target = (out or Path("geometry")) / case.stem
        record = _guarded(lambda: runner.export_case(case, target, formats))
        for name, part in record["parts"].items():
            typer.echo(f"{case.stem}/{name}: {part['built']}, flank deviation "
                       f"{part['flank_deviation_um']:.3f} µm, valid {part['valid']} -> {target}")


@app.command()
def cases():
    """List the bundled cases."""
    from . import case as schema, runner

    for path in _guarded(runner.bundled_cases):
        info, _ = _guarded(lambda: schema.load_case(path))
        typer.echo(f"{path.stem:32s} {info.kind:16s} {info.title}")


@app.command()
def demo(out: Path = typer.Option(Path("out"), "--out", help="output folder")):
    """Run every bundled case into OUT/<case>/."""
    from rich.console import Console
    from rich.table import Table

    from . import runner

    table = Table("case", "kind", "checks", "STEP/STL", title=f"bundled cases -> {out}/<case>/")
    for path in _guarded(runner.bundled_cases):
        document, _ = _guarded(lambda: runner.run_case(path, out / path.stem))
        failed = sum(not c["ok"] for c in document["checks"])
        solids = ""
        if document["kind"] in runner.GEOMETRY_KINDS:
            record = _guarded(lambda: runner.export_case(path, out / path.stem))
            solids = ", ".join(f"{n} {p['flank_deviation_um']:.2f} µm" for n, p in record["parts"].items())
        table.add_row(path.stem, document["kind"],
                      f"{len(document['checks']) - failed} pass, {failed} flagged", solids)
    Console(width=100).print(table)
