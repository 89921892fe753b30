"""Quasi-static ball-bearing models (seed QS5): equilibrium of the inner ring under five loads,
ring misalignment, ball-distribution error, stiffness matrices and their fluctuation.

- :mod:`.inputs` — validated inputs (misalignment, speed effects, method) and the derived
  groove-centre geometry shared by both methods (seed QS5 eqs. (1)–(5)).
- :mod:`.jones` — the Jones/Harris 5-DOF model (seed QS5 eqs. (1)–(7)), analytic tangent stiffness.
- :mod:`._kernels` — its compiled inner loops (private; packed parameter vector).
- :mod:`.iso16281` — the ISO/TS 16281 load-distribution method, independent of Jones's.
- :mod:`.result` — :class:`QuasiStaticSolution` and the labelled :class:`StiffnessMatrix`
  (netCDF save/load, the result pattern of :mod:`bearingsim.results`).
- :mod:`.stiffness` — stiffness vs cage angle, order spectra, :class:`StiffnessResult`.

May import: errors, geometry, materials, results, :mod:`bearingsim.contact`,
:mod:`bearingsim.io`, :mod:`bearingsim.signal`.
"""

from .inputs import (
    DEFAULT_GROOVE_DEPTH_RATIO,
    Method,
    Misalignment,
    QSGeometry,
    SpeedEffects,
    check_ball_errors,
    check_misalignment,
    load_vector,
    max_contact_angle_default,
    max_tilt,
    qs_geometry,
)
from .iso16281 import (
    ISO_CP_FACTOR,
    ISO_INNER_CONFORMITY,
    ISO_OUTER_CONFORMITY,
    Conformities,
    iso_geometry,
    iso_stiffness_constant,
    run_iso16281,
)
from .jones import run_quasi_static, solve_equilibrium
from .result import (
    DOF_NAMES,
    DOF_UNITS,
    LOAD_NAMES,
    LOAD_UNITS,
    STIFFNESS_UNITS,
    QuasiStaticSolution,
    StiffnessMatrix,
)
from .stiffness import (
    SERIES,
    SpectralComponent,
    StiffnessResult,
    StiffnessSpectrum,
    stiffness_vs_cage,
)

__all__ = [
    "DEFAULT_GROOVE_DEPTH_RATIO",
    "DOF_NAMES",
    "DOF_UNITS",
    "ISO_CP_FACTOR",
    "ISO_INNER_CONFORMITY",
    "ISO_OUTER_CONFORMITY",
    "LOAD_NAMES",
    "LOAD_UNITS",
    "SERIES",
    "STIFFNESS_UNITS",
    "Conformities",
    "Method",
    "Misalignment",
    "QSGeometry",
    "QuasiStaticSolution",
    "SpectralComponent",
    "SpeedEffects",
    "StiffnessMatrix",
    "StiffnessResult",
    "StiffnessSpectrum",
    "check_ball_errors",
    "check_misalignment",
    "iso_geometry",
    "iso_stiffness_constant",
    "load_vector",
    "max_contact_angle_default",
    "max_tilt",
    "qs_geometry",
    "run_iso16281",
    "run_quasi_static",
    "solve_equilibrium",
    "stiffness_vs_cage",
]
