"""The foundation CLI commands: JSON contracts and one-line errors with exit code 2."""

from __future__ import annotations

import json
import math

import numpy as np
import pytest
from numpy.testing import assert_allclose

from bearingsim import __version__
from bearingsim.report.published import entry, value


def test_version(run_cli):
    r = run_cli("--version")
    assert r.code == 0 and __version__ in r.out


def test_bearings_json(run_cli):
    r = run_cli("bearings", "--json")
    assert r.code == 0
    ids = {b["id"] for b in r.json()["bearings"]}
    assert {"6205", "6205-cwru", "6203-cwru", "6206", "NU204-ECP"} <= ids


def test_info_json(run_cli):
    r = run_cli("info", "6205", "--rpm", "1748", "--json")
    assert r.code == 0, r.err
    d = r.json()
    assert set(d) == {
        "ftf_hz",
        "bpfo_hz",
        "bpfi_hz",
        "bsf_hz",
        "ftf_order",
        "bpfo_order",
        "bpfi_order",
        "bsf_order",
    }
    assert_allclose(
        d["bpfi_hz"], value("vsm.eq20.bpfi_6205_1748rpm"), rtol=1e-3, err_msg="seed VSM eq (20)"
    )


def test_contact_json_ball_load(run_cli):
    r = run_cli("contact", "6206", "--ball-load-n", str(4.37 * 5000 / 9), "--json")
    assert r.code == 0, r.err
    d = r.json()
    keys = {
        "a_m",
        "b_m",
        "delta_m",
        "p_max_pa",
        "k_hertz",
        "tau_max_pa",
        "tau_max_depth_m",
        "tau_orth_pa",
        "tau_orth_depth_m",
    }
    assert keys <= set(d["inner"]) and keys <= set(d["outer"])
    assert "k_combined" in d
    p_pub = entry("life.table2.inner_pmax_theory").si
    assert_allclose(d["inner"]["p_max_pa"], p_pub, rtol=0.01, err_msg="seed LIFE table 2")


def test_contact_json_radial_load(run_cli):
    r = run_cli("contact", "6206", "--radial-load-n", "5000", "--json")
    assert r.code == 0, r.err
    d = r.json()
    assert_allclose(d["q_max_stribeck_n"], 4.37 * 5000 / 9, rtol=1e-12)
    assert d["q_max_n"] == d["ball_load_n"]
    # discrete balls at zero clearance: within 1 % of Stribeck's 4.37 (Harris & Kotzalas §7.2)
    assert_allclose(d["q_max_n"], d["q_max_stribeck_n"], rtol=0.01)


def test_contact_roller(run_cli):
    r = run_cli("contact", "NU204-ECP", "--ball-load-n", "200", "--json")
    assert r.code == 0, r.err
    assert_allclose(r.json()["inner"]["exponent"], 10 / 9)


def test_load_json(run_cli, tmp_path):
    png = tmp_path / "l.png"
    r = run_cli("load", "6205", "--fx-n", "10", "--fy-n", "50", "--plot", png, "--json")
    assert r.code == 0, r.err
    d = r.json()
    for k in (
        "theta0_deg",
        "fr_n",
        "delta_max_m",
        "delta_r_m",
        "epsilon",
        "psi_l_deg",
        "ball_angles_deg",
        "ball_loads_n",
        "n_loaded",
    ):
        assert k in d
    assert len(d["ball_loads_n"]) == 9
    assert np.abs(d["force_residual_n"]).max() < 1e-9  # free motion: both components balance
    assert_allclose(d["fr_n"], value("vsm.s2_1.radial_load"), rtol=1e-3, err_msg="seed VSM §2.1")
    assert png.stat().st_size > 1000


def test_load_line_reports_the_force_it_leaves(run_cli):
    """A helper's exploratory testing (twenty-eighth session): ``--motion load_line`` balances
    the load line only; the perpendicular 2.2 N (of a 51 N load) went unreported."""
    d = run_cli(
        "load", "6205", "--fx-n", "10", "--fy-n", "50", "--motion", "load_line", "--json"
    ).json()
    assert d["residual_rel"] < 1e-12
    rx, ry = d["force_residual_n"]
    assert 2.0 < math.hypot(rx, ry) < 2.5, (rx, ry)
    assert abs(rx * 10 + ry * 50) < 1e-9 * 50  # perpendicular to the load (10, 50) N
    r = run_cli("load", "6205", "--fx-n", "10", "--fy-n", "50", "--motion", "load_line")
    assert "unbalanced force: (2.196, -0.4392) N (x, y)" in r.out, r.out


@pytest.mark.parametrize(
    "args, name, lo",
    [
        (["info", "6205"], "rpm", "(0"),
        (["stiffness", "6205", "--fy-n", "100", "--cage-revs", "1", "--points-per-rev", "36"],
         "shaft speed", "[0"),
        (["stiffness", "6205", "--fy-n", "100", "--method", "iso16281"], "shaft speed", "[0"),
        (["vsm-trace", "--cage-revs", "0.1", "--json"], "rpm", "(0"),
        (["life", "6205", "--radial-load-n", "3000", "-o", "x.nc"], "rpm", "(0"),
    ],
    ids=["info", "stiffness", "stiffness-iso", "vsm-trace", "life"],
)  # fmt: skip
def test_shaft_speed_where_the_rings_burst_refused(run_cli, tmp_path, args, name, lo):
    """Issue 14 sweep: ``--rpm 1e30`` was accepted by info, stiffness, vsm-trace, rotor-modes and
    life. A speed factor n d_m above 1e7 mm r/min (hoop stress rho v^2 of a steel ring beyond its
    strength) is refused: 256 410 r/min on a 6205 (d_m = 39 mm)."""
    r = run_cli(*[str(tmp_path / a) if a == "x.nc" else a for a in args], "--rpm", "1e30")
    assert r.code == 2 and not list(tmp_path.iterdir())
    assert r.err == (
        f"error: {name} = 1e+30 r/min gives the speed factor n d_m = 3.9e+31 mm r/min of 6205 "
        "(d_m = 39 mm), above 1e+07, where a steel ring bursts (hoop stress rho v^2 beyond its "
        f"strength); valid range {lo}, 256410] r/min\n"
    )
    r = run_cli("info", "6205", "--rpm", "256410", "--json")  # the limit itself is valid
    assert r.code == 0 and math.isfinite(r.json()["bpfi_hz"])


def test_user_bearing_file(run_cli, tmp_path):
    f = tmp_path / "mine.toml"
    f.write_text(
        'id = "mine"\ntype = "ball"\nn_elements = 8\nelement_diameter_m = 6.35e-3\n'
        "pitch_diameter_m = 28.5e-3\ninner_groove_radius_m = 3.3e-3\n"
        "outer_groove_radius_m = 3.35e-3\n"
    )
    r = run_cli("info", "--bearing-file", f, "--rpm", "1200", "--json")
    assert r.code == 0, r.err
    assert r.json()["bpfo_order"] > 0


def test_material_override(run_cli):
    a = run_cli("contact", "6205", "--ball-load-n", "100", "--json").json()
    b = run_cli("contact", "6205", "--ball-load-n", "100", "--E-pa", "100e9", "--json").json()
    assert b["inner"]["p_max_pa"] < a["inner"]["p_max_pa"]


def test_json_output_is_one_object(run_cli):
    r = run_cli("load", "6205", "--fy-n", "100", "--json")
    assert r.out.count("\n") == 1 and isinstance(json.loads(r.out), dict)


BAD = [
    (["info", "6299", "--rpm", "100"], "bearing"),
    (["info", "6205", "--rpm", "-5"], "rpm"),
    (["info", "6205", "--rpm", "0"], "rpm"),
    (["info", "6205", "--rpm", "nan"], "rpm"),
    (["info", "6205", "--rpm", "abc"], "rpm"),
    (["contact", "6205", "--ball-load-n", "-3"], "ball_load_n"),
    (["contact", "6205", "--radial-load-n", "inf"], "radial_load_n"),
    (["contact", "6205"], "--ball-load-n"),
    (["load", "6205", "--fx-n", "nan", "--fy-n", "1"], "fx_n"),
    (["load", "6205", "--fy-n", "10", "--clearance-m", "0.01"], "clearance_m"),
    (["info", "6205", "--rpm", "100", "--E-pa", "-1"], "E_pa = -1 Pa is out of range"),
    (["info", "6205", "--rpm", "100", "--nu", "0.7"], "nu = 0.7 is out of range"),
]


@pytest.mark.parametrize("args, field", BAD, ids=[" ".join(a) for a, _ in BAD])
def test_bad_input_one_line_exit_2(run_cli, args, field):
    r = run_cli(*args)
    assert r.code == 2
    lines = r.err.strip().splitlines()
    assert len(lines) == 1, r.err
    assert field in lines[0]
    assert "Traceback" not in r.err


@pytest.mark.parametrize(
    "content, field",
    [
        (
            "id = 'x'\ntype = 'ball'\nn_elements = 2\nelement_diameter_m = 0.005\n"
            "pitch_diameter_m = 0.03\ninner_groove_radius_m = 0.0026\n"
            "outer_groove_radius_m = 0.0027",
            "n_elements",
        ),
        (
            "id = 'x'\ntype = 'ball'\nn_elements = 9\nelement_diameter_m = -0.005\n"
            "pitch_diameter_m = 0.03\ninner_groove_radius_m = 0.0026\n"
            "outer_groove_radius_m = 0.0027",
            "element_diameter_m",
        ),
        (
            "id = 'x'\ntype = 'ball'\nn_elements = 9\nelement_diameter_m = 0.04\n"
            "pitch_diameter_m = 0.03\ninner_groove_radius_m = 0.0026\n"
            "outer_groove_radius_m = 0.0027",
            "element_diameter_m",
        ),
        (
            "id = 'x'\ntype = 'ball'\nn_elements = 9\nelement_diameter_m = 0.005\n"
            "pitch_diameter_m = 0.03\ninner_groove_radius_m = 0.0024\n"
            "outer_groove_radius_m = 0.0027",
            "inner_groove_radius_m",
        ),
        ("id = 'x'\ntype = 'ball'\nn_elements = 9\nshoe_size = 3", "shoe_size"),
        ("id = 'x\ntype = ball", "TOML"),
    ],
    ids=["few-elements", "negative-d", "d-ge-D", "conformity", "unknown-key", "malformed"],
)
def test_bad_bearing_file(run_cli, tmp_path, content, field):
    f = tmp_path / "bad.toml"
    f.write_text(content)
    r = run_cli("info", "--bearing-file", f, "--rpm", "100")
    assert r.code == 2
    assert len(r.err.strip().splitlines()) == 1 and field in r.err


def test_missing_bearing_file(run_cli, tmp_path):
    r = run_cli("info", "--bearing-file", tmp_path / "nope.toml", "--rpm", "100")
    assert r.code == 2 and "bearing_file" in r.err


def test_console_script_subprocess():
    """The installed console entry point runs (guards the pyproject script entry)."""
    import subprocess
    import sys

    p = subprocess.run(
        [sys.executable, "-m", "bearingsim", "info", "6205-cwru", "--rpm", "1797", "--json"],
        capture_output=True,
        text=True,
        timeout=120,
    )
    assert p.returncode == 0, p.stderr
    bpfo_order = value("cwru.drive_end.bpfo_order")
    assert math.isclose(json.loads(p.stdout)["bpfo_order"], bpfo_order, rel_tol=1e-3)
    p = subprocess.run(
        [sys.executable, "-m", "bearingsim", "info", "6205", "--rpm", "-1"],
        capture_output=True,
        text=True,
        timeout=120,
    )
    assert p.returncode == 2 and p.stderr.count("\n") == 1
