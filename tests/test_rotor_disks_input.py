"""Disk input of the rotor model (``simulate --model rotor``): a disk count that makes a beam mesh
too large for the dense reduction is refused before anything is built; the automatic RK4 step
stays stable for every accepted disk count (the overdamped high rotor modes of the
stiffness-proportional damping); ``disks`` and ``disk_positions_mm`` must agree, and the
positions must increase; an unknown bearing id names its key."""

from __future__ import annotations

import time

import numpy as np
import pytest

from bearingsim.config import Scenario
from bearingsim.dynamics.budget import Budget
from bearingsim.dynamics.rotor import model as rotor_model
from bearingsim.dynamics.rotor.config import Armature, cwru_rotor_config
from bearingsim.errors import ConfigError

#: a memory budget any mesh below the DOF limit fits in (1 TB): the refusals tested here must not
#: depend on the memory the machine has available
BIG = Budget(max_memory=1e12)
#: a short rotor run: 0.002 s at 12 kHz (24 samples)
SHORT = ["simulate", "--model", "rotor", "--duration-s", "0.002", "--fs-hz", "12000"]


@pytest.fixture
def no_build(monkeypatch):
    """Building the reduced rotor fails the test: a refusal must come before it."""

    def built(*args, **kw):
        raise AssertionError("the rotor model was built before the refusal")

    monkeypatch.setattr(rotor_model, "build_rotor", built)


# ----------------------------------------------------------------------- 1. many disks


def test_1000_disks_refused_before_building(run_cli, tmp_path, no_build):
    """``--disks 1000 --duration-s 0.001 --json`` ran > 2 min and past 1.7 GB building a 4008-DOF
    dense model; now refused at once naming disks, its value and the range (248 equally spaced
    disks: 4 (248 + 2) = 1000 DOFs, MAX_FE_DOF)."""
    out = tmp_path / "d.nc"
    t0 = time.perf_counter()
    # a memory budget the 5.1 GB dense mesh fits in: the refusal must not depend on the machine
    r = run_cli("simulate", "--model", "rotor", "--disks", "1000", "--duration-s", "0.001",
                "--max-memory-gb", "1000", "-o", out, "--json")  # fmt: skip
    r.refused("disks = 1000 ", "4008 DOFs", "valid range [1, 248]", "distributed")
    assert time.perf_counter() - t0 < 10.0
    assert r.out == "" and not out.exists()


def test_disk_limit_is_the_mesh_size():
    """248 equally spaced disks make a 1000-DOF mesh (accepted), 249 one of 1004 (refused); the
    Python API names the RotorConfig field n_disks."""
    assert rotor_model.MAX_FE_DOF == 1000
    assert rotor_model.check_fe_size(cwru_rotor_config(248)) == 1000
    with pytest.raises(ConfigError) as ei:
        rotor_model.check_fe_size(cwru_rotor_config(249))
    msg = str(ei.value)
    assert msg.startswith("n_disks = 249 makes a beam mesh of 250 elements, 1004 DOFs")
    assert "valid range [1, 248]" in msg and "\n" not in msg


def test_python_api_refuses_before_building(no_build):
    with pytest.raises(ConfigError, match=r"n_disks = 1000 .* valid range \[1, 248\]"):
        rotor_model.simulate_rotor(cwru_rotor_config(1000), duration=0.001, budget=BIG)


def test_many_elements_refused_naming_n_elements(run_cli, tmp_path, no_build):
    """--elements 400 with the 9 default disks (1604 DOFs) was built for seconds; the range is
    the largest element count whose mesh keeps 1000 DOFs (10 intervals of 24: 241 nodes)."""
    r = run_cli(*SHORT, "--elements", "400", "-o", tmp_path / "e.nc")
    r.refused("n_elements = 400 ", "1604 DOFs", "valid range [10, 240]")


# ------------------------------------------------------------------ 2. the automatic step


def _rk4_growth(plan) -> float:
    """Largest RK4 amplification ``|R(lambda h)|`` over the eigenvalues of the plan's reduced,
    damped, gyroscopic rotor (free ends), at the step the plan chose [-]."""
    rot = plan.model.rotor
    n = rot.n
    omega = 2 * np.pi * 1750.0 / 60.0
    a = np.zeros((2 * n, 2 * n))
    a[:n, n:] = np.eye(n)
    a[n:, :n] = -np.linalg.solve(rot.M, rot.K)
    a[n:, n:] = -np.linalg.solve(rot.M, rot.C + omega * rot.G)
    h = 1.0 / (plan.q * plan.fs * plan.decim)
    z = np.linalg.eigvals(a) * h
    return float(np.max(np.abs(1 + z + z**2 / 2 + z**3 / 6 + z**4 / 24)))


@pytest.mark.parametrize("disks", [12, 15, 20, 40])
def test_automatic_step_is_stable_for_the_rotor_modes(disks):
    """Stiffness-proportional damping puts a rotor mode w at -beta w^2 once overdamped (|lambda|
    2.5e6 1/s with 20 disks at 48 kHz); the step from the undamped frequencies (5.2 us) made the
    RK4 amplification up to 1.5e3 a step. Now every rotor eigenvalue lies in RK4's stability
    region."""
    plan = rotor_model.plan_rotor(cwru_rotor_config(disks), duration=0.001, sample_rate=48000.0)
    # 1e-6: the free rotor's rigid-body eigenvalues are zero to rounding (R = 1 + z there)
    assert _rk4_growth(plan) <= 1.0 + 1e-6


def test_15_disks_run_with_the_automatic_step(run_cli, tmp_path):
    """``--disks 15 --duration-s 0.005`` diverged at t = 3.1e-05 s with dt = 5.21e-06 s."""
    out = tmp_path / "dn.nc"
    r = run_cli("simulate", "--model", "rotor", "--disks", "15", "--duration-s", "0.002",
                "-o", out, "--json")  # fmt: skip
    assert r.code == 0, r.err
    js = r.json()
    assert js["n_samples"] == 96 and np.isfinite(js["rms_acc_y"]) and js["rms_acc_y"] < 1.0


# ------------------------------------------------------------ 3. disks and their positions


def test_disks_and_positions_disagree_cli(run_cli, tmp_path):
    """``--disks 3 --disk-positions-mm 1,2`` exited 0, storing disks = 3 for a 2-disk model."""
    out = tmp_path / "dp.nc"
    r = run_cli(*SHORT, "--disks", "3", "--disk-positions-mm", "1,2", "-o", out)
    r.refused("disks = 3 and disk_positions_mm = [1, 2] (2 positions) disagree",
             "disks = 2")  # fmt: skip
    assert not out.exists()


def test_disks_and_positions_disagree_scenario_and_rotor_modes(run_cli):
    with pytest.raises(ConfigError, match=r"disks = 3 and disk_positions_mm = \[60, 140\]"):
        Scenario(model="rotor", disks=3, disk_positions_mm=(60.0, 140.0))
    r = run_cli("rotor-modes", "--disks", "3", "--disk-positions-mm", "50,100")
    r.refused("disks = 3 and disk_positions_mm = [50,100] (2 positions) disagree")
    with pytest.raises(ConfigError) as ei:
        Armature(n_disks=3, positions=(0.05, 0.1))
    assert str(ei.value) == (
        "n_disks = 3 and disk_positions_m = (0.05, 0.1) m (2 positions) disagree; valid: one "
        "position per disk (n_disks = 2 for these positions)"
    )


def test_unset_disks_follow_the_positions(run_cli, tmp_path):
    """Positions alone set the disk count; the stored scenario no longer says 9 disks for a
    2-disk model (disks stays unset, None, and follows new positions)."""
    sc = Scenario(model="rotor", disk_positions_mm=(60.0, 140.0))
    assert sc.disks == 2 and sc.to_dict()["disks"] is None
    assert Scenario.from_dict(sc.to_dict()) == sc
    assert sc.replace(disk_positions_mm=(50.0, 100.0, 150.0)).disks == 3
    assert sc.replace(disk_positions_mm=None).disks == 9
    given = Scenario(model="rotor", disks=2, disk_positions_mm=(60.0, 140.0))
    assert given.to_dict()["disks"] == 2
    out = tmp_path / "p.nc"
    r = run_cli(*SHORT, "--disk-positions-mm", "60,140", "-o", out, "--json")
    assert r.code == 0, r.err
    from bearingsim.results import SimulationResult

    res = SimulationResult.load(out)
    assert res.scenario["disks"] is None
    assert res.meta["rotor"]["inputs"]["armature"]["n_disks"] == 2


@pytest.mark.parametrize(
    "positions, needle",
    [
        ("100,50", "disk_positions_m = (0.1, 0.05) m is not strictly increasing (0.05 m follows "
         "0.1 m); valid: distinct positions in increasing order within (0, 0.2032) m"),
        ("50,50", "disk_positions_m = (0.05, 0.05) m is not strictly increasing (0.05 m follows "
         "0.05 m)"),
        ("150,50,100", "(0.05 m follows 0.15 m)"),
    ],
    ids=["decreasing", "duplicate", "unordered"],
)  # fmt: skip
def test_positions_must_increase(run_cli, tmp_path, positions, needle, no_build):
    r = run_cli(*SHORT, "--disk-positions-mm", positions, "-o", tmp_path / "o.nc")
    r.refused(needle)


# ----------------------------------------------------------------------------- 4. bearing id


@pytest.mark.parametrize("end", ["de", "fe"])
def test_unknown_bearing_names_its_key(run_cli, tmp_path, end):
    r = run_cli(*SHORT, f"--{end}-bearing", "nosuch", "-o", tmp_path / "b.nc")
    r.refused(f"{end}_bearing = 'nosuch' is not in the catalogue; valid: ")
    with pytest.raises(ConfigError, match=f"^{end}_bearing = 'nosuch' is not in the catalogue"):
        cwru_rotor_config(**{f"{end}_bearing": "nosuch"})
