"""The amplitude spectrum: one window and scaling convention for every spectrum of the package
(Hz spectra, envelope spectra, order spectra of IAS and of stiffness series).

The convention (:func:`amplitude_spectrum`)
    1. the mean of the record is removed;
    2. the record is multiplied by a Hann window ``w`` — by default the symmetric one
       (``numpy.hanning``), ``sym=False`` gives the periodic (DFT-even) one
       (``scipy.signal.windows.hann(n, sym=False)``; Harris 1978, "On the use of windows for
       harmonic analysis with the discrete Fourier transform", Proc. IEEE 66, 51–83);
    3. optional zero padding to ``n_fft >= n`` samples (interpolates the spectrum; the resolution
       stays ``fs / n``);
    4. single-sided amplitude ``A_k = 2 |X_k| / sum(w)`` for ``k >= 1`` and ``A_0 = |X_0| /
       sum(w)``: the division by the window's sum corrects its coherent gain, so a sinusoid of
       amplitude ``a`` centred on a line reads ``a`` (between lines the Hann scalloping loss is at
       most 1.42 dB).

The abscissa is a frequency [Hz] (:attr:`Domain.HZ`) or an order [-] (:attr:`Domain.ORDER`, cycles
per shaft revolution; ``fs`` is then the number of samples per revolution).
"""

from __future__ import annotations

import enum
import functools
import math
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike, NDArray

from ..errors import ConfigError, check_positive
from ..geometry import parse_enum

__all__ = ["MIN_SAMPLES", "Domain", "Spectrum", "amplitude_spectrum", "as_signal"]

#: fewest samples a signal must have to be analysed [-]
MIN_SAMPLES = 16


class Domain(enum.Enum):
    """Abscissa of a spectrum."""

    #: frequency [Hz] (time-domain signal sampled at ``fs`` [Hz])
    HZ = "Hz"
    #: order [-] = cycles per shaft revolution (angle-domain signal, ``fs`` samples per revolution)
    ORDER = "order"


#: the range of a signal's peak magnitude the signal functions take, in any unit [-]: far
#: inside the floating-point range, so that powers and sums over a record stay finite and
#: normal (a peak of 1e200 overflowed in DRS and came out NaN; 1e-320 read as "constant")
PEAK_RANGE = (1e-100, 1e100)


def as_signal(
    x: ArrayLike,
    name: str = "signal",
    min_samples: int = MIN_SAMPLES,
    peak_range: tuple[float, float] = PEAK_RANGE,
) -> NDArray[np.float64]:
    """``x`` as a finite one-dimensional float array (a column or row vector is flattened) of at
    least ``min_samples`` samples whose peak magnitude, unless 0, lies in ``peak_range``
    (default :data:`PEAK_RANGE`; a caller that squares the signal asks for a narrower one);
    anything else (complex, text, dates, masked samples) raises a one-line
    :class:`ConfigError` naming ``name``."""
    if np.ma.isMaskedArray(x) and np.ma.getmaskarray(x).any():
        raise ConfigError(
            f"{name} has {int(np.ma.getmaskarray(x).sum())} masked samples; valid: no masked "
            "samples (fill or cut them first)"
        )
    raw = np.asarray(x)
    if np.iscomplexobj(raw):  # NumPy would drop the imaginary part with a warning
        raise ConfigError(
            f"{name} is complex; valid: a real signal (pass its real part or magnitude)"
        )
    if raw.dtype.kind in "USMmV":  # text, bytes, dates, durations: never samples
        raise ConfigError(f"{name} is not numeric (dtype {raw.dtype}); valid: real numbers")
    try:
        a = np.asarray(raw, dtype=float)
    except (TypeError, ValueError):
        raise ConfigError(
            f"{name} is not numeric (dtype {raw.dtype}); valid: real numbers"
        ) from None
    if a.ndim != 1:
        a = np.squeeze(a)
        if a.ndim != 1:
            raise ConfigError(f"{name} must be one-dimensional; got shape {np.shape(x)}")
    if a.size < min_samples:
        raise ConfigError(f"{name} has {a.size} samples; valid range [{min_samples}, inf) samples")
    if not np.all(np.isfinite(a)):
        raise ConfigError(f"{name} contains non-finite values; valid: finite numbers")
    peak = float(np.max(np.abs(a)))
    lo, hi = peak_range
    if peak != 0.0 and not lo <= peak <= hi:
        raise ConfigError(
            f"{name} has a peak magnitude of {peak:.3g}; valid range [{lo:g}, {hi:g}] in any "
            "unit (rescale the signal)"
        )
    return a


@dataclass(frozen=True)
class Spectrum:
    """Single-sided amplitude spectrum (the convention of :func:`amplitude_spectrum`).

    Attributes
    ----------
    freq : ndarray
        Frequencies [Hz], or orders [-] when ``domain`` is :attr:`Domain.ORDER`.
    amplitude : ndarray
        Amplitude (unit of the signal).
    unit : str
        Unit of the amplitude.
    domain : Domain
        Abscissa: :attr:`Domain.HZ` or :attr:`Domain.ORDER` (strings ``"Hz"``, ``"order"``
        accepted).
    resolution : float
        Frequency resolution ``fs / n`` of the record [Hz or -]: the line spacing without zero
        padding (default), coarser than :attr:`bin_width` with it.
    """

    freq: NDArray[np.float64]
    amplitude: NDArray[np.float64]
    unit: str = ""
    domain: Domain = Domain.HZ
    resolution: float = math.nan

    def __post_init__(self) -> None:
        object.__setattr__(self, "domain", parse_enum(Domain, self.domain, "domain"))
        if math.isnan(self.resolution):
            object.__setattr__(self, "resolution", self.bin_width)

    @property
    def bin_width(self) -> float:
        """Spacing of the spectral lines [Hz or -]."""
        return float(self.freq[1] - self.freq[0])

    def plot(
        self,
        f_max: float | None = None,
        title: str = "",
        ax=None,
        *,
        scale: float = 1.0,
        unit: str | None = None,
        marks: ArrayLike | None = None,
        marks_label: str | None = None,
        quantity: str = "amplitude",
        **kw,
    ):
        """Line plot up to ``f_max`` [Hz or -]; returns the Figure (of :mod:`bearingsim.plotting`'s
        standard when it makes one).

        Parameters
        ----------
        f_max : float, optional
            Largest frequency [Hz] or order [-] shown (default: all).
        title : str
            Axes title.
        ax : matplotlib Axes, optional
            Axes to draw in (default: a new figure).
        scale : float
            Factor applied to the amplitude (e.g. ``60 / (2 pi)`` for rad/s -> r/min) [-].
        unit : str, optional
            Unit label of the scaled amplitude (default :attr:`unit`; ``"signal unit"`` when
            neither is known).
        marks : array_like, optional
            Abscissae marked with dashed vertical lines [Hz or -].
        marks_label : str, optional
            Legend entry of the marks.
        quantity : str
            Quantity of the amplitude axis (``"envelope amplitude"``...).
        """
        from ..plotting import legend_outside, mark_lines, new_figure, unit_text

        if ax is None:
            fig, ax = new_figure(height=3.2)
        else:
            fig = ax.figure
        sel = slice(None) if f_max is None else self.freq <= f_max
        ax.plot(self.freq[sel], self.amplitude[sel] * scale, lw=0.8, **kw)
        m = np.atleast_1d(marks if marks is not None else [])
        if m.size:
            mark_lines(ax, m, marks_label, ls="--", lw=0.7)
            if marks_label:
                legend_outside(ax)
        ax.set_xlabel("frequency [Hz]" if self.domain is Domain.HZ else "order [-]")
        u = self.unit if unit is None else unit
        ax.set_ylabel(f"{quantity} [{unit_text(u) or 'signal unit'}]")
        if title:
            ax.set_title(title)
        return fig


@functools.lru_cache(maxsize=8)
def _hann(n: int, sym: bool) -> NDArray[np.float64]:
    """Hann window of ``n`` samples: symmetric (``numpy.hanning``) or periodic
    (``scipy.signal.windows.hann(n, sym=False)``); the two libraries' symmetric windows differ in
    the last bit, NumPy's is the one the published comparisons were made with. Cached (a batch
    computes the same window for every spectrum of a record); read-only."""
    if sym:
        w = np.hanning(n)
    else:
        from scipy.signal.windows import hann

        w = hann(n, sym=False)
    w.flags.writeable = False
    return w


def amplitude_spectrum(
    x: ArrayLike,
    fs: float,
    unit: str = "",
    domain: Domain | str = Domain.HZ,
    *,
    n_fft: int | None = None,
    sym: bool = True,
) -> Spectrum:
    """Single-sided amplitude spectrum, Hann window corrected for its coherent gain (the
    convention of the module docstring: a sinusoid of amplitude ``a`` reads ``a``).

    Parameters
    ----------
    x : array_like
        Signal (any unit), at least 16 samples; its mean is removed.
    fs : float
        Sample rate [Hz] (samples per revolution [1/rev] for an angle-domain signal).
    unit : str
        Unit label of ``x``.
    domain : Domain
        :attr:`Domain.HZ` (default) or :attr:`Domain.ORDER`; sets the abscissa's meaning.
    n_fft : int, optional
        FFT length [-], ``>= len(x)``: zero padding interpolates the spectrum (default: none).
    sym : bool
        Symmetric Hann window (default) or periodic (``False``).

    Returns
    -------
    Spectrum
        Lines at ``k fs / n_fft`` [Hz or -], resolution ``fs / len(x)``.
    """
    a = as_signal(x)
    fs = check_positive("fs_hz", fs, "Hz")
    n = a.size
    nf = n if n_fft is None else int(n_fft)
    if nf < n:
        raise ConfigError(f"n_fft = {n_fft!r} is invalid; valid range [{n}, inf) (the signal)")
    a = a - a.mean()
    w = _hann(n, sym)
    amp = 2.0 * np.abs(np.fft.rfft(a * w, nf)) / w.sum()
    amp[0] *= 0.5  # the DC line has no negative-frequency twin
    return Spectrum(np.fft.rfftfreq(nf, 1.0 / fs), amp, unit, domain, fs / n)
