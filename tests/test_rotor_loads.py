"""Extra constant loads on the rotor at its bearings (scenario keys ``de_fx_n``, ``de_fy_n``,
``fe_fx_n``, ``fe_fy_n``; ``RotorConfig.bearing_loads``): a coupling, belt or test-rig load
beside the rotor's weight. No published number: the checks are statics and behaviour."""

from __future__ import annotations

import math

import numpy as np
import pytest
from numpy.testing import assert_allclose

from bearingsim import simulate
from bearingsim.config import Scenario
from bearingsim.dynamics.rotor.model import evaluate_rhs, pack_model, static_state
from bearingsim.dynamics.rotor.scenario import rotor_config_from_scenario
from bearingsim.errors import ConfigError

LOADS = {"de_fx_n": 30.0, "de_fy_n": -80.0, "fe_fx_n": 0.0, "fe_fy_n": -40.0}


def _bearing_forces(sc) -> dict[str, np.ndarray]:
    """Force the balls of each bearing put on the shaft at rest, (x, y) [N]."""
    cfg = rotor_config_from_scenario(sc)
    m = pack_model(cfg, sc.fs_hz, ball_forces=True)
    y0 = static_state(m, cfg)
    dydt, aux = evaluate_rhs(m, 0.0, y0)
    assert np.abs(dydt[m.n_pos :]).max() < 1e-3, "accelerations vanish at rest"
    zde, zfe = cfg.de.bearing.n_elements, cfg.fe.bearing.n_elements
    out = {}
    for end, q, z in (
        ("de", aux[4 : 4 + zde], zde),
        ("fe", aux[4 + 2 * zde : 4 + 2 * zde + zfe], zfe),
    ):
        psi = 2 * np.pi * np.arange(z) / z  # ball 1 at 0 (+y) at t = 0
        out[end] = np.array([-np.sum(q * np.sin(psi)), -np.sum(q * np.cos(psi))])
    return out


@pytest.mark.parametrize("ball_inertia", [True, False])
def test_each_bearing_carries_the_load_at_its_node(ball_inertia):
    """Statics of a shaft on two supports: a force at a bearing's node goes to that bearing
    alone, whatever the shaft's flexibility; the balls' force on the shaft changes by minus the
    load (to 1e-8 of it), the other bearing's not at all."""
    base = dict(model="rotor", fs_hz=12000.0, ball_inertia=ball_inertia)
    f0 = _bearing_forces(Scenario(**base))
    f1 = _bearing_forces(Scenario(**base, **LOADS))
    for end in ("de", "fe"):
        load = np.array([LOADS[f"{end}_fx_n"], LOADS[f"{end}_fy_n"]])
        assert_allclose(f1[end] - f0[end], -load, atol=1e-8 * 80.0, err_msg=end)


def test_a_load_pressing_the_shaft_into_the_defect_raises_the_level():
    """An outer-race defect at 6 o'clock under a downward DE load: the balls over it carry more,
    so the DE housing's acceleration grows with the load (quasi-static balls, 0.5 s)."""
    sc = dict(model="rotor", de_fault="outer", duration_s=0.5, fs_hz=12000.0, ball_inertia=False)
    rms = [simulate({**sc, "de_fy_n": fy}).rms("acc_y") for fy in (0.0, -50.0, -200.0)]
    assert rms[0] < rms[1] < rms[2], rms
    assert rms[1] > 1.5 * rms[0], rms


def test_bad_loads_are_refused_in_one_line():
    with pytest.raises(ConfigError, match="de_fy_n = nan"):
        Scenario(model="rotor", de_fy_n=math.nan)
    with pytest.raises(ConfigError, match=r"hypot\(fe_fx_n, fe_fy_n\)"):
        simulate(dict(model="rotor", duration_s=0.01, fs_hz=12000.0, fe_fy_n=-1e6))
    with pytest.raises(ConfigError, match="unknown key 'fy_n'"):
        Scenario.from_dict({"model": "rotor", "fy_n": -50.0})
