"""Fault-dynamics commands: ``simulate``, ``vsm-trace``, ``analyze`` (SPEC §1, §0.5)."""

from __future__ import annotations

import csv
import functools
import io
import math
import re
import sys
import time
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import click

from ..config import Model, Solver
from ..errors import ConfigError, check_range
from .common import (
    Number,
    allow_overload_option,
    available_cores,
    check_outputs,
    cli,
    deprecated,
    echo_warnings,
    emit_json,
    json_option,
    map_in_processes,
    output_option,
)
from .common import scenario_default as _d
from .limits import budget_options
from .rotor import rotor_simulate_options

__all__ = [
    "analyze_cmd",
    "simulate_cmd",
    "vsm_trace_cmd",
]

_FAULTS = ["none", "outer", "inner", "ball"]


def _opt(f):
    """Options shared by ``simulate`` and ``vsm-trace``; each overrides the scenario key of the
    same name (``--fx-n`` sets ``fx_n``); ``[default: ...]`` is the value when neither the option
    nor the scenario file sets it."""
    opts = [
        click.option(
            "--bearing", "bearing", default=None, show_default=_d("bearing"), help="Catalogue id."
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
            show_default=_d("fault"),
            help="Defect location (ball: ball 1 carries it).",
        ),
        click.option(
            "--defect-width-m",
            type=Number(0.0, lo_open=True, unit="m"),
            default=None,
            show_default=_d("defect_width_m"),
            help="Defect width b along the raceway [m] (CWRU 0.007 in).",
        ),
        click.option(
            "--defect-depth-m",
            type=Number(0.0, lo_open=True, unit="m"),
            default=None,
            show_default=_d("defect_depth_m"),
            help="Defect depth h_d [m] (CWRU 0.011 in).",
        ),
        click.option(
            "--defect-edge-angle-deg",
            type=Number(-360.0, 360.0, unit="deg"),
            default=None,
            show_default=_d("defect_edge_angle_deg"),
            help="Azimuth of the defect's left edge at t = 0, beta_0 [deg] (seed VSM table 1).",
        ),
        deprecated("--defect-angle-deg", "--defect-edge-angle-deg"),
        click.option(
            "--rpm",
            type=Number(0.0, lo_open=True, unit="r/min"),
            default=None,
            show_default=_d("rpm"),
            help="Shaft speed [r/min].",
        ),
        click.option(
            "--fx-n",
            "fx_n",
            type=Number(unit="N"),
            default=None,
            show_default=_d("fx_n"),
            help="Radial force x [N].",
        ),
        deprecated("--fx", "--fx-n"),
        click.option(
            "--fy-n",
            "fy_n",
            type=Number(unit="N"),
            default=None,
            show_default=_d("fy_n"),
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
            type=Number(0.0, unit="m"),
            default=None,
            show_default="the bearing's",
            help="Diametral clearance P_d [m].",
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
    from ..config import Scenario

    base = Scenario.from_toml(path).to_dict() if path else {}
    extra = _parse_set(overrides.pop("set_keys", ()) or ())
    given = {k: v for k, v in overrides.items() if v is not None}
    clash = sorted(set(extra) & set(given))
    if clash:
        raise ConfigError(f"--set {clash[0]}=... and its option given together; give one")
    given.update(extra)
    if "bearing_file" in given:
        base["bearing"] = None
    if "bearing" in given:
        base["bearing_file"] = None
    base.update(given)
    return Scenario.from_dict(base, origin=Path(path).name if path else "options")


@cli.command("simulate")
@click.argument(
    "scenario_file", metavar="[SCENARIO.toml]", required=False, type=click.Path(dir_okay=False)
)
@click.option(
    "--model",
    type=click.Choice([m.value for m in Model]),
    default=None,
    show_default=_d("model"),
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
    show_default=_d("fs_hz"),
    help="Output sample rate [Hz].",
)
@deprecated("--fs", "--fs-hz")
@click.option(
    "--seed",
    type=Number(0, integer=True),
    default=None,
    show_default=_d("seed"),
    help="Seed of the measurement noise.",
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
    show_default="seed VSM table 1",
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
    show_default="automatic",
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
    "spall_width_m=2e-3 for --model ias; VALUE is a TOML value.",
)
@click.option(
    "--rig",
    "rig_name",
    default=None,
    metavar="NAME|FILE",
    help="Pass the output through a measurement chain (a shipped rig profile such as "
    "cwru-de-12k, or a rig TOML file): the sensor's signal is written as channel acc_sensor "
    "(bearingsim.rig).",
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
    from tqdm import tqdm

    from ..simulation import simulate, validate_scenario

    if rig_name is not None:  # the scenario's rig key (checked with the scenario)
        if kw.get("model") == Model.IAS.value:
            raise ConfigError("--rig applies to acceleration outputs; model ias has none")
        kw["rig"] = rig_name
    sc = _scenario(scenario_file, kw)
    rig = getattr(sc, "rig", None)
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
    res.save(output)
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
            what += f", through rig {out['rig']}: RMS {out['rms_acc_sensor']:.4g} m/s^2"
    if as_json:
        emit_json(out)
        return
    click.echo(
        f"wrote {output}: {sc.model.value} {res.meta['bearing_id']} fault {fault}, "
        f"{out['n_samples']} samples at {res.fs_hz:g} Hz, {what}, {wall:.2f} s"
    )


@cli.command("vsm-trace")
@_opt
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
    """Quasi-static VSM stiffness, contact force and deformation vs cage angle."""
    check_outputs(("-o/--output", output), ("--plot", plot))
    import numpy as np

    from ..dynamics.budget import check_budget
    from ..dynamics.checks import check_load
    from ..dynamics.ring.scenario import model_inputs
    from ..dynamics.ring.trace import stiffness_trace, trace_estimate
    from ..geometry import check_speed_limit

    if output is None and plot is None and not as_json:
        raise ConfigError("vsm-trace: give -o/--output OUT.csv, --plot PNG and/or --json")
    revs = check_range("cage_revs", cage_revs, 0.0, 100.0, lo_open=True)
    step = check_range("step_deg", step_deg, 0.0, 10.0, lo_open=True, unit="deg")
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
        if ball is not None:
            p = Path(plot)
            save_figure(tr.plot_ball(ball), p.with_name(f"{p.stem}_ball{ball}{p.suffix}"))
    ev = [{"cage_angle_deg": a, "ball": b, "event": k} for a, b, k in tr.events()]
    out = {
        "output": output,
        "plot": plot,
        "n_points": n,
        "label": tr.label,
        "psi_l0_deg": math.degrees(tr.psi_l0),
        "k_load_min_n_m": float(tr.k_load.min()),
        "k_load_max_n_m": float(tr.k_load.max()),
        "n_loaded_min": int(tr.n_loaded.min()),
        "n_loaded_max": int(tr.n_loaded.max()),
        "residual_max": float(tr.residual.max()),
        "events": ev,
    }
    if as_json:
        emit_json(out)
        return
    click.echo(
        f"{tr.label}: k_load {out['k_load_min_n_m']:.4g}..{out['k_load_max_n_m']:.4g} N/m, "
        f"{out['n_loaded_min']}-{out['n_loaded_max']} loaded balls, {len(ev)} events"
        + (f", wrote {output}" if output else "")
    )


#: CWRU nominal motor speed [r/min] at each motor load [hp] (CWRU Bearing Data Center,
#: drive-end and fan-end data pages; ../shared/data/cwru/manifest.csv, column nominal_rpm)
CWRU_NOMINAL_RPM = {0: 1797.0, 1: 1772.0, 2: 1750.0, 3: 1730.0}
#: the CWRU file-name convention ``..._<load hp>_<record number>.<ext>`` (``normal_0_97.mat``,
#: ``12k_Drive_End_IR014_2_171.mat``)
_CWRU_NAME = re.compile(r"(?:^|_)([0-3])_\d+$")
#: modules an analysis imports; loaded before the worker processes are forked
_ANALYZE_MODULES = (
    *("numpy", "scipy.constants", "scipy.fft", "scipy.io", "scipy.signal"),
    *("bearingsim.catalog", "bearingsim.io", "bearingsim.signal"),
)
#: columns of ``analyze --csv``
_CSV_COLUMNS = (
    *("file", "channel", "fs_hz", "rpm", "rpm_source", "bearing", "diagnosis", "confidence"),
    *("band_lo_hz", "band_hi_hz", "error"),
)


def cwru_nominal_rpm(name: str) -> tuple[int, float] | None:
    """``(load [hp], nominal speed [r/min])`` that a CWRU file name (``..._<load>_<number>.mat``,
    load 0-3 hp) gives, or None when the name does not follow that convention."""
    m = _CWRU_NAME.search(Path(name).stem)
    if m is None:
        return None
    load = int(m.group(1))
    return load, CWRU_NOMINAL_RPM[load]


@dataclass(frozen=True)
class _Request:
    """What ``analyze`` does with each file (the options, checked)."""

    channel: str | None
    fs_hz: float | None
    rpm: float | None
    band: tuple[float, float] | str
    bearing: Any  # Bearing or None (the file's, else the CWRU bearing of the channel)
    plot: str | None = None


@cli.command("analyze", context_settings={"ignore_unknown_options": False})
@click.argument("inputs", nargs=-1, required=True, metavar="FILE...")
@click.option(
    "--bearing",
    "bearing_id",
    default=None,
    show_default="6205-cwru for .mat, 6203-cwru for its channel FE; the result's for .nc",
    help="Catalogue bearing id.",
)
@click.option(
    "--bearing-file", default=None, type=click.Path(dir_okay=False), help="User bearing TOML file."
)
@click.option(
    "--rpm",
    type=Number(0.0, lo_open=True, unit="r/min"),
    default=None,
    show_default="from the file, else the CWRU nominal speed of the load in the file name",
    help="Shaft speed [r/min].",
)
@click.option(
    "--fs-hz",
    "fs_hz",
    type=Number(0.0, lo_open=True, unit="Hz"),
    default=None,
    show_default="from the file; CWRU: 12k/48k in the name, else 48000",
    help="Sample rate of the signal [Hz].",
)
@deprecated("--fs", "--fs-hz")
@click.option(
    "--channel",
    default=None,
    show_default="DE for .mat, y for results",
    help="DE|FE|BA (CWRU .mat; auto: FE when the file name contains Fan_End, else DE), "
    "x|y (result; rotor results also x_fe|y_fe), or a CSV column.",
)
@click.option(
    "--band-hz",
    "band",
    default="auto",
    help="Envelope band: 'auto' (fast kurtogram), LO,HI or LO HI [Hz].",
)
@deprecated("--band", "--band-hz")
@click.option(
    "--plot",
    default=None,
    type=click.Path(dir_okay=False),
    help="PNG with the envelope spectrum and the matched lines (one FILE only).",
)
@click.option(
    "--jobs",
    type=Number(1, integer=True),
    default=None,
    show_default="the available cores",
    help="Files analysed at once, one process each; 1: one after the other in this process [-].",
)
@click.option("--csv", "as_csv", is_flag=True, help="Print a CSV table, one row per FILE.")
@click.option(
    "--json",
    "as_json",
    is_flag=True,
    help="Print one JSON object (SI) per FILE, one per line (JSON Lines), on stdout.",
)
def analyze_cmd(
    inputs: tuple[str, ...],
    bearing_id: str | None,
    bearing_file: str | None,
    rpm: float | None,
    fs_hz: float | None,
    channel: str | None,
    band: str,
    plot: str | None,
    jobs: int | None,
    as_csv: bool,
    as_json: bool,
) -> None:
    """Envelope analysis and diagnosis of a measured (CWRU .mat), simulated (.nc) or CSV signal.

    Prints {"diagnosis": outer|inner|ball|none|uncertain, "confidence", "band_hz", "shaft_hz"
    (shaft frequency), "fs_hz" (sample rate), "rpm", "rpm_source", "channel", "bearing",
    "peaks": [...]}; "uncertain" when the evidence is weak or ambiguous. Several FILEs are
    analysed in parallel (--jobs) and reported in their order, one line (--json: one object, --csv:
    one row) each; a FILE that cannot be analysed gets its own error line (--json: {"file",
    "error"}) and the others go on; the exit code is then 2.
    """
    check_outputs(("--plot", plot))
    if as_json and as_csv:
        raise ConfigError("--json and --csv given together; give one")
    files, band_v = _parse_band(inputs, band)
    if plot is not None and len(files) > 1:
        raise ConfigError(
            f"--plot writes the figure of one FILE; {len(files)} FILEs given: give one FILE"
        )
    if rpm is not None:
        check_range("rpm", rpm, 0.0, lo_open=True, unit="r/min")
    if fs_hz is not None:
        check_range("fs_hz", fs_hz, 0.0, lo_open=True, unit="Hz")
    if jobs is not None:
        check_range("jobs", jobs, 1.0)
    if channel is not None and channel.strip().lower() == "auto":
        channel = "auto"
    bearing = None
    if bearing_id is not None or bearing_file is not None:  # an empty id is an error too
        from ..catalog import resolve_bearing

        bearing = resolve_bearing(bearing_id, bearing_file)
    req = _Request(channel, fs_hz, rpm, band_v, bearing, plot)
    if len(files) == 1 and not (as_json or as_csv):  # today's output; an error is the one line
        _echo_text(_analyze_file(files[0], req), detail=True)
        return
    if as_csv:
        click.echo(_csv_line(_CSV_COLUMNS))
    failed = 0
    work = functools.partial(_analyze_or_error, req=req)
    n_jobs = available_cores() if jobs is None else jobs
    for out in map_in_processes(work, files, n_jobs, preload=_ANALYZE_MODULES):
        if "error" in out:
            failed += 1
            where = "" if len(files) == 1 else f"{out['file']}: "
            click.echo(f"{where}error: {out['error']}", err=True)
        if as_json:
            emit_json(out)
        elif as_csv:
            click.echo(_csv_line(_csv_row(out)))
        elif "error" not in out:
            _echo_text(out, detail=False)
    if failed:
        sys.exit(2)


def _analyze_or_error(path: str, req: _Request) -> dict[str, Any]:
    """:func:`_analyze_file`, or ``{"file", "error"}`` (the one-line message) when the file
    cannot be analysed."""
    from ..errors import BearingsimError

    try:
        return _analyze_file(path, req)
    except BearingsimError as exc:
        return {"file": path, "error": " ".join(str(exc).split())}


def _analyze_file(path: str, req: _Request) -> dict[str, Any]:
    """Load, check and diagnose one file: the JSON object of ``analyze --json``."""
    from ..catalog import resolve_bearing
    from ..io.jsonable import to_jsonable
    from ..signal import analyze_record
    from ..signal.diagnosis import check_resolvable, check_samples

    rec, rpm_source = _load_record(path, req)
    check_samples(rec)
    check_resolvable(rec)
    cwru = Path(rec.source).suffix.lower() == ".mat"
    bearing = (
        req.bearing
        or rec.bearing
        or resolve_bearing("6203-cwru" if cwru and rec.channel == "FE" else "6205-cwru")
    )
    d = analyze_record(rec, bearing, band=req.band)
    if req.plot:
        from ..report.figures import save_figure

        # CWRU channels and result accelerations are in m/s^2; a text column's unit is unknown
        acc = not rec.columns and (
            rec.channel.upper() in ("DE", "FE", "BA") or rec.channel.startswith("acc")
        )
        save_figure(
            d.plot(
                title=f"{Path(path).name} [{rec.channel}]: {d.diagnosis} ({d.confidence:.2f})",
                unit="m/s^2" if acc else None,
            ),
            req.plot,
        )
    out = {
        "file": str(path),
        **d.as_dict(),
        "channel": rec.channel,
        "fs_hz": rec.fs,
        "bearing": bearing.id,
        "rpm": rec.rpm,
        **rec.info,
        "rpm_source": rpm_source,
    }
    return to_jsonable(out)


def _load_record(path: str, req: _Request) -> tuple[Any, str]:
    """The record (``load_signal``) and where its speed came from: the option, the file, or the
    CWRU nominal speed of the load in the file name when the file gives none."""
    from ..signal import load_signal

    ch = req.channel
    if ch == "auto":  # CWRU: the fan-end records' fault is at the fan end
        mat = Path(path).suffix.lower() == ".mat"
        ch = ("FE" if "fan_end" in Path(path).name.lower() else "DE") if mat else None
    if req.rpm is not None:
        return load_signal(path, channel=ch, fs_hz=req.fs_hz, rpm=req.rpm), "option"
    try:
        return load_signal(path, channel=ch, fs_hz=req.fs_hz), "file"
    except ConfigError:
        nominal = cwru_nominal_rpm(path)
        if nominal is None:
            raise
    # the file gives no (usable) speed: read it again at the name's; a failure that was not
    # the speed's fails again, the same way
    load, r = nominal
    rec = load_signal(path, channel=ch, fs_hz=req.fs_hz, rpm=r)
    return rec, f"name (CWRU nominal speed at load {load} hp)"


def _echo_text(out: dict[str, Any], detail: bool) -> None:
    """The human line of one analysed file (``detail``: the file's name and its detected
    lines, as for a single FILE; else the path as given)."""
    name = Path(out["file"]).name if detail else out["file"]
    lo, hi = out["band_hz"]
    speed = ""
    if out["rpm_source"].startswith("name"):  # say when the speed is not the record's
        speed = f", rpm {out['rpm']:g} from the file {out['rpm_source']}"
    click.echo(
        f"{name} [{out['channel']}]: {out['diagnosis']} (confidence "
        f"{out['confidence']:.2f}), band {lo:.0f}-{hi:.0f}{speed}"
    )
    if not detail:
        return
    for p in out["peaks"]:
        if p["detected"]:
            click.echo(
                f"  {p['label']:<12} {p['freq_hz']:9.2f} Hz  order {p['order']:7.3f}  "
                f"SNR {p['snr_db']:5.1f} dB"
            )


def _csv_row(out: dict[str, Any]) -> list[Any]:
    """The ``--csv`` row of one file; the band is empty for an order-tracked record (its band
    is in orders: ``--json``)."""
    row = {k: out.get(k) for k in _CSV_COLUMNS}
    if "error" not in out and out.get("domain") != "order":
        row["band_lo_hz"], row["band_hi_hz"] = out["band_hz"]
    return [row[k] for k in _CSV_COLUMNS]


def _csv_line(values: Any) -> str:
    """One CSV line (RFC 4180 quoting; None as an empty field)."""
    buf = io.StringIO()
    csv.writer(buf, lineterminator="").writerow(["" if v is None else v for v in values])
    return buf.getvalue()


def _parse_band(inputs: tuple[str, ...], band: str) -> tuple[list[str], tuple[float, float] | str]:
    """The FILEs and the band of ``--band-hz auto``, ``--band-hz LO,HI`` or ``--band-hz LO HI``.

    In the last form click hands HI over as a positional argument beside the FILEs: HI is then
    the one positional argument that is a number and not an existing path; with ``auto`` or two
    values every positional argument is a FILE."""
    items = list(inputs)
    b = band.strip().lower()
    if b == "auto":
        return items, "auto"
    parts = [v for v in b.replace(",", " ").split() if v]
    if len(parts) == 1 and _is_float(parts[0]):
        nums = [v for v in items if _is_float(v) and not Path(v).exists()]
        if len(nums) != 1:
            found = f"{len(nums)} numbers among the FILEs" if nums else "no HI"
            raise ConfigError(
                f"band = {band!r} is invalid ({found}); valid: --band-hz auto or --band-hz LO,HI "
                "(two numbers in Hz)"
            )
        parts.append(nums[0])
        items.remove(nums[0])
    if len(parts) != 2 or not all(_is_float(v) for v in parts):
        raise ConfigError(
            f"band = {band!r} is invalid; valid: --band-hz auto or --band-hz LO,HI [Hz]"
        )
    if not items:
        raise ConfigError("analyze: no FILE given")
    return items, (float(parts[0]), float(parts[1]))


def _is_float(v: str) -> bool:
    try:
        float(v)
        return True
    except ValueError:
        return False
