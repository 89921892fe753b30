"""examples/sim_to_real.py (issue 16, item 6, first version): a classifier trained on simulated
signals only labels measured records; JSON lines, a cached dataset, one line per bad file."""

from __future__ import annotations

import importlib.util
import json
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

pytest.importorskip("sklearn")

ROOT = Path(__file__).resolve().parents[1]
CWRU = ROOT.parent / "shared" / "data" / "cwru"
REC = CWRU / "12k_Drive_End_OR007@6_2_132.mat"


def _module():
    spec = importlib.util.spec_from_file_location(
        "sim_to_real", ROOT / "examples" / "sim_to_real.py"
    )
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    return mod


@pytest.fixture()
def small(monkeypatch):
    """The example with a small grid (two speeds, one size and slip, one rig, the outer-race
    defect at @6 only, 0.5 s)."""
    m = _module()
    monkeypatch.setattr(m, "OUTER_POSITIONS", {"@6": m.OUTER_POSITIONS["@6"]})
    monkeypatch.setattr(m, "RPMS", (1750.0, 1797.0))
    monkeypatch.setattr(m, "SIZES_IN", (0.014,))
    monkeypatch.setattr(m, "SLIPS", (1.5,))
    monkeypatch.setattr(m, "PROFILES", {"cwru-de-12k": ("6205-cwru", 12000.0)})
    monkeypatch.setattr(m, "DURATION_S", 0.5)
    return m


def test_features_are_levels_over_the_floor(small):
    """An outer-race fault simulated at 1750 r/min: the BPFO line stands above the floor; a
    ball fault: the FTF line and 2xBSF do (the ball pattern, Smith & Randall 2015 table 1)."""
    from bearingsim import simulate

    r = simulate(dict(model="vsm", fault="outer", duration_s=0.5, fs_hz=12000.0))
    f = small.features(r["acc_y"], 12000.0, 1750.0, "6205")
    assert f.shape == (len(small.FEATURES),)
    assert f[small.FEATURES.index("bpfo")] > 20.0
    assert np.all(np.isfinite(f))
    r = simulate(
        dict(model="vsm", fault="ball", duration_s=1.0, fs_hz=12000.0, defect_width_m=3.556e-4)
    )
    f = small.features(r["acc_y"], 12000.0, 1750.0, "6205")
    assert f[small.FEATURES.index("ftf")] > 10.0
    assert f[small.FEATURES.index("2bsf")] > 10.0


@pytest.mark.skipif(not CWRU.is_dir(), reason="needs ../shared/data/cwru")
def test_dataset_is_cached_and_predictions_are_json_lines(small, tmp_path):
    X, y, meta = small.build_dataset(tmp_path, progress=False)
    # 2 speeds x (healthy + inner, outer, ball at one size): labels none, inner, outer, ball
    assert X.shape == (8, len(small.FEATURES)) and sorted(set(y)) == [0, 1, 2, 3]
    X2, y2, meta2 = small.build_dataset(tmp_path, progress=False)  # from the cache
    assert np.array_equal(X, X2) and np.array_equal(y, y2) and "grid" in meta2
    clf = small.train(X, y)
    out = list(small.predict(clf, [REC, tmp_path / "missing.mat"]))
    ok, bad = out
    assert ok["file"] == str(REC) and ok["predicted"] in small.LABELS
    assert set(ok["probabilities"]) == set(small.LABELS)
    assert sum(ok["probabilities"].values()) == pytest.approx(1.0)
    assert bad["predicted"] is None and "does not exist" in bad["error"]
    json.dumps(out)


@pytest.mark.skipif(not CWRU.is_dir(), reason="needs ../shared/data/cwru")
def test_a_record_without_rpm_gets_the_nominal_speed_of_its_load(small, tmp_path):
    """The CWRU 0.028 in records store no speed. --predict takes the CWRU nominal speed of the
    load in the file name (load 2 hp: 1750 r/min; CWRU Bearing Data Center), as `analyze`
    does, and says so; a name without a load is its own error line; --rpm overrides both.
    (Before, a missing speed was taken as 1797 r/min whatever the load.)"""
    from scipy.io import loadmat, savemat

    m = loadmat(REC)
    keep = {k: v for k, v in m.items() if not k.startswith("__") and not k.endswith("RPM")}
    named = tmp_path / "12k_Drive_End_IR028_2_3003.mat"
    savemat(named, keep)
    anon = tmp_path / "record.mat"
    savemat(anon, keep)
    x, fs, rpm, source, bearing = small._record(named)
    assert (rpm, source, bearing) == (1750.0, "name (CWRU nominal speed at load 2 hp)", "6205-cwru")
    assert small._record(named, 1772.0)[2:4] == (1772.0, "option")
    assert small._record(REC)[2:4] == (1750.0, "file")  # 132 stores 1750
    # no rate, no speed, no load in the name: with --rpm the rate is read off the shaft lines
    # (before the ninth session the file was read, at 48 kHz, before --rpm was looked at)
    assert small._record(anon, 1750.0)[1:4] == (12000.0, 1750.0, "option")
    X, y, _meta = small.build_dataset(tmp_path / "cache", progress=False)
    ok, bad = small.predict(small.train(X, y), [named, anon])
    assert ok["rpm"] == 1750.0 and ok["rpm_source"].startswith("name")
    assert bad["predicted"] is None and "give --rpm" in bad["error"]


def test_cli_without_a_task_is_a_usage_error():
    r = subprocess.run([sys.executable, str(ROOT / "examples" / "sim_to_real.py")],
                       capture_output=True, text=True)  # fmt: skip
    assert r.returncode == 2 and "give --predict FILE... or --evaluate" in r.stderr


def test_grid_draws_every_machine_fact_and_is_reproducible():
    """Each run draws the unpublished machine facts (ball spread, unbalance, clearance, axial
    spring preload) from
    their sets; over the grid every value occurs for every fault, and the draw is the same on
    every call (the cache key does not change under a user)."""
    m = _module()
    runs = list(m._grid())
    assert runs == list(m._grid())
    at6 = [r for r in runs if r.get("edge_deg", 10.0) == m.OUTER_POSITIONS["@6"]]
    assert len(at6) == len(m.PROFILES) * len(m.RPMS) * len(m.SLIPS) * (1 + 3 * len(m.SIZES_IN))
    # outside the load zone (@3, @12) only runs whose preload or axial load loads a ball there
    away = [r for r in runs if r not in at6]
    assert {r["edge_deg"] for r in away} == {m.OUTER_POSITIONS[p] for p in ("@3", "@12")}
    assert all(r["fault"] == "outer" and (r["clearance"] < 0 or r["axial_k"] > 0) for r in away)
    assert len(away) == 184  # of 216: the 32 with neither a preload nor an axial load left out
    # the runs at @6 draw what they drew before the other positions entered the grid
    six = dict(m.OUTER_POSITIONS)
    try:
        m.OUTER_POSITIONS = {"@6": six["@6"]}
        assert list(m._grid()) == at6
    finally:
        m.OUTER_POSITIONS = six
    for fault in m.LABELS:
        sub = [r for r in runs if r["fault"] == fault]
        assert {r["spread"] for r in sub} == set(m.SPREADS_M)
        assert {r["unbalance"] for r in sub} == set(m.UNBALANCE)
        assert {r["clearance"] for r in sub} == set(m.CLEARANCES_M)
        assert {r["axial_k"] for r in sub} == set(m.AXIAL_K)


def test_a_long_record_is_judged_on_pieces_of_the_training_length(small):
    """A measured record longer than the simulations is cut into pieces of their length: the
    features are levels over the envelope floor, which falls with the record's length."""
    fs = 12000.0
    n = int(small.DURATION_S * fs)
    x = np.arange(int(3.7 * n), dtype=float)
    pieces = small.segments(x, fs)
    assert [p.size for p in pieces] == [n, n, n]
    assert np.array_equal(np.concatenate(pieces), x[: 3 * n])
    assert [p.size for p in small.segments(x[: n + 10], fs)] == [n]
    assert [p.size for p in small.segments(x[: n // 2], fs)] == [n // 2]
    # the reason: the same impulse train's BPFO level over the floor grows with the length
    from bearingsim import simulate

    r = simulate(dict(model="vsm", fault="outer", duration_s=2.0, fs_hz=fs, slip_percent=1.0))
    y = r["acc_y"]
    f_short = small.features(y[: y.size // 2], fs, 1750.0, "6205")[0]
    f_long = small.features(y, fs, 1750.0, "6205")[0]
    assert f_long > f_short + 1.5  # 2.7 dB measured (2 s against 1 s)


@pytest.mark.skipif(not CWRU.is_dir(), reason="needs ../shared/data/cwru")
def test_held_out_rig_sets_never_use_the_judged_size(small, tmp_path, monkeypatch):
    """The held-out evaluation: each set's rigs are identified from the records of the other
    fault size only (never the judged size, never the healthy record); a mounting with no
    other size (the fan end has only 0.014 in records here) has no rig, so its runs leave that
    training set. Each run is simulated once and passed through every set's rig; the sets
    are cached under keys that hold the rigs' tables."""
    monkeypatch.setattr(small, "RPMS", (1797.0,))
    monkeypatch.setattr(
        small,
        "PROFILES",
        {"cwru-de-12k": ("6205-cwru", 12000.0), "cwru-fe-12k": ("6203-cwru", 12000.0)},
    )
    held = small.rig_set("without-0.014", CWRU)
    assert held["cwru-fe-12k"] is None
    used = held["cwru-de-12k"].provenance
    assert "014" not in used and "normal" not in used
    assert "IR007_2_107" in used and "OR007@6_2_132" in used and "B007_2_120" in used
    other = small.rig_set("without-0.007", CWRU)
    assert "007" not in other["cwru-de-12k"].provenance
    assert "007" not in other["cwru-fe-12k"].provenance
    with pytest.raises(ValueError, match="without-0.021"):
        small.rig_set("without-0.021", CWRU)

    sets, meta = small.build_datasets(tmp_path, ["without-0.014"], data=CWRU, progress=False)
    assert set(sets) == {"shipped", "without-0.014"}
    (Xs, ys), (Xh, yh) = sets["shipped"], sets["without-0.014"]
    assert np.array_equal(ys[:4], yh)  # the same runs, in the same order
    assert Xs.shape == (8, len(small.FEATURES)) and Xh.shape == (4, len(small.FEATURES))
    assert np.all(np.isfinite(Xh)) and sorted(set(yh)) == [0, 1, 2, 3]
    assert not np.allclose(Xs[:4], Xh)  # the same runs through another rig
    again, _ = small.build_datasets(tmp_path, ["without-0.014"], data=CWRU, progress=False)
    assert np.array_equal(again["without-0.014"][0], Xh)
    assert small._set_key("g", {"a": held["cwru-de-12k"]}) != small._set_key(
        "g", {"a": other["cwru-de-12k"]}
    )
    assert small._profile("FE", 12000.0) == "cwru-fe-12k" and small._profile("DE", 48000) is None
