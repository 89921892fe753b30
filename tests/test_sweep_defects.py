"""Sweep defects found in review: runs committed ok whose signal chunk files were lost are refused
by every reader and computed again by ``sweep run`` (never served as NaN); an empty sweep file;
the table-axis message; the plan's wall-time estimate with more workers than runs; the text of a
``sweep run`` with nothing to do; random splits with an empty side.

Most tests build their dataset with ``create_dataset`` and ``RunWriter`` directly, as
``run_sweep`` does (no cluster); the resume tests start one local cluster of one worker."""

from __future__ import annotations

import json
import re
import shutil
import warnings
from pathlib import Path

import numpy as np
import pytest
from numpy.testing import assert_array_equal
from test_sweep_cli import SPEC as RUN_TOML  # the cluster sweeps: 4 short DEM runs
from test_sweep_store import commit, new_store  # the six-run store of the reader tests

from bearingsim.errors import ConfigError
from bearingsim.sweep import store as stores
from bearingsim.sweep.dataset import SplitWarning, open_dataset
from bearingsim.sweep.execute import LostDataWarning, connect, run_sweep
from bearingsim.sweep.plan import plan_sweep
from bearingsim.sweep.spec import SweepSpec
from bearingsim.sweep.store import FAILED, PENDING, RunWriter, read_status

#: the store's spec (6 runs, labels none, none, outer, outer, inner, inner) as a sweep file, for
#: the resume from the command line; the store itself is tests/test_sweep_store.py's
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


def make_store(path: Path, ok: range, failed: tuple[int, ...] = ()) -> Path:
    """A dataset of ``SPEC`` with the runs ``ok`` committed ok, ``failed`` failed, the rest
    pending."""
    new_store(path)
    w = RunWriter(path)
    for i in ok:
        commit(w, i)
    for i in failed:
        commit(w, i, FAILED)
    w.close()
    return path


@pytest.fixture
def store(tmp_path) -> Path:
    """Runs 0-3 ok, run 4 failed, run 5 pending."""
    return make_store(tmp_path / "ds.zarr", range(4), (4,))


def one_line(exc_info) -> str:
    msg = str(exc_info.value)
    assert len(msg.splitlines()) == 1, msg
    return msg


# ------------------------------------------------------------------------------ lost chunks
@pytest.mark.parametrize("listing", [False, True], ids=["stat-per-run", "directory-listing"])
def test_lost_signal_chunks_are_refused_by_every_reader(store, run_cli, monkeypatch, listing):
    """A run committed ok whose signal chunk file is gone is refused in one line naming the
    dataset, the run and the chunk, with what to do (before: NaN served as data, summary ok)."""
    if listing:  # the check of many runs lists the directory once instead of a stat per run
        monkeypatch.setattr(stores, "LIST_DIR_RUNS", 0)
    good = open_dataset(store).arrays()[0]
    for i in (1, 3):
        (store / "signal" / f"{i}.0.0").unlink()
    ds = open_dataset(store)  # opening checks nothing per run (cheap)
    what = (
        rf"^dataset = '{store}' is damaged: '{store}/signal/1\.0\.0' is missing \(the signal "
        r"chunk of run 1, committed ok; 2 runs committed ok have lost theirs: 1, 3\); run "
        r"'bearingsim sweep run' again with the dataset's sweep file and this dataset as -o: "
        r"it computes the runs whose signal chunk is missing again$"
    )
    for call in (
        lambda: ds.arrays(["acc_x"]),
        lambda: ds.completed().arrays(),
        lambda: ds.summary(),
        lambda: ds.xr,
    ):
        with pytest.raises(ConfigError, match=what) as e:
            call()
        one_line(e)
    one = r"'.*/signal/3\.0\.0' is missing \(the signal chunk of run 3, committed ok\); run 'bea"
    with pytest.raises(ConfigError, match=one):
        ds.result(3)
    # the runs that kept their chunks, the failed and the pending runs read as before
    intact = ds.select(fault="none").select(rpm=1730.0)  # run 0
    assert_array_equal(intact.arrays()[0], good[[0]])
    assert_array_equal(ds.result(2)["acc_x"], good[2, 0])
    rest = ds.select(fault="inner")  # run 4 failed, run 5 pending: no chunks, NaN is normal
    assert_array_equal(read_status(store)[rest.runs], [FAILED, PENDING])
    assert np.isnan(rest.arrays()[0]).all()
    assert rest.summary()["n_failed"] == 1 and ds.labels().size == 6 and ds.records()[0]
    r = run_cli("sweep", "summary", store)
    assert r.code == 2 and r.out == "" and len(r.err.splitlines()) == 1, r.err
    assert r.err.startswith(f"error: dataset = '{store}' is damaged: '{store}/signal/1.0.0'")


def test_the_check_reads_no_chunk(store):
    """Only the chunk files' existence is checked: a summary of a dataset whose chunks hold
    garbage reads none of them (the arrays then refuse it when they read it)."""
    for i in range(4):
        (store / "signal" / f"{i}.0.0").write_bytes(b"garbage")
    (store / "signal" / "0.0.0").unlink()
    ds = open_dataset(store)
    with pytest.raises(ConfigError, match=r"'.*/signal/0\.0\.0' is missing \(the signal chunk"):
        ds.summary()
    s = ds.select(rpm=1797.0).summary()  # runs 1, 3, 5: chunks exist (garbage), not read
    assert (s["n_ok"], s["n_pending"]) == (2, 1)
    with pytest.raises(ConfigError, match=r"'.*/signal/1\.0\.0' cannot be decoded"):
        ds.result(1)


def test_failed_run_without_its_error_is_refused(store, run_cli):
    (store / "error" / "4").unlink()
    r = run_cli("sweep", "summary", store)
    assert r.code == 2 and r.out == "" and len(r.err.splitlines()) == 1, r.err
    assert r.err.strip() == (
        f"error: dataset = '{store}' is damaged: '{store}/error/4' is missing or empty (the "
        "error of run 4, committed failed); run 'bearingsim sweep run' again with the "
        "dataset's sweep file, this dataset as -o and --retry-failed: it computes the failed "
        "runs again"
    )


def test_result_of_a_run_out_of_range_is_one_line(store):
    for run in (6, -1, 1.5):
        with pytest.raises(ConfigError, match=r"^run = .* is out of range; valid range \[0, 5\]"):
            open_dataset(store).result(run)


@pytest.fixture(scope="module")
def client():
    with connect(workers=1) as (cl, _):
        yield cl


@pytest.mark.integration
def test_resume_recomputes_runs_that_lost_their_chunks(client, tmp_path):
    """``run_sweep`` sets runs committed ok without their signal chunk back to pending and
    computes them again, with a warning (before: "2 already committed", NaN kept)."""
    spec_file = tmp_path / "s.toml"
    spec_file.write_text(RUN_TOML)
    spec = SweepSpec.from_toml(spec_file)
    out = tmp_path / "ds.zarr"
    assert run_sweep(spec, out, client=client).n_ok == 4
    X0, _ = open_dataset(out).arrays()
    copy = tmp_path / "copy.zarr"
    shutil.copytree(out, copy)
    for i in (1, 2):
        (copy / "signal" / f"{i}.0.0").unlink()
    with pytest.warns(LostDataWarning) as caught:
        rep = run_sweep(spec, copy, client=client)
    assert len(caught) == 1
    assert str(caught[0].message) == (
        f"dataset = '{copy}': 2 run(s) committed ok had lost their signal chunk (1, 2; "
        f"'{copy}/signal/1.0.0' is missing): set back to pending and computed again"
    )
    assert (rep.n_lost, rep.n_skipped, rep.n_computed, rep.n_ok, rep.n_pending) == (2, 2, 2, 4, 0)
    ds = open_dataset(copy)
    assert_array_equal(ds.arrays()[0], X0)  # bit for bit, as the first time
    # runs 0 and 3 were not computed again: one record line each in the copy
    lines = [
        json.loads(x)
        for f in (copy / "records").glob("*.jsonl")
        for x in f.read_text().splitlines()
    ]
    assert sorted(r["run"] for r in lines) == [0, 1, 1, 2, 2, 3]
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # nothing lost any more: no warning, nothing to do
        assert run_sweep(spec, copy, client=client).n_skipped == 4


@pytest.mark.integration
def test_cli_run_recomputes_lost_runs_and_says_so(run_cli, tmp_path):
    spec_file = tmp_path / "s.toml"
    spec_file.write_text(RUN_TOML)
    out = tmp_path / "ds.zarr"
    assert run_cli("sweep", "run", spec_file, "-o", out, "--workers", "1").code == 0
    (out / "signal" / "3.0.0").unlink()
    assert run_cli("sweep", "summary", out).code == 2
    r = run_cli("sweep", "run", spec_file, "-o", out, "--workers", "1")
    assert r.code == 0, r.err
    lines = [x for x in r.err.splitlines() if x.startswith("warning: ")]
    assert lines == [
        f"warning: dataset = '{out}': 1 run(s) committed ok had lost their signal chunk (3; "
        f"'{out}/signal/3.0.0' is missing): set back to pending and computed again"
    ], r.err
    assert "3 already committed, 1 computed (1 ok, 0 failed)" in r.out
    r = run_cli("sweep", "summary", out, "--json")
    assert r.code == 0 and r.json()["n_ok"] == 4


# ------------------------------------------------------------------------------------- nits
def test_empty_sweep_file_is_refused(run_cli, tmp_path):
    empty = tmp_path / "empty.toml"
    empty.write_bytes(b"")
    r = run_cli("sweep", "plan", empty, "--timing-runs", "0")
    assert r.code == 2 and r.out == "", r.out
    assert r.err.strip() == (
        "error: empty.toml: the sweep file is empty; valid: a [base] scenario (or "
        "sweep.base_file) and/or [axes]"
    )
    named = tmp_path / "named.toml"
    named.write_text('[sweep]\nname = "x"\n')
    r = run_cli("sweep", "plan", named, "--timing-runs", "0")
    assert (
        r.code == 2 and "named.toml: the sweep has no [base], no sweep.base_file and no " in r.err
    )
    base_only = tmp_path / "base.toml"
    base_only.write_text('[base]\nmodel = "dem"\nduration_s = 0.05\n')
    r = run_cli("sweep", "plan", base_only, "--timing-runs", "0")
    assert r.code == 0 and "1 runs (cartesian: no axes)" in r.out, r.err


def test_table_axis_message_has_single_braces():
    with pytest.raises(ConfigError) as e:
        SweepSpec.from_dict({"base": {"model": "dem"}, "axes": {"rpm": {"values": [1.0], "n": 2}}})
    assert one_line(e).endswith(
        "axes.rpm has keys ['n', 'values']; a value list is { values = [...] } alone"
    )


def test_plan_wall_time_is_at_least_one_run():
    """More workers than runs: the wall time is one run's, not the total over the workers."""
    spec = SweepSpec.from_dict(
        {
            "base": {"model": "dem", "duration_s": 0.05, "fs_hz": 4000.0},
            "axes": {"fault": ["outer", "inner"], "rpm": [1730.0, 1797.0]},
        }
    )
    many = plan_sweep(spec, timing_runs=1, timing_duration_s=0.01, workers=100_000)
    # every run has the same model and duration: each is estimated at the mean
    assert many.wall_s == pytest.approx(many.compute_s_per_run, rel=1e-12)
    assert many.workers == 100_000
    two = plan_sweep(spec, timing_runs=1, timing_duration_s=0.01, workers=2)
    assert two.wall_s == pytest.approx(two.compute_s_total / 2, rel=1e-12)
    assert np.isnan(plan_sweep(spec, timing_runs=0, workers=2).wall_s)  # no estimate


def test_run_with_nothing_to_do_says_so(run_cli, tmp_path):
    """Every run committed: no cluster starts, and the line says so (before: '... in 0 s on ')."""
    out = make_store(tmp_path / "ds.zarr", range(5), (5,))
    spec = tmp_path / "s.toml"
    spec.write_text(SPEC_TOML)
    r = run_cli("sweep", "run", spec, "-o", out)
    assert r.code == 0, r.err
    assert r.out.splitlines() == [
        f"{out}: 6 runs; 6 already committed, 0 computed: nothing to do",
        "  dataset: 5 ok, 1 failed, 0 pending",
    ]


def test_random_split_with_an_empty_side_is_refused(store):
    ds = open_dataset(store).completed()  # runs 0-3: none, none, outer, outer
    with pytest.raises(ConfigError) as e:
        ds.random_split(0.25)  # round(0.25 x 2) = 0 of each label
    assert one_line(e) == (
        "test_fraction = 0.25 of 4 run(s) leaves the test set empty (round(test_fraction x the "
        "runs of each label): none (2 run(s), none in the test set), outer (2 run(s), none in "
        "the test set)); valid: a test_fraction that puts at least one run on each side, or "
        "stratify=False"
    )
    with pytest.raises(ConfigError, match=r"^test_fraction = 0\.9 of 4 run\(s\) leaves the train"):
        ds.random_split(0.9)
    with pytest.warns(SplitWarning):  # one test run: the other label is on one side only
        a, b = ds.random_split(0.25, stratify=False)  # round(0.25 x 4) = 1
    assert (len(a), len(b)) == (3, 1)


def test_an_unstratified_split_warns_of_a_label_on_one_side_only(store):
    # twenty-first session: random_split(stratify=False) only checked the whole selection,
    # so a split putting both "none" runs in train and both "outer" runs in test was silent
    ds = open_dataset(store).completed()  # runs 0-3: none, none, outer, outer
    for seed in range(50):
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", SplitWarning)
            a, b = ds.random_split(0.5, stratify=False, seed=seed)
        if sorted(b.labels()) in (["none", "none"], ["outer", "outer"]):
            break
    else:  # pragma: no cover - 50 draws of 2 of 4
        pytest.fail("no seed split the labels apart")
    with pytest.warns(SplitWarning, match=r"none \(2 run\(s\), none in the (train|test) set\)"):
        ds.random_split(0.5, stratify=False, seed=seed)


def test_random_split_warns_when_a_label_is_on_one_side_only(tmp_path):
    ds = open_dataset(make_store(tmp_path / "ds.zarr", range(5))).completed()
    with pytest.warns(SplitWarning) as caught:
        a, b = ds.random_split(0.5, seed=3)  # none 2, outer 2, inner 1: round(0.5) = 0
    assert str(caught[0].message) == (
        "random_split(test_fraction = 0.5): label inner (1 run(s), none in the test set); "
        "these labels are on one side only"
    )
    assert sorted(b.labels()) == ["none", "outer"] and sorted(a.labels()) == [
        "inner",
        "none",
        "outer",
    ]


def test_a_rotor_sweep_is_planned(tmp_path):
    """A rotor sweep failed at its spec hash (exploratory testing, fourteenth session): the
    hash resolved a ring bearing the rotor family has no key for, and said "bearing: give
    exactly one of a catalogue id or --bearing-file PATH"."""
    p = tmp_path / "rotor.toml"
    p.write_text(
        '[base]\nmodel = "rotor"\nduration_s = 0.02\nfs_hz = 12000.0\nde_fault = "ball"\n'
        'rig = "cwru-de-12k"\n[axes]\nseed = [0, 1]\n',
        encoding="utf-8",
    )
    spec = SweepSpec.from_toml(p)
    assert spec.n_runs == 2 and len(spec.spec_hash) == 64
    assert "bearings" in spec.canonical() and spec.canonical()["bearings"] == {}


def test_an_edited_rig_file_is_a_changed_spec(tmp_path, monkeypatch):
    """The spec hash covers the rig's content, as it covers a bearing file's: resuming a sweep
    after its rig file was edited (a model gain 0.5 -> 5) mixed runs of both gains in one
    dataset (exploratory testing, fourteenth session); now the hashes differ, so the resume is
    refused as a different spec."""
    from bearingsim.rig import load_rig
    from bearingsim.rig_identify import rig_to_toml

    monkeypatch.chdir(tmp_path)
    rig = load_rig("cwru-de-12k")
    (tmp_path / "myrig.toml").write_text(rig_to_toml(rig), encoding="utf-8")
    p = tmp_path / "ring.toml"
    p.write_text(
        '[base]\nmodel = "vsm"\nduration_s = 0.02\nfs_hz = 12000.0\nrig = "myrig.toml"\n'
        "[axes]\nseed = [0, 1]\n",
        encoding="utf-8",
    )
    before = SweepSpec.from_toml(p).spec_hash
    text = (tmp_path / "myrig.toml").read_text(encoding="utf-8")
    edited = re.sub(r"scale = ([0-9.e+-]+)", lambda m: f"scale = {10 * float(m[1])!r}", text,
                    count=1)  # fmt: skip
    assert edited != text
    (tmp_path / "myrig.toml").write_text(edited, "utf-8")
    assert SweepSpec.from_toml(p).spec_hash != before


def test_a_selection_that_matches_no_run_is_refused(store):
    # twenty-first session: ds.select(rig="rig.toml") silently gave 0 runs (runs store a rig
    # file by its absolute path); any value that matches no run is now named, with the values
    # present, as split() does
    ds = open_dataset(store).completed()  # runs 0-3: none, none, outer, outer
    with pytest.raises(ConfigError, match=r"^fault = 'inner' matches no run; values present: "):
        ds.select(fault="inner")
    assert len(ds.select(fault=["inner", "outer"])) == 2  # one value of a list may be absent


def test_a_rig_file_is_selected_by_the_name_the_sweep_file_gave(tmp_path, monkeypatch):
    from bearingsim.rig import load_rig
    from bearingsim.rig_identify import rig_to_toml
    from bearingsim.sweep import SweepSpec, run_sweep

    monkeypatch.chdir(tmp_path)
    (tmp_path / "myrig.toml").write_text(rig_to_toml(load_rig("cwru-de-12k")), encoding="utf-8")
    (tmp_path / "s.toml").write_text(
        '[base]\nmodel = "vsm"\nduration_s = 0.02\nfs_hz = 12000.0\n'
        '[axes]\nrig = ["myrig.toml", "cwru-de-12k"]\n'
    )
    run_sweep(SweepSpec.from_toml("s.toml"), "o.zarr", workers=1, progress=False)
    ds = open_dataset("o.zarr")
    assert len(ds.select(rig="myrig.toml")) == 1 and len(ds.select(rig="cwru-de-12k")) == 1
    assert ds.scenario(int(ds.select(rig="myrig.toml").runs[0]))["rig"] == str(
        tmp_path / "myrig.toml"
    )


def test_selections_and_splits_say_when_nothing_or_everything_matches(tmp_path, monkeypatch):
    # twenty-first session (a helper on this session's changes): conditions that matched runs
    # each but none together gave an empty view in silence; a set of values matched nothing;
    # split() put every run in the test set without a word; a dataset opened by a relative
    # path failed after os.chdir
    ds = open_dataset(make_store(tmp_path / "ds.zarr", range(5))).completed()
    assert sorted(ds.param("fault")) == ["inner", "none", "none", "outer", "outer"]
    inner_rpm = float(ds.select(fault="inner").param("rpm")[0])
    other = next(r for r in ds.param("rpm") if r != inner_rpm)
    with pytest.raises(ConfigError, match="no run has all of these"):
        ds.select(fault="inner", rpm=float(other))
    assert len(ds.select(fault={"none", "outer"})) == 4
    with pytest.raises(ConfigError, match=r"holds every run \('fault'"):
        ds.split("fault", ["none", "outer", "inner"])
    monkeypatch.chdir(tmp_path)
    rel = open_dataset("ds.zarr")
    (tmp_path / "elsewhere").mkdir()
    monkeypatch.chdir(tmp_path / "elsewhere")
    assert len(rel.completed().select(fault="outer")) == 2


def test_force_new_refuses_a_sweep_file_inside_the_dataset(run_cli, tmp_path):
    # twenty-first session: `sweep run ds.zarr/sweep.toml -o ds.zarr --force-new` removed the
    # dataset folder and the sweep file in it
    store = make_store(tmp_path / "ds.zarr", range(2))
    spec = store / "sweep.toml"
    spec.write_text('[base]\nmodel = "vsm"\nduration_s = 0.01\n[axes]\nrpm = [1730.0, 1797.0]\n')
    r = run_cli("sweep", "run", spec, "-o", store, "--force-new", "--workers", "1")
    assert r.code == 2 and "lies inside -o/--output" in r.err and spec.is_file()


# ------------------------------------------------------------------ runs that cannot start
#: five VSM runs, the first four with an outer-race slot wider than the 6205's ball (7.94 mm,
#: the catalogue's ``d``): model-level errors the sweep file's own fields do not show
WIDE_TOML = """
[base]
model = "vsm"
duration_s = 0.005
fs_hz = 4000.0
fault = "outer"
[axes]
defect_width_m = [9e-3, 10e-3, 11e-3, 12e-3, 1e-3]
"""


def test_plan_lists_the_runs_that_cannot_start(tmp_path, run_cli):
    """``sweep plan`` checked the sweep file's fields only; a defect wider than the ball (or a
    pit too shallow, a load above the static capacity) failed at run time, run by run (left
    for planning, twenty-second session). The plan now runs each run's own check and lists
    them with their axis values and the error the run records; its probe and timing runs are
    taken among the runs that start."""
    p = tmp_path / "wide.toml"
    p.write_text(WIDE_TOML)
    plan = plan_sweep(SweepSpec.from_toml(p), timing_runs=2, timing_duration_s=0.005)
    assert [d["run"] for d in plan.invalid_runs] == [0, 1, 2, 3]
    assert plan.invalid_runs[1]["values"] == {"defect_width_m": 10e-3}
    err = plan.invalid_runs[1]["error"]
    assert err.startswith("defect_width_m = 0.01 m is wider than the ball"), err
    assert plan.channels == ["acc_x", "acc_y"]
    assert [t["run"] for t in plan.timing] == [4] and not plan.timing[0].get("failed")
    t = plan.timing[0]
    assert plan.compute_s_total == pytest.approx(t["fixed_s"] + 0.005 * t["rate_s_per_s"])
    r = run_cli("sweep", "plan", str(p), "--timing-runs", "0")
    assert r.code == 0, r.err
    lines = r.out.splitlines()
    i = lines.index("  4 of 5 runs cannot start ('sweep run' records them as failed):")
    assert lines[i + 1].startswith("    run 0 (defect_width_m = 0.009): defect_width_m = 0.009 m")
    assert len(lines) == i + 5
    d = run_cli("sweep", "plan", str(p), "--timing-runs", "0", "--json").json()
    assert [x["run"] for x in d["invalid_runs"]] == [0, 1, 2, 3]


def test_plan_of_runs_that_all_fail_is_one_line(tmp_path, run_cli):
    p = tmp_path / "none.toml"
    p.write_text(WIDE_TOML.replace(", 1e-3]", "]"))
    with pytest.raises(ConfigError) as e:
        plan_sweep(SweepSpec.from_toml(p), timing_runs=0)
    assert one_line(e).startswith("no run can start; run 0: defect_width_m = 0.009 m is wider")
    r = run_cli("sweep", "plan", str(p))
    assert r.code == 2 and "no run can start; run 0: defect_width_m" in r.err
    assert len(r.err.strip().splitlines()) == 1


def test_plan_checks_a_pit_and_a_load_at_the_model_level(tmp_path):
    """Two more model-level checks the sweep file's fields pass: a pit shallower than the
    contact's approach (``geometry.check_pit_depth``) and a load above twice C0 (ISO 76)."""
    p = tmp_path / "pit.toml"
    p.write_text(
        '[base]\nmodel = "vsm"\nduration_s = 0.005\nfs_hz = 4000.0\nfault = "outer"\n'
        'defect_profile = "pit"\ndefect_width_m = 0.3e-3\n[axes]\n'
        "defect_depth_m = [1e-9, 0.2e-3]\nfy_n = [50.0, 1e6]\n"
    )
    plan = plan_sweep(SweepSpec.from_toml(p), timing_runs=0)
    errs = {d["run"]: d["error"] for d in plan.invalid_runs}
    assert sorted(errs) == [0, 1, 3]
    assert errs[0].startswith("defect_depth_m = 1e-09 m is not deeper than a ball sinks")
    assert errs[1] == errs[0]  # its load is too high as well: the first check stops it
    assert "fy_n" in errs[3] and "C0" in errs[3], errs[3]


OVERLOAD_TOML = """
[sweep]
allow_overload = true
[base]
model = "vsm"
duration_s = 0.005
fs_hz = 4000.0
[axes]
fy_n = [50.0, 25000.0]
"""


@pytest.mark.integration
@pytest.mark.filterwarnings("default")  # StaticCapacityWarning: the overloaded run's own
def test_a_sweep_may_allow_overload(client, tmp_path):
    """Left for planning (twenty-fourth session): a load above twice the static capacity C0
    failed its run, and the single run's ``allow_overload`` (which the error names) was not a
    sweep option. ``[sweep] allow_overload = true`` now runs it (25 kN on the 6205-cwru, C0
    9.37 kN, ISO 76 via :func:`bearingsim.contact.capacity.static_capacity`), in the plan's
    checks and on the workers; a sweep without it keeps its spec hash."""
    p = tmp_path / "o.toml"
    p.write_text(OVERLOAD_TOML)
    spec = SweepSpec.from_toml(p)
    assert spec.allow_overload and plan_sweep(spec, timing_runs=0).invalid_runs == []
    q = tmp_path / "n.toml"
    q.write_text(OVERLOAD_TOML.replace("allow_overload = true", ""))
    no = SweepSpec.from_toml(q)
    errs = plan_sweep(no, timing_runs=0).invalid_runs
    assert [d["run"] for d in errs] == [1] and "C0" in errs[0]["error"], errs
    # the way past it is the sweep's key, not the single run's flag (twenty-fifth session)
    assert errs[0]["error"].endswith("; [sweep] allow_overload = true in the sweep file runs it "
                                     "anyway"), errs[0]["error"]  # fmt: skip
    assert "allow_overload" not in no.canonical() and no.spec_hash != spec.spec_hash
    q.write_text(OVERLOAD_TOML.replace("allow_overload = true", "allow_overload = false"))
    assert SweepSpec.from_toml(q).spec_hash == no.spec_hash
    q.write_text(OVERLOAD_TOML.replace("allow_overload = true", "allow_overload = 1"))
    with pytest.raises(ConfigError) as e:
        SweepSpec.from_toml(q)
    assert one_line(e).endswith("sweep.allow_overload = 1 is invalid; valid: true or false")
    rep = run_sweep(spec, tmp_path / "o.zarr", client=client)
    assert (rep.n_ok, rep.n_failed) == (2, 0)
    rep = run_sweep(no, tmp_path / "n.zarr", client=client)
    assert (rep.n_ok, rep.n_failed) == (1, 1)
    from bearingsim.sweep.dataset import open_dataset

    (f,) = open_dataset(tmp_path / "n.zarr").summary()["failures"]
    assert "[sweep] allow_overload = true" in f["error"], f


@pytest.mark.integration
def test_a_run_starts_when_its_first_runs_cannot(client, tmp_path):
    """``sweep run`` probed the first three runs of a model for the dataset's channels and
    refused the whole sweep when none started — naming run 0 with run 2's error (the last
    candidate's). Now later runs are probed too; the four that cannot start are recorded as
    failed, the fifth is computed."""
    p = tmp_path / "wide.toml"
    p.write_text(WIDE_TOML)
    rep = run_sweep(SweepSpec.from_toml(p), tmp_path / "w.zarr", client=client)
    assert (rep.n_ok, rep.n_failed) == (1, 4)
    p.write_text(WIDE_TOML.replace(", 1e-3]", "]"))
    with pytest.raises(ConfigError) as e:
        run_sweep(SweepSpec.from_toml(p), tmp_path / "n.zarr", client=client)
    msg = one_line(e)
    assert msg.startswith("no run can start; run 0: defect_width_m = 0.009 m is wider"), msg
    assert not (tmp_path / "n.zarr").exists()


#: a slot that the 6205's ball (7.94 mm) spans and the 6203-cwru's (6.75 mm) does not, in runs
#: of three lengths: the longest cannot start
GROUPS_TOML = """
[sweep]
combine = "zip"
[base]
model = "vsm"
fs_hz = 4000.0
fault = "outer"
defect_width_m = 7.5e-3
[axes]
bearing = ["6205", "6205", "6203-cwru"]
duration_s = [0.005, 0.01, 0.5]
"""


@pytest.mark.integration
def test_a_group_of_runs_that_cannot_start_is_recorded_failed(client, tmp_path, run_cli):
    """Exploratory testing (twenty-third session): when every run of one group (model,
    per_ball, bearing) could not start, ``sweep run`` refused the whole sweep that ``sweep
    plan`` had said would run with those runs failed. And the runs that cannot start sized the
    dataset's time axis and the plan's disk estimate (a run of 0.5 s that stores nothing made
    every run's row 2000 samples long)."""
    p = tmp_path / "groups.toml"
    p.write_text(GROUPS_TOML)
    spec = SweepSpec.from_toml(p)
    plan = plan_sweep(spec, timing_runs=0)
    assert [d["run"] for d in plan.invalid_runs] == [2]
    assert tuple(plan.n_samples) == (20, 40)  # the runs that start: 0.005 and 0.01 s at 4 kHz
    assert plan.bytes_raw == 2 * 2 * 40 * 8  # two runs, acc_x and acc_y, 40 samples
    rep = run_sweep(spec, tmp_path / "g.zarr", client=client)
    assert (rep.n_ok, rep.n_failed) == (2, 1)
    ds = open_dataset(tmp_path / "g.zarr")
    X, _ = ds.completed().arrays(["acc_y"])
    assert X.shape == (2, 1, 40)
    r = run_cli("sweep", "summary", str(tmp_path / "g.zarr"))
    assert r.code == 0 and "wider than the ball" in r.out, r.out


RIG_SWEEP_TOML = """
[base]
model = "vsm"
duration_s = 0.005
rig = "cwru-de-12k"
fault = "none"
[axes]
bearing = ["6205-cwru", "6206"]
rpm = [900.0, 1750.0]
"""


@pytest.mark.filterwarnings("default")
def test_plan_lists_the_rig_warnings_the_runs_will_give(tmp_path, run_cli, capsys):
    """Exploratory testing (twenty-fourth session): ``sweep plan`` printed its timing runs'
    warnings as raw Python warnings, three times each, and none of the other runs'. It now
    lists the measurement chain's warnings of every run, found without running it (a bearing
    of another size than the rig's, a speed far from its), grouped by message; the speed
    warning does not name the run's speed, so a speed axis groups into one line."""
    p = tmp_path / "rig.toml"
    p.write_text(RIG_SWEEP_TOML)
    plan = plan_sweep(SweepSpec.from_toml(p), timing_runs=2, timing_duration_s=0.005)
    assert capsys.readouterr().err == ""  # the timing runs' warnings are not printed raw
    got = {k.split(":")[0] + (" 6206" if "6206" in k else ""): v
           for k, v in plan.run_warnings.items()}  # fmt: skip
    assert got == {"RigBearingWarning 6206": [2, 3], "RigSpeedWarning": [0, 2]}, got
    r = run_cli("sweep", "plan", str(p), "--timing-runs", "0")
    assert r.code == 0 and "  2 of 4 runs will warn (runs 0, 2): RigSpeedWarning: rig " in r.out
    d = run_cli("sweep", "plan", str(p), "--timing-runs", "0", "--json").json()
    assert sorted(map(sorted, d["run_warnings"].values())) == [[0, 2], [2, 3]]
    # what the runs then record: the same messages, the same runs
    out = tmp_path / "out"
    r = run_cli("sweep", "run", str(p), "-o", str(out), "--workers", "1")
    assert r.code == 0, r.err
    s = open_dataset(out).summary()
    assert {k: sorted(v) for k, v in s["warnings"].items()} == plan.run_warnings
    assert list(s["by_axis"]["rpm"]) == ["900.0", "1750.0"]  # numbers in order, not as text
