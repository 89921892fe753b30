"""Angle-domain processing on synthetic signals with known answers."""

from __future__ import annotations

import math

import numpy as np
import pytest
from numpy.testing import assert_allclose

from bearingsim import ConfigError
from bearingsim.dynamics.ias.spall import (
    SpallEstimator,
    analyze_speed_signal,
    estimate_spall_width,
    spall_width_from_angle,
)
from bearingsim.report.published import entry, value
from bearingsim.signal import (
    AngleSignal,
    angle_from_speed,
    order_spectrum,
    resample_to_angle,
    spectrum_peaks,
    speed_from_angle,
    synchronous_average,
)

TWO_PI = 2 * math.pi
#: NU204-ECP kinematics (seed IAS table 1, eq. (36)): cage ratio (1 - 7.94/34)/2, BPFO order 11x
RHO = 0.5 * (1 - 7.94 / 34)
BPFO = 11 * RHO
DO = 41.5e-3


def _time_signal(omega_of_angle, n_revs=12.0, fs=20_000.0):
    """Uniformly timed samples of a shaft whose speed is a known function of its angle:
    ``t(theta) = int dtheta / omega`` on a fine angle grid (trapezoid), then inverted."""
    fine = np.linspace(0.0, n_revs * TWO_PI, int(n_revs * 200_000) + 1)
    inv = 1.0 / omega_of_angle(fine)
    t_of = np.concatenate([[0.0], np.cumsum(0.5 * (inv[1:] + inv[:-1]) * np.diff(fine))])
    t = np.arange(0.0, t_of[-1], 1.0 / fs)
    th = np.interp(t, t_of, fine)
    return t, th, omega_of_angle(th)


def test_speed_and_angle_roundtrip():
    t = np.linspace(0, 2, 2001)
    th = 3.0 * t + 0.5 * t**2
    assert_allclose(
        speed_from_angle(t, th),
        3.0 + t,
        rtol=1e-12,
        atol=1e-12,
        err_msg="d/dt of a quadratic is exact with second-order differences",
    )
    assert_allclose(
        angle_from_speed(t, 3.0 + t),
        th,
        rtol=0,
        atol=1e-12,
        err_msg="trapezoid integral of a linear speed is exact",
    )


def test_order_spectrum_finds_non_integer_order_under_varying_speed():
    # omega(theta) = w0 (1 + a sin(BPFO theta)): the speed varies, the order does not
    a = 0.01
    t, th, w = _time_signal(lambda x: TWO_PI * (1 + a * np.sin(BPFO * x)))
    sig = resample_to_angle(th, w, 512)
    spec = order_spectrum(sig)
    pk = spectrum_peaks(spec, n_peaks=1, f_min=0.5)[0]
    assert_allclose(pk.order, BPFO, atol=2e-3, err_msg="order of the synthetic ripple")
    assert_allclose(pk.amplitude, a * TWO_PI, rtol=0.02, err_msg="Hann amplitude correction")


def test_synchronous_average_recovers_waveform():
    period = TWO_PI / BPFO
    ang = np.arange(0, 40 * TWO_PI, TWO_PI / 2048)
    wave = lambda x: np.sin(TWO_PI * x / period) + 0.3 * np.cos(3 * TWO_PI * x / period)  # noqa: E731
    sig = AngleSignal(ang, wave(ang) + 1.0, 2048)
    ph, avg, k = synchronous_average(sig, period, 512)
    assert k == int((ang[-1] - ang[0]) // period)
    assert_allclose(avg, wave(ph) + 1.0, atol=2e-4, err_msg="periodic signal averages to itself")


def _spall_train(crossing, depth=0.2, w0=TWO_PI, ripple=1e-4):
    """Shaft speed with the event shape of a bridged spall: a step down at entry decaying to 0 at
    mid-crossing, a second step down at the impact decaying to 0 at the exit (seed IAS eq. (30)
    shape), repeated every 2 pi / BPFO; plus a small smooth ball-pass ripple."""
    period = TWO_PI / BPFO

    def omega(x):
        u = np.mod(x, period) - 0.3 * period  # entry at 0.3 period
        h = 0.5 * crossing
        ev = np.where((u >= 0) & (u < h), np.sin(0.5 * np.pi * (h - u) / h), 0.0)
        ev = np.where((u >= h) & (u < crossing), 1 - np.sin(0.5 * np.pi * (u - h) / h), ev)
        return w0 * (1 + ripple * np.cos(BPFO * x)) - depth * ev

    return omega


@pytest.mark.parametrize("crossing", [0.063, 0.126, 0.252])
def test_spall_width_estimate_on_synthetic_events(crossing):
    t, th, w = _time_signal(_spall_train(crossing), n_revs=6.0, fs=40_000.0)
    sig = resample_to_angle(th, w)
    est = estimate_spall_width(sig, DO, RHO, BPFO)
    assert est is not None and est.method is SpallEstimator.STEPS
    assert_allclose(est.crossing_angle, crossing, rtol=0.02, err_msg="entry-to-exit angle")
    assert_allclose(
        est.width, spall_width_from_angle(crossing, DO, RHO), rtol=0.02, err_msg="seed IAS eq. (37)"
    )
    assert_allclose(est.fault_order, BPFO, atol=5e-3)
    ext = estimate_spall_width(sig, DO, RHO, BPFO, method="extent", threshold=0.02)
    # the smooth exit tail ends inside the threshold: EXTENT reads short by (2/pi) acos(0.98)/2
    short = 1 - math.acos(1 - 0.02) / math.pi
    assert_allclose(ext.crossing_angle, crossing * short, rtol=0.03)


def test_seed_eq37_numbers():
    # seed IAS §3.1: 0.12 rad of shaft angle -> 0.96 mm
    assert_allclose(
        spall_width_from_angle(value("ias.fig10.crossing_angle"), DO, RHO),
        entry("ias.eq37.spall_width_estimate").si,
        rtol=0.01,
        err_msg="seed IAS eq. (37) with theta_shaft = 0.12 rad",
    )


def test_no_spall_means_no_estimate():
    t, th, w = _time_signal(lambda x: TWO_PI * (1 + 1e-4 * np.cos(BPFO * x)), n_revs=6.0)
    summ = analyze_speed_signal(
        resample_to_angle(th, w), bpfo_order=BPFO, outer_raceway_diameter=DO, cage_ratio=RHO
    )
    assert summ.estimate is None
    assert summ.as_dict()["spall_width_estimate_m"] is None
    top = max(summ.peaks, key=lambda p: p.amplitude)
    assert_allclose(top.order, BPFO, atol=5e-3)
    assert len(summ.peaks) == 1, summ.peaks
    assert_allclose(summ.mean_speed, TWO_PI, rtol=1e-5)


def test_bad_signals():
    with pytest.raises(ConfigError, match="not strictly increasing"):
        resample_to_angle([0, 1, 0.5, 2, 3], [1, 1, 1, 1, 1])
    with pytest.raises(ConfigError, match="must match"):
        speed_from_angle([0, 1, 2, 3], [0, 1, 2, 3, 4])
    with pytest.raises(ConfigError, match="non-finite"):
        resample_to_angle([0, 1, 2, np.nan], [1, 1, 1, 1])
    with pytest.raises(ConfigError, match="samples"):
        resample_to_angle([0, 1], [1, 1])
