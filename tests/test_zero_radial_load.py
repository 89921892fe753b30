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
        (dict(model="dem"), "0 N only with a preload, clearance_m <= -1e-09 m, or an axial"),
        (dict(model="vsm"), "the ring position is undetermined"),
        (dict(model="vsm", clearance_m=-5e-6), "clearance_m = -5e-06 m (a preload) is out of"),
        (dict(model="dem", unbalance_n=5.0), "the ring position is undetermined"),
        # a vanishing preload holds nothing (exploratory testing: an all-zero signal before)
        (dict(model="dem", clearance_m=-1e-300), "clearance_m <= -1e-09 m"),
    ],
)
def test_an_unheld_ring_without_radial_load_is_still_refused(sc, message):
    with pytest.raises(ConfigError) as e:
        simulate({**BASE, "fault": "none", **sc})
    assert message in str(e.value) and "\n" not in str(e.value)


def test_scenario_validation_refuses_an_unheld_zero_load_and_a_vsm_preload_up_front():
    """A sweep validates every run's scenario before it starts (docs/sweeps.md); the zero-load
    and VSM-preload refusals lived in the model inputs and so failed runs part-way through a
    sweep (exploratory testing, fourteenth session). They are scenario checks now."""
    from bearingsim.config import Scenario

    for d, message in (
        (dict(model="dem", fx_n=0.0, fy_n=0.0), "the ring position is undetermined"),
        (dict(model="vsm", clearance_m=-5e-6), "(a preload) is out of range for model vsm"),
        (dict(model="vsm", axial_load_n=10.0), "axial_load_n = 10 N is out of range for model"),
    ):
        with pytest.raises(ConfigError, match=message.replace("(", r"\(").replace(")", r"\)")):
            Scenario.from_dict(d)


def test_a_held_ring_takes_a_float32_preload_and_its_unbalance_against_the_capacity():
    """np.float32 and text preloads were not seen as holding the ring when an unbalance was
    given (the check ran before the value was converted); an unbalance far above the static
    capacity was accepted on a held ring (1e6 N: ±1.4 mm ring excursions) and is now checked
    with the static load as the peak radial load against 2 C0 (ISO 76)."""
    from bearingsim.config import Scenario

    sc = Scenario.from_dict(
        dict(model="dem", fx_n=0.0, fy_n=0.0, clearance_m=np.float32(-5e-6), unbalance_n=5.0)
    )
    assert sc.unbalance_n == 5.0
    with pytest.raises(ConfigError, match=r"\|\(fx_n, fy_n\)\| \+ unbalance_n = 1e\+06 N exceeds"):
        simulate(dict(model="dem", fault="none", unbalance_n=1e6, clearance_m=-5e-6, **BASE))


def test_negative_zero_loads_give_the_load_direction_of_zero():
    """--fx-n -0.0 --fy-n -0.0 gave theta0 = -180 deg (atan2 of signed zeros)."""
    from bearingsim.catalog import get_bearing
    from bearingsim.load_distribution import radial_load_distribution

    r = radial_load_distribution(get_bearing("6205"), -0.0, -0.0, clearance=-5e-6)
    assert float(np.ravel(r.theta0)[0]) == 0.0
