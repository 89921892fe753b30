"""One diagnosis over the evidence of the benchmark methods (Smith & Randall 2015, MSSP 64–65,
100–131), with a calibrated confidence.

**Views.**
Four squared envelope spectra (SES) of the same record (:mod:`.benchmark`) and one enhanced
envelope spectrum (:mod:`.coherence`):

============  ==============================================================================
``raw``       SES of the raw signal, whole band (Smith & Randall's method 1)
``cpw``       SES of the cepstrally pre-whitened signal, whole band (method 2)
``drs_sk``    SES of the DRS random part in the band of largest spectral kurtosis (method 3,
              the "benchmark method"; fast kurtogram, Antoni 2007)
``drs_info``  SES of the DRS random part in the band of largest *spectral* negentropy (the
              infogram, Antoni 2016): repetitive transients, not isolated impulses, choose it
``csc``       enhanced envelope spectrum of the DRS random part: its cyclic spectral coherence
              averaged over every carrier band (Antoni, Xin & Hamzaoui 2017): no band is chosen,
              each band counts by its modulation depth, not its energy (fifteenth session;
              not run, with a note, when the sample rate is below 8 x the highest line read)
============  ==============================================================================

A band given by the caller replaces the whole band and the two selected bands (the three
methods are then run in that band, and the coherence is averaged over the STFT carriers within
half a carrier spacing of it, 375 Hz for the 6205 at 1800 r/min: the view's ``band`` says
which).
The coherence view reads the DRS random part because cyclostationary analysis of the second
order needs the periodic (first-order) part removed first (Antoni 2007, JSV 304): shaft
and supply tones and their products otherwise stand as coherence lines at shaft orders.

**Patterns (Smith & Randall 2015, table 1).**
In each view the lines of :func:`.diagnosis.find_lines` are searched with the shaft-harmonic
cursors on (:attr:`.diagnosis.DiagnosisRule.shaft_cursors`: a line nearer a shaft harmonic than
its fault target is the shaft's) and each line gets the quality
``q = 0.5 + 0.5 clip((SNR - 12 dB) / 20 dB, 0, 2)`` when detected (0 otherwise; it grows up to
52 dB so that two strong families do not tie at a cap):

* **outer** — BPFO and harmonics: supported when BPFO and one of 2×, 3×BPFO are detected;
  score = mean q of the three;
* **inner** — BPFI and harmonics with sidebands at ±f_r (shaft modulation): supported when
  BPFI, one of 2×, 3×BPFI and at least one sideband are detected; score = mean q + 0.1 per
  detected sideband;
* **ball** — 2×BSF and harmonics with ±FTF sidebands (supported and scored like inner), *or*
  the cage modulation alone: FTF detected in a view where no race-fault or 2×BSF series is
  supported (score = mean q of FTF and 2×FTF). The cage pattern counts only when it is seen
  in at least two views: an FTF line also rides on outer- and inner-race faults (ball-to-ball
  differences pass the load zone at the cage speed), so beside a race-fault series it is no
  evidence of a ball fault.

**Kinematic check (one cage speed; sixteenth session).** The outer-race lines are ``BPFO = Z
f_c`` and the inner-race lines ``BPFI = Z (f_r - f_c)`` for the cage speed ``f_c``, so
``BPFO + BPFI = Z f_r`` whatever the contact angle and the cage slip — the two quantities that
make the line search's windows wide (±1 % and the contact-angle range), wide enough that on the
6205 1.5×BPFO falls into the BPFI window. In a view where both fundamentals are detected and
their sum is more than :data:`KINEMATIC_TOL` resolutions off ``Z f_r`` (``f_r`` measured from
the record's shaft harmonics, :func:`.contact_angle.measured_shaft_hz`; exactly 1 in the order
domain), the two lines cannot both be this bearing's fault lines: the lines of the race family
supported in fewer views are not counted in that view (found and reported, not detected).
When both are supported in as many views, or the speed cannot be measured, nothing changes.

The fused score of a family is the mean over the views of its score where it is supported (0
elsewhere). A family is a candidate when it is supported in at least two views
(:data:`MIN_VIEWS`; all views when fewer are run): one method alone is no evidence. The
leading family is the candidate with the largest fused score and the **margin** is its score
minus the largest score of the other two families.

What is not a bearing fault is reported, not diagnosed: shaft harmonics f_r, 2f_r, 3f_r
detected in most views ("looseness or shaft modulation"), and lines at the harmonics of 50 or
60 Hz supply frequency in the raw view ("electrical"; where both stand, the frequency whose
lines are stronger in sum: a machine has one supply).

**Decision and confidence.**

* a speed the record refutes → ``uncertain`` (0), the leading family and ``p`` kept
  (sixteenth session): the fault lines are searched within ``tol_rel`` (1 %) of the speed
  given; when the comb of ten shaft harmonics that stands highest within ±15 % of it
  (:func:`.contact_angle.shaft_speed_comb`) lies further away and stands
  :data:`.contact_angle.COMB_PROMINENCE_DB` out and :data:`.contact_angle.COMB_GAIN_DB` over
  the comb at the speed given,
  the lines were searched at the wrong speed (record 132 at ``--rpm 1797`` instead of its
  1750 r/min read "ball" at 0.90, its 2×BPFO taken for 7 f_r);
* no candidate family but a family's whole pattern in one view → ``uncertain`` (0), with a
  note naming the view (sixteenth session; ``none`` before, with confidence 0, e.g. a
  simulation without slip whose BPFO series at 56 dB only the raw view keeps: DRS removes a
  strictly periodic impulse train and CPW whitens it);
* no candidate family and fault lines in at most one view → ``none`` with the confidence of
  :func:`.diagnosis.diagnose` (``clip((12 dB - strongest fault-line SNR) / 10 dB, 0, 1)``);
* no family supported but isolated fault lines in at least two views → ``uncertain`` (0);
  fault lines in one view only count as noise (five views search about five times as many
  lines as one);
* otherwise the probability that the leading family is the fault is
  ``p = 1 / (1 + exp(-b margin))`` (:class:`Calibration`, :data:`CALIBRATION`; no intercept:
  at zero margin two families are equally supported and the leading one is right at most half
  the time — with a free intercept a development set with few wrong answers puts ``p(0)`` near
  0.8, a confident guess between two tied families; the slope ``b`` is fitted by
  ``scripts/calibrate_diagnosis.py`` on the CWRU development set; the leave-one-mounting-out
  evaluation is in ``docs/validation.md``). ``p >= 0.5`` → the leading family with confidence
  ``p``; below → ``uncertain`` (confidence 0), the leading family and ``p`` kept in the result.
  Without an intercept ``p`` falls below 0.5 only when the margin is negative (a family that
  is no candidate outscores the leading one); "uncertain" otherwise comes from the rule (no
  candidate in two views), not from the calibration.
* **agreement**: the leading family must be the reading of at least one method on its own (the
  single-view rule of :func:`.diagnosis.diagnose_spectrum`, whose harmonic amplitudes must
  dominate the other families' twice over; for ``ball`` also the cage pattern). Otherwise the
  methods disagree — the fused score leads with a family that no method concludes, e.g. when
  an outer-race series and its shaft-order modulation read as a BPFI series of comparable
  strength in every view — and the verdict is ``uncertain`` (confidence 0), the leading family
  and ``p`` kept. This mirrors Smith & Randall's grading, in which a record is diagnosable when
  at least one of their methods diagnoses it.

Every ``uncertain`` verdict says why in :attr:`FusedDiagnosis.why` (the deciding rule's note).

The rule never looks at the file name or the expected answer.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any

import numpy as np
from numpy.typing import ArrayLike

from ..errors import ConfigError, check_positive
from ..geometry import Bearing
from .benchmark import cepstral_prewhitening, discrete_random_separation
from .coherence import MIN_WINDOW as COHERENCE_MIN_WINDOW
from .coherence import cyclic_modulation_coherence
from .diagnosis import (
    FAMILIES,
    FAMILY_LINE,
    Diagnosis,
    DiagnosisRule,
    diagnose_spectrum,
    min_band_width,
)
from .envelope import BandEnvelopes, check_band
from .kurtogram import Infogram, Kurtogram, band_maps
from .peaks import match_peaks
from .spectrum import Domain, Spectrum, as_signal

__all__ = [
    "CALIBRATION",
    "Calibration",
    "FusedDiagnosis",
    "VIEWS",
    "View",
    "diagnose_fused",
    "fit_calibration",
    "view_scores",
]

#: the five views, in order
VIEWS = ("raw", "cpw", "drs_sk", "drs_info", "csc")
#: what each view is
VIEW_TEXT = {
    "raw": "squared envelope spectrum of the raw signal (Smith & Randall 2015 method 1)",
    "cpw": "squared envelope spectrum after cepstral pre-whitening (method 2)",
    "drs_sk": "DRS, spectral-kurtosis band, squared envelope spectrum (method 3, benchmark)",
    "drs_info": "DRS, spectral-infogram band, squared envelope spectrum (Antoni 2016)",
    "csc": "DRS, cyclic spectral coherence averaged over all carriers: enhanced envelope "
    "spectrum (Antoni, Xin & Hamzaoui 2017)",
}
#: views in which a family must be supported (or FTF detected, for the cage-modulation pattern of
#: a ball fault) to be a candidate: one method alone is not evidence [-]
MIN_VIEWS = 2
#: supply frequencies whose harmonics are reported as electrical lines [Hz]
SUPPLY_HZ = (50.0, 60.0)


@dataclass(frozen=True)
class Calibration:
    """Logistic map from the fused margin to the probability that the leading family is right.

    Attributes
    ----------
    intercept, slope : float
        ``p = 1 / (1 + exp(-(intercept + slope margin)))`` [-].
    fitted_on : str
        Records it was fitted on.
    command : str
        Command that fitted it.
    """

    intercept: float
    slope: float
    fitted_on: str = ""
    command: str = ""

    def __call__(self, margin: float) -> float:
        """Probability [-] for a margin [-]."""
        z = self.intercept + self.slope * float(margin)
        return float(1.0 / (1.0 + math.exp(-max(min(z, 50.0), -50.0))))


#: the shipped calibration (``scripts/calibrate_diagnosis.py``; see the module docstring)
CALIBRATION = Calibration(
    intercept=0.0,
    slope=4.8585,
    fitted_on="the 24 CWRU 0.014 in records (development set, ../shared/data/cwru) with a "
    "leading family",
    command="python scripts/calibrate_diagnosis.py",
)


@dataclass(frozen=True)
class View:
    """One method's squared envelope spectrum and what it shows.

    Attributes
    ----------
    name : str
        One of :data:`VIEWS`.
    band : tuple[float, float]
        Band of the envelope [Hz or orders].
    diagnosis : Diagnosis
        Lines and the single-view rule's reading (:func:`.diagnosis.diagnose_spectrum`).
    scores : dict[str, float]
        Family scores in this view (0 where not supported) [-].
    supported : list[str]
        Families supported in this view.
    cage : bool
        The cage-modulation pattern of a ball fault holds in this view (FTF detected, no family
        supported).
    """

    name: str
    band: tuple[float, float]
    diagnosis: Diagnosis
    scores: dict[str, float]
    supported: list[str]
    cage: bool = False

    def names(self, family: str) -> bool:
        """This method's own reading is ``family``: the single-view rule's verdict
        (:func:`.diagnosis.diagnose_spectrum`), or for ``"ball"`` also the cage pattern."""
        return self.diagnosis.diagnosis == family or (family == "ball" and self.cage)

    def as_dict(self) -> dict[str, Any]:
        """JSON-ready summary: band, supported families, scores and the detected lines."""
        return {
            "method": self.name,
            "what": VIEW_TEXT[self.name],
            "band_hz": list(self.band),
            "supported": self.supported,
            "scores": self.scores,
            "lines": [
                {"label": p.label, "freq_hz": p.freq_hz, "order": p.order, "snr_db": p.snr_db}
                for p in self.diagnosis.peaks
                if p.detected
            ],
        }


#: SNR above the detection threshold at which a line's quality stops growing [dB]
Q_SPAN_DB = 40.0


def _q(p, threshold_db: float) -> float:
    """Line quality: 0 undetected, 0.5 at the threshold, +0.5 per 20 dB above it, up to 1.5
    (:data:`Q_SPAN_DB` above)."""
    if p is None or not p.detected:
        return 0.0
    return 0.5 + 0.5 * min(max((p.snr_db - threshold_db) / 20.0, 0.0), Q_SPAN_DB / 20.0)


def view_scores(d: Diagnosis, rule: DiagnosisRule) -> tuple[dict[str, float], list[str], bool]:
    """Family scores of one view (module docstring, "Patterns").

    Returns
    -------
    scores : dict
        Family -> score where supported, else 0 [-].
    supported : list of str
        Supported families (the ball family by its 2×BSF series only).
    cage : bool
        FTF detected and no family supported in this view (the cage-modulation pattern; its
        score is then ``scores["ball"]``).
    """
    by = {p.label: p for p in d.peaks}
    t = rule.threshold_db
    base = FAMILY_LINE
    side = {
        "outer": [],
        "inner": ["BPFI-fr", "BPFI+fr", "2xBPFI-fr", "2xBPFI+fr"],
        "ball": ["2xBSF-FTF", "2xBSF+FTF", "2x2xBSF-FTF", "2x2xBSF+FTF"],
    }
    scores: dict[str, float] = {}
    supported: list[str] = []
    for fam in FAMILIES:
        labels = [base[fam] if h == 1 else f"{h}x{base[fam]}" for h in (1, 2, 3)]
        q = [_q(by.get(lab), t) for lab in labels]
        n_sb = sum(1 for lab in side[fam] if lab in by and by[lab].detected)
        ok = q[0] > 0 and sum(v > 0 for v in q) >= 2 and (fam != "inner" or n_sb >= 1)
        scores[fam] = float(np.mean(q)) + rule.sideband_weight * n_sb if ok else 0.0
        if ok:
            supported.append(fam)
    cage = _q(by.get("FTF"), t) > 0 and not supported
    if cage:
        scores["ball"] = 0.5 * (_q(by.get("FTF"), t) + _q(by.get("2xFTF"), t))
    return scores, supported, cage


@dataclass(frozen=True)
class FusedDiagnosis:
    """Result of :func:`diagnose_fused`.

    Attributes
    ----------
    diagnosis : str
        ``"outer"``, ``"inner"``, ``"ball"``, ``"none"`` or ``"uncertain"``.
    confidence : float
        Calibrated probability that the verdict is right (0 for ``uncertain``) [-].
    leading : str or None
        The supported family with the largest fused score.
    probability : float or None
        Calibrated probability that ``leading`` is the fault [-].
    margin : float
        Fused score of ``leading`` minus the largest other family's [-].
    scores : dict[str, float]
        Fused family scores [-].
    views : list[View]
        The methods' evidence.
    shaft_hz : float
        Shaft frequency [Hz] (1 in the order domain).
    non_bearing : dict[str, Any]
        Shaft harmonics and supply-frequency lines seen (not bearing faults).
    notes : list[str]
        Reasoning.
    domain : Domain
        Abscissa of the spectra.
    kurtogram, infogram : Kurtogram, Infogram or None
        The band maps of the DRS random part (None when the band was given).
    calibration : Calibration or None
        The margin-to-probability map that was used (None: uncalibrated).
    why : str
        Why the verdict is ``uncertain`` (the rule that decided it; also among ``notes``),
        empty otherwise.
    speed_unchecked : str
        In the order domain, a note where the tracked record's shaft comb cannot judge the
        speed it was tracked with (no comb 20 dB out near order 1), empty otherwise
        (``analyze``'s ``rpm_unchecked``).
    """

    diagnosis: str
    confidence: float
    leading: str | None
    probability: float | None
    margin: float
    scores: dict[str, float]
    views: list[View]
    shaft_hz: float
    non_bearing: dict[str, Any] = field(default_factory=dict)
    notes: list[str] = field(default_factory=list)
    domain: Domain = Domain.HZ
    kurtogram: Kurtogram | None = None
    infogram: Infogram | None = None
    calibration: Calibration | None = None
    why: str = ""
    speed_unchecked: str = ""

    @property
    def methods_agree(self) -> bool:
        """At least one method reads :attr:`leading` on its own (:meth:`View.names`; module
        docstring, "agreement"); False without a leading family."""
        return self.leading is not None and _agree(self.views, self.leading)

    @property
    def best_view(self) -> View:
        """The view with the largest score of the verdict's (or leading) family among those
        that support it (all views when none does: a view scoring the family without its
        whole pattern showed a "ball" verdict by FTF lines alone)."""
        fam = self.diagnosis if self.diagnosis in FAMILIES else self.leading
        if fam is None:  # the benchmark method's view (the kurtogram band), else the first
            by_name = {v.name: v for v in self.views}
            return by_name.get("drs_sk", self.views[0])
        views = [v for v in self.views if fam in v.supported] or self.views
        return max(views, key=lambda v: v.scores.get(fam, 0.0))

    @property
    def band_hz(self) -> tuple[float, float]:
        """Band of :attr:`best_view` [Hz or orders]."""
        return self.best_view.band

    @property
    def peaks(self):
        """Lines of :attr:`best_view`, without the shaft-harmonic cursors above 3 f_r (those
        only decide which family a line belongs to; :attr:`views` keeps them)."""
        return [p for p in self.best_view.diagnosis.peaks if not _cursor(p.label)]

    @property
    def spectrum(self) -> Spectrum:
        """Squared envelope spectrum of :attr:`best_view`."""
        return self.best_view.diagnosis.spectrum

    def as_dict(self) -> dict[str, Any]:
        """JSON-ready summary (the ``analyze --json`` object)."""
        return {
            "diagnosis": self.diagnosis,
            "confidence": self.confidence,
            "leading": self.leading,
            "probability": self.probability,
            "margin": self.margin,
            "methods_agree": self.methods_agree,
            "scores": self.scores,
            "band_hz": list(self.band_hz),
            "method": self.best_view.name,
            "shaft_hz": self.shaft_hz,
            "peaks": [p.as_dict() for p in self.peaks],
            "evidence": [v.as_dict() for v in self.views],
            "non_bearing": self.non_bearing,
            "calibration": None
            if self.calibration is None
            else {
                "intercept": self.calibration.intercept,
                "slope": self.calibration.slope,
                "fitted_on": self.calibration.fitted_on,
            },
            "domain": self.domain.value,
            "why": self.why,
            "notes": self.notes,
        }

    def plot(self, title: str = "", f_max: float | None = None, unit: str | None = None):
        """Envelope spectrum of :attr:`best_view` with its lines marked (see
        :meth:`.diagnosis.Diagnosis.plot`): a squared envelope spectrum [unit^2], or for the
        ``csc`` view the enhanced envelope spectrum (a coherence [-]); returns the Figure."""
        from dataclasses import replace

        v = self.best_view
        shown = replace(v.diagnosis, peaks=self.peaks)  # without the shaft cursors
        if v.name == "csc":
            what, u, quantity = "enhanced envelope spectrum", "-", "mean cyclic coherence"
        else:
            what, u = "squared envelope spectrum", f"({unit})^2" if unit else None
            quantity = "squared-envelope amplitude"
        dom = "Hz" if self.domain is Domain.HZ else "orders"
        view = f"{v.name}: {what}, band {v.band[0]:.0f}-{v.band[1]:.0f} {dom}"
        fig = shown.plot(
            title=f"{title}\n{view}"
            if title
            else f"{view}: {self.diagnosis} ({self.confidence:.2f})",
            f_max=f_max,
            unit=u,
            quantity=quantity,
        )
        if v.name == "csc":  # its abscissa is the cyclic frequency of the coherence
            fig.axes[0].set_xlabel(f"cyclic frequency [{dom}]")
        return fig


def diagnose_fused(
    x: ArrayLike,
    fs: float,
    bearing: Bearing,
    shaft_hz: float,
    *,
    band: tuple[float, float] | None = None,
    rule: DiagnosisRule | None = None,
    domain: Domain | str = Domain.HZ,
    calibration: Calibration | None = CALIBRATION,
    supply_hz: tuple[float, ...] = SUPPLY_HZ,
    stated_hz: float | None = None,
    speed_from: str = "--rpm",
) -> FusedDiagnosis:
    """Fused diagnosis of ``x`` (module docstring).

    Parameters
    ----------
    x : array_like
        Vibration signal (acceleration, any unit).
    fs : float
        Sample rate [Hz] (samples per revolution in the order domain).
    bearing : Bearing
        Geometry for the characteristic frequencies.
    shaft_hz : float
        Shaft frequency [Hz] (1 in the order domain).
    band : (lo, hi), optional
        Envelope band for every method [Hz], at least :func:`min_band_width` wide (else a
        one-line error: a narrower envelope cannot hold the lines the rule reads); default:
        whole band for methods 1–2, the kurtogram and infogram bands for the DRS views.
    rule : DiagnosisRule, optional
        Line search (default: the documented one with shaft cursors).
    domain : Domain
        :attr:`Domain.HZ` or :attr:`Domain.ORDER`.
    calibration : Calibration or None
        Margin-to-probability map; ``None`` leaves ``probability`` unset and gives the leading
        family with confidence 0 (used to fit the calibration).
    supply_hz : tuple of float
        Supply frequencies whose lines are searched and noted [Hz] (default 50 and 60 Hz; a
        simulation's: those its rig adds as fixed tones, usually none).
    stated_hz : float, optional
        The speed the record's file states [Hz] where ``shaft_hz`` overrides it: shaft
        harmonics that confirm it and refute ``shaft_hz`` make the verdict "uncertain"
        (:func:`.contact_angle.refuted_speed`).
    speed_from : str
        Where ``shaft_hz`` came from, for the reason of a refuted speed ("check --rpm").
    """
    from ..catalog import as_bearing
    from ..geometry import parse_enum

    bearing = as_bearing(bearing)
    rule = rule or DiagnosisRule(shaft_cursors=True)
    domain = parse_enum(Domain, domain, "domain")
    a = as_signal(x, peak_range=PEAK_RANGE)
    fs = check_positive("fs_hz", fs, "Hz")
    shaft_hz = check_positive("shaft_hz", shaft_hz, "Hz")
    min_bw = min_band_width(bearing, shaft_hz, fs, rule)
    if band is not None:
        band = check_band(band, fs, orders=domain is Domain.ORDER)
        if band[1] - band[0] < min_bw:  # its envelope cannot hold the lines the rule reads
            raise ConfigError(
                f"band = ({band[0]:.6g}, {band[1]:.6g}) Hz is {band[1] - band[0]:.6g} Hz wide, "
                f"too narrow for the fault lines ({rule.n_harmonics} harmonics of the highest "
                f"and the shaft sidebands); valid: a band at least {min_bw:.6g} Hz wide"
            )
    whole = band or (0.0, 0.5 * fs)
    rnd, _det = discrete_random_separation(a)
    ses_rnd = BandEnvelopes(rnd, fs, domain)
    kg = ig = None
    if band is None:
        kg, ig = band_maps(rnd, fs, min_bandwidth_hz=min_bw, alpha_max_hz=min_bw, spectrum=ses_rnd)
        b_sk, b_info = kg.band, ig.band
    else:
        b_sk = b_info = band
    ses_raw = BandEnvelopes(a, fs, domain)
    ses_cpw = BandEnvelopes(cepstral_prewhitening(a), fs, domain)
    spectra = {
        "raw": (whole, ses_raw.squared_spectrum(whole)),
        "cpw": (whole, ses_cpw.squared_spectrum(whole)),
        "drs_sk": (b_sk, ses_rnd.squared_spectrum(b_sk)),
    }
    if band is None:
        spectra["drs_info"] = (b_info, ses_rnd.squared_spectrum(b_info))
    skipped = []
    if min_bw <= fs / COHERENCE_MIN_WINDOW:
        csc = cyclic_modulation_coherence(rnd, fs, min_bw, carrier_band=band)
        spectra["csc"] = (csc.band, csc.enhanced_envelope_spectrum(domain))
    else:  # no window of >= 8 samples passes the highest line: the other views still can
        u = "Hz" if domain is Domain.HZ else "orders"
        skipped.append(
            f"csc: not run, the sample rate {fs:.6g} {'Hz' if u == 'Hz' else 'per rev'} is "
            f"below {COHERENCE_MIN_WINDOW} x the highest line read ({min_bw:.6g} {u}); the "
            "other views decide"
        )
    views: list[View] = []
    for name, (b, es) in spectra.items():
        d = diagnose_spectrum(es, bearing, shaft_hz, b, rule=rule)
        views.append(View(name, b, d, *view_scores(d, rule)))
    from .contact_angle import padded_spectrum

    raw_sp = padded_spectrum(a, fs) if domain is Domain.HZ else None  # read twice below
    kin_notes = _kinematic_check(
        views, spectra, _measured_speed(raw_sp, fs, shaft_hz), bearing, shaft_hz, rule
    )
    unchecked = ""
    if domain is Domain.HZ:
        refuted = _speed_refuted(raw_sp, fs, shaft_hz, rule, stated_hz)
    else:
        refuted, unchecked = _order_refuted(a, fs, rule, speed_from)
    cage_views = sum(v.cage for v in views)
    nv = len(views)
    fused = {}
    supported = []
    for fam in FAMILIES:
        fused[fam] = float(sum(v.scores[fam] for v in views) / nv)
        if sum(fam in v.supported for v in views) >= min(MIN_VIEWS, nv):
            supported.append(fam)
    if "ball" not in supported and cage_views >= min(MIN_VIEWS, nv):
        supported.append("ball")
    non_bearing = _non_bearing(views, ses_raw, shaft_hz, domain, rule, supply_hz)
    notes = (
        [
            f"{v.name}: band {v.band[0]:.6g}-{v.band[1]:.6g}, supported "
            f"{', '.join(v.supported) or 'nothing'}, scores "
            + ", ".join(f"{f} {v.scores[f]:.2f}" for f in FAMILIES)
            for v in views
        ]
        + skipped
        + kin_notes
    )
    if kg is not None:
        notes.append(f"kurtogram of the DRS random part: kurtosis {kg.max_kurtosis:.3g}")
    if ig is not None:
        notes.append(f"infogram of the DRS random part: spectral negentropy {ig.max_spectral:.3g}")
    notes += non_bearing.get("notes", [])

    def _res(diag, conf, leading=None, prob=None, margin=0.0):
        why = notes[-1] if diag == "uncertain" else ""  # the deciding rule's note, last
        return FusedDiagnosis(diag, conf, leading, prob, margin, fused, views, shaft_hz,
                              non_bearing, notes, domain, kg, ig, calibration, why,
                              unchecked)  # fmt: skip

    top = max(supported, key=lambda f: fused[f]) if supported else None
    margin = fused[top] - max(fused[f] for f in FAMILIES if f != top) if top else 0.0
    if refuted is not None:
        # the line search looks within tol_rel of the speed given: at another speed its
        # windows miss the fault lines and may take others (a record's 2xBPFO read as 7 f_r)
        p = calibration(margin) if top is not None and calibration is not None else None
        f_rec = refuted.shaft_hz
        how = (
            f"its harmonics between those of the speed used stand {refuted.prominence_db:.0f} "
            "dB out"
            if refuted.between > 1
            else f"a comb of 10 stands {refuted.gain_db:.0f} dB over the one at the speed used"
        )
        off = f"{100.0 * (shaft_hz / f_rec - 1.0):+.2f} %"
        if domain is Domain.HZ:
            named = (
                f"{60.0 * f_rec:.6g} r/min ({how}); the {60.0 * shaft_hz:.6g} r/min used is "
                f"{off} off it"
            )
        else:  # order tracked: the comb stands at an order of the speed tracked with
            named = (
                f"order {f_rec:.5g} of the speed tracked with ({how}); that speed is {off} off "
                "the record's"
            )
        wrong = "speed" if domain is Domain.HZ else "orders"
        notes.append(
            f"{SPEED_REFUTED} {named}, beyond the line search's ±{100.0 * rule.tol_rel:g} %: the "
            f"fault lines were searched at the wrong {wrong} (check {speed_from})"
        )
        return _res("uncertain", 0.0, top, p, margin)
    if not supported:
        alone = [(v.name, f) for v in views for f in v.supported]
        if alone:  # a family's whole pattern in one view: not "none", not a candidate either
            notes.append(
                "no candidate family: "
                + ", ".join(f"{f} supported in the {n} view only" for n, f in alone)
                + f" (a candidate needs {min(MIN_VIEWS, nv)} views)"
                + (
                    "; DRS removes and CPW whitens a strictly periodic impulse train (e.g. a "
                    "simulation without slip), so only the raw view may show it"
                    if any(n == "raw" for n, _ in alone)
                    else ""
                )
            )
            return _res("uncertain", 0.0)
        n_det = sum(any(p.detected and _series(p.label) for p in v.diagnosis.peaks) for v in views)
        if n_det >= min(MIN_VIEWS, nv):
            notes.append(
                f"fault lines in {n_det} views, but no family's whole pattern (fundamental and a "
                "harmonic; for inner also a shaft sideband) in any"
            )
            return _res("uncertain", 0.0)
        fault_snr = [
            p.snr_db
            for v in views
            for p in v.diagnosis.peaks
            if _series(p.label) and np.isfinite(p.snr_db)
        ]
        best = max(fault_snr, default=-math.inf)
        return _res("none", float(min(max((rule.threshold_db - best) / 10.0, 0.0), 1.0)))
    if calibration is None:
        notes.append("no calibration: the leading family and its margin, without a verdict")
        return _res("uncertain", 0.0, top, None, margin)
    p = calibration(margin)
    if not _agree(views, top):
        # a family that scores higher but is no candidate: say why it does not lead (the
        # scores alone read as a contradiction; exploratory testing, twenty-fifth session)
        above = [
            f"{f} scores higher ({fused[f]:.2f}) but is supported in "
            f"{sum(f in v.supported for v in views)} view(s), a candidate needs "
            f"{min(MIN_VIEWS, nv)}"
            for f in FAMILIES
            if f not in supported and fused[f] > fused[top]
        ]
        notes.append(
            f"leading family {top} (margin {margin:.3f}, p {p:.2f}) is no method's own reading ("
            + ", ".join(f"{v.name} {v.diagnosis.diagnosis}" for v in views)
            + (  # every method undecided is not a disagreement (exploratory testing)
                "): no method settles on a family"
                if all(v.diagnosis.diagnosis == "uncertain" for v in views)
                else "): the methods disagree"
            )
            + "".join(f"; {t}" for t in above)
        )
        return _res("uncertain", 0.0, top, p, margin)
    if p >= 0.5:
        return _res(top, p, top, p, margin)
    notes.append(
        f"leading family {top} (margin {margin:.3f}) has calibrated probability {p:.2f} < 0.5"
    )
    return _res("uncertain", 0.0, top, p, margin)


#: the range of a signal's peak magnitude the fused diagnosis takes [-]: the square root of the
#: signal functions' (:data:`.spectrum.PEAK_RANGE`), since its squared envelopes square the
#: signal (a peak of 2.9e-59 was refused as "a peak magnitude of 8.8e-118", one of 1e80 as
#: "non-finite values"; both lie inside 1e-100-1e100)
PEAK_RANGE = (1e-45, 1e45)


#: tolerance of the kinematic check [spectral resolutions]: each found line is the bin of
#: its largest amplitude (half a resolution off at most) and the speed varies over a record
KINEMATIC_TOL = 3.0


#: how the reason of an "uncertain" whose speed the record's shaft lines refute begins (its
#: caller knows the speed was wrong: ``analyze`` gives no cage-revolution note then)
SPEED_REFUTED = "the record's shaft harmonics put the speed at"


def refuted_rpm(why: str | None) -> float | None:
    """The record's own speed [r/min] that a reason beginning with :data:`SPEED_REFUTED`
    names, else None."""
    import re

    m = re.search(re.escape(SPEED_REFUTED) + r" ([0-9.eE+-]+) r/min", why or "")
    return float(m.group(1)) if m else None


def _measured_speed(raw_sp, fs, shaft_hz) -> float | None:
    """The shaft speed [Hz] measured from the record's shaft harmonics within ±0.5 % of
    ``shaft_hz`` (:func:`.contact_angle.measured_shaft_hz` on ``raw_sp``, the record's
    :func:`.contact_angle.padded_spectrum`); exactly 1 in the order domain (``raw_sp`` None),
    None where no three harmonics stand out (a simulation, most short records)."""
    from .contact_angle import measured_shaft_hz

    if raw_sp is None:
        return 1.0
    try:
        return measured_shaft_hz(None, fs, shaft_hz, spectrum=raw_sp)[0]
    except ConfigError:
        return None


def _speed_refuted(raw_sp, fs, shaft_hz, rule, stated_hz=None):
    """:func:`.contact_angle.refuted_speed` of the record (``raw_sp``, its
    :func:`.contact_angle.padded_spectrum`) beyond ``rule.tol_rel``, ``stated_hz`` the speed
    its file states [Hz]; None in the order domain (``raw_sp`` None)."""
    from .contact_angle import refuted_speed

    if raw_sp is None:
        return None
    return refuted_speed(
        None, fs, shaft_hz, tol_rel=rule.tol_rel, spectrum=raw_sp, stated_hz=stated_hz
    )


def _order_refuted(a, fs, rule, speed_from: str = "the speed"):
    """``(refuted, unchecked)`` of an order-tracked record ``a`` (``fs`` samples per
    revolution): :func:`.contact_angle.refuted_speed` at order 1, a shaft comb standing at
    another order (beyond ``rule.tol_rel``) saying the speed it was tracked with is off the
    record's own, as a ``--rpm`` is judged in Hz (twenty-eighth session: a speed column 4 %
    high and drifting over 1 % was tracked unchecked; 172 read "ball" 0.94); and where that
    does not refute it, a note when no comb near order 1 stands out enough to judge it
    (:func:`.contact_angle.unchecked_speed_note`; a later helper of the session: columns 5-10
    % off read "ball" 0.6-0.9 with their comb 9-19.6 dB out, without a word), else ``""``.
    Supply lines sit at no fixed order and are far above the comb's orders."""
    from .contact_angle import padded_spectrum, refuted_speed, unchecked_order_note

    spec = padded_spectrum(a, fs)
    c = refuted_speed(None, fs, 1.0, tol_rel=rule.tol_rel, spectrum=spec)
    if c is not None:
        return c, ""
    return None, unchecked_order_note(spec, fs, speed_from) or ""


def _kinematic_check(views, spectra, fr, bearing, shaft_hz, rule) -> list[str]:
    """One cage speed (module docstring, "Kinematic check"): in a view where the outer- and
    the inner-race fundamentals are both detected, ``BPFO = Z f_c`` and ``BPFI = Z (f_r -
    f_c)`` must share the cage speed ``f_c``, i.e. ``f_o + f_i = Z f_r`` whatever the contact
    angle and the cage slip. Where they do not (beyond :data:`KINEMATIC_TOL` resolutions), the
    lines of the race family supported in fewer views are not counted in that view (nothing
    when both are supported in as many). ``views`` is updated in place; returns notes.
    ``fr`` is the measured shaft speed [Hz or orders] (:func:`_measured_speed`; None: not
    measured, and the check is not made)."""
    pairs = []
    for i, v in enumerate(views):
        by = {p.label: p for p in v.diagnosis.peaks}
        o, n = by.get("BPFO"), by.get("BPFI")
        if o is not None and n is not None and o.detected and n.detected:
            pairs.append((i, o.freq_hz, n.freq_hz))
    if not pairs:
        return []
    z = bearing.n_elements
    if fr is None:  # no shaft lines to measure the speed: the check cannot be made
        return ["kinematic check not made: the shaft speed could not be measured"]
    support = {f: sum(f in v.supported for v in views) for f in ("outer", "inner")}
    if support["outer"] == support["inner"]:
        return []
    loser = "inner" if support["outer"] > support["inner"] else "outer"
    notes = []
    for i, fo, fi in pairs:
        v = views[i]
        es = spectra[v.name][1]
        off = fo + fi - z * fr
        if abs(off) <= KINEMATIC_TOL * es.resolution:
            continue
        d = diagnose_spectrum(es, bearing, shaft_hz, v.band, rule=rule, drop=frozenset({loser}))
        views[i] = View(v.name, v.band, d, *view_scores(d, rule))
        notes.append(
            f"{v.name}: BPFO {fo:.4g} + BPFI {fi:.4g} is {off:+.3g} off Z f_r = {z * fr:.5g} "
            f"(more than {KINEMATIC_TOL:g} resolutions): no one cage speed; the {loser}-race "
            f"lines (its family supported in fewer views) are not counted here"
        )
    return notes


def _agree(views: list[View], family: str) -> bool:
    """The agreement rule (module docstring): some method reads ``family`` on its own."""
    return any(v.names(family) for v in views)


def _cursor(label: str) -> bool:
    """A shaft-harmonic cursor line ``kxfr`` with k > 3 (:attr:`DiagnosisRule.shaft_cursors`)."""
    head, _, rest = label.partition("x")
    return rest == "fr" and head.isdigit() and int(head) > 3


def _series(label: str) -> bool:
    """A harmonic of BPFO, BPFI or 2×BSF (not a sideband, FTF or shaft line)."""
    if "-" in label or "+" in label:
        return False
    return label.endswith(("BPFO", "BPFI", "2xBSF"))


def _non_bearing(views, ses_raw, shaft_hz, domain, rule, supply_hz=SUPPLY_HZ) -> dict[str, Any]:
    """Shaft harmonics and supply-frequency lines (module docstring)."""
    shaft_views = 0
    for v in views:
        by = {p.label: p for p in v.diagnosis.peaks}
        if sum(1 for lab in ("fr", "2xfr", "3xfr") if lab in by and by[lab].detected) >= 2:
            shaft_views += 1
    out: dict[str, Any] = {"shaft_harmonic_views": shaft_views, "supply_lines": []}
    notes = []
    if shaft_views > len(views) // 2:
        notes.append(
            "shaft harmonics f_r, 2f_r, 3f_r in most views: looseness or shaft modulation "
            "(not by itself a bearing fault)"
        )
    if domain is Domain.HZ:
        es = views[0].diagnosis.spectrum
        by_f0: list[list[dict[str, Any]]] = []  # the lines of each supply frequency
        for f0 in supply_hz:
            found: list[dict[str, Any]] = []
            tg = [(f"{h}x{f0:g}Hz", h * f0) for h in (1, 2) if h * f0 < es.freq[-1]]
            # a supply line is only told apart from a shaft harmonic when it is > 1 % away
            tg = [t for t in tg if abs(t[1] / shaft_hz - round(t[1] / shaft_hz)) * shaft_hz
                  > 0.01 * t[1]]  # fmt: skip
            # the supply's frequency is exact: within 0.2 % or half a bin (a short record's
            # bins are coarse: the default two-bin floor let BPFO at 107 Hz pass for 2x50 Hz
            # in 0.3 s), and a line, not the skirt of a stronger one beside it
            for p in match_peaks(
                es, tg, shaft_hz, tol_rel=0.002, tol_min_bins=0.5, threshold_db=rule.threshold_db
            ):
                k = int(np.argmin(np.abs(es.freq - p.freq_hz)))
                line = es.amplitude[k] >= es.amplitude[max(k - 1, 0) : k + 2].max()
                if p.detected and line:
                    found.append({"label": p.label, "snr_db": p.snr_db})
            if found:
                by_f0.append(found)
        # a machine has one supply: where lines of both frequencies stand, the one whose
        # lines are stronger in sum (the other's are chance lines of the envelope)
        if by_f0:
            out["supply_lines"] = max(by_f0, key=lambda ls: sum(d["snr_db"] for d in ls))
        if out["supply_lines"]:
            notes.append(
                "supply-frequency lines in the raw envelope: "
                + ", ".join(d["label"] for d in out["supply_lines"])
                + " (electrical, not a bearing fault)"
            )
    out["notes"] = notes
    return out


#: L2 penalty on the logistic slope of :func:`fit_calibration` [-]: with a few dozen records the
#: classes are often separable and the unpenalised slope would be infinite (every probability 0
#: or 1); the penalty is a Gaussian prior of standard deviation ``1/sqrt(CALIBRATION_L2)`` = 3.2
CALIBRATION_L2 = 0.1


def fit_calibration(
    margins: ArrayLike, correct: ArrayLike, *, l2: float = CALIBRATION_L2, fitted_on: str = ""
) -> Calibration:
    """Penalised logistic fit (slope only, no intercept: module docstring) of "the leading
    family is right" against the fused margin.

    Parameters
    ----------
    margins : array_like
        Fused margins of the records [-].
    correct : array_like of bool
        Whether each record's leading family is its true fault.
    l2 : float
        Penalty on the slope (:data:`CALIBRATION_L2`) [-].
    fitted_on : str
        Description of the records, kept in the result.
    """
    from scipy.optimize import minimize

    m = np.asarray(margins, dtype=float)
    y = np.asarray(correct, dtype=float)
    if m.ndim != 1 or m.shape != y.shape or m.size < 2:
        raise ConfigError(
            f"margins and correct must be 1-D of the same length >= 2; got {m.shape}, {y.shape}"
        )
    if not np.all(np.isfinite(m)):
        raise ConfigError("margins contain non-finite values; valid: finite numbers")

    def nll(w):
        z = w[0] * m
        # log(1 + e^z) - y z, stable
        return float(np.sum(np.logaddexp(0.0, z) - y * z) + 0.5 * l2 * w[0] ** 2)

    def grad(w):
        r = 1.0 / (1.0 + np.exp(-w[0] * m)) - y
        return np.array([(r * m).sum() + l2 * w[0]])

    w = minimize(nll, np.zeros(1), jac=grad, method="BFGS").x
    return Calibration(0.0, float(w[0]), fitted_on=fitted_on)
