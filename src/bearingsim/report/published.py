"""Published numbers: the data file ``published.toml`` that the report and the tests read.

Every number a source publishes as a result (of its model, its test or its table) that the
reproduction report or a literature test compares ours with lives once, in
``bearingsim/report/published.toml``, with its unit, its source and its kind
(:class:`Kind`). Read one with :func:`value` (the number as printed) or :func:`entry` (all of
it; :attr:`Published.si` converts to SI)::

    >>> from bearingsim.report.published import entry, value
    >>> value("vsm.eq20.bpfi_6205_1748rpm")
    157.76
    >>> entry("life.table2.inner_pmax_theory").si
    2890000000.0

Tolerances are not in the file: each comparison states its own (see the file's header).
"""

from __future__ import annotations

import difflib
import math
import tomllib
from collections.abc import Mapping
from dataclasses import dataclass, field
from enum import StrEnum
from functools import cache
from importlib import resources
from typing import Any

from ..errors import ConfigError

__all__ = ["DATA_FILE", "Kind", "Published", "entries", "entry", "value"]

#: name of the data file inside the ``bearingsim.report`` package
DATA_FILE = "published.toml"

#: factor to SI of the units used in the file (degrees go through :func:`math.radians`)
_SI_FACTOR = {
    "-": 1.0,
    "Hz": 1.0,
    "N": 1.0,
    "rad": 1.0,
    "rad/s": 1.0,
    "m/s^2": 1.0,
    "cycles": 1.0,
    "rev": 1.0,
    "mm": 1e-3,
    "kN": 1e3,
    "MPa": 1e6,
    "r/min": math.pi / 30.0,
}
_FIELDS = {"value", "unit", "source", "kind", "note"}


class Kind(StrEnum):
    """What kind of reference a published number is."""

    #: a number a paper (or a reference such as a textbook example) computed with its model
    PAPER = "paper"
    #: a measurement: a fatigue test, a feature of a measured (CWRU) record
    MEASURED = "measured"
    #: an ISO or catalogue value, the CWRU bearing table
    STANDARD = "standard"


@dataclass(frozen=True)
class Published:
    """One published number (or table) of ``published.toml``.

    Attributes
    ----------
    id : str
        Dotted id, e.g. ``"life.table4.predicted_life"``.
    value : float or str or tuple of float
        The value as the source prints it, in ``unit``.
    unit : str
        Unit of ``value`` (``"-"`` for dimensionless).
    source : str
        Where it is printed (seed + table/figure/equation, standard or catalogue).
    kind : Kind
        Paper (model result), measured, or standard.
    note : str
        What the number is, how it was read.
    columns : mapping of str to tuple
        Further columns of a published table, each as long as ``value``.
    """

    id: str
    value: float | str | tuple[float, ...]
    unit: str
    source: str
    kind: Kind
    note: str = ""
    columns: Mapping[str, tuple[Any, ...]] = field(default_factory=dict)

    @property
    def si(self) -> float | tuple[float, ...]:
        """``value`` in SI units (degrees to radians, MPa to Pa, kN to N, mm to m)."""
        if self.unit != "deg" and self.unit not in _SI_FACTOR:
            raise ConfigError(f"published {self.id!r}: unit {self.unit!r} has no SI form")
        if isinstance(self.value, str):
            raise ConfigError(f"published {self.id!r} = {self.value!r} is not a number")
        vals = self.value if isinstance(self.value, tuple) else (self.value,)
        si = tuple(
            math.radians(x) if self.unit == "deg" else x * _SI_FACTOR[self.unit] for x in vals
        )
        return si if isinstance(self.value, tuple) else si[0]

    def rows(self, *columns: str) -> list[tuple[Any, ...]]:
        """The table as rows ``(value, column, ...)``, e.g. ``rows("ball", "event")``."""
        if not isinstance(self.value, tuple):
            raise ConfigError(f"published {self.id!r} is a single value, not a table")
        for c in columns:
            if c not in self.columns:
                raise ConfigError(
                    f"published {self.id!r} has no column {c!r}; valid: "
                    + ", ".join(sorted(self.columns))
                )
        return list(zip(self.value, *(self.columns[c] for c in columns), strict=True))


def _number(eid: str, x: Any) -> float:
    if isinstance(x, bool) or not isinstance(x, int | float) or not math.isfinite(x):
        raise ConfigError(f"published {eid!r}: value {x!r} is not a finite number")
    return float(x)


def _parse(eid: str, d: dict[str, Any]) -> Published:
    for k in ("value", "unit", "source", "kind"):
        if k not in d:
            raise ConfigError(f"published {eid!r} has no {k!r} ({DATA_FILE})")
    try:
        kind = Kind(d["kind"])
    except ValueError:
        raise ConfigError(
            f"published {eid!r}: kind = {d['kind']!r} is invalid; valid: "
            + ", ".join(k.value for k in Kind)
        ) from None
    v = d["value"]
    if isinstance(v, list):
        val: float | str | tuple[float, ...] = tuple(_number(eid, x) for x in v)
    elif isinstance(v, str):
        val = v
    else:
        val = _number(eid, v)
    columns = {}
    for k, col in d.items():
        if k in _FIELDS:
            continue
        if not isinstance(val, tuple) or not isinstance(col, list) or len(col) != len(val):
            raise ConfigError(
                f"published {eid!r}: {k!r} is neither a field ({', '.join(sorted(_FIELDS))}) "
                "nor a column as long as the value list"
            )
        columns[k] = tuple(col)
    return Published(eid, val, d["unit"], d["source"], kind, d.get("note", ""), columns)


def _flatten(prefix: str, d: dict[str, Any], out: dict[str, Published]) -> None:
    for k, v in d.items():
        eid = f"{prefix}.{k}" if prefix else k
        if not isinstance(v, dict):
            raise ConfigError(f"published {eid!r} is not a table ({DATA_FILE})")
        if "value" in v:
            out[eid] = _parse(eid, v)
        else:
            _flatten(eid, v, out)


@cache
def entries() -> Mapping[str, Published]:
    """Every entry of ``published.toml`` by id (parsed once per process)."""
    text = resources.files(__package__).joinpath(DATA_FILE).read_text(encoding="utf-8")
    out: dict[str, Published] = {}
    _flatten("", tomllib.loads(text), out)
    return out


def entry(eid: str) -> Published:
    """The published entry ``eid``; an unknown id raises a one-line :class:`ConfigError`."""
    found = entries()
    if eid not in found:
        near = difflib.get_close_matches(eid, found, n=3, cutoff=0.6)
        hint = f"; closest: {', '.join(near)}" if near else ""
        raise ConfigError(
            f"published id = {eid!r} is unknown; valid: one of the {len(found)} ids in "
            f"bearingsim/report/{DATA_FILE}{hint}"
        )
    return found[eid]


def value(eid: str) -> float | str | tuple[float, ...]:
    """The value of the published entry ``eid`` as the source prints it (in its ``unit``)."""
    return entry(eid).value
