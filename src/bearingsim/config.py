"""Scenario schema: TOML/dict → validated :class:`Scenario` (clear one-line errors).

A scenario file holds exactly the keys below (SI units; the suffix names the unit; angles in
degrees and speed in r/min at this edge only). Any other key is an error naming the valid keys.

============================  ==============  ===================================================
key                           default         meaning
============================  ==============  ===================================================
``model``                     ``"vsm"``       ``vsm`` | ``dem`` | ``tvsm`` | ``rotor`` (``Model``)
``bearing``                   ``"6205"``      catalogue id (seed VSM table 1 bearing)
``bearing_file``              –               user bearing TOML (instead of ``bearing``)
``fault``                     ``"none"``      ``none`` | ``outer`` | ``inner``
``defect_width_m``            1.778e-4        defect width b along the raceway [m] (CWRU 0.007 in)
``defect_depth_m``            2.794e-4        defect depth h_d [m] (CWRU EDM depth 0.011 in)
``defect_angle_deg``          10.0            defect left edge at t = 0, beta_0 [deg] (seed table 1)
``first_ball_angle_deg``      0.0             ball 1 azimuth at t = 0, alpha_0 [deg] (seed table 1)
``rpm``                       1750.0          shaft speed [r/min] (seed table 1)
``fx_n``, ``fy_n``            10.0, 50.0      radial force on the inner ring [N] (seed table 1)
``duration_s``                1.0             simulated time [s]
``fs_hz``                     48000.0         output sample rate [Hz] (CWRU rate)
``seed``                      0               seed of the measurement noise (integer >= 0)
``noise_rms_m_s2``            0.0             RMS of white measurement noise on the accelerations
``mass_kg``                   by fault        vibrating mass m; seed table 1: 0.063 (outer ring,
                                              also for ``none``), 0.045 (inner ring, inner fault)
``damping_n_s_m``             300.0           c_eq (seed table 1)
``stiffness_n_m15``           Hertz           ball constant K [N/m^1.5] override (seed eq. (10))
``clearance_m``               bearing         diametral clearance P_d [m] override (>= 0)
``retention_factor``          eq. (11)        prescribed constant gamma in [0, 1] for a ball over
                                              the defect (seed figs. 6–7); default: eq. (11)
``load_zone_half_angle_deg``  contact         fixed load-zone half angle psi_L (seed eq. (14)
                                              literal); default: the contact decides
``dt_s``                      auto            RK4 step [s]; must divide 1/fs_hz into an integer
                                              number of steps (rounded); auto: omega_max dt <= 0.35
``solver``                    ``"rk4"``       ``rk4`` (fixed step) | ``dopri5`` (adaptive check)
``per_ball``                  false           also store per-ball loads and deformations
============================  ==============  ===================================================

Keys of the bearing–rotor–housing model (``model = "rotor"``, seed ROTOR, SPEC §2; the ring-model
keys ``bearing``, ``fault``, ``defect_angle_deg``, ``first_ball_angle_deg``, ``fx_n``, ``fy_n``,
``mass_kg``, ``damping_n_s_m``, ``stiffness_n_m15``, ``clearance_m``, ``retention_factor`` and
``load_zone_half_angle_deg`` are not used by it; ``fault`` must stay ``"none"``):

============================  ==============  ===================================================
key                           default         meaning
============================  ==============  ===================================================
``de_bearing``, ``fe_bearing``  6205-cwru,    drive-end / fan-end catalogue ids (CWRU motor)
                                6203-cwru
``de_fault``, ``fe_fault``    ``"none"``      defect of each bearing: none | outer | inner
                                              (width and depth from ``defect_width_m/_depth_m``)
``de_defect_angle_deg``,      180.0           defect **centre** azimuth at t = 0 [deg], from +y
``fe_defect_angle_deg``                       towards +x (180 = 6 o'clock, CWRU ``OR@6``)
``disks``                     9               number of equal disks carrying the rotor mass
``disk_positions_mm``         equal spacing   disk positions from the DE bearing [mm] (list)
``distributed_rotor``         false           rotor mass spread along the shaft instead of disks
``n_elements``                auto            minimum number of beam elements
``shaft_mass_model``          ``"lumped"``    lumped (half at each bearing, seed) | distributed
``housing_mass_kg``           6.638           mass of each housing [kg] (Sawalhi & Randall 2008
                                              pedestal, as used for CWRU by Ruan et al. 2022)
``housing_stiffness_n_m``     1.51e7          housing mount stiffness, X and Y [N/m] (same source)
``housing_damping_n_s_m``     2210.7          housing mount damping, X and Y [N s/m] (same source)
``contact_damping_n_s_m``     50.0            damping of each ball-race contact [N s/m]
``gravity``                   true            gravity (-y) on every mass
``unbalance_kg_m``            0.0             static unbalance m e of the rotor [kg m]
``antialias``                 true            4x (2x above 24 kHz) internal sampling and FIR
                                              decimation of the accelerations (like a DAQ)
============================  ==============  ===================================================
"""

from __future__ import annotations

import dataclasses
import enum
import math
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from .errors import ConfigError, check_positive, check_range, read_toml


class Model(enum.Enum):
    """Time-domain models available to :func:`bearingsim.simulate`."""

    VSM = "vsm"
    DEM = "dem"
    TVSM = "tvsm"
    ROTOR = "rotor"


class Solver(enum.Enum):
    """Time integrator."""

    RK4 = "rk4"
    DOPRI5 = "dopri5"


#: maximum number of output samples of one simulation (memory guard)
MAX_SAMPLES = 50_000_000


@dataclass(frozen=True)
class Scenario:
    """One simulation: every input, validated (see the module docstring for the keys)."""

    model: Model = Model.VSM
    bearing: str | None = "6205"
    bearing_file: str | None = None
    fault: str = "none"
    defect_width_m: float = 0.007 * 25.4e-3
    defect_depth_m: float = 0.011 * 25.4e-3
    defect_angle_deg: float = 10.0
    first_ball_angle_deg: float = 0.0
    rpm: float = 1750.0
    fx_n: float = 10.0
    fy_n: float = 50.0
    duration_s: float = 1.0
    fs_hz: float = 48000.0
    seed: int = 0
    noise_rms_m_s2: float = 0.0
    mass_kg: float | None = None
    damping_n_s_m: float = 300.0
    stiffness_n_m15: float | None = None
    clearance_m: float | None = None
    retention_factor: float | None = None
    load_zone_half_angle_deg: float | None = None
    dt_s: float | None = None
    solver: Solver = Solver.RK4
    per_ball: bool = False
    # bearing-rotor-housing model (model = "rotor"); see the second table above
    de_bearing: str = "6205-cwru"
    fe_bearing: str = "6203-cwru"
    de_fault: str = "none"
    fe_fault: str = "none"
    de_defect_angle_deg: float = 180.0
    fe_defect_angle_deg: float = 180.0
    disks: int = 9
    disk_positions_mm: tuple[float, ...] | None = None
    distributed_rotor: bool = False
    n_elements: int | None = None
    shaft_mass_model: str = "lumped"
    housing_mass_kg: float = 6.638
    housing_stiffness_n_m: float = 1.51e7
    housing_damping_n_s_m: float = 2210.7
    contact_damping_n_s_m: float = 50.0
    gravity: bool = True
    unbalance_kg_m: float = 0.0
    antialias: bool = True

    def __post_init__(self) -> None:
        s = object.__setattr__
        try:
            s(self, "model", Model(self.model))
        except ValueError:
            raise ConfigError(
                f"model = {self.model!r} is invalid; valid: " + ", ".join(m.value for m in Model)
            ) from None
        try:
            s(self, "solver", Solver(self.solver))
        except ValueError:
            raise ConfigError(
                f"solver = {self.solver!r} is invalid; valid: " + ", ".join(m.value for m in Solver)
            ) from None
        if self.fault not in ("none", "outer", "inner"):
            raise ConfigError(f"fault = {self.fault!r} is invalid; valid: none, outer, inner")
        if self.bearing_file is not None:
            s(self, "bearing", None)
        elif not isinstance(self.bearing, str) or not self.bearing:
            raise ConfigError(f"bearing = {self.bearing!r} is invalid; valid: a catalogue id")
        s(self, "defect_width_m", check_positive("defect_width_m", self.defect_width_m, "m"))
        s(self, "defect_depth_m", check_positive("defect_depth_m", self.defect_depth_m, "m"))
        s(
            self,
            "defect_angle_deg",
            check_range("defect_angle_deg", self.defect_angle_deg, -360.0, 360.0, unit="deg"),
        )
        s(
            self,
            "first_ball_angle_deg",
            check_range(
                "first_ball_angle_deg", self.first_ball_angle_deg, -360.0, 360.0, unit="deg"
            ),
        )
        s(self, "rpm", check_positive("rpm", self.rpm, "r/min"))
        s(self, "fx_n", check_range("fx_n", self.fx_n, unit="N"))
        s(self, "fy_n", check_range("fy_n", self.fy_n, unit="N"))
        s(self, "duration_s", check_positive("duration_s", self.duration_s, "s"))
        s(self, "fs_hz", check_positive("fs_hz", self.fs_hz, "Hz"))
        n = round(self.duration_s * self.fs_hz)
        if n < 2 or n > MAX_SAMPLES:
            raise ConfigError(
                f"duration_s * fs_hz = {self.duration_s * self.fs_hz:.6g} samples is out of "
                f"range; valid range [2, {MAX_SAMPLES}] samples"
            )
        if isinstance(self.seed, bool) or not isinstance(self.seed, int) or self.seed < 0:
            raise ConfigError(f"seed = {self.seed!r} is invalid; valid range [0, inf) integer")
        s(
            self,
            "noise_rms_m_s2",
            check_range("noise_rms_m_s2", self.noise_rms_m_s2, 0.0, unit="m/s^2"),
        )
        if self.mass_kg is not None:
            s(self, "mass_kg", check_positive("mass_kg", self.mass_kg, "kg"))
        s(
            self,
            "damping_n_s_m",
            check_range("damping_n_s_m", self.damping_n_s_m, 0.0, unit="N s/m"),
        )
        if self.stiffness_n_m15 is not None:
            s(
                self,
                "stiffness_n_m15",
                check_positive("stiffness_n_m15", self.stiffness_n_m15, "N/m^1.5"),
            )
        if self.clearance_m is not None:
            s(self, "clearance_m", check_range("clearance_m", self.clearance_m, 0.0, unit="m"))
        if self.retention_factor is not None:
            s(
                self,
                "retention_factor",
                check_range("retention_factor", self.retention_factor, 0.0, 1.0),
            )
        if self.load_zone_half_angle_deg is not None:
            s(
                self,
                "load_zone_half_angle_deg",
                check_range(
                    "load_zone_half_angle_deg",
                    self.load_zone_half_angle_deg,
                    0.0,
                    180.0,
                    lo_open=True,
                    hi_open=True,
                    unit="deg",
                ),
            )
        if self.dt_s is not None:
            dt = check_positive("dt_s", self.dt_s, "s")
            if dt > (1.0 + 1e-9) / self.fs_hz:
                raise ConfigError(
                    f"dt_s = {dt:.6g} s is larger than the output interval 1/fs_hz; valid range "
                    f"(0, {1.0 / self.fs_hz:.6g}] s"
                )
            s(self, "dt_s", dt)
        if not isinstance(self.per_ball, bool):
            raise ConfigError(f"per_ball = {self.per_ball!r} is invalid; valid: true or false")
        self._check_rotor_keys()

    def _check_rotor_keys(self) -> None:
        """Types and simple ranges of the rotor keys (the rotor model validates the rest when
        it builds its :class:`~bearingsim.dynamics.rotor_config.RotorConfig`)."""
        s = object.__setattr__
        for name in ("de_fault", "fe_fault"):
            if getattr(self, name) not in ("none", "outer", "inner"):
                raise ConfigError(
                    f"{name} = {getattr(self, name)!r} is invalid; valid: none, outer, inner"
                )
        if self.model is Model.ROTOR and self.fault != "none":
            raise ConfigError(
                f"fault = {self.fault!r} is not used by model rotor; valid: none (give the "
                "defects with de_fault / fe_fault)"
            )
        for name in ("de_bearing", "fe_bearing"):
            if not isinstance(getattr(self, name), str) or not getattr(self, name):
                raise ConfigError(
                    f"{name} = {getattr(self, name)!r} is invalid; valid: a catalogue id"
                )
        for name in ("de_defect_angle_deg", "fe_defect_angle_deg"):
            s(self, name, check_range(name, getattr(self, name), -360.0, 360.0, unit="deg"))
        for name, lo in (("disks", 1), ("n_elements", 1)):
            v = getattr(self, name)
            if v is None and name == "n_elements":
                continue
            if isinstance(v, bool) or not isinstance(v, int) or v < lo:
                raise ConfigError(f"{name} = {v!r} is invalid; valid range [{lo}, inf) integer")
        if self.disk_positions_mm is not None:
            try:
                pos = tuple(float(v) for v in self.disk_positions_mm)
            except (TypeError, ValueError):
                raise ConfigError(
                    f"disk_positions_mm = {self.disk_positions_mm!r} is invalid; valid: a list "
                    "of positions [mm]"
                ) from None
            if not pos:
                raise ConfigError("disk_positions_mm = [] is invalid; valid: a non-empty list")
            s(self, "disk_positions_mm", pos)
        if self.shaft_mass_model not in ("lumped", "distributed"):
            raise ConfigError(
                f"shaft_mass_model = {self.shaft_mass_model!r} is invalid; valid: lumped, "
                "distributed"
            )
        s(self, "housing_mass_kg", check_positive("housing_mass_kg", self.housing_mass_kg, "kg"))
        s(
            self,
            "housing_stiffness_n_m",
            check_positive("housing_stiffness_n_m", self.housing_stiffness_n_m, "N/m"),
        )
        s(
            self,
            "housing_damping_n_s_m",
            check_range("housing_damping_n_s_m", self.housing_damping_n_s_m, 0.0, unit="N s/m"),
        )
        s(
            self,
            "contact_damping_n_s_m",
            check_range("contact_damping_n_s_m", self.contact_damping_n_s_m, 0.0, unit="N s/m"),
        )
        s(
            self,
            "unbalance_kg_m",
            check_range("unbalance_kg_m", self.unbalance_kg_m, 0.0, unit="kg m"),
        )
        for name in ("distributed_rotor", "gravity", "antialias"):
            if not isinstance(getattr(self, name), bool):
                raise ConfigError(
                    f"{name} = {getattr(self, name)!r} is invalid; valid: true or false"
                )

    # ------------------------------------------------------------------ conversions
    @property
    def n_samples(self) -> int:
        """Number of output samples ``round(duration_s * fs_hz)`` [-]."""
        return int(round(self.duration_s * self.fs_hz))

    @property
    def shaft_hz(self) -> float:
        """Shaft frequency ``rpm / 60`` [Hz]."""
        return self.rpm / 60.0

    @property
    def resolved_mass_kg(self) -> float:
        """Vibrating mass [kg]: given, else seed table 1 (0.045 inner fault, 0.063 otherwise)."""
        if self.mass_kg is not None:
            return self.mass_kg
        return 0.045 if self.fault == "inner" else 0.063

    def to_dict(self) -> dict[str, Any]:
        """All keys as plain TOML/JSON values (``None`` = default)."""
        d = dataclasses.asdict(self)
        d["model"] = self.model.value
        d["solver"] = self.solver.value
        return d

    def replace(self, **changes: Any) -> Scenario:
        """Copy with ``changes`` (validated)."""
        return dataclasses.replace(self, **changes)

    @classmethod
    def from_dict(cls, data: dict[str, Any], origin: str = "<scenario>") -> Scenario:
        """Build from the documented keys; unknown keys raise :class:`ConfigError`."""
        if not isinstance(data, dict):
            raise ConfigError(f"{origin}: a scenario must be a table of keys")
        valid = [f.name for f in dataclasses.fields(cls)]
        unknown = sorted(set(data) - set(valid))
        if unknown:
            raise ConfigError(
                f"{origin}: unknown key {unknown[0]!r}; valid keys: " + ", ".join(valid)
            )
        try:
            return cls(**data)
        except ConfigError as exc:
            raise ConfigError(f"{origin}: {exc}") from None

    @classmethod
    def from_toml(cls, path: str | Path) -> Scenario:
        """Read a scenario TOML file (keys as in the module docstring)."""
        p = Path(path)
        data = read_toml(p, "scenario file")
        if "bearing_file" in data and isinstance(data["bearing_file"], str):
            bf = Path(data["bearing_file"])
            if not bf.is_absolute():
                data["bearing_file"] = str(p.parent / bf)
        return cls.from_dict(data, origin=p.name)

    @property
    def defect_angle_rad(self) -> float:
        """beta_0 [rad]."""
        return math.radians(self.defect_angle_deg)
