"""IAS commands: ``ias`` (simulate seed IAS's 3-DOF roller-bearing model and analyse its
instantaneous angular speed) and ``analyze-ias`` (the same analysis of a measured signal)."""

from __future__ import annotations

import math
from pathlib import Path
from typing import Any

import click
import numpy as np

from ..catalog import resolve_bearing
from ..errors import ConfigError, check_range
from ..geometry import RollerBearing
from ..signal.order import ShaftSignalKind
from .common import cli, emit_json, json_option

TWO_PI = 2.0 * math.pi


def _print_summary(d: dict[str, Any]) -> None:
    click.echo(f"mean speed        {d['mean_speed_rpm']:.4f} r/min")
    click.echo(f"IAS ripple        {d['ias_ripple_rel']:.4g} (peak-to-peak / mean)")
    if d.get("bpfo_order_theory") is not None:
        click.echo(f"BPFO order        {d['bpfo_order_theory']:.4f} (kinematic)")
    for p in d["order_peaks"]:
        click.echo(f"  peak at order {p['order']:8.4f}  amplitude {p['amplitude']:.4g} rad/s")
    est = d.get("spall_width_estimate_m")
    click.echo("spall width       " + ("not detected" if est is None else f"{est * 1e3:.4f} mm"))


def _summary_figure(summary, title: str):
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(3, 1, figsize=(8, 9))
    sig = summary.signal
    ax[0].plot(sig.angle / TWO_PI, sig.value * 60 / TWO_PI, lw=0.7)
    ax[0].set_xlabel("shaft angle [rev]")
    ax[0].set_ylabel("IAS [r/min]")
    ax[0].set_title(title)
    marks = []
    if summary.bpfo_order:
        marks = summary.bpfo_order * np.arange(1, int(30 / summary.bpfo_order) + 1)
    summary.spectrum.plot(30.0, ax=ax[1], scale=60 / TWO_PI, unit="r/min", marks=marks)
    e = summary.estimate
    if e is not None:
        ax[2].plot(e.phase, e.average * 60 / TWO_PI, lw=1.0)
        for a, col in ((e.entry_angle, "g"), (e.impact_angle, "m"), (e.exit_angle, "r")):
            if a is not None:
                ax[2].axvline(a, color=col, ls="--", lw=0.8)
        ax[2].set_xlim(
            max(0.0, e.entry_angle - e.crossing_angle),
            min(e.phase[-1], e.exit_angle + e.crossing_angle),
        )
        ax[2].set_title(
            f"averaged roller pass: crossing {e.crossing_angle:.4f} rad -> "
            f"L_d = {e.width * 1e3:.3f} mm"
        )
    else:
        ax[2].text(0.5, 0.5, "no spall event detected", ha="center", transform=ax[2].transAxes)
    ax[2].set_xlabel("shaft angle within one roller pass [rad]")
    ax[2].set_ylabel("IAS [r/min]")
    fig.tight_layout()
    return fig


@cli.command("ias")
@click.argument("scenario", required=False, type=click.Path(dir_okay=False))
@click.option(
    "--bearing",
    "bearing_id",
    default=None,
    help="Catalogue id of a cylindrical roller bearing [default NU204-ECP].",
)
@click.option(
    "--bearing-file", type=click.Path(dir_okay=False), default=None, help="User bearing TOML file."
)
@click.option(
    "--rpm",
    type=float,
    default=None,
    help="Target speed [r/min]: sets M_z = C_T * speed (the speed itself comes out of "
    "the torque balance).",
)
@click.option("--torque-nm", type=float, default=None, help="Motor torque M_z [N m] [9.54].")
@click.option("--initial-rpm", type=float, default=None, help="Initial shaft speed [r/min] [0].")
@click.option(
    "--spall-width-m",
    type=float,
    default=None,
    help="Outer-race spall width L_d [m]; 0 = healthy [1e-3].",
)
@click.option(
    "--spall-angle-deg",
    type=float,
    default=None,
    help="Spall centre azimuth from +y towards +x [deg] [180 = bottom].",
)
@click.option("--fx", "fx_n", type=float, default=None, help="Radial load along +x [N] [0].")
@click.option(
    "--fy",
    "fy_n",
    type=float,
    default=None,
    help="Radial load pushing the shaft down (-y) [N] [400].",
)
@click.option("--duration-s", type=float, default=None, help="Simulated time [s] [10].")
@click.option("--dt-s", type=float, default=None, help="RK4 step [s] [1e-6].")
@click.option("--output-rate-hz", type=float, default=None, help="Output sample rate [Hz] [48000].")
@click.option(
    "--method", type=click.Choice(["rk4", "dopri5"]), default=None, help="Integrator [rk4]."
)
@click.option(
    "--contact-law",
    type=click.Choice(["seed", "harris"]),
    default=None,
    help="Roller stiffness: seed eqs. (5)-(12) or Harris/Palmgren [seed].",
)
@click.option(
    "--spall-load",
    type=click.Choice(["stribeck", "dynamic"]),
    default=None,
    help="Roller load in the spall force, seed eq. (30) [stribeck].",
)
@click.option(
    "--skip-s",
    type=float,
    default=None,
    help="Start-up left out of the analysis [s] [10 % of the run].",
)
@click.option(
    "-o", "--out", required=True, type=click.Path(dir_okay=False), help="Result file (netCDF)."
)
@click.option(
    "--plot",
    type=click.Path(dir_okay=False),
    default=None,
    help="Write a PNG: IAS vs angle, order spectrum, spall estimate.",
)
@json_option
def ias_cmd(
    scenario: str | None,
    bearing_id: str | None,
    bearing_file: str | None,
    out: str,
    plot: str | None,
    as_json: bool,
    **opts: Any,
) -> None:
    """Simulate the 3-DOF IAS model of seed IAS (NU204-ECP with an outer-race spall) and analyse
    the instantaneous angular speed in the angle domain."""
    from ..dynamics.ias.model import simulate_ias
    from ..dynamics.ias.scenario import build_scenario, read_scenario

    settings: dict[str, Any] = read_scenario(scenario) if scenario else {}
    if bearing_id is not None or bearing_file is not None:
        settings.pop("bearing", None)
        settings.pop("bearing_file", None)
        settings.update(bearing=bearing_id, bearing_file=bearing_file)
    if opts.get("rpm") is not None or opts.get("torque_nm") is not None:
        if opts.get("rpm") is not None and opts.get("torque_nm") is not None:
            raise ConfigError("give at most one of --rpm and --torque-nm")
        settings.pop("rpm", None)
        settings.pop("torque_nm", None)
    settings.update({k: v for k, v in opts.items() if v is not None})
    params, run = build_scenario(settings)
    res = simulate_ias(params, run["duration_s"], run["dt_s"], run["output_rate_hz"], run["method"])
    summary = res.analyze(run["skip_s"])
    if plot:
        from ..report.figures import save_figure

        lab = f"spall {params.spall_width * 1e3:g} mm" if params.spall_width > 0 else "healthy"
        save_figure(_summary_figure(summary, f"{params.bearing.id}, {lab}"), plot)
    res.save(out)
    d = summary.as_dict()
    d.update(
        wall_s=res.solver["wall_s"],
        cpu_s=res.solver["cpu_s"],
        free_speed_rpm=res.constants.free_speed * 60 / TWO_PI,
        torque_nm=params.torque,
        spall_width_m=params.spall_width,
        bearing=params.bearing.id,
        solver={k: res.solver[k] for k in ("method", "dt_s", "n_steps", "output_rate_hz")},
        output=str(out),
    )
    if as_json:
        emit_json(d)
        return
    click.echo(
        f"{params.bearing.id}: {run['duration_s']:g} s simulated in {d['wall_s']:.2f} s "
        f"({run['method']}, dt {run['dt_s']:g} s); M_z {params.torque:g} N m, free speed "
        f"{d['free_speed_rpm']:.4f} r/min"
    )
    _print_summary(d)
    click.echo(f"wrote {out}")


_KINDS = tuple(k.value for k in ShaftSignalKind)


@cli.command("analyze-ias")
@click.argument("file", type=click.Path(dir_okay=False))
@click.option(
    "--kind",
    type=click.Choice(_KINDS),
    default=None,
    help="What the second column of a text file is (default: from its header).",
)
@click.option(
    "--bearing",
    "bearing_id",
    default=None,
    help="Catalogue id (for the BPFO order and the spall-width estimate).",
)
@click.option(
    "--bearing-file", type=click.Path(dir_okay=False), default=None, help="User bearing TOML file."
)
@click.option(
    "--skip-s",
    type=float,
    default=None,
    help="Leading time left out [s] (default 0; for an IAS result 10 % of the run).",
)
@click.option(
    "--samples-per-rev",
    type=int,
    default=None,
    help="Angular resampling density [1/rev] (default from the data).",
)
@click.option("--plot", type=click.Path(dir_okay=False), default=None, help="Write a PNG.")
@json_option
def analyze_ias_cmd(
    file: str,
    kind: str | None,
    bearing_id: str | None,
    bearing_file: str | None,
    skip_s: float | None,
    samples_per_rev: int | None,
    plot: str | None,
    as_json: bool,
) -> None:
    """Angle-domain analysis of a shaft angle or speed signal vs time (encoder/IAS): mean speed,
    ripple, order peaks and, with a roller bearing, the outer-race spall width (seed IAS eq. (37)).

    FILE is a two-column text file (time [s], angle or speed) or an IAS result (.nc)."""
    from ..dynamics.ias.spall import analyze_speed_signal
    from ..signal.order import (
        angle_from_speed,
        read_shaft_signal,
        resample_to_angle,
        speed_from_angle,
    )

    bearing = None
    if bearing_id is not None or bearing_file is not None:
        bearing = resolve_bearing(bearing_id, bearing_file)
        if not isinstance(bearing, RollerBearing):
            raise ConfigError(
                f"bearing = {bearing.id!r} is not a cylindrical roller bearing; the "
                "spall-width estimate (seed IAS eq. (37)) needs rollers"
            )
    p = Path(file)
    if p.suffix.lower() == ".nc":
        from ..dynamics.ias.result import IasResult

        res = IasResult.load(p)
        bearing = bearing or res.params.bearing
        sig = res.angle_signal(skip_s, samples_per_rev)
    else:
        if not p.is_file():
            raise ConfigError(f"file = {str(p)!r} does not exist")
        t, v, kind = read_shaft_signal(p, kind)
        if skip_s is not None:
            skip = check_range("skip_s", skip_s, 0.0, float(t[-1] - t[0]), hi_open=True, unit="s")
            m = t >= t[0] + skip
            t, v = t[m], v[m]
        if kind.is_angle:
            angle, speed = v, speed_from_angle(t, v)
        else:
            angle, speed = angle_from_speed(t, v), v
        sig = resample_to_angle(angle, speed, samples_per_rev)
    kw: dict[str, Any] = {}
    if bearing is not None:
        from ..geometry import characteristic_frequencies

        kin = characteristic_frequencies(bearing, 1.0)
        kw = {
            "bpfo_order": kin.bpfo_order,
            "outer_raceway_diameter": bearing.outer_raceway_diameter,
            "cage_ratio": kin.ftf_order,
        }
    summary = analyze_speed_signal(sig, **kw)
    if plot:
        from ..report.figures import save_figure

        save_figure(_summary_figure(summary, p.name), plot)
    d = summary.as_dict()
    d["bearing"] = None if bearing is None else bearing.id
    if as_json:
        emit_json(d)
        return
    _print_summary(d)
