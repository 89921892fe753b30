"""Outputs (issue 14, items 1 and 4): every output location checked writable before any work,
one line naming the option, the path and the reason; files created with the umask's mode;
temporaries removed on any failure, and those of a killed writer removed by the next write to the
same place (never those of a writer still running)."""

from __future__ import annotations

import contextlib
import errno
import json
import math
import os
import re
import signal
import stat
import subprocess
import sys
import threading
import time
from pathlib import Path

import numpy as np
import pytest

import bearingsim
from bearingsim.errors import ConfigError
from bearingsim.io import atomic
from bearingsim.io.atomic import (
    LEGACY_TEMP_AGE_S,
    atomic_open,
    atomic_path,
    check_output,
    clean_stale_temporaries,
    write_json,
)
from bearingsim.results import SimulationResult, load_result

ROOT = os.geteuid() == 0
#: root ignores permission bits, so a chmod-ed folder does not stop it writing
ROOT_SKIP = "running as root: permission bits do not stop root (EACCES is simulated below)"
SRC = str(Path(bearingsim.__file__).resolve().parents[1])
ENV = {**os.environ, "PYTHONPATH": SRC}


def _one_line_error(r) -> str:
    """The message of a refused command: exit code 2, one line ``error: ...`` on stderr."""
    assert r.code == 2, (r.code, r.out, r.err)
    lines = r.err.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("error: "), r.err
    assert "Traceback" not in r.err
    return lines[0]


def _tree(p: Path) -> list[str]:
    return sorted(str(q.relative_to(p)) for q in p.rglob("*"))


def _small_result() -> SimulationResult:
    t = np.arange(64) / 1000.0
    return SimulationResult(
        time=t,
        channels={"acc_x": np.cos(t), "acc_y": np.sin(t)},
        units={"acc_x": "m/s^2", "acc_y": "m/s^2"},
        scenario={"rpm": 1796.0},
        meta={"fs_hz": 1000.0, "shaft_hz": 1796.0 / 60},
    )


# ----------------------------------------------------------------------------------------------
# every output option of every command, checked before the work (the work function must not run)

#: (argv with {out} for the output under test, the option named, the work that must not start);
#: ``{ok}`` is a writable file for the other required output, ``{file}`` an input name
OUTPUTS = {
    "simulate -o": (["simulate", "-o", "{out}"], "-o/--output", "bearingsim.simulation.simulate"),
    "ias -o": (["ias", "-o", "{out}"], "-o/--output", "bearingsim.dynamics.ias.scenario.run_ias"),
    "ias --plot": (
        ["ias", "-o", "{ok}", "--plot", "{out}"],
        "--plot",
        "bearingsim.dynamics.ias.scenario.run_ias",
    ),
    "life -o": (
        ["life", "6205", "--radial-load-n", "1000", "-o", "{out}"],
        "-o/--output",
        "bearingsim.life.fatigue.contact_fatigue_life",
    ),
    "life --plot": (
        ["life", "6205", "--radial-load-n", "1000", "-o", "{ok}", "--plot", "{out}"],
        "--plot",
        "bearingsim.life.fatigue.contact_fatigue_life",
    ),
    "life --plot-curve": (
        ["life", "6205", "--radial-load-n", "1000", "-o", "{ok}", "--plot-curve", "{out}"],
        "--plot-curve",
        "bearingsim.life.fatigue.contact_fatigue_life",
    ),
    "life --plot-weibull": (
        ["life", "6205", "--radial-load-n", "1000", "-o", "{ok}", "--plot-weibull", "{out}"],
        "--plot-weibull",
        "bearingsim.life.fatigue.contact_fatigue_life",
    ),
    "stiffness -o": (
        ["stiffness", "6205", "--fy-n", "1000", "-o", "{out}"],
        "-o/--output",
        "bearingsim.cli.stiffness.stiffness_vs_cage",
    ),
    "stiffness --plot": (
        ["stiffness", "6205", "--fy-n", "1000", "--plot", "{out}"],
        "--plot",
        "bearingsim.cli.stiffness.stiffness_vs_cage",
    ),
    "vsm-trace -o": (
        ["vsm-trace", "-o", "{out}"],
        "-o/--output",
        "bearingsim.dynamics.ring.trace.stiffness_trace",
    ),
    "vsm-trace --plot": (
        ["vsm-trace", "--plot", "{out}"],
        "--plot",
        "bearingsim.dynamics.ring.trace.stiffness_trace",
    ),
    "load --plot": (
        ["load", "6205", "--fy-n", "1000", "--plot", "{out}"],
        "--plot",
        "bearingsim.cli.foundation.radial_load_distribution",
    ),
    "analyze --plot": (
        ["analyze", "{file}", "--plot", "{out}"],
        "--plot",
        "bearingsim.signal.load_signal",
    ),
    "analyze-ias --plot": (
        ["analyze-ias", "{file}", "--plot", "{out}"],
        "--plot",
        "bearingsim.signal.order.read_shaft_signal",
    ),
    "rig identify -o": (
        ["rig", "identify", "{file}", "--name", "x", "-o", "{out}"],
        "-o/--output",
        "bearingsim.io.signal.read_signal",
    ),
    "rig identify --plot": (
        ["rig", "identify", "{file}", "--name", "x", "-o", "{ok}", "--plot", "{out}"],
        "--plot",
        "bearingsim.io.signal.read_signal",
    ),
    "reproduce -o": (
        ["reproduce", "--quick", "-o", "{out}"],
        "-o/--output",
        "bearingsim.cli.report.run_report",
    ),
    "sweep run -o": (
        ["sweep", "run", "{file}", "-o", "{out}"],
        "-o/--output",
        "bearingsim.sweep.execute.run_sweep",
    ),
}
DIRECTORY_OUTPUTS = {"reproduce -o", "sweep run -o"}


def _unwritable(case: str, tmp_path: Path) -> tuple[Path, str]:
    """An output path that cannot be written, and the reason the message must give."""
    if case == "proc":
        return Path("/proc/bearingsim-test/out"), "it is under /proc, a virtual file system"
    if case == "parent is a file":
        (tmp_path / "afile").write_text("x")
        return tmp_path / "afile" / "out", f"'{tmp_path / 'afile'}' is a file, not a directory"
    ro = tmp_path / "ro"
    ro.mkdir()
    ro.chmod(0o555)
    return ro / "out", f"permission denied in '{ro}'"


@pytest.mark.parametrize(
    "case",
    [
        "proc",
        "parent is a file",
        pytest.param("no permission", marks=pytest.mark.skipif(ROOT, reason=ROOT_SKIP)),
    ],
)
@pytest.mark.parametrize("command", list(OUTPUTS))
def test_an_unwritable_output_is_refused_before_any_work(
    run_cli, monkeypatch, tmp_path, command, case
):
    """Issue 14, "Tracebacks": FileNotFoundError/PermissionError/FileExistsError from simulate,
    ias, life, stiffness, vsm-trace, --plot, reproduce --out, sweep run --out, after the whole
    computation ran. Now: one line naming the option, the path and the reason, exit 2, before
    the work starts, nothing written."""
    argv, option, work = OUTPUTS[command]

    def work_started(*a, **k):
        raise AssertionError(f"{work} ran before the output check")

    monkeypatch.setattr(work, work_started)
    out, reason = _unwritable(case, tmp_path)
    suffix = "" if command in DIRECTORY_OUTPUTS else ".png" if "--plot" in option else ".nc"
    out = out.with_name(out.name + suffix)
    fields = {"out": out, "ok": tmp_path / "ok.nc", "file": tmp_path / "in.csv"}
    before = _tree(tmp_path)
    msg = _one_line_error(run_cli(*[a.format(**fields) for a in argv]))
    assert msg.startswith(f"error: {option} = '{out}' cannot be written: {reason}"), msg
    valid = "a directory that can be" if command in DIRECTORY_OUTPUTS else "a regular file in"
    assert f"; valid: {valid}" in msg, msg
    assert _tree(tmp_path) == before, "nothing written"


def test_the_output_check_covers_every_output_option_of_every_command():
    """Every option of type click.Path that is not an input is in OUTPUTS (a new output option
    needs its check_outputs call and a row here)."""
    import click

    from bearingsim.cli import COMMANDS, cli

    inputs = {
        "--bearing-file",
        "--conditions",
        "scenario_file",
        "scenario",
        "file",
        "spec_file",
        "dataset",
    }
    found = set()
    ctx = click.Context(cli)
    for name in COMMANDS:
        cmd = cli.get_command(ctx, name)
        subs = cmd.commands.values() if isinstance(cmd, click.Group) else [cmd]
        for sub in subs:
            label = f"{name} {sub.name}" if sub is not cmd else name
            for p in sub.params:
                if isinstance(p.type, click.Path) and not ({p.name, *p.opts} & inputs):
                    opt = "-o" if "-o" in p.opts else p.opts[-1]
                    found.add(f"{label} {opt}")
    assert found == set(OUTPUTS)


@pytest.mark.skipif(ROOT, reason=ROOT_SKIP)
def test_a_read_only_directory_refused_for_the_library_writers(tmp_path):
    ro = tmp_path / "ro"
    ro.mkdir()
    ro.chmod(0o555)
    with pytest.raises(ConfigError, match=r"^path = .* cannot be written: permission denied"):
        _small_result().save(ro / "r.nc")
    assert not any(ro.iterdir())


def _deny(monkeypatch, folder: Path, err: int) -> None:
    """Make creating a file under ``folder`` fail with ``err`` (as a read-only mount or a folder
    without write permission does, even for root)."""
    real = os.open

    def fake(path, flags, *args, **kw):
        if str(path).startswith(str(folder)) and flags & os.O_CREAT:
            raise OSError(err, os.strerror(err), str(path))
        return real(path, flags, *args, **kw)

    monkeypatch.setattr(atomic.os, "open", fake)


@pytest.mark.parametrize(
    ("err", "reason"),
    [
        (errno.EACCES, "permission denied in '{d}'"),
        (errno.EPERM, "permission denied in '{d}'"),
        (errno.EROFS, "'{d}' is on a read-only file system"),
        (errno.ENOSPC, "no space left in '{d}'"),
    ],
    ids=["EACCES", "EPERM", "EROFS", "ENOSPC"],
)
def test_a_folder_that_refuses_files_is_reported_with_its_reason(
    monkeypatch, run_cli, tmp_path, err, reason
):
    """What the probe of check_output finds (simulated, so that it also runs as root): the
    CLI refuses before the work, the library's writers say the same in one line."""
    d = tmp_path / "d"
    d.mkdir()
    _deny(monkeypatch, d, err)
    why = reason.format(d=d)
    with pytest.raises(ConfigError, match="cannot be written: " + re.escape(why)):
        check_output(d / "x.nc", "-o/--output")
    msg = _one_line_error(run_cli("load", "6205", "--fy-n", "100", "--plot", d / "p.png"))
    assert f"--plot = '{d / 'p.png'}' cannot be written: {why}" in msg
    with pytest.raises(ConfigError, match=r"^path = '.*r\.nc' cannot be written: "):
        _small_result().save(d / "sub" / "r.nc")
    assert list(d.iterdir()) == [], "no temporary, no folder left"


def test_an_existing_output_directory_is_looked_at_never_written(monkeypatch, tmp_path):
    """A sweep store may be in use by another client: its folder is checked with os.access,
    no probe file goes into it."""
    store = tmp_path / "store"
    store.mkdir()
    real = os.access
    monkeypatch.setattr(atomic.os, "access", lambda p, mode: Path(p) != store and real(p, mode))
    with pytest.raises(ConfigError, match=f"cannot be written: permission denied in '{store}'"):
        check_output(store, "-o/--output", directory=True)
    monkeypatch.setattr(atomic.os, "open", None)  # any probe would fail loudly
    monkeypatch.setattr(atomic.os, "access", real)
    assert check_output(store, "-o/--output", directory=True) == store


@pytest.mark.parametrize(
    ("path", "directory", "reason"),
    [
        ("/proc/self/out.nc", False, "it is under /proc, a virtual file system of the kernel"),
        ("/sys/out", True, "it is under /sys, a virtual file system of the kernel"),
        ("/dev/null", False, "it is a character device, not a regular file"),
        ("", False, "the path is empty"),
        ("{tmp}", False, "it is a directory, not a regular file"),
        ("{tmp}/afile", True, "it is a file, not a directory"),
        ("{tmp}/afile/x/y/out.nc", False, "'{tmp}/afile' is a file, not a directory"),
    ],
)
def test_check_output_reasons(tmp_path, path, directory, reason):
    (tmp_path / "afile").write_text("x")
    path = path.format(tmp=tmp_path)
    with pytest.raises(ConfigError) as exc:
        check_output(path, "--x", directory=directory)
    assert str(exc.value).startswith(
        f"--x = {path!r} cannot be written: {reason.format(tmp=tmp_path)}; valid: "
    ), str(exc.value)


def test_check_output_accepts_new_folders_and_existing_files_and_writes_nothing(tmp_path):
    (tmp_path / "old.nc").write_text("x")
    assert check_output(tmp_path / "a" / "b" / "new.nc", "-o") == tmp_path / "a" / "b" / "new.nc"
    check_output(tmp_path / "old.nc", "-o")
    check_output(tmp_path / "rep", "-o", directory=True)
    check_output(tmp_path, "-o", directory=True)
    assert _tree(tmp_path) == ["old.nc"], "no folder created, no probe left"


def test_the_library_writers_refuse_in_one_line_and_leave_nothing(tmp_path):
    """Result.save, write_json, atomic_open: the one-line error instead of an OSError."""
    (tmp_path / "afile").write_text("x")
    for write in (
        lambda p: _small_result().save(p),
        lambda p: write_json(p, {"a": 1}),
        lambda p: atomic_open(p).__enter__(),
    ):
        for p, why in (
            (tmp_path / "afile" / "r.nc", "is a file, not a directory"),
            (Path("/proc/bearingsim-test.nc"), "virtual file system"),
            (tmp_path, "it is a directory, not a regular file"),
        ):
            with pytest.raises(ConfigError, match=f"^path = '{p}' cannot be written: .*{why}"):
                write(p)
    assert _tree(tmp_path) == ["afile"]


def test_a_device_is_never_replaced(tmp_path):
    """``-o /dev/null`` would have renamed a regular file over the device (as root)."""
    with pytest.raises(ConfigError, match="is a character device, not a regular file"):
        write_json("/dev/null", {})
    assert stat.S_ISCHR(os.stat("/dev/null").st_mode)


# ----------------------------------------------------------------------------------------------
# modes, failures


@pytest.fixture
def umask():
    """``os.umask``, the process umask restored after the test."""
    old = os.umask(0o022)
    os.umask(old)
    yield os.umask
    os.umask(old)


@pytest.mark.parametrize("mask", [0o022, 0o027, 0o002])
def test_outputs_get_the_mode_the_umask_gives(tmp_path, umask, mask):
    """Issue 14: every output was created 0600 whatever the umask (tempfile.mkstemp)."""
    from bearingsim.report.figures import save_figure

    umask(mask)
    import matplotlib.pyplot as plt

    written = [
        _small_result().save(tmp_path / "r.nc"),
        save_figure(plt.figure(), tmp_path / "f.png"),
    ]
    write_json(tmp_path / "j.json", {"a": 1})
    with atomic_open(tmp_path / "t.csv") as fh:
        fh.write("1,2\n")
    written += [tmp_path / "j.json", tmp_path / "t.csv"]
    for p in written:
        assert stat.S_IMODE(os.stat(p).st_mode) == 0o666 & ~mask, p
    assert _tree(tmp_path) == ["f.png", "j.json", "r.nc", "t.csv"], "no temporary left"


def test_cli_outputs_get_the_mode_the_umask_gives(run_cli, tmp_path, umask):
    umask(0o022)
    png = tmp_path / "load.png"
    r = run_cli("load", "6205", "--fy-n", "1000", "--plot", png, "--json")
    assert r.code == 0, r.err
    assert stat.S_IMODE(os.stat(png).st_mode) == 0o644


def test_a_failed_write_leaves_nothing_and_keeps_the_old_file(tmp_path):
    out = tmp_path / "new" / "deeper" / "out.json"
    with pytest.raises(RuntimeError, match="writer failed"), atomic_path(out) as tmp:
        tmp.write_text("half")
        raise RuntimeError("writer failed")
    assert _tree(tmp_path) == [], "no temporary, and the folders created for it removed"
    old = tmp_path / "old.json"
    old.write_text("complete")
    with pytest.raises(KeyboardInterrupt), atomic_open(old) as fh:
        fh.write("half")
        raise KeyboardInterrupt
    assert old.read_text() == "complete" and _tree(tmp_path) == ["old.json"]


def test_a_full_disk_while_writing_is_one_line(tmp_path):
    out = tmp_path / "out.nc"
    with pytest.raises(ConfigError, match=r"^path = '.*out.nc' cannot be written: no space"):
        with atomic_path(out):
            raise OSError(errno.ENOSPC, os.strerror(errno.ENOSPC))
    assert _tree(tmp_path) == []


# ----------------------------------------------------------------------------------------------
# temporaries of killed writers


def _temp(dest: Path, pid: int, start: int, host: str | None = None, suffix=".json") -> Path:
    host = host or atomic._host_tag()
    p = dest.parent / f".{dest.name}.tmp-{host}-{pid}-{start}-0123abcd{suffix}"
    p.write_bytes(b"x" * 100)
    return p


def _dead_pid() -> int:
    """The process id of a process that has exited and been reaped."""
    code = "import os; print(os.getpid())"
    r = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    return int(r.stdout)


def test_the_next_write_removes_only_the_temporaries_of_gone_writers(tmp_path):
    dest = tmp_path / "out.json"
    me = os.getpid()
    dead = _temp(dest, _dead_pid(), 0)
    dead_started = _temp(dest, _dead_pid(), 12345)
    reused = _temp(dest, me, atomic._start_time(me) + 1)  # this pid, but a process before us
    alive = _temp(dest, me, atomic._start_time(me))
    other_host = _temp(dest, _dead_pid(), 0, host="00000000")
    other_file = _temp(tmp_path / "other.json", _dead_pid(), 0)
    legacy_old = tmp_path / ".out.json.ab12cd_9.json"
    legacy_new = tmp_path / ".out.json.zz12cd_9.json"
    for p in (legacy_old, legacy_new):
        p.write_bytes(b"x")
    old = time.time() - LEGACY_TEMP_AGE_S - 60
    os.utime(legacy_old, (old, old))
    user_file = tmp_path / ".out.json.notes"
    user_file.write_text("mine")
    write_json(dest, {"a": 1})
    assert json.loads(dest.read_text()) == {"a": 1}
    for p in (dead, dead_started, reused, legacy_old):
        assert not p.exists(), p
    for p in (alive, other_host, other_file, legacy_new, user_file):
        assert p.exists(), p
    assert clean_stale_temporaries(dest) == []


_WRITER = """
import sys, time
from bearingsim.io.atomic import atomic_path
with atomic_path(sys.argv[1]) as tmp:
    tmp.write_bytes(b"half-written " * 100000)
    print(tmp, flush=True)
    sys.stdin.readline()  # killed here, or told to finish
    tmp.write_bytes(b"from the other writer")
"""


@contextlib.contextmanager
def _writer(dest: Path):
    """A process writing ``dest`` through atomic_path, stopped half-way; yields (process, its
    temporary)."""
    proc = subprocess.Popen(
        [sys.executable, "-c", _WRITER, str(dest)],
        stdin=subprocess.PIPE,
        stdout=subprocess.PIPE,
        text=True,
        env=ENV,
    )
    try:
        tmp = Path(proc.stdout.readline().strip())
        assert tmp.is_file() and tmp.parent == dest.parent, tmp
        yield proc, tmp
    finally:
        with contextlib.suppress(ProcessLookupError):
            proc.kill()
        proc.wait(timeout=30)
        proc.stdin.close()
        proc.stdout.close()


@pytest.mark.integration
@pytest.mark.parametrize("reaped", [True, False], ids=["reaped", "zombie"])
def test_a_sigkilled_writer_leaves_a_temporary_that_the_next_write_removes(tmp_path, reaped):
    """Issue 14: a killed run leaves hidden temporary files (``.out.nc.XXXX.nc``, up to 48 MB)
    that nothing removes. Now the next write to the same place removes them (the writer's
    process is in the name; a zombie not yet reaped by its parent counts as gone)."""
    dest = tmp_path / "out.nc"
    with _writer(dest) as (proc, tmp):
        os.kill(proc.pid, signal.SIGKILL)
        if reaped:
            proc.wait(timeout=30)
        else:
            deadline = time.monotonic() + 30
            while atomic._proc_stat(proc.pid)[0] != "Z":
                assert time.monotonic() < deadline
                time.sleep(0.01)
        assert tmp.exists() and not dest.exists(), "the kill left its temporary"
        _small_result().save(dest)
        assert not tmp.exists(), "removed by the next write"
        assert load_result(dest).identical(_small_result())
        assert _tree(tmp_path) == ["out.nc"]


@pytest.mark.integration
def test_two_processes_writing_the_same_file_keep_each_others_temporaries(tmp_path):
    dest = tmp_path / "out.nc"
    with _writer(dest) as (proc, tmp):
        _small_result().save(dest)
        assert tmp.exists(), "a running writer's temporary is kept"
        proc.stdin.write("finish\n")
        proc.stdin.flush()
        assert proc.wait(timeout=30) == 0
        assert dest.read_bytes() == b"from the other writer", "the last rename wins"
    assert _tree(tmp_path) == ["out.nc"]


def test_threads_writing_the_same_file_at_once(tmp_path):
    dest = tmp_path / "out.json"
    errors = []

    def write(i: int) -> None:
        try:
            for _ in range(20):
                write_json(dest, {"writer": i, "pad": "x" * 10000})
        except Exception as exc:  # pragma: no cover - the assertion below reports it
            errors.append(exc)

    threads = [threading.Thread(target=write, args=(i,)) for i in range(4)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    assert not errors
    assert json.loads(dest.read_text())["writer"] in range(4)
    assert _tree(tmp_path) == ["out.json"]


_KILLED_PLOT = """
import sys, time
import matplotlib.figure
def slow_savefig(self, fname, **kw):
    with open(fname, "wb") as fh:
        fh.write(b"\\x89PNG half")
    print(fname, flush=True)
    time.sleep(600)
matplotlib.figure.Figure.savefig = slow_savefig
from bearingsim.cli import main
main(sys.argv[1:])
"""


@pytest.mark.integration
def test_cli_a_run_killed_while_writing_then_run_again(run_cli, tmp_path):
    """End to end: ``load --plot`` killed while writing its PNG leaves a hidden temporary; the
    same command run again writes the PNG and removes it."""
    png = tmp_path / "load.png"
    argv = ["load", "6205", "--fy-n", "1000", "--plot", str(png)]
    proc = subprocess.Popen(
        [sys.executable, "-c", _KILLED_PLOT, *argv], stdout=subprocess.PIPE, text=True, env=ENV
    )
    try:
        tmp = Path(proc.stdout.readline().strip())
        proc.kill()
        proc.wait(timeout=30)
    finally:
        with contextlib.suppress(ProcessLookupError):
            proc.kill()
        proc.wait(timeout=30)
        proc.stdout.close()
    assert tmp.name.startswith(".load.png.tmp-") and tmp.exists()
    r = run_cli(*argv)
    assert r.code == 0, r.err
    assert _tree(tmp_path) == ["load.png"]
    assert png.read_bytes().startswith(b"\x89PNG\r\n\x1a\n")


def test_an_output_that_is_a_symbolic_link_is_written_through_it(tmp_path):
    # twenty-first session: the rename replaced the link by a file and left its target with
    # the old content, which anyone reading through the target then took for the new output
    from bearingsim.io.atomic import atomic_open

    (tmp_path / "data").mkdir()
    target = tmp_path / "data" / "target.txt"
    target.write_text("old")
    link = tmp_path / "link.txt"
    link.symlink_to(target)
    with atomic_open(link) as fh:
        fh.write("new")
    assert link.is_symlink() and target.read_text() == "new"
    assert sorted(p.name for p in (tmp_path / "data").iterdir()) == ["target.txt"]


def test_an_output_that_links_to_the_commands_input_is_refused(tmp_path, monkeypatch):
    # twenty-first session: outputs are written through symbolic links, so `simulate sc.toml
    # -o o.nc` with o.nc -> sc.toml replaced the scenario file by the netCDF result (and
    # `analyze a.csv --plot p.png`, p.png -> a.csv, the record by a PNG)
    from bearingsim.cli import main

    monkeypatch.chdir(tmp_path)
    sc = tmp_path / "sc.toml"
    sc.write_text('model = "vsm"\nfault = "outer"\nduration_s = 0.01\nfs_hz = 12000.0\n')
    (tmp_path / "o.nc").symlink_to(sc)
    text = sc.read_text()
    with pytest.raises(SystemExit) as e:
        main(["simulate", "sc.toml", "-o", "o.nc"])
    assert e.value.code == 2 and sc.read_text() == text
    rec = tmp_path / "a.csv"
    rec.write_text("t,x\n" + "".join(f"{k / 100},{math.sin(k)}\n" for k in range(400)))
    (tmp_path / "p.png").symlink_to(rec)
    with pytest.raises(SystemExit) as e:
        main(["analyze", "a.csv", "--rpm", "1796", "--plot", "p.png"])
    assert e.value.code == 2 and rec.read_text().startswith("t,x\n")


def test_a_full_disk_names_the_option_and_asks_for_space(tmp_path, monkeypatch, capsys):
    # twenty-first session: the full-disk error named `path` (the read-only one -o/--output)
    # and advised "a regular file in a writable directory"
    import xarray as xr

    from bearingsim.cli import main

    def full(self, *args, **kw):
        raise OSError(errno.ENOSPC, "No space left on device")

    monkeypatch.setattr(xr.Dataset, "to_netcdf", full)
    with pytest.raises(SystemExit) as e:
        main(["simulate", "--duration-s", "0.01", "--fs-hz", "12000", "-o", str(tmp_path / "r.nc")])
    err = capsys.readouterr().err
    assert e.value.code == 2 and err.count("\n") == 1, err
    assert err.startswith("error: -o/--output = ") and "no space left" in err
    assert err.rstrip().endswith("valid: free space there, or another path")
    assert not (tmp_path / "r.nc").exists()


def test_outputs_that_are_files_an_input_names_or_a_derived_figure_are_refused(
    tmp_path, monkeypatch, capsys
):
    # twenty-first session (a helper on this session's changes): `simulate sc.toml -o lb.nc`
    # with lb.nc -> the scenario's bearing_file replaced the bearing file; `vsm-trace -o
    # p_ball2.png --plot p.png --ball 2` replaced the -o file by the ball figure; the refusal
    # named parameters as the code calls them (rig-name) instead of the option typed (--rig)
    import bearingsim.catalog
    from bearingsim.cli import main

    monkeypatch.chdir(tmp_path)
    cat = Path(bearingsim.catalog.__file__).parent / "6205.toml"
    (tmp_path / "b.toml").write_text(cat.read_text(encoding="utf-8"), encoding="utf-8")
    (tmp_path / "sc.toml").write_text(
        'model = "vsm"\nbearing_file = "b.toml"\nduration_s = 0.01\nfs_hz = 12000.0\n'
    )
    (tmp_path / "lb.nc").symlink_to(tmp_path / "b.toml")
    before = (tmp_path / "b.toml").read_text()
    with pytest.raises(SystemExit) as e:
        main(["simulate", "sc.toml", "-o", "lb.nc"])
    assert e.value.code == 2 and (tmp_path / "b.toml").read_text() == before
    assert "is the scenario's bearing_file" in capsys.readouterr().err
    with pytest.raises(SystemExit) as e:
        main(["vsm-trace", "--fy-n", "500", "--cage-revs", "0.05", "-o", "p_ball2.png",
              "--plot", "p.png", "--ball", "2"])  # fmt: skip
    assert e.value.code == 2 and "is also -o/--output" in capsys.readouterr().err
    (tmp_path / "r.nc").symlink_to(tmp_path / "b.toml")
    with pytest.raises(SystemExit) as e:
        main(["simulate", "--bearing-file", "b.toml", "-o", "r.nc"])
    assert e.value.code == 2 and "is the input --bearing-file = 'b.toml'" in capsys.readouterr().err
