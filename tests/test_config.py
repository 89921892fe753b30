"""Scenario schemas, one per model family (issue 13): dispatch on ``model``, keys of other
families refused by name, renamed keys, and ``bearingsim.simulate`` over every family."""

from __future__ import annotations

import dataclasses
import math

import numpy as np
import pytest
from numpy.testing import assert_allclose

import bearingsim
from bearingsim.config import (
    IasScenario,
    Model,
    RingScenario,
    RotorScenario,
    Scenario,
    Solver,
    family,
)
from bearingsim.errors import ConfigError, DeprecatedKeyWarning


@pytest.mark.parametrize(
    ("keys", "cls"),
    [
        ({}, RingScenario),
        ({"model": "dem"}, RingScenario),
        ({"model": Model.TVSM}, RingScenario),
        ({"model": "rotor", "disks": 3}, RotorScenario),
        ({"model": "ias", "spall_width_m": 0.0}, IasScenario),
    ],
)
def test_scenario_dispatches_on_model(keys, cls):
    """``Scenario(**keys)`` and ``Scenario.from_dict(keys)`` return the family's class."""
    a, b = Scenario(**keys), Scenario.from_dict(keys)
    assert type(a) is cls and type(b) is cls and a == b
    assert a.to_dict() == b.to_dict() and list(a.to_dict()) == list(cls.KEYS)
    assert Scenario.from_dict(a.to_dict()) == a, "to_dict round-trips"
    assert family(a.model) is cls


def test_every_key_belongs_to_a_family():
    keys = Scenario.keys()
    assert keys[:2] == ("model", "bearing") and len(keys) == len(set(keys))
    for fam in (RingScenario, RotorScenario, IasScenario):
        assert set(fam.KEYS) <= set(keys)
        assert {f.name for f in dataclasses.fields(fam)} == set(fam.KEYS), fam.__name__


@pytest.mark.parametrize(
    ("keys", "match"),
    [
        ({"model": "vsm", "disks": 3}, r"unknown key 'disks' \(a key of model rotor\)"),
        ({"model": "rotor", "fault": "outer"}, r"unknown key 'fault' \(a key of model vsm/dem"),
        ({"model": "ias", "per_ball": True}, r"unknown key 'per_ball' \(a key of model vsm"),
        ({"model": "vsm", "rpn": 1.0}, r"unknown key 'rpn'; valid keys: model, bearing"),
        ({"model": "lstm"}, r"model = 'lstm' is invalid; valid: vsm, dem, tvsm, rotor, ias"),
        ({"solver": "euler"}, r"solver = 'euler' is invalid; valid: rk4, dopri5"),
        ({"model": "ias", "rpm": 60.0, "torque_n_m": 9.0}, r"give at most one"),
        ({"model": "ias", "contact_law": "x"}, r"contact_law = 'x' is invalid; valid: seed"),
        ({"model": "rotor", "disks": 0}, r"disks = 0 is invalid; valid range \[1, inf\)"),
    ],
)
def test_bad_scenarios_give_one_line(keys, match):
    with pytest.raises(ConfigError, match=match) as ei:
        Scenario.from_dict(keys)
    assert "\n" not in str(ei.value)


def test_family_class_refuses_a_model_of_another_family():
    with pytest.raises(ConfigError, match="model = 'rotor' is not a model of RingScenario"):
        RingScenario(model="rotor")


@pytest.mark.parametrize(
    ("cls", "old", "new", "value"),
    [
        (RingScenario, "defect_angle_deg", "defect_edge_angle_deg", 12.0),
        (RingScenario, "noise_rms_m_s2", "noise_rms_m_per_s2", 0.5),
        (RingScenario, "damping_n_s_m", "damping_n_s_per_m", 200.0),
        (RingScenario, "stiffness_n_m15", "stiffness_n_per_m1_5", 5e9),
        (RotorScenario, "housing_stiffness_n_m", "housing_stiffness_n_per_m", 2e7),
        (RotorScenario, "housing_damping_n_s_m", "housing_damping_n_s_per_m", 1e3),
        (RotorScenario, "contact_damping_n_s_m", "contact_damping_n_s_per_m", 20.0),
        (IasScenario, "radial_damping_n_s_m", "radial_damping_n_s_per_m", 300.0),
        (IasScenario, "torsional_damping_n_m_s_rad", "torsional_damping_n_m_s_per_rad", 1.0),
        (IasScenario, "torque_nm", "torque_n_m", 9.0),
        (IasScenario, "output_rate_hz", "fs_hz", 20000.0),
        (IasScenario, "method", "solver", "dopri5"),
    ],
)
def test_renamed_keys_warn_and_work(cls, old, new, value):
    with pytest.warns(DeprecatedKeyWarning, match=f"'{old}' is deprecated; use '{new}'"):
        sc = cls.from_dict({old: value})
    with pytest.raises(ConfigError, match=f"keys '{old}' and '{new}' given"):
        cls.from_dict({old: value, new: value})
    expect = Solver(value) if new == "solver" else value
    assert getattr(sc, new) == expect


@pytest.mark.parametrize("old", ["spall_angle_rad", "first_roller_angle_rad"])
def test_keys_whose_meaning_changed_name_their_replacement(old):
    new = old.replace("_rad", "_deg")
    with pytest.raises(ConfigError, match=f"key '{old}' was replaced: {new}"):
        IasScenario.from_dict({old: 1.0})


def test_ias_angles_map_to_the_seed_frame():
    """Project azimuths (from +y towards +x) map to the seed IAS frame (from +x
    counter-clockwise): psi = pi/2 - phi. The defaults are the seed's phi_os = 1.5 pi and
    Phi_0 = 0."""
    from bearingsim.dynamics.ias.scenario import ias_params

    p = ias_params(IasScenario())
    assert_allclose(p.spall_phi, 1.5 * math.pi, rtol=1e-15)
    assert p.first_roller_angle == 0.0
    top = ias_params(IasScenario(spall_angle_deg=0.0))
    assert_allclose(top.spall_phi, 0.5 * math.pi, rtol=1e-15)
    assert ias_params(IasScenario(spall_width_m=0.0)).spall is None


def test_ias_output_grid_keeps_the_seed_step():
    """A whole number of RK4 steps per output sample; the seed's 1e-6 s is kept at 50 kHz."""
    from bearingsim.dynamics.ias.scenario import output_grid

    assert output_grid(IasScenario()) == (20, 1e-6)
    decim, dt = output_grid(IasScenario(fs_hz=48000.0))
    assert decim == 21 and dt * decim * 48000.0 == pytest.approx(1.0, rel=1e-15)


def test_simulate_runs_every_family():
    """One entry point: the ring, rotor and IAS models all run through ``bearingsim.simulate``;
    the IAS run equals ``simulate_ias`` on the same inputs (bit for bit)."""
    from bearingsim.dynamics.ias.model import simulate_ias
    from bearingsim.dynamics.ias.scenario import ias_params

    ring = bearingsim.simulate({"model": "vsm", "duration_s": 0.005, "fs_hz": 12000.0})
    rotor = bearingsim.simulate({"model": "rotor", "duration_s": 0.005, "fs_hz": 12000.0})
    assert ring["acc_y"].size == rotor["acc_y"].size == 60
    sc = IasScenario(duration_s=0.05, dt_s=1e-5, fs_hz=10000.0)
    ias = bearingsim.simulate(sc)
    ref = simulate_ias(ias_params(sc), 0.0499, 1e-5, 10000.0, "rk4")  # 500 samples from t = 0
    np.testing.assert_array_equal(ias.omega, ref.omega)
    assert ias.time.size == sc.n_samples == 500 and ias.fs_hz == 10000.0
    assert ias.scenario == sc.to_dict() and np.array_equal(ias["omega"], ias.omega)


def test_sweep_refuses_a_model_axis_across_families():
    from bearingsim.sweep import SweepSpec

    with pytest.raises(ConfigError, match="axis model = 'rotor' is a rotor model but the base"):
        SweepSpec.from_dict({"base": {"model": "vsm"}, "axes": {"model": ["vsm", "rotor"]}})


def test_cli_simulate_runs_the_ias_model(run_cli, tmp_path):
    """``bearingsim simulate --model ias`` works like the other models: the family's keys come
    from the scenario file or ``--set KEY=VALUE``; the file reads back as an IasResult."""
    from bearingsim.results import load_result

    out = tmp_path / "ias.nc"
    args = ["--model", "ias", "--duration-s", "0.2", "--dt-s", "1e-5", "--fs-hz", "10000"]
    r = run_cli("simulate", *args, "--set", "spall_width_m=2e-3", "-o", out, "--json")
    assert r.code == 0, r.err
    d = r.json()
    assert d["n_samples"] == 2000 and d["spall_width_m"] == 2e-3
    back = load_result(out)
    assert type(back).__name__ == "IasResult" and back.params.spall_width == 2e-3
    assert_allclose(d["mean_speed_rpm"], back.omega.mean() * 30 / math.pi, rtol=1e-12)


@pytest.mark.parametrize(
    ("args", "needle"),
    [
        (["--model", "ias", "--disks", "3"], "unknown key 'disks' (a key of model rotor)"),
        (["--set", "rpn=3"], "unknown key 'rpn'"),
        (["--set", "rpm"], "--set 'rpm' is invalid; valid: KEY=VALUE"),
        (["--rpm", "1700", "--set", "rpm=1800"], "--set rpm=... and its option given together"),
    ],
)
def test_cli_simulate_bad_keys_one_line(run_cli, tmp_path, args, needle):
    r = run_cli("simulate", *args, "--duration-s", "0.01", "-o", tmp_path / "x.nc")
    assert r.code == 2 and r.err.startswith("error: ") and needle in r.err, r.err
    assert len(r.err.strip().splitlines()) == 1 and not (tmp_path / "x.nc").exists()
