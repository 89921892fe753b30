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
                            client's lock (:mod:`bearingsim.sweep.lock`; ``.lock.mutex``
                            stays) and claim files (``.claim-<task>``: the position in
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

Readers
-------
:func:`read_metadata`, :func:`read_attrs`, :func:`read_status`, :func:`read_error` and
:func:`read_records` check what they read: a damaged dataset (a file that is not UTF-8 JSON, a
missing or wrong status byte, an error chunk whose length field disagrees with its size, ...)
raises one :class:`~bearingsim.errors.ConfigError` line naming the file and what is wrong
(:func:`damaged_error`), never a decoding exception; record lines that are not records are
skipped (they are auxiliary: the status byte is the commit). A run committed ok always has its
``signal`` chunk (written before its status byte, never removed): :func:`lost_runs` finds the
runs whose chunk file is missing (data lost, e.g. a copy without the chunks) by the files'
existence alone, which the dataset readers refuse and a resume computes again.
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
from .lock import LOCK_NAME, LOCK_TEMP_PREFIX, ClientLock, client_lock, remove_stale_creations

__all__ = [
    "ChannelLayout",
    "claim_path",
    "CLAIM_PREFIX",
    "client_lock",
    "create_dataset",
    "damaged_error",
    "DatasetExistsError",
    "FAILED",
    "FORMAT",
    "Layout",
    "LIST_DIR_RUNS",
    "LOCK_NAME",
    "lost_runs",
    "lost_runs_error",
    "OK",
    "PENDING",
    "read_attrs",
    "read_claim",
    "read_error",
    "read_metadata",
    "read_records",
    "read_status",
    "RECORDS_DIR",
    "remove_stale_temporaries",
    "RUN_ARRAYS",
    "RunWriter",
    "signal_chunk",
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
#: claim files (``records/.claim-<task id>``): the client hands the tail of a task to a helper
CLAIM_PREFIX = ".claim-"
#: :func:`lost_runs` checks more runs than this with one listing of the ``signal`` directory
#: instead of one ``stat`` per run
LIST_DIR_RUNS = 64


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
        md = read_metadata(path)
        attrs = md[".zattrs"]
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
        self.codecs = {}
        for name in names:
            try:
                self.codecs[name] = _ChunkCodec(self.path, name, md[f"{name}/.zarray"])
            except Exception as exc:  # a damaged .zarray entry: any decoding error
                raise damaged_error(
                    path, _zmetadata(path), f"its entry {name + '/.zarray'!r} is invalid", exc
                ) from None
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

    def mark_pending(self, i: int) -> None:
        """Set run ``i`` back to pending (its data were lost, :func:`lost_runs`), so that it is
        computed again: one byte written in place, by the client holding the lock."""
        self._mark(i, PENDING)

    def _mark(self, i: int, status: int) -> None:
        """Overwrite the one byte of run ``i``'s ``status`` chunk (created with the dataset) in
        place: a one-byte write cannot be torn; no file is created, nothing is renamed."""
        fd = os.open(self._status_dir + str(i), os.O_WRONLY)
        try:
            os.pwrite(fd, bytes((status,)), 0)
        finally:
            os.close(fd)


# ---------------------------------------------------------------------------- creation
class DatasetExistsError(ConfigError):
    """The dataset directory exists (e.g. another client created it first)."""


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
    lock: ClientLock | None = None,
) -> str:
    """Create an empty dataset atomically (temporary directory renamed into place).

    Two clients creating the same dataset at once: exactly one rename succeeds, the other
    client gets :class:`DatasetExistsError` and its temporary directory is removed; the winner's
    dataset is untouched. Temporary directories of creations whose client is gone are removed
    first (:func:`~bearingsim.sweep.lock.remove_stale_creations`).

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
    lock : ClientLock, optional
        Written into the dataset before it is renamed into place, so that the dataset is
        locked by this client from its first instant (the caller then calls
        :meth:`ClientLock.adopt`).

    Returns
    -------
    str
        The new dataset's uuid.

    Raises
    ------
    DatasetExistsError
        ``path`` exists (before, or created by another client meanwhile).
    """
    import numcodecs
    import zarr

    dest = Path(path)
    if dest.exists():
        raise DatasetExistsError(f"out = {str(dest)!r} exists already")
    dest.parent.mkdir(parents=True, exist_ok=True)
    remove_stale_creations(dest)
    uid = uuidlib.uuid4().hex
    tmp = dest.parent / f".{dest.name}.creating-{uid}"
    n, t = layout.n_runs, layout.n_time
    tdim = layout.time_dim
    blosc = numcodecs.Blosc(cname="lz4", clevel=5, shuffle=numcodecs.Blosc.SHUFFLE)
    try:
        g = zarr.open_group(str(tmp), mode="w-", zarr_format=2)
        if lock is not None:  # first, so that a concurrent client can tell whether we live
            lock.write_into(tmp)
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
        try:
            os.rename(tmp, dest)
        except OSError:
            if not dest.exists():
                raise
            # another client renamed its dataset into place first (ENOTEMPTY/EEXIST)
            raise DatasetExistsError(
                f"out = {str(dest)!r} was created by another client meanwhile"
            ) from None
    except BaseException:
        shutil.rmtree(tmp, ignore_errors=True)
        raise
    return uid


# ---------------------------------------------------------------------------- readers
def _error_text(exc: BaseException) -> str:
    return f"{type(exc).__name__}: {' '.join(str(exc).split())}"


def damaged_error(
    dataset: str | Path,
    file: str | Path,
    what: str,
    exc: BaseException | None = None,
    valid: str | None = None,
    todo: str = "delete the dataset and run the sweep again",
) -> ConfigError:
    """The one-line error of a damaged dataset: the file, what is wrong with it (and the
    decoding error ``exc``), what would be valid, what to do."""
    if isinstance(exc, PermissionError):  # not damage: deleting would be the wrong advice
        # (exploratory testing, twenty-seventh session: a file of another user's mode 000)
        return ConfigError(
            f"dataset = {str(dataset)!r}: {str(file)!r} cannot be read (permission denied); "
            "check its permissions, or ask the dataset's owner"
        )
    why = "" if exc is None else f" ({_error_text(exc)})"
    ok = "" if valid is None else f"; valid: {valid}"
    return ConfigError(
        f"dataset = {str(dataset)!r} is damaged: {str(file)!r} {what}{why}{ok}; {todo}"
    )


def signal_chunk(path: str | Path, run: int, zarray: dict[str, Any]) -> Path:
    """File of run ``run``'s chunk of the ``signal`` array (``zarray``: its ``.zarray``)."""
    sep = zarray.get("dimension_separator")
    sep = sep if sep in (".", "/") else "."
    return Path(path) / "signal" / sep.join(map(str, (run,) + (0,) * (len(zarray["shape"]) - 1)))


def lost_runs(
    path: str | Path,
    runs: Any,
    status: NDArray[np.int8],
    metadata: dict[str, Any] | None = None,
) -> list[int]:
    """The runs among ``runs`` committed ok whose ``signal`` chunk file is missing: their data
    are lost (a dataset copied without its chunks, files deleted), not pending.

    A run committed ok always has its signal chunk: the commit renames the chunk into place
    before it writes the status byte, and nothing removes a chunk afterwards (a rewrite
    replaces it atomically). Pending and failed runs have none, which is normal. Only the
    existence of the files is checked (one ``stat`` per run, or one listing of the directory
    for more than :data:`LIST_DIR_RUNS` runs), no chunk is read. Per-ball channels are not
    checked: a run that does not produce them (``per_ball = false``) has no chunk either.

    Parameters
    ----------
    path : str or Path
        The dataset.
    runs : array of int
        Run numbers to check.
    status : ndarray of int8
        :func:`read_status`, read *before* this call (a run seen ok then had its chunk
        already, so a run committed meanwhile is no false alarm).
    metadata : dict, optional
        :func:`read_metadata` of the dataset (read when not given).

    Returns
    -------
    list of int
        The runs that lost their signal chunk, in the order of ``runs``.
    """
    md = read_metadata(path) if metadata is None else metadata
    zarray = md.get("signal/.zarray")
    if zarray is None:  # no time series stored
        return []
    ok = [
        int(i)
        for i in np.asarray(runs, dtype=np.int64).ravel()
        if 0 <= i < status.size and status[i] == OK
    ]
    if len(ok) <= LIST_DIR_RUNS or zarray.get("dimension_separator") == "/":  # nested keys
        return [i for i in ok if not os.path.exists(signal_chunk(path, i, zarray))]
    sdir = Path(path) / "signal"
    try:
        names = set(os.listdir(sdir))
    except OSError as exc:
        raise damaged_error(path, sdir, f"cannot be listed ({exc.strerror})") from None
    return [i for i in ok if signal_chunk(path, i, zarray).name not in names]


def lost_runs_error(dataset: str | Path, lost: list[int], metadata: dict[str, Any]) -> ConfigError:
    """The one-line error of a dataset whose runs ``lost`` (:func:`lost_runs`) are committed ok
    but lost their signal chunk, with what to do: ``sweep run`` computes them again."""
    i = lost[0]
    more = ""
    if len(lost) > 1:
        shown = ", ".join(map(str, lost[:10])) + (", ..." if len(lost) > 10 else "")
        more = f"; {len(lost)} runs committed ok have lost theirs: {shown}"
    return damaged_error(
        dataset,
        signal_chunk(dataset, i, metadata["signal/.zarray"]),
        f"is missing (the signal chunk of run {i}, committed ok{more})",
        todo="run 'bearingsim sweep run' again with the dataset's sweep file and this dataset "
        "as -o: it computes the runs whose signal chunk is missing again",
    )


def _zmetadata(path: str | Path) -> Path:
    return Path(path) / ".zmetadata"


def _load_json(dataset: str | Path, file: Path, missing: str) -> Any:
    """The JSON document ``file`` of a dataset; a file that cannot be read is ``missing`` (a
    one-line :class:`ConfigError`), one that is not UTF-8 JSON is damage."""
    try:
        with open(file, "rb") as fh:
            raw = fh.read()
    except OSError:
        if not Path(dataset).exists():  # (exploratory testing, twenty-seventh session)
            raise ConfigError(
                f"dataset = {str(dataset)!r} does not exist; valid: a sweep dataset "
                "directory (sweep run -o)"
            ) from None
        raise ConfigError(
            f"dataset = {str(dataset)!r} is not a bearingsim sweep dataset ({missing})"
        ) from None
    try:
        return json.loads(raw.decode("utf-8"))
    except UnicodeDecodeError as exc:
        raise damaged_error(dataset, file, "is not UTF-8 text", exc) from None
    except ValueError as exc:
        raise damaged_error(dataset, file, "is not valid JSON", exc) from None


def _check_attrs(dataset: str | Path, file: Path, attrs: Any) -> dict[str, Any]:
    """The root attributes ``attrs`` read from ``file``, checked for what the readers use."""
    if not isinstance(attrs, dict):
        raise damaged_error(dataset, file, f"holds a JSON {type(attrs).__name__}, not an object")
    if attrs.get("format") != FORMAT:
        raise ConfigError(
            f"dataset = {str(dataset)!r} is not a bearingsim sweep dataset (format = "
            f"{attrs.get('format')!r}; valid: {FORMAT!r})"
        )

    def bad(key: str, valid: str) -> ConfigError:
        return damaged_error(dataset, file, f"has {key} = {attrs.get(key)!r}", valid=valid)

    def count(v: Any) -> bool:
        return isinstance(v, int) and not isinstance(v, bool) and v >= 0

    if not isinstance(attrs.get("uuid"), str):
        raise bad("uuid", "a string")
    for key in ("n_runs", "n_time"):
        if not count(attrs.get(key)):
            raise bad(key, "an integer >= 0")
    chans = attrs.get("channels")
    if not isinstance(chans, list) or not all(
        isinstance(c, dict)
        and isinstance(c.get("name"), str)
        and isinstance(c.get("units"), str)
        and (c.get("extra_dim") is None or isinstance(c.get("extra_dim"), str))
        and count(c.get("n_extra", 0))
        for c in chans
    ):
        raise bad("channels", "a list of {name, units, extra_dim, n_extra}")
    for key in ("coordinate_keys", "label", "axes"):
        v = attrs.get(key, [])
        if not isinstance(v, list) or not all(isinstance(k, str) for k in v):
            raise bad(key, "a list of strings")
    return attrs


def read_metadata(path: str | Path) -> dict[str, Any]:
    """The consolidated metadata of a sweep dataset (``.zmetadata``: every ``.zarray`` and
    ``.zattrs`` by key), checked; any problem is a one-line :class:`ConfigError` naming the
    file and what is wrong with it."""
    file = _zmetadata(path)
    doc = _load_json(path, file, "no readable .zmetadata")
    md = doc.get("metadata") if isinstance(doc, dict) else None
    if not isinstance(md, dict) or not all(isinstance(v, dict) for v in md.values()):
        raise damaged_error(path, file, "has no 'metadata' object of JSON objects")
    _check_attrs(path, file, md.get(".zattrs", {}))
    for name in ("status", "error", "scenario_json", RECORDS_DIR):
        if f"{name}/.zarray" not in md:
            raise damaged_error(path, file, f"has no entry {name + '/.zarray'!r}")
    for key, za in md.items():
        if key.endswith(".zarray") and not _zarray_ok(za):
            raise damaged_error(
                path,
                file,
                f"has an invalid entry {key!r}",
                valid="a zarr v2 array: shape and chunks (integer lists of one length), dtype, "
                "compressor and filters (null or codec objects with an id), zarr_format 2",
            )
    return md


def _zarray_ok(za: dict[str, Any]) -> bool:
    """Whether ``za`` has the fields of a zarr v2 ``.zarray`` document that readers use."""

    def ints(v: Any) -> bool:
        return isinstance(v, list) and all(
            isinstance(x, int) and not isinstance(x, bool) and x >= 0 for x in v
        )

    def codec(c: Any) -> bool:
        return isinstance(c, dict) and isinstance(c.get("id"), str)

    filters = za.get("filters")
    return (
        ints(za.get("shape"))
        and ints(za.get("chunks"))
        and len(za["shape"]) == len(za["chunks"])
        and isinstance(za.get("dtype"), str | list)
        and (za.get("compressor") is None or codec(za["compressor"]))
        and (filters is None or (isinstance(filters, list) and all(map(codec, filters))))
        and za.get("zarr_format") == 2
    )


def read_attrs(path: str | Path) -> dict[str, Any]:
    """Root attributes of a sweep dataset (``.zattrs``), checked; a directory that is not a
    sweep dataset, or a damaged one, raises a one-line :class:`ConfigError`."""
    file = Path(path) / ".zattrs"
    return _check_attrs(path, file, _load_json(path, file, "no readable .zattrs"))


def read_status(path: str | Path) -> NDArray[np.int8]:
    """The ``status`` of every run (0 pending, 1 ok, 2 failed), read from its one-byte chunks.

    A chunk that is missing or does not hold one of those bytes means a damaged dataset (every
    chunk is written when the dataset is created, and only its byte changes afterwards): a
    one-line :class:`ConfigError` naming the file.
    """
    sdir = Path(path) / "status"
    zarray = sdir / ".zarray"
    meta = _load_json(path, zarray, "no readable status/.zarray")
    ok = (
        isinstance(meta, dict)
        and isinstance(meta.get("shape"), list)
        and len(meta["shape"]) == 1
        and isinstance(meta["shape"][0], int)
        and meta["shape"][0] >= 0
        and meta.get("chunks") == [1]
        and meta.get("dtype") == "|i1"
        and meta.get("compressor") is None
        and not meta.get("filters")
    )
    if not ok:
        raise damaged_error(
            path, zarray, "does not describe one uncompressed int8 byte per run (chunks [1])"
        )
    n = meta["shape"][0]
    out = np.empty(n, dtype=np.int8)
    prefix = str(sdir) + os.sep
    for i in range(n):
        name = prefix + str(i)
        try:
            fd = os.open(name, os.O_RDONLY)
        except FileNotFoundError:
            raise damaged_error(path, name, f"is missing (the status chunk of run {i})") from None
        except OSError as exc:
            raise damaged_error(path, name, f"cannot be read ({exc.strerror})") from None
        try:
            b = os.read(fd, 2)
        except OSError as exc:
            raise damaged_error(path, name, f"cannot be read ({exc.strerror})") from None
        finally:
            os.close(fd)
        if len(b) != 1 or b[0] not in STATUS_NAMES:
            raise damaged_error(
                path,
                name,
                "is empty" if not b else f"holds {b!r}" + ("..." if len(b) > 1 else ""),
                valid="one byte 0 (pending), 1 (ok) or 2 (failed)",
            )
        out[i] = b[0]
    return out


def read_error(path: str | Path, run: int) -> str:
    """The ``error`` of run ``run`` (``""`` when it has none), decoded from its chunk file.

    The chunk is checked before it is decoded (one VLenUTF8 item: count 1, then the length of
    the UTF-8 text and the text, as written by :class:`RunWriter`): a damaged length field would
    otherwise make the decoder allocate whatever it says. Anything else raises a one-line
    :class:`ConfigError` naming the file.
    """
    f = Path(path) / "error" / str(run)
    try:
        with open(f, "rb") as fh:
            b = fh.read()
    except FileNotFoundError:
        return ""
    except OSError as exc:
        raise damaged_error(path, f, f"cannot be read ({exc.strerror})") from None
    n = int.from_bytes(b[:4], "little") if len(b) >= 8 else -1
    size = int.from_bytes(b[4:8], "little") if n == 1 else -1
    if size != len(b) - 8:
        raise damaged_error(
            path,
            f,
            f"holds {len(b)} bytes that are not one text item",
            valid="a VLenUTF8 chunk of one item (count 1, length, UTF-8 text)",
        )
    try:
        return b[8:].decode("utf-8")
    except UnicodeDecodeError as exc:
        raise damaged_error(path, f, "is not UTF-8 text", exc) from None


def records_offsets(path: str | Path) -> dict[str, int]:
    """Size of every ``records/*.jsonl`` file now [bytes] (:func:`read_records` ``since``)."""
    out = {}
    for f in (Path(path) / RECORDS_DIR).glob("*.jsonl"):
        with contextlib.suppress(OSError):
            out[f.name] = f.stat().st_size
    return out


def _record(line: bytes) -> dict[str, Any] | None:
    """One record line, ``None`` when it is not a valid record (cut by a killed writer)."""
    try:
        r = json.loads(line.decode("utf-8"))
    except ValueError:  # UnicodeDecodeError included
        return None
    if not isinstance(r, dict):
        return None
    i, st, t = r.get("run"), r.get("status"), r.get("t", 0.0)
    if not isinstance(i, int) or isinstance(i, bool) or st not in (OK, FAILED):
        return None
    if not isinstance(t, int | float) or isinstance(t, bool):
        return None
    for key in ("compute_s", "cpu_s"):
        v = r.get(key)
        if v is not None and (not isinstance(v, int | float) or isinstance(v, bool)):
            return None
    return r


def read_records(
    path: str | Path, status: NDArray[np.int8], since: dict[str, int] | None = None
) -> dict[int, dict[str, Any]]:
    """The record of every committed run, from ``records/*.jsonl``.

    Parameters
    ----------
    path : str or Path
        The dataset.
    status : ndarray of int8
        :func:`read_status`: only a line whose status equals the run's committed status
        counts; of those the newest (``t``) wins.
    since : dict, optional
        :func:`records_offsets` taken earlier: only the lines appended since then are read.

    Returns
    -------
    dict
        Record by run number. Lines that are not valid records (cut by a killed writer, or
        garbage) are skipped; a records file that cannot be read raises a one-line
        :class:`ConfigError` naming it.
    """
    best: dict[int, dict[str, Any]] = {}
    for f in sorted((Path(path) / RECORDS_DIR).glob("*.jsonl")):
        start = 0 if since is None else since.get(f.name, 0)
        try:
            with open(f, "rb") as fh:
                fh.seek(start)
                data = fh.read()
        except OSError as exc:
            raise damaged_error(path, f, f"cannot be read ({exc.strerror})") from None
        for line in data.splitlines():
            r = _record(line)
            if r is None:
                continue
            i = r["run"]
            if 0 <= i < status.size and r["status"] == status[i]:
                if i not in best or r.get("t", 0.0) >= best[i].get("t", 0.0):
                    best[i] = r
    return best


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
    """Delete temporary chunk files, claim files and lock temporaries left by killed writers and
    clients; returns how many. Called by the client holding the lock."""
    n = 0
    for d in Path(path).iterdir():
        if d.is_dir():
            for f in itertools.chain(
                d.glob(".*.tmp"), d.glob(CLAIM_PREFIX + "*"), d.glob(LOCK_TEMP_PREFIX + "*")
            ):
                with contextlib.suppress(OSError):
                    f.unlink()
                    n += 1
    return n
