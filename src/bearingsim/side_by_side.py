"""A simulated fault signal beside a measured record of the same condition (issue 16, item 5,
first version).

For a CWRU fault record: simulate its condition (the record's bearing, shaft speed and sample
rate; the CWRU fault diameter as the defect width, the EDM depth 0.011 in, the ball resting on
the slot's nearer edge, :data:`DEFECT_PROFILE`; the random slip real bearings show,
:data:`SLIP_PERCENT`; rough contacts, :data:`CONTACT_ROUGHNESS_M`; together
:data:`REALISM`; sampled through an anti-aliasing filter) with a ring model or the
bearing-rotor-housing model (the fault in the record's bearing), pass the result through a rig
(:mod:`bearingsim.rig`), and compute the same numbers on both signals with the same code
(:func:`signal_metrics`): RMS, kurtosis, crest factor, fault-line
amplitude and prominence in the envelope spectrum, and the ringing band (fast kurtogram).

Line prominence (issue 16's definition): the envelope-spectrum line at the fault frequency over
the median level of the envelope spectrum in 20-600 Hz [dB]. Each signal's envelope is taken in
its own fast-kurtogram band, as an analyst would. The fault line is BPFO (outer), BPFI (inner)
or 2×BSF (ball: the ring models' ball defect, issue 16 item 2).

What is compared with what: every number is ours (model + rig) against a measurement (the CWRU
record). A rig identified from records of the same mounting as the record judged is system
identification on the judged data; :func:`side_by_side` takes the rig as given, and
``scripts/side_by_side.py`` identifies it without the judged record's fault size
(leave-one-mounting-out).
"""

from __future__ import annotations

import math
from dataclasses import asdict, dataclass, replace
from pathlib import Path

import numpy as np
from numpy.typing import NDArray

from .config import (
    REALISM,
    REALISM_CONTACT_ROUGHNESS_M,
    REALISM_DEFECT_PROFILE,
    REALISM_SLIP_PERCENT,
)
from .errors import ConfigError
from .io.cwru import cwru_bearing, cwru_manifest

__all__ = [
    "CONTACT_ROUGHNESS_M",
    "DEFECT_PROFILE",
    "REALISM",
    "SLIP_PERCENT",
    "SignalMetrics",
    "lomo_rig",
    "rig_other_loads",
    "model_path_fit",
    "model_path_fit_conditions",
    "model_path_scale",
    "model_path_scale_conditions",
    "cwru_row",
    "ratios",
    "rig_without_size",
    "side_by_side",
    "signal_metrics",
    "simulate_record",
]

#: CWRU EDM fault depth [m] (0.011 in, the Case Western Reserve University Bearing Data Center)
CWRU_DEPTH_M = 0.011 * 0.0254
#: the bearing faults a record can be simulated with (and a model gain matched to)
FAULT_FAMILIES = ("outer", "inner", "ball")
#: the realism of a simulation beside a measurement: the random slip [%], the drop profile and
#: the contacts' composite RMS roughness [m] a scenario with a rig takes by default, defined
#: with their sources in :mod:`bearingsim.config` (:data:`~bearingsim.config.REALISM`)
SLIP_PERCENT = REALISM_SLIP_PERCENT
DEFECT_PROFILE = REALISM_DEFECT_PROFILE
CONTACT_ROUGHNESS_M = REALISM_CONTACT_ROUGHNESS_M


@dataclass(frozen=True)
class SignalMetrics:
    """Numbers of one signal (acceleration [m/s^2])."""

    rms: float  #: root mean square [m/s^2]
    kurtosis: float  #: Pearson kurtosis (3 for a Gaussian) [-]
    crest: float  #: largest absolute value over the RMS [-]
    line: float  #: envelope-spectrum amplitude at the fault frequency [m/s^2]
    prominence_db: float  #: that line over the median 20-600 Hz level [dB]
    band_lo_hz: float  #: the envelope band (fast kurtogram), low edge [Hz]
    band_hi_hz: float  #: high edge [Hz]


def signal_metrics(
    x: NDArray[np.float64],
    fs: float,
    fault_hz: float,
    band: tuple[float, float] | None = None,
) -> SignalMetrics:
    """:class:`SignalMetrics` of ``x`` [m/s^2] sampled at ``fs`` [Hz] for the fault frequency
    ``fault_hz`` [Hz] (the envelope-spectrum maximum within +/- 2 % of it, read on the
    spectrum zero padded 8x so that a line between two bins is not read up to 15 % low: a
    helper's exploratory testing, twenty-eighth session; the prominence's median level is the
    unpadded spectrum's), its envelope taken in ``band`` [Hz] (low, high), or by default in the
    signal's own fast-kurtogram band."""
    from scipy.fft import next_fast_len
    from scipy.stats import kurtosis

    from .signal.envelope import envelope
    from .signal.kurtogram import fast_kurtogram
    from .signal.spectrum import amplitude_spectrum

    a = np.asarray(x, dtype=float)
    a = a - a.mean()
    rms = float(np.sqrt(np.mean(a * a)))
    if band is None:
        lo, hi = fast_kurtogram(a, fs, min_bandwidth_hz=max(4.0 * fault_hz, 200.0)).band
    else:
        lo, hi = (float(b) for b in band)
    e = envelope(a, fs, (lo, hi))
    spec = amplitude_spectrum(e, fs)
    f, amp = spec.freq, spec.amplitude
    fine = amplitude_spectrum(e, fs, n_fft=next_fast_len(8 * e.size))
    w = (fine.freq >= 0.98 * fault_hz) & (fine.freq <= 1.02 * fault_hz)
    line = float(fine.amplitude[w].max()) if np.any(w) else math.nan
    base = float(np.median(amp[(f >= 20.0) & (f <= 600.0)]))
    return SignalMetrics(
        rms=rms,
        kurtosis=float(kurtosis(a, fisher=False)),
        crest=float(np.max(np.abs(a)) / rms),
        line=line,
        prominence_db=float(20.0 * np.log10(line / base)) if base > 0 else math.nan,
        band_lo_hz=float(lo),
        band_hi_hz=float(hi),
    )


def simulate_record(
    record: str | Path,
    rig,
    *,
    model: str = "vsm",
    duration_s: float = 2.0,
    seed: int = 0,
    realism: dict | None = None,
) -> dict:
    """Simulate the condition of a CWRU fault record through ``rig``: the two signals and the
    condition (see :func:`side_by_side` for the parameters).

    Returns
    -------
    dict
        ``record``, ``fault``, ``size_in``, ``end``, ``rpm``, ``fs_hz``, ``fault_hz``,
        ``grade``, ``scenario``, ``measured`` and ``simulated`` (the signals [m/s^2], the
        record's first ``duration_s``) and ``background`` (the part of ``simulated`` the rig
        adds whatever the model does: its background, tones and sensor noise with the same
        seed [m/s^2]; ``simulated - background`` is the model's output through the path).
    """
    from . import simulate
    from .catalog import get_bearing
    from .geometry import characteristic_frequencies
    from .io.signal import read_signal
    from .rig import Rig, load_rig

    p = Path(record)
    row = cwru_row(p)
    if row is None:
        raise ConfigError(f"record {p.name!r} is not in {p.parent / 'manifest.csv'}")
    fault = row["fault"].split()[0]
    if fault not in FAULT_FAMILIES:
        raise ConfigError(
            f"record {p.name}: fault {row['fault']!r} cannot be simulated; valid: a record of "
            "an outer-race, inner-race or ball fault"
        )
    end = row["end"]
    rig = rig if isinstance(rig, Rig) else load_rig(rig)
    meas = read_signal(p, channel=end)
    fs = float(meas.fs)
    rpm = float(meas.rpm or row["nominal_rpm"])
    bearing = cwru_bearing(end)
    size_in = float(row["fault_diameter_in"])
    keys = {**REALISM, **(realism or {})}
    common = dict(
        defect_width_m=size_in * 0.0254,
        defect_depth_m=CWRU_DEPTH_M,
        rpm=rpm,
        duration_s=duration_s,
        fs_hz=fs,
        seed=seed,
        antialias=True,  # through a measurement chain: its anti-aliasing filter
    )
    if model == "rotor":
        # the CWRU motor with both bearings; the fault in the record's bearing, the sensor on
        # its housing; the same realism keys (slip, drop profile, rough contacts)
        from .config import RotorScenario

        end_key = "de" if end == "DE" else "fe"
        sc = dict(
            model="rotor",
            **{f"{end_key}_fault": fault},
            **{k: v for k, v in keys.items() if k in RotorScenario.KEYS},
            **common,
        )
        if end == "FE":
            rig = replace(rig, input_channel="acc_y_fe")
    else:
        sc = dict(model=model, bearing=bearing, fault=fault, **keys, **common)
    sensor, background = _through_rig(simulate(sc), rig, seed)
    kin = characteristic_frequencies(get_bearing(bearing), rpm / 60.0)
    fault_hz = {"outer": kin.bpfo_hz, "inner": kin.bpfi_hz, "ball": 2.0 * kin.bsf_hz}[fault]
    n = int(round(duration_s * fs))
    return {
        "record": p.name,
        "fault": fault,
        "size_in": size_in,
        "end": end,
        "rpm": rpm,
        "fs_hz": fs,
        "fault_hz": fault_hz,
        "grade": row.get("smith_randall_grade", ""),
        "scenario": sc,
        "measured": np.asarray(meas.x[:n], dtype=float),
        "simulated": sensor,
        "background": background,
    }


def ratios(measured: SignalMetrics, simulated: SignalMetrics) -> dict[str, float]:
    """Simulated over measured for RMS, kurtosis, crest factor and line [-]; the prominence as
    the difference [dB]."""
    return {
        "rms": simulated.rms / measured.rms,
        "kurtosis": simulated.kurtosis / measured.kurtosis,
        "crest": simulated.crest / measured.crest,
        "line": simulated.line / measured.line,
        "prominence_db": simulated.prominence_db - measured.prominence_db,
    }


def side_by_side(
    record: str | Path,
    rig,
    *,
    model: str = "vsm",
    duration_s: float = 2.0,
    seed: int = 0,
    realism: dict | None = None,
    band: str = "own",
) -> dict:
    """Simulate the condition of a CWRU fault record, pass it through ``rig`` and set the
    numbers of both side by side.

    Parameters
    ----------
    record : path
        A CWRU ``.mat`` file in a folder with its ``manifest.csv``.
    rig : Rig, str or path
        The measurement chain (a :class:`~bearingsim.rig.Rig`, a profile name or a file).
    model : {"vsm", "dem", "tvsm", "rotor"}
        The ring model, or the bearing-rotor-housing model of the CWRU motor (the fault in the
        record's bearing, the rig on that bearing's housing acceleration).
    duration_s : float
        Simulated time [s] (the record's first ``duration_s`` are used too).
    seed : int
        Seed of the rig's random parts and of the slip.
    realism : dict, optional
        Scenario keys replacing those of :data:`REALISM` (``slip_percent`` [%],
        ``defect_profile``, ``contact_roughness_m`` [m]).
    band : {"own", "measured"}
        Where each signal's envelope is taken (the fault line and its prominence): ``own``,
        each signal's own fast-kurtogram band (the default, the tables of
        docs/validation.md); ``measured``, both in the measured record's (one band for both:
        the simulation judged where the record rings).

    Returns
    -------
    dict
        JSON-ready: ``record``, ``fault``, ``size_in``, ``end``, ``rpm``, ``fs_hz``,
        ``fault_hz``, ``grade`` (Smith & Randall's), ``scenario`` (the simulated one), the
        ``measured`` and ``simulated`` :class:`SignalMetrics` (as dicts) and their ``ratio``
        (simulated / measured; prominence as the difference in dB). The signals themselves
        are :func:`simulate_record`'s.
    """
    if band not in ("own", "measured"):
        raise ConfigError(f"band = {band!r} is invalid; valid: own, measured")
    c = simulate_record(
        record,
        rig,
        model=model,
        duration_s=duration_s,
        seed=seed,
        realism=realism,
    )
    m_meas = signal_metrics(c["measured"], c["fs_hz"], c["fault_hz"])
    common = (m_meas.band_lo_hz, m_meas.band_hi_hz) if band == "measured" else None
    m_sim = signal_metrics(c["simulated"], c["fs_hz"], c["fault_hz"], band=common)
    ratio = ratios(m_meas, m_sim)
    return {
        # the signals stay out (the rig's background too: a whole record, not JSON-ready)
        **{k: v for k, v in c.items() if k not in ("measured", "simulated", "background")},
        "measured": asdict(m_meas),
        "simulated": asdict(m_sim),
        "ratio": ratio,
    }


def model_path_scale(
    rig,
    records: list[Path],
    *,
    model: str = "vsm",
    duration_s: float = 1.0,
    realism: dict | None = None,
    progress: bool = False,
):
    """The rig with its path (direct gain and every mode's gain) scaled so that the model's
    output through it carries the power of ``records`` that the rig's background does not
    explain — a model-based gain, the part an output-only identification cannot give (issue
    16, item 4). The background, tones and sensor noise are kept (they are measured levels
    already).

    The scale ``k`` is the power balance over the records (mean-removed signals):

    ``k**2 = sum_r (P_meas,r - P_bg,r) / sum_r P_path,r``

    with ``P_meas`` the record's power, ``P_bg`` the power the rig adds on its own (same seed)
    and ``P_path`` the power of the model's output through the unscaled path [(m/s^2)^2]. On
    one record it gives that record's RMS (to the small cross term of background and path).
    It holds whether the model's output lies above the background (the ring models) or below
    it (the rotor model with its heavy housing): a ratio of total RMS would measure the
    background in the second case and leave the path unscaled.

    Parameters
    ----------
    rig : Rig
        The output-only rig (:func:`bearingsim.rig_identify.identify_rig`).
    records : list of Path
        CWRU fault records of the same mounting (end and sample rate) used to fit the scale
        (healthy records among them are skipped: no fault power to match).
    model : {"vsm", "dem", "tvsm", "rotor"}
        The model.
    duration_s : float
        Simulated time per record [s].
    realism : dict, optional
        Scenario keys replacing those of :data:`REALISM`.
    progress : bool
        A tqdm bar on stderr, one step per record.

    Returns
    -------
    (Rig, float)
        The rig with the scale as its ``[[model_gain]]`` for ``model`` (replacing one it had;
        :meth:`bearingsim.rig.Rig.for_model` applies it) and the scale [-].

    Raises
    ------
    ConfigError
        ``records`` is empty, or the rig's background alone carries as much power as the
        records (nothing left for the path to explain).
    """
    rig = _without_gain(rig, model)
    records = _fault_records(records)
    from tqdm import tqdm

    powers = []
    bar = tqdm(records, desc=f"{model} gain", unit="record", disable=not progress, leave=False)
    for rec in bar:
        c = simulate_record(
            rec,
            rig,
            model=model,
            duration_s=duration_s,
            realism=realism,
        )
        powers.append(_powers(c["measured"], c["simulated"], c["background"]))
    return _with_gain(
        rig, model, powers, [Path(r).name for r in records], duration_s, _profile_of(realism)
    )


def model_path_fit(
    rig,
    records: list[Path],
    *,
    model: str = "vsm",
    duration_s: float = 1.0,
    realism: dict | None = None,
    objective: str = "spectral",
    progress: bool = False,
):
    """The rig with its direct gain and every mode's gain fitted, with the model's output as
    the known input, so that the model through the path plus the rig's background has the
    power spectra of ``records`` (:func:`bearingsim.rig_identify.fit_path_gains`, its
    ``objective``: ``"spectral"``, the shape in decibels and the level by the power balance,
    or ``"whittle"``). Where :func:`model_path_scale` scales the output-only path as a whole (its
    direct gain of 1 kept relative to the modes: the structure output-only data cannot tell),
    this fit weighs the direct path against the modes from the model: what the sensor sees of
    the model's own broadband output.

    The fitted path is the path **for this model** (another model's output has another
    spectrum): it goes in the rig as the model's ``[[model_gain]]`` in its fitted form
    (``path_gain``, ``mode_gains``; :meth:`bearingsim.rig.Rig.for_model` applies it to that
    model's output only), replacing one it had; the output-only path stays for the others.
    Parameters as :func:`model_path_scale`.

    Returns
    -------
    (Rig, PathFit)
        The rig with the fitted ``[[model_gain]]`` and the fit's details.

    Raises
    ------
    ConfigError
        ``records`` is empty or holds no fault record; a record shorter than 1 s.
    """
    from tqdm import tqdm

    from .rig import Rig

    rig = _without_gain(rig, model)
    records = _fault_records(records)
    bare = Rig(name="bare", description="", provenance="the model's output itself",
               input_channel=rig.input_channel)  # fmt: skip
    pairs, rates, rpms = [], set(), []
    bar = tqdm(records, desc=f"{model} path fit", unit="record", disable=not progress,
               leave=False)  # fmt: skip
    for rec in bar:
        c = simulate_record(rec, bare, model=model, duration_s=duration_s, realism=realism)
        pairs.append((c["measured"], c["simulated"]))
        rates.add(c["fs_hz"])
        rpms.append(c["rpm"])
    names = [Path(r).name for r in records]
    return _with_path(rig, model, pairs, rates, names, duration_s, objective,
                      _profile_of(realism), rpms)  # fmt: skip


def _profile_of(realism: dict | None) -> str:
    """The drop profile a model gain identified with ``realism`` simulates its faults with."""
    from .geometry import DefectProfile, parse_enum

    prof = {**REALISM, **(realism or {})}["defect_profile"]
    return parse_enum(DefectProfile, prof, "defect_profile").value


def _with_path(rig, model: str, pairs, rates: set, names: list[str], duration_s: float,
               objective: str, profile: str = "geometric", rpms=None):  # fmt: skip
    """The rig with the path fitted on ``pairs`` (measured, model output; their sample
    ``rates`` [Hz], one rate; their shaft speeds ``rpms`` [r/min]) as its fitted
    ``[[model_gain]]`` for ``model``, and the :class:`~bearingsim.rig_identify.PathFit`."""
    from .rig import ModelGain
    from .rig_identify import fit_path_gains

    if len(rates) != 1:
        raise ConfigError(
            f"records: sample rates {sorted(rates)} Hz; valid: records of one rate (one rig)"
        )
    fs = next(iter(rates))
    why = f"the {model} model's output for {', '.join(names)}, {duration_s:g} s each"
    fit = fit_path_gains(rig, pairs, fs, objective=objective, provenance=why, rpms=rpms)
    gain = ModelGain(model, None, fit.provenance, fit.gains[0], tuple(fit.gains[1:]), profile)
    return replace(rig, model_gains=(*rig.model_gains, gain)), fit


def model_path_scale_conditions(
    rig,
    records: list,
    conditions: list[dict],
    *,
    model: str = "vsm",
    duration_s: float = 1.0,
    realism: dict | None = None,
    seed: int = 0,
    progress: bool = False,
):
    """:func:`model_path_scale` for a user's own machine: each measured record comes with the
    condition it was recorded in instead of a CWRU manifest row. The ring models only (the
    rotor model is the CWRU motor).

    Parameters
    ----------
    rig : Rig
        The output-only rig.
    records : list of SignalRecord
        Measured records (:func:`bearingsim.io.signal.read_signal`), each with its sample rate
        and, unless its condition gives ``rpm``, its shaft speed (a speed column: its median).
    conditions : list of dict
        Per record: ``fault`` (none | outer | inner | ball; ``none`` records are skipped: no
        fault power to match), ``bearing`` (a catalogue id) or
        ``bearing_file`` (a bearing TOML),
        ``defect_width_m`` [m], optional ``defect_depth_m`` [m] (the model's default when
        absent) and ``rpm`` [r/min] (the record's own when absent).
    model : {"vsm", "dem", "tvsm"}
        The ring model.
    duration_s : float
        Simulated time per record [s] (at most the record's length).
    realism : dict, optional
        Scenario keys replacing those of :data:`REALISM`.
    seed : int
        Seed of the slip and of the rig's random parts.
    progress : bool
        A tqdm bar on stderr.

    Returns
    -------
    (Rig, float)
        As :func:`model_path_scale`.
    """
    rig = _without_gain(rig, model)
    powers, names = [], []
    for name, measured, bare in _user_simulations(
        records, conditions, model, duration_s, realism, seed, progress
    ):
        sim, bg = _through_rig(bare, rig, seed)
        powers.append(_powers(measured[: sim.size], sim, bg))
        names.append(name)
    return _with_gain(rig, model, powers, names, duration_s, _profile_of(realism))


def model_path_fit_conditions(
    rig,
    records: list,
    conditions: list[dict],
    *,
    model: str = "vsm",
    duration_s: float = 1.0,
    realism: dict | None = None,
    seed: int = 0,
    objective: str = "spectral",
    progress: bool = False,
):
    """:func:`model_path_fit` for a user's own machine: the records and their conditions as
    in :func:`model_path_scale_conditions` (one sample rate). Returns ``(Rig, PathFit)``."""
    from .rig import _result_fs, _shaft_hz

    rig = _without_gain(rig, model)
    pairs, names, rates, rpms = [], [], set(), []
    for name, measured, bare in _user_simulations(
        records, conditions, model, duration_s, realism, seed, progress
    ):
        x = np.asarray(bare.channels[rig.input_channel], dtype=float)
        pairs.append((measured[: x.size], x))
        names.append(name)
        rates.add(_result_fs(bare))
        fsh = _shaft_hz(bare)
        rpms.append(None if fsh is None else 60.0 * fsh)
    return _with_path(rig, model, pairs, rates, names, duration_s, objective,
                      _profile_of(realism), rpms)  # fmt: skip


def _user_simulations(records, conditions, model, duration_s, realism, seed, progress):
    """Check a user's records and conditions (:func:`model_path_scale_conditions`) and yield,
    per fault record, ``(file name, measured signal [m/s^2], the model's bare result)``."""
    from tqdm import tqdm

    from . import simulate

    if model == "rotor":
        raise ConfigError(
            "model = 'rotor' is invalid for a user's records: the rotor model is the CWRU motor "
            "(its gain is identified from CWRU records); valid: vsm, dem, tvsm"
        )
    if not records or len(records) != len(conditions):
        raise ConfigError(
            f"records ({len(records)}) and conditions ({len(conditions)}) must be non-empty "
            "and of the same length"
        )
    allowed = {"fault", "bearing", "bearing_file", "defect_width_m", "defect_depth_m", "rpm"}
    for i, cond in enumerate(conditions):
        if not isinstance(cond, dict):
            raise ConfigError(f"conditions[{i}] = {cond!r} is invalid; valid: a dict")
        extra = sorted(set(cond) - allowed)
        if extra:
            raise ConfigError(
                f"conditions[{i}]: unknown key {extra[0]!r}; valid keys: "
                + ", ".join(sorted(allowed))
            )
        if cond.get("fault") not in ("none", *FAULT_FAMILIES):
            raise ConfigError(
                f"conditions[{i}].fault = {cond.get('fault')!r} is invalid; valid: none, outer, "
                "inner, ball"
            )
    # healthy records carry no fault power to match: skipped
    kept = [(r, c) for r, c in zip(records, conditions, strict=True) if c["fault"] != "none"]
    if not kept:
        raise ConfigError(
            "conditions: no record has a bearing fault; valid: at least one outer, inner or ball "
            "condition (a model gain is matched to a fault's power)"
        )
    keys = {**REALISM, **(realism or {})}
    bar = tqdm(kept, desc=f"{model} gain", unit="record", disable=not progress, leave=False)
    for rec, cond in bar:
        rpm = cond.get("rpm") or rec.rpm
        if rpm is None and rec.speed_hz is not None:  # a speed column: its median
            rpm = 60.0 * float(np.median(rec.speed_hz))
        if rpm is None:
            raise ConfigError(
                f"record {Path(rec.source).name}: no shaft speed; valid: an rpm in its "
                "condition, --rpm or an rpm in the file"
            )
        fs = float(rec.fs)
        dur = min(duration_s, rec.x.size / fs)
        sc = condition_scenario(model, cond, rpm, dur, fs, seed, keys)
        yield Path(rec.source).name, np.asarray(rec.x, dtype=float), simulate(sc)


def condition_scenario(
    model: str, cond: dict, rpm: float, duration_s: float, fs_hz: float, seed: int, keys: dict
) -> dict:
    """The scenario (a dict of :mod:`bearingsim.config` keys) that simulates a user's record
    in its condition ``cond`` (:func:`model_path_scale_conditions`) with ``model`` at ``rpm``
    [r/min] for ``duration_s`` [s] at ``fs_hz`` [Hz], anti-aliased, with the realism keys
    ``keys``; ``bearingsim rig identify --conditions`` checks each row with it before any
    work."""
    which = {"bearing_file": cond["bearing_file"]} if "bearing_file" in cond else {}
    return dict(
        model=model,
        **(which or {"bearing": cond["bearing"]}),
        fault=cond["fault"],
        defect_width_m=cond["defect_width_m"],
        **({"defect_depth_m": cond["defect_depth_m"]} if cond.get("defect_depth_m") else {}),
        rpm=float(rpm),
        duration_s=duration_s,
        fs_hz=fs_hz,
        seed=seed,
        antialias=True,
        **keys,
    )


def cwru_row(record: str | Path) -> dict[str, str] | None:
    """The ``manifest.csv`` row of a CWRU record (the manifest beside it), or None when the
    folder has no manifest or the manifest does not list the record."""
    p = Path(record)
    if not (p.parent / "manifest.csv").is_file():
        return None
    return cwru_manifest(p.parent).get(p.name)


def _fault_records(records: list) -> list:
    """The fault records among CWRU ``records`` (healthy ones carry no fault power to match);
    a one-line error when there are none."""
    if not records:
        raise ConfigError("records is empty; valid: at least one CWRU fault record")
    kept = [r for r in records if _has_fault(Path(r))]
    if not kept:
        raise ConfigError(
            "records: none has a bearing fault; valid: at least one CWRU outer-race, inner-race "
            "or ball fault record"
        )
    return kept


def _has_fault(record: Path) -> bool:
    """Whether a CWRU record's manifest row names one of :data:`FAULT_FAMILIES` (a record
    outside the manifest passes, for :func:`simulate_record`'s error)."""
    row = cwru_row(record)
    return row is None or row["fault"].split()[0] in FAULT_FAMILIES


def _through_rig(bare, rig, seed: int):
    """The sensor signal of a simulation result through ``rig`` (a :class:`Rig`) and the part
    of it the rig adds whatever the model does (background, tones, sensor noise) [m/s^2]. The
    rig is linear in the model's output: with a zero input, the same rate, shaft speed and
    seed as :func:`bearingsim.rig.apply_rig`'s, it gives exactly what it adds."""
    from .rig import _result_fs, _shaft_hz, apply_rig

    sensor = np.asarray(apply_rig(bare, rig, seed=seed)["acc_sensor"], dtype=float)
    background = rig.apply(
        np.zeros(sensor.size), _result_fs(bare), shaft_hz=_shaft_hz(bare), seed=seed
    )
    return sensor, background


def _without_gain(rig, model: str):
    """``rig`` without a model gain for ``model`` (the output-only path the scale is fitted
    on: a gain it already has is not compounded); ``model`` checked."""
    from .rig import GAIN_MODELS

    if model not in GAIN_MODELS:
        raise ConfigError(f"model = {model!r} is invalid; valid: " + ", ".join(GAIN_MODELS))
    return replace(rig, model_gains=tuple(g for g in rig.model_gains if g.model != model))


def _powers(measured, simulated, background) -> tuple[float, float]:
    """(measured power above the rig's background, power of the model's output through the
    path) of one record, mean-removed [(m/s^2)^2]."""
    m = measured - measured.mean()
    b = background - background.mean()
    x = simulated - background
    x = x - x.mean()
    return float(np.mean(m * m) - np.mean(b * b)), float(np.mean(x * x))


def _with_gain(
    rig, model: str, powers, names: list[str], duration_s: float, profile: str = "geometric"
):
    """The rig with the power-balance scale of ``powers`` as its ``[[model_gain]]``."""
    from .rig import ModelGain

    excess = sum(e for e, _ in powers)
    path = sum(q for _, q in powers)
    joined = ", ".join(names)
    if excess <= 0.0:
        raise ConfigError(
            f"records {joined}: the rig's background alone carries their power; no path gain "
            "can be identified from them; valid: records whose power exceeds the rig's background"
        )
    if path <= 0.0:
        raise ConfigError(f"records {joined}: the {model} model's output through the path is 0")
    k = float(math.sqrt(excess / path))
    gain = ModelGain(
        model,
        k,
        f"power of {joined} above the rig's background over the {model} model's path power "
        f"(bearingsim.side_by_side.model_path_scale, {duration_s:g} s per record)",
        defect_profile=profile,
    )
    return replace(rig, model_gains=(*rig.model_gains, gain)), k


def _other_size_records(data_dir: Path, end: str, fs_hz: float, size_in: str | None) -> list[str]:
    """File names of the CWRU fault records of ``end`` at ``fs_hz`` [Hz] with a fault size
    other than ``size_in`` (None: every size; the healthy record has none), sorted."""
    return sorted(
        f
        for f, q in cwru_manifest(data_dir).items()
        if q["end"] == end
        and float(q["fs_hz"]) == float(fs_hz)
        and q["fault_diameter_in"]
        and q["fault_diameter_in"] != size_in
    )


def rig_without_size(data_dir: Path, end: str, fs_hz: float, size_in: str):
    """The rig of one mounting of the CWRU rig (the accelerometer of ``end`` at ``fs_hz``)
    identified from its fault records of every size **but** ``size_in`` (output-only,
    :func:`bearingsim.rig_identify.identify_rig`), or None when the folder holds no fault record
    of that end and rate with another size. The held-out split of issue 16 (item 5): a rig
    judged on the records of one fault size is identified on the others; the healthy record,
    which has no size, is never used.

    Parameters
    ----------
    data_dir : Path
        A CWRU folder with its ``manifest.csv``.
    end : {"DE", "FE"}
        The bearing whose accelerometer the rig is.
    fs_hz : float
        Sample rate of the records [Hz].
    size_in : str
        The fault size left out, as the manifest writes it (``"0.007"``) [in].
    """
    from .io.signal import read_signal
    from .rig_identify import identify_rig

    data_dir = Path(data_dir)
    others = _other_size_records(data_dir, end, fs_hz, size_in)
    if not others:
        return None
    recs = [read_signal(data_dir / f, channel=end) for f in others]
    return identify_rig(
        recs,
        name=f"lomo-{end}-{float(fs_hz):g}-without-{size_in}",
        provenance="bearingsim.side_by_side.rig_without_size: identified from " + ", ".join(others),
    ).rig


def lomo_rig(
    data_dir: Path,
    record: str,
    *,
    model_gain: str | None = None,
    realism: dict | None = None,
    gain_method: str = "power",
):
    """The rig of ``record``'s mounting identified WITHOUT its fault size (leave-one-mounting-
    out: :func:`rig_without_size` for the record's end, sample rate and size), or None when the
    folder holds no other size of that end and rate.

    Parameters
    ----------
    data_dir : Path
        A CWRU folder with its ``manifest.csv``.
    record : str
        The record's file name.
    model_gain : {"vsm", "dem", "tvsm", "rotor"}, optional
        Also identify this model's path gain on those other records (by ``gain_method``; the
        same leave-one-mounting-out split).
    realism : dict, optional
        Scenario keys replacing those of :data:`REALISM` for ``model_gain``.
    gain_method : {"power", "spectral", "whittle"}
        How ``model_gain`` is identified: one scale of the output-only path
        (:func:`model_path_scale`) or every gain of the path fitted to the records' spectra
        with that objective (:func:`model_path_fit`).
    """
    rows = cwru_manifest(data_dir)
    r = rows[record]
    rig = rig_without_size(data_dir, r["end"], float(r["fs_hz"]), r["fault_diameter_in"])
    if rig is None:
        return None
    if model_gain:
        others = _other_size_records(data_dir, r["end"], float(r["fs_hz"]), r["fault_diameter_in"])
        rig = _model_gain(rig, [data_dir / f for f in others], model_gain, realism, gain_method)
    return rig


#: how a model's path gain is identified (:func:`lomo_rig`, :func:`rig_other_loads`)
GAIN_METHODS = ("power", "spectral", "whittle")


def _model_gain(rig, records: list[Path], model: str, realism, method: str):
    """``rig`` with ``model``'s path gain identified on ``records`` by ``method``."""
    if method not in GAIN_METHODS:
        raise ConfigError(f"gain_method = {method!r} is invalid; valid: " + ", ".join(GAIN_METHODS))
    if method == "power":
        return model_path_scale(rig, records, model=model, realism=realism)[0]
    return model_path_fit(rig, records, model=model, realism=realism, objective=method)[0]


def _same_mounting_records(rows: dict[str, dict[str, str]], record: str) -> list[str]:
    """File names of the CWRU records of ``record``'s mounting at the other motor loads: the
    same end, sample rate, fault (race and position) and size, another load; sorted.
    ``rows``: the folder's manifest (:func:`~bearingsim.io.cwru.cwru_manifest`)."""
    r = rows[record]
    same = ("end", "fs_hz", "fault", "or_position", "fault_diameter_in")
    return sorted(
        f
        for f, q in rows.items()
        if f != record and all(q[k] == r[k] for k in same) and q["load_hp"] != r["load_hp"]
    )


def rig_other_loads(
    data_dir: Path,
    record: str,
    *,
    model_gain: str | None = None,
    realism: dict | None = None,
    gain_method: str = "power",
):
    """The rig of ``record``'s own mounting identified from that mounting's records at the
    **other** motor loads (output-only, :func:`bearingsim.rig_identify.identify_rig`; with
    ``model_gain``, also that model's path gain on the same records, by ``gain_method``), or
    None when the
    folder holds no other load of it (the 0.007 in mountings: one record each).

    The split a user's own machine has: a rig identified on some records of the machine,
    judged on another record of it (leave-one-load-out). CWRU replaced the bearing for every
    fault, so each fault record set (race, position, size) is its own mounting (Smith &
    Randall 2015); :func:`lomo_rig` judges across mountings instead.

    Parameters
    ----------
    data_dir : Path
        A CWRU folder with its ``manifest.csv``.
    record : str
        The judged record's file name (never among the identification records).
    model_gain : {"vsm", "dem", "tvsm", "rotor"}, optional
        Also identify this model's path gain on the identification records (by
        ``gain_method``).
    realism : dict, optional
        Scenario keys replacing those of :data:`REALISM` for ``model_gain``.
    gain_method : {"power", "spectral", "whittle"}
        As :func:`lomo_rig`.
    """
    from .io.signal import read_signal
    from .rig_identify import identify_rig

    data_dir = Path(data_dir)
    rows = cwru_manifest(data_dir)
    if record not in rows:
        raise ConfigError(f"record {record!r} is not in {data_dir / 'manifest.csv'}")
    others = _same_mounting_records(rows, record)
    if not others:
        return None
    end = rows[record]["end"]
    recs = [read_signal(data_dir / f, channel=end) for f in others]
    rig = identify_rig(
        recs,
        name=f"mounting-of-{Path(record).stem}-other-loads",
        provenance="bearingsim.side_by_side.rig_other_loads: identified from " + ", ".join(others),
    ).rig
    if model_gain:
        rig = _model_gain(rig, [data_dir / f for f in others], model_gain, realism, gain_method)
    return rig


#: issue 16's bounds: RMS and line within x2, kurtosis within x1.5, prominence within 6 dB
BOUNDS = {"rms": 2.0, "line": 2.0, "kurtosis": 1.5, "prominence_db": 6.0}


def within_bounds(ratio: dict) -> dict[str, bool]:
    """Which of issue 16's bounds a :func:`side_by_side` ratio meets."""
    out = {}
    for k, b in BOUNDS.items():
        v = ratio[k]
        out[k] = bool(abs(v) <= b) if k == "prominence_db" else bool(1.0 / b <= v <= b)
    return out
