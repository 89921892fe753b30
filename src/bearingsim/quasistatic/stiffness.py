"""Bearing stiffness vs cage angle and its fluctuation spectrum (seed QS5 §2–3).

The 5x5 tangent stiffness of :mod:`bearingsim.quasistatic.jones` (or of the ISO/TS 16281
method, :mod:`bearingsim.quasistatic.iso16281`) is evaluated at ``points_per_rev`` cage positions
per cage revolution over ``cage_revs`` revolutions. Three scalar stiffnesses are extracted:

* radial ``k_r = n^T K_xy n`` along the radial-load direction ``n = (sin theta_0, cos theta_0)``
  (``n = e_y`` without radial load) [N/m];
* axial ``k_a = K_zz`` [N/m];
* tilting (overturning) ``k_t = m^T K_theta m`` about the in-plane axis normal to the load plane,
  ``m = (cos theta_0, -sin theta_0)`` (rotation vector components ``theta_x, theta_y``)
  [N m/rad].

Each series is analysed in orders: ``order_cage`` = cycles per cage revolution, ``order_shaft =
order_cage * FTF order`` (cycles per shaft revolution). The amplitude spectrum is
:func:`bearingsim.signal.amplitude_spectrum` (mean removed, Hann window corrected for its coherent
gain: a sinusoid of amplitude ``a`` reads ``a``), with the periodic Hann window.
Peaks are labelled with the nearest named component within 1.5 frequency bins: ``cage``, ``m×cage``,
``Z×cage (VC)`` (the outer-race ball pass, variable compliance), ``n×shaft`` and their
combinations ``kZ×cage ± n×shaft``.
"""

from __future__ import annotations

import math
from dataclasses import asdict, dataclass
from typing import ClassVar

import numpy as np
from numpy.typing import NDArray
from scipy.signal import find_peaks

from ..dynamics.budget import F8, Budget, Estimate, check_budget
from ..errors import ConfigError, check_range
from ..geometry import Bearing, parse_enum
from ..results import Result, json_attr, read_json_attr
from ..signal.peaks import refine_peak
from ..signal.spectrum import Domain, amplitude_spectrum
from .inputs import Method
from .jones import run_quasi_static
from .result import QuasiStaticSolution

__all__ = [
    "SERIES",
    "SpectralComponent",
    "StiffnessResult",
    "StiffnessSpectrum",
    "component_names",
    "label_order",
    "order_spectrum",
    "stiffness_vs_cage",
]

#: the three scalar stiffness series, in order
SERIES = ("radial", "axial", "tilt")
_UNITS = {"radial": "N/m", "axial": "N/m", "tilt": "N m/rad"}
#: plotted unit of each series: (factor from SI, unit)
_PLOT_UNITS = {"radial": (1e6, "MN/m"), "axial": (1e6, "MN/m"), "tilt": (1.0, "N m/rad")}


@dataclass(frozen=True)
class SpectralComponent:
    """One labelled peak of a stiffness spectrum.

    Attributes
    ----------
    order_shaft : float
        Cycles per shaft revolution [-] (interpolated peak).
    order_cage : float
        Cycles per cage revolution [-].
    amplitude : float
        Peak amplitude, unit of the series [N/m or N m/rad].
    amplitude_rel : float
        Amplitude / mean of the series [-].
    label : str
        Named component (empty when none is within tolerance).
    """

    order_shaft: float
    order_cage: float
    amplitude: float
    amplitude_rel: float
    label: str


@dataclass(frozen=True)
class StiffnessSpectrum:
    """Order spectrum of one stiffness series.

    Attributes
    ----------
    order_cage, order_shaft : ndarray
        Frequency axis in cage and shaft orders [-].
    amplitude : ndarray
        One-sided amplitude [unit of the series].
    components : list of SpectralComponent
        Dominant peaks, largest first.
    """

    order_cage: NDArray[np.float64]
    order_shaft: NDArray[np.float64]
    amplitude: NDArray[np.float64]
    components: list[SpectralComponent]

    def amplitude_at(self, order_shaft: float, halfwidth_bins: float = 1.5) -> float:
        """Largest amplitude within ``halfwidth_bins`` bins of ``order_shaft`` [series unit]."""
        df = self.order_shaft[1] - self.order_shaft[0]
        sel = np.abs(self.order_shaft - order_shaft) <= halfwidth_bins * df
        return float(self.amplitude[sel].max()) if np.any(sel) else 0.0


def component_names(
    n_balls: int, cage_ratio: float, cage_harmonics: bool = True, shaft_harmonics: bool = True
) -> list[tuple[str, float]]:
    """Named orders ``(label, order_shaft)``: ball-pass multiples ``kZ×cage`` always; cage
    harmonics ``m×cage`` when the balls are unevenly spaced; shaft harmonics ``n×shaft`` and the
    combinations ``n×shaft ± kZ×cage`` (e.g. the inner-race ball pass ``Z×shaft-Z×cage``) when a
    pattern turns with the shaft."""
    Z = n_balls
    out: list[tuple[str, float]] = [(f"Z×cage (VC, {Z}×cage)", Z * cage_ratio)]
    out += [(f"{k}Z×cage", k * Z * cage_ratio) for k in (2, 3, 4)]
    if cage_harmonics:
        out.append(("cage", cage_ratio))
        out += [(f"{m}×cage", m * cage_ratio) for m in range(2, 4 * Z + 1) if m % Z]
    if shaft_harmonics:
        out += [("shaft", 1.0)] + [(f"{n}×shaft", float(n)) for n in range(2, 2 * Z + 1)]
        for k in (1, 2):
            kz = "Z" if k == 1 else f"{k}Z"
            for n in range(1, 2 * Z + 1):
                ns = "shaft" if n == 1 else f"{n}×shaft"
                out.append((f"{kz}×cage+{ns}", k * Z * cage_ratio + n))
                o = n - k * Z * cage_ratio
                if o > 0:
                    name = f"{ns}-{kz}×cage" + (" (BPFI)" if (n == Z and k == 1) else "")
                    out.append((name, o))
                elif o < 0:
                    out.append((f"{kz}×cage-{ns}", -o))
    return out


def label_order(
    order_shaft: float,
    n_balls: int,
    cage_ratio: float,
    tolerance: float,
    cage_harmonics: bool = True,
    shaft_harmonics: bool = True,
) -> str:
    """Nearest named component within ``tolerance`` shaft orders, or ``""``."""
    best, dbest = "", tolerance
    for name, o in component_names(n_balls, cage_ratio, cage_harmonics, shaft_harmonics):
        dd = abs(order_shaft - o)
        if dd <= dbest * (1 - 1e-12):
            best, dbest = name, dd
    return best


#: components smaller than this share of the series' mean are not reported (a constant
#: stiffness, e.g. under a centred axial load, has only round-off in its spectrum) [-]
CONSTANT_REL = 1e-8


def order_spectrum(
    series: NDArray[np.float64],
    points_per_rev: int,
    cage_ratio: float,
    n_balls: int,
    n_components: int = 5,
    cage_harmonics: bool = True,
    shaft_harmonics: bool = True,
) -> StiffnessSpectrum:
    """Hann-windowed amplitude spectrum of a stiffness series sampled ``points_per_rev`` times
    per cage revolution, in cage and shaft orders, with its ``n_components`` largest peaks
    labelled (:func:`bearingsim.signal.refine_peak` on the log amplitude around each peak)."""
    x = np.asarray(series, dtype=float)
    sp = amplitude_spectrum(x, points_per_rev, domain=Domain.ORDER, sym=False)
    amp, oc = sp.amplitude, sp.freq
    os_ = oc * cage_ratio
    mean = abs(float(x.mean())) or 1.0
    # a component below CONSTANT_REL of the mean is the solver's round-off, not a fluctuation
    floor = max(1e-9 * max(float(amp.max()), 1e-300), CONSTANT_REL * mean)
    peaks, _ = find_peaks(np.r_[0.0, amp[1:]], height=floor)
    peaks = peaks[np.argsort(amp[peaks])[::-1]][:n_components]
    df = oc[1] - oc[0]
    comps = []
    for p in peaks:
        shift, _ = refine_peak(amp, int(p), log=True)
        o_c = (p + shift) * df
        o_s = o_c * cage_ratio
        comps.append(
            SpectralComponent(
                order_shaft=float(o_s),
                order_cage=float(o_c),
                amplitude=float(amp[p]),
                amplitude_rel=float(amp[p] / mean),
                label=label_order(
                    o_s, n_balls, cage_ratio, 1.5 * df * cage_ratio, cage_harmonics, shaft_harmonics
                ),
            )
        )
    return StiffnessSpectrum(oc, os_, amp, comps)


@dataclass(frozen=True)
class StiffnessResult(Result):
    """Stiffness vs cage angle with its spectra (seed QS5 §2–3).

    Saved as netCDF-4 (:meth:`save`, lossless :meth:`load`); :meth:`to_dict` is the JSON
    summary (``bearingsim stiffness --json``).

    Attributes
    ----------
    solution : QuasiStaticSolution
        Equilibria, stiffness matrices and ball loads at every cage angle.
    cage_revs : int
        Number of cage revolutions [-].
    points_per_rev : int
        Cage positions per revolution [-].
    radial_direction : ndarray, shape (2,)
        Unit vector ``n`` of the radial stiffness [-].
    k_radial, k_axial, k_tilt : ndarray
        Stiffness series [N/m, N/m, N m/rad].
    spectra : dict of StiffnessSpectrum
        Keys ``radial``, ``axial``, ``tilt``.
    """

    FORMAT: ClassVar[str] = "bearingsim.StiffnessResult/1"

    solution: QuasiStaticSolution
    cage_revs: int
    points_per_rev: int
    radial_direction: NDArray[np.float64]
    k_radial: NDArray[np.float64]
    k_axial: NDArray[np.float64]
    k_tilt: NDArray[np.float64]
    spectra: dict[str, StiffnessSpectrum]

    def series(self, name: str) -> NDArray[np.float64]:
        """Stiffness series ``radial`` [N/m], ``axial`` [N/m] or ``tilt`` [N m/rad]."""
        if name not in SERIES:
            raise ConfigError(f"series = {name!r} is invalid; valid: " + ", ".join(SERIES))
        return {"radial": self.k_radial, "axial": self.k_axial, "tilt": self.k_tilt}[name]

    def fluctuation(self) -> dict[str, dict[str, object]]:
        """Mean, peak-to-peak (absolute and relative) and dominant orders of each series."""
        out: dict[str, dict[str, object]] = {}
        for name in SERIES:
            k = self.series(name)
            mean = float(k.mean())
            p2p = float(k.max() - k.min())
            comps = self.spectra[name].components
            out[name] = {
                "unit": _UNITS[name],
                "mean": mean,
                "peak_to_peak": p2p,
                "peak_to_peak_rel": p2p / abs(mean) if mean else math.nan,
                "dominant_orders_shaft": [c.order_shaft for c in comps],
                "components": [asdict(c) for c in comps],
            }
        return out

    def to_dict(self, full: bool = True) -> dict[str, object]:
        """JSON-ready summary (``full`` adds every array, enough to rebuild the result)."""
        s = self.solution
        u0 = s.displacement[0]
        out: dict[str, object] = {
            "bearing": s.bearing_id,
            "method": s.method.value,
            "displacement": dict(
                zip(
                    ("x_m", "y_m", "z_m", "theta_x_rad", "theta_y_rad"), map(float, u0), strict=True
                )
            ),
            "stiffness_matrix": s.stiffness_matrix.at(0).values,
            "k_radial_mean": float(self.k_radial.mean()),
            "k_axial_mean": float(self.k_axial.mean()),
            "k_tilt_mean": float(self.k_tilt.mean()),
            "fluctuation": self.fluctuation(),
            "cage_revs": self.cage_revs,
            "points_per_rev": self.points_per_rev,
            "cage_order_shaft": s.geometry.cage_ratio,
            "ball_pass_order_shaft": s.geometry.n_balls * s.geometry.cage_ratio,
        }
        if full:
            out["inputs"] = {
                "applied": s.applied,
                "free": s.free,
                "misalignment": asdict(s.misalignment),
                "ball_errors_rad": s.ball_errors,
                "speed": asdict(s.speed),
                "geometry": asdict(s.geometry),
            }
            out["arrays"] = {
                "cage_angle": s.cage_angle,
                "displacement": s.displacement,
                "stiffness_matrix": s.stiffness_matrix.values,
                "reaction": s.reaction,
                "ball_angles": s.ball_angles,
                "ball_loads": s.ball_loads,
                "contact_angles": s.contact_angles,
                "deflections": s.deflections,
                "iterations": s.iterations,
                "residual": s.residual,
                "radial_direction": self.radial_direction,
            }
        return out

    # ---------------------------------------------------------------------------- files
    def to_dataset(self):
        """The result as an :class:`xarray.Dataset`: the solution's variables
        (:meth:`QuasiStaticSolution.to_dataset`), the series ``k_radial``, ``k_axial``,
        ``k_tilt`` over ``position``, the amplitude spectra ``spectrum_<series>`` over ``order``
        (coordinates ``order_cage``, ``order_shaft``) and the analysis settings and labelled
        peaks as JSON attributes."""
        ds = self.solution.to_dataset()
        for name in SERIES:
            ds[f"k_{name}"] = ("position", self.series(name), {"units": _UNITS[name]})
        sp0 = self.spectra[SERIES[0]]
        ds = ds.assign_coords(
            order_cage=("order", sp0.order_cage, {"units": "1", "long_name": "cage orders"}),
            order_shaft=("order", sp0.order_shaft, {"units": "1", "long_name": "shaft orders"}),
        )
        for name in SERIES:  # one order axis: every series has the same length and sampling
            amp = self.spectra[name].amplitude
            ds[f"spectrum_{name}"] = ("order", amp, {"units": _UNITS[name]})
        ds.attrs["format"] = self.FORMAT
        ds.attrs["analysis_json"] = json_attr(
            {
                "cage_revs": self.cage_revs,
                "points_per_rev": self.points_per_rev,
                "radial_direction": self.radial_direction,
                "components": {
                    name: [asdict(c) for c in self.spectra[name].components] for name in SERIES
                },
            }
        )
        return ds

    @classmethod
    def from_dataset(cls, ds) -> StiffnessResult:
        """Inverse of :meth:`to_dataset`."""
        cls.check_format(ds)
        an = read_json_attr(ds, "analysis_json")
        oc = np.asarray(ds["order_cage"].values)
        os_ = np.asarray(ds["order_shaft"].values)
        spectra = {
            name: StiffnessSpectrum(
                oc,
                os_,
                np.asarray(ds[f"spectrum_{name}"].values),
                [SpectralComponent(**c) for c in an["components"][name]],
            )
            for name in SERIES
        }
        return cls(
            QuasiStaticSolution._read(ds),
            int(an["cage_revs"]),
            int(an["points_per_rev"]),
            np.array(an["radial_direction"], dtype=float),
            *(np.asarray(ds[f"k_{name}"].values) for name in SERIES),
            spectra,
        )

    # ---------------------------------------------------------------------------- plots
    def _draw_series(self, ax, name: str) -> None:
        f, u = _PLOT_UNITS[name]
        ax.plot(np.degrees(self.solution.cage_angle), self.series(name) / f, lw=1)
        ax.set_ylabel(f"k_{name} [{u}]")
        ax.ticklabel_format(axis="y", useOffset=False)
        ax.grid(alpha=0.3)

    def _draw_spectrum(self, ax, name: str, top: float) -> None:
        from ..plotting import label_points

        f, u = _PLOT_UNITS[name]
        sp = self.spectra[name]
        sel = (sp.order_shaft > 0) & (sp.order_shaft <= top)
        ax.plot(sp.order_shaft[sel], sp.amplitude[sel] / f, lw=1)
        comps = [c for c in sp.components[:3] if c.order_shaft <= top]
        label_points(
            ax,
            [c.order_shaft for c in comps],
            [c.amplitude / f for c in comps],
            [c.label or f"{c.order_shaft:.3f}" for c in comps],
            marker=None,
            min_sep=0.12,
        )
        ax.set_ylim(top=1.25 * ax.get_ylim()[1])  # room for the labels
        ax.set_ylabel(f"k_{name} amplitude [{u}]")
        ax.grid(alpha=0.3)

    def plot_series(self):
        """Radial, axial and tilting stiffness vs cage angle; returns the Figure."""
        from ..plotting import FULL_WIDTH, new_figure

        fig, axs = new_figure(3, 1, width=FULL_WIDTH, row_height=2.0, sharex=True)
        for ax, name in zip(axs, SERIES, strict=True):
            self._draw_series(ax, name)
        axs[-1].set_xlabel("cage angle [deg]")
        axs[0].set_title(
            f"{self.solution.bearing_id}: stiffness vs cage angle ({self.solution.method.value})"
        )
        return fig

    def plot_spectra(self, max_order_shaft: float | None = None):
        """Amplitude spectra in shaft orders with the dominant peaks labelled; returns the
        Figure."""
        from ..plotting import FULL_WIDTH, new_figure

        g = self.solution.geometry
        top = max_order_shaft or 2.5 * g.n_balls * g.cage_ratio
        fig, axs = new_figure(3, 1, width=FULL_WIDTH, row_height=2.0, sharex=True)
        for ax, name in zip(axs, SERIES, strict=True):
            self._draw_spectrum(ax, name, top)
        axs[-1].set_xlabel("order [cycles per shaft revolution]")
        axs[0].set_title("stiffness fluctuation spectra")
        return fig

    def plot(self):
        """Series (left) and spectra (right) of the three stiffnesses; returns the Figure."""
        from ..plotting import FULL_WIDTH, new_figure

        g = self.solution.geometry
        top = 2.5 * g.n_balls * g.cage_ratio
        fig, axs = new_figure(3, 2, width=FULL_WIDTH, row_height=2.1, sharex="col")
        for row, name in enumerate(SERIES):
            self._draw_series(axs[row, 0], name)
            self._draw_spectrum(axs[row, 1], name, top)
        axs[-1, 0].set_xlabel("cage angle [deg]")
        axs[-1, 1].set_xlabel("order [cycles per shaft revolution]")
        axs[0, 0].set_title(f"{self.solution.bearing_id}: stiffness vs cage angle")
        axs[0, 1].set_title("fluctuation amplitude spectra")
        return fig

    def plot_loads(self, index: int = 0):
        """Polar bar plot of the ball loads at cage position ``index``; returns the Figure."""
        return self.solution.plot_loads(index)


def _build(
    sol: QuasiStaticSolution,
    cage_revs: int,
    points_per_rev: int,
    n: NDArray[np.float64],
    n_components: int = 5,
) -> StiffnessResult:
    H = sol.stiffness_matrix.stack
    m = np.array([n[1], -n[0]])
    kr = np.einsum("i,mij,j->m", n, H[:, :2, :2], n)
    kt = np.einsum("i,mij,j->m", m, H[:, 3:, 3:], m)
    ka = H[:, 2, 2].copy()
    g = sol.geometry
    ch = bool(np.any(sol.ball_errors != 0))
    sh = sol.misalignment.inner_tilt > 0
    spectra = {
        name: order_spectrum(k, points_per_rev, g.cage_ratio, g.n_balls, n_components, ch, sh)
        for name, k in zip(SERIES, (kr, ka, kt), strict=True)
    }
    return StiffnessResult(sol, cage_revs, points_per_rev, n, kr, ka, kt, spectra)


# (duplicates) the load arguments repeat run_quasi_static's: the same loads, swept in cage angle
#: memory held per cage position [float64 words]: the 5x5 stiffness, the equilibrium and the
#: spectra, and per ball its loads, angles and deflections (measured with tracemalloc: about
#: 1000 B per position for the 6205, Z = 9, Jones method)
BASE_PER_POINT, BALL_PER_POINT = 40, 12


def stiffness_vs_cage(
    bearing: Bearing,
    fx: float = 0.0,
    fy: float = 0.0,
    fz: float = 0.0,
    mx: float = 0.0,
    my: float = 0.0,
    *,
    cage_revs: int = 10,
    points_per_rev: int = 360,
    method: Method | str = Method.JONES,
    n_components: int = 5,
    budget: Budget | None = None,
    **kwargs: object,
) -> StiffnessResult:
    """Radial, axial and tilting stiffness over ``cage_revs`` cage revolutions and their order
    spectra (seed QS5 §2–3; SPEC §5).

    Parameters
    ----------
    bearing : BallBearing
        Geometry and material.
    fx, fy, fz : float
        Forces on the inner ring [N].
    mx, my : float
        Moments on the inner ring [N m].
    cage_revs : int
        Cage revolutions [-], >= 1.
    points_per_rev : int
        Cage positions per revolution [-], >= 4 Z (resolves the ball pass and its harmonic).
    method : Method or {"jones", "iso16281"}
        Load-distribution method.
    n_components : int
        Number of labelled spectral peaks per series [-].
    budget : Budget, optional
        Memory the run may use (default: half the available memory); a run estimated above it
        (:data:`BASE_PER_POINT`, :data:`BALL_PER_POINT`) is refused in one line before any
        work.
    **kwargs
        ``clearance``, ``misalignment``, ``ball_errors``, ``first_ball_angle``, ``tilt_free``,
        ``speed``, ``stiffness``, ``max_contact_angle`` as :func:`run_quasi_static`;
        ``conformities`` for the ISO method (:func:`~.iso16281.run_iso16281`).
    """
    method = parse_enum(Method, method, "method")
    revs = check_range("cage_revs", cage_revs, 1, 10000, unit="rev")
    if revs != int(revs):
        raise ConfigError(f"cage_revs = {cage_revs!r} is not an integer; valid range [1, 10000]")
    Z = bearing.n_elements
    ppr = check_range("points_per_rev", points_per_rev, 4 * Z, 100000)
    if ppr != int(ppr):
        raise ConfigError(
            f"points_per_rev = {points_per_rev!r} is not an integer; valid range [{4 * Z}, 100000]"
        )
    revs, ppr = int(revs), int(ppr)
    n_pts = revs * ppr
    check_budget(
        Estimate(
            f"stiffness: {revs} cage revolutions x {ppr} points",
            float(n_pts) * F8 * (BASE_PER_POINT + BALL_PER_POINT * Z),
            0.0,
        ),
        budget,
    )
    cage = 2.0 * np.pi * np.arange(n_pts) / ppr
    if method is Method.JONES:
        sol = run_quasi_static(bearing, cage, fx, fy, fz, mx, my, **kwargs)
    else:
        from .iso16281 import run_iso16281

        sol = run_iso16281(bearing, cage, fx, fy, fz, mx, my, **kwargs)
    fr = math.hypot(sol.applied[0], sol.applied[1])
    n = sol.applied[:2] / fr if fr > 0 else np.array([0.0, 1.0])
    return _build(sol, revs, ppr, n, n_components)
