"""``bearingsim stiffness`` command: JSON contract, files, bad input (exit 2, one line)."""

from __future__ import annotations

import json
import math

import pytest

from bearingsim.cli import main
from bearingsim.quasistatic import StiffnessResult
from bearingsim.results import load_result

BASE = ["stiffness", "6205", "--fy-n", "500", "--cage-revs", "2", "--points-per-rev", "90"]


def deg(rad: float) -> str:
    """An angle given in rad before the CLI took degrees, as the option's text [deg]."""
    return repr(math.degrees(rad))


def test_json_contract(run_cli):
    r = run_cli(*BASE, "--inner-tilt-deg", deg(3e-3), "--json")
    assert r.code == 0, r.err
    d = r.json()
    assert set(d["displacement"]) == {"x_m", "y_m", "z_m", "theta_x_rad", "theta_y_rad"}
    assert len(d["stiffness_matrix"]) == 5 and all(len(row) == 5 for row in d["stiffness_matrix"])
    for key in ("k_radial_mean", "k_axial_mean", "k_tilt_mean"):
        assert d[key] > 0
    for name in ("radial", "axial", "tilt"):
        f = d["fluctuation"][name]
        assert f["peak_to_peak_rel"] >= 0
        assert isinstance(f["dominant_orders_shaft"], list) and f["dominant_orders_shaft"]
    assert abs(d["fluctuation"]["axial"]["dominant_orders_shaft"][0] - 2.0) < 0.3
    assert r.err == ""


def test_files_and_iso_method(run_cli, tmp_path):
    out, png = tmp_path / "r.nc", tmp_path / "r.png"
    r = run_cli(
        *BASE,
        "--method",
        "iso16281",
        "--conformities",
        "iso",
        "-o",
        out,
        "--plot",
        png,
        "--ball-errors-deg",
        f"{deg(0.05)},0,0,0,{deg(-0.03)},0,0,0,0",
        "--json",
    )
    assert r.code == 0, r.err
    assert r.json()["method"] == "iso16281"
    assert png.stat().st_size > 1000
    res = StiffnessResult.load(out)
    assert res.solution.cage_angle.size == 180
    # the -o file is the netCDF StiffnessResult (it was JSON before issue 13)
    assert load_result(out).solution.method.value == "iso16281"


def test_text_output(run_cli):
    r = run_cli(*BASE, "--rpm", "3000", "--centrifugal", "--gyroscopic")
    assert r.code == 0, r.err
    assert "k_radial" in r.out and "dominant shaft orders" in r.out
    assert "note:" not in r.err


def test_rpm_without_inertia_flags_says_it_applies_no_load(run_cli):
    """--rpm alone applies no inertia load (its help says it is the speed for inertia loads):
    the run says so on stderr instead of ignoring the option in silence."""
    r = run_cli(*BASE, "--rpm", "3000")
    assert r.code == 0, r.err
    assert "note: --rpm without --centrifugal or --gyroscopic applies no inertia load" in r.err


def test_a_bearing_files_contact_angle_is_said_to_set_only_the_curvatures(run_cli, tmp_path):
    """The quasi-static models take the free contact angle from the clearance and the groove
    radii (7.9 deg for the 6205's 6 um); a bearing file's nominal angle sets only the Hertz
    curvatures, and the run says so instead of leaving the user to assume it is used."""
    from pathlib import Path

    import bearingsim

    src = Path(bearingsim.__file__).parent / "catalog" / "6205.toml"
    text = src.read_text().replace("contact_angle_rad = 0.0", "contact_angle_rad = 0.2618")
    f = tmp_path / "acbb.toml"
    f.write_text(text.replace('id = "6205"', 'id = "my-acbb"'))
    r = run_cli("stiffness", "--bearing-file", f, *BASE[2:])
    assert r.code == 0, r.err
    assert "note: the bearing's contact angle (15 deg) sets only the Hertz curvatures" in r.err
    assert "(7.88 deg;" in r.err
    assert "note:" not in run_cli(*BASE).err


def test_tilt_azimuth_without_tilt_says_it_has_no_effect(run_cli):
    r = run_cli(*BASE, "--outer-tilt-azimuth-deg", "30")
    assert r.code == 0, r.err
    assert "note: --outer-tilt-azimuth-deg 30 has no effect: the outer ring is not tilted" in r.err
    refused = run_cli(*BASE, "--rpm", "1e9")  # a refused run prints its error line only
    assert refused.code == 2 and "note:" not in refused.err, refused.err
    r2 = run_cli(*BASE, "--outer-tilt-azimuth-deg", "30", "--outer-tilt-deg", "0.01")
    assert r2.code == 0 and "note:" not in r2.err, r2.err


@pytest.mark.parametrize(
    ("args", "needle"),
    [
        (["--outer-tilt-deg", deg(0.1)], "outer_tilt_rad = 0.1 rad is beyond what the clearance"),
        (
            ["--inner-tilt-deg", deg(0.05), "--outer-tilt-deg", deg(0.02)],
            "inner_tilt_rad = 0.05 rad",
        ),
        (["--ball-errors-deg", f"{deg(0.5)},0,0,0,0,0,0,0,0"], "overlap or pass each other"),
        (["--ball-errors-deg", "0,0,0"], "has 3 values; valid: exactly n_elements = 9"),
        (["--ball-errors-deg", "0,0,0,0,nan,0,0,0,0"], "ball_errors_rad[4] = nan"),
        (["--ball-errors-deg", "0,0,a,0,0,0,0,0,0"], "ball_errors_deg[2] = 'a' is not a number"),
        (["--fx-n", "inf"], "fx_n = inf is not finite"),
        (["--inner-tilt-deg", "nan"], "inner_tilt_deg = nan is not finite"),
        (["--outer-tilt-azimuth-deg", "inf"], "outer_tilt_azimuth_deg = inf is not finite"),
        (["--clearance-m", "1e-3"], "clearance_m = 0.001 m is out of range"),
        # 1 MN axial is also beyond 2 C0 (refused, test_overload_refused): past the overload
        # check, the groove limit refuses it
        (["--fz-n", "1e6", "--allow-overload"], "beyond the groove limit"),
        (["--cage-revs", "0"], "cage_revs = 0"),
        (["--points-per-rev", "10"], "points_per_rev = 10"),
        (["--centrifugal"], "need --rpm"),
        (["--mx-n-m", "1", "--inner-tilt-deg", deg(1e-3)], "held by a misalignment"),
    ],
    ids=[
        "outer-tilt",
        "combined-tilt",
        "overlap",
        "count",
        "nan-error",
        "text-error",
        "inf-load",
        "nan-tilt",
        "inf-azimuth",
        "clearance",
        "overload",
        "revs",
        "points",
        "rpm",
        "moment",
    ],
)
def test_bad_input_exit_2_one_line(args, needle, capsys, tmp_path):
    out = tmp_path / "never.json"
    with pytest.raises(SystemExit) as exc:
        main([*BASE, *args, "-o", str(out), "--json"])
    cap = capsys.readouterr()
    assert exc.value.code == 2
    assert cap.out == ""
    lines = cap.err.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("error: "), cap.err
    assert needle in lines[0], lines[0]
    assert not out.exists() and not list(tmp_path.iterdir())


def test_reproduce_section_qs5(run_cli, tmp_path):
    r = run_cli("reproduce", "--quick", "--section", "qs5", "-o", tmp_path, "--json")
    assert r.code == 0, r.err
    rows = json.loads((tmp_path / "results.json").read_text())
    assert rows and all(row["section"] == "qs5" for row in rows)
    bad = [row["quantity"] for row in rows if row["status"] == "mismatch"]
    assert not bad, bad
    for name in ("outer", "outer_err", "inner", "inner_err"):
        assert (tmp_path / f"qs5_{name}.png").stat().st_size > 1000


def test_a_constant_stiffness_lists_no_dominant_orders(run_cli):
    """A centred axial load loads every ball alike: the stiffness is constant and its spectrum
    is round-off, which is not listed as 'dominant orders' (exploratory testing: three unlabelled
    orders with relative amplitude 0 were printed)."""
    r = run_cli("stiffness", "6205", "--fz-n", "100", "--json")
    assert r.code == 0, r.err
    for name in ("radial", "axial", "tilt"):
        assert r.json()["fluctuation"][name]["components"] == []
    t = run_cli("stiffness", "6205", "--fz-n", "100")
    assert "none (constant to 1e-8 of the mean)" in t.out


def test_a_stiffness_run_beyond_the_memory_budget_is_refused_before_any_work(run_cli, tmp_path):
    """10000 cage revolutions x 3600 points (each option in its range) need ~40 GB: refused in
    one line naming the estimate and the budget, nothing written (exploratory testing: a
    traceback from NumPy after allocating). --max-memory-gb sets the budget."""
    out = tmp_path / "k.nc"
    r = run_cli("stiffness", "6205", "--fy-n", "500", "--cage-revs", "10000",
                "--points-per-rev", "3600", "-o", out)  # fmt: skip
    r.refused("stiffness: 10000 cage revolutions x 3600 points", "exceeds the memory budget")
    assert not out.exists()
    r = run_cli("stiffness", "6205", "--fy-n", "500", "--max-memory-gb", "1e-6")
    r.refused("estimated memory", "max_memory")


@pytest.mark.parametrize("extra", [[], ["--clearance-m", "0"], ["--my-n-m", "-4"]])
def test_a_moment_alone_is_solved(run_cli, extra):
    """A moment without a force (exploratory testing: 'no equilibrium found ... relative
    residual nan' — Newton started untilted, where a ring with clearance touches no ball). The
    ring tilts along the moment: theta_x > 0 for M_x > 0, by a few mrad (a plausibility window,
    no published number: the tilt that takes up the clearance and deflects the balls), with a
    finite positive radial stiffness; with a preload the result is the one the untilted start
    gave before (theta_x 0.003767 rad, checked by hand)."""
    r = run_cli("stiffness", "6205", "--mx-n-m", "5", *extra, "--json")
    assert r.code == 0, r.err
    u = r.json()["displacement"]
    assert 1e-3 < u["theta_x_rad"] < 1e-2
    k = r.json()["fluctuation"]["radial"]["mean"]
    assert math.isfinite(k) and k > 0


@pytest.mark.parametrize("method", ["jones", "iso16281"])
def test_a_moment_that_overloads_a_ball_is_refused(run_cli, method):
    """1000 N m on a 6205 loads one ball with ~20 kN, 3.9 Q_0 (the ISO 76 element limit,
    5201 N here): refused in one line naming the largest ball load and the limit, unless
    --allow-overload, which warns; 200 N m (5.5 kN, just above Q_0) warns and runs
    (exploratory testing: the moment passed the check of the forces unseen)."""
    base = ["stiffness", "6205", "--fz-n", "100", "--method", method]
    run_cli(*base, "--mx-n-m", "1000").refused("largest ball load under the moment", "Q0")
    r = run_cli(*base, "--mx-n-m", "1000", "--allow-overload", "--json")
    assert r.code == 0 and "exceeds the element load" in r.err
    r = run_cli(*base, "--mx-n-m", "200", "--json")
    assert r.code == 0 and "warning: largest ball load under the moment" in r.err


def test_the_file_records_the_material_the_stiffness_was_computed_with(run_cli, tmp_path):
    # twenty-first session: `stiffness 6205 --E-pa 100e9 --nu 0.25 -o f.nc` recorded the
    # catalogue id alone; E and nu were nowhere in the file, only their effect on k
    out = tmp_path / "soft.nc"
    r = run_cli(*BASE, "--E-pa", "100e9", "--nu", "0.25", "-o", out, "--json")
    assert r.code == 0, r.err
    g = StiffnessResult.load(out).solution.geometry
    assert (g.youngs_modulus, g.poisson_ratio) == (100e9, 0.25)
