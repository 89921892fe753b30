"""Signal files: one reader, :func:`read_signal`, for the vibration and shaft records the
analyses take — CWRU ``.mat`` records, bearingsim simulation results (``.nc``/``.h5``) and text
tables (``.csv``/``.txt``, through :func:`.read_table`)."""

from __future__ import annotations

import math
import re
from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from ..errors import ConfigError, check_positive
from .text import read_table

if TYPE_CHECKING:
    from ..geometry import Bearing

__all__ = [
    "CWRU_DEFAULT_FS",
    "SignalRecord",
    "column_speed_refutes",
    "read_signal",
    "speed_span_text",
    "steady_speed_hz",
]

#: the sample rate the CWRU normal baselines (``normal_0_97.mat``, no rate in the name) and 48k
#: drive-end records have (/work/shared/data/cwru/SOURCES.md) [Hz]. No longer a default: a
#: CWRU file whose name gives no rate has it read off its shaft lines (``io.cwru.infer_cwru_fs``)
CWRU_DEFAULT_FS = 48000.0

#: names of a time column [s] in a text file (lower case)
_TIME_NAMES = ("time_s", "time", "t", "time_ms", "time_us")
#: a time column's unit from its name's suffix: the factor to seconds
_TIME_UNITS = {"_ms": 1e-3, "_us": 1e-6}
#: standard gravity, the factor from g to m/s^2 (ISO 80000-3) [m/s^2]
G0 = 9.80665
#: an acceleration unit at the end of a signal column's name (``de_g``, ``DE (g)``,
#: ``acc[m/s^2]``, ``de_mps2``): the factor to m/s^2. A column named without one is read as
#: written; ``de_g`` was read as m/s^2, 9.8 times too small for every level and rig gain
_UNITS = r"(g|g0|m/s\^?2|m/s²|mps2|ms2|m_s2)"
_SIGNAL_UNIT = re.compile(rf"(?:_{_UNITS}|\s*\(\s*{_UNITS}\s*\)|\s*\[\s*{_UNITS}\s*\])$", re.I)


@dataclass(frozen=True)
class SignalRecord:
    """A signal read from a file.

    Attributes
    ----------
    x : ndarray
        Samples (acceleration [m/s^2] for CWRU and our results; a text file's column as written,
        or in [m/s^2] when its name ends in an acceleration unit: ``de_g``, ``DE (g)``,
        ``acc [m/s^2]``; a column in g is multiplied by 9.80665).
    fs : float
        Sample rate [Hz].
    rpm : float or None
        Shaft speed [r/min] (None when unknown or when a speed column is given).
    source : str
        File path.
    channel : str
        Channel (column) read.
    bearing : Bearing or None
        Bearing stored in the file (our results).
    speed_hz : ndarray or None
        Shaft speed per sample [Hz] (text ``speed_hz`` or ``rpm`` column) for order tracking.
    info : dict
        How fs/rpm were obtained (``fs_source``, ``rpm_source``); ``rpm_file`` [r/min], the
        speed the file states (a result's, a CWRU ``X###RPM``) where ``rpm`` overrode it.
    time : ndarray or None
        Sample times [s] (text time column).
    columns : tuple of str
        Column names of a text file (header or ``col0``, ``col1``, ...); empty otherwise.
    """

    x: NDArray[np.float64]
    fs: float
    rpm: float | None
    source: str
    channel: str
    bearing: Bearing | None = None
    speed_hz: NDArray[np.float64] | None = None
    info: dict[str, Any] = field(default_factory=dict)
    time: NDArray[np.float64] | None = None
    columns: tuple[str, ...] = ()


#: file suffixes read as bearingsim results (netCDF)
RESULT_SUFFIXES = (".nc", ".h5", ".nc4")


def _cwru_fs_from_name(name: str) -> float | None:
    m = re.search(r"(?<![0-9])(12|48)k", name, flags=re.IGNORECASE)
    return float(m.group(1)) * 1000.0 if m else None


#: how far a time column's sample may lie from the even grid through its first and last
#: samples [sample steps]: a time printed with round-off stays well within it; a gap or a
#: second rate puts samples whole steps off
EVEN_TIME_TOL_STEPS = 0.5


#: the largest relative uncertainty of a time column's rate that :func:`rate_of_times` rounds
#: within (printing round-off; a clock that drifts more keeps its measured rate) [-]
RATE_ROUNDING_REL = 1e-6


def rate_of_times(t: NDArray[np.float64]) -> float:
    """The sample rate [Hz] of evenly spaced, increasing times ``t`` [s]: over the whole span,
    then the number with the fewest significant digits within the rate's uncertainty that the
    times' own round-off leaves (twice their largest distance from the even grid, over the
    span), where that is at most :data:`RATE_ROUNDING_REL`; else to 10 significant digits.
    Exploratory testing, twenty-seventh session: a column printed with ``%.9g`` gave 12000.00004
    Hz, printed as such, and record 120 read "inner" at it and "uncertain" at 12000."""
    n = t.size - 1
    span = float(t[-1] - t[0])
    fs = n / span
    off = float(np.max(np.abs(t - (t[0] + span / n * np.arange(t.size)))))
    rel = 2.0 * off / span
    if rel <= RATE_ROUNDING_REL:
        for digits in range(1, 11):
            r = float(f"{fs:.{digits}g}")
            if abs(r / fs - 1.0) <= rel:
                return r
    return float(f"{fs:.10g}")


def _check_even(t: NDArray[np.float64], name: str, file: str) -> None:
    """Refuse a time column [s] (strictly increasing) that is not evenly spaced: a gap or a
    change of rate would be read as one rate, so every frequency after it is wrong without a
    word."""
    n = t.size - 1
    if n < 2:
        return
    step = (t[-1] - t[0]) / n
    off = np.abs(t - (t[0] + step * np.arange(t.size))) / step
    if float(off.max()) > EVEN_TIME_TOL_STEPS:
        dt = np.diff(t)
        med = float(np.median(dt))
        k = int(np.argmax(np.abs(dt - med)))
        raise ConfigError(
            f"file = {file!r}: the time column {name!r} is not evenly spaced: the step from "
            f"t = {t[k]:.9g} s is {dt[k]:.6g} s against a median {med:.6g} s (a gap or a "
            f"second rate; samples up to {float(off.max()):.3g} steps off an even grid); "
            "valid: evenly sampled times at one rate"
        )


def read_signal(
    path: str | Path,
    *,
    channel: str | None = None,
    fs_hz: float | None = None,
    rpm: float | None = None,
    time_column: int | None = None,
) -> SignalRecord:
    """Read a signal file.

    * ``.mat`` (CWRU Bearing Data Center): channel ``DE`` (default), ``FE`` or ``BA``,
      acceleration in [m/s^2]; rpm from ``X###RPM`` unless ``rpm`` is given; fs from ``fs_hz``,
      else from ``12k``/``48k`` in the file name, else 48 kHz.
    * ``.nc``/``.h5`` (bearingsim simulation result): channel ``x`` or ``y`` (default ``y``;
      rotor results also ``x_fe``, ``y_fe``, the fan-end housing; a result simulated through a
      rig also ``sensor``, the rig's output ``acc_sensor``, and that is then the default); fs,
      rpm and bearing from the file (``fs_hz``, ``rpm`` override).
    * ``.csv``/``.txt`` (:func:`.read_table`): a time column (named ``time_s``, ``time``,
      ``t``, ``time_ms`` or ``time_us`` — a name ending in ``_ms``/``_us`` is read in that unit
      —, or the one at index ``time_column``) gives the sample times and fs (from the whole
      span; times not evenly spaced, a gap or a second rate, are refused; an ``fs_hz`` that
      contradicts it by more than 0.1 % is refused, as for a simulation result, sixteenth
      session: it was taken over the times, and ``rig identify`` put modes at 4× their
      frequencies); a ``speed_hz`` or ``rpm`` column gives a per-sample
      shaft speed (order tracking); the signal is the column named ``channel`` or the first
      other one, read in [m/s^2] when its name ends in a unit of acceleration (``_g``,
      ``(g)``, ``[g]`` are multiplied by 9.80665; ``_mps2``, ``(m/s^2)``, ``[m/s^2]`` are kept;
      ``info["signal_unit_source"]`` says which), else as written. Without a time column
      ``fs_hz`` is required.

    Parameters
    ----------
    path : str or Path
        The file.
    channel : str, optional
        Channel or column name (see above).
    fs_hz : float, optional
        Sample rate [Hz].
    rpm : float, optional
        Shaft speed [r/min].
    time_column : int, optional
        Index of the time column of a text file whose header does not name it (or that has no
        header).

    Returns
    -------
    SignalRecord
        Samples with what the file says of them; ``rpm`` and ``speed_hz`` are both ``None``
        when the file gives no speed and ``rpm`` is not given.
    """
    p = Path(path)
    if not p.is_file():
        raise ConfigError(f"file = {str(p)!r} does not exist or is not a file")
    suffix = p.suffix.lower()
    if suffix == ".mat":
        return _read_cwru(p, channel, fs_hz, rpm)
    if suffix in RESULT_SUFFIXES:
        return _read_result(p, channel, fs_hz, rpm)
    if suffix in (".csv", ".txt"):
        return _read_text(p, channel, fs_hz, rpm, time_column)
    raise ConfigError(
        f"file = {p.name!r} has an unknown type; valid: .mat (CWRU), .nc/.h5 "
        "(bearingsim result), .csv/.txt"
    )


def _read_cwru(p: Path, channel: str | None, fs: float | None, rpm: float | None) -> SignalRecord:
    from .cwru import check_cwru_name_rate, cwru_nominal_rpm, infer_cwru_fs, read_cwru_mat

    rec = read_cwru_mat(p)
    ch = ("DE" if channel is None else channel).upper()
    if ch not in rec.channels or ch not in ("DE", "FE", "BA"):
        raise ConfigError(
            f"channel = {ch!r} not in {p.name} (keys X###_{ch}_time); valid: "
            + ", ".join(sorted(rec.channels))
        )
    info: dict[str, Any] = {}
    r = rpm if rpm is not None else rec.rpm
    if r is not None:
        info["rpm_source"] = "option" if rpm is not None else "file"
        r = check_positive("rpm", r, "r/min")
    if rpm is not None and rec.rpm is not None:  # the file's own, which the option overrides
        info["rpm_file"] = float(rec.rpm)
    named = _cwru_fs_from_name(p.name)
    if fs is None:
        fs = named
        info["fs_source"] = "file name"
    else:
        info["fs_source"] = "option"
    x = rec.acceleration(ch)
    # the speed a named rate is checked at: the file's own (X###RPM), else the name's nominal
    # one, else the option (a wrong --rpm must not overrule a rate the record confirms)
    nominal = cwru_nominal_rpm(p.name)
    check_speed = rec.rpm if rec.rpm is not None else (nominal[1] if nominal else r)

    def flat() -> None:  # no shaft line to read a rate off: say what the record is
        if x.size and np.all(x == x[0]):
            raise ConfigError(
                f"file = {p.name!r}, channel {ch!r}: all {x.size} samples equal {x[0]:.6g}; "
                "valid: a vibration signal"
            )

    if fs is None:  # the CWRU site's own names (105.mat) carry no rate: read it off the shaft
        if r is None:
            raise ConfigError(
                f"file = {p.name!r} has no X###RPM key and no --rpm was given, and its name no "
                "sample rate (12k/48k); valid: give --rpm R (> 0 r/min), and --fs-hz F (CWRU: "
                "12000 or 48000) unless the rate can be read off the shaft lines"
            )
        flat()
        # at the file's own speed where it states one: a --rpm 1 % off blamed the rate
        # (exploratory testing, twenty-sixth session: normal_0_97 at --rpm 1814)
        fs, why = infer_cwru_fs(x, rec.rpm if rec.rpm is not None else r)
        info["fs_source"] = f"inferred from the shaft lines ({why})"
    elif info["fs_source"] == "file name":  # the name's rate, unless the shaft lines refute it
        if check_speed is not None:
            flat()
            fs, why = check_cwru_name_rate(x, fs, check_speed)
            if why is not None:
                info["fs_source"] = f"inferred from the shaft lines ({why})"
    elif named is not None and float(fs) != named:  # an option against the name's rate
        refuted = check_speed is not None and check_cwru_name_rate(x, named, check_speed)[1]
        if not refuted:
            raise ConfigError(
                f"fs_hz = {float(fs):.6g} Hz contradicts the rate in the name of {p.name!r} "
                f"({named / 1000.0:g}k), which its shaft lines do not refute; valid: no "
                "--fs-hz for a CWRU file whose name gives its rate, or that rate"
            )
    return SignalRecord(
        x,
        check_positive("fs_hz", fs, "Hz"),
        r,
        str(p),
        ch,
        None,
        None,
        info,
    )


def _read_result(p: Path, channel: str | None, fs: float | None, rpm: float | None):
    from ..results import SimulationResult

    res = SimulationResult.load(p)
    # a result simulated through a rig carries what the sensor records (acc_sensor): that is
    # the signal a diagnosis reads by default, as it would an accelerometer's
    sensor = "acc_sensor" in res.channels
    ch = (("sensor" if sensor else "y") if channel is None else channel).lower()
    # rotor results also carry the fan-end housing (acc_x_fe, acc_y_fe) and its bearing
    valid = ("x", "y", "x_fe", "y_fe") if "acc_y_fe" in res.channels else ("x", "y")
    valid += ("sensor",) if sensor else ()
    if ch not in valid:
        raise ConfigError(
            f"channel = {channel!r} is invalid for this simulation result; valid: "
            + ", ".join(valid)
        )
    # the fan-end housing's bearing: its channels, or the sensor of a rig fed by that housing
    rig_in = (res.meta.get("rig") or {}).get("input_channel") if ch == "sensor" else None
    fan_end = ch.endswith("_fe") or (isinstance(rig_in, str) and rig_in.endswith("_fe"))
    meta = {"bearing": res.meta.get("bearing_fe")} if fan_end else res.meta
    try:
        r = rpm if rpm is not None else float(res.scenario["rpm"])
        fs_file = res.fs_hz
    except (KeyError, TypeError, ValueError):
        raise ConfigError(
            f"file = {str(p)!r}: the result names no shaft speed (rpm) or sample rate (fs_hz); "
            "valid: a simulation result written by bearingsim"
        ) from None
    if fs is not None and not math.isclose(float(fs), float(fs_file), rel_tol=1e-9):
        raise ConfigError(
            f"fs_hz = {float(fs):.6g} Hz contradicts the sample rate of the result "
            f"{p.name!r} ({float(fs_file):.6g} Hz); valid: no fs_hz for a simulation result "
            "(it states its own)"
        )
    x = res[f"acc_{ch}"]
    if not np.all(np.isfinite(x)):
        raise ConfigError(
            f"file = {str(p)!r}: channel acc_{ch} holds samples that are not finite; valid: "
            "finite samples"
        )
    info: dict[str, Any] = {"fs_source": "file", "rpm_source": "file" if rpm is None else "option"}
    if rpm is not None:  # the speed it was simulated at, which the option overrides
        info["rpm_file"] = float(res.scenario["rpm"])
    # a model's own channel without noise: a line spectrum over a floor no measurement has
    noise = res.scenario.get("noise_rms_m_per_s2", 0.0)
    if ch != "sensor" and not (isinstance(noise, int | float) and noise > 0.0):
        info["noise_free"] = True
    # a simulation's discrete lines at fixed frequencies are those its rig adds (none on a bare
    # model channel): the diagnosis reads a supply only there (signal.diagnosis._supply)
    tones = (res.meta.get("rig") or {}).get("tone", []) if ch == "sensor" else []
    info["fixed_tones_hz"] = tuple(
        float(t["frequency_hz"]) for t in tones if t.get("frequency_hz") is not None
    )
    if "oversampling" in res.meta:
        # 1: the ring models' default (the seeds'): each output sample is the mean of the
        # integrator's samples over its interval, which lets the broadband impacts' content
        # above fs/2 alias into the band (docs/models.md "Sampling")
        info["antialiased"] = int(res.meta["oversampling"]) > 1
    return SignalRecord(x, fs_file, r, str(p), ch, _bearing_from_meta(meta), None, info)


#: how far a speed given (``--rpm``) may lie outside the speeds a record's own speed column
#: holds (its 1st-99th percentile range) [-]: a CSV's ``rpm`` column of 1748 r/min and
#: ``--rpm 1500`` were read at 1500, silently, and a fault read "none" (exploratory testing,
#: twenty-fifth session); a run-up's column takes any speed it passed through
RPM_OPTION_REL = 0.01


def column_median_rpm(rec: SignalRecord) -> float | None:
    """The median [r/min] of ``rec``'s speed column over its positive finite samples (a
    tachometer's dropouts left out), None without a speed column or such a sample."""
    if rec.speed_hz is None:
        return None
    v = 60.0 * np.asarray(rec.speed_hz, dtype=float)
    v = v[np.isfinite(v) & (v > 0.0)]
    return float(np.median(v)) if v.size else None


def steady_speed_hz(speed_hz: ArrayLike, rel: float = RPM_OPTION_REL) -> float | None:
    """The median [Hz] of a speed column ``speed_hz`` [Hz] whose 1st-99th percentile range is
    positive and spans at most ``rel`` [-] (a steady speed, which a record's shaft lines can
    judge as they judge a ``--rpm``), else None."""
    sp = np.asarray(speed_hz, dtype=float)
    lo, hi = np.percentile(sp, [1.0, 99.0])
    if not (lo > 0.0 and hi / lo - 1.0 <= rel):
        return None
    return float(np.median(sp))


def column_speed_refutes(rec: SignalRecord, rpm: float) -> tuple[float, float] | None:
    """The 1st-99th percentile range ``(lo, hi)`` [r/min] of ``rec``'s speed column when the
    speed ``rpm`` [r/min] lies outside it by more than :data:`RPM_OPTION_REL`, else None (also
    without a speed column)."""
    if rec.speed_hz is None:
        return None
    v = 60.0 * np.asarray(rec.speed_hz, dtype=float)
    # a tachometer's dropouts (zeros) and invalid samples are no speed the machine ran at: with
    # more than 1 % of them the 1st percentile was 0 and any lower --rpm passed (exploratory
    # testing, twenty-fifth session); a column with no positive sample gives no range at all
    v = v[np.isfinite(v) & (v > 0.0)]
    if not v.size:
        return None
    span = tuple(float(q) for q in np.percentile(v, [1.0, 99.0]))
    return None if _holds(span, rpm) else span


def _holds(span: tuple[float, float], rpm: float) -> bool:
    """``rpm`` lies within :data:`RPM_OPTION_REL` of the range ``span`` [r/min]."""
    return span[0] * (1.0 - RPM_OPTION_REL) <= rpm <= span[1] * (1.0 + RPM_OPTION_REL)


def speed_span_text(span: tuple[float, float], rpm: float | None = None) -> str:
    """A :func:`column_speed_refutes` range as the messages write it: ``1748 r/min``, or
    ``1000-2000 r/min, 1st-99th percentile``; with the speed given ``rpm`` [r/min], a hint
    when the column reads like that speed in Hz (a column named ``rpm`` holding Hz)."""
    lo, hi = span
    text = (
        f"{lo:.5g} r/min" if f"{lo:.5g}" == f"{hi:.5g}"
        else f"{lo:.5g}-{hi:.5g} r/min, 1st-99th percentile"
    )  # fmt: skip
    if rpm is not None and _holds(span, rpm / 60.0):
        text += "; it reads like the speed in Hz: name such a column speed_hz"
    return text


def _bearing_from_meta(meta: dict[str, Any]) -> Bearing | None:
    from ..geometry import BallBearing, RollerBearing
    from ..materials import Material

    d = dict(meta.get("bearing") or {})
    if not d:
        return None
    try:
        d["material"] = Material(**d["material"])
        cls = BallBearing if "inner_groove_radius" in d else RollerBearing
        return cls(**d)
    except (TypeError, KeyError) as exc:
        raise ConfigError(f"bearing metadata in the result is invalid ({exc})") from None


def _read_text(
    p: Path, channel: str | None, fs: float | None, rpm: float | None, time_column: int | None
) -> SignalRecord:
    table = read_table(p)
    data = table.data
    header = list(table.names)
    cols = {h.lower(): i for i, h in enumerate(header)}
    info: dict[str, Any] = {}
    if time_column is not None:
        tcol = int(time_column)
        if not 0 <= tcol < len(header):
            raise ConfigError(
                f"time_column = {time_column!r} is invalid for {p.name}; valid range "
                f"[0, {len(header) - 1}]"
            )
    else:
        tcol = next((cols[n] for n in _TIME_NAMES if n in cols), None)
    t = None if tcol is None else data[:, tcol]
    if t is not None:
        # a unit in the column's name (time_ms, time_us) is taken, not ignored
        t = t * next((f for u, f in _TIME_UNITS.items() if header[tcol].lower().endswith(u)), 1.0)
        dt = np.diff(t)
        increasing = bool(dt.size and np.all(dt > 0))
        # to 10 significant digits: a time column written in decimals gives its rate with
        # round-off (12000.000000001 Hz for 1/12000 s printed to 18 digits), which a rate does
        # not have and which made a 1 s file 0.99999999 s long
        # the rate over the whole span, not the median step: times printed to the
        # microsecond have steps of 83 and 84 us at 12 kHz, whose median read 12048 Hz
        fs_t = rate_of_times(t) if increasing and t.size > 1 else math.nan
        if increasing:
            _check_even(t, header[tcol], p.name)
        if fs is None:
            if not increasing:
                raise ConfigError(
                    f"file = {str(p)!r}: the time column must increase; valid: strictly "
                    "increasing times [s]"
                )
            fs = fs_t
            info["fs_source"] = "time column"
        elif t.size > 1 and not abs(float(fs) / fs_t - 1.0) <= 1e-3:  # also when not increasing
            raise ConfigError(
                f"fs_hz = {float(fs):.6g} Hz contradicts the time column {header[tcol]!r} of "
                f"{p.name!r} ({fs_t:.6g} Hz); valid: no fs_hz for a file with a time column "
                "(its unit from the name: time_s, time_ms, time_us), or its rate"
            )
    if fs is None:
        raise ConfigError(
            f"file = {str(p)!r} has no time column; give fs_hz, its sample rate [Hz] (> 0; "
            "CLI --fs-hz)"
        )
    speed = None
    scol = cols.get("speed_hz")
    rcol = cols.get("rpm")
    if scol is not None:
        speed = data[:, scol]
    elif rcol is not None:
        speed = data[:, rcol] / 60.0
    skip = {c for c in (tcol, scol, rcol) if c is not None}
    if channel is not None:
        # the time and speed columns are read as such, not as a signal
        if channel.lower() not in cols or cols[channel.lower()] in skip:
            what = "not in" if channel.lower() not in cols else "is the time or speed column of"
            raise ConfigError(
                f"channel = {channel!r} {what} {p.name}; valid: "
                + ", ".join(h for i, h in enumerate(header) if i not in skip)
            )
        xcol = cols[channel.lower()]
    else:
        rest = [i for i in range(len(header)) if i not in skip]
        if not rest:
            raise ConfigError(f"file = {str(p)!r} has no signal column")
        # the one column named as an acceleration (acc...), else the first: by position a
        # speed column named speed_rpm, or a misspelt rpm, before it was read as the signal
        # (exploratory testing, twenty-fourth session)
        acc = [i for i in rest if header[i].strip().lower().startswith("acc")]
        xcol = acc[0] if len(acc) == 1 else rest[0]
    x = data[:, xcol]
    unit = _SIGNAL_UNIT.search(header[xcol].strip())
    if unit is not None:
        g = next(u for u in unit.groups() if u is not None).lower() in ("g", "g0")
        if g:
            x = x * G0
        info["signal_unit"] = "m/s^2"
        info["signal_unit_source"] = (
            f"column {header[xcol]!r}: g, read as m/s^2 (x {G0})"
            if g
            else f"column {header[xcol]!r}: m/s^2"
        )
    return SignalRecord(
        x,
        check_positive("fs_hz", fs, "Hz"),
        rpm,
        str(p),
        header[xcol],
        None,
        speed,
        info,
        t,
        tuple(header),
    )
