"""Scenarios: the inputs of one time-domain simulation, one schema per model family.

A scenario is a flat table of keys (TOML file, dict or keyword arguments) whose ``model`` key
selects the family and so the schema:

- :class:`RingScenario` — ``model = "vsm" | "dem" | "tvsm"``: one ball bearing with a local defect
  (seed VSM, Guo et al. 2025, and its two baselines);
- :class:`RotorScenario` — ``model = "rotor"``: the bearing–rotor–housing system of the CWRU rig
  (seed ROTOR, Liu et al. 2021);
- :class:`IasScenario` — ``model = "ias"``: the 3-DOF instantaneous-angular-speed model of a
  cylindrical roller bearing with an outer-race spall (seed IAS, Han, Guo & Fan 2025).

``Scenario(**keys)``, :meth:`Scenario.from_dict` and :meth:`Scenario.from_toml` return the
family's class (``model`` defaults to ``"vsm"``). Keys are SI with the unit in the name; speeds are
in r/min and angles in degrees at this edge only (azimuths from +y towards +x, the project
convention). A key of another family, an unknown key or a bad value raises a one-line
:class:`~bearingsim.errors.ConfigError`; a renamed key still works for one release with a
:class:`~bearingsim.errors.DeprecatedKeyWarning` (or, where its meaning changed, names its
replacement). The defaults are the seeds' cases; every literature default is defined once, here,
with its source, and the models import it from here.

Keys common to every family: ``model``, ``duration_s``, ``fs_hz`` (output sample rate [Hz]),
``dt_s`` (integration step [s]; ``None`` = the model's automatic choice), ``solver`` (``rk4`` |
``dopri5``). The family keys are listed in each class's docstring.

May import: :mod:`bearingsim.errors`, :mod:`bearingsim.geometry`. The model families import this
module, never the reverse (the runner of each family is found by :mod:`bearingsim.simulation`).
"""

from __future__ import annotations

import dataclasses
import enum
import math
import warnings
from dataclasses import dataclass
from pathlib import Path
from typing import Any, ClassVar

from .errors import (
    MAX_ACCELERATION,
    ConfigError,
    DeprecatedKeyWarning,
    check_int,
    check_positive,
    check_range,
    read_toml,
)
from .geometry import (
    CWRU_DEFECT_DEPTH_M,
    CWRU_DEFECT_WIDTH_M,
    HOLDING_PRELOAD_M,
    DefectProfile,
    parse_enum,
)


class Model(enum.Enum):
    """Time-domain models available to :func:`bearingsim.simulate`."""

    VSM = "vsm"
    DEM = "dem"
    TVSM = "tvsm"
    ROTOR = "rotor"
    IAS = "ias"


class Solver(enum.Enum):
    """Time integrator: fixed-step RK4 (every seed's solver) or adaptive Dormand–Prince 5(4)."""

    RK4 = "rk4"
    DOPRI5 = "dopri5"


#: maximum number of output samples of one simulation (memory guard)
MAX_SAMPLES = 50_000_000

# ------------------------------------------------------------------ literature defaults
#: seed VSM table 1: vibrating mass of an outer-race (also healthy) case [kg]
SEED_VSM_MASS_OUTER_KG = 0.063
#: seed VSM table 1: vibrating mass of an inner-race case [kg]
SEED_VSM_MASS_INNER_KG = 0.045
#: seed VSM table 1 / Petersen et al. (2015): equivalent damping c_eq [N s/m]
SEED_VSM_DAMPING_N_S_M = 300.0
#: seed VSM table 1: radial force on the inner ring along x [N]
SEED_VSM_FX_N = 10.0
#: seed VSM table 1: radial force on the inner ring along y [N]
SEED_VSM_FY_N = 50.0
#: largest ball diameter spread accepted [m] (ISO 3290-1 grade G200's lot variation, 10 µm)
MAX_BALL_SPREAD_M = 10e-6
#: largest composite RMS contact roughness accepted [m] (``contact_roughness_m``): ground bearing
#: surfaces are an order of magnitude below it (bearingsim.contact.rough)
MAX_ROUGHNESS_M = 1e-6
#: seed VSM table 1: shaft speed [r/min]
SEED_VSM_RPM = 1750.0
#: seed VSM table 1: the defect's left edge at t = 0, beta_0 [deg]
SEED_VSM_DEFECT_EDGE_DEG = 10.0
#: shaft speed of the ring and rotor scenarios unless given [r/min]: seed VSM table 1
DEFAULT_RPM = SEED_VSM_RPM

#: Default housing of each bearing, per direction (X and Y). The bearing pedestal of the 5-DOF
#: bearing model of Sawalhi & Randall (2008, *Mech. Syst. Signal Process.* 22, 1924–1951,
#: "pedestal": outer race + housing on a spring and damper to the base), with the values used
#: for the CWRU drive-end 6205 by Ruan, Chen, Gühmann, Yan & Li (2022), "Dynamics modeling of
#: bearing with defect in Modelica and application in direct transfer learning from simulation
#: to test bench for bearing fault diagnosis", *Electronics* 11(4), 622
#: (doi:10.3390/electronics11040622; also Ruan, Li & Gühmann, Proc. 14th Modelica Conf. 2021,
#: doi:10.3384/ecp21181373), whose simulated signals are compared with the CWRU records. The
#: numbers were read from the authors' published model (test-bearing parameters mp, kp, cp);
#: see docs/models.md (ROTOR, "Housings"). Mount frequency sqrt(k/m)/2pi = 240 Hz, damping
#: ratio 0.110. Mass [kg]:
HOUSING_MASS_KG = 6.638
#: the housing mount's stiffness, X and Y (same source as :data:`HOUSING_MASS_KG`) [N/m]
HOUSING_STIFFNESS_N_M = 1.51e7
#: the housing mount's damping, X and Y (same source as :data:`HOUSING_MASS_KG`) [N s/m]
HOUSING_DAMPING_N_S_M = 2210.7
#: damping of each ball–race contact [N s/m] (seed ROTOR eq. (11) ``C_v``; the seed gives no
#: value: an assumption, see docs/models.md)
CONTACT_DAMPING_N_S_M = 50.0
#: lowest natural frequency the rotor model resolves [Hz]: below it a root is a rigid-body mode;
#: the rotor's first bending mode (``bearingsim.dynamics.rotor.model.rotor_modes``) and each
#: housing's mount frequency ``sqrt(k/m) / (2 pi)`` must lie above it
MIN_MODE_HZ = 1e-3
#: seed ROTOR: the rotor mass carried by 9 equal disks
SEED_ROTOR_DISKS = 9

#: seed IAS §3.1 (NU204-ECP): motor torque M_z [N m]
SEED_IAS_TORQUE_N_M = 9.54
#: seed IAS §3.1: radial load F_y, pushing the shaft down [N]
SEED_IAS_FY_N = 400.0
#: seed IAS §3.1: inner ring and shaft mass m [kg]
SEED_IAS_MASS_KG = 1.3
#: seed IAS §3.1: radial damping C_s [N s/m]
SEED_IAS_RADIAL_DAMPING_N_S_M = 400.0
#: seed IAS §3.1: torsional damping C_T [N m s/rad]
SEED_IAS_TORSIONAL_DAMPING_N_M_S = 1.52
#: seed IAS §3.1, eq. (14): rolling-resistance coefficient mu [-]
SEED_IAS_ROLLING_RESISTANCE = 0.0015
#: seed IAS §3.1: spall width L_d [m]
SEED_IAS_SPALL_WIDTH_M = 1e-3
#: seed IAS §3.1: RK4 step [s]
SEED_IAS_DT_S = 1e-6
#: seed IAS §3.1: simulated time [s]
SEED_IAS_DURATION_S = 10.0
#: output sample rate of the IAS model unless given [Hz]: 20 seed steps per sample
IAS_FS_HZ = 50_000.0
#: polar inertia of the shaft [kg m^2]: not given by seed IAS; a 1.3 kg solid steel shaft of the
#: NU204's 20 mm bore, ``m r^2 / 2`` (an assumption, docs/models.md)
IAS_INERTIA_KG_M2 = 6.5e-5


#: A simulation through a measurement chain (``rig``) is meant to stand beside a measured
#: record, so the ring and rotor scenarios take these values for the keys a rig scenario leaves
#: unset (the values of ``bearingsim.side_by_side``, docs/models.md "Realistic defaults with a
#: rig"); without a rig the seeds' values stay. Random slip [%]: the middle of the 1-2 % real
#: bearings show (Randall & Antoni 2011, MSSP 25, 485-520, §2.1); the CWRU rig's own is not
#: published.
REALISM_SLIP_PERCENT = 1.5
#: drop of a ball across the slot: the ball rests on the nearer edge (``"geometric"``: 0 at the
#: edges, h_min at the centre; the rotor model's default, the ball path of Sawalhi & Randall
#: 2008), not the seed VSM's rectangle (h_min over the whole extent, a step at each edge), which
#: the seed comparisons keep
REALISM_DEFECT_PROFILE = "geometric"
#: composite RMS roughness of the ball-raceway contacts [m] (``contact_roughness_m``): the order
#: of ground and honed raceways (R_a 0.05-0.1 um, R_q ~ 1.25 R_a) with grade <= G20 balls (R_a
#: <= 0.02 um); the CWRU bearings' own is not published
REALISM_CONTACT_ROUGHNESS_M = 1.0e-7
#: the scenario keys of a realistic simulation beside a measurement, with their values
REALISM: dict[str, Any] = {
    "slip_percent": REALISM_SLIP_PERCENT,
    "defect_profile": REALISM_DEFECT_PROFILE,
    "contact_roughness_m": REALISM_CONTACT_ROUGHNESS_M,
}


# ------------------------------------------------------------------ helpers
#: the refusal of a ring scenario without radial load and without anything holding the ring
ZERO_RADIAL_LOAD = (
    "radial load |(fx_n, fy_n)| = 0 N: the ring position is undetermined; valid range (0, inf) "
    f"N (0 N only with a preload, clearance_m <= -{HOLDING_PRELOAD_M:g} m, or an axial load; "
    "models dem, tvsm)"
)


def ring_is_held(clearance_m: float | None, axial_load_n: float) -> bool:
    """Whether a preload (``clearance_m <= -HOLDING_PRELOAD_M`` [m]) or an axial load [N]
    holds a ring without a radial load (every ball loaded, the ring concentric)."""
    pre = clearance_m is not None and clearance_m <= -HOLDING_PRELOAD_M
    return pre or axial_load_n > 0.0


def profile_gamma_refusal(profile: str, retention_factor: float | None) -> None:
    """Refuse a prescribed retention factor with a profile other than the rectangle (a slot's
    drop along the path or a pit's share: the gamma would replace what the profile describes),
    in one line (the ring scenario before any run, and the model inputs)."""
    if retention_factor is not None and profile != "rectangular":
        raise ConfigError(
            f"defect_profile = {profile!r} with retention_factor = {retention_factor:g}: a "
            "prescribed gamma replaces the drop the profile describes; valid: defect_profile "
            "= 'rectangular' with a retention_factor, or no retention_factor"
        )


def secant_refusal(who: str, clearance_m: float | None, axial_load_n: float) -> None:
    """Refuse a preload (``clearance_m`` < 0 [m]) or an axial load [N] for ``who`` (the VSM and
    its static trace): their secant stiffness ``Q_j / (u.e_j)`` is measured from the
    concentric position, where a preloaded or axially loaded ball already carries load (seed
    VSM eqs. (17)-(18))."""
    if axial_load_n > 0.0:
        raise ConfigError(
            f"axial_load_n = {axial_load_n:.6g} N is out of range for {who}: its secant "
            "stiffness is measured from the concentric position, where an axially loaded "
            "ball already carries load; valid: 0 N (simulate an axial load with model dem "
            "or tvsm)"
        )
    if clearance_m is not None and clearance_m < 0.0:
        raise ConfigError(
            f"clearance_m = {clearance_m:.6g} m (a preload) is out of range for {who}: its secant "
            "stiffness needs P_d >= 0; valid range [0, inf) m (simulate a preloaded bearing "
            "with model dem or tvsm)"
        )


def _bool(name: str, value: Any) -> bool:
    if not isinstance(value, bool):
        raise ConfigError(f"{name} = {value!r} is invalid; valid: true or false")
    return value


def _choice(name: str, value: Any, valid: tuple[str, ...]) -> str:
    if value not in valid:
        raise ConfigError(f"{name} = {value!r} is invalid; valid: " + ", ".join(valid))
    return value


def _angle(name: str, value: Any) -> float:
    return check_range(name, value, -360.0, 360.0, unit="deg")


#: defect sites of the ring and rotor models (``ball``: ball 1 carries it; issue 16, item 2)
_RING_FAULTS = ("none", "outer", "inner", "ball")
#: values of ``defect_profile`` (ring and rotor models; :class:`~bearingsim.geometry.DefectProfile`)
DEFECT_PROFILES = tuple(m.value for m in DefectProfile)


def _family_of(model: Any) -> type[Scenario]:
    m = parse_enum(Model, model, "model")
    return _FAMILY[m]


def check_mount(stiffness: float, mass: float, name: str = "housing_stiffness_n_per_m") -> float:
    """Refuse a housing mount whose frequency ``sqrt(k/m) / (2 pi)`` is below
    :data:`MIN_MODE_HZ` (one-line :class:`ConfigError`): the rotor model cannot resolve it, and
    a mount that soft sags beyond what its static solution can represent (1e-300 N/m: 1e301 m).
    Returns ``stiffness`` [N/m] (``mass`` [kg])."""
    f = math.sqrt(stiffness / mass) / (2.0 * math.pi)
    if not f >= MIN_MODE_HZ:
        k_min = mass * (2.0 * math.pi * MIN_MODE_HZ) ** 2
        raise ConfigError(
            f"{name} = {stiffness:.6g} N/m puts the housing's mount frequency at {f:.3g} Hz, "
            f"below the {MIN_MODE_HZ:g} Hz the rotor model resolves; valid range "
            f"[{k_min:.6g}, inf) N/m for housing_mass_kg = {mass:.6g} kg"
        )
    return stiffness


# ------------------------------------------------------------------ the base schema
@dataclass(frozen=True)
class Scenario:
    """Inputs of one simulation; the base of the per-family schemas.

    ``Scenario(**keys)`` returns the family's class chosen by ``model`` (like
    :class:`pathlib.Path` returns a ``PosixPath``), so ``bearingsim.Scenario(model="rotor",
    disks=3)`` is a :class:`RotorScenario`.

    Parameters
    ----------
    model : Model or str
        The model (and so the family).
    duration_s : float
        Simulated time [s].
    fs_hz : float
        Output sample rate [Hz].
    dt_s : float or None
        Integration step [s]; ``None`` = the model's automatic or seed step.
    solver : Solver or str
        ``rk4`` (fixed step) or ``dopri5`` (adaptive, as a check).
    """

    #: the models of this family (filled per subclass)
    MODELS: ClassVar[tuple[Model, ...]] = ()
    #: the keys of this family in documentation order
    KEYS: ClassVar[tuple[str, ...]] = ()
    #: renamed keys: old -> new (same meaning; a warning) or old -> message (meaning changed)
    RENAMED: ClassVar[dict[str, str]] = {}
    #: whether ``dt_s`` must not exceed the output interval ``1/fs_hz``
    DT_WITHIN_OUTPUT: ClassVar[bool] = True

    #: the output rate a scenario takes when it sets none and its rig (if any) gives none [Hz]
    FS_DEFAULT_HZ: ClassVar[float] = 48000.0

    model: Model = Model.VSM
    duration_s: float = 1.0
    #: None: the rig's ``fs_hz`` (the rate it was identified at) when the scenario has a rig
    #: that gives one, else :attr:`FS_DEFAULT_HZ`
    fs_hz: float | None = None
    dt_s: float | None = None
    solver: Solver = Solver.RK4

    def __new__(cls, *args: Any, **kw: Any):
        if cls is Scenario:
            if args:
                raise ConfigError("Scenario(...) takes keyword arguments only (the scenario keys)")
            cls = _family_of(kw.get("model", Model.VSM))
        return object.__new__(cls)

    def __post_init__(self) -> None:
        s = object.__setattr__
        s(self, "model", parse_enum(Model, self.model, "model"))
        if self.model not in self.MODELS:
            raise ConfigError(
                f"model = {self.model.value!r} is not a model of {type(self).__name__}; valid: "
                + ", ".join(m.value for m in self.MODELS)
            )
        s(self, "solver", parse_enum(Solver, self.solver, "solver"))
        s(self, "duration_s", check_positive("duration_s", self.duration_s, "s"))
        auto = []
        if self.fs_hz is None:
            s(self, "fs_hz", self._default_fs_hz())
            auto.append("fs_hz")
        self.__dict__["auto_keys"] = tuple(auto)
        s(self, "fs_hz", check_positive("fs_hz", self.fs_hz, "Hz"))
        n = self.duration_s * self.fs_hz
        if not 2 <= round(n) <= MAX_SAMPLES:
            raise ConfigError(
                f"duration_s = {self.duration_s:.6g} s at fs_hz = {self.fs_hz:.6g} Hz gives "
                f"{n:.6g} output samples; valid range [2, {MAX_SAMPLES:.6g}] samples: duration_s "
                f"in [{2 / self.fs_hz:.6g}, {MAX_SAMPLES / self.fs_hz:.6g}] s at this fs_hz, or "
                f"fs_hz in [{2 / self.duration_s:.6g}, {MAX_SAMPLES / self.duration_s:.6g}] Hz at "
                "this duration_s"
            )
        if self.dt_s is not None:
            dt = check_positive("dt_s", self.dt_s, "s")
            if self.DT_WITHIN_OUTPUT and dt > (1.0 + 1e-9) / self.fs_hz:
                raise ConfigError(
                    f"dt_s = {dt:.6g} s is larger than the output interval 1/fs_hz; valid range "
                    f"(0, {1.0 / self.fs_hz:.6g}] s"
                )
            s(self, "dt_s", dt)
        self._validate()

    #: the seeds' values of the realism keys (:data:`REALISM`) of families that take them
    SEED_REALISM: ClassVar[dict[str, Any]] = {}

    def _default_fs_hz(self) -> float:
        """The output rate of a scenario that sets none [Hz]: its rig's ``fs_hz`` (the rate the
        rig was identified at: a profile of 12 kHz records gives 12 kHz signals), else
        :attr:`FS_DEFAULT_HZ`."""
        rig = getattr(self, "rig", None)
        if isinstance(rig, str) and rig:  # anything else: _check_rig says what is wrong
            from .rig import load_rig

            r = self.__dict__["loaded_rig"] = load_rig(rig)  # _check_rig validates this one
            if r.fs_hz is not None:
                return r.fs_hz
        return self.FS_DEFAULT_HZ

    def _validate(self) -> None:
        """Family checks (subclasses)."""

    # ------------------------------------------------------------------ conversions
    @property
    def n_samples(self) -> int:
        """Number of output samples ``round(duration_s * fs_hz)`` [-]."""
        return int(round(self.duration_s * self.fs_hz))

    def to_dict(self, rate: bool = True) -> dict[str, Any]:
        """Every key as a plain TOML/JSON value, in documentation order (``None`` = default).

        Keys the scenario resolved itself (:attr:`auto_keys`) are written ``None``, except the
        output rate ``fs_hz``, which stays a number (result and sweep readers take it from
        here) unless ``rate`` is false: the unset form, for a scenario to be completed and
        resolved again (a scenario file under command-line options, a sweep's base under a
        ``rig`` axis), where another rig may give another rate."""
        d = dataclasses.asdict(self)
        out = {k: d[k] for k in self.KEYS}
        for k, v in out.items():
            if isinstance(v, enum.Enum):
                out[k] = v.value
        for k in self.auto_keys:  # resolved from the rig: the default again
            if k != "fs_hz" or not rate:
                out[k] = None
        return out

    @property
    def auto_keys(self) -> tuple[str, ...]:
        """Keys left unset whose values this scenario chose (the realistic defaults with a
        ``rig``, else the seeds'; :data:`REALISM`) [-]."""
        return self.__dict__.get("auto_keys", ())

    @property
    def realism_defaults(self) -> dict[str, Any]:
        """The :data:`REALISM` keys this scenario left unset and took, because it has a
        ``rig``, at a value other than the seeds', with their values (empty without a rig)."""
        if getattr(self, "rig", None) is None:
            return {}
        seed = self.SEED_REALISM | {"fs_hz": self.FS_DEFAULT_HZ}
        return {
            k: getattr(self, k) for k in self.auto_keys if k in seed and getattr(self, k) != seed[k]
        }

    @property
    def defaults_record(self) -> dict[str, Any]:
        """What a result's ``meta["defaults"]`` records: the keys this scenario chose itself
        (:attr:`auto_keys`) with their values, and where they came from."""
        rig = getattr(self, "rig", None) is not None
        return {
            "keys": {k: getattr(self, k) for k in self.auto_keys},
            "source": "realistic defaults with a rig (bearingsim.config.REALISM)"
            if rig
            else "the seeds' defaults",
        }

    def replace(self, **changes: Any) -> Scenario:
        """Copy with ``changes`` (validated; ``model`` may only change within the family).
        Keys the scenario resolved itself (:attr:`auto_keys`) are resolved again."""
        changes = self._renamed(dict(changes), "replace")  # old spellings, as from_dict
        unknown = [k for k in changes if k not in self.KEYS]
        if unknown:  # a TypeError from the dataclass before
            raise ConfigError(
                f"replace: unknown key {unknown[0]!r}; valid keys: " + ", ".join(self.KEYS)
            )
        auto = {k: None for k in self.auto_keys if k not in changes}
        return dataclasses.replace(self, **auto, **changes)

    @classmethod
    def keys(cls) -> tuple[str, ...]:
        """The keys of this family (of every family, on :class:`Scenario`), documentation order."""
        if cls is Scenario:
            out: list[str] = []
            for fam in _FAMILIES:
                out += [k for k in fam.KEYS if k not in out]
            return tuple(out)
        return cls.KEYS

    @classmethod
    def from_dict(cls, data: dict[str, Any], origin: str = "<scenario>") -> Scenario:
        """Build from a table of keys (the family from ``model``; unknown keys raise)."""
        if not isinstance(data, dict):
            raise ConfigError(f"{origin}: a scenario must be a table of keys")
        try:
            fam = cls
            if cls is Scenario:
                fam = _family_of(data.get("model", Model.VSM))
            data = fam._renamed(dict(data), origin)
            unknown = [k for k in data if k not in fam.KEYS]
            if unknown:
                # the key given a value first (a command line passes its unset options as None:
                # `simulate --model rotor --bearing 6206` named bearing_file, the option not
                # given; exploratory testing, twenty-fourth session)
                k = next((u for u in unknown if data[u] is not None), unknown[0])
                other = [f for f in _FAMILIES if k in f.KEYS]
                where = (  # every family that has it (rig: the ring models' and the rotor's)
                    f" (a key of model {'/'.join(m.value for f in other for m in f.MODELS)})"
                    if other
                    else ""
                )
                if k in ("bearing", "bearing_file") and "de_bearing" in fam.KEYS:
                    where += "; this model's bearings are de_bearing and fe_bearing"
                raise ConfigError(f"unknown key {k!r}{where}; valid keys: " + ", ".join(fam.KEYS))
            return fam(**data)
        except ConfigError as exc:
            raise ConfigError(f"{origin}: {exc}") from None

    @classmethod
    def _renamed(cls, data: dict[str, Any], origin: str) -> dict[str, Any]:
        for old, new in cls.RENAMED.items():
            if old not in data:
                continue
            if new not in cls.KEYS:  # the meaning changed: say what replaces it
                raise ConfigError(f"key {old!r} was replaced: {new}")
            if new in data:
                raise ConfigError(f"keys {old!r} and {new!r} given; {old!r} is the old name")
            warnings.warn(
                f"{origin}: scenario key {old!r} is deprecated; use {new!r}",
                DeprecatedKeyWarning,
                stacklevel=3,
            )
            data[new] = data.pop(old)
        return data

    @classmethod
    def from_toml(cls, path: str | Path) -> Scenario:
        """Read a scenario TOML file (relative ``bearing_file`` paths are taken relative to it)."""
        p = Path(path)
        data = read_toml(p, "scenario file")
        if isinstance(data.get("bearing_file"), str):
            bf = Path(data["bearing_file"])
            if not bf.is_absolute():
                data["bearing_file"] = str(p.parent / bf)
        if relative_rig_file(data.get("rig")):
            data["rig"] = str(p.parent / data["rig"])  # a rig file beside the scenario
        return cls.from_dict(data, origin=p.name)


def is_rig_file(value: Any) -> bool:
    """Whether :func:`bearingsim.rig.load_rig` reads a ``rig`` value as a file (a ``*.toml``
    path, or a file of that name), not as a shipped profile."""
    if not isinstance(value, str | Path):
        return False
    p = Path(value)
    return p.suffix.lower() == ".toml" or p.is_file()


def relative_rig_file(value: Any) -> bool:
    """Whether a ``rig`` value names a rig file by a relative path (``*.toml``), which a
    scenario or sweep file takes relative to itself (a profile name or an absolute path is
    kept as it is)."""
    return (
        isinstance(value, str) and value.lower().endswith(".toml") and not Path(value).is_absolute()
    )


def _check_bearing(sc: Any, default: str) -> None:
    s = object.__setattr__
    if sc.bearing_file is not None:
        if not isinstance(sc.bearing_file, str) or not sc.bearing_file:
            raise ConfigError(f"bearing_file = {sc.bearing_file!r} is invalid; valid: a path")
        # by its absolute path: the scenario a result stores reruns from any folder (a
        # relative one read another folder's file, or none; twenty-first session)
        s(sc, "bearing_file", str(Path(sc.bearing_file).resolve()))
        s(sc, "bearing", None)
    elif sc.bearing is None:
        s(sc, "bearing", default)
    elif not isinstance(sc.bearing, str) or not sc.bearing:
        raise ConfigError(f"bearing = {sc.bearing!r} is invalid; valid: a catalogue id")


def check_roughness(value: object) -> float:
    """``contact_roughness_m`` [m] within [0, :data:`MAX_ROUGHNESS_M`], else a one-line
    :class:`~bearingsim.errors.ConfigError` (ring and rotor scenarios and models)."""
    return check_range("contact_roughness_m", value, 0.0, MAX_ROUGHNESS_M, unit="m")


def check_ball_spread(value: object) -> float:
    """``ball_diameter_spread_m`` [m] within [0, :data:`MAX_BALL_SPREAD_M`], else a one-line
    :class:`~bearingsim.errors.ConfigError` (ring and rotor scenarios and models)."""
    return check_range("ball_diameter_spread_m", value, 0.0, MAX_BALL_SPREAD_M, unit="m")


def _pass_jitter(sc: Scenario, needs_rk4: bool = True) -> None:
    """Check ``slip_percent`` and ``pocket_jitter_percent`` (each at most 10 %; the ring models'
    adaptive solver reads no pass-instant table, so there either needs ``solver = "rk4"``)."""
    for name in ("slip_percent", "pocket_jitter_percent"):
        v = check_range(name, getattr(sc, name), 0.0, 10.0, unit="%")
        object.__setattr__(sc, name, v)
        if needs_rk4 and v > 0.0 and sc.solver is not Solver.RK4:
            raise ConfigError(
                f"{name} = {v:g} % needs solver = 'rk4' (the adaptive solver has no slip); "
                f"valid: {name} = 0 with solver = '{sc.solver.value}'"
            )


def _resolve_realism(sc: Any) -> None:
    """Give the realism keys left unset (``None``) their values: :data:`REALISM`'s when the
    scenario has a ``rig``, else the seeds' (the family's ``SEED_REALISM``). An adaptive solver
    has no slip, so there the slip stays 0. The keys resolved here are kept in
    ``sc.auto_keys``: :meth:`Scenario.to_dict` gives them as ``None`` again and
    :meth:`Scenario.replace` resolves them anew (a copy without the rig returns to the seeds'
    values)."""
    auto = []
    for name, seed in sc.SEED_REALISM.items():
        if getattr(sc, name) is not None:
            continue
        v = REALISM[name] if sc.rig is not None else seed
        if name == "slip_percent" and sc.solver is not Solver.RK4:
            v = 0.0
        object.__setattr__(sc, name, v)
        auto.append(name)
    sc.__dict__["auto_keys"] = (*sc.auto_keys, *auto)


def _check_rig(sc: Any, channels: tuple[str, ...]) -> None:
    """A ``rig`` key: a loadable rig (one-line errors), its modes below the output's Nyquist
    frequency, its input one of the family's acceleration channels."""
    if sc.rig is None:
        return
    if not isinstance(sc.rig, str) or not sc.rig:
        raise ConfigError(f"rig = {sc.rig!r} is invalid; valid: a rig profile name or TOML file")
    from .rig import load_rig

    r = sc.__dict__.get("loaded_rig") or load_rig(sc.rig)  # loaded once when it set fs_hz
    if is_rig_file(sc.rig):  # a file by its absolute path: the scenario a result stores reruns
        object.__setattr__(sc, "rig", str(Path(sc.rig).resolve()))  # from any folder
    bad = r.rate_problem(sc.fs_hz)
    if bad is not None:  # the remedy is the run's rate, not the rig file's value
        raise ConfigError(
            f"fs_hz = {sc.fs_hz:g} Hz is too low for rig {r.name!r} ({bad[0]}); valid: fs_hz "
            f"above {r.min_rate_hz():.6g} Hz, or a rig identified at this rate"
        )
    if r.input_channel not in channels:
        raise ConfigError(
            f"rig {r.name!r}: input_channel {r.input_channel!r} is not an acceleration output of "
            f"model {sc.model.value}; valid: " + ", ".join(channels)
        )


# ------------------------------------------------------------------ ring models
@dataclass(frozen=True)
class RingScenario(Scenario):
    """One ball bearing with a local raceway defect: VSM (seed VSM), DEM, TVSM.

    ==============================  ==============  ================================================
    key                             default         meaning
    ==============================  ==============  ================================================
    ``model``                       ``"vsm"``       ``vsm`` | ``dem`` | ``tvsm``
    ``bearing``                     ``"6205"``      catalogue id (seed VSM table 1 bearing)
    ``bearing_file``                –               user bearing TOML (instead of ``bearing``)
    ``fault``                       ``"none"``      ``none`` | ``outer`` | ``inner`` | ``ball``
                                                    (ball: ball 1 carries the defect)
    ``defect_width_m``              1.778e-4        defect width b along the raceway (or across
                                                    the ball; a pit's diameter) [m] (CWRU
                                                    0.007 in)
    ``defect_depth_m``              2.794e-4        defect depth h_d [m] (CWRU EDM 0.011 in)
    ``defect_profile``              rectangular     drop of a ball across the defect:
                                    (geometric      ``rectangular`` (seed VSM eqs. (1)–(3): h_min
                                    with ``rig``)
                                                    over the whole extent) or ``geometric`` (the
                                                    ball rests on the nearer edge: 0 at the
                                                    edges, h_min at the centre; the rotor
                                                    model's) or ``pit`` (a round pit narrower
                                                    than the contact: the groove beside it
                                                    keeps carrying the ball; CWRU's EDM
                                                    faults); not with ``retention_factor``
    ``defect_edge_angle_deg``       10.0            the defect's **left edge** at t = 0, seed VSM
                                                    beta_0 [deg] (table 1); its centre is half the
                                                    defect's extent further on (ball: the edge's
                                                    spin angle, 0 = facing the outer race)
    ``first_ball_angle_deg``        0.0             ball 1 azimuth at t = 0, alpha_0 [deg]
    ``rpm``                         1750.0          shaft speed [r/min] (seed table 1)
    ``fx_n``, ``fy_n``              10.0, 50.0      radial force on the inner ring [N] (table 1)
    ``duration_s``                  1.0             simulated time [s]
    ``fs_hz``                       48000.0 (the    output sample rate [Hz] (CWRU rate; a rig's
                                    rig's with      ``fs_hz`` is the rate of the records it was
                                    ``rig``)        identified from)
    ``seed``                        0               seed of the measurement noise (integer >= 0)
    ``noise_rms_m_per_s2``          0.0             RMS of white measurement noise on the
                                                    accelerations [m/s^2]
    ``slip_percent``                0.0 (1.5        random slip: standard deviation of each
                                    with ``rig``)
                                                    ball-pass interval [% of its mean], 1–2 in
                                                    real bearings (Randall & Antoni 2011); 0 =
                                                    kinematic; needs ``solver = "rk4"``
    ``pocket_jitter_percent``       0.0             balls wandering in their pockets: standard
                                                    deviation of each ball-pass interval [%]
                                                    from independent moves of the pass instants
                                                    (no phase drift, unlike ``slip_percent``);
                                                    needs ``solver = "rk4"``
    ``ball_diameter_spread_m``      0.0             largest minus smallest ball diameter [m]
                                                    (ISO 3290-1 lot variation V_DwL: G10 0.5e-6,
                                                    G20 1e-6, G40 2e-6); unequal ball loads,
                                                    hence FTF lines with a race fault; 0 =
                                                    identical balls; at most 1e-5
    ``unbalance_n``                 0.0             amplitude of a radial force turning with the
                                                    shaft [N] (rotor unbalance m e w^2; ISO
                                                    21940-11 grades); less than the load
                                                    ``hypot(fx_n, fy_n)``
    ``axial_load_n``                0.0             constant axial force on the inner ring [N]
                                                    (dem, tvsm): the balls run at a contact
                                                    angle (Jones geometry), enough of it loads
                                                    every ball, and the fault lines move with
                                                    the angle (``docs/models.md``, "Axial
                                                    load"); 0 = the seeds' radial model
    ``contact_roughness_m``         0.0 (1e-7       composite RMS roughness sigma of the
                                    with ``rig``)
                                                    ball-raceway contacts [m] (0 to 1e-6): the
                                                    load law is Hertz's averaged over it, a
                                                    smooth onset where balls enter and leave
                                                    the load zone (``docs/models.md``, "Rough
                                                    contact onset"); 0 = Hertz (the seeds')
    ``mass_kg``                     by fault        vibrating mass m [kg]; seed table 1: 0.063
                                                    (outer ring, also ``none``), 0.045 (inner)
    ``damping_n_s_per_m``           300.0           c_eq [N s/m] (seed table 1)
    ``stiffness_n_per_m1_5``        Hertz           ball constant K [N/m^1.5] override (eq. (10))
    ``clearance_m``                 bearing         diametral clearance P_d [m] override;
                                                    negative = preload (dem, tvsm; the vsm
                                                    needs >= 0), within +/- ISO 5753-1 group 5
    ``retention_factor``            eq. (11)        prescribed constant gamma in [0, 1] for a ball
                                                    over the defect (seed figs. 6–7)
    ``load_zone_half_angle_deg``    contact         fixed load-zone half angle psi_L (seed eq. (14)
                                                    literal); default: the contact decides
    ``dt_s``                        auto            RK4 step [s], rounded to divide 1/fs_hz;
                                                    auto: omega_max dt <= 0.35
    ``solver``                      ``"rk4"``       ``rk4`` | ``dopri5`` (adaptive check)
    ``per_ball``                    false           also store per-ball loads and deformations
    ``antialias``                   with ``rig``    integrate at 4x ``fs_hz`` (2x above 24 kHz)
                                                    and FIR-decimate the accelerations, as a
                                                    data-acquisition chain does; default: on
                                                    when ``rig`` is set, else off (a boxcar mean
                                                    over 1/fs_hz, the seed comparisons' sampling;
                                                    ``docs/models.md``, "Sampling")
    ``rig``                         –               measurement chain applied to the output: a
                                                    shipped profile name or a rig TOML file
                                                    (:mod:`bearingsim.rig`; channel
                                                    ``acc_sensor``); with it, unset
                                                    ``slip_percent``, ``defect_profile`` and
                                                    ``contact_roughness_m`` take
                                                    :data:`REALISM`'s values
    ==============================  ==============  ================================================

    Renamed in 0.2.0 (same meanings; the old keys warn): ``defect_angle_deg`` →
    ``defect_edge_angle_deg``, ``noise_rms_m_s2`` → ``noise_rms_m_per_s2``, ``damping_n_s_m`` →
    ``damping_n_s_per_m``, ``stiffness_n_m15`` → ``stiffness_n_per_m1_5`` (the unit-suffix rule
    of ``docs/cli.md``: ``_per_`` divides).
    """

    MODELS: ClassVar[tuple[Model, ...]] = (Model.VSM, Model.DEM, Model.TVSM)
    #: the seeds' values of the :data:`REALISM` keys (a scenario without a rig)
    SEED_REALISM: ClassVar[dict[str, Any]] = {
        "slip_percent": 0.0,
        "defect_profile": "rectangular",
        "contact_roughness_m": 0.0,
    }
    KEYS: ClassVar[tuple[str, ...]] = (
        "model",
        "bearing",
        "bearing_file",
        "fault",
        "defect_width_m",
        "defect_depth_m",
        "defect_profile",
        "defect_edge_angle_deg",
        "first_ball_angle_deg",
        "rpm",
        "fx_n",
        "fy_n",
        "duration_s",
        "fs_hz",
        "seed",
        "noise_rms_m_per_s2",
        "slip_percent",
        "pocket_jitter_percent",
        "ball_diameter_spread_m",
        "unbalance_n",
        "axial_load_n",
        "contact_roughness_m",
        "mass_kg",
        "damping_n_s_per_m",
        "stiffness_n_per_m1_5",
        "clearance_m",
        "retention_factor",
        "load_zone_half_angle_deg",
        "dt_s",
        "solver",
        "per_ball",
        "antialias",
        "rig",
    )
    RENAMED: ClassVar[dict[str, str]] = {
        "defect_angle_deg": "defect_edge_angle_deg",
        "noise_rms_m_s2": "noise_rms_m_per_s2",
        "damping_n_s_m": "damping_n_s_per_m",
        "stiffness_n_m15": "stiffness_n_per_m1_5",
    }

    model: Model = Model.VSM
    bearing: str | None = "6205"
    bearing_file: str | None = None
    fault: str = "none"
    defect_width_m: float = CWRU_DEFECT_WIDTH_M
    defect_depth_m: float = CWRU_DEFECT_DEPTH_M
    defect_profile: str | None = None
    defect_edge_angle_deg: float = SEED_VSM_DEFECT_EDGE_DEG
    first_ball_angle_deg: float = 0.0
    rpm: float = DEFAULT_RPM
    fx_n: float = SEED_VSM_FX_N
    fy_n: float = SEED_VSM_FY_N
    seed: int = 0
    noise_rms_m_per_s2: float = 0.0
    slip_percent: float | None = None
    pocket_jitter_percent: float = 0.0
    ball_diameter_spread_m: float = 0.0
    unbalance_n: float = 0.0
    axial_load_n: float = 0.0
    contact_roughness_m: float | None = None
    mass_kg: float | None = None
    damping_n_s_per_m: float = SEED_VSM_DAMPING_N_S_M
    stiffness_n_per_m1_5: float | None = None
    clearance_m: float | None = None
    retention_factor: float | None = None
    load_zone_half_angle_deg: float | None = None
    per_ball: bool = False
    antialias: bool | None = None
    rig: str | None = None

    def _validate(self) -> None:
        s = object.__setattr__
        _resolve_realism(self)
        _check_bearing(self, "6205")
        _choice("fault", self.fault, _RING_FAULTS)
        s(self, "defect_width_m", check_positive("defect_width_m", self.defect_width_m, "m"))
        s(self, "defect_depth_m", check_positive("defect_depth_m", self.defect_depth_m, "m"))
        _choice("defect_profile", self.defect_profile, DEFECT_PROFILES)
        s(
            self,
            "defect_edge_angle_deg",
            _angle("defect_edge_angle_deg", self.defect_edge_angle_deg),
        )
        s(self, "first_ball_angle_deg", _angle("first_ball_angle_deg", self.first_ball_angle_deg))
        s(self, "rpm", check_positive("rpm", self.rpm, "r/min"))
        s(self, "fx_n", check_range("fx_n", self.fx_n, unit="N") + 0.0)  # -0.0 -> 0.0
        s(self, "fy_n", check_range("fy_n", self.fy_n, unit="N") + 0.0)
        s(self, "seed", check_int("seed", self.seed, 0))
        s(
            self,
            "noise_rms_m_per_s2",
            check_range(
                "noise_rms_m_per_s2", self.noise_rms_m_per_s2, 0.0, MAX_ACCELERATION, unit="m/s^2"
            ),
        )
        _pass_jitter(self)
        s(self, "ball_diameter_spread_m", check_ball_spread(self.ball_diameter_spread_m))
        s(self, "axial_load_n", check_range("axial_load_n", self.axial_load_n, 0.0, unit="N"))
        if self.clearance_m is not None:
            # negative = preload, bounded by the bearing (dynamics.ring.base.ModelInputs)
            s(self, "clearance_m", check_range("clearance_m", self.clearance_m, unit="m"))
        if self.model is Model.VSM:  # its secant stiffness: no preload, no axial load
            secant_refusal(f"model {self.model.value}", self.clearance_m, self.axial_load_n)
        fr = math.hypot(self.fx_n, self.fy_n)
        held = ring_is_held(self.clearance_m, self.axial_load_n)
        if fr == 0.0 and not held:
            raise ConfigError(ZERO_RADIAL_LOAD)
        # below the static load, unless a preload or axial load holds the ring (the peak
        # radial load is checked against the static capacity before the run)
        hi = math.inf if held else fr
        ub = check_range("unbalance_n", self.unbalance_n, 0.0, hi, hi_open=True, unit="N")
        s(self, "unbalance_n", ub)
        s(self, "contact_roughness_m", check_roughness(self.contact_roughness_m))
        if self.mass_kg is not None:
            s(self, "mass_kg", check_positive("mass_kg", self.mass_kg, "kg"))
        s(
            self,
            "damping_n_s_per_m",
            check_range("damping_n_s_per_m", self.damping_n_s_per_m, 0.0, unit="N s/m"),
        )
        if self.stiffness_n_per_m1_5 is not None:
            s(
                self,
                "stiffness_n_per_m1_5",
                check_positive("stiffness_n_per_m1_5", self.stiffness_n_per_m1_5, "N/m^1.5"),
            )
        if self.retention_factor is not None:
            s(
                self,
                "retention_factor",
                check_range("retention_factor", self.retention_factor, 0.0, 1.0),
            )
            if self.fault != "none":  # checked before any run (a sweep's plan)
                profile_gamma_refusal(self.defect_profile or "rectangular", self.retention_factor)
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
        _bool("per_ball", self.per_ball)
        if self.antialias is not None:
            _bool("antialias", self.antialias)
        _check_rig(self, ("acc_x", "acc_y"))

    @property
    def oversampling(self) -> int:
        """Internal samples per output sample [-]: 4 (2 above 24 kHz) with ``antialias`` (on by
        default when ``rig`` is set), else 1."""
        from .dynamics.sampling import oversampling_for

        on = self.rig is not None if self.antialias is None else self.antialias
        return oversampling_for(self.fs_hz) if on else 1

    @property
    def shaft_hz(self) -> float:
        """Shaft frequency ``rpm / 60`` [Hz]."""
        return self.rpm / 60.0

    @property
    def resolved_mass_kg(self) -> float:
        """Vibrating mass [kg]: given, else seed VSM table 1 (0.045 inner fault, 0.063 else)."""
        if self.mass_kg is not None:
            return self.mass_kg
        return SEED_VSM_MASS_INNER_KG if self.fault == "inner" else SEED_VSM_MASS_OUTER_KG

    @property
    def defect_edge_angle_rad(self) -> float:
        """Seed VSM beta_0, the defect's left edge at t = 0 [rad]."""
        return math.radians(self.defect_edge_angle_deg)


# ------------------------------------------------------------------ rotor model
@dataclass(frozen=True)
class RotorScenario(Scenario):
    """The bearing–rotor–housing system of the CWRU rig (seed ROTOR, SPEC §2).

    ==================================  ==============  ============================================
    key                                 default         meaning
    ==================================  ==============  ============================================
    ``model``                           ``"rotor"``
    ``de_bearing``, ``fe_bearing``      6205-cwru,      drive-end / fan-end catalogue ids (CWRU
                                        6203-cwru       motor)
    ``de_clearance_m``,                 catalogue       diametral clearance of each bearing [m];
    ``fe_clearance_m``                                  negative = preload (every ball loaded),
                                                        within +/- ISO 5753-1 group 5
    ``de_fault``, ``fe_fault``          ``"none"``      defect of each bearing: none | outer | inner
                                                        | ball
    ``defect_width_m``                  1.778e-4        defect width b [m] (CWRU 0.007 in)
    ``defect_depth_m``                  2.794e-4        defect depth h_d [m] (CWRU EDM 0.011 in)
    ``defect_profile``                  geometric       drop of a ball across the defect:
                                                        ``geometric`` (it rests on the nearer
                                                        edge), ``rectangular`` (h_min over
                                                        the extent, seed VSM) or ``pit`` (a
                                                        round pit narrower than the contact)
    ``de_defect_angle_deg``,            180.0           defect **centre** azimuth at t = 0 [deg]
    ``fe_defect_angle_deg``                             (180 = 6 o'clock, CWRU ``OR@6``; ball:
                                                        the slot's spin angle, 0 = facing the
                                                        outer race, advancing as the ball
                                                        spins, as the ring models' edge angle)
    ``rpm``                             1750.0          shaft speed [r/min]
    ``duration_s``, ``fs_hz``           1.0, 48000.0    simulated time [s], output sample rate [Hz]
                                        (``fs_hz``:     (a rig's ``fs_hz``: the rate of the records
                                        the rig's with  it was identified from)
                                        ``rig``)
    ``seed``, ``noise_rms_m_per_s2``    0, 0.0          white measurement noise on the accelerations
    ``disks``                           9 (one per      number of equal disks carrying the rotor
                                        position)       mass; with ``disk_positions_mm`` it must
                                                        equal their count (unset: it follows them)
    ``disk_positions_mm``               equal spacing   disk positions from the DE bearing [mm]
                                                        (list, strictly increasing)
    ``distributed_rotor``               false           rotor mass spread along the shaft instead
    ``n_elements``                      auto            minimum number of beam elements
    ``shaft_mass_model``                ``"lumped"``    lumped (half at each bearing, seed) |
                                                        distributed
    ``housing_mass_kg``                 6.638           mass of each housing [kg] (Sawalhi &
                                                        Randall 2008 pedestal, values of Ruan et
                                                        al. 2022)
    ``housing_stiffness_n_per_m``       1.51e7          housing mount stiffness, X and Y [N/m]
    ``housing_damping_n_s_per_m``       2210.7          housing mount damping, X and Y [N s/m]
    ``contact_damping_n_s_per_m``       50.0            damping of each ball–race contact [N s/m]
    ``contact_roughness_m``             0.0 (1e-7       composite RMS roughness of the ball-race
                                        with ``rig``)
                                                        contacts [m]: Hertz's law averaged over it
                                                        (0 = Hertz; as the ring models,
                                                        ``docs/models.md`` "Rough contact onset")
    ``gravity``                         true            gravity (-y) on every mass
    ``ball_inertia``                    true            balls are masses with a radial DOF (the
                                                        seed's); false: quasi-static (massless)
                                                        balls, the two contacts in series — a
                                                        3x larger step, valid while the balls'
                                                        radial mode (34–42 kHz, CWRU) lies well
                                                        above the output band
    ``axial_load_n``                    0.0             axial force each bearing carries [N] (a
                                                        wave spring's preload): the balls run at
                                                        the Jones contact angles (needs
                                                        ``ball_inertia = false``)
    ``unbalance_kg_m``                  0.0             static unbalance m e of the rotor [kg m]
    ``de_fx_n``, ``de_fy_n``,           0.0             extra constant force on the shaft at the
    ``fe_fx_n``, ``fe_fy_n``                            DE / FE bearing [N] (a coupling, belt or
                                                        test-rig load; +y up, gravity is -y: a
                                                        load pressing the shaft down is fy < 0);
                                                        its bearing carries it with the weight
    ``antialias``                       true            4x (2x above 24 kHz) internal sampling and
                                                        FIR decimation of the accelerations (like
                                                        a DAQ)
    ``slip_percent``                    0.0 (1.5        random slip of each bearing's cage: standard
                                        with ``rig``)
                                                        deviation of each ball-pass interval [%]
    ``pocket_jitter_percent``           0.0             balls wandering in their pockets: standard
                                                        deviation of each ball-pass interval [%]
                                                        from independent moves of the pass
                                                        instants (no phase drift)
    ``ball_diameter_spread_m``          0.0             largest minus smallest ball diameter in
                                                        each bearing [m] (ISO 3290-1 lot
                                                        variation; seeded per bearing)
    ``dt_s``, ``solver``                auto, rk4       integration step [s] and integrator
    ``per_ball``                        false           also store per-ball contact forces
    ``rig``                             –               measurement chain applied to the output
                                                        (:mod:`bearingsim.rig`; ``acc_sensor``);
                                                        with it, unset ``slip_percent`` and
                                                        ``contact_roughness_m`` take
                                                        :data:`REALISM`'s values
    ==================================  ==============  ============================================
    """

    MODELS: ClassVar[tuple[Model, ...]] = (Model.ROTOR,)
    #: the seed's values of the :data:`REALISM` keys (a scenario without a rig)
    SEED_REALISM: ClassVar[dict[str, Any]] = {
        "slip_percent": 0.0,
        "defect_profile": "geometric",
        "contact_roughness_m": 0.0,
    }
    RENAMED: ClassVar[dict[str, str]] = {
        "noise_rms_m_s2": "noise_rms_m_per_s2",
        "housing_stiffness_n_m": "housing_stiffness_n_per_m",
        "housing_damping_n_s_m": "housing_damping_n_s_per_m",
        "contact_damping_n_s_m": "contact_damping_n_s_per_m",
    }
    KEYS: ClassVar[tuple[str, ...]] = (
        "model",
        "de_bearing",
        "fe_bearing",
        "de_clearance_m",
        "fe_clearance_m",
        "de_fault",
        "fe_fault",
        "defect_width_m",
        "defect_depth_m",
        "defect_profile",
        "de_defect_angle_deg",
        "fe_defect_angle_deg",
        "rpm",
        "duration_s",
        "fs_hz",
        "seed",
        "noise_rms_m_per_s2",
        "slip_percent",
        "pocket_jitter_percent",
        "ball_diameter_spread_m",
        "disks",
        "disk_positions_mm",
        "distributed_rotor",
        "n_elements",
        "shaft_mass_model",
        "housing_mass_kg",
        "housing_stiffness_n_per_m",
        "housing_damping_n_s_per_m",
        "contact_damping_n_s_per_m",
        "contact_roughness_m",
        "gravity",
        "ball_inertia",
        "axial_load_n",
        "unbalance_kg_m",
        "de_fx_n",
        "de_fy_n",
        "fe_fx_n",
        "fe_fy_n",
        "antialias",
        "dt_s",
        "solver",
        "per_ball",
        "rig",
    )

    model: Model = Model.ROTOR
    de_bearing: str = "6205-cwru"
    fe_bearing: str = "6203-cwru"
    de_clearance_m: float | None = None
    fe_clearance_m: float | None = None
    de_fault: str = "none"
    fe_fault: str = "none"
    defect_width_m: float = CWRU_DEFECT_WIDTH_M
    defect_depth_m: float = CWRU_DEFECT_DEPTH_M
    defect_profile: str | None = None
    de_defect_angle_deg: float = 180.0
    fe_defect_angle_deg: float = 180.0
    rpm: float = DEFAULT_RPM
    seed: int = 0
    noise_rms_m_per_s2: float = 0.0
    slip_percent: float | None = None
    pocket_jitter_percent: float = 0.0
    ball_diameter_spread_m: float = 0.0
    disks: int | None = None
    disk_positions_mm: tuple[float, ...] | None = None
    distributed_rotor: bool = False
    n_elements: int | None = None
    shaft_mass_model: str = "lumped"
    housing_mass_kg: float = HOUSING_MASS_KG
    housing_stiffness_n_per_m: float = HOUSING_STIFFNESS_N_M
    housing_damping_n_s_per_m: float = HOUSING_DAMPING_N_S_M
    contact_damping_n_s_per_m: float = CONTACT_DAMPING_N_S_M
    contact_roughness_m: float | None = None
    gravity: bool = True
    ball_inertia: bool = True
    axial_load_n: float = 0.0
    unbalance_kg_m: float = 0.0
    de_fx_n: float = 0.0
    de_fy_n: float = 0.0
    fe_fx_n: float = 0.0
    fe_fy_n: float = 0.0
    antialias: bool = True
    per_ball: bool = False
    rig: str | None = None

    def _validate(self) -> None:
        s = object.__setattr__
        _resolve_realism(self)
        for name in ("de_fault", "fe_fault"):
            _choice(name, getattr(self, name), _RING_FAULTS)
        for name in ("de_bearing", "fe_bearing"):
            if not isinstance(getattr(self, name), str) or not getattr(self, name):
                raise ConfigError(
                    f"{name} = {getattr(self, name)!r} is invalid; valid: a catalogue id"
                )
        s(self, "defect_width_m", check_positive("defect_width_m", self.defect_width_m, "m"))
        s(self, "defect_depth_m", check_positive("defect_depth_m", self.defect_depth_m, "m"))
        _choice("defect_profile", self.defect_profile, DEFECT_PROFILES)
        for name in ("de_defect_angle_deg", "fe_defect_angle_deg"):
            s(self, name, _angle(name, getattr(self, name)))
        s(self, "rpm", check_positive("rpm", self.rpm, "r/min"))
        for name in ("de_clearance_m", "fe_clearance_m"):  # bounded by the bearing (rotor)
            if getattr(self, name) is not None:
                s(self, name, check_range(name, getattr(self, name), unit="m"))
        s(self, "seed", check_int("seed", self.seed, 0))
        s(
            self,
            "noise_rms_m_per_s2",
            check_range(
                "noise_rms_m_per_s2", self.noise_rms_m_per_s2, 0.0, MAX_ACCELERATION, unit="m/s^2"
            ),
        )
        if self.disks is not None:
            s(self, "disks", check_int("disks", self.disks, 1))
        if self.n_elements is not None:
            s(self, "n_elements", check_int("n_elements", self.n_elements, 1))
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
        self._resolve_disks()
        _choice("shaft_mass_model", self.shaft_mass_model, ("lumped", "distributed"))
        s(self, "housing_mass_kg", check_positive("housing_mass_kg", self.housing_mass_kg, "kg"))
        s(
            self,
            "housing_stiffness_n_per_m",
            check_positive("housing_stiffness_n_per_m", self.housing_stiffness_n_per_m, "N/m"),
        )
        check_mount(self.housing_stiffness_n_per_m, self.housing_mass_kg)
        for name in ("housing_damping_n_s_per_m", "contact_damping_n_s_per_m"):
            s(self, name, check_range(name, getattr(self, name), 0.0, unit="N s/m"))
        s(
            self,
            "unbalance_kg_m",
            check_range("unbalance_kg_m", self.unbalance_kg_m, 0.0, unit="kg m"),
        )
        for name in ("de_fx_n", "de_fy_n", "fe_fx_n", "fe_fy_n"):
            s(self, name, check_range(name, getattr(self, name), unit="N"))
        for name in ("distributed_rotor", "gravity", "ball_inertia", "antialias", "per_ball"):
            _bool(name, getattr(self, name))
        s(self, "axial_load_n", check_range("axial_load_n", self.axial_load_n, 0.0, unit="N"))
        _pass_jitter(self, needs_rk4=False)
        s(self, "ball_diameter_spread_m", check_ball_spread(self.ball_diameter_spread_m))
        s(self, "contact_roughness_m", check_roughness(self.contact_roughness_m))
        _check_rig(self, ("acc_x", "acc_y", "acc_x_fe", "acc_y_fe"))

    def _resolve_disks(self) -> None:
        """``disks`` left unset (``None``) becomes one per ``disk_positions_mm`` value, else the
        seed's :data:`SEED_ROTOR_DISKS`, and joins :attr:`auto_keys` (unset again in
        :meth:`to_dict`, resolved anew by :meth:`replace`, so it follows new positions); given
        beside ``disk_positions_mm``, it must equal their count."""
        pos = self.disk_positions_mm
        if self.disks is None:
            object.__setattr__(self, "disks", SEED_ROTOR_DISKS if pos is None else len(pos))
            self.__dict__["auto_keys"] = (*self.auto_keys, "disks")
        elif pos is not None and len(pos) != self.disks:
            shown = ", ".join(f"{v:g}" for v in pos[:8]) + (", ..." if len(pos) > 8 else "")
            raise ConfigError(
                f"disks = {self.disks} and disk_positions_mm = [{shown}] ({len(pos)} positions) "
                f"disagree; valid: one position per disk (disks = {len(pos)}, or disks unset)"
            )

    @property
    def shaft_hz(self) -> float:
        """Shaft frequency ``rpm / 60`` [Hz]."""
        return self.rpm / 60.0


# ------------------------------------------------------------------ IAS model
@dataclass(frozen=True)
class IasScenario(Scenario):
    """The 3-DOF IAS model of a cylindrical roller bearing with an outer-race spall (seed IAS,
    SPEC §3). The shaft speed is not imposed: the motor torque drives the shaft against the
    torsional damping and the bearing, and the speed comes out of the torque balance.

    ===================================  ===========  ============================================
    key                                  default      meaning
    ===================================  ===========  ============================================
    ``model``                            ``"ias"``
    ``bearing``                          NU204-ECP    catalogue id (seed IAS table 1)
    ``bearing_file``                     –            user bearing TOML (a roller bearing)
    ``rpm``                              –            target speed [r/min]: sets the motor
                                                      torque ``M_z = C_T 2 pi rpm/60``
    ``torque_n_m``                       9.54         motor torque M_z [N m] (seed; exclusive
                                                      with ``rpm``)
    ``initial_rpm``                      0.0          initial shaft speed [r/min]
    ``spall_width_m``                    1e-3         outer-race spall width L_d [m]; 0 = healthy
    ``spall_angle_deg``                  180.0        spall centre azimuth [deg] (the bottom;
                                                      the seed's ``phi_os = 1.5 pi`` from +x)
    ``fx_n``, ``fy_n``                   0.0, 400.0   radial load [N]; ``fy_n`` pushes the shaft
                                                      **down** (seed IAS eq. (1))
    ``duration_s``                       10.0         simulated time [s] (seed)
    ``dt_s``                             1e-6         RK4 step [s] (seed)
    ``fs_hz``                            50000.0      output sample rate [Hz] (a whole number of
                                                      seed steps per sample)
    ``solver``                           ``"rk4"``    ``rk4`` (seed) | ``dopri5``
    ``contact_law``                      ``"seed"``   ``seed`` (eqs. (5)–(12)) | ``harris``
    ``spall_load``                       stribeck     roller load in eq. (30): ``stribeck`` |
                                                      ``dynamic``
    ``skip_s``                           10 % of run  start-up left out of the analysis [s]
    ``mass_kg``                          1.3          inner ring + shaft mass m [kg] (seed)
    ``inertia_kg_m2``                    6.5e-5       polar inertia I [kg m^2] (assumed)
    ``radial_damping_n_s_per_m``         400.0        C_s [N s/m] (seed)
    ``torsional_damping_n_m_s_per_rad``  1.52         C_T [N m s/rad] (seed)
    ``rolling_resistance``               0.0015       mu [-] (seed eq. (14))
    ``first_roller_angle_deg``           90.0         roller 1 azimuth at t = 0 [deg] (the
                                                      seed's ``Phi_0 = 0`` from +x)
    ``reference_load_n``                 F_r / Z      roller load of the seed contact stiffness
                                                      [N]
    ===================================  ===========  ============================================

    Renamed in 0.2.0: ``torque_nm`` → ``torque_n_m``, ``output_rate_hz`` → ``fs_hz``,
    ``method`` → ``solver``, ``radial_damping_n_s_m`` → ``radial_damping_n_s_per_m``,
    ``torsional_damping_n_m_s_rad`` → ``torsional_damping_n_m_s_per_rad`` (same meanings);
    ``spall_angle_rad`` and ``first_roller_angle_rad`` (from +x, counter-clockwise) →
    ``spall_angle_deg`` and ``first_roller_angle_deg`` (project convention).
    """

    MODELS: ClassVar[tuple[Model, ...]] = (Model.IAS,)
    #: a step above the output interval is checked for stability by the model first; the
    #: output grid then uses one step per sample (:mod:`bearingsim.dynamics.ias.scenario`)
    DT_WITHIN_OUTPUT: ClassVar[bool] = False
    KEYS: ClassVar[tuple[str, ...]] = (
        "model",
        "bearing",
        "bearing_file",
        "rpm",
        "torque_n_m",
        "initial_rpm",
        "spall_width_m",
        "spall_angle_deg",
        "fx_n",
        "fy_n",
        "duration_s",
        "dt_s",
        "fs_hz",
        "solver",
        "contact_law",
        "spall_load",
        "skip_s",
        "mass_kg",
        "inertia_kg_m2",
        "radial_damping_n_s_per_m",
        "torsional_damping_n_m_s_per_rad",
        "rolling_resistance",
        "first_roller_angle_deg",
        "reference_load_n",
    )
    RENAMED: ClassVar[dict[str, str]] = {
        "torque_nm": "torque_n_m",
        "radial_damping_n_s_m": "radial_damping_n_s_per_m",
        "torsional_damping_n_m_s_rad": "torsional_damping_n_m_s_per_rad",
        "output_rate_hz": "fs_hz",
        "method": "solver",
        "spall_angle_rad": "spall_angle_deg (centre azimuth from +y towards +x [deg]; the old "
        "phi_os from +x counter-clockwise is 90 - degrees(phi_os), so 1.5 pi is 180)",
        "first_roller_angle_rad": "first_roller_angle_deg (azimuth from +y towards +x [deg]; "
        "the old Phi_0 from +x counter-clockwise is 90 - degrees(Phi_0))",
    }

    model: Model = Model.IAS
    bearing: str | None = "NU204-ECP"
    bearing_file: str | None = None
    rpm: float | None = None
    torque_n_m: float | None = None
    initial_rpm: float = 0.0
    spall_width_m: float = SEED_IAS_SPALL_WIDTH_M
    spall_angle_deg: float = 180.0
    fx_n: float = 0.0
    fy_n: float = SEED_IAS_FY_N
    duration_s: float = SEED_IAS_DURATION_S
    FS_DEFAULT_HZ: ClassVar[float] = IAS_FS_HZ
    fs_hz: float | None = IAS_FS_HZ
    dt_s: float | None = SEED_IAS_DT_S
    contact_law: str = "seed"
    spall_load: str = "stribeck"
    skip_s: float | None = None
    mass_kg: float = SEED_IAS_MASS_KG
    inertia_kg_m2: float = IAS_INERTIA_KG_M2
    radial_damping_n_s_per_m: float = SEED_IAS_RADIAL_DAMPING_N_S_M
    torsional_damping_n_m_s_per_rad: float = SEED_IAS_TORSIONAL_DAMPING_N_M_S
    rolling_resistance: float = SEED_IAS_ROLLING_RESISTANCE
    first_roller_angle_deg: float = 90.0
    reference_load_n: float | None = None

    def _validate(self) -> None:
        s = object.__setattr__
        _check_bearing(self, "NU204-ECP")
        if self.dt_s is None:
            s(self, "dt_s", SEED_IAS_DT_S)
        if self.rpm is not None and self.torque_n_m is not None:
            raise ConfigError(
                f"rpm = {self.rpm!r} and torque_n_m = {self.torque_n_m!r}: give at most one "
                "(rpm sets M_z = C_T 2 pi rpm/60)"
            )
        if self.rpm is not None:
            s(self, "rpm", check_positive("rpm", self.rpm, "r/min"))
        if self.torque_n_m is not None:
            s(self, "torque_n_m", check_range("torque_n_m", self.torque_n_m, 0.0, unit="N m"))
        s(self, "initial_rpm", check_range("initial_rpm", self.initial_rpm, 0.0, unit="r/min"))
        s(self, "spall_width_m", check_range("spall_width_m", self.spall_width_m, 0.0, unit="m"))
        s(self, "spall_angle_deg", _angle("spall_angle_deg", self.spall_angle_deg))
        s(self, "fx_n", check_range("fx_n", self.fx_n, unit="N"))
        s(self, "fy_n", check_range("fy_n", self.fy_n, unit="N"))
        _choice("contact_law", self.contact_law, ("seed", "harris"))
        _choice("spall_load", self.spall_load, ("stribeck", "dynamic"))
        if self.skip_s is not None:
            s(
                self,
                "skip_s",
                check_range("skip_s", self.skip_s, 0.0, self.duration_s, hi_open=True, unit="s"),
            )
        s(
            self,
            "first_roller_angle_deg",
            _angle("first_roller_angle_deg", self.first_roller_angle_deg),
        )
        if self.reference_load_n is not None:
            s(
                self,
                "reference_load_n",
                check_positive("reference_load_n", self.reference_load_n, "N"),
            )
        # mass, inertia, damping, rolling resistance: IasParams checks them with their ranges

    @property
    def motor_torque_n_m(self) -> float:
        """Motor torque M_z [N m]: given, from ``rpm`` (``C_T 2 pi rpm/60``), else the seed's."""
        if self.torque_n_m is not None:
            return self.torque_n_m
        if self.rpm is not None:
            return self.torsional_damping_n_m_s_per_rad * 2.0 * math.pi * self.rpm / 60.0
        return SEED_IAS_TORQUE_N_M


#: the families, in documentation order
_FAMILIES: tuple[type[Scenario], ...] = (RingScenario, RotorScenario, IasScenario)
#: model -> its family's scenario class
_FAMILY: dict[Model, type[Scenario]] = {m: f for f in _FAMILIES for m in f.MODELS}


def family(model: Model | str) -> type[Scenario]:
    """The scenario class of ``model`` (:class:`RingScenario`, :class:`RotorScenario` or
    :class:`IasScenario`)."""
    return _family_of(model)


__all__ = [
    "IasScenario",
    "Model",
    "RingScenario",
    "RotorScenario",
    "Scenario",
    "Solver",
    "family",
]
