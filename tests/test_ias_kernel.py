"""The compiled IAS kernel (``bearingsim.dynamics.ias._kernel``): its 10/9 power against exact
arithmetic, its right-hand side against the NumPy reference state by state, and its compiled
form free of reference counting (which costs a quarter of the seed case's time when it creeps
back). The trajectory-level checks against SciPy are in ``test_ias.py``."""

from __future__ import annotations

import json
import math
import os
import subprocess
import sys
from dataclasses import replace
from decimal import Decimal, localcontext
from pathlib import Path

import numpy as np
import pytest
from numba import cfunc, njit
from numpy.testing import assert_allclose, assert_array_less

from bearingsim import get_bearing
from bearingsim.contact.pereira import LINE_EXPONENT
from bearingsim.dynamics.ias import _kernel as kernel
from bearingsim.dynamics.ias.model import (
    N_AUX,
    IasParams,
    initial_state,
    pack_parameters,
    simulate_ias,
)
from bearingsim.dynamics.ias.reference import ReferenceRhs
from bearingsim.dynamics.integrate import RHS_SIG, run_fixed
from bearingsim.errors import SolverError

B = get_bearing("NU204-ECP")
#: roller 1 starts 0.04 rad (cage) before the seed's spall: it crosses it within 0.03 s
CROSSING = IasParams(B, first_roller_angle=1.5 * math.pi - 0.04)


@njit
def _powers(d, n):
    out = np.empty(d.size)
    for i in range(d.size):
        out[i] = kernel._power(d[i], n)
    return out


@njit
def _roots(d):
    out = np.empty(d.size)
    for i in range(d.size):
        out[i] = kernel._root9(d[i])
    return out


def _exact(values, exponent: Decimal) -> np.ndarray:
    """``v^exponent`` in 40-digit decimal arithmetic, rounded to float64."""
    with localcontext() as ctx:
        ctx.prec = 40
        return np.array([float((Decimal(float(v)).ln() * exponent).exp()) for v in values])


def _samples() -> np.ndarray:
    rng = np.random.default_rng(13)
    return np.concatenate(
        [
            10 ** rng.uniform(-12, -4, 4000),  # roller approaches and loads of the model [m]
            10 ** rng.uniform(-307, 270, 2000),  # the rest of the range (10/9 power finite)
            # subnormal, the ends of the fast path, both ends of the mantissa
            [5e-324, 1e-310, 2.2250738585072014e-308, 1e270, 1.0, 2.0],
            [np.nextafter(1.0, 2.0), np.nextafter(2.0, 1.0), np.nextafter(1e-6, 1.0)],
        ]
    )


def test_line_contact_power_is_exact_to_3_ulp():
    """``delta^(10/9)`` of seed IAS eq. (13) within 3 units in the last place of the exact
    power (the former ``exp(10/9 ln delta)`` errs by up to 41 ulp on 1e-12..1e-4)."""
    d = _samples()
    exact = _exact(d, Decimal(10) / Decimal(9))
    ulp = np.abs(_powers(d, LINE_EXPONENT) - exact) / np.spacing(exact)
    assert ulp.max() <= 3.0, (ulp.max(), d[ulp.argmax()])
    assert np.mean(ulp) < 0.6


def test_ninth_root_is_exact_to_2_ulp():
    d = np.concatenate([_samples(), [1e300, 1.7e308]])
    exact = _exact(d, Decimal(1) / Decimal(9))
    ulp = np.abs(_roots(d) - exact) / np.spacing(exact)
    assert ulp.max() <= 2.0, (ulp.max(), d[ulp.argmax()])
    inf_nan = _roots(np.array([np.inf, np.nan]))
    assert inf_nan[0] == np.inf and np.isnan(inf_nan[1])


def test_other_exponents_use_exp_log():
    d = 10 ** np.linspace(-12, -4, 50)
    assert_allclose(_powers(d, 1.5), d**1.5, rtol=1e-13)


@njit
def _sincos_all(a):
    out = np.empty((a.size, 2))
    for i in range(a.size):
        out[i, 0], out[i, 1] = kernel._sincos(a[i])
    return out


def test_sincos_is_exact_to_1_ulp_of_1():
    """The table cos/sin of roller 1's angle: absolute error <= 1.2e-16 against the extended
    precision libm (about one unit in the last place of 1; the angle itself carries more)."""
    rng = np.random.default_rng(7)
    a = np.concatenate(
        [
            rng.uniform(-30.0, 30.0, 20000),  # the seed case: rho theta up to 24 rad
            rng.uniform(-2e4, 2e4, 5000),  # up to the end of the table reduction
            [0.0, math.pi / 2, math.pi, -math.pi / 2, 2e4, -2e4, 2.0001e4, 1e6],  # then libm
        ]
    )
    got = _sincos_all(a)
    if np.finfo(np.longdouble).eps < np.finfo(float).eps:
        ref = np.stack([np.cos(a.astype(np.longdouble)), np.sin(a.astype(np.longdouble))], 1)
        assert np.abs(got - ref).astype(float).max() <= 1.2e-16
    assert_allclose(got[:, 0], np.cos(a), rtol=0, atol=3e-16)
    assert_allclose(got[:, 1], np.sin(a), rtol=0, atol=3e-16)


#: the NumPy reference sums the forces in another order: 1e-12 of each component's largest
#: value over the span covers that rounding (observed <= 1.1e-13)
RHS_RTOL = 1e-12


@pytest.mark.parametrize(
    "params",
    [
        CROSSING,
        replace(CROSSING, spall_load="dynamic"),
        replace(CROSSING, contact_law="harris"),
        replace(CROSSING, spall=None),
        # the spall at the top, outside the load zone, roller 1 crossing it
        replace(
            CROSSING, spall=replace(CROSSING.spall, angle=0.0), first_roller_angle=0.5 * math.pi
        ),
    ],
    ids=["seed-spall", "dynamic-spall-load", "harris-contact", "healthy", "spall-at-top"],
)
def test_rhs_equals_numpy_reference_state_by_state(params):
    """The compiled right-hand side of seed IAS eq. (32) and the independent NumPy one at the
    states of a 0.05 s run (a spall crossing for the spalled cases)."""
    r = simulate_ias(params, 0.05, 1e-5, 20_000.0)
    p = pack_parameters(params)
    ref = ReferenceRhs(params)
    states = r.state[::2]
    got = np.empty_like(states)
    want = np.empty_like(states)
    spall = np.empty(len(states))
    for i, y in enumerate(states):
        kernel._rhs(0.0, y, p, got[i])
        want[i] = ref(0.0, y)
        spall[i] = kernel._forces(y, p, 1.0)[4]
    if params.spall is not None and params.spall.angle == math.pi:
        assert np.count_nonzero(spall) > 50  # the crossing is sampled
    scale = np.abs(want).max(axis=0)
    assert_array_less(
        np.abs(got - want).max(axis=0), RHS_RTOL * scale + 1e-300, err_msg="kernel vs NumPy"
    )


def test_compiled_rhs_has_no_reference_counting():
    """A fresh compile of ``ias_rhs`` and ``ias_aux`` holds no ``NRT_incref``/``NRT_decref``
    call (module docstring of the kernel: they cost about a quarter of the step)."""
    for f in (kernel.ias_rhs, kernel.ias_aux):
        ir = cfunc(RHS_SIG, error_model="numpy")(f._pyfunc).inspect_llvm()
        assert "call void @NRT_incref" not in ir and "call void @NRT_decref" not in ir


def test_inlined_driver_equals_generic_integrator():
    """``kernel.ias_rk4`` (``integrate._rk4_inline`` with the right-hand side inlined, used by
    ``simulate_ias``) steps exactly as the generic ``_rk4_fixed`` with the cfuncs: same bits."""
    p = pack_parameters(CROSSING)
    y0 = initial_state(CROSSING)
    kw = dict(dt=1e-6, n_out=61, decim=500, n_aux=N_AUX, bound=1e9)
    generic = run_fixed(kernel.ias_rhs, kernel.ias_aux, y0, p, **kw)
    inlined = run_fixed(kernel.ias_rhs, kernel.ias_aux, y0, p, driver=kernel.ias_rk4, **kw)
    assert generic.aux[:, 2].max() > 100.0  # the spall crossing is in the 0.03 s
    for name in ("t", "y", "aux"):
        assert np.array_equal(getattr(generic, name), getattr(inlined, name)), name
    # the driver reports a divergence as the generic loop does: theta passes 1e-3 rad
    with pytest.raises(SolverError, match="integration diverged at t = .* past its bound"):
        kw["bound"] = 1e-3
        run_fixed(kernel.ias_rhs, kernel.ias_aux, y0, p, driver=kernel.ias_rk4, **kw)


def test_second_process_loads_the_ias_kernels_from_the_cache():
    """The driver and the cfuncs are cached on disk (their lookup tables are compile-time
    constants, not dynamic globals): a second process compiles nothing."""
    code = (
        "import json\n"
        "from bearingsim import get_bearing\n"
        "from bearingsim.dynamics.ias import _kernel as kernel\n"
        "from bearingsim.dynamics.ias.model import IasParams, simulate_ias\n"
        "s = IasParams(get_bearing('NU204-ECP'))\n"
        "simulate_ias(s, 0.002, 1e-6, 10_000.0)\n"
        "simulate_ias(s, 0.002, 1e-6, 10_000.0, method='dopri5')\n"
        "miss = sum(kernel.ias_rk4.stats.cache_misses.values())\n"
        "hits = [f.cache_hits for f in (kernel.ias_rhs, kernel.ias_aux)]\n"
        "print(json.dumps({'miss': miss, 'cfunc_hits': hits}))\n"
    )
    src = str(Path(__file__).resolve().parents[1] / "src")
    env = {**os.environ, "PYTHONPATH": src}
    for _ in range(2):
        p = subprocess.run(
            [sys.executable, "-W", "error", "-c", code],
            capture_output=True,
            text=True,
            env=env,
            timeout=600,
        )
        assert p.returncode == 0, p.stderr
    d = json.loads(p.stdout.strip().splitlines()[-1])
    assert d["miss"] == 0 and all(h >= 1 for h in d["cfunc_hits"]), d
