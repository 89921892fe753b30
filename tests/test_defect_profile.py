"""The ring models' ``defect_profile``: the seed VSM's rectangular drop (default) or the ball
resting on the slot's nearer edge (``geometric``, the rotor model's rule).

Reference values: seed VSM eqs. (1)-(3) (``h_min``, ``Delta_beta``; via
:func:`bearingsim.geometry.defect_geometry`) and eq. (2) with ``b/2`` replaced by the distance
``e`` to the nearer edge, written out below with NumPy.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from bearingsim import simulate
from bearingsim.catalog import get_bearing
from bearingsim.config import RingScenario
from bearingsim.dynamics.ring import _balance as bl
from bearingsim.dynamics.ring.base import ModelInputs
from bearingsim.errors import ConfigError
from bearingsim.geometry import Defect, defect_geometry
from bearingsim.signal.envelope import envelope_spectrum

B = get_bearing("6205-cwru")
R_BALL = 0.5 * B.element_diameter


def _eq2(e, rr, sg):
    """Seed VSM eq. (2) with b/2 -> e: ball chord plus/minus raceway chord [m]."""
    return (R_BALL - math.sqrt(R_BALL**2 - e * e)) + sg * (rr - math.sqrt(rr * rr - e * e))


@pytest.mark.parametrize("race", ["outer", "inner"])
@pytest.mark.parametrize("width_in", [0.007, 0.014, 0.021])
def test_geometric_drop_is_eq2_along_the_path(race, width_in):
    """0 at both edges, seed VSM's h_min at the centre, eq. (2) with the nearer edge's distance
    in between; symmetric about the centre."""
    b = width_in * 0.0254
    depth = 0.011 * 0.0254
    g = defect_geometry(B, Defect(race, b, depth))
    rr = B.outer_raceway_radius if race == "outer" else B.inner_raceway_radius
    sg = -1.0 if race == "outer" else 1.0
    db = g.delta_beta

    def drop(r):
        return bl.geometric_drop(r, db, rr, R_BALL, rr, sg, 0.5 * b, depth)

    assert drop(0.0) == 0.0 and drop(db) == 0.0 and drop(1.5 * db) == 0.0
    assert drop(0.5 * db) == pytest.approx(g.h_min, rel=1e-12)
    for s in (0.1, 0.3, 0.45):
        e = 0.5 * b - rr * abs(s * db - 0.5 * db)
        assert drop(s * db) == pytest.approx(min(_eq2(e, rr, sg), depth), rel=1e-12)
        assert drop(s * db) == pytest.approx(drop((1.0 - s) * db), rel=1e-9)
    assert drop(0.01 * db) < 0.01 * g.h_min  # continuous at the edge (the rectangle jumps)


def test_shallow_wide_defect_is_capped_by_its_depth():
    """A 2 mm slot 5 um deep: the ball reaches the bottom, which caps the drop (eq. (1))."""
    b, depth = 2e-3, 5e-6
    g = defect_geometry(B, Defect("outer", b, depth))
    rr = B.outer_raceway_radius
    d = [bl.geometric_drop(s * g.delta_beta, g.delta_beta, rr, R_BALL, rr, -1.0, b / 2, depth)
         for s in np.linspace(0.3, 0.7, 9)]  # fmt: skip
    assert max(d) == depth == g.h_min


def _run(profile, model="vsm", fault="outer", **kw):
    sc = dict(model=model, bearing="6205-cwru", fault=fault, duration_s=0.5, fs_hz=12000.0)
    return simulate({**sc, "antialias": True, "defect_profile": profile, **kw})


@pytest.mark.parametrize("model", ["vsm", "dem"])
def test_geometric_profile_is_gentler_and_keeps_the_fault_line(model):
    """The ball descends from the edge instead of stepping down at both edges: the impacts
    carry less energy (RMS at most 0.6 of the rectangle's; measured 0.39-0.42), the BPFO series
    stays (envelope line > 20 dB over the median below 600 Hz)."""
    rect, geo = _run("rectangular", model), _run("geometric", model)
    a_r, a_g = np.asarray(rect["acc_y"]), np.asarray(geo["acc_y"])
    assert a_g.std() < 0.6 * a_r.std()
    fs = geo.meta["fs_hz"]
    bpfo = geo.meta["kinematics"]["bpfo_hz"]
    s = envelope_spectrum(a_g - a_g.mean(), fs, (500.0, 0.475 * fs))
    f, amp = s.freq, s.amplitude
    line = amp[(f > 0.98 * bpfo) & (f < 1.02 * bpfo)].max()
    assert 20 * np.log10(line / np.median(amp[(f > 20) & (f < 600)])) > 20.0
    if model == "vsm":  # the tabulated static balance converged along the drop profile
        assert geo.meta["static_residual_max"] < 1e-9


def test_geometric_profile_ball_defect_runs_and_differs():
    rect, geo = _run("rectangular", fault="ball"), _run("geometric", fault="ball")
    assert np.asarray(geo["acc_y"]).std() < np.asarray(rect["acc_y"]).std()


def test_default_is_the_seed_rectangle():
    assert RingScenario().defect_profile == "rectangular"
    a = _run("rectangular", duration_s=0.05)
    b = simulate(dict(model="vsm", bearing="6205-cwru", fault="outer", duration_s=0.05,
                      fs_hz=12000.0, antialias=True))  # fmt: skip
    np.testing.assert_array_equal(a["acc_y"], b["acc_y"])


def test_bad_profile_and_profile_with_gamma_one_line():
    with pytest.raises(ConfigError, match=r"^defect_profile = 'smooth' is invalid; valid: "):
        RingScenario(defect_profile="smooth")
    with pytest.raises(ConfigError, match=r"defect_profile = 'geometric' with retention_factor"):
        ModelInputs(B, 10.0, 50.0, 29.0, Defect("outer"), retention_factor=0.4,
                    profile="geometric")  # fmt: skip
    with pytest.raises(ConfigError, match=r"defect_profile = 'geometric' with retention_factor"):
        simulate(dict(model="vsm", fault="outer", duration_s=0.01, retention_factor=0.4,
                      defect_profile="geometric"))  # fmt: skip
    assert math.isfinite(_run("geometric", duration_s=0.02).meta["static_residual_max"])


def test_rotor_takes_the_key_too():
    """The rotor model's defects are geometric by default (docs/models.md, ROTOR); the same key
    chooses the rectangle, and a bad value is one line."""
    from bearingsim.config import RotorScenario

    assert RotorScenario().defect_profile == "geometric"
    sc = dict(model="rotor", de_fault="outer", duration_s=0.05, fs_hz=12000.0)
    geo = simulate(sc)
    rect = simulate({**sc, "defect_profile": "rectangular"})
    assert not np.array_equal(np.asarray(geo["acc_y"]), np.asarray(rect["acc_y"]))
    np.testing.assert_array_equal(
        np.asarray(geo["acc_y"]),
        np.asarray(simulate({**sc, "defect_profile": "geometric"})["acc_y"]),
    )
    with pytest.raises(ConfigError, match=r"^defect_profile = 'flat' is invalid; valid: "):
        RotorScenario(defect_profile="flat")
