"""The ring models behind :func:`bearingsim.simulate` (``model = "vsm" | "dem" | "tvsm"``):
a :class:`~bearingsim.config.RingScenario` becomes :class:`~.base.ModelInputs`, is integrated by
the model's compiled kernel and returned as a :class:`~bearingsim.results.SimulationResult`.
"""

from __future__ import annotations

import dataclasses
import math
import time
from collections.abc import Callable
from typing import Any

import numpy as np

from ..._version import __version__
from ...catalog import resolve_bearing
from ...config import Model, RingScenario, Solver
from ...errors import SolverError
from ...geometry import characteristic_frequencies, defect_at_edge, defect_geometry
from ...results import SimulationResult
from . import dem, tvsm, vsm
from .base import (
    AUX_NAMES,
    ModelInputs,
    ModelKernel,
    integrate_model,
    integrate_model_adaptive,
    max_frequency,
    static_path,
)

__all__ = ["choose_steps", "model_inputs", "run_ring"]

#: accuracy target of the automatic RK4 step: omega_max * dt <= this [-] (see choose_steps)
OMEGA_DT = 0.35
#: RK4 stability limit on the imaginary axis, ``|omega dt| < 2 sqrt(2)`` [-]
RK4_STABILITY = 2.0 * math.sqrt(2.0)

#: compiled kernels of the ring models
KERNELS: dict[Model, ModelKernel] = {
    Model.VSM: vsm.KERNEL,
    Model.DEM: dem.KERNEL,
    Model.TVSM: tvsm.KERNEL,
}


def model_inputs(scenario: RingScenario) -> ModelInputs:
    """Physical inputs of a VSM/DEM/TVSM scenario (bearing resolved, defect validated)."""
    bearing = resolve_bearing(scenario.bearing, scenario.bearing_file)
    defect = None
    if scenario.fault != "none":  # the scenario gives seed VSM's left edge beta_0
        defect = defect_at_edge(
            bearing,
            scenario.fault,
            scenario.defect_width_m,
            scenario.defect_depth_m,
            scenario.defect_edge_angle_rad,
        )
    return ModelInputs(
        bearing=bearing,
        fx=scenario.fx_n,
        fy=scenario.fy_n,
        shaft_hz=scenario.shaft_hz,
        defect=defect,
        first_ball_angle=math.radians(scenario.first_ball_angle_deg),
        mass=scenario.resolved_mass_kg,
        damping=scenario.damping_n_s_per_m,
        stiffness=scenario.stiffness_n_per_m1_5,
        clearance=scenario.clearance_m,
        retention_factor=scenario.retention_factor,
        load_zone_half_angle=(
            None
            if scenario.load_zone_half_angle_deg is None
            else math.radians(scenario.load_zone_half_angle_deg)
        ),
    )


def choose_steps(scenario: RingScenario, inputs: ModelInputs) -> tuple[int, float, float]:
    """RK4 steps per output sample, step [s] and the largest natural frequency [rad/s].

    Automatic: the smallest integer ``decim`` with ``omega_max dt <= 0.35``: RK4's phase error
    ``(omega dt)^5/120`` (4e-5 rad) and amplitude error ``(omega dt)^6/144`` (1.3e-5) per step
    are then far below the physical damping per step of these models (``zeta omega dt``, about
    0.04 for c_eq = 300 N s/m); ``omega_max`` from the stiffness the model uses over one cage
    revolution. With ``dt_s`` given: ``decim = max(1, round(1/(fs dt_s)))``.
    """
    use = "secant" if KERNELS[scenario.model].stiffness == "secant" else "tangent"
    w = max_frequency(inputs, use)
    fs = scenario.fs_hz
    if scenario.dt_s is None:
        decim = max(1, math.ceil(w / (OMEGA_DT * fs)))
    else:
        decim = max(1, round(1.0 / (fs * scenario.dt_s)))
    return decim, 1.0 / (fs * decim), w


def run_ring(
    scenario: RingScenario, progress: Callable[[int], None] | None = None
) -> SimulationResult:
    """Run a VSM/DEM/TVSM scenario (the runner behind :func:`bearingsim.simulate`)."""
    t_wall = time.perf_counter()
    inputs = model_inputs(scenario)
    kernel = KERNELS[scenario.model]
    n = scenario.n_samples
    fs = scenario.fs_hz
    table0, res0 = static_path(inputs, np.zeros(1))
    y0 = np.array([table0[0, 0], table0[0, 1], 0.0, 0.0])
    decim, dt, w = choose_steps(scenario, inputs)
    if scenario.solver is Solver.RK4:
        try:
            raw = integrate_model(
                kernel, inputs, y0, fs, n + 1, decim, per_ball=scenario.per_ball, progress=progress
            )
        except SolverError as exc:
            auto = 1.0 / (fs * max(1, math.ceil(w / (OMEGA_DT * fs))))
            raise SolverError(
                f"dt_s = {dt:.6g} s is too large: {exc}; RK4 is stable only for "
                f"omega_max dt < 2.83 (omega_max = {w:.6g} rad/s): valid range "
                f"(0, {RK4_STABILITY / w:.3g}) s (automatic step {auto:.3g} s)"
            ) from None
    else:
        raw = integrate_model_adaptive(kernel, inputs, y0, fs, n + 1, per_ball=scenario.per_ball)
        dt = math.nan
    Z = inputs.bearing.n_elements
    ys, aux = raw.y[:n], raw.aux[:n]
    # sensor-like acceleration: mean over [t_k, t_k + 1/fs] = (v_{k+1} - v_k) fs, i.e. the
    # instantaneous model acceleration through a boxcar anti-aliasing filter (the model's
    # acceleration jumps when a ball meets a defect edge; point samples of a jump alias)
    acc_mean = np.diff(raw.y[:, 2:4], axis=0) * fs
    ch: dict[str, np.ndarray] = {
        "disp_x": ys[:, 0].copy(),
        "disp_y": ys[:, 1].copy(),
        "vel_x": ys[:, 2].copy(),
        "vel_y": ys[:, 3].copy(),
        "acc_x": acc_mean[:, 0].copy(),
        "acc_y": acc_mean[:, 1].copy(),
    }
    units = {"disp_x": "m", "disp_y": "m", "vel_x": "m/s", "vel_y": "m/s"}
    for k, name in enumerate(AUX_NAMES):
        key = name.replace("acc_", "acc_inst_")
        ch[key] = aux[:, k].copy()
    units.update(
        {
            "acc_x": "m/s^2",
            "acc_y": "m/s^2",
            "acc_inst_x": "m/s^2",
            "acc_inst_y": "m/s^2",
            "k_xx": "N/m",
            "k_xy": "N/m",
            "k_yy": "N/m",
            "k_load": "N/m",
            "n_loaded": "1",
        }
    )
    if scenario.per_ball:
        ch["ball_load"] = aux[:, 7 : 7 + Z].copy()
        ch["ball_deformation"] = aux[:, 7 + Z : 7 + 2 * Z].copy()
        units["ball_load"] = "N"
        units["ball_deformation"] = "m"
    if scenario.noise_rms_m_per_s2 > 0:
        rng = np.random.default_rng(scenario.seed)
        noise = scenario.noise_rms_m_per_s2 * rng.standard_normal((n, 2))
        ch["acc_x"] = ch["acc_x"] + noise[:, 0]
        ch["acc_y"] = ch["acc_y"] + noise[:, 1]
    kin = characteristic_frequencies(inputs.bearing, inputs.shaft_hz)
    geo: dict[str, Any] = {}
    if inputs.defect is not None:
        g = defect_geometry(inputs.bearing, inputs.defect)
        geo = {
            "h_s_m": g.h_s,
            "h_min_m": g.h_min,
            "delta_beta_rad": g.delta_beta,
            "race_radius_m": g.race_radius,
        }
    meta = {
        "channels": {
            "acc_x, acc_y": "mean acceleration over [t, t + 1/fs] (boxcar anti-aliasing) plus "
            "the optional measurement noise",
            "acc_inst_x, acc_inst_y": "instantaneous model acceleration at t",
            "k_xx, k_xy, k_yy, k_load": f"{kernel.stiffness} stiffness at t (k_load along the "
            "load direction)",
            "ball_load, ball_deformation": "per-ball contact force and (Q/K)^(2/3) at t",
        },
        "model": scenario.model.value,
        "model_stiffness": kernel.stiffness,
        "bearing_id": inputs.bearing.id,
        "bearing": dataclasses.asdict(inputs.bearing),
        "fs_hz": fs,
        "shaft_hz": inputs.shaft_hz,
        "cage_hz": inputs.cage_hz,
        "kinematics": kin.as_dict(),
        "defect": geo,
        "resolved": {
            "mass_kg": inputs.mass,
            "stiffness_n_per_m1_5": inputs.k_ball,
            "clearance_m": inputs.diametral_clearance,
            "theta0_rad": inputs.theta0,
            "initial_displacement_m": [float(y0[0]), float(y0[1])],
        },
        "solver": raw.solver,
        "dt_s": dt,
        "steps_per_sample": decim if raw.solver == "rk4" else None,
        "n_steps": raw.n_steps,
        "omega_max_rad_s": w,
        "static_residual_max": (
            float(res0.max()) if kernel.needs_table is False else raw.static_residual_max
        ),
        "noise": {
            "rms_m_s2": scenario.noise_rms_m_per_s2,
            "seed": scenario.seed,
            "generator": "numpy.random.default_rng(seed).standard_normal((n, 2))",
        },
        "bearingsim_version": __version__,
        "wall_s": time.perf_counter() - t_wall,
    }
    return SimulationResult(raw.t[:n].copy(), ch, units, scenario.to_dict(), meta)
