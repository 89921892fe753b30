"""Fault-dynamics commands: ``simulate``, ``vsm-trace`` (SPEC §1, §0.5); ``analyze`` is in
:mod:`.analyze`."""

from __future__ import annotations

import math
import sys
import time
from pathlib import Path
from typing import Any

import click

from ..config import DEFECT_PROFILES, IasScenario, Model, Scenario, Solver
from ..errors import ConfigError, check_range
from .common import (
    CLEARANCE,
    Number,
    allow_overload_option,
    check_outputs,
    cli,
    deprecated,
    echo_warnings,
    emit_json,
    json_option,
    output_option,
)
from .common import scenario_default as _d
from .limits import budget_options
from .rotor import rotor_simulate_options

__all__ = [
    "simulate_cmd",
    "vsm_trace_cmd",
]

_FAULTS = ["none", "outer", "inner", "ball"]


def _shared_options(f, every_family: bool):
    """Options shared by ``simulate`` and ``vsm-trace``; each overrides the scenario key of the
    same name (``--fx-n`` sets ``fx_n``); ``[default: ...]`` is the value when neither the option
    nor the scenario file sets it (``every_family``: also each other model family's that
    differs, for ``simulate``; ``vsm-trace`` runs the ring models only)."""
    opts = [
        click.option(
            "--bearing",
            "bearing",
            default=None,
            show_default=_d("bearing", others=every_family),
            help="Catalogue id.",
        ),
        click.option(
            "--bearing-file",
            default=None,
            type=click.Path(dir_okay=False),
            help="User bearing TOML file.",
        ),
        click.option(
            "--fault",
            type=click.Choice(_FAULTS),
            default=None,
            show_default=_d("fault", others=every_family),
            help="Defect location (ball: ball 1 carries it).",
        ),
        click.option(
            "--defect-width-m",
            type=Number(0.0, lo_open=True, unit="m"),
            default=None,
            show_default=_d("defect_width_m", others=every_family),
            help="Defect width b along the raceway [m] (CWRU 0.007 in).",
        ),
        click.option(
            "--defect-depth-m",
            type=Number(0.0, lo_open=True, unit="m"),
            default=None,
            show_default=_d("defect_depth_m", others=every_family),
            help="Defect depth h_d [m] (CWRU 0.011 in).",
        ),
        click.option(
            "--defect-profile",
            type=click.Choice(DEFECT_PROFILES),
            default=None,
            show_default="rectangular; rotor and with --rig: geometric"
            if every_family
            else "rectangular",
            help="How a ball loses support over the defect: a slot across the track (the "
            "seed's rectangular drop, or geometric: resting on the nearer edge), or pit: a round "
            "pit of diameter --defect-width-m narrower than the contact (CWRU's EDM faults).",
        ),
        click.option(
            "--defect-edge-angle-deg",
            type=Number(-360.0, 360.0, unit="deg"),
            default=None,
            show_default=_d("defect_edge_angle_deg", others=every_family),
            help="Azimuth of the defect's left edge at t = 0, beta_0 [deg] (seed VSM table 1); "
            "a ball fault: the slot's spin angle at t = 0, 0 = facing the outer race, advancing "
            "as the ball spins (90: the inner race after a quarter turn).",
        ),
        deprecated("--defect-angle-deg", "--defect-edge-angle-deg"),
        click.option(
            "--rpm",
            type=Number(0.0, lo_open=True, unit="r/min"),
            default=None,
            show_default=_d("rpm", others=every_family),
            help="Shaft speed [r/min].",
        ),
        click.option(
            "--fx-n",
            "fx_n",
            type=Number(unit="N"),
            default=None,
            show_default=_d("fx_n", others=every_family),
            help="Radial force x [N].",
        ),
        deprecated("--fx", "--fx-n"),
        click.option(
            "--fy-n",
            "fy_n",
            type=Number(unit="N"),
            default=None,
            show_default=_d("fy_n", others=every_family),
            help="Radial force y [N].",
        ),
        deprecated("--fy", "--fy-n"),
        click.option(
            "--stiffness-n-per-m1.5",
            "stiffness_n_per_m1_5",
            type=Number(0.0, lo_open=True, unit="N/m^1.5"),
            default=None,
            show_default="Hertz value",
            help="Ball load-deflection constant K [N/m^1.5] (seed VSM eq. (10)).",
        ),
        deprecated("--stiffness", "--stiffness-n-per-m1.5"),
        click.option(
            "--clearance-m",
            type=CLEARANCE,
            default=None,
            show_default="the bearing's",
            help="Diametral clearance P_d [m]; negative = preload (dem, tvsm)."
            if every_family
            else "Diametral clearance P_d [m], >= 0 (a preload needs simulate with dem or tvsm).",
        ),
        click.option(
            "--retention-factor",
            type=Number(0.0, 1.0),
            default=None,
            show_default="seed VSM eq. (11)",
            help="Prescribed gamma in [0, 1] for a ball over the defect (seed VSM figs. 6-7) [-].",
        ),
        click.option(
            "--load-zone-deg",
            "load_zone_half_angle_deg",
            type=Number(0.0, 180.0, lo_open=True, hi_open=True, unit="deg"),
            default=None,
            show_default="from the contact",
            help="Fixed load-zone half angle psi_L [deg] (seed VSM eq. (14) literal).",
        ),
    ]
    for o in reversed(opts):
        f = o(f)
    return f


def _opt(f):
    """The shared options for ``simulate`` (every model family's defaults)."""
    return _shared_options(f, True)


def _ring_opt(f):
    """The shared options for ``vsm-trace`` (the ring models' defaults)."""
    return _shared_options(f, False)


def _parse_set(items: tuple[str, ...]) -> dict[str, Any]:
    """``KEY=VALUE`` pairs of ``--set`` as scenario keys (VALUE read as a TOML value; a bare word
    is a string)."""
    import tomllib

    out: dict[str, Any] = {}
    for item in items:
        key, sep, raw = item.partition("=")
        key = key.strip()
        if not sep or not key:
            raise ConfigError(f"--set {item!r} is invalid; valid: KEY=VALUE (a scenario key)")
        if key in out:  # the later one silently won
            raise ConfigError(f"--set {key}=... is given twice; valid: each key once")
        try:
            out[key] = tomllib.loads(f"v = {raw.strip()}")["v"]
        except tomllib.TOMLDecodeError:
            out[key] = raw.strip()
        except RecursionError:  # the TOML parser recurses once per nesting level
            raise ConfigError(
                f"--set {key}=... is nested too deeply; valid: a number, string, boolean or list"
            ) from None
    return out


def _scenario(path: str | None, overrides: dict[str, Any]):
    # unset keys stay unset (the rate too): an option's rig gives its own rate and defaults
    base = Scenario.from_toml(path).to_dict(rate=False) if path else {}
    extra = _parse_set(overrides.pop("set_keys", ()) or ())
    given = {k: v for k, v in overrides.items() if v is not None}
    clash = sorted(set(extra) & set(given))
    if clash:
        raise ConfigError(f"--set {clash[0]}=... and its option given together; give one")
    given.update(extra)
    if "bearing_file" in given and "bearing" in given:  # the option wins over a file's key,
        # but two given together contradict each other
        raise ConfigError(
            f"bearing = {given['bearing']!r} and bearing_file = {given['bearing_file']!r} given "
            "together; valid: exactly one of a catalogue id (--bearing) or --bearing-file PATH"
        )
    if "bearing_file" in given:
        base["bearing"] = None
    if "bearing" in given:
        base["bearing_file"] = None
    base.update(given)
    # an error names where its value may have come from: the file, the options, or both (a
    # --set value was blamed on the file; exploratory testing, twenty-sixth session)
    origin = Path(path).name if path else "options"
    if path and given:
        origin += " with the options given"
    return Scenario.from_dict(base, origin=origin)


@cli.command("simulate")
@click.argument(
    "scenario_file", metavar="[SCENARIO.toml]", required=False, type=click.Path(dir_okay=False)
)
@click.option(
    "--model",
    type=click.Choice([m.value for m in Model]),
    default=None,
    show_default=_d("model", others=False),
    help="Model.",
)
@_opt
@rotor_simulate_options
@click.option(
    "--duration-s",
    type=Number(0.0, lo_open=True, unit="s"),
    default=None,
    show_default=_d("duration_s"),
    help="Simulated time [s].",
)
@click.option(
    "--fs-hz",
    "fs_hz",
    type=Number(0.0, lo_open=True, unit="Hz"),
    default=None,
    show_default=f"{Scenario.FS_DEFAULT_HZ:g}; with --rig: the rate its records had; ias: "
    f"{IasScenario.FS_DEFAULT_HZ:g}",
    help="Output sample rate [Hz].",
)
@deprecated("--fs", "--fs-hz")
@click.option(
    "--seed",
    type=Number(0, integer=True),
    default=None,
    show_default=_d("seed"),
    help="Seed of every random part of the run: measurement noise, random slip and pocket "
    "jitter, ball-size spread, a rig's background and tone phases.",
)
@click.option(
    "--noise-rms-m-per-s2",
    "noise_rms_m_per_s2",
    type=Number(0.0, unit="m/s^2"),
    default=None,
    show_default=_d("noise_rms_m_per_s2"),
    help="RMS of white measurement noise added to the accelerations [m/s^2].",
)
@deprecated("--noise-rms", "--noise-rms-m-per-s2")
@click.option(
    "--mass-kg",
    type=Number(0.0, lo_open=True, unit="kg"),
    default=None,
    show_default=f"seed VSM table 1; ias: {_d('mass_kg', 'ias', others=False)}",
    help="Vibrating mass [kg].",
)
@click.option(
    "--damping-n-s-per-m",
    "damping_n_s_per_m",
    type=Number(0.0, unit="N s/m"),
    default=None,
    show_default=_d("damping_n_s_per_m"),
    help="Equivalent damping c_eq [N s/m].",
)
@deprecated("--damping", "--damping-n-s-per-m")
@click.option(
    "--dt-s",
    type=Number(0.0, lo_open=True, unit="s"),
    default=None,
    show_default=f"automatic; ias: {_d('dt_s', 'ias', others=False)}",
    help="RK4 step [s].",
)
@click.option(
    "--solver",
    type=click.Choice([s.value for s in Solver]),
    default=None,
    show_default=_d("solver"),
    help="Integrator; dopri5 = adaptive check.",
)
@click.option("--per-ball", is_flag=True, default=None, help="Store per-ball loads/deformations.")
@click.option(
    "--set",
    "set_keys",
    multiple=True,
    metavar="KEY=VALUE",
    help="Set any scenario key of the model's family (repeatable), e.g. --set "
    "slip_percent=1.5 (random slip of the ring and rotor models) or --set spall_width_m=2e-3 "
    "for --model ias; VALUE is a TOML value.",
)
@click.option(
    "--rig",
    "rig_name",
    default=None,
    metavar="NAME|FILE",
    help="Pass the output through a measurement chain (a shipped rig profile such as "
    "cwru-de-12k, or a rig TOML file): the sensor's signal is written as channel acc_sensor "
    "(bearingsim.rig); a model gain the rig has for this model scales its path.",
)
@allow_overload_option
@budget_options()
@output_option("Output file (netCDF-4).", required=True)
@json_option
def simulate_cmd(
    scenario_file: str | None,
    output: str,
    as_json: bool,
    budget: Any,
    allow_overload: bool,
    rig_name: str | None,
    **kw: Any,
) -> None:
    """Simulate a (faulty) bearing and write a self-describing netCDF file.

    Options override the keys of SCENARIO.toml (see bearingsim.config for the keys).
    """
    check_outputs(("-o/--output", output))
    if Path(output).suffix.lower() not in (".nc", ".nc4", ".h5"):  # it writes netCDF-4
        raise ConfigError(
            f"-o/--output = {output!r} names no netCDF file; valid: a name ending in .nc, .nc4 "
            "or .h5 (the result is netCDF-4; load_result and analyze read it)"
        )
    from tqdm import tqdm

    from ..simulation import simulate, validate_scenario

    if rig_name is not None:  # the scenario's rig key (checked with the scenario)
        if kw.get("model") == Model.IAS.value:
            raise ConfigError("--rig applies to acceleration outputs; model ias has none")
        kw["rig"] = rig_name
    sc = _scenario(scenario_file, kw)
    rig = getattr(sc, "rig", None)
    target = Path(output).expanduser().resolve()
    for key in ("bearing_file", "rig"):  # files the scenario names (by absolute path)
        named = getattr(sc, key, None)
        if isinstance(named, str) and Path(named).is_file() and Path(named).resolve() == target:
            raise ConfigError(
                f"-o/--output = {output!r} is the scenario's {key} ({named!r}): writing it "
                "would replace that file; valid: another path"
            )
    seen: set[str] = set()
    with echo_warnings(seen):  # everything checked before any work or output
        validate_scenario(sc, budget, allow_overload)
    t0 = time.perf_counter()
    bar = tqdm(
        total=sc.n_samples,
        desc=f"simulate {sc.model.value}",
        unit="sample",
        disable=as_json,
        leave=False,
        delay=1.0,
        file=sys.stderr,
    )
    last = [0]

    def progress(n: int) -> None:
        bar.update(n - last[0])
        last[0] = n

    try:
        with echo_warnings(seen):
            res = simulate(sc, progress=progress, budget=budget, allow_overload=allow_overload)
    finally:
        bar.close()
    res.save(output, field="-o/--output")
    wall = time.perf_counter() - t0
    out = {
        "output": str(output),
        "fs_hz": res.fs_hz,
        "n_samples": int(res.time.size),
        "wall_s": wall,
    }
    if sc.model is Model.IAS:  # the shaft speed is the IAS model's output
        out["mean_speed_rpm"] = float(res.omega.mean()) * 60.0 / (2.0 * math.pi)
        out["spall_width_m"] = res.params.spall_width
        fault = f"spall {sc.spall_width_m * 1e3:g} mm" if sc.spall_width_m else "none"
        what = f"mean speed {out['mean_speed_rpm']:.4f} r/min"
    else:
        out["rms_acc_x"] = res.rms("acc_x")
        out["rms_acc_y"] = res.rms("acc_y")
        if "acc_y_fe" in res.channels:  # rotor: per-end accelerations (acc_x/y = drive end)
            out["rms_acc_x_fe"] = res.rms("acc_x_fe")
            out["rms_acc_y_fe"] = res.rms("acc_y_fe")
        fault = sc.fault if sc.model is not Model.ROTOR else f"DE {sc.de_fault} / FE {sc.fe_fault}"
        what = f"RMS acc x {out['rms_acc_x']:.4g} y {out['rms_acc_y']:.4g} m/s^2"
        if rig is not None:
            out["rig"] = res.meta["rig"]["name"]
            out["rms_acc_sensor"] = res.rms("acc_sensor")
            mg = res.meta["rig"].get("applied_model_gain")
            out["rig_model_gain"] = None if mg is None else mg.get("scale")
            gain = ""
            if mg is not None:
                from ..rig import ModelGain

                g = ModelGain(mg["model"], mg.get("scale"), "", mg.get("path_gain"),
                              mg.get("mode_gains"))  # fmt: skip
                gain = f" ({g.describe()} for this model)"
                if g.scale is None:  # the fitted form
                    out["rig_model_path"] = {k: mg[k] for k in ("path_gain", "mode_gains")}
            what += f", through rig {out['rig']}{gain}: RMS {out['rms_acc_sensor']:.4g} m/s^2"
            real = sc.realism_defaults
            if real:  # the keys the rig chose (docs/models.md "Realistic defaults with a rig")
                out["realism_defaults"] = real
                what += " (rig defaults: " + ", ".join(f"{k} = {v}" for k, v in real.items()) + ")"
    if as_json:
        emit_json(out)
        return
    click.echo(
        f"wrote {output}: {sc.model.value} {res.meta['bearing_id']} fault {fault}, "
        f"{out['n_samples']} samples at {res.fs_hz:g} Hz, {what}, {wall:.2f} s"
    )


def _check_zero_load(kw: dict[str, Any]) -> None:
    """``vsm-trace``: a radial load of zero refused before the scenario is built, with the rule
    of the trace (:func:`bearingsim.dynamics.ring.trace.check_trace_load`: the ring position is
    undetermined in a clearance, there is no stiffness without one, a preload is refused
    whatever the load), not the scenario's bound on ``unbalance_n`` that it would hit first."""
    import dataclasses

    from ..catalog import resolve_bearing
    from ..config import RingScenario
    from ..dynamics.ring.trace import check_trace_load

    default = {f.name: f.default for f in dataclasses.fields(RingScenario)}
    fx = default["fx_n"] if kw.get("fx_n") is None else kw["fx_n"]
    fy = default["fy_n"] if kw.get("fy_n") is None else kw["fy_n"]
    if not (fx == 0.0 and fy == 0.0):  # other loads: the scenario checks them
        return
    bid, bfile = kw.get("bearing"), kw.get("bearing_file")
    bearing = resolve_bearing(default["bearing"] if bid is None and bfile is None else bid, bfile)
    check_trace_load(bearing, fx, fy, kw.get("clearance_m"))


@cli.command("vsm-trace")
@_ring_opt
@click.option(
    "--first-ball-deg",
    type=Number(-360.0, 360.0, unit="deg"),
    default=0.0,
    help="Ball 1 azimuth alpha_0 [deg].",
)
@click.option(
    "--cage-revs",
    type=Number(0.0, 100.0, lo_open=True),
    default=1.0,
    help="Cage revolutions to trace [-].",
)
@click.option(
    "--step-deg",
    type=Number(0.0, 10.0, lo_open=True, unit="deg"),
    default=0.05,
    help="Cage-angle step [deg].",
)
@output_option("CSV output (one row per cage angle).")
@click.option(
    "--plot",
    default=None,
    type=click.Path(dir_okay=False),
    help="PNG: total stiffness (seed VSM figs. 5-8).",
)
@click.option(
    "--ball",
    type=Number(valid="[1, Z], Z the number of balls", integer=True),
    default=None,
    help="Also plot this ball's stiffness/force/deformation (seed VSM figs. 9, 11) "
    "to PLOT with suffix _ballN.",
)
@allow_overload_option
@budget_options(steps=False)
@json_option
def vsm_trace_cmd(
    output: str | None,
    plot: str | None,
    allow_overload: bool,
    as_json: bool,
    cage_revs: float,
    step_deg: float,
    first_ball_deg: float,
    ball: int | None,
    budget: Any,
    **kw: Any,
) -> None:
    """Quasi-static VSM stiffness, contact force and deformation vs cage angle.

    Needs a radial load (fx_n, fy_n) other than zero and a clearance P_d >= 0 (a preload is
    simulated with model dem or tvsm); an overriding ball constant must be a physical one,
    [1e8, 1e12] N/m^1.5. A static balance that does not converge is refused, not written.

    CSV columns and JSON keys of stiffnesses end in _n_per_m [N/m] (formerly _n_m; the JSON
    keeps k_load_min_n_m and k_load_max_n_m as deprecated copies for one release)."""
    # --ball draws a second figure beside --plot's: checked as an output too (it replaced an
    # -o file of its name without a word; twenty-first session)
    ball_plot = (
        None
        if ball is None or plot is None
        else str(Path(plot).with_name(f"{Path(plot).stem}_ball{ball}{Path(plot).suffix}"))
    )
    check_outputs(("-o/--output", output), ("--plot", plot), ("--plot (--ball)", ball_plot))
    import numpy as np

    from ..dynamics.budget import check_budget
    from ..dynamics.checks import check_load
    from ..dynamics.ring.scenario import model_inputs
    from ..dynamics.ring.trace import stiffness_trace, trace_estimate
    from ..geometry import check_speed_limit

    if output is None and plot is None and not as_json:
        raise ConfigError("vsm-trace: give -o/--output OUT.csv, --plot PNG and/or --json")
    if ball is not None and plot is None:  # its figure is PLOT with suffix _ballN
        raise ConfigError(
            f"ball = {ball} is given without --plot: the ball's figure is written beside the "
            "--plot PNG (suffix _ballN); valid: --ball with --plot PNG"
        )
    revs = check_range("cage_revs", cage_revs, 0.0, 100.0, lo_open=True)
    step = check_range("step_deg", step_deg, 0.0, 10.0, lo_open=True, unit="deg")
    _check_zero_load(kw)
    sc = _scenario(None, {**kw, "first_ball_angle_deg": first_ball_deg, "duration_s": 1.0})
    inputs = model_inputs(sc)
    check_speed_limit(inputs.bearing, sc.rpm)  # the speed the trace's shaft angle assumes
    if ball is not None and not 1 <= ball <= inputs.bearing.n_elements:
        raise ConfigError(
            f"ball = {ball} is out of range; valid range [1, {inputs.bearing.n_elements}]"
        )
    n = int(round(360.0 * revs / step)) + 1
    if n > 2_000_000:
        raise ConfigError(f"cage_revs/step_deg = {n} points is too many; valid range [2, 2e6]")
    with echo_warnings():  # the load against C0 first, then the budget, then the work
        check_load(
            inputs.bearing, math.hypot(inputs.fx, inputs.fy), allow_overload, name="|(fx_n, fy_n)|"
        )
        check_budget(trace_estimate(inputs, n), budget)
        angles = np.radians(np.linspace(0.0, 360.0 * revs, n))
        tr = stiffness_trace(inputs, angles, allow_overload=allow_overload)
    if output:
        tr.to_csv(output)
    if plot:
        from ..report.figures import save_figure

        save_figure(tr.plot_total(), plot)
        if ball_plot is not None:
            save_figure(tr.plot_ball(ball), ball_plot)
    ev = [{"cage_angle_deg": a, "ball": b, "event": k} for a, b, k in tr.events()]
    out = {
        "output": output,
        "plot": plot,
        "n_points": n,
        "label": tr.label,
        "psi_l0_deg": math.degrees(tr.psi_l0),
        "k_load_min_n_per_m": float(tr.k_load.min()),
        "k_load_max_n_per_m": float(tr.k_load.max()),
        "n_loaded_min": int(tr.n_loaded.min()),
        "n_loaded_max": int(tr.n_loaded.max()),
        "residual_max": float(tr.residual.max()),
        "events": ev,
    }
    # the former keys (N/m spelled _n_m, which the unit rule reads N m), for one release
    out["k_load_min_n_m"] = out["k_load_min_n_per_m"]
    out["k_load_max_n_m"] = out["k_load_max_n_per_m"]
    if as_json:
        emit_json(out)
        return
    click.echo(
        f"{tr.label}: k_load {out['k_load_min_n_per_m']:.4g}..{out['k_load_max_n_per_m']:.4g} N/m, "
        f"{out['n_loaded_min']}-{out['n_loaded_max']} loaded balls, {len(ev)} events"
        + (f", wrote {output}" if output else "")
    )
