"""Figure helpers (Agg backend, atomic PNG writes)."""

from __future__ import annotations

from pathlib import Path

import matplotlib

matplotlib.use("Agg")

from ..io.atomic import atomic_path  # noqa: E402

__all__ = [
    "save_figure",
]


def save_figure(fig, path: str | Path, dpi: int = 110) -> Path:
    """Save a Matplotlib figure as PNG atomically and close it; returns the path."""
    import matplotlib.pyplot as plt

    p = Path(path)
    with atomic_path(p, suffix=".png") as tmp:
        fig.savefig(tmp, dpi=dpi, bbox_inches="tight", format="png")
    plt.close(fig)
    return p
