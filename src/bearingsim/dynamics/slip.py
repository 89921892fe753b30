"""Random slip of the rolling elements (issue 16, item 1), shared by the ring and rotor models.

Rolling elements do not keep their kinematic rate (Antoni & Randall 2002, "Differential
diagnosis of gear and bearing faults", J. Vib. Acoust. 124; Randall & Antoni 2011, MSSP 25):
the ball-pass instants jitter by about 1-2 % of their period. Model: from one ball pass to the
next the cage turns at ``w_cage (1 + s_k)``, ``s_k`` independent and normal with standard
deviation ``slip``, so the ball-pass intervals are ``T / (1 + s_k)``: jittered by ``slip`` of
their period, the phase a random walk. Between two passes the cage turns uniformly. The
intervals are divided by their expectation ``E[1 / (1 + s_k)]`` (:func:`mean_interval_factor`,
``1 + slip^2`` to second order), so that the mean interval is ``T`` and the long-run pass rate
the kinematic one, ``Z f_cage``; without it the rate fell by ``slip^2`` (1 % at 10 % slip;
twenty-first session). The compiled kernels read the tabulated pass instants ``t_k`` (the cage at
``k 2 pi / Z``, ``t_0 = 0``).

Pocket jitter (the balls wander within their cage pockets): each pass instant moves by an
independent ``e_k T`` around where the cage-speed process puts it, so the intervals jitter
(standard deviation ``jitter`` of the period) but the phase does not drift: after many passes
the pattern is still locked to the cage. The cage-speed process (a renewal process, Antoni &
Randall 2003) lets the phase wander without bound, which spreads the envelope spectrum's lines
into a raised floor; the pocket jitter smears the high harmonics only. Both may act together.
"""

from __future__ import annotations

import functools
import math

import numpy as np
from numba import njit
from numpy.typing import NDArray

__all__ = ["ball_pass_instants", "cage_angle", "mean_interval_factor"]

#: the cage-speed fluctuation ``s_k`` is clipped to this magnitude (a pass interval between
#: ``T / 1.5`` and ``2 T``) [-]
_S_CLIP = 0.5
#: standard deviations past which the normal density is below double precision's smallest
#: normal number (exp(-37^2 / 2) ~ 1e-298) [-]: the integration range of
#: :func:`mean_interval_factor`
_Z_FAR = 37.0


@functools.lru_cache(maxsize=64)
def mean_interval_factor(slip: float) -> float:
    """``E[1 / (1 + s)]`` for ``s`` normal with standard deviation ``slip`` [-] clipped to
    ``±0.5`` (the cage-speed process's pass intervals over their nominal ``T``) [-]; exactly 1
    at zero slip. (The integral by SciPy's ``quad`` over the standard normal density; cached:
    one slip level is asked for by every run of a sweep.)"""
    if slip <= 0.0:
        return 1.0
    from scipy import integrate

    a = _S_CLIP / slip
    # the density is below 1e-300 past 37 standard deviations: integrating out to a = 0.5/slip
    # (5000 at slip 1e-4) let quad miss the peak, and gave 6e-25 there and 0 below (every pass
    # instant divided by it: a frozen cage, a silent zero signal; exploratory testing,
    # twenty-fifth session)
    b = min(a, _Z_FAR)
    c = 1.0 / math.sqrt(2.0 * math.pi)
    mid, _err = integrate.quad(
        lambda z: c * math.exp(-0.5 * z * z) / (1.0 + slip * z), -b, b, epsabs=1e-14, epsrel=1e-12
    )
    tail = 0.5 * math.erfc(a / math.sqrt(2.0))  # each side's mass, at the clipped value
    return mid + tail / (1.0 - _S_CLIP) + tail / (1.0 + _S_CLIP)


def ball_pass_instants(
    n_balls: int,
    cage_hz: float,
    slip: float,
    duration: float,
    seed: tuple[int, ...],
    jitter: float = 0.0,
) -> tuple[NDArray[np.float64], float]:
    """The ball-pass instants ``t_k`` [s] covering ``duration`` [s] and the nominal period
    ``1 / (Z f_cage)`` [s] (see the module docstring): the cage-speed process ``slip`` from
    ``numpy.random.SeedSequence(seed)`` and the pocket ``jitter`` from ``SeedSequence(seed +
    (3,))`` (streams of their own, apart from any noise; without jitter the instants are those
    of the cage-speed process alone, bit for bit)."""
    dt = 1.0 / (n_balls * cage_hz)
    n = int(math.ceil(1.1 * duration / dt)) + 4
    rng = np.random.default_rng(np.random.SeedSequence(list(seed)))
    s = np.clip(slip * rng.standard_normal(n - 1), -_S_CLIP, _S_CLIP)
    t = np.concatenate([[0.0], np.cumsum(dt / (1.0 + s))])
    if slip > 0.0:  # the mean interval T: the long-run rate the kinematic one
        t = t / mean_interval_factor(slip)
    if jitter > 0.0:
        # each instant moves by e_k dt, e_k ~ N(0, jitter^2 / 2) independent, so an interval
        # (t_k - t_{k-1}) has the standard deviation jitter dt; |e_k| <= 0.2 keeps the instants
        # ordered (intervals >= dt / 1.5 - 0.4 dt > 0)
        rj = np.random.default_rng(np.random.SeedSequence([*seed, 3]))
        e = np.clip(jitter / math.sqrt(2.0) * rj.standard_normal(n), -0.2, 0.2)
        e[0] = 0.0  # the cage starts where the scenario puts it
        t = t + dt * e
    return t, dt


@njit(cache=True, inline="always")
def cage_angle(t, p, off, n, dt, step):  # pragma: no cover - compiled
    """The cage's angle [rad] past its position at ``t = 0`` and its speed [rad/s] at ``t``,
    from the ``n`` ball-pass instants at ``p[off:]`` (nominal spacing ``dt`` [s], the cage at
    ``k step`` at the ``k``-th): uniform rotation between two passes."""
    k = int(math.floor(t / dt))  # the nominal pass; the jittered one is near
    k = 0 if k < 0 else (n - 2 if k > n - 2 else k)
    while k > 0 and p[off + k] > t:
        k -= 1
    while k < n - 2 and p[off + k + 1] <= t:
        k += 1
    t0 = p[off + k]
    t1 = p[off + k + 1]
    return step * (k + (t - t0) / (t1 - t0)), step / (t1 - t0)
