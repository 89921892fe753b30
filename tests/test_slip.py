"""Random slip in the ring models (issue 16, item 1): the cage speed fluctuates from one ball
pass to the next, so the ball-pass instants jitter by the given share of their period; seeded,
bit-reproducible; zero slip is the kinematic model (the golden ring case checks it is
unchanged)."""

from __future__ import annotations

import math

import numpy as np
import pytest
from numpy.testing import assert_array_equal

from bearingsim import simulate
from bearingsim.catalog import get_bearing
from bearingsim.dynamics.ring.base import ModelInputs
from bearingsim.errors import ConfigError
from bearingsim.signal.envelope import envelope_spectrum


def _pass_intervals(inputs: ModelInputs, duration: float) -> np.ndarray:
    """Intervals between the instants the kernel's cage angle w t + phi(t) crosses the
    multiples of 2 pi / Z (phi from the compiled slip_phase on a fine grid)."""
    from bearingsim.dynamics.ring import _balance as bl

    table, dt = inputs.slip_table(duration)
    p = np.zeros(bl.HEADER)
    p[bl.P_Z] = inputs.bearing.n_elements
    p[bl.P_WCAGE] = 2 * math.pi * inputs.cage_hz
    p[bl.P_SLIPN] = table.size
    p[bl.P_SLIPDT] = dt
    p = np.concatenate([p, table])
    p[bl.P_SLIP] = bl.HEADER
    t = np.linspace(0.0, duration, 400001)
    theta = p[bl.P_WCAGE] * t + np.array([bl.slip_phase(x, p) for x in t])
    step = 2 * math.pi / inputs.bearing.n_elements
    levels = step * np.arange(1, int(theta[-1] / step))
    return np.diff(np.interp(levels, theta, t))


def test_slip_jitters_the_ball_pass_intervals_by_its_share():
    b = get_bearing("6205")
    for slip in (0.01, 0.02):
        inp = ModelInputs(bearing=b, fx=10.0, fy=50.0, shaft_hz=29.2, slip=slip, slip_seed=3)
        iv = _pass_intervals(inp, 25.0)
        nominal = 1.0 / (b.n_elements * inp.cage_hz)
        assert iv.size > 2000
        assert np.mean(iv) == pytest.approx(nominal, rel=2e-3)  # the FTF on average
        assert np.std(iv) / np.mean(iv) == pytest.approx(slip, rel=0.1)


def test_zero_slip_has_no_table():
    inp = ModelInputs(bearing=get_bearing("6205"), fx=10.0, fy=50.0, shaft_hz=29.2)
    assert inp.slip == 0.0


SC = dict(model="vsm", fault="outer", duration_s=1.0, fs_hz=12000.0)


def test_slip_is_seeded_and_smears_the_high_harmonics():
    a = simulate(SC | {"slip_percent": 1.5, "seed": 2})
    b = simulate(SC | {"slip_percent": 1.5, "seed": 2})
    c = simulate(SC | {"slip_percent": 1.5, "seed": 3})
    k = simulate(SC)
    assert_array_equal(a["acc_y"], b["acc_y"])
    assert not np.array_equal(a["acc_y"], c["acc_y"])
    assert a.meta["slip"]["interval_sd_percent"] == 1.5
    # the same impacts, so the same energy; random intervals smear the envelope's harmonics
    assert np.std(a["acc_y"]) == pytest.approx(np.std(k["acc_y"]), rel=0.05)

    def harmonic(r, h):
        x = r["acc_y"] - r["acc_y"].mean()
        s = envelope_spectrum(x, 12000.0, (2000.0, 5500.0))
        f0 = h * r.meta["kinematics"]["bpfo_hz"]
        return s.amplitude[(s.freq > 0.97 * f0) & (s.freq < 1.03 * f0)].max()

    assert harmonic(a, 8) < 0.7 * harmonic(k, 8)
    assert harmonic(a, 1) == pytest.approx(harmonic(k, 1), rel=0.2)


def test_slip_needs_the_fixed_step_solver():
    with pytest.raises(ConfigError, match="slip_percent = 1 % needs solver = 'rk4'"):
        simulate(SC | {"slip_percent": 1.0, "solver": "dopri5"})


def test_slip_out_of_range_is_refused():
    with pytest.raises(
        ConfigError, match=r"slip_percent = 12 % is out of range; valid range \[0, 10\]"
    ):
        simulate(SC | {"slip_percent": 12.0})


def test_rotor_slip_is_seeded_and_zero_slip_unchanged():
    """The rotor model's cages slip too (each bearing its own process); zero slip is the
    kinematic model (the golden rotor case)."""
    sc = dict(model="rotor", de_fault="outer", duration_s=0.2, fs_hz=12000.0)
    a = simulate(sc | {"slip_percent": 1.5, "seed": 4})
    b = simulate(sc | {"slip_percent": 1.5, "seed": 4})
    k = simulate(sc)
    assert_array_equal(a["acc_y"], b["acc_y"])
    assert not np.array_equal(a["acc_y"], k["acc_y"])
    assert np.std(a["acc_y"]) == pytest.approx(np.std(k["acc_y"]), rel=0.2)
