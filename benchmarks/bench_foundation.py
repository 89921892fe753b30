"""Foundation benchmarks (issue 2 targets): load distribution at 3,600 cage angles for the 6205
(<= 0.2 s) and exact Hertz contact for 10,000 loads (<= 0.1 s). Warm timings, best of 5.

Run: ``python benchmarks/bench_foundation.py``
"""

from __future__ import annotations

import numpy as np
from _timing import best

from bearingsim import get_bearing
from bearingsim.contact.hertz import ball_contact, ellipticity
from bearingsim.load_distribution import radial_load_distribution


def main() -> None:
    b = get_bearing("6205")
    cage = np.linspace(0.0, 2 * np.pi, 3600, endpoint=False)
    radial_load_distribution(b, 10.0, 50.0, cage[:2])  # warm (compile / load cache)
    t_free = best(lambda: radial_load_distribution(b, 10.0, 50.0, cage), warm=False)
    t_line = best(
        lambda: radial_load_distribution(b, 10.0, 50.0, cage, motion="load_line"), warm=False
    )
    loads = np.linspace(1.0, 5000.0, 10_000)
    ball_contact(b, loads[:2], "inner")

    def hertz_cold_geometry():
        ellipticity.cache_clear()  # include the exact ellipticity solve in the timing
        ball_contact(b, loads, "inner")

    t_hertz = best(hertz_cold_geometry, warm=False)
    print(
        f"load distribution, 6205, 3600 cage angles, free ring : {t_free * 1e3:8.2f} ms "
        f"(target <= 200 ms)"
    )
    print(f"load distribution, 6205, 3600 cage angles, load line : {t_line * 1e3:8.2f} ms")
    print(
        f"exact Hertz point contact, 10,000 loads              : {t_hertz * 1e3:8.2f} ms "
        f"(target <= 100 ms)"
    )


if __name__ == "__main__":
    main()
