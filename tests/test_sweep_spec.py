"""Sweep specification: axes (lists, ranges, seeded random draws), cartesian/zip combination,
run numbering, per-run seeds, the canonical spec hash, and bad input (no Dask here)."""

from __future__ import annotations

import itertools

import numpy as np
import pytest
from numpy.testing import assert_allclose, assert_array_equal

from bearingsim.config import Scenario
from bearingsim.errors import ConfigError
from bearingsim.sweep.spec import SweepSpec, expand_axis, spec_differences

BASE = {"model": "dem", "duration_s": 0.05, "fs_hz": 4000.0}


def spec(axes, sweep=None, base=None) -> SweepSpec:
    return SweepSpec.from_dict(
        {"sweep": sweep or {}, "base": base or dict(BASE), "axes": axes}, origin="t.toml"
    )


# ------------------------------------------------------------------------------ axes
def test_axis_forms():
    assert expand_axis("rpm", [1730, 1750], 0).values == (1730, 1750)
    assert expand_axis("rpm", {"values": [1.0, 2.0]}, 0).values == (1.0, 2.0)
    assert_allclose(
        expand_axis("fy_n", {"start": 50.0, "stop": 200.0, "num": 4}, 0).values,
        np.linspace(50.0, 200.0, 4),
        rtol=0,
        atol=0,
        err_msg="linspace range, stop included",
    )
    assert_allclose(
        expand_axis(
            "defect_width_m", {"start": 1e-4, "stop": 1e-2, "num": 3, "scale": "log"}, 0
        ).values,
        [1e-4, 1e-3, 1e-2],
        rtol=1e-12,
        err_msg="geomspace range",
    )
    # integer step range keeps ints (valid seeds); float step includes stop within rounding
    assert expand_axis("seed", {"start": 0, "stop": 9, "step": 3}, 0).values == (0, 3, 6, 9)
    assert_allclose(
        expand_axis("rpm", {"start": 0.1, "stop": 0.3, "step": 0.1}, 0).values,
        [0.1, 0.2, 0.3],
        rtol=1e-12,
        err_msg="float step range includes stop",
    )


def test_random_axes_seeded_and_independent():
    u = expand_axis("fy_n", {"random": "uniform", "low": 20.0, "high": 200.0, "n": 50}, seed=7)
    v = np.asarray(u.values)
    assert v.min() >= 20.0 and v.max() < 200.0 and len(set(u.values)) == 50
    assert u == expand_axis("fy_n", {"random": "uniform", "low": 20.0, "high": 200.0, "n": 50}, 7)
    assert u != expand_axis("fy_n", {"random": "uniform", "low": 20.0, "high": 200.0, "n": 50}, 8)
    # each axis has its own stream: adding another random axis leaves this one unchanged
    axes = {"fy_n": {"random": "uniform", "low": 20.0, "high": 200.0, "n": 5}}
    a = spec(dict(axes), {"seed": 3})
    b = spec({"fx_n": {"random": "normal", "mean": 0.0, "std": 5.0, "n": 4}, **axes}, {"seed": 3})
    assert a.axes[0].values == b.axes[1].values
    lu = expand_axis(
        "defect_width_m", {"random": "loguniform", "low": 1e-4, "high": 1e-3, "n": 200}, 0
    )
    assert 1e-4 <= min(lu.values) and max(lu.values) <= 1e-3
    ints = expand_axis("seed", {"random": "integers", "low": 0, "high": 3, "n": 200}, 0).values
    assert set(ints) == {0, 1, 2, 3} and all(isinstance(x, int) for x in ints)
    ch = expand_axis("fault", {"random": "choice", "values": ["outer", "inner"], "n": 30}, 0)
    assert set(ch.values) == {"outer", "inner"}


# ------------------------------------------------------------------------------ combination
def test_cartesian_order_and_scenarios():
    s = spec({"fault": ["outer", "inner"], "rpm": [1730.0, 1750.0, 1797.0]})
    assert s.n_runs == 6 and s.shape == (2, 3)
    expect = list(itertools.product(["outer", "inner"], [1730.0, 1750.0, 1797.0]))
    got = [(v["fault"], v["rpm"]) for v in s.iter_values()]
    assert got == expect
    assert [s.run_values(i) for i in range(6)] == list(s.iter_values())
    sc = s.scenario(4)
    assert isinstance(sc, Scenario)
    assert (sc.fault, sc.rpm, sc.duration_s, sc.model.value) == ("inner", 1750.0, 0.05, "dem")
    assert [x.to_dict() for x in s.scenarios()] == [s.scenario(i).to_dict() for i in range(6)]


def test_zip_and_zip_groups():
    z = spec({"rpm": [1730.0, 1797.0], "fy_n": [50.0, 100.0]}, {"combine": "zip"})
    assert z.n_runs == 2
    assert list(z.iter_values()) == [
        {"rpm": 1730.0, "fy_n": 50.0},
        {"rpm": 1797.0, "fy_n": 100.0},
    ]
    g = spec(
        {"fault": ["outer", "inner"], "rpm": [1730.0, 1797.0], "fy_n": [50.0, 100.0]},
        {"zip": [["rpm", "fy_n"]]},
    )
    assert g.n_runs == 4
    assert [(v["fault"], v["rpm"], v["fy_n"]) for v in g.iter_values()] == [
        ("outer", 1730.0, 50.0),
        ("outer", 1797.0, 100.0),
        ("inner", 1730.0, 50.0),
        ("inner", 1797.0, 100.0),
    ]


def test_per_run_seed_and_coordinates():
    s = spec({"rpm": [1730.0, 1797.0]}, {"per_run_seed": True}, {**BASE, "seed": 100})
    assert [s.scenario(i).seed for i in range(2)] == [100, 101]
    assert s.coordinate_keys == ("rpm", "seed", "fault")
    assert spec({}).n_runs == 1 and spec({}).scenario(0).to_dict() == Scenario(**BASE).to_dict()


def test_bearing_axis_overrides_base_file(tmp_path):
    bf = tmp_path / "b.toml"
    bf.write_text(
        'id = "mine"\ntype = "ball"\nn_elements = 9\nelement_diameter_m = 7.94e-3\n'
        "pitch_diameter_m = 39e-3\ninner_groove_radius_m = 4.089e-3\n"
        "outer_groove_radius_m = 4.169e-3\ndiametral_clearance_m = 6e-6\n"
        "youngs_modulus_pa = 2.07e11\npoisson_ratio = 0.3\ndensity_kg_m3 = 7850.0\n"
        'source = "test"\n'
    )
    (tmp_path / "s.toml").write_text(
        '[base]\nmodel = "dem"\nbearing_file = "b.toml"\n[axes]\nrpm = [1700, 1800]\n'
    )
    s = SweepSpec.from_toml(tmp_path / "s.toml")
    assert s.scenario(0).bearing_file == str(tmp_path / "b.toml")
    assert "mine" not in s.canonical()["bearings"] and str(bf) in s.canonical()["bearings"]
    s2 = spec({"bearing": ["6205", "6205-cwru"]})
    assert [s2.scenario(i).bearing for i in range(2)] == ["6205", "6205-cwru"]
    assert set(s2.canonical()["bearings"]) == {"6205", "6205-cwru"}


# ------------------------------------------------------------------------------ identity
def test_spec_hash_tracks_results_not_form(tmp_path):
    a = tmp_path / "a.toml"
    b = tmp_path / "b.toml"
    a.write_text(
        '[sweep]\nlabel = "fault"\nname = "x"\n[base]\nmodel = "dem"\nduration_s = 0.05\n'
        '[axes]\nfault = ["outer", "inner"]\nrpm = { start = 1700.0, stop = 1800.0, num = 3 }\n'
    )
    # same runs written differently, other label and name: same hash
    b.write_text(
        '[sweep]\nlabel = ["rpm"]\n[base]\nduration_s = 5e-2\nmodel = "dem"\n'
        '[axes]\nfault = { values = ["outer", "inner"] }\nrpm = [1700.0, 1750.0, 1800.0]\n'
    )
    sa, sb = SweepSpec.from_toml(a), SweepSpec.from_toml(b)
    assert sa.spec_hash == sb.spec_hash
    file_base = {"model": "dem", "duration_s": 0.05}
    c = spec({"fault": ["outer", "inner"], "rpm": [1700.0, 1750.0, 1801.0]}, base=file_base)
    assert c.spec_hash != sa.spec_hash
    assert spec_differences(sa.canonical(), c.canonical()) == ["axes.rpm"]
    d = spec(
        {"fault": ["outer", "inner"], "rpm": [1700.0, 1750.0, 1800.0]},
        {"channels": "all"},
        base=file_base,
    )
    assert spec_differences(sa.canonical(), d.canonical()) == ["channels"]
    e = SweepSpec.from_dict(
        {"base": {**BASE, "duration_s": 0.06}, "axes": {"rpm": [1700.0]}}, origin="e"
    )
    f = SweepSpec.from_dict({"base": BASE, "axes": {"rpm": [1700.0]}}, origin="f")
    assert spec_differences(e.canonical(), f.canonical()) == ["base.duration_s"]


def test_example_sweep_file():
    from pathlib import Path

    ex = Path(__file__).resolve().parents[1] / "examples" / "sweep_faults.toml"
    s = SweepSpec.from_toml(ex)
    assert s.n_runs == 48 and s.label == ("fault",)
    assert_array_equal(sorted({sc.fault for sc in s.scenarios()}), ["inner", "none", "outer"])


# ------------------------------------------------------------------------------ bad input
@pytest.mark.parametrize(
    "data, match",
    [
        ({"sweeps": {}}, r"unknown table 'sweeps'; valid tables: \[sweep\], \[base\], \[axes\]"),
        ({"sweep": {"combin": "zip"}}, r"unknown key 'combin' in \[sweep\]; valid keys: combine"),
        ({"axes": {"rmp": [1.0]}}, r"axis 'rmp' is not a scenario key; valid: model, bearing"),
        ({"axes": {"rpm": []}}, r"axes.rpm has no values; valid: at least one value"),
        (
            {"axes": {"rpm": {"start": 1.0, "stop": 2.0, "num": 0}}},
            r"axes.rpm.num = 0 is out of range; valid range \[1, 1000000\]",
        ),
        (
            {"axes": {"rpm": {"start": 1.0, "stop": 2.0, "step": 0.0}}},
            r"axes.rpm.step = 0 is out of range; valid range \(0, inf\)",
        ),
        (
            {"axes": {"rpm": {"start": 2.0, "stop": 1.0, "step": 0.5}}},
            r"axes.rpm.stop = 1 is below start = 2; valid range \[2, inf\)",
        ),
        (
            {"axes": {"rpm": {"start": 1.0, "stop": 2.0}}},
            r"axes.rpm needs exactly one of num or step",
        ),
        (
            {"axes": {"fy_n": {"random": "gauss", "n": 3}}},
            r"axes.fy_n.random = 'gauss' is invalid; valid: uniform, loguniform, normal",
        ),
        (
            {"axes": {"fy_n": {"random": "uniform", "low": 1.0, "n": 3}}},
            r"axes.fy_n \(random = 'uniform'\) needs key 'high'",
        ),
        (
            {"axes": {"fy_n": {"random": "loguniform", "low": 0.0, "high": 1.0, "n": 3}}},
            r"axes.fy_n.low = 0 is out of range for loguniform; valid range \(0, inf\)",
        ),
        (
            {"axes": {"rpm": [1.0, 2.0], "fy_n": [1.0]}, "sweep": {"combine": "zip"}},
            r"combine = 'zip' needs axes of equal length; got rpm 2, fy_n 1",
        ),
        (
            {"axes": {"rpm": [1.0, 2.0], "fy_n": [1.0]}, "sweep": {"zip": [["rpm", "fy_n"]]}},
            r"zip group \['rpm', 'fy_n'\] has unequal lengths: rpm 2, fy_n 1",
        ),
        (
            {"axes": {"rpm": [1.0]}, "sweep": {"zip": [["rpm", "fx_n"]]}},
            r"zip group \['rpm', 'fx_n'\] names 'fx_n', which is not an axis",
        ),
        (
            {"axes": {"seed": [1, 2]}, "sweep": {"per_run_seed": True}},
            r"per_run_seed = true and a 'seed' axis exclude each other",
        ),
        ({"sweep": {"channels": []}}, r"sweep.channels = \[\] is invalid; valid: \"all\""),
        ({"sweep": {"label": "speed"}}, r"label key 'speed' is not a scenario key"),
        ({"sweep": {"seed": -1}}, r"sweep.seed = -1 is invalid; valid range \[0, inf\)"),
        ({"sweep": {"combine": "outer"}}, r"sweep.combine = 'outer' is invalid; valid"),
        ({"base": {"rpn": 1.0}}, r"t.toml \[base\]: unknown key 'rpn'; valid keys: model"),
        (
            {"axes": {"fault": ["outer"], "rpm": [1750.0, -5.0]}},
            r"t.toml: run 1: rpm = -5 r/min is out of range; valid range \(0, inf\) r/min "
            r"\(fault = 'outer', rpm = -5.0\)",
        ),
        (
            {"axes": {"seed": {"start": 0.0, "stop": 1.0, "num": 2}}},
            r"run 0: seed = 0.0 is invalid; valid range \[0, inf\) integer",
        ),
        (
            {"axes": {f"{k}": list(range(1, 101)) for k in ("rpm", "fx_n", "fy_n", "seed")}},
            r"number of runs = 100000000 is too large; valid range \[1, 10000000\]",
        ),
    ],
)
def test_bad_spec(data, match):
    data = {"base": dict(BASE), **data}
    with pytest.raises(ConfigError, match=match):
        s = SweepSpec.from_dict(data, origin="t.toml")
        s.scenarios()


def test_bad_spec_files(tmp_path):
    with pytest.raises(ConfigError, match=r"sweep file '.*nope.toml' cannot be read"):
        SweepSpec.from_toml(tmp_path / "nope.toml")
    bad = tmp_path / "bad.toml"
    bad.write_text("[axes\nrpm = 1")
    with pytest.raises(ConfigError, match=r"sweep file '.*bad.toml' is not valid TOML"):
        SweepSpec.from_toml(bad)


def test_repeated_axis_values_are_refused_unless_each_run_has_its_own_seed():
    """Exploratory testing (twentieth session): ``fault = ["outer", "outer"]`` (or ``fs_hz =
    [12000, 12000.0]``) planned two identical runs, bit for bit, which a random split put on
    both sides. Refused in one line naming the axis and the positions; a zip group repeats a
    value legitimately as long as its rows differ; with per_run_seed each run differs."""
    base = {"model": "vsm", "duration_s": 0.05}
    for axes, pos in (({"fault": ["outer", "outer"]}, "(values 0 and 1)"),
                      ({"fs_hz": [12000, 24000.0, 12000.0]}, "(values 0 and 2)")):  # fmt: skip
        with pytest.raises(ConfigError) as e:
            SweepSpec.from_dict({"base": base, "axes": axes}, origin="t.toml")
        msg = str(e.value)
        assert "\n" not in msg and pos in msg and "valid: distinct values" in msg
    zipped = {"sweep": {"zip": [["fault", "rpm"]]}, "base": base,
              "axes": {"fault": ["outer", "outer"], "rpm": [1700.0, 1750.0]}}  # fmt: skip
    assert SweepSpec.from_dict(zipped, origin="z").n_runs == 2
    zipped["axes"]["rpm"] = [1700.0, 1700]
    with pytest.raises(ConfigError, match=r"axis fault and rpm repeats 'outer', 1700"):
        SweepSpec.from_dict(zipped, origin="z")
    seeded = {"sweep": {"per_run_seed": True}, "base": base, "axes": {"fault": ["outer"] * 2}}
    assert SweepSpec.from_dict(seeded, origin="s").n_runs == 2
