"""Inputs of the quasi-static 5-DOF family, validated, and the derived geometry shared by the
Jones model (:mod:`.jones`) and the ISO/TS 16281 method (:mod:`.iso16281`).

Seed QS5 (Xu, Yang, Wang, Ma, J. Northeastern Univ. 2023, 44(3)) eqs. (1)–(5): ball azimuths with
distribution errors, ring misalignments, groove-centre geometry. Conventions as in :mod:`.jones`
(SI; ball azimuth ``psi`` from +y towards +x; ring DOFs ``(x, y, z, theta_x, theta_y)``).
"""

from __future__ import annotations

import enum
import math
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike, NDArray

from ..contact.hertz import ball_contact, ball_stiffness
from ..errors import ConfigError, check_range
from ..geometry import (
    BallBearing,
    Bearing,
    Race,
    characteristic_frequencies,
    check_clearance,
    contact_race,
)
from ..load_distribution import check_angles

__all__ = [
    "DEFAULT_GROOVE_DEPTH_RATIO",
    "Method",
    "Misalignment",
    "QSGeometry",
    "SpeedEffects",
    "check_ball_errors",
    "check_misalignment",
    "load_vector",
    "max_contact_angle_default",
    "max_tilt",
    "qs_geometry",
]

#: Groove depth / ball diameter assumed for the default largest contact angle. Our assumption,
#: not a literature value: the catalogue gives no shoulder heights, and deep-groove raceways are
#: about a quarter of the ball diameter deep. Override with ``max_contact_angle``.
DEFAULT_GROOVE_DEPTH_RATIO = 0.25


class Method(enum.Enum):
    """Load-distribution method."""

    #: Jones/Harris groove-centre model with exact Hertz ``K`` (:mod:`.jones`)
    JONES = "jones"
    #: ISO/TS 16281 ball-bearing method (:mod:`.iso16281`)
    ISO16281 = "iso16281"


@dataclass(frozen=True)
class Misalignment:
    """Ring misalignments (seed QS5 fig. 2, eqs. (2)–(3)).

    Parameters
    ----------
    outer_tilt : float
        Outer-ring tilt magnitude theta_to [rad], >= 0.
    outer_azimuth : float
        Azimuth of the outer-ring tilt axis phi_to, from +y towards +x [rad], in
        [-2 pi, 2 pi] (fixed).
    inner_tilt : float
        Inner-ring tilt magnitude theta_ti [rad], >= 0.
    inner_azimuth : float
        Azimuth of the inner-ring tilt axis at shaft angle 0, phi_ti [rad], in [-2 pi, 2 pi]; it
        rotates with the shaft.
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
                    -2.0 * math.pi,
                    2.0 * math.pi,
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
    f_i, f_o : float
        Inner and outer groove conformities ``R/d`` [-].
    cage_ratio : float
        Cage speed / shaft speed (FTF order) [-].
    max_contact_angle : float
        Largest admissible contact angle [rad].
    density : float
        Ball material density [kg/m^3] (inertia loads).
    youngs_modulus, poisson_ratio : float
        The material's E [Pa] and nu [-] that the Hertz constants were computed with (a saved
        result records them: `stiffness --E-pa` left no trace but in ``k``; NaN in files
        written before the twenty-first session).
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
    youngs_modulus: float = math.nan
    poisson_ratio: float = math.nan


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
        Diametral clearance P_d [m] overriding the bearing's (negative = preload); within
        :func:`bearingsim.geometry.clearance_range` (ISO 5753-1) and below ``2 A0``.
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
    # ISO 5753-1 bounds (geometry.clearance_range), and below 2 A0 (free contact angle 90 deg)
    pd = check_clearance(bearing, pd, "clearance_m", hi=2.0 * a0)
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
        youngs_modulus=bearing.material.youngs_modulus,
        poisson_ratio=bearing.material.poisson_ratio,
    )


def max_tilt(geom: QSGeometry, race: Race | str, other: float = 0.0) -> float:
    """Largest misalignment tilt [rad] of ring ``race`` for which the unloaded contact angle
    stays below ``geom.max_contact_angle``.

    Parameters
    ----------
    geom : QSGeometry
        Derived geometry.
    race : Race or {"inner", "outer"}
        Tilted ring.
    other : float
        Axial offset already taken by the other ring's tilt, ``r_p * tilt`` [m].
    """
    race = contact_race(race, "race")
    budget = geom.y0 * math.tan(geom.max_contact_angle) - other
    r = geom.r_pi if race is Race.INNER else geom.r_po
    return max(budget, 0.0) / r


def check_misalignment(geom: QSGeometry, mis: Misalignment) -> None:
    """Raise a one-line :class:`ConfigError` when a tilt exceeds what clearance and groove allow:
    the misalignment alone must not push any ball past ``max_contact_angle``."""
    off_o = geom.r_po * mis.outer_tilt
    tmax_o = max_tilt(geom, Race.OUTER)
    if mis.outer_tilt > tmax_o:
        raise ConfigError(
            f"outer_tilt_rad = {mis.outer_tilt:.6g} rad is beyond what the clearance and groove "
            f"geometry allow (contact angle would exceed {math.degrees(geom.max_contact_angle):.1f}"
            f" deg); valid range [0, {tmax_o:.6g}] rad"
        )
    tmax_i = max_tilt(geom, Race.INNER, other=off_o)
    if mis.inner_tilt > tmax_i:
        raise ConfigError(
            f"inner_tilt_rad = {mis.inner_tilt:.6g} rad is beyond what the clearance and groove "
            f"geometry allow together with outer_tilt_rad = {mis.outer_tilt:.6g} rad (contact "
            f"angle would exceed {math.degrees(geom.max_contact_angle):.1f} deg); valid range "
            f"[0, {tmax_i:.6g}] rad"
        )


def check_ball_errors(geom: QSGeometry, errors: ArrayLike | None) -> NDArray[np.float64]:
    """Validate the per-ball angular offsets e_j [rad] (seed QS5 eq. (1)): exactly Z finite
    values within one ball pitch ``2 pi / Z`` either way, and neighbouring balls may neither
    overlap nor pass each other (centre spacing on the pitch circle at least
    ``2 arcsin(d/d_m)``)."""
    Z = geom.n_balls
    if errors is None:
        return np.zeros(Z)
    e = np.atleast_1d(np.asarray(errors, dtype=float)).ravel()
    if e.size != Z:
        raise ConfigError(
            f"ball_errors_rad has {e.size} values; valid: exactly n_elements = {Z} values"
        )
    pitch = 2.0 * math.pi / Z
    bad = np.flatnonzero(~(np.abs(e) <= pitch))
    if bad.size:
        # a ball moved by a whole pitch is in its neighbour's pocket
        j = int(bad[0])
        check_range(f"ball_errors_rad[{j}]", float(e[j]), -pitch, pitch, unit="rad")
    gap_min = 2.0 * math.asin(geom.d / geom.dm)
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


def load_vector(
    fx: float = 0.0, fy: float = 0.0, fz: float = 0.0, mx: float = 0.0, my: float = 0.0
) -> NDArray[np.float64]:
    """Validated applied load on the inner ring as one vector ``(Fx, Fy, Fz, Mx, My)``.

    Parameters
    ----------
    fx, fy, fz : float
        Forces along x, y (radial) and z (axial) [N].
    mx, my : float
        Moments about x and y [N m].
    """
    return np.array(
        [
            check_range("fx_n", fx, unit="N"),
            check_range("fy_n", fy, unit="N"),
            check_range("fz_n", fz, unit="N"),
            check_range("mx_nm", mx, unit="N m"),
            check_range("my_nm", my, unit="N m"),
        ]
    )


def _ball_azimuths(
    cage: NDArray[np.float64], psi0: float, errors: NDArray[np.float64]
) -> NDArray[np.float64]:
    """Ball azimuths ``psi_j = cage + psi0 + 2 pi j/Z + e_j`` (seed QS5 eq. (1)) [rad], shape
    ``cage.shape + (Z,)``."""
    c = np.asarray(cage, dtype=float)[..., None]
    Z = errors.size
    return c + psi0 + 2.0 * np.pi * np.arange(Z) / Z + errors


@dataclass(frozen=True)
class _Case:
    """Validated inputs of one quasi-static run (both methods)."""

    misalignment: Misalignment
    ball_errors: NDArray[np.float64]
    applied: NDArray[np.float64]
    first_ball_angle: float
    cage: NDArray[np.float64]
    free: NDArray[np.bool_]
    #: ``cage_angles`` was one value: the stiffness comes back as one 5x5 matrix
    single: bool


#: smallest ball deflection, relative to the diametral clearance, that fixes the ring's position
#: [-] (double precision resolves 2.2e-16; four more digits are kept for the Newton iteration)
RESOLVED_DEFLECTION_REL = 1e-12


def _validate_case(
    geom: QSGeometry,
    cage_angles: ArrayLike,
    loads: tuple[float, float, float, float, float],
    misalignment: Misalignment | None,
    ball_errors: ArrayLike | None,
    first_ball_angle: float,
    tilt_free: bool | None,
    inertia: bool,
) -> _Case:
    """Validate the inputs shared by :func:`~.jones.run_quasi_static` and
    :func:`~.iso16281.run_iso16281`, each error one line naming the field and the valid range."""
    mis = misalignment if misalignment is not None else Misalignment()
    if not isinstance(mis, Misalignment):
        raise ConfigError("misalignment must be a Misalignment")
    check_misalignment(geom, mis)
    err = check_ball_errors(geom, ball_errors)
    F = load_vector(*loads)
    psi0 = check_range(
        "first_ball_angle_rad", first_ball_angle, -2 * math.pi, 2 * math.pi, unit="rad"
    )
    cage = check_angles("cage_angle_rad", cage_angles)
    if cage.size == 0:
        raise ConfigError("cage_angle_rad is empty; valid: one or more angles [rad]")
    held = mis.any if tilt_free is None else not tilt_free
    if held and (F[3] != 0.0 or F[4] != 0.0):
        raise ConfigError(
            f"mx_nm = {F[3]:.6g}, my_nm = {F[4]:.6g} N m cannot be applied while the ring tilts "
            "are held by a misalignment (the moments are then reactions); valid: 0 N m, or no "
            "misalignment"
        )
    if not np.any(F) and geom.clearance > 0 and not mis.any and not inertia:
        raise ConfigError(
            "load = 0 with positive clearance and no misalignment: the ring position is "
            "undetermined; apply a force or moment (valid: |F| > 0)"
        )
    if np.any(F) and geom.clearance > 0 and not mis.any and not inertia:
        # the ring sits at half the clearance plus the balls' Hertz deflection; a load whose
        # deflection (F/K)^(2/3) on one ball is below RESOLVED_DEFLECTION_REL of the clearance is
        # lost beside it in double precision (1e-300 N: zero stiffness, NaN fluctuation)
        f = max(math.hypot(F[0], F[1]), abs(F[2]), math.hypot(F[3], F[4]) / (0.5 * geom.dm))
        f_min = geom.k * (RESOLVED_DEFLECTION_REL * geom.clearance) ** 1.5
        if f < f_min:
            raise ConfigError(
                f"load = {f:.6g} N (largest force, or moment / pitch radius) with positive "
                f"clearance: its Hertz deflection is lost beside the clearance {geom.clearance:.6g}"
                f" m, so the ring position is undetermined; apply a larger force or moment "
                f"(valid: |F| >= {f_min:.3g} N)"
            )
    if not np.any(F) and geom.clearance == 0 and not mis.any and not inertia:
        # every ball just touches both grooves: the ring is held (any displacement compresses
        # some ball), but Q = K delta^1.5 has no tangent stiffness at delta = 0, so the
        # stiffness matrix would be all zero (Hertz: dQ/d delta = 1.5 K delta^0.5)
        raise ConfigError(
            "load = 0 with zero clearance and no misalignment: every ball just touches, and "
            "Hertz contacts have no stiffness at zero deflection (the 5x5 matrix would be all "
            "zero); apply a force or moment (valid: |F| > 0) or a preload (clearance_m < 0)"
        )
    free = np.array([True, True, True, not held, not held])
    return _Case(mis, err, F, psi0, cage, free, np.ndim(cage_angles) == 0)
