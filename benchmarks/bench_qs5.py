"""Benchmark for issue 4 (QS5): equilibrium + 5x5 stiffness at 360 cage positions of one
revolution, 6205 with both ring misalignments. Target: <= 0.2 s warm.

Run: ``PYTHONPATH=src python benchmarks/bench_qs5.py``
"""

from __future__ import annotations

import statistics
import time

import numpy as np

from bearingsim.catalog import get_bearing
from bearingsim.quasistatic import Misalignment, run_iso16281, run_quasi_static, stiffness_vs_cage


def timeit(fn, repeat: int = 7) -> tuple[float, float]:
    ts = []
    for _ in range(repeat):
        t0 = time.perf_counter()
        fn()
        ts.append(time.perf_counter() - t0)
    return min(ts), statistics.median(ts)


def main() -> None:
    b = get_bearing("6205")
    mis = Misalignment(outer_tilt=3e-3, outer_azimuth=0.3, inner_tilt=3e-3, inner_azimuth=0.0)
    cage = 2 * np.pi * np.arange(360) / 360

    t0 = time.perf_counter()
    sol = run_quasi_static(b, cage, 0.0, 500.0, misalignment=mis)
    print(f"first call (numba cache load or compile): {time.perf_counter() - t0:.3f} s")
    print(
        f"  Newton iterations per position: max {sol.iterations.max()}, "
        f"mean {sol.iterations.mean():.2f}; max relative residual {sol.residual.max():.2e}"
    )

    tmin, tmed = timeit(lambda: run_quasi_static(b, cage, 0.0, 500.0, misalignment=mis))
    print(
        f"equilibrium + 5x5 stiffness, 360 positions, both misalignments (jones): "
        f"min {tmin * 1e3:.2f} ms, median {tmed * 1e3:.2f} ms  (target <= 200 ms)"
    )
    tmin, tmed = timeit(
        lambda: stiffness_vs_cage(b, 0.0, 500.0, cage_revs=1, points_per_rev=360, misalignment=mis)
    )
    print(
        f"  + radial/axial/tilt series and labelled spectra (StiffnessResult): "
        f"min {tmin * 1e3:.2f} ms, median {tmed * 1e3:.2f} ms"
    )
    tmin, tmed = timeit(
        lambda: stiffness_vs_cage(
            b, 0.0, 500.0, cage_revs=10, points_per_rev=360, misalignment=mis
        ),
        3,
    )
    print(
        f"  CLI default size (10 revs x 360): min {tmin * 1e3:.2f} ms, median {tmed * 1e3:.2f} ms"
    )
    tmin, tmed = timeit(lambda: run_iso16281(b, cage, 0.0, 500.0, misalignment=mis), 3)
    print(
        f"ISO/TS 16281 method (scipy hybr + FD stiffness), same 360 positions: "
        f"min {tmin * 1e3:.1f} ms, median {tmed * 1e3:.1f} ms (not a target)"
    )


if __name__ == "__main__":
    main()
