"""A sweep's samples analysed on Dask (dask.distributed): a LocalCluster sized to the
machine by default, or an existing cluster at a scheduler address (Workers); one task per
sample, retried where a worker dies. Each finished sample is checkpointed at once (sweep.store), so
a killed sweep resumed skips what is done; the table is ordered by sample number, the same
whatever the workers and the order they finish in."""

from __future__ import annotations

import contextlib
import logging
import math
import subprocess
import sys
import threading
import time
from collections.abc import Callable
from pathlib import Path

from ..case import CaseInfo
from . import store
from .sampling import Sample

#: tries of a sample whose worker died under it (a sample that fails by itself is recorded
#: with its error and not tried again)
RETRIES = 2


def sample_record(number: int, inputs: dict, case: CaseInfo, positions: bool = False
                  ) -> tuple[dict, list[dict]]:
    """One sample's case, as the sweep parsed it when planning (a worker neither parses
    nor imports the units' library), analysed on a worker (its positions one after the
    other on the worker's thread: a Dask worker's process may not fork, and threads gain
    nothing, see toothcontact.parallel): its record, `sample`, each varied input (the
    case's value in core units, or its text), `status` ("ok" or the error) and the
    summary's figures (the case's `summary` under its own names; numbers, flags and
    texts; no positions check, the stresses below the contacts only where the case's
    `[analysis] subsurface` is true, the rigid patterns only where its `rigid_patterns`
    is or the rows are kept, the ease-off only where its `ease_off` is); and, if
    `positions`, the result's rows per mesh position and pair (their table cells, with
    `sample`), else []."""
    from ..analyses import analyse
    from ..memory import keep_freed_memory
    from ..parallel import workers

    keep_freed_memory()
    record: dict = {"sample": number}
    rows: list[dict] = []
    try:
        for field in inputs:
            record[f"input:{field}"] = _value(case, field)
        if getattr(case, "analysis", None) is not None:
            # the positions' convergence is the base design's question: a sample skips it,
            # the stresses below the contacts and the ease-off (a map no table holds) unless
            # the case asks for them, and the rigid patterns (row keys only) unless its rows
            # are kept
            analysis = case.analysis
            patterns = positions if analysis.rigid_patterns is None else analysis.rigid_patterns
            case = case.model_copy(update={"analysis": analysis.model_copy(update={
                "positions_check": False, "subsurface": analysis.subsurface or False,
                "rigid_patterns": patterns, "ease_off": bool(analysis.ease_off)})})
        with workers(1):
            sections = analyse(case).sections
        record.update(_cells(sections.get("summary", {})))
        if positions:
            rows = [{"sample": number, **_cells(row)} for row in sections.get("positions", [])]
        record["status"] = "ok"
    except Exception as exc:        # noqa: BLE001 - a failed sample is recorded, the rest go on
        record["status"] = f"{type(exc).__name__}: {exc}"
    return record, rows


def _cells(entries: dict) -> dict:
    """The entries a table can hold (see _cell)."""
    return {key: _cell(value) for key, value in entries.items() if _cell(value) is not None}


def _value(case, field: str):
    """The parsed case's value at a dotted field (a float in core units where it is one)."""
    node = case
    for name in field.split("."):
        node = getattr(node, name, None)
    return _cell(node)


def _cell(value):
    """A table cell: a finite float, a flag or a text; None for what a table cannot hold."""
    if isinstance(value, bool):
        return value
    if isinstance(value, (int, float)):
        return float(value) if math.isfinite(value) else None
    if isinstance(value, str):
        return value
    return None


class Workers:
    """Where samples run: an existing Dask scheduler at `scheduler`, else a LocalCluster of
    `workers` processes (the machine's cores) started at `start` or its first use and
    closed with this (a context manager); one cluster serves every sweep an optimisation
    runs. A sample takes one worker's thread."""

    def __init__(self, scheduler: str | None = None, workers: int | None = None):
        self.scheduler, self.workers = scheduler, workers
        self._cluster = self._client = None
        self._failure: Exception | None = None
        self._starting: threading.Thread | None = None
        self._closing: threading.Thread | None = None

    def start(self) -> None:
        """Start the local cluster in the background (its workers spawn while the sweep
        plans and checks its samples: 0.8 s less on two cores); `client` waits for it. A
        scheduler's address is connected to when the client is first asked for."""
        if self.scheduler is None and self._client is None and self._starting is None:
            self._starting = threading.Thread(target=self._connect, name="starting Dask",
                                              daemon=True)
            self._starting.start()

    def _connect(self) -> None:
        """The client, on a new local cluster or at the scheduler (an error is kept for
        `client` to raise)."""
        from distributed import Client, LocalCluster

        from ..parallel import machine_cores

        try:
            if self.scheduler is None:
                # errors only: a worker slow to stop at the end ("still alive after 4.0
                # seconds, killing") is Dask's housekeeping, not the user's business
                self._cluster = LocalCluster(n_workers=self.workers or machine_cores(),
                                             threads_per_worker=1, processes=True,
                                             dashboard_address=":0",
                                             silence_logs=logging.ERROR)
            self._client = Client(self.scheduler or self._cluster)
        except Exception as exc:        # noqa: BLE001 - raised where the client is asked for
            self._failure = exc

    def _started(self) -> None:
        """Wait for a start under way."""
        if self._starting is not None:
            self._starting.join()
            self._starting = None

    @property
    def client(self):
        self._started()
        if self._client is None and self._failure is None:
            self._connect()
        if self._failure is not None:
            raise self._failure
        return self._client

    def __enter__(self) -> Workers:
        return self

    def release(self) -> None:
        """Close the client and the local cluster in the background (the sweep's tables
        and figures are written meanwhile: half a second less); leaving the context waits
        for it."""
        if self._closing is None and (self._client or self._cluster) is not None:
            self._closing = threading.Thread(target=self._close, name="closing Dask")
            self._closing.start()

    def _close(self) -> None:
        if self._client is not None:
            self._client.close()
        if self._cluster is not None:
            self._cluster.close()
        self._client = self._cluster = None

    def __exit__(self, *exc) -> None:
        self._started()
        if self._closing is not None:
            self._closing.join()
            self._closing = None
        self._close()


def run(samples: list[Sample], out: Path, workers: Workers, *,
        resume: bool = False, positions: bool = False,
        on_done: Callable[[dict], None] | None = None) -> list[dict]:
    """Analyse on `workers` the samples not yet done in `out` (all of them unless
    `resume`) and return every sample's record, ordered by sample, with its `time_share`
    under a load spectrum (with `positions`, each sample's rows per position are
    checkpointed too: store.position_rows)."""
    from distributed import as_completed

    done = store.finished(out, positions) if resume else store.clear(out)
    todo = [s for s in samples if s.sample not in done]
    if todo:
        shares = {s.sample: s.time_share for s in todo}
        futures = workers.client.map(
            sample_record, [s.sample for s in todo], [s.inputs for s in todo],
            [s.case for s in todo], [positions] * len(todo), retries=RETRIES,
            pure=False)
        for future in as_completed(futures):
            record, rows = future.result()
            if shares[record["sample"]] is not None:
                record["time_share"] = shares[record["sample"]]
            store.write_part(out, record, rows if positions else None)
            if on_done is not None:
                on_done(record)
    return store.records(out, [s.sample for s in samples])


@contextlib.contextmanager
def separate_processes(folder: Path, workers: int = 2):
    """A Dask scheduler and `workers` one-thread workers started as separate processes on
    this machine (`dask scheduler`, `dask worker --no-nanny`), as a deployment runs them:
    yields the scheduler's address and the worker processes (to kill one, say); all are
    killed on exit. `folder` holds the scheduler file."""
    from distributed import Client

    def dask(command: str) -> list[str]:
        """`dask COMMAND` run as its module by this interpreter (no `dask` script needed
        beside it: packages installed with --target have none)."""
        return [sys.executable, "-m", f"distributed.cli.dask_{command}"]

    address = Path(folder) / "scheduler.json"
    quiet = {"stdout": subprocess.DEVNULL, "stderr": subprocess.DEVNULL}
    scheduler = subprocess.Popen([*dask("scheduler"), "--scheduler-file", str(address),
                                  "--port", "0", "--no-dashboard"], **quiet)
    started = []
    try:
        for _ in range(300):
            if address.is_file():
                break
            if scheduler.poll() is not None:
                raise RuntimeError(f"the Dask scheduler exited ({scheduler.returncode}) "
                                   f"before writing {address}")
            time.sleep(0.1)
        started = [subprocess.Popen([*dask("worker"), "--scheduler-file", str(address),
                                     "--nthreads", "1", "--no-nanny", "--no-dashboard"],
                                    **quiet) for _ in range(workers)]
        with Client(scheduler_file=str(address)) as client:
            client.wait_for_workers(workers, timeout=60)
            where = client.scheduler.address
        yield where, started
    finally:
        for process in [*started, scheduler]:
            process.kill()
            process.wait(timeout=30)
