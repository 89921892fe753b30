"""Render a reproduction report (``report.html``) in headless Chromium as a reader sees it, save
screenshots and check the figures' on-screen size (issue 15, part 3).

    python scripts/screenshot_report.py OUT/report.html [-o /tmp/figs_shots] [--width 1400]

What it does:

1. Loads a copy of the page (with a ``<base>`` pointing at the report's folder, so the PNGs load;
   the report folder is not written to) in headless Chromium at ``--width`` CSS px and reads,
   through the page's own JavaScript (``--dump-dom``), every image's rendered width, natural
   width, load state and enclosing link, and the page height.
2. Checks each figure: loaded, wrapped in a link to its own PNG, and shown large enough that the
   smallest font of the figure standard (:data:`bearingsim.plotting.MIN_FONT_PT`) is at least
   ``--min-px`` CSS px on screen (rendered width / (PNG width / its dpi) = CSS px per figure inch).
3. Takes one screenshot of the whole page and cuts it into ``page_NN.png`` tiles of ``--tile``
   px height (the file viewer shows them at readable scale), plus ``page_full.png``.

Exit status 1 when a check fails (the problems are printed), 2 when Chromium is missing. Not a
test: CI has no browser; run it before submitting a change to the figures or the page.
"""

from __future__ import annotations

import argparse
import json
import re
import shutil
import subprocess
import sys
import tempfile
from pathlib import Path

#: injected before </body>: writes the measurements into the DOM once everything has loaded
_PROBE = """
<script>
window.addEventListener("load", () => {
  const imgs = [...document.querySelectorAll("img")].map((im) => {
    const a = im.closest("a");
    const r = im.getBoundingClientRect();
    return {src: im.getAttribute("src"), width: r.width, natural: im.naturalWidth,
            complete: im.complete, href: a ? a.getAttribute("href") : null};
  });
  const pre = document.createElement("pre");
  pre.id = "screenshot-probe";
  const body = document.body.getBoundingClientRect();
  pre.textContent = JSON.stringify({
    height: Math.ceil(document.documentElement.scrollHeight),
    body: [Math.floor(body.left), Math.ceil(body.right)],
    width: document.documentElement.clientWidth, imgs: imgs});
  document.body.appendChild(pre);
});
</script>
"""


def _chromium() -> str | None:
    for name in ("chromium", "chromium-browser", "google-chrome", "chrome"):
        p = shutil.which(name)
        if p:
            return p
    return None


def _run(browser: str, args: list[str], timeout: float = 180.0) -> str:
    cmd = [browser, "--headless", "--disable-gpu", "--no-sandbox", "--hide-scrollbars",
           "--force-device-scale-factor=1", *args]  # fmt: skip
    r = subprocess.run(cmd, capture_output=True, text=True, timeout=timeout, check=False)
    if r.returncode != 0:
        raise RuntimeError(f"{' '.join(cmd[:2])} ... failed ({r.returncode}): {r.stderr[-500:]}")
    return r.stdout


def measure(browser: str, page: Path, width: int, tmp: Path) -> dict:
    """Measurements of the page rendered at ``width`` CSS px (see :data:`_PROBE`)."""
    src = page.read_text(encoding="utf-8")
    base = f"<base href='{page.parent.resolve().as_uri()}/'>"
    src = src.replace("<head>", "<head>" + base, 1).replace("</body>", _PROBE + "</body>", 1)
    probe = tmp / "probe.html"
    probe.write_text(src, encoding="utf-8")
    dom = _run(
        browser,
        [f"--window-size={width},1000", "--virtual-time-budget=20000", "--dump-dom",
         probe.as_uri()],
    )  # fmt: skip
    m = re.search(r'<pre id="screenshot-probe">(.*?)</pre>', dom, flags=re.S)
    if not m:
        raise RuntimeError("the page's measurements were not found in the dumped DOM")
    import html

    return json.loads(html.unescape(m.group(1)))


def check(meas: dict, report_dir: Path, min_px: float) -> list[str]:
    """Problems of the figures (empty when none)."""
    from bearingsim.plotting import MIN_FONT_PT
    from bearingsim.report.html import png_size

    out = []
    if not meas["imgs"]:
        out.append("the page has no figure")
    for im in meas["imgs"]:
        src = im["src"]
        if not im["complete"] or not im["natural"]:
            out.append(f"{src}: not loaded")
            continue
        if im["href"] != src:
            out.append(f"{src}: not wrapped in a link to its full-size image (href {im['href']})")
        size = png_size(report_dir / src)
        if size is None:
            out.append(f"{src}: not a PNG")
            continue
        px, _h, dpi = size
        per_inch = im["width"] / (px / dpi)  # CSS px per inch of figure
        font_px = MIN_FONT_PT / 72.0 * per_inch
        if font_px < min_px - 1e-6:
            out.append(
                f"{src}: shown {im['width']:.0f} px wide, its {MIN_FONT_PT:g} pt text is "
                f"{font_px:.1f} px < {min_px:g} px"
            )
    if meas["width"] and any(im["width"] > meas["width"] for im in meas["imgs"]):
        out.append("a figure is wider than the window")
    return out


def screenshots(
    browser: str, page: Path, width: int, height: int, out: Path, tile: int, body: list[int]
):
    """One screenshot of the whole page, cut into tiles of the body's width (the margins left
    out) and ``tile`` px height, at 1:1; returns the files written."""
    from PIL import Image

    full = out / "page_full.png"
    _run(browser, [f"--window-size={width},{height}", "--virtual-time-budget=20000",
                   f"--screenshot={full}", page.resolve().as_uri()])  # fmt: skip
    written = [full]
    with Image.open(full) as im:
        for k, top in enumerate(range(0, im.height, tile)):
            p = out / f"page_{k:02d}.png"
            left, right = max(0, body[0]), min(im.width, body[1])
            im.crop((left, top, right, min(top + tile, im.height))).save(p)
            written.append(p)
    return written


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("report", type=Path, help="report.html")
    ap.add_argument("-o", "--out", type=Path, default=Path("/tmp/figs_shots"))
    ap.add_argument("--width", type=int, default=1400, help="window width [CSS px]")
    ap.add_argument("--tile", type=int, default=900, help="tile height [px]")
    ap.add_argument("--min-px", type=float, default=9.0, help="smallest text on screen [px]")
    a = ap.parse_args(argv)
    browser = _chromium()
    if browser is None:
        print("chromium not found (Debian package 'chromium')", file=sys.stderr)
        return 2
    a.out.mkdir(parents=True, exist_ok=True)
    with tempfile.TemporaryDirectory() as tmp:
        meas = measure(browser, a.report, a.width, Path(tmp))
    problems = check(meas, a.report.parent, a.min_px)
    for old in a.out.glob("page_*.png"):
        old.unlink()
    files = screenshots(browser, a.report, a.width, meas["height"], a.out, a.tile, meas["body"])
    print(f"{len(meas['imgs'])} figures, page {meas['width']} x {meas['height']} px")
    for im in meas["imgs"]:
        print(f"  {im['src']}: shown {im['width']:.0f} px (PNG {im['natural']} px)")
    print("screenshots: " + ", ".join(str(f) for f in files))
    for p in problems:
        print("PROBLEM: " + p)
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
