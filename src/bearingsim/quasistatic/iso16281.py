"""ISO/TS 16281:2008 internal load distribution of a single-row radial ball bearing.

An independent implementation (NumPy + SciPy ``root``, finite-difference stiffness) used to
cross-check the Jones model of :mod:`bearingsim.quasistatic.jones`. We could not consult the
standard itself; the formulas below are the ones of its clause 4.2 (ball bearings) and 6.3
(reference geometry) as transcribed in public re-implementations and summaries. What each step is:

* **Reference geometry** (ISO/TS 16281 §6.3, deep-groove and angular-contact ball bearings): when
  the bearing gives no groove radii, ``r_i = 0.52 D_w`` and ``r_e = 0.53 D_w``
  (``conformities=Conformities.ISO`` forces these defaults).
* **Clearance** (§4.2): ``A = r_i + r_e - D_w``, initial contact angle
  ``alpha_0 = arccos(1 - s_r/(2A))`` from the radial operating clearance ``s_r`` (our diametral
  ``P_d``), axial clearance ``s_a = 2 A sin(alpha_0)``, inner groove-centre radius
  ``R_i = D_pw/2 + (r_i - D_w/2) cos(alpha_0)``.
* **Simplified stiffness constant** (§4.2): one constant for the ball with both contacts,
  evaluated once at the nominal contact angle,
  ``c_p = 1.48 E/(1 - nu^2) [K(chi_i) (Sigma rho_i / (chi_i^2 E(chi_i)))^(1/3)
  + K(chi_e) (Sigma rho_e / (chi_e^2 E(chi_e)))^(1/3)]^(-3/2)`` with the curvature sums
  ``Sigma rho_i = 2/D_w (2 + gamma/(1 - gamma) - D_w/(2 r_i))``,
  ``Sigma rho_e = 2/D_w (2 - gamma/(1 + gamma) - D_w/(2 r_e))``, ``gamma = D_w cos(alpha)/D_pw``,
  the ellipticity ``chi`` solving ``1 - 2/(chi^2 - 1) (K(chi)/E(chi) - 1) = F(rho)`` with the
  relative curvature differences ``F(rho)``, and ``K``, ``E`` the complete elliptic integrals of
  parameter ``1 - 1/chi^2``.
* **Element deflection** (§4.2, eq. (12) of the transcription), generalised here from the
  standard's load plane to both radial and both tilt directions (our extension):
  ``delta_j = sqrt((A cos(alpha_0) + d_x sin psi_j + d_y cos psi_j)^2
  + (A sin(alpha_0) + d_a + R_i (sin(t_x) cos psi_j - sin(t_y) sin psi_j))^2) - A``,
  ``Q_j = c_p delta_j^1.5``, ``tan(alpha_j) = (axial term)/(radial term)``; ``d_a`` is measured
  from the one-sided contact position, so our centred ``z = d_a + s_a/2``. A misalignment enters as
  a tilt of arm ``R_i`` (the standard knows only the relative ring tilt).
* **Equilibrium** (§4.2, eqs. (16)–(18)): ``F_r = sum Q cos(alpha) cos(psi)``,
  ``F_a = sum Q sin(alpha)``, ``M = (D_pw/2) sum Q sin(alpha) cos(psi)`` — the moment arm is the
  pitch radius, not ``R_i``, so the ISO system is not the exact gradient of an energy and its
  stiffness matrix is only nearly symmetric.

Solved with SciPy's MINPACK ``hybr`` from an ISO-style start (independent of the Jones solver);
the 5x5 stiffness is the central finite difference of the equilibrium forces.
"""

from __future__ import annotations

import enum
import math
from dataclasses import replace

import numpy as np
from numpy.typing import ArrayLike, NDArray
from scipy.optimize import brentq, root
from scipy.special import ellipe, ellipk

from ..contact.capacity import check_load
from ..errors import ConfigError, SolverError, check_range
from ..geometry import (
    ISO_INNER_CONFORMITY,
    ISO_OUTER_CONFORMITY,
    BallBearing,
    Bearing,
    check_speed_limit,
    parse_enum,
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

__all__ = [
    "ISO_CP_FACTOR",
    "ISO_INNER_CONFORMITY",
    "ISO_OUTER_CONFORMITY",
    "Conformities",
    "iso_geometry",
    "iso_stiffness_constant",
    "run_iso16281",
]


#: constant of the ISO/TS 16281 §4.2 simplified stiffness (steel-independent form, E/(1-nu^2)
#: factored out)
ISO_CP_FACTOR = 1.48
#: Stribeck's ``Q_max = 5 F_r / Z`` for a ball bearing with nominal clearance (Stribeck 1901;
#: Harris & Kotzalas 2007 vol. 1 §7.2), used only for the solver's starting point
_STRIBECK_CLEARANCE = 5.0


class Conformities(enum.Enum):
    """Groove conformities used by the ISO method."""

    #: the groove radii of the bearing
    BEARING = "bearing"
    #: the ISO/TS 16281 §6.3 reference values ``r_i = 0.52 D_w``, ``r_e = 0.53 D_w``
    ISO = "iso"


def _chi(F_rho: float) -> float:
    """Ellipticity ``chi = a/b`` solving ``1 - 2/(chi^2-1) (K/E - 1) = F(rho)`` (ISO/TS 16281
    §4.2)."""

    def g(c: float) -> float:
        m = 1.0 - 1.0 / (c * c)
        return 1.0 - 2.0 / (c * c - 1.0) * (ellipk(m) / ellipe(m) - 1.0) - F_rho

    return brentq(g, 1.0 + 1e-9, 1e3, xtol=1e-14, rtol=1e-14)


def iso_stiffness_constant(
    d: float,
    dm: float,
    r_i: float,
    r_e: float,
    contact_angle: float,
    youngs_modulus: float,
    poisson_ratio: float,
) -> float:
    """ISO/TS 16281 §4.2 simplified ball stiffness constant ``c_p`` [N/m^1.5], ``Q = c_p
    delta^1.5`` with ``delta`` the total (inner + outer) approach.

    Parameters
    ----------
    d, dm : float
        Ball diameter D_w and pitch diameter D_pw [m].
    r_i, r_e : float
        Inner and outer groove radii [m].
    contact_angle : float
        Nominal contact angle [rad].
    youngs_modulus : float
        E [Pa].
    poisson_ratio : float
        nu [-].
    """
    g = d * math.cos(contact_angle) / dm
    s_i = 2.0 / d * (2.0 + g / (1.0 - g) - d / (2.0 * r_i))
    s_e = 2.0 / d * (2.0 - g / (1.0 + g) - d / (2.0 * r_e))
    F_i = (g / (1.0 - g) + d / (2.0 * r_i)) / (2.0 + g / (1.0 - g) - d / (2.0 * r_i))
    F_e = (-g / (1.0 + g) + d / (2.0 * r_e)) / (2.0 - g / (1.0 + g) - d / (2.0 * r_e))
    terms = 0.0
    for s, F in ((s_i, F_i), (s_e, F_e)):
        c = _chi(F)
        m = 1.0 - 1.0 / (c * c)
        terms += ellipk(m) * (s / (c * c * ellipe(m))) ** (1.0 / 3.0)
    return ISO_CP_FACTOR * youngs_modulus / (1.0 - poisson_ratio**2) * terms**-1.5


def iso_geometry(
    bearing: Bearing,
    clearance: float | None = None,
    conformities: Conformities | str = Conformities.BEARING,
    max_contact_angle: float | None = None,
    stiffness: float | None = None,
) -> tuple[QSGeometry, float, float]:
    """Derived geometry, ``c_p`` and ``R_i`` of the ISO method (ISO/TS 16281 §4.2, §6.3).

    Parameters
    ----------
    bearing : BallBearing
        Geometry and material.
    clearance : float, optional
        Diametral clearance P_d [m] overriding the bearing's.
    conformities : Conformities or {"bearing", "iso"}
        Groove radii of the bearing or the ISO reference values.
    max_contact_angle : float, optional
        Largest admissible contact angle [rad].
    stiffness : float, optional
        Ball constant [N/m^1.5] overriding ``c_p``.

    Returns
    -------
    tuple
        ``(geometry, c_p [N/m^1.5], R_i [m])``; ``geometry.k`` holds ``c_p`` (or the override
        ``stiffness``).
    """
    if not isinstance(bearing, BallBearing):
        raise ConfigError(
            f"bearing = {bearing.id!r} is a {bearing.kind} bearing; ISO/TS 16281 "
            "ball method needs a ball bearing"
        )
    conformities = parse_enum(Conformities, conformities, "conformities")
    d = bearing.element_diameter
    if conformities is Conformities.ISO:
        bearing = replace(
            bearing,
            inner_groove_radius=ISO_INNER_CONFORMITY * d,
            outer_groove_radius=ISO_OUTER_CONFORMITY * d,
        )
    base = qs_geometry(bearing, clearance, max_contact_angle)
    cp = iso_stiffness_constant(
        d,
        bearing.pitch_diameter,
        bearing.inner_groove_radius,
        bearing.outer_groove_radius,
        bearing.contact_angle,
        bearing.material.youngs_modulus,
        bearing.material.poisson_ratio,
    )
    k = (
        cp
        if stiffness is None
        else check_range("stiffness", stiffness, 0.0, lo_open=True, unit="N/m^1.5")
    )
    # ISO: R_i = D_pw/2 + (r_i - D_w/2) cos(alpha_0)  (same as seed QS5 eq. (5))
    geom = replace(base, k=k)
    return geom, cp, geom.r_pi


def _forces(
    u: NDArray[np.float64],
    psi: NDArray[np.float64],
    moff: NDArray[np.float64],
    geom: QSGeometry,
    Ri: float,
) -> tuple[NDArray[np.float64], NDArray[np.float64], NDArray[np.float64], NDArray[np.float64]]:
    """ISO equilibrium forces ``(Fx, Fy, Fz, Mx, My)`` and per-ball (Q, alpha, delta)."""
    s, c = np.sin(psi), np.cos(psi)
    ax = u[2] + Ri * (math.sin(u[3]) * c - math.sin(u[4]) * s) + moff
    ra = geom.y0 + u[0] * s + u[1] * c
    dl = np.hypot(ax, ra) - geom.a0
    Q = geom.k * np.maximum(dl, 0.0) ** 1.5
    al = np.arctan2(ax, ra)
    qa, qr = Q * np.sin(al), Q * np.cos(al)
    arm = 0.5 * geom.dm  # ISO/TS 16281 eq. (18): moment arm D_pw/2
    F = np.array(
        [np.sum(qr * s), np.sum(qr * c), np.sum(qa), arm * np.sum(qa * c), -arm * np.sum(qa * s)]
    )
    return F, Q, al, dl


def _start(geom: QSGeometry, psi: NDArray[np.float64], F: NDArray[np.float64]) -> NDArray:
    """ISO-style start: radial deflection from Stribeck's ``Q_max = 5 F_r / Z`` (at least the
    displacement that brings the ball nearest the load line into contact) and axial from
    equal ball loads at the free contact angle; tilts 0."""
    u = np.zeros(5)
    fr = math.hypot(F[0], F[1])
    if fr > 0:
        dmax = (_STRIBECK_CLEARANCE * fr / (geom.n_balls * geom.k)) ** (2.0 / 3.0)
        dr = dmax + 0.5 * geom.clearance
        # a small load with clearance: no ball may reach contact when none sits on the load
        # line (the solver then sees no force at all); move far enough for the nearest ball
        cmax = float(np.max(np.cos(psi - math.atan2(F[0], F[1]))))
        if geom.clearance > 0 and dr * cmax <= 0.5 * geom.clearance:
            dr = dmax + 0.5 * geom.clearance / cmax
        u[0], u[1] = dr * F[0] / fr, dr * F[1] / fr
    if F[2] != 0:
        da = abs(F[2]) / (geom.n_balls * geom.k * max(math.sin(geom.free_contact_angle), 0.1))
        u[2] = math.copysign(0.5 * geom.axial_clearance + da ** (2.0 / 3.0) * 2.0, F[2])
    return u


def _solve_free(
    u: NDArray[np.float64],
    idx: NDArray[np.int64],
    psi: NDArray[np.float64],
    moff: NDArray[np.float64],
    geom: QSGeometry,
    Ri: float,
    F: NDArray[np.float64],
    fscale: float,
) -> tuple[NDArray[np.float64], int]:
    """Solve the equilibrium of the DOFs ``idx`` (others held) with MINPACK ``hybr``, falling
    back to Levenberg–Marquardt; unknowns scaled to micrometres (tilts: um / R_i)."""
    if idx.size == 0:
        return u, 0
    scale = np.array([1e-6, 1e-6, 1e-6, 1e-6 / Ri, 1e-6 / Ri])[idx]

    def fun(x: NDArray[np.float64]) -> NDArray[np.float64]:
        uu = u.copy()
        uu[idx] = x * scale
        r = _forces(uu, psi, moff, geom, Ri)[0] - F
        r[3:] /= Ri
        return r[idx] / fscale

    best, nfev = None, 0
    for method, opts in (
        ("hybr", {"xtol": 1e-13, "maxfev": 2000}),
        ("lm", {"xtol": 1e-15, "ftol": 1e-15, "maxiter": 5000}),
    ):
        sol = root(fun, u[idx] / scale, method=method, options=opts)
        nfev += int(sol.get("nfev", 0))
        nrm = float(np.linalg.norm(fun(sol.x)))
        if best is None or nrm < best[1]:
            best = (sol.x, nrm)
        if nrm < 1e-12:
            break
    out = u.copy()
    out[idx] = best[0] * scale
    return out, nfev


def _attempt(
    start: NDArray[np.float64] | None,
    idx: NDArray[np.int64],
    psi: NDArray[np.float64],
    moff: NDArray[np.float64],
    geom: QSGeometry,
    Ri: float,
    F: NDArray[np.float64],
    fscale: float,
) -> tuple[NDArray[np.float64], int, float]:
    """Solve the free DOFs ``idx`` from ``start`` (``None``: the ISO-style start, translations
    solved first with the tilts at 0); returns the solution, the function evaluations of the
    last solve and the residual relative to ``max(fscale, sum Q)`` (moments over ``R_i``)."""
    if start is None:
        start, _ = _solve_free(_start(geom, psi, F), idx[idx < 3], psi, moff, geom, Ri, F, fscale)
    u, nfev = _solve_free(start, idx, psi, moff, geom, Ri, F, fscale)
    Fq, Q, _al, _dl = _forces(u, psi, moff, geom, Ri)
    r = Fq - F
    r[3:] /= Ri
    return u, nfev, float(np.linalg.norm(r[idx])) / max(fscale, float(np.sum(Q)), 1e-300)


# (duplicates) the signature of jones.run_quasi_static on purpose: the two methods take the
# same loads and options, so either can be passed where the other is (method=...)
def run_iso16281(
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
    conformities: Conformities | str = Conformities.BEARING,
    max_contact_angle: float | None = None,
    stiffness: float | None = None,
    speed: SpeedEffects | None = None,
    tol: float = 1e-12,
    allow_overload: bool | None = False,
) -> QuasiStaticSolution:
    """ISO/TS 16281 ball-bearing load distribution at each cage angle (module docstring).

    Parameters as :func:`bearingsim.quasistatic.jones.run_quasi_static`, plus ``conformities``
    (:class:`Conformities`: ``BEARING``, the groove radii of the bearing, or ``ISO``, the
    ISO/TS 16281 §6.3 defaults 0.52/0.53). ``stiffness`` overrides ``c_p`` [N/m^1.5] (to
    isolate kinematic differences). Inertia loads are not part of ISO/TS 16281. The load is
    checked against the static capacity first (``allow_overload``, as ``run_quasi_static``).
    """
    if speed is not None and speed.active:
        raise ConfigError(
            "centrifugal/gyroscopic loads are not part of the ISO/TS 16281 method; "
            "valid: method 'jones' for inertia loads"
        )
    if speed is not None:
        check_speed_limit(bearing, speed.shaft_speed * 30.0 / math.pi, "shaft speed", "[0")
    geom, _cp, Ri = iso_geometry(bearing, clearance, conformities, max_contact_angle, stiffness)
    case = _validate_case(
        geom,
        cage_angles,
        (fx, fy, fz, mx, my),
        misalignment,
        ball_errors,
        first_ball_angle,
        tilt_free,
        False,
    )
    mis, cage, F, free = case.misalignment, case.cage, case.applied, case.free
    check_load(
        bearing, math.hypot(F[0], F[1]), allow_overload, F[2], name=_RADIAL, axial_name="fz_n"
    )
    Z = geom.n_balls
    m = cage.size
    idx = np.flatnonzero(free)
    # force scale of the equations: the applied load (1 N when only a preload acts)
    fnorm = float(np.linalg.norm(np.r_[F[:3], F[3:] / Ri]))
    fscale = fnorm if fnorm > 0.0 else 1.0
    out = {k: np.zeros((m, Z)) for k in ("Q", "al", "dl")}
    U = np.zeros((m, 5))
    H = np.zeros((m, 5, 5))
    R = np.zeros((m, 5))
    res = np.zeros(m)
    its = np.zeros(m, dtype=np.int64)
    u = None
    for i, cg in enumerate(cage):
        psi = _ball_azimuths(cg, case.first_ball_angle, case.ball_errors)
        sh = cg / geom.cage_ratio
        azi = mis.inner_azimuth + sh
        ti = (mis.inner_tilt * math.sin(azi), mis.inner_tilt * math.cos(azi))
        to = (
            mis.outer_tilt * math.sin(mis.outer_azimuth),
            mis.outer_tilt * math.cos(mis.outer_azimuth),
        )
        c, s = np.cos(psi), np.sin(psi)
        moff = Ri * (
            (math.sin(ti[0]) - math.sin(to[0])) * c - (math.sin(ti[1]) - math.sin(to[1])) * s
        )

        u, nfev, rel = _attempt(u, idx, psi, moff, geom, Ri, F, fscale)
        if not rel <= 1e-8 and i > 0:
            # started from the previous cage angle and failed (a load carried by one or two
            # balls, the ring sliding between them): start again as at the first angle, once
            u2, nfev2, rel2 = _attempt(None, idx, psi, moff, geom, Ri, F, fscale)
            if rel2 <= 1e-8:
                u, nfev, rel = u2, nfev + nfev2, rel2
        if not np.isfinite(rel) or rel > 1e-8:
            raise SolverError(
                f"ISO/TS 16281: no equilibrium found at cage angle {cg:.6g} rad "
                f"(relative residual {rel:.3g}); check the load and clearance"
            )
        Fq, Q, al, dl = _forces(u, psi, moff, geom, Ri)
        # 5x5 stiffness by central differences of the equilibrium forces
        hs = np.array([1e-9, 1e-9, 1e-9, 1e-9 / Ri, 1e-9 / Ri])
        for k in range(5):
            up, um = u.copy(), u.copy()
            up[k] += hs[k]
            um[k] -= hs[k]
            H[i, :, k] = (
                _forces(up, psi, moff, geom, Ri)[0] - _forces(um, psi, moff, geom, Ri)[0]
            ) / (2 * hs[k])
        U[i], R[i], res[i], its[i] = u, Fq, rel, nfev
        out["Q"][i], out["al"][i], out["dl"][i] = Q, al, dl
    from .jones import check_moment_ball_load

    check_moment_ball_load(bearing, F, out["Q"], allow_overload)
    amax = np.max(np.abs(out["al"]) * (out["Q"] > 0))
    if amax > geom.max_contact_angle:
        raise SolverError(
            f"no equilibrium the geometry allows: contact angle {math.degrees(amax):.1f} deg "
            f"beyond the groove limit {math.degrees(geom.max_contact_angle):.1f} deg; reduce the "
            "load"
        )
    return QuasiStaticSolution._build(
        case,
        geom,
        Method.ISO16281,
        SpeedEffects(),
        bearing.id,
        H,
        displacement=U,
        reaction=R,
        ball_loads=out["Q"],
        contact_angles=out["al"],
        deflections=out["dl"],
        iterations=its,
        residual=res,
    )
