"""Linear rotor finite elements: Euler–Bernoulli (Rayleigh) beam, rigid disks, gyroscopics.

The rotor is a beam along ``z`` with four degrees of freedom per node, in the order
``(x, y, theta_x, theta_y)``: lateral displacements [m] and small rotations about the x and y
axes [rad]. In the x–z plane the slope is ``dx/dz = theta_y``; in the y–z plane
``dy/dz = -theta_x`` (right-handed rotations). The shaft spins at ``Omega`` [rad/s] **about -z**,
i.e. in the sense in which the project's azimuth ``psi`` (measured from +y towards +x) increases,
so a ball-bearing cage, an unbalance and the shaft all turn the same way.

Equations of motion of the free rotor::

    M q'' + (C + Omega G) q' + K q = f(t)

with ``M`` the mass (translational + rotary inertia), ``K`` the bending stiffness, ``G`` the
skew-symmetric gyroscopic matrix per unit spin speed and ``C`` any damping the caller adds.

Sources
-------
* Beam element: cubic Hermite shape functions in each bending plane, Euler–Bernoulli kinematics
  with the rotary inertia and gyroscopic moment of the cross-section (a Rayleigh beam; Nelson &
  McVaugh 1976, *J. Eng. Ind.* 98, eqs. 10–13, without shear). The element matrices are built by
  5-point Gauss quadrature of the shape functions, which is exact for these polynomials.
* Rigid disk: ``diag(m, m, I_d, I_d)`` and the gyroscopic coupling ``I_p Omega`` (Friswell et al.
  2010, *Dynamics of Rotating Machines*, §5.3; Lalanne & Ferraris 1998, §1.2). With the spin about
  -z the disk's moment equations read ``I_d theta_x'' - I_p Omega theta_y' = M_x`` and
  ``I_d theta_y'' + I_p Omega theta_x' = M_y``.
* Massless degrees of freedom (a massless shaft carrying lumped masses, as in seed ROTOR eqs. 2–7)
  are removed by exact static condensation (Guyan 1965); the rest is reduced by the Craig–Bampton
  method (Craig & Bampton 1968): the boundary (bearing) translations are kept physical and the
  fixed-interface modes are truncated at a cut-off frequency.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np
import scipy.linalg as sla
from numpy.typing import ArrayLike, NDArray

from ...errors import ConfigError, SolverError, check_positive, check_range

__all__ = [
    "assemble_rotor",
    "beam_element",
    "complex_modes",
    "condense_massless",
    "craig_bampton",
    "Disk",
    "DOF_NAMES",
    "mesh_nodes",
    "Modes",
    "NDOF_NODE",
    "Reduction",
    "RotorFE",
]

#: degrees of freedom per node and their names
NDOF_NODE = 4
DOF_NAMES = ("x", "y", "theta_x", "theta_y")

# 5-point Gauss–Legendre rule on [0, 1]
_GX, _GW = np.polynomial.legendre.leggauss(5)
_GX = 0.5 * (_GX + 1.0)
_GW = 0.5 * _GW


def _hermite(xi: float, le: float) -> tuple[NDArray, NDArray, NDArray]:
    """Cubic Hermite functions (value, d/dz, d2/dz2) on an element of length ``le`` [m]."""
    h = np.array(
        [1 - 3 * xi**2 + 2 * xi**3, le * (xi - 2 * xi**2 + xi**3), 3 * xi**2 - 2 * xi**3,
         le * (-(xi**2) + xi**3)]
    )  # fmt: skip
    d1 = np.array([-6 * xi + 6 * xi**2, le * (1 - 4 * xi + 3 * xi**2), 6 * xi - 6 * xi**2,
                   le * (-2 * xi + 3 * xi**2)]) / le  # fmt: skip
    d2 = np.array([-6 + 12 * xi, le * (-4 + 6 * xi), 6 - 12 * xi, le * (-2 + 6 * xi)]) / le**2
    return h, d1, d2


def _plane_vectors(xi: float, le: float):
    """Row vectors mapping the 8 element DOFs to x, y, theta_x, theta_y and curvatures."""
    h, d1, d2 = _hermite(xi, le)
    # element DOFs: 0 x1, 1 y1, 2 thx1, 3 thy1, 4 x2, 5 y2, 6 thx2, 7 thy2
    ix = [0, 3, 4, 7]  # x-z plane: (x1, thy1, x2, thy2) with thy = dx/dz
    iy = [1, 2, 5, 6]  # y-z plane: (y1, thx1, y2, thx2) with thx = -dy/dz
    sgn_y = np.array([1.0, -1.0, 1.0, -1.0])
    nx = np.zeros(8)
    ny = np.zeros(8)
    nx[ix] = h
    ny[iy] = h * sgn_y
    dx1 = np.zeros(8)
    dy1 = np.zeros(8)
    dx1[ix] = d1
    dy1[iy] = d1 * sgn_y
    dx2 = np.zeros(8)
    dy2 = np.zeros(8)
    dx2[ix] = d2
    dy2[iy] = d2 * sgn_y
    n_thy = dx1  # theta_y = dx/dz
    n_thx = -dy1  # theta_x = -dy/dz
    return nx, ny, n_thx, n_thy, dx2, dy2


def beam_element(
    le: float, ei: float, rho_a: float, rho_i: float = 0.0
) -> tuple[NDArray, NDArray, NDArray]:
    """Euler–Bernoulli (Rayleigh) beam element matrices ``(K, M, G)`` (8 x 8).

    Parameters
    ----------
    le : float
        Element length [m].
    ei : float
        Bending stiffness E I [N m^2].
    rho_a : float
        Mass per unit length rho A [kg/m] (0 for a massless shaft).
    rho_i : float
        Diametral mass moment of inertia per unit length rho I [kg m]; the polar one is
        ``2 rho I`` for a circular section. 0 neglects rotary inertia and gyroscopics.

    Returns
    -------
    K : ndarray
        Bending stiffness [N/m, N, N m] (Nelson & McVaugh 1976 eq. 13).
    M : ndarray
        Consistent translational plus rotary mass (eqs. 10–11).
    G : ndarray
        Gyroscopic matrix per unit spin speed (eq. 12) for the spin about -z.
    """
    K = np.zeros((8, 8))
    M = np.zeros((8, 8))
    G = np.zeros((8, 8))
    for xi, w in zip(_GX, _GW, strict=True):
        nx, ny, nthx, nthy, cx, cy = _plane_vectors(xi, le)
        wl = w * le
        K += wl * ei * (np.outer(cx, cx) + np.outer(cy, cy))
        M += wl * rho_a * (np.outer(nx, nx) + np.outer(ny, ny))
        M += wl * rho_i * (np.outer(nthx, nthx) + np.outer(nthy, nthy))
        # polar inertia 2 rho I; theta_x: -Ip Omega theta_y', theta_y: +Ip Omega theta_x'
        G += wl * 2.0 * rho_i * (np.outer(nthy, nthx) - np.outer(nthx, nthy))
    return K, M, G


@dataclass(frozen=True)
class Disk:
    """A rigid disk on the shaft.

    Parameters
    ----------
    position : float
        Axial position z [m].
    mass : float
        Mass m [kg], > 0.
    transverse_inertia : float
        Diametral moment of inertia I_d [kg m^2], >= 0.
    polar_inertia : float
        Polar moment of inertia I_p [kg m^2], >= 0.
    """

    position: float
    mass: float
    transverse_inertia: float = 0.0
    polar_inertia: float = 0.0

    def __post_init__(self) -> None:
        object.__setattr__(self, "position", check_range("disk_position_m", self.position))
        object.__setattr__(self, "mass", check_positive("disk_mass_kg", self.mass, "kg"))
        for name in ("transverse_inertia", "polar_inertia"):
            v = check_range(f"disk_{name}_kg_m2", getattr(self, name), 0.0, unit="kg m^2")
            object.__setattr__(self, name, v)

    @classmethod
    def from_geometry(
        cls,
        position: float,
        mass: float,
        outer_diameter: float,
        inner_diameter: float = 0.0,
        thickness: float = 0.0,
    ) -> Disk:
        """Annular disk of given mass: ``I_p = m (r_o^2 + r_i^2)/2``,
        ``I_d = I_p/2 + m t^2/12`` (thick-disk formula; Friswell et al. 2010 eq. 5.13)."""
        do = check_positive("disk_diameter_m", outer_diameter, "m")
        di = check_range("disk_bore_m", inner_diameter, 0.0, do, hi_open=True, unit="m")
        t = check_range("disk_thickness_m", thickness, 0.0, unit="m")
        ip = 0.5 * mass * (0.25 * do * do + 0.25 * di * di)
        idd = 0.5 * ip + mass * t * t / 12.0
        return cls(position, mass, idd, ip)


@dataclass
class RotorFE:
    """Assembled linear rotor: node positions, DOF layout and the matrices ``M, K, G``.

    Attributes
    ----------
    z : ndarray
        Node positions [m] (sorted).
    M, K, G : ndarray
        Mass, stiffness and gyroscopic-per-unit-speed matrices over all ``4 n_nodes`` DOFs.
    disk_nodes : list of int
        Node index of every disk (in the order given).
    """

    z: NDArray[np.float64]
    M: NDArray[np.float64]
    K: NDArray[np.float64]
    G: NDArray[np.float64]
    disk_nodes: list[int] = field(default_factory=list)

    @property
    def n_nodes(self) -> int:
        return int(self.z.size)

    @property
    def n_dof(self) -> int:
        return NDOF_NODE * self.n_nodes

    def dof(self, node: int, name: str) -> int:
        """Global index of DOF ``name`` ('x', 'y', 'theta_x', 'theta_y') of ``node``."""
        return NDOF_NODE * node + DOF_NAMES.index(name)

    def node_at(self, z: float, tol: float = 1e-9) -> int:
        """Index of the node at axial position ``z`` [m]."""
        i = int(np.argmin(np.abs(self.z - z)))
        if abs(self.z[i] - z) > tol * max(1.0, float(self.z[-1] - self.z[0])):
            raise ConfigError(f"no node at z = {z:.6g} m")
        return i


def mesh_nodes(length: float, key_points: ArrayLike, n_elements: int) -> NDArray[np.float64]:
    """Node positions on ``[0, length]`` [m] containing every key point (bearings, disks) with at
    least ``n_elements`` elements, each interval between key points split evenly.

    Parameters
    ----------
    length : float
        Shaft length [m].
    key_points : array_like
        Positions that must be nodes [m], inside ``[0, length]``.
    n_elements : int
        Minimum number of beam elements, >= 1.
    """
    length = check_positive("shaft_length_m", length, "m")
    if isinstance(n_elements, bool) or int(n_elements) != n_elements or n_elements < 1:
        raise ConfigError(f"n_elements = {n_elements!r} is out of range; valid range [1, inf)")
    pts = np.unique(np.concatenate([[0.0, length], np.asarray(key_points, float).ravel()]))
    for p in pts:
        check_range("key_point_m", p, 0.0, length, unit="m")
    gaps = np.diff(pts)
    gaps = gaps[gaps > 1e-12 * length]
    pts = np.concatenate([[0.0], np.cumsum(gaps)])
    # distribute the elements over the intervals in proportion to their lengths
    n_int = np.maximum(1, np.ceil(gaps / length * n_elements - 1e-9).astype(int))
    nodes = [0.0]
    for a, g, k in zip(pts[:-1], gaps, n_int, strict=True):
        nodes.extend(a + g * np.arange(1, k + 1) / k)
    z = np.array(nodes)
    z[-1] = length
    return z


def assemble_rotor(
    z: ArrayLike,
    ei: float,
    rho_a: float = 0.0,
    rho_i: float = 0.0,
    disks: list[Disk] | tuple[Disk, ...] = (),
    point_masses: dict[int, float] | None = None,
) -> RotorFE:
    """Assemble ``M, K, G`` of a uniform shaft with rigid disks and lumped point masses.

    Parameters
    ----------
    z : array_like
        Node positions [m], strictly increasing; each disk must sit on a node.
    ei : float
        Bending stiffness E I [N m^2].
    rho_a, rho_i : float
        Shaft mass and diametral inertia per unit length [kg/m], [kg m] (see
        :func:`beam_element`).
    disks : sequence of Disk
        Rigid disks (seed ROTOR eq. 1: x, y, theta_x, theta_y per disk).
    point_masses : dict node -> mass [kg]
        Translational point masses (seed ROTOR eq. 2: half the shaft mass at each bearing).
    """
    z = np.asarray(z, dtype=float)
    if z.ndim != 1 or z.size < 2 or np.any(np.diff(z) <= 0):
        raise ConfigError("node positions must be a strictly increasing list of >= 2 values")
    n = NDOF_NODE * z.size
    M = np.zeros((n, n))
    K = np.zeros((n, n))
    G = np.zeros((n, n))
    for e in range(z.size - 1):
        ke, me, ge = beam_element(z[e + 1] - z[e], ei, rho_a, rho_i)
        s = slice(NDOF_NODE * e, NDOF_NODE * (e + 2))
        K[s, s] += ke
        M[s, s] += me
        G[s, s] += ge
    rotor = RotorFE(z, M, K, G, [])
    for d in disks:
        i = rotor.node_at(d.position)
        rotor.disk_nodes.append(i)
        b = NDOF_NODE * i
        M[b, b] += d.mass
        M[b + 1, b + 1] += d.mass
        M[b + 2, b + 2] += d.transverse_inertia
        M[b + 3, b + 3] += d.transverse_inertia
        G[b + 2, b + 3] -= d.polar_inertia
        G[b + 3, b + 2] += d.polar_inertia
    for node, m in (point_masses or {}).items():
        m = check_range("point_mass_kg", m, 0.0, unit="kg")
        b = NDOF_NODE * int(node)
        M[b, b] += m
        M[b + 1, b + 1] += m
    return rotor


def condense_massless(
    M: NDArray, K: NDArray, keep: ArrayLike, tol: float = 0.0
) -> tuple[NDArray, NDArray]:
    """Exact static condensation of DOFs without mass (Guyan 1965).

    Returns ``(master, T)``: the retained DOF indices (those with mass plus ``keep``) and the
    transformation ``q = T q_master`` with ``T = [I; -K_ss^-1 K_sm]`` (reordered to the full DOF
    numbering). DOFs without mass carry no inertia, so condensing them is exact for the
    undamped, non-gyroscopic part; the caller must not put damping or gyroscopic terms on them.

    Parameters
    ----------
    M, K : ndarray
        Full mass and stiffness matrices.
    keep : array_like of int
        DOFs to retain even if massless (e.g. where nonlinear forces act).
    tol : float
        Mass threshold below which a DOF counts as massless (relative to the largest diagonal).
    """
    n = M.shape[0]
    diag = np.abs(np.diag(M))
    massive = diag > tol * diag.max()
    massive[np.asarray(keep, dtype=int)] = True
    master = np.flatnonzero(massive)
    slave = np.flatnonzero(~massive)
    T = np.zeros((n, master.size))
    T[master, np.arange(master.size)] = 1.0
    if slave.size:
        kss = K[np.ix_(slave, slave)]
        ksm = K[np.ix_(slave, master)]
        try:
            T[slave] = -sla.solve(kss, ksm, assume_a="sym")
        except sla.LinAlgError:
            raise ConfigError(
                "the massless part of the rotor is a mechanism (singular stiffness); "
                "add elements or supports"
            ) from None
    return master, T


@dataclass(frozen=True)
class Reduction:
    """A reduction basis ``q_full = T q_red`` and facts about it.

    Attributes
    ----------
    T : ndarray
        Basis (n_full x n_red); the first ``n_boundary`` reduced coordinates are the boundary
        DOFs themselves.
    n_boundary : int
        Number of boundary coordinates.
    mode_hz : ndarray
        Natural frequencies [Hz] of the kept fixed-interface modes.
    cutoff_hz : float
        Cut-off used [Hz].
    n_dropped : int
        Number of fixed-interface modes discarded.
    """

    T: NDArray[np.float64]
    n_boundary: int
    mode_hz: NDArray[np.float64]
    cutoff_hz: float
    n_dropped: int


def craig_bampton(
    M: NDArray, K: NDArray, boundary: ArrayLike, cutoff_hz: float = math.inf, massless_tol=0.0
) -> Reduction:
    """Craig–Bampton reduction with boundary DOFs ``boundary`` (Craig & Bampton 1968).

    Massless DOFs are first condensed exactly (:func:`condense_massless`). The interior of the
    condensed model is then represented by its fixed-interface normal modes below
    ``cutoff_hz`` plus the static constraint modes of the boundary, so the static response to
    boundary forces is exact whatever the truncation.

    Parameters
    ----------
    M, K : ndarray
        Full mass and stiffness matrices (undamped, non-gyroscopic).
    boundary : array_like of int
        DOFs kept physical (where the bearing forces act).
    cutoff_hz : float
        Highest fixed-interface mode kept [Hz] (``inf`` keeps all).
    massless_tol : float
        See :func:`condense_massless`.
    """
    boundary = np.asarray(boundary, dtype=int)
    master, Tg = condense_massless(M, K, boundary, massless_tol)
    Mc = Tg.T @ M @ Tg
    Kc = Tg.T @ K @ Tg
    pos = {int(d): i for i, d in enumerate(master)}
    b = np.array([pos[int(d)] for d in boundary])
    interior = np.setdiff1d(np.arange(master.size), b)
    nb = b.size
    if interior.size == 0:
        Tcb = np.eye(master.size)[:, b]
        return Reduction(Tg @ Tcb, nb, np.zeros(0), float(cutoff_hz), 0)
    kii = Kc[np.ix_(interior, interior)]
    kib = Kc[np.ix_(interior, b)]
    mii = Mc[np.ix_(interior, interior)]
    try:
        psi = -sla.solve(kii, kib, assume_a="sym")
        lam, phi = sla.eigh(kii, mii)
    except (sla.LinAlgError, ValueError):
        raise ConfigError(
            "the rotor with its bearing nodes fixed is not stable (singular stiffness); "
            "check the shaft and the bearing positions"
        ) from None
    f = np.sqrt(np.maximum(lam, 0.0)) / (2 * math.pi)
    keep = f <= cutoff_hz
    n_keep = int(keep.sum())
    Tcb = np.zeros((master.size, nb + n_keep))
    Tcb[b, np.arange(nb)] = 1.0
    Tcb[np.ix_(interior, np.arange(nb))] = psi
    Tcb[np.ix_(interior, nb + np.arange(n_keep))] = phi[:, keep]
    return Reduction(Tg @ Tcb, nb, f[keep], float(cutoff_hz), int((~keep).sum()))


@dataclass(frozen=True)
class Modes:
    """Complex modes of ``M q'' + (C + Omega G) q' + K q = 0``.

    Attributes
    ----------
    frequency_hz : ndarray
        Damped natural frequencies [Hz], ascending (positive imaginary parts only).
    damping_ratio : ndarray
        Modal damping ratios [-].
    whirl : ndarray of str
        ``"forward"`` (whirl in the spin sense), ``"backward"`` or ``"planar"`` per mode
        (``"planar"`` for every mode at zero speed, where the x and y planes decouple).
    """

    frequency_hz: NDArray[np.float64]
    damping_ratio: NDArray[np.float64]
    whirl: NDArray[np.str_]


def complex_modes(
    M: NDArray,
    K: NDArray,
    G: NDArray | None = None,
    spin: float = 0.0,
    C: NDArray | None = None,
    x_dofs: ArrayLike | None = None,
    y_dofs: ArrayLike | None = None,
    min_hz: float = 1e-6,
) -> Modes:
    """Eigenvalues of the first-order form of ``M q'' + (C + spin G) q' + K q = 0``.

    Parameters
    ----------
    M, K, G, C : ndarray
        System matrices (``M`` must be non-singular: condense massless DOFs first).
    spin : float
        Shaft speed Omega [rad/s] (about -z, the project's positive sense).
    x_dofs, y_dofs : array_like of int, optional
        Matching x and y translational DOFs used to classify the whirl direction.
    min_hz : float
        Modes with smaller frequency (rigid-body) are dropped [Hz].
    """
    n = M.shape[0]
    D = (C if C is not None else np.zeros((n, n))) + spin * (G if G is not None else 0.0)
    if not np.any(D):
        # undamped and not spinning: K phi = w^2 M phi, a symmetric-definite problem (eigenvalues
        # +-i w of the first-order form); the symmetric solver is ~10x cheaper than eig of 2n
        w2 = sla.eigh(0.5 * (K + K.T), 0.5 * (M + M.T), eigvals_only=True)
        freq = np.sqrt(np.clip(w2, 0.0, None)) / (2 * math.pi)
        freq = np.sort(freq[freq > min_hz])
        return Modes(freq, np.zeros(freq.size), np.full(freq.size, "planar", dtype="<U8"))
    A = np.zeros((2 * n, 2 * n))
    A[:n, n:] = np.eye(n)
    with np.errstate(over="ignore", invalid="ignore"):
        Minv = np.linalg.inv(M)
        A[n:, :n] = -Minv @ K
        A[n:, n:] = -Minv @ D
    if not np.all(np.isfinite(A)):  # a mass negligible beside its stiffness: K/m overflows
        raise SolverError("complex_modes: M^-1 K is not finite in double precision")
    lam, vec = np.linalg.eig(A)
    sel = lam.imag > 2 * math.pi * min_hz
    lam = lam[sel]
    vec = vec[:n, sel]
    order = np.argsort(lam.imag)
    lam = lam[order]
    vec = vec[:, order]
    freq = lam.imag / (2 * math.pi)
    zeta = -lam.real / np.abs(lam)
    whirl = np.full(lam.size, "planar", dtype="<U8")
    if x_dofs is not None and y_dofs is not None and spin != 0.0:
        X = vec[np.asarray(x_dofs, dtype=int)]
        Y = vec[np.asarray(y_dofs, dtype=int)]
        # q = Re(V e^{i w t}); the orbit turns from +y towards +x (the spin sense, psi
        # increasing) when Im(conj(X) Y) > 0 for w > 0
        s = np.sum(np.imag(np.conj(X) * Y), axis=0)
        scale = np.sum(np.abs(X) ** 2 + np.abs(Y) ** 2, axis=0)
        r = s / np.maximum(scale, 1e-300)
        whirl = np.where(r > 1e-6, "forward", np.where(r < -1e-6, "backward", "planar"))
    return Modes(freq, zeta, whirl)
