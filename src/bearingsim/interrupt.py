"""Ctrl-C held while a step that must not be cut runs: :func:`held_interrupt`.

Two places cannot take a ``KeyboardInterrupt`` in the middle: a compiled (Numba ``nogil``)
kernel, where it is raised inside the boxing of the returned arrays (CPython's "returned a
result with an exception set"; a rotor run with slip crashed with a segmentation fault,
fifteenth session), and a netCDF write, where h5py's weak-reference callbacks swallow it
("Exception ignored in ...") and the file was written as if no Ctrl-C had come (twenty-first
session). Within :func:`held_interrupt` a SIGINT is only noted; once the block is done it is
handed to the handler in place before (Python's default raises ``KeyboardInterrupt``; an
ignored SIGINT stays ignored).
"""

from __future__ import annotations

import contextlib
import signal
import threading
from collections.abc import Iterator

__all__ = ["held_interrupt"]


@contextlib.contextmanager
def held_interrupt() -> Iterator[None]:
    """Hold SIGINT while the block runs (main thread only; elsewhere, and where signals are not
    available, the block runs as it is) and deliver it after (module docstring). A block that
    raises keeps its own exception."""
    if threading.current_thread() is not threading.main_thread():
        yield
        return
    got: list[int] = []
    try:
        old = signal.signal(signal.SIGINT, lambda signum, frame: got.append(signum))
    except (ValueError, OSError):  # signals not available here
        yield
        return
    try:
        yield
    finally:
        signal.signal(signal.SIGINT, old)
    if got:
        if callable(old):  # Python's default raises KeyboardInterrupt; a custom one decides
            old(signal.SIGINT, None)
        elif old == signal.SIG_DFL:
            raise KeyboardInterrupt
