"""The sweep store without a cluster (issue 14, item 5): damaged stores give one line naming the
file, the client lock (empty, dead, reused-PID and other-host locks; takeover races; heartbeat),
dataset creation raced by several clients, exact counts from the disk, and the temporary
directories of killed creations. Stores are built with ``create_dataset`` and ``RunWriter``
directly, as ``run_sweep`` does, so no Dask cluster is started here."""

from __future__ import annotations

import json
import os
import socket
import threading
import time
import warnings
from pathlib import Path

import numpy as np
import pytest
from numpy.testing import assert_array_equal

from bearingsim.errors import ConfigError
from bearingsim.sweep import lock as locks
from bearingsim.sweep.dataset import SplitWarning, open_dataset
from bearingsim.sweep.execute import SweepReport, _exact_counts, _remove_dataset, run_sweep
from bearingsim.sweep.lock import ClientLock, client_lock, judge_lock, this_process
from bearingsim.sweep.plan import coordinates
from bearingsim.sweep.spec import SweepSpec
from bearingsim.sweep.store import (
    FAILED,
    OK,
    PENDING,
    ChannelLayout,
    DatasetExistsError,
    Layout,
    RunWriter,
    create_dataset,
    read_attrs,
    read_records,
    read_status,
    records_offsets,
    remove_stale_temporaries,
)

N_TIME = 20
SPEC = SweepSpec.from_dict(
    {
        "sweep": {"label": "fault"},
        "base": {"model": "dem", "duration_s": 0.005, "fs_hz": 4000.0},
        "axes": {"fault": ["none", "outer", "inner"], "rpm": [1730.0, 1797.0]},
    },
    origin="t.toml",
)
LAYOUT = Layout(
    n_runs=SPEC.n_runs,
    n_time=N_TIME,
    fs_hz=4000.0,
    channels=(ChannelLayout("acc_x", "m/s^2"), ChannelLayout("acc_y", "m/s^2")),
)


def new_store(path: Path, lock: ClientLock | None = None) -> str:
    """An empty dataset of ``SPEC``, as ``run_sweep`` creates it."""
    scenarios = SPEC.scenarios()
    attrs = {
        "spec_hash": SPEC.spec_hash,
        "spec_json": json.dumps(SPEC.canonical()),
        "label": list(SPEC.label),
        "axes": list(SPEC.axis_names),
        "name": SPEC.name,
    }
    sdicts = [s.to_dict() for s in scenarios]
    return create_dataset(path, LAYOUT, attrs, coordinates(SPEC, scenarios), sdicts, lock=lock)


def signal(i: int) -> dict[str, np.ndarray]:
    t = np.arange(N_TIME, dtype=float)
    return {"acc_x": np.sin(t + i), "acc_y": np.cos(t * i)}


def commit(w: RunWriter, i: int, status: int = OK, compute_s: float = 0.5) -> None:
    rec = {"compute_s": compute_s, "cpu_s": compute_s, "host": "h", "pid": 1, "meta": {"k": i}}
    if status == OK:
        w.commit(i, OK, rec, "", signal(i))
    else:
        w.commit(i, FAILED, rec, f"SolverError: run {i} diverged")


@pytest.fixture
def store(tmp_path) -> Path:
    """Runs 0-3 ok, run 4 failed, run 5 pending."""
    out = tmp_path / "ds.zarr"
    new_store(out)
    w = RunWriter(out)
    for i in range(4):
        commit(w, i)
    commit(w, 4, FAILED)
    w.close()
    return out


# ------------------------------------------------------------------------- damaged stores
def _write(rel: str, data: bytes):
    def damage(p: Path) -> str:
        (p / rel).write_bytes(data)
        return rel

    return damage


def _rewrite_json(rel: str, change):
    def damage(p: Path) -> str:
        d = json.loads((p / rel).read_text())
        (p / rel).write_text(json.dumps(change(d)))
        return rel

    return damage


def _remove(rel: str):
    def damage(p: Path) -> str:
        (p / rel).unlink()
        return rel

    return damage


GARBAGE = bytes(range(255, 100, -3))  # not UTF-8, not JSON, not a codec's header
DAMAGE = {
    # the two cases: JSONDecodeError / UnicodeDecodeError from `sweep summary`
    "zmetadata_garbage": (_write(".zmetadata", GARBAGE), "is not UTF-8 text"),
    "zmetadata_not_json": (_write(".zmetadata", b"{metadata"), "is not valid JSON"),
    "zmetadata_no_metadata": (_write(".zmetadata", b'{"zarr": 2}'), "has no 'metadata' object"),
    "status_chunk_garbage": (_write("status/1", GARBAGE), r"holds b'\\xff\\xfc'\.\.\.; valid: one"),
    "status_chunk_bad_byte": (_write("status/1", b"\x07"), r"holds b'\\x07'; valid: one byte 0"),
    "status_chunk_missing": (_remove("status/1"), r"is missing \(the status chunk of run 1\)"),
    "status_zarray_garbage": (_write("status/.zarray", GARBAGE), "is not UTF-8 text"),
    "zattrs_list": (_write(".zattrs", b"[1, 2]"), "holds a JSON list, not an object"),
    "zattrs_n_runs": (
        _rewrite_json(".zattrs", lambda d: {**d, "n_runs": "six"}),
        r"has n_runs = 'six'; valid: an integer >= 0",
    ),
    "zmetadata_zarray_of_error": (
        _rewrite_json(
            ".zmetadata",
            lambda d: {**d, "metadata": {**d["metadata"], "error/.zarray": {"chunks": 1}}},
        ),
        r"has an invalid entry 'error/.zarray'; valid: a zarr v2 array",
    ),
    "error_chunk_garbage": (_write("error/4", GARBAGE), r"holds \d+ bytes that are not one text"),
    "coordinate_chunk_garbage": (_write("fault/0", GARBAGE), r"cannot be decoded \("),
}
#: damage that a resume does not read (it writes only the pending runs' chunks): resumable
RESUMABLE = {"error_chunk_garbage", "coordinate_chunk_garbage"}


@pytest.mark.parametrize("case", sorted(DAMAGE))
def test_damaged_store_readers_give_one_line(case, store, run_cli):
    """Every reader of a damaged store (``sweep summary``, ``open_dataset`` and its methods,
    ``read_attrs``, ``read_status``, records, a resume) raises one ``ConfigError`` line naming
    the damaged file, or reads on; never another exception."""
    damage, what = DAMAGE[case]
    rel = damage(store)
    r = run_cli("sweep", "summary", store)
    assert r.code == 2 and r.out == "", (r.out, r.err)
    lines = r.err.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith(f"error: dataset = '{store}' "), r.err
    assert f"'{store / rel}'" in lines[0], lines[0]
    assert pytest.importorskip("re").search(what, lines[0]), lines[0]
    assert lines[0].endswith("delete the dataset and run the sweep again"), lines[0]

    errors = read_everything(store)
    assert any(f"'{store / rel}'" in e for e in errors), errors
    if case in RESUMABLE:
        return
    # a resume is refused in one line before any work (the client is never touched)
    with pytest.raises(ConfigError, match=r"is (damaged|not a bearingsim sweep dataset)"):
        run_sweep(SPEC, store, client=_NoCluster())
    assert not (store / "records" / ".lock").exists()


def read_everything(d: Path) -> list[str]:
    """Every reader of a dataset: ``read_attrs``, ``read_status``, ``RunWriter``,
    ``open_dataset`` and its methods; each works or raises a one-line ``ConfigError``
    (returned), never another exception."""
    calls = [lambda: read_attrs(d), lambda: read_status(d), lambda: RunWriter(d).close()]
    errors: list[str] = []
    try:
        ds = open_dataset(d)
    except ConfigError as exc:
        errors.append(str(exc))
    else:
        calls += [ds.summary, ds.records, ds.arrays, ds.labels, lambda: ds.scenario(0)]
        calls += [lambda i=i: ds.result(i) for i in range(SPEC.n_runs)]
        calls += [lambda: ds.completed().random_split(0.5)]
    for call in calls:
        try:
            with warnings.catch_warnings():
                # a damaged label column may leave a label on one side of a split: a warning
                # (SplitWarning), which the suite's 'error' filter would make an exception
                warnings.simplefilter("ignore", SplitWarning)
                call()
        except ConfigError as exc:
            errors.append(str(exc))
    assert all(len(e.splitlines()) == 1 for e in errors), errors
    return errors


class _NoCluster:
    """A Dask client stand-in that fails the test when touched."""

    def __getattr__(self, name):
        pytest.fail(f"the cluster was used ({name}) although the dataset is damaged")


def test_random_damage_never_leaks_an_exception(store):
    """50 seeded random damages (garbage, truncation, flipped bytes, bytes appended) of a
    random file of the store: every reader works or raises ``ConfigError``, never another
    exception (a local run of 6,000 more cases, seeds 0-7, found none either)."""
    import shutil

    files = sorted(p.relative_to(store) for p in store.rglob("*") if p.is_file())
    rng = np.random.default_rng(14)
    for k in range(50):
        d = store.parent / f"damaged{k}.zarr"
        shutil.copytree(store, d)
        f = d / files[rng.integers(len(files))]
        b = f.read_bytes()
        mode = rng.integers(4)
        if mode == 0:
            new = rng.bytes(int(rng.integers(0, 64)))
        elif mode == 1:
            new = b[: rng.integers(0, len(b) + 1)]
        elif mode == 2:
            a = bytearray(b or b"\0")
            for _ in range(rng.integers(1, 4)):
                a[rng.integers(len(a))] = rng.integers(256)
            new = bytes(a)
        else:
            new = b + rng.bytes(int(rng.integers(1, 16)))
        f.write_bytes(new)
        read_everything(d)
        shutil.rmtree(d)


def test_garbage_record_lines_are_skipped(store, run_cli):
    """Records are auxiliary (the status byte is the commit): lines that are not records —
    binary garbage, a cut line, JSON of the wrong shape or types — are skipped like a line cut
    by a kill, and every reader reads on."""
    clean = open_dataset(store).records()
    summary = open_dataset(store).summary()
    log = next((store / "records").glob("*.jsonl"))
    with open(log, "ab") as fh:
        fh.write(GARBAGE + b"\n" + b"\xff\xfe\n")
        for bad in ([0, 1], {"run": "0", "status": 1}, {"run": 0, "status": 1, "t": "late"}):
            fh.write(json.dumps(bad).encode() + b"\n")
        fh.write(json.dumps({"run": 1, "status": OK, "t": 1e12, "compute_s": "slow"}).encode())
        fh.write(b"\n" + json.dumps({"run": True, "status": OK, "t": 1e12}).encode() + b"\n")
        fh.write(b'{"run": 2, "status": 1, "t": 1e12, "compute_s": 9.0')  # cut by a kill
    (store / "records" / "other.jsonl").write_bytes(GARBAGE)
    ds = open_dataset(store)
    assert ds.records() == clean
    assert ds.summary() == summary and summary["compute_s_total"] == pytest.approx(2.5)
    r = run_cli("sweep", "summary", store, "--json")
    assert r.code == 0 and r.json()["n_ok"] == 4, r.err
    (store / "records" / "dir.jsonl").mkdir()  # a records "file" that cannot be read
    with pytest.raises(ConfigError, match=r"is damaged: '.*dir.jsonl' cannot be read"):
        ds.records()


def test_failed_run_error_is_read_from_its_chunk(store):
    s = open_dataset(store).summary()
    assert [(f["run"], f["error"]) for f in s["failures"]] == [(4, "SolverError: run 4 diverged")]
    assert s["by_label"] == {
        "inner": {"ok": 0, "failed": 1, "pending": 1},
        "none": {"ok": 2, "failed": 0, "pending": 0},
        "outer": {"ok": 2, "failed": 0, "pending": 0},
    }


# ------------------------------------------------------------------------------- the lock
def _lock_file(store: Path) -> Path:
    return store / "records" / ".lock"


def _age(p: Path, seconds: float) -> None:
    t = time.time() - seconds
    os.utime(p, (t, t))


def _holder(store: Path) -> dict:
    return json.loads(_lock_file(store).read_text())


@pytest.mark.parametrize(
    "content, age_s",
    [
        (b"", 10.0),  # the issue: a kill between creating and writing the lock
        (b"", 0.0),  # the same, just now: waited for (LOCK_EMPTY_GRACE_S), then taken over
        (b"\xff\xfe{", 10.0),  # not JSON
        (b"[1, 2]", 10.0),  # JSON, not an object
    ],
    ids=["empty", "empty-young", "garbage", "not-an-object"],
)
def test_empty_or_unreadable_lock_is_taken_over(store, content, age_s, monkeypatch):
    monkeypatch.setattr(locks, "LOCK_EMPTY_GRACE_S", 0.3)
    _lock_file(store).write_bytes(content)
    _age(_lock_file(store), age_s)
    t0 = time.monotonic()
    with client_lock(store) as lk:
        assert lk.held and _holder(store)["token"] == lk.owner["token"]
        assert _holder(store)["pid"] == os.getpid()
    assert time.monotonic() - t0 < (1.0 if age_s == 0.0 else 0.25)
    assert not _lock_file(store).exists()
    assert not list((store / "records").glob(".lock-*"))  # no temporaries left


def _dead_pid() -> int:
    """A PID of no running process (of a child that has exited and been reaped)."""
    import subprocess
    import sys

    p = subprocess.Popen([sys.executable, "-c", "pass"])
    p.wait()
    return p.pid


def test_lock_of_a_dead_process_or_a_reused_pid_is_taken_over(store):
    me = this_process()
    for owner in (
        {"host": me["host"], "pid": _dead_pid()},  # the format of earlier versions
        {**me, "pid": _dead_pid(), "token": "x"},
        # the PID is alive but belongs to a process started at another time: reused
        {**me, "pid": os.getppid(), "start": -1, "token": "x"},
    ):
        _lock_file(store).write_text(json.dumps(owner))
        with client_lock(store) as lk:
            assert _holder(store)["token"] == lk.owner["token"]
        assert not _lock_file(store).exists()


def test_live_locks_are_in_use_with_their_owner(store):
    me = this_process()
    with client_lock(store):  # another client in this very process (another token)
        with pytest.raises(
            ConfigError,
            match=rf"^dataset = '{store}' is in use by the sweep client {me['host']}:"
            rf"{os.getpid()} \(a running process of this host; lock '{_lock_file(store)}'\)",
        ):
            with client_lock(store):
                pass
        assert _holder(store)["pid"] == os.getpid()  # untouched
    # another host: its processes cannot be seen; in use until not refreshed for 300 s
    other = {"host": "node7", "pid": 1, "start": 5, "boot_id": "b", "token": "t"}
    _lock_file(store).write_text(json.dumps(other))
    _age(_lock_file(store), locks.LOCK_STALE_S - 30.0)
    with pytest.raises(ConfigError, match=r"in use by the sweep client node7:1 \(refreshed 27\d s"):
        client_lock(store).acquire()
    assert _holder(store) == other
    # this host name, another boot id: this host before a reboot, or another machine of the
    # same name: judged by age too
    _lock_file(store).write_text(json.dumps({**other, "host": me["host"]}))
    with pytest.raises(ConfigError, match=r"in use by the sweep client .*refreshed 0 s ago"):
        client_lock(store).acquire()
    (store / "records" / ".lock").unlink()
    (store / "records" / ".lock").mkdir()  # a lock that cannot be read
    with pytest.raises(ConfigError, match=r"lock '.*\.lock' of dataset '.*' cannot be read"):
        client_lock(store).acquire()


def test_stale_lock_of_another_host_is_taken_over(store):
    other = {"host": "node7", "pid": 1, "start": 5, "boot_id": "b", "token": "t"}
    _lock_file(store).write_text(json.dumps(other))
    _age(_lock_file(store), locks.LOCK_STALE_S + 1.0)
    with client_lock(store) as lk:
        assert _holder(store)["token"] == lk.owner["token"]


def test_lock_without_hard_links_or_flock(store, monkeypatch):
    """File systems without hard links (some FUSE and SMB mounts) or without locks (NFS
    mounted ``nolock``): the lock is created with ``O_EXCL`` and written at once, and the
    decision is not serialized; it still works and is still refused when live."""
    import errno
    import fcntl

    def no_link(*a, **k):
        raise PermissionError(errno.EPERM, "Operation not permitted")

    def no_flock(*a, **k):
        raise OSError(errno.ENOLCK, "No locks available")

    monkeypatch.setattr(os, "link", no_link)
    monkeypatch.setattr(fcntl, "flock", no_flock)
    _lock_file(store).write_text(json.dumps({"host": this_process()["host"], "pid": _dead_pid()}))
    with client_lock(store) as lk:
        assert _holder(store)["token"] == lk.owner["token"]
        with pytest.raises(ConfigError, match="is in use by the sweep client"):
            client_lock(store).acquire()
    assert not _lock_file(store).exists()

    def read_only(*a, **k):
        raise PermissionError(errno.EACCES, "Permission denied")

    monkeypatch.setattr(ClientLock, "_write_tmp", read_only)
    with pytest.raises(ConfigError, match=r"the lock '.*' cannot be written \(Permission denied\)"):
        client_lock(store).acquire()


def test_lock_temporary_removed_by_the_holders_cleaner_is_still_in_use(store, monkeypatch):
    """The holder's ``remove_stale_temporaries`` deletes every ``records/.lock-*``, also the
    temporary a second client is judging the lock with (CI, 2026-12-07: two clients at once on
    a new dataset; the loser said "the lock cannot be written (No such file or directory)"
    instead of "in use"). The temporary is written again; the answer is "in use"."""
    link = ClientLock._link
    removed = []

    def link_then_clean(self, tmp):
        ok = link(self, tmp)
        if not ok and len(removed) < 3:  # the cleaner runs between the link and the look
            removed.append(remove_stale_temporaries(store))
        return ok

    with client_lock(store):
        monkeypatch.setattr(ClientLock, "_link", link_then_clean)
        with pytest.raises(ConfigError, match=r"is in use by the sweep client .*running process"):
            client_lock(store).acquire()
    assert removed == [1, 1, 1]  # the temporary was there to be removed, three times
    assert not list((store / "records").glob(".lock-*"))


def test_an_unreadable_file_is_not_called_damage():
    """Exploratory testing (twenty-seventh session): a file of the dataset this user may not
    read was reported as damage, "delete the dataset and run the sweep again": the wrong, and
    a risky, advice on a shared machine. A permission error says so and what to do."""
    import errno

    from bearingsim.sweep.store import damaged_error

    e = damaged_error("d.zarr", "d.zarr/status/3", "cannot be read",
                      PermissionError(errno.EACCES, "Permission denied"))  # fmt: skip
    assert str(e) == (
        "dataset = 'd.zarr': 'd.zarr/status/3' cannot be read (permission denied); check its "
        "permissions, or ask the dataset's owner"
    )
    e = damaged_error("d.zarr", "d.zarr/status/3", "is truncated")
    assert "is damaged" in str(e) and "delete the dataset" in str(e)


def test_judge_lock_rules():
    me = {"host": "a", "pid": os.getpid(), "start": this_process()["start"], "boot_id": "b1"}
    assert judge_lock(me, 0.0, me)[0] is False
    assert judge_lock({**me, "boot_id": None}, 0.0, me)[0] is False  # older format: pid only
    assert judge_lock({**me, "pid": _dead_pid()}, 0.0, me)[0] is True
    assert judge_lock({**me, "boot_id": "b0"}, 1e4, me)[0] is True  # another boot, old
    assert judge_lock({**me, "boot_id": "b0"}, 10.0, me)[0] is False
    assert judge_lock({**me, "host": "z"}, locks.LOCK_STALE_S, me)[0] is True
    assert judge_lock(None, 0.0, me)[0] is None  # empty and young: wait
    assert judge_lock({"pid": True, "host": "a"}, 0.0, me)[0] is False  # not a PID: by age
    # ... and said so: it was "a lock of another host" (exploratory testing, 27th session)
    assert (
        "a lock without a readable PID is taken over"
        in judge_lock({"pid": "abc", "host": "a"}, 5.0, me)[1]
    )
    assert "a lock of another host" in judge_lock({"pid": 1, "host": "z"}, 5.0, me)[1]


def race(n: int, fn) -> list:
    """Run ``fn()`` in ``n`` threads released at once; their results or exceptions."""
    barrier = threading.Barrier(n)
    out: list = []

    def one() -> None:
        barrier.wait()
        try:
            out.append(fn())
        except Exception as exc:
            out.append(exc)

    threads = [threading.Thread(target=one) for _ in range(n)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    return out


def test_concurrent_takeovers_of_a_stale_lock_leave_one_holder(store):
    """Eight clients (threads) take the same stale lock over at once, 15 times: exactly one
    holds it each time, the others are told it is in use."""

    def take() -> ClientLock:
        lk = ClientLock(store)
        lk.acquire()
        return lk

    for _ in range(15):
        _lock_file(store).write_text(json.dumps({"host": "node7", "pid": 1}))
        _age(_lock_file(store), locks.LOCK_STALE_S + 1.0)
        out = race(8, take)
        held = [r for r in out if isinstance(r, ClientLock)]
        errors = [r for r in out if not isinstance(r, ClientLock)]
        assert len(held) == 1 and len(errors) == 7, out
        assert all("is in use by the sweep client" in str(e) for e in errors), errors
        assert _holder(store)["token"] == held[0].owner["token"]
        held[0].release()
        assert not _lock_file(store).exists()
    assert not list((store / "records").glob(".lock-*"))


def test_heartbeat_refreshes_and_notices_a_takeover(store, monkeypatch):
    monkeypatch.setattr(locks, "LOCK_REFRESH_S", 0.05)
    with client_lock(store) as lk:
        _age(_lock_file(store), 100.0)
        deadline = time.monotonic() + 5.0
        while time.time() - _lock_file(store).stat().st_mtime > 50.0:
            assert time.monotonic() < deadline, "the heartbeat did not refresh the lock"
            time.sleep(0.02)
        lk.check()  # still ours
        thief = {"host": "node7", "pid": 9, "token": "other"}
        _lock_file(store).write_text(json.dumps(thief))
        while lk.lost is None:
            assert time.monotonic() < deadline, "the heartbeat did not notice the takeover"
            time.sleep(0.02)
        with pytest.raises(ConfigError, match=r"the lock was taken over by the sweep client "):
            lk.check()
    assert _holder(store) == thief  # not removed: it is not ours
    _lock_file(store).unlink()
    with client_lock(store) as lk:
        _lock_file(store).unlink()  # deleted by hand
        assert not lk.refresh()
        with pytest.raises(ConfigError, match=r"the lock '.*\.lock' of this client was removed"):
            lk.check()


# ---------------------------------------------------------------------------- creation
def test_concurrent_creation_one_winner_intact(tmp_path):
    """Four clients (threads) create the same new dataset at once, five times: exactly one
    creates it, locked by it from the first instant; the others get ``DatasetExistsError``,
    then the "in use" error when they take the lock; nothing else is left behind."""

    def create(out: Path):
        lk = ClientLock(out)
        try:
            new_store(out, lock=lk)
            lk.adopt()
            return lk
        except DatasetExistsError:
            lk.acquire()  # the winner holds it: ConfigError "in use"
            return lk  # a second holder: fails below

    for k in range(5):
        out = tmp_path / f"d{k}.zarr"
        res = race(4, lambda out=out: create(out))
        won = [r for r in res if isinstance(r, ClientLock)]
        assert len(won) == 1, res
        assert all("is in use by the sweep client" in str(e) for e in res if e is not won[0])
        assert _holder(out)["token"] == won[0].owner["token"]
        assert_array_equal(read_status(out), [PENDING] * SPEC.n_runs)  # intact
        assert read_attrs(out)["spec_hash"] == SPEC.spec_hash
        won[0].release()
    assert sorted(p.name for p in tmp_path.iterdir()) == [f"d{k}.zarr" for k in range(5)]


def test_rename_lost_to_another_client(tmp_path, monkeypatch):
    """The loser's rename onto the winner's directory (``OSError: Directory not empty`` in
    the issue) becomes ``DatasetExistsError``; its temporary directory is removed."""
    out = tmp_path / "d.zarr"
    rename = os.rename

    def winner_first(src, dst):
        if Path(dst) == out and not out.exists():
            monkeypatch.setattr(os, "rename", rename)
            new_store(out)  # the other client, between our check and our rename
        return rename(src, dst)

    monkeypatch.setattr(os, "rename", winner_first)
    with pytest.raises(DatasetExistsError, match="was created by another client meanwhile"):
        new_store(out)
    assert [p.name for p in tmp_path.iterdir()] == ["d.zarr"]
    assert_array_equal(read_status(out), [PENDING] * SPEC.n_runs)


def test_stale_creation_directories_are_removed(tmp_path):
    """A client killed while creating leaves ``.NAME.creating-*``: removed by the next
    creation when its lock names a dead process; a live creation is left alone."""
    out = tmp_path / "d.zarr"
    me = this_process()
    for name, owner in (("dead", {**me, "pid": _dead_pid()}), ("live", me)):
        d = tmp_path / f".d.zarr.creating-{name}"
        (d / "records").mkdir(parents=True)
        (d / "records" / ".lock").write_text(json.dumps(owner))
    young = tmp_path / ".d.zarr.creating-nolock"  # killed before its lock was written
    young.mkdir()
    new_store(out)
    left = sorted(p.name for p in tmp_path.iterdir())
    assert left == [".d.zarr.creating-live", ".d.zarr.creating-nolock", "d.zarr"]
    _age(young, locks.CREATION_LOCKLESS_S - 5.0)  # written to milliseconds ago: kept
    assert locks.remove_stale_creations(out) == 0 and young.exists()
    # 30 s, not 300: a Ctrl-C during creation left a lockless one that a rerun kept
    # (exploratory testing, twenty-seventh session)
    _age(young, locks.CREATION_LOCKLESS_S + 1.0)
    assert locks.remove_stale_creations(out) == 1 and not young.exists()
    # a dataset --force-new renamed aside, its client killed before the deletion ended
    # (read from the code in the twenty-seventh session; twenty-eighth): removed at any age
    aside = tmp_path / ".d.zarr.removing-0123abcd"
    (aside / "signal").mkdir(parents=True)
    (aside / "signal" / "0.0").write_bytes(b"x")
    assert locks.remove_stale_creations(out) == 1 and not aside.exists()
    assert sorted(p.name for p in tmp_path.iterdir()) == [".d.zarr.creating-live", "d.zarr"]
    # a name with glob characters: its own leftovers, not another dataset's (a helper,
    # twenty-eighth session: "ds[12].zarr" removed ".ds2.zarr.removing-*" and kept its own)
    other = tmp_path / ".ds2.zarr.removing-x"
    own = tmp_path / ".ds[12].zarr.removing-y"
    other.mkdir()
    own.mkdir()
    assert locks.remove_stale_creations(tmp_path / "ds[12].zarr") == 1
    assert other.exists() and not own.exists()


def test_a_resume_removes_a_stale_creation_beside_the_dataset(store):
    """A lockless ``.NAME.creating-*`` older than 30 s is removed by a run on the existing
    dataset too (it was only by the next creation, which a dataset that exists never has)."""
    w = RunWriter(store)
    commit(w, 5)  # every run committed: the run needs no cluster
    w.close()
    old = store.parent / f".{store.name}.creating-x"
    (old / "signal").mkdir(parents=True)
    _age(old, locks.CREATION_LOCKLESS_S + 1.0)
    rep = run_sweep(SPEC, store, client=_NoCluster())
    assert rep.n_skipped == SPEC.n_runs and not old.exists()


def test_resuming_a_dataset_in_use_is_refused_before_any_work(store):
    with client_lock(store):
        with pytest.raises(ConfigError, match=rf"^dataset = '{store}' is in use by the sweep"):
            run_sweep(SPEC, store, client=_NoCluster())
        assert _holder(store)["pid"] == os.getpid()


SPEC_TOML = """
[sweep]
label = "fault"
[base]
model = "dem"
duration_s = 0.005
fs_hz = 4000.0
[axes]
fault = ["none", "outer", "inner"]
rpm = [1730.0, 1797.0]
"""


def test_cli_run_in_use_or_damaged_is_one_line(store, tmp_path, run_cli):
    """``sweep run`` on a dataset in use, or damaged, is refused in one line before a cluster
    starts (a cluster would take seconds; this test takes milliseconds)."""
    spec = tmp_path / "sweep.toml"
    spec.write_text(SPEC_TOML)
    assert SweepSpec.from_toml(spec).spec_hash == SPEC.spec_hash
    with client_lock(store):
        r = run_cli("sweep", "run", spec, "-o", store, "--workers", "1")
    assert r.code == 2 and r.out == "" and len(r.err.splitlines()) == 1, r.err
    assert r.err.startswith(f"error: dataset = '{store.absolute()}' is in use by the sweep client ")
    (store / "status" / "3").write_bytes(b"")
    r = run_cli("sweep", "run", spec, "-o", store, "--workers", "1")
    assert r.code == 2 and r.out == "" and len(r.err.splitlines()) == 1, r.err
    assert f"is damaged: '{store}/status/3' is empty; valid: one byte 0 (pending)" in r.err


def test_replacing_a_dataset_in_use_is_refused(store):
    with client_lock(store):
        with pytest.raises(ConfigError, match="is in use by the sweep client"):
            _remove_dataset(store)
        assert_array_equal(read_status(store)[:5], [OK, OK, OK, OK, FAILED])
    _remove_dataset(store)
    assert not store.exists() and list(store.parent.iterdir()) == []


def test_lock_temporaries_are_stale_temporaries(store):
    (store / "records" / ".lock-abc").write_text("{}")
    (store / "records" / ".lock-abc-stale").write_text("{}")
    assert remove_stale_temporaries(store) == 2


# ------------------------------------------------------------------------------- counts
def test_counts_include_runs_whose_task_never_reported(store):
    """Worker killed after committing runs (its task never reports them), Ctrl-C before a
    task finished: the counts come from the disk. Runs 0-3 ok and 4 failed before this
    call; this call (``--retry-failed``) had runs 4 and 5 to do."""
    st0 = read_status(store)
    offsets = records_offsets(store)
    todo = np.array([4, 5])
    w = RunWriter(store)
    commit(w, 5, compute_s=0.25)  # by a task that was lost with its worker
    commit(w, 4, FAILED, compute_s=0.5)  # retried, failed again, also never reported
    w.close()
    rep = SweepReport(out=str(store), n_runs=6, n_skipped=4)
    _exact_counts(rep, store, todo, st0, set(), offsets)
    assert (rep.n_ok, rep.n_failed, rep.n_pending) == (5, 1, 0)
    assert (rep.n_computed, rep.n_failed_now) == (2, 1)
    assert rep.compute_s == pytest.approx(0.75) and rep.compute_cpu_s == pytest.approx(0.75)
    # only what was reported counts again; a retried run not recomputed is not computed
    rep = SweepReport(out=str(store), n_runs=6, n_skipped=4, compute_s=0.25)
    _exact_counts(rep, store, todo, st0, {5}, records_offsets(store))
    assert (rep.n_computed, rep.n_failed_now, rep.compute_s) == (1, 0, 0.25)
    assert read_records(store, read_status(store))[5]["compute_s"] == 0.25


def test_lock_in_a_new_dataset_from_its_first_instant(tmp_path):
    out = tmp_path / "d.zarr"
    lk = ClientLock(out)
    new_store(out, lock=lk)
    assert _holder(out)["token"] == lk.owner["token"] and not lk.held
    with pytest.raises(ConfigError, match="is in use by the sweep client"):
        client_lock(out).acquire()
    lk.adopt()
    lk.release()
    assert not _lock_file(out).exists()
    assert socket.gethostname() == lk.owner["host"]
