"""The bearing–rotor–housing system of the CWRU rig (seed ROTOR, Liu et al. 2021).

- :mod:`.fe` — Euler–Bernoulli/Rayleigh beam elements, disks, condensation, Craig–Bampton,
  complex modes.
- :mod:`.config` — the system's inputs (shaft, armature, bearings, housings, defects).
- :mod:`.model` — assembly, static equilibrium, :func:`simulate_rotor`, :func:`rotor_modes`.
- :mod:`._kernel` (private) — the compiled right-hand side (ball DOFs, Hertz contacts, defects).
- :mod:`.response` — :class:`RotorResponse`.
- :mod:`.scenario` — the runner behind ``bearingsim.simulate`` for ``model = "rotor"``.

May import: errors, geometry, catalog, contact, io, signal, results,
:mod:`bearingsim.dynamics.integrate`.
"""

from ...geometry import DefectProfile
from .config import (
    Armature,
    BearingSupport,
    Housing,
    RotorConfig,
    Shaft,
    ShaftMassModel,
    cwru_rotor_config,
    default_housing,
    housing_from_frequency,
)
from .fe import Disk
from .model import rotor_modes, simulate_rotor
from .response import RotorResponse

__all__ = [
    "Armature",
    "BearingSupport",
    "DefectProfile",
    "Disk",
    "Housing",
    "RotorConfig",
    "RotorResponse",
    "Shaft",
    "ShaftMassModel",
    "cwru_rotor_config",
    "default_housing",
    "housing_from_frequency",
    "rotor_modes",
    "simulate_rotor",
]
