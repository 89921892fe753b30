"""DEM: displacement-excitation model, the seed VSM's first baseline.

The classic nonlinear 2-DOF ball-bearing model (Sawalhi & Randall 2008, MSSP 22(8) 1924–1951;
Petersen et al. 2015, MSSP 50–51, 139–160): the geometric drop of a ball over the defect enters
its deflection directly and the nonlinear Hertz forces of all balls are summed at the *dynamic*
ring displacement ``u``:

    m u'' + c_eq u' + sum_j f_j K (u . e_j - P_d/2 - o_j)_+^1.5 e_j = F,

with ``o_j = h_min`` (seed VSM eqs. (1)–(2)) for a ball over the defect (eq. (15)) and 0
otherwise (or ``f_j = gamma`` when a constant retention factor is prescribed). Same inputs,
defect geometry and kinematics as the VSM (:mod:`.balance`).
"""

from __future__ import annotations

from numba import cfunc, njit

from . import balance as bl
from .common import ModelKernel
from .integrate import RHS_SIG


@njit(cache=True)
def dem_force(t, ux, uy, p, point):
    """Bearing force on the ring ``sum Q_j e_j`` [N] and tangent stiffness entries [N/m] at
    displacement ``u`` and time ``t`` (cell-averaged defect indicator, or point values when
    ``point``; no allocation: the hot loop of the DEM)."""
    Z = int(p[bl.P_Z])
    s0, c0, rd, rw, hd, hw = bl.frame_cached(t, p)  # seed VSM eqs. (12)-(15)
    if point:
        hd = 0.0
        hw = 0.0
    step = bl.TWO_PI / Z
    fault = int(p[bl.P_FAULT])
    psil2 = 2.0 * p[bl.P_PSIL]
    ss = p[bl.P_SSTEP]
    cc = p[bl.P_CSTEP]
    dbeta = p[bl.P_DBETA]
    clr, doff, dfac, K, n = bl.constants(p)
    gx = 0.0
    gy = 0.0
    jxx = 0.0
    jxy = 0.0
    jyy = 0.0
    for _j in range(Z):
        # a ball over the defect loses the geometric drop h_min from its deflection
        fr, zf = bl.ball_flags(rd, rw, hd, hw, fault, psil2, dbeta)
        q, kk, _e = bl.ball_load(ux * s0 + uy * c0, fr, zf, clr, doff, dfac, K, n)
        if q > 0.0:
            gx += q * s0
            gy += q * c0
            jxx += kk * s0 * s0
            jxy += kk * s0 * c0
            jyy += kk * c0 * c0
        rd = bl.advance(rd, step)
        rw = bl.advance(rw, step)
        s1 = s0 * cc + c0 * ss
        c0 = c0 * cc - s0 * ss
        s0 = s1
    return gx, gy, jxx, jxy, jyy


@njit(cache=True)
def _deriv(t, y, p, out):
    gx, gy, _jxx, _jxy, _jyy = dem_force(t, y[0], y[1], p, False)
    m = p[bl.P_MASS]
    c = p[bl.P_DAMP]
    out[0] = y[2]
    out[1] = y[3]
    out[2] = (p[bl.P_FX] - gx - c * y[2]) / m  # DEM equation of motion
    out[3] = (p[bl.P_FY] - gy - c * y[3]) / m


@cfunc(RHS_SIG, cache=True)
def dem_rhs(t, y, p, dydt):
    """DEM right-hand side (nonlinear Hertz forces at the dynamic displacement)."""
    _deriv(t, y, p, dydt)


@cfunc(RHS_SIG, cache=True)
def dem_aux(t, y, p, out):
    """DEM auxiliary outputs; the stiffness is the tangent at the dynamic state."""
    gx, gy, jxx, jxy, jyy = dem_force(t, y[0], y[1], p, True)
    m = p[bl.P_MASS]
    c = p[bl.P_DAMP]
    ax = (p[bl.P_FX] - gx - c * y[2]) / m
    ay = (p[bl.P_FY] - gy - c * y[3]) / m
    bl.fill_aux_common(t, p, y[0], y[1], jxx, jxy, jyy, ax, ay, out)


KERNEL = ModelKernel("dem", dem_rhs, dem_aux, dem_rhs, dem_aux, False, "state")
