"""Rotor commands: ``rotor-modes`` (natural frequencies of the rotor alone); the options that
build a :class:`~bearingsim.dynamics.rotor.RotorConfig` from the command line; and the
rotor options of ``bearingsim simulate --model rotor`` (:func:`rotor_simulate_options`, keys of
:class:`bearingsim.config.Scenario`). Lengths in millimetres at this edge, SI inside.

``simulate`` imports this module for its options, so the rotor model (and its compiled kernels)
is imported only inside the functions that need it."""

from __future__ import annotations

import functools
from collections.abc import Callable
from typing import Any

import click

from ..config import SEED_ROTOR_DISKS
from ..errors import ConfigError
from ..materials import YOUNGS_MODULUS_RANGE
from .common import DeferredDefaultOption, Number, cli, deprecated, emit_json, json_option
from .common import scenario_default as _d
from .limits import budget_options

__all__ = [
    "rotor_modes_cmd",
    "rotor_options",
    "rotor_simulate_options",
]

#: what ``--disks`` shows as its default (``disks`` unset: :data:`SEED_ROTOR_DISKS`, or one per
#: ``--disk-positions-mm`` value)
_DISKS_DEFAULT = f"{SEED_ROTOR_DISKS}, or one per --disk-positions-mm value"

#: values of :class:`~bearingsim.dynamics.rotor.ShaftMassModel` (checked by the CLI tests; the
#: enum's module loads the rotor kernels, which ``simulate --model vsm`` does not need)
_SHAFT_MASS_MODELS = ["lumped", "distributed"]


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
    faults = click.Choice(["none", "outer", "inner", "ball"])
    opts = [
        click.option(
            "--de-bearing",
            default=None,
            show_default=_d("de_bearing"),
            help="Drive-end bearing id.",
        ),
        click.option(
            "--fe-bearing", default=None, show_default=_d("fe_bearing"), help="Fan-end bearing id."
        ),
        click.option(
            "--de-fault",
            type=faults,
            default=None,
            show_default=_d("de_fault"),
            help="Drive-end defect.",
        ),
        click.option(
            "--fe-fault",
            type=faults,
            default=None,
            show_default=_d("fe_fault"),
            help="Fan-end defect.",
        ),
        click.option(
            "--de-defect-angle-deg",
            type=Number(-360.0, 360.0, unit="deg"),
            default=None,
            show_default=_d("de_defect_angle_deg"),
            help="DE defect centre azimuth at t = 0 from +y towards +x [deg] (180 = 6 o'clock); "
            "a ball fault: the slot's spin angle at t = 0, 0 = facing the outer race, advancing "
            "as the ball spins.",
        ),
        click.option(
            "--fe-defect-angle-deg",
            type=Number(-360.0, 360.0, unit="deg"),
            default=None,
            show_default=_d("fe_defect_angle_deg"),
            help="FE defect centre azimuth at t = 0 [deg] (as --de-defect-angle-deg).",
        ),
        click.option(
            "--disks",
            type=Number(1, integer=True),
            default=None,
            show_default=_DISKS_DEFAULT,
            help="Number of rotor disks [-] (with --disk-positions-mm: their count).",
        ),
        click.option(
            "--disk-positions-mm",
            default=None,
            callback=_positions_option,
            show_default="equal spacing",
            help="Disk positions from the DE bearing, comma-separated [mm].",
        ),
        click.option(
            "--distributed-rotor/--disk-rotor",
            default=None,
            show_default="disk-rotor",
            help="Rotor mass spread along the shaft instead of on disks.",
        ),
        click.option(
            "--elements",
            "n_elements",
            type=Number(10, integer=True),
            default=None,
            show_default="automatic",
            help="Minimum number of beam elements [-].",
        ),
        click.option(
            "--shaft-mass-model",
            type=click.Choice(_SHAFT_MASS_MODELS),
            default=None,
            show_default=_d("shaft_mass_model"),
            help="Half the shaft mass at each bearing (seed ROTOR) or distributed.",
        ),
        click.option(
            "--housing-mass-kg",
            type=Number(0.0, lo_open=True, unit="kg"),
            default=None,
            show_default=_d("housing_mass_kg"),
            help="Housing mass [kg].",
        ),
        click.option(
            "--housing-stiffness-n-per-m",
            "housing_stiffness_n_per_m",
            type=Number(0.0, lo_open=True, unit="N/m"),
            default=None,
            show_default=_d("housing_stiffness_n_per_m"),
            help="Housing mount stiffness, X and Y [N/m].",
        ),
        deprecated("--housing-stiffness-n-m", "--housing-stiffness-n-per-m"),
        click.option(
            "--housing-damping-n-s-per-m",
            "housing_damping_n_s_per_m",
            type=Number(0.0, unit="N s/m"),
            default=None,
            show_default=_d("housing_damping_n_s_per_m"),
            help="Housing mount damping, X and Y [N s/m].",
        ),
        deprecated("--housing-damping-n-s-m", "--housing-damping-n-s-per-m"),
        click.option(
            "--contact-damping-n-s-per-m",
            "contact_damping_n_s_per_m",
            type=Number(0.0, unit="N s/m"),
            default=None,
            show_default=_d("contact_damping_n_s_per_m"),
            help="Damping of each ball-race contact [N s/m].",
        ),
        deprecated("--contact-damping", "--contact-damping-n-s-per-m"),
        click.option(
            "--gravity/--no-gravity",
            default=None,
            show_default=_d("gravity"),
            help="Gravity on every mass.",
        ),
        click.option(
            "--ball-inertia/--quasi-static-balls",
            "ball_inertia",
            default=None,
            show_default=_d("ball_inertia"),
            help="Balls as masses with a radial DOF (seed ROTOR) or quasi-static (massless, "
            "the two contacts in series: ~3x faster; valid while the balls' 34-42 kHz radial "
            "mode lies above the output band).",
        ),
        click.option(
            "--unbalance-kg-m",
            type=Number(0.0, unit="kg m"),
            default=None,
            show_default=_d("unbalance_kg_m"),
            help="Static rotor unbalance m e [kg m].",
        ),
        *(
            click.option(
                f"--{end}-{c}-n",
                f"{end}_{c}_n",
                type=Number(unit="N"),
                default=None,
                show_default=_d(f"{end}_{c}_n"),
                help=f"Extra constant force {c[1]} on the shaft at the {end.upper()} bearing [N] "
                "(+y up; gravity is -y).",
            )
            for end in ("de", "fe")
            for c in ("fx", "fy")
        ),
        click.option(
            "--antialias/--no-antialias",
            default=None,
            show_default="vsm/dem/tvsm: --antialias with --rig, else --no-antialias; rotor: "
            "--antialias",
            help="Oversample (4x, 2x above 24 kHz) and FIR-decimate the accelerations "
            "(rotor: on; vsm/dem/tvsm: on with --rig, else off).",
        ),
    ]
    for o in reversed(opts):
        f = o(f)
    return f


def _seed(name: str, scale: float = 1.0) -> dict[str, Any]:
    """``default``, ``cls`` and ``show_default`` of a rotor option whose default is
    ``scale * dynamics.rotor.config.<name>`` (seed ROTOR table 1), looked up when needed."""

    def text() -> str:
        from ..dynamics.rotor import config

        return format(getattr(config, name) * scale, "g")

    return {"default": None, "cls": DeferredDefaultOption, "show_default": text}


def rotor_options(f: Callable) -> Callable:
    """Options describing the rotor (shaft, armature, mesh); the command receives
    ``rotor_kw`` (keyword arguments for :func:`cwru_rotor_config`) instead."""

    @click.option(
        "--disks",
        type=Number(1, integer=True),
        default=None,
        show_default=_DISKS_DEFAULT,
        help="Number of disks [-] (with --disk-positions-mm: their count).",
    )
    @click.option(
        "--disk-positions-mm",
        default=None,
        show_default="equal spacing",
        help="Disk positions from the drive-end bearing, comma-separated [mm].",
    )
    @click.option(
        "--distributed-rotor",
        is_flag=True,
        help="Spread the rotor mass uniformly along the shaft instead of disks.",
    )
    @click.option(
        "--elements",
        type=Number(10, integer=True),
        default=None,
        show_default="automatic",
        help="Minimum number of beam elements [-].",
    )
    @click.option(
        "--shaft-mass-model",
        type=click.Choice(_SHAFT_MASS_MODELS),
        default="lumped",
        help="Half the shaft mass at each bearing (seed ROTOR) or distributed.",
    )
    @click.option(
        "--shaft-length-mm",
        type=Number(0.0, lo_open=True, unit="mm"),
        help="Shaft length between the bearings [mm].",
        **_seed("SEED_SHAFT_LENGTH_M", 1e3),
    )
    @click.option(
        "--shaft-diameter-mm",
        type=Number(0.0, lo_open=True, unit="mm"),
        help="Shaft diameter [mm].",
        **_seed("SEED_SHAFT_DIAMETER_M", 1e3),
    )
    @click.option(
        "--shaft-E-pa",
        "shaft_e",
        type=Number(*YOUNGS_MODULUS_RANGE, unit="Pa"),
        help="Young's modulus of the shaft [Pa].",
        **_seed("SEED_SHAFT_E_PA"),
    )
    @click.option(
        "--shaft-mass-kg",
        type=Number(0.0, lo_open=True, unit="kg"),
        help="Shaft mass [kg].",
        **_seed("SEED_SHAFT_MASS_KG"),
    )
    @click.option(
        "--rotor-mass-kg",
        type=Number(0.0, lo_open=True, unit="kg"),
        help="Armature (rotor) mass [kg].",
        **_seed("SEED_ROTOR_MASS_KG"),
    )
    @click.option(
        "--disk-diameter-mm",
        type=Number(0.0, lo_open=True, unit="mm"),
        help="Diameter of the disks [mm].",
        **_seed("SEED_DISK_DIAMETER_M", 1e3),
    )
    @functools.wraps(f)
    def wrapper(
        disks: int | None,
        disk_positions_mm: str | None,
        distributed_rotor: bool,
        elements: int | None,
        shaft_mass_model: str,
        shaft_length_mm: float | None,
        shaft_diameter_mm: float | None,
        shaft_e: float | None,
        shaft_mass_kg: float | None,
        rotor_mass_kg: float | None,
        disk_diameter_mm: float | None,
        **kw: Any,
    ) -> Any:
        from ..dynamics.rotor import config as rc

        def given(v: float | None, seed: float) -> float:
            return seed if v is None else v

        shaft_length_mm = given(shaft_length_mm, rc.SEED_SHAFT_LENGTH_M * 1e3)
        shaft_diameter_mm = given(shaft_diameter_mm, rc.SEED_SHAFT_DIAMETER_M * 1e3)
        disk_diameter_mm = given(disk_diameter_mm, rc.SEED_DISK_DIAMETER_M * 1e3)
        shaft = rc.Shaft(
            shaft_length_mm * 1e-3, shaft_diameter_mm * 1e-3, given(shaft_e, rc.SEED_SHAFT_E_PA),
            given(shaft_mass_kg, rc.SEED_SHAFT_MASS_KG), shaft_mass_model,
        )  # fmt: skip
        pos = _positions_mm(disk_positions_mm) or None
        if distributed_rotor and (disks is not None or pos is not None):  # they were ignored
            raise ConfigError(
                "--distributed-rotor spreads the rotor mass along the shaft: --disks and "
                "--disk-positions-mm do not apply; valid: one of the two descriptions"
            )
        if disks is None:  # unset: one per position, else the seed's
            disks = SEED_ROTOR_DISKS if pos is None else len(pos)
        elif pos is not None and len(pos) != disks:
            raise ConfigError(
                f"disks = {disks} and disk_positions_mm = [{disk_positions_mm}] ({len(pos)} "
                f"positions) disagree; valid: one position per disk (--disks {len(pos)}, or "
                "--disks unset)"
            )
        arm = rc.Armature(
            given(rotor_mass_kg, rc.SEED_ROTOR_MASS_KG),
            disk_diameter_mm * 1e-3,
            n_disks=disks,
            positions=pos,
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
    help="Bearing nodes held in x, y (simply supported) or free-free.",
)
@click.option("--rpm", type=Number(0.0, unit="r/min"), default=0.0, help="Spin speed [r/min].")
@click.option("--n-modes", type=Number(1, integer=True), default=8, help="Number of modes [-].")
@budget_options(steps=False)
@json_option
def rotor_modes_cmd(
    rotor_kw: dict[str, Any],
    supports: str,
    rpm: float,
    n_modes: int,
    as_json: bool,
    budget: Any,
) -> None:
    """Natural frequencies of the CWRU rotor alone (seed ROTOR table 2 by default)."""
    from ..dynamics.rotor.config import cwru_rotor_config
    from ..dynamics.rotor.model import rotor_modes

    if n_modes < 1:
        raise ConfigError(f"n_modes = {n_modes} is out of range; valid range [1, inf)")
    cfg = cwru_rotor_config(**rotor_kw)
    m = rotor_modes(cfg, supports=supports, speed_rpm=rpm, n_modes=n_modes, budget=budget)
    if len(m.frequency_hz) < n_modes:  # the model has fewer (its FE degrees of freedom)
        click.echo(
            f"warning: n_modes = {n_modes}: the model has {len(m.frequency_hz)} modes "
            f"({m.n_dof} FE DOF); all are listed",
            err=True,
        )
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
