"""Vibration signal processing for bearing diagnosis (SPEC §0.5).

* :func:`amplitude_spectrum` — single-sided amplitude spectrum (Hann window, coherent-gain
  corrected: a sinusoid of amplitude A reads A).
* :func:`envelope`, :func:`envelope_spectrum` — band-pass, Hilbert envelope, spectrum of the
  envelope (Randall & Antoni 2011, "Rolling element bearing diagnostics — a tutorial", MSSP 25).
  The band-pass is an ideal (brick-wall) FFT-domain filter that directly builds the analytic
  band signal, the same filter bank as the kurtogram below.
* :func:`fast_kurtogram` — spectral kurtosis on the 1/3-binary tree of bands of Antoni's fast
  kurtogram (Antoni 2007, "Fast computation of the kurtogram for the detection of transient
  faults", MSSP 21, 108–124): levels 0, 1, 1.6, 2, 2.6, ... with ``2^k`` bands of width
  ``fs/2^(k+1)`` at level k and ``3·2^(k-1)`` bands of width ``fs/(3·2^k)`` at level
  ``k + log2(3) - 1``. Each band's complex envelope is obtained exactly with FFT-domain filters
  (instead of Antoni's quasi-analytic FIR cascade) and its kurtosis is
  ``<|c|^4> / <|c|^2>^2 - 2`` (0 for Gaussian noise).
* :func:`angular_resample`, :func:`order_spectrum` — computed order tracking: resampling at
  uniform shaft-angle increments from a speed or angle signal (Fyfe & Munck 1997).
* :func:`match_peaks` — peak picking at target frequencies (harmonics, sidebands) within an
  explicit tolerance, with a local signal-to-noise ratio.
"""

from __future__ import annotations

import enum
import math
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike, NDArray

from ..errors import ConfigError, check_positive, check_range


def _signal(x: ArrayLike, name: str = "signal") -> NDArray[np.float64]:
    a = np.asarray(x, dtype=float)
    if a.ndim != 1:
        raise ConfigError(f"{name} must be one-dimensional; got shape {a.shape}")
    if a.size < 16:
        raise ConfigError(f"{name} has {a.size} samples; valid range [16, inf) samples")
    if not np.all(np.isfinite(a)):
        raise ConfigError(f"{name} contains non-finite values; valid: finite numbers")
    return a


def check_band(band: tuple[float, float], fs: float) -> tuple[float, float]:
    """Validate a frequency band ``(lo, hi)`` [Hz] against the Nyquist frequency ``fs/2``."""
    if len(band) != 2:
        raise ConfigError(f"band_hz = {band!r} is invalid; valid: two numbers LO HI")
    lo, hi = float(band[0]), float(band[1])
    nyq = 0.5 * fs
    check_range("band_hz low", lo, 0.0, unit="Hz")
    if hi > nyq:
        raise ConfigError(
            f"band_hz high = {hi:.6g} Hz is above the Nyquist frequency of fs_hz = {fs:.6g} Hz "
            f"(fs too low for the requested band); valid range ({lo:.6g}, {nyq:.6g}] Hz"
        )
    if not hi > lo:
        raise ConfigError(
            f"band_hz = [{lo:.6g}, {hi:.6g}] Hz is empty; valid: LO < HI <= {nyq:.6g} Hz"
        )
    return lo, hi


@dataclass(frozen=True)
class Spectrum:
    """Single-sided amplitude spectrum.

    Attributes
    ----------
    freq : ndarray
        Frequencies [Hz] (orders [-] for an order spectrum).
    amplitude : ndarray
        Amplitude (unit of the signal).
    unit : str
        Unit of the amplitude.
    domain : str
        ``"Hz"`` or ``"order"``.
    """

    freq: NDArray[np.float64]
    amplitude: NDArray[np.float64]
    unit: str = ""
    domain: str = "Hz"

    @property
    def resolution(self) -> float:
        """Bin spacing [Hz] or [-]."""
        return float(self.freq[1] - self.freq[0])

    def plot(self, f_max: float | None = None, title: str = "", ax=None, **kw):
        """Line plot up to ``f_max``; returns the Figure."""
        import matplotlib.pyplot as plt

        if ax is None:
            fig, ax = plt.subplots(figsize=(8, 3))
        else:
            fig = ax.figure
        sel = slice(None) if f_max is None else self.freq <= f_max
        ax.plot(self.freq[sel], self.amplitude[sel], lw=0.8, **kw)
        ax.set_xlabel("frequency [Hz]" if self.domain == "Hz" else "order [-]")
        ax.set_ylabel(f"amplitude [{self.unit}]" if self.unit else "amplitude")
        if title:
            ax.set_title(title)
        return fig


def amplitude_spectrum(x: ArrayLike, fs: float, unit: str = "", domain: str = "Hz") -> Spectrum:
    """Single-sided amplitude spectrum with a Hann window, corrected for its coherent gain.

    Parameters
    ----------
    x : array_like
        Signal (any unit); its mean is removed.
    fs : float
        Sample rate [Hz] (samples per revolution for an angle-domain signal).
    unit : str
        Unit label of ``x``.
    domain : str
        ``"Hz"`` or ``"order"`` (label only).
    """
    a = _signal(x)
    fs = check_positive("fs_hz", fs, "Hz")
    a = a - a.mean()
    w = np.hanning(a.size)
    X = np.fft.rfft(a * w)
    amp = 2.0 * np.abs(X) / w.sum()
    amp[0] *= 0.5
    return Spectrum(np.fft.rfftfreq(a.size, 1.0 / fs), amp, unit, domain)


#: fraction of the record tapered at each end before FFT-domain filtering (removes the
#: wrap-around discontinuity of the circular filter) [-]
EDGE_TAPER = 0.01


def _tapered(x: NDArray[np.float64]) -> NDArray[np.float64]:
    """Mean removed, Tukey taper over ``EDGE_TAPER`` of the record at each end."""
    from scipy.signal.windows import tukey

    return (x - x.mean()) * tukey(x.size, 2.0 * EDGE_TAPER)


def _analytic_band(x: NDArray[np.float64], fs: float, band: tuple[float, float]):
    """Analytic signal of ``x`` restricted to ``band`` (ideal FFT-domain filter)."""
    n = x.size
    X = np.fft.fft(_tapered(x))
    f = np.fft.fftfreq(n, 1.0 / fs)
    keep = (f >= band[0]) & (f < band[1]) & (f > 0)
    Z = np.zeros(n, dtype=complex)
    Z[keep] = 2.0 * X[keep]
    return np.fft.ifft(Z)


class EnvelopeKind(enum.Enum):
    """Envelope used for the envelope spectrum."""

    #: |analytic band signal| (unit of the signal)
    MAGNITUDE = "magnitude"
    #: |analytic band signal|^2 (Randall & Antoni 2011's squared envelope)
    SQUARED = "squared"


def envelope(
    x: ArrayLike, fs: float, band: tuple[float, float], kind: EnvelopeKind = EnvelopeKind.MAGNITUDE
) -> NDArray[np.float64]:
    """Envelope of ``x`` band-passed to ``band`` [Hz] (Hilbert transform; ideal FFT filter)."""
    a = _signal(x)
    fs = check_positive("fs_hz", fs, "Hz")
    band = check_band(band, fs)
    z = np.abs(_analytic_band(a, fs, band))
    return z * z if EnvelopeKind(kind) is EnvelopeKind.SQUARED else z


def envelope_spectrum(
    x: ArrayLike,
    fs: float,
    band: tuple[float, float],
    kind: EnvelopeKind = EnvelopeKind.MAGNITUDE,
    unit: str = "",
    domain: str = "Hz",
) -> Spectrum:
    """Amplitude spectrum of the envelope of ``x`` in ``band`` [Hz] (mean removed)."""
    e = envelope(x, fs, band, kind)
    return amplitude_spectrum(e, fs, unit=unit, domain=domain)


# --------------------------------------------------------------------------- fast kurtogram


@dataclass(frozen=True)
class Kurtogram:
    """Spectral kurtosis over Antoni's 1/3-binary tree of bands.

    Attributes
    ----------
    levels : ndarray (L,)
        Level values 0, 1, 1.585, 2, ... [-].
    kurtosis : ndarray (L, B)
        Kurtosis of each band's complex envelope [-]; NaN where the level has fewer bands or
        the band was excluded.
    n_bands : ndarray (L,)
        Bands per level.
    fs : float
        Sample rate [Hz].
    band : tuple[float, float]
        The selected (maximum-kurtosis) band [Hz].
    level : float
        Its level [-].
    max_kurtosis : float
        Its kurtosis [-].
    """

    levels: NDArray[np.float64]
    kurtosis: NDArray[np.float64]
    n_bands: NDArray[np.int64]
    fs: float
    band: tuple[float, float]
    level: float
    max_kurtosis: float

    def plot(self, title: str = ""):
        """Kurtogram image (frequency vs level); returns the Figure."""
        import matplotlib.pyplot as plt

        fig, ax = plt.subplots(figsize=(7, 4))
        nyq = 0.5 * self.fs
        fine = int(np.lcm.reduce(self.n_bands))
        img = np.full((self.levels.size, fine), np.nan)
        for i, nb in enumerate(self.n_bands):
            img[i] = np.repeat(self.kurtosis[i, :nb], fine // nb)
        ax.imshow(
            img,
            aspect="auto",
            origin="upper",
            extent=(0, nyq, self.levels.size - 0.5, -0.5),
            cmap="viridis",
        )
        ax.set_yticks(range(self.levels.size), [f"{v:.1f}" for v in self.levels])
        ax.set_xlabel("frequency [Hz]")
        ax.set_ylabel("level")
        ax.set_title(
            title
            or f"kurtogram: max {self.max_kurtosis:.2f} at level {self.level:.1f}, "
            f"band {self.band[0]:.0f}-{self.band[1]:.0f} Hz"
        )
        return fig


def kurtogram_levels(max_level: int) -> list[tuple[float, int]]:
    """``(level, number of bands)`` of the 1/3-binary tree up to integer level ``max_level``."""
    out = [(0.0, 1)]
    for k in range(1, max_level + 1):
        out.append((float(k), 2**k))
    for k in range(max_level - 1):
        out.append((k + math.log2(3.0), 3 * 2**k))  # levels 1.585, 2.585, ... < max_level
    return sorted(out)


def fast_kurtogram(
    x: ArrayLike,
    fs: float,
    *,
    max_level: int | None = None,
    min_bandwidth_hz: float = 0.0,
    min_bins: int = 64,
) -> Kurtogram:
    """Fast kurtogram (Antoni 2007) with exact FFT-domain band filters.

    Parameters
    ----------
    x : array_like
        Signal.
    fs : float
        Sample rate [Hz].
    max_level : int, optional
        Deepest integer level; default the deepest whose bands are at least
        ``min_bandwidth_hz`` wide and hold at least ``min_bins`` FFT bins.
    min_bandwidth_hz : float
        Bands narrower than this are not considered [Hz] (an envelope of a band of width B only
        contains modulation frequencies below B).
    min_bins : int
        Fewest spectral lines (= complex-envelope samples) per band [-] for a usable kurtosis
        estimate.
    """
    a = _signal(x)
    fs = check_positive("fs_hz", fs, "Hz")
    n = a.size
    nyq = 0.5 * fs
    df = fs / n
    if max_level is None:
        max_level = 0
        while True:
            bw = nyq / 2 ** (max_level + 1)
            if bw < max(min_bandwidth_hz, 0.0) or bw / df < min_bins or max_level >= 12:
                break
            max_level += 1
    if max_level < 0:
        raise ConfigError(f"max_level = {max_level} is invalid; valid range [0, 12]")
    X = np.fft.fft(_tapered(a))
    npos = n // 2 + 1
    Xp = 2.0 * X[:npos]
    fpos = np.arange(npos) * df
    levs = kurtogram_levels(max_level)
    nbmax = max(nb for _, nb in levs)
    kur = np.full((len(levs), nbmax), np.nan)
    best = (-np.inf, 0.0, (0.0, nyq))
    for i, (lev, nb) in enumerate(levs):
        bw = nyq / nb
        edges = np.searchsorted(fpos, np.arange(nb + 1) * bw)
        for b in range(nb):
            i0, i1 = edges[b], edges[b + 1] if b < nb - 1 else npos
            if i0 == 0:
                i0 = 1  # drop DC
            m = i1 - i0
            if m < min_bins or bw < min_bandwidth_hz:
                continue
            c = np.fft.ifft(Xp[i0:i1])
            cut = int(math.ceil(EDGE_TAPER * m))  # skip the tapered ends
            p2 = np.abs(c[cut : m - cut]) ** 2
            mu = p2.mean()
            if mu <= 0.0:
                continue
            k = float(np.mean(p2 * p2) / (mu * mu) - 2.0)
            kur[i, b] = k
            if k > best[0]:
                best = (k, lev, (b * bw, (b + 1) * bw))
    if not np.isfinite(best[0]):
        raise ConfigError(
            f"kurtogram: no band of width >= {min_bandwidth_hz:.6g} Hz with >= {min_bins} lines "
            f"fits below fs_hz/2 = {nyq:.6g} Hz (signal too short or fs too low for the band); "
            "valid: a longer signal or a higher sample rate"
        )
    return Kurtogram(
        np.array([v for v, _ in levs]),
        kur,
        np.array([nb for _, nb in levs]),
        fs,
        best[2],
        float(best[1]),
        float(best[0]),
    )


# --------------------------------------------------------------------------- order tracking


def angular_resample(
    x: ArrayLike,
    fs: float,
    *,
    speed_hz: ArrayLike | None = None,
    angle_rev: ArrayLike | None = None,
    samples_per_rev: int = 256,
) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """Computed order tracking: resample ``x`` at uniform shaft-angle increments.

    The shaft angle comes from ``angle_rev`` (revolutions, one per sample) or is the running
    integral (trapezoidal) of ``speed_hz`` (rev/s, one per sample). ``x`` is low-pass filtered
    below the angular Nyquist rate at the lowest speed (anti-aliasing, ideal FFT filter), then
    interpolated with a cubic spline (Fyfe & Munck 1997, MSSP 11(2) 187–205).

    Parameters
    ----------
    x : array_like
        Signal sampled at ``fs`` [Hz].
    fs : float
        Sample rate [Hz].
    speed_hz : array_like, optional
        Shaft speed per sample [Hz] (> 0).
    angle_rev : array_like, optional
        Shaft angle per sample [rev] (increasing).
    samples_per_rev : int
        Output samples per revolution [-].

    Returns
    -------
    theta : ndarray
        Uniform shaft angles [rev].
    x_theta : ndarray
        Resampled signal.
    """
    from scipy.interpolate import CubicSpline

    a = _signal(x)
    fs = check_positive("fs_hz", fs, "Hz")
    if (speed_hz is None) == (angle_rev is None):
        raise ConfigError("order tracking: give exactly one of speed_hz or angle_rev")
    if speed_hz is not None:
        sp = np.asarray(speed_hz, dtype=float)
        if sp.shape != a.shape or not np.all(np.isfinite(sp)) or np.any(sp <= 0):
            raise ConfigError(
                "speed_hz must be finite, > 0 and as long as the signal; valid range (0, inf) Hz"
            )
        ang = np.concatenate([[0.0], np.cumsum(0.5 * (sp[1:] + sp[:-1]) / fs)])
    else:
        ang = np.asarray(angle_rev, dtype=float)
        if ang.shape != a.shape or not np.all(np.diff(ang) > 0):
            raise ConfigError("angle_rev must increase strictly and be as long as the signal")
        sp = np.gradient(ang) * fs
    if not (isinstance(samples_per_rev, int) and samples_per_rev >= 8):
        raise ConfigError(
            f"samples_per_rev = {samples_per_rev!r} is invalid; valid range [8, inf) integer"
        )
    # anti-aliasing: keep frequencies below the angular Nyquist rate at the slowest speed
    f_cut = 0.5 * samples_per_rev * float(sp.min())
    if f_cut < 0.5 * fs:
        X = np.fft.rfft(a)
        X[np.fft.rfftfreq(a.size, 1.0 / fs) > f_cut] = 0.0
        a = np.fft.irfft(X, a.size)
    theta = np.arange(ang[0], ang[-1], 1.0 / samples_per_rev)
    return theta, CubicSpline(ang, a)(theta)


def order_spectrum(x_theta: ArrayLike, samples_per_rev: int, unit: str = "") -> Spectrum:
    """Amplitude spectrum of an angle-domain signal: abscissa in orders [-]."""
    return amplitude_spectrum(x_theta, float(samples_per_rev), unit=unit, domain="order")


# --------------------------------------------------------------------------- peak matching


@dataclass(frozen=True)
class Peak:
    """A spectral line found near a target.

    Attributes
    ----------
    label : str
        Target name (e.g. ``"2xBPFO"``, ``"BPFI-fs"``).
    target_hz : float
        Expected frequency [Hz].
    freq_hz : float
        Frequency of the largest line within the tolerance [Hz].
    amplitude : float
        Its amplitude (unit of the spectrum).
    snr_db : float
        ``20 log10(amplitude / noise floor)``, the floor being the median amplitude in the
        surrounding window without the tolerance band [dB].
    order : float
        ``freq_hz / shaft_hz`` [-].
    detected : bool
        ``snr_db >= threshold``.
    """

    label: str
    target_hz: float
    freq_hz: float
    amplitude: float
    snr_db: float
    order: float
    detected: bool

    def as_dict(self) -> dict[str, float | str | bool]:
        """JSON-ready dict."""
        return {
            "label": self.label,
            "order": self.order,
            "freq_hz": self.freq_hz,
            "amplitude": self.amplitude,
            "snr_db": self.snr_db,
            "target_hz": self.target_hz,
            "detected": self.detected,
        }


def match_peaks(
    spectrum: Spectrum,
    targets: list[tuple[str, float]],
    shaft_hz: float,
    *,
    tol_rel: float = 0.01,
    tol_min_bins: float = 2.0,
    noise_rel: float = 0.1,
    threshold_db: float = 12.0,
) -> list[Peak]:
    """Find the largest line within ``max(tol_rel f, tol_min_bins df)`` of every target.

    Parameters
    ----------
    spectrum : Spectrum
        Usually an envelope spectrum.
    targets : list of (label, frequency [Hz])
        What to look for.
    shaft_hz : float
        Shaft frequency for the ``order`` column [Hz].
    tol_rel : float
        Relative frequency tolerance [-] (speed uncertainty and ball slip).
    tol_min_bins : float
        Smallest tolerance in frequency bins [-].
    noise_rel : float
        Half-width of the noise-floor window relative to the target frequency, at least five
        tolerances [-]; the floor is the median amplitude there without the tolerance band.
    threshold_db : float
        SNR above which a line counts as detected [dB].
    """
    f = spectrum.freq
    A = spectrum.amplitude
    df = spectrum.resolution
    out = []
    for label, ft in targets:
        tol = max(tol_rel * ft, tol_min_bins * df)
        win = (f >= ft - tol) & (f <= ft + tol)
        if ft + tol >= f[-1] or not np.any(win):
            continue
        idx = np.flatnonzero(win)
        k = idx[np.argmax(A[idx])]
        hw = max(noise_rel * ft, 5.0 * tol)
        nw = (f >= ft - hw) & (f <= ft + hw) & ~win & (f > 0)
        floor = float(np.median(A[nw])) if np.any(nw) else float("nan")
        snr = 20.0 * math.log10(A[k] / floor) if floor > 0 and A[k] > 0 else float("nan")
        out.append(
            Peak(
                label,
                float(ft),
                float(f[k]),
                float(A[k]),
                snr,
                float(f[k] / shaft_hz),
                bool(np.isfinite(snr) and snr >= threshold_db),
            )
        )
    return out
