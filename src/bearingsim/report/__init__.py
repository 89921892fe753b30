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
    "info",
    "judge",
    "kind_of",
    "REF_KINDS",
    "RefKind",
    "Row",
    "run_report",
    "Section",
    "SECTIONS",
    "Status",
    "STATUSES",
]

Status = Literal["match", "deviates", "mismatch", "info"]
RefKind = Literal["paper", "measured", "standard", "none"]
#: the statuses, in the order the report lists them
STATUSES: tuple[str, ...] = ("mismatch", "deviates", "match", "info")
#: the reference kinds, in the order the report lists them
REF_KINDS: tuple[str, ...] = ("measured", "paper", "standard", "none")

#: preferred order of the report sections; any other module in ``report/sections`` follows
_ORDER = ["foundation", "vsm", "qs5", "ias", "life", "rotor", "signals", "diagnosis", "sweep"]
#: the sections present (modules in ``report/sections``), in report order
SECTIONS = sorted(
    (m.name for m in pkgutil.iter_modules([str(Path(__file__).parent / "sections")])),
    key=lambda n: (_ORDER.index(n) if n in _ORDER else len(_ORDER), n),
)


@dataclass
class Row:
    """One reference-vs-ours comparison.

    ``published`` and ``ours`` in the unit named in ``quantity``; ``rel_diff`` is
    ``(ours - published)/|published|``.

    ``reference_kind`` says what ``published`` is: ``paper`` (a number a paper computed with its
    model), ``measured`` (a measurement: a CWRU record, a fatigue test), ``standard`` (ISO, a
    catalogue, the CWRU bearing table) or ``none`` (no reference: ``published`` is ``None``).

    ``status``: ``match`` (within ``tolerance``, the tolerance the source supports),
    ``deviates`` (outside it against a ``paper`` or ``standard`` reference, with a quantitative
    reason in ``note`` that the test named in ``verified_by`` checks), ``mismatch`` (outside the
    tolerance: always so against a ``measured`` reference, whatever the reason; the note stays)
    or ``info`` (no reference). The combinations are checked on construction: a row that breaks
    them raises :class:`ValueError` (a report bug, not a user error).
    """

    quantity: str
    source: str
    published: float | str | None
    ours: float | str | None
    rel_diff: float | None = None
    status: Status = "match"
    note: str = ""
    tolerance: float | None = None
    reference_kind: RefKind = field(kw_only=True)
    verified_by: str = field(default="", kw_only=True)
    #: ``published`` and ``ours`` are levels in dB (20 log10 of an amplitude ratio): their
    #: difference is the size, and :attr:`factor` the amplitude ratio it stands for
    db_level: bool = field(default=False, kw_only=True)

    def __post_init__(self) -> None:
        if self.status not in STATUSES:
            raise ValueError(f"row {self.quantity!r}: status {self.status!r} not in {STATUSES}")
        if self.reference_kind not in REF_KINDS:
            raise ValueError(
                f"row {self.quantity!r}: reference_kind {self.reference_kind!r} not in {REF_KINDS}"
            )
        no_ref = self.reference_kind == "none"
        if no_ref != (self.status == "info"):
            raise ValueError(
                f"row {self.quantity!r}: status 'info' goes with reference_kind 'none' and only "
                f"with it (got {self.status!r}, {self.reference_kind!r})"
            )
        if no_ref and self.published is not None:
            raise ValueError(f"row {self.quantity!r}: reference_kind 'none' with a published value")
        if self.status == "deviates":
            if self.reference_kind == "measured":
                raise ValueError(
                    f"row {self.quantity!r}: a miss against a measurement is a mismatch, "
                    "never 'deviates'"
                )
            if not (self.verified_by and self.note):
                raise ValueError(
                    f"row {self.quantity!r}: 'deviates' needs a reason (note) and the test "
                    "that verifies it (verified_by)"
                )
        if self.verified_by and self.status != "deviates":
            # a verified reason is only carried by a deviating row
            self.verified_by = ""

    @property
    def factor(self) -> float | None:
        """``ours / published`` when both are non-zero finite numbers of the same sign [-]; for
        levels in dB (:attr:`db_level`) the amplitude ratio ``10^((ours - published)/20)``."""
        p, o = self.published, self.ours
        if isinstance(p, bool) or isinstance(o, bool):
            return None
        if not (isinstance(p, int | float) and isinstance(o, int | float)):
            return None
        if self.db_level:
            d = o - p
            return 10.0 ** (d / 20.0) if math.isfinite(d) else None
        if not (p and o and math.isfinite(p) and math.isfinite(o)) or (p > 0) != (o > 0):
            return None
        return o / p

    @property
    def size(self) -> str:
        """How far ``ours`` is from ``published``: ``"58.1× low (-35.3 dB)"``, in per cent
        within 10 % (``"+0.39 %"``), or for levels in dB (:attr:`db_level`) their difference
        (``"+34.1 dB"``); ``""`` when :attr:`factor` is undefined. (A helper's review of the
        report, twenty-fifth session: a prominence of 3.7 against 37.8 dB read "50.5× high",
        and a frequency 0.4 % off carried "(+0.03 dB)".)"""
        r = self.factor
        if r is None:
            return ""
        db = 20.0 * math.log10(r)
        if self.db_level:
            return f"{db:+.1f} dB"
        if 1 / 1.1 < r < 1.1:  # a small miss reads better in per cent
            return f"{100 * (r - 1):+.2g} %"
        word = f"{r:.3g}× high" if r >= 1 else f"{1 / r:.3g}× low"
        return f"{word} ({db:+.1f} dB)"


def kind_of(eid: str) -> RefKind:
    """The reference kind of the ``published.toml`` entry ``eid``."""
    from .published import entry

    return entry(eid).kind.value  # type: ignore[return-value]


def info(quantity: str, source: str, ours: float | str | None, note: str = "") -> Row:
    """A row without a reference (status ``info``): a result of ours shown for context."""
    return Row(quantity, source, None, ours, None, "info", note, None, reference_kind="none")


def _judged(
    quantity: str,
    source: str,
    published: float | str,
    ours: float | str,
    rel: float | None,
    ok: bool,
    note: str,
    tolerance: float | None,
    kind: RefKind,
    verified_by: str,
    db_level: bool = False,
) -> Row:
    """The row of a comparison whose outcome ``ok`` is known: the status rules in one place."""
    if kind == "none":
        raise ValueError(f"row {quantity!r}: a comparison needs a reference; use info()")
    deviates = kind != "measured" and bool(note) and bool(verified_by)
    status: Status = "match" if ok else ("deviates" if deviates else "mismatch")
    return Row(
        quantity,
        source,
        published,
        ours,
        rel,
        status,
        note,
        tolerance,
        reference_kind=kind,
        verified_by=verified_by if status == "deviates" else "",
        db_level=db_level,
    )


def compare(
    quantity: str,
    source: str,
    published: float,
    ours: float,
    tolerance: float,
    explanation: str = "",
    *,
    kind: RefKind,
    verified_by: str = "",
) -> Row:
    """Row comparing two numbers against a reference of ``kind``.

    ``match`` within ``tolerance`` (relative); outside it ``deviates`` when the reference is a
    ``paper`` or ``standard`` one and both a reason (``explanation``) and the test verifying it
    (``verified_by``, a pytest node id such as ``"tests/test_x.py::test_y"``) are given, else
    ``mismatch`` (always so for a ``measured`` reference; the reason stays in the note).
    """
    rel = (ours - published) / abs(published) if published else math.nan
    ok = abs(rel) <= tolerance
    note = explanation if not ok else ""
    return _judged(quantity, source, published, ours, rel, ok, note, tolerance, kind, verified_by)


def judge(
    quantity: str,
    source: str,
    published: str,
    ours: str,
    ok: bool,
    explanation: str = "",
    *,
    kind: RefKind,
    verified_by: str = "",
    db_level: bool = False,
) -> Row:
    """Row for a comparison judged by the caller (a statement, a label, numbers against a bound
    of their own): ``match`` when ``ok``, otherwise ``deviates`` or ``mismatch`` by the rules of
    :func:`compare`; ``explanation`` is kept as the note either way. ``db_level``: the two
    numbers are levels in dB (:attr:`Row.db_level`)."""
    return _judged(
        quantity, source, published, ours, None, ok, explanation, None, kind, verified_by,
        db_level,
    )  # fmt: skip


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
    names = list(dict.fromkeys(sections or SECTIONS))  # a section given twice runs once
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
            d["size"] = r.size
            d["section"] = sec.name
            rows.append(d)
    write_json(out / "results.json", rows)
    write_html(out / "report.html", done, quick)
    _write_run(out, done, quick)
    return done


def _write_run(out: Path, done: list[Section], quick: bool) -> None:
    """``run.json``: how the folder's report was made (version, ``quick``, sections, figures);
    the figures a previous run recorded there and this one did not make are removed, so the
    folder holds one report (twenty-first session: a second `reproduce --section vsm` kept the
    first run's figures of other sections beside its own results)."""
    import contextlib
    import datetime
    import json

    from .._version import __version__

    figs = [f for sec in done for f, _cap in sec.figures]
    prev: list[str] = []
    with contextlib.suppress(OSError, ValueError, TypeError, AttributeError):
        prev = [str(f) for f in json.loads((out / "run.json").read_text("utf-8"))["figures"]]
    for f in set(prev) - set(figs):
        if Path(f).name == f and f.lower().endswith(".png"):  # only a figure it wrote there
            with contextlib.suppress(OSError):
                (out / f).unlink()
    write_json(
        out / "run.json",
        {
            "bearingsim_version": __version__,
            "quick": quick,
            "sections": [sec.name for sec in done],
            "figures": figs,
            "written_utc": datetime.datetime.now(datetime.UTC).isoformat(timespec="seconds"),
        },
    )
