"""Rotor commands: ``rotor-modes`` (natural frequencies of the rotor alone); the options that
build a :class:`~bearingsim.dynamics.rotor_config.RotorConfig` from the command line; and the
rotor options of ``bearingsim simulate --model rotor`` (:func:`rotor_simulate_options`, keys of
:class:`bearingsim.config.Scenario`). Lengths in millimetres at this edge, SI inside."""

from __future__ import annotations

import functools
from collections.abc import Callable
from typing import Any

import click

from ..dynamics.rotor.config import (
    SEED_DISK_DIAMETER_M,
    SEED_ROTOR_MASS_KG,
    SEED_SHAFT_DIAMETER_M,
    SEED_SHAFT_E_PA,
    SEED_SHAFT_LENGTH_M,
    SEED_SHAFT_MASS_KG,
    Armature,
    Shaft,
    ShaftMassModel,
    cwru_rotor_config,
)
from ..errors import ConfigError
from .common import cli, emit_json, json_option


def _positions_mm(text: str | None) -> tuple[float, ...] | None:
    if text is None:
        return None
    try:
        return tuple(float(v) * 1e-3 for v in text.replace(";", ",").split(",") if v.strip())
    except ValueError:
        raise ConfigError(
            f"disk_positions_mm = {text!r} is not a comma-separated list of numbers"
        ) from None


def _positions_option(ctx, param, value):
    """``--disk-positions-mm "20,100,180"`` -> (20.0, 100.0, 180.0) [mm] (Scenario key)."""
    pos = _positions_mm(value)
    return None if pos is None else tuple(v * 1e3 for v in pos)


def rotor_simulate_options(f: Callable) -> Callable:
    """Options of ``simulate`` for ``--model rotor``; each sets the Scenario key of the same
    name (None = the scenario file's value or the default)."""
    faults = click.Choice(["none", "outer", "inner"])
    opts = [
        click.option("--de-bearing", default=None, help="Drive-end bearing id [6205-cwru]."),
        click.option("--fe-bearing", default=None, help="Fan-end bearing id [6203-cwru]."),
        click.option("--de-fault", type=faults, default=None, help="Drive-end defect [none]."),
        click.option("--fe-fault", type=faults, default=None, help="Fan-end defect [none]."),
        click.option(
            "--de-defect-angle-deg",
            type=float,
            default=None,
            help="DE defect centre azimuth at t = 0 from +y towards +x [deg] (180 = 6 o'clock).",
        ),
        click.option(
            "--fe-defect-angle-deg", type=float, default=None, help="FE defect centre [deg] (180)."
        ),
        click.option("--disks", type=int, default=None, help="Number of rotor disks [9]."),
        click.option(
            "--disk-positions-mm",
            default=None,
            callback=_positions_option,
            help="Disk positions from the DE bearing, comma-separated [mm] (equal spacing).",
        ),
        click.option(
            "--distributed-rotor/--disk-rotor",
            default=None,
            help="Rotor mass spread along the shaft instead of on disks.",
        ),
        click.option(
            "--elements", "n_elements", type=int, default=None, help="Min. beam elements (auto)."
        ),
        click.option(
            "--shaft-mass-model",
            type=click.Choice(["lumped", "distributed"]),
            default=None,
            help="Half the shaft mass at each bearing (seed) or distributed [lumped].",
        ),
        click.option(
            "--housing-mass-kg", type=float, default=None, help="Housing mass [kg] (6.638)."
        ),
        click.option(
            "--housing-stiffness-n-m",
            type=float,
            default=None,
            help="Housing mount stiffness, X and Y [N/m] (1.51e7).",
        ),
        click.option(
            "--housing-damping-n-s-m",
            type=float,
            default=None,
            help="Housing mount damping, X and Y [N s/m] (2210.7).",
        ),
        click.option(
            "--contact-damping",
            "contact_damping_n_s_m",
            type=float,
            default=None,
            help="Damping of each ball-race contact [N s/m] (50).",
        ),
        click.option("--gravity/--no-gravity", default=None, help="Gravity on every mass [on]."),
        click.option("--unbalance-kg-m", type=float, default=None, help="Rotor unbalance m e."),
        click.option(
            "--antialias/--no-antialias",
            default=None,
            help="Oversample (4x, 2x above 24 kHz) and FIR-decimate the accelerations [on].",
        ),
    ]
    for o in reversed(opts):
        f = o(f)
    return f


def rotor_options(f: Callable) -> Callable:
    """Options describing the rotor (shaft, armature, mesh); the command receives
    ``rotor_kw`` (keyword arguments for :func:`cwru_rotor_config`) instead."""

    @click.option("--disks", type=int, default=9, show_default=True, help="Number of disks.")
    @click.option(
        "--disk-positions-mm",
        default=None,
        help="Disk positions from the drive-end bearing, comma-separated [mm] "
        "(default: equally spaced).",
    )
    @click.option(
        "--distributed-rotor",
        is_flag=True,
        help="Spread the rotor mass uniformly along the shaft instead of disks.",
    )
    @click.option("--elements", type=int, default=None, help="Minimum number of beam elements.")
    @click.option(
        "--shaft-mass-model",
        type=click.Choice([m.value for m in ShaftMassModel]),
        default="lumped",
        show_default=True,
        help="Half the shaft mass at each bearing (seed) or distributed.",
    )
    @click.option(
        "--shaft-length-mm", type=float, default=SEED_SHAFT_LENGTH_M * 1e3, show_default=True
    )
    @click.option(
        "--shaft-diameter-mm", type=float, default=SEED_SHAFT_DIAMETER_M * 1e3, show_default=True
    )
    @click.option("--shaft-E-pa", "shaft_e", type=float, default=SEED_SHAFT_E_PA, show_default=True)
    @click.option("--shaft-mass-kg", type=float, default=SEED_SHAFT_MASS_KG, show_default=True)
    @click.option("--rotor-mass-kg", type=float, default=SEED_ROTOR_MASS_KG, show_default=True)
    @click.option(
        "--disk-diameter-mm", type=float, default=SEED_DISK_DIAMETER_M * 1e3, show_default=True
    )
    @functools.wraps(f)
    def wrapper(
        disks: int,
        disk_positions_mm: str | None,
        distributed_rotor: bool,
        elements: int | None,
        shaft_mass_model: str,
        shaft_length_mm: float,
        shaft_diameter_mm: float,
        shaft_e: float,
        shaft_mass_kg: float,
        rotor_mass_kg: float,
        disk_diameter_mm: float,
        **kw: Any,
    ) -> Any:
        shaft = Shaft(
            shaft_length_mm * 1e-3, shaft_diameter_mm * 1e-3, shaft_e, shaft_mass_kg,
            shaft_mass_model,
        )  # fmt: skip
        pos = _positions_mm(disk_positions_mm)
        arm = Armature(
            rotor_mass_kg,
            disk_diameter_mm * 1e-3,
            n_disks=len(pos) if pos else disks,
            positions=pos or None,
            distributed=distributed_rotor,
        )
        rotor_kw = {"shaft": shaft, "armature": arm, "n_elements": elements}
        return f(rotor_kw=rotor_kw, **kw)

    return wrapper


@cli.command("rotor-modes")
@rotor_options
@click.option(
    "--supports",
    type=click.Choice(["pinned", "free"]),
    default="pinned",
    show_default=True,
    help="Bearing nodes held in x, y (simply supported) or free-free.",
)
@click.option("--rpm", type=float, default=0.0, show_default=True, help="Spin speed [r/min].")
@click.option("--n-modes", type=int, default=8, show_default=True)
@json_option
def rotor_modes_cmd(
    rotor_kw: dict[str, Any], supports: str, rpm: float, n_modes: int, as_json: bool
) -> None:
    """Natural frequencies of the CWRU rotor alone (seed ROTOR table 2 by default)."""
    from ..dynamics.rotor.model import rotor_modes

    if n_modes < 1:
        raise ConfigError(f"n_modes = {n_modes} is out of range; valid range [1, inf)")
    cfg = cwru_rotor_config(**rotor_kw)
    m = rotor_modes(cfg, supports=supports, speed_rpm=rpm, n_modes=n_modes)
    out = {
        "supports": supports,
        "speed_rpm": rpm,
        "n_fe_dof": m.n_dof,
        "frequency_hz": m.frequency_hz,
        "whirl": list(m.whirl),
        "disk_positions_m": list(cfg.disk_positions),
    }
    if as_json:
        emit_json(out)
        return
    click.echo(
        f"rotor alone ({supports}, {rpm:g} r/min, {len(cfg.disk_positions)} disk(s), "
        f"{m.n_dof} FE DOF):"
    )
    for i, (f, w) in enumerate(zip(m.frequency_hz, m.whirl, strict=True), 1):
        click.echo(f"  mode {i:2d}: {f:10.3f} Hz  {w}")
