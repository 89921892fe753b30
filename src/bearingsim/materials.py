"""Elastic materials of rings and rolling elements."""

from __future__ import annotations

from dataclasses import dataclass

from .errors import check_range

__all__ = [
    "BEARING_STEEL",
    "DENSITY_RANGE",
    "effective_modulus",
    "Material",
    "POISSON_RANGE",
    "YOUNGS_MODULUS_RANGE",
]

#: Young's modulus of the materials rolling bearings are made of [Pa]: from engineering
#: polymers (POM, PA, PEEK: 2-4 GPa) through bearing steel (~210 GPa), silicon nitride
#: (~310 GPa) and tungsten carbide (~600 GPa) to diamond (~1.1 TPa, the stiffest solid);
#: Ashby, "Materials Selection in Mechanical Design" (2011), chart of E.
YOUNGS_MODULUS_RANGE = (1e9, 1.2e12)
#: Poisson's ratio of isotropic bearing materials [-]: ceramics ~0.25, steel 0.3, polymers up
#: to ~0.45; 0.5 is incompressible (excluded); negative values are auxetic foams (Ashby 2011).
POISSON_RANGE = (0.0, 0.5)
#: Density [kg/m^3]: polymers (~900) to the densest element, osmium (22 590); steel 7850,
#: silicon nitride 3200, tungsten carbide 15 600 (Ashby 2011).
DENSITY_RANGE = (800.0, 22600.0)


@dataclass(frozen=True)
class Material:
    """Linear-elastic isotropic material.

    Parameters
    ----------
    youngs_modulus : float
        Young's modulus E [Pa], in [1 GPa, 1.2 TPa] (:data:`YOUNGS_MODULUS_RANGE`).
    poisson_ratio : float
        Poisson's ratio nu [-], in [0, 0.5) (:data:`POISSON_RANGE`).
    density : float
        Mass density [kg/m^3], in [800, 22600] (:data:`DENSITY_RANGE`).
    name : str
        Label, e.g. ``"bearing steel"``.
    """

    youngs_modulus: float = 207e9
    poisson_ratio: float = 0.3
    density: float = 7850.0
    name: str = "bearing steel"

    def __post_init__(self) -> None:
        e = check_range("youngs_modulus_pa", self.youngs_modulus, *YOUNGS_MODULUS_RANGE, unit="Pa")
        nu = check_range("poisson_ratio", self.poisson_ratio, *POISSON_RANGE, hi_open=True)
        rho = check_range("density_kg_m3", self.density, *DENSITY_RANGE, unit="kg/m^3")
        object.__setattr__(self, "youngs_modulus", e)
        object.__setattr__(self, "poisson_ratio", nu)
        object.__setattr__(self, "density", rho)

    @property
    def plane_strain_modulus(self) -> float:
        """``E / (1 - nu^2)`` [Pa]."""
        return self.youngs_modulus / (1.0 - self.poisson_ratio**2)


#: Through-hardened bearing steel (AISI 52100 / GCr15), Harris & Kotzalas (2007) table 5.x values.
BEARING_STEEL = Material()


def effective_modulus(m1: Material, m2: Material) -> float:
    """Hamrock–Brewe effective modulus ``E' = 2 / [(1-nu1^2)/E1 + (1-nu2^2)/E2]`` [Pa].

    For two equal materials ``E' = E / (1 - nu^2)``. Hamrock & Brewe (1983), eq. (6).
    """
    return 2.0 / (
        (1.0 - m1.poisson_ratio**2) / m1.youngs_modulus
        + (1.0 - m2.poisson_ratio**2) / m2.youngs_modulus
    )
