"""VSM: variable-stiffness model of a deep-groove ball bearing with one local defect.

Guo, Zhao, Zheng, Li & Duan, "Dynamic modeling of variable stiffness for single local damage
fault of rolling bearing", J. Vib. Eng. 38(5) 2025 (seed VSM), SPEC §1.

At every instant the static balance of eq. (16) is solved over the discrete balls with the
retention factor of eq. (11) for a ball over the defect (:mod:`._balance`); the other loaded balls
take up the load the defective contact sheds. The effective stiffness of eqs. (17)–(18) is made
dimensionally consistent as the **secant** stiffness matrix

    S(t) = sum_j [Q_j / (u_s . e_j)] e_j e_j^T        [N/m]

(ball load over the ring approach along the ball measured from the concentric position, at the
static solution ``u_s(t)``), so that ``S u_s = F`` exactly and eq. (19) reads

    m u'' + c_eq u' + S(t) u = F,       u = (x, y).

As printed, eq. (18) ``k_i = lambda mu K v^1.5 cos(psi - theta_0)`` has units N/m^1.5 and its
sums equal ``F_r / delta_max^1.5`` (and ``F_x/delta_max^1.5``, ``F_y/delta_max^1.5``), so the
literal eq. (19) would put the ring statically at ``x = y = delta_max^1.5`` whatever the load
direction; no consistent reading of that normalisation exists, so none is offered. We keep the
full 2×2 matrix (the printed eq. (19) drops the off-diagonal term; with it the static solution
is the true ring displacement). The secant needs ``P_d >= 0``.

The step function in time (a ball dropping into the defect) enters through ``S(t)``; the
quasi-static path is tabulated on the RK4 half-step grid (:func:`.common.integrate_model`).
"""

from __future__ import annotations

import numpy as np
from numba import cfunc, njit

from ..integrate import RHS_SIG
from . import _balance as bl
from .base import MODEL_FACTS, ModelKernel

__all__ = ["KERNEL"]


@njit(cache=True)
def _acc(t, y, p, row, r):
    """Seed VSM eq. (19) with the secant matrix ``S`` at ``row[r:]``: acceleration [m/s^2]."""
    m = p[bl.P_MASS]
    c = p[bl.P_DAMP]
    f0x, f0y = bl.applied_force(t, p)
    fx = f0x - row[r + bl.C_SXX] * y[0] - row[r + bl.C_SXY] * y[1]
    fy = f0y - row[r + bl.C_SXY] * y[0] - row[r + bl.C_SYY] * y[1]
    return (fx - c * y[2]) / m, (fy - c * y[3]) / m


@cfunc(RHS_SIG, cache=True)
def _vsm_rhs(t, y, p, dydt):
    """VSM right-hand side reading the tabulated secant stiffness (written out: no calls)."""
    j = int((t - p[bl.P_T0]) / p[bl.P_HTAB] + 0.5)  # table row of this stage time
    nt = int(p[bl.P_NTAB])
    j = 0 if j < 0 else (nt - 1 if j >= nt else j)
    r = bl.HEADER + bl.NCOL * j
    m = p[bl.P_MASS]
    c = p[bl.P_DAMP]
    f0x, f0y = bl.applied_force(t, p)
    fx = f0x - p[r + bl.C_SXX] * y[0] - p[r + bl.C_SXY] * y[1]
    fy = f0y - p[r + bl.C_SXY] * y[0] - p[r + bl.C_SYY] * y[1]
    dydt[0] = y[2]
    dydt[1] = y[3]
    dydt[2] = (fx - c * y[2]) / m  # seed VSM eq. (19), x
    dydt[3] = (fy - c * y[3]) / m  # seed VSM eq. (19), y


@cfunc(RHS_SIG, cache=True)
def _vsm_aux(t, y, p, out):
    """VSM auxiliary outputs (see :mod:`.common`); point values at the sample instant."""
    buf = np.empty(bl.NCOL)
    src, r = bl.output_row(t, p, buf)
    ax, ay = _acc(t, y, p, src, r)
    bl.fill_aux_row(t, p, src, r, bl.C_SXX, ax, ay, out)


@cfunc(RHS_SIG, cache=True)
def _vsm_rhs_exact(t, y, p, dydt):
    """VSM right-hand side solving the static balance at ``t`` (any time)."""
    row = np.empty(bl.NCOL)
    bl.static_on_the_fly(t, p, row, False)
    ax, ay = _acc(t, y, p, row, 0)
    dydt[0] = y[2]
    dydt[1] = y[3]
    dydt[2] = ax
    dydt[3] = ay


@cfunc(RHS_SIG, cache=True)
def _vsm_aux_exact(t, y, p, out):
    """VSM auxiliary outputs with the on-the-fly static solve."""
    row = np.empty(bl.NCOL)
    bl.static_on_the_fly(t, p, row, False)
    ax, ay = _acc(t, y, p, row, 0)
    bl.fill_aux_row(t, p, row, 0, bl.C_SXX, ax, ay, out)


KERNEL = ModelKernel("vsm", _vsm_rhs, _vsm_aux, _vsm_rhs_exact, _vsm_aux_exact, *MODEL_FACTS["vsm"])
