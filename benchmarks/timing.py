"""Wall-clock timing shared by the benchmarks (each runs in its own environment, so this
is a plain module beside them, not part of the package): the best of repeated calls, and a
commit checked out beside this one to time in the same run."""

from __future__ import annotations

import math
import os
import subprocess
import tempfile
import time
from contextlib import contextmanager
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent


def source_path(source: Path) -> dict:
    """The environment with `source`'s `src` first on PYTHONPATH (what the caller's
    PYTHONPATH names, carried packages say, after it)."""
    paths = [str(source / "src"), *filter(None, [os.environ.get("PYTHONPATH")])]
    return {**os.environ, "PYTHONPATH": os.pathsep.join(paths)}


def timed(fn, repeat: int = 1):
    """(best wall time over `repeat` calls (s), the last call's result)."""
    best, result = math.inf, None
    for _ in range(repeat):
        t0 = time.perf_counter()
        result = fn()
        best = min(best, time.perf_counter() - t0)
    return best, result


@contextmanager
def checked_out(revision: str):
    """The repository at `revision`, checked out with `git worktree` into a temporary
    folder for the block (its path; removed after); a `revision` that names a folder is
    that tree as it is (a machine without the repository's history: the old tree copied
    there)."""
    if Path(revision).is_dir():
        yield Path(revision).resolve()
        return
    with tempfile.TemporaryDirectory() as folder:
        old = Path(folder) / "old"
        subprocess.run(["git", "worktree", "add", "--detach", str(old), revision],
                       cwd=ROOT, check=True, capture_output=True)
        try:
            yield old
        finally:
            subprocess.run(["git", "worktree", "remove", "--force", str(old)], cwd=ROOT,
                           check=True, capture_output=True)
