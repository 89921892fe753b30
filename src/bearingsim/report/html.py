"""HTML rendering of the reproduction report (one self-contained page + PNG files beside it)."""

from __future__ import annotations

import html
import math
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


def _summary(sections) -> list[str]:
    """The counts per reference kind x status, then every mismatch with its size."""
    from . import REF_KINDS, STATUSES

    rows = [(s, r) for s in sections for r in s.rows]
    n = {(k, st): 0 for k in REF_KINDS for st in STATUSES}
    for _s, r in rows:
        n[(r.reference_kind, r.status)] += 1
    out = [
        "<h2>Summary</h2><table class='counts'><tr><th>reference</th>"
        + "".join(f"<th class='{st}'>{st}</th>" for st in STATUSES)
        + "<th>all</th></tr>"
    ]
    for k in REF_KINDS:
        cells = "".join(f"<td>{n[(k, st)] or '–'}</td>" for st in STATUSES)
        out.append(f"<tr><th>{k}</th>{cells}<td>{sum(n[(k, st)] for st in STATUSES)}</td></tr>")
    tot = "".join(f"<td>{sum(n[(k, st)] for k in REF_KINDS)}</td>" for st in STATUSES)
    out.append(f"<tr><th>all</th>{tot}<td>{len(rows)}</td></tr></table>")
    bad = [(s, r) for s, r in rows if r.status == "mismatch"]
    if bad:
        # measured first, then by size (largest miss first)
        def miss(r) -> float:
            return 0.0 if r.factor is None else abs(math.log(r.factor))

        bad.sort(key=lambda sr: (sr[1].reference_kind != "measured", -miss(sr[1])))
        out.append(
            f"<h3>Mismatches ({len(bad)})</h3><table><tr><th>section</th><th>quantity</th>"
            "<th>kind</th><th>reference</th><th>ours</th><th>size</th><th>note</th></tr>"
        )
        for s, r in bad:
            out.append(
                f"<tr class='mismatch'><td>{html.escape(s.name)}</td>"
                f"<td>{html.escape(r.quantity)}</td><td>{r.reference_kind}</td>"
                f"<td>{_fmt(r.published)}</td><td>{_fmt(r.ours)}</td>"
                f"<td>{html.escape(r.size) or '–'}</td><td>{html.escape(r.note)}</td></tr>"
            )
        out.append("</table>")
    return out


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


#: the terms the rows use, explained once at the top of the report (HTML list items)
GLOSSARY = "".join(
    f"<li><b>{html.escape(k)}</b>: {html.escape(v)}</li>"
    for k, v in (
        ("VSM, TVSM, DEM",
         "the ring models of seed VSM: a 2-DOF inner ring on the balls' Hertz contacts with "
         "a secant (variable-stiffness, VSM) or tangent (TVSM) stiffness, or the full "
         "nonlinear contact forces (dynamic equivalent model, DEM); docs/models.md"),
        ("rotor", "the bearing-rotor-housing model of the CWRU motor (seed ROTOR)"),
        ("rig", "a measurement chain: the transfer path's modes, background, tones and sensor "
         "noise between a model's output and the accelerometer, identified from records"),
        ("SES", "squared envelope spectrum: the spectrum of the squared envelope of the signal "
         "in a band, where a fault's repetition rate shows as lines"),
        ("S&R grade", "Smith & Randall (2015)'s diagnosability of a CWRU record: Y1/Y2 "
         "diagnosable (classic / non-classic symptoms), P1/P2 partially, N not"),
        ("development set", "the CWRU 0.014 in records, used to develop and calibrate the "
         "diagnosis; the 0.007 in records judge it"),
        ("mounting", "a faulty bearing as installed once on the CWRU rig (end, fault type, "
         "size, outer-race position; its 12 and 48 kHz records are one mounting). Leave one "
         "mounting out: the diagnosis's calibration is fitted without the record's mounting; "
         "the side-by-side's rig is identified from the same end's and rate's records of the "
         "other fault size"),
        ("kind", "what a row is compared with: measured (a record, a test), paper, standard, "
         "or none"),
    )
)  # fmt: skip


def write_html(path: Path, sections, quick: bool) -> None:
    """Write the report page."""
    css = (
        "body{font-family:sans-serif;max-width:1120px;margin:auto;padding:1em}"
        "table{border-collapse:collapse;width:100%;font-size:90%}"
        "td,th{border:1px solid #ccc;padding:3px 6px;text-align:left;vertical-align:top}"
        ".match{background:#e6f4e6}.deviates{background:#fff5d6}.mismatch{background:#fadada}"
        ".info{background:#f2f2f2}table.counts{width:auto}table.counts td{text-align:right}"
        "figure{display:inline-block;vertical-align:top;margin:0.6em 0.35em;max-width:100%;"
        "box-sizing:border-box}figure a{display:block}figure img{width:100%;height:auto;"
        "display:block;box-sizing:border-box;border:1px solid #eee}"
        "figcaption{font-size:90%;margin-top:0.3em}"
    )
    parts = [
        f"<!doctype html><html><head><meta charset='utf-8'><title>bearingsim reproduction report"
        f"</title><style>{css}</style></head><body>",
        f"<h1>bearingsim {__version__}: reproduction report</h1>",
        f"<p>Mode: {'quick' if quick else 'full'}. Every row compares ours with a reference of "
        "one kind: <b>measured</b> (a CWRU record, a fatigue test), <b>paper</b> (a number a "
        "paper, a textbook solution or a simulation's known input gives), <b>standard</b> (ISO, "
        "a catalogue, the CWRU bearing table) or <b>none</b>. Status: <b>match</b> (within the "
        "tolerance the source supports), <b>deviates</b> (outside it against a paper or a "
        "standard, for a quantitative reason that the named test verifies), <b>mismatch</b> "
        "(outside it; always so against a measurement, whatever the reason), <b>info</b> (no "
        "reference). See docs/validation.md.</p>",
    ]
    from . import STATUSES

    # a table of contents with each section's counts, anchors (report.html#signals) and the
    # terms the rows use (a helper's review, twenty-fifth session: a 48 000 px page without
    # either, and S&R grades, VSM/DEM/TVSM, SES, "mounting" never explained)
    toc = []
    for s in sections:
        c = {st: sum(r.status == st for r in s.rows) for st in STATUSES}
        counts = ", ".join(f"{c[st]} {st}" for st in STATUSES if c[st])
        toc.append(
            f"<li><a href='#{html.escape(s.name)}'>{html.escape(s.title)}</a>"
            f"{f' <small>({counts})</small>' if counts else ''}</li>"
        )
    parts.append("<h2>Sections</h2><ul>" + "".join(toc) + "</ul>")
    parts.append(f"<h3>Terms</h3><ul>{GLOSSARY}</ul>")
    parts += _summary(sections)
    for s in sections:
        parts.append(
            f"<h2 id='{html.escape(s.name)}'>{html.escape(s.title)}</h2><p><small>section run "
            f"time {s.wall_s:.1f} s</small></p>"
        )
        if s.text:
            parts.append(f"<p>{html.escape(s.text)}</p>")
        parts.append(
            "<table><tr><th>quantity</th><th>source</th><th>reference</th><th>ours</th>"
            "<th>difference</th><th>kind</th><th>status</th><th>note</th></tr>"
        )
        for r in s.rows:
            # a row judged against a bound of its own (the side-by-side's ratios) has no
            # rel_diff: its size (a factor, or dB) filled an empty column (twenty-fourth session)
            if r.rel_diff is None:
                rel = html.escape(r.size) or "–"
            else:
                rel = f"{100 * r.rel_diff:+.2f} %"
                if r.tolerance is not None:  # the bound it was judged by (a helper's review:
                    # identical offsets read match and mismatch with no tolerance shown)
                    rel += f"<br><small>tolerance ±{100 * r.tolerance:.3g} %</small>"
            status = r.status
            if r.verified_by:
                status += f"<br><small>verified by {html.escape(r.verified_by)}</small>"
            parts.append(
                f"<tr class='{r.status}'><td>{html.escape(r.quantity)}</td><td>"
                f"{html.escape(r.source)}</td><td>{_fmt(r.published)}</td><td>{_fmt(r.ours)}</td>"
                f"<td>{rel}</td><td>{r.reference_kind}</td><td>{status}</td>"
                f"<td>{html.escape(r.note)}</td></tr>"
            )
        parts.append("</table>")
        for fname, cap in s.figures:
            parts.append(figure_html(path.parent, fname, cap))
    parts.append("</body></html>")
    with atomic_open(path, "w", encoding="utf-8") as fh:
        fh.write("\n".join(parts))
