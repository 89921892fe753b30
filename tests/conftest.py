"""Shared test fixtures: the ``../shared`` folder beside the repository and a CLI runner."""

from __future__ import annotations

import json
import os
from pathlib import Path

import pytest

#: ``../shared`` beside the repository root (CI clones the repo with shared/ beside it);
#: ``BEARINGSIM_SHARED`` overrides it.
SHARED = Path(os.environ.get("BEARINGSIM_SHARED", Path(__file__).resolve().parents[2] / "shared"))
CWRU = SHARED / "data" / "cwru"


class CliResult:
    """Exit code, stdout and stderr of one ``bearingsim`` invocation."""

    def __init__(self, code: int, out: str, err: str) -> None:
        self.code, self.out, self.err = code, out, err

    def json(self):
        return json.loads(self.out)


@pytest.fixture
def run_cli(capsys):
    """Run ``bearingsim ARGS`` in-process; returns a :class:`CliResult`."""
    from bearingsim.cli import main

    def _run(*args: str) -> CliResult:
        capsys.readouterr()
        try:
            main([str(a) for a in args])
            code = 0
        except SystemExit as exc:
            code = int(exc.code or 0)
        cap = capsys.readouterr()
        return CliResult(code, cap.out, cap.err)

    return _run
