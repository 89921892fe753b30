"""STUB (issue 14) of the shared load-capacity check written by the statics engineer.

The statics work of issue 14 provides ``check_load(bearing, radial_load, allow_overload=False)``
(in :mod:`bearingsim.contact` or :mod:`bearingsim.load_distribution`). Until it lands, this
stand-in with that signature is what :mod:`.checks` re-exports and the ring and IAS runners
call; when merging, import the shared function in :mod:`.checks` instead and delete this module.
It reuses :func:`bearingsim.life.iso281.static_capacity` lazily (a sibling model family, so never
at import time).
"""

from __future__ import annotations

import warnings

from ..errors import ConfigError, check_range

__all__ = ["OverloadWarning", "check_load"]


class OverloadWarning(UserWarning):
    """The radial load exceeds the bearing's static capacity C0 (ISO 76)."""


def check_load(bearing, radial_load: float, allow_overload: bool = False) -> float:
    """Radial load ``F_r`` [N] against the static capacity ``C_0`` of ``bearing`` (ISO 76 contact
    stress, :func:`bearingsim.life.iso281.static_capacity`): refuse above
    ``STATIC_LIMIT_FACTOR C_0`` (2 C0) unless ``allow_overload``, warn above ``C_0``. Returns
    ``C_0`` [N]."""
    from ..life.iso281 import STATIC_LIMIT_FACTOR, static_capacity

    fr = check_range("radial_load_n", radial_load, 0.0, unit="N")
    sc = static_capacity(bearing)
    hi = STATIC_LIMIT_FACTOR * sc.c0
    if fr > hi and not allow_overload:
        raise ConfigError(
            f"radial_load_n = {fr:.6g} N exceeds {STATIC_LIMIT_FACTOR:g} x the static capacity "
            f"C0 = {sc.c0:.6g} N of {bearing.id} (contact stress {sc.stress_limit / 1e6:.0f} MPa, "
            f"ISO 76); valid range [0, {hi:.6g}] N (--allow-overload to run it anyway)"
        )
    if fr > sc.c0:
        warnings.warn(
            f"radial load {fr:.6g} N exceeds the static capacity C0 = {sc.c0:.6g} N of "
            f"{bearing.id} (ISO 76): the most loaded contact exceeds "
            f"{sc.stress_limit / 1e6:.0f} MPa and would deform plastically; the elastic model "
            "is outside its range",
            OverloadWarning,
            stacklevel=2,
        )
    return sc.c0
