"""Cyclic spectral coherence and the enhanced envelope spectrum (``bearingsim.signal.coherence``;
issue 17, item 1: the view for records where the kurtogram's band misses the fault).

Reference values are derived in the docstrings from the definitions of Antoni, Xin & Hamzaoui
2017 (MSSP 92, 248–277), not taken from data.
"""

from __future__ import annotations

import numpy as np
import pytest
from scipy import signal as sps

from bearingsim.errors import ConfigError
from bearingsim.signal.benchmark import squared_envelope_spectrum
from bearingsim.signal.coherence import (
    coherence_window,
    cyclic_modulation_coherence,
    enhanced_envelope_spectrum,
)

FS = 12000.0


def _line(spec, f0: float) -> float:
    """Largest value within +-2 resolutions of ``f0``."""
    m = np.abs(spec.freq - f0) <= 2 * spec.resolution
    return float(spec.amplitude[m].max())


def _floor(spec, lo: float = 20.0, hi: float = 500.0) -> float:
    m = (spec.freq >= lo) & (spec.freq <= hi)
    return float(np.median(spec.amplitude[m]))


def test_amplitude_modulated_noise_has_its_coherence():
    """x = n(t) (1 + m cos 2 pi a0 t), n white: in every carrier the squared envelope is
    |N|^2 (1 + m cos)^2, whose mean is 1 + m^2/2 and whose component at a0 has one-sided
    magnitude m, so |gamma(a0, f)| = m / (1 + m^2/2) = 0.444 for m = 0.5, in every band; the
    estimate over 10 s (15 000 frames) within 10 %. At alpha = 0 the coherence is 1 by
    definition and the result gives 0 (the mean removed, as in the other views' spectra)."""
    rng = np.random.default_rng(11)
    t = np.arange(int(10 * FS)) / FS
    m, a0 = 0.5, 97.0
    x = rng.standard_normal(t.size) * (1 + m * np.cos(2 * np.pi * a0 * t))
    ees = enhanced_envelope_spectrum(x, FS, 500.0)
    assert abs(ees.amplitude[0]) < 1e-12
    assert _line(ees, a0) == pytest.approx(m / (1 + m**2 / 2), rel=0.10)
    # and at twice a0, the m^2/2 cos(2 a0) term: (m^2/4) / (1 + m^2/2) = 0.056
    assert _line(ees, 2 * a0) == pytest.approx(m**2 / 4 / (1 + m**2 / 2), rel=0.25)


def test_white_noise_has_no_cyclic_line():
    """Stationary white noise: no carrier is modulated; the estimate's own floor over 15 000
    frames is about 1/sqrt(15 000) = 0.008 per carrier, so no value above 0.05 in 5–500 Hz."""
    x = np.random.default_rng(12).standard_normal(int(10 * FS))
    ees = enhanced_envelope_spectrum(x, FS, 500.0)
    m = (ees.freq >= 5.0) & (ees.freq <= 500.0)
    assert ees.amplitude[m].max() < 0.05


def test_a_weak_band_counts_by_its_modulation_not_its_energy():
    """What the view is for: a train of 3 kHz ring-downs at 107 Hz (a BPFO) 30 dB below a
    stationary 0.5–1.5 kHz noise band. In the raw envelope spectrum the strong band buries the
    line (under 6 dB over the floor); in the enhanced envelope spectrum every carrier counts by
    its modulation depth and the line stands at least 10 dB over the floor."""
    rng = np.random.default_rng(13)
    n = int(10 * FS)
    t = np.arange(n) / FS
    train = np.zeros(n)
    period = FS / 107.0
    for k in range(int(n / period)):
        i = int(round(k * period + rng.normal(0, 0.01 * period)))
        if i < n:
            train[i] = 1.0
    ring = np.exp(-t[:120] * 1500.0) * np.sin(2 * np.pi * 3000.0 * t[:120])
    fault = np.convolve(train, ring)[:n]
    b, a = sps.butter(4, (500.0, 1500.0), btype="bandpass", fs=FS)
    loud = sps.lfilter(b, a, rng.standard_normal(n))
    fault *= 10 ** (-30 / 20) * loud.std() / fault.std()
    x = loud + fault + 1e-3 * loud.std() * rng.standard_normal(n)
    raw = squared_envelope_spectrum(x, FS)
    ees = enhanced_envelope_spectrum(x, FS, 500.0)
    raw_db = 20 * np.log10(_line(raw, 107.0) / _floor(raw))
    ees_db = 20 * np.log10(_line(ees, 107.0) / _floor(ees))
    assert raw_db < 6.0, raw_db
    assert ees_db > 10.0, ees_db


def test_window_passes_the_highest_cyclic_frequency_at_half_response():
    """The window rule (module docstring): the longest power of two whose Hann window passes
    alpha_max at >= 1/2 of its zero-frequency response; twice as long would not. The same
    carrier spacing at 12 and 48 kHz (750 Hz for alpha_max = 516 Hz, the 6205's lines at
    1797 r/min)."""
    from bearingsim.signal.coherence import _cyclic_response, _hann

    for fs in (12000.0, 48000.0):
        nw, hop = coherence_window(fs, 516.0)
        assert fs / nw == 750.0
        assert _cyclic_response(_hann(nw) ** 2, np.array([516.0]), fs)[0] >= 0.5
        assert _cyclic_response(_hann(2 * nw) ** 2, np.array([516.0]), fs)[0] < 0.5
        assert fs / hop >= 2 * 516.0 and hop <= nw // 4


def test_carrier_band_keeps_its_bins():
    """A carrier band keeps the STFT bins within half a spacing of it (never DC or Nyquist)."""
    x = np.random.default_rng(14).standard_normal(int(2 * FS))
    c = cyclic_modulation_coherence(x, FS, 500.0, carrier_band=(2000.0, 4000.0))
    assert c.carrier.min() >= 2000.0 - 375.0 and c.carrier.max() <= 4000.0 + 375.0
    d = cyclic_modulation_coherence(x, FS, 500.0)
    assert d.carrier.min() >= 500.0 and d.carrier.max() < FS / 2
    assert d.gamma.shape == (d.carrier.size, d.alpha.size)
    assert d.band == (d.carrier[0] - 375.0, d.carrier[-1] + 375.0)  # what the view reports


@pytest.mark.parametrize(
    "kwargs, field",
    [
        (dict(alpha_max=2000.0), "alpha_max_hz"),
        (dict(alpha_max=-1.0), "alpha_max_hz"),
        (dict(alpha_max=500.0, carrier_band=(5000.0, 7000.0)), "carrier_band"),
        (dict(alpha_max=500.0, carrier_band=(3000.0, 2000.0)), "carrier_band"),
        (dict(alpha_max=500.0, carrier_band=("a", "b")), "carrier_band"),
        (dict(alpha_max=500.0, carrier_band=(1.0, 2.0, 3.0)), "carrier_band"),
        (dict(alpha_max=500.0, carrier_band=5.0), "carrier_band"),
        (dict(alpha_max=500.0, carrier_band=(float("nan"), 3000.0)), "carrier_band"),
        (dict(alpha_max=1e-4), "alpha_max_hz"),
        (dict(alpha_max=1e-3), "samples"),
    ],
)
def test_bad_input_is_one_line(kwargs, field):
    x = np.random.default_rng(15).standard_normal(int(FS))
    with pytest.raises(ConfigError) as e:
        cyclic_modulation_coherence(x, FS, **kwargs)
    assert field in str(e.value) and "\n" not in str(e.value)


def test_short_and_nan_signals_are_refused():
    with pytest.raises(ConfigError, match="samples"):
        cyclic_modulation_coherence(np.ones(50), FS, 500.0)
    x = np.random.default_rng(16).standard_normal(int(FS))
    x[10] = np.nan
    with pytest.raises(ConfigError):
        cyclic_modulation_coherence(x, FS, 500.0)


def test_a_verdict_shown_in_the_coherence_view_is_plotted_as_a_coherence():
    """CWRU 185 (ball 0.014 in; measured): its best view is the coherence's (the cage line,
    docs/validation.md's benchmark table). The figure says what that spectrum is: a mean
    coherence [-], not a squared envelope in the signal's unit squared."""
    from conftest import CWRU

    from bearingsim.catalog import resolve_bearing
    from bearingsim.io.signal import read_signal
    from bearingsim.signal.fused import diagnose_fused

    path = CWRU / "12k_Drive_End_B014_0_185.mat"
    if not path.is_file():
        pytest.skip(f"shared CWRU data not available in {CWRU}")
    rec = read_signal(path, channel="DE")
    d = diagnose_fused(rec.x, rec.fs, resolve_bearing("6205-cwru"), rec.rpm / 60.0)
    assert d.best_view.name == "csc"
    assert d.band_hz == (375.0, 5625.0)  # the carriers averaged (750-5250 Hz), not 0-6000 Hz
    fig = d.plot(unit="m/s^2")
    ax = fig.axes[0]
    assert "enhanced envelope spectrum" in ax.get_title()
    assert "coherence" in ax.get_ylabel() and "m/s^2" not in ax.get_ylabel()
    assert ax.get_xlabel() == "cyclic frequency [Hz]"
    plt_close = fig
    fig = d.plot(title="185.mat [DE]: ball", unit="m/s^2")  # a caller's title keeps the view
    assert "csc: enhanced envelope spectrum, band 375-5625 Hz" in fig.axes[0].get_title()
    import matplotlib.pyplot as plt

    plt.close(plt_close)
    import matplotlib.pyplot as plt

    plt.close(fig)


def test_a_rate_too_low_for_the_coherence_leaves_four_views():
    """At 2 kHz the 6205's highest line read (516 Hz at 1797 r/min) needs a window shorter than
    the coherence's shortest (8 samples would pass only 250 Hz): the fused diagnosis runs the
    other four views and says why, instead of failing on a record the four views can read
    (the coherence view's first version refused it)."""
    from bearingsim.signal.fused import diagnose_fused

    x = np.random.default_rng(17).standard_normal(int(20 * 2000.0))
    d = diagnose_fused(x, 2000.0, "6205-cwru", 1797.0 / 60.0)
    assert [v.name for v in d.views] == ["raw", "cpw", "drs_sk", "drs_info"]
    assert d.diagnosis == "none"
    note = next(n for n in d.notes if n.startswith("csc: not run"))
    assert "2000 Hz" in note and "516.508 Hz" in note and "other views decide" in note


def test_the_coherence_map_plots_with_units_and_marks():
    """The map and the enhanced spectrum on one cyclic axis: labelled, with units, no overlaps
    (``figure_problems``), the marked lines labelled left to right."""
    import matplotlib.pyplot as plt

    from bearingsim.plotting import figure_problems

    rng = np.random.default_rng(18)
    t = np.arange(int(4 * FS)) / FS
    x = rng.standard_normal(t.size) * (1 + 0.5 * np.cos(2 * np.pi * 97.0 * t))
    c = cyclic_modulation_coherence(x, FS, 500.0)
    fig = c.plot(lines={"2x": 194.0, "f0": 97.0})
    try:
        assert figure_problems(fig) == []
        a1, a2 = fig.axes[:2]
        assert a1.get_ylabel() == "carrier [kHz]"
        assert a2.get_xlabel() == "cyclic frequency [Hz]"
        labels = a2.get_legend_handles_labels()[1]
        assert labels == ["f0", "2x"]  # one entry each, left to right
    finally:
        plt.close(fig)


def test_extreme_rates_are_refused_before_any_window_is_built():
    """A rate 1e300 times the highest line, or a line so low that no window fits the record,
    is a one-line error within a second (exploratory testing: the window search built windows
    of ever more samples until the memory ran out)."""
    import time

    x = np.random.default_rng(19).standard_normal(int(10 * FS))
    for fs, alpha in ((1e300, 516.0), (FS, 1e-3), (FS, 1e-4)):
        t0 = time.perf_counter()
        with pytest.raises(ConfigError):
            cyclic_modulation_coherence(x, fs, alpha)
        assert time.perf_counter() - t0 < 1.0


def test_a_line_between_bins_keeps_its_coherence():
    """The frames' transform is zero padded twice: AM noise (m = 1, coherence 2/3) at 107.36 Hz
    (the 6205's BPFO, between two bins of a 10 s record) within 10 % of 2/3, as on a bin
    (exploratory testing: 0.43, 36 % low, without the padding)."""
    t = np.arange(int(10 * FS)) / FS
    for f0 in (100.0, 100.05, 107.36):
        x = np.random.default_rng(20).standard_normal(t.size) * (1 + np.cos(2 * np.pi * f0 * t))
        assert _line(enhanced_envelope_spectrum(x, FS, 516.0), f0) == pytest.approx(
            2 / 3, rel=0.10
        ), f0


def test_a_silent_signal_has_no_coherence():
    """All zeros, or a constant: zero everywhere (alpha = 0 included), no NaN."""
    for x in (np.zeros(int(FS)), np.full(int(FS), 1e5)):
        e = enhanced_envelope_spectrum(x, FS, 500.0)
        assert np.all(e.amplitude == 0.0) or np.max(np.abs(e.amplitude)) < 1e-12


def test_a_leaderless_verdict_reports_the_kurtogram_band():
    """A "none" verdict has no family to pick the best view by; it reports the benchmark
    method's view (DRS, kurtogram band), whatever other views ran (exploratory testing: with
    the coherence view appended the positional fallback became the infogram's)."""
    from bearingsim.signal.fused import diagnose_fused

    x = np.random.default_rng(21).standard_normal(int(10 * FS))
    d = diagnose_fused(x, FS, "6205-cwru", 1797.0 / 60.0)
    assert d.diagnosis == "none"
    assert d.best_view.name == "drs_sk"


def test_marked_lines_must_be_numbers():
    x = np.random.default_rng(22).standard_normal(int(2 * FS))
    c = cyclic_modulation_coherence(x, FS, 500.0)
    with pytest.raises(ConfigError, match="lines"):
        c.plot(lines={"b": "x"})
    with pytest.raises(ConfigError, match="lines"):
        c.plot(lines={"b": -5.0})


@pytest.mark.parametrize("band", [("a", 3000.0), 5.0, (1.0, 2.0, 3.0), (float("nan"), 3000.0)])
def test_a_malformed_band_is_one_line(band):
    """The fused diagnosis's band: text, a scalar, three values or NaN are one-line errors
    (exploratory testing: text and a scalar gave Python's ValueError and TypeError)."""
    from bearingsim.signal.fused import diagnose_fused

    x = np.random.default_rng(23).standard_normal(int(10 * FS))
    with pytest.raises(ConfigError, match="band_hz") as e:
        diagnose_fused(x, FS, "6205-cwru", 1797.0 / 60.0, band=band)
    assert "\n" not in str(e.value)
