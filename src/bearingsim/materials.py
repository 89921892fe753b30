"""Elastic materials of rings and rolling elements."""

from __future__ import annotations

from dataclasses import dataclass

from .errors import check_positive, check_range

__all__ = [
    "BEARING_STEEL",
    "effective_modulus",
    "Material",
]


@dataclass(frozen=True)
class Material:
    """Linear-elastic isotropic material.

    Parameters
    ----------
    youngs_modulus : float
        Young's modulus E [Pa].
    poisson_ratio : float
        Poisson's ratio nu [-], in (-1, 0.5).
    density : float
        Mass density [kg/m^3].
    name : str
        Label, e.g. ``"bearing steel"``.
    """

    youngs_modulus: float = 207e9
    poisson_ratio: float = 0.3
    density: float = 7850.0
    name: str = "bearing steel"

    def __post_init__(self) -> None:
        object.__setattr__(
            self, "youngs_modulus", check_positive("youngs_modulus_pa", self.youngs_modulus, "Pa")
        )
        object.__setattr__(
            self,
            "poisson_ratio",
            check_range("poisson_ratio", self.poisson_ratio, -1.0, 0.5, lo_open=True, hi_open=True),
        )
        object.__setattr__(self, "density", check_positive("density_kg_m3", self.density, "kg/m^3"))

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
