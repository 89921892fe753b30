"""Contact-fatigue life: damage mechanics on a plane-strain FE model (seed LIFE) and the ISO 281 /
ISO/TS 16281 ratings beside it.

Modules: :mod:`.damage` (damage law, S–N fit, torsion check), :mod:`.analytic` (McEwen
line-contact field), :mod:`.fe` (scikit-fem plane-strain section under a moving Hertz pressure),
:mod:`.validation` (FE vs McEwen), :mod:`.fatigue` (semi-decoupled damage loop,
:class:`LifeResult`), :mod:`.iso281` (ISO 281 rating, static capacity, cycle/revolution/hour
conversions), :mod:`.reference_life` (ISO/TS 16281 reference rating life from the load
distribution).

May import: errors, io, geometry, materials, catalog, signal, results, contact,
load_distribution; never another model family.
"""

from .damage import GCR15_TORSION, DamageLaw, SNCurve, fit_sn_curve, torsion_check
from .fatigue import ElementLoadMethod, LifeResult, contact_fatigue_life, inner_contact
from .fe import ShearMeasure, contact_section, section_spec
from .iso281 import (
    StaticCapacityWarning,
    basic_rating_life,
    dynamic_load_rating,
    inner_race_cycles_per_revolution,
    static_capacity,
)
from .reference_life import reference_rating_life
from .validation import validate_against_hertz

__all__ = [
    "GCR15_TORSION",
    "DamageLaw",
    "ElementLoadMethod",
    "LifeResult",
    "SNCurve",
    "ShearMeasure",
    "StaticCapacityWarning",
    "basic_rating_life",
    "contact_fatigue_life",
    "contact_section",
    "dynamic_load_rating",
    "fit_sn_curve",
    "inner_contact",
    "inner_race_cycles_per_revolution",
    "reference_rating_life",
    "section_spec",
    "static_capacity",
    "torsion_check",
    "validate_against_hertz",
]
