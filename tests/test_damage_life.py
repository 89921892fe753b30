"""Damage law, S–N fit and torsion check (seed LIFE §1)."""

from __future__ import annotations

import matplotlib

matplotlib.use("Agg")

import numpy as np
import pytest
from numpy.testing import assert_allclose

from bearingsim.errors import ConfigError
from bearingsim.life.damage import (
    GCR15_TORSION,
    DamageLaw,
    SNCurve,
    cycles_to_failure,
    fit_sn_curve,
    integrate_uniform,
    torsion_check,
)
from bearingsim.report.published import entry, value


def test_gcr15_fit_reproduces_seed_parameters():
    fit = fit_sn_curve(GCR15_TORSION)
    assert_allclose(
        fit.law.kappa, value("life.s1_1.kappa"), atol=0.05, err_msg="kappa vs seed LIFE §1.1 (11.1)"
    )
    assert_allclose(
        fit.law.sigma_t,
        entry("life.s1_1.sigma_t").si,
        rtol=5e-3,
        err_msg="sigma_t vs seed LIFE §1.1 (5979 MPa)",
    )
    assert fit.residual_rms == 0.0


def test_fit_is_exact_on_the_integrated_law():
    # the fitted law must give back the S-N curve through eq. (6): Delta_tau = 2 tau_a
    law = fit_sn_curve(GCR15_TORSION).law
    n = np.logspace(5, 9, 7)
    assert_allclose(
        law.stress_range(n),
        2 * GCR15_TORSION.amplitude(n),
        rtol=1e-12,
        err_msg="eq. (6) vs eq. (5)",
    )
    assert_allclose(law.cycles_to_failure(2 * GCR15_TORSION.amplitude(n)), n, rtol=1e-10)


def test_fit_from_points_recovers_power_law_and_handles_scatter():
    rng = np.random.default_rng(3)
    n = np.logspace(5, 8.5, 25)
    ta = GCR15_TORSION.amplitude(n)
    exact = fit_sn_curve(n_cycles=n, tau_amplitude=ta).law
    ref = fit_sn_curve(GCR15_TORSION).law
    assert_allclose([exact.kappa, exact.sigma_t], [ref.kappa, ref.sigma_t], rtol=1e-9)
    noisy = fit_sn_curve(n_cycles=n, tau_amplitude=ta * np.exp(0.02 * rng.standard_normal(n.size)))
    assert_allclose(noisy.law.kappa, ref.kappa, rtol=0.15)
    assert 0.003 < noisy.residual_rms < 0.02


def test_fit_bad_input():
    with pytest.raises(ConfigError, match="S-N points"):
        fit_sn_curve(n_cycles=[1e6], tau_amplitude=[1e9])
    with pytest.raises(ConfigError, match="tau_amplitude_pa = -1"):
        fit_sn_curve(n_cycles=[1e5, 1e6], tau_amplitude=[1e9, -1.0])
    with pytest.raises(ConfigError, match="slope"):
        fit_sn_curve(n_cycles=[1e5, 1e6], tau_amplitude=[1e9, 2e9])


@pytest.mark.parametrize(
    "kappa, sigma_t, field",
    [
        (0.0, 5e9, "kappa"),
        (-1.0, 5e9, "kappa"),
        (11.1, 0.0, "sigma_t_pa"),
        (11.1, -5e9, "sigma_t_pa"),
    ],
)
def test_damage_law_rejects_nonpositive(kappa, sigma_t, field):
    with pytest.raises(ConfigError, match=f"{field} = .* valid range \\(0, inf\\)"):
        DamageLaw(kappa, sigma_t)


def test_block_integration_converges_first_order():
    """Left Riemann sum of eq. (4): relative excess ~ Delta_D (kappa + 1)/2."""
    law = DamageLaw(11.1, 5979e6)
    exact = float(cycles_to_failure(1.4e9, law.kappa, law.sigma_t))
    for dd in (0.01, 0.001, 0.0001):
        n, hist_n, hist_d = integrate_uniform(law, 1.4e9, dd)
        assert_allclose(hist_d[-1], 1.0, rtol=0, atol=1e-12)
        assert np.all(np.diff(hist_n) >= 0) and hist_n[1] > 0
        assert_allclose(
            (n / exact - 1.0) / dd,
            (law.kappa + 1) / 2,
            rtol=0.06,
            err_msg=f"first-order excess at Delta_D = {dd}",
        )


def test_torsion_check_matches_sn_curve():
    """Seed LIFE §1.2: 1000 -> 400 MPa by 50 MPa; uniform torsion reproduces the fitted S-N
    curve up to the block error Delta_D (kappa+1)/2 ~ 0.6 %."""
    law = fit_sn_curve(GCR15_TORSION).law
    tc = torsion_check(law)
    assert_allclose(tc.tau_amplitude / 1e6, np.arange(1000, 399, -50))
    assert_allclose(tc.cycles_exact, tc.cycles_sn, rtol=1e-9, err_msg="eq. (6) vs eq. (5)")
    ratio = tc.cycles_predicted / tc.cycles_sn
    assert np.all(ratio > 1.0) and np.all(ratio < 1.0 + 0.001 * (law.kappa + 1))
    fig = tc.plot()
    assert len(fig.axes) == 1


def test_sn_curve_and_fit_plot():
    c = SNCurve(1e9, 0.1, "test")
    assert_allclose(c.cycles(c.amplitude(1e6)), 1e6, rtol=1e-12)
    fig = fit_sn_curve(GCR15_TORSION).plot(GCR15_TORSION)
    assert fig.axes[0].get_xscale() == "log"
