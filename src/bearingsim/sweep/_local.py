"""Worker plugin of the local cluster of ``sweep run`` (imports Dask: loaded with the cluster)."""

from __future__ import annotations

import signal
import threading

from distributed.diagnostics.plugin import WorkerPlugin

__all__ = ["IgnoreSigint"]


class IgnoreSigint(WorkerPlugin):
    """Ctrl-C in a terminal signals the whole process group, the local cluster's worker
    processes included: each would print a traceback of its ``KeyboardInterrupt``. The client
    handles Ctrl-C alone (it stops the tasks and closes the cluster), so the workers ignore
    ``SIGINT``; being a plugin, this holds for workers restarted by their nanny too."""

    name = "bearingsim-ignore-sigint"
    idempotent = True

    def setup(self, worker) -> None:  # noqa: ARG002 (the plugin interface)
        if threading.current_thread() is threading.main_thread():
            signal.signal(signal.SIGINT, signal.SIG_IGN)
