"""Result object of the IAS model (:mod:`bearingsim.dynamics.ias`): time series, angle-domain
analysis, plots, lossless netCDF save/load."""

from __future__ import annotations

from dataclasses import asdict, dataclass
from typing import Any

import numpy as np
from numpy.typing import NDArray

from ...errors import ConfigError, check_range
from ...geometry import Defect, RollerBearing
from .model import AUX_NAMES, OMEGA_EPS, STATE_NAMES, IasConstants, IasParams
from .spall import IasSummary, SpallEstimator


@dataclass(frozen=True)
class IasResult:
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
    """

    t: NDArray[np.float64]
    state: NDArray[np.float64]
    aux: NDArray[np.float64]
    params: IasParams
    constants: IasConstants
    solver: dict[str, Any]
    version: str

    def __getattr__(self, name: str) -> NDArray[np.float64]:
        if name in STATE_NAMES:
            return self.state[:, STATE_NAMES.index(name)]
        if name in AUX_NAMES:
            return self.aux[:, AUX_NAMES.index(name)]
        raise AttributeError(name)

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

    def angle_signal(self, skip_s: float | None = None, samples_per_rev: int | None = None):
        """IAS resampled to uniform shaft angle after ``skip_s`` [s] (an
        :class:`~bearingsim.signal.AngleSignal`, anti-aliased:
        :func:`bearingsim.signal.resample_to_angle`); ``samples_per_rev`` [1/rev] defaults to
        the smallest power of two at least the samples per revolution of the output rate."""
        from ...signal.order import resample_to_angle

        m = self.steady(skip_s)
        wmin = float(self.omega[m].min())
        if not (wmin > 0.0 and np.all(np.diff(self.theta[m]) > 0.0)):
            raise ConfigError(
                f"shaft speed = {wmin:.6g} rad/s after the start-up: the angle-domain analysis "
                "needs a turning shaft; valid range speed > 0 (raise torque_nm or skip_s)"
            )
        return resample_to_angle(self.theta[m], self.omega[m], samples_per_rev)

    def analyze(
        self,
        skip_s: float | None = None,
        n_peaks: int = 5,
        method: SpallEstimator | str = SpallEstimator.STEPS,
    ) -> IasSummary:
        """Angle-domain summary (:func:`.spall.analyze_speed_signal`) with the bearing's
        kinematic BPFO order, D_o and cage ratio.

        Parameters
        ----------
        skip_s : float, optional
            Start-up left out [s] (default :meth:`default_skip`).
        n_peaks : int
            Order peaks reported [-].
        method : SpallEstimator
            Crossing-angle reading of the spall-width estimate.
        """
        from .spall import analyze_speed_signal

        b = self.params.bearing
        return analyze_speed_signal(
            self.angle_signal(skip_s),
            bpfo_order=self.constants.bpfo_order,
            outer_raceway_diameter=b.outer_raceway_diameter,
            cage_ratio=self.constants.cage_ratio,
            n_peaks=n_peaks,
            method=method,
        )

    def plot_ias(self, skip_s: float | None = None, revs: float | None = None):
        """IAS [r/min] vs shaft angle [rev] (seed fig. 8 analogue); returns the Figure."""
        import matplotlib.pyplot as plt

        sig = self.angle_signal(skip_s)
        fig, ax = plt.subplots(figsize=(8, 3.5))
        n = sig.value.size if revs is None else int(revs * sig.samples_per_rev)
        ax.plot(sig.angle[:n] / (2 * np.pi), sig.value[:n] * 60 / (2 * np.pi), lw=0.8)
        ax.set_xlabel("shaft angle [rev]")
        ax.set_ylabel("IAS [r/min]")
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
        )
        fig.axes[0].set_title(f"IAS order spectrum (BPFO order {bp:.4f} and harmonics dashed)")
        return fig

    # ------------------------------------------------------------------------- save / load
    def save(self, path) -> None:
        """Write a netCDF file (xarray/h5netcdf, float64, lossless) atomically."""
        import json

        import xarray as xr

        from ...io.atomic import atomic_path
        from ...io.jsonable import to_jsonable

        data = {n: ("t", self.state[:, i]) for i, n in enumerate(STATE_NAMES)}
        data.update({n: ("t", self.aux[:, i]) for i, n in enumerate(AUX_NAMES)})
        ds = xr.Dataset(data, coords={"t": self.t})
        pd = self.params.as_dict()
        pd["bearing"] = asdict(self.params.bearing)
        ds.attrs.update(
            model="IAS (seed 002, Han, Guo, Fan 2025)",
            params=json.dumps(to_jsonable(pd)),
            constants=json.dumps(to_jsonable(asdict(self.constants))),
            solver=json.dumps(to_jsonable(self.solver)),
            version=self.version,
            units="SI: t s, x y m, theta rad, vx vy m/s, omega rad/s, torques N m, forces N",
        )
        with atomic_path(path, suffix=".nc") as tmp:
            ds.to_netcdf(tmp, engine="h5netcdf")

    @classmethod
    def load(cls, path) -> IasResult:
        """Read a file written by :meth:`save`."""
        import json

        import xarray as xr

        from ...materials import Material

        try:
            with xr.open_dataset(path, engine="h5netcdf") as ds:
                ds.load()
        except (OSError, ValueError) as exc:
            raise ConfigError(
                f"file = {str(path)!r} is not a readable IAS result ({exc})"
            ) from None
        if "params" not in ds.attrs or "omega" not in ds:
            raise ConfigError(f"file = {str(path)!r} is not an IAS result written by bearingsim")
        pd = json.loads(ds.attrs["params"])
        bd = pd.pop("bearing")
        bd["material"] = Material(**bd["material"])
        pd["bearing"] = RollerBearing(**bd)
        pd["initial_displacement"] = tuple(pd["initial_displacement"])
        if pd.get("spall") is not None:
            pd["spall"] = Defect(**pd["spall"])
        params = IasParams(**pd)
        cd = json.loads(ds.attrs["constants"])
        const = IasConstants(**cd)
        state = np.stack([ds[n].values for n in STATE_NAMES], 1)
        aux = np.stack([ds[n].values for n in AUX_NAMES], 1)
        return cls(
            ds["t"].values,
            state,
            aux,
            params,
            const,
            json.loads(ds.attrs["solver"]),
            ds.attrs["version"],
        )
