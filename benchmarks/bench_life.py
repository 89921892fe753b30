"""Benchmark of the damage-mechanics life prediction (issues 7 and 15).

Target (issue 15 part 2): the default full run -- 6206 at 5 kN, default mesh, Delta_D = 0.001,
to the spall -- in <= 15 s warm on one core, with the same answer as the direct solve of every
block to <= 0.5 %. Also times the same run with the earlier block after initiation
(Delta_D_spall 0.01 instead of the default 0.1) and compares the two. Run it on one core::

    OMP_NUM_THREADS=1 OPENBLAS_NUM_THREADS=1 MKL_NUM_THREADS=1 NUMBA_NUM_THREADS=1 \
        PYTHONPATH=src python benchmarks/bench_life.py [--direct]

``--direct`` also times the direct solve (a new factorization every block, about a minute) and
prints the agreement. ``--convergence`` adds life vs mesh, ``--sensitivity`` Delta_D and the
measures (slow).

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


def _run(bearing, solver: str, **kw):
    t0 = time.perf_counter()
    r = contact_fatigue_life(bearing, 5000.0, mesh="default", solver=solver, **kw)
    return r, time.perf_counter() - t0


def target(bearing, direct: bool) -> None:
    # warm-up: the compiled kernels and the imports (a short run of each solver)
    for solver in ("pcg", "direct"):
        contact_fatigue_life(bearing, 5000.0, mesh="coarse", max_steps=200, stop="initiation",
                             delta_d=0.01, solver=solver)  # fmt: skip
    print("== target: default full run (6206, 5 kN, default mesh, Delta_D 0.001, to the spall)")
    runs = [("pcg", *_run(bearing, "pcg"))]
    runs.append(("pcg, Delta_D_spall 0.01", *_run(bearing, "pcg", delta_d_spall=0.01)))
    if direct:
        runs.append(("direct", *_run(bearing, "direct")))
    for solver, r, total in runs:
        m = r.meta
        print(f"   solver {solver} (Delta_D_spall {m['delta_d_spall']:g})")
        print(f"     blocks to initiation / spall   {r.steps_initiation} / {r.steps_spall}")
        print(f"     cycles to initiation / spall   {r.cycles_initiation:.8g} / "
              f"{r.cycles_spall:.8g}")  # fmt: skip
        print(f"     failed elements at the spall   {int((r.damage_final >= 1.0).sum())}")
        print(
            f"     core elements / dofs          {m['n_core_elements']} / {m['n_core_dofs']} "
            f"({m['n_elements']} in the section), {m['n_positions']} load positions"
        )
        print(
            f"     factorizations {m['n_factorizations']}, triangular solves "
            f"{m['n_preconditioner']}, PCG iterations {m['n_iterations']}, blocks accepted "
            f"at the extrapolated start {m['n_accepted']}"
        )
        print(f"     setup {m['setup_s']:.2f} s, damage loop {m['wall_s']:.2f} s "
              f"({1e3 * m['time_per_step_s']:.1f} ms per block)")  # fmt: skip
        print(f"     total {total:.2f} s  (target <= 15 s warm on one core)")
    p, p01 = runs[0][1], runs[1][1]
    same = np.array_equal(p.damage_final >= 1.0, p01.damage_final >= 1.0)
    rel = p.cycles_spall / p01.cycles_spall - 1
    print(f"   Delta_D_spall 0.1 vs 0.01: spall cycles {rel:+.2e}, same failed elements: {same}")
    if direct:
        d, td = runs[2][1], runs[2][2]
        for name in ("cycles_initiation", "cycles_spall"):
            a, b = getattr(p, name), getattr(d, name)
            print(f"   {name}: pcg / direct - 1 = {a / b - 1:+.2e}  (target |.| <= 5e-3)")
        same = np.array_equal(p.damage_final >= 1.0, d.damage_final >= 1.0)
        print(f"   same failed elements as the direct solve: {same}")
        print(f"   speed-up {td / runs[0][2]:.2f}x")


def scaling(bearing, n_steps: int = 20) -> None:
    c = inner_contact(bearing, 5000.0)
    print(f"== time per damage block vs element count ({n_steps} blocks each, direct solve)")
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
    ap.add_argument("--direct", action="store_true", help="also time the direct solve")
    ap.add_argument("--convergence", action="store_true")
    ap.add_argument("--sensitivity", action="store_true")
    a = ap.parse_args()
    b = get_bearing("6206")
    print(f"bench_life on {os.cpu_count()} cpu(s), load average {os.getloadavg()[0]:.2f}")
    target(b, a.direct)
    scaling(b)
    if a.convergence:
        convergence(b)
    if a.sensitivity:
        sensitivity(b)
    print(f"load average at the end {os.getloadavg()[0]:.2f}")


if __name__ == "__main__":
    main()
