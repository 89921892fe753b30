"""A scenario with a rig takes realistic values for the keys it leaves unset (docs/models.md,
"Realistic defaults with a rig"): the side-by-side's random slip, drop profile and contact
roughness (bearingsim.config.REALISM); without a rig the seeds' values stay, bit for bit."""

from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

import pytest
from numpy.testing import assert_array_equal

import bearingsim
from bearingsim import simulate
from bearingsim.config import REALISM, Scenario
from bearingsim.errors import ConfigError
from bearingsim.results import load_result

SRC = str(Path(bearingsim.__file__).resolve().parents[1])
RIG = "cwru-de-12k"
SEED_RING = {"slip_percent": 0.0, "defect_profile": "rectangular", "contact_roughness_m": 0.0}
SEED_ROTOR = {"slip_percent": 0.0, "defect_profile": "geometric", "contact_roughness_m": 0.0}


def _values(sc) -> dict:
    return {k: getattr(sc, k) for k in REALISM}


@pytest.mark.parametrize(("model", "seed_values"), [("vsm", SEED_RING), ("dem", SEED_RING),
                                                    ("tvsm", SEED_RING),
                                                    ("rotor", SEED_ROTOR)])  # fmt: skip
def test_unset_keys_follow_the_rig(model, seed_values):
    plain = Scenario(model=model, fs_hz=12000.0)
    assert _values(plain) == seed_values
    assert plain.realism_defaults == {}
    rigged = Scenario(model=model, fs_hz=12000.0, rig=RIG)
    assert _values(rigged) == REALISM
    # what the rig changed (the rotor's seed already has the geometric drop)
    assert rigged.realism_defaults == {k: v for k, v in REALISM.items() if v != seed_values[k]}
    # stored unset: the copy without the rig, and the dict round trip, resolve anew
    assert all(rigged.to_dict()[k] is None for k in REALISM)
    assert Scenario.from_dict(rigged.to_dict()) == rigged
    assert _values(rigged.replace(rig=None)) == seed_values
    assert _values(plain.replace(rig=RIG)) == REALISM


def test_a_given_key_keeps_its_value_through_a_rig():
    sc = Scenario(
        model="dem", fs_hz=12000.0, rig=RIG, slip_percent=0.0, defect_profile="rectangular"
    )
    assert sc.slip_percent == 0.0 and sc.defect_profile == "rectangular"
    assert sc.contact_roughness_m == REALISM["contact_roughness_m"]
    assert sc.realism_defaults == {"contact_roughness_m": REALISM["contact_roughness_m"]}
    assert sc.to_dict()["slip_percent"] == 0.0
    assert sc.replace(rig=None).slip_percent == 0.0  # given, so kept
    # the adaptive solver has no slip: a rig does not turn it on there
    assert Scenario(model="vsm", fs_hz=12000.0, rig=RIG, solver="dopri5").slip_percent == 0.0
    # an explicit slip with dopri5 is still refused in one line
    with pytest.raises(ConfigError, match="slip_percent = 1.5 % needs solver = 'rk4'"):
        Scenario(model="vsm", fs_hz=12000.0, rig=RIG, solver="dopri5", slip_percent=1.5)


def test_without_a_rig_the_output_is_the_seed_default_bit_for_bit():
    """The defaults resolved to the seeds' values give the same signal as those values given
    explicitly (the seed comparisons keep running unchanged)."""
    sc = dict(model="vsm", fault="outer", duration_s=0.05, fs_hz=12000.0)
    a = simulate(sc)
    b = simulate({**sc, **SEED_RING})
    assert_array_equal(a["acc_y"], b["acc_y"])
    assert a.meta["defaults"]["keys"] == SEED_RING
    assert a.meta["defaults"]["source"] == "the seeds' defaults"


def test_with_a_rig_the_output_is_the_realism_bit_for_bit():
    sc = dict(model="vsm", fault="outer", duration_s=0.05, fs_hz=12000.0, rig=RIG)
    a = simulate(sc)
    b = simulate({**sc, **REALISM})
    assert_array_equal(a["acc_sensor"], b["acc_sensor"])
    assert a.meta["defaults"]["keys"] == REALISM and b.meta["defaults"]["keys"] == {}
    assert "REALISM" in a.meta["defaults"]["source"]


def _cli(*args, cwd):
    import os

    env = {**os.environ, "PYTHONPATH": SRC}
    return subprocess.run([sys.executable, "-m", "bearingsim", *args], capture_output=True,
                          text=True, env=env, cwd=cwd)  # fmt: skip


def test_cli_rig_option_on_a_scenario_file_without_one(tmp_path):
    """`simulate SC.toml --rig NAME`: the file's unset keys take the rig's defaults (the file's
    own keys stay), and the command says which it chose."""
    (tmp_path / "sc.toml").write_text(
        'model = "vsm"\nfault = "outer"\nduration_s = 0.05\nfs_hz = 12000.0\nslip_percent = 0.5\n'
    )
    out = tmp_path / "s.nc"
    r = _cli("simulate", "sc.toml", "--rig", RIG, "-o", str(out), "--json", cwd=tmp_path)
    assert r.returncode == 0, r.stderr
    rep = json.loads(r.stdout)
    assert rep["realism_defaults"] == {k: v for k, v in REALISM.items() if k != "slip_percent"}
    res = load_result(out)
    assert res.scenario["slip_percent"] == 0.5 and res.scenario["contact_roughness_m"] is None
    assert res.meta["defaults"]["keys"]["contact_roughness_m"] == REALISM["contact_roughness_m"]
    r = _cli("simulate", "sc.toml", "--rig", RIG, "-o", str(tmp_path / "t.nc"), cwd=tmp_path)
    assert r.returncode == 0, r.stderr
    assert "(rig defaults: defect_profile = geometric, contact_roughness_m = 1e-07)" in r.stdout


@pytest.mark.parametrize("model", ["vsm", "dem", "tvsm", "rotor"])
def test_an_unset_rate_is_the_rigs(model):
    """A scenario with a rig and no ``fs_hz`` is sampled at the rate of the records the rig was
    identified from (the shipped profiles: 12 or 48 kHz); without a rig, 48 kHz as before; a
    rate given is kept. The resolved rate is stored as a number and listed among the rig's
    defaults."""
    assert Scenario(model=model).fs_hz == 48000.0
    sc = Scenario(model=model, rig=RIG)
    assert sc.fs_hz == 12000.0 and "fs_hz" in sc.auto_keys
    assert sc.realism_defaults["fs_hz"] == 12000.0
    assert sc.to_dict()["fs_hz"] == 12000.0 and Scenario.from_dict(sc.to_dict()).fs_hz == 12000.0
    assert sc.replace(rig=None).fs_hz == 48000.0
    assert sc.replace(rig="cwru-de-48k").fs_hz == 48000.0
    given = Scenario(model=model, rig=RIG, fs_hz=24000.0)
    assert given.fs_hz == 24000.0 and "fs_hz" not in given.realism_defaults
    assert Scenario(model=model, fs_hz=12000.0).replace(rig=RIG).fs_hz == 12000.0


def test_a_12_khz_profile_on_a_48_khz_output_warns():
    """A rig's background table ends at its records' Nyquist frequency (6 kHz for the 12 kHz CWRU
    profiles): on a 48 kHz output the sensor signal above it is the model's alone, said in one
    warning (RigRateWarning); the 48 kHz profile on the same output says nothing."""
    import warnings

    from bearingsim.rig import RigRateWarning

    sc = dict(model="vsm", duration_s=0.02, fs_hz=48000.0)
    with pytest.warns(RigRateWarning, match="background is defined up to 6000 Hz"):
        simulate({**sc, "rig": RIG})
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        simulate({**sc, "rig": "cwru-de-48k"})


def test_cli_simulate_with_a_shipped_rig_writes_its_rate(tmp_path):
    """`simulate --rig cwru-de-12k` without --fs-hz writes a 12 kHz signal (48 kHz before, whose
    band above the profile's 5.4 kHz was the model's output alone, with a RigRateWarning) and
    says it chose the rate."""
    out = tmp_path / "s.nc"
    r = _cli("simulate", "--fault", "outer", "--duration-s", "0.05", "--rig", RIG, "-o",
             str(out), "--json", cwd=tmp_path)  # fmt: skip
    assert r.returncode == 0, r.stderr
    assert "RigRateWarning" not in r.stderr and "background is defined" not in r.stderr
    rep = json.loads(r.stdout)
    assert rep["fs_hz"] == 12000.0 and rep["realism_defaults"]["fs_hz"] == 12000.0
    res = load_result(out)
    assert res.fs_hz == 12000.0 and res.scenario["fs_hz"] == 12000.0 and res.time.size == 600
