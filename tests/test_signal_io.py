"""Signal files: the one text-table parser, ``io.read_signal`` for CWRU ``.mat``, bearingsim
results and text files, the shaft angle/speed reader of ``analyze-ias``, and their one-line
errors."""

from __future__ import annotations

import math
from dataclasses import asdict

import numpy as np
import pytest
from numpy.testing import assert_allclose

from bearingsim import get_bearing
from bearingsim.errors import ConfigError
from bearingsim.io import SignalRecord, read_signal, read_table
from bearingsim.signal import ShaftSignalKind, load_signal, read_shaft_signal

G0 = 9.80665  #: standard gravity [m/s^2]: CWRU stores g


@pytest.mark.parametrize(
    "text",
    [
        "# a comment\ntime_s, acc\n0, 1.5\n0.5, -2\n\n1.0, 3e-1\n",
        "time_s;acc\n0;1.5\n0.5;-2\n1.0;0.3\n",
        '"time_s","acc"\n"0","1.5"\n0.5,-2\n1.0,0.3\n',
        "time_s\tacc\n0 1.5\n0.5\t-2\n  1.0   0.3\n",
    ],
    ids=["comma", "semicolon", "quoted", "blanks"],
)
def test_read_table_separators_header_comments(tmp_path, text):
    p = tmp_path / "t.csv"
    p.write_text(text)
    tab = read_table(p)
    assert tab.header == ("time_s", "acc")
    assert_allclose(tab.data, [[0, 1.5], [0.5, -2], [1.0, 0.3]], rtol=0, atol=0)


def test_read_table_without_header_names_columns(tmp_path):
    p = tmp_path / "t.txt"
    p.write_text("1 2 3\n4 5 6\n")
    tab = read_table(p)
    assert tab.header is None and tab.names == ("col0", "col1", "col2")


@pytest.mark.parametrize(
    ("text", "needle"),
    [
        ("a,b\n1,2\nx,3\n", "non-numeric line 'x,3'"),
        ("1,2\n3\n", "line '3' has 1 values, the first data line 2"),
        ("# only a comment\n", "is empty; valid: at least one line of numbers"),
        # a one-word file was "empty" (exploratory testing, twenty-third session)
        ("hello\n", "has a header line ('hello') and no line of numbers; valid: at least"),
        ("a,b,c\n1,2\n", "the header names 3 columns, the data has 2"),
        ("1,,2\n", "non-numeric line '1,,2'"),
    ],
)
def test_read_table_errors(tmp_path, text, needle):
    p = tmp_path / "bad.csv"
    p.write_text(text)
    with pytest.raises(ConfigError, match="file = '.*bad.csv'") as exc:
        read_table(p)
    assert needle in str(exc.value) and "\n" not in str(exc.value)


def test_read_table_unreadable(tmp_path):
    with pytest.raises(ConfigError, match="cannot be read"):
        read_table(tmp_path)
    p = tmp_path / "latin.csv"
    p.write_bytes(b"t,\xe9\n1,2\n")
    with pytest.raises(ConfigError, match="is not a UTF-8 text file"):
        read_table(p)


def test_read_signal_text_time_speed_and_channel(tmp_path):
    t = np.arange(100) / 2000.0
    p = tmp_path / "s.csv"
    np.savetxt(
        p,
        np.column_stack([t, np.sin(t), np.cos(t), np.full(t.size, 1800.0)]),
        delimiter=",",
        header="time,acc_a,acc_b,rpm",
        comments="",
    )
    rec = read_signal(p)
    assert isinstance(rec, SignalRecord)
    assert_allclose(rec.fs, 2000.0, rtol=1e-9, err_msg="fs from the median time step")
    assert rec.channel == "acc_a" and rec.info == {"fs_source": "time column"}
    assert_allclose(rec.x, np.sin(t), atol=1e-15)
    assert_allclose(rec.speed_hz, 30.0, rtol=1e-15, err_msg="rpm column / 60")
    assert_allclose(rec.time, t, atol=1e-15)
    assert rec.columns == ("time", "acc_a", "acc_b", "rpm") and rec.rpm is None
    b = read_signal(p, channel="ACC_B", fs_hz=2000.0, rpm=1750.0)
    assert b.channel == "acc_b" and b.fs == 2000.0 and b.rpm == 1750.0 and b.info == {}
    # an fs_hz that contradicts the time column is refused (it was taken over the times)
    with pytest.raises(ConfigError, match=r"fs_hz = 1000 Hz contradicts the time column 'time'"):
        read_signal(p, fs_hz=1000.0)
    # a time column in ms says so in its name and is read in ms
    q = tmp_path / "ms.csv"
    np.savetxt(q, np.column_stack([1e3 * t, np.sin(t)]), delimiter=",", header="time_ms,acc",
               comments="")  # fmt: skip
    ms = read_signal(q)
    assert_allclose(ms.fs, 2000.0, rtol=1e-9)
    assert_allclose(ms.time, t, atol=1e-15)
    with pytest.raises(ConfigError, match=r"channel = 'z' not in s.csv; valid: acc_a, acc_b"):
        read_signal(p, channel="z")


def _two_columns(p, name, t, x):
    """Write a time column [s] and a signal column named ``name`` to the CSV ``p``."""
    rows = "".join(f"{a:.17g},{b:.17g}\n" for a, b in zip(t, x, strict=True))
    p.write_text(f"time_s,{name}\n" + rows)


@pytest.mark.parametrize(
    ("name", "factor"),
    [("de_g", 9.80665), ("DE (g)", 9.80665), ("acc [g]", 9.80665), ("de_mps2", 1.0),
     ("acc (m/s^2)", 1.0), ("acc [m/s2]", 1.0)],
)  # fmt: skip
def test_a_signal_column_named_in_g_is_read_in_m_s2(tmp_path, name, factor):
    # twentieth session: a column de_g was read as m/s^2, 9.8 times too small for every level,
    # RMS and rig gain; g to m/s^2 is standard gravity, 9.80665 m/s^2 (ISO 80000-3)
    t = np.arange(200) / 2000.0
    p = tmp_path / "g.csv"
    x = np.sin(2 * np.pi * 50.0 * t)
    _two_columns(p, name, t, x)
    rec = read_signal(p)
    assert_allclose(rec.x, factor * x, rtol=1e-15)
    assert rec.info["signal_unit"] == "m/s^2" and name in rec.info["signal_unit_source"]


@pytest.mark.parametrize("name", ["lag", "deg", "acc", "de_gx", "signal (V)", "de (g"])
def test_a_signal_column_without_an_acceleration_unit_is_read_as_written(tmp_path, name):
    t = np.arange(200) / 2000.0
    p = tmp_path / "w.csv"
    x = np.sin(2 * np.pi * 50.0 * t)
    _two_columns(p, name, t, x)
    rec = read_signal(p)
    assert_allclose(rec.x, x, rtol=1e-15)
    assert "signal_unit" not in rec.info


def test_a_time_column_with_a_gap_or_two_rates_is_refused(tmp_path):
    """A time column jumping 5 s halfway, or at 6 kHz after 12 kHz, was read as one rate from
    its median step (rig identify wrote fs_hz = 12000 and spectra of the spliced signal, exit
    0). It is refused in one line naming the column and where; times printed to the
    microsecond (round-off up to half a step of 83 us) and an fs_hz given beside them read."""
    rng = np.random.default_rng(0)
    x = rng.standard_normal(2400)
    t = np.arange(x.size) / 12000.0

    def csv(name, tt, fmt="%.9f"):
        f = tmp_path / name
        np.savetxt(f, np.c_[tt, x], delimiter=",", header="time_s,de", comments="", fmt=fmt)
        return f

    rec = read_signal(csv("ok.csv", t, "%.6f"))
    assert rec.fs == pytest.approx(12000.0, rel=1e-3)
    gap = t.copy()
    gap[1200:] += 5.0
    two = t.copy()
    two[1400:] = t[1400] + np.arange(1000) / 6000.0
    for name, tt, at in (("gap.csv", gap, "t = 0.0999166"), ("two.csv", two, "t = 0.116833")):
        for kw in ({}, {"fs_hz": 12000.0}):
            with pytest.raises(ConfigError) as e:
                read_signal(csv(name, tt), **kw)
            msg = str(e.value)
            assert "\n" not in msg and "the time column 'time_s' is not evenly spaced" in msg
            assert at in msg and "valid: evenly sampled times at one rate" in msg


def test_read_signal_text_needs_fs_or_a_time_column(tmp_path):
    p = tmp_path / "x.txt"
    np.savetxt(p, np.column_stack([np.arange(20.0), np.ones(20)]))
    with pytest.raises(ConfigError, match="has no time column; give fs_hz, its sample rate"):
        read_signal(p)
    rec = read_signal(p, fs_hz=100.0)
    assert rec.channel == "col0" and rec.time is None
    rec0 = read_signal(p, time_column=0)
    assert rec0.channel == "col1"
    assert_allclose(rec0.fs, 1.0, rtol=1e-12, err_msg="fs from the first column's steps")
    with pytest.raises(
        ConfigError, match=r"time_column = 2 is invalid for x.txt; valid range \[0, 1\]"
    ):
        read_signal(p, time_column=2)
    p.write_text("time_s,a\n0,1\n0,2\n")
    with pytest.raises(ConfigError, match="the time column must increase"):
        read_signal(p)


def _cwru_file(tmp_path, name, rpm=True):
    from scipy.io import savemat

    p = tmp_path / name
    d = {"X105_DE_time": np.arange(64.0)[:, None], "X105_FE_time": -np.arange(64.0)[:, None]}
    if rpm:
        d["X105RPM"] = np.array([[1797.0]])
    savemat(p, d)
    return p


def test_read_signal_cwru_mat(tmp_path):
    rec = read_signal(_cwru_file(tmp_path, "12k_Drive_End_IR007_0_105.mat"))
    assert rec.channel == "DE" and rec.fs == 12000.0 and rec.rpm == 1797.0
    assert rec.info == {"rpm_source": "file", "fs_source": "file name"}
    assert_allclose(rec.x, np.arange(64.0) * G0, rtol=1e-15, err_msg="g -> m/s^2")
    fe = read_signal(_cwru_file(tmp_path, "r.mat"), channel="fe", fs_hz=48000.0, rpm=1750.0)
    assert fe.channel == "FE" and fe.fs == 48000.0 and fe.rpm == 1750.0
    # the file's own X###RPM, which the option overrode (analyze and rig identify judge it)
    assert fe.info == {"rpm_source": "option", "fs_source": "option", "rpm_file": 1797.0}
    # no rate in the name: read off the shaft lines (io.cwru.infer_cwru_fs); a ramp has none
    with pytest.raises(ConfigError, match=r"cannot be told from its shaft lines.*--fs-hz"):
        read_signal(_cwru_file(tmp_path, "d.mat"))
    assert read_signal(_cwru_file(tmp_path, "d.mat"), fs_hz=48000.0).info["fs_source"] == "option"
    norpm = _cwru_file(tmp_path, "norpm_12k.mat", rpm=False)
    assert read_signal(norpm).rpm is None
    with pytest.raises(ConfigError, match=r"'norpm_12k.mat' has no X###RPM key and no --rpm"):
        load_signal(norpm)
    # neither a speed nor a rate: one line naming both options
    with pytest.raises(ConfigError, match=r"file = 'norpm.mat' has no X###RPM key.*--fs-hz F"):
        read_signal(_cwru_file(tmp_path, "norpm.mat", rpm=False))
    with pytest.raises(ConfigError, match=r"channel = 'BA' not in r.mat"):
        read_signal(tmp_path / "r.mat", channel="BA")


def test_read_signal_simulation_result(tmp_path):
    from bearingsim.results import SimulationResult

    b = get_bearing("6205")
    t = np.arange(256) / 12000.0
    res = SimulationResult(
        time=t,
        channels={"acc_x": np.cos(t), "acc_y": np.sin(t)},
        units={"acc_x": "m/s^2", "acc_y": "m/s^2"},
        scenario={"rpm": 1796.0},
        meta={"fs_hz": 12000.0, "shaft_hz": 1796.0 / 60, "bearing": asdict(b)},
    )
    p = res.save(tmp_path / "r.nc")
    rec = read_signal(p)
    assert rec.channel == "y" and rec.fs == 12000.0 and rec.rpm == 1796.0
    assert rec.bearing == b, "bearing rebuilt from the file"
    assert_allclose(rec.x, np.sin(t), rtol=0, atol=0)
    assert read_signal(p, channel="X", rpm=1700.0).rpm == 1700.0
    with pytest.raises(ConfigError, match=r"channel = 'y_fe' is invalid .*; valid: x, y"):
        read_signal(p, channel="y_fe")


def test_read_signal_bad_files(tmp_path):
    with pytest.raises(ConfigError, match="does not exist or is not a file"):
        read_signal(tmp_path / "missing.csv")
    p = tmp_path / "a.wav"
    p.write_bytes(b"RIFF")
    with pytest.raises(ConfigError, match=r"file = 'a.wav' has an unknown type; valid: .mat"):
        read_signal(p)


def test_load_signal_needs_speed_and_16_rows(tmp_path):
    p = tmp_path / "short.csv"
    np.savetxt(p, np.column_stack([np.arange(10) / 1e3, np.ones(10)]), delimiter=",",
               header="time,acc", comments="")  # fmt: skip
    with pytest.raises(ConfigError, match="has no rpm/speed_hz column and no --rpm was given"):
        load_signal(p)
    with pytest.raises(ConfigError, match=r"has too few rows; valid range \[16, inf\) rows"):
        load_signal(p, rpm=1800.0)


@pytest.mark.parametrize(
    ("header", "kind", "factor"),
    [
        ("time_s,angle_rad", None, 1.0),
        ("time_s,angle_deg", None, math.pi / 180),
        ("time_s,value", "angle_rev", 2 * math.pi),
        ("", "speed_rpm", 2 * math.pi / 60),
        ("t speed_rad_s", None, 1.0),
    ],
)
def test_read_shaft_signal_kinds_to_si(tmp_path, header, kind, factor):
    p = tmp_path / "enc.csv"
    a = np.column_stack([np.arange(8) * 1e-3, np.arange(8) * 0.5])
    np.savetxt(p, a, delimiter="," if "," in header or not header else " ", header=header,
               comments="")  # fmt: skip
    t, v, k = read_shaft_signal(p, kind)
    assert k is ShaftSignalKind(kind or header.replace(" ", ",").split(",")[1])
    assert_allclose(t, a[:, 0], rtol=0, atol=0)
    assert_allclose(v, a[:, 1] * factor, rtol=1e-15)


def test_read_shaft_signal_errors(tmp_path):
    p = tmp_path / "x.csv"
    p.write_text("0,1\n1,2\n")
    with pytest.raises(ConfigError, match="give --kind .* or name the second column"):
        read_shaft_signal(p)
    with pytest.raises(ConfigError, match="kind = 'angle' is invalid; valid: angle_rad"):
        read_shaft_signal(p, "angle")
    p.write_text("0,1,2\n1,2,3\n")
    with pytest.raises(ConfigError, match=r"must have two numeric columns \(time \[s\], value\)"):
        read_shaft_signal(p, "angle_rad")
    p.write_text("time_s,speed_rpm\n0,1\n1,2\n")
    assert read_shaft_signal(p, "speed_rpm")[2] is ShaftSignalKind.SPEED_RPM
    with pytest.raises(
        ConfigError, match="kind = 'angle_rad' contradicts the header .* 'speed_rpm'"
    ):
        read_shaft_signal(p, "angle_rad")


def test_a_short_text_record_names_the_rate_and_speed_it_was_given(tmp_path):
    # a text file's speed is always the user's (--rpm): a record too short at that speed gets
    # the rates and speeds that would resolve it, not "a longer record"; before, a text file
    # with a time column was told only to be longer, as if its speed were the file's own
    from bearingsim.signal.diagnosis import MIN_REVOLUTIONS, check_resolvable

    t = np.arange(240) / 12000.0
    p = tmp_path / "short.csv"
    _two_columns(p, "de_g", t, np.sin(2 * np.pi * 100.0 * t))
    rec = read_signal(p, rpm=1750.0)
    assert 240 / 12000.0 < MIN_REVOLUTIONS * 60.0 / 1750.0
    with pytest.raises(ConfigError, match=r"valid range fs_hz in \(0, "):
        check_resolvable(rec)


def test_a_time_columns_rate_is_the_simplest_within_its_round_off():
    """Exploratory testing (twenty-seventh session): times printed with ``%.9g`` gave 12000.00004
    Hz (printed as such; record 120 read "inner" at that rate and "uncertain" at 12000). The
    rate is the number with the fewest digits within the round-off the times carry; exact
    times keep an odd rate, and a clock off its rate by more than 1e-6 keeps its own."""
    from bearingsim.io.signal import rate_of_times

    t = np.arange(121_846) / 12000.0
    for fmt in ("%.6f", "%.9g", "%.12g", "%.18g"):
        assert rate_of_times(np.array([float(fmt % v) for v in t])) == 12000.0, fmt
    assert rate_of_times(np.arange(10_000) / 12000.3) == 12000.3
    assert rate_of_times(np.arange(10_000) / 12345.678) == 12345.678
    drift = np.arange(10_000) / 12000.0 * (1.0 + 1e-5 * np.linspace(0.0, 1.0, 10_000))
    assert rate_of_times(drift) == pytest.approx(9_999 / drift[-1], rel=1e-9) != 12000.0
