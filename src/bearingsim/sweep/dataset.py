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
    RECORDS_DIR,
    STATUS_NAMES,
    ChannelLayout,
    Layout,
    RunWriter,
    client_lock,
    create_dataset,
    read_attrs,
    read_status,
    remove_stale_temporaries,
)

#: at most this many axis values are listed per axis in a summary
SUMMARY_MAX_VALUES = 50


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
        import xarray as xr

        self.path = Path(path)
        self.attrs = read_attrs(self.path)
        self._ds = (
            _xr
            if _xr is not None
            else xr.open_dataset(
                self.path, engine="zarr", chunks=None, cache=False, consolidated=True
            )
        )
        n = int(self.attrs["n_runs"])
        self.runs = np.arange(n) if runs is None else np.asarray(runs, dtype=np.int64)

    def _view(self, runs: NDArray[np.int64]) -> SweepDataset:
        return SweepDataset(self.path, runs, _xr=self._ds)

    def __len__(self) -> int:
        return int(self.runs.size)

    def __repr__(self) -> str:
        return f"SweepDataset({str(self.path)!r}, {len(self)} of {self.attrs['n_runs']} runs)"

    @property
    def xr(self):
        """The selected runs as an :class:`xarray.Dataset` (lazy; ``.load()`` to read)."""
        return self._ds.isel(run=self.runs)

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
        [s], ``host``, ``pid``, ``bearingsim_version``, ``meta`` (``SimulationResult.meta``).

        Read from the JSON-lines files in ``DATASET/records/``; when a run was computed more
        than once (a resume after a kill, ``--retry-failed``) the newest line whose status
        equals the committed status wins.
        """
        status = read_status(self.path)
        best: dict[int, dict[str, Any]] = {}
        for f in sorted((self.path / RECORDS_DIR).glob("*.jsonl")):
            with open(f, encoding="utf-8") as fh:
                for line in fh:
                    try:
                        r = json.loads(line)
                        i = int(r["run"])
                    except (ValueError, KeyError, TypeError):
                        continue  # a line cut by a killed writer
                    if 0 <= i < status.size and r.get("status") == status[i]:
                        if i not in best or r.get("t", 0.0) >= best[i].get("t", 0.0):
                            best[i] = r
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
        v = np.asarray(self._ds[key].values)[self.runs]
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

    def select(self, **conditions: Any) -> SweepDataset:
        """Runs whose coordinate ``key`` is one of the given values (a scalar or a list)."""
        mask = np.ones(len(self), dtype=bool)
        for key, vals in conditions.items():
            v = vals if isinstance(vals, list | tuple | np.ndarray) else [vals]
            mask &= np.isin(self.param(key), np.asarray(v))
        return self._view(self.runs[mask])

    def split(self, by: str, test: Any) -> tuple[SweepDataset, SweepDataset]:
        """Train/test split by parameter: runs with ``by`` in ``test`` form the test set."""
        v = test if isinstance(test, list | tuple | np.ndarray) else [test]
        mask = np.isin(self.param(by), np.asarray(v))
        if not mask.any():
            raise ConfigError(
                f"test = {list(v)!r} matches no run for {by!r}; values present: "
                + ", ".join(map(str, np.unique(self.param(by))[:SUMMARY_MAX_VALUES]))
            )
        return self._view(self.runs[~mask]), self._view(self.runs[mask])

    def random_split(
        self, test_fraction: float, seed: int = 0, stratify: bool = True
    ) -> tuple[SweepDataset, SweepDataset]:
        """Random train/test split (stratified by label when ``stratify``), seeded."""
        if not 0.0 < test_fraction < 1.0:
            raise ConfigError(
                f"test_fraction = {test_fraction!r} is out of range; valid range (0, 1)"
            )
        rng = np.random.default_rng(seed)
        groups = self.labels() if stratify and self.label_keys else np.zeros(len(self), dtype=int)
        test = np.zeros(len(self), dtype=bool)
        for g in np.unique(groups):
            idx = np.flatnonzero(groups == g)
            k = int(round(test_fraction * idx.size))
            test[rng.choice(idx, size=k, replace=False)] = True
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
            Signals in their units (``self.xr[name].attrs["units"]``, SI).
        y : ndarray of str, shape (n_runs,)
            Labels.
        """
        one_d = self.series
        chans = one_d if channels is None else list(channels)
        for c in chans:
            if c not in one_d:
                raise ConfigError(
                    f"channel = {c!r} is not a stored time series; valid: " + ", ".join(one_d)
                )
        idx = [one_d.index(c) for c in chans]
        sig = self._ds["signal"].variable
        X = (
            np.asarray(sig[self.runs].values)[:, idx, :]
            if len(self)
            else np.empty((0, len(idx), 0))
        )
        return X, self.labels(label)

    def scenario(self, run: int) -> dict[str, Any]:
        """Full scenario of run number ``run``."""
        return json.loads(str(self._ds["scenario_json"].values[run]))

    def result(self, run: int):
        """Run number ``run`` as a :class:`~bearingsim.results.SimulationResult` (stored
        channels only; time = the nominal sample times)."""
        from ..results import SimulationResult

        st = int(read_status(self.path)[run])
        if st != OK:
            raise ConfigError(f"run = {run} has status {STATUS_NAMES[st]!r}; valid: an ok run")
        sc = self.scenario(run)
        n = int(round(sc["duration_s"] * sc["fs_hz"]))
        chans, units, dims = {}, {}, {}
        series = self.series
        if series:
            sig = np.asarray(self._ds["signal"].variable[run].values)
        for c in self.attrs["channels"]:
            if c["extra_dim"]:
                x = np.asarray(self._ds[c["name"]].variable[run].values)[:n]
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
        """Counts by label and by axis value, failures with their errors, totals."""
        st = self.status
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
            for v in np.unique(values.astype(str)):
                m = values.astype(str) == v
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
        cs = np.array([r.get("compute_s", np.nan) for r in self.records()], dtype=float)
        done = np.isfinite(cs)
        out["compute_s_total"] = float(cs[done].sum())
        out["compute_s_mean"] = float(cs[done].mean()) if done.any() else None
        err = np.asarray(self._ds["error"].values).astype(object)[self.runs]
        coords = {k: self.param(k) for k in self.attrs["coordinate_keys"]}
        out["failures"] = [
            {
                "run": int(self.runs[j]),
                "params": {k: _scalar(v[j]) for k, v in coords.items()},
                "error": str(err[j]),
            }
            for j in np.flatnonzero(st == FAILED)
        ]
        out["spec_hash"] = self.attrs.get("spec_hash")
        return out


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
    "SweepDataset",
    "client_lock",
    "create_dataset",
    "open_dataset",
    "read_attrs",
    "read_status",
    "remove_stale_temporaries",
]
