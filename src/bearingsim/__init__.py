"""bearingsim: physics-based rolling-bearing analysis.

The short public API: bearings (:func:`get_bearing`, :class:`BallBearing`, …), kinematics, the
errors, and — loaded on first use — :func:`simulate`, :class:`Scenario`,
:class:`SimulationResult`. Everything else lives in its model family's subpackage
(``docs/architecture.md`` has the folder map and the layers: io → bearing data → config →
signal → results → contact → load distribution → model families → simulation → sweep → report →
cli; a lower layer never imports a higher one, and ``tests/test_layers.py`` checks it).
``import bearingsim`` imports no SciPy, Numba, xarray, Dask or Matplotlib.
"""

from ._version import __version__
from .catalog import get_bearing, list_bearings, load_bearing_file
from .errors import BearingsimError, ConfigError, SolverError
from .geometry import BallBearing, RollerBearing, characteristic_frequencies
from .materials import Material

#: lazily loaded names (PEP 562): name -> (module, attribute); ``import bearingsim`` stays light
_LAZY = {
    "simulate": (".simulation", "simulate"),
    "Scenario": (".config", "Scenario"),
    "RingScenario": (".config", "RingScenario"),
    "RotorScenario": (".config", "RotorScenario"),
    "IasScenario": (".config", "IasScenario"),
    "Defect": (".geometry", "Defect"),
    "Race": (".geometry", "Race"),
    "SimulationResult": (".results", "SimulationResult"),
    "load_result": (".results", "load_result"),
}


def __getattr__(name: str):
    """The lazy names of :data:`_LAZY`: ``bearingsim.simulate(scenario)``, the scenario classes,
    ``Defect``, ``Race``, ``SimulationResult``, ``load_result``."""
    if name in _LAZY:
        import importlib

        mod, attr = _LAZY[name]
        return getattr(importlib.import_module(mod, __name__), attr)
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")


__all__ = [
    "BallBearing",
    "BearingsimError",
    "ConfigError",
    "Defect",
    "IasScenario",
    "Material",
    "Race",
    "RingScenario",
    "RollerBearing",
    "RotorScenario",
    "Scenario",
    "SimulationResult",
    "SolverError",
    "__version__",
    "characteristic_frequencies",
    "get_bearing",
    "list_bearings",
    "load_bearing_file",
    "load_result",
    "simulate",
]
