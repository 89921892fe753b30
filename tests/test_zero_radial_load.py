"""A ring model with no radial load (the DEM and TVSM): a preload (negative operating
clearance) or an axial load holds the ring, so the position is determined and the run is valid
(a spring-preloaded motor bearing with little radial load). Until the fourteenth session every
ring model refused zero radial load ("the ring position is undetermined"), even with a preload
("noticed and left alone" in the thirteenth session's note). Without a preload or axial load
the refusal stays, and the VSM, whose secant stiffness needs P_d >= 0 and no axial load,
refuses as before."""

from __future__ import annotations

import numpy as np
import pytest

from bearingsim import simulate
from bearingsim.errors import ConfigError

BASE = dict(fx_n=0.0, fy_n=0.0, duration_s=0.25, fs_hz=12000.0, seed=0)
HOLD = [{"clearance_m": -5e-6}, {"axial_load_n": 100.0}]


@pytest.mark.parametrize("model", ["dem", "tvsm"])
@pytest.mark.parametrize("hold", HOLD, ids=["preload", "axial"])
def test_held_ring_without_radial_load_is_centred_and_quiet(model, hold):
    """Healthy: every ball carries the same load, the forces cancel at every cage angle, the
    ring stays concentric (displacement below 1e-12 m; the preload's ball deflection is
    microns) and the bearing is silent (RMS below 1e-9 m/s^2)."""
    r = simulate(dict(model=model, fault="none", **BASE, **hold))
    for c in ("disp_x", "disp_y"):
        assert np.all(np.isfinite(r[c])) and np.max(np.abs(r[c])) < 1e-12
    assert np.std(r["acc_y"]) < 1e-9


@pytest.mark.parametrize("hold", HOLD, ids=["preload", "axial"])
def test_held_ring_without_radial_load_strikes_an_outer_defect_at_bpfo(hold):
    """An outer-race defect is struck by every ball (all are loaded): the squared envelope of
    the ring's acceleration has its strongest line in 20-600 Hz at BPFO (at the operating
    contact angle with an axial load: the result's own kinematics), within one bin."""
    r = simulate(dict(model="dem", fault="outer", **BASE, **hold))
    a = np.asarray(r["acc_y"])
    assert np.std(a) > 1.0  # [m/s^2]: impacts
    env = np.abs(np.fft.rfft((a - a.mean()) ** 2 - np.mean((a - a.mean()) ** 2)))
    f = np.fft.rfftfreq(a.size, 1.0 / 12000.0)
    band = (f > 20.0) & (f < 600.0)
    peak = f[band][np.argmax(env[band])]
    bpfo = r.meta["kinematics"]["bpfo_hz"]
    assert abs(peak - bpfo) <= 12000.0 / a.size, (peak, bpfo)  # one bin


def test_an_unbalance_is_valid_on_a_held_ring_without_radial_load():
    r = simulate(dict(model="dem", fault="none", unbalance_n=20.0, **BASE, clearance_m=-5e-6))
    assert 1e-3 < np.std(r["acc_x"]) < 1.0  # once per turn [m/s^2]


@pytest.mark.parametrize(
    "sc, message",
    [
        (dict(model="dem"), "0 N only with a preload, clearance_m < 0, or an axial load"),
        (dict(model="vsm"), "the ring position is undetermined"),
        (dict(model="vsm", clearance_m=-5e-6), "clearance_m = -5e-06 m (a preload) is out of"),
        (dict(model="dem", unbalance_n=5.0), "unbalance_n = 5.0 N needs a radial load"),
    ],
)
def test_an_unheld_ring_without_radial_load_is_still_refused(sc, message):
    with pytest.raises(ConfigError) as e:
        simulate({**BASE, "fault": "none", **sc})
    assert message in str(e.value) and "\n" not in str(e.value)
