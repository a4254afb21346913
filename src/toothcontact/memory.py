"""Keep freed memory for reuse (glibc only; elsewhere nothing happens).

The ray solves allocate and free many arrays of a few hundred kilobytes to a few megabytes
per step. glibc serves such sizes with fresh mmap pages and returns them on free, so every
step pays the kernel to fault in and zero its pages again: about 35,000 page faults and a
third of the wall time of the crowned spur case's contact cycle. Raising the mmap and trim
thresholds keeps that memory in the heap for the next step (measured: cycle with its gap
fields 0.28 s -> 0.20 s). The command line and a sweep's samples set it (a process-wide
setting: importing the package leaves a host program's allocator alone).
"""

from __future__ import annotations

import ctypes
import ctypes.util

#: allocations below this come from the heap (bytes); larger ones still map their own pages
MMAP_THRESHOLD = 64 * 1024 * 1024
#: freed heap memory up to this much is kept rather than returned to the system (bytes)
TRIM_THRESHOLD = 512 * 1024 * 1024
_M_TRIM_THRESHOLD, _M_MMAP_THRESHOLD = -1, -3


def keep_freed_memory() -> bool:
    """Set glibc's mmap and trim thresholds; False where the C library is not glibc."""
    try:
        libc = ctypes.CDLL(ctypes.util.find_library("c") or "libc.so.6")
        mallopt = libc.mallopt
    except (OSError, AttributeError):
        return False
    return bool(mallopt(_M_MMAP_THRESHOLD, MMAP_THRESHOLD)) and bool(
        mallopt(_M_TRIM_THRESHOLD, TRIM_THRESHOLD))
