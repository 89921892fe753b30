"""Angle-domain processing (order analysis) of signals, simulated or measured: shaft speed and
angle conversion, the anti-aliased angular resampler, the order spectrum, synchronous
averaging, and reading shaft angle/speed files (encoders, IAS).

Angular resampling (:func:`resample_to_angle`)
    Computed order tracking (Fyfe & Munck 1997, "Analysis of computed order tracking", MSSP
    11(2), 187–205). A signal given at known, strictly increasing shaft angles (uniform in time,
    or encoder timestamps) is resampled at ``samples_per_rev`` uniform angle steps. Where the
    input is denser than the output (slow shaft, high sample rate), orders above the output's
    Nyquist order ``samples_per_rev / 2`` would alias; the signal is then first interpolated
    onto a grid ``L`` times finer than the output, with ``L samples_per_rev`` at least the
    densest input (nothing aliases there), and decimated by ``L`` with
    :func:`scipy.signal.resample_poly` (Kaiser-windowed FIR low-pass at ``samples_per_rev / 2``
    orders, zero phase, the ends extended along the line through the first and last samples).
    Where the output is at least as dense as the input, plain interpolation is exact enough and
    nothing is filtered. The density is the 1st percentile of the angle steps (robust to timing
    jitter), and the finer grid holds at most four times the input's samples. The FIR (SciPy's
    default Kaiser window, beta 5, 10 taps per phase) passes orders below 0.8 of the Nyquist
    order within 0.2 % and attenuates orders above 1.2 of it by more than 50 dB (the transition
    band lies between); its end transients span ~10 output samples.

Memory (:func:`angle_grid`, :attr:`AngleGrid.memory`)
    The output holds ``n_revs * samples_per_rev`` samples, whatever the input's length: a
    ``samples_per_rev`` of 16 million over 125 revolutions, a speed in r/min read as rad/s, or
    times in the wrong unit ask for terabytes. :func:`angle_grid` estimates, before anything is
    allocated, the memory of the resampling and of the zero-padded order spectrum that every
    angle-domain analysis computes next; :func:`resample_to_angle` with ``max_memory`` refuses
    in one line a grid above it, naming the ``samples_per_rev`` that would fit.

Order spectrum (:func:`order_spectrum`)
    the amplitude spectrum of :mod:`.spectrum` over orders (cycles per shaft revolution), zero
    padded to interpolate between the lines (the resolution stays ``1 / n_revs``).

Everything here works on a *signal* and never on a model's internals.
"""

from __future__ import annotations

import enum
import math
from dataclasses import dataclass
from pathlib import Path

import numpy as np
from numpy.typing import ArrayLike, NDArray

from ..errors import ConfigError, check_positive, check_range
from ..geometry import parse_enum
from .spectrum import Domain, Spectrum, amplitude_spectrum, as_signal

__all__ = [
    "AngleGrid",
    "AngleSignal",
    "Interpolation",
    "ShaftSignalKind",
    "analysis_memory",
    "angle_from_speed",
    "angle_grid",
    "order_spectrum",
    "read_shaft_signal",
    "resample_to_angle",
    "speed_from_angle",
    "synchronous_average",
]

TWO_PI = 2.0 * math.pi


def _arr(name: str, v: ArrayLike) -> NDArray[np.float64]:
    return as_signal(v, name, min_samples=4)


def _time_and(t: ArrayLike, name: str, v: ArrayLike) -> tuple[NDArray, NDArray]:
    """Validated sample times [s] (strictly increasing) and a signal ``name`` as long."""
    tt = _arr("time_s", t)
    a = _arr(name, v)
    if tt.size != a.size:
        raise ConfigError(f"{name} has {a.size} samples but time has {tt.size}; they must match")
    if np.any(np.diff(tt) <= 0):
        raise ConfigError("time_s is not strictly increasing; valid: increasing sample times")
    return tt, a


@dataclass(frozen=True)
class AngleSignal:
    """A signal sampled uniformly in shaft angle.

    Attributes
    ----------
    angle : ndarray
        Shaft angle [rad], uniform step ``2 pi / samples_per_rev``.
    value : ndarray
        Signal at those angles (any unit; for IAS the angular speed [rad/s]).
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
        """Signal vs shaft angle in revolutions; returns the Figure.

        Parameters
        ----------
        ax : matplotlib Axes, optional
            Axes to draw in (default: a new figure).
        label : str, optional
            Legend label.
        scale : float
            Factor applied to the values (default rad/s -> r/min) [-].
        ylabel : str
            Label of the value axis.
        """
        from ..plotting import FULL_WIDTH, new_figure

        fig = None
        if ax is None:
            fig, ax = new_figure(width=FULL_WIDTH, height=3.2)
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
    tt, th = _time_and(t, "angle_rad", angle)
    return np.gradient(th, tt, edge_order=2)


def angle_from_speed(t: ArrayLike, speed: ArrayLike) -> NDArray[np.float64]:
    """Shaft angle [rad] by trapezoidal integration of the speed from 0 at ``t[0]``.

    Parameters
    ----------
    t : array_like
        Sample times [s], strictly increasing.
    speed : array_like
        Angular speed [rad/s] at ``t``.
    """
    tt, w = _time_and(t, "speed_rad_s", speed)
    out = np.empty_like(w)
    out[0] = 0.0
    np.cumsum(0.5 * (w[1:] + w[:-1]) * np.diff(tt), out=out[1:])
    return out


class Interpolation(enum.Enum):
    """Interpolation between the input samples of :func:`resample_to_angle`."""

    #: piecewise linear (:func:`numpy.interp`): no overshoot at steps (IAS events)
    LINEAR = "linear"
    #: not-a-knot cubic spline (:class:`scipy.interpolate.CubicSpline`): smaller error for
    #: band-limited vibration signals (Fyfe & Munck 1997)
    CUBIC = "cubic"


#: relative excess of the input density over the output's tolerated without filtering [-]
#: (an encoder with as many lines per revolution as output samples is not filtered)
_DENSITY_TOL = 1e-6
#: valid range of ``samples_per_rev`` [1/rev]
SAMPLES_PER_REV_RANGE = (8, 2**24)
#: default zero padding of :func:`order_spectrum` [-]
PAD_FACTOR = 16
#: bytes of one float64 [B]
_F8 = 8.0
#: memory per sample of the interpolation grid while resampling [B]: the grid, the index array
#: it is built from, the interpolated values and :func:`scipy.signal.resample_poly`'s padded copy
#: (measured with ``tracemalloc``: 17-32 B)
_BYTES_PER_GRID_SAMPLE = 4 * _F8
#: memory per line of the zero-padded FFT of :func:`order_spectrum` [B]: the padded input, the
#: complex half spectrum, its magnitude and the order axis (measured: 19-20 B)
_BYTES_PER_FFT_LINE = 3 * _F8


def _pow2_at_least(x: float) -> float:
    """The power of two at least ``x`` (> 0), as :func:`order_spectrum` sizes its FFT; ``inf``
    beyond ``2**1000``."""
    if not x < 2.0**1000:
        return math.inf
    return float(1 << math.ceil(math.log2(x))) if x > 1.0 else 1.0


@dataclass(frozen=True)
class AngleGrid:
    """The uniform angle grid :func:`resample_to_angle` builds for a signal, known before
    anything is allocated (:func:`angle_grid`).

    Attributes
    ----------
    samples_per_rev : int
        Samples per revolution of the output [1/rev].
    n_revs : float
        Angle spanned by the input [rev].
    n_samples : float
        Output samples ``floor(n_revs samples_per_rev) + 1`` [-] (a float: it may be far beyond
        anything that can be allocated).
    oversampling : int
        Factor ``L`` of the anti-aliasing interpolation grid (1 = plain interpolation) [-].
    """

    samples_per_rev: int
    n_revs: float
    n_samples: float
    oversampling: int

    @property
    def memory(self) -> float:
        """Largest memory the resampling and the order spectrum of its result hold [B]
        (:func:`analysis_memory`)."""
        return analysis_memory(self.n_samples, self.oversampling)


def analysis_memory(n_samples: float, oversampling: int = 1) -> float:
    """Largest memory [B] of resampling a signal to ``n_samples`` samples uniform in angle with
    an interpolation grid ``oversampling`` times finer, and of the order spectrum of the result
    (default zero padding, :data:`PAD_FACTOR`), an upper bound: the interpolation grid
    (``(n - 1) L + 1`` samples, 32 B each), the output (angles and values, 16 B a sample) and
    the FFT (``2^ceil(log2(16 n))`` lines, 24 B each).

    Parameters
    ----------
    n_samples : float
        Output samples [-] (a float: it may be beyond anything that can be allocated).
    oversampling : int
        Factor ``L`` of the interpolation grid [-].
    """
    n = float(n_samples)
    grid = (n - 1.0) * oversampling + 1.0
    return (
        _BYTES_PER_GRID_SAMPLE * grid
        + 2 * _F8 * n
        + _BYTES_PER_FFT_LINE * _pow2_at_least(PAD_FACTOR * n)
    )


def _checked_angle(angle: ArrayLike) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """The angles [rad] (finite, strictly increasing) and their steps [rad]."""
    th = _arr("angle_rad", angle)
    dth = np.diff(th)
    if np.any(dth <= 0):
        raise ConfigError(
            "angle_rad is not strictly increasing; the shaft must turn one way "
            "(drop the start-up or the stopped part)"
        )
    return th, dth


def _densest(dth: NDArray) -> float:
    """Densest input [samples/rev]: the 1st percentile of the angle steps (robust to jitter)."""
    return TWO_PI / float(np.quantile(dth, 0.01))


def _grid(th: NDArray, densest: float, samples_per_rev: int | None) -> AngleGrid:
    span = float(th[-1] - th[0])
    if samples_per_rev is None:
        dens = (th.size - 1) / (span / TWO_PI) * (1.0 - _DENSITY_TOL)  # mean steps per rev
        samples_per_rev = max(64, 2 ** math.ceil(math.log2(max(dens, 1.0))))
    spr = int(check_range("samples_per_rev", samples_per_rev, *SAMPLES_PER_REV_RANGE))
    x = span / (TWO_PI / spr)
    n = float(math.floor(x)) + 1.0 if math.isfinite(x) else math.inf
    # oversampling of the interpolation grid: at least the densest input [samples/rev], at most
    # 4 times the input's samples
    L = max(1, math.ceil(min(densest / spr * (1.0 - _DENSITY_TOL), 4 * th.size / n)))
    return AngleGrid(spr, span / TWO_PI, n, L)


def angle_grid(angle: ArrayLike, samples_per_rev: int | None = None) -> AngleGrid:
    """The grid :func:`resample_to_angle` would build for samples at ``angle``, and so its
    memory (:attr:`AngleGrid.memory`), without allocating it.

    Parameters
    ----------
    angle : array_like
        Shaft angle of each sample [rad], strictly increasing.
    samples_per_rev : int, optional
        Samples per revolution of the output [1/rev] (default as :func:`resample_to_angle`).
    """
    th, dth = _checked_angle(angle)
    return _grid(th, _densest(dth), samples_per_rev)


def _check_memory(grid: AngleGrid, th: NDArray, densest: float, max_memory: float) -> None:
    """Refuse, in one line, a grid whose memory exceeds ``max_memory`` [B], naming the largest
    ``samples_per_rev`` that fits."""
    if grid.memory <= max_memory:
        return
    lo, hi = SAMPLES_PER_REV_RANGE

    def gb(b: float) -> str:
        return f"an estimated {b / 1e9:.3g} GB" if b < 1e30 else "more memory than any machine"

    limit = f"the memory budget {max_memory / 1e9:.3g} GB (max_memory, --max-memory-gb)"
    least = _grid(th, densest, lo).memory
    if least > max_memory:
        raise ConfigError(
            f"the signal spans {grid.n_revs:.4g} shaft revolutions: even samples_per_rev = {lo} "
            f"needs {gb(least)} for the angular resampling and its order spectrum, above "
            f"{limit}; valid: a shorter record (check the units of the time [s] and of the speed "
            "or angle column)"
        )
    while hi - lo > 1:  # the memory grows with samples_per_rev: bisect for the largest that fits
        mid = (lo + hi) // 2
        lo, hi = (mid, hi) if _grid(th, densest, mid).memory <= max_memory else (lo, mid)
    raise ConfigError(
        f"samples_per_rev = {grid.samples_per_rev} over {grid.n_revs:.4g} shaft revolutions needs "
        f"{gb(grid.memory)} for the angular resampling and its order spectrum, above {limit}; "
        f"valid range [{SAMPLES_PER_REV_RANGE[0]}, {lo}] for this signal"
    )


def resample_to_angle(
    angle: ArrayLike,
    value: ArrayLike,
    samples_per_rev: int | None = None,
    *,
    interpolation: Interpolation | str = Interpolation.LINEAR,
    max_memory: float | None = None,
) -> AngleSignal:
    """Resample ``value`` given at strictly increasing shaft angles onto a uniform angle grid,
    anti-aliased (module docstring).

    Parameters
    ----------
    angle : array_like
        Shaft angle of each sample [rad]; must increase strictly (the shaft turns one way).
    value : array_like
        Signal at those samples (any unit, e.g. angular speed [rad/s] or acceleration
        [m/s^2]).
    samples_per_rev : int, optional
        Samples per revolution of the output [-]; default: the smallest power of two at least the
        input's mean density (at least 64) — nothing is filtered unless the shaft is slower than
        average by more than that power of two's margin.
    interpolation : Interpolation
        Between input samples: ``LINEAR`` (default) or ``CUBIC``.
    max_memory : float, optional
        Memory the resampling and the order spectrum of its result may take [B]
        (:attr:`AngleGrid.memory`); a grid above it is refused in one line before anything is
        allocated, naming the largest ``samples_per_rev`` that fits. Default: no limit.

    Returns
    -------
    AngleSignal
        Samples at ``angle[0] + k 2 pi / samples_per_rev`` up to ``angle[-1]``.
    """
    th, dth = _checked_angle(angle)
    v = _arr("value", value)
    interp = parse_enum(Interpolation, interpolation, "interpolation")
    if th.size != v.size:
        raise ConfigError(f"value has {v.size} samples but angle has {th.size}; they must match")
    densest = _densest(dth)
    g = _grid(th, densest, samples_per_rev)
    if max_memory is not None:
        _check_memory(g, th, densest, check_positive("max_memory_bytes", max_memory, "B"))
    spr, L = g.samples_per_rev, g.oversampling
    if not g.n_samples <= np.iinfo(np.intp).max // max(L, 1):  # no limit given: still indexable
        raise ConfigError(
            f"samples_per_rev = {spr} over {g.n_revs:.4g} shaft revolutions gives "
            f"{g.n_samples:.3g} samples, more than an array can hold; valid: a smaller "
            "samples_per_rev or a shorter record"
        )
    step = TWO_PI / spr
    n = int(g.n_samples)
    grid = th[0] + (step / L) * np.arange((n - 1) * L + 1) if L > 1 else th[0] + step * np.arange(n)
    if interp is Interpolation.LINEAR:
        y = np.interp(grid, th, v)
    else:
        from scipy.interpolate import CubicSpline

        y = CubicSpline(th, v)(grid)
    if L > 1:
        from scipy.signal import resample_poly

        y = resample_poly(y, 1, L, padtype="line")[:n]
        grid = th[0] + step * np.arange(n)
    return AngleSignal(grid, y, spr)


def order_spectrum(
    sig: AngleSignal, pad_factor: int | None = PAD_FACTOR, unit: str = ""
) -> Spectrum:
    """Order spectrum of an angle-domain signal (:func:`.amplitude_spectrum`: mean removed,
    symmetric Hann window, coherent-gain corrected), zero padded.

    Parameters
    ----------
    sig : AngleSignal
        Uniformly sampled in angle.
    pad_factor : int or None
        The FFT length is the power of two at least ``pad_factor`` times the signal [-] (the
        resolution stays ``1 / n_revs``); ``None``: no padding.
    unit : str
        Unit label of the signal.

    Returns
    -------
    Spectrum
        Over orders [-] (:attr:`Domain.ORDER`).
    """
    n = sig.value.size
    n_fft = None
    if pad_factor is not None:
        pad = int(check_range("pad_factor", pad_factor, 1, 1024))
        n_fft = 1 << int(math.ceil(math.log2(n * pad)))
    return amplitude_spectrum(sig.value, sig.samples_per_rev, unit, Domain.ORDER, n_fft=n_fft)


def synchronous_average(
    sig: AngleSignal, period: float, samples_per_period: int = 1024
) -> tuple[NDArray[np.float64], NDArray[np.float64], int]:
    """Average of the signal over consecutive angular periods (linear interpolation onto each
    period's grid).

    Parameters
    ----------
    sig : AngleSignal
        Uniform in shaft angle.
    period : float
        Angular period [rad] (e.g. ``2 pi / BPFO order``).
    samples_per_period : int
        Samples of the averaged period [-].

    Returns
    -------
    phase : ndarray
        Angle within the period [rad], from the first sample of ``sig``.
    mean : ndarray
        Averaged signal (unit of the signal).
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
    # in blocks of periods (a long record has millions of them: k x spp at once took tens of
    # GB); the rows are summed in order, each block onto the running sum, which is what
    # ``mean(axis=0)`` of the whole (k, spp) table does, to the bit
    per = max(1, _SYNC_BLOCK // spp)
    total = None
    for i in range(0, k, per):
        rows = np.arange(i, min(k, i + per))
        grid = sig.angle[0] + (rows[:, None] * period + phase[None, :])
        vals = np.interp(grid.ravel(), sig.angle, sig.value).reshape(rows.size, spp)
        total = vals.sum(axis=0) if total is None else np.vstack([total, vals]).sum(axis=0)
    return phase, total / k, k


#: samples interpolated at once by :func:`synchronous_average` [-] (8 MB per array)
_SYNC_BLOCK = 2**20


# --------------------------------------------------------------------------- shaft signal files


class ShaftSignalKind(enum.Enum):
    """What the value column of a shaft angle/speed file holds (its unit in the name)."""

    ANGLE_RAD = "angle_rad"
    ANGLE_DEG = "angle_deg"
    ANGLE_REV = "angle_rev"
    SPEED_RAD_S = "speed_rad_s"
    SPEED_RPM = "speed_rpm"

    @property
    def si_factor(self) -> float:
        """Factor to SI (rad or rad/s) [-]."""
        return _SHAFT_TO_SI[self.value]

    @property
    def is_angle(self) -> bool:
        """Whether the column is an angle (else a speed)."""
        return self.value.startswith("angle")


_SHAFT_TO_SI = {
    "angle_rad": 1.0,
    "angle_deg": math.pi / 180.0,
    "angle_rev": TWO_PI,
    "speed_rad_s": 1.0,
    "speed_rpm": TWO_PI / 60.0,
}


def read_shaft_signal(
    path: str | Path, kind: ShaftSignalKind | str | None = None
) -> tuple[NDArray[np.float64], NDArray[np.float64], ShaftSignalKind]:
    """Read a two-column text file ``time [s], value`` (encoder timestamps or an IAS record)
    through :func:`bearingsim.io.read_signal`.

    Columns are separated by commas, semicolons, tabs or blanks; an optional header line names
    them, e.g. ``time_s,angle_rad`` — the second name, when it is a :class:`ShaftSignalKind`
    value, gives the kind.

    Parameters
    ----------
    path : str or Path
        The file.
    kind : ShaftSignalKind, optional
        What the second column is (default: from the header; a kind that contradicts the
        header's is refused).

    Returns
    -------
    t : ndarray
        Sample times [s].
    value : ndarray
        Shaft angle [rad] or speed [rad/s] (SI).
    kind : ShaftSignalKind
        The kind read.
    """
    from ..io.signal import read_signal

    p = Path(path)
    rec = read_signal(p, time_column=0)
    if len(rec.columns) != 2:
        raise ConfigError(f"file = {str(p)!r} must have two numeric columns (time [s], value)")
    kinds = [k.value for k in ShaftSignalKind]
    named = rec.channel.lower() if rec.channel.lower() in kinds else None
    if kind is None:
        if named is None:
            raise ConfigError(
                f"file = {str(p)!r}: give --kind (one of {', '.join(kinds)}) or name "
                "the second column in a header line"
            )
        kind = named
    k = parse_enum(ShaftSignalKind, kind, "kind")
    if named is not None and k.value != named:
        raise ConfigError(
            f"kind = {k.value!r} contradicts the header of file = {str(p)!r}, which names the "
            f"second column {named!r}; valid: the header's kind, or no --kind"
        )
    return rec.time, rec.x * k.si_factor, k
