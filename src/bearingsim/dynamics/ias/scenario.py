"""The IAS model behind :func:`bearingsim.simulate` (``model = "ias"``): an
:class:`~bearingsim.config.IasScenario` becomes :class:`~.model.IasParams` and runs on the
output grid of the scenario.

The keys are those of :class:`bearingsim.config.IasScenario` (seed IAS §3.1 defaults). The shaft
speed is never imposed: ``rpm`` only sets the motor torque ``M_z = C_T w`` so that the free speed
``M_z / C_T`` equals it; the actual speed comes out of the torque balance.

Output grid: ``decim = max(1, round(1/(fs_hz dt_s)))`` RK4 steps per output sample and the step
``1/(fs_hz decim)`` (``dt_s`` rounded so that the output interval is an exact number of steps, as
in the ring models); the seed's ``dt_s = 1e-6`` s is kept exactly at ``fs_hz`` = 50, 20 or 10 kHz.
"""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Callable
from dataclasses import replace
from pathlib import Path
from typing import TYPE_CHECKING, Any

from ...catalog import resolve_bearing
from ...config import IasScenario
from ...errors import ConfigError, read_toml
from ..budget import Budget, Estimate, check_budget
from ..checks import check_load, check_speed
from .model import (
    MAX_COUNT,
    SEED_SPALL,
    ContactLaw,
    IasParams,
    SpallLoad,
    _grid,
    check_step,
    ias_estimate,
    simulate_ias,
)

if TYPE_CHECKING:
    from .result import IasResult

__all__ = ["check_ias", "ias_params", "output_grid", "read_scenario", "run_ias"]


def ias_params(sc: IasScenario) -> IasParams:
    """The :class:`IasParams` of an IAS scenario (every value validated; bad ones raise a
    one-line :class:`~bearingsim.errors.ConfigError`)."""
    if not isinstance(sc, IasScenario):
        raise ConfigError(f"scenario model = {sc.model.value!r} is not the IAS model")
    bearing = resolve_bearing(sc.bearing, sc.bearing_file)
    spall = None
    if sc.spall_width_m > 0.0:
        spall = replace(SEED_SPALL, width=sc.spall_width_m, angle=math.radians(sc.spall_angle_deg))
    return IasParams(
        bearing,
        spall=spall,
        fx=sc.fx_n,
        fy=sc.fy_n,
        torque=sc.motor_torque_n_m,
        mass=sc.mass_kg,
        inertia=sc.inertia_kg_m2,
        radial_damping=sc.radial_damping_n_s_per_m,
        torsional_damping=sc.torsional_damping_n_m_s_per_rad,
        rolling_resistance=sc.rolling_resistance,
        contact_law=ContactLaw(sc.contact_law),
        spall_load=SpallLoad(sc.spall_load),
        reference_load=sc.reference_load_n,
        # the model's frame: Phi_0 from +x counter-clockwise = pi/2 - psi_0
        first_roller_angle=0.5 * math.pi - math.radians(sc.first_roller_angle_deg),
        initial_speed=2.0 * math.pi * sc.initial_rpm / 60.0,
    )


def output_grid(sc: IasScenario) -> tuple[int, float]:
    """RK4 steps per output sample and the step [s] (module docstring)."""
    decim = max(1, round(min(1.0 / (sc.fs_hz * sc.dt_s), MAX_COUNT)))
    return decim, 1.0 / (sc.fs_hz * decim)


def check_ias(
    sc: IasScenario, budget: Budget | None = None, allow_overload: bool = False
) -> Estimate:
    """Check an IAS scenario without running it: every input (:func:`ias_params`), the radial
    load against the bearing's static capacity (:func:`..checks.check_load`), the free speed
    ``M_z / C_T`` and the initial speed against what the output resolves
    (:func:`..checks.check_speed`), the step's stability and the memory and step estimate
    against ``budget``; returns the estimate."""
    params = ias_params(sc)
    check_load(params.bearing, params.radial_load, allow_overload, name="|(fx_n, fy_n)|")
    free_rpm = 60.0 * params.torque / (2.0 * math.pi * params.torsional_damping)
    if free_rpm > 0.0:
        check_speed(params.bearing, free_rpm, sc.fs_hz, "free speed M_z/C_T")
    if sc.initial_rpm > 0.0:
        check_speed(params.bearing, sc.initial_rpm, sc.fs_hz, "initial_rpm")
    check_step(params, sc.dt_s)  # the given step must be stable before it is rounded
    _decim, dt = output_grid(sc)
    decim, _n, n_out = _grid((sc.n_samples - 1) / sc.fs_hz, dt, sc.fs_hz)
    return check_budget(ias_estimate(n_out, decim), budget)


def run_ias(
    sc: IasScenario,
    progress: Callable[[int], None] | None = None,
    budget: Budget | None = None,
    allow_overload: bool = False,
) -> IasResult:
    """Run an IAS scenario (the runner behind :func:`bearingsim.simulate`): ``n_samples``
    output samples at ``fs_hz`` from ``t = 0``, checked first by :func:`check_ias`;
    ``progress`` is called with the samples done after each piece of the run."""
    check_ias(sc, budget, allow_overload)
    params = ias_params(sc)
    _decim, dt = output_grid(sc)
    span = (sc.n_samples - 1) / sc.fs_hz  # n_samples samples, the last at span
    res = simulate_ias(params, span, dt, sc.fs_hz, sc.solver.value, progress=progress,
                       budget=budget)  # fmt: skip
    return dataclasses.replace(res, scenario=sc.to_dict())


# ------------------------------------------------------------------ the `ias` command's files
def read_scenario(path: str | Path) -> dict[str, Any]:
    """Read an IAS scenario TOML (keys of :class:`~bearingsim.config.IasScenario`; ``model`` may
    be left out) into a dict of validated keys; ``bearing_file`` is made absolute."""
    p = Path(path)
    data = read_toml(p, "scenario =")
    if not isinstance(data, dict):
        raise ConfigError(f"{p.name}: a scenario must be a table of keys")
    data.setdefault("model", "ias")
    if isinstance(data.get("bearing_file"), str):
        data["bearing_file"] = str((p.parent / data["bearing_file"]).resolve())
    sc = IasScenario.from_dict(data, origin=p.name)
    given = set(data) | {IasScenario.RENAMED.get(k, k) for k in data}
    return {k: v for k, v in sc.to_dict().items() if k in given}
