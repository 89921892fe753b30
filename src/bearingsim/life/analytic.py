"""Closed-form stress field under a Hertz line contact (plane strain, frictionless).

McEwen (1949), as given by Johnson (1985) *Contact Mechanics*, eq. (4.75)–(4.76): for the pressure
``p(x) = p0 sqrt(1 - (x/b)^2)`` on the half-space ``z >= 0`` (``z`` depth),

``sigma_x = -(p0/b) [m (1 + (z^2 + n^2)/(m^2 + n^2)) - 2 z]``,
``sigma_z = -(p0/b) m (1 - (z^2 + n^2)/(m^2 + n^2))``,
``tau_xz  = -(p0/b) n (m^2 - z^2)/(m^2 + n^2)``,

with ``m^2 = [sqrt((b^2 - x^2 + z^2)^2 + 4 x^2 z^2) + (b^2 - x^2 + z^2)]/2``,
``n^2 = [sqrt((b^2 - x^2 + z^2)^2 + 4 x^2 z^2) - (b^2 - x^2 + z^2)]/2``, ``m`` taking the sign of
``z`` and ``n`` that of ``x``. The sign of ``tau_xz`` is the one that satisfies equilibrium
(``d sigma_x/dx + d tau_xz/dz = 0``) in this frame with ``z`` pointing into the solid (checked in
``tests/test_fe_life.py``); it agrees with the Flamant line-load limit
``tau_xz = -2 P x z^2 / (pi r^4)``. Plane strain adds ``sigma_y = nu (sigma_x + sigma_z)``. On
the axis this reduces to :func:`bearingsim.hertz.line_subsurface_stresses`; the orthogonal shear
``tau_xz`` peaks at ``+/- 0.25 p0`` at ``x = +/- 0.87 b``, ``z = 0.5 b`` (Johnson 1985, §4.2).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike, NDArray

__all__ = [
    "LineContactField",
    "mcewen_stresses",
]


@dataclass(frozen=True)
class LineContactField:
    """Stresses [Pa] at points ``(x, z)``, tension positive, ``z`` depth below the surface."""

    sigma_x: NDArray[np.float64]
    sigma_z: NDArray[np.float64]
    tau_xz: NDArray[np.float64]
    sigma_y: NDArray[np.float64]


def mcewen_stresses(
    x: ArrayLike, z: ArrayLike, p0: float, b: float, nu: float = 0.3
) -> LineContactField:
    """Stress field of a frictionless Hertz line contact (McEwen 1949; Johnson 1985 eq. (4.75)).

    Parameters
    ----------
    x : array_like
        Coordinate along the surface from the contact centre [m].
    z : array_like
        Depth below the surface [m], >= 0.
    p0 : float
        Maximum contact pressure [Pa].
    b : float
        Contact semi-width [m].
    nu : float
        Poisson's ratio [-] for the out-of-plane (plane-strain) stress.
    """
    x = np.asarray(x, dtype=float)
    z = np.asarray(z, dtype=float)
    x, z = np.broadcast_arrays(x, z)
    k = b * b - x * x + z * z
    r = np.sqrt(k * k + 4.0 * x * x * z * z)
    m = np.sqrt(np.maximum(0.5 * (r + k), 0.0)) * np.where(z >= 0, 1.0, -1.0)
    n = np.sqrt(np.maximum(0.5 * (r - k), 0.0)) * np.sign(x)
    mn = m * m + n * n
    with np.errstate(invalid="ignore", divide="ignore"):
        ratio = np.where(mn > 0, (z * z + n * n) / np.where(mn > 0, mn, 1.0), 1.0)
        q = np.where(mn > 0, (m * m - z * z) / np.where(mn > 0, mn, 1.0), 0.0)
    sx = -(p0 / b) * (m * (1.0 + ratio) - 2.0 * z)
    sz = -(p0 / b) * m * (1.0 - ratio)
    txz = -(p0 / b) * n * q
    # on the surface (z = 0) the field is the applied pressure: sigma_x = sigma_z = -p(x)
    surf = (z == 0) & (np.abs(x) <= b)
    if np.any(surf):
        p = p0 * np.sqrt(np.clip(1.0 - (x / b) ** 2, 0.0, None))
        sx = np.where(surf, -p, sx)
        sz = np.where(surf, -p, sz)
        txz = np.where(surf, 0.0, txz)
    return LineContactField(sx, sz, txz, nu * (sx + sz))
