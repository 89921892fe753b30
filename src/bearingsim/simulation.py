"""``bearingsim.simulate(scenario)``: one entry point for every time-domain model family.

The scenario's ``model`` chooses the family (:mod:`bearingsim.config`) and so the runner:

- ``vsm``, ``dem``, ``tvsm``: :func:`bearingsim.dynamics.ring.scenario.run_ring`;
- ``rotor``: :func:`bearingsim.dynamics.rotor.scenario.run_rotor`;
- ``ias``: :func:`bearingsim.dynamics.ias.scenario.run_ias`.

Every result is a :class:`~bearingsim.results.SimulationResult` (``time``, named ``channels``
with units, the scenario and the solver metadata; netCDF save/load). The families are imported
on first use, so ``import bearingsim`` loads no compiled kernel. Results are bit-reproducible
for the same scenario (measurement noise from ``numpy.random.default_rng(seed)``, or with a rig
from ``SeedSequence([seed, 4])``, added after the rig's path).
"""

from __future__ import annotations

import importlib
from collections.abc import Callable
from pathlib import Path
from typing import Any

from .config import Model, Scenario
from .dynamics.budget import Budget, Estimate
from .errors import ConfigError

#: model -> (module, runner, checker): ``runner(scenario, progress, budget, allow_overload) ->
#: SimulationResult``; ``checker(scenario, budget, allow_overload) -> Estimate`` checks every
#: input and the resources without running (bad values raise)
_RUNNERS: dict[Model, tuple[str, str, str]] = {
    Model.VSM: ("bearingsim.dynamics.ring.scenario", "run_ring", "check_ring"),
    Model.DEM: ("bearingsim.dynamics.ring.scenario", "run_ring", "check_ring"),
    Model.TVSM: ("bearingsim.dynamics.ring.scenario", "run_ring", "check_ring"),
    Model.ROTOR: ("bearingsim.dynamics.rotor.scenario", "run_rotor", "check_rotor"),
    Model.IAS: ("bearingsim.dynamics.ias.scenario", "run_ias", "check_ias"),
}

#: the models :func:`simulate` runs
MODELS: tuple[Model, ...] = tuple(_RUNNERS)


def _entry(model: Model, which: int) -> Callable[..., Any]:
    try:
        mod, *names = _RUNNERS[model]
    except KeyError:
        raise ConfigError(f"model = {model.value!r} has no registered runner") from None
    from .dynamics.notice import compile_notice

    with compile_notice(f"the {model.value} model"):
        return getattr(importlib.import_module(mod), names[which])


def as_scenario(scenario: Scenario | dict[str, Any] | str | Path) -> Scenario:
    """A validated :class:`~bearingsim.config.Scenario` from a scenario, a dict of its keys or a
    TOML path."""
    if isinstance(scenario, dict):
        scenario = Scenario.from_dict(scenario)
    elif isinstance(scenario, str | Path):
        scenario = Scenario.from_toml(scenario)
    if not isinstance(scenario, Scenario):
        raise ConfigError(f"scenario = {scenario!r} is not a Scenario, dict or TOML path")
    return scenario


def validate_scenario(
    scenario: Scenario, budget: Budget | None = None, allow_overload: bool = False
) -> Estimate:
    """Check ``scenario`` without running it — every input, the load against the bearing's
    static capacity, the speed, and the memory and step estimate against ``budget`` — so that
    bad values raise their one-line :class:`ConfigError` before any work or output; returns the
    resource :class:`~bearingsim.dynamics.budget.Estimate`."""
    return _entry(scenario.model, 1)(scenario, budget, allow_overload)


def simulate(
    scenario: Scenario | dict[str, Any] | str | Path,
    progress: Callable[[int], None] | None = None,
    *,
    budget: Budget | None = None,
    allow_overload: bool = False,
):
    """Run one simulation of any model family.

    Parameters
    ----------
    scenario : Scenario, dict or path
        The inputs (:class:`bearingsim.config.Scenario` of the model's family, a dict of its
        keys or a TOML path; ``model`` chooses the family).
    progress : callable, optional
        Called with the number of output samples done (for progress bars).
    budget : Budget, optional
        Memory [B] and step limits of the run (:class:`bearingsim.dynamics.budget.Budget`;
        default: half the available memory, 10^9 steps); a run whose estimate exceeds it is
        refused before it starts.
    allow_overload : bool
        Run a radial load above twice the bearing's static capacity C0 (ISO 76) instead of
        refusing it (a warning is given above C0 either way).

    Returns
    -------
    SimulationResult
        Time [s] and the model's channels with their units (ring models: displacement [m],
        velocity [m/s], acceleration [m/s^2] in x and y, effective stiffness [N/m], optionally
        per-ball loads [N]; rotor: drive- and fan-end housing accelerations; IAS: the inner-ring
        state, shaft angle [rad] and speed [rad/s], torques [N m]) and every input as metadata;
        for ``model = "ias"`` an :class:`~bearingsim.dynamics.ias.result.IasResult`.
    """
    scenario = as_scenario(scenario)
    return _entry(scenario.model, 0)(scenario, progress, budget, allow_overload)


__all__ = ["MODELS", "as_scenario", "simulate", "validate_scenario"]
