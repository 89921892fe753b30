"""Catalogue commands: ``bearings`` and ``info``.

They run at every start of a new user's session, so this module imports nothing heavy (the
catalogue and the kinematic frequencies need neither SciPy nor Numba); keep it that way.
"""

from __future__ import annotations

import click

from ..catalog import list_bearings
from ..errors import check_range
from ..geometry import Bearing, characteristic_frequencies, check_speed_limit
from .common import Number, bearing_options, bearing_summary, cli, emit_json, json_option

__all__ = [
    "bearings_cmd",
    "info_cmd",
]


@cli.command("bearings")
@json_option
def bearings_cmd(as_json: bool) -> None:
    """List the catalogue bearings with their sources."""
    items = [bearing_summary(b) for b in list_bearings()]
    if as_json:
        emit_json({"bearings": items})
        return
    for b in items:
        click.echo(
            f"{b['id']:<16} {b['type']:<18} Z={b['n_elements']:<3} "
            f"d={b['element_diameter_m'] * 1e3:.3f} mm"
            f"  D={b['pitch_diameter_m'] * 1e3:.3f} mm  ({_short(b['source'])})"
        )


@cli.command("info")
@bearing_options()
@click.option(
    "--rpm",
    type=Number(0.0, lo_open=True, unit="r/min"),
    required=True,
    help="Shaft (inner-ring) speed [r/min].",
)
@json_option
def info_cmd(bearing: Bearing, rpm: float, as_json: bool) -> None:
    """Kinematic frequencies of BEARING at --rpm (outer ring fixed)."""
    rpm = check_speed_limit(bearing, check_range("rpm", rpm, 0.0, lo_open=True, unit="r/min"))
    kin = characteristic_frequencies(bearing, rpm / 60.0).as_dict()
    if as_json:
        emit_json(kin)
        return
    click.echo(bearing_summary(bearing)["id"] + f" at {rpm:g} r/min (shaft {rpm / 60:.4f} Hz)")
    for k in ("ftf", "bpfo", "bpfi", "bsf"):
        click.echo(f"  {k.upper():<5} {kin[k + '_hz']:10.4f} Hz   order {kin[k + '_order']:.5f}")


def _short(source: str, limit: int = 70) -> str:
    """``source`` cut at a word boundary to at most ``limit`` characters, marked by an
    ellipsis (``--json`` has the whole text)."""
    if len(source) <= limit:
        return source
    return source[: limit - 1].rsplit(" ", 1)[0].rstrip(" ,;(") + "…"
