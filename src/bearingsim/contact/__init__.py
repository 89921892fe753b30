"""Contact mechanics of one rolling element against a raceway.

- :mod:`.hertz` — Hertz point contact (balls: exact elliptic integrals or Hamrock–Brewe),
  subsurface stresses on the depth axis, line contact (rollers: Hertz half-width, Palmgren
  10/9 load–deflection), element stiffness constants.
- :mod:`.pereira` — the empirical line-contact stiffness laws of Pereira et al. (2011) that the
  seed IAS model uses (seed IAS eqs. (5)–(13)).
- :mod:`.capacity` — the static capacity ``C_0`` (ISO 76) from the bearing's own Hertz contact
  and the load check every model applies before it runs (:func:`check_load`: warn above
  ``C_0``, refuse above ``2 C_0`` unless ``allow_overload``).

May import: :mod:`bearingsim.errors`, :mod:`~bearingsim.geometry`, :mod:`~bearingsim.materials`.
"""

from .capacity import (
    STATIC_LIMIT_FACTOR,
    StaticCapacity,
    StaticCapacityWarning,
    check_element_load,
    check_load,
    equivalent_static_load,
    static_capacity,
)
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
    "STATIC_LIMIT_FACTOR",
    "StaticCapacity",
    "StaticCapacityWarning",
    "check_element_load",
    "check_load",
    "equivalent_static_load",
    "static_capacity",
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
