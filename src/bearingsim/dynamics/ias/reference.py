"""Plain NumPy/SciPy reference of the IAS model (seed IAS eq. (32)) for verification.

An independent, vectorised re-implementation of the right-hand side of
:func:`bearingsim.dynamics.ias._kernel.ias_rhs` (same equations, no shared code beyond the derived
constants), integrated with :func:`scipy.integrate.solve_ivp`. It is slow (a Python call per
right-hand-side evaluation) and exists to check the compiled kernel on short spans and to measure
the compiled kernel's speed-up (``benchmarks/bench_ias.py``).
"""

from __future__ import annotations

import math
import time

import numpy as np
from numpy.typing import NDArray
from scipy.integrate import solve_ivp

from .model import GRAVITY, OMEGA_EPS, IasConstants, IasParams, SpallLoad, derive_constants

__all__ = [
    "ReferenceRhs",
    "simulate_ias_scipy",
]


class ReferenceRhs:
    """Callable ``f(t, y)`` of seed IAS eq. (32) in NumPy (see module docstring).

    Parameters
    ----------
    params : IasParams
        Model inputs.
    const : IasConstants, optional
        Derived constants (computed when omitted).
    """

    def __init__(self, params: IasParams, const: IasConstants | None = None) -> None:
        self.p = params
        self.k = const or derive_constants(params)
        b = params.bearing
        self.Z = b.n_elements
        self.offsets = 2.0 * np.pi * np.arange(self.Z) / self.Z
        self.rc = 0.5 * b.element_diameter
        self.ri = b.inner_raceway_radius
        self.do = b.outer_raceway_diameter
        dcos = b.element_diameter * math.cos(b.contact_angle)
        self.v1c = (b.pitch_diameter**2 - dcos**2) / (4.0 * b.pitch_diameter)
        self.n_calls = 0

    def forces(self, y: NDArray[np.float64]) -> dict[str, float]:
        """Ring forces and torques at state ``y``: keys ``fx, fy, torque, m_t`` [N], [N m]."""
        p, k = self.p, self.k
        x, yy, th, w = y[0], y[1], y[2], y[5]
        sgn = w / math.hypot(w, OMEGA_EPS)
        phi = p.first_roller_angle + k.cage_ratio * th + self.offsets  # eq. (3)
        cphi, sphi = np.cos(phi), np.sin(phi)
        d0 = x * cphi + yy * sphi - k.clearance  # eq. (33)
        u = (phi - p.spall_phi + np.pi) % (2.0 * np.pi) - np.pi
        th_os = k.spall_half_angle
        gamma = (np.abs(u) <= th_os) if p.spall_width > 0 else np.zeros(self.Z, bool)  # eq. (34)
        sh = np.where(gamma, np.sin(0.5 * np.pi * np.abs(u) / max(th_os, 1e-300)), 0.0)
        cd = np.where(gamma, k.spall_depth * (1.0 - sh), 0.0)  # eq. (18)
        delta = d0 - cd
        eta = delta > 0  # eq. (35)
        N = np.where(eta, k.k_total * np.abs(delta) ** k.exponent, 0.0)  # eq. (13)
        bn = p.rolling_resistance * self.rc  # eq. (14)
        T = N * bn / self.rc  # eq. (16)
        fx = np.sum(-N * cphi + sgn * T * sphi)
        fy = np.sum(-N * sphi - sgn * T * cphi)
        torque = np.sum(self.ri * T + bn * N)  # eq. (17)
        m_t = 0.0
        if np.any(gamma):
            if p.spall_load is SpallLoad.STRIBECK:  # eqs. (1)-(2)
                a = (k.load_zone_centre - phi + np.pi) % (2.0 * np.pi) - np.pi
                br = 1.0 - (1.0 - np.cos(a)) / (2.0 * k.epsilon)
                q = np.where(
                    (np.abs(a) <= k.load_zone_half_angle) & (br > 0),
                    k.q_max * np.abs(br) ** k.exponent,
                    0.0,
                )
            else:
                q = np.where(d0 > 0, k.k_total * np.abs(d0) ** k.exponent, 0.0)
            lam = k.impact_angle
            v1 = abs(k.cage_ratio * w) * self.v1c  # eqs. (24)-(25)
            v2 = math.sqrt(0.6 * v1**2 + 0.8 * GRAVITY * self.rc * (1.0 - math.cos(lam)))
            fos = 2.0 * k.roller_mass * v1 * v2 / (self.rc * math.cos(lam))  # eqs. (26)-(28)
            imp = np.where(q > 0, fos * math.cos(lam), 0.0)  # loaded rollers only
            ft = np.where(u < 0, q * sh, (q + imp) * (1.0 - sh))  # eq. (30)
            ft = np.where(gamma, ft, 0.0)
            sl = math.sin(lam) * sgn
            fx += np.sum(-ft * (math.cos(lam) * cphi - sl * sphi))
            fy += np.sum(-ft * (math.cos(lam) * sphi + sl * cphi))
            m_t = float(np.sum(0.5 * self.do * ft * math.sin(lam - th_os)))  # eq. (31)
        return {"fx": float(fx), "fy": float(fy), "torque": float(torque), "m_t": m_t}

    def __call__(self, t: float, y: NDArray[np.float64]) -> NDArray[np.float64]:
        self.n_calls += 1
        p = self.p
        f = self.forces(y)
        w = y[5]
        sgn = w / math.hypot(w, OMEGA_EPS)
        return np.array(
            [
                y[3],
                y[4],
                w,
                (p.fx - p.radial_damping * y[3] + f["fx"]) / p.mass,
                (-p.fy - p.radial_damping * y[4] + f["fy"]) / p.mass,
                (p.torque - p.torsional_damping * w - sgn * (f["torque"] + f["m_t"])) / p.inertia,
            ]
        )


def simulate_ias_scipy(
    params: IasParams,
    t_eval: NDArray[np.float64],
    *,
    method: str = "RK45",
    rtol: float = 1e-9,
    atol: float = 1e-13,
    max_step: float = np.inf,
):
    """Integrate the reference right-hand side with :func:`scipy.integrate.solve_ivp`.

    Parameters
    ----------
    params : IasParams
        Model inputs.
    t_eval : ndarray
        Output times [s], starting at 0.
    method : str
        ``solve_ivp`` method.
    rtol, atol : float
        Tolerances.
    max_step : float
        Largest step [s].

    Returns
    -------
    y : ndarray, shape (n, 6)
        States at ``t_eval``.
    info : dict
        ``wall_s``, ``cpu_s``, ``n_rhs`` (right-hand-side calls), ``status``.
    """
    from .model import initial_state

    rhs = ReferenceRhs(params)
    te = np.asarray(t_eval, dtype=float)
    t0 = time.perf_counter()
    c0 = time.process_time()
    sol = solve_ivp(
        rhs,
        (float(te[0]), float(te[-1])),
        initial_state(params),
        method=method,
        t_eval=te,
        rtol=rtol,
        atol=atol,
        max_step=max_step,
    )
    wall = time.perf_counter() - t0
    cpu = time.process_time() - c0
    return sol.y.T, {"wall_s": wall, "cpu_s": cpu, "n_rhs": rhs.n_calls, "status": int(sol.status)}
