"""The roller/raceway line-contact formulas of seed IAS (Han, Guo, Fan 2025, eqs. (5)–(13)).

The seed quotes empirical line-contact laws from Pereira, Ramalho & Ambrósio (2011). Its OCR copy
is garbled; this module implements one *consistent* reading and documents it (also in
``docs/models.md``):

``E`` (eq. (6))
    ``1/E = [(1 - nu_1^2)/E_1 + (1 - nu_2^2)/E_2] / 2``, i.e. the Hamrock–Brewe effective
    modulus ``E'`` (:func:`bearingsim.materials.effective_modulus`).
Load
    The seed writes its laws with ``F_y / (E Z l)``: the radial load shared equally by the ``Z``
    rollers. Every function here takes the roller load ``q`` [N]; the seed's reference value is
    ``q_ref = F_y / Z`` (:func:`seed_reference_load`).
Stiffness, eqs. (9)–(10) (taken as printed; they are what the model uses)
    ``K_1 = dq/dzeta_1 = 0.43 E l / [ln(E l (r_c + r_i) / q) - 1.04]`` (roller–inner raceway,
    external contact) and ``K_2 = dq/dzeta_2 = 0.27 E l / [ln(E l R_2 / q) - 0.715]`` (roller–
    outer raceway, internal contact) with ``R_2 = r_c r_o / (r_o - r_c)``. The printed log
    argument of eq. (10), ``(r_2 - r_1) E Z l / (r_1 r_2 F_y)``, is not dimensionless; its
    reciprocal radius is read as the internal-contact radius ``R_2``.
Deflections, eqs. (7)–(8)
    The integrals of ``1/K`` from 0 to ``q``:
    ``zeta_1 = q/(0.43 E l) [ln(E l (r_c + r_i)/q) - 0.04]`` — the printed constant −0.04 and
    coefficient 2.37 (here 1/0.43 = 2.33, 2 % apart) agree — and
    ``zeta_2 = q/(0.27 E l) [ln(E l R_2/q) + 0.285] = 7.41 q/(E l) [0.5 ln(E l R_2/q) + 0.1425]``
    — the printed coefficient 7.43 and factor 0.5 agree, the printed constant −1.38 does not
    (it would need −3.76 in eq. (10)); we keep eq. (10).
Half-width, eq. (5)
    ``b = 1.59 sqrt(q R / (l E'))`` (Hertz: ``sqrt(8/pi) = 1.596``), ``R = r_1 r_2/(r_1 ± r_2)``.
Total stiffness, eqs. (12)–(13)
    Eq. (12) ``1/K_t = [(1/K_1)^(9/10) + (1/K_2)^(9/10)]^(10/9)`` is the series combination of two
    power laws ``q = K_j zeta_j^(10/9)`` and eq. (13) is ``N = K_t zeta^(10/9)``; both need
    constants in [N/m^(10/9)], whereas eqs. (9)–(10) are tangent stiffnesses in [N/m]. Using the
    [N/m] numbers as [N/m^(10/9)] constants is unit-dependent, so we convert each tangent
    stiffness to the power-law constant with the same tangent stiffness at the reference load:
    ``K_j^(p) = (k_j / n)^n q_ref^(1 - n)`` (:func:`power_law_constant`).

Against Harris/Palmgren (:func:`bearingsim.hertz.line_contact`) the half-width agrees to 0.4 %,
but the seed's deflections are about 3.5 times Palmgren's (and Johnson's external-contact
formula), so the seed-law ``K_t`` is about 4 times softer. Both are offered to the IAS model.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike, NDArray

from ..errors import ConfigError, check_positive
from ..geometry import RollerBearing
from ..materials import effective_modulus
from .hertz import combined_stiffness

__all__ = [
    "A1",
    "A2",
    "C1",
    "C2",
    "external_deflection",
    "external_radius",
    "external_stiffness",
    "half_width",
    "HALF_WIDTH_COEFF",
    "internal_deflection",
    "internal_radius",
    "internal_stiffness",
    "LINE_EXPONENT",
    "normal_force",
    "power_law_constant",
    "seed_line_stiffness",
    "seed_reference_load",
    "SeedLineStiffness",
]

#: load–deflection exponent of a line contact, seed IAS eq. (1) and (13) (Palmgren 1959)
LINE_EXPONENT = 10.0 / 9.0
#: coefficient of seed IAS eq. (5) (Hertz: sqrt(8/pi) = 1.5958)
HALF_WIDTH_COEFF = 1.59
#: seed IAS eq. (9): K_1 = A1 E l / [ln(E l (r_1 + r_2)/q) - C1]
A1, C1 = 0.43, 1.04
#: seed IAS eq. (10): K_2 = A2 E l / [ln(E l R_2/q) - C2]
A2, C2 = 0.27, 0.715


def _q(load: ArrayLike) -> NDArray[np.float64]:
    q = np.asarray(load, dtype=float)
    if not np.all(np.isfinite(q)) or np.any(q <= 0):
        bad = q[~np.isfinite(q) | (q <= 0)].ravel()[0]
        raise ConfigError(f"roller_load_n = {bad:.6g} N is out of range; valid range (0, inf) N")
    return q


def _log_arg(name: str, el: float, radius: float, q: NDArray[np.float64], const: float):
    arg = np.log(el * radius / q)
    if np.any(arg <= const):
        qmax = el * radius / math.exp(const)
        raise ConfigError(
            f"roller_load_n = {float(q.max()):.6g} N is out of range for seed IAS {name}; "
            f"valid range (0, {qmax:.6g}) N"
        )
    return arg


def external_radius(r_roller: float, r_inner: float) -> float:
    """Effective radius ``r_c r_i / (r_c + r_i)`` [m] of the roller–inner-raceway contact."""
    return r_roller * r_inner / (r_roller + r_inner)


def internal_radius(r_roller: float, r_outer: float) -> float:
    """Effective radius ``r_c r_o / (r_o - r_c)`` [m] of the roller–outer-raceway contact."""
    if r_outer <= r_roller:
        raise ConfigError(
            f"outer_raceway_radius_m = {r_outer:.6g} m must exceed the roller radius "
            f"{r_roller:.6g} m for an internal contact"
        )
    return r_roller * r_outer / (r_outer - r_roller)


def half_width(load: ArrayLike, length: float, r_eff: float, e_eff: float) -> NDArray[np.float64]:
    """Contact half-width ``b = 1.59 sqrt(q R / (l E'))`` [m] (seed IAS eq. (5)).

    Parameters
    ----------
    load : array_like
        Roller load q [N].
    length : float
        Effective contact length l [m].
    r_eff : float
        Effective radius ``r_1 r_2 / (r_1 ± r_2)`` [m].
    e_eff : float
        Effective modulus E' of seed IAS eq. (6) [Pa].
    """
    q = np.asarray(load, dtype=float)
    ln = check_positive("length_m", length, "m")
    return HALF_WIDTH_COEFF * np.sqrt(np.maximum(q, 0.0) * r_eff / (ln * e_eff))


def external_stiffness(
    load: ArrayLike, length: float, r_roller: float, r_inner: float, e_eff: float
) -> NDArray[np.float64]:
    """Tangent stiffness ``K_1 = dq/dzeta_1`` [N/m] of the roller–inner contact (seed IAS eq. (9)).

    ``K_1 = 0.43 E l / [ln(E l (r_c + r_i) / q) - 1.04]``.

    Parameters
    ----------
    load : array_like
        Roller load q [N], > 0.
    length : float
        Contact length l [m].
    r_roller, r_inner : float
        Roller radius r_c and inner raceway radius r_i [m].
    e_eff : float
        Effective modulus E' [Pa] (seed eq. (6)).
    """
    q = _q(load)
    el = e_eff * length
    arg = _log_arg("eq. (9)", el, r_roller + r_inner, q, C1)
    return A1 * el / (arg - C1)


# (duplicates) the shape of external_stiffness: seed IAS eqs. (9) and (10) are two published
# formulas with their own constants, one function per equation as the seed writes them
def internal_stiffness(
    load: ArrayLike, length: float, r_roller: float, r_outer: float, e_eff: float
) -> NDArray[np.float64]:
    """Tangent stiffness ``K_2 = dq/dzeta_2`` [N/m] of the roller–outer contact (seed IAS eq. (10)).

    ``K_2 = 0.27 E l / [ln(E l R_2 / q) - 0.715]``, ``R_2 = r_c r_o / (r_o - r_c)``.

    Parameters
    ----------
    load : array_like
        Roller load q [N], > 0.
    length : float
        Contact length l [m].
    r_roller, r_outer : float
        Roller radius r_c and outer raceway radius r_o [m].
    e_eff : float
        Effective modulus E' [Pa] (seed eq. (6)).
    """
    q = _q(load)
    el = e_eff * length
    arg = _log_arg("eq. (10)", el, internal_radius(r_roller, r_outer), q, C2)
    return A2 * el / (arg - C2)


def external_deflection(
    load: ArrayLike, length: float, r_roller: float, r_inner: float, e_eff: float
) -> NDArray[np.float64]:
    """Approach ``zeta_1`` [m] of the roller–inner contact (seed IAS eq. (7), integral of 1/K_1).

    ``zeta_1 = q / (0.43 E l) [ln(E l (r_c + r_i) / q) - 0.04]``; parameters as
    :func:`external_stiffness`.
    """
    q = _q(load)
    el = e_eff * length
    arg = _log_arg("eq. (7)", el, r_roller + r_inner, q, C1)
    return q / (A1 * el) * (arg + 1.0 - C1)


def internal_deflection(
    load: ArrayLike, length: float, r_roller: float, r_outer: float, e_eff: float
) -> NDArray[np.float64]:
    """Approach ``zeta_2`` [m] of the roller–outer contact (seed IAS eq. (8), integral of 1/K_2).

    ``zeta_2 = q / (0.27 E l) [ln(E l R_2 / q) + 0.285]``; parameters as
    :func:`internal_stiffness`.
    """
    q = _q(load)
    el = e_eff * length
    arg = _log_arg("eq. (8)", el, internal_radius(r_roller, r_outer), q, C2)
    return q / (A2 * el) * (arg + 1.0 - C2)


def power_law_constant(
    tangent_stiffness: float, reference_load: float, exponent: float = LINE_EXPONENT
) -> float:
    """Constant ``K`` [N/m^n] of ``q = K zeta^n`` whose tangent stiffness at ``reference_load``
    equals ``tangent_stiffness`` [N/m]: ``K = (k/n)^n q_ref^(1-n)``.

    From ``dq/dzeta = n K zeta^(n-1)`` with ``zeta = (q/K)^(1/n)``.
    """
    k = check_positive("tangent_stiffness_n_m", tangent_stiffness, "N/m")
    q = check_positive("reference_load_n", reference_load, "N")
    return (k / exponent) ** exponent * q ** (1.0 - exponent)


def seed_reference_load(bearing: RollerBearing, radial_load: float) -> float:
    """The seed's roller load ``F_y / Z`` [N] (its eqs. (7)–(10) use ``F_y/(E Z l)``)."""
    fr = check_positive("radial_load_n", radial_load, "N")
    return fr / bearing.n_elements


@dataclass(frozen=True)
class SeedLineStiffness:
    """Seed IAS line-contact stiffness of one roller at a reference load.

    Attributes
    ----------
    reference_load : float
        Roller load q_ref at which the tangent stiffnesses are evaluated [N].
    e_eff : float
        Effective modulus E' (seed eq. (6)) [Pa].
    k_inner, k_outer : float
        Tangent stiffnesses K_1, K_2 (eqs. (9), (10)) [N/m].
    zeta_inner, zeta_outer, zeta : float
        Approaches zeta_1, zeta_2 (eqs. (7), (8)) and their sum (eq. (11)) at q_ref [m].
    b_inner, b_outer : float
        Contact half-widths at q_ref (eq. (5)) [m].
    kp_inner, kp_outer : float
        Power-law constants with the same tangent stiffness at q_ref [N/m^(10/9)].
    k_total : float
        ``K_t`` of eq. (12) [N/m^(10/9)], used in eq. (13) ``N = K_t zeta^(10/9)``.
    exponent : float
        10/9 [-].
    """

    reference_load: float
    e_eff: float
    k_inner: float
    k_outer: float
    zeta_inner: float
    zeta_outer: float
    zeta: float
    b_inner: float
    b_outer: float
    kp_inner: float
    kp_outer: float
    k_total: float
    exponent: float = LINE_EXPONENT


def seed_line_stiffness(bearing: RollerBearing, reference_load: float) -> SeedLineStiffness:
    """Seed IAS eqs. (5)–(12) for one roller of ``bearing`` at roller load ``reference_load``.

    Parameters
    ----------
    bearing : RollerBearing
        Geometry (roller radius r_c, raceway radii r_i, r_o, length l) and material.
    reference_load : float
        Roller load q_ref [N]; the seed uses ``F_y / Z`` (:func:`seed_reference_load`).
    """
    if not isinstance(bearing, RollerBearing):
        raise ConfigError(
            f"bearing = {bearing.id!r} is not a roller bearing; the seed IAS "
            "line-contact laws need rollers"
        )
    q = check_positive("reference_load_n", reference_load, "N")
    ee = effective_modulus(bearing.material, bearing.material)  # seed eq. (6)
    rc = 0.5 * bearing.element_diameter
    ri, ro, ln = bearing.inner_raceway_radius, bearing.outer_raceway_radius, bearing.roller_length
    k1 = float(external_stiffness(q, ln, rc, ri, ee))  # eq. (9)
    k2 = float(internal_stiffness(q, ln, rc, ro, ee))  # eq. (10)
    z1 = float(external_deflection(q, ln, rc, ri, ee))  # eq. (7)
    z2 = float(internal_deflection(q, ln, rc, ro, ee))  # eq. (8)
    b1 = float(half_width(q, ln, external_radius(rc, ri), ee))  # eq. (5)
    b2 = float(half_width(q, ln, internal_radius(rc, ro), ee))
    kp1 = power_law_constant(k1, q)
    kp2 = power_law_constant(k2, q)
    kt = combined_stiffness(kp1, kp2, LINE_EXPONENT)  # eq. (12)
    return SeedLineStiffness(q, ee, k1, k2, z1, z2, z1 + z2, b1, b2, kp1, kp2, kt)


def normal_force(
    zeta: ArrayLike, k_total: float, exponent: float = LINE_EXPONENT
) -> NDArray[np.float64]:
    """Normal contact force ``N = K_t zeta^n`` for ``zeta > 0``, else 0 [N] (seed IAS eq. (13)).

    Parameters
    ----------
    zeta : array_like
        Total contact approach [m].
    k_total : float
        ``K_t`` [N/m^n].
    exponent : float
        n [-] (10/9 for rollers).
    """
    z = np.asarray(zeta, dtype=float)
    return k_total * np.maximum(z, 0.0) ** exponent
