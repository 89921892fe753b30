"""Gaps found by exploratory testing of the command line (2026-11-27): each case was
reproduced on the previous HEAD (a traceback, a silent wrong answer or an option range quoted
but not enforced) and is now one line on stderr with exit code 2, or right."""

from __future__ import annotations

import tomllib
from pathlib import Path

import numpy as np
import pytest
from conftest import cwru_record

R132 = "12k_Drive_End_OR007@6_2_132.mat"


def test_option_ranges_are_enforced_by_the_option_itself(run_cli, tmp_path):
    """``Number`` quoted its range in messages but did not check it: rig identify --max-modes 0
    (or -2) ran and wrote one mode."""
    rec = cwru_record(R132)
    for v in ("0", "-2"):
        line = run_cli(
            "rig", "identify", rec, "--name", "m", "--max-modes", v, "-o", tmp_path / "m"
        ).refused()
        assert f"max_modes = {v} is out of range; valid range [1, inf)" in line
    assert not list(tmp_path.iterdir())


def test_rig_identify_refuses_a_rate_too_low_and_an_empty_name(run_cli, tmp_path):
    """--fs-hz 100 raised 'nperseg must be a positive integer' from SciPy (exit 1, a
    traceback); --name '' failed after the work. (The record is copied under the CWRU site's
    own name, which gives no rate: --fs-hz against a rate its name gives is refused as such.)"""
    rec = tmp_path / "in" / "132.mat"
    rec.parent.mkdir()
    rec.write_bytes(Path(cwru_record(R132)).read_bytes())
    out = tmp_path / "out"
    line = run_cli(
        "rig", "identify", rec, "--name", "m", "--fs-hz", "100", "-o", out / "m.toml"
    ).refused()
    assert "fs_hz = 100 Hz is too low to identify a transfer path" in line
    assert "valid range [4526, inf) Hz" in line
    line = run_cli("rig", "identify", rec, "--name", " ", "-o", out / "m.toml").refused()
    assert "name = ' ' is empty" in line
    assert not out.exists()


def test_an_identified_cwru_rig_names_its_sensor_end(run_cli, tmp_path):
    """A rig identified on CWRU fan-end records says so (``end = "FE"``), and the rotor model
    feeds that end's housing into it (before, the fan-end profile read the drive-end housing,
    acc_y); a rig without an end keeps acc_y."""
    from bearingsim.rig import load_rig

    out = tmp_path / "fe.toml"
    rec = cwru_record("12k_Fan_End_OR014@6_0_313.mat")
    r = run_cli("rig", "identify", rec, "--name", "fe", "-o", out)
    assert r.code == 0, r.err
    assert tomllib.loads(out.read_text())["end"] == "FE"
    assert load_rig(str(out)).end == "FE" and load_rig("cwru-fe-12k").end == "FE"
    assert load_rig("cwru-de-12k").end == "DE"
    assert "sensor at the FE end" in run_cli("rig", "show", "cwru-fe-12k").out
    bad = out.read_text().replace('end = "FE"', 'end = "middle"')
    (tmp_path / "bad.toml").write_text(bad)
    line = run_cli("rig", "show", tmp_path / "bad.toml").refused()
    assert "rig.end = 'middle' is invalid; valid: DE, FE" in line


@pytest.mark.parametrize(
    "make, message",
    [
        (lambda x: np.hstack([x, x]), "X001_DE_time is a 12000 x 2 array; valid: one column"),
        (lambda x: x * (1 + 1j), "X001_DE_time is complex; valid: real samples"),
        # a CWRU file holds g: 1 g is 9.80665 m/s^2
        (lambda x: np.ones_like(x), "all 12000 samples equal 9.80665; valid: a vibration signal"),
    ],
    ids=["two-columns", "complex", "constant"],
)
def test_mat_channels_that_are_not_one_real_signal(run_cli, tmp_path, make, message):
    """Two columns were flattened and interleaved (record 132 read 'uncertain', leading inner
    at 0.94); complex samples lost their imaginary part with a raw NumPy warning; a constant
    record got the sample-rate inference error."""
    from scipy.io import loadmat, savemat

    d = loadmat(cwru_record(R132))
    x = next(v for k, v in d.items() if k.endswith("DE_time"))[:12000]
    f = tmp_path / "site_2_1.mat"  # a CWRU site name: no rate in it
    savemat(f, {"X001_DE_time": make(x), "X001RPM": np.array([[1750.0]])})
    assert message in run_cli("analyze", f).refused()
    row = tmp_path / "row_2_1.mat"  # one row is one signal, as one column
    savemat(row, {"X001_DE_time": x.T, "X001RPM": np.array([[1750.0]])})
    assert run_cli("analyze", row, "--fs-hz", "12000").code == 0


def test_two_outputs_on_one_path_and_plot_formats(run_cli, tmp_path):
    """vsm-trace -o same.csv --plot same.csv replaced the CSV with the PNG and said 'wrote';
    load --plot x.pdf wrote PNG bytes under a .pdf name."""
    line = run_cli(
        "vsm-trace",
        "--cage-revs",
        "0.05",
        "-o",
        tmp_path / "same.png",
        "--plot",
        tmp_path / "same.png",
    ).refused()
    assert "--plot = " in line and "is also -o/--output" in line
    assert not list(tmp_path.iterdir())
    line = run_cli("load", "6205", "--fy-n", "50", "--plot", tmp_path / "x.txt").refused()
    assert "has no figure suffix; valid: a name ending in .png, .pdf, .svg, .jpg, .jpeg" in line
    # .jpg was refused as "no figure suffix" and save_figure wrote PNG bytes for it
    cases = ((".pdf", b"%PDF"), (".svg", b"<?xml"), (".png", b"\x89PNG"), (".jpg", b"\xff\xd8"))
    for suffix, magic in cases:
        p = tmp_path / f"load{suffix}"
        assert run_cli("load", "6205", "--fy-n", "50", "--plot", p).code == 0
        assert p.read_bytes().startswith(magic)


def _write(path, **keys):
    lines = [f"{k} = {v!r}" if isinstance(v, str) else f"{k} = {v}" for k, v in keys.items()]
    path.write_text("\n".join(lines).replace("'", '"') + "\n")
    return path


NU204 = dict(id="r", type="cylindrical_roller", n_elements=11, element_diameter_m=7.94e-3,
             pitch_diameter_m=34e-3, roller_length_m=9e-3)  # fmt: skip


def test_bearing_files_that_are_not_a_bearing(run_cli, tmp_path):
    """A roller bearing with raceways of 1 and 100 mm around 7.94 mm rollers on a 34 mm pitch
    circle was accepted (inner p_max 1831 MPa against NU204-ECP's 734); an empty file named
    'type = None'; a numeric source and a 1000 m wide bearing were accepted."""
    f = _write(tmp_path / "r.toml", **NU204, inner_raceway_diameter_m=1e-3,
               outer_raceway_diameter_m=0.1)  # fmt: skip
    line = run_cli("contact", "--bearing-file", f, "--radial-load-n", "1000").refused()
    # d_m - D = 26.06 mm, within 0.1 D = 0.794 mm
    assert "inner_raceway_diameter_m = 0.001 m is out of range; valid range [0.025266" in line
    # the seed IAS's printed raceways (26.5/41.5 mm, 0.055 D off) stay valid
    f = _write(tmp_path / "ok.toml", **NU204, inner_raceway_diameter_m=26.5e-3,
               outer_raceway_diameter_m=41.5e-3)  # fmt: skip
    assert run_cli("contact", "--bearing-file", f, "--radial-load-n", "1000").code == 0
    (tmp_path / "empty.toml").write_text("")
    line = run_cli("info", "--bearing-file", tmp_path / "empty.toml", "--rpm", "1").refused()
    assert "missing required key 'type'" in line
    f = _write(tmp_path / "s.toml", **NU204, source=5)
    assert (
        "source = 5 is not a text" in run_cli("info", "--bearing-file", f, "--rpm", "1").refused()
    )
    f = _write(tmp_path / "w.toml", **NU204, width_m=1000.0, outer_diameter_m=47e-3)
    line = run_cli("info", "--bearing-file", f, "--rpm", "1").refused()
    assert "width_m = 1000 m is out of range; valid range [0.009, 0.047] m" in line


def test_bearings_json_writes_bearing_files_that_read_back_the_same(run_cli, tmp_path):
    """bearings --json left out bore, outside diameter and width, so a bearing file written
    from it lost the checks that depend on them (the clearance range of the bore: a 60 um
    clearance on the 6205 was refused from the catalogue and accepted from the file)."""
    from bearingsim.catalog import bearing_from_dict, get_bearing

    for item in run_cli("bearings", "--json").json()["bearings"]:
        assert bearing_from_dict(item, "json") == get_bearing(item["id"])
    item = next(b for b in run_cli("bearings", "--json").json()["bearings"] if b["id"] == "6205")
    f = _write(tmp_path / "rt.toml", **item)
    line = run_cli("load", "--bearing-file", f, "--fy-n", "50", "--clearance-m", "6e-5").refused()
    assert "clearance" in line


def test_load_at_zero_radial_load_with_a_preload(run_cli):
    """Every ball is loaded: the load zone is the whole bearing (psi_L = 180 deg) and the
    load-distribution factor is unbounded (epsilon -> inf as F_r -> 0, Harris); it said
    psi_L = 90 deg and epsilon = 0.5 at zero load and 180 deg at 1 mN."""
    d = run_cli("load", "6205", "--clearance-m", "-6e-6", "--json").json()
    assert (d["psi_l_deg"], d["epsilon"], d["n_loaded"]) == (180.0, None, 9)
    d = run_cli("load", "6205", "--clearance-m", "0", "--fy-n", "0", "--json").json()
    assert (d["psi_l_deg"], d["epsilon"]) == (90.0, 0.5)  # zero clearance: Harris's limit


def test_messages_that_point_somewhere_useful(run_cli, tmp_path):
    """A rig table whose frequencies do not increase named the whole 40-value list; analyze on
    an IAS result said 'load_result reads any kind' instead of naming analyze-ias."""
    from bearingsim.rig import load_rig
    from bearingsim.rig_identify import rig_to_toml

    d = load_rig("cwru-de-12k")
    text = tmp_path / "r.toml"

    rig = rig_to_toml(d).replace("frequency_hz = [10.0, ", "frequency_hz = [10.0, 5.0, ", 1)
    rig = rig.replace("psd_m2_per_s4_per_hz = [", "psd_m2_per_s4_per_hz = [1e-3, ", 1)
    text.write_text(rig)
    line = run_cli("rig", "show", text).refused()
    assert "background.frequency_hz[1] = 5 Hz does not exceed [0] = 10 Hz" in line
    assert len(line) < 300
    import xarray as xr

    out = tmp_path / "ias.nc"  # what an IAS result's file says it is (IasResult.FORMAT)
    xr.Dataset(attrs={"format": "bearingsim.IasResult/1"}).to_netcdf(out, engine="h5netcdf")
    line = run_cli("analyze", out).refused()
    assert "an IAS result: bearingsim analyze-ias reads it" in line


def test_the_fan_end_profile_reads_the_rotors_fan_end_housing(tmp_path):
    """With the rotor model, cwru-fe-12k (end = "FE") is fed the fan-end housing; before, every
    profile read acc_y, the drive-end housing, so a fan-end fault reached the fan-end sensor
    through the drive end. analyze reads that sensor with the fan-end bearing (6203)."""
    from bearingsim import simulate
    from bearingsim.io.signal import read_signal
    from bearingsim.rig import Rig, load_rig
    from bearingsim.rig_identify import rig_to_toml

    sc = dict(model="rotor", fe_fault="outer", duration_s=0.1, fs_hz=12000.0, rig="cwru-fe-12k")
    r = simulate(sc)
    assert r.meta["rig"]["input_channel"] == "acc_y_fe"
    r.save(tmp_path / "fe.nc")
    assert read_signal(tmp_path / "fe.nc").bearing.id == "6203-cwru"
    de = simulate({**sc, "rig": "cwru-de-12k"})
    assert de.meta["rig"]["input_channel"] == "acc_y"
    # a fan-end rig reading the horizontal direction reads the fan end's too (it read acc_x,
    # the drive end's housing)
    fe_x = load_rig("cwru-fe-12k").to_dict() | {"input_channel": "acc_x"}
    (tmp_path / "fex.toml").write_text(rig_to_toml(Rig.from_dict(fe_x)), encoding="utf-8")
    rx = simulate({**sc, "rig": str(tmp_path / "fex.toml")})
    assert rx.meta["rig"]["input_channel"] == "acc_x_fe"


def test_simulate_options_that_contradict_each_other(run_cli, tmp_path, capsys):
    """--bearing with --bearing-file ran with the file's bearing and ignored an invalid id;
    --set KEY twice kept the last silently; -o x.csv wrote netCDF under a CSV name; zero radial
    load named unbalance_n with the empty range [0, 0)."""
    f = _write(tmp_path / "mb.toml", id="mine", type="ball", n_elements=9,
               element_diameter_m=7.94e-3, pitch_diameter_m=39e-3,
               inner_groove_radius_m=4.089e-3, outer_groove_radius_m=4.169e-3)  # fmt: skip
    out = tmp_path / "r.nc"
    line = run_cli(
        "simulate", "--bearing-file", f, "--bearing", "nosuch", "--duration-s", "0.01", "-o", out
    ).refused()
    assert "bearing = 'nosuch' and bearing_file = " in line and "given together" in line
    line = run_cli(
        "simulate", "--duration-s", "0.01", "--set", "rpm=100", "--set", "rpm=200", "-o", out
    ).refused()
    assert "--set rpm=... is given twice" in line
    line = run_cli("simulate", "--duration-s", "0.01", "-o", tmp_path / "x.csv").refused()
    assert "names no netCDF file; valid: a name ending in .nc, .nc4 or .h5" in line
    line = run_cli(
        "simulate", "--duration-s", "0.01", "--fx-n", "0", "--fy-n", "0", "-o", out
    ).refused()
    assert "unbalance_n" not in line and "radial load |(fx_n, fy_n)| = 0 N" in line
    assert not list(tmp_path.glob("*.nc")) and not (tmp_path / "x.csv").exists()
    assert run_cli("simulate", "--bearing-file", f, "--duration-s", "0.01", "-o", out).code == 0


def test_rotor_modes_says_what_it_cannot_give(run_cli):
    """--n-modes 1000 returned the model's 36 modes without a word; --distributed-rotor with
    --disks gave the same answer for any disk count (the disks were ignored)."""
    r = run_cli("rotor-modes", "--n-modes", "1000", "--json")
    assert r.code == 0 and len(r.json()["frequency_hz"]) < 1000
    assert "warning: n_modes = 1000: the model has" in r.err
    line = run_cli("rotor-modes", "--distributed-rotor", "--disks", "3").refused()
    assert "--disks and --disk-positions-mm do not apply" in line
    assert run_cli("rotor-modes", "--distributed-rotor").code == 0


def test_analyze_refuses_an_order_grid_beyond_the_memory_budget(run_cli, tmp_path):
    """A speed column in the wrong unit asked analyze's order tracking for an unbounded angle
    grid (3e10 revolutions x 512 samples here); analyze-ias had the check, analyze did not."""
    n, fs = 12000, 12000.0
    t = np.arange(n) / fs
    x = np.random.default_rng(0).standard_normal(n)
    rows = ["time_s,DE,rpm"] + [f"{a:.8f},{b:.6f},1.8e12" for a, b in zip(t, x, strict=True)]
    f = tmp_path / "speed.csv"
    f.write_text("\n".join(rows) + "\n")
    line = run_cli("analyze", f, "--bearing", "6205-cwru").refused()
    assert "the signal spans 3e+10 shaft revolutions" in line and "memory budget" in line


def test_the_speed_range_quoted_is_the_one_the_run_accepts(run_cli, tmp_path):
    """At 48 kHz the rpm message said (0, 265871] while the ring-burst limit (speed factor
    1e7 mm r/min / 39 mm) refuses everything above 256410."""
    line = run_cli(
        "simulate", "--rpm", "1e6", "--duration-s", "0.01", "-o", tmp_path / "q.nc"
    ).refused()
    assert "valid range (0, 256410] r/min at this fs_hz (above that the rings burst)" in line


def test_rig_identify_never_writes_over_a_record_and_writes_toml_only(run_cli, tmp_path):
    """`rig identify rec.mat -o rec.mat` replaced the measured record with TOML (exit 0), and
    `-o out.nc` wrote a rig file that `--rig out.nc` would look up as a profile name. Both are
    refused in one line before any work; the record is left as it was."""
    import shutil

    rec = tmp_path / "rec.mat"
    shutil.copy(cwru_record(R132), rec)
    before = rec.read_bytes()
    line = run_cli("rig", "identify", rec, "--name", "x", "-o", rec).refused()
    assert "names no TOML file; valid: a name ending in .toml" in line
    line = run_cli("rig", "identify", rec, "--name", "x", "-o", tmp_path / "r.nc").refused()
    assert "-o/--output" in line and "names no TOML file" in line
    twin = tmp_path / "rec.toml"  # a record that happens to end in .toml
    shutil.copy(rec, twin)
    line = run_cli("rig", "identify", twin, "--name", "x", "-o", twin).refused()
    assert "is the record" in line and "valid: an output apart from the records" in line
    line = run_cli(
        "rig", "identify", rec, "--name", "x", "-o", tmp_path / "ok.toml", "--plot", rec
    ).refused()
    assert "--plot" in line
    assert rec.read_bytes() == before and twin.read_bytes() == before
    assert sorted(p.name for p in tmp_path.iterdir()) == ["rec.mat", "rec.toml"]


def test_simulate_help_shows_the_ias_models_own_defaults(run_cli):
    # twenty-first session: the help showed only the ring models' defaults (1 s, 48 kHz,
    # 1750 r/min, automatic step), and `simulate --model ias` then ran 10 s at 50 kHz with a
    # 1 us step, ten times longer than the help said
    text = " ".join(run_cli("simulate", "--help").out.split())
    shown = ("(1; ias: 10)", "ias: 50000)", "(automatic; ias: 1e-06)", "(6205; ias: NU204-ECP)")
    for s in (*shown, "(10; ias: 0)", "(50; ias: 400)", "(seed VSM table 1; ias: 1.3)"):
        assert s in text, s
    assert "[default: (vsm)]" in text  # the model's own default, not each family's name
    # vsm-trace runs the ring models only: their defaults alone (the shared options showed
    # the IAS model's beside them once simulate's did)
    trace = " ".join(run_cli("vsm-trace", "--help").out.split())
    assert "ias:" not in trace and "(6205)" in trace and "(10)" in trace


def test_a_bearing_option_the_model_does_not_take_is_named_as_given(run_cli, tmp_path):
    """Exploratory testing (twenty-fourth session): ``simulate --model rotor --bearing 6206``
    said "unknown key 'bearing_file'", the option not given (the command line passes its unset
    options as None), and never pointed to the rotor's own bearing keys; a roller bearing
    through a ring model without a fault said "this defect geometry needs balls", with no
    defect asked for."""
    out = str(tmp_path / "x.nc")
    r = run_cli("simulate", "--model", "rotor", "--bearing", "6206", "--duration-s", "0.01",
                "-o", out)  # fmt: skip
    assert r.code == 2 and r.err.startswith(
        "error: options: unknown key 'bearing' (a key of model vsm/dem/tvsm/ias); this model's "
        "bearings are de_bearing and fe_bearing; valid keys: model, de_bearing, "
    ), r.err
    r = run_cli("simulate", "--model", "vsm", "--bearing", "NU204-ECP", "--duration-s", "0.01",
                "-o", out)  # fmt: skip
    assert r.code == 2 and r.err == (
        "error: bearing = 'NU204-ECP' is not a ball bearing; the VSM/DEM/TVSM models need a "
        "ball bearing\n"
    ), r.err


def test_a_csvs_acceleration_column_is_the_one_named_so_and_a_time_ramp_is_refused(
    run_cli, tmp_path
):
    """Exploratory testing (twenty-fourth session), a user's CSV records: with the columns
    ``time_s,speed_rpm,acc_mps2`` the first column after the time (the speed) was read as the
    acceleration, without a word; and with the time column misspelt (``tiem_s``), the "no
    time column; give fs_hz" error led to ``--fs-hz``, which read the time ramp as the
    signal (``rig identify`` made a rig of it, exit 0). The one column named acc... is now
    the signal, and an even ramp is refused as a time column."""
    import numpy as np

    fs, n = 12000.0, 12000
    t = np.arange(n) / fs
    acc = np.random.default_rng(0).standard_normal(n) + np.sin(2 * np.pi * 107.0 * t)
    p = tmp_path / "r.csv"
    np.savetxt(p, np.column_stack([t, np.full(n, 1750.0), acc]), delimiter=",",
               header="time_s,speed_rpm,acc_mps2", comments="")  # fmt: skip
    d = run_cli("analyze", str(p), "--bearing", "6205-cwru", "--rpm", "1750", "--json").json()
    d = d[0] if isinstance(d, list) else d
    assert d["channel"] == "acc_mps2", d["channel"]
    q = tmp_path / "typo.csv"  # (with acc_mps2 as the second column it is now taken)
    np.savetxt(q, np.column_stack([t, acc]), delimiter=",", header="tiem_s,vib",
               comments="")  # fmt: skip
    r = run_cli("analyze", str(q), "--bearing", "6205-cwru", "--rpm", "1750", "--fs-hz",
                "12000")  # fmt: skip
    assert r.code == 2 and r.err.startswith("error: file = 'typo.csv', channel 'tiem_s' "
                                            "changes in even steps"), r.err  # fmt: skip
    assert r.err.count("\n") == 1
