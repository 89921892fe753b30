"""Sweep datasets for analysis and machine learning: :func:`open_dataset` → :class:`SweepDataset`.

The storage (layout, commit protocol, writer) is in :mod:`bearingsim.sweep_store`; the names most
used with a dataset are re-exported here.
"""

from __future__ import annotations

import json
from pathlib import Path
from typing import Any

import numpy as np
from numpy.typing import NDArray

from ..errors import ConfigError
from ..io.jsonable import to_jsonable
from .store import (
    FAILED,
    FORMAT,
    OK,
    PENDING,
    STATUS_NAMES,
    ChannelLayout,
    Layout,
    RunWriter,
    client_lock,
    create_dataset,
    damaged_error,
    lost_runs,
    lost_runs_error,
    read_attrs,
    read_error,
    read_metadata,
    read_records,
    read_status,
    remove_stale_temporaries,
)

#: at most this many axis values are listed per axis in a summary
SUMMARY_MAX_VALUES = 50


class SplitWarning(UserWarning):
    """A train/test split leaves a class out of one side (too few runs of that label)."""


class SweepDataset:
    """A sweep dataset (or a subset of its runs) ready for analysis and machine learning.

    Parameters
    ----------
    path : str or Path
        Dataset directory written by ``bearingsim sweep run``.
    runs : array of int, optional
        Run numbers of this view (default: every run).

    Examples
    --------
    >>> ds = open_dataset("faults.zarr").completed()            # doctest: +SKIP
    >>> train, test = ds.split("rpm", test=[1797])              # doctest: +SKIP
    >>> X, y = train.arrays(["acc_y"])     # X (n, 1, n_time) [m/s^2], y labels  # doctest: +SKIP
    """

    def __init__(self, path: str | Path, runs: NDArray[np.int64] | None = None, _xr=None) -> None:
        # absolute: a notebook that changes its working folder keeps reading the same
        # dataset (a relative path failed after os.chdir; twenty-first session)
        self.path = Path(path).absolute()
        self.attrs = read_attrs(self.path)
        self._ds = _xr if _xr is not None else self._open()
        n = int(self.attrs["n_runs"])
        self.runs = np.arange(n) if runs is None else np.asarray(runs, dtype=np.int64)

    def _open(self):
        """The dataset through xarray (lazy); a damaged one raises a one-line
        :class:`ConfigError` naming the file."""
        import xarray as xr

        read_metadata(self.path)  # names .zmetadata when it is not what xarray expects
        try:
            return xr.open_dataset(
                self.path, engine="zarr", chunks=None, cache=False, consolidated=True
            )
        except Exception as exc:  # any decoding error of metadata or an eagerly read coordinate
            raise self._damage(None, exc) from None

    def _damage(self, name: str | None, exc: BaseException, index: Any = None) -> ConfigError:
        """The error of an array that cannot be read, naming its first unreadable chunk file
        (among those of the runs ``index``, when given; for ``name=None`` of any array)."""
        names = [name] if name is not None else sorted(self._arrays())
        runs = None if index is None else np.atleast_1d(np.asarray(index, dtype=np.int64))
        for nm in names:
            bad = _bad_chunk(self.path, nm, runs)
            if bad is not None:
                if isinstance(bad[1], ConfigError):
                    return bad[1]
                return damaged_error(self.path, bad[0], "cannot be decoded", bad[1])
        where = self.path / name if name is not None else self.path
        return damaged_error(self.path, where, "cannot be read", exc)

    def _arrays(self) -> list[str]:
        """The small arrays (every one but the time series, whose chunks may be many GB)."""
        big = {"signal"} | {c["name"] for c in self.attrs["channels"] if c["extra_dim"]}
        md = read_metadata(self.path)
        return [
            k[: -len("/.zarray")]
            for k in md
            if k.endswith("/.zarray") and k[: -len("/.zarray")] not in big
        ]

    def _values(self, name: str, index: Any = None) -> NDArray:
        """Values of array ``name`` (all, or ``[index]`` along its first axis), read now."""
        try:
            v = self._ds[name].variable
            return np.asarray((v if index is None else v[index]).values)
        except ConfigError:
            raise
        except Exception as exc:  # a chunk that does not decode: a damaged dataset
            raise self._damage(name, exc, index) from None

    def _view(self, runs: NDArray[np.int64]) -> SweepDataset:
        return SweepDataset(self.path, runs, _xr=self._ds)

    def __len__(self) -> int:
        return int(self.runs.size)

    def __repr__(self) -> str:
        return f"SweepDataset({str(self.path)!r}, {len(self)} of {self.attrs['n_runs']} runs)"

    @property
    def xr(self):
        """The selected runs as an :class:`xarray.Dataset` (lazy; ``.load()`` to read).

        A run committed ok whose signal chunk is missing is refused here (one existence check
        per selected run, :meth:`check_data`): xarray would read it as NaN."""
        self.check_data()
        return self._ds.isel(run=self.runs)

    def check_data(self, runs: Any = None) -> NDArray[np.int8]:
        """Refuse (one-line :class:`ConfigError`) when a selected run committed ok has lost its
        signal chunk file, which a reader would serve as NaN (a dataset copied without its
        chunks, files deleted); pending and failed runs have no chunk, which is normal.

        Only the files' existence is checked (:func:`~bearingsim.sweep.store.lost_runs`: one
        ``stat`` per run, or one directory listing), no chunk is read.

        Parameters
        ----------
        runs : array of int, optional
            Run numbers to check (default: the selected runs).

        Returns
        -------
        ndarray of int8
            The status of every run of the dataset (read before the check).
        """
        st = read_status(self.path)
        md = read_metadata(self.path)
        lost = lost_runs(self.path, self.runs if runs is None else runs, st, md)
        if lost:
            raise lost_runs_error(self.path, lost, md)
        return st

    @property
    def channels(self) -> list[str]:
        """Stored channel names."""
        return [c["name"] for c in self.attrs["channels"]]

    @property
    def series(self) -> list[str]:
        """Stored time-series channels (the ``channel`` axis of ``signal``)."""
        return [c["name"] for c in self.attrs["channels"] if not c["extra_dim"]]

    def records(self) -> list[dict[str, Any]]:
        """Record of each selected run (``{}`` for a pending run): ``status``, ``compute_s``
        [s], ``host``, ``pid``, ``bearingsim_version``, ``warnings`` (the run's warnings, one
        ``"Category: message"`` line each; absent in older datasets), ``meta``
        (``SimulationResult.meta``).

        Read from the JSON-lines files in ``DATASET/records/``; when a run was computed more
        than once (a resume after a kill, ``--retry-failed``) the newest line whose status
        equals the committed status wins. Lines that are not valid records (cut by a kill, or
        garbage) are skipped (:func:`~bearingsim.sweep.store.read_records`).
        """
        best = read_records(self.path, read_status(self.path))
        return [best.get(int(i), {}) for i in self.runs]

    @property
    def label_keys(self) -> list[str]:
        """Scenario keys that form the label."""
        return list(self.attrs.get("label", []))

    @property
    def status(self) -> NDArray[np.int8]:
        """0 pending, 1 ok, 2 failed, per selected run (read now, so it is current)."""
        return read_status(self.path)[self.runs]

    def completed(self) -> SweepDataset:
        """Only the runs committed ok."""
        return self._view(self.runs[self.status == OK])

    def param(self, key: str) -> NDArray:
        """Per-run values of a coordinate (a swept or label key)."""
        if key not in self.attrs["coordinate_keys"]:
            raise ConfigError(
                f"key = {key!r} is not stored per run; valid: "
                + ", ".join(self.attrs["coordinate_keys"])
            )
        v = self._values(key)[self.runs]
        return v.astype(object) if v.dtype.kind == "T" else v  # numpy StringDType

    def labels(self, keys: str | list[str] | None = None) -> NDArray:
        """Class label of each selected run (label keys joined by ``|``)."""
        ks = self.label_keys if keys is None else ([keys] if isinstance(keys, str) else keys)
        if not ks:
            raise ConfigError("label: the dataset has no label keys; pass keys=")
        cols = [self.param(k).astype(str) for k in ks]
        if len(cols) == 1:
            return cols[0].astype(object)
        return np.array(["|".join(v) for v in zip(*cols, strict=True)], dtype=object)

    def _match(self, key: str, vals: Any) -> NDArray[np.bool_]:
        """Which runs have coordinate ``key`` among ``vals`` (a scalar, list, tuple, set or
        array; a rig file also by the name the sweep file gave it, resolved from the working
        folder: runs store it by its absolute path)."""
        from ..config import is_rig_file

        many = isinstance(vals, list | tuple | set | frozenset | range | np.ndarray)
        v = list(vals) if many else [vals]
        if key == "rig":
            v += [str(Path(x).resolve()) for x in v if is_rig_file(x)]
        return np.isin(self.param(key), np.asarray(v))

    def select(self, **conditions: Any) -> SweepDataset:
        """Runs whose coordinate ``key`` is one of the given values (a scalar or a list).

        A rig file may be named as the sweep file did (``rig="rig.toml"``, resolved from the
        working folder): runs store it by its absolute path. Values that match no run of a
        non-empty view are refused, naming the values present, and so are conditions that
        match runs each but none together (an empty selection was silent: twenty-first
        session)."""
        mask = np.ones(len(self), dtype=bool)
        for key, vals in conditions.items():
            hit = self._match(key, vals)
            if len(self) and not hit.any():
                raise ConfigError(
                    f"{key} = {vals!r} matches no run; values present: "
                    + ", ".join(map(str, np.unique(self.param(key))[:SUMMARY_MAX_VALUES]))
                )
            mask &= hit
        if len(self) and not mask.any():
            given = ", ".join(f"{k} = {v!r}" for k, v in conditions.items())
            raise ConfigError(
                f"{given}: no run has all of these; valid: values that occur together"
            )
        return self._view(self.runs[mask])

    def split(self, by: str, test: Any) -> tuple[SweepDataset, SweepDataset]:
        """Train/test split by parameter: runs with ``by`` in ``test`` form the test set (a
        rig file also by the sweep file's name, as :meth:`select`). A split that leaves a side
        empty is refused, as :meth:`random_split` does."""
        mask = self._match(by, test)
        if not mask.any():
            raise ConfigError(
                f"test = {test!r} matches no run for {by!r}; values present: "
                + ", ".join(map(str, np.unique(self.param(by))[:SUMMARY_MAX_VALUES]))
            )
        if mask.all():
            raise ConfigError(
                f"test = {test!r} holds every run ({by!r}: "
                + ", ".join(map(str, np.unique(self.param(by))[:SUMMARY_MAX_VALUES]))
                + "); valid: values that leave runs to train on"
            )
        return self._view(self.runs[~mask]), self._view(self.runs[mask])

    def random_split(
        self, test_fraction: float, seed: int = 0, stratify: bool = True
    ) -> tuple[SweepDataset, SweepDataset]:
        """Random train/test split (stratified by label when ``stratify``), seeded.

        Each label (each stratum; the whole view without ``stratify``) puts
        ``round(test_fraction * n)`` of its ``n`` runs into the test set. A split with an empty
        test or train set is refused (:class:`ConfigError` naming the counts); a label left
        out of one side while the other labels are on both warns (:class:`SplitWarning`).

        Parameters
        ----------
        test_fraction : float
            Fraction of the runs of each label in the test set; valid range (0, 1) [-].
        seed : int
            Seed of the choice [-].
        stratify : bool
            Split each label separately (when the dataset has label keys).
        """
        if not 0.0 < test_fraction < 1.0:
            raise ConfigError(
                f"test_fraction = {test_fraction!r} is out of range; valid range (0, 1)"
            )
        rng = np.random.default_rng(seed)
        strat = stratify and bool(self.label_keys)
        groups = self.labels() if strat else np.zeros(len(self), dtype=int)
        test = np.zeros(len(self), dtype=bool)
        short: list[str] = []
        for g in np.unique(groups):
            idx = np.flatnonzero(groups == g)
            k = int(round(test_fraction * idx.size))
            if k in (0, idx.size):
                side = "test" if k == 0 else "train"
                short.append(f"{g!s} ({idx.size} run(s), none in the {side} set)")
            test[rng.choice(idx, size=k, replace=False)] = True
        if not strat and self.label_keys:  # the labels land where the draw put them: each
            labels = self.labels()  # one on one side only is named as well (twenty-first
            for g in np.unique(labels):  # session: none was, the warning never came)
                on = test[labels == g]
                if on.all() or not on.any():
                    side = "train" if on.all() else "test"
                    short.append(f"{g!s} ({on.size} run(s), none in the {side} set)")
        n_test = int(test.sum())
        if n_test in (0, len(self)):
            side = "test" if n_test == 0 else "train"
            per = " of each label" if strat else ""
            raise ConfigError(
                f"test_fraction = {test_fraction!r} of {len(self)} run(s) leaves the {side} set "
                f"empty (round(test_fraction x the runs{per})"
                + (f": {', '.join(short[:5])}" if strat and short else "")
                + "); valid: a test_fraction that puts at least one run on each side"
                + (", or stratify=False" if strat else "")
            )
        if short:
            import warnings

            warnings.warn(
                f"random_split(test_fraction = {test_fraction!r}): label "
                + ", ".join(short[:5])
                + (f" and {len(short) - 5} more" if len(short) > 5 else "")
                + "; these labels are on one side only",
                SplitWarning,
                stacklevel=2,
            )
        return self._view(self.runs[~test]), self._view(self.runs[test])

    def arrays(
        self, channels: list[str] | None = None, label: str | list[str] | None = None
    ) -> tuple[NDArray[np.float64], NDArray]:
        """Signals and labels as NumPy arrays.

        Parameters
        ----------
        channels : list of str, optional
            Time-series channels to stack (default: every 1-D stored channel).
        label : str or list of str, optional
            Label keys (default: the dataset's).

        Returns
        -------
        X : ndarray, shape (n_runs, n_channels, n_time)
            Signals in their units (``self.xr[name].attrs["units"]``, SI). Runs of different
            lengths (e.g. a ``rig`` axis mixing 12 and 48 kHz profiles) are padded with NaN to
            the longest; each run's rate is its scenario's (``self.scenario(i)["fs_hz"]``).
        y : ndarray of str, shape (n_runs,)
            Labels.
        """
        one_d = self.series
        chans = one_d if channels is None else ([channels] if isinstance(channels, str)
                                                 else list(channels))  # fmt: skip
        for c in chans:
            if c not in one_d:
                raise ConfigError(
                    f"channel = {c!r} is not a stored time series; valid: " + ", ".join(one_d)
                )
        idx = [one_d.index(c) for c in chans]
        self.check_data()
        X = (
            self._values("signal", self.runs)[:, idx, :]
            if len(self)
            else np.empty((0, len(idx), 0))
        )
        return X, self.labels(label)

    def scenario(self, run: int) -> dict[str, Any]:
        """Full scenario of run number ``run``."""
        text = str(self._values("scenario_json", run))
        try:
            sc = json.loads(text)
        except ValueError as exc:
            sc = exc
        if not isinstance(sc, dict) or not all(
            isinstance(sc.get(k), int | float) and sc.get(k) > 0 for k in ("duration_s", "fs_hz")
        ):
            raise damaged_error(
                self.path,
                self.path / "scenario_json",
                f"holds no scenario for run {run} (a JSON object with duration_s and fs_hz)",
                sc if isinstance(sc, Exception) else None,
            )
        return sc

    def result(self, run: int):
        """Run number ``run`` as a :class:`~bearingsim.results.SimulationResult` (stored
        channels only; time = the nominal sample times)."""
        from ..results import SimulationResult

        n_runs = int(self.attrs["n_runs"])
        if isinstance(run, bool) or not isinstance(run, int | np.integer) or not 0 <= run < n_runs:
            raise ConfigError(
                f"run = {run!r} is out of range; valid range [0, {n_runs - 1}] integer"
            )
        run = int(run)
        st = int(self.check_data(np.array([run]))[run])
        if st != OK:
            raise ConfigError(f"run = {run} has status {STATUS_NAMES[st]!r}; valid: an ok run")
        sc = self.scenario(run)
        n = int(round(sc["duration_s"] * sc["fs_hz"]))
        chans, units, dims = {}, {}, {}
        series = self.series
        if series:
            sig = self._values("signal", run)
        for c in self.attrs["channels"]:
            if c["extra_dim"]:
                x = self._values(c["name"], run)[:n]
                z = int(np.sum(~np.all(np.isnan(x), axis=0)))
                if z == 0:
                    continue  # not produced by this run (e.g. per_ball = false)
                x = x[:, :z]
                dims[c["name"]] = ("time", c["extra_dim"])
            else:
                x = sig[series.index(c["name"]), :n]
            chans[c["name"]] = x
            units[c["name"]] = c["units"]
        meta = self._view(np.array([run])).records()[0].get("meta") or {}
        return SimulationResult(np.arange(n) / sc["fs_hz"], chans, units, sc, meta, dims)

    def summary(self, label: str | list[str] | None = None) -> dict[str, Any]:
        """Counts by label and by axis value, failures with their errors, totals, and each
        warning the runs raised with the runs that raised it (``warnings``: message -> runs)."""
        st = self.check_data()[self.runs]
        out: dict[str, Any] = {
            "path": str(self.path),
            "n_runs": len(self),
            "n_ok": int(np.sum(st == OK)),
            "n_failed": int(np.sum(st == FAILED)),
            "n_pending": int(np.sum(st == PENDING)),
        }
        out["complete"] = out["n_pending"] == 0
        names = ["pending", "ok", "failed"]

        def counts(values: NDArray) -> dict[str, dict[str, int]]:
            res: dict[str, dict[str, int]] = {}
            # numbers in their order, not as text (1200 before 900: exploratory testing,
            # twenty-fourth session); text, and numbers with a NaN, as text
            num = values.dtype.kind in "biuf" and not np.any(np.isnan(values.astype(float)))
            vals = values if num else values.astype(str)
            for v in np.unique(vals):
                m = vals == v
                res[str(v)] = {names[s]: int(np.sum(st[m] == s)) for s in (OK, FAILED, PENDING)}
            return res

        keys = self.label_keys if label is None else ([label] if isinstance(label, str) else label)
        out["label"] = keys
        out["by_label"] = counts(self.labels(keys)) if keys else {}
        by_axis = {}
        for key in self.attrs["coordinate_keys"]:
            v = self.param(key)
            if np.unique(v.astype(str)).size <= SUMMARY_MAX_VALUES:
                by_axis[key] = counts(v)
        out["by_axis"] = by_axis
        records = self.records()
        cs = np.array([r.get("compute_s", np.nan) for r in records], dtype=float)
        done = np.isfinite(cs)
        warned: dict[str, list[int]] = {}
        for j, r in enumerate(records):
            for w in dict.fromkeys(r.get("warnings") or ()):
                warned.setdefault(w, []).append(int(self.runs[j]))
        out["warnings"] = warned
        out["compute_s_total"] = float(cs[done].sum())
        out["compute_s_mean"] = float(cs[done].mean()) if done.any() else None
        coords = {k: self.param(k) for k in self.attrs["coordinate_keys"]}
        out["failures"] = [
            {
                "run": int(self.runs[j]),
                "params": {k: _scalar(v[j]) for k, v in coords.items()},
                "error": self._failure(int(self.runs[j])),
            }
            for j in np.flatnonzero(st == FAILED)
        ]
        out["spec_hash"] = self.attrs.get("spec_hash")
        return out

    def _failure(self, run: int) -> str:
        """The error of the failed run ``run``; a failed run always has one (its commit writes
        it), so a missing error chunk is damage."""
        err = read_error(self.path, run)
        if not err:
            raise damaged_error(
                self.path,
                self.path / "error" / str(run),
                f"is missing or empty (the error of run {run}, committed failed)",
                todo="run 'bearingsim sweep run' again with the dataset's sweep file, this "
                "dataset as -o and --retry-failed: it computes the failed runs again",
            )
        return err


def _bad_chunk(
    path: Path, name: str, runs: NDArray[np.int64] | None = None
) -> tuple[Path, BaseException] | None:
    """The first chunk file of array ``name`` that zarr cannot decode, with the error (``None``
    when every chunk decodes): the diagnosis of a damaged dataset, chunk by chunk (of the runs
    ``runs`` only, when given and the array has one chunk per run)."""
    import zarr

    try:
        a = zarr.open_array(str(path / name), mode="r", zarr_format=2)
    except Exception as exc:  # its .zarray
        return path / name / ".zarray", exc
    sep = getattr(a.metadata, "dimension_separator", None) or "."
    grid = list(np.ndindex(*a.cdata_shape))
    if runs is not None and a.ndim and a.chunks[0] == 1:
        grid = [(int(i),) + (0,) * (a.ndim - 1) for i in runs]
    for idx in grid:
        if name == "error":  # checked before decoding (see read_error)
            try:
                read_error(path, idx[0])
            except ConfigError as exc:
                return path / name / str(idx[0]), exc
            continue
        try:
            a.get_block_selection(idx)
        except Exception as exc:
            return path / name / sep.join(map(str, idx)), exc
    return None


def _scalar(v: Any) -> Any:
    """NumPy scalar → plain JSON-able Python value."""
    v = v.item() if isinstance(v, np.generic) else v
    return str(v) if not isinstance(v, bool | int | float) else to_jsonable(v)


def open_dataset(path: str | Path) -> SweepDataset:
    """Open a sweep dataset for reading (see :class:`SweepDataset`)."""
    return SweepDataset(path)


__all__ = [
    "FAILED",
    "FORMAT",
    "OK",
    "PENDING",
    "STATUS_NAMES",
    "ChannelLayout",
    "Layout",
    "RunWriter",
    "SplitWarning",
    "SweepDataset",
    "client_lock",
    "create_dataset",
    "open_dataset",
    "read_attrs",
    "read_status",
    "remove_stale_temporaries",
]
