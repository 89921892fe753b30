"""Reliability sweep of the ``bearingsim`` command (issue 14, "Reliability"): bad input to every
command, and SIGKILLs at random instants into every command that writes a file.

Not a test (``benchmarks/`` is not collected): a measurement printed as figures, to be run after
changes to the CLI, the readers or the writers. It runs ``python -m bearingsim`` in subprocesses
against the source tree this file belongs to (``src/`` beside ``benchmarks/``).

Part 1, bad input. The cases are generated from click's command objects (``bearingsim.cli.cli``,
every command and sub-command), so that a new option is swept without editing this file:

- every numeric option (:class:`bearingsim.cli.common.Number`) gets ``0``, ``-1``, ``1e-300``,
  ``1e30``, ``-1e30``, ``inf``, ``nan``, ``abc``, ``true``, ``""`` and a valid value; ``simulate``
  is swept once per ``--model`` (vsm, dem, tvsm, rotor, ias) with the options of that model's
  family, an option of another family once (it must be refused), and the numeric scenario keys
  that have no option through ``--set KEY=VALUE``;
- every file argument (``--bearing-file``, ``SCENARIO``, ``SWEEP.toml``, ``FILE``, ``DATASET``):
  a missing file, a directory, an empty file, random bytes, non-UTF-8 text, a truncated valid
  file, and what is wrong in its own terms (a bearing with a 1e30 m groove radius, a scenario or
  sweep with ``rpm = true``, a dataset whose metadata or status is cut);
- every output (``-o/--output``, ``--plot``, ``--plot-curve``): a path under ``/proc`` and
  ``/sys``, a parent that is a file, an existing directory where a file goes (or a file where a
  directory goes), ``/dev/null``, and a missing folder (valid: it is created). The sweep runs as
  root, so permission bits would not stop a write: paths under ``/proc`` and ``/sys`` stand for
  read-only places;
- every choice option: a value not in the list and ``""``; every text option: ``""``, ``abc``,
  ``1e30``, ``nan``, ``-1`` (and the ones with a grammar, ``--set``, ``--band-hz``,
  ``--ball-errors-deg``, ``--disk-positions-mm``, ``--scheduler``, a few more).

Each case runs in its own directory, with ``--json`` where the command has it, the runs kept
short (``--duration-s`` small, one cage revolution, the coarse FE mesh), in a pool of ``--jobs``
subprocesses with a time limit of 120 s. Its outcome is one of

========================  =====================================================================
``ok``                    exit 0, stdout one JSON object whose numbers are finite (a ``null``
                          where the command's valid run has a number counts as NaN: the CLI
                          writes non-finite floats as ``null``), output files readable and
                          finite where the valid run's are
``refused``               exit 2 and exactly one line on stderr, ``error: ...``, nothing written
``traceback``             "Traceback" on stderr, an exit code other than 0 and 2, or more than
                          one ``error:`` line
``hang``                  not finished within the time limit (killed)
``leftover``              a refused or failed run left a file (its output, a temporary, a
                          folder) in its directory, or a successful one a hidden temporary
``nan``                   exit 0 with non-finite numbers (JSON or output file)
``accepted-absurd``       exit 0 for a value the option's own valid range excludes, or for
                          1e30 in a physical quantity (speed, load, length, mass, stiffness,
                          ...): the case was generated with an expected refusal
``bad-output``            exit 0 or 2 but the streams break ``docs/cli.md``: stderr lines other
                          than ``warning:``/``error:``, exit 2 without an ``error:`` line,
                          stdout not one JSON object with ``--json``
========================  =====================================================================

Part 2, kills: ``--kills`` SIGKILLs at seeded random instants (half uniform over the run, half in
its last 20 %, where the output is written) into ``simulate -o`` (vsm, dem, rotor), ``ias -o
--plot``, ``stiffness -o``, ``life -o`` and ``sweep run`` (20 DEM runs, a fresh dataset, killed,
then resumed with the same command; the whole process group is killed, or the client alone,
leaving its workers; 3 kills in 4 at a uniform instant after the dataset appears, while runs
are committed, 1 in 4 from the start). Half of the single-file trials write over an existing
output. After each kill the output must be absent or complete
(``bearingsim.results.load_result``; a PNG must end with its IEND chunk); the same command is
then run to the end, and must succeed, write a readable output and leave no temporary
(``.NAME.*``) beside it. A resumed sweep must end with every run ok, no run committed before the
kill computed again, and data equal to an uninterrupted sweep and to ``simulate`` of the same
scenario.

Run (about 20 min on 2 cores: 14 min of cases, 6 of kills)::

    PYTHONPATH=src python benchmarks/reliability_sweep.py --json relsweep.json

Options: ``--seed``, ``--cases N`` (a seeded subsample of the cases), ``--kills N``, ``--jobs``,
``--commands simulate,life`` (only these), ``--keep DIR`` (keep the directories of the cases
that are neither ok nor refused), ``--json FILE`` (every case and figure, written atomically).
"""

from __future__ import annotations

import argparse
import concurrent.futures
import contextlib
import dataclasses
import json
import math
import os
import random
import re
import shlex
import shutil
import signal
import subprocess
import sys
import tempfile
import threading
import time
from pathlib import Path
from typing import Any

ROOT = Path(__file__).resolve().parents[1]
SRC = ROOT / "src"
sys.path.insert(0, str(SRC))  # the tree this file belongs to, also in the subprocesses

import click  # noqa: E402
from tqdm import tqdm  # noqa: E402

from bearingsim.cli import cli  # noqa: E402
from bearingsim.cli.common import Number  # noqa: E402

#: time limit of one case [s]; a case still running is a hang
TIMEOUT_S = 120.0
#: the bad values of every numeric option (the valid value is added per option)
BAD_NUMBERS = ("0", "-1", "1e-300", "1e30", "-1e30", "inf", "nan", "abc", "true", "")
#: text options: values that are not what the option wants (or are, by accident)
BAD_TEXT = ("", "abc", "1e30", "nan", "-1")
#: options whose huge values are a legitimate "no limit" (budgets, time-outs, caps)
HUGE_OK = {"--max-memory-gb", "--max-steps", "--connect-timeout-s", "--timing-duration-s"}
#: the classes, in the order of the table
CLASSES = (
    "ok",
    "refused",
    "traceback",
    "hang",
    "leftover",
    "nan",
    "accepted-absurd",
    "bad-output",
)
OUTPUT_OPTIONS = ("--output", "--plot", "--plot-curve")
#: JSON keys that are null by design (not computed, not detected): a fixed --band-hz has no
#: kurtogram, a CSV with a per-sample rpm column no single rpm, --stop initiation no spall (nor
#: its hours with --rpm), a healthy IAS run (or a spall outside the load zone) no spall event,
#: --timing-runs 0 times nothing, a given --runs-per-task needs no run-time estimate
KNOWN_NULLS = {
    ("analyze", ".kurtosis"),
    ("analyze", ".rpm"),
    ("ias", ".fault_order_measured"),
    ("ias", ".spall_crossing_angle_rad"),
    ("ias", ".spall_width_estimate_m"),
    ("life", ".hours_spall"),
    ("sweep plan", ".compute_s_per_run"),
    ("sweep plan", ".compute_s_total"),
    ("sweep plan", ".wall_s"),
    ("sweep run", ".estimate_s"),
}
#: simulate: the models swept, with the options of a short run
SIMULATE_MODELS = {
    "vsm": ["--duration-s", "0.05", "--fs-hz", "12000"],
    "dem": ["--duration-s", "0.05", "--fs-hz", "12000"],
    "tvsm": ["--duration-s", "0.05", "--fs-hz", "12000"],
    "rotor": ["--duration-s", "0.05"],
    "ias": ["--duration-s", "0.1"],
}


# ----------------------------------------------------------------------------- the cases
@dataclasses.dataclass
class Case:
    """One run of the command: ``argv`` after ``bearingsim`` (``{fx}`` = the fixtures folder),
    run in a fresh directory prepared by ``setup``."""

    id: int
    command: str  # table row: "contact", "simulate --model dem", "sweep run"
    what: str  # what is bad: "--rpm=1e30", "SCENARIO=garbage", "-o=/proc"
    argv: list[str]
    expect: str | None  # "ok", "refuse" or None (either is fine)
    setup: list[tuple[str, str, str]] = dataclasses.field(default_factory=list)
    base: bool = False  # the command's valid run (reference for NaN and output checks)
    outputs: list[str] = dataclasses.field(default_factory=list)  # files to check on exit 0
    # results
    cls: str = ""
    code: int | None = None
    wall_s: float = 0.0
    stderr: str = ""
    note: str = ""
    nulls: frozenset[str] = frozenset()
    numbers: frozenset[str] = frozenset()
    nonfinite_files: dict[str, list[str]] = dataclasses.field(default_factory=dict)


def _walk() -> list[tuple[str, click.Command]]:
    """``(path, command)`` of every command and sub-command of ``bearingsim`` (loaded)."""
    ctx = click.Context(cli)
    out = []
    for name in cli.list_commands(ctx):
        cmd = cli.get_command(ctx, name)
        if isinstance(cmd, click.Group):
            out += [(f"{name} {sub}", cmd.get_command(ctx, sub)) for sub in sorted(cmd.commands)]
        else:
            out.append((name, cmd))
    return out


#: the valid run of each command: (positional arguments, options); every case changes one thing
BASE: dict[str, tuple[list[str], list[tuple[str, str | None]]]] = {
    "bearings": ([], []),
    "simulate": ([], []),  # per model: SIMULATE_MODELS
    "info": (["6205"], [("--rpm", "1000")]),
    "contact": (["6205"], [("--radial-load-n", "1000")]),
    "load": (["6205"], [("--fy-n", "1000")]),
    "stiffness": (
        ["6205"],
        [("--fy-n", "1000"), ("--cage-revs", "1"), ("--points-per-rev", "36"), ("-o", "out.nc")],
    ),
    "vsm-trace": ([], [("--cage-revs", "0.1"), ("-o", "out.csv")]),
    "analyze": (["{fx}/signal.nc"], []),
    "rotor-modes": ([], []),
    "ias": ([], [("--duration-s", "0.5"), ("-o", "out.nc")]),
    "analyze-ias": (["{fx}/ias.nc"], []),
    "life": (
        ["6205"],
        [
            ("--radial-load-n", "3000"),
            ("--mesh", "coarse"),
            ("--stop", "initiation"),
            ("-o", "out.nc"),
        ],
    ),
    "sweep plan": (
        ["{fx}/spec.toml"],
        [("--timing-runs", "1"), ("--timing-duration-s", "0.05"), ("--workers", "1")],
    ),
    "sweep run": (["{fx}/spec.toml"], [("-o", "store"), ("--workers", "1")]),
    "sweep summary": (["store"], []),
    "reproduce": ([], [("--quick", None), ("--section", "foundation"), ("-o", "rep")]),
}
#: commands swept for their outputs only (a valid run is too slow for a sweep)
OUTPUTS_ONLY = {"reproduce"}
#: files each command's valid run needs in its directory
BASE_SETUP = {"sweep summary": [("copytree", "{fx}/store", "store")]}
#: what each positional argument is (file kinds: see ``_file_variants``)
ARGUMENT_KIND = {
    "bearing_id": "catalogue",
    "scenario_file": "scenario",
    "scenario": "ias_scenario",
    "inputs": "signal",
    "file": "shaft",
    "spec_file": "spec",
    "dataset": "store",
}
#: a valid value of the numeric options whose default is not one (None) or is given by the base
VALID: dict[str, str] = {
    "--E-pa": "2.07e11",
    "--nu": "0.3",
    "--rpm": "1000",
    "--ball-load-n": "100",
    "--radial-load-n": "1000",
    "--clearance-m": "6e-6",
    "--stiffness-n-per-m1.5": "8e9",
    "--retention-factor": "0.5",
    "--load-zone-deg": "90",
    "--mass-kg": "1.0",
    "--dt-s": "1e-6",
    "--elements": "20",
    "--ball": "1",
    "--max-steps": "1e9",
    "--max-memory-gb": "4",
    "--element-size-um": "30",
    "--kappa": "11.1",
    "--sigma-t-pa": "5.98e9",
    "--skip-s": "0.02",
    "--samples-per-rev": "256",
    "--torque-n-m": "9.54",
    "--spall-width-m": "0.001",
    "--timing-runs": "1",
    "--runs-per-task": "1",
    "--workers": "1",
    "--shaft-length-mm": "203.2",
    "--shaft-diameter-mm": "12.53",
    "--shaft-E-pa": "2.06e11",
    "--shaft-mass-kg": "0.68",
    "--rotor-mass-kg": "1.361",
    "--disk-diameter-mm": "46.07",
}
#: per command (prefix) overrides of VALID
VALID_BY_COMMAND: dict[tuple[str, str], str] = {
    ("analyze", "--rpm"): "1750",
    ("analyze", "--fs-hz"): "12000",
    ("analyze-ias", "--skip-s"): "0.05",
    ("simulate --model rotor", "--fs-hz"): "48000",
    ("simulate --model ias", "--fs-hz"): "50000",
    ("simulate --model ias", "--duration-s"): "0.1",
    ("simulate --model rotor", "--dt-s"): "2e-6",
    ("ias", "--fs-hz"): "50000",
    ("ias", "--skip-s"): "0.05",
    ("life", "--max-steps"): "20000",
    ("life", "--radial-load-n"): "3000",
    ("vsm-trace", "--cage-revs"): "0.1",
}
#: text options with a grammar: their bad (and valid) values; None = expectation unknown
TEXT_VALUES: dict[str, list[tuple[str, str | None]]] = {
    "--bearing": [("nonexistent-id", "refuse"), ("", "refuse"), ("../../etc/passwd", "refuse")],
    "--de-bearing": [("nonexistent-id", "refuse"), ("", "refuse")],
    "--fe-bearing": [("nonexistent-id", "refuse"), ("", "refuse")],
    "--disk-positions-mm": [
        ("abc", "refuse"),
        ("", None),
        ("1e30", "refuse"),
        ("nan", "refuse"),
        ("-1", "refuse"),
        ("inf,inf", "refuse"),
        ("50,50", None),
        ("50,100,150", "ok"),
    ],
    "--ball-errors-deg": [
        ("abc", "refuse"),
        ("", "refuse"),
        ("1e30", "refuse"),
        ("nan", "refuse"),
        (",".join(["nan"] * 9), "refuse"),
        (",".join(["1e30"] * 9), "refuse"),
        (",".join(["0.1"] * 9), "ok"),
    ],
    "--band-hz": [
        ("abc", "refuse"),
        ("", "refuse"),
        ("1e30,2e30", "refuse"),
        ("nan,nan", "refuse"),
        ("-1,5", "refuse"),
        ("5000,1000", "refuse"),
        ("inf,inf", "refuse"),
        ("2000,4000", "ok"),
    ],
    "--channel": [("zz", "refuse"), ("", "refuse"), ("x", "ok")],
    "--label": [("zz", "refuse"), ("", None), ("fault", "ok")],
    "--scheduler": [("abc", "refuse"), ("", "refuse"), ("tcp://127.0.0.1:1", "refuse")],
    "--set": [
        ("rpm=1e30", "refuse"),
        ("rpm=nan", "refuse"),
        ("rpm=inf", "refuse"),
        ("rpm=true", "refuse"),
        ("rpm=abc", "refuse"),
        ("rpm=", "refuse"),
        ("=1", "refuse"),
        ("nokey=1", "refuse"),
        ("rpm", "refuse"),
        ("rpm=[1,2]", "refuse"),
        ("rpm={a=1}", "refuse"),
        ("solver=rk4", "ok"),
    ],
}
#: file variants (name in the fixtures folder) by kind of file argument
FILE_KINDS = {
    "bearing": ("bearing.toml", [("groove1e30.toml", "a bearing with a 1e30 m groove radius")]),
    "roller": ("roller.toml", [("roller1e30.toml", "a roller 1e30 m long")]),
    "scenario": ("scenario.toml", [("scenario_rpm_true.toml", "rpm = true")]),
    "ias_scenario": ("ias_scenario.toml", [("ias_rpm_true.toml", "rpm = true")]),
    "spec": ("spec.toml", [("spec_rpm_true.toml", "rpm = true in [base]")]),
    "signal": ("signal.nc", []),
    "shaft": ("shaft.csv", []),
}


def _valid(command: str, opt: str, param: click.Parameter) -> str | None:
    """A valid value of option ``opt`` of ``command``: the tables above, else the option's
    default, else the scenario default of the key it sets (``simulate``, ``vsm-trace``,
    ``ias``)."""
    import dataclasses as dc

    from bearingsim.config import family

    for (prefix, o), v in VALID_BY_COMMAND.items():
        if o == opt and command.startswith(prefix):
            return v
    if opt in VALID:
        return VALID[opt]
    model = {"vsm-trace": "vsm", "ias": "ias"}.get(command, command.rsplit(" ", 1)[-1])
    with contextlib.suppress(Exception):
        fields = {f.name: f.default for f in dc.fields(family(model))}
        v = fields.get(param.name)
        if isinstance(v, int | float) and not isinstance(v, bool):
            return repr(v)
    d = param.default
    if d is None or callable(d) or isinstance(d, tuple | list | bool):
        return None
    return str(d)


_RANGE = re.compile(r"^\s*([\[(])\s*([^,]*?)\s*,\s*([^\])]*?)\s*([\])])")


def _bounds(valid: str) -> tuple[float | None, bool, float | None, bool]:
    """``(lo, lo_open, hi, hi_open)`` of a Number's range text (``None``: in words)."""
    m = _RANGE.match(valid)
    if not m:
        return None, False, None, False

    def num(s: str) -> float | None:
        try:
            return float(s)
        except ValueError:
            return None

    return num(m[2]), m[1] == "(", num(m[3]), m[4] == ")"


def _expect_number(opt: str, ptype: Number, value: str) -> str | None:
    """``"refuse"`` when the option must refuse ``value``, else ``None`` (can't tell)."""
    if value in ("abc", "true", "", "nan", "inf"):
        return "refuse"
    x = float(value)
    if ptype.integer:
        try:
            int(value)
        except ValueError:
            return "refuse"
    lo, lo_open, hi, hi_open = _bounds(ptype.valid)
    if lo is not None and (x < lo or (x == lo and lo_open)):
        return "refuse"
    if hi is not None and (x > hi or (x == hi and hi_open)):
        return "refuse"
    if abs(x) >= 1e30 and opt not in HUGE_OK:
        return "refuse"  # 1e30 r/min, N, m, kg, Pa, ...: physically absurd
    return None


class Builder:
    """Builds the cases of one command from its valid run (positionals, options)."""

    def __init__(
        self,
        cases: list[Case],
        command: str,
        path: str,
        cmd: click.Command,
        pos: list[str],
        opts: list[tuple[str, str | None]],
        setup=(),
    ) -> None:
        self.cases, self.command, self.path, self.cmd = cases, command, path, cmd
        self.pos, self.opts, self.setup = list(pos), list(opts), list(setup)
        if any(p.name == "as_json" for p in cmd.params):
            self.opts.append(("--json", None))
        self.arguments = [p for p in cmd.params if isinstance(p, click.Argument)]

    def argv(self, pos: list[str], opts: list[tuple[str, str | None]]) -> list[str]:
        out = self.path.split() + list(pos)
        for o, v in opts:
            out += [o] if v is None else [o, v]
        return out

    def add(
        self,
        what: str,
        expect: str | None,
        *,
        set_opt=None,
        drop=(),
        pos=None,
        setup=(),
        base=False,
        extra=(),
    ) -> None:
        """A case: the valid run with ``set_opt = (option, value)`` (replacing the option's
        value when the valid run gives it), without the options ``drop``, with positionals
        ``pos`` (default: the valid run's)."""
        opts = [(o, v) for o, v in self.opts if o not in drop]
        if set_opt is not None:
            o, v = set_opt
            names = self._names(o)
            i = next((k for k, (oo, _) in enumerate(opts) if oo in names), None)
            if i is None:
                opts.insert(len(opts) - bool(opts and opts[-1][0] == "--json"), (o, v))
            else:
                opts[i] = (o, v)
        opts += list(extra)
        argv = self.argv(self.pos if pos is None else pos, opts)
        outputs = [v for o, v in opts if o in ("-o", "--output", "--plot", "--plot-curve") and v]
        self.cases.append(
            Case(
                len(self.cases),
                self.command,
                what,
                argv,
                expect,
                [*self.setup, *setup],
                base,
                outputs,
            )
        )

    def _names(self, opt: str) -> set[str]:
        for p in self.cmd.params:
            if isinstance(p, click.Option) and opt in p.opts:
                return set(p.opts)
        return {opt}


def _option_label(p: click.Option) -> str:
    return max(p.opts, key=len)


def _file_variants(kind: str) -> list[tuple[str, str, str | None]]:
    """``(path, what, expect)`` for a file argument of ``kind`` (``{fx}`` = fixtures)."""
    if kind == "store":
        return [
            ("missing-store", "missing", "refuse"),
            ("{fx}/afile", "a file, not a directory", "refuse"),
            ("{fx}/emptydir", "an empty directory", "refuse"),
            ("{fx}/garbagedir", "a directory of random files", "refuse"),
            ("{fx}/store_cut_meta", "a dataset whose .zmetadata is cut", "refuse"),
            ("{fx}/store_bad_status", "a dataset whose status chunk is garbage", "refuse"),
            ("{fx}/store_no_attrs", "a dataset without .zattrs", "refuse"),
        ]
    if kind == "signal":
        out = [
            ("{fx}/record_12k.mat", "valid CWRU-like .mat", "ok"),
            ("{fx}/signal.csv", "valid CSV", "ok"),
        ]
        for ext in ("nc", "mat", "csv"):
            out += _generic(f"x.{ext}", ext)
        out.append(("{fx}/garbage.bin", "unknown suffix", "refuse"))
        return out
    if kind == "shaft":
        return (
            _generic("x.csv", "csv")
            + _generic("x.nc", "nc")
            + [
                ("{fx}/ias.nc", "valid IAS result", "ok"),
                ("{fx}/signal.nc", "a ring result, not IAS", "refuse"),
                ("{fx}/shaft_nokind.csv", "no header naming the kind", "refuse"),
            ]
        )
    valid, specials = FILE_KINDS[kind]
    ext = valid.rsplit(".", 1)[1]
    out = _generic(f"x.{ext}", ext, trunc=f"{{fx}}/trunc_{valid}")
    if kind in ("scenario", "ias_scenario", "spec"):  # every key optional: the defaults
        out = [(v, w, None if w.startswith("empty") else e) for v, w, e in out]
    out += [(f"{{fx}}/{name}", what, "refuse") for name, what in specials]
    return out


def _generic(name: str, ext: str, trunc: str | None = None) -> list[tuple[str, str, str]]:
    return [
        (f"missing/{name}", f"missing .{ext}", "refuse"),
        (f"{{fx}}/dir.{ext}", f"a directory named .{ext}", "refuse"),
        (f"{{fx}}/empty.{ext}", f"empty .{ext}", "refuse"),
        (f"{{fx}}/garbage.{ext}", f"random bytes .{ext}", "refuse"),
        (f"{{fx}}/nonutf8.{ext}", f"non-UTF-8 text .{ext}", "refuse"),
        (trunc or f"{{fx}}/trunc.{ext}", f"truncated valid .{ext}", "refuse"),
    ]


def _output_variants(p: click.Option, ext: str) -> list[tuple[str, str, str | None]]:
    directory = isinstance(p.type, click.Path) and p.type.dir_okay
    if directory:
        return [
            ("/proc/x/y", "under /proc", "refuse"),
            ("/sys/y", "under /sys (read-only)", "refuse"),
            ("afile/y", "a parent that is a file", "refuse"),
            ("afile", "an existing file where a directory goes", "refuse"),
            ("/dev/null", "a device", "refuse"),
        ]
    return [
        (f"/proc/x/y.{ext}", "under /proc", "refuse"),
        (f"/sys/y.{ext}", "under /sys (read-only)", "refuse"),
        (f"afile/y.{ext}", "a parent that is a file", "refuse"),
        ("adir", "an existing directory where a file goes", "refuse"),
        ("/dev/null", "a device", "refuse"),
        (f"new/sub/y.{ext}", "missing folders (created)", "ok"),
    ]


def _set_keys(model: str, covered: set[str]) -> list[str]:
    """Numeric scenario keys of ``model``'s family that no option of ``simulate`` sets."""
    import typing

    from bearingsim.config import family

    fam = family(model)
    hints = typing.get_type_hints(fam)
    out = []
    for k in fam.KEYS:
        t = str(hints.get(k, ""))
        if k not in covered and ("float" in t or "int" in t) and "str" not in t:
            out.append(k)
    return out


def generate() -> tuple[list[Case], list[str]]:
    """Every case of every command, and notes on what could not be swept."""
    from bearingsim.config import family

    cases: list[Case] = []
    notes: list[str] = []
    for path, cmd in _walk():
        if path not in BASE:
            notes.append(f"{path}: no valid run known; only its --help is run")
            b = Builder(cases, path, path, cmd, [], [("--help", None)])
            b.add("--help", "ok", base=True)
            continue
        pos, opts = BASE[path]
        if path == "simulate":
            for model, extra in SIMULATE_MODELS.items():
                mopts = [("--model", model)] + [
                    (extra[i], extra[i + 1]) for i in range(0, len(extra), 2)
                ]
                mopts.append(("-o", "out.nc"))
                b = Builder(cases, f"simulate --model {model}", path, cmd, pos, mopts)
                keys = set(family(model).KEYS)
                _sweep_command(b, notes, keys)
                covered = {p.name for p in cmd.params}
                for key in _set_keys(model, covered):
                    for v in BAD_NUMBERS:
                        exp = (
                            "refuse"
                            if v in ("nan", "inf", "abc", "true", "", "1e30", "-1e30")
                            else None
                        )
                        b.add(f"--set {key}={v}", exp, set_opt=("--set", f"{key}={v}"))
            continue
        b = Builder(cases, path, path, cmd, pos, opts, BASE_SETUP.get(path, ()))
        _sweep_command(b, notes, None)
    return cases, notes


def _sweep_command(b: Builder, notes: list[str], family_keys: set[str] | None) -> None:
    """The cases of one command (``family_keys``: simulate's keys of the model swept)."""
    outputs_only = b.command in OUTPUTS_ONLY
    if not outputs_only:
        b.add("valid run", "ok", base=True)
    for p in b.cmd.params:
        if isinstance(p, click.Argument):
            if outputs_only:
                continue
            _argument_cases(b, p)
            continue
        if not isinstance(p, click.Option) or p.hidden or p.name in ("as_json", "help"):
            continue
        label = _option_label(p)
        if isinstance(p.type, click.Path) and any(o in OUTPUT_OPTIONS for o in p.opts):
            ext = {"--plot": "png", "--plot-curve": "png"}.get(label, _out_ext(b))
            for value, what, exp in _output_variants(p, ext):
                b.add(f"{label}={what}", exp, set_opt=(p.opts[0], value))
            continue
        if outputs_only:
            continue
        if label == "--bearing-file":
            rollers = ("ias", "simulate --model ias", "analyze-ias")
            kind = "roller" if b.command in rollers else "bearing"
            if family_keys is not None and "bearing_file" not in family_keys:
                b.add(
                    "--bearing-file (another model's option)",
                    "refuse",
                    set_opt=(label, "{fx}/bearing.toml"),
                )
                continue
            drop = [a for a in b.pos if a == "6205"]
            pos = [a for a in b.pos if a not in drop]
            b.add(
                "--bearing-file=valid",
                "ok",
                set_opt=(label, f"{{fx}}/{FILE_KINDS[kind][0]}"),
                pos=pos,
            )
            for value, what, exp in _file_variants(kind):
                b.add(f"--bearing-file={what}", exp, set_opt=(label, value), pos=pos)
            continue
        if (
            family_keys is not None
            and p.name not in family_keys
            and p.name
            not in (
                "max_steps",
                "max_memory_gb",
                "set_keys",
                "allow_overload",
                "output",
                "model",
            )
        ):
            if not p.is_flag:
                v = _valid(b.command, label, p) or "1"
                if isinstance(p.type, click.Choice):
                    v = str(p.type.choices[-1])
                b.add(f"{label} (another model's option)", "refuse", set_opt=(label, v))
            continue
        if p.is_flag or isinstance(p.type, click.types.BoolParamType):
            continue
        if isinstance(p.type, Number):
            drop = ["--radial-load-n"] if label == "--ball-load-n" else []
            good = next((v for o, v in b.opts if o in p.opts), None) or _valid(b.command, label, p)
            if good is None:
                notes.append(f"{b.command} {label}: no valid value known")
            else:
                b.add(f"{label}={good} (valid)", "ok", set_opt=(label, good), drop=drop)
            for v in BAD_NUMBERS:
                b.add(
                    f"{label}={v}", _expect_number(label, p.type, v), set_opt=(label, v), drop=drop
                )
            continue
        if isinstance(p.type, click.Choice):
            if label == "--model":
                continue
            for v in ("bogus", ""):
                b.add(f"{label}={v!r}", "refuse", set_opt=(label, v))
            continue
        values = TEXT_VALUES.get(label, [(v, None) for v in BAD_TEXT])
        for v, exp in values:
            extra = []
            if label == "--scheduler":
                extra = [("--connect-timeout-s", "2")]
            b.add(f"{label}={v!r}", exp, set_opt=(label, v), extra=extra)


def _out_ext(b: Builder) -> str:
    return {"vsm-trace": "csv"}.get(b.command, "nc")


def _argument_cases(b: Builder, p: click.Argument) -> None:
    kind = ARGUMENT_KIND.get(p.name)
    if kind is None:
        return
    i = len([q for q in b.arguments[: b.arguments.index(p)]])
    if kind == "catalogue":
        for v, exp in (
            ("nonexistent-id", "refuse"),
            ("", "refuse"),
            ("6205-cwru", "ok"),
            ("NU204-ECP", None),
        ):
            b.add(f"BEARING={v!r}", exp, pos=_replace(b.pos, i, v))
        return
    if kind in ("scenario", "ias_scenario"):
        if b.command.startswith("simulate") and b.command != "simulate --model vsm":
            return  # the scenario file is read before the model: swept once
        valid = "{fx}/" + FILE_KINDS[kind][0]
        b.add("SCENARIO=valid", "ok", pos=[valid])
        for value, what, exp in _file_variants(kind):
            b.add(f"SCENARIO={what}", exp, pos=[value])
        return
    name = p.human_readable_name
    for value, what, exp in _file_variants(kind):
        b.add(f"{name}={what}", exp, pos=_replace(b.pos, i, value))


def _replace(pos: list[str], i: int, v: str) -> list[str]:
    out = list(pos)
    if i < len(out):
        out[i] = v
    else:
        out.append(v)
    return out


# ----------------------------------------------------------------------------- fixtures
def _run_cli(argv: list[str], cwd: Path, env: dict[str, str], timeout: float = 300.0):
    r = subprocess.run(
        [sys.executable, "-m", "bearingsim", *argv],
        cwd=cwd,
        env=env,
        capture_output=True,
        text=True,
        timeout=timeout,
    )
    if r.returncode != 0:
        raise RuntimeError(f"fixture: bearingsim {' '.join(argv)} failed:\n{r.stderr}")
    return r


def make_fixtures(fx: Path, env: dict[str, str], seed: int) -> None:
    """The input files of the cases (valid and damaged) in ``fx``."""
    import numpy as np

    rng = random.Random(seed)
    fx.mkdir(parents=True)
    cat = SRC / "bearingsim" / "catalog"
    bearing = (cat / "6205.toml").read_text()
    roller = (cat / "NU204-ECP.toml").read_text()
    (fx / "bearing.toml").write_text(bearing)
    (fx / "roller.toml").write_text(roller)
    (fx / "groove1e30.toml").write_text(
        re.sub(r"outer_groove_radius_m = .*", "outer_groove_radius_m = 1e30", bearing)
    )
    (fx / "roller1e30.toml").write_text(
        re.sub(r"roller_length_m = .*", "roller_length_m = 1e30", roller)
    )
    scenario = 'model = "vsm"\nfault = "outer"\nrpm = 1750.0\nduration_s = 0.05\nfs_hz = 12000.0\n'
    (fx / "scenario.toml").write_text(scenario)
    (fx / "scenario_rpm_true.toml").write_text(scenario.replace("rpm = 1750.0", "rpm = true"))
    ias = "spall_width_m = 0.001\nrpm = 1000.0\nduration_s = 0.2\n"
    (fx / "ias_scenario.toml").write_text(ias)
    (fx / "ias_rpm_true.toml").write_text(ias.replace("rpm = 1000.0", "rpm = true"))
    spec = (
        '[sweep]\nchannels = ["acc_x", "acc_y"]\nlabel = "fault"\n\n'
        '[base]\nmodel = "dem"\nduration_s = 0.05\nfs_hz = 12000.0\nrpm = 1750.0\n\n'
        '[axes]\nfault = ["outer", "inner"]\n'
    )
    (fx / "spec.toml").write_text(spec)
    (fx / "spec_rpm_true.toml").write_text(spec.replace("rpm = 1750.0", "rpm = true"))
    (fx / "spec20.toml").write_text(
        '[sweep]\nchannels = ["acc_x", "acc_y"]\nlabel = "fault"\n\n'
        '[base]\nmodel = "dem"\nduration_s = 4.0\nfs_hz = 48000.0\n\n'
        '[axes]\nfault = ["outer", "inner"]\nrpm = { start = 1700.0, stop = 1800.0, num = 10 }\n'
    )
    # results and signals
    _run_cli(
        [
            "simulate",
            "--model",
            "dem",
            "--fault",
            "outer",
            "--duration-s",
            "1",
            "--fs-hz",
            "12000",
            "-o",
            str(fx / "signal.nc"),
        ],
        fx,
        env,
    )
    _run_cli(["ias", "--duration-s", "0.5", "-o", str(fx / "ias.nc")], fx, env)
    from bearingsim.results import load_result

    res = load_result(fx / "signal.nc")
    acc = res["acc_y"]
    t = res.time
    with open(fx / "signal.csv", "w") as fh:
        fh.write("time_s,acc_y,rpm\n")
        for a, b in zip(t, acc, strict=True):
            fh.write(f"{a:.9g},{b:.9g},1750\n")
    import scipy.io

    scipy.io.savemat(
        fx / "record_12k.mat",
        {"X097_DE_time": (acc / 9.80665)[:, None], "X097RPM": np.array([[1750.0]])},
    )
    ts = np.arange(0, 1.0, 1e-4)
    ang = 2 * np.pi * 20 * ts + 0.01 * np.sin(2 * np.pi * 87 * ts)
    with open(fx / "shaft.csv", "w") as fh:
        fh.write("time_s,angle_rad\n")
        fh.writelines(f"{a:.9g},{b:.12g}\n" for a, b in zip(ts, ang, strict=True))
    with open(fx / "shaft_nokind.csv", "w") as fh:
        fh.writelines(f"{a:.9g},{b:.12g}\n" for a, b in zip(ts, ang, strict=True))
    # damaged files of every kind
    valid = {
        "toml": fx / "bearing.toml",
        "nc": fx / "signal.nc",
        "mat": fx / "record_12k.mat",
        "csv": fx / "signal.csv",
    }
    for ext, src in valid.items():
        (fx / f"dir.{ext}").mkdir()
        (fx / f"empty.{ext}").write_bytes(b"")
        (fx / f"garbage.{ext}").write_bytes(rng.randbytes(4096))
        (fx / f"nonutf8.{ext}").write_bytes(b"rpm = 1750\n\xff\xfe\xfa caf\xe9 = 1\n")
        data = src.read_bytes()
        (fx / f"trunc.{ext}").write_bytes(data[: len(data) // 2])
    (fx / "garbage.bin").write_bytes(rng.randbytes(4096))
    for name in ("bearing.toml", "roller.toml", "scenario.toml", "ias_scenario.toml", "spec.toml"):
        text = (fx / name).read_text()  # cut after a key's "=": not TOML any more
        (fx / f"trunc_{name}").write_text(text[: text.index("=", len(text) // 2) + 1])
    (fx / "afile").write_text("a file\n")
    (fx / "emptydir").mkdir()
    g = fx / "garbagedir"
    g.mkdir()
    for i, name in enumerate((".zattrs", ".zmetadata", "status", "x")):
        (g / name).write_bytes(rng.randbytes(100 + 50 * i))
    # a sweep dataset, and damaged copies
    _run_cli(
        ["sweep", "run", str(fx / "spec.toml"), "-o", str(fx / "store"), "--workers", "1"], fx, env
    )
    shutil.copytree(fx / "store", fx / "store_cut_meta")
    zm = fx / "store_cut_meta" / ".zmetadata"
    zm.write_bytes(zm.read_bytes()[: zm.stat().st_size // 2])
    shutil.copytree(fx / "store", fx / "store_bad_status")
    for f in (fx / "store_bad_status" / "status").iterdir():
        if not f.name.startswith("."):
            f.write_bytes(rng.randbytes(7))
    shutil.copytree(fx / "store", fx / "store_no_attrs")
    (fx / "store_no_attrs" / ".zattrs").unlink()


def _snapshot(root: Path) -> dict[str, tuple[int, int]]:
    out = {}
    for dirpath, dirnames, filenames in os.walk(root):
        for n in dirnames + filenames:
            p = Path(dirpath) / n
            with contextlib.suppress(OSError):
                st = p.lstat()
                out[str(p.relative_to(root))] = (st.st_size, st.st_mtime_ns)
    return out


# ----------------------------------------------------------------------------- running a case
def _env(work: Path) -> dict[str, str]:
    env = dict(os.environ)
    env["PYTHONPATH"] = os.pathsep.join([str(SRC), env.get("PYTHONPATH", "")]).rstrip(os.pathsep)
    env.update(
        MPLBACKEND="Agg",
        MPLCONFIGDIR=str(work / "mpl"),
        TMPDIR=str(work / "tmp"),
        OMP_NUM_THREADS="1",
        OPENBLAS_NUM_THREADS="1",
        MKL_NUM_THREADS="1",
        NUMBA_NUM_THREADS="1",
        PYTHONWARNINGS="default",
    )
    return env


def _run(argv: list[str], cwd: Path, env: dict[str, str], timeout: float):
    """Run ``bearingsim argv`` in its own process group: (code or None on timeout, out, err, s)."""
    t0 = time.perf_counter()
    proc = subprocess.Popen(
        [sys.executable, "-m", "bearingsim", *argv],
        cwd=cwd,
        env=env,
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
        errors="replace",
        start_new_session=True,
    )
    try:
        out, err = proc.communicate(timeout=timeout)
        code: int | None = proc.returncode
    except subprocess.TimeoutExpired:
        with contextlib.suppress(ProcessLookupError):
            os.killpg(proc.pid, signal.SIGKILL)
        out, err = proc.communicate()
        code = None
    with contextlib.suppress(ProcessLookupError):  # whatever it started (Dask workers)
        os.killpg(proc.pid, signal.SIGKILL)
    return code, out, err, time.perf_counter() - t0


def _flatten(obj: Any, prefix: str = "") -> tuple[set[str], set[str]]:
    """(paths holding null, paths holding a number) of a JSON value (list indices as [])."""
    nulls, nums = set(), set()
    if isinstance(obj, dict):
        for k, v in obj.items():
            a, b = _flatten(v, f"{prefix}.{k}")
            nulls |= a
            nums |= b
    elif isinstance(obj, list):
        for v in obj:
            a, b = _flatten(v, prefix + "[]")
            nulls |= a
            nums |= b
    elif obj is None:
        nulls.add(prefix)
    elif isinstance(obj, int | float) and not isinstance(obj, bool):
        (nums if math.isfinite(obj) else nulls).add(prefix)
    return nulls, nums


def _nonfinite_in_file(path: Path) -> list[str] | str:
    """Names of the variables of an output file holding non-finite numbers; a string when the
    file cannot be read."""
    import numpy as np

    try:
        if path.suffix == ".csv":
            rows = [ln for ln in path.read_text().splitlines() if not ln.startswith("#")]
            names = rows[0].split(",")
            data = np.array([[float(v) for v in ln.split(",")] for ln in rows[1:]])
            assert data.shape[1] == len(names), "ragged CSV"
            return [n for j, n in enumerate(names) if not np.all(np.isfinite(data[:, j]))]
        if path.suffix == ".png":
            return [] if _png_complete(path) else "not a complete PNG"
        from bearingsim.results import _open

        ds = _open(path)
        bad = []
        for name, v in ds.data_vars.items():
            if v.dtype.kind == "f" and not np.all(np.isfinite(v.values)):
                bad.append(str(name))
        return bad
    except Exception as exc:  # noqa: BLE001 - any failure to read is the finding
        return f"unreadable: {type(exc).__name__}: {' '.join(str(exc).split())[:200]}"


def _png_complete(path: Path) -> bool:
    data = path.read_bytes()
    return (
        data.startswith(b"\x89PNG\r\n\x1a\n")
        and data[-12:-8] == b"\0\0\0\0"
        and (data[-8:-4] == b"IEND")
    )


def run_case(case: Case, work: Path, fx: Path, env: dict[str, str], timeout: float) -> Case:
    d = work / "cases" / f"{case.id:05d}"
    d.mkdir(parents=True)
    (d / "afile").write_text("a file\n")
    (d / "adir").mkdir()
    for op, src, dst in case.setup:
        if op == "copytree":
            shutil.copytree(src.replace("{fx}", str(fx)), d / dst)
    before = _snapshot(d)
    argv = [a.replace("{fx}", str(fx)) for a in case.argv]
    code, out, err, wall = _run(argv, d, env, timeout)
    after = _snapshot(d)
    case.code, case.wall_s, case.stderr = code, wall, err
    lines = [ln for ln in err.splitlines() if ln.strip()]
    errors = [ln for ln in lines if ln.startswith("error: ")]
    stray = [ln for ln in lines if not ln.startswith(("error: ", "warning: "))]
    new = sorted(set(after) - set(before))
    temps = [n for n in new if Path(n).name.startswith(".") and "tmp" in Path(n).name]
    if code is None:
        case.cls = "hang"
    elif "Traceback" in err or code not in (0, 2) or len(errors) > 1:
        case.cls = "traceback"
    elif code == 2:
        if new:
            case.cls, case.note = "leftover", "left " + ", ".join(new[:5])
        elif len(errors) != 1 or stray:
            case.cls, case.note = "bad-output", "stderr is not one error: line"
        else:
            case.cls = "refused"
    else:  # exit 0
        case.cls = "ok"
        if temps:
            case.cls, case.note = "leftover", "left temporaries " + ", ".join(temps[:5])
        elif "--json" in argv:
            try:
                obj = json.loads(out)
                assert isinstance(obj, dict)
            except (ValueError, AssertionError):
                case.cls, case.note = "bad-output", "stdout is not one JSON object"
            else:
                if re.search(r"\b(NaN|-?Infinity)\b", out):
                    case.cls, case.note = "nan", "NaN/Infinity in the JSON"
                nulls, nums = _flatten(obj)
                case.nulls, case.numbers = frozenset(nulls), frozenset(nums)
        if case.cls == "ok" and stray:
            case.cls, case.note = "bad-output", "stderr: " + stray[0][:200]
        if case.cls == "ok":
            for o in case.outputs:
                p = d / o.replace("{fx}", str(fx)) if not o.startswith("/") else Path(o)
                if p.is_file() and not o.startswith("/dev"):
                    bad = _nonfinite_in_file(p)
                    if isinstance(bad, str):
                        case.cls, case.note = "nan", f"{o}: {bad}"
                    else:
                        case.nonfinite_files[Path(o).suffix] = bad
        if case.cls == "ok" and case.expect == "refuse":
            case.cls = "accepted-absurd"
    return case


def _finish_nan(cases: list[Case]) -> None:
    """``ok`` cases whose JSON has a null (or whose output file a non-finite variable) where
    the command's valid run has a number become ``nan``."""
    base = {c.command: c for c in cases if c.base and c.cls == "ok"}
    for c in cases:
        if c.cls not in ("ok", "accepted-absurd"):
            continue
        ref = base.get(c.command)
        ref_nums = ref.numbers if ref else frozenset()
        ref_nulls = ref.nulls if ref else frozenset()
        extra = sorted(
            n
            for n in c.nulls
            if (n in ref_nums or n not in ref_nulls) and (c.command, n) not in KNOWN_NULLS
        )
        files = {
            ext: sorted(set(v) - set(ref.nonfinite_files.get(ext, []) if ref else []))
            for ext, v in c.nonfinite_files.items()
        }
        files = {k: v for k, v in files.items() if v}
        if extra or files:
            c.note = (f"null in JSON at {', '.join(extra[:4])}" if extra else "") + (
                f" non-finite in {files}" if files else ""
            )
            c.cls = "nan"


# ----------------------------------------------------------------------------- kill sweep
@dataclasses.dataclass
class Trial:
    target: str
    argv: list[str]
    output: str  # file (or dataset directory) name in the trial folder
    extra_outputs: list[str]
    overwrite: bool
    kill_at: float
    mode: str = "group"  # sweep: "group" or "client"
    after_created: bool = False  # sweep: kill_at counts from the dataset's appearance
    # results
    killed: bool = False
    after_kill: str = ""  # absent / complete / damaged
    temps_after_kill: int = 0
    rewrite_ok: bool = False
    stale_after_rewrite: int = 0
    note: str = ""
    lost: int = 0
    duplicated: int = 0
    changed: int = 0
    orphans: int = 0
    ok_at_kill: int = 0  # sweep: runs committed ok when it was killed


KILL_TARGETS = {
    # name: (argv, output, extra outputs, share of the kills)
    "simulate vsm": (
        ["simulate", "--duration-s", "2", "--fs-hz", "48000", "-o", "out.nc", "--json"],
        "out.nc",
        [],
        0.10,
    ),
    "simulate dem": (
        ["simulate", "--model", "dem", "--duration-s", "2", "-o", "out.nc", "--json"],
        "out.nc",
        [],
        0.10,
    ),
    "simulate rotor": (
        ["simulate", "--model", "rotor", "--duration-s", "0.1", "-o", "out.nc", "--json"],
        "out.nc",
        [],
        0.10,
    ),
    "ias": (
        ["ias", "--duration-s", "1", "-o", "out.nc", "--plot", "out.png", "--json"],
        "out.nc",
        ["out.png"],
        0.20,
    ),
    "stiffness": (
        ["stiffness", "6205", "--fy-n", "1000", "-o", "out.nc", "--json"],
        "out.nc",
        [],
        0.18,
    ),
    "life": (
        [
            "life",
            "6205",
            "--radial-load-n",
            "3000",
            "--mesh",
            "coarse",
            "--stop",
            "initiation",
            "-o",
            "out.nc",
            "--json",
        ],
        "out.nc",
        [],
        0.14,
    ),
    "sweep run": (
        ["sweep", "run", "{fx}/spec20.toml", "-o", "store", "--workers", "2", "--json"],
        "store",
        [],
        0.18,
    ),
}


def _state(path: Path) -> str:
    if not path.exists():
        return "absent"
    bad = _nonfinite_in_file(path)
    return "damaged" if isinstance(bad, str) else "complete"


def _temps(folder: Path, name: str) -> list[str]:
    if not folder.is_dir():
        return []
    return sorted(n for n in os.listdir(folder) if n.startswith(f".{name}."))


def _kill_run(argv, cwd, env, kill_at, mode="group", after: Path | None = None):
    """Start ``bearingsim argv``, SIGKILL it at ``kill_at`` s (counted from the appearance of
    ``after``, when given); returns (killed, orphans)."""
    proc = subprocess.Popen(
        [sys.executable, "-m", "bearingsim", *argv],
        cwd=cwd,
        env=env,
        stdout=subprocess.DEVNULL,
        stderr=subprocess.DEVNULL,
        start_new_session=True,
    )
    if after is not None:
        t0 = time.monotonic()
        while not after.exists() and proc.poll() is None and time.monotonic() - t0 < TIMEOUT_S:
            time.sleep(0.01)
    try:
        proc.wait(timeout=kill_at)
        killed = False
    except subprocess.TimeoutExpired:
        killed = True
        if mode == "client":
            proc.kill()
        else:
            os.killpg(proc.pid, signal.SIGKILL)
        proc.wait()
    orphans = 0
    if mode == "client" and killed:  # the workers lose their scheduler: do they stop?
        t0 = time.monotonic()
        while time.monotonic() - t0 < 30.0 and _group_alive(proc.pid):
            time.sleep(0.5)
        orphans = int(_group_alive(proc.pid))
    with contextlib.suppress(ProcessLookupError):
        os.killpg(proc.pid, signal.SIGKILL)
    return killed, orphans


def _group_alive(pgid: int) -> bool:
    for pid in os.listdir("/proc"):
        if not pid.isdigit():
            continue
        try:
            with open(f"/proc/{pid}/stat", "rb") as fh:
                raw = fh.read()
        except OSError:
            continue
        fields = raw[raw.rfind(b")") + 2 :].split()
        if int(fields[2]) == pgid and fields[0] != b"Z":
            return True
    return False


class SweepCheck:
    """The uninterrupted sweep of ``spec20.toml`` and ``simulate`` of each of its runs."""

    def __init__(self, fx: Path, ref_store: Path) -> None:
        import numpy as np

        from bearingsim.simulation import simulate
        from bearingsim.sweep.dataset import open_dataset
        from bearingsim.sweep.spec import SweepSpec

        self.spec = SweepSpec.from_toml(fx / "spec20.toml")
        ds = open_dataset(ref_store)
        self.n = len(ds)
        self.ref = ds.arrays()[0]
        self.direct = {}
        for i in range(self.n):  # simulate() of the same scenario, in this process
            r = simulate(self.spec.scenario(i))
            self.direct[i] = np.stack([r[c] for c in ds.series])
        self.ref_vs_direct = sum(
            not np.array_equal(self.ref[i], self.direct[i]) for i in range(self.n)
        )
        self.lock = threading.Lock()

    def check(
        self,
        store: Path,
        ok_before: set[int],
        offsets: dict[str, int],
        t: Trial,
        rng: random.Random,
    ) -> None:
        import numpy as np

        from bearingsim.sweep.dataset import open_dataset
        from bearingsim.sweep.store import OK

        ds = open_dataset(store)
        st = ds.status
        t.lost = int(np.sum(st != OK))
        computed: dict[int, int] = {}
        for f in sorted((store / "records").glob("*.jsonl")):
            with open(f, "rb") as fh:
                fh.seek(offsets.get(f.name, 0))
                for line in fh.read().splitlines():
                    with contextlib.suppress(ValueError):
                        r = json.loads(line)
                        if isinstance(r, dict) and r.get("status") == OK:
                            computed[r["run"]] = computed.get(r["run"], 0) + 1
        t.duplicated = sum(1 for i in ok_before if i in computed) + sum(
            n - 1 for n in computed.values() if n > 1
        )
        x = ds.arrays()[0]
        picks = set(rng.sample(range(self.n), 3))
        for i in range(self.n):
            if st[i] != OK:
                continue
            same = np.array_equal(x[i], self.ref[i])
            if i in picks:
                same = same and np.array_equal(x[i], self.direct[i])
            t.changed += int(not same)


def run_trial(
    t: Trial,
    tdir: Path,
    fx: Path,
    env,
    ref: Path | None,
    check: SweepCheck | None,
    rng: random.Random,
) -> Trial:
    tdir.mkdir(parents=True)
    argv = [a.replace("{fx}", str(fx)) for a in t.argv]
    out = tdir / t.output
    if t.overwrite and ref is not None:
        shutil.copy2(ref, out)
    offsets: dict[str, int] = {}
    ok_before: set[int] = set()
    after = out if t.after_created else None
    t.killed, t.orphans = _kill_run(argv, tdir, env, t.kill_at, t.mode, after)
    if t.target == "sweep run":
        t.after_kill, ok_before, offsets = _store_state(out)
        t.ok_at_kill = len(ok_before)
    else:
        states = [_state(out)] + [_state(tdir / e) for e in t.extra_outputs]
        t.after_kill = "damaged" if "damaged" in states else states[0]
        t.temps_after_kill = sum(len(_temps(tdir, n)) for n in [t.output, *t.extra_outputs])
    code, _, err, _ = _run(argv, tdir, env, TIMEOUT_S * 2)
    t.rewrite_ok = code == 0 and all(
        _state(tdir / n) == "complete" for n in [t.output, *t.extra_outputs]
    )
    if t.target == "sweep run":
        t.rewrite_ok = code == 0
        t.stale_after_rewrite = len([n for n in os.listdir(tdir) if n.startswith(".store")])
        if code == 0 and check is not None:
            try:
                check.check(out, ok_before, offsets, t, rng)
            except Exception as exc:  # noqa: BLE001
                t.note = f"check failed: {type(exc).__name__}: {exc}"
                t.lost = check.n
    else:
        t.stale_after_rewrite = sum(len(_temps(tdir, n)) for n in [t.output, *t.extra_outputs])
    if code != 0:
        t.note = (t.note + " resume/rewrite: " + " | ".join(err.strip().splitlines()[-2:]))[:400]
    return t


def _store_state(store: Path) -> tuple[str, set[int], dict[str, int]]:
    """State of a dataset after a kill: absent (nothing or only its creation temporary),
    complete (opens; runs ok so far) or damaged; the runs ok; the sizes of its record files."""
    import numpy as np

    if not store.exists():
        return "absent", set(), {}
    try:
        from bearingsim.sweep.dataset import open_dataset
        from bearingsim.sweep.store import OK, records_offsets

        ds = open_dataset(store)
        ok = set(np.flatnonzero(ds.status == OK).tolist())
        return "complete", ok, records_offsets(store)
    except Exception:  # noqa: BLE001
        return "damaged", set(), {}


def kill_sweep(n_kills: int, work: Path, fx: Path, env, jobs: int, seed: int) -> dict[str, Any]:
    rng = random.Random(seed + 1)
    kdir = work / "kills"
    kdir.mkdir()
    refs: dict[str, tuple[float, Path]] = {}
    print(f"kill sweep: reference runs of {len(KILL_TARGETS)} targets", file=sys.stderr)
    created = 0.0  # when the dataset of the reference sweep appeared [s]
    for name, (argv, output, _, _) in KILL_TARGETS.items():
        d = kdir / ("ref-" + name.replace(" ", "-"))
        d.mkdir()
        t0 = time.monotonic()
        proc = subprocess.Popen(
            [sys.executable, "-m", "bearingsim", *[a.replace("{fx}", str(fx)) for a in argv]],
            cwd=d, env=env, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True,
        )  # fmt: skip
        while proc.poll() is None:
            if not created and name == "sweep run" and (d / output).exists():
                created = time.monotonic() - t0
            time.sleep(0.01)
        wall = time.monotonic() - t0
        if proc.returncode != 0:
            raise RuntimeError(f"reference run of {name} failed: {proc.stderr.read()}")
        proc.stderr.close()
        refs[name] = (wall, d / output)
    check = SweepCheck(fx, refs["sweep run"][1])
    trials: list[Trial] = []
    shares = {k: v[3] for k, v in KILL_TARGETS.items()}
    quota = {k: max(1, round(n_kills * s)) for k, s in shares.items()}
    while sum(quota.values()) < n_kills:
        quota["simulate vsm"] += 1
    for name, q in quota.items():
        argv, output, extra, _ = KILL_TARGETS[name]
        wall = refs[name][0]
        for k in range(q):
            late = k % 2 == 1
            at = rng.uniform(0.8 * wall, 1.0 * wall) if late else rng.uniform(0.05, wall)
            mode = "client" if name == "sweep run" and k % 3 == 2 else "group"
            over = name != "sweep run" and rng.random() < 0.5
            after = name == "sweep run" and k % 4 != 0  # 3 in 4 while the runs are committed
            if after:
                at = rng.uniform(0.0, max(0.1, wall - created))
            trials.append(Trial(name, argv, output, extra, over, at, mode, after))
    done: list[Trial] = []
    retry_budget = n_kills
    with (
        concurrent.futures.ThreadPoolExecutor(jobs) as pool,
        tqdm(total=len(trials), desc="kills", file=sys.stderr) as bar,
    ):
        pending = {
            pool.submit(
                run_trial,
                t,
                kdir / f"{i:04d}",
                fx,
                env,
                refs[t.target][1],
                check,
                random.Random(seed + i),
            ): t
            for i, t in enumerate(trials)
        }
        n = len(trials)
        while pending:
            fut = next(concurrent.futures.as_completed(pending))
            pending.pop(fut)
            t = fut.result()
            bar.update()
            done.append(t)
            if not t.killed and retry_budget > 0:  # finished first: try an earlier instant
                retry_budget -= 1
                t2 = dataclasses.replace(
                    t,
                    kill_at=t.kill_at * 0.7,
                    killed=False,
                    note="",
                    after_kill="",
                    lost=0,
                    duplicated=0,
                    changed=0,
                )
                n += 1
                bar.total = n
                pending[
                    pool.submit(
                        run_trial,
                        t2,
                        kdir / f"{n:04d}",
                        fx,
                        env,
                        refs[t.target][1],
                        check,
                        random.Random(seed + n),
                    )
                ] = t2
    return {
        "trials": done,
        "refs": {k: v[0] for k, v in refs.items()},
        "ref_vs_simulate_changed": check.ref_vs_direct,
    }


# ----------------------------------------------------------------------------- report
def print_table(cases: list[Case]) -> None:
    rows: dict[str, dict[str, int]] = {}
    for c in cases:
        rows.setdefault(c.command, dict.fromkeys(CLASSES, 0))[c.cls] += 1
    w = max(len(r) for r in rows) + 2
    head = "command".ljust(w) + "".join(f"{k:>{_w(k)}}" for k in ("cases", *CLASSES))
    print(head)
    print("-" * len(head))
    tot = dict.fromkeys(CLASSES, 0)
    for r in sorted(rows):
        counts = rows[r]
        for k in CLASSES:
            tot[k] += counts[k]
        print(
            r.ljust(w)
            + f"{sum(counts.values()):>6}"
            + "".join(f"{counts[k]:>{_w(k)}}" for k in CLASSES)
        )
    print("-" * len(head))
    print(
        "total".ljust(w)
        + f"{sum(tot.values()):>6}"
        + "".join(f"{tot[k]:>{_w(k)}}" for k in CLASSES)
    )


def _w(k: str) -> int:
    return max(6, len(k) + 2)


def _cmdline(c: Case, fx: Path) -> str:
    return "bearingsim " + " ".join(shlex.quote(a.replace("{fx}", "$FX")) for a in c.argv)


def print_findings(cases: list[Case], fx: Path) -> None:
    bad = [c for c in cases if c.cls not in ("ok", "refused")]
    print(f"\n{len(bad)} cases neither ok nor refused (FX = {fx}):")
    for c in bad:
        print(
            f"\n[{c.cls}] #{c.id} {c.command}: {c.what} (exit {c.code}, {c.wall_s:.1f} s)"
            + (f" - {c.note}" if c.note else "")
        )
        print("  $ " + _cmdline(c, fx))
        for ln in c.stderr.strip().splitlines()[-4:]:
            print("  | " + ln[:300])
    wrong = [c for c in cases if c.expect == "ok" and c.cls == "refused"]
    if wrong:
        print(
            f"\n{len(wrong)} valid cases refused (a false refusal, or the sweep's valid value "
            "is not one):"
        )
        for c in wrong:
            first = c.stderr.strip().splitlines()[:1]
            print(f"  #{c.id} {c.command}: {c.what}: {first[0][:250] if first else ''}")


def kill_figures(res: dict[str, Any]) -> dict[str, Any]:
    trials: list[Trial] = res["trials"]
    out: dict[str, Any] = {}
    for name in KILL_TARGETS:
        ts = [t for t in trials if t.target == name]
        k = [t for t in ts if t.killed]
        d = {
            "reference_s": round(res["refs"][name], 2),
            "trials": len(ts),
            "kills": len(k),
            "finished_before_kill": len(ts) - len(k),
            "absent": sum(t.after_kill == "absent" for t in k),
            "complete": sum(t.after_kill == "complete" for t in k),
            "damaged": sum(t.after_kill == "damaged" for t in k),
            "temporaries_after_kill": sum(t.temps_after_kill for t in k),
            "rewrite_failed": sum(not t.rewrite_ok for t in ts),
            "stale_temporaries_after_rewrite": sum(t.stale_after_rewrite for t in ts),
        }
        if name == "sweep run":
            d |= {
                "client_only_kills": sum(t.mode == "client" for t in k),
                "orphaned_workers_after_30s": sum(t.orphans for t in k),
                "runs_ok_at_kill": sorted(t.ok_at_kill for t in k),
                "runs_lost": sum(t.lost for t in ts),
                "runs_duplicated": sum(t.duplicated for t in ts),
                "runs_changed": sum(t.changed for t in ts),
            }
        out[name] = d
    return out


def print_kills(fig: dict[str, Any], res: dict[str, Any]) -> None:
    cols = [
        "reference_s",
        "kills",
        "finished_before_kill",
        "absent",
        "complete",
        "damaged",
        "temporaries_after_kill",
        "rewrite_failed",
        "stale_temporaries_after_rewrite",
    ]
    short = [
        "ref s",
        "kills",
        "early",
        "absent",
        "complete",
        "damaged",
        "tmp@kill",
        "rewr.fail",
        "stale",
    ]
    print(
        "\nkill sweep (SIGKILL at random instants; 'stale' = temporaries left after the next write)"
    )
    print("target".ljust(16) + "".join(f"{s:>10}" for s in short))
    for name, d in fig.items():
        print(name.ljust(16) + "".join(f"{d[c]:>10}" for c in cols))
    tot = sum(d["kills"] for d in fig.values())
    print(f"total kills: {tot}")
    s = fig.get("sweep run")
    if s:
        print(
            f"sweep run: {s['kills']} kills ({s['client_only_kills']} of the client alone, "
            f"{s['orphaned_workers_after_30s']} left workers alive after 30 s; runs committed "
            f"at the kill: {s['runs_ok_at_kill']}); after resume: "
            f"runs lost {s['runs_lost']}, duplicated {s['runs_duplicated']}, changed "
            f"{s['runs_changed']}; uninterrupted sweep vs simulate(): "
            f"{res['ref_vs_simulate_changed']} runs differ"
        )
    notes = [t for t in res["trials"] if t.note or t.after_kill == "damaged" or not t.rewrite_ok]
    for t in notes:
        print(
            f"  {t.target} killed at {t.kill_at:.2f} s ({t.mode}, overwrite {t.overwrite}): "
            f"after kill {t.after_kill}; {t.note}"
        )


# ----------------------------------------------------------------------------- main
def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--seed", type=int, default=14)
    ap.add_argument("--cases", type=int, default=None, help="seeded subsample of the cases")
    ap.add_argument("--kills", type=int, default=110, help="SIGKILLs (0: no kill sweep)")
    ap.add_argument("--jobs", type=int, default=2, help="cases run at once")
    ap.add_argument(
        "--commands",
        default=None,
        help="only these table rows (comma-separated prefixes, e.g. simulate,life)",
    )
    ap.add_argument("--timeout-s", type=float, default=TIMEOUT_S)
    ap.add_argument("--keep", default=None, help="keep the folders of the findings here")
    ap.add_argument("--json", dest="json_file", default=None, help="write every result here")
    args = ap.parse_args(argv)
    t0 = time.perf_counter()
    cases, notes = generate()
    if args.commands:
        pre = [s.strip() for s in args.commands.split(",")]
        cases = [c for c in cases if any(c.command.startswith(p) for p in pre)]
    if args.cases is not None and args.cases < len(cases):
        keep = [c for c in cases if c.base]
        rest = [c for c in cases if not c.base]
        cases = keep + random.Random(args.seed).sample(rest, max(0, args.cases - len(keep)))
        cases.sort(key=lambda c: c.id)
    work = Path(tempfile.mkdtemp(prefix="relsweep-"))
    (work / "tmp").mkdir()
    env = _env(work)
    fx = work / "fixtures"
    print(
        f"reliability sweep: {len(cases)} cases, {args.kills} kills, {args.jobs} jobs, "
        f"seed {args.seed}; work in {work}",
        file=sys.stderr,
    )
    make_fixtures(fx, env, args.seed)
    fx_before = _snapshot(fx)
    with (
        concurrent.futures.ThreadPoolExecutor(args.jobs) as pool,
        tqdm(total=len(cases), desc="cases", file=sys.stderr) as bar,
    ):
        futs = [pool.submit(run_case, c, work, fx, env, args.timeout_s) for c in cases]
        for f in concurrent.futures.as_completed(futs):
            f.result()
            bar.update()
    _finish_nan(cases)
    fx_after = _snapshot(fx)
    changed = sorted(
        k for k in set(fx_before) | set(fx_after) if fx_before.get(k) != fx_after.get(k)
    )
    t_cases = time.perf_counter() - t0
    kills = None
    if args.kills > 0:
        kills = kill_sweep(args.kills, work, fx, env, args.jobs, args.seed)
    wall = time.perf_counter() - t0
    print(f"\nbad-input sweep: {len(cases)} cases in {t_cases:.0f} s (seed {args.seed})\n")
    print_table(cases)
    print_findings(cases, fx)
    for n in notes:
        print(f"note: {n}")
    if changed:
        print(f"\nfixtures changed by the cases: {changed[:20]}")
    fig = None
    if kills is not None:
        fig = kill_figures(kills)
        print_kills(fig, kills)
    print(f"\nwall time {wall:.0f} s")
    if args.keep:
        keep = Path(args.keep)
        keep.mkdir(parents=True, exist_ok=True)
        for c in cases:
            if c.cls not in ("ok", "refused"):
                src = work / "cases" / f"{c.id:05d}"
                with contextlib.suppress(OSError):
                    shutil.copytree(src, keep / f"{c.id:05d}", symlinks=True)
    if args.json_file:
        from bearingsim.io.atomic import write_json

        doc = {
            "seed": args.seed,
            "wall_s": wall,
            "cases_wall_s": t_cases,
            "counts": {
                cmd: {k: sum(1 for c in cases if c.command == cmd and c.cls == k) for k in CLASSES}
                for cmd in sorted({c.command for c in cases})
            },
            "cases": [
                {
                    "id": c.id,
                    "command": c.command,
                    "what": c.what,
                    "argv": c.argv,
                    "expect": c.expect,
                    "class": c.cls,
                    "exit": c.code,
                    "wall_s": round(c.wall_s, 3),
                    "note": c.note,
                    "stderr": c.stderr.strip().splitlines()[-4:],
                }
                for c in cases
            ],
            "notes": notes,
            "fixtures_changed": changed,
            "kills": fig,
            "kill_trials": None
            if kills is None
            else [dataclasses.asdict(t) for t in kills["trials"]],
        }
        write_json(args.json_file, doc, field="--json")
    shutil.rmtree(work, ignore_errors=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
