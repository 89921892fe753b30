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
from .common import (
    DeferredDefaultOption,
    Number,
    allow_overload_option,
    check_outputs,
    cli,
    deprecated,
    echo_warnings,
    emit_json,
    json_option,
    output_option,
    scenario_default,
)
from .limits import budget_options

__all__ = [
    "analyze_ias_cmd",
    "ias_cmd",
]

TWO_PI = 2.0 * math.pi


def _print_summary(d: dict[str, Any]) -> None:
    click.echo(f"mean speed        {d['mean_speed_rpm']:.4f} r/min")
    click.echo(f"IAS ripple        {d['ias_ripple_rel']:.4g} (peak-to-peak / mean)")
    if d.get("bpfo_order_theory") is not None:
        click.echo(f"BPFO order        {d['bpfo_order_theory']:.4f} (kinematic)")
    for p in d["order_peaks"]:
        click.echo(f"  peak at order {p['order']:8.4f}  amplitude {p['amplitude']:.4g} rad/s")
    est = d.get("spall_width_estimate_m")
    click.echo(
        "spall width       "
        + (
            "not detected (no spall event, or its entry and impact drops not resolved apart "
            "on the signal's angle grid: a narrow spall at a high speed)"
            if est is None
            else f"{est * 1e3:.4f} mm"
        )
    )


def _summary_figure(summary, title: str):
    from ..plotting import FULL_WIDTH, new_figure

    fig, ax = new_figure(3, 1, width=FULL_WIDTH, row_height=2.6)
    sig = summary.signal
    ax[0].plot(sig.angle / TWO_PI, sig.value * 60 / TWO_PI, lw=0.7)
    ax[0].set_xlabel("shaft angle [rev]")
    ax[0].set_ylabel("IAS [r/min]")
    ax[0].set_title(title)
    marks = []
    if summary.bpfo_order:
        marks = summary.bpfo_order * np.arange(1, int(30 / summary.bpfo_order) + 1)
    summary.spectrum.plot(
        30.0,
        ax=ax[1],
        scale=60 / TWO_PI,
        unit="r/min",
        marks=marks,
        marks_label="BPFO order and harmonics" if len(marks) else None,
        quantity="IAS amplitude",
    )
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
            f"averaged roller pass: crossing {e.crossing_angle:.4f} rad → "
            f"L_d = {e.width * 1e3:.3f} mm"
        )
    else:
        ax[2].text(0.5, 0.5, "no spall event detected", ha="center", transform=ax[2].transAxes)
    ax[2].set_xlabel("shaft angle within one roller pass [rad]")
    ax[2].set_ylabel("IAS [r/min]")
    return fig


def _default(key: str) -> dict[str, Any]:
    """``cls`` and ``show_default`` of an option that sets IAS scenario key ``key``: its default
    (the seed's case, :class:`~bearingsim.config.IasScenario`), looked up only when help is
    shown."""

    def text() -> str | bool:
        from ..config import SEED_IAS_TORQUE_N_M

        if key == "torque_n_m":
            return format(SEED_IAS_TORQUE_N_M, "g")
        return scenario_default(key, model="ias")

    return {"cls": DeferredDefaultOption, "show_default": text}


@cli.command("ias")
@click.argument("scenario", required=False, type=click.Path(dir_okay=False))
@click.option(
    "--bearing",
    "bearing_id",
    default=None,
    show_default="NU204-ECP",
    help="Catalogue id of a cylindrical roller bearing.",
)
@click.option(
    "--bearing-file", type=click.Path(dir_okay=False), default=None, help="User bearing TOML file."
)
@click.option(
    "--rpm",
    type=Number(0.0, lo_open=True, unit="r/min"),
    default=None,
    show_default="set by --torque-n-m",
    help="Target speed [r/min]: sets M_z = C_T * speed (the speed itself comes out of "
    "the torque balance).",
)
@click.option(
    "--torque-n-m",
    "torque_n_m",
    type=Number(0.0, unit="N m"),
    default=None,
    **_default("torque_n_m"),
    help="Motor torque M_z [N m].",
)
@deprecated("--torque-nm", "--torque-n-m")
@click.option(
    "--initial-rpm",
    type=Number(0.0, unit="r/min"),
    default=None,
    **_default("initial_rpm"),
    help="Initial shaft speed [r/min].",
)
@click.option(
    "--spall-width-m",
    type=Number(valid="[0, d) m, d the roller diameter"),
    default=None,
    **_default("spall_width_m"),
    help="Outer-race spall width L_d [m]; 0 = healthy.",
)
@click.option(
    "--spall-angle-deg",
    type=Number(-360.0, 360.0, unit="deg"),
    default=None,
    **_default("spall_angle_deg"),
    help="Spall centre azimuth from +y towards +x [deg] (180 = bottom).",
)
@click.option(
    "--fx-n",
    "fx_n",
    type=Number(unit="N"),
    default=None,
    **_default("fx_n"),
    help="Radial load along +x [N].",
)
@deprecated("--fx", "--fx-n")
@click.option(
    "--fy-n",
    "fy_n",
    type=Number(unit="N"),
    default=None,
    **_default("fy_n"),
    help="Radial load pushing the shaft down (-y) [N].",
)
@deprecated("--fy", "--fy-n")
@click.option(
    "--duration-s",
    type=Number(0.0, lo_open=True, unit="s"),
    default=None,
    **_default("duration_s"),
    help="Simulated time [s].",
)
@click.option(
    "--dt-s",
    type=Number(0.0, lo_open=True, unit="s"),
    default=None,
    **_default("dt_s"),
    help="RK4 step [s].",
)
@click.option(
    "--fs-hz",
    "fs_hz",
    type=Number(0.0, lo_open=True, unit="Hz"),
    default=None,
    **_default("fs_hz"),
    help="Output sample rate [Hz].",
)
@deprecated("--output-rate-hz", "--fs-hz")
@click.option(
    "--solver",
    "solver",
    type=click.Choice(["rk4", "dopri5"]),
    default=None,
    **_default("solver"),
    help="Integrator.",
)
@deprecated("--method", "--solver")
@click.option(
    "--contact-law",
    type=click.Choice(["seed", "harris"]),
    default=None,
    **_default("contact_law"),
    help="Roller stiffness: seed IAS eqs. (5)-(12) or Harris/Palmgren.",
)
@click.option(
    "--spall-load",
    type=click.Choice(["stribeck", "dynamic"]),
    default=None,
    **_default("spall_load"),
    help="Roller load in the spall force, seed IAS eq. (30).",
)
@click.option(
    "--skip-s",
    type=Number(valid="[0, duration) s"),
    default=None,
    show_default="10 % of the run",
    help="Start-up left out of the analysis [s].",
)
@output_option("Result file (netCDF).", required=True, dest="out")
@deprecated("--out", "--output")
@click.option(
    "--plot",
    type=click.Path(dir_okay=False),
    default=None,
    help="Write a PNG: IAS vs angle, order spectrum, spall estimate.",
)
@allow_overload_option
@budget_options()
@json_option
def ias_cmd(
    scenario: str | None,
    bearing_id: str | None,
    bearing_file: str | None,
    out: str,
    plot: str | None,
    as_json: bool,
    budget: Any,
    allow_overload: bool,
    **opts: Any,
) -> None:
    """Simulate the 3-DOF IAS model of seed IAS (NU204-ECP, outer-race spall) and analyse the
    instantaneous angular speed.

    The analysis is in the angle domain (order spectrum, spall-width estimate); SCENARIO is an
    IAS scenario file whose keys the options override."""
    check_outputs(("-o/--output", out), ("--plot", plot))
    import sys

    from tqdm import tqdm

    from ..config import IasScenario
    from ..dynamics.ias.scenario import check_ias, read_scenario, run_ias
    from ..dynamics.ias.spall import ShortSignalError

    settings: dict[str, Any] = read_scenario(scenario) if scenario else {}
    if bearing_id is not None or bearing_file is not None:
        settings.pop("bearing", None)
        settings.pop("bearing_file", None)
        settings.update(bearing=bearing_id, bearing_file=bearing_file)
    if opts.get("rpm") is not None or opts.get("torque_n_m") is not None:
        if opts.get("rpm") is not None and opts.get("torque_n_m") is not None:
            raise ConfigError("give at most one of --rpm and --torque-n-m")
        settings.pop("rpm", None)
        settings.pop("torque_n_m", None)
    settings.update({k: v for k, v in opts.items() if v is not None})
    settings = {k: v for k, v in settings.items() if v is not None}
    settings["model"] = "ias"
    sc = IasScenario.from_dict(settings, origin=Path(scenario).name if scenario else "options")
    seen: set[str] = set()
    with echo_warnings(seen):  # everything checked before any work or output
        check_ias(sc, budget, allow_overload)
    bar = tqdm(total=sc.n_samples, desc="ias", unit="sample", disable=as_json, leave=False,
               delay=1.0, file=sys.stderr)  # fmt: skip
    try:
        with echo_warnings(seen):
            res = run_ias(sc, lambda n: bar.update(n - bar.n), budget, allow_overload)
    finally:
        bar.close()
    params = res.params
    try:
        summary = res.analyze(sc.skip_s, budget=budget)
    except ShortSignalError as exc:  # too little rotation to resolve the BPFO order
        raise ConfigError(_too_short(res, sc, exc)) from None
    res.save(
        out, field="-o/--output"
    )  # the data before its figure: a failed write leaves no figure of it
    if plot:
        from ..report.figures import save_figure

        lab = f"spall {params.spall_width * 1e3:g} mm" if params.spall_width > 0 else "healthy"
        save_figure(_summary_figure(summary, f"{params.bearing.id}, {lab}"), plot)
    d = summary.as_dict()
    d.update(
        wall_s=res.solver["wall_s"],
        cpu_s=res.solver["cpu_s"],
        free_speed_rpm=res.constants.free_speed * 60 / TWO_PI,
        torque_n_m=params.torque,
        spall_width_m=params.spall_width,
        bearing=params.bearing.id,
        solver={k: res.solver[k] for k in ("method", "dt_s", "n_steps", "output_rate_hz")},
        output=str(out),
    )
    if as_json:
        emit_json(d)
        return
    click.echo(
        f"{params.bearing.id}: {sc.duration_s:g} s simulated in {d['wall_s']:.2f} s "
        f"({sc.solver.value}, dt {res.solver['dt_s']:g} s); M_z {params.torque:g} N m, free speed "
        f"{d['free_speed_rpm']:.4f} r/min"
    )
    _print_summary(d)
    click.echo(f"wrote {out}")


def _too_short(res, sc, exc: Exception) -> str:
    """The refusal of a run too short to resolve the BPFO order (``exc``, a
    :class:`~bearingsim.dynamics.ias.spall.ShortSignalError`): its ``duration_s`` and
    ``skip_s``, why, and the duration that would do at the simulated speed (the analysed span,
    after ``skip_s`` — 10 % of the run unless given —, covering
    :func:`~bearingsim.dynamics.ias.spall.min_revs` revolutions)."""
    from ..dynamics.ias.spall import min_revs

    skip = res.default_skip() if sc.skip_s is None else sc.skip_s
    why = str(exc).split("; valid")[0]
    revs = min_revs(res.constants.bpfo_order)
    hint = f" for n_revs >= {revs:.4g}"
    m = res.steady(skip)
    t, th = res.t[m], res.theta[m]
    revs_per_s = (th[-1] - th[0]) / TWO_PI / (t[-1] - t[0])
    if revs_per_s > 0.0:
        need = revs / revs_per_s  # analysed time needed [s]
        dur = need / 0.9 if sc.skip_s is None else skip + need
        hint += f" (about duration_s >= {dur:.3g} s at the simulated {revs_per_s * 60:.4g} r/min)"
    return (
        f"duration_s = {sc.duration_s:g} s with skip_s = {skip:g} s leaves too little rotation "
        f"to analyse ({why}); valid: a longer duration_s or a smaller skip_s{hint}"
    )


_KINDS = tuple(k.value for k in ShaftSignalKind)


@cli.command("analyze-ias")
@click.argument("file", type=click.Path(dir_okay=False))
@click.option(
    "--kind",
    type=click.Choice(_KINDS),
    default=None,
    show_default="from the header",
    help="What the second column of a text file is.",
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
    type=Number(valid="[0, duration) s"),
    default=None,
    show_default="0; for an IAS result 10 % of the run",
    help="Leading time left out [s].",
)
@click.option(
    "--samples-per-rev",
    type=Number(8, 2**24, integer=True),
    default=None,
    show_default="from the data",
    help="Angular resampling density [1/rev].",
)
@click.option("--plot", type=click.Path(dir_okay=False), default=None, help="Write a PNG.")
@budget_options(steps=False)
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
    budget: Any,
) -> None:
    """Angle-domain analysis of a shaft angle or speed signal vs time (encoder/IAS).

    Mean speed, ripple, order peaks and, with a roller bearing, the outer-race spall width
    (seed IAS eq. (37)); with a bearing, the signal must span at least 4 / BPFO order
    revolutions (the order resolution that separates the fault order from its harmonics).
    The resampling and the order spectrum must fit the memory budget (--max-memory-gb).

    FILE is a two-column text file (time [s], angle or speed) or an IAS result (.nc)."""
    check_outputs(("--plot", plot))
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
        sig = res.angle_signal(skip_s, samples_per_rev, budget=budget)
        mean_speed = None
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
        # total angle over total time: exact, where the samples' derivative amplifies any
        # timing noise (a mean of d angle/dt over jittered stamps is biased upwards)
        mean_speed = float((angle[-1] - angle[0]) / (t[-1] - t[0]))
        limit = budget.memory_limit()[0]  # refused before anything is allocated
        sig = resample_to_angle(angle, speed, samples_per_rev,
                                max_memory=limit if math.isfinite(limit) else None)  # fmt: skip
    kw: dict[str, Any] = {}
    if bearing is not None:
        from ..geometry import characteristic_frequencies

        kin = characteristic_frequencies(bearing, 1.0)
        kw = {
            "bpfo_order": kin.bpfo_order,
            "outer_raceway_diameter": bearing.outer_raceway_diameter,
            "cage_ratio": kin.ftf_order,
        }
    summary = analyze_speed_signal(sig, mean_speed=mean_speed, **kw)
    if plot:
        from ..report.figures import save_figure

        save_figure(_summary_figure(summary, p.name), plot)
    d = summary.as_dict()
    d["bearing"] = None if bearing is None else bearing.id
    if as_json:
        emit_json(d)
        return
    _print_summary(d)
