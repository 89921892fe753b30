"""The contact angle a bearing runs at, read from a measured record's own lines.

A contact angle ``alpha`` moves the outer-race line up and the inner-race line down
(``BPFO = Z f_s/2 (1 - d cos(alpha)/D)``, ``BPFI = Z f_s/2 (1 + d cos(alpha)/D)``,
:func:`bearingsim.geometry.characteristic_frequencies`); a deep-groove bearing under a pure
radial load runs at ``alpha`` near 0, under an axial load (a wave spring, a fit, a thrust) at
several degrees, and then *every* ball is loaded. The shaft speed stored with a record is
rounded and may be off; so both are measured here from the record itself:

1. the shaft speed ``f_s``: the median of ``f_k / k`` over the shaft harmonics ``k = 1..6``
   of the amplitude spectrum (zero-padded 4×, parabolic refinement,
   :func:`.peaks.refine_peak`) that stand at least ``min_shaft_snr_db`` over their
   neighbourhood — an average over many lines, robust to one line of another source;
2. the fault line: the strongest (by SNR) of the family's first three harmonics in the squared
   envelope spectrum of the raw signal, searched between the orders of ``alpha = 0`` and
   :data:`ALPHA_SEARCH_MAX` (only the direction a contact angle moves it) widened by
   ``pad_rel``; a harmonic whose window meets a window of the other race's first three
   harmonics is not used (the 6205's 3×BPFO and 2×BPFI lie 0.7 % apart);
3. ``alpha`` from that order (:func:`bearingsim.geometry.contact_angle_from_order`);
4. its resolution: the angle that a line off its rate by three standard deviations of a
   random slip's wander reads (:func:`slip_resolution`). Random slip (:data:`SLIP_ASSUMED`,
   1.5 %) makes the ball passes a random walk, so the mean rate over ``N`` passes is off by
   ``slip sqrt(1.2 / N)`` (one standard deviation of the least-squares slope of a Brownian
   phase over the record, ``sqrt(6/5)`` of the end-point estimate's). The line's peak scatters
   1.2–1.4 times that (30 VSM simulations at ``alpha = 0`` through ``cwru-de-12k`` for each
   of 1, 2 and 4 s: the phase decorrelates within a record, more so at the higher harmonics),
   so three of the slope's standard deviations are about 2.2–2.5 of the peak's. An estimate
   below the resolution is not told from 0 (twenty-first session).

Used for ``docs/validation.md`` ("Contact angle of the CWRU bearings", `python
scripts/contact_angles.py`): what the fault-line offsets of the CWRU records mean.
"""

from __future__ import annotations

import math
from collections.abc import Collection
from dataclasses import asdict, dataclass, replace
from fractions import Fraction

import numpy as np
from numpy.typing import ArrayLike
from scipy import fft as sp_fft
from scipy.fft import next_fast_len

from ..errors import ConfigError, check_positive
from ..geometry import Bearing, characteristic_frequencies, contact_angle_from_order
from .peaks import refine_peak
from .spectrum import Spectrum, amplitude_spectrum

__all__ = [
    "ALPHA_SEARCH_MAX",
    "SLIP_ASSUMED",
    "ContactAngleEstimate",
    "check_speed_given",
    "estimate_contact_angle",
    "hz_given_as_rpm",
    "hz_hint",
    "hz_warning",
    "rpm_column_text",
    "measured_shaft_hz",
    "padded_spectrum",
    "refuted_speed",
    "SpeedComb",
    "shaft_speed_comb",
    "slip_resolution",
]

#: random slip the resolution assumes: the middle of the 1–2 % that real bearings show
#: (Randall & Antoni 2011), the rigs' realistic default [-]
SLIP_ASSUMED = 0.015

#: standard deviations of the slip's wander that the resolution spans [-] (module docstring)
RESOLUTION_SIGMAS = 3.0

#: largest contact angle the fault-line search reaches [rad] (25°: beyond it a deep-groove
#: bearing's contact ellipse nears the groove shoulder, Harris & Kotzalas 2007)
ALPHA_SEARCH_MAX = math.radians(25.0)
_PAD = 4  #: zero padding of the spectra [-]


def _analytic(x: np.ndarray) -> np.ndarray:
    """The analytic signal of ``x``: its spectrum, zero padded to a fast FFT length ``m`` (a
    CWRU record's length has a large prime factor, 2-3x slower), one-sided and doubled, back
    in time and cut to ``x``'s length (SciPy's ``hilbert`` at length ``m``, written out with
    :mod:`scipy.fft`: ``analyze`` does not import :mod:`scipy.signal`, whose import takes
    about a second). Every number of docs/validation.md "Contact angle of the CWRU bearings"
    is the same at its printed precision as with ``hilbert`` at the record's own length."""
    n = x.size
    m = next_fast_len(n)
    X = sp_fft.fft(x, m)
    h = np.zeros(m, dtype=X.dtype)
    if m % 2 == 0:
        h[0] = h[m // 2] = 1
        h[1 : m // 2] = 2
    else:
        h[0] = 1
        h[1 : (m + 1) // 2] = 2
    return sp_fft.ifft(X * h)[:n]


def _line(f, A, lo: float, hi: float, df: float) -> tuple[float, float]:
    """Refined frequency [Hz] and SNR [dB] of the largest line in ``[lo, hi]`` [Hz]; the floor
    is the median amplitude within ±5 % of it outside the search window."""
    i0 = int(np.searchsorted(f, lo, side="left"))
    i1 = int(np.searchsorted(f, hi, side="right"))
    if i1 <= i0 or i1 >= f.size:
        return float("nan"), float("nan")
    k = int(i0 + np.argmax(A[i0:i1]))
    off, _h = refine_peak(A, k, log=True)
    fc = 0.5 * (lo + hi)
    j0 = int(np.searchsorted(f, 0.95 * fc - 0.5 * (hi - lo), side="left"))
    j1 = int(np.searchsorted(f, 1.05 * fc + 0.5 * (hi - lo), side="right"))
    floor = np.median(np.concatenate((A[max(j0, 1) : i0], A[i1:j1])))
    snr = 20.0 * math.log10(A[k] / floor) if floor > 0 and A[k] > 0 else float("nan")
    return float(f[k] + off * df), snr


def measured_shaft_hz(
    x: ArrayLike,
    fs: float,
    shaft_hz_hint: float,
    *,
    harmonics: int = 6,
    rel_tol: float = 0.005,
    min_snr_db: float = 20.0,
    min_lines: int = 3,
    spectrum: Spectrum | None = None,
) -> tuple[float, int]:
    """Shaft speed measured from the shaft harmonics of a record (module docstring, step 1).

    Parameters
    ----------
    x : array_like
        Signal (any unit).
    fs : float
        Sample rate [Hz].
    shaft_hz_hint : float
        Expected shaft speed (e.g. the stored one) [Hz]; each harmonic ``k`` is searched within
        ``k shaft_hz_hint (1 ± rel_tol)``.
    harmonics : int
        Highest harmonic used [-].
    rel_tol : float
        Relative half-width of the search windows [-].
    min_snr_db : float
        A harmonic counts when it stands this far over its neighbourhood [dB].
    min_lines : int
        Harmonics that must count [-]: one line of another source within a window must not set
        the speed (every CWRU record the estimate reads shows 5 or 6).
    spectrum : Spectrum, optional
        ``x``'s amplitude spectrum zero padded 4× (:func:`padded_spectrum`), when the caller
        has it already.

    Returns
    -------
    shaft_hz : float
        Median of ``f_k / k`` over the harmonics that count [Hz].
    n_lines : int
        How many counted.

    Raises
    ------
    ConfigError
        No shaft harmonic stands out (the speed cannot be measured from this record).
    """
    fs = check_positive("fs_hz", fs, "Hz")
    hint = check_positive("shaft_hz_hint", shaft_hz_hint, "Hz")
    spec = spectrum if spectrum is not None else padded_spectrum(x, fs)
    f, A, df = spec.freq, spec.amplitude, spec.bin_width
    est = []
    for k in range(1, harmonics + 1):
        fk, snr = _line(f, A, k * hint * (1 - rel_tol), k * hint * (1 + rel_tol), df)
        if math.isfinite(snr) and snr >= min_snr_db:
            est.append(fk / k)
    if len(est) < min_lines:
        raise ConfigError(
            f"{len(est)} shaft harmonic(s) of {hint:.6g} Hz (k = 1..{harmonics}, within "
            f"±{rel_tol:.2%}) stand {min_snr_db:g} dB over their neighbourhood, fewer than "
            f"{min_lines}: the shaft speed cannot be measured here"
        )
    return float(np.median(est)), len(est)


@dataclass(frozen=True)
class SpeedComb:
    """What :func:`shaft_speed_comb` read from a record.

    Attributes
    ----------
    shaft_hz : float
        Speed whose harmonic comb stands highest [Hz].
    prominence_db : float
        Mean level of its harmonics over their neighbourhood's median, minus the median of that
        mean over all speeds searched [dB]: how far the comb stands out.
    gain_db : float
        Its mean level minus the best within ±0.5 % of the speed given [dB].
    between : int
        1, or ``p`` where the comb is of the harmonics that are not multiples of ``p``: the
        lines a speed ``p/q`` times the record's lacks (:func:`refuted_speed`) [-].
    """

    shaft_hz: float
    prominence_db: float
    gain_db: float
    between: int = 1


def padded_spectrum(x: ArrayLike, fs: float) -> Spectrum:
    """The amplitude spectrum of ``x`` sampled at ``fs`` [Hz], zero padded 4× to a fast FFT
    length (what :func:`measured_shaft_hz` and :func:`shaft_speed_comb` read)."""
    xa = np.asarray(x, dtype=float)
    return amplitude_spectrum(xa, fs, n_fft=next_fast_len(_PAD * xa.size))


def shaft_speed_comb(
    x: ArrayLike,
    fs: float,
    shaft_hz_hint: float,
    *,
    rel_tol: float = 0.05,
    harmonics: int = 10,
    spectrum: Spectrum | None = None,
    skip_multiples_of: int | None = None,
    skip_harmonics: Collection[int] = (),
    at_hz: float | None = None,
) -> SpeedComb | None:
    """The shaft speed within ``shaft_hz_hint (1 ± rel_tol)`` [Hz] whose first ``harmonics``
    harmonics stand highest on average in the record's amplitude spectrum (zero-padded 4×;
    each harmonic's level in dB over the median within ±10 % of it, the largest line within
    two padded bins taken): a comb of ten lines, which one fault line near a shaft harmonic (the
    6203's BPFO at 3.05 orders) cannot carry, unlike the three-line search of
    :func:`measured_shaft_hz`. On the 34 CWRU records of ``../shared/data/cwru`` it lies
    within 0.25 % of the stored speed and 14.9-32.7 dB out (174, without shaft lines, 0.8 dB;
    a helper's measurement, twenty-sixth session: "20-39 dB" before held for 26 of them).
    Returns None when fewer than three harmonics lie below the Nyquist frequency.
    ``spectrum``: :func:`padded_spectrum` of ``x`` when the caller has it already.
    ``skip_multiples_of``: leave out the harmonics that are multiples of this integer (the
    lines a speed that many times higher shares with this one; :func:`refuted_speed`).
    ``skip_harmonics``: harmonic numbers left out too (those on supply lines,
    :func:`supply_harmonics`). ``at_hz``: report the comb at this speed [Hz] (the best
    within 0.1 % of it) instead of the best one, scored against the same search.
    """
    fs = check_positive("fs_hz", fs, "Hz")
    f0 = check_positive("shaft_hz_hint", shaft_hz_hint, "Hz")
    spec = spectrum if spectrum is not None else padded_spectrum(x, fs)
    df = spec.bin_width
    level = 20.0 * np.log10(np.maximum(spec.amplitude, 1e-300))
    peak = level.copy()  # the largest line within two padded bins
    for sh in range(1, 5):
        peak[sh:] = np.maximum(peak[sh:], level[:-sh])
        peak[:-sh] = np.maximum(peak[:-sh], level[sh:])
    k = np.arange(1, harmonics + 1)
    if skip_multiples_of is not None:
        k = k[k % skip_multiples_of != 0]
    k = k[~np.isin(k, list(skip_harmonics))]
    k = k[k * f0 * (1.0 + rel_tol) * 1.1 < spec.freq[-1]]
    if k.size < 3:
        return None
    floors = np.array(
        [np.median(level[int(h * f0 * 0.9 / df) : int(h * f0 * 1.1 / df) + 1]) for h in k]
    )
    grid = np.arange(f0 * (1.0 - rel_tol), f0 * (1.0 + rel_tol), df / k[-1])
    idx = np.rint(np.outer(grid, k) / df).astype(int)
    score = np.mean(peak[idx] - floors, axis=1)
    if at_hz is None:
        j = int(np.argmax(score))
    else:  # the best within 0.1 % of at_hz (the grid point nearest it if none)
        there = np.abs(grid / at_hz - 1.0) <= 0.001
        if not there.any():
            there = np.abs(grid - at_hz) == np.min(np.abs(grid - at_hz))
        j = int(np.flatnonzero(there)[np.argmax(score[there])])
    near = np.abs(grid / f0 - 1.0) <= 0.005
    if not near.any():  # a grid coarser than ±0.5 % (few shaft turns): the point nearest f0
        # (exploratory testing, twenty-sixth session: rig identify --rpm 29.95 on a 1.3 s
        # record raised from np.max of an empty array)
        near = np.abs(grid - f0) == np.min(np.abs(grid - f0))
    return SpeedComb(
        float(grid[j]),
        float(score[j] - np.median(score)),
        float(score[j] - np.max(score[near])),
    )


#: how far the harmonic comb of another speed must stand out (:func:`refuted_speed`) [dB]:
#: over the combs of all speeds searched (the 34 shared records' own combs stand 14.9-32.7 dB
#: out, 26 of them 20 or more; 174 0.8); over the comb at the speed given, ten times
#: in power. On a quarter of a record a fault comb can pass for a shaft comb (313's quarters,
#: 6203 outer race: BPFO = 3.05 f_r, a comb at BPFO/3 standing 12-14 dB out and 4-7 dB over
#: the true speed's); these values, chosen on the shared records and the wrong speeds tried on
#: them (132 at 1797 and 1700 r/min, 172 at 1797: 21-25 dB out, 10-23 dB over), refute no piece
#: of a shared record at its stored speed (whole, halves, quarters)
COMB_PROMINENCE_DB = 20.0
COMB_GAIN_DB = 10.0

#: how far from the speed given :func:`refuted_speed` searches the record's own shaft comb
#: [-]. Twenty-seventh session: ±5 % left a record without a stated speed judged only that
#: near (a CSV of record 107 at 2000 r/min, 11 % off, read "ball"). On the 34 shared records
#: (whole, halves, quarters) at their stored speeds the best comb within ±15 % that lies over
#: 1 % away stands at most 19.4 dB out and 7.0 dB over the true speed's (313's quarters: a
#: fault comb at 1.02 f_r); wrong speeds of 0.88-1.14 times theirs are refuted on 22-31 of the
#: 34 (not on 174, without shaft lines, nor where the shaft comb stands 14-20 dB out: 187,
#: 188, 199, 200, 288, 289; less often on the 1796 r/min records, whose supply-line rule
#: leaves them four harmonics). Wider is worse: within ±25 % a speed 1.3 times 132's was put
#: at 1.6 times it (a comb of 8/5 standing 22 dB out), and 6/5 shares every fifth harmonic
COMB_SEARCH_REL = 0.15


def refuted_speed(
    x: ArrayLike | None,
    fs: float,
    shaft_hz: float,
    *,
    tol_rel: float = 0.01,
    spectrum: Spectrum | None = None,
    stated_hz: float | None = None,
) -> SpeedComb | None:
    """The record's own speed when its shaft harmonics refute ``shaft_hz`` [Hz]: the comb of
    ten harmonics that stands highest within ±:data:`COMB_SEARCH_REL` (15 %;
    :func:`shaft_speed_comb`) lies more than
    ``tol_rel`` [-] away (the fault-line search's tolerance), stands
    :data:`COMB_PROMINENCE_DB` out and :data:`COMB_GAIN_DB` over the comb at the speed given.
    Or, where the file states a speed ``stated_hz`` [Hz] more than ``tol_rel`` from
    ``shaft_hz`` (a CWRU record's ``X###RPM`` that an option overrides), the comb found
    within 1 % of it stands :data:`COMB_PROMINENCE_DB` out and :data:`COMB_GAIN_DB` more than
    the one at the speed given (checked first: a speed far from the stated one lies outside
    the search, and 107 at 3000 r/min was said to run at 3147, a comb of its harmonics'
    multiples; exploratory testing, twenty-sixth session, 107 at 1000-2500 passed). A comb with
    harmonics on 50/60 Hz multiples (:func:`supply_harmonics`) must refute without them; where
    it does not, the best comb of the spectrum with the supply lines taken out is judged. Else
    None (also where the record has no shaft lines). ``spectrum``: the record's
    :func:`padded_spectrum` when the caller has it."""
    spec = spectrum if spectrum is not None else padded_spectrum(x, fs)
    if stated_hz is not None and abs(stated_hz / shaft_hz - 1.0) > tol_rel:
        s = _speed_against(spec, fs, shaft_hz, stated_hz, tol_rel, STATED_COMB_DB)
        if s is not None:
            return s
    c = _comb_refutes(spec, fs, shaft_hz, tol_rel)
    if c is None:  # supply lines may lift the comb at the speed given: judged without them
        # (the spectrum's supply lines taken out, and the given speed's harmonics on them)
        quiet = _without_supply(spec, COMB_SEARCH_REL, shaft_hz)
        c = _comb_refutes(quiet, fs, shaft_hz, tol_rel, supply_harmonics(shaft_hz))
    return c


def _comb_refutes(
    spec: Spectrum, fs: float, shaft_hz: float, tol_rel: float, skip: tuple[int, ...] = ()
) -> SpeedComb | None:
    """The best comb within ±:data:`COMB_SEARCH_REL` of ``shaft_hz`` [Hz] on ``spec`` (its
    harmonics ``skip`` left out) when it refutes that speed (:func:`_refutes`), also without
    its own harmonics on supply lines (:func:`supply_harmonics`); else None."""
    c = _best_comb(spec, fs, shaft_hz, skip)
    if not _refutes(c, shaft_hz, tol_rel):
        return None
    # it must stand out without its harmonics on the supply's lines
    return c if _refutes(_off_supply(spec, fs, shaft_hz, c, skip), shaft_hz, tol_rel) else None


def _best_comb(
    spec: Spectrum, fs: float, shaft_hz: float, skip: tuple[int, ...] = ()
) -> SpeedComb | None:
    """The best comb within ±:data:`COMB_SEARCH_REL` of ``shaft_hz`` [Hz] on ``spec``, its
    harmonics ``skip`` left out (:func:`shaft_speed_comb`)."""
    return shaft_speed_comb(
        None, fs, shaft_hz, spectrum=spec, rel_tol=COMB_SEARCH_REL, skip_harmonics=skip
    )


def _off_supply(
    spec: Spectrum, fs: float, shaft_hz: float, c: SpeedComb | None, skip: tuple[int, ...] = ()
) -> SpeedComb | None:
    """The comb ``c`` (of :func:`_best_comb` with ``skip``) scored again without its
    harmonics on supply lines (:func:`supply_harmonics`), at its own speed; ``c`` itself when
    none lies on them (or ``c`` is None)."""
    on_supply = () if c is None else supply_harmonics(c.shaft_hz)
    if not on_supply:
        return c
    return shaft_speed_comb(
        None,
        fs,
        shaft_hz,
        spectrum=spec,
        rel_tol=COMB_SEARCH_REL,
        skip_harmonics=set(on_supply) | set(skip),
        at_hz=c.shaft_hz,
    )


def unchecked_speed_note(
    x: ArrayLike | None, fs: float, shaft_hz: float, *, spectrum: Spectrum | None = None
) -> str | None:
    """A note where a record's shaft harmonics cannot judge the speed given ``shaft_hz`` [Hz]:
    the best comb within ±:data:`COMB_SEARCH_REL` stands less than :data:`COMB_PROMINENCE_DB`
    out, so :func:`refuted_speed` neither confirms nor refutes it; else None. Exploratory
    testing, twenty-seventh session: a 2 s piece of record 172 at ``--rpm 1780`` (+3 %) read
    "ball" at 0.76 without a word, its comb 15 dB out. ``spectrum``: the record's
    :func:`padded_spectrum` when the caller has it."""
    spec = spectrum if spectrum is not None else padded_spectrum(x, fs)
    # a comb resting on supply lines judges nothing (exploratory testing, twenty-seventh
    # session: 1 m/s² of 60 Hz lines took the note away from the 2 s piece of 172)
    c = _off_supply(spec, fs, shaft_hz, _best_comb(spec, fs, shaft_hz))
    return _unchecked(c, f"the speed given ({60.0 * shaft_hz:.6g} r/min)", "the record", "it")


def unchecked_order_note(spec: Spectrum, fs: float, speed_from: str = "the speed") -> str | None:
    """:func:`unchecked_speed_note` of an order-tracked record's :func:`padded_spectrum`
    ``spec`` (``fs`` samples per revolution): a note where no shaft comb near order 1 stands
    :data:`COMB_PROMINENCE_DB` out, so the speed it was tracked with (``speed_from``, e.g.
    "the speed column") is neither confirmed nor refuted; else None."""
    c = _best_comb(spec, fs, 1.0)
    return _unchecked(c, speed_from, "the order-tracked record", "order 1")


def _unchecked(c: SpeedComb | None, what: str, record: str, near: str) -> str | None:
    """The "not checked" note of :func:`unchecked_speed_note` and :func:`unchecked_order_note`
    for the best comb ``c``; None where it stands :data:`COMB_PROMINENCE_DB` out."""
    if c is not None and c.prominence_db >= COMB_PROMINENCE_DB:
        return None
    level = "no shaft comb" if c is None else f"a shaft comb only {c.prominence_db:.1f} dB out"
    return (
        f"{what} is not checked: {record} has {level} near {near} "
        f"({COMB_PROMINENCE_DB:.0f} dB needed); a wrong speed reads wrong lines"
    )


def _without_supply(spec: Spectrum, rel_tol: float, shaft_hz: float) -> Spectrum:
    """``spec`` with the lines within :data:`SUPPLY_REL` of the 50 and 60 Hz multiples that a
    comb of ten harmonics within ``rel_tol`` of ``shaft_hz`` [Hz] reaches set to the median
    amplitude within ±5 % of them."""
    amp = spec.amplitude.copy()
    df = spec.bin_width
    top = min(10.0 * shaft_hz * (1.0 + rel_tol) * 1.15, float(spec.freq[-1]) / 1.05)
    for b in SUPPLY_HZ:
        for m in range(1, int(top / b) + 1):
            f = m * b
            lo, hi = int(f * (1.0 - SUPPLY_REL) / df), int(f * (1.0 + SUPPLY_REL) / df) + 1
            wlo, whi = int(f * 0.95 / df), int(f * 1.05 / df) + 1
            amp[lo:hi] = np.median(spec.amplitude[wlo:whi])
    return replace(spec, amplitude=amp)


def _refutes(c: SpeedComb | None, shaft_hz: float, tol_rel: float) -> bool:
    return (
        c is not None
        and abs(c.shaft_hz / shaft_hz - 1.0) > tol_rel
        and c.prominence_db >= COMB_PROMINENCE_DB
        and c.gain_db >= COMB_GAIN_DB
    )


#: mains frequencies whose harmonics a motor-driven machine's records carry [Hz]
SUPPLY_HZ = (50.0, 60.0)
#: how near a supply harmonic a shaft harmonic is taken to lie on it [-]: the supply's own
#: ±0.2 % (grid frequency), the comb's tolerance and a strong line's skirt (0.5 % let a comb
#: at 1809 r/min, 0.51 % off the 60 Hz multiples, take 3 m/s² mains lines for a shaft's;
#: exploratory testing, twenty-seventh session)
SUPPLY_REL = 0.01


def supply_harmonics(shaft_hz: float, harmonics: int = 10) -> tuple[int, ...]:
    """The harmonic numbers ``k`` (1..``harmonics``) of a shaft speed ``shaft_hz`` [Hz] whose
    frequency lies within :data:`SUPPLY_REL` of a multiple of 50 or 60 Hz: a comb at 30 Hz
    (1800 r/min) has its even harmonics on 60 Hz mains lines. Twenty-seventh session
    (exploratory testing): record 132 (1750 r/min) with 60-300 Hz supply lines of 0.72 m/s²
    added was refuted at its own speed, "put at 1800.24 r/min"; a speed the record's comb
    refutes must now stand out without these harmonics (:func:`refuted_speed`)."""
    out = []
    for k in range(1, harmonics + 1):
        f = k * shaft_hz
        lines = [max(round(f / b), 1) * b for b in SUPPLY_HZ]  # the nearest supply lines
        if any(abs(f - line) <= SUPPLY_REL * f for line in lines):
            out.append(k)
    return tuple(out)


def _speed_against(
    spec: Spectrum, fs: float, shaft_hz: float, ref_hz: float, tol_rel: float, level_db: float
) -> SpeedComb | None:
    """The comb at ``ref_hz`` [Hz] (a file's stated speed, or a hypothesis) when it refutes
    the speed given ``shaft_hz`` [Hz] (:func:`refuted_speed`), standing ``level_db`` [dB] out;
    else None."""
    # a speed p/q times the file's (p, q <= 3) shares the file's harmonics that are
    # multiples of p, and has its own lines at its harmonics not multiples of q: the file's
    # lines it lacks refute it (p >= 2), else its own lines are compared with the file's
    # (2x was refuted on none of the 34 records, and 197 at 3592 r/min read "inner"; 1.5x
    # left 188, 172, 198 and 312 a fault verdict; exploratory testing, twenty-sixth session)
    ratio = Fraction(shaft_hz / ref_hz).limit_denominator(3)
    p, q = ratio.numerator, ratio.denominator
    if ratio == 0 or abs(shaft_hz / (float(ratio) * ref_hz) - 1.0) > tol_rel:
        p = q = 1  # no small ratio: the two combs compared whole
    if p >= 2:
        s = shaft_speed_comb(None, fs, ref_hz, spectrum=spec, skip_multiples_of=p)
        if s is not None and abs(s.shaft_hz / ref_hz - 1.0) <= 0.01 and s.prominence_db >= level_db:
            return replace(s, between=p)
        return None
    own = shaft_speed_comb(  # the given speed's own comb, within ±5 %
        None, fs, shaft_hz, spectrum=spec, skip_multiples_of=q if q >= 2 else None
    )
    return _comb_over(spec, fs, ref_hz, own, level_db, COMB_GAIN_DB)


#: how far the comb at the speed a file states must stand out for :func:`refuted_speed` to
#: refute a speed given more than 1 % from it [dB] (and :data:`COMB_GAIN_DB` over the comb at
#: the speed given; for a multiple of the file's speed, the comb of the harmonics between its
#: lines). Lower than :data:`COMB_PROMINENCE_DB`: the file's statement is the stronger
#: prior. On the 34 shared records, whole, the comb at the stated speed stands 14.9-32.7 dB
#: out and its odd harmonics alone 15.7-33.8 (174, without shaft lines, 0.8 and 2.1); white
#: noise's best comb 2-3 dB. 20 dB left 8 records' wrong speeds unjudged (188 at 1690 r/min
#: read "ball"; exploratory testing, twenty-sixth session)
STATED_COMB_DB = 12.0


#: how far the comb at 60 times a speed given must stand out, and over the comb at the speed
#: given, for :func:`hz_given_as_rpm` to say the speed reads like its value in Hz [dB]. Lower
#: than :data:`COMB_PROMINENCE_DB`: a shaft comb on a 3 s piece of record 107 stands 15 dB
#: out (26.5 on the whole record), white noise's best comb 2-3 dB (40 draws), a comb at a
#: speed that is no shaft's up to 16 dB on the 34 shared records' 0.5-3 s pieces (fault
#: combs); so it warns and never refuses (a gearbox's output shaft may turn at 1/60 of a motor
#: whose comb the record holds)
HZ_COMB_DB = 10.0


def hz_given_as_rpm(
    x: ArrayLike | None,
    fs: float,
    shaft_hz: float,
    *,
    spectrum: Spectrum | None = None,
    factor: float = 60.0,
) -> SpeedComb | None:
    """The comb of ten harmonics within ±5 % of ``60 shaft_hz`` (:func:`shaft_speed_comb`)
    when it stands :data:`HZ_COMB_DB` out and as much over the comb at ``shaft_hz`` [Hz]
    itself, and lies within 1 % of ``60 shaft_hz``: the speed given reads like its value in
    Hz given as r/min (29.1 for 29.1 Hz, read as 0.485 Hz). Its ``gain_db`` is the difference
    of the two combs' prominences. Else None, also where fewer than five harmonics of
    ``60 shaft_hz`` lie below the Nyquist frequency (three until the twenty-eighth session: a
    helper's column of 1662 r/min on record 132 was said to read like Hz, its "comb" three
    lines at 1679, 3357 and 5036 Hz among the structure's resonances, and that note took the
    place of the column's "not checked" one). For a warning only (:data:`HZ_COMB_DB`).
    Twenty-sixth session: a ``--conditions`` row typed in Hz moved a model gain 250-fold,
    unwarned. ``factor`` 1/60: the reverse, a speed in r/min given as Hz (a ``speed_hz``
    column holding r/min)."""
    fs = check_positive("fs_hz", fs, "Hz")
    hz = factor * check_positive("shaft_hz", shaft_hz, "Hz")
    if 5.0 * hz * 1.05 * 1.1 >= fs / 2.0:  # half the comb of ten at least below Nyquist
        return None
    spec = spectrum if spectrum is not None else padded_spectrum(x, fs)
    given = shaft_speed_comb(None, fs, shaft_hz, spectrum=spec)
    return _comb_over(spec, fs, hz, given, HZ_COMB_DB, HZ_COMB_DB)


def _comb_over(
    spec: Spectrum,
    fs: float,
    target_hz: float,
    given: SpeedComb | None,
    level_db: float,
    over_db: float,
) -> SpeedComb | None:
    """The comb found within ±5 % of ``target_hz`` [Hz] (:func:`shaft_speed_comb` on
    ``spec``) when it lies within 1 % of it, stands ``level_db`` out and ``over_db`` [dB] over
    the comb at the speed given itself (``given``, that speed's search: its best less its gain
    over the best within ±0.5 %); its ``gain_db`` then that difference. Else None."""
    c = shaft_speed_comb(None, fs, target_hz, spectrum=spec)
    base = given.prominence_db - given.gain_db if given is not None else 0.0
    if (
        c is not None
        and abs(c.shaft_hz / target_hz - 1.0) <= 0.01
        and c.prominence_db >= level_db
        and c.prominence_db - base >= over_db
    ):
        return replace(c, gain_db=float(c.prominence_db - base))
    return None


def check_speed_given(
    x: ArrayLike, fs: float, shaft_hz: float, *, stated_hz: float | None = None
) -> tuple[SpeedComb | None, SpeedComb | None]:
    """``(refuted, in_hz)`` for a speed given ``shaft_hz`` [Hz] on one padded spectrum of
    ``x``: :func:`refuted_speed` (``stated_hz``: the speed the file states [Hz]) and, where
    that does not refute it, :func:`hz_given_as_rpm` (else None)."""
    spec = padded_spectrum(x, fs)
    c = refuted_speed(None, fs, shaft_hz, spectrum=spec, stated_hz=stated_hz)
    if c is not None:
        return c, None
    return None, hz_given_as_rpm(None, fs, shaft_hz, spectrum=spec)


def hz_hint(rpm: float, own_rpm: float) -> str:
    """``"; it reads like the speed in Hz"`` where the speed given ``rpm`` [r/min] is the
    record's own ``own_rpm`` [r/min] over 60 (within 2 %), else ``""``: for the messages that
    refuse or warn about a speed (29.1 typed for 1746 r/min)."""
    return "; it reads like the speed in Hz" if abs(60.0 * rpm / own_rpm - 1.0) <= 0.02 else ""


def rpm_column_text(rpm: float, comb: SpeedComb) -> str:
    """The text of a :func:`hz_given_as_rpm` finding with ``factor`` 1/60 for a speed column
    of median ``rpm`` [r/min] (its values r/min, its name read as Hz)."""
    return (
        f"the speed column (median {rpm:.6g} r/min) reads like the speed in r/min in a column "
        f"of Hz: the record's shaft comb stands at {comb.shaft_hz:.5g} Hz "
        f"({60.0 * comb.shaft_hz:.5g} r/min); name such a column rpm"
    )


def hz_warning(rpm: float, comb: SpeedComb, column: bool = False) -> str:
    """The text of a :func:`hz_given_as_rpm` finding for the speed given ``rpm`` [r/min]
    (``column``: the median of the record's speed column)."""
    what = f"the speed column (median {rpm:.6g} r/min)" if column else f"rpm = {rpm:.6g} r/min"
    return (
        f"{what} reads like the speed in Hz: the record has no shaft comb at "
        f"{rpm / 60.0:.4g} Hz but one at {comb.shaft_hz:.5g} Hz, {comb.gain_db:.0f} dB stronger "
        f"({60.0 * comb.shaft_hz:.5g} r/min); give the speed in r/min"
    )


@dataclass(frozen=True)
class ContactAngleEstimate:
    """What :func:`estimate_contact_angle` read from a record.

    Attributes
    ----------
    family : str
        ``"outer"`` (BPFO) or ``"inner"`` (BPFI).
    shaft_hz : float
        Shaft speed measured from the record [Hz].
    shaft_lines : int
        Shaft harmonics it rests on [-].
    harmonic : int
        Harmonic of the fault line used (1–3) [-].
    order : float
        Order of the fault line's fundamental against the measured speed [-].
    order_alpha0 : float
        Its order at ``alpha = 0`` [-].
    snr_db : float
        SNR of the line used in the squared envelope spectrum [dB].
    contact_angle_rad : float
        The contact angle that puts the line there [rad]; 0 for a line within the search
        window's padding on the far side of the ``alpha = 0`` order.
    resolution_rad : float
        The angle a 3-sigma wander of the line under :data:`SLIP_ASSUMED` random slip reads
        over this record (:func:`slip_resolution`) [rad]: an angle below it is not told from 0.
    """

    family: str
    shaft_hz: float
    shaft_lines: int
    harmonic: int
    order: float
    order_alpha0: float
    snr_db: float
    contact_angle_rad: float
    resolution_rad: float = float("nan")

    @property
    def contact_angle_deg(self) -> float:
        """The contact angle [deg]."""
        return math.degrees(self.contact_angle_rad)

    @property
    def resolution_deg(self) -> float:
        """The resolution [deg] (``resolution_rad``)."""
        return math.degrees(self.resolution_rad)

    def as_dict(self) -> dict[str, float | int | str]:
        """JSON-ready dict (the fields, ``contact_angle_deg`` and ``resolution_deg``)."""
        return {
            **asdict(self),
            "contact_angle_deg": self.contact_angle_deg,
            "resolution_deg": self.resolution_deg,
        }


def slip_resolution(
    bearing: Bearing, family: str, n_passes: float, slip: float = SLIP_ASSUMED
) -> float:
    """The contact angle [rad] that a race's fault line reads when its rate over ``n_passes``
    passes [-] is off by three standard deviations of a random slip's wander, ``3 slip
    sqrt(1.2 / n_passes)`` (module docstring, step 4), in the direction an angle moves it
    (BPFO up, BPFI down); ``pi/2`` when that wander reaches past the orders an angle gives.

    Parameters
    ----------
    bearing : Bearing
        Geometry.
    family : str
        ``"outer"`` or ``"inner"``.
    n_passes : float
        Passes of the line over the record (its frequency times the record's duration) [-].
    slip : float
        Standard deviation of the random slip, a share of the pass interval [-].
    """
    fam = str(family).lower()
    if fam not in ("outer", "inner"):
        raise ConfigError(f"family = {family!r} is not one of outer, inner")
    n = check_positive("n_passes", n_passes)
    rel = RESOLUTION_SIGMAS * float(slip) * math.sqrt(1.2 / n)
    line = "bpfo" if fam == "outer" else "bpfi"
    o0 = getattr(characteristic_frequencies(replace(bearing, contact_angle=0.0), 1.0), f"{line}_hz")
    try:
        return contact_angle_from_order(
            bearing, line, o0 * (1.0 + rel if fam == "outer" else 1.0 - rel)
        )
    except ConfigError:  # past the 90 deg order: the record tells no angle
        return 0.5 * math.pi


def estimate_contact_angle(
    x: ArrayLike,
    fs: float,
    bearing: Bearing,
    family: str,
    shaft_hz_hint: float,
    *,
    pad_rel: float = 0.003,
    measure_shaft: bool = True,
) -> ContactAngleEstimate:
    """Contact angle of a bearing with a race fault, from the record's own lines (module
    docstring).

    Parameters
    ----------
    x : array_like
        Signal of a record with an outer- or inner-race fault (any unit).
    fs : float
        Sample rate [Hz].
    bearing : BallBearing or RollerBearing
        The faulty bearing's geometry.
    family : str
        ``"outer"`` or ``"inner"``: the fault whose line is read.
    shaft_hz_hint : float
        Expected shaft speed [Hz] (:func:`measured_shaft_hz`).
    pad_rel : float
        Relative widening of the fault-line search window on both sides [-].
    measure_shaft : bool
        Measure the shaft speed from the record's shaft harmonics (step 1); False takes
        ``shaft_hz_hint`` as the speed (a simulation's, a tachometer's; ``shaft_lines`` 0).
    """
    fam = str(family).lower()
    if fam not in ("outer", "inner"):
        raise ConfigError(f"family = {family!r} is not one of outer, inner")
    fs = check_positive("fs_hz", fs, "Hz")
    xa = np.asarray(x, dtype=float)
    if measure_shaft:
        shaft, n_lines = measured_shaft_hz(xa, fs, shaft_hz_hint)
    else:
        shaft, n_lines = check_positive("shaft_hz_hint", shaft_hz_hint, "Hz"), 0
    # the orders (shaft_hz = 1) of both races' lines at alpha = 0 and at ALPHA_SEARCH_MAX
    k0 = characteristic_frequencies(replace(bearing, contact_angle=0.0), 1.0)
    k1 = characteristic_frequencies(replace(bearing, contact_angle=ALPHA_SEARCH_MAX), 1.0)

    def window(attr: str) -> tuple[float, float, float, float]:
        """alpha = 0 order, order at ALPHA_SEARCH_MAX, and the padded search window [-]."""
        a, b = getattr(k0, attr), getattr(k1, attr)
        return a, b, min(a, b) * (1.0 - pad_rel), max(a, b) * (1.0 + pad_rel)

    own, other = ("bpfo_hz", "bpfi_hz") if fam == "outer" else ("bpfi_hz", "bpfo_hz")
    o0, o1, lo, hi = window(own)
    _a, _b, lo_x, hi_x = window(other)  # the other race's line
    # a harmonic whose window meets one of the other race's first three (the 6205's 3xBPFO
    # and 2xBPFI, 0.7 % apart) could read the other fault's line: not used
    usable = [
        h for h in (1, 2, 3)
        if not any(h * lo <= k * hi_x and k * lo_x <= h * hi for k in (1, 2, 3))
    ]  # fmt: skip
    xa = xa - xa.mean()
    se = np.abs(_analytic(xa)) ** 2
    spec = amplitude_spectrum(se, fs, n_fft=next_fast_len(_PAD * xa.size))
    f, A, df = spec.freq, spec.amplitude, spec.bin_width
    best = (float("nan"), float("-inf"), 0)
    for h in usable:
        fh, snr = _line(f, A, h * lo * shaft, h * hi * shaft, df)
        if math.isfinite(snr) and snr > best[1]:
            best = (fh / (h * shaft), snr, h)
    order, snr, h = best
    if h == 0:
        raise ConfigError(f"no {fam}-race line within the spectrum (fs_hz = {fs:g} Hz)")
    # a line within the window's padding on the far side of the alpha = 0 order (measurement
    # precision, a slightly low speed estimate) reads alpha = 0
    order_c = min(max(order, min(o0, o1)), max(o0, o1))
    alpha = contact_angle_from_order(bearing, "bpfo" if fam == "outer" else "bpfi", order_c)
    res = slip_resolution(bearing, fam, o0 * shaft * xa.size / fs)
    return ContactAngleEstimate(fam, shaft, n_lines, h, order, o0, snr, alpha, res)
