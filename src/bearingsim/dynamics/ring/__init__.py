"""Ring models of a deep-groove ball bearing with one local defect (seed VSM, Guo et al. 2025).

- :mod:`.base` — the physical inputs (:class:`ModelInputs`), the compiled-kernel record and the
  integration drivers.
- :mod:`._balance` (private) — the static balance of the inner ring over the discrete balls
  (seed VSM eq. (16)) and the ball-frame helpers, compiled.
- :mod:`.defects` — defect geometry and the retention factor (seed VSM eqs. (1)–(3), (11)).
- :mod:`.vsm`, :mod:`.dem`, :mod:`.tvsm` — the variable-stiffness model and its two baselines.
- :mod:`.trace` — quasi-static stiffness traces vs cage angle (seed VSM figs. 5–12).

May import: errors, geometry, catalog, contact, load_distribution, io, results,
:mod:`bearingsim.dynamics.integrate`.
"""

from ...geometry import DefectGeometry, defect_geometry
from .base import ModelInputs
from .defects import retention_factor
from .trace import StiffnessTrace, stiffness_trace

__all__ = [
    "DefectGeometry",
    "ModelInputs",
    "StiffnessTrace",
    "defect_geometry",
    "retention_factor",
    "stiffness_trace",
]
