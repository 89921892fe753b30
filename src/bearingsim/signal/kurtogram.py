"""Fast kurtogram: spectral kurtosis on the 1/3-binary tree of bands of Antoni's fast kurtogram
(Antoni 2007, "Fast computation of the kurtogram for the detection of transient faults", MSSP
21, 108–124).

Levels 0, 1, 1.6, 2, 2.6, ... with ``2^k`` bands of width ``fs/2^(k+1)`` at level k and
``3·2^(k-1)`` bands of width ``fs/(3·2^k)`` at level ``k + log2(3) - 1``. Each band's complex
envelope is obtained exactly with FFT-domain filters (instead of Antoni's quasi-analytic FIR
cascade; the same filters as :mod:`.envelope`) and its kurtosis is ``<|c|^4> / <|c|^2>^2 - 2``
(0 for Gaussian noise).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike, NDArray

from ..errors import ConfigError, check_positive
from .envelope import EDGE_TAPER, BandEnvelopes
from .spectrum import as_signal

__all__ = [
    "EULER_GAMMA",
    "Infogram",
    "Kurtogram",
    "band_maps",
    "fast_kurtogram",
    "kurtogram_levels",
]


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
        from ..plotting import FULL_WIDTH, new_figure

        fig, ax = new_figure(width=FULL_WIDTH, height=3.8)
        nyq = 0.5 * self.fs
        fine = int(np.lcm.reduce(self.n_bands))
        img = np.full((self.levels.size, fine), np.nan)
        for i, nb in enumerate(self.n_bands):
            img[i] = np.repeat(self.kurtosis[i, :nb], fine // nb)
        im = ax.imshow(
            img,
            aspect="auto",
            origin="upper",
            extent=(0, nyq / 1e3, self.levels.size - 0.5, -0.5),
            cmap="viridis",
        )
        ax.set_yticks(range(self.levels.size), [f"{v:.1f}" for v in self.levels])
        ax.set_xlabel("frequency [kHz]")
        ax.set_ylabel("level [-]")
        fig.colorbar(im, ax=ax, label="spectral kurtosis [-]")
        ax.set_title(
            title
            or f"kurtogram: max {self.max_kurtosis:.2f} at level {self.level:.1f}, "
            f"band {self.band[0]:.0f}-{self.band[1]:.0f} Hz"
        )
        return fig


#: finest level of the kurtogram: 2^13 bands, far finer than a bearing's resonance [-]
MAX_LEVEL = 12


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
        Signal (any unit), at least 16 samples.
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
    return band_maps(
        x, fs, max_level=max_level, min_bandwidth_hz=min_bandwidth_hz, min_bins=min_bins,
        infogram=False,
    )[0]  # fmt: skip


#: Euler–Mascheroni constant: ``1 - EULER_GAMMA`` is the negentropy of the squared envelope of
#: stationary Gaussian noise (exponentially distributed) [-]
EULER_GAMMA = 0.5772156649015329


@dataclass(frozen=True)
class Infogram:
    """Spectral negentropy over the same 1/3-binary tree of bands (Antoni 2016, "The infogram:
    Entropic evidence of the signature of repetitive transients", MSSP 74, 73–94).

    For a band's squared envelope ``SE`` the negentropy is
    ``Delta I = < (SE/<SE>) ln(SE/<SE>) >`` (eq. 9 there); computed on ``SE`` in time it
    measures impulsiveness (:attr:`time`), computed on ``|DFT(SE)|^2`` over the non-zero cyclic
    frequencies it measures cyclostationarity, i.e. *repetitive* transients (:attr:`spectral`,
    which an isolated impulse does not raise). Stationary Gaussian noise gives
    ``1 - EULER_GAMMA`` = 0.42 in time and about the same in frequency; a constant envelope 0.

    Attributes
    ----------
    levels : ndarray (L,)
        Level values [-].
    time, spectral : ndarray (L, B)
        Negentropy of the squared envelope and of its spectrum [-]; NaN where excluded.
    n_bands : ndarray (L,)
        Bands per level.
    fs : float
        Sample rate [Hz].
    band : tuple[float, float]
        The band of largest spectral negentropy [Hz].
    level : float
        Its level [-].
    max_spectral : float
        Its spectral negentropy [-].
    """

    levels: NDArray[np.float64]
    time: NDArray[np.float64]
    spectral: NDArray[np.float64]
    n_bands: NDArray[np.int64]
    fs: float
    band: tuple[float, float]
    level: float
    max_spectral: float


def _negentropy(e: NDArray[np.float64]) -> float:
    """``< (e/<e>) ln(e/<e>) >`` of a non-negative series ``e`` [-]."""
    mu = e.mean()
    if not mu > 0.0:
        return float("nan")
    r = e / mu
    with np.errstate(divide="ignore", invalid="ignore"):
        v = np.where(r > 0.0, r * np.log(r), 0.0)
    return float(v.mean())


def band_maps(
    x: ArrayLike,
    fs: float,
    *,
    max_level: int | None = None,
    min_bandwidth_hz: float = 0.0,
    min_bins: int = 64,
    infogram: bool = True,
    alpha_max_hz: float | None = None,
    spectrum: BandEnvelopes | None = None,
) -> tuple[Kurtogram, Infogram | None]:
    """The fast kurtogram (:func:`fast_kurtogram`) and, with ``infogram=True``, the infogram
    (:class:`Infogram`) from one pass over the band filters.

    Parameters
    ----------
    x : array_like
        Signal (any unit), at least 16 samples.
    fs : float
        Sample rate [Hz].
    max_level : int, optional
        Deepest integer level (see :func:`fast_kurtogram`).
    min_bandwidth_hz : float
        Narrowest band considered [Hz].
    min_bins : int
        Fewest spectral lines per band [-].
    infogram : bool
        Also compute the time and spectral negentropies.
    alpha_max_hz : float, optional
        Highest cyclic frequency of the spectral negentropy [Hz] (default
        ``min_bandwidth_hz``, or each band's width when that is 0). The same range in every
        band keeps the bands comparable: over more cyclic-frequency lines the negentropy of a
        spectrum with the same few lines is larger (about ``ln(lines / peaks)``).
    spectrum : BandEnvelopes, optional
        ``BandEnvelopes(x, fs)`` when the caller has it already: its FFT is the one read here
        (computed here otherwise).
    """
    from scipy import fft as sfft

    a = as_signal(x)
    fs = check_positive("fs_hz", fs, "Hz")
    if a.size and np.all(a == a[0]):  # no band has a kurtosis
        raise ConfigError(f"x: all {a.size} samples equal {a[0]:.6g}; valid: a varying signal")
    n = a.size
    nyq = 0.5 * fs
    df = fs / n
    if isinstance(min_bins, bool) or not isinstance(min_bins, int | np.integer) or min_bins < 1:
        raise ConfigError(f"min_bins = {min_bins!r} is invalid; valid range [1, inf) integer")
    if max_level is None:
        max_level = 0
        while True:
            bw = nyq / 2 ** (max_level + 1)
            if bw < max(min_bandwidth_hz, 0.0) or bw / df < min_bins or max_level >= MAX_LEVEL:
                break
            max_level += 1
    if isinstance(max_level, bool) or not isinstance(max_level, int | np.integer):
        raise ConfigError(f"max_level = {max_level!r} is invalid; valid range [0, 12] integer")
    # the finest level's bands must each hold a bin: nyq / 2^(level+1) >= df
    top = min(MAX_LEVEL, max(int(math.floor(math.log2(nyq / df))) - 1, 0))
    if not 0 <= max_level <= top:
        raise ConfigError(
            f"max_level = {max_level} is out of range; valid range [0, {top}] (bands of at "
            f"least one bin of {df:.3g} Hz, at most level {MAX_LEVEL})"
        )
    if spectrum is None:
        spectrum = BandEnvelopes(a, fs)
    elif spectrum.n != n or spectrum.fs != fs:
        raise ConfigError(
            f"spectrum is of {spectrum.n} samples at {spectrum.fs:.6g} Hz; valid: the FFT of "
            f"this signal ({n} samples at {fs:.6g} Hz)"
        )
    nf, X = spectrum.nf, spectrum.X  # the tapered record, zero padded to a fast FFT length
    npos = nf // 2 + 1
    Xp = 2.0 * X[:npos]
    fpos = np.arange(npos) * (fs / nf)
    levs = kurtogram_levels(max_level)
    nbmax = max(nb for _, nb in levs)
    kur = np.full((len(levs), nbmax), np.nan)
    neg_t = np.full((len(levs), nbmax), np.nan)
    neg_f = np.full((len(levs), nbmax), np.nan)
    best = (-np.inf, 0.0, (0.0, nyq))
    best_i = (-np.inf, 0.0, (0.0, nyq))
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
            c = sfft.ifft(Xp[i0:i1])
            cut = int(math.ceil(EDGE_TAPER * m))  # skip the tapered ends
            p2 = c.real[cut : m - cut] ** 2 + c.imag[cut : m - cut] ** 2
            mu = p2.mean()
            if mu <= 0.0:
                continue
            k = float(np.mean(p2 * p2) / (mu * mu) - 2.0)
            kur[i, b] = k
            if k > best[0]:
                best = (k, lev, (b * bw, (b + 1) * bw))
            if infogram:
                neg_t[i, b] = _negentropy(p2)
                amax = alpha_max_hz or min_bandwidth_hz or bw
                n_alpha = max(int(amax * p2.size * nf / (m * fs)), 8)
                ses = np.abs(sfft.rfft(p2 - mu)[1 : n_alpha + 1]) ** 2
                v = _negentropy(ses)
                neg_f[i, b] = v
                if v > best_i[0]:
                    best_i = (v, lev, (b * bw, (b + 1) * bw))
    if not np.isfinite(best[0]):
        raise ConfigError(
            f"kurtogram: no band of width >= {min_bandwidth_hz:.6g} Hz with >= {min_bins} lines "
            f"fits below fs_hz/2 = {nyq:.6g} Hz (signal too short or fs too low for the band); "
            "valid: a longer signal or a higher sample rate"
        )
    levels = np.array([v for v, _ in levs])
    n_bands = np.array([nb for _, nb in levs])
    kg = Kurtogram(levels, kur, n_bands, fs, best[2], float(best[1]), float(best[0]))
    ig = None
    if infogram:
        ig = Infogram(
            levels, neg_t, neg_f, n_bands, fs, best_i[2], float(best_i[1]), float(best_i[0])
        )
    return kg, ig
