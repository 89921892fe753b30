"""``bearingsim simulate --model rotor`` and ``bearingsim.simulate`` for the bearing–rotor–housing
model (issue 6): output file, ``--json`` contract, per-end accelerations, analysis, bad input."""

from __future__ import annotations

import json

import pytest
from numpy.testing import assert_allclose

import bearingsim
from bearingsim.cli import main
from bearingsim.config import Scenario
from bearingsim.errors import ConfigError
from bearingsim.report.published import value
from bearingsim.results import SimulationResult

BASE = ["simulate", "--model", "rotor", "--duration-s", "0.5", "--fs-hz", "12000"]


def test_cli_simulate_rotor_json_file_and_api_agree(run_cli, tmp_path):
    out = tmp_path / "r.nc"
    r = run_cli(*BASE, "--de-fault", "outer", "--disks", "3", "-o", out, "--json")
    assert r.code == 0, r.err
    js = r.json()  # exactly one JSON object on stdout
    assert r.out.strip().count("\n") == 0
    assert js["n_samples"] == 6000 and js["fs_hz"] == 12000.0
    for k in ("rms_acc_x", "rms_acc_y", "rms_acc_x_fe", "rms_acc_y_fe"):
        assert js[k] > 0
    res = SimulationResult.load(out)
    for ch in ("acc_x", "acc_y", "acc_x_fe", "acc_y_fe", "disp_y_de", "shaft_y_fe"):
        assert res[ch].shape == (6000,)
    assert res.meta["model"] == "rotor" and res.meta["bearing_id"] == "6205-cwru"
    assert res.meta["bearing_fe_id"] == "6203-cwru"
    assert res.scenario["de_fault"] == "outer" and res.scenario["disks"] == 3
    assert_allclose(js["rms_acc_y"], res.rms("acc_y"), rtol=1e-12)
    # the same scenario through the Python API gives the same numbers (deterministic)
    api = bearingsim.simulate(
        {"model": "rotor", "de_fault": "outer", "disks": 3, "duration_s": 0.5, "fs_hz": 12000.0}
    )
    assert_allclose(api["acc_y"], res["acc_y"], rtol=0, atol=0)
    assert_allclose(api["acc_y_fe"], res["acc_y_fe"], rtol=0, atol=0)


def test_analyze_rotor_result_both_ends(run_cli, tmp_path):
    out = tmp_path / "fe.nc"
    assert run_cli(*BASE, "--fe-fault", "outer", "--disks", "2", "-o", out, "--json").code == 0
    fe = run_cli("analyze", out, "--channel", "y_fe", "--json")
    assert fe.code == 0, fe.err
    d = fe.json()
    assert d["diagnosis"] == "outer"
    bpfo = [p for p in d["peaks"] if p["label"] == "BPFO"][0]
    bpfo_fe = value("cwru.fan_end.bpfo_order") * 1750 / 60
    assert abs(bpfo["target_hz"] - bpfo_fe) < 0.01, "FE (6203) BPFO, CWRU order"
    assert bpfo["detected"]
    bad = run_cli("analyze", out, "--channel", "z")
    assert bad.code == 2 and "valid: x, y, x_fe, y_fe" in bad.err


def test_scenario_file_with_rotor_keys_and_per_ball(tmp_path):
    toml = tmp_path / "rotor.toml"
    toml.write_text(
        'model = "rotor"\nde_fault = "inner"\ndisk_positions_mm = [60.0, 140.0]\n'
        "duration_s = 0.05\nfs_hz = 12000.0\nper_ball = true\nunbalance_kg_m = 1e-5\n"
    )
    sc = Scenario.from_toml(toml)
    assert sc.disk_positions_mm == (60.0, 140.0)
    res = bearingsim.simulate(sc)
    assert res["ball_load_outer_de"].shape == (600, 9)
    assert res["ball_load_inner_fe"].shape == (600, 8)
    out = res.save(tmp_path / "b.nc")
    back = SimulationResult.load(out)
    assert_allclose(back["ball_load_outer_fe"], res["ball_load_outer_fe"], rtol=0, atol=0)
    assert back.dims["ball_load_outer_fe"] == ("time", "ball_fe")
    rotor_meta = back.meta["rotor"]["inputs"]
    assert rotor_meta["armature"]["positions"] == pytest.approx([0.06, 0.14])
    assert json.loads(json.dumps(back.scenario)) == back.scenario


@pytest.mark.parametrize(
    "args, needle",
    [
        (["--de-fault", "outer", "--disk-positions-mm", "50,250"],
         "disk_position_m = 0.25 m is out of range; valid range (0, 0.2032) m"),
        (["--disk-positions-mm", "0,100"], "disk_position_m = 0 m is out of range"),
        (["--housing-mass-kg", "0"], "housing_mass_kg = 0 kg is out of range; valid range (0,"),
        (["--housing-stiffness-n-per-m", "-3"],
         "housing_stiffness_n_per_m = -3 N/m is out of range"),
        # issue 14 sweep: 1e-300 N/m sagged the housing 1e301 m, then ZeroDivisionError
        (["--housing-stiffness-n-per-m", "1e-300"],
         "housing_stiffness_n_per_m = 1e-300 N/m puts the housing's mount frequency at 6.18e-152 "
         "Hz, below the 0.001 Hz the rotor model resolves; valid range [0.000262058, inf) N/m"),
        (["--contact-damping-n-s-per-m", "-1"],
         "contact_damping_n_s_per_m = -1 N s/m is out of range"),
        (["--disks", "9", "--elements", "4"], "elements = 4 is out of range; valid range [10"),
        (["--disks", "0"], "disks = 0 is out of range; valid range [1, inf)"),
        (["--fault", "outer"], "unknown key 'fault' (a key of model vsm/dem/tvsm)"),
        (["--de-bearing", "nope"], "nope"),
        (["--de-fault", "outer", "--defect-width-m", "0.01"],
         "defect_width_m = 0.01 m is out of range"),
        # issue 14 sweep: without a fault the defect keys were not checked (1e30 m accepted)
        (["--defect-width-m", "1e30"], "defect_width_m = 1e+30 m is wider than the ball can "
         "span; valid range (0, 0.00794004) m"),
        (["--defect-depth-m", "1e30"], "defect_depth_m = 1e+30 m is not less than the outer "
         "ring wall 0.00250953 m of 6205-cwru"),
    ],
    ids=["pos-outside", "pos-at-bearing", "housing-mass", "housing-stiffness", "housing-soft",
         "contact-damping",
         "elements", "disks", "ring-fault-key", "bearing-id", "defect-width", "unused-width",
         "unused-depth"],
)  # fmt: skip
def test_cli_simulate_rotor_bad_input(args, needle, capsys, tmp_path):
    out = tmp_path / "x.nc"
    with pytest.raises(SystemExit) as ei:
        main([*BASE, *args, "-o", str(out)])
    assert ei.value.code == 2
    cap = capsys.readouterr()
    lines = cap.err.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("error: "), cap.err
    assert needle in lines[0]
    assert cap.out == ""
    assert not out.exists(), "no output file on bad input"
    assert not list(tmp_path.iterdir()), "no partial file either"


def test_rotor_keys_refused_by_ring_models():
    """Each family has its own schema (issue 13): a rotor key in a ring scenario is an error that
    names the family it belongs to (before 0.2.0 it was silently ignored)."""
    with pytest.raises(ConfigError, match=r"unknown key 'disks' \(a key of model rotor\)"):
        bearingsim.simulate({"model": "vsm", "duration_s": 0.01, "fs_hz": 12000.0, "disks": 3})
