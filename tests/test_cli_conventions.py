"""The CLI conventions of ``docs/cli.md`` hold for every command and option; deprecated
spellings warn and work (or convert); ``--help``, ``--version``, ``bearings`` and ``info`` start
without importing the heavy libraries (issue 13, items 7 and 8)."""

from __future__ import annotations

import importlib
import json
import math
import os
import re
import subprocess
import sys
from pathlib import Path

import click
import pytest

from bearingsim.cli import COMMANDS, cli
from bearingsim.cli.common import Command, _DeprecatedOption

ROOT = Path(__file__).resolve().parents[1]
DOCS = ROOT / "docs" / "cli.md"

#: libraries that must not be imported by the start-up commands (the issue's list)
HEAVY = ("scipy", "numba", "xarray", "dask", "matplotlib", "skfem")

#: unit in an option's help ``[...]`` -> the suffix its name must end with (docs/cli.md table)
SUFFIX = {
    "m": "-m",
    "mm": "-mm",
    "um": "-um",
    "s": "-s",
    "Hz": "-hz",
    "r/min": "rpm",
    "deg": "-deg",
    "N": "-n",
    "N m": "-n-m",
    "N/m": "-n-per-m",
    "N s/m": "-n-s-per-m",
    "N/m^1.5": "-n-per-m1.5",
    "m/s^2": "-m-per-s2",
    "kg": "-kg",
    "kg m": "-kg-m",
    "Pa": "-pa",
    "GB": "-gb",
}
#: option names that are not lower-case kebab: E is the usual symbol of Young's modulus
MIXED_CASE = {"--E-pa", "--shaft-E-pa"}


def _all_commands() -> list[tuple[str, click.Command]]:
    """(path, command) of every leaf command, loading every command module."""
    out = []

    def walk(group: click.Group, prefix: str) -> None:
        ctx = click.Context(group)
        for name in group.list_commands(ctx):
            cmd = group.get_command(ctx, name)
            if isinstance(cmd, click.Group):
                walk(cmd, f"{prefix}{name} ")
            else:
                out.append((f"{prefix}{name}", cmd))

    walk(cli, "")
    return out


ALL = _all_commands()
IDS = [p for p, _ in ALL]


def _visible_options(cmd: click.Command) -> list[click.Option]:
    return [p for p in cmd.params if isinstance(p, click.Option) and not p.hidden]


# ------------------------------------------------------------------------ start-up (item 8)


@pytest.mark.parametrize(
    "args",
    [
        ["--version"],
        ["--help"],
        ["bearings"],
        ["bearings", "--json"],
        ["info", "6205-cwru", "--rpm", "1797"],
        ["info", "6205-cwru", "--rpm", "1797", "--json"],
    ],
    ids=" ".join,
)
def test_startup_imports_nothing_heavy(args):
    code = (
        "import bearingsim.cli, sys, json\n"
        "try:\n"
        "    bearingsim.cli.main(sys.argv[1:])\n"
        "except SystemExit as exc:\n"
        "    rc = exc.code\n"
        f"heavy = sorted(m for m in sys.modules if m.split('.')[0] in {HEAVY!r})\n"
        "print('IMPORTED ' + json.dumps({'rc': rc, 'heavy': heavy}), file=sys.stderr)\n"
    )
    env = {**os.environ, "PYTHONPATH": str(ROOT / "src")}
    p = subprocess.run(
        [sys.executable, "-c", code, *args], capture_output=True, text=True, env=env, timeout=120
    )
    line = [ln for ln in p.stderr.splitlines() if ln.startswith("IMPORTED ")][-1]
    d = json.loads(line.removeprefix("IMPORTED "))
    assert d["rc"] in (0, None), p.stderr
    assert d["heavy"] == [], f"bearingsim {' '.join(args)} imported {d['heavy']}"
    assert p.stdout.strip()


def test_help_lists_every_command_with_its_one_line_help(run_cli):
    r = run_cli("--help")
    assert r.code == 0
    for name, (_, text) in COMMANDS.items():
        line = next(ln for ln in r.out.splitlines() if ln.split()[:1] == [name])
        assert text.startswith(line.split(None, 1)[1].removesuffix("...")), line


def test_command_table_matches_the_modules():
    """Every command module registers exactly the commands the table gives it, and the table's
    one-line help is the first sentence of the command's docstring."""
    mods = {m for m, _ in COMMANDS.values()}
    for m in mods:
        importlib.import_module(f"bearingsim.cli.{m}")
    assert set(cli.commands) == set(COMMANDS)
    for name, (mod, text) in COMMANDS.items():
        cmd = cli.commands[name]
        assert cmd.callback.__module__ == f"bearingsim.cli.{mod}", name
        assert cmd.get_short_help_str(limit=10_000) == text, name


# -------------------------------------------------------------------- conventions (item 7)


@pytest.mark.parametrize("cmd", [c for _, c in ALL], ids=IDS)
def test_option_names_follow_the_conventions(cmd):
    assert isinstance(cmd, Command), "commands are bearingsim.cli.common.Command"
    for opt in _visible_options(cmd):
        names = opt.opts + opt.secondary_opts
        long = [n for n in names if n.startswith("--")]
        for n in long:
            assert n in MIXED_CASE or n == n.lower(), n
            assert not n.endswith("-rad"), f"{n}: angles are degrees at the CLI"
            assert n not in ("--out", "--fs", "--band"), f"{n}: old spelling visible"
        if "-o" in names:
            assert "--output" in names, f"-o is -o/--output ({names})"
        text = opt.help or ""
        assert "default" not in text.lower(), f"{long}: default written in the help: {text!r}"
        units = re.findall(r"\[([^\]]+)\]", text)
        unit = next((u for u in units if u in SUFFIX), None)
        if unit is not None and not opt.is_flag:
            assert any(n.lower().endswith(SUFFIX[unit]) for n in long), (
                f"{long}: help says [{unit}], the name must end in {SUFFIX[unit]}"
            )
        for n in long:
            ends = [u for u, suf in SUFFIX.items() if n.lower().endswith(suf)]
            if ends:  # the longest suffix a name ends in is its unit, which the help states
                u = max(ends, key=lambda u: len(SUFFIX[u]))
                assert f"[{u}]" in text, f"{n} ends in {SUFFIX[u]} but the help gives no [{u}]"


@pytest.mark.parametrize("cmd", [c for _, c in ALL], ids=IDS)
def test_deprecated_spellings_are_hidden_and_documented(cmd):
    docs = DOCS.read_text(encoding="utf-8")
    for old, new in cmd.deprecated_spellings.items():
        alias = next(p for p in cmd.params if isinstance(p, _DeprecatedOption) and p.old == old)
        assert alias.hidden and not alias.expose_value
        rows = [ln for ln in docs.splitlines() if f"`{old}`" in ln and f"`{new}`" in ln]
        assert rows, f"docs/cli.md has no row `{old}` -> `{new}` ({cmd.name})"
    help_text = cmd.get_help(click.Context(cmd, info_name=cmd.name))
    for old in cmd.deprecated_spellings:
        assert not re.search(rf"{re.escape(old)}(?![-\w.])", help_text), f"{old} shown in help"


def test_every_command_has_json_and_help():
    for path, cmd in ALL:
        names = {n for p in cmd.params for n in getattr(p, "opts", [])}
        assert "--json" in names, path


# ------------------------------------------------------------- deprecated spellings (item 7)


def _warning(err: str, old: str, new: str) -> None:
    lines = err.strip().splitlines()
    assert f"warning: {old} is deprecated; use {new}" in lines, err


def test_old_spelling_warns_and_gives_the_same_result(run_cli):
    new = run_cli("contact", "6206", "--radial-load-n", "5000", "--json")
    old = run_cli("contact", "6206", "--radial-load", "5000", "--json")
    assert new.code == old.code == 0
    assert new.err == ""
    assert old.err.strip() == "warning: --radial-load is deprecated; use --radial-load-n"
    assert old.json() == new.json(), "exactly one JSON object on stdout, the same numbers"
    load_new = run_cli("load", "6205", "--fx-n", "10", "--fy-n", "50", "--json").json()
    load_old = run_cli("load", "6205", "--fx=10", "--fy", "50", "--json")
    _warning(load_old.err, "--fx", "--fx-n")
    _warning(load_old.err, "--fy", "--fy-n")
    assert load_old.json() == load_new


def test_old_spelling_keeps_checks_and_errors(run_cli):
    r = run_cli("contact", "6205", "--ball-load", "-3")
    assert r.code == 2
    lines = r.err.strip().splitlines()
    assert lines[0] == "warning: --ball-load is deprecated; use --ball-load-n"
    assert lines[1:] == ["error: ball_load_n = -3 N is out of range; valid range [0, inf) N"]
    r = run_cli("ias", "--torque-nm", "0", "-o", "never.nc")
    assert r.code == 2 and "torque_n_m = 0 N m with zero initial speed" in r.err
    r = run_cli("ias", "--rpm", "60", "--torque-nm", "9", "-o", "never.nc")
    assert r.code == 2 and "at most one of --rpm and --torque-n-m" in r.err


def test_old_output_spelling_satisfies_a_required_output(run_cli, tmp_path):
    """``--out`` reaches the required ``-o/--output``: the run gets past option parsing to the
    model's own check; without any output option the error names -o/--output."""
    r = run_cli("ias", "--spall-width-m", "9e-3", "--out", tmp_path / "r.nc")
    assert r.code == 2
    _warning(r.err, "--out", "--output")
    assert "spall_width_m = 0.009 m" in r.err
    r = run_cli("ias", "--spall-width-m", "9e-3")
    assert r.code == 2 and r.err.strip() == "error: Missing option '-o' / '--output'."
    assert not list(tmp_path.iterdir())


def test_old_and_new_spelling_together_is_an_error(run_cli, tmp_path):
    r = run_cli("contact", "6205", "--ball-load", "1", "--ball-load-n", "2")
    assert r.code == 2
    lines = r.err.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("error: give --ball-load-n, not both")
    assert "--ball-load" in lines[0]
    r = run_cli("stiffness", "6205", "--fy-n", "500", "-o", tmp_path / "a.json", "--out", "b")
    assert r.code == 2 and "give --output, not both" in r.err and not list(tmp_path.iterdir())


STIFF = ["stiffness", "6205", "--fy-n", "500", "--cage-revs", "2", "--points-per-rev", "90"]


def test_radian_spellings_convert_to_degrees(run_cli):
    """The meaning changed (rad -> deg): the old ``-rad`` options still take radians."""
    deg = run_cli(
        *STIFF,
        "--inner-tilt-deg",
        repr(math.degrees(3e-3)),
        "--outer-tilt-azimuth-deg",
        "90",
        "--json",
    )
    rad = run_cli(
        *STIFF, "--inner-tilt-rad", "3e-3", "--outer-tilt-azimuth-rad", repr(math.pi / 2), "--json"
    )
    assert deg.code == rad.code == 0, rad.err
    _warning(rad.err, "--inner-tilt-rad", "--inner-tilt-deg")
    _warning(rad.err, "--outer-tilt-azimuth-rad", "--outer-tilt-azimuth-deg")
    assert rad.json() == deg.json()
    errs = "0.05,0,0,0,-0.03,0,0,0,0"
    a = run_cli(*STIFF, "--ball-errors-rad", errs, "--json")
    deg_errs = ",".join(repr(math.degrees(float(e))) for e in errs.split(","))
    b = run_cli(*STIFF, "--ball-errors-deg", deg_errs, "--json")
    assert a.code == b.code == 0, a.err
    _warning(a.err, "--ball-errors-rad", "--ball-errors-deg")
    assert a.json() == b.json()
    bad = run_cli(*STIFF, "--ball-errors-rad", "0,0,a,0,0,0,0,0,0")
    assert bad.code == 2 and "ball_errors_deg[2] = 'a' is not a number" in bad.err


def test_simulate_old_spellings(run_cli, tmp_path):
    """Renamed scenario-override options of ``simulate`` keep working for one release."""
    args = ["simulate", "--fault", "outer", "--duration-s", "0.01", "--json"]
    new = run_cli(
        *args, "--fs-hz", "24000", "--fy-n", "60", "--damping-n-s-per-m", "310",
        "--noise-rms-m-per-s2", "0.5", "--stiffness-n-per-m1.5", "8e9", "-o", tmp_path / "a.nc",
    )  # fmt: skip
    old = run_cli(
        *args, "--fs", "24000", "--fy", "60", "--damping", "310", "--noise-rms", "0.5",
        "--stiffness", "8e9", "--output", tmp_path / "b.nc",
    )  # fmt: skip
    assert new.code == old.code == 0, old.err
    renamed = {
        "--fs": "--fs-hz",
        "--fy": "--fy-n",
        "--damping": "--damping-n-s-per-m",
        "--noise-rms": "--noise-rms-m-per-s2",
        "--stiffness": "--stiffness-n-per-m1.5",
    }
    for o, n in renamed.items():
        _warning(old.err, o, n)
    a, b = new.json(), old.json()
    assert a["n_samples"] == b["n_samples"] == 240
    for k in ("fs_hz", "rms_acc_x", "rms_acc_y"):
        assert a[k] == b[k], k


def test_analyze_never_calls_the_shaft_frequency_fs(run_cli):
    cmd = cli.get_command(click.Context(cli), "analyze")
    names = {n for p in _visible_options(cmd) for n in p.opts}
    assert "--fs" not in names and "--fs-hz" in names
    assert "shaft" not in cmd.params[[p.name for p in cmd.params].index("fs_hz")].help.lower()


def test_choices_written_out_match_their_enums():
    """Choices the CLI spells out (so that its modules need not import the models) are exactly
    the values of the library's enums."""
    from bearingsim.config import Solver
    from bearingsim.dynamics.ias import ContactLaw, SpallLoad
    from bearingsim.dynamics.rotor import ShaftMassModel

    ctx = click.Context(cli)

    def choices(command: str, option: str) -> list[str]:
        cmd = cli.get_command(ctx, command)
        return list(next(p for p in cmd.params if option in p.opts).type.choices)

    assert choices("rotor-modes", "--shaft-mass-model") == [m.value for m in ShaftMassModel]
    assert choices("simulate", "--shaft-mass-model") == [m.value for m in ShaftMassModel]
    assert choices("ias", "--contact-law") == [m.value for m in ContactLaw]
    assert choices("ias", "--spall-load") == [m.value for m in SpallLoad]
    assert choices("ias", "--solver") == [m.value for m in Solver]
