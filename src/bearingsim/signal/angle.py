"""Angle-domain processing of shaft-speed signals: angular resampling, order spectrum, synchronous
averaging and spall-width estimation (seed IAS §3.1, eq. (37); SPEC §0.5 order tracking).

Everything here works on a *signal* — simulated or measured (encoder timestamps, angle vs time
or speed vs time) — and never on a model's internals.

Spall-width estimation (:func:`estimate_spall_width`)
    1. the IAS ``omega(theta)`` on a uniform shaft-angle grid;
    2. its order spectrum; the fault order ``f_o`` is the strongest peak within ±10 % of an
       expected order (e.g. the kinematic BPFO order), refined by interpolation — so cage slip
       in a measurement is followed;
    3. synchronous average of ``omega`` over the fault period ``2 pi / f_o`` (one roller pass);
    4. the crossing angle from the averaged event:

       ``STEPS`` (default)
           the two sharpest speed drops of the event are the roller's entry into the spall (its
           load is released onto the leading edge) and its impact on the trailing edge. A roller
           that bridges a spall narrower than its diameter touches the trailing edge when its
           centre is above the spall centre (seed IAS eqs. (19)–(21): the drop ``H_m`` and
           ``lambda`` refer to that position), so the entry-to-exit angle is twice the
           entry-to-impact angle;
       ``EXTENT``
           the angular extent of the event: where the averaged speed deviates from its baseline
           (median) by more than ``threshold`` times the event's peak deviation (what one reads
           off the seed's fig. 10). Smooth tails end inside the threshold, so this reads short;
    5. the width by seed IAS eq. (37): ``L_d = D_o theta_shaft f_cage / (2 f_shaft)``.
"""

from __future__ import annotations

import enum
import math
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike, NDArray
from scipy.signal import find_peaks

from ..errors import ConfigError, check_positive, check_range

TWO_PI = 2.0 * math.pi


def _arr(name: str, v: ArrayLike) -> NDArray[np.float64]:
    a = np.asarray(v, dtype=float).ravel()
    if a.size < 4:
        raise ConfigError(f"{name} has {a.size} samples; valid range >= 4 samples")
    if not np.all(np.isfinite(a)):
        raise ConfigError(f"{name} contains a non-finite value; valid range finite numbers")
    return a


@dataclass(frozen=True)
class AngleSignal:
    """A signal sampled uniformly in shaft angle.

    Attributes
    ----------
    angle : ndarray
        Shaft angle [rad], uniform step ``2 pi / samples_per_rev``.
    value : ndarray
        Signal at those angles (here the angular speed [rad/s]).
    samples_per_rev : int
        Samples per shaft revolution [-].
    """

    angle: NDArray[np.float64]
    value: NDArray[np.float64]
    samples_per_rev: int

    @property
    def n_revs(self) -> float:
        """Length in shaft revolutions [-]."""
        return self.value.size / self.samples_per_rev

    def plot(
        self,
        ax=None,
        label: str | None = None,
        scale: float = 60.0 / TWO_PI,
        ylabel: str = "IAS [r/min]",
    ):
        """Signal vs shaft angle in revolutions; returns the Figure."""
        import matplotlib.pyplot as plt

        fig = None
        if ax is None:
            fig, ax = plt.subplots(figsize=(8, 3.5))
        ax.plot(self.angle / TWO_PI, self.value * scale, lw=0.8, label=label)
        ax.set_xlabel("shaft angle [rev]")
        ax.set_ylabel(ylabel)
        return fig or ax.figure


def speed_from_angle(t: ArrayLike, angle: ArrayLike) -> NDArray[np.float64]:
    """Angular speed ``d angle/dt`` [rad/s] at the samples (second-order differences; for encoder
    timestamps this is the elapsed-time method).

    Parameters
    ----------
    t : array_like
        Sample times [s], strictly increasing.
    angle : array_like
        Shaft angle [rad] at ``t``.
    """
    tt = _arr("time_s", t)
    th = _arr("angle_rad", angle)
    if tt.size != th.size:
        raise ConfigError(f"angle has {th.size} samples but time has {tt.size}; they must match")
    if np.any(np.diff(tt) <= 0):
        raise ConfigError("time_s is not strictly increasing; valid: increasing sample times")
    return np.gradient(th, tt, edge_order=2)


def angle_from_speed(t: ArrayLike, speed: ArrayLike) -> NDArray[np.float64]:
    """Shaft angle [rad] by trapezoidal integration of the speed [rad/s] from 0 at ``t[0]``."""
    tt = _arr("time_s", t)
    w = _arr("speed_rad_s", speed)
    if tt.size != w.size:
        raise ConfigError(f"speed has {w.size} samples but time has {tt.size}; they must match")
    if np.any(np.diff(tt) <= 0):
        raise ConfigError("time_s is not strictly increasing; valid: increasing sample times")
    out = np.empty_like(w)
    out[0] = 0.0
    np.cumsum(0.5 * (w[1:] + w[:-1]) * np.diff(tt), out=out[1:])
    return out


def resample_to_angle(
    angle: ArrayLike,
    value: ArrayLike,
    samples_per_rev: int | None = None,
) -> AngleSignal:
    """Resample ``value`` given at (monotonic) shaft angles onto a uniform angle grid.

    Parameters
    ----------
    angle : array_like
        Shaft angle of each sample [rad]; must increase strictly (the shaft turns one way).
    value : array_like
        Signal at those samples (e.g. angular speed [rad/s]).
    samples_per_rev : int, optional
        Samples per revolution of the output; default: the power of two nearest the input's mean
        density (at least 64).
    """
    th = _arr("angle_rad", angle)
    v = _arr("value", value)
    if th.size != v.size:
        raise ConfigError(f"value has {v.size} samples but angle has {th.size}; they must match")
    if np.any(np.diff(th) <= 0):
        raise ConfigError(
            "angle_rad is not strictly increasing; the shaft must turn one way "
            "(drop the start-up or the stopped part)"
        )
    span = th[-1] - th[0]
    if samples_per_rev is None:
        dens = th.size / (span / TWO_PI)
        samples_per_rev = max(64, 2 ** int(round(math.log2(max(dens, 1.0)))))
    spr = int(check_range("samples_per_rev", samples_per_rev, 8, 2**24))
    step = TWO_PI / spr
    n = int(math.floor(span / step)) + 1
    grid = th[0] + step * np.arange(n)
    return AngleSignal(grid, np.interp(grid, th, v), spr)


@dataclass(frozen=True)
class OrderSpectrum:
    """Single-sided amplitude spectrum versus order (cycles per shaft revolution).

    Attributes
    ----------
    order : ndarray
        Orders [-] (zero-padded grid).
    amplitude : ndarray
        Amplitude of a sinusoid at that order (Hann window, amplitude-corrected), in the unit of
        the signal (e.g. [rad/s]).
    resolution : float
        ``1 / n_revs``, the true order resolution [-].
    """

    order: NDArray[np.float64]
    amplitude: NDArray[np.float64]
    resolution: float

    def plot(
        self,
        ax=None,
        max_order: float = 30.0,
        scale: float = 60.0 / TWO_PI,
        ylabel: str = "amplitude [r/min]",
        marks: ArrayLike | None = None,
    ):
        """Spectrum up to ``max_order`` with optional vertical marks; returns the Figure."""
        import matplotlib.pyplot as plt

        fig = None
        if ax is None:
            fig, ax = plt.subplots(figsize=(8, 3.5))
        m = self.order <= max_order
        ax.plot(self.order[m], self.amplitude[m] * scale, lw=0.8)
        for o in np.atleast_1d(marks if marks is not None else []):
            ax.axvline(o, color="r", ls="--", lw=0.7)
        ax.set_xlabel("order [-]")
        ax.set_ylabel(ylabel)
        return fig or ax.figure


def order_spectrum(sig: AngleSignal, pad_factor: int = 16) -> OrderSpectrum:
    """Order spectrum of an angle-domain signal (mean removed, Hann window, zero padding).

    Parameters
    ----------
    sig : AngleSignal
        Uniformly sampled in angle.
    pad_factor : int
        Zero padding factor (interpolates the spectrum; the resolution stays ``1/n_revs``).
    """
    pad = int(check_range("pad_factor", pad_factor, 1, 1024))
    v = sig.value - sig.value.mean()
    w = np.hanning(v.size)
    nfft = 1 << int(math.ceil(math.log2(v.size * pad)))
    spec = np.abs(np.fft.rfft(v * w, nfft)) * 2.0 / w.sum()
    order = np.fft.rfftfreq(nfft, d=1.0 / sig.samples_per_rev)
    return OrderSpectrum(order, spec, 1.0 / sig.n_revs)


@dataclass(frozen=True)
class OrderPeak:
    """A spectral peak: order [-] and amplitude (signal unit)."""

    order: float
    amplitude: float


def _refine(spec: OrderSpectrum, i: int) -> OrderPeak:
    a = spec.amplitude
    if 0 < i < a.size - 1:
        y0, y1, y2 = a[i - 1], a[i], a[i + 1]
        den = y0 - 2.0 * y1 + y2
        d = 0.5 * (y0 - y2) / den if den != 0 else 0.0
        d = min(max(d, -0.5), 0.5)
        step = spec.order[1] - spec.order[0]
        return OrderPeak(float(spec.order[i] + d * step), float(y1 - 0.25 * (y0 - y2) * d))
    return OrderPeak(float(spec.order[i]), float(a[i]))


def find_order_peaks(
    spec: OrderSpectrum,
    n_peaks: int = 5,
    min_order: float = 0.5,
    max_order: float | None = None,
    rel_height: float = 0.05,
) -> list[OrderPeak]:
    """The ``n_peaks`` largest spectral peaks (refined by parabolic interpolation), by amplitude.

    Peaks closer than two resolutions (the Hann main lobe) are merged; a peak must reach
    ``rel_height`` times the largest one in ``[min_order, max_order]`` (the default 0.05 is above
    the Hann window's highest side lobe, -31.5 dB = 0.027).
    """
    m = spec.order >= min_order
    if max_order is not None:
        m &= spec.order <= max_order
    if not np.any(m):
        return []
    i0 = int(np.argmax(m))
    a = np.where(m, spec.amplitude, 0.0)
    step = spec.order[1] - spec.order[0]
    dist = max(1, int(round(2.0 * spec.resolution / step)))
    idx, _ = find_peaks(a, height=rel_height * a[i0:].max(), distance=dist)
    idx = sorted(idx, key=lambda i: -a[i])[:n_peaks]
    return [_refine(spec, int(i)) for i in idx]


def dominant_order(spec: OrderSpectrum, near: float, rel_tol: float = 0.1) -> OrderPeak:
    """Strongest peak within ``near (1 ± rel_tol)`` [-], refined; raises if none."""
    near = check_positive("expected_order", near)
    m = (spec.order >= near * (1 - rel_tol)) & (spec.order <= near * (1 + rel_tol))
    if not np.any(m):
        raise ConfigError(
            f"expected_order = {near:.6g} is beyond the spectrum (max order "
            f"{spec.order[-1]:.4g}); sample the signal more finely"
        )
    i = int(np.flatnonzero(m)[np.argmax(spec.amplitude[m])])
    return _refine(spec, i)


def synchronous_average(
    sig: AngleSignal, period: float, samples_per_period: int = 1024
) -> tuple[NDArray[np.float64], NDArray[np.float64], int]:
    """Average of the signal over consecutive angular periods.

    Parameters
    ----------
    sig : AngleSignal
        Uniform in shaft angle.
    period : float
        Angular period [rad] (e.g. ``2 pi / BPFO order``).
    samples_per_period : int
        Samples of the averaged period.

    Returns
    -------
    phase : ndarray
        Angle within the period [rad], from the first sample of ``sig``.
    mean : ndarray
        Averaged signal.
    n_periods : int
        Number of whole periods averaged.
    """
    period = check_positive("period_rad", period, "rad")
    span = sig.angle[-1] - sig.angle[0]
    k = int(math.floor(span / period))
    if k < 1:
        raise ConfigError(
            f"signal spans {span:.4g} rad, less than one period {period:.4g} rad; "
            "valid: a longer signal"
        )
    spp = int(check_range("samples_per_period", samples_per_period, 16, 2**20))
    phase = period * np.arange(spp) / spp
    grid = sig.angle[0] + (np.arange(k)[:, None] * period + phase[None, :])
    vals = np.interp(grid.ravel(), sig.angle, sig.value).reshape(k, spp)
    return phase, vals.mean(axis=0), k


def spall_width_from_angle(
    crossing_angle: float, outer_raceway_diameter: float, cage_ratio: float
) -> float:
    """Seed IAS eq. (37): ``L_d = D_o theta_shaft f_cage / (2 f_shaft)`` [m].

    Parameters
    ----------
    crossing_angle : float
        Shaft angle swept while a roller crosses the spall [rad].
    outer_raceway_diameter : float
        D_o [m].
    cage_ratio : float
        ``f_cage / f_shaft`` [-].
    """
    return 0.5 * outer_raceway_diameter * crossing_angle * cage_ratio


class SpallEstimator(enum.Enum):
    """How the crossing angle is read from the synchronous-averaged event."""

    #: twice the angle between the two sharpest speed drops (entry, trailing-edge impact)
    STEPS = "steps"
    #: extent of the deviation above a fraction of its peak (visual reading of seed fig. 10)
    EXTENT = "extent"


@dataclass(frozen=True)
class SpallEstimate:
    """Spall-width estimate from an IAS signal.

    Attributes
    ----------
    width : float
        Estimated spall width L_d [m] (seed eq. (37)).
    crossing_angle : float
        Shaft angle swept while a roller crosses the spall [rad].
    entry_angle, exit_angle : float
        Entry and exit within the averaged period [rad]; for ``STEPS`` also ``impact_angle``.
    impact_angle : float or None
        Angle of the second sharp drop (trailing-edge impact) [rad].
    fault_order : float
        Measured fault order (the averaging period is ``2 pi / fault_order``) [-].
    n_periods : int
        Roller passes averaged [-].
    method : SpallEstimator
        Reading used.
    contrast : float
        Sharpest drop rate over the median absolute rate of the averaged event [-]: a spall gives
        steps far above the smooth ball-pass ripple (>> 10); a healthy bearing does not.
    phase, average : ndarray
        The averaged event (angle [rad], speed [rad/s]), rotated to start mid-way between events.
    """

    width: float
    crossing_angle: float
    entry_angle: float
    exit_angle: float
    impact_angle: float | None
    fault_order: float
    n_periods: int
    method: SpallEstimator
    contrast: float
    phase: NDArray[np.float64]
    average: NDArray[np.float64]

    def plot(self, scale: float = 60.0 / TWO_PI):
        """Averaged roller pass with the detected entry/impact/exit (seed fig. 10 analogue)."""
        import matplotlib.pyplot as plt

        fig, ax = plt.subplots(figsize=(7, 3.5))
        ax.plot(self.phase, self.average * scale, lw=1.0)
        for a, lab, col in (
            (self.entry_angle, "entry", "g"),
            (self.impact_angle, "impact", "m"),
            (self.exit_angle, "exit", "r"),
        ):
            if a is not None:
                ax.axvline(a, color=col, ls="--", lw=0.8, label=lab)
        ax.set_xlim(
            max(0.0, self.entry_angle - self.crossing_angle),
            min(self.phase[-1], self.exit_angle + self.crossing_angle),
        )
        ax.set_xlabel("shaft angle within one roller pass [rad]")
        ax.set_ylabel("IAS [r/min]")
        ax.set_title(
            f"crossing {self.crossing_angle:.4f} rad -> L_d = {self.width * 1e3:.3f} mm "
            f"({self.method.value}, {self.n_periods} passes)"
        )
        ax.legend(loc="lower right")
        return fig


#: minimum step contrast for a spall to be reported (see :attr:`SpallEstimate.contrast`)
MIN_CONTRAST = 20.0


def estimate_spall_width(
    sig: AngleSignal,
    outer_raceway_diameter: float,
    cage_ratio: float,
    expected_order: float,
    *,
    method: SpallEstimator | str = SpallEstimator.STEPS,
    threshold: float = 0.02,
    samples_per_period: int = 4096,
    min_contrast: float = MIN_CONTRAST,
) -> SpallEstimate | None:
    """Estimate an outer-race spall width from an IAS signal (seed IAS eq. (37)); see the module
    docstring for the steps. Returns ``None`` when the averaged pass shows no spall event (step
    contrast below ``min_contrast``).

    Parameters
    ----------
    sig : AngleSignal
        Angular speed [rad/s] uniform in shaft angle (start-up transient removed).
    outer_raceway_diameter : float
        D_o [m].
    cage_ratio : float
        ``f_cage / f_shaft`` [-] (kinematic: ``(1 - D_c cos(alpha)/D_p)/2``).
    expected_order : float
        Where to look for the fault order [-] (the BPFO order).
    method : SpallEstimator
        ``STEPS`` (default) or ``EXTENT``.
    threshold : float
        ``EXTENT`` only: fraction of the peak deviation bounding the event [-].
    samples_per_period : int
        Resolution of the averaged pass [-].
    min_contrast : float
        Detection threshold on the step contrast [-].
    """
    method = SpallEstimator(method)
    do = check_positive("outer_raceway_diameter_m", outer_raceway_diameter, "m")
    rho = check_range("cage_ratio", cage_ratio, 0.0, 1.0, lo_open=True, hi_open=True)
    thr = check_range("threshold", threshold, 0.0, 1.0, lo_open=True, hi_open=True)
    spec = order_spectrum(sig)
    fo = dominant_order(spec, expected_order).order
    period = TWO_PI / fo
    phase, avg, k = synchronous_average(sig, period, samples_per_period)
    n = avg.size
    step = period / n
    rate = np.diff(np.concatenate([avg, avg[:1]])) / step  # circular d(omega)/d(angle)
    med = float(np.median(np.abs(rate)))
    i1 = int(np.argmin(rate))
    contrast = float(-rate[i1] / med) if med > 0 else math.inf
    if not contrast >= min_contrast:
        return None
    # second sharpest drop, outside the first one's neighbourhood
    excl = max(2, n // 200)
    r2 = rate.copy()
    for j in range(-excl, excl + 1):
        r2[(i1 + j) % n] = np.inf
    i2 = int(np.argmin(r2))
    # order them so that entry -> impact is the shorter way round
    d12 = (i2 - i1) % n
    entry, impact = (i1, i2) if d12 <= n // 2 else (i2, i1)
    half = (impact - entry) % n
    # rotate the average so that the event sits in the middle of the plotted pass
    shift = (entry - n // 4) % n
    ph = phase
    av = np.roll(avg, -shift)
    e_idx = (entry - shift) % n
    if method is SpallEstimator.STEPS:
        crossing = 2.0 * half * step
        ex_idx = e_idx + 2 * half
        imp = (e_idx + half) * step + 0.5 * step
        e_ang = e_idx * step + 0.5 * step
        x_ang = ex_idx * step + 0.5 * step
    else:
        base = float(np.median(av))
        dev = np.abs(av - base)
        lim = thr * dev.max()
        idx = np.flatnonzero(dev > lim)
        lo, hi = int(idx[0]), int(idx[-1])
        crossing = (hi - lo + 1) * step
        e_ang, x_ang, imp = lo * step, (hi + 1) * step, None
    width = spall_width_from_angle(crossing, do, rho)
    return SpallEstimate(width, crossing, e_ang, x_ang, imp, fo, k, method, contrast, ph, av)


@dataclass(frozen=True)
class IasSummary:
    """Angle-domain summary of a shaft-speed signal.

    Attributes
    ----------
    mean_speed : float
        Mean angular speed [rad/s] (angle-domain mean).
    ripple_rel : float
        ``(max - min) / mean`` of the speed [-].
    peaks : list of OrderPeak
        Largest order-spectrum peaks, sorted by order.
    spectrum : OrderSpectrum
        The order spectrum.
    bpfo_order : float or None
        Kinematic BPFO order of the bearing, when known [-].
    estimate : SpallEstimate or None
        Spall-width estimate (``None`` when no bearing is known or no spall event is found).
    signal : AngleSignal
        The analysed angle-domain signal.
    """

    mean_speed: float
    ripple_rel: float
    peaks: list[OrderPeak]
    spectrum: OrderSpectrum
    bpfo_order: float | None
    estimate: SpallEstimate | None
    signal: AngleSignal

    def as_dict(self) -> dict:
        """The JSON keys of ``bearingsim ias`` / ``analyze-ias`` (SI; speed also in r/min)."""
        return {
            "mean_speed_rpm": self.mean_speed * 60.0 / TWO_PI,
            "mean_speed_rad_s": self.mean_speed,
            "ias_ripple_rel": self.ripple_rel,
            "order_peaks": [{"order": p.order, "amplitude": p.amplitude} for p in self.peaks],
            "order_peaks_amplitude_unit": "rad/s",
            "bpfo_order_theory": self.bpfo_order,
            "spall_width_estimate_m": None if self.estimate is None else self.estimate.width,
            "spall_crossing_angle_rad": (
                None if self.estimate is None else self.estimate.crossing_angle
            ),
            "fault_order_measured": None if self.estimate is None else self.estimate.fault_order,
            "n_revs_analysed": self.signal.n_revs,
        }


def analyze_speed_signal(
    sig: AngleSignal,
    *,
    bpfo_order: float | None = None,
    outer_raceway_diameter: float | None = None,
    cage_ratio: float | None = None,
    n_peaks: int = 5,
    method: SpallEstimator | str = SpallEstimator.STEPS,
) -> IasSummary:
    """Mean speed, ripple, order peaks and (when the bearing is known) spall-width estimate.

    Parameters
    ----------
    sig : AngleSignal
        Angular speed [rad/s] uniform in shaft angle.
    bpfo_order : float, optional
        Kinematic BPFO order [-]; needed for the estimate.
    outer_raceway_diameter : float, optional
        D_o [m]; needed for the estimate.
    cage_ratio : float, optional
        ``f_cage/f_shaft`` [-]; needed for the estimate.
    n_peaks : int
        Number of order peaks reported.
    method : SpallEstimator
        Crossing-angle reading.
    """
    mean = float(sig.value.mean())
    if not mean > 0:
        raise ConfigError(
            f"mean speed = {mean:.6g} rad/s; valid range (0, inf) rad/s (the shaft must turn)"
        )
    ripple = float((sig.value.max() - sig.value.min()) / mean)
    spec = order_spectrum(sig)
    peaks = sorted(find_order_peaks(spec, n_peaks=n_peaks), key=lambda p: p.order)
    est = None
    if None not in (bpfo_order, outer_raceway_diameter, cage_ratio):
        est = estimate_spall_width(
            sig, outer_raceway_diameter, cage_ratio, bpfo_order, method=method
        )
    return IasSummary(mean, ripple, peaks, spec, bpfo_order, est, sig)
