"""Issue 14 (quasi-static solver messages and angle ranges): tiny loads and heavy preload converge
(the convergence test knows the round-off floor of the contact forces), zero load with zero
clearance is refused (Hertz contacts have no stiffness at zero deflection), and every angle of
``load`` and ``stiffness`` has a meaningful range."""

from __future__ import annotations

import math

import numpy as np
import pytest
from numpy.testing import assert_allclose

from bearingsim.catalog import get_bearing
from bearingsim.errors import ConfigError
from bearingsim.load_distribution import MAX_ANGLE_RAD, radial_load_distribution
from bearingsim.quasistatic import (
    Misalignment,
    qs_geometry,
    run_iso16281,
    run_quasi_static,
    solve_equilibrium,
)

B6205, B6206 = get_bearing("6205"), get_bearing("6206")
CAGE = 2 * np.pi * np.arange(36) / 36


def one_line_error(r) -> str:
    assert r.code == 2, (r.code, r.out, r.err)
    lines = r.err.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("error: "), r.err
    return lines[0]


# ------------------------------------------------------------------ no false "no equilibrium"
def test_tiny_load_converges_with_the_single_ball_stiffness():
    """Issue 14: ``stiffness --fy 0.01`` reported "no equilibrium" at a relative residual of
    2e-12. At cage angle 0 one ball (on the load line, inside the 6 um clearance) carries the
    whole load: ``k_yy = dQ/d delta = 1.5 K^(2/3) F^(1/3)`` (Hertz, ``Q = K delta^1.5``)."""
    F = 0.01
    s = solve_equilibrium(B6205, fy=F)
    K = qs_geometry(B6205).k
    assert_allclose(s.stiffness_matrix.at(0).values[1][1], 1.5 * K ** (2 / 3) * F ** (1 / 3), 1e-9)
    assert_allclose(s.reaction[0, 1], F, rtol=1e-9, err_msg="force balance")
    for b, f in ((B6205, 0.01), (B6205, 1e-6), (B6206, 0.01)):
        sol = run_quasi_static(b, CAGE, 0.0, f)
        assert np.all(sol.residual < 1e-8) and np.all(sol.stiffness_matrix.stack[:, 1, 1] > 0)
        assert_allclose(sol.reaction[:, 1], f, rtol=1e-8, err_msg=f"{b.id} force balance")


def test_heavy_preload_converges_to_the_equal_ball_loads():
    """Issue 14: heavy preload reported "no equilibrium". With no load and a preload ``P_d``
    every ball carries ``Q = K (-P_d/2)^1.5`` and ``k_yy = sum 1.5 K delta^0.5 cos^2 psi_j =
    1.5 K delta^0.5 Z/2`` (equal spacing)."""
    pd = -50e-6
    K = qs_geometry(B6205, pd).k
    d = -0.5 * pd
    s = run_quasi_static(B6205, CAGE, clearance=pd)
    assert_allclose(s.ball_loads, K * d**1.5, rtol=1e-9, err_msg="preload ball load")
    assert_allclose(s.stiffness_matrix.stack[:, 1, 1], 1.5 * K * math.sqrt(d) * 9 / 2, rtol=1e-9)
    assert np.all(s.residual <= 1e-12)
    for kw in (dict(fy=1.0), dict(fz=1.0), dict(fy=0.01)):
        sol = run_quasi_static(B6205, CAGE, clearance=pd, **kw)
        assert np.all(sol.residual < 1e-8)
        iso = run_iso16281(B6205, CAGE, clearance=pd, **kw)
        assert np.all(iso.residual < 1e-8)


def test_cli_tiny_load_and_preload(run_cli):
    base = ["stiffness", "6205", "--cage-revs", "1", "--points-per-rev", "36", "--json"]
    for extra in (["--fy-n", "0.01"], ["--clearance-m", "-5e-5"], ["--fy-n", "1e-3"]):
        r = run_cli(*base, *extra)
        assert r.code == 0, r.err
        assert r.json()["k_radial_mean"] > 0 and r.err == ""


def test_zero_load_zero_clearance_refused():
    """Issue 14: zero load with zero clearance returned an all-zero stiffness matrix with exit
    0. Every ball just touches: the ring is held, but ``dQ/d delta = 1.5 K delta^0.5 = 0``."""
    for run in (run_quasi_static, run_iso16281):
        with pytest.raises(ConfigError, match="no stiffness at zero deflection") as ei:
            run(B6206, 0.0)
        assert "valid: |F| > 0" in str(ei.value) and "clearance_m < 0" in str(ei.value)
    # a preload or a misalignment holds it: a stiffness, no error
    assert solve_equilibrium(B6206, clearance=-1e-6).stiffness_matrix.at(0).values[1][1] > 0
    tilted = run_quasi_static(B6206, 0.0, misalignment=Misalignment(inner_tilt=1e-4))
    assert tilted.ball_loads.max() > 0 and tilted.residual[0] <= 1e-12


def test_cli_zero_load_zero_clearance(run_cli, tmp_path):
    out = tmp_path / "k.nc"
    line = one_line_error(run_cli("stiffness", "6206", "--cage-revs", "1", "-o", out))
    assert "no stiffness at zero deflection" in line and not out.exists()


def test_negligible_load_with_clearance_refused(run_cli):
    """Issue 14 sweep: ``stiffness --fy-n 1e-300`` gave an all-zero stiffness and NaN relative
    fluctuations with exit 0 (the Hertz deflection 1e-206 m vanishes beside the 6 um clearance);
    1e-30 N "too few balls hold the ring". Below a deflection of 1e-12 of the clearance the load
    is refused like a zero load; 1e-15 N (deflection 2e-17 m) still runs."""
    K = qs_geometry(B6205).k
    f_min = K * (1e-12 * 6e-6) ** 1.5
    for run in (run_quasi_static, run_iso16281):
        with pytest.raises(ConfigError, match="ring position is undetermined") as ei:
            run(B6205, 0.0, 0.0, 1e-300)
        assert f"valid: |F| >= {f_min:.3g} N" in str(ei.value)
    with pytest.raises(ConfigError, match=r"load = 5.12821e-299 N \(largest force, or moment"):
        run_quasi_static(B6205, 0.0, my=1e-300)  # a moment over the pitch radius 19.5 mm
    base = ["stiffness", "6205", "--cage-revs", "1", "--points-per-rev", "36", "--json"]
    line = one_line_error(run_cli(*base, "--fy-n", "1e-300"))
    assert line.startswith("error: load = 1e-300 N (largest force, or moment / pitch radius)")
    r = run_cli(*base, "--fy-n", "1e-15")
    assert r.code == 0, r.err
    fl = r.json()["fluctuation"]
    assert all(math.isfinite(fl[k]["peak_to_peak_rel"]) for k in ("radial", "axial", "tilt"))


# ---------------------------------------------------------------------------------- angles
def test_load_cage_angle_range(run_cli):
    """Issue 14: ``load --cage-angle-deg 1e30`` gave delta_max 9.8e54 m."""
    line = one_line_error(run_cli("load", "6205", "--fy-n", "100", "--cage-angle-deg", "1e30"))
    assert "cage_angle_deg = 1e+30 deg is out of range; valid range [-360, 360] deg" in line
    r = run_cli("load", "6205", "--fy-n", "100", "--cage-angle-deg", "-360", "--json")
    assert r.code == 0 and r.json()["delta_max_m"] < 1e-4
    with pytest.raises(ConfigError, match="cage_angle_rad = 1e\\+30 rad is out of range"):
        radial_load_distribution(B6205, 0.0, 100.0, 1e30)
    with pytest.raises(ConfigError, match=r"cage_angle_rad\[1\] = inf is not finite"):
        radial_load_distribution(B6205, 0.0, 100.0, [0.0, np.inf])
    radial_load_distribution(B6205, 0.0, 100.0, [-MAX_ANGLE_RAD, MAX_ANGLE_RAD])
    with pytest.raises(ConfigError, match="first_element_angle_rad"):
        radial_load_distribution(B6205, 0.0, 100.0, first_element_angle=100.0)


@pytest.mark.parametrize(
    "args, needle",
    [
        (["--outer-tilt-azimuth-deg", "1e30"], "outer_tilt_azimuth_deg = 1e+30 deg is out"),
        (["--inner-tilt-azimuth-deg", "720.5"], "inner_tilt_azimuth_deg = 720.5 deg is out"),
        # the tilt magnitudes were already checked against the geometry: 1e30 too
        (["--outer-tilt-deg", "1e30"], "is beyond what the clearance and groove geometry allow"),
        (["--inner-tilt-deg", "1e30"], "is beyond what the clearance and groove geometry allow"),
        (["--ball-errors-deg", ",".join(["1e30"] * 9)], "ball_errors_rad[0] = 1.74533e+28 rad"),
        (["--ball-errors-deg", ",".join(["50"] * 9)], "valid range [-0.698132, 0.698132] rad"),
    ],
    ids=["outer-azimuth", "inner-azimuth", "outer-tilt", "inner-tilt", "errors-1e30", "errors"],
)
def test_stiffness_angle_ranges(run_cli, args, needle):
    r = run_cli("stiffness", "6205", "--fy-n", "500", "--cage-revs", "1", *args)
    assert needle in one_line_error(r)


def test_library_angle_ranges():
    with pytest.raises(ConfigError, match="outer_tilt_azimuth_rad = 7 rad is out of range"):
        Misalignment(outer_tilt=1e-4, outer_azimuth=7.0)
    with pytest.raises(ConfigError, match="first_ball_angle_rad"):
        solve_equilibrium(B6205, fy=100.0, first_ball_angle=1e30)
    with pytest.raises(ConfigError, match="cage_angle_rad = 1e\\+30 rad"):
        run_quasi_static(B6205, 1e30, 0.0, 100.0)


def test_vsm_trace_first_ball_angle(run_cli):
    line = one_line_error(run_cli("vsm-trace", "--first-ball-deg", "1e30", "--json"))
    assert "first_ball_deg = 1e+30 deg is out of range; valid range [-360, 360]" in line


def test_centrifugal_force_against_the_static_limit(run_cli):
    """``stiffness --rpm 1e30 --centrifugal`` blamed the load ("contact angle 180 deg; reduce
    the load"): the balls' centrifugal force is checked against the ISO 76 element limit."""
    line = one_line_error(
        run_cli("stiffness", "6205", "--fy-n", "500", "--rpm", "1e30", "--centrifugal")
    )
    assert "ball centrifugal force F_c = " in line and "static stress limit Q0" in line
    assert "--allow-overload" in line
