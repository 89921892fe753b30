"""Inputs of the bearing–rotor–housing model (seed ROTOR, Liu et al. 2021; SPEC §2).

Frozen, validated dataclasses in SI units: :class:`Shaft`, :class:`Armature` (the rotor mass
spread over ``n`` disks), :class:`BearingSupport` (a ball bearing with an optional
:class:`~bearingsim.geometry.Defect`), :class:`Housing` and the whole :class:`RotorConfig`;
:func:`cwru_rotor_config` builds the seed's CWRU case. Every bad value raises a one-line
:class:`~bearingsim.errors.ConfigError` naming the field, the value and the valid range.
"""

from __future__ import annotations

import dataclasses
import enum
import math
from dataclasses import dataclass, field
from typing import Any

import numpy as np
from scipy.constants import g as STANDARD_GRAVITY

from ...catalog import get_bearing
from ...config import (
    CONTACT_DAMPING_N_S_M,
    DEFAULT_RPM,
    HOUSING_DAMPING_N_S_M,
    HOUSING_MASS_KG,
    HOUSING_STIFFNESS_N_M,
    check_ball_spread,
    check_mount,
    check_roughness,
)
from ...errors import ConfigError, check_positive, check_range
from ...geometry import (
    BallBearing,
    Defect,
    DefectProfile,
    KinematicFrequencies,
    characteristic_frequencies,
    check_defect_depth,
    check_pit_depth,
    parse_enum,
)
from ...materials import DENSITY_RANGE, YOUNGS_MODULUS_RANGE

__all__ = [
    "MASS_RATIO_MIN",
    "Armature",
    "AUX_NAMES",
    "BAND_TUNED_HOUSING",
    "BearingSupport",
    "catalogue_bearing",
    "config_summary",
    "cwru_rotor_config",
    "default_housing",
    "ENDS",
    "G0",
    "Housing",
    "housing_from_frequency",
    "RotorConfig",
    "SEED_DISK_DIAMETER_M",
    "SEED_ROTOR_MASS_KG",
    "SEED_SHAFT_DIAMETER_M",
    "SEED_SHAFT_E_PA",
    "SEED_SHAFT_LENGTH_M",
    "SEED_SHAFT_MASS_KG",
    "Shaft",
    "ShaftMassModel",
]

#: seed ROTOR table 2 (CWRU motor): shaft mass, rotor (armature) mass [kg], shaft length,
#: shaft diameter, disk diameter [m], shaft modulus [Pa]
SEED_SHAFT_MASS_KG = 0.68
SEED_ROTOR_MASS_KG = 1.361
SEED_SHAFT_LENGTH_M = 203.2e-3
SEED_SHAFT_DIAMETER_M = 12.53e-3
SEED_DISK_DIAMETER_M = 46.07e-3
SEED_SHAFT_E_PA = 206e9
#: smallest ratio of the lightest to the heaviest lumped mass of the rotor (a shaft half, a
#: disk) [-]: below it the mass matrix is singular to double precision (its condition number
#: exceeds ~1e9 x the stiffness spread) and the eigensolvers fail (Hypothesis found a 1e-300 kg
#: armature); a numerical limit, far beyond any real rotor
MASS_RATIO_MIN = 1e-9
#: standard acceleration of gravity g_n = 9.80665 m/s^2 (exact; scipy.constants.g) [m/s^2]
G0 = STANDARD_GRAVITY

AUX_NAMES = ("acc_x_DE", "acc_y_DE", "acc_x_FE", "acc_y_FE")
ENDS = ("DE", "FE")


class ShaftMassModel(enum.Enum):
    """How the shaft's own mass enters: ``LUMPED`` = half at each bearing on a massless beam
    (seed ROTOR eq. 2); ``DISTRIBUTED`` = consistent beam mass and rotary inertia."""

    LUMPED = "lumped"
    DISTRIBUTED = "distributed"


@dataclass(frozen=True)
class BearingSupport:
    """One ball bearing of the rotor.

    Parameters
    ----------
    bearing : BallBearing
        Geometry and material; the inner and outer Hertz constants come from
        :func:`bearingsim.hertz.ball_contact`.
    fault : Defect or None
        Local raceway defect (its ``angle`` is the centre azimuth at t = 0; None = healthy).
    contact_damping : float
        Linear damping of each ball–race contact, acting along the compression while in
        contact [N s/m] (seed ROTOR eq. 11 ``C_v``; value not given in the seed).
    first_ball_angle : float
        Azimuth of ball 1 at t = 0 [rad].
    ball_density : float or None
        Ball density [kg/m^3] (default: the bearing material's).
    contact_roughness : float
        Composite RMS roughness of the ball–race contacts [m]: the Hertz load is averaged over
        it (:mod:`bearingsim.contact.rough`), so a ball takes up load over a few roughnesses
        instead of with Hertz's singular onset; 0 = Hertz (seed ROTOR eq. 10).
    """

    bearing: BallBearing
    fault: Defect | None = None
    contact_damping: float = CONTACT_DAMPING_N_S_M
    first_ball_angle: float = 0.0
    ball_density: float | None = None
    contact_roughness: float = 0.0

    def __post_init__(self) -> None:
        if not isinstance(self.bearing, BallBearing):
            raise ConfigError(
                f"bearing = {getattr(self.bearing, 'id', self.bearing)!r} is not a ball "
                "bearing; the rotor model needs ball bearings"
            )
        from ..ring.base import check_no_contact_angle

        check_no_contact_angle(self.bearing, "rotor model's bearings")
        check_range("contact_damping_n_s_per_m", self.contact_damping, 0.0, unit="N s/m")
        check_roughness(self.contact_roughness)
        check_range("first_ball_angle_rad", self.first_ball_angle, unit="rad")
        if self.ball_density is not None:
            check_positive("ball_density_kg_m3", self.ball_density, "kg/m^3")
        if self.fault is not None and self.fault.width >= self.bearing.element_diameter:
            raise ConfigError(
                f"defect_width_m = {self.fault.width:.6g} m is out of range; valid range "
                f"(0, {self.bearing.element_diameter:.6g}) m (the ball must span the defect)"
            )
        if self.fault is not None:
            check_defect_depth(self.bearing, self.fault)
            if self.fault.profile is DefectProfile.PIT:
                check_pit_depth(self.bearing, self.fault)

    @property
    def ball_mass(self) -> float:
        """Ball mass ``rho pi d^3 / 6`` [kg]."""
        rho = self.ball_density or self.bearing.material.density
        return rho * math.pi * self.bearing.element_diameter**3 / 6.0


@dataclass(frozen=True)
class Housing:
    """Bearing housing: a rigid mass on linear springs and dampers to the base in X and Y.

    Parameters
    ----------
    mass : float
        Housing mass m_h [kg] (the outer ring moves with it).
    stiffness_x, stiffness_y : float
        Mount stiffness [N/m].
    damping_x, damping_y : float
        Mount damping [N s/m].
    """

    mass: float
    stiffness_x: float
    stiffness_y: float
    damping_x: float
    damping_y: float

    def __post_init__(self) -> None:
        check_positive("housing_mass_kg", self.mass, "kg")
        check_positive("housing_stiffness_x_n_m", self.stiffness_x, "N/m")
        check_positive("housing_stiffness_y_n_m", self.stiffness_y, "N/m")
        check_mount(self.stiffness_x, self.mass, "housing_stiffness_x_n_m")
        check_mount(self.stiffness_y, self.mass, "housing_stiffness_y_n_m")
        check_range("housing_damping_x_n_s_m", self.damping_x, 0.0, unit="N s/m")
        check_range("housing_damping_y_n_s_m", self.damping_y, 0.0, unit="N s/m")

    @property
    def natural_frequency_hz(self) -> tuple[float, float]:
        """Uncoupled mount frequencies ``sqrt(k/m)/(2 pi)`` in X and Y [Hz]."""
        return tuple(math.sqrt(k / self.mass) / (2 * math.pi) for k in
                     (self.stiffness_x, self.stiffness_y))  # fmt: skip


#: An alternative that is *not* from the literature: a 1 kg end shield whose mount alone rings
#: at 3.3 kHz with 5 % damping, chosen from the measured resonance band of CWRU record 132
#: (2.5–3.5 kHz, PSD maximum 3.36 kHz). Kept for comparison in the report (docs/validation.md);
#: build it with ``housing_from_frequency(*BAND_TUNED_HOUSING)``.
BAND_TUNED_HOUSING = (1.0, 3300.0, 0.05)


def default_housing(
    mass: float = HOUSING_MASS_KG,
    stiffness: float = HOUSING_STIFFNESS_N_M,
    damping: float = HOUSING_DAMPING_N_S_M,
) -> Housing:
    """Isotropic housing: ``mass`` [kg] on a mount of ``stiffness`` [N/m] and ``damping``
    [N s/m] in X and Y (defaults: Sawalhi & Randall 2008 pedestal as used for the CWRU rig by
    Ruan et al. 2022)."""
    return Housing(mass, stiffness, stiffness, damping, damping)


def housing_from_frequency(mass: float, frequency_hz: float, damping_ratio: float) -> Housing:
    """Isotropic housing of ``mass`` [kg] whose mount alone resonates at ``frequency_hz`` [Hz]
    with damping ratio ``damping_ratio`` [-]: ``k = m w^2``, ``c = 2 zeta m w``."""
    m = check_positive("housing_mass_kg", mass, "kg")
    w = 2 * math.pi * check_positive("housing_frequency_hz", frequency_hz, "Hz")
    z = check_range("housing_damping_ratio", damping_ratio, 0.0, unit="")
    return Housing(m, m * w * w, m * w * w, 2 * z * m * w, 2 * z * m * w)


@dataclass(frozen=True)
class Shaft:
    """Uniform flexible shaft between the two bearings (bearings at z = 0 and z = length).

    Parameters
    ----------
    length : float
        Distance between the bearings [m] (seed table 2: 203.2 mm).
    diameter : float
        Diameter [m] (12.53 mm).
    youngs_modulus : float
        E [Pa] (206 GPa).
    mass : float
        Shaft mass [kg] (0.68 kg).
    mass_model : ShaftMassModel
        ``LUMPED`` (seed: half the mass at each bearing, massless beam) or ``DISTRIBUTED``.
    """

    length: float = SEED_SHAFT_LENGTH_M
    diameter: float = SEED_SHAFT_DIAMETER_M
    youngs_modulus: float = SEED_SHAFT_E_PA
    mass: float = SEED_SHAFT_MASS_KG
    mass_model: ShaftMassModel | str = ShaftMassModel.LUMPED

    def __post_init__(self) -> None:
        check_positive("shaft_length_m", self.length, "m")
        check_positive("shaft_diameter_m", self.diameter, "m")
        check_range(
            "shaft_youngs_modulus_pa", self.youngs_modulus, *YOUNGS_MODULUS_RANGE, unit="Pa"
        )
        check_positive("shaft_mass_kg", self.mass, "kg")
        object.__setattr__(
            self, "mass_model", parse_enum(ShaftMassModel, self.mass_model, "shaft_mass_model")
        )

    @property
    def ei(self) -> float:
        """Bending stiffness E pi d^4 / 64 [N m^2]."""
        return self.youngs_modulus * math.pi * self.diameter**4 / 64.0


@dataclass(frozen=True)
class Armature:
    """The rotor (armature) mass, spread over ``n_disks`` rigid disks or distributed.

    Parameters
    ----------
    mass : float
        Total armature mass [kg] (seed table 2: 1.361 kg).
    diameter : float
        Disk diameter [m] (46.07 mm).
    n_disks : int
        Number of equal disks (ignored when ``distributed``).
    positions : tuple of float or None
        Disk positions from the DE bearing [m], one per disk, strictly increasing and strictly
        inside (0, shaft length) (checked by :class:`RotorConfig`); default equally spaced
        ``L i / (n + 1)``.
    density : float
        Density used to infer the armature length ``m / (rho pi (D^2 - d_shaft^2)/4)`` [kg/m^3];
        each disk is the slice ``length / n`` thick (this sets its diametral inertia).
    distributed : bool
        Spread the mass uniformly along the whole shaft instead (the limit of many equally
        spaced disks; the "converged FE limit" of the disk study).
    """

    mass: float = SEED_ROTOR_MASS_KG
    diameter: float = SEED_DISK_DIAMETER_M
    n_disks: int = 1
    positions: tuple[float, ...] | None = None
    density: float = 7850.0
    distributed: bool = False

    def __post_init__(self) -> None:
        check_positive("rotor_mass_kg", self.mass, "kg")
        check_positive("disk_diameter_m", self.diameter, "m")
        check_range("rotor_density_kg_m3", self.density, *DENSITY_RANGE, unit="kg/m^3")
        n = self.n_disks
        if isinstance(n, bool) or not isinstance(n, int | np.integer) or n < 1:
            raise ConfigError(f"n_disks = {n!r} is out of range; valid range [1, inf) integer")
        if self.positions is not None:
            try:
                pos = tuple(float(x) for x in self.positions)
            except (TypeError, ValueError):
                raise ConfigError(
                    f"disk_positions_m = {self.positions!r} is invalid; valid: a list of positions "
                    "[m], one per disk"
                ) from None
            if len(pos) != n:
                raise ConfigError(
                    f"n_disks = {n} and disk_positions_m = {_fmt_positions(pos)} m "
                    f"({len(pos)} positions) disagree; valid: one position per disk (n_disks = "
                    f"{len(pos)} for these positions)"
                )
            object.__setattr__(self, "positions", pos)


@dataclass(frozen=True)
class RotorConfig:
    """Every input of the bearing–rotor–housing model (SI units).

    Parameters
    ----------
    de, fe : BearingSupport
        Drive-end (z = 0) and fan-end (z = L) bearings.
    housing_de, housing_fe : Housing
        The two housings.
    shaft : Shaft
        Shaft data.
    armature : Armature
        Rotor mass distribution.
    speed_rpm : float
        Shaft speed [r/min] (> 0).
    gravity : bool
        Apply gravity (-y) to every mass.
    unbalance : float
        Static unbalance m e of the armature [kg m], at the armature's centre disk(s) (0 = none).
    unbalance_phase : float
        Azimuth of the unbalance at t = 0 [rad].
    bearing_loads : tuple
        Extra constant forces on the shaft at the DE and FE bearing nodes ``((fx, fy), (fx,
        fy))`` [N] (e.g. a belt or coupling load; 0 by default).
    n_elements : int or None
        Minimum number of beam elements (default ``max(16, n_disks + 1)``); at least one per
        interval between disks and bearings.
    mode_cutoff_hz : float or None
        Highest fixed-interface rotor mode kept by the Craig–Bampton reduction [Hz] (default
        the output sample rate, i.e. twice the highest output frequency).
    shaft_damping_ratio : float
        Stiffness-proportional rotor damping: ratio of the first fixed-interface mode [-].
    disk_damping : float
        Absolute damping on each disk's x and y (seed ROTOR eq. 3 ``C_disk``) [N s/m].
    ball_diameter_spread : float
        Largest minus smallest ball diameter in each bearing [m] (ISO 3290-1 lot variation;
        0 = identical balls), drawn per bearing from ``SeedSequence([ball_seed, 2, end])``
        (end 0 DE, 1 FE; :mod:`bearingsim.dynamics.ballset`).
    ball_seed : int
        Seed of the ball diameters.
    ball_inertia : bool
        True (default, the seed's model): each ball is a mass with a radial degree of freedom
        between its two Hertz contacts. False: quasi-static (massless) balls, the two contacts
        in series as in the ring models — the ball's radial mode (34–42 kHz for the CWRU
        bearings) and its centrifugal and weight forces are dropped, which lets the step grow
        3x (valid while that mode lies well above the output band; docs/models.md, ROTOR).
    axial_load : float
        Axial force each bearing carries [N] (a wave spring's preload passes through the shaft
        to both; 0 = none). The balls then run at the contact angles of the Jones equilibrium
        of the bearing's radial and axial load (:mod:`bearingsim.quasistatic.jones`, tilts
        held), as in the ring models' DEM. Needs quasi-static balls (``ball_inertia`` False).
    """

    de: BearingSupport
    fe: BearingSupport
    housing_de: Housing = field(default_factory=default_housing)
    housing_fe: Housing = field(default_factory=default_housing)
    shaft: Shaft = field(default_factory=Shaft)
    armature: Armature = field(default_factory=Armature)
    speed_rpm: float = DEFAULT_RPM
    gravity: bool = True
    unbalance: float = 0.0
    unbalance_phase: float = 0.0
    bearing_loads: tuple[tuple[float, float], tuple[float, float]] = ((0.0, 0.0), (0.0, 0.0))
    n_elements: int | None = None
    mode_cutoff_hz: float | None = None
    shaft_damping_ratio: float = 0.02
    disk_damping: float = 0.0
    ball_diameter_spread: float = 0.0
    ball_seed: int = 0
    ball_inertia: bool = True
    axial_load: float = 0.0

    def __post_init__(self) -> None:
        if not isinstance(self.ball_inertia, bool | np.bool_):
            raise ConfigError(
                f"ball_inertia = {self.ball_inertia!r} is not a boolean; valid: true or false"
            )
        check_range("axial_load_n", self.axial_load, 0.0, unit="N")
        if self.axial_load > 0.0 and self.ball_inertia:
            raise ConfigError(
                f"axial_load_n = {self.axial_load:g} N needs quasi-static balls (ball_inertia = "
                "false, --quasi-static-balls): the balls with masses move radially only; valid "
                "with ball masses: 0"
            )
        check_positive("speed_rpm", self.speed_rpm, "r/min")
        check_ball_spread(self.ball_diameter_spread)
        check_range("unbalance_kg_m", self.unbalance, 0.0, unit="kg m")
        check_range("unbalance_phase_rad", self.unbalance_phase, unit="rad")
        check_range("shaft_damping_ratio", self.shaft_damping_ratio, 0.0, 1.0)
        check_range("disk_damping_n_s_per_m", self.disk_damping, 0.0, unit="N s/m")
        if self.mode_cutoff_hz is not None:
            check_positive("mode_cutoff_hz", self.mode_cutoff_hz, "Hz")
        for fx, fy in self.bearing_loads:
            check_range("bearing_load_n", fx, unit="N")
            check_range("bearing_load_n", fy, unit="N")
        L = self.shaft.length
        widths = [sup.bearing.width for sup in (self.de, self.fe)]
        if all(w is not None for w in widths) and L < 0.5 * sum(widths):
            # the bearings sit at z = 0 and z = L (their centres): they cannot overlap
            raise ConfigError(
                f"shaft_length_m = {L:.6g} m is shorter than half the widths of the two bearings "
                f"({widths[0]:.6g} m and {widths[1]:.6g} m), which would overlap; valid range "
                f"[{0.5 * sum(widths):.6g}, inf) m"
            )
        self._check_geometry()
        given = () if self.armature.distributed else (self.armature.positions or ())
        for z in given:  # equally spaced positions (the default) are inside and distinct
            check_range("disk_position_m", z, 0.0, L, lo_open=True, hi_open=True, unit="m")
        for a, b in zip(given[:-1], given[1:], strict=True):
            # 1e-12 L: the mesh merges nodes closer than that (.fe.mesh_nodes)
            if not b - a > 1e-12 * L:
                raise ConfigError(
                    f"disk_positions_m = {_fmt_positions(given)} m is not strictly increasing "
                    f"({b:.6g} m follows {a:.6g} m); valid: distinct positions in increasing "
                    f"order within (0, {L:.6g}) m"
                )
        n_min = (0 if self.armature.distributed else self.armature.n_disks) + 1
        if self.n_elements is not None:
            ne = self.n_elements
            if isinstance(ne, bool) or not isinstance(ne, int | np.integer) or ne < n_min:
                raise ConfigError(
                    f"n_elements = {ne!r} is too few; valid range [{n_min}, inf) (one element "
                    f"at least between consecutive disks and bearings)"
                )

    def _check_geometry(self) -> None:
        """The shaft is a slender beam and the armature fits on it between the bearings.

        The shaft is an Euler–Bernoulli (Rayleigh) beam, which neglects shear: it needs a shaft
        longer than it is thick (``L > d``; at ``L/d`` near 1 the beam model is already far off).
        The lumped masses (the shaft's halves, each disk) lie within :data:`MASS_RATIO_MIN` of each
        other, or the mass matrix is numerically singular. The armature is a steel annulus on the
        shaft: its outer diameter must exceed the shaft's,
        and its length ``m / (rho pi (D^2 - d^2) / 4)`` (the same length that sets the disks'
        inertia) must fit between the bearings (``<= L``).
        """
        sh, arm = self.shaft, self.armature
        if not sh.length > sh.diameter:
            raise ConfigError(
                f"shaft_length_m = {sh.length:.6g} m is not longer than the shaft diameter "
                f"{sh.diameter:.6g} m: the beam model needs a slender shaft; valid range "
                f"({sh.diameter:.6g}, inf) m"
            )
        if not arm.diameter > sh.diameter:
            raise ConfigError(
                f"disk_diameter_m = {arm.diameter:.6g} m is not larger than the shaft diameter "
                f"{sh.diameter:.6g} m; valid range ({sh.diameter:.6g}, inf) m"
            )
        masses = {"shaft_mass_kg / 2": 0.5 * sh.mass}
        if not arm.distributed:
            masses[f"rotor_mass_kg / {arm.n_disks} disks"] = arm.mass / arm.n_disks
        lo, hi = min(masses.items(), key=lambda kv: kv[1]), max(masses.values())
        if not lo[1] >= MASS_RATIO_MIN * hi:
            raise ConfigError(
                f"{lo[0]} = {lo[1]:.6g} kg is {lo[1] / hi:.3g} times the heaviest lumped mass "
                f"{hi:.6g} kg: the mass matrix is singular in double precision; valid: a ratio "
                f"of at least {MASS_RATIO_MIN:g}"
            )
        length = self.armature_length
        if not length <= sh.length:
            m_max = sh.length * arm.mass / length
            raise ConfigError(
                f"rotor_mass_kg = {arm.mass:.6g} kg makes an armature {length:.6g} m long (density "
                f"{arm.density:g} kg/m^3, diameters {arm.diameter:.6g} / {sh.diameter:.6g} m), "
                f"longer than the shaft_length_m = {sh.length:.6g} m between the bearings; valid "
                f"range (0, {m_max:.6g}] kg for this geometry"
            )

    @property
    def shaft_hz(self) -> float:
        return self.speed_rpm / 60.0

    @property
    def omega(self) -> float:
        """Shaft speed [rad/s]."""
        return 2 * math.pi * self.shaft_hz

    @property
    def armature_length(self) -> float:
        """Length of the armature [m]: its mass over its density times the annulus between the
        disk and shaft diameters, ``m / (rho pi (D^2 - d^2) / 4)`` (sets the disks' inertia)."""
        arm = self.armature
        area = math.pi * ((0.5 * arm.diameter) ** 2 - (0.5 * self.shaft.diameter) ** 2)
        return arm.mass / (arm.density * area)

    @property
    def disk_positions(self) -> tuple[float, ...]:
        """Disk positions [m] (none when the armature is distributed)."""
        a = self.armature
        if a.distributed:
            return ()
        if a.positions is not None:
            return a.positions
        L = self.shaft.length
        return tuple(L * (i + 1) / (a.n_disks + 1) for i in range(a.n_disks))

    def kinematics(self) -> dict[str, KinematicFrequencies]:
        """Characteristic frequencies of the DE and FE bearings at the shaft speed [Hz]."""
        return {
            "DE": characteristic_frequencies(self.de.bearing, self.shaft_hz),
            "FE": characteristic_frequencies(self.fe.bearing, self.shaft_hz),
        }


def _fmt_positions(pos: tuple[float, ...]) -> str:
    """``(0.05, 0.1)``: positions [m] for a message (6 significant digits, at most 8 shown)."""
    shown = ", ".join(f"{z:.6g}" for z in pos[:8])
    return f"({shown}{', ...' if len(pos) > 8 else ''})"


def catalogue_bearing(bearing_id: str, name: str = "bearing") -> BallBearing:
    """The catalogue bearing ``bearing_id`` (:func:`bearingsim.catalog.get_bearing`); an unknown
    id is refused with one line naming the field ``name`` (``de_bearing``, ``fe_bearing``)."""
    try:
        return get_bearing(bearing_id)
    except ConfigError as exc:
        msg = str(exc)
        head = f"bearing = {bearing_id!r}"
        if name != "bearing" and msg.startswith(head):
            raise ConfigError(f"{name} = {bearing_id!r}{msg[len(head) :]}") from None
        raise


def cwru_rotor_config(
    n_disks: int = 9,
    de_fault: Defect | None = None,
    fe_fault: Defect | None = None,
    speed_rpm: float = DEFAULT_RPM,
    de_bearing: str = "6205-cwru",
    fe_bearing: str = "6203-cwru",
    **kw: Any,
) -> RotorConfig:
    """The seed's CWRU case: 6205 (DE) and 6203 (FE) on the seed table 2 rotor.

    Parameters
    ----------
    n_disks : int
        Number of armature disks (equally spaced).
    de_fault, fe_fault : Defect or None
        Defects (e.g. ``Defect("outer")``: 0.007 in x 0.011 in at 6 o'clock, record 132).
    speed_rpm : float
        Shaft speed [r/min] (CWRU record 132: 1750).
    de_bearing, fe_bearing : str
        Catalogue ids (``6205-cwru-rotor`` gives the seed table 1 values).
    **kw
        Any other :class:`RotorConfig` field (``armature=`` overrides ``n_disks``).
    """
    arm = kw.pop("armature", None) or Armature(n_disks=n_disks)
    return RotorConfig(
        de=BearingSupport(catalogue_bearing(de_bearing, "de_bearing"), de_fault),
        fe=BearingSupport(catalogue_bearing(fe_bearing, "fe_bearing"), fe_fault),
        armature=arm,
        speed_rpm=speed_rpm,
        **kw,
    )


def config_summary(config: RotorConfig) -> dict[str, Any]:
    """Plain, JSON-able description of ``config`` (SI units; enums as strings)."""

    def conv(o: Any) -> Any:
        if isinstance(o, enum.Enum):
            return o.value
        if isinstance(o, BallBearing):
            return o.id
        if dataclasses.is_dataclass(o):
            return {f.name: conv(getattr(o, f.name)) for f in dataclasses.fields(o)}
        if isinstance(o, tuple | list):
            return [conv(v) for v in o]
        return o

    return conv(config)
