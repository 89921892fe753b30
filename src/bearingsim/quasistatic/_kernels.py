"""Compiled (Numba, ``cache=True``) kernels of the quasi-static 5-DOF ball-bearing model.

The physics and notation are documented in :mod:`bearingsim.quasi_static` (seed QS5 eqs. (1)–(7),
Jones 1960, Harris & Kotzalas 2007 vol. 2 ch. 3). Ring DOF vector ``u = (x, y, z, theta_x,
theta_y)``; ball ``j`` at azimuth ``psi_j`` from +y towards +x; ``X_j`` axial and ``Y_j`` radial
separation of the inner from the outer groove-curvature centre.
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit


@njit(cache=True)
def _assemble(u, psi, moff, r_pi, y0, a0, K, f, H):
    """Ring force ``f = sum Q dA/du`` and tangent stiffness ``H``; returns (elastic energy,
    minimum radial separation Y_j). Seed QS5 eqs. (6)–(7); SPEC §5."""
    for i in range(5):
        f[i] = 0.0
        for k in range(5):
            H[i, k] = 0.0
    en = 0.0
    ymin = 1e300
    g = np.empty(5)
    t = np.empty(5)
    for j in range(psi.size):
        s = math.sin(psi[j])
        c = math.cos(psi[j])
        X = u[2] + r_pi * (u[3] * c - u[4] * s) + moff[j]
        Y = y0 + u[0] * s + u[1] * c
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


@njit(cache=True)
def _hess2(n1, n2, kn, kt, out):
    """2x2 Hessian ``kn n n^T + kt (I - n n^T)`` of ``phi(|w|)``."""
    out[0, 0] = kn * n1 * n1 + kt * (1.0 - n1 * n1)
    out[0, 1] = (kn - kt) * n1 * n2
    out[1, 0] = out[0, 1]
    out[1, 1] = kn * n2 * n2 + kt * (1.0 - n2 * n2)


@njit(cache=True)
def _ball_residual(v1, v2, X, Y, ci, co, Ki, Ko, Fc, mg0, gam, Ri, Jvv, Hi, Ho):
    """Residual of one ball's equilibrium (Harris & Kotzalas 2007 vol. 2 eqs. (3.36)–(3.37),
    outer-raceway control) at ball centre ``v`` (axial, radial, from the outer groove centre),
    with its Jacobian ``Jvv`` and the two contact Hessians; returns (Qi, Qo, dli, dlo)."""
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
def _ball_solve(X, Y, v, ci, co, Ki, Ko, Fc, mg0, gam):
    """Newton solve of one ball's centre ``v`` (in place); returns the final residual norm."""
    Jvv = np.empty((2, 2))
    Hi = np.empty((2, 2))
    Ho = np.empty((2, 2))
    R = np.empty(2)
    scale = Fc + 1e-300
    res = 0.0
    for _ in range(60):
        Qi, Qo, dli, dlo = _ball_residual(
            v[0], v[1], X, Y, ci, co, Ki, Ko, Fc, mg0, gam, R, Jvv, Hi, Ho
        )
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
            _ball_residual(
                v[0] + tstep * s0,
                v[1] + tstep * s1,
                X,
                Y,
                ci,
                co,
                Ki,
                Ko,
                Fc,
                mg0,
                gam,
                R,
                Jvv,
                Hi,
                Ho,
            )
            if math.hypot(R[0], R[1]) < (1.0 - 1e-4 * tstep) * res:
                break
            tstep *= 0.5
        v[0] += tstep * s0
        v[1] += tstep * s1
    return res


@njit(cache=True)
def _assemble_speed(
    u, psi, moff, r_pi, y0, ci, co, Ki, Ko, Fc, mg0, gam, V, f, H, Qi_out, Qo_out, ai_out, ao_out
):
    """Ring force and condensed tangent stiffness with ball inertia loads: per ball the centre
    ``V[j]`` is solved, then ``dF/dA = H_i - H_i J_vv^-1 H_i`` (implicit function theorem)."""
    for i in range(5):
        f[i] = 0.0
        for k in range(5):
            H[i, k] = 0.0
    Jvv = np.empty((2, 2))
    Hi = np.empty((2, 2))
    Ho = np.empty((2, 2))
    R = np.empty(2)
    b1 = np.empty(5)
    b2 = np.empty(5)
    ymin = 1e300
    worst = 0.0
    for j in range(psi.size):
        s = math.sin(psi[j])
        c = math.cos(psi[j])
        X = u[2] + r_pi * (u[3] * c - u[4] * s) + moff[j]
        Y = y0 + u[0] * s + u[1] * c
        ymin = min(ymin, Y)
        v = V[j]
        res = _ball_solve(X, Y, v, ci, co, Ki, Ko, Fc, mg0, gam)
        Qi, Qo, dli, dlo = _ball_residual(
            v[0], v[1], X, Y, ci, co, Ki, Ko, Fc, mg0, gam, R, Jvv, Hi, Ho
        )
        worst = max(worst, res / (Fc + Qi + Qo + 1e-300))
        Qi_out[j] = Qi
        Qo_out[j] = Qo
        w1 = X - v[0]
        w2 = Y - v[1]
        ai_out[j] = math.atan2(w1, w2)
        ao_out[j] = math.atan2(v[0], v[1])
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
def _solve_ring(
    u,
    free,
    F,
    psi,
    moff,
    r_pi,
    y0,
    a0,
    K,
    ci,
    co,
    Ki,
    Ko,
    Fc,
    mg0,
    gam,
    speed,
    V,
    tol,
    maxit,
    out_info,
):
    """Newton–Raphson for the free DOFs of the inner ring (in place).

    Merit: the convex potential (Armijo) without inertia loads, the residual norm with them.
    ``out_info`` receives (iterations, relative residual, minimum radial separation, status)
    with status 0 converged, 1 not converged, 2 geometry violated (Y_j <= 0).
    """
    idx = np.empty(5, dtype=np.int64)
    n = 0
    for i in range(5):
        if free[i]:
            idx[n] = i
            n += 1
    f = np.empty(5)
    H = np.empty((5, 5))
    Hr = np.empty((5, 5))
    r = np.empty(5)
    step = np.empty(5)
    ut = np.empty(5)
    Qi = np.empty(psi.size)
    Qo = np.empty(psi.size)
    ai = np.empty(psi.size)
    ao = np.empty(psi.size)
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
    for it in range(maxit + 1):
        if speed:
            _w, ymin = _assemble_speed(
                u, psi, moff, r_pi, y0, ci, co, Ki, Ko, Fc, mg0, gam, V, f, H, Qi, Qo, ai, ao
            )
            qs = Fc * psi.size
            for j in range(psi.size):
                qs += Qi[j]
            en = 0.0
        else:
            en, ymin = _assemble(u, psi, moff, r_pi, y0, a0, K, f, H)
            qs = 0.0
            for i in range(2):
                qs += f[i] * f[i]
            qs = math.sqrt(qs + f[2] * f[2])
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
        p0 = en
        slope = 0.0
        for m in range(n):
            p0 -= F[idx[m]] * u[idx[m]]
            slope += r[m] * step[m]
        tstep = 1.0
        for _ls in range(60):
            for i in range(5):
                ut[i] = u[i]
            for m in range(n):
                ut[idx[m]] += tstep * step[m]
            if speed:
                Vt = V.copy()
                _w, yt = _assemble_speed(
                    ut, psi, moff, r_pi, y0, ci, co, Ki, Ko, Fc, mg0, gam, Vt, f, H, Qi, Qo, ai, ao
                )
                nt = 0.0
                for m in range(n):
                    i = idx[m]
                    w = (f[i] - F[i]) / r_pi if i >= 3 else f[i] - F[i]
                    nt += w * w
                if yt > 0.0 and math.sqrt(nt) < (1.0 - 1e-4 * tstep) * nr:
                    V[:, :] = Vt
                    break
            else:
                e1, yt = _assemble(ut, psi, moff, r_pi, y0, a0, K, f, H)
                p1 = e1
                nt = 0.0
                for m in range(n):
                    i = idx[m]
                    p1 -= F[i] * ut[i]
                    w = (f[i] - F[i]) / r_pi if i >= 3 else f[i] - F[i]
                    nt += w * w
                if yt > 0.0 and (
                    p1 <= p0 + 1e-4 * tstep * slope or math.sqrt(nt) < (1.0 - 1e-4 * tstep) * nr
                ):
                    break
            tstep *= 0.5
        for m in range(n):
            u[idx[m]] += tstep * step[m]
    out_info[0] = it
    out_info[1] = rel
    out_info[2] = ymin
    out_info[3] = status


@njit(cache=True)
def _ball_setup(cage, psi0, errors, shaft_angle, to_x, to_y, ti_amp, ti_az0, r_pi, r_po, psi, moff):
    """Ball azimuths ``psi_j = cage + psi0 + 2 pi j/Z + e_j`` (seed eq. (1)) and misalignment
    offsets ``m_j`` (seed eqs. (2)–(3)) at one cage angle."""
    Z = psi.size
    az = ti_az0 + shaft_angle
    ti_x = ti_amp * math.sin(az)
    ti_y = ti_amp * math.cos(az)
    for j in range(Z):
        p = cage + psi0 + 2.0 * math.pi * j / Z + errors[j]
        psi[j] = p
        c = math.cos(p)
        s = math.sin(p)
        moff[j] = r_pi * (ti_x * c - ti_y * s) - r_po * (to_x * c - to_y * s)


@njit(cache=True)
def _sweep(
    cage,
    psi0,
    errors,
    cage_ratio,
    to_x,
    to_y,
    ti_amp,
    ti_az0,
    u0,
    free,
    F,
    r_pi,
    r_po,
    y0,
    a0,
    K,
    ci,
    co,
    Ki,
    Ko,
    Fc,
    mg0,
    gam,
    speed,
    V0,
    tol,
    maxit,
    out_u,
    out_H,
    out_f,
    out_Q,
    out_alpha,
    out_delta,
    out_info,
):
    """Equilibrium and tangent stiffness at every cage angle, each started from the previous."""
    Z = errors.size
    psi = np.empty(Z)
    moff = np.empty(Z)
    u = u0.copy()
    V = V0.copy()
    f = np.empty(5)
    H = np.empty((5, 5))
    info = np.empty(4)
    Qi = np.empty(Z)
    Qo = np.empty(Z)
    ai = np.empty(Z)
    ao = np.empty(Z)
    for m in range(cage.size):
        _ball_setup(
            cage[m],
            psi0,
            errors,
            cage[m] / cage_ratio,
            to_x,
            to_y,
            ti_amp,
            ti_az0,
            r_pi,
            r_po,
            psi,
            moff,
        )
        _solve_ring(
            u,
            free,
            F,
            psi,
            moff,
            r_pi,
            y0,
            a0,
            K,
            ci,
            co,
            Ki,
            Ko,
            Fc,
            mg0,
            gam,
            speed,
            V,
            tol,
            maxit,
            info,
        )
        for i in range(4):
            out_info[m, i] = info[i]
        if info[3] != 0.0:
            return m
        if speed:
            _assemble_speed(
                u, psi, moff, r_pi, y0, ci, co, Ki, Ko, Fc, mg0, gam, V, f, H, Qi, Qo, ai, ao
            )
            for j in range(Z):
                out_Q[m, j] = Qi[j]
                out_alpha[m, j] = ai[j]
                out_delta[m, j] = (Qi[j] / Ki) ** (2.0 / 3.0) + (Qo[j] / Ko) ** (2.0 / 3.0)
        else:
            _assemble(u, psi, moff, r_pi, y0, a0, K, f, H)
            for j in range(Z):
                s = math.sin(psi[j])
                c = math.cos(psi[j])
                X = u[2] + r_pi * (u[3] * c - u[4] * s) + moff[j]
                Y = y0 + u[0] * s + u[1] * c
                A = math.sqrt(X * X + Y * Y)
                dl = A - a0
                out_delta[m, j] = dl
                out_alpha[m, j] = math.atan2(X, Y)
                out_Q[m, j] = K * dl * math.sqrt(dl) if dl > 0.0 else 0.0
        for i in range(5):
            out_u[m, i] = u[i]
            out_f[m, i] = f[i]
            for k in range(5):
                out_H[m, i, k] = H[i, k]
    return cage.size
