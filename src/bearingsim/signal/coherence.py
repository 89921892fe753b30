"""Cyclic spectral coherence and the enhanced envelope spectrum (issue 17, item 1: the view "where
impulsive noise fools the kurtogram").

**Source.** Antoni, Xin & Hamzaoui 2017, "Fast computation of the spectral correlation", MSSP 92,
248–277 (the fast spectral correlation, §3–4), and Antoni 2007, "Cyclic spectral analysis of
rolling-element bearing signals: facts and fictions", JSV 304, 497–529 (the integrated coherence as
a band-free envelope spectrum).

**Equations.** With ``X(f_k, n)`` the short-time Fourier transform of ``x`` (window ``w`` of
``N_w`` samples, hop ``R``), the *cyclic modulation spectrum* of carrier ``f_k`` is the Fourier
transform over the frames of the squared magnitude (Antoni et al. 2017, §3: the fast spectral
correlation's term without frequency shift)::

    S(alpha, f_k) = (1 / N_T) | sum_n |X(f_k, n)|^2 exp(-2 pi j alpha n R / fs) |

It is the spectral correlation ``S_x(alpha, f_k)`` seen through the window's cyclic response
``W(alpha) = | sum_m w(m)^2 exp(-2 pi j alpha m / fs) |`` (ibid.; the fast algorithm adds
frequency-shifted products to extend it beyond the window's bandwidth, which is not needed here:
the window is chosen short enough to pass every cyclic frequency read). Dividing by the carrier's
mean power (whitening) and by ``W(alpha) / W(0)`` gives the magnitude of the cyclic spectral
coherence ``|gamma(alpha, f_k)|``, between 0 and about 1 for ``alpha > 0``: the depth at which
carrier ``f_k`` is modulated at ``alpha``, whatever its power. (At ``alpha = 0`` it is 1 by
definition; the results give 0 there, the mean removed as in the other views' spectra.)

The **enhanced envelope spectrum** (EES) is its mean over the carriers::

    EES(alpha) = mean_k |gamma(alpha, f_k)|,  f_k in [f_lo, f_hi]

It is an envelope spectrum in which every frequency band counts by its modulation depth, not its
energy: a fault that modulates weak high-frequency bands shows although the strongest band
(picked by a kurtogram, or dominating the raw envelope) carries something else.

**Choices** (none fitted to data):

* ``N_w``: the longest power of two (at least 8 samples) whose window still passes the highest
  cyclic frequency read, ``alpha_max``, at half its response or more
  (``W(alpha_max) >= W(0) / 2``): ``fs / N_w >= 0.77 alpha_max`` for the Hann window. The
  carrier resolution is then set by the lines read, not by the sample rate: 750 Hz for the
  6205 at 1797 r/min (``alpha_max`` = 516 Hz) at 12 and at 48 kHz;
* ``R``: the largest hop up to ``N_w / 4`` with a frame rate of at least ``2 alpha_max``
  (the rule of Antoni's reference implementation of the fast spectral correlation);
* carriers from ``alpha_max`` (a band below its own modulation frequency cannot carry it) up to
  one resolution below ``fs / 2``.

**Limits.** A discrete tone within the window's bandwidth of DC or of Nyquist beats with its
mirror image in the carriers there: a pure 30 Hz tone gives a coherence line at 60 Hz (0.5 for
a tone alone, 0.08 with noise of a tenth of its amplitude). The fused diagnosis reads the DRS
random part, from which discrete tones are removed. The Fourier transform over the frames is
zero padded twice (``PAD``): a line between two cyclic bins loses at most 10 %.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike, NDArray

from ..errors import ConfigError, check_positive, check_range
from .envelope import check_band
from .spectrum import Domain, Spectrum, as_signal

__all__ = [
    "CyclicCoherence",
    "coherence_window",
    "cyclic_modulation_coherence",
    "enhanced_envelope_spectrum",
]

#: shortest STFT window [samples]
MIN_WINDOW = 8
#: zero padding of the Fourier transform over the frames [-]
PAD = 2
#: longest STFT window [samples] (2^24: a cyclic resolution 2e6 times finer than fs)
MAX_WINDOW = 2**24
#: a Hann window of N_w samples passes a cyclic frequency at half its response up to
#: HALF_RESPONSE fs / N_w (computed by :func:`_cyclic_response`) [-]
HALF_RESPONSE = 1.294
#: the window must pass the highest cyclic frequency at this share of its zero-frequency
#: response or more [-]
MIN_CYCLIC_RESPONSE = 0.5


def _too_short(n: int, nw: int, alpha_max: float, fs: float) -> None:
    """The one-line refusal of a signal shorter than 8 windows of ``nw`` samples."""
    raise ConfigError(
        f"signal has {n} samples: valid range >= {8 * nw} (8 windows of {nw}) for a cyclic "
        f"coherence up to {alpha_max:.6g} Hz at {fs:.6g} Hz"
    )


def _hann(n: int) -> NDArray[np.float64]:
    """Periodic Hann window of ``n`` samples (NumPy only: ``analyze`` does not import
    ``scipy.signal``, whose import costs more than the analysis)."""
    return 0.5 - 0.5 * np.cos(2.0 * np.pi * np.arange(n) / n)


def _cyclic_response(w2: NDArray[np.float64], alpha: NDArray[np.float64], fs: float):
    """``W(alpha) / W(0)`` of a squared window ``w2`` [-] (module docstring)."""
    m = np.arange(w2.size) - 0.5 * (w2.size - 1)  # centred: a real response for a symmetric w
    return np.abs(np.cos(2.0 * np.pi * np.outer(alpha, m) / fs) @ w2) / w2.sum()


def coherence_window(fs: float, alpha_max: float, n_samples: int | None = None) -> tuple[int, int]:
    """``(N_w, R)`` for :func:`cyclic_modulation_coherence` (module docstring) [samples].

    Parameters
    ----------
    fs : float
        Sample rate [Hz] (samples per revolution in the order domain).
    alpha_max : float
        Highest cyclic frequency to read [Hz] (orders), below ``fs / 8``.
    n_samples : int, optional
        Length of the signal: refused in one line, before any window is built, when it holds
        fewer than 8 windows.
    """
    fs = check_positive("fs_hz", fs, "Hz")
    alpha_max = check_positive("alpha_max_hz", alpha_max, "Hz")
    if alpha_max > fs / MIN_WINDOW:
        raise ConfigError(
            f"alpha_max_hz = {alpha_max:.6g} Hz is too high for fs_hz = {fs:.6g} Hz: valid "
            f"range (0, {fs / MIN_WINDOW:.6g}] Hz (the shortest window, {MIN_WINDOW} samples, "
            "must still pass it)"
        )
    ratio = fs / alpha_max
    if ratio > MAX_WINDOW:  # checked before any window is built
        raise ConfigError(
            f"alpha_max_hz = {alpha_max:.6g} Hz is too low for fs_hz = {fs:.6g} Hz: valid "
            f"range [{fs / MAX_WINDOW:.6g}, {fs / MIN_WINDOW:.6g}] Hz (windows of "
            f"{MIN_WINDOW}-{MAX_WINDOW} samples)"
        )
    nw = max(MIN_WINDOW, 2 ** int(math.floor(math.log2(HALF_RESPONSE * ratio))))
    if n_samples is not None and n_samples < 8 * max(MIN_WINDOW, nw // 2):
        _too_short(n_samples, nw, alpha_max, fs)  # before windows this long are built

    def passes(n: int) -> bool:
        w2 = _hann(n) ** 2
        return _cyclic_response(w2, np.array([alpha_max]), fs)[0] >= MIN_CYCLIC_RESPONSE

    while nw > MIN_WINDOW and not passes(nw):  # the estimate is exact to round-off; make sure
        nw //= 2
    while 2 * nw <= MAX_WINDOW and passes(2 * nw):
        nw *= 2
    if n_samples is not None and n_samples < 8 * nw:
        _too_short(n_samples, nw, alpha_max, fs)
    hop = max(1, min(nw // 4, int(math.floor(fs / (2.0 * alpha_max)))))
    return nw, hop


@dataclass(frozen=True)
class CyclicCoherence:
    """Magnitude of the cyclic spectral coherence on a carrier × cyclic-frequency grid.

    Attributes
    ----------
    carrier : ndarray
        Carrier frequencies f_k [Hz] (orders), shape ``(K,)``.
    alpha : ndarray
        Cyclic frequencies [Hz] (orders), shape ``(A,)``, from 0 to ``alpha_max``.
    gamma : ndarray
        ``|gamma(alpha, f_k)|`` [-], shape ``(K, A)`` (0 at ``alpha = 0``: module docstring).
    window : int
        STFT window ``N_w`` [samples].
    hop : int
        STFT hop ``R`` [samples].
    resolution : float
        Cyclic resolution ``fs / n`` of the record [Hz] (orders).
    spacing : float
        Carrier spacing ``fs / N_w`` [Hz] (orders).
    """

    carrier: NDArray[np.float64]
    alpha: NDArray[np.float64]
    gamma: NDArray[np.float64]
    window: int
    hop: int
    resolution: float
    spacing: float

    @property
    def band(self) -> tuple[float, float]:
        """Frequency band the carriers cover, half a spacing beyond the outer ones [Hz]."""
        half = 0.5 * self.spacing
        return float(max(self.carrier[0] - half, 0.0)), float(self.carrier[-1] + half)

    def enhanced_envelope_spectrum(self, domain: Domain | str = Domain.HZ) -> Spectrum:
        """The mean of ``gamma`` over the carriers (module docstring) [-]."""
        return Spectrum(self.alpha, self.gamma.mean(axis=0), "-", domain, self.resolution)

    def plot(
        self,
        title: str = "",
        lines: dict[str, float] | None = None,
        domain: Domain | str = Domain.HZ,
    ):
        """The coherence map (cyclic frequency × carrier, ``|gamma|`` in colour) above the
        enhanced envelope spectrum, on one cyclic-frequency axis; returns the Figure. Which
        carrier bands hold a cyclic line shows on the map (a kurtogram shows one band, the
        enhanced spectrum none).

        Parameters
        ----------
        title : str
            Figure title.
        lines : dict, optional
            Cyclic frequencies to mark, by label [Hz] (orders), e.g. ``{"BPFO": 107.4}``.
        domain : Domain
            Abscissa: Hz (carriers in kHz) or orders (carriers in orders).
        """
        from ..geometry import parse_enum
        from ..plotting import FULL_WIDTH, legend_outside, mark_lines, new_figure

        domain = parse_enum(Domain, domain, "domain")
        marks = sorted(
            ((str(k), check_range(f"lines[{k!r}]", v, 0.0, unit="Hz")) for k, v in
             (lines or {}).items()),
            key=lambda kv: kv[1],
        )  # fmt: skip
        hz = domain is Domain.HZ
        fig, (a1, a2) = new_figure(2, 1, width=FULL_WIDTH, row_height=2.6, sharex=True)
        scale, cu = (1e-3, "kHz") if hz else (1.0, "orders")
        au = "Hz" if hz else "orders"
        a = self.alpha[1:]  # alpha = 0 is 0 by construction (module docstring)
        g = self.gamma[:, 1:]
        top = float(np.quantile(g, 0.999)) if g.size else 1.0
        mesh = a1.pcolormesh(
            a, self.carrier * scale, g, shading="nearest", cmap="viridis", vmin=0.0,
            vmax=top if top > 0.0 else None, rasterized=True,
        )  # fmt: skip
        fig.colorbar(mesh, ax=a1, label="|coherence| [-]")
        a1.set_ylabel(f"carrier [{cu}]")
        a1.set_title(
            title
            or f"cyclic spectral coherence: window {self.window} samples, "
            f"{self.carrier.size} carriers of {self.spacing:.4g} {au}"
        )
        a2.plot(a, g.mean(axis=0), lw=0.7, color="C0")
        a2.set_xlabel(f"cyclic frequency [{au}]")
        a2.set_ylabel("mean coherence [-]")
        a2.set_xlim(0.0, float(self.alpha[-1]))
        a2.set_ylim(bottom=0.0)
        for i, (k, v) in enumerate(marks):  # one colour and legend entry each
            mark_lines(a2, [v], k, color=f"C{(i + 1) % 10}", ls="--")
        if marks:
            legend_outside(a2)
        return fig


def cyclic_modulation_coherence(
    x: ArrayLike,
    fs: float,
    alpha_max: float,
    *,
    carrier_band: tuple[float, float] | None = None,
) -> CyclicCoherence:
    """``|gamma(alpha, f)|`` of ``x`` for ``0 <= alpha <= alpha_max`` (module docstring).

    Parameters
    ----------
    x : array_like
        Signal (any unit), at least 8 windows long.
    fs : float
        Sample rate [Hz] (samples per revolution in the order domain).
    alpha_max : float
        Highest cyclic frequency [Hz] (orders).
    carrier_band : (lo, hi), optional
        Band whose carriers are kept [Hz] (orders): the STFT bins within half a bin spacing of
        it, DC and Nyquist left out; default ``[alpha_max, fs/2 - fs/N_w]``.
    """
    a = as_signal(x)
    nw, hop = coherence_window(fs, alpha_max, a.size)
    if carrier_band is not None:
        carrier_band = check_band(carrier_band, fs, "carrier_band")
    w = _hann(nw)
    frames = np.lib.stride_tricks.sliding_window_view(a - a.mean(), nw)[::hop]
    X = np.fft.rfft(frames * w, axis=1).T  # carriers x frames
    f = np.fft.rfftfreq(nw, 1.0 / fs)
    df = fs / nw
    if carrier_band is None:
        keep = (f >= alpha_max) & (f <= fs / 2 - df)
    else:
        lo, hi = carrier_band
        keep = (f >= lo - df / 2) & (f <= hi + df / 2) & (f > 0.0) & (f < fs / 2)
        if not keep.any():
            raise ConfigError(
                f"carrier_band = ({lo:.6g}, {hi:.6g}) Hz holds no STFT bin (spacing "
                f"{df:.6g} Hz) other than DC and Nyquist; valid: a band reaching within half a "
                "spacing of one"
            )
    power = np.abs(X[keep]) ** 2
    mean = power.mean(axis=1, keepdims=True)
    silent = mean[:, 0] <= 0.0
    mean[silent] = 1.0
    # the mean removed, as in the other views' spectra: gamma(0) = 1 by definition carries
    # nothing and would dwarf every line in a plot; a silent carrier has zero coherence
    mod = power / mean - 1.0
    mod[silent] = 0.0
    n_t = power.shape[1]
    # zero padded to twice the frames: a line between two bins loses at most 10 % (the
    # rectangular window's scalloping at a quarter bin), not 36 % (at half a bin)
    gamma = np.abs(np.fft.rfft(mod, n=PAD * n_t, axis=1)) / n_t
    alpha = np.fft.rfftfreq(PAD * n_t, hop / fs)
    m = alpha <= alpha_max
    w2 = w**2
    gamma = gamma[:, m] / _cyclic_response(w2, alpha[m], fs)[None, :]
    return CyclicCoherence(f[keep], alpha[m], gamma, nw, hop, fs / a.size, df)


def enhanced_envelope_spectrum(
    x: ArrayLike,
    fs: float,
    alpha_max: float,
    *,
    carrier_band: tuple[float, float] | None = None,
    domain: Domain | str = Domain.HZ,
) -> Spectrum:
    """EES: the cyclic coherence averaged over the carriers (module docstring), as a
    :class:`.Spectrum` of cyclic frequency [Hz] (orders) with a coherence amplitude [-].

    Parameters
    ----------
    x, fs, alpha_max, carrier_band
        As :func:`cyclic_modulation_coherence`.
    domain : Domain
        Abscissa of the result.
    """
    c = cyclic_modulation_coherence(x, fs, alpha_max, carrier_band=carrier_band)
    return c.enhanced_envelope_spectrum(domain)
