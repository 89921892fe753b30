"""Seed IAS line-contact formulas (eqs. (5)–(13)) against their own consistency and Harris."""

from __future__ import annotations

import math

import numpy as np
import pytest
from numpy.testing import assert_allclose

from bearingsim import ConfigError, get_bearing
from bearingsim.contact.hertz import combined_stiffness, element_stiffness, roller_contact
from bearingsim.contact.pereira import (
    A1,
    A2,
    C1,
    C2,
    LINE_EXPONENT,
    external_deflection,
    external_radius,
    external_stiffness,
    half_width,
    internal_deflection,
    internal_radius,
    internal_stiffness,
    normal_force,
    power_law_constant,
    seed_line_stiffness,
    seed_reference_load,
)
from bearingsim.geometry import Race
from bearingsim.materials import effective_modulus

B = get_bearing("NU204-ECP")
RC = 0.5 * B.element_diameter
RI, RO, L = B.inner_raceway_radius, B.outer_raceway_radius, B.roller_length
EE = effective_modulus(B.material, B.material)
#: seed IAS §3.1: F_y = 400 N shared by Z = 11 rollers
QREF = 400.0 / 11


def test_reference_load_is_fy_over_z():
    assert_allclose(
        seed_reference_load(B, 400.0),
        QREF,
        rtol=1e-15,
        err_msg="seed IAS eqs. (7)-(10) written with F_y/(E Z l)",
    )


@pytest.mark.parametrize("race", ["inner", "outer"])
def test_half_width_matches_hertz(race):
    r = external_radius(RC, RI) if race == "inner" else internal_radius(RC, RO)
    b_seed = half_width(QREF, L, r, EE)
    b_hertz = roller_contact(B, QREF, Race(race)).b
    # 1.59 vs sqrt(8/pi) = 1.5958: 0.37 % apart
    assert_allclose(
        b_seed,
        b_hertz,
        rtol=4e-3,
        err_msg="seed IAS eq. (5) vs Hertz b = sqrt(8QR/(pi l E')), Johnson (1985) eq. (4.43)",
    )


@pytest.mark.parametrize("q", [1.0, QREF, 159.0, 2000.0])
def test_stiffness_is_derivative_of_deflection(q):
    h = 1e-4 * q
    for defl, stiff, r in (
        (external_deflection, external_stiffness, RI),
        (internal_deflection, internal_stiffness, RO),
    ):
        dz = (defl(q + h, L, RC, r, EE) - defl(q - h, L, RC, r, EE)) / (2 * h)
        assert_allclose(
            1.0 / dz,
            stiff(q, L, RC, r, EE),
            rtol=1e-7,
            err_msg="seed IAS eqs. (9)/(10) = dq/dzeta of eqs. (7)/(8)",
        )


def test_reconstruction_matches_printed_constants():
    # eq. (7) as printed: zeta_1 = 2.37 F/(E Z l) [ln(...) - 0.04]; our integral of eq. (9)
    assert_allclose(1.0 / A1, 2.37, rtol=0.02, err_msg="seed IAS eq. (7) coefficient 2.37")
    assert_allclose(1.0 - C1, -0.04, atol=1e-12, err_msg="seed IAS eq. (7) constant -0.04")
    # eq. (8) as printed: zeta_2 = 7.43 F/(E Z l) [0.5 ln(...) ...]
    assert_allclose(2.0 / A2, 7.43, rtol=0.005, err_msg="seed IAS eq. (8) coefficient 7.43 x 0.5")
    # the printed -1.38 of eq. (8) would need eq. (10)'s constant to be 2 * 1.38 + 1 = 3.76
    assert abs(C2 - 3.76) > 1.0


def test_deflection_values_at_seed_load():
    # zeta_1 = q/(0.43 E' l) [ln(E' l (r_c + r_i)/q) - 0.04], evaluated by hand
    el = EE * L
    z1 = QREF / (0.43 * el) * (math.log(el * (RC + RI) / QREF) - 0.04)
    z2 = QREF / (0.27 * el) * (math.log(el * RC * RO / (RO - RC) / QREF) + 0.285)
    s = seed_line_stiffness(B, QREF)
    assert_allclose(
        [s.zeta_inner, s.zeta_outer, s.zeta],
        [z1, z2, z1 + z2],
        rtol=1e-12,
        err_msg="seed IAS eqs. (7), (8), (11)",
    )
    assert_allclose(
        s.k_total,
        combined_stiffness(s.kp_inner, s.kp_outer, 10 / 9),
        rtol=1e-12,
        err_msg="seed IAS eq. (12)",
    )


def test_power_law_constant_has_the_tangent_stiffness():
    k, q = 6.9e7, QREF
    K = power_law_constant(k, q)
    zeta = (q / K) ** (1 / LINE_EXPONENT)
    assert_allclose(
        LINE_EXPONENT * K * zeta ** (LINE_EXPONENT - 1),
        k,
        rtol=1e-12,
        err_msg="dq/dzeta of q = K zeta^(10/9) at q_ref",
    )
    assert_allclose(normal_force(zeta, K), q, rtol=1e-12, err_msg="seed IAS eq. (13)")
    assert normal_force(-1e-6, K) == 0.0


def test_series_combination_carries_the_same_load():
    s = seed_line_stiffness(B, QREF)
    q = 120.0
    z1 = (q / s.kp_inner) ** 0.9
    z2 = (q / s.kp_outer) ** 0.9
    assert_allclose(
        s.k_total * (z1 + z2) ** (10 / 9),
        q,
        rtol=1e-12,
        err_msg="seed IAS eq. (12): series contacts carry the same load",
    )


def test_seed_law_is_softer_than_palmgren():
    """Documented discrepancy (docs/validation.md): the seed's deflection at F_y/Z is about 4.2
    times Palmgren's, so its K_t is about 5 times softer."""
    s = seed_line_stiffness(B, QREF)
    d_palm = 2 * float(roller_contact(B, QREF, Race.INNER).delta)
    ratio = s.zeta / d_palm
    assert 3.0 < ratio < 6.0, ratio
    k_harris, n = element_stiffness(B)
    assert n == LINE_EXPONENT
    assert 3.0 < k_harris / s.k_total < 7.0


def test_bad_inputs():
    with pytest.raises(ConfigError, match=r"roller_load_n = -1 N is out of range"):
        external_stiffness(-1.0, L, RC, RI, EE)
    with pytest.raises(ConfigError, match=r"valid range \(0, "):
        internal_deflection(1e12, L, RC, RO, EE)
    with pytest.raises(ConfigError, match="not a roller bearing"):
        seed_line_stiffness(get_bearing("6205"), 10.0)
    with pytest.raises(ConfigError, match="must exceed the roller radius"):
        internal_radius(5e-3, 4e-3)
    assert np.all(np.isfinite(external_deflection([1.0, 10.0], L, RC, RI, EE)))
