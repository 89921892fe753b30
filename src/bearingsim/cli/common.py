"""Shared CLI pieces: the root group, bearing options, JSON output."""

from __future__ import annotations

import functools
import json
from collections.abc import Callable
from typing import Any

import click

from .._version import __version__
from ..catalog import resolve_bearing
from ..geometry import Bearing
from ..io.jsonable import to_jsonable


@click.group(context_settings={"help_option_names": ["-h", "--help"]})
@click.version_option(__version__, "--version", prog_name="bearingsim")
def cli() -> None:
    """bearingsim: physics-based rolling-bearing analysis (SI units inside)."""


def emit_json(obj: Any) -> None:
    """Print exactly one JSON object on stdout."""
    click.echo(json.dumps(to_jsonable(obj)))


json_option = click.option("--json", "as_json", is_flag=True, help="Print one JSON object (SI).")


def bearing_options(required: bool = True) -> Callable:
    """Decorator adding ``BEARING`` (catalogue id), ``--bearing-file``, ``--E-pa``, ``--nu``.

    The wrapped command receives ``bearing: Bearing`` instead of the raw options.
    """

    def deco(f: Callable) -> Callable:
        @click.argument("bearing_id", metavar="BEARING", required=False)
        @click.option(
            "--bearing-file",
            type=click.Path(dir_okay=False),
            default=None,
            help="User bearing TOML file (instead of a catalogue id).",
        )
        @click.option(
            "--E-pa", "e_pa", type=float, default=None, help="Override Young's modulus [Pa]."
        )
        @click.option("--nu", type=float, default=None, help="Override Poisson's ratio [-].")
        @functools.wraps(f)
        def wrapper(
            bearing_id: str | None,
            bearing_file: str | None,
            e_pa: float | None,
            nu: float | None,
            **kw: Any,
        ) -> Any:
            if bearing_id is None and bearing_file is None and not required:
                return f(bearing=None, **kw)
            b = resolve_bearing(bearing_id, bearing_file, youngs_modulus=e_pa, poisson_ratio=nu)
            return f(bearing=b, **kw)

        return wrapper

    return deco


def bearing_summary(b: Bearing) -> dict[str, Any]:
    """Plain-dict description of a bearing (SI)."""
    out = {
        "id": b.id,
        "type": b.kind,
        "n_elements": b.n_elements,
        "element_diameter_m": b.element_diameter,
        "pitch_diameter_m": b.pitch_diameter,
        "contact_angle_rad": b.contact_angle,
        "diametral_clearance_m": b.diametral_clearance,
        "youngs_modulus_pa": b.material.youngs_modulus,
        "poisson_ratio": b.material.poisson_ratio,
        "density_kg_m3": b.material.density,
        "source": b.source,
    }
    if b.kind == "ball":
        out["inner_groove_radius_m"] = b.inner_groove_radius
        out["outer_groove_radius_m"] = b.outer_groove_radius
    else:
        out["roller_length_m"] = b.roller_length
        out["inner_raceway_diameter_m"] = b.inner_raceway_diameter
        out["outer_raceway_diameter_m"] = b.outer_raceway_diameter
    return out
