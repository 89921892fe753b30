"""Unequal balls (issue 16, realistic signals), shared by the ring and rotor models.

The balls of one bearing differ in diameter by up to the ISO 3290-1 lot diameter variation
``V_DwL`` of their grade (G5 0.25, G10 0.5, G16 0.8, G20 1.0, G28 1.4, G40 2.0 µm). A ball larger
than nominal by ``Delta D_j`` closes the raceway gap along its line by its whole ``Delta D_j``.
"""

from __future__ import annotations

import numpy as np
from numpy.typing import NDArray

__all__ = ["ball_deviations"]


def ball_deviations(n_balls: int, spread: float, seed: tuple[int, ...]) -> NDArray[np.float64]:
    """Diameter deviation of each ball from the nominal, ``Delta D_j`` [m] (ball 1 first; empty
    for ``spread == 0``).

    Draws ``u_j`` uniform in [0, 1) from ``numpy.random.SeedSequence(seed)``, maps them
    affinely so that the largest minus the smallest deviation is ``spread`` [m] exactly, and
    centres them on zero mean (the mean ball keeps the nominal diameter, so the mean clearance
    is unchanged).
    """
    if spread == 0.0 or n_balls < 2:
        return np.zeros(0)
    rng = np.random.default_rng(np.random.SeedSequence(list(seed)))
    u = rng.uniform(size=n_balls)
    u = (u - u.min()) / (u.max() - u.min())
    return spread * (u - u.mean())
