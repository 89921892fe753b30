"""Sweeps across real processes: SIGKILL and SIGINT of the client part-way and resume, and a
Dask scheduler with two workers started on loopback by the test (one worker SIGKILLed
mid-sweep). Every process the tests start is killed in ``finally`` blocks."""

from __future__ import annotations

import contextlib
import json
import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import numpy as np
import pytest
from numpy.testing import assert_array_equal

import bearingsim
from bearingsim.simulation import simulate
from bearingsim.sweep.dataset import OK, open_dataset, read_status
from bearingsim.sweep.spec import SweepSpec

#: runs of ~0.2 s each (DEM, 400 samples, 1250 RK4 steps per sample), so that a kill lands
#: part-way through the sweep
SLOW = """
[base]
model = "dem"
duration_s = 0.1
fs_hz = 4000.0
dt_s = 2e-7
noise_rms_m_per_s2 = 0.2
[sweep]
per_run_seed = true
[axes]
fault = ["outer", "inner"]
rpm = [1730.0, 1750.0, 1772.0, 1797.0]
"""
N_RUNS = 8
SRC = str(Path(bearingsim.__file__).resolve().parents[1])
ENV = {**os.environ, "PYTHONPATH": SRC}
TIMEOUT_S = 120.0
#: every test here starts real processes (CLI clients, a scheduler, workers) and kills some
pytestmark = pytest.mark.integration


def n_committed(out: Path) -> int:
    try:
        return int(np.sum(read_status(out) == OK)) if (out / ".zmetadata").exists() else 0
    except Exception:  # the store is being created
        return 0


def committed_pids(out: Path) -> set[int]:
    """Worker pids that wrote records (a cheap look at ``records/*.jsonl``)."""
    pids = set()
    for f in (out / "records").glob("*.jsonl"):
        for line in f.read_text().splitlines():
            with contextlib.suppress(ValueError):
                pids.add(json.loads(line)["pid"])
    return pids


def start(args: list[str], log: Path) -> subprocess.Popen:
    with open(log, "wb") as fh:
        return subprocess.Popen(
            [sys.executable, *args],
            env=ENV,
            stdout=fh,
            stderr=subprocess.STDOUT,
            start_new_session=True,  # its own process group: killpg cleans up every child
        )


def kill_group(p: subprocess.Popen, sig=signal.SIGKILL) -> None:
    with contextlib.suppress(ProcessLookupError, PermissionError):
        os.killpg(p.pid, sig)
    with contextlib.suppress(subprocess.TimeoutExpired):
        p.wait(timeout=20)


def wait_for(cond, proc: subprocess.Popen | None, what: str, timeout: float = TIMEOUT_S):
    t0 = time.monotonic()
    while not cond():
        if proc is not None and proc.poll() is not None:
            pytest.fail(f"process ended (code {proc.returncode}) before {what}")
        if time.monotonic() - t0 > timeout:
            pytest.fail(f"timed out waiting for {what}")
        time.sleep(0.02)


def sweep_cmd(spec: Path, out: Path, *extra: str) -> list[str]:
    return ["-m", "bearingsim", "sweep", "run", str(spec), "-o", str(out), "--json", *extra]


def same_data(a: Path, b: Path) -> None:
    da, db = open_dataset(a), open_dataset(b)
    assert_array_equal(da.status, db.status)
    assert_array_equal(da.arrays()[0], db.arrays()[0])
    for ra, rb in zip(da.records(), db.records(), strict=True):
        ma = {k: v for k, v in ra["meta"].items() if k != "wall_s"}
        mb = {k: v for k, v in rb["meta"].items() if k != "wall_s"}
        assert ma == mb


@pytest.fixture
def slow_spec_16(tmp_path):
    p = tmp_path / "slow16.toml"
    p.write_text(SLOW.replace("1797.0]", "1797.0, 1700.0, 1710.0, 1720.0, 1740.0]"))
    return p


@pytest.fixture
def slow_spec(tmp_path):
    p = tmp_path / "slow.toml"
    p.write_text(SLOW)
    return p


def test_sigkill_client_then_resume(slow_spec, tmp_path, run_cli):
    out = tmp_path / "killed.zarr"
    proc = start(sweep_cmd(slow_spec, out, "--workers", "1"), tmp_path / "client.log")
    try:
        wait_for(lambda: n_committed(out) >= 2, proc, "two committed runs")
        os.kill(proc.pid, signal.SIGKILL)  # the client only; its workers die with it
        proc.wait(timeout=20)
    finally:
        kill_group(proc)
    assert proc.returncode == -signal.SIGKILL
    before = read_status(out)
    k = int(np.sum(before == OK))
    assert 2 <= k < N_RUNS, f"killed after {k} of {N_RUNS} runs"
    done = np.flatnonzero(before == OK)
    mtimes = {i: (out / "signal" / f"{i}.0.0").stat().st_mtime_ns for i in done}
    # resume: only the missing runs are computed (the dead client's lock is taken over)
    r = run_cli(*sweep_cmd(slow_spec, out, "--workers", "1")[2:])
    assert r.code == 0, r.err
    d = r.json()
    assert (d["n_skipped"], d["n_computed"], d["n_ok"], d["n_pending"]) == (
        k,
        N_RUNS - k,
        N_RUNS,
        0,
    )
    for i in done:  # runs committed before the kill were not recomputed
        assert (out / "signal" / f"{i}.0.0").stat().st_mtime_ns == mtimes[i]
    # identical to an uninterrupted sweep, and to simulate() run by run
    ref = tmp_path / "ref.zarr"
    assert run_cli(*sweep_cmd(slow_spec, ref, "--workers", "1")[2:]).code == 0
    same_data(out, ref)
    spec = SweepSpec.from_toml(slow_spec)
    X = open_dataset(out).arrays()[0]
    for i in (0, N_RUNS - 1):
        assert_array_equal(X[i, 1], simulate(spec.scenario(i))["acc_y"], err_msg=f"run {i}")


def test_sigint_client_keeps_commits(slow_spec, tmp_path):
    out = tmp_path / "interrupted.zarr"
    log = tmp_path / "client.log"
    proc = start(sweep_cmd(slow_spec, out, "--workers", "1"), log)
    try:
        wait_for(lambda: n_committed(out) >= 1, proc, "one committed run")
        os.kill(proc.pid, signal.SIGINT)
        proc.wait(timeout=60)
    finally:
        kill_group(proc)
    assert proc.returncode == 130
    k = n_committed(out)
    assert 1 <= k < N_RUNS
    last = log.read_text().strip().splitlines()[-1]
    assert last.startswith("error: interrupted: ") and last.endswith(
        "run the same command again to resume"
    ), last
    assert not (out / "records" / ".lock").exists()  # released on the way out


def test_real_cluster_two_workers_one_killed(slow_spec_16, tmp_path):
    """``dask scheduler`` + two ``dask worker`` processes on 127.0.0.1; the sweep points at the
    scheduler by address; one worker (with its nanny) is SIGKILLed part-way."""
    from distributed import Client

    sched_file = tmp_path / "scheduler.json"
    procs: list[subprocess.Popen] = []
    try:
        procs.append(
            start(
                [
                    "-m",
                    "dask",
                    "scheduler",
                    "--host",
                    "127.0.0.1",
                    "--port",
                    "0",
                    "--no-dashboard",
                    "--scheduler-file",
                    str(sched_file),
                ],
                tmp_path / "scheduler.log",
            )
        )
        wait_for(sched_file.exists, procs[0], "the scheduler file", 60)
        wait_for(lambda: "address" in sched_file.read_text(), procs[0], "the address", 10)
        addr = json.loads(sched_file.read_text())["address"]
        assert addr.startswith("tcp://127.0.0.1:")
        for k in range(2):
            procs.append(
                start(
                    [
                        "-m",
                        "dask",
                        "worker",
                        addr,
                        "--nthreads",
                        "1",
                        "--nworkers",
                        "1",
                        "--host",
                        "127.0.0.1",
                        "--no-dashboard",
                        "--name",
                        f"w{k}",
                        "--death-timeout",
                        "60",
                        "--local-directory",
                        str(tmp_path / f"w{k}"),
                    ],
                    tmp_path / f"worker{k}.log",
                )
            )
        with Client(addr, timeout=30, set_as_default=False) as c:
            c.wait_for_workers(2, timeout=90)
        out = tmp_path / "cluster.zarr"
        client = start(sweep_cmd(slow_spec_16, out, "--scheduler", addr), tmp_path / "client.log")
        procs.append(client)
        wait_for(lambda: len(committed_pids(out)) == 2, client, "a run from each worker")
        kill_group(procs[2])  # worker w1 and its nanny
        k = n_committed(out)
        assert k < 2 * N_RUNS, "the sweep ended before the worker was killed"
        client.wait(timeout=TIMEOUT_S)
        text = (tmp_path / "client.log").read_text()
        assert client.returncode == 0, text
        d = json.loads(text.strip().splitlines()[-1])
        assert (d["n_ok"], d["n_failed"], d["n_pending"]) == (2 * N_RUNS, 0, 0)
        assert d["cluster"] == addr and d["committed_by"]["client"] == 0
    finally:
        for p in reversed(procs):
            kill_group(p)
    ds = open_dataset(out)
    pids = {r["pid"] for r in ds.records()}
    assert len(pids) == 2, pids  # both workers ran runs before one was killed
    spec = SweepSpec.from_toml(slow_spec_16)
    X = ds.arrays()[0]
    for i in range(2 * N_RUNS):
        res = simulate(spec.scenario(i))
        assert_array_equal(X[i, 0], res["acc_x"], err_msg=f"run {i} on the cluster vs simulate")
        assert_array_equal(X[i, 1], res["acc_y"], err_msg=f"run {i} on the cluster vs simulate")
