"""Identify a measurement chain ("rig") from measured records of one machine (issue 16, item 4).

Output-only identification: the records are what the sensor gave; the bearing's own vibration is
not known. What can be identified from them, and how:

1. **Resonances of the path** -- a bearing fault excites the structure with short impacts, so
   the path's modes are where the signal is impulsive. The spectral kurtosis
   ``SK(f) = <|X(t, f)|^4> / <|X(t, f)|^2>^2 - 2`` of a short-time Fourier transform (Antoni
   2006, MSSP 20) marks those frequencies; the impulsive part of the power spectrum is taken as
   ``E(f) = max(SK(f), 0) PSD(f)``, averaged over the records (each normalised to its total).
   The largest peaks of the smoothed ``E`` are the modes (``max_modes``, at least a factor
   ``min_separation`` apart in frequency), each refined to a peak of the PSD
   (:func:`_psd_peak`).
2. **Damping** -- from the decay of the ringing after each impact: the signal is band-passed
   around the mode (zero-phase Butterworth, the band at least 5 half-power bandwidths wide so
   the filter's own ringing is short), its envelope (Hilbert) is cut after each impact (the
   envelope maxima above ``median + 0.4 (P99.5 - median)``, 2 ms apart at least), the
   median envelope is fitted by ``exp(-sigma t)`` from the peak down to 20 % of it, and
   ``zeta = sigma / (2 pi f_n)`` (a lightly damped mode rings at ``f_n`` and decays at
   ``zeta w_n``).
3. **Gain** -- output-only, a gain is a ratio of levels in the measured spectrum: near a mode
   the bearing's excitation is broadband and smooth, so the measured PSD at ``f_n`` over the
   PSD of its shoulders (log-log trend of the background one octave around it, the mode
   excluded) is ``|1 + g|^2`` for a path of direct gain 1: ``g = sqrt(peak/shoulder) - 1``.
   What the bearing model itself gives is not an input of the identification; how a model plus
   this rig compares with a record is the side-by-side test (issue 16, item 5).
4. **Background** -- the machine's own vibration, the non-impulsive part of the records: each
   record's Welch PSD (about 4 Hz resolution) times the non-impulsive share of its band,
   ``min(1, median_t P(t, f) / (ln 2 mean_t P(t, f)))`` of the short-time power ``P`` in the
   spectral kurtosis's 2.5 ms segments. A segment that short falls between two impacts of a
   fault line (an inner-race fault at 162 Hz strikes every 6.2 ms), so the median over time
   ignores the impacts; for stationary Gaussian noise the share is 1 (a periodogram's median
   is ln 2 times its mean), for a steady tone it is capped at 1. The median over the records,
   smoothed over 1/6 octave and tabulated at log-spaced frequencies.
   **Growth with speed** (twenty-fourth session): when the records' shaft speeds span at
   least :data:`MIN_SPEED_SPAN` (highest over lowest, at least :data:`MIN_SPEED_RECORDS`
   records with a speed), each record's background level ``ln b`` (the median over frequency
   of its log amplitude relative to the others', :func:`_background_levels`) is fitted by
   least squares as a line in the log of its speed, ``ln b = a + n ln(N / N_ref)`` with
   ``N_ref`` the speeds' geometric mean; the slope ``n`` is kept when its
   standard error is at most :data:`MAX_SPEED_EXPONENT_SE` (and within the rig's
   ``MAX_SPEED_EXPONENT``). Each record's PSD is then referred to ``N_ref`` (times
   ``(N_ref / N)^(2 n)``) before the median, and the table is the background at ``N_ref``
   (``speed_exponent``, ``rpm_ref`` of :class:`~bearingsim.rig.Background`). Otherwise the
   background is the same at every speed, and why is said in its provenance (the CWRU
   records span 1723-1797 r/min, 4 %: too narrow). (Until the seventeenth
   session the background was the median-averaged Welch PSD itself, over 0.25 s segments: each
   held tens of impacts, so the median kept them, and its ln 2 correction inflated tonal
   content by 1.44: its power exceeded the records' own, 41 against 31 (m/s^2)^2 on record
   132, 0.68 against 0.51 on the healthy record 97.)
5. **Tones** -- the lines at 1, 2 and 3 times the shaft speed of each record (its own rpm),
   kept where the Hann line stands over the background at a false-alarm probability of
   :data:`TONE_FALSE_ALARM` (6 dB over it until the twenty-eighth session, which noise
   crossed on 44.5 % of the records); the amplitude is the least-squares sinusoid's at the
   line's refined frequency (the Hann peak until then, up to 1.4 dB low between bins); the
   median amplitude over the records. A kept tone is taken out of each record before its background
   (step 4) is estimated (:func:`_without_tones`: its frequency read within 1 % of the order,
   refined, and the least-squares sinusoid subtracted); until the twenty-fourth session it
   stayed in the background as well and a run through the rig carried it twice.

A record too short (under 1 s), one whose channel does not exist, and a set of records without
impulsive content (``SK`` nowhere above ``min_kurtosis``) are refused with one line.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from pathlib import Path

import numpy as np
from numpy.typing import NDArray

from .errors import ConfigError
from .rig import Background, Mode, Rig, Tone

__all__ = [
    "PATH_FIT_OBJECTIVES",
    "IdentifiedRig",
    "PathFit",
    "SpeedLaw",
    "fit_path_gains",
    "identify_rig",
    "speed_law",
]

#: shortest record [s]
MIN_DURATION_S = 1.0
#: fewest samples in the spectral-kurtosis segment (2.5 ms, shorter than a ring-down): with
#: fewer the STFT has too few frequency bins to place a mode [-]; at 2.5 ms this asks for
#: fs >= 2**3.5 / 0.0025 = 4525 Hz (the segment is the nearest power of 2)
MIN_SEGMENT = 16
#: smallest mode gain kept [-]: a PSD peak 1.21 x its shoulders (0.8 dB) is within the scatter
MIN_GAIN = 0.1
#: the background table's points above its log-spaced ones [fraction of fs], up to the Nyquist
#: frequency: where a recorder's anti-aliasing filter rolls the records off (CWRU: 3-5
#: decades between 0.45 and 0.5 fs), each the mean over +/- ROLL_OFF_HALF_BAND fs (a sixth of
#: an octave would blur the roll-off). Without them the table ended at 0.45 fs and a signal at
#: the rig's own rate was the model's output alone above it, with no floor
ROLL_OFF_POINTS = (0.46, 0.47, 0.48, 0.49, 0.5)
ROLL_OFF_HALF_BAND = 0.005
#: smallest ratio of the records' highest to lowest shaft speed over which the background's
#: growth with speed is fitted [-]: the twelve 0.014 in drive-end 12 kHz CWRU records'
#: background levels (:func:`_background_levels`) scatter by 1.3 dB (standard deviation)
#: within their 1723-1796 r/min, and fitted over that 4 % span the slope is -0.09 +/- 3.1
#: (docs/validation.md); the same scatter over a 1.5x span gives about +/- 0.3
MIN_SPEED_SPAN = 1.5
#: fewest records with a known shaft speed for that fit (two give a slope without a scatter)
MIN_SPEED_RECORDS = 3
#: largest standard error of the fitted speed exponent that is kept [-]
MAX_SPEED_EXPONENT_SE = 0.5


@dataclass(frozen=True)
class SpeedLaw:
    """The background's growth with shaft speed as identified (:func:`speed_law`).

    Attributes
    ----------
    exponent : float or None
        ``n`` of ``b ~ N^n`` [-] (amplitude); None when not identified.
    rpm_ref : float or None
        The speed the background table is referred to [r/min] (the speeds' geometric mean).
    stderr : float or None
        Standard error of ``n`` [-].
    note : str
        How it was fitted, or why it was not (for the provenance and the command's output).
    """

    exponent: float | None
    rpm_ref: float | None
    stderr: float | None
    note: str


@dataclass
class IdentifiedRig:
    """A rig and the spectra it was identified from.

    Attributes
    ----------
    rig : Rig
        The identified chain.
    freq : ndarray
        Frequencies of the spectra [Hz].
    psd_records : ndarray, shape (n_records, n_freq)
        Mean-averaged Welch PSD of each record [(m/s^2)^2/Hz].
    freq_sk : ndarray
        Frequencies of the impulsive spectrum (the STFT's) [Hz].
    impulsive : ndarray
        The records' mean normalised impulsive spectrum ``E(f)`` [1/Hz].
    sources : list of str
        The records.
    decay : list of dict
        Per mode: the fitted decay rate [1/s] and the number of impacts used.
    speed_law : SpeedLaw or None
        The background's growth with shaft speed, or why it was not fitted.
    """

    rig: Rig
    freq: NDArray[np.float64]
    psd_records: NDArray[np.float64]
    freq_sk: NDArray[np.float64]
    impulsive: NDArray[np.float64]
    sources: list[str]
    decay: list[dict]
    speed_law: SpeedLaw | None = None

    def plot(self, rig: Rig | None = None):
        """Measured PSDs and the identified background (sensor side), the identified path's
        power gain ``|H(f)|^2`` with its modes, and the impulsive spectrum the modes were found
        in; returns the Figure. ``rig``: the rig as written, whose ``[[model_gain]]`` paths
        (scaled or fitted, one per model) are drawn beside the output-only one."""
        from .plotting import FULL_WIDTH, legend_outside, new_figure

        fs = 2.0 * float(self.freq[-1])
        f = self.freq[1:]
        fig, (a, b, c) = new_figure(3, 1, width=FULL_WIDTH, height=7.5, sharex=True)
        for k, p in enumerate(self.psd_records):
            a.loglog(f, p[1:], color="0.7", lw=0.6,
                     label="measured records (Welch)" if k == 0 else None)  # fmt: skip
        bg = self.rig.background
        if bg is not None:
            fb = np.asarray(bg.frequency_hz)
            at = "" if bg.rpm_ref is None else f" at {bg.rpm_ref:.5g} r/min"
            a.loglog(fb, bg.psd, "b.-", lw=1.2, ms=3,
                     label=f"identified background (table{at})")  # fmt: skip
            if bg.speed_exponent is not None:  # the table is the background at rpm_ref; the
                # records' own speeds span rpm_range (a law needs it): draw it at both ends too
                for n, ls in zip(self.rig.rpm_range, (":", "--"), strict=True):
                    law = f"the same at {n:.5g} r/min (speed^{bg.speed_exponent:.2g})"
                    a.loglog(fb, bg.psd_at(fb, n / 60.0), "b", ls=ls, lw=0.8, label=law)
        a.set_ylabel("PSD [(m/s²)²/Hz]")
        a.set_title(f"rig {self.rig.name}: measured spectra, identified background and path")
        h2 = np.abs(self.rig.transfer(f, fs)) ** 2
        b.loglog(f, h2, "r-", lw=1.0, label="path power gain |H(f)|² (direct gain + modes)")
        top = float(h2.max())
        for g in rig.model_gains if rig is not None else ():
            h2 = np.abs(rig.for_model(g.model).transfer(f, fs)) ** 2
            top = max(top, float(h2.max()))
            b.loglog(f, h2, lw=1.0, ls="--",
                     label=f"{g.model} model's path ({g.describe()})")  # fmt: skip
        # a path without a direct gain falls to 0 at Nyquist: keep 8 decades below the top
        b.set_ylim(bottom=max(b.get_ylim()[0], 1e-8 * top))
        b.set_ylabel("|H(f)|² [-]")
        c.semilogx(self.freq_sk[1:], self.impulsive[1:], "k.-", lw=1.0, ms=3,
                   label="impulsive spectrum E(f)")  # fmt: skip
        for ax in (b, c):
            for m in self.rig.modes:
                ax.axvline(m.frequency_hz, color="r", ls=":", lw=1.0)
        c.plot([], [], "r:", label="identified modes")
        c.set_xlabel("frequency [Hz]")
        c.set_ylabel("E(f), normalised [1/Hz]")
        for ax in (a, b, c):
            legend_outside(ax)
        return fig


def _stft_power(x: NDArray[np.float64], fs: float, nperseg: int):
    from scipy.signal import stft

    f, _, Z = stft(x, fs=fs, nperseg=nperseg, noverlap=nperseg * 3 // 4, boundary=None,
                   padded=False)  # fmt: skip
    return f, np.abs(Z) ** 2


#: a periodogram value of stationary Gaussian noise is exponentially distributed: its median
#: is ln 2 times its mean
_MEDIAN_OVER_MEAN = math.log(2.0)


def _spectral_kurtosis(x, fs, nperseg):
    """Frequencies [Hz], spectral kurtosis [-], mean power of the STFT and its non-impulsive
    share [-] (one transform). The share is ``min(1, median_t P(t, f) / (ln 2 mean_t P(t,
    f)))``: 1 for stationary Gaussian noise (whose periodogram's median is ln 2 times its mean)
    and for a steady tone (median = mean, capped), small where short impacts carry the power
    (most segments, shorter than the time between two impacts, hold none)."""
    f, P = _stft_power(x, fs, nperseg)
    m2 = P.mean(axis=1)
    med = np.median(P, axis=1)
    share = np.minimum(med / (_MEDIAN_OVER_MEAN * np.maximum(m2, 1e-300)), 1.0)
    share = np.where(m2 > 0, share, 1.0)
    m4 = (P * P).mean(axis=1)
    sk = np.where(m2 > 0, m4 / np.maximum(m2, 1e-300) ** 2 - 2.0, 0.0)
    # the DC and Nyquist bins are real: a Gaussian gives SK = 1 there, not 0, and a
    # median/mean of 0.455 (chi-squared with one degree of freedom), not ln 2: both bins take
    # their neighbour's values
    sk[0] = 0.0
    share[0] = share[1]
    if nperseg % 2 == 0:
        sk[-1] = 0.0
        share[-1] = share[-2]
    return f, sk, m2, share


def _psd_peak(f, psd, fc):
    """The frequency [Hz] of the resonance an impulsive band at ``fc`` [Hz] points to: the
    maximum of the smoothed PSD ``psd`` on the grid ``f`` within +/- 1/12 octave when it lies
    inside that window; when it lies on the window's edge the PSD still climbs there and the
    window holds no peak (the band sits between two resonances, or on one's flank): then the
    highest local maximum within +/- 1/6 octave, or None if there is none."""
    from scipy.signal import find_peaks

    idx = np.flatnonzero((f >= fc * 2 ** (-1 / 12)) & (f <= fc * 2 ** (1 / 12)))
    k = int(idx[np.argmax(psd[idx])])
    if idx[0] < k < idx[-1]:
        return float(f[k])
    wide = np.flatnonzero((f >= fc * 2 ** (-1 / 6)) & (f <= fc * 2 ** (1 / 6)))
    peaks, _ = find_peaks(psd[wide])
    if peaks.size == 0:
        return None
    return float(f[wide[peaks[np.argmax(psd[wide][peaks])]]])


#: how far from its kinematic position a shaft line is searched before it is taken out of a
#: record [share of its frequency]: the 1 % a speed read off a file may be off
TONE_SEARCH_REL = 0.01
#: zero padding of the spectrum a shaft line's frequency is read from [-]
TONE_PAD = 8


#: false-alarm probability of a shaft tone's detection, per record and order [-]: a tone is
#: kept in a record where its Hann line's largest of the 5 bins around the order exceeds what
#: noise exceeds with this probability (each bin's squared amplitude of noise is exponential
#: with mean ``2 PSD ENBW``, read off the record's own spectrum beside the line,
#: :func:`_local_noise2`: the threshold is ``2 PSD ENBW ln(5 / p)``, 12.3 dB over
#: ``sqrt(PSD ENBW)``). Until the twenty-eighth session the threshold was 6 dB over
#: ``sqrt(PSD ENBW)``, which white noise crossed on 44.5 % of the records (a helper's
#: exploratory testing: tones "found" in 6 of 10 toneless trials).
TONE_FALSE_ALARM = 1e-3


def _local_noise2(spec, k: int, ft: float, ff) -> float:
    """Noise's mean squared amplitude [(m/s^2)^2] in the Hann amplitude spectrum ``spec``
    (frequencies ``ff`` [Hz]) around the bin ``k`` of a line at ``ft`` [Hz]: the median of
    the squared amplitudes within +/- 25 % of ``ft`` (at least 12 bins each side), the line's
    own +/- 4 bins left out, over ln 2 (the median of an exponential). The record's own
    spectrum, not the Welch background: at 4 Hz resolution and 1/6-octave smoothing that held
    the tone itself near 30 Hz, and a 0.3 m/s^2 tone on a 1 or 2 s record was missed (a
    helper's exploratory testing, twenty-eighth session)."""
    half = max(12, int(np.ceil(0.25 * ft / (ff[1] - ff[0]))))
    idx = np.arange(max(k - half, 1), min(k + half + 1, spec.size))
    idx = idx[np.abs(idx - k) > 4]
    return float(np.median(spec[idx] ** 2)) / math.log(2.0)


def _line_at(y, t, fs, spec, fx, f0) -> float | None:
    """The frequency [Hz] of the record's line near ``f0`` [Hz]: read off its zero-padded Hann
    spectrum ``spec`` (frequencies ``fx``) within :data:`TONE_SEARCH_REL`, then refined to a
    small part of the padded bin by the least-squares amplitude (``y`` at times ``t``); None
    where ``f0`` lies outside (0, fs/2)."""
    w = np.flatnonzero((fx >= f0 * (1.0 - TONE_SEARCH_REL)) & (fx <= f0 * (1.0 + TONE_SEARCH_REL)))
    if not w.size or not 0.0 < f0 < 0.5 * fs:
        return None
    fk = float(fx[w[np.argmax(spec[w])]])
    # the fitted amplitude over 9 frequencies across +/- one padded bin, and the vertex of a
    # parabola through the best three (a frequency off by 0.0125 Hz over 5 s drifts 0.4 rad and
    # leaves a fifth of the line)
    grid = fk + (fx[1] - fx[0]) * np.linspace(-1.0, 1.0, 9)
    amp = np.array([_line_fit(y, t, g)[0] for g in grid])
    k = int(np.clip(np.argmax(amp), 1, grid.size - 2))
    a0, a1, a2 = amp[k - 1 : k + 2]
    den = a0 - 2.0 * a1 + a2
    step = 0.5 * (a0 - a2) / den if den < 0.0 else 0.0
    return float(grid[k] + step * (grid[1] - grid[0]))


def _padded_hann(x, fs) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """The record's zero-padded (:data:`TONE_PAD`) Hann amplitude (unscaled) and frequencies."""
    n = x.size
    return (
        np.abs(np.fft.rfft(x * np.hanning(n), n=TONE_PAD * n)),
        np.fft.rfftfreq(TONE_PAD * n, 1.0 / fs),
    )


def _line_amplitude(x, fs, f0, padded) -> float:
    """The least-squares amplitude [m/s^2] of the record's line near ``f0`` [Hz] at its refined
    frequency (:func:`_line_at` on ``padded``, the record's :func:`_padded_hann`; 0 outside
    (0, fs/2)): a Hann peak reads up to 1.4 dB low between bins (a helper's exploratory
    testing, twenty-eighth session: a 0.3 m/s^2 tone at 29.95 Hz read 0.255)."""
    t = np.arange(x.size) / fs
    fk = _line_at(x, t, fs, *padded, f0)
    return 0.0 if fk is None else _line_fit(x, t, fk)[0]


def _without_tones(x, fs, lines) -> NDArray[np.float64]:
    """The record ``x`` [m/s^2] at ``fs`` [Hz] without its lines near ``lines`` [Hz]: each
    line's frequency read off the record's zero-padded Hann spectrum within
    :data:`TONE_SEARCH_REL` of the given one and refined (:func:`_line_at`), then the sinusoid
    of that frequency fitted by least squares over the whole record and subtracted (a line is
    stationary; its Hann leakage, 31 dB down three bins away, would stay in a notch)."""
    t = np.arange(x.size) / fs
    spec, fx = _padded_hann(x, fs)
    y = np.array(x, dtype=float)
    for f0 in lines:
        fk = _line_at(y, t, fs, spec, fx, f0)
        if fk is not None:
            y -= _line_fit(y, t, fk)[1]
    return y


def _line_fit(y, t, f) -> tuple[float, NDArray[np.float64]]:
    """The least-squares sinusoid of frequency ``f`` [Hz] in ``y`` at times ``t`` [s]: its
    amplitude and its samples."""
    c, s = np.cos(2.0 * np.pi * f * t), np.sin(2.0 * np.pi * f * t)
    a = np.linalg.solve([[c @ c, c @ s], [c @ s, s @ s]], [c @ y, s @ y])
    return float(np.hypot(a[0], a[1])), a[0] * c + a[1] * s


def _smooth_octave(f, y, frac):
    """Mean over ``[f 2^(-frac/2), f 2^(frac/2)]`` at each frequency."""
    out = np.empty_like(y)
    c = np.concatenate([[0.0], np.cumsum(y)])
    lo = np.searchsorted(f, f * 2.0 ** (-frac / 2.0), side="left")
    hi = np.searchsorted(f, f * 2.0 ** (frac / 2.0), side="right")
    out[:] = (c[hi] - c[lo]) / np.maximum(hi - lo, 1)
    return out


def _decay_rate(x, fs, fn, bw):
    """Median envelope decay rate [1/s] of the ringing at ``fn`` [Hz] after the impacts, and
    the number of impacts used."""
    from scipy.signal import butter, find_peaks, hilbert, sosfiltfilt

    half = max(2.5 * bw, 0.08 * fn, 150.0)
    lo, hi = max(fn - half, 20.0), min(fn + half, 0.49 * fs)
    y = sosfiltfilt(butter(4, [lo, hi], btype="band", fs=fs, output="sos"), x)
    env = np.abs(hilbert(y))
    med = np.median(env)
    # impacts: envelope maxima well above its median (between it and the top 0.5 % level)
    thr = med + 0.4 * (float(np.percentile(env, 99.5)) - med)
    peaks, _ = find_peaks(env, height=thr, distance=max(1, int(0.002 * fs)))
    n = int(0.004 * fs)
    segs = [env[p : p + n] / env[p] for p in peaks if p + n <= env.size]
    if len(segs) < 5:
        return math.nan, len(segs)
    m = np.median(np.array(segs), axis=0)
    below = np.flatnonzero(m < 0.2)
    cut = int(below[0]) if below.size else n
    if cut < 3:
        return math.nan, len(segs)
    t = np.arange(cut) / fs
    sigma = -np.polyfit(t, np.log(m[:cut]), 1)[0]
    return float(sigma), len(segs)


#: the damping ratio whose half-power band the decay's first analysis band is made for [-]
ZETA_FIRST = 0.025


def _mode_decay(xs, fs, fn) -> tuple[float | None, list]:
    """The median decay rate [1/s] over the records ``xs`` of the ringing at ``fn`` [Hz]
    (:func:`_decay_rate`) and each record's ``(rate, impacts)``; None where no record rings.
    The analysis band is first made for :data:`ZETA_FIRST` (five half-power bandwidths of
    ``bw = 2 zeta fn``); a band can only cap the decay it passes, so where the damping found
    exceeds what the band was made for, the band is made for it and the decay read again, the
    wider band's kept only where it is faster (up to four times). A band fixed at fn +/- 12.5 %
    capped the damping at about 0.07 (a helper's exploratory testing, twenty-eighth session:
    0.3 read 0.073)."""
    zeta = ZETA_FIRST
    sigma, sig = None, []
    for _ in range(4):
        trial = [_decay_rate(x, fs, fn, 2.0 * zeta * fn) for x in xs]
        rates = [s for s, _n in trial if np.isfinite(s)]
        if not rates:
            break
        found = float(np.median(rates))
        if sigma is not None and found <= sigma:  # the narrower band did not cap it
            break
        sigma, sig = found, trial
        new = sigma / (2.0 * math.pi * fn)
        if new <= zeta * 1.05:  # within what its band resolves
            break
        zeta = new
    return sigma, sig


def _rpm_range(rpms: list[float | None]) -> tuple[float, float] | None:
    """The lowest and highest of the records' shaft speeds ``rpms`` [r/min]
    (:func:`_record_rpm`), or None when none is known."""
    v = [n for n in rpms if n]
    return (min(v), max(v)) if v else None


def _record_rpm(r) -> float | None:
    """A record's shaft speed [r/min]: its ``rpm``, else the median of its speed column; None
    when it has neither. A speed that is not positive is refused in one line naming the
    record."""
    if r.rpm is not None:
        n, what = float(r.rpm), "shaft speed"
    elif getattr(r, "speed_hz", None) is not None:
        n, what = 60.0 * float(np.median(r.speed_hz)), "median of its speed column"
    else:
        return None
    if not (math.isfinite(n) and n > 0.0):
        raise ConfigError(
            f"rig identify: {Path(r.source).name}: {what} = {n:g} r/min; valid: a positive "
            "shaft speed"
        )
    return n


#: points of the background's level per record [-] (log-spaced, 10 Hz to 0.45 fs)
N_LEVEL_POINTS = 60


def _background_levels(f, psd_bg, fs) -> list[float]:
    """Each record's background level [-]: the median over :data:`N_LEVEL_POINTS`
    log-spaced frequencies (10 Hz to 0.45 fs) of ``0.5 ln(S_i / S_mean)``, ``S_i`` its
    non-impulsive PSD smoothed over 1/6 octave and ``S_mean`` the records' geometric mean:
    the log of its amplitude relative to the others. A median over frequency, not the RMS:
    the ringing a fault leaves between its impacts stays in a mode's band of the non-impulsive
    PSD and does not follow the machine's speed (on synthetic records whose background grows
    as speed^2 the RMS gave a slope of 0.89, this level 2.0)."""
    fl = np.geomspace(10.0, 0.45 * fs, N_LEVEL_POINTS)
    logs = np.array([
        np.log(np.maximum(np.interp(fl, f, _smooth_octave(f, p, 1.0 / 6.0)), 1e-300))
        for p in psd_bg
    ])  # fmt: skip
    common = logs.mean(axis=0)
    return [float(np.median(0.5 * (lg - common))) for lg in logs]


def speed_law(levels: list[float], rpms: list[float | None]) -> SpeedLaw:
    """Fit the background's speed law from each record's background level ``levels`` [-]
    (the log of its amplitude on any common reference, :func:`_background_levels`) and shaft
    speed ``rpms`` [r/min] (None: unknown), as the module docstring says (step 4)."""
    from .rig import MAX_SPEED_EXPONENT

    pts = [(b, n) for b, n in zip(levels, rpms, strict=True) if n and math.isfinite(b)]
    if len(pts) < MIN_SPEED_RECORDS:
        return SpeedLaw(None, None, None,
                        f"not fitted: {len(pts)} record(s) with a known shaft speed, "
                        f"{MIN_SPEED_RECORDS} needed")  # fmt: skip
    b, n = np.array([p[0] for p in pts]), np.log([p[1] for p in pts])
    lo, hi = math.exp(n.min()), math.exp(n.max())
    span = hi / lo
    if span < MIN_SPEED_SPAN:
        return SpeedLaw(None, None, None,
                        f"not fitted: the records' speeds span {lo:.4g}-{hi:.4g} r/min (x"
                        f"{span:.3g}), under the x{MIN_SPEED_SPAN:g} a speed law needs; the "
                        "background is the same at every speed")  # fmt: skip
    ref = float(math.exp(n.mean()))
    x = n - n.mean()
    slope = float(np.sum(x * (b - b.mean())) / np.sum(x * x))
    resid = b - b.mean() - slope * x
    dof = len(pts) - 2
    se = float(math.sqrt(np.sum(resid**2) / dof / np.sum(x * x))) if dof > 0 else math.inf
    how = (
        "least-squares slope of the records' background level (the median over 10 Hz-0.45 fs "
        "of ln amplitude) over ln(shaft speed), "
        f"{len(pts)} records at {lo:.4g}-{hi:.4g} r/min: {slope:.3g} +/- {se:.2g}"
    )
    if not se <= MAX_SPEED_EXPONENT_SE:
        return SpeedLaw(None, None, se,
                        f"not fitted: {how}, a standard error above {MAX_SPEED_EXPONENT_SE:g}; "
                        "the background is the same at every speed")  # fmt: skip
    if abs(slope) > MAX_SPEED_EXPONENT:
        return SpeedLaw(None, None, se,
                        f"not fitted: {how}, beyond +/- {MAX_SPEED_EXPONENT:g}; the background "
                        "is the same at every speed")  # fmt: skip
    return SpeedLaw(slope, ref, se, f"{how}; the table is the background at {ref:.5g} r/min")


def identify_rig(
    records: list,
    *,
    name: str,
    description: str = "",
    provenance: str = "",
    max_modes: int = 3,
    min_separation: float = 1.25,
    min_kurtosis: float = 0.5,
    nperseg_sk: int | None = None,
    n_background: int = 40,
    end: str | None = None,
) -> IdentifiedRig:
    """Identify a rig from measured records of one machine and channel (see the module
    docstring).

    Parameters
    ----------
    records : list of SignalRecord
        Records of one channel at one sample rate (:func:`bearingsim.io.signal.read_signal`),
        each at least 1 s long, with the shaft speed known (``rpm``) for the tones.
    name, description, provenance : str
        The rig's name, description and provenance (the command that made it).
    max_modes : int
        Largest number of modes [-].
    min_separation : float
        Smallest frequency ratio between two modes [-].
    min_kurtosis : float
        Spectral kurtosis below which a record set counts as without impulsive content [-].
    nperseg_sk : int, optional
        STFT segment for the spectral kurtosis [samples] (default: 2.5 ms, a power of 2).
    n_background : int
        Points of the background table [-].
    end : {"DE", "FE"}, optional
        The machine end whose housing the records' sensor is on (:attr:`Rig.end`).
    """
    from scipy.signal import welch

    if not records:
        raise ConfigError("rig identify: no records given")
    fs = float(records[0].fs)
    for r in records:
        # rates read off time columns differ in their last digits (11999.9998 and
        # 11999.99996 Hz were "12000 Hz and 12000 Hz"; exploratory testing, twenty-sixth session)
        if abs(float(r.fs) / fs - 1.0) > 1e-6:
            raise ConfigError(
                f"rig identify: {Path(r.source).name} is sampled at {r.fs:g} Hz, the first record "
                f"at {fs:g} Hz; identify one sample rate at a time"
            )
        dur = r.x.size / fs
        if r.x.size < round(MIN_DURATION_S * fs):  # in samples: a 1 s record at fs passes
            raise ConfigError(
                f"rig identify: {Path(r.source).name} is {dur:.6g} s long ({r.x.size} samples "
                f"at {fs:g} Hz); at least {MIN_DURATION_S:g} s is needed"
            )
    rpms = [_record_rpm(r) for r in records]  # before any work: a bad speed is one line
    nps = nperseg_sk or int(2 ** round(math.log2(0.0025 * fs)))
    if nps < MIN_SEGMENT:
        lo = 2 ** (math.log2(MIN_SEGMENT) - 0.5) / 0.0025 if nperseg_sk is None else None
        raise ConfigError(
            f"fs_hz = {fs:g} Hz is too low to identify a transfer path: the spectral-kurtosis "
            f"segment holds {nps} samples, fewer than {MIN_SEGMENT}; valid range "
            + (f"[{math.ceil(lo)}, inf) Hz" if lo else f"nperseg_sk >= {MIN_SEGMENT}")
        )
    nwelch = int(2 ** round(math.log2(fs / 4.0)))  # ~4 Hz resolution
    psd_mean, psd_med, psd_bg, imp, shares = [], [], [], [], []
    f_sk = None
    xs = [np.asarray(r.x, dtype=float) - float(np.mean(r.x)) for r in records]  # centred
    for x in xs:
        f, pm = welch(x, fs=fs, nperseg=nwelch)
        _, pd = welch(x, fs=fs, nperseg=nwelch, average="median")
        psd_mean.append(pm)
        psd_med.append(pd)
        f_sk, sk, p, share = _spectral_kurtosis(x, fs, nps)
        # the background: the fine PSD times the non-impulsive share of its band (segments
        # of 2.5 ms, shorter than the time between two impacts; a Welch median over 0.25 s
        # segments, each holding tens of impacts, kept them)
        shares.append(np.interp(f, f_sk, share))
        psd_bg.append(pm * shares[-1])
        e = np.maximum(sk, 0.0) * p
        imp.append((e / max(float(np.trapezoid(e, f_sk)), 1e-300), float(np.max(sk))))
    f = np.asarray(f)
    if max(k for _, k in imp) < min_kurtosis:
        raise ConfigError(
            f"rig identify: no impulsive content (spectral kurtosis at most "
            f"{max(k for _, k in imp):.2g}, below {min_kurtosis:g}): the modes of the path "
            "cannot be seen; give records with a fault"
        )
    E = np.mean([e for e, _ in imp], axis=0)
    # modes: largest peaks of E, separated
    from scipy.signal import find_peaks

    Es = _smooth_octave(f_sk, E, 1.0 / 6.0)
    cand, _ = find_peaks(Es)
    cand = cand[np.argsort(Es[cand])[::-1]]
    chosen: list[int] = []
    for c in cand:
        if f_sk[c] < 100.0 or f_sk[c] > 0.45 * fs or Es[c] < 0.1 * Es[cand[0]]:
            continue
        if all(max(f_sk[c], f_sk[k]) / min(f_sk[c], f_sk[k]) >= min_separation for k in chosen):
            chosen.append(int(c))
        if len(chosen) == max_modes:
            break
    # the shoulders of the modes' gains (step 3): the median-averaged PSD, smoothed
    bg_s = _smooth_octave(f, np.median(np.array(psd_med), axis=0), 1.0 / 6.0)
    # tones at shaft orders: each record's amplitude spectrum (Hann), computed once
    from .signal.spectrum import amplitude_spectrum

    # (a record's speed: its rpm, or its speed column's median; a column alone placed no tone
    # until the twenty-fourth session)
    spectra = [(x, rn, amplitude_spectrum(x, fs))
               for x, rn in zip(xs, rpms, strict=True) if rn]  # fmt: skip
    orders = (1.0, 2.0, 3.0)
    found_amps: dict[float, list[float]] = {o: [] for o in orders}
    for x, rn, sp in spectra:
        spec, ff = sp.amplitude, sp.freq
        padded = None  # the record's padded Hann spectrum, once for its orders' amplitudes
        for order in orders:
            ft = order * rn / 60.0
            k = np.argmin(np.abs(ff - ft))
            w = slice(max(k - 2, 0), k + 3)
            line = float(spec[w].max())
            found = line * line > _local_noise2(spec, k, ft, ff) * math.log(5.0 / TONE_FALSE_ALARM)
            if found and padded is None:
                padded = _padded_hann(x, fs)
            found_amps[order].append(_line_amplitude(x, fs, ft, padded) if found else 0.0)
    tones = []
    for order in orders:
        amps = found_amps[order]
        if amps and np.median(amps) > 0.0:
            tones.append(
                Tone(float(np.median(amps)),
                     f"median over {len(amps)} records of the least-squares sinusoid at "
                     f"{order:g} x the record's shaft speed (kept where its Hann line stands "
                     f"over the background's at a false-alarm probability of "
                     f"{TONE_FALSE_ALARM:g})", order=order)
            )  # fmt: skip
    # the tones kept are the rig's [[tone]]s: out of each record before its background, or
    # they count twice (exploratory testing, twenty-fourth session: a 0.3 m/s^2 line at 1 x
    # put 1.8e-3 (m/s^2)^2 into 10-22 Hz of the table against the records' 1.4e-8; the
    # shipped CWRU profiles carried their 1 x line there, 100 times their floor)
    if tones:
        psd_bg = [
            welch(_without_tones(x, fs, [t.order * rn / 60.0 for t in tones]), fs=fs,
                  nperseg=nwelch)[1] * sh if rn else p
            for x, rn, sh, p in zip(xs, rpms, shares, psd_bg, strict=True)
        ]  # fmt: skip
    # the background's growth with speed (step 4), then each record's referred to rpm_ref
    law = speed_law(_background_levels(f, psd_bg, fs), rpms)
    if law.exponent is not None:
        psd_bg = [p * (law.rpm_ref / n) ** (2.0 * law.exponent) if n else p
                  for p, n in zip(psd_bg, rpms, strict=True)]  # fmt: skip
    # the background table (step 4): the non-impulsive PSD, median over the records, smoothed
    bg_t = _smooth_octave(f, np.median(np.array(psd_bg), axis=0), 1.0 / 6.0)
    mean_psd = np.median(np.array(psd_mean), axis=0)
    mean_psd_s = _smooth_octave(f, mean_psd, 1 / 24)
    modes, decay, rejected = [], [], []
    for c in sorted(chosen, key=lambda k: f_sk[k]):
        # refine the frequency on the fine Welch grid: the PSD maximum within +/- 1/12 octave
        fc = float(f_sk[c])
        fn = _psd_peak(f, mean_psd_s, fc)
        if fn is None:
            rejected.append(
                f"{fc:.0f} Hz (no PSD peak within 1/6 octave: an impulsive band between resonances)"
            )
            continue
        sigma, sig = _mode_decay(xs, fs, fn)
        if sigma is None:
            rejected.append(f"{fn:.0f} Hz (no ringing decay after the impacts)")
            continue
        zeta = min(max(sigma / (2 * math.pi * fn), 0.005), 0.5)
        # gain: PSD at fn over the shoulders' log-log trend (one octave, the mode's band out)
        bwn = 2 * zeta * fn
        sh = ((f > fn / 2) & (f < fn - 3 * bwn)) | (
            (f > fn + 3 * bwn) & (f < min(2 * fn, 0.45 * fs))
        )
        if np.count_nonzero(sh) < 4:
            rejected.append(f"{fn:.0f} Hz (no shoulders to measure a resonance against)")
            continue
        coef = np.polyfit(np.log(f[sh]), np.log(bg_s[sh]), 1)
        shoulder = float(np.exp(np.polyval(coef, np.log(fn))))
        peak = float(mean_psd_s[np.argmin(np.abs(f - fn))])
        gain = math.sqrt(peak / shoulder) - 1.0
        if gain < MIN_GAIN:  # no resonance stands out of the shoulders: not a mode of the path
            rejected.append(f"{fn:.0f} Hz (gain {gain:.2g} over its shoulders, below {MIN_GAIN:g})")
            continue
        # a resonance holds its level across its half-power band (fn +/- zeta fn, from the
        # decay); a line of the fault's own harmonic comb is narrower, and averaged over that
        # band falls to the shoulders
        held = (f >= fn * (1.0 - zeta)) & (f <= fn * (1.0 + zeta))
        gain_held = math.sqrt(float(np.mean(mean_psd[held])) / shoulder) - 1.0
        if gain_held < MIN_GAIN:
            rejected.append(
                f"{fn:.0f} Hz (a line, not a resonance: gain {gain_held:.2g} over its shoulders "
                f"across its half-power band {2 * zeta * fn:.0f} Hz, below {MIN_GAIN:g})"
            )
            continue
        modes.append(
            Mode(fn, zeta, gain,
                 f"impulsive-spectrum peak at {fc:.0f} Hz refined on the PSD; zeta from the median "
                 f"envelope decay of {sum(n for _, n in sig)} impacts (sigma = {sigma:.0f} 1/s); "
                 f"gain = sqrt(PSD peak / shoulder trend) - 1 = sqrt({peak / shoulder:.3g}) - 1")
        )  # fmt: skip
        decay.append({"frequency_hz": fn, "sigma_per_s": sigma, "impacts": sum(n for _, n in sig)})
    if not modes:
        raise ConfigError(
            "rig identify: no mode could be identified: no resonance rings after the impacts "
            "in the impulsive bands (" + "; ".join(rejected or ["none above 100 Hz"]) + "); give "
            "records whose faults ring the structure (a model's output through a rig's direct "
            "gain is broadband spikes, not ringing)"
        )
    # background table at log-spaced points from 10 Hz to 0.45 fs, then the roll-off to fs/2
    fb = np.geomspace(10.0, 0.45 * fs, n_background)
    pb = np.exp(np.interp(np.log(fb), np.log(f[1:]), np.log(np.maximum(bg_t[1:], 1e-30))))
    bg_raw = np.median(np.array(psd_bg), axis=0)
    top = []
    for q in ROLL_OFF_POINTS:  # the Nyquist bin itself left out (Welch halves it)
        w = (f >= (q - ROLL_OFF_HALF_BAND) * fs) & (f <= (q + ROLL_OFF_HALF_BAND) * fs)
        w[-1] = False
        top.append(max(float(np.mean(bg_raw[w])), 1e-30))
    fb = np.concatenate([fb, np.array(ROLL_OFF_POINTS) * fs])
    pb = np.concatenate([pb, top])
    bg = Background(
        tuple(float(v) for v in fb),
        tuple(float(v) for v in pb),
        f"non-impulsive PSD of each record (Welch, nperseg {nwelch}, times the share "
        f"median/(ln 2 mean) <= 1 of STFT power in segments of {nps} samples), median over "
        f"{len(records)} records, mean over 1/6 octave, at {n_background} log-spaced points "
        f"to 0.45 fs; above, the recorder's roll-off: the mean over +/- {ROLL_OFF_HALF_BAND:g} "
        f"fs at {', '.join(f'{q:g}' for q in ROLL_OFF_POINTS)} fs; speed law: {law.note}",
        speed_exponent=law.exponent,
        rpm_ref=law.rpm_ref,
    )
    rig = Rig(
        name=name,
        description=description,
        provenance=provenance or "bearingsim.rig_identify.identify_rig",
        input_channel="acc_y",
        end=end,
        fs_hz=float(fs),
        rpm_range=_rpm_range(rpms),
        gain=1.0,
        gain_provenance="output-only identification: the path's direct gain is taken as 1 and "
        "each mode's gain is relative to it (bearingsim.rig_identify, item 3)",
        modes=tuple(modes),
        background=bg,
        tones=tuple(tones),
        noise_rms_m_per_s2=0.0,
        noise_provenance="not separable from the background in output-only data: part of it",
    )
    return IdentifiedRig(
        rig=rig,
        freq=f,
        psd_records=np.array(psd_mean),
        freq_sk=np.asarray(f_sk),
        impulsive=E,
        sources=[str(r.source) for r in records],
        decay=decay,
        speed_law=law,
    )


#: resolution of the path fit's Welch spectra [Hz] (the segment is the nearest power of two):
#: fine enough for the modes' half-power bands (2 zeta f_n >= 100 Hz for the CWRU modes), coarse
#: enough to average 40 segments per second of record
PATH_FIT_RESOLUTION_HZ = 25.0
#: band of the path fit [Hz, fraction of fs]: above the shaft tones' lowest harmonics, below
#: a recorder's anti-aliasing roll-off
PATH_FIT_LOW_HZ = 20.0
PATH_FIT_HIGH_FS = 0.45


#: the objectives of :func:`fit_path_gains`
PATH_FIT_OBJECTIVES = ("spectral", "whittle")


@dataclass(frozen=True)
class PathFit:
    """Result of :func:`fit_path_gains`.

    Attributes
    ----------
    rig : Rig
        The rig with its direct gain and mode gains replaced by the fitted ones (everything
        else as given).
    gains : tuple of float
        The fitted direct gain and the gain of each mode, in the rig's order [-].
    start_gains : tuple of float
        The rig's gains before the fit [-].
    objective : str
        ``"spectral"`` or ``"whittle"`` (:func:`fit_path_gains`).
    power_ratio : float
        Fitted over measured power in the fit band, summed over the records [-] (1 for the
        ``"spectral"`` objective by construction).
    provenance : str
        How the gains were fitted, and on what (the gains' provenance).
    """

    rig: Rig
    gains: tuple[float, ...]
    start_gains: tuple[float, ...]
    objective: str
    power_ratio: float
    provenance: str


def fit_path_gains(
    rig: Rig,
    pairs: list[tuple[NDArray[np.float64], NDArray[np.float64]]],
    fs: float,
    *,
    objective: str = "spectral",
    provenance: str = "",
    rpms: list[float | None] | None = None,
) -> PathFit:
    """Model-based gains of the path: the direct gain and every mode's gain of ``rig`` fitted so
    that the model's output through the path, plus the rig's background, has the measured
    records' power spectra (the known-input part an output-only identification cannot give;
    the modes' frequencies and damping ratios are kept).

    For each pair (measured ``y``, the model's output ``x`` for the same condition, both
    [m/s^2] at ``fs``) the Welch spectra ``P_y`` and ``P_x`` (Hann, 50 % overlap, about
    :data:`PATH_FIT_RESOLUTION_HZ`) over [:data:`PATH_FIT_LOW_HZ`, :data:`PATH_FIT_HIGH_FS`
    fs] are compared with

    ``S(f) = P_bg(f) + |g_0 + sum_k g_k R_k(f)|^2 P_x(f)``

    (``R_k`` the mode's resonator at unit gain, :meth:`bearingsim.rig.Mode.sos`; ``P_bg`` the
    rig's background table). Objectives:

    * ``"spectral"`` (default) -- the **shape** by least squares of ``ln S - ln P_y`` over
      every Welch ordinate of every pair (a fit in decibels, as transfer-function magnitudes are
      fitted: an ordinate ten times too high weighs as one ten times too low), then the
      **level** by the power balance of :func:`bearingsim.side_by_side.model_path_scale`
      over the band, every gain times ``k`` with
      ``k^2 = sum (P_y - P_bg) / sum |H|^2 P_x``: the fitted path carries the records' power
      above the background.
    * ``"whittle"`` -- Whittle's negative log-likelihood ``sum (ln S + P_y / S)``, the
      maximum-likelihood estimate for averaged periodograms (Whittle 1953). It is exact when
      the model's spectrum has the records' shape; where it has not, the likelihood punishes
      an ordinate too low far more than one too high, and the fit overshoots the power (1.9x
      on CWRU record 132 with the VSM, docs/validation.md).

    The gains are bounded to [0, :data:`~bearingsim.rig.MAX_GAIN`] and started from the
    rig's own gains scaled by 1e-3 ... 1 (the best of the four starts). The phases of the
    model's output are not used: a power-spectral fit cannot tell a mode's sign, so gains are
    >= 0.

    Parameters
    ----------
    rig : Rig
        The output-only rig (:func:`identify_rig`) whose modes and background are kept.
    pairs : list of (ndarray, ndarray)
        ``(measured, model output)`` per record [m/s^2], each pair of one length (>= 1 s);
        the model output without the rig (no background).
    fs : float
        Sample rate of every signal [Hz].
    objective : {"spectral", "whittle"}
        See above.
    provenance : str
        Where the pairs come from (the records and the model), put in the gains' provenance.
    rpms : list of float or None, optional
        Each pair's shaft speed [r/min] (None: unknown): the background a rig with a speed law
        adds at it (:meth:`bearingsim.rig.Background.speed_factor`); default unknown for all.

    Returns
    -------
    PathFit

    Raises
    ------
    ConfigError
        ``pairs`` empty, a pair of unequal lengths, shorter than :data:`MIN_DURATION_S`, or
        not finite; a model output that is zero in the fit band; records whose power in the
        band the background alone carries (``"spectral"``).
    """
    from dataclasses import replace as dc_replace

    from scipy.optimize import least_squares, minimize
    from scipy.signal import sosfreqz, welch

    from .errors import check_range
    from .rig import MAX_GAIN

    fs = check_range("fs_hz", fs, 0.0, lo_open=True, unit="Hz")
    if objective not in PATH_FIT_OBJECTIVES:
        raise ConfigError(
            f"objective = {objective!r} is invalid; valid: " + ", ".join(PATH_FIT_OBJECTIVES)
        )
    if not pairs:
        raise ConfigError("pairs is empty; valid: at least one (measured, model output) pair")
    if rpms is not None and len(rpms) != len(pairs):
        raise ConfigError(
            f"rpms has {len(rpms)} speeds for {len(pairs)} pairs; valid: one per pair (None "
            "where unknown)"
        )
    nperseg = 2 ** int(round(math.log2(fs / PATH_FIT_RESOLUTION_HZ)))
    data = []
    for i, pair in enumerate(pairs):
        y, x = (np.asarray(v, dtype=float) for v in pair)
        if y.ndim != 1 or y.shape != x.shape:
            raise ConfigError(
                f"pairs[{i}]: measured {y.shape} and model output {x.shape} samples; valid: "
                "two 1-D signals of one length"
            )
        if y.size < MIN_DURATION_S * fs:
            raise ConfigError(
                f"pairs[{i}]: {y.size / fs:.3g} s is too short; valid: at least "
                f"{MIN_DURATION_S:g} s"
            )
        if not (np.all(np.isfinite(y)) and np.all(np.isfinite(x))):
            raise ConfigError(f"pairs[{i}]: a signal has non-finite samples")
        f, py = welch(y - y.mean(), fs, nperseg=nperseg)
        _, px = welch(x - x.mean(), fs, nperseg=nperseg)
        band = (f >= PATH_FIT_LOW_HZ) & (f <= PATH_FIT_HIGH_FS * fs)
        for what, p in (("measured signal", py), ("model output", px)):
            if not np.any(p[band] > 0.0):
                raise ConfigError(
                    f"pairs[{i}]: the {what} is zero in {PATH_FIT_LOW_HZ:g}-"
                    f"{PATH_FIT_HIGH_FS * fs:g} Hz; no path gain can be fitted to it"
                )
        fb = f[band]
        pb = np.zeros(fb.size)
        if rig.background is not None:
            n = rpms[i] if rpms is not None else None
            pb = rig.background.psd_at(fb, None if n is None else n / 60.0)
        resp = [sosfreqz(dc_replace(m, gain=1.0).sos(fs), worN=fb, fs=fs)[1] for m in rig.modes]
        data.append((py[band], px[band], pb, np.array(resp).reshape(len(rig.modes), fb.size)))
    # a floor for S and P_y where a Welch ordinate is exactly 0 (not a spectrum): 1e-12 of the
    # records' mean PSD
    floor = 1e-12 * float(np.mean([d[0].mean() for d in data]))

    def path_power(g, px, resp):
        h = g[0] + np.asarray(g[1:]) @ resp
        return (h.real**2 + h.imag**2) * px

    def log_residual(g):
        return np.concatenate(
            [
                np.log(pb + path_power(g, px, resp) + floor) - np.log(py + floor)
                for py, px, pb, resp in data
            ]  # fmt: skip
        )

    def nll(g):
        tot = 0.0
        for py, px, pb, resp in data:
            s_ = pb + path_power(g, px, resp) + floor
            tot += float(np.sum(np.log(s_) + py / s_))
        return tot

    start = np.array([rig.gain, *(m.gain for m in rig.modes)], dtype=float)
    bounds = [(0.0, MAX_GAIN)] * start.size
    best, best_cost = None, math.inf
    for scale in (1e-3, 1e-2, 1e-1, 1.0):
        if objective == "spectral":
            r = least_squares(log_residual, start * scale, bounds=(0.0, MAX_GAIN))
            cost = float(r.cost)
        else:
            r = minimize(nll, start * scale, method="L-BFGS-B", bounds=bounds)
            cost = float(r.fun)
        if cost < best_cost:
            best, best_cost = r, cost
    g = np.asarray(best.x, dtype=float)
    g[g < 1e-9 * g.max()] = 0.0  # at the bound in all but rounding (1e-14 in a fit): none
    excess = sum(float(np.sum(py - pb)) for py, _, pb, _ in data)
    carried = sum(float(np.sum(path_power(g, px, resp))) for _, px, _, resp in data)
    if objective == "spectral":
        if excess <= 0.0:
            raise ConfigError(
                "pairs: the rig's background alone carries the records' power in the fit band; "
                "no path gain can be fitted; valid: records whose power exceeds the background"
            )
        if carried <= 0.0:
            raise ConfigError("pairs: the fitted path carries none of the model's output")
        g = g * math.sqrt(excess / carried)
        carried = excess
    measured = sum(float(np.sum(py)) for py, *_ in data)
    background = sum(float(np.sum(pb)) for _, _, pb, _ in data)
    how = {
        "spectral": "least squares of the log Welch spectra for the shape, the power balance "
        "for the level",
        "whittle": "Whittle likelihood of the Welch spectra",
    }[objective]
    why = (
        f"model-based fit (bearingsim.rig_identify.fit_path_gains: {how}, {PATH_FIT_LOW_HZ:g} Hz"
        f" to {PATH_FIT_HIGH_FS:g} fs" + (f"; {provenance}" if provenance else "") + ")"
    )
    fitted = dc_replace(rig.with_gains(g[0], g[1:], why), model_gains=())
    return PathFit(fitted, tuple(float(v) for v in g), tuple(float(v) for v in start), objective,
                   (background + carried) / measured, why)  # fmt: skip


#: TOML basic-string escapes (TOML 1.0, "String"); other control characters as \uXXXX
_TOML_ESCAPES = {
    "\\": "\\\\",
    '"': '\\"',
    "\b": "\\b",
    "\t": "\\t",
    "\n": "\\n",
    "\f": "\\f",
    "\r": "\\r",
}


def _toml_string(v: str) -> str:
    """``v`` as a TOML basic string: a name or description holding a newline or another
    control character made a file that TOML could not read back (twenty-first session)."""
    out = []
    for ch in v:
        if ch in _TOML_ESCAPES:
            out.append(_TOML_ESCAPES[ch])
        elif ord(ch) < 0x20 or ord(ch) == 0x7F:
            out.append(f"\\u{ord(ch):04x}")
        else:
            out.append(ch)
    return '"' + "".join(out) + '"'


def rig_to_toml(rig: Rig) -> str:
    """The rig as TOML text (the layout :func:`bearingsim.rig.load_rig` reads)."""
    d = rig.to_dict()

    def val(v):
        if isinstance(v, str):
            return _toml_string(v)
        if isinstance(v, bool):
            return "true" if v else "false"
        if isinstance(v, list):
            return "[" + ", ".join(val(x) for x in v) + "]"
        return repr(float(v)) if isinstance(v, float) else str(v)

    # every top-level value before the tables (a key added to Rig.to_dict is written too)
    lines = [f"{k} = {val(v)}" for k, v in d.items()
             if not isinstance(v, dict) and not (isinstance(v, list) and v and
                                                  isinstance(v[0], dict))]  # fmt: skip
    for table in ("bearing", "path", "background", "sensor"):
        if isinstance(d.get(table), dict):  # bearing: a catalogue id is a top-level value
            lines += ["", f"[{table}]"] + [f"{k} = {val(v)}" for k, v in d[table].items()]
    for arr in ("mode", "tone", "model_gain"):
        for item in d.get(arr, []):
            lines += ["", f"[[{arr}]]"] + [f"{k} = {val(v)}" for k, v in item.items()]
    return "\n".join(lines) + "\n"
