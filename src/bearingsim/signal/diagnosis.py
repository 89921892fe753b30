"""Envelope-analysis diagnosis of a rolling-bearing vibration signal, and loading a record to
diagnose (:func:`load_signal`, over :func:`bearingsim.io.read_signal`).

One fixed rule (:class:`DiagnosisRule`), the same for every signal (measured or simulated):

1. **Band.** The band is given or chosen by the fast kurtogram (:func:`.kurtogram.fast_kurtogram`)
   among bands at least ``3 f_max + f_r`` wide (``f_max`` the largest of BPFO, BPFI, 2×BSF), so
   that the envelope keeps the first three harmonics and the shaft sidebands.
2. **Envelope spectrum** of that band (:func:`.envelope.envelope_spectrum`).
3. **Lines** (:func:`find_lines`). The fundamentals of BPFO (outer), BPFI (inner), 2×BSF (ball),
   FTF (cage) and f_r (shaft) are searched within ``max(1 % of the target, 2 bins)`` (1 %:
   allowance for the speed uncertainty and the 1–2 % slip of rolling elements, Randall & Antoni
   2011), BPFO, FTF and BPFI of a ball bearing from their positions at its catalogue contact
   angle to those at ``DiagnosisRule.contact_angle_max_deg`` (20°: an axial load moves BPFO and
   FTF up and BPFI down), that range widened by the same 1 %; harmonics 2 and 3 at exact
   multiples of the *found* fundamental within ``max(2, h)`` bins; sidebands ±f_r of BPFO and
   BPFI and ±FTF of 2×BSF (first two harmonics). Each line's SNR is taken against the median
   amplitude within ±10 % of the target (at least five tolerances), without the tolerance band.
   A line is *detected* at SNR >= 12 dB: for Gaussian noise the envelope-spectrum amplitudes are
   Rayleigh distributed and the largest of ~30–200 bins in a tolerance window exceeds 12 dB
   above the median with probability ~1e-3. A line claimed by targets of two families counts
   only for the nearer target (e.g. 3×BPFO and 2×BPFI differ by 0.7 %).
4. **Decision** (:func:`diagnose`). A family (outer, inner, ball) is *supported* when its
   fundamental and at least one of its 2nd/3rd harmonics are detected; its *evidence* is the
   summed envelope amplitude of its detected harmonics, its *quality* the mean over the three
   harmonics of ``0.5 + 0.5 clip((SNR - 12 dB)/20 dB, 0, 1)`` (0 when not detected) plus 0.1 per
   detected sideband (BPFI ± f_r, 2×BSF ± FTF), capped at 1.

   * the supported family with the largest evidence, if that evidence is at least twice every
     other family's → that fault, ``confidence = quality × (1 − runner-up evidence / evidence)``.
     A rival's line that lies on a modulation sideband of the leading family (``h F ± m f_r``
     of an inner-race fault, ``h 2BSF ± m FTF`` of a ball fault, ``m`` up to
     :data:`MAX_SIDEBAND_ORDER`) is the leading family's own and not counted in the rival's
     evidence (twenty-fourth session: on the 6203, 2 and 3 × 2×BSF lie 0.3 Hz from BPFI + 3 f_r
     and 2 BPFI + 2 f_r);
   * otherwise (another family's lines are comparable) → ``"uncertain"`` (confidence 0);
   * no supported family and no detected fault line → ``"none"``, ``confidence =
     clip((12 dB − strongest fault-line SNR) / 10 dB, 0, 1)``;
   * no supported family but isolated fault lines → ``"uncertain"`` (confidence 0);
   * a record too short to resolve the lines (resolution > f_r/4) → ``"uncertain"``.

The rule never looks at the file name or the expected answer.
"""

from __future__ import annotations

import enum
import math
from dataclasses import dataclass, field, replace
from pathlib import Path
from typing import Any

import numpy as np
from numpy.typing import NDArray

from ..errors import ConfigError, check_positive
from ..geometry import BallBearing, Bearing, characteristic_frequencies, parse_enum
from ..io.signal import SignalRecord, column_speed_refutes, read_signal, speed_span_text
from .envelope import check_band, envelope_spectrum
from .kurtogram import Kurtogram, fast_kurtogram
from .order import Interpolation, angle_from_speed, resample_to_angle
from .peaks import Peak, match_peaks
from .spectrum import MIN_SAMPLES, Domain, Spectrum

#: shaft revolutions a record must cover for its envelope spectrum to resolve the fault lines
#: (line spacing ``f_r / 4``, a quarter of the shaft-frequency sidebands of the inner-race and
#: ball lines) [-]
MIN_REVOLUTIONS = 4

__all__ = [
    "BandSelection",
    "FAMILIES",
    "FAMILY_LINE",
    "Diagnosis",
    "DiagnosisRule",
    "MIN_REVOLUTIONS",
    "analyze_record",
    "check_resolvable",
    "diagnose",
    "diagnose_spectrum",
    "min_band_width",
    "find_lines",
    "load_signal",
    "refuted_column",
    "rpm_over_column",
]

FAMILIES = ("outer", "inner", "ball")
#: the fundamental line label of each fault family (the labels of :func:`find_lines`)
FAMILY_LINE = {"outer": "BPFO", "inner": "BPFI", "ball": "2xBSF"}


class BandSelection(enum.Enum):
    """How the envelope band is chosen when it is not given."""

    #: the band of highest spectral kurtosis among bands wide enough for the fault lines (fast
    #: kurtogram, Antoni 2007; :func:`.kurtogram.fast_kurtogram`)
    KURTOGRAM = "auto"


@dataclass(frozen=True)
class DiagnosisRule:
    """The fixed decision rule (see the module docstring for the justification).

    Attributes
    ----------
    n_harmonics : int
        Harmonics examined per family [-].
    threshold_db : float
        SNR for a line to count as detected [dB].
    tol_rel : float
        Relative frequency tolerance [-].
    tol_min_bins : float
        Smallest tolerance [bins].
    noise_rel : float
        Noise-floor window half-width relative to the target frequency [-].
    dominance : float
        Score ratio that separates one supported family from another [-].
    sideband_weight : float
        Score added per detected sideband [-].
    shaft_cursors : bool
        Also search every shaft harmonic ``k f_r`` below the highest fault line, so that a
        fault line nearer to a shaft harmonic than to its own target goes to the shaft (the
        6203's BSF is 1.994 f_r: its lines sit on the shaft harmonics until the harmonic
        cursors separate them).
    contact_angle_max_deg : float
        Largest contact angle the search of the fundamentals allows for [deg]: BPFO and FTF
        are searched from their positions at the bearing's own angle up to those at this
        angle (a contact angle moves them up), BPFI down to its position there, each widened
        by ``tol_rel`` (ball bearings; 0, or an angle not above the bearing's, searches
        ``±tol_rel`` about the kinematic position). 20°: the free contact angle of a 6205
        with 40 µm diametral clearance, the top of ISO 5753-1 group 4 (an axial load on a
        deep-groove bearing sets its angle near the free one); the CWRU records run at
        2.5–14° (docs/validation.md, "Contact angle of the CWRU bearings"), at the edge of
        what ``±1 %`` covers (BPFO up to 16°).
    """

    n_harmonics: int = 3
    threshold_db: float = 12.0
    tol_rel: float = 0.01
    tol_min_bins: float = 2.0
    noise_rel: float = 0.1
    dominance: float = 2.0
    sideband_weight: float = 0.1
    shaft_cursors: bool = False
    contact_angle_max_deg: float = 20.0


@dataclass(frozen=True)
class Diagnosis:
    """Result of :func:`diagnose`.

    Attributes
    ----------
    diagnosis : str
        ``"outer"``, ``"inner"``, ``"ball"``, ``"none"`` or ``"uncertain"``.
    confidence : float
        0..1 [-].
    band_hz : tuple[float, float]
        Envelope band [Hz] (orders when ``domain`` is :attr:`Domain.ORDER`).
    shaft_hz : float
        Shaft frequency [Hz] (1 in the order domain).
    peaks : list[Peak]
        Every line examined.
    scores : dict[str, float]
        Family scores [-].
    supported : list[str]
        Families meeting the support condition.
    kurtosis : float or None
        Spectral kurtosis of the chosen band (kurtogram) [-].
    spectrum : Spectrum
        The envelope spectrum.
    kurtogram : Kurtogram or None
        The kurtogram when the band was automatic.
    notes : list[str]
        Human-readable reasoning.
    """

    diagnosis: str
    confidence: float
    band_hz: tuple[float, float]
    shaft_hz: float
    peaks: list[Peak]
    scores: dict[str, float]
    supported: list[str]
    kurtosis: float | None
    spectrum: Spectrum
    kurtogram: Kurtogram | None = None
    notes: list[str] = field(default_factory=list)
    domain: Domain = Domain.HZ

    def as_dict(self) -> dict[str, Any]:
        """JSON-ready summary (the ``analyze --json`` object)."""
        return {
            "diagnosis": self.diagnosis,
            "confidence": self.confidence,
            "band_hz": list(self.band_hz),
            "shaft_hz": self.shaft_hz,
            "peaks": [p.as_dict() for p in self.peaks],
            "scores": self.scores,
            "supported": self.supported,
            "kurtosis": self.kurtosis,
            "domain": self.domain.value,
            "notes": self.notes,
        }

    def plot(
        self,
        title: str = "",
        f_max: float | None = None,
        unit: str | None = None,
        quantity: str = "envelope amplitude",
    ):
        """Envelope spectrum with the detected lines marked, one colour and legend entry per
        family; the fundamentals and harmonics are labelled where the labels do not overlap,
        the diagnosed family's first (sidebands are marked, not labelled). Returns the Figure.

        Parameters
        ----------
        title : str
            Axes title (default: the band [Hz] and the diagnosis).
        f_max : float, optional
            Largest frequency shown [Hz or -] (default 1.15 x the highest line examined).
        unit : str, optional
            Unit of the analysed signal (e.g. ``"m/s^2"``); ``"signal unit"`` when not given.
        quantity : str
            What the spectrum's amplitude is (the y label).
        """
        from ..plotting import FULL_WIDTH, label_points, legend_outside, new_figure

        fmax = f_max or 1.15 * max((p.target_hz for p in self.peaks), default=500.0)
        fig, ax = new_figure(width=FULL_WIDTH, height=3.6)
        dom = "Hz" if self.domain is Domain.HZ else "orders"
        self.spectrum.plot(
            f_max=fmax,
            ax=ax,
            unit=unit,
            quantity=quantity,
            title=title
            or (
                f"envelope spectrum, band {self.band_hz[0]:.0f}-{self.band_hz[1]:.0f} {dom}: "
                f"{self.diagnosis} (confidence {self.confidence:.2f})"
            ),
        )
        colors = {
            "outer": "tab:red",
            "inner": "tab:green",
            "ball": "tab:purple",
            "cage": "tab:gray",
            "shaft": "tab:orange",
        }
        names = {
            "outer": "BPFO family",
            "inner": "BPFI family",
            "ball": "2xBSF family",
            "cage": "FTF",
            "shaft": "shaft f_r",
        }
        ax.set_ylim(top=1.18 * ax.get_ylim()[1])  # room for the labels above the peaks
        labelled = []
        for fam, col in colors.items():
            found = [
                p
                for p in self.peaks
                if p.detected and _family(p.label) == fam and p.freq_hz <= fmax
            ]
            if not found:
                continue
            ax.plot(
                [p.freq_hz for p in found],
                [p.amplitude for p in found],
                "v",
                color=col,
                ms=5,
                label=f"{names[fam]} (detected)",
            )
            # lines of the series are labelled, sidebands only marked
            labelled += [(p, col) for p in found if "+" not in p.label and "-" not in p.label]
        # the diagnosed family's lines first (the plot shows why), each family's fundamentals
        # before its harmonics: a label that would overlap one already written is left out
        labelled.sort(
            key=lambda pc: (
                _family(pc[0].label) != self.diagnosis,
                _harmonic(pc[0].label),
                pc[0].freq_hz,
            )
        )
        label_points(
            ax,
            [p.freq_hz for p, _ in labelled],
            [p.amplitude for p, _ in labelled],
            [p.label for p, _ in labelled],
            color=[c for _, c in labelled],
            marker=None,
        )
        if labelled or any(p.detected for p in self.peaks):
            legend_outside(ax)
        return fig


def _harmonic(label: str) -> int:
    """Harmonic number of a line label (``"3xBPFO"`` -> 3, ``"2xBSF"`` -> 1, sidebands 99)."""
    for name, _attr, _mult in _FUNDAMENTALS:
        if label == name:
            return 1
        head, _, rest = label.partition("x")
        if rest == name and head.isdigit():
            return int(head)
    return 99


def _family(label: str) -> str:
    if "BPFO" in label:
        return "outer"
    if "BPFI" in label:
        return "inner"
    if "BSF" in label:
        return "ball"
    if "FTF" in label:
        return "cage"
    return "shaft"


#: label of the shaft rotation frequency f_r (Randall & Antoni 2011's notation; ``fs`` is the
#: sample rate)
SHAFT = "fr"
#: fundamental of each family: (label, characteristic-frequency attribute, multiple)
_FUNDAMENTALS = (
    ("BPFO", "bpfo_hz", 1.0),
    ("BPFI", "bpfi_hz", 1.0),
    ("2xBSF", "bsf_hz", 2.0),
    ("FTF", "ftf_hz", 1.0),
    (SHAFT, "shaft_hz", 1.0),
)
#: relative frequency within which two searched targets of a shared line count as equally near
#: (then the kinematic positions decide) [-]
TIE_REL = 1e-4
#: smallest tolerance of the shaft line's search [bins]: the shaft speed is the record's to
#: within the speed's uncertainty, not a fault line's slip, and two bins of a short record at
#: a low speed took a cage harmonic for it (600 r/min, 1 s: 2 x FTF at 8 Hz for f_r at 10 Hz,
#: and every shaft harmonic and sideband after it; exploratory testing, twenty-fourth session)
SHAFT_TOL_BINS = 1.0
#: sidebands: family fundamental -> modulating line
_SIDEBANDS = {"BPFO": SHAFT, "BPFI": SHAFT, "2xBSF": "FTF"}


def _label(name: str, h: int) -> str:
    return name if h == 1 else f"{h}x{name}"


def find_lines(
    es: Spectrum, bearing: Bearing, shaft_hz: float, rule: DiagnosisRule, f_limit: float
) -> list[Peak]:
    """Harmonic-series line search in an envelope spectrum.

    Stage 1: each family's fundamental (BPFO, BPFI, 2×BSF, FTF, f_r) within
    ``max(tol_rel f, tol_min_bins df)``; BPFO, FTF and BPFI of a ball bearing over the range of
    contact angles the rule allows, widened by ``tol_rel`` (:func:`_windows`). Stage 2:
    harmonics ``h`` at exact multiples of the *found* fundamental (when detected; else of the
    nominal one) within ``max(tol_min_bins, h)`` bins (the fundamental's position is known to
    half a bin), and the first two harmonics' sidebands (±f_r for BPFO and BPFI, ±FTF for 2×BSF)
    at the found spacings. Finally a line claimed by targets of two families goes to the nearer
    target.
    """
    k = characteristic_frequencies(bearing, shaft_hz)
    first = [(name, mult * getattr(k, attr)) for name, attr, mult in _FUNDAMENTALS]
    first = [(n, f) for n, f in first if f < f_limit]
    win = _windows(first, bearing, shaft_hz, rule)
    peaks = []
    for targets, bins in (([w for w in win if w[0] != SHAFT], rule.tol_min_bins),
                          ([w for w in win if w[0] == SHAFT], SHAFT_TOL_BINS)):  # fmt: skip
        peaks += match_peaks(
            es,
            targets,
            shaft_hz,
            tol_rel=rule.tol_rel,
            tol_min_bins=bins,
            noise_rel=rule.noise_rel,
            threshold_db=rule.threshold_db,
        )
    found = {p.label: (p.freq_hz if p.detected else p.target_hz) for p in peaks}
    nominal = dict(first)  # the kinematic positions, for attributing shared lines
    for name, f in first:
        found.setdefault(name, f)
        for h in range(2, rule.n_harmonics + 1):
            nominal[_label(name, h)] = h * f
    for h in range(2, rule.n_harmonics + 1):
        tg = [(_label(n, h), h * found[n]) for n, _ in first if h * found[n] < f_limit]
        peaks += match_peaks(
            es,
            tg,
            shaft_hz,
            tol_rel=0.0,
            tol_min_bins=max(rule.tol_min_bins, float(h)),
            noise_rel=rule.noise_rel,
            threshold_db=rule.threshold_db,
        )
    if rule.shaft_cursors:
        top = max((h * found[n] for n, _ in first if n != SHAFT for h in (1, rule.n_harmonics)),
                  default=0.0)  # fmt: skip
        ks = range(rule.n_harmonics + 1, int(top / found[SHAFT]) + 2) if SHAFT in found else ()
        nominal.update({_label(SHAFT, k): k * nominal[SHAFT] for k in ks})
        peaks += match_peaks(
            es,
            [(_label(SHAFT, k), k * found[SHAFT]) for k in ks if k * found[SHAFT] < f_limit],
            shaft_hz,
            tol_rel=0.0,
            tol_min_bins=rule.tol_min_bins,
            noise_rel=rule.noise_rel,
            threshold_db=rule.threshold_db,
        )
    for h in (1, 2):
        tg = []
        for n, mod in _SIDEBANDS.items():
            if n in found and mod in found:
                c = h * found[n]
                tg += [
                    (f"{_label(n, h)}-{mod}", c - found[mod]),
                    (f"{_label(n, h)}+{mod}", c + found[mod]),
                ]
                if n in nominal and mod in nominal:
                    nominal[f"{_label(n, h)}-{mod}"] = h * nominal[n] - nominal[mod]
                    nominal[f"{_label(n, h)}+{mod}"] = h * nominal[n] + nominal[mod]
        tg = [t for t in tg if 0 < t[1] < f_limit]
        peaks += match_peaks(
            es,
            tg,
            shaft_hz,
            tol_rel=0.0,
            tol_min_bins=max(rule.tol_min_bins, float(h + 1)),
            noise_rel=rule.noise_rel,
            threshold_db=rule.threshold_db,
        )
    # the fundamental's higher sidebands (m = 2 .. MAX_SIDEBAND_ORDER) of a modulated family,
    # where its fundamental and a first sideband are detected: a line another family's search
    # took there goes to the nearer target (_attribute). A ball fault's cage modulation puts
    # 2 x BSF - 3 FTF 2 Hz from BPFO on the CWRU 6205 (BPFO = Z FTF: its whole comb of FTF
    # harmonics lands on the BPFO series), and a 1 s record's BPFO search (+/- 2 bins) took it
    # for the outer race (twenty-fifth session, docs/validation.md)
    # the gate on the lines as attributed: on a short 6203 record an outer-race fault's
    # BPFO + 2 f_r and BPFO + f_r fall in BPFI's and BPFI - f_r's windows; those "detected"
    # BPFI lines are the outer race's (or the shaft's) once attributed, and must not open a
    # search whose BPFI - 2 f_r target then lands on BPFO itself (a helper's stress test,
    # twenty-fifth session: CWRU 312 in 0.5 s pieces read "inner")
    attributed = _attribute(peaks, nominal, es.resolution)
    det = {p.label for p in attributed if p.detected}
    tg = []
    for n, mod in _SIDEBANDS.items():
        first_sb = {f"{n}-{mod}", f"{n}+{mod}"}
        if n == "BPFO" or n not in det or not (first_sb & det):  # a fixed race: no modulation
            continue
        # the spacing: the kinematic modulation rate scaled as the found carrier is from its
        # kinematic position (the same speed and slip move both). The found FTF of a 1 s
        # record is off by up to half a bin, 3 times that at m = 3 (12 Hz for 11.6 put
        # 2 x BSF - 3 FTF 1.2 Hz low, and BPFO's nearer target kept the line)
        step = nominal[mod] * found[n] / nominal[n] if nominal[n] > 0 else found[mod]
        for m in range(2, MAX_SIDEBAND_ORDER + 1):
            for sign in (-1, 1):
                lab = f"{n}{'+' if sign > 0 else '-'}{m}x{mod}"
                nominal[lab] = nominal[n] + sign * m * nominal[mod]
                f = found[n] + sign * m * step
                if 0 < f < f_limit:
                    tg.append((lab, f))
    if not tg:  # nothing more searched: the attribution above is the answer
        return attributed
    peaks += match_peaks(
        es,
        tg,
        shaft_hz,
        tol_rel=0.0,
        tol_min_bins=rule.tol_min_bins,
        noise_rel=rule.noise_rel,
        threshold_db=rule.threshold_db,
    )
    return _attribute(peaks, nominal, es.resolution)


#: the fundamentals a contact angle moves, and the attribute of their position
_ANGLE_MOVES = {"BPFO": "bpfo_hz", "BPFI": "bpfi_hz", "FTF": "ftf_hz"}


def _windows(first, bearing: Bearing, shaft_hz: float, rule: DiagnosisRule) -> list[tuple]:
    """The stage-1 targets of :func:`find_lines`: ``(label, f)`` searched within ``±tol_rel``,
    or, for the lines a contact angle moves (BPFO, FTF up; BPFI down) when
    ``rule.contact_angle_max_deg`` is above the bearing's angle, ``(label, f, low, high)``:
    from the kinematic position to the one at that angle, widened by ``tol_rel``."""
    a_max = math.radians(rule.contact_angle_max_deg)
    if not isinstance(bearing, BallBearing) or a_max <= bearing.contact_angle:
        return list(first)
    k_max = characteristic_frequencies(replace(bearing, contact_angle=a_max), shaft_hz)
    out = []
    for name, f in first:
        if name not in _ANGLE_MOVES:
            out.append((name, f))
            continue
        g = getattr(k_max, _ANGLE_MOVES[name])
        lo, hi = min(f, g), max(f, g)
        out.append((name, f, lo * (1.0 - rule.tol_rel), hi * (1.0 + rule.tol_rel)))
    return out


def _attribute(
    peaks: list[Peak], nominal: dict[str, float] | None = None, res: float = 0.0
) -> list[Peak]:
    """A detected line claimed by targets of different families counts only for the family
    whose searched target (a multiple of the *found* fundamental) is nearer. When the two
    targets are equally near (within :data:`TIE_REL` of the line's frequency; 3×BPFO of a
    fundamental found 0.7 % high lands exactly on 2×BPFI), the kinematic (``nominal``)
    positions decide."""
    nominal = nominal or {}

    def _beats(p: Peak, q: Peak) -> bool:
        """The target of ``q`` is nearer to the line than the target of ``p``."""
        own = abs(p.freq_hz - p.target_hz)
        d = abs(p.freq_hz - q.target_hz)
        tie = TIE_REL * max(p.freq_hz, 1e-12)
        if d < own - tie:
            return True
        own_nom = abs(p.freq_hz - nominal.get(p.label, p.target_hz))
        return abs(d - own) <= tie and abs(p.freq_hz - nominal.get(q.label, q.target_hz)) < own_nom

    shaft = [q for q in peaks if _family(q.label) == "shaft"]
    out = []
    for p in peaks:
        fam = _family(p.label)
        stolen = p.detected and any(
            _family(q.label) != fam
            and (
                abs(q.freq_hz - p.freq_hz) <= 1e-9 * max(1.0, p.freq_hz)
                # a line between two bins: two searches may take its two bins (a ball fault's
                # 2 x BSF - 3 FTF at 101.5 Hz, BPFO's search took 102 and its own 101; the DEM
                # run of docs/validation.md), one line all the same. The smaller bin is the
                # larger one's skirt: only it can go (a 0.32 s piece of CWRU 109 lost its
                # inner-race peak to a ball line in the next bin otherwise)
                or (
                    q.detected
                    and abs(q.freq_hz - p.freq_hz) <= res * (1.0 + 1e-9)
                    and q.amplitude >= p.amplitude
                )
            )
            and _beats(p, q)
            for q in peaks
            if q is not p
        )
        # a fault line nearer to a shaft harmonic's target than to its own goes to the shaft,
        # whichever line that harmonic's own search took (on a short record the 6203's BPFO,
        # 3.05 f_r, lies within a bin or two of 3 f_r; the 3 f_r search, +/-3 bins, may take a
        # stronger neighbour, BPFI - 2 f_r, and leave the shaft line to BPFO)
        stolen = stolen or (p.detected and fam != "shaft" and any(_beats(p, q) for q in shaft))
        out.append(
            Peak(
                p.label,
                p.target_hz,
                p.freq_hz,
                p.amplitude,
                p.snr_db,
                p.order,
                p.detected and not stolen,
            )
        )
    return out


def min_band_width(bearing: Bearing, shaft_hz: float, fs: float, rule: DiagnosisRule) -> float:
    """Narrowest envelope band that keeps the first ``rule.n_harmonics`` harmonics of the
    highest fault line and the shaft sidebands: ``n max(BPFO, BPFI, 2 BSF) + f_r`` [Hz]; a
    one-line :class:`ConfigError` when it does not fit below ``fs/2``.

    Parameters
    ----------
    bearing : Bearing
        Geometry.
    shaft_hz : float
        Shaft frequency [Hz] (1 in the order domain).
    fs : float
        Sample rate [Hz].
    rule : DiagnosisRule
        For the number of harmonics.
    """
    kin = characteristic_frequencies(bearing, shaft_hz)
    f_max = max(kin.bpfo_hz, kin.bpfi_hz, 2 * kin.bsf_hz)
    min_bw = rule.n_harmonics * f_max + shaft_hz
    if min_bw > 0.5 * fs:
        raise ConfigError(
            f"fs_hz = {fs:.6g} Hz is too low for an envelope band of {min_bw:.6g} Hz "
            f"({rule.n_harmonics} x {f_max:.6g} Hz + shaft); valid range ({2 * min_bw:.6g}, "
            "inf) Hz"
        )
    return min_bw


def diagnose(
    x: NDArray[np.float64],
    fs: float,
    bearing: Bearing,
    shaft_hz: float,
    *,
    band: tuple[float, float] | BandSelection | str = BandSelection.KURTOGRAM,
    rule: DiagnosisRule | None = None,
    domain: Domain | str = Domain.HZ,
) -> Diagnosis:
    """Envelope-analysis diagnosis of ``x`` with the fixed :class:`DiagnosisRule`.

    Parameters
    ----------
    x : ndarray
        Vibration signal (acceleration, any unit).
    fs : float
        Sample rate [Hz] (samples per revolution in the order domain).
    bearing : Bearing
        Geometry for the characteristic frequencies.
    shaft_hz : float
        Shaft frequency [Hz] (1 in the order domain).
    band : (lo, hi) or BandSelection
        Envelope band [Hz], or how to choose it (:class:`BandSelection`; ``"auto"`` = the fast
        kurtogram).
    rule : DiagnosisRule, optional
        Decision rule (default: the documented one).
    domain : Domain
        :attr:`Domain.HZ` or :attr:`Domain.ORDER` (abscissa of the spectra).
    """
    from ..catalog import as_bearing

    bearing = as_bearing(bearing)
    rule = rule or DiagnosisRule()
    domain = parse_enum(Domain, domain, "domain")
    fs = check_positive("fs_hz", fs, "Hz")
    shaft_hz = check_positive("shaft_hz", shaft_hz, "Hz")
    notes: list[str] = []
    kg = None
    kurt = None
    band_v = _band_value(band)
    if band_v is None:
        min_bw = min_band_width(bearing, shaft_hz, fs, rule)
        kg = fast_kurtogram(x, fs, min_bandwidth_hz=min_bw)
        band_t = kg.band
        kurt = kg.max_kurtosis
        notes.append(
            f"kurtogram band {band_t[0]:.6g}-{band_t[1]:.6g}, kurtosis {kurt:.3g}, "
            f"level {kg.level:.2f}"
        )
    else:
        band_t = check_band(band_v, fs)
    es = envelope_spectrum(x, fs, band_t, domain=domain)
    return diagnose_spectrum(es, bearing, shaft_hz, band_t, rule=rule, kurtogram=kg, notes=notes)


def _band_value(band) -> tuple | None:
    """``None`` for the kurtogram's choice (``"auto"`` / :attr:`BandSelection.KURTOGRAM`), else
    the band as a tuple (checked by :func:`.envelope.check_band` where it is used); any other
    string is refused in one line."""
    if isinstance(band, str | BandSelection):
        if band not in (BandSelection.KURTOGRAM, BandSelection.KURTOGRAM.value):
            raise ConfigError(f"band = {band!r} is invalid; valid: 'auto' or two numbers LO HI")
        return None
    return tuple(band)


#: the highest order ``m`` of a modulation sideband ``h F +/- m f_mod`` of a supported family
#: (f_mod: the shaft speed for an inner-race fault, the cage's for a ball fault) a rival
#: family's line may be and then does not count against it [-]: an inner-race fault turning
#: through the load zone modulates its impacts at the shaft speed, and the load zone's shape
#: puts sidebands at several multiples of it (Randall & Antoni 2011, MSSP 25, sec. 2)
MAX_SIDEBAND_ORDER = 3
#: the line each family's impacts are modulated by (none for a fixed outer race)
_MODULATION = {"inner": SHAFT, "ball": "FTF"}


def _rival_evidence(
    fam: str,
    top: str,
    by: dict[str, Peak],
    evidence: dict[str, float],
    rule: DiagnosisRule,
    res: float,
    notes: list[str],
) -> float:
    """The harmonic amplitude sum of family ``fam``'s detected lines (``evidence[fam]``),
    without those that lie on a modulation sideband of the supported family ``top``
    (``h F_top +/- m f_mod``, ``m <= MAX_SIDEBAND_ORDER``, within the sideband search's
    ``max(tol_min_bins, h + 1)`` bins of ``res`` [Hz]): such a line is ``top``'s own. On the
    6203, 2 x and 3 x (2 x BSF) lie 0.3 Hz from BPFI + 3 f_r and 2 BPFI + 2 f_r at 1797 r/min,
    and a simulated inner-race fault read "uncertain" in every view (twenty-third session,
    docs/validation.md)."""
    mod = _MODULATION.get(top)
    fund = by.get(FAMILY_LINE[top])
    fm = by.get(mod) if mod else None
    if fund is None or fm is None:
        return evidence[fam]
    f_top = fund.freq_hz if fund.detected else fund.target_hz
    f_mod = fm.freq_hz if fm.detected else fm.target_hz
    amp, on = 0.0, []
    for h in range(1, rule.n_harmonics + 1):
        p = by.get(_label(FAMILY_LINE[fam], h))
        if p is None or not p.detected:
            continue
        tol = max(rule.tol_min_bins, h + 1.0) * res
        hit = next(
            (f"{_label(FAMILY_LINE[top], k)}{'+' if m > 0 else '-'}{abs(m)}x{mod}"
             for k in range(1, rule.n_harmonics + 1)
             for m in range(-MAX_SIDEBAND_ORDER, MAX_SIDEBAND_ORDER + 1)
             if m != 0 and abs(p.freq_hz - (k * f_top + m * f_mod)) <= tol),
            None,
        )  # fmt: skip
        if hit is None:
            amp += p.amplitude
        else:
            on.append(f"{p.label} on {hit}")
    if on:
        notes.append(f"{fam} lines on {top}'s modulation sidebands, not counted against it: "
                     + ", ".join(on))  # fmt: skip
    return amp


def diagnose_spectrum(
    es: Spectrum,
    bearing: Bearing,
    shaft_hz: float,
    band: tuple[float, float],
    *,
    rule: DiagnosisRule | None = None,
    kurtogram: Kurtogram | None = None,
    notes: list[str] | None = None,
    drop: frozenset[str] = frozenset(),
) -> Diagnosis:
    """Steps 3–4 of the rule (module docstring) on an envelope spectrum already computed.

    Parameters
    ----------
    es : Spectrum
        Envelope (or squared-envelope) spectrum [Hz or orders].
    bearing : Bearing
        Geometry for the characteristic frequencies.
    shaft_hz : float
        Shaft frequency [Hz] (1 in the order domain).
    band : (float, float)
        The band the envelope was taken in [Hz or orders]; its width bounds the lines searched.
    rule : DiagnosisRule, optional
        Decision rule.
    kurtogram : Kurtogram, optional
        The kurtogram that chose the band (kept in the result).
    notes : list of str, optional
        Notes so far.
    drop : frozenset of str
        Fault families (``"outer"``, ``"inner"``, ``"ball"``) whose lines are found and
        reported but not counted as detected (the fused diagnosis's kinematic check,
        :func:`.fused.diagnose_fused`).
    """
    rule = rule or DiagnosisRule()
    domain = es.domain
    band_t = (float(band[0]), float(band[1]))
    kg = kurtogram
    kurt = kg.max_kurtosis if kg is not None else None
    notes = list(notes or [])
    if es.resolution > shaft_hz / MIN_REVOLUTIONS:
        notes.append(
            f"record too short: resolution {es.resolution:.3g} > f_r/4; cannot resolve "
            "the fault lines"
        )
        return Diagnosis(
            "uncertain", 0.0, band_t, shaft_hz, [], {}, [], kurt, es, kg, notes, domain
        )
    peaks = find_lines(es, bearing, shaft_hz, rule, band_t[1] - band_t[0])
    if drop:
        peaks = [replace(p, detected=False) if _family(p.label) in drop else p for p in peaks]
    by = {p.label: p for p in peaks}
    base = FAMILY_LINE
    side = {
        "outer": [],
        "inner": [f"BPFI-{SHAFT}", f"BPFI+{SHAFT}", f"2xBPFI-{SHAFT}", f"2xBPFI+{SHAFT}"],
        "ball": ["2xBSF-FTF", "2xBSF+FTF", "2x2xBSF-FTF", "2x2xBSF+FTF"],
    }
    scores: dict[str, float] = {}
    evidence: dict[str, float] = {}
    supported: list[str] = []
    best_fault_snr = -math.inf

    def _result(label: str, confidence: float) -> Diagnosis:
        return Diagnosis(label, confidence, band_t, shaft_hz, peaks, scores, supported, kurt, es,
                         kg, notes, domain)  # fmt: skip

    any_detected = False
    for fam in FAMILIES:
        labels = [_label(base[fam], h) for h in range(1, rule.n_harmonics + 1)]
        hs = [by.get(lab) for lab in labels]
        z = []
        amp = 0.0
        for p in hs:
            if p is not None and np.isfinite(p.snr_db):
                best_fault_snr = max(best_fault_snr, p.snr_db)
            if p is not None and p.detected:
                any_detected = True
                z.append(0.5 + 0.5 * min(max((p.snr_db - rule.threshold_db) / 20.0, 0.0), 1.0))
                amp += p.amplitude
            else:
                z.append(0.0)
        n_sb = sum(1 for lab in side[fam] if lab in by and by[lab].detected)
        scores[fam] = min(1.0, float(np.mean(z)) + rule.sideband_weight * n_sb)
        evidence[fam] = amp
        n_det = sum(1 for p in hs if p is not None and p.detected)
        if hs[0] is not None and hs[0].detected and n_det >= 2:
            supported.append(fam)
        notes.append(
            f"{fam}: {n_det}/{rule.n_harmonics} harmonics, {n_sb} sidebands, "
            f"quality {scores[fam]:.3f}, harmonic amplitude sum {amp:.4g}"
        )
    if supported:
        top = max(supported, key=lambda f: evidence[f])
        rival = max(
            (_rival_evidence(f, top, by, evidence, rule, es.resolution, notes)
             for f in FAMILIES if f != top),
            default=0.0,
        )  # fmt: skip
        if rule.dominance * rival > evidence[top]:
            notes.append("another fault family has comparable harmonic amplitudes")
            return _result("uncertain", 0.0)
        conf = scores[top] * (1.0 - rival / evidence[top])
        return _result(top, float(max(conf, 0.0)))
    if any_detected:
        notes.append("isolated fault lines without a harmonic series")
        return _result("uncertain", 0.0)
    conf = min(max((rule.threshold_db - best_fault_snr) / 10.0, 0.0), 1.0)
    return _result("none", float(conf))


# --------------------------------------------------------------------------- signal files


def check_resolvable(rec: SignalRecord) -> SignalRecord:
    """Refuse a record that, at its sample rate and shaft speed, covers fewer than
    :data:`MIN_REVOLUTIONS` shaft revolutions: its envelope spectrum (resolution ``fs / n``)
    cannot separate the fault lines and :func:`diagnose` could only answer "uncertain". The
    one-line :class:`~bearingsim.errors.ConfigError` gives the valid range of each of the two.
    Records with a per-sample speed are order tracked and not checked here.

    Parameters
    ----------
    rec : SignalRecord
        The record (:func:`load_signal`).
    """
    if rec.rpm is None:
        return rec
    n = rec.x.size
    shaft_hz = rec.rpm / 60.0
    span = n / rec.fs
    need = MIN_REVOLUTIONS / shaft_hz
    if span >= need:
        return rec
    if "option" in (rec.info.get("fs_source"), rec.info.get("rpm_source")) or rec.columns:
        # a rate or speed given (a text file's speed always is): the values that would
        # resolve these samples
        valid = (
            f"valid range fs_hz in (0, {n * shaft_hz / MIN_REVOLUTIONS:.6g}] Hz at this rpm, or "
            f"rpm in [{60.0 * MIN_REVOLUTIONS / span:.6g}, inf) r/min at this fs_hz"
        )
    else:  # both the file's own: only a longer record helps
        valid = (
            f"valid: a record of at least {math.ceil(need * rec.fs)} samples ({need:.3g} s) at "
            "its rate and speed"
        )
    raise ConfigError(
        f"fs_hz = {rec.fs:.6g} Hz and rpm = {rec.rpm:.6g} r/min: the {n} samples of "
        f"{Path(rec.source).name!r} last {span:.3g} s, shorter than the {MIN_REVOLUTIONS} shaft "
        f"revolutions ({need:.3g} s) the envelope spectrum needs to resolve the fault lines; "
        + valid
    )


#: consecutive samples at the record's largest (or smallest) value that make a flat top: the
#: signal of a saturated sensor, amplifier or converter. A sampled peak of a vibration signal
#: is met by one sample, rarely two equal ones (none of the 34 CWRU records, on any channel,
#: has two) [-]
CLIPPED_RUN = 3


def check_samples(rec: SignalRecord) -> SignalRecord:
    """Refuse a record whose samples cannot be diagnosed: a sample that is not finite (NaN,
    inf), a constant record, or a clipped one — :data:`CLIPPED_RUN` or more consecutive samples
    equal to the record's largest or to its smallest value (a flat top or bottom: the envelope
    of a clipped impact loses the impact's shape and adds lines of its own). One-line
    :class:`~bearingsim.errors.ConfigError` naming the file, the channel and the samples.

    Parameters
    ----------
    rec : SignalRecord
        The record (:func:`load_signal`).
    """
    x = np.asarray(rec.x, dtype=float)
    where = f"file = {Path(rec.source).name!r}, channel {rec.channel!r}"
    bad = ~np.isfinite(x)
    if bad.any():
        raise ConfigError(
            f"{where}: {int(bad.sum())} of {x.size} samples are not finite (NaN or inf; the "
            f"first is sample {int(np.argmax(bad))}); valid: finite samples"
        )
    if x.size == 0:
        raise ConfigError(f"{where} holds no samples; valid: a vibration signal")
    hi, lo = float(x.max()), float(x.min())
    if hi == lo:
        raise ConfigError(
            f"{where}: all {x.size} samples equal {hi:.6g}; valid: a vibration signal"
        )
    d = np.diff(x)
    if x.size > 2 and (np.all(d > 0) or np.all(d < 0)) and np.ptp(d) <= 1e-6 * abs(d.mean()):
        # a time column whose name was not recognised (tiem_s) read as the signal with
        # --fs-hz, as the "no time column" error suggested: it made a rig out of a straight
        # line (exploratory testing, twenty-fourth session)
        raise ConfigError(
            f"{where} changes in even steps ({d.mean():.6g} per sample): a time or counter "
            "column, not a vibration signal; valid: a vibration channel (--channel), and a "
            "time column named time_s, time or t"
        )
    for v, side in ((hi, "largest"), (lo, "smallest")):
        at = np.concatenate(([0], (x == v).astype(np.int8), [0]))
        step = np.diff(at)
        starts, ends = np.flatnonzero(step == 1), np.flatnonzero(step == -1)
        runs = ends - starts
        if runs.max() >= CLIPPED_RUN:
            i = int(np.argmax(runs >= CLIPPED_RUN))
            raise ConfigError(
                f"{where} is clipped: {int(runs[i])} consecutive samples ({int(starts[i])} to "
                f"{int(ends[i]) - 1}) equal its {side} value {v:.6g} (a flat top: a saturated "
                f"sensor or amplifier); valid: fewer than {CLIPPED_RUN} consecutive samples at "
                "the extreme value"
            )
    return rec


def load_signal(
    path: str | Path,
    *,
    channel: str | None = None,
    fs_hz: float | None = None,
    rpm: float | None = None,
) -> SignalRecord:
    """A record to diagnose: :func:`bearingsim.io.read_signal` (see there for the formats and
    parameters), which must give the shaft speed (``rpm``, a file's ``X###RPM`` key or rpm, or
    a ``speed_hz``/``rpm`` column) and, for a text file, at least 16 rows.

    Parameters
    ----------
    path : str or Path
        CWRU ``.mat``, bearingsim result ``.nc``/``.h5``, or ``.csv``/``.txt``.
    channel : str, optional
        Channel or column.
    fs_hz : float, optional
        Sample rate [Hz].
    rpm : float, optional
        Shaft speed [r/min].
    """
    rec = read_signal(path, channel=channel, fs_hz=fs_hz, rpm=rpm)
    name = Path(path).name
    if rpm is not None:
        rec = rpm_over_column(
            rec, rpm, valid="a speed it holds, or no --rpm (the column is then read)"
        )
    if rec.rpm is None and rec.speed_hz is None:
        what = "no X###RPM key" if rec.source.lower().endswith(".mat") else "no rpm/speed_hz column"
        raise ConfigError(
            f"file = {name!r} has {what} and no --rpm was given; valid: give --rpm R (> 0 r/min)"
        )
    if rec.columns and rec.x.size < MIN_SAMPLES:
        raise ConfigError(
            f"file = {name!r} has too few rows; valid range [{MIN_SAMPLES}, inf) rows"
        )
    return rec


def refuted_column(rec: SignalRecord, tol_rel: float = 0.01) -> tuple[float, Any] | None:
    """``(median [Hz], comb)`` where ``rec``'s speed column is steady within ``tol_rel``
    (:func:`bearingsim.io.signal.steady_speed_hz`) and its shaft harmonics refute that median
    (:func:`.contact_angle.refuted_speed`, ``comb`` the record's own speed's
    :class:`~.contact_angle.SpeedComb`), else None (also without a speed column): the one rule
    of ``analyze`` and ``rig identify`` for a speed column, judged as a ``--rpm`` is."""
    if rec.speed_hz is None:
        return None
    from ..io.signal import steady_speed_hz

    med = steady_speed_hz(rec.speed_hz, tol_rel)
    if med is None:
        return None
    from .contact_angle import refuted_speed

    c = refuted_speed(rec.x, rec.fs, med, tol_rel=tol_rel)
    return None if c is None else (med, c)


def rpm_over_column(rec: SignalRecord, rpm: float, *, valid: str) -> SignalRecord:
    """``rec`` read at a speed given ``rpm`` [r/min] (``--rpm``) against its speed column:
    unchanged where it has none or the column holds that speed (within 1 %); where the column
    is steady (:func:`bearingsim.io.signal.steady_speed_hz`) and the record's own shaft
    harmonics refute it (:func:`.contact_angle.refuted_speed`), the column is set aside and its
    median kept as the speed the file states (``info["rpm_file"]`` [r/min], with
    ``info["speed_column_refuted"]`` True), which the speed given overrides and is judged
    against, as a CWRU file's ``X###RPM``. Exploratory testing, twenty-seventh session: a
    column of 1800 r/min on record 172 (1728 r/min) was refused by its shaft lines and the
    ``--rpm 1728`` that corrects it was refused as contradicting the column, so only an edit
    of the file got past it.

    Raises
    ------
    ConfigError
        One line where the speed given contradicts a column the record does not refute
        (``valid``: the message's way on).
    """
    span = column_speed_refutes(rec, rpm)
    if span is None:
        return rec
    if (refuted := refuted_column(rec)) is not None:
        med = refuted[0]
        info = {**rec.info, "rpm_file": 60.0 * med, "speed_column_refuted": True}
        return replace(rec, speed_hz=None, info=info)
    raise ConfigError(
        f"rpm = {rpm:.6g} r/min contradicts the speed column of {Path(rec.source).name!r} "
        f"({speed_span_text(span, rpm)}); valid: {valid}"
    )


def load_signal_and_speed(
    path: str | Path,
    *,
    channel: str | None = None,
    fs_hz: float | None = None,
    rpm: float | None = None,
) -> tuple[SignalRecord, str]:
    """:func:`load_signal`, and where the shaft speed came from: ``"option"`` (``rpm``),
    ``"file"`` (the file's), or, when the file gives none, the CWRU nominal speed of the motor
    load in its name (``"name (CWRU nominal speed at load 2 hp)"``,
    :func:`bearingsim.io.cwru.cwru_nominal_rpm`; the CWRU 0.028 in records store no speed).
    The one rule of ``bearingsim analyze`` and ``examples/sim_to_real.py``. The speed is also
    what a CWRU file without a sample rate in its name has its rate read with
    (:func:`bearingsim.io.cwru.infer_cwru_fs`).

    Parameters
    ----------
    path, channel, fs_hz, rpm
        As :func:`load_signal`.

    Raises
    ------
    ConfigError
        As :func:`load_signal`, when neither ``rpm``, the file nor its name gives a speed.
    """
    from ..io.cwru import cwru_nominal_rpm

    if rpm is not None:
        return load_signal(path, channel=channel, fs_hz=fs_hz, rpm=rpm), "option"
    try:
        return load_signal(path, channel=channel, fs_hz=fs_hz), "file"
    except ConfigError:
        nominal = cwru_nominal_rpm(path)
        if nominal is None:
            raise
    # the file gives no (usable) speed: read it again at the name's; a failure that was not
    # the speed's fails again, the same way
    load, r = nominal
    rec = load_signal(path, channel=channel, fs_hz=fs_hz, rpm=r)
    return rec, f"name (CWRU nominal speed at load {load} hp)"


#: fewest samples per revolution of the default order tracking [1/rev]: 16 orders, the
#: third harmonic of a 6205's BPFI and its shaft sidebands (a record whose fs over its speed is
#: lower has no room for the fault lines; the fused diagnosis's band check then says so)
MIN_SAMPLES_PER_REV = 32


def analyze_record(
    rec: SignalRecord,
    bearing: Bearing | str,
    *,
    band: tuple[float, float] | BandSelection | str = BandSelection.KURTOGRAM,
    rule: DiagnosisRule | None = None,
    samples_per_rev: int | None = None,
    max_memory: float | None = None,
):
    """Diagnose a :class:`SignalRecord` with the fused benchmark methods
    (:func:`.fused.diagnose_fused`); with a per-sample speed the signal is first order tracked
    (:func:`.resample_to_angle`, cubic interpolation) and analysed in the order domain.

    Parameters
    ----------
    rec : SignalRecord
        The signal (:func:`load_signal`).
    bearing : Bearing or str
        Geometry for the characteristic frequencies (or its catalogue id).
    band : (lo, hi) or BandSelection
        Envelope band of every method [Hz] (orders when order tracked), or ``"auto"`` (whole
        band for the raw and pre-whitened views, kurtogram and infogram bands for the DRS
        views).
    rule : DiagnosisRule, optional
        Line search (default: the documented one with shaft cursors).
    samples_per_rev : int, optional
        Order-tracking density [1/rev]; default: the largest even number with
        ``samples_per_rev * max(speed_hz) <= fs``, so that the orders analysed stay below the
        record's Nyquist frequency at its fastest (a fixed 512 analysed 12 kHz records up to
        7.7 kHz, beyond their 6 kHz, and 48 kHz records only up to 7.7 kHz).
    max_memory : float, optional
        Memory the order-tracked grid and its spectrum may take [B]
        (:func:`.resample_to_angle`: refused in one line beyond it; ``bearingsim analyze``
        passes the memory budget); ``None``: not checked.

    Returns
    -------
    FusedDiagnosis
        Verdict, calibrated confidence and the evidence of each method.
    """
    from ..catalog import as_bearing
    from .fused import diagnose_fused

    if not isinstance(rec, SignalRecord):
        raise ConfigError(
            f"rec = {type(rec).__name__} is invalid; valid: a SignalRecord (load_signal, or "
            "SignalRecord(x, fs, rpm, source, channel))"
        )
    bearing = as_bearing(bearing)
    band_v = _band_value(band)
    rule = rule or DiagnosisRule(shaft_cursors=True)
    if rec.speed_hz is not None and rec.rpm is None:
        sp = np.asarray(rec.speed_hz, dtype=float)
        if sp.shape != rec.x.shape or not np.all(np.isfinite(sp)) or np.any(sp <= 0):
            # which file, how many samples, and the way on (exploratory testing, twenty-fifth
            # session: a tachometer's dropouts to 0 were refused naming neither)
            bad = (
                int(np.count_nonzero(~(np.isfinite(sp) & (sp > 0))))
                if sp.shape == rec.x.shape
                else None
            )
            what = (
                f"{bad} of its {sp.size} samples are not finite and > 0"
                if bad is not None
                else f"it has {sp.size} samples for the signal's {rec.x.size}"
            )
            raise ConfigError(
                f"file = {Path(rec.source).name!r}: the speed column cannot be order tracked "
                f"({what}); valid: a speed > 0 at every sample (range (0, inf) Hz), or --rpm R "
                "to judge the record at one speed"
            )
        # a steady column the shaft lines refute is judged at its median in Hz (exploratory
        # testing, twenty-seventh session: a constant column of 1800 r/min on record 172,
        # 1728 r/min, read "ball" at 0.79, where --rpm 1800 is refuted)
        if (refuted := refuted_column(rec, rule.tol_rel)) is not None:
            med = refuted[0]
            b = None if band_v is None else (band_v[0] * med, band_v[1] * med)
            return diagnose_fused(
                rec.x, rec.fs, bearing, med, band=b, rule=rule, **_supply(rec),
                speed_from="the speed column",
            )  # fmt: skip
        t = np.arange(rec.x.size) / rec.fs
        if samples_per_rev is None:
            samples_per_rev = max(2 * int(rec.fs / float(sp.max()) / 2.0), MIN_SAMPLES_PER_REV)
        sig = resample_to_angle(
            angle_from_speed(t, 2.0 * math.pi * sp),
            rec.x,
            samples_per_rev,
            interpolation=Interpolation.CUBIC,
            max_memory=max_memory,
        )
        return diagnose_fused(
            sig.value, float(samples_per_rev), bearing, 1.0, band=band_v, rule=rule,
            domain=Domain.ORDER, speed_from="the speed column",
        )  # fmt: skip
    stated = rec.info.get("rpm_file")  # the file's own speed, where --rpm overrode it
    return diagnose_fused(
        rec.x, rec.fs, bearing, rec.rpm / 60.0, band=band_v, rule=rule, **_supply(rec),
        stated_hz=None if stated is None else float(stated) / 60.0,
    )  # fmt: skip


def _supply(rec: SignalRecord) -> dict:
    """The supply frequencies to note for ``rec``: a simulation has no electrical supply, so
    only those of :data:`.fused.SUPPLY_HZ` whose multiple its rig adds as a fixed tone
    (``info["fixed_tones_hz"]``, :func:`bearingsim.io.signal.read_signal`); a measured record,
    all of them (the default)."""
    from .fused import SUPPLY_HZ

    fixed = (rec.info or {}).get("fixed_tones_hz")
    if fixed is None:
        return {}
    return {
        "supply_hz": tuple(
            f0 for f0 in SUPPLY_HZ if any(abs(f / f0 - round(f / f0)) < 1e-6 for f in fixed)
        )
    }
