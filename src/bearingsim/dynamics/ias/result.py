"""Result object of the IAS model (:mod:`bearingsim.dynamics.ias`): time series, angle-domain
analysis, plots; the result pattern of :class:`~bearingsim.results.Result` (lossless
``to_dataset``/``from_dataset``, netCDF ``save`` returning the path, ``load``)."""

from __future__ import annotations

import math
from dataclasses import asdict, dataclass
from typing import Any, ClassVar

import numpy as np
from numpy.typing import NDArray

from ...errors import ConfigError, check_range
from ...geometry import Defect, RollerBearing
from ...results import Result, json_attr, read_json_attr, var_attrs
from ..budget import Budget
from .model import AUX_NAMES, OMEGA_EPS, STATE_NAMES, IasConstants, IasParams
from .spall import IasSummary, SpallEstimator

__all__ = ["IasResult"]

#: units and description of every column of ``state`` and ``aux`` (:data:`STATE_NAMES`,
#: :data:`AUX_NAMES`)
_UNITS: dict[str, tuple[str, str]] = {
    "x": ("m", "inner-ring displacement x"),
    "y": ("m", "inner-ring displacement y"),
    "theta": ("rad", "shaft angle"),
    "vx": ("m/s", "inner-ring velocity x"),
    "vy": ("m/s", "inner-ring velocity y"),
    "omega": ("rad/s", "shaft angular speed (IAS)"),
    "bearing_torque": ("N m", "resisting torque of the rollers sum(r_i T_k + b_n N_k)"),
    "spall_torque": ("N m", "spall torque M_T"),
    "spall_force": ("N", "spall force F_T"),
    "impact_force": ("N", "impact part F_os cos(lambda) (1 - sin(...)) of F_T"),
    "normal_force_sum": ("N", "sum of the roller normal forces N_k"),
    "n_loaded": ("1", "number of loaded rollers"),
}


@dataclass(frozen=True)
class IasResult(Result):
    """Time series of the IAS model with its inputs and solver facts (SI).

    Attributes
    ----------
    t : ndarray, shape (n,)
        Time [s].
    state : ndarray, shape (n, 6)
        ``x, y`` [m], ``theta`` [rad], ``x', y'`` [m/s], ``theta'`` [rad/s] (:data:`STATE_NAMES`).
    aux : ndarray, shape (n, 6)
        :data:`AUX_NAMES`: resisting torque of the rollers ``sum (r_i T_k + b_n N_k)`` [N m],
        spall torque ``M_T`` [N m], spall force ``F_T`` [N], its impact part
        ``F_os cos(lambda) (1 - sin(...))`` [N], ``sum N_k`` [N], loaded rollers [-].
    params : IasParams
        Inputs.
    constants : IasConstants
        Derived constants.
    solver : dict
        Method, step, decimation, steps, output rate, wall time.
    version : str
        bearingsim version.
    scenario : dict or None
        The :class:`~bearingsim.config.IasScenario` keys when the run came from
        :func:`bearingsim.simulate` (``None`` for a direct :func:`.model.simulate_ias` call).

    Like every result of :func:`bearingsim.simulate`, it also reads as a time series of named
    channels: ``time``, ``channels`` (the columns of ``state`` and ``aux`` by name),
    ``units``, ``fs_hz``, ``meta``, ``res["omega"]`` — which is what sweeps store.
    """

    FORMAT: ClassVar[str] = "bearingsim.IasResult/1"

    t: NDArray[np.float64]
    state: NDArray[np.float64]
    aux: NDArray[np.float64]
    params: IasParams
    constants: IasConstants
    solver: dict[str, Any]
    version: str
    scenario: dict[str, Any] | None = None

    def __getattr__(self, name: str) -> NDArray[np.float64]:
        if name in STATE_NAMES:
            return self.state[:, STATE_NAMES.index(name)]
        if name in AUX_NAMES:
            return self.aux[:, AUX_NAMES.index(name)]
        raise AttributeError(name)

    # ------------------------------------------------------------ the time-series view
    @property
    def time(self) -> NDArray[np.float64]:
        """Sample times [s] (``t``)."""
        return self.t

    @property
    def channels(self) -> dict[str, NDArray[np.float64]]:
        """Every column of ``state`` and ``aux`` by name (units in :attr:`units`)."""
        out = {n: self.state[:, i] for i, n in enumerate(STATE_NAMES)}
        out.update({n: self.aux[:, i] for i, n in enumerate(AUX_NAMES)})
        return out

    @property
    def units(self) -> dict[str, str]:
        """Unit of each channel."""
        return {n: _UNITS[n][0] for n in (*STATE_NAMES, *AUX_NAMES)}

    @property
    def dims(self) -> dict[str, tuple[str, ...]]:
        """Dimensions of the channels that are not 1-D (none here)."""
        return {}

    def _dims(self, name: str, arr: NDArray) -> tuple[str, ...]:
        return ("time",)

    @property
    def fs_hz(self) -> float:
        """Output sample rate [Hz]."""
        return float(self.solver["output_rate_hz"])

    @property
    def meta(self) -> dict[str, Any]:
        """Model, bearing, inputs, derived constants and solver facts (as in the other
        simulation results)."""
        return {
            "model": "ias",
            "bearing_id": self.params.bearing.id,
            "fs_hz": self.fs_hz,
            "params": self.params.as_dict(),
            "constants": asdict(self.constants),
            "solver": self.solver,
            "bearingsim_version": self.version,
        }

    def rms(self, name: str) -> float:
        """Root mean square of a channel (its unit)."""
        x = self[name]
        return float(np.sqrt(np.mean(x * x)))

    def __getitem__(self, name: str) -> NDArray[np.float64]:
        ch = self.channels
        if name not in ch:
            raise ConfigError(f"channel = {name!r} is not in the result; valid: " + ", ".join(ch))
        return ch[name]

    # ------------------------------------------------------------------ analysis
    def default_skip(self) -> float:
        """Start-up time left out of the analysis: 10 % of the run [s]."""
        return 0.1 * float(self.t[-1] - self.t[0])

    def steady(self, skip_s: float | None = None) -> NDArray[np.bool_]:
        """Mask of the samples after ``skip_s`` (default :meth:`default_skip`)."""
        skip = (
            self.default_skip() if skip_s is None else check_range("skip_s", skip_s, 0.0, unit="s")
        )
        m = self.t >= self.t[0] + skip
        if m.sum() < 16:
            raise ConfigError(
                f"skip_s = {skip:.6g} s leaves {int(m.sum())} samples; valid range "
                f"[0, {float(self.t[-1] - self.t[0]):.6g}) s"
            )
        return m

    def net_torque(self) -> NDArray[np.float64]:
        """Net shaft torque ``M_z - C_T theta' - s (sum(r_i T + b_n N) + M_T)`` [N m]
        (= ``I theta''``, seed eq. (32))."""
        w = self.omega
        sgn = w / np.sqrt(w * w + OMEGA_EPS**2)
        p = self.params
        return p.torque - p.torsional_damping * w - sgn * (self.bearing_torque + self.spall_torque)

    def angle_signal(
        self,
        skip_s: float | None = None,
        samples_per_rev: int | None = None,
        budget: Budget | None = None,
    ):
        """IAS resampled to uniform shaft angle after ``skip_s`` [s] (an
        :class:`~bearingsim.signal.AngleSignal`, anti-aliased:
        :func:`bearingsim.signal.resample_to_angle`); ``samples_per_rev`` [1/rev] defaults to
        the smallest power of two at least the samples per revolution of the output rate. The
        memory of the resampling and of its order spectrum is checked against ``budget``
        (default :class:`~bearingsim.dynamics.budget.Budget`) before anything is allocated."""
        from ...signal.order import resample_to_angle

        m = self.steady(skip_s)
        wmin = float(self.omega[m].min())
        if not (wmin > 0.0 and np.all(np.diff(self.theta[m]) > 0.0)):
            raise ConfigError(
                f"shaft speed = {wmin:.6g} rad/s after the start-up: the angle-domain analysis "
                "needs a turning shaft; valid range speed > 0 (raise torque_n_m or skip_s)"
            )
        limit = (Budget() if budget is None else budget).memory_limit()[0]
        return resample_to_angle(
            self.theta[m],
            self.omega[m],
            samples_per_rev,
            max_memory=limit if math.isfinite(limit) else None,
        )

    def analyze(
        self,
        skip_s: float | None = None,
        n_peaks: int = 5,
        method: SpallEstimator | str = SpallEstimator.STEPS,
        *,
        budget: Budget | None = None,
    ) -> IasSummary:
        """Angle-domain summary (:func:`.spall.analyze_speed_signal`) with the bearing's
        kinematic BPFO order, D_o and cage ratio; a run too short to resolve the BPFO order
        (:func:`.spall.min_revs`) raises :class:`.spall.ShortSignalError`.

        Parameters
        ----------
        skip_s : float, optional
            Start-up left out [s] (default :meth:`default_skip`).
        n_peaks : int
            Order peaks reported [-].
        method : SpallEstimator
            Crossing-angle reading of the spall-width estimate.
        budget : Budget, optional
            Memory budget of the angle-domain analysis (:meth:`angle_signal`).
        """
        from .spall import analyze_speed_signal

        b = self.params.bearing
        return analyze_speed_signal(
            self.angle_signal(skip_s, budget=budget),
            bpfo_order=self.constants.bpfo_order,
            outer_raceway_diameter=b.outer_raceway_diameter,
            cage_ratio=self.constants.cage_ratio,
            n_peaks=n_peaks,
            method=method,
        )

    def plot_ias(self, skip_s: float | None = None, revs: float | None = None):
        """IAS [r/min] vs shaft angle [rev] (seed fig. 8 analogue); returns the Figure."""
        from ...plotting import FULL_WIDTH, new_figure

        sig = self.angle_signal(skip_s)
        fig, ax = new_figure(width=FULL_WIDTH, height=3.2)
        n = sig.value.size if revs is None else int(revs * sig.samples_per_rev)
        ax.plot(sig.angle[:n] / (2 * np.pi), sig.value[:n] * 60 / (2 * np.pi), lw=0.8)
        ax.set_xlabel("shaft angle [rev]")
        ax.set_ylabel("IAS [r/min]")
        ax.ticklabel_format(axis="y", useOffset=False)
        lab = (
            f"spall {self.params.spall_width * 1e3:g} mm"
            if self.params.spall_width > 0
            else "healthy"
        )
        ax.set_title(
            f"{self.params.bearing.id}, {lab}, F_y {self.params.fy:g} N, "
            f"M_z {self.params.torque:g} N m"
        )
        return fig

    def plot_order_spectrum(self, skip_s: float | None = None, max_order: float = 30.0):
        """IAS order spectrum up to ``max_order`` [-] with the BPFO harmonics marked (seed fig. 9
        analogue)."""
        from ...signal.order import order_spectrum

        spec = order_spectrum(self.angle_signal(skip_s), unit="rad/s")
        bp = self.constants.bpfo_order
        fig = spec.plot(
            max_order,
            scale=60.0 / (2 * np.pi),
            unit="r/min",
            marks=bp * np.arange(1, int(max_order / bp) + 1),
            marks_label=f"BPFO order {bp:.4f} and harmonics",
            quantity="IAS amplitude",
        )
        fig.axes[0].set_title("IAS order spectrum")
        return fig

    # ------------------------------------------------------------------------- files
    def to_dataset(self):
        """Lossless :class:`xarray.Dataset`: one variable per column of ``state`` and ``aux``
        on the ``time`` dimension (coordinate [s]) with its ``units``; ``params`` (bearing and
        spall spelled out), ``constants`` and ``solver`` as JSON attributes."""
        import xarray as xr

        data = {}
        for arr, names in ((self.state, STATE_NAMES), (self.aux, AUX_NAMES)):
            for i, n in enumerate(names):
                units, desc = _UNITS[n]
                data[n] = ("time", arr[:, i], var_attrs(units, desc))
        pd = self.params.as_dict()
        pd["bearing"] = asdict(self.params.bearing)
        attrs = self._base_attrs(
            model="IAS (seed 002, Han, Guo, Fan 2025)",
            params=json_attr(pd),
            constants=json_attr(asdict(self.constants)),
            solver=json_attr(self.solver),
            version=self.version,
        )
        if self.scenario is not None:
            attrs["scenario_json"] = json_attr(self.scenario)
        return xr.Dataset(data, coords={"time": ("time", self.t, var_attrs("s"))}, attrs=attrs)

    @classmethod
    def check_format(cls, ds: Any, path: Any = None) -> None:
        """As :meth:`Result.check_format`; files written before the result pattern (no
        ``format``, time dimension ``t``) are accepted too."""
        if ds.attrs.get("format") is None and "params" in ds.attrs and "omega" in ds:
            return
        super().check_format(ds, path)

    @classmethod
    def from_dataset(cls, ds) -> IasResult:
        """Inverse of :meth:`to_dataset`."""
        from ...materials import Material

        cls.check_format(ds)
        pd = read_json_attr(ds, "params")
        bd = pd.pop("bearing")
        bd["material"] = Material(**bd["material"])
        pd["bearing"] = RollerBearing(**bd)
        pd["initial_displacement"] = tuple(pd["initial_displacement"])
        if pd.get("spall") is not None:
            pd["spall"] = Defect(**pd["spall"])
        params = IasParams(**pd)
        const = IasConstants(**read_json_attr(ds, "constants"))
        state = np.stack([ds[n].values for n in STATE_NAMES], 1)
        aux = np.stack([ds[n].values for n in AUX_NAMES], 1)
        time = "time" if "time" in ds.coords else "t"  # "t": files before the result pattern
        return cls(
            ds[time].values,
            state,
            aux,
            params,
            const,
            read_json_attr(ds, "solver"),
            str(ds.attrs.get("version", "")),
            read_json_attr(ds, "scenario_json") if "scenario_json" in ds.attrs else None,
        )
