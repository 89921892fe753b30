"""Contact mechanics of one rolling element against a raceway.

- :mod:`.hertz` — Hertz point contact (balls: exact elliptic integrals or Hamrock–Brewe),
  subsurface stresses on the depth axis, line contact (rollers: Hertz half-width, Palmgren
  10/9 load–deflection), element stiffness constants.
- :mod:`.pereira` — the empirical line-contact stiffness laws of Pereira et al. (2011) that the
  seed IAS model uses (seed IAS eqs. (5)–(13)).

May import: :mod:`bearingsim.errors`, :mod:`~bearingsim.geometry`, :mod:`~bearingsim.materials`.
"""

from .hertz import (
    EllipticMethod,
    LineContact,
    PointContact,
    SubsurfaceStresses,
    ball_contact,
    ball_stiffness,
    combined_stiffness,
    element_stiffness,
    ellipticity,
    line_contact,
    line_subsurface_stresses,
    point_contact,
    roller_contact,
    subsurface_stresses,
)
from .pereira import SeedLineStiffness, seed_line_stiffness, seed_reference_load

__all__ = [
    "EllipticMethod",
    "LineContact",
    "PointContact",
    "SeedLineStiffness",
    "SubsurfaceStresses",
    "ball_contact",
    "ball_stiffness",
    "combined_stiffness",
    "element_stiffness",
    "ellipticity",
    "line_contact",
    "line_subsurface_stresses",
    "point_contact",
    "roller_contact",
    "seed_line_stiffness",
    "seed_reference_load",
    "subsurface_stresses",
]
