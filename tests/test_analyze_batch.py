"""``bearingsim analyze FILE...`` (issue 17, item 4): several files in one call, analysed in
parallel and reported in input order (JSON Lines, CSV or text); a bad file reported on its own
line while the others are analysed; the shaft speed from the CWRU file name; ``--channel auto``;
the checks of the samples (not finite, clipped)."""

from __future__ import annotations

import csv
import io
import json

import numpy as np
import pytest
from conftest import cwru_record

from bearingsim.errors import ConfigError
from bearingsim.io import SignalRecord, read_cwru_mat
from bearingsim.signal.diagnosis import CLIPPED_RUN, check_samples

#: the columns of ``analyze --csv`` (issue 17, item 4)
CSV_COLUMNS = [
    "file",
    "channel",
    "fs_hz",
    "rpm",
    "rpm_source",
    "bearing",
    "diagnosis",
    "confidence",
    "leading",
    "probability",
    "band_lo_hz",
    "band_hi_hz",
    "error",
    "channel_source",
    "contact_angle_deg",
    "why",
    "rpm_unchecked",
]
#: what ``rpm_source`` says of a speed taken from a CWRU file name at motor load 2 hp
NAME_LOAD_2 = "name (CWRU nominal speed at load 2 hp)"


@pytest.fixture
def three():
    """Three short 12 kHz CWRU records, deliberately not in sorted order: 132 (outer race
    0.007 in @6, drive end), 310 (outer race 0.014 in @3, fan end), 107 (inner race 0.007 in,
    drive end) — SOURCES.md."""
    return [cwru_record("132"), cwru_record("310"), cwru_record("107")]


def _lines(r) -> list[dict]:
    return [json.loads(ln) for ln in r.out.splitlines()]


def _sine_csv(path, clip: float | None = None, nan_at: int | None = None):
    """A 500 Hz tone with a little noise at 12 kHz (0.5 s, 24 samples per period), a time
    column; ``clip``: clipped at ±clip (a flat top of ~5 samples per period at 0.8 of the
    amplitude: 24 (pi - 2 asin 0.8) / (2 pi) = 4.9); ``nan_at``: one NaN sample."""
    t = np.arange(6000) / 12000.0
    x = np.sin(2 * np.pi * 500.0 * t) + 0.01 * np.random.default_rng(17).standard_normal(t.size)
    if clip is not None:
        x = np.clip(x, -clip, clip)
    rows = [f"{a:.17g},{b:.17g}" for a, b in zip(t, x, strict=True)]
    if nan_at is not None:
        rows[nan_at] = f"{t[nan_at]:.17g},nan"
    path.write_text("time_s,acc\n" + "\n".join(rows) + "\n")
    return path


# ------------------------------------------------------------------------- several files


def test_several_files_give_json_lines_in_input_order(run_cli, three):
    """One JSON object per line, in the order of the FILEs, each the object the file alone
    gives; --channel auto reads the fan-end records' FE channel with the fan-end bearing."""
    r = run_cli("analyze", *three, "--channel", "auto", "--json", "--jobs", "2")
    assert r.code == 0, r.err
    got = _lines(r)
    assert [d["file"] for d in got] == [str(p) for p in three]
    assert [d["channel"] for d in got] == ["DE", "FE", "DE"]
    assert [d["bearing"] for d in got] == ["6205-cwru", "6203-cwru", "6205-cwru"]
    assert {d["rpm_source"] for d in got} == {"file"}
    # CWRU labels (SOURCES.md), as in tests/test_analyze.py
    assert got[0]["diagnosis"] == "outer" and got[2]["diagnosis"] == "inner"
    for p, d in zip(three, got, strict=True):
        alone = run_cli("analyze", p, "--channel", "auto", "--json")
        assert alone.code == 0, alone.err
        assert alone.json() == d, p.name


def test_jobs_1_and_2_give_the_same_output(run_cli, three):
    one = run_cli("analyze", *three, "--json", "--jobs", "1")
    two = run_cli("analyze", *three, "--json", "--jobs", "2")
    assert one.code == two.code == 0, (one.err, two.err)
    assert one.out == two.out and len(one.out.splitlines()) == 3


def test_csv_header_and_rows(run_cli, three):
    """--csv: the header, then one row per file with the values of --json."""
    r = run_cli("analyze", *three, "--channel", "auto", "--csv")
    assert r.code == 0, r.err
    rows = list(csv.reader(io.StringIO(r.out)))
    assert rows[0] == CSV_COLUMNS and len(rows) == 4
    js = _lines(run_cli("analyze", *three, "--channel", "auto", "--json"))
    for row, d in zip(rows[1:], js, strict=True):
        c = dict(zip(CSV_COLUMNS, row, strict=True))
        for k in ("file", "channel", "rpm_source", "bearing", "diagnosis"):
            assert c[k] == d[k], k
        for k in ("fs_hz", "rpm", "confidence"):
            assert float(c[k]) == d[k], k  # written with every digit
        assert c["leading"] == (d["leading"] or "")
        assert (float(c["probability"]) if c["probability"] else None) == d["probability"]
        assert [float(c["band_lo_hz"]), float(c["band_hi_hz"])] == d["band_hz"]
        assert c["error"] == ""
        assert c["channel_source"] == d["channel_source"]
        ca = d["contact_angle"]  # 132 outer, 310 outer, 107 inner: each reads its angle
        assert float(c["contact_angle_deg"]) == ca["contact_angle_deg"]
        assert c["why"] == d["why"]
        assert c["rpm_unchecked"] == (d.get("rpm_unchecked") or "")


def test_csv_says_why_a_refuted_speed_is_uncertain(run_cli):
    """Exploratory testing (twenty-seventh session): ``--csv`` of records at a wrong ``--rpm``
    gave "uncertain, leading ball, probability 0.996" and no reason, and the text line said
    "leading family ball at p 1.00" beside the refutation. The ``why`` column gives the
    reason; the text line leaves out a family that led at the wrong speed."""
    r = run_cli("analyze", cwru_record("107"), "--rpm", 2000, "--csv")
    c = dict(zip(CSV_COLUMNS, list(csv.reader(io.StringIO(r.out)))[1], strict=True))
    assert c["diagnosis"] == "uncertain"
    assert c["why"].startswith("the record's shaft harmonics put the speed at 1747"), c["why"]
    t = run_cli("analyze", cwru_record("107"), "--rpm", 2000)
    assert "leading family" not in t.out.splitlines()[0], t.out


def test_text_output_one_line_per_file(run_cli, three):
    """One line per file; the fan-end record (310) is read on its FE channel by default, and
    the line says so."""
    r = run_cli("analyze", *three)
    assert r.code == 0, r.err
    lines = r.out.splitlines()
    assert len(lines) == 3
    for p, ln, ch in zip(three, lines, ("DE", "FE", "DE"), strict=True):
        assert ln.startswith(f"{p} [{ch}]: "), ln
    assert lines[1].endswith(", channel FE and 6203-cwru from the file name"), lines[1]
    assert "from the file name" not in lines[0] + lines[2]
    assert r.err == ""


def test_fan_end_records_default_to_their_fan_end_channel_and_bearing(run_cli, three):
    """A CWRU fan-end record's fault is in the fan-end bearing (6203), which the FE
    accelerometer faces (CWRU Bearing Data Center; SOURCES.md): without --channel, analyze reads
    FE with the 6203 there and DE with the 6205 elsewhere, as --channel auto does, and says
    where the channel came from; --channel DE still reads the drive end."""
    got = _lines(run_cli("analyze", *three, "--json"))
    assert [d["channel"] for d in got] == ["DE", "FE", "DE"]
    assert [d["bearing"] for d in got] == ["6205-cwru", "6203-cwru", "6205-cwru"]
    assert [d["channel_source"] for d in got] == ["default", "file name (Fan_End)", "default"]
    auto = _lines(run_cli("analyze", *three, "--json", "--channel", "auto"))
    assert [{**d, "channel_source": None} for d in got] == [
        {**d, "channel_source": None} for d in auto
    ]
    de = run_cli("analyze", three[1], "--json", "--channel", "DE").json()
    assert (de["channel"], de["bearing"], de["channel_source"]) == ("DE", "6205-cwru", "option")


def test_a_text_file_with_a_cwru_fan_end_name_gets_the_fan_end_bearing(run_cli, tmp_path):
    """A CSV named like a CWRU fan-end record takes, like a .mat file of that name, the fan
    end's 6203 (it took the drive end's 6205 while its speed came from the name), with --rpm
    too; a drive-end name keeps the 6205, --bearing still decides."""
    from bearingsim.io.signal import read_signal

    src = read_signal(cwru_record("313"), channel="FE")
    n = int(2 * src.fs)
    rows = np.c_[np.arange(n) / src.fs, src.x[:n]]
    fe = tmp_path / "12k_Fan_End_OR014@6_0_313.csv"
    de = tmp_path / "12k_Drive_End_OR014@6_0_313.csv"
    for f in (fe, de):
        np.savetxt(f, rows, delimiter=",", header="time_s,acc", comments="")
    got = _lines(run_cli("analyze", fe, de, "--json"))
    assert [d["bearing"] for d in got] == ["6203-cwru", "6205-cwru"]
    assert "bearing from the file name (Fan_End)" in got[0]["channel_source"]
    assert got[0]["rpm_source"].startswith("name")
    opt = run_cli("analyze", fe, "--json", "--rpm", "1796").json()
    assert (opt["bearing"], opt["diagnosis"]) == ("6203-cwru", "outer"), opt["why"]
    own = run_cli("analyze", fe, "--json", "--bearing", "6205-cwru").json()
    assert own["bearing"] == "6205-cwru" and "bearing from" not in own["channel_source"]


# ------------------------------------------------------------------------- a bad file


def _no_de_channel(tmp_path):
    from scipy.io import savemat

    p = tmp_path / "fe_only.mat"
    x = np.random.default_rng(3).standard_normal((4000, 1))
    savemat(p, {"X999_FE_time": x, "X999RPM": np.array([[1750.0]])})
    return p, "channel = 'DE' not in fe_only.mat"


def _text(tmp_path):
    p = tmp_path / "notes.txt"
    p.write_text("these are my notes\non the test rig\n")
    return p, "notes.txt"


def _nan_csv(tmp_path):
    return _sine_csv(tmp_path / "nan.csv", nan_at=100), "not finite"


def _clipped_csv(tmp_path):
    # named as a CWRU record (load 2): the speed comes from the name and the samples are read
    return _sine_csv(tmp_path / "clipped_2_901.csv", clip=0.8), "is clipped"


BAD = {
    "text file": _text,
    ".mat without the channel": _no_de_channel,
    "CSV with NaN": _nan_csv,
    "clipped CSV": _clipped_csv,
}


@pytest.mark.parametrize("case", list(BAD))
def test_a_bad_file_in_a_batch_is_its_own_line(run_cli, tmp_path, three, case):
    """The bad file (second of three) gets {"file", "error"} and one line on stderr; the
    others are analysed; exit code 2."""
    bad, needle = BAD[case](tmp_path)
    files = [three[0], bad, three[2]]
    r = run_cli("analyze", *files, "--json", "--jobs", "2")
    assert r.code == 2, r.err
    got = _lines(r)
    assert [d["file"] for d in got] == [str(p) for p in files]
    assert set(got[1]) == {"file", "error"} and needle in got[1]["error"], got[1]
    assert "\n" not in got[1]["error"]
    assert got[0]["diagnosis"] == "outer" and got[2]["diagnosis"] == "inner"
    err = r.err.strip().splitlines()
    assert err == [f"{bad}: error: {got[1]['error']}"], r.err
    assert "Traceback" not in r.err


def test_a_bad_file_in_csv_and_text_output(run_cli, tmp_path, three):
    bad, needle = _clipped_csv(tmp_path)
    files = [three[0], bad, three[2]]
    c = run_cli("analyze", *files, "--csv")
    assert c.code == 2
    rows = list(csv.reader(io.StringIO(c.out)))
    err = CSV_COLUMNS.index("error")
    assert len(rows) == 4 and rows[2][0] == str(bad) and needle in rows[2][err]
    assert rows[2][1:err] + rows[2][err + 1 :] == [""] * (len(CSV_COLUMNS) - 2)
    assert rows[1][err] == rows[3][err] == ""
    t = run_cli("analyze", *files)
    assert t.code == 2
    assert [ln.split(" [")[0] for ln in t.out.splitlines()] == [str(three[0]), str(three[2])]
    err = t.err.strip().splitlines()
    assert len(err) == 1 and err[0].startswith(f"{bad}: error: ") and needle in err[0]


def test_a_single_bad_file(run_cli, tmp_path):
    """One FILE: the text output is the one line ``error: ...`` as before; --json gives its
    object with the error, and the same line on stderr."""
    bad, needle = _clipped_csv(tmp_path)
    t = run_cli("analyze", bad)
    assert t.code == 2 and t.out == ""
    assert t.err.strip().splitlines() == [t.err.strip()] and t.err.startswith("error: ")
    assert needle in t.err
    j = run_cli("analyze", bad, "--json")
    assert j.code == 2
    assert j.json() == {"file": str(bad), "error": t.err.strip().removeprefix("error: ")}
    assert j.err == t.err


# ------------------------------------------------------------------------- the shaft speed


def _mat_without_rpm(tmp_path, name):
    """The drive-end samples of record 107 (inner race 0.007 in, load 2 hp, 1748 r/min in its
    file) saved without its X###RPM variable."""
    from scipy.io import savemat

    rec = read_cwru_mat(cwru_record("107"))
    p = tmp_path / name
    savemat(p, {"X999_DE_time": rec.channels["DE"][:, None]})
    return p


def test_rpm_from_the_cwru_file_name(run_cli, tmp_path):
    """No X###RPM, no --rpm: the CWRU nominal speed of the load in the name (2 hp: 1750 r/min,
    manifest.csv column nominal_rpm); --rpm still wins; the record is still diagnosed as the
    inner-race fault it is (1750 vs 1748 r/min: 0.1 %, within the 1 % tolerance of the rule)."""
    mat = _mat_without_rpm(tmp_path, "12k_Drive_End_IR028_2_999.mat")
    r = run_cli("analyze", mat, "--json")
    assert r.code == 0, r.err
    d = r.json()
    assert d["rpm"] == 1750.0 and d["rpm_source"] == NAME_LOAD_2
    assert d["fs_hz"] == 12000.0 and d["diagnosis"] == "inner"
    t = run_cli("analyze", mat)
    assert f"rpm 1750 from the file {NAME_LOAD_2}" in t.out.splitlines()[0]
    o = run_cli("analyze", mat, "--rpm", "1748", "--json")
    assert o.json()["rpm"] == 1748.0 and o.json()["rpm_source"] == "option"


def test_rpm_from_the_name_of_a_csv_and_no_rpm_at_all(run_cli, tmp_path):
    """A CSV named like a CWRU record at load 3 hp takes 1730 r/min; one that is not gets its
    own one-line error naming the file and --rpm."""
    named = _sine_csv(tmp_path / "rig_3_17.csv")
    plain = _sine_csv(tmp_path / "rig.csv")
    r = run_cli("analyze", named, plain, "--json")
    assert r.code == 2
    a, b = _lines(r)
    assert a["rpm"] == 1730.0 and a["rpm_source"] == "name (CWRU nominal speed at load 3 hp)"
    assert b["file"] == str(plain) and "'rig.csv'" in b["error"] and "--rpm" in b["error"]


def test_an_rpm_the_speed_column_refutes_is_refused(run_cli, tmp_path):
    """Exploratory testing (twenty-fifth session): a CSV with an ``rpm`` column of 1748 r/min
    and ``--rpm 1500`` was read at 1500 r/min, silently ("none" for an inner-race fault). A
    speed outside the column's (1st-99th percentile, +/- 1 %) is now refused in one line; one
    a run-up passed through is taken (judged at it, as docs/sim_to_real.md says)."""
    t = np.arange(6000) / 12000.0
    x = np.sin(2 * np.pi * 500.0 * t) + 0.01 * np.random.default_rng(17).standard_normal(t.size)
    steady, runup = tmp_path / "steady.csv", tmp_path / "runup.csv"
    for path, rpm in ((steady, np.full(t.size, 1748.0)), (runup, np.linspace(1000, 2000, t.size))):
        np.savetxt(path, np.c_[t, x, rpm], delimiter=",", header="time_s,acc,rpm", comments="")
    r = run_cli("analyze", steady, "--rpm", "1500")
    assert r.code == 2 and r.err == (
        "error: rpm = 1500 r/min contradicts the speed column of 'steady.csv' (1748 r/min); "
        "valid: a speed it holds, or no --rpm (the column is then read)\n"
    ), r.err
    assert run_cli("analyze", steady, "--rpm", "1760").code == 0  # within 1 %
    r = run_cli("analyze", runup, "--rpm", "2500")
    assert "(1010-1990 r/min, 1st-99th percentile)" in r.err, r.err
    assert run_cli("analyze", runup, "--rpm", "1500").code == 0
    # a tachometer's dropouts to 0 (more than 1 % of the samples) are no speed: they made the
    # 1st percentile 0, and any lower --rpm passed; a column in Hz named rpm gets a hint
    drop = np.full(t.size, 1748.0)
    drop[::20] = 0.0
    hz = np.full(t.size, 1748.0 / 60.0)
    for path, col in ((tmp_path / "drop.csv", drop), (tmp_path / "hz.csv", hz)):
        np.savetxt(path, np.c_[t, x, col], delimiter=",", header="time_s,acc,rpm", comments="")
    r = run_cli("analyze", tmp_path / "drop.csv", "--rpm", "1500")
    assert r.code == 2 and "(1748 r/min)" in r.err, r.err
    r = run_cli("analyze", tmp_path / "drop.csv")  # the dropouts cannot be order tracked
    assert r.code == 2 and r.err.startswith(
        "error: file = 'drop.csv': the speed column cannot be order tracked (300 of its 6000 "
        "samples are not finite and > 0); valid:"
    ), r.err
    assert run_cli("analyze", tmp_path / "drop.csv", "--rpm", "1748").code == 0
    r = run_cli("analyze", tmp_path / "hz.csv", "--rpm", "1748")
    assert r.code == 2 and "it reads like the speed in Hz: name such a column speed_hz" in r.err


# ------------------------------------------------------------------------- options


def test_band_forms(run_cli, three):
    """--band-hz LO,HI for several files; LO HI (HI a positional number that is no file) too;
    a lone LO, or two numbers among the FILEs, is refused before any work."""
    files = three[::2]
    a = run_cli("analyze", *files, "--band-hz", "2000,5000", "--json")
    b = run_cli("analyze", *files, "--band-hz", "2000", "5000", "--json")
    assert a.code == b.code == 0, (a.err, b.err)
    assert a.out == b.out
    assert [d["band_hz"] for d in _lines(a)] == [[2000.0, 5000.0]] * 2
    for argv in (["--band-hz", "2000"], ["--band-hz", "2000", "5000", "6000"]):
        r = run_cli("analyze", *files, *argv)
        assert r.code == 2 and r.out == ""
        assert r.err.startswith("error: band = '2000' is invalid"), r.err


def test_refused_before_any_work(run_cli, tmp_path, three):
    png = tmp_path / "a.png"
    r = run_cli("analyze", *three, "--plot", png)
    assert r.code == 2 and r.out == "" and not png.exists()
    assert (
        r.err.strip() == "error: --plot writes the figure of one FILE; 3 FILEs given: give one FILE"
    )
    r = run_cli("analyze", *three, "--json", "--csv")
    assert r.code == 2 and r.err.strip() == "error: --json and --csv given together; give one"
    r = run_cli("analyze", *three, "--jobs", "0")
    assert r.code == 2 and "jobs = 0 is out of range; valid range [1, inf)" in r.err


# ------------------------------------------------------------------------- check_samples


def _rec(x):
    return SignalRecord(np.asarray(x, dtype=float), 1000.0, 1800.0, "/x/r.csv", "acc")


def test_check_samples():
    """Not finite, constant and clipped records are refused; a peak met by CLIPPED_RUN - 1
    equal samples is not a flat top."""
    rng = np.random.default_rng(5)
    x = rng.standard_normal(1000)
    assert check_samples(_rec(x)).x is not None
    top = x.copy()
    top[500 : 500 + CLIPPED_RUN - 1] = 10.0
    check_samples(_rec(top))
    for bad, needle in [
        (np.where(np.arange(1000) == 7, np.nan, x), "1 of 1000 samples are not finite"),
        (np.where(np.arange(1000) == 9, -np.inf, x), "the first is sample 9"),
        (np.full(1000, 0.5), "all 1000 samples equal 0.5"),
        (np.concatenate([x, np.full(CLIPPED_RUN, -10.0)]), "equal its smallest value -10"),
    ]:
        with pytest.raises(ConfigError, match="^file = 'r.csv', channel 'acc'") as exc:
            check_samples(_rec(bad))
        assert needle in str(exc.value), str(exc.value)
    top[500 + CLIPPED_RUN - 1] = 10.0
    with pytest.raises(ConfigError, match=f"is clipped: {CLIPPED_RUN} consecutive samples"):
        check_samples(_rec(top))


def test_the_cwru_records_are_not_clipped():
    """No channel of any CWRU record has a flat top: the check does not refuse real data."""
    files = sorted(cwru_record("97").parent.glob("*.mat"))
    assert len(files) >= 7  # SOURCES.md: 7 records, and the development set
    for f in files:
        for x in read_cwru_mat(f).channels.values():
            check_samples(_rec(x))


def test_one_analysis_does_not_import_scipy_signal_or_stats(tmp_path):
    """Importing scipy.signal (and the scipy.stats it pulls in) takes 0.8-1.4 s with SciPy
    >= 1.15, five to ten times the analysis of a 10 s record; ``analyze`` needs neither (issue
    17: the start-up of one call). A fresh interpreter analyses a CWRU record and a CSV file;
    the test fails if either module was imported."""
    import subprocess
    import sys

    code = (
        "import sys\n"
        "from bearingsim.cli import main\n"
        "try:\n"
        "    main(['analyze', '--jobs', '1', '--json', *sys.argv[1:]])\n"
        "except SystemExit as e:\n"
        "    assert not e.code, e.code\n"
        "bad = sorted(m for m in ('scipy.signal', 'scipy.stats') if m in sys.modules)\n"
        "assert not bad, bad\n"
    )
    cases = (
        ([str(cwru_record("107"))], "inner"),
        (["--rpm", "1750", str(_sine_csv(tmp_path / "tone.csv"))], None),
    )
    for args, want in cases:
        r = subprocess.run(
            [sys.executable, "-c", code, *args], capture_output=True, text=True, timeout=300
        )
        assert r.returncode == 0, r.stderr[-2000:]
        out = json.loads(r.stdout)
        assert "error" not in out
        if want:
            assert out["diagnosis"] == want
