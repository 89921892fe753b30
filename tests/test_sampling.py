"""The ring models' anti-aliased output (``antialias``; :mod:`bearingsim.dynamics.sampling`).

Reference values: the filter's specification (pass band to 0.9 of the output Nyquist frequency,
80 dB from it up; Kaiser 1974 window design through :func:`scipy.signal.kaiserord`) and the
sampling theorem: an impact train sampled without aliasing has no line at the beat of the
impact period against the sample grid.
"""

from __future__ import annotations

import numpy as np
import pytest
from scipy.signal import freqz

from bearingsim import simulate
from bearingsim.config import RingScenario
from bearingsim.dynamics.sampling import PASS, STOP_DB, decimate_antialias, fir_taps
from bearingsim.errors import ConfigError
from bearingsim.signal.envelope import envelope_spectrum


@pytest.mark.parametrize("q", [2, 4])
def test_fir_meets_its_specification(q):
    """Unit gain at 0 Hz, within 0.1 dB up to PASS x Nyquist, >= STOP_DB
    down from the output Nyquist frequency up (the Kaiser design's stated attenuation, 1 dB
    allowed for the window's approximation)."""
    h = fir_taps(q)
    assert h.size % 2 == 1
    assert h.sum() == pytest.approx(1.0, abs=1e-12)
    w, H = freqz(h, worN=1 << 15)  # w in [0, pi): pi / q is the output Nyquist frequency
    g = 20 * np.log10(np.abs(H) + 1e-300)
    assert np.max(np.abs(g[w <= PASS * np.pi / q])) < 0.1
    assert g[w >= np.pi / q].max() < -(STOP_DB - 1.0)


def _beat_line_db(res):
    """Envelope-spectrum line at the beat of BPFO against the sample grid, re the BPFO line
    [dB]."""
    fs = res.meta["fs_hz"]
    bpfo = res.meta["kinematics"]["bpfo_hz"]
    a = np.asarray(res["acc_y"])
    s = envelope_spectrum(a - a.mean(), fs, (500.0, 0.475 * fs))
    f, amp = s.freq, s.amplitude
    frac = (fs / bpfo) % 1.0
    beat = bpfo * min(frac, 1.0 - frac)

    def line(x):
        return amp[(f > x - 0.6) & (f < x + 0.6)].max()

    return 20 * np.log10(line(beat) / line(bpfo)), beat


def test_antialias_removes_the_sample_grid_line():
    """VSM outer race at 1797 r/min, 12 kHz: fs / BPFO = 111.77 samples, so the impacts fall
    0.23 sample later each time and the boxcar mean alone aliases a line at 24.8 Hz (measured
    -24 dB re BPFO); through the anti-aliasing filter it is below -60 dB."""
    sc = dict(model="vsm", bearing="6205-cwru", fault="outer", rpm=1797.0, duration_s=2.0)
    plain, beat = _beat_line_db(simulate(dict(sc, fs_hz=12000.0)))
    aa, _ = _beat_line_db(simulate(dict(sc, fs_hz=12000.0, antialias=True)))
    assert beat == pytest.approx(24.77, abs=0.05)
    assert plain > -30.0  # the artefact is there without the filter (the test can fail)
    assert aa < -60.0


def test_antialiased_run_is_the_fine_run_filtered():
    """A 12 kHz anti-aliased run integrates exactly the 48 kHz run (same steps, same bits) and
    outputs its filtered, decimated acceleration and its every 4th state sample."""
    sc = dict(model="dem", bearing="6205-cwru", fault="inner", duration_s=0.25)
    fine = simulate(dict(sc, fs_hz=48000.0))
    aa = simulate(dict(sc, fs_hz=12000.0, antialias=True))
    assert aa.meta["oversampling"] == 4
    assert aa.meta["dt_s"] == fine.meta["dt_s"]
    np.testing.assert_array_equal(aa["disp_y"], fine["disp_y"][::4])
    np.testing.assert_array_equal(aa.time, fine.time[::4])
    np.testing.assert_allclose(
        aa["acc_y"], decimate_antialias(np.asarray(fine["acc_y"]), 4), rtol=0, atol=1e-12
    )


def test_the_first_samples_do_not_depend_on_the_records_length():
    """The filter's start sees the record's start only: the first output samples of a record
    and of its first half are equal (the line through both ends that padded them before made
    the first ~50 differ; found by exploratory testing, twenty-first session). A simulation
    without slip is its own first half up to there, so the same holds for simulate."""
    rng = np.random.default_rng(0)
    x = np.cumsum(rng.normal(size=48000)) + 5.0 * rng.normal(size=48000)
    whole, half = decimate_antialias(x, 4), decimate_antialias(x[:24000], 4)
    np.testing.assert_array_equal(whole[:5900], half[:5900])
    # the end: the continuation in place of the signal that follows (differs, by design)
    assert np.abs(whole[5990:6000] - half[5990:6000]).max() > 0.0
    sc = dict(model="vsm", bearing="6205-cwru", fault="outer", fs_hz=12000.0, antialias=True)
    long, short = simulate(dict(sc, duration_s=0.2)), simulate(dict(sc, duration_s=0.1))
    np.testing.assert_array_equal(
        np.asarray(long["acc_y"])[:1100], np.asarray(short["acc_y"])[:1100]
    )


def test_antialias_default_follows_the_rig():
    """Off by default (the seed comparisons' sampling, bit for bit), on with a rig; 2x above
    24 kHz."""
    assert RingScenario(fs_hz=12000.0).oversampling == 1
    assert RingScenario(fs_hz=12000.0, rig="cwru-de-12k").oversampling == 4
    assert RingScenario(fs_hz=12000.0, rig="cwru-de-12k", antialias=False).oversampling == 1
    assert RingScenario(fs_hz=48000.0, antialias=True).oversampling == 2
    sc = dict(model="vsm", fault="outer", duration_s=0.05, fs_hz=12000.0)
    a, b = simulate(sc), simulate(dict(sc, antialias=False))
    np.testing.assert_array_equal(a["acc_y"], b["acc_y"])
    assert a.meta["oversampling"] == 1


def test_antialias_bad_value_one_line():
    with pytest.raises(ConfigError, match=r"^antialias = 'yes' is invalid; valid: true or false$"):
        RingScenario(antialias="yes")
