"""``scripts/screenshot_report.py`` (issue 15, part 3): a page whose figures are linked and shown at
the planned size passes; the old page (figures squeezed to 48 % of the width, not linked) fails.
Needs headless Chromium (Debian package ``chromium``); skipped without it."""

from __future__ import annotations

import importlib.util
import shutil
from pathlib import Path

import pytest

SCRIPT = Path(__file__).resolve().parents[1] / "scripts" / "screenshot_report.py"

pytestmark = pytest.mark.skipif(
    not any(shutil.which(n) for n in ("chromium", "chromium-browser", "google-chrome")),
    reason="headless Chromium not installed (Debian package 'chromium')",
)


def _script():
    spec = importlib.util.spec_from_file_location("screenshot_report", SCRIPT)
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    return mod


def _page(tmp_path: Path) -> Path:
    from bearingsim.plotting import new_figure
    from bearingsim.report import Section
    from bearingsim.report.figures import save_figure
    from bearingsim.report.html import write_html

    fig, axs = new_figure(2, 2)
    for a in axs.ravel():
        a.plot([0, 1], [0, 1])
        a.set_xlabel("time [s]")
        a.set_ylabel("acceleration [m/s²]")
    save_figure(fig, tmp_path / "wide.png")
    sec = Section("s", "a section", figures=[("wide.png", "four panels")])
    write_html(tmp_path / "report.html", [sec], quick=True)
    return tmp_path / "report.html"


def test_a_page_of_the_standard_passes(tmp_path, capsys):
    page = _page(tmp_path)
    shots = tmp_path / "shots"
    assert _script().main([str(page), "-o", str(shots)]) == 0, capsys.readouterr().out
    assert (shots / "page_full.png").stat().st_size > 0 and (shots / "page_00.png").is_file()
    assert list(tmp_path.glob("*.html")) == [page]  # the report folder is not written to


def test_the_old_page_fails(tmp_path, capsys):
    page = _page(tmp_path)
    old = (
        "<!doctype html><html><head><style>body{max-width:1100px;margin:auto}"
        "figure{display:inline-block;margin:0.5em;max-width:48%}figure img{max-width:100%}"
        "</style></head><body><figure><img src='wide.png'><figcaption>x</figcaption></figure>"
        "</body></html>"
    )
    page.write_text(old)
    assert _script().main([str(page), "-o", str(tmp_path / "shots")]) == 1
    out = capsys.readouterr().out
    assert "not wrapped in a link" in out and "7 pt text is" in out
