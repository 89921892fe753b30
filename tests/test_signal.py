"""Signal processing: amplitude and envelope spectra, fast kurtogram, order tracking, angular
resampling, peak refinement and matching — analytic cases with known answers."""

from __future__ import annotations

import math

import numpy as np
import pytest
from numpy.testing import assert_allclose

from bearingsim.errors import ConfigError
from bearingsim.signal import (
    AngleSignal,
    Domain,
    EnvelopeKind,
    Interpolation,
    Spectrum,
    amplitude_spectrum,
    angle_from_speed,
    check_band,
    envelope,
    envelope_spectrum,
    fast_kurtogram,
    kurtogram_levels,
    match_peaks,
    order_spectrum,
    refine_peak,
    resample_to_angle,
    spectrum_peaks,
    strongest_peak,
)

FS = 48000.0
TWO_PI = 2 * math.pi


def test_amplitude_spectrum_reads_sinusoid_amplitude():
    t = np.arange(48000) / FS
    x = 0.7 + 2.5 * np.sin(2 * np.pi * 1000.0 * t) + 0.3 * np.cos(2 * np.pi * 2500.0 * t)
    s = amplitude_spectrum(x, FS)
    assert_allclose(s.resolution, 1.0)
    assert_allclose(s.amplitude[1000], 2.5, rtol=1e-9, err_msg="Hann coherent-gain correction")
    assert_allclose(s.amplitude[2500], 0.3, rtol=1e-9)
    assert s.amplitude[0] < 1e-9, "mean removed"


def test_envelope_of_am_signal():
    """x = A (1 + m cos 2 pi f_m t) cos 2 pi f_c t: envelope A(1 + m cos), line m A at f_m."""
    t = np.arange(96000) / FS
    A, m, fm, fc = 2.0, 0.4, 107.0, 6000.0
    x = A * (1 + m * np.cos(2 * np.pi * fm * t)) * np.cos(2 * np.pi * fc * t)
    e = envelope(x, FS, (4000.0, 8000.0))
    core = slice(2000, -2000)  # away from the tapered ends
    assert_allclose(e[core], A * (1 + m * np.cos(2 * np.pi * fm * t[core])), rtol=1e-6)
    es = envelope_spectrum(x, FS, (4000.0, 8000.0))
    k = int(np.argmax(es.amplitude[1:2000])) + 1
    assert_allclose(es.freq[k], fm, atol=es.resolution)
    assert_allclose(es.amplitude[k], m * A, rtol=0.03, err_msg="modulation line m*A")
    sq = envelope_spectrum(x, FS, (4000.0, 8000.0), kind=EnvelopeKind.SQUARED)
    assert_allclose(sq.amplitude[k], 2 * m * A * A, rtol=0.03, err_msg="squared envelope 2 m A^2")


def test_kurtogram_levels_follow_antoni_tree():
    """Antoni (2007) 1/3-binary tree: levels 0, 1, 1.6, 2, 2.6, 3 with 1, 2, 3, 4, 6, 8 bands."""
    lv = kurtogram_levels(3)
    assert_allclose([v for v, _ in lv], [0, 1, math.log2(3), 2, 1 + math.log2(3), 3])
    assert [nb for _, nb in lv] == [1, 2, 3, 4, 6, 8]


def test_kurtogram_finds_resonance_band_of_impulses():
    """Decaying 9 kHz bursts every 1/107 s buried in noise: the selected band contains 9 kHz
    and its kurtosis is far above the Gaussian value 0."""
    rng = np.random.default_rng(0)
    n = 48000
    t = np.arange(n) / FS
    x = rng.normal(0.0, 1.0, n)
    h = np.exp(-2000.0 * t[:480]) * np.sin(2 * np.pi * 9000.0 * t[:480])
    for t0 in np.arange(0.0, 1.0 - 0.011, 1 / 107.0):
        i = int(t0 * FS)
        x[i : i + 480] += 6.0 * h
    kg = fast_kurtogram(x, FS, min_bandwidth_hz=1000.0)
    assert kg.band[0] <= 9000.0 <= kg.band[1]
    assert kg.max_kurtosis > 3.0
    # Gaussian noise alone: complex-envelope kurtosis ~ 0 (estimator spread ~ sqrt(4/N))
    kn = fast_kurtogram(rng.normal(size=n), FS, max_level=3)
    assert np.nanmax(np.abs(kn.kurtosis)) < 0.2


def test_order_tracking_sharpens_a_swept_order():
    """A 6th-order component during a speed ramp 20 -> 30 Hz: spread over 120-180 Hz in the
    frequency spectrum, one line at order 6 after angular resampling."""
    n = 96000
    t = np.arange(n) / FS
    speed = 20.0 + 5.0 * t  # Hz
    angle = 20.0 * t + 2.5 * t * t  # rev
    x = np.sin(2 * np.pi * 6.0 * angle)
    sig = resample_to_angle(
        angle_from_speed(t, TWO_PI * speed), x, 128, interpolation=Interpolation.CUBIC
    )
    assert_allclose((sig.angle[-1] - sig.angle[0]) / TWO_PI, angle[-1], rtol=1e-3)
    osp = order_spectrum(sig, pad_factor=None)
    k = int(np.argmax(osp.amplitude))
    assert_allclose(osp.freq[k], 6.0, atol=osp.resolution)
    assert osp.amplitude[k] > 0.9, "full amplitude in one order line"
    fsp = amplitude_spectrum(x, FS)
    assert fsp.amplitude.max() < 0.35, "smeared in the frequency domain"
    # the angle route gives the same signal
    sig2 = resample_to_angle(TWO_PI * angle, x, 128, interpolation=Interpolation.CUBIC)
    m = min(sig.value.size, sig2.value.size)
    assert_allclose(sig2.value[100 : m - 100], sig.value[100 : m - 100], atol=1e-3)


def test_match_peaks_tolerance_and_snr():
    f = np.arange(0, 1000.0, 0.5)
    a = np.full(f.size, 0.01)
    a[f == 108.0] = 1.0  # 0.65 % above the 107.3 Hz target
    a[f == 215.0] = 0.02  # weak line: 6 dB
    sp = Spectrum(f, a)
    pk = match_peaks(sp, [("BPFO", 107.3), ("2xBPFO", 214.6), ("far", 150.0)], 29.93, tol_rel=0.01)
    d = {p.label: p for p in pk}
    assert d["BPFO"].freq_hz == 108.0 and d["BPFO"].detected
    assert_allclose(d["BPFO"].snr_db, 40.0, atol=1e-9, err_msg="20 log10(1/0.01)")
    assert_allclose(d["BPFO"].order, 108.0 / 29.93)
    assert not d["2xBPFO"].detected and d["2xBPFO"].snr_db == pytest.approx(6.0206, abs=1e-3)
    pk2 = match_peaks(sp, [("BPFO", 107.3)], 29.93, tol_rel=0.001, tol_min_bins=0.5)
    assert pk2[0].freq_hz != 108.0, "outside a 0.1 % tolerance"


def test_match_peaks_leaves_out_targets_whose_window_reaches_zero_frequency():
    """A 0.15 s record's envelope spectrum (6.7 Hz lines): FTF (11.6 Hz) searched within two
    lines would reach the zero-frequency line's leakage and be "found" at the first line; it is
    left out, while f_r (29 Hz, window from 15.8 Hz) is searched."""
    df = 1.0 / 0.15
    f = np.arange(0.0, 600.0, df)
    a = np.full(f.size, 0.01)
    a[1] = 1.0  # leakage of the zero-frequency line
    sp = Spectrum(f, a)
    pk = match_peaks(sp, [("FTF", 11.6), ("2xFTF", 23.2), ("fr", 29.2)], 29.2, tol_rel=0.01)
    assert [p.label for p in pk] == ["fr"]
    assert not pk[0].detected, "the window of f_r does not reach the first line"
    # the same targets in a 10 s record's spectrum (0.1 Hz lines) are all searched
    f10 = np.arange(0.0, 600.0, 0.1)
    pk10 = match_peaks(Spectrum(f10, np.full(f10.size, 0.01)), [("FTF", 11.6)], 29.2)
    assert [p.label for p in pk10] == ["FTF"]


@pytest.mark.parametrize(
    ("band", "match"),
    [
        ((1000.0, 30000.0), "fs too low for the requested band"),
        ((5000.0, 4000.0), "is empty"),
        ((-5.0, 100.0), "band_hz low = -5"),
        # the range a high edge can have, not "(-inf, inf)"
        ((1000.0, math.inf), r"band_hz high = inf is not finite; valid range \(1000, "),
    ],
)
def test_band_validation(band, match):
    with pytest.raises(ConfigError, match=match):
        check_band(band, FS)


# ---------------------------------------------------------------- one convention per primitive


def test_order_spectrum_reads_sinusoid_amplitude_with_and_without_padding():
    """The one amplitude convention in the order domain: sinusoids of amplitude A at integer
    orders read A (on a line), zero padding keeps the amplitudes and the resolution 1/n_revs."""
    spr, revs = 64, 128  # long enough for the symmetric window's leakage to stay < 1e-9
    ang = np.arange(spr * revs) * TWO_PI / spr
    sig = AngleSignal(ang, 3.0 + 0.8 * np.sin(5 * ang) + 0.05 * np.cos(11 * ang), spr)
    for pad, lines_per_order in ((None, revs), (16, 16 * revs)):
        s = order_spectrum(sig, pad_factor=pad)
        assert s.domain is Domain.ORDER
        assert_allclose(s.resolution, 1.0 / revs, rtol=1e-12, err_msg="1 / n_revs")
        assert_allclose(s.bin_width, 1.0 / lines_per_order, rtol=1e-12)
        assert_allclose(s.amplitude[5 * lines_per_order], 0.8, rtol=1e-9, err_msg=f"pad {pad}")
        assert_allclose(s.amplitude[11 * lines_per_order], 0.05, rtol=1e-9, err_msg=f"pad {pad}")
        assert s.amplitude[0] < 1e-9, "mean removed"
    per = amplitude_spectrum(sig.value, spr, domain=Domain.ORDER, sym=False)
    assert_allclose(per.amplitude[5 * revs], 0.8, rtol=1e-9, err_msg="periodic Hann, same scaling")


def test_spectrum_domain_is_an_enum():
    f = np.arange(32.0)
    assert Spectrum(f, f, domain="order").domain is Domain.ORDER
    assert Spectrum(f, f).domain is Domain.HZ
    with pytest.raises(ConfigError, match=r"domain = 'rev' is invalid; valid: Hz, order"):
        Spectrum(f, f, domain="rev")
    with pytest.raises(ConfigError, match=r"n_fft = 10 is invalid; valid range \[32, inf\)"):
        amplitude_spectrum(np.ones(32), 1.0, n_fft=10)


def _tone_revs(order, density=1000, revs=64):
    ang = np.arange(density * revs) * TWO_PI / density
    return ang, np.sin(order * ang)


def test_resample_to_angle_attenuates_above_the_new_nyquist():
    """1000 samples/rev resampled to 256/rev: order 375 (above the output's Nyquist order 128)
    would alias to order 119 with plain interpolation; anti-aliased it is > 60 dB down, while
    order 20 keeps its amplitude."""
    ang, x = _tone_revs(375)
    ang, x20 = _tone_revs(20)
    sig = resample_to_angle(ang, x + x20, 256)
    s = order_spectrum(sig, pad_factor=None)
    at = lambda o: s.amplitude[int(np.argmin(np.abs(s.freq - o)))]  # noqa: E731
    assert at(119) < 1e-3, "alias of order 375"
    assert_allclose(at(20), 1.0, atol=2e-3, err_msg="pass band (linear interpolation)")
    naive = amplitude_spectrum(np.interp(sig.angle, ang, x + x20), 256, domain=Domain.ORDER)
    assert naive.amplitude[int(np.argmin(np.abs(naive.freq - 119)))] > 0.5, "aliases without"
    cub = resample_to_angle(ang, x20, 256, interpolation=Interpolation.CUBIC)
    core = slice(50, -50)  # the FIR's end transients
    assert_allclose(cub.value[core], np.sin(20 * cub.angle[core]), atol=1e-3)


def test_resample_to_angle_does_not_filter_when_the_output_is_as_dense():
    """An encoder with as many lines per revolution as output samples: plain interpolation."""
    ang = np.arange(1024 * 8 + 1) * TWO_PI / 1024
    v = np.sin(3 * ang) + 0.1 * np.sign(np.sin(50 * ang))
    sig = resample_to_angle(ang, v)
    assert sig.samples_per_rev == 1024, "default: power of two at least the mean density"
    assert_allclose(sig.value, np.interp(sig.angle, ang, v), rtol=0, atol=0)
    ang2 = np.sort(np.random.default_rng(1).uniform(0, 4 * TWO_PI, 20_000))
    assert resample_to_angle(ang2, np.ones_like(ang2)).samples_per_rev == 8192
    with pytest.raises(ConfigError, match="interpolation = 'spline' is invalid; valid: linear"):
        resample_to_angle(ang, v, interpolation="spline")


def test_refine_peak_vertex_of_parabola_and_gaussian():
    x = np.arange(-3.0, 4.0)
    y = 3.0 - 2.0 * (x - 0.3) ** 2
    d, h = refine_peak(y, 3)
    assert_allclose([d, h], [0.3, 3.0], rtol=1e-12, err_msg="exact on a parabola")
    g = 2.0 * np.exp(-((x + 0.2) ** 2) / 1.5)
    assert_allclose(refine_peak(g, 3, log=True), [-0.2, 2.0], rtol=1e-12, err_msg="log: Gaussian")
    assert refine_peak(y, 0) == (0.0, y[0]), "no neighbour: no refinement"
    assert refine_peak(np.array([0.0, 1.0, 0.5]), 1, log=True) == (0.0, 1.0), "log of 0"


def test_spectrum_peaks_and_strongest_peak():
    spr, revs = 64, 16
    ang = np.arange(spr * revs) * TWO_PI / spr
    sig = AngleSignal(ang, 0.5 * np.sin(4.25 * ang) + 0.2 * np.sin(9.5 * ang), spr)
    s = order_spectrum(sig)
    pk = spectrum_peaks(s, 3, f_min=0.5)
    assert len(pk) == 2, pk
    assert_allclose([p.order for p in pk], [4.25, 9.5], atol=2e-3)
    assert_allclose([p.amplitude for p in pk], [0.5, 0.2], rtol=2e-3)
    sp = strongest_peak(s, 9.0)
    assert_allclose(sp.freq, 9.5, atol=2e-3)
    with pytest.raises(ConfigError, match="expected_order = 100 is beyond the spectrum"):
        strongest_peak(s, 100.0)


@pytest.mark.parametrize("n", [0, 1, 2, 3, 7, 100, 1001, 121846])
@pytest.mark.parametrize("alpha", [0.0, 0.01, 0.02, 0.3, 0.999, 1.0, 1.5])
def test_tukey_window_is_scipys(n, alpha):
    """The envelope's edge taper is ``scipy.signal.windows.tukey``'s definition (Harris 1978,
    eq. (38)), written out so that an analysis does not import scipy.signal (issue 17: the
    start-up of one call): equal bit for bit, including the Hann window at alpha >= 1."""
    from scipy.signal.windows import tukey

    from bearingsim.signal.envelope import tukey_window

    w = tukey_window(n, alpha)
    ref = tukey(n, alpha)
    assert w.shape == ref.shape
    assert np.array_equal(w, ref)


def test_one_supply_frequency_is_reported():
    """A machine has one supply: envelope lines at 50 and 100 Hz (strong) and a weak chance
    line at 60 Hz are reported as the 50 Hz supply alone (both were listed before)."""
    from bearingsim.catalog import get_bearing
    from bearingsim.signal.fused import diagnose_fused

    fs = 12000.0
    t = np.arange(int(4 * fs)) / fs
    carrier = np.random.default_rng(0).standard_normal(t.size)
    mod = 1 + 0.8 * np.sin(2 * np.pi * 50 * t) + 0.3 * np.sin(2 * np.pi * 100 * t)
    mod += 0.08 * np.sin(2 * np.pi * 60 * t) + 0.05 * np.sin(2 * np.pi * 120 * t)
    d = diagnose_fused(carrier * mod, fs, get_bearing("6205-cwru"), 29.1)
    labels = [s["label"] for s in d.non_bearing["supply_lines"]]
    assert labels == ["1x50Hz", "2x50Hz"], labels


def test_a_simulation_has_a_supply_only_where_its_rig_adds_one(tmp_path):
    """A simulated result has no electrical supply: read through its rig's sensor it gets no
    supply frequencies to search (`supply_hz` empty), so `analyze` notes none (the
    rotor's inner-race fault through cwru-de-12k was told of "2x50Hz (electrical)" lines). A
    rig that adds a fixed 100 Hz tone gives the 50 Hz supply; a measured record keeps the
    default 50 and 60 Hz, and the search notes a 50 Hz line only where it is searched."""
    from bearingsim import simulate
    from bearingsim.catalog import get_bearing
    from bearingsim.io.signal import read_signal
    from bearingsim.rig import Rig, Tone
    from bearingsim.rig_identify import rig_to_toml
    from bearingsim.signal.diagnosis import _supply
    from bearingsim.signal.fused import diagnose_fused

    fs = 12000.0
    sc = dict(model="vsm", fault="none", duration_s=1.0, fs_hz=fs, seed=0, rpm=1746.0)
    plain = Rig(name="plain", description="", provenance="test")
    mains = Rig(name="mains", description="", provenance="test",
                tones=(Tone(2.0, "test", frequency_hz=100.0),))  # fmt: skip
    infos = {}
    for rig in (plain, mains):
        p = tmp_path / f"{rig.name}.nc"
        (tmp_path / f"{rig.name}.toml").write_text(rig_to_toml(rig), encoding="utf-8")
        simulate({**sc, "rig": str(tmp_path / f"{rig.name}.toml")}).save(p)
        infos[rig.name] = _supply(read_signal(p))["supply_hz"]
    assert infos == {"plain": (), "mains": (50.0,)}
    assert _supply(read_signal(tmp_path / "plain.nc", channel="y"))["supply_hz"] == ()
    # the search itself: a 50 Hz line in the envelope is noted only where a supply is searched
    t = np.arange(int(4 * fs)) / fs
    x = np.random.default_rng(0).standard_normal(t.size) * (1 + 0.8 * np.sin(2 * np.pi * 50 * t))
    b = get_bearing("6205-cwru")
    assert diagnose_fused(x, fs, b, 29.1).non_bearing["supply_lines"] != []
    assert diagnose_fused(x, fs, b, 29.1, supply_hz=()).non_bearing["supply_lines"] == []
