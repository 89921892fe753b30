"""DEM: displacement-excitation model, the seed VSM's first baseline.

The classic nonlinear 2-DOF ball-bearing model (Sawalhi & Randall 2008, MSSP 22(8) 1924–1951;
Petersen et al. 2015, MSSP 50–51, 139–160): the geometric drop of a ball over the defect enters
its deflection directly and the nonlinear Hertz forces of all balls are summed at the *dynamic*
ring displacement ``u``:

    m u'' + c_eq u' + sum_j f_j K (u . e_j - P_d/2 - o_j)_+^1.5 e_j = F,

with ``o_j = h_min`` (seed VSM eqs. (1)–(2)) for a ball over the defect (eq. (15)) and 0
otherwise (or ``f_j = gamma`` when a constant retention factor is prescribed). Same inputs,
defect geometry and kinematics as the VSM (:mod:`._balance`).
"""

from __future__ import annotations

import math

from numba import cfunc, njit

from ..integrate import RHS_SIG
from . import _balance as bl
from .base import MODEL_FACTS, ModelKernel

__all__ = ["KERNEL"]


@njit(cache=True, inline="always")
def _ball_sum(ux, uy, s0, c0, rd, rw, hd, hw, p, full, rough, axial, pit):
    """Bearing force ``sum Q_j e_j`` [N] and tangent entries [N/m] at displacement ``u`` from
    ball 1's direction ``(s0, c0)``, its angles past the defect/zone edges ``rd, rw`` and the
    cell half-widths ``hd, hw`` (the ball frame of :func:`._balance.frame_cached`), with the
    model's parameters read once from the packed vector ``p`` (layout :mod:`._balance`). This is
    the DEM's hot loop: inlined, scalars only inside the loop. ``rough``: the rough load law,
    a literal at the call site (:func:`._balance.ball_load`); ``full = False`` (the
    right-hand side) needs the force only: with rough contacts the tangent entries are then
    0. ``axial``: an axial load (:func:`._balance.ball_load_ax`), a literal at the hot call
    sites like ``rough`` (the axial copy is called out of line, :func:`_ball_sum_axial`), and
    so is ``pit``, a round pit (:func:`._balance.ball_load_pit`; :func:`_ball_sum_pit`)."""
    Z = int(p[bl.P_Z])
    fault = int(p[bl.P_FAULT])
    psil2 = 2.0 * p[bl.P_PSIL]
    dbeta = p[bl.P_DBETA]
    ss = p[bl.P_SSTEP]
    cc = p[bl.P_CSTEP]
    clr = p[bl.P_CLR]
    doff = p[bl.P_DOFF]
    doffi = p[bl.P_DOFFI]
    dfac = p[bl.P_DFAC]
    K = p[bl.P_K]
    n = p[bl.P_N]
    step = bl.TWO_PI / Z
    boff = int(p[bl.P_BDEV])
    gx = 0.0
    gy = 0.0
    jxx = 0.0
    jxy = 0.0
    jyy = 0.0
    for j in range(Z):
        # a ball over the defect loses the geometric drop h_min from its deflection
        fr, zf, dof = bl.ball_flags(j, rd, rw, hd, hw, fault, psil2, dbeta, doff, doffi, p)
        if pit:  # a literal: only the pit's copy has this
            if fr > 0.0:
                dof = bl.pit_dof(j, rd, hd, fault, dbeta, p)
        cl = bl.ball_clearance(p, boff, j, clr)  # a ball's diameter deviation, if any
        ue = ux * s0 + uy * c0
        q, kk, _e = bl.ball_load_ax(ue, fr, zf, cl, dof, dfac, K, n, p, full, rough, axial, pit)
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
def _ball_sum_axial(ux, uy, s0, c0, rd, rw, hd, hw, p, full, rough):
    """:func:`_ball_sum` under an axial load, compiled out of line: inlined into the
    right-hand side as a run-time choice, the axial law slowed the radial path (the static
    solve's equivalent measured ~10 %)."""
    return _ball_sum(ux, uy, s0, c0, rd, rw, hd, hw, p, full, rough, True, False)


@njit(cache=True)
def _ball_sum_pit(ux, uy, s0, c0, rd, rw, hd, hw, p, full, rough, axial):
    """:func:`_ball_sum` over a round pit, compiled out of line (a run-time test of the
    profile in the hot loop slowed every profile)."""
    return _ball_sum(ux, uy, s0, c0, rd, rw, hd, hw, p, full, rough, axial, True)


@njit(cache=True)
def _dem_force(t, ux, uy, p, point):
    """Bearing force on the ring ``sum Q_j e_j`` [N] and tangent stiffness entries [N/m] at
    displacement ``u`` and time ``t`` (cell-averaged defect indicator, or point values when
    ``point``)."""
    s0, c0, rd, rw, hd, hw = bl.frame_cached(t, p)  # seed VSM eqs. (12)-(15)
    if point:
        hd = 0.0
        hw = 0.0
    # once per output sample: a run-time choice of the law (one compiled copy) is cheap here
    rough = p[bl.P_ROUGH] > 0.0
    axial = p[bl.P_AXZ] != 0.0
    if p[bl.P_PROFILE] < -0.5:
        return _ball_sum_pit(ux, uy, s0, c0, rd, rw, hd, hw, p, True, rough, axial)
    return _ball_sum(ux, uy, s0, c0, rd, rw, hd, hw, p, True, rough, axial, False)


@cfunc(RHS_SIG, cache=True)
def _dem_rhs(t, y, p, dydt):
    """DEM right-hand side: nonlinear Hertz forces at the dynamic displacement (written out
    with scalar helpers only, so that nothing but arithmetic runs per call).

    The ball-frame block below is a hand-inlined copy of ``bl.frame_cached`` (the same
    arithmetic: results are bitwise equal); calling ``frame_cached`` or :func:`_dem_force`
    instead made DEM 15-20 % slower in ``benchmarks/bench_dynamics.py`` (2026-11-21), so keep
    the two in step when either changes."""
    if t == p[bl.P_CT]:  # the ball frame at this instant was computed for the previous stage
        s0 = p[bl.P_CS0]
        c0 = p[bl.P_CC0]
        rd = p[bl.P_CRD]
        rw = p[bl.P_CRW]
        hd = p[bl.P_CHD]
        hw = p[bl.P_CHW]
    else:
        wc = p[bl.P_WCAGE]
        th = wc * t + p[bl.P_ALPHA0]  # seed VSM eq. (12)
        if p[bl.P_SLIP] > 0.0:
            th += bl.slip_phase(t, p)
        rd = bl.defect_angle(th, t, p)  # eqs. (13), (15); a ball defect's spin angle
        rw = bl.wrap(th - p[bl.P_TH0] + p[bl.P_PSIL]) if p[bl.P_PSIL] > 0.0 else 0.0
        hd = 0.0
        hw = 0.0
        if p[bl.P_CELL] > 0.0:
            hh = p[bl.P_HTAB]
            k = int(math.floor((t - p[bl.P_T0]) / hh + 0.5))
            ht = hh / 3.0 if k % 2 == 0 else 2.0 * hh / 3.0
            hd = bl.defect_rate(p) * ht
            hw = wc * ht
        s0 = math.sin(th)
        c0 = math.cos(th)
        p[bl.P_CT] = t
        p[bl.P_CS0] = s0
        p[bl.P_CC0] = c0
        p[bl.P_CRD] = rd
        p[bl.P_CRW] = rw
        p[bl.P_CHD] = hd
        p[bl.P_CHW] = hw
    if p[bl.P_PROFILE] < -0.5:  # a round pit: its copy, out of line
        rough = p[bl.P_ROUGH] > 0.0
        axial = p[bl.P_AXZ] != 0.0
        gx, gy, _a, _b, _c = _ball_sum_pit(
            y[0], y[1], s0, c0, rd, rw, hd, hw, p, False, rough, axial
        )
    elif p[bl.P_AXZ] != 0.0:  # an axial load: its copy, out of line
        rough = p[bl.P_ROUGH] > 0.0
        gx, gy, _a, _b, _c = _ball_sum_axial(y[0], y[1], s0, c0, rd, rw, hd, hw, p, False, rough)
    elif p[bl.P_ROUGH] > 0.0:
        gx, gy, _a, _b, _c = _ball_sum(
            y[0], y[1], s0, c0, rd, rw, hd, hw, p, False, True, False, False
        )
    else:
        gx, gy, _a, _b, _c = _ball_sum(
            y[0], y[1], s0, c0, rd, rw, hd, hw, p, False, False, False, False
        )
    m = p[bl.P_MASS]
    c = p[bl.P_DAMP]
    dydt[0] = y[2]
    dydt[1] = y[3]
    f0x, f0y = bl.applied_force(t, p)
    dydt[2] = (f0x - gx - c * y[2]) / m  # DEM equation of motion
    dydt[3] = (f0y - gy - c * y[3]) / m


@cfunc(RHS_SIG, cache=True)
def _dem_aux(t, y, p, out):
    """DEM auxiliary outputs (point values at t); the stiffness is the tangent at the state."""
    gx, gy, jxx, jxy, jyy = _dem_force(t, y[0], y[1], p, True)
    m = p[bl.P_MASS]
    c = p[bl.P_DAMP]
    f0x, f0y = bl.applied_force(t, p)
    ax = (f0x - gx - c * y[2]) / m
    ay = (f0y - gy - c * y[3]) / m
    bl.fill_aux_common(t, p, y[0], y[1], jxx, jxy, jyy, ax, ay, out)


KERNEL = ModelKernel("dem", _dem_rhs, _dem_aux, _dem_rhs, _dem_aux, *MODEL_FACTS["dem"])
