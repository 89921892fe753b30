"""The fused diagnosis on every record of ``../shared/data/cwru`` (measured; truth = the CWRU
label, grades = Smith & Randall 2015, table B2, via ``manifest.csv``), its calibration and the
leave-one-mounting-out evaluation (issue 17, "what it must show").

Known misses are strict xfails naming the record: they fail the suite the day they start to
pass (then the docs must change), and they stay visible in docs/validation.md until then.
"""

from __future__ import annotations

import csv

import numpy as np
import pytest
from conftest import CWRU

from bearingsim.errors import ConfigError
from bearingsim.signal.fused import CALIBRATION, fit_calibration

pytestmark = pytest.mark.skipif(
    not (CWRU / "manifest.csv").is_file(), reason=f"shared CWRU data not available in {CWRU}"
)

ROWS: list[dict] = []
if (CWRU / "manifest.csv").is_file():
    with open(CWRU / "manifest.csv", newline="") as fh:
        ROWS = list(csv.DictReader(fh))

#: records where the fused diagnosis misses what the issue asks; each is in the benchmark table
#: of docs/validation.md with the reason
#: (none since the sixteenth session's kinematic check: 197, "uncertain" before, is outer)
KNOWN_MISS_Y: dict[str, str] = {}
KNOWN_CONFIDENT_WRONG: dict[str, str] = {}


@pytest.fixture(scope="module")
def bench():
    from bearingsim.signal.cwru_benchmark import evaluate, evidence

    cal, recs = evaluate(evidence(CWRU))
    return cal, {r["file"]: r for r in recs}


def _param(rows, misses):
    return [
        pytest.param(
            r["file"],
            marks=pytest.mark.xfail(strict=True, reason=misses[r["file"]])
            if r["file"] in misses
            else (),
            id=r["file"][:-4],
        )
        for r in rows
    ]


@pytest.mark.parametrize(
    "file", _param([r for r in ROWS if r["smith_randall_grade"].startswith("Y")], KNOWN_MISS_Y)
)
def test_grade_y_records_right(bench, file):
    """Every record Smith & Randall grade Y (diagnosable) is diagnosed right."""
    r = bench[1][file]
    assert r["verdict"] == r["truth"], r


@pytest.mark.parametrize("file", _param(ROWS, KNOWN_CONFIDENT_WRONG))
def test_no_confident_wrong_fault_type(bench, file):
    """No wrong fault type with confidence >= 0.5, the confidence of a development record
    coming from the map fitted without its mounting."""
    r = bench[1][file]
    wrong = r["verdict"] in ("inner", "outer", "ball") and r["verdict"] != r["truth"]
    assert not (wrong and r["confidence"] >= 0.5), r


@pytest.mark.parametrize(
    "file, leading, p_min",
    # leading family and its p before the agreement gate (docs/validation.md's benchmark
    # table: 120 inner 0.83 held out, 198 inner 0.56 leaving its mounting out; 0.77 / 0.75
    # with four views, before the coherence view read 198's BPFO series, fifteenth session;
    # 0.76 / 0.85 before the search followed the contact angle, ninth session): without the
    # gate both would be stated wrong answers at p >= 0.5
    [
        ("12k_Drive_End_B007_2_120.mat", "inner", 0.7),
        ("12k_Drive_End_OR014@6_1_198.mat", "inner", 0.5),
    ],
)
def test_agreement_gate_says_uncertain_when_no_method_reads_the_leading_family(
    bench, file, leading, p_min
):
    """120 (ball, S&R N1) and 198 (outer, S&R P2): the fused score leads with a wrong family at a
    calibrated p above 0.5, but none of the five methods' own readings is that family (120:
    outer, outer, uncertain, none, uncertain; 198: uncertain, none, uncertain, uncertain and
    outer, the coherence view's own reading). The verdict is
    "uncertain" with the leading family and p kept; the gate, not the calibration, stops it."""
    r = bench[1][file]
    assert r["leading"] == leading and r["p"] >= p_min and not r["named"], r
    assert (r["verdict"], r["confidence"]) == ("uncertain", 0.0), r


@pytest.mark.parametrize(
    "file, leading, verdict",
    [
        ("12k_Drive_End_OR014@6_0_197.mat", "outer", "outer"),
        ("12k_Drive_End_OR014@6_1_198.mat", "inner", "uncertain"),
        ("12k_Drive_End_OR014@6_2_199.mat", "outer", "outer"),
    ],
)
def test_the_coherence_view_reads_the_weak_outer_race_records(bench, file, leading, verdict):
    """197-199 (outer 0.014 in @6, S&R Y2, P2, P1; measured): no view of the four band-choosing
    ones reads outer on its own; the coherence view, which averages every band by its modulation
    depth, does (fifteenth session). 199 is then diagnosed outer; so is 197 since the kinematic
    check (sixteenth session; it led with outer at p 0.46 before, the raw view reading inner);
    198 leads with inner (which no method reads) and stays "uncertain"."""
    r = bench[1][file]
    assert r["views"]["csc"].split(" (")[0] == "outer", r["views"]
    assert all(r["views"][v].split(" (")[0] != "outer" for v in ("cpw", "drs_sk", "drs_info"))
    assert (r["leading"], r["verdict"]) == (leading, verdict), r


def test_kinematic_check_on_record_197(bench):
    """197 (outer 0.014 in @6, S&R Y2; measured): its raw view's "BPFI series" lies at 1.5, 3
    and 4.5 BPFO, five resolutions (0.5 Hz) off Z f_r - BPFO: no cage speed makes it the inner
    race's. The kinematic check leaves those lines out of the raw view (the inner race is
    supported in one view, the outer in two), which read inner (22.5 dB against BPFO 13 dB)
    before; the verdict is outer, by two methods."""
    r = bench[1]["12k_Drive_End_OR014@6_0_197.mat"]
    assert "inner" not in r["views"]["raw"], r["views"]
    assert (r["verdict"], r["named"]) == ("outer", True) and r["confidence"] >= 0.5, r


@pytest.mark.parametrize("file", [r["file"] for r in ROWS])
def test_agreement_gate_keeps_every_right_answer(bench, file):
    """Every record whose leading family is the truth at p >= 0.5 has a method that reads it
    (the gate costs no right answer on the shared records)."""
    r = bench[1][file]
    if r["leading"] == r["truth"] and r["p"] is not None and r["p"] >= 0.5:
        assert r["named"] and r["verdict"] == r["truth"], r


@pytest.mark.parametrize(
    "file",
    [r["file"] for r in ROWS if r["smith_randall_grade"].startswith("P") and r["fault"] == "ball"],
)
def test_ball_faults_found_where_the_paper_found_them(bench, file):
    """Smith & Randall found the 0.014 in drive-end ball faults (185-188) partially (P2): the
    fused diagnosis says ball."""
    r = bench[1][file]
    assert r["verdict"] == "ball", r


def test_fan_end_ball_faults_not_taken_for_shaft_harmonics(bench):
    """6203 (fan end): BSF = 1.994 f_r; the ball family must not be built on the 2 f_r line.
    The four fan-end 0.014 in ball records are ball, and no fan-end race-fault record is."""
    fe = {f: r for f, r in bench[1].items() if "Fan_End" in f}
    for r in fe.values():
        if r["truth"] == "ball":
            assert r["verdict"] == "ball", r
        else:
            assert r["verdict"] == r["truth"], r


def test_shipped_calibration_is_the_development_fit(bench):
    """CALIBRATION in fused.py is what scripts/calibrate_diagnosis.py fits (to the 4 digits
    shipped)."""
    cal = bench[0]
    assert cal.intercept == 0.0 == CALIBRATION.intercept
    np.testing.assert_allclose(CALIBRATION.slope, cal.slope, atol=6e-5)


def test_reliability_is_not_overconfident_in_aggregate(bench):
    """Over all records with a leading family, the mean stated probability does not exceed the
    share right by more than 0.05 (the reliability table of docs/validation.md)."""
    ps = [(r["p"], r["leading"] == r["truth"]) for r in bench[1].values() if r["p"] is not None]
    assert len(ps) >= 20
    assert np.mean([p for p, _ in ps]) <= np.mean([ok for _, ok in ps]) + 0.05


def test_fit_calibration_properties():
    """p(0) = 1/2 (no intercept), increasing in the margin, finite on separable data."""
    m = np.array([0.1, 0.3, 0.5, 0.9, 1.2, 0.05])
    c = fit_calibration(m, [True] * 6)
    assert c(0.0) == pytest.approx(0.5)
    assert 0.5 < c(0.2) < c(1.0) < 1.0
    assert np.isfinite(c.slope)
    c2 = fit_calibration(m, [False, True, True, True, True, False])
    assert c2.slope < c.slope
    with pytest.raises(ConfigError, match="same length"):
        fit_calibration([0.1, 0.2], [True])
    with pytest.raises(ConfigError, match="non-finite"):
        fit_calibration([0.1, np.nan], [True, False])


@pytest.mark.skipif(not CWRU.is_dir(), reason="needs ../shared/data/cwru")
def test_report_section_diagnosis(tmp_path):
    """The report's section for issue 17: one row per CWRU record against its label (a
    measurement), match exactly when the verdict is the label, the counts the benchmark
    prints, the halves of the records against issue 17's criterion, and the reliability
    figure."""
    from bearingsim.report import run_report
    from bearingsim.signal.cwru_benchmark import evaluate, evidence

    (sec,) = run_report(tmp_path, quick=True, sections=["diagnosis"], progress=False)
    judged = [r for r in sec.rows if r.status != "info" and "halves" not in r.quantity]
    _cal, recs = evaluate(evidence(CWRU))
    assert len(judged) == len(recs) == 34
    # the halves of the records (docs/validation.md, "Parts of the records"): a mismatch row
    (halves,) = [r for r in sec.rows if "halves" in r.quantity]
    assert halves.reference_kind == "measured" and halves.published == "0"
    assert halves.status == ("match" if halves.ours.startswith("0 of") else "mismatch")
    assert all(r.reference_kind == "measured" for r in judged)
    for row, rec in zip(judged, recs, strict=True):
        assert rec["file"].replace(".mat", "") in row.quantity
        assert row.published == rec["truth"]
        assert row.ours.startswith(rec["verdict"] + " (")
        assert row.status == ("match" if rec["verdict"] == rec["truth"] else "mismatch")
    right = sum(r.status == "match" for r in judged)
    infos = {r.quantity: r.ours for r in sec.rows if r.status == "info"}
    assert infos["records right"] == f"{right} of 34"
    assert (tmp_path / "diagnosis_reliability.png").is_file()


def test_diagnose_fused_applies_the_agreement_gate():
    """The library function itself (not only the benchmark's evaluation) answers "uncertain" on
    198 with the shipped calibration, keeps the leading family and its p, and says why."""
    from bearingsim.catalog import resolve_bearing
    from bearingsim.signal.diagnosis import load_signal
    from bearingsim.signal.fused import diagnose_fused

    rec = load_signal(CWRU / "12k_Drive_End_OR014@6_1_198.mat", channel="DE")
    d = diagnose_fused(rec.x, rec.fs, resolve_bearing("6205-cwru"), rec.rpm / 60.0)
    assert d.diagnosis == "uncertain" and d.confidence == 0.0
    assert d.leading == "inner" and d.probability is not None and d.probability > 0.5
    assert not any(v.names("inner") for v in d.views) and not d.methods_agree
    assert d.as_dict()["methods_agree"] is False
    assert any("no method's own reading" in n for n in d.notes)


@pytest.mark.xfail(
    strict=True,
    reason="issue 17's criterion applied to halves of the records (its asks are on whole "
    "records, where it holds), a mismatch: 5 of 68 parts get a wrong fault type "
    "at p >= 0.5 (120 1/2 inner 0.82; 198 2/2 inner 0.90; 199 1/2 and 2/2 inner 0.77, 0.73; "
    "174 1/2 ball 0.63): the 0.014 in drive-end outer-race records carry a BPFI series that "
    "the DRS views read on their own (docs/validation.md, 'Parts of the records')",
)
def test_no_confident_wrong_fault_type_on_halves_of_the_records():
    """Shorter recordings of the same mountings, no new data: each record cut in two, each half
    diagnosed on its own (`bearingsim.signal.cwru_benchmark.parts_check`). Issue 17's criterion
    (no wrong fault type with confidence >= 0.5) holds on the whole records (28 right, 6
    none/uncertain); on the halves it does not (`python scripts/segment_robustness.py`: 50
    right, 5 wrong, 13 none/uncertain)."""
    from bearingsim.signal.cwru_benchmark import parts_check

    parts = parts_check(CWRU, 2)
    assert len(parts) == 2 * len(ROWS)
    wrong = [(p["file"], p["part"], p["verdict"], round(p["confidence"], 2)) for p in parts
             if p["outcome"] == "wrong"]  # fmt: skip
    assert not wrong, wrong


def test_no_confident_wrong_fault_type_through_the_other_ends_accelerometer():
    """Another transfer path, no new data: each record diagnosed from the accelerometer at the
    *other* end of the motor (the faulty bearing's geometry kept). The fault reaches that
    sensor through the rotor and frame, weaker and coloured differently: what a fault of
    another mounting would look like to the rule. The rule must still give no wrong fault type
    with confidence >= 0.5 (issue 17's criterion). Eighth session: 26 of 34 right, the other 8
    none/uncertain (docs/validation.md)."""
    from bearingsim.signal.cwru_benchmark import parts_check

    parts = parts_check(CWRU, 1, sensor="other")
    assert len(parts) == len(ROWS)  # every record has both ends' sensors
    wrong = [(p["file"], p["truth"], p["verdict"], round(p["confidence"], 2)) for p in parts
             if p["outcome"] == "wrong"]  # fmt: skip
    assert not wrong, wrong


@pytest.mark.skipif(not CWRU.is_dir(), reason="needs ../shared/data/cwru")
def test_short_pieces_of_a_fan_end_outer_race_record_stay_outer():
    """A helper's stress test of the higher-sideband search (twenty-fifth session): on a 0.5 s
    piece of CWRU 312 (fan end, 6203, outer race @3), the outer race's BPFO + 2 f_r and
    BPFO + f_r fall in BPFI's and BPFI - f_r's windows; counted as detected before the
    attribution, they opened the inner race's search, whose BPFI - 2 f_r target landed on
    BPFO itself: pieces 1 and 14 of 20 read "inner" (0.71, 0.76; outer 0.78, 0.80 before).
    Two changes keep them "outer": the higher sidebands are spaced by the carrier-scaled
    kinematic rate (either alone suffices here), and the search is opened by the lines as
    attributed (test_benchmark_methods.py::
    test_an_outer_race_faults_shaft_sidebands_do_not_open_the_inner_races_search)."""
    from dataclasses import replace

    from bearingsim.signal import analyze_record
    from bearingsim.signal.diagnosis import load_signal

    rec = load_signal(CWRU / "12k_Fan_End_OR014@3_3_312.mat", channel="FE")
    n = rec.x.size // 20
    for k in (0, 13):
        d = analyze_record(replace(rec, x=rec.x[k * n : (k + 1) * n]), "6203-cwru")
        assert d.diagnosis == "outer", (k + 1, d.diagnosis, d.confidence, d.why)
