"""Rotor finite elements (issue 6): textbook natural frequencies, mesh convergence, gyroscopics,
static condensation and Craig–Bampton reduction."""

from __future__ import annotations

import math

import numpy as np
import pytest
import scipy.linalg as sla
from numpy.testing import assert_allclose

from bearingsim.dynamics.rotor.fe import (
    Disk,
    assemble_rotor,
    beam_element,
    complex_modes,
    condense_massless,
    craig_bampton,
    mesh_nodes,
)
from bearingsim.errors import ConfigError
from bearingsim.report.published import value

# a steel shaft (Friswell et al. 2010, Example 5.9.1: 1.5 m, diameter 50 mm, E 211 GPa, 7810 kg/m3)
E, RHO, D, L = 211e9, 7810.0, 0.05, 1.5
A = math.pi * D**2 / 4
I2 = math.pi * D**4 / 64  # second moment of area [m^4]


def _pinned_frequencies(n_el: int, n: int = 3) -> np.ndarray:
    r = assemble_rotor(np.linspace(0, L, n_el + 1), E * I2, RHO * A)
    fixed = [r.dof(0, "x"), r.dof(0, "y"), r.dof(n_el, "x"), r.dof(n_el, "y")]
    free = np.setdiff1d(np.arange(r.n_dof), fixed)
    lam = sla.eigh(r.K[np.ix_(free, free)], r.M[np.ix_(free, free)], eigvals_only=True)
    return (np.sqrt(lam) / (2 * np.pi))[0 : 2 * n : 2]  # x and y planes give equal pairs


@pytest.mark.parametrize("mode", [1, 2, 3], ids=["mode1", "mode2", "mode3"])
def test_simply_supported_beam_frequencies(mode):
    f = _pinned_frequencies(16)
    fa = (mode * math.pi / L) ** 2 * math.sqrt(E * I2 / (RHO * A)) / (2 * math.pi)
    assert_allclose(
        f[mode - 1], fa, rtol=1e-3,
        err_msg="vs simply supported Euler-Bernoulli beam w_n = (n pi/L)^2 sqrt(EI/rhoA) "
        "(Rao, Mechanical Vibrations, 5th ed., eq. 8.94)",
    )  # fmt: skip


def test_mesh_convergence_order_four():
    """Hermite elements with consistent mass: frequency error ~ h^4 (Strang & Fix 1973)."""
    fa = (math.pi / L) ** 2 * math.sqrt(E * I2 / (RHO * A)) / (2 * math.pi) * np.array([1, 4, 9])
    errs = np.array([np.abs(_pinned_frequencies(n) / fa - 1) for n in (4, 8, 16, 32)])
    order = np.log2(errs[:-1, 1] / errs[1:, 1])  # second mode
    assert_allclose(order, 4.0, atol=0.2, err_msg="observed convergence order of mode 2")
    assert np.all(np.diff(errs[:, 0]) < 0), "errors must decrease monotonically with refinement"
    assert errs[1, 0] < 0.01, "8 elements already within 1 % on mode 1"


def test_free_free_beam_frequencies():
    r = assemble_rotor(np.linspace(0, L, 17), E * I2, RHO * A)
    lam = np.sort(sla.eigh(r.K, r.M, eigvals_only=True))
    assert_allclose(lam[:4], 0.0, atol=1e-6 * lam[4], err_msg="four rigid-body modes")
    f = np.sqrt(lam[4::2][:3]) / (2 * np.pi)
    bl = np.array([4.730040745, 7.853204624, 10.99560784])  # roots of cos(bL) cosh(bL) = 1
    fa = bl**2 * math.sqrt(E * I2 / (RHO * A * L**4)) / (2 * np.pi)
    assert_allclose(f, fa, rtol=1e-3, err_msg="vs free-free beam (Blevins 1979, table 8-1)")


def test_jeffcott_rotor_massless_shaft_exact():
    """Disk at mid-span of a massless pinned shaft: w = sqrt(48 EI / (m L^3)) exactly."""
    m = 20.0
    r = assemble_rotor([0.0, L / 2, L], E * I2, disks=[Disk(L / 2, m, 0.1, 0.2)])
    fixed = [r.dof(0, "x"), r.dof(0, "y"), r.dof(2, "x"), r.dof(2, "y")]
    free = np.setdiff1d(np.arange(r.n_dof), fixed)
    M, K = r.M[np.ix_(free, free)], r.K[np.ix_(free, free)]
    master, T = condense_massless(M, K, [])
    lam = sla.eigh(T.T @ K @ T, T.T @ M @ T, eigvals_only=True)
    assert_allclose(np.sqrt(lam[0]), math.sqrt(48 * E * I2 / (m * L**3)), rtol=1e-10,
                    err_msg="Jeffcott rotor (Friswell et al. 2010 eq. 3.4)")  # fmt: skip


def test_element_matrices_structure():
    K, M, G = beam_element(0.3, E * I2, RHO * A, RHO * I2)
    assert_allclose(K, K.T, atol=1e-9 * abs(K).max())
    assert_allclose(M, M.T, atol=1e-12 * abs(M).max())
    assert_allclose(G, -G.T, atol=1e-12 * abs(G).max(), err_msg="gyroscopic matrix is skew")
    assert np.all(np.linalg.eigvalsh(M) > 0)
    # total translational mass of the element
    u = np.zeros(8)
    u[[0, 4]] = 1.0  # rigid x translation
    Kt, Mt, _ = beam_element(0.3, E * I2, RHO * A, 0.0)
    assert_allclose(u @ Mt @ u, RHO * A * 0.3, rtol=1e-12)
    assert_allclose(K @ u, 0.0, atol=1e-6, err_msg="rigid translation carries no bending force")


def _friswell_591(n_el: int = 6):
    def disk(z, do, t=0.07, di=0.05):
        return Disk.from_geometry(z, RHO * math.pi * (do**2 - di**2) / 4 * t, do, di, t)

    z = np.linspace(0, L, n_el + 1)
    r = assemble_rotor(z, E * I2, RHO * A, RHO * I2, [disk(0.5, 0.28), disk(1.0, 0.35)])
    K = r.K.copy()
    for nd in (0, n_el):  # isotropic bearings 1 MN/m
        K[r.dof(nd, "x"), r.dof(nd, "x")] += 1e6
        K[r.dof(nd, "y"), r.dof(nd, "y")] += 1e6
    xd = [r.dof(i, "x") for i in range(n_el + 1)]
    yd = [r.dof(i, "y") for i in range(n_el + 1)]
    return r, K, xd, yd


#: Friswell et al. (2010) Example 5.9.1 natural frequencies [rad/s] at 0 and 4000 r/min as
#: computed by ROSS with 6 Timoshenko elements (petrobras/ross docs/examples/example_05_09_01.rst)
ROSS_591 = {rpm: value(f"friswell.ex5_9_1.ross_{rpm}rpm") for rpm in (0, 4000)}


@pytest.mark.parametrize("rpm", [0, 4000], ids=["0rpm", "4000rpm"])
def test_friswell_example_5_9_1_with_gyroscopics(rpm):
    r, K, xd, yd = _friswell_591()
    m = complex_modes(r.M, K, r.G, rpm * math.pi / 30, x_dofs=xd, y_dofs=yd)
    ours = m.frequency_hz[:6] * 2 * math.pi
    # Euler-Bernoulli (ours) vs Timoshenko (ROSS): shear makes ROSS at most ~0.2 % lower here
    assert_allclose(ours, ROSS_591[rpm], rtol=3e-3,
                    err_msg="vs Friswell et al. 2010 Example 5.9.1 (ROSS, Timoshenko)")  # fmt: skip
    assert np.all(ours >= np.array(ROSS_591[rpm]) * (1 - 1e-5)), "EB is stiffer than Timoshenko"
    assert_allclose(m.damping_ratio[:6], 0.0, atol=1e-9, err_msg="undamped gyroscopic: no decay")


def test_rotor_at_rest_symmetric_solver_equals_first_order_form():
    """At rest and undamped complex_modes solves K phi = w^2 M phi (symmetric, ~10x cheaper);
    its frequencies equal the imaginary parts of the first-order form's eigenvalues (round-off)."""
    r, K, _, _ = _friswell_591()
    n = r.M.shape[0]
    A = np.block([[np.zeros((n, n)), np.eye(n)], [-np.linalg.solve(r.M, K), np.zeros((n, n))]])
    lam = np.linalg.eigvals(A)
    ref = np.sort(lam.imag[lam.imag > 2 * math.pi * 1e-6]) / (2 * math.pi)
    m = complex_modes(r.M, K, r.G, 0.0)
    assert_allclose(m.frequency_hz, ref, rtol=1e-9)
    assert np.all(m.damping_ratio == 0.0) and set(m.whirl) == {"planar"}


def test_gyroscopic_sign_forward_whirl_stiffens():
    """Forward whirl (in the spin sense, psi increasing) rises with speed, backward falls."""
    r, K, xd, yd = _friswell_591()
    m = complex_modes(r.M, K, r.G, 4000 * math.pi / 30, x_dofs=xd, y_dofs=yd)
    m0 = complex_modes(r.M, K, r.G, 0.0)
    for k in (0, 2, 4):  # each split pair: lower = backward, upper = forward
        assert m.whirl[k] == "backward" and m.whirl[k + 1] == "forward"
        assert m.frequency_hz[k] < m0.frequency_hz[k] < m.frequency_hz[k + 1]


def test_whirl_matches_a_time_simulation():
    """Independent check of the gyroscopic sign: integrate a spinning overhung disk released
    in its forward-whirl mode shape and verify the orbit turns from +y towards +x."""
    from scipy.integrate import solve_ivp

    r, K, xd, yd = _friswell_591(6)
    spin = 4000 * math.pi / 30
    n = r.n_dof
    Minv = np.linalg.inv(r.M)
    Acl = np.block([[np.zeros((n, n)), np.eye(n)], [-Minv @ K, -Minv @ (spin * r.G)]])
    lam, V = np.linalg.eig(Acl)
    sel = np.flatnonzero(lam.imag > 1.0)
    k = sel[np.argsort(lam[sel].imag)][1]  # second mode: forward per complex_modes
    y0 = np.real(V[:, k]) / np.abs(V[:n, k]).max() * 1e-4
    sol = solve_ivp(lambda t, y: Acl @ y, (0, 0.02), y0, rtol=1e-9, atol=1e-14, max_step=5e-4)
    x, y = sol.y[xd[2]], sol.y[yd[2]]
    ang = np.unwrap(np.arctan2(x, y))  # azimuth from +y towards +x
    assert ang[-1] - ang[0] > 0.5, "forward mode must whirl in the spin sense"


def test_craig_bampton_exact_without_truncation_and_converges_with_it():
    r, K, xd, yd = _friswell_591(12)
    bnd = [r.dof(0, "x"), r.dof(0, "y"), r.dof(12, "x"), r.dof(12, "y")]
    full = complex_modes(r.M, K, r.G, 400.0).frequency_hz[:8]
    red = craig_bampton(r.M, r.K, bnd)
    T = red.T
    Kr = T.T @ K @ T
    assert_allclose(T[bnd, :4], np.eye(4), atol=1e-12, err_msg="boundary coordinates physical")
    f_all = complex_modes(T.T @ r.M @ T, Kr, T.T @ r.G @ T, 400.0).frequency_hz[:8]
    assert_allclose(f_all, full, rtol=1e-9, err_msg="CB without truncation is exact")
    red = craig_bampton(r.M, r.K, bnd, cutoff_hz=400.0)
    T = red.T
    assert red.n_dropped > 0
    f_tr = complex_modes(T.T @ r.M @ T, T.T @ K @ T, T.T @ r.G @ T, 400.0).frequency_hz[:4]
    assert_allclose(f_tr, full[:4], rtol=2e-3, err_msg="modes far below the cut-off")


def test_condensation_requires_a_structure():
    with pytest.raises(ConfigError):
        craig_bampton(np.diag([1.0, 0.0]), np.zeros((2, 2)), [0])


def test_mesh_nodes_contains_key_points():
    z = mesh_nodes(0.2, [0.05, 0.1234], 10)
    assert z[0] == 0.0 and z[-1] == 0.2
    for p in (0.05, 0.1234):
        assert np.min(np.abs(z - p)) < 1e-15
    assert z.size - 1 >= 10
    with pytest.raises(ConfigError, match="key_point_m"):
        mesh_nodes(0.2, [0.3], 4)
