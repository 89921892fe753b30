"""simulate(): scenario schema, result files, reproducibility, compiled kernels vs the SciPy
reference, divergence, and the ``bearingsim simulate`` command (including bad input)."""

from __future__ import annotations

import json
import math
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest
from dynamics_reference import Reference
from numpy.testing import assert_allclose

from bearingsim.config import Scenario
from bearingsim.dynamics.ring.scenario import model_inputs
from bearingsim.errors import ConfigError, SolverError
from bearingsim.results import SimulationResult
from bearingsim.simulation import simulate

#: seed VSM §2.5 / CWRU: 0.007 in outer defect at 1796 r/min, 0.014 in inner defect at 1748
OUTER = {"fault": "outer", "rpm": 1796.0, "defect_width_m": 1.778e-4}
INNER = {"fault": "inner", "rpm": 1748.0, "defect_width_m": 3.556e-4}


def test_scenario_defaults_are_seed_table1():
    sc = Scenario()
    assert (sc.bearing, sc.fx_n, sc.fy_n, sc.rpm, sc.damping_n_s_per_m) == (
        "6205",
        10.0,
        50.0,
        1750.0,
        300.0,
    )
    assert sc.resolved_mass_kg == 0.063 and sc.replace(fault="inner").resolved_mass_kg == 0.045


def test_scenario_toml_roundtrip_and_unknown_key(tmp_path):
    p = tmp_path / "s.toml"
    p.write_text('model = "dem"\nfault = "outer"\nrpm = 1796.0\nduration_s = 0.1\nseed = 3\n')
    sc = Scenario.from_toml(p)
    assert sc.model.value == "dem" and sc.seed == 3
    assert Scenario.from_dict(sc.to_dict()) == sc
    p.write_text("rpm = 1796.0\nspeed = 3\n")
    with pytest.raises(ConfigError, match="unknown key 'speed'; valid keys: model"):
        Scenario.from_toml(p)


@pytest.mark.parametrize(
    ("key", "value", "match"),
    [
        ("rpm", 0.0, "rpm = 0"),
        ("rpm", -5.0, "rpm = -5"),
        ("duration_s", 0.0, "duration_s = 0"),
        ("fs_hz", -1.0, "fs_hz"),
        ("defect_depth_m", 0.0, "defect_depth_m = 0"),
        ("model", "fem", "model = 'fem'"),
        ("fault", "cage", "fault = 'cage'"),
        ("retention_factor", 1.5, "retention_factor"),
        ("seed", -1, "seed = -1"),
        ("dt_s", 1e-3, "dt_s = 0.001 s is larger than the output interval"),
    ],
)
def test_scenario_bad_values(key, value, match):
    with pytest.raises(ConfigError, match=match):
        Scenario(**{key: value})


def test_defect_too_wide_for_ball():
    with pytest.raises(
        ConfigError,
        match=r"defect_width_m = 0.008 m is wider than the ball can "
        r"span; valid range \(0, 0.00794\) m",
    ):
        simulate(Scenario(fault="outer", defect_width_m=8e-3, duration_s=0.01))


@pytest.mark.parametrize("model", ["vsm", "tvsm", "dem"])
def test_result_roundtrip_lossless(tmp_path, model):
    res = simulate(
        Scenario(model=model, duration_s=0.02, per_ball=True, noise_rms_m_per_s2=0.1, **OUTER)
    )
    path = res.save(tmp_path / "r.nc")
    back = SimulationResult.load(path)
    assert back.scenario == res.scenario and back.meta == res.meta
    assert set(back.channels) == set(res.channels)
    for k, v in res.channels.items():
        assert np.array_equal(back.channels[k], v), k
        assert back.units[k] == res.units[k]
    assert np.array_equal(back.time, res.time)
    assert back.channels["ball_load"].shape == (res.time.size, 9)
    import xarray as xr

    with xr.open_dataset(path, engine="h5netcdf") as ds:  # self-describing
        assert ds["acc_y"].attrs["units"] == "m/s^2" and ds["ball_load"].dims == ("time", "ball")


def test_bit_reproducible_and_seeded_noise():
    sc = Scenario(duration_s=0.02, noise_rms_m_per_s2=0.5, seed=7, **OUTER)
    a, b = simulate(sc), simulate(sc)
    for k in a.channels:
        assert np.array_equal(a.channels[k], b.channels[k]), k
    c = simulate(sc.replace(seed=8))
    assert not np.array_equal(a["acc_y"], c["acc_y"])
    assert np.array_equal(a["disp_y"], c["disp_y"]), "noise only on the accelerations"
    clean = simulate(sc.replace(noise_rms_m_per_s2=0.0))
    assert_allclose(np.std(a["acc_y"] - clean["acc_y"]), 0.5, rtol=0.05)


@pytest.mark.parametrize("model", ["vsm", "tvsm", "dem"])
def test_starts_in_static_equilibrium(model):
    res = simulate(Scenario(model=model, duration_s=0.002, fault="none"))
    assert abs(res["acc_inst_y"][0]) < 1e-6 * 50.0 / 0.063, "eq. (19) balanced at t = 0"
    assert res.meta["static_residual_max"] <= 1e-9


@pytest.mark.parametrize("model", ["vsm", "tvsm"])
def test_static_balance_every_step(model):
    """Eq. (16) solved to 1e-9 relative at every RK4 stage time of the run (per-ball loads at
    the samples also balance the load)."""
    res = simulate(Scenario(model=model, duration_s=0.02, per_ball=True, **INNER))
    assert res.meta["static_residual_max"] <= 1e-9
    th = 2 * math.pi * res.meta["cage_hz"] * res.time[:, None] + 2 * math.pi * np.arange(9) / 9
    f = np.stack(
        [(res["ball_load"] * np.sin(th)).sum(1), (res["ball_load"] * np.cos(th)).sum(1)], 1
    )
    assert_allclose(f, np.broadcast_to([10.0, 50.0], f.shape), rtol=0, atol=1e-9 * 51.0)


#: compiled RK4 (automatic step, cell-averaged defect edges) vs the SciPy reference over 10 ms:
#: acceleration within 1 % of its peak, displacement within 0.1 % of its peak
CASES = [
    ("vsm", OUTER),
    ("tvsm", INNER),
    ("dem", OUTER),
    ("dem", INNER),
    pytest.param("vsm", INNER, marks=pytest.mark.slow),
    pytest.param("tvsm", OUTER, marks=pytest.mark.slow),
]


@pytest.mark.parametrize(
    ("model", "case"), CASES, ids=lambda v: v if isinstance(v, str) else v["fault"]
)
def test_compiled_matches_scipy_reference(model, case):
    sc = Scenario(model=model, duration_s=0.01, **case)
    res = simulate(sc)
    ref = Reference(model_inputs(sc), model)
    assert ref.jump_times(0.01), "the span must contain a defect passage"
    y0 = [res["disp_x"][0], res["disp_y"][0], 0.0, 0.0]
    _t, y, acc = ref.run(y0, sc.fs_hz, sc.n_samples)
    for k, name in enumerate(("acc_inst_x", "acc_inst_y")):
        assert_allclose(
            res[name],
            acc[:, k],
            rtol=0,
            atol=1e-2 * np.abs(acc).max(),
            err_msg=f"{model} {name} vs SciPy reference",
        )
    for k, name in enumerate(("disp_x", "disp_y")):
        assert_allclose(
            res[name],
            y[:, k],
            rtol=0,
            atol=1e-3 * np.abs(y[:, :2]).max(),
            err_msg=f"{model} {name} vs SciPy reference",
        )


@pytest.mark.parametrize("model", ["vsm", "tvsm", "dem"])
def test_compiled_adaptive_matches_scipy_reference(model):
    """The compiled Dormand-Prince path (exact defect indicator) and the SciPy reference solve
    the same equations: agreement to 1e-6 of the peak acceleration over a defect passage."""
    sc = Scenario(model=model, duration_s=0.005, solver="dopri5", **OUTER)
    res = simulate(sc)
    ref = Reference(model_inputs(sc), model)
    _t, y, acc = ref.run([res["disp_x"][0], res["disp_y"][0], 0.0, 0.0], sc.fs_hz, sc.n_samples)
    assert_allclose(res["acc_inst_y"], acc[:, 1], rtol=0, atol=1e-6 * np.abs(acc).max())
    assert_allclose(res["disp_y"], y[:, 1], rtol=0, atol=1e-8 * np.abs(y[:, 1]).max())


@pytest.mark.parametrize("model", ["vsm", "dem"])
def test_fixed_step_converges_to_adaptive(model):
    """RK4 error against the compiled Dormand-Prince run shrinks as the step shrinks."""
    sc = Scenario(model=model, duration_s=0.005, **OUTER)
    ref = simulate(sc.replace(solver="dopri5"))
    errs = []
    for dt in (1 / 48000 / 2, 1 / 48000 / 8):
        r = simulate(sc.replace(dt_s=dt))
        errs.append(
            np.abs(r["acc_inst_y"] - ref["acc_inst_y"]).max() / np.abs(ref["acc_inst_y"]).max()
        )
    assert errs[1] < 0.35 * errs[0] and errs[1] < 2e-3, errs


def test_zero_defect_limit_is_healthy():
    """gamma = 1 (a defect that releases nothing) reproduces the healthy bearing exactly."""
    a = simulate(Scenario(duration_s=0.02, fault="none", rpm=1796.0))
    b = simulate(Scenario(duration_s=0.02, retention_factor=1.0, **OUTER))
    assert_allclose(b["acc_y"], a["acc_y"], rtol=0, atol=1e-12 * np.abs(a["acc_y"]).max() + 1e-12)


def test_divergence_is_reported():
    with pytest.raises(SolverError, match=r"dt_s = 0.0005 s is too large.*valid range \(0, "):
        simulate(Scenario(fs_hz=2000.0, dt_s=5e-4, duration_s=0.05))


# ---------------------------------------------------------------------------------- CLI


def test_cli_simulate_json(run_cli, tmp_path):
    out = tmp_path / "o.nc"
    r = run_cli(
        "simulate",
        "--model",
        "dem",
        "--fault",
        "outer",
        "--rpm",
        "1796",
        "--duration-s",
        "0.02",
        "--fs-hz",
        "48000",
        "--seed",
        "1",
        "-o",
        out,
        "--json",
    )
    assert r.code == 0, r.err
    d = r.json()
    assert set(d) == {"output", "fs_hz", "n_samples", "rms_acc_x", "rms_acc_y", "wall_s"}
    assert d["n_samples"] == 960 and d["fs_hz"] == 48000.0
    res = SimulationResult.load(out)
    assert res.scenario["model"] == "dem" and res.scenario["seed"] == 1
    assert_allclose(d["rms_acc_y"], res.rms("acc_y"), rtol=1e-12)


def test_cli_scenario_file_and_override(run_cli, tmp_path):
    sc = tmp_path / "s.toml"
    sc.write_text('model = "tvsm"\nfault = "inner"\nrpm = 1748.0\nduration_s = 0.01\n')
    out = tmp_path / "o.nc"
    r = run_cli("simulate", sc, "--rpm", "1700", "-o", out, "--json")
    assert r.code == 0, r.err
    res = SimulationResult.load(out)
    assert res.scenario["model"] == "tvsm" and res.scenario["rpm"] == 1700.0


@pytest.mark.parametrize(
    ("args", "match"),
    [
        (["--fault", "outer", "--defect-width-m", "0.01"], "defect_width_m = 0.01 m is wider"),
        (["--fault", "outer", "--defect-depth-m", "0"], "defect_depth_m = 0 m is out of range"),
        (["--rpm", "0"], "rpm = 0 r/min is out of range; valid range (0, inf) r/min"),
        (["--rpm", "-100"], "rpm = -100 r/min is out of range"),
        (["--duration-s", "0"], "duration_s = 0 s is out of range; valid range (0, inf) s"),
        (
            ["--fs-hz", "2000", "--dt-s", "5e-4", "--duration-s", "0.05"],
            "dt_s = 0.0005 s is too large",
        ),
        (  # issue 14 sweep: the defect keys without --fault were not checked (1e30 m accepted)
            ["--defect-width-m", "1e30"],
            "defect_width_m = 1e+30 m is wider than the ball can span; valid range (0, 0.00794) m",
        ),
        (
            ["--defect-depth-m", "1e30"],
            "defect_depth_m = 1e+30 m is not less than the outer ring wall 0.00253 m of 6205",
        ),
        (  # issue 14 sweep: resolved at this fs, but beyond where a steel ring bursts
            ["--rpm", "300000", "--fs-hz", "400000", "--duration-s", "0.001"],
            "rpm = 300000 r/min gives the speed factor n d_m = 1.17e+07 mm r/min of 6205 (d_m = "
            "39 mm), above 1e+07, where a steel ring bursts",
        ),
    ],
)
def test_cli_bad_input(args, match, tmp_path, capsys):
    from bearingsim.cli import main

    out = tmp_path / "bad.nc"
    with pytest.raises(SystemExit) as exc:
        main(["simulate", *args, "-o", str(out)])
    assert exc.value.code == 2
    err = capsys.readouterr().err
    lines = [ln for ln in err.splitlines() if ln.strip()]
    assert len(lines) == 1 and lines[0].startswith("error: ") and match in lines[0], err
    assert not out.exists() and not list(tmp_path.iterdir()), "no partial output"


def test_second_process_does_not_recompile(tmp_path):
    """Numba's on-disk cache: a second process loads every kernel from the cache."""
    code = (
        "import json, numba\n"
        "from bearingsim.simulation import simulate\n"
        "from bearingsim.config import Scenario\n"
        "from bearingsim.dynamics import integrate\n"
        "from bearingsim.dynamics.ring import vsm, tvsm, dem, _balance as balance\n"
        "for m in ('vsm', 'tvsm', 'dem'):\n"
        "    simulate(Scenario(model=m, fault='outer', duration_s=0.002))\n"
        "miss = sum(sum(d.stats.cache_misses.values()) for d in (integrate._rk4_fixed,\n"
        "           balance.quasi_static_path, integrate._bad))\n"
        "hits = [k.cache_hits for k in\n"
        "        (vsm._vsm_rhs, vsm._vsm_aux, tvsm._tvsm_rhs, dem._dem_rhs)]\n"
        "print(json.dumps({'miss': miss, 'cfunc_hits': hits}))\n"
    )
    src = str(Path(__file__).resolve().parents[1] / "src")
    env = {"PYTHONPATH": src, "PATH": "/usr/bin:/bin"}
    import os

    env = {**os.environ, **env}
    for _ in range(2):
        p = subprocess.run(
            [sys.executable, "-c", code], capture_output=True, text=True, env=env, timeout=600
        )
        assert p.returncode == 0, p.stderr
    d = json.loads(p.stdout.strip().splitlines()[-1])
    assert d["miss"] == 0, d
    assert all(h >= 1 for h in d["cfunc_hits"]), d


def test_example_scenario_runs(run_cli, tmp_path):
    """examples/vsm_outer_cwru.toml, run as its header says, is diagnosed as outer (twenty-first
    session: as shipped, strictly periodic, it read "uncertain"; the test ran it shortened to
    0.5 s, which read outer)."""
    ex = Path(__file__).resolve().parents[1] / "examples" / "vsm_outer_cwru.toml"
    out = tmp_path / "o.nc"
    r = run_cli("simulate", ex, "-o", out, "--json")
    assert r.code == 0, r.err
    r2 = run_cli("analyze", out, "--json")
    assert r2.code == 0 and r2.json()["diagnosis"] == "outer", r2.err


def test_a_run_compiles_only_its_own_ring_model():
    """Each ring model's kernels are imported (and so compiled, once after installation) on
    its first run only: checking a scenario compiles nothing, a VSM run does not build the DEM
    and TVSM kernels (a cold start of ~1 min each). The facts a plan needs without compiling
    (:data:`MODEL_FACTS`) are those of each model's kernel record."""
    code = (
        "import json, sys\n"
        "from bearingsim.config import Scenario\n"
        "from bearingsim.simulation import simulate, validate_scenario\n"
        "validate_scenario(Scenario.from_dict({'model': 'dem', 'fault': 'outer'}))\n"
        "checked = sorted(m for m in sys.modules if m.split('.')[-1] in ('vsm', 'dem', 'tvsm'))\n"
        "simulate({'model': 'vsm', 'fault': 'outer', 'duration_s': 0.002})\n"
        "ran = sorted(m for m in sys.modules if m.split('.')[-1] in ('vsm', 'dem', 'tvsm'))\n"
        "print(json.dumps([checked, ran]))\n"
    )
    p = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=600)
    assert p.returncode == 0, p.stderr
    checked, ran = json.loads(p.stdout.strip().splitlines()[-1])
    assert checked == [] and ran == ["bearingsim.dynamics.ring.vsm"]
    from bearingsim.config import Model
    from bearingsim.dynamics.ring.base import MODEL_FACTS
    from bearingsim.dynamics.ring.scenario import model_kernel

    for m in (Model.VSM, Model.DEM, Model.TVSM):
        k = model_kernel(m)
        assert k.name == m.value and (k.needs_table, k.stiffness) == MODEL_FACTS[m.value]


class _Tty:
    def __init__(self):
        self.text = ""

    def isatty(self):
        return True

    def write(self, s):
        self.text += s

    def flush(self):
        pass


def test_compile_notice_only_on_a_terminal_and_only_when_slow(monkeypatch):
    """A cold compile (a minute) says so in one line on a terminal; a cached start, or any
    stream that is not a terminal (pipes, captured runs), stays silent."""
    import time

    from bearingsim.dynamics.notice import compile_notice

    tty = _Tty()
    monkeypatch.setattr(sys, "stderr", tty)
    with compile_notice("the vsm kernels", after_s=0.05):
        time.sleep(0.3)
    assert tty.text.strip() == (
        "bearingsim: compiling the vsm kernels (once after installation; about a minute) ..."
    )
    tty.text = ""
    with compile_notice("the vsm kernels", after_s=0.5):
        pass
    time.sleep(0.6)
    assert tty.text == ""
    with pytest.raises(RuntimeError, match="inside"):  # the timer stops on an error too
        with compile_notice("x", after_s=0.2):
            raise RuntimeError("inside")
    time.sleep(0.3)
    assert tty.text == ""
    monkeypatch.setattr(sys, "stderr", None)
    with compile_notice("x", after_s=0.0):
        time.sleep(0.05)


def test_a_step_beyond_the_accuracy_rule_warns():
    """A given dt_s with omega_max dt above the automatic step's 0.35 (but inside RK4's
    stability) runs with a warning naming both steps (exploratory testing: DEM outer fault,
    dt_s = 8.33e-5 s at 12 kHz, omega_max dt = 2.09, RMS 48 % low without a word)."""
    sc = dict(model="dem", fault="outer", duration_s=0.02, fs_hz=12000.0, dt_s=8.33e-5)
    with pytest.warns(RuntimeWarning, match=r"dt_s = 8\.33\d*e-05 s gives omega_max dt = 2\.0"):
        simulate(sc)


def test_the_adaptive_solver_stops_where_it_would_crawl():
    """A right-hand side that switches sign across y = 0 (chattering, dy/dt = -sign(y)) makes an
    explicit adaptive step shrink to nothing without underflowing; the solver stops after
    MAX_STEPS_PER_SAMPLE steps in one output interval with a one-line SolverError naming rk4
    (exploratory testing: a VSM with a 30 deg load zone and solver dopri5 ran >200 s for 24
    samples and could not be interrupted)."""
    from numba import cfunc

    from bearingsim.dynamics.integrate import MAX_STEPS_PER_SAMPLE, RHS_SIG, run_adaptive
    from bearingsim.errors import SolverError

    @cfunc(RHS_SIG)
    def chatter(t, y, p, dydt):
        dydt[0] = -1.0 if y[0] > 0.0 else 1.0

    t_eval = np.array([0.0, 1.0])
    msg = f"more than {MAX_STEPS_PER_SAMPLE} steps.*use solver rk4"
    with pytest.raises(SolverError, match=msg):
        run_adaptive(chatter, chatter, np.array([0.5]), np.zeros(1), t_eval, n_aux=0,
                     rtol=1e-9, atol=1e-15, h0=1e-3, bound=10.0)  # fmt: skip


def test_ctrl_c_during_a_compiled_kernel_is_raised_after_it_returns():
    """SIGINT while a nogil kernel runs: the kernel finishes, its arrays are boxed, then
    KeyboardInterrupt is raised; an ignored SIGINT stays ignored. (The crash this guards
    against is timing-dependent and not reproduced here: a rotor run with slip, interrupted
    through the CLI after 2-3.5 s, crashed with a segmentation fault in 2 of 6 tries and once
    finished as if no Ctrl-C had come, before the interrupt was held until the kernel
    returned; 0 of 10 after, docs/validation.md.)"""
    import os
    import signal
    import threading

    from numba import njit

    from bearingsim.dynamics.integrate import call_compiled

    @njit(nogil=True, cache=False)
    def spin(n):
        out = np.zeros(3)
        acc = 0.0
        for i in range(n):
            acc += math.sin(i * 1e-9)
        out[0] = acc
        return out, np.ones(5)

    spin(10)  # compile first
    n = 300_000_000  # ~1 s
    # Python's own handler, whatever the test run inherited: a suite started as a background
    # job of a non-interactive shell starts with SIGINT ignored (POSIX), and Python keeps that
    first = signal.signal(signal.SIGINT, signal.default_int_handler)
    try:
        timer = threading.Timer(0.2, lambda: os.kill(os.getpid(), signal.SIGINT))
        timer.start()
        with pytest.raises(KeyboardInterrupt):
            call_compiled(spin, n)
        timer.join()
    finally:
        signal.signal(signal.SIGINT, first)
    old = signal.signal(signal.SIGINT, signal.SIG_IGN)
    try:
        timer = threading.Timer(0.2, lambda: os.kill(os.getpid(), signal.SIGINT))
        timer.start()
        a, b = call_compiled(spin, n)
        timer.join()
        assert b.sum() == 5.0
    finally:
        signal.signal(signal.SIGINT, old)
