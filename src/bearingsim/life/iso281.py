"""ISO 281 basic dynamic load rating and basic rating life; static capacity; unit conversions.

Radial bearings, pure radial load (``P = F_r``), units of the standard inside the formulas
(N, mm), SI at the interface.

- Ball bearings (ISO 281:2007, eq. (2)): ``C_r = b_m f_c (i cos alpha)^0.7 Z^(2/3) D_w^1.8``
  for ``D_w <= 25.4 mm`` and ``C_r = 3.647 b_m f_c (i cos alpha)^0.7 Z^(2/3) D_w^1.4`` above;
  ``b_m = 1.3`` (table 1, radial ball bearings); ``f_c`` from table 2 (single-row radial contact
  groove ball bearings) at ``gamma = D_w cos alpha / D_pw``, linear interpolation between rows.
- Roller bearings (ISO 281:2007, eq. (7)): ``C_r = b_m f_c (i L_we cos alpha)^(7/9) Z^(3/4)
  D_we^(29/27)``; ``b_m = 1.1`` (table 1, cylindrical roller bearings); ``f_c`` from table 3.
- Basic rating life ``L_10 = (C_r/P)^p`` [10^6 revolutions], ``p = 3`` balls, ``10/3`` rollers.

The ``f_c`` rows below are transcribed from ISO 281:2007 tables 2 and 3. They follow the
Lundberg–Palmgren closed forms (ISO/TR 1281-1) — ball:
``f_c = K [1 + (1.04 ((1-g)/(1+g))^1.72)^(10/3)]^-0.3 g^0.3 (1-g)^1.39 / (1+g)^(1/3)``
with ``K = 145.3`` reproduces every ball row to 0.13 %; roller:
``f_c = 207.9 lambda nu [1 + (1.04 ((1-g)/(1+g))^(143/108))^(9/2)]^(-2/9) g^(2/9) (1-g)^(29/27) /
(1+g)^(1/4)`` with ``lambda nu = 0.83`` reproduces the roller rows to 0.1 % for ``g <= 0.30`` —
which is checked in ``tests/test_iso281_life.py`` as a guard against transcription errors. The
roller rows above ``g = 0.30`` are not carried (our transcription of them disagrees with the closed
form by up to 1.6 %), so roller ``f_c`` is limited to ``g <= 0.30``.
"""

from __future__ import annotations

import math
import warnings
from dataclasses import dataclass

import numpy as np

from ..contact.capacity import (
    STATIC_LIMIT_FACTOR,
    STATIC_STRESS_BALL,
    STATIC_STRESS_ROLLER,
    STRIBECK_STATIC,
    StaticCapacity,
    StaticCapacityWarning,
    static_capacity,
)
from ..errors import ConfigError, check_positive, check_range
from ..geometry import BallBearing, Bearing, RollerBearing

__all__ = [
    "B_M_BALL",
    "B_M_ROLLER",
    "basic_rating_life",
    "check_static_load",
    "cycles_to_revolutions",
    "dynamic_load_rating",
    "DynamicRating",
    "fc_ball",
    "fc_ball_closed_form",
    "FC_BALL_TABLE",
    "fc_roller",
    "fc_roller_closed_form",
    "FC_ROLLER_TABLE",
    "gamma",
    "inner_race_cycles_per_revolution",
    "revolutions_to_cycles",
    "revolutions_to_hours",
    "static_capacity",
    "STATIC_LIMIT_FACTOR",
    "STATIC_STRESS_BALL",
    "STATIC_STRESS_ROLLER",
    "StaticCapacity",
    "StaticCapacityWarning",
    "STRIBECK_STATIC",
]

#: ISO 281:2007 table 1: b_m for radial ball bearings (other than filling-slot / insert bearings)
B_M_BALL = 1.3
#: ISO 281:2007 table 1: b_m for cylindrical roller bearings
B_M_ROLLER = 1.1

#: ISO 281:2007 table 2, f_c of single-row radial contact groove ball bearings vs
#: gamma = D_w cos(alpha)/D_pw
FC_BALL_TABLE = np.array(
    [
        (0.01, 29.1), (0.02, 35.8), (0.03, 40.3), (0.04, 43.8), (0.05, 46.7), (0.06, 49.1),
        (0.07, 51.1), (0.08, 52.8), (0.09, 54.3), (0.10, 55.5), (0.12, 57.5), (0.14, 58.8),
        (0.16, 59.6), (0.18, 59.9), (0.20, 59.9), (0.22, 59.6), (0.24, 59.0), (0.26, 58.2),
        (0.28, 57.1), (0.30, 56.0), (0.32, 54.6), (0.34, 53.2), (0.36, 51.7), (0.38, 50.0),
        (0.40, 48.4),
    ]
)  # fmt: skip

#: ISO 281:2007 table 3, f_c of radial roller bearings vs gamma = D_we cos(alpha)/D_pw
#: (rows up to 0.30 only, see the module docstring)
FC_ROLLER_TABLE = np.array(
    [
        (0.01, 52.1), (0.02, 60.8), (0.03, 66.5), (0.04, 70.7), (0.05, 74.1), (0.06, 76.9),
        (0.07, 79.2), (0.08, 81.2), (0.09, 82.8), (0.10, 84.2), (0.12, 86.4), (0.14, 87.7),
        (0.16, 88.5), (0.18, 88.8), (0.20, 88.7), (0.22, 88.2), (0.24, 87.5), (0.26, 86.4),
        (0.28, 85.2), (0.30, 83.8),
    ]
)  # fmt: skip


def gamma(bearing: Bearing) -> float:
    """``gamma = D_w cos(alpha) / D_pw`` [-]."""
    return bearing.element_diameter * math.cos(bearing.contact_angle) / bearing.pitch_diameter


def fc_ball(g: float) -> float:
    """``f_c`` of a single-row radial contact groove ball bearing (ISO 281:2007 table 2, linear
    interpolation) [-].

    Parameters
    ----------
    g : float
        ``gamma = D_w cos(alpha)/D_pw`` [-], in [0.01, 0.40].
    """
    g = check_range("gamma", g, FC_BALL_TABLE[0, 0], FC_BALL_TABLE[-1, 0])
    return float(np.interp(g, FC_BALL_TABLE[:, 0], FC_BALL_TABLE[:, 1]))


def fc_roller(g: float) -> float:
    """``f_c`` of a radial roller bearing (ISO 281:2007 table 3, linear interpolation) [-].

    Parameters
    ----------
    g : float
        ``gamma = D_we cos(alpha)/D_pw`` [-], in [0.01, 0.30].
    """
    g = check_range("gamma", g, FC_ROLLER_TABLE[0, 0], FC_ROLLER_TABLE[-1, 0])
    return float(np.interp(g, FC_ROLLER_TABLE[:, 0], FC_ROLLER_TABLE[:, 1]))


def fc_ball_closed_form(g: float, k: float = 145.3) -> float:
    """Lundberg–Palmgren shape of the ISO ball ``f_c`` (see module docstring) [-]."""
    br = (1.0 + (1.04 * ((1 - g) / (1 + g)) ** 1.72) ** (10.0 / 3.0)) ** -0.3
    return k * br * g**0.3 * (1 - g) ** 1.39 / (1 + g) ** (1.0 / 3.0)


def fc_roller_closed_form(g: float, lambda_nu: float = 0.83) -> float:
    """Lundberg–Palmgren roller ``f_c`` (ISO/TR 1281-1 form, ``lambda nu = 0.83``) [-]."""
    br = (1.0 + (1.04 * ((1 - g) / (1 + g)) ** (143.0 / 108.0)) ** 4.5) ** (-2.0 / 9.0)
    return 207.9 * lambda_nu * br * g ** (2.0 / 9.0) * (1 - g) ** (29.0 / 27.0) / (1 + g) ** 0.25


@dataclass(frozen=True)
class DynamicRating:
    """ISO 281 basic dynamic radial load rating.

    Attributes
    ----------
    c : float
        Basic dynamic radial load rating C_r [N].
    b_m : float
        Rating factor for contemporary material and manufacturing quality [-].
    f_c : float
        Geometry/manufacturing factor [-].
    gamma : float
        ``D_w cos(alpha) / D_pw`` [-].
    life_exponent : float
        ``p`` in ``L_10 = (C/P)^p`` [-].
    """

    c: float
    b_m: float
    f_c: float
    gamma: float
    life_exponent: float


def dynamic_load_rating(bearing: Bearing, rows: int = 1) -> DynamicRating:
    """ISO 281:2007 basic dynamic radial load rating from the bearing geometry.

    Parameters
    ----------
    bearing : BallBearing or RollerBearing
        Geometry (ball: D_w, Z, D_pw, alpha; roller: also the effective length L_we).
    rows : int
        Number of rows ``i`` [-].
    """
    if isinstance(rows, bool) or not float(check_range("rows", rows, 1, 8)).is_integer():
        raise ConfigError(f"rows = {rows!r} is invalid; valid range [1, 8] integer")
    i = int(rows)
    g = gamma(bearing)
    ca = math.cos(bearing.contact_angle)
    Z = bearing.n_elements
    Dw = bearing.element_diameter * 1e3  # mm
    if isinstance(bearing, BallBearing):
        fc = fc_ball(g)
        if Dw <= 25.4:
            c = B_M_BALL * fc * (i * ca) ** 0.7 * Z ** (2.0 / 3.0) * Dw**1.8  # ISO 281 eq. (2)
        else:
            c = 3.647 * B_M_BALL * fc * (i * ca) ** 0.7 * Z ** (2.0 / 3.0) * Dw**1.4
        return DynamicRating(c, B_M_BALL, fc, g, 3.0)
    if isinstance(bearing, RollerBearing):
        fc = fc_roller(g)
        Lwe = bearing.roller_length * 1e3
        # ISO 281 eq. (7)
        c = B_M_ROLLER * fc * (i * Lwe * ca) ** (7.0 / 9.0) * Z**0.75 * Dw ** (29.0 / 27.0)
        return DynamicRating(c, B_M_ROLLER, fc, g, 10.0 / 3.0)
    raise ConfigError(f"bearing = {bearing!r} is not a BallBearing or RollerBearing")


def basic_rating_life(bearing: Bearing, radial_load: float, rows: int = 1) -> float:
    """ISO 281 basic rating life ``L_10 = (C_r/P)^p`` [revolutions] for a pure radial load
    ``P = F_r``.

    Parameters
    ----------
    bearing : BallBearing or RollerBearing
        Geometry.
    radial_load : float
        Radial load F_r [N], > 0.
    rows : int
        Number of rows [-].
    """
    fr = check_positive("radial_load_n", radial_load, "N")
    r = dynamic_load_rating(bearing, rows)
    return 1e6 * (r.c / fr) ** r.life_exponent


def inner_race_cycles_per_revolution(bearing: Bearing) -> float:
    """Over-rollings of a point on the rotating inner race per inner-ring revolution [-]:
    ``u_i = Z (1 + gamma) / 2`` (the BPFI order; outer ring fixed; Harris & Kotzalas 2007,
    vol. 1, ch. 8). Every over-rolling is counted as one stress cycle (a point passes the load
    zone once per revolution; ``u_i`` counts all element passes)."""
    return 0.5 * bearing.n_elements * (1.0 + gamma(bearing))


def cycles_to_revolutions(bearing: Bearing, cycles: float) -> float:
    """Inner-race stress cycles → inner-ring revolutions [rev] (``N / u_i``)."""
    return float(cycles) / inner_race_cycles_per_revolution(bearing)


def revolutions_to_cycles(bearing: Bearing, revolutions: float) -> float:
    """Inner-ring revolutions → inner-race stress cycles [cycles] (``L u_i``)."""
    return float(revolutions) * inner_race_cycles_per_revolution(bearing)


def revolutions_to_hours(revolutions: float, rpm: float) -> float:
    """Revolutions at constant speed → hours [h]: ``L / (60 n)``.

    Parameters
    ----------
    revolutions : float
        Revolutions [rev].
    rpm : float
        Shaft speed n [r/min], > 0.
    """
    n = check_positive("rpm", rpm, "r/min")
    return float(revolutions) / (60.0 * n)


def check_static_load(bearing: Bearing, radial_load: float) -> StaticCapacity:
    """Warn (:class:`StaticCapacityWarning`) when ``F_r > C_0``; refuse (one-line
    :class:`~bearingsim.errors.ConfigError`) when ``F_r > 2 C_0``, without an override: the
    damage model of the life family is elastic. (The other models use
    :func:`bearingsim.contact.capacity.check_load`, which ``allow_overload`` can override; the
    capacity itself lives there, and is re-exported here.)

    Parameters
    ----------
    bearing : BallBearing or RollerBearing
        Geometry.
    radial_load : float
        Radial load F_r [N].
    """
    fr = check_positive("radial_load_n", radial_load, "N")
    sc = static_capacity(bearing)
    if fr > STATIC_LIMIT_FACTOR * sc.c0:
        raise ConfigError(
            f"radial_load_n = {fr:.6g} N exceeds {STATIC_LIMIT_FACTOR:g} x the static capacity "
            f"C0 = {sc.c0:.6g} N of {bearing.id} (contact stress {sc.stress_limit / 1e6:.0f} MPa, "
            f"ISO 76); valid range (0, {STATIC_LIMIT_FACTOR * sc.c0:.6g}] N"
        )
    if fr > sc.c0:
        warnings.warn(
            f"radial load {fr:.6g} N exceeds the static capacity C0 = {sc.c0:.6g} N of "
            f"{bearing.id}: the most loaded contact exceeds {sc.stress_limit / 1e6:.0f} MPa "
            "(ISO 76); the elastic damage model is outside its range",
            StaticCapacityWarning,
            stacklevel=2,
        )
    return sc
