"""Shared test fixtures: the measured CWRU records of ``../shared/data`` (skipped cleanly when
absent) and a CLI runner."""

from __future__ import annotations

import json
import os
from pathlib import Path

import pytest

from bearingsim.io.cwru import SHARED_ENV, cwru_data_dir

# every report figure drawn by a test (and by the CLI it starts) must meet the figure standard
# (bearingsim.report.figures.save_figure refuses one that does not)
os.environ["BEARINGSIM_STRICT_FIGURES"] = "1"

#: ``<shared>/data/cwru``: ``$BEARINGSIM_SHARED/data/cwru`` when that variable is set, else the
#: ``shared/`` found beside the repository (CI clones the repo with shared/ beside it); it may
#: be missing, and the tests that need it skip (:func:`cwru_record`)
CWRU = cwru_data_dir(near=__file__)
SHARED = CWRU.parents[1]


def cwru_record(name: str) -> Path:
    """Path of a measured CWRU record: a record number (``"132"`` finds ``*_132.mat``) or a
    file name. The calling test (or fixture) skips, with the reason, when the shared data
    folder or the record is missing."""
    if not CWRU.is_dir():
        pytest.skip(
            f"shared data not available: {CWRU} does not exist (put shared/ beside the "
            f"repository or set {SHARED_ENV})"
        )
    if name.endswith(".mat"):
        found = [CWRU / name] if (CWRU / name).is_file() else []
    else:
        found = sorted(CWRU.glob(f"*_{name}.mat"))
    if not found:
        pytest.skip(f"CWRU record {name} not available in {CWRU}")
    return found[0]


@pytest.fixture
def cwru():
    """:func:`cwru_record` as a fixture: ``cwru("132")`` is the record's path (or a skip)."""
    return cwru_record


class CliResult:
    """Exit code, stdout and stderr of one ``bearingsim`` invocation."""

    def __init__(self, code: int, out: str, err: str) -> None:
        self.code, self.out, self.err = code, out, err

    def json(self):
        return json.loads(self.out)

    def refused(self, *parts: str) -> str:
        """The one error line of a refusal (exit 2, nothing on stdout, ``error: ...`` alone on
        stderr), asserted to contain each of ``parts``."""
        assert self.code == 2, (self.code, self.out, self.err)
        assert self.out == "", self.out
        lines = self.err.strip().splitlines()
        assert len(lines) == 1 and lines[0].startswith("error: "), self.err
        for p in parts:
            assert p in lines[0], (p, lines[0])
        return lines[0]


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
