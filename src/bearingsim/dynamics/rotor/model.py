"""Bearing–rotor–housing model with a multi-disk rotor mass distribution (seed ROTOR).

Liu, Gao, Zhang & Yan (2021), *Dynamic modeling and vibration response analysis of bearing–rotor
system* (seed ``001``; SPEC §2), model the CWRU test motor: a flexible shaft carried by a
drive-end (DE) 6205 and a fan-end (FE) 6203 ball bearing, the rotor (armature) mass spread over
``n`` rigid disks with gyroscopic coupling, half the shaft mass lumped at each bearing, each
ball a mass with a radial degree of freedom in Hertz contact with both races, and each bearing
housing a mass on linear springs and dampers to the base in X and Y. The seed's equations
(1)–(13) are garbled in the source; this module builds the same system from beam finite elements
and lumped disks (:mod:`.rotor_fe`) and couples the nonlinear bearing forces
(:mod:`.rotor_kernel`), as documented in ``docs/models.md`` (ROTOR).

Public entry points: :class:`RotorConfig` (all inputs, SI), :func:`cwru_rotor_config` (the
seed's CWRU case), :func:`build_rotor` (linear rotor, reduced), :func:`rotor_modes` (natural
frequencies of the rotor alone) and :func:`simulate_rotor` -> :class:`RotorResponse`.
"""

from __future__ import annotations

import dataclasses
import enum
import math
import time
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

import numpy as np
from numpy.typing import NDArray
from scipy.optimize import least_squares, root

from ..._version import __version__
from ...config import MIN_MODE_HZ, Solver  # lowest frequency resolved [Hz]: rigid-body below
from ...contact.hertz import ball_contact
from ...errors import ConfigError, SolverError, check_positive, check_range
from ...geometry import (
    DefectProfile,
    Race,
    characteristic_frequencies,
    check_speed_limit,
    defect_geometry,
    parse_enum,
)
from ..budget import F8, Budget, Estimate, check_budget
from ..defect_pit import pit_contacts
from ..integrate import run_adaptive, run_fixed
from . import _kernel as rk
from .config import (
    ENDS,
    G0,
    BearingSupport,
    RotorConfig,
    ShaftMassModel,
    config_summary,
)
from .fe import (
    DOF_NAMES,
    NDOF_NODE,
    Disk,
    Reduction,
    RotorFE,
    assemble_rotor,
    complex_modes,
    condense_massless,
    craig_bampton,
    mesh_nodes,
)
from .response import RotorResponse

__all__ = [
    "MIN_MODE_HZ",
    "PackedModel",
    "Supports",
    "RotorAssembly",
    "RotorModes",
    "build_fe",
    "build_rotor",
    "check_fe_size",
    "evaluate_rhs",
    "fe_estimate",
    "first_bending_hz",
    "MAX_FE_DOF",
    "max_disks",
    "pack_model",
    "rotor_eigenvalue_bound",
    "rotor_modes",
    "simulate_rotor",
    "stable_step",
    "static_state",
]

# ------------------------------------------------------------------------------ linear rotor

#: dense float64 arrays of the full FE size ``n_dof^2`` held at once while the linear rotor is
#: assembled and reduced: M, K, G, the interior blocks, the Craig-Bampton eigenvectors and the
#: basis, and the products that reduce them [-]
FE_ARRAYS_SIMULATE = 10
#: the same for :func:`rotor_modes`: M, K, G and the first-order state matrix ``(2n)^2`` with its
#: complex eigenvectors [-]
FE_ARRAYS_MODES = 24
#: largest first-order state (2 x FE DOFs) :func:`rotor_modes` solves with the dense
#: non-symmetric eigensolver (a spinning rotor) [-]: LAPACK's QR algorithm costs ~25 N^3 flops,
#: about half a minute at N = 4000 on one core of a 2-core VM (measured: 8.5 min at N = 7320);
#: a rotor at rest uses the symmetric solver and has no such limit
MAX_GYRO_STATE = 4000


def n_fe_elements(config: RotorConfig) -> int:
    """Number of beam elements of ``config``'s mesh (:func:`.fe.mesh_nodes`: at least
    ``n_elements``, one more per interval at most), computed without building it."""
    arm = config.armature
    n_disks = 0 if arm.distributed else arm.n_disks
    ne = config.n_elements or max(16, n_disks + 1)
    return int(ne) + n_disks + 1


def fe_estimate(config: RotorConfig, arrays: int = FE_ARRAYS_SIMULATE) -> Estimate:
    """Memory [B] of the dense finite-element model of ``config`` (``arrays`` arrays of
    ``n_dof^2`` float64, ``n_dof = 4 (n_elements + 1)``), before it is built."""
    ne = n_fe_elements(config)
    n_dof = float(NDOF_NODE) * (ne + 1)
    return Estimate(f"rotor mesh: {ne} beam elements, {n_dof:.6g} DOFs", arrays * n_dof**2 * F8)


#: largest finite-element rotor (DOFs, 4 per node) :func:`plan_rotor` builds [-]. The rotor is
#: assembled and reduced with dense linear algebra whose cost grows as ``n_dof^3`` (the interior
#: eigenproblem of the Craig-Bampton reduction): measured 2.7 s at 1000 DOFs (248 disks), 15 s at
#: 2000 and 47 s at 4008 (1000 disks, past 1.7 GB; issue: a check that ran > 2 min) on the 2-core
#: development VM under load (2026). The limit costs no physics: with 248 equally spaced disks
#: the kept fixed-interface modes below 6 kHz lie within 0.2 % of the distributed rotor's
#: (``Armature(distributed=True)``, the limit of many disks), and from ~100 disks on the reduced
#: model has as many coordinates as that limit
MAX_FE_DOF = 1000


def _mesh_dof(length: float, positions: tuple[float, ...], n_elements: int) -> int:
    """DOFs of the beam mesh :func:`.fe.mesh_nodes` makes on ``length`` [m] with disks at
    ``positions`` [m] and at least ``n_elements`` elements [-]."""
    return NDOF_NODE * int(mesh_nodes(length, positions, n_elements).size)


def max_disks(config: RotorConfig) -> int:
    """Most equally spaced disks [-] whose automatic mesh (``max(16, n + 1)`` elements) stays
    within :data:`MAX_FE_DOF`: from 15 disks on the mesh has one element per interval,
    ``4 (n + 2)`` DOFs."""
    L = config.shaft.length

    def fits(n: int) -> bool:
        pos = tuple(L * (i + 1) / (n + 1) for i in range(n))
        return _mesh_dof(L, pos, max(16, n + 1)) <= MAX_FE_DOF

    n = MAX_FE_DOF // NDOF_NODE - 2
    while n > 1 and not fits(n):
        n -= 1
    return n


def check_fe_size(config: RotorConfig, disks: str = "n_disks") -> int:
    """Refuse, with one line, a rotor whose beam mesh exceeds :data:`MAX_FE_DOF` (the dense
    reduction would run for minutes); the message names the field that sets the mesh: the
    disks (``disks``: the name of that field in the message) or ``n_elements``, its value and
    its valid range. Returns the mesh's DOF count [-]. Check the mesh's memory first
    (:func:`fe_estimate`): this builds the node list."""
    n_dof = NDOF_NODE * int(fe_nodes(config).size)
    if n_dof <= MAX_FE_DOF:
        return n_dof
    arm = config.armature
    pos = config.disk_positions
    L = config.shaft.length
    why = (
        f"beam mesh of {n_dof // NDOF_NODE - 1} elements, {n_dof} DOFs, above the "
        f"{MAX_FE_DOF} DOFs of the dense finite-element reduction (MAX_FE_DOF; its cost grows as "
        "DOFs^3)"
    )
    auto = _mesh_dof(L, pos, max(16, len(pos) + 1))
    if not arm.distributed and (config.n_elements is None or auto > MAX_FE_DOF):
        uneven = ", fewer at uneven disk_positions" if arm.positions is not None else ""
        raise ConfigError(
            f"{disks} = {arm.n_disks} makes a {why}; valid range [1, {max_disks(config)}] "
            f"equally spaced disks with the automatic mesh{uneven}, or the distributed rotor "
            "(distributed_rotor, the limit of many disks)"
        )
    lo = len(pos) + 1
    hi = MAX_FE_DOF // NDOF_NODE  # the mesh has at least n_elements + 1 nodes
    while lo < hi:  # the largest n_elements that fits (the mesh grows with it)
        mid = (lo + hi + 1) // 2
        lo, hi = (mid, hi) if _mesh_dof(L, pos, mid) <= MAX_FE_DOF else (lo, mid - 1)
    raise ConfigError(
        f"n_elements = {config.n_elements} makes a {why}; valid range [{len(pos) + 1}, {lo}] "
        "for this rotor"
    )


def first_bending_hz(config: RotorConfig) -> float:
    """Lower bound of the first bending frequency of the rotor on pinned bearings [Hz]: the
    shaft as a massless simply supported beam with the whole rotor and shaft mass at mid-span,
    ``sqrt(48 E I / (m L^3)) / (2 pi)`` (Roark's Formulas for Stress and Strain, 7th ed., table
    8.1 case 1a; Rayleigh's quotient: moving mass towards mid-span only lowers the frequency)."""
    sh = config.shaft
    m = sh.mass + config.armature.mass
    L = sh.length
    return math.sqrt(48.0 * sh.ei / (m * L * L * L)) / (2.0 * math.pi)


@dataclass
class RotorAssembly:
    """The linear rotor of a :class:`RotorConfig`, full and reduced.

    Attributes
    ----------
    fe : RotorFE
        Full finite-element model (``M, K, G`` over all nodes).
    reduction : Reduction
        Craig–Bampton basis; reduced coordinates start with x, y of the DE and FE bearing
        nodes.
    M, K, C, G : ndarray
        Reduced mass, stiffness, damping and gyroscopic-per-unit-speed matrices.
    f_static : ndarray
        Reduced constant load (gravity and ``bearing_loads``) [N].
    f_unb_cos, f_unb_sin : ndarray
        Reduced unbalance load coefficients of cos(Omega t) and sin(Omega t) [N].
    boundary_dofs : ndarray
        Full-model DOFs of the four boundary coordinates.
    """

    fe: RotorFE
    reduction: Reduction
    M: NDArray
    K: NDArray
    C: NDArray
    G: NDArray
    f_static: NDArray
    f_unb_cos: NDArray
    f_unb_sin: NDArray
    boundary_dofs: NDArray

    @property
    def n(self) -> int:
        return int(self.M.shape[0])


def fe_nodes(config: RotorConfig) -> NDArray[np.float64]:
    """Node positions [m] of ``config``'s beam mesh (:func:`.fe.mesh_nodes` with the bearings and
    disks as nodes; ``n_elements`` or 16, at least one element between neighbours)."""
    pos = config.disk_positions
    ne = config.n_elements or max(16, len(pos) + 1)
    return mesh_nodes(config.shaft.length, pos, ne)


def build_fe(config: RotorConfig) -> RotorFE:
    """Finite-element rotor (no supports) of ``config``: shaft, disks, lumped shaft halves."""
    sh, arm = config.shaft, config.armature
    pos = config.disk_positions
    z = fe_nodes(config)
    L = sh.length
    rho_a = rho_i = 0.0
    lumped: dict[int, float] = {}
    if sh.mass_model is ShaftMassModel.DISTRIBUTED:
        rho_a = sh.mass / L
        rho_i = rho_a * sh.diameter**2 / 16.0
    else:  # seed ROTOR eq. (2): half the shaft mass at each bearing
        lumped = {0: 0.5 * sh.mass, z.size - 1: 0.5 * sh.mass}
    disks: list[Disk] = []
    ro2 = (0.5 * arm.diameter) ** 2
    ri2 = (0.5 * sh.diameter) ** 2
    if arm.distributed:
        rho_a += arm.mass / L
        rho_i += arm.mass / L * (ro2 + ri2) / 4.0
    else:
        length = config.armature_length
        m = arm.mass / len(pos)
        for zp in pos:
            disks.append(Disk.from_geometry(zp, m, arm.diameter, sh.diameter, length / len(pos)))
    return assemble_rotor(z, sh.ei, rho_a, rho_i, disks, lumped)


def build_rotor(config: RotorConfig, cutoff_hz: float = math.inf) -> RotorAssembly:
    """Reduced linear rotor of ``config`` (Craig–Bampton, boundary = bearing-node x, y)."""
    fe = build_fe(config)
    last = fe.n_nodes - 1
    bnd = np.array([fe.dof(0, "x"), fe.dof(0, "y"), fe.dof(last, "x"), fe.dof(last, "y")])
    red = craig_bampton(fe.M, fe.K, bnd, cutoff_hz)
    T = red.T
    M = T.T @ fe.M @ T
    K = T.T @ fe.K @ T
    G = T.T @ fe.G @ T
    M = 0.5 * (M + M.T)
    K = 0.5 * (K + K.T)
    # stiffness-proportional damping with ratio zeta at the first fixed-interface mode
    C = np.zeros_like(K)
    if red.mode_hz.size and config.shaft_damping_ratio > 0:
        beta = 2 * config.shaft_damping_ratio / (2 * math.pi * red.mode_hz[0])
        C += beta * K
    if config.disk_damping > 0:
        cd = np.zeros(fe.n_dof)
        for node in fe.disk_nodes:
            cd[fe.dof(node, "x")] = cd[fe.dof(node, "y")] = config.disk_damping
        C += T.T @ (cd[:, None] * T)
    # constant loads: gravity on the consistent mass, bearing loads at the bearing nodes
    f = np.zeros(fe.n_dof)
    if config.gravity:
        ones_y = np.zeros(fe.n_dof)
        ones_y[1::NDOF_NODE] = 1.0
        f -= G0 * fe.M @ ones_y
    (fx0, fy0), (fx1, fy1) = config.bearing_loads
    f[bnd] += [fx0, fy0, fx1, fy1]
    # unbalance m e Omega^2 (sin(Omega t + phi), cos(Omega t + phi)) shared by the disks
    # nearest the armature centre (or the centre node when distributed)
    fc = np.zeros(fe.n_dof)
    fs = np.zeros(fe.n_dof)
    if config.unbalance > 0:
        zc = 0.5 * config.shaft.length
        nodes = fe.disk_nodes or [int(np.argmin(np.abs(fe.z - zc)))]
        dist = np.abs(fe.z[nodes] - zc)
        sel = [n for n, dd in zip(nodes, dist, strict=True) if dd <= dist.min() + 1e-12]
        me = config.unbalance * config.omega**2 / len(sel)
        ph = config.unbalance_phase
        for node in sel:
            fc[fe.dof(node, "x")] += me * math.sin(ph)
            fc[fe.dof(node, "y")] += me * math.cos(ph)
            fs[fe.dof(node, "x")] += me * math.cos(ph)
            fs[fe.dof(node, "y")] -= me * math.sin(ph)
    return RotorAssembly(fe, red, M, K, C, G, T.T @ f, T.T @ fc, T.T @ fs, bnd)


@dataclass(frozen=True)
class Supports(enum.Enum):
    """Boundary conditions of the rotor alone in :func:`rotor_modes`."""

    #: bearing nodes held in x and y (simply supported)
    PINNED = "pinned"
    #: free-free rotor
    FREE = "free"


@dataclass
class RotorModes:
    """Natural frequencies of the rotor alone.

    Attributes
    ----------
    frequency_hz : ndarray
        Natural frequencies [Hz], ascending.
    whirl : ndarray of str
        Whirl direction per mode (``forward``/``backward``/``planar``).
    supports : Supports
        Pinned bearing nodes or a free-free rotor.
    speed_rpm : float
        Speed used for the gyroscopic terms [r/min].
    n_dof : int
        Number of DOFs of the full FE model.
    """

    frequency_hz: NDArray[np.float64]
    whirl: NDArray[np.str_]
    supports: Supports
    speed_rpm: float
    n_dof: int


def rotor_modes(config: RotorConfig, supports: Supports | str = Supports.PINNED,
                speed_rpm: float = 0.0, n_modes: int = 8,
                budget: Budget | None = None) -> RotorModes:  # fmt: skip
    """Natural frequencies of the rotor alone (no bearings, no housings).

    Refused before any work (one-line :class:`~bearingsim.errors.ConfigError`): a rotor whose
    first bending mode (:func:`first_bending_hz`) is below :data:`MIN_MODE_HZ`, a mesh whose
    dense matrices (:func:`fe_estimate`) exceed ``budget``, and a spinning rotor whose state
    exceeds :data:`MAX_GYRO_STATE`. At rest (``speed_rpm = 0``) the modes come from the
    symmetric problem ``K phi = w^2 M phi``.

    Parameters
    ----------
    config : RotorConfig
        Rotor data (shaft, armature, mesh).
    supports : Supports or {"pinned", "free"}
        Bearing nodes held in x and y (simply supported) or a free-free rotor.
    speed_rpm : float
        Spin speed for the gyroscopic coupling [r/min] (>= 0).
    n_modes : int
        Number of frequencies returned.
    budget : Budget, optional
        Memory limit [B] (:class:`bearingsim.dynamics.budget.Budget`; default half the
        available memory).
    """
    supports = parse_enum(Supports, supports, "supports")
    spin = check_range("speed_rpm", speed_rpm, 0.0, unit="r/min") * math.pi / 30.0
    for sup in (config.de, config.fe):  # the shaft turns in both bearings
        check_speed_limit(sup.bearing, float(speed_rpm), "speed_rpm", "[0")
    f1 = first_bending_hz(config)
    if f1 < MIN_MODE_HZ:
        sh = config.shaft
        m = sh.mass + config.armature.mass
        l_max = (48.0 * sh.ei / (m * (2.0 * math.pi * MIN_MODE_HZ) ** 2)) ** (1.0 / 3.0)
        raise ConfigError(
            f"shaft_length_m = {sh.length:.6g} m puts the first bending mode of the rotor near "
            f"{f1:.3g} Hz, below the {MIN_MODE_HZ:g} Hz the modal analysis resolves; valid range "
            f"({sh.diameter:.6g}, {l_max:.6g}] m for this shaft and rotor mass"
        )
    check_budget(fe_estimate(config, FE_ARRAYS_MODES), budget)
    n_nodes = fe_nodes(config).size
    n_state = 2 * NDOF_NODE * n_nodes
    if spin > 0.0 and n_state > MAX_GYRO_STATE:
        raise ConfigError(
            f"rotor mesh of {n_nodes - 1} beam elements: a spinning rotor's modes need the dense "
            f"eigensolver on a state of "
            f"{n_state} (about {25 * n_state**3 / 1e10:.3g} s at 10 GFLOP/s); valid: at most "
            f"{MAX_GYRO_STATE} states (fewer disks or elements, or the distributed rotor), or "
            "speed_rpm = 0"
        )
    fe = build_fe(config)
    last = fe.n_nodes - 1
    fixed = []
    if supports is Supports.PINNED:
        fixed = [fe.dof(0, "x"), fe.dof(0, "y"), fe.dof(last, "x"), fe.dof(last, "y")]
    free = np.setdiff1d(np.arange(fe.n_dof), fixed)
    M = fe.M[np.ix_(free, free)]
    K = fe.K[np.ix_(free, free)]
    G = fe.G[np.ix_(free, free)]
    master, Tg = condense_massless(M, K, [])
    Mc, Kc, Gc = (Tg.T @ A @ Tg for A in (M, K, G))
    names = np.array([DOF_NAMES[d % NDOF_NODE] for d in free])[master]
    nodes = free[master] // NDOF_NODE
    xd = [i for i, (nm, nd) in enumerate(zip(names, nodes, strict=True)) if nm == "x"]
    yd = [
        int(np.flatnonzero((names == "y") & (nodes == nodes[i]))[0]) if np.any(
            (names == "y") & (nodes == nodes[i])) else i for i in xd
    ]  # fmt: skip
    try:
        modes = complex_modes(Mc, Kc, Gc, spin, x_dofs=xd, y_dofs=yd, min_hz=MIN_MODE_HZ)
    except (SolverError, np.linalg.LinAlgError):
        arm, sh = config.armature, config.shaft
        raise SolverError(
            f"rotor_mass_kg = {arm.mass:.6g} kg, shaft_mass_kg = {sh.mass:.6g} kg: a mass this "
            "small beside the shaft's stiffness overflows the modal problem in double precision "
            "(M^-1 K is not finite); valid: masses that are not negligible"
        ) from None
    k = int(n_modes)
    if modes.frequency_hz.size == 0:
        raise SolverError(
            f"no natural frequency above {MIN_MODE_HZ:g} Hz found for the rotor (shaft "
            f"{config.shaft.length:.6g} m x {config.shaft.diameter:.6g} m); check the shaft data"
        )
    return RotorModes(modes.frequency_hz[:k], modes.whirl[:k], supports, float(speed_rpm),
                      fe.n_dof)  # fmt: skip


# ------------------------------------------------------------------------- parameter packing


def _bearing_block(sup: BearingSupport, config: RotorConfig) -> NDArray[np.float64]:
    """Kernel block (:data:`rotor_kernel.BRG_LEN` values) of one bearing."""
    b = sup.bearing
    blk = np.zeros(rk.BRG_LEN)
    blk[rk.B_Z] = b.n_elements
    blk[rk.B_PSI0] = sup.first_ball_angle
    blk[rk.B_OMEGA_C] = 2 * math.pi * characteristic_frequencies(b, config.shaft_hz).ftf_hz
    blk[rk.B_MBALL] = sup.ball_mass
    blk[rk.B_KIN] = ball_contact(b, 1.0, Race.INNER).k_hertz
    blk[rk.B_KOUT] = ball_contact(b, 1.0, Race.OUTER).k_hertz
    blk[rk.B_KEFF] = (blk[rk.B_KIN] ** (-2 / 3) + blk[rk.B_KOUT] ** (-2 / 3)) ** -1.5
    blk[rk.B_C] = sup.contact_damping
    blk[rk.B_RP] = 0.5 * b.pitch_diameter
    blk[rk.B_CH] = 0.5 * b.diametral_clearance
    sig = sup.contact_roughness
    if sig > 0.0:  # 1/sigma and sigma^(1/2) cached for the hot loop (rough_ball)
        blk[rk.B_ROUGH] = sig
        blk[rk.B_RINV] = 1.0 / sig
        blk[rk.B_RSN1] = math.sqrt(sig)
    f = sup.fault
    if f is not None:
        g = defect_geometry(b, f)
        blk[rk.B_FAULT] = {Race.OUTER: 1, Race.INNER: 2, Race.BALL: 3}[f.race]
        blk[rk.B_FANG] = f.angle
        blk[rk.B_FHALF] = 0.5 * g.delta_beta
        blk[rk.B_DEPTH] = f.depth
        blk[rk.B_HALFW] = 0.5 * f.width
        blk[rk.B_RBALL] = 0.5 * b.element_diameter
        blk[rk.B_RRACE] = g.race_radius
        blk[rk.B_RSIGN] = -1.0 if f.race is Race.OUTER else 1.0
        blk[rk.B_PROFILE] = {
            DefectProfile.GEOMETRIC: 0.0,
            DefectProfile.RECTANGULAR: 1.0,
            DefectProfile.PIT: 2.0,
        }[f.profile]
        blk[rk.B_HMAX] = g.h_min
        blk[rk.B_FOMEGA] = config.omega if f.race is Race.INNER else 0.0
        if f.race is Race.BALL:  # the slot meets the outer race (B_RRACE) and the inner race
            k = characteristic_frequencies(b, config.shaft_hz)
            blk[rk.B_SPIN] = k.bsf_hz / k.ftf_hz
            blk[rk.B_RRACE] = b.outer_raceway_radius
            blk[rk.B_RSIGN] = -1.0
            blk[rk.B_RRACE_I] = b.inner_raceway_radius
            blk[rk.B_HMAX_I] = g.h_min_inner
        if f.profile is DefectProfile.PIT:  # the contact(s) the pit meets (..defect_pit)
            first, inner, grow = pit_contacts(b, f)
            blk[rk.B_PITA], blk[rk.B_PITB], blk[rk.B_PITW] = first
            if inner is not None:
                blk[rk.B_PITAI], blk[rk.B_PITBI], blk[rk.B_PITWI] = inner
            blk[rk.B_FHALF] += grow  # every position where the contact overlaps the pit
    return blk


@dataclass
class PackedModel:
    """A :class:`RotorConfig` packed for the compiled kernel.

    Attributes
    ----------
    p : ndarray
        Flat parameter vector (layout in :mod:`.rotor_kernel`).
    rotor : RotorAssembly
        The reduced linear rotor.
    n_r, n_balls, n_pos : int
        Reduced rotor coordinates, balls, position states (state size ``2 n_pos``; the balls
        have no coordinates when they are quasi-static, ``RotorConfig.ball_inertia`` False).
    """

    p: NDArray[np.float64]
    rotor: RotorAssembly
    n_r: int
    n_balls: int
    n_pos: int
    z_de: int
    z_fe: int
    #: per bearing (DE, FE) under an axial load, the Jones equilibrium
    #: (:class:`bearingsim.quasistatic.jones.AxialState`); None without one
    axial: tuple[Any, Any] | None = None

    def kinematic_bearings(self, config: RotorConfig) -> tuple[Any, Any]:
        """The DE and FE bearings at their operating contact angles (the cage and ball spin
        follow them)."""
        b = (config.de.bearing, config.fe.bearing)
        if self.axial is None:
            return b
        return tuple(
            dataclasses.replace(x, contact_angle=a.contact_angle)
            for x, a in zip(b, self.axial, strict=True)
        )


def pack_model(config: RotorConfig, cutoff_hz: float, ball_forces: bool = False) -> PackedModel:
    """Build the reduced rotor and the kernel's parameter vector for ``config``."""
    rot = build_rotor(config, cutoff_hz)
    nr = rot.n
    Minv = np.linalg.inv(rot.M)
    AK = Minv @ rot.K
    AC = Minv @ (rot.C + config.omega * rot.G)
    Tb = np.zeros((nr, 4))
    Tb[:4, :4] = np.eye(4)  # boundary coordinates are the bearing-node x, y themselves
    assert np.allclose(rot.reduction.T[rot.boundary_dofs, :4], np.eye(4))
    BB = Minv @ Tb
    # A_K and A_C transposed: the kernel's layout (its sums run column by column)
    blocks = [
        AK.T.ravel(), AC.T.ravel(), BB.ravel(), Minv @ rot.f_static, Minv @ rot.f_unb_cos,
        Minv @ rot.f_unb_sin,
    ]  # fmt: skip
    hdr = np.zeros(rk.HDR)
    off = rk.HDR
    offs = []
    for blk in blocks:
        offs.append(off)
        off += blk.size
    brg = [_bearing_block(config.de, config), _bearing_block(config.fe, config)]
    hs = np.zeros(rk.HOUS_LEN)
    for e, h in enumerate((config.housing_de, config.housing_fe)):
        hs[5 * e : 5 * e + 5] = [h.mass, h.stiffness_x, h.stiffness_y, h.damping_x, h.damping_y]
    z_de, z_fe = config.de.bearing.n_elements, config.fe.bearing.n_elements
    hdr[rk.H_NR] = nr
    hdr[rk.H_Z_DE] = z_de
    hdr[rk.H_Z_FE] = z_fe
    hdr[rk.H_OMEGA] = config.omega
    hdr[rk.H_GRAV] = G0 if config.gravity else 0.0
    for key, o in zip((rk.H_AK, rk.H_AC, rk.H_BB, rk.H_F0, rk.H_UC, rk.H_US), offs, strict=True):
        hdr[key] = o
    hdr[rk.H_BRG_DE] = off
    hdr[rk.H_BRG_FE] = off + rk.BRG_LEN
    hdr[rk.H_HOUS] = off + 2 * rk.BRG_LEN
    hdr[rk.H_BALL_OUT] = 1.0 if ball_forces else 0.0
    hdr[rk.H_QS] = 0.0 if config.ball_inertia else 1.0
    p = np.concatenate([hdr, *blocks, *brg, hs])
    if config.ball_diameter_spread > 0.0:  # each bearing's ball diameters after the blocks
        from ..ballset import ball_deviations

        tails = []
        off = p.size
        for e, (sup, key) in enumerate(((config.de, rk.H_BRG_DE), (config.fe, rk.H_BRG_FE))):
            dev = ball_deviations(
                sup.bearing.n_elements,
                config.ball_diameter_spread,
                (int(config.ball_seed), 2, e),
            )
            p[int(hdr[key]) + rk.B_BDEV] = off
            tails.append(dev)
            off += dev.size
        p = np.concatenate([p, *tails])
    nb = z_de + z_fe
    model = PackedModel(p, rot, nr, nb, nr + 4 + (nb if config.ball_inertia else 0), z_de, z_fe)
    if config.axial_load > 0.0:
        model = _with_axial_load(model, config)
    return model


def _with_axial_load(model: PackedModel, config: RotorConfig) -> PackedModel:
    """``model`` with each bearing's balls at the contact angles of an axial load: the radial
    load each bearing carries at rest (the static state without it) and ``config.axial_load``
    give the Jones equilibrium (tilts held) of that bearing with the balls' series Hertz
    constant; its axial offset ``z`` is held in the kernel, and the cage and ball spin turn at
    the load-weighted mean contact angle (as the ring models' DEM, docs/models.md "Axial
    load")."""
    from ...quasistatic.jones import axial_state

    y0 = static_state(model, config)
    _, aux = evaluate_rhs(model, 0.0, y0)
    p = model.p.copy()
    states = []
    for e, (sup, key) in enumerate(((config.de, rk.H_BRG_DE), (config.fe, rk.H_BRG_FE))):
        b = sup.bearing
        z = b.n_elements
        o = int(p[key])
        off = 4 + (0 if e == 0 else 2 * model.z_de)
        psi = p[o + rk.B_PSI0] + 2.0 * np.pi * np.arange(z) / z
        q = aux[off : off + z]  # the balls' loads at rest; the bearing carries sum Q e_j
        fx, fy = float(np.sum(q * np.sin(psi))), float(np.sum(q * np.cos(psi)))
        st = axial_state(  # the scenario's load check (_checked_config) covers the load
            b,
            fx,
            fy,
            config.axial_load,
            clearance=b.diametral_clearance,
            stiffness=float(p[o + rk.B_KEFF]),
            first_ball_angle=float(p[o + rk.B_PSI0]),
        )
        p[o + rk.B_AXZ] = st.z
        p[o + rk.B_A0] = st.a0
        kb = dataclasses.replace(b, contact_angle=st.contact_angle)
        k = characteristic_frequencies(kb, config.shaft_hz)
        p[o + rk.B_OMEGA_C] = 2 * math.pi * k.ftf_hz
        if sup.fault is not None and sup.fault.race is Race.BALL:
            p[o + rk.B_SPIN] = k.bsf_hz / k.ftf_hz
        states.append(st)
    return dataclasses.replace(model, p=p, axial=tuple(states))


def _with_slip(
    model: PackedModel,
    config: RotorConfig,
    slip: float,
    seed: int,
    duration: float,
    jitter: float = 0.0,
) -> PackedModel:
    """``model`` with each bearing's ball-pass instants (random slip) appended to ``p``."""
    from ..slip import ball_pass_instants

    p = model.p.copy()
    tables = []
    off = p.size
    kbs = model.kinematic_bearings(config)
    for e, (sup, key) in enumerate(((config.de, rk.H_BRG_DE), (config.fe, rk.H_BRG_FE))):
        b = sup.bearing
        ftf = characteristic_frequencies(kbs[e], config.shaft_hz).ftf_hz
        t_k, dt = ball_pass_instants(b.n_elements, ftf, slip, duration, (int(seed), 1, e), jitter)
        o = int(p[key])
        p[o + rk.B_SLIP] = off
        p[o + rk.B_SLIPN] = t_k.size
        p[o + rk.B_SLIPDT] = dt
        tables.append(t_k)
        off += t_k.size
    return dataclasses.replace(model, p=np.concatenate([p, *tables]))


def n_aux(model: PackedModel, ball_forces: bool) -> int:
    """Number of auxiliary outputs per sample."""
    return 4 + (2 * model.n_balls if ball_forces else 0)


def evaluate_rhs(model: PackedModel, t: float, y: NDArray) -> tuple[NDArray, NDArray]:
    """``(dy/dt, aux)`` of the compiled kernel at time ``t`` [s] and state ``y`` (for checks)."""
    y = np.ascontiguousarray(y, dtype=float)
    dydt = np.zeros_like(y)
    aux = np.zeros(4 + 2 * model.n_balls)
    p = model.p.copy()
    p[rk.H_BALL_OUT] = 1.0
    rk.rhs_core(float(t), y, p, dydt, aux, True)
    return dydt, aux


def static_state(model: PackedModel, config: RotorConfig) -> NDArray[np.float64]:
    """State at rest in static equilibrium at t = 0 (balls at their cage positions, all
    velocities zero; gravity, ``bearing_loads`` and centrifugal ball forces balanced).

    In the Craig–Bampton coordinates the interior modes are statically decoupled from the
    boundary (``K_r`` is block diagonal and the bearing forces act on the boundary only), so
    they follow directly from the constant load; the balls are put in equilibrium by
    :func:`.rotor_kernel.settle_balls`; the remaining 8 unknowns (bearing-node and housing
    x, y) are found with MINPACK's hybrid Powell method (:func:`scipy.optimize.root`) on the
    force residual (unknowns in micrometres), falling back on Levenberg–Marquardt
    (:func:`scipy.optimize.least_squares`) with a tiny regularisation, and where both fail on
    the derivative-free spectral residual method (``method="df-sane"``) from the best point.
    """
    npos = model.n_pos
    nr = model.n_r
    rot = model.rotor
    mh = np.array([config.housing_de.mass] * 2 + [config.housing_fe.mass] * 2)
    um = 1e-6
    y = np.zeros(2 * npos)
    dydt = np.zeros(2 * npos)
    if nr > 4:
        y[4:nr] = np.linalg.solve(rot.K[4:, 4:], rot.f_static[4:])

    def resid(xi: NDArray) -> NDArray:
        y[:4] = xi[:4] * um
        y[nr : nr + 4] = xi[4:] * um
        rk.settle_balls(0.0, y, model.p, dydt, 64)
        rk.rhs_core(0.0, y, model.p, dydt, dydt, False)
        a = dydt[npos:]
        return np.concatenate([(rot.M @ a[:nr])[:4], mh * a[nr : nr + 4]])

    def solve(fb: NDArray) -> tuple[float, NDArray, NDArray]:
        """(largest residual [N], solution, guess) from the guess built for the end loads
        ``fb`` (DE x, y, FE x, y) [N]."""
        # initial guess: housings on their springs under the bearing loads; each shaft end
        # moved along its load until the balls carry that load (bisection, ends separately)
        x0 = np.zeros(8)
        for e, h in enumerate(housings):
            x0[4 + 2 * e] = fb[2 * e] / h.stiffness_x / um
            x0[5 + 2 * e] = (fb[2 * e + 1] - h.mass * g) / h.stiffness_y / um
        y[nr : nr + 4] = x0[4:] * um
        for e in range(2):
            f = float(np.hypot(fb[2 * e], fb[2 * e + 1]))
            if f == 0.0:
                continue
            d = fb[2 * e : 2 * e + 2] / f
            z0, z = (0, model.z_de) if e == 0 else (model.z_de, model.z_fe)
            psi = np.array([pb[int(pb[rk.H_BRG_DE if e == 0 else rk.H_BRG_FE]) + rk.B_PSI0]])
            psi = psi + 2 * np.pi * np.arange(z) / z
            lo, hi = 0.0, 1e-4
            for _ in range(60):
                u = 0.5 * (lo + hi)
                y[2 * e : 2 * e + 2] = y[nr + 2 * e : nr + 2 * e + 2] + u * d
                rk.settle_balls(0.0, y, model.p, dydt, 64)
                rk.rhs_core(0.0, y, pb, dydt, aux, True)
                qa = aux[4 + 2 * z0 : 4 + 2 * z0 + z]  # inner contact forces of this bearing
                carried = float(np.sum(qa * (np.sin(psi) * d[0] + np.cos(psi) * d[1])))
                lo, hi = (u, hi) if carried < f else (lo, u)
            x0[2 * e : 2 * e + 2] = y[2 * e : 2 * e + 2] / um
        sol = root(resid, x0, method="hybr")
        best = (float(np.max(np.abs(resid(sol.x)))), sol.x)
        if best[0] > 1e-9 * weight:
            # Levenberg-Marquardt with a tiny Tikhonov term (1e-6 N per um): it keeps any
            # neutral direction (e.g. a shaft end resting on a single ball, free sideways within
            # the clearance) at the initial guess instead of letting the Jacobian go singular
            ls = least_squares(lambda x: np.concatenate([resid(x), 1e-6 * (x - x0)]), x0,
                               method="lm", xtol=1e-15, ftol=1e-15, gtol=1e-15)  # fmt: skip
            r = float(np.max(np.abs(resid(ls.x))))
            if r < best[0]:
                best = (r, ls.x)
        return best[0], best[1], x0

    fb0 = rot.f_static[:4]
    g = G0 if config.gravity else 0.0
    pb = model.p.copy()
    pb[rk.H_BALL_OUT] = 1.0
    aux = np.zeros(4 + 2 * model.n_balls)
    housings = (config.housing_de, config.housing_fe)
    weight = float(np.abs(fb0).sum()) + 1.0
    best = solve(fb0)[:2]
    if best[0] > 1e-6 * weight and np.any(rot.f_unb_cos[:4] != 0.0):
        # the unbalance at t = 0 (larger than the weight: the net load points up) moves the
        # ends the other way; the guess along the static load alone starts them in the
        # clearance, where no ball carries anything
        r2, x2, _ = solve(fb0 + rot.f_unb_cos[:4])
        if r2 < best[0]:
            best = (r2, x2)
    r, x = best
    if r > 1e-6 * weight:
        # the derivative-free spectral residual method (DF-SANE) from the best point: both
        # Jacobian methods stall where the residual has a kink (a ball's rough contact onset;
        # exploratory testing, twenty-fourth session: the 6206 at 1750 r/min with 0.1 um
        # roughness stopped at 1.3e-3 N, DF-SANE reaches 9e-11 N). Only where they failed, so
        # every equilibrium found before is found unchanged
        ds = root(resid, x, method="df-sane")
        r2 = float(np.max(np.abs(resid(ds.x))))
        if r2 < r:
            r, x = r2, ds.x
    if r > 1e-6 * weight:
        raise SolverError(
            f"no static equilibrium found for the rotor (force residual {r:.3g} N); "
            "check the loads, clearances and stiffnesses"
        )
    resid(x)
    return y.copy()


def stable_step(model: PackedModel, config: RotorConfig, y0: NDArray, margin: float = 2.0):
    """Largest RK4 step [s] for the fastest mode of the linearised system, ``margin / omega_max``
    [s] with ``omega_max`` [rad/s] the largest eigenvalue modulus (the RK4 stability region holds
    the left half-disk of radius 2.6: 2.83 on the imaginary axis, 2.79 on the negative real axis).

    The contact stiffness is the Hertz tangent ``1.5 k^(2/3) Q^(1/3)`` at four times the
    largest static contact load (plus 1 N) to cover the dynamic load peaks. The modes bounded:
    each ball's radial mode between its two contacts, each housing on its mount and its balls,
    the undamped rotor on each bearing's stiffness, and the damped, gyroscopic rotor on both
    (:func:`rotor_eigenvalue_bound`): the stiffness-proportional damping ``beta K`` puts a
    rotor mode of ``omega`` at the real eigenvalue ``-beta omega^2`` once it is overdamped
    (``zeta = beta omega / 2 > 1``), which outgrows ``omega`` itself (from ~12 disks at 48 kHz
    output the fastest eigenvalue is such a mode).
    """
    _, aux = evaluate_rhs(model, 0.0, y0)
    q = aux[4:]
    qd = 4.0 * float(q.max()) + 1.0
    w2 = []
    kb_ends = []
    for sup, h in ((config.de, config.housing_de), (config.fe, config.housing_fe)):
        b = sup.bearing
        ki = ball_contact(b, 1.0, Race.INNER).k_hertz
        ko = ball_contact(b, 1.0, Race.OUTER).k_hertz
        kti = 1.5 * ki ** (2 / 3) * qd ** (1 / 3)
        kto = 1.5 * ko ** (2 / 3) * qd ** (1 / 3)
        if config.ball_inertia:  # the ball's radial mode between its two contacts
            w2.append((kti + kto) / sup.ball_mass)
        kser = 1.0 / (1.0 / kti + 1.0 / kto)
        w2.append((max(h.stiffness_x, h.stiffness_y) + b.n_elements * kser) / h.mass)
        kb = np.zeros_like(model.rotor.K)
        kb[:4, :4] = np.eye(4) * b.n_elements * kser
        lam = np.linalg.eigvals(np.linalg.solve(model.rotor.M, model.rotor.K + kb))
        w2.append(float(np.max(lam.real)))
        kb_ends += [b.n_elements * kser] * 2
    w = math.sqrt(max(w2))
    return margin / max(w, rotor_eigenvalue_bound(model.rotor, config, np.array(kb_ends)))


def rotor_eigenvalue_bound(rot: RotorAssembly, config: RotorConfig, k_ends: NDArray) -> float:
    """Largest eigenvalue modulus [rad/s] of the reduced rotor with its damping and gyroscopic
    coupling, ``M q'' + (C + Omega G) q' + (K + K_b) q = 0``, on bearing springs ``k_ends``
    [N/m] at its four boundary coordinates (DE x, y, FE x, y): the eigenvalues of the
    first-order matrix ``[[0, I], [-M^-1 (K + K_b), -M^-1 (C + Omega G)]]``."""
    n = rot.n
    kb = rot.K.copy()
    kb[np.arange(4), np.arange(4)] += k_ends
    a = np.zeros((2 * n, 2 * n))
    a[:n, n:] = np.eye(n)
    a[n:, :n] = -np.linalg.solve(rot.M, kb)
    a[n:, n:] = -np.linalg.solve(rot.M, rot.C + config.omega * rot.G)
    return float(np.max(np.abs(np.linalg.eigvals(a))))


# ------------------------------------------------------------------------------ simulation


def _run(model, y0, fs_int, n_int, decim, na, method, rtol, atol, progress=None, q=1,
         chunk=1 << 15):  # fmt: skip
    """Integrate in chunks of ``chunk`` output samples (bounded memory); returns the times,
    auxiliary outputs, positions of the bearing nodes and housings, and the step count.
    ``progress(n)`` is called with the number of final (every ``q``-th) samples done."""
    nr = model.n_r
    h = 1.0 / (fs_int * decim) if decim else None
    t_all = np.empty(n_int)
    aux = np.empty((n_int, na))
    pos = np.empty((n_int, 8))
    y = y0
    i = 0
    n_steps = 0
    bound = 1.0  # ball radii are ~0.02 m; any coordinate past 1 m (or 1 m/s) is divergence
    while i < n_int - 1 or i == 0:
        n_c = min(chunk, n_int - 1 - i) + 1
        t0 = i / fs_int
        if method == "rk4":
            tr = run_fixed(rk.rotor_rhs, rk.rotor_aux, y, model.p, dt=h, n_out=n_c, decim=decim,
                           n_aux=na, bound=bound, t0=t0)  # fmt: skip
        else:
            te = (i + np.arange(n_c)) / fs_int
            tr = run_adaptive(rk.rotor_rhs, rk.rotor_aux, y, model.p, te, n_aux=na, rtol=rtol,
                              atol=atol, h0=1e-8, bound=bound)  # fmt: skip
        t_all[i : i + n_c] = tr.t
        aux[i : i + n_c] = tr.aux
        pos[i : i + n_c, :4] = tr.y[:, :4]
        pos[i : i + n_c, 4:] = tr.y[:, nr : nr + 4]
        n_steps += tr.n_steps
        y = tr.y[-1].copy()
        i += n_c - 1
        if progress is not None:
            progress(i // q + 1)
        if n_int == 1:
            break
    return t_all, aux, pos, n_steps


#: largest number of RK4 steps in one chunk of :func:`_run` [-]: bounds the time between two
#: progress reports (and Ctrl-C checks); the chunk keeps 32768 samples up to 128 steps per sample
MAX_CHUNK_STEPS = 1 << 22
#: steps per sample beyond which a run is counted as this many (far beyond any step budget) [-]
MAX_DECIM = float(2**62)


@dataclass
class RotorPlan:
    """A checked rotor run (:func:`plan_rotor`): the packed model, its static state and the
    output grid (``q`` internal samples per output sample, ``decim`` RK4 steps per internal
    sample, ``chunk`` internal samples per compiled call) and the resource estimate."""

    model: PackedModel
    y0: NDArray[np.float64]
    fs: float
    q: int
    n_out: int
    n_int: int
    decim: int
    chunk: int
    cutoff: float
    method: str
    estimate: Estimate


def _run_estimate(config: RotorConfig, n_int: int, n_out: int, decim: float, n_state: int,
                  na: int, chunk: int, ball_forces: bool) -> Estimate:  # fmt: skip
    """Memory [B] and RK4 steps of a rotor run: the internal-rate outputs (times, auxiliary
    outputs, 8 positions), one chunk's trajectory, and the output channels with their copy in
    the result's dataset."""
    nb = config.de.bearing.n_elements + config.fe.bearing.n_elements
    n_ch = 12 + (2 * nb if ball_forces else 0)
    mem = n_int * (1 + na + 8) * F8 + min(chunk, n_int) * (1 + n_state + na) * F8
    mem += 2 * n_out * n_ch * F8
    what = f"rotor: {n_int} internal samples x {decim:.6g} RK4 steps"
    return Estimate(what, mem, float(n_int - 1) * decim)


def plan_rotor(
    config: RotorConfig,
    duration: float = 1.0,
    sample_rate: float = 12000.0,
    dt: float | None = None,
    ball_forces: bool = False,
    antialias: bool = True,
    method: Solver | str = Solver.RK4,
    budget: Budget | None = None,
) -> RotorPlan:
    """Check a rotor run before it starts (arguments of :func:`simulate_rotor`): the mesh's
    memory, its size (:func:`check_fe_size`), then a lower bound of the step count from the
    housing mounts alone, all before the model is built; then the model, its static state, the
    step and the full estimate against ``budget`` (:mod:`..budget`)."""
    duration = check_positive("duration_s", duration, "s")
    fs = check_positive("sample_rate_hz", sample_rate, "Hz")
    method = parse_enum(Solver, method, "solver").value
    n_out = int(round(duration * fs))
    if n_out < 2:
        raise ConfigError(
            f"duration_s * sample_rate_hz = {duration * fs:.6g} samples is too few; valid range "
            "[2, inf) samples"
        )
    q = (4 if fs <= 24000.0 else 2) if antialias else 1
    fs_int = q * fs
    n_int = q * (n_out - 1) + 1
    check_budget(fe_estimate(config), budget)
    check_fe_size(config)
    if method == "rk4" and dt is None:  # the mounts alone bound the stable step (stable_step)
        w = max(math.sqrt(max(h.stiffness_x, h.stiffness_y) / h.mass)
                for h in (config.housing_de, config.housing_fe))  # fmt: skip
        low = max(1.0, math.ceil(min(w / (2.0 * fs_int), MAX_DECIM)))
        check_budget(_run_estimate(config, n_int, n_out, low, 0, 0, 1, False), budget)
    cutoff = config.mode_cutoff_hz or fs
    model = pack_model(config, cutoff, ball_forces)
    y0 = static_state(model, config)
    na = n_aux(model, ball_forces)
    decim = 0
    if method == "rk4":
        if dt is None:
            decim = math.ceil(min(1.0 / (fs_int * stable_step(model, config, y0)), MAX_DECIM))
        else:
            decim = round(min(1.0 / (fs_int * check_positive("dt_s", dt, "s")), MAX_DECIM))
        decim = max(1, int(decim))
    chunk = max(1, min(1 << 15, MAX_CHUNK_STEPS // max(decim, 1)))
    est = _run_estimate(config, n_int, n_out, max(decim, 1), 2 * model.n_pos, na, chunk,
                        ball_forces)  # fmt: skip
    check_budget(est, budget)
    return RotorPlan(model, y0, fs, q, n_out, n_int, decim, chunk, cutoff, method, est)


def simulate_rotor(
    config: RotorConfig,
    duration: float = 1.0,
    sample_rate: float = 12000.0,
    dt: float | None = None,
    ball_forces: bool = False,
    antialias: bool = True,
    method: Solver | str = Solver.RK4,
    rtol: float = 1e-8,
    atol: float = 1e-13,
    progress: Callable[[int], None] | None = None,
    budget: Budget | None = None,
    slip: float = 0.0,
    slip_seed: int = 0,
    jitter: float = 0.0,
) -> RotorResponse:
    """Simulate the bearing–rotor–housing system from static equilibrium.

    Parameters
    ----------
    config : RotorConfig
        Inputs.
    duration : float
        Simulated time [s] (> 0): ``round(duration * sample_rate)`` samples from t = 0.
    sample_rate : float
        Output sample rate [Hz] (CWRU: 12 000 or 48 000).
    dt : float or None
        RK4 step [s]; default: the largest step from :func:`stable_step` that divides the
        internal output interval. Ignored by ``method="dopri5"``.
    ball_forces : bool
        Also return every ball's contact forces.
    antialias : bool
        Like a data-acquisition system, sample internally at ``q`` x ``sample_rate`` (q = 4 up
        to 24 kHz output, 2 above) and low-pass filter the accelerations before keeping every
        q-th sample (:func:`scipy.signal.decimate`, zero-phase FIR, cut-off at the output
        Nyquist frequency); the other outputs are sampled without filtering. ``False`` samples the
        model's acceleration directly (content above ``sample_rate/2`` then aliases).
    method : Solver or {"rk4", "dopri5"}
        Compiled fixed-step RK4 (default) or adaptive Dormand–Prince 5(4) with ``rtol``,
        ``atol`` (for checking).
    progress : callable, optional
        Called with the number of output samples done (for progress bars).
    budget : Budget, optional
        Memory [B] and step limits (:class:`bearingsim.dynamics.budget.Budget`), checked before
        the run by :func:`plan_rotor`.
    slip : float
        Random slip: standard deviation of each ball-pass interval relative to its mean [-]
        (:mod:`bearingsim.dynamics.slip`), each bearing's cage its own process; 0 = kinematic.
    slip_seed : int
        Seed of the slip processes (``SeedSequence([slip_seed, 1, end])``, end 0 DE, 1 FE).
    jitter : float
        Pocket jitter: standard deviation of each ball-pass interval from independent moves of
        the pass instants (no phase drift) [-] (:mod:`bearingsim.dynamics.slip`).

    Returns
    -------
    RotorResponse
    """
    from scipy.signal import decimate

    t_wall = time.perf_counter()
    plan = plan_rotor(config, duration, sample_rate, dt, ball_forces, antialias, method, budget)
    model, y0, fs, q, decim = plan.model, plan.y0, plan.fs, plan.q, plan.decim
    method, cutoff = plan.method, plan.cutoff
    duration = check_positive("duration_s", duration, "s")
    if slip > 0.0 or jitter > 0.0:
        model = _with_slip(model, config, slip, slip_seed, duration, jitter)
    fs_int = q * fs
    na = n_aux(model, ball_forces)
    if method == "rk4":
        solver = {"solver": "rk4", "dt_s": 1.0 / (fs_int * decim), "decim": decim}
    else:
        solver = {"solver": "dopri5", "rtol": rtol, "atol": atol}
    t, aux, pos, n_steps = _run(
        model, y0, fs_int, plan.n_int, decim, na, method, rtol, atol, progress, q, plan.chunk
    )
    acc = aux[:, :4]
    if q > 1:
        acc = decimate(acc, q, ftype="fir", axis=0, zero_phase=True)
        t, aux, pos = t[::q], aux[::q], pos[::q]
    kin = {
        end: characteristic_frequencies(kb, config.shaft_hz)
        for end, kb in zip(ENDS, model.kinematic_bearings(config), strict=True)
    }
    red = model.rotor.reduction
    arm = config.armature
    meta = {
        "model": "rotor",
        "version": __version__,
        "inputs": config_summary(config),
        "sample_rate_hz": fs,
        "duration_s": duration,
        "antialias": bool(antialias),
        "n_rotor_coordinates": model.n_r,
        "n_fe_dof": model.rotor.fe.n_dof,
        "mode_cutoff_hz": cutoff,
        "n_modes_kept": int(red.mode_hz.size),
        "n_modes_dropped": red.n_dropped,
        "n_disks_label": "distributed rotor mass" if arm.distributed else f"{arm.n_disks} disk(s)",
        "kinematics": {e: kin[e].as_dict() | {"shaft_hz": kin[e].shaft_hz} for e in ENDS},
        "n_steps": n_steps,
        "wall_time_s": time.perf_counter() - t_wall,
        **solver,
    }
    if model.axial is not None:
        meta["axial"] = {
            end: {
                "axial_load_n": config.axial_load,
                "offset_z_m": a.z,
                "contact_angle_deg": math.degrees(a.contact_angle),
                "ball_contact_angles_deg": np.degrees(a.ball_contact_angles).tolist(),
            }
            for end, a in zip(ENDS, model.axial, strict=True)
        }
    bi = bo = None
    if ball_forces:
        zde, zfe = model.z_de, model.z_fe
        bi = np.concatenate([aux[:, 4 : 4 + zde], aux[:, 4 + 2 * zde : 4 + 2 * zde + zfe]], 1)
        bo = np.concatenate([aux[:, 4 + zde : 4 + 2 * zde], aux[:, 4 + 2 * zde + zfe :]], 1)
    return RotorResponse(
        t, np.ascontiguousarray(acc), pos[:, 4:].copy(), pos[:, :4].copy(), bi, bo, kin, meta
    )
