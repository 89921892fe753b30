"""``bearingsim stiffness``: quasi-static 5-DOF stiffness and its fluctuation (seed QS5)."""

from __future__ import annotations

import math

import click

from ..errors import ConfigError, check_range
from ..geometry import Bearing
from ..quasistatic.inputs import Method, Misalignment, SpeedEffects
from ..quasistatic.iso16281 import Conformities
from ..quasistatic.stiffness import SERIES, stiffness_vs_cage
from .common import bearing_options, cli, emit_json, json_option


def _parse_errors(text: str | None) -> list[float] | None:
    if text is None:
        return None
    out = []
    for i, item in enumerate(text.split(",")):
        try:
            out.append(float(item))
        except ValueError:
            raise ConfigError(
                f"ball_errors_rad[{i}] = {item.strip()!r} is not a number; valid: comma-separated "
                "angles in rad, one per ball"
            ) from None
    return out


@cli.command("stiffness")
@bearing_options()
@click.option("--fx", type=float, default=0.0, show_default=True, help="Force x [N].")
@click.option("--fy", type=float, default=0.0, show_default=True, help="Force y [N].")
@click.option("--fz", type=float, default=0.0, show_default=True, help="Axial force [N].")
@click.option("--mx", type=float, default=0.0, show_default=True, help="Moment about x [N m].")
@click.option("--my", type=float, default=0.0, show_default=True, help="Moment about y [N m].")
@click.option(
    "--clearance-m",
    type=float,
    default=None,
    help="Diametral clearance P_d [m] (negative = preload).",
)
@click.option(
    "--outer-tilt-rad",
    type=float,
    default=0.0,
    show_default=True,
    help="Outer-ring misalignment [rad].",
)
@click.option(
    "--outer-tilt-azimuth-rad",
    type=float,
    default=0.0,
    show_default=True,
    help="Azimuth of the outer tilt axis, from +y towards +x [rad].",
)
@click.option(
    "--inner-tilt-rad",
    type=float,
    default=0.0,
    show_default=True,
    help="Inner-ring misalignment, rotating with the shaft [rad].",
)
@click.option(
    "--inner-tilt-azimuth-rad",
    type=float,
    default=0.0,
    show_default=True,
    help="Azimuth of the inner tilt axis at shaft angle 0 [rad].",
)
@click.option(
    "--ball-errors-rad",
    default=None,
    metavar="E1,E2,...",
    help="Ball-distribution errors, one angle per ball [rad].",
)
@click.option("--cage-revs", type=int, default=10, show_default=True, help="Cage revolutions [-].")
@click.option(
    "--points-per-rev",
    type=int,
    default=360,
    show_default=True,
    help="Cage positions per revolution [-].",
)
@click.option(
    "--method",
    type=click.Choice([m.value for m in Method]),
    default="jones",
    show_default=True,
    help="Jones/Harris model or the ISO/TS 16281 method.",
)
@click.option(
    "--conformities",
    type=click.Choice([c.value for c in Conformities]),
    default=Conformities.BEARING.value,
    show_default=True,
    help="iso16281: groove radii of the bearing or ISO defaults.",
)
@click.option("--rpm", type=float, default=None, help="Shaft speed for inertia loads [r/min].")
@click.option("--centrifugal", is_flag=True, help="Include ball centrifugal forces (needs --rpm).")
@click.option("--gyroscopic", is_flag=True, help="Include gyroscopic moments (needs --rpm).")
@click.option(
    "--plot",
    type=click.Path(dir_okay=False),
    default=None,
    help="Write stiffness series and spectra as PNG.",
)
@click.option(
    "-o",
    "--out",
    "out",
    type=click.Path(dir_okay=False),
    default=None,
    help="Write the full result (netCDF-4, lossless; StiffnessResult.load reads it).",
)
@json_option
def stiffness_cmd(
    bearing: Bearing,
    fx: float,
    fy: float,
    fz: float,
    mx: float,
    my: float,
    clearance_m: float | None,
    outer_tilt_rad: float,
    outer_tilt_azimuth_rad: float,
    inner_tilt_rad: float,
    inner_tilt_azimuth_rad: float,
    ball_errors_rad: str | None,
    cage_revs: int,
    points_per_rev: int,
    method: str,
    conformities: str,
    rpm: float | None,
    centrifugal: bool,
    gyroscopic: bool,
    plot: str | None,
    out: str | None,
    as_json: bool,
) -> None:
    """5x5 stiffness of BEARING at equilibrium and its fluctuation over the cage revolutions."""
    mis = Misalignment(
        outer_tilt=outer_tilt_rad,
        outer_azimuth=outer_tilt_azimuth_rad,
        inner_tilt=inner_tilt_rad,
        inner_azimuth=inner_tilt_azimuth_rad,
    )
    if (centrifugal or gyroscopic) and rpm is None:
        raise ConfigError(
            "--centrifugal/--gyroscopic need --rpm (shaft speed); valid range (0, inf) r/min"
        )
    w = 0.0 if rpm is None else check_range("rpm", rpm, 0.0, unit="r/min") * 2.0 * math.pi / 60
    speed = SpeedEffects(shaft_speed=w, centrifugal=centrifugal, gyroscopic=gyroscopic)
    kw: dict[str, object] = dict(
        clearance=clearance_m,
        misalignment=mis,
        ball_errors=_parse_errors(ball_errors_rad),
        speed=speed,
    )
    if Method(method) is Method.ISO16281:
        kw["conformities"] = Conformities(conformities)
    elif Conformities(conformities) is not Conformities.BEARING:
        raise ConfigError("--conformities applies to --method iso16281 only")
    res = stiffness_vs_cage(
        bearing,
        fx,
        fy,
        fz,
        mx,
        my,
        cage_revs=cage_revs,
        points_per_rev=points_per_rev,
        method=Method(method),
        **kw,
    )
    if plot:
        from ..report.figures import save_figure

        save_figure(res.plot(), plot)
    if out:
        res.save(out)
    d = res.to_dict(full=False)
    if as_json:
        emit_json(d)
        return
    u = d["displacement"]
    click.echo(
        f"{bearing.id} ({method}): at cage angle 0 x={u['x_m'] * 1e6:.4f} um "
        f"y={u['y_m'] * 1e6:.4f} um z={u['z_m'] * 1e6:.4f} um "
        f"theta_x={u['theta_x_rad']:.4g} rad theta_y={u['theta_y_rad']:.4g} rad"
    )
    fl = d["fluctuation"]
    for name in SERIES:
        f = fl[name]
        comps = ", ".join(
            f"{c['order_shaft']:.3f} ({c['label'] or '?'})" for c in f["components"][:3]
        )
        click.echo(
            f"  k_{name:<6} mean {f['mean']:.5g} {f['unit']}"
            f"  p-p {100 * f['peak_to_peak_rel']:.3f} %"
            f"  dominant shaft orders: {comps}"
        )
