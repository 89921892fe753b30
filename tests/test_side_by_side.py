"""Simulated beside measured (issue 16, item 5, first version): the same numbers computed the
same way on both signals."""

from __future__ import annotations

import json
import re
from pathlib import Path

import numpy as np
import pytest

from bearingsim.errors import ConfigError
from bearingsim.io.signal import read_signal
from bearingsim.side_by_side import (
    CONTACT_ROUGHNESS_M,
    DEFECT_PROFILE,
    SLIP_PERCENT,
    side_by_side,
    signal_metrics,
    within_bounds,
)

CWRU = Path(__file__).resolve().parents[2] / "shared" / "data" / "cwru"
needs_data = pytest.mark.skipif(not CWRU.is_dir(), reason="needs ../shared/data/cwru")


def _ringing_impacts(fs: float, rate: float, fn=3000.0, zeta=0.03) -> np.ndarray:
    """2 s of impacts at ``rate`` [Hz] ringing at ``fn`` [Hz] (damping ``zeta``) in weak white
    noise, sampled at ``fs`` [Hz]."""
    n = int(2 * fs)
    x = np.zeros(n)
    x[:: int(fs / rate)] = 1.0
    t = np.arange(int(0.02 * fs)) / fs
    h = np.exp(-zeta * 2 * np.pi * fn * t) * np.sin(2 * np.pi * fn * t)
    return np.convolve(x, h)[:n] + 0.001 * np.random.default_rng(0).standard_normal(n)


def test_metrics_of_periodic_impacts():
    """Impacts at 100 Hz ringing at 3 kHz (zeta 0.03) in weak white noise: the envelope line at
    100 Hz stands far out, the kurtosis is high, the RMS is the signal's."""
    fs, rate = 12000.0, 100.0
    y = _ringing_impacts(fs, rate)
    k = signal_metrics(y, fs, rate)
    assert k.rms == pytest.approx(np.std(y), rel=1e-9)
    # the kurtogram takes the most impulsive band: here the impacts' short broadband part above
    # the ringing (4-6 kHz), where the envelope line stands out most
    assert 0.0 <= k.band_lo_hz < k.band_hi_hz <= fs / 2
    assert k.prominence_db > 30.0
    assert k.kurtosis > 5.0  # impulsive


def test_metrics_in_a_given_band():
    """``band``: the envelope in that band instead of the signal's own kurtogram band (the
    side by side's ``band="measured"``). Its own band given gives the default's numbers;
    impacts ringing at 3 kHz read in 300-900 Hz, below the ringing, have a weaker line (half);
    RMS and kurtosis do not depend on the band."""
    fs, rate = 12000.0, 100.0
    y = _ringing_impacts(fs, rate)
    own = signal_metrics(y, fs, rate)
    assert signal_metrics(y, fs, rate, band=(own.band_lo_hz, own.band_hi_hz)) == own
    low = signal_metrics(y, fs, rate, band=(300.0, 900.0))
    assert (low.band_lo_hz, low.band_hi_hz) == (300.0, 900.0)
    assert low.line < 0.7 * own.line and (low.rms, low.kurtosis) == (own.rms, own.kurtosis)


def test_a_pure_tone_has_kurtosis_1_5_and_crest_sqrt2():
    fs = 12000.0
    t = np.arange(24000) / fs
    k = signal_metrics(np.sin(2 * np.pi * 1000.0 * t), fs, 100.0)
    assert k.kurtosis == pytest.approx(1.5, rel=1e-3)
    assert k.crest == pytest.approx(np.sqrt(2), rel=1e-3)


@pytest.mark.parametrize("fm", [107.0, 107.25, 107.35])
def test_the_fault_line_is_read_between_bins_too(fm):
    """A helper's exploratory testing (twenty-eighth session): the line was the largest bin
    within +/- 2 %, so a modulation half-way between two bins (107.25 Hz on 2 s) read 0.878 of
    the one on a bin. A carrier in the band, amplitude-modulated at depth 0.5: its envelope's
    line is 0.5 whatever its place against the bins."""
    fs = 12000.0
    t = np.arange(24000) / fs
    x = (1.0 + 0.5 * np.cos(2 * np.pi * fm * t)) * np.sin(2 * np.pi * 3000.0 * t)
    assert signal_metrics(x, fs, fm, band=(2000.0, 4000.0)).line == pytest.approx(0.5, rel=0.01)


def test_bounds():
    ok = within_bounds({"rms": 1.9, "line": 0.6, "kurtosis": 1.4, "prominence_db": -5.0})
    assert all(ok.values())
    bad = within_bounds({"rms": 2.1, "line": 0.4, "kurtosis": 1.6, "prominence_db": 6.5})
    assert not any(bad.values())


@needs_data
def test_record_132_side_by_side():
    rec = CWRU / "12k_Drive_End_OR007@6_2_132.mat"
    s = side_by_side(rec, "cwru-de-12k", duration_s=0.5)
    json.dumps(s)  # JSON-ready: the rig's background signal was returned with the numbers
    assert set(s) == {"record", "fault", "size_in", "end", "rpm", "fs_hz", "fault_hz", "grade",
                      "scenario", "measured", "simulated", "ratio"}  # fmt: skip
    assert s["fault"] == "outer" and s["end"] == "DE" and s["fs_hz"] == 12000.0
    assert s["scenario"]["defect_width_m"] == pytest.approx(0.007 * 0.0254)
    x = read_signal(rec, channel="DE").x[:6000]
    x = x - x.mean()
    assert s["measured"]["rms"] == pytest.approx(np.sqrt(np.mean(x * x)), rel=1e-12)
    for k in ("rms", "kurtosis", "crest", "line"):
        assert s["ratio"][k] == pytest.approx(s["simulated"][k] / s["measured"][k])
    assert s["fault_hz"] == pytest.approx(3.5848 * s["rpm"] / 60.0, rel=1e-3)  # BPFO order
    # the slip of real bearings (Randall & Antoni 2011: 1-2 %), sampled like a recorder
    assert s["scenario"]["slip_percent"] == SLIP_PERCENT == 1.5
    assert s["scenario"]["antialias"] is True
    assert s["scenario"]["defect_profile"] == DEFECT_PROFILE == "geometric"
    assert s["scenario"]["contact_roughness_m"] == CONTACT_ROUGHNESS_M == 1e-7
    z = side_by_side(rec, "cwru-de-12k", duration_s=0.5, realism={"slip_percent": 0.0})
    assert z["scenario"]["slip_percent"] == 0.0 and z["measured"] == s["measured"]
    assert z["simulated"]["prominence_db"] != s["simulated"]["prominence_db"]


@needs_data
def test_ball_record_side_by_side():
    """A ball record is simulated with the ball defect; its fault line is 2×BSF (CWRU table:
    4.7135 orders)."""
    s = side_by_side(CWRU / "12k_Drive_End_B007_2_120.mat", "cwru-de-12k", duration_s=0.5)
    assert s["fault"] == "ball" and s["scenario"]["fault"] == "ball"
    assert s["fault_hz"] == pytest.approx(4.7135 * s["rpm"] / 60.0, rel=1e-3)
    assert np.isfinite(s["ratio"]["line"])


@needs_data
def test_normal_record_is_refused_in_one_line():
    with pytest.raises(ConfigError, match="cannot be simulated"):
        side_by_side(CWRU / "normal_0_97.mat", "cwru-de-48k", duration_s=0.2)


@needs_data
def test_report_section_signals(tmp_path):
    """The report section (issue 16, item 5): four rows per judged record, all against a
    measurement, each row's status the bound it meets, the info row counting the records
    within all bounds, and the side-by-side figure."""
    from bearingsim.report import run_report

    (sec,) = run_report(tmp_path, quick=True, sections=["signals"], progress=False)
    # beside each judged record, its crest factor (shown: issue 16 gives no bound) and its
    # ringing band, judged by whether it overlaps the record's (twenty-fifth session: both
    # were "info", which hid band misses against the measurements)
    bands = [r for r in sec.rows if "ringing band" in r.quantity]
    # the fan end (one fault size here) is judged leave-one-load-out, counted apart (it was not
    # judged at all; a helper's review, twenty-fifth session)
    lolo = [r for r in sec.rows if r.status != "info" and "leave-one-load-out" in r.quantity
            and r not in bands]  # fmt: skip
    judged = [r for r in sec.rows if r.status != "info" and "rotor + rig" not in r.quantity
              and r not in bands and r not in lolo]  # fmt: skip
    shown = [r for r in sec.rows if r.status == "info" and "crest factor" in r.quantity]
    # the rotor's record 132 too
    assert len(shown) == len(bands) == len(judged) // 4 + 1 + len(lolo) // 4
    assert lolo and len(lolo) % 4 == 0 and all("Fan_End" not in r.quantity for r in lolo)
    assert {r.quantity.split(":")[0].split()[1] for r in lolo} == {
        "274", "276", "277", "286", "287", "288", "289", "309", "310", "311", "312"
    }  # fmt: skip
    (alone,) = [r for r in sec.rows if r.ours == "not judged"]  # 313: one record, one load
    assert "CWRU 313" in alone.quantity and "no other load" in alone.note
    (lolo_sum,) = [r for r in sec.rows if r.status == "info" and "the fan end" in r.quantity]
    n_lolo = len(lolo) // 4
    lolo_ok = sum(all(r.status == "match" for r in lolo[4 * i : 4 * i + 4]) for i in range(n_lolo))
    assert lolo_sum.ours == f"{lolo_ok} of {n_lolo}"
    assert all(re.fullmatch(r"[0-9.]+", r.ours) for r in shown)
    for r in bands:
        lo_m, hi_m = (float(v) for v in r.published.removesuffix(" kHz").split("–"))
        lo_s, hi_s = (float(v) for v in r.ours.removesuffix(" kHz").split("–"))
        overlap = min(hi_m, hi_s) > max(lo_m, lo_s)
        assert r.reference_kind == "measured" and r.status == ("match" if overlap else "mismatch")
    assert judged and len(judged) % 4 == 0
    assert all(r.reference_kind == "measured" for r in judged)
    assert {r.status for r in judged} <= {"match", "mismatch"}
    n_rec = len(judged) // 4
    ok_all = sum(all(r.status == "match" for r in judged[4 * i : 4 * i + 4]) for i in range(n_rec))
    summary, rotor_summary = [
        r for r in sec.rows if r.status == "info" and "crest factor" not in r.quantity
        and r not in (alone, lolo_sum)
    ]  # fmt: skip
    assert summary.ours == f"{ok_all} of {n_rec}"
    # the rotor model beside record 132 (issue 16), four rows against the measurement
    rotor = [r for r in sec.rows if "rotor + rig" in r.quantity and r.status != "info"
             and r not in bands]  # fmt: skip
    assert len(rotor) == 4 and all("CWRU 132" in r.quantity for r in rotor)
    assert all(r.reference_kind == "measured" for r in rotor)
    assert rotor_summary.ours == ("yes" if all(r.status == "match" for r in rotor) else "no")
    assert (tmp_path / "signals_side_by_side.png").is_file()
    assert (tmp_path / "report.html").is_file()
    # the caption named three dashed lines where each panel draws one, unlabelled (exploratory
    # testing, twenty-third session): each panel's line now has its name in a legend
    (cap,) = [c for f, c in sec.figures if f == "signals_side_by_side.png"]
    assert "dashed: the record's fault line, BPFO, BPFI or 2×BSF, as its legend says" in cap
    # the figure drew three best-case records only (a helper's review, twenty-fifth session):
    # the largest RMS miss of the judged records is drawn too, named in the caption
    rms = {int(re.match(r"CWRU (\d+)", r.quantity)[1]): float(r.ours) / float(r.published)
           for r in judged if "RMS [" in r.quantity}  # fmt: skip
    num = max(rms, key=lambda n: abs(np.log(rms[n])))
    assert f"(here CWRU {num}, simulated RMS" in cap, cap


@needs_data
def test_model_path_scale_matches_the_identification_rms():
    """The model-based path scale (issue 16, item 4): fitted on one record, the scaled rig
    gives that record's RMS (within 3 %: the power balance leaves out only the cross term of
    the background and the path), and the scale is below 1 (the VSM is louder than the
    record, docs/validation.md)."""
    from bearingsim.rig import load_rig
    from bearingsim.side_by_side import model_path_scale, simulate_record

    rec = CWRU / "12k_Drive_End_OR007@6_2_132.mat"
    rig = load_rig("cwru-de-12k")
    scaled, k = model_path_scale(rig, [rec], duration_s=0.5)
    assert 0.0 < k < 1.0
    assert scaled.model_gain("vsm").scale == k and scaled.model_gain("rotor") is not None
    applied = scaled.for_model("vsm")
    assert applied.gain == pytest.approx(rig.gain * k)
    assert [m.gain for m in applied.modes] == pytest.approx([m.gain * k for m in rig.modes])
    c = simulate_record(rec, scaled, duration_s=0.5)
    rms = [float(np.std(c[w])) for w in ("measured", "simulated")]
    assert rms[1] / rms[0] == pytest.approx(1.0, rel=0.03)
    with pytest.raises(ConfigError, match="records is empty"):
        model_path_scale(rig, [])


@needs_data
def test_simulate_record_background_is_what_the_rig_adds_on_its_own():
    """``simulated - background`` is the model's output through the path alone: the rig with
    a zero path gives ``background`` sample for sample (same seed, rate and shaft speed)."""
    from dataclasses import replace

    from bearingsim.rig import load_rig
    from bearingsim.side_by_side import simulate_record

    rec = CWRU / "12k_Drive_End_OR007@6_2_132.mat"
    rig = load_rig("cwru-de-12k")
    silent = replace(rig, gain=0.0, modes=())
    c = simulate_record(rec, rig, duration_s=0.2)
    c0 = simulate_record(rec, silent, duration_s=0.2)
    np.testing.assert_allclose(c["background"], c0["simulated"], rtol=0, atol=1e-12)
    np.testing.assert_allclose(c0["background"], c0["simulated"], rtol=0, atol=1e-12)
    assert np.std(c["simulated"] - c["background"]) > 1.0  # the VSM's impacts [m/s^2]


@needs_data
def test_model_path_scale_scales_a_model_below_the_background():
    """A model whose output lies far below the rig's background (the rotor with its 6.6 kg
    housing, docs/validation.md ROTOR "Amplitudes") still gets the gain that gives the
    record's RMS. The former estimator, a ratio of total RMS, measured the background there
    and left the path nearly unscaled (k near 1); the power balance scales it by tens."""
    from bearingsim.rig import load_rig
    from bearingsim.side_by_side import model_path_scale, simulate_record

    rec = CWRU / "12k_Drive_End_OR007@6_2_132.mat"
    rig = load_rig("cwru-de-12k")
    scaled, k = model_path_scale(rig, [rec], model="rotor", duration_s=0.3)
    assert k > 10.0
    c = simulate_record(rec, scaled, model="rotor", duration_s=0.3)
    rms = [float(np.std(c[w])) for w in ("measured", "simulated")]
    assert rms[1] / rms[0] == pytest.approx(1.0, rel=0.05)


@needs_data
def test_model_path_scale_refuses_records_the_background_explains():
    """Records quieter than the rig's background (a 0.014 in outer-race record, 0.91 m/s^2
    RMS, against the cwru-de-12k background made 4x as strong in power, 1.5 m/s^2) leave no
    power for the path: a one-line error instead of a zero or imaginary gain. (With the shipped
    background, 0.75 m/s^2 since the seventeenth session, the record leaves some.)"""
    from dataclasses import replace

    from bearingsim.rig import load_rig
    from bearingsim.side_by_side import model_path_scale

    rig = load_rig("cwru-de-12k")
    loud = replace(rig, background=replace(
        rig.background, psd=tuple(4.0 * v for v in rig.background.psd)))  # fmt: skip
    rec = CWRU / "12k_Drive_End_OR014@6_1_198.mat"
    with pytest.raises(ConfigError, match="background alone carries their power"):
        model_path_scale(loud, [rec], duration_s=0.2)
    assert model_path_scale(rig, [rec], duration_s=0.2)[1] > 0.0


@needs_data
def test_rotor_side_by_side_simulates_the_records_bearing():
    """The rotor model beside a record (issue 16: "the rotor model with the CWRU profile ...
    on record 132"): the fault goes into the record's bearing of the two-bearing motor, the
    slip, the drop profile and the rough contacts travel, and the rig reads the housing of the
    record's end."""
    from bearingsim.side_by_side import simulate_record

    c = simulate_record(
        CWRU / "12k_Drive_End_OR007@6_2_132.mat", "cwru-de-12k", model="rotor", duration_s=0.2
    )
    sc = c["scenario"]
    assert sc["model"] == "rotor" and sc["de_fault"] == "outer" and "fe_fault" not in sc
    assert sc["slip_percent"] == SLIP_PERCENT and sc["defect_profile"] == DEFECT_PROFILE
    assert sc["contact_roughness_m"] == CONTACT_ROUGHNESS_M
    assert sc["defect_width_m"] == pytest.approx(0.007 * 0.0254)
    assert c["simulated"].shape == c["measured"].shape == (2400,)
    assert np.all(np.isfinite(c["simulated"]))
    f = simulate_record(
        CWRU / "12k_Fan_End_B014_0_286.mat", "cwru-fe-12k", model="rotor", duration_s=0.2
    )
    assert f["scenario"]["fe_fault"] == "ball" and "de_fault" not in f["scenario"]
    assert f["fault_hz"] == pytest.approx(3.9874 * f["rpm"] / 60.0, rel=1e-3)  # 6203 2xBSF


@needs_data
def test_model_path_scale_conditions_skips_healthy_records_and_checks_its_conditions():
    """The Python form of ``rig identify --conditions``: a healthy record is skipped as the
    command line skips it (it gave a gain 3x the CLI's before, and a gain of 30 alone), and a
    condition that is not a dict or has an unknown key is a one-line error (an AttributeError;
    silently ignored) — exploratory testing, fourteenth session."""
    from bearingsim.io.signal import read_signal
    from bearingsim.rig import load_rig
    from bearingsim.side_by_side import model_path_scale, model_path_scale_conditions

    rig = load_rig("cwru-de-48k")
    a = read_signal(CWRU / "48k_Drive_End_OR007@6_0_135.mat", channel="DE")
    b = read_signal(CWRU / "normal_0_97.mat", channel="DE")
    outer = dict(fault="outer", bearing="6205-cwru", defect_width_m=0.007 * 0.0254)
    none = dict(fault="none")
    _, k1 = model_path_scale_conditions(rig, [a], [outer], duration_s=0.2)
    _, k2 = model_path_scale_conditions(rig, [a, b], [outer, none], duration_s=0.2)
    assert k2 == k1
    for conds, message in (
        ([none], "no record has a bearing fault"),
        (["outer"], "conditions[0] = 'outer' is invalid; valid: a dict"),
        ([outer | {"foo": 1}], "conditions[0]: unknown key 'foo'"),
    ):
        with pytest.raises(ConfigError, match=re.escape(message)):
            model_path_scale_conditions(rig, [a], conds, duration_s=0.2)
    # the CWRU form skips the healthy record too (docs/models.md: "Healthy records are skipped")
    recs = [CWRU / "48k_Drive_End_OR007@6_0_135.mat", CWRU / "normal_0_97.mat"]
    assert (
        model_path_scale(rig, recs, duration_s=0.2)[1]
        == model_path_scale(rig, recs[:1], duration_s=0.2)[1]
    )


@needs_data
def test_the_outer_race_pair_spans_more_than_two_bounds():
    """The measured fact behind docs/validation.md "What leave-one-mounting-out allows": at the
    drive end, 12 kHz, the 0.007 in outer-race record (132) carries more than 4x the RMS of every
    0.014 in one (197-200), the widest ratio two x2 bounds span. So a simulation whose level does
    not fall as the defect grows (the next test), through a rig identified on the other size's
    records, misses the RMS bound on both 132 and 197."""
    rms = {}
    for n in ("OR007@6_2_132", "OR014@6_0_197", "OR014@6_1_198", "OR014@6_2_199",
              "OR014@6_3_200"):  # fmt: skip
        x = read_signal(CWRU / f"12k_Drive_End_{n}.mat", channel="DE").x[:24000]
        rms[n[-3:]] = float(np.sqrt(np.mean((x - x.mean()) ** 2)))
    quiet = max(v for k, v in rms.items() if k != "132")
    assert rms["132"] / quiet > 4.0, rms
    assert rms["132"] == pytest.approx(5.54, rel=0.01)  # the side-by-side table's measured RMS


@pytest.mark.parametrize("fault", ["outer", "inner"])
def test_the_models_level_grows_with_the_defect(fault):
    """The other half of that argument, for the VSM as the side-by-side runs it (the realism a
    rig brings, record 132's speed): the bare output's RMS at 0.014 in is above that at
    0.007 in (the geometric drop grows with the width squared)."""
    from bearingsim import simulate
    from bearingsim.side_by_side import CWRU_DEPTH_M, REALISM

    def rms(size_in: float) -> float:
        sc = dict(model="vsm", bearing="6205-cwru", fault=fault, **REALISM, rpm=1750.0,
                  defect_width_m=size_in * 0.0254, defect_depth_m=CWRU_DEPTH_M,
                  duration_s=0.3, fs_hz=12000.0, antialias=True, seed=0)  # fmt: skip
        y = np.asarray(simulate(sc)["acc_y"])
        return float(np.sqrt(np.mean((y - y.mean()) ** 2)))

    assert rms(0.014) > 2.0 * rms(0.007)


@needs_data
def test_rig_other_loads_is_identified_on_the_mountings_other_loads_only(tmp_path):
    """Leave-one-load-out (scripts/side_by_side.py --split load): the rig of 170 (inner 0.014
    in, load 1) comes from 169, 171 and 172 (the same mounting's other loads), never from 170
    itself nor from another mounting; a mounting with one record here (107) has none; a record
    not in the manifest is refused in one line."""
    from bearingsim.side_by_side import rig_other_loads

    rig = rig_other_loads(CWRU, "12k_Drive_End_IR014_1_170.mat")
    used = re.findall(r"12k_\w+?_\d+\.mat", rig.provenance)
    assert sorted(used) == [f"12k_Drive_End_IR014_{k}.mat" for k in ("0_169", "2_171", "3_172")]
    assert rig_other_loads(CWRU, "12k_Drive_End_IR007_2_107.mat") is None
    with pytest.raises(ConfigError, match="is not in"):
        rig_other_loads(CWRU, "nothing.mat")


@needs_data
def test_model_path_fit_gives_the_records_spectrum_and_weighs_the_direct_path():
    """The model-based path fit (bearingsim.rig_identify.fit_path_gains, the default objective:
    the shape in dB, the level by the power balance) on record 132 with the VSM's output as
    the known input: the fitted rig gives the record's RMS within 3 % (the balance is over
    20 Hz to 0.45 fs and leaves out the cross term of background and path);
    its gains differ from the output-only ones (direct gain 1), and its provenance names
    the fit, the model and the record. Healthy-only or no records are refused in one line;
    an unknown gain method too."""
    from bearingsim.rig import load_rig
    from bearingsim.side_by_side import model_path_fit, rig_other_loads, simulate_record

    rec = CWRU / "12k_Drive_End_OR007@6_2_132.mat"
    rig = load_rig("cwru-de-12k")
    fitted, fit = model_path_fit(rig, [rec], duration_s=1.0)
    assert fit.start_gains == (rig.gain, *(m.gain for m in rig.modes))
    assert fit.gains != pytest.approx(fit.start_gains, rel=0.1)
    g = fitted.model_gain("vsm")  # the fitted form, for the VSM only
    assert g.scale is None and (g.path_gain, *g.mode_gains) == fit.gains
    assert fitted.model_gain("rotor") == rig.model_gain("rotor"), "the other model's kept"
    assert (fitted.gain, fitted.modes, fitted.background) == (rig.gain, rig.modes, rig.background)
    assert "log Welch spectra" in g.provenance and "vsm" in g.provenance
    assert rec.name in g.provenance and fit.power_ratio == pytest.approx(1.0)
    applied = fitted.for_model("vsm")
    assert (applied.gain, *(m.gain for m in applied.modes)) == fit.gains
    c = simulate_record(rec, fitted, duration_s=1.0)
    rms = [float(np.std(c[w])) for w in ("measured", "simulated")]
    assert rms[1] / rms[0] == pytest.approx(1.0, rel=0.03)
    with pytest.raises(ConfigError, match="records is empty"):
        model_path_fit(rig, [])
    with pytest.raises(ConfigError, match="none has a bearing fault"):
        model_path_fit(rig, [CWRU / "normal_0_97.mat"])
    with pytest.raises(
        ConfigError, match="gain_method = 'x' is invalid; valid: power, spectral, whittle"
    ):
        rig_other_loads(CWRU, "12k_Drive_End_IR014_1_170.mat", model_gain="vsm", gain_method="x")


@pytest.mark.parametrize(
    ("args", "message"),
    [
        (["--duration-s", "-1"], "error: options: duration_s = -1 s is out of range"),
        (["--slip-percent", "-5"], "error: options: slip_percent = -5 % is out of range"),
        (["--data", "/nonexistent"], "error: --data = '/nonexistent' is not a folder"),
        (["--json", "/proc/x.json"], "error: --json = '/proc/x.json' cannot be written"),
    ],
)
def test_the_script_refuses_bad_options_before_any_simulation(args, message):
    """Exploratory testing (twenty-third session): a negative duration or slip wrote an error
    into every row and exited 0; --data naming no folder and an unwritable --json (checked
    after every simulation) ended in tracebacks. Each is now one line on stderr, exit 2."""
    import subprocess
    import sys

    script = Path(__file__).resolve().parents[1] / "scripts" / "side_by_side.py"
    r = subprocess.run([sys.executable, str(script), *args], capture_output=True, text=True,
                       timeout=120)  # fmt: skip
    assert r.returncode == 2 and r.stdout == "", (r.returncode, r.stdout[:200])
    assert r.stderr.startswith(message) and r.stderr.count("\n") == 1, r.stderr
