"""IAS scenario files: a flat TOML table of the IAS model inputs (SI, unit in the key name).

Every key is optional; the defaults are the seed's case (seed IAS §3.1). Unknown keys are errors.

==============================  ============================================================
key                             meaning
==============================  ============================================================
``bearing``                     catalogue id (default ``"NU204-ECP"``)
``bearing_file``                user bearing TOML (relative to the scenario file)
``rpm``                         target speed [r/min]: sets ``M_z = C_T 2 pi rpm/60``
``torque_nm``                   motor torque M_z [N m] (default 9.54; exclusive with ``rpm``)
``initial_rpm``                 initial shaft speed [r/min] (default 0)
``spall_width_m``               spall width L_d [m] (default 1e-3; 0 = healthy)
``spall_angle_deg``             spall centre azimuth [deg] from +y towards +x (project
                                convention; default 180, the bottom: seed ``phi_os = 1.5 pi``)
``fx_n``, ``fy_n``              radial load [N] (``F_y`` downward; default 0, 400)
``duration_s``, ``dt_s``        simulated time and RK4 step [s] (default 10, 1e-6)
``output_rate_hz``              output sample rate [Hz] (default 48000)
``method``                      ``"rk4"`` (default) or ``"dopri5"``
``contact_law``                 ``"seed"`` (default) or ``"harris"``
``spall_load``                  ``"stribeck"`` (default) or ``"dynamic"``
``skip_s``                      start-up left out of the analysis [s] (default 10 % of the run)
``mass_kg``                     m (1.3)
``inertia_kg_m2``               I (6.5e-5, not given by the seed)
``radial_damping_n_s_m``        C_s (400)
``torsional_damping_n_m_s_rad`` C_T (1.52)
``rolling_resistance``          mu (0.0015)
``first_roller_angle_rad``      Phi_0 (0)
``reference_load_n``            roller load for the seed contact stiffness [N] (F_r/Z)
==============================  ============================================================
"""

from __future__ import annotations

import math
from dataclasses import replace
from pathlib import Path
from typing import Any

from ...catalog import resolve_bearing
from ...errors import ConfigError, check_positive, check_range, read_toml
from .model import SEED_SPALL, ContactLaw, IasParams, SpallLoad

#: scenario key -> (IasParams field or run option, type)
SCENARIO_KEYS: dict[str, type] = {
    "bearing": str,
    "bearing_file": str,
    "rpm": float,
    "torque_nm": float,
    "initial_rpm": float,
    "spall_width_m": float,
    "spall_angle_deg": float,
    "fx_n": float,
    "fy_n": float,
    "duration_s": float,
    "dt_s": float,
    "output_rate_hz": float,
    "method": str,
    "contact_law": str,
    "spall_load": str,
    "skip_s": float,
    "mass_kg": float,
    "inertia_kg_m2": float,
    "radial_damping_n_s_m": float,
    "torsional_damping_n_m_s_rad": float,
    "rolling_resistance": float,
    "first_roller_angle_rad": float,
    "reference_load_n": float,
}
_FIELDS = {
    "fx_n": "fx",
    "fy_n": "fy",
    "mass_kg": "mass",
    "inertia_kg_m2": "inertia",
    "radial_damping_n_s_m": "radial_damping",
    "torsional_damping_n_m_s_rad": "torsional_damping",
    "rolling_resistance": "rolling_resistance",
    "first_roller_angle_rad": "first_roller_angle",
    "reference_load_n": "reference_load",
}
RUN_DEFAULTS = {"duration_s": 10.0, "dt_s": 1e-6, "output_rate_hz": 48_000.0, "method": "rk4"}


def read_scenario(path: str | Path) -> dict[str, Any]:
    """Read and type-check a scenario TOML; ``bearing_file`` is made absolute."""
    p = Path(path)
    data = read_toml(p, "scenario =")
    out: dict[str, Any] = {}
    for k, v in data.items():
        if k not in SCENARIO_KEYS:
            raise ConfigError(
                f"scenario key {k!r} in {p.name} is unknown; valid keys: "
                f"{', '.join(sorted(SCENARIO_KEYS))}"
            )
        typ = SCENARIO_KEYS[k]
        if typ is float and isinstance(v, int | float) and not isinstance(v, bool):
            v = float(v)
        if not isinstance(v, typ):
            raise ConfigError(f"scenario key {k} = {v!r} in {p.name} must be a {typ.__name__}")
        out[k] = v
    if "bearing_file" in out:
        out["bearing_file"] = str((p.parent / out["bearing_file"]).resolve())
    return out


def build_scenario(settings: dict[str, Any]) -> tuple[IasParams, dict[str, Any]]:
    """Turn scenario settings (file keys, CLI overrides merged) into :class:`IasParams` and the
    run options ``duration, dt, output_rate, method, skip_s``.

    The shaft speed is never imposed: ``rpm`` only sets the motor torque ``M_z = C_T w`` so that
    the free speed ``M_z / C_T`` equals it; the actual speed comes out of the torque balance.
    """
    s = {k: v for k, v in settings.items() if v is not None}
    unknown = set(s) - set(SCENARIO_KEYS)
    if unknown:
        raise ConfigError(
            f"scenario key {sorted(unknown)[0]!r} is unknown; valid keys: "
            f"{', '.join(sorted(SCENARIO_KEYS))}"
        )
    bid = s.get("bearing")
    bfile = s.get("bearing_file")
    if bid is None and bfile is None:
        bid = "NU204-ECP"
    bearing = resolve_bearing(bid, bfile)
    kw: dict[str, Any] = {_FIELDS[k]: v for k, v in s.items() if k in _FIELDS}
    for k in ("contact_law", "spall_load"):
        if k in s:
            enum_t = ContactLaw if k == "contact_law" else SpallLoad
            valid = [e.value for e in enum_t]
            if s[k] not in valid:
                raise ConfigError(f"{k} = {s[k]!r} is not valid; valid: {', '.join(valid)}")
            kw[k] = enum_t(s[k])
    ct = kw.get("torsional_damping", 1.52)
    if "rpm" in s and "torque_nm" in s:
        raise ConfigError("give at most one of rpm (sets M_z = C_T w) and torque_nm")
    if "rpm" in s:
        rpm = check_positive("rpm", s["rpm"], "r/min")
        kw["torque"] = float(ct) * 2.0 * math.pi * rpm / 60.0
    elif "torque_nm" in s:
        kw["torque"] = s["torque_nm"]
    if "initial_rpm" in s:
        kw["initial_speed"] = (
            2.0 * math.pi * check_range("initial_rpm", s["initial_rpm"], 0.0, unit="r/min") / 60.0
        )
    if "spall_width_m" in s or "spall_angle_deg" in s:
        width = check_range(
            "spall_width_m", s.get("spall_width_m", SEED_SPALL.width), 0.0, unit="m"
        )
        angle = math.radians(
            check_range(
                "spall_angle_deg", s.get("spall_angle_deg", 180.0), -360.0, 360.0, unit="deg"
            )
        )
        kw["spall"] = None if width == 0.0 else replace(SEED_SPALL, width=width, angle=angle)
    params = IasParams(bearing, **kw)
    run = {k: s.get(k, v) for k, v in RUN_DEFAULTS.items()}
    if run["method"] not in ("rk4", "dopri5"):
        raise ConfigError(f"method = {run['method']!r} is not valid; valid: rk4, dopri5")
    run["duration_s"] = check_positive("duration_s", run["duration_s"], "s")
    run["dt_s"] = check_positive("dt_s", run["dt_s"], "s")
    run["skip_s"] = s.get("skip_s")
    if run["skip_s"] is not None:
        run["skip_s"] = check_range(
            "skip_s", run["skip_s"], 0.0, run["duration_s"], hi_open=True, unit="s"
        )
    return params, run
