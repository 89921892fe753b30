"""Signal processing for bearing diagnosis, on simulated and measured signals alike; one
implementation of each primitive.

- :mod:`.spectrum` — :class:`Domain` (Hz or order), :class:`Spectrum`, and
  :func:`amplitude_spectrum`, the one window and scaling convention (mean removed, Hann window
  corrected for its coherent gain, optional zero padding) of every spectrum here and in the
  models (IAS order spectra, stiffness order spectra).
- :mod:`.envelope` — band-pass, Hilbert envelope, envelope spectrum.
- :mod:`.kurtogram` — Antoni's fast kurtogram.
- :mod:`.order` — shaft speed/angle conversion, the anti-aliased angular resampler (computed
  order tracking), the order spectrum, synchronous averaging, shaft angle/speed files.
- :mod:`.peaks` — the parabolic peak refinement, largest and strongest peaks, peak matching.
- :mod:`.diagnosis` — fault diagnosis from the envelope spectrum; loading a record to diagnose.
- :mod:`.contact_angle` — the shaft speed and the contact angle a bearing runs at, read from a
  race-fault record's own lines.

Signal files are read by :func:`bearingsim.io.read_signal`.

May import: errors, geometry, materials, catalog, io — never a model family (the IAS spall-width
estimate, a model analysis, is :mod:`bearingsim.dynamics.ias.spall`).
"""

from .benchmark import cepstral_prewhitening, discrete_random_separation
from .diagnosis import (
    BandSelection,
    Diagnosis,
    DiagnosisRule,
    analyze_record,
    diagnose,
    load_signal,
)
from .envelope import EnvelopeKind, check_band, envelope, envelope_spectrum
from .fused import FusedDiagnosis, diagnose_fused
from .kurtogram import Kurtogram, fast_kurtogram, kurtogram_levels
from .order import (
    AngleSignal,
    Interpolation,
    ShaftSignalKind,
    angle_from_speed,
    order_spectrum,
    read_shaft_signal,
    resample_to_angle,
    speed_from_angle,
    synchronous_average,
)
from .peaks import Peak, SpectralPeak, match_peaks, refine_peak, spectrum_peaks, strongest_peak
from .spectrum import Domain, Spectrum, amplitude_spectrum

__all__ = [
    "BandSelection",
    "AngleSignal",
    "Diagnosis",
    "DiagnosisRule",
    "FusedDiagnosis",
    "Domain",
    "EnvelopeKind",
    "Interpolation",
    "Kurtogram",
    "Peak",
    "ShaftSignalKind",
    "SpectralPeak",
    "Spectrum",
    "amplitude_spectrum",
    "analyze_record",
    "angle_from_speed",
    "cepstral_prewhitening",
    "check_band",
    "diagnose",
    "diagnose_fused",
    "discrete_random_separation",
    "envelope",
    "envelope_spectrum",
    "fast_kurtogram",
    "kurtogram_levels",
    "load_signal",
    "match_peaks",
    "order_spectrum",
    "read_shaft_signal",
    "refine_peak",
    "resample_to_angle",
    "speed_from_angle",
    "spectrum_peaks",
    "strongest_peak",
    "synchronous_average",
]
