"""ISO 281 rating and life, the ISO/TS 16281-style reference life, static capacity, units."""

from __future__ import annotations

import math
from dataclasses import replace

import numpy as np
import pytest
from numpy.testing import assert_allclose

from bearingsim.catalog import get_bearing
from bearingsim.contact.hertz import ball_contact
from bearingsim.errors import ConfigError
from bearingsim.geometry import Race, characteristic_frequencies
from bearingsim.life.iso281 import (
    FC_BALL_TABLE,
    FC_ROLLER_TABLE,
    basic_rating_life,
    cycles_to_revolutions,
    dynamic_load_rating,
    fc_ball,
    fc_ball_closed_form,
    fc_roller_closed_form,
    inner_race_cycles_per_revolution,
    revolutions_to_hours,
    static_capacity,
)
from bearingsim.life.reference_life import load_integrals, raceway_ratings, reference_rating_life
from bearingsim.report.published import entry

B6206 = get_bearing("6206")
B6205 = get_bearing("6205")


def test_fc_tables_follow_lundberg_palmgren_forms():
    """Guard against transcription errors in ISO 281 tables 2 and 3: every row follows the
    ISO/TR 1281-1 closed forms (ball within 0.15 %, roller within 0.15 % up to gamma 0.30)."""
    g, fc = FC_BALL_TABLE.T
    assert_allclose(
        fc,
        [fc_ball_closed_form(x) for x in g],
        rtol=1.5e-3,
        err_msg="ISO 281 table 2 vs Lundberg-Palmgren form",
    )
    g, fc = FC_ROLLER_TABLE.T
    assert_allclose(
        fc,
        [fc_roller_closed_form(x) for x in g],
        rtol=1.5e-3,
        err_msg="ISO 281 table 3 vs ISO/TR 1281-1 form, lambda nu = 0.83",
    )


@pytest.mark.parametrize(
    "bearing, c_catalog, source",
    [
        ("6206", entry("catalogue.nsk.6206.c_r").si, "NSK catalogue 6206 C_r = 19.5 kN"),
        ("6205", entry("catalogue.nsk.6205.c_r").si, "NSK catalogue 6205 C_r = 14.0 kN"),
        ("6203-cwru", entry("catalogue.nsk.6203.c_r").si, "NSK catalogue 6203 C_r = 9.55 kN"),
    ],
)
def test_c_against_catalogue(bearing, c_catalog, source):
    """ISO 281 C_r from geometry vs a catalogue listing plain ISO 281 ratings (the catalogue
    rounds to 3 figures and uses its own pitch diameter)."""
    r = dynamic_load_rating(get_bearing(bearing))
    assert_allclose(r.c, c_catalog, rtol=0.01, err_msg=source)
    assert r.b_m == 1.3


def test_l10_definition_and_roller_exponent():
    c = dynamic_load_rating(B6206).c
    assert_allclose(basic_rating_life(B6206, 5000.0), 1e6 * (c / 5000.0) ** 3, rtol=1e-12)
    nu = get_bearing("NU204-ECP")
    r = dynamic_load_rating(nu)
    assert r.life_exponent == pytest.approx(10 / 3)
    assert r.b_m == 1.1
    assert_allclose(basic_rating_life(nu, 5000.0), 1e6 * (r.c / 5000.0) ** (10 / 3), rtol=1e-12)


def test_fc_range_errors():
    with pytest.raises(ConfigError, match="gamma = 0.5 .* valid range"):
        fc_ball(0.5)


def test_cycles_per_revolution_is_bpfi_order():
    u = inner_race_cycles_per_revolution(B6206)
    assert_allclose(u, characteristic_frequencies(B6206, 1.0).bpfi_order, rtol=1e-12)
    assert_allclose(cycles_to_revolutions(B6206, 1e9), 1e9 / u, rtol=1e-12)
    assert_allclose(revolutions_to_hours(1.2e6, 1200.0), 1e6 / 60e3 * 1.0, rtol=1e-12)
    with pytest.raises(ConfigError, match="rpm = 0"):
        revolutions_to_hours(1e6, 0.0)


def test_load_integrals_against_harris():
    J = load_integrals(0.5)
    assert_allclose(
        [J.j_r, J.j_1, J.j_2],
        [0.2288, 0.5625, 0.5875],
        atol=1e-4,
        err_msg="Harris & Kotzalas point-contact J_r, J_1, J_2 at epsilon = 0.5",
    )
    # Stribeck: Q_max = F_r / (Z J_r) = 4.37 F_r / Z
    assert_allclose(1.0 / J.j_r, 4.37, rtol=1e-3, err_msg="Stribeck constant")


def test_reference_life_reduces_to_iso281_in_the_nominal_case():
    """Reference conformities 0.52/0.53, zero clearance: L10r = L10 up to the discrete-ball
    averaging (construction of the raceway ratings, module docstring item 3)."""
    b = replace(
        B6206,
        inner_groove_radius=0.52 * B6206.element_diameter,
        outer_groove_radius=0.53 * B6206.element_diameter,
        diametral_clearance=0.0,
    )
    ref = reference_rating_life(b, 5000.0, n_cage=32)
    assert_allclose(ref.l10r, basic_rating_life(b, 5000.0), rtol=2e-3)


def test_reference_life_trends():
    base = reference_rating_life(B6206, 5000.0)
    # clearance narrows the load zone: shorter life
    lives = [reference_rating_life(B6206, 5000.0, clearance=c).l10r for c in (0, 10e-6, 30e-6)]
    assert lives[0] > lives[1] > lives[2]
    assert_allclose(lives[0], base.l10r, rtol=1e-12)
    # the 6206 grooves (f_i 0.515, f_e 0.520) are tighter than the reference: higher ratings
    r = raceway_ratings(B6206)
    b = replace(
        B6206,
        inner_groove_radius=0.52 * B6206.element_diameter,
        outer_groove_radius=0.53 * B6206.element_diameter,
    )
    r0 = raceway_ratings(b)
    assert r.q_ci > r0.q_ci and r.q_ce > r0.q_ce
    # inner raceway governs (rotating, convex): shorter raceway life
    assert base.l_inner < base.l_outer


def test_static_capacity_is_the_iso76_stress():
    sc = static_capacity(B6206)
    q = 5.0 * sc.c0 / B6206.n_elements
    assert_allclose(
        float(ball_contact(B6206, q, Race.INNER).p_max),
        4200e6,
        rtol=1e-9,
        err_msg="ISO 76: 4200 MPa at the most loaded ball contact",
    )
    # the 6206 of seed LIFE has tighter grooves than ISO 76 assumes: above NSK's C0r 11.3 kN
    c0_nsk = entry("catalogue.nsk.6206.c0_r").si
    assert c0_nsk < sc.c0 < 1.3 * c0_nsk
    nu = get_bearing("NU204-ECP")
    assert static_capacity(nu).stress_limit == 4000e6


def test_reference_life_bad_input():
    with pytest.raises(ConfigError, match="radial_load_n = -1"):
        reference_rating_life(B6206, -1.0)
    with pytest.raises(ConfigError, match="radial_load_n = 0"):
        basic_rating_life(B6206, 0.0)
    assert math.isfinite(reference_rating_life(B6205, 1000.0).l10r)
    assert np.isfinite(dynamic_load_rating(get_bearing("NU204-ECP")).c)
