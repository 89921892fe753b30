"""Check of the undamaged plane-strain FE section against McEwen's line-contact field."""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..signal.peaks import parabola_vertex
from .analytic import mcewen_stresses
from .fe import ContactSection, SectionStresses, ShearMeasure

__all__ = [
    "HertzValidation",
    "validate_against_hertz",
]


@dataclass(frozen=True)
class HertzValidation:
    """Undamaged FE stresses vs the McEwen line-contact field, load centred at ``x_c = 0``.

    Attributes
    ----------
    tau_max_fe, tau_max_exact : float
        Peak ``|tau_xz|`` [Pa] (FE: element averages, peak refined by a quadratic through the
        neighbouring centroids in depth and along x; exact ``0.25 p_max``).
    depth_fe, depth_exact : float
        Depth of that peak [m] (exact ``0.5 b``).
    range_max_fe, range_max_exact : float
        Peak of the orthogonal shear range over the pass [Pa] (exact ``0.5 p_max``).
    rms_rel_error : float
        RMS difference of ``tau_xz`` at the centroids in ``|x| <= 3b``, ``z <= 3b`` relative to
        ``0.25 p_max`` [-].
    n_elements : int
        Mesh size [-].
    element_size : float
        Fine element size [m].
    """

    tau_max_fe: float
    tau_max_exact: float
    depth_fe: float
    depth_exact: float
    range_max_fe: float
    range_max_exact: float
    rms_rel_error: float
    n_elements: int
    element_size: float

    @property
    def tau_error(self) -> float:
        """Relative error of the peak orthogonal shear [-]."""
        return self.tau_max_fe / self.tau_max_exact - 1.0

    @property
    def depth_error(self) -> float:
        """Relative error of its depth [-]."""
        return self.depth_fe / self.depth_exact - 1.0


def validate_against_hertz(
    section: ContactSection, stresses: SectionStresses | None = None
) -> HertzValidation:
    """Compare the undamaged FE field with McEwen's line-contact solution (Johnson 1985,
    eq. (4.75)); see :class:`HertzValidation`."""
    st = stresses if stresses is not None else section.solve()
    k0 = int(np.argmin(np.abs(section.positions)))
    tau = st.tau_xz[:, k0]
    cx, cz = section.centroids
    b, p0 = section.b, section.p_max
    i = int(np.argmax(np.abs(tau)))
    sgn = math.copysign(1.0, tau[i])
    # refine in depth along the column of element i, and along x in its row
    col = np.flatnonzero(np.isclose(cx, cx[i], rtol=0, atol=1e-3 * section.spec.element_size))
    col = col[np.argsort(cz[col])]
    j = int(np.flatnonzero(col == i)[0])
    depth, tpeak = cz[i], abs(tau[i])
    if 0 < j < col.size - 1:
        ids = col[j - 1 : j + 2]
        depth, tpeak = parabola_vertex(cz[ids], sgn * tau[ids])
    row = np.flatnonzero(np.isclose(cz, cz[i], rtol=0, atol=1e-3 * section.spec.element_size))
    row = row[np.argsort(cx[row])]
    j = int(np.flatnonzero(row == i)[0])
    if 0 < j < row.size - 1:
        ids = row[j - 1 : j + 2]
        _, tx = parabola_vertex(cx[ids], sgn * tau[ids])
        tpeak = tpeak + (tx - abs(tau[i]))
    sel = (np.abs(cx) <= 3 * b) & (cz <= 3 * b)
    exact = mcewen_stresses(cx[sel], cz[sel], p0, b).tau_xz
    rms = float(np.sqrt(np.mean((tau[sel] - exact) ** 2)) / (0.25 * p0))
    rng = st.shear_range(ShearMeasure.ORTHOGONAL)
    return HertzValidation(
        tau_max_fe=float(tpeak),
        tau_max_exact=0.25 * p0,
        depth_fe=float(depth),
        depth_exact=0.5 * b,
        range_max_fe=float(rng.max()),
        range_max_exact=0.5 * p0,
        rms_rel_error=rms,
        n_elements=section.n_elements,
        element_size=section.spec.element_size,
    )
