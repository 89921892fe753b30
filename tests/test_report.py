"""The reproduce report (main job): files, row schema, and the foundation rows."""

from __future__ import annotations

import json

import pytest

from bearingsim.report import SECTIONS
from bearingsim.report.published import value


@pytest.fixture(scope="module")
def report_dir(tmp_path_factory):
    from bearingsim.report import run_report

    out = tmp_path_factory.mktemp("rep")
    run_report(out, quick=True, sections=["foundation"], progress=False)
    return out


def test_report_files(report_dir):
    rows = json.loads((report_dir / "results.json").read_text())
    html = (report_dir / "report.html").read_text()
    assert rows and "<table>" in html
    for r in rows:
        assert {"quantity", "source", "published", "ours", "rel_diff", "status"} <= set(r)
        assert r["status"] in {"match", "explained", "mismatch"}
    for png in report_dir.glob("*.png"):
        assert png.name in html


def test_foundation_rows(report_dir):
    rows = [
        r
        for r in json.loads((report_dir / "results.json").read_text())
        if r["section"] == "foundation"
    ]
    by_q = {r["quantity"]: r for r in rows}
    assert by_q["6205 BPFI at 1748 r/min [Hz]"]["status"] == "match"
    psi = by_q["6205 load-zone half angle psi_L [deg]"]
    assert psi["status"] == "explained" and psi["note"]
    assert psi["published"] == value("vsm.s2_1.load_zone_half_angle")
    assert not [r for r in rows if r["status"] == "mismatch"]


def test_reproduce_cli_json(run_cli, tmp_path):
    r = run_cli("reproduce", "--quick", "--section", "foundation", "-o", tmp_path / "o", "--json")
    assert r.code == 0, r.err
    d = r.json()
    assert d["sections"] == ["foundation"] and d["counts"]["match"] > 10
    assert "foundation" in SECTIONS
