"""Benchmark of the IAS model (issue 5): the seed's full case and the SciPy reference ratio.

Run: ``PYTHONPATH=src python benchmarks/bench_ias.py [--quick]``

Prints
  1. the seed's full case (NU204-ECP, 11 rollers, RK4, dt = 1e-6 s, 10 s = 1e7 steps) with the
     shared compiled integrator (``integrate.run_fixed`` + cfunc right-hand side), warm;
  2. the same stepping with a model-specific ``njit`` RK4 loop calling the right-hand side
     directly (no cfunc indirection), to measure the cost of the generic design;
  3. the plain NumPy right-hand side on a 0.05 s span: under ``scipy.integrate.solve_ivp``
     (RK45, rtol 1e-9, atol 1e-13) and stepped by a Python RK4 loop at the same dt = 1e-6 s,
     against the compiled RK4 on the same span.
Target (issue 5): item 1 <= 10 s on one core (faster than real time).
"""

from __future__ import annotations

import argparse
import math
import time

import numpy as np
from numba import njit

from bearingsim import get_bearing
from bearingsim.dynamics.ias.kernel import _forces
from bearingsim.dynamics.ias.model import (
    IasParams,
    derive_constants,
    initial_state,
    pack_parameters,
    simulate_ias,
)
from bearingsim.dynamics.ias.reference import ReferenceRhs, simulate_ias_scipy


@njit(cache=True)
def _rhs_direct(y, p, out):
    w = y[5]
    sgn = w / math.sqrt(w * w + p[30] * p[30])
    fx, fy, torque, m_t, _a, _b, _c, _d = _forces(y, p, sgn)
    out[0] = y[3]
    out[1] = y[4]
    out[2] = w
    out[3] = (p[4] - p[2] * y[3] + fx) / p[0]
    out[4] = (p[5] - p[2] * y[4] + fy) / p[0]
    out[5] = (p[6] - p[3] * w - sgn * (torque + m_t)) / p[1]


@njit(cache=True)
def _rk4_direct(y0, p, dt, n_steps, decim):
    y = y0.copy()
    k1 = np.empty(6)
    k2 = np.empty(6)
    k3 = np.empty(6)
    k4 = np.empty(6)
    yt = np.empty(6)
    out = np.empty((n_steps // decim + 1, 6))
    out[0] = y
    h2 = 0.5 * dt
    h6 = dt / 6.0
    for i in range(n_steps):
        _rhs_direct(y, p, k1)
        for j in range(6):
            yt[j] = y[j] + h2 * k1[j]
        _rhs_direct(yt, p, k2)
        for j in range(6):
            yt[j] = y[j] + h2 * k2[j]
        _rhs_direct(yt, p, k3)
        for j in range(6):
            yt[j] = y[j] + dt * k3[j]
        _rhs_direct(yt, p, k4)
        for j in range(6):
            y[j] += h6 * (k1[j] + 2.0 * k2[j] + 2.0 * k3[j] + k4[j])
        if (i + 1) % decim == 0:
            out[(i + 1) // decim] = y
    return out


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--quick", action="store_true", help="1 s instead of 10 s for item 1-2")
    a = ap.parse_args()
    seed = IasParams(get_bearing("NU204-ECP"))
    dur = 1.0 if a.quick else 10.0
    dt = 1e-6
    # warm-up (compilation or cache load)
    simulate_ias(seed, 0.01, dt, 10_000.0)
    p = pack_parameters(seed, derive_constants(seed))
    _rk4_direct(initial_state(seed), p, dt, 100, 100)

    t0 = time.perf_counter()
    c0 = time.process_time()
    r = simulate_ias(seed, dur, dt, 48_000.0)
    wall = time.perf_counter() - t0
    cpu = time.process_time() - c0
    kc = r.solver["cpu_s"]
    n = r.solver["n_steps"]
    s = r.analyze()
    met = "MET" if kc * 10 / dur <= 10 else "NOT MET"
    print(
        f"[1] seed case, shared run_fixed + cfunc RHS: {dur:g} s simulated, {n:.4g} RK4 steps, "
        f"11 rollers: kernel CPU {kc:.2f} s (wall {r.solver['wall_s']:.2f} s; whole call CPU "
        f"{cpu:.2f} s, wall {wall:.2f} s), {n / kc / 1e6:.2f} M steps per CPU-s, "
        f"{dur / kc:.2f}x real time; target 10 s case <= 10 s on one core: {met}"
    )
    print(
        f"    mean speed {s.mean_speed * 60 / (2 * math.pi):.4f} r/min, spall estimate "
        f"{s.estimate.width * 1e3:.4f} mm, peaks "
        + ", ".join(f"{q.order:.4f}" for q in s.peaks[:3])
    )

    c0 = time.process_time()
    yd = _rk4_direct(initial_state(seed), p, dt, n, r.solver["decim"])
    wd = time.process_time() - c0
    print(
        f"[2] model-specific njit RK4 loop (direct RHS call): CPU {wd:.2f} s "
        f"({n / wd / 1e6:.2f} M steps per CPU-s); generic/direct = {kc / wd:.2f}; "
        f"max |omega diff| = {np.abs(yd[:, 5] - r.omega).max():.2e} rad/s"
    )

    span = 0.05
    rc = simulate_ias(seed, span, dt, 20_000.0)
    rc = simulate_ias(seed, span, dt, 20_000.0)
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
    n_py = int(round(span / dt))
    c0 = time.process_time()
    for i in range(n_py):
        t = i * dt
        k1 = rhs(t, yy)
        k2 = rhs(t, yy + 0.5 * dt * k1)
        k3 = rhs(t, yy + 0.5 * dt * k2)
        k4 = rhs(t, yy + dt * k3)
        yy = yy + dt / 6.0 * (k1 + 2 * k2 + 2 * k3 + k4)
    wp = time.process_time() - c0
    print(
        f"    same RK4 (dt 1e-6) stepped in Python with the NumPy RHS: {wp:.2f} s -> ratio "
        f"{wp / wc:.0f}x; |omega(0.05 s) diff| {abs(yy[5] - rc.omega[-1]):.2e} rad/s"
    )


if __name__ == "__main__":
    main()
