"""bearingsim: physics-based rolling-bearing analysis.

Layers (lower never imports higher): geometry/materials/catalog → hertz → load_distribution →
models (quasi_static, dynamics/*, life/*) → signal → report/cli.
"""

from ._version import __version__
from .catalog import get_bearing, list_bearings, load_bearing_file
from .errors import BearingsimError, ConfigError, SolverError
from .geometry import BallBearing, RollerBearing, characteristic_frequencies
from .materials import Material


def __getattr__(name: str):
    """Lazy attributes (PEP 562) of the fault-dynamics layer, so that ``import bearingsim``
    does not load the compiled kernels: ``bearingsim.simulate(scenario)``, ``Scenario``,
    ``SimulationResult``."""
    if name == "simulate":
        from .simulation import simulate

        return simulate
    if name == "Scenario":
        from .config import Scenario

        return Scenario
    if name == "SimulationResult":
        from .results import SimulationResult

        return SimulationResult
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")


__all__ = [
    "BallBearing",
    "BearingsimError",
    "ConfigError",
    "Material",
    "RollerBearing",
    "SolverError",
    "__version__",
    "characteristic_frequencies",
    "get_bearing",
    "list_bearings",
    "load_bearing_file",
]
