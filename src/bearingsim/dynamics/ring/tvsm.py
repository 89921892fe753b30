"""TVSM: time-varying stiffness model after Petersen et al. (2015), the seed VSM's second baseline.

Petersen, Howard, Sawalhi, Moazen Ahmadi & Singh, "Analysis of bearing stiffness variations,
contact forces and vibrations in radially loaded double row rolling element bearings with raceway
defects", Mech. Syst. Signal Process. 50–51 (2015) 139–160 (seed VSM ref. [14]).

The bearing stiffness is Petersen's: the tangent matrix ``T = -dF_bearing/du`` of the nonlinear
Hertz contacts at the quasi-static equilibrium ``u_s(t)``, in which a ball over the defect loses
the geometric drop from its deflection (seed VSM: "[14] also counts the geometric distance as
released contact deformation"). The vibration is the linear time-varying response about that
quasi-static path,

    m u'' + c_eq u' + T(t) (u - u_s(t)) = 0,

i.e. the linearisation of the DEM (:mod:`.dem`) about ``u_s(t)``: parametric excitation by
``T(t)`` and displacement excitation by the jumps of ``u_s(t)``. With the retention factor of
seed eq. (11) evaluated implicitly, ``gamma K delta^1.5 = K (delta - h_min)^1.5``, so the
quasi-static path ``u_s`` is the same as the VSM's; the models differ in the stiffness
(tangent here, secant in the VSM) and in the form of the equation of motion.
"""

from __future__ import annotations

import numpy as np
from numba import cfunc, njit

from ..integrate import RHS_SIG
from . import _balance as bl
from .base import MODEL_FACTS, ModelKernel

__all__ = ["KERNEL"]


@njit(cache=True)
def _acc(y, p, row, r):
    """``m u'' = T (u_s - u) - c_eq u'`` with ``u_s``, ``T`` at ``row[r:]`` [m/s^2]."""
    m = p[bl.P_MASS]
    c = p[bl.P_DAMP]
    ex = row[r + bl.C_UX] - y[0]
    ey = row[r + bl.C_UY] - y[1]
    fx = row[r + bl.C_TXX] * ex + row[r + bl.C_TXY] * ey
    fy = row[r + bl.C_TXY] * ex + row[r + bl.C_TYY] * ey
    return (fx - c * y[2]) / m, (fy - c * y[3]) / m


@cfunc(RHS_SIG, cache=True)
def _tvsm_rhs(t, y, p, dydt):
    """TVSM right-hand side reading the tabulated tangent stiffness and static path
    (written out: no calls)."""
    j = int((t - p[bl.P_T0]) / p[bl.P_HTAB] + 0.5)  # table row of this stage time
    nt = int(p[bl.P_NTAB])
    j = 0 if j < 0 else (nt - 1 if j >= nt else j)
    r = bl.HEADER + bl.NCOL * j
    m = p[bl.P_MASS]
    c = p[bl.P_DAMP]
    ex = p[r + bl.C_UX] - y[0]
    ey = p[r + bl.C_UY] - y[1]
    fx = p[r + bl.C_TXX] * ex + p[r + bl.C_TXY] * ey
    fy = p[r + bl.C_TXY] * ex + p[r + bl.C_TYY] * ey
    dydt[0] = y[2]
    dydt[1] = y[3]
    dydt[2] = (fx - c * y[2]) / m
    dydt[3] = (fy - c * y[3]) / m


# (duplicates) the three entry points below match vsm.py's line for line but for the
# stiffness columns: each model's cfuncs must bind its own _acc at compile time, and cfuncs made
# by a shared factory are closures, which Numba does not cache on disk (checked with numba 0.68)
@cfunc(RHS_SIG, cache=True)
def _tvsm_aux(t, y, p, out):
    """TVSM auxiliary outputs (see :mod:`.common`); point values at the sample instant."""
    buf = np.empty(bl.NCOL)
    src, r = bl.output_row(t, p, buf)
    ax, ay = _acc(y, p, src, r)
    bl.fill_aux_row(t, p, src, r, bl.C_TXX, ax, ay, out)


@cfunc(RHS_SIG, cache=True)
def _tvsm_rhs_exact(t, y, p, dydt):
    """TVSM right-hand side solving the static balance at ``t``."""
    row = np.empty(bl.NCOL)
    bl.static_on_the_fly(t, p, row, False)
    ax, ay = _acc(y, p, row, 0)
    dydt[0] = y[2]
    dydt[1] = y[3]
    dydt[2] = ax
    dydt[3] = ay


@cfunc(RHS_SIG, cache=True)
def _tvsm_aux_exact(t, y, p, out):
    """TVSM auxiliary outputs with the on-the-fly static solve."""
    row = np.empty(bl.NCOL)
    bl.static_on_the_fly(t, p, row, False)
    ax, ay = _acc(y, p, row, 0)
    bl.fill_aux_row(t, p, row, 0, bl.C_TXX, ax, ay, out)


KERNEL = ModelKernel(
    "tvsm", _tvsm_rhs, _tvsm_aux, _tvsm_rhs_exact, _tvsm_aux_exact, *MODEL_FACTS["tvsm"]
)
