"""The ring models behind :func:`bearingsim.simulate` (``model = "vsm" | "dem" | "tvsm"``):
a :class:`~bearingsim.config.RingScenario` becomes :class:`~.base.ModelInputs`, is integrated by
the model's compiled kernel and returned as a :class:`~bearingsim.results.SimulationResult`.
"""

from __future__ import annotations

import dataclasses
import math
import time
import warnings
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np

from ..._version import __version__
from ...catalog import resolve_bearing
from ...config import Model, RingScenario, Solver
from ...errors import ConfigError, SolverError
from ...geometry import (
    characteristic_frequencies,
    check_unused_defect,
    defect_at_edge,
)
from ...results import SimulationResult
from ..budget import F8, Budget, Estimate, check_budget
from ..checks import check_load, check_speed
from ..defect_meta import defect_meta
from ..sampling import PASS, STOP_DB, decimate_antialias
from . import _balance as bl
from .base import (
    AUX_NAMES,
    MODEL_FACTS,
    ModelInputs,
    ModelKernel,
    check_ball_bearing,
    integrate_model,
    integrate_model_adaptive,
    max_frequency,
    n_aux,
    static_path,
)

__all__ = [
    "RingPlan",
    "check_ring",
    "choose_steps",
    "model_inputs",
    "model_kernel",
    "plan_ring",
    "run_ring",
]

#: accuracy target of the automatic RK4 step: omega_max * dt <= this [-] (see choose_steps)
OMEGA_DT = 0.35
#: RK4 stability limit on the imaginary axis, ``|omega dt| < 2 sqrt(2)`` [-]
RK4_STABILITY = 2.0 * math.sqrt(2.0)

#: output samples per chunk of the fixed-step integration (:func:`.base.integrate_model`) [-]
CHUNK = 4800
#: largest number of RK4 steps in one chunk [-]: bounds the tabulated quasi-static solution
#: (two rows of :data:`._balance.NCOL` values per step) and the time between two progress
#: reports (and Ctrl-C checks); the chunk keeps :data:`CHUNK` samples up to 873 steps per sample
MAX_CHUNK_STEPS = 1 << 22

#: steps per sample beyond which a run is counted as this many (far beyond any step budget;
#: keeps the count an exact integer) [-]
MAX_DECIM = float(2**62)


def model_kernel(model: Model) -> ModelKernel:
    """The compiled kernels of one ring model. Its module is imported on first use, so a run
    compiles (once per installation: Numba's cache) only its own model's kernels and the shared
    ones, not the other two models' (each model's cold compile is about a minute)."""
    import importlib

    from ..notice import compile_notice

    with compile_notice(f"the {model.value} kernels"):
        return importlib.import_module(f".{model.value}", __package__).KERNEL


def _facts(model: Model) -> tuple[bool, str]:
    """``(needs_table, stiffness)`` of a model (:data:`.base.MODEL_FACTS`), without compiling."""
    return MODEL_FACTS[model.value]


def model_inputs(scenario: RingScenario) -> ModelInputs:
    """Physical inputs of a VSM/DEM/TVSM scenario (bearing resolved, defect validated)."""
    bearing = resolve_bearing(scenario.bearing, scenario.bearing_file)
    check_ball_bearing(bearing)  # before the defect keys (NU204-ECP: "this defect geometry
    # needs balls" without a fault; exploratory testing, twenty-fourth session)
    defect = None
    if scenario.fault != "none":  # the scenario gives seed VSM's left edge beta_0
        defect = defect_at_edge(
            bearing,
            scenario.fault,
            scenario.defect_width_m,
            scenario.defect_depth_m,
            scenario.defect_edge_angle_rad,
        )
    else:
        check_unused_defect(bearing, scenario.defect_width_m, scenario.defect_depth_m)
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
        slip=scenario.slip_percent / 100.0,
        slip_seed=scenario.seed,
        jitter=scenario.pocket_jitter_percent / 100.0,
        ball_diameter_spread=scenario.ball_diameter_spread_m,
        unbalance=scenario.unbalance_n,
        profile=scenario.defect_profile,
        roughness=scenario.contact_roughness_m,
        axial_load=scenario.axial_load_n,
    )


def choose_steps(scenario: RingScenario, inputs: ModelInputs) -> tuple[int, float, float]:
    """RK4 steps per internal sample (``oversampling`` of them per output sample), step [s] and
    the largest natural frequency [rad/s].

    Automatic: the smallest integer ``decim`` with ``omega_max dt <= 0.35``: RK4's phase error
    ``(omega dt)^5/120`` (4e-5 rad) and amplitude error ``(omega dt)^6/144`` (1.3e-5) per step
    are then far below the physical damping per step of these models (``zeta omega dt``, about
    0.04 for c_eq = 300 N s/m); ``omega_max`` from the stiffness the model uses over one cage
    revolution. With ``dt_s`` given: ``decim = max(1, round(1/(fs dt_s)))``, ``fs`` the
    internal rate ``oversampling * fs_hz``.
    """
    use = "secant" if _facts(scenario.model)[1] == "secant" else "tangent"
    # the fastest rate of the ring: its stiffest mode, or the damping's c/m where the ring is
    # overdamped (the eigenvalue of m x'' + c x' + k x tends to -c/m; with c = 1e30 N s/m the
    # stiffness-chosen step diverged)
    w = max(max_frequency(inputs, use), inputs.damping / inputs.mass)
    if not math.isfinite(w) or w <= 0.0:
        raise SolverError(
            f"the stiffness of {inputs.bearing.id} under fx_n = {inputs.fx:.6g} N, fy_n = "
            f"{inputs.fy:.6g} N has no finite natural frequency (omega_max = {w:.6g} rad/s); "
            "check the load, clearance and stiffness"
        )
    fs = scenario.fs_hz * scenario.oversampling
    if scenario.dt_s is None:
        decim = max(1, math.ceil(min(w / (OMEGA_DT * fs), MAX_DECIM)))
    else:
        decim = max(1, round(min(1.0 / (fs * scenario.dt_s), MAX_DECIM)))
        dt = 1.0 / (fs * decim)
        if w * dt > OMEGA_DT * 1.0001 and w * dt < RK4_STABILITY:  # beyond: refused when run
            warnings.warn(
                f"dt_s = {dt:.6g} s gives omega_max dt = {w * dt:.2f}, above the {OMEGA_DT} of "
                f"the automatic step ({1.0 / (fs * math.ceil(w / (OMEGA_DT * fs))):.3g} s): RK4 "
                "is stable but its phase and amplitude errors are no longer small beside the "
                "model's damping (a DEM outer fault at 2.1 read 48 % low in RMS)",
                RuntimeWarning,
                stacklevel=2,
            )
    return decim, 1.0 / (fs * decim), w


@dataclass(frozen=True)
class RingPlan:
    """A checked ring-model run: its inputs, steps and resource estimate
    (:func:`plan_ring`), and the static state at ``t = 0`` (``static_path``'s table row and
    residual, solved once for the deflection check and the run's initial state)."""

    inputs: ModelInputs
    decim: int
    dt: float
    omega_max: float
    chunk: int
    estimate: Estimate
    static0: tuple[np.ndarray, np.ndarray]


def _estimate(scenario: RingScenario, inputs: ModelInputs, decim: int, chunk: int) -> Estimate:
    """Memory [B] and RK4 steps of a run: the raw trajectory (at the internal rate), the
    channels and their copy in the result's dataset, and the largest chunk's table of the
    quasi-static solution."""
    n_out = scenario.n_samples
    n = n_out * scenario.oversampling
    na = n_aux(inputs, scenario.per_ball)
    n_ch = 6 + len(AUX_NAMES) + (2 * inputs.bearing.n_elements if scenario.per_ball else 0)
    raw = (n + 1) * (1 + 4 + na) * F8
    channels = 2 * n_out * n_ch * F8
    table = 0.0
    if _facts(scenario.model)[0]:
        n_tab = 2.0 * min(chunk, n) * decim + 1
        table = n_tab * (2 * bl.NCOL + 3) * F8  # the table, its copy in p, times, residuals
    over = f" ({scenario.oversampling}x oversampled)" if scenario.oversampling > 1 else ""
    what = f"{scenario.model.value}: {n + 1} samples{over} x {decim} RK4 steps"
    return Estimate(what, raw + channels + table, float(n) * decim)


def _check_deflection(inputs: ModelInputs) -> tuple[np.ndarray, np.ndarray]:
    """The static state at ``t = 0`` (``static_path``'s table and residual), after refusing a
    stiffness (or load) whose static deflection exceeds the rolling element's diameter: not a
    contact's, and the run diverged at t = 0 with a message about the state's bound
    (``stiffness_n_per_m1_5 = 1`` passed every check before; exploratory testing,
    twenty-third session)."""
    from ...contact.hertz import element_stiffness

    table0, res0 = static_path(inputs, np.zeros(1))
    u = math.hypot(float(table0[0, 0]), float(table0[0, 1]))
    d = inputs.bearing.element_diameter
    if not u < d:  # also NaN
        hertz = element_stiffness(inputs.bearing)[0]
        f = math.hypot(inputs.fx, inputs.fy)
        raise ConfigError(
            f"stiffness_n_per_m1_5 = {inputs.k_ball:.6g} N/m^1.5 under |(fx_n, fy_n)| = "
            f"{f:.6g} N puts the static deflection at {u:.3g} m, more than the rolling "
            f"element's diameter ({d:.3g} m); valid: a contact's stiffness (Hertz gives "
            f"{hertz:.3g} N/m^1.5 for {inputs.bearing.id}, the default) and a load it carries"
        )
    return table0, res0


def plan_ring(
    scenario: RingScenario, budget: Budget | None = None, allow_overload: bool = False
) -> RingPlan:
    """Check a VSM/DEM/TVSM scenario before any work and plan its run.

    Builds the model inputs (every value checked), checks the peak radial load (static plus
    unbalance) against the bearing's static capacity (:func:`..checks.check_load`;
    ``allow_overload`` lifts the refusal above 2 C0), the speed against what the output
    resolves (:func:`..checks.check_speed`), chooses the step (:func:`choose_steps`) and checks
    the memory and step estimate against ``budget`` (:mod:`..budget`). Bad values raise a
    one-line :class:`~bearingsim.errors.ConfigError`.
    """
    inputs = model_inputs(scenario)
    if _facts(scenario.model)[1] == "secant":
        inputs.require_clearance(f"model {scenario.model.value}")
    check_load(  # the peak radial load: the static one plus the rotating unbalance
        inputs.bearing,
        math.hypot(inputs.fx, inputs.fy) + inputs.unbalance,
        allow_overload,
        inputs.axial_load,
        name="|(fx_n, fy_n)| + unbalance_n" if inputs.unbalance > 0.0 else "|(fx_n, fy_n)|",
    )
    inputs.axial_state  # noqa: B018 -- solved here: a bad axial load fails before any work
    check_speed(inputs.bearing, scenario.rpm, scenario.fs_hz)
    static0 = _check_deflection(inputs)
    decim, dt, w = choose_steps(scenario, inputs)
    chunk = max(1, min(CHUNK, MAX_CHUNK_STEPS // decim))
    est = check_budget(_estimate(scenario, inputs, decim, chunk), budget)
    return RingPlan(inputs, decim, dt, w, chunk, est, static0)


def check_ring(
    scenario: RingScenario, budget: Budget | None = None, allow_overload: bool = False
) -> Estimate:
    """:func:`plan_ring` without running: the resource estimate of a valid scenario."""
    return plan_ring(scenario, budget, allow_overload).estimate


def run_ring(
    scenario: RingScenario,
    progress: Callable[[int], None] | None = None,
    budget: Budget | None = None,
    allow_overload: bool = False,
) -> SimulationResult:
    """Run a VSM/DEM/TVSM scenario (the runner behind :func:`bearingsim.simulate`); checked
    first by :func:`plan_ring` (``budget``, ``allow_overload``)."""
    t_wall = time.perf_counter()
    plan = plan_ring(scenario, budget, allow_overload)
    inputs = plan.inputs
    kernel = model_kernel(scenario.model)
    n = scenario.n_samples
    fs = scenario.fs_hz
    q = scenario.oversampling
    fs_int = q * fs  # the internal rate (antialias: q > 1)
    table0, res0 = plan.static0
    y0 = np.array([table0[0, 0], table0[0, 1], 0.0, 0.0])
    decim, dt, w = plan.decim, plan.dt, plan.omega_max
    if scenario.solver is Solver.RK4:
        try:
            raw = integrate_model(
                kernel, inputs, y0, fs_int, q * n + 1, decim, per_ball=scenario.per_ball,
                chunk=plan.chunk, progress=None if progress is None else lambda i: progress(i // q),
            )  # fmt: skip
        except SolverError as exc:
            auto = 1.0 / (fs_int * max(1, math.ceil(w / (OMEGA_DT * fs_int))))
            if w * dt <= OMEGA_DT * 1.0001:  # the step is well inside RK4's stability limit
                what = str(exc).split(" with dt = ")[0]  # without the step hint
                raise SolverError(
                    f"{what} with dt_s = {dt:.3g} s, well inside RK4's stability limit "
                    f"(omega_max dt = {w * dt:.2f} < 2.83): not the step; the model's state "
                    "itself ran away — check stiffness_n_per_m1_5, damping_n_s_per_m, mass_kg "
                    "and the loads"
                ) from None
            raise SolverError(
                f"dt_s = {dt:.6g} s is too large: {exc}; RK4 is stable only for "
                f"omega_max dt < 2.83 (omega_max = {w:.6g} rad/s): valid range "
                f"(0, {RK4_STABILITY / w:.3g}) s (automatic step {auto:.3g} s)"
            ) from None
    else:
        raw = integrate_model_adaptive(
            kernel, inputs, y0, fs_int, q * n + 1, per_ball=scenario.per_ball
        )
        dt = math.nan
    Z = inputs.bearing.n_elements
    ys, aux = raw.y[: q * n : q], raw.aux[: q * n : q]
    # sensor-like acceleration: mean over [t_k, t_k + 1/fs] = (v_{k+1} - v_k) fs, i.e. the
    # instantaneous model acceleration through a boxcar anti-aliasing filter (the model's
    # acceleration jumps when a ball meets a defect edge; point samples of a jump alias).
    # antialias: the same at the internal rate, then the anti-aliasing filter of a
    # data-acquisition chain and every q-th sample (..sampling.decimate_antialias)
    acc_mean = decimate_antialias(np.diff(raw.y[:, 2:4], axis=0) * fs_int, q)
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
    noise: dict[str, np.ndarray] = {}
    if scenario.noise_rms_m_per_s2 > 0:
        from ...rig import measurement_noise

        e = measurement_noise(
            scenario.seed, scenario.noise_rms_m_per_s2, (n, 2), scenario.rig is not None
        )
        noise = {"acc_x": e[:, 0], "acc_y": e[:, 1]}
        if scenario.rig is None:  # with a rig, added after the path (rig.apply_rig)
            ch = ch | {k: ch[k] + v for k, v in noise.items()}
    kin = characteristic_frequencies(inputs.kinematic_bearing, inputs.shaft_hz)
    defect = inputs.defect  # the ring's Defect leaves the profile to the inputs
    if defect is not None:
        defect = dataclasses.replace(defect, profile=inputs.profile)
    meta = {
        "channels": {
            "acc_x, acc_y": (
                f"mean acceleration over [t, t + 1/({q} fs)], low-passed (Kaiser FIR, pass "
                f"band to {PASS:g} x Nyquist, {STOP_DB:g} dB from Nyquist) and decimated by {q} "
                "(dynamics.sampling), plus the optional measurement noise"
                if q > 1
                else "mean acceleration over [t, t + 1/fs] (boxcar anti-aliasing) plus the "
                "optional measurement noise"
            ),
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
        "defect": defect_meta(inputs.bearing, defect),
        "resolved": {
            "mass_kg": inputs.mass,
            "stiffness_n_per_m1_5": inputs.k_ball,
            "clearance_m": inputs.diametral_clearance,
            "theta0_rad": inputs.theta0,
            "initial_displacement_m": [float(y0[0]), float(y0[1])],
        },
        "solver": raw.solver,
        "oversampling": q,
        "dt_s": dt,
        "steps_per_sample": q * decim if raw.solver == "rk4" else None,
        "n_steps": raw.n_steps,
        "omega_max_rad_s": w,
        "static_residual_max": (
            float(res0.max()) if kernel.needs_table is False else raw.static_residual_max
        ),
        "noise": {
            "rms_m_s2": scenario.noise_rms_m_per_s2,
            "seed": scenario.seed,
            "generator": "numpy.random.default_rng(seed).standard_normal((n, 2))"
            if scenario.rig is None
            else "numpy.random.default_rng(SeedSequence([seed, 4])).standard_normal((n, 2)), "
            "added to the sensor's signal after the rig's path",
        },
        "slip": {
            "interval_sd_percent": scenario.slip_percent,
            "pocket_jitter_percent": scenario.pocket_jitter_percent,
            "seed": scenario.seed,
            "model": "cage speed w_cage (1 + s_k) over each ball-pass period, s_k ~ "
            "N(0, slip^2) clipped to +-0.5 from numpy.random.SeedSequence([seed, 1]), the "
            "intervals divided by E[1/(1 + s_k)] (the kinematic pass rate on average); pocket "
            "jitter: each pass "
            "instant moved by e_k T, e_k ~ N(0, jitter^2/2) from SeedSequence([seed, 1, 3]) "
            "(ModelInputs.slip_table, dynamics.slip)",
        },
        "contact": {
            "roughness_m": scenario.contact_roughness_m,
            "model": "Hertz load law averaged over a normal asperity-height offset of standard "
            "deviation roughness_m (bearingsim.contact.rough); 0 = Hertz",
        },
        "axial": {
            "force_n": inputs.axial_load,
            "offset_z_m": inputs.axial_state.z,
            "contact_angle_deg": math.degrees(inputs.axial_state.contact_angle),
            "ball_contact_angles_deg": [
                float(math.degrees(a)) for a in inputs.axial_state.ball_contact_angles
            ],
            "model": "inner ring's groove centres offset axially by z (Jones equilibrium of "
            "(fx_n, fy_n, axial_load_n) at t = 0, tilts held), held while the ring moves "
            "radially; the cage and ball spin at the load-weighted mean contact angle; "
            "0 N = the radial model",
        },
        "unbalance": {
            "force_n": scenario.unbalance_n,
            "model": "F_u (sin w_s t, cos w_s t) added to (fx_n, fy_n), turning with the shaft",
        },
        "ball_diameters": {
            "spread_m": scenario.ball_diameter_spread_m,
            "deviation_m": [float(v) for v in inputs.ball_deviations()],
            "seed": scenario.seed,
            "model": "uniform from numpy.random.SeedSequence([seed, 2]), scaled to span the "
            "spread, zero mean (ModelInputs.ball_deviations)",
        },
        "defaults": scenario.defaults_record,
        "bearingsim_version": __version__,
        "wall_s": time.perf_counter() - t_wall,
    }
    res = SimulationResult(raw.t[: q * n : q].copy(), ch, units, scenario.to_dict(), meta)
    if scenario.rig is not None:  # the measurement chain (channel acc_sensor)
        from ...rig import apply_rig

        res = apply_rig(res, scenario.rig, noise=noise)
    return res
