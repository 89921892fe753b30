"""Result of the bearing–rotor–housing model: :class:`RotorResponse` (SI arrays, metadata,
plots; the result pattern of :class:`~bearingsim.results.Result`: lossless
:class:`xarray.Dataset` round trip, netCDF ``save``/``load``)."""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any, ClassVar

import numpy as np
from numpy.typing import NDArray

from ...errors import ConfigError
from ...geometry import KinematicFrequencies
from ...results import Result, json_attr, read_json_attr, var_attrs
from .config import AUX_NAMES, ENDS, G0

__all__ = ["RotorResponse"]

#: array fields: name -> (dims, units, description)
_VARIABLES: dict[str, tuple[tuple[str, str], str, str]] = {
    "acceleration": (("time", "channel"), "m/s^2", "housing acceleration"),
    "housing_displacement": (("time", "channel"), "m", "housing displacement"),
    "shaft_displacement": (("time", "channel"), "m", "shaft displacement at the bearing nodes"),
    "ball_load_inner": (("time", "ball"), "N", "inner-race contact force, DE balls first"),
    "ball_load_outer": (("time", "ball"), "N", "outer-race contact force, DE balls first"),
}
_KINEMATICS = ("shaft_hz", "ftf_hz", "bpfo_hz", "bpfi_hz", "bsf_hz")


@dataclass
class RotorResponse(Result):
    """Time response of the bearing–rotor–housing model.

    Attributes
    ----------
    time : ndarray
        Sample times [s].
    acceleration : ndarray
        Housing accelerations (n, 4): DE x, DE y, FE x, FE y [m/s^2] (the accelerometer
        signals; CWRU's DE sensor sits at 12 o'clock, i.e. along y).
    housing_displacement : ndarray
        Housing displacements (n, 4) [m], same columns.
    shaft_displacement : ndarray
        Shaft displacement at the DE and FE bearing nodes (n, 4) [m].
    ball_load_inner, ball_load_outer : ndarray or None
        Contact force of every ball on the inner / outer race (n, Z_DE + Z_FE) [N], DE balls
        first (when requested).
    kinematics : dict
        :class:`~bearingsim.geometry.KinematicFrequencies` of the DE and FE bearings.
    meta : dict
        Model, version, inputs (:func:`config_summary`), solver facts.
    """

    FORMAT: ClassVar[str] = "bearingsim.RotorResponse/1"

    time: NDArray[np.float64]
    acceleration: NDArray[np.float64]
    housing_displacement: NDArray[np.float64]
    shaft_displacement: NDArray[np.float64]
    ball_load_inner: NDArray[np.float64] | None
    ball_load_outer: NDArray[np.float64] | None
    kinematics: dict[str, KinematicFrequencies]
    meta: dict[str, Any]

    @property
    def sample_rate(self) -> float:
        """Output sample rate [Hz]."""
        return float(self.meta["sample_rate_hz"])

    def channel(self, end: str = "DE", axis: str = "y") -> NDArray[np.float64]:
        """Housing acceleration of ``end`` ("DE"/"FE") along ``axis`` ("x"/"y") [m/s^2]."""
        end, axis = end.upper(), axis.lower()
        if end not in ENDS or axis not in ("x", "y"):
            raise ConfigError(f"channel = {end}/{axis} is invalid; valid: DE|FE and x|y")
        return self.acceleration[:, 2 * ENDS.index(end) + ("x", "y").index(axis)]

    def plot_waveform(self, end: str = "DE", axis: str = "y", t0: float | None = None,
                      t1: float | None = None, unit_g: bool = False):  # fmt: skip
        """Housing acceleration [m/s^2, or g with ``unit_g``] against time between ``t0`` and
        ``t1`` [s]; returns a Figure."""
        from ...plotting import FULL_WIDTH, new_figure

        a = self.channel(end, axis) / (G0 if unit_g else 1.0)
        m = np.ones(self.time.size, bool)
        if t0 is not None:
            m &= self.time >= t0
        if t1 is not None:
            m &= self.time <= t1
        fig, ax = new_figure(width=FULL_WIDTH, height=3.2)
        ax.plot(self.time[m], a[m], lw=0.7)
        ax.set_xlabel("time [s]")
        ax.set_ylabel(f"{end} {axis} acceleration [{'g' if unit_g else 'm/s²'}]")
        ax.set_title(f"rotor model, {self.meta['n_disks_label']}")
        return fig

    def spectrum(self, end: str = "DE", axis: str = "y", unit_g: bool = True):
        """One-sided amplitude spectrum (:func:`bearingsim.signal.amplitude_spectrum`: Hann
        window, amplitude-corrected) of a channel: ``(f [Hz], amplitude [g or m/s^2])``."""
        from ...signal.spectrum import amplitude_spectrum

        sp = amplitude_spectrum(self.channel(end, axis) / (G0 if unit_g else 1.0), self.sample_rate)
        return sp.freq, sp.amplitude

    def plot_spectrum(self, end: str = "DE", axis: str = "y", f_max: float = 1000.0,
                      mark: str = "bpfo", n_harmonics: int = 3):  # fmt: skip
        """Amplitude spectrum up to ``f_max`` [Hz] with the ``mark`` frequency ("bpfo",
        "bpfi", "ftf", "bsf" of that end's bearing) and its harmonics; amplitude [m/s^2];
        returns a Figure."""
        from ...plotting import FULL_WIDTH, legend_outside, mark_lines, new_figure

        f, amp = self.spectrum(end, axis, unit_g=False)
        m = f <= f_max
        fig, ax = new_figure(width=FULL_WIDTH, height=3.2)
        ax.plot(f[m], amp[m], lw=0.7)
        fk = getattr(self.kinematics[end.upper()], f"{mark}_hz")
        mark_lines(ax, fk * np.arange(1, n_harmonics + 1),
                   f"{mark.upper()} = {fk:.2f} Hz and harmonics")  # fmt: skip
        legend_outside(ax)
        ax.set_xlabel("frequency [Hz]")
        ax.set_ylabel(f"{end} {axis} acceleration amplitude [m/s²]")
        ax.set_title(f"rotor model, {self.meta['n_disks_label']}: amplitude spectrum")
        return fig

    def to_dataset(self):
        """Lossless :class:`xarray.Dataset`: dims ``time`` (coordinate [s]), ``channel``
        (:data:`AUX_NAMES`) and ``ball`` (1..Z_DE+Z_FE, DE balls first); every variable with
        its ``units``; ``meta`` (inputs, solver, kinematics) as a JSON attribute."""
        import xarray as xr

        data = {}
        for name, (dims, units, desc) in _VARIABLES.items():
            arr = getattr(self, name)
            if arr is not None:
                data[name] = (dims, arr, var_attrs(units, desc))
        coords: dict[str, Any] = {
            "time": ("time", self.time, var_attrs("s")),
            "channel": ("channel", list(AUX_NAMES)),
        }
        if self.ball_load_inner is not None:
            coords["ball"] = ("ball", np.arange(1, self.ball_load_inner.shape[1] + 1))
        attrs = self._base_attrs(model="rotor", meta_json=json_attr(self.meta))
        return xr.Dataset(data, coords=coords, attrs=attrs)

    @classmethod
    def from_dataset(cls, ds) -> RotorResponse:
        """Inverse of :meth:`to_dataset`."""
        cls.check_format(ds)
        meta = read_json_attr(ds, "meta_json")
        kin = {
            e: KinematicFrequencies(**{k: meta["kinematics"][e][k] for k in _KINEMATICS})
            for e in ENDS
        }
        bi = ds["ball_load_inner"].values if "ball_load_inner" in ds else None
        bo = ds["ball_load_outer"].values if "ball_load_outer" in ds else None
        return cls(
            ds["time"].values, ds["acceleration"].values, ds["housing_displacement"].values,
            ds["shaft_displacement"].values, bi, bo, kin, meta,
        )  # fmt: skip
