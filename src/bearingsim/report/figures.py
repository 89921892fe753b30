"""Figure helpers of the report: the package's figure standard (:mod:`bearingsim.plotting`:
sizes, fonts, constrained layout, units) and atomic PNG writes (Agg backend).

Every section draws with :func:`new_figure` (or a result's ``plot_*`` method, which uses it too)
and saves with :func:`save_figure`; the page (:mod:`.html`) shows each PNG at
:data:`~bearingsim.plotting.CSS_PX_PER_IN` CSS pixels per inch of figure, which keeps every text
at 9 px or more on screen, and links it to the full-size image.
"""

from __future__ import annotations

import os
from pathlib import Path

import matplotlib

matplotlib.use("Agg")

from ..io.atomic import atomic_path  # noqa: E402
from ..plotting import (  # noqa: E402
    ACC,
    FULL_WIDTH,
    G0,
    HALF_WIDTH,
    figure_problems,
    label_points,
    log_if_wide,
    mark_lines,
    new_figure,
)

__all__ = [
    "ACC",
    "DPI",
    "FULL_WIDTH",
    "G0",
    "HALF_WIDTH",
    "label_points",
    "log_if_wide",
    "mark_lines",
    "new_figure",
    "save_figure",
    "STRICT_ENV",
]

#: resolution of the saved PNGs [dots/in]: a page-wide figure is 1650 px wide, 1.6 x the
#: 1056 CSS px it is shown at (sharp on high-density screens; the link shows it at full size)
DPI = 150
#: environment variable: ``1`` makes :func:`save_figure` refuse a figure that breaks the
#: standard (the test suite sets it, so every report section run by a test is checked)
STRICT_ENV = "BEARINGSIM_STRICT_FIGURES"


def save_figure(fig, path: str | Path, dpi: int = DPI) -> Path:
    """Save a Matplotlib figure atomically and close it; returns the path. The format follows
    the suffix: PDF for ``.pdf``, SVG for ``.svg``, JPEG for ``.jpg``/``.jpeg`` (Pillow,
    Matplotlib's own dependency), PNG otherwise.

    With ``$BEARINGSIM_STRICT_FIGURES=1`` a figure that breaks the figure standard
    (:func:`bearingsim.plotting.figure_problems`) raises ``ValueError`` naming the file and the
    problems, and is not written."""
    import matplotlib.pyplot as plt

    p = Path(path)
    if os.environ.get(STRICT_ENV) == "1":
        problems = figure_problems(fig)
        if problems:
            plt.close(fig)
            raise ValueError(f"figure {p.name} breaks the figure standard: " + "; ".join(problems))
    fmt = p.suffix.lower().lstrip(".")
    fmt = {"jpg": "jpeg"}.get(fmt, fmt)
    fmt = fmt if fmt in ("pdf", "svg", "jpeg") else "png"  # the CLI allows these suffixes only
    with atomic_path(p, suffix=f".{fmt}") as tmp:
        fig.savefig(tmp, dpi=dpi, bbox_inches="tight", pad_inches=0.04, format=fmt)
    plt.close(fig)
    return p
