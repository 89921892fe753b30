"""Foundation commands: ``contact`` (Hertz contact) and ``load`` (load distribution)."""

from __future__ import annotations

import math
from typing import Any

import click
import numpy as np

from ..contact.capacity import check_element_load, check_load
from ..contact.hertz import (
    EllipticMethod,
    ball_contact,
    combined_stiffness,
    line_subsurface_stresses,
    roller_contact,
    subsurface_stresses,
)
from ..errors import ConfigError, check_range
from ..geometry import BallBearing, Bearing, Race
from ..load_distribution import RingMotion, radial_load_distribution, stribeck_qmax
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
)

__all__ = [
    "CAGE_ANGLE_MAX_DEG",
    "contact_cmd",
    "load_cmd",
]

#: the cage angle of ``load`` is one turn either way [deg] (the pattern repeats every
#: 360/Z deg; larger angles only lose digits: 1e30 deg gave delta_max = 9.8e54 m)
CAGE_ANGLE_MAX_DEG = 360.0


def _contact_dict(bearing: Bearing, q: float, method: EllipticMethod) -> dict[str, Any]:
    out: dict[str, Any] = {}
    nu = bearing.material.poisson_ratio
    for race in (Race.INNER, Race.OUTER):
        if isinstance(bearing, BallBearing):
            c = ball_contact(bearing, q, race, method)
            s = subsurface_stresses(c, nu) if q > 0 else None
            a, b, k = float(c.a), float(c.b), c.k_hertz
            extra = {"ellipticity": c.ellipticity.k, "exponent": 1.5}
        else:
            c = roller_contact(bearing, q, race)
            s = line_subsurface_stresses(c, nu) if q > 0 else None
            a, b, k = 0.5 * c.length, float(c.b), c.k_line
            extra = {"exponent": 10.0 / 9.0}
        out[race.value] = {
            "a_m": a,
            "b_m": b,
            "delta_m": float(c.delta),
            "p_max_pa": float(c.p_max),
            "k_hertz": k,
            "tau_max_pa": s.tau_max if s else 0.0,
            "tau_max_depth_m": s.tau_max_depth if s else 0.0,
            "tau_orth_pa": s.tau_orth if s else 0.0,
            "tau_orth_depth_m": s.tau_orth_depth if s else 0.0,
            **extra,
        }
    n = out["inner"]["exponent"]
    out["k_combined"] = combined_stiffness(out["inner"]["k_hertz"], out["outer"]["k_hertz"], n)
    return out


@cli.command("contact")
@bearing_options()
@click.option(
    "--ball-load-n",
    "ball_load",
    type=Number(0.0, unit="N"),
    default=None,
    help="Element load Q [N].",
)
@deprecated("--ball-load", "--ball-load-n")
@click.option(
    "--radial-load-n",
    "radial_load",
    type=Number(0.0, lo_open=True, unit="N"),
    default=None,
    help="Bearing radial load F_r [N]; the most-loaded element is used.",
)
@deprecated("--radial-load", "--radial-load-n")
@click.option(
    "--method",
    type=click.Choice([m.value for m in EllipticMethod]),
    default="exact",
    help="Point-contact solution.",
)
@allow_overload_option
@json_option
def contact_cmd(
    bearing: Bearing,
    ball_load: float | None,
    radial_load: float | None,
    method: str,
    allow_overload: bool,
    as_json: bool,
) -> None:
    """Hertz contact of the most-loaded element with both raceways."""
    if (ball_load is None) == (radial_load is None):
        raise ConfigError("contact: give exactly one of --ball-load-n Q or --radial-load-n F_R")
    extra: dict[str, Any] = {}
    with echo_warnings():
        if radial_load is not None:
            fr = check_range("radial_load_n", radial_load, 0.0, lo_open=True, unit="N")
            check_load(bearing, fr, allow_overload)
            ld = radial_load_distribution(bearing, 0.0, fr, allow_overload=None)
            q = float(ld.ball_loads.max())
            q_stribeck = stribeck_qmax(bearing, fr)
            extra = {"radial_load_n": fr, "q_max_n": q, "q_max_stribeck_n": q_stribeck}
        else:
            q = check_range("ball_load_n", ball_load, 0.0, unit="N")
            check_element_load(bearing, q, allow_overload)
        out = {"ball_load_n": q, **extra, **_contact_dict(bearing, q, EllipticMethod(method))}
    if as_json:
        emit_json(out)
        return
    click.echo(f"{bearing.id}: element load {q:.4g} N")
    for race in ("inner", "outer"):
        r = out[race]
        click.echo(
            f"  {race:<5} a={r['a_m'] * 1e3:.4f} mm b={r['b_m'] * 1e3:.4f} mm "
            f"delta={r['delta_m'] * 1e6:.3f} um p_max={r['p_max_pa'] / 1e6:.1f} MPa "
            f"tau_max={r['tau_max_pa'] / 1e6:.1f} MPa @ {r['tau_max_depth_m'] * 1e3:.4f} mm"
        )
    click.echo(f"  combined K = {out['k_combined']:.5g}")


@cli.command("load")
@bearing_options()
@click.option("--fx-n", "fx", type=Number(unit="N"), default=0.0, help="Radial force x [N].")
@deprecated("--fx", "--fx-n")
@click.option("--fy-n", "fy", type=Number(unit="N"), default=0.0, help="Radial force y [N].")
@deprecated("--fy", "--fy-n")
@click.option(
    "--cage-angle-deg",
    type=Number(-CAGE_ANGLE_MAX_DEG, CAGE_ANGLE_MAX_DEG, unit="deg"),
    default=0.0,
    help="Cage angle, position of element 1 from +y towards +x [deg].",
)
@click.option(
    "--clearance-m",
    type=CLEARANCE,
    default=None,
    show_default="the bearing's",
    help="Diametral clearance [m] (negative = preload).",
)
@click.option(
    "--motion",
    type=click.Choice([m.value for m in RingMotion]),
    default="free",
    help="Ring DOF: free in the plane, or along the load line (seed form).",
)
@click.option(
    "--plot", type=click.Path(dir_okay=False), default=None, help="Write a polar plot PNG."
)
@allow_overload_option
@json_option
def load_cmd(
    bearing: Bearing,
    fx: float,
    fy: float,
    cage_angle_deg: float,
    clearance_m: float | None,
    motion: str,
    plot: str | None,
    allow_overload: bool,
    as_json: bool,
) -> None:
    """Radial load distribution over the discrete elements."""
    check_outputs(("--plot", plot))
    a = CAGE_ANGLE_MAX_DEG
    cage = math.radians(check_range("cage_angle_deg", cage_angle_deg, -a, a, unit="deg"))
    with echo_warnings():
        ld = radial_load_distribution(
            bearing,
            fx,
            fy,
            cage,
            clearance=clearance_m,
            motion=motion,
            allow_overload=allow_overload,
        )
    out = {
        "theta0_deg": math.degrees(ld.theta0),
        "fr_n": ld.fr,
        "delta_max_m": float(ld.delta_max[0]),
        "delta_r_m": float(ld.delta_r[0]),
        "epsilon": float(ld.epsilon[0]),
        "psi_l_deg": math.degrees(float(ld.psi_l[0])),
        "ball_angles_deg": np.degrees(ld.ball_angles[0]),
        "ball_loads_n": ld.ball_loads[0],
        "n_loaded": int(ld.n_loaded[0]),
        "displacement_m": ld.displacement[0],
        "residual_rel": float(ld.residual[0]),
        # the unbalanced force (x, y) [N]: with --motion load_line the perpendicular force is
        # not balanced (residual_rel is the load line's; a helper's exploratory testing,
        # twenty-eighth session: 2.2 N of a 51 N load went unreported)
        "force_residual_n": ld.force_residual[0],
        "stiffness": ld.stiffness,
    }
    if plot:
        from ..report.figures import save_figure

        save_figure(ld.plot(0), plot)
    if as_json:
        emit_json(out)
        return
    click.echo(
        f"{bearing.id}: F_r={ld.fr:.4g} N theta0={out['theta0_deg']:.2f} deg "
        f"delta_max={out['delta_max_m'] * 1e6:.4f} um psi_L={out['psi_l_deg']:.2f} deg "
        f"n_loaded={out['n_loaded']}"
    )
    for a, q in zip(out["ball_angles_deg"], out["ball_loads_n"], strict=True):
        click.echo(f"  psi={a:8.2f} deg  Q={q:10.4f} N")
    rx, ry = out["force_residual_n"]
    if math.hypot(rx, ry) > 1e-9 * max(ld.fr, 1.0):  # load_line: the force it leaves
        click.echo(f"  unbalanced force: ({rx:.4g}, {ry:.4g}) N (x, y)")
