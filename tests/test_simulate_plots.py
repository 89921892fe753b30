"""Plot methods of the fault-dynamics results return figures without warnings (Agg)."""

from __future__ import annotations

import math

import matplotlib

matplotlib.use("Agg")

import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import bearingsim  # noqa: E402
from bearingsim.dynamics.ring.base import ModelInputs  # noqa: E402
from bearingsim.dynamics.ring.trace import stiffness_trace  # noqa: E402
from bearingsim.geometry import defect_at_edge  # noqa: E402
from bearingsim.signal import fast_kurtogram  # noqa: E402


def test_package_level_simulate_and_plots():
    res = bearingsim.simulate(bearingsim.Scenario(fault="outer", rpm=1796.0, duration_s=0.1))
    assert isinstance(res, bearingsim.SimulationResult)
    figs = [res.plot_time(t_range=(0.0, 0.05)), res.plot_stiffness(), res.plot_envelope()]
    kg = fast_kurtogram(res["acc_y"], res.fs_hz, min_bandwidth_hz=600.0)
    figs.append(kg.plot())
    inp = ModelInputs(
        bearingsim.get_bearing("6205"),
        10.0,
        50.0,
        1750 / 60,
        defect_at_edge(bearingsim.get_bearing("6205"), "outer", 1e-3, 1e-3, math.radians(10)),
        retention_factor=0.38,
    )
    tr = stiffness_trace(inp, np.radians(np.arange(0, 360, 0.5)))
    figs += [tr.plot_total(), tr.plot_ball(5), tr.plot_balls([4, 5, 6])]
    for f in figs:
        assert isinstance(f, matplotlib.figure.Figure) and f.axes
        plt.close(f)
