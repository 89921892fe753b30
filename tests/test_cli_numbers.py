"""Issue 14, "Messages": click's "'abc' is not a valid float" gave no range. Every numeric option
of every command parses with :class:`bearingsim.cli.common.Number`, whose message says the valid
range (``docs/cli.md``, "Exit codes and errors")."""

from __future__ import annotations

import click
import pytest

from bearingsim.cli import COMMANDS, cli
from bearingsim.cli.common import Number


def _commands():
    """``(path, command)`` for every command and sub-command, loaded."""
    ctx = click.Context(cli)
    out = []
    for name in sorted(COMMANDS):
        cmd = cli.get_command(ctx, name)
        if isinstance(cmd, click.Group):
            out += [((name, sub), cmd.get_command(ctx, sub)) for sub in sorted(cmd.commands)]
        else:
            out.append(((name,), cmd))
    return out


def _numeric_options():
    rows = []
    for path, cmd in _commands():
        for p in cmd.params:
            if isinstance(p, click.Option) and not p.hidden and not p.is_flag:
                if isinstance(p.type, Number | click.types._NumberParamTypeBase):
                    rows.append((path, p))
    return rows


NUMERIC = _numeric_options()


def test_every_numeric_option_says_its_range():
    assert len(NUMERIC) > 80  # every command's numbers (issue 14: ~100 options)
    plain = [
        f"{' '.join(path)} {p.opts[-1]}" for path, p in NUMERIC if not isinstance(p.type, Number)
    ]
    assert not plain, f"numeric options without a valid range (use cli.common.Number): {plain}"
    for path, p in NUMERIC:
        assert p.type.valid[0] in "[(", (path, p.opts, p.type.valid)  # an interval first


@pytest.mark.parametrize(
    "path, opt", [(path, p.opts[-1]) for path, p in NUMERIC], ids=lambda x: str(x)
)
def test_not_a_number_names_the_range(run_cli, path, opt, tmp_path):
    r = run_cli(*path, opt, "abc")
    assert r.code == 2, r.err
    lines = r.err.strip().splitlines()
    assert len(lines) == 1 and "Traceback" not in r.err, r.err
    p = next(q for q in dict(_commands())[path].params if opt in q.opts)
    kind = "an integer" if p.type.integer else "a number"
    assert lines[0].startswith(f"error: Invalid value for '{opt}'"), lines[0]
    assert lines[0].endswith(f"'abc' is not {kind}; valid range {p.type.valid}"), lines[0]
    assert not list(tmp_path.iterdir())


def test_examples_of_the_messages(run_cli):
    r = run_cli("contact", "6205", "--radial-load-n", "abc")
    assert r.err.strip() == (
        "error: Invalid value for '--radial-load-n': 'abc' is not a number; valid range (0, inf) N"
    )
    r = run_cli("stiffness", "6205", "--cage-revs", "2.5")
    assert "'2.5' is not an integer; valid range [1, 10000]" in r.err
    # the deprecated spelling hands its text to the new option, which answers
    r = run_cli("load", "6205", "--fy", "abc")
    assert "Invalid value for '--fy-n': 'abc' is not a number; valid range (-inf, inf) N" in r.err
    # the range itself is checked by the library, in its words (unchanged messages)
    r = run_cli("info", "6205", "--rpm", "-5")
    assert "rpm = -5 r/min is out of range; valid range (0, inf) r/min" in r.err
