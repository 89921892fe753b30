"""Quasi-static 5-DOF model of a ball bearing with ring misalignment and ball-distribution error.

Seed QS5 (Xu, Yang, Wang, Ma, J. Northeastern Univ. 2023, 44(3)) eqs. (1)–(7), completed with the
standard Jones (1960) / Harris & Kotzalas (2007, vol. 2 ch. 3) quasi-static model as SPEC §5 asks
(the seed is cut off after its eq. (7)).

Conventions (shared with :mod:`bearingsim.load_distribution`): SI units; outer ring fixed, inner
ring displaced by ``u = (x, y, z, theta_x, theta_y)``; ball azimuth ``psi`` measured from +y
towards +x, so the radial unit vector at ball ``j`` is ``e_r = (sin psi_j, cos psi_j, 0)``.

Geometry of ball ``j`` (groove-curvature centres, Harris & Kotzalas 2007 §2.3; seed eqs. (2)–(7)):

* ``A0 = (f_i + f_o - 1) d`` is the distance of the groove centres when the ball just touches
  both grooves (seed "A0"; Harris "A = B D").
* radial separation of the groove centres ``Y_j = A0 - P_d/2 + x sin psi_j + y cos psi_j``
  (seed eq. (7) with ``S_r = P_d`` the diametral clearance, in our azimuth convention);
* axial separation ``X_j = z + r_pi (theta_x cos psi_j - theta_y sin psi_j) + m_j`` (seed eq. (6):
  the small-rotation displacement of the inner groove centre, radius ``r_pi`` from seed eq. (5)),
  ``z`` measured from the axially centred position, which is the seed's ``z - S_a/2`` measured from
  the one-sided contact position with ``S_a = 2 A0 sin(alpha_f)``;
* ``m_j`` the misalignment offset (seed eqs. (2)–(3)):
  ``m_j = r_pi (t_ix cos psi_j - t_iy sin psi_j) - r_po (t_ox cos psi_j - t_oy sin psi_j)`` where a
  tilt ``T`` about the in-plane axis at azimuth ``A`` is the rotation vector
  ``(T sin A, T cos A, 0)``; the inner-ring tilt axis rotates with the shaft
  (``A_i = A_i0 + shaft angle``), the outer-ring axis is fixed. The minus sign makes ``t_o`` the
  physical rotation of the outer ring (the seed writes the relative tilt with a plus sign; for a
  single misalignment the two are the same case with the azimuth turned by pi);
* ``A_j = sqrt(X_j^2 + Y_j^2)``, contact deformation ``delta_j = A_j - A0`` (> 0 in contact),
  contact angle ``alpha_j = atan2(X_j, Y_j)``, load ``Q_j = K delta_j^1.5`` (SPEC §5, Hertz ``K`` of
  seed VSM eq. (10), :func:`bearingsim.contact.hertz.ball_stiffness`).

Equilibrium of the inner ring: ``sum_j Q_j dA_j/du = F`` with ``F = (Fx, Fy, Fz, Mx, My)`` —
``Fx = sum Q cos(alpha) sin(psi)``, ``Fy = sum Q cos(alpha) cos(psi)``, ``Fz = sum Q sin(alpha)``,
``Mx = r_pi sum Q sin(alpha) cos(psi)``, ``My = -r_pi sum Q sin(alpha) sin(psi)``. This is the
gradient of the potential ``sum K delta^2.5 / 2.5 - F.u``, so the analytic Jacobian (the tangent
stiffness matrix) is its Hessian, symmetric:
``K_ring = sum 1.5 K delta^0.5 g g^T + (Q/A) t t^T`` with ``g = dA/du`` and ``t`` the unit
direction normal to it in the (axial, radial) plane. It is solved by Newton–Raphson with an
Armijo line search on the (convex) potential, started from the radial solution.

Misalignment is an abnormal preload (seed §1.1): when a misalignment is given the ring tilts are
*held* (the shaft imposes them) and the moments become reactions; otherwise a free tilt would just
rotate the inner ring back and remove the misalignment exactly.

Optional speed effects (off by default; Harris & Kotzalas 2007 vol. 2 eqs. (3.32)–(3.37)): the
ball centrifugal force ``F_c = m d_m omega_c^2 / 2`` and the gyroscopic moment
``M_g = J omega_R omega_c sin(beta)`` taken by the outer raceway (outer-raceway control,
``lambda_i = 0, lambda_o = 2``), with two ball-centre unknowns per ball solved inside the ring
Newton loop and condensed into the ring Jacobian analytically.
"""

from __future__ import annotations

import math
from typing import NamedTuple

import numpy as np
from numpy.typing import ArrayLike, NDArray

from ..contact.capacity import check_element_load, check_load
from ..errors import ConfigError, SolverError
from ..geometry import Bearing, check_speed_limit
from ._kernels import (
    B_ALPHA,
    B_DELTA,
    B_Q,
    I_ITER,
    I_RES,
    I_STATUS,
    P_CO,
    R_F,
    R_U,
    _params,
    _sweep,
)
from .inputs import (
    Method,
    Misalignment,
    QSGeometry,
    SpeedEffects,
    _ball_azimuths,
    _validate_case,
    qs_geometry,
)
from .result import QuasiStaticSolution

#: how the load check names the radial load
_RADIAL = "|(fx_n, fy_n)|"

__all__ = ["AxialState", "axial_state", "run_quasi_static", "solve_equilibrium"]


class AxialState(NamedTuple):
    """The static state of a ball set under an axial load (:func:`axial_state`)."""

    z: float  #: axial offset of the inner ring's groove centres [m]
    contact_angle: float  #: load-weighted mean contact angle of the loaded balls [rad]
    ball_contact_angles: NDArray[np.float64]  #: each ball's contact angle at t = 0 [rad]
    #: groove-centre distance ``A0 = (f_i + f_o - 1) d`` of the Jones solution's geometry [m]
    #: (0 without an axial load: not solved, not used)
    a0: float = 0.0


def axial_state(
    bearing: Bearing,
    fx: float,
    fy: float,
    fa: float,
    *,
    clearance: float,
    stiffness: float,
    first_ball_angle: float,
) -> AxialState:
    """The axial offset ``z`` and the contact angles of a ball set under the radial load
    ``(fx, fy)`` [N] and the axial load ``fa`` [N] (:func:`run_quasi_static` at cage angle 0,
    the ring tilts held, no load check: the caller's), with the ball constant ``stiffness``
    [N/m^1.5] and the diametral ``clearance`` [m]; the dynamic models (DEM, TVSM, rotor with
    quasi-static balls) hold this ``z`` and turn the cage at the load-weighted mean angle.
    ``first_ball_angle`` [rad]: ball 1's azimuth at t = 0."""
    sol = run_quasi_static(
        bearing,
        0.0,
        fx,
        fy,
        fa,
        clearance=clearance,
        stiffness=stiffness,
        first_ball_angle=math.remainder(first_ball_angle, 2.0 * math.pi),
        tilt_free=False,
        allow_overload=None,
    )
    q = sol.ball_loads[0]
    alpha = sol.contact_angles[0]
    return AxialState(
        float(sol.displacement[0, 2]),
        float(np.sum(q * alpha) / np.sum(q)),
        alpha.copy(),
        float(sol.geometry.a0),
    )


def _radial_start(geom: QSGeometry, psi: NDArray[np.float64], F: NDArray[np.float64]) -> tuple:
    """Radial ring displacement solving ``sum K (dr cos_j - P_d/2)_+^1.5 cos_j = F_r`` along the
    load line for the actual ball positions (SPEC §0.4), by bisection; (ux, uy) [m]."""
    fr = math.hypot(F[0], F[1])
    if fr == 0.0:
        return 0.0, 0.0
    th0 = math.atan2(F[0], F[1])
    cosl = np.cos(psi - th0)
    c = 0.5 * geom.clearance

    def g(dr: float) -> float:
        dj = np.maximum(dr * cosl - c, 0.0)
        return float(np.sum(geom.k * dj**1.5 * cosl)) - fr

    hi = max(c, 0.0) + (fr / geom.k) ** (2.0 / 3.0) + 1e-12
    while g(hi) <= 0.0:
        hi *= 2.0
    lo = 0.0
    for _ in range(100):
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if g(mid) < 0.0 else (lo, mid)
    return hi * math.sin(th0), hi * math.cos(th0)


def _axial_start(geom: QSGeometry, fz: float) -> float:
    """Axial displacement with all Z balls equally loaded, ``Z K delta^1.5 sin(alpha) = F_z``
    (Harris & Kotzalas 2007 eq. (7.35) form), by bisection [m]."""
    if fz == 0.0:
        return 0.0
    Z, K, a0, y0 = geom.n_balls, geom.k, geom.a0, geom.y0

    def g(z: float) -> float:
        A = math.hypot(z, y0)
        dl = max(A - a0, 0.0)
        return Z * K * dl**1.5 * z / A - abs(fz)

    hi = a0
    while g(hi) <= 0.0:
        hi *= 2.0
    lo = 0.0
    for _ in range(100):
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if g(mid) < 0.0 else (lo, mid)
    return math.copysign(hi, fz)


def check_moment_ball_load(
    bearing: Bearing, F: NDArray[np.float64], ball_loads: NDArray[np.float64], allow_overload
) -> None:
    """Under a moment the largest ball load is known only after the solve (the check of the
    forces against C_0 before it does not see the moment): check it against the element limit
    Q_0 (:func:`~bearingsim.contact.capacity.check_element_load`: a warning above Q_0, a
    one-line refusal above its static limit unless ``allow_overload``)."""
    if F[3] == 0.0 and F[4] == 0.0:
        return
    check_element_load(
        bearing, float(np.max(ball_loads)), allow_overload,
        name=f"largest ball load under the moment ({F[3]:.6g}, {F[4]:.6g}) N m",
    )  # fmt: skip


def _start(geom: QSGeometry, psi: NDArray[np.float64], F: NDArray[np.float64]):
    """Newton's start ``(x, y, z, theta_x, theta_y)`` [m, rad] for balls at ``psi``: radial
    along the load line, axial from equal ball loads, tilted for a moment alone."""
    return np.array([*_radial_start(geom, psi, F), _axial_start(geom, F[2]), *_tilt_start(geom, F)])


def _tilt_start(geom: QSGeometry, F: NDArray[np.float64]) -> tuple[float, float]:
    """Tilt start ``(theta_x, theta_y)`` [rad] for a moment without forces: with a clearance
    the untilted ring touches no ball, so Newton starts from a tilt that takes it up — the
    axial displacement of :func:`_axial_start` under ``2 |M| / r_m`` at the pitch radius
    ``r_m``, along the moment's direction. With a force the start stays untilted."""
    mx, my = float(F[3]), float(F[4])
    m = math.hypot(mx, my)
    if m == 0.0 or np.any(F[:3] != 0.0):
        return 0.0, 0.0
    rm = 0.5 * geom.dm
    theta = _axial_start(geom, 2.0 * m / rm) / rm
    return theta * mx / m, theta * my / m


def _inertia(geom: QSGeometry, speed: SpeedEffects) -> tuple[float, float, float]:
    """``(F_c [N], 2 J omega_R omega_c / d [N], gamma' = d/d_m)`` from nominal kinematics
    (Harris & Kotzalas 2007 vol. 2 eqs. (3.17), (3.33): ``F_c = m d_m omega_c^2 / 2``,
    ``J = rho pi d^5 / 60``, ball spin ``omega_R`` = 2 pi BSF)."""
    if not speed.active:
        return 0.0, 0.0, geom.d / geom.dm
    d, dm, rho = geom.d, geom.dm, geom.density
    wc = geom.cage_ratio * speed.shaft_speed
    g = geom.d / geom.dm  # deep groove: cos(alpha_n) taken as in the kinematics
    w_r = speed.shaft_speed * dm / (2.0 * d) * (1.0 - g * g)
    mass = rho * math.pi * d**3 / 6.0
    fc = 0.5 * mass * dm * wc**2 if speed.centrifugal else 0.0
    J = rho * math.pi * d**5 / 60.0
    mg0 = 2.0 * J * w_r * wc / d if speed.gyroscopic else 0.0
    return fc, mg0, g


def run_quasi_static(
    bearing: Bearing,
    cage_angles: ArrayLike = 0.0,
    fx: float = 0.0,
    fy: float = 0.0,
    fz: float = 0.0,
    mx: float = 0.0,
    my: float = 0.0,
    *,
    clearance: float | None = None,
    misalignment: Misalignment | None = None,
    ball_errors: ArrayLike | None = None,
    first_ball_angle: float = 0.0,
    tilt_free: bool | None = None,
    speed: SpeedEffects | None = None,
    stiffness: float | None = None,
    max_contact_angle: float | None = None,
    tol: float = 1e-12,
    max_iterations: int = 100,
    allow_overload: bool | None = False,
) -> QuasiStaticSolution:
    """Jones–Harris 5-DOF quasi-static equilibrium and tangent stiffness at each cage angle
    (seed QS5 eqs. (1)–(7) completed per SPEC §5; Harris & Kotzalas 2007 vol. 2 ch. 3).

    Parameters
    ----------
    bearing : BallBearing
        Geometry and material.
    cage_angles : float or array_like
        Cage angle(s) [rad]; solved in order, each started from the previous solution. One
        value gives one labelled 5x5 stiffness matrix, a sequence a stack (m, 5, 5).
    fx, fy, fz : float
        Forces on the inner ring [N] (x, y radial; z axial).
    mx, my : float
        Moments on the inner ring about x and y [N m].
    clearance : float, optional
        Diametral clearance P_d [m] (seed S_r) overriding the bearing's; negative = preload.
    misalignment : Misalignment, optional
        Outer/inner ring tilts (seed eqs. (2)–(3)).
    ball_errors : array_like, optional
        Ball-distribution errors e_j [rad], Z values (seed eq. (1)).
    first_ball_angle : float
        Azimuth of ball 1 at cage angle 0 [rad].
    tilt_free : bool, optional
        Solve the ring tilts (moment equilibrium) or hold them at 0. Default: held when a
        misalignment is given (it is an imposed preload), free otherwise.
    speed : SpeedEffects, optional
        Centrifugal/gyroscopic ball loads (off by default).
    stiffness : float, optional
        Combined ball constant K [N/m^1.5] overriding the Hertz value (no inertia loads).
    max_contact_angle : float, optional
        Largest admissible contact angle [rad] (groove shoulder); beyond it there is no
        equilibrium the geometry allows.
    tol : float
        Relative force-residual tolerance [-]; a residual that stays at the round-off floor of
        the contact forces for two iterations also counts as converged (tiny loads, heavy
        preload).
    max_iterations : int
        Newton iterations per cage angle [-].
    allow_overload : bool or None
        The static equivalent load of ``(fx, fy)`` and ``fz`` is checked against the static
        capacity before the solution (:func:`bearingsim.contact.capacity.check_load`: a warning
        above ``C_0``, refused above ``2 C_0``), and the ball centrifugal force against the
        element load at the ISO 76 stress (``check_element_load``); ``True`` runs an overload
        anyway, ``None`` skips the checks.

    Returns
    -------
    QuasiStaticSolution
        Ring displacement, labelled tangent stiffness, ball loads and contact angles at every
        cage angle, with the inputs (saved and loaded losslessly as netCDF).
    """
    geom = qs_geometry(bearing, clearance, max_contact_angle, stiffness)
    spd = speed if speed is not None else SpeedEffects()
    if spd.active and stiffness is not None:
        raise ConfigError(
            "stiffness override is not available with inertia loads (it needs the "
            "separate inner and outer Hertz constants)"
        )
    case = _validate_case(
        geom,
        cage_angles,
        (fx, fy, fz, mx, my),
        misalignment,
        ball_errors,
        first_ball_angle,
        tilt_free,
        spd.active,
    )
    mis, cage, F = case.misalignment, case.cage, case.applied
    check_load(
        bearing, math.hypot(F[0], F[1]), allow_overload, F[2], name=_RADIAL, axial_name="fz_n"
    )
    fc, mg0, gam = _inertia(geom, spd)
    # the centrifugal force presses each ball on the outer raceway: the same static limit
    check_element_load(bearing, fc, allow_overload, name="ball centrifugal force F_c")
    check_speed_limit(bearing, spd.shaft_speed * 30.0 / math.pi, "shaft speed", "[0")
    p = _params(
        geom,
        F,
        case.free,
        first_ball_angle=case.first_ball_angle,
        outer_tilt_xy=(
            mis.outer_tilt * math.sin(mis.outer_azimuth),
            mis.outer_tilt * math.cos(mis.outer_azimuth),
        ),
        inner_tilt=(mis.inner_tilt, mis.inner_azimuth),
        inertia=(fc, mg0, gam) if spd.active else None,
        tol=tol,
        max_iterations=int(max_iterations),
    )
    # start: radial solution along the load line, axial from equal ball loads; ball centres on
    # the outer groove (pushed out by the centrifugal force)
    Z = geom.n_balls
    psi_first = _ball_azimuths(cage[0], case.first_ball_angle, case.ball_errors)
    u0 = _start(geom, psi_first, F)
    co = p[P_CO]
    V0 = np.zeros((Z, 2))
    V0[:, 1] = co + (fc / geom.k_outer) ** (2.0 / 3.0) if spd.centrifugal else co
    m = cage.size
    out_ring = np.zeros((m, 2, 5))
    out_H = np.zeros((m, 5, 5))
    out_balls = np.zeros((m, 3, Z))
    out_info = np.zeros((m, 4))
    done = _sweep(cage, case.ball_errors, p, u0, V0, out_ring, out_H, out_balls, out_info)
    retried = -1
    while retried < done < m:
        # each cage angle starts from the previous solution; where that start fails (a load
        # carried by one or two balls, the ring sliding between them), start it again from the
        # radial solution at that angle, once
        retried = done
        psi_k = _ball_azimuths(cage[done], case.first_ball_angle, case.ball_errors)
        uk = _start(geom, psi_k, F)
        done += _sweep(
            cage[done:],
            case.ball_errors,
            p,
            uk,
            V0,
            out_ring[done:],
            out_H[done:],
            out_balls[done:],
            out_info[done:],
        )
    if done < m:
        status = int(out_info[done, I_STATUS])
        where = f"at cage angle {cage[done]:.6g} rad"
        if status == 2:
            psi_k = _ball_azimuths(cage[done], case.first_ball_angle, case.ball_errors)
            if math.hypot(*_radial_start(geom, psi_k, F)) < geom.y0:
                # the radial load alone stays well inside the grooves: the iteration ran off
                # because too few balls hold the ring, not because the load is too large
                lift = " and the balls' centrifugal lift" if spd.centrifugal else ""
                raise SolverError(
                    f"no equilibrium found {where}: too few balls hold the ring (a load of "
                    f"{math.hypot(F[0], F[1]):.6g} N radial, {F[2]:.6g} N axial against the "
                    f"clearance {geom.clearance:.6g} m{lift}); increase the load or reduce the "
                    "clearance"
                )
            raise SolverError(
                f"no equilibrium {where}: the radial displacement exceeds the groove-centre "
                "distance (load beyond what the geometry allows); reduce the load"
            )
        raise SolverError(
            f"no equilibrium found {where} after {int(out_info[done, I_ITER])} Newton iterations "
            f"(relative residual {out_info[done, I_RES]:.3g}); check the load and clearance"
        )
    out_Q, out_a = out_balls[:, B_Q], out_balls[:, B_ALPHA]
    check_moment_ball_load(bearing, F, out_Q, allow_overload)
    amax = np.max(np.abs(out_a) * (out_Q > 0))
    if amax > geom.max_contact_angle:
        i, j = np.unravel_index(np.argmax(np.abs(out_a) * (out_Q > 0)), out_a.shape)
        raise SolverError(
            f"no equilibrium the geometry allows: ball {j + 1} needs contact angle "
            f"{math.degrees(amax):.1f} deg at cage angle {cage[i]:.6g} rad, beyond the groove "
            f"limit {math.degrees(geom.max_contact_angle):.1f} deg (max_contact_angle); reduce "
            "the load"
        )
    return QuasiStaticSolution._build(
        case,
        geom,
        Method.JONES,
        spd,
        bearing.id,
        out_H,
        displacement=np.ascontiguousarray(out_ring[:, R_U]),
        reaction=np.ascontiguousarray(out_ring[:, R_F]),
        ball_loads=np.ascontiguousarray(out_Q),
        contact_angles=np.ascontiguousarray(out_a),
        deflections=np.ascontiguousarray(out_balls[:, B_DELTA]),
        iterations=out_info[:, I_ITER].astype(np.int64),
        residual=out_info[:, I_RES].copy(),
    )


# (duplicates) the load arguments repeat run_quasi_static's: the one-position shortcut
def solve_equilibrium(
    bearing: Bearing,
    fx: float = 0.0,
    fy: float = 0.0,
    fz: float = 0.0,
    mx: float = 0.0,
    my: float = 0.0,
    *,
    cage_angle: float = 0.0,
    **kwargs: object,
) -> QuasiStaticSolution:
    """Equilibrium at one cage angle; its stiffness is one labelled 5x5 matrix.

    Parameters
    ----------
    bearing : BallBearing
        Geometry and material.
    fx, fy, fz : float
        Forces on the inner ring [N].
    mx, my : float
        Moments on the inner ring [N m].
    cage_angle : float
        Cage angle [rad].
    **kwargs
        Keywords of :func:`run_quasi_static`.
    """
    return run_quasi_static(bearing, cage_angle, fx, fy, fz, mx, my, **kwargs)
