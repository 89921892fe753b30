"""Instantaneous angular speed of a cylindrical roller bearing with an outer-race spall
(seed IAS, Han, Guo & Fan 2025): the 3-DOF model, its SciPy reference and its result.

- :mod:`.model` — inputs (:class:`IasParams`), derived constants, the packed parameter vector,
  :func:`simulate_ias`.
- :mod:`.kernel` — the compiled right-hand side (Numba cfuncs) and its parameter layout.
- :mod:`.reference` — a NumPy/SciPy implementation of the same equations (for checks and
  benchmarks).
- :mod:`.result` — :class:`IasResult`.
- :mod:`.scenario` — the IAS scenario file.

May import: errors, geometry, catalog, contact, load_distribution, io, signal, results,
:mod:`bearingsim.dynamics.integrate`.
"""

from .model import ContactLaw, IasParams, SpallLoad, derive_constants, simulate_ias
from .result import IasResult

__all__ = ["ContactLaw", "IasParams", "IasResult", "SpallLoad", "derive_constants", "simulate_ias"]
