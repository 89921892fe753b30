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
  seed VSM eq. (10), :func:`bearingsim.hertz.ball_stiffness`).

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

import enum
import math
from dataclasses import dataclass, field

import numpy as np
from numpy.typing import ArrayLike, NDArray

from ..contact.hertz import ball_contact, ball_stiffness
from ..errors import ConfigError, SolverError, check_range
from ..geometry import BallBearing, Bearing, Race, characteristic_frequencies
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

#: names of the five inner-ring degrees of freedom, in vector order
DOF_NAMES = ("x", "y", "z", "theta_x", "theta_y")
#: assumed groove depth / ball diameter used for the default maximum contact angle (the
#: catalogue gives no shoulder heights; typical deep-groove grooves are about a quarter of the
#: ball diameter deep). Override with ``max_contact_angle``.
DEFAULT_GROOVE_DEPTH_RATIO = 0.25


class Method(enum.Enum):
    """Load-distribution method."""

    #: Jones/Harris groove-centre model with exact Hertz ``K`` (this module)
    JONES = "jones"
    #: ISO/TS 16281 ball-bearing method (:mod:`bearingsim.iso16281`)
    ISO16281 = "iso16281"


# ------------------------------------------------------------------------------------- inputs


@dataclass(frozen=True)
class Misalignment:
    """Ring misalignments (seed QS5 fig. 2, eqs. (2)–(3)).

    Parameters
    ----------
    outer_tilt : float
        Outer-ring tilt magnitude theta_to [rad], >= 0.
    outer_azimuth : float
        Azimuth of the outer-ring tilt axis phi_to, from +y towards +x [rad] (fixed).
    inner_tilt : float
        Inner-ring tilt magnitude theta_ti [rad], >= 0.
    inner_azimuth : float
        Azimuth of the inner-ring tilt axis at shaft angle 0, phi_ti [rad]; it rotates with the
        shaft.
    """

    outer_tilt: float = 0.0
    outer_azimuth: float = 0.0
    inner_tilt: float = 0.0
    inner_azimuth: float = 0.0

    def __post_init__(self) -> None:
        for name, unit in (("outer_tilt", "rad"), ("inner_tilt", "rad")):
            object.__setattr__(
                self, name, check_range(f"{name}_rad", getattr(self, name), 0.0, unit=unit)
            )
        for name in ("outer_azimuth", "inner_azimuth"):
            object.__setattr__(
                self,
                name,
                check_range(
                    f"{name.replace('azimuth', 'tilt_azimuth')}_rad",
                    getattr(self, name),
                    unit="rad",
                ),
            )

    @property
    def any(self) -> bool:
        """True when either ring is tilted."""
        return self.outer_tilt > 0.0 or self.inner_tilt > 0.0


@dataclass(frozen=True)
class SpeedEffects:
    """Optional ball inertia loads (off by default).

    Parameters
    ----------
    shaft_speed : float
        Inner-ring angular speed omega_s [rad/s], > 0 when an effect is on.
    centrifugal : bool
        Include the ball centrifugal force ``m d_m omega_c^2 / 2``.
    gyroscopic : bool
        Include the gyroscopic moment ``J omega_R omega_c sin(beta)`` (outer-raceway control).
    """

    shaft_speed: float = 0.0
    centrifugal: bool = False
    gyroscopic: bool = False

    def __post_init__(self) -> None:
        w = check_range("shaft_speed_rad_s", self.shaft_speed, 0.0, unit="rad/s")
        if (self.centrifugal or self.gyroscopic) and w <= 0.0:
            raise ConfigError(
                f"shaft_speed_rad_s = {w:.6g} rad/s must be > 0 when centrifugal or gyroscopic "
                "loads are on; valid range (0, inf) rad/s"
            )
        object.__setattr__(self, "shaft_speed", w)

    @property
    def active(self) -> bool:
        """True when any inertia load is on."""
        return self.centrifugal or self.gyroscopic


@dataclass(frozen=True)
class QSGeometry:
    """Derived quantities of the quasi-static model for one bearing and clearance (SI).

    Attributes
    ----------
    n_balls : int
        Z [-].
    d, dm : float
        Ball and pitch diameter [m].
    a0 : float
        ``(f_i + f_o - 1) d`` [m].
    clearance : float
        Diametral clearance P_d (= seed S_r) [m].
    y0 : float
        Radial groove-centre separation of the centred unloaded rings, ``a0 - P_d/2`` [m].
    free_contact_angle : float
        ``arccos(1 - P_d/(2 a0))`` for P_d > 0, else 0 [rad] (Harris & Kotzalas eq. (2.10)).
    axial_clearance : float
        Total axial play ``S_a = 2 a0 sin(alpha_f)`` [m].
    r_pi, r_po : float
        Radii of the inner/outer groove-centre loci, seed eq. (5) [m].
    k : float
        Combined ball constant K [N/m^1.5] (seed VSM eq. (10)).
    k_inner, k_outer : float
        Hertz constants of the inner and outer contacts [N/m^1.5].
    cage_ratio : float
        Cage speed / shaft speed (FTF order) [-].
    max_contact_angle : float
        Largest admissible contact angle [rad].
    """

    n_balls: int
    d: float
    dm: float
    a0: float
    clearance: float
    y0: float
    free_contact_angle: float
    axial_clearance: float
    r_pi: float
    r_po: float
    k: float
    k_inner: float
    k_outer: float
    f_i: float
    f_o: float
    cage_ratio: float
    max_contact_angle: float
    density: float


def max_contact_angle_default(bearing: BallBearing) -> float:
    """Contact angle at which the contact point reaches an assumed groove shoulder of depth
    ``DEFAULT_GROOVE_DEPTH_RATIO * d``: ``arccos(1 - h/R)`` for the shallower groove [rad]."""
    h = DEFAULT_GROOVE_DEPTH_RATIO * bearing.element_diameter
    r = max(bearing.inner_groove_radius, bearing.outer_groove_radius)
    return math.acos(max(-1.0, 1.0 - h / r))


def qs_geometry(
    bearing: Bearing,
    clearance: float | None = None,
    max_contact_angle: float | None = None,
    stiffness: float | None = None,
) -> QSGeometry:
    """Validated derived geometry of the 5-DOF model (seed QS5 eqs. (4)–(5); SPEC §5).

    Parameters
    ----------
    bearing : BallBearing
        Geometry and material.
    clearance : float, optional
        Diametral clearance P_d [m] overriding the bearing's (negative = preload).
    max_contact_angle : float, optional
        Largest admissible contact angle [rad] (default :func:`max_contact_angle_default`).
    stiffness : float, optional
        Combined ball constant K [N/m^1.5] overriding the Hertz value.
    """
    if not isinstance(bearing, BallBearing):
        raise ConfigError(
            f"bearing = {bearing.id!r} is a {bearing.kind} bearing; the quasi-static 5-DOF model "
            "needs a ball bearing"
        )
    d, dm = bearing.element_diameter, bearing.pitch_diameter
    fi, fo = bearing.inner_conformity, bearing.outer_conformity
    a0 = (fi + fo - 1.0) * d
    pd = bearing.diametral_clearance if clearance is None else clearance
    pd = check_range("clearance_m", pd, -0.5 * d, 2.0 * a0, hi_open=True, unit="m")
    af = math.acos(1.0 - pd / (2.0 * a0)) if pd > 0 else 0.0
    r_pi = 0.5 * dm + (fi - 0.5) * d * math.cos(af)  # seed QS5 eq. (5)
    r_po = 0.5 * dm - (fo - 0.5) * d * math.cos(af)  # seed QS5 eq. (5)
    amax = max_contact_angle_default(bearing) if max_contact_angle is None else max_contact_angle
    amax = check_range(
        "max_contact_angle_rad", amax, 0.0, 0.5 * math.pi, lo_open=True, hi_open=True, unit="rad"
    )
    k = (
        ball_stiffness(bearing)
        if stiffness is None
        else check_range("stiffness", stiffness, 0.0, lo_open=True, unit="N/m^1.5")
    )
    ki = ball_contact(bearing, 1.0, Race.INNER).k_hertz
    ko = ball_contact(bearing, 1.0, Race.OUTER).k_hertz
    return QSGeometry(
        n_balls=bearing.n_elements,
        d=d,
        dm=dm,
        a0=a0,
        clearance=pd,
        y0=a0 - 0.5 * pd,
        free_contact_angle=af,
        axial_clearance=2.0 * a0 * math.sin(af),
        r_pi=r_pi,
        r_po=r_po,
        k=k,
        k_inner=ki,
        k_outer=ko,
        f_i=fi,
        f_o=fo,
        cage_ratio=characteristic_frequencies(bearing, 1.0).ftf_order,
        max_contact_angle=amax,
        density=bearing.material.density,
    )


def max_tilt(geom: QSGeometry, race: str, other: float = 0.0) -> float:
    """Largest misalignment tilt [rad] of ``race`` ('inner' or 'outer') for which the unloaded
    contact angle stays below ``geom.max_contact_angle``; ``other`` is the axial offset [m]
    already taken by the other ring's tilt (``r_p * tilt``)."""
    budget = geom.y0 * math.tan(geom.max_contact_angle) - other
    r = geom.r_pi if race == "inner" else geom.r_po
    return max(budget, 0.0) / r


def check_misalignment(geom: QSGeometry, mis: Misalignment) -> None:
    """Raise a one-line :class:`ConfigError` when a tilt exceeds what clearance and groove allow:
    the misalignment alone must not push any ball past ``max_contact_angle``."""
    off_o = geom.r_po * mis.outer_tilt
    tmax_o = max_tilt(geom, "outer")
    if mis.outer_tilt > tmax_o:
        raise ConfigError(
            f"outer_tilt_rad = {mis.outer_tilt:.6g} rad is beyond what the clearance and groove "
            f"geometry allow (contact angle would exceed {math.degrees(geom.max_contact_angle):.1f}"
            f" deg); valid range [0, {tmax_o:.6g}] rad"
        )
    tmax_i = max_tilt(geom, "inner", other=off_o)
    if mis.inner_tilt > tmax_i:
        raise ConfigError(
            f"inner_tilt_rad = {mis.inner_tilt:.6g} rad is beyond what the clearance and groove "
            f"geometry allow together with outer_tilt_rad = {mis.outer_tilt:.6g} rad (contact "
            f"angle would exceed {math.degrees(geom.max_contact_angle):.1f} deg); valid range "
            f"[0, {tmax_i:.6g}] rad"
        )


def check_ball_errors(geom: QSGeometry, errors: ArrayLike | None) -> NDArray[np.float64]:
    """Validate the per-ball angular offsets e_j [rad] (seed QS5 eq. (1)): exactly Z finite
    values, and neighbouring balls may neither overlap nor pass each other (centre spacing on the
    pitch circle at least ``2 arcsin(d/d_m)``)."""
    Z = geom.n_balls
    if errors is None:
        return np.zeros(Z)
    e = np.atleast_1d(np.asarray(errors, dtype=float)).ravel()
    if e.size != Z:
        raise ConfigError(
            f"ball_errors_rad has {e.size} values; valid: exactly n_elements = {Z} values"
        )
    bad = np.flatnonzero(~np.isfinite(e))
    if bad.size:
        raise ConfigError(
            f"ball_errors_rad[{bad[0]}] = {float(e[bad[0]])} is not finite; "
            "valid range (-inf, inf) rad"
        )
    gap_min = 2.0 * math.asin(geom.d / geom.dm)
    pitch = 2.0 * math.pi / Z
    for j in range(Z):
        k = (j + 1) % Z
        gap = pitch + e[k] - e[j]
        if gap < gap_min:
            raise ConfigError(
                f"ball_errors_rad[{j}] = {e[j]:.6g} rad and ball_errors_rad[{k}] = {e[k]:.6g} rad "
                f"make balls {j + 1} and {k + 1} overlap or pass each other (centre spacing "
                f"{gap:.6g} rad < ball angular width {gap_min:.6g} rad); valid: "
                f"ball_errors_rad[{k}] - ball_errors_rad[{j}] >= {gap_min - pitch:.6g} rad"
            )
    return e


# ------------------------------------------------------------------------------ Python API


@dataclass(frozen=True)
class QuasiStaticSolution:
    """Equilibria of the inner ring at one or more cage angles (leading axis: cage angle).

    Attributes
    ----------
    cage_angle : ndarray, shape (m,)
        Cage angles [rad].
    shaft_angle : ndarray, shape (m,)
        Inner-ring (shaft) angles ``cage_angle / cage_ratio`` [rad].
    displacement : ndarray, shape (m, 5)
        ``(x [m], y [m], z [m], theta_x [rad], theta_y [rad])`` of the inner ring.
    stiffness_matrix : ndarray, shape (m, 5, 5)
        Tangent stiffness ``dF/du`` [N/m, N, N/rad, N m/rad] (rows: Fx, Fy, Fz, Mx, My).
    reaction : ndarray, shape (m, 5)
        Resultant of the ball forces on the inner ring ``(Fx, Fy, Fz [N], Mx, My [N m])``; equals
        the applied load on the free DOFs; on held tilts it is the reaction moment.
    ball_angles : ndarray, shape (m, Z)
        Ball azimuths psi_j [rad] (seed eq. (1)).
    ball_loads : ndarray, shape (m, Z)
        Inner-contact loads Q_j [N].
    contact_angles : ndarray, shape (m, Z)
        Inner contact angles alpha_j [rad].
    deflections : ndarray, shape (m, Z)
        Total contact deformation delta_j (negative = gap) [m].
    iterations : ndarray, shape (m,)
        Newton iterations [-].
    residual : ndarray, shape (m,)
        Relative force residual at the solution [-].
    applied : ndarray, shape (5,)
        Applied ``(Fx, Fy, Fz, Mx, My)`` [N, N m].
    free : ndarray of bool, shape (5,)
        Which DOFs were solved (the others were held at 0).
    geometry : QSGeometry
        Derived geometry used.
    method : Method
        Load-distribution method.
    misalignment : Misalignment
        Ring misalignments.
    ball_errors : ndarray, shape (Z,)
        Ball-distribution errors e_j [rad].
    speed : SpeedEffects
        Inertia-load options.
    bearing_id : str
        Catalogue id.
    """

    cage_angle: NDArray[np.float64]
    shaft_angle: NDArray[np.float64]
    displacement: NDArray[np.float64]
    stiffness_matrix: NDArray[np.float64]
    reaction: NDArray[np.float64]
    ball_angles: NDArray[np.float64]
    ball_loads: NDArray[np.float64]
    contact_angles: NDArray[np.float64]
    deflections: NDArray[np.float64]
    iterations: NDArray[np.int64]
    residual: NDArray[np.float64]
    applied: NDArray[np.float64]
    free: NDArray[np.bool_]
    geometry: QSGeometry
    method: Method
    misalignment: Misalignment
    ball_errors: NDArray[np.float64]
    speed: SpeedEffects = field(default_factory=SpeedEffects)
    bearing_id: str = ""

    @property
    def delta_r(self) -> NDArray[np.float64]:
        """Radial displacement ``|(x, y)|`` [m]."""
        return np.hypot(self.displacement[:, 0], self.displacement[:, 1])

    @property
    def delta_max(self) -> NDArray[np.float64]:
        """``delta_r - P_d/2``: radial deflection on the displacement line [m] (SPEC §0.4)."""
        return self.delta_r - 0.5 * self.geometry.clearance

    @property
    def psi_l(self) -> NDArray[np.float64]:
        """Load-zone half angle ``arccos(P_d / (2 delta_r))`` [rad] (SPEC §0.4)."""
        dr = self.delta_r
        with np.errstate(divide="ignore", invalid="ignore"):
            ratio = np.where(dr > 0, 0.5 * self.geometry.clearance / np.where(dr > 0, dr, 1.0), 0)
        return np.arccos(np.clip(ratio, -1.0, 1.0))

    def equilibrium(self, index: int = 0) -> dict[str, object]:
        """Plain-dict summary of the state at cage angle ``index`` (SI)."""
        u = self.displacement[index]
        return {
            "cage_angle_rad": float(self.cage_angle[index]),
            "displacement": dict(
                zip(("x_m", "y_m", "z_m", "theta_x_rad", "theta_y_rad"), map(float, u), strict=True)
            ),
            "stiffness_matrix": self.stiffness_matrix[index],
            "reaction": dict(
                zip(
                    ("fx_n", "fy_n", "fz_n", "mx_nm", "my_nm"),
                    map(float, self.reaction[index]),
                    strict=True,
                )
            ),
            "ball_angles_rad": self.ball_angles[index],
            "ball_loads_n": self.ball_loads[index],
            "contact_angles_rad": self.contact_angles[index],
            "deflections_m": self.deflections[index],
            "iterations": int(self.iterations[index]),
            "residual_rel": float(self.residual[index]),
        }


def load_vector(
    fx: float = 0.0, fy: float = 0.0, fz: float = 0.0, mx: float = 0.0, my: float = 0.0
) -> NDArray[np.float64]:
    """Validated applied load ``(Fx, Fy, Fz [N], Mx, My [N m])`` on the inner ring."""
    return np.array(
        [
            check_range("fx_n", fx, unit="N"),
            check_range("fy_n", fy, unit="N"),
            check_range("fz_n", fz, unit="N"),
            check_range("mx_nm", mx, unit="N m"),
            check_range("my_nm", my, unit="N m"),
        ]
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
) -> QuasiStaticSolution:
    """Jones–Harris 5-DOF quasi-static equilibrium and tangent stiffness at each cage angle
    (seed QS5 eqs. (1)–(7) completed per SPEC §5; Harris & Kotzalas 2007 vol. 2 ch. 3).

    Parameters
    ----------
    bearing : BallBearing
        Geometry and material.
    cage_angles : float or array_like
        Cage angle(s) [rad]; solved in order, each started from the previous solution.
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
        Relative force-residual tolerance [-].
    max_iterations : int
        Newton iterations per cage angle [-].
    """
    geom = qs_geometry(bearing, clearance, max_contact_angle, stiffness)
    mis = misalignment if misalignment is not None else Misalignment()
    if not isinstance(mis, Misalignment):
        raise ConfigError("misalignment must be a Misalignment")
    check_misalignment(geom, mis)
    err = check_ball_errors(geom, ball_errors)
    spd = speed if speed is not None else SpeedEffects()
    if spd.active and stiffness is not None:
        raise ConfigError(
            "stiffness override is not available with inertia loads (it needs the "
            "separate inner and outer Hertz constants)"
        )
    F = load_vector(fx, fy, fz, mx, my)
    psi0 = check_range("first_ball_angle_rad", first_ball_angle, unit="rad")
    cage = np.atleast_1d(np.asarray(cage_angles, dtype=float)).ravel()
    if cage.size == 0 or not np.all(np.isfinite(cage)):
        raise ConfigError("cage_angle must be finite values; valid range (-inf, inf) rad")
    held = mis.any if tilt_free is None else not tilt_free
    if held and (F[3] != 0.0 or F[4] != 0.0):
        raise ConfigError(
            f"mx_nm = {F[3]:.6g}, my_nm = {F[4]:.6g} N m cannot be applied while the ring tilts "
            "are held by a misalignment (the moments are then reactions); valid: 0 N m, or no "
            "misalignment"
        )
    free = np.array([True, True, True, not held, not held])
    if not np.any(F) and geom.clearance > 0 and not mis.any and not spd.active:
        raise ConfigError(
            "load = 0 with positive clearance and no misalignment: the ring position is "
            "undetermined; apply a force or moment (valid: |F| > 0)"
        )
    fc, mg0, gam = _inertia(geom, spd)
    p = _params(
        geom,
        F,
        free,
        first_ball_angle=psi0,
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
    psi_first = cage[0] + psi0 + 2.0 * np.pi * np.arange(Z) / Z + err
    ux, uy = _radial_start(geom, psi_first, F)
    u0 = np.array([ux, uy, _axial_start(geom, F[2]), 0.0, 0.0])
    co = p[P_CO]
    V0 = np.zeros((Z, 2))
    V0[:, 1] = co + (fc / geom.k_outer) ** (2.0 / 3.0) if spd.centrifugal else co
    m = cage.size
    out_ring = np.zeros((m, 2, 5))
    out_H = np.zeros((m, 5, 5))
    out_balls = np.zeros((m, 3, Z))
    out_info = np.zeros((m, 4))
    done = _sweep(cage, err, p, u0, V0, out_ring, out_H, out_balls, out_info)
    if done < m:
        status = int(out_info[done, I_STATUS])
        where = f"at cage angle {cage[done]:.6g} rad"
        if status == 2:
            raise SolverError(
                f"no equilibrium {where}: the radial displacement exceeds the groove-centre "
                "distance (load beyond what the geometry allows); reduce the load"
            )
        raise SolverError(
            f"no equilibrium found {where} after {int(out_info[done, I_ITER])} Newton iterations "
            f"(relative residual {out_info[done, I_RES]:.3g}); check the load and clearance"
        )
    out_Q, out_a = out_balls[:, B_Q], out_balls[:, B_ALPHA]
    amax = np.max(np.abs(out_a) * (out_Q > 0))
    if amax > geom.max_contact_angle:
        i, j = np.unravel_index(np.argmax(np.abs(out_a) * (out_Q > 0)), out_a.shape)
        raise SolverError(
            f"no equilibrium the geometry allows: ball {j + 1} needs contact angle "
            f"{math.degrees(amax):.1f} deg at cage angle {cage[i]:.6g} rad, beyond the groove "
            f"limit {math.degrees(geom.max_contact_angle):.1f} deg (max_contact_angle); reduce "
            "the load"
        )
    psi = cage[:, None] + psi0 + 2.0 * np.pi * np.arange(Z)[None, :] / Z + err[None, :]
    return QuasiStaticSolution(
        cage_angle=cage,
        shaft_angle=cage / geom.cage_ratio,
        displacement=np.ascontiguousarray(out_ring[:, R_U]),
        stiffness_matrix=out_H,
        reaction=np.ascontiguousarray(out_ring[:, R_F]),
        ball_angles=psi,
        ball_loads=np.ascontiguousarray(out_Q),
        contact_angles=np.ascontiguousarray(out_a),
        deflections=np.ascontiguousarray(out_balls[:, B_DELTA]),
        iterations=out_info[:, I_ITER].astype(np.int64),
        residual=out_info[:, I_RES].copy(),
        applied=F,
        free=free,
        geometry=geom,
        method=Method.JONES,
        misalignment=mis,
        ball_errors=err,
        speed=spd,
        bearing_id=bearing.id,
    )


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
    """Equilibrium at a single cage angle [rad]; keywords as :func:`run_quasi_static`."""
    return run_quasi_static(bearing, cage_angle, fx, fy, fz, mx, my, **kwargs)
