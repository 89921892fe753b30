"""Rotor unbalance and preload in the ring models (issue 16, realistic signals).

- ``unbalance_n``: a radial force turning with the shaft, added to the constant load; it moves
  the load zone once per shaft turn, so the impacts of a race fault are modulated at the shaft
  frequency.
- a negative ``clearance_m`` (preload: negative operating clearance, Harris & Kotzalas 2007
  ch. 7): every ball is loaded, so an inner-race defect meets a loaded ball at every pass
  instead of only inside the load zone (DEM and TVSM; the VSM's secant needs P_d >= 0).

Zero unbalance and the bearing's own clearance leave every result unchanged (golden ring case).
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.optimize import fsolve

from bearingsim import simulate
from bearingsim.catalog import get_bearing
from bearingsim.contact.hertz import element_stiffness
from bearingsim.dynamics.ring import _balance as bl
from bearingsim.dynamics.ring.base import ModelInputs, static_path
from bearingsim.dynamics.ring.trace import stiffness_trace
from bearingsim.errors import ConfigError
from bearingsim.geometry import characteristic_frequencies
from bearingsim.signal.envelope import envelope_spectrum

B = get_bearing("6205-cwru")
FX, FY = 10.0, 50.0
SHAFT_HZ = 1797.0 / 60.0
KIN = characteristic_frequencies(B, SHAFT_HZ)


def _independent_static(t: float, inp: ModelInputs) -> np.ndarray:
    """Ring displacement [m] balancing sum_j K (u.e_j - P_d/2)_+^1.5 e_j against the load at
    ``t`` (constant plus unbalance), from the ball azimuths alone (SciPy's fsolve)."""
    K = element_stiffness(B)[0]
    clr = 0.5 * inp.diametral_clearance
    psi = 2 * math.pi * (inp.cage_hz * t + np.arange(B.n_elements) / B.n_elements)
    e = np.stack([np.sin(psi), np.cos(psi)])
    ph = 2 * math.pi * inp.shaft_hz * t
    f = np.array([FX + inp.unbalance * math.sin(ph), FY + inp.unbalance * math.cos(ph)])

    def residual(u_um):  # [N] from the displacement in micrometres
        d = np.maximum(1e-6 * u_um @ e - clr, 0.0)
        return (K * d**1.5) @ e.T - f

    return 1e-6 * fsolve(residual, np.array([0.0, 3.0]), xtol=1e-12)


@pytest.mark.parametrize(("unbalance", "clearance"), [(20.0, None), (0.0, -8e-6), (15.0, -4e-6)])
def test_static_balance_matches_an_independent_solve(unbalance, clearance):
    inp = ModelInputs(
        bearing=B, fx=FX, fy=FY, shaft_hz=SHAFT_HZ, unbalance=unbalance, clearance=clearance
    )
    times = np.linspace(0.0, 1.0 / SHAFT_HZ, 9)
    table, res = static_path(inp, times)
    assert res.max() < 1e-9
    for t, row in zip(times, table, strict=True):
        u = _independent_static(float(t), inp)
        assert row[bl.C_UX] == pytest.approx(u[0], rel=1e-6, abs=1e-13)
        assert row[bl.C_UY] == pytest.approx(u[1], rel=1e-6, abs=1e-13)


def test_preload_loads_every_ball():
    r = simulate(
        dict(model="dem", bearing="6205-cwru", duration_s=0.1, fs_hz=12000.0, clearance_m=-5e-6)
    )
    assert r["n_loaded"].min() == B.n_elements
    plain = simulate(dict(model="dem", bearing="6205-cwru", duration_s=0.1, fs_hz=12000.0))
    assert plain["n_loaded"].max() < B.n_elements  # the catalogue's 6 um: a load zone


def _line(s, hz: float) -> float:
    i = int(np.argmin(np.abs(s.freq - hz)))
    return float(s.amplitude[max(i - 2, 0) : i + 3].max())


def _envelope(**kw):
    sc = dict(bearing="6205-cwru", rpm=1797.0, duration_s=2.0, fs_hz=12000.0)
    sc |= dict(defect_width_m=0.007 * 0.0254) | kw
    x = simulate(sc)["acc_y"]
    return envelope_spectrum(x[2400:], 12000.0, (2000.0, 6000.0))


def test_unbalance_modulates_an_outer_race_fault_at_the_shaft_frequency():
    """Zero slip, no noise: a constant load repeats every ball pass (no shaft line); a force
    turning with the shaft (40 % of the load) moves the load zone once a turn: the shaft line
    and the BPFO +/- shaft sidebands appear."""
    rel = {}
    for fu in (0.0, 20.0):
        s = _envelope(model="vsm", fault="outer", unbalance_n=fu)
        lines = [_line(s, f) for f in (SHAFT_HZ, KIN.bpfo_hz - SHAFT_HZ, KIN.bpfo_hz + SHAFT_HZ)]
        rel[fu] = max(lines) / _line(s, KIN.bpfo_hz)
    assert rel[0.0] < 1e-3
    assert rel[20.0] > 0.1


def test_preload_spreads_inner_race_impacts_over_every_pass():
    """With the catalogue's clearance only balls in the load zone strike the inner-race defect,
    once a shaft turn: the envelope's shaft line is as strong as BPFI. Preloaded, every pass
    strikes a loaded ball: BPFI stands well above the shaft line."""
    ratio = {}
    for clr in (6e-6, -10e-6):
        s = _envelope(model="dem", fault="inner", clearance_m=clr)
        ratio[clr] = _line(s, KIN.bpfi_hz) / _line(s, SHAFT_HZ)
    assert ratio[6e-6] < 3.0
    assert ratio[-10e-6] > 10.0 * ratio[6e-6]


def test_bad_unbalance_and_preload_are_refused_in_one_line():
    cases = [
        (dict(model="vsm", unbalance_n=-1.0), "unbalance_n = -1 N is out of range"),
        (dict(model="vsm", unbalance_n=60.0), "unbalance_n = 60 N is out of range"),
        (dict(model="vsm", unbalance_n=math.nan), "unbalance_n"),
        (dict(model="vsm", clearance_m=-2e-6), "clearance_m = -2e-06 m (a preload)"),
        (dict(model="dem", bearing="6205-cwru", clearance_m=-1e-3), "ISO 5753-1"),
    ]
    for sc, msg in cases:
        with pytest.raises(ConfigError, match=re_escape(msg)) as e:
            simulate(sc | {"duration_s": 0.01, "fs_hz": 12000.0})
        assert "\n" not in str(e.value)
        assert "valid" in str(e.value)
    inp = ModelInputs(bearing=B, fx=FX, fy=FY, shaft_hz=SHAFT_HZ, clearance=-2e-6)
    with pytest.raises(ConfigError, match="the VSM stiffness trace"):
        stiffness_trace(inp, n_points=10)


def re_escape(s: str) -> str:
    import re

    return re.escape(s)


def test_unbalance_is_recorded_in_the_result():
    r = simulate(dict(model="dem", duration_s=0.05, fs_hz=12000.0, unbalance_n=5.0))
    assert r.meta["unbalance"]["force_n"] == 5.0


def test_machine_facts_survive_save_and_load(tmp_path):
    from bearingsim.results import SimulationResult

    sc = dict(model="dem", duration_s=0.05, fs_hz=12000.0, clearance_m=-4e-6, unbalance_n=5.0)
    r = simulate(sc | {"ball_diameter_spread_m": 1e-6})
    r.save(tmp_path / "r.nc")
    back = SimulationResult.load(tmp_path / "r.nc")
    assert back.meta["ball_diameters"] == r.meta["ball_diameters"]
    assert back.meta["unbalance"] == r.meta["unbalance"]
    assert back.scenario["clearance_m"] == -4e-6
    np.testing.assert_array_equal(back["acc_y"], r["acc_y"])


def test_rotor_preload_loads_every_ball_of_that_bearing():
    """The rotor model's bearings take a clearance override each (``de_clearance_m``,
    ``fe_clearance_m``): negative = preload, every ball of that bearing loaded at every
    instant; the catalogue's 6 um leaves a load zone."""
    sc = dict(model="rotor", de_fault="inner", duration_s=0.1, fs_hz=12000.0, per_ball=True)
    pre = simulate(sc | {"de_clearance_m": -5e-6})
    assert (pre["ball_load_inner_de"] > 0).sum(axis=1).min() == B.n_elements
    assert pre.scenario["de_clearance_m"] == -5e-6
    plain = simulate(sc)
    assert (plain["ball_load_inner_de"] > 0).sum(axis=1).max() < B.n_elements
    with pytest.raises(ConfigError, match=r"de_clearance_m = -0.001 m is out of range") as e:
        simulate(dict(model="rotor", de_clearance_m=-1e-3, duration_s=0.01))
    assert "ISO 5753-1" in str(e.value) and "\n" not in str(e.value)
