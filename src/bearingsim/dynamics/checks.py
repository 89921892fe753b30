"""Plausibility checks shared by the time-domain models, run before any work (issue 14).

- :func:`check_speed`: the shaft speed against the bearing's speed factor (a warning) and against
  what the model's output can resolve (a refusal);
- :func:`check_load`: the radial load against the bearing's static capacity ``C_0`` (ISO 76):
  :func:`bearingsim.contact.capacity.check_load`, shared with the static models.
"""

from __future__ import annotations

import warnings

from ..contact.capacity import check_load
from ..errors import ConfigError, check_positive
from ..geometry import SPEED_FACTOR_MAX, Bearing, characteristic_frequencies, check_speed_limit

__all__ = [
    "SPEED_FACTOR_WARN",
    "SpeedWarning",
    "check_load",
    "check_speed",
    "max_resolved_rpm",
    "speed_factor",
]

#: speed factor ``n d_m`` [mm r/min] above which a warning is given: the order of the largest
#: speed factors that catalogue lubrication guidance admits for rolling bearings with oil
#: lubrication (grease: about half of it for deep-groove ball bearings; SKF Rolling bearings
#: catalogue, "Lubrication", speed factor ``A = n d_m``); beyond it a real bearing needs a
#: special design (cage, oil-jet or oil-air lubrication), which none of the models describes.
SPEED_FACTOR_WARN = 1.0e6


class SpeedWarning(UserWarning):
    """The shaft speed is beyond the bearing's speed factor (:data:`SPEED_FACTOR_WARN`)."""


def speed_factor(bearing: Bearing, rpm: float) -> float:
    """Speed factor ``n d_m`` [mm r/min]: shaft speed [r/min] times the pitch diameter [mm]."""
    return rpm * bearing.pitch_diameter * 1e3


def max_resolved_rpm(bearing: Bearing, fs_hz: float) -> float:
    """Largest shaft speed [r/min] whose fastest ball-pass frequency (BPFI, inner ring rotating)
    lies below the Nyquist frequency ``fs_hz / 2`` of the output [Hz]."""
    bpfi_per_hz = characteristic_frequencies(bearing, 1.0).bpfi_hz  # BPFI / f_shaft [-]
    return 60.0 * 0.5 * fs_hz / bpfi_per_hz


def check_speed(bearing: Bearing, rpm: float, fs_hz: float, name: str = "rpm") -> float:
    """Check the shaft speed ``rpm`` [r/min] of a simulation with output rate ``fs_hz`` [Hz].

    Refuses (one-line :class:`~bearingsim.errors.ConfigError`) a speed whose inner-race ball-pass
    frequency BPFI (the fastest element-pass frequency of the kinematics, Harris & Kotzalas 2007,
    ch. 8; :func:`bearingsim.geometry.characteristic_frequencies`) is above the Nyquist frequency
    of the output: the output could not represent one ball passage, whatever the step, and a
    speed where the rings burst (:func:`bearingsim.geometry.check_speed_limit`). Warns
    (:class:`SpeedWarning`) above the speed factor :data:`SPEED_FACTOR_WARN`. Returns ``rpm``.

    Parameters
    ----------
    bearing : BallBearing or RollerBearing
        The bearing (pitch diameter, kinematics).
    rpm : float
        Shaft speed [r/min].
    fs_hz : float
        Output sample rate [Hz].
    name : str
        Field name in the messages.
    """
    n = check_positive(name, rpm, "r/min")
    hi = max_resolved_rpm(bearing, fs_hz)
    if n > hi:
        bpfi = characteristic_frequencies(bearing, n / 60.0).bpfi_hz
        # the range quoted is the one the run accepts: the ring-burst limit may be lower
        ok = min(hi, SPEED_FACTOR_MAX / (bearing.pitch_diameter * 1e3))
        raise ConfigError(
            f"{name} = {n:.6g} r/min puts the ball-pass frequency BPFI = {bpfi:.6g} Hz of "
            f"{bearing.id} above the Nyquist frequency {0.5 * fs_hz:.6g} Hz of fs_hz = "
            f"{fs_hz:.6g} Hz: the output cannot resolve the ball passes; valid range "
            f"(0, {ok:.6g}] r/min at this fs_hz"
            + (" (above that the rings burst)" if ok < hi else "")
        )
    check_speed_limit(bearing, n, name)
    a = speed_factor(bearing, n)
    if a > SPEED_FACTOR_WARN:
        warnings.warn(
            f"{name} = {n:.6g} r/min gives the speed factor n d_m = {a:.3g} mm r/min of "
            f"{bearing.id} (d_m = {bearing.pitch_diameter * 1e3:.4g} mm), above "
            f"{SPEED_FACTOR_WARN:.3g}: beyond the speed of catalogue bearings (r/min up to "
            f"{SPEED_FACTOR_WARN / (bearing.pitch_diameter * 1e3):.0f}); the model has no "
            "lubrication, cage or thermal limits",
            SpeedWarning,
            stacklevel=2,
        )
    return n
