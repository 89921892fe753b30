"""The timing helper the benchmarks share (a module beside them: each benchmark is run as a
script, whose folder is on ``sys.path``)."""

from __future__ import annotations

import time
from collections.abc import Callable


def best(fn: Callable[[], object], repeats: int = 5, *, warm: bool = True) -> float:
    """Shortest wall time of ``repeats`` calls of ``fn`` [s], after one untimed call when
    ``warm`` (compiled kernels loaded, caches filled)."""
    if warm:
        fn()
    times = []
    for _ in range(repeats):
        t0 = time.perf_counter()
        fn()
        times.append(time.perf_counter() - t0)
    return min(times)
