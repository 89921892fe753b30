"""Benchmark of the damage-mechanics life prediction (issue 7).

Target: the default-mesh 6206 life prediction (1000 damage blocks, seed LIFE Delta_D = 0.001)
in <= 60 s on the 2-core machine; time per damage block and its scaling with element count.

Usage::

    PYTHONPATH=src python benchmarks/bench_life.py                 # target + scaling
    PYTHONPATH=src python benchmarks/bench_life.py --convergence   # + life vs mesh (slow)
    PYTHONPATH=src python benchmarks/bench_life.py --sensitivity   # + Delta_D, Delta_tau (slow)

Prints plain text; writes nothing.
"""

from __future__ import annotations

import argparse
import math
import os
import time

import numpy as np

from bearingsim.catalog import get_bearing
from bearingsim.life.fatigue import contact_fatigue_life, inner_contact
from bearingsim.life.fe import contact_section, core_substructure, section_spec


def target(bearing) -> None:
    t0 = time.perf_counter()
    r = contact_fatigue_life(bearing, 5000.0, mesh="default", stop="initiation")
    total = time.perf_counter() - t0
    m = r.meta
    print("== target: default mesh, 6206 at 5 kN, Delta_D = 0.001, stop at first failure")
    print(f"   blocks to initiation      {r.steps_initiation}")
    print(f"   cycles to initiation      {r.cycles_initiation:.4g}")
    print(
        f"   core elements / dofs      {m['n_core_elements']} / {m['n_core_dofs']} "
        f"({m['n_elements']} in the section), {m['n_positions']} load positions"
    )
    print(f"   setup (mesh, condensation, undamaged check) {m['setup_s']:.2f} s")
    print(
        f"   damage loop               {m['wall_s']:.2f} s "
        f"({1e3 * m['time_per_step_s']:.1f} ms per block)"
    )
    print(f"   total                     {total:.2f} s  (target <= 60 s)")


def scaling(bearing, n_steps: int = 20) -> None:
    c = inner_contact(bearing, 5000.0)
    print(f"== time per damage block vs element count ({n_steps} blocks each)")
    print("   mesh     h[um]  core_el  core_dofs  positions  ms/block  ms/(dof*pos)*1e3")
    rows = []
    for mesh in ("coarse", "default", "fine"):
        sec = contact_section(bearing.material, c.p_max, c.b, section_spec(c.b, mesh))
        core = core_substructure(sec)
        f = np.ones(core.n_elements)
        core.solve(f)  # warm-up
        t0 = time.perf_counter()
        for k in range(n_steps):
            f[k % f.size] *= 0.999  # a changing damage state
            st = core.solve(f)
            st.shear_range()
        dt = (time.perf_counter() - t0) / n_steps
        rows.append((core.n_elements, dt))
        print(
            f"   {mesh:<8} {1e6 * sec.spec.element_size:5.1f}  {core.n_elements:7d}  "
            f"{core.n_dofs:9d}  {sec.n_positions:9d}  {1e3 * dt:8.1f}  "
            f"{1e6 * dt / (core.n_dofs * sec.n_positions):8.3f}"
        )
    ne = np.array([r[0] for r in rows], dtype=float)
    tt = np.array([r[1] for r in rows])
    slope = np.polyfit(np.log(ne), np.log(tt), 1)[0]
    print(f"   log-log slope of time per block vs core elements: {slope:.2f}")


def convergence(bearing) -> None:
    print("== life vs mesh (Delta_D = 0.001, orthogonal shear, stop at first failure)")
    print("   mesh     h/b     N_initiation    depth/b   wall[s]")
    out = []
    for mesh in ("coarse", "default", "fine"):
        r = contact_fatigue_life(bearing, 5000.0, mesh=mesh, stop="initiation")
        b = r.meta["b_m"]
        out.append((r.meta["element_size_m"] / b, r.cycles_initiation))
        print(
            f"   {mesh:<8} {r.meta['element_size_m'] / b:5.3f}  {r.cycles_initiation:13.5g}  "
            f"{r.initiation_depth / b:7.3f}  {r.wall_s:8.1f}"
        )
    (h1, n1), (h2, n2), (h3, n3) = out
    # Richardson extrapolation with the observed order from three meshes
    try:
        p = math.log(abs((n1 - n2) / (n2 - n3))) / math.log(h1 / h2)
        n_inf = n3 + (n3 - n2) / ((h2 / h3) ** p - 1)
        print(f"   observed order {p:.2f}, extrapolated N_initiation {n_inf:.5g}")
    except (ValueError, ZeroDivisionError):
        print("   (no monotone convergence: no extrapolation)")


def sensitivity(bearing) -> None:
    print("== sensitivity (default mesh unless stated)")
    print("   Delta_D    N_initiation   N_spall (Delta_D_spall = 0.01)   blocks")
    for dd in (0.01, 0.003, 0.001):
        r = contact_fatigue_life(bearing, 5000.0, mesh="default", delta_d=dd, delta_d_spall=0.01)
        print(
            f"   {dd:<8g}  {r.cycles_initiation:13.5g}  {r.cycles_spall:13.5g}"
            f"                  {r.steps_initiation}/{r.steps_spall}"
        )
    print("   Delta_D_spall (coarse mesh, Delta_D = 0.001): N_spall")
    for dds in (0.001, 0.01):
        r = contact_fatigue_life(bearing, 5000.0, mesh="coarse", delta_d_spall=dds)
        print(f"   {dds:<8g}  {r.cycles_spall:.7g} ({r.steps_spall} blocks)")
    print("   measure          N_initiation   depth/b   max Delta_tau0 [MPa]")
    for meas in ("orthogonal", "critical_plane", "max_shear"):
        r = contact_fatigue_life(bearing, 5000.0, mesh="default", measure=meas, stop="initiation")
        print(
            f"   {meas:<15}  {r.cycles_initiation:13.5g}  "
            f"{r.initiation_depth / r.meta['b_m']:7.3f}  {r.delta_tau0.max() / 1e6:8.1f}"
        )


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--convergence", action="store_true")
    ap.add_argument("--sensitivity", action="store_true")
    a = ap.parse_args()
    b = get_bearing("6206")
    print(f"bench_life on {os.cpu_count()} cpu(s), load average {os.getloadavg()[0]:.2f}")
    target(b)
    scaling(b)
    if a.convergence:
        convergence(b)
    if a.sensitivity:
        sensitivity(b)
    print(f"load average at the end {os.getloadavg()[0]:.2f}")


if __name__ == "__main__":
    main()
