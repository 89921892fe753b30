"""Sweep dataset storage: one Zarr store, one slot per run, atomic per-run commits.

Layout (Zarr format 2 with consolidated metadata: ``xarray.open_zarr(path)`` reads it)::

    DATASET/
      .zattrs               format, uuid, spec hash, canonical spec, channels, label, axes, ...
      run (run)             run number 0..n-1
      time (time)           nominal sample times k/fs [s] when every run has the same fs and
                            length; otherwise the dimension is ``sample`` (no coordinate)
      <key> (run)           each swept scenario key (and each label key) as a coordinate
      scenario_json (run)   the full scenario of each run (JSON), written at creation
      channel, units (channel)   names and units of the stored time series
      signal (run, channel, time)   the stored time series, float64 (SI), one chunk per run;
                            NaN where not (yet) written
      <name> (run, time, ball)   each stored per-ball channel, one chunk per run
      status (run)          int8 commit marker: 0 pending, 1 ok, 2 failed (one uncompressed
                            byte per run, every chunk written at creation)
      error (run)           "ErrorType: message" of a failed run ("" otherwise)
      records               0-d placeholder array; its directory holds records/*.jsonl, one
                            line per committed run, one file per writer process:
                            {"run", "status", "t", "compute_s": wall time of simulate [s],
                            "cpu_s", "host", "pid", "bearingsim_version",
                            "meta": SimulationResult.meta}; while a sweep runs also the
                            client's lock and claim files (``.claim-<task>``: the position in
                            that task from which a helper task has taken over its runs)

Commit protocol
---------------
All metadata (every ``.zarray``/``.zattrs``, the coordinates, ``scenario_json`` and a zero
``status`` chunk for every run) is written once, into a temporary directory beside ``DATASET``
that is then renamed into place (``os.rename`` of a directory is atomic); afterwards only chunks
are written, never metadata, so the consolidated metadata stays valid. Run ``i`` owns chunk ``i``
of every per-run array, so concurrent writers never touch the same file. Committing run ``i``
writes its data chunks (``signal``, per-ball arrays) and its ``error`` (failed runs), each under
a temporary name in its array directory renamed onto its key (``os.replace``, atomic on POSIX: a
reader sees no chunk or a complete one), then appends its record as one line to the writer's
``records/*.jsonl`` file, and last overwrites the single byte of its ``status`` chunk in place (a
one-byte write cannot be torn). A run counts
as done only when its ``status`` byte says ok (1) or failed (2): a process killed at any instant
leaves every earlier commit intact and at most one run per writer whose data chunks exist
without its marker; that run is still pending and is computed again on resume (rewriting the
same chunks). Chunks are encoded with the codecs recorded in each array's own ``.zarray`` (the
numcodecs objects zarr uses, built from the consolidated metadata read once by each writer; a
test checks the bytes equal zarr-python's) and written with plain
file operations, because a one-chunk write through zarr-python's asynchronous store costs ~1 ms
and writing a new file on the test machine's ext4 (create, 87 kB into the page cache, rename)
0.1-0.5 ms, depending on the state of the VM: a commit creates one file (the signal chunk),
appends one line and writes one byte. A line cut by a kill belongs to a run that is
still pending; the reader skips it. Durability against a power cut would need ``fsync``; against
killed processes it does not.
"""

from __future__ import annotations

import contextlib
import dataclasses
import itertools
import json
import os
import shutil
import socket
import threading
import time
import uuid as uuidlib
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np
from numpy.typing import NDArray

from .._version import __version__
from ..errors import ConfigError
from ..io.jsonable import dumps_jsonable, to_jsonable

__all__ = [
    "ChannelLayout",
    "claim_path",
    "CLAIM_PREFIX",
    "client_lock",
    "create_dataset",
    "FAILED",
    "FORMAT",
    "Layout",
    "LOCK_NAME",
    "OK",
    "PENDING",
    "read_attrs",
    "read_claim",
    "read_status",
    "RECORDS_DIR",
    "remove_stale_temporaries",
    "RUN_ARRAYS",
    "RunWriter",
    "STATUS_NAMES",
    "write_claim",
]

#: identifies a sweep dataset (root attribute ``format``)
FORMAT = "bearingsim.Sweep/1"
#: values of the ``status`` array
PENDING, OK, FAILED = 0, 1, 2
STATUS_NAMES = {PENDING: "pending", OK: "ok", FAILED: "failed"}
#: per-run bookkeeping arrays (besides the channels)
RUN_ARRAYS = ("status", "error")
#: directory (inside the dataset) of the per-run records, one JSON-lines file per writer process
RECORDS_DIR = "records"
#: lock file of the client running a sweep on the dataset
LOCK_NAME = "records/.lock"
#: claim files (``records/.claim-<task id>``): the client hands the tail of a task to a helper
CLAIM_PREFIX = ".claim-"


@dataclass(frozen=True)
class ChannelLayout:
    """One stored channel: name, unit and an optional second dimension (e.g. ``ball``)."""

    name: str
    units: str
    extra_dim: str | None = None
    n_extra: int = 0


@dataclass(frozen=True)
class Layout:
    """Array shapes of a dataset.

    Attributes
    ----------
    n_runs : int
        Number of runs.
    n_time : int
        Samples per run (the longest run; shorter runs are NaN-padded).
    fs_hz : float or None
        Common sample rate [Hz] when every run has the same rate and length, else ``None``.
    channels : tuple of ChannelLayout
        Stored channels.
    """

    n_runs: int
    n_time: int
    fs_hz: float | None
    channels: tuple[ChannelLayout, ...]

    @property
    def time_dim(self) -> str:
        """``time`` (uniform runs, with a time coordinate) or ``sample``."""
        return "time" if self.fs_hz is not None else "sample"


# ---------------------------------------------------------------------------- chunk writing
_tmp_counter = itertools.count()


def _atomic_write(path: str, data: bytes) -> None:
    """Write ``data`` to a temporary file beside ``path`` and rename it onto ``path``."""
    d, name = os.path.split(path)
    tmp = os.path.join(d, f".{name}.{os.getpid()}-{threading.get_ident()}-{next(_tmp_counter)}.tmp")
    fd = os.open(tmp, os.O_WRONLY | os.O_CREAT | os.O_EXCL, 0o644)
    try:
        view = memoryview(data)
        while view:
            view = view[os.write(fd, view) :]
    finally:
        os.close(fd)
    try:
        os.replace(tmp, path)
    except BaseException:
        with contextlib.suppress(OSError):
            os.unlink(tmp)
        raise


class _ChunkCodec:
    """Encoder of one array's per-run chunk, from the array's own zarr v2 metadata.

    Parameters
    ----------
    root : Path
        The dataset directory.
    name : str
        The array (its directory inside ``root``).
    zarray : dict
        The array's ``.zarray`` document (shape, chunks, dtype, filters, compressor,
        dimension_separator).
    """

    def __init__(self, root: Path, name: str, zarray: dict[str, Any]) -> None:
        import numcodecs

        self.dir = str(Path(root) / name)
        self.chunk_shape = tuple(zarray["chunks"])
        self.filters = tuple(numcodecs.get_codec(f) for f in zarray.get("filters") or ())
        comp = zarray.get("compressor")
        self.compressor = None if comp is None else numcodecs.get_codec(comp)
        self.sep = zarray.get("dimension_separator") or "."
        self.ndim = len(zarray["shape"])
        self.dtype = np.dtype(object) if self.filters else np.dtype(zarray["dtype"])

    @classmethod
    def from_store(cls, root: str | Path, name: str) -> _ChunkCodec:
        """The codec of array ``name`` from its ``.zarray`` file."""
        with open(Path(root) / name / ".zarray", encoding="utf-8") as fh:
            return cls(Path(root), name, json.load(fh))

    def encode(self, chunk: Any) -> bytes:
        """Chunk bytes as zarr v2 stores them: filters in order, then the compressor."""
        buf: Any = np.ascontiguousarray(chunk, dtype=self.dtype).reshape(self.chunk_shape)
        for f in self.filters:
            buf = f.encode(buf)
        if self.compressor is not None:
            buf = self.compressor.encode(buf)
        return buf if isinstance(buf, bytes) else memoryview(buf).tobytes()

    def path(self, i: int) -> str:
        """File of the per-run chunk ``i``."""
        return os.path.join(self.dir, self.sep.join(map(str, (i,) + (0,) * (self.ndim - 1))))

    def write(self, i: int, chunk: Any) -> None:
        _atomic_write(self.path(i), self.encode(chunk))


class RunWriter:
    """Commits runs into an existing dataset (see the module docstring for the protocol).

    Parameters
    ----------
    path : str or Path
        The dataset directory.
    uuid : str, optional
        Expected dataset id; a different id raises :class:`ConfigError` (a stale copy).
    """

    def __init__(self, path: str | Path, uuid: str | None = None) -> None:
        self.path = Path(path)
        # the consolidated metadata written at creation (never changed afterwards): one small
        # JSON read instead of opening the group through zarr-python (~3 ms)
        try:
            with open(self.path / ".zmetadata", encoding="utf-8") as fh:
                md = json.load(fh)["metadata"]
        except (OSError, ValueError, KeyError):
            raise ConfigError(
                f"dataset = {str(path)!r} is not a bearingsim sweep dataset"
            ) from None
        attrs = md.get(".zattrs", {})
        if attrs.get("format") != FORMAT:
            raise ConfigError(f"dataset = {str(path)!r} is not a bearingsim sweep dataset")
        if uuid is not None and attrs.get("uuid") != uuid:
            raise ConfigError(
                f"dataset = {str(path)!r} has uuid {attrs.get('uuid')!r}, expected {uuid!r}"
            )
        self.uuid = attrs["uuid"]
        self.n_time = int(attrs["n_time"])
        chans = attrs["channels"]
        self.series = [c["name"] for c in chans if not c["extra_dim"]]
        self.wide = {c["name"]: int(c["n_extra"]) for c in chans if c["extra_dim"]}
        names = list(RUN_ARRAYS) + list(self.wide) + (["signal"] if self.series else [])
        self.codecs = {name: _ChunkCodec(self.path, name, md[f"{name}/.zarray"]) for name in names}
        self._status_dir = self.codecs["status"].dir + os.sep
        self._log: int | None = None  # this process's records file (opened on first commit)

    def _log_fd(self) -> int:
        if self._log is None:
            name = f"{socket.gethostname()}-{os.getpid()}-{uuidlib.uuid4().hex[:8]}.jsonl"
            self._log = os.open(
                self.path / RECORDS_DIR / name, os.O_WRONLY | os.O_CREAT | os.O_APPEND, 0o644
            )
        return self._log

    def close(self) -> None:
        """Close this process's records file."""
        if self._log is not None:
            os.close(self._log)
            self._log = None

    def __del__(self) -> None:
        with contextlib.suppress(Exception):
            self.close()

    def status_of(self, i: int) -> int:
        """Status of run ``i`` from its marker file (:data:`PENDING` when absent)."""
        try:
            fd = os.open(self._status_dir + str(i), os.O_RDONLY)
        except FileNotFoundError:
            return PENDING
        try:
            b = os.read(fd, 2)
        finally:
            os.close(fd)
        return b[0] if len(b) == 1 and b[0] in (OK, FAILED) else PENDING

    def committed(self, i: int) -> bool:
        """Whether run ``i`` has its commit marker (status ok or failed)."""
        return self.status_of(i) != PENDING

    def _signal(self, channels: dict[str, NDArray]) -> NDArray[np.float64]:
        """The (1, n_channel, n_time) chunk of the time series (NaN where absent or short)."""
        xs = [
            np.asarray(channels[k], dtype=np.float64) if k in channels else None
            for k in self.series
        ]
        if all(x is not None and x.shape == (self.n_time,) for x in xs):
            return np.stack(xs)[None]  # type: ignore[arg-type]
        out = np.full((1, len(self.series), self.n_time), np.nan)
        for k, x in enumerate(xs):
            if x is not None:
                out[0, k, : x.shape[0]] = x
        return out

    def _wide(self, name: str, x: NDArray) -> NDArray[np.float64]:
        a = np.asarray(x, dtype=np.float64)
        out = np.full((1, self.n_time, self.wide[name]), np.nan)
        out[0, : a.shape[0], : a.shape[1]] = a
        return out

    def commit(
        self,
        i: int,
        status: int,
        record: dict[str, Any],
        error: str = "",
        channels: dict[str, NDArray] | None = None,
        rerun: bool = True,
    ) -> None:
        """Commit run ``i``: data chunks, error, record, then the ``status`` marker last.

        Parameters
        ----------
        i : int
            Run number.
        status : int
            :data:`OK` or :data:`FAILED`.
        record : dict
            ``{"compute_s": [s], "host", "pid", "meta": SimulationResult.meta, ...}``.
        error : str
            ``"ErrorType: message"`` of a failed run.
        channels : dict, optional
            The run's arrays by channel name (stored ones are picked).
        rerun : bool
            The run may have been committed as failed before (``False`` skips removing a stale
            error chunk).
        """
        if status not in (OK, FAILED):
            raise ConfigError(
                f"status = {status!r} is invalid; valid: {OK} (ok), {FAILED} (failed)"
            )
        c = self.codecs
        if channels:
            if self.series:
                c["signal"].write(i, self._signal(channels))
            for name in self.wide:
                if name in channels:
                    c[name].write(i, self._wide(name, channels[name]))
        if error:
            c["error"].write(i, np.array([error], dtype=object))
        elif rerun:  # a retried run that succeeds drops its old error
            with contextlib.suppress(FileNotFoundError):
                os.unlink(c["error"].path(i))
        line = {"run": i, "status": status, "t": time.time(), **record}
        os.write(self._log_fd(), (dumps_jsonable(line) + "\n").encode())
        self._mark(i, status)  # the commit marker, last

    def _mark(self, i: int, status: int) -> None:
        """Overwrite the one byte of run ``i``'s ``status`` chunk (created with the dataset) in
        place: a one-byte write cannot be torn; no file is created, nothing is renamed."""
        fd = os.open(self._status_dir + str(i), os.O_WRONLY)
        try:
            os.pwrite(fd, bytes((status,)), 0)
        finally:
            os.close(fd)


# ---------------------------------------------------------------------------- creation
def _dims(a, dims: list[str]) -> None:
    a.attrs["_ARRAY_DIMENSIONS"] = dims


def _coord_array(values: list[Any]) -> NDArray:
    """Per-run coordinate values as one NumPy array (numbers, bools or strings)."""
    if all(isinstance(v, bool) for v in values):
        return np.array(values, dtype=bool)
    if all(isinstance(v, int) and not isinstance(v, bool) for v in values):
        return np.array(values, dtype=np.int64)
    if all(isinstance(v, int | float) and not isinstance(v, bool) for v in values):
        return np.array(values, dtype=np.float64)
    return np.array(["" if v is None else str(v) for v in values], dtype=object)


def create_dataset(
    path: str | Path,
    layout: Layout,
    attrs: dict[str, Any],
    coords: dict[str, list[Any]],
    scenarios: list[dict[str, Any]],
) -> str:
    """Create an empty dataset atomically (temporary directory renamed into place).

    Parameters
    ----------
    path : str or Path
        Dataset directory (must not exist).
    layout : Layout
        Shapes and channels.
    attrs : dict
        Root attributes to add (spec, hash, label, ...).
    coords : dict
        Per-run coordinate values by scenario key.
    scenarios : list of dict
        Full scenario of every run.

    Returns
    -------
    str
        The new dataset's uuid.
    """
    import numcodecs
    import zarr

    dest = Path(path)
    if dest.exists():
        raise ConfigError(f"out = {str(dest)!r} exists already")
    dest.parent.mkdir(parents=True, exist_ok=True)
    uid = uuidlib.uuid4().hex
    tmp = dest.parent / f".{dest.name}.creating-{uid}"
    n, t = layout.n_runs, layout.n_time
    tdim = layout.time_dim
    blosc = numcodecs.Blosc(cname="lz4", clevel=5, shuffle=numcodecs.Blosc.SHUFFLE)
    try:
        g = zarr.open_group(str(tmp), mode="w-", zarr_format=2)
        coord_names = list(coords)
        run = g.create_array(
            "run", shape=(n,), chunks=(min(n, 65536),), dtype="int64", fill_value=None
        )
        _dims(run, ["run"])
        run[:] = np.arange(n)
        if layout.fs_hz is not None:
            tm = g.create_array("time", shape=(t,), chunks=(t,), dtype="float64", fill_value=None)
            _dims(tm, ["time"])
            tm.attrs["units"] = "s"
            tm.attrs["long_name"] = "nominal sample time k/fs"
            tm[:] = np.arange(t) / layout.fs_hz
        for key, values in coords.items():
            arr = _coord_array(values)
            dtype = str if arr.dtype == object else arr.dtype
            a = g.create_array(
                key, shape=(n,), chunks=(min(n, 65536),), dtype=dtype, fill_value=None
            )
            _dims(a, ["run"])
            a[:] = arr
        sj = g.create_array(
            "scenario_json", shape=(n,), chunks=(min(n, 4096),), dtype=str, fill_value=None
        )
        _dims(sj, ["run"])
        sj[:] = np.array([dumps_jsonable(s) for s in scenarios], dtype=object)
        series = [ch for ch in layout.channels if not ch.extra_dim]
        if series:
            nc = len(series)
            cn = g.create_array("channel", shape=(nc,), chunks=(nc,), dtype=str, fill_value=None)
            _dims(cn, ["channel"])
            cn[:] = np.array([ch.name for ch in series], dtype=object)
            cu = g.create_array("units", shape=(nc,), chunks=(nc,), dtype=str, fill_value=None)
            _dims(cu, ["channel"])
            cu[:] = np.array([ch.units for ch in series], dtype=object)
            a = g.create_array(
                "signal",
                shape=(n, nc, t),
                chunks=(1, nc, t),
                dtype="float64",
                fill_value=np.nan,
                compressors=blosc,
            )
            _dims(a, ["run", "channel", tdim])
            a.attrs["long_name"] = "stored time series; the unit of each channel is in 'units'"
            a.attrs["coordinates"] = " ".join(coord_names + ["units"])
        for ch in layout.channels:
            if not ch.extra_dim:
                continue
            a = g.create_array(
                ch.name,
                shape=(n, t, ch.n_extra),
                chunks=(1, t, ch.n_extra),
                dtype="float64",
                fill_value=np.nan,
                compressors=blosc,
            )
            _dims(a, ["run", tdim, ch.extra_dim])
            a.attrs["units"] = ch.units
            a.attrs["coordinates"] = " ".join(coord_names)
        st = g.create_array(
            "status", shape=(n,), chunks=(1,), dtype="int8", fill_value=None, compressors=None
        )
        _dims(st, ["run"])
        st.attrs["flag_values"] = [PENDING, OK, FAILED]
        st.attrs["flag_meanings"] = "pending ok failed"
        st.attrs["coordinates"] = " ".join(coord_names)
        a = g.create_array(
            "error", shape=(n,), chunks=(1,), dtype=str, fill_value=None, compressors=None
        )
        _dims(a, ["run"])
        # the records directory is a 0-d placeholder array, so that zarr's hierarchy walkers
        # accept it; the JSON-lines files (and the client lock) beside its chunk are ignored
        rec = g.create_array(RECORDS_DIR, shape=(), dtype="int8", fill_value=None, compressors=None)
        _dims(rec, [])
        rec.attrs["content"] = (
            "records/*.jsonl in this directory: one JSON line per committed run (status, "
            "compute_s, host, pid, bearingsim_version, meta = SimulationResult.meta)"
        )
        rec[...] = 0
        # every status chunk exists from the start, holding 0 (pending): a commit then only
        # overwrites its byte in place
        codec = _ChunkCodec.from_store(tmp, "status")
        zero = codec.encode(np.zeros(1, dtype=np.int8))
        for i in range(n):
            with open(codec.path(i), "xb") as fh:
                fh.write(zero)
        g.attrs.update(
            to_jsonable(
                {
                    **attrs,
                    "format": FORMAT,
                    "uuid": uid,
                    "n_runs": n,
                    "n_time": t,
                    "time_dim": tdim,
                    "fs_hz": layout.fs_hz,
                    "channels": [dataclasses.asdict(c) for c in layout.channels],
                    "coordinate_keys": coord_names,
                    "created_utc": time.strftime("%Y-%m-%dT%H:%M:%SZ", time.gmtime()),
                    "created_with": f"bearingsim {__version__}",
                }
            )
        )
        zarr.consolidate_metadata(str(tmp))
        os.rename(tmp, dest)
    except BaseException:
        shutil.rmtree(tmp, ignore_errors=True)
        raise
    return uid


def read_attrs(path: str | Path) -> dict[str, Any]:
    """Root attributes of a sweep dataset (``ConfigError`` if it is not one)."""
    p = Path(path)
    zattrs = p / ".zattrs"
    try:
        with open(zattrs, encoding="utf-8") as fh:
            attrs = json.load(fh)
    except (OSError, ValueError):
        raise ConfigError(
            f"dataset = {str(p)!r} is not a bearingsim sweep dataset (no readable .zattrs)"
        ) from None
    if attrs.get("format") != FORMAT:
        raise ConfigError(
            f"dataset = {str(p)!r} is not a bearingsim sweep dataset (format = "
            f"{attrs.get('format')!r}; valid: {FORMAT!r})"
        )
    return attrs


def read_status(path: str | Path) -> NDArray[np.int8]:
    """The ``status`` array (0 pending, 1 ok, 2 failed) of every run."""
    import zarr

    a = zarr.open_array(str(Path(path) / "status"), mode="r", zarr_format=2)
    return np.asarray(a[:], dtype=np.int8)


def claim_path(dataset: str | Path, task_id: str) -> str:
    """File by which the client hands the tail of task ``task_id`` to a helper task."""
    return os.path.join(dataset, RECORDS_DIR, CLAIM_PREFIX + task_id)


def write_claim(dataset: str | Path, task_id: str, keep: int) -> str:
    """Tell task ``task_id`` to stop before its run number ``keep`` (its position in the task);
    written atomically. Returns the claim file."""
    p = claim_path(dataset, task_id)
    _atomic_write(p, str(keep).encode())
    return p


def read_claim(path: str) -> int | None:
    """The ``keep`` of a claim file, ``None`` when there is none (a missing file: one failed
    ``stat``)."""
    try:
        with open(path, encoding="ascii") as fh:
            return int(fh.read())
    except (OSError, ValueError):
        return None


def remove_stale_temporaries(path: str | Path) -> int:
    """Delete temporary chunk files and claim files left by killed writers and clients; returns
    how many."""
    n = 0
    for d in Path(path).iterdir():
        if d.is_dir():
            for f in itertools.chain(d.glob(".*.tmp"), d.glob(CLAIM_PREFIX + "*")):
                with contextlib.suppress(OSError):
                    f.unlink()
                    n += 1
    return n


# ---------------------------------------------------------------------------- lock
@contextlib.contextmanager
def client_lock(path: str | Path):
    """Hold ``DATASET/records/.lock`` while a sweep client writes (one client at a time).

    A lock left by a dead process on this host is taken over; a live one (or one from another
    host) is an error naming its owner.
    """
    lock = Path(path) / LOCK_NAME
    me = {"host": socket.gethostname(), "pid": os.getpid()}
    for _ in range(2):
        try:
            fd = os.open(lock, os.O_WRONLY | os.O_CREAT | os.O_EXCL, 0o644)
        except FileExistsError:
            try:
                owner = json.loads(lock.read_text())
            except (OSError, ValueError):
                owner = {}
            if owner.get("host") == me["host"] and not _pid_alive(int(owner.get("pid", -1))):
                with contextlib.suppress(OSError):
                    lock.unlink()
                continue
            raise ConfigError(
                f"dataset = {str(path)!r} is in use by the sweep client {owner.get('host')}:"
                f"{owner.get('pid')}; if that process is gone, delete {str(lock)!r}"
            ) from None
        with os.fdopen(fd, "w") as fh:
            json.dump(me, fh)
        break
    try:
        yield
    finally:
        with contextlib.suppress(OSError):
            if json.loads(lock.read_text()).get("pid") == me["pid"]:
                lock.unlink()


def _pid_alive(pid: int) -> bool:
    if pid <= 0:
        return False
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    except PermissionError:
        return True
    return True
