"""A one-line note on a terminal while compiled kernels are built for the first time.

Numba compiles a model's kernels on their first use after installation and caches them (the
ring models about a minute each, on a 2-core machine); later runs load them in about a second.
A user at a terminal would otherwise see nothing during that minute. The note is written to
``stderr`` only when it is a terminal and only if the work takes longer than ``after_s``, so a
cached start, a pipe, a captured test run or a library call in a notebook stays silent.
"""

from __future__ import annotations

import sys
import threading
from collections.abc import Iterator
from contextlib import contextmanager

__all__ = ["compile_notice"]


@contextmanager
def compile_notice(what: str, after_s: float = 2.0) -> Iterator[None]:
    """Say ``bearingsim: compiling <what> ...`` on a terminal's stderr if the block takes longer
    than ``after_s`` [s] (a cold Numba compile)."""
    err = sys.stderr
    try:
        tty = err is not None and err.isatty()
    except (AttributeError, ValueError):  # a closed or replaced stream
        tty = False
    if not tty:
        yield
        return

    def say() -> None:
        try:
            print(
                f"bearingsim: compiling {what} (once after installation; about a minute) ...",
                file=err,
                flush=True,
            )
        except (OSError, ValueError):
            pass

    timer = threading.Timer(after_s, say)
    timer.daemon = True
    timer.start()
    try:
        yield
    finally:
        timer.cancel()
