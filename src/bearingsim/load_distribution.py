"""Static radial load distribution over the discrete rolling elements (Stribeck/Harris).

Ball ``j`` sits at azimuth ``psi_j = cage_angle + (j-1) 2 pi / Z + psi_0`` measured from the +y axis
towards +x (seed VSM fig. 1). A rigid inner-ring displacement ``u = (u_x, u_y)`` compresses it by
``delta_j = (u_x sin psi_j + u_y cos psi_j) cos alpha - P_d/2`` and it carries
``Q_j = K max(delta_j, 0)^n`` (``n = 1.5`` balls, ``10/9`` rollers; ``K`` the combined
inner+outer constant, seed VSM eq. (10); ``alpha`` the nominal contact angle, 0 for every
catalogue bearing), whose radial component ``Q_j cos alpha`` balances the load (Harris &
Kotzalas 2007, §7.2 and §7.4 with no axial displacement: the axial components
``Q_j sin alpha`` go to the mounting). Writing ``delta_r = |u|`` and the displacement direction
``theta_u``, this is exactly the Harris form used by seed VSM eqs. (4)–(9):
``delta_j = delta_max {1 - (1 - cos(psi_j - theta_u))/(2 eps)}`` with
``delta_max = delta_r cos alpha - P_d/2``, ``eps = (1 - P_d/(2 delta_r cos alpha))/2`` and
load-zone half angle ``psi_L = arccos(P_d/(2 delta_r cos alpha))``. (Until the twenty-eighth
session ``alpha`` was left out: a user's bearing with ``alpha`` = 25 deg carried its load
with elements 1/cos alpha too light; a helper's exploratory testing.)

Two ring motions are offered (:class:`RingMotion`):

``FREE`` (default)
    ``u`` is free in the plane; both force components balance (``sum Q_j e_j = F``). With a
    finite number of balls the ring moves slightly off the load line at most cage angles.
``LOAD_LINE``
    ``u`` is constrained to the load direction ``theta_0`` (the textbook/seed form: solve
    ``sum Q_j cos(psi_j - theta_0) = F_r`` for ``delta_max``); the perpendicular force is then not
    balanced and is reported.

Both are solved for the actual element positions at every cage angle in a compiled kernel.
"""

from __future__ import annotations

import enum
import math
from dataclasses import dataclass

import numpy as np
from numba import njit
from numpy.typing import ArrayLike, NDArray

from .contact.capacity import check_load
from .contact.hertz import element_stiffness
from .errors import ConfigError, SolverError, check_range
from .geometry import Bearing, check_clearance, parse_enum

__all__ = [
    "check_angles",
    "LoadDistribution",
    "MAX_ANGLE_RAD",
    "radial_load_distribution",
    "RingMotion",
    "STRIBECK_CONSTANT",
    "STRIBECK_CONSTANT_LINE",
    "stribeck_qmax",
]


#: Largest magnitude of a cage or ball angle [rad]: 10^6 rad (about 160 000 turns). Beyond it the
#: spacing of double-precision numbers exceeds 1e-10 rad and the angle no longer places an
#: element (a cage angle of 1e30 deg gave delta_max = 9.8e54 m).
MAX_ANGLE_RAD = 1e6


def check_angles(name: str, values: ArrayLike) -> NDArray[np.float64]:
    """``values`` as a flat float array, each finite and within +/- :data:`MAX_ANGLE_RAD` [rad];
    else a one-line :class:`~bearingsim.errors.ConfigError` naming ``name``."""
    a = np.atleast_1d(np.asarray(values, dtype=float)).ravel()
    bad = np.flatnonzero(~(np.abs(a) <= MAX_ANGLE_RAD))
    if bad.size:
        i = int(bad[0])
        where = f"{name}[{i}]" if a.size > 1 else name
        check_range(where, float(a[i]), -MAX_ANGLE_RAD, MAX_ANGLE_RAD, unit="rad")
    return a


class RingMotion(enum.Enum):
    """Degrees of freedom of the inner ring in the radial-load solution."""

    FREE = "free"
    LOAD_LINE = "load_line"


@njit(cache=True)
def _force_1d(dr, cosines, factors, c, K, n, F):
    g = -F
    dg = 0.0
    for j in range(cosines.size):
        dj = dr * cosines[j] - c
        if dj > 0.0:
            q = factors[j] * K * dj**n
            g += q * cosines[j]
            dg += n * q / dj * cosines[j] * cosines[j]
    return g, dg


@njit(cache=True)
def _solve_1d(cosines, factors, c, K, n, F):
    """Root of the nondecreasing ``g(dr) = sum K (dr cos_j - c)_+^n cos_j - F``."""
    if F <= 0.0:
        return 0.0
    lo = 0.0
    kmax = 0.0
    for j in range(factors.size):
        kmax = max(kmax, factors[j])
    hi = max(c, 0.0) + (F / (K * kmax)) ** (1.0 / n) + 1e-12
    for _ in range(200):
        g, _dg = _force_1d(hi, cosines, factors, c, K, n, F)
        if g > 0.0:
            break
        hi *= 2.0
    x = hi
    for _ in range(200):
        g, dg = _force_1d(x, cosines, factors, c, K, n, F)
        if g > 0.0:
            hi = x
        else:
            lo = x
        if abs(g) <= 1e-14 * F:
            return x
        xn = x - g / dg if dg > 0.0 else 0.5 * (lo + hi)
        if not (lo < xn < hi):
            xn = 0.5 * (lo + hi)
        if hi - lo <= 1e-16 * hi:
            return xn
        x = xn
    return x


@njit(cache=True)
def _potential(ux, uy, sn, cs, factors, c, K, n, fx, fy):
    p = -(fx * ux + fy * uy)
    for j in range(sn.size):
        dj = ux * sn[j] + uy * cs[j] - c
        if dj > 0.0:
            p += factors[j] * K * dj ** (n + 1.0) / (n + 1.0)
    return p


@njit(cache=True, inline="always")
def _gradient(ux, uy, sn, cs, factors, c, K, n, fx, fy):
    """Force residual ``sum Q_j e_j - F`` [N] and its Jacobian entries [N/m] at ``u``."""
    gx = -fx
    gy = -fy
    jxx = 0.0
    jxy = 0.0
    jyy = 0.0
    for j in range(sn.size):
        dj = ux * sn[j] + uy * cs[j] - c
        if dj > 0.0:
            q = factors[j] * K * dj**n
            gx += q * sn[j]
            gy += q * cs[j]
            kk = n * q / dj
            jxx += kk * sn[j] * sn[j]
            jxy += kk * sn[j] * cs[j]
            jyy += kk * cs[j] * cs[j]
    return gx, gy, jxx, jxy, jyy


@njit(cache=True)
def _residual(ux, uy, sn, cs, factors, c, K, n, fx, fy):
    gx, gy, _a, _b, _c = _gradient(ux, uy, sn, cs, factors, c, K, n, fx, fy)
    return math.hypot(gx, gy)


@njit(cache=True)
def _solve_2d(ux, uy, sn, cs, factors, c, K, n, fx, fy):
    """Newton with backtracking on the convex potential; returns (ux, uy, rel residual)."""
    F = math.hypot(fx, fy)
    scale = F if F > 0.0 else 1.0
    res = 0.0
    for _ in range(100):
        gx, gy, jxx, jxy, jyy = _gradient(ux, uy, sn, cs, factors, c, K, n, fx, fy)
        res = math.hypot(gx, gy) / scale
        if res <= 1e-13:
            break
        tr = jxx + jyy
        reg = 1e-12 * tr + 1e-300
        a11 = jxx + reg
        a22 = jyy + reg
        det = a11 * a22 - jxy * jxy
        if det <= 0.0 or not math.isfinite(det):
            # degenerate (one or no element in contact): gradient step
            sx = -gx / (tr + 1.0)
            sy = -gy / (tr + 1.0)
        else:
            sx = -(a22 * gx - jxy * gy) / det
            sy = -(-jxy * gx + a11 * gy) / det
        # backtracking: accept a step that lowers the convex potential (Armijo) or, near the
        # solution where the potential is flat to round-off, one that lowers the residual
        p0 = _potential(ux, uy, sn, cs, factors, c, K, n, fx, fy)
        slope = gx * sx + gy * sy
        t = 1.0
        for _ls in range(60):
            p1 = _potential(ux + t * sx, uy + t * sy, sn, cs, factors, c, K, n, fx, fy)
            if p1 <= p0 + 1e-4 * t * slope:
                break
            if (
                _residual(ux + t * sx, uy + t * sy, sn, cs, factors, c, K, n, fx, fy)
                < (1.0 - 1e-4 * t) * res * scale
            ):
                break
            t *= 0.5
        ux += t * sx
        uy += t * sy
    return ux, uy, res


@njit(cache=True)
def _distribute(cage, psi0, Z, factors, c, K, n, fx, fy, free, out_u, out_res):
    F = math.hypot(fx, fy)
    th0 = math.atan2(fx, fy)
    sn = np.empty(Z)
    cs = np.empty(Z)
    cosl = np.empty(Z)
    for i in range(cage.size):
        for j in range(Z):
            psi = cage[i] + psi0 + 2.0 * math.pi * j / Z
            sn[j] = math.sin(psi)
            cs[j] = math.cos(psi)
            cosl[j] = math.cos(psi - th0)
        f = factors[i]
        dr = _solve_1d(cosl, f, c, K, n, F)
        ux = dr * math.sin(th0)
        uy = dr * math.cos(th0)
        if free:
            ux, uy, res = _solve_2d(ux, uy, sn, cs, f, c, K, n, fx, fy)
        else:
            gx = -fx
            gy = -fy
            for j in range(Z):
                dj = ux * sn[j] + uy * cs[j] - c
                if dj > 0.0:
                    q = f[j] * K * dj**n
                    gx += q * sn[j]
                    gy += q * cs[j]
            # residual along the load line (the equation solved)
            gl = gx * math.sin(th0) + gy * math.cos(th0)
            res = abs(gl) / (F if F > 0.0 else 1.0)
        out_u[i, 0] = ux
        out_u[i, 1] = uy
        out_res[i] = res


@dataclass(frozen=True)
class LoadDistribution:
    """Radial load distribution at one or more cage angles (arrays have a leading cage axis).

    Attributes
    ----------
    fx, fy : float
        Applied force components on the inner ring [N].
    fr : float
        Radial load magnitude ``F_r`` [N].
    theta0 : float
        Load direction from +y towards +x [rad].
    cage_angle : ndarray, shape (m,)
        Cage angles [rad].
    ball_angles : ndarray, shape (m, Z)
        Element azimuths psi_j [rad].
    ball_deflections : ndarray, shape (m, Z)
        Contact deflections ``delta_j`` (negative = gap) [m].
    ball_loads : ndarray, shape (m, Z)
        Element loads Q_j [N].
    displacement : ndarray, shape (m, 2)
        Inner-ring displacement (u_x, u_y) [m].
    delta_r : ndarray, shape (m,)
        ``|u|``, relative radial displacement of the rings [m].
    delta_max : ndarray, shape (m,)
        ``delta_r cos alpha - P_d/2``, deflection on the displacement line [m].
    epsilon : ndarray, shape (m,)
        Load-distribution factor ``(1 - P_d/(2 delta_r cos alpha))/2`` [-]; above 1 every element is
        loaded. With a preload (``P_d < 0``) it grows without bound as the radial load goes to
        0, and is ``inf`` at zero load (JSON: ``null``).
    psi_l : ndarray, shape (m,)
        Load-zone half angle ``arccos(P_d/(2 delta_r cos alpha))`` [rad], clipped to [0, pi].
    n_loaded : ndarray, shape (m,)
        Number of elements with ``Q_j > 0`` [-].
    residual : ndarray, shape (m,)
        Relative force-balance residual [-] (vector for FREE, load-line component for
        LOAD_LINE).
    stiffness : float
        Element load–deflection constant K [N/m^n].
    exponent : float
        Load–deflection exponent n [-].
    clearance : float
        Diametral clearance P_d used [m].
    motion : RingMotion
        Ring degrees of freedom used.
    contact_angle : float
        Nominal contact angle alpha of the bearing [rad] (the elements' radial share
        ``cos alpha``).
    """

    fx: float
    fy: float
    fr: float
    theta0: float
    cage_angle: NDArray[np.float64]
    ball_angles: NDArray[np.float64]
    ball_deflections: NDArray[np.float64]
    ball_loads: NDArray[np.float64]
    displacement: NDArray[np.float64]
    delta_r: NDArray[np.float64]
    delta_max: NDArray[np.float64]
    epsilon: NDArray[np.float64]
    psi_l: NDArray[np.float64]
    n_loaded: NDArray[np.int64]
    residual: NDArray[np.float64]
    stiffness: float
    exponent: float
    clearance: float
    motion: RingMotion
    contact_angle: float = 0.0

    @property
    def force_residual(self) -> NDArray[np.float64]:
        """Vector residual ``sum Q_j cos(alpha) e_j - F`` per cage angle, shape (m, 2) [N]."""
        q = self.ball_loads * math.cos(self.contact_angle)
        sn, cs = np.sin(self.ball_angles), np.cos(self.ball_angles)
        return np.stack([(q * sn).sum(1) - self.fx, (q * cs).sum(1) - self.fy], 1)

    def plot(self, index: int = 0):
        """Polar bar plot of the element loads at cage angle ``index``; returns the Figure."""
        from .plotting import HALF_WIDTH, new_figure

        fig, ax = new_figure(width=HALF_WIDTH, height=5.0, polar=True)
        ax.set_theta_zero_location("N")
        ax.set_theta_direction(-1)
        ang = self.ball_angles[index]
        ax.bar(ang, self.ball_loads[index], width=0.15, color="tab:blue", alpha=0.8)
        psl = self.psi_l[index]
        th = math.atan2(*self.displacement[index])
        for s in (-1, 1):
            ax.plot([th + s * psl] * 2, [0, self.ball_loads[index].max() * 1.1], "r--", lw=1)
        ax.set_ylabel("element load Q [N]", labelpad=28)
        ax.set_title(
            f"element loads at their angles (0° at the top): F_r = {self.fr:.4g} N,\n"
            f"load zone ψ_L = ±{math.degrees(psl):.1f}° (red dashes)"
        )
        return fig


def radial_load_distribution(
    bearing: Bearing,
    fx: float,
    fy: float,
    cage_angle: ArrayLike = 0.0,
    *,
    clearance: float | None = None,
    first_element_angle: float = 0.0,
    motion: RingMotion | str = RingMotion.FREE,
    stiffness: float | None = None,
    element_factors: ArrayLike | None = None,
    allow_overload: bool | None = False,
) -> LoadDistribution:
    """Static radial load distribution over the discrete elements (SPEC §0.4; Harris & Kotzalas
    2007, §7.2; seed VSM eqs. (4)–(9), (16)).

    Parameters
    ----------
    bearing : BallBearing or RollerBearing
        Geometry and material.
    fx, fy : float
        Radial force components on the inner ring [N] (x horizontal, y vertical reference).
    cage_angle : float or array_like
        Cage angle(s) [rad], each within +/- :data:`MAX_ANGLE_RAD`; vectorised.
    clearance : float, optional
        Diametral clearance P_d [m] overriding the bearing's; negative = preload; within
        :func:`bearingsim.geometry.clearance_range` (ISO 5753-1).
    first_element_angle : float
        Azimuth of element 1 at cage angle 0, ``alpha_0`` [rad], in [-2 pi, 2 pi].
    motion : RingMotion
        ``FREE`` (both force components balanced, default) or ``LOAD_LINE`` (seed form).
    stiffness : float, optional
        Element constant K [N/m^n] overriding the Hertz value of the bearing.
    element_factors : array_like, optional
        Per-element multipliers of K, shape (Z,) or (m, Z) [-] (e.g. seed VSM's ``mu_i``).
    allow_overload : bool or None
        The radial load is checked against the static capacity before the solution
        (:func:`bearingsim.contact.capacity.check_load`: a warning above ``C_0``, refused above
        ``2 C_0``); ``True`` runs an overload anyway, ``None`` skips the check (a caller that
        has made it).
    """
    motion = parse_enum(RingMotion, motion, "motion")
    fx = check_range("fx_n", fx, unit="N") + 0.0  # -0.0 -> 0.0 (the load direction)
    fy = check_range("fy_n", fy, unit="N") + 0.0
    Pd = bearing.diametral_clearance if clearance is None else clearance
    Pd = check_clearance(bearing, Pd, "clearance_m")
    psi0 = check_range(
        "first_element_angle_rad", first_element_angle, -2 * math.pi, 2 * math.pi, unit="rad"
    )
    cage = check_angles("cage_angle_rad", cage_angle)
    K, n = element_stiffness(bearing)
    if stiffness is not None:
        K = check_range("stiffness", stiffness, 0.0, lo_open=True, unit="N/m^n")
    Z = bearing.n_elements
    if element_factors is None:
        fac = np.ones((cage.size, Z))
    else:
        try:
            fac = np.asarray(element_factors, dtype=float)
            fac = np.broadcast_to(fac, (cage.size, Z)).copy()
        except (TypeError, ValueError):
            shape = np.shape(element_factors)
            raise ConfigError(
                f"element_factors of shape {shape} is invalid; valid: numbers of shape ({Z},) "
                f"or ({cage.size}, {Z}), one per element"
            ) from None
        if not np.all(np.isfinite(fac)) or np.any(fac < 0):
            raise ConfigError("element_factors must be finite and >= 0; valid range [0, inf)")
        if np.any(np.all(fac == 0.0, axis=1)):
            raise ConfigError(
                "element_factors are all 0: no element carries load; valid: at least one > 0"
            )
    fr = math.hypot(fx, fy)
    check_load(bearing, fr, allow_overload, name="|(fx_n, fy_n)|")
    if fr == 0.0 and Pd > 0:
        raise ConfigError(
            "radial load = 0 N with positive clearance: the ring position is undetermined; "
            "valid range (0, inf) N"
        )
    # the problem in u' = u cos(alpha): delta_j = u' . e_j - P_d/2 and sum Q_j e_j = F/cos(alpha),
    # the contact angle's zero form (exact for alpha = 0: x / 1.0 is x)
    ca = math.cos(bearing.contact_angle)
    u = np.empty((cage.size, 2))
    res = np.empty(cage.size)
    _distribute(
        cage, psi0, Z, fac, 0.5 * Pd, K, n, fx / ca, fy / ca, motion is RingMotion.FREE, u, res
    )
    if not np.all(np.isfinite(u)):
        raise SolverError(
            "radial load distribution: no equilibrium found (non-finite displacement)"
        )
    psi = cage[:, None] + psi0 + 2.0 * np.pi * np.arange(Z)[None, :] / Z
    dj = u[:, :1] * np.sin(psi) + u[:, 1:] * np.cos(psi) - 0.5 * Pd
    Q = fac * K * np.maximum(dj, 0.0) ** n
    dr = np.hypot(u[:, 0], u[:, 1])  # |u'| = delta_r cos(alpha)
    # P_d/(2 delta_r); at delta_r = 0 (no radial load) its limit: 0 without clearance (half
    # the elements at the edge of loading, Harris), -inf with a preload (every element
    # loaded equally: epsilon infinite, psi_l = pi; it was 0.5 and pi/2 there, while every
    # element carried load)
    at_rest = -math.inf if Pd < 0 else 0.0
    with np.errstate(divide="ignore", invalid="ignore"):
        ratio = np.where(dr > 0, 0.5 * Pd / np.where(dr > 0, dr, 1.0), at_rest)
    return LoadDistribution(
        fx=fx,
        fy=fy,
        fr=fr,
        theta0=math.atan2(fx, fy),
        cage_angle=cage,
        ball_angles=psi,
        ball_deflections=dj,
        ball_loads=Q,
        displacement=u / ca,
        delta_r=dr / ca,
        delta_max=dr - 0.5 * Pd,
        epsilon=0.5 * (1.0 - ratio),
        psi_l=np.arccos(np.clip(ratio, -1.0, 1.0)),
        n_loaded=(Q > 0).sum(axis=1),
        residual=res,
        stiffness=K,
        exponent=n,
        clearance=Pd,
        motion=motion,
        contact_angle=float(bearing.contact_angle),
    )


STRIBECK_CONSTANT = 4.37
"""Stribeck's ``Q_max = 4.37 F_r / (Z cos alpha)`` for point contact (ball bearings, zero
clearance; Harris & Kotzalas 2007, eq. (7.26); seed LIFE §2.1; seed IAS eq. (2) uses it for its
roller bearing, and the IAS model keeps the seed's value)."""

STRIBECK_CONSTANT_LINE = 4.08
"""The same for line contact (roller bearings, load exponent 10/9; Harris & Kotzalas 2007,
§7.2): ``Q_max = 4.08 F_r / (Z cos alpha)``; the discrete distribution gives 4.07 on the
NU204-ECP's 11 rollers."""


def stribeck_qmax(bearing: Bearing, radial_load: float) -> float:
    """Stribeck's estimate of the most-loaded element load ``4.37 F_r / (Z cos alpha)`` [N]
    (ball bearings; ``4.08`` for roller bearings, :data:`STRIBECK_CONSTANT_LINE`: until the
    twenty-eighth session a roller bearing got the ball bearings' 4.37, 7 % high; a helper's
    exploratory testing)."""
    from .geometry import RollerBearing

    fr = check_range("radial_load_n", radial_load, 0.0, unit="N")
    c = STRIBECK_CONSTANT_LINE if isinstance(bearing, RollerBearing) else STRIBECK_CONSTANT
    return c * fr / (bearing.n_elements * math.cos(bearing.contact_angle))
