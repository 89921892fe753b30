"""Bearing geometry as validated, frozen data: bearings, raceways, local defects, and the
kinematic (characteristic) frequencies.

Conventions (used by every model): SI units; the outer ring is fixed and the inner ring rotates;
element azimuths ``psi`` are measured from the +y axis towards +x (seed VSM fig. 1); the
diametral clearance ``P_d`` is the total free play across a diameter (negative = preload).
"""

from __future__ import annotations

import enum
import math
from dataclasses import dataclass, field

from .errors import ConfigError, check_positive, check_range
from .materials import Material

__all__ = [
    "angular_extent",
    "BallBearing",
    "Bearing",
    "characteristic_frequencies",
    "check_defect_depth",
    "CWRU_DEFECT_DEPTH_M",
    "CWRU_DEFECT_WIDTH_M",
    "Defect",
    "defect_at_edge",
    "defect_geometry",
    "DefectGeometry",
    "DefectProfile",
    "ISO_INNER_CONFORMITY",
    "ISO_OUTER_CONFORMITY",
    "KinematicFrequencies",
    "parse_enum",
    "Race",
    "raceway_radius",
    "ring_wall",
    "RollerBearing",
]


def _set(obj: object, name: str, value: object) -> None:
    object.__setattr__(obj, name, value)


def _check_common(b: BallBearing | RollerBearing) -> None:
    if not isinstance(b.id, str) or not b.id.strip():
        raise ConfigError(f"id = {b.id!r} is invalid; valid: a non-empty string")
    if isinstance(b.n_elements, bool) or not isinstance(b.n_elements, int | float):
        raise ConfigError(f"n_elements = {b.n_elements!r} is not an integer; valid range [3, inf)")
    if float(b.n_elements) != int(b.n_elements) or b.n_elements < 3:
        raise ConfigError(
            f"n_elements = {b.n_elements!r} is out of range; valid range [3, inf) integer"
        )
    _set(b, "n_elements", int(b.n_elements))
    _set(b, "element_diameter", check_positive("element_diameter_m", b.element_diameter, "m"))
    _set(b, "pitch_diameter", check_positive("pitch_diameter_m", b.pitch_diameter, "m"))
    d, D = b.element_diameter, b.pitch_diameter
    if d >= D:
        raise ConfigError(
            f"element_diameter_m = {d:.6g} m must be smaller than pitch_diameter_m = {D:.6g} m; "
            f"valid range (0, {D:.6g}) m"
        )
    # neighbouring elements must not overlap on the pitch circle
    d_max = D * math.sin(math.pi / b.n_elements)
    if d >= d_max:
        raise ConfigError(
            f"element_diameter_m = {d:.6g} m is too large for n_elements = {b.n_elements} on "
            f"pitch_diameter_m = {D:.6g} m (elements overlap); valid range (0, {d_max:.6g}) m"
        )
    _set(
        b,
        "contact_angle",
        check_range(
            "contact_angle_rad", b.contact_angle, 0.0, math.pi / 2, hi_open=True, unit="rad"
        ),
    )
    _set(
        b,
        "diametral_clearance",
        check_range("diametral_clearance_m", b.diametral_clearance, -0.5 * d, 0.5 * d, unit="m"),
    )
    if not isinstance(b.material, Material):
        raise ConfigError(f"material = {b.material!r} is not a Material")
    for name in ("bore", "outer_diameter", "width"):
        v = getattr(b, name)
        if v is not None:
            _set(b, name, check_positive(f"{name}_m", v, "m"))


@dataclass(frozen=True)
class BallBearing:
    """Deep-groove or angular-contact ball bearing.

    Parameters
    ----------
    id : str
        Catalogue identifier.
    n_elements : int
        Number of balls Z [-], >= 3.
    element_diameter : float
        Ball diameter d [m].
    pitch_diameter : float
        Pitch diameter D (d_m) [m].
    contact_angle : float
        Nominal contact angle alpha [rad]; 0 for a deep-groove bearing.
    diametral_clearance : float
        Diametral clearance P_d [m]; negative for preload.
    inner_groove_radius, outer_groove_radius : float
        Groove curvature radii R_i, R_o [m]; conformities ``f = R/d`` must exceed 0.5.
    material : Material
        Material of rings and balls.
    source : str
        Where the data come from.
    bore, outer_diameter, width : float or None
        Envelope dimensions [m] (informative).
    """

    id: str
    n_elements: int
    element_diameter: float
    pitch_diameter: float
    inner_groove_radius: float
    outer_groove_radius: float
    contact_angle: float = 0.0
    diametral_clearance: float = 0.0
    material: Material = field(default_factory=Material)
    source: str = ""
    bore: float | None = None
    outer_diameter: float | None = None
    width: float | None = None

    kind = "ball"

    def __post_init__(self) -> None:
        _check_common(self)
        d = self.element_diameter
        for name in ("inner_groove_radius", "outer_groove_radius"):
            v = check_positive(f"{name}_m", getattr(self, name), "m")
            if v <= 0.5 * d:
                raise ConfigError(
                    f"{name}_m = {v:.6g} m gives conformity {v / d:.4f} <= 0.5; valid range "
                    f"({0.5 * d:.6g}, inf) m (conformity R/d > 0.5)"
                )
            _set(self, name, v)

    @property
    def inner_conformity(self) -> float:
        """f_i = R_i / d [-]."""
        return self.inner_groove_radius / self.element_diameter

    @property
    def outer_conformity(self) -> float:
        """f_o = R_o / d [-]."""
        return self.outer_groove_radius / self.element_diameter

    @property
    def inner_raceway_radius(self) -> float:
        """Radius of the inner groove bottom, ``(D - d)/2`` [m] (seed VSM table 1: r_i)."""
        return 0.5 * (self.pitch_diameter - self.element_diameter)

    @property
    def outer_raceway_radius(self) -> float:
        """Radius of the outer groove bottom, ``(D + d)/2`` [m] (seed VSM table 1: r_o)."""
        return 0.5 * (self.pitch_diameter + self.element_diameter)


@dataclass(frozen=True)
class RollerBearing:
    """Cylindrical roller bearing.

    Parameters
    ----------
    id : str
        Catalogue identifier.
    n_elements : int
        Number of rollers Z [-], >= 3.
    element_diameter : float
        Roller diameter D_c = 2 r_c [m].
    pitch_diameter : float
        Pitch diameter D_p [m].
    roller_length : float
        Effective contact length l [m].
    contact_angle : float
        Contact angle [rad]; 0 for a cylindrical roller bearing.
    diametral_clearance : float
        Diametral clearance [m] (twice the radial gap ``c``); negative for preload.
    inner_raceway_diameter, outer_raceway_diameter : float or None
        Raceway diameters [m] when the source gives them (default ``D_p -/+ D_c``).
    material : Material
        Material of rings and rollers.
    source : str
        Where the data come from.
    """

    id: str
    n_elements: int
    element_diameter: float
    pitch_diameter: float
    roller_length: float
    contact_angle: float = 0.0
    diametral_clearance: float = 0.0
    material: Material = field(default_factory=Material)
    source: str = ""
    inner_raceway_diameter: float | None = None
    outer_raceway_diameter: float | None = None
    bore: float | None = None
    outer_diameter: float | None = None
    width: float | None = None

    kind = "cylindrical_roller"

    def __post_init__(self) -> None:
        _check_common(self)
        _set(self, "roller_length", check_positive("roller_length_m", self.roller_length, "m"))
        for name in ("inner_raceway_diameter", "outer_raceway_diameter"):
            v = getattr(self, name)
            if v is not None:
                _set(self, name, check_positive(f"{name}_m", v, "m"))
        if self.inner_raceway_diameter is None:
            _set(self, "inner_raceway_diameter", self.pitch_diameter - self.element_diameter)
        if self.outer_raceway_diameter is None:
            _set(self, "outer_raceway_diameter", self.pitch_diameter + self.element_diameter)
        if self.inner_raceway_diameter >= self.outer_raceway_diameter:
            raise ConfigError(
                f"inner_raceway_diameter_m = {self.inner_raceway_diameter:.6g} m must be smaller "
                f"than outer_raceway_diameter_m = {self.outer_raceway_diameter:.6g} m"
            )

    @property
    def inner_raceway_radius(self) -> float:
        """Inner raceway radius r_i [m]."""
        return 0.5 * self.inner_raceway_diameter

    @property
    def outer_raceway_radius(self) -> float:
        """Outer raceway radius r_o [m]."""
        return 0.5 * self.outer_raceway_diameter


Bearing = BallBearing | RollerBearing


@dataclass(frozen=True)
class KinematicFrequencies:
    """Characteristic frequencies for a fixed outer ring and rotating inner ring.

    All frequencies in [Hz]; orders are per shaft revolution [-].
    """

    shaft_hz: float
    ftf_hz: float
    bpfo_hz: float
    bpfi_hz: float
    bsf_hz: float

    def _order(self, f: float) -> float:
        return f / self.shaft_hz

    @property
    def ftf_order(self) -> float:
        return self._order(self.ftf_hz)

    @property
    def bpfo_order(self) -> float:
        return self._order(self.bpfo_hz)

    @property
    def bpfi_order(self) -> float:
        return self._order(self.bpfi_hz)

    @property
    def bsf_order(self) -> float:
        return self._order(self.bsf_hz)

    def as_dict(self) -> dict[str, float]:
        """Keys ``ftf_hz, bpfo_hz, bpfi_hz, bsf_hz`` and the four ``*_order`` [Hz], [-]."""
        out = {k: getattr(self, k) for k in ("ftf_hz", "bpfo_hz", "bpfi_hz", "bsf_hz")}
        for k in ("ftf", "bpfo", "bpfi", "bsf"):
            out[f"{k}_order"] = getattr(self, f"{k}_order")
        return out


def characteristic_frequencies(bearing: Bearing, shaft_hz: float) -> KinematicFrequencies:
    """Cage, ball-pass and ball-spin frequencies (SPEC §0.2; seed VSM eqs (20)–(21)).

    With ``g = d cos(alpha) / D``: ``FTF = f_s/2 (1 - g)``, ``BPFO = Z f_s/2 (1 - g)``,
    ``BPFI = Z f_s/2 (1 + g)``, ``BSF = D/(2d) f_s (1 - g^2)`` (Harris & Kotzalas 2007, ch. 8).

    Parameters
    ----------
    bearing : BallBearing or RollerBearing
        Geometry.
    shaft_hz : float
        Inner-ring (shaft) rotation frequency f_s [Hz], > 0.
    """
    fs = check_positive("shaft_hz", shaft_hz, "Hz")
    d, D, Z = bearing.element_diameter, bearing.pitch_diameter, bearing.n_elements
    g = d * math.cos(bearing.contact_angle) / D
    return KinematicFrequencies(
        shaft_hz=fs,
        ftf_hz=0.5 * fs * (1.0 - g),
        bpfo_hz=0.5 * Z * fs * (1.0 - g),
        bpfi_hz=0.5 * Z * fs * (1.0 + g),
        bsf_hz=D / (2.0 * d) * fs * (1.0 - g * g),
    )


# ------------------------------------------------------------------------- raceways and defects


class Race(enum.Enum):
    """A raceway: the ring of a contact, or the ring that carries a local defect. The outer ring
    is fixed; the inner ring turns with the shaft."""

    INNER = "inner"
    OUTER = "outer"


class DefectProfile(enum.Enum):
    """Extra clearance under an element crossing a local defect: ``GEOMETRIC`` (the ball rests on
    the nearer edge; seed VSM eq. (2) evaluated along the path, continuous) or ``RECTANGULAR``
    (the constant maximum drop ``h_min`` over the defect's extent, seed VSM eqs. (1)–(3)). Used by
    the bearing–rotor–housing model; the ring models follow seed VSM (rectangular, with the
    retention factor of its eq. (11)); the IAS model follows seed IAS eqs. (19)–(28)."""

    GEOMETRIC = "geometric"
    RECTANGULAR = "rectangular"


#: reference groove conformities ``r / D_w`` of radial ball bearings, inner and outer raceway
#: [-] (ISO/TS 16281:2008 §6.3; the same values underlie ISO 281's ratings, ISO/TR 1281-1)
ISO_INNER_CONFORMITY = 0.52
ISO_OUTER_CONFORMITY = 0.53

#: CWRU seeded faults, 0.007 in wide (CWRU Bearing Data Center, "Fault Specifications") [m]
CWRU_DEFECT_WIDTH_M = 0.007 * 25.4e-3
#: CWRU electro-discharge-machined fault depth, 0.011 in (``../shared/data/cwru/SOURCES.md``) [m]
CWRU_DEFECT_DEPTH_M = 0.011 * 25.4e-3


def parse_enum(cls: type[enum.Enum], value: object, name: str) -> enum.Enum:
    """``cls(value)`` (an enum member or its value); anything else raises a one-line
    :class:`ConfigError` naming ``name`` and the valid values."""
    try:
        return cls(value.value if isinstance(value, enum.Enum) else value)
    except ValueError:
        valid = ", ".join(str(m.value) for m in cls)
        raise ConfigError(f"{name} = {value!r} is invalid; valid: {valid}") from None


@dataclass(frozen=True)
class Defect:
    """A local raceway defect: a slot across the raceway (seed VSM fig. 2; seed ROTOR §1.2;
    the spall of seed IAS fig. 3). Shared by the ring, rotor and IAS models.

    Parameters
    ----------
    race : Race or {"inner", "outer"}
        Raceway carrying the defect.
    width : float
        Width ``b`` (``L_d`` in seed IAS) along the raceway [m], > 0 (default: CWRU 0.007 in).
        Each model states the widths it admits (the element must span the defect).
    depth : float
        Depth ``h_d`` [m], > 0 (default: the CWRU EDM depth 0.011 in). The IAS model does not use
        it (seed IAS assumes the spall deeper than the roller's drop).
    angle : float
        Azimuth of the defect **centre** at ``t = 0`` [rad], from +y towards +x (the project
        convention); ``pi`` = 6 o'clock, the bottom of a horizontal machine (CWRU ``@6``). An
        inner-race defect turns with the shaft from there.
    profile : DefectProfile or str
        Drop profile across the defect (rotor model; see :class:`DefectProfile`).
    """

    race: Race | str = Race.OUTER
    width: float = CWRU_DEFECT_WIDTH_M
    depth: float = CWRU_DEFECT_DEPTH_M
    angle: float = math.pi
    profile: DefectProfile | str = DefectProfile.GEOMETRIC

    def __post_init__(self) -> None:
        _set(self, "race", parse_enum(Race, self.race, "fault_race"))
        _set(self, "profile", parse_enum(DefectProfile, self.profile, "defect_profile"))
        _set(self, "width", check_positive("defect_width_m", self.width, "m"))
        _set(self, "depth", check_positive("defect_depth_m", self.depth, "m"))
        _set(self, "angle", check_range("defect_angle_rad", self.angle, unit="rad"))


@dataclass(frozen=True)
class DefectGeometry:
    """Geometric quantities of a defect on a given bearing (seed VSM eqs. (1)–(3)).

    Attributes
    ----------
    race : Race
        Raceway.
    race_radius : float
        Raceway radius ``r_i`` or ``r_o`` [m].
    h_s : float
        Drop of a ball resting on both edges without touching the bottom, eq. (2) [m].
    h_min : float
        Maximum drop ``min(h_d, h_s)``, eq. (1) [m].
    delta_beta : float
        Central angle spanned by the defect on its raceway, eq. (3) [rad].
    edge_angle : float
        Azimuth of the defect's left (lower-azimuth) edge at ``t = 0``, ``beta_0`` of seed VSM
        [rad]: the defect centre less half the extent.
    """

    race: Race
    race_radius: float
    h_s: float
    h_min: float
    delta_beta: float
    edge_angle: float


def defect_geometry(bearing: Bearing, defect: Defect) -> DefectGeometry:
    """Maximum ball drop and angular extent of ``defect`` on ``bearing``.

    Seed VSM eqs. (1)–(3)::

        h_s = [r - sqrt(r^2 - (b/2)^2)] +/- [r_race - sqrt(r_race^2 - (b/2)^2)]
        h_min = min(h_d, h_s)
        Delta_beta = 2 arcsin(b / (2 r_race))

    (``+`` and ``r_i`` for the inner race, whose convex surface falls away under the chord;
    ``-`` and ``r_o`` for the concave outer race.) ``r = d/2`` is the ball radius; the raceway
    radii are ``(D -/+ d)/2`` (seed table 1: 15.53 and 23.47 mm).

    Parameters
    ----------
    bearing : BallBearing
        Geometry.
    defect : Defect
        The defect (its ``angle`` is the centre azimuth).

    Raises
    ------
    ConfigError
        If the ball cannot span the defect (``b >= d``): the seed's geometry (a ball resting on
        both edges, fig. 2) no longer applies.
    """
    if not isinstance(bearing, BallBearing):
        raise ConfigError(
            f"bearing = {bearing.id!r} is not a ball bearing; this defect geometry needs balls"
        )
    if not isinstance(defect, Defect):
        raise ConfigError(f"defect = {defect!r} is not a Defect (a healthy bearing has none)")
    d = bearing.element_diameter
    r = 0.5 * d
    b = defect.width
    if b >= d:
        raise ConfigError(
            f"defect_width_m = {b:.6g} m is wider than the ball can span; valid range "
            f"(0, {d:.6g}) m (ball diameter d)"
        )
    half = 0.5 * b
    ball_chord = r - math.sqrt(r * r - half * half)
    if defect.race is Race.INNER:
        rr = bearing.inner_raceway_radius
        h_s = ball_chord + (rr - math.sqrt(rr * rr - half * half))  # seed VSM eq. (2), inner
    else:
        rr = bearing.outer_raceway_radius
        h_s = ball_chord - (rr - math.sqrt(rr * rr - half * half))  # seed VSM eq. (2), outer
    check_defect_depth(bearing, defect)
    h_min = min(defect.depth, h_s)  # seed VSM eq. (1): a deeper defect is not touched
    dbeta = 2.0 * math.asin(b / (2.0 * rr))  # seed VSM eq. (3)
    edge = defect.angle - 0.5 * dbeta
    return DefectGeometry(defect.race, rr, h_s, h_min, dbeta, edge)


def ring_wall(bearing: Bearing, race: Race | str) -> float:
    """Thickness of the ring under the raceway of ``race`` [m]: ``r_i - bore/2`` (inner) or
    ``D_out/2 - r_o`` (outer) from the bearing's envelope; the element diameter when the bearing
    gives no bore or outer diameter."""
    race = parse_enum(Race, race, "fault_race")
    if race is Race.INNER and bearing.bore is not None:
        return bearing.inner_raceway_radius - 0.5 * bearing.bore
    if race is Race.OUTER and bearing.outer_diameter is not None:
        return 0.5 * bearing.outer_diameter - bearing.outer_raceway_radius
    return bearing.element_diameter


def check_defect_depth(bearing: Bearing, defect: Defect) -> float:
    """Refuse a defect at least as deep as the ring's wall under its raceway
    (:func:`ring_wall`): it would cut the ring through. A depth beyond the element's drop is
    valid (the element does not reach the bottom, seed VSM eq. (1)). Returns the depth [m]."""
    wall = ring_wall(bearing, defect.race)
    known = bearing.bore is not None and bearing.outer_diameter is not None
    if defect.depth >= wall:
        what = "ring wall" if known else "element diameter (no bore/outer diameter given)"
        raise ConfigError(
            f"defect_depth_m = {defect.depth:.6g} m is not less than the {defect.race.value} "
            f"{what} {wall:.6g} m of {bearing.id}; valid range (0, {wall:.6g}) m"
        )
    return defect.depth


def raceway_radius(bearing: Bearing, race: Race) -> float:
    """Raceway radius ``r_i`` or ``r_o`` [m] of ``race``."""
    return bearing.inner_raceway_radius if race is Race.INNER else bearing.outer_raceway_radius


def angular_extent(bearing: Bearing, race: Race | str, width: float) -> float:
    """Central angle ``Delta_beta = 2 arcsin(b / (2 r_race))`` spanned by a defect of width ``b``
    [m] on ``race`` (seed VSM eq. (3)) [rad]."""
    rr = raceway_radius(bearing, parse_enum(Race, race, "fault_race"))
    return 2.0 * math.asin(min(1.0, width / (2.0 * rr)))


def defect_at_edge(
    bearing: Bearing, race: Race | str, width: float, depth: float, edge_angle: float
) -> Defect:
    """The :class:`Defect` whose left (lower-azimuth) edge is at ``edge_angle`` at ``t = 0``
    [rad] — seed VSM's ``beta_0`` (its table 1: 10 deg) — i.e. whose centre is at
    ``edge_angle + Delta_beta/2`` (eq. (3)).

    Parameters
    ----------
    bearing : BallBearing
        Geometry.
    race : Race or str
        Raceway.
    width, depth : float
        Defect width ``b`` and depth ``h_d`` [m].
    edge_angle : float
        Left-edge azimuth ``beta_0`` [rad].
    """
    race = parse_enum(Race, race, "fault_race")
    w = check_positive("defect_width_m", width, "m")
    return Defect(race, w, depth, edge_angle + 0.5 * angular_extent(bearing, race, w))
