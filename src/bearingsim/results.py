"""The result pattern shared by every model, and the time-domain :class:`SimulationResult`.

Every model result (ring/rotor/IAS simulations, quasi-static solutions, stiffness matrices and
traces, contact-fatigue life) derives from :class:`Result`:

- ``to_dataset()`` — an :class:`xarray.Dataset`: SI arrays with ``units`` attributes, every input
  and the solver metadata as JSON attributes, ``format`` naming the class and its version;
- ``from_dataset(ds)`` — the exact inverse (lossless);
- ``save(path) -> Path`` — a self-describing netCDF-4 file (engine ``h5netcdf``) written
  atomically (a temporary file beside ``path``, renamed on success);
- ``load(path)`` — reads it back, refusing a file of another kind in one line;
- ``plot_*()`` — Matplotlib figures, returned without being shown;
- ``identical(other)`` — whether two results have identical datasets (the lossless check).

:func:`load_result` reads any result file and returns the right class (by its ``format``).

A subclass sets ``FORMAT`` (``"bearingsim.<Class>/<version>"``), starts its dataset's
attributes with :meth:`Result._base_attrs` and calls :meth:`Result.check_format` first in
``from_dataset``. Arrays become variables with named dimensions and coordinates and the
attributes of :func:`var_attrs` (``units``, ``"1"`` for dimensionless); inputs and metadata become
JSON attributes (:func:`json_attr`, :func:`read_json_attr`); scalars that may be NaN become 0-d
variables (JSON has no NaN). A module defining a result class is listed in
:data:`RESULT_MODULES` so that :func:`load_result` finds it without the caller importing it.

A :class:`SimulationResult` holds the sample times and named channels (first axis = time; a
second axis, e.g. ``ball``, is allowed and named in ``dims``), their units, the scenario that
produced it and solver metadata. ``save``/``load`` round-trip it exactly through a
self-describing netCDF-4 file written with xarray (engine ``h5netcdf``): float64 variables with
``units`` attributes, the scenario and metadata as JSON attributes. Later models add channels
(e.g. per-bearing-end accelerations) without changing the format.
"""

from __future__ import annotations

import io
import json
import math
import os
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, ClassVar

import numpy as np
from numpy.typing import NDArray

from ._version import __version__
from .errors import BearingsimError, ConfigError, exception_text
from .io.atomic import atomic_path
from .io.jsonable import to_jsonable

#: identifies our files
FORMAT = "bearingsim.SimulationResult/1"

#: ``format`` attribute -> result class (filled by :meth:`Result.__init_subclass__`)
_FORMATS: dict[str, type[Result]] = {}
#: what reads a file of another result class, where a command does (``check_format``'s hint)
_OTHER_USE = {
    "bearingsim.IasResult/1": " (an IAS result: bearingsim analyze-ias reads it)",
}

#: modules that define result classes, imported by :func:`load_result` when a file's format is
#: not registered yet (the layers above this module may not be imported by it otherwise)
RESULT_MODULES: tuple[str, ...] = (
    "bearingsim.dynamics.ring.trace",
    "bearingsim.dynamics.rotor.response",
    "bearingsim.dynamics.ias.result",
    "bearingsim.life.fatigue",
    "bearingsim.quasistatic.result",
    "bearingsim.quasistatic.stiffness",
)

__all__ = [
    "FORMAT",
    "RESULT_MODULES",
    "Result",
    "SimulationResult",
    "json_attr",
    "load_result",
    "read_json_attr",
    "var_attrs",
]


def json_attr(obj: Any) -> str:
    """``obj`` as a JSON string for a netCDF attribute (NumPy types converted, non-finite floats
    written as ``null``)."""
    return json.dumps(to_jsonable(obj))


def var_attrs(units: str, long_name: str = "") -> dict[str, str]:
    """The attributes of a result variable: its ``units`` (``"1"`` for dimensionless) and, when
    given, a ``long_name`` describing it."""
    return {"units": units, "long_name": long_name} if long_name else {"units": units}


def read_json_attr(ds: Any, name: str) -> Any:
    """The JSON attribute ``name`` of dataset ``ds``, parsed; a missing or broken one raises a
    one-line :class:`ConfigError`."""
    try:
        return json.loads(ds.attrs[name])
    except (KeyError, TypeError, ValueError):
        raise ConfigError(
            f"attribute {name!r} is missing or not JSON; valid: a file written by bearingsim"
        ) from None


#: attribute keys that record how long a run took, not what it computed (left out by
#: ``Result.identical(other, timing=False)``)
TIMING_KEYS = frozenset({"wall_s", "wall_time_s", "cpu_s", "time_per_step_s"})


def _drop_timing(v: Any) -> Any:
    if isinstance(v, dict):
        return {k: _drop_timing(x) for k, x in v.items() if k not in TIMING_KEYS}
    if isinstance(v, list):
        return [_drop_timing(x) for x in v]
    return v


def _without_timing(ds: Any) -> Any:
    """``ds`` with :data:`TIMING_KEYS` removed from its attributes and from the JSON held in
    them (a shallow copy)."""
    out = ds.copy()
    attrs = {}
    for k, v in ds.attrs.items():
        if k in TIMING_KEYS:
            continue
        if isinstance(v, str) and v[:1] in "{[":
            try:
                v = json.dumps(_drop_timing(json.loads(v)), sort_keys=True)
            except ValueError:
                pass
        attrs[k] = v
    out.attrs = attrs
    return out


class Result:
    """Base class of every model result (see the module docstring for the pattern).

    A subclass sets ``FORMAT`` (``"bearingsim.<Class>/<version>"``) and implements
    :meth:`to_dataset` and :meth:`from_dataset`; :meth:`save`, :meth:`load` and
    :meth:`identical` come from here.
    """

    #: the ``format`` attribute of this class's files
    FORMAT: ClassVar[str] = ""

    def __init_subclass__(cls, **kw: Any) -> None:
        super().__init_subclass__(**kw)
        if cls.FORMAT:
            _FORMATS[cls.FORMAT] = cls

    def to_dataset(self):
        """The result as an :class:`xarray.Dataset` (SI, units in attributes, inputs as JSON)."""
        raise NotImplementedError

    @classmethod
    def from_dataset(cls, ds):
        """Inverse of :meth:`to_dataset`."""
        raise NotImplementedError

    def _base_attrs(self, **extra: Any) -> dict[str, Any]:
        """The attributes every result dataset starts with (``format``, ``bearingsim_version``)
        followed by ``extra``."""
        return {"format": self.FORMAT, "bearingsim_version": __version__, **extra}

    @classmethod
    def check_format(cls, ds: Any, path: str | Path | None = None) -> None:
        """Raise a one-line :class:`ConfigError` unless ``ds`` was written by this class; the
        message names the file's class and the expected one."""
        got = ds.attrs.get("format")
        if got != cls.FORMAT:
            other = _FORMATS.get(got)
            kind = f" ({other.__name__})" if other is not None else ""
            where = f"file = {str(path)!r}: " if path is not None else ""
            raise ConfigError(
                f"{where}format = {got!r}{kind} is not a {cls.__name__} file; valid: "
                f"{cls.FORMAT!r}" + _OTHER_USE.get(got, " (load_result reads any kind)")
            )

    def identical(self, other: Any, *, timing: bool = True) -> bool:
        """Whether ``other`` is a result of the same class with an identical dataset (values,
        dims, coordinates and attributes; NaN equals NaN): what a lossless ``load(save(r))``
        gives. ``timing=False`` leaves out how long the run took (the keys of
        :data:`TIMING_KEYS` at any depth of the attributes): what a rerun of the same inputs
        gives, whose wall time differs."""
        if type(other) is not type(self):
            return False
        a, b = self.to_dataset(), other.to_dataset()
        if not timing:
            a, b = _without_timing(a), _without_timing(b)
        return a.identical(b)

    def save(self, path: str | Path, *, field: str = "path") -> Path:
        """Write a netCDF-4 file (engine h5netcdf) atomically; returns the path (``field``:
        its name in an error, e.g. the command's ``-o/--output``).

        The file is made in memory and then written as bytes (twenty-first session): h5py
        writing to a full disk raised the one-line error and then crashed at exit (a
        segmentation fault closing its failed file). Ctrl-C is held while it is made and
        written (:func:`~bearingsim.interrupt.held_interrupt`) and then raised, so nothing is
        written: h5py's callbacks swallowed it and the file was written as if no Ctrl-C had
        come."""
        from .interrupt import held_interrupt

        p = Path(path)
        ds = self.to_dataset()
        ds.attrs["format"] = self.FORMAT
        ds.attrs.setdefault("bearingsim_version", __version__)
        with atomic_path(p, suffix=".nc", field=field) as tmp:
            with held_interrupt():
                buf = io.BytesIO()
                ds.to_netcdf(buf, engine="h5netcdf")
                with open(tmp, "wb") as fh:
                    fh.write(buf.getbuffer())
        return p

    @classmethod
    def load(cls, path: str | Path):
        """Read a file written by :meth:`save` (of this class, or of any class when called on
        :class:`Result`)."""
        ds = _open(path)
        if cls is Result:
            return load_result(path, ds)
        cls.check_format(ds, path)
        return _from_dataset(cls, ds, path)


#: first bytes of a zip archive, e.g. a NumPy ``.npz`` (the former ``LifeResult`` format)
_ZIP_MAGIC = b"PK\x03\x04"

#: first bytes of a netCDF-3 file (classic, 64-bit offset, 64-bit data): not HDF5, so not ours
_NETCDF3_MAGIC = (b"CDF\x01", b"CDF\x02", b"CDF\x05")

#: the HDF5 signature, at offset 0 or 512, 1024, 2048, ... (HDF5 file format specification,
#: "Format Signature"): a netCDF-4 file is an HDF5 file
_HDF5_MAGIC = b"\x89HDF\r\n\x1a\n"


def _open(path: str | Path):
    """The dataset of result file ``path``, loaded; any file that is not a readable netCDF-4
    file (missing, empty, another format, truncated or damaged) is a one-line
    :class:`ConfigError` naming the file and what is wrong."""
    import xarray as xr

    p = Path(path)
    bad = f"file = {str(p)!r} is not a readable bearingsim result"
    try:
        with open(p, "rb") as fh:
            head = fh.read(8)
            size = os.fstat(fh.fileno()).st_size
            hdf5 = _hdf5_signature(fh, size)
    except OSError as exc:
        raise ConfigError(f"{bad} ({exc.strerror})") from None
    if head[:4] == _ZIP_MAGIC:
        raise ConfigError(
            f"file = {str(p)!r} is a NumPy .npz archive (the former LifeResult format); "
            "valid: a netCDF result file (.nc) written by save(); re-run to write one"
        )
    if not size:
        raise ConfigError(f"{bad} (empty file); valid: a netCDF-4 file written by save()")
    if head[:4] in _NETCDF3_MAGIC:
        raise ConfigError(
            f"{bad} (a netCDF-3 file, written by another program); valid: a netCDF-4 file "
            "written by save()"
        )
    if not hdf5:
        raise ConfigError(
            f"{bad} (not a netCDF-4/HDF5 file); valid: a netCDF-4 file written by save()"
        )
    try:
        import h5py

        # read the root attributes with h5py first: h5netcdf fails on a damaged root and then
        # prints an error from its half-built File's __del__ on stderr
        with h5py.File(p, "r") as f:
            f.attrs.get("_nc3_strict")
        with xr.open_dataset(p, engine="h5netcdf") as ds:
            return ds.load()
    except Exception as exc:  # noqa: BLE001 - a damaged HDF5 file raises OSError, KeyError,
        # RuntimeError, ValueError, ... from h5py, h5netcdf and xarray
        raise ConfigError(f"{bad} (damaged or truncated: {exception_text(exc)})") from None


def _hdf5_signature(fh: Any, size: int) -> bool:
    offset = 0
    while offset + len(_HDF5_MAGIC) <= size:
        fh.seek(offset)
        if fh.read(len(_HDF5_MAGIC)) == _HDF5_MAGIC:
            return True
        offset = 512 if offset == 0 else 2 * offset
    return False


def _from_dataset(cls: type[Result], ds: Any, path: str | Path) -> Result:
    """``cls.from_dataset(ds)``; a file whose format attribute is right but whose content is
    incomplete or damaged is a one-line :class:`ConfigError` naming it."""
    where = f"file = {str(path)!r}"
    try:
        return cls.from_dataset(ds)
    except BearingsimError as exc:
        msg = str(exc)
        raise type(exc)(msg if str(path) in msg else f"{where}: {msg}") from None
    except (KeyError, IndexError, TypeError, ValueError, AttributeError) as exc:
        raise ConfigError(
            f"{where}: a {cls.__name__} file with incomplete or invalid content "
            f"({exception_text(exc)}); valid: a file written by save()"
        ) from None


#: words for the channel-name prefixes of :class:`SimulationResult` (axis labels)
_CHANNEL_WORDS = {
    "acc": "acceleration",
    "vel": "velocity",
    "disp": "displacement",
    "shaft": "shaft displacement",
    "k": "stiffness",
    "n": "number",
}


def _quantity(channel: str) -> str:
    """Axis quantity of a channel: ``"acc_y"`` -> ``"acceleration acc_y"``."""
    word = _CHANNEL_WORDS.get(channel.split("_")[0])
    return f"{word} {channel}" if word else channel


def load_result(path: str | Path, _ds: Any = None) -> Result:
    """Read any bearingsim result file; the class comes from its ``format`` attribute."""
    ds = _open(path) if _ds is None else _ds
    fmt = ds.attrs.get("format")
    if fmt not in _FORMATS:
        import importlib

        for mod in RESULT_MODULES:
            importlib.import_module(mod)
    cls = _FORMATS.get(fmt)
    if cls is None:
        raise ConfigError(
            f"file = {str(path)!r}: format = {fmt!r} is not a bearingsim result; valid: "
            + ", ".join(sorted(_FORMATS))
        )
    return _from_dataset(cls, ds, path)


@dataclass
class SimulationResult(Result):
    """Time series of one simulation.

    Attributes
    ----------
    time : ndarray (n,)
        Sample times [s].
    channels : dict[str, ndarray]
        Named arrays with first axis time (e.g. ``acc_y`` [m/s^2], ``ball_load`` [N] with shape
        (n, Z)).
    units : dict[str, str]
        Unit of each channel.
    scenario : dict
        Every input (:meth:`bearingsim.config.Scenario.to_dict`).
    meta : dict
        Model, solver, resolved defaults, bearing, kinematic frequencies, version, wall time.
    dims : dict[str, tuple[str, ...]]
        Dimension names of the channels that are not 1-D (default ``("time", "ball")``).
    """

    FORMAT: ClassVar[str] = FORMAT

    time: NDArray[np.float64]
    channels: dict[str, NDArray[np.float64]]
    units: dict[str, str]
    scenario: dict[str, Any]
    meta: dict[str, Any]
    dims: dict[str, tuple[str, ...]] = field(default_factory=dict)

    def __getitem__(self, name: str) -> NDArray[np.float64]:
        try:
            return self.channels[name]
        except KeyError:
            raise ConfigError(
                f"channel = {name!r} is not in the result; valid: " + ", ".join(self.channels)
            ) from None

    def __repr__(self) -> str:
        """One line: samples, rate, channels and the model (not the arrays)."""
        chans = ", ".join(f"{k} [{self.units.get(k, '')}]" for k in self.channels)
        model = self.meta.get("model", self.scenario.get("model", "?"))
        return (
            f"SimulationResult({model}: {len(self.time)} samples at {self.fs_hz:g} Hz; "
            f"channels {chans})"
        )

    @property
    def fs_hz(self) -> float:
        """Output sample rate [Hz]: ``meta["fs_hz"]``, else from the sample times (a result
        built by hand)."""
        if "fs_hz" in self.meta:
            return float(self.meta["fs_hz"])
        t = np.asarray(self.time, dtype=float)
        if t.size < 2 or not np.all(np.diff(t) > 0):
            raise ConfigError(
                "time: a result needs at least 2 increasing sample times (or meta['fs_hz'])"
            )
        return float((t.size - 1) / (t[-1] - t[0]))

    @property
    def shaft_hz(self) -> float:
        """Shaft frequency [Hz]."""
        return float(self.meta["shaft_hz"])

    def acceleration(self, axis: str = "y") -> NDArray[np.float64]:
        """Acceleration along ``axis`` (``"x"`` or ``"y"``) [m/s^2]."""
        a = axis.lower()
        if a not in ("x", "y"):
            raise ConfigError(f"axis = {axis!r} is invalid; valid: x, y")
        return self[f"acc_{a}"]

    def rms(self, name: str) -> float:
        """Root mean square of a channel (its unit)."""
        x = self[name]
        return float(np.sqrt(np.mean(x * x)))

    # ------------------------------------------------------------------------ files
    def _dims(self, name: str, arr: NDArray) -> tuple[str, ...]:
        if name in self.dims:
            return self.dims[name]
        if arr.ndim == 1:
            return ("time",)
        if arr.ndim == 2:
            return ("time", "ball")
        raise ConfigError(f"channel {name!r} has {arr.ndim} dims; name them in dims")

    def to_dataset(self):
        """The result as an :class:`xarray.Dataset` (units in attributes, metadata as JSON)."""
        import xarray as xr

        data_vars = {}
        for name, arr in self.channels.items():
            a = np.asarray(arr)
            data_vars[name] = (self._dims(name, a), a, {"units": self.units.get(name, "")})
        coords: dict[str, Any] = {"time": ("time", np.asarray(self.time), {"units": "s"})}
        for name, arr in self.channels.items():
            d = self._dims(name, np.asarray(arr))
            if len(d) == 2 and d[1] not in coords:
                coords[d[1]] = (d[1], np.arange(1, np.asarray(arr).shape[1] + 1))
        attrs = {
            "format": FORMAT,
            "bearingsim_version": __version__,
            "scenario_json": json.dumps(to_jsonable(self.scenario)),
            "meta_json": json.dumps(to_jsonable(self.meta)),
            "dims_json": json.dumps({k: list(v) for k, v in self.dims.items()}),
            "model": str(self.meta.get("model", "")),
            "fs_hz": self.fs_hz,
        }
        return xr.Dataset(data_vars, coords=coords, attrs=attrs)

    @classmethod
    def from_dataset(cls, ds) -> SimulationResult:
        """Inverse of :meth:`to_dataset`."""
        cls.check_format(ds)
        dims = {k: tuple(v) for k, v in json.loads(ds.attrs.get("dims_json", "{}")).items()}
        channels = {}
        units = {}
        for name, var in ds.data_vars.items():
            channels[str(name)] = np.asarray(var.values)
            units[str(name)] = str(var.attrs.get("units", ""))
        return cls(
            time=np.asarray(ds["time"].values),
            channels=channels,
            units=units,
            scenario=json.loads(ds.attrs["scenario_json"]),
            meta=json.loads(ds.attrs["meta_json"]),
            dims=dims,
        )

    # ------------------------------------------------------------------------ plots
    def plot_time(self, channel: str = "acc_y", t_range: tuple[float, float] | None = None):
        """Time waveform of ``channel`` (page-wide figure of :mod:`bearingsim.plotting`);
        returns the Figure.

        Parameters
        ----------
        channel : str
            Channel name (e.g. ``"acc_y"`` [m/s^2]).
        t_range : (float, float), optional
            Time window shown [s].
        """
        from .plotting import FULL_WIDTH, new_figure, unit_text

        x = self[channel]
        t = self.time
        sel = slice(None) if t_range is None else (t >= t_range[0]) & (t <= t_range[1])
        if t_range is not None and np.count_nonzero(sel) < 2:  # it drew an empty figure
            raise ConfigError(
                f"t_range = {tuple(t_range)!r} s holds {np.count_nonzero(sel)} samples; valid: "
                f"a window within [{t[0]:.6g}, {t[-1]:.6g}] s holding at least 2"
            )
        fig, ax = new_figure(width=FULL_WIDTH, height=3.2)
        ax.plot(t[sel], x[sel], lw=0.6)
        ax.set_xlabel("time [s]")
        ax.set_ylabel(f"{_quantity(channel)} [{unit_text(self.units.get(channel, '')) or '-'}]")
        ax.set_title(self.title)
        return fig

    def plot_stiffness(self):
        """Total effective stiffness along the load direction vs time; returns the Figure."""
        from .plotting import FULL_WIDTH, new_figure

        fig, ax = new_figure(width=FULL_WIDTH, height=3.2)
        ax.plot(self.time, self["k_load"] / 1e6, lw=0.8)
        ax.set_xlabel("time [s]")
        ax.set_ylabel("stiffness along the load k_load [MN/m]")
        ax.set_title(self.title)
        return fig

    def plot_envelope(
        self, channel: str = "acc_y", band: tuple[float, float] | None = None, f_max: float = 600.0
    ):
        """Envelope spectrum of ``channel`` up to ``f_max`` [Hz] (band [Hz] from the kurtogram
        unless given; named in the title) with the harmonics of the simulated fault's
        characteristic frequency marked; returns the Figure."""
        from .plotting import FULL_WIDTH, legend_outside, mark_lines, new_figure, unit_text
        from .signal import envelope_spectrum, fast_kurtogram

        x = self[channel]
        if band is None:
            band = fast_kurtogram(x, self.fs_hz).band
        es = envelope_spectrum(x, self.fs_hz, band, unit=unit_text(self.units.get(channel, "")))
        fig, ax = new_figure(width=FULL_WIDTH, height=3.4)
        es.plot(f_max=f_max, ax=ax, quantity=f"envelope amplitude of {channel}")
        ax.set_title(f"{self.title}: envelope band {band[0]:.0f}-{band[1]:.0f} Hz")
        fault = self.scenario.get("fault") or self.scenario.get("de_fault")
        key = {"outer": "bpfo", "inner": "bpfi", "ball": "bsf"}.get(str(fault))
        kin = self.meta.get("kinematics") or {}
        if key and f"{key}_hz" in kin:
            f0 = (2.0 if key == "bsf" else 1.0) * float(kin[f"{key}_hz"])
            name = "2xBSF" if key == "bsf" else key.upper()
            n = int(f_max // f0)
            if n:
                mark_lines(
                    ax,
                    f0 * np.arange(1, n + 1),
                    f"{name} = {f0:.2f} Hz and harmonics",
                    texts=[f"{h}x" for h in range(1, n + 1)],
                )
                legend_outside(ax)
        return fig

    @property
    def title(self) -> str:
        """Short description: model, bearing, fault, speed."""
        m = self.meta
        return (
            f"{m.get('model', '?').upper()} {m.get('bearing_id', '')} fault "
            f"{self.scenario.get('fault', '?')} at {self.scenario.get('rpm', math.nan):g} r/min"
        )
