"""Signal processing for bearing diagnosis, on simulated and measured signals alike.

- :mod:`.core` — spectra, envelope, fast kurtogram, computed order tracking, peak matching.
- :mod:`.angle` — angle-domain analysis of speed signals (IAS): resampling, order spectrum,
  synchronous average, spall-width estimate.
- :mod:`.diagnosis` — fault diagnosis from the envelope spectrum; signal-file loading.

May import: errors, geometry, materials, io (and :mod:`bearingsim.results` lazily, for reading
result files).
"""

from .angle import AngleSignal, analyze_speed_signal, estimate_spall_width, resample_to_angle
from .core import (
    EnvelopeKind,
    Kurtogram,
    Peak,
    Spectrum,
    amplitude_spectrum,
    angular_resample,
    envelope,
    envelope_spectrum,
    fast_kurtogram,
    match_peaks,
)
from .diagnosis import Diagnosis, analyze_record, diagnose, load_signal

__all__ = [
    "AngleSignal",
    "Diagnosis",
    "EnvelopeKind",
    "Kurtogram",
    "Peak",
    "Spectrum",
    "amplitude_spectrum",
    "analyze_record",
    "analyze_speed_signal",
    "angular_resample",
    "diagnose",
    "envelope",
    "envelope_spectrum",
    "estimate_spall_width",
    "fast_kurtogram",
    "load_signal",
    "match_peaks",
    "resample_to_angle",
]
