"""The ``bearingsim`` command: a thin layer over the library.

Each sub-module registers its commands on :data:`cli`. Errors from bad input print one line on
stderr and exit with code 2; ``--json`` makes a command print exactly one JSON object on stdout.
"""

from __future__ import annotations

import importlib
import pkgutil
import sys

import click

from .._version import __version__
from ..errors import BearingsimError
from .common import cli

#: command modules (every module of this package but ``common``), each registering its
#: commands on ``cli`` when imported
COMMAND_MODULES = sorted(m.name for m in pkgutil.iter_modules(__path__) if m.name != "common")

for _m in COMMAND_MODULES:
    importlib.import_module(f"{__name__}.{_m}")


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


__all__ = ["cli", "main", "__version__"]
