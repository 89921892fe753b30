"""The reproduction report: published numbers beside ours, with figures.

Each section (``report/sections/<name>.py``, one per seed paper: foundation, vsm, qs5, ias, life,
rotor) exposes ``TITLE`` and ``run(ctx) -> Section``. The report writes ``results.json`` (list of
rows), the PNG figures and ``report.html``; the published numbers it compares with are data
(:mod:`.published`, ``published.toml``).

May import every layer below it (the model families, simulation, signal, io); only the CLI
imports it.
"""

from __future__ import annotations

import importlib
import math
import pkgutil
import time
from dataclasses import asdict, dataclass, field
from pathlib import Path
from typing import Literal

from ..io.atomic import check_output, write_json

__all__ = [
    "compare",
    "Context",
    "Row",
    "run_report",
    "Section",
    "SECTIONS",
    "Status",
]

Status = Literal["match", "explained", "mismatch"]

#: preferred order of the report sections; any other module in ``report/sections`` follows
_ORDER = ["foundation", "vsm", "qs5", "ias", "life", "rotor", "sweep"]
#: the sections present (modules in ``report/sections``), in report order
SECTIONS = sorted(
    (m.name for m in pkgutil.iter_modules([str(Path(__file__).parent / "sections")])),
    key=lambda n: (_ORDER.index(n) if n in _ORDER else len(_ORDER), n),
)


@dataclass
class Row:
    """One published-vs-ours comparison.

    ``published`` and ``ours`` in the unit named in ``quantity``; ``rel_diff`` is
    ``(ours - published)/|published|``; ``status``: ``match`` (within ``tolerance``), ``explained``
    (differs for a documented reason, see ``note``), ``mismatch``.
    """

    quantity: str
    source: str
    published: float | str | None
    ours: float | str | None
    rel_diff: float | None = None
    status: Status = "match"
    note: str = ""
    tolerance: float | None = None


def compare(
    quantity: str,
    source: str,
    published: float,
    ours: float,
    tolerance: float,
    explanation: str = "",
) -> Row:
    """Row comparing two numbers; ``match`` within ``tolerance`` (relative), otherwise
    ``explained`` when an explanation is given, else ``mismatch``."""
    rel = (ours - published) / abs(published) if published else math.nan
    ok = abs(rel) <= tolerance
    status: Status = "match" if ok else ("explained" if explanation else "mismatch")
    return Row(
        quantity, source, published, ours, rel, status, explanation if not ok else "", tolerance
    )


@dataclass
class Section:
    """A report section: rows, figures (file names in the output dir) and free text."""

    name: str
    title: str
    rows: list[Row] = field(default_factory=list)
    figures: list[tuple[str, str]] = field(default_factory=list)  # (file name, caption)
    text: str = ""
    wall_s: float = 0.0


@dataclass
class Context:
    """What a section gets: the output directory and whether to run the quick variant."""

    out_dir: Path
    quick: bool = True


def run_report(
    out_dir: str | Path,
    quick: bool = True,
    sections: list[str] | None = None,
    progress: bool = True,
) -> list[Section]:
    """Run the report sections, write ``results.json``, figures and ``report.html``.

    Parameters
    ----------
    out_dir : path
        Output directory (created).
    quick : bool
        Reduced-size variants of long computations.
    sections : list of str, optional
        Subset of :data:`SECTIONS`.
    progress : bool
        Show a progress bar on stderr.
    """
    from tqdm import tqdm

    from .html import write_html

    out = check_output(out_dir, "out_dir", directory=True)  # before any section runs
    out.mkdir(parents=True, exist_ok=True)
    names = sections or SECTIONS
    ctx = Context(out, quick)
    done: list[Section] = []
    bar = tqdm(names, desc="reproduce", unit="section", disable=not progress, leave=False)
    for name in bar:
        bar.set_postfix_str(name)
        mod = importlib.import_module(f"{__name__}.sections.{name}")
        t0 = time.perf_counter()
        sec = mod.run(ctx)
        sec.wall_s = time.perf_counter() - t0
        done.append(sec)
    rows = []
    for sec in done:
        for r in sec.rows:
            d = asdict(r)
            d["section"] = sec.name
            rows.append(d)
    write_json(out / "results.json", rows)
    write_html(out / "report.html", done, quick)
    return done
