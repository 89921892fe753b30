"""Instantaneous angular speed of a cylindrical roller bearing with an outer-race spall
(seed IAS, Han, Guo & Fan 2025): the 3-DOF model, its SciPy reference, its result and the
spall-width estimate.

- :mod:`.model` — inputs (:class:`IasParams`), derived constants, the packed parameter vector,
  :func:`simulate_ias`.
- :mod:`._kernel` — the compiled right-hand side (Numba cfuncs) and its parameter layout.
- :mod:`.reference` — a NumPy/SciPy implementation of the same equations (for checks and
  benchmarks).
- :mod:`.result` — :class:`IasResult`.
- :mod:`.spall` — the spall-width estimate from an IAS signal (seed IAS eq. (37)), simulated or
  measured, and the angle-domain summary :class:`IasSummary`.
- :mod:`.scenario` — the IAS scenario file.

May import: errors, geometry, catalog, contact, load_distribution, io, signal, results,
:mod:`bearingsim.dynamics.integrate`.
"""

from .model import ContactLaw, IasParams, SpallLoad, derive_constants, simulate_ias
from .result import IasResult
from .spall import (
    IasSummary,
    SpallEstimate,
    SpallEstimator,
    analyze_speed_signal,
    estimate_spall_width,
    spall_width_from_angle,
)

__all__ = [
    "ContactLaw",
    "IasParams",
    "IasResult",
    "IasSummary",
    "SpallEstimate",
    "SpallEstimator",
    "SpallLoad",
    "analyze_speed_signal",
    "derive_constants",
    "estimate_spall_width",
    "simulate_ias",
    "spall_width_from_angle",
]
