"""Benchmark of the diagnosis (issue 17).

Prints
1. the warm in-process time of all methods (DRS, CPW, kurtogram + infogram, four squared
   envelope spectra, the cyclic-coherence view, line search, fusion) on one 10 s 12 kHz
   record (CWRU 169) and the share of each step; issue 17's target: <= 0.2 s on one core;
   and of the contact-angle report ``analyze`` adds to a race-fault verdict;
2. the wall time of one ``bearingsim analyze`` call on every ``.mat`` of ``../shared/data/cwru``
   (start-up included, ``--json``, all cores); target: <= 15 s on 2 cores;
3. the wall time of one call on one record (CWRU 169), start-up included (the median of
   ``--repeats`` calls): issue 17 measured 3-4 s per call, 1.6 s of it start-up (no target).

Run:  PYTHONPATH=src python benchmarks/bench_diagnosis.py [--repeats 5] [--data DIR]

Prints plain text; writes nothing.
"""

from __future__ import annotations

import argparse
import os
import statistics
import subprocess
import sys
import time
from pathlib import Path

os.environ.setdefault("OMP_NUM_THREADS", "1")
os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")

from _timing import best  # noqa: E402

from bearingsim.catalog import resolve_bearing  # noqa: E402
from bearingsim.signal import load_signal  # noqa: E402
from bearingsim.signal.benchmark import (  # noqa: E402
    cepstral_prewhitening,
    discrete_random_separation,
)
from bearingsim.signal.coherence import enhanced_envelope_spectrum  # noqa: E402
from bearingsim.signal.contact_angle import estimate_contact_angle  # noqa: E402
from bearingsim.signal.fused import diagnose_fused  # noqa: E402
from bearingsim.signal.kurtogram import band_maps  # noqa: E402

ROOT = Path(__file__).resolve().parents[1]
DATA = ROOT.parent / "shared" / "data" / "cwru"


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--repeats", type=int, default=5)
    ap.add_argument("--data", type=Path, default=DATA)
    a = ap.parse_args()
    path = a.data / "12k_Drive_End_IR014_0_169.mat"
    if not path.is_file():
        print(f"error: data = {str(a.data)!r} lacks {path.name}", file=sys.stderr)
        return 2
    rec = load_signal(path, channel="DE")
    b = resolve_bearing("6205-cwru")
    fr = rec.rpm / 60.0
    x, fs = rec.x, rec.fs
    rnd, _ = discrete_random_separation(x)
    steps = {
        "DRS": lambda: discrete_random_separation(x),
        "CPW": lambda: cepstral_prewhitening(x),
        "kurtogram + infogram": lambda: band_maps(rnd, fs, min_bandwidth_hz=3 * 5.4152 * fr + fr),
        "cyclic coherence (EES)": lambda: enhanced_envelope_spectrum(rnd, fs, 3 * 5.4152 * fr + fr),
    }
    total = best(lambda: diagnose_fused(x, fs, b, fr), a.repeats)
    print(f"record {path.name}: {x.size} samples at {fs:.0f} Hz ({x.size / fs:.2f} s)")
    print(f"all methods + fusion, warm, one core: {total * 1e3:7.1f} ms   (target <= 200 ms)")
    for name, fn in steps.items():
        t = best(fn, a.repeats)
        print(f"  {name:<22} {t * 1e3:7.1f} ms  ({100 * t / total:4.1f} %)")
    t_ca = best(lambda: estimate_contact_angle(x, fs, b, "inner", fr), a.repeats)
    print(
        f"contact-angle report (analyze, race-fault verdicts): {t_ca * 1e3:7.1f} ms  "
        f"(with the methods: {(total + t_ca) * 1e3:.1f} ms)"
    )
    files = sorted(str(p) for p in a.data.glob("*.mat"))
    cmd = [sys.executable, "-m", "bearingsim", "analyze", *files, "--json"]
    env = dict(os.environ)
    env.pop("OMP_NUM_THREADS", None)
    env.pop("OPENBLAS_NUM_THREADS", None)
    t0 = time.perf_counter()
    r = subprocess.run(cmd, capture_output=True, text=True, env=env)
    wall = time.perf_counter() - t0
    n_ok = sum(1 for line in r.stdout.splitlines() if '"diagnosis"' in line)
    print(
        f"analyze {len(files)} records in one call ({os.cpu_count()} cores seen): {wall:6.2f} s "
        f"wall, start-up included (target <= 15 s on 2 cores); {n_ok} diagnosed, "
        f"exit {r.returncode}"
    )
    one = [sys.executable, "-m", "bearingsim", "analyze", str(path), "--json"]
    walls = []
    for _ in range(max(a.repeats, 1)):
        t0 = time.perf_counter()
        subprocess.run(one, capture_output=True, text=True, env=env, check=True)
        walls.append(time.perf_counter() - t0)
    print(
        f"analyze one record ({path.name}) in one call: {statistics.median(walls):5.2f} s wall "
        f"(median of {len(walls)}; start-up included; issue 17 measured 3-4 s)"
    )
    return 0


if __name__ == "__main__":
    sys.exit(main())
