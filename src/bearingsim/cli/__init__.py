"""The ``bearingsim`` command: a thin layer over the library.

Each sub-module registers its commands on :data:`cli`; :data:`COMMANDS` says which module holds
which command, and the module is imported only when its command runs, so ``bearingsim --help``,
``--version``, ``bearings`` and ``info`` import nothing heavy. The conventions every command
follows (output option, unit suffixes, degrees, defaults, ``--json``, exit codes, deprecated
spellings) are in ``docs/cli.md``. Errors from bad input print one line on stderr and exit with
code 2; ``--json`` makes a command print exactly one JSON object on stdout.
"""

from __future__ import annotations

import sys

import click

from .._version import __version__
from ..errors import BearingsimError
from .common import cli

#: command name -> (module that registers it, the one-line help ``bearingsim --help`` shows,
#: the first sentence of the command's docstring)
COMMANDS: dict[str, tuple[str, str]] = {
    "bearings": ("bearings", "List the catalogue bearings with their sources."),
    "info": ("bearings", "Kinematic frequencies of BEARING at --rpm (outer ring fixed)."),
    "contact": ("foundation", "Hertz contact of the most-loaded element with both raceways."),
    "load": ("foundation", "Radial load distribution over the discrete elements."),
    "stiffness": (
        "stiffness",
        "5x5 stiffness of BEARING at equilibrium and its fluctuation over the cage revolutions.",
    ),
    "simulate": (
        "dynamics",
        "Simulate a (faulty) bearing and write a self-describing netCDF file.",
    ),
    "vsm-trace": (
        "dynamics",
        "Quasi-static VSM stiffness, contact force and deformation vs cage angle.",
    ),
    "analyze": (
        "analyze",
        "Envelope analysis and diagnosis of a measured (CWRU .mat), simulated (.nc) or CSV signal.",
    ),
    "rotor-modes": (
        "rotor",
        "Natural frequencies of the CWRU rotor alone (seed ROTOR table 2 by default).",
    ),
    "ias": (
        "ias",
        "Simulate the 3-DOF IAS model of seed IAS (NU204-ECP, outer-race spall) and analyse the "
        "instantaneous angular speed.",
    ),
    "analyze-ias": (
        "ias",
        "Angle-domain analysis of a shaft angle or speed signal vs time (encoder/IAS).",
    ),
    "life": (
        "life",
        "Contact-fatigue life of BEARING by damage mechanics, beside ISO 281 and ISO/TS 16281.",
    ),
    "rig": (
        "rig",
        "Measurement chains (rigs): identify one from measured records, show one.",
    ),
    "sweep": (
        "sweep",
        "Parameter sweeps: plan, run (local Dask cluster or --scheduler), summary.",
    ),
    "reproduce": (
        "report",
        "Reproduce the published numbers: write results.json, PNG figures and report.html.",
    ),
}

cli.lazy = {name: (f"{__name__}.{mod}", text) for name, (mod, text) in COMMANDS.items()}


def main(argv: list[str] | None = None) -> None:
    """Console entry point: run the CLI, turning errors into one line and exit code 2."""
    args = sys.argv[1:] if argv is None else argv
    try:
        rv = cli.main(args=args, prog_name="bearingsim", standalone_mode=False)
    except click.exceptions.Exit as exc:
        sys.exit(exc.exit_code)
    except click.exceptions.Abort:
        click.echo("error: aborted", err=True)
        sys.exit(130)
    except click.ClickException as exc:
        msg = " ".join(exc.format_message().split())
        click.echo(f"error: {msg}", err=True)
        sys.exit(2)
    except BearingsimError as exc:
        click.echo(f"error: {' '.join(str(exc).split())}", err=True)
        sys.exit(2)
    sys.exit(rv if isinstance(rv, int) else 0)


__all__ = ["COMMANDS", "cli", "main", "__version__"]
