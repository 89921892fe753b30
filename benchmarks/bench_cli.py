"""CLI start-up benchmark (issue 13, item 8): median warm wall time of ``bearingsim --version``,
``--help``, ``bearings`` and ``info 6205-cwru --rpm 1797`` beside a bare
``python -c "import numpy"`` on the same machine, each a new process. Targets: <= 0.3 s and
<= 2.5x the bare NumPy import.

Run: ``python benchmarks/bench_cli.py [--repeat N]`` (not a test: timings depend on the machine
and its load; the median of N runs after one warm-up run each).
"""

from __future__ import annotations

import argparse
import os
import statistics
import subprocess
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]

CASES = {
    'python -c "import numpy"': ["-c", "import numpy"],
    "bearingsim --version": ["-m", "bearingsim", "--version"],
    "bearingsim --help": ["-m", "bearingsim", "--help"],
    "bearingsim bearings": ["-m", "bearingsim", "bearings"],
    "bearingsim info 6205-cwru --rpm 1797": [
        "-m",
        "bearingsim",
        "info",
        "6205-cwru",
        "--rpm",
        "1797",
    ],
}
TARGET_S = 0.3
TARGET_RATIO = 2.5


def wall(args: list[str], repeat: int) -> float:
    """Median wall time [s] of ``python ARGS`` over ``repeat`` runs after one warm-up run."""
    env = {**os.environ, "PYTHONPATH": str(ROOT / "src")}
    cmd = [sys.executable, *args]
    subprocess.run(cmd, env=env, capture_output=True, check=True)  # warm the OS file cache
    ts = []
    for _ in range(repeat):
        t0 = time.perf_counter()
        subprocess.run(cmd, env=env, capture_output=True, check=True)
        ts.append(time.perf_counter() - t0)
    return statistics.median(ts)


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--repeat", type=int, default=15, help="runs per case (median)")
    a = ap.parse_args()
    times = {name: wall(args, a.repeat) for name, args in CASES.items()}
    base = times['python -c "import numpy"']
    print(f"median wall time of {a.repeat} warm runs, each a new Python process:")
    print(f"{'command':<40}{'wall s':>9}{'/ numpy':>9}   target")
    for name, t in times.items():
        if name == 'python -c "import numpy"':
            print(f"{name:<40}{t:>9.3f}{1.0:>9.2f}   (reference)")
            continue
        ok = t <= TARGET_S and t / base <= TARGET_RATIO
        print(
            f"{name:<40}{t:>9.3f}{t / base:>9.2f}   <= {TARGET_S} s and <= {TARGET_RATIO}x"
            f"  {'ok' if ok else 'MISSED'}"
        )


if __name__ == "__main__":
    main()
