"""The signal-processing methods of the CWRU benchmark study (Smith & Randall 2015, "Rolling
element bearing diagnostics using the Case Western Reserve University data: A benchmark study",
MSSP 64–65, 100–131, §4), one function each, as building blocks of
:mod:`bearingsim.signal.diagnosis`.

1. **Envelope analysis of the raw signal**: the squared envelope spectrum (SES) of the whole
   band, :func:`squared_envelope_spectrum` with ``band=None``.
2. **Cepstral pre-whitening** (CPW; Sawalhi & Randall 2011, "Signal pre-whitening using cepstrum
   editing (liftering) to enhance fault detection in rolling element bearings", Proc. 24th
   COMADEM, 330–336; Borghesani, Pennacchi, Randall, Sawalhi & Ricci 2013, "Application of
   cepstrum pre-whitening for the diagnosis of bearing faults under variable speed conditions",
   MSSP 36, 370–384): :func:`cepstral_prewhitening`, then the whole-band SES.
3. **Discrete/random separation** (DRS; Antoni & Randall 2004, "Unsupervised noise cancellation
   for vibration signals: part II — a novel frequency-domain algorithm", MSSP 18, 103–117):
   :func:`discrete_random_separation`, then the band of largest spectral kurtosis
   (:func:`.kurtogram.band_maps`) and its SES — Smith & Randall's "benchmark method".

The fourth view, for records where impulsive noise fools the kurtogram, is the spectral infogram
(Antoni 2016; :func:`.kurtogram.band_maps`); the fifth, which chooses no band at all, the
enhanced envelope spectrum of the cyclic spectral coherence (Antoni, Xin & Hamzaoui 2017;
:mod:`.coherence`).

**Equations.**
SES (Randall & Antoni 2011, §3.2): ``SE(t) = |x_a(t)|^2`` with ``x_a`` the analytic signal of
the band, ``SES(alpha) = |DFT(SE)|`` in the amplitude convention of :func:`.amplitude_spectrum`.

CPW: the real cepstrum ``c = IFFT(ln|X|)`` set to zero except at zero quefrency; back in the
frequency domain this divides the spectrum by its magnitude, ``x_w = IFFT(X / |X|)``: every
discrete line and every resonance is flattened to unit magnitude and the phase kept, so a train
of impulses (phase-coherent over the band) stands out of the whitened signal.

DRS: the deterministic (discrete-frequency) part of ``x`` is what its own past predicts once the
past is older than the correlation length of the random part but not of the periodic one. The
Wiener filter from the past ``x_D`` to the present (Antoni & Randall 2004, eq. 5) is
``H(f) = S_{x_D x}(f) / S_{x_D x_D}(f)``, estimated by Welch averages of ``N``-point windowed
segments; its magnitude is near 1 at discrete frequencies and near 0 elsewhere. Here the filter
is applied in zero phase with the gain ``|H|^2 S_{x_D x_D} / S_{xx}`` (the coherence; see
:func:`discrete_random_separation`).
"""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike, NDArray

from ..errors import ConfigError, check_positive
from .envelope import BandEnvelopes
from .spectrum import Domain, Spectrum, as_signal

__all__ = [
    "DRS_DELAY",
    "DRS_WINDOW",
    "cepstral_prewhitening",
    "discrete_random_separation",
    "squared_envelope_spectrum",
]

#: DRS window length N [samples] and delay Delta [samples]: the values of the openConMo
#: implementation of Smith & Randall's benchmark method (``benchmark_method(N=16384,
#: Delta=500)``); at 12 kHz they are 1.37 s (0.73 Hz resolution, finer than the 0.4 Hz-wide
#: discrete lines are not needed) and 42 ms (ten times the 2–5 ms ring-down of the bearing
#: resonances)
DRS_WINDOW = 16384
DRS_DELAY = 500


def cepstral_prewhitening(x: ArrayLike) -> NDArray[np.float64]:
    """Cepstral pre-whitening (module docstring): ``IFFT(X / |X|)`` of the mean-removed signal.

    Parameters
    ----------
    x : array_like
        Signal (any unit), at least 16 finite samples.

    Returns
    -------
    ndarray
        Whitened signal, same length [-] (unit magnitude spectrum; no unit).
    """
    from scipy import fft as sfft

    a = as_signal(x)
    nf = sfft.next_fast_len(a.size, real=True)  # zero padded: a prime-length FFT is slow
    X = sfft.rfft(a - a.mean(), nf)
    mag = np.abs(X)
    floor = 1e-12 * float(mag.max()) if mag.size else 0.0
    if not floor > 0.0:
        raise ConfigError("signal is constant; valid: a signal with a non-zero AC part")
    W = X / np.maximum(mag, floor)
    W[0] = 0.0
    return sfft.irfft(W, nf)[: a.size]


def discrete_random_separation(
    x: ArrayLike, *, window: int = DRS_WINDOW, delay: int = DRS_DELAY
) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """Discrete/random separation (module docstring; Antoni & Randall 2004).

    Each ``window``-sample segment of the present is paired with the segment that ends
    ``delay`` samples before it starts (the two share no sample, so the random part of one does
    not predict the other; Antoni & Randall's "delay greater than the correlation length").
    The spectra are Welch averages over the segment pairs with Hann windows at 50 % overlap.
    The separation filter is applied in zero phase to the present signal: its gain is the
    magnitude-squared coherence of the signal with its past,
    ``G = |S_{x_D x}|^2 / (S_{x_D x_D} S_{xx})`` (``|H|^2`` normalised by the two
    auto-spectra), 1 at discrete frequencies and about ``1/K`` (K averages) for the random
    part, interpolated linearly to the record's FFT lines. The deterministic part is
    ``IFFT(G X)`` and the random part ``x - IFFT(G X)``.

    Parameters
    ----------
    x : array_like
        Signal (any unit); at least ``3 window + delay`` samples (two segment pairs).
    window : int
        Welch window N [samples], >= 64; halved (down to 256) until the record holds at least
        four segment pairs.
    delay : int
        Gap Delta between a segment and its past [samples], >= 1.

    Returns
    -------
    random, deterministic : ndarray
        The two parts (unit of ``x``); ``random + deterministic == x``.
    """
    from scipy import fft as sfft

    a = as_signal(x)
    if not isinstance(window, int | np.integer) or window < 64:
        raise ConfigError(f"window = {window!r} is invalid; valid range [64, inf) samples")
    if not isinstance(delay, int | np.integer) or delay < 1:
        raise ConfigError(f"delay = {delay!r} is invalid; valid range [1, inf) samples")
    n = a.size
    window, delay = int(window), int(delay)
    while window > 256 and 3 * window + delay + 2 * window > n:  # >= 4 pairs at 50 % overlap
        window //= 2
    lag = window + delay
    if lag + 2 * window > n:
        raise ConfigError(
            f"signal has {n} samples; valid range [{lag + 2 * window}, inf) samples for DRS "
            f"(window {window}, delay {delay})"
        )
    xm = a - a.mean()
    # Welch averages of the segment pairs (Hann, 50 % overlap) from one STFT of each series
    hop = window // 2
    starts = np.arange(0, n - lag - window + 1, hop)
    w = np.hanning(window + 1)[:window]  # periodic Hann
    idx = starts[:, None] + np.arange(window)[None, :]
    P = sfft.rfft(xm[idx] * w, axis=1)
    N = sfft.rfft(xm[idx + lag] * w, axis=1)
    s_dx = np.mean(np.conj(P) * N, axis=0)
    s_dd = np.mean(P.real**2 + P.imag**2, axis=0)
    s_nn = np.mean(N.real**2 + N.imag**2, axis=0)
    f = np.arange(s_dx.size) / window  # [cycles/sample]
    # a floor relative to the product it guards (it was relative to one spectrum: a signal at
    # 1e-44 then had its floor above every product, and the diagnosis depended on the unit)
    tiny = 1e-30 * float(s_dd.max()) * float(s_nn.max()) + 1e-300
    coh = np.clip(np.abs(s_dx) ** 2 / np.maximum(s_dd * s_nn, tiny), 0.0, 1.0)
    nf = sfft.next_fast_len(n, real=True)
    X = sfft.rfft(xm, nf)
    g = np.interp(np.arange(X.size) / nf, f, coh)
    det = sfft.irfft(g * X, nf)[:n]
    return a - det, det


def squared_envelope_spectrum(
    x: ArrayLike,
    fs: float,
    band: tuple[float, float] | None = None,
    *,
    domain: Domain | str = Domain.HZ,
) -> Spectrum:
    """Squared envelope spectrum of ``x`` in ``band`` (whole band ``(0, fs/2)`` when ``None``):
    :class:`.envelope.BandEnvelopes`, the same computation as the views of :mod:`.fused`.

    Parameters
    ----------
    x : array_like
        Signal (any unit).
    fs : float
        Sample rate [Hz] (samples per revolution in the order domain).
    band : (float, float), optional
        Band [Hz] (orders in the order domain).
    domain : Domain
        Abscissa of the result.

    Returns
    -------
    Spectrum
        Amplitude of the SES (unit of ``x`` squared).
    """
    fs = check_positive("fs_hz", fs, "Hz")
    return BandEnvelopes(x, fs, domain).squared_spectrum((0.0, 0.5 * fs) if band is None else band)
