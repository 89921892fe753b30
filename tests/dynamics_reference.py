"""Plain SciPy reference implementation of the VSM, TVSM and DEM equations (for tests and the
benchmark): pure NumPy right-hand sides, ``scipy.optimize.root`` for the static balance of seed
VSM eq. (16), ``scipy.integrate.solve_ivp`` (DOP853) split at the analytic instants where a ball
enters or leaves the defect, so that the step discontinuity is resolved exactly.

It shares nothing with the compiled kernels but the physical inputs (:class:`ModelInputs`); the
defect geometry and the ball constant come from the tested foundation/defect functions.
"""

from __future__ import annotations

import math

import numpy as np
from scipy.integrate import solve_ivp
from scipy.optimize import root

from bearingsim.dynamics.ring.base import ModelInputs
from bearingsim.geometry import Race, defect_geometry


class Reference:
    """Reference model for one :class:`ModelInputs` and model name ``vsm|tvsm|dem``."""

    def __init__(self, inputs: ModelInputs, model: str):
        self.model = model
        self.m = inputs.mass
        self.c = inputs.damping
        self.F = np.array([inputs.fx, inputs.fy])
        self.Z = inputs.bearing.n_elements
        self.K = inputs.k_ball
        self.clr = 0.5 * inputs.diametral_clearance
        self.w_cage = 2 * math.pi * inputs.cage_hz
        self.w_shaft = 2 * math.pi * inputs.shaft_hz
        self.alpha0 = inputs.first_ball_angle
        self.loc = None if inputs.defect is None else inputs.defect.race
        self.beta0 = 0.0
        self.dbeta = 0.0
        self.h = 0.0
        self.gamma = None
        if self.loc is not None:
            g = defect_geometry(inputs.bearing, inputs.defect)
            self.beta0 = g.edge_angle  # seed VSM beta_0: the left edge
            self.dbeta = g.delta_beta
            if inputs.retention_factor is None:
                self.h = g.h_min
            else:
                self.gamma = inputs.retention_factor
        self._u = None
        self.frozen = None  # (offsets, factors) held fixed between two jumps

    def directions(self, t: float):
        """Unit vectors (sin psi_j, cos psi_j) of the balls at t (seed eq. 12), shape (Z, 2)."""
        psi = self.w_cage * t + self.alpha0 + 2 * math.pi * np.arange(self.Z) / self.Z
        return np.stack([np.sin(psi), np.cos(psi)], axis=1), psi

    def membership(self, t: float):
        """Deflection offsets (Z,) and load factors (Z,) at t (seed eqs. 13, 15)."""
        _e, psi = self.directions(t)
        off = np.full(self.Z, self.clr)
        fac = np.ones(self.Z)
        if self.loc is not None:
            edge = self.beta0 + (self.w_shaft * t if self.loc is Race.INNER else 0.0)
            over = np.mod(psi - edge, 2 * math.pi) < self.dbeta
            off[over] += self.h
            if self.gamma is not None:
                fac[over] = self.gamma
        return off, fac

    def contact(self, u, t):
        """Bearing force (2,), tangent (2, 2) and secant (2, 2) matrices at displacement u."""
        e, _psi = self.directions(t)
        off, fac = self.frozen if self.frozen is not None else self.membership(t)
        ue = e @ u
        d = ue - off
        on = d > 0
        Q = np.where(on, fac * self.K * np.maximum(d, 0) ** 1.5, 0.0)
        kt = np.where(on, 1.5 * Q / np.where(on, d, 1.0), 0.0)
        ks = np.where(on, Q / np.where(on, ue, 1.0), 0.0)
        F = (Q[:, None] * e).sum(0)
        T = np.einsum("j,ja,jb->ab", kt, e, e)
        S = np.einsum("j,ja,jb->ab", ks, e, e)
        return F, T, S

    def static(self, t):
        """Static ring displacement at t: root of sum Q e = F (seed eq. 16)."""
        u0 = self._u if self._u is not None else np.array([0.0, 5e-6])
        sol = root(
            lambda u: self.contact(u, t)[0] - self.F,
            u0,
            jac=lambda u: self.contact(u, t)[1],
            method="hybr",
            tol=1e-15,
        )
        self._u = sol.x
        return sol.x

    def acc(self, t, y):
        """Acceleration [m/s^2] of the model's equation of motion."""
        u, v = y[:2], y[2:]
        if self.model == "dem":
            return (self.F - self.contact(u, t)[0] - self.c * v) / self.m
        us = self.static(t)
        _F, T, S = self.contact(us, t)
        if self.model == "vsm":
            return (self.F - S @ u - self.c * v) / self.m  # seed VSM eq. (19), secant
        return (T @ (us - u) - self.c * v) / self.m  # TVSM, tangent about u_s

    def rhs(self, t, y):
        return np.concatenate([y[2:], self.acc(t, y)])

    def jump_times(self, t_end: float) -> list[float]:
        """Instants in (0, t_end) at which some ball enters or leaves the defect."""
        if self.loc is None:
            return []
        w_rel = self.w_cage - (self.w_shaft if self.loc is Race.INNER else 0.0)
        n_turns = int(abs(w_rel) * t_end / (2 * math.pi)) + 3
        out = []
        for j in range(self.Z):
            a0 = self.alpha0 + 2 * math.pi * j / self.Z - self.beta0
            for target in (0.0, self.dbeta):
                for k in range(-n_turns - 2, n_turns + 3):
                    t = (target + 2 * math.pi * k - a0) / w_rel
                    if 0 < t < t_end:
                        out.append(t)
        return sorted(out)

    def run(
        self,
        y0,
        fs: float,
        n: int,
        rtol: float = 1e-10,
        method: str = "DOP853",
        atol_scale: float = 1.0,
    ):
        """Integrate to the output times k/fs, k < n; returns (t, y (n, 4), acc (n, 2)).

        ``rtol``, ``method`` and ``atol_scale`` (multiplying atol = 1e-16 m, 1e-12 m/s) are
        passed to ``solve_ivp``."""
        t_eval = np.arange(n) / fs
        t_end = t_eval[-1]
        edges = [0.0, *self.jump_times(t_end), t_end]
        ys = np.empty((n, 4))
        acc = np.empty((n, 2))
        y = np.asarray(y0, float)
        atol = atol_scale * np.array([1e-16, 1e-16, 1e-12, 1e-12])
        for a, b in zip(edges[:-1], edges[1:], strict=True):
            if b <= a:
                continue
            self.frozen = self.membership(0.5 * (a + b))
            sel = np.flatnonzero((t_eval >= a) & (t_eval <= b))
            te = np.append(t_eval[sel], b) if sel.size == 0 or t_eval[sel[-1]] < b else t_eval[sel]
            sol = solve_ivp(self.rhs, (a, b), y, method=method, t_eval=te, rtol=rtol, atol=atol)
            ys[sel] = sol.y[:, : sel.size].T
            for i in sel:
                acc[i] = self.acc(t_eval[i], ys[i])
            y = sol.y[:, -1]
        self.frozen = None
        return t_eval, ys, acc
