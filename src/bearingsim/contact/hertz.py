"""Hertz contact: point contact (balls), line contact (rollers), subsurface stresses.

Point contact follows Hamrock & Brewe (1983) notation: ``R_x`` is the effective radius in the
rolling direction, ``R_y`` transverse, ``1/R = 1/R_x + 1/R_y``, ellipticity ``k = a/b`` with ``a``
the semi-axis transverse to rolling (semi-major for ball/groove contacts) and ``b`` the semi-axis
along the rolling direction. The exact solution uses the complete elliptic integrals
``K(m)``, ``E(m)`` with ``m = 1 - 1/k^2`` (SciPy's parameter convention); the ellipticity solves
``R_y/R_x = (k^2 E - K) / (K - E)`` (Johnson 1985, eq. (4.30)).
"""

from __future__ import annotations

import enum
import math
from dataclasses import dataclass
from functools import lru_cache
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray
from scipy.optimize import brentq
from scipy.special import ellipe, ellipk

from ..errors import ConfigError, check_positive, check_range
from ..geometry import BallBearing, Race, RollerBearing, contact_race
from ..materials import effective_modulus
from ..signal.peaks import refine_peak

__all__ = [
    "ball_contact",
    "ball_race_radii",
    "ball_stiffness",
    "combined_stiffness",
    "element_stiffness",
    "Ellipticity",
    "ellipticity",
    "EllipticMethod",
    "line_contact",
    "line_subsurface_stresses",
    "LineContact",
    "PALMGREN_C_SI",
    "point_contact",
    "PointContact",
    "roller_contact",
    "roller_race_radius",
    "subsurface_stresses",
    "SubsurfaceStresses",
]


class EllipticMethod(enum.Enum):
    """How the ellipticity and elliptic integrals of a point contact are obtained."""

    #: solve the ellipticity equation with the complete elliptic integrals (exact)
    EXACT = "exact"
    #: Hamrock & Brewe (1983) closed forms ``k = a_r^(2/pi)``, ``E = 1 + q/a_r``,
    #: ``F = pi/2 + q ln a_r`` (``q = pi/2 - 1``). Measured against EXACT over
    #: 1 <= R_y/R_x <= 100: k and delta within 4.2 %, a, b and p_max within 2.7 %.
    HAMROCK_BREWE = "hamrock_brewe"


@dataclass(frozen=True)
class Ellipticity:
    """Ellipticity ``k = a/b`` [-] and the complete elliptic integrals K (first kind) and E
    (second kind) [-] of a point contact with curvature ratio ``R_y/R_x``."""

    k: float
    K: float
    E: float


def _ratio(k: float) -> float:
    m = 1.0 - 1.0 / (k * k)
    K, E = ellipk(m), ellipe(m)
    return (k * k * E - K) / (K - E)


@lru_cache(maxsize=4096)
def ellipticity(radius_ratio: float, method: EllipticMethod = EllipticMethod.EXACT) -> Ellipticity:
    """Ellipticity and elliptic integrals for ``radius_ratio = R_y / R_x`` (>= 1 or < 1).

    Parameters
    ----------
    radius_ratio : float
        ``R_y / R_x`` [-]. Values below 1 are handled by symmetry (``k < 1``).
    method : EllipticMethod
        Exact solution (default) or Hamrock–Brewe (1983) closed forms.
    """
    ar = check_positive("radius_ratio", radius_ratio)
    if ar < 1.0:  # swap the axes: ellipse elongated along the rolling direction
        e = ellipticity(1.0 / ar, method)
        # a/b inverts; K and E refer to the eccentricity, which is unchanged
        return Ellipticity(1.0 / e.k, e.K, e.E)
    if method is EllipticMethod.HAMROCK_BREWE:
        q = 0.5 * math.pi - 1.0
        return Ellipticity(ar ** (2.0 / math.pi), 0.5 * math.pi + q * math.log(ar), 1.0 + q / ar)
    if ar - 1.0 < 1e-12:
        return Ellipticity(1.0, 0.5 * math.pi, 0.5 * math.pi)
    # bracket: the Hamrock-Brewe estimate is within a few per cent
    k0 = ar ** (2.0 / math.pi)
    lo, hi = 1.0 + 1e-9, max(2.0 * k0, 2.0)
    while _ratio(hi) < ar:
        hi *= 2.0
    k = brentq(lambda kk: _ratio(kk) - ar, lo, hi, xtol=1e-14, rtol=1e-14, maxiter=200)
    m = 1.0 - 1.0 / (k * k)
    return Ellipticity(k, float(ellipk(m)), float(ellipe(m)))


@dataclass(frozen=True)
class PointContact:
    """Hertz point-contact result (arrays broadcast over the loads).

    Attributes
    ----------
    load : ndarray
        Normal load Q [N].
    a, b : ndarray
        Semi-axes transverse to and along the rolling direction [m].
    delta : ndarray
        Elastic approach [m].
    p_max : ndarray
        Maximum contact pressure ``3Q/(2 pi a b)`` [Pa].
    k_hertz : float
        Load–deflection constant, ``Q = k_hertz delta^1.5`` [N/m^1.5].
    ellipticity : Ellipticity
        ``k = a/b`` and the elliptic integrals.
    rx, ry : float
        Effective radii [m].
    e_eff : float
        Effective modulus ``E'`` [Pa].
    """

    load: NDArray[np.float64]
    a: NDArray[np.float64]
    b: NDArray[np.float64]
    delta: NDArray[np.float64]
    p_max: NDArray[np.float64]
    k_hertz: float
    ellipticity: Ellipticity
    rx: float
    ry: float
    e_eff: float


def _loads(load: ArrayLike, name: str = "load_n") -> NDArray[np.float64]:
    q = np.asarray(load, dtype=float)
    if not np.all(np.isfinite(q)):
        raise ConfigError(f"{name} contains a non-finite value; valid range [0, inf) N")
    if np.any(q < 0):
        raise ConfigError(f"{name} = {float(q.min()):.6g} N is negative; valid range [0, inf) N")
    return q


def point_contact(
    load: ArrayLike,
    rx: float,
    ry: float,
    e_eff: float,
    method: EllipticMethod = EllipticMethod.EXACT,
) -> PointContact:
    """Hertz elliptical point contact (Hamrock & Brewe 1983, eqs. (12)–(17); Harris & Kotzalas
    2007, ch. 6).

    ``a = (6 k^2 E Q R / (pi E'))^(1/3)``, ``b = (6 E Q R / (pi k E'))^(1/3)``,
    ``delta = K [9/(2 E R) (Q/(pi k E'))^2]^(1/3)``, ``p_max = 3 Q / (2 pi a b)``.

    Parameters
    ----------
    load : array_like
        Normal load(s) Q [N], >= 0.
    rx, ry : float
        Effective radii of curvature in and across the rolling direction [m] (> 0; the
        contact must be conforming-convex overall).
    e_eff : float
        Effective modulus ``E'`` [Pa] (:func:`bearingsim.materials.effective_modulus`).
    method : EllipticMethod
        Exact elliptic integrals (default) or Hamrock–Brewe closed forms.
    """
    q = _loads(load)
    rx = check_positive("rx_m", rx, "m")
    ry = check_positive("ry_m", ry, "m")
    ee = check_positive("e_eff_pa", e_eff, "Pa")
    el = ellipticity(ry / rx, method)
    R = 1.0 / (1.0 / rx + 1.0 / ry)
    k, Kf, Ef = el.k, el.K, el.E
    a = np.cbrt(6.0 * k * k * Ef * q * R / (math.pi * ee))
    b = np.cbrt(6.0 * Ef * q * R / (math.pi * k * ee))
    delta = Kf * np.cbrt(9.0 / (2.0 * Ef * R) * (q / (math.pi * k * ee)) ** 2)
    with np.errstate(invalid="ignore", divide="ignore"):
        p_max = np.where(q > 0, 1.5 * q / (math.pi * np.where(q > 0, a * b, 1.0)), 0.0)
    k_hertz = math.pi * k * ee * math.sqrt(2.0 * Ef * R / 9.0) / Kf**1.5
    return PointContact(q, a, b, delta, p_max, k_hertz, el, rx, ry, ee)


def ball_race_radii(bearing: BallBearing, race: Race) -> tuple[float, float]:
    """Effective radii ``(R_x, R_y)`` [m] of a ball/raceway contact at the nominal contact angle.

    ``1/R_x = 2/d +/- 2 cos(alpha)/(D -/+ d cos(alpha))`` (+ inner, - outer) and
    ``1/R_y = 2/d - 1/R_groove`` (Harris & Kotzalas 2007, eqs. (2.27)–(2.33)).
    """
    if not isinstance(bearing, BallBearing):
        raise ConfigError(
            f"bearing = {bearing.id!r} is not a ball bearing; point contact needs balls"
        )
    d, D, ca = bearing.element_diameter, bearing.pitch_diameter, math.cos(bearing.contact_angle)
    if race is Race.INNER:
        rho_x = 2.0 / d + 2.0 * ca / (D - d * ca)
        rg = bearing.inner_groove_radius
    else:
        rho_x = 2.0 / d - 2.0 * ca / (D + d * ca)
        rg = bearing.outer_groove_radius
    rho_y = 2.0 / d - 1.0 / rg
    return 1.0 / rho_x, 1.0 / rho_y


def ball_contact(
    bearing: BallBearing,
    load: ArrayLike,
    race: Race | str,
    method: EllipticMethod = EllipticMethod.EXACT,
) -> PointContact:
    """Hertz contact of a ball with the inner or outer raceway of ``bearing``.

    Parameters
    ----------
    bearing : BallBearing
        Geometry and material (balls and rings of the same material).
    load : array_like
        Ball load Q [N].
    race : Race or {"inner", "outer"}
        Which raceway.
    method : EllipticMethod
        Exact (default) or Hamrock–Brewe.
    """
    race = contact_race(race, "race")
    rx, ry = ball_race_radii(bearing, race)
    e_eff = effective_modulus(bearing.material, bearing.material)
    return point_contact(load, rx, ry, e_eff, method)


def combined_stiffness(k_inner: float, k_outer: float, exponent: float = 1.5) -> float:
    """Series combination of two contacts ``Q = K_i delta_i^n = K_o delta_o^n`` [N/m^n].

    ``K = [(1/K_i)^(1/n) + (1/K_o)^(1/n)]^(-n)``; for ``n = 1.5`` this is seed VSM eq. (10),
    for ``n = 10/9`` seed IAS eq. (12).
    """
    ki = check_positive("k_inner", k_inner)
    ko = check_positive("k_outer", k_outer)
    return ((1.0 / ki) ** (1.0 / exponent) + (1.0 / ko) ** (1.0 / exponent)) ** (-exponent)


def ball_stiffness(bearing: BallBearing, method: EllipticMethod = EllipticMethod.EXACT) -> float:
    """Combined inner+outer load–deflection constant K of one ball, ``Q = K delta^1.5``
    [N/m^1.5] (seed VSM eq. (10))."""
    ki = ball_contact(bearing, 1.0, Race.INNER, method).k_hertz
    ko = ball_contact(bearing, 1.0, Race.OUTER, method).k_hertz
    return combined_stiffness(ki, ko, 1.5)


# --------------------------------------------------------------------------- subsurface stresses


@dataclass(frozen=True)
class SubsurfaceStresses:
    """Stresses on the depth axis below the centre of an elliptical Hertz contact.

    Attributes
    ----------
    depth : ndarray
        Depth z below the surface [m].
    sigma_x, sigma_y, sigma_z : ndarray
        Normal stresses along the rolling direction (x), across it (y) and the depth (z) [Pa],
        tension positive; they are principal stresses on this axis.
    tau_max : float
        Maximum over depth of the maximum shear stress ``(sigma_1 - sigma_3)/2`` [Pa].
    tau_max_depth : float
        Depth of ``tau_max`` [m].
    tau_orth : float
        Amplitude of the orthogonal shear stress ``tau_yz`` (Lundberg & Palmgren 1947) [Pa].
    tau_orth_depth : float
        Its depth [m].
    """

    depth: NDArray[np.float64]
    sigma_x: NDArray[np.float64]
    sigma_y: NDArray[np.float64]
    sigma_z: NDArray[np.float64]
    tau_max: float
    tau_max_depth: float
    tau_orth: float
    tau_orth_depth: float


@lru_cache(maxsize=256)
def _axis_stress_shape(k: float, nu: float, n_depth: int = 400, z_max: float = 3.0):
    """Dimensionless stresses ``sigma/p_max`` on the z axis vs ``z/b`` for ellipticity
    ``k = a/b``: integral of the Boussinesq point-load field (Johnson 1985, eq. (3.20)) over the
    Hertz pressure ``p_max sqrt(1 - (x/b)^2 - (y/a)^2)`` by Gauss quadrature in elliptic polar
    coordinates (the radial variable ``s = sin t`` removes the square-root edge)."""
    bb, aa = 1.0, k  # b along x (rolling), a along y
    nt, nphi = 96, 128
    t, wt = np.polynomial.legendre.leggauss(nt)
    t = 0.25 * math.pi * (t + 1.0)  # map to (0, pi/2)
    wt = 0.25 * math.pi * wt
    s = np.sin(t)
    # dA = a b s ds dphi, ds = cos t dt; pressure sqrt(1-s^2) = cos t
    w_s = wt * s * np.cos(t) ** 2 * aa * bb
    phi = (np.arange(nphi) + 0.5) * (2.0 * math.pi / nphi)
    w_phi = 2.0 * math.pi / nphi
    X = bb * np.outer(s, np.cos(phi))
    Y = aa * np.outer(s, np.sin(phi))
    W = np.outer(w_s, np.full(nphi, w_phi))
    r2 = (X * X + Y * Y)[None]
    z = np.linspace(z_max / n_depth, z_max, n_depth)[:, None, None]
    rho = np.sqrt(r2 + z * z)
    c = 1.0 / (2.0 * math.pi)
    x2, y2 = (X * X)[None], (Y * Y)[None]
    with np.errstate(invalid="ignore", divide="ignore"):
        f = (1.0 - z / rho) / r2
    # point load P = 1 pressing on the surface; the field point sits at -(X, Y) from the load
    sx = c * ((1 - 2 * nu) * (f * (x2 - y2) / r2 + z * y2 / (r2 * rho**3)) - 3 * z * x2 / rho**5)
    sy = c * ((1 - 2 * nu) * (f * (y2 - x2) / r2 + z * x2 / (r2 * rho**3)) - 3 * z * y2 / rho**5)
    sz = -3.0 * c * z**3 / rho**5
    # p_max normalisation: total load of the ellipsoidal pressure is (2/3) pi a b p_max
    Sx = np.sum(sx * W, axis=(1, 2))
    Sy = np.sum(sy * W, axis=(1, 2))
    Sz = np.sum(sz * W, axis=(1, 2))
    return z[:, 0, 0], Sx, Sy, Sz


def _lundberg_palmgren(b_over_a: float) -> tuple[float, float]:
    """Orthogonal shear amplitude ``tau_0/p_max`` and depth ``z_0/b`` (Lundberg & Palmgren 1947;
    Harris & Kotzalas 2007, eqs. (6.41)–(6.43)) with ``b/a = sqrt((t^2 - 1)(2t - 1))``."""
    g = lambda t: math.sqrt((t * t - 1.0) * (2.0 * t - 1.0)) - b_over_a  # noqa: E731
    t = brentq(g, 1.0 + 1e-15, 10.0, xtol=1e-15)
    tau0 = math.sqrt(2.0 * t - 1.0) / (2.0 * t * (t + 1.0))
    z0 = 1.0 / ((t + 1.0) * math.sqrt(2.0 * t - 1.0))
    return tau0, z0


def _check_nu_index(nu: Any, index: Any, n: int) -> tuple[float, int]:
    """Poisson's ratio in [0, 0.5) (:data:`~bearingsim.materials.POISSON_RANGE`) and a load
    index in [0, n): one-line errors."""
    from ..materials import POISSON_RANGE

    nu = check_range("nu", nu, *POISSON_RANGE, hi_open=True)
    if isinstance(index, bool) or not isinstance(index, int | np.integer) or not 0 <= index < n:
        raise ConfigError(f"index = {index!r} is out of range; valid range [0, {n - 1}] integer")
    return nu, int(index)


def subsurface_stresses(contact: PointContact, nu: float, index: int = 0) -> SubsurfaceStresses:
    """Subsurface stresses on the depth axis under the centre of a point contact.

    The normal stresses come from the Boussinesq field integrated over the Hertz pressure
    (checked against the closed-form circular case, Johnson 1985 eq. (3.46)); ``tau_max`` is the
    largest ``(sigma_max - sigma_min)/2`` over depth; the orthogonal shear amplitude and depth
    follow Lundberg & Palmgren (1947).

    Parameters
    ----------
    contact : PointContact
        From :func:`point_contact`.
    nu : float
        Poisson's ratio of the body whose stresses are wanted [-].
    index : int
        Which load of ``contact`` (flat index) [-].
    """
    nu, index = _check_nu_index(nu, index, np.size(contact.p_max))
    p0 = float(np.ravel(contact.p_max)[index])
    b = float(np.ravel(contact.b)[index])
    k = contact.ellipticity.k
    if k < 1.0:
        raise ConfigError(
            "subsurface_stresses: ellipse elongated along rolling (k < 1) not supported"
        )
    zs, Sx, Sy, Sz = _axis_stress_shape(round(k, 10), float(nu))
    s = np.vstack([Sx, Sy, Sz])
    tau = 0.5 * (s.max(axis=0) - s.min(axis=0))
    i = int(np.argmax(tau))
    dz, tmax = refine_peak(tau, i)  # parabolic refinement of the maximum (uniform depths)
    zmax = zs[i] + dz * (zs[1] - zs[0])
    t0, z0 = _lundberg_palmgren(1.0 / k)
    return SubsurfaceStresses(
        depth=zs * b,
        sigma_x=Sx * p0,
        sigma_y=Sy * p0,
        sigma_z=Sz * p0,
        tau_max=float(tmax * p0),
        tau_max_depth=float(zmax * b),
        tau_orth=t0 * p0,
        tau_orth_depth=z0 * b,
    )


# ----------------------------------------------------------------------------- line contact

#: Palmgren (1959) roller-raceway deflection of steel, one contact:
#: ``delta = 3.84e-5 Q^0.9 / l^0.8`` with delta [mm], Q [N], l [mm] (Harris & Kotzalas 2007,
#: eq. (6.58)); in SI: ``delta = C Q^0.9 / l^0.8`` with ``C = 3.84e-8 * 1e-3**0.8``.
PALMGREN_C_SI = 3.84e-5 * 1e-3 / (1e3) ** 0.8
#: effective modulus of steel on steel for which Palmgren's constant holds (E 207 GPa, nu 0.3)
_PALMGREN_E_EFF = 207e9 / (1 - 0.3**2)


@dataclass(frozen=True)
class LineContact:
    """Hertz line-contact result.

    Attributes
    ----------
    load : ndarray
        Normal load Q [N].
    b : ndarray
        Half-width of the contact strip [m].
    p_max : ndarray
        Maximum pressure ``2Q/(pi b l)`` [Pa].
    delta : ndarray
        Approach by Palmgren's formula [m].
    k_line : float
        ``Q = k_line delta^(10/9)`` [N/m^(10/9)].
    r_eff : float
        Effective radius ``R_x`` [m].
    length : float
        Contact length l [m].
    """

    load: NDArray[np.float64]
    b: NDArray[np.float64]
    p_max: NDArray[np.float64]
    delta: NDArray[np.float64]
    k_line: float
    r_eff: float
    length: float


def line_contact(load: ArrayLike, r_eff: float, length: float, e_eff: float) -> LineContact:
    """Hertz line contact and Palmgren load–deflection (exponent 10/9).

    ``b = sqrt(8 Q R / (pi l E'))``, ``p_max = 2 Q / (pi b l)`` (Johnson 1985, eqs. (4.43)–(4.45)
    with ``E* = E'/2``); ``delta = 3.84e-5 Q^0.9 / l^0.8`` (mm, N; Palmgren 1959, Harris &
    Kotzalas 2007 eq. (6.58)), scaled by ``(E'_steel/E')^0.9`` for other materials (the
    deflection of a line contact is inversely proportional to E' at fixed load shape).

    Parameters
    ----------
    load : array_like
        Normal load Q [N].
    r_eff : float
        Effective radius in the rolling direction [m].
    length : float
        Effective contact length l [m].
    e_eff : float
        Effective modulus ``E'`` [Pa].
    """
    q = _loads(load)
    R = check_positive("r_eff_m", r_eff, "m")
    ln = check_positive("length_m", length, "m")
    ee = check_positive("e_eff_pa", e_eff, "Pa")
    b = np.sqrt(8.0 * q * R / (math.pi * ln * ee))
    with np.errstate(invalid="ignore", divide="ignore"):
        p = np.where(q > 0, 2.0 * q / (math.pi * np.where(q > 0, b, 1.0) * ln), 0.0)
    scale = (_PALMGREN_E_EFF / ee) ** 0.9
    c = PALMGREN_C_SI * scale / ln**0.8
    delta = c * q**0.9
    k_line = c ** (-10.0 / 9.0)
    return LineContact(q, b, p, delta, k_line, R, ln)


def roller_race_radius(bearing: RollerBearing, race: Race | str) -> float:
    """Effective radius ``R_x`` [m] of a roller/raceway contact (roller radius with the inner
    raceway convex, outer concave)."""
    race = contact_race(race, "race")
    rc = 0.5 * bearing.element_diameter
    rr = bearing.inner_raceway_radius if race is Race.INNER else -bearing.outer_raceway_radius
    return 1.0 / (1.0 / rc + 1.0 / rr)


def roller_contact(bearing: RollerBearing, load: ArrayLike, race: Race | str) -> LineContact:
    """Line contact of a roller with a raceway of ``bearing`` (same material)."""
    if not isinstance(bearing, RollerBearing):
        raise ConfigError(
            f"bearing = {bearing.id!r} is not a roller bearing; line contact needs rollers"
        )
    e_eff = effective_modulus(bearing.material, bearing.material)
    return line_contact(load, roller_race_radius(bearing, race), bearing.roller_length, e_eff)


def element_stiffness(bearing: BallBearing | RollerBearing) -> tuple[float, float]:
    """Combined inner+outer constant and exponent of one rolling element: ``(K, n)`` with
    ``Q = K delta^n`` [N/m^n]; ``n = 1.5`` for balls, ``10/9`` for rollers."""
    if isinstance(bearing, BallBearing):
        return ball_stiffness(bearing), 1.5
    ki = roller_contact(bearing, 1.0, Race.INNER).k_line
    ko = roller_contact(bearing, 1.0, Race.OUTER).k_line
    return combined_stiffness(ki, ko, 10.0 / 9.0), 10.0 / 9.0


def line_subsurface_stresses(contact: LineContact, nu: float, index: int = 0) -> SubsurfaceStresses:
    """Stresses on the depth axis under the centre of a line contact (plane strain; McEwen 1949,
    Johnson 1985 eq. (4.75)): ``sigma_z = -p0/sqrt(1+s^2)``,
    ``sigma_x = -p0 [(1+2 s^2)/sqrt(1+s^2) - 2 s]``, ``sigma_y = nu (sigma_x + sigma_z)``,
    ``s = z/b``. The orthogonal shear ``tau_xz`` peaks at ``0.25 p0`` at depth ``0.5 b``
    (Johnson 1985, §4.2).

    Parameters
    ----------
    contact : LineContact
        From :func:`line_contact`.
    nu : float
        Poisson's ratio [-].
    index : int
        Which load (flat index).
    """
    nu, index = _check_nu_index(nu, index, np.size(contact.p_max))
    p0 = float(np.ravel(contact.p_max)[index])
    b = float(np.ravel(contact.b)[index])
    s = np.linspace(3.0 / 4000, 3.0, 4000)
    r = np.sqrt(1.0 + s * s)
    sz = -1.0 / r
    sx = -((1.0 + 2.0 * s * s) / r - 2.0 * s)
    sy = nu * (sx + sz)
    st = np.vstack([sx, sy, sz])
    tau = 0.5 * (st.max(0) - st.min(0))
    i = int(np.argmax(tau))
    return SubsurfaceStresses(
        depth=s * b,
        sigma_x=sx * p0,
        sigma_y=sy * p0,
        sigma_z=sz * p0,
        tau_max=float(tau[i] * p0),
        tau_max_depth=float(s[i] * b),
        tau_orth=0.25 * p0,
        tau_orth_depth=0.5 * b,
    )
