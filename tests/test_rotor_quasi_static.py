"""Quasi-static (massless) balls in the bearing–rotor–housing model (``ball_inertia = false``):
the series Hertz law of the kernel, the static state, and the signals beside the seed's model
with ball masses (the reference here is that model, ours: docs/validation.md, ROTOR,
"Quasi-static balls")."""

from __future__ import annotations

import math

import numpy as np
import pytest
from numpy.testing import assert_allclose
from scipy.stats import kurtosis

from bearingsim.config import Scenario
from bearingsim.contact.hertz import ball_contact
from bearingsim.dynamics.rotor.config import G0, cwru_rotor_config
from bearingsim.dynamics.rotor.model import evaluate_rhs, pack_model, simulate_rotor, static_state
from bearingsim.dynamics.rotor.scenario import rotor_config_from_scenario
from bearingsim.errors import ConfigError
from bearingsim.geometry import Defect, Race
from bearingsim.signal.envelope import envelope_spectrum

FS = 12000.0


def _metrics(cfg, fault_hz: float, duration: float = 0.5):
    """RMS [m/s^2], kurtosis [-] and envelope line at ``fault_hz`` [m/s^2] (fixed 0.5–5.5 kHz
    band, the maximum within +/- 2 %) of the DE housing's y acceleration, and the step count."""
    r = simulate_rotor(cfg, duration=duration, sample_rate=FS)
    a = r.channel("DE", "y")
    a = a - a.mean()
    spec = envelope_spectrum(a, FS, (500.0, 5500.0))
    w = (spec.freq >= 0.98 * fault_hz) & (spec.freq <= 1.02 * fault_hz)
    rms = float(np.sqrt(np.mean(a * a)))
    return rms, float(kurtosis(a, fisher=False)), float(spec.amplitude[w].max()), r.meta


def test_ball_force_is_hertz_of_the_two_contacts_in_series():
    """Every ball carries ``k_e delta^1.5 + c/2 d(delta)/dt`` through both contacts, ``delta``
    the total approach of shaft node and housing along the ball's azimuth less the clearance,
    ``k_e = (k_in^-2/3 + k_out^-2/3)^-3/2`` (Harris & Kotzalas 2007, eq. 7.13's series rule);
    checked against NumPy at a perturbed state with a moving shaft."""
    cfg = cwru_rotor_config(3, ball_inertia=False)
    m = pack_model(cfg, 5000.0, ball_forces=True)
    y0 = static_state(m, cfg)
    assert m.n_pos == m.n_r + 4, "no ball coordinates"
    y = y0.copy()
    nr, npos = m.n_r, m.n_pos
    y[0:2] += (1.5e-6, -2.0e-6)  # DE shaft node
    y[nr : nr + 2] += (0.3e-6, 0.4e-6)  # DE housing
    y[npos : npos + 2] = (1e-3, -2e-3)  # DE shaft node velocity [m/s]
    y[npos + nr : npos + nr + 2] = (-5e-4, 1e-4)  # DE housing velocity
    t = 1.3e-3
    _, aux = evaluate_rhs(m, t, y)
    b = cfg.de.bearing
    z = b.n_elements
    kin = ball_contact(b, 1.0, Race.INNER).k_hertz
    kout = ball_contact(b, 1.0, Race.OUTER).k_hertz
    ke = (kin ** (-2 / 3) + kout ** (-2 / 3)) ** -1.5
    wc = 2 * math.pi * cfg.kinematics()["DE"].ftf_hz
    psi = cfg.de.first_ball_angle + wc * t + 2 * math.pi * np.arange(z) / z
    e = np.stack([np.sin(psi), np.cos(psi)], 1)
    de = np.stack([np.cos(psi), -np.sin(psi)], 1) * wc
    ur = y[0:2] - y[nr : nr + 2]
    vr = y[npos : npos + 2] - y[npos + nr : npos + nr + 2]
    d = e @ ur - 0.5 * b.diametral_clearance
    rate = e @ vr + de @ ur
    q = np.where(d > 0, ke * np.clip(d, 0, None) ** 1.5 + 0.5 * cfg.de.contact_damping * rate, 0)
    q = np.clip(q, 0, None)
    assert np.count_nonzero(q) >= 2
    assert_allclose(aux[4 : 4 + z], q, rtol=1e-12, atol=1e-12 * q.max(), err_msg="Q_in")
    assert_allclose(aux[4 + z : 4 + 2 * z], q, rtol=1e-12, atol=1e-12 * q.max(), err_msg="Q_out")


def test_static_state_carries_the_rotor_weight_as_the_massive_model_does():
    """At rest the inner contacts lift the rotor's weight (to 1e-8) and the DE shaft node sits
    within 1 % of where it sits with ball masses (their weight and centrifugal force, 0.02 and
    0.2 N per ball at 1750 r/min, are what the quasi-static balls drop)."""
    out = {}
    for inertia in (True, False):
        cfg = cwru_rotor_config(9, de_fault=Defect("outer"), ball_inertia=inertia)
        m = pack_model(cfg, FS, ball_forces=True)
        y0 = static_state(m, cfg)
        dydt, aux = evaluate_rhs(m, 0.0, y0)
        assert np.abs(dydt[m.n_pos :]).max() < 1e-3, "accelerations vanish at rest"
        zde, zfe = cfg.de.bearing.n_elements, cfg.fe.bearing.n_elements
        q_in = np.concatenate([aux[4 : 4 + zde], aux[4 + 2 * zde : 4 + 2 * zde + zfe]])
        psi = np.concatenate([2 * np.pi * np.arange(z) / z for z in (zde, zfe)])
        weight = (cfg.shaft.mass + cfg.armature.mass) * G0
        assert_allclose(-np.sum(q_in * np.cos(psi)), weight, rtol=1e-8)
        out[inertia] = y0[1] - y0[m.n_r + 1]  # DE shaft node y relative to its housing
    assert_allclose(out[False], out[True], rtol=0.01)


@pytest.mark.parametrize(
    "fault, key, harmonic",
    [("outer", "bpfo_hz", 1), ("inner", "bpfi_hz", 1), ("ball", "bsf_hz", 2)],
)
def test_defect_signals_match_the_model_with_ball_masses(fault, key, harmonic):
    """0.5 s at 12 kHz, 9 disks, the CWRU 0.007 in defect, against the seed's model with ball
    masses: RMS and envelope line within 15 %, kurtosis within 25 % — well inside the ×2 and
    ×1.5 bounds issue 16 sets between a simulation and a measurement, so the approximation does
    not decide a comparison. Measured (RMS, line, kurtosis): outer +2.5 %, +2.0 %, −1.9 %;
    inner +5.0 %, +11.8 %, +5.8 %; ball +2.2 %, −3.2 %, +20.6 % (the massless ball strikes
    harder). In a third of the RK4 steps."""
    ref = cwru_rotor_config(9, de_fault=Defect(fault))
    fh = harmonic * getattr(ref.kinematics()["DE"], key)
    r1, k1, l1, m1 = _metrics(ref, fh)
    r0, k0, l0, m0 = _metrics(cwru_rotor_config(9, de_fault=Defect(fault), ball_inertia=False), fh)
    assert_allclose(r0, r1, rtol=0.15, err_msg="RMS")
    assert_allclose(l0, l1, rtol=0.15, err_msg="envelope line")
    assert_allclose(k0, k1, rtol=0.25, err_msg="kurtosis")
    assert m1["n_steps"] >= 2.9 * m0["n_steps"]


def test_scenario_key_and_bad_input():
    sc = Scenario.from_dict({"model": "rotor", "ball_inertia": False})
    assert rotor_config_from_scenario(sc).ball_inertia is False
    assert rotor_config_from_scenario(Scenario.from_dict({"model": "rotor"})).ball_inertia
    with pytest.raises(ConfigError, match="ball_inertia = 3 is invalid; valid: true or false"):
        Scenario.from_dict({"model": "rotor", "ball_inertia": 3})
    with pytest.raises(ConfigError, match="ball_inertia = 'no' is not a boolean"):
        cwru_rotor_config(1, ball_inertia="no")
    with pytest.raises(ConfigError, match="ball_inertia"):
        Scenario.from_dict({"model": "vsm", "ball_inertia": False})


def test_cli_quasi_static_balls(run_cli, tmp_path):
    out = tmp_path / "r.nc"
    res = run_cli("simulate", "--model", "rotor", "--de-fault", "outer", "--quasi-static-balls",
                  "--duration-s", "0.02", "--fs-hz", "12000", "-o", out)  # fmt: skip
    assert res.code == 0, res.err
    from bearingsim.results import SimulationResult

    r = SimulationResult.load(out)
    assert r.meta["rotor"]["inputs"]["ball_inertia"] is False


# ------------------------------------------------------------------------------ axial load


def test_axial_load_static_state_is_the_jones_equilibrium():
    """Under an axial load each bearing's balls sit at the Jones equilibrium of its radial load
    at rest and the axial load (quasistatic.jones, tilts held, the balls' series Hertz
    constant): the kernel's normal ball loads equal Jones's to 1e-6, and the rotor's weight is
    still carried by their radial components."""
    from dataclasses import replace

    from bearingsim.quasistatic.jones import run_quasi_static

    fa = 20.0
    cfg = cwru_rotor_config(9, de_fault=Defect("outer"), ball_inertia=False, axial_load=fa)
    m = pack_model(cfg, FS, ball_forces=True)
    y0 = static_state(m, cfg)
    dydt, aux = evaluate_rhs(m, 0.0, y0)
    assert np.abs(dydt[m.n_pos :]).max() < 1e-3
    ref = pack_model(replace(cfg, axial_load=0.0), FS, ball_forces=True)
    _, aux0 = evaluate_rhs(ref, 0.0, static_state(ref, replace(cfg, axial_load=0.0)))
    lift = 0.0
    for e, sup in enumerate((cfg.de, cfg.fe)):
        b = sup.bearing
        z = b.n_elements
        off = 4 + (0 if e == 0 else 2 * m.z_de)
        psi = 2 * np.pi * np.arange(z) / z
        q0 = aux0[off : off + z]  # the radial load each bearing carries at rest
        fx, fy = float(np.sum(q0 * np.sin(psi))), float(np.sum(q0 * np.cos(psi)))
        kin = ball_contact(b, 1.0, Race.INNER).k_hertz
        kout = ball_contact(b, 1.0, Race.OUTER).k_hertz
        ke = (kin ** (-2 / 3) + kout ** (-2 / 3)) ** -1.5
        sol = run_quasi_static(b, 0.0, fx, fy, fa, clearance=b.diametral_clearance,
                               stiffness=ke, tilt_free=False)  # fmt: skip
        q = aux[off : off + z]
        assert_allclose(q, sol.ball_loads[0], rtol=1e-6, atol=1e-6 * q.max())
        assert np.all(q > 0), "an axial load loads every ball"
        lift -= np.sum(q * np.cos(sol.contact_angles[0]) * np.cos(psi))
        assert_allclose(m.axial[e].ball_contact_angles, sol.contact_angles[0], rtol=1e-9)
    weight = (cfg.shaft.mass + cfg.armature.mass) * G0
    assert_allclose(lift, weight, rtol=1e-6)


def test_axial_load_moves_the_fault_line_and_strikes_a_defect_at_12_oclock():
    """An outer-race defect at 12 o'clock, opposite the rotor's weight, is never struck without
    an axial load (the DE signal is the healthy one bit for bit); 20 N of axial load loads every
    ball, the defect is struck, and the envelope's BPFO line sits at the order of the
    load-weighted contact angle (read back within 0.5 deg, as the DEM's,
    tests/test_axial_load.py)."""
    from bearingsim.geometry import contact_angle_from_order
    from bearingsim.signal.contact_angle import estimate_contact_angle

    def run(defect, fa, dur=0.3):
        cfg = cwru_rotor_config(9, de_fault=defect, ball_inertia=False, axial_load=fa)
        return simulate_rotor(cfg, duration=dur, sample_rate=FS)

    at12 = Defect("outer", angle=0.0)
    assert np.array_equal(run(at12, 0.0).acceleration, run(None, 0.0).acceleration)
    r = run(at12, 20.0, 2.0)
    alpha = r.meta["axial"]["DE"]["contact_angle_deg"]
    assert 5.0 < alpha < 15.0
    b = cwru_rotor_config(9).de.bearing
    # the simulation's speed is exact (it has no shaft line to measure it from)
    est = estimate_contact_angle(r.channel("DE", "y"), FS, b, "outer", 1750.0 / 60.0,
                                 measure_shaft=False)  # fmt: skip
    assert est.snr_db > 20.0, "the defect at 12 o'clock is struck"
    assert math.degrees(contact_angle_from_order(b, "bpfo", est.order)) == pytest.approx(
        alpha, abs=0.5
    )
    assert r.kinematics["DE"].bpfo_hz == pytest.approx(est.order * 1750.0 / 60.0, rel=1e-3)


def test_axial_load_bad_input():
    with pytest.raises(ConfigError, match=r"axial_load_n = 20 N needs quasi-static balls"):
        cwru_rotor_config(1, axial_load=20.0)
    with pytest.raises(ConfigError, match=r"axial_load_n = -1"):
        cwru_rotor_config(1, ball_inertia=False, axial_load=-1.0)
    with pytest.raises(ConfigError, match=r"axial_load_n = 20 N needs quasi-static balls"):
        rotor_config_from_scenario(Scenario.from_dict({"model": "rotor", "axial_load_n": 20.0}))
    sc = Scenario.from_dict({"model": "rotor", "axial_load_n": 20.0, "ball_inertia": False})
    assert rotor_config_from_scenario(sc).axial_load == 20.0
    # above twice the static capacity (ISO 76), before any work, as the ring models
    from bearingsim import simulate

    big = dict(model="rotor", axial_load_n=1e6, ball_inertia=False, duration_s=0.01)
    with pytest.raises(ConfigError, match=r"F_a = axial_load_n = 1e\+06 N\) exceeds 2 x"):
        simulate(big)
