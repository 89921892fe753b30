"""Quasi-static ball-bearing models (seed QS5): equilibrium of the inner ring under five loads,
ring misalignment, ball-distribution error, stiffness matrices and their fluctuation.

- :mod:`.jones` — the Jones/Harris 5-DOF model (seed QS5 eqs. (1)–(7)), analytic tangent stiffness.
- :mod:`._kernels` — its compiled inner loops (private).
- :mod:`.iso16281` — the ISO/TS 16281 load-distribution method, independent of Jones's.
- :mod:`.stiffness` — stiffness vs cage angle, order spectra, :class:`StiffnessResult`.

May import: errors, geometry, materials, :mod:`bearingsim.contact`, :mod:`bearingsim.io`,
:mod:`bearingsim.signal`.
"""

from .iso16281 import iso_geometry, run_iso16281
from .jones import (
    DOF_NAMES,
    Method,
    Misalignment,
    QSGeometry,
    QuasiStaticSolution,
    SpeedEffects,
    qs_geometry,
    run_quasi_static,
    solve_equilibrium,
)
from .stiffness import StiffnessResult, stiffness_vs_cage

__all__ = [
    "DOF_NAMES",
    "Method",
    "Misalignment",
    "QSGeometry",
    "QuasiStaticSolution",
    "SpeedEffects",
    "StiffnessResult",
    "iso_geometry",
    "qs_geometry",
    "run_iso16281",
    "run_quasi_static",
    "solve_equilibrium",
    "stiffness_vs_cage",
]
