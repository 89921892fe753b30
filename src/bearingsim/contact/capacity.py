"""Static capacity of a bearing (ISO 76) and the load check every model applies before it runs.

ISO 76:2006 defines the basic static radial load rating ``C_0`` as the radial load that produces,
at the centre of the most heavily loaded element/raceway contact, a contact stress of 4200 MPa
(ball bearings other than self-aligning) or 4000 MPa (roller bearings): the stress at which the
permanent deformation of element and raceway reaches about 1e-4 of the element diameter. We
compute ``C_0`` from the bearing's own Hertz contact (:func:`static_capacity`; its actual groove
conformities enter, not the ``f_0`` table of the standard), and compare with it the static
equivalent load ``P_0`` of ISO 76 (:func:`equivalent_static_load`).

The load check (:func:`check_load`, :func:`check_element_load`):

* ``P_0 <= C_0``: silent;
* ``C_0 < P_0 <= STATIC_LIMIT_FACTOR C_0``: a :class:`StaticCapacityWarning` (permanent
  deformation expected; the elastic models are outside their range);
* ``P_0 > STATIC_LIMIT_FACTOR C_0``: refused with a one-line
  :class:`~bearingsim.errors.ConfigError`, unless ``allow_overload=True`` (the command-line flag
  ``--allow-overload``), which turns the refusal into the warning.

``STATIC_LIMIT_FACTOR = 2`` is the static safety factor ``s_0 = C_0/P_0 = 0.5``, the lowest
guideline value for rotating ball bearings where quiet running is unimportant (SKF rolling
bearings catalogue, "Guideline values for the static safety factor s0"; roller bearings: 1).

May import: :mod:`bearingsim.errors`, :mod:`~bearingsim.geometry`, :mod:`~bearingsim.materials`
and :mod:`.hertz`.
"""

from __future__ import annotations

import functools
import math
import warnings
from dataclasses import dataclass

import numpy as np
from scipy.optimize import brentq

from ..errors import ConfigError, check_range
from ..geometry import BallBearing, Bearing, Race, RollerBearing
from .hertz import ball_contact, roller_contact

__all__ = [
    "check_element_load",
    "check_load",
    "equivalent_static_load",
    "ISO76_Y0_ANGULAR",
    "static_capacity",
    "STATIC_LIMIT_FACTOR",
    "STATIC_STRESS_BALL",
    "STATIC_STRESS_ROLLER",
    "StaticCapacity",
    "StaticCapacityWarning",
    "STRIBECK_STATIC",
]

#: ISO 76 static-capacity contact stress at the most loaded contact [Pa]: 4200 MPa for ball
#: bearings (other than self-aligning), 4000 MPa for roller bearings
STATIC_STRESS_BALL = 4200e6
STATIC_STRESS_ROLLER = 4000e6
#: Stribeck constant of static ratings, ``Q_max = 5 F_r / (Z cos alpha)`` (accounts for a normal
#: clearance; Harris & Kotzalas 2007, vol. 1, §7.2)
STRIBECK_STATIC = 5.0
#: loads above this multiple of the static capacity are refused (static safety factor
#: ``s_0 = 0.5``, module docstring)
STATIC_LIMIT_FACTOR = 2.0
#: ISO 76:2006 table 1, single-row angular-contact groove ball bearings: ``Y_0`` vs the nominal
#: contact angle [deg] (``X_0 = 0.5``); radial-contact groove ball bearings have ``X_0 = 0.6``,
#: ``Y_0 = 0.5``
ISO76_Y0_ANGULAR = np.array(
    [(5.0, 0.52), (10.0, 0.50), (15.0, 0.46), (20.0, 0.42), (25.0, 0.38), (30.0, 0.33),
     (35.0, 0.29), (40.0, 0.26), (45.0, 0.22)]
)  # fmt: skip


class StaticCapacityWarning(UserWarning):
    """The load exceeds the static capacity ``C_0`` (ISO 76): permanent deformation expected."""


@dataclass(frozen=True)
class StaticCapacity:
    """Static capacity of a bearing from its own Hertz contact (ISO 76 stress criterion).

    Attributes
    ----------
    c0 : float
        Radial load [N] at which the most loaded inner contact reaches ``stress_limit`` with
        ``Q_max = 5 F_r/(Z cos alpha)``.
    stress_limit : float
        ISO 76 contact-stress limit [Pa] (4200 MPa balls, 4000 MPa rollers).
    element_load : float
        Element load ``Q_0`` [N] that reaches ``stress_limit`` on the inner raceway.
    """

    c0: float
    stress_limit: float
    element_load: float = math.nan


@functools.lru_cache(maxsize=64)
def static_capacity(bearing: Bearing) -> StaticCapacity:
    """Static capacity ``C_0`` [N]: the radial load whose most loaded inner contact (Stribeck
    ``Q_max = 5 F_r / (Z cos alpha)``) has the ISO 76 limit pressure (4200 MPa balls,
    4000 MPa rollers) by our Hertz solution (not the ISO 76 ``f_0`` table: the actual groove
    conformities enter). Cached per bearing (a frozen dataclass)."""
    ca = math.cos(bearing.contact_angle)
    Z = bearing.n_elements
    if isinstance(bearing, BallBearing):
        lim = STATIC_STRESS_BALL
        # p_max ∝ Q^(1/3) for a point contact: exact inversion
        p1 = float(ball_contact(bearing, 1.0, Race.INNER).p_max)
        q = (lim / p1) ** 3
    elif isinstance(bearing, RollerBearing):
        lim = STATIC_STRESS_ROLLER
        p1 = float(roller_contact(bearing, 1.0, Race.INNER).p_max)
        q = (lim / p1) ** 2  # p_max ∝ Q^(1/2) for a line contact
        q = brentq(
            lambda x: float(roller_contact(bearing, x, Race.INNER).p_max) - lim, 0.5 * q, 2.0 * q
        )
    else:
        raise ConfigError(f"bearing = {bearing!r} is not a BallBearing or RollerBearing")
    return StaticCapacity(q * Z * ca / STRIBECK_STATIC, lim, q)


def _iso76_factors(bearing: Bearing) -> tuple[float, float] | None:
    """``(X_0, Y_0)`` of ISO 76:2006 §6.1 for ``bearing``; ``None`` for a radial roller bearing
    with ``alpha = 0`` (``P_0 = F_r``)."""
    alpha = bearing.contact_angle
    if isinstance(bearing, BallBearing):
        if alpha == 0.0:
            return 0.6, 0.5
        tab = ISO76_Y0_ANGULAR
        return 0.5, float(np.interp(math.degrees(alpha), tab[:, 0], tab[:, 1]))
    if alpha == 0.0:
        return None
    return 0.5, 0.22 / math.tan(alpha)


def equivalent_static_load(bearing: Bearing, radial_load: float, axial_load: float = 0.0) -> float:
    """Static equivalent radial load ``P_0`` [N] (ISO 76:2006 §6.1):
    ``P_0 = max(F_r, X_0 F_r + Y_0 F_a)``. Radial-contact ball bearings: ``X_0 = 0.6``,
    ``Y_0 = 0.5``; angular-contact ball bearings: ``X_0 = 0.5``, ``Y_0`` from
    :data:`ISO76_Y0_ANGULAR` (interpolated in the contact angle); radial roller bearings:
    ``X_0 = 0.5``, ``Y_0 = 0.22 cot(alpha)``, and ``P_0 = F_r`` for ``alpha = 0`` (a
    cylindrical roller bearing carries no axial load in this model).

    Parameters
    ----------
    bearing : BallBearing or RollerBearing
        Geometry (its nominal contact angle selects the factors).
    radial_load : float
        Radial load F_r [N], >= 0.
    axial_load : float
        Axial load F_a [N]; its magnitude counts.
    """
    fr = check_range("radial_load_n", radial_load, 0.0, unit="N")
    fa = abs(check_range("axial_load_n", axial_load, unit="N"))
    xy = _iso76_factors(bearing)
    return fr if xy is None else max(fr, xy[0] * fr + xy[1] * fa)


#: how a refusal says that it can be overridden
_OVERLOAD_HINT = "; allow_overload=True (--allow-overload) runs it anyway"


def check_load(
    bearing: Bearing,
    radial_load: float,
    allow_overload: bool | None = False,
    axial_load: float = 0.0,
    *,
    name: str = "radial_load_n",
    axial_name: str = "axial_load_n",
) -> StaticCapacity | None:
    """Compare the static equivalent load with the bearing's static capacity (ISO 76): warn
    (:class:`StaticCapacityWarning`) above ``C_0``, refuse (one-line
    :class:`~bearingsim.errors.ConfigError`) above ``STATIC_LIMIT_FACTOR C_0`` unless
    ``allow_overload`` (module docstring). Every model calls it before it runs.

    Parameters
    ----------
    bearing : BallBearing or RollerBearing
        Geometry and material.
    radial_load : float
        Radial load F_r [N], >= 0 (for force components, their resultant).
    allow_overload : bool or None
        ``True`` runs above the limit (with the warning); ``None`` skips the check (for a
        caller that has made it already).
    axial_load : float
        Axial load F_a [N] (ISO 76 static equivalent load, :func:`equivalent_static_load`).
    name, axial_name : str
        The fields named in the messages.

    Returns
    -------
    StaticCapacity or None
        The capacity used (``None`` when skipped or unloaded).
    """
    if allow_overload is None:
        return None
    fr = check_range(name, radial_load, 0.0, unit="N")
    fa = abs(check_range(axial_name, axial_load, unit="N"))
    p0 = equivalent_static_load(bearing, fr, fa)
    if p0 == 0.0:
        return None
    sc = static_capacity(bearing)
    limit = STATIC_LIMIT_FACTOR * sc.c0
    if p0 == fr:
        what, rng = f"{name} = {fr:.6g} N", f"[0, {limit:.6g}] N"
    else:
        x0, y0 = _iso76_factors(bearing)
        what = (
            f"static equivalent load P0 = {x0:g} F_r + {y0:g} F_a = {p0:.6g} N (ISO 76; "
            f"F_r = {name} = {fr:.6g} N, F_a = {axial_name} = {fa:.6g} N)"
        )
        rng = f"P0 in [0, {limit:.6g}] N"
    if p0 > limit and not allow_overload:
        raise ConfigError(
            f"{what} exceeds {STATIC_LIMIT_FACTOR:g} x the static capacity C0 = {sc.c0:.6g} N "
            f"of {bearing.id} (contact stress {sc.stress_limit / 1e6:.0f} MPa, ISO 76); valid "
            f"range {rng}" + _OVERLOAD_HINT
        )
    if p0 > sc.c0:
        warnings.warn(
            f"{what} exceeds the static capacity C0 = {sc.c0:.6g} N of {bearing.id}: the most "
            f"loaded contact exceeds {sc.stress_limit / 1e6:.0f} MPa (ISO 76) and deforms "
            "permanently; the elastic contact model is outside its range",
            StaticCapacityWarning,
            stacklevel=2,
        )
    return sc


def check_element_load(
    bearing: Bearing,
    element_load: float,
    allow_overload: bool | None = False,
    *,
    name: str = "ball_load_n",
) -> StaticCapacity | None:
    """:func:`check_load` for one element: the element load ``Q`` against ``Q_0``, the load
    that reaches the ISO 76 stress on the inner raceway (warn above ``Q_0``, refuse above
    ``STATIC_LIMIT_FACTOR Q_0`` unless ``allow_overload``).

    Parameters
    ----------
    bearing : BallBearing or RollerBearing
        Geometry and material.
    element_load : float
        Element load Q [N], >= 0.
    allow_overload : bool or None
        As :func:`check_load`.
    name : str
        The field named in the messages.
    """
    if allow_overload is None:
        return None
    q = check_range(name, element_load, 0.0, unit="N")
    if q == 0.0:
        return None
    sc = static_capacity(bearing)
    q0 = sc.element_load
    stress = f"{sc.stress_limit / 1e6:.0f} MPa on the inner raceway of {bearing.id}, ISO 76"
    if q > STATIC_LIMIT_FACTOR * q0 and not allow_overload:
        raise ConfigError(
            f"{name} = {q:.6g} N exceeds {STATIC_LIMIT_FACTOR:g} x the element load at the "
            f"static stress limit Q0 = {q0:.6g} N ({stress}); valid range "
            f"[0, {STATIC_LIMIT_FACTOR * q0:.6g}] N" + _OVERLOAD_HINT
        )
    if q > q0:
        warnings.warn(
            f"{name} = {q:.6g} N exceeds the element load at the static stress limit "
            f"Q0 = {q0:.6g} N ({stress}): permanent deformation; the elastic contact model is "
            "outside its range",
            StaticCapacityWarning,
            stacklevel=2,
        )
    return sc
