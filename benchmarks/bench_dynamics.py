"""Benchmark of the fault-dynamics models (issue 3 performance targets).

Prints, per model, the wall and CPU seconds per simulated second at 48 kHz output (warm, one
core; target <= 0.1 s), the same for the plain SciPy reference implementation of the same
equations (tests/dynamics_reference.py, on a short span) and their ratio (target >= 100), and
the wall time of two consecutive ``bearingsim simulate`` processes (the second must not
recompile: Numba's on-disk cache).

Run:  PYTHONPATH=src python benchmarks/bench_dynamics.py [--duration 2.0] [--ref-span 0.02]
"""

from __future__ import annotations

import argparse
import os
import subprocess
import sys
import tempfile
import time
from pathlib import Path

os.environ.setdefault("NUMBA_NUM_THREADS", "1")
os.environ.setdefault("OMP_NUM_THREADS", "1")
os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "tests"))

import numpy as np  # noqa: E402

from bearingsim.config import Scenario  # noqa: E402
from bearingsim.dynamics.ring.scenario import model_inputs  # noqa: E402
from bearingsim.simulation import simulate  # noqa: E402

CASES = {
    "outer": {"fault": "outer", "rpm": 1796.0, "defect_width_m": 1.778e-4},
    "inner": {"fault": "inner", "rpm": 1748.0, "defect_width_m": 3.556e-4},
    "none": {"fault": "none", "rpm": 1796.0},
}


def _best(fn, repeat: int) -> tuple[float, float]:
    walls, cpus = [], []
    for _ in range(repeat):
        w0, c0 = time.perf_counter(), time.process_time()
        fn()
        walls.append(time.perf_counter() - w0)
        cpus.append(time.process_time() - c0)
    return min(walls), min(cpus)


def bench_compiled(duration: float, repeat: int) -> dict:
    out = {}
    for model in ("vsm", "dem", "tvsm"):
        for case, kw in CASES.items():
            sc = Scenario(model=model, duration_s=duration, fs_hz=48000.0, **kw)
            simulate(sc.replace(duration_s=0.01))  # warm: load the compiled kernels
            res = simulate(sc)
            wall, cpu = _best(lambda sc=sc: simulate(sc), repeat)
            out[(model, case)] = (wall / duration, cpu / duration, res.meta["steps_per_sample"])
    return out


#: SciPy settings: the tight reference of the tests, and a looser everyday setting whose
#: accuracy (acceleration error vs the tight one) is printed beside its speed
REF_SETTINGS = {
    "DOP853 rtol 1e-10 (tests)": {"method": "DOP853", "rtol": 1e-10},
    "RK45 rtol 1e-6": {"method": "RK45", "rtol": 1e-6, "atol_scale": 1e4},
}


def bench_reference(span: float) -> dict:
    from dynamics_reference import Reference

    out = {}
    for model in ("vsm", "dem", "tvsm"):
        sc = Scenario(model=model, duration_s=span, **CASES["outer"])
        res = simulate(sc)
        y0 = [res["disp_x"][0], res["disp_y"][0], 0.0, 0.0]
        tight = None
        for name, kw in REF_SETTINGS.items():
            ref = Reference(model_inputs(sc), model)
            w0, c0 = time.perf_counter(), time.process_time()
            _t, _y, acc = ref.run(y0, sc.fs_hz, sc.n_samples, **kw)
            wall, cpu = (time.perf_counter() - w0) / span, (time.process_time() - c0) / span
            if tight is None:
                tight = acc
            err_ref = np.abs(acc - tight).max() / np.abs(tight).max()
            err_ours = (
                np.abs(np.column_stack([res["acc_inst_x"], res["acc_inst_y"]]) - tight).max()
                / np.abs(tight).max()
            )
            out[(model, name)] = (wall, cpu, err_ref, err_ours)
    return out


def bench_cli() -> list[float]:
    env = {**os.environ, "PYTHONPATH": str(ROOT / "src")}
    times = []
    with tempfile.TemporaryDirectory() as d:
        for k in range(2):
            t0 = time.perf_counter()
            p = subprocess.run(
                [
                    sys.executable,
                    "-m",
                    "bearingsim",
                    "simulate",
                    "--model",
                    "vsm",
                    "--fault",
                    "outer",
                    "--rpm",
                    "1796",
                    "--duration-s",
                    "0.1",
                    "-o",
                    f"{d}/o{k}.nc",
                    "--json",
                ],
                capture_output=True,
                text=True,
                env=env,
                timeout=600,
            )
            times.append(time.perf_counter() - t0)
            if p.returncode != 0:
                raise SystemExit(p.stderr)
    return times


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--duration", type=float, default=2.0, help="simulated seconds per run")
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--ref-span", type=float, default=0.02, help="SciPy reference span [s]")
    a = ap.parse_args()
    print(
        f"bench_dynamics: 6205, 48 kHz output, {a.duration:g} s per run, best of {a.repeat}; "
        f"load average {os.getloadavg()[0]:.2f} on {os.cpu_count()} cores"
    )
    comp = bench_compiled(a.duration, a.repeat)
    ref = bench_reference(a.ref_span)
    print(
        f"\n{'model':<6}{'fault':<7}{'steps/sample':>13}{'wall s/sim s':>14}{'cpu s/sim s':>13}"
        f"{'target':>8}"
    )
    for (model, case), (w, c, d) in comp.items():
        print(
            f"{model:<6}{case:<7}{d:>13}{w:>14.4f}{c:>13.4f}{'<=0.1':>8}"
            f"{'  ok' if c <= 0.1 else '  MISSED'}"
        )
    print(
        f"\nSciPy reference (tests/dynamics_reference.py: solve_ivp + scipy.optimize.root), "
        f"outer defect, {a.ref_span:g} s span; errors = max |acc - tight reference| / peak:"
    )
    print(
        f"{'model':<6}{'setting':<27}{'wall s/sim s':>13}{'cpu s/sim s':>12}{'its error':>11}"
        f"{'our error':>11}{'speed-up':>10}{'target':>8}"
    )
    for (model, name), (w, c, e_ref, e_ours) in ref.items():
        ratio = c / comp[(model, "outer")][1]
        print(
            f"{model:<6}{name:<27}{w:>13.2f}{c:>12.2f}{e_ref:>11.1e}{e_ours:>11.1e}"
            f"{ratio:>10.0f}{'>=100':>8}{'  ok' if ratio >= 100 else '  MISSED'}"
        )
    cli = bench_cli()
    print(
        f"\nCLI 'bearingsim simulate' (0.1 s VSM), two consecutive processes: "
        f"{cli[0]:.2f} s, {cli[1]:.2f} s (the second loads every kernel from Numba's cache)"
    )
    np.set_printoptions(precision=4)


if __name__ == "__main__":
    main()
