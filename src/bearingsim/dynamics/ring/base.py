"""Inputs, parameter packing and the chunked integration driver shared by the VSM, TVSM and DEM.

Every model of this package is a 2-DOF ring (seed VSM eq. (19)) with state
``y = (u_x, u_y, v_x, v_y)`` — displacement [m] and velocity [m/s] of the inner ring relative to
the outer ring — whose right-hand side is a Numba ``cfunc`` (:data:`..integrate.RHS_SIG`)
reading the flat parameter vector laid out in :mod:`._balance`. The VSM and TVSM need the
quasi-static solution at every RK4 stage time; :func:`integrate_model` tabulates it on the
half-step grid (compiled, warm-started) chunk by chunk, so that the whole stepping loop stays
compiled and memory stays bounded for long runs.

Auxiliary outputs per sample (all models), in this order: ``acc_x, acc_y`` [m/s^2],
``k_xx, k_xy, k_yy`` [N/m], ``k_load`` (stiffness along the load direction ``theta_0``) [N/m],
``n_loaded`` [-], then, when per-ball outputs are requested, ``Q_1..Q_Z`` [N] and the contact
deformations ``(Q_j/K)^(1/n)`` [m].
"""

from __future__ import annotations

import functools
import math
from collections.abc import Callable
from dataclasses import dataclass, replace
from typing import TYPE_CHECKING

import numpy as np
from numpy.typing import NDArray

from ...config import (
    SEED_VSM_DAMPING_N_S_M,
    SEED_VSM_MASS_OUTER_KG,
    ZERO_RADIAL_LOAD,
    check_ball_spread,
    check_roughness,
    profile_gamma_refusal,
    ring_is_held,
    secant_refusal,
)
from ...contact.hertz import element_stiffness
from ...errors import ConfigError, check_positive, check_range
from ...geometry import (
    BallBearing,
    Bearing,
    Defect,
    DefectProfile,
    Race,
    characteristic_frequencies,
    check_clearance,
    check_pit_depth,
    defect_geometry,
    parse_enum,
)
from ..defect_pit import pit_contacts
from ..integrate import call_compiled, run_adaptive, run_fixed
from . import _balance as bl
from .defects import FAULT_CODE

if TYPE_CHECKING:
    from ...quasistatic.jones import AxialState

__all__ = [
    "AUX_NAMES",
    "integrate_model",
    "integrate_model_adaptive",
    "max_frequency",
    "ModelInputs",
    "ModelKernel",
    "n_aux",
    "N_AUX_FIXED",
    "RawRun",
    "static_path",
]

#: number of fixed auxiliary outputs before the per-ball block
N_AUX_FIXED = 7
AUX_NAMES = ("acc_x", "acc_y", "k_xx", "k_xy", "k_yy", "k_load", "n_loaded")


def check_ball_bearing(bearing) -> None:
    """Refuse (one line) a bearing that is not a ball bearing, the ring models' contacts and
    defects being those of balls; and one with a nominal contact angle
    (:func:`check_no_contact_angle`)."""
    if not isinstance(bearing, BallBearing):
        raise ConfigError(
            f"bearing = {getattr(bearing, 'id', bearing)!r} is not a ball bearing; the "
            "VSM/DEM/TVSM models need a ball bearing"
        )
    check_no_contact_angle(bearing, "VSM/DEM/TVSM models")


def check_no_contact_angle(bearing, models: str) -> None:
    """Refuse (one line) a ball bearing with a nominal contact angle for the dynamic models
    (``models``, for the message): they hold a deep-groove bearing's contacts at the groove
    bottom under a radial load and take the angle an axial load gives from the geometry
    (:func:`bearingsim.quasistatic.jones.axial_state`), so the nominal angle set the fault
    frequencies and not the forces (a helper's exploratory testing, twenty-eighth session: a
    25 deg bearing gave the 0 deg bearing's loads and stiffness at its own BPFO)."""
    a = float(getattr(bearing, "contact_angle", 0.0))
    if a != 0.0:
        raise ConfigError(
            f"bearing = {getattr(bearing, 'id', bearing)!r} has contact_angle = "
            f"{math.degrees(a):.4g} deg; the {models} take a deep-groove bearing's contacts at "
            "the groove bottom (0 deg) and the angle an axial load gives from its geometry, so "
            "a nominal angle would set the fault frequencies and not the forces; valid: "
            "contact_angle_rad = 0 (an axial load through axial_load_n)"
        )


@dataclass(frozen=True)
class ModelInputs:
    """Physical inputs common to the VSM, TVSM and DEM (SI units).

    Parameters
    ----------
    bearing : BallBearing
        Geometry and material (ball bearing).
    fx, fy : float
        Constant radial force on the inner ring [N] (seed table 1: 10 N and 50 N; include
        the rotor weight).
    shaft_hz : float
        Inner-ring speed f_s [Hz]; the cage turns at the FTF.
    defect : Defect or None
        The local raceway defect (its ``angle`` is the centre azimuth at ``t = 0``; see
        :func:`.defects.defect_at_edge` for seed VSM's left-edge ``beta_0``); ``None`` for a
        healthy bearing.
    first_ball_angle : float
        Azimuth of ball 1 at ``t = 0``, ``alpha_0`` [rad].
    mass : float
        Vibrating mass m of eq. (19) [kg].
    damping : float
        Equivalent damping c_eq [N s/m].
    stiffness : float or None
        Ball load–deflection constant K [N/m^1.5] overriding the Hertz value (seed eq. (10)).
    clearance : float or None
        Diametral clearance P_d [m] overriding the bearing's; negative = a preloaded bearing
        (every ball loaded), within the ISO 5753-1 group 5 limit of the bore. The VSM (secant
        stiffness) needs ``P_d >= 0``: :meth:`require_clearance`.
    retention_factor : float or None
        Prescribed constant ``gamma`` for a ball over the defect (seed figs. 6–7); ``None``
        evaluates eq. (11) implicitly from the geometric drop ``h_min``.
    load_zone_half_angle : float or None
        ``None`` (default): a ball is in the load zone when its nominal deflection is positive
        (contact decides). A value ``psi_L`` [rad] applies the seed's literal eq. (14): only
        balls inside the fixed window ``theta_0 +/- psi_L`` carry load.
    tol : float
        Relative force tolerance of the static balance [-].
    slip : float
        Random slip: standard deviation of each ball-pass interval relative to its mean [-]
        (0: the cage turns at the FTF exactly). Literature: 0.01–0.02 (Randall & Antoni 2011,
        MSSP 25). See :meth:`slip_table`.
    jitter : float
        Pocket jitter: standard deviation of each ball-pass interval from independent moves of
        the pass instants around the cage-speed process, relative to the period [-] (the balls
        wander within their pockets; no phase drift). See :mod:`bearingsim.dynamics.slip`.
    slip_seed : int
        Seed of the slip process (``numpy.random.SeedSequence([slip_seed, 1])``: a stream of
        its own, apart from the measurement noise's ``default_rng(seed)``) and of the ball
        diameters (``SeedSequence([slip_seed, 2])``).
    ball_diameter_spread : float
        Largest minus smallest ball diameter of the set [m] (0: identical balls). ISO 3290-1
        calls it the lot diameter variation V_DwL and bounds it by grade: G5 0.25, G10 0.5,
        G16 0.8, G20 1.0, G28 1.4, G40 2.0 µm. See :meth:`ball_deviations`.
    unbalance : float
        Amplitude F_u of a radial force turning with the shaft [N] (rotor unbalance
        ``m e w_s^2``), added to ``(fx, fy)`` as ``F_u (sin w_s t, cos w_s t)``; less than
        ``|(fx, fy)|`` so that the load never vanishes. 0: a constant load (the seed's).
    profile : DefectProfile or str
        Drop of a ball across the defect: ``"rectangular"`` (default; seed VSM eqs. (1)–(3):
        the constant ``h_min`` over the extent) or ``"geometric"`` (the ball rests on the
        nearer edge, seed VSM eq. (2) along the path: 0 at the edges, ``h_min`` at the centre;
        the rotor model's default). The geometric profile needs the implicit eq. (11)
        (``retention_factor`` unset). This field, not ``defect.profile``, sets it.
    roughness : float
        Composite RMS surface roughness ``sigma = sqrt(R_q,ball^2 + R_q,race^2)`` of the
        ball-raceway contacts [m], in [0, 1e-6]: the ball load law is Hertz's averaged over a
        normal asperity-height offset of that standard deviation
        (:mod:`bearingsim.contact.rough`), so a ball entering or leaving the load zone takes
        up its load over a few ``sigma`` of approach instead of with the smooth contact's
        singular onset. 0 (default): Hertz's law, the seeds'.
    axial_load : float
        Constant axial force ``F_a`` on the inner ring [N] (a motor's wave spring, a thrust, a
        fit), >= 0. Each ball then touches its grooves at a contact angle: the inner ring's
        groove centres sit axially offset by the ``z`` of the Jones equilibrium of
        ``(fx, fy, F_a)`` with the ring tilts held at 0
        (:func:`bearingsim.quasistatic.jones.run_quasi_static`, at ``t = 0``, identical balls),
        and ``z`` is held there while the ring moves radially: every ball's load follows the
        groove-centre distance ``sqrt((A0 - P_d/2 + u.e_j)^2 + z^2)`` and acts along its
        contact angle, of which the radial part enters the ring's balance. Enough axial load
        loads every ball (a defect at 12 o'clock is struck). The cage and ball spin follow the
        load-weighted mean contact angle (:attr:`axial_state`), so the fault lines move as in a
        measured record (``BPFO = Z f_s/2 (1 - d cos(alpha)/D)``). 0 (default): the seeds'
        radial model, bit for bit. DEM and TVSM (the VSM's secant stiffness is measured from the
        concentric position: :meth:`require_clearance`).
    """

    bearing: Bearing
    fx: float
    fy: float
    shaft_hz: float
    defect: Defect | None = None
    first_ball_angle: float = 0.0
    mass: float = SEED_VSM_MASS_OUTER_KG
    damping: float = SEED_VSM_DAMPING_N_S_M
    stiffness: float | None = None
    clearance: float | None = None
    retention_factor: float | None = None
    load_zone_half_angle: float | None = None
    tol: float = 1e-12
    slip: float = 0.0
    slip_seed: int = 0
    jitter: float = 0.0
    ball_diameter_spread: float = 0.0
    unbalance: float = 0.0
    profile: DefectProfile | str = DefectProfile.RECTANGULAR
    roughness: float = 0.0
    axial_load: float = 0.0

    def __post_init__(self) -> None:
        b = self.bearing
        check_ball_bearing(b)
        fx = check_range("fx_n", self.fx, unit="N") + 0.0  # -0.0 -> 0.0 (the load direction)
        fy = check_range("fy_n", self.fy, unit="N") + 0.0
        cl = None if self.clearance is None else check_range("clearance_m", self.clearance)
        ax = check_range("axial_load_n", self.axial_load, 0.0, unit="N")
        held = ring_is_held(cl, ax)
        if math.hypot(fx, fy) == 0.0 and not held:
            raise ConfigError(ZERO_RADIAL_LOAD)
        object.__setattr__(self, "fx", fx)
        object.__setattr__(self, "fy", fy)
        object.__setattr__(self, "shaft_hz", check_positive("shaft_hz", self.shaft_hz, "Hz"))
        object.__setattr__(self, "mass", check_positive("mass_kg", self.mass, "kg"))
        object.__setattr__(
            self, "damping", check_range("damping_n_s_per_m", self.damping, 0.0, unit="N s/m")
        )
        object.__setattr__(
            self,
            "first_ball_angle",
            check_range("first_ball_angle_rad", self.first_ball_angle, unit="rad"),
        )
        if self.stiffness is not None:
            object.__setattr__(
                self, "stiffness", check_positive("stiffness_n_per_m1_5", self.stiffness, "N/m^1.5")
            )
        pd = b.diametral_clearance if self.clearance is None else self.clearance
        # negative = preload (negative operating clearance after fits and heat; Harris &
        # Kotzalas 2007, ch. 7: every ball loaded); the VSM refuses it (require_clearance)
        pd = check_clearance(b, pd, name="clearance_m", hi=0.5 * b.element_diameter)
        if self.clearance is not None:
            object.__setattr__(self, "clearance", pd)
        if self.retention_factor is not None:
            object.__setattr__(
                self,
                "retention_factor",
                check_range("retention_factor", self.retention_factor, 0.0, 1.0),
            )
        if self.load_zone_half_angle is not None:
            object.__setattr__(
                self,
                "load_zone_half_angle",
                check_range(
                    "load_zone_half_angle_rad",
                    self.load_zone_half_angle,
                    0.0,
                    math.pi,
                    lo_open=True,
                    hi_open=True,
                    unit="rad",
                ),
            )
            # two balls must stay in the window at every cage angle: one alone carries only
            # the load along its own line, and the ring drifted sideways without bound (a
            # helper's exploratory testing, twenty-eighth session: 30 deg on the 6205-cwru
            # left 17 % of the load unbalanced, the ring 11 clearances off, written silently)
            pitch = 2.0 * math.pi / b.n_elements
            if self.load_zone_half_angle < pitch * (1.0 - 1e-12):
                raise ConfigError(
                    f"load_zone_half_angle = {math.degrees(self.load_zone_half_angle):.6g} deg "
                    f"is below the ball pitch of {b.id} ({math.degrees(pitch):.6g} deg): at some "
                    "cage angles one ball alone would carry the load, which it balances only "
                    f"along its own line; valid range [{math.degrees(pitch):.6g}, 180) deg, or "
                    "none (the contact decides)"
                )
        if self.defect is not None:
            if not isinstance(self.defect, Defect):
                raise ConfigError(f"defect = {self.defect!r} is not a Defect or None")
            defect_geometry(b, self.defect)  # validates the width against the ball
        object.__setattr__(self, "tol", check_range("tol", self.tol, 0.0, 1e-6, lo_open=True))
        object.__setattr__(
            self, "jitter", check_range("pocket_jitter", self.jitter, 0.0, 0.1, unit="")
        )
        object.__setattr__(
            self,
            "unbalance",
            check_range(  # below the static load, unless a preload or axial load holds the ring
                "unbalance_n",
                self.unbalance,
                0.0,
                math.inf if held else math.hypot(fx, fy),
                hi_open=True,
                unit="N",
            ),
        )
        object.__setattr__(
            self, "ball_diameter_spread", check_ball_spread(self.ball_diameter_spread)
        )
        object.__setattr__(self, "roughness", check_roughness(self.roughness))
        object.__setattr__(self, "axial_load", ax)  # checked above, with the radial load
        prof = parse_enum(DefectProfile, self.profile, "defect_profile")
        object.__setattr__(self, "profile", prof)
        if prof is DefectProfile.PIT and self.defect is not None:
            check_pit_depth(self.bearing, self.defect)
        profile_gamma_refusal(prof.value, self.retention_factor)

    def require_clearance(self, who: str) -> None:
        """Refuse a negative clearance or an axial load for ``who`` (the VSM and its static
        trace; :func:`bearingsim.config.secant_refusal`)."""
        secant_refusal(who, self.diametral_clearance, self.axial_load)

    @property
    def diametral_clearance(self) -> float:
        """P_d used [m]."""
        return self.bearing.diametral_clearance if self.clearance is None else self.clearance

    @property
    def k_ball(self) -> float:
        """Ball constant K used [N/m^1.5] (Hertz, seed eq. (10), unless overridden)."""
        if self.stiffness is not None:
            return self.stiffness
        return element_stiffness(self.bearing)[0]

    @functools.cached_property
    def axial_state(self) -> AxialState:
        """The static axial offset and contact angles under :attr:`axial_load` (see there);
        ``z = 0`` and the bearing's own angle without one."""
        from ...quasistatic.jones import AxialState, axial_state

        b = self.bearing
        if self.axial_load <= 0.0:
            return AxialState(0.0, b.contact_angle, np.full(b.n_elements, b.contact_angle))

        return axial_state(  # the scenario's load check (plan_ring) covers the load
            b,
            self.fx,
            self.fy,
            self.axial_load,
            clearance=self.diametral_clearance,
            stiffness=self.k_ball,
            first_ball_angle=self.first_ball_angle,
        )

    @property
    def kinematic_bearing(self) -> Bearing:
        """The bearing at its operating contact angle (:attr:`axial_state`): the geometry
        the cage and ball speeds follow."""
        if self.axial_load <= 0.0:
            return self.bearing
        return replace(self.bearing, contact_angle=self.axial_state.contact_angle)

    @property
    def cage_hz(self) -> float:
        """Cage frequency f_m = FTF [Hz] (at the operating contact angle)."""
        return characteristic_frequencies(self.kinematic_bearing, self.shaft_hz).ftf_hz

    @property
    def theta0(self) -> float:
        """Load direction from +y towards +x [rad]."""
        return math.atan2(self.fx, self.fy)

    def slip_table(self, duration: float) -> tuple[NDArray[np.float64], float]:
        """The ball-pass instants ``t_k`` [s] covering ``duration`` [s] and the nominal
        ball-pass period [s] of random slip (:mod:`bearingsim.dynamics.slip`; seed
        ``SeedSequence([slip_seed, 1])``)."""
        from ..slip import ball_pass_instants

        return ball_pass_instants(
            self.bearing.n_elements,
            self.cage_hz,
            self.slip,
            duration,
            (int(self.slip_seed), 1),
            self.jitter,
        )

    def ball_deviations(self) -> NDArray[np.float64]:
        """Diameter deviation of each ball from the nominal, ``Delta D_j`` [m] (ball 1 first;
        empty without a spread): :func:`bearingsim.dynamics.ballset.ball_deviations` seeded
        with ``(slip_seed, 2)``.

        Ball-to-ball diameter differences make the balls carry unequal loads, so the impacts of
        successive balls on a race defect differ and the pattern repeats every cage turn: lines
        at the FTF and its harmonics in the envelope spectrum of an outer- or inner-race fault.
        """
        from ..ballset import ball_deviations

        return ball_deviations(
            self.bearing.n_elements, self.ball_diameter_spread, (int(self.slip_seed), 2)
        )

    def pack(
        self, q: NDArray[np.float64], slip: NDArray[np.float64] | None = None
    ) -> NDArray[np.float64]:
        """The parameter vector ``q`` (header and any table) with the tail tables the kernels
        read by offset appended: the slip instants (``P_SLIP``) and the ball diameter deviations
        (``P_BDEV``); ``q`` itself (a copy) when there are none."""
        dev = self.ball_deviations()
        parts = [q]
        size = q.size
        out_off = {}
        if slip is not None and slip.size:
            out_off[bl.P_SLIP] = size
            parts.append(slip)
            size += slip.size
        if dev.size:
            out_off[bl.P_BDEV] = size
            parts.append(dev)
        out = np.concatenate(parts) if len(parts) > 1 else q.copy()
        for k, v in out_off.items():
            out[k] = v
        return out

    def header(self, per_ball: bool = False) -> NDArray[np.float64]:
        """The parameter vector header (layout :mod:`._balance`), without a table."""
        p = np.zeros(bl.HEADER)
        p[bl.P_MASS] = self.mass
        p[bl.P_DAMP] = self.damping
        p[bl.P_FX] = self.fx
        p[bl.P_FY] = self.fy
        p[bl.P_FU] = self.unbalance
        p[bl.P_Z] = self.bearing.n_elements
        p[bl.P_K] = self.k_ball
        p[bl.P_N] = 1.5
        p[bl.P_CLR] = 0.5 * self.diametral_clearance
        p[bl.P_WCAGE] = 2.0 * math.pi * self.cage_hz
        p[bl.P_WSHAFT] = 2.0 * math.pi * self.shaft_hz
        p[bl.P_ALPHA0] = self.first_ball_angle
        p[bl.P_FAULT] = FAULT_CODE[None if self.defect is None else self.defect.race]
        p[bl.P_DFAC] = 1.0
        if self.defect is not None:
            g = defect_geometry(self.bearing, self.defect)
            p[bl.P_BETA0] = g.edge_angle
            p[bl.P_DBETA] = g.delta_beta
            if self.retention_factor is None:
                p[bl.P_DOFF] = g.h_min  # eq. (11) implicit: gamma K delta^1.5 = K(delta-h)^1.5
                if g.h_min_inner is not None:  # a ball defect meets both races
                    p[bl.P_DOFFI] = g.h_min_inner
            else:
                p[bl.P_DFAC] = self.retention_factor
            if self.defect.race is Race.BALL:
                k = characteristic_frequencies(self.kinematic_bearing, self.shaft_hz)
                p[bl.P_SPIN] = k.bsf_hz / k.ftf_hz  # spin angle per cage angle
            if self.profile is not DefectProfile.RECTANGULAR:
                b = self.bearing
                r_i, r_o = b.inner_raceway_radius, b.outer_raceway_radius
                p[bl.P_PROFILE] = -1.0 if self.profile is DefectProfile.PIT else 1.0
                p[bl.P_RBALL] = 0.5 * b.element_diameter
                p[bl.P_HALFW] = 0.5 * self.defect.width
                p[bl.P_DEPTH] = self.defect.depth
                p[bl.P_RRACE] = r_i if self.defect.race is Race.INNER else r_o
                p[bl.P_RRACEI] = r_i
            if self.profile is DefectProfile.PIT:  # the contact(s) the pit meets
                first, inner, grow = pit_contacts(self.bearing, self.defect)
                k23 = self.k_ball ** (2.0 / 3.0)  # a^2 = a_1^2 Q^(2/3), Q = K d^1.5
                p[bl.P_PITA], p[bl.P_PITB], p[bl.P_PITW] = first[0] * k23, first[1] * k23, first[2]
                if inner is not None:
                    p[bl.P_PITAI], p[bl.P_PITBI] = inner[0] * k23, inner[1] * k23
                    p[bl.P_PITWI] = inner[2]
                # the window holds every position where the contact overlaps the pit
                p[bl.P_BETA0] -= grow
                p[bl.P_DBETA] += 2.0 * grow
        p[bl.P_NTAB] = 0
        p[bl.P_PERBALL] = 1.0 if per_ball else 0.0
        p[bl.P_WARMX] = math.nan
        p[bl.P_WARMY] = math.nan
        p[bl.P_TOL] = self.tol
        p[bl.P_PSIL] = self.load_zone_half_angle or 0.0
        p[bl.P_TH0] = self.theta0
        Z = self.bearing.n_elements
        p[bl.P_SSTEP] = math.sin(2.0 * math.pi / Z)
        p[bl.P_CSTEP] = math.cos(2.0 * math.pi / Z)
        p[bl.P_CT] = math.nan
        p[bl.P_ROUGH] = self.roughness
        if self.roughness > 0.0:
            p[bl.P_RINV] = 1.0 / self.roughness
            p[bl.P_RSN1] = math.sqrt(self.roughness)  # sigma^(n-1), balls: n = 3/2
        if self.axial_load > 0.0:  # the geometry of the Jones solution z comes from
            p[bl.P_AXZ] = self.axial_state.z
            p[bl.P_A0] = self.axial_state.a0
        return p


def static_path(inputs: ModelInputs, times: NDArray[np.float64]):
    """Quasi-static solution at ``times`` [s]: ``(table (m, NCOL), residual (m,))``."""
    p = inputs.pack(inputs.header())
    t = np.ascontiguousarray(times, dtype=float)
    table = np.empty((t.size, bl.NCOL))
    res = np.empty(t.size)
    bl.quasi_static_path(t, p, table, res, math.nan, math.nan)
    return table, res


#: what each ring model's kernels need, by model name: ``(needs_table, stiffness)`` (see
#: :class:`ModelKernel`). Known without compiling anything, so a scenario is checked and planned
#: before (or without) its model's kernels are compiled.
MODEL_FACTS: dict[str, tuple[bool, str]] = {
    "vsm": (True, "secant"),
    "dem": (False, "state"),
    "tvsm": (True, "tangent"),
}


@dataclass(frozen=True)
class ModelKernel:
    """Compiled pieces of one model.

    ``rhs``/``aux`` are the fixed-step versions (reading the tabulated quasi-static solution
    when ``needs_table``); ``rhs_exact``/``aux_exact`` solve the static balance on the fly and
    may be called at any time (adaptive integrator, checks). ``stiffness`` names which table
    stiffness the model uses (``"secant"``, ``"tangent"`` or ``"state"``).
    """

    name: str
    rhs: Callable
    aux: Callable
    rhs_exact: Callable
    aux_exact: Callable
    needs_table: bool
    stiffness: str


@dataclass(frozen=True)
class RawRun:
    """Output of :func:`integrate_model`: sample times [s], states, auxiliary outputs and
    solver facts."""

    t: NDArray[np.float64]
    y: NDArray[np.float64]
    aux: NDArray[np.float64]
    dt: float
    decim: int
    solver: str
    static_residual_max: float
    n_steps: int


def n_aux(inputs: ModelInputs, per_ball: bool) -> int:
    """Number of auxiliary outputs per sample."""
    return N_AUX_FIXED + (2 * inputs.bearing.n_elements if per_ball else 0)


def max_frequency(inputs: ModelInputs, use: str = "tangent", n: int = 721) -> float:
    """Largest natural angular frequency ``sqrt(lambda_max(K)/m)`` over one cage revolution of
    the quasi-static path [rad/s] (for choosing the step)."""
    t_cage = 1.0 / inputs.cage_hz
    times = np.linspace(0.0, t_cage, n)
    table, _ = static_path(inputs, times)
    if use == "secant":
        a, b, c = table[:, bl.C_SXX], table[:, bl.C_SXY], table[:, bl.C_SYY]
    else:
        a, b, c = table[:, bl.C_TXX], table[:, bl.C_TXY], table[:, bl.C_TYY]
    lam = 0.5 * (a + c) + np.sqrt(0.25 * (a - c) ** 2 + b * b)
    return float(math.sqrt(np.max(lam) / inputs.mass))


def integrate_model(
    kernel: ModelKernel,
    inputs: ModelInputs,
    y0: NDArray[np.float64],
    fs: float,
    n_out: int,
    decim: int,
    *,
    per_ball: bool = False,
    chunk: int = 4800,
    bound: float = 1.0,
    cell_average: bool = True,
    progress: Callable[[int], None] | None = None,
) -> RawRun:
    """Fixed-step RK4 integration of ``kernel`` from ``y0`` at ``t = 0``.

    Output every ``1/fs`` seconds (``n_out`` samples including ``t = 0``) with ``decim`` steps
    per sample. Runs in chunks of ``chunk`` samples; for table models the quasi-static solution
    is tabulated on the chunk's half-step grid first (compiled).

    Parameters
    ----------
    kernel : ModelKernel
        The model.
    inputs : ModelInputs
        Physical inputs.
    y0 : ndarray, shape (4,)
        Initial state [m, m, m/s, m/s].
    fs : float
        Output sample rate [Hz].
    n_out : int
        Number of output samples.
    decim : int
        RK4 steps per output sample.
    per_ball : bool
        Also output per-ball loads and deformations.
    chunk : int
        Output samples per chunk.
    bound : float
        Divergence guard on every state component (``|u|`` [m], ``|v|`` [m/s]).
    cell_average : bool
        Average the defect and fixed-zone indicators over each RK4 stage's quadrature cell
        (:func:`._balance.cell_halfwidth`), which resolves the instants a ball enters or leaves
        the defect to second order; ``False`` = point evaluation (first order).
    progress : callable, optional
        Called with the number of samples done after each chunk.
    """
    header = inputs.header(per_ball)
    na = n_aux(inputs, per_ball)
    dt = 1.0 / (fs * decim)
    h = 0.5 * dt
    header[bl.P_CELL] = 1.0 if cell_average else 0.0
    header[bl.P_HTAB] = h
    slip = np.zeros(0)
    if inputs.slip > 0.0 or inputs.jitter > 0.0:  # the slip table goes at the end of p
        slip, sdt = inputs.slip_table(n_out / fs)
        header[bl.P_SLIPN] = slip.size
        header[bl.P_SLIPDT] = sdt

    t_all = np.empty(n_out)
    y_all = np.empty((n_out, 4))
    a_all = np.empty((n_out, na))
    y = np.ascontiguousarray(y0, dtype=float).copy()
    res_max = 0.0
    ux = uy = math.nan
    i0 = 0
    while True:
        i1 = min(i0 + chunk, n_out - 1)
        m = i1 - i0 + 1
        t_start = i0 / fs
        header[bl.P_T0] = t_start
        header[bl.P_CT] = math.nan
        if kernel.needs_table:
            n_tab = 2 * (m - 1) * decim + 1
            times = t_start + h * np.arange(n_tab)
            table = np.empty((n_tab, bl.NCOL))
            res = np.empty(n_tab)
            ux, uy = call_compiled(
                bl.quasi_static_path, times, inputs.pack(header, slip), table, res, ux, uy
            )
            res_max = max(res_max, float(res.max()))
            p = inputs.pack(np.concatenate([header, table.ravel()]), slip)
            p[bl.P_T0] = t_start
            p[bl.P_HTAB] = h
            p[bl.P_NTAB] = n_tab
        else:
            p = inputs.pack(header, slip)
        tr = run_fixed(
            kernel.rhs,
            kernel.aux,
            y,
            p,
            dt=dt,
            n_out=m,
            decim=decim,
            n_aux=na,
            bound=bound,
            t0=t_start,
        )
        s = 0 if i0 == 0 else 1
        t_all[i0 + s : i1 + 1] = tr.t[s:]
        y_all[i0 + s : i1 + 1] = tr.y[s:]
        a_all[i0 + s : i1 + 1] = tr.aux[s:]
        y = tr.y[-1].copy()
        if progress is not None:
            progress(i1 + 1)
        if i1 >= n_out - 1:
            break
        i0 = i1
    return RawRun(t_all, y_all, a_all, dt, decim, "rk4", res_max, (n_out - 1) * decim)


def integrate_model_adaptive(
    kernel: ModelKernel,
    inputs: ModelInputs,
    y0: NDArray[np.float64],
    fs: float,
    n_out: int,
    *,
    per_ball: bool = False,
    rtol: float = 1e-9,
    atol: float = 1e-15,
    bound: float = 1.0,
) -> RawRun:
    """Dormand–Prince 5(4) integration with the exact (on-the-fly static solve) right-hand
    side, output at ``k / fs`` [s]; for checking the fixed-step results."""
    p = inputs.pack(inputs.header(per_ball))
    na = n_aux(inputs, per_ball)
    t_eval = np.arange(n_out) / fs
    tr = run_adaptive(
        kernel.rhs_exact,
        kernel.aux_exact,
        y0,
        p,
        t_eval,
        n_aux=na,
        rtol=rtol,
        atol=atol,
        h0=1e-7,
        hmax=1.0 / fs,
        bound=bound,
    )
    return RawRun(tr.t, tr.y, tr.aux, math.nan, 0, "dopri5", math.nan, tr.n_steps)
