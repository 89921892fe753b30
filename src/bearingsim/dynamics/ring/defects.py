"""Single local raceway defect in the ring models: kinematics and the retention factor.

The defect itself (:class:`bearingsim.geometry.Defect`) and its geometry (seed VSM eqs. (1)–(3),
:func:`bearingsim.geometry.defect_geometry`) are shared with the other model families.

Seed VSM (Guo et al., J. Vib. Eng. 2025) §1, eqs. (1)–(3), (11)–(15). A rectangular defect of
width ``b`` along the raceway and depth ``h_d`` sits on the outer race (fixed, left edge at
azimuth ``beta_0``) or on the inner race (rotating with the shaft, left edge at
``theta_s = 2 pi f_s t + beta_0``, eq. (13)). A ball over the defect drops by at most ``h_min``
(eqs. (1)–(2)); the defect spans the central angle ``Delta_beta`` of its raceway (eq. (3)).

Azimuths follow the project convention: measured from the +y axis towards +x (seed fig. 1); the
ball ``i`` (1-based) sits at ``alpha_mi = 2 pi f_m t + (i - 1) 2 pi / Z + alpha_0`` (eq. (12)).
"""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike, NDArray

from ...errors import check_range
from ...geometry import Race

__all__ = [
    "ball_azimuths",
    "FAULT_CODE",
    "in_defect",
    "retention_factor",
]

#: integer codes of the defect's raceway inside the compiled kernels (0 = no defect)
FAULT_CODE = {None: 0, Race.OUTER: 1, Race.INNER: 2, Race.BALL: 3}


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
