"""ROTOR benchmark (issue 6 target): 1 simulated second of the CWRU case (6205 DE with the
0.007 in outer-race defect at 6 o'clock, 6203 FE, 9 disks, 1750 r/min) at 12 kHz output in
<= 2 s warm on one core. Prints the warm wall time (best of 3) of the whole
``simulate_rotor`` call (rotor assembly and reduction, static equilibrium, integration,
anti-alias decimation) and its parts; and the same with quasi-static balls (``ball_inertia =
False``).

Run: ``NUMBA_NUM_THREADS=1 python benchmarks/bench_rotor.py``
"""

from __future__ import annotations

import os
import time

os.environ.setdefault("NUMBA_NUM_THREADS", "1")

from bearingsim.dynamics.integrate import run_fixed  # noqa: E402
from bearingsim.dynamics.rotor import _kernel as rk  # noqa: E402
from bearingsim.dynamics.rotor.config import cwru_rotor_config
from bearingsim.dynamics.rotor.model import pack_model, simulate_rotor, stable_step, static_state
from bearingsim.geometry import Defect

TARGET_S = 2.0


def best(f, n=3):
    ts = []
    for _ in range(n):
        t0 = time.perf_counter()
        out = f()
        ts.append(time.perf_counter() - t0)
    return min(ts), out


def main() -> None:
    cfg = cwru_rotor_config(9, de_fault=Defect("outer"))
    t0 = time.perf_counter()
    simulate_rotor(cfg, duration=0.01)  # load the compiled kernels (numba cache) / compile
    t_first = time.perf_counter() - t0
    print(f"first call (numba cache load or compile) + 0.01 s simulation: {t_first:.2f} s")
    for aa in (True, False):
        t, r = best(lambda aa=aa: simulate_rotor(cfg, duration=1.0, sample_rate=12000.0,
                                                 antialias=aa))  # fmt: skip
        ok = "OK" if t <= TARGET_S else "SLOW"
        print(
            f"simulate_rotor 1 s, 9 disks, 12 kHz, antialias={aa}: {t:.3f} s warm "
            f"(target <= {TARGET_S} s) {ok}; {r.meta['n_rotor_coordinates']} rotor coords, "
            f"{r.meta['n_steps']} RK4 steps of {r.meta['dt_s'] * 1e6:.3f} us"
        )
    qs = cwru_rotor_config(9, de_fault=Defect("outer"), ball_inertia=False)
    simulate_rotor(qs, duration=0.01)
    t, r = best(lambda: simulate_rotor(qs, duration=1.0, sample_rate=12000.0))
    print(
        f"simulate_rotor 1 s, 9 disks, 12 kHz, quasi-static balls: {t:.3f} s warm "
        f"(target <= {TARGET_S} s) {'OK' if t <= TARGET_S else 'SLOW'}; "
        f"{r.meta['n_steps']} RK4 steps of {r.meta['dt_s'] * 1e6:.3f} us"
    )
    # parts
    t_pack, m = best(lambda: pack_model(cfg, 12000.0))
    t_static, y0 = best(lambda: static_state(m, cfg))
    dt = stable_step(m, cfg, y0)
    decim = int(-(-1.0 // (48000.0 * dt)))
    n_out = 48001
    t_int, _ = best(
        lambda: run_fixed(
            rk.rotor_rhs,
            rk.rotor_aux,
            y0,
            m.p,
            dt=1 / (48000.0 * decim),
            n_out=n_out,
            decim=decim,
            n_aux=4,
            bound=1.0,
        )  # fmt: skip
    )
    n_rhs = 4 * (n_out - 1) * decim
    print(f"  assembly + Craig-Bampton + packing: {t_pack * 1e3:.1f} ms")
    print(f"  static equilibrium:                 {t_static * 1e3:.1f} ms")
    print(
        f"  RK4 integration (48 kHz internal):  {t_int:.3f} s, {n_rhs} RHS calls, "
        f"{t_int / n_rhs * 1e6:.2f} us per RHS"
    )


if __name__ == "__main__":
    main()
