"""``bearingsim vsm-trace`` and :func:`bearingsim.dynamics.ring.trace.stiffness_trace` refuse
what they cannot trace in one line: a zero radial load (with the rule of the model), a ball
constant outside the Hertz constants of real bearings, a static balance that did not converge;
``--ball`` without ``--plot``; stiffness columns and keys named by their unit N/m."""

from __future__ import annotations

import csv
import json
import math
from dataclasses import replace

import numpy as np
import pytest
from numpy.testing import assert_allclose

from bearingsim import get_bearing
from bearingsim.contact.hertz import ball_stiffness
from bearingsim.dynamics.ring.base import ModelInputs
from bearingsim.dynamics.ring.trace import (
    STIFFNESS_RANGE,
    TRACE_RESIDUAL_TOL,
    stiffness_trace,
)
from bearingsim.errors import ConfigError, SolverError
from bearingsim.geometry import BallBearing
from bearingsim.materials import Material

B6205 = get_bearing("6205")
#: seed VSM table 1 loads and speed (the command's defaults)
FX, FY, SHAFT = 10.0, 50.0, 1750.0 / 60.0
CAGE = np.radians(np.linspace(0.0, 36.0, 721))
SHORT = ["--cage-revs", "0.1"]


# ------------------------------------------------------------------------------ zero load
def test_zero_radial_load_with_clearance_names_fx_fy(run_cli, tmp_path):
    """--fx-n 0 --fy-n 0 said 'unbalance_n = 0 N is out of range; valid range [0, 0) N'."""
    out = tmp_path / "v0.csv"
    r = run_cli("vsm-trace", "--fx-n", "0", "--fy-n", "0", "-o", out)
    r.refused("radial load |(fx_n, fy_n)| = 0 N (fx_n = 0 N, fy_n = 0 N)",
                    "clearance_m = 6e-06 m > 0", "undetermined",
                    "valid range |(fx_n, fy_n)| > 0 N")  # fmt: skip
    assert not out.exists()


def test_zero_radial_load_without_clearance_has_no_stiffness(run_cli, tmp_path):
    """P_d = 0: every ball touches unloaded; the secant stiffness of a Hertz contact, K delta^0.5,
    vanishes with the load. Analytic limit: at P_d = 0 every contact deflects as
    (Q/K)^(2/3), so the trace's secant stiffness scales as F^(1/3) (1000 times the load: 10
    times the stiffness) and is 0 at F = 0."""
    r = run_cli("vsm-trace", "--fx-n", "0", "--fy-n", "0", "--clearance-m", "0", "--json")
    r.refused("clearance_m = 0 m every ball touches unloaded",
                    "no stiffness to trace")  # fmt: skip
    k = [
        stiffness_trace(ModelInputs(B6205, 0.0, f, SHAFT, clearance=0.0), CAGE[:1]).k_load[0]
        for f in (0.05, 50.0)
    ]
    assert_allclose(k[0] / k[1], 1e-3 ** (1 / 3), rtol=1e-6, err_msg="Hertz: k ~ F^(1/3)")


def test_zero_radial_load_with_preload_names_the_clearance(run_cli, tmp_path):
    """With a preload a zero radial load is a valid state (ring centred, every ball loaded),
    but the VSM trace measures its secant stiffness from the concentric position: refused
    whatever the load, as with a radial load."""
    r = run_cli("vsm-trace", "--fx-n", "0", "--fy-n", "0", "--clearance-m", "-5e-6", "--json")
    r.refused("clearance_m = -5e-06 m (a preload)", "fx_n = fy_n = 0 N is a valid state",
                    "valid range [0, inf) m", "dem or tvsm")  # fmt: skip


# ------------------------------------------------------------------------------ stiffness
@pytest.mark.parametrize("k", ["1e25", "1e18", "1e-6", "1e7"])
def test_stiffness_outside_the_hertz_range_refused(run_cli, tmp_path, k):
    """1e25 wrote residual_max 0.36 (not converged), 1e-6 wrote ring displacements of 83 km;
    nothing is written now."""
    out = tmp_path / "v.csv"
    r = run_cli("vsm-trace", *SHORT, "-o", out, "--stiffness-n-per-m1.5", k, "--json")
    r.refused(f"stiffness_n_per_m1_5 = {float(k):g} N/m^1.5 is out of range",
                    "valid range [1e+08, 1e+12] N/m^1.5", "6205: 9.37e+09")  # fmt: skip
    assert not out.exists()


def _ball_bearing(d, f, mat):
    """A radial ball bearing of ball diameter ``d`` [m], groove radii ``f d``, pitch 5 d."""
    return BallBearing(
        id="x",
        n_elements=9,
        element_diameter=d,
        pitch_diameter=5 * d,
        inner_groove_radius=f * d,
        outer_groove_radius=f * d,
        material=mat,
    )


def test_stiffness_range_is_the_hertz_envelope_with_a_decade_of_margin():
    """The derivation of STIFFNESS_RANGE (trace.py): Hertz constants of steel and Si3N4 ball
    contacts (E, nu: bearing steel 207 GPa, 0.3, Harris & Kotzalas 2007; Si3N4 310 GPa, 0.26)
    from a 0.5 mm ball in 0.60 grooves to a 100 mm ball in 0.505 grooves; the seed VSM's fitted
    constant (its load zone psi_L = 68.2 deg, tests/test_vsm_trace.py::k_paper) inside."""
    steel = Material(207e9, 0.3, 7850.0)
    si3n4 = Material(310e9, 0.26, 3200.0, "silicon nitride")
    soft = ball_stiffness(_ball_bearing(0.5e-3, 0.60, steel))
    stiff = ball_stiffness(_ball_bearing(100e-3, 0.505, si3n4))
    assert_allclose([soft, stiff], [1.4e9, 8.0e10], rtol=0.03, err_msg="trace.py comment")
    lo, hi = STIFFNESS_RANGE
    assert lo * 10 <= soft and stiff * 10 <= hi
    assert lo < 2.587e9 < ball_stiffness(B6205) < hi
    # both ends of the range trace the seed case, converged
    for k in STIFFNESS_RANGE:
        tr = stiffness_trace(ModelInputs(B6205, FX, FY, SHAFT, stiffness=k), CAGE)
        assert tr.residual.max() < 1e-11, k


# ----------------------------------------------------------------------------- convergence
def test_unconverged_balance_refused(run_cli, tmp_path):
    """A load so small that the contact deflection is below what the ring position resolves
    (1 uN on the 6205: (F/K)^(2/3) = 2e-11 m against P_d/2 = 3 um) left a residual of 6e-3
    (~1e-12 converged) and was written; refused now, naming what to change."""
    msg = (
        r"did not converge: residual_max = .* above 1e-06.*"
        r"valid: a larger radial load or a smaller stiffness_n_per_m1_5"
    )
    with pytest.raises(SolverError, match=msg):
        stiffness_trace(ModelInputs(B6205, 0.0, 1e-6, SHAFT), CAGE)
    out = tmp_path / "v.csv"
    r = run_cli("vsm-trace", *SHORT, "--fx-n", "0", "--fy-n", "1e-6", "-o", out)
    r.refused("static balance of seed VSM eq. (16) did not converge")
    assert not out.exists()
    assert TRACE_RESIDUAL_TOL == 1e-6


def test_valid_traces_unchanged(run_cli, tmp_path):
    """The seed case and the report's fitted constant: converged at ~1e-12, far below the
    tolerance, and the command writes the library's numbers."""
    for kw in ({}, {"stiffness": 2.587e9}):
        tr = stiffness_trace(ModelInputs(B6205, FX, FY, SHAFT, **kw), CAGE)
        assert tr.residual.max() < 1e-11
    out = tmp_path / "v.csv"
    r = run_cli("vsm-trace", *SHORT, "-o", out, "--json")
    assert r.code == 0, r.err
    d = r.json()
    ref = stiffness_trace(ModelInputs(B6205, FX, FY, SHAFT), np.radians(np.linspace(0, 36, 721)))
    assert d["k_load_min_n_per_m"] == float(ref.k_load.min())
    assert d["residual_max"] == float(ref.residual.max())


# ---------------------------------------------------------------------------------- nits
def test_ball_without_plot_refused(run_cli, tmp_path):
    r = run_cli("vsm-trace", *SHORT, "--ball", "1", "-o", tmp_path / "v.csv")
    r.refused("ball = 1 is given without --plot", "valid: --ball with --plot PNG")
    assert not list(tmp_path.iterdir())


def test_stiffness_columns_and_keys_say_n_per_m(run_cli, tmp_path):
    """N/m is `_n_per_m` (docs/cli.md unit rule; `_n_m` reads N m); the JSON keeps the former
    keys for one release."""
    out = tmp_path / "v.csv"
    r = run_cli("vsm-trace", *SHORT, "-o", out, "--json")
    assert r.code == 0, r.err
    d = r.json()
    assert d["k_load_min_n_per_m"] == d["k_load_min_n_m"] > 0
    assert d["k_load_max_n_per_m"] == d["k_load_max_n_m"] >= d["k_load_min_n_per_m"]
    with open(out, encoding="utf-8") as fh:
        label = next(fh)  # the label line, with the inputs (twenty-first session)
        header = next(csv.reader(fh))
    inputs = json.loads(label.split("; inputs: ", 1)[1])
    assert inputs["bearing"]["id"] == "6205" and inputs["fy"] == 50.0
    for c in ("k_load_n_per_m", "k_x_n_per_m", "k_y_n_per_m", "k_xy_n_per_m", "k9_load_n_per_m"):
        assert c in header
    assert not [c for c in header if c.endswith("_n_m")]


def test_max_memory_help_has_one_pair_of_parentheses(run_cli):
    r = run_cli("vsm-trace", "--help")
    assert r.code == 0
    text = " ".join(r.out.split())
    assert "[default: (half the available memory)]" in text and "((" not in text


def test_library_refuses_the_override_too():
    with pytest.raises(ConfigError, match=r"stiffness_n_per_m1_5 = 1e\+25 N/m\^1.5"):
        stiffness_trace(ModelInputs(B6205, FX, FY, SHAFT, stiffness=1e25), CAGE)
    # the Hertz constant of a user bearing is not an override: a polymer 6205 traces
    soft = replace(B6205, material=Material(3e9, 0.35, 1400.0, "POM"))
    assert math.isclose(ball_stiffness(soft), 1.4e8, rel_tol=0.05)
    assert stiffness_trace(ModelInputs(soft, FX, FY, SHAFT), CAGE[:10]).residual.max() < 1e-11


def test_the_csv_records_one_drop_profile(run_cli, tmp_path):
    # twenty-first session: the inputs on the CSV's first line held "profile": "rectangular"
    # (the one in force) and, on the defect, "profile": "geometric" (the rotor's field)
    out = tmp_path / "o.csv"
    r = run_cli("vsm-trace", "--fault", "outer", "--fy-n", "500", "--cage-revs", "0.05", "-o", out)
    assert r.code == 0, r.err
    inputs = json.loads(out.read_text(encoding="utf-8").splitlines()[0].split("; inputs: ", 1)[1])
    assert inputs["profile"] == "rectangular" and "profile" not in inputs["defect"]
