"""Compiled (Numba, ``cache=True``) kernels of the quasi-static 5-DOF ball-bearing model.

The physics and notation are documented in :mod:`bearingsim.quasistatic.jones` (seed QS5
eqs. (1)–(7), Jones 1960, Harris & Kotzalas 2007 vol. 2 ch. 3). Ring DOF vector ``u = (x, y, z,
theta_x, theta_y)``; ball ``j`` at azimuth ``psi_j`` from +y towards +x; ``X_j`` axial and
``Y_j`` radial separation of the inner from the outer groove-curvature centre.

The kernels read their scalar inputs from one float64 parameter vector ``p`` laid out by the
``P_*`` offsets below (the project's convention, as :mod:`bearingsim.dynamics.ring.balance`),
built by :func:`_params`; arrays are the ball azimuths and misalignment offsets, the ring state,
the ball-centre state of the inertia model, and output or work buffers whose rows are named by the
``R_*``, ``B_*``, ``W_*`` and ``I_*`` constants. Everything here is private to the package.
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

__all__: list[str] = []

# ---------------------------------------------------------------- parameter vector layout
P_RPI = 0  #: radius of the inner groove-centre locus r_pi [m] (seed QS5 eq. (5))
P_RPO = 1  #: radius of the outer groove-centre locus r_po [m] (seed QS5 eq. (5))
P_Y0 = 2  #: radial groove-centre separation of the centred rings A0 - P_d/2 [m]
P_A0 = 3  #: groove-centre distance at first contact A0 = (f_i + f_o - 1) d [m]
P_K = 4  #: combined ball constant K [N/m^1.5]
P_CI = 5  #: inner groove radius minus ball radius (f_i - 1/2) d [m]
P_CO = 6  #: outer groove radius minus ball radius (f_o - 1/2) d [m]
P_KI = 7  #: Hertz constant of the inner contact [N/m^1.5]
P_KO = 8  #: Hertz constant of the outer contact [N/m^1.5]
P_FC = 9  #: ball centrifugal force F_c [N]
P_MG0 = 10  #: gyroscopic friction scale 2 J omega_R omega_c / d [N]
P_GAM = 11  #: d / d_m [-]
P_SPEED = 12  #: 1 = inertia loads on (ball centres solved), 0 = off [-]
P_TOL = 13  #: relative force-residual tolerance [-]
P_MAXIT = 14  #: Newton iterations per cage angle [-]
P_CAGE_RATIO = 15  #: cage speed / shaft speed [-]
P_PSI0 = 16  #: azimuth of ball 1 at cage angle 0 [rad]
P_TOX = 17  #: outer-ring tilt rotation vector, x component [rad]
P_TOY = 18  #: outer-ring tilt rotation vector, y component [rad]
P_TIAMP = 19  #: inner-ring tilt magnitude [rad]
P_TIAZ0 = 20  #: azimuth of the inner-ring tilt axis at shaft angle 0 [rad]
P_F = 21  #: applied load (Fx, Fy, Fz [N], Mx, My [N m]), 5 entries
P_FREE = 26  #: 1 = DOF solved, 0 = held at its start value, 5 entries
N_PARAMS = 31  #: length of ``p``

# ---------------------------------------------------------------- named rows of the buffers
#: ring output rows (m, 2, 5): displacement u, resultant f of the ball forces
R_U, R_F = 0, 1
#: ball output rows (m, 3, Z): load Q_j [N], contact angle alpha_j [rad], deformation delta_j [m]
B_Q, B_ALPHA, B_DELTA = 0, 1, 2
#: ball rows of the inertia model (4, Z): inner/outer loads [N], inner/outer contact angles [rad]
W_QI, W_QO, W_AI, W_AO = 0, 1, 2, 3
#: solver info: iterations, relative residual, minimum Y_j [m], status
I_ITER, I_RES, I_YMIN, I_STATUS = 0, 1, 2, 3
#: 2x2 blocks of one ball (3, 2, 2): ball Jacobian, inner and outer contact Hessians
M_JVV, M_HI, M_HO = 0, 1, 2


def _params(
    geom,
    applied=None,
    free=None,
    *,
    first_ball_angle: float = 0.0,
    outer_tilt_xy: tuple[float, float] = (0.0, 0.0),
    inner_tilt: tuple[float, float] = (0.0, 0.0),
    inertia: tuple[float, float, float] | None = None,
    tol: float = 1e-12,
    max_iterations: int = 100,
) -> np.ndarray:
    """The parameter vector ``p`` of the kernels for a
    :class:`~bearingsim.quasistatic.inputs.QSGeometry` ``geom``.

    Parameters
    ----------
    geom : QSGeometry
        Derived geometry.
    applied : array_like, shape (5,), optional
        ``(Fx, Fy, Fz [N], Mx, My [N m])`` (default 0).
    free : array_like of bool, shape (5,), optional
        DOFs solved (default all).
    first_ball_angle : float
        Azimuth of ball 1 at cage angle 0 [rad].
    outer_tilt_xy : tuple of float
        Outer-ring tilt rotation vector ``(T sin A, T cos A)`` [rad].
    inner_tilt : tuple of float
        Inner-ring tilt magnitude [rad] and axis azimuth at shaft angle 0 [rad].
    inertia : tuple of float, optional
        ``(F_c [N], 2 J omega_R omega_c / d [N], d/d_m [-])``; given = inertia loads on.
    tol : float
        Relative force-residual tolerance [-].
    max_iterations : int
        Newton iterations per cage angle [-].
    """
    p = np.zeros(N_PARAMS)
    p[P_RPI] = geom.r_pi
    p[P_RPO] = geom.r_po
    p[P_Y0] = geom.y0
    p[P_A0] = geom.a0
    p[P_K] = geom.k
    p[P_CI] = (geom.f_i - 0.5) * geom.d
    p[P_CO] = (geom.f_o - 0.5) * geom.d
    p[P_KI] = geom.k_inner
    p[P_KO] = geom.k_outer
    if inertia is None:
        p[P_GAM] = geom.d / geom.dm
    else:
        p[P_FC], p[P_MG0], p[P_GAM] = inertia
        p[P_SPEED] = 1.0
    p[P_TOL] = tol
    p[P_MAXIT] = max_iterations
    p[P_CAGE_RATIO] = geom.cage_ratio
    p[P_PSI0] = first_ball_angle
    p[P_TOX], p[P_TOY] = outer_tilt_xy
    p[P_TIAMP], p[P_TIAZ0] = inner_tilt
    if applied is not None:
        p[P_F : P_F + 5] = applied
    p[P_FREE : P_FREE + 5] = 1.0 if free is None else np.asarray(free, dtype=float)
    return p


@njit(cache=True, inline="always")
def _separation(u, psi_j, moff_j, r_pi, y0):
    """``(sin psi_j, cos psi_j, X_j, Y_j)``: axial ``X_j = z + r_pi (theta_x cos psi_j -
    theta_y sin psi_j) + m_j`` and radial ``Y_j = A0 - P_d/2 + x sin psi_j + y cos psi_j``
    separation of the groove centres of ball ``j`` [m] (seed QS5 eqs. (6)–(7))."""
    s = math.sin(psi_j)
    c = math.cos(psi_j)
    return s, c, u[2] + r_pi * (u[3] * c - u[4] * s) + moff_j, y0 + u[0] * s + u[1] * c


@njit(cache=True)
def _assemble(u, psi, moff, p, f, H):
    """Ring force ``f = sum Q dA/du`` and tangent stiffness ``H``; returns (elastic energy,
    minimum radial separation Y_j). Seed QS5 eqs. (6)–(7); SPEC §5."""
    r_pi = p[P_RPI]
    y0 = p[P_Y0]
    a0 = p[P_A0]
    K = p[P_K]
    for i in range(5):
        f[i] = 0.0
        for k in range(5):
            H[i, k] = 0.0
    en = 0.0
    ymin = 1e300
    g = np.empty(5)
    t = np.empty(5)
    for j in range(psi.size):
        s, c, X, Y = _separation(u, psi[j], moff[j], r_pi, y0)
        ymin = min(ymin, Y)
        A = math.sqrt(X * X + Y * Y)
        dl = A - a0
        if dl <= 0.0:
            continue
        sa = X / A
        ca = Y / A
        sq = math.sqrt(dl)
        Q = K * dl * sq
        en += Q * dl / 2.5
        # g = sin(a) b1 + cos(a) b2 ; t = cos(a) b1 - sin(a) b2 with b1 = dX/du, b2 = dY/du
        g[0] = ca * s
        g[1] = ca * c
        g[2] = sa
        g[3] = sa * r_pi * c
        g[4] = -sa * r_pi * s
        t[0] = -sa * s
        t[1] = -sa * c
        t[2] = ca
        t[3] = ca * r_pi * c
        t[4] = -ca * r_pi * s
        kn = 1.5 * K * sq
        kt = Q / A
        for i in range(5):
            f[i] += Q * g[i]
            for k in range(5):
                H[i, k] += kn * g[i] * g[k] + kt * t[i] * t[k]
    return en, ymin


#: round-off floor of the ring force residual, in units of ``eps sum_j (k_j A_j + Q_j)``
#: (:func:`_roundoff`)
ROUNDOFF_FACTOR = 16.0


@njit(cache=True)
def _load_sum(u, psi, moff, p):
    """Sum of the ball loads ``sum_j Q_j`` [N] at ring displacement ``u`` (no inertia)."""
    r_pi = p[P_RPI]
    y0 = p[P_Y0]
    a0 = p[P_A0]
    K = p[P_K]
    acc = 0.0
    for j in range(psi.size):
        _s, _c, X, Y = _separation(u, psi[j], moff[j], r_pi, y0)
        dl = math.sqrt(X * X + Y * Y) - a0
        if dl > 0.0:
            acc += K * dl * math.sqrt(dl)
    return acc


@njit(cache=True)
def _roundoff(u, psi, moff, p):
    """Force [N] below which the ring force residual cannot be resolved in double precision:
    ``16 eps sum_j (k_j A_j + Q_j) + 16 eps Z F_c``. The deformation ``delta_j = A_j - A0``
    is the difference of two lengths of about ``A0``, so it carries an absolute error
    ``eps A_j``, a force error ``k_j eps A_j`` with ``k_j = 1.5 K delta_j^0.5``, and the sum of
    the ball loads adds ``eps Q_j`` each. A small load on large ball loads (preload) or on
    nearly unloaded balls (a load of 0.01 N) cannot be balanced better than this."""
    r_pi = p[P_RPI]
    y0 = p[P_Y0]
    a0 = p[P_A0]
    K = p[P_K]
    acc = p[P_FC] * psi.size
    for j in range(psi.size):
        _s, _c, X, Y = _separation(u, psi[j], moff[j], r_pi, y0)
        A = math.sqrt(X * X + Y * Y)
        dl = A - a0
        if dl > 0.0:
            sq = math.sqrt(dl)
            acc += 1.5 * K * sq * A + K * dl * sq
    return ROUNDOFF_FACTOR * 2.220446049250313e-16 * acc


@njit(cache=True)
def _hess2(n1, n2, kn, kt, out):
    """2x2 Hessian ``kn n n^T + kt (I - n n^T)`` of ``phi(|w|)``."""
    out[0, 0] = kn * n1 * n1 + kt * (1.0 - n1 * n1)
    out[0, 1] = (kn - kt) * n1 * n2
    out[1, 0] = out[0, 1]
    out[1, 1] = kn * n2 * n2 + kt * (1.0 - n2 * n2)


@njit(cache=True)
def _ball_residual(v1, v2, X, Y, p, Ri, M):
    """Residual ``Ri`` of one ball's equilibrium (Harris & Kotzalas 2007 vol. 2 eqs.
    (3.36)–(3.37), outer-raceway control) at ball centre ``v`` (axial, radial, from the outer
    groove centre), with its Jacobian and the two contact Hessians in ``M`` (rows ``M_*``);
    returns (Qi, Qo, dli, dlo)."""
    ci = p[P_CI]
    co = p[P_CO]
    Ki = p[P_KI]
    Ko = p[P_KO]
    Fc = p[P_FC]
    mg0 = p[P_MG0]
    gam = p[P_GAM]
    Jvv = M[M_JVV]
    Hi = M[M_HI]
    Ho = M[M_HO]
    w1 = X - v1
    w2 = Y - v2
    Lw = math.sqrt(w1 * w1 + w2 * w2)
    Lv = math.sqrt(v1 * v1 + v2 * v2)
    dli = Lw - ci
    dlo = Lv - co
    Qi = 0.0
    Qo = 0.0
    for a in range(2):
        for b in range(2):
            Hi[a, b] = 0.0
            Ho[a, b] = 0.0
    if dli > 0.0:
        Qi = Ki * dli * math.sqrt(dli)
        _hess2(w1 / Lw, w2 / Lw, 1.5 * Ki * math.sqrt(dli), Qi / Lw, Hi)
    if dlo > 0.0:
        Qo = Ko * dlo * math.sqrt(dlo)
        _hess2(v1 / Lv, v2 / Lv, 1.5 * Ko * math.sqrt(dlo), Qo / Lv, Ho)
    # forces on the ball: Qi w/|w| - Qo v/|v| + Fc e_radial + G = 0 ; residual = minus that
    Ri[0] = -Qi * w1 / Lw + Qo * v1 / Lv
    Ri[1] = -Qi * w2 / Lw + Qo * v2 / Lv - Fc
    for a in range(2):
        for b in range(2):
            Jvv[a, b] = Hi[a, b] + Ho[a, b]
    if mg0 != 0.0:
        # gyroscopic friction at the outer contact: G = (2 M_g / d)(cos a_o, -sin a_o) with
        # M_g = mg0 sin(beta), tan(beta) = sin a_o / (cos a_o + gam) (outer-raceway control)
        ao = math.atan2(v1, v2)
        sn = math.sin(ao)
        cs = math.cos(ao)
        W = math.sqrt(1.0 + 2.0 * gam * cs + gam * gam)
        gg = mg0 * sn / W
        dg = mg0 * (cs / W + gam * sn * sn / W**3)
        Ri[0] -= gg * cs
        Ri[1] -= -gg * sn
        dv = Lv * Lv
        da1 = v2 / dv
        da2 = -v1 / dv
        # dG/da = dg (cos, -sin) + gg (-sin, -cos)
        G1a = dg * cs - gg * sn
        G2a = -dg * sn - gg * cs
        Jvv[0, 0] -= G1a * da1
        Jvv[0, 1] -= G1a * da2
        Jvv[1, 0] -= G2a * da1
        Jvv[1, 1] -= G2a * da2
    return Qi, Qo, dli, dlo


@njit(cache=True)
def _ball_solve(X, Y, v, p):
    """Newton solve of one ball's centre ``v`` (in place); returns the final residual norm."""
    co = p[P_CO]
    Fc = p[P_FC]
    M = np.empty((3, 2, 2))
    Jvv = M[M_JVV]
    R = np.empty(2)
    scale = Fc + 1e-300
    res = 0.0
    for _ in range(60):
        Qi, Qo, dli, dlo = _ball_residual(v[0], v[1], X, Y, p, R, M)
        res = math.hypot(R[0], R[1])
        scale = max(scale, Qi, Qo)
        if res <= 1e-13 * scale:
            break
        det = Jvv[0, 0] * Jvv[1, 1] - Jvv[0, 1] * Jvv[1, 0]
        if det == 0.0 or not math.isfinite(det):
            break
        s0 = -(Jvv[1, 1] * R[0] - Jvv[0, 1] * R[1]) / det
        s1 = -(-Jvv[1, 0] * R[0] + Jvv[0, 0] * R[1]) / det
        # limit the step to a fraction of the groove-centre distance (robustness far away)
        sn = math.hypot(s0, s1)
        lim = 0.05 * co
        if sn > lim:
            s0 *= lim / sn
            s1 *= lim / sn
        tstep = 1.0
        for _ls in range(30):
            _ball_residual(v[0] + tstep * s0, v[1] + tstep * s1, X, Y, p, R, M)
            if math.hypot(R[0], R[1]) < (1.0 - 1e-4 * tstep) * res:
                break
            tstep *= 0.5
        v[0] += tstep * s0
        v[1] += tstep * s1
    return res


@njit(cache=True)
def _assemble_speed(u, psi, moff, p, V, f, H, balls):
    """Ring force and condensed tangent stiffness with ball inertia loads: per ball the centre
    ``V[j]`` is solved, then ``dF/dA = H_i - H_i J_vv^-1 H_i`` (implicit function theorem).
    ``balls`` (4, Z) receives the rows ``W_*``; returns (worst relative ball residual, minimum
    radial separation Y_j)."""
    r_pi = p[P_RPI]
    y0 = p[P_Y0]
    Fc = p[P_FC]
    for i in range(5):
        f[i] = 0.0
        for k in range(5):
            H[i, k] = 0.0
    M = np.empty((3, 2, 2))
    Jvv = M[M_JVV]
    Hi = M[M_HI]
    R = np.empty(2)
    b1 = np.empty(5)
    b2 = np.empty(5)
    ymin = 1e300
    worst = 0.0
    for j in range(psi.size):
        s, c, X, Y = _separation(u, psi[j], moff[j], r_pi, y0)
        ymin = min(ymin, Y)
        v = V[j]
        res = _ball_solve(X, Y, v, p)
        Qi, Qo, dli, dlo = _ball_residual(v[0], v[1], X, Y, p, R, M)
        worst = max(worst, res / (Fc + Qi + Qo + 1e-300))
        balls[W_QI, j] = Qi
        balls[W_QO, j] = Qo
        w1 = X - v[0]
        w2 = Y - v[1]
        balls[W_AI, j] = math.atan2(w1, w2)
        balls[W_AO, j] = math.atan2(v[0], v[1])
        if Qi <= 0.0:
            continue
        Lw = math.hypot(w1, w2)
        fA0 = Qi * w1 / Lw
        fA1 = Qi * w2 / Lw
        det = Jvv[0, 0] * Jvv[1, 1] - Jvv[0, 1] * Jvv[1, 0]
        # M = Hi - Hi Jvv^-1 Hi
        inv00 = Jvv[1, 1] / det
        inv01 = -Jvv[0, 1] / det
        inv10 = -Jvv[1, 0] / det
        inv11 = Jvv[0, 0] / det
        T00 = inv00 * Hi[0, 0] + inv01 * Hi[1, 0]
        T01 = inv00 * Hi[0, 1] + inv01 * Hi[1, 1]
        T10 = inv10 * Hi[0, 0] + inv11 * Hi[1, 0]
        T11 = inv10 * Hi[0, 1] + inv11 * Hi[1, 1]
        M00 = Hi[0, 0] - (Hi[0, 0] * T00 + Hi[0, 1] * T10)
        M01 = Hi[0, 1] - (Hi[0, 0] * T01 + Hi[0, 1] * T11)
        M10 = Hi[1, 0] - (Hi[1, 0] * T00 + Hi[1, 1] * T10)
        M11 = Hi[1, 1] - (Hi[1, 0] * T01 + Hi[1, 1] * T11)
        b1[0] = 0.0
        b1[1] = 0.0
        b1[2] = 1.0
        b1[3] = r_pi * c
        b1[4] = -r_pi * s
        b2[0] = s
        b2[1] = c
        b2[2] = 0.0
        b2[3] = 0.0
        b2[4] = 0.0
        for i in range(5):
            f[i] += fA0 * b1[i] + fA1 * b2[i]
            for k in range(5):
                H[i, k] += b1[i] * (M00 * b1[k] + M01 * b2[k]) + b2[i] * (M10 * b1[k] + M11 * b2[k])
    return worst, ymin


@njit(cache=True)
def _chol_solve(A, b, n, out):
    """Solve the SPD system ``A x = b`` (n x n leading block) by Cholesky; False if not PD."""
    L = np.zeros((n, n))
    for i in range(n):
        for k in range(i + 1):
            sm = A[i, k]
            for m in range(k):
                sm -= L[i, m] * L[k, m]
            if i == k:
                if sm <= 0.0 or not math.isfinite(sm):
                    return False
                L[i, i] = math.sqrt(sm)
            else:
                L[i, k] = sm / L[k, k]
    y = np.empty(n)
    for i in range(n):
        sm = b[i]
        for m in range(i):
            sm -= L[i, m] * y[m]
        y[i] = sm / L[i, i]
    for i in range(n - 1, -1, -1):
        sm = y[i]
        for m in range(i + 1, n):
            sm -= L[m, i] * out[m]
        out[i] = sm / L[i, i]
    return True


@njit(cache=True)
def _lu_solve(A, b, n, out):
    """Gaussian elimination with partial pivoting (non-symmetric Jacobians); False if singular."""
    M = np.empty((n, n + 1))
    for i in range(n):
        for k in range(n):
            M[i, k] = A[i, k]
        M[i, n] = b[i]
    for col in range(n):
        p = col
        for r in range(col + 1, n):
            if abs(M[r, col]) > abs(M[p, col]):
                p = r
        if M[p, col] == 0.0 or not math.isfinite(M[p, col]):
            return False
        if p != col:
            for k in range(n + 1):
                tmp = M[col, k]
                M[col, k] = M[p, k]
                M[p, k] = tmp
        for r in range(col + 1, n):
            fac = M[r, col] / M[col, col]
            for k in range(col, n + 1):
                M[r, k] -= fac * M[col, k]
    for i in range(n - 1, -1, -1):
        sm = M[i, n]
        for k in range(i + 1, n):
            sm -= M[i, k] * out[k]
        out[i] = sm / M[i, i]
    return True


@njit(cache=True)
def _solve_ring(u, p, psi, moff, V, out_info):
    """Newton–Raphson for the free DOFs of the inner ring (in place).

    Merit: the convex potential (Armijo) without inertia loads, the residual norm with them.
    ``out_info`` receives the rows ``I_*``: iterations, relative residual, minimum radial
    separation, status (0 converged, 1 not converged, 2 geometry violated, Y_j <= 0).
    Converged: the relative residual is at most ``tol``, or the residual has stayed at the
    round-off floor of the contact forces (:func:`_roundoff`) for two iterations. The residual
    is relative to the applied load, or to the sum of the ball loads when no load is applied.
    """
    r_pi = p[P_RPI]
    Fc = p[P_FC]
    speed = p[P_SPEED] != 0.0
    tol = p[P_TOL]
    maxit = int(p[P_MAXIT])
    F = p[P_F : P_F + 5]
    idx = np.empty(5, dtype=np.int64)
    n = 0
    for i in range(5):
        if p[P_FREE + i] != 0.0:
            idx[n] = i
            n += 1
    f = np.empty(5)
    H = np.empty((5, 5))
    Hr = np.empty((5, 5))
    r = np.empty(5)
    step = np.empty(5)
    ut = np.empty(5)
    balls = np.empty((4, psi.size))
    # force scale: moments are converted to forces with the arm r_pi
    fscale = 0.0
    for i in range(5):
        w = F[i] / r_pi if i >= 3 else F[i]
        fscale += w * w
    fscale = math.sqrt(fscale)
    it = 0
    rel = 0.0
    ymin = 1e300
    status = 1
    floored = False
    for it in range(maxit + 1):
        if speed:
            _w, ymin = _assemble_speed(u, psi, moff, p, V, f, H, balls)
            qs = Fc * psi.size
            for j in range(psi.size):
                qs += balls[W_QI, j]
            en = 0.0
        else:
            en, ymin = _assemble(u, psi, moff, p, f, H)
            qs = 0.0
            for i in range(2):
                qs += f[i] * f[i]
            qs = math.sqrt(qs + f[2] * f[2])
            if fscale == 0.0:
                # no applied load (a preload or a misalignment alone): the net ring force is
                # the residual itself; measure it against the ball loads it balances
                qs = _load_sum(u, psi, moff, p)
        if ymin <= 0.0:
            status = 2
            break
        nr = 0.0
        for m in range(n):
            i = idx[m]
            r[m] = f[i] - F[i]
            w = r[m] / r_pi if i >= 3 else r[m]
            nr += w * w
        nr = math.sqrt(nr)
        scale = max(fscale, qs, 1e-300)
        rel = nr / scale
        if n == 0 or rel <= tol:
            status = 0
            break
        # the residual stays at the round-off floor of the contact forces (two iterations in a
        # row): converged as far as double precision allows (tiny loads, heavy preload)
        at_floor = nr <= _roundoff(u, psi, moff, p)
        if at_floor and floored:
            status = 0
            break
        floored = at_floor
        if it == maxit:
            break
        tr = 0.0
        for m in range(n):
            tr += H[idx[m], idx[m]]
        reg = 1e-13 * tr + 1e-300
        ok = False
        for _k in range(12):
            for a in range(n):
                for b in range(n):
                    Hr[a, b] = H[idx[a], idx[b]]
                Hr[a, a] += reg
            for a in range(n):
                ut[a] = -r[a]
            if speed:
                ok = _lu_solve(Hr, ut, n, step)
            else:
                ok = _chol_solve(Hr, ut, n, step)
            if ok:
                break
            reg = reg * 100.0 + 1e-3 * (tr + 1.0)
        if not ok:
            status = 1
            break
        # backtracking line search
        pot0 = en
        slope = 0.0
        for m in range(n):
            pot0 -= F[idx[m]] * u[idx[m]]
            slope += r[m] * step[m]
        tstep = 1.0
        for _ls in range(60):
            for i in range(5):
                ut[i] = u[i]
            for m in range(n):
                ut[idx[m]] += tstep * step[m]
            if speed:
                Vt = V.copy()
                _w, yt = _assemble_speed(ut, psi, moff, p, Vt, f, H, balls)
                nt = 0.0
                for m in range(n):
                    i = idx[m]
                    w = (f[i] - F[i]) / r_pi if i >= 3 else f[i] - F[i]
                    nt += w * w
                if yt > 0.0 and math.sqrt(nt) < (1.0 - 1e-4 * tstep) * nr:
                    V[:, :] = Vt
                    break
            else:
                e1, yt = _assemble(ut, psi, moff, p, f, H)
                pot1 = e1
                nt = 0.0
                for m in range(n):
                    i = idx[m]
                    pot1 -= F[i] * ut[i]
                    w = (f[i] - F[i]) / r_pi if i >= 3 else f[i] - F[i]
                    nt += w * w
                if yt > 0.0 and (
                    pot1 <= pot0 + 1e-4 * tstep * slope or math.sqrt(nt) < (1.0 - 1e-4 * tstep) * nr
                ):
                    break
            tstep *= 0.5
        for m in range(n):
            u[idx[m]] += tstep * step[m]
    out_info[I_ITER] = it
    out_info[I_RES] = rel
    out_info[I_YMIN] = ymin
    out_info[I_STATUS] = status


@njit(cache=True)
def _ball_setup(cage, p, errors, psi, moff):
    """Ball azimuths ``psi_j = cage + psi0 + 2 pi j/Z + e_j`` (seed eq. (1)) and misalignment
    offsets ``m_j`` (seed eqs. (2)–(3)) at one cage angle ``cage`` [rad]."""
    r_pi = p[P_RPI]
    r_po = p[P_RPO]
    psi0 = p[P_PSI0]
    to_x = p[P_TOX]
    to_y = p[P_TOY]
    ti_amp = p[P_TIAMP]
    Z = psi.size
    az = p[P_TIAZ0] + cage / p[P_CAGE_RATIO]
    ti_x = ti_amp * math.sin(az)
    ti_y = ti_amp * math.cos(az)
    for j in range(Z):
        q = cage + psi0 + 2.0 * math.pi * j / Z + errors[j]
        psi[j] = q
        c = math.cos(q)
        s = math.sin(q)
        moff[j] = r_pi * (ti_x * c - ti_y * s) - r_po * (to_x * c - to_y * s)


@njit(cache=True)
def _sweep(cage, errors, p, u0, V0, out_ring, out_H, out_balls, out_info):
    """Equilibrium and tangent stiffness at every cage angle ``cage[m]``, each started from the
    previous (``u0``, ``V0`` at the first): ``out_ring`` (m, 2, 5) rows ``R_*``, ``out_H``
    (m, 5, 5), ``out_balls`` (m, 3, Z) rows ``B_*``, ``out_info`` (m, 4) rows ``I_*``. Returns
    the number of cage angles solved (``cage.size`` unless one failed)."""
    r_pi = p[P_RPI]
    y0 = p[P_Y0]
    a0 = p[P_A0]
    K = p[P_K]
    Ki = p[P_KI]
    Ko = p[P_KO]
    speed = p[P_SPEED] != 0.0
    Z = errors.size
    psi = np.empty(Z)
    moff = np.empty(Z)
    u = u0.copy()
    V = V0.copy()
    f = np.empty(5)
    H = np.empty((5, 5))
    info = np.empty(4)
    balls = np.empty((4, Z))
    for m in range(cage.size):
        _ball_setup(cage[m], p, errors, psi, moff)
        _solve_ring(u, p, psi, moff, V, info)
        for i in range(4):
            out_info[m, i] = info[i]
        if info[I_STATUS] != 0.0:
            return m
        if speed:
            _assemble_speed(u, psi, moff, p, V, f, H, balls)
            for j in range(Z):
                Qi = balls[W_QI, j]
                Qo = balls[W_QO, j]
                out_balls[m, B_Q, j] = Qi
                out_balls[m, B_ALPHA, j] = balls[W_AI, j]
                out_balls[m, B_DELTA, j] = (Qi / Ki) ** (2.0 / 3.0) + (Qo / Ko) ** (2.0 / 3.0)
        else:
            _assemble(u, psi, moff, p, f, H)
            for j in range(Z):
                _s, _c, X, Y = _separation(u, psi[j], moff[j], r_pi, y0)
                A = math.sqrt(X * X + Y * Y)
                dl = A - a0
                out_balls[m, B_DELTA, j] = dl
                out_balls[m, B_ALPHA, j] = math.atan2(X, Y)
                out_balls[m, B_Q, j] = K * dl * math.sqrt(dl) if dl > 0.0 else 0.0
        for i in range(5):
            out_ring[m, R_U, i] = u[i]
            out_ring[m, R_F, i] = f[i]
            for k in range(5):
                out_H[m, i, k] = H[i, k]
    return cage.size
