"""Compiled right-hand side of the bearing–rotor–housing model (seed ROTOR, Liu et al. 2021).

State vector ``y`` (all SI), with ``n_r`` reduced rotor coordinates (the first four are the
x, y displacements of the drive-end and fan-end bearing nodes, see
:func:`bearingsim.dynamics.rotor_fe.craig_bampton`), 4 housing coordinates and ``n_b = Z_DE +
Z_FE`` ball coordinates::

    y = [q_r (n_r), x_hDE, y_hDE, x_hFE, y_hFE, s_1..s_nb,   # positions [m]
         v_r (n_r), housing velocities (4), s'_1..s'_nb]       # velocities [m/s]

``s_j`` is the radial coordinate of ball ``j``'s centre measured from the undeflected bearing axis
along its azimuth ``psi_j`` (inertial frame), the ball's one degree of freedom (seed ROTOR eq. 8
uses the radius relative to the inner ring; measuring it in the inertial frame gives a diagonal
mass matrix and the same physics). Ball ``j`` of a bearing sits at
``psi_j = psi_0 + omega_c t + (j-1) 2 pi/Z`` (rigid cage; azimuth from +y towards +x), with
unit vector ``e_j = (sin psi_j, cos psi_j)``.

Contact deflections (positive = compression), with the diametral clearance ``P_d`` put on the
outer contact and the raceway groove bottoms at ``D/2 -/+ d/2``::

    delta_in  = D/2 - s_j + u_s . e_j - h_in(psi_j, t) + Delta D_j / 2
    delta_out = s_j - u_h . e_j - D/2 - P_d/2 - h_out(psi_j) + Delta D_j / 2

(``u_s`` shaft displacement at the bearing node, ``u_h`` housing displacement, ``h`` the extra
clearance a local defect opens under the ball, ``Delta D_j`` ball ``j``'s diameter deviation,
:mod:`bearingsim.dynamics.ballset`). Contact force (seed ROTOR eqs. 10–11: Hertz
potential ``2/5 k delta^2.5`` plus linear damping along the compression)::

    Q = max(0, k delta^1.5 + c d(delta)/dt)  for delta > 0,   0 otherwise

or, with a composite RMS roughness ``sigma > 0`` (``B_ROUGH``), Hertz's law averaged over it,
``k sigma^1.5 g_1.5(delta / sigma)`` (:mod:`bearingsim.contact.rough`), which carries load from
``delta = -8 sigma`` on (no damping before ``delta > 0``),

with ``k`` the Hertz constant of that contact (inner and outer separately). Equations of motion::

    m_b (s_j'' - s_j omega_c^2) = Q_in - Q_out - m_b g cos(psi_j)
    rotor:   q_r'' = -A_K q_r - A_C q_r' + B_b F_b + f_0 + u_c cos(Omega t) + u_s sin(Omega t)
    housing: m_h x_h'' = -k_hx x_h - c_hx x_h' + sum_j Q_out,j sin(psi_j)   (and y, with -m_h g)

where ``F_b = -sum_j Q_in,j e_j`` per bearing node and ``A_K, A_C, B_b, f_0, u_c, u_s`` are the
reduced rotor matrices premultiplied by ``M_r^-1`` (built by :mod:`bearingsim.dynamics.rotor`).

With quasi-static balls (``H_QS``; :attr:`RotorConfig.ball_inertia` False) the balls are
massless and have no coordinates (``n_b = 0`` in the state): each carries one load through both
contacts, ``Q = max(0, k_e delta^1.5 + c/2 d(delta)/dt)`` on the total approach
``delta = delta_in + delta_out = (u_s - u_h) . e_j - P_d/2 - h_in - h_out + Delta D_j`` with
``k_e = (k_in^(-2/3) + k_out^(-2/3))^(-3/2)`` (the two Hertz contacts in series, as the ring
models' ``K``) and the two contact dampers in series (``c/2``); the rough law, when set, acts
on ``delta`` with the contacts' ``sigma``. Under an axial load (``B_AXZ`` != 0) the groove
centres lie ``A = sqrt((A0 + delta_r)^2 + z^2)`` apart (``delta_r`` the radial approach above,
without the drop; the axial offset ``z`` of the Jones equilibrium, held); the normal approach
is ``A - A0 - h`` and the load's radial component ``Q (A0 + delta_r) / A`` acts on the rings.

Parameter vector ``p`` layout: a header of :data:`HDR` values (indices ``H_*``) holding the
sizes and the offsets of the blocks that follow; two bearing blocks of :data:`BRG_LEN` values
(indices ``B_*``); one housing block of :data:`HOUS_LEN` values (indices ``HS_*``).
"""

from __future__ import annotations

import math

import numpy as np
from numba import cfunc, njit

from ...contact.rough import U_MIN, rough_ball
from ..defect_drop import edge_drop
from ..defect_pit import pit_share
from ..integrate import RHS_SIG
from ..slip import cage_angle

__all__: list[str] = []  # private: the compiled right-hand side of the rotor model

# ----------------------------------------------------------------------------- p layout
H_NR = 0  # number of reduced rotor coordinates
H_Z_DE = 1  # balls in the drive-end bearing
H_Z_FE = 2  # balls in the fan-end bearing
H_OMEGA = 3  # shaft speed Omega [rad/s]
H_GRAV = 4  # gravity acceleration on balls and housings [m/s^2] (0 = off), along -y
H_AK = 5  # offset of A_K, stored transposed (row j holds column j of A_K; n_r x n_r)
H_AC = 6  # offset of A_C, stored transposed
H_BB = 7  # offset of B_b (n_r x 4)
H_F0 = 8  # offset of f_0 (n_r)
H_UC = 9  # offset of u_c (n_r)
H_US = 10  # offset of u_s (n_r)
H_BRG_DE = 11  # offset of the drive-end bearing block
H_BRG_FE = 12  # offset of the fan-end bearing block
H_HOUS = 13  # offset of the housing block
H_BALL_OUT = 14  # 1: auxiliary output includes per-ball contact forces
H_QS = 15  # 1: quasi-static (massless) balls, no ball coordinates in the state
HDR = 16

B_Z = 0  # number of balls
B_PSI0 = 1  # azimuth of ball 1 at t = 0 [rad]
B_OMEGA_C = 2  # cage speed [rad/s]
B_MBALL = 3  # ball mass [kg]
B_KIN = 4  # Hertz constant, inner contact [N/m^1.5]
B_KOUT = 5  # Hertz constant, outer contact [N/m^1.5]
B_C = 6  # contact damping per contact [N s/m]
B_RP = 7  # pitch radius D/2 [m]
B_CH = 8  # half the diametral clearance [m]
B_FAULT = 9  # 0 none, 1 outer race, 2 inner race, 3 ball 1
B_FANG = 10  # defect centre azimuth at t = 0 [rad] (ball: its spin angle, 0 = outer race)
B_FHALF = 11  # defect half angle on its raceway [rad] (ball: on the ball)
B_DEPTH = 12  # defect depth h_d [m]
B_HALFW = 13  # defect half width b/2 [m]
B_RBALL = 14  # ball radius [m]
B_RRACE = 15  # radius of the faulty raceway [m] (ball: of the outer raceway)
B_RSIGN = 16  # -1 outer (concave) race, +1 inner (convex) race (seed VSM eq. 2)
B_PROFILE = 17  # 0 geometric ball path, 1 rectangular (constant h_min), 2 round pit
B_HMAX = 18  # h_min = min(h_d, h_s) [m] (ball: at the outer race)
B_FOMEGA = 19  # angular speed of the defect [rad/s] (0 outer, Omega inner)
B_SLIP = 20  # offset in p of the bearing's ball-pass instants (random slip); 0 = no slip
B_SLIPN = 21  # entries of that table
B_SLIPDT = 22  # nominal ball-pass period [s]
B_SPIN = 23  # ball defect: ball spin angle per cage angle, BSF / FTF [-]
B_RRACE_I = 24  # ball defect: inner raceway radius [m]
B_HMAX_I = 25  # ball defect: h_min at the inner race [m]
B_BDEV = 26  # offset in p of the bearing's ball diameter deviations Delta D_j; 0 = none
B_ROUGH = 27  # composite RMS roughness sigma of the contacts [m]; 0 = Hertz
B_RINV = 28  # 1 / sigma [1/m] (0 when sigma = 0)
B_RSN1 = 29  # sigma^(1/2) [m^0.5]
B_KEFF = 30  # quasi-static balls: Hertz constant of the two contacts in series [N/m^1.5]
B_AXZ = 31  # quasi-static balls under an axial load: axial offset z of the groove centres [m]
B_A0 = 32  # and their unloaded distance A0 = (f_i + f_o - 1) d [m] (0 without an axial load)
B_PITA = 33  # pit: a^2 / Q^(2/3) of the faulty contact (ball: at the outer race) [m^2/N^(2/3)]
B_PITB = 34  # pit: b^2 / Q^(2/3) [m^2/N^(2/3)]
B_PITW = 35  # pit: that contact's share of the two contacts' compliance (quasi-static balls) [-]
B_PITAI = 36  # ball pit: B_PITA at the inner-race contact
B_PITBI = 37  # ball pit: B_PITB at the inner-race contact
B_PITWI = 38  # ball pit: B_PITW of the inner-race contact
BRG_LEN = 39

HS_M = 0  # DE housing mass [kg]; FE at +5
HS_KX = 1
HS_KY = 2
HS_CX = 3
HS_CY = 4
HOUS_LEN = 10

TWO_PI = 2.0 * math.pi


@njit(cache=True, inline="always")
def _wrap(a):
    return a - TWO_PI * math.floor((a + math.pi) / TWO_PI)


@njit(cache=True)
def defect_drop(p, o, dpsi):
    """Extra clearance ``h`` [m] and ``dh/d(dpsi)`` [m/rad] under a ball at angular distance
    ``dpsi`` [rad] from the defect centre (bearing block at offset ``o``)."""
    rr = p[o + B_RRACE]
    return defect_drop_on(p, o, dpsi, rr, rr, p[o + B_RSIGN], p[o + B_HMAX])


@njit(cache=True)
def defect_drop_on(p, o, dpsi, rpath, rr, sg, hmax):
    """:func:`defect_drop` for a defect whose centre is ``dpsi`` [rad] away along a circle of
    radius ``rpath`` [m] (the faulty raceway's, or the ball's for a ball defect), meeting a
    surface of radius ``rr`` [m] and sign ``sg`` (-1 concave outer race, +1 convex inner race;
    seed VSM eq. (2)), at most ``hmax`` [m] (rectangular profile)."""
    half = p[o + B_FHALF]
    if abs(dpsi) >= half or p[o + B_PROFILE] > 1.5:  # off the defect, or a pit (no drop)
        return 0.0, 0.0
    if p[o + B_PROFILE] > 0.5:  # rectangular: the seed VSM h_min over the whole extent
        return hmax, 0.0
    # geometric: the ball rests on the nearer edge, at distance e from its centre line;
    # seed VSM eq. (2) with b/2 replaced by e: d(e) = [r - sqrt(r^2-e^2)] +/- [R - sqrt(R^2-e^2)]
    x = rpath * abs(dpsi)
    e = p[o + B_HALFW] - x
    if e <= 0.0:
        return 0.0, 0.0
    d, dd_de = edge_drop(e, p[o + B_RBALL], rr, sg, p[o + B_DEPTH])
    sgn = 1.0 if dpsi > 0.0 else -1.0
    return d, -dd_de * rpath * sgn


@njit(cache=True)
def pit_factor(p, o, dpsi, rpath, d, k, inner, series):
    """Factor [-] on the elastic load of a contact of constant ``k`` [N/m^1.5] at the Hertz
    compression ``d`` [m] of its load (``(Q/k)^(2/3)``: a rough contact carries load, and has
    a size, before the surfaces meet) whose ball lies ``dpsi`` [rad] from a round pit's
    centre along a circle of radius ``rpath`` [m] (:mod:`bearingsim.dynamics.defect_pit`): 1
    off the pit's window, else the share the contact beside the pit keeps, ``g`` for one
    contact, or with ``series`` (the quasi-static ball's two contacts in series of constant
    ``k``) ``(w g^(-2/3) + 1 - w)^(-3/2)``. ``inner``: the ball pit's inner-race contact
    constants."""
    if abs(dpsi) >= p[o + B_FHALF] or d <= 0.0:  # off the window, or no load to share
        return 1.0
    k23 = k ** (2.0 / 3.0)  # a^2 = a_1^2 Q^(2/3), Q = k d^1.5
    w = p[o + (B_PITWI if inner else B_PITW)] if series else 1.0
    a2 = p[o + (B_PITAI if inner else B_PITA)] * k23
    b2 = p[o + (B_PITBI if inner else B_PITB)] * k23
    return pit_share(d, rpath * abs(dpsi), p[o + B_HALFW], a2, b2, w, 1.5, False)[0]


@njit(cache=True)
def _pit_g(p, o, fault, phi, dpsi, q, k, inner):
    """:func:`pit_factor` of a massive ball's one contact (``inner`` or outer, constant ``k``
    [N/m^1.5]) carrying the elastic load ``q`` [N] over the bearing's pit (``fault`` 1, 2 or 3:
    ``phi`` the ball's spin angle of the pit, else ``dpsi`` its azimuth from it [rad])."""
    if q <= 0.0:
        return 1.0
    d = (q / k) ** (2.0 / 3.0)
    if fault == 3:
        ang = _wrap(phi - math.pi) if inner else phi
        return pit_factor(p, o, ang, p[o + B_RBALL], d, k, inner, False)
    return pit_factor(p, o, dpsi, p[o + B_RRACE], d, k, False, False)


@njit(cache=True, inline="always")
def _slip(t, p, o, z, wc):
    """Random slip (:mod:`bearingsim.dynamics.slip`): the cage's angle at ``t`` minus
    ``wc t`` [rad] and its speed there [rad/s], from the bearing's ball-pass instants."""
    angle, speed = cage_angle(
        t, p, int(p[o + B_SLIP]), int(p[o + B_SLIPN]), p[o + B_SLIPDT], TWO_PI / z
    )
    return angle - wc * t, speed


@njit(cache=True, inline="always")
def _cage(t, p, o, z):
    """Ball 1's azimuth [rad], the cage speed [rad/s], the balls' speed relative to the defect
    [rad/s], one ball pitch [rad] and its cos and sin, at ``t`` (random slip included)."""
    wc = p[o + B_OMEGA_C]
    psi = p[o + B_PSI0] + wc * t
    if p[o + B_SLIP] > 0.0:
        ph, wc = _slip(t, p, o, z, wc)
        psi += ph
    step = TWO_PI / z
    return psi, wc, wc - p[o + B_FOMEGA], step, math.cos(step), math.sin(step)


@njit(cache=True, inline="always")
def _elastic(d, k, sig, p, o):
    """Elastic load [N] of one contact at compression ``d`` [m]: Hertz ``k d^1.5`` (``sig`` =
    0), or Hertz averaged over the roughness ``sig`` [m] (:func:`bearingsim.contact.rough.
    rough_ball`; ``1/sig`` and ``sig^0.5`` cached in the bearing block at offset ``o``)."""
    if sig > 0.0:
        return rough_ball(d, k, sig, p[o + B_RINV], p[o + B_RSN1], False)[0]
    return k * d * math.sqrt(d)


@njit(cache=True)
def _bearing(t, y, p, o, nr, ib, node, hous, dydt, aux, aux_off, want_ball, grav):
    """Ball forces of one bearing; writes the ball accelerations and returns the forces on the
    shaft node (fx, fy) and on the housing (fx, fy) [N]."""
    z = int(p[o + B_Z])
    npos = nr + 4 + int(p[H_Z_DE]) + int(p[H_Z_FE])
    psi, wc, rel_speed, step, ca, sa = _cage(t, p, o, z)
    mb = p[o + B_MBALL]
    kin = p[o + B_KIN]
    kout = p[o + B_KOUT]
    c = p[o + B_C]
    rp = p[o + B_RP]
    ch = p[o + B_CH]
    fault = int(p[o + B_FAULT])
    pit = p[o + B_PROFILE] > 1.5
    fang = p[o + B_FANG] + p[o + B_FOMEGA] * t
    xs = y[node]
    ys = y[node + 1]
    vxs = y[npos + node]
    vys = y[npos + node + 1]
    xh = y[nr + hous]
    yh = y[nr + hous + 1]
    vxh = y[npos + nr + hous]
    vyh = y[npos + nr + hous + 1]
    sp = math.sin(psi)
    cp = math.cos(psi)
    boff = int(p[o + B_BDEV])
    sig = p[o + B_ROUGH]
    onset = U_MIN * sig  # a rough contact carries load from a few sigma before touching (0: Hertz)
    fsx = 0.0
    fsy = 0.0
    fhx = 0.0
    fhy = 0.0
    for j in range(z):
        k = nr + 4 + ib + j
        s = y[k]
        sd = y[npos + k]
        h_in = 0.0
        hd_in = 0.0
        h_out = 0.0
        hd_out = 0.0
        phi = 0.0
        dpsi = 0.0
        if fault == 3:
            if j == 0:  # ball 1's slot: spin angle of its centre from the outer contact
                spin = p[o + B_SPIN]
                phi = _wrap(spin * (psi - p[o + B_PSI0]) + fang)
                rb = p[o + B_RBALL]
                h_out, dh = defect_drop_on(p, o, phi, rb, p[o + B_RRACE], -1.0, p[o + B_HMAX])
                hd_out = dh * spin * wc
                h_in, dh = defect_drop_on(
                    p, o, _wrap(phi - math.pi), rb, p[o + B_RRACE_I], 1.0, p[o + B_HMAX_I]
                )
                hd_in = dh * spin * wc
        elif fault != 0:
            dpsi = _wrap(psi + j * step - fang)
            h, dh = defect_drop(p, o, dpsi)
            if fault == 1:
                h_out = h
                hd_out = dh * rel_speed
            else:
                h_in = h
                hd_in = dh * rel_speed
        # e = (sp, cp); de/dt = wc (cp, -sp)
        d_in = rp - s + xs * sp + ys * cp - h_in
        d_out = s - xh * sp - yh * cp - rp - ch - h_out
        if boff > 0:  # a ball larger by Delta D_j: each contact closes by half of it
            d_in += 0.5 * p[boff + j]
            d_out += 0.5 * p[boff + j]
        # elastic load (rough from `onset` on, Hertz from 0), then the damping once touching
        q_in = 0.0
        if d_in > onset:
            q_in = _elastic(d_in, kin, sig, p, o)
            if pit and (fault == 2 or (fault == 3 and j == 0)):  # a round pit: a share kept
                q_in *= _pit_g(p, o, fault, phi, dpsi, q_in, kin, True)
            if d_in > 0.0:
                q_in = q_in + c * (-sd + vxs * sp + vys * cp + wc * (xs * cp - ys * sp) - hd_in)
                if q_in < 0.0:
                    q_in = 0.0
        q_out = 0.0
        if d_out > onset:
            q_out = _elastic(d_out, kout, sig, p, o)
            if pit and (fault == 1 or (fault == 3 and j == 0)):  # a round pit: a share kept
                q_out *= _pit_g(p, o, fault, phi, dpsi, q_out, kout, False)
            if d_out > 0.0:
                q_out = q_out + c * (sd - vxh * sp - vyh * cp - wc * (xh * cp - yh * sp) - hd_out)
                if q_out < 0.0:
                    q_out = 0.0
        # seed ROTOR eq. (12) in the inertial radial coordinate: centrifugal and gravity terms
        dydt[k] = sd
        dydt[npos + k] = (q_in - q_out) / mb + s * wc * wc - grav * cp
        fsx -= q_in * sp
        fsy -= q_in * cp
        fhx += q_out * sp
        fhy += q_out * cp
        if want_ball:
            aux[aux_off + j] = q_in
            aux[aux_off + z + j] = q_out
        # rotate (sp, cp) by one ball pitch
        sp, cp = sp * ca + cp * sa, cp * ca - sp * sa
    return fsx, fsy, fhx, fhy


@njit(cache=True)
def _bearing_qs(t, y, p, o, nr, npos, node, hous, aux, aux_off, want_ball):
    """:func:`_bearing` with quasi-static (massless) balls: each ball carries the same load
    ``Q`` through both contacts, Hertz's law of the two in series on the total approach
    ``delta_in + delta_out`` (constant ``B_KEFF``) with the contact damping of two equal
    dampers in series (``c/2``); no ball coordinates, no centrifugal or gravity force on the
    balls. Returns the forces on the shaft node (fx, fy) and on the housing (fx, fy) [N].
    The ball loop is compiled twice, with and without the axial geometry (the choice made
    once per call, not per ball: 5 % of the radial rotor's time in an A/B)."""
    if p[o + B_AXZ] != 0.0:
        return _qs_balls(t, y, p, o, nr, npos, node, hous, aux, aux_off, want_ball, True)
    return _qs_balls(t, y, p, o, nr, npos, node, hous, aux, aux_off, want_ball, False)


@njit(cache=True, inline="always")
def _qs_balls(t, y, p, o, nr, npos, node, hous, aux, aux_off, want_ball, axial):
    """The ball loop of :func:`_bearing_qs`; ``axial`` is a constant at each call site, so
    the geometry's branch folds away."""
    z = int(p[o + B_Z])
    psi, wc, rel_speed, step, ca, sa = _cage(t, p, o, z)
    keff = p[o + B_KEFF]
    c2 = 0.5 * p[o + B_C]
    ch = p[o + B_CH]
    fault = int(p[o + B_FAULT])
    fang = p[o + B_FANG] + p[o + B_FOMEGA] * t
    # relative displacement and velocity of shaft node and housing
    xr = y[node] - y[nr + hous]
    yr = y[node + 1] - y[nr + hous + 1]
    vxr = y[npos + node] - y[npos + nr + hous]
    vyr = y[npos + node + 1] - y[npos + nr + hous + 1]
    sp = math.sin(psi)
    cp = math.cos(psi)
    boff = int(p[o + B_BDEV])
    sig = p[o + B_ROUGH]
    onset = U_MIN * sig
    z_ax = p[o + B_AXZ]
    a0 = p[o + B_A0]
    fx = 0.0
    fy = 0.0
    pit = p[o + B_PROFILE] > 1.5
    for j in range(z):
        h = 0.0
        hd = 0.0
        phi = 0.0
        dpsi = 0.0
        if fault == 3:
            if j == 0:  # ball 1's slot meets the outer race, half a spin turn later the inner
                spin = p[o + B_SPIN]
                phi = _wrap(spin * (psi - p[o + B_PSI0]) + fang)
                rb = p[o + B_RBALL]
                h, dh = defect_drop_on(p, o, phi, rb, p[o + B_RRACE], -1.0, p[o + B_HMAX])
                h_i, dh_i = defect_drop_on(
                    p, o, _wrap(phi - math.pi), rb, p[o + B_RRACE_I], 1.0, p[o + B_HMAX_I]
                )
                h += h_i
                hd = (dh + dh_i) * spin * wc
        elif fault != 0:
            dpsi = _wrap(psi + j * step - fang)
            h, dh = defect_drop(p, o, dpsi)
            hd = dh * rel_speed
        d = xr * sp + yr * cp - ch - h
        if boff > 0:  # a ball larger by Delta D_j closes the two contacts by Delta D_j
            d += p[boff + j]
        cos_a = 1.0  # cosine of the ball's contact angle
        if axial:  # groove centres A0 + radial approach apart radially, z axially
            r = a0 + d + h
            a = math.sqrt(r * r + z_ax * z_ax)
            cos_a = r / a
            d = a - a0 - h  # the normal approach, the drop taken from it
        q = 0.0
        if d > onset:
            q = _elastic(d, keff, sig, p, o)
            if pit and fault != 0 and q > 0.0:  # a round pit: the contact beside it keeps a share
                de = (q / keff) ** (2.0 / 3.0)  # the Hertz approach of the load
                if fault == 3:
                    if j == 0:
                        rb = p[o + B_RBALL]
                        q *= pit_factor(p, o, phi, rb, de, keff, False, True) * pit_factor(
                            p, o, _wrap(phi - math.pi), rb, de, keff, True, True
                        )
                else:
                    q *= pit_factor(p, o, dpsi, p[o + B_RRACE], de, keff, False, True)
            if d > 0.0:
                rate = cos_a * (vxr * sp + vyr * cp + wc * (xr * cp - yr * sp)) - hd
                q = q + c2 * rate
                if q < 0.0:
                    q = 0.0
        if want_ball:
            aux[aux_off + j] = q
            aux[aux_off + z + j] = q
        q = q * cos_a  # its radial component
        fx += q * sp
        fy += q * cp
        sp, cp = sp * ca + cp * sa, cp * ca - sp * sa
    return -fx, -fy, fx, fy


@njit(cache=True)
def rhs_core(t, y, p, dydt, aux, want_aux, rotor=True):
    """Evaluate ``dy/dt``; when ``want_aux`` also fill ``aux`` (housing accelerations
    [m/s^2], then per-ball inner and outer contact forces [N] if requested). ``rotor`` False
    skips the rotor's equations and the position derivatives (``dydt`` then holds only the
    ball and housing accelerations: what :func:`rotor_aux` needs)."""
    nr = int(p[H_NR])
    zde = int(p[H_Z_DE])
    zfe = int(p[H_Z_FE])
    qs = p[H_QS] > 0.5
    npos = nr + 4 if qs else nr + 4 + zde + zfe
    grav = p[H_GRAV]
    want_ball = want_aux and p[H_BALL_OUT] > 0.5
    if rotor:
        for i in range(npos):
            dydt[i] = y[npos + i]
    if qs:
        fde = _bearing_qs(t, y, p, int(p[H_BRG_DE]), nr, npos, 0, 0, aux, 4, want_ball)
        ffe = _bearing_qs(t, y, p, int(p[H_BRG_FE]), nr, npos, 2, 2, aux, 4 + 2 * zde, want_ball)
    else:
        fde = _bearing(t, y, p, int(p[H_BRG_DE]), nr, 0, 0, 0, dydt, aux, 4, want_ball, grav)
        ffe = _bearing(
            t, y, p, int(p[H_BRG_FE]), nr, zde, 2, 2, dydt, aux, 4 + 2 * zde, want_ball, grav
        )
    if rotor:
        _rotor_accelerations(t, y, p, dydt, nr, npos, fde, ffe)
    _housings(y, p, dydt, aux, want_aux, nr, npos, grav, fde, ffe)


@njit(cache=True)
def _rotor_accelerations(t, y, p, dydt, nr, npos, fde, ffe):
    """The reduced rotor's accelerations (``M_r^-1``-premultiplied equations) into ``dydt``."""
    om = p[H_OMEGA]
    cw = math.cos(om * t)
    sw = math.sin(om * t)
    oak = int(p[H_AK])
    oac = int(p[H_AC])
    obb = int(p[H_BB])
    of0 = int(p[H_F0])
    ouc = int(p[H_UC])
    ous = int(p[H_US])
    f0 = fde[0]
    f1 = fde[1]
    f2 = ffe[0]
    f3 = ffe[1]
    # views of the blocks (indices from range() are known non-negative: no wrap-around code)
    akt = p[oak : oak + nr * nr].reshape((nr, nr))  # akt[j, i] = A_K[i, j]
    act = p[oac : oac + nr * nr].reshape((nr, nr))
    q = y[:nr]
    v = y[npos : npos + nr]
    acc = dydt[npos : npos + nr]
    for i in range(nr):
        acc[i] = p[of0 + i] + p[ouc + i] * cw + p[ous + i] * sw
    # column by column: the n_r sums advance side by side (SIMD lanes), each in the order of a
    # row-by-row dot product (the same result to the last bit), 2.5x faster than one
    for j in range(nr):
        qj = q[j]
        vj = v[j]
        for i in range(nr):
            acc[i] -= akt[j, i] * qj + act[j, i] * vj
    for i in range(nr):
        rb = obb + 4 * i
        acc[i] += p[rb] * f0 + p[rb + 1] * f1 + p[rb + 2] * f2 + p[rb + 3] * f3


@njit(cache=True)
def _housings(y, p, dydt, aux, want_aux, nr, npos, grav, fde, ffe):
    """The housings' accelerations into ``dydt`` (and ``aux[:4]`` when ``want_aux``)."""
    oh = int(p[H_HOUS])
    for e in range(2):
        fx = fde[2] if e == 0 else ffe[2]
        fy = fde[3] if e == 0 else ffe[3]
        b = oh + 5 * e
        m = p[b + HS_M]
        ix = nr + 2 * e
        ax = (fx - p[b + HS_KX] * y[ix] - p[b + HS_CX] * y[npos + ix]) / m
        ay = (fy - p[b + HS_KY] * y[ix + 1] - p[b + HS_CY] * y[npos + ix + 1]) / m - grav
        dydt[npos + ix] = ax
        dydt[npos + ix + 1] = ay
        if want_aux:
            aux[2 * e] = ax
            aux[2 * e + 1] = ay


@cfunc(RHS_SIG, cache=True)
def rotor_rhs(t, y, p, dydt):
    """Numba cfunc RHS (signature :data:`~bearingsim.dynamics.integrate.RHS_SIG`)."""
    rhs_core(t, y, p, dydt, dydt, False)


@cfunc(RHS_SIG, cache=True)
def rotor_aux(t, y, p, out):
    """Auxiliary outputs: housing accelerations ``a_xDE, a_yDE, a_xFE, a_yFE`` [m/s^2], then
    (if enabled) ``Q_in`` and ``Q_out`` of every DE ball and of every FE ball [N]."""
    if p[H_QS] > 0.5:  # no ball coordinates: nothing but the housings' entries is written
        tmp = np.empty(y.size)
    else:
        tmp = np.zeros(y.size)
    rhs_core(t, y, p, tmp, out, True, False)


@njit(cache=True)
def settle_balls(t, y, p, dydt, n_iter):
    """Put every ball at rest in radial equilibrium for the shaft and housing positions in
    ``y`` (modified in place): vectorised bisection on the ball accelerations, each monotone
    (decreasing) in its own ball's coordinate, within ``D/2 +/- 0.1 mm``."""
    if p[H_QS] > 0.5:  # quasi-static balls: no ball coordinates
        return
    nr = int(p[H_NR])
    zde = int(p[H_Z_DE])
    zfe = int(p[H_Z_FE])
    nb = zde + zfe
    npos = nr + 4 + nb
    lo = np.empty(nb)
    hi = np.empty(nb)
    for j in range(nb):
        o = int(p[H_BRG_DE]) if j < zde else int(p[H_BRG_FE])
        lo[j] = p[o + B_RP] - 1e-4
        hi[j] = p[o + B_RP] + 1e-4
        y[npos + nr + 4 + j] = 0.0
    for _ in range(n_iter):
        for j in range(nb):
            y[nr + 4 + j] = 0.5 * (lo[j] + hi[j])
        rhs_core(t, y, p, dydt, dydt, False)
        for j in range(nb):
            if dydt[npos + nr + 4 + j] > 0.0:
                lo[j] = y[nr + 4 + j]
            else:
                hi[j] = y[nr + 4 + j]
    for j in range(nb):
        y[nr + 4 + j] = 0.5 * (lo[j] + hi[j])
