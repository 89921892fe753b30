"""Discrete radial load distribution (SPEC §0.4)."""

from __future__ import annotations

import math

import numpy as np
import pytest
from numpy.testing import assert_allclose

from bearingsim import ConfigError, get_bearing
from bearingsim.contact.hertz import ball_stiffness
from bearingsim.load_distribution import RingMotion, radial_load_distribution, stribeck_qmax
from bearingsim.report.published import value

CAGE = np.radians(np.linspace(0.0, 360.0, 721))


def test_seed_vsm_load_and_angle():
    ld = radial_load_distribution(get_bearing("6205"), 10.0, 50.0)
    assert_allclose(ld.fr, value("vsm.s2_1.radial_load"), rtol=1e-3, err_msg="F_r vs seed VSM §2.1")
    assert_allclose(
        math.degrees(ld.theta0),
        value("vsm.s2_1.load_angle"),
        atol=0.05,
        err_msg="theta_0 vs seed VSM §2.1",
    )


def test_seed_vsm_psi_l_is_ours_not_papers():
    """Seed VSM §2.1 states psi_L = 68.2 deg. With the Hertz K of the 6205 (exact elliptic
    integrals, E 207 GPa, nu 0.3) and P_d = 6 um we get 56.0 deg; the reason is recorded in
    docs/validation.md (the paper's K is not stated; 68.2 deg needs K about 0.28 x Hertz).
    Golden value of our model: regenerate with
    ``bearingsim load 6205 --fx 10 --fy 50 --json`` (key psi_l_deg)."""
    ld = radial_load_distribution(get_bearing("6205"), 10.0, 50.0)
    assert_allclose(math.degrees(ld.psi_l[0]), 56.027, atol=0.01)
    # the relation of seed VSM eq (8) holds by construction
    assert_allclose(np.cos(ld.psi_l), 3e-6 / ld.delta_r, rtol=1e-12)


@pytest.mark.parametrize("motion", list(RingMotion))
@pytest.mark.parametrize("clearance", [6e-6, 0.0, -3e-6, 25e-6])
@pytest.mark.parametrize("load", [(10.0, 50.0), (0.0, 5000.0), (-700.0, 300.0)])
def test_equilibrium_residual(motion, clearance, load):
    """Invariant: force balance to 1e-9 relative at every cage angle (FREE: both components;
    LOAD_LINE: the load-line component, the equation that form solves)."""
    b = get_bearing("6205")
    ld = radial_load_distribution(b, *load, CAGE, clearance=clearance, motion=motion)
    assert ld.residual.max() <= 1e-9
    if motion is RingMotion.FREE:
        r = np.hypot(*ld.force_residual.T) / ld.fr
        assert r.max() <= 1e-9
    else:
        th = ld.theta0
        along = ld.force_residual @ np.array([math.sin(th), math.cos(th)]) / ld.fr
        assert np.abs(along).max() <= 1e-9


def test_symmetric_load_gives_symmetric_ball_loads():
    """Ball 1 on the load line: loads of balls j and Z+2-j are equal (mirror symmetry)."""
    b = get_bearing("6205")
    ld = radial_load_distribution(b, 0.0, 800.0, 0.0)
    q = ld.ball_loads[0]
    assert_allclose(q[1:], q[1:][::-1], rtol=1e-10)
    assert_allclose(ld.displacement[0, 0], 0.0, atol=1e-15)
    # the free and load-line solutions coincide when the ball set is symmetric
    ll = radial_load_distribution(b, 0.0, 800.0, 0.0, motion="load_line")
    assert_allclose(ll.ball_loads, ld.ball_loads, rtol=1e-10, atol=1e-12)


def test_rotated_load_rotates_solution():
    """Rotating load and cage together by one ball pitch leaves the loads unchanged."""
    b = get_bearing("6205")
    phi = 2 * math.pi / 9
    a = radial_load_distribution(b, 10.0, 50.0, 0.3)
    f = np.array([10.0, 50.0])
    # psi from +y toward +x: rotating by phi maps (fx, fy) -> R(-phi) in (x, y) terms
    rot = np.array([[math.cos(phi), math.sin(phi)], [-math.sin(phi), math.cos(phi)]])
    fx2, fy2 = rot @ f
    c = radial_load_distribution(b, fx2, fy2, 0.3 + phi)
    assert_allclose(np.sort(c.ball_loads[0]), np.sort(a.ball_loads[0]), rtol=1e-9, atol=1e-9)


def test_psi_l_tends_to_90_deg_as_clearance_vanishes():
    b = get_bearing("6205")
    psis = [
        math.degrees(radial_load_distribution(b, 0, 500, 0.1, clearance=c).psi_l[0])
        for c in (20e-6, 5e-6, 1e-6, 1e-8, 0.0)
    ]
    assert np.all(np.diff(psis) > 0)
    assert_allclose(psis[-1], 90.0, atol=1e-9)
    assert_allclose(psis[-2], 90.0, atol=0.5)


def test_preload_loads_every_ball():
    b = get_bearing("6205")
    ld = radial_load_distribution(b, 0, 10.0, CAGE[:50], clearance=-4e-6)
    assert (ld.n_loaded == 9).all()
    assert (ld.psi_l > math.pi / 2).all()


def test_stribeck_constant_large_z():
    """Zero clearance, many balls: Z Q_max / F_r -> 4.37 (Stribeck 1901; Harris & Kotzalas 2007
    §7.2: the exact integral gives 4.37)."""
    from dataclasses import replace

    b = replace(
        get_bearing("6205"),
        n_elements=40,
        element_diameter=2.5e-3,
        inner_groove_radius=1.3e-3,
        outer_groove_radius=1.32e-3,
        diametral_clearance=0.0,
    )
    ld = radial_load_distribution(b, 0.0, 1000.0, np.linspace(0, 2 * math.pi / 40, 21))
    ratio = b.n_elements * ld.ball_loads.max(axis=1) / 1000.0
    assert_allclose(ratio.mean(), 4.37, rtol=0.01, err_msg="Stribeck constant")
    assert_allclose(stribeck_qmax(b, 1000.0), 4.37 * 1000 / 40, rtol=1e-12)


@pytest.mark.parametrize("alpha_deg", [25.0, 40.0])
@pytest.mark.parametrize("clearance", [0.0, 10e-6, -5e-6])
def test_a_contact_angle_carries_the_load_with_its_radial_share(alpha_deg, clearance):
    """A helper's exploratory testing (twenty-eighth session): the distribution ignored the
    nominal contact angle, so a 25 deg bearing carried 1000 N with the 0 deg bearing's
    element loads (487.2 N) and its elements' radial components summed to 906 N. Harris &
    Kotzalas 2007 §7.2/§7.4 (no axial displacement): ``delta = (u . e) cos alpha - P_d/2``
    and ``sum Q cos alpha e = F``; as ``u' = u cos alpha`` turns it into the 0 deg problem
    under ``F / cos alpha``, the element loads are the 0 deg bearing's under that load."""
    from dataclasses import replace

    b0 = replace(get_bearing("6205"), diametral_clearance=clearance)
    b = replace(b0, contact_angle=math.radians(alpha_deg))
    ca = math.cos(b.contact_angle)
    k = ball_stiffness(b)  # the raceways' curvature has alpha in it: one K for both
    for motion in ("free", "load_line"):
        ld = radial_load_distribution(b, 0.0, 1000.0, CAGE[:9], motion=motion)
        ref = radial_load_distribution(b0, 0.0, 1000.0 / ca, CAGE[:9], motion=motion, stiffness=k)
        assert_allclose(ld.ball_loads, ref.ball_loads, rtol=1e-12)
        # the radial balance, which the 0 deg loads missed by cos alpha (906 N at 25 deg)
        fy = (ld.ball_loads * ca * np.cos(ld.ball_angles)).sum(axis=1)
        assert_allclose(fy, 1000.0, rtol=1e-9)
        assert np.abs(ld.force_residual).max() <= 1e-9 * 1000.0 + (motion == "load_line") * 50
        # the ring moves 1/cos alpha further for the same contact deflections
        assert_allclose(ld.delta_r * ca, ref.delta_r, rtol=1e-12)
        assert_allclose(ld.delta_max, ref.delta_max, rtol=1e-12, atol=1e-18)
        assert_allclose(ld.psi_l, ref.psi_l, rtol=1e-12)
    # Stribeck's estimate has the same 1/cos alpha (Harris & Kotzalas 2007, eq. (7.26))
    if clearance == 0.0:
        z_ratio = b.n_elements * ld.ball_loads.max() * ca / 1000.0
        assert 4.2 < z_ratio < 4.5, z_ratio


def test_stribeck_constant_of_line_contact():
    """Harris & Kotzalas 2007 §7.2: ``Q_max = 4.08 F_r / Z`` for line contact (rollers, load
    exponent 10/9), which the discrete distribution approaches at zero clearance; rollers got
    the ball bearings' 4.37 (a helper's exploratory testing, twenty-eighth session)."""
    from dataclasses import replace

    b = replace(get_bearing("NU204-ECP"), diametral_clearance=0.0)
    assert_allclose(stribeck_qmax(b, 1000.0), 4.08 * 1000.0 / b.n_elements, rtol=1e-12)
    ld = radial_load_distribution(b, 0.0, 1000.0, np.linspace(0, 2 * math.pi / 11, 21))
    ratio = b.n_elements * ld.ball_loads.max() / 1000.0  # a roller on the load line: 4.072
    assert_allclose(ratio, 4.08, rtol=0.005)
    assert abs(ratio / 4.37 - 1.0) > 0.06  # the ball bearings' constant is 7 % off


def test_uses_hertz_stiffness_and_override():
    b = get_bearing("6205")
    ld = radial_load_distribution(b, 0.0, 100.0)
    assert_allclose(ld.stiffness, ball_stiffness(b), rtol=1e-12)
    ld2 = radial_load_distribution(b, 0.0, 100.0, stiffness=2 * ld.stiffness)
    assert ld2.delta_max[0] < ld.delta_max[0]


def test_vectorised_equals_scalar():
    b = get_bearing("6203-cwru")
    vec = radial_load_distribution(b, 30.0, 200.0, CAGE[:20])
    for i in range(0, 20, 7):
        one = radial_load_distribution(b, 30.0, 200.0, CAGE[i])
        assert_allclose(one.ball_loads[0], vec.ball_loads[i], rtol=1e-12, atol=1e-12)


def test_roller_bearing_exponent():
    ld = radial_load_distribution(get_bearing("NU204-ECP"), 0.0, 400.0)
    assert_allclose(ld.exponent, 10 / 9)
    assert ld.residual[0] <= 1e-9


@pytest.mark.parametrize(
    "kw, field",
    [
        ({"fx": float("nan")}, "fx_n"),
        ({"fy": float("inf")}, "fy_n"),
        ({"clearance": 1.0}, "clearance_m"),
        ({"cage_angle": [0.0, float("nan")]}, "cage_angle"),
    ],
)
def test_bad_input(kw, field):
    args = {"fx": 10.0, "fy": 50.0, **kw}
    fx, fy = args.pop("fx"), args.pop("fy")
    with pytest.raises(ConfigError, match=field):
        radial_load_distribution(get_bearing("6205"), fx, fy, **args)


def test_zero_load_with_clearance_is_an_error():
    with pytest.raises(ConfigError, match="radial load"):
        radial_load_distribution(get_bearing("6205"), 0.0, 0.0)
