"""Single local raceway defect: geometry, kinematics and the contact-deformation retention factor.

Seed VSM (Guo et al., J. Vib. Eng. 2025) §1, eqs. (1)–(3), (11)–(15). A rectangular defect of
width ``b`` along the raceway and depth ``h_d`` sits on the outer race (fixed, left edge at
azimuth ``beta_0``) or on the inner race (rotating with the shaft, left edge at
``theta_s = 2 pi f_s t + beta_0``, eq. (13)). A ball over the defect drops by at most ``h_min``
(eqs. (1)–(2)); the defect spans the central angle ``Delta_beta`` of its raceway (eq. (3)).

Azimuths follow the project convention: measured from the +y axis towards +x (seed fig. 1); the
ball ``i`` (1-based) sits at ``alpha_mi = 2 pi f_m t + (i - 1) 2 pi / Z + alpha_0`` (eq. (12)).
"""

from __future__ import annotations

import enum
import math
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike, NDArray

from ...errors import ConfigError, check_positive, check_range
from ...geometry import BallBearing, Bearing

#: CWRU seeded faults: 0.007 in wide (CWRU "Fault Specifications"), EDM depth 0.011 in
#: (/work/shared/data/cwru/SOURCES.md)
CWRU_WIDTH_007_M = 0.007 * 25.4e-3
CWRU_DEPTH_M = 0.011 * 25.4e-3


class FaultLocation(enum.Enum):
    """Where the single local defect is."""

    NONE = "none"
    OUTER = "outer"
    INNER = "inner"


#: integer codes used inside the compiled kernels
FAULT_CODE = {FaultLocation.NONE: 0, FaultLocation.OUTER: 1, FaultLocation.INNER: 2}


@dataclass(frozen=True)
class Defect:
    """A rectangular raceway defect (seed VSM fig. 2).

    Parameters
    ----------
    location : FaultLocation
        ``OUTER`` (fixed) or ``INNER`` (rotating with the shaft); ``NONE`` = healthy bearing.
    width : float
        Width ``b`` along the raceway [m]; the ball must span it (``0 < b < d``).
    depth : float
        Depth ``h_d`` [m], > 0.
    angle : float
        Azimuth of the defect's left (lower-azimuth) edge at ``t = 0``, ``beta_0`` [rad]
        (seed table 1: 10 deg).
    """

    location: FaultLocation = FaultLocation.NONE
    width: float = CWRU_WIDTH_007_M
    depth: float = CWRU_DEPTH_M
    angle: float = math.radians(10.0)

    def __post_init__(self) -> None:
        try:
            object.__setattr__(self, "location", FaultLocation(self.location))
        except ValueError:
            raise ConfigError(
                f"fault = {self.location!r} is invalid; valid: none, outer, inner"
            ) from None
        object.__setattr__(self, "width", check_positive("defect_width_m", self.width, "m"))
        object.__setattr__(self, "depth", check_positive("defect_depth_m", self.depth, "m"))
        object.__setattr__(self, "angle", check_range("defect_angle_rad", self.angle, unit="rad"))


@dataclass(frozen=True)
class DefectGeometry:
    """Geometric quantities of a defect on a given bearing (seed VSM eqs. (1)–(3)).

    Attributes
    ----------
    location : FaultLocation
        Raceway.
    race_radius : float
        Raceway radius ``r_i`` or ``r_o`` [m].
    h_s : float
        Drop of a ball resting on both edges without touching the bottom, eq. (2) [m].
    h_min : float
        Maximum drop ``min(h_d, h_s)``, eq. (1) [m].
    delta_beta : float
        Central angle spanned by the defect on its raceway, eq. (3) [rad].
    angle : float
        Left-edge azimuth at ``t = 0``, ``beta_0`` [rad].
    """

    location: FaultLocation
    race_radius: float
    h_s: float
    h_min: float
    delta_beta: float
    angle: float


def defect_geometry(bearing: Bearing, defect: Defect) -> DefectGeometry:
    """Maximum ball drop and angular extent of ``defect`` on ``bearing``.

    Seed VSM eqs. (1)–(3)::

        h_s = [r - sqrt(r^2 - (b/2)^2)] +/- [r_race - sqrt(r_race^2 - (b/2)^2)]
        h_min = min(h_d, h_s)
        Delta_beta = 2 arcsin(b / (2 r_race))

    (``+`` and ``r_i`` for the inner race, whose convex surface falls away under the chord;
    ``-`` and ``r_o`` for the concave outer race.) ``r = d/2`` is the ball radius; the raceway
    radii are ``(D -/+ d)/2`` (seed table 1: 15.53 and 23.47 mm).

    Parameters
    ----------
    bearing : BallBearing
        Geometry.
    defect : Defect
        Defect; ``location`` must not be ``NONE``.

    Raises
    ------
    ConfigError
        If the ball cannot span the defect (``b >= d``): the seed's geometry (a ball resting on
        both edges, fig. 2) no longer applies.
    """
    if not isinstance(bearing, BallBearing):
        raise ConfigError(
            f"bearing = {bearing.id!r} is not a ball bearing; the VSM defect model needs balls"
        )
    if defect.location is FaultLocation.NONE:
        raise ConfigError("defect_geometry: fault = 'none' has no defect geometry")
    d = bearing.element_diameter
    r = 0.5 * d
    b = defect.width
    if b >= d:
        raise ConfigError(
            f"defect_width_m = {b:.6g} m is wider than the ball can span; valid range "
            f"(0, {d:.6g}) m (ball diameter d)"
        )
    half = 0.5 * b
    ball_chord = r - math.sqrt(r * r - half * half)
    if defect.location is FaultLocation.INNER:
        rr = bearing.inner_raceway_radius
        h_s = ball_chord + (rr - math.sqrt(rr * rr - half * half))  # seed VSM eq. (2), inner
    else:
        rr = bearing.outer_raceway_radius
        h_s = ball_chord - (rr - math.sqrt(rr * rr - half * half))  # seed VSM eq. (2), outer
    h_min = min(defect.depth, h_s)  # seed VSM eq. (1)
    dbeta = 2.0 * math.asin(b / (2.0 * rr))  # seed VSM eq. (3)
    return DefectGeometry(defect.location, rr, h_s, h_min, dbeta, defect.angle)


def retention_factor(delta: ArrayLike, h_min: float) -> NDArray[np.float64]:
    """Contact-deformation retention factor ``gamma`` (seed VSM eq. (11)) [-].

    ``gamma = (1 - h_min/delta)^1.5`` when ``h_min < delta``, else 0. Note that
    ``gamma K delta^1.5 = K (delta - h_min)^1.5``: the retained load equals the Hertz load of
    the deformation left after the drop ``h_min``.

    Parameters
    ----------
    delta : array_like
        Contact deformation the ball would have without the defect [m].
    h_min : float
        Maximum drop into the defect, eq. (1) [m].
    """
    dl = np.asarray(delta, dtype=float)
    h = check_range("h_min_m", h_min, 0.0, unit="m")
    with np.errstate(divide="ignore", invalid="ignore"):
        g = np.where(dl > h, (1.0 - h / np.where(dl > 0, dl, 1.0)) ** 1.5, 0.0)
    return g


def ball_azimuths(
    n_elements: int, cage_angle: ArrayLike, first_ball_angle: float = 0.0
) -> NDArray[np.float64]:
    """Ball azimuths ``alpha_mi = theta_m + (i-1) 2 pi / Z + alpha_0`` (seed VSM eq. (12)) [rad].

    Parameters
    ----------
    n_elements : int
        Number of balls Z [-].
    cage_angle : array_like
        Cage angle ``theta_m = 2 pi f_m t`` [rad].
    first_ball_angle : float
        ``alpha_0`` [rad].
    """
    cage = np.atleast_1d(np.asarray(cage_angle, dtype=float))
    step = 2.0 * np.pi / n_elements
    return cage[:, None] + first_ball_angle + step * np.arange(n_elements)[None, :]


def in_defect(psi: ArrayLike, edge: ArrayLike, delta_beta: float) -> NDArray[np.bool_]:
    """Whether a ball at azimuth ``psi`` is over a defect whose left edge is at ``edge``:
    ``mod(psi - edge, 2 pi) < Delta_beta`` (seed VSM eq. (15)) [-].

    Parameters
    ----------
    psi : array_like
        Ball azimuth(s) [rad].
    edge : array_like
        Defect left edge: ``beta_0`` (outer) or ``theta_s`` (inner, eq. (13)) [rad].
    delta_beta : float
        Angular extent, eq. (3) [rad].
    """
    return np.mod(np.asarray(psi, float) - np.asarray(edge, float), 2.0 * np.pi) < delta_beta
