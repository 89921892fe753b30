"""Benchmark of the IAS model (issues 5 and 13): the seed case beside its references.

Run: ``PYTHONPATH=src python benchmarks/bench_ias.py [--quick] [--repeat N]``

Prints
  1. the seed's full case (NU204-ECP, 11 rollers, RK4, dt = 1e-6 s, 10 s = 1e7 steps), warm, for
     every entry point in :func:`seed_case_runs`: CPU time of the integration (``solver.cpu_s``)
     and of the whole call, smallest / median / largest of ``--repeat`` runs;
  2. the same stepping through the generic ``integrate._rk4_fixed`` (the ``ias_rhs``/``ias_aux``
     cfuncs called through their addresses, as every model can) instead of the IAS driver
     ``kernel.ias_rk4`` (``integrate._rk4_inline`` with the right-hand side inlined), which
     ``simulate_ias`` uses: what the inlining saves;
  3. on a 0.05 s span, CPU times: the compiled RK4 against the NumPy right-hand side under
     ``scipy.integrate.solve_ivp`` (RK45, rtol 1e-9, atol 1e-13) and against the same RK4 at
     dt = 1e-6 s stepped by a pure-Python loop.
Target (issue 13): item 1 <= 3 s on one core (median). The machine may be shared: CPU time
(``time.process_time``) is the fair figure, and the spread of the repeats says how noisy it was.
"""

from __future__ import annotations

import argparse
import math
import statistics
import time
from collections.abc import Callable

import numpy as np

from bearingsim import get_bearing
from bearingsim.dynamics.ias._kernel import ias_aux, ias_rhs
from bearingsim.dynamics.ias.model import (
    N_AUX,
    IasParams,
    IasResult,
    initial_state,
    pack_parameters,
    simulate_ias,
)
from bearingsim.dynamics.ias.reference import ReferenceRhs, simulate_ias_scipy
from bearingsim.dynamics.integrate import run_fixed

DT = 1e-6  # the seed's RK4 step [s]
RATE = 50_000.0  # output sample rate [Hz]: 20 seed steps per sample (exact, as simulate needs)
TARGET_S = 3.0  # issue 13: the 10 s seed case on one core [s]


def seed_case_runs(seed: IasParams) -> list[tuple[str, Callable[[float], IasResult]]]:
    """The entry points timed in item 1: ``(label, run(duration))``: the model function, and
    ``bearingsim.simulate`` on the seed's IAS scenario (the same run through the scenario
    schema, the output grid and the runner; ``duration_s`` = the seed's 10 s)."""
    from bearingsim import simulate
    from bearingsim.config import IasScenario

    return [
        ("simulate_ias", lambda dur: simulate_ias(seed, dur, DT, RATE, "rk4")),
        (
            "bearingsim.simulate",
            lambda dur: simulate(IasScenario(duration_s=dur, dt_s=DT, fs_hz=RATE)),
        ),
    ]


def _spread(v: list[float]) -> str:
    return f"{min(v):.2f} / {statistics.median(v):.2f} / {max(v):.2f} s"


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--quick", action="store_true", help="1 s instead of 10 s for items 1-2")
    ap.add_argument("--repeat", type=int, default=3, help="runs of item 1 per entry point")
    a = ap.parse_args()
    seed = IasParams(get_bearing("NU204-ECP"))
    dur = 1.0 if a.quick else 10.0
    scale = 10.0 / dur  # figures scaled to the 10 s case
    p = pack_parameters(seed)
    y0 = initial_state(seed)
    simulate_ias(seed, 0.01, DT, 10_000.0)  # warm-up: compilation or cache load

    def generic(n_out: int, decim: int):
        return run_fixed(
            ias_rhs, ias_aux, y0, p, dt=DT, n_out=n_out, decim=decim, n_aux=N_AUX, bound=1e9
        )

    generic(2, 100)

    r = None
    for label, run in seed_case_runs(seed):
        run(0.01)
        kern, call = [], []
        for _ in range(a.repeat):
            c0 = time.process_time()
            r = run(dur)
            call.append((time.process_time() - c0) * scale)
            kern.append(r.solver["cpu_s"] * scale)
        n = r.solver["n_steps"]
        med = statistics.median(kern)
        met = "MET" if med <= TARGET_S else "NOT MET"
        print(
            f"[1] seed case via {label}: {dur:g} s simulated ({n:.4g} RK4 steps, dt {DT:g} s, 11 "
            f"rollers), CPU scaled to 10 s, min / median / max of {a.repeat}: integration "
            f"{_spread(kern)}, whole call {_spread(call)}; {n * scale / med / 1e6:.2f} M steps "
            f"per CPU-s; target <= {TARGET_S:g} s on one core: {met}"
        )
    s = r.analyze()
    print(
        f"    mean speed {s.mean_speed * 60 / (2 * math.pi):.4f} r/min, spall estimate "
        f"{s.estimate.width * 1e3:.4f} mm, peaks "
        + ", ".join(f"{q.order:.4f}" for q in s.peaks[:3])
    )

    decim = r.solver["decim"]
    c0 = time.process_time()
    tg = generic(len(r.t), decim)
    wg = (time.process_time() - c0) * scale
    print(
        f"[2] same steps through the generic _rk4_fixed (cfuncs called through their addresses): "
        f"CPU {wg:.2f} s (10 s case); generic / inlined driver = {wg / med:.2f}; max |state "
        f"diff| {np.abs(tg.y - r.state).max():.2e}"
    )

    span = 0.05
    simulate_ias(seed, span, DT, 20_000.0)
    rc = simulate_ias(seed, span, DT, 20_000.0)
    wc = rc.solver["cpu_s"]
    y, info = simulate_ias_scipy(seed, rc.t, method="RK45", rtol=1e-9, atol=1e-13)
    err = np.abs(y[:, 5] - rc.omega).max()
    print(
        f"[3] 0.05 s span, CPU times: compiled RK4 (dt 1e-6) {wc * 1e3:.1f} ms; SciPy RK45 on "
        f"the NumPy RHS {info['cpu_s']:.2f} s ({info['n_rhs']} RHS calls) -> ratio "
        f"{info['cpu_s'] / wc:.0f}x; max |omega diff| {err:.2e} rad/s"
    )
    rhs = ReferenceRhs(seed)
    yy = initial_state(seed)
    n_py = int(round(span / DT))
    c0 = time.process_time()
    for i in range(n_py):
        t = i * DT
        k1 = rhs(t, yy)
        k2 = rhs(t, yy + 0.5 * DT * k1)
        k3 = rhs(t, yy + 0.5 * DT * k2)
        k4 = rhs(t, yy + DT * k3)
        yy = yy + DT / 6.0 * (k1 + 2 * k2 + 2 * k3 + k4)
    wp = time.process_time() - c0
    print(
        f"    same RK4 (dt 1e-6) stepped in Python with the NumPy RHS: {wp:.2f} s -> ratio "
        f"{wp / wc:.0f}x; |omega(0.05 s) diff| {abs(yy[5] - rc.omega[-1]):.2e} rad/s"
    )


if __name__ == "__main__":
    main()
