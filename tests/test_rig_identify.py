"""Rig identification from measured records (issue 16, item 4): output-only modes, damping,
background and tones; bad records refused in one line, nothing written."""

from __future__ import annotations

import json
import os
import re
import subprocess
import sys
from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from scipy.signal import welch

import bearingsim
import bearingsim.catalog
from bearingsim import simulate
from bearingsim.errors import ConfigError
from bearingsim.io.signal import SignalRecord, read_signal
from bearingsim.rig import load_rig
from bearingsim.rig_identify import identify_rig, rig_to_toml

SRC = str(Path(bearingsim.__file__).resolve().parents[1])
CWRU = Path(__file__).resolve().parents[2] / "shared" / "data" / "cwru"


def _impacts(fs=12000.0, dur=5.0, fn=3000.0, zeta=0.03, rate=107.0, seed=0, noise=0.02):
    """Impacts at ``rate`` (1 % jitter) ringing in one mode, plus white noise [m/s^2]."""
    rng = np.random.default_rng(seed)
    n = int(fs * dur)
    x = np.zeros(n)
    t_imp = np.cumsum(rng.normal(1.0 / rate, 0.01 / rate, int(dur * rate) + 2))
    idx = (t_imp * fs).astype(int)
    x[idx[idx < n]] = 1.0
    t = np.arange(int(0.02 * fs)) / fs
    wn = 2 * np.pi * fn
    h = np.exp(-zeta * wn * t) * np.sin(wn * np.sqrt(1 - zeta**2) * t)
    y = np.convolve(x, h)[:n] + noise * rng.standard_normal(n)
    return SignalRecord(x=y, fs=fs, rpm=1750.0, source=f"synthetic{seed}", channel="y")


def test_a_known_mode_is_recovered():
    """Frequency within 2 %, damping within 30 % (envelope-decay fit), from three records."""
    recs = [_impacts(seed=s) for s in range(3)]
    ir = identify_rig(recs, name="synthetic", max_modes=1)
    (m,) = ir.rig.modes
    assert m.frequency_hz == pytest.approx(3000.0, rel=0.02)
    assert m.damping_ratio == pytest.approx(0.03, rel=0.3)
    assert m.gain > 1.0  # a resonance stands well above its shoulders
    assert ir.rig.fs_hz == recs[0].fs  # the rate of the records, for a scenario that sets none
    back = load_rig_text(rig_to_toml(ir.rig))
    assert back == ir.rig


def test_a_mode_frequency_is_a_peak_of_the_psd_not_its_search_windows_edge():
    """Impacts through two modes a quarter octave apart (cwru-de-12k's 2769 and 3299 Hz): the
    smoothed impulsive spectrum peaks between them, at 3000 Hz, and the refinement took the
    PSD maximum within +/- 1/12 octave, which lay on the window's edge, 2833 Hz, a dip of
    the path (exploratory testing, twentieth session). Each mode found is now a local peak of
    the PSD: within 1 % of one of the two."""
    path = replace(load_rig("cwru-de-12k"), background=None, tones=(), noise_rms_m_per_s2=0.0)
    path = replace(path, modes=path.modes[:2], fs_hz=None)
    recs = []
    for s in range(2):
        rng = np.random.default_rng(s)
        fs, n = 12000.0, 60000
        x = np.zeros(n)
        t = np.cumsum(rng.normal(1.0 / 105.0, 0.01 / 105.0, 600))
        k = (t * fs).astype(int)
        x[k[k < n]] = 50.0 * (1.0 + 0.2 * rng.standard_normal(np.count_nonzero(k < n)))
        y = path.apply(x + rng.standard_normal(n), fs, seed=s)
        recs.append(SignalRecord(x=y, fs=fs, rpm=1796.0, source=f"two{s}", channel="y"))
    ir = identify_rig(recs, name="two", max_modes=3)
    assert ir.rig.modes
    for m in ir.rig.modes:
        assert min(abs(m.frequency_hz / f - 1.0) for f in (2769.0, 3299.0)) < 0.01, m


def test_the_background_reaches_the_nyquist_frequency_with_the_records_roll_off():
    """Above 0.45 fs a recorder's anti-aliasing filter rolls the records off (CWRU: 3-5
    decades to fs/2). The table follows it in narrow bands up to fs/2, so a signal at the
    rig's own rate has the records' floor there (before, the table ended at 0.45 fs and the
    band above was the model's output alone): white noise low-passed at 0.46 fs comes out
    at its level below 0.45 fs and orders of magnitude under it at 0.49-0.5 fs."""
    from scipy.signal import butter, sosfiltfilt

    recs = []
    for s in range(3):
        rec = _impacts(seed=s)
        sos = butter(12, 0.46 * rec.fs, fs=rec.fs, output="sos")
        recs.append(replace(rec, x=sosfiltfilt(sos, rec.x)))
    bg = identify_rig(recs, name="roll", max_modes=1).rig.background
    f, p = np.array(bg.frequency_hz), np.array(bg.psd)
    assert f[-1] == 0.5 * recs[0].fs and np.all(np.diff(f) > 0)
    low = np.median(p[(f > 1000.0) & (f < 2000.0)])
    assert p[-1] < 1e-3 * low and p[-2] < 1e-3 * low  # 0.49 and 0.5 fs: the filter's floor
    assert 0.3 * low < p[np.argmin(np.abs(f - 0.45 * recs[0].fs))] < 3.0 * low


def test_the_background_is_the_records_non_impulsive_part():
    """The background table is the part of the records between the impacts (issue 16, item 4:
    "from the non-impulsive part of faulty ones"): impacts at 107 Hz ringing at 3 kHz over white
    noise of 0.05 m/s^2 RMS. Away from the mode (1 and 5 kHz) the table is the noise's level
    within 0.7-1.6x (the median-averaged Welch PSD over 0.25 s segments, each holding 27
    impacts, gave 2.2-2.3x), and the table carries under 0.3 of the records' power (that one
    0.87: nearly all of it). At the mode the ringing fills most of the time between two impacts
    and stays in it (24x the noise)."""
    recs = [_impacts(seed=s, noise=0.05) for s in range(3)]
    bg = identify_rig(recs, name="synthetic", max_modes=1).rig.background
    f, p = np.array(bg.frequency_hz), np.array(bg.psd)
    white = 0.05**2 / 6000.0  # one-sided PSD of the noise [(m/s^2)^2/Hz]
    off = np.interp([1000.0, 5000.0], f, p) / white
    assert np.all((off > 0.7) & (off < 1.6)), off
    total = np.mean([np.var(r.x) for r in recs])
    assert np.trapezoid(p, f) < 0.3 * total


def _speed_records(rpms, noise=0.05):
    """Impacts ringing at 3 kHz (the same at every speed) over white background noise whose
    amplitude grows as speed^2: ``noise`` [m/s^2] RMS at 1000 r/min."""
    recs = []
    for s, n in enumerate(rpms):
        r = _impacts(seed=s, noise=0.0)
        bg = noise * (n / 1000.0) ** 2 * np.random.default_rng(100 + s).standard_normal(r.x.size)
        recs.append(replace(r, x=r.x + bg, rpm=float(n), source=f"speed{s}"))
    return recs


def test_the_backgrounds_growth_with_speed_is_identified():
    """Records at 900-1800 r/min whose background grows as speed^2 (twenty-fourth session;
    last note: a rig's background did not scale with speed). The fitted exponent is 2 within
    0.15 (2.00 with this seed; the ringing left between impacts at the mode does not grow,
    and the record-level median over frequency keeps it out: the background RMS gave 0.89),
    the table is the noise at the speeds' geometric mean within the 0.7-1.6x of the
    one-speed test above, and the rig gives that noise's level at 1800 r/min."""
    rpms = (900.0, 1200.0, 1500.0, 1800.0)
    ir = identify_rig(_speed_records(rpms), name="law", max_modes=1)
    b = ir.rig.background
    assert b.speed_exponent == pytest.approx(2.0, abs=0.15)
    assert b.rpm_ref == pytest.approx(float(np.exp(np.mean(np.log(rpms)))))
    assert ir.speed_law.stderr < 0.2 and "4 records at 900-1800 r/min" in b.provenance
    white = lambda n: (0.05 * (n / 1000.0) ** 2) ** 2 / 6000.0  # noqa: E731 [(m/s^2)^2/Hz]
    off = np.interp([1000.0, 5000.0], b.frequency_hz, b.psd) / white(b.rpm_ref)
    assert np.all((off > 0.7) & (off < 1.6)), off
    y = ir.rig.apply(np.zeros(60000), 12000.0, shaft_hz=30.0, seed=0)
    f, p = welch(y, fs=12000.0, nperseg=1024)
    at = np.median(p[(f > 4000.0) & (f < 5000.0)]) / white(1800.0)
    assert 0.7 < at < 1.6, at
    assert load_rig_text(rig_to_toml(ir.rig)) == ir.rig
    # the plot draws the table at rpm_ref and the background at the records' ends
    labels = [ln.get_label() for ln in ir.plot().axes[0].get_lines()]
    assert f"identified background (table at {b.rpm_ref:.5g} r/min)" in labels, labels
    assert (
        "the same at 900 r/min (speed^2)" in labels and "the same at 1800 r/min (speed^2)" in labels
    )


@pytest.mark.parametrize(
    ("rpms", "why"),
    [
        (
            (1730.0, 1750.0, 1772.0, 1797.0),
            r"speeds span 1730-1797 r/min \(x1.04\), under the x1.5",
        ),
        ((900.0, 1800.0), r"2 record\(s\) with a known shaft speed, 3 needed"),
    ],
)
def test_no_speed_law_without_the_speeds_to_fit_it(rpms, why):
    """Records over the CWRU rig's 4 % span, or too few, give no speed law: the background is
    the same at every speed, and the provenance says why."""
    ir = identify_rig(_speed_records(rpms), name="flat", max_modes=1)
    assert ir.rig.background.speed_exponent is None and ir.rig.background.rpm_ref is None
    assert re.search("speed law: not fitted: .*" + why, ir.rig.background.provenance)


def test_a_shaft_tone_is_a_tone_and_not_also_background():
    """Exploratory testing (twenty-fourth session): a user's 0.3 m/s^2 line at 1 x the shaft
    speed became a [[tone]] and stayed in the background table too (1.8e-3 (m/s^2)^2 in
    10-22 Hz against the records' 1.4e-8), so a run through the rig carried it twice; the
    shipped CWRU profiles had their 1 x line in the table at 100 times their floor. A kept
    tone is now fitted and taken out of each record before its background: with a 1 m/s^2
    line at 1 x over white noise of 0.05 m/s^2, the table at the line is the noise's level
    within 0.5-2x (before: 4 decades above it), and the tone is the line's amplitude."""
    recs = []
    for s in range(3):
        r = _impacts(seed=s, noise=0.05)
        t = np.arange(r.x.size) / r.fs
        recs.append(replace(r, x=r.x + np.sin(2 * np.pi * r.rpm / 60.0 * t + s)))
    rig = identify_rig(recs, name="tone", max_modes=1).rig
    (one,) = [t for t in rig.tones if t.order == 1.0]
    assert one.amplitude_m_per_s2 == pytest.approx(1.0, rel=0.02)
    white = 0.05**2 / 6000.0
    at = rig.background.psd_at(np.array([1750.0 / 60.0, 2 * 1750.0 / 60.0])) / white
    assert np.all((at > 0.5) & (at < 2.0)), at


def test_no_tone_from_noise_and_a_tone_between_bins_at_its_amplitude():
    """A helper's exploratory testing (twenty-eighth session): a tone was kept where its Hann
    line stood 6 dB over sqrt(PSD ENBW), which noise alone crossed on 44.5 % of the records
    (tones "found" in 6 of 10 toneless trials), and its amplitude was the Hann peak, 15 % low
    between bins (0.255 for 0.3 m/s^2 at 29.95 Hz over 10 s). Now the false-alarm probability
    is 1e-3 per record and order, and the amplitude the least-squares sinusoid's."""
    for trial in range(4):  # noise only: no tone at any order
        recs = [_impacts(seed=10 * trial + s) for s in range(3)]
        assert identify_rig(recs, name="n", max_modes=1).rig.tones == ()
    recs = []
    for s in range(3):  # 0.1 m/s^2 at 29.95 Hz on 5 s: half-way between two 0.2 Hz bins
        r = replace(_impacts(seed=s), rpm=1797.0)
        t = np.arange(r.x.size) / r.fs
        recs.append(replace(r, x=r.x + 0.1 * np.sin(2 * np.pi * 1797.0 / 60.0 * t + s)))
    (one,) = identify_rig(recs, name="t", max_modes=1).rig.tones
    assert one.order == 1.0 and one.amplitude_m_per_s2 == pytest.approx(0.1, rel=0.02)
    # ... and on records of 1 s, where the Welch background beside the line held the line
    # itself and the first form of the threshold missed it (the same session's helper)
    short = []
    for s in range(3):
        r = replace(_impacts(seed=s, dur=1.0, noise=0.2), rpm=1797.0)
        t = np.arange(r.x.size) / r.fs
        short.append(replace(r, x=r.x + 0.3 * np.sin(2 * np.pi * 1797.0 / 60.0 * t + s)))
    (one,) = identify_rig(short, name="t", max_modes=1).rig.tones
    assert one.order == 1.0 and one.amplitude_m_per_s2 == pytest.approx(0.3, rel=0.05)


@pytest.mark.parametrize("zeta", [0.01, 0.05, 0.12, 0.3])
def test_the_damping_of_a_heavily_damped_mode_is_not_capped(zeta):
    """A helper's exploratory testing (twenty-eighth session): the decay was read in a band
    fixed at fn +/- 12.5 %, which passes five half-power bandwidths only for zeta <= 0.025
    and capped the damping near 0.07 (0.12, 0.2, 0.3 read 0.067, 0.072, 0.073). Impacts
    ringing in one mode (no direct path, no background), 48 kHz."""
    from bearingsim.rig import Mode, Rig
    from bearingsim.rig_identify import _mode_decay

    fs, n = 48000.0, 480000
    rng = np.random.default_rng(0)
    x = np.zeros(n)
    t = np.cumsum(rng.normal(1.0 / 107.4, 0.015 / 107.4, 1100))
    x[(t[t < n / fs] * fs).astype(int)] = 50.0
    rig = Rig(name="m", description="", provenance="p", gain=0.0,
              modes=(Mode(3000.0, zeta, 5.0, "p"),))  # fmt: skip
    sigma, _ = _mode_decay([rig.apply(x, fs, seed=0)], fs, 3000.0)
    assert sigma / (2 * np.pi * 3000.0) == pytest.approx(zeta, rel=0.3)


def test_white_noise_is_all_background_in_every_band():
    """Stationary Gaussian noise is non-impulsive in every STFT band, the real DC and Nyquist
    bins included (their median/mean is that of one degree of freedom, 0.455, not ln 2: read as
    such, they took a third off the background below 375 Hz at 12 kHz)."""
    from bearingsim.rig_identify import _spectral_kurtosis

    x = np.random.default_rng(0).standard_normal(120000)
    _, _, _, share = _spectral_kurtosis(x, 12000.0, 32)
    assert np.all(share > 0.95), share


def load_rig_text(text):
    import tomllib

    from bearingsim.rig import Rig

    return Rig.from_dict(tomllib.loads(text), source="text")


def _path_pairs(true_rig, n_rec=3, fs=12000.0, dur=2.0):
    """(measured, model output) pairs: a "model output" of jittered impacts (each a 0.2 ms
    half-sine, broadband) at 107 Hz, and what ``true_rig`` makes of it (background included)."""
    pairs = []
    for s in range(n_rec):
        rng = np.random.default_rng(10 + s)
        n = int(fs * dur)
        x = 0.05 * rng.standard_normal(n)
        t_imp = np.cumsum(rng.normal(1.0 / 107.0, 0.01 / 107.0, int(dur * 107) + 2))
        idx = (t_imp * fs).astype(int)
        pulse = np.sin(np.pi * np.arange(3) / 2.0) * 50.0
        for i in idx[idx < n - 3]:
            x[i : i + 3] += pulse
        pairs.append((true_rig.apply(x, fs, seed=s), x))
    return pairs


@pytest.mark.parametrize("objective", ["spectral", "whittle"])
def test_the_path_gains_are_recovered_from_known_inputs(objective):
    """A known path (direct gain 0.1, modes at 2 and 4.5 kHz with gains 3 and 1) and a known
    background: from three 2 s (measured, model output) pairs each objective, started from
    the output-only gains (1; 5, 5), returns the path's gains within 10 % (the modes' own
    frequencies and damping kept) and the records' power within 5 %: when the model's
    output is the path's input, the two agree."""
    from bearingsim.rig import Background, Mode, Rig
    from bearingsim.rig_identify import fit_path_gains

    modes = (Mode(2000.0, 0.02, 3.0, "test"), Mode(4500.0, 0.015, 1.0, "test"))
    bg = Background((10.0, 6000.0), (1e-4, 1e-4), "test")
    true = Rig(name="true", description="", provenance="test", gain=0.1, modes=modes,
               background=bg)  # fmt: skip
    start = Rig(name="start", description="", provenance="test", gain=1.0,
                modes=tuple(replace(m, gain=5.0) for m in modes), background=bg)  # fmt: skip
    fit = fit_path_gains(
        start, _path_pairs(true), 12000.0, objective=objective, provenance="synthetic"
    )
    assert fit.gains == pytest.approx((0.1, 3.0, 1.0), rel=0.1)
    assert fit.start_gains == (1.0, 5.0, 5.0)
    assert fit.power_ratio == pytest.approx(1.0, rel=0.05)
    assert fit.rig.gain == fit.gains[0] and fit.rig.modes[1].gain == fit.gains[2]
    assert [m.frequency_hz for m in fit.rig.modes] == [2000.0, 4500.0]
    how = {"spectral": "log Welch spectra", "whittle": "Whittle likelihood"}[objective]
    assert fit.objective == objective and how in fit.rig.gain_provenance
    assert "synthetic" in fit.rig.modes[0].provenance
    back = load_rig_text(rig_to_toml(fit.rig))
    assert back == fit.rig


def test_the_path_fit_refuses_bad_pairs_in_one_line():
    from bearingsim.rig import Background, Rig
    from bearingsim.rig_identify import fit_path_gains

    rig = Rig(name="r", description="", provenance="test")
    x = np.random.default_rng(0).standard_normal(24000)
    cases = [
        ([], "pairs is empty"),
        ([(x, x[:-1])], "pairs[0]: measured (24000,) and model output (23999,)"),
        ([(x[:6000], x[:6000])], "pairs[0]: 0.5 s is too short"),
        ([(x, np.where(np.arange(x.size) == 5, np.nan, x))], "pairs[0]: a signal has non-fin"),
        ([(x, np.zeros(x.size))], "pairs[0]: the model output is zero in 20-5400 Hz"),
        ([(np.zeros(x.size), x)], "pairs[0]: the measured signal is zero in 20-5400 Hz"),
    ]
    loud = Rig(name="r", description="", provenance="test",
               background=Background((10.0, 6000.0), (1.0, 1.0), "test"))  # fmt: skip
    for pairs, msg in cases:
        with pytest.raises(ConfigError) as e:
            fit_path_gains(rig, pairs, 12000.0)
        assert msg in str(e.value) and "\n" not in str(e.value), str(e.value)
    with pytest.raises(ConfigError, match="fs_hz"):
        fit_path_gains(rig, [(x, x)], -1.0)
    with pytest.raises(ConfigError, match="objective = 'ml' is invalid; valid: spectral, whit"):
        fit_path_gains(rig, [(x, x)], 12000.0, objective="ml")
    with pytest.raises(ConfigError, match="background alone carries the records' power"):
        fit_path_gains(loud, [(x, x)], 12000.0)
    # a background with a speed law is the one at each pair's speed: 10x slower is 100x
    # quieter in amplitude (n = 2), and no longer carries the records' power
    law = Rig(name="r", description="", provenance="test", rpm_range=(100.0, 1000.0),
              background=Background((10.0, 6000.0), (1.0, 1.0), "test", 2.0, 1000.0))  # fmt: skip
    with pytest.raises(ConfigError, match="background alone carries the records' power"):
        fit_path_gains(law, [(x, x)], 12000.0, rpms=[1000.0])
    assert fit_path_gains(law, [(x, x)], 12000.0, rpms=[100.0]).gains[0] > 0.0
    with pytest.raises(ConfigError, match=r"^rpms has 2 speeds for 1 pairs; valid: one per pair"):
        fit_path_gains(law, [(x, x)], 12000.0, rpms=[100.0, 200.0])


def test_the_plot_draws_each_models_path_beside_the_output_only_one():
    """`rig identify --plot` with model gains: the path panel holds the output-only path and
    one curve per ``[[model_gain]]`` (scaled or fitted), named by its model; a modes-only path
    (0 at Nyquist) does not stretch the axis beyond 8 decades below the top."""
    from bearingsim.rig import ModelGain

    recs = [_impacts(seed=s) for s in range(2)]
    ir = identify_rig(recs, name="synthetic", max_modes=1)
    rig = replace(ir.rig, model_gains=(ModelGain("vsm", None, "test", 0.0, (0.5,)),
                                       ModelGain("rotor", 20.0, "test")))  # fmt: skip
    fig = ir.plot(rig)
    panel = fig.axes[1]
    labels = [ln.get_label() for ln in panel.get_lines()][:3]
    assert labels[0].startswith("path power gain") and labels[1].startswith("vsm model's path")
    assert labels[2] == "rotor model's path (path x 20)"
    top = max(float(np.max(ln.get_ydata())) for ln in panel.get_lines()[:3])
    lo = panel.get_ylim()[0]
    assert lo >= 0.99e-8 * top, (lo, top)  # without the floor: ~1e-37 (the modes-only path)
    assert len(ir.plot().axes[1].get_lines()) < len(panel.get_lines())


def test_a_record_without_impacts_is_refused():
    rng = np.random.default_rng(1)
    rec = SignalRecord(x=rng.standard_normal(24000), fs=12000.0, rpm=1750.0, source="noise",
                       channel="y")  # fmt: skip
    with pytest.raises(ConfigError, match="no impulsive content"):
        identify_rig([rec], name="x")


def test_a_refusal_without_modes_names_each_band_tried(monkeypatch):
    """When no impulsive band passes as a mode, the refusal names each band tried and why
    (exploratory testing, nineteenth session: a DEM outer-race fault through a rig's direct
    gain, kurtosis 15, was refused with "give records with a fault"). Here every band fails
    the gain test (the threshold raised out of reach)."""
    import bearingsim.rig_identify as ri

    monkeypatch.setattr(ri, "MIN_GAIN", 1e9)
    with pytest.raises(ConfigError) as exc:
        identify_rig([_impacts()], name="x", max_modes=1)
    msg = str(exc.value)
    assert "no mode could be identified" in msg and "\n" not in msg
    m = re.search(r"\((\d+) Hz \(gain [0-9.e+-]+ over its shoulders, below 1e\+09\)\)", msg)
    assert m and abs(int(m.group(1)) - 3000) < 100, msg
    assert "a model's output through a rig's direct gain" in msg


@pytest.mark.parametrize("seed", [1, 3])
def test_a_fault_comb_over_white_noise_gives_no_mode(seed):
    """Impacts that ring no structure (one-sample spikes at 107 Hz, 2 % jitter, over white
    noise) have a harmonic comb whose low lines stand above the smoothed shoulders: the
    identification took them for modes of gain 0.8-0.9 at 750 Hz (nineteenth session). A mode
    must hold its level across its half-power band (fn +/- zeta fn from the decay); a comb
    line averaged over it falls to the shoulders, so these records give no mode. (The CWRU
    profiles and every held-out and load-split rig keep their modes: the shipped files
    regenerate byte for byte.)"""
    rng = np.random.default_rng(seed)
    fs, n = 12000.0, 24000
    x = 0.05 * rng.standard_normal(n)
    t = np.cumsum(rng.normal(1 / 107, 0.02 / 107, 300))
    idx = (t * fs).astype(int)
    x[idx[idx < n]] += 3.0
    rec = SignalRecord(x=x, fs=fs, rpm=1750.0, source="comb", channel="y")
    # (since the twenty-eighth session the decay's band follows the damping found: a spike
    # that rings nothing decays as fast as any band lets it, so the "mode" comes out too
    # damped to have shoulders within its octave, and is dropped for that)
    with pytest.raises(
        ConfigError,
        match=r"750 Hz \((a line, not a resonance: gain -?[0-9.]+ |no shoulders to measure a "
        r"resonance against)",
    ):
        identify_rig([rec], name="x")


def test_a_short_record_is_refused():
    rec = _impacts(dur=0.5)
    msg = r"synthetic0 is 0.5 s long \(6000 samples at 12000 Hz\); at least 1 s is needed"
    with pytest.raises(ConfigError, match=msg):
        identify_rig([rec], name="x")


def test_a_one_second_csv_with_a_decimal_time_column_is_long_enough(tmp_path):
    """Exploratory testing (nineteenth session): a 1 s record written as CSV with a time column
    (what `numpy.savetxt` writes for a 12 kHz result) was refused as "1 s long; at least 1 s is
    needed": its rate read from the time column was 12000.000000001 Hz, so 12000 samples came
    to 0.99999999 s. The rate is now read to 10 significant digits, and the length is counted
    in samples."""
    from bearingsim.io.signal import read_signal

    rec = _impacts(dur=1.0)
    t = np.arange(rec.x.size) / rec.fs
    p = tmp_path / "one_second.csv"
    np.savetxt(p, np.c_[t, rec.x], delimiter=",", header="time,acc", comments="")
    r = read_signal(p)
    assert r.fs == 12000.0 and r.x.size == 12000
    ir = identify_rig([r], name="csv", max_modes=1)
    assert ir.rig.fs_hz == 12000.0 and len(ir.rig.modes) == 1


def test_mixed_sample_rates_are_refused():
    with pytest.raises(ConfigError, match="identify one sample rate at a time"):
        identify_rig([_impacts(), _impacts(fs=48000.0)], name="x")


@pytest.mark.skipif(not CWRU.is_dir(), reason="needs ../shared/data/cwru")
def test_cwru_drive_end_rings_near_3_35_khz():
    """The drive-end records ring in their 2.5-3.5 kHz band (CWRU record 132's Welch maximum,
    3352 Hz, docs/validation.md ROTOR): the 0.007 in records alone give the strongest mode
    there, and so do the 0.014 in records (a different mounting) within 5 %."""
    seven = [read_signal(CWRU / f, channel="DE") for f in (
        "12k_Drive_End_OR007@6_2_132.mat", "12k_Drive_End_IR007_2_107.mat",
        "12k_Drive_End_B007_2_120.mat")]  # fmt: skip
    fourteen = [
        read_signal(p, channel="DE") for p in sorted(CWRU.glob("12k_Drive_End_*014*.mat"))[:4]
    ]
    a = identify_rig(seven, name="a").rig
    b = identify_rig(fourteen, name="b").rig
    fa = max(a.modes, key=lambda m: m.gain).frequency_hz
    fb = max(b.modes, key=lambda m: m.gain).frequency_hz
    assert 2500.0 <= fa <= 3600.0
    assert fb == pytest.approx(fa, rel=0.05)


def _cli(*args, cwd):
    env = {**os.environ, "PYTHONPATH": SRC}
    return subprocess.run([sys.executable, "-m", "bearingsim", *args], capture_output=True,
                          text=True, env=env, cwd=cwd)  # fmt: skip


@pytest.mark.skipif(not CWRU.is_dir(), reason="needs ../shared/data/cwru")
def test_cli_identify_writes_a_valid_rig_with_its_command(tmp_path):
    out = tmp_path / "rig.toml"
    rec = CWRU / "12k_Drive_End_OR007@6_2_132.mat"
    r = _cli("rig", "identify", str(rec), "--name", "t132", "-o", str(out), "--plot",
             str(tmp_path / "rig.png"), cwd=tmp_path)  # fmt: skip
    assert r.returncode == 0, r.stderr
    rig = load_rig(out)
    assert rig.name == "t132" and rig.modes
    assert f"bearingsim rig identify {rec} --name t132" in rig.provenance
    # one record: no speed law, and the command says why
    assert "background speed law: not fitted: 1 record(s) with a known shaft speed" in r.stdout
    assert rig.background.speed_exponent is None
    assert (tmp_path / "rig.png").stat().st_size > 10_000


def test_cli_identify_a_users_csv_records(tmp_path):
    """A user's own machine: CSV records of one accelerometer column without a time column need
    --fs-hz (said in one line, nothing written, without it); with it the rig is identified and
    its mode is the one the records ring in."""
    paths = []
    for seed in (0, 1):
        rec = _impacts(seed=seed)
        p = tmp_path / f"m{seed}.csv"
        np.savetxt(p, rec.x, header="acc_m_per_s2", comments="")
        paths.append(p.name)
    out = tmp_path / "rig.toml"
    r = _cli("rig", "identify", *paths, "--name", "mine", "-o", str(out), cwd=tmp_path)
    assert r.returncode == 2 and r.stderr.count("\n") == 1 and "--fs-hz" in r.stderr
    assert not out.exists()
    r = _cli("rig", "identify", *paths, "--name", "mine", "--fs-hz", "12000", "--rpm", "1750",
             "-o", str(out), cwd=tmp_path)  # fmt: skip
    assert r.returncode == 0, r.stderr
    rig = load_rig(out)
    assert any(abs(m.frequency_hz - 3000.0) < 150.0 for m in rig.modes), rig.modes
    assert f"background {rig.background.rms():.3g} m/s^2 RMS" in r.stdout, r.stdout
    assert "--fs-hz 12000" in rig.provenance
    # without a speed the rig gets no shaft-order tones: said after the rig is written ...
    out.unlink()
    r = _cli("rig", "identify", *paths, "--name", "mine", "--fs-hz", "12000", "-o", str(out),
             cwd=tmp_path)  # fmt: skip
    assert r.returncode == 0 and out.exists(), r.stderr
    assert r.stderr.startswith("warning: no shaft speed for m0.csv, m1.csv"), r.stderr
    # ... and not at all when the run ends in an error (here: no impulsive content)
    quiet = tmp_path / "q.csv"
    noise = np.random.default_rng(3).standard_normal(60000)
    np.savetxt(quiet, noise, header="acc_m_per_s2", comments="")
    r = _cli("rig", "identify", quiet.name, "--name", "q", "--fs-hz", "12000", "-o", "q.toml",
             cwd=tmp_path)  # fmt: skip
    assert r.returncode == 2 and r.stderr.startswith("error: "), r.stderr
    assert r.stderr.count("\n") == 1 and not (tmp_path / "q.toml").exists()


def test_cli_identify_reads_each_csv_records_speed_column(tmp_path):
    """Exploratory testing (twenty-fourth session), a user's records with an ``rpm`` column:
    the column gave the speed law but no shaft-order tone (the tones took only a file's single
    rpm), ``--rpm`` overrode the columns without a word (and lost the law), and a negative
    column printed a NumPy warning and an error naming no file. Now: the tones are placed at
    each column's median, ``--rpm`` against a column is one line, and so is a speed <= 0."""
    paths = []
    rpms = (900.0, 1500.0, 2400.0)
    for seed, n in enumerate(rpms):
        rec = _speed_records([n])[0]
        t = np.arange(rec.x.size) / rec.fs
        x = rec.x + 1.0 * np.sin(2.0 * np.pi * n / 60.0 * t)  # a 1 m/s^2 line at 1 x
        p = tmp_path / f"r{seed}.csv"
        np.savetxt(p, np.column_stack([t, x, np.full(t.size, n)]), delimiter=",",
                   header="time_s,acc_m_per_s2,rpm", comments="")  # fmt: skip
        paths.append(p.name)
    r = _cli("rig", "identify", *paths, "--name", "cols", "-o", "cols.toml", "--json",
             cwd=tmp_path)  # fmt: skip
    assert r.returncode == 0, r.stderr
    d = json.loads(r.stdout)
    assert [t["order"] for t in d["tones"]][:1] == [1.0], d["tones"]
    assert d["tones"][0]["amplitude_m_per_s2"] == pytest.approx(1.0, rel=0.05)
    # 1.85 for a background built as speed^2: the impacts (the same at every speed) and the
    # 1 x line pull the fit toward 0, the bias docs/models.md reports ("Speed law"); the
    # records' own scatter is the +/- only
    assert 1.8 < d["background_speed_exponent"] < 2.0
    assert 0.0 < d["background_speed_exponent_stderr"] < 0.5
    assert load_rig(tmp_path / "cols.toml").rpm_range == (900.0, 2400.0)
    r = _cli("rig", "identify", *paths, "--name", "cols", "--rpm", "1500", "-o", "x.toml",
             cwd=tmp_path)  # fmt: skip
    assert r.returncode == 2 and r.stderr == (
        "error: rpm = 1500 r/min contradicts the speed column of 'r0.csv' (900 r/min); "
        "valid: the records' speed (or no --rpm, to take each file's)\n"
    ), r.stderr
    for bad in (-900.0, 0.0):
        data = np.loadtxt(tmp_path / "r0.csv", delimiter=",", skiprows=1)
        data[:, 2] = bad
        np.savetxt(tmp_path / "bad.csv", data, delimiter=",", header="time_s,acc_m_per_s2,rpm",
                   comments="")  # fmt: skip
        r = _cli("rig", "identify", paths[1], paths[2], "bad.csv", "--name", "b", "-o",
                 "b.toml", cwd=tmp_path)  # fmt: skip
        assert r.returncode == 2 and r.stderr == (
            f"error: rig identify: bad.csv: median of its speed column = {bad:g} r/min; valid: "
            "a positive shaft speed\n"
        ), r.stderr
    assert not (tmp_path / "x.toml").exists() and not (tmp_path / "b.toml").exists()


@pytest.mark.skipif(not CWRU.is_dir(), reason="needs ../shared/data/cwru")
def test_cli_identify_refuses_in_one_line_and_writes_nothing(tmp_path):
    out = tmp_path / "rig.toml"
    rec = CWRU / "12k_Drive_End_OR007@6_2_132.mat"
    r = _cli("rig", "identify", str(rec), "--name", "x", "--channel", "XX", "-o", str(out),
             cwd=tmp_path)  # fmt: skip
    assert r.returncode == 2
    lines = r.stderr.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("error: ") and "XX" in lines[0]
    assert not out.exists() and list(tmp_path.iterdir()) == []
    # one record given twice (it would count twice in every median of the identification)
    r2 = _cli("rig", "identify", str(rec), str(CWRU / ".." / "cwru" / rec.name), "--name", "x",
              "-o", str(out), cwd=tmp_path)  # fmt: skip
    assert r2.returncode == 2 and "is the same file as" in r2.stderr, r2.stderr
    assert len(r2.stderr.strip().splitlines()) == 1 and not out.exists()
    # an --rpm the record's own shaft harmonics refute (132 runs at 1750 r/min): the tones'
    # orders would be placed at the wrong speed
    r3 = _cli("rig", "identify", str(rec), "--rpm", "1797", "--name", "x", "-o", str(out),
              cwd=tmp_path)  # fmt: skip
    assert r3.returncode == 2 and "put its speed at 1749" in r3.stderr, r3.stderr
    assert len(r3.stderr.strip().splitlines()) == 1 and not out.exists()


@pytest.mark.skipif(not CWRU.is_dir(), reason="needs ../shared/data/cwru")
def test_cli_identify_reads_fan_end_records_on_their_fan_end_sensor(tmp_path):
    """Without --channel, CWRU records whose names all say Fan_End are read on FE (their
    faults and chain are the fan end's, as analyze reads them): the rig equals the one of
    --channel FE. Records of both ends in one call are a one-line error naming --channel;
    nothing is written."""
    fe = [str(CWRU / n) for n in ("12k_Fan_End_OR014@3_0_310.mat", "12k_Fan_End_IR014_0_274.mat")]
    rigs = {}
    for tag, extra in (("auto", ()), ("fe", ("--channel", "FE"))):
        out = tmp_path / f"{tag}.toml"
        r = _cli("rig", "identify", *fe, "--name", "f", *extra, "-o", str(out), cwd=tmp_path)
        assert r.returncode == 0, r.stderr
        rigs[tag] = load_rig(out)
    a, b = rigs["auto"], rigs["fe"]
    assert a.modes == b.modes and a.background == b.background and a.tones == b.tones
    out = tmp_path / "mixed.toml"
    r = _cli("rig", "identify", fe[0], str(CWRU / "12k_Drive_End_OR007@6_2_132.mat"), "--name",
             "m", "-o", str(out), cwd=tmp_path)  # fmt: skip
    assert r.returncode == 2 and not out.exists()
    assert "1 of the 2 CWRU records are fan-end records" in r.stderr and "--channel" in r.stderr


@pytest.mark.skipif(not CWRU.is_dir(), reason="needs ../shared/data/cwru")
def test_cli_identify_model_gain_writes_the_models_gain(tmp_path):
    """`rig identify --model-gain vsm` adds the VSM's path gain fitted on the fault records
    (issue 16 item 4, the model-based part): below 1 on record 135 (the VSM is louder than
    the record), with its provenance; the healthy record is skipped, a folder without a
    manifest and a set of healthy records only are refused in one line before any
    simulation, writing nothing."""
    from bearingsim.cli.rig import identify_cmd
    from bearingsim.rig import GAIN_MODELS

    # the option's choices are written out (the CLI starts without NumPy): the rig's models
    opt = next(p for p in identify_cmd.params if p.name == "model_gains")
    assert tuple(opt.type.choices) == GAIN_MODELS
    rec, healthy = CWRU / "48k_Drive_End_OR007@6_0_135.mat", CWRU / "normal_0_97.mat"
    out = tmp_path / "rig.toml"
    r = _cli("rig", "identify", str(rec), str(healthy), "--channel", "DE", "--name", "g",
             "--model-gain", "vsm", "-o", str(out), cwd=tmp_path)  # fmt: skip
    assert r.returncode == 0, r.stderr
    (g,) = load_rig(out).model_gains
    assert g.model == "vsm" and 0.0 < g.scale < 1.0
    assert "48k_Drive_End_OR007@6_0_135.mat" in g.provenance and "normal_0_97" not in g.provenance
    assert "--model-gain vsm" in load_rig(out).provenance
    out.unlink()
    r = _cli("rig", "identify", str(healthy), "--channel", "DE", "--name", "g", "--model-gain",
             "vsm", "-o", str(out), cwd=tmp_path)  # fmt: skip
    assert r.returncode == 2 and "no record has a bearing fault" in r.stderr
    assert r.stderr.count("\n") == 1 and not out.exists()
    alone = tmp_path / "135.mat"
    alone.write_bytes(rec.read_bytes())
    r = _cli("rig", "identify", str(alone), "--name", "g", "--fs-hz", "48000", "--model-gain",
             "vsm", "-o", str(out), cwd=tmp_path)  # fmt: skip
    assert r.returncode == 2 and "is not in" in r.stderr and "manifest.csv" in r.stderr
    assert "--conditions FILE.csv" in r.stderr  # the way for a user's own records
    assert r.stderr.count("\n") == 1 and not out.exists()


@pytest.mark.skipif(not CWRU.is_dir(), reason="needs ../shared/data/cwru")
def test_cli_identify_model_gain_from_a_users_conditions_file(tmp_path):
    """A user's own machine (issue 16 item 4: "A user's own machine gets its profile the same
    way"): records outside a CWRU manifest get their model gain from a --conditions CSV. Records
    135 and 97 (healthy) copied under other names, with their CWRU conditions written in the
    CSV, give the same VSM gain as the manifest route, to round-off (the same simulation); the
    healthy row is skipped. Bad files are one-line errors before any simulation, writing nothing."""
    rec, healthy = CWRU / "48k_Drive_End_OR007@6_0_135.mat", CWRU / "normal_0_97.mat"
    ref = tmp_path / "ref.toml"
    r = _cli("rig", "identify", str(rec), str(healthy), "--channel", "DE", "--name", "g",
             "--model-gain", "vsm", "-o", str(ref), cwd=tmp_path)  # fmt: skip
    assert r.returncode == 0, r.stderr
    mine = tmp_path / "mine"
    mine.mkdir()
    (mine / "run1.mat").write_bytes(rec.read_bytes())
    (mine / "run0.mat").write_bytes(healthy.read_bytes())
    cond = mine / "conditions.csv"
    cond.write_text(
        "file,fault,bearing,defect_width_m,defect_depth_m\n"
        f"run1.mat,outer,6205-cwru,{0.007 * 0.0254!r},{0.011 * 0.0254!r}\n"
        "run0.mat,none,,,\n",
        encoding="utf-8",
    )
    out = mine / "rig.toml"
    r = _cli("rig", "identify", "run1.mat", "run0.mat", "--channel", "DE", "--fs-hz", "48000",
             "--name", "g", "--model-gain", "vsm", "--conditions", "conditions.csv", "-o",
             "rig.toml", cwd=mine)  # fmt: skip
    assert r.returncode == 0, r.stderr
    (g,) = load_rig(out).model_gains
    assert g.scale == pytest.approx(load_rig(ref).model_gain("vsm").scale, rel=1e-9)
    assert "run1.mat" in g.provenance and "--conditions conditions.csv" in load_rig(out).provenance
    out.unlink()
    # a spreadsheet's "CSV UTF-8" (a byte-order mark) with padded header names reads the same
    text = cond.read_text(encoding="utf-8").replace("file,fault,", " file , fault ,", 1)
    (mine / "excel.csv").write_bytes(b"\xef\xbb\xbf" + text.encode("utf-8"))
    r = _cli("rig", "identify", "run1.mat", "run0.mat", "--channel", "DE", "--fs-hz", "48000",
             "--name", "g", "--model-gain", "vsm", "--conditions", "excel.csv", "-o",
             "rig.toml", cwd=mine)  # fmt: skip
    assert r.returncode == 0, r.stderr
    assert load_rig(out).model_gain("vsm").scale == pytest.approx(g.scale, rel=1e-12)
    out.unlink()
    bad = {
        "no_width.csv": ("file,fault,bearing\nrun1.mat,outer,6205-cwru\n",
                         "column 'defect_width_m' is missing"),
        "fault.csv": ("file,fault,bearing,defect_width_m\nrun1.mat,crack,6205-cwru,1e-4\n",
                      "line 2: fault = 'crack' is invalid"),
        "width.csv": ("file,fault,bearing,defect_width_m\nrun1.mat,outer,6205-cwru,-1\n",
                      "width.csv, line 2: defect_width_m = -1 is out of range"),
        "other.csv": ("file,fault,bearing,defect_width_m\nrun9.mat,outer,6205-cwru,1e-4\n",
                      "record 'run1.mat' is not listed (rows name 'run9.mat')"),
        "colour.csv": ("file,fault,bearing,defect_width_m,colour\nrun1.mat,outer,6205,1e-4,red\n",
                       "unknown column 'colour'"),
        # exploratory testing (fourteenth session): tracebacks or messages without a place
        "extra.csv": ("file,fault,bearing,defect_width_m\nrun1.mat,outer,6205,1e-4,red\n",
                      "line 2: more fields than the header's 4"),
        "blank.csv": ("file,fault,bearing,defect_width_m\nrun1.mat,outer,,1e-4\n",
                      "blank.csv, line 2: bearing"),
        "nosuch.csv": ("file,fault,bearing,defect_width_m\nrun1.mat,outer,nosuch.toml,1e-4\n",
                       "nosuch.csv, line 2: bearing_file"),
        # exploratory testing (twenty-fourth session): a row's rpm the record refutes was
        # accepted, and the gain was fitted to another condition
        "speed.csv": ("file,fault,bearing,defect_width_m,rpm\nrun1.mat,outer,6205,1e-4,1500\n",
                      "speed.csv, line 2: rpm = 1500 r/min for 'run1.mat', whose own speed is"),
        # a width the model refuses named neither file nor line (twenty-fifth session)
        "wide.csv": ("file,fault,bearing,defect_width_m\nrun1.mat,outer,6205,0.02\n",
                     "wide.csv, line 2: defect_width_m = 0.02 m is wider than the ball"),
    }  # fmt: skip
    (mine / "latin1.csv").write_bytes(
        b"file,fault,bearing,defect_width_m\nrun1.mat,outer,6205,1e-4 # caf\xe9\n"
    )
    bad["latin1.csv"] = (None, "is not UTF-8; valid: a UTF-8 text file")
    for name, (text, message) in bad.items():
        if text is not None:
            (mine / name).write_text(text, encoding="utf-8")
        r = _cli("rig", "identify", "run1.mat", "--channel", "DE", "--fs-hz", "48000", "--name",
                 "g", "--model-gain", "vsm", "--conditions", name, "-o", "rig.toml",
                 cwd=mine)  # fmt: skip
        assert r.returncode == 2 and message in r.stderr, (name, r.stderr)
        assert r.stderr.count("\n") == 1 and not out.exists()
    # a pit row is checked as a pit with --defect-profile pit (twenty-fifth session: the check
    # took the slot's profile, and the pit's error came after the other rows' simulations,
    # naming no row)
    (mine / "pit.csv").write_text(
        "file,fault,bearing,defect_width_m,defect_depth_m\nrun1.mat,outer,6205,3e-4,1e-9\n"
    )
    r = _cli("rig", "identify", "run1.mat", "--channel", "DE", "--fs-hz", "48000", "--name", "g",
             "--model-gain", "dem", "--defect-profile", "pit", "--conditions", "pit.csv", "-o",
             "rig.toml", cwd=mine)  # fmt: skip
    assert r.returncode == 2 and r.stderr.startswith(
        "error: --conditions pit.csv, line 2: defect_depth_m = 1e-09 m is not deeper than a "
        "ball sinks"
    ), r.stderr
    # CWRU-format records of another machine: the rows' bearing is the rig's, not the CWRU
    # end's 6205-cwru (twenty-fifth session: the end's won, and runs of the rows' own size
    # through the rig were warned)
    (mine / "b6206.csv").write_text("file,fault,bearing,defect_width_m\nrun1.mat,outer,6206,3e-4\n")
    r = _cli("rig", "identify", "run1.mat", "--channel", "DE", "--fs-hz", "48000", "--name", "g",
             "--model-gain", "vsm", "--conditions", "b6206.csv", "-o", "rig.toml",
             cwd=mine)  # fmt: skip
    assert r.returncode == 0 and "RigBearingWarning" not in r.stderr, r.stderr
    assert load_rig(out).bearing == "6206"
    out.unlink()
    for extra, message in (
        (("--model-gain", "rotor", "--conditions", "conditions.csv"), "rotor model is the CWRU"),
        (("--conditions", "conditions.csv"), "--conditions is only read with --model-gain"),
    ):
        r = _cli("rig", "identify", "run1.mat", "--channel", "DE", "--fs-hz", "48000", "--name",
                 "g", *extra, "-o", "rig.toml", cwd=mine)  # fmt: skip
        assert r.returncode == 2 and message in r.stderr, r.stderr
        assert not out.exists()


def test_a_conditions_files_own_bearing_is_recorded_by_its_size(tmp_path):
    """Exploratory testing (twenty-fourth session): with a --conditions file naming a bearing
    TOML the rig recorded no ``bearing``, and a later run of another size through it was not
    warned. The rig now records that bearing's size (a ``[bearing]`` table); rows of different
    sizes record none, and the command says so after writing the rig."""
    import shutil
    import warnings

    from bearingsim.rig import RigBearing, RigBearingWarning

    paths = []
    for s in range(2):
        rec = _impacts(seed=s)
        p = tmp_path / f"m{s}.csv"
        np.savetxt(p, rec.x, header="acc_m_per_s2", comments="")
        paths.append(p.name)
    shutil.copy(Path(bearingsim.__file__).parent / "catalog" / "6205-cwru.toml",
                tmp_path / "mine.toml")  # fmt: skip
    (tmp_path / "c.csv").write_text(
        "file,fault,bearing,defect_width_m\nm0.csv,outer,mine.toml,3e-4\nm1.csv,none,,\n"
    )
    r = _cli("rig", "identify", *paths, "--name", "b", "--fs-hz", "12000", "--rpm", "1750",
             "--model-gain", "vsm", "--conditions", "c.csv", "-o", "b.toml",
             cwd=tmp_path)  # fmt: skip
    assert r.returncode == 0, r.stderr
    assert "names no bearing" not in r.stderr, r.stderr
    cw = bearingsim.catalog.get_bearing("6205-cwru")
    rig = load_rig(tmp_path / "b.toml")
    assert rig.bearing == RigBearing(cw.id, 9, cw.pitch_diameter, cw.element_diameter)
    assert "[bearing]" in (tmp_path / "b.toml").read_text()
    r = _cli("rig", "show", "b.toml", cwd=tmp_path)
    assert ("identified on records of the 6205-cwru (pitch diameter 39.04 mm, 9 elements of "
            "7.94 mm)") in r.stdout, r.stdout  # fmt: skip
    with pytest.warns(RigBearingWarning, match="identified on records of the 6205-cwru"):
        simulate(dict(model="vsm", duration_s=0.01, bearing="6206", rig=str(tmp_path / "b.toml")))
    with warnings.catch_warnings():
        warnings.simplefilter("error", RigBearingWarning)
        simulate(dict(model="vsm", duration_s=0.01, bearing="6205", rig=str(tmp_path / "b.toml")))
    # rows of two sizes record none (the command then says so); one catalogue id is kept as
    # its id, and a file of a catalogue bearing's size under the catalogue's name is one size
    from bearingsim.cli.rig import _conditions_bearing

    f = str(tmp_path / "mine.toml")
    assert _conditions_bearing([{"bearing_file": f}, {"bearing": "6206"}]) is None
    assert _conditions_bearing([{"bearing": "6206"}, {"bearing": "6206"}, {}]) == "6206"
    # one size under two names: the catalogue's id is recorded; the 6205 and the CWRU's 6205
    # (0.1 % apart) are one size, as RigBearingWarning judges (twenty-fifth session)
    assert _conditions_bearing([{"bearing_file": f}, {"bearing": "6205-cwru"}]) == "6205-cwru"
    assert _conditions_bearing([{"bearing": "6205"}, {"bearing": "6205-cwru"}]) == "6205"
    assert _conditions_bearing([{}]) is None


def test_shipped_profiles_load_and_carry_their_command():
    """The three CWRU profiles (issue 16 item 4), each identified only from the records of
    ../shared/data/cwru by the command in its provenance."""
    from bearingsim.rig import available_rigs

    assert {"cwru-de-12k", "cwru-de-48k", "cwru-fe-12k"} <= set(available_rigs())
    for name, ch in (("cwru-de-12k", "DE"), ("cwru-de-48k", "DE"), ("cwru-fe-12k", "FE")):
        rig = load_rig(name)
        assert rig.name == name and rig.modes
        assert rig.provenance.startswith(
            "identified by `bearingsim rig identify ../shared/data/cwru/"
        )
        assert f"--channel {ch}" in rig.provenance and f"--name {name}" in rig.provenance
        rig.check_rate(12000.0 if "12k" in name else 48000.0)
        # the rotor's model-based path gain, identified by the same command (fourteenth
        # session): the rotor's output lies below the background of every profile
        assert "--model-gain rotor" in rig.provenance
        assert [g.model for g in rig.model_gains] == ["rotor"]
        assert rig.model_gain("rotor").scale > 1.0


@pytest.mark.skipif(not CWRU.is_dir(), reason="needs ../shared/data/cwru")
def test_cli_identify_gain_method_spectral_writes_the_fitted_path(tmp_path):
    """`rig identify --model-gain vsm --gain-method spectral`: the VSM's path fitted with its
    output as the known input, written as path_gain and mode_gains (one per mode) with the
    output-only path kept for other models; the --conditions route for a user's copy of the
    records gives the same gains; `rig show` and `simulate --rig` name the fitted path;
    --gain-method without --model-gain is a one-line error writing nothing."""
    rec, healthy = CWRU / "48k_Drive_End_OR007@6_0_135.mat", CWRU / "normal_0_97.mat"
    out = tmp_path / "rig.toml"
    r = _cli("rig", "identify", str(rec), str(healthy), "--channel", "DE", "--name", "g",
             "--model-gain", "vsm", "--gain-method", "spectral", "--json", "-o", str(out),
             cwd=tmp_path)  # fmt: skip
    assert r.returncode == 0, r.stderr
    rig = load_rig(out)
    (g,) = rig.model_gains
    assert g.scale is None and len(g.mode_gains) == len(rig.modes) and g.path_gain >= 0.0
    assert rig.gain == 1.0, "the output-only path stays for the other models"
    assert "log Welch spectra" in g.provenance and rec.name in g.provenance
    assert "model_path_fit" in rig.provenance and "--gain-method spectral" in rig.provenance
    got = json.loads(r.stdout)
    assert got["model_paths"]["vsm"]["mode_gains"] == list(g.mode_gains)
    assert got["model_gains"] == {"vsm": None}
    show = _cli("rig", "show", str(out), cwd=tmp_path)
    assert f"fitted path: direct gain {g.path_gain:.4g}" in show.stdout, show.stdout
    sim = _cli("simulate", "--model", "vsm", "--fault", "outer", "--duration-s", "0.1",
               "--fs-hz", "48000", "--rig", str(out), "-o", str(tmp_path / "s.nc"),
               cwd=tmp_path)  # fmt: skip
    assert sim.returncode == 0 and "fitted path: direct gain" in sim.stdout, sim.stderr
    mine = tmp_path / "mine"
    mine.mkdir()
    (mine / "run1.mat").write_bytes(rec.read_bytes())
    (mine / "run0.mat").write_bytes(healthy.read_bytes())
    (mine / "c.csv").write_text(
        "file,fault,bearing,defect_width_m,defect_depth_m\n"
        f"run1.mat,outer,6205-cwru,{0.007 * 0.0254!r},{0.011 * 0.0254!r}\n"
        "run0.mat,none,,,\n",
        encoding="utf-8",
    )
    r = _cli("rig", "identify", "run1.mat", "run0.mat", "--channel", "DE", "--fs-hz", "48000",
             "--name", "g", "--model-gain", "vsm", "--gain-method", "spectral", "--conditions",
             "c.csv", "-o", "rig.toml", cwd=mine)  # fmt: skip
    assert r.returncode == 0, r.stderr
    mg = load_rig(mine / "rig.toml").model_gain("vsm")
    assert (mg.path_gain, *mg.mode_gains) == pytest.approx((g.path_gain, *g.mode_gains),
                                                           rel=1e-6, abs=1e-12)  # fmt: skip
    bad = tmp_path / "bad.toml"
    r = _cli("rig", "identify", str(rec), "--channel", "DE", "--name", "g", "--gain-method",
             "spectral", "-o", str(bad), cwd=tmp_path)  # fmt: skip
    assert r.returncode == 2 and "--gain-method spectral is only read with --model-gain" in (
        r.stderr
    )
    assert r.stderr.count("\n") == 1 and not bad.exists()


@settings(max_examples=6, deadline=None)
@given(st.floats(0.1, 10.0))
def test_the_path_fit_scales_with_the_records(c):
    """A property of the fit (both objectives are homogeneous): records and background c times
    louder in amplitude (c² in power) give gains c times larger, to the optimiser's
    tolerance."""
    from bearingsim.rig import Background, Mode, Rig
    from bearingsim.rig_identify import fit_path_gains

    modes = (Mode(2000.0, 0.02, 3.0, "test"), Mode(4500.0, 0.015, 1.0, "test"))
    bg = Background((10.0, 6000.0), (1e-4, 1e-4), "test")
    true = Rig(name="true", description="", provenance="test", gain=0.1, modes=modes,
               background=bg)  # fmt: skip
    pairs = _path_pairs(true, n_rec=1)
    loud_bg = Background((10.0, 6000.0), (c * c * 1e-4, c * c * 1e-4), "test")
    one = fit_path_gains(replace(true, background=bg), pairs, 12000.0)
    many = fit_path_gains(
        replace(true, background=loud_bg), [(c * y, x) for y, x in pairs], 12000.0
    )
    assert many.gains == pytest.approx(tuple(c * g for g in one.gains), rel=2e-3, abs=1e-9)


@settings(max_examples=200, deadline=None)
@given(text=st.text(st.characters(blacklist_categories=("Cs",)), max_size=40))
def test_any_name_or_description_round_trips_through_the_rig_file(text):
    # twenty-first session: `rig identify --description $'line1\nline2'` wrote a TOML string
    # holding a raw newline, and the round-trip check failed with tomllib's traceback
    import tomllib

    rig = replace(load_rig("cwru-de-12k"), description=text)
    assert tomllib.loads(rig_to_toml(rig))["description"] == text


@pytest.mark.skipif(not CWRU.is_dir(), reason="needs ../shared/data/cwru")
def test_a_name_that_is_not_utf8_is_one_line(tmp_path):
    # twenty-first session: `--name $'bad\xffname'` reached the writer as a surrogate and
    # ended in UnicodeEncodeError's traceback (exit 1)
    rec = CWRU / "12k_Drive_End_OR007@6_2_132.mat"
    env = {**os.environ, "PYTHONPATH": SRC}
    args = [sys.executable, "-m", "bearingsim", "rig", "identify", str(rec), "--name"]
    r = subprocess.run([*args, b"bad\xffname", "-o", "r.toml"], capture_output=True, env=env,
                       cwd=tmp_path)  # fmt: skip
    err = r.stderr.decode("utf-8", "replace")
    assert r.returncode == 2 and err.count("\n") == 1, err
    assert "is not UTF-8 text" in err and not (tmp_path / "r.toml").exists()


@pytest.mark.skipif(not CWRU.is_dir(), reason="needs ../shared/data/cwru")
def test_an_output_that_is_a_bearing_file_the_conditions_name_is_refused(tmp_path):
    # twenty-first session (a helper on this session's changes): `-o mybrg.toml` where the
    # --conditions CSV names mybrg.toml as a record's bearing replaced the user's bearing file
    import bearingsim.catalog

    (tmp_path / "run1.mat").write_bytes((CWRU / "48k_Drive_End_OR007@6_0_135.mat").read_bytes())
    cat = Path(bearingsim.catalog.__file__).parent / "6205-cwru.toml"
    brg = tmp_path / "mybrg.toml"
    brg.write_text(cat.read_text(encoding="utf-8"), encoding="utf-8")
    (tmp_path / "c.csv").write_text(
        f"file,fault,bearing,defect_width_m\nrun1.mat,outer,mybrg.toml,{0.007 * 0.0254!r}\n",
        encoding="utf-8",
    )
    before = brg.read_text(encoding="utf-8")
    r = _cli("rig", "identify", "run1.mat", "--channel", "DE", "--fs-hz", "48000", "--name",
             "g", "--model-gain", "vsm", "--conditions", "c.csv", "-o", "mybrg.toml",
             cwd=tmp_path)  # fmt: skip
    assert r.returncode == 2 and "that --conditions names" in r.stderr, r.stderr
    assert brg.read_text(encoding="utf-8") == before


def test_a_conditions_rows_speed_is_judged_by_its_records_speed_column(tmp_path):
    """A row's ``rpm`` against its record's speed column takes the rule ``--rpm`` has (a
    speed outside the column's 1st-99th percentile range by more than 1 % is refused; a
    run-up takes any speed it passed through), and the error names the line (twenty-fifth
    session: it compared with the column's median and named no line)."""
    rec = _impacts(seed=0)
    t = np.arange(rec.x.size) / 12000.0
    for name, rpm in (("steady.csv", np.full(t.size, 1500.0)),
                      ("runup.csv", np.linspace(1000.0, 2000.0, t.size))):  # fmt: skip
        np.savetxt(tmp_path / name, np.c_[t, rec.x, rpm], delimiter=",",
                   header="time_s,acc_m_per_s2,rpm", comments="")  # fmt: skip
    for name, rpm, ok in (("steady.csv", 1000, False), ("runup.csv", 1200, True)):
        (tmp_path / "c.csv").write_text(
            f"file,fault,bearing,defect_width_m,rpm\n{name},outer,6205,3e-4,{rpm}\n"
        )
        r = _cli("rig", "identify", name, "--name", "s", "--model-gain", "vsm", "--conditions",
                 "c.csv", "-o", "s.toml", cwd=tmp_path)  # fmt: skip
        if ok:
            assert "contradicts" not in r.stderr and "speed column holds" not in r.stderr, r.stderr
        else:
            assert r.returncode == 2 and r.stderr == (
                "error: --conditions c.csv, line 2: rpm = 1000 r/min for 'steady.csv', whose "
                "speed column holds 1500 r/min; valid: a speed it holds (or an empty rpm, to "
                "take its median)\n"
            ), r.stderr


@pytest.mark.skipif(not CWRU.is_dir(), reason="needs ../shared/data/cwru")
def test_a_conditions_rows_speed_serves_a_record_without_one(tmp_path):
    """Exploratory testing (twenty-fifth session): a --conditions row's ``rpm`` for a record
    without a speed of its own reached the model gain only: the rig still warned "no shaft
    speed", got no shaft-order tones and no ``rpm_range``; and a row typed in Hz (29.1 for
    1748 r/min) was taken silently. Record 107's first 3 s written without its speed: the row's
    1748 r/min now gives the tones and the range, unwarned; 29.1 is warned, naming the line
    (a warning: a slow shaft may have a comb at 60 times its speed), as ``--rpm 29.1`` is; a
    healthy row's rpm is read (and checked) too."""
    from bearingsim.cli.rig import _user_conditions

    rec = read_signal(CWRU / "12k_Drive_End_IR007_2_107.mat", channel="DE")
    n = int(3 * rec.fs)
    np.savetxt(tmp_path / "mine.csv", np.c_[np.arange(n) / rec.fs, rec.x[:n]], delimiter=",",
               header="time_s,acc_m_per_s2", comments="")  # fmt: skip
    (tmp_path / "ok.csv").write_text(
        "file,fault,bearing,defect_width_m,rpm\nmine.csv,inner,6205-cwru,1.778e-4,1748\n"
    )
    r = _cli("rig", "identify", "mine.csv", "--name", "m", "--model-gain", "vsm",
             "--conditions", "ok.csv", "-o", "m.toml", cwd=tmp_path)  # fmt: skip
    assert r.returncode == 0 and "no shaft speed" not in r.stderr, r.stderr
    rig = load_rig(tmp_path / "m.toml")
    assert rig.rpm_range == (1748.0, 1748.0) and len(rig.tones) >= 1
    r = _cli("rig", "identify", "mine.csv", "--name", "m", "-o", "h.toml", cwd=tmp_path)
    assert r.returncode == 0 and "warning: no shaft speed for mine.csv" in r.stderr
    assert load_rig(tmp_path / "h.toml").rpm_range is None
    r = _cli("rig", "identify", "mine.csv", "--name", "m", "--rpm", "29.1", "-o", "h.toml",
             cwd=tmp_path)  # fmt: skip
    assert r.returncode == 0, r.stderr
    assert "warning: mine.csv: rpm = 29.1 r/min reads like the speed in Hz" in r.stderr
    (tmp_path / "hz.csv").write_text(
        "file,fault,bearing,defect_width_m,rpm\nmine.csv,inner,6205-cwru,1.778e-4,29.1\n"
    )
    recs = [read_signal(tmp_path / "mine.csv")]
    warned: list[str] = []
    (pair,) = _user_conditions(str(tmp_path / "hz.csv"), ("mine.csv",), recs, ("vsm",), {},
                               warned)  # fmt: skip
    assert pair[0].rpm == 29.1 and recs[0].rpm == 29.1  # taken, as written
    assert len(warned) == 1 and warned[0].startswith(
        f"warning: --conditions {tmp_path / 'hz.csv'}, line 2: mine.csv: rpm = 29.1 r/min "
        "reads like the speed in Hz"
    ), warned
    (tmp_path / "none.csv").write_text(
        "file,fault,bearing,defect_width_m,rpm\nmine.csv,none,,,fast\n"
    )
    r = _cli("rig", "identify", "mine.csv", "--name", "m", "--model-gain", "vsm",
             "--conditions", "none.csv", "-o", "n.toml", cwd=tmp_path)  # fmt: skip
    assert r.returncode == 2 and r.stderr == (
        "error: --conditions none.csv, line 2: rpm = 'fast' is not a number\n"
    ), r.stderr


@pytest.mark.skipif(not CWRU.is_dir(), reason="needs ../shared/data/cwru")
def test_identify_refuses_a_rpm_far_from_the_files_own(tmp_path):
    """Exploratory testing (twenty-sixth session): ``rig identify`` of record 107 (X107RPM
    1748) took ``--rpm`` 1000-2500 and wrote a rig whose tones and ``rpm_range`` sat at that
    speed, while 1797 was refused: the shaft-comb check searched ±5 % of the speed given.
    The comb near the file's speed refutes 2000 now, in one line, writing nothing; a record
    whose shaft lines cannot tell (174, none stand out) is warned that the speed overrides
    its file's."""
    r = _cli("rig", "identify", str(CWRU / "12k_Drive_End_IR007_2_107.mat"), "--name", "a",
             "--rpm", "2000", "-o", "a.toml", cwd=tmp_path)  # fmt: skip
    assert r.returncode == 2 and r.stderr.startswith(
        "error: rpm = 2000 r/min: the shaft harmonics of '12k_Drive_End_IR007_2_107.mat' put "
        "its speed at 1747"
    ), r.stderr
    assert r.stderr.count("\n") == 1 and not (tmp_path / "a.toml").exists()
    r = _cli("rig", "identify", str(CWRU / "48k_Drive_End_IR014_0_174.mat"), "--name", "b",
             "--rpm", "1900", "-o", "b.toml", cwd=tmp_path)  # fmt: skip
    assert r.returncode == 0, r.stderr
    assert "warning: 48k_Drive_End_IR014_0_174.mat: rpm = 1900 r/min overrides the 1796 r/min" \
        in r.stderr, r.stderr  # fmt: skip


@pytest.mark.skipif(not CWRU.is_dir(), reason="needs ../shared/data/cwru")
def test_identify_refuses_a_steady_speed_column_the_shaft_lines_refute(tmp_path):
    """Exploratory testing (twenty-seventh session): record 172 (1728 r/min) with a constant
    speed column of 1800 r/min gave a rig with ``rpm_range = [1800, 1800]``; a steady column
    is judged as ``--rpm`` is, in one line, writing nothing."""
    from bearingsim.io.signal import read_signal

    rec = read_signal(CWRU / "12k_Drive_End_IR014_3_172.mat", channel="DE")
    t = np.arange(rec.x.size) / rec.fs
    np.savetxt(tmp_path / "c.csv", np.c_[t, rec.x, np.full(t.size, 1800.0)], delimiter=",",
               header="time_s,acc_m_per_s2,rpm", comments="")  # fmt: skip
    r = _cli("rig", "identify", "c.csv", "--name", "a", "-o", "a.toml", cwd=tmp_path)
    assert r.returncode == 2 and r.stderr == (
        "error: the speed column of 'c.csv' (median 1800 r/min) is refuted by its shaft "
        "harmonics, which put its speed at 1726.87 r/min (the column is +4.23 % off it); valid: "
        "a column with the record's speed (or --rpm R)\n"
    ), r.stderr
    assert not (tmp_path / "a.toml").exists()
    # the way on the message gives (twenty-eighth session: --rpm 1727 was refused as
    # contradicting the column, so only an edit of the file got past it) ...
    r = _cli("rig", "identify", "c.csv", "--rpm", "1727", "--name", "a", "-o", "a.toml",
             cwd=tmp_path)  # fmt: skip
    assert r.returncode == 0, r.stderr
    assert (
        "warning: c.csv: rpm = 1727 r/min overrides the 1800 r/min steady speed column its "
        "shaft harmonics refute (-4.06 %)" in r.stderr
    ), r.stderr
    assert "rpm_range = [1727.0, 1727.0]" in (tmp_path / "a.toml").read_text()
    # ... but not a speed the record refutes too, nor one contradicting a column it confirms
    (tmp_path / "a.toml").unlink()
    r = _cli("rig", "identify", "c.csv", "--rpm", "1650", "--name", "a", "-o", "a.toml",
             cwd=tmp_path)  # fmt: skip
    assert r.returncode == 2 and "put its speed at 1726" in r.stderr, r.stderr
    np.savetxt(tmp_path / "c.csv", np.c_[t, rec.x, np.full(t.size, 1727.0)], delimiter=",",
               header="time_s,acc_m_per_s2,rpm", comments="")  # fmt: skip
    r = _cli("rig", "identify", "c.csv", "--rpm", "1800", "--name", "a", "-o", "a.toml",
             cwd=tmp_path)  # fmt: skip
    assert r.returncode == 2 and "contradicts the speed column of 'c.csv'" in r.stderr, r.stderr
    assert not (tmp_path / "a.toml").exists()


@pytest.mark.skipif(not CWRU.is_dir(), reason="needs ../shared/data/cwru")
def test_identify_speed_checks_on_short_and_weak_records(tmp_path):
    """Exploratory testing (twenty-sixth session): ``--rpm 29.95`` on record 174 raised a
    traceback (the shaft comb's ±0.5 % window held no grid point); 188 at 1690 r/min (its comb
    14.9 dB out) was only warned; two CSVs of one 12 kHz logger (rates 11999.9998 and
    11999.99996 Hz from their time columns) were refused as "12000 Hz, the first at 12000 Hz";
    a speed column in Hz was taken as r/min silently."""
    r = _cli("rig", "identify", str(CWRU / "48k_Drive_End_IR014_0_174.mat"), "--name", "t",
             "--rpm", "29.95", "-o", "a.toml", cwd=tmp_path)  # fmt: skip
    assert r.returncode == 0 and "Traceback" not in r.stderr, r.stderr
    assert "(-98.33 %; it reads like the speed in Hz)" in r.stderr, r.stderr
    r = _cli("rig", "identify", str(CWRU / "12k_Drive_End_B014_3_188.mat"), "--name", "t",
             "--rpm", "1690", "-o", "b.toml", cwd=tmp_path)  # fmt: skip
    assert r.returncode == 2 and "put its speed at 1722" in r.stderr, r.stderr
    rec = read_signal(CWRU / "12k_Drive_End_IR007_2_107.mat", channel="DE")
    for name, n, dt in (("a.csv", 24000, 1 / 11999.9998), ("b.csv", 12000, 1 / 11999.99996)):
        np.savetxt(tmp_path / name, np.c_[np.arange(n) * dt, rec.x[:n], np.full(n, 29.13)],
                   delimiter=",", header="time_s,acc_m_per_s2,rpm", comments="")  # fmt: skip
    r = _cli("rig", "identify", "a.csv", "b.csv", "--name", "t", "-o", "c.toml", cwd=tmp_path)
    assert r.returncode == 0, r.stderr
    assert "warning: a.csv: the speed column (median 29.13 r/min) reads like the speed in Hz" \
        in r.stderr, r.stderr  # fmt: skip
    # the reverse, r/min named speed_hz: rpm_range = [104880, 104880] was written unsaid
    n = 24000
    np.savetxt(tmp_path / "r.csv", np.c_[np.arange(n) / 12000.0, rec.x[:n], np.full(n, 1748.0)],
               delimiter=",", header="time_s,acc_m_per_s2,speed_hz", comments="")  # fmt: skip
    r = _cli("rig", "identify", "r.csv", "--name", "t", "-o", "r.toml", cwd=tmp_path)
    assert r.returncode == 0 and "reads like the speed in r/min in a column of Hz" in r.stderr
