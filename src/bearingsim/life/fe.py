"""Plane-strain finite-element model of the inner-race section under a moving Hertz pressure.

Seed LIFE §2.3 (fig. 14): a ``12 mm x 4 mm`` section of the inner race under the most-loaded
contact, loaded by the Hertz pressure ``p(x) = p_max sqrt(1 - (x/b)^2)`` (eq. (9)); the damaged
plane-strain constitutive law ``sigma = (1 - D) C : epsilon`` (eq. (2)) per element.

**Idealisation (the seed's).** The ball/raceway contact is elliptical (``a >> b``); the seed takes
the point-contact ``p_max`` and the semi-axis ``b`` *along the rolling direction* from Hertz theory
and applies them to a plane-strain section in the rolling plane, i.e. it treats the central strip
of the ellipse as a line contact. The subsurface field of this 2-D model is therefore the McEwen
line-contact field scaled by the point-contact ``p_max`` and ``b`` (orthogonal shear
``0.25 p_max`` at ``0.5 b``), not the 3-D elliptical field — though for a slender ellipse the two
are close (6206 inner contact, ``a/b = 11``: Lundberg–Palmgren ``tau_yz = 0.2495 p_max`` at
``0.497 b``, :func:`bearingsim.hertz.subsurface_stresses`).

**Load cycle.** The pressure is moved across the surface in steps (one pass = one load cycle on
every material point of the section): centres ``x_c`` from ``-s`` to ``+s`` with a step equal to
the fine element size ``h``. Elements within about ``s - b`` of the centre see the full reversal
of the orthogonal shear ``tau_xz`` (``+0.25 p_max`` → ``-0.25 p_max``); elements near the ends of
the traverse see only part of it.

**Numerics.** scikit-fem bilinear (Q1) or biquadratic (Q2) quadrilaterals on a tensor-product
mesh, uniform (size ``h``) in the stressed zone and geometrically graded outside; bottom edge
clamped, lateral edges traction-free. The element stiffness of element ``e`` is
``(1 - D_e) K_e``: the COO assembly data of ``K_e`` are computed once and mapped to the fixed CSR
pattern of the free degrees of freedom, so re-assembly after a damage update is one sparse
mat-vec (``K.data = P (1 - D)``); the load vectors of all load positions and the element-average
strain operators are also built once. Each damage state needs one sparse LU factorisation
(SuperLU, COLAMD) and one multi-right-hand-side solve.
"""

from __future__ import annotations

import enum
import math
from dataclasses import dataclass, field

import numpy as np
import scipy.sparse as sp
from numpy.typing import ArrayLike, NDArray
from scipy.sparse.linalg import splu

from ..errors import ConfigError, SolverError, check_positive, check_range
from ..materials import Material

__all__ = [
    "build_mesh",
    "contact_section",
    "ContactSection",
    "core_substructure",
    "CoreSubstructure",
    "DEFAULT_MEASURE",
    "MESH_PRESETS",
    "MAX_ELEMENTS_PER_B",
    "MIN_ELEMENTS_PER_B",
    "section_spec",
    "SectionSpec",
    "SectionStresses",
    "ShearMeasure",
]


class ShearMeasure(enum.Enum):
    """Which shear-stress range ``Delta_tau`` over one load pass drives damage (seed LIFE
    eq. (4)).

    ``MAX_SHEAR`` (default)
        Range of the in-plane maximum (Tresca) shear ``sqrt(((sigma_x - sigma_z)/2)^2 + tau_xz^2)``
        over the pass: ``0 -> tau_max -> 0`` as the ball passes (the pass starts and ends
        unloaded, see :meth:`SectionStresses.shear_range`), so the range is ``tau_max`` itself,
        ``0.300 p_max`` at ``z = 0.78 b`` for the line-contact field (``0.314 p_max`` at
        ``0.75 b`` with the finite section's ``sigma_x``, docs/validation.md). This is the
        seed's own damage driver: its table 3 gives the "maximum shear stress" (最大切应力) of the
        contact as 459 MPa, and eq. (4) takes ``Delta_tau`` as twice the amplitude; the 3-D Hertz
        maximum shear of its contact (6206 inner race at 5 kN: a/b = 11.1, p_max = 2890 MPa) is
        ``0.313 p_max = 906 MPa``, of which 459 MPa is (to 1.3 %) the half — the amplitude of the
        ``0 -> tau_max -> 0`` cycle — and ``Delta_tau = 2 x 459 = 918 MPa``
        (``tests/test_fe_life.py::test_seed_table3_shear_is_half_the_hertz_tresca_shear``).
    ``ORTHOGONAL``
        Range (max − min over the pass) of the orthogonal shear ``tau_xz`` in the rolling plane
        (``x`` rolling, ``z`` depth). Fully reversed under a rolling Hertz contact:
        ``Delta_tau = 0.5 p_max`` at ``z = 0.5 b`` (1445 MPa for the seed's contact, which the
        seed's law turns into a life ~250 x shorter than its tests; it was our default before).
    ``CRITICAL_PLANE``
        Largest range, over all in-plane orientations ``theta``, of the shear stress on the plane
        at ``theta``: ``max_theta (max_k tau_theta,k - min_k tau_theta,k)``. With
        ``tau_theta = -(sigma_x - sigma_z)/2 sin 2theta + tau_xz cos 2theta`` this is the diameter
        of the point set ``{((sigma_x - sigma_z)/2, tau_xz)_k}`` over the pass; equals the
        orthogonal range under a rolling Hertz contact.
    """

    ORTHOGONAL = "orthogonal"
    CRITICAL_PLANE = "critical_plane"
    MAX_SHEAR = "max_shear"

    @classmethod
    def parse(cls, value: ShearMeasure | str, field: str = "measure") -> ShearMeasure:
        """The measure named ``value``; an unknown name raises a one-line :class:`ConfigError`
        listing the valid ones."""
        try:
            return cls(value)
        except ValueError:
            raise ConfigError(
                f"{field} = {value!r} is not a damage measure; valid: "
                + ", ".join(m.value for m in cls)
            ) from None


#: the damage driver used unless another is asked for (see :class:`ShearMeasure`)
DEFAULT_MEASURE = ShearMeasure.MAX_SHEAR


#: fine-zone elements per contact semi-width ``b`` of the named meshes
MESH_PRESETS: dict[str, float] = {"coarse": 5.0, "default": 10.0, "fine": 16.0, "finer": 24.0}
#: the fine-zone element size must not exceed ``b / MIN_ELEMENTS_PER_B``
MIN_ELEMENTS_PER_B = 4.0
#: ... nor fall below ``b / MAX_ELEMENTS_PER_B`` (8 times the finest preset; a finer fine zone
#: has more than ~10^6 elements: 1e-300 um asked numpy for 1e302 node coordinates)
MAX_ELEMENTS_PER_B = 200.0


@dataclass(frozen=True)
class SectionSpec:
    """Geometry and mesh of the plane-strain race section.

    Parameters
    ----------
    length : float
        Section length along the rolling direction [m] (seed LIFE fig. 14: 12 mm).
    height : float
        Section depth [m] (seed: 4 mm).
    element_size : float
        Element size ``h`` in the uniform fine zone [m].
    traverse : float
        Half-length ``s`` of the load traverse [m]: centres from ``-s`` to ``+s``.
    fine_margin : float
        Extent of the fine zone beyond the ends of the traverse [m] (>= b so that the pressure
        stays on the fine zone).
    fine_depth : float
        Depth of the fine zone [m].
    growth : float
        Geometric growth ratio of the element size outside the fine zone [-], in [1, 2].
    order : int
        1 (bilinear Q1) or 2 (biquadratic Q2) elements.
    """

    length: float
    height: float
    element_size: float
    traverse: float
    fine_margin: float
    fine_depth: float
    growth: float = 1.2
    order: int = 1

    def __post_init__(self) -> None:
        check_positive("section_length_m", self.length, "m")
        check_positive("section_height_m", self.height, "m")
        check_positive("element_size_m", self.element_size, "m")
        check_range("traverse_m", self.traverse, 0.0, unit="m")
        check_positive("fine_margin_m", self.fine_margin, "m")
        check_positive("fine_depth_m", self.fine_depth, "m")
        check_range("growth", self.growth, 1.0, 2.0)
        if self.order not in (1, 2):
            raise ConfigError(f"order = {self.order!r} is invalid; valid values 1 or 2")
        if self.traverse + self.fine_margin >= 0.5 * self.length:
            raise ConfigError(
                f"traverse + fine zone = {1e3 * (self.traverse + self.fine_margin):.4g} mm does "
                f"not fit in half the section length {0.5e3 * self.length:.4g} mm; "
                "valid range: smaller traverse or a longer section"
            )
        if self.fine_depth >= self.height:
            raise ConfigError(
                f"fine zone depth {1e3 * self.fine_depth:.4g} mm exceeds the section height "
                f"{1e3 * self.height:.4g} mm; valid range (0, {1e3 * self.height:.4g}) mm"
            )


def section_spec(
    b: float,
    mesh: str | float = "default",
    *,
    length: float = 12e-3,
    height: float = 4e-3,
    traverse_b: float = 2.0,
    margin_b: float = 1.5,
    depth_b: float = 2.5,
    growth: float = 1.2,
    order: int = 1,
    element_size: float | None = None,
) -> SectionSpec:
    """Section spec scaled on the contact semi-width ``b``.

    Parameters
    ----------
    b : float
        Hertz semi-width along the rolling direction [m].
    mesh : {"coarse", "default", "fine", "finer"} or float
        Named preset (elements per ``b``: 5, 10, 16, 24) or a number of elements per ``b``.
    length, height : float
        Section size [m] (seed LIFE: 12 mm x 4 mm).
    traverse_b : float
        Load traverse half-length in units of ``b`` [-].
    margin_b : float
        Fine-zone extent beyond the traverse in units of ``b`` [-] (>= 1).
    depth_b : float
        Fine-zone depth in units of ``b`` [-].
    growth : float
        Element growth ratio outside the fine zone [-].
    order : int
        Element order (1 or 2).
    element_size : float, optional
        Explicit fine element size [m] overriding ``mesh``; must be <= ``b/4``.
    """
    b = check_positive("b_m", b, "m")
    if element_size is None:
        if isinstance(mesh, str):
            if mesh not in MESH_PRESETS:
                raise ConfigError(
                    f"mesh = {mesh!r} is invalid; valid values {sorted(MESH_PRESETS)} or a number "
                    "of elements per b"
                )
            per_b = MESH_PRESETS[mesh]
        else:
            per_b = check_range("elements_per_b", mesh, MIN_ELEMENTS_PER_B, MAX_ELEMENTS_PER_B)
        h = b / per_b
    else:
        h = check_positive("element_size_m", element_size, "m")
        lo, hi = b / MAX_ELEMENTS_PER_B, b / MIN_ELEMENTS_PER_B
        if h > hi * (1 + 1e-12):
            raise ConfigError(
                f"element_size_m = {h:.4g} m ({1e6 * h:.3g} um) does not resolve the contact "
                f"semi-width b = {1e6 * b:.3g} um; need element size <= b/{MIN_ELEMENTS_PER_B:g} = "
                f"{1e6 * hi:.3g} um (valid range [{lo:.4g}, {hi:.4g}] m)"
            )
        if h < lo * (1 - 1e-12):
            raise ConfigError(
                f"element_size_m = {h:.4g} m ({1e6 * h:.3g} um) is finer than "
                f"b/{MAX_ELEMENTS_PER_B:g} = {1e6 * lo:.3g} um, b = {1e6 * b:.3g} um the contact "
                f"semi-width (the mesh would be too large); valid range [{lo:.4g}, {hi:.4g}] m"
            )
    n_half = max(1, int(round(traverse_b * b / h)))
    return SectionSpec(
        length=length,
        height=height,
        element_size=h,
        traverse=n_half * h,
        fine_margin=margin_b * b,
        fine_depth=depth_b * b,
        growth=growth,
        order=order,
    )


def _graded(h: float, fine: float, total: float, growth: float) -> NDArray[np.float64]:
    """Node coordinates from 0 to ``total``: uniform ``h`` up to ``fine`` (rounded up to a
    multiple of ``h``), then growing by ``growth`` per element, the last spacing adjusted."""
    n_fine = int(math.ceil(fine / h - 1e-9))
    xs = list(h * np.arange(n_fine + 1))
    step = h
    while xs[-1] < total - 1e-12:
        step *= growth
        nxt = xs[-1] + step
        if nxt >= total or total - nxt < 0.5 * step * growth:
            xs.append(total)
            break
        xs.append(nxt)
    return np.asarray(xs)


def build_mesh(spec: SectionSpec):
    """Tensor-product quadrilateral mesh of ``[-L/2, L/2] x [-H, 0]`` (surface at ``y = 0``),
    uniform in ``|x| <= s + margin``, ``-y <= depth``; returns a ``skfem.MeshQuad``."""
    from skfem import MeshQuad

    xh = _graded(
        spec.element_size, spec.traverse + spec.fine_margin, 0.5 * spec.length, spec.growth
    )
    x = np.concatenate([-xh[:0:-1], xh])
    yh = _graded(spec.element_size, spec.fine_depth, spec.height, spec.growth)
    y = -yh[::-1]
    return MeshQuad.init_tensor(x, y)


@dataclass
class SectionStresses:
    """Element-average stresses for every load position [Pa], tension positive, in the frame
    ``x`` (rolling) / ``z`` (depth, into the race); arrays of shape ``(n_elements, n_positions)``.
    """

    sigma_x: NDArray[np.float64]
    sigma_z: NDArray[np.float64]
    tau_xz: NDArray[np.float64]
    sigma_y: NDArray[np.float64]

    def shear_range(self, measure: ShearMeasure | str = DEFAULT_MEASURE) -> NDArray[np.float64]:
        """``Delta_tau`` per element over one ball pass [Pa] (see :class:`ShearMeasure`).

        A pass starts and ends with the ball far away, where the (elastic) section is unloaded,
        so the zero-stress state belongs to every pass: the range is taken over the load
        positions and that state. Without it the finite traverse (``+/- traverse_b b``) would
        cut the pass short: an element at the centre would never see the Tresca shear return
        to zero (it is still ~0.07 p_max with the load 2 b away) and the damage would start at
        the ends of the traverse, an artefact of its length. The orthogonal shear reverses
        within +/- b, so the state changes its range only outside the reversal zone.
        """
        measure = ShearMeasure.parse(measure)
        if measure is ShearMeasure.ORTHOGONAL:
            t = self.tau_xz
            return np.maximum(t.max(axis=1), 0.0) - np.minimum(t.min(axis=1), 0.0)
        a = 0.5 * (self.sigma_x - self.sigma_z)
        if measure is ShearMeasure.MAX_SHEAR:
            return np.hypot(a, self.tau_xz).max(axis=1)  # from 0 (unloaded) to the peak
        # CRITICAL_PLANE: diameter of the point set (a_k, tau_k) over the positions and (0, 0)
        out = np.hypot(a, self.tau_xz).max(axis=1)
        for k in range(a.shape[1]):
            d = np.hypot(a - a[:, k : k + 1], self.tau_xz - self.tau_xz[:, k : k + 1]).max(axis=1)
            np.maximum(out, d, out=out)
        return out


@dataclass
class ContactSection:
    """Assembled plane-strain FE model of the race section under a moving Hertz pressure.

    Build with :func:`contact_section`. Everything that does not depend on the damage is built
    once: mesh, basis, the COO→CSR assembly map ``P`` of the free-DOF stiffness, the load matrix
    ``F`` (one column per load position) and the element-average strain operators.

    Attributes
    ----------
    spec : SectionSpec
        Geometry and mesh parameters.
    material : Material
        Undamaged material (E [Pa], nu [-]).
    p_max : float
        Peak Hertz pressure [Pa].
    b : float
        Contact semi-width along rolling [m].
    positions : ndarray
        Load-centre positions ``x_c`` [m].
    mesh : skfem.MeshQuad
        The mesh (``x`` along rolling, ``y = -z`` up, surface at ``y = 0``).
    centroids : ndarray, shape (2, n_elements)
        Element centroids ``(x, z)`` with ``z`` the depth [m].
    areas : ndarray
        Element areas [m^2].
    surface : ndarray of bool
        Elements with an edge on the loaded surface.
    """

    spec: SectionSpec
    material: Material
    p_max: float
    b: float
    positions: NDArray[np.float64]
    mesh: object = field(repr=False)
    centroids: NDArray[np.float64] = field(repr=False)
    areas: NDArray[np.float64] = field(repr=False)
    surface: NDArray[np.bool_] = field(repr=False)
    _P: sp.csr_matrix = field(repr=False)
    _indptr: NDArray[np.int32] = field(repr=False)
    _indices: NDArray[np.int32] = field(repr=False)
    _F: NDArray[np.float64] = field(repr=False)
    _Bxx: sp.csr_matrix = field(repr=False)
    _Byy: sp.csr_matrix = field(repr=False)
    _Gxy: sp.csr_matrix = field(repr=False)
    n_dofs: int = 0
    n_free: int = 0
    _coo: tuple = field(default=(), repr=False)
    _g2f: NDArray[np.int64] = field(default=None, repr=False)
    _edofs: NDArray[np.int64] = field(default=None, repr=False)
    _work_y: NDArray[np.float64] = field(default=None, repr=False)

    @property
    def n_elements(self) -> int:
        """Number of elements [-]."""
        return int(self.areas.size)

    @property
    def n_positions(self) -> int:
        """Number of load positions per pass [-]."""
        return int(self.positions.size)

    def stiffness(self, factor: ArrayLike | None = None) -> sp.csc_matrix:
        """Free-DOF stiffness ``sum_e factor_e K_e`` [N/m per m thickness] (CSC; symmetric).

        Parameters
        ----------
        factor : array_like, optional
            Per-element stiffness factor ``1 - D_e`` [-]; default 1.
        """
        f = np.ones(self.n_elements) if factor is None else np.asarray(factor, dtype=float)
        data = self._P @ f
        # the matrix is symmetric: its CSR arrays are also its CSC arrays
        return sp.csc_matrix((data, self._indices, self._indptr), shape=(self.n_free,) * 2)

    def solve(self, factor: ArrayLike | None = None) -> SectionStresses:
        """Element-average stresses for every load position with stiffness factors ``factor``.

        Parameters
        ----------
        factor : array_like, optional
            Per-element stiffness factor ``1 - D_e`` [-] (> 0); default undamaged.
        """
        f = np.ones(self.n_elements) if factor is None else np.asarray(factor, dtype=float)
        K = self.stiffness(f)
        try:
            lu = splu(K, permc_spec="COLAMD")
        except RuntimeError as exc:  # singular factor
            raise SolverError(f"plane-strain FE: stiffness matrix is singular ({exc})") from exc
        U = lu.solve(self._F)
        if not np.all(np.isfinite(U)):
            raise SolverError("plane-strain FE: non-finite displacements (stiffness too degraded)")
        return self.stresses_from(U, f)

    def stresses_from(self, U: NDArray[np.float64], factor: NDArray[np.float64]) -> SectionStresses:
        """Element-average stresses [Pa] from free-DOF displacements ``U`` (n_free, n_pos)."""
        E, nu = self.material.youngs_modulus, self.material.poisson_ratio
        lam = E * nu / ((1 + nu) * (1 - 2 * nu))
        mu = E / (2 * (1 + nu))
        exx = self._Bxx @ U
        eyy = self._Byy @ U
        gxy = self._Gxy @ U
        f = factor[:, None]
        sxx = f * ((lam + 2 * mu) * exx + lam * eyy)
        syy = f * (lam * exx + (lam + 2 * mu) * eyy)
        # y points up (y = -z): tau_xz = -tau_xy
        return SectionStresses(
            sigma_x=sxx, sigma_z=syy, tau_xz=-f * mu * gxy, sigma_y=nu * (sxx + syy)
        )

    def load_resultant(self) -> NDArray[np.float64]:
        """Total vertical force per unit thickness of each load position [N/m] (should equal
        ``pi b p_max / 2``)."""
        return -self._work_y

    def plot_mesh(self, zoom: float | None = None):
        """The mesh (optionally zoomed to ``|x|, z <= zoom`` [m]); returns the Figure."""
        from matplotlib.collections import PolyCollection

        from ..plotting import FULL_WIDTH, new_figure

        m = self.mesh
        verts = np.moveaxis(m.p[:, m.t], 0, -1).transpose(1, 0, 2)
        verts = verts.copy()
        verts[..., 1] *= -1.0
        fig, ax = new_figure(width=FULL_WIDTH, height=4.0)
        ax.add_collection(
            PolyCollection(verts * 1e3, facecolors="none", edgecolors="k", linewidths=0.2)
        )
        lim = (zoom if zoom else 0.5 * self.spec.length) * 1e3
        ax.set_xlim(-lim, lim)
        ax.set_ylim((zoom if zoom else self.spec.height) * 1e3, 0)
        ax.set_aspect("equal")
        ax.set_xlabel("x [mm]")
        ax.set_ylabel("depth z [mm]")
        ax.set_title(f"{self.n_elements} elements, h = {1e6 * self.spec.element_size:.1f} µm")
        return fig


@dataclass
class CoreSubstructure:
    """The fine zone of a :class:`ContactSection` with the rest of the section condensed onto
    its boundary (static condensation; the outer region is assumed to stay undamaged).

    With ``E`` the degrees of freedom of the outer region only and ``G`` those shared with the
    core, the outer stiffness (constant) contributes the Schur complement
    ``S = K_GG - K_GE K_EE^-1 K_EG`` (dense, computed once with one factorisation of ``K_EE``).
    A damage state then needs only the core system ``K_core(D) + S`` (sparse plus one dense
    boundary block): same displacements in the core as the full model, to round-off, as long as
    the outer elements keep ``D = 0`` (the loads act on the core surface only).

    Attributes
    ----------
    elements : ndarray of int
        Indices of the core elements in the section.
    n_dofs : int
        Core degrees of freedom [-].
    n_interface : int
        Boundary degrees of freedom carrying the condensed outer region [-].

    Mirror symmetry: the section, its mesh and the load positions are symmetric about the
    contact centre ``x = 0``, so for a damage field that is symmetric too (the undamaged one,
    and every one the damage law grows from it) the stresses under the load at ``-x_c`` are the
    mirror image of those under ``+x_c`` (``tau_xz`` changes sign). :attr:`half_loads` are the
    load columns with ``x_c <= 0``; :meth:`stresses` accepts displacements for those columns
    only and mirrors the rest: half the solve work.
    """

    section: ContactSection = field(repr=False)
    elements: NDArray[np.int64] = field(repr=False)
    n_dofs: int
    n_interface: int
    # (duplicates) the operator fields of ContactSection, restricted to the core: the same
    # assembly (_P, _indptr, _indices) and stress operators (_Bxx, _Byy, _Gxy) on fewer elements
    _P: sp.csr_matrix = field(repr=False)
    _s_data: NDArray[np.float64] = field(repr=False)
    _indptr: NDArray[np.int32] = field(repr=False)
    _indices: NDArray[np.int32] = field(repr=False)
    _F: NDArray[np.float64] = field(repr=False)
    _Bxx: sp.csr_matrix = field(repr=False)
    _Byy: sp.csr_matrix = field(repr=False)
    _Gxy: sp.csr_matrix = field(repr=False)
    #: mirror image (x -> -x) of each core element, or None if the model is not mirror-symmetric
    _mirror: NDArray[np.int64] | None = field(default=None, repr=False)
    #: the strain operators on one CSR pattern (indptr, indices, xx, yy, xy values), built once
    _ops: tuple | None = field(default=None, repr=False)

    @property
    def n_elements(self) -> int:
        """Number of core elements [-]."""
        return int(self.elements.size)

    def stiffness(self, factor: ArrayLike | None = None) -> sp.csc_matrix:
        """Condensed core stiffness for core-element factors ``1 - D`` [-] (CSC, symmetric)."""
        f = np.ones(self.n_elements) if factor is None else np.asarray(factor, dtype=float)
        data = self._P @ f + self._s_data
        return sp.csc_matrix((data, self._indices, self._indptr), shape=(self.n_dofs,) * 2)

    def solve(self, factor: ArrayLike | None = None) -> SectionStresses:
        """Stresses [Pa] of the core elements for every load position (arrays of shape
        ``(n_core_elements, n_positions)``).

        Parameters
        ----------
        factor : array_like, optional
            Stiffness factor ``1 - D`` of each core element [-] (> 0); default 1.
        """
        f = np.ones(self.n_elements) if factor is None else np.asarray(factor, dtype=float)
        K = self.stiffness(f)
        try:
            lu = splu(K, permc_spec="MMD_AT_PLUS_A")
        except RuntimeError as exc:
            raise SolverError(f"plane-strain FE: core stiffness is singular ({exc})") from exc
        U = lu.solve(self._F)
        if not np.all(np.isfinite(U)):
            raise SolverError("plane-strain FE: non-finite displacements (stiffness too degraded)")
        return self.stresses(U, f)

    @property
    def symmetric(self) -> bool:
        """Whether the model is mirror-symmetric about ``x = 0`` (see the class docstring)."""
        return self._mirror is not None

    @property
    def half_loads(self) -> NDArray[np.float64]:
        """Load columns of the positions ``x_c <= 0`` [N] (all columns if not symmetric)."""
        if self._mirror is None:
            return self._F
        return self._F[:, : (self._F.shape[1] + 1) // 2]

    def symmetrize(self, values: NDArray[np.float64]) -> NDArray[np.float64]:
        """Mean of an element field and its mirror image (exactly mirror-symmetric) [-]."""
        v = np.asarray(values, dtype=float)
        return v if self._mirror is None else 0.5 * (v + v[self._mirror])

    def shear_range_from(
        self, U: NDArray[np.float64], factor: NDArray[np.float64], measure: ShearMeasure | str
    ) -> NDArray[np.float64]:
        """``Delta_tau`` per core element [Pa] from displacements ``U`` [m] (all positions, or
        the half of a symmetric model) and element factors [-]; the same numbers as
        ``stresses(U, factor).shear_range(measure)`` (compiled for the ``max_shear`` and
        ``orthogonal`` measures, which the damage loop evaluates every block)."""
        measure = ShearMeasure.parse(measure)
        f = np.asarray(factor, dtype=float)
        n_pos = self._F.shape[1]
        if measure is ShearMeasure.CRITICAL_PLANE or U.shape[1] not in (n_pos, (n_pos + 1) // 2):
            return self.stresses(U, f).shear_range(measure)
        from .block_solver import _shear_range

        if self._ops is None:
            ops = [M.tocsr() for M in (self._Bxx, self._Byy, self._Gxy)]
            pat = (abs(ops[0]) + abs(ops[1]) + abs(ops[2])).tocsr()  # the union pattern
            pat.sort_indices()
            rows = np.repeat(np.arange(pat.shape[0]), np.diff(pat.indptr))
            vals = [np.ascontiguousarray(np.asarray(M[rows, pat.indices]).ravel()) for M in ops]
            self._ops = (pat.indptr, pat.indices, *vals)
        E, nu = self.section.material.youngs_modulus, self.section.material.poisson_ratio
        mu = E / (2 * (1 + nu))
        mirror = self._mirror if U.shape[1] != n_pos else np.zeros(0, dtype=np.int64)
        return _shear_range(
            *self._ops,
            np.ascontiguousarray(U),
            f,
            mu,
            mirror,
            measure is ShearMeasure.ORTHOGONAL,
        )

    def block_solver(self, **options):
        """A :class:`~bearingsim.life.block_solver.BlockSolver` for this core's stiffness and
        loads (preconditioned conjugate gradients reusing the work between damage blocks)."""
        from .block_solver import BlockSolver

        return BlockSolver(
            self._P, self._s_data, self._indptr, self._indices, self.half_loads, **options
        )

    def stresses(self, U: NDArray[np.float64], factor: NDArray[np.float64]) -> SectionStresses:
        """Core-element stresses [Pa] from core displacements ``U`` (n_dofs, n_positions) [m]
        and element factors ``1 - D`` [-]."""
        f = np.asarray(factor, dtype=float)
        sec = self.section
        E, nu = sec.material.youngs_modulus, sec.material.poisson_ratio
        lam = E * nu / ((1 + nu) * (1 - 2 * nu))
        mu = E / (2 * (1 + nu))
        exx, eyy, gxy = self._Bxx @ U, self._Byy @ U, self._Gxy @ U
        ff = f[:, None]
        sxx = ff * ((lam + 2 * mu) * exx + lam * eyy)
        syy = ff * (lam * exx + (lam + 2 * mu) * eyy)
        txz = -ff * mu * gxy
        n_pos = self._F.shape[1]
        if U.shape[1] != n_pos:
            if self._mirror is None or U.shape[1] != (n_pos + 1) // 2:
                raise ValueError(f"U has {U.shape[1]} columns; expected {n_pos} or its half")
            # position n_pos - 1 - k is the mirror of position k: mirror element, tau_xz sign
            m, rest = self._mirror, slice(n_pos // 2 - 1, None, -1)
            sxx = np.hstack([sxx, sxx[m, rest]])
            syy = np.hstack([syy, syy[m, rest]])
            txz = np.hstack([txz, -txz[m, rest]])
        return SectionStresses(sigma_x=sxx, sigma_z=syy, tau_xz=txz, sigma_y=nu * (sxx + syy))


def _csr_pattern(r: NDArray[np.int64], c: NDArray[np.int64], n: int):
    """Sorted CSR pattern of the (row, col) pairs; returns (inverse map, indptr, indices)."""
    key = r * n + c
    uniq, inv = np.unique(key, return_inverse=True)
    ur = uniq // n
    indices = (uniq % n).astype(np.int32)
    indptr = np.searchsorted(ur, np.arange(n + 1)).astype(np.int32)
    return inv, indptr, indices, uniq


def core_substructure(section: ContactSection) -> CoreSubstructure:
    """Condense everything outside the fine zone of ``section`` onto the fine zone's boundary
    (see :class:`CoreSubstructure`). The fine zone is ``|x| <= s + margin``, ``z <= margin``."""
    spec = section.spec
    cx, cz = section.centroids
    tol = 1e-6 * spec.element_size
    in_core = (np.abs(cx) <= spec.traverse + spec.fine_margin + tol) & (cz <= spec.fine_depth + tol)
    core_el = np.flatnonzero(in_core)
    g2f, edofs = section._g2f, section._edofs
    fe_core = g2f[edofs[:, in_core]].ravel()
    fe_ext = g2f[edofs[:, ~in_core]].ravel()
    core_dofs = np.unique(fe_core[fe_core >= 0])
    ext_dofs = np.unique(fe_ext[fe_ext >= 0])
    gam = np.intersect1d(core_dofs, ext_dofs)
    E_only = np.setdiff1d(ext_dofs, core_dofs)
    rows, cols, data, eidx = section._coo
    r, c = g2f[rows], g2f[cols]
    ok = (r >= 0) & (c >= 0)
    r, c, d, e = r[ok], c[ok], data[ok], eidx[ok]
    ext = ~in_core[e]
    nf = section.n_free
    K_ext = sp.csr_matrix((d[ext], (r[ext], c[ext])), shape=(nf, nf))
    K_EE = K_ext[E_only][:, E_only].tocsc()
    K_EG = K_ext[E_only][:, gam].toarray()
    K_GG = K_ext[gam][:, gam].toarray()
    lu = splu(K_EE, permc_spec="MMD_AT_PLUS_A")
    S = K_GG - K_EG.T @ lu.solve(np.asfortranarray(K_EG))
    S = 0.5 * (S + S.T)
    # loads must act on the core only
    F = section._F
    if E_only.size and np.abs(F[E_only]).max() > 1e-12 * np.abs(F).max():
        raise ConfigError(
            "core_substructure: the load reaches outside the fine zone; increase fine_margin"
        )
    # core numbering
    loc = np.full(nf, -1, dtype=np.int64)
    loc[core_dofs] = np.arange(core_dofs.size)
    nc = core_dofs.size
    cm = ~ext
    rc, cc, dc = loc[r[cm]], loc[c[cm]], d[cm]
    el_loc = np.full(section.n_elements, -1, dtype=np.int64)
    el_loc[core_el] = np.arange(core_el.size)
    ec = el_loc[e[cm]]
    gl = loc[gam]
    gr = np.repeat(gl, gl.size)
    gc = np.tile(gl, gl.size)
    inv, indptr, indices, uniq = _csr_pattern(
        np.concatenate([rc, gr]), np.concatenate([cc, gc]), nc
    )
    n_el_entries = rc.size
    P = sp.csr_matrix((dc, (inv[:n_el_entries], ec)), shape=(uniq.size, core_el.size))
    P.sum_duplicates()
    s_data = np.bincount(inv[n_el_entries:], weights=S.ravel(), minlength=uniq.size)
    Fc = np.asfortranarray(F[core_dofs])
    # mirror map: the element at (-x, z) of each core element, if the model is symmetric
    ccx, ccz = cx[core_el], cz[core_el]
    order = np.lexsort((ccz, ccx))
    morder = np.lexsort((ccz, -ccx))
    mirror = np.empty(core_el.size, dtype=np.int64)
    mirror[order] = morder
    pos = section.positions
    symmetric = (
        np.allclose(ccx[mirror], -ccx, rtol=0.0, atol=tol)
        and np.allclose(ccz[mirror], ccz, rtol=0.0, atol=tol)
        and np.allclose(pos, -pos[::-1], rtol=0.0, atol=tol)
    )
    ops = []
    for M in (section._Bxx, section._Byy, section._Gxy):
        Mc = M[core_el][:, core_dofs].tocsr()
        ops.append(Mc)
    return CoreSubstructure(
        section=section,
        elements=core_el,
        n_dofs=nc,
        n_interface=int(gam.size),
        _P=P,
        _s_data=s_data,
        _indptr=indptr,
        _indices=indices,
        _F=Fc,
        _Bxx=ops[0],
        _Byy=ops[1],
        _Gxy=ops[2],
        _mirror=mirror if symmetric else None,
    )


def contact_section(
    material: Material, p_max: float, b: float, spec: SectionSpec
) -> ContactSection:
    """Build the plane-strain section model (mesh, assembly map, loads, strain operators).

    Parameters
    ----------
    material : Material
        Race material (E [Pa], nu [-]).
    p_max : float
        Peak Hertz pressure [Pa] (seed LIFE eq. (9)).
    b : float
        Hertz semi-width along the rolling direction [m].
    spec : SectionSpec
        Geometry and mesh (see :func:`section_spec`).
    """
    from skfem import (
        Basis,
        ElementQuad1,
        ElementQuad2,
        ElementVector,
        FacetBasis,
        LinearForm,
    )
    from skfem.models.elasticity import lame_parameters, linear_elasticity

    p_max = check_positive("p_max_pa", p_max, "Pa")
    b = check_positive("b_m", b, "m")
    if spec.element_size > b / MIN_ELEMENTS_PER_B * (1 + 1e-12):
        raise ConfigError(
            f"element_size_m = {spec.element_size:.4g} m does not resolve b = {1e6 * b:.3g} um; "
            f"need element size <= b/{MIN_ELEMENTS_PER_B:g} = {1e6 * b / MIN_ELEMENTS_PER_B:.3g} um"
        )
    if spec.fine_margin < b:
        raise ConfigError(
            f"fine_margin_m = {spec.fine_margin:.4g} m is smaller than b = {b:.4g} m; "
            f"valid range [{b:.4g}, inf) m"
        )
    mesh = build_mesh(spec)
    elem = ElementVector(ElementQuad2() if spec.order == 2 else ElementQuad1())
    basis = Basis(mesh, elem, intorder=2 * spec.order + 1)
    E, nu = material.youngs_modulus, material.poisson_ratio
    coo = linear_elasticity(*lame_parameters(E, nu)).elemental(basis)
    nt = mesh.t.shape[1]
    rows, cols = coo.indices
    data = coo.data
    eidx = np.arange(data.size) % nt  # skfem stores local (j, i, element) in C order
    # Dirichlet: clamped bottom edge
    fixed = basis.get_dofs(lambda x: np.isclose(x[1], -spec.height)).all()
    n = basis.N
    g2f = np.full(n, -1, dtype=np.int64)
    free = np.setdiff1d(np.arange(n), fixed)
    g2f[free] = np.arange(free.size)
    keep = (g2f[rows] >= 0) & (g2f[cols] >= 0)
    r, c, d, e = g2f[rows[keep]], g2f[cols[keep]], data[keep], eidx[keep]
    nf = free.size
    key = r * nf + c
    uniq, inv = np.unique(key, return_inverse=True)
    ur = (uniq // nf).astype(np.int64)
    indices = (uniq % nf).astype(np.int32)
    indptr = np.searchsorted(ur, np.arange(nf + 1)).astype(np.int32)
    P = sp.csr_matrix((d, (inv, e)), shape=(uniq.size, nt))
    P.sum_duplicates()
    # load positions and the Hertz pressure of eq. (9) moving across the surface
    h = spec.element_size
    n_half = int(round(spec.traverse / h))
    positions = h * np.arange(-n_half, n_half + 1)
    top = mesh.facets_satisfying(lambda x: np.isclose(x[1], 0.0))
    fb = FacetBasis(mesh, elem, facets=top, intorder=12)

    @LinearForm
    def traction(v, w):
        xi = (w.x[0] - w.xc) / b
        p = p_max * np.sqrt(np.clip(1.0 - xi * xi, 0.0, None))
        return -p * v[1]  # seed LIFE eq. (9), pressing into the race (-y)

    F_full = np.empty((n, positions.size))
    for k, xc in enumerate(positions):
        F_full[:, k] = traction.assemble(fb, xc=xc)
    F = np.asfortranarray(F_full[free])
    # element-average strains: rows = elements, columns = free dofs
    Bxx, Byy, Gxy = _strain_operators(basis, nt, g2f, nf)
    cx = mesh.p[0, mesh.t].mean(axis=0)
    cz = -mesh.p[1, mesh.t].mean(axis=0)
    areas = np.asarray(basis.dx.sum(axis=1))
    ymax = mesh.p[1, mesh.t].max(axis=0)
    surface = np.isclose(ymax, 0.0)
    sec = ContactSection(
        spec=spec,
        material=material,
        p_max=p_max,
        b=b,
        positions=positions,
        mesh=mesh,
        centroids=np.vstack([cx, cz]),
        areas=areas,
        surface=surface,
        _P=P,
        _indptr=indptr,
        _indices=indices,
        _F=F,
        _Bxx=Bxx,
        _Byy=Byy,
        _Gxy=Gxy,
        n_dofs=n,
        n_free=nf,
        _coo=(rows, cols, data, eidx),
        _g2f=g2f,
        _edofs=np.asarray(basis.element_dofs),
    )
    # vertical resultant: work of the load on a unit rigid translation in +y
    unit_y = basis.project(lambda x: np.stack([0.0 * x[0], 1.0 + 0.0 * x[0]]))
    sec._work_y = unit_y @ F_full
    return sec


def _strain_operators(basis, nt: int, g2f: NDArray[np.int64], nf: int):
    """Sparse operators mapping free-DOF displacements to element-average ``eps_xx``,
    ``eps_yy`` and ``gamma_xy`` (quadrature-weighted means over each element)."""
    dx = basis.dx  # (nt, nqp)
    area = dx.sum(axis=1)
    w = dx / area[:, None]
    rows_l, cols_l, vals = ([], [], []), ([], [], []), ([], [], [])
    el = np.arange(nt)
    for i in range(basis.Nbfun):
        g = basis.basis[i][0].grad  # (2 comp, 2 dir, nt, nqp)
        dofs = basis.element_dofs[i]
        comps = (
            (g[0, 0] * w).sum(axis=1),
            (g[1, 1] * w).sum(axis=1),
            ((g[0, 1] + g[1, 0]) * w).sum(axis=1),
        )
        f = g2f[dofs]
        ok = f >= 0
        for k in range(3):
            rows_l[k].append(el[ok])
            cols_l[k].append(f[ok])
            vals[k].append(comps[k][ok])
    ops = []
    for k in range(3):
        M = sp.csr_matrix(
            (np.concatenate(vals[k]), (np.concatenate(rows_l[k]), np.concatenate(cols_l[k]))),
            shape=(nt, nf),
        )
        M.sum_duplicates()
        M.eliminate_zeros()
        ops.append(M)
    return tuple(ops)
