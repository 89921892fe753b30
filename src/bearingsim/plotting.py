"""One figure standard for every plot of the package (issue 15): the report's figures and the
results' ``plot_*`` methods.

The standard, and why:

- **Size and text.** A figure is :data:`FULL_WIDTH` (page width) or :data:`HALF_WIDTH` (two per
  row) wide. The report shows every figure at :data:`CSS_PX_PER_IN` CSS pixels per inch of figure,
  so a font of ``s`` points is ``s * 96 / 72`` pixels on screen: the smallest font used,
  :data:`MIN_FONT_PT`, is 9.3 px.
- **Layout.** Constrained layout (``layout="constrained"``): labels, titles, legends and colour
  bars are placed inside the figure, nothing is clipped.
- **Axes.** Every axis that shows numbers has a quantity and a unit in brackets
  (``"envelope amplitude [m/s²]"``); a frequency band goes in the title, never as an axis label.
  Acceleration in m/s² (``g`` records converted with :data:`G0`), lengths in µm or mm. A value axis
  on which the plotted values span more than :data:`LOG_RATIO` is logarithmic
  (:func:`log_if_wide`).
- **Markers.** Harmonic markers carry their meaning in the legend; their text labels never
  overlap (:func:`mark_lines`, :func:`label_points`).

:func:`figure_problems` checks a drawn figure against the parts of this standard a program can
check; the tests run it on every ``plot_*`` method.

Matplotlib is imported inside the functions (the package imports without it being loaded).
"""

from __future__ import annotations

import math
from collections.abc import Iterable, Sequence
from typing import Any

import numpy as np

__all__ = [
    "ACC",
    "ANNOTATION_PT",
    "FONT_PT",
    "SMALL_PT",
    "CSS_PX_PER_IN",
    "FULL_WIDTH",
    "G0",
    "HALF_WIDTH",
    "LOG_RATIO",
    "MIN_FONT_PT",
    "figure_problems",
    "label_points",
    "legend_outside",
    "log_if_wide",
    "mark_lines",
    "new_figure",
    "unit_text",
]

#: width of a page-wide figure [in] (1056 CSS px in the report)
FULL_WIDTH = 11.0
#: width of a figure shown two per row [in] (509 CSS px)
HALF_WIDTH = 5.3
#: CSS pixels per inch of figure at which the report shows every figure [px/in]
CSS_PX_PER_IN = 96.0
#: body text of a figure (axis labels, titles) [pt] (13.3 px in the report)
FONT_PT = 10.0
#: tick labels and legends [pt] (12 px)
SMALL_PT = 9.0
#: text labels on data (peaks, harmonics) [pt] (10.7 px)
ANNOTATION_PT = 8.0
#: smallest font any figure may use [pt] (9.3 px in the report)
MIN_FONT_PT = 7.0
#: a value axis spanning more than this ratio is logarithmic [-]
LOG_RATIO = 20.0
#: standard acceleration of gravity: ``g`` records are converted to m/s² with it [m/s^2]
G0 = 9.80665
#: the acceleration unit of every figure
ACC = "m/s²"

#: Matplotlib settings of the standard (applied while a figure is created)
STYLE: dict[str, Any] = {
    "font.size": FONT_PT,
    "axes.titlesize": FONT_PT,
    "axes.labelsize": FONT_PT,
    "xtick.labelsize": SMALL_PT,
    "ytick.labelsize": SMALL_PT,
    "legend.fontsize": SMALL_PT,
    "figure.titlesize": FONT_PT + 1.0,
    "lines.linewidth": 0.9,
    "axes.formatter.limits": (-3, 4),
    "axes.formatter.use_mathtext": True,
}

_UNIT_TEXT = {"m/s^2": "m/s²", "m/s2": "m/s²", "um": "µm", "us": "µs", "1": "-"}


def unit_text(unit: str) -> str:
    """The unit as figures write it: ``"m/s^2"`` -> ``"m/s²"``, ``"um"`` -> ``"µm"``."""
    return _UNIT_TEXT.get(unit.strip(), unit.strip())


def new_figure(
    nrows: int = 1,
    ncols: int = 1,
    *,
    width: float | None = None,
    height: float | None = None,
    row_height: float = 2.4,
    polar: bool = False,
    **subplots_kw,
):
    """A figure of the standard with its axes: ``(fig, ax)`` for one axes, else ``(fig, axs)``
    (an array, as :meth:`matplotlib.figure.Figure.subplots` returns it).

    Parameters
    ----------
    nrows, ncols : int
        Grid of axes [-].
    width : float, optional
        Figure width [in]; default :data:`FULL_WIDTH` for several axes, :data:`HALF_WIDTH` for
        one.
    height : float, optional
        Figure height [in]; default ``row_height * nrows + 0.6`` (at least 3.2).
    row_height : float
        Height per row of axes for the default height [in].
    polar : bool
        Polar axes.
    **subplots_kw
        Passed to :meth:`~matplotlib.figure.Figure.subplots` (``sharex``, ``squeeze``...).
    """
    import matplotlib as mpl
    import matplotlib.pyplot as plt

    if width is None:
        width = FULL_WIDTH if nrows * ncols > 1 else HALF_WIDTH
    if height is None:
        height = max(3.2, row_height * nrows + 0.6)
    if polar:
        subplots_kw.setdefault("subplot_kw", {})["projection"] = "polar"
    with mpl.rc_context(STYLE):
        fig = plt.figure(figsize=(width, height), layout="constrained")
        axs = fig.subplots(nrows, ncols, **subplots_kw)
        for ax in np.atleast_1d(axs).ravel():
            ax.tick_params(labelsize=SMALL_PT)
    return fig, axs


def log_if_wide(ax, values: Iterable[float], axis: str = "y", ratio: float = LOG_RATIO) -> bool:
    """Make the ``axis`` ("x" or "y") of ``ax`` logarithmic when the positive finite ``values``
    span more than ``ratio``; returns whether it did."""
    v = np.asarray(list(values), dtype=float).ravel()
    v = v[np.isfinite(v) & (v > 0)]
    if v.size < 2 or v.max() / v.min() <= ratio:
        return False
    (ax.set_yscale if axis == "y" else ax.set_xscale)("log")
    return True


def mark_lines(
    ax,
    positions: Sequence[float],
    label: str | None = None,
    *,
    color: str = "tab:red",
    ls: str = ":",
    texts: Sequence[str] | None = None,
    max_texts: int = 4,
    lw: float = 0.9,
) -> None:
    """Vertical lines at ``positions`` (harmonics of a characteristic frequency); one legend
    entry ``label`` for all of them and, optionally, short ``texts`` ("1×", "2×"...) at the top
    of the axes for the first ``max_texts`` lines, skipping any that would overlap the previous
    one."""
    tr = ax.get_xaxis_transform()
    for i, x in enumerate(positions):
        ax.axvline(x, color=color, ls=ls, lw=lw, label=label if i == 0 else None, zorder=1)
    if not texts:
        return
    xmin, xmax = ax.get_xlim()
    span = (xmax - xmin) or 1.0
    last = -math.inf
    for x, t in list(zip(positions, texts, strict=False))[:max_texts]:
        fx = (x - xmin) / span
        if not 0.0 <= fx <= 1.0 or fx - last < 0.04:
            continue
        ax.annotate(t, (x, 1.0), xycoords=tr, xytext=(2, -2), textcoords="offset points",
                    ha="left", va="top", fontsize=ANNOTATION_PT, color=color)  # fmt: skip
        last = fx


def label_points(
    ax,
    x: Sequence[float],
    y: Sequence[float],
    texts: Sequence[str],
    *,
    color: str | Sequence[str] = "k",
    marker: str | None = "v",
    transform=None,
    min_sep: float = 0.06,
    fontsize: float = ANNOTATION_PT,
) -> int:
    """Mark points and write ``texts`` above them without overlaps: points are taken in the order
    given (put the important ones first); a text closer than ``min_sep`` (fraction of the axes
    width) to one already written is left out (its marker stays). Returns the number written.

    ``transform``: that of ``x, y`` (default data coordinates); ``color``: one for all or one per
    point."""
    tr = transform or ax.transData
    xmin, xmax = ax.get_xlim()
    span = (xmax - xmin) or 1.0
    placed: list[float] = []
    n = 0
    colors = [color] * len(texts) if isinstance(color, str) else list(color)
    for xi, yi, t, color in zip(x, y, texts, colors, strict=True):
        if marker is not None:
            ax.plot([xi], [yi], marker, color=color, ms=5, transform=tr)
        fx = (xi - xmin) / span if ax.get_xscale() == "linear" else None
        if fx is not None and any(abs(fx - p) < min_sep for p in placed):
            continue
        if fx is not None and not 0.0 <= fx <= 1.0:
            continue
        ax.annotate(
            t,
            (xi, yi),
            xycoords=tr,
            xytext=(0, 4),
            textcoords="offset points",
            ha="center",
            va="bottom",
            fontsize=fontsize,
            color=color,
            annotation_clip=False,
        )
        if fx is not None:
            placed.append(fx)
        n += 1
    return n


def legend_outside(ax, **kw):
    """The legend of ``ax`` to the right of the axes, top aligned (constrained layout makes room
    for it): it never covers data or labels."""
    return ax.legend(loc="upper left", bbox_to_anchor=(1.01, 1.0), borderaxespad=0.0, **kw)


def _overlap(a, b, tol: float = 1.0) -> bool:
    """Two window boxes overlap by more than ``tol`` pixels both ways."""
    return min(a.x1, b.x1) - max(a.x0, b.x0) > tol and min(a.y1, b.y1) - max(a.y0, b.y0) > tol


def _same_box(a, b, tol: float = 1.0) -> bool:
    return all(abs(u - v) <= tol for u, v in zip(a.extents, b.extents, strict=True))


def _axes_name(ax) -> str:
    if _is_colorbar(ax):
        return "colour bar " + (ax.get_ylabel() or ax.get_xlabel())
    return ax.get_title() or ax.get_ylabel() or ax.get_xlabel() or "(unnamed)"


def _is_colorbar(ax) -> bool:
    return hasattr(ax, "_colorbar") or ax.get_label() == "<colorbar>"


def _has_unit(text: str) -> bool:
    return "[" in text and text.rstrip().endswith("]") and text.rfind("[") < text.rfind("]") - 1


def _visible_ticklabels(axis, renderer=None) -> list:
    """Tick labels drawn (visible, non-empty, inside the axes' extent along the axis)."""
    if not axis.get_visible():
        return []
    out = [t for t in axis.get_ticklabels() if t.get_visible() and t.get_text()]
    if renderer is None:
        return out
    ab = axis.axes.get_window_extent(renderer)
    lo, hi = (ab.x0, ab.x1) if axis.axis_name == "x" else (ab.y0, ab.y1)
    keep = []
    for t in out:
        bb = t.get_window_extent(renderer)
        c = 0.5 * (bb.x0 + bb.x1) if axis.axis_name == "x" else 0.5 * (bb.y0 + bb.y1)
        if lo - 1 <= c <= hi + 1:
            keep.append(t)
    return keep


def figure_problems(fig) -> list[str]:
    """What breaks the standard in ``fig`` (drawn here with Agg), as readable strings; empty when
    none.

    Checked: constrained layout; width at most :data:`FULL_WIDTH`; every text at least
    :data:`MIN_FONT_PT`; every axis that shows tick labels has a label ending in a unit in
    brackets (a polar plot's angle axis and colour bars are exempt; a colour bar needs its own
    label); the tick labels of an axis do not overlap; no text sticks out of the figure; no two
    texts overlap (titles, axis and tick labels, legends, labels on the data, figure texts).
    """
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.layout_engine import ConstrainedLayoutEngine
    from matplotlib.text import Text

    out: list[str] = []
    if fig.axes and not isinstance(fig.get_layout_engine(), ConstrainedLayoutEngine):
        out.append("layout is not constrained")
    w, _h = fig.get_size_inches()
    if w > FULL_WIDTH + 1e-9:
        out.append(f"width {w:.2f} in > {FULL_WIDTH} in")
    if not isinstance(fig.canvas, FigureCanvasAgg):
        FigureCanvasAgg(fig)
    fig.canvas.draw()
    r = fig.canvas.get_renderer()
    fb = fig.bbox
    for ax in fig.axes:
        name = ax.get_title() or ax.get_ylabel() or f"axes {fig.axes.index(ax)}"
        if _is_colorbar(ax):
            lab = ax.get_ylabel() or ax.get_xlabel()
            if not _has_unit(lab):
                out.append(f"colour bar of {name!r}: label {lab!r} has no [unit]")
            continue
        polar = ax.name == "polar"
        for which, axis, label in (
            ("x", ax.xaxis, ax.get_xlabel()),
            ("y", ax.yaxis, ax.get_ylabel()),
        ):
            if polar and which == "x":
                continue
            if _visible_ticklabels(axis, r) and not _has_unit(label):
                out.append(f"{name!r}: {which} label {label!r} has no quantity [unit]")
        for which, axis in (("x", ax.xaxis), ("y", ax.yaxis)):
            boxes = [t.get_window_extent(r) for t in _visible_ticklabels(axis, r)]
            if any(_overlap(a, b) for a, b in zip(boxes, boxes[1:], strict=False)):
                out.append(f"{name!r}: {which} tick labels overlap")
    # every other pair of texts: titles, axis labels, tick labels of different axes, legends,
    # texts on the data, figure-level texts and legends
    items = []
    for i, ax in enumerate(fig.axes):
        texts = [("title", t) for t in (ax.title, ax._left_title, ax._right_title)]
        texts += [("axis label", ax.xaxis.label), ("axis label", ax.yaxis.label)]
        texts += [("text", t) for t in ax.texts]
        for axis in (ax.xaxis, ax.yaxis):
            texts += [("tick", t) for t in _visible_ticklabels(axis, r)]
        for kind, t in texts:
            if t.get_visible() and t.get_text().strip():
                items.append((i, kind, t.get_text(), t.get_window_extent(r)))
        leg = ax.get_legend()
        if leg is not None and leg.get_visible():
            items.append((i, "legend", "legend", leg.get_window_extent(r)))
    for t in {
        id(t): t for t in (fig._suptitle, fig._supxlabel, fig._supylabel, *fig.texts)
    }.values():
        if t is not None and t.get_visible() and t.get_text().strip():
            items.append((-1, "text", t.get_text(), t.get_window_extent(r)))
    items += [(-1, "legend", "figure legend", leg.get_window_extent(r)) for leg in fig.legends]
    for k, (ia, ka, ta, a) in enumerate(items):
        for ib, kb, tb, b in items[k + 1 :]:
            if ia == ib and ka == kb == "tick":
                continue  # the same axes' tick labels: checked above
            if _overlap(a, b):
                out.append(f"{ta!r} overlaps {tb!r}")
    # texts of one axes (or of the figure) over the plotting area of another (twins excepted)
    areas = [ax.get_window_extent(r) for ax in fig.axes]
    for ia, _ka, ta, a in items:
        for j, b in enumerate(areas):
            if j == ia or (ia >= 0 and _same_box(areas[ia], b)):
                continue
            if _overlap(a, b):
                out.append(f"{ta!r} overlaps the axes {_axes_name(fig.axes[j])!r}")
    ticks: set[int] = set()  # tick labels: only those drawn (inside the axes' span) count
    drawn: list = []
    for ax in fig.axes:
        for axis in (ax.xaxis, ax.yaxis):
            for tk in axis.get_major_ticks() + axis.get_minor_ticks():
                ticks |= {id(tk.label1), id(tk.label2)}
            drawn += _visible_ticklabels(axis, r)
            drawn += [
                t for t in axis.get_ticklabels(minor=True) if t.get_visible() and t.get_text()
            ]
    for t in [t for t in fig.findobj(Text) if id(t) not in ticks] + drawn:
        if not t.get_visible() or not t.get_text().strip():
            continue
        if t.get_fontsize() < MIN_FONT_PT - 1e-9:
            out.append(f"text {t.get_text()!r}: {t.get_fontsize():.1f} pt < {MIN_FONT_PT} pt")
        bb = t.get_window_extent(r)
        if bb.width == 0:
            continue
        if bb.x0 < fb.x0 - 1 or bb.x1 > fb.x1 + 1 or bb.y0 < fb.y0 - 1 or bb.y1 > fb.y1 + 1:
            out.append(f"text {t.get_text()!r} sticks out of the figure")
    return sorted(set(out))
