"""Resource budgets of one time-domain run: memory and RK4 steps, estimated from the inputs and
checked before anything is computed or allocated (issue 14).

Every runner (:func:`bearingsim.simulate` and the ``simulate``, ``ias``, ``vsm-trace`` and
``rotor-modes`` commands) estimates the largest memory it will hold at once and the number of
integration steps it will take, from the scenario alone (the automatic step from the stiffness,
the output length, the size of the finite-element mesh), and refuses a run that exceeds its
:class:`Budget` with one line naming the estimate and the budget.

A budget is not a physics input: it is not a scenario key (the scenario is what a sweep hashes
and stores), but an argument of the runners (``simulate(scenario, budget=Budget(...))``) and an
option of the commands (``--max-memory-gb``, ``--max-steps``).

Defaults
    memory: :data:`MEMORY_SHARE` of the memory the operating system reports available when the
    check runs (``MemAvailable`` of ``/proc/meminfo`` on Linux, ``os.sysconf`` elsewhere);
    steps: :data:`MAX_STEPS` RK4 steps (a bound on the work, hence on the wall time, that does
    not depend on the machine: the same scenario is refused or run everywhere).
"""

from __future__ import annotations

import math
import os
from dataclasses import dataclass

from ..errors import ConfigError, check_positive

__all__ = [
    "GB",
    "MAX_STEPS",
    "MEMORY_SHARE",
    "Budget",
    "Estimate",
    "available_memory",
    "check_budget",
]

#: one gigabyte, 10^9 bytes (``--max-memory-gb``) [B]
GB = 1e9
#: share of the available memory a run may use unless told otherwise [-]: half, leaving the
#: other half to the rest of the machine (other processes, the operating system's caches)
MEMORY_SHARE = 0.5
#: RK4 steps a run may take unless told otherwise [-]: 10^9 steps take about 15 min with the ring
#: models (0.4-0.9 us a step), 4 min with the IAS model (0.26 us) and 3 h with the rotor model
#: (11 us) on the development machine (2 cores, 2026); 100 times the seed IAS run (10 s at 1 us)
#: and 10^4 times a 1 s ring run at 48 kHz
MAX_STEPS = 1e9
#: bytes of one float64 [B]
F8 = 8


def available_memory() -> float | None:
    """Memory the operating system can give a new allocation without swapping [B]:
    ``MemAvailable`` of ``/proc/meminfo`` (Linux), else ``os.sysconf("SC_AVPHYS_PAGES")`` times
    the page size; ``None`` when neither is known."""
    try:
        with open("/proc/meminfo", encoding="ascii") as fh:
            for line in fh:
                if line.startswith("MemAvailable:"):
                    return float(line.split()[1]) * 1024.0  # the kernel reports kB
    except (OSError, ValueError, IndexError):
        pass
    try:
        return float(os.sysconf("SC_AVPHYS_PAGES")) * float(os.sysconf("SC_PAGE_SIZE"))
    except (AttributeError, OSError, ValueError):
        return None


@dataclass(frozen=True)
class Budget:
    """Resource limits of one run.

    Parameters
    ----------
    max_memory : float or None
        Largest memory the run may hold at once [B]; ``None`` = :data:`MEMORY_SHARE` of
        :func:`available_memory` when the check runs.
    max_steps : float or None
        Largest number of integration steps [-]; ``None`` = :data:`MAX_STEPS`.
    """

    max_memory: float | None = None
    max_steps: float | None = None

    def __post_init__(self) -> None:
        if self.max_memory is not None:
            object.__setattr__(
                self, "max_memory", check_positive("max_memory_bytes", self.max_memory, "B")
            )
        if self.max_steps is not None:
            object.__setattr__(self, "max_steps", check_positive("max_steps", self.max_steps))

    def memory_limit(self) -> tuple[float, str]:
        """The memory budget [B] and how it was set (for the messages)."""
        if self.max_memory is not None:
            return self.max_memory, "max_memory"  # as given
        avail = available_memory()
        if avail is None:  # nothing known about the machine: no memory limit
            return math.inf, "the available memory is unknown"
        return MEMORY_SHARE * avail, f"{MEMORY_SHARE:.0%} of the {avail / GB:.3g} GB available"

    def step_limit(self) -> float:
        """The step budget [-]."""
        return MAX_STEPS if self.max_steps is None else self.max_steps


@dataclass(frozen=True)
class Estimate:
    """What a run will need, estimated before it starts.

    Attributes
    ----------
    what : str
        The run, briefly (``"vsm: 48001 samples x 3 RK4 steps"``).
    memory : float
        Largest memory held at once [B] (outputs, their copies in the result, the largest
        working array).
    steps : float
        Integration steps [-] (0 when nothing is integrated).
    """

    what: str
    memory: float
    steps: float = 0.0


def _fmt_bytes(n: float) -> str:
    return f"{n / GB:.3g} GB" if math.isfinite(n) else "inf"


def check_budget(estimate: Estimate, budget: Budget | None = None) -> Estimate:
    """Refuse, with one line naming the estimate and the budget, a run whose ``estimate``
    exceeds ``budget`` (default :class:`Budget`); return the estimate otherwise."""
    budget = Budget() if budget is None else budget
    steps = budget.step_limit()
    if not estimate.steps <= steps:
        raise ConfigError(
            f"{estimate.what}: estimated {estimate.steps:.3g} integration steps exceed the step "
            f"budget {steps:.3g}; valid: a shorter or coarser run, or a larger budget "
            "(max_steps, --max-steps)"
        )
    mem, how = budget.memory_limit()
    if not estimate.memory <= mem:
        raise ConfigError(
            f"{estimate.what}: estimated memory {_fmt_bytes(estimate.memory)} exceeds the memory "
            f"budget {_fmt_bytes(mem)} ({how}); valid: a shorter or smaller run, or a larger "
            "budget (max_memory, --max-memory-gb)"
        )
    return estimate
