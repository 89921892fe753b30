"""IAS: 3-DOF model of a cylindrical roller bearing with an outer-race spall (seed IAS, SPEC §3).

Han, Guo & Fan (J. Vib. Eng. 2025), "Dynamic modelling of the IAS disturbance of a cylindrical
roller bearing caused by an outer-race fault", eqs. (1)–(35). The inner ring and shaft have three
degrees of freedom, ``x``, ``y`` and the rotation ``theta``; the shaft is driven by a constant
motor torque ``M_z`` against a viscous torsional damping ``C_T`` and the bearing's resisting
torque, so the instantaneous angular speed (IAS) comes out of the torque balance.

Sign convention (one for the whole model, stated in ``docs/models.md``)
    ``x`` to the right, ``y`` up, roller azimuth ``phi`` from +x counter-clockwise (the seed's
    eqs. (3), (33)); the shaft turns counter-clockwise (``theta`` and ``theta'`` > 0), so the cage
    and rollers advance with ``phi``. The applied force on the inner ring is
    ``(Q_x, Q_y) = (F_x, -F_y)``: the seed's ``F_y`` pushes the shaft *down*, centring the load
    zone on ``phi = 1.5 pi`` as in its eq. (1); the spall sits at ``phi_os = 1.5 pi`` (bottom).
    Mapping to the project-wide azimuth ``psi`` (from +y towards +x): ``psi = pi/2 - phi``.

Model (each term with its seed equation)
    * roller ``k`` at ``phi_k = Phi_0 + 2 pi (k-1)/Z + rho theta`` with the cage ratio
      ``rho = (1 - D_c cos(alpha)/D_p)/2`` (eqs. (3)–(4) with the cage driven kinematically by the
      shaft angle, assumption (1) "no slip");
    * approach ``delta_k = x cos phi_k + y sin phi_k - c - gamma_k C_d(phi_k)`` (eq. (33)),
      ``gamma_k`` = 1 inside the spall (eq. (34)); spall profile ``C_d`` (eq. (18)) with
      ``H_m = r_c - sqrt(r_c^2 - (L_d/2)^2)`` (eq. (19)), ``Theta_os = arcsin(L_d/D_o)`` (eq. (20));
    * normal force ``N_k = K_t delta_k^n`` when ``delta_k > 0`` (eqs. (13), (35)), ``K_t`` from the
      seed's line-contact laws (:mod:`bearingsim.hertz_ias`) or Harris/Palmgren;
    * rolling resistance: ``b_n = mu r_c``, ``T_k = N_k b_n / r_c`` acting on the inner ring
      against its surface motion, resisting torque ``r_i T_k + b_n N_k`` (eqs. (14)–(17));
    * spall contact force ``F_T`` (eq. (30)) with the trailing-edge impact force ``F_os`` derived
      from eqs. (21)–(28) (:func:`impact_force`; the printed eq. (29) lacks the factor ``V_2``),
      applied to the inner ring along the roller's radius tilted by ``lambda`` against the
      rolling direction, and its torque ``M_T = (D_o/2) F_T sin(lambda - Theta_os)`` (eq. (31));
    * equations of motion (eq. (32)):
      ``m x'' = Q_x - C_s x' + f_x``, ``m y'' = Q_y - C_s y' + f_y``,
      ``I theta'' = M_z - C_T theta' - s (sum_k (r_i T_k + b_n N_k) + M_T)``, with ``f`` the sum of
      the contact, tangential and spall forces on the ring and ``s`` a regularised
      ``sign(theta')`` (``theta'/sqrt(theta'^2 + w_eps^2)``, ``w_eps`` = 0.01 rad/s): the seed
      assumes ``theta' > 0``; the regularisation only matters at standstill.

The compiled right-hand side is in :mod:`._kernel`: RK4 runs through its driver ``ias_rk4`` (the
shared loop :func:`bearingsim.dynamics.integrate._rk4_inline` with the right-hand side inlined),
Dormand–Prince through the shared adaptive kernel on the ``ias_rhs`` cfunc.
"""

from __future__ import annotations

import enum
import math
import time
from collections.abc import Callable
from dataclasses import asdict, dataclass, field
from typing import TYPE_CHECKING, Any

import numpy as np
from numpy.typing import NDArray
from scipy.constants import g as STANDARD_GRAVITY

from ..._version import __version__
from ...config import (
    IAS_INERTIA_KG_M2,
    SEED_IAS_FY_N,
    SEED_IAS_MASS_KG,
    SEED_IAS_RADIAL_DAMPING_N_S_M,
    SEED_IAS_ROLLING_RESISTANCE,
    SEED_IAS_SPALL_WIDTH_M,
    SEED_IAS_TORQUE_N_M,
    SEED_IAS_TORSIONAL_DAMPING_N_M_S,
    Solver,
)
from ...contact.hertz import element_stiffness
from ...contact.pereira import LINE_EXPONENT, seed_line_stiffness, seed_reference_load
from ...errors import ConfigError, check_positive, check_range
from ...geometry import CWRU_DEFECT_DEPTH_M, Defect, Race, RollerBearing, parse_enum
from ...load_distribution import STRIBECK_CONSTANT, radial_load_distribution
from ...signal.order import analysis_memory
from ..budget import F8, Budget, Estimate, check_budget
from ..integrate import Trajectory, run_adaptive, run_fixed
from ._kernel import (
    AUX_NAMES,
    N_AUX,
    P_C,
    P_COSLAM,
    P_CS,
    P_CT,
    P_DO,
    P_EPS,
    P_G,
    P_HM,
    P_I,
    P_INVI,
    P_INVM,
    P_KT,
    P_LAM,
    P_M,
    P_MC,
    P_MU,
    P_MZ,
    P_N,
    P_PHI0,
    P_PHIC,
    P_PHIO,
    P_PHIOS,
    P_QMAX,
    P_QMODE,
    P_QX,
    P_QY,
    P_RC,
    P_RHO,
    P_RI,
    P_SINLAM,
    P_SINLT,
    P_SPALL,
    P_TARM,
    P_THOS,
    P_TRIG,
    P_V1C,
    P_WEPS,
    P_Z,
    STATE_NAMES,
    ias_aux,
    ias_rhs,
    ias_rk4,
)

if TYPE_CHECKING:
    from .result import IasResult

__all__ = [
    "AUX_NAMES",
    "GRAVITY",
    "N_AUX",
    "OMEGA_EPS",
    "SEED_SPALL",
    "STATE_NAMES",
    "ContactLaw",
    "IasConstants",
    "IasParams",
    "IasResult",
    "SpallLoad",
    "check_spall_width",
    "check_step",
    "derive_constants",
    "ias_estimate",
    "impact_force",
    "initial_state",
    "max_spall_width",
    "pack_parameters",
    "simulate_ias",
]

#: gravity in the roller energy balance, seed IAS eq. (21): the standard g_n = 9.80665 m/s^2
#: (exact; scipy.constants.g) [m/s^2]
GRAVITY = STANDARD_GRAVITY
#: speed scale of the regularised sign of the shaft speed [rad/s]
OMEGA_EPS = 1e-2


class ContactLaw(enum.Enum):
    """Roller load–deflection constant ``K_t`` of ``N = K_t delta^(10/9)``."""

    #: seed IAS eqs. (5)–(12) (Pereira et al. 2011 laws, :mod:`bearingsim.hertz_ias`)
    SEED = "seed"
    #: Harris/Palmgren line contact (:func:`bearingsim.hertz.element_stiffness`)
    HARRIS = "harris"


class SpallLoad(enum.Enum):
    """Roller load ``Q(phi_k)`` that scales the spall contact force of seed IAS eq. (30)."""

    #: seed eqs. (1)–(2): ``Q_max = 4.37 F_r/Z`` and the Harris load-zone shape
    STRIBECK = "stribeck"
    #: the roller's instantaneous Hertz force without the spall drop, ``K_t (x cos + y sin - c)^n``
    DYNAMIC = "dynamic"


#: the seed's spall (seed IAS §3.1): 1 mm wide at the bottom of the outer race
SEED_SPALL = Defect(Race.OUTER, SEED_IAS_SPALL_WIDTH_M, CWRU_DEFECT_DEPTH_M, math.pi)

# ----------------------------------------------------------------------------- parameters


@dataclass(frozen=True)
class IasParams:
    """Inputs of the IAS model (SI). Defaults are the seed's case (seed IAS §3.1).

    Parameters
    ----------
    bearing : RollerBearing
        Cylindrical roller bearing (seed: ``NU204-ECP``).
    spall : Defect or None
        The outer-race spall: its ``width`` is ``L_d`` [m] (seed: 1 mm) and its ``angle`` the
        centre azimuth in the project convention [rad] (from +y towards +x; seed: ``pi``, the
        bottom, i.e. the seed's ``phi_os = 1.5 pi`` from +x); its ``depth`` is not used (the
        seed's roller drop, eq. (19), assumes the spall deeper than the drop). ``None`` = healthy
        bearing.
    fx, fy : float
        Radial load components [N]: ``Q_x = F_x``, ``Q_y = -F_y`` (``F_y`` downward; seed 0, 400).
    torque : float
        Motor torque ``M_z`` [N m] (seed 9.54).
    mass : float
        Inner ring + shaft mass m [kg] (seed 1.3).
    inertia : float
        Polar inertia I [kg m^2]. Not given by the seed; default: a 1.3 kg solid steel shaft of
        the 20 mm bore, ``m r^2/2 = 6.5e-5``.
    radial_damping : float
        ``C_s`` [N s/m] (seed 400).
    torsional_damping : float
        ``C_T`` [N m s/rad] (seed 1.52).
    rolling_resistance : float
        Rolling-resistance coefficient mu [-] (seed 0.0015, eq. (14)).
    contact_law : ContactLaw
        Seed eqs. (5)–(12) (default) or Harris/Palmgren.
    spall_load : SpallLoad
        Roller load in eq. (30): seed eqs. (1)–(2) (default) or the dynamic Hertz force.
    reference_load : float or None
        Roller load at which the seed contact stiffness is evaluated [N]; default ``F_r/Z``.
    first_roller_angle : float
        ``Phi_0`` [rad] (eq. (3); not given by the seed, 0).
    initial_displacement : tuple of float
        ``(x0, y0)`` [m] (seed 1e-9, 1e-9).
    initial_angle : float
        ``theta0`` [rad] (seed 1e-9).
    initial_speed : float
        ``theta'0`` [rad/s] (seed 0).
    """

    bearing: RollerBearing
    spall: Defect | None = SEED_SPALL
    fx: float = 0.0
    fy: float = SEED_IAS_FY_N
    torque: float = SEED_IAS_TORQUE_N_M
    mass: float = SEED_IAS_MASS_KG
    inertia: float = IAS_INERTIA_KG_M2
    radial_damping: float = SEED_IAS_RADIAL_DAMPING_N_S_M
    torsional_damping: float = SEED_IAS_TORSIONAL_DAMPING_N_M_S
    rolling_resistance: float = SEED_IAS_ROLLING_RESISTANCE
    contact_law: ContactLaw = ContactLaw.SEED
    spall_load: SpallLoad = SpallLoad.STRIBECK
    reference_load: float | None = None
    first_roller_angle: float = 0.0
    initial_displacement: tuple[float, float] = (1e-9, 1e-9)
    initial_angle: float = 1e-9
    initial_speed: float = 0.0

    def __post_init__(self) -> None:
        b = self.bearing
        if not isinstance(b, RollerBearing):
            raise ConfigError(
                f"bearing = {getattr(b, 'id', b)!r} is not a cylindrical roller "
                "bearing; the IAS model needs rollers"
            )
        s = object.__setattr__
        s(self, "contact_law", ContactLaw(self.contact_law))
        s(self, "spall_load", SpallLoad(self.spall_load))
        if self.spall is not None:
            if not isinstance(self.spall, Defect):
                raise ConfigError(f"spall = {self.spall!r} is not a Defect or None")
            if self.spall.race is not Race.OUTER:
                raise ConfigError(
                    f"spall race = {self.spall.race.value!r} is not modelled; valid: outer "
                    "(seed IAS models an outer-race spall)"
                )
            check_spall_width(b, self.spall.width)
        s(self, "fx", check_range("fx_n", self.fx, unit="N"))
        s(self, "fy", check_range("fy_n", self.fy, unit="N"))
        if math.hypot(self.fx, self.fy) == 0.0:
            raise ConfigError(
                "radial load = 0 N: the IAS model needs a radial load to form a "
                "load zone; valid range fy_n != 0 or fx_n != 0"
            )
        s(self, "torque", check_range("torque_n_m", self.torque, 0.0, unit="N m"))
        s(
            self,
            "initial_speed",
            check_range("initial_speed_rad_s", self.initial_speed, 0.0, unit="rad/s"),
        )
        if self.torque == 0.0 and self.initial_speed == 0.0:
            raise ConfigError(
                "torque_n_m = 0 N m with zero initial speed: the shaft cannot turn; "
                "valid range torque_n_m > 0, or give an initial speed > 0 (initial_rpm)"
            )
        for name, unit in (
            ("mass", "kg"),
            ("inertia", "kg m^2"),
            ("radial_damping", "N s/m"),
            ("torsional_damping", "N m s/rad"),
        ):
            s(self, name, check_positive(name, getattr(self, name), unit))
        s(
            self,
            "rolling_resistance",
            check_range("rolling_resistance", self.rolling_resistance, 0.0, 0.5),
        )
        if self.reference_load is not None:
            s(self, "reference_load", check_positive("reference_load_n", self.reference_load, "N"))
        s(
            self,
            "first_roller_angle",
            check_range("first_roller_angle_rad", self.first_roller_angle, unit="rad"),
        )
        x0, y0 = (float(v) for v in self.initial_displacement)
        s(
            self,
            "initial_displacement",
            (
                check_range("x0_m", x0, -1e-3, 1e-3, unit="m"),
                check_range("y0_m", y0, -1e-3, 1e-3, unit="m"),
            ),
        )
        s(self, "initial_angle", check_range("initial_angle_rad", self.initial_angle, unit="rad"))

    @property
    def radial_load(self) -> float:
        """``F_r = |(F_x, F_y)|`` [N]."""
        return math.hypot(self.fx, self.fy)

    @property
    def spall_width(self) -> float:
        """Spall width ``L_d`` [m]; 0 for a healthy bearing."""
        return 0.0 if self.spall is None else self.spall.width

    @property
    def spall_phi(self) -> float:
        """Spall centre ``phi_os`` in the model's frame (from +x counter-clockwise,
        ``phi = pi/2 - psi``) [rad], in ``[0, 2 pi)``."""
        if self.spall is None:
            return 0.0
        return (0.5 * math.pi - self.spall.angle) % (2.0 * math.pi)

    def as_dict(self) -> dict[str, Any]:
        """Plain-dict description (SI, bearing by id), for metadata."""
        d = asdict(self)
        d["bearing"] = self.bearing.id
        if self.spall is not None:
            d["spall"] = {
                "race": self.spall.race.value,
                "width": self.spall.width,
                "depth": self.spall.depth,
                "angle": self.spall.angle,
                "profile": self.spall.profile.value,
            }
        d["contact_law"] = self.contact_law.value
        d["spall_load"] = self.spall_load.value
        d["initial_displacement"] = list(self.initial_displacement)
        return d


def max_spall_width(bearing: RollerBearing) -> float:
    """Largest spall width [m] the model admits: the roller must bridge the spall
    (``L_d < D_c``, seed eq. (19)) and only one roller may be inside it at a time (``2 Theta_os``
    below the roller pitch, ``L_d < D_o sin(pi/Z)``)."""
    return min(
        bearing.element_diameter,
        bearing.outer_raceway_diameter * math.sin(math.pi / bearing.n_elements),
    )


def check_spall_width(bearing: RollerBearing, width: float) -> float:
    """Validate the spall width ``L_d`` [m] against :func:`max_spall_width`."""
    hi = max_spall_width(bearing)
    w = check_range("spall_width_m", width, 0.0, unit="m")
    pitch = bearing.outer_raceway_diameter * math.sin(math.pi / bearing.n_elements)
    if w >= hi:
        raise ConfigError(
            f"spall_width_m = {w:.6g} m is out of range; valid range [0, {hi:.6g}) m (the roller "
            f"of diameter {bearing.element_diameter:.6g} m must bridge the spall and the spall "
            f"must be narrower than the roller spacing {pitch:.6g} m)"
        )
    return w


# ------------------------------------------------------------------------ derived constants


@dataclass(frozen=True)
class IasConstants:
    """Quantities derived from :class:`IasParams` (SI).

    Attributes
    ----------
    k_total : float
        ``K_t`` [N/m^(10/9)] (seed eq. (12) or Harris).
    exponent : float
        Load–deflection exponent n = 10/9 [-].
    clearance : float
        Radial clearance ``c = P_d/2`` [m] (seed eq. (33)).
    cage_ratio : float
        ``rho = f_cage/f_shaft = (1 - D_c cos(alpha)/D_p)/2`` [-] (seed eq. (4)).
    bpfo_order : float
        ``Z rho`` [-] (seed eq. (36)).
    spall_half_angle : float
        ``Theta_os = arcsin(L_d/D_o)`` [rad] (seed eq. (20)).
    spall_depth : float
        ``H_m`` [m] (seed eq. (19)).
    impact_angle : float
        ``lambda = arcsin(L_d/(2 r_c))`` [rad], the roller's rotation about the leading edge until
        it touches the trailing edge (so that ``r_c (1 - cos lambda) = H_m``, seed eq. (21)).
    roller_mass : float
        ``m_c = rho_steel pi r_c^2 l`` [kg].
    q_max : float
        Stribeck ``4.37 F_r/(Z cos alpha)`` [N] (seed eq. (2)).
    epsilon, load_zone_half_angle : float
        Load-distribution factor [-] and half angle ``phi_o`` [rad] of seed eq. (1), from the static
        discrete-roller solution with the same ``K_t`` and clearance.
    load_zone_centre : float
        ``atan2(Q_y, Q_x)`` [rad] (1.5 pi for the seed).
    free_speed : float
        ``M_z / C_T`` [rad/s].
    max_rate : float
        Largest eigen-rate estimate of the linearised system [1/s] (stability check).
    """

    k_total: float
    exponent: float
    clearance: float
    cage_ratio: float
    bpfo_order: float
    spall_half_angle: float
    spall_depth: float
    impact_angle: float
    roller_mass: float
    q_max: float
    epsilon: float
    load_zone_half_angle: float
    load_zone_centre: float
    free_speed: float
    max_rate: float
    extra: dict[str, float] = field(default_factory=dict)


def impact_force(
    roller_mass: float,
    roller_radius: float,
    cage_speed: float,
    pitch_diameter: float,
    element_diameter_cos: float,
    spall_width: float,
    gravity: float = GRAVITY,
) -> float:
    """Trailing-edge impact force ``F_os`` [N] derived from seed IAS eqs. (21)–(28).

    Energy (eqs. (21)–(24)): ``3/4 m_c V_1^2 + m_c g r_c (1 - cos lambda) = 5/4 m_c V_2^2`` gives
    eq. (25) ``V_2 = [3/5 V_1^2 + 4/5 g r_c (1 - cos lambda)]^(1/2)`` with
    ``V_1 = w_cage (D_p^2 - D_c^2 cos^2 alpha) / (4 D_p)``. Momentum (eq. (26))
    ``F_os cos(lambda) t_lambda = m_c V_os``, ``V_os = V_2 sin(lambda)`` (eq. (27)),
    ``t_lambda = r_c sin(lambda) / (2 V_1)`` (eq. (28), ``V_out = 0``) give
    ``F_os = 2 m_c V_1 V_2 / (r_c cos lambda) = m_c w_cage (D_p^2 - D_c^2 cos^2 alpha) V_2 /
    (D_p sqrt(4 r_c^2 - L_d^2))``: the printed eq. (29) without the factor ``V_2`` [m/s], which is
    why it is not a force.

    Parameters
    ----------
    roller_mass : float
        m_c [kg].
    roller_radius : float
        r_c [m].
    cage_speed : float
        Cage angular speed [rad/s].
    pitch_diameter : float
        D_p [m].
    element_diameter_cos : float
        ``D_c cos(alpha)`` [m].
    spall_width : float
        L_d [m], ``< 2 r_c``.
    gravity : float
        g [m/s^2].
    """
    if spall_width <= 0.0:
        return 0.0
    lam = math.asin(spall_width / (2.0 * roller_radius))
    v1 = abs(cage_speed) * (pitch_diameter**2 - element_diameter_cos**2) / (4.0 * pitch_diameter)
    v2 = math.sqrt(0.6 * v1 * v1 + 0.8 * gravity * roller_radius * (1.0 - math.cos(lam)))
    return 2.0 * roller_mass * v1 * v2 / (roller_radius * math.cos(lam))


def derive_constants(params: IasParams) -> IasConstants:
    """Derived constants of the IAS model (see :class:`IasConstants`)."""
    b = params.bearing
    rc = 0.5 * b.element_diameter
    n = LINE_EXPONENT
    extra: dict[str, float] = {}
    if params.contact_law is ContactLaw.SEED:
        qref = params.reference_load or seed_reference_load(b, params.radial_load)
        st = seed_line_stiffness(b, qref)
        kt = st.k_total
        extra.update(reference_load=qref, k_inner_tangent=st.k_inner, k_outer_tangent=st.k_outer)
    else:
        kt, n = element_stiffness(b)
    c = 0.5 * b.diametral_clearance
    dcos = b.element_diameter * math.cos(b.contact_angle)
    rho = 0.5 * (1.0 - dcos / b.pitch_diameter)
    ld = params.spall_width
    do = b.outer_raceway_diameter
    th_os = math.asin(ld / do)  # seed eq. (20)
    hm = rc - math.sqrt(rc * rc - 0.25 * ld * ld)  # seed eq. (19)
    lam = math.asin(ld / (2.0 * rc))
    mc = b.material.density * math.pi * rc * rc * b.roller_length
    qx, qy = params.fx, -params.fy
    phic = math.atan2(qy, qx) % (2.0 * math.pi)
    # static discrete-roller solution (project convention psi = pi/2 - phi) for eq. (1)'s eps, phi_o
    ld0 = radial_load_distribution(
        b,
        qx,
        qy,
        0.0,
        first_element_angle=0.5 * math.pi - params.first_roller_angle,
        stiffness=kt,
        allow_overload=None,  # the scenario's load is checked where the run starts
    )
    eps = float(ld0.epsilon[0])
    phio = float(ld0.psi_l[0])
    qmax = STRIBECK_CONSTANT * params.radial_load / (b.n_elements * math.cos(b.contact_angle))
    dj = np.maximum(ld0.ball_deflections[0], 0.0)
    k_rad = float(np.sum(n * kt * dj ** (n - 1.0) * (dj > 0)))
    rate_r = math.sqrt(k_rad / params.mass) + params.radial_damping / params.mass
    rate_t = params.torsional_damping / params.inertia
    t_res = (b.inner_raceway_radius + rc) * params.rolling_resistance * float(ld0.ball_loads.sum())
    rate_reg = t_res / (OMEGA_EPS * params.inertia)
    extra.update(radial_stiffness=k_rad, static_normal_force_sum=float(ld0.ball_loads.sum()))
    return IasConstants(
        k_total=kt,
        exponent=n,
        clearance=c,
        cage_ratio=rho,
        bpfo_order=b.n_elements * rho,
        spall_half_angle=th_os,
        spall_depth=hm,
        impact_angle=lam,
        roller_mass=mc,
        q_max=qmax,
        epsilon=eps,
        load_zone_half_angle=phio,
        load_zone_centre=phic,
        free_speed=params.torque / params.torsional_damping,
        max_rate=max(rate_r, rate_t, rate_reg),
        extra=extra,
    )


def pack_parameters(params: IasParams, const: IasConstants | None = None) -> NDArray[np.float64]:
    """Flat parameter vector of :func:`ias_rhs` (offsets ``P_*`` in this module)."""
    k = const or derive_constants(params)
    b = params.bearing
    Z = b.n_elements
    p = np.zeros(P_TRIG + 2 * Z)
    p[P_M], p[P_I], p[P_CS], p[P_CT] = (
        params.mass,
        params.inertia,
        params.radial_damping,
        params.torsional_damping,
    )
    p[P_QX], p[P_QY], p[P_MZ] = params.fx, -params.fy, params.torque
    p[P_KT], p[P_N], p[P_C], p[P_Z] = k.k_total, k.exponent, k.clearance, Z
    p[P_RHO], p[P_PHI0] = k.cage_ratio, params.first_roller_angle
    p[P_RI], p[P_RC], p[P_MU] = (
        b.inner_raceway_radius,
        0.5 * b.element_diameter,
        params.rolling_resistance,
    )
    p[P_PHIOS], p[P_THOS], p[P_HM], p[P_LAM] = (
        params.spall_phi,
        k.spall_half_angle,
        k.spall_depth,
        k.impact_angle,
    )
    p[P_DO], p[P_MC] = b.outer_raceway_diameter, k.roller_mass
    dcos = b.element_diameter * math.cos(b.contact_angle)
    p[P_V1C] = (b.pitch_diameter**2 - dcos**2) / (4.0 * b.pitch_diameter)
    p[P_G] = GRAVITY
    p[P_QMODE] = 0.0 if params.spall_load is SpallLoad.STRIBECK else 1.0
    p[P_QMAX], p[P_EPS], p[P_PHIO], p[P_PHIC] = (
        k.q_max,
        k.epsilon,
        k.load_zone_half_angle,
        k.load_zone_centre,
    )
    p[P_SPALL] = 1.0 if params.spall_width > 0.0 else 0.0
    p[P_WEPS] = OMEGA_EPS
    p[P_COSLAM], p[P_SINLAM] = math.cos(k.impact_angle), math.sin(k.impact_angle)
    p[P_SINLT] = math.sin(k.impact_angle - k.spall_half_angle)
    p[P_INVM], p[P_INVI] = 1.0 / params.mass, 1.0 / params.inertia
    p[P_TARM] = params.rolling_resistance * (p[P_RI] + p[P_RC])  # seed eqs. (14)-(17)
    ang = 2.0 * np.pi * np.arange(Z) / Z
    p[P_TRIG : P_TRIG + Z] = np.cos(ang)
    p[P_TRIG + Z : P_TRIG + 2 * Z] = np.sin(ang)
    return p


def initial_state(params: IasParams) -> NDArray[np.float64]:
    """``(x0, y0, theta0, 0, 0, theta'0)`` (seed IAS §3.1)."""
    x0, y0 = params.initial_displacement
    return np.array([x0, y0, params.initial_angle, 0.0, 0.0, params.initial_speed])


# ------------------------------------------------------------------------------- simulation


def check_step(params: IasParams, dt: float, const: IasConstants | None = None) -> float:
    """Validate the fixed step ``dt`` [s]: positive and below ``1/max_rate`` (about a third of
    RK4's stability limit ``2.8/max_rate`` for the stiffest linearised mode)."""
    dt = check_positive("dt_s", dt, "s")
    k = const or derive_constants(params)
    hi = 1.0 / k.max_rate
    if dt > hi:
        raise ConfigError(
            f"dt_s = {dt:.6g} s is too large for stability; valid range (0, {hi:.3g}] s "
            f"(fastest linearised rate {k.max_rate:.4g} 1/s)"
        )
    return dt


def _rk4_chunked(p, y0, dt: float, n_out: int, decim: int, progress) -> Trajectory:
    """RK4 of the IAS model in pieces of about :data:`MAX_CHUNK_STEPS` steps, bit-identical to
    one call (same ``t0 = 0``, the step count carried in ``k0``)."""
    per = max(1, MAX_CHUNK_STEPS // decim)  # output intervals per piece
    t_all = np.empty(n_out)
    y_all = np.empty((n_out, len(STATE_NAMES)))
    a_all = np.empty((n_out, N_AUX))
    y = y0
    i = 0
    while True:
        m = min(per, n_out - 1 - i) + 1  # samples of this piece, its first = the last done
        tr = run_fixed(ias_rhs, ias_aux, y, p, dt=dt, n_out=m, decim=decim, n_aux=N_AUX,
                       bound=1e9, driver=ias_rk4, k0=i * decim)  # fmt: skip
        t_all[i : i + m] = tr.t
        y_all[i : i + m] = tr.y
        a_all[i : i + m] = tr.aux
        y = tr.y[-1].copy()
        i += m - 1
        if progress is not None:
            progress(i + 1)
        if i >= n_out - 1:
            break
    return Trajectory(t_all, y_all, a_all, "rk4", (n_out - 1) * decim)


#: largest number of RK4 steps in one compiled call of :func:`simulate_ias` [-]: the run is split
#: into pieces of about this many steps (bit-identical to one call, see
#: :func:`bearingsim.dynamics.integrate._rk4_inline`), between which progress is reported and
#: Ctrl-C is seen; 2^22 steps take about a second
MAX_CHUNK_STEPS = 1 << 22


def ias_estimate(n_out: int, decim: int) -> Estimate:
    """Memory [B] and RK4 steps of an IAS run with ``n_out`` output samples of ``decim`` steps:
    times, states and auxiliary outputs and their copy in the result's dataset, then the
    angle-domain analysis (:func:`bearingsim.signal.order.analysis_memory`: at most twice as many
    samples in angle as in time, the resolution being the power of two at least the output's
    samples per revolution, on a grid at most twice finer, and the zero-padded order
    spectrum)."""
    per_sample = (1 + len(STATE_NAMES) + N_AUX) * F8
    what = f"ias: {n_out} samples x {decim} RK4 steps"
    memory = 2.0 * n_out * per_sample + analysis_memory(2.0 * n_out, 2)
    return Estimate(what, memory, float(n_out - 1) * decim)


def _grid(duration: float, dt: float, rate: float) -> tuple[int, int, int]:
    """``(decim, n_steps, n_out)`` of :func:`simulate_ias`; counts far beyond any budget are
    capped (:data:`MAX_COUNT`) so that they stay exact integers."""
    decim = max(1, int(round(min(1.0 / (rate * dt), MAX_COUNT))))
    n_steps = int(round(min(duration / dt, MAX_COUNT)))
    if n_steps < decim:
        raise ConfigError(
            f"duration_s = {duration:.6g} s is shorter than one output interval "
            f"{decim * dt:.3g} s; valid range [{decim * dt:.3g}, inf) s"
        )
    return decim, n_steps, -(-n_steps // decim) + 1  # covers at least ``duration``


#: count beyond which steps or samples are counted as this many (far beyond any budget) [-]
MAX_COUNT = float(2**62)


def simulate_ias(
    params: IasParams,
    duration: float = 10.0,
    dt: float = 1e-6,
    output_rate: float = 48_000.0,
    method: Solver | str = Solver.RK4,
    rtol: float = 1e-9,
    atol: float = 1e-13,
    progress: Callable[[int], None] | None = None,
    budget: Budget | None = None,
) -> IasResult:
    """Integrate the IAS model of seed IAS eq. (32) (seed: RK4, dt = 1e-6 s, 10 s).

    Parameters
    ----------
    params : IasParams
        Model inputs.
    duration : float
        Simulated time [s].
    dt : float
        RK4 step [s] (also the output grid unit for ``dopri5``).
    output_rate : float
        Requested output sample rate [Hz]; the output interval is ``decim dt`` with
        ``decim = max(1, round(1/(output_rate dt)))``; the run covers at least ``duration``
        (up to ``decim - 1`` extra steps).
    method : Solver or {"rk4", "dopri5"}
        Fixed-step RK4 (the seed's solver) or adaptive Dormand–Prince 5(4) as a check.
    rtol, atol : float
        ``dopri5`` tolerances [-], [state units].
    progress : callable, optional
        Called with the number of output samples done after each piece of
        :data:`MAX_CHUNK_STEPS` steps (RK4; ``dopri5`` runs in one call).
    budget : Budget, optional
        Memory [B] and step limits (:class:`bearingsim.dynamics.budget.Budget`): the run is
        refused before it starts when :func:`ias_estimate` exceeds them.
    """
    duration = check_positive("duration_s", duration, "s")
    rate = check_positive("output_rate_hz", output_rate, "Hz")
    const = derive_constants(params)
    dt = check_step(params, dt, const)
    decim, n_steps, n_out = _grid(duration, dt, rate)
    method = parse_enum(Solver, method, "solver").value
    check_budget(ias_estimate(n_out, decim), budget)
    p = pack_parameters(params, const)
    y0 = initial_state(params)
    t0 = time.perf_counter()
    c0 = time.process_time()
    if method == "rk4":
        tr = _rk4_chunked(p, y0, dt, n_out, decim, progress)
    elif method == "dopri5":
        t_eval = np.arange(n_out) * (decim * dt)
        tr = run_adaptive(
            ias_rhs,
            ias_aux,
            y0,
            p,
            t_eval,
            n_aux=N_AUX,
            rtol=rtol,
            atol=atol,
            hmax=decim * dt,
            bound=1e9,
        )
        if progress is not None:
            progress(n_out)
    else:
        raise ConfigError(f"method = {method!r} is not valid; valid: 'rk4', 'dopri5'")
    wall = time.perf_counter() - t0
    cpu = time.process_time() - c0
    from .result import IasResult

    # the output interval decim dt is 1/rate when the grid meets the requested rate (as
    # run_ias builds it: dt = 1/(rate decim)); 1/(decim dt) then differs from rate by the
    # rounding of dt alone (49999.99999999999 for 50 kHz), so the rate itself is reported
    out_rate = 1.0 / (decim * dt)
    if math.isclose(out_rate, rate, rel_tol=1e-12):
        out_rate = rate
    solver = {
        "method": method,
        "dt_s": dt,
        "decim": decim,
        "n_steps": tr.n_steps,
        "output_rate_hz": out_rate,
        "duration_s": duration,
        "wall_s": wall,
        "cpu_s": cpu,
    }
    if method == "dopri5":
        solver.update(rtol=rtol, atol=atol)
    return IasResult(tr.t, tr.y, tr.aux, params, const, solver, __version__)


def __getattr__(name: str):
    if name == "IasResult":  # re-export without a circular import
        from .result import IasResult

        return IasResult
    raise AttributeError(name)
