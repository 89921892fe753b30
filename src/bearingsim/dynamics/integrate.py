"""Compiled time integrators shared by every dynamic model.

A model supplies its right-hand side as a Numba ``cfunc`` with the fixed signature
:data:`RHS_SIG` ``rhs(t, y, p, dydt)`` (time [s], state, flat parameter vector, output), and
optionally an auxiliary-output function with the same signature ``aux(t, y, p, out)`` that fills
extra per-sample outputs (stiffness, contact forces, ...). Because the signature is fixed, the
integrators below are compiled once and cached on disk (``cache=True``): a second process does
not recompile them, and the whole stepping loop runs in machine code with no Python call per step.
They release the GIL (``nogil=True``) while they step, so another thread of the same process
(e.g. a sweep worker committing the previous run) runs at the same time.

Integrators
-----------
The public entry points are :func:`run_fixed` and :func:`run_adaptive`; the compiled loops
behind them are private:

``_rk4_fixed``
    Classical 4th-order Runge–Kutta with a fixed step, output every ``decim`` steps.
``_rk4_inline``
    The same loop, for a model's own compiled driver with its right-hand side inlined.
``_dopri``
    Dormand–Prince 5(4) embedded pair with step-size control (Hairer, Nørsett & Wanner 1993,
    §II.4 and §II.5), stepping exactly onto the output times; for checking fixed-step results.

Both stop at the first non-finite state or a state component beyond ``bound`` and report it
through the returned status (see :func:`run_fixed`, which raises a clear error).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from numba import njit, types
from numpy.typing import NDArray

from ..errors import SolverError

#: signature of a model right-hand side / auxiliary output: (t, y, p, out) -> None
RHS_SIG = types.void(types.float64, types.float64[::1], types.float64[::1], types.float64[::1])

__all__ = [
    "RHS_SIG",
    "call_compiled",
    "STATUS_BOUND",
    "STATUS_NONFINITE",
    "STATUS_OK",
    "STATUS_STEP_UNDERFLOW",
    "Trajectory",
    "run_adaptive",
    "run_fixed",
]

STATUS_OK = 0
STATUS_NONFINITE = 1
STATUS_BOUND = 2
STATUS_STEP_UNDERFLOW = 3
STATUS_TOO_MANY_STEPS = 4
#: adaptive steps allowed within one output interval (LSODA's ``mxstep`` idea): beyond, the
#: right-hand side is too stiff or discontinuous for an explicit adaptive step, which would
#: otherwise crawl on (a VSM with a 30 deg load zone took >200 s for 24 samples) [-]
MAX_STEPS_PER_SAMPLE = 10_000


@njit(cache=True)
def _bad(y, bound):
    for i in range(y.size):
        v = y[i]
        if not math.isfinite(v):
            return STATUS_NONFINITE
        if abs(v) > bound:
            return STATUS_BOUND
    return STATUS_OK


@njit(inline="always")
def _rk4_inline(rhs, aux, y0, ny, t0, dt, n_out, decim, p, n_aux, bound, k0=0):
    """Fixed-step RK4 (the body of :func:`_rk4_fixed`), to inline into a model's own driver.

    For a model whose ``rhs``/``aux`` are Numba ``njit`` functions (signature of
    :data:`RHS_SIG`, ``inline="always"``) and whose state size ``ny`` is a literal::

        @njit(cache=True, nogil=True)
        def driver(y0, t0, dt, n_out, decim, p, bound, k0):
            return _rk4_inline(rhs, aux, y0, NY, t0, dt, n_out, decim, p, N_AUX, bound, k0)

    Numba then inlines the right-hand side into the stepping loop and unrolls the stage updates
    (no call through a function pointer, no array passed per call): the IAS seed case steps
    1.4 times faster than through :func:`_rk4_fixed`, with bit-identical results. The inlined
    code is compiled with the driver's options: give the driver the right-hand side's
    ``error_model``. Run it with ``run_fixed(..., driver=driver)``; the driver is compiled once
    per model and cached like any kernel.

    Times are ``t0 + dt k`` with the step number ``k`` counted from ``k0``: a run split into
    pieces that each start at ``k0`` = the steps done before, with ``t0`` the same for all,
    has the same times, hence the same bits, as one run (``k0 = 0`` is the plain run).
    """
    t_out = np.empty(n_out)
    y_out = np.empty((n_out, ny))
    a_out = np.empty((n_out, max(n_aux, 1)))
    y = y0.copy()
    k1 = np.empty(ny)
    k2 = np.empty(ny)
    k3 = np.empty(ny)
    k4 = np.empty(ny)
    yt = np.empty(ny)
    av = np.empty(max(n_aux, 1))
    t = t0 if k0 == 0 else t0 + dt * k0
    status = _bad(y, bound)
    h2 = 0.5 * dt
    h6 = dt / 6.0
    for i in range(n_out):
        if i > 0:
            for _s in range(decim):
                rhs(t, y, p, k1)
                for j in range(ny):
                    yt[j] = y[j] + h2 * k1[j]
                rhs(t + h2, yt, p, k2)
                for j in range(ny):
                    yt[j] = y[j] + h2 * k2[j]
                rhs(t + h2, yt, p, k3)
                for j in range(ny):
                    yt[j] = y[j] + dt * k3[j]
                rhs(t + dt, yt, p, k4)
                for j in range(ny):
                    y[j] += h6 * (k1[j] + 2.0 * k2[j] + 2.0 * k3[j] + k4[j])
                t = t0 + dt * (k0 + (i - 1) * decim + _s + 1)
            status = _bad(y, bound)
        t_out[i] = t
        y_out[i] = y
        if n_aux > 0:
            aux(t, y, p, av)
            a_out[i] = av
        if status != STATUS_OK:
            return t_out, y_out, a_out, status, i + 1
    return t_out, y_out, a_out, status, n_out


@njit(cache=True, nogil=True)
def _rk4_fixed(rhs, aux, y0, t0, dt, n_out, decim, p, n_aux, bound, k0):
    """Fixed-step RK4; returns ``(t_out, y_out, aux_out, status, n_done)``.

    ``n_out`` output samples, the first at ``t0`` (the initial state), then every ``decim``
    steps of size ``dt``. ``aux`` is called at output samples only (``n_aux`` values).
    ``rhs`` and ``aux`` are cfuncs (:data:`RHS_SIG`), called through their addresses: this one
    compiled loop serves every model (see :func:`_rk4_inline` for a model-specific driver).
    """
    return _rk4_inline(rhs, aux, y0, y0.size, t0, dt, n_out, decim, p, n_aux, bound, k0)


# Dormand-Prince 5(4) tableau (Hairer, Norsett & Wanner 1993, table II.5.2)
_C = np.array([0.0, 1 / 5, 3 / 10, 4 / 5, 8 / 9, 1.0, 1.0])
_A = np.zeros((7, 7))
_A[1, 0] = 1 / 5
_A[2, :2] = [3 / 40, 9 / 40]
_A[3, :3] = [44 / 45, -56 / 15, 32 / 9]
_A[4, :4] = [19372 / 6561, -25360 / 2187, 64448 / 6561, -212 / 729]
_A[5, :5] = [9017 / 3168, -355 / 33, 46732 / 5247, 49 / 176, -5103 / 18656]
_A[6, :6] = [35 / 384, 0.0, 500 / 1113, 125 / 192, -2187 / 6784, 11 / 84]
_B5 = _A[6].copy()
_B4 = np.array([5179 / 57600, 0.0, 7571 / 16695, 393 / 640, -92097 / 339200, 187 / 2100, 1 / 40])


@njit(cache=True, nogil=True)
def _dopri(rhs, aux, y0, t_eval, p, n_aux, rtol, atol, h0, hmax, bound, C, A, B5, B4):
    ny = y0.size
    n_out = t_eval.size
    y_out = np.empty((n_out, ny))
    a_out = np.empty((n_out, max(n_aux, 1)))
    av = np.empty(max(n_aux, 1))
    K = np.empty((7, ny))
    y = y0.copy()
    yt = np.empty(ny)
    y5 = np.empty(ny)
    t = t_eval[0]
    y_out[0] = y
    if n_aux > 0:
        aux(t, y, p, av)
        a_out[0] = av
    h = h0
    n_steps = 0
    status = _bad(y, bound)
    if status != STATUS_OK:
        return y_out, a_out, status, 1, n_steps
    for i in range(1, n_out):
        t_target = t_eval[i]
        n_here = 0
        while t < t_target:
            n_here += 1
            if n_here > MAX_STEPS_PER_SAMPLE:
                return y_out, a_out, STATUS_TOO_MANY_STEPS, i, n_steps
            hh = min(h, hmax, t_target - t)
            rhs(t, y, p, K[0])
            for s in range(1, 7):
                for j in range(ny):
                    acc = y[j]
                    for r in range(s):
                        acc += hh * A[s, r] * K[r, j]
                    yt[j] = acc
                rhs(t + C[s] * hh, yt, p, K[s])
            err = 0.0
            for j in range(ny):
                s5 = y[j]
                s4 = y[j]
                for r in range(7):
                    s5 += hh * B5[r] * K[r, j]
                    s4 += hh * B4[r] * K[r, j]
                y5[j] = s5
                sc = atol + rtol * max(abs(y[j]), abs(s5))
                e = (s5 - s4) / sc
                err += e * e
            err = math.sqrt(err / ny)
            if err <= 1.0 or hh < 1e-15 * max(1.0, abs(t)):
                if hh < 1e-15 * max(1.0, abs(t)) and err > 1.0:
                    return y_out, a_out, STATUS_STEP_UNDERFLOW, i, n_steps
                t = t + hh if t_target - t > hh else t_target
                y[:] = y5
                n_steps += 1
                status = _bad(y, bound)
                if status != STATUS_OK:
                    return y_out, a_out, status, i, n_steps
            fac = 0.9 * (1.0 / err) ** 0.2 if err > 0.0 else 5.0
            h = hh * min(5.0, max(0.2, fac))
        y_out[i] = y
        if n_aux > 0:
            aux(t, y, p, av)
            a_out[i] = av
    return y_out, a_out, status, n_out, n_steps


@dataclass(frozen=True)
class Trajectory:
    """Integrator output: sample times [s], states, auxiliary outputs, solver facts."""

    t: NDArray[np.float64]
    y: NDArray[np.float64]
    aux: NDArray[np.float64]
    solver: str
    n_steps: int


def call_compiled(kernel, *args):
    """``kernel(*args)`` for a compiled (Numba) function, with Ctrl-C seen as itself.

    In the main thread, SIGINT is only noted while the kernel runs and handed to the handler in
    place before once the kernel has returned (Python's default raises ``KeyboardInterrupt``;
    an ignored SIGINT stays ignored): a SIGINT that arrives while a ``nogil`` kernel runs otherwise
    raises inside Numba's boxing of the returned arrays, which CPython reports as
    ``SystemError`` ("returned a result with an exception set"), and a rotor run with slip
    interrupted that way crashed with a segmentation fault (exploratory testing, fifteenth
    session). Elsewhere that ``SystemError`` is turned into the ``KeyboardInterrupt``."""
    from ..interrupt import held_interrupt

    with held_interrupt():
        return _call(kernel, args)


def _call(kernel, args):
    """:func:`call_compiled`'s call, the ``SystemError`` of a pending interrupt unwrapped."""
    try:
        return kernel(*args)
    except SystemError as exc:
        cause: BaseException | None = exc
        while isinstance(cause, SystemError):  # Numba may nest them (a callback it was in)
            cause = cause.__cause__
        if isinstance(cause, KeyboardInterrupt):
            raise KeyboardInterrupt from None
        raise


def _fail(status: int, t: float, dt: float | None) -> SolverError:
    cause = {
        STATUS_NONFINITE: "the state became non-finite",
        STATUS_BOUND: "the state grew past its bound",
        STATUS_STEP_UNDERFLOW: "the adaptive step size underflowed",
        STATUS_TOO_MANY_STEPS: f"the adaptive solver took more than {MAX_STEPS_PER_SAMPLE} "
        "steps (accepted or not) within one output interval: the model is too stiff or "
        "discontinuous there for it; use solver rk4",
    }[status]
    hint = f" with dt = {dt:.3g} s; the step is probably too large (reduce dt_s)" if dt else ""
    what = "stopped" if status == STATUS_TOO_MANY_STEPS else "diverged"
    return SolverError(f"integration {what} at t = {t:.6g} s: {cause}{hint}")


def run_fixed(
    rhs,
    aux,
    y0,
    p,
    *,
    dt: float,
    n_out: int,
    decim: int,
    n_aux: int = 0,
    bound: float = 1e3,
    t0: float = 0.0,
    driver=None,
    k0: int = 0,
) -> Trajectory:
    """Run :func:`_rk4_fixed` (or a model's own ``driver``) and raise :class:`SolverError` on
    divergence.

    Parameters
    ----------
    rhs, aux : numba cfunc
        With signature :data:`RHS_SIG`; ``aux`` may equal ``rhs`` when ``n_aux == 0``.
        Unused with ``driver``.
    y0 : ndarray
        Initial state.
    p : ndarray
        Flat float64 parameter vector passed to ``rhs``/``aux``.
    dt : float
        Step [s].
    n_out : int
        Number of output samples (including the initial state).
    decim : int
        Steps per output sample.
    n_aux : int
        Number of auxiliary outputs per sample.
    bound : float
        Largest admissible absolute state component (divergence guard).
    t0 : float
        Initial time [s].
    driver : numba dispatcher, optional
        ``driver(y0, t0, dt, n_out, decim, p, bound, k0)`` built on :func:`_rk4_inline` with
        the model's right-hand side and ``n_aux`` auxiliary outputs inlined.
    k0 : int
        Steps done before this piece of a longer run: times are ``t0 + dt (k0 + k)``
        (:func:`_rk4_inline`).
    """
    y0 = np.ascontiguousarray(y0, dtype=float)
    p = np.ascontiguousarray(p, dtype=float)
    if driver is None:
        t, y, a, status, n_done = call_compiled(
            _rk4_fixed, rhs, aux, y0, float(t0), float(dt), int(n_out), int(decim), p,
            int(n_aux), float(bound), int(k0),
        )  # fmt: skip
    else:
        t, y, a, status, n_done = call_compiled(
            driver, y0, float(t0), float(dt), int(n_out), int(decim), p, float(bound), int(k0)
        )
    if status != STATUS_OK:
        raise _fail(status, float(t[n_done - 1]), dt)
    return Trajectory(t, y, a[:, :n_aux], "rk4", (n_out - 1) * decim)


def run_adaptive(
    rhs,
    aux,
    y0,
    p,
    t_eval,
    *,
    n_aux: int = 0,
    rtol: float = 1e-8,
    atol: float = 1e-12,
    h0: float = 1e-7,
    hmax: float = np.inf,
    bound: float = 1e3,
) -> Trajectory:
    """Run the Dormand–Prince 5(4) integrator to the output times ``t_eval`` [s]."""
    y0 = np.ascontiguousarray(y0, dtype=float)
    p = np.ascontiguousarray(p, dtype=float)
    te = np.ascontiguousarray(t_eval, dtype=float)
    y, a, status, n_done, n_steps = call_compiled(
        _dopri,
        rhs,
        aux,
        y0,
        te,
        p,
        int(n_aux),
        float(rtol),
        float(atol),
        float(h0),
        float(hmax),
        float(bound),
        _C,
        _A,
        _B5,
        _B4,
    )
    if status != STATUS_OK:
        raise _fail(status, float(te[max(n_done - 1, 0)]), None)
    return Trajectory(te, y, a[:, :n_aux], "dopri5", int(n_steps))
