"""Sweeps on a local Dask cluster (two process workers shared by this module): results equal
``simulate`` run by run, the Zarr layout and its commit protocol, resume, spec changes,
recorded failures, the client-side writer, and the ML loader."""

from __future__ import annotations

import json
import os
from pathlib import Path

import numpy as np
import pytest
from numpy.testing import assert_allclose, assert_array_equal

from bearingsim.errors import ConfigError
from bearingsim.simulation import simulate
from bearingsim.sweep.dataset import (
    FAILED,
    OK,
    PENDING,
    RunWriter,
    client_lock,
    open_dataset,
    read_status,
)
from bearingsim.sweep.execute import connect, run_sweep
from bearingsim.sweep.spec import SweepSpec

#: short DEM runs at a low sample rate keep the module fast
BASE = {"model": "dem", "duration_s": 0.05, "fs_hz": 4000.0}


def make_spec(axes, sweep=None, base=None) -> SweepSpec:
    return SweepSpec.from_dict(
        {"sweep": sweep or {}, "base": {**BASE, **(base or {})}, "axes": axes}, origin="t.toml"
    )


NOISY = make_spec(
    {"fault": ["none", "outer", "inner"], "rpm": [1730.0, 1797.0]},
    {"per_run_seed": True},
    {"noise_rms_m_per_s2": 0.5, "seed": 11},
)


#: the module shares one local cluster of two process workers (``client``); all its tests but
#: two small unit tests use it
pytestmark = pytest.mark.integration


@pytest.fixture(scope="module")
def client():
    with connect(workers=2) as (cl, _):
        yield cl


@pytest.fixture(scope="module")
def noisy(client, tmp_path_factory):
    out = tmp_path_factory.mktemp("sweep") / "noisy.zarr"
    rep = run_sweep(NOISY, out, client=client)
    return out, rep


def strip_wall(meta: dict) -> dict:
    return {k: v for k, v in meta.items() if k != "wall_s"}


def test_sweep_equals_simulate_run_by_run(noisy):
    out, rep = noisy
    assert (rep.n_runs, rep.n_computed, rep.n_ok, rep.n_failed, rep.n_pending) == (6, 6, 6, 0, 0)
    assert rep.committed_by == {"worker": 6, "client": 0}
    ds = open_dataset(out)
    X, y = ds.arrays()
    assert X.shape == (6, 2, 200)
    recs = ds.records()
    for i in range(NOISY.n_runs):
        res = simulate(NOISY.scenario(i))
        # bitwise: the same compiled kernels and the same seeded noise (seed = 11 + i)
        assert_array_equal(X[i, 0], res["acc_x"], err_msg=f"run {i} acc_x vs simulate")
        assert_array_equal(X[i, 1], res["acc_y"], err_msg=f"run {i} acc_y vs simulate")
        assert recs[i]["meta"]["noise"]["seed"] == 11 + i
        assert strip_wall(recs[i]["meta"]) == json.loads(json.dumps(strip_wall(res.meta)))
        # the nominal time coordinate k/fs vs the integrator's accumulated time
        assert_allclose(ds.xr["time"].values, res.time, rtol=0, atol=1e-15)
        r = ds.result(i)
        assert_array_equal(r["acc_y"], res["acc_y"])
        assert r.scenario == res.scenario
    assert list(y) == [NOISY.scenario(i).fault for i in range(6)]


def test_all_channels_and_per_ball_equal_simulate(client, tmp_path):
    spec = make_spec({"fault": ["outer", "inner"]}, {"channels": "all"}, {"per_ball": True})
    out = tmp_path / "all.zarr"
    rep = run_sweep(spec, out, client=client, writer="client")
    assert rep.committed_by == {"worker": 0, "client": 2}
    ds = open_dataset(out)
    assert "ball_load" in ds.channels and "k_load" in ds.series
    for i in range(2):
        res = simulate(spec.scenario(i))
        r = ds.result(i)
        assert set(r.channels) == set(res.channels)
        for name, x in res.channels.items():
            assert_array_equal(r[name], x, err_msg=f"run {i} {name} vs simulate")
        assert r.units == res.units
    assert ds.xr["ball_load"].dims == ("run", "time", "ball")
    assert list(ds.xr["units"].values) == [res.units[c] for c in ds.series]


def test_zarr_layout_readable_by_xarray(noisy):
    import xarray as xr

    out, _ = noisy
    with xr.open_zarr(out) as d:  # consolidated metadata: no warning (warnings are errors)
        assert d["signal"].dims == ("run", "channel", "time")
        assert list(d["channel"].values) == ["acc_x", "acc_y"]
        assert list(d["units"].values) == ["m/s^2", "m/s^2"]
        for key in ("fault", "rpm", "seed"):
            assert key in d.coords
        assert_array_equal(d["rpm"].values, [NOISY.scenario(i).rpm for i in range(6)])
        assert d["status"].dtype == np.int8
        assert_array_equal(d["status"].values, np.full(6, OK))
        sc = json.loads(str(d["scenario_json"].values[3]))
        assert sc == NOISY.scenario(3).to_dict()
        assert d.attrs["spec_hash"] == NOISY.spec_hash


def test_chunks_bytes_equal_zarr_python(noisy, tmp_path):
    """The fast commit path writes exactly the bytes zarr-python writes for the same data."""
    import zarr

    from bearingsim.sweep.store import _ChunkCodec

    out, _ = noisy
    g = zarr.open_group(str(out), mode="r", zarr_format=2)
    twin = zarr.open_group(str(tmp_path / "twin.zarr"), mode="w", zarr_format=2)
    data = {
        "signal": g["signal"][2:3],
        "status": np.array([FAILED], dtype=np.int8),
        "error": np.array(["SolverError: dt_s = 0.0005 s is too large"], dtype=object),
    }
    for name, d in data.items():
        src = g[name]
        a = twin.create_array(
            name,
            shape=src.shape,
            chunks=src.chunks,
            dtype=src.dtype,
            fill_value=src.fill_value,
            compressors=src.metadata.compressor,
        )
        a[2:3] = d
        ours = _ChunkCodec.from_store(out, name).encode(d)
        theirs = Path(_ChunkCodec.from_store(tmp_path / "twin.zarr", name).path(2)).read_bytes()
        assert ours == theirs, name
    assert (out / "signal" / "2.0.0").read_bytes() == _ChunkCodec.from_store(out, "signal").encode(
        data["signal"]
    )


@pytest.mark.parametrize("overlap", [False, True], ids=["commit-inline", "commit-thread"])
def test_helper_takes_over_the_tail_of_a_task(noisy, tmp_path, overlap):
    """A claim file makes a task stop before the runs it hands over; the helper task computes
    them in reverse, skips what is committed; every run once, equal to ``simulate`` — with each
    commit inline or in the commit thread overlapping the next run."""
    import shutil

    from bearingsim.sweep.execute import run_task
    from bearingsim.sweep.store import (
        claim_path,
        read_attrs,
        remove_stale_temporaries,
        write_claim,
    )

    src, _ = noisy
    out = tmp_path / "helped.zarr"
    shutil.copytree(src, out)
    for i in range(6):
        (out / "status" / str(i)).write_bytes(b"\x00")
    base = {
        "dataset": str(out),
        "uuid": read_attrs(out)["uuid"],
        "version": __import__("bearingsim").__version__,
        "channels": None,
        "writer": "auto",
        "retry_failed": False,
        "overlap_commit": overlap,
    }
    runs = [(i, NOISY.scenario(i).to_dict()) for i in range(6)]
    write_claim(out, "t1", 2)  # the task keeps runs[:2]
    first = run_task({**base, "runs": runs, "id": "t1"})
    assert [(r["run"], r["status"]) for r in first] == [(0, OK), (1, OK)] + [
        (i, "handed") for i in range(2, 6)
    ]
    (out / "status" / "3").write_bytes(bytes((OK,)))  # as if the original had overrun into run 3
    helper = run_task({**base, "runs": runs[2:][::-1], "id": "t2"})
    assert [(r["run"], r["status"]) for r in helper] == [(5, OK), (4, OK), (3, "skipped"), (2, OK)]
    rerun = run_task({**base, "runs": runs, "id": "t1"})  # Dask reruns the original: nothing new
    assert [r["status"] for r in rerun] == ["skipped"] * 2 + ["handed"] * 4
    assert_array_equal(read_status(out), [OK] * 6)
    X, _ = open_dataset(out).arrays()
    for i in (2, 4, 5):
        assert_array_equal(X[i, 0], simulate(NOISY.scenario(i))["acc_x"], err_msg=f"run {i}")
    assert remove_stale_temporaries(out) == 1 and not os.path.exists(claim_path(out, "t1"))


def test_uneven_runs_are_balanced_by_helpers(client, tmp_path, monkeypatch):
    """Long runs at the end of the run order: the worker that runs out of tasks first takes over
    half of the other's remaining runs; every run is computed and counted once."""
    from bearingsim.sweep import execute as sweep

    monkeypatch.setattr(sweep, "MIN_HELP_S", 0.0)
    rpm = {"start": 1730.0, "stop": 1797.0, "num": 8}
    spec = make_spec({"duration_s": [0.01, 0.6], "rpm": rpm})
    assert [spec.scenario(i).duration_s for i in (7, 8)] == [0.01, 0.6]
    out = tmp_path / "uneven.zarr"
    rep = run_sweep(spec, out, client=client)
    assert (rep.n_ok, rep.n_computed, rep.n_pending) == (16, 16, 0)
    assert rep.helper_tasks >= 1, rep
    assert rep.n_computed + rep.n_recomputed == len(open_dataset(out).records())
    assert not list((out / "records").glob(".claim-*"))
    X, _ = open_dataset(out).arrays()
    for i in range(16):
        res = simulate(spec.scenario(i))
        assert_array_equal(X[i, 0, : res["acc_x"].size], res["acc_x"], err_msg=f"run {i}")


def test_resume_computes_only_missing(client, noisy, tmp_path):
    import shutil

    src, _ = noisy
    out = tmp_path / "resume.zarr"
    shutil.copytree(src, out)
    # nothing left: returns without a cluster
    rep = run_sweep(NOISY, out)
    assert (rep.n_skipped, rep.n_computed, rep.tasks) == (6, 0, 0)
    # forget runs 1 and 4 (zero their commit markers) as if killed before committing them
    for i in (1, 4):
        (out / "status" / str(i)).write_bytes(b"\x00")
    keep = {i: (out / "status" / str(i)).stat().st_mtime_ns for i in (0, 2, 3, 5)}
    keep_sig = {i: (out / "signal" / f"{i}.0.0").stat().st_mtime_ns for i in (0, 2, 3, 5)}
    assert_array_equal(read_status(out), [OK, PENDING, OK, OK, PENDING, OK])
    rep = run_sweep(NOISY, out, client=client)
    assert (rep.n_skipped, rep.n_computed, rep.n_ok) == (4, 2, 6)
    for i in keep:  # committed runs were not rewritten
        assert (out / "status" / str(i)).stat().st_mtime_ns == keep[i]
        assert (out / "signal" / f"{i}.0.0").stat().st_mtime_ns == keep_sig[i]
    assert_array_equal(open_dataset(out).arrays()[0], open_dataset(src).arrays()[0])


def test_ctrl_c_with_workers_that_outlive_the_client(client, tmp_path):
    """Ctrl-C (here a KeyboardInterrupt from the progress callback after the first task) on a
    cluster whose workers outlive the client: the tasks in flight stop after their current
    run, which they commit; the counts and the message are then those of the dataset (issue
    14: the client said "20 of 240 committed" when 28 were on disk)."""
    from bearingsim.sweep.execute import SweepInterrupted

    spec = make_spec({"rpm": [1700.0 + 10.0 * k for k in range(12)]}, base={"dt_s": 1e-6})
    out = tmp_path / "ctrl_c.zarr"
    first: list[int] = []

    def progress(rep) -> None:
        if not first:
            first.append(rep.n_computed)
            raise KeyboardInterrupt

    with pytest.raises(SweepInterrupted) as ei:
        run_sweep(spec, out, client=client, runs_per_task=3, progress=progress)
    rep = ei.value.report
    st = read_status(out)
    k = int(np.sum(st == OK))
    assert first == [3] and k >= 3 and int(np.sum(st == FAILED)) == 0
    assert (rep.n_ok, rep.n_pending, rep.n_computed, rep.n_skipped) == (k, 12 - k, k, 0)
    assert str(ei.value) == (
        f"interrupted: {k} of 12 runs committed ({k} by this call); run the same command "
        "again to resume"
    )
    assert not (out / "records" / ".lock").exists()
    rep = run_sweep(spec, out, client=client)
    assert (rep.n_skipped, rep.n_computed, rep.n_ok, rep.n_pending) == (k, 12 - k, 12, 0)


def test_ctrl_c_after_the_last_commit_says_nothing_is_left(client, tmp_path):
    """Exploratory testing (twenty-seventh session): a Ctrl-C after the last run was committed
    said "8 of 8 runs committed ...; run the same command again to resume"."""
    from bearingsim.sweep.execute import SweepInterrupted

    spec = make_spec({"rpm": [1700.0, 1750.0, 1797.0]})
    out = tmp_path / "late.zarr"

    def progress(rep) -> None:
        if rep.n_computed == 3:
            raise KeyboardInterrupt

    with pytest.raises(SweepInterrupted) as ei:
        run_sweep(spec, out, client=client, runs_per_task=1, progress=progress)
    assert str(ei.value) == (
        "interrupted: 3 of 3 runs committed (3 by this call); every run is committed, nothing "
        "is left to resume"
    )


def test_spec_change_refused_or_replaced(client, noisy, tmp_path):
    import shutil

    src, _ = noisy
    out = tmp_path / "change.zarr"
    shutil.copytree(src, out)
    other = make_spec(
        {"fault": ["none", "outer", "inner"], "rpm": [1730.0, 1750.0]},
        {"per_run_seed": True},
        {"noise_rms_m_per_s2": 0.5, "seed": 11},
    )
    with pytest.raises(
        ConfigError,
        match=r"holds a dataset of a different sweep spec \(differs in: axes.rpm\); use another "
        r"-o/--output, or --force-new to replace it",
    ):
        run_sweep(other, out, client=client)
    assert open_dataset(out).attrs["spec_hash"] == NOISY.spec_hash  # untouched
    uid = open_dataset(out).attrs["uuid"]
    rep = run_sweep(other, out, client=client, force_new=True)
    assert rep.created and rep.n_ok == 6
    ds = open_dataset(out)
    assert ds.attrs["spec_hash"] == other.spec_hash and ds.attrs["uuid"] != uid
    assert_array_equal(ds.param("rpm"), [1730.0, 1750.0] * 3)


def test_failures_recorded_sweep_goes_on(client, tmp_path):
    # dt_s = 5e-4 s at fs = 2000 Hz is beyond RK4's stability limit: SolverError (see
    # tests/test_simulate.py::test_divergence_is_reported); dt_s = 1e-5 s runs
    spec = make_spec(
        {"dt_s": [1e-5, 5e-4], "fault": ["outer", "inner"]},
        base={"fs_hz": 2000.0},
    )
    out = tmp_path / "fail.zarr"
    rep = run_sweep(spec, out, client=client)
    assert (rep.n_ok, rep.n_failed, rep.n_failed_now) == (2, 2, 2)
    ds = open_dataset(out)
    assert_array_equal(ds.status, [OK, OK, FAILED, FAILED])
    s = ds.summary()
    assert s["by_label"] == {
        "inner": {"ok": 1, "failed": 1, "pending": 0},
        "outer": {"ok": 1, "failed": 1, "pending": 0},
    }
    assert [f["run"] for f in s["failures"]] == [2, 3]
    assert s["failures"][0]["params"] == {"dt_s": 5e-4, "fault": "outer"}
    assert s["failures"][0]["error"].startswith("SolverError: dt_s = 0.0005 s is too large")
    assert np.isnan(ds.arrays()[0][2]).all()
    assert len(ds.completed()) == 2
    # a resume leaves failed runs alone; --retry-failed computes them again
    assert run_sweep(spec, out).n_computed == 0
    rep = run_sweep(spec, out, client=client, retry_failed=True)
    assert (rep.n_computed, rep.n_failed_now, rep.n_failed) == (2, 2, 2)


def test_task_sizes_and_progress(client, tmp_path):
    spec = make_spec({"rpm": [1700.0 + 10 * k for k in range(7)]})
    seen = []
    rep = run_sweep(spec, tmp_path / "p.zarr", client=client, runs_per_task=3, progress=seen.append)
    assert rep.tasks == 3 and rep.n_ok == 7  # ceil(7 / 3) tasks
    assert len(seen) == 3 and seen[-1].n_computed == 7


def test_loader_for_ml(noisy):
    out, _ = noisy
    ds = open_dataset(out)
    train, test = ds.split("rpm", test=1797.0)
    assert_array_equal(train.runs, [0, 2, 4]) and assert_array_equal(test.runs, [1, 3, 5])
    Xt, yt = test.arrays(["acc_y"])
    assert Xt.shape == (3, 1, 200) and list(yt) == ["none", "outer", "inner"]
    # one channel named by a string (it was read as the list of its characters)
    assert_array_equal(test.arrays("acc_y")[0], Xt)
    assert_array_equal(Xt[:, 0], ds.arrays()[0][[1, 3, 5], 1])
    # stratified: each class (2 runs) puts round(0.5 * 2) = 1 run in the test set
    a, b = ds.random_split(0.5, seed=1)
    assert len(a) == 3 and sorted(b.labels()) == ["inner", "none", "outer"]
    assert sorted(np.concatenate([a.runs, b.runs])) == list(range(6))
    assert_array_equal(ds.random_split(0.5, seed=1)[1].runs, b.runs)  # seeded
    assert sorted(ds.select(fault=["outer", "inner"]).runs) == [2, 3, 4, 5]
    assert_array_equal(ds.labels(["fault", "rpm"])[:2], ["none|1730.0", "none|1797.0"])
    with pytest.raises(ConfigError, match=r"key = 'speed' is not stored per run; valid: fault"):
        ds.param("speed")
    with pytest.raises(ConfigError, match=r"test = \[1.0\] matches no run for 'rpm'"):
        ds.split("rpm", test=[1.0])
    with pytest.raises(ConfigError, match=r"channel = 'k_load' is not a stored time series"):
        ds.arrays(["k_load"])


def test_commit_marker_is_last(noisy, tmp_path, monkeypatch):
    """A writer killed after the data and before the marker leaves the run pending."""
    import shutil

    src, _ = noisy
    out = tmp_path / "marker.zarr"
    shutil.copytree(src, out)
    (out / "status" / "0").write_bytes(b"\x00")
    w = RunWriter(out)
    sig = out / "signal" / "0.0.0"
    before = sig.read_bytes()

    def killed(self, i, status):
        raise KeyboardInterrupt("killed before the marker")

    monkeypatch.setattr(RunWriter, "_mark", killed)
    x = np.ones(200)
    with pytest.raises(KeyboardInterrupt):
        w.commit(0, OK, {"compute_s": 0.0, "meta": {}}, "", {"acc_x": x, "acc_y": x})
    assert sig.read_bytes() != before  # the data chunk was replaced ...
    assert read_status(out)[0] == PENDING and not w.committed(0)  # ... but the run is pending
    assert open_dataset(out).summary()["n_pending"] == 1
    assert not list((out / "signal").glob(".*.tmp"))
    monkeypatch.undo()
    w.commit(0, OK, {"compute_s": 0.0, "meta": {}}, "", {"acc_x": x, "acc_y": x})
    assert read_status(out)[0] == OK and w.committed(0)


def test_client_lock(noisy):
    out, _ = noisy
    with client_lock(out):
        (out / "records" / ".lock").write_text(json.dumps({"host": "elsewhere", "pid": 1}))
        with pytest.raises(ConfigError, match=r"is in use by the sweep client elsewhere:1"):
            with client_lock(out):
                pass
        (out / "records" / ".lock").unlink()
    # a lock of a dead process on this host is taken over
    import socket

    (out / "records" / ".lock").write_text(
        json.dumps({"host": socket.gethostname(), "pid": 2**22 + 12345})
    )
    with client_lock(out):
        assert json.loads((out / "records" / ".lock").read_text())["pid"] == os.getpid()
    assert not (out / "records" / ".lock").exists()


def test_dataset_creation_is_atomic(client, tmp_path, monkeypatch):
    import zarr

    def boom(*a, **k):
        raise OSError("disk full")

    monkeypatch.setattr(zarr, "consolidate_metadata", boom)
    with pytest.raises(OSError, match="disk full"):
        run_sweep(make_spec({"rpm": [1700.0]}), tmp_path / "x.zarr", client=client)
    assert list(Path(tmp_path).iterdir()) == []  # neither the dataset nor its temporary


def test_records_retry_and_torn_lines(noisy, tmp_path):
    """Records are JSON lines: a line cut by a kill is skipped; a rerun's newest line whose
    status matches the committed one wins; a retried run that succeeds drops its error."""
    import shutil

    src, _ = noisy
    out = tmp_path / "rec.zarr"
    shutil.copytree(src, out)
    w = RunWriter(out)
    w.commit(0, FAILED, {"compute_s": 1.0, "meta": None}, "SolverError: boom")
    ds = open_dataset(out)
    assert ds.summary()["failures"][0]["error"] == "SolverError: boom"
    assert ds.records()[0]["compute_s"] == 1.0
    x = np.ones(200)
    w.commit(0, OK, {"compute_s": 2.0, "meta": {"model": "dem"}}, "", {"acc_x": x, "acc_y": x})
    logs = list((out / "records").glob("*.jsonl"))
    with open(logs[0], "a") as fh:
        fh.write('{"run": 1, "sta')  # a writer killed mid-line
    with open(logs[-1], "a") as fh:  # a newer attempt killed before its marker
        fh.write(json.dumps({"run": 0, "status": FAILED, "t": 1e12, "compute_s": 9.0}) + "\n")
    w.close()
    ds = open_dataset(out)
    r0 = ds.records()[0]
    assert (r0["status"], r0["compute_s"], r0["meta"]) == (OK, 2.0, {"model": "dem"})
    assert ds.summary()["failures"] == [] and str(ds.xr["error"].values[0]) == ""
    assert ds.records()[1]["meta"] == json.loads(json.dumps(open_dataset(src).records()[1]["meta"]))


def test_zarr_hierarchy_walk_without_warnings(noisy):
    """zarr's own hierarchy walk (no consolidated metadata) accepts the dataset, also while a
    client holds the lock (warnings are errors in the tests)."""
    import zarr

    out, _ = noisy
    g = zarr.open_group(str(out), mode="r", use_consolidated=False)
    names = sorted(n for n, _ in g.members())
    assert {"signal", "status", "error", "records", "scenario_json"} <= set(names)
    with client_lock(out):
        zarr.open_group(str(out), mode="r", use_consolidated=False).members()


def test_workers_that_cannot_write_hand_runs_to_the_client(client, tmp_path):
    """A worker whose commit fails (e.g. a read-only mount) sends its runs back; the client
    commits them, nothing is lost."""

    def break_commit():  # runs in the worker processes (pickled by value)
        from bearingsim.sweep import dataset as sweep_dataset

        def commit(self, *a, **k):
            raise PermissionError("read-only file system")

        sweep_dataset.RunWriter._real_commit = sweep_dataset.RunWriter.commit
        sweep_dataset.RunWriter.commit = commit

    def restore():
        from bearingsim.sweep import dataset as sweep_dataset
        from bearingsim.sweep import execute as sweep

        sweep_dataset.RunWriter.commit = sweep_dataset.RunWriter._real_commit
        sweep._WRITERS.clear()

    spec = make_spec({"fault": ["outer", "inner"], "rpm": [1730.0, 1797.0]})
    client.run(break_commit)
    try:
        rep = run_sweep(spec, tmp_path / "ro.zarr", client=client)
    finally:
        client.run(restore)
    assert rep.committed_by == {"worker": 0, "client": 4} and rep.n_ok == 4
    X = open_dataset(tmp_path / "ro.zarr").arrays()[0]
    for i in range(4):
        assert_array_equal(X[i, 1], simulate(spec.scenario(i))["acc_y"], err_msg=f"run {i}")


def test_mixed_models_rates_and_per_ball(client, tmp_path):
    """Three models, per-ball on/off and two sample rates in one dataset (dimension ``sample``,
    NaN padding): every run reads back equal to ``simulate``, channel set included."""
    spec = make_spec(
        {"model": ["vsm", "dem", "tvsm"], "per_ball": [False, True], "fs_hz": [4000.0, 8000.0]},
        {"channels": "all"},
        {"fault": "outer", "duration_s": 0.02},
    )
    out = tmp_path / "mixed.zarr"
    assert run_sweep(spec, out, client=client).n_ok == 12
    ds = open_dataset(out)
    assert ds.attrs["time_dim"] == "sample" and ds.xr["signal"].shape == (12, 13, 160)
    for i in range(12):
        r, s = ds.result(i), simulate(spec.scenario(i))
        assert set(r.channels) == set(s.channels), i
        for k, x in s.channels.items():
            assert_array_equal(r[k], x, err_msg=f"run {i} {k} vs simulate")
        assert_allclose(r.time, s.time, rtol=0, atol=1e-15)


def test_a_task_that_raises_is_recorded(client, tmp_path):
    """A task that dies as a whole (here it raises; a task lost with its worker too often gives
    ``KilledWorker`` the same way) records its runs as failed; the sweep finishes."""

    def break_task():  # runs in the worker processes (pickled by value)
        from bearingsim.sweep import execute as sweep

        def run_task(task):
            raise RuntimeError("worker lost its disk")

        sweep._real_run_task = sweep.run_task
        sweep.run_task = run_task

    def restore():
        from bearingsim.sweep import execute as sweep

        sweep.run_task = sweep._real_run_task

    spec = make_spec({"rpm": [1730.0, 1750.0, 1797.0]})
    client.run(break_task)
    try:
        rep = run_sweep(spec, tmp_path / "t.zarr", client=client, runs_per_task=2)
    finally:
        client.run(restore)
    assert (rep.n_failed, rep.n_pending, rep.tasks) == (3, 0, 2)
    s = open_dataset(tmp_path / "t.zarr").summary()
    assert [f["error"] for f in s["failures"]] == ["RuntimeError: worker lost its disk"] * 3
    rep = run_sweep(spec, tmp_path / "t.zarr", client=client, retry_failed=True)
    assert (rep.n_ok, rep.n_failed) == (3, 0)


def test_commit_overlaps_only_where_a_core_is_free():
    from bearingsim.sweep.execute import spare_core_workers

    hello = {
        "tcp://a:1": {"host": "a", "cores": 2},
        "tcp://a:2": {"host": "a", "cores": 2},
        "tcp://b:1": {"host": "b", "cores": 4},
        "tcp://c:1": {"host": "c", "cores": 2},
    }
    nthreads = {"tcp://a:1": 1, "tcp://a:2": 1, "tcp://b:1": 2, "tcp://c:1": 1}
    # host a: 2 threads on 2 cores (busy); b: 2 threads on 4 cores; c: 1 thread on 2 cores
    assert spare_core_workers(hello, nthreads) == {"tcp://b:1", "tcp://c:1"}


def test_claims_are_reread_and_only_move_the_end_earlier(noisy, tmp_path, monkeypatch):
    """A task reads its claim before every run: a lower one (Ctrl-C writes 0 for every running
    task) stops it before its next run; a higher one never extends it."""
    import shutil

    import bearingsim.simulation
    from bearingsim.sweep.execute import run_task
    from bearingsim.sweep.store import read_attrs, write_claim

    src, _ = noisy
    out = tmp_path / "claims.zarr"
    base = {
        "version": __import__("bearingsim").__version__,
        "channels": None,
        "writer": "auto",
        "retry_failed": False,
        "runs": [(i, NOISY.scenario(i).to_dict()) for i in range(6)],
    }
    real = bearingsim.simulation.simulate
    for first, during, ran in ((4, 0, [0]), (2, 5, [0, 1])):
        shutil.rmtree(out, ignore_errors=True)
        shutil.copytree(src, out)
        for i in range(6):
            (out / "status" / str(i)).write_bytes(b"\x00")
        write_claim(out, "t1", first)
        calls = []

        def sim(sc, during=during, calls=calls, **kw):
            calls.append(sc)
            if len(calls) == 1:
                write_claim(out, "t1", during)
            return real(sc, **kw)

        monkeypatch.setattr(bearingsim.simulation, "simulate", sim)
        task = {**base, "dataset": str(out), "uuid": read_attrs(out)["uuid"], "id": "t1"}
        recs = run_task(task)
        assert [r["run"] for r in recs if r["status"] == OK] == ran, (first, during)
        assert [r["status"] for r in recs[len(ran) :]] == ["handed"] * (6 - len(ran))
        assert list(np.flatnonzero(read_status(out) == OK)) == ran


def test_first_tasks_sized_from_the_timing_probe(client, tmp_path):
    """The timing probe estimates the run time before the first task: a sweep much shorter than
    TARGET_TASK_S per thread goes out as one task per worker thread (plus helpers)."""
    spec = make_spec({"rpm": [1700.0 + 10 * k for k in range(8)]})
    rep = run_sweep(spec, tmp_path / "e.zarr", client=client)
    assert rep.n_ok == 8
    assert rep.estimate_s is not None and 0.0 < rep.estimate_s < 0.5, rep.estimate_s
    assert rep.tasks - rep.helper_tasks == 2, rep


def test_without_an_estimate_timing_tasks_come_first(client, tmp_path):
    """When the timing probe fails (the first run cannot start: dt_s beyond RK4's limit), each
    thread first gets a one-run timing task and a two-run task; the failure is recorded."""
    spec = make_spec({"dt_s": [5e-4, 1e-5], "fault": ["outer", "inner"]}, base={"fs_hz": 2000.0})
    rep = run_sweep(spec, tmp_path / "f.zarr", client=client)
    assert rep.estimate_s is None
    assert (rep.n_ok, rep.n_failed) == (2, 2)
    assert rep.tasks - rep.helper_tasks == 3, rep  # runs 1 + 1 + 2


def test_timing_probe():
    from bearingsim.sweep.plan import timing_probe

    # 0.2 s at 12 kHz: the integration (~5 ms) outweighs the fixed part (~1 ms)
    sc = NOISY.scenario(0).replace(duration_s=0.2, fs_hz=12000.0)
    fixed, rate = timing_probe(sc.to_dict(), 0.2)
    assert fixed > 0.0 and rate > 0.0
    assert timing_probe({"model": "no-such-model"}, 0.02) is None  # any error: no estimate


def test_local_workers_keep_glibc_dynamic_mmap_threshold(client):
    """Dask's nanny sets MALLOC_TRIM_THRESHOLD_=65536 in every worker, which turns off glibc's
    dynamic mmap threshold (each run's arrays then come from fresh pages, ~13 % slower); the
    local cluster leaves it unset."""
    if "MALLOC_TRIM_THRESHOLD_" in os.environ:
        pytest.skip("MALLOC_TRIM_THRESHOLD_ is set in this environment (the workers inherit it)")
    got = client.run(os.environ.get, "MALLOC_TRIM_THRESHOLD_")
    assert len(got) == 2 and set(got.values()) == {None}


def test_ias_scenarios_sweep_like_the_others(client, tmp_path):
    """The IAS model runs in a sweep through ``simulate`` (issue 13): its default label is the
    spall width, its default channel the shaft speed, and every run reads back equal to
    ``simulate`` of the same scenario."""
    spec = SweepSpec.from_dict(
        {
            "base": {"model": "ias", "duration_s": 0.02, "dt_s": 1e-5, "fs_hz": 10000.0},
            "axes": {"spall_width_m": [0.0, 1e-3], "fy_n": [300.0, 400.0]},
        },
        origin="ias.toml",
    )
    assert spec.label == ("spall_width_m",) and spec.channels == ("omega",)
    out = tmp_path / "ias.zarr"
    assert run_sweep(spec, out, client=client).n_ok == 4
    ds = open_dataset(out)
    assert list(ds.labels()) == ["0.0", "0.0", "0.001", "0.001"]
    for i in range(4):
        r, s = ds.result(i), simulate(spec.scenario(i))
        assert_array_equal(r["omega"], s["omega"], err_msg=f"run {i} vs simulate")
        assert_allclose(r.time, s.time, rtol=0, atol=1e-15)


def test_each_run_records_its_own_warnings(client, tmp_path):
    # a 12 kHz rig on a 48 kHz output warns (RigRateWarning, bearingsim.rig); both 48 kHz runs
    # run in one task on one worker, so the second is recorded although its warning repeats
    # the first's text and code location (the default action would show it once per process)
    spec = make_spec(
        {"fs_hz": [12000.0, 48000.0], "fault": ["none", "outer"]},
        base={"model": "vsm", "duration_s": 0.02, "fs_hz": 12000.0, "rig": "cwru-de-12k"},
    )
    out = tmp_path / "warn.zarr"
    rep = run_sweep(spec, out, client=client, runs_per_task=4)
    assert rep.n_ok == 4
    ds = open_dataset(out)
    warned = [r["warnings"] for r in ds.records()]
    assert warned[0] == warned[1] == []
    assert len(warned[2]) == 1 and warned[2] == warned[3]
    assert warned[2][0].startswith("RigRateWarning: rig 'cwru-de-12k': its background")
    assert rep.warnings == {warned[2][0]: 2}
    assert ds.summary()["warnings"] == {warned[2][0]: [2, 3]}


def test_a_rig_axis_samples_each_run_at_its_rigs_rate_and_stores_the_sensor(client, tmp_path):
    """Exploratory testing (nineteenth session): a sweep with a ``rig`` axis and no ``fs_hz``
    ran every run at 48 kHz (its canonical base pinned the default) and stored only acc_x and
    acc_y, so a labelled dataset of sensor signals had none unless ``channels`` named it. Each
    run now takes its own rig's rate, and a rig in the base or the axes adds acc_sensor to the
    default channels; without a rig they are as before."""
    spec = SweepSpec.from_dict(
        {"base": {"model": "vsm", "duration_s": 0.02, "fault": "outer"},
         "axes": {"rig": ["cwru-de-12k", "cwru-de-48k"]}},
        origin="rigs.toml",
    )  # fmt: skip
    assert spec.channels == ("acc_x", "acc_y", "acc_sensor")
    assert [sc.fs_hz for sc in spec.scenarios()] == [12000.0, 48000.0]
    out = tmp_path / "rigs.zarr"
    assert run_sweep(spec, out, client=client).n_ok == 2
    ds = open_dataset(out)
    for i, n in enumerate((240, 960)):
        r = ds.result(i)
        assert r["acc_sensor"].size == n and ds.scenario(i)["fs_hz"] == n / 0.02
        assert_array_equal(r["acc_sensor"], simulate(spec.scenario(i))["acc_sensor"])
    plain = make_spec({"fault": ["none", "outer"]})
    assert plain.channels == ("acc_x", "acc_y") and plain.base["fs_hz"] == BASE["fs_hz"]
    based = SweepSpec.from_dict(
        {"base": {"model": "vsm", "rig": "cwru-de-12k"}, "axes": {"seed": [0, 1]}}, origin="b"
    )
    assert based.channels == ("acc_x", "acc_y", "acc_sensor") and based.base["fs_hz"] is None
    assert [sc.fs_hz for sc in based.scenarios()] == [12000.0, 12000.0]
    # channels named without acc_sensor: said (twenty-eighth session; stored silently before)
    assert spec.unstored_sensor_note is None and plain.unstored_sensor_note is None
    for base, axes in (({"model": "vsm", "rig": "cwru-de-12k"}, {"seed": [0, 1]}),
                       ({"model": "vsm"}, {"rig": ["cwru-de-12k", "cwru-de-48k"]})):  # fmt: skip
        named = SweepSpec.from_dict(
            {"sweep": {"channels": ["acc_y"]}, "base": base, "axes": axes}, origin="n"
        )
        assert named.unstored_sensor_note.startswith(
            "sweep.channels = ['acc_y'] omits 'acc_sensor' while the runs pass through a rig"
        )
    everything = SweepSpec.from_dict(
        {"sweep": {"channels": "all"}, "base": {"model": "vsm", "rig": "cwru-de-12k"}}, origin="a"
    )
    assert everything.unstored_sensor_note is None


def test_a_sweeps_rig_gives_its_rate_from_a_base_file_and_beside_the_sweep_file(
    tmp_path, monkeypatch
):
    """Exploratory testing (twentieth session), each written silently before:
    * a base_file without fs_hz pinned 48 kHz, so a rig axis (or a rig in [base]) over it ran
      at 48 kHz with a RigRateWarning; now each run takes its rig's rate;
    * a rig file named in the sweep was looked up from the working directory (a decoy there
      was used); it is now taken beside the sweep file, as bearing_file is;
    * a folder named like a shipped profile (a sweep's own -o cwru-de-12k) hid the profile;
    * with a rig in [base] the runs' recorded defaults left the rate out."""
    import shutil

    from bearingsim.rig import PROFILES_DIR

    (tmp_path / "plain.toml").write_text('model = "vsm"\nduration_s = 0.1\nfault = "outer"\n')
    (tmp_path / "axis.toml").write_text(
        '[sweep]\nbase_file = "plain.toml"\n[axes]\nrig = ["cwru-de-12k", "cwru-de-48k"]\n'
    )
    (tmp_path / "based.toml").write_text(
        '[sweep]\nbase_file = "plain.toml"\n[base]\nrig = "cwru-de-12k"\n[axes]\nseed = [0]\n'
    )
    assert [sc.fs_hz for sc in SweepSpec.from_toml(tmp_path / "axis.toml").scenarios()] == [
        12000.0, 48000.0
    ]  # fmt: skip
    (sc,) = SweepSpec.from_toml(tmp_path / "based.toml").scenarios()
    assert sc.fs_hz == 12000.0 and sc.defaults_record["keys"]["fs_hz"] == 12000.0
    rel = tmp_path / "rel"
    rel.mkdir()
    shutil.copy(PROFILES_DIR / "cwru-fe-12k.toml", rel / "myrig.toml")
    shutil.copy(PROFILES_DIR / "cwru-de-48k.toml", tmp_path / "myrig.toml")  # the decoy
    (rel / "s.toml").write_text(
        '[base]\nmodel = "vsm"\nduration_s = 0.1\nrig = "myrig.toml"\n[axes]\nseed = [0]\n\n'
    )
    (rel / "a.toml").write_text(
        '[base]\nmodel = "vsm"\nduration_s = 0.1\n[axes]\nrig = ["myrig.toml"]\n'
    )
    monkeypatch.chdir(tmp_path)
    for name in ("s.toml", "a.toml"):
        (sc,) = SweepSpec.from_toml(rel / name).scenarios()
        assert sc.fs_hz == 12000.0 and sc.rig == str(rel / "myrig.toml"), name
    (tmp_path / "cwru-de-12k").mkdir()  # e.g. a sweep's output folder of that name
    spec = SweepSpec.from_dict(
        {"base": {"model": "vsm", "duration_s": 0.1, "rig": "cwru-de-12k"}}, origin="x"
    )
    assert spec.scenario(0).fs_hz == 12000.0


def test_a_sweep_run_records_the_rate_its_rig_chose_as_the_cli_run_does(client, tmp_path):
    """Exploratory testing (twenty-sixth session): a sweep run whose rate its rig chose did
    not record ``fs_hz`` among its defaults (the tasks carried the rate as a number, so the
    worker took it as set), unlike ``simulate`` of the same scenario; docs/sweeps.md says
    the rate is recorded. The arrays were and are the same."""
    spec = SweepSpec.from_dict(
        {
            "base": {"model": "vsm", "fault": "ball", "duration_s": 0.05, "rig": "cwru-de-12k"},
            "axes": {"seed": [1]},
        },
        origin="r.toml",
    )
    out = tmp_path / "r.zarr"
    assert run_sweep(spec, out, client=client).n_ok == 1
    r, s = open_dataset(out).result(0), simulate(spec.scenario(0))
    assert s.meta["defaults"]["keys"]["fs_hz"] == 12000.0
    assert r.meta["defaults"] == s.meta["defaults"]
    assert_array_equal(r["acc_sensor"], s["acc_sensor"])
