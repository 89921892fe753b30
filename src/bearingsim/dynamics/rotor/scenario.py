"""The bearing–rotor–housing model behind :func:`bearingsim.simulate` (``model = "rotor"``).

Maps a :class:`~bearingsim.config.Scenario` (keys documented in :mod:`bearingsim.config`) to a
:class:`~bearingsim.dynamics.rotor_config.RotorConfig`, runs :func:`.rotor.simulate_rotor` and
returns a :class:`~bearingsim.results.SimulationResult` in the common file format.

Channels: ``acc_x``, ``acc_y`` — drive-end housing acceleration [m/s^2] (the CWRU DE
accelerometer; what ``analyze`` reads by default), ``acc_x_fe``, ``acc_y_fe`` — fan-end housing;
``disp_x_de``, ``disp_y_de``, ``disp_x_fe``, ``disp_y_fe`` — housing displacements [m];
``shaft_x_de``, ``shaft_y_de``, ``shaft_x_fe``, ``shaft_y_fe`` — shaft displacement at the bearing
nodes [m]; with ``per_ball``: ``ball_load_inner_de``/``_outer_de`` (time, ball_de) and
``ball_load_inner_fe``/``_outer_fe`` (time, ball_fe) [N].
"""

from __future__ import annotations

import dataclasses
import math
import time
from collections.abc import Callable

import numpy as np

from ..._version import __version__
from ...config import RotorScenario
from ...errors import ConfigError
from ...geometry import (
    Defect,
    check_clearance,
    check_unused_defect,
)
from ...results import SimulationResult
from ..budget import Budget, Estimate, check_budget
from ..checks import check_load, check_speed
from ..defect_meta import defect_meta
from .config import (
    Armature,
    BearingSupport,
    RotorConfig,
    Shaft,
    catalogue_bearing,
    default_housing,
)
from .model import check_fe_size, fe_estimate, plan_rotor, simulate_rotor

__all__ = [
    "check_rotor",
    "rotor_config_from_scenario",
    "run_rotor",
]


def _support(
    bearing_id: str, fault: str, angle_deg: float, sc: RotorScenario, end: str
) -> BearingSupport:
    f = None
    if fault != "none":
        f = Defect(
            fault, sc.defect_width_m, sc.defect_depth_m, math.radians(angle_deg),
            sc.defect_profile,
        )  # fmt: skip
    b = catalogue_bearing(bearing_id, f"{end}_bearing")
    clearance = getattr(sc, f"{end}_clearance_m")
    if clearance is not None:  # negative = preload; bounded like a bearing file's
        pd = check_clearance(b, clearance, name=f"{end}_clearance_m")
        b = dataclasses.replace(b, diametral_clearance=pd)
    try:
        return BearingSupport(
            b,
            f,
            contact_damping=sc.contact_damping_n_s_per_m,
            contact_roughness=sc.contact_roughness_m,
        )
    except ConfigError as exc:  # the two ends differ (6205 DE, 6203 FE): say which it is
        if f is None:
            raise
        raise ConfigError(
            f"{end}_fault = {fault!r} on the {end.upper()} bearing ({b.id}): {exc}"
        ) from None


def rotor_config_from_scenario(sc: RotorScenario) -> RotorConfig:
    """The :class:`RotorConfig` of a ``model = "rotor"`` scenario (validates every input and
    raises a one-line :class:`~bearingsim.errors.ConfigError` on bad values)."""
    bearings = {}  # each catalogue id once, named by the first key that gives it
    for name in ("de_bearing", "fe_bearing"):
        bid = getattr(sc, name)
        if bid not in bearings:
            bearings[bid] = catalogue_bearing(bid, name)
    if sc.de_fault == sc.fe_fault == "none":  # the defect keys are unused: a defect of either
        errors = []  # bearing, as a fault there would be
        for b in bearings.values():
            try:
                check_unused_defect(b, sc.defect_width_m, sc.defect_depth_m)
                break
            except ConfigError as exc:
                errors.append(exc)
        else:
            raise errors[0]
    pos = None
    if sc.disk_positions_mm is not None:  # one per disk (RotorScenario checks the count)
        pos = tuple(v * 1e-3 for v in sc.disk_positions_mm)
    arm = Armature(n_disks=sc.disks, positions=pos, distributed=sc.distributed_rotor)
    housing = default_housing(
        sc.housing_mass_kg, sc.housing_stiffness_n_per_m, sc.housing_damping_n_s_per_m
    )
    return RotorConfig(
        de=_support(sc.de_bearing, sc.de_fault, sc.de_defect_angle_deg, sc, "de"),
        fe=_support(sc.fe_bearing, sc.fe_fault, sc.fe_defect_angle_deg, sc, "fe"),
        housing_de=housing,
        housing_fe=housing,
        shaft=Shaft(mass_model=sc.shaft_mass_model),
        armature=arm,
        speed_rpm=sc.rpm,
        gravity=sc.gravity,
        ball_inertia=sc.ball_inertia,
        axial_load=sc.axial_load_n,
        unbalance=sc.unbalance_kg_m,
        bearing_loads=((sc.de_fx_n, sc.de_fy_n), (sc.fe_fx_n, sc.fe_fy_n)),
        n_elements=sc.n_elements,
        ball_diameter_spread=sc.ball_diameter_spread_m,
        ball_seed=sc.seed,
    )


def _checked_config(
    sc: RotorScenario, allow_overload: bool = False, budget: Budget | None = None
) -> RotorConfig:
    """The scenario's :class:`RotorConfig` with the speed checked for both bearings
    (:func:`..checks.check_speed`) and, under an axial load or an extra bearing load, each
    bearing's static equivalent load against its static capacity (ISO 76,
    :func:`..checks.check_load`; the radial load is the extra load at that bearing, the
    rotor's weight left out: ``allow_overload`` lifts the refusal above 2 C0); then the beam
    mesh's memory against ``budget`` and its size (:func:`.model.check_fe_size`, naming the
    scenario's ``disks``), before anything is built."""
    cfg = rotor_config_from_scenario(sc)
    for sup, (fx, fy), end in zip((cfg.de, cfg.fe), cfg.bearing_loads, ("de", "fe"), strict=True):
        check_speed(sup.bearing, sc.rpm, sc.fs_hz)
        fr = math.hypot(fx, fy)
        if cfg.axial_load > 0.0 or fr > 0.0:
            check_load(
                sup.bearing,
                fr,
                allow_overload,
                cfg.axial_load,
                name=f"hypot({end}_fx_n, {end}_fy_n)",
            )
    check_budget(fe_estimate(cfg), budget)  # a mesh too large to hold is refused first
    check_fe_size(cfg, disks="disks")
    return cfg


def _plan_args(sc: RotorScenario) -> dict:
    return {
        "duration": sc.duration_s,
        "sample_rate": sc.fs_hz,
        "dt": sc.dt_s,
        "ball_forces": sc.per_ball,
        "antialias": sc.antialias,
        "method": sc.solver.value,
    }


def check_rotor(
    scenario: RotorScenario, budget: Budget | None = None, allow_overload: bool = False
) -> Estimate:
    """Check a rotor scenario without running it: every input, the speed, the mesh and run
    estimates against ``budget`` (:func:`.model.plan_rotor`; this builds the model and its static
    state). ``allow_overload`` runs an axial load above twice the static capacity."""
    cfg = _checked_config(scenario, allow_overload, budget)
    return plan_rotor(cfg, **_plan_args(scenario), budget=budget).estimate


def run_rotor(
    scenario: RotorScenario,
    progress: Callable[[int], None] | None = None,
    budget: Budget | None = None,
    allow_overload: bool = False,
) -> SimulationResult:
    """Runner registered for ``Model.ROTOR`` in :mod:`bearingsim.simulate` (checked first, see
    :func:`check_rotor`)."""
    t_wall = time.perf_counter()
    cfg = _checked_config(scenario, allow_overload, budget)
    r = simulate_rotor(
        cfg,
        duration=scenario.duration_s,
        sample_rate=scenario.fs_hz,
        dt=scenario.dt_s,
        ball_forces=scenario.per_ball,
        antialias=scenario.antialias,
        method=scenario.solver.value,
        progress=progress,
        budget=budget,
        slip=scenario.slip_percent / 100.0,
        slip_seed=scenario.seed,
        jitter=scenario.pocket_jitter_percent / 100.0,
    )
    ch: dict[str, np.ndarray] = {}
    units: dict[str, str] = {}
    dims: dict[str, tuple[str, ...]] = {}
    names = ("acc_x", "acc_y", "acc_x_fe", "acc_y_fe")
    for k, name in enumerate(names):
        ch[name] = r.acceleration[:, k].copy()
        units[name] = "m/s^2"
    for k, name in enumerate(("x_de", "y_de", "x_fe", "y_fe")):
        ch[f"disp_{name}"] = r.housing_displacement[:, k].copy()
        ch[f"shaft_{name}"] = r.shaft_displacement[:, k].copy()
        units[f"disp_{name}"] = units[f"shaft_{name}"] = "m"
    if scenario.per_ball:
        zde = cfg.de.bearing.n_elements
        for race, arr in (("inner", r.ball_load_inner), ("outer", r.ball_load_outer)):
            for end, sl in (("de", slice(0, zde)), ("fe", slice(zde, None))):
                name = f"ball_load_{race}_{end}"
                ch[name] = arr[:, sl].copy()
                units[name] = "N"
                dims[name] = ("time", f"ball_{end}")
    noise: dict[str, np.ndarray] = {}
    if scenario.noise_rms_m_per_s2 > 0:
        from ...rig import measurement_noise

        e = measurement_noise(
            scenario.seed, scenario.noise_rms_m_per_s2, (r.time.size, 4), scenario.rig is not None
        )
        noise = {name: e[:, k] for k, name in enumerate(names)}
        if scenario.rig is None:  # with a rig, added after the path (rig.apply_rig)
            for name, v in noise.items():
                ch[name] = ch[name] + v
    kin = r.kinematics
    meta = {
        "model": "rotor",
        "bearing_id": cfg.de.bearing.id,
        "bearing": dataclasses.asdict(cfg.de.bearing),
        "bearing_fe_id": cfg.fe.bearing.id,
        "bearing_fe": dataclasses.asdict(cfg.fe.bearing),
        "fs_hz": scenario.fs_hz,
        "shaft_hz": cfg.shaft_hz,
        "kinematics": kin["DE"].as_dict(),
        "kinematics_fe": kin["FE"].as_dict(),
        "rotor": r.meta,
        "solver": r.meta["solver"],
        "dt_s": r.meta.get("dt_s", math.nan),
        "n_steps": r.meta["n_steps"],
        "noise": {
            "rms_m_s2": scenario.noise_rms_m_per_s2,
            "seed": scenario.seed,
            "generator": "numpy.random.default_rng(seed).standard_normal((n, 4)) on acc_x, "
            "acc_y, acc_x_fe, acc_y_fe"
            if scenario.rig is None
            else "numpy.random.default_rng(SeedSequence([seed, 4])).standard_normal((n, 4)) on "
            "acc_x, acc_y, acc_x_fe, acc_y_fe; the rig's input channel's added to the sensor's "
            "signal after the rig's path",
        },
        # as the ring models' meta["slip"] (exploratory testing, twenty-fifth session: a rotor
        # result did not say its slip; through a rig only meta["defaults"] had it)
        "slip": {
            "interval_sd_percent": scenario.slip_percent,
            "pocket_jitter_percent": scenario.pocket_jitter_percent,
            "seed": scenario.seed,
            "model": "each bearing's cage (end e: 0 DE, 1 FE) at speed w_cage (1 + s_k) over "
            "each ball-pass period, s_k ~ N(0, slip^2) clipped to +-0.5 from "
            "numpy.random.SeedSequence([seed, 1, e]), the intervals divided by E[1/(1 + s_k)] "
            "(the kinematic pass rate on average); pocket jitter: each pass instant moved by "
            "e_k T, e_k ~ N(0, jitter^2/2) from SeedSequence([seed, 1, e, 3]) "
            "(dynamics.rotor.model._with_slip, dynamics.slip)",
        },
        "defaults": scenario.defaults_record,
        "defect": {
            "DE": defect_meta(cfg.de.bearing, cfg.de.fault),
            "FE": defect_meta(cfg.fe.bearing, cfg.fe.fault),
        },  # fmt: skip
        "bearingsim_version": __version__,
        "wall_s": time.perf_counter() - t_wall,
    }
    res = SimulationResult(r.time.copy(), ch, units, scenario.to_dict(), meta, dims)
    if scenario.rig is not None:  # the measurement chain (channel acc_sensor)
        from ...rig import apply_rig, load_rig

        res = apply_rig(res, load_rig(scenario.rig).for_rotor(), noise=noise)
    return res
