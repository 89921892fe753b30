"""``bearingsim reproduce --section rotor`` (issue 6): rows without mismatch, the seed figs. 5–7
analogues, and the key comparisons with CWRU record 132."""

from __future__ import annotations

import json

import pytest
from conftest import cwru_record

from bearingsim.report.published import value


@pytest.fixture(scope="module")
def rotor_rows(tmp_path_factory):
    from bearingsim.report import run_report

    # the section compares with CWRU record 132: without it the measured rows and figure are
    # missing, so these tests need it
    cwru_record("12k_Drive_End_OR007@6_2_132.mat")

    out = tmp_path_factory.mktemp("rotor_rep")
    run_report(out, quick=True, sections=["rotor"], progress=False)
    rows = [r for r in json.loads((out / "results.json").read_text()) if r["section"] == "rotor"]
    return out, {r["quantity"]: r for r in rows}


def test_rotor_section_rows_and_figures(rotor_rows):
    out, rows = rotor_rows
    for q, r in rows.items():
        if r["status"] in ("deviates", "mismatch"):
            assert r["note"], f"{r['status']} row without a reason: {q}"
        if r["status"] == "deviates":
            assert r["reference_kind"] in ("paper", "standard") and r["verified_by"], q
    # the model analyses: no mismatch against a paper's model or a closed form
    assert not [
        q for q, r in rows.items() if r["status"] == "mismatch" and q.startswith("rotor alone")
    ]
    for png in ("rotor_fig5_6_cwru132.png", "rotor_fig7_spectra.png", "rotor_fig7_amplitude.png"):
        assert (out / png).stat().st_size > 10_000
    html = (out / "report.html").read_text()
    assert "rotor_fig7_amplitude.png" in html


def test_rotor_section_key_comparisons(rotor_rows):
    _, rows = rotor_rows
    imp = rows["impacts between 0.10 s and 0.20 s [-]"]
    assert imp["status"] == "match"
    assert imp["published"] == imp["ours"] == value("cwru.record132.impacts")
    ff = rows["DE outer fault: fault frequency, simulated vs measured 132 [Hz]"]
    assert ff["status"] == "match"
    assert (
        rows["fault frequency over 1, 2, 3, 5, 9 disks and the FE limit: spread [Hz]"]["status"]
        == "match"
    )
    drop = rows["envelope amplitude at BPFO, highest to lowest disk case [%]"]
    assert drop["published"] == value("rotor.s3.amplitude_drop")
    assert drop["status"] in ("match", "mismatch")
    # the amplitude misses against the measured record stay mismatches until the model closes
    # them (issue 15): a reason explains a difference, it does not remove it
    for q in (
        "DE acceleration RMS, 1 s [m/s²]",
        "DE envelope amplitude at BPFO (2-5 kHz band) [m/s²]",
    ):
        r = rows[q]
        assert r["reference_kind"] == "measured"
        ratio = r["ours"] / r["published"]
        assert r["status"] == ("match" if abs(ratio - 1) <= 0.5 else "mismatch"), (q, ratio)
    assert rows["rotor alone, 1 disk, pinned: 1st natural frequency [Hz]"]["status"] == "match"
