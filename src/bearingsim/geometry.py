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
    "ANGLE_LINES",
    "BallBearing",
    "Bearing",
    "characteristic_frequencies",
    "check_clearance",
    "check_defect_depth",
    "check_speed_limit",
    "check_unused_defect",
    "clearance_range",
    "contact_angle_from_order",
    "CONFORMITY_RANGE",
    "CONTACT_ANGLE_MAX",
    "CWRU_DEFECT_DEPTH_M",
    "CWRU_DEFECT_WIDTH_M",
    "Defect",
    "defect_at_edge",
    "defect_geometry",
    "DEFECT_ANGLE_MAX",
    "DefectGeometry",
    "DefectProfile",
    "GAMMA_RANGE_BALL",
    "GAMMA_RANGE_ROLLER",
    "ISO5753_GROUP5_BALL",
    "ISO5753_GROUP5_ROLLER",
    "ISO_INNER_CONFORMITY",
    "ISO_OUTER_CONFORMITY",
    "KinematicFrequencies",
    "max_clearance",
    "parse_enum",
    "PITCH_DIAMETER_RANGE",
    "Race",
    "raceway_radius",
    "ring_wall",
    "ROLLER_LENGTH_RANGE",
    "RollerBearing",
    "SPEED_FACTOR_MAX",
    "Z_MAX",
]


def _set(obj: object, name: str, value: object) -> None:
    object.__setattr__(obj, name, value)


# ------------------------------------------------------------------ what a bearing can be
#: Most rolling elements in one row [-]: with ``gamma >= 0.01`` (below) at most
#: ``pi / asin(0.01) ~ 314`` fit on the pitch circle; the bound keeps the count a number.
Z_MAX = 1000
#: Pitch diameters D_pw of rolling bearings [m]: miniature bearings of about 1 mm bore to the
#: largest radial bearings of the ISO 15 general plan (bores up to 2.5 m), with margin.
PITCH_DIAMETER_RANGE = (1e-3, 5.0)
#: ``gamma = D_w cos(alpha) / D_pw`` of ball bearings [-]: the span of ISO 281:2007 table 2 (the
#: ratings of radial ball bearings are given for 0.01 <= gamma <= 0.40).
GAMMA_RANGE_BALL = (0.01, 0.40)
#: ``gamma = D_we cos(alpha) / D_pw`` of roller bearings [-]: the span of ISO 281:2007 table 3.
GAMMA_RANGE_ROLLER = (0.01, 0.50)
#: Effective roller length in roller diameters, ``l / D_we`` [-]: from half a diameter (shorter
#: is a disc, not a line contact) to ten (needle rollers, the slenderest, are up to about ten
#: diameters long; ISO 3096).
ROLLER_LENGTH_RANGE = (0.5, 10.0)
#: Largest nominal contact angle of a radial bearing [rad]: 45 deg (ISO 5593 and ISO 281:2007
#: §3: radial bearings have nominal contact angles from 0 to 45 deg; above are thrust bearings).
CONTACT_ANGLE_MAX = math.radians(45.0)
#: Groove conformity ``f = R / D_w`` of deep-groove and angular-contact ball bearings [-]:
#: above 0.5 (a groove no wider than the ball is not a groove) and at most 0.60. Catalogue
#: bearings have 0.515-0.53 (Harris & Kotzalas 2007, vol. 1 ch. 2; the ISO/TS 16281 reference
#: values are 0.52 inner, 0.53 outer); low-torque miniature bearings go to 0.56 +/- 0.03
#: (Dynaroll, "Raceway curvature"). A larger groove radius is a self-aligning (spherical) outer
#: race, which this model does not describe.
CONFORMITY_RANGE = (0.5, 0.60)

#: ISO 5753-1:2009, radial internal clearance of deep-groove ball bearings with cylindrical bore:
#: upper limit of the largest group (group 5, "C5") by bore. Rows ``(bore d up to and including
#: [mm], clearance [um])``, transcribed from the manufacturers' reproductions of the standard's
#: table (SKF, NSK catalogues), not from the standard itself; the row up to 10 mm serves every
#: smaller bore. Above the last row the limit grows in proportion to the bore (1.2 um per mm,
#: as the last rows do).
ISO5753_GROUP5_BALL = (
    (10.0, 37.0), (18.0, 45.0), (24.0, 48.0), (30.0, 53.0), (40.0, 64.0), (50.0, 73.0),
    (65.0, 90.0), (80.0, 105.0), (100.0, 120.0),
)  # fmt: skip
#: ISO 5753-1:2009, cylindrical roller bearings with cylindrical bore: group 5 upper limit by
#: bore, rows and transcription as :data:`ISO5753_GROUP5_BALL`; proportional above 1000 mm.
ISO5753_GROUP5_ROLLER = (
    (24.0, 90.0), (30.0, 95.0), (40.0, 105.0), (50.0, 125.0), (65.0, 140.0), (80.0, 165.0),
    (100.0, 190.0), (120.0, 220.0), (140.0, 245.0), (160.0, 275.0), (180.0, 300.0),
    (200.0, 330.0), (225.0, 365.0), (250.0, 395.0), (280.0, 440.0), (315.0, 485.0),
    (355.0, 535.0), (400.0, 600.0), (450.0, 665.0), (500.0, 735.0), (560.0, 810.0),
    (630.0, 900.0), (710.0, 1005.0), (800.0, 1135.0), (900.0, 1265.0), (1000.0, 1405.0),
)  # fmt: skip


def _bore_for_clearance(b: BallBearing | RollerBearing) -> float:
    """The bore [m] that selects the ISO 5753-1 row: the bearing's, or when it gives none the
    inner raceway diameter, which exceeds any bore (so the limit is never tighter)."""
    if b.bore is not None:
        return b.bore
    if isinstance(b, RollerBearing) and b.inner_raceway_diameter is not None:
        return b.inner_raceway_diameter
    return b.pitch_diameter - b.element_diameter * math.cos(b.contact_angle)


def max_clearance(bearing: BallBearing | RollerBearing) -> float:
    """Largest diametral clearance a new bearing of this type and bore is made with [m]: the
    upper limit of group 5 of ISO 5753-1:2009 (deep-groove ball or cylindrical roller bearings)
    for the bore (:data:`ISO5753_GROUP5_BALL`, :data:`ISO5753_GROUP5_ROLLER`)."""
    rows = ISO5753_GROUP5_ROLLER if isinstance(bearing, RollerBearing) else ISO5753_GROUP5_BALL
    d_mm = 1e3 * _bore_for_clearance(bearing)
    for upto, c_um in rows:
        if d_mm <= upto:
            return 1e-6 * c_um
    upto, c_um = rows[-1]
    return 1e-6 * c_um * d_mm / upto


def clearance_range(bearing: BallBearing | RollerBearing) -> tuple[float, float]:
    """Valid diametral clearance ``P_d`` [m] of ``bearing``: ``[-c5, c5]`` with ``c5`` =
    :func:`max_clearance`. The positive side is the largest clearance of ISO 5753-1; a negative
    operating clearance (preload) arises when fits and temperature take up more than the
    clearance, and we accept at most as much preload as the largest clearance of the same bore
    (our bound: -3.9 mm on a 6205 gave 808 kN per ball under 5 kN)."""
    c5 = max_clearance(bearing)
    return -c5, c5


#: smallest preload (negative diametral clearance) that holds a ring without a radial load
#: [m]: 1 nm, below any raceway's roughness; the ball loads of a smaller one vanish beside the
#: balls' Hertz constants (a 1e-300 m "preload" gave an all-zero DEM signal, fault unseen)
HOLDING_PRELOAD_M = 1e-9


def check_clearance(
    bearing: BallBearing | RollerBearing,
    value: object,
    name: str = "diametral_clearance_m",
    hi: float | None = None,
) -> float:
    """``value`` [m] within :func:`clearance_range` (and below ``hi`` when given), else a
    one-line :class:`ConfigError` that names the source of the limit."""
    lo, c5 = clearance_range(bearing)
    top = c5 if hi is None else min(c5, hi)
    try:
        return check_range(name, value, lo, top, hi_open=hi is not None and hi < c5, unit="m")
    except ConfigError as exc:
        bore = 1e3 * _bore_for_clearance(bearing)
        raise ConfigError(
            f"{exc} (+/- the largest radial internal clearance of ISO 5753-1, group 5, for a "
            f"{bore:.4g} mm bore)"
        ) from None


def _check_common(b: BallBearing | RollerBearing) -> None:
    if not isinstance(b.id, str) or not b.id.strip():
        raise ConfigError(f"id = {b.id!r} is invalid; valid: a non-empty string")
    n = b.n_elements
    if isinstance(n, bool) or not isinstance(n, int | float):
        raise ConfigError(f"n_elements = {n!r} is not an integer; valid range [3, {Z_MAX}]")
    if (isinstance(n, float) and not n.is_integer()) or not 3 <= n <= Z_MAX:
        raise ConfigError(f"n_elements = {n!r} is out of range; valid range [3, {Z_MAX}] integer")
    _set(b, "n_elements", int(n))
    _set(b, "element_diameter", check_positive("element_diameter_m", b.element_diameter, "m"))
    _set(
        b,
        "pitch_diameter",
        check_range("pitch_diameter_m", b.pitch_diameter, *PITCH_DIAMETER_RANGE, unit="m"),
    )
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
        check_range("contact_angle_rad", b.contact_angle, 0.0, CONTACT_ANGLE_MAX, unit="rad"),
    )
    g_lo, g_hi = GAMMA_RANGE_BALL if isinstance(b, BallBearing) else GAMMA_RANGE_ROLLER
    ca = math.cos(b.contact_angle)
    if not g_lo <= d * ca / D <= g_hi:
        raise ConfigError(
            f"element_diameter_m = {d:.6g} m gives gamma = d cos(alpha)/D = {d * ca / D:.4g} on "
            f"pitch_diameter_m = {D:.6g} m; valid range [{g_lo * D / ca:.6g}, "
            f"{min(g_hi * D / ca, d_max):.6g}] m (gamma in [{g_lo:g}, {g_hi:g}], ISO 281 tables "
            "2 and 3)"
        )
    if not isinstance(b.material, Material):
        raise ConfigError(f"material = {b.material!r} is not a Material")


def _check_envelope(b: BallBearing | RollerBearing) -> None:
    """Bore and outside diameter around the raceways, and the clearance (after the raceways
    are known)."""
    d, D, ca = b.element_diameter, b.pitch_diameter, math.cos(b.contact_angle)
    for name in ("bore", "outer_diameter", "width"):
        v = getattr(b, name)
        if v is not None:
            _set(b, name, check_positive(f"{name}_m", v, "m"))
    if isinstance(b, BallBearing):
        inner, outer = D - d * ca, D + d * ca
    else:
        inner, outer = b.inner_raceway_diameter, b.outer_raceway_diameter
    if b.bore is not None and b.bore >= inner:
        raise ConfigError(
            f"bore_m = {b.bore:.6g} m is not inside the inner raceway (diameter {inner:.6g} m); "
            f"valid range (0, {inner:.6g}) m"
        )
    if b.outer_diameter is not None and b.outer_diameter <= outer:
        raise ConfigError(
            f"outer_diameter_m = {b.outer_diameter:.6g} m is not outside the outer raceway "
            f"(diameter {outer:.6g} m); valid range ({outer:.6g}, inf) m"
        )
    if b.width is not None:
        # the rings hold the rolling elements (a ball's diameter, a roller's length) and a
        # radial bearing is no wider than its outside diameter (ISO 15 series: B < D)
        w_lo = b.element_diameter if isinstance(b, BallBearing) else b.roller_length
        w_hi = b.outer_diameter if b.outer_diameter is not None else outer
        _set(b, "width", check_range("width_m", b.width, w_lo, w_hi, unit="m"))
    _set(b, "diametral_clearance", check_clearance(b, b.diametral_clearance))


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
        Ball diameter d [m]; ``d cos(alpha)/D`` in [0.01, 0.40] (:data:`GAMMA_RANGE_BALL`) and
        the balls must not overlap on the pitch circle.
    pitch_diameter : float
        Pitch diameter D (d_m) [m], in [1 mm, 5 m] (:data:`PITCH_DIAMETER_RANGE`).
    contact_angle : float
        Nominal contact angle alpha [rad], in [0, pi/4] (a radial bearing); 0 for a
        deep-groove bearing.
    diametral_clearance : float
        Diametral clearance P_d [m]; negative for preload; within :func:`clearance_range`
        (the largest ISO 5753-1 clearance of the bore, either sign).
    inner_groove_radius, outer_groove_radius : float
        Groove curvature radii R_i, R_o [m]; conformities ``f = R/d`` in (0.5, 0.6]
        (:data:`CONFORMITY_RANGE`).
    material : Material
        Material of rings and balls.
    source : str
        Where the data come from.
    bore, outer_diameter, width : float or None
        Envelope dimensions [m]: the bore inside the inner raceway, the outside diameter outside
        the outer one; the bore selects the ISO 5753-1 clearance limit.
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
        f_lo, f_hi = CONFORMITY_RANGE
        for name in ("inner_groove_radius", "outer_groove_radius"):
            v = check_positive(f"{name}_m", getattr(self, name), "m")
            if not f_lo * d < v <= f_hi * d:
                raise ConfigError(
                    f"{name}_m = {v:.6g} m gives conformity R/d = {v / d:.4g}; valid range "
                    f"({f_lo * d:.6g}, {f_hi * d:.6g}] m (conformity in ({f_lo:g}, {f_hi:g}], "
                    "Harris & Kotzalas 2007 vol. 1 ch. 2)"
                )
            _set(self, name, v)
        _check_envelope(self)

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


#: how far a given raceway diameter may lie from pitch diameter -/+ roller diameter, as a
#: fraction of the roller diameter [-] (:class:`RollerBearing`)
RACEWAY_TOLERANCE = 0.1


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
        Roller diameter D_c = 2 r_c [m]; ``D_c cos(alpha)/D_p`` in [0.01, 0.50]
        (:data:`GAMMA_RANGE_ROLLER`).
    pitch_diameter : float
        Pitch diameter D_p [m], in [1 mm, 5 m] (:data:`PITCH_DIAMETER_RANGE`).
    roller_length : float
        Effective contact length l [m], 0.5 to 10 roller diameters
        (:data:`ROLLER_LENGTH_RANGE`).
    contact_angle : float
        Contact angle [rad], in [0, pi/4]; 0 for a cylindrical roller bearing.
    diametral_clearance : float
        Diametral clearance [m] (twice the radial gap ``c``); negative for preload; within
        :func:`clearance_range`.
    inner_raceway_diameter, outer_raceway_diameter : float or None
        Raceway diameters [m] when the source gives them (default ``D_p -/+ D_c``).
    material : Material
        Material of rings and rollers.
    source : str
        Where the data come from.
    bore, outer_diameter, width : float or None
        Envelope dimensions [m], as :class:`BallBearing`.
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
        d = self.element_diameter
        lo, hi = ROLLER_LENGTH_RANGE
        _set(
            self,
            "roller_length",
            check_range("roller_length_m", self.roller_length, lo * d, hi * d, unit="m"),
        )
        for name, sign in (("inner_raceway_diameter", -1.0), ("outer_raceway_diameter", 1.0)):
            v = getattr(self, name)
            if v is not None:
                # a raceway touches the rollers: d_m -/+ D up to the clearance; within
                # RACEWAY_TOLERANCE x D, which keeps printed values such as the seed IAS's
                # NU204 (26.5/41.5 mm against 26.06/41.94 mm, 0.055 D) and refuses a raceway
                # that could not hold the rollers
                c = self.pitch_diameter + sign * d
                tol = RACEWAY_TOLERANCE * d
                _set(self, name, check_range(f"{name}_m", v, c - tol, c + tol, unit="m"))
        if self.inner_raceway_diameter is None:
            _set(self, "inner_raceway_diameter", self.pitch_diameter - self.element_diameter)
        if self.outer_raceway_diameter is None:
            _set(self, "outer_raceway_diameter", self.pitch_diameter + self.element_diameter)
        if self.inner_raceway_diameter >= self.outer_raceway_diameter:
            raise ConfigError(
                f"inner_raceway_diameter_m = {self.inner_raceway_diameter:.6g} m must be smaller "
                f"than outer_raceway_diameter_m = {self.outer_raceway_diameter:.6g} m"
            )
        _check_envelope(self)

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


#: the kinematic lines whose order fixes the contact angle (:func:`contact_angle_from_order`)
ANGLE_LINES = ("bpfo", "bpfi", "ftf")


def contact_angle_from_order(bearing: Bearing, line: str, order: float) -> float:
    """Contact angle [rad] at which the kinematic ``line`` (``"bpfo"``, ``"bpfi"`` or ``"ftf"``)
    falls at ``order`` [-] (per shaft revolution): the inverse of
    :func:`characteristic_frequencies` for ``alpha``.

    From ``g = d cos(alpha) / D``: ``g = 1 - 2 order / Z`` (BPFO), ``2 order / Z - 1`` (BPFI),
    ``1 - 2 order`` (FTF). A contact angle moves BPFO and FTF up and BPFI down, and keeps
    ``BPFO + BPFI = Z f_s``; a speed error moves all three the same way, and slip lowers BPFO,
    FTF and BPFI alike. So a measured BPFO above its ``alpha = 0`` order with the shaft speed
    measured from the same record (not taken from a file) is the signature of a contact
    angle, i.e. of an axial load on a deep-groove bearing (Harris & Kotzalas 2007, ch. 2–3).

    Parameters
    ----------
    bearing : BallBearing or RollerBearing
        Geometry (its own ``contact_angle`` is not used).
    line : str
        ``"bpfo"``, ``"bpfi"`` or ``"ftf"``.
    order : float
        Measured order of the line's fundamental [-].

    Returns
    -------
    float
        ``alpha`` in [0, pi/2] [rad].

    Raises
    ------
    ConfigError
        ``order`` outside the orders a contact angle from 0 to 90° gives (a line below the
        ``alpha = 0`` BPFO, for instance: slip or a wrong speed, not a contact angle).
    """
    name = str(line).lower()
    if name not in ANGLE_LINES:
        raise ConfigError(f"line = {line!r} is not one of {', '.join(ANGLE_LINES)}")
    d, D, Z = bearing.element_diameter, bearing.pitch_diameter, bearing.n_elements
    gamma = d / D
    o = float(order)
    if not math.isfinite(o):
        raise ConfigError(f"order = {order!r} must be finite")
    g = {"bpfo": 1.0 - 2.0 * o / Z, "bpfi": 2.0 * o / Z - 1.0, "ftf": 1.0 - 2.0 * o}[name]
    # an order at an end of the range, computed in floating point, may land a rounding off it
    # (the 6203-cwru's own alpha = 0 BPFI order was refused as outside [.., itself])
    eps = 1e-9 * gamma
    if -eps <= g < 0.0 or gamma < g <= gamma + eps:
        g = min(max(g, 0.0), gamma)
    if not 0.0 <= g <= gamma:
        ends = {
            "bpfo": (0.5 * Z * (1.0 - gamma), 0.5 * Z),
            "bpfi": (0.5 * Z, 0.5 * Z * (1.0 + gamma)),
            "ftf": (0.5 * (1.0 - gamma), 0.5),
        }[name]
        raise ConfigError(
            f"order = {o:.6g} of {name.upper()} is outside the orders a contact angle of 0 to "
            f"90 deg gives for {bearing.id}: valid range [{min(ends):.6g}, {max(ends):.6g}]"
        )
    return math.acos(min(1.0, g / gamma))


#: largest speed factor ``n d_m`` [mm r/min] a shaft speed may have: a steel ring bursts there.
#: The hoop stress of a thin rotating ring is ``rho v^2`` (``v`` its peripheral speed; Timoshenko
#: & Goodier, "Theory of Elasticity", rotating disks); it reaches the ~2 GPa tensile strength of
#: hardened bearing steel (rho = 7850 kg/m^3) at v ~ 500 m/s, i.e. ``n d_m = 60 v / pi`` ~ 1e7
#: mm r/min taken at the pitch diameter (the inner ring turns inside it: a little below its burst
#: speed). The fastest bearings built (hybrid, oil-jet lubricated) reach ~4e6.
SPEED_FACTOR_MAX = 1.0e7


def check_speed_limit(bearing: Bearing, rpm: float, name: str = "rpm", lo: str = "(0") -> float:
    """Refuse (one-line :class:`ConfigError`) a shaft speed ``rpm`` [r/min] whose speed factor
    ``n d_m`` exceeds :data:`SPEED_FACTOR_MAX`, where the rings burst; returns ``rpm``.

    Parameters
    ----------
    bearing : BallBearing or RollerBearing
        The bearing the shaft turns in (its pitch diameter ``d_m``).
    rpm : float
        Shaft speed [r/min] (finite; its lower bound is checked by the caller).
    name : str
        Field name in the message.
    lo : str
        Lower end of the valid range in the message (``"(0"`` or ``"[0"``).
    """
    dm_mm = bearing.pitch_diameter * 1e3
    hi = SPEED_FACTOR_MAX / dm_mm
    if rpm > hi:
        raise ConfigError(
            f"{name} = {rpm:.6g} r/min gives the speed factor n d_m = {rpm * dm_mm:.3g} mm r/min "
            f"of {bearing.id} (d_m = {dm_mm:.4g} mm), above {SPEED_FACTOR_MAX:.3g}, where a steel "
            f"ring bursts (hoop stress rho v^2 beyond its strength); valid range {lo}, "
            f"{hi:.6g}] r/min"
        )
    return rpm


# ------------------------------------------------------------------------- raceways and defects


class Race(enum.Enum):
    """A raceway: the ring of a contact, or what carries a local defect. The outer ring is
    fixed; the inner ring turns with the shaft. ``BALL`` is a defect site only (one rolling
    element carries the defect; ring and rotor models, issue 16 item 2): contact functions refuse it
    (:func:`contact_race`)."""

    INNER = "inner"
    OUTER = "outer"
    BALL = "ball"


def contact_race(race: Race | str, name: str = "race") -> Race:
    """``race`` as a raceway of a contact (:attr:`Race.INNER` or :attr:`Race.OUTER`); a ball or
    any other value is a one-line :class:`ConfigError` naming ``name``."""
    r = parse_enum(Race, race, name)
    if r is Race.BALL:
        raise ConfigError(f"{name} = 'ball' is invalid; valid: inner, outer (a raceway)")
    return r


class DefectProfile(enum.Enum):
    """How an element crossing a local defect loses support. A slot across the track:
    ``GEOMETRIC`` (the ball rests on the nearer edge; seed VSM eq. (2) evaluated along the path,
    continuous) or ``RECTANGULAR`` (the constant maximum drop ``h_min`` over the defect's extent,
    seed VSM eqs. (1)–(3)). ``PIT``: a round pit of diameter ``width`` (CWRU's EDM faults)
    narrower than the contact ellipse across the track; the contact beside it keeps carrying
    the ball (:mod:`bearingsim.dynamics.defect_pit`; ring and rotor models). The ring models default
    to seed VSM's rectangle (with the retention factor of its eq. (11)), the rotor model to the
    geometric slot; the IAS model follows seed IAS eqs. (19)–(28)."""

    GEOMETRIC = "geometric"
    RECTANGULAR = "rectangular"
    PIT = "pit"


#: reference groove conformities ``r / D_w`` of radial ball bearings, inner and outer raceway
#: [-] (ISO/TS 16281:2008 §6.3; the same values underlie ISO 281's ratings, ISO/TR 1281-1)
ISO_INNER_CONFORMITY = 0.52
ISO_OUTER_CONFORMITY = 0.53

#: Largest defect-centre azimuth, either sign [rad]: two turns (the scenario keys give the left
#: edge within one turn, +/- 360 deg, and the centre lies half the defect's extent past it); a
#: larger angle only loses digits of its position.
DEFECT_ANGLE_MAX = 4.0 * math.pi

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
    race : Race or {"inner", "outer", "ball"}
        Raceway carrying the defect, or ``"ball"``: one ball carries it (ring and rotor models; its
        ``angle`` is then the ball's spin angle of the defect centre at ``t = 0``, 0 = facing
        the outer race).
    width : float
        Width ``b`` (``L_d`` in seed IAS) along the raceway [m], > 0 (default: CWRU 0.007 in).
        Each model states the widths it admits (the element must span the defect).
    depth : float
        Depth ``h_d`` [m], > 0 (default: the CWRU EDM depth 0.011 in). The IAS model does not use
        it (seed IAS assumes the spall deeper than the roller's drop).
    angle : float
        Azimuth of the defect **centre** at ``t = 0`` [rad], in [-4 pi, 4 pi]
        (:data:`DEFECT_ANGLE_MAX`), from +y towards +x (the project convention); ``pi`` =
        6 o'clock, the bottom of a horizontal machine (CWRU ``@6``). An inner-race defect turns
        with the shaft from there.
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
        _set(
            self,
            "angle",
            check_range(
                "defect_angle_rad", self.angle, -DEFECT_ANGLE_MAX, DEFECT_ANGLE_MAX, unit="rad"
            ),
        )


@dataclass(frozen=True)
class DefectGeometry:
    """Geometric quantities of a defect on a given bearing (seed VSM eqs. (1)–(3)).

    Attributes
    ----------
    race : Race
        Raceway (or :attr:`Race.BALL`).
    race_radius : float
        Raceway radius ``r_i`` or ``r_o`` [m] (the ball radius for a ball defect).
    h_s : float
        Drop of a ball resting on both edges without touching the bottom, eq. (2) [m] (ball
        defect: the loss of approach at the outer-race contact).
    h_min : float
        Maximum drop ``min(h_d, h_s)``, eq. (1) [m] (ball defect: at the outer-race contact).
    delta_beta : float
        Central angle spanned by the defect on its raceway, eq. (3) [rad] (ball defect: on the
        ball, ``2 arcsin(b/d)``).
    edge_angle : float
        Azimuth of the defect's left (lower-azimuth) edge at ``t = 0``, ``beta_0`` of seed VSM
        [rad]: the defect centre less half the extent (ball defect: the spin angle).
    h_min_inner : float or None
        Ball defect: the maximum loss of approach at the inner-race contact [m] (None for a
        raceway defect).
    h_s_inner : float or None
        Ball defect: eq. (2)'s drop at the inner-race contact, before the depth caps it
        (``h_min_inner = min(h_d, h_s_inner)``) [m] (None for a raceway defect).
    """

    race: Race
    race_radius: float
    h_s: float
    h_min: float
    delta_beta: float
    edge_angle: float
    h_min_inner: float | None = None
    h_s_inner: float | None = None


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
    if defect.race is Race.BALL:
        # the same chords (eq. (2)) with the roles swapped: the raceway's surface enters the
        # slot on the ball, convex inner race deeper, concave outer race shallower
        ri = bearing.inner_raceway_radius
        ro = bearing.outer_raceway_radius
        h_o = ball_chord - (ro - math.sqrt(ro * ro - half * half))
        h_i = ball_chord + (ri - math.sqrt(ri * ri - half * half))
        check_defect_depth(bearing, defect)
        dpsi = 2.0 * math.asin(b / d)  # the slot's central angle on the ball
        return DefectGeometry(
            Race.BALL, r, h_o, min(defect.depth, h_o), dpsi, defect.angle - 0.5 * dpsi,
            min(defect.depth, h_i), h_i,
        )  # fmt: skip
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
    if race is Race.BALL:
        return 0.5 * bearing.element_diameter  # a slot in a ball is shallower than its radius
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
        what = (
            f"{defect.race.value} ring wall"
            if known
            else (f"{defect.race.value} element diameter (no bore/outer diameter given)")
        )
        if defect.race is Race.BALL:
            what = "ball radius"
        raise ConfigError(
            f"defect_depth_m = {defect.depth:.6g} m is not less than the {what} {wall:.6g} m "
            f"of {bearing.id}; valid range (0, {wall:.6g}) m"
        )
    return defect.depth


def check_pit_depth(bearing: Bearing, defect: Defect) -> float:
    """Refuse a pit (:attr:`DefectProfile.PIT`) shallower than a ball sinks into it: the pit
    model has the ball held by the groove beside the pit, never touching its bottom. The bound
    is seed VSM eq. (2) for a slot as wide as the pit's diameter, the most a ball can sink into
    it (the rim across the track holds it higher), at each contact the pit meets (a ball's
    pit: the outer and the inner race; :func:`defect_geometry`'s ``h_s``, ``h_s_inner``).
    Returns the depth [m]."""
    g = defect_geometry(bearing, defect)
    sag = g.h_s if g.h_s_inner is None else max(g.h_s, g.h_s_inner)
    if not defect.depth > sag:
        raise ConfigError(
            f"defect_depth_m = {defect.depth:.6g} m is not deeper than a ball sinks into a pit "
            f"of diameter {defect.width:.6g} m ({sag:.3g} m) with defect_profile = 'pit'; "
            f"valid range ({sag:.3g}, inf) m, or a slot profile (geometric, rectangular)"
        )
    return defect.depth


def check_unused_defect(bearing: Bearing, width: float, depth: float) -> None:
    """The defect keys of a scenario without a fault (``fault = "none"``): unused, but refused
    (one-line :class:`ConfigError`, as for a fault of the outer ring) when neither raceway of
    ``bearing`` could have a defect of ``width`` x ``depth`` [m] (``--defect-width-m 1e30``
    without ``--fault`` was accepted)."""
    first: ConfigError | None = None
    for race in (Race.OUTER, Race.INNER):
        try:
            d = Defect(race, width, depth)
            defect_geometry(bearing, d)
            check_defect_depth(bearing, d)
            return
        except ConfigError as exc:
            first = first or exc
    assert first is not None
    raise first


def raceway_radius(bearing: Bearing, race: Race) -> float:
    """Raceway radius ``r_i`` or ``r_o`` [m] of ``race``."""
    return bearing.inner_raceway_radius if race is Race.INNER else bearing.outer_raceway_radius


def angular_extent(bearing: Bearing, race: Race | str, width: float) -> float:
    """Central angle ``Delta_beta = 2 arcsin(b / (2 r_race))`` spanned by a defect of width ``b``
    [m] on ``race`` (seed VSM eq. (3)) [rad]."""
    rr = raceway_radius(bearing, contact_race(race, "fault_race"))
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
        Raceway, or ``"ball"``.
    width, depth : float
        Defect width ``b`` and depth ``h_d`` [m].
    edge_angle : float
        Left-edge azimuth ``beta_0`` [rad] (ball: the edge's spin angle, 0 = facing the outer
        race).
    """
    race = parse_enum(Race, race, "fault_race")
    w = check_positive("defect_width_m", width, "m")
    if race is Race.BALL:  # the edge's spin angle; the slot spans 2 arcsin(b/d) of the ball
        ext = 2.0 * math.asin(min(1.0, w / bearing.element_diameter))
    else:
        ext = angular_extent(bearing, race, w)
    return Defect(race, w, depth, edge_angle + 0.5 * ext)
