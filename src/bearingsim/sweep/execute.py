"""Parameter sweeps on Dask: a local cluster by default, a cluster by address, resumable.

:func:`run_sweep` executes the runs of a :class:`~bearingsim.sweep_spec.SweepSpec` (which
:func:`~bearingsim.sweep_plan.plan_sweep`, also importable from here, counts and estimates),
each run being ``bearingsim.simulate(scenario_i)`` — exactly the single-run API, so a sweep
result equals the same scenario run on its own, bit for bit (the nominal ``time`` coordinate
``k/fs`` differs from the integrator's accumulated time by < 1e-16 s).

Execution
---------
The client (this process) validates every run's scenario, connects to Dask — a
:class:`distributed.LocalCluster` of *process* workers with one thread each by default (the
Numba kernels hold the GIL, so threads would serialise), or an existing scheduler by address —
and imports the compiled kernels on every worker. A few probe runs (two samples each) on the
workers give the channels, units and shapes; the client then creates the Zarr dataset
(:mod:`bearingsim.sweep_store`), or checks that an existing one was created by the same spec
(same :attr:`SweepSpec.spec_hash`, otherwise refused unless ``force_new``), and submits only the
runs whose commit marker is missing (plus the failed ones with ``retry_failed``).

Runs travel in Dask tasks of one or more runs. With ``runs_per_task=None`` (automatic) the task
size follows the run time: before the first task, a timing probe on a worker per model
(:func:`~bearingsim.sweep_plan.timing_probe`: a two-sample run and one of at most
``TIMING_PROBE_S`` simulated, extrapolated in ``duration_s``) estimates it; the run times measured
in the finished tasks replace the estimate. Tasks hold ~``TARGET_TASK_S`` of runs, so Dask's
~5-7 ms of CPU per task (client, scheduler and worker together) stays below 1 %. With several
threads the sizes come in batches of one task per thread, each an equal share of the runs left
(factoring), so a short sweep needs one task per thread. When the probe fails (the run raises;
the sweep records its error), every thread first gets a one-run timing task and a two-run task at
once instead. The client places each task on the worker
with the fewest tasks in flight (loose restrictions: a task whose worker is gone goes to another;
the scheduler itself sees all tasks as equally long). When a worker runs out of tasks while
another task still has at least ``MIN_HELP_S`` of runs left, the client hands the second half of
them to a *helper* task on that worker: a claim file (:func:`~bearingsim.sweep_store.write_claim`)
tells the running task to stop before them, and the helper runs them in reverse, skipping
committed runs, so that the two meet at most at one run. At most two tasks per worker thread are
in flight; the client submits the next one as each finishes, which keeps memory bounded for any
number of runs. Each run is committed on its own as soon as it finishes: by the worker when it
sees the dataset directory (same machine or a shared file system; checked with the dataset's
uuid) — in the worker's commit thread, while the next run computes (the compiled integrators
release the GIL, so the write overlaps the computation when a core is free; at most one commit is
outstanding and a task returns only after its commits) — otherwise its arrays are sent back and
the client commits them (no helpers then). A run that raises is committed as *failed* with
``"ErrorType: message"`` and the sweep goes on. A worker that dies loses at most its running run
and the one being committed: Dask reruns the task elsewhere and the runs
already committed by it are skipped; a task lost more than
``distributed.scheduler.allowed-failures`` times is recorded as failed (``KilledWorker``).
Killing the client loses nothing committed (claim files left behind are removed when the dataset
is opened again); running the same command again resumes. On Ctrl-C the client writes a stop
claim for every running task (a task reads its claim before each run), so the workers stop after
their current run: the local cluster's workers ignore ``SIGINT`` (a terminal sends it to the
whole process group) and end when the cluster is closed; workers of another cluster outlive the
client, which waits for their running runs to be committed (a second Ctrl-C leaves them). One
client at a time writes a dataset (:mod:`bearingsim.sweep.lock`; a new dataset is created with its
creator's lock inside, so a second client started at once gets the one-line "in use" error).
The counts of :class:`SweepReport` are read from the dataset at the end, after the local cluster
is closed, so they include runs committed by tasks that never reported (their worker was killed,
or Ctrl-C came first).

The local cluster leaves ``MALLOC_TRIM_THRESHOLD_`` unset in its workers (Dask's nanny sets it to
65536 by default, which turns off glibc's dynamic mmap threshold: every run's arrays then come
from freshly mapped pages, which made ``simulate`` ~13 % slower here).
"""

from __future__ import annotations

import asyncio
import concurrent.futures
import contextlib
import enum
import json
import logging
import math
import os
import re
import shutil
import socket
import sys
import threading
import time
import uuid as uuidlib
import warnings
from collections import deque
from collections.abc import Callable, Iterator
from dataclasses import asdict, dataclass, field
from pathlib import Path
from typing import Any

import numpy as np

from .._version import __version__
from ..config import Scenario
from ..errors import BearingsimError, ConfigError, check_range, collect_warnings
from ..geometry import parse_enum
from ..io.jsonable import to_jsonable
from .lock import ClientLock, remove_stale_creations
from .plan import (
    SweepPlan,
    coordinates,
    first_valid,
    make_layout,
    plan_sweep,
    probe_first,
    probe_groups,
)
from .spec import SweepSpec, canonical_hash, spec_differences
from .store import (
    FAILED,
    OK,
    PENDING,
    DatasetExistsError,
    RunWriter,
    claim_path,
    create_dataset,
    lost_runs,
    read_attrs,
    read_claim,
    read_metadata,
    read_records,
    read_status,
    records_offsets,
    remove_stale_temporaries,
    signal_chunk,
    write_claim,
)

#: automatic task size: aim at this much compute per task [s]
TARGET_TASK_S = 1.0
#: tasks in flight per worker thread
INFLIGHT_PER_THREAD = 2
#: longest simulated time of the timing probe that estimates the run time before the first
#: task [s]
TIMING_PROBE_S = 0.1
#: without an estimate (the probe failed): runs of each thread's second task, submitted together
#: with its one-run timing task, so that the worker has its next task while the client waits for
#: the first run time [-]
SECOND_TASK_RUNS = 2
#: a helper task takes over half of a running task's remaining runs only when that half holds at
#: least this much compute [s]: about what a helper costs (a Dask task, ~5-7 ms of CPU, and
#: ~5-9 ms from the end of the finished task to the helper's start, measured on 2 cores)
MIN_HELP_S = 0.010
#: scheduler connection timeout [s]
CONNECT_TIMEOUT_S = 20.0
#: Dask settings of the local cluster, all diagnostics for a dashboard nobody looks at: no
#: statistical profiler (it samples the running thread every 10 ms), a 1 s event-loop tick
#: instead of 20 ms, system monitoring every 5 s instead of 0.5 s; and the memory monitor of the
#: workers and nannies every 0.5 s instead of 0.1 s (it still pauses, spills or restarts a worker
#: near its memory limit, within 0.5 s: a sweep task holds a few runs' arrays at a time). Together
#: they cut the idle cluster's CPU use from ~30 to ~15 ms per second (client with scheduler and
#: nannies ~15 -> 8, each worker ~7 -> 3.5) and the overhead of ``benchmarks/bench_sweep.py``.
#: Not a diagnostic: ``MALLOC_TRIM_THRESHOLD_`` unset in the workers (see the module docstring).
LOCAL_CLUSTER_CONFIG = {
    "distributed.worker.profile.enabled": False,
    "distributed.admin.tick.interval": "1s",
    "distributed.admin.system-monitor.interval": "5s",
    "distributed.worker.memory.monitor-interval": "500ms",
    "distributed.nanny.pre-spawn-environ.MALLOC_TRIM_THRESHOLD_": None,
}
_ADDRESS = re.compile(r"^((tcp|tls|ws|wss|ucx)://)?[A-Za-z0-9_.\-\[\]:]+:\d{1,5}$")


class Writer(enum.Enum):
    """Who commits a run's arrays to the dataset."""

    #: the workers, when they can open the dataset (a shared file system); else the client
    AUTO = "auto"
    #: always the client (workers send the arrays back)
    CLIENT = "client"


class LostDataWarning(UserWarning):
    """Runs committed ok had lost their signal chunk; the sweep computes them again."""


class SweepInterrupted(BearingsimError):
    """The sweep was interrupted (Ctrl-C); committed runs are kept (``report`` has counts)."""

    def __init__(self, message: str, report: SweepReport) -> None:
        super().__init__(message)
        self.report = report
        #: tasks still running on workers that outlive the client (they may commit one run)
        self.left_running = 0


# ------------------------------------------------------------------------------ worker side
#: per worker process: (dataset path, uuid) -> (RunWriter, or None when the dataset is not
#: visible or not writable from here, time of the last attempt)
_WRITERS: dict[tuple[str, str], tuple[RunWriter | None, float]] = {}
#: a worker that could not open the dataset tries again after this long [s] (a shared file
#: system may show a new directory late)
RETRY_OPEN_S = 10.0


def _writer_for(path: str, uuid: str) -> RunWriter | None:
    key = (path, uuid)
    w, t = _WRITERS.get(key, (None, -math.inf))
    if w is None and time.monotonic() - t > RETRY_OPEN_S:
        try:
            w = RunWriter(path, uuid)
        except (OSError, ValueError, KeyError):
            w = None
        _WRITERS[key] = (w, time.monotonic())
    return w


def _writer_failed(path: str, uuid: str) -> None:
    """Stop committing from this process (e.g. the dataset is read-only here)."""
    w, _ = _WRITERS.get((path, uuid), (None, 0.0))
    if w is not None:
        w.close()
    _WRITERS[(path, uuid)] = (None, time.monotonic())


def worker_hello() -> dict[str, Any]:
    """Run on each worker before the sweep: loads the compiled kernels (a two-sample run of
    every registered model), reports identity."""
    import numcodecs  # noqa: F401  (the commit path's imports, outside the timed runs)
    import zarr  # noqa: F401

    from ..simulation import MODELS, simulate

    for model in MODELS:
        with contextlib.suppress(BearingsimError):
            simulate(Scenario(model=model, duration_s=2.0 / 4000.0, fs_hz=4000.0))
    cores = len(os.sched_getaffinity(0)) if hasattr(os, "sched_getaffinity") else os.cpu_count()
    return {
        "version": __version__,
        "host": socket.gethostname(),
        "pid": os.getpid(),
        "cores": cores or 1,
    }


def spare_core_workers(hello: dict[str, dict[str, Any]], nthreads: dict[str, int]) -> set[str]:
    """Workers whose host has more cores than worker threads (``hello`` from
    :func:`worker_hello`, ``nthreads`` by address): there a run's commit can overlap the next
    run on a free core; elsewhere it would only compete with the computing runs."""
    per_host: dict[str, int] = {}
    for a, v in hello.items():
        per_host[v["host"]] = per_host.get(v["host"], 0) + int(nthreads.get(a, 1))
    return {a for a, v in hello.items() if per_host[v["host"]] < int(v.get("cores", 1))}


def _error_text(exc: BaseException) -> str:
    from .plan import sweep_text

    return f"{type(exc).__name__}: {sweep_text(' '.join(str(exc).split()))}"


_COMMIT_POOL: concurrent.futures.ThreadPoolExecutor | None = None
_COMMIT_POOL_LOCK = threading.Lock()


def _commit_pool() -> concurrent.futures.ThreadPoolExecutor:
    """This process's single commit thread (created on first use)."""
    global _COMMIT_POOL
    with _COMMIT_POOL_LOCK:
        if _COMMIT_POOL is None:
            _COMMIT_POOL = concurrent.futures.ThreadPoolExecutor(1, "bearingsim-commit")
        return _COMMIT_POOL


class _Inline:
    """Executor-like: runs the call at once and returns its outcome as a done future (the
    commit without overlap, handled like an overlapped one)."""

    @staticmethod
    def submit(fn: Callable[..., Any], *args: Any, **kw: Any) -> concurrent.futures.Future:
        fut: concurrent.futures.Future = concurrent.futures.Future()
        try:
            fut.set_result(fn(*args, **kw))
        except Exception as exc:
            fut.set_exception(exc)
        return fut


_INLINE = _Inline()


def _timed_commit(writer: RunWriter, *args: Any, rerun: bool) -> float:
    t = time.perf_counter()
    writer.commit(*args, rerun=rerun)
    return time.perf_counter() - t


def run_task(task: dict[str, Any]) -> list[dict[str, Any]]:
    """Execute a group of runs on a worker and commit each one (see the module docstring).

    With ``overlap_commit`` (the client sets it where the host has a core to spare, see
    :func:`spare_core_workers`) run ``k`` is committed by the process's commit thread while run
    ``k + 1`` computes (the compiled integrators release the GIL); at most one commit is
    outstanding, and all are finished before the task returns, so the task's result reports only
    committed runs. Otherwise each run is committed before the next one starts.

    ``task``: ``dataset`` (absolute path), ``uuid``, ``version``, ``channels`` (names or
    ``None`` = all), ``writer`` (``"auto"`` | ``"client"``), ``retry_failed`` (bool), ``runs``
    (list of (run, scenario dict)), optionally ``id`` (the name of its claim file) and
    ``allow_overload`` (the sweep's, :attr:`~bearingsim.sweep.spec.SweepSpec.allow_overload`;
    default false). Returns one
    record per run: ``run``, ``status`` (1 ok, 2 failed, ``"skipped"`` when already committed,
    ``"handed"`` when left to a helper task), ``compute_s``, ``error``, ``commit_s``, and when
    the client must commit: ``record`` and ``channels``.
    """
    import time as _t

    from ..simulation import simulate

    writer = None if task["writer"] == "client" else _writer_for(task["dataset"], task["uuid"])
    host, pid = socket.gethostname(), os.getpid()
    version_error = (
        ""
        if task["version"] == __version__
        else f"ConfigError: worker {host}:{pid} runs bearingsim {__version__}, the client "
        f"{task['version']}; install the same version on every worker"
    )
    claim = claim_path(task["dataset"], task["id"]) if task.get("id") else None
    overlap = bool(task.get("overlap_commit", False))
    keep: int | None = None  # runs[keep:] were handed to a helper task
    names = task["channels"]
    retry = task["retry_failed"]
    allow = bool(task.get("allow_overload", False))
    out: list[dict[str, Any]] = []
    runs = task["runs"]
    # the previous run's commit in flight: (future, its result record, record, channels)
    pending: tuple[Any, dict[str, Any], dict[str, Any], Any] | None = None

    def settle() -> None:
        """Wait for the outstanding commit; if it could not write, the client commits it."""
        nonlocal writer, pending
        if pending is None:
            return
        fut, r, record, chans = pending
        pending = None
        try:
            r["commit_s"] = fut.result()
        except OSError:  # not writable from here after all: the client commits
            _writer_failed(task["dataset"], task["uuid"])
            writer = None
            r["record"] = to_jsonable(record)
            r["channels"] = chans

    for k, (i, sd) in enumerate(runs):
        if writer is not None:
            if claim is not None:  # a claim can only move the end earlier (a helper, a stop)
                c = read_claim(claim)
                keep = c if keep is None or (c is not None and c < keep) else keep
            if keep is not None and k >= keep:
                out.extend({"run": j, "status": "handed"} for j, _ in runs[k:])
                break
            st = writer.status_of(i)
            if st == OK or (st == FAILED and not retry):
                out.append({"run": i, "status": "skipped"})  # done before (a rerun, a helper)
                continue
        t0 = _t.perf_counter()
        c0 = _t.thread_time()
        res, err = None, version_error
        caught: list[str] = []
        if not err:
            try:  # the run's warnings go into its record, not onto the worker's stderr
                with collect_warnings() as caught:
                    res = simulate(Scenario.from_dict(sd, origin=f"run {i}"),
                                   allow_overload=allow)  # fmt: skip
            except Exception as exc:  # every failure is recorded; the sweep goes on
                err = _error_text(exc)
        compute = _t.perf_counter() - t0
        cpu = _t.thread_time() - c0
        chans = None
        if res is not None:
            chans = {c: v for c, v in res.channels.items() if names is None or c in names}
        status = OK if res is not None else FAILED
        rec: dict[str, Any] = {
            "run": i,
            "status": status,
            "compute_s": compute,
            "cpu_s": cpu,
            "error": err,
            "warnings": caught,
        }
        record = {
            "compute_s": compute,
            "cpu_s": cpu,
            "host": host,
            "pid": pid,
            "bearingsim_version": __version__,
            "warnings": caught,
            "meta": None if res is None else res.meta,
        }
        settle()  # the previous run's commit (it ran while this run computed)
        if writer is not None:
            pool = _commit_pool() if overlap else _INLINE
            fut = pool.submit(_timed_commit, writer, i, status, record, err, chans, rerun=retry)
            pending = (fut, rec, record, chans)
            if not overlap:
                settle()
        else:
            rec["record"] = to_jsonable(record)
            rec["channels"] = chans
        out.append(rec)
    settle()
    return out


# ------------------------------------------------------------------------------ run
@dataclass
class SweepReport:
    """Outcome of one :func:`run_sweep` call.

    Attributes
    ----------
    out : str
        Dataset path.
    n_runs : int
        Runs in the spec.
    n_skipped : int
        Runs already committed when this call started (not recomputed).
    n_computed : int
        Runs computed and committed by this call, read from the dataset at the end (also those
        of tasks that never reported: a killed worker, Ctrl-C).
    n_ok, n_failed, n_pending : int
        Status counts of the whole dataset at the end.
    n_failed_now : int
        Runs of this call that failed (of ``n_computed``).
    n_recomputed : int
        Runs computed a second time in this call (a helper task and the task it helps both
        started the run where they met; counted once in ``n_computed`` and ``compute_s``).
    wall_s : float
        Wall time from the first submitted task to the last commit [s].
    setup_s : float
        Wall time before that: cluster start, kernel loading, probes, dataset creation [s].
    compute_s : float
        Sum of the runs' ``simulate`` wall times [s].
    compute_cpu_s : float
        Sum of the runs' ``simulate`` CPU times (thread time on the worker) [s].
    commit_s : float
        Sum of the per-run commit times on the workers and the client [s].
    client_cpu_s : float
        CPU time of this process during ``wall_s`` (with a local cluster it hosts the Dask
        scheduler too) [s].
    worker_cpu_s : float
        CPU time of the worker processes during ``wall_s`` (all their threads; on a shared
        cluster also other clients' work), with ``measure_cpu`` [s].
    workers : int
        Worker threads at the end [-].
    tasks : int
        Dask tasks submitted [-].
    helper_tasks : int
        Of these, tasks that took over the second half of a running task's runs [-].
    estimate_s : float or None
        Per-run compute time estimated by the timing probes before the first task (``None``:
        fixed ``runs_per_task``, nothing to compute, or every probe failed) [s].
    committed_by : dict
        Runs committed by workers and by the client.
    warnings : dict
        Each warning the runs of this call raised (``"Category: message"``) and how many runs
        raised it; every run's own list is in its record (``SweepDataset.records``).
    n_lost : int
        Runs committed ok whose signal chunk was missing when this call started (their data
        were lost): set back to pending and computed again (counted in ``n_computed``, not in
        ``n_skipped``; :class:`LostDataWarning` names them).
    """

    out: str
    n_runs: int
    n_skipped: int = 0
    n_computed: int = 0
    n_ok: int = 0
    n_failed: int = 0
    n_pending: int = 0
    n_failed_now: int = 0
    n_recomputed: int = 0
    wall_s: float = 0.0
    setup_s: float = 0.0
    compute_s: float = 0.0
    compute_cpu_s: float = 0.0
    commit_s: float = 0.0
    client_cpu_s: float = 0.0
    worker_cpu_s: float = 0.0
    workers: int = 0
    tasks: int = 0
    helper_tasks: int = 0
    estimate_s: float | None = None
    cluster: str = ""
    created: bool = False
    committed_by: dict[str, int] = field(default_factory=lambda: {"worker": 0, "client": 0})
    interrupted: bool = False
    warnings: dict[str, int] = field(default_factory=dict)
    n_lost: int = 0

    def as_dict(self) -> dict[str, Any]:
        """Plain dict (JSON)."""
        d = to_jsonable(asdict(self))
        d["throughput_runs_per_s"] = self.n_computed / self.wall_s if self.wall_s > 0 else None
        return d


@contextlib.contextmanager
def connect(
    workers: int | None = None,
    scheduler: str | None = None,
    timeout_s: float = CONNECT_TIMEOUT_S,
) -> Iterator[tuple[Any, str]]:
    """A :class:`distributed.Client` on a new local cluster of ``workers`` process workers
    (one thread each), or on the scheduler at ``scheduler``; closed on exit."""
    from distributed import Client, LocalCluster

    check_cluster_args(workers, scheduler)
    check_range("connect_timeout_s", timeout_s, 0.0, lo_open=True, unit="s")
    if scheduler is not None:
        if scheduler.startswith(("tls://", "wss://")):
            import dask

            if not dask.config.get("distributed.comm.tls.ca-file", None):
                # Dask's Client raised a TypeError, and its half-made client a TimeoutError
                # at exit (a helper, twenty-seventh session)
                raise ConfigError(
                    f"scheduler = {scheduler!r} needs TLS, and Dask has no TLS configuration "
                    "(distributed.comm.tls.ca-file unset); valid: a tcp:// address, or Dask's "
                    "TLS settings (its configuration file or DASK_DISTRIBUTED__COMM__TLS__CA_FILE)"
                )
        _wait_for_port(scheduler, timeout_s)
        try:
            client = Client(scheduler, timeout=timeout_s, set_as_default=False)
        except (OSError, TimeoutError) as exc:
            raise _unreachable(scheduler, timeout_s, exc) from None
        try:
            yield client, scheduler
        finally:
            client.close()
        return
    import dask

    n = workers if workers is not None else (os.cpu_count() or 1)
    with warnings.catch_warnings(), dask.config.set(LOCAL_CLUSTER_CONFIG):
        # distributed warns when creating its scratch directory is slow on a busy disk
        warnings.filterwarnings("ignore", message="Creating scratch directories")
        cluster = LocalCluster(
            n_workers=n,
            threads_per_worker=1,
            processes=True,
            dashboard_address=":0",  # the scheduler's HTTP server on a free port: no clash
            # CRITICAL, not ERROR: a worker whose scheduler closed first (Ctrl-C sent to the
            # whole process group) logs "Failed to communicate with scheduler during heartbeat"
            # at ERROR with a traceback on the client's stderr, breaking its one-line message
            # (CI, 2026-11-26); a failed run still reaches the client as its task's exception
            silence_logs=logging.CRITICAL,
        )
    try:
        client = Client(cluster, set_as_default=False, direct_to_workers=True)
        try:
            from ._local import IgnoreSigint

            client.register_plugin(IgnoreSigint())  # Ctrl-C is the client's to handle
            yield client, f"local cluster, {n} process worker(s)"
        finally:
            client.close()
    finally:
        cluster.close()


def _wait_for_port(scheduler: str, timeout_s: float) -> None:
    """Wait until a ``tcp://HOST:PORT`` scheduler accepts a connection, in steps of at most
    1 s (a Ctrl-C stops it at once; other address forms are left to Dask). Exploratory
    testing, twenty-seventh session: a Ctrl-C while ``Client`` waited for an unreachable
    scheduler printed "aborted", then hung 40 s and printed the half-made client's
    ``TimeoutError`` traceback. Unreachable within ``timeout_s`` [s]: the one-line error."""
    import socket
    from urllib.parse import urlsplit

    try:
        u = urlsplit(scheduler)
        host, port = u.hostname, u.port
    except ValueError:
        return
    if u.scheme != "tcp" or not host or port is None:
        return
    deadline = time.monotonic() + timeout_s
    while True:
        left = deadline - time.monotonic()
        try:
            socket.create_connection((host, port), timeout=max(min(left, 1.0), 0.01)).close()
            return
        except OSError as exc:
            if time.monotonic() + 0.2 >= deadline:
                raise _unreachable(scheduler, timeout_s, exc) from None
            time.sleep(0.2)


def _unreachable(scheduler: str, timeout_s: float, exc: BaseException) -> ConfigError:
    """The one-line error of a scheduler not reached within ``timeout_s`` [s]."""
    return ConfigError(
        f"scheduler = {scheduler!r} is not reachable within {timeout_s:g} s "
        f"({type(exc).__name__}); valid: the address printed by a running 'dask scheduler'"
    )


#: candidates of a group's first probe task; when none of them starts, the next task takes
#: twice as many (a run that cannot start fails at its check, in milliseconds)
PROBE_BATCH = 3


def _batches(cl: Any, fn: Callable, idx: list[int], sdicts: list[dict[str, Any]], start: int,
             size: int, allow: bool) -> Iterator[tuple[list[int], Any]]:  # fmt: skip
    """``(part, fn(its scenario dicts, allow))`` on a worker for the runs ``idx[start:]`` in
    batches of ``size``, then twice as many at a time (the caller stops at the first it
    needs); ``allow``: the sweep's ``allow_overload``."""
    while start < len(idx):
        part = idx[start : start + size]
        yield part, cl.submit(fn, [sdicts[i] for i in part], allow, pure=False).result()
        start, size = start + size, 2 * size


def _probe_rest(
    cl: Any, first: dict[str, Any] | str, idx: list[int], sdicts: list[dict[str, Any]],
    allow: bool,
) -> dict[str, Any] | str:  # fmt: skip
    """The probe of a group whose first :data:`PROBE_BATCH` runs gave ``first``: when none of
    them started, the group's later runs in growing batches until one starts; the first run's
    error text when none does (the group's runs are then recorded as failed)."""
    if not isinstance(first, str):
        return first
    for _part, p in _batches(cl, probe_first, idx, sdicts, PROBE_BATCH, 2 * PROBE_BATCH, allow):
        if not isinstance(p, str):
            return p
    return first


def _longest_valid(
    cl: Any, scenarios: list[Scenario], sdicts: list[dict[str, Any]], allow: bool
) -> int:
    """Samples of the longest run that passes its check (the dataset's time axis; a run that
    cannot start stores nothing): the runs from the longest down, checked on a worker in
    growing batches (usually the first passes). Every run's length when they are all equal;
    the longest run's when none passes (each is then recorded as failed)."""
    ns = [sc.n_samples for sc in scenarios]
    if min(ns) == max(ns):
        return ns[0]
    order = sorted(range(len(ns)), key=lambda i: -ns[i])
    for part, k in _batches(cl, first_valid, order, sdicts, 0, PROBE_BATCH, allow):
        if k >= 0:
            return ns[part[k]]
    return max(ns)


def check_cluster_args(workers: int | None, scheduler: str | None) -> None:
    """Validate ``workers`` (>= 1) and ``scheduler`` (``tcp://HOST:PORT``; not both)."""
    if workers is not None and (
        isinstance(workers, bool) or not isinstance(workers, int) or workers < 1
    ):
        raise ConfigError(f"workers = {workers!r} is out of range; valid range [1, inf) integer")
    if scheduler is not None:
        if not isinstance(scheduler, str) or not _ADDRESS.match(scheduler):
            raise ConfigError(
                f"scheduler = {scheduler!r} is invalid; valid: an address like tcp://HOST:PORT"
            )
        port = int(scheduler.rsplit(":", 1)[1])
        if not 1 <= port <= 65535:  # "not reachable (OSError)" before (a helper, 27th session)
            raise ConfigError(
                f"scheduler = {scheduler!r} has port {port}, out of range; valid range [1, 65535]"
            )
        if workers is not None:
            raise ConfigError(
                f"workers = {workers} applies to a local cluster only; with scheduler = "
                f"{scheduler!r} the cluster's own workers run the sweep"
            )


def process_cpu_s() -> float:
    """CPU time (user + system, every thread) of the calling process [s]."""
    import psutil

    t = psutil.Process().cpu_times()
    return t.user + t.system


def _workers_cpu(client) -> dict[str, float]:
    try:
        return client.run(process_cpu_s)
    except Exception:  # bookkeeping only; a lost scheduler shows up in the task results
        return {}


def _worker_threads(client) -> dict[str, int]:
    """Threads of each worker by address (empty when the scheduler cannot be asked)."""
    try:
        return {str(a): int(n) for a, n in client.nthreads().items()}
    except Exception:  # a lost scheduler shows up in the task results
        return {}


def run_sweep(
    spec: SweepSpec,
    out: str | Path,
    *,
    workers: int | None = None,
    scheduler: str | None = None,
    client: Any = None,
    force_new: bool = False,
    retry_failed: bool = False,
    runs_per_task: int | None = None,
    writer: Writer | str = "auto",
    progress: bool | Callable[[SweepReport], None] = False,
    connect_timeout_s: float = CONNECT_TIMEOUT_S,
    measure_cpu: bool = False,
) -> SweepReport:
    """Run (or resume) a sweep into the Zarr dataset ``out``.

    Parameters
    ----------
    spec : SweepSpec
        The sweep.
    out : str or Path
        Dataset directory; created, or resumed when it holds the same spec.
    workers : int, optional
        Process workers of the local cluster (default: CPU count).
    scheduler : str, optional
        Address of a running Dask scheduler (``tcp://HOST:PORT``) instead of a local cluster.
    client : distributed.Client, optional
        An existing client to use (neither cluster is created nor closed).
    force_new : bool
        Replace an existing dataset made by a different spec (deleted first).
    retry_failed : bool
        Compute the runs recorded as failed again.
    runs_per_task : int, optional
        Fixed number of runs per Dask task (default: automatic, see the module docstring).
    writer : Writer or {"auto", "client"}
        Who commits the runs (:class:`Writer`).
    progress : bool or callable
        ``True``: a tqdm bar on stderr (runs done, failed, ETA); a callable gets the report
        after every finished task.
    connect_timeout_s : float
        How long to try reaching ``scheduler`` [s].
    measure_cpu : bool
        Also measure the workers' CPU time during the sweep (``SweepReport.worker_cpu_s``; two
        extra calls to every worker).

    Returns
    -------
    SweepReport
        Counts and timings. Raises :class:`SweepInterrupted` on Ctrl-C (committed runs kept).
    """
    t_start = time.perf_counter()
    writer = parse_enum(Writer, writer, "writer").value  # tasks carry the plain value
    if runs_per_task is not None and (
        isinstance(runs_per_task, bool) or not isinstance(runs_per_task, int) or runs_per_task < 1
    ):
        raise ConfigError(
            f"runs_per_task = {runs_per_task!r} is out of range; valid range [1, inf) integer"
        )
    if client is None:
        check_cluster_args(workers, scheduler)
    scenarios = spec.scenarios()
    sdicts = [s.to_dict() for s in scenarios]  # what the tasks carry (and the dataset stores)
    allow = spec.allow_overload
    canonical = spec.canonical()
    h = canonical_hash(canonical)
    path = Path(out).absolute()
    replace_old = False
    rep = SweepReport(out=str(out), n_runs=len(scenarios))
    if path.exists():
        remove_stale_creations(path)  # a killed creation's leftovers beside it (only at the
        # next creation before: a Ctrl-C during creation, then a rerun, kept one for good)
        replace_old = _other_spec(path, h, canonical, out, force_new)
        if not replace_old:
            md = read_metadata(path)  # a damaged dataset is refused before any work
            st = read_status(path)
            lost = lost_runs(path, np.flatnonzero(st == OK), st, md)
            if not lost and not np.any((st == PENDING) | ((st == FAILED) & retry_failed)):
                rep.n_skipped = len(scenarios)  # nothing to compute: no cluster needed
                _final_counts(rep, st)
                rep.setup_s = time.perf_counter() - t_start
                return rep
    lock = ClientLock(path)
    # workers of a local cluster end with it; those of another cluster outlive this client
    own_cluster = client is None and scheduler is None
    interrupted: SweepInterrupted | None = None
    ctx = contextlib.nullcontext((client, "given client")) if client is not None else None
    # the lock is held until the counts are read, after the cluster is closed
    with contextlib.ExitStack() as held:
        held.callback(lock.release)
        if path.exists() and not replace_old:  # a resume: "in use" before any work
            lock.acquire()
            _other_spec(path, h, canonical, out, False)  # may have changed meanwhile
        with ctx or connect(workers, scheduler, connect_timeout_s) as (cl, desc):
            rep.cluster = desc
            if not cl.nthreads():
                if progress is True:
                    print(f"sweep: waiting for a worker to join {desc}", file=sys.stderr)
                cl.wait_for_workers(1)
            hello = cl.run(worker_hello)
            bad = {a: v for a, v in hello.items() if v["version"] != __version__}
            if bad:
                a, v = next(iter(bad.items()))
                raise ConfigError(
                    f"worker {a} runs bearingsim {v['version']}, this client {__version__}; "
                    "install the same version on every worker"
                )
            futs: dict[Any, Any] = {}  # setup tasks, released at the end (see _estimate_run_s)
            if not path.exists() or replace_old:
                groups = probe_groups(scenarios)
                futs = {
                    k: cl.submit(probe_first, [sdicts[i] for i in idx[:PROBE_BATCH]], allow,
                                 pure=False)
                    for k, idx in groups.items()
                }  # fmt: skip
                tried = {k: _probe_rest(cl, f.result(), groups[k], sdicts, allow)
                         for k, f in futs.items()}  # fmt: skip
                probes = {k: v for k, v in tried.items() if not isinstance(v, str)}
                if not probes:  # the groups of runs that cannot start are recorded as failed
                    k0 = next(iter(groups))
                    raise ConfigError(f"no run can start; run {groups[k0][0]}: {tried[k0]}")
                n_time = _longest_valid(cl, scenarios, sdicts, allow)
                layout = make_layout(spec, scenarios, probes, n_time)
                if replace_old:  # read_attrs() above proved it is a sweep dataset
                    _remove_dataset(path)
                attrs_new = {
                    "spec_hash": h,
                    "spec_json": json.dumps(to_jsonable(canonical)),
                    "label": list(spec.label),
                    "axes": list(spec.axis_names),
                    "name": spec.name,
                }
                try:
                    create_dataset(
                        path, layout, attrs_new, coordinates(spec, scenarios), sdicts, lock=lock
                    )
                    lock.adopt()  # renamed into place with this client's lock in it
                    rep.created = True
                except DatasetExistsError:
                    pass  # another client created it first: joined below (in use while it runs)
            if not lock.held:
                lock.acquire()  # a live client's lock: "in use"
                _other_spec(path, h, canonical, out, False)  # may have changed meanwhile
            attrs = read_attrs(path)
            uid = attrs["uuid"]
            remove_stale_temporaries(path)
            cw = RunWriter(path, uid)
            st0 = read_status(path)
            md = read_metadata(path)
            lost = lost_runs(path, np.flatnonzero(st0 == OK), st0, md)
            if lost:  # committed ok, data gone: pending again (under the lock), computed again
                for i in lost:
                    cw.mark_pending(i)
                st0[lost] = PENDING
                rep.n_lost = len(lost)
                warnings.warn(_lost_message(out, path, lost, md), LostDataWarning, stacklevel=2)
            todo_mask = st0 == PENDING
            if retry_failed:
                todo_mask |= st0 == FAILED
            todo_runs = np.flatnonzero(todo_mask)
            todo = deque(int(i) for i in todo_runs)
            rep.n_skipped = len(scenarios) - len(todo)
            offsets = records_offsets(path)
            counted: set[int] = set()
            if runs_per_task is None and todo:
                rep.estimate_s = _estimate_run_s(cl, [scenarios[i] for i in todo], futs, allow)
            rep.setup_s = time.perf_counter() - t_start
            try:
                _execute(
                    cl,
                    spec,
                    # the tasks carry a rate the rig chose as unset: the run resolves it again
                    # and records it among its defaults, as the CLI's run does (exploratory
                    # testing, twenty-sixth session: a sweep's meta["defaults"] lacked fs_hz)
                    [sc.to_dict(rate=False) for sc in scenarios],
                    todo,
                    str(path),
                    uid,
                    cw,
                    rep,
                    runs_per_task,
                    writer,
                    progress,
                    retry_failed,
                    measure_cpu,
                    spare_core_workers(hello, cl.nthreads()),
                    counted=counted,
                    lock=lock,
                    drain=not own_cluster,
                )
            except SweepInterrupted as exc:
                interrupted = exc
            finally:
                cw.close()
        # the local cluster is closed: its workers commit nothing more, so the counts are final
        _exact_counts(rep, path, todo_runs, st0, counted, offsets)
    if interrupted is not None:
        more = interrupted.left_running
        done = rep.n_ok + rep.n_failed
        # a Ctrl-C after the last commit: nothing is left (exploratory testing, twenty-seventh
        # session: "8 of 8 runs committed ...; run the same command again to resume")
        tail = (
            "; run the same command again to resume"
            if done < rep.n_runs or more
            else "; every run is committed, nothing is left to resume"
        )
        raise SweepInterrupted(
            f"interrupted: {done} of {rep.n_runs} runs committed ({rep.n_computed} by this call"
            + (f"; {more} task(s) left running may commit one run each" if more else "")
            + ")"
            + tail,
            rep,
        ) from None
    return rep


def _lost_message(out: Any, path: Path, lost: list[int], md: dict[str, Any]) -> str:
    """What :class:`LostDataWarning` says: how many runs, which, what happens."""
    shown = ", ".join(map(str, lost[:10])) + (", ..." if len(lost) > 10 else "")
    first = signal_chunk(path, lost[0], md["signal/.zarray"])
    return (
        f"dataset = {str(out)!r}: {len(lost)} run(s) committed ok had lost their signal chunk "
        f"({shown}; {str(first)!r} is missing): set back to pending and computed again"
    )


def _other_spec(path: Path, h: str, canonical: dict[str, Any], out: Any, force_new: bool) -> bool:
    """Whether the dataset ``path`` holds another spec than ``h`` (refused unless
    ``force_new``: then ``True``, to be replaced)."""
    attrs = read_attrs(path)
    if attrs.get("spec_hash") == h:
        return False
    if not force_new:
        try:
            old = json.loads(attrs.get("spec_json", "{}"))
        except (TypeError, ValueError):
            old = {}
        new = json.loads(json.dumps(to_jsonable(canonical)))
        diff = ", ".join(spec_differences(old, new)[:6]) if isinstance(old, dict) else ""
        raise ConfigError(
            f"out = {str(out)!r} holds a dataset of a different sweep spec (differs in: "
            f"{diff or 'content'}); use another -o/--output, or --force-new to replace it"
        )
    return True


def _remove_dataset(path: Path) -> None:
    """Delete the dataset ``path`` under its lock (refused while another client uses it): it
    is renamed aside first, so that no client sees a half-deleted dataset."""
    aside = path.parent / f".{path.name}.removing-{uuidlib.uuid4().hex}"
    with ClientLock(path):
        os.rename(path, aside)
    shutil.rmtree(aside, ignore_errors=True)


def _exact_counts(
    rep: SweepReport,
    path: Path,
    todo: np.ndarray,
    st0: np.ndarray,
    counted: set[int],
    offsets: dict[str, int],
) -> None:
    """Counts of ``rep`` from the dataset itself: the status counts, and the runs committed by
    this call (``n_computed``, ``n_failed_now``), including those whose task never reported
    (its worker was killed after committing them; Ctrl-C before it finished). Their compute
    times come from the records appended during this call."""
    st1 = read_status(path)
    _final_counts(rep, st1)
    was_pending = todo[st0[todo] == PENDING]
    retried = todo[st0[todo] == FAILED]
    computed = {int(i) for i in was_pending[st1[was_pending] != PENDING]}
    computed |= {int(i) for i in retried[st1[retried] == OK]}
    computed |= counted & {int(i) for i in retried}
    unsure = [int(i) for i in retried if st1[i] == FAILED and int(i) not in counted]
    unreported = sorted(computed - counted)
    if unreported or unsure:
        recs = read_records(path, st1, since=offsets)
        computed |= {i for i in unsure if i in recs}  # failed again, in a task that was lost
        for i in sorted(computed - counted):
            r = recs.get(i, {})
            rep.compute_s += r.get("compute_s") or 0.0
            rep.compute_cpu_s += r.get("cpu_s") or 0.0
    rep.n_computed = len(computed)
    rep.n_failed_now = sum(1 for i in computed if st1[i] == FAILED)


def _estimate_run_s(cl, todo: list[Scenario], keep: dict[Any, Any], allow: bool) -> float | None:
    """Mean compute time of the runs ``todo`` [s] from one timing probe per model on the
    workers (:func:`~bearingsim.sweep_plan.timing_probe`); ``None`` when every probe raises.
    The probes' futures go into ``keep``: releasing them right before the first tasks would
    delay those by the client's message batching (up to 10 ms)."""
    from .plan import extrapolate, timing_probe

    first: dict[str, Scenario] = {}
    for sc in todo:
        first.setdefault(sc.model.value, sc)
    futs = {
        m: cl.submit(timing_probe, sc.to_dict(), TIMING_PROBE_S, allow, pure=False)
        for m, sc in first.items()
    }
    fit = {}
    for m, f in futs.items():
        with contextlib.suppress(Exception):  # a lost worker: the estimate only sizes tasks
            if (r := f.result()) is not None:
                fit[m] = [r]
    keep.update({("timing", m): f for m, f in futs.items()})
    est = extrapolate(todo, fit)
    return float(np.mean(est)) if fit else None


def _final_counts(rep: SweepReport, st: np.ndarray) -> None:
    rep.n_ok = int(np.sum(st == OK))
    rep.n_failed = int(np.sum(st == FAILED))
    rep.n_pending = int(np.sum(st == PENDING))


@dataclass
class _Task:
    """A submitted task as the client sees it."""

    id: str
    runs: list[int]
    helper: bool = False
    worker: str | None = None  # where the client placed it
    keep: int | None = None  # runs[keep:] handed to a helper (claim written)


def _execute(
    cl,
    spec: SweepSpec,
    sdicts: list[dict[str, Any]],
    todo: deque,
    path: str,
    uid: str,
    cw: RunWriter,
    rep: SweepReport,
    runs_per_task: int | None,
    writer: str,
    progress: bool | Callable[[SweepReport], None],
    retry_failed: bool,
    measure_cpu: bool,
    overlap: set[str] = frozenset(),  # type: ignore[assignment]
    counted: set[int] | None = None,
    lock: ClientLock | None = None,
    drain: bool = False,
) -> None:
    """The submission loop: feed tasks, commit what the workers send back, count.

    ``counted`` collects the runs reported by finished tasks; ``lock`` is checked after every
    task (:meth:`ClientLock.check`); with ``drain`` (workers that outlive this client), Ctrl-C
    waits for the tasks in flight to commit their current run (a second Ctrl-C leaves them).
    """
    from distributed import as_completed

    n_todo = len(todo)
    wcpu0 = _workers_cpu(cl) if measure_cpu else {}
    bar = None
    if progress is True:
        from tqdm import tqdm

        bar = tqdm(total=n_todo, desc="sweep", unit="run", file=sys.stderr, smoothing=0.1)
    channels = None if spec.channels is None else list(spec.channels)
    run_time: list[float] = []  # per-run compute + commit on the workers
    workers = _worker_threads(cl)
    threads = max(1, sum(workers.values()))
    t_threads = time.perf_counter()
    placed: dict[str, int] = {}  # tasks in flight on each worker, as placed by this loop
    # results are fetched in the background as tasks finish (not when this loop asks for them)
    ac = as_completed(loop=cl.loop, with_results=True, raise_errors=False)
    inflight: dict[Any, _Task] = {}
    # runs counted in rep (a run computed twice counts once)
    counted = set() if counted is None else counted
    claims: list[str] = []
    batch = [0, 0]  # size and tasks left of the current batch (several threads)

    def per_run() -> float:
        """Per-run time [s]: measured in the finished tasks, else the probes' estimate."""
        t = float(np.mean(run_time[-64:])) if run_time else rep.estimate_s
        return max(t or 0.0, 1e-6)

    def refresh() -> None:
        nonlocal workers, threads, t_threads
        if time.perf_counter() - t_threads > 2.0:
            workers = _worker_threads(cl) or workers
            threads, t_threads = max(1, sum(workers.values())), time.perf_counter()

    def next_size() -> int:
        if runs_per_task is not None:
            return runs_per_task
        if not run_time and rep.estimate_s is None:  # per thread a one-run timing task, then
            return 1 if rep.tasks < threads else SECOND_TASK_RUNS  # a small second one
        size = max(1, int(TARGET_TASK_S / per_run()))
        if threads == 1:  # nothing to balance: no short task at the end
            return len(todo) if len(todo) < 1.5 * size else size
        # factoring: batches of one task per thread, each an equal share of what is left; a
        # worker that runs out of tasks before the others takes over half of a running task
        if batch[1] == 0:
            batch[:] = [max(1, math.ceil(len(todo) / threads)), threads]
        batch[1] -= 1
        return min(size, batch[0])

    def least_loaded() -> str | None:
        return min(workers, key=lambda a: placed.get(a, 0) / workers[a], default=None)

    def submit(runs: list[int], helper: bool = False, worker: str | None = None) -> None:
        worker = worker or least_loaded()
        tid = f"bearingsim-sweep-run{runs[0]}-{uuidlib.uuid4().hex[:12]}"
        task = {
            "dataset": path,
            "uuid": uid,
            "version": __version__,
            "channels": channels,
            "writer": writer,
            "retry_failed": retry_failed,
            "runs": [(i, sdicts[i]) for i in runs],
            "id": tid,
            "overlap_commit": worker in overlap,
            "allow_overload": spec.allow_overload,
        }
        # placed by this loop (the scheduler does not know how long a task is), loosely: a task
        # whose worker is gone goes to another
        where = {} if worker is None else {"workers": [worker], "allow_other_workers": True}
        fut = cl.submit(run_task, task, pure=False, key=tid, **where)
        inflight[fut] = _Task(tid, runs, helper, worker)
        if worker is not None:
            placed[worker] = placed.get(worker, 0) + 1
        ac.add(fut)
        rep.tasks += 1
        rep.helper_tasks += helper

    def submit_next() -> None:
        size = next_size()
        submit([todo.popleft() for _ in range(min(size, len(todo)))])

    def done(i: int) -> bool:
        st = cw.status_of(i)
        return st == OK or (st == FAILED and not retry_failed)

    def help_one(worker: str) -> bool:
        """Hand the second half of the remaining runs of the longest task in flight to a new
        task on the idle ``worker`` (reversed, so that the two meet at most at one run)."""
        best, best_share = None, 0
        for t in inflight.values():
            if t.keep is not None:
                continue
            first = next((k for k, i in enumerate(t.runs) if not done(i)), len(t.runs))
            share = (len(t.runs) - first) // 2
            if share > best_share:
                best, best_share = t, share
        if best is None or best_share * per_run() < MIN_HELP_S:
            return False
        best.keep = len(best.runs) - best_share
        claims.append(write_claim(path, best.id, best.keep))
        submit(best.runs[best.keep :][::-1], helper=True, worker=worker)
        return True

    def may_help() -> bool:
        return (
            runs_per_task is None
            and writer == "auto"
            and bool(run_time)
            and rep.committed_by["client"] == 0
            and rep.committed_by["worker"] > 0
        )

    cpu0 = time.process_time()
    t0 = time.perf_counter()

    def fill() -> None:
        while todo and len(inflight) < INFLIGHT_PER_THREAD * threads:
            submit_next()

    async def fill_at_once() -> None:
        fill()

    def handle(fut, result) -> int:
        """Count (and, for the client writer, commit) the runs of a finished task; returns
        how many runs it newly committed."""
        task = inflight.pop(fut)
        if task.worker is not None:
            placed[task.worker] -= 1
        if isinstance(result, asyncio.CancelledError | concurrent.futures.CancelledError):
            raise ConfigError(
                f"lost the Dask scheduler ({_error_text(result)}); committed runs are kept: "
                "run the same command again to resume"
            )
        if fut.status == "error":  # KilledWorker, a bug in a task: recorded, sweep goes on
            mine = task.runs if task.keep is None else task.runs[: task.keep]
            records = _failed_records(cw, mine, result[1])
        else:
            records = result
        n_new = 0
        for r in records:
            if r["status"] not in (OK, FAILED):  # skipped or handed over
                continue
            if "commit_s" in r:
                rep.committed_by["worker"] += 1
                rep.commit_s += r["commit_s"]
                run_time.append(r["compute_s"] + r["commit_s"])
            else:
                tc = time.perf_counter()
                cw.commit(r["run"], r["status"], r["record"], r["error"], r.get("channels"))
                rep.commit_s += time.perf_counter() - tc
                rep.committed_by["client"] += 1
                run_time.append(r["compute_s"])
            if r["run"] in counted:  # computed twice (a helper met its task): wasted
                rep.n_recomputed += 1
                continue
            counted.add(r["run"])
            n_new += 1
            rep.n_computed += 1
            rep.compute_s += r["compute_s"]
            rep.compute_cpu_s += r.get("cpu_s", 0.0)
            for w in dict.fromkeys(r.get("warnings") or ()):
                rep.warnings[w] = rep.warnings.get(w, 0) + 1
            if r["status"] == FAILED:
                rep.n_failed_now += 1
        if bar is not None:  # the counts first: update() draws them (it showed the last batch's)
            bar.set_postfix_str(
                f"ok={rep.n_computed - rep.n_failed_now} failed={rep.n_failed_now}",
                refresh=False,
            )
            bar.update(n_new)
        return n_new

    try:
        # the first tasks are submitted from one callback of the client's event loop, so that
        # they leave in one message (submitted one by one from here, the second would wait for
        # the client's next message batch, up to 10 ms later)
        cl.sync(fill_at_once)
        for fut, result in ac:
            handle(fut, result)
            if lock is not None:
                lock.check()  # another client took the lock over: stop
            if callable(progress):
                progress(rep)
            refresh()
            fill()
            if not todo and may_help():
                for a, n in list(workers.items()):
                    while placed.get(a, 0) < n and help_one(a):
                        pass
            # released after the submissions above: its release message would otherwise hold
            # them back in the client's message batching (up to 10 ms)
            del fut, result
    except KeyboardInterrupt:
        rep.interrupted = True
        for t in inflight.values():  # running tasks stop after their current run
            with contextlib.suppress(OSError):
                write_claim(path, t.id, 0)
        claims.clear()  # left for the tasks still running (removed when the dataset is reopened)
        if drain and inflight:  # workers that outlive this client: wait for their current runs
            if progress is True:
                print(
                    f"sweep: interrupted; waiting for {len(inflight)} task(s) to commit their "
                    "current run (Ctrl-C again to leave them running)",
                    file=sys.stderr,
                )
            try:
                for fut, result in ac:
                    with contextlib.suppress(Exception):  # a lost task: its runs stay pending
                        handle(fut, result)
                    del fut, result
            except KeyboardInterrupt:
                pass
        left = len(inflight)
        cl.cancel(list(inflight))
        rep.wall_s = time.perf_counter() - t0
        exc = SweepInterrupted("interrupted", rep)
        exc.left_running = left if drain else 0
        raise exc from None
    finally:
        if bar is not None:
            bar.close()
        rep.workers = threads
        rep.wall_s = time.perf_counter() - t0
        rep.client_cpu_s = time.process_time() - cpu0
        for c in claims:
            with contextlib.suppress(OSError):
                os.unlink(c)
        if measure_cpu:
            wcpu = _workers_cpu(cl)
            rep.worker_cpu_s = sum(v - wcpu0[a] for a, v in wcpu.items() if a in wcpu0)


def _failed_records(cw: RunWriter, runs: list[int], exc: BaseException) -> list[dict[str, Any]]:
    """Failure records for the runs of a task that raised, except those it committed."""
    err = _error_text(exc)
    return [
        {
            "run": i,
            "status": FAILED,
            "compute_s": 0.0,
            "error": err,
            "record": {"compute_s": None, "host": None, "pid": None, "meta": None},
        }
        if not cw.committed(i)
        else {"run": i, "status": "skipped"}
        for i in runs
    ]


__all__ = [
    "LostDataWarning",
    "SweepInterrupted",
    "SweepPlan",
    "SweepReport",
    "Writer",
    "check_cluster_args",
    "connect",
    "plan_sweep",
    "run_sweep",
    "run_task",
    "worker_hello",
]
