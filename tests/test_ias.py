"""IAS model of seed IAS (Han, Guo, Fan 2025): literature numbers, invariants, solver checks.

Default runs use dt = 1e-5 s and 2 s of simulated time: the step is 4.3x below the stability
bound of :func:`check_step` (the torsional rate C_T/I = 2.3e4 1/s), and halving it changes the
order peaks by < 1e-3 orders (``test_halving_dt_keeps_the_order_peaks``); the seed's own
dt = 1e-6 s, 10 s case is the ``slow`` test at the end.
"""

from __future__ import annotations

import math
from dataclasses import replace

import numpy as np
import pytest
from numpy.testing import assert_allclose, assert_array_less

from bearingsim import ConfigError, get_bearing
from bearingsim.dynamics.ias.model import (
    IasParams,
    IasResult,
    derive_constants,
    impact_force,
    simulate_ias,
)
from bearingsim.dynamics.ias.reference import simulate_ias_scipy
from bearingsim.load_distribution import radial_load_distribution
from bearingsim.report.published import entry, value

B = get_bearing("NU204-ECP")
SEED = IasParams(B)  # seed IAS §3.1 defaults: F_y 400 N, M_z 9.54 N m, C_T 1.52, L_d 1 mm
DT, DUR, RATE = 1e-5, 2.0, 20_000.0
#: seed IAS eq. (36) and §3.1: BPFO order 4.22 and harmonics 8.44, 12.66 (+/- 0.02 order)
PUBLISHED_ORDERS = list(value("ias.fig9.order_peaks"))


@pytest.fixture(scope="module")
def faulty():
    return simulate_ias(SEED, DUR, DT, RATE)


@pytest.fixture(scope="module")
def healthy():
    return simulate_ias(replace(SEED, spall=None), DUR, DT, RATE)


def test_constants_of_the_seed_case():
    k = derive_constants(SEED)
    assert_allclose(
        k.bpfo_order,
        value("ias.eq36.bpfo_order"),
        atol=5e-3,
        err_msg="BPFO order, seed IAS eq. (36)",
    )
    assert_allclose(k.free_speed, 9.54 / 1.52, rtol=1e-12, err_msg="M_z / C_T, seed IAS §3.1")
    assert_allclose(k.clearance, 1e-6, rtol=1e-12, err_msg="c = 1 um, seed IAS table 1")
    assert_allclose(
        k.spall_half_angle,
        math.asin(1.0 / 41.5),
        rtol=1e-12,
        err_msg="Theta_os = arcsin(L_d/D_o), seed IAS eq. (20)",
    )
    rc = 3.97e-3
    assert_allclose(
        k.spall_depth,
        rc - math.sqrt(rc**2 - 0.5e-3**2),
        rtol=1e-12,
        err_msg="H_m, seed IAS eq. (19)",
    )
    assert_allclose(
        rc * (1 - math.cos(k.impact_angle)),
        k.spall_depth,
        rtol=1e-12,
        err_msg="drop r_c (1 - cos lambda) of seed IAS eq. (21) equals H_m",
    )
    assert_allclose(k.q_max, 4.37 * 400 / 11, rtol=1e-12, err_msg="Stribeck, seed IAS eq. (2)")


def test_impact_force_from_momentum_balance():
    """F_os of seed IAS eqs. (21)-(28), evaluated step by step, and the printed eq. (29) times
    V_2 (the printed form lacks that velocity and is not a force)."""
    k = derive_constants(SEED)
    rc, dp, dc, ld = 3.97e-3, 34e-3, 7.94e-3, 1e-3
    w_cage = k.cage_ratio * k.free_speed
    lam = math.asin(ld / (2 * rc))
    v1 = w_cage * (dp**2 - dc**2) / (4 * dp)  # eq. (25) with V = w_c r_c
    v2 = math.sqrt(0.6 * v1**2 + 0.8 * 9.80665 * rc * (1 - math.cos(lam)))  # eq. (25)
    v_os = v2 * math.cos(math.pi / 2 - lam)  # eq. (27)
    t_lam = rc * math.sin(lam) / (2 * abs(0.0 - v1))  # eq. (28), V_out = 0
    f_momentum = k.roller_mass * v_os / (t_lam * math.cos(lam))  # eq. (26)
    f = impact_force(k.roller_mass, rc, w_cage, dp, dc, ld)
    assert_allclose(f, f_momentum, rtol=1e-12, err_msg="seed IAS eqs. (26)-(28)")
    eq29 = k.roller_mass * w_cage * (dp**2 - 4 * rc**2) / (dp * math.sqrt(4 * rc**2 - ld**2))
    assert_allclose(f, eq29 * v2, rtol=1e-12, err_msg="printed eq. (29) x V_2")
    assert impact_force(k.roller_mass, rc, w_cage, dp, dc, 0.0) == 0.0


def test_mean_speed_from_torque_balance(faulty, healthy):
    for r in (faulty, healthy):
        s = r.analyze()
        assert_allclose(
            s.mean_speed * 60 / (2 * math.pi),
            value("ias.s3_1.mean_speed"),
            rtol=0.01,
            err_msg="mean speed 60 r/min, seed IAS §3.1",
        )
        # the speed is not imposed: it sits below the free speed M_z/C_T by the bearing torque
        assert s.mean_speed < r.constants.free_speed


def test_torque_balance_at_steady_state(faulty, healthy):
    for r in (faulty, healthy):
        m = r.steady()
        net = r.net_torque()[m]
        assert abs(net.mean()) < 1e-5 * r.params.torque, net.mean()
        # mean speed = (M_z - mean resisting torques) / C_T
        w_bal = (r.params.torque - (r.bearing_torque + r.spall_torque)[m].mean()) / 1.52
        assert_allclose(r.omega[m].mean(), w_bal, rtol=1e-5)


@pytest.mark.parametrize("case", ["faulty", "healthy"])
def test_order_peaks_at_bpfo_harmonics(case, request):
    r = request.getfixturevalue(case)
    peaks = r.analyze().peaks
    top = sorted(peaks, key=lambda p: -p.amplitude)
    if case == "faulty":
        got = sorted(p.order for p in top[:3])
        assert_allclose(
            got,
            PUBLISHED_ORDERS,
            atol=0.02,
            err_msg="IAS order peaks 4.22x, 8.44x, 12.66x, seed IAS fig. 9",
        )
    else:
        # the healthy bearing shows the ball-pass ripple too (the seed's point, fig. 8(a))
        assert_allclose(
            top[0].order,
            value("ias.eq36.bpfo_order"),
            atol=0.02,
            err_msg="healthy ripple period 0.237 rev",
        )


def test_healthy_ripple_is_small_but_present(faulty, healthy):
    rh = healthy.analyze().ripple_rel
    rf = faulty.analyze().ripple_rel
    assert 1e-6 < rh < 1e-3, rh
    assert rf > 10 * rh


def test_no_spall_no_impact(healthy, faulty):
    for name in ("spall_force", "impact_force", "spall_torque"):
        assert np.all(getattr(healthy, name) == 0.0), name
    assert faulty.impact_force.max() > 0.0
    assert healthy.analyze().estimate is None


def test_dynamic_steady_state_matches_static_distribution(healthy):
    """At 60 r/min the healthy bearing is quasi-static: the dynamic sum of roller loads follows the
    static discrete-roller solution (foundation load_distribution) with the same K_t."""
    m = healthy.steady()
    cage = healthy.constants.cage_ratio * healthy.theta[m][::50]
    ld = radial_load_distribution(
        B,
        0.0,
        -400.0,
        -cage,
        first_element_angle=0.5 * math.pi,
        stiffness=healthy.constants.k_total,
    )
    assert_allclose(
        healthy.normal_force_sum[m][::50],
        ld.ball_loads.sum(1),
        rtol=5e-3,
        err_msg="dynamic vs static roller loads (rolling resistance adds 0.15 %)",
    )


@pytest.mark.parametrize("width", [0.5e-3, 1e-3, 2e-3])
def test_spall_width_estimate(width, faulty):
    r = (
        faulty
        if width == 1e-3
        else simulate_ias(replace(SEED, spall=replace(SEED.spall, width=width)), DUR, DT, RATE)
    )
    est = r.analyze().estimate
    assert est is not None
    assert_allclose(est.width, width, rtol=0.10, err_msg="spall width, seed IAS eq. (37)")


@pytest.mark.parametrize("width", [0.05e-3, 0.1e-3])
def test_the_width_of_a_narrow_spall(width):
    """A helper's exploratory testing (twenty-eighth session): the second drop of the averaged
    pass was searched outside a fixed n/200 bins of the first, which held the whole event of
    a spall under ~0.12 mm: 0.05 and 0.1 mm read 0.15 and 0.23 mm. Seed eq. (37)."""
    r = simulate_ias(replace(SEED, spall=replace(SEED.spall, width=width)), DUR, DT, RATE)
    assert_allclose(r.analyze().estimate.width, width, rtol=0.10)


def test_the_width_on_a_coarse_angle_grid(run_cli, tmp_path):
    """The same helper: at 6000 r/min and 50 kHz (500 samples per revolution) the drop is
    smeared over more than n/200 bins of the averaged pass, and its own flank was taken as the
    second drop (0.19 mm for 1 mm; 3000 r/min gave 0.12 mm before the session's first fix)."""
    for rpm in (3000, 6000):
        d = run_cli("ias", "--rpm", rpm, "--duration-s", 0.2, "--dt-s", 1e-6, "-o",
                    tmp_path / f"{rpm}.nc", "--json").json()  # fmt: skip
        assert_allclose(d["spall_width_estimate_m"], d["spall_width_m"], rtol=0.05)
    # a spall the grid cannot resolve is not given a width: 0.2 mm at 3000 r/min and 50 kHz
    # took a 2 % ripple for the impact and read 1.94 mm (the same session's later helper)
    r = run_cli("ias", "--rpm", 3000, "--duration-s", 0.2, "--dt-s", 1e-6, "--spall-width-m",
                2e-4, "-o", tmp_path / "n.nc")  # fmt: skip
    assert "spall width       not detected (no spall event, or its entry and impact" in r.out


def test_halving_dt_keeps_the_order_peaks(faulty):
    fine = simulate_ias(SEED, DUR, DT / 2, RATE)
    a, b = faulty.analyze(), fine.analyze()
    assert_allclose(
        [p.order for p in a.peaks],
        [p.order for p in b.peaks],
        atol=1e-3,
        err_msg="order peaks, dt = 1e-5 vs 5e-6 s",
    )
    assert_allclose([p.amplitude for p in a.peaks], [p.amplitude for p in b.peaks], rtol=0.01)
    assert_allclose(a.estimate.width, b.estimate.width, rtol=0.01)


#: largest |difference| / max|state| for (x, y, theta, x', y', theta') over a spall crossing
TOL_STATE = [2e-3, 1e-3, 1e-6, 3e-3, 1e-3, 5e-4]


def _spall_crossing_params():
    # roller 1 starts 0.04 rad (cage) before the spall: it crosses it within 0.03 s
    return replace(SEED, first_roller_angle=1.5 * math.pi - 0.04)


def test_compiled_kernel_matches_scipy_reference():
    """Compiled RK4 (dt 1e-6 s) vs the NumPy right-hand side under SciPy's DOP853 on 0.03 s with
    a spall crossing. The spall force (seed eq. (30)) jumps at the spall entry and centre; RK4's
    O(dt) error at those jumps bounds the agreement (it halves with dt)."""
    p = _spall_crossing_params()
    r = simulate_ias(p, 0.03, 1e-6, 20_000.0)
    assert r.spall_force.max() > 100.0  # the crossing is in the span
    y, info = simulate_ias_scipy(p, r.t, method="DOP853", rtol=1e-10, atol=1e-14)
    assert info["status"] == 0
    scale = np.abs(r.state).max(axis=0)
    err = np.abs(y - r.state) / scale
    assert_array_less(err.max(axis=0), TOL_STATE, err_msg="max |diff| / max |state|, vs SciPy")
    assert_array_less(np.median(err, axis=0), 2e-4, err_msg="median |diff| / max |state|")


def test_adaptive_matches_fixed_step():
    p = _spall_crossing_params()
    r = simulate_ias(p, 0.05, 1e-6, 10_000.0)
    a = simulate_ias(p, 0.05, 1e-6, 10_000.0, method="dopri5", rtol=1e-8, atol=1e-12)
    err = np.abs(a.state - r.state) / np.abs(r.state).max(axis=0)
    assert_array_less(err.max(axis=0), TOL_STATE, err_msg="RK4 vs Dormand-Prince 5(4)")


def test_save_load_roundtrip(tmp_path, faulty):
    f = tmp_path / "r.nc"
    faulty.save(f)
    back = IasResult.load(f)
    assert np.array_equal(back.state, faulty.state) and np.array_equal(back.aux, faulty.aux)
    assert np.array_equal(back.t, faulty.t)
    assert back.params == faulty.params and back.constants == faulty.constants
    assert back.solver == faulty.solver


def test_plots(faulty):
    import matplotlib.pyplot as plt

    for fig in (faulty.plot_ias(), faulty.plot_order_spectrum(), faulty.analyze().estimate.plot()):
        assert len(fig.axes) >= 1
        plt.close(fig)


def test_bad_parameters():
    with pytest.raises(ConfigError, match=r"spall_width_m = 0.009 m is out of range"):
        replace(SEED, spall=replace(SEED.spall, width=9e-3))
    with pytest.raises(ConfigError, match="torque_n_m = 0 N m with zero initial speed"):
        replace(SEED, torque=0.0)
    replace(SEED, torque=0.0, initial_speed=6.0)  # coasting down is a valid case
    with pytest.raises(ConfigError, match=r"dt_s = 0.001 s is too large for stability"):
        simulate_ias(SEED, 0.1, 1e-3)
    with pytest.raises(ConfigError, match=r"duration_s = -1 s is out of range"):
        simulate_ias(SEED, -1.0, 1e-5)
    with pytest.raises(ConfigError, match="not a cylindrical roller bearing"):
        IasParams(get_bearing("6205"))


@pytest.mark.slow
def test_seed_case_full():
    """The seed's case as published: RK4, dt = 1e-6 s, 10 s (seed IAS §3.1)."""
    r = simulate_ias(SEED, 10.0, 1e-6, 10_000.0)
    s = r.analyze()
    assert_allclose(
        s.mean_speed * 60 / (2 * math.pi),
        value("ias.s3_1.mean_speed"),
        rtol=0.01,
        err_msg="mean speed, seed IAS §3.1",
    )
    got = sorted(p.order for p in sorted(s.peaks, key=lambda p: -p.amplitude)[:3])
    assert_allclose(got, PUBLISHED_ORDERS, atol=0.02, err_msg="seed IAS fig. 9")
    assert_allclose(s.estimate.width, 1e-3, rtol=0.10, err_msg="true width 1 mm")
    assert_allclose(
        s.estimate.width,
        entry("ias.eq37.spall_width_estimate").si,
        rtol=0.10,
        err_msg="seed IAS §3.1 estimate",
    )
    coarse = simulate_ias(SEED, 10.0, 1e-5, 10_000.0).analyze()
    assert_allclose(
        [p.order for p in coarse.peaks],
        [p.order for p in s.peaks],
        atol=1e-3,
        err_msg="the default tests' dt = 1e-5 s vs the seed's 1e-6 s",
    )


@pytest.mark.parametrize(
    "change",
    [{"contact_law": "harris"}, {"spall_load": "dynamic"}],
    ids=["harris-contact", "dynamic-spall-load"],
)
def test_model_options_keep_the_kinematic_results(change):
    """Order peaks and the width estimate are kinematic: the contact-law and spall-load options
    change amplitudes, not them."""
    r = simulate_ias(replace(SEED, **change), DUR, DT, RATE)
    s = r.analyze()
    top = sorted(p.order for p in sorted(s.peaks, key=lambda p: -p.amplitude)[:3])
    assert_allclose(top, PUBLISHED_ORDERS, atol=0.02, err_msg="seed IAS fig. 9")
    assert_allclose(s.estimate.width, 1e-3, rtol=0.10)


def test_spall_outside_the_load_zone_is_silent():
    """A spall at the top (phi_os = pi/2) sits outside the load zone of a downward load: its roller
    load Q(phi) of seed eq. (1) is zero, so no spall force, no spall torque, no event."""
    r = simulate_ias(replace(SEED, spall=replace(SEED.spall, angle=0.0)), DUR, DT, RATE)  # top
    assert np.all(r.spall_force == 0.0) and np.all(r.spall_torque == 0.0)
    assert r.analyze().estimate is None
