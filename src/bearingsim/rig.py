"""The measurement chain ("rig"): from a bearing model's output to what an accelerometer records
(issue 16, item 3).

A bearing model gives the vibration at the bearing. A sensor on a machine records it through
the structure between them and adds what else the machine does. A :class:`Rig` is that chain as
data, applied to any model's output as a linear system plus additive signals:

``a_sensor(t) = g_0 a(t) + sum_k (h_k * a)(t) + b(t) + sum_i A_i sin(2 pi f_i t + phi_i) + n(t)``

* ``g_0`` -- the direct (broadband) gain of the path [-];
* ``h_k`` -- a resonant mode of the path, the band-pass of a single degree of freedom,
  ``H_k(s) = g_k 2 zeta_k w_k s / (s^2 + 2 zeta_k w_k s + w_k^2)``, whose gain at its natural
  frequency ``w_k = 2 pi f_k`` is ``g_k`` and whose half-power bandwidth is ``2 zeta_k f_k``
  (a structure's accelerance near one mode, e.g. Ewins, *Modal Testing*, 2nd ed., §2.3);
  discretised as the digital resonator with the same centre, gain and half-power bandwidth
  (:meth:`Mode.sos`) and applied as second-order sections;
* ``b(t)`` -- the machine's background vibration: Gaussian noise whose one-sided power spectral
  density follows the rig's table (log-log interpolation between its points, zero outside),
  optionally scaled with the shaft speed (``(N / rpm_ref)^speed_exponent`` in amplitude);
* tones -- discrete lines at multiples of the shaft speed (``order``) or at fixed frequencies,
  with seeded random phases;
* ``n(t)`` -- the sensor's white noise of a given RMS.

Every value of a rig file carries its provenance (where the number comes from); a file with an
unknown key, a non-physical value or without provenance is refused with one line. The random
parts come from ``numpy.random.default_rng(seed)``: the same seed gives the same signal, bit for
bit.

TOML layout (SI units in the key names)::

    name = "my-rig"
    description = "drive-end accelerometer of ..."
    provenance = "how the whole profile was made (the exact command)"
    input_channel = "acc_y"          # the model channel that enters the chain
    end = "FE"                       # optional: the machine end whose housing the sensor is on
                                     # (DE|FE; the rotor model then reads that housing)
    bearing = "6203-cwru"            # optional: catalogue id of the bearing the records were
                                     # taken on (a run's bearing of another size is warned);
                                     # one outside the catalogue is a [bearing] table of id,
                                     # n_elements, pitch_diameter_m, element_diameter_m
    fs_hz = 12000.0                  # optional: the sampling rate of the records it was
                                     # identified from [Hz]; a scenario with this rig and no
                                     # fs_hz of its own is sampled at it
    rpm_range = [1730.0, 1797.0]     # optional: the shaft speeds of those records [r/min];
                                     # a run far outside them is warned (RigSpeedWarning)

    [path]
    gain = 1.0
    provenance = "..."

    [[mode]]
    frequency_hz = 3350.0
    damping_ratio = 0.05
    gain = 4.0
    provenance = "..."

    [background]
    frequency_hz = [20.0, 500.0, 6000.0]
    psd_m2_per_s4_per_hz = [1e-4, 1e-5, 1e-6]
    speed_exponent = 2.0             # optional, with rpm_ref: the table is the background at
    rpm_ref = 1500.0                 # rpm_ref [r/min]; at N its amplitude is (N/rpm_ref)^2 x
    provenance = "..."

    [[tone]]
    order = 1.0                      # or frequency_hz = 60.0
    amplitude_m_per_s2 = 0.05
    provenance = "..."

    [sensor]
    noise_rms_m_per_s2 = 0.01
    provenance = "..."

    [[model_gain]]                   # optional, one per model: a model-based path gain
    model = "rotor"                  # vsm | dem | tvsm | rotor
    scale = 6.8
    defect_profile = "pit"           # optional: the drop profile it was identified with
    provenance = "..."               # (default geometric, the realism a rig brings)

    [[model_gain]]                   # or the fitted form: the path's gains replaced
    model = "vsm"
    path_gain = 0.01
    mode_gains = [0.08]              # one per [[mode]], in their order
    provenance = "..."

A ``[[model_gain]]`` sets the path for the output of one model. An output-only
identification cannot tell the path's gain from the excitation's size (it takes
``g_0 = 1``); a model-based one simulates the records' conditions with that model. Its
``scale`` form multiplies the whole path (``g_0`` and every ``g_k``) so that the model
carries the power the records have above the background
(:func:`bearingsim.side_by_side.model_path_scale`); its fitted form replaces ``g_0`` and
every ``g_k`` by gains fitted to the records' spectra with the model's output as the known
input (:func:`bearingsim.side_by_side.model_path_fit`), which also weighs the direct path
against the modes. ``bearingsim rig identify --model-gain MODEL [--gain-method
power|spectral]`` writes either. :func:`apply_rig` applies the gain of the result's own model
and no other.
"""

from __future__ import annotations

import dataclasses
import math
import warnings
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np
from numpy.typing import NDArray

from .errors import (
    MAX_ACCELERATION,
    ConfigError,
    check_int,
    check_positive,
    check_range,
    read_toml,
)

__all__ = [
    "Background",
    "GAIN_MODELS",
    "Mode",
    "ModelGain",
    "Rig",
    "RigBearing",
    "RigBearingWarning",
    "RigGainWarning",
    "RigRateWarning",
    "RigSpeedWarning",
    "Tone",
    "apply_rig",
    "available_rigs",
    "coverage_rate_hz",
    "load_rig",
]

#: the models' acceleration channels a rig can take as its input (ring models: ``acc_x``,
#: ``acc_y``; the rotor model also the fan-end housing's ``acc_x_fe``, ``acc_y_fe``)
INPUT_CHANNELS = ("acc_x", "acc_y", "acc_x_fe", "acc_y_fe")

#: folder of the rig profiles shipped with the package (``bearingsim/rigs/NAME.toml``)
PROFILES_DIR = Path(__file__).resolve().parent / "rigs"


#: largest gain a rig takes (direct, mode, model scale) [-]: a lightly damped structure
#: amplifies by ~1/(2 zeta) at resonance (5000 at zeta = 1e-4); 1e6 leaves room for a sensor in
#: other units, and keeps the filters and signals finite (a scale of 1e308 overflowed the mode
#: filters with a traceback; 1e200 wrote an infinite RMS)
MAX_GAIN = 1e6
#: largest identification rate a rig file takes [Hz] (a rate a recorder has; 10 MHz)
MAX_RIG_RATE_HZ = 1e7
#: largest magnitude of a background's speed exponent [-]: forces from unbalance and
#: misalignment grow as speed^2 (their accelerations with them); a law steeper than speed^4
#: either way is a typo or a fit of scatter, not a machine
MAX_SPEED_EXPONENT = 4.0


def _provenance(table: dict[str, Any], where: str) -> str:
    p = table.get("provenance")
    if not isinstance(p, str) or not p.strip():
        raise ConfigError(
            f"{where}.provenance is missing; every value of a rig needs its source (a text)"
        )
    return p.strip()


def _profile(table: dict[str, Any], where: str) -> str:
    """A ``[[model_gain]]``'s ``defect_profile`` (default ``"geometric"``), checked."""
    from .geometry import DefectProfile, parse_enum

    return parse_enum(DefectProfile, table.get("defect_profile", "geometric"),
                      f"{where}.defect_profile").value  # fmt: skip


def _keys(
    table: Any, allowed: tuple[str, ...], where: str, required: tuple[str, ...] = ()
) -> dict[str, Any]:
    if not isinstance(table, dict):
        raise ConfigError(f"{where} must be a table of keys")
    unknown = [k for k in table if k not in allowed]
    if unknown:
        raise ConfigError(f"{where}: unknown key {unknown[0]!r}; valid keys: " + ", ".join(allowed))
    for k in required:
        if k not in table:
            raise ConfigError(f"{where}.{k} is missing")
    return table


@dataclass(frozen=True)
class RigBearing:
    """The size of a bearing outside the catalogue that a rig's records were taken on: what
    :func:`bearing_note` compares a run's bearing with. ``id`` [-] names it (a user's bearing
    file's ``id``), ``n_elements`` [-], ``pitch_diameter_m`` and ``element_diameter_m`` [m].

    In a rig file it is the ``[bearing]`` table (a catalogue bearing is ``bearing = "ID"``)."""

    id: str
    n_elements: int
    pitch_diameter_m: float
    element_diameter_m: float

    KEYS = ("id", "n_elements", "pitch_diameter_m", "element_diameter_m")

    def __post_init__(self) -> None:
        # a RigBearing built in code is checked as a file's [bearing] table is (twenty-sixth
        # session: it validated nothing, and a zero diameter divided by zero in same_size)
        bid, n, pd, ed = self._checked({k: getattr(self, k) for k in self.KEYS}, "bearing")
        for k, v in zip(self.KEYS, (bid, n, pd, ed), strict=True):
            object.__setattr__(self, k, v)

    @classmethod
    def from_dict(cls, d: Any, where: str = "bearing") -> RigBearing:
        """Build and validate from the ``[bearing]`` table (one-line errors)."""
        d = _keys(d, cls.KEYS, where, required=cls.KEYS)
        return cls(*cls._checked(d, where))

    @staticmethod
    def _checked(d: dict, where: str) -> tuple[str, int, float, float]:
        """The checked ``(id, n_elements, pitch_diameter_m, element_diameter_m)`` of ``d``,
        each error naming ``where``."""
        from .geometry import PITCH_DIAMETER_RANGE, Z_MAX

        bid = d["id"]
        if not isinstance(bid, str) or not bid.strip() or not bid.isprintable():
            raise ConfigError(f"{where}.id = {bid!r} is invalid; valid: printable text")
        n = d["n_elements"]  # as a bearing file takes it: an integer, 9.0 too (not a bool)
        if (
            isinstance(n, bool)
            or not isinstance(n, int | float)
            or not float(n).is_integer()
            or not 3 <= n <= Z_MAX
        ):
            raise ConfigError(
                f"{where}.n_elements = {n!r} is invalid; valid range [3, {Z_MAX}] integer"
            )
        n = int(n)
        pd = check_range(f"{where}.pitch_diameter_m", d["pitch_diameter_m"],
                         *PITCH_DIAMETER_RANGE, unit="m")  # fmt: skip
        # neighbouring elements must not overlap on the pitch circle (geometry._check_common)
        top = pd * math.sin(math.pi / n)
        ed = check_range(f"{where}.element_diameter_m", d["element_diameter_m"], 0.0, top,
                         lo_open=True, hi_open=True, unit="m")  # fmt: skip
        return bid.strip(), n, pd, ed

    @classmethod
    def of(cls, bearing: Any) -> RigBearing:
        """The size of a :class:`~bearingsim.geometry.BallBearing` (or roller bearing)."""
        return cls(bearing.id, int(bearing.n_elements), float(bearing.pitch_diameter),
                   float(bearing.element_diameter))  # fmt: skip

    def sizes(self) -> str:
        """``pitch diameter P mm, Z elements of D mm``."""
        return (
            f"pitch diameter {1e3 * self.pitch_diameter_m:.4g} mm, {self.n_elements} elements "
            f"of {1e3 * self.element_diameter_m:.4g} mm"
        )

    def describe(self) -> str:
        """``ID (pitch diameter P mm, Z elements of D mm)``."""
        return f"{self.id} ({self.sizes()})"

    def same_size(self, other: RigBearing) -> bool:
        """The same number of elements, and pitch and element diameters within
        :data:`BEARING_SIZE_REL` of ``other``'s: one size, as :class:`RigBearingWarning`
        judges it (the seed's 6205 and the CWRU's, 0.1 % apart, are one)."""
        return self.n_elements == other.n_elements and all(
            abs(getattr(other, k) / getattr(self, k) - 1.0) <= BEARING_SIZE_REL
            for k in ("pitch_diameter_m", "element_diameter_m")
        )


#: smallest damping ratio of a mode [-]: no structure is damped less (a steel tuning fork's
#: ~1e-5); far below it the digital resonator's poles lie within round-off of the unit
#: circle and SciPy's design warns of badly conditioned coefficients (1e-17 did)
MIN_DAMPING = 1e-6


@dataclass(frozen=True)
class Mode:
    """A resonant mode of the transfer path: natural frequency ``frequency_hz`` [Hz], damping
    ratio ``damping_ratio`` [-] (:data:`MIN_DAMPING` <= zeta < 1), gain at resonance ``gain``
    [-] (0: the mode contributes nothing)."""

    frequency_hz: float
    damping_ratio: float
    gain: float
    provenance: str

    KEYS = ("frequency_hz", "damping_ratio", "gain", "provenance")

    @classmethod
    def from_dict(cls, d: Any, where: str) -> Mode:
        d = _keys(d, cls.KEYS, where, required=cls.KEYS[:3])
        return cls(
            check_range(f"{where}.frequency_hz", d["frequency_hz"], 0.0, lo_open=True, unit="Hz"),
            check_range(
                f"{where}.damping_ratio", d["damping_ratio"], MIN_DAMPING, 1.0, hi_open=True
            ),  # fmt: skip
            check_range(f"{where}.gain", d["gain"], 0.0, MAX_GAIN),
            _provenance(d, where),
        )

    @property
    def upper_half_power_hz(self) -> float:
        """Upper half-power frequency of the mode, ``f_n (sqrt(1 + zeta^2) + zeta)`` [Hz] (the
        band-pass's half-power band is ``2 zeta f_n`` wide, centred geometrically on ``f_n``)."""
        z = self.damping_ratio
        return self.frequency_hz * (np.sqrt(1.0 + z * z) + z)

    def rate_problem(
        self, fs: float, where: str, rate: str = "the output rate"
    ) -> tuple[str, str] | None:
        """What is wrong with the rate ``fs`` [Hz] for this mode, as ``(reason, valid)``, or
        None: its Nyquist frequency reaches the mode or its half-power band (the digital
        resonator of :meth:`sos` has no such band: its poles leave the unit circle once the
        band is as wide as the Nyquist band, and the signal grows without bound). ``where``
        names the mode in the reason, ``rate`` the rate."""
        ny = 0.5 * fs
        if self.frequency_hz >= ny:
            return (
                f"{where}.frequency_hz = {self.frequency_hz:g} Hz is at or above the Nyquist "
                f"frequency of {rate} ({ny:g} Hz)",
                f"valid range (0, {ny:g}) Hz",
            )
        if self.upper_half_power_hz >= ny:
            r = ny / self.frequency_hz  # f_n (sqrt(1 + z^2) + z) = ny  <=>  z = (r^2 - 1) / 2r
            return (
                f"{where}.damping_ratio = {self.damping_ratio:.6g}: the half-power band of the "
                f"mode at {self.frequency_hz:g} Hz reaches {self.upper_half_power_hz:.6g} Hz, at "
                f"or above the Nyquist frequency of {rate} ({ny:g} Hz)",
                f"valid range [{MIN_DAMPING:g}, {(r * r - 1.0) / (2.0 * r):.6g}) at this rate",
            )
        return None

    def check_rate(self, fs: float, where: str, rate: str = "the output rate") -> None:
        """Refuse (one line) a rate ``fs`` [Hz] with a :meth:`rate_problem`."""
        bad = self.rate_problem(fs, where, rate)
        if bad is not None:
            raise ConfigError("; ".join(bad))

    def sos(self, fs: float) -> NDArray[np.float64]:
        """Second-order section of the mode at sample rate ``fs`` [Hz]: the digital resonator
        with the mode's centre frequency, gain and half-power bandwidth ``2 zeta f_n``
        (:func:`scipy.signal.iirpeak` with ``Q = 1 / (2 zeta)``: the bilinear transform with
        the band edges pre-warped). Pre-warping the centre alone would keep ``f_n`` but
        narrow the band, by 0.56 at ``f_n = 0.28 fs`` (a ringing decaying too slowly)."""
        from scipy.signal import iirpeak, tf2sos

        self.check_rate(fs, "mode")
        b, a = iirpeak(self.frequency_hz, 1.0 / (2.0 * self.damping_ratio), fs=fs)
        # the gain on the section's numerator after the conversion: the same coefficients,
        # and a gain below ~3e-13 no longer reads as a numerator of leading zeros
        # (scipy's BadCoefficients; a fitted mode gain of 1e-20 stopped apply with it)
        sos = tf2sos(b, a)
        sos[0, :3] *= self.gain
        return sos


#: the models a rig can carry a model-based path gain for (``[[model_gain]]``)
GAIN_MODELS = ("vsm", "dem", "tvsm", "rotor")


@dataclass(frozen=True)
class ModelGain:
    """A model-based path for the output of one ``model`` (one of :data:`GAIN_MODELS`), with
    its provenance (module docstring), in one of two forms:

    * ``scale`` [-] -- the whole path (direct gain and every mode's gain) times it
      (:func:`bearingsim.side_by_side.model_path_scale`);
    * ``path_gain`` [-] and ``mode_gains`` [-] (one per ``[[mode]]``, in their order) -- the
      path's gains replaced by these, the modes' frequencies and damping kept
      (:func:`bearingsim.side_by_side.model_path_fit`).

    ``defect_profile``: the drop profile the records' faults were simulated with
    (:class:`bearingsim.geometry.DefectProfile`; the gain matches that profile's level, and
    :func:`apply_rig` warns when a faulty run uses another); default ``"geometric"``, the
    realism a rig brings (:data:`bearingsim.config.REALISM`), which every file written before
    this key existed was identified with. Written only when it is not the default.
    """

    model: str
    scale: float | None
    provenance: str
    path_gain: float | None = None
    mode_gains: tuple[float, ...] | None = None
    defect_profile: str = "geometric"

    KEYS = ("model", "scale", "path_gain", "mode_gains", "defect_profile", "provenance")

    def __post_init__(self) -> None:
        from .geometry import DefectProfile, parse_enum

        prof = parse_enum(DefectProfile, self.defect_profile, "model_gain.defect_profile")
        object.__setattr__(self, "defect_profile", prof.value)

    @classmethod
    def from_dict(cls, d: Any, where: str) -> ModelGain:
        d = _keys(d, cls.KEYS, where, required=("model",))
        if d["model"] not in GAIN_MODELS:
            raise ConfigError(
                f"{where}.model = {d['model']!r} is invalid; valid: " + ", ".join(GAIN_MODELS)
            )
        fitted = "path_gain" in d or "mode_gains" in d
        if ("scale" in d) == fitted:
            raise ConfigError(
                f"{where}: give either scale or path_gain with mode_gains; valid: one of the "
                "two forms"
            )
        prof = _profile(d, where)
        if not fitted:
            return cls(
                d["model"],
                check_range(f"{where}.scale", d["scale"], 0.0, MAX_GAIN, lo_open=True),
                _provenance(d, where),
                defect_profile=prof,
            )
        for k in ("path_gain", "mode_gains"):
            if k not in d:
                raise ConfigError(f"{where}.{k} is missing (path_gain and mode_gains go together)")
        mg = d["mode_gains"]
        if not isinstance(mg, list):
            raise ConfigError(f"{where}.mode_gains = {mg!r} is invalid; valid: a list of gains")
        return cls(
            d["model"],
            None,
            _provenance(d, where),
            check_range(f"{where}.path_gain", d["path_gain"], 0.0, MAX_GAIN),
            tuple(
                check_range(f"{where}.mode_gains[{i}]", v, 0.0, MAX_GAIN) for i, v in enumerate(mg)
            ),
            prof,
        )

    def to_dict(self) -> dict[str, Any]:
        """The ``[[model_gain]]`` table (only the keys of its form)."""
        out: dict[str, Any] = {"model": self.model}
        if self.scale is not None:
            out["scale"] = self.scale
        else:
            out["path_gain"] = self.path_gain
            out["mode_gains"] = list(self.mode_gains or ())
        if self.defect_profile != "geometric":
            out["defect_profile"] = self.defect_profile
        out["provenance"] = self.provenance
        return out

    def describe(self) -> str:
        """One phrase: what the gain does to the path (and the defect profile it was identified
        with, when not the default geometric one)."""
        prof = "" if self.defect_profile == "geometric" else f" ({self.defect_profile} defects)"
        if self.scale is not None:
            return f"path x {self.scale:.4g}{prof}"
        modes = ", ".join(f"{g:.4g}" for g in self.mode_gains or ())
        return f"fitted path: direct gain {self.path_gain:.4g}, mode gains {modes or '-'}{prof}"


@dataclass(frozen=True)
class Background:
    """Background vibration: one-sided acceleration PSD ``psd`` [(m/s^2)^2/Hz] at
    ``frequency_hz`` [Hz] (log-log interpolation between the points, zero outside).

    ``speed_exponent`` [-] and ``rpm_ref`` [r/min], given together or not at all: the table is
    the background at the shaft speed ``rpm_ref``, and at a speed ``N`` its amplitude is
    ``(N / rpm_ref)^speed_exponent`` times it (the PSD the square of that; the frequencies
    stay: a machine's structure rings where it rings). :func:`bearingsim.rig_identify.
    identify_rig` fits the exponent when its records span enough speeds
    (:data:`~bearingsim.rig_identify.MIN_SPEED_SPAN`); without it the background is the same
    at every speed (the records' own)."""

    frequency_hz: tuple[float, ...]
    psd: tuple[float, ...]
    provenance: str
    speed_exponent: float | None = None
    rpm_ref: float | None = None

    KEYS = ("frequency_hz", "psd_m2_per_s4_per_hz", "speed_exponent", "rpm_ref", "provenance")

    def __post_init__(self) -> None:  # a file's table and a background built in code alike
        n, ref = self.speed_exponent, self.rpm_ref
        if (n is None) != (ref is None):
            given, missing = ("speed_exponent", "rpm_ref") if ref is None else (
                "rpm_ref", "speed_exponent")  # fmt: skip
            raise ConfigError(
                f"background.{missing} is missing ({given} is given); valid: speed_exponent "
                "and rpm_ref together, or neither"
            )
        if n is not None:
            object.__setattr__(
                self,
                "speed_exponent",
                check_range(
                    "background.speed_exponent", n, -MAX_SPEED_EXPONENT, MAX_SPEED_EXPONENT
                ),
            )
            object.__setattr__(self, "rpm_ref",
                               check_positive("background.rpm_ref", ref, "r/min"))  # fmt: skip

    def speed_factor(self, shaft_hz: float | None) -> float:
        """The background's amplitude at shaft speed ``shaft_hz`` [Hz] over the table's [-]:
        1 without a speed law or a speed (inf where the power overflows)."""
        if self.speed_exponent is None or self.rpm_ref is None or shaft_hz is None:
            return 1.0
        try:
            return float((60.0 * shaft_hz / self.rpm_ref) ** self.speed_exponent)
        except OverflowError:
            return math.inf

    @classmethod
    def from_dict(cls, d: Any, where: str) -> Background:
        d = _keys(d, cls.KEYS, where)
        law = {k: d[k] for k in ("speed_exponent", "rpm_ref") if k in d}  # __post_init__ checks
        f, s = d.get("frequency_hz"), d.get("psd_m2_per_s4_per_hz")
        if not isinstance(f, list) or not isinstance(s, list) or len(f) != len(s) or len(f) < 2:
            raise ConfigError(
                f"{where}: frequency_hz and psd_m2_per_s4_per_hz must be lists of the same "
                "length, at least 2 points"
            )
        fv = [check_range(f"{where}.frequency_hz[{i}]", v, 0.0, lo_open=True, unit="Hz")
              for i, v in enumerate(f)]  # fmt: skip
        sv = [check_range(f"{where}.psd_m2_per_s4_per_hz[{i}]", v, 0.0, MAX_ACCELERATION**2,
                          lo_open=True, unit="(m/s^2)^2/Hz") for i, v in enumerate(s)]  # fmt: skip
        if any(b <= a for a, b in zip(fv, fv[1:], strict=False)):
            k = next(i for i in range(1, len(fv)) if fv[i] <= fv[i - 1])
            raise ConfigError(
                f"{where}.frequency_hz[{k}] = {fv[k]:g} Hz does not exceed [{k - 1}] = "
                f"{fv[k - 1]:g} Hz; valid: frequencies that increase strictly"
            )
        return cls(tuple(fv), tuple(sv), _provenance(d, where), **law)

    def psd_at(self, f: NDArray[np.float64], shaft_hz: float | None = None) -> NDArray[np.float64]:
        """PSD [(m/s^2)^2/Hz] at frequencies ``f`` [Hz] (log-log interpolation, 0 outside), at
        the shaft speed ``shaft_hz`` [Hz] (the square of :meth:`speed_factor` times the
        table's; the table's without a speed law or a speed)."""
        f = np.asarray(f, dtype=float)
        fp, sp_ = np.log(self.frequency_hz), np.log(self.psd)
        out = np.zeros_like(f)
        inside = (f >= self.frequency_hz[0]) & (f <= self.frequency_hz[-1])
        out[inside] = np.exp(np.interp(np.log(f[inside]), fp, sp_))
        k = self.speed_factor(shaft_hz)
        if k != 1.0:  # without a speed law the values are bit for bit those of before
            out *= k * k
        return out

    def rms(self, f_hi: float | None = None) -> float:
        """RMS of the background [m/s^2]: the square root of the table's PSD integrated over
        its frequencies (log-log interpolation, 2000 log-spaced points), up to ``f_hi`` [Hz]
        if given (e.g. the Nyquist frequency of an output)."""
        hi = self.frequency_hz[-1] if f_hi is None else min(f_hi, self.frequency_hz[-1])
        if hi <= self.frequency_hz[0]:
            return 0.0
        f = np.geomspace(self.frequency_hz[0], hi, 2000)
        return float(np.sqrt(np.trapezoid(self.psd_at(f), f)))

    def synthesize(
        self, n: int, fs: float, rng: np.random.Generator, shaft_hz: float | None = None
    ) -> NDArray[np.float64]:
        """``n`` samples at ``fs`` [Hz] of Gaussian noise with this PSD [m/s^2] at the shaft
        speed ``shaft_hz`` [Hz] (:meth:`speed_factor`): each Fourier coefficient complex normal
        with ``E|X_k|^2 = S(f_k) fs n / 2``, so the periodogram ``2 |X_k|^2 / (fs n)`` has
        expectation ``S(f_k)``."""
        f = np.fft.rfftfreq(n, 1.0 / fs)
        amp = np.sqrt(self.psd_at(f, shaft_hz) * fs * n / 4.0)
        X = amp * (rng.standard_normal(f.size) + 1j * rng.standard_normal(f.size))
        X[0] = 0.0
        if n % 2 == 0:
            X[-1] = 0.0
        return np.fft.irfft(X, n=n)


@dataclass(frozen=True)
class Tone:
    """A discrete line of amplitude ``amplitude_m_per_s2`` [m/s^2] at ``order`` times the shaft
    speed or at ``frequency_hz`` [Hz] (exactly one of the two)."""

    amplitude_m_per_s2: float
    provenance: str
    order: float | None = None
    frequency_hz: float | None = None

    KEYS = ("order", "frequency_hz", "amplitude_m_per_s2", "provenance")

    @classmethod
    def from_dict(cls, d: Any, where: str) -> Tone:
        d = _keys(d, cls.KEYS, where)
        if ("order" in d) == ("frequency_hz" in d):
            raise ConfigError(f"{where}: give exactly one of order and frequency_hz")
        if "amplitude_m_per_s2" not in d:
            raise ConfigError(f"{where}.amplitude_m_per_s2 is missing")
        order = (check_range(f"{where}.order", d["order"], 0.0, lo_open=True)
                 if "order" in d else None)  # fmt: skip
        freq = (check_range(f"{where}.frequency_hz", d["frequency_hz"], 0.0, lo_open=True,
                            unit="Hz") if "frequency_hz" in d else None)  # fmt: skip
        amp = check_range(f"{where}.amplitude_m_per_s2", d["amplitude_m_per_s2"], 0.0,
                          MAX_ACCELERATION, unit="m/s^2")  # fmt: skip
        return cls(amp, _provenance(d, where), order, freq)

    def frequency(self, shaft_hz: float | None) -> float:
        """The tone's frequency [Hz] at shaft speed ``shaft_hz`` [Hz]."""
        if self.frequency_hz is not None:
            return self.frequency_hz
        if shaft_hz is None:
            raise ConfigError(f"tone of order {self.order:g} needs the shaft speed of the signal")
        return self.order * shaft_hz


@dataclass(frozen=True)
class Rig:
    """A measurement chain (see the module docstring): direct gain, modes, background, tones,
    sensor noise, each with its provenance."""

    name: str
    description: str
    provenance: str
    input_channel: str = "acc_y"
    #: the end of a two-bearing machine whose housing the sensor is on ("DE" | "FE"; None: not
    #: said). The ring models simulate one bearing and ignore it; the rotor model feeds the
    #: housing of that end into the chain (acc_y at DE, acc_y_fe at FE) when ``input_channel``
    #: is the default acc_y
    end: str | None = None
    #: the sampling rate of the records the rig was identified from [Hz] (None: not said); a
    #: scenario with this rig and no ``fs_hz`` of its own is sampled at it
    fs_hz: float | None = None
    #: the shaft speeds of the records the rig was identified from, ``(lowest, highest)``
    #: [r/min] (None: not said); its background and tones are those speeds' (a run far outside
    #: them gets a :class:`RigSpeedWarning`)
    rpm_range: tuple[float, float] | None = None
    #: the bearing the records were taken on: a catalogue id, or the size of one outside the
    #: catalogue (None: not said); a run whose bearing is of another size gets a
    #: :class:`RigBearingWarning` (another bearing sits in another housing, with other modes)
    bearing: str | RigBearing | None = None
    gain: float = 1.0
    gain_provenance: str = "default: the model's output passes unchanged"
    modes: tuple[Mode, ...] = ()
    background: Background | None = None
    tones: tuple[Tone, ...] = ()
    noise_rms_m_per_s2: float = 0.0
    noise_provenance: str = "default: no sensor noise"
    #: model-based paths, one per model at most (:meth:`for_model`)
    model_gains: tuple[ModelGain, ...] = ()
    source: str = field(default="", compare=False)

    KEYS = ("name", "description", "provenance", "input_channel", "end", "bearing", "fs_hz",
            "rpm_range", "path", "mode", "background", "tone", "sensor", "model_gain")  # fmt: skip

    def __post_init__(self) -> None:
        if self.rpm_range is not None:
            r = self.rpm_range
            if not isinstance(r, list | tuple) or len(r) != 2:
                raise ConfigError(
                    f"rig.rpm_range = {r!r} is invalid; valid: [lowest, highest] shaft speed "
                    "[r/min]"
                )
            lo = check_positive("rig.rpm_range[0]", r[0], "r/min")
            hi = check_range("rig.rpm_range[1]", r[1], lo, unit="r/min")
            object.__setattr__(self, "rpm_range", (lo, hi))
        bg = self.background
        if bg is not None and bg.speed_exponent is not None:  # a law holds where it was fitted
            if self.rpm_range is None:
                raise ConfigError(
                    "background.speed_exponent needs rig.rpm_range (the shaft speeds the law "
                    "was fitted over; a run far outside them is warned); valid: rpm_range = "
                    "[lowest, highest] r/min"
                )
            lo, hi = self.rpm_range
            if not lo <= bg.rpm_ref <= hi:
                raise ConfigError(
                    f"background.rpm_ref = {bg.rpm_ref:g} r/min lies outside rig.rpm_range "
                    f"[{lo:g}, {hi:g}] r/min; valid: a speed within the range the law was "
                    "fitted over"
                )
        if self.fs_hz is not None:  # checked here for a file and a rig built in code alike;
            # its own modes lie below the Nyquist frequency of its rate
            rate = check_range(
                "rig.fs_hz", self.fs_hz, 0.0, MAX_RIG_RATE_HZ, lo_open=True, unit="Hz"
            )
            object.__setattr__(self, "fs_hz", rate)
            for i, m in enumerate(self.modes):
                m.check_rate(self.fs_hz, f"mode[{i}]", "the rig's fs_hz")
        # a fitted model path replaces every mode's gain: one gain per mode (a file's
        # [[model_gain]] and a rig built in code alike)
        for i, g in enumerate(self.model_gains):
            if g.mode_gains is not None and len(g.mode_gains) != len(self.modes):
                raise ConfigError(
                    f"model_gain[{i}].mode_gains has {len(g.mode_gains)} gains; valid: one "
                    f"per [[mode]] ({len(self.modes)})"
                )

    @classmethod
    def from_dict(cls, d: Any, source: str = "<rig>") -> Rig:
        """Build and validate from a table (the TOML layout of the module docstring)."""
        try:
            d = _keys(d, cls.KEYS, "rig")
            name = d.get("name")
            if not isinstance(name, str) or not name.strip():
                raise ConfigError("rig.name is missing (a text)")
            if not name.isprintable():  # a newline or an escape in a name breaks every line
                raise ConfigError(  # that prints it (twenty-first session)
                    f"rig.name = {name!r} holds a control character; valid: printable text"
                )
            desc = d.get("description", "")
            if not isinstance(desc, str):
                raise ConfigError("rig.description must be a text")
            prov = _provenance(d, "rig")
            ch = d.get("input_channel", "acc_y")
            if ch not in INPUT_CHANNELS:  # a typo failed only when a run applied the rig
                raise ConfigError(
                    f"rig.input_channel = {ch!r} is invalid; valid: " + ", ".join(INPUT_CHANNELS)
                )
            end = d.get("end")
            if end is not None and end not in ("DE", "FE"):
                raise ConfigError(f"rig.end = {end!r} is invalid; valid: DE, FE")
            bearing = d.get("bearing")
            if isinstance(bearing, dict):  # a bearing outside the catalogue: its size
                bearing = RigBearing.from_dict(bearing)
                _check_not_a_catalogue_twin(bearing)
            elif bearing is not None:
                from .catalog import _catalog_files

                ids = sorted(_catalog_files())
                if not isinstance(bearing, str):  # bearing = 6205, unquoted: a number
                    raise ConfigError(
                        f"rig.bearing = {bearing!r} is not text; valid: a catalogue id in "
                        'quotes (bearing = "6205-cwru"), or a [bearing] table of id, '
                        "n_elements, pitch_diameter_m, element_diameter_m"
                    )
                if bearing not in ids:
                    raise ConfigError(
                        f"rig.bearing = {bearing!r} is not a catalogue bearing; valid: "
                        + ", ".join(ids)
                        + " (a bearing of your own: a [bearing] table of id, n_elements, "
                        "pitch_diameter_m, element_diameter_m)"
                    )
            gain, gprov = 1.0, cls.gain_provenance
            if "path" in d:
                p = _keys(d["path"], ("gain", "provenance"), "path")
                if "gain" not in p:
                    raise ConfigError("path.gain is missing")
                gain = check_range("path.gain", p["gain"], 0.0, MAX_GAIN)
                gprov = _provenance(p, "path")
            modes = d.get("mode", [])
            if not isinstance(modes, list):
                raise ConfigError("mode must be an array of tables ([[mode]])")
            tones = d.get("tone", [])
            if not isinstance(tones, list):
                raise ConfigError("tone must be an array of tables ([[tone]])")
            noise, nprov = 0.0, cls.noise_provenance
            if "sensor" in d:
                s = _keys(d["sensor"], ("noise_rms_m_per_s2", "provenance"), "sensor")
                if "noise_rms_m_per_s2" not in s:
                    raise ConfigError("sensor.noise_rms_m_per_s2 is missing")
                noise = check_range("sensor.noise_rms_m_per_s2", s["noise_rms_m_per_s2"], 0.0,
                                    MAX_ACCELERATION, unit="m/s^2")  # fmt: skip
                nprov = _provenance(s, "sensor")
            mg = d.get("model_gain", [])
            if not isinstance(mg, list):
                raise ConfigError("model_gain must be an array of tables ([[model_gain]])")
            gains = tuple(ModelGain.from_dict(g, f"model_gain[{i}]") for i, g in enumerate(mg))
            seen = [g.model for g in gains]
            twice = sorted({m for m in seen if seen.count(m) > 1})
            if twice:
                raise ConfigError(
                    f"model_gain: model {twice[0]!r} is given twice; valid: one gain per model"
                )
            return cls(
                name=name.strip(),
                description=desc,
                provenance=prov,
                input_channel=ch,
                end=end,
                bearing=bearing,
                fs_hz=d.get("fs_hz"),  # checked in __post_init__
                rpm_range=d.get("rpm_range"),  # checked in __post_init__
                gain=gain,
                gain_provenance=gprov,
                modes=tuple(Mode.from_dict(m, f"mode[{i}]") for i, m in enumerate(modes)),
                background=(
                    Background.from_dict(d["background"], "background")
                    if "background" in d
                    else None
                ),  # fmt: skip
                tones=tuple(Tone.from_dict(t, f"tone[{i}]") for i, t in enumerate(tones)),
                noise_rms_m_per_s2=noise,
                noise_provenance=nprov,
                model_gains=gains,
                source=source,
            )
        except ConfigError as exc:
            raise ConfigError(f"{source}: {exc}") from None

    def to_dict(self) -> dict[str, Any]:
        """The rig as its TOML table (round-trips through :meth:`from_dict`)."""
        out: dict[str, Any] = {
            "name": self.name,
            "description": self.description,
            "provenance": self.provenance,
            "input_channel": self.input_channel,
            "path": {"gain": self.gain, "provenance": self.gain_provenance},
        }
        if self.end is not None:
            out["end"] = self.end
        if isinstance(self.bearing, RigBearing):
            out["bearing"] = dataclasses.asdict(self.bearing)
        elif self.bearing is not None:
            out["bearing"] = self.bearing
        if self.fs_hz is not None:
            out["fs_hz"] = self.fs_hz
        if self.rpm_range is not None:
            out["rpm_range"] = list(self.rpm_range)
        if self.modes:
            out["mode"] = [dataclasses.asdict(m) for m in self.modes]
        if self.background is not None:
            b = self.background
            out["background"] = {
                "frequency_hz": list(b.frequency_hz),
                "psd_m2_per_s4_per_hz": list(b.psd),
            }
            if b.speed_exponent is not None:
                out["background"] |= {"speed_exponent": b.speed_exponent, "rpm_ref": b.rpm_ref}
            out["background"]["provenance"] = b.provenance
        if self.tones:
            out["tone"] = [
                {k: v for k, v in dataclasses.asdict(t).items() if v is not None}
                for t in self.tones
            ]
        out["sensor"] = {
            "noise_rms_m_per_s2": self.noise_rms_m_per_s2,
            "provenance": self.noise_provenance,
        }
        if self.model_gains:
            out["model_gain"] = [g.to_dict() for g in self.model_gains]
        return out

    def for_rotor(self) -> Rig:
        """The rig as the rotor model applies it: a fan-end rig (``end = "FE"``) whose input
        is a drive-end name (``acc_x``, ``acc_y``) reads the fan-end housing's channel
        (``acc_x_fe``, ``acc_y_fe``)."""
        if self.end == "FE" and self.input_channel in ("acc_x", "acc_y"):
            return dataclasses.replace(self, input_channel=f"{self.input_channel}_fe")
        return self

    def model_gain(self, model: str | None) -> ModelGain | None:
        """The model-based path gain of ``model``, or None when the rig has none for it."""
        return next((g for g in self.model_gains if g.model == model), None)

    def for_model(self, model: str | None) -> Rig:
        """The rig as applied to the output of ``model``: its path (direct gain and every
        mode) scaled by that model's ``[[model_gain]]`` (or, in its fitted form, those gains
        replaced by the fitted ones), with no model gains left; the rig itself, without its
        model gains, when it has none for ``model``."""
        g = self.model_gain(model)
        if g is None:
            return dataclasses.replace(self, model_gains=()) if self.model_gains else self
        if g.scale is None:  # the fitted form: the path's gains replaced
            return dataclasses.replace(
                self.with_gains(g.path_gain, g.mode_gains, f"for the {g.model} model "
                                f"({g.provenance})"),
                model_gains=(),
            )  # fmt: skip
        return dataclasses.replace(
            self,
            gain=self.gain * g.scale,
            gain_provenance=f"{self.gain_provenance}; x {g.scale:.6g} for the {g.model} model "
            f"({g.provenance})",
            modes=tuple(dataclasses.replace(m, gain=m.gain * g.scale) for m in self.modes),
            model_gains=(),
        )

    def with_gains(self, gain: float, mode_gains, why: str) -> Rig:
        """The rig with its direct gain and every mode's gain replaced (``mode_gains`` in the
        modes' order; frequencies and damping kept), each provenance saying ``why`` and the
        gain it replaces."""
        return dataclasses.replace(
            self,
            gain=float(gain),
            gain_provenance=f"{why}; output-only {self.gain:.6g}",
            modes=tuple(
                dataclasses.replace(
                    m,
                    gain=float(gk),
                    provenance=f"{m.provenance}; gain {why}, output-only {m.gain:.6g}",
                )  # fmt: skip
                for m, gk in zip(self.modes, mode_gains, strict=True)
            ),
        )

    def min_rate_hz(self) -> float:
        """The output rate :meth:`check_rate` needs to be above [Hz]: twice the highest of the
        modes' upper half-power frequencies, the fixed-frequency tones and the background
        table's first frequency (0 for a rig with none of them)."""
        f = [m.upper_half_power_hz for m in self.modes]
        f += [t.frequency_hz for t in self.tones if t.frequency_hz is not None]
        if self.background is not None:
            f.append(float(self.background.frequency_hz[0]))
        return 2.0 * float(max(f, default=0.0))

    def rate_problem(self, fs: float) -> tuple[str, str] | None:
        """What is wrong with the output rate ``fs`` [Hz] for this rig, as ``(reason,
        valid)``, or None: a mode (or its half-power band, :meth:`Mode.rate_problem`) or a
        fixed-frequency tone at or above its Nyquist frequency, or a background table lying
        wholly there (it would add nothing). (A tone given as an order is left out of a signal
        whose shaft speed puts it there, as a recorder's anti-aliasing filter removes it: that
        depends on the signal, not on the rig.)"""
        who = self.source or self.name
        for i, m in enumerate(self.modes):
            bad = m.rate_problem(fs, f"{who}: mode[{i}]")
            if bad is not None:
                return bad
        ny = 0.5 * fs
        for i, t in enumerate(self.tones):
            if t.frequency_hz is not None and t.frequency_hz >= ny:
                return (
                    f"{who}: tone[{i}].frequency_hz = {t.frequency_hz:g} Hz is at or above the "
                    f"Nyquist frequency of the output rate ({ny:g} Hz)",
                    f"valid range (0, {ny:g}) Hz",
                )
        bg = self.background
        if bg is not None and bg.frequency_hz[0] >= ny:
            return (
                f"{who}: background.frequency_hz[0] = {bg.frequency_hz[0]:g} Hz: the whole "
                f"background table lies at or above the Nyquist frequency of the output rate "
                f"({ny:g} Hz) and would add nothing",
                f"valid: a table that starts below {ny:g} Hz",
            )
        return None

    def check_rate(self, fs: float) -> None:
        """Refuse (one line) an output rate ``fs`` [Hz] with a :meth:`rate_problem`."""
        bad = self.rate_problem(fs)
        if bad is not None:
            raise ConfigError("; ".join(bad))

    def transfer(self, f: NDArray[np.float64], fs: float) -> NDArray[np.complex128]:
        """Frequency response of the path (direct gain plus modes, as discretised at ``fs``)
        at frequencies ``f`` [Hz] [-]."""
        from scipy.signal import sosfreqz

        self.check_rate(fs)
        h = np.full(np.shape(f), self.gain, dtype=complex)
        for m in self.modes:
            if m.gain == 0.0:  # contributes nothing (its filter would divide by zero)
                continue
            _, hk = sosfreqz(m.sos(fs), worN=np.asarray(f, dtype=float), fs=fs)
            h += hk
        return h

    def _check_speed_law(self, shaft_hz: float | None) -> None:
        """Refuse (one line) a shaft speed at which the background's speed law gives an RMS
        above :data:`~bearingsim.errors.MAX_ACCELERATION`."""
        b = self.background
        k = b.speed_factor(shaft_hz) if b is not None else 1.0
        if k == 1.0:
            return
        level = k * b.rms()
        if not level <= MAX_ACCELERATION:
            raise ConfigError(
                f"rig {self.name!r}: at {60.0 * shaft_hz:g} r/min the background's speed law, "
                f"(N / {b.rpm_ref:g} r/min)^{b.speed_exponent:g}, gives {level:.3g} m/s^2 RMS; "
                f"valid: a speed at which it stays below {MAX_ACCELERATION:g} m/s^2"
            )

    def apply(
        self,
        signal: NDArray[np.float64],
        fs: float,
        *,
        shaft_hz: float | None = None,
        seed: int = 0,
    ) -> NDArray[np.float64]:
        """The sensor's signal [m/s^2] for the bearing's acceleration ``signal`` [m/s^2]
        sampled at ``fs`` [Hz] (shaft speed ``shaft_hz`` [Hz] for the tones given as orders;
        ``seed`` for the background, the tones' phases and the sensor noise). A tone given as
        an order that lies at or above the Nyquist frequency at ``shaft_hz`` is left out (a
        recorder's anti-aliasing filter removes it)."""
        from scipy.signal import sosfilt

        seed = check_int("seed", seed)
        if shaft_hz is not None:
            shaft_hz = check_range("shaft_hz", shaft_hz, 0.0, lo_open=True, unit="Hz")
        x = np.asarray(signal, dtype=float)
        if x.ndim != 1 or x.size < 2:
            raise ConfigError(f"signal must be 1-D with at least 2 samples; got shape {x.shape}")
        if not np.all(np.isfinite(x)):
            raise ConfigError("signal has non-finite samples")
        fs = check_range("fs_hz", fs, 0.0, lo_open=True, unit="Hz")
        self.check_rate(fs)
        y = self.gain * x
        for m in self.modes:
            if m.gain != 0.0:  # a zero-gain mode contributes nothing
                y = y + sosfilt(m.sos(fs), x)
        rng = np.random.default_rng(seed)
        if self.background is not None:
            self._check_speed_law(shaft_hz)
            y = y + self.background.synthesize(x.size, fs, rng, shaft_hz)
        t = np.arange(x.size) / fs
        for tone in self.tones:
            f = tone.frequency(shaft_hz)
            if f < 0.5 * fs:
                y = y + tone.amplitude_m_per_s2 * np.sin(
                    2 * np.pi * f * t + rng.uniform(0, 2 * np.pi)
                )
        if self.noise_rms_m_per_s2 > 0.0:
            y = y + self.noise_rms_m_per_s2 * rng.standard_normal(x.size)
        if not np.all(np.isfinite(y)):
            raise ConfigError(
                f"rig {self.name!r}: the sensor signal is not finite (peak input "
                f"{float(np.max(np.abs(x))):.3g}, path gain {self.gain:.3g}); valid: a signal and "
                "gains whose product stays finite"
            )
        return y


def available_rigs() -> list[str]:
    """Names of the rig profiles shipped with the package."""
    return sorted(p.stem for p in PROFILES_DIR.glob("*.toml"))


def load_rig(name_or_path: str | Path) -> Rig:
    """A rig from a shipped profile name or a TOML file (validated; one-line errors). A name
    without ``.toml`` is a file where one exists, else a shipped profile; a folder of that
    name (e.g. a sweep's output ``-o cwru-de-12k``) does not hide the profile."""
    p = Path(name_or_path)
    if p.suffix.lower() != ".toml" and not p.is_file():
        shipped = PROFILES_DIR / f"{name_or_path}.toml"
        if not shipped.exists():
            names = available_rigs()
            raise ConfigError(
                f"rig = {str(name_or_path)!r} is neither a file nor a shipped profile; shipped: "
                + (", ".join(names) if names else "none yet (identify one with `rig identify`)")
            )
        p = shipped
    return Rig.from_dict(read_toml(p, "rig file"), source=p.name)


def _result_fs(result) -> float:
    """Sample rate of a simulation result [Hz]: its ``fs_hz`` or its time step's."""
    return float(result.meta.get("fs_hz") or 1.0 / float(np.mean(np.diff(result.time))))


def _shaft_hz(result) -> float | None:
    meta, sc = result.meta, result.scenario
    if isinstance(meta.get("shaft_hz"), int | float):
        return float(meta["shaft_hz"])
    for key in ("rpm", "speed_rpm"):
        if isinstance(sc.get(key), int | float):
            return float(sc[key]) / 60.0
    return None


class RigRateWarning(UserWarning):
    """The output rate reaches far above the band a rig was identified in: above its
    background table the sensor signal carries the model's output alone."""


class RigSpeedWarning(UserWarning):
    """A run's shaft speed lies far outside the speeds a rig was identified at: its
    background and tones are those speeds' machine, while the model's own vibration follows
    the run's speed."""


#: how far outside a rig's ``rpm_range`` a run's speed may lie before :func:`apply_rig` warns
#: (a share of the range's ends) [-]
RPM_MARGIN = 0.1


def speed_note(r: Rig, rpm: float | None) -> str | None:
    """The :class:`RigSpeedWarning` a run at shaft speed ``rpm`` [r/min] through ``r`` gets
    (more than :data:`RPM_MARGIN` outside ``r.rpm_range``), or None. The message does not
    name the run's speed: a sweep groups its runs' warnings by message, and a speed axis gave
    one line per speed (exploratory testing, twenty-fourth session)."""
    if r.rpm_range is None or rpm is None:
        return None
    lo, hi = r.rpm_range
    if lo * (1.0 - RPM_MARGIN) <= rpm <= hi * (1.0 + RPM_MARGIN):
        return None
    bg = r.background
    if bg is not None and bg.speed_exponent is not None:  # scaled, but beyond what was measured
        what = (
            f"its background is scaled as speed^{bg.speed_exponent:.3g}, a law fitted within "
            "those speeds" + (", and its tones are the machine's at them" if r.tones else "")
        )
    else:
        what = (
            "the rig's background and tones are the machine's at those speeds, while the "
            "model's own vibration follows the run's (a healthy bearing's ball-pass line grows "
            "with speed and can stand out of a background that does not)"
        )
    return (
        f"rig {r.name!r} was identified at {lo:g}-{hi:g} r/min; this run turns more than "
        f"{RPM_MARGIN:.0%} outside those speeds: {what}"
    )


def _warn_speed(r: Rig, fsh: float | None) -> None:
    """Warn (:func:`speed_note`) for the shaft speed ``fsh`` [Hz]."""
    note = speed_note(r, None if fsh is None else 60.0 * fsh)
    if note is not None:
        warnings.warn(note, RigSpeedWarning, stacklevel=3)


class RigBearingWarning(UserWarning):
    """A run's bearing is of another size than the one a rig's records were taken on: it sits
    in another housing, whose modes and background the rig does not have."""


#: relative difference of the pitch or rolling-element diameter, or any difference in the
#: number of elements, above which a run's bearing is another size than its rig's [-] (the
#: 6205 of seed VSM and the CWRU's measured 6205 differ by 0.1 %)
BEARING_SIZE_REL = 0.02


def bearing_note(r: Rig, run: dict | None) -> str | None:
    """The :class:`RigBearingWarning` a run whose bearing is ``run`` (the fields of a
    :class:`~bearingsim.geometry.BallBearing` as a result's ``meta["bearing"]`` holds them:
    ``id``, ``n_elements``, ``pitch_diameter``, ``element_diameter`` [m]) gets through ``r``,
    or None: another size than ``r.bearing`` (:data:`BEARING_SIZE_REL`)."""
    if r.bearing is None or not isinstance(run, dict):
        return None
    if isinstance(r.bearing, RigBearing):
        own = r.bearing
    else:
        from .catalog import get_bearing

        own = RigBearing.of(get_bearing(r.bearing))
    try:
        theirs = RigBearing(  # a run's bearing of no id is still compared by its sizes
            run.get("id") or "(no id)",
            int(run["n_elements"]),
            float(run["pitch_diameter"]),
            float(run["element_diameter"]),
        )
        if own.same_size(theirs):
            return None
    except (KeyError, TypeError, ValueError, ZeroDivisionError):
        return None
    # the three sizes compared, each side (an element diameter alone differing printed two
    # identical sizes; exploratory testing, twenty-fifth session)
    return (
        f"rig {r.name!r} was identified on records of the {own.describe()}; this run's "
        f"bearing {theirs.id} is another size ({theirs.sizes()}): it sits in another housing, "
        "whose modes and background the rig does not have"
    )


def _check_not_a_catalogue_twin(b: RigBearing) -> None:
    """Refuse a ``[bearing]`` table whose ``id`` names a catalogue bearing of another size (a
    run of that catalogue bearing was then warned that "the 6205-cwru is another size than the
    6205-cwru"; exploratory testing, twenty-fifth session)."""
    from .catalog import _catalog_files, get_bearing

    if b.id not in _catalog_files():
        return
    cat = RigBearing.of(get_bearing(b.id))
    if cat.same_size(b):
        return
    raise ConfigError(
        f"bearing.id = {b.id!r} names a catalogue bearing of another size ({cat.describe()}); "
        f'valid: bearing = "{b.id}" for that bearing, or another id for your own'
    )


def _warn_bearing(r: Rig, meta: dict) -> None:
    """Warn (:func:`bearing_note`) when the result's bearing (``meta["bearing"]``, or
    ``meta["bearing_fe"]`` for a rig fed by the fan-end housing) is another size than
    ``r.bearing``."""
    key = "bearing_fe" if r.input_channel.endswith("_fe") else "bearing"
    note = bearing_note(r, meta.get(key))
    if note is not None:
        warnings.warn(note, RigBearingWarning, stacklevel=3)


def _warn_no_gain(r: Rig, model: str | None) -> None:
    """Warn (:class:`RigGainWarning`) when ``r`` has a model-based path for another ring model
    but none for ``model`` (a ring model): the run passes through the output-only path (gain
    1), whose level the other ring model's gain says is not the records' (exploratory testing,
    twenty-fourth session: a VSM run through a rig with a DEM path, 102 m/s^2 RMS against the
    records' 1.7, without a word). A rig with only a rotor gain (the shipped profiles) does not
    warn: the ring models' output passes at gain 1 by design there."""
    ring = ("vsm", "dem", "tvsm")
    if model not in ring:
        return
    others = [g.model for g in r.model_gains if g.model in ring]
    if others:
        warnings.warn(
            f"rig {r.name!r} has a model-based path for {', '.join(others)} but none for "
            f"{model}: this run passes through the output-only path (gain 1), not at the "
            f"records' level; valid: a [[model_gain]] for {model} (rig identify --model-gain "
            f"{model}) or model = {others[0]!r}",
            RigGainWarning,
            stacklevel=3,
        )


class RigGainWarning(UserWarning):
    """A rig's model gain was identified with another defect profile than the run's (it
    matched that profile's level to the records, not this run's), or the rig has a gain for
    another ring model but none for the run's (it passes at the output-only gain 1)."""


def _defect_profiles(meta: dict) -> list[str]:
    """The drop profiles of the defects a result records (``meta["defect"]``: a ring model's
    one defect, or the rotor's per bearing), in order, without repeats."""
    d = meta.get("defect") or {}
    found = [d] if "profile" in d else [v for v in d.values() if isinstance(v, dict)]
    return list(dict.fromkeys(v["profile"] for v in found if v.get("profile")))


def _warn_gain_profile(mg: ModelGain, rig_name: str, meta: dict) -> None:
    other = [p for p in _defect_profiles(meta) if p != mg.defect_profile]
    if other:
        warnings.warn(
            f"rig {rig_name!r}: its {mg.model} model gain was identified with "
            f"defect_profile = {mg.defect_profile!r}; this run's defect is {other[0]!r}, whose "
            "level differs, so the sensor's level is not what identification matched (identify "
            "the gain with 'rig identify --model-gain ... --defect-profile')",
            RigGainWarning,
            stacklevel=3,
        )


#: share of the output's Nyquist frequency below which a rig's background table may end
#: before :func:`apply_rig` warns [-] (the shipped 12 kHz profiles' tables reach their
#: records' Nyquist frequency, 6 kHz, since the nineteenth session: a warning above 24 kHz)
COVERAGE_WARN = 0.5


def coverage_rate_hz(r: Rig) -> float:
    """The output rate above which :func:`apply_rig` warns that ``r``'s background table ends
    below :data:`COVERAGE_WARN` of the Nyquist frequency [Hz] (inf without a background)."""
    if r.background is None or not r.background.frequency_hz:
        return float("inf")
    return max(r.background.frequency_hz) / (COVERAGE_WARN * 0.5)


def _warn_coverage(r: Rig, fs: float) -> None:
    """Warn (:class:`RigRateWarning`) when ``r``'s background ends below :data:`COVERAGE_WARN`
    of the Nyquist frequency of ``fs`` [Hz], e.g. a 12 kHz profile on a 48 kHz output."""
    if fs > coverage_rate_hz(r):
        top = max(r.background.frequency_hz)
        warnings.warn(
            f"rig {r.name!r}: its background is defined up to {top:.4g} Hz, the output reaches "
            f"{0.5 * fs:.6g} Hz (fs {fs:.6g} Hz): above {top:.4g} Hz the sensor signal is the "
            "model's output alone; a profile identified at this rate fits it (e.g. "
            "cwru-de-48k for 48 kHz)",
            RigRateWarning,
            stacklevel=3,
        )


def measurement_noise(seed: int, rms: float, shape: tuple[int, ...], rig: bool):
    """The white measurement noise a model adds to its acceleration channels [m/s^2]: ``rms``
    times standard normal samples of ``shape``. Without a rig from ``default_rng(seed)`` (the
    stream since the first release); with one from ``SeedSequence([seed, 4])``, a stream of its
    own: the rig's background, tones and sensor noise draw from ``default_rng(seed)``, and the
    same stream made the noise's samples the background's Fourier coefficients (twenty-first
    session)."""
    gen = np.random.default_rng(np.random.SeedSequence([seed, 4]) if rig else seed)
    return rms * gen.standard_normal(shape)


def apply_rig(
    result,
    rig: Rig | str | Path,
    *,
    seed: int | None = None,
    channel: str = "acc_sensor",
    noise: dict[str, NDArray[np.float64]] | None = None,
):
    """A copy of a :class:`~bearingsim.results.SimulationResult` with the sensor's signal as
    channel ``channel`` [m/s^2]: the rig applied to its ``input_channel``. ``seed`` defaults to
    the scenario's ``seed`` (0 if it has none). A rig with a ``[[model_gain]]`` for the
    result's model sets its path (:meth:`Rig.for_model`). The rig as applied (its
    table, the model gain already in its path), the seed and the model gain are recorded in
    ``meta["rig"]``.

    ``noise`` (channel name -> samples [m/s^2]): the model's white measurement noise, for a
    result whose channels do not hold it yet. It is added to those channels, and the input
    channel's noise to the sensor's signal *after* the path: a measurement noise is the
    sensor's, not a vibration the structure rings with (before the twenty-first session it
    went through the rig's modes, ×27–57 in power at their frequencies)."""
    from .results import SimulationResult

    r = rig if isinstance(rig, Rig) else load_rig(rig)
    model = result.scenario.get("model") if isinstance(result.scenario, dict) else None
    mg = r.model_gain(model)
    if mg is not None:
        _warn_gain_profile(mg, r.name, result.meta)
    else:
        _warn_no_gain(r, model)
    r = r.for_model(model)
    _warn_bearing(r, result.meta)
    if r.input_channel not in result.channels:
        raise ConfigError(
            f"rig {r.name!r}: input_channel {r.input_channel!r} is not a channel of the result; "
            "channels: " + ", ".join(sorted(result.channels))
        )
    x = np.asarray(result.channels[r.input_channel])
    if x.ndim != 1:
        raise ConfigError(f"rig {r.name!r}: input_channel {r.input_channel!r} is not 1-D")
    sd = check_int("seed", result.scenario.get("seed", 0) or 0 if seed is None else seed)
    if not isinstance(channel, str) or not channel or channel in result.channels:
        raise ConfigError(
            f"channel = {channel!r} is invalid; valid: a new channel name (not one of the "
            f"result's: {', '.join(sorted(result.channels))})"
        )
    fs = _result_fs(result)
    _warn_coverage(r, fs)
    shaft_hz = _shaft_hz(result)
    _warn_speed(r, shaft_hz)
    y = r.apply(x, fs, shaft_hz=shaft_hz, seed=sd)
    channels = dict(result.channels)
    for name, v in (noise or {}).items():
        channels[name] = channels[name] + v
    if noise and r.input_channel in noise:
        y = y + noise[r.input_channel]
    channels[channel] = y
    units = dict(result.units) | {channel: "m/s^2"}
    applied = r.to_dict() | {"seed": sd, "output_channel": channel}
    if mg is not None:
        applied["applied_model_gain"] = {k: v for k, v in mg.to_dict().items() if k != "provenance"}
    meta = dict(result.meta) | {"rig": applied}
    return SimulationResult(
        time=result.time,
        channels=channels,
        units=units,
        scenario=result.scenario,
        meta=meta,
        dims=dict(result.dims),
    )
