"""Issue 14, item 1 (load against the bearing's capacity): every model checks the load against
the static capacity C0 of ISO 76 before it runs — a warning above C0, refused above 2 C0 unless
``--allow-overload`` / ``allow_overload=True`` (``bearingsim.contact.capacity``)."""

from __future__ import annotations

import math
import warnings

import numpy as np
import pytest
from numpy.testing import assert_allclose

from bearingsim.catalog import get_bearing
from bearingsim.contact.capacity import (
    STATIC_LIMIT_FACTOR,
    StaticCapacityWarning,
    check_element_load,
    check_load,
    equivalent_static_load,
    static_capacity,
)
from bearingsim.contact.hertz import ball_contact
from bearingsim.errors import ConfigError
from bearingsim.geometry import Race
from bearingsim.load_distribution import radial_load_distribution
from bearingsim.quasistatic import run_iso16281, run_quasi_static, stiffness_vs_cage

B6205, B6206 = get_bearing("6205"), get_bearing("6206")
C0_6205, C0_6206 = static_capacity(B6205).c0, static_capacity(B6206).c0


def one_line_error(r) -> str:
    assert r.code == 2, (r.code, r.out, r.err)
    lines = r.err.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("error: "), r.err
    assert r.out == ""
    return lines[0]


def test_capacity_lives_below_the_model_families():
    """The life family re-exports the same capacity (its check and messages are unchanged)."""
    from bearingsim.life import iso281

    assert iso281.static_capacity is static_capacity
    assert iso281.StaticCapacityWarning is StaticCapacityWarning
    sc = static_capacity(B6206)
    # Q0 reaches the ISO 76 stress on the inner raceway; C0 = Q0 Z cos(alpha) / 5 (Stribeck)
    assert_allclose(float(ball_contact(B6206, sc.element_load, Race.INNER).p_max), 4200e6, 1e-12)
    assert_allclose(sc.c0, sc.element_load * 9 / 5.0, rtol=1e-12)


@pytest.mark.parametrize(
    "alpha_deg, fr, fa, p0",
    [
        (0.0, 1000.0, 0.0, 1000.0),  # pure radial: P0 = F_r
        (0.0, 1000.0, 500.0, 1000.0),  # 0.6 Fr + 0.5 Fa = 850 < Fr: P0 = F_r (ISO 76 §6.1)
        (0.0, 1000.0, 2000.0, 1600.0),  # X0 = 0.6, Y0 = 0.5 (radial-contact ball bearings)
        (0.0, 0.0, 2000.0, 1000.0),
        (25.0, 1000.0, 2000.0, 0.5 * 1000.0 + 0.38 * 2000.0),  # ISO 76 table 1, alpha 25 deg
        (40.0, 1000.0, 3000.0, 0.5 * 1000.0 + 0.26 * 3000.0),  # alpha 40 deg
    ],
)
def test_equivalent_static_load_iso76(alpha_deg, fr, fa, p0):
    from dataclasses import replace

    b = replace(B6205, contact_angle=math.radians(alpha_deg))
    assert_allclose(equivalent_static_load(b, fr, fa), p0, rtol=1e-12, err_msg="vs ISO 76 §6.1")
    nu = get_bearing("NU204-ECP")
    assert equivalent_static_load(nu, fr, fa) == fr  # cylindrical roller: radial only


def test_check_load_bands():
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        assert check_load(B6205, 0.99 * C0_6205).c0 == C0_6205  # below C0: silent
        assert check_load(B6205, 1e9, None) is None  # None: the caller has checked
    with pytest.warns(StaticCapacityWarning, match="exceeds the static capacity C0"):
        check_load(B6205, 1.5 * C0_6205)
    with pytest.raises(ConfigError) as ei:
        check_load(B6205, 2.01 * C0_6205)
    msg = str(ei.value)
    assert f"{STATIC_LIMIT_FACTOR:g} x the static capacity C0 = {C0_6205:.6g} N of 6205" in msg
    assert f"valid range [0, {2 * C0_6205:.6g}] N" in msg and "--allow-overload" in msg
    with pytest.warns(StaticCapacityWarning):
        check_load(B6205, 100 * C0_6205, allow_overload=True)
    with pytest.raises(ConfigError, match="P0 = 0.6 F_r \\+ 0.5 F_a"):
        check_load(B6205, 100.0, axial_load=5 * C0_6205, axial_name="fz_n")
    q0 = static_capacity(B6205).element_load
    with pytest.raises(ConfigError, match="ball_load_n = .* Q0 = "):
        check_element_load(B6205, 2.5 * q0)
    with pytest.warns(StaticCapacityWarning, match="static stress limit"):
        check_element_load(B6205, 1.5 * q0)


@pytest.mark.parametrize(
    "run",
    [
        lambda b, f, **k: radial_load_distribution(b, 0.0, f, **k),
        lambda b, f, **k: run_quasi_static(b, 0.0, 0.0, f, **k),
        lambda b, f, **k: run_iso16281(b, 0.0, 0.0, f, **k),
        lambda b, f, **k: stiffness_vs_cage(b, 0.0, f, cage_revs=1, points_per_rev=36, **k),
    ],
    ids=["load_distribution", "jones", "iso16281", "stiffness_vs_cage"],
)
def test_library_functions_check_before_they_run(run):
    """Issue 14: 'simulate, contact, load, stiffness and vsm-trace accept 50 kN and 1 MN'."""
    for f in (50e3, 1e6):
        with pytest.raises(ConfigError, match=r"exceeds 2 x the static capacity"):
            run(B6205, f)
    with pytest.warns(StaticCapacityWarning):
        run(B6205, 1.2 * C0_6205)
    with pytest.warns(StaticCapacityWarning):
        run(B6205, 2.5 * C0_6205, allow_overload=True)


def test_vsm_stiffness_trace_checks():
    from bearingsim.config import Scenario
    from bearingsim.dynamics.ring.scenario import model_inputs
    from bearingsim.dynamics.ring.trace import stiffness_trace

    inputs = model_inputs(Scenario(model="vsm", fy_n=50e3, fx_n=0.0))
    with pytest.raises(ConfigError, match=r"\|\(fx_n, fy_n\)\| = 50000 N exceeds 2 x"):
        stiffness_trace(inputs, np.linspace(0.0, 0.1, 3))


# --------------------------------------------------------------------------------- the CLI
def test_contact_1mn_refused_and_allowed(run_cli):
    """Issue 14: ``contact 6206 --radial-load 1e6`` gave p_max 16.9 GPa, 0.63 mm approach."""
    line = one_line_error(run_cli("contact", "6206", "--radial-load-n", "1e6"))
    assert f"radial_load_n = 1e+06 N exceeds 2 x the static capacity C0 = {C0_6206:.6g}" in line
    assert "valid range [0, " in line and "--allow-overload" in line
    r = run_cli("contact", "6206", "--radial-load-n", "1e6", "--allow-overload", "--json")
    assert r.code == 0
    assert r.err.count("\n") == 1 and r.err.startswith("warning: radial_load_n = 1e+06 N")
    assert r.json()["inner"]["p_max_pa"] > 16e9  # what the issue saw, now with a warning


def test_contact_ball_load(run_cli):
    q0 = static_capacity(B6205).element_load
    line = one_line_error(run_cli("contact", "6205", "--ball-load-n", f"{3 * q0:.0f}"))
    assert "ball_load_n = " in line and "static stress limit" in line
    r = run_cli("contact", "6205", "--ball-load-n", f"{1.5 * q0:.0f}", "--json")
    assert r.code == 0 and r.err.startswith("warning: ball_load_n") and r.json()["ball_load_n"]


@pytest.mark.parametrize(
    "args",
    [
        ["load", "6205", "--fy-n", "50000"],
        ["load", "6206", "--fx-n", "1e6"],
        ["stiffness", "6205", "--fy-n", "50000", "--cage-revs", "1"],
        ["stiffness", "6206", "--fz-n", "1e6", "--cage-revs", "1"],
        ["vsm-trace", "--fy-n", "50000", "--json"],
        ["vsm-trace", "--bearing", "6205", "--fy-n", "1e6", "--json"],
    ],
    ids=lambda a: "-".join(a[:3]),
)
def test_commands_refuse_beyond_twice_c0(run_cli, tmp_path, args):
    out = tmp_path / "never"
    extra = ["-o", str(out)] if args[0] in ("stiffness", "vsm-trace") else []
    line = one_line_error(run_cli(*args, *extra))
    assert "exceeds 2 x the static capacity C0" in line and "--allow-overload" in line
    assert not out.exists()


@pytest.mark.parametrize("cmd", ["load", "stiffness", "vsm-trace"])
def test_commands_warn_between_c0_and_twice_c0(run_cli, cmd):
    f = f"{1.3 * C0_6205:.0f}"
    args = {
        "load": ["load", "6205", "--fy-n", f],
        "stiffness": ["stiffness", "6205", "--fy-n", f, "--cage-revs", "1"],
        "vsm-trace": ["vsm-trace", "--fy-n", f, "--fx-n", "0", "--cage-revs", "0.1"],
    }[cmd]
    r = run_cli(*args, "--json")
    assert r.code == 0, r.err
    assert r.err.count("\n") == 1 and r.err.startswith("warning: |(fx_n, fy_n)| = "), r.err
    assert "exceeds the static capacity C0" in r.err
    assert isinstance(r.json(), dict)  # stdout: one JSON object
    # beyond 2 C0 with --allow-overload: it runs, with the warning
    over = f"{2.5 * C0_6205:.0f}"
    r = run_cli(*[over if a == f else a for a in args], "--allow-overload", "--json")
    assert r.code == 0, r.err
    assert r.err.startswith("warning: ") and "exceeds the static capacity" in r.err
