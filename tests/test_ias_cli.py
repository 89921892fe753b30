"""``bearingsim ias`` and ``bearingsim analyze-ias``: outputs and bad input."""

from __future__ import annotations

import math

import numpy as np
import pytest
from numpy.testing import assert_allclose

from bearingsim.cli import main
from bearingsim.dynamics.ias.model import IasResult
from bearingsim.report.published import value

#: short runs: dt 1e-5 s (valid, see tests/test_ias.py), 1.5 s simulated, 10 kHz output
FAST = ["--duration-s", "1.5", "--dt-s", "1e-5", "--fs-hz", "10000"]
KEYS = {
    "mean_speed_rpm",
    "ias_ripple_rel",
    "order_peaks",
    "bpfo_order_theory",
    "spall_width_estimate_m",
    "wall_s",
}


def test_ias_json_and_files(run_cli, tmp_path):
    out, png = tmp_path / "r.nc", tmp_path / "r.png"
    r = run_cli(
        "ias",
        "--bearing",
        "NU204-ECP",
        "--torque-n-m",
        "9.54",
        "--fy-n",
        "400",
        "--spall-width-m",
        "1e-3",
        *FAST,
        "-o",
        out,
        "--plot",
        png,
        "--json",
    )
    assert r.code == 0, r.err
    d = r.json()
    assert KEYS <= set(d)
    assert_allclose(
        d["mean_speed_rpm"], value("ias.s3_1.mean_speed"), rtol=0.01, err_msg="seed IAS §3.1"
    )
    assert_allclose(
        d["bpfo_order_theory"], value("ias.eq36.bpfo_order"), atol=5e-3, err_msg="seed IAS eq. (36)"
    )
    assert_allclose(d["spall_width_estimate_m"], 1e-3, rtol=0.1, err_msg="seed IAS eq. (37)")
    assert {"order", "amplitude"} == set(d["order_peaks"][0])
    assert out.stat().st_size > 0 and png.stat().st_size > 0
    res = IasResult.load(out)
    assert res.params.spall_width == 1e-3


def test_ias_scenario_file_and_rpm(run_cli, tmp_path):
    sc = tmp_path / "s.toml"
    sc.write_text("spall_width_m = 0.0\nfy_n = 400\nduration_s = 1.5\ndt_s = 1e-5\nfs_hz = 10000\n")
    r = run_cli("ias", sc, "--rpm", "60", "-o", tmp_path / "h.nc", "--json")
    assert r.code == 0, r.err
    d = r.json()
    assert_allclose(d["torque_n_m"], 1.52 * 2 * math.pi, rtol=1e-12, err_msg="M_z = C_T w")
    assert d["spall_width_estimate_m"] is None
    assert_allclose(
        d["order_peaks"][0]["order"],
        value("ias.eq36.bpfo_order"),
        atol=0.02,
        err_msg="healthy ripple",
    )


def test_ias_text_output(run_cli, tmp_path):
    r = run_cli("ias", "--spall-width-m", "2e-3", *FAST, "-o", tmp_path / "r.nc")
    assert r.code == 0, r.err
    assert "spall width" in r.out and "mean speed" in r.out


@pytest.fixture(scope="module")
def encoder_csv(tmp_path_factory):
    """Encoder timestamps (1024 lines/rev) of a simulated 1 mm spall, as a measured IAS file."""
    from bearingsim import get_bearing
    from bearingsim.dynamics.ias.model import IasParams, simulate_ias

    r = simulate_ias(IasParams(get_bearing("NU204-ECP")), 2.0, 1e-5, 20_000.0)
    m = r.t > 0.2
    th, t = r.theta[m], r.t[m]
    ticks = (
        np.arange(
            math.ceil(th[0] / (2 * math.pi / 1024)), math.floor(th[-1] / (2 * math.pi / 1024))
        )
        * 2
        * math.pi
        / 1024
    )
    tt = np.interp(ticks, th, t)
    d = tmp_path_factory.mktemp("enc")
    f = d / "encoder.csv"
    np.savetxt(f, np.c_[tt, ticks], delimiter=",", header="time_s,angle_rad", comments="")
    g = d / "speed.csv"
    np.savetxt(g, np.c_[t, r.omega[m] * 60 / (2 * math.pi)], delimiter=",")
    return f, g


def test_analyze_encoder_timestamps(run_cli, encoder_csv, tmp_path):
    f, _ = encoder_csv
    r = run_cli("analyze-ias", f, "--bearing", "NU204-ECP", "--plot", tmp_path / "a.png", "--json")
    assert r.code == 0, r.err
    d = r.json()
    assert_allclose(d["mean_speed_rpm"], 60.0, rtol=0.01)
    assert_allclose(
        d["spall_width_estimate_m"],
        1e-3,
        rtol=0.1,
        err_msg="width from encoder timestamps, seed IAS eq. (37)",
    )
    assert (tmp_path / "a.png").stat().st_size > 0


def test_analyze_speed_without_bearing(run_cli, encoder_csv):
    _, g = encoder_csv
    r = run_cli("analyze-ias", g, "--kind", "speed_rpm", "--json")
    assert r.code == 0, r.err
    d = r.json()
    assert d["bpfo_order_theory"] is None and d["spall_width_estimate_m"] is None
    top = max(d["order_peaks"], key=lambda p: p["amplitude"])
    assert_allclose(top["order"], value("ias.eq36.bpfo_order"), atol=0.02)


def _bad(capsys, args, *needles, out=None):
    with pytest.raises(SystemExit) as exc:
        main([str(a) for a in args])
    cap = capsys.readouterr()
    assert exc.value.code == 2
    assert cap.out == ""
    lines = cap.err.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("error: "), cap.err
    for n in needles:
        assert n in lines[0], lines[0]
    if out is not None:
        assert not out.exists()
        assert list(out.parent.iterdir()) == []


@pytest.mark.parametrize(
    "args, needles",
    [
        (["--spall-width-m", "9e-3"], ["spall_width_m = 0.009 m", "valid range [0, 0.00794) m"]),
        (["--spall-width-m", "-1e-3"], ["spall_width_m = -0.001 m", "valid range"]),
        (["--dt-s", "0"], ["dt_s = 0 s", "valid range (0, inf) s"]),
        (["--dt-s", "-1e-6"], ["dt_s = -1e-06 s", "valid range"]),
        (["--duration-s", "0"], ["duration_s = 0 s", "valid range (0, inf) s"]),
        (["--dt-s", "1e-3"], ["dt_s = 0.001 s is too large for stability", "valid range (0, "]),
        (["--torque-n-m", "0"], ["torque_n_m = 0 N m with zero initial speed"]),
        (["--torque-n-m", "0", "--initial-rpm", "60", "--dt-s", "1e-5"], ["needs a turning shaft"]),
        (["--rpm", "0"], ["rpm = 0 r/min", "valid range (0, inf)"]),
        (["--rpm", "60", "--torque-n-m", "9"], ["at most one of --rpm and --torque-n-m"]),
        (["--fy-n", "0"], ["radial load = 0 N"]),
        (["--bearing", "6205"], ["not a cylindrical roller bearing"]),
        (["--bearing", "nope"], ["bearing = 'nope' is not in the catalogue"]),
    ],
)
def test_ias_bad_input(capsys, tmp_path, args, needles):
    d = tmp_path / "out"
    d.mkdir()
    _bad(
        capsys,
        ["ias", *args, "--duration-s", "0.2", "-o", d / "r.nc"]
        if "--duration-s" not in args
        else ["ias", *args, "-o", d / "r.nc"],
        *needles,
        out=d / "r.nc",
    )


def test_ias_bad_scenario(capsys, tmp_path):
    sc = tmp_path / "s.toml"
    sc.write_text("spall_widht_m = 1e-3\n")
    _bad(capsys, ["ias", sc, "-o", tmp_path / "r.nc"], "unknown key 'spall_widht_m'", "valid keys")
    sc.write_text("dt_s = 'fast'\n")
    _bad(capsys, ["ias", sc, "-o", tmp_path / "r.nc"], "dt_s = 'fast'", "is text")


def test_analyze_bad_input(capsys, tmp_path):
    f = tmp_path / "x.csv"
    f.write_text("0,1\n1,2\n2,3\n3,4\n")
    _bad(capsys, ["analyze-ias", f], "give --kind")
    f.write_text("0,1\n1,0.5\n2,3\n3,4\n4,5\n")
    _bad(capsys, ["analyze-ias", f, "--kind", "angle_rad"], "not strictly increasing")
    _bad(capsys, ["analyze-ias", tmp_path / "missing.csv"], "does not exist")
    _bad(
        capsys,
        ["analyze-ias", f, "--kind", "angle_rad", "--bearing", "6205"],
        "not a cylindrical roller bearing",
    )


def test_user_bearing_with_other_roller_count(run_cli, tmp_path):
    """The estimator is not tuned to the seed bearing: 13 rollers move the BPFO order to
    13/2 (1 - 7.94/34) = 4.982 and a 1.5 mm spall is still sized within 10 %."""
    bf = tmp_path / "nu13.toml"
    bf.write_text(
        'id = "NU-13"\ntype = "cylindrical_roller"\nn_elements = 13\n'
        "element_diameter_m = 7.94e-3\npitch_diameter_m = 34.0e-3\nroller_length_m = 9.0e-3\n"
        "diametral_clearance_m = 2.0e-6\ninner_raceway_diameter_m = 26.5e-3\n"
        "outer_raceway_diameter_m = 41.5e-3\n"
    )
    sc = tmp_path / "s.toml"
    sc.write_text('bearing_file = "nu13.toml"\nspall_width_m = 1.5e-3\n')
    r = run_cli("ias", sc, *FAST, "-o", tmp_path / "r.nc", "--json")
    assert r.code == 0, r.err
    d = r.json()
    assert_allclose(d["bpfo_order_theory"], 6.5 * (1 - 7.94 / 34), rtol=1e-12)
    top = max(d["order_peaks"], key=lambda p: p["amplitude"])
    assert_allclose(top["order"], d["bpfo_order_theory"], atol=0.02)
    assert_allclose(d["spall_width_estimate_m"], 1.5e-3, rtol=0.10)


def test_mean_speed_is_total_angle_over_total_time(run_cli, tmp_path):
    """A constant 600 r/min shaft stamped at 2 kHz with 50 us of Gaussian timing jitter: the
    mean speed is the total angle over the total time, 600 r/min to 0.01 %. (Exploratory
    testing: the mean of the differentiated speed samples read 622.65 r/min; the derivative
    amplifies the jitter and its mean is biased upwards.)"""
    rng = np.random.default_rng(7)
    n = 20000
    t_true = np.arange(n) / 2000.0
    t = np.sort(t_true + rng.normal(0.0, 50e-6, n))
    angle = 2 * np.pi * 10.0 * t_true  # the encoder angle at the true instants
    f = tmp_path / "jitter.csv"
    np.savetxt(f, np.column_stack([t, angle]), delimiter=",", header="time_s,angle_rad",
               comments="")  # fmt: skip
    r = run_cli("analyze-ias", f, "--json")
    assert r.code == 0, r.err
    d = r.json()
    expect = (angle[-1] - angle[0]) / (t[-1] - t[0]) * 60 / (2 * np.pi)
    assert d["mean_speed_rpm"] == pytest.approx(expect, rel=1e-9)
    assert d["mean_speed_rpm"] == pytest.approx(600.0, rel=1e-4)
