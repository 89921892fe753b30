"""bearingsim: physics-based rolling-bearing analysis.

Layers (lower never imports higher): geometry/materials/catalog → hertz → load_distribution →
models (quasi_static, dynamics/*, life/*) → signal → report/cli.
"""

from ._version import __version__
from .catalog import get_bearing, list_bearings, load_bearing_file
from .errors import BearingsimError, ConfigError, SolverError
from .geometry import BallBearing, RollerBearing, characteristic_frequencies
from .materials import Material

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
