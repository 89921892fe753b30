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
from .envelope import EDGE_TAPER, _tapered
from .spectrum import as_signal

__all__ = ["Kurtogram", "fast_kurtogram", "kurtogram_levels"]


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
    a = as_signal(x)
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
