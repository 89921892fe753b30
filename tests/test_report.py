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
        assert {
            "quantity",
            "source",
            "published",
            "ours",
            "rel_diff",
            "status",
            "reference_kind",
            "verified_by",
            "size",
        } <= set(r)
        assert r["status"] in {"match", "deviates", "mismatch", "info"}
        assert r["reference_kind"] in {"paper", "measured", "standard", "none"}
    for png in report_dir.glob("*.png"):
        assert png.name in html
    assert "<h2>Summary</h2>" in html


def test_foundation_rows(report_dir):
    rows = [
        r
        for r in json.loads((report_dir / "results.json").read_text())
        if r["section"] == "foundation"
    ]
    by_q = {r["quantity"]: r for r in rows}
    assert by_q["6205 BPFI at 1748 r/min [Hz]"]["status"] == "match"
    psi = by_q["6205 load-zone half angle psi_L [deg]"]
    assert psi["status"] == "deviates" and psi["note"] and psi["reference_kind"] == "paper"
    assert psi["verified_by"] == "tests/test_deviations.py::test_psi_l_68_deg_needs_k_028_hertz"
    assert psi["published"] == value("vsm.s2_1.load_zone_half_angle")
    assert not [r for r in rows if r["status"] == "mismatch"]
    assert by_q["6205-cwru BPFI order [-]"]["reference_kind"] == "standard"


def test_reproduce_cli_json(run_cli, tmp_path):
    r = run_cli("reproduce", "--quick", "--section", "foundation", "-o", tmp_path / "o", "--json")
    assert r.code == 0, r.err
    d = r.json()
    assert d["sections"] == ["foundation"] and d["counts"]["match"] > 10
    assert d["counts_by_kind"]["standard"]["match"] == 8  # the CWRU bearing table
    assert "foundation" in SECTIONS
    # a section named twice runs once (exploratory testing: its rows were counted twice)
    twice = run_cli("reproduce", "--quick", "--section", "foundation", "--section", "foundation",
                    "-o", tmp_path / "t", "--json")  # fmt: skip
    assert twice.code == 0, twice.err
    assert twice.json()["sections"] == ["foundation"]
    assert twice.json()["counts"] == d["counts"]


# ------------------------------------------------------------------------- status rules


def test_status_rules():
    """A miss against a measurement is a mismatch whatever the reason; against a paper or a
    standard it deviates only with a reason and the test verifying it; no reference is info."""
    from bearingsim.report import Row, compare, info, judge

    tid = "tests/test_deviations.py::test_psi_l_68_deg_needs_k_028_hertz"
    assert compare("q", "s", 1.0, 1.05, 0.1, kind="measured").status == "match"
    m = compare("q", "s", 1.0, 100.0, 0.1, "a reason", kind="measured", verified_by=tid)
    assert m.status == "mismatch" and m.note == "a reason" and m.verified_by == ""
    assert m.size == "100× high (+40.0 dB)"
    assert compare("q", "s", 1.0, 2.0, 0.1, "a reason", kind="paper").status == "mismatch"
    d = compare("q", "s", 1.0, 2.0, 0.1, "a reason", kind="standard", verified_by=tid)
    assert d.status == "deviates" and d.verified_by == tid
    assert compare("q", "s", 4.0, 0.04, 0.1, kind="paper").size == "100× low (-40.0 dB)"
    assert judge("q", "s", "ball", "none", False, "why", kind="measured").status == "mismatch"
    assert info("q", "s", 3.0).status == "info"
    with pytest.raises(ValueError, match="never 'deviates'"):
        Row("q", "s", 1.0, 2.0, 1.0, "deviates", "why", reference_kind="measured", verified_by=tid)
    with pytest.raises(ValueError, match="verified_by"):
        Row("q", "s", 1.0, 2.0, 1.0, "deviates", "why", reference_kind="paper")
    with pytest.raises(ValueError, match="info"):
        Row("q", "s", None, 2.0, None, "match", reference_kind="none")
    with pytest.raises(ValueError, match="needs a reference"):
        compare("q", "s", 1.0, 2.0, 0.1, kind="none")


def test_levels_in_db_get_their_size_and_rank_among_the_misses():
    """A prominence in dB was stored as text, so its row had no size ('–') and the report
    listed it last among the misses; now the two levels are numbers whose difference is the
    size (-> the amplitude ratio it stands for), and a 34.9 dB miss ranks above a 5x one."""
    from bearingsim.report import Section, compare, judge
    from bearingsim.report.html import _summary

    r = judge("prominence [dB]", "CWRU 197", 14.3, 49.2, False, kind="measured", db_level=True)
    # its size is the difference in dB (twenty-fifth session: it read "55.6× high (+34.9 dB)",
    # a ratio of levels that are already logarithmic); it still ranks by the ratio it stands for
    assert r.size == "+34.9 dB" and r.factor == pytest.approx(10 ** (34.9 / 20))
    assert compare("f [Hz]", "paper", 100.0, 100.4, 0.01, kind="paper").size == "+0.4 %"
    five = judge("RMS [m/s²]", "CWRU 132", 1.0, 5.0, False, kind="measured")
    assert five.size == "5× high (+14.0 dB)"
    html = "".join(_summary([Section("signals", "t", rows=[five, r])]))
    assert html.index("prominence [dB]") < html.index("RMS [m/s²]")


def test_a_row_judged_on_its_own_bound_shows_its_size_in_the_difference_column(tmp_path):
    """The side-by-side rows (judge: no relative tolerance) left the section table's difference
    column empty (last note's planning list); they now show their size, a compare row its
    relative difference, and a row without numbers a dash."""
    import re

    from bearingsim.report import Section, compare, info, judge
    from bearingsim.report.html import write_html

    rows = [
        judge("RMS [m/s²]", "CWRU 132", 1.0, 5.0, False, kind="measured"),
        compare("f [Hz]", "paper", 100.0, 101.0, 0.05, kind="paper"),
        info("crest [-]", "ours", "crest 4"),
    ]
    write_html(tmp_path / "r.html", [Section("s", "t", rows=rows)], quick=True)
    page = (tmp_path / "r.html").read_text()
    table = page[page.index("<th>difference</th>") :]
    cells = re.findall(r"<tr class='\w+'><td>[^<]*</td><td>[^<]*</td><td>[^<]*</td><td>[^<]*"
                       r"</td><td>(.*?)</td>", table)  # fmt: skip
    # a compare row also shows the tolerance it was judged by (a helper's review, twenty-fifth
    # session: identical offsets read match and mismatch with no tolerance in sight)
    assert cells == ["5× high (+14.0 dB)", "+1.00 %<br><small>tolerance ±5 %</small>", "–"]


def test_a_side_by_side_rows_ratio_reads_on_its_side_of_the_bound():
    """Exploratory testing (twentieth session): the signals section printed a kurtosis ratio
    of 1.502 as "1.5×; bound ×1.5" in a mismatch row. The ratio (or dB difference) now takes
    the digits it needs to read on the side of the bound its status says."""
    from bearingsim.report.sections.signals import _size_text

    assert _size_text("kurtosis", 1.502, 1.5, False) == "1.502×"
    assert _size_text("kurtosis", 1.45, 1.5, True) == "1.45×"
    assert _size_text("rms", 0.6663, 2.0, True) == "0.666×"
    assert _size_text("kurtosis", 0.66664, 1.5, False) == "0.6666×"
    assert _size_text("prominence_db", -6.04, 6.0, False) == "-6.04 dB"
    assert _size_text("prominence_db", -5.2, 6.0, True) == "-5.2 dB"


def test_a_second_run_leaves_one_report_and_records_how_it_was_made(tmp_path, monkeypatch):
    # twenty-first session: `reproduce --section vsm -o rep` after a full run replaced
    # results.json but kept the first run's figures of the other sections, and nothing in the
    # folder said whether it was a --quick run or which version made it
    import sys
    import types

    from bearingsim import __version__
    from bearingsim.report import Section, run_report

    def fake(name):
        mod = types.ModuleType(f"bearingsim.report.sections.{name}")

        def run(ctx):
            (ctx.out_dir / f"{name}.png").write_bytes(b"\x89PNG\r\n\x1a\n")
            return Section(name, name, figures=[(f"{name}.png", "a figure")])

        mod.TITLE, mod.run = name, run
        monkeypatch.setitem(sys.modules, mod.__name__, mod)

    fake("fake_a")
    fake("fake_b")
    (tmp_path / "mine.png").write_bytes(b"x")  # a user's file in the folder: never touched
    run_report(tmp_path, quick=True, sections=["fake_a", "fake_b"], progress=False)
    run = json.loads((tmp_path / "run.json").read_text())
    assert run["quick"] is True and run["bearingsim_version"] == __version__
    assert run["sections"] == ["fake_a", "fake_b"] and run["figures"] == [
        "fake_a.png",
        "fake_b.png",
    ]
    run_report(tmp_path, quick=False, sections=["fake_b"], progress=False)
    assert sorted(p.name for p in tmp_path.glob("*.png")) == ["fake_b.png", "mine.png"]
    run = json.loads((tmp_path / "run.json").read_text())
    assert run["quick"] is False and run["sections"] == ["fake_b"]


def test_a_record_standing_in_for_the_papers_says_so():
    """Exploratory testing (twenty-third session): the fig. 15 rows set the paper's 0.014 in
    inner-race simulation beside CWRU 107, a 0.007 in fault (the paper's record is not in
    shared/data), and the row did not say so. The rows' note now starts with why the record
    stands in."""
    from bearingsim.report import Section
    from bearingsim.report.sections.vsm import _peak_rows

    sec = Section("vsm", "t")
    why = "CWRU 107 is a 0.007 in (0.1778 mm) fault standing in for the paper's record; "
    _peak_rows(sec, "fig. 15", "107", 10.0, {"VSM": 1.0, "TVSM": 2.0, "DEM": 3.0}, why)
    assert len(sec.rows) == 3 and all(r.note.startswith(why) for r in sec.rows)
    _peak_rows(sec, "other", "109", 10.0, {"VSM": 1.0, "TVSM": 2.0, "DEM": 3.0})
    assert sec.rows[-1].note.startswith("the seed's own models miss the tests too")
