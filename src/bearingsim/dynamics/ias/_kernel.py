"""Compiled right-hand side of the IAS model (seed IAS eq. (32)); the equations are in
:mod:`bearingsim.dynamics.ias.model`.

The parameter vector ``p`` is packed by :func:`bearingsim.dynamics.ias.model.pack_parameters`
at the offsets ``P_*`` below (SI). :func:`ias_rhs` and :func:`ias_aux` are Numba cfuncs with the
shared signature :data:`bearingsim.dynamics.integrate.RHS_SIG` (for the adaptive integrator and
any generic caller); :func:`ias_rk4` is the fixed-step RK4 driver with the same right-hand side
inlined (:func:`bearingsim.dynamics.integrate._rk4_inline`), bit-identical and 1.4 times faster.

Cost per call (the seed case: 11 rollers, about 5 loaded; 4 calls per RK4 step, 1e7 steps)
    * one ``cos``/``sin`` pair, of roller 1's angle: the roller angles ``phi_k = phi_1 +
      2 pi k/Z`` enter only through ``x cos(phi_k) + y sin(phi_k) = x' cos(2 pi k/Z) +
      y' sin(2 pi k/Z)`` with the ring displacement ``(x', y')`` turned into roller 1's frame,
      and ``cos/sin(2 pi k/Z)`` are packed once; the pair itself is advanced by rotation from
      the nearest of 1024 tabulated angles (:func:`_sincos`); nothing is carried from one call
      to the next;
    * the contact law ``K_t delta^(10/9)`` only for the rollers with ``delta > 0`` (seed
      eq. (35)); ``delta^(10/9) = delta delta^(1/9)`` with :func:`_root9` (no ``pow``, no call
      into libm; within 3 ulp of the exact power, where ``exp(10/9 ln delta)`` errs by up to
      40 ulp for the approaches of the model);
    * the spall terms only for the one roller that can be in the spall (``2 Theta_os < 2 pi/Z``,
      :func:`bearingsim.dynamics.ias.model.check_spall_width`);
    * no division but in ``sgn(theta')``: reciprocals and products of constants are packed;
    * no Python reference counting and no division checks: the helpers take scalars and are
      inlined (``inline="always"``), ``y`` and ``p`` are last read on one path (an array handed
      to a non-inlined function, or last read in different branches, makes Numba keep atomic
      ``NRT_incref``/``NRT_decref`` calls on every call, about a quarter of the step's time);
      ``error_model="numpy"``: a zero divisor gives inf/nan, which the integrator reports as a
      divergence (a Python exception cannot leave a cfunc anyway).
"""

from __future__ import annotations

import math

import numpy as np
from numba import cfunc, njit

from ...contact.pereira import LINE_EXPONENT
from ..integrate import RHS_SIG, _rk4_inline

__all__: list[str] = []  # private: the IAS model imports what it needs

# ------------------------------------------------------------------ parameter vector offsets
P_M = 0  #: inner ring + shaft mass m [kg]
P_I = 1  #: polar inertia I [kg m^2]
P_CS = 2  #: radial damping C_s [N s/m]
P_CT = 3  #: torsional damping C_T [N m s/rad]
P_QX = 4  #: applied force Q_x [N]
P_QY = 5  #: applied force Q_y [N]
P_MZ = 6  #: motor torque M_z [N m]
P_KT = 7  #: roller contact constant K_t [N/m^n]
P_N = 8  #: load-deflection exponent n [-]
P_C = 9  #: radial clearance c [m]
P_Z = 10  #: number of rollers Z [-]
P_RHO = 11  #: cage ratio rho [-]
P_PHI0 = 12  #: first roller angle Phi_0 [rad]
P_RI = 13  #: inner raceway radius r_i [m]
P_RC = 14  #: roller radius r_c [m]
P_MU = 15  #: rolling-resistance coefficient mu [-]
P_PHIOS = 16  #: spall centre phi_os [rad]
P_THOS = 17  #: spall half angle Theta_os [rad]
P_HM = 18  #: roller drop H_m [m]
P_LAM = 19  #: impact angle lambda [rad]
P_DO = 20  #: outer raceway diameter D_o [m]
P_MC = 21  #: roller mass m_c [kg]
P_V1C = 22  #: V_1 per unit cage speed, (D_p^2 - D_c^2 cos^2 alpha)/(4 D_p) [m]
P_G = 23  #: gravity g [m/s^2]
P_QMODE = 24  #: spall load Q of eq. (30): 0 Stribeck, 1 dynamic Hertz force
P_QMAX = 25  #: Stribeck Q_max [N]
P_EPS = 26  #: load-distribution factor epsilon [-]
P_PHIO = 27  #: load-zone half angle phi_o [rad]
P_PHIC = 28  #: load-zone centre [rad]
P_SPALL = 29  #: 1 with a spall, 0 healthy
P_WEPS = 30  #: speed scale w_eps of the regularised sign [rad/s]
P_COSLAM = 31  #: cos(lambda) [-]
P_SINLAM = 32  #: sin(lambda) [-]
P_SINLT = 33  #: sin(lambda - Theta_os) [-] (eq. (31))
P_INVM = 34  #: 1/m [1/kg]
P_INVI = 35  #: 1/I [1/(kg m^2)]
P_TARM = 36  #: resisting torque per unit roller load, r_i mu + b_n = mu (r_i + r_c) [m]
#: cos(2 pi k/Z) for k = 0..Z-1 start here, followed by sin(2 pi k/Z)
P_TRIG = 37

#: auxiliary outputs per sample (see :class:`~bearingsim.dynamics.ias.result.IasResult`)
AUX_NAMES = (
    "bearing_torque",
    "spall_torque",
    "spall_force",
    "impact_force",
    "normal_force_sum",
    "n_loaded",
)
N_AUX = len(AUX_NAMES)
STATE_NAMES = ("x", "y", "theta", "vx", "vy", "omega")

# ----------------------------------------------------------------------- delta^(1/9) seeds
#: 128 mantissa intervals [1 + j/128, 1 + (j+1)/128): centres m_j, m_j^(1/9), 1/m_j
_R9_MID = 1.0 + (np.arange(128) + 0.5) / 128.0
_R9_ROOT = _R9_MID ** (1.0 / 9.0)
_R9_INV = 1.0 / _R9_MID
#: Taylor coefficients binom(1/9, i), i = 1..5, of (1 + u)^(1/9)
_R9_TAYLOR = (1.0 / 9.0, -4.0 / 81.0, 68.0 / 2187.0, -442.0 / 19683.0, 3094.0 / 177147.0)
#: 2^((r - 6)/9), r = 0..8
_R9_EXP = 2.0 ** ((np.arange(9) - 6) / 9.0)
_MANTISSA_BITS = np.int64(0x000FFFFFFFFFFFFF)
_EXPONENT_ONE = np.int64(0x3FF0000000000000)
_NORMAL_MIN = 2.2250738585072014e-308  # smallest normal float64


@njit(cache=True, inline="always")
def _root9(x):
    """``x^(1/9)`` for ``x > 0`` within 2 ulp (inf and nan pass through).

    With ``x = 2^e m``, ``m`` in [1, 2) and the biased exponent ``e + 1023 = 9 q + r``:
    ``x^(1/9) = 2^(q - 113) 2^((r - 6)/9) m_j^(1/9) (1 + u)^(1/9)``, ``u = (m - m_j)/m_j``, with
    ``m_j`` the centre of ``m``'s interval of width 1/128 (``|u| < 1/256``) and ``(1 + u)^(1/9)``
    by its Taylor series to ``u^5`` (truncation error < 6e-17). Subnormal and huge ``x`` are
    first scaled by ``2^180`` or ``2^-90`` (exact).
    """
    scale = 1.0
    if x < _NORMAL_MIN:
        x *= 2.0**180
        scale = 2.0**-20
    elif x > 1e300:
        x *= 2.0**-90
        scale = 2.0**10
    bits = np.float64(x).view(np.int64)
    eb = bits >> 52  # biased exponent 1..2046
    m = np.int64((bits & _MANTISSA_BITS) | _EXPONENT_ONE).view(np.float64)
    j = (bits >> 45) & 127  # the first 7 mantissa bits
    q = eb // 9
    r = eb - 9 * q
    # 2^(q - 113) from its bits; q is in 0..227 for finite x
    a = _R9_ROOT[j] * (_R9_EXP[r] * (np.int64((q + 910) << 52).view(np.float64) * scale))
    u = (m - _R9_MID[j]) * _R9_INV[j]
    u2 = u * u
    c = _R9_TAYLOR
    y = a + a * (u * ((c[0] + c[1] * u) + u2 * ((c[2] + c[3] * u) + u2 * c[4])))
    return y if x < math.inf else x


@njit(cache=True, inline="always")
def _power(d, n):
    """``d^n`` for ``d > 0`` (seed eq. (13)); ``d^(10/9) = d d^(1/9)``."""
    if n == LINE_EXPONENT:
        return d * _root9(d)
    return math.exp(n * math.log(d))


# ------------------------------------------------------------------------------ cos, sin
#: cos and sin of 2 pi j/N, j = 0..N-1, rounded from extended precision where NumPy has it
_SC_N = 1024
_SC_PI = np.longdouble("3.14159265358979323846264338327950288419716939937510582097494459")
_SC_COS = np.cos(_SC_PI * np.arange(_SC_N, dtype=np.longdouble) / (_SC_N // 2)).astype(float)
_SC_SIN = np.sin(_SC_PI * np.arange(_SC_N, dtype=np.longdouble) / (_SC_N // 2)).astype(float)
#: 2 pi/N in two parts (fdlibm's pio2_1 and pio2_1t, e_rem_pio2.c, divided by N/4): the first
#: has 31 significant bits, so k times it is exact for |k| < 2^22, i.e. |angle| < 2.5e4 rad
_SC_HI = 1.57079632673412561417e00 / (_SC_N // 4)
_SC_LO = 6.07710050650619224932e-11 / (_SC_N // 4)
#: 1.5 2^52: x + M - M rounds x to an integer, whose low bits stay in the bits of x + M
_SC_ROUND = 6755399441055744.0
#: beyond this |angle| [rad] the libm functions are used
_SC_MAX = 2e4


@njit(cache=True, inline="always")
def _sincos(a):
    """``(cos a, sin a)``, absolute error below 1.2e-16 for ``|a| <= 2e4`` (libm beyond).

    The nearest table angle ``2 pi j/N`` and the remainder ``r`` (``|r| <= pi/N``, Cody-Waite
    reduction), then ``cos a = C_j cos r - S_j sin r``, ``sin a = S_j cos r + C_j sin r`` with
    ``sin r = r - r^3/6 + r^5/120`` and ``cos r - 1 = -r^2/2 + r^4/24`` (the next terms are
    below 2e-18). Inlined, it costs a fraction of the libm calls it replaces.
    """
    if abs(a) <= _SC_MAX:
        x = a * (_SC_N / (2.0 * math.pi))
        t = x + _SC_ROUND
        k = t - _SC_ROUND
        j = np.float64(t).view(np.int64) & (_SC_N - 1)  # k mod N
        r = (a - k * _SC_HI) - k * _SC_LO
        z = r * r
        sr = r + r * z * (-1.0 / 6.0 + z * (1.0 / 120.0))
        cm1 = z * (-0.5 + z * (1.0 / 24.0))
        cj = _SC_COS[j]
        sj = _SC_SIN[j]
        c = cj + (cj * cm1 - sj * sr)
        s = sj + (sj * cm1 + cj * sr)
    else:
        c = math.cos(a)
        s = math.sin(a)
    return c, s


# --------------------------------------------------------------------------------- forces


@njit(cache=True, inline="always")
def _wrap(a):
    """Angle wrapped to [-pi, pi)."""
    return a - 2.0 * math.pi * math.floor((a + math.pi) * (0.5 / math.pi))


@njit(cache=True, inline="always")
def _sign(w, eps):
    """Regularised ``sign(theta')``: ``w / sqrt(w^2 + w_eps^2)``."""
    return w / math.sqrt(w * w + eps * eps)


@njit(cache=True, inline="always")
def _spall_roller(phi1, phi_os, th_os, Z):
    """The roller inside the spall (seed eq. (34)) and its angle ``u`` from the spall centre.

    Returns ``(k, u)`` with ``k`` = -1 when no roller is inside. At most one roller is: the
    spall is narrower than the roller spacing (``2 Theta_os < 2 pi/Z``), so only the roller
    nearest the spall centre needs the test.
    """
    dphi = 2.0 * math.pi / Z
    base = _wrap(phi1 - phi_os)  # angle of roller 1 from the spall centre, [-pi, pi)
    k = int(math.floor(0.5 - base * (Z * (0.5 / math.pi))))  # nearest roller, (-Z/2, Z/2]
    if k < 0:
        k += Z
    elif k >= Z:
        k -= Z
    u = base + k * dphi
    if u >= math.pi:
        u -= 2.0 * math.pi
    ks = k if -th_os <= u <= th_os else -1
    return ks, u


@njit(cache=True, error_model="numpy", inline="always")
def _forces(y, p, sgn):
    """Forces on the inner ring and torques at state ``y``, ``sgn`` = :func:`_sign` of
    ``theta'``; returns ``(f_x, f_y, resisting torque, M_T, F_T, impact part, sum N,
    n loaded)`` [N], [N m], [-].

    ``y`` is read before any branch and ``p`` is last read outside any branch (module
    docstring: no reference counting).
    """
    x = y[0]
    yy = y[1]
    w = y[5]
    Z = int(p[P_Z])
    c = p[P_C]
    Kt = p[P_KT]
    n = p[P_N]
    rc = p[P_RC]
    phi1 = p[P_PHI0] + p[P_RHO] * y[2]  # seed eq. (3), cage driven by the shaft angle
    c1, s1 = _sincos(phi1)
    fx = 0.0
    fy = 0.0
    m_t = 0.0
    f_t = 0.0
    f_imp = 0.0
    ks, u = -1, 0.0
    cd = 0.0
    if p[P_SPALL] > 0.0:
        ks, u = _spall_roller(phi1, p[P_PHIOS], p[P_THOS], Z)
    if ks >= 0:  # spall contact force F_T of seed eq. (30) on the roller in the spall
        ck = c1 * p[P_TRIG + ks] - s1 * p[P_TRIG + Z + ks]  # cos(phi_k)
        sk = s1 * p[P_TRIG + ks] + c1 * p[P_TRIG + Z + ks]  # sin(phi_k)
        sh = math.sin(0.5 * math.pi * abs(u) / p[P_THOS])
        cd = p[P_HM] * (1.0 - sh)  # seed eq. (18): C_d = H_m [1 - sin(pi |u|/(2 Theta_os))]
        q = 0.0
        if p[P_QMODE] == 0.0:  # seed eqs. (1)-(2)
            a = _wrap(p[P_PHIC] - (phi1 + ks * (2.0 * math.pi / Z)))
            if abs(a) <= p[P_PHIO]:
                br = 1.0 - (1.0 - math.cos(a)) / (2.0 * p[P_EPS])
                if br > 0.0:
                    q = p[P_QMAX] * br**n
        else:  # the roller's Hertz force without the spall drop
            d0 = x * ck + yy * sk - c
            if d0 > 0.0:
                q = Kt * d0**n
        if u < 0.0:  # entering half: Q cos(pi u/(2 Theta) + pi/2)
            f_t = q * sh
        else:  # leaving half: (Q + F_os cos(lambda)) (1 + sin(pi u/(2 Theta) + pi))
            # impact force F_os (derived from seed eqs. (21)-(28)) at the current cage speed;
            # only a loaded roller rides on the outer race and hits the trailing edge
            if q > 0.0:
                cl = p[P_COSLAM]
                v1 = abs(p[P_RHO] * w) * p[P_V1C]
                v2 = math.sqrt(0.6 * v1 * v1 + 0.8 * p[P_G] * rc * (1.0 - cl))
                fos = 2.0 * p[P_MC] * v1 * v2 / (rc * cl)
                f_imp = fos * cl * (1.0 - sh)
            f_t = q * (1.0 - sh) + f_imp
        # inward along the roller radius, tilted by lambda against the rolling direction
        cl = p[P_COSLAM]
        sl = p[P_SINLAM] * sgn
        fx = -f_t * (cl * ck - sl * sk)
        fy = -f_t * (cl * sk + sl * ck)
        m_t = 0.5 * p[P_DO] * f_t * p[P_SINLT]  # seed eq. (31)
    # ring displacement in roller 1's frame: x cos(phi_k) + y sin(phi_k)
    # = xr cos(2 pi k/Z) + yr sin(2 pi k/Z)
    xr = x * c1 + yy * s1
    yr = yy * c1 - x * s1
    # sums over the loaded rollers of N_k, N_k cos(2 pi k/Z), N_k sin(2 pi k/Z)
    nsum = 0.0
    ncos = 0.0
    nsin = 0.0
    nload = 0.0
    for k in range(Z):
        ck = p[P_TRIG + k]
        sk = p[P_TRIG + Z + k]
        dk = xr * ck + yr * sk - c  # seed eq. (33)
        if k == ks:
            dk -= cd  # gamma_k = 1 in the spall, eq. (34)
        if dk > 0.0:  # seed eq. (35)
            nk = Kt * _power(dk, n)  # seed eq. (13)
            nsum += nk
            ncos += nk * ck
            nsin += nk * sk
            nload += 1.0
    # back to the (x, y) frame: sum N cos(phi_k), sum N sin(phi_k)
    nx = ncos * c1 - nsin * s1
    ny = ncos * s1 + nsin * c1
    # rolling resistance T_k = N_k b_n / r_c = mu N_k (seed eqs. (14), (16)) on the ring opposes
    # its surface motion: -sgn T e_t with e_t = (-sin, cos)
    tr = sgn * p[P_MU]
    fx += tr * ny - nx
    fy -= tr * nx + ny
    torque = p[P_TARM] * nsum  # seed eq. (17): sum of r_i T_k + b_n N_k
    return fx, fy, torque, m_t, f_t, f_imp, nsum, nload


@njit(cache=True, error_model="numpy", inline="always")
def _rhs(t, y, p, dydt):
    """Seed IAS eq. (32) into ``dydt``; state ``(x, y, theta, x', y', theta')``."""
    w = y[5]
    sgn = _sign(w, p[P_WEPS])
    fx, fy, torque, m_t, _ft, _fi, _ns, _nl = _forces(y, p, sgn)
    dydt[0] = y[3]
    dydt[1] = y[4]
    dydt[2] = w
    dydt[3] = (p[P_QX] - p[P_CS] * y[3] + fx) * p[P_INVM]
    dydt[4] = (p[P_QY] - p[P_CS] * y[4] + fy) * p[P_INVM]
    dydt[5] = (p[P_MZ] - p[P_CT] * w - sgn * (torque + m_t)) * p[P_INVI]


@njit(cache=True, error_model="numpy", inline="always")
def _aux(t, y, p, out):
    """Auxiliary outputs :data:`AUX_NAMES` at state ``y``."""
    _fx, _fy, torque, m_t, ft, fi, ns, nl = _forces(y, p, _sign(y[5], p[P_WEPS]))
    out[0] = torque
    out[1] = m_t
    out[2] = ft
    out[3] = fi
    out[4] = ns
    out[5] = nl


@cfunc(RHS_SIG, cache=True, error_model="numpy")
def ias_rhs(t, y, p, dydt):
    """Right-hand side of seed IAS eq. (32); state ``(x, y, theta, x', y', theta')`` (SI)."""
    _rhs(t, y, p, dydt)


@cfunc(RHS_SIG, cache=True, error_model="numpy")
def ias_aux(t, y, p, out):
    """Auxiliary outputs :data:`AUX_NAMES` at state ``y``."""
    _aux(t, y, p, out)


@njit(cache=True, error_model="numpy")
def _aux_sample(t, y, p, out):
    """:func:`_aux` as a call of its own: the driver runs it at output samples only, and not
    inlining it halves the driver's compile time."""
    _aux(t, y, p, out)


@njit(cache=True, nogil=True, error_model="numpy")
def ias_rk4(y0, t0, dt, n_out, decim, p, bound, k0):
    """RK4 of :func:`bearingsim.dynamics.integrate._rk4_inline` with the right-hand side of
    :func:`ias_rhs` inlined (the driver of ``run_fixed``); same arithmetic as ``_rk4_fixed``."""
    return _rk4_inline(_rhs, _aux_sample, y0, 6, t0, dt, n_out, decim, p, N_AUX, bound, k0)
