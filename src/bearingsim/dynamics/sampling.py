"""From the model's internal rate to the output rate: the anti-aliasing filter of a
data-acquisition chain.

A model's acceleration has content far above any output Nyquist frequency: a ball meeting a
defect edge changes the contact force within microseconds. Sampled at the output rate, that
content folds back; for an impact train it folds back *differently for every impact*, because
the impacts fall at a different fraction of the sample interval each time, and the envelope
spectrum gets a line at ``f_fault * distance of fs / f_fault from the nearest integer`` (VSM
outer race, 1797 r/min, 12 kHz: 24.8 Hz at -24 dB re BPFO with the boxcar mean alone; the
ring models' default output, kept for the seed comparisons). A recorder prevents that with an
analogue low-pass before its converter. :func:`decimate_antialias` is that filter: a
linear-phase FIR (Kaiser window, Kaiser 1974) whose pass band ends at :data:`PASS` of the
output Nyquist frequency and whose stop band, :data:`STOP_DB` down, starts at it, applied by
:func:`scipy.signal.resample_poly` (delay compensated, so zero phase). The same case then has
its line at -71 dB (``tests/test_sampling.py``). :func:`scipy.signal.decimate`'s default FIR
puts its cut-off *at* the new Nyquist frequency (its transition band straddles it): -38 dB.
"""

from __future__ import annotations

import numpy as np
from numpy.typing import NDArray

__all__ = ["PASS", "STOP_DB", "decimate_antialias", "oversampling_for"]

#: end of the pass band, as a fraction of the output Nyquist frequency [-]
PASS = 0.9
#: stop-band attenuation from the output Nyquist frequency up [dB]
STOP_DB = 80.0


def oversampling_for(fs: float) -> int:
    """Internal samples per output sample for an output rate ``fs`` [Hz]: 4, or 2 above
    24 kHz (the rotor model's rule) [-]."""
    return 4 if fs <= 24000.0 else 2


def fir_taps(q: int) -> NDArray[np.float64]:
    """The anti-aliasing FIR of a decimation by ``q`` (module docstring): odd length, unit gain
    at 0 Hz [-]."""
    from scipy.signal import firwin, kaiserord

    n, beta = kaiserord(STOP_DB, (1.0 - PASS) / q)
    return firwin(n | 1, 0.5 * (1.0 + PASS) / q, window=("kaiser", beta))


def decimate_antialias(x: NDArray[np.float64], q: int, axis: int = 0) -> NDArray[np.float64]:
    """Every ``q``-th sample of ``x`` after the anti-aliasing low-pass (module docstring):
    ``ceil(len / q)`` samples along ``axis``, sample ``k`` at the time of input sample ``k q``
    (zero phase) [unit of ``x``].

    Each end is continued by the signal's point reflection about its end sample (``2 x_0 -
    x_k``: the value and slope kept), so the first samples depend on the record's start only.
    Until the twenty-second session the ends were padded by the line through the first and
    last samples, which made the first ~50 output samples depend on the record's length. The
    last samples are the filter's with that continuation in place of the signal that would
    follow, as at the end of any zero-phase filtered record."""
    from scipy.signal import resample_poly

    if q == 1:
        return np.asarray(x, dtype=float)
    return resample_poly(x, 1, q, axis=axis, window=fir_taps(q), padtype="antireflect")
