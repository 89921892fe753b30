"""The README's Python tour runs as a doctest; its CLI lines are valid commands."""

from __future__ import annotations

import doctest
import json
import re
import shlex
from pathlib import Path

README = Path(__file__).resolve().parents[1] / "README.md"


def test_readme_python_examples():
    res = doctest.testfile(str(README), module_relative=False, optionflags=doctest.ELLIPSIS)
    assert res.attempted > 5 and res.failed == 0


def test_readme_setup_commands_are_first_and_two():
    text = README.read_text()
    block = re.search(r"```bash\n(.*?)```", text, re.S).group(1).strip().splitlines()
    assert len(block) == 2
    assert "reproduce --quick" in block[0]
    assert "pytest" in block[1]


def test_readme_cli_examples_run(run_cli, tmp_path, monkeypatch):
    import shutil

    shutil.copytree(README.parent / "examples", tmp_path / "examples")
    monkeypatch.chdir(tmp_path)
    (tmp_path / "my_bearing.toml").write_text(
        'id = "mine"\ntype = "ball"\nn_elements = 9\nelement_diameter_m = 7.94e-3\n'
        "pitch_diameter_m = 39e-3\ninner_groove_radius_m = 4.089e-3\n"
        "outer_groove_radius_m = 4.169e-3\n"
    )
    text = README.read_text()
    blocks = re.findall(r"```bash\n(.*?)```", text, re.S)[1:]
    n = n_verdicts = 0
    for block in blocks:
        for line in block.strip().splitlines():
            args = shlex.split(line)
            assert args[0] == "bearingsim"
            r = run_cli(*args[1:])
            assert r.code == 0, f"{line}: {r.err}"
            assert "deprecated" not in r.err, f"{line}: old option spelling ({r.err})"
            if args[1:] == ["analyze", "outer.nc", "ball.nc", "--json"]:
                # the README's simulated faults are diagnosed as what they are (before
                # --antialias the outer race read "uncertain", leading ball: aliased lines)
                verdicts = [json.loads(x)["diagnosis"] for x in r.out.splitlines()]
                assert verdicts == ["outer", "ball"], line
                n_verdicts = 1
            n += 1
    assert n >= 4 and n_verdicts == 1
