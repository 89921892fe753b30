"""Quasi-static force balance of the inner ring over the discrete balls with a local defect.

This is the static core shared by the VSM, TVSM and DEM kernels (seed VSM eqs. (4)–(16)). At
time ``t`` ball ``j`` sits at ``psi_j = w_cage t + alpha_0 + (j-1) 2 pi / Z`` (eq. (12)); a rigid
inner-ring displacement ``u = (u_x, u_y)`` gives it the *nominal* deflection
``delta_j = u_x sin psi_j + u_y cos psi_j - P_d/2`` (the Harris form of eqs. (4)–(7)) and the load

    Q_j = f_j K (delta_j - o_j)_+^n,                                  (seed VSM eqs. (9), (11))

with ``f_j = 1, o_j = 0`` for a ball on intact raceway and, for a ball over the defect
(eq. (15)), either

* the retention factor of eq. (11) evaluated implicitly: ``gamma_j = (1 - h_min/delta_j)^1.5``
  so that ``gamma_j K delta_j^1.5 = K (delta_j - h_min)_+^1.5`` — i.e. ``o_j = h_min``,
  ``f_j = 1`` (default, "physical"); or
* a prescribed constant retention factor ``f_j = gamma`` (``o_j = 0``), which is how the seed
  draws its figs. 6–7 (``gamma = 0.38``).

The balance ``sum_j Q_j (sin psi_j, cos psi_j) = (F_x, F_y)`` — all three lines of eq. (16):
both components, hence also the load-line one — is solved for ``u`` by Newton's method on the
convex potential ``sum f K (delta - o)_+^(n+1)/(n+1) - F.u`` with backtracking, warm-started
from the previous instant. In the fixed-step integration the defect indicator is averaged over
each RK4 stage's quadrature cell and the ball load is the corresponding blend of the intact and
the defective load (:func:`cell_halfwidth`, :func:`ball_load`); traces and the adaptive
integrator use the point values. The load-zone flag ``lambda_j`` of eq. (14) is ``delta_j > 0`` (the
contact decides, default) or, for the seed's literal rule, membership of the fixed window
``[theta_0 - psi_L, theta_0 + psi_L]`` with a given ``psi_L`` (a ball outside it carries no
load even when compressed).

Stiffness matrices returned (2×2, symmetric, [N/m]):

secant ``S = sum_j s_j e_j e_j^T``, ``s_j = Q_j / (u . e_j)``
    Ball force over the ring approach measured from the concentric position, so that
    ``S u = F`` holds exactly at the static solution. This is the dimensionally consistent form
    of seed VSM eqs. (17)–(18) used by the VSM (SPEC §1.5). It requires ``P_d >= 0``.
tangent ``T = sum_j n Q_j / (delta_j - o_j) e_j e_j^T``
    ``-dF_bearing/du``, the bearing stiffness of Petersen et al. (2015), used by the TVSM.

The compiled functions read their inputs from the flat model parameter vector ``p`` whose
layout is given by the ``P_*`` offsets below (shared by every kernel in this package).

Developer note: Numba's on-disk cache of a function is keyed on its own source file only, so
the cached cfuncs of :mod:`.vsm`, :mod:`.tvsm` and :mod:`.dem` keep the constants of this
module that were current when they were compiled. After editing this module delete the
package's ``__pycache__/*.nbi`` and ``*.nbc`` files.
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

from ...contact.rough import rough_ball
from ...load_distribution import _solve_1d
from ..defect_drop import edge_drop
from ..defect_pit import pit_share
from ..slip import cage_angle

__all__: list[str] = []  # private: compiled helpers of the ring models

# ---------------------------------------------------------------- parameter vector layout
P_MASS = 0  #: vibrating mass m [kg]
P_DAMP = 1  #: equivalent damping c_eq [N s/m]
P_FX = 2  #: applied force F_x [N]
P_FY = 3  #: applied force F_y [N]
P_Z = 4  #: number of balls Z [-]
P_K = 5  #: ball load-deflection constant K [N/m^n]
P_N = 6  #: load-deflection exponent n [-]
P_CLR = 7  #: half diametral clearance P_d/2 [m]
P_WCAGE = 8  #: cage angular speed 2 pi f_m [rad/s]
P_WSHAFT = 9  #: shaft angular speed 2 pi f_s [rad/s]
P_ALPHA0 = 10  #: first-ball azimuth alpha_0 [rad]
P_FAULT = 11  #: 0 none, 1 outer, 2 inner, 3 ball (ball 1 carries the defect)
P_BETA0 = 12  #: defect left edge at t = 0, beta_0 [rad] (ball: its spin angle)
P_DBETA = 13  #: defect angular extent Delta_beta [rad] (ball: on the ball)
P_DFAC = 14  #: load factor of a ball over the defect (prescribed gamma, else 1) [-]
P_DOFF = 15  #: deflection offset of a ball over the defect (h_min, else 0) [m]
P_T0 = 16  #: time of the first table row [s]
P_HTAB = 17  #: table spacing (half the RK4 step) [s]
P_NTAB = 18  #: number of table rows [-]
P_PERBALL = 19  #: 1 to fill per-ball auxiliary outputs [-]
P_WARMX = 20  #: warm start u_x of the on-the-fly static solve (scratch) [m]
P_WARMY = 21  #: warm start u_y (scratch) [m]
P_TOL = 22  #: relative force tolerance of the static solve [-]
P_PSIL = 23  #: fixed load-zone half angle psi_L of eq. (14) [rad]; 0 = contact-defined zone
P_TH0 = 24  #: load direction theta_0 = atan2(F_x, F_y) [rad]
P_SSTEP = 25  #: sin(2 pi / Z) [-]
P_CSTEP = 26  #: cos(2 pi / Z) [-]
P_CT = 27  #: time of the cached ball frame (scratch, NaN = empty) [s]
P_CS0 = 28  #: cached sin of ball 1's azimuth (scratch) [-]
P_CC0 = 29  #: cached cos of ball 1's azimuth (scratch) [-]
P_CRD = 30  #: cached ball-1 angle past the defect edge (scratch) [rad]
P_CRW = 31  #: cached ball-1 angle past the fixed-zone edge (scratch) [rad]
P_CELL = 32  #: 1 = average the defect/zone indicators over the RK4 quadrature cell of t [-]
P_CHD = 33  #: cached angular half-width of the defect cell (scratch) [rad]
P_CHW = 34  #: cached angular half-width of the zone cell (scratch) [rad]
P_SLIP = 35  #: offset in ``p`` of the slip table of ball-pass instants (0 = no slip) [-]
P_SLIPN = 36  #: entries of the slip table [-]
P_SLIPDT = 37  #: nominal ball-pass period 2 pi / (Z w_cage) [s]
P_DOFFI = 38  #: ball defect: deflection offset at the inner-race contact (h_min_inner) [m]
P_SPIN = 39  #: ball defect: ball spin angle per cage angle, BSF / FTF [-]
P_BDEV = 40  #: offset in ``p`` of the Z ball-diameter deviations Delta D_j (0 = none) [-]
P_FU = 41  #: amplitude of a force rotating with the shaft (unbalance) F_u [N]
P_PROFILE = 42  #: profile of the defect: 0 rectangular (seed VSM), 1 geometric, -1 pit [-]
P_RBALL = 43  #: ball radius r [m] (geometric profile)
P_HALFW = 44  #: half the defect width b/2 [m] (geometric profile)
P_DEPTH = 45  #: defect depth h_d [m] (geometric profile)
P_RRACE = 46  #: radius of the faulty raceway [m] (ball defect: the outer raceway's)
P_RRACEI = 47  #: ball defect: the inner raceway's radius [m] (geometric profile)
P_ROUGH = 48  #: composite RMS surface roughness sigma of the rough load law [m] (0 = Hertz)
P_RINV = 49  #: 1 / sigma [1/m] (rough law)
P_RSN1 = 50  #: sigma^(1/2) [m^(1/2)] (rough law, balls: n = 3/2)
P_AXZ = 51  #: axial offset z of the inner ring's groove centres under an axial load [m] (0 = none)
P_A0 = 52  #: distance A0 = (f_i + f_o - 1) d of the groove centres of a just-touching ball [m]
P_PITA = 53  #: pit: a^2 per unit approach of the faulty contact, A of :mod:`..defect_pit` [m]
P_PITB = 54  #: pit: b^2 per unit approach, B [m]
P_PITW = 55  #: pit: the faulty contact's share of the ball's compliance, w [-]
P_PITAI = 56  #: ball pit: A at the inner-race contact [m] (P_PITA..P_PITW: the outer race's)
P_PITBI = 57  #: ball pit: B at the inner-race contact [m]
P_PITWI = 58  #: ball pit: w of the inner-race contact [-]
HEADER = 59  #: first table entry

#: table columns: static u_x, u_y, secant S_xx, S_xy, S_yy, tangent T_xx, T_xy, T_yy
NCOL = 8
C_UX, C_UY, C_SXX, C_SXY, C_SYY, C_TXX, C_TXY, C_TYY = range(NCOL)

TWO_PI = 2.0 * math.pi


@njit(cache=True, inline="always")
def hertz(dj, n):
    """``dj^n`` with the fast path ``dj sqrt(dj)`` for balls (n = 1.5)."""
    return dj * math.sqrt(dj) if n == 1.5 else dj**n


@njit(cache=True, inline="always")
def hertz_and_slope(d, K, n):
    """``K d^n`` [N] and ``n K d^(n-1)`` [N/m] for ``d > 0`` (no division for n = 1.5)."""
    if n == 1.5:
        sd = math.sqrt(d)
        return K * d * sd, 1.5 * K * sd
    q = K * d**n
    return q, n * q / d


@njit(cache=True, inline="always")
def wrap(x):
    """``x`` modulo 2 pi in [0, 2 pi) [rad]."""
    r = x - TWO_PI * math.floor(x / TWO_PI)
    return r if r < TWO_PI else 0.0


@njit(cache=True, inline="always")
def slip_phase(t, p):
    """Random slip: the cage's angle at ``t`` minus its kinematic angle ``w_cage t`` [rad]
    (0 without slip). The table at ``p[P_SLIP]`` holds the ball-pass instants ``t_k`` (the
    cage at ``k 2 pi / Z``); between two of them the cage turns uniformly (see
    :meth:`.base.ModelInputs.slip_table`)."""
    off = int(p[P_SLIP])
    if off == 0:
        return 0.0
    angle, _ = cage_angle(t, p, off, int(p[P_SLIPN]), p[P_SLIPDT], TWO_PI / p[P_Z])
    return angle - p[P_WCAGE] * t


@njit(cache=True, inline="always")
def defect_angle(th, t, p):
    """Angle past the defect's left edge modulo 2 pi [rad] for ball 1 at azimuth ``th``: on the
    outer race ``th - beta_0``; on the inner race ``th - w_shaft t - beta_0`` (eq. (13): the
    defect turns with the shaft); on ball 1 its spin angle ``spin (th - alpha_0) + beta_0``
    (the ball rolls on the fixed outer race: it spins ``BSF/FTF`` times the cage angle, random
    slip included), the defect facing the outer race at 0 and the inner race at pi; 0 without a
    defect."""
    fault = int(p[P_FAULT])
    if fault == 1:
        return wrap(th - p[P_BETA0])
    if fault == 2:
        return wrap(th - p[P_WSHAFT] * t - p[P_BETA0])
    if fault == 3:
        return wrap(p[P_SPIN] * (th - p[P_ALPHA0]) + p[P_BETA0])
    return 0.0


@njit(cache=True, inline="always")
def defect_rate(p):
    """Rate of :func:`defect_angle` [rad/s] (slip aside): ``w_cage`` (outer), ``|w_cage -
    w_shaft|`` (inner), ``spin w_cage`` (ball)."""
    fault = int(p[P_FAULT])
    if fault == 2:
        return abs(p[P_WCAGE] - p[P_WSHAFT])
    if fault == 3:
        return p[P_SPIN] * p[P_WCAGE]
    return p[P_WCAGE]


@njit(cache=True, inline="always")
def frame(t, p):
    """Angles of ball 1 at time ``t``: its azimuth (eq. (12)), its angle past the defect's left
    edge modulo 2 pi (eqs. (13), (15)) and past the lower edge of a fixed load-zone window
    (eq. (14)) [rad]."""
    th = p[P_WCAGE] * t + p[P_ALPHA0]  # seed VSM eq. (12)
    if p[P_SLIP] > 0.0:
        th += slip_phase(t, p)
    rel_d = defect_angle(th, t, p)
    rel_w = 0.0
    if p[P_PSIL] > 0.0:
        rel_w = wrap(th - p[P_TH0] + p[P_PSIL])
    return th, rel_d, rel_w


@njit(cache=True, inline="always")
def cell_halfwidth(t, p):
    """Half-width [s] of the RK4 quadrature cell of stage time ``t`` (0 = point evaluation).

    RK4 integrates a time-only forcing with Simpson's weights 1/6, 4/6, 1/6 at ``t``,
    ``t + dt/2``, ``t + dt``; giving each stage time the cell ``[t - dt/6, t + dt/6]`` (step
    boundaries, shared by two steps) or ``[t - dt/3, t + dt/3]`` (midpoints) tiles the time axis
    with cells proportional to the weights. Averaging a step function (a ball entering the
    defect) over these cells makes its time integral exact instead of first-order in dt.
    """
    if p[P_CELL] <= 0.0:
        return 0.0
    h = p[P_HTAB]  # dt / 2
    k = int(math.floor((t - p[P_T0]) / h + 0.5))
    return h / 3.0 if k % 2 == 0 else 2.0 * h / 3.0


@njit(cache=True, inline="always")
def frame_cached(t, p):
    """``(sin, cos)`` of ball 1's azimuth, the two relative angles of :func:`frame` and the
    angular half-widths of the defect and zone cells at ``t``, cached in the scratch slots of
    ``p`` (RK4 evaluates each stage time twice)."""
    if t == p[P_CT]:
        return p[P_CS0], p[P_CC0], p[P_CRD], p[P_CRW], p[P_CHD], p[P_CHW]
    th, rd, rw = frame(t, p)
    s0 = math.sin(th)
    c0 = math.cos(th)
    ht = cell_halfwidth(t, p)
    hd = defect_rate(p) * ht
    hw = p[P_WCAGE] * ht
    p[P_CT] = t
    p[P_CS0] = s0
    p[P_CC0] = c0
    p[P_CRD] = rd
    p[P_CRW] = rw
    p[P_CHD] = hd
    p[P_CHW] = hw
    return s0, c0, rd, rw, hd, hw


@njit(cache=True, inline="always")
def _overlap(a0, a1, b0, b1):
    lo = a0 if a0 > b0 else b0
    hi = a1 if a1 < b1 else b1
    return hi - lo if hi > lo else 0.0


@njit(cache=True, inline="always")
def cell_fraction(r, half, width):
    """Fraction of the angle interval ``[r - half, r + half]`` (``r`` in [0, 2 pi)) lying in
    ``[0, width)`` modulo 2 pi; the indicator ``r < width`` when ``half == 0``."""
    if half <= 0.0:
        return 1.0 if r < width else 0.0
    if width + half <= r <= TWO_PI - half:
        return 0.0  # the cell does not reach the window (the common case)
    if half <= r <= width - half:
        return 1.0
    a0 = r - half
    a1 = r + half
    ov = (
        _overlap(a0, a1, 0.0, width)
        + _overlap(a0, a1, TWO_PI, TWO_PI + width)
        + _overlap(a0, a1, -TWO_PI, width - TWO_PI)
    )
    return ov / (a1 - a0)


@njit(cache=True, inline="always")
def geometric_drop(r, dbeta, rpath, rb, rr, sg, halfw, depth):
    """Drop [m] of a ball whose angle past the defect's left edge is ``r`` [rad] (extent
    ``dbeta``, measured along a circle of radius ``rpath`` [m]): it rests on the nearer edge,
    ``e = b/2 - |x|`` from its centre line (``x`` the arc distance from the defect centre), and
    drops :func:`..defect_drop.edge_drop` (``sg`` -1 outer race, +1 inner race; at most
    ``depth``): 0 at the edges, ``h_min`` at the centre."""
    if r >= dbeta:
        return 0.0
    e = halfw - rpath * abs(r - 0.5 * dbeta)
    if e <= 0.0:
        return 0.0
    return edge_drop(e, rb, rr, sg, depth)[0]


@njit(cache=True, inline="always")
def pit_offset(r, dbeta, rpath):
    """Distance [m] along the track from a round pit's centre to the contact of a ball whose
    angle past the pit's window edge is ``r`` [rad] (the window of extent ``dbeta``, the pit's
    plus the contact's length, centred on it; measured along a circle of radius ``rpath`` [m])."""
    return rpath * abs(r - 0.5 * dbeta)


@njit(cache=True)
def pit_dof(j, rd, hd, fault, dbeta, p):
    """What a pit's load (:func:`_pit_load`) takes in place of ball ``j``'s drop: the distance
    ``x_c`` [m] of the pit's centre from the ball's contact (:func:`pit_offset`, at the cell's
    centre), for a ball pit ``-1 - x_c`` where it meets the inner race (which contact's
    constants to take). Called on the pit's paths only, out of line: a test of the profile in
    :func:`defect_fraction` slowed every profile's hot loop (twenty-second session, A/B)."""
    if fault != 3:
        return pit_offset(rd, dbeta, p[P_RRACE])
    rb = p[P_RBALL]
    ri = advance(rd, math.pi)
    if cell_fraction(rd, hd, dbeta) >= cell_fraction(ri, hd, dbeta):
        return pit_offset(rd, dbeta, rb)
    return -1.0 - pit_offset(ri, dbeta, rb)


@njit(cache=True)
def _pit_dofs(rd, step, hd, fault, dbeta, p, fr, dof):
    """:func:`pit_dof` of every ball over the pit (``fr > 0``) into ``dof``, ball 0's angle
    past the pit's window edge ``rd`` [rad] and one ball pitch ``step`` [rad] apart."""
    for j in range(fr.size):
        if fr[j] > 0.0:
            dof[j] = pit_dof(j, rd, hd, fault, dbeta, p)
        rd = advance(rd, step)


@njit(cache=True, inline="always")
def defect_fraction(j, rd, hd, fault, dbeta, doff, doffi, p):
    """Defect fraction ``f_d`` of ball ``j`` (0-based; eq. (15): 1 = over the defect, averaged
    over the quadrature cell) and its drop [m]. A raceway defect: ``rd`` is the ball's angle
    past the defect edge. A ball defect (``fault == 3``): only ball 0 carries it, ``rd`` is its
    spin angle past the defect edge, and the defect meets the outer race (drop ``doff``) at
    ``rd`` in ``[0, dbeta)`` and the inner race (drop ``doffi``) half a turn later. The drop
    is the constant ``doff`` / ``doffi`` (rectangular profile, seed VSM) or, with
    ``p[P_PROFILE] == 1``, :func:`geometric_drop` at ``rd`` (the cell's centre; it is 0 at the
    edges, where the cell average of the indicator matters). A pit (``p[P_PROFILE] == -1``)
    takes the rectangle's branch here; its paths replace the drop by :func:`pit_dof`."""
    if fault == 0:
        return 0.0, doff
    geo = p[P_PROFILE] > 0.5
    if fault != 3:
        fr = cell_fraction(rd, hd, dbeta)
        if geo and fr > 0.0:
            rr = p[P_RRACE]
            sg = -1.0 if fault == 1 else 1.0
            return fr, geometric_drop(rd, dbeta, rr, p[P_RBALL], rr, sg, p[P_HALFW], p[P_DEPTH])
        return fr, doff
    if j != 0:
        return 0.0, doff
    fo = cell_fraction(rd, hd, dbeta)
    ri = advance(rd, math.pi)
    fi = cell_fraction(ri, hd, dbeta)
    if geo:
        rb = p[P_RBALL]
        if fo >= fi:
            return fo + fi, geometric_drop(
                rd, dbeta, rb, rb, p[P_RRACE], -1.0, p[P_HALFW], p[P_DEPTH]
            )
        return fo + fi, geometric_drop(ri, dbeta, rb, rb, p[P_RRACEI], 1.0, p[P_HALFW], p[P_DEPTH])
    return fo + fi, (doff if fo >= fi else doffi)


@njit(cache=True, inline="always")
def ball_flags(j, rd, rw, hd, hw, fault, psil2, dbeta, doff, doffi, p):
    """Defect fraction ``f_d`` and drop (:func:`defect_fraction`) and zone factor ``f_z``
    (eq. (14) fixed window: 1 = inside) of ball ``j`` from its angle past the defect edge
    ``rd`` and past the window edge ``rw``, averaged over the quadrature cell [-]."""
    fr, dof = defect_fraction(j, rd, hd, fault, dbeta, doff, doffi, p)
    zf = cell_fraction(rw, hw, psil2) if psil2 > 0.0 else 1.0
    return fr, zf, dof


@njit(cache=True)
def _pit_load(ue, fr, zf, clr, xc, dfac, K, n, p, full, rough):
    """:func:`ball_load` of a ball over a round pit (``p[P_PROFILE] == -1``), out of line (only
    the ball over the defect pays for it): the blend ``(1 - f_d) Q(d) + f_d rho(d) Q(d)`` of the
    intact law ``Q`` (Hertz or rough) at ``d = u.e - P_d/2``, ``rho`` the share the contact
    beside the pit keeps (:func:`..defect_pit.pit_share` at the Hertz approach of ``Q``, ``(Q /
    K)^(1/n)``: ``d`` for Hertz's law; ``xc`` the pit centre's distance from the contact [m],
    ``-1 - x_c`` for a ball pit at the inner race). The potential is ``rho`` times the intact
    one (no solver uses it)."""
    d = ue - clr
    if rough:
        q0, k0, e0 = rough_ball(d, K, p[P_ROUGH], p[P_RINV], p[P_RSN1], full)
    elif d > 0.0:
        q0, k0 = hertz_and_slope(d, K, n)
        e0 = q0 * d / (n + 1.0)
    else:
        return 0.0, 0.0, 0.0
    rh = p[P_HALFW]
    # the contact's size from the load it carries: the Hertz approach of that load (d itself
    # for Hertz's law; a rough contact carries load, and has a size, before the surfaces meet)
    de = (q0 / K) ** (1.0 / n) if q0 > 0.0 else 0.0
    if xc < 0.0:
        rho, drho = pit_share(de, -1.0 - xc, rh, p[P_PITAI], p[P_PITBI], p[P_PITWI], n, full)
    else:
        rho, drho = pit_share(de, xc, rh, p[P_PITA], p[P_PITB], p[P_PITW], n, full)
    if full and de > 0.0:  # d rho / d d = d rho / d de * d de / d d
        drho *= de * k0 / (n * q0)
    w = 1.0 - fr + fr * dfac * rho
    dw = fr * dfac * drho
    return zf * w * q0, zf * (w * k0 + dw * q0), zf * w * e0


@njit(cache=True, inline="always")
def ball_load(ue, fr, zf, clr, doff, dfac, K, n, p, full, rough):
    """Load Q [N], stiffness dQ/d(u.e) [N/m] and contact potential [J] of one ball whose ring
    approach is ``u.e`` [m]: the blend ``(1 - f_d) Q_intact + f_d Q_defect`` (times ``f_z``)
    with ``Q_intact = K (u.e - P_d/2)_+^n`` and ``Q_defect = gamma K (u.e - P_d/2 - h)_+^n``
    (seed VSM eqs. (9), (11)). With ``rough`` (a roughness ``p[P_ROUGH] > 0``) each is the
    rough law (:func:`..contact.rough.rough_ball`, n = 3/2, called out of line) of the same
    deflection instead of ``(.)_+^n``; ``full = False`` then gives the load only (stiffness
    and potential 0).

    The DEM's right-hand side (its hot loop, every RK4 stage) passes ``rough`` as a literal
    constant chosen once per call, so its Hertz copy compiles without the rough branch: a
    run-time test there slowed the DEM's Hertz path by ~45 %. The static solve
    (:func:`static_kernel`) and the per-sample outputs test it at run time: no slower measured,
    and a second compiled copy of the Newton loop doubled the VSM kernels' compile time."""
    q = 0.0
    dq = 0.0
    pot = 0.0
    if zf > 0.0:
        if rough:
            sig = p[P_ROUGH]
            inv = p[P_RINV]
            sn1 = p[P_RSN1]
            if fr < 1.0:
                w = (1.0 - fr) * zf
                qo, ko, eo = rough_ball(ue - clr, K, sig, inv, sn1, full)
                q += w * qo
                dq += w * ko
                pot += w * eo
            if fr > 0.0:
                w = fr * zf * dfac
                qi, ki, ei = rough_ball(ue - clr - doff, K, sig, inv, sn1, full)
                q += w * qi
                dq += w * ki
                pot += w * ei
            return q, dq, pot
        if fr < 1.0:
            d = ue - clr
            if d > 0.0:
                w = (1.0 - fr) * zf
                qo, ko = hertz_and_slope(d, K, n)
                q += w * qo
                dq += w * ko
                pot += w * qo * d / (n + 1.0)
        if fr > 0.0:
            d = ue - clr - doff
            if d > 0.0:
                w = fr * zf * dfac
                qi, ki = hertz_and_slope(d, K, n)
                q += w * qi
                dq += w * ki
                pot += w * qi * d / (n + 1.0)
    return q, dq, pot


@njit(cache=True, inline="always")
def ball_load_pit(ue, fr, zf, clr, doff, dfac, K, n, p, full, rough, pit):
    """:func:`ball_load`, or with ``pit`` (``p[P_PROFILE] == -1``) for a ball over the defect
    :func:`_pit_load`. ``pit`` is a literal at the hot call sites, where the branch then
    compiles away: a run-time test of the profile inside :func:`ball_load` made the VSM's static
    solve 1.9x slower (twenty-second session, A/B), as the axial law's did (:func:`_side_sums`)."""
    if pit:
        if fr > 0.0:
            return _pit_load(ue, fr, zf, clr, doff, dfac, K, n, p, full, rough)
    return ball_load(ue, fr, zf, clr, doff, dfac, K, n, p, full, rough)


@njit(cache=True, inline="always")
def axial_approach(ue, cl, p):
    """Normal approach of a ball, written as the radial approach that gives it,
    ``sqrt((A0 - cl + u.e)^2 + z^2) - A0 + cl`` [m], and the cosine of its contact angle
    ``(A0 - cl + u.e) / sqrt(...)`` [-], with the inner ring's groove centres offset axially
    by ``z = p[P_AXZ]`` (Jones 1960; Harris & Kotzalas 2007 vol. 2 §3; the geometry of
    :mod:`bearingsim.quasistatic.jones` with the ring tilts held at 0). ``cl``: the ball's half
    clearance (:func:`ball_clearance`)."""
    a0 = p[P_A0]
    r = a0 - cl + ue
    z = p[P_AXZ]
    a = math.sqrt(r * r + z * z)
    return a - a0 + cl, r / a, a


@njit(cache=True, inline="always")
def ball_load_ax(ue, fr, zf, cl, doff, dfac, K, n, p, full, rough, axial, pit):
    """:func:`ball_load` of a ball under an axial load (``axial``): the load ``Q`` along the
    contact normal at the normal approach of :func:`axial_approach` (the defect's drop taken
    from it), returned as its radial component ``Q cos(alpha)`` [N] with the radial stiffness
    ``dQ_r/d(u.e) = Q' cos^2(alpha) + Q sin^2(alpha) / A`` [N/m] (the groove centres' distance
    ``A``) and the contact potential [J]. Without ``axial``, :func:`ball_load` itself (bit for
    bit). ``pit``: :func:`ball_load_pit`'s."""
    if not axial:
        return ball_load_pit(ue, fr, zf, cl, doff, dfac, K, n, p, full, rough, pit)
    un, ca, a = axial_approach(ue, cl, p)
    q, kk, pot = ball_load_pit(un, fr, zf, cl, doff, dfac, K, n, p, full, rough, pit)
    return q * ca, kk * ca * ca + q * (1.0 - ca * ca) / a, pot


@njit(cache=True, inline="always")
def loaded_threshold(p):
    """Load above which a ball counts as loaded [N]: 0 for Hertz; with a roughness the load of
    a ball at zero nominal deflection, ``K sigma^n g_n(0)`` (a ball counts as loaded when its
    mean planes overlap, not when its asperities first touch)."""
    sig = p[P_ROUGH]
    if sig <= 0.0:
        return 0.0
    return rough_ball(0.0, p[P_K], sig, p[P_RINV], p[P_RSN1], False)[0]


@njit(cache=True, inline="always")
def applied_force(t, p):
    """Force on the inner ring at ``t`` [N]: the constant ``(F_x, F_y)`` plus, with an
    unbalance, ``F_u (sin w_s t, cos w_s t)`` turning with the shaft (azimuth from +y towards
    +x, the sense of the balls' eq. (12))."""
    fu = p[P_FU]
    if fu == 0.0:
        return p[P_FX], p[P_FY]
    ph = p[P_WSHAFT] * t
    return p[P_FX] + fu * math.sin(ph), p[P_FY] + fu * math.cos(ph)


@njit(cache=True, inline="always")
def ball_clearance(p, off, j, clr):
    """Half clearance ``P_d/2`` less ball ``j``'s diameter deviation ``Delta D_j`` [m]: a ball
    larger than nominal by ``Delta D_j`` closes the gap between the raceways along its line by
    its whole ``Delta D_j`` (it touches both races), so its nominal deflection is
    ``u.e_j - P_d/2 + Delta D_j``. ``off = int(p[P_BDEV])`` (read once by the caller); ``clr``
    itself without deviations (``off == 0``)."""
    return clr if off == 0 else clr - p[off + j]


@njit(cache=True, inline="always")
def advance(r, step):
    """``r + step`` wrapped into [0, 2 pi) (``0 <= r < 2 pi``, ``0 < step < 2 pi``)."""
    r += step
    return r - TWO_PI if r >= TWO_PI else r


@njit(cache=True, inline="always")
def constants(p):
    """``(P_d/2, h, gamma, K, n)`` of the ball load law from ``p``."""
    return p[P_CLR], p[P_DOFF], p[P_DFAC], p[P_K], p[P_N]


@njit(cache=True)
def initial_guess(sn, cs, clr, K, n, fx, fy):
    """Ring displacement of the intact bearing along the load line (start for Newton) [m]."""
    F = math.hypot(fx, fy)
    th0 = math.atan2(fx, fy)
    s0 = math.sin(th0)
    c0 = math.cos(th0)
    cosl = np.empty(sn.size)
    ones = np.ones(sn.size)
    for j in range(sn.size):
        cosl[j] = sn[j] * s0 + cs[j] * c0
    dr = _solve_1d(cosl, ones, clr, K, n, F)
    return dr * s0, dr * c0


@njit(cache=True)
def _side_sums(vx, vy, sn, cs, fr, zf, clj, dof, dfac, K, n, p, rough, axial):
    """Bearing force ``sum Q_j cos(alpha_j) e_j`` [N], tangent and secant entries [N/m] of the
    static solve at ring displacement ``(vx, vy)`` [m] under an axial load
    (:func:`ball_load_ax`) or over a pit (:func:`ball_load_pit`; the profile read at run
    time): the static solve's paths off the radial slot's, compiled out of line so that they
    do not slow it. The secant is formed without an axial load only (the VSM, which needs it,
    refuses one)."""
    pit = p[P_PROFILE] < -0.5
    qx = qy = kxx = kxy = kyy = lxx = lxy = lyy = 0.0
    for j in range(sn.size):
        ue = vx * sn[j] + vy * cs[j]
        q, kk, _e = ball_load_ax(
            ue, fr[j], zf[j], clj[j], dof[j], dfac, K, n, p, True, rough, axial, pit
        )
        if q > 0.0:
            a = sn[j]
            b = cs[j]
            qx += q * a
            qy += q * b
            kxx += kk * a * a
            kxy += kk * a * b
            kyy += kk * b * b
            if not axial:  # the secant from the concentric position (as the radial loop)
                sk = q / ue if ue > 0.0 else 0.0
                lxx += sk * a * a
                lxy += sk * a * b
                lyy += sk * b * b
    return qx, qy, kxx, kxy, kyy, lxx, lxy, lyy


@njit(cache=True)
def static_kernel(times, point, p, table, residual, ux, uy):
    """Static solution of eq. (16) and the secant/tangent matrices at every time of ``times``.

    Fills ``table`` (shape ``(len(times), NCOL)``) and ``residual`` (relative force residual
    ``|sum Q e - F| / |F|``); ``(ux, uy)`` is the warm start (NaN = cold start) and Newton
    starts from the linear extrapolation of the two previous solutions. The defect and zone
    indicators are cell averages (``p[P_CELL]``) unless ``point``. Damped Newton: a step is
    halved until the force residual decreases (the Newton direction of a convex potential's
    gradient is a descent direction of the residual norm); a start that does not converge is
    retried from the intact bearing's load-line solution. Returns the last ``(ux, uy)``.

    Written as one loop over scalars (no array-argument helper calls in the hot path: each such
    call costs reference-count updates that dominate a 9-ball sum).
    """
    Z = int(p[P_Z])
    sn = np.empty(Z)
    cs = np.empty(Z)
    fr = np.empty(Z)
    zf = np.empty(Z)
    dof = np.empty(Z)
    clj = np.empty(Z)
    boff = int(p[P_BDEV])
    for j in range(Z):
        clj[j] = ball_clearance(p, boff, j, p[P_CLR])
    wc = p[P_WCAGE]
    a0 = p[P_ALPHA0]
    fault = p[P_FAULT]
    dbeta = p[P_DBETA]
    psil = p[P_PSIL]
    psil2 = 2.0 * psil
    th0 = p[P_TH0]
    ss = p[P_SSTEP]
    cc = p[P_CSTEP]
    step = TWO_PI / Z
    clr = p[P_CLR]
    doff = p[P_DOFF]
    doffi = p[P_DOFFI]
    ifault = int(fault)
    dfac = p[P_DFAC]
    K = p[P_K]
    n = p[P_N]
    fx = p[P_FX]
    fy = p[P_FY]
    scale = math.hypot(fx, fy)
    if scale <= 0.0:
        scale = 1.0
    tol = p[P_TOL]
    cell = p[P_CELL] > 0.0 and not point
    rough = p[P_ROUGH] > 0.0
    axial = p[P_AXZ] != 0.0  # an axial load: the normal approach of axial_approach
    pit = p[P_PROFILE] < -0.5  # a round pit: its share of the load (_pit_load)
    hh = p[P_HTAB]
    t0 = p[P_T0]
    w_rel = defect_rate(p)
    px = math.nan
    py = math.nan
    for i in range(times.size):
        t = times[i]
        fx, fy = applied_force(t, p)
        # ---- ball positions and defect/zone indicators (eqs. 12-15)
        th = wc * t + a0
        if p[P_SLIP] > 0.0:
            th += slip_phase(t, p)
        rd = defect_angle(th, t, p)
        rw = wrap(th - th0 + psil) if psil > 0.0 else 0.0
        hd = 0.0
        hw = 0.0
        if cell:
            k = int(math.floor((t - t0) / hh + 0.5))
            ht = hh / 3.0 if k % 2 == 0 else 2.0 * hh / 3.0
            hd = w_rel * ht
            hw = wc * ht
        s0 = math.sin(th)
        c0 = math.cos(th)
        rd0 = rd
        for j in range(Z):
            sn[j] = s0
            cs[j] = c0
            fr[j], zf[j], dof[j] = ball_flags(
                j, rd, rw, hd, hw, ifault, psil2, dbeta, doff, doffi, p
            )
            rd = advance(rd, step)
            rw = advance(rw, step)
            s1 = s0 * cc + c0 * ss
            c0 = c0 * cc - s0 * ss
            s0 = s1
        if pit:  # the pit's offsets in place of the drops (out of line)
            _pit_dofs(rd0, step, hd, ifault, dbeta, p, fr, dof)
        # ---- start
        if not (math.isfinite(ux) and math.isfinite(uy)):
            gx, gy = initial_guess(sn, cs, clr, K, n, fx, fy)
        elif math.isfinite(px):
            gx = 2.0 * ux - px
            gy = 2.0 * uy - py
        else:
            gx = ux
            gy = uy
        px = ux
        py = uy
        bx = gx
        by = gy
        rbest = math.inf
        sxx = sxy = syy = txx = txy = tyy = 0.0
        for attempt in range(2):
            if attempt == 1:
                if rbest <= tol:
                    break
                gx, gy = initial_guess(sn, cs, clr, K, n, fx, fy)
            vx = gx
            vy = gy
            rbest = math.inf
            lam = 1.0
            dx = 0.0
            dy = 0.0
            it = 0
            while True:
                # contact sums at (vx, vy)
                qx = qy = kxx = kxy = kyy = lxx = lxy = lyy = 0.0
                if axial or pit:  # out of line: inlined here, the axial law slowed the
                    # radial path by ~10 %, a test of the pit in the loop by 1.9x
                    qx, qy, kxx, kxy, kyy, lxx, lxy, lyy = _side_sums(
                        vx, vy, sn, cs, fr, zf, clj, dof, dfac, K, n, p, rough, axial
                    )
                for j in range(Z if not (axial or pit) else 0):
                    ue = vx * sn[j] + vy * cs[j]
                    q, kk, _e = ball_load(
                        ue, fr[j], zf[j], clj[j], dof[j], dfac, K, n, p, True, rough
                    )
                    if q > 0.0:
                        a = sn[j]
                        b = cs[j]
                        qx += q * a
                        qy += q * b
                        kxx += kk * a * a
                        kxy += kk * a * b
                        kyy += kk * b * b
                        # secant from the concentric position (P_d >= 0: ue > 0 when loaded;
                        # a preloaded ball at ue <= 0 has none: only the VSM uses it, and
                        # the VSM refuses P_d < 0)
                        sk = q / ue if ue > 0.0 else 0.0
                        lxx += sk * a * a
                        lxy += sk * a * b
                        lyy += sk * b * b
                rx = qx - fx
                ry = qy - fy
                r = math.hypot(rx, ry) / scale
                tr = kxx + kyy
                if it > 0 and r >= rbest and tr > 0.0 and lam > 1e-12:
                    lam *= 0.5  # damped Newton: halve the step until the residual decreases
                    vx = bx + lam * dx
                    vy = by + lam * dy
                    continue
                bx = vx
                by = vy
                rbest = r
                sxx, sxy, syy, txx, txy, tyy = lxx, lxy, lyy, kxx, kxy, kyy
                if r <= tol or it >= 100:
                    break
                it += 1
                lam = 1.0
                if tr <= 0.0:
                    # no ball in contact: move along the force until contact
                    dx = 1e-7 * fx / scale
                    dy = 1e-7 * fy / scale
                    rbest = math.inf
                else:
                    reg = 1e-12 * tr
                    a11 = kxx + reg
                    a22 = kyy + reg
                    det = a11 * a22 - kxy * kxy
                    if det <= 1e-14 * tr * tr or not math.isfinite(det):
                        dx = -rx / tr  # one ball in contact: gradient step
                        dy = -ry / tr
                    else:
                        dx = -(a22 * rx - kxy * ry) / det
                        dy = -(-kxy * rx + a11 * ry) / det
                vx = bx + dx
                vy = by + dy
        row = table[i]
        row[C_UX] = bx
        row[C_UY] = by
        row[C_SXX] = sxx
        row[C_SXY] = sxy
        row[C_SYY] = syy
        row[C_TXX] = txx
        row[C_TXY] = txy
        row[C_TYY] = tyy
        residual[i] = rbest
        ux = bx
        uy = by
    return ux, uy


@njit(cache=True)
def quasi_static_path(times, p, table, residual, ux, uy):
    """Static solution and stiffness matrices at every time of ``times`` (indicators as
    ``p[P_CELL]`` says); see :func:`static_kernel`. Returns the last ``(ux, uy)``."""
    return static_kernel(times, False, p, table, residual, ux, uy)


@njit(cache=True)
def table_row(t, p):
    """Index of the table row for time ``t`` (nearest half step)."""
    j = int((t - p[P_T0]) / p[P_HTAB] + 0.5)
    nt = int(p[P_NTAB])
    if j < 0:
        j = 0
    elif j >= nt:
        j = nt - 1
    return HEADER + NCOL * j


@njit(cache=True)
def static_on_the_fly(t, p, row, point):
    """Static solution at arbitrary ``t`` (warm start kept in ``p``), filling ``row``; the
    defect/zone indicators are point values when ``point`` (else as ``p[P_CELL]`` says).

    Used by the exact right-hand sides that the adaptive integrator calls at arbitrary times
    and for the outputs at samples next to a defect edge.
    """
    times = np.empty(1)
    times[0] = t
    tab = np.empty((1, NCOL))
    res = np.empty(1)
    ux, uy = static_kernel(times, point, p, tab, res, p[P_WARMX], p[P_WARMY])
    p[P_WARMX] = ux
    p[P_WARMY] = uy
    row[:] = tab[0]
    return res[0]


@njit(cache=True)
def per_ball(t, p, ux, uy, out, k0, fill):
    """Number of loaded balls at ring displacement ``u`` and time ``t``; when ``fill``, also
    write the ball loads Q_j [N] at ``out[k0:k0+Z]`` and the contact deformations
    ``(Q_j/K)^(1/n)`` [m] at ``out[k0+Z:k0+2Z]`` (point values at ``t``; no allocation)."""
    Z = int(p[P_Z])
    s0, c0, rd, rw, _hd, _hw = frame_cached(t, p)
    hd = 0.0
    hw = 0.0
    step = TWO_PI / Z
    fault = int(p[P_FAULT])
    psil2 = 2.0 * p[P_PSIL]
    ss = p[P_SSTEP]
    cc = p[P_CSTEP]
    dbeta = p[P_DBETA]
    clr, doff, dfac, K, n = constants(p)
    doffi = p[P_DOFFI]
    boff = int(p[P_BDEV])
    qthr = loaded_threshold(p)
    rough = qthr > 0.0  # once per output sample: the law chosen at run time (one copy)
    axial = p[P_AXZ] != 0.0
    pit = p[P_PROFILE] < -0.5
    n_loaded = 0
    for j in range(Z):
        fr, zf, dof = ball_flags(j, rd, rw, hd, hw, fault, psil2, dbeta, doff, doffi, p)
        if pit and fr > 0.0:
            dof = pit_dof(j, rd, hd, fault, dbeta, p)
        cl = ball_clearance(p, boff, j, clr)
        ue = ux * s0 + uy * c0
        if axial:  # the load along the contact normal
            ue = axial_approach(ue, cl, p)[0]
        q, _dq, _e = ball_load_pit(ue, fr, zf, cl, dof, dfac, K, n, p, False, rough, pit)
        if q > qthr:
            n_loaded += 1
        if fill:
            out[k0 + j] = q
            out[k0 + Z + j] = (q / K) ** (1.0 / n) if q > 0.0 else 0.0
        rd = advance(rd, step)
        rw = advance(rw, step)
        s1 = s0 * cc + c0 * ss
        c0 = c0 * cc - s0 * ss
        s0 = s1
    return n_loaded


@njit(cache=True)
def has_partial(t, p):
    """Whether some ball's cell-averaged defect or zone indicator at ``t`` is fractional, i.e.
    differs from its point value (a defect or window edge lies within the cell)."""
    if p[P_CELL] <= 0.0:
        return False
    Z = int(p[P_Z])
    _s0, _c0, rd, rw, hd, hw = frame_cached(t, p)
    step = TWO_PI / Z
    fault = int(p[P_FAULT])
    psil2 = 2.0 * p[P_PSIL]
    for j in range(Z):
        fr, zf, _dof = ball_flags(j, rd, rw, hd, hw, fault, psil2, p[P_DBETA], 0.0, 0.0, p)
        if 0.0 < fr < 1.0 or 0.0 < zf < 1.0:
            return True
        rd = advance(rd, step)
        rw = advance(rw, step)
    return False


@njit(cache=True)
def output_row(t, p, out_row):
    """Row of quasi-static values for an *output* sample at ``t``: the table row, or a point
    re-solve (warm-started from it) when a defect/zone edge lies within the cell. Returns the
    offset ``r`` such that ``out_row[r + C_*]`` holds the values."""
    r = table_row(t, p)
    if not has_partial(t, p):
        return p, r
    p[P_WARMX] = p[r + C_UX]
    p[P_WARMY] = p[r + C_UY]
    static_on_the_fly(t, p, out_row, True)
    return out_row, 0


@njit(cache=True)
def fill_aux_common(t, p, ux, uy, kxx, kxy, kyy, acc_x, acc_y, out):
    """Fill the auxiliary outputs shared by all models (see :mod:`.common`)."""
    out[0] = acc_x
    out[1] = acc_y
    out[2] = kxx
    out[3] = kxy
    out[4] = kyy
    th0 = p[P_TH0]
    s = math.sin(th0)
    c = math.cos(th0)
    out[5] = kxx * s * s + 2.0 * kxy * s * c + kyy * c * c
    out[6] = per_ball(t, p, ux, uy, out, 7, p[P_PERBALL] > 0.5)


@njit(cache=True, inline="always")
def fill_aux_row(t, p, row, r, k0, ax, ay, out):
    """:func:`fill_aux_common` from the table row ``row[r:]``: the static displacement and the
    stiffness triple (xx, xy, yy) starting at column ``k0`` (``C_SXX`` secant, ``C_TXX``
    tangent)."""
    fill_aux_common(
        t,
        p,
        row[r + C_UX],
        row[r + C_UY],
        row[r + k0],
        row[r + k0 + 1],
        row[r + k0 + 2],
        ax,
        ay,
        out,
    )
