"""A round pit narrower than the ball's contact (:class:`bearingsim.geometry.DefectProfile.PIT`):
the share of a ball's load that the contact beside the pit still carries.

CWRU's seeded faults are electro-discharge-machined pits of 0.007-0.040 in *diameter* and
0.011 in depth (CWRU Bearing Data Center, "Fault Specifications"), not slots across the track.
A ball-raceway contact of a deep-groove ball bearing is an ellipse whose semi-axis ``a``
across the rolling direction is 6-10 times the one along it, ``b``
(:func:`bearingsim.contact.hertz.ball_contact`; 6205 outer race at 25 N: ``a`` = 0.34 mm,
``b`` = 0.054 mm). A pit of radius ``r_h`` = 0.09 mm (0.007 in) under the ball removes a part
of that ellipse, not the whole contact: the groove on both sides of the pit keeps carrying the
ball, whose transverse curvature conforms to it (the ball sinks by ``r_h^2 / (2 R_y)`` = 0.05 µm
to touch the rim of a 0.007 in pit across the track, against the 0.83 µm of seed VSM eq. (2)
along it). The slot profiles (``rectangular``, ``geometric``) unload the ball by the drop
along the track.

**Share the pit takes.** Hertz's pressure ``p0 sqrt(1 - x^2/b^2 - y^2/a^2)`` (``x`` along the
rolling direction from the contact's centre, ``y`` across it) on the pit's disc ``(x_c + x)^2 +
y^2 < r_h^2`` (``x_c`` the contact centre's distance from the pit's centre along the track),
as a share of the load ``Q = 2 pi p0 a b / 3``:

    F = int_{-1}^{1} 3/4 (1 - u^2) G(s(x_c + b u) / (a sqrt(1 - u^2))) du,
    G(v) = (2/pi) (asin v + v sqrt(1 - v^2))  (G = 1 for v >= 1),

``s(x) = sqrt(r_h^2 - x^2)`` the half-chord of the pit across the track at ``x`` (0 off the
pit). Each slice ``u`` of the ellipse carries ``3/4 (1 - u^2)`` of the load with a semicircular
pressure across the track, of which ``G`` lies on the pit's chord. A strip of constant half-width
``s`` gives ``F = 1.5 t - 0.5 t^3``, ``t = s/a`` (:func:`strip_share`, the check of the
quadrature). The integral is a 12-point Gauss-Legendre sum over the slices that cross the pit
(a pit far shorter than the contact falls between nodes spread over the whole contact): the
contact's length ``2 b`` along the track smooths the pit's entry and exit over that length.
The contact keeps ``g = 1 - F`` of its Hertz constant at the same approach, ``Q = g k
delta^1.5``. This holds the pressure beside the pit at Hertz's value; the elastic half-space
carries part of the pit's share to its sides, so ``1 - g`` is an upper bound of the load a pit
removes at a given approach (a numerical contact solution would tighten it).

**Semi-axes from the approach.** Hertz's ``a, b ∝ Q^(1/3)`` and ``delta ∝ Q^(2/3)`` make ``a^2
/ delta`` and ``b^2 / delta`` constants of the contact: with the ring models' combined constant
``Q = K d^n`` (``d`` the approach of both contacts), ``a^2 = A d`` and ``b^2 = B d``, ``A = a_1^2
K^(2/3)``, ``B = b_1^2 K^(2/3)`` (``a_1, b_1`` the semi-axes at 1 N, :func:`pit_contact`): the
intact contact's at the same approach (the ball sinks a little deeper beside a pit; second
order). Where the pit covers the whole contact (``F = 1``) the race carries nothing until the
ball has sunk far enough for the contact to reach past it.

**Two contacts in series** (the ring models' ball, seed VSM eq. (10)): the pit's contact, of
compliance share ``w = k_p^(-1/n) / (k_p^(-1/n) + k_q^(-1/n))``, keeps ``g k_p``, so the ball's
constant becomes ``K rho(g)``, ``rho = (w g^(-1/n) + 1 - w)^(-n)``. One contact (``w = 1``):
``rho = g``.

**Where the contact meets the pit.** From ``x_c = -(r_h + b)`` to ``r_h + b``: the ring models
widen the defect's window by ``b`` at ISO 76's 4.2 GPa on each side (:func:`pit_contacts`);
a contact pressed harder is longer than the window.
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

__all__ = ["pit_contact", "pit_contacts", "pit_lost_share", "pit_share", "strip_share"]

#: Gauss-Legendre nodes and weights on [-1, 1] of the share integral (module docstring)
_GL_U, _GL_W = np.polynomial.legendre.leggauss(12)
#: ISO 76's static-capacity pressure of ball bearings, the load up to which the window of
#: :func:`pit_contacts` holds the whole contact [Pa]
P_CAPACITY_PA = 4.2e9


@njit(cache=True, inline="always")
def strip_share(t):
    """Share ``F(t) = 1.5 t - 0.5 t^3`` [-] of a Hertz contact's load on the strip ``|y| < t a``
    across it (1 for ``t >= 1``)."""
    if t >= 1.0:
        return 1.0
    return 1.5 * t - 0.5 * t * t * t


@njit(cache=True, inline="always")
def _semicircle_share(v):
    """``G(v)`` [-]: the share of a semicircular load profile of half-width 1 on ``|y| < v``."""
    if v >= 1.0:
        return 1.0
    return (2.0 / math.pi) * (math.asin(v) + v * math.sqrt(1.0 - v * v))


@njit(cache=True)
def pit_lost_share(xc, rh, a, b):
    """Share ``F`` [-] of a Hertz contact's load (semi-axes ``a`` across and ``b`` along the
    rolling direction [m]) on a round pit of radius ``rh`` [m] whose centre lies ``xc`` [m]
    from the contact's centre along the track (module docstring)."""
    x = abs(xc)
    if x >= rh + b or not a > 0.0:
        return 0.0
    if not b > 0.0 or rh / b > 1e12:  # a contact of no length: the strip at its centre
        return strip_share(math.sqrt(rh * rh - x * x) / a) if x < rh else 0.0
    # the slices u of the contact that cross the pit, |x + b u| < rh: the nodes on them only
    # (on the whole contact a pit much shorter than it fell between the nodes)
    lo = max(-1.0, (-rh - x) / b)
    hi = min(1.0, (rh - x) / b)
    if hi <= lo:
        return 0.0
    mid = 0.5 * (hi + lo)
    half = 0.5 * (hi - lo)
    f = 0.0
    for k in range(_GL_U.size):
        u = mid + half * _GL_U[k]
        xs = x + b * u
        e2 = rh * rh - xs * xs
        c = 1.0 - u * u
        if e2 <= 0.0 or c <= 0.0:
            continue
        den = a * math.sqrt(c)  # the slice's half-width across the track [m]
        g = _semicircle_share(math.sqrt(e2) / den) if den > 0.0 else 1.0
        f += _GL_W[k] * 0.75 * c * g
    f *= half
    return f if f < 1.0 else 1.0


@njit(cache=True, inline="always")
def _rho(d, xc, rh, a2, b2, w, n):
    """``rho`` [-] of :func:`pit_share` at approach ``d`` [m] (``d > 0``)."""
    g = 1.0 - pit_lost_share(xc, rh, math.sqrt(a2 * d), math.sqrt(b2 * d))
    if g <= 0.0:
        return 0.0
    if w >= 1.0:
        return g
    return (w * g ** (-1.0 / n) + 1.0 - w) ** (-n)


@njit(cache=True)
def pit_share(d, xc, rh, a2, b2, w, n, slope):
    """Factor ``rho`` [-] on a ball's load ``K d^n`` with a pit of radius ``rh`` [m] whose
    centre lies ``xc`` [m] from the contact's centre along the track, and ``d rho / d d``
    [1/m] when ``slope`` (else 0; a central difference of relative step 1e-6).

    ``a^2 = a2 d``, ``b^2 = b2 d`` [m] at the approach ``d`` [m]; ``w`` the pit contact's
    compliance share [-], ``n`` the load exponent [-] (module docstring). ``d <= 0`` (a rough
    contact's asperities carry load before the surfaces meet; the Hertz contact has no size):
    0 with its centre over the pit, else 1 (the limits of ``d -> 0+``)."""
    if d <= 0.0:
        return (0.0 if abs(xc) < rh else 1.0), 0.0
    rho = _rho(d, xc, rh, a2, b2, w, n)
    if not slope:
        return rho, 0.0
    h = 1e-6 * d
    if not h > 0.0:  # a subnormal approach (a rough contact's faint load): no slope resolved
        return rho, 0.0
    return rho, (_rho(d + h, xc, rh, a2, b2, w, n) - _rho(d - h, xc, rh, a2, b2, w, n)) / (2 * h)


def pit_contact(bearing, race) -> tuple[float, float, float, float]:
    """``(a_1^2, b_1^2, w, margin)`` of the ``race`` contact (a
    :class:`~bearingsim.geometry.Race`, inner or outer) of a ball of ``bearing``: its Hertz
    semi-axes squared at 1 N [m^2/N^(2/3)] (``a^2 = a_1^2 Q^(2/3)``), its share of the two
    contacts' compliance ``w`` [-], and its semi-axis ``b`` along the track at ISO 76's
    4.2 GPa, by which a defect's window is widened on each side [m] (module docstring)."""
    from ..contact.hertz import ball_contact
    from ..geometry import Race

    this = ball_contact(bearing, 1.0, race)
    other = ball_contact(bearing, 1.0, Race.INNER if race is Race.OUTER else Race.OUTER)
    a1, b1, p1 = float(this.a), float(this.b), float(this.p_max)
    ct = this.k_hertz ** (-2.0 / 3.0)
    co = other.k_hertz ** (-2.0 / 3.0)
    return a1 * a1, b1 * b1, ct / (ct + co), b1 * P_CAPACITY_PA / p1


def pit_contacts(bearing, defect) -> tuple[tuple[float, float, float], tuple | None, float]:
    """The contacts a pit ``defect`` of ``bearing`` meets and its window, for the models' set-up:
    ``(a_1^2, b_1^2, w)`` of :func:`pit_contact` at the pit's race (a ball pit: the outer race),
    the same at the inner race for a ball pit (else ``None``), and the angle [rad] by which the
    defect's window widens on each side (the larger ``margin`` over the pit's path: the
    raceway, or the ball for a ball pit)."""
    from ..geometry import Race, defect_geometry

    ball = defect.race is Race.BALL
    *first, margin = pit_contact(bearing, Race.OUTER if ball else defect.race)
    inner = None
    if ball:
        *inner, m_i = pit_contact(bearing, Race.INNER)
        margin = max(margin, m_i)
    rpath = 0.5 * bearing.element_diameter if ball else defect_geometry(bearing, defect).race_radius
    return tuple(first), (tuple(inner) if inner else None), margin / rpath
