"""Weibull view of fatigue lives (``bearingsim.life.weibull``)."""

from __future__ import annotations

import math

import numpy as np
import pytest
from numpy.testing import assert_allclose

from bearingsim.errors import ConfigError
from bearingsim.life.weibull import (
    LP_SLOPE_POINT,
    median_ranks,
    rating_life_ratio,
    weibull_fit,
)
from bearingsim.report.published import value


def test_median_ranks_bernard():
    """Bernard's approximation (i - 0.3)/(n + 0.4); n = 3 gives 20.6 / 50.0 / 79.4 %."""
    assert_allclose(median_ranks(3), [0.7 / 3.4, 1.7 / 3.4, 2.7 / 3.4], rtol=1e-15)
    assert_allclose(median_ranks(3)[1], 0.5, rtol=1e-15)


def test_fit_recovers_a_known_population():
    """Maximum likelihood on 4000 draws recovers beta and eta to a few per cent."""
    rng = np.random.default_rng(15)
    lives = 3e8 * rng.weibull(1.5, 4000)
    f = weibull_fit(lives)
    assert_allclose(f.beta, 1.5, rtol=0.05)
    assert_allclose(f.eta, 3e8, rtol=0.05)
    assert_allclose(f.probability_at(f.life_at(0.1)), 0.1, rtol=1e-12)
    assert_allclose(f.life_at(1 - math.exp(-1)), f.eta, rtol=1e-12)  # 63.2 % at eta


def test_l50_over_l10_for_ball_bearings():
    """Weibull slope 10/9 (Lundberg & Palmgren, point contact): L50/L10 = (ln 2/ln(1/0.9))^0.9
    = 5.45."""
    assert LP_SLOPE_POINT == 10 / 9
    assert_allclose(rating_life_ratio(0.5), (math.log(2) / math.log(1 / 0.9)) ** 0.9, rtol=1e-12)
    assert_allclose(rating_life_ratio(0.5), 5.449, atol=1e-3)
    assert rating_life_ratio(0.1) == pytest.approx(1.0)


def test_seed_tests_fit_and_plot():
    """The three tests of seed LIFE table 4: a slope between 1 and 5 and a median between the
    first and the last test."""
    tests = value("life.table4.test_lives")
    f = weibull_fit(tests)
    assert 1 < f.beta < 5 and min(tests) < f.l50 < max(tests)
    fig = f.plot({"a life": 1e8, "L10": 3.19e8}, title="t")
    ax = fig.axes[0]
    assert ax.get_xscale() == "log" and "[cycles]" in ax.get_xlabel()
    assert fig.get_layout_engine() is not None  # constrained: nothing clipped


@pytest.mark.parametrize(
    "bad, match",
    [([1.0], "at least 2"), ([1.0, -2.0], "finite values > 0"), ([1, math.nan], "finite")],
)
def test_bad_lives(bad, match):
    with pytest.raises(ConfigError, match=match):
        weibull_fit(bad)
