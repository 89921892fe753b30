"""HTML rendering of the reproduction report (one self-contained page + PNG files beside it)."""

from __future__ import annotations

import html
from pathlib import Path

from .._version import __version__
from ..io.atomic import atomic_open

__all__ = [
    "write_html",
]


def _fmt(v) -> str:
    if v is None:
        return "–"
    if isinstance(v, float):
        return f"{v:.6g}"
    return html.escape(str(v))


def write_html(path: Path, sections, quick: bool) -> None:
    """Write the report page."""
    css = (
        "body{font-family:sans-serif;max-width:1100px;margin:auto;padding:1em}"
        "table{border-collapse:collapse;width:100%;font-size:90%}"
        "td,th{border:1px solid #ccc;padding:3px 6px;text-align:left;vertical-align:top}"
        ".match{background:#e6f4e6}.explained{background:#fff5d6}.mismatch{background:#fadada}"
        "figure{display:inline-block;margin:0.5em;max-width:48%}figure img{max-width:100%}"
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
            parts.append(
                f"<figure><img src='{html.escape(fname)}' alt='{html.escape(cap)}'>"
                f"<figcaption>{html.escape(cap)}</figcaption></figure>"
            )
    parts.append("</body></html>")
    with atomic_open(path, "w", encoding="utf-8") as fh:
        fh.write("\n".join(parts))
