"""Spectral peaks: the one parabolic refinement, the largest peaks of a spectrum, the strongest
peak near an expected position, and peak matching at target frequencies (harmonics, sidebands)
with a local signal-to-noise ratio.

Parabolic refinement (:func:`refine_peak`)
    the vertex of the parabola through the line ``y_i`` and its two neighbours: offset
    ``d = (y_{i-1} - y_{i+1}) / (2 (y_{i-1} - 2 y_i + y_{i+1}))`` bins (clipped to ±0.5) and
    height ``y_i - (y_{i-1} - y_{i+1}) d / 4`` (Smith & Serra 1987, "PARSHL", quadratic
    interpolation of spectral peaks). With ``log=True`` the parabola goes through ``ln y``
    (Gaussian interpolation, closer for the Hann main lobe).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from ..errors import ConfigError, check_positive
from .spectrum import Domain, Spectrum

__all__ = [
    "parabola_vertex",
    "Peak",
    "SpectralPeak",
    "match_peaks",
    "refine_peak",
    "spectrum_peaks",
    "strongest_peak",
]


def refine_peak(y: NDArray[np.float64], i: int, *, log: bool = False) -> tuple[float, float]:
    """Parabolic interpolation of the peak at line ``i`` of ``y`` (module docstring).

    Parameters
    ----------
    y : ndarray
        Amplitudes (any unit).
    i : int
        Index of the line to refine.
    log : bool
        Fit the parabola to ``ln y`` (needs the three lines > 0, else no refinement).

    Returns
    -------
    offset : float
        Vertex position relative to line ``i`` [bins], in [-0.5, 0.5]; 0 at the ends of ``y``.
    height : float
        Vertex height (unit of ``y``).
    """
    if not 0 < i < y.size - 1:
        return 0.0, float(y[i])
    y0, y1, y2 = y[i - 1], y[i], y[i + 1]
    if log:
        if min(y0, y1, y2) <= 0.0:
            return 0.0, float(y1)
        y0, y1, y2 = np.log(y0), np.log(y1), np.log(y2)
    den = y0 - 2.0 * y1 + y2
    d = float(0.5 * (y0 - y2) / den) if den != 0 else 0.0
    d = min(max(d, -0.5), 0.5)
    h = float(y1 - 0.25 * (y0 - y2) * d)
    return d, math.exp(h) if log else h


def parabola_vertex(
    x: tuple[float, float, float], y: tuple[float, float, float]
) -> tuple[float, float]:
    """Vertex ``(x_v, y_v)`` of the parabola through three points with any spacing, for a
    maximum between them (the general form of :func:`refine_peak`, for samples that are not on a
    uniform grid, e.g. element centroids of a mesh).

    Parameters
    ----------
    x : (float, float, float)
        Abscissae, ascending or descending (any unit).
    y : (float, float, float)
        Values at ``x`` (any unit).

    Returns
    -------
    (float, float)
        The vertex; the middle point when the parabola opens upwards, is singular, or its vertex
        falls outside ``[min(x), max(x)]``.
    """
    x0, x1, x2 = (float(v) for v in x)
    y0, y1, y2 = (float(v) for v in y)
    A = np.array([[x0 * x0, x0, 1.0], [x1 * x1, x1, 1.0], [x2 * x2, x2, 1.0]])
    try:
        a, bb, c = np.linalg.solve(A, [y0, y1, y2])
    except np.linalg.LinAlgError:
        return x1, y1
    if a >= 0:
        return x1, y1
    xv = -bb / (2 * a)
    if not (min(x0, x2) <= xv <= max(x0, x2)):
        return x1, y1
    return xv, c - bb * bb / (4 * a)


@dataclass(frozen=True)
class SpectralPeak:
    """A refined spectral peak.

    Attributes
    ----------
    freq : float
        Position [Hz], or order [-] in an order spectrum.
    amplitude : float
        Height (unit of the spectrum).
    """

    freq: float
    amplitude: float

    @property
    def order(self) -> float:
        """The position read as an order [-] (order spectra)."""
        return self.freq


def _refined(spec: Spectrum, i: int) -> SpectralPeak:
    d, h = refine_peak(spec.amplitude, i)
    return SpectralPeak(float(spec.freq[i] + d * spec.bin_width), float(h))


def spectrum_peaks(
    spec: Spectrum,
    n_peaks: int = 5,
    *,
    f_min: float = 0.0,
    f_max: float | None = None,
    rel_height: float = 0.05,
) -> list[SpectralPeak]:
    """The ``n_peaks`` largest peaks of ``spec`` in ``[f_min, f_max]``, refined by
    :func:`refine_peak`, largest first.

    Peaks closer than two resolutions (the Hann main lobe) are merged; a peak must reach
    ``rel_height`` times the largest line in the range (the default 0.05 is above the Hann
    window's highest side lobe, -31.5 dB = 0.027).

    Parameters
    ----------
    spec : Spectrum
        Amplitude spectrum (zero padded or not).
    n_peaks : int
        Peaks returned at most [-].
    f_min, f_max : float
        Range searched [Hz or -] (``f_max`` default: the whole spectrum).
    rel_height : float
        Smallest peak relative to the largest line in the range [-].
    """
    from scipy.signal import find_peaks

    m = spec.freq >= f_min
    if f_max is not None:
        m &= spec.freq <= f_max
    if not np.any(m):
        return []
    i0 = int(np.argmax(m))
    a = np.where(m, spec.amplitude, 0.0)
    dist = max(1, int(round(2.0 * spec.resolution / spec.bin_width)))
    idx, _ = find_peaks(a, height=rel_height * a[i0:].max(), distance=dist)
    idx = sorted(idx, key=lambda i: -a[i])[:n_peaks]
    return [_refined(spec, int(i)) for i in idx]


def strongest_peak(spec: Spectrum, near: float, rel_tol: float = 0.1) -> SpectralPeak:
    """Largest line within ``near (1 ± rel_tol)`` [Hz or -], refined by :func:`refine_peak`.

    Parameters
    ----------
    spec : Spectrum
        Amplitude spectrum.
    near : float
        Expected position [Hz or -], > 0.
    rel_tol : float
        Relative half-width of the search window [-].
    """
    what = "expected_order" if spec.domain is Domain.ORDER else "expected_freq_hz"
    near = check_positive(what, near)
    m = (spec.freq >= near * (1 - rel_tol)) & (spec.freq <= near * (1 + rel_tol))
    if not np.any(m):
        raise ConfigError(
            f"{what} = {near:.6g} is beyond the spectrum (max "
            f"{'order' if spec.domain is Domain.ORDER else 'frequency'} {spec.freq[-1]:.4g}); "
            "sample the signal more finely"
        )
    i = int(np.flatnonzero(m)[np.argmax(spec.amplitude[m])])
    return _refined(spec, i)


# --------------------------------------------------------------------------- peak matching


@dataclass(frozen=True)
class Peak:
    """A spectral line found near a target.

    Attributes
    ----------
    label : str
        Target name (e.g. ``"2xBPFO"``, ``"BPFI-fr"``).
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


#: a target whose search window starts less than this many resolutions ``fs / n`` above 0 Hz is
#: not searched: the window would reach the spectrum's zero-frequency line and its leakage
#: (one to two resolutions each side for the tapers used here), which a short record shows
#: as a strong "line" near 0 Hz (e.g. FTF, 2×FTF and 3×FTF all taken at one 6.7 Hz bin of a
#: 0.15 s record) [-]
DC_GUARD = 2.0


def match_peaks(
    spectrum: Spectrum,
    targets: list[tuple[str, float]] | list[tuple[str, float, float, float]],
    shaft_hz: float,
    *,
    tol_rel: float = 0.01,
    tol_min_bins: float = 2.0,
    noise_rel: float = 0.1,
    threshold_db: float = 12.0,
) -> list[Peak]:
    """Find the largest line within ``max(tol_rel f, tol_min_bins df)`` of every target.

    A target whose window reaches above the spectrum's last line, or below
    :data:`DC_GUARD` resolutions of 0 Hz, is left out of the result (not resolvable).

    Parameters
    ----------
    spectrum : Spectrum
        Usually an envelope spectrum.
    targets : list of (label, frequency [Hz]) or (label, frequency, low, high [Hz])
        What to look for; with ``low, high`` the line is searched in ``[low, high]`` (widened
        to ``tol_min_bins`` bins about ``frequency`` at least) instead of about ``frequency``
        (a window that follows the direction a line may move, e.g. with the contact angle).
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
    df = spectrum.bin_width
    out = []
    for target in targets:
        label, ft = target[0], target[1]
        tol = max(tol_rel * ft, tol_min_bins * df)
        lo, hi = ft - tol, ft + tol
        if len(target) == 4:  # an explicit window
            lo = min(target[2], ft - tol_min_bins * df)
            hi = max(target[3], ft + tol_min_bins * df)
            tol = 0.5 * (hi - lo)
        # f is ascending: index ranges instead of masks over the whole spectrum
        i0 = int(np.searchsorted(f, lo, side="left"))
        i1 = int(np.searchsorted(f, hi, side="right"))
        if hi >= f[-1] or i1 <= i0 or lo < DC_GUARD * spectrum.resolution:
            continue
        k = int(i0 + np.argmax(A[i0:i1]))
        hw = max(noise_rel * ft, 5.0 * tol)
        j0 = int(np.searchsorted(f, ft - hw, side="left"))
        j1 = int(np.searchsorted(f, ft + hw, side="right"))
        j0 = max(j0, int(np.searchsorted(f, 0.0, side="right")))  # f > 0
        nw = np.concatenate((A[j0 : min(i0, j1)], A[max(i1, j0) : j1]))
        floor = float(np.median(nw)) if nw.size else float("nan")
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
