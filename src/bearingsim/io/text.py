"""Reader of numeric text tables (CSV and the like): the one parser behind every text signal
file (:func:`bearingsim.io.read_signal`)."""

from __future__ import annotations

import math
import re
from dataclasses import dataclass
from pathlib import Path

import numpy as np
from numpy.typing import NDArray

from ..errors import ConfigError

__all__ = ["TextTable", "read_table"]

_DELIMITED = re.compile(r"[,;]")


@dataclass(frozen=True)
class TextTable:
    """A numeric table read from a text file.

    Attributes
    ----------
    header : tuple of str or None
        Column names from the header line (``None`` without one).
    data : ndarray, shape (rows, columns)
        The numbers.
    """

    header: tuple[str, ...] | None
    data: NDArray[np.float64]

    @property
    def names(self) -> tuple[str, ...]:
        """Column names: the header's, else ``col0``, ``col1``, ..."""
        return self.header or tuple(f"col{i}" for i in range(self.data.shape[1]))


def _fields(line: str) -> list[str]:
    """Split on commas or semicolons when the line has any (blanks then belong to the fields),
    else on blanks and tabs; surrounding quotes are dropped."""
    parts = _DELIMITED.split(line) if _DELIMITED.search(line) else line.split()
    return [x.strip().strip("\"'") for x in parts]


def _number(s: str) -> float | None:
    """The number a field holds, or None. Python's digit grouping (``1_000``) is not a number
    in a data file: a spreadsheet never writes it, and a field such as ``3_2`` is more likely a
    label than 32."""
    if "_" in s:
        return None
    try:
        return float(s)
    except ValueError:
        return None


def read_table(path: str | Path) -> TextTable:
    """Read a numeric text table.

    Lines that are blank or start with ``#`` are skipped. Values are separated by commas or
    semicolons (then blanks may surround them), else by blanks or tabs. A first line without any
    number is the header naming the columns. Every data line must hold as many numbers as the
    first, every number finite. A leading UTF-8 byte-order mark (spreadsheet exports) is
    skipped. Anything else — a binary file, another encoding — is a one-line
    :class:`ConfigError`.

    Parameters
    ----------
    path : str or Path
        The file (UTF-8).
    """
    p = Path(path)
    try:
        lines = p.read_text(encoding="utf-8-sig").splitlines()
    except OSError as exc:
        raise ConfigError(f"file = {str(p)!r} cannot be read ({exc.strerror})") from None
    except UnicodeDecodeError:
        raise ConfigError(f"file = {str(p)!r} is not a UTF-8 text file") from None
    header: tuple[str, ...] | None = None
    rows: list[list[float]] = []
    for ln in lines:
        s = ln.strip()
        if not s or s.startswith("#"):
            continue
        parts = _fields(s)
        vals = [_number(x) for x in parts]
        if all(v is not None for v in vals):
            if not all(math.isfinite(v) for v in vals):
                raise ConfigError(
                    f"file = {str(p)!r}: line {s[:40]!r} holds a value that is not finite; "
                    "valid: finite numbers (no nan, inf)"
                )
            if rows and len(vals) != len(rows[0]):
                raise ConfigError(
                    f"file = {str(p)!r}: line {s[:40]!r} has {len(vals)} values, the first data "
                    f"line {len(rows[0])}; valid: the same number of columns on every line"
                )
            rows.append(vals)
        elif not rows and header is None and all(v is None for v in vals):
            header = tuple(parts)
        else:
            raise ConfigError(
                f"file = {str(p)!r}: non-numeric line {s[:40]!r}; valid: numbers separated by "
                "commas, semicolons, tabs or blanks, after an optional header line"
            )
    if not rows:
        what = (
            f"has a header line ({', '.join(header)[:40]!r}) and no line of numbers"
            if header is not None
            else "is empty"
        )
        raise ConfigError(f"file = {str(p)!r} {what}; valid: at least one line of numbers")
    if header is not None and len(header) != len(rows[0]):
        raise ConfigError(
            f"file = {str(p)!r}: the header names {len(header)} columns, the data has "
            f"{len(rows[0])}; valid: one name per column"
        )
    return TextTable(header, np.asarray(rows, dtype=float))
