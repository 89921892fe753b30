"""HTML rendering of the reproduction report (one self-contained page + PNG files beside it)."""

from __future__ import annotations

import html
import struct
from pathlib import Path

from .._version import __version__
from ..io.atomic import atomic_open
from ..plotting import CSS_PX_PER_IN
from .figures import DPI

__all__ = [
    "write_html",
]


def _fmt(v) -> str:
    if v is None:
        return "–"
    if isinstance(v, float):
        return f"{v:.6g}"
    return html.escape(str(v))


def png_size(path: Path) -> tuple[int, int, float] | None:
    """Width and height [px] and resolution [dots/in] of a PNG (its ``pHYs`` chunk, else
    :data:`~.figures.DPI`); None when the file is missing or not a PNG."""
    try:
        data = path.read_bytes()
    except OSError:
        return None
    if data[:8] != b"\x89PNG\r\n\x1a\n" or data[12:16] != b"IHDR":
        return None
    w, h = struct.unpack(">II", data[16:24])
    dpi = float(DPI)
    pos = 8
    while pos + 8 <= len(data):
        n, kind = struct.unpack(">I4s", data[pos : pos + 8])
        if kind == b"pHYs" and n == 9:
            ppu, _ppu_y, unit = struct.unpack(">IIB", data[pos + 8 : pos + 17])
            if unit == 1 and ppu > 0:  # pixels per metre
                dpi = ppu * 0.0254
            break
        if kind in (b"IDAT", b"IEND"):
            break
        pos += 12 + n
    return w, h, dpi


def figure_html(out_dir: Path, fname: str, caption: str) -> str:
    """One figure: the PNG shown at :data:`~bearingsim.plotting.CSS_PX_PER_IN` CSS px per inch of
    figure (so its text is as large on screen as the figure standard plans), linked to the
    full-size image, with its caption."""
    src, cap = html.escape(fname), html.escape(caption)
    size = png_size(out_dir / fname)
    if size is None:
        style = ""
    else:
        w, _h, dpi = size
        css_w = round(w * CSS_PX_PER_IN / dpi)
        style = f" style='width:{css_w}px'"
    return (
        f"<figure{style}><a href='{src}' title='open the full-size image'>"
        f"<img src='{src}' alt='{cap}'></a><figcaption>{cap}</figcaption></figure>"
    )


def write_html(path: Path, sections, quick: bool) -> None:
    """Write the report page."""
    css = (
        "body{font-family:sans-serif;max-width:1120px;margin:auto;padding:1em}"
        "table{border-collapse:collapse;width:100%;font-size:90%}"
        "td,th{border:1px solid #ccc;padding:3px 6px;text-align:left;vertical-align:top}"
        ".match{background:#e6f4e6}.explained{background:#fff5d6}.mismatch{background:#fadada}"
        "figure{display:inline-block;vertical-align:top;margin:0.6em 0.35em;max-width:100%;"
        "box-sizing:border-box}figure a{display:block}figure img{width:100%;height:auto;"
        "display:block;box-sizing:border-box;border:1px solid #eee}"
        "figcaption{font-size:90%;margin-top:0.3em}"
    )
    parts = [
        f"<!doctype html><html><head><meta charset='utf-8'><title>bearingsim reproduction report"
        f"</title><style>{css}</style></head><body>",
        f"<h1>bearingsim {__version__}: reproduction report</h1>",
        f"<p>Mode: {'quick' if quick else 'full'}. Every row: the published value, ours, the "
        "relative difference and a status (match within the stated tolerance; explained = differs "
        "for a documented reason, see docs/validation.md; mismatch).</p>",
    ]
    counts: dict[str, int] = {}
    for s in sections:
        for r in s.rows:
            counts[r.status] = counts.get(r.status, 0) + 1
    parts.append("<p>" + ", ".join(f"{k}: {v}" for k, v in sorted(counts.items())) + "</p>")
    for s in sections:
        parts.append(f"<h2>{html.escape(s.title)}</h2><p><small>{s.wall_s:.1f} s</small></p>")
        if s.text:
            parts.append(f"<p>{html.escape(s.text)}</p>")
        parts.append(
            "<table><tr><th>quantity</th><th>source</th><th>published</th><th>ours</th>"
            "<th>rel. diff</th><th>status</th><th>note</th></tr>"
        )
        for r in s.rows:
            rel = "–" if r.rel_diff is None else f"{100 * r.rel_diff:+.2f} %"
            parts.append(
                f"<tr class='{r.status}'><td>{html.escape(r.quantity)}</td><td>"
                f"{html.escape(r.source)}</td><td>{_fmt(r.published)}</td><td>{_fmt(r.ours)}</td>"
                f"<td>{rel}</td><td>{r.status}</td><td>{html.escape(r.note)}</td></tr>"
            )
        parts.append("</table>")
        for fname, cap in s.figures:
            parts.append(figure_html(path.parent, fname, cap))
    parts.append("</body></html>")
    with atomic_open(path, "w", encoding="utf-8") as fh:
        fh.write("\n".join(parts))
