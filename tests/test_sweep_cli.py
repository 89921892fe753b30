"""``bearingsim sweep plan|run|summary``: JSON contracts, text output and bad input (one line on
stderr, exit code 2, no dataset left behind)."""

from __future__ import annotations

import json
import sys

import pytest

from bearingsim.sweep.spec import SweepSpec

SPEC = """
[sweep]
label = "fault"
[base]
model = "dem"
duration_s = 0.05
fs_hz = 4000.0
[axes]
fault = ["outer", "inner"]
rpm = [1730.0, 1797.0]
"""


@pytest.fixture
def spec_file(tmp_path):
    p = tmp_path / "sweep.toml"
    p.write_text(SPEC)
    return p


def test_plan_json_and_text(run_cli, spec_file):
    r = run_cli("sweep", "plan", spec_file, "--json", "--workers", "2")
    assert r.code == 0, r.err
    d = r.json()
    assert (d["n_runs"], d["axes"], d["channels"]) == (
        4,
        {"fault": 2, "rpm": 2},
        ["acc_x", "acc_y"],
    )
    assert d["n_samples"] == [200, 200] and d["workers"] == 2
    # 4 runs x 2 channels x 200 samples x 8 bytes
    assert d["bytes_raw"] == 4 * 2 * 200 * 8
    assert 0 < d["bytes_estimate"] < 2 * d["bytes_raw"]
    assert d["compute_s_per_run"] > 0 and len(d["timing"]) == 3
    assert d["compute_s_total"] == pytest.approx(4 * d["compute_s_per_run"], rel=1e-12)
    assert d["spec_hash"] == SweepSpec.from_toml(spec_file).spec_hash
    r = run_cli("sweep", "plan", spec_file, "--timing-runs", "0")
    assert r.code == 0 and "4 runs (cartesian: fault 2 x rpm 2)" in r.out
    assert "disk ~" in r.out and "timing runs" not in r.out


@pytest.mark.integration
def test_run_summary_resume(run_cli, spec_file, tmp_path):
    out = tmp_path / "ds.zarr"
    r = run_cli("sweep", "run", spec_file, "-o", out, "--workers", "1", "--json")
    assert r.code == 0, r.err
    d = r.json()
    assert (d["n_runs"], d["n_computed"], d["n_ok"], d["n_pending"], d["created"]) == (
        4,
        4,
        4,
        0,
        True,
    )
    assert d["throughput_runs_per_s"] > 0 and d["cluster"].startswith("local cluster, 1")
    r = run_cli("sweep", "summary", out, "--json")
    assert r.code == 0
    s = r.json()
    assert s["by_label"] == {
        "inner": {"ok": 2, "failed": 0, "pending": 0},
        "outer": {"ok": 2, "failed": 0, "pending": 0},
    }
    assert s["by_axis"]["rpm"]["1797.0"]["ok"] == 2 and s["complete"] and s["failures"] == []
    r = run_cli("sweep", "summary", out, "--label", "rpm")
    assert r.code == 0 and "4 runs: 4 ok, 0 failed, 0 pending" in r.out and "1730.0" in r.out
    # the text lists the counts by axis value too, as its help says (only --json had them)
    r = run_cli("sweep", "summary", out)
    assert "  by rpm:" in r.out and "  by fault:" in r.out and r.out.count("2 ok") == 4
    r = run_cli("sweep", "run", spec_file, "-o", out)
    assert r.code == 0 and "4 already committed, 0 computed" in r.out
    # the same spec file, reformatted, is the same sweep
    spec_file.write_text(SPEC.replace('["outer", "inner"]', '{ values = ["outer", "inner"] }'))
    assert run_cli("sweep", "run", spec_file, "-o", out, "--json").json()["n_skipped"] == 4


def _dataset_spec(tmp_path):
    p = tmp_path / "other.toml"
    p.write_text(SPEC.replace("1797.0", "1772.0"))
    return p


@pytest.mark.parametrize(
    "args, match",
    [
        (["sweep", "run", "{missing}", "-o", "{out}"], r"sweep file '.*nope.toml' cannot be"),
        (["sweep", "run", "{bad_toml}", "-o", "{out}"], r"is not valid TOML"),
        (
            ["sweep", "run", "{bad_axis}", "-o", "{out}"],
            r"axis 'rmp' is not a scenario key; valid: model",
        ),
        (
            ["sweep", "run", "{bad_value}", "-o", "{out}"],
            r"run 1: rpm = -5 r/min is out of range; valid range \(0, inf\) r/min",
        ),
        (
            ["sweep", "run", "{spec}", "-o", "{out}", "--workers", "0"],
            r"workers = 0 is out of range; valid range \[1, inf\)",
        ),
        (
            ["sweep", "run", "{spec}", "-o", "{out}", "--runs-per-task", "0"],
            r"runs_per_task = 0 is out of range; valid range \[1, inf\)",
        ),
        (
            ["sweep", "run", "{spec}", "-o", "{out}", "--scheduler", "my-laptop"],
            r"scheduler = 'my-laptop' is invalid; valid: an address like tcp://HOST:PORT",
        ),
        (
            [
                "sweep",
                "run",
                "{spec}",
                "-o",
                "{out}",
                "--scheduler",
                "tcp://127.0.0.1:9",
                "--workers",
                "2",
            ],
            r"workers = 2 applies to a local cluster only; with scheduler = 'tcp://127.0.0.1:9'",
        ),
        (
            [
                "sweep",
                "run",
                "{spec}",
                "-o",
                "{out}",
                "--scheduler",
                "tcp://127.0.0.1:9",
                "--connect-timeout-s",
                "1",
            ],
            r"scheduler = 'tcp://127.0.0.1:9' is not reachable within 1 s \(.*\); valid: the "
            r"address printed by a running 'dask scheduler'",
        ),
        (  # a helper (twenty-seventh session): "not reachable (OSError)"
            ["sweep", "run", "{spec}", "-o", "{out}", "--scheduler", "tcp://127.0.0.1:70000"],
            r"scheduler = 'tcp://127.0.0.1:70000' has port 70000, out of range; valid range "
            r"\[1, 65535\]",
        ),
        (  # ... and a TypeError traceback, then a TimeoutError one at exit
            ["sweep", "run", "{spec}", "-o", "{out}", "--scheduler", "tls://127.0.0.1:9"],
            r"scheduler = 'tls://127.0.0.1:9' needs TLS, and Dask has no TLS configuration",
        ),
        (
            ["sweep", "run", "{spec}", "-o", "{out}", "--connect-timeout-s", "0"],
            r"connect_timeout_s = 0 s is out of range; valid range \(0, inf\) s",
        ),
        (
            ["sweep", "run", "{spec}", "-o", "{afile}"],
            r"-o/--output = '.*afile.txt' cannot be written: it is a file, not a directory; "
            r"valid: a directory",
        ),
        (
            ["sweep", "run", "{spec}", "-o", "{notds}"],
            r"dataset = '.*notds' is not a bearingsim sweep dataset \(no readable .zattrs\)",
        ),
        (
            ["sweep", "run", "{bad_channel}", "-o", "{out}", "--workers", "1"],
            r"channel 'acc_z' is not produced by the runs with model = 'dem', per_ball = False; "
            r"valid: disp_x",
        ),
        (
            ["sweep", "plan", "{spec}", "--timing-runs", "-1"],
            r"timing_runs = -1 is out of range; valid range \[0, inf\)",
        ),
        (
            ["sweep", "plan", "{spec}", "--timing-duration-s", "0"],
            r"timing_duration_s = 0 s is out of range; valid range \(0, inf\) s",
        ),
        (["sweep", "summary", "{notds}"], r"is not a bearingsim sweep dataset"),
        (
            ["sweep", "summary", "{missing}"],  # it said "is not a sweep dataset (no
            # readable .zattrs)" (exploratory testing, twenty-seventh session)
            r"dataset = '.*nope.toml' does not exist; valid: a sweep dataset directory",
        ),
    ],
)
def test_bad_input(args, match, run_cli, spec_file, tmp_path):
    files = {
        "spec": spec_file,
        "out": tmp_path / "new.zarr",
        "missing": tmp_path / "nope.toml",
        "afile": tmp_path / "afile.txt",
        "notds": tmp_path / "notds",
    }
    files["afile"].write_text("x")
    files["notds"].mkdir()
    (files["notds"] / "data.csv").write_text("1,2\n")
    for name, text in {
        "bad_toml": "[axes\nrpm = 1",
        "bad_axis": SPEC.replace("rpm = [", "rmp = ["),
        "bad_value": SPEC.replace("1797.0", "-5.0"),
        "bad_channel": SPEC.replace('label = "fault"', 'channels = ["acc_x", "acc_z"]'),
    }.items():
        files[name] = tmp_path / f"{name}.toml"
        files[name].write_text(text)
    r = run_cli(*[a.format(**files) for a in args])
    assert r.code == 2, (r.out, r.err)
    assert r.out == ""
    lines = r.err.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("error: "), r.err
    assert pytest.importorskip("re").search(match, lines[0]), lines[0]
    assert not files["out"].exists()  # nothing written
    assert sorted(p.name for p in files["notds"].iterdir()) == ["data.csv"]


@pytest.mark.integration
def test_spec_change_refused_then_force_new(run_cli, spec_file, tmp_path):
    out = tmp_path / "ds.zarr"
    assert run_cli("sweep", "run", spec_file, "-o", out, "--workers", "1", "--json").code == 0
    other = _dataset_spec(tmp_path)
    r = run_cli("sweep", "run", other, "-o", out, "--workers", "1")
    assert r.code == 2 and r.out == ""
    assert r.err.strip() == (
        f"error: out = '{out}' holds a dataset of a different sweep spec (differs in: axes.rpm); "
        "use another -o/--output, or --force-new to replace it"
    )
    r = run_cli("sweep", "run", other, "-o", out, "--workers", "1", "--force-new", "--json")
    assert r.code == 0 and r.json()["created"] and r.json()["n_ok"] == 4
    s = json.loads(run_cli("sweep", "summary", out, "--json").out)
    assert set(s["by_axis"]["rpm"]) == {"1730.0", "1772.0"}
    r = run_cli("sweep", "summary", out, "--label", "speed")
    assert r.code == 2 and "label = 'speed' is not stored per run; valid: fault, rpm" in r.err


@pytest.mark.integration
def test_docs_python_example_runs(tmp_path, monkeypatch):
    """The Python block of docs/sweeps.md runs as written (on a small sweep.toml)."""
    import re
    from pathlib import Path

    doc = (Path(__file__).resolve().parents[1] / "docs" / "sweeps.md").read_text()
    code = re.search(r"```python\n(.*?)```", doc, re.S).group(1)
    monkeypatch.chdir(tmp_path)
    (tmp_path / "sweep.toml").write_text(SPEC)
    ns = {"__name__": "__main__"}
    # the example's names are main()'s locals (twenty-first session: code outside main() ran
    # in every worker process the local cluster started, so the example crashed as a script)
    seen: dict = {}

    def keep(frame, event, arg):
        if event == "return" and frame.f_code.co_name == "main":
            seen.update(frame.f_locals)

    sys.setprofile(keep)
    try:
        exec(compile(code, "docs/sweeps.md", "exec"), ns)
    finally:
        sys.setprofile(None)
    ns = seen
    assert ns["report"].n_ok == 4
    assert ns["X"].shape == (2, 2, 200) and list(ns["y"]) == ["outer", "inner"]
    assert len(ns["test"]) == 2 and ns["r"].fs_hz == 4000.0
    assert ns["outer"].shape == (2, 200)


@pytest.mark.integration
def test_run_prints_each_runs_warning_once_and_summary_lists_the_runs(run_cli, tmp_path):
    spec = tmp_path / "w.toml"
    spec.write_text(
        '[base]\nmodel = "vsm"\nduration_s = 0.02\nrig = "cwru-de-12k"\n'
        '[axes]\nfs_hz = [12000.0, 48000.0]\nfault = ["none", "outer"]\n'
    )
    out = tmp_path / "w.zarr"
    r = run_cli("sweep", "run", spec, "-o", out, "--workers", "1")
    assert r.code == 0, r.err
    lines = [x for x in r.err.splitlines() if "RigRateWarning" in x]
    assert len(lines) == 1 and lines[0].startswith("warning: RigRateWarning: rig 'cwru-de-12k'")
    assert lines[0].endswith("(in 2 of the 4 runs computed; 'sweep summary' lists the runs)")
    r = run_cli("sweep", "summary", out)
    assert r.code == 0 and "  warning in 2 run(s) (2, 3): RigRateWarning: rig" in r.out


def test_a_dataset_removed_or_unwritable_during_a_sweep_is_one_line(
    run_cli, spec_file, tmp_path, monkeypatch
):
    """Exploratory testing (twenty-seventh session): the dataset deleted while a sweep wrote it
    ended in ``FileNotFoundError`` with a traceback, exit 1; a dataset whose ``signal/`` was
    not writable in a ``PermissionError`` traceback. Both are one line, exit 2."""
    import errno

    from bearingsim.sweep import execute

    out = tmp_path / "o.zarr"

    def removed(*args, **kw):
        raise FileNotFoundError(errno.ENOENT, "No such file or directory", str(out / "s" / "t"))

    monkeypatch.setattr(execute, "run_sweep", removed)
    r = run_cli("sweep", "run", spec_file, "-o", out, "--workers", "1")
    assert r.code == 2 and r.err == (
        f"error: -o/--output = '{out}' was removed or moved while this sweep wrote it; run the "
        "same command again to start it anew\n"
    ), r.err

    def denied(*args, **kw):
        out.mkdir(exist_ok=True)
        raise PermissionError(errno.EACCES, "Permission denied", str(out / "signal" / "t"))

    monkeypatch.setattr(execute, "run_sweep", denied)
    r = run_cli("sweep", "run", spec_file, "-o", out, "--workers", "1")
    assert r.code == 2 and r.err.count("\n") == 1, r.err
    assert r.err.startswith(f"error: -o/--output = '{out}' cannot be written: permission denied")


def test_the_working_folder_is_refused_as_the_output(run_cli, spec_file, tmp_path, monkeypatch):
    """Exploratory testing (twenty-seventh session): ``-o .`` in an empty folder crashed with
    ``OSError: Invalid argument: '.'``, and ``-o "$PWD"`` removed the working folder (an empty
    folder is taken as a new dataset) before crashing; both, and a parent, are one line."""
    work = tmp_path / "w" / "e"
    work.mkdir(parents=True)
    monkeypatch.chdir(work)
    for out in (".", str(work), str(work.parent)):
        r = run_cli("sweep", "run", spec_file, "-o", out, "--workers", "1")
        assert r.code == 2 and r.err == (
            f"error: -o/--output = {out!r} is the working folder or one of its parents; valid: "
            "a dataset directory inside or beside it (e.g. -o sweep.zarr)\n"
        ), r.err
    assert work.is_dir()


def test_a_full_disk_during_a_sweep_is_one_line(run_cli, spec_file, tmp_path, monkeypatch):
    # twenty-first session: zarr's OSError (errno 28) from the dataset's creation or a commit
    # came out as a traceback, exit 1 (reproduced on a 12 kB and a 400 kB tmpfs)
    import errno

    from bearingsim.sweep import execute

    def full(*args, **kw):
        raise OSError(errno.ENOSPC, "No space left on device", str(tmp_path / "o.zarr" / "x"))

    monkeypatch.setattr(execute, "run_sweep", full)
    r = run_cli("sweep", "run", spec_file, "-o", tmp_path / "o.zarr", "--workers", "1")
    assert r.code == 2, r.err
    assert r.err.count("\n") == 1 and r.err.startswith("error: -o/--output = ")
    assert "no space left" in r.err and "run the same command to resume" in r.err
