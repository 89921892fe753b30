"""Hertz's ball load law averaged over the surface roughness (the rough-contact onset).

A smooth Hertz contact takes load the instant the nominal deflection ``delta`` turns positive,
``Q = K delta_+^(3/2)``: its force is continuous, but its second time derivative is singular
(``~ delta^(-1/2)``) wherever a ball enters or leaves the load zone, so a healthy bearing model
rings its contact resonance at every ball pass — impulses at BPFO that a measured healthy
bearing does not show (``docs/models.md``, "Rough contact onset"). Real surfaces carry
asperities whose heights scatter about the mean plane with the composite RMS roughness
``sigma = sqrt(R_q,ball^2 + R_q,race^2)``; the surfaces begin to touch a few ``sigma`` before
their mean planes do and the load builds up over that approach.

**Model.** The mean-plane separation of ball and raceway at a contact is offset by a random
height ``z ~ N(0, sigma^2)`` (the surfaces' combined asperity height at the contact), and the
ball load is Hertz's law averaged over it:

    Q(delta) = K E[(delta - z)_+^n] = K sigma^n g_n(delta / sigma),

    g_nu(u) = E[(u - Z)_+^nu] = Gamma(nu + 1) exp(-u^2/4) D_{-nu-1}(-u) / sqrt(2 pi),

``Z ~ N(0, 1)``, ``D`` the parabolic cylinder function (DLMF 12.5.1; :func:`scipy.special.pbdv`),
``nu > -1``. Its properties: ``g_nu' = nu g_{nu-1}`` (so the contact stiffness is
``dQ/d delta = K n sigma^(n-1) g_{n-1}`` and the contact potential ``K sigma^(n+1) g_{n+1} /
(n+1)``); ``g_nu(u) -> u^nu`` for ``u >> 1`` (Hertz far from the onset, relative difference
``nu (nu-1) / (2 u^2)``); ``g_nu(u) -> 0`` faster than ``exp(-u^2/2)`` for ``u << -1``; every
derivative is continuous. This is the simplest rough-contact law with the right two limits; it
is not Greenwood & Williamson's (1966) asperity model (no asperity curvature or plasticity, no
EHL film) and it is only used for the onset: a ball loaded to ``delta >> sigma`` obeys Hertz.
With ``sigma = 0`` it is Hertz's law exactly.

**Compiled evaluation.** :func:`rough_hertz` reads a table (:func:`rough_table`) of ``g_nu`` for
``nu = n+1, n, n-1, n-2`` at spacing :data:`TABLE_STEP` on ``[U_MIN, U_MAX]`` and interpolates
with cubic Hermite polynomials whose slopes are the exact ``nu g_{nu-1}`` (error < 1e-8 of
``sigma^n``); above :data:`U_MAX` the asymptotic series ``g_nu(u) = u^nu sum_k binom(nu, 2k)
(2k-1)!! u^(-2k)`` (five terms, relative error < 1e-8); below :data:`U_MIN` the load is 0.
"""

from __future__ import annotations

import math
from functools import lru_cache

import numpy as np
from numba import njit
from numpy.typing import ArrayLike, NDArray
from scipy.special import gamma, pbdv

from ..errors import ConfigError

__all__ = ["BALL_TABLE", "rough_ball", "rough_hertz", "rough_mean_power", "rough_table"]
#: table range in units of sigma [-]: below U_MIN the load is < 1e-13 K sigma^n (taken as 0)
U_MIN = -8.0
#: above U_MAX the asymptotic series is used [-]
U_MAX = 12.0
#: table spacing in units of sigma [-]
TABLE_STEP = 1.0 / 32.0
#: terms of the asymptotic series above U_MAX
N_SERIES = 5
#: header of the packed table: u0, step, nodes, n, then 3 x N_SERIES series coefficients
_HEAD = 4 + 3 * N_SERIES


def rough_mean_power(u: ArrayLike, nu: float) -> NDArray[np.float64]:
    """``g_nu(u) = E[(u - Z)_+^nu]``, ``Z ~ N(0, 1)`` (module docstring) [-].

    Parameters
    ----------
    u : array_like
        Nominal deflection over the roughness, ``delta / sigma`` [-].
    nu : float
        Exponent, ``> -1`` [-].
    """
    if not nu > -1.0:
        raise ConfigError(f"rough-contact exponent nu = {nu:g} is out of range; valid: > -1")
    u = np.asarray(u, dtype=float)
    out = np.zeros_like(u)
    lo = u > U_MIN
    hi = u >= U_MAX
    mid = lo & ~hi
    if np.any(mid):
        d, _ = pbdv(-nu - 1.0, -u[mid])
        out[mid] = gamma(nu + 1.0) * np.exp(-0.25 * u[mid] ** 2) * d / math.sqrt(2.0 * math.pi)
    if np.any(hi):
        c = _series(nu)
        uh = u[hi]
        s = np.ones_like(uh)
        for k in range(1, N_SERIES + 1):
            s += c[k - 1] * uh ** (-2.0 * k)
        out[hi] = uh**nu * s
    return out


def _series(nu: float) -> NDArray[np.float64]:
    """Coefficients ``binom(nu, 2k) (2k-1)!!``, k = 1..N_SERIES, of the asymptotic series."""
    c = np.empty(N_SERIES)
    b = 1.0  # binom(nu, j) built up
    dfact = 1.0  # (2k-1)!!
    j = 0
    for k in range(1, N_SERIES + 1):
        for _ in range(2):
            b *= (nu - j) / (j + 1.0)
            j += 1
        dfact *= 2 * k - 1
        c[k - 1] = b * dfact
    return c


@lru_cache(maxsize=4)
def rough_table(n: float) -> NDArray[np.float64]:
    """Packed table of the rough load law for exponent ``n`` (> 1) read by :func:`rough_hertz`:
    ``[U_MIN, TABLE_STEP, nodes, n, series(n+1), series(n), series(n-1), g_{n+1}, g_n,
    g_{n-1}, g_{n-2} at every node]`` (built once per exponent; read-only)."""
    if not n > 1.0:
        raise ConfigError(f"load-deflection exponent n = {n:g}: the rough law needs n > 1")
    m = int(round((U_MAX - U_MIN) / TABLE_STEP)) + 1
    u = U_MIN + TABLE_STEP * np.arange(m)
    cols = np.stack([rough_mean_power(u, n + 1 - k) for k in range(4)], axis=1)
    head = np.concatenate(
        [[U_MIN, TABLE_STEP, float(m), n], _series(n + 1.0), _series(n), _series(n - 1.0)]
    )
    out = np.concatenate([head, cols.ravel()])
    out.flags.writeable = False
    return out


@njit(cache=True, inline="always")
def _herm(t, h, y0, m0, y1, m1):
    """Cubic Hermite interpolant at ``t`` in [0, 1] of an interval of width ``h``."""
    t2 = t * t
    t3 = t2 * t
    return (
        (2.0 * t3 - 3.0 * t2 + 1.0) * y0
        + (t3 - 2.0 * t2 + t) * h * m0
        + (-2.0 * t3 + 3.0 * t2) * y1
        + (t3 - t2) * h * m1
    )


@njit(cache=True, inline="always")
def _ser(u, w, p, k0):
    """``1 + sum c_k u^-2k`` with the coefficients at ``p[k0:]`` and ``w = 1/u^2``."""
    s = 0.0
    for k in range(N_SERIES - 1, -1, -1):
        s = (s + p[k0 + k]) * w
    return 1.0 + s


@njit(cache=True, inline="always")
def rough_hertz(d, K, sig, p, off, full=True, inv_sig=0.0, sig_n1=0.0):
    """Rough ball load [N], its slope dQ/d delta [N/m] and contact potential [J] at nominal
    deflection ``d`` [m] (may be negative) for ``Q = K sigma^n g_n(d/sigma)`` (module
    docstring); ``K`` [N/m^n], ``sig`` the composite RMS roughness [m] (> 0), the table
    (:func:`rough_table`) at ``p[off:]``. ``full = False`` returns the load only (slope and
    potential 0: a force-only right-hand side); ``inv_sig = 1/sig`` and ``sig_n1 =
    sig^(n-1)`` precomputed by a caller in a hot loop (0: computed here). Inlined into
    :func:`rough_ball`, which the ring kernels call out of line (inlined into their Hertz
    loops, its copies slowed every ring model's Hertz path by 15-45 %)."""
    n = p[off + 3]
    if inv_sig <= 0.0:
        inv_sig = 1.0 / sig
        sig_n1 = sig ** (n - 1.0)
    u = d * inv_sig
    u0 = p[off]
    if u <= u0:
        return 0.0, 0.0, 0.0
    h = p[off + 1]
    g0 = 0.0
    g2 = 0.0
    if u >= U_MAX:
        # asymptotic series; u^n, u^(n+1), u^(n-1) from one power (one sqrt for balls)
        un1 = math.sqrt(u) if n == 1.5 else u ** (n - 1.0)
        w = 1.0 / (u * u)
        g1 = u * un1 * _ser(u, w, p, off + 4 + N_SERIES)
        if full:
            g0 = un1 * _ser(u, w, p, off + 4 + 2 * N_SERIES)
            g2 = u * u * un1 * _ser(u, w, p, off + 4)
    else:
        x = (u - u0) / h
        i = int(x)
        t = x - i
        a = off + _HEAD + 4 * i
        b = a + 4
        g1 = _herm(t, h, p[a + 1], n * p[a + 2], p[b + 1], n * p[b + 2])
        if full:
            g2 = _herm(t, h, p[a], (n + 1.0) * p[a + 1], p[b], (n + 1.0) * p[b + 1])
            g0 = _herm(t, h, p[a + 2], (n - 1.0) * p[a + 3], p[b + 2], (n - 1.0) * p[b + 3])
    kq = K * sig_n1 * sig
    return kq * g1, K * n * sig_n1 * g0, kq * sig * g2 / (n + 1.0)


#: the table of the ball exponent n = 3/2 (every ring model), frozen into the compiled
#: :func:`rough_ball` as a constant
BALL_TABLE = rough_table(1.5)


@njit(cache=True)
def rough_ball(d, K, sig, inv_sig, sig_n1, full):
    """:func:`rough_hertz` for balls (n = 3/2, :data:`BALL_TABLE`) with scalar arguments only:
    the ring kernels call it out of line, so their Hertz loops stay as small (and as fast) as
    without the rough law, and a call costs no reference counting (no array argument).
    ``inv_sig = 1/sig``, ``sig_n1 = sig^(1/2)``."""
    return rough_hertz(d, K, sig, BALL_TABLE, 0, full, inv_sig, sig_n1)
