"""``bearingsim ias`` / ``analyze-ias`` and the angle-domain analysis refuse what they cannot do
in one line: a resampling grid beyond the memory budget (a ``--samples-per-rev`` of 16 million,
a speed or time column in the wrong unit), a signal too short to resolve the fault order; and
the nits of the commands (key names, the ``--max-steps`` count, the reported output rate)."""

from __future__ import annotations

import math
import tracemalloc

import numpy as np
import pytest
from numpy.testing import assert_allclose

from bearingsim import get_bearing
from bearingsim.dynamics.ias.model import IasParams, simulate_ias
from bearingsim.dynamics.ias.spall import (
    RESOLUTION_FRACTION,
    ShortSignalError,
    analyze_speed_signal,
    min_revs,
)
from bearingsim.errors import ConfigError
from bearingsim.report.published import value
from bearingsim.signal.order import (
    AngleSignal,
    angle_from_speed,
    angle_grid,
    order_spectrum,
    resample_to_angle,
    synchronous_average,
)

TWO_PI = 2.0 * math.pi
B = get_bearing("NU204-ECP")
#: NU204-ECP kinematics (seed IAS table 1): cage ratio (1 - 7.94/34)/2, BPFO order 11 x that
#: = 4.2156 (seed IAS eq. (36) prints 4.22)
RHO = 0.5 * (1 - 7.94 / 34)
BPFO = 11 * RHO
DO = 41.5e-3


def _speed_csv(path, t_scale=1.0, rpm=1500.0, rows=5000):
    """5 s of a constant shaft speed [r/min], header ``time_s,speed_rpm`` (the reported file)."""
    t = np.linspace(0.0, 5.0, rows) * t_scale
    np.savetxt(path, np.c_[t, np.full(rows, rpm)], delimiter=",", header="time_s,speed_rpm",
               comments="")  # fmt: skip
    return path


# ----------------------------------------------------------------- memory of the resampling
def test_analyze_ias_samples_per_rev_beyond_the_memory_budget(run_cli, tmp_path):
    """--samples-per-rev 16000000 over 125 rev (2e9 samples) tried to allocate 14.9 GiB and
    died with a traceback; now refused in one line naming the largest samples_per_rev that
    fits the budget."""
    f = _speed_csv(tmp_path / "speed.csv")
    r = run_cli("analyze-ias", f, "--samples-per-rev", "16000000", "--max-memory-gb", "1",
                "--json")  # fmt: skip
    line = r.refused("samples_per_rev = 16000000 over 125 shaft revolutions",
                           "memory budget 1 GB", "valid range [8, ")  # fmt: skip
    # the largest value named fits the budget and the next one does not
    top = int(line.rsplit("valid range [8, ", 1)[1].split("]")[0])
    t = np.linspace(0.0, 5.0, 5000)
    th = angle_from_speed(t, np.full(t.size, 1500.0 * TWO_PI / 60.0))
    assert angle_grid(th, top).memory <= 1e9 < angle_grid(th, top + 1).memory
    r = run_cli("analyze-ias", f, "--samples-per-rev", str(top), "--max-memory-gb", "1",
                "--json")  # fmt: skip
    assert r.code == 0, r.err


@pytest.mark.parametrize(
    ("kw", "parts"),
    [
        ({"rpm": 1e12}, ("8.333e+10 shaft revolutions", "even samples_per_rev = 8",
                         "memory budget 4 GB", "check the units")),
        # since the fourteenth session the signal check refuses it first (a peak magnitude
        # beyond 1e100 overflows the signal functions' sums)
        ({"t_scale": 1e300}, ("time_s has a peak magnitude of 5e+300", "valid range [1e-100, "
                              "1e+100] in any unit")),
    ],
    ids=["speed-1e12-rpm", "times-x1e300"],
)  # fmt: skip
def test_analyze_ias_absurd_units_refused(run_cli, tmp_path, kw, parts):
    """A speed of 1e12 r/min or times scaled by 1e300 asked for 15.5 TiB or raised 'Maximum
    allowed size exceeded'; now one line: even the coarsest grid does not fit, or the times
    are out of the signals' range."""
    f = _speed_csv(tmp_path / "s.csv", **kw)
    r = run_cli("analyze-ias", f, "--max-memory-gb", "4", "--json")
    r.refused(*parts)


def test_resample_to_angle_max_memory_and_estimate_bounds_the_use():
    """The estimate refuses before allocating, and is an upper bound of what the resampling and
    the analysis hold (tracemalloc), with and without the anti-aliasing grid."""
    th = np.linspace(0.0, 125 * TWO_PI, 5000)
    with pytest.raises(ConfigError, match=r"samples_per_rev = 16000000 over 125 shaft .* valid "
                       r"range \[8, "):  # fmt: skip
        resample_to_angle(th, np.ones(th.size), 16_000_000, max_memory=1e9)
    for n_in, revs, spr in ((100_000, 100, 4096), (200_000, 20, 1024)):  # L = 1, L = 10
        t = np.linspace(0.0, 1.0, n_in)
        a = revs * TWO_PI * t + 0.01 * np.sin(50 * t)
        w = np.gradient(a, t)
        g = angle_grid(a, spr)
        tracemalloc.start()
        try:
            sig = resample_to_angle(a, w, spr, max_memory=g.memory)
            order_spectrum(sig)
            peak = tracemalloc.get_traced_memory()[1]
        finally:
            tracemalloc.stop()
        assert sig.value.size == g.n_samples
        assert peak <= g.memory, (peak, g.memory, g.oversampling)
        assert g.memory < 4 * peak, "an upper bound, not a wild one"


def test_synchronous_average_in_blocks_is_bounded_and_bit_identical():
    """3000 periods x 4096 samples took 3 x 98 MB at once (tens of GB for a long record); now
    in blocks, with the same bits as the mean over the whole table."""
    period = TWO_PI / BPFO
    ang = np.arange(0.0, 3000.5 * period, period / 64)
    sig = AngleSignal(ang, 6.0 + 0.1 * np.sin(BPFO * ang) + 0.01 * np.cos(7.3 * ang), 0)
    tracemalloc.start()
    try:
        phase, avg, k = synchronous_average(sig, period, 4096)
        peak = tracemalloc.get_traced_memory()[1]
    finally:
        tracemalloc.stop()
    assert k == 3000
    assert peak < 64e6, peak
    grid = sig.angle[0] + (np.arange(k)[:, None] * period + phase[None, :])  # the former table
    ref = np.interp(grid.ravel(), sig.angle, sig.value).reshape(k, 4096).mean(axis=0)
    assert np.array_equal(avg, ref)


# ------------------------------------------------------- the span that resolves the fault order
def test_min_revs_separates_the_fault_order_from_its_harmonics():
    """4 / f_o revolutions: the Hann main lobes (half-width 2/n_revs) of the fault order and of
    its second harmonic meet at their zeros, the spectrum between them falls to nothing; 5 %
    shorter they overlap (the gap filled to > 3 % of the peak), at half of it they merge."""
    assert RESOLUTION_FRACTION == 0.25
    assert_allclose(min_revs(BPFO), 4.0 / BPFO, rtol=1e-15)

    def dip(n_revs):
        ang = np.linspace(0.0, n_revs * TWO_PI, int(n_revs * 4096), endpoint=False)
        spec = order_spectrum(AngleSignal(ang, np.cos(BPFO * ang) + np.cos(2 * BPFO * ang), 4096))
        m = (spec.freq > 1.2 * BPFO) & (spec.freq < 1.8 * BPFO)
        return spec.amplitude[m].min() / spec.amplitude.max()

    assert dip(min_revs(BPFO)) < 1e-3
    assert dip(0.95 * min_revs(BPFO)) > 0.03
    assert dip(0.5 * min_revs(BPFO)) > 0.9


def _synthetic(n_revs):
    ang = np.arange(round(n_revs * 4096)) * (TWO_PI / 4096)
    return AngleSignal(ang, TWO_PI * (1 + 1e-3 * np.cos(BPFO * ang)), 4096)


def test_analysis_refuses_a_span_shorter_than_min_revs():
    kw = {"bpfo_order": BPFO, "outer_raceway_diameter": DO, "cage_ratio": RHO}
    with pytest.raises(ShortSignalError, match=r"n_revs = 0.875 shaft revolutions, an order "
                       r"resolution 1/n_revs = 1.143.*valid range n_revs >= 0.9489"):  # fmt: skip
        analyze_speed_signal(_synthetic(0.875), **kw)
    with pytest.raises(ShortSignalError, match="less than one period 0.2372 rev"):
        analyze_speed_signal(_synthetic(0.125), **kw)
    s = analyze_speed_signal(_synthetic(1.0), **kw)
    top = max(s.peaks, key=lambda p: p.amplitude)
    assert_allclose(top.order, BPFO, atol=0.02, err_msg="the ripple's order, resolved")
    # without a bearing there is no fault order to resolve
    assert analyze_speed_signal(_synthetic(0.5)).bpfo_order is None


def test_ias_run_too_short_to_resolve_the_bpfo_order(run_cli, tmp_path):
    """`ias --duration-s 0.5 --dt-s 1e-5` analysed 0.448 rev and reported the fault order 4.6875
    for the kinematic 4.2156 (seed IAS eq. (36)) and a spall width from it; now refused in one
    line with the duration that would do, nothing written."""
    out = tmp_path / "ix.nc"
    r = run_cli("ias", "--duration-s", "0.5", "--dt-s", "1e-5", "-o", out, "--json")
    line = r.refused(
        "duration_s = 0.5 s with skip_s = 0.049998 s leaves too little rotation",
        "n_revs = 0.4482 shaft revolutions",
        "valid: a longer duration_s or a smaller skip_s for n_revs >= 0.9489",
        "about duration_s >= 1.06 s",
    )
    assert not out.exists() and not list(tmp_path.iterdir())
    # the duration it names is long enough, and measures the fault order of seed IAS eq. (36)
    dur = line.split("about duration_s >= ")[1].split(" s")[0]
    r = run_cli("ias", "--duration-s", dur, "--dt-s", "1e-5", "-o", out, "--json")
    assert r.code == 0, r.err
    assert r.json()["n_revs_analysed"] >= min_revs(BPFO)
    assert_allclose(r.json()["fault_order_measured"], value("ias.eq36.bpfo_order"), atol=0.02,
                    err_msg="seed IAS eq. (36)")  # fmt: skip


def test_flat_speed_has_no_spall_event():
    """A constant speed (every rate exactly 0) read as an infinite step contrast: a spall was
    'detected'."""
    s = analyze_speed_signal(
        AngleSignal(np.arange(0.0, 20 * TWO_PI, TWO_PI / 1024), np.full(20 * 1024, 157.0), 1024),
        bpfo_order=BPFO,
        outer_raceway_diameter=DO,
        cage_ratio=RHO,
    )
    assert s.estimate is None and s.as_dict()["spall_width_estimate_m"] is None


# -------------------------------------------------------------------------------- the nits
def test_zero_torque_names_the_scenario_key(run_cli, tmp_path):
    r = run_cli("ias", "--torque-n-m", "0", "--duration-s", "0.2", "-o", tmp_path / "r.nc")
    r.refused("torque_n_m = 0 N m with zero initial speed",
                    "valid range torque_n_m > 0")  # fmt: skip
    assert "torque_nm" not in r.err


def test_max_steps_is_an_integer_count(run_cli, tmp_path):
    out = tmp_path / "r.nc"
    r = run_cli("ias", "--max-steps", "1.5", "-o", out)
    r.refused("'1.5' is not an integer", "valid range [1, inf)")
    r = run_cli("ias", "--duration-s", "0.05", "--max-steps", "1e3", "-o", out)
    r.refused("exceed the step budget 1e+03")
    r = run_cli("ias", "--help")
    assert r.code == 0
    assert "--max-steps INTEGER" in r.out and "[default: (1e9)]" in r.out
    assert "((" not in r.out


def test_output_rate_is_the_requested_rate():
    """1/(decim dt) with dt = 1/(rate decim) read 49999.99999999999 for 50 kHz; the output
    interval is exactly 1/rate, so the rate is reported. n_steps is (n_out - 1) decim: the
    last sample at n_steps dt (the CLI's runs have n_samples = duration fs samples, the last at
    (n_samples - 1)/fs)."""
    r = simulate_ias(IasParams(B), 0.01, 1e-5, 50_000.0)
    assert r.solver["output_rate_hz"] == 50_000.0 and r.fs_hz == 50_000.0
    assert r.solver["n_steps"] == (r.t.size - 1) * r.solver["decim"] == 1000
    r = simulate_ias(IasParams(B), 0.01, 1e-5, 48_000.0)  # not met: 2 steps of 1e-5 s
    assert_allclose(r.solver["output_rate_hz"], 50_000.0, rtol=1e-12)
