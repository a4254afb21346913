"""Independent tasks on the machine's cores: worker processes forked for the call where the
platform and the process allow it, else one after the other in this thread; BLAS on one
thread either way.

Why processes: a loaded cycle's positions are many small transforms, sparse products and
numpy operations, and the Python between them holds the GIL. Two forked processes solved
the bundled spur case's positions 1.55 times faster than one (each runs some 15 % slower
beside the other). A forked worker inherits what the task reads (the cycle, its fields,
the tooth model): only the task's answer is pickled back.

Why not threads where no process can be forked: they gain nothing. Analyses with their
positions on two threads against one, in a process that may not fork (as a Dask worker's),
on two cores: the bundled spur case 3.86-4.34 s against 3.42-4.30 s, using 5.6-5.9 s of
CPU against 3.4-4.3 s; the helical case 5.42-6.76 s against 5.91-6.37 s (8.0-9.8 s of
CPU against 5.9-6.4 s); the worm set slower on two (2.22-2.44 s against 1.99-2.01 s).

Why BLAS on one thread: OpenBLAS's threads spin after each call and take the core from the
other workers. Two analyses of the bundled spur case run side by side took 1.6 to 2.6
times as long as one alone; with BLAS on one thread, as long as one alone (the matrices
here are small). Between the parallel maps too, a context of `workers(n)` keeps BLAS on at
most n threads: one sweep sample on one core otherwise used 1.09 cores of two (OpenBLAS's
second thread, for no gain in wall time).

Forking is safe only where no other thread can hold a lock the child needs. Processes are
therefore used only where:
- the platform is Linux (macOS's system libraries are not safe to fork, which is why its
  default start method is spawn; Windows does not fork);
- this process is not a daemon (a Dask worker's process may have no children);
- no other Python thread runs (a progress display's refresh thread, a Dask client).
Elsewhere the tasks run in order, in this thread.
"""

from __future__ import annotations

import multiprocessing
import os
import sys
import threading
from collections.abc import Callable
from concurrent.futures import ProcessPoolExecutor
from contextlib import contextmanager
from contextvars import ContextVar

from threadpoolctl import threadpool_info, threadpool_limits

#: the workers `parallel_map` uses in this context: None for the machine's cores
_WORKERS: ContextVar[int | None] = ContextVar("workers", default=None)


@contextmanager
def workers(count: int):
    """Run every `parallel_map` in this context on `count` workers, and BLAS on at most
    `count` threads between them (1: in order, in this thread, as a sweep's sample runs).
    BLAS's limit is the process's, not the context's: a process runs one sample at a
    time."""
    if not (isinstance(count, int) and count >= 1):
        raise ValueError(f"count: {count!r} must be an integer >= 1 (workers)")
    token = _WORKERS.set(count)
    try:
        with threadpool_limits(min(count, _blas_threads() or count), "blas"):
            yield
    finally:
        _WORKERS.reset(token)


def _blas_threads() -> int | None:
    """The most threads a loaded BLAS library runs on now (None: none loaded)."""
    return max((pool["num_threads"] for pool in threadpool_info() if pool["user_api"] == "blas"),
               default=None)


def machine_cores() -> int:
    """The cores this process may run on."""
    return len(os.sched_getaffinity(0)) if hasattr(os, "sched_getaffinity") else os.cpu_count() or 1


def can_fork() -> bool:
    """Whether worker processes may be forked here (see the module)."""
    return (sys.platform.startswith("linux")
            and not multiprocessing.current_process().daemon
            and threading.active_count() == 1)


def parallel_map(task: Callable[[int], object], count: int,
                 done: Callable[[int], None] | None = None) -> list:
    """[task(0), ..., task(count - 1)], on the context's workers (see `workers`; at most
    `count`): forked processes where `can_fork`, else in order in this thread (see the
    module). The answers come back in order and are the same whatever the workers; an
    exception a task raises is raised here. `done(i)` is called here, in this thread, as
    each answer comes back in order."""
    n = min(_WORKERS.get() or machine_cores(), count)
    with threadpool_limits(1, "blas"):
        processes = _forked_pool(n, task) if n > 1 and can_fork() else None
        if processes is None:
            return _collected((task(i) for i in range(count)), done)
        with processes:
            return _collected(processes.map(_run, range(count)), done)


def _collected(answers, done: Callable[[int], None] | None) -> list:
    """The answers as a list, `done(i)` told as answer i comes."""
    out = []
    for i, answer in enumerate(answers):
        out.append(answer)
        if done is not None:
            done(i)
    return out


def _forked_pool(n: int, task: Callable[[int], object]) -> ProcessPoolExecutor | None:
    """n forked workers that run `task`, or None where the pool cannot be made (no working
    semaphores: a container without /dev/shm)."""
    try:
        return ProcessPoolExecutor(n, mp_context=multiprocessing.get_context("fork"),
                                   initializer=_adopt, initargs=(task,))
    except (OSError, NotImplementedError):
        return None


#: a forked worker's task (set in the worker by `_adopt`, never in the parent)
_TASK: Callable[[int], object] | None = None


def _adopt(task: Callable[[int], object]) -> None:
    """A forked worker's start: the task it runs (inherited, not pickled), BLAS on one
    thread."""
    global _TASK
    _TASK = task
    threadpool_limits(1, "blas")


def _run(index: int):
    return _TASK(index)
