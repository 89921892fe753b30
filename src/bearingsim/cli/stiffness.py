"""``bearingsim stiffness``: quasi-static 5-DOF stiffness and its fluctuation (seed QS5)."""

from __future__ import annotations

import math
from typing import Any

import click

from ..errors import ConfigError, check_range
from ..geometry import Bearing
from ..quasistatic.inputs import Method, Misalignment, SpeedEffects
from ..quasistatic.iso16281 import Conformities
from ..quasistatic.stiffness import SERIES, stiffness_vs_cage
from .common import (
    CLEARANCE,
    Number,
    allow_overload_option,
    bearing_options,
    check_outputs,
    cli,
    deprecated,
    echo_warnings,
    emit_json,
    json_option,
    output_option,
    rad_to_deg,
)
from .limits import budget_options

#: azimuths of the tilt axes: one turn either way [deg]
AZIMUTH_MAX_DEG = 360.0
AZIMUTH = Number(-AZIMUTH_MAX_DEG, AZIMUTH_MAX_DEG, unit="deg")

__all__ = [
    "stiffness_cmd",
]


def _parse_errors(text: str | None, n_balls: int) -> list[float] | None:
    """``--ball-errors-deg "E1,E2,..."`` -> the errors in radians (each within one ball pitch,
    checked by the model: ``ball_errors_rad``)."""
    if text is None:
        return None
    out = []
    pitch = 360.0 / n_balls
    for i, item in enumerate(text.split(",")):
        try:
            out.append(math.radians(float(item)))
        except ValueError:
            raise ConfigError(
                f"ball_errors_deg[{i}] = {item.strip()!r} is not a number; valid: comma-separated "
                f"angles in deg, one per ball, each in [-{pitch:.6g}, {pitch:.6g}] deg (one ball "
                "pitch)"
            ) from None
    return out


@cli.command("stiffness")
@bearing_options()
@click.option("--fx-n", "fx", type=Number(unit="N"), default=0.0, help="Force x [N].")
@deprecated("--fx", "--fx-n")
@click.option("--fy-n", "fy", type=Number(unit="N"), default=0.0, help="Force y [N].")
@deprecated("--fy", "--fy-n")
@click.option("--fz-n", "fz", type=Number(unit="N"), default=0.0, help="Axial force [N].")
@deprecated("--fz", "--fz-n")
@click.option("--mx-n-m", "mx", type=Number(unit="N m"), default=0.0, help="Moment about x [N m].")
@deprecated("--mx", "--mx-n-m")
@click.option("--my-n-m", "my", type=Number(unit="N m"), default=0.0, help="Moment about y [N m].")
@deprecated("--my", "--my-n-m")
@click.option(
    "--clearance-m",
    type=CLEARANCE,
    default=None,
    show_default="the bearing's",
    help="Diametral clearance P_d [m] (negative = preload).",
)
@click.option(
    "--outer-tilt-deg",
    type=Number(0.0, valid="[0, what clearance and grooves allow] deg"),
    default=0.0,
    help="Outer-ring misalignment [deg].",
)
@deprecated("--outer-tilt-rad", "--outer-tilt-deg", rad_to_deg)
@click.option(
    "--outer-tilt-azimuth-deg",
    type=AZIMUTH,
    default=0.0,
    help="Azimuth of the outer tilt axis, from +y towards +x [deg].",
)
@deprecated("--outer-tilt-azimuth-rad", "--outer-tilt-azimuth-deg", rad_to_deg)
@click.option(
    "--inner-tilt-deg",
    type=Number(0.0, valid="[0, what clearance, grooves and the outer tilt allow] deg"),
    default=0.0,
    help="Inner-ring misalignment, rotating with the shaft [deg].",
)
@deprecated("--inner-tilt-rad", "--inner-tilt-deg", rad_to_deg)
@click.option(
    "--inner-tilt-azimuth-deg",
    type=AZIMUTH,
    default=0.0,
    help="Azimuth of the inner tilt axis at shaft angle 0 [deg].",
)
@deprecated("--inner-tilt-azimuth-rad", "--inner-tilt-azimuth-deg", rad_to_deg)
@click.option(
    "--ball-errors-deg",
    default=None,
    metavar="E1,E2,...",
    help="Ball-distribution errors, one angle per ball [deg].",
)
@deprecated("--ball-errors-rad", "--ball-errors-deg", rad_to_deg)
@click.option(
    "--cage-revs",
    type=Number(1, 10000, integer=True),
    default=10,
    help="Cage revolutions [-].",
)
@click.option(
    "--points-per-rev",
    type=Number(valid="[4 Z, 100000], Z the number of balls", integer=True),
    default=360,
    help="Cage positions per revolution [-].",
)
@click.option(
    "--method",
    type=click.Choice([m.value for m in Method]),
    default="jones",
    help="Jones/Harris model or the ISO/TS 16281 method.",
)
@click.option(
    "--conformities",
    type=click.Choice([c.value for c in Conformities]),
    default=Conformities.BEARING.value,
    help="iso16281 only: the bearing's groove radii or the ISO/TS 16281 values.",
)
@click.option(
    "--rpm",
    type=Number(0.0, unit="r/min"),
    default=None,
    show_default="no inertia loads",
    help="Shaft speed for inertia loads [r/min].",
)
@click.option("--centrifugal", is_flag=True, help="Include ball centrifugal forces (needs --rpm).")
@click.option("--gyroscopic", is_flag=True, help="Include gyroscopic moments (needs --rpm).")
@click.option(
    "--plot",
    type=click.Path(dir_okay=False),
    default=None,
    help="Write stiffness series and spectra as PNG.",
)
@output_option(
    "Write the full result (netCDF-4, lossless; StiffnessResult.load reads it).", dest="out"
)
@deprecated("--out", "--output")
@allow_overload_option
@budget_options(steps=False)
@json_option
def stiffness_cmd(
    bearing: Bearing,
    fx: float,
    fy: float,
    fz: float,
    mx: float,
    my: float,
    clearance_m: float | None,
    outer_tilt_deg: float,
    outer_tilt_azimuth_deg: float,
    inner_tilt_deg: float,
    inner_tilt_azimuth_deg: float,
    ball_errors_deg: str | None,
    cage_revs: int,
    points_per_rev: int,
    method: str,
    conformities: str,
    rpm: float | None,
    centrifugal: bool,
    gyroscopic: bool,
    plot: str | None,
    out: str | None,
    allow_overload: bool,
    budget: Any,
    as_json: bool,
) -> None:
    """5x5 stiffness of BEARING at equilibrium and its fluctuation over the cage revolutions.

    Angles are given in degrees; errors from the model name the field in SI (``outer_tilt_rad``).
    """
    check_outputs(("-o/--output", out), ("--plot", plot))
    mis = Misalignment(
        outer_tilt=math.radians(outer_tilt_deg),
        outer_azimuth=math.radians(outer_tilt_azimuth_deg),
        inner_tilt=math.radians(inner_tilt_deg),
        inner_azimuth=math.radians(inner_tilt_azimuth_deg),
    )
    notes = []  # said once the run has succeeded (a refused run prints its error line only)
    for ring, tilt, azimuth in (("outer", outer_tilt_deg, outer_tilt_azimuth_deg),
                                ("inner", inner_tilt_deg, inner_tilt_azimuth_deg)):  # fmt: skip
        if tilt == 0.0 and azimuth != 0.0:
            notes.append(
                f"--{ring}-tilt-azimuth-deg {azimuth:g} has no effect: the {ring} ring is not "
                f"tilted (--{ring}-tilt-deg 0)"
            )
    if (centrifugal or gyroscopic) and rpm is None:
        raise ConfigError(
            "--centrifugal/--gyroscopic need --rpm (shaft speed); valid range (0, inf) r/min"
        )
    w = 0.0 if rpm is None else check_range("rpm", rpm, 0.0, unit="r/min") * 2.0 * math.pi / 60
    if rpm is not None and not (centrifugal or gyroscopic):
        notes.append(
            "--rpm without --centrifugal or --gyroscopic applies no inertia load (the "
            "speed is only checked against the bearing's limit)"
        )
    if bearing.contact_angle > 0.0:
        from ..quasistatic.inputs import qs_geometry

        af = qs_geometry(bearing, clearance_m).free_contact_angle
        notes.append(
            f"the bearing's contact angle ({math.degrees(bearing.contact_angle):.3g} deg) "
            f"sets only the Hertz curvatures here: the quasi-static models take the unloaded "
            f"(free) contact angle from the diametral clearance and the groove radii "
            f"({math.degrees(af):.3g} deg; docs/models.md, QS5)"
        )
    speed = SpeedEffects(shaft_speed=w, centrifugal=centrifugal, gyroscopic=gyroscopic)
    kw: dict[str, object] = dict(
        clearance=clearance_m,
        misalignment=mis,
        ball_errors=_parse_errors(ball_errors_deg, bearing.n_elements),
        speed=speed,
        allow_overload=allow_overload,
    )
    if Method(method) is Method.ISO16281:
        kw["conformities"] = Conformities(conformities)
    elif Conformities(conformities) is not Conformities.BEARING:
        raise ConfigError("--conformities applies to --method iso16281 only")
    with echo_warnings():
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
            budget=budget,
            **kw,
        )
    for n in notes:
        click.echo(f"note: {n}", err=True)
    if out:  # the data before its figure: a failed write leaves no figure of it
        res.save(out, field="-o/--output")
    if plot:
        from ..report.figures import save_figure

        save_figure(res.plot(), plot)
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
        comps = (
            ", ".join(f"{c['order_shaft']:.3f} ({c['label'] or '?'})" for c in f["components"][:3])
            or "none (constant to 1e-8 of the mean)"
        )
        click.echo(
            f"  k_{name:<6} mean {f['mean']:.5g} {f['unit']}"
            f"  p-p {100 * f['peak_to_peak_rel']:.3f} %"
            f"  dominant shaft orders: {comps}"
        )
