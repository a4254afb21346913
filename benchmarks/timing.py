"""Wall-clock timing shared by the peer benchmarks (each runs in its own environment, so
this is a plain module beside them, not part of the package)."""

from __future__ import annotations

import math
import time


def timed(fn, repeat: int = 1):
    """(best wall time over `repeat` calls (s), the last call's result)."""
    best, result = math.inf, None
    for _ in range(repeat):
        t0 = time.perf_counter()
        result = fn()
        best = min(best, time.perf_counter() - t0)
    return best, result
