"""Benchmark of ``bearingsim sweep``: 64 DEM runs (0.5 s at 12 kHz each) on 1 and 2 workers.

Targets (issue 8): throughput with 2 workers >= 1.8 x that with 1 worker; overhead per run
<= 5 % of its compute time.

Definitions (printed):

- throughput = runs / wall, wall from the first submitted task to the last commit (cluster
  start, kernel loading on the workers, probes and dataset creation are ``setup``, printed apart);
- compute = the wall time of ``simulate()`` of each run inside the worker;
- overhead per run (wall) = (workers x wall - sum of compute) / runs: everything that is not
  ``simulate`` (Dask scheduling and transfer, Zarr commits, idle workers at the end), also
  against a serial baseline measured in this process without Dask or writing;
- overhead per run (CPU) = (CPU time of the worker processes and of this client process, which
  also hosts the local schedulers and nannies of both clusters, during the wall interval above -
  CPU time inside ``simulate``) / runs. Unlike the wall-clock figures it hardly depends
  on what else runs on the machine.

The two clusters (1 and 2 workers) stay up side by side and the measurements alternate between
them, so that a drift of the machine's speed during the benchmark falls on both; the ratio is
that of the median throughputs (the per-repeat ratios are printed too).

Other jobs on the machine inflate every wall-clock figure: the load average is printed with each
measurement; ``--max-load`` waits (up to ``--wait-s``) for a 1-minute load average below it.

Run::

    PYTHONPATH=src python benchmarks/bench_sweep.py [--repeats 5] [--runs 64] [--max-load 1.0]
"""

from __future__ import annotations

import argparse
import os
import shutil
import statistics
import tempfile
import time
from pathlib import Path

from bearingsim.simulation import simulate
from bearingsim.sweep.execute import connect, run_sweep, worker_hello
from bearingsim.sweep.spec import SweepSpec


def make_spec(n_runs: int, duration_s: float = 0.5) -> SweepSpec:
    """``n_runs`` DEM runs (outer/inner fault x speed x load), ``duration_s`` at 12 kHz."""
    n_load = max(1, n_runs // 16)
    return SweepSpec.from_dict(
        {
            "sweep": {"channels": ["acc_x", "acc_y"], "label": "fault"},
            "base": {"model": "dem", "duration_s": duration_s, "fs_hz": 12000.0},
            "axes": {
                "fault": ["outer", "inner"],
                "rpm": {"start": 1700.0, "stop": 1800.0, "num": 8},
                "fy_n": {"start": 50.0, "stop": 200.0, "num": n_load},
            },
        },
        origin="bench",
    )


def load() -> str:
    return f"{os.getloadavg()[0]:.2f}"


def wait_load(max_load: float, wait_s: float) -> None:
    t0 = time.monotonic()
    while os.getloadavg()[0] > max_load and time.monotonic() - t0 < wait_s:
        time.sleep(5.0)


def report(rep, w: int, r: int, n: int, serial: float, la: str) -> None:
    """Print one measurement and keep its CPU overhead ratio on ``rep``."""
    cpu_w = rep.worker_cpu_s
    cpu_all = cpu_w + rep.client_cpu_s
    assert rep.n_ok == n, rep
    ov = (w * rep.wall_s - rep.compute_s) / n
    ov_base = (w * rep.wall_s - serial) / n
    ov_cpu = (cpu_all - rep.compute_cpu_s) / n
    rep.ov_cpu = ov_cpu / (rep.compute_cpu_s / n)  # type: ignore[attr-defined]
    est = "-" if rep.estimate_s is None else f"{1e3 * rep.estimate_s:.1f}"
    print(
        f"repeat {r}, {w} worker(s): wall {rep.wall_s:.3f} s, {n / rep.wall_s:6.1f} "
        f"runs/s, compute {1e3 * rep.compute_s / n:.2f} ms/run (CPU "
        f"{1e3 * rep.compute_cpu_s / n:.2f}; estimated {est}), commit "
        f"{1e3 * rep.commit_s / n:.3f} ms/run, {rep.tasks} tasks; overhead "
        f"{1e3 * ov:.2f} ms/run = {100 * ov / (rep.compute_s / n):.1f} % of "
        f"compute ({100 * ov_base / (serial / n):.1f} % vs serial baseline); "
        f"CPU overhead {1e3 * ov_cpu:.2f} ms/run = {100 * rep.ov_cpu:.1f} % of "
        f"CPU compute (workers {1e3 * (cpu_w - rep.compute_cpu_s) / n:.2f}, "
        f"client {1e3 * rep.client_cpu_s / n:.2f}); setup {rep.setup_s:.2f} s; "
        f"load {la} -> {load()}"
    )


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--repeats", type=int, default=5)
    ap.add_argument("--runs", type=int, default=64)
    ap.add_argument("--runs-per-task", type=int, default=None)
    ap.add_argument("--max-load", type=float, default=float("inf"))
    ap.add_argument("--wait-s", type=float, default=600.0)
    ap.add_argument("--duration-s", type=float, default=0.5, help="Simulated time per run [s].")
    ap.add_argument("--dir", default=None, help="Where the datasets go [a new temporary dir].")
    args = ap.parse_args()
    spec = make_spec(args.runs, args.duration_s)
    n = spec.n_runs
    print(
        f"sweep: {n} runs of DEM, {args.duration_s:g} s at 12 kHz "
        f"({round(args.duration_s * 12000)} samples), channels acc_x, acc_y"
    )
    print(f"machine: {os.cpu_count()} cores; load average at start {load()}")
    scen = spec.scenarios()
    simulate(scen[0])  # compile or load the Numba cache before timing
    wait_load(args.max_load, args.wait_s)
    base = []
    for _ in range(args.repeats):
        t0 = time.perf_counter()
        for sc in scen:
            simulate(sc)
        base.append(time.perf_counter() - t0)
    serial = min(base)
    print(
        f"serial baseline (this process, no Dask, no writing): {serial:.3f} s = "
        f"{1e3 * serial / n:.2f} ms per run (best of {args.repeats}; all "
        + ", ".join(f"{b:.3f}" for b in base)
        + f"); load {load()}"
    )
    tmp = Path(tempfile.mkdtemp(prefix="bench_sweep_", dir=args.dir))
    print(f"datasets in {tmp}")
    results: dict[int, list] = {1: [], 2: []}
    try:
        # both clusters stay up and the worker counts alternate, so that a slow drift of the
        # machine's speed (other jobs, the VM's host) does not fall on one worker count only;
        # the idle cluster's heartbeats (~1 % of a core) burden both measurements
        t0 = time.perf_counter()
        with connect(workers=1) as (c1, _), connect(workers=2) as (c2, _):
            print(f"two clusters (1 and 2 workers) started in {time.perf_counter() - t0:.2f} s")
            for c in (c1, c2):
                c.run(worker_hello)  # kernels loaded on every worker
            for r in range(args.repeats):
                for w, client in ((1, c1), (2, c2)):
                    wait_load(args.max_load, args.wait_s)
                    out = tmp / f"w{w}_r{r}.zarr"
                    la = load()
                    rep = run_sweep(
                        spec, out, client=client, runs_per_task=args.runs_per_task, measure_cpu=True
                    )
                    report(rep, w, r, n, serial, la)
                    results[w].append(rep)
                    shutil.rmtree(out)
                a, b = results[1][-1], results[2][-1]
                print(f"repeat {r}: 2-worker / 1-worker throughput {a.wall_s / b.wall_s:.2f}")
    finally:
        shutil.rmtree(tmp, ignore_errors=True)
    print("\nsummary (median over repeats):")
    thr = {w: statistics.median(n / r.wall_s for r in reps) for w, reps in results.items()}
    for w, reps in results.items():
        ov = statistics.median(
            (w * r.wall_s - r.compute_s) / r.compute_s for r in reps
        )  # per-run overhead / per-run compute
        ovc = statistics.median(r.ov_cpu for r in reps)
        print(
            f"  {w} worker(s): {thr[w]:.1f} runs/s, overhead {100 * ov:.1f} % of compute per run "
            f"(wall), {100 * ovc:.1f} % (CPU)"
        )
    pairs = sorted(a.wall_s / b.wall_s for a, b in zip(results[1], results[2], strict=True))
    print(
        f"  2-worker / 1-worker throughput: {thr[2] / thr[1]:.2f} (ratio of the medians; target "
        f">= 1.8); per repeat {', '.join(f'{p:.2f}' for p in pairs)}"
    )
    print(f"load average at end {load()}")


if __name__ == "__main__":
    main()
