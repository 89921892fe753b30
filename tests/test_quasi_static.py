"""Quasi-static 5-DOF model (seed QS5, SPEC §5): invariants, analytics, seed behaviour."""

from __future__ import annotations

import math

import numpy as np
import pytest
from numpy.testing import assert_allclose
from scipy.optimize import brentq

from bearingsim.catalog import get_bearing
from bearingsim.contact.capacity import StaticCapacityWarning
from bearingsim.errors import ConfigError, SolverError
from bearingsim.load_distribution import radial_load_distribution
from bearingsim.quasistatic import (
    Misalignment,
    SpeedEffects,
    StiffnessResult,
    qs_geometry,
    run_quasi_static,
    solve_equilibrium,
    stiffness_vs_cage,
)
from bearingsim.quasistatic._kernels import _assemble, _assemble_speed, _params
from bearingsim.report.published import value

B6205 = get_bearing("6205")
#: seed-QS5-style cases (the seed's own values are cut off; SPEC §5): 6205, radial load 500 N,
#: tilts beyond the free angular play (about 2.2 mrad for P_d = 6 um)
FY = 500.0
TILT = 3e-3
ERRORS = np.zeros(9)
ERRORS[0], ERRORS[4] = 0.05, -0.03


# ------------------------------------------------------------------ cross-check: SPEC §0.4


@pytest.mark.parametrize(
    ("fx", "fy", "clearance"),
    [(10.0, 50.0, None), (0.0, 2000.0, None), (300.0, -800.0, 0.0), (0.0, 1000.0, -2e-6)],
    ids=["seedVSM-10-50N", "2kN", "zero-clearance", "preload"],
)
def test_pure_radial_matches_foundation(fx, fy, clearance):
    cage = np.radians([0.0, 7.3, 20.0, 33.0])
    ld = radial_load_distribution(B6205, fx, fy, cage, clearance=clearance, motion="free")
    qs = run_quasi_static(B6205, cage, fx, fy, clearance=clearance)
    assert_allclose(
        qs.delta_max,
        ld.delta_max,
        rtol=1e-6,
        err_msg="delta_max vs foundation radial distribution (SPEC §5 cross-check)",
    )
    if (clearance if clearance is not None else B6205.diametral_clearance) > 0:
        assert_allclose(qs.psi_l, ld.psi_l, rtol=1e-6, err_msg="psi_L vs foundation (SPEC §5)")
    assert_allclose(
        qs.ball_loads,
        ld.ball_loads,
        rtol=1e-6,
        atol=1e-9 * ld.ball_loads.max(),
        err_msg="ball loads vs foundation (SPEC §5)",
    )
    assert_allclose(qs.displacement[:, 2:], 0.0, atol=1e-15)


# --------------------------------------------------------------------- analytic Jacobian


def _fd_jacobian(fun, u, h):
    J = np.empty((5, 5))
    for k in range(5):
        up, um = u.copy(), u.copy()
        up[k] += h[k]
        um[k] -= h[k]
        J[:, k] = (fun(up) - fun(um)) / (2 * h[k])
    return J


def test_analytic_jacobian_equals_finite_difference():
    g = qs_geometry(B6205)
    rng = np.random.default_rng(4)
    h = np.array([1e-10, 1e-10, 1e-10, 1e-10 / g.r_pi, 1e-10 / g.r_pi])
    for _ in range(20):
        psi = np.sort(rng.uniform(0, 2 * np.pi, 9))
        moff = rng.normal(0, 5e-6, 9)
        u = np.r_[rng.normal(0, 8e-6, 3), rng.normal(0, 4e-4, 2)]
        f, H = np.empty(5), np.empty((5, 5))
        p = _params(g)

        def force(uu, psi=psi, moff=moff, p=p):
            ff, HH = np.empty(5), np.empty((5, 5))
            _assemble(uu, psi, moff, p, ff, HH)
            return ff

        _assemble(u, psi, moff, p, f, H)
        if not np.any(f):
            continue
        J = _fd_jacobian(force, u, h)
        assert_allclose(
            H,
            J,
            rtol=1e-6,
            atol=1e-6 * np.abs(H).max(),
            err_msg="analytic tangent stiffness vs central differences",
        )
        assert_allclose(
            H,
            H.T,
            rtol=1e-12,
            atol=1e-12 * np.abs(H).max(),
            err_msg="Jones stiffness is a Hessian: symmetric",
        )


@pytest.mark.parametrize("gyro", [False, True], ids=["centrifugal", "centrifugal+gyroscopic"])
def test_condensed_jacobian_with_inertia_loads(gyro):
    g = qs_geometry(B6205)
    co = (g.f_o - 0.5) * g.d
    fc, mg0, gam = 40.0, (3.0 if gyro else 0.0), g.d / g.dm
    p = _params(g, inertia=(fc, mg0, gam))
    rng = np.random.default_rng(7)
    h = np.array([1e-10, 1e-10, 1e-10, 1e-10 / g.r_pi, 1e-10 / g.r_pi])
    psi = np.linspace(0, 2 * np.pi, 9, endpoint=False) + 0.1
    for _ in range(5):
        moff = rng.normal(0, 3e-6, 9)
        u = np.r_[rng.normal(0, 2e-6, 2), 1e-6 + 5e-6 * rng.random(), rng.normal(0, 1e-4, 2)]
        V = np.zeros((9, 2))
        V[:, 1] = co + 1e-6

        def force(uu, moff=moff, V=V):
            ff, HH = np.empty(5), np.empty((5, 5))
            Vt = V.copy()
            _assemble_speed(uu, psi, moff, p, Vt, ff, HH, np.empty((4, 9)))
            return ff

        f, H = np.empty(5), np.empty((5, 5))
        _assemble_speed(u, psi, moff, p, V, f, H, np.empty((4, 9)))
        J = _fd_jacobian(force, u, h)
        assert_allclose(
            H,
            J,
            rtol=1e-5,
            atol=1e-6 * np.abs(H).max(),
            err_msg="condensed Jacobian with ball inertia vs central differences",
        )
        if not gyro:
            assert_allclose(
                H,
                H.T,
                atol=1e-9 * np.abs(H).max(),
                err_msg="conservative (centrifugal) model: symmetric stiffness",
            )


# -------------------------------------------------------------------- equilibrium invariants


@pytest.mark.parametrize(
    "loads",
    [dict(fy=800.0, fz=300.0), dict(fx=-200.0, fy=400.0, mx=3.0, my=-1.0), dict(fz=500.0)],
    ids=["radial+axial", "radial+moments", "axial"],
)
def test_equilibrium_balances_applied_load(loads):
    s = solve_equilibrium(B6205, cage_angle=0.2, **loads)
    F = np.array([loads.get(k, 0.0) for k in ("fx", "fy", "fz", "mx", "my")])
    # reaction recomputed from the ball loads and contact angles (independent of the kernel)
    Q, a, psi, r = s.ball_loads[0], s.contact_angles[0], s.ball_angles[0], s.geometry.r_pi
    R = np.array(
        [
            np.sum(Q * np.cos(a) * np.sin(psi)),
            np.sum(Q * np.cos(a) * np.cos(psi)),
            np.sum(Q * np.sin(a)),
            r * np.sum(Q * np.sin(a) * np.cos(psi)),
            -r * np.sum(Q * np.sin(a) * np.sin(psi)),
        ]
    )
    scale = np.linalg.norm(np.r_[F[:3], F[3:] / r])
    assert_allclose(
        np.r_[R[:3], R[3:] / r],
        np.r_[F[:3], F[3:] / r],
        atol=1e-9 * scale,
        err_msg="sum of ball forces balances the applied load (DESIGN invariant)",
    )


def test_pure_axial_load_matches_harris_closed_form():
    # Harris & Kotzalas (2007) eq. (7.40) form:
    # F_a = Z K (A0 (cos a_f / cos a - 1))^1.5 sin a
    Fa = 400.0
    s = solve_equilibrium(B6205, fz=Fa)
    g = s.geometry
    cf = g.y0 / g.a0  # cos of the free contact angle

    def h(a):
        return g.n_balls * g.k * (g.a0 * (cf / math.cos(a) - 1.0)) ** 1.5 * math.sin(a) - Fa

    a_exact = brentq(h, math.acos(cf) + 1e-12, 1.2)
    assert_allclose(
        s.contact_angles[0],
        a_exact,
        rtol=1e-8,
        err_msg="axial contact angle vs Harris & Kotzalas eq. (7.40)",
    )
    assert_allclose(s.ball_loads[0], Fa / (g.n_balls * math.sin(a_exact)), rtol=1e-8)


def test_free_tilt_absorbs_misalignment():
    # with the ring free to tilt, a misalignment is undone by the ring rotation (module docs)
    mis = Misalignment(outer_tilt=TILT, outer_azimuth=0.4)
    free = solve_equilibrium(B6205, fy=FY, misalignment=mis, tilt_free=True)
    ref = solve_equilibrium(B6205, fy=FY)
    assert_allclose(free.ball_loads, ref.ball_loads, rtol=1e-7, atol=1e-9)
    held = solve_equilibrium(B6205, fy=FY, misalignment=mis)
    assert np.abs(held.ball_loads - ref.ball_loads).max() > 1.0


def test_outer_and_inner_tilt_equivalence():
    # outer tilt T about A equals inner tilt T r_po/r_pi about A + pi at shaft angle 0 (eq. (2)-(3))
    g = qs_geometry(B6205)
    o = solve_equilibrium(
        B6205, fy=FY, misalignment=Misalignment(outer_tilt=TILT, outer_azimuth=0.3)
    )
    i = solve_equilibrium(
        B6205,
        fy=FY,
        misalignment=Misalignment(inner_tilt=TILT * g.r_po / g.r_pi, inner_azimuth=0.3 + math.pi),
    )
    assert_allclose(i.ball_loads, o.ball_loads, rtol=1e-9, atol=1e-9)
    assert_allclose(i.stiffness_matrix.values, o.stiffness_matrix.values, rtol=1e-9, atol=1e-3)


def test_centrifugal_limits():
    spd = SpeedEffects(shaft_speed=1e-3, centrifugal=True)
    slow = solve_equilibrium(B6205, fy=FY, speed=spd)
    ref = solve_equilibrium(B6205, fy=FY)
    assert_allclose(
        slow.ball_loads,
        ref.ball_loads,
        rtol=1e-6,
        atol=1e-6,
        err_msg="inertia model at vanishing speed = static model",
    )
    assert_allclose(
        slow.stiffness_matrix.values,
        ref.stiffness_matrix.values,
        rtol=1e-5,
        atol=1e-6 * np.abs(ref.stiffness_matrix.values).max(),
    )
    fast = solve_equilibrium(B6205, fy=FY, speed=SpeedEffects(shaft_speed=2000.0, centrifugal=True))
    g = fast.geometry
    wc = g.cage_ratio * 2000.0
    fc = 0.5 * g.density * math.pi * g.d**3 / 6 * g.dm * wc**2  # Harris eq. (3.17)
    # radial ball balance at alpha = 0 (Harris vol. 2 eq. (3.37)): Q_o = Q_i + F_c, so the total
    # approach is (Q_i/K_i)^(2/3) + ((Q_i + F_c)/K_o)^(2/3); unloaded balls sit on the outer race
    qi = fast.ball_loads[0]
    assert_allclose(fast.contact_angles[0], 0.0, atol=1e-12)
    expect = (qi / g.k_inner) ** (2 / 3) + ((qi + fc) / g.k_outer) ** (2 / 3)
    loaded = qi > 0
    assert loaded.any() and (~loaded).any()
    assert_allclose(
        fast.deflections[0][loaded],
        expect[loaded],
        rtol=1e-9,
        err_msg="ball radial balance with centrifugal force (Harris eq. (3.37))",
    )
    assert_allclose(fast.reaction[0, 1], FY, rtol=1e-9)


# ---------------------------------------------------------------- seed QS5 published behaviour


def _dominant(res: StiffnessResult, name: str) -> float:
    return res.spectra[name].components[0].order_shaft


def test_outer_misalignment_fluctuates_at_ball_pass():
    r = stiffness_vs_cage(
        B6205, fy=FY, cage_revs=4, points_per_rev=180, misalignment=Misalignment(outer_tilt=TILT)
    )
    vc = 9 * r.solution.geometry.cage_ratio
    tol = 1.5 * r.solution.geometry.cage_ratio / 4
    for name in ("radial", "tilt"):
        assert abs(_dominant(r, name) - vc) < tol, f"seed QS5 abstract: VC period ({name})"
        assert r.spectra[name].components[0].label.startswith("Z×cage")


def test_distribution_error_gives_cage_order():
    ref = stiffness_vs_cage(
        B6205, fy=FY, cage_revs=4, points_per_rev=180, misalignment=Misalignment(outer_tilt=TILT)
    )
    r = stiffness_vs_cage(
        B6205,
        fy=FY,
        cage_revs=4,
        points_per_rev=180,
        misalignment=Misalignment(outer_tilt=TILT),
        ball_errors=ERRORS,
    )
    c = r.solution.geometry.cage_ratio
    assert abs(_dominant(r, "radial") - c) < 1.5 * c / 4, "seed QS5: cage-period fluctuation"
    assert r.spectra["radial"].components[0].label == "cage"
    assert r.spectra["radial"].amplitude_at(c) > 100 * ref.spectra["radial"].amplitude_at(c)
    p2p = r.fluctuation()["radial"]["peak_to_peak_rel"]
    assert p2p > 3 * ref.fluctuation()["radial"]["peak_to_peak_rel"]


def test_inner_misalignment_fluctuates_at_twice_shaft():
    kw = dict(fy=FY, cage_revs=4, points_per_rev=180, misalignment=Misalignment(inner_tilt=TILT))
    r = stiffness_vs_cage(B6205, **kw)
    re = stiffness_vs_cage(B6205, ball_errors=ERRORS, **kw)
    tol = 1.5 * r.solution.geometry.cage_ratio / 4
    for name in ("axial", "tilt"):
        order = value("qs5.abstract.inner_misalignment_order")
        assert abs(_dominant(r, name) - order) < tol, f"seed QS5: half inner-ring period ({name})"
        assert r.spectra[name].components[0].label == "2×shaft"
        p2p = r.fluctuation()[name]["peak_to_peak_rel"]
        assert re.fluctuation()[name]["peak_to_peak_rel"] > p2p, "seed QS5: errors increase it"


def test_stiffness_result_save_load_lossless(tmp_path):
    r = stiffness_vs_cage(
        B6205,
        fy=FY,
        cage_revs=1,
        points_per_rev=72,
        misalignment=Misalignment(inner_tilt=TILT),
        ball_errors=ERRORS,
    )
    p = r.save(tmp_path / "res.nc")
    r2 = StiffnessResult.load(p)
    np.testing.assert_array_equal(
        r2.solution.stiffness_matrix.values, r.solution.stiffness_matrix.values
    )
    np.testing.assert_array_equal(r2.k_radial, r.k_radial)
    from bearingsim.io.jsonable import to_jsonable

    assert to_jsonable(r2.to_dict()) == to_jsonable(r.to_dict())


def test_plots_return_figures():
    import matplotlib.pyplot as plt

    r = stiffness_vs_cage(B6205, fy=FY, cage_revs=1, points_per_rev=72)
    for fig in (r.plot(), r.plot_series(), r.plot_spectra(), r.plot_loads(0)):
        assert fig.axes
        plt.close(fig)


# ------------------------------------------------------------------------------ bad input


def test_bad_inputs_raise_one_line_errors():
    with pytest.raises(ConfigError, match="outer_tilt_rad = 0.1 rad is beyond"):
        solve_equilibrium(B6205, fy=FY, misalignment=Misalignment(outer_tilt=0.1))
    with pytest.raises(ConfigError, match="exactly n_elements = 9"):
        solve_equilibrium(B6205, fy=FY, ball_errors=[0.0] * 8)
    with pytest.raises(ConfigError, match="overlap or pass"):
        solve_equilibrium(B6205, fy=FY, ball_errors=[0.5] + [0.0] * 8)
    with pytest.raises(ConfigError, match="not finite"):
        solve_equilibrium(B6205, fy=math.nan)
    with pytest.raises(ConfigError, match="undetermined"):
        solve_equilibrium(B6205)
    with pytest.raises(ConfigError, match="held by a misalignment"):
        solve_equilibrium(B6205, fy=FY, mx=1.0, misalignment=Misalignment(inner_tilt=TILT))
    with pytest.raises(ConfigError, match="needs a ball bearing"):
        solve_equilibrium(get_bearing("NU204-ECP"), fy=FY)
    with pytest.raises(ConfigError, match=r"P0 = .* exceeds 2 x the static capacity"):
        solve_equilibrium(B6205, fz=1e6)
    # past the overload check (a warning then), the groove limit refuses it
    with (
        pytest.warns(StaticCapacityWarning),
        pytest.raises(SolverError, match="beyond the groove limit"),
    ):
        solve_equilibrium(B6205, fz=1e6, allow_overload=True)
