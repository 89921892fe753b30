"""An axial load in the ring models (``axial_load_n``, DEM and TVSM): the balls run at a contact
angle given by the Jones geometry, enough axial load loads every ball, and the fault lines move
with the angle (docs/models.md, "Axial load").

Reference values: the static state is compared with the Jones 5-DOF solver of the quasi-static
model (an independent implementation of the same geometry, Jones 1960; Harris & Kotzalas 2007
vol. 2 §3: seed QS5); the fault-line positions with the kinematic formulae
(``BPFO = Z f_s/2 (1 - d cos(alpha)/D)``, Harris & Kotzalas 2007 vol. 1 §8).
"""

from __future__ import annotations

import math
from dataclasses import replace

import numpy as np
import pytest
from numpy.testing import assert_allclose, assert_array_equal

from bearingsim import simulate
from bearingsim.catalog import resolve_bearing
from bearingsim.config import RingScenario
from bearingsim.dynamics.ring.scenario import model_inputs
from bearingsim.errors import ConfigError
from bearingsim.geometry import characteristic_frequencies, contact_angle_from_order

B = resolve_bearing("6205-cwru")
RPM = 1750.0


@pytest.mark.parametrize(("fa", "clearance"), [(10.0, None), (100.0, None), (100.0, -5e-6)])
def test_static_state_is_the_jones_equilibrium(fa, clearance):
    """At t = 0 the DEM's own static solve (the radial balance of its compiled kernel, at the
    held axial offset z) gives the ring displacement and every ball's load of the Jones 5-DOF
    equilibrium of the same forces with the tilts held (quasistatic.jones), to 1e-9 relative:
    the kernel's contact-angle geometry is the quasi-static model's."""
    from bearingsim.quasistatic.jones import run_quasi_static

    sc = RingScenario(
        model="dem",
        bearing="6205-cwru",
        duration_s=0.002,
        fs_hz=12000.0,
        axial_load_n=fa,
        clearance_m=clearance,
        per_ball=True,
    )
    inp = model_inputs(sc)
    r = simulate(sc)
    sol = run_quasi_static(
        inp.bearing,
        0.0,
        inp.fx,
        inp.fy,
        fa,
        clearance=inp.diametral_clearance,
        stiffness=inp.k_ball,
        tilt_free=False,
    )
    assert_allclose(r.meta["resolved"]["initial_displacement_m"], sol.displacement[0, :2],
                    rtol=1e-9)  # fmt: skip
    assert_allclose(np.asarray(r["ball_load"])[0], sol.ball_loads[0], rtol=1e-9)
    assert r.meta["axial"]["offset_z_m"] == pytest.approx(sol.displacement[0, 2], rel=1e-12)
    angles = np.asarray(r.meta["axial"]["ball_contact_angles_deg"])
    assert_allclose(angles, np.degrees(sol.contact_angles[0]), rtol=1e-12)
    if fa >= 100.0:  # (10 N with the seed's 10 N + 50 N radial load leaves four balls free)
        assert (np.asarray(r["ball_load"])[0] > 0.0).all()  # every ball loaded


@pytest.mark.parametrize("fa", [20.0, 300.0])
@pytest.mark.parametrize("fault", ["outer", "inner"])
def test_fault_lines_move_with_the_contact_angle(fa, fault):
    """The cage turns at the FTF of the load-weighted mean contact angle, so the squared
    envelope spectrum's fault line (4 s, refined) reads that angle back through
    ``contact_angle_from_order`` within 0.5 deg (the model's angle: 9.3 deg at 20 N, 13.6 deg
    at 300 N), and the result's kinematics are those of that angle."""
    from bearingsim.signal import EnvelopeKind, envelope_spectrum, strongest_peak

    sc = dict(model="dem", bearing="6205-cwru", fault=fault, rpm=RPM, duration_s=4.0,
              fs_hz=12000.0, axial_load_n=fa)  # fmt: skip
    r = simulate(sc)
    alpha = r.meta["axial"]["contact_angle_deg"]
    assert 9.0 < alpha < 14.0
    fr = RPM / 60.0
    k0 = characteristic_frequencies(B, fr)
    line = "bpfo" if fault == "outer" else "bpfi"
    es = envelope_spectrum(np.asarray(r["acc_y"], float), 12000.0, (1000.0, 5000.0),
                           EnvelopeKind.SQUARED)  # fmt: skip
    pk = strongest_peak(es, getattr(k0, f"{line}_hz"), 0.02)
    read = math.degrees(contact_angle_from_order(B, line, pk.freq / fr))
    assert read == pytest.approx(alpha, abs=0.5)
    at_alpha = characteristic_frequencies(replace(B, contact_angle=math.radians(alpha)), fr)
    assert r.meta["kinematics"][f"{line}_hz"] == pytest.approx(getattr(at_alpha, f"{line}_hz"))
    assert read > 3.0  # far from the radial model's alpha = 0


def test_an_axial_load_strikes_an_outer_defect_at_12_oclock():
    """An outer-race defect opposite the radial load (@12) under the catalogue clearance and
    the seed's 50 N is never struck: the sensor signal is the healthy one bit for bit and the
    diagnosis says "none". 20 N of axial load loads every ball (9.3 deg): the same defect is
    struck and diagnosed "outer" (DEM with the side-by-side's realism through cwru-de-12k,
    2 s), as the CWRU @12 records are (Smith & Randall 2015)."""
    from bearingsim.side_by_side import CWRU_DEPTH_M, REALISM
    from bearingsim.signal.fused import diagnose_fused

    def run(fault, edge, fa):
        sc = dict(model="dem", bearing="6205-cwru", fault=fault, **REALISM,
                  defect_width_m=0.007 * 0.0254, defect_depth_m=CWRU_DEPTH_M,
                  defect_edge_angle_deg=edge, rpm=RPM, duration_s=2.0, fs_hz=12000.0, seed=3,
                  rig="cwru-de-12k", axial_load_n=fa)  # fmt: skip
        return np.asarray(simulate(sc)["acc_sensor"], dtype=float)

    healthy = run("none", 10.0, 0.0)
    at12 = run("outer", 190.0, 0.0)
    assert_array_equal(at12, healthy)
    loaded = run("outer", 190.0, 20.0)
    d = diagnose_fused(loaded, 12000.0, B, RPM / 60.0)
    assert d.diagnosis == "outer" and d.confidence >= 0.8, (d.diagnosis, d.confidence)
    d0 = diagnose_fused(run("none", 10.0, 20.0), 12000.0, B, RPM / 60.0)
    assert d0.diagnosis == "none"


def test_tvsm_takes_an_axial_load():
    """The TVSM's quasi-static table is solved with the same geometry: its static start equals
    the DEM's, and a short run is finite."""
    out = {}
    for model in ("dem", "tvsm"):
        r = simulate(dict(model=model, bearing="6205-cwru", fault="outer", duration_s=0.01,
                          fs_hz=12000.0, axial_load_n=50.0))  # fmt: skip
        assert np.isfinite(np.asarray(r["acc_y"])).all()
        out[model] = r.meta["resolved"]["initial_displacement_m"]
    assert_allclose(out["tvsm"], out["dem"], rtol=1e-9)


@pytest.mark.parametrize(
    ("keys", "match"),
    [
        (
            dict(model="vsm", axial_load_n=10.0),
            r"axial_load_n = 10 N is out of range for model vsm",
        ),
        (dict(model="dem", axial_load_n=-1.0), r"axial_load_n = -1"),
        (dict(model="dem", axial_load_n=float("nan")), r"axial_load_n"),
        (dict(model="dem", axial_load_n=1e6), r"static"),
    ],
)
def test_bad_axial_load_is_one_line(keys, match):
    """A negative or NaN axial load, one the VSM cannot take, and one above twice the static
    capacity (ISO 76 equivalent load) are one-line errors before any work."""
    from bearingsim.dynamics.ring.scenario import plan_ring

    with pytest.raises(ConfigError, match=match) as e:
        plan_ring(RingScenario(bearing="6205-cwru", **keys))
    assert "\n" not in str(e.value)


def test_cli_refuses_an_axial_load_for_the_vsm(run_cli, tmp_path):
    """``bearingsim simulate --model vsm --set axial_load_n=10``: one line, exit 2, no file."""
    out = tmp_path / "x.nc"
    r = run_cli("simulate", "--model", "vsm", "--set", "axial_load_n=10", "-o", str(out))
    assert r.code == 2
    assert "axial_load_n" in r.err and len(r.err.strip().splitlines()) == 1
    assert not out.exists()
