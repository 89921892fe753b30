"""The record of a raceway or ball defect in a result's metadata (``meta["defect"]``), one
layout for the ring models (VSM, DEM, TVSM) and the rotor model (one entry per bearing)."""

from __future__ import annotations

from typing import Any

from ..geometry import Defect, DefectProfile, defect_geometry

__all__ = ["defect_meta"]


def defect_meta(bearing: Any, defect: Defect | None) -> dict[str, Any]:
    """The keys every defect records — ``race``, ``width_m``, ``depth_m`` [m], ``angle_rad``
    (its centre at ``t = 0``) [rad], ``profile`` and ``race_radius_m`` (the radius of the
    surface it is on; a ball defect's: the ball's) [m] — and, by profile:

    - a slot (``geometric``, ``rectangular``): seed VSM eqs. (1)-(3), ``h_s_m`` (the drop across
      the whole width) [m], ``h_min_m`` (the drop the ball takes, at most the depth) [m],
      ``delta_beta_rad`` (its extent) [rad]; a ball defect also ``h_min_inner_m`` (at the inner
      race; ``h_min_m`` is then at the outer race) [m];
    - a pit: ``pit_radius_m`` [m] and ``window_rad``, the azimuth span over which a contact
      overlaps it (the pit and the contact's length at ISO 76's 4.2 GPa on each side) [rad].

    ``{}`` without a defect."""
    if defect is None:
        return {}
    g = defect_geometry(bearing, defect)
    out: dict[str, Any] = {
        "race": defect.race.value,
        "width_m": defect.width,
        "depth_m": defect.depth,
        "angle_rad": defect.angle,
        "profile": defect.profile.value,
        "race_radius_m": g.race_radius,
    }
    if defect.profile is DefectProfile.PIT:
        from .defect_pit import pit_contacts

        grow = pit_contacts(bearing, defect)[2]
        out |= {"pit_radius_m": 0.5 * defect.width, "window_rad": g.delta_beta + 2.0 * grow}
    else:
        out |= {"h_s_m": g.h_s, "h_min_m": g.h_min, "delta_beta_rad": g.delta_beta}
        if g.h_min_inner is not None:
            out["h_min_inner_m"] = g.h_min_inner
    return out
