"""Envelope analysis: band-pass, Hilbert envelope, spectrum of the envelope (Randall & Antoni
2011, "Rolling element bearing diagnostics — a tutorial", MSSP 25, 485–520, §3.2).

The band-pass is an ideal (brick-wall) FFT-domain filter that directly builds the analytic band
signal — the same filter bank as the fast kurtogram (:mod:`.kurtogram`). The record is first
tapered over :data:`EDGE_TAPER` of its length at each end (removes the wrap-around discontinuity
of the circular filter).
"""

from __future__ import annotations

import enum
import math

import numpy as np
from numpy.typing import ArrayLike, NDArray

from ..errors import ConfigError, check_positive, check_range
from .spectrum import Domain, Spectrum, amplitude_spectrum, as_signal

__all__ = [
    "BandEnvelopes",
    "EDGE_TAPER",
    "EnvelopeKind",
    "check_band",
    "envelope",
    "envelope_spectrum",
]

#: fraction of the record tapered at each end before FFT-domain filtering [-]
EDGE_TAPER = 0.01


def check_band(
    band: tuple[float, float], fs: float, name: str = "band_hz", *, orders: bool = False
) -> tuple[float, float]:
    """Validate a frequency band ``(lo, hi)`` [Hz] against the Nyquist frequency ``fs/2`` [Hz];
    ``name`` is the field the one-line errors name. ``orders``: an order-tracked signal, the
    band in orders and ``fs`` in samples per revolution (the messages say so)."""
    u, rate = ("orders", "samples_per_rev") if orders else ("Hz", "fs_hz")
    ru, what = ("per rev", "order") if orders else ("Hz", "frequency")
    try:
        ok = len(band) == 2
    except TypeError:  # a scalar, None
        ok = False
    if not ok:
        raise ConfigError(f"{name} = {band!r} is invalid; valid: two numbers LO HI")
    nyq = 0.5 * fs
    lo = check_range(f"{name} low", band[0], 0.0, unit=u)
    hi = band[1]
    if isinstance(hi, float | int) and not isinstance(hi, bool) and not math.isfinite(hi):
        # "high = inf is not finite", with the range a high edge can have
        check_range(f"{name} high", hi, lo, nyq, lo_open=True, unit=u)
    hi = check_range(f"{name} high", hi, unit=u)
    if lo >= nyq:
        raise ConfigError(
            f"{name} low = {lo:.6g} {u} is not below the Nyquist {what} "
            f"{nyq:.6g} {u} of {rate} = {fs:.6g} {ru} (fs too low for the requested band); valid "
            f"range [0, {nyq:.6g}) {u}"
        )
    if hi > nyq:
        raise ConfigError(
            f"{name} high = {hi:.6g} {u} is above the Nyquist {what} "
            f"of {rate} = {fs:.6g} {ru} (fs too low for the requested band); valid range "
            f"({lo:.6g}, {nyq:.6g}] {u}"
        )
    if not hi > lo:
        raise ConfigError(
            f"{name} = [{lo:.6g}, {hi:.6g}] {u} is empty; valid: LO < HI <= {nyq:.6g} {u}"
        )
    return lo, hi


def tukey_window(n: int, alpha: float) -> NDArray[np.float64]:
    """Tukey (tapered cosine) window of ``n`` samples [-]: flat, with cosine tapers over the
    fraction ``alpha/2`` of the window at each end; the definition of
    ``scipy.signal.windows.tukey(n, alpha)`` (Harris 1978, eq. (38)), equal to it bit for bit
    (``tests/test_envelope.py``).

    Written out here because importing :mod:`scipy.signal` (SciPy >= 1.15 builds its array-API
    wrappers and imports :mod:`scipy.stats` on import) takes 0.8-1.4 s, five to ten times a
    whole ``bearingsim analyze`` of a 10 s record, and this window is all the analysis needs
    from it (issue 17: the start-up of one call).
    """
    if n < 2 or alpha <= 0.0:
        return np.ones(max(int(n), 0))
    if alpha >= 1.0:  # the Hann window, as SciPy's general cosine window computes it
        fac = np.linspace(-np.pi, np.pi, n)
        return np.zeros(n) + 0.5 + 0.5 * np.cos(fac)
    k = np.arange(n)
    width = int(np.floor(alpha * (n - 1) / 2.0))
    k1 = k[: width + 1]
    k3 = k[n - width - 1 :]
    w1 = 0.5 * (1 + np.cos(np.pi * (-1 + 2.0 * k1 / alpha / (n - 1))))
    w3 = 0.5 * (1 + np.cos(np.pi * (-2.0 / alpha + 1 + 2.0 * k3 / alpha / (n - 1))))
    return np.concatenate((w1, np.ones(n - w1.size - w3.size), w3))


def _tapered(x: NDArray[np.float64]) -> NDArray[np.float64]:
    """Mean removed, Tukey taper over :data:`EDGE_TAPER` of the record at each end."""
    return (x - x.mean()) * tukey_window(x.size, 2.0 * EDGE_TAPER)


def _analytic_band(x: NDArray[np.float64], fs: float, band: tuple[float, float]):
    """Analytic signal of ``x`` restricted to ``band`` [Hz] (ideal FFT-domain filter)."""
    n = x.size
    X = np.fft.fft(_tapered(x))
    f = np.fft.fftfreq(n, 1.0 / fs)
    keep = (f >= band[0]) & (f < band[1]) & (f > 0)
    Z = np.zeros(n, dtype=complex)
    Z[keep] = 2.0 * X[keep]
    return np.fft.ifft(Z)


class BandEnvelopes:
    """Squared envelope spectra of one signal in several bands from one FFT: the record is
    tapered (:data:`EDGE_TAPER`) and zero padded to a fast FFT length once (a CWRU record's
    length has a large prime factor: the plain FFT is several times slower), then each band is
    the ideal filter of :func:`envelope` and the amplitude spectrum of ``|analytic|^2``
    (:func:`.amplitude_spectrum`, zero padded to the same length: lines a hair closer than
    ``fs/n``, the same resolution). The kurtogram's band tree reads the same FFT
    (:func:`.kurtogram.band_maps`).

    Parameters
    ----------
    x : array_like
        Signal (any unit), at least 16 finite samples.
    fs : float
        Sample rate [Hz] (samples per revolution in the order domain).
    domain : Domain
        Abscissa of the spectra.
    """

    def __init__(self, x: ArrayLike, fs: float, domain: Domain | str = Domain.HZ) -> None:
        from scipy import fft as sfft

        from ..geometry import parse_enum

        a = as_signal(x)
        self.fs = check_positive("fs_hz", fs, "Hz")
        self.domain = parse_enum(Domain, domain, "domain")
        self.n = a.size
        #: the fast FFT length [-]
        self.nf = sfft.next_fast_len(self.n)
        #: FFT of the tapered, zero-padded record (``nf`` lines)
        self.X = sfft.fft(_tapered(a), self.nf)
        self._f = np.arange(self.nf // 2 + 1) * (self.fs / self.nf)

    def squared_spectrum(self, band: tuple[float, float]) -> Spectrum:
        """Amplitude spectrum of the squared envelope in ``band`` [Hz or orders] (unit of ``x``
        squared)."""
        from scipy import fft as sfft

        band = check_band(band, self.fs)
        lo, hi = np.searchsorted(self._f, band)  # lines with lo <= f < hi, as envelope()
        lo = max(int(lo), 1)
        Z = np.zeros(self.nf, dtype=complex)
        Z[lo:hi] = 2.0 * self.X[lo:hi]
        z = sfft.ifft(Z)[: self.n]
        return amplitude_spectrum(z.real**2 + z.imag**2, self.fs, domain=self.domain, n_fft=self.nf)


class EnvelopeKind(enum.Enum):
    """Envelope used for the envelope spectrum."""

    #: |analytic band signal| (unit of the signal)
    MAGNITUDE = "magnitude"
    #: |analytic band signal|^2 (Randall & Antoni 2011's squared envelope)
    SQUARED = "squared"


def envelope(
    x: ArrayLike, fs: float, band: tuple[float, float], kind: EnvelopeKind = EnvelopeKind.MAGNITUDE
) -> NDArray[np.float64]:
    """Envelope of ``x`` band-passed to ``band`` (Hilbert transform; ideal FFT filter).

    Parameters
    ----------
    x : array_like
        Signal (any unit), at least 16 samples.
    fs : float
        Sample rate [Hz].
    band : (float, float)
        Pass band ``(lo, hi)`` [Hz], ``0 <= lo < hi <= fs/2``.
    kind : EnvelopeKind
        Magnitude (unit of ``x``) or squared magnitude (unit of ``x`` squared).
    """
    a = as_signal(x)
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
    domain: Domain | str = Domain.HZ,
) -> Spectrum:
    """Amplitude spectrum (:func:`.amplitude_spectrum`) of the envelope of ``x`` in ``band``.

    Parameters
    ----------
    x : array_like
        Signal (any unit).
    fs : float
        Sample rate [Hz] (samples per revolution in the order domain).
    band : (float, float)
        Envelope band [Hz] (orders in the order domain).
    kind : EnvelopeKind
        Envelope kind.
    unit : str
        Unit label of the envelope.
    domain : Domain
        Abscissa of the result.
    """
    e = envelope(x, fs, band, kind)
    return amplitude_spectrum(e, fs, unit=unit, domain=domain)
