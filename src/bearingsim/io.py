"""File input/output: atomic writes, JSON, CWRU ``.mat`` records."""

from __future__ import annotations

import contextlib
import json
import math
import os
import re
import tempfile
from collections.abc import Iterator
from dataclasses import dataclass
from pathlib import Path
from typing import IO, Any

import numpy as np

from .errors import ConfigError


@contextlib.contextmanager
def atomic_path(path: str | Path, suffix: str | None = None) -> Iterator[Path]:
    """Yield a temporary path beside ``path``; on success rename it onto ``path``.

    Nothing is left at ``path`` if the block raises (no half-written output).
    """
    dest = Path(path)
    dest.parent.mkdir(parents=True, exist_ok=True)
    fd, tmp = tempfile.mkstemp(
        prefix=f".{dest.name}.", suffix=suffix or dest.suffix or ".tmp", dir=dest.parent
    )
    os.close(fd)
    tmp_path = Path(tmp)
    try:
        yield tmp_path
        os.replace(tmp_path, dest)
    finally:
        if tmp_path.exists():
            tmp_path.unlink()


@contextlib.contextmanager
def atomic_open(path: str | Path, mode: str = "w", **kw: Any) -> Iterator[IO[Any]]:
    """Open a temporary file beside ``path`` and rename it onto ``path`` on success."""
    with atomic_path(path) as tmp, open(tmp, mode, **kw) as fh:
        yield fh


def to_jsonable(obj: Any) -> Any:
    """Convert NumPy scalars/arrays and tuples to plain JSON types; non-finite floats -> None."""
    if isinstance(obj, dict):
        return {str(k): to_jsonable(v) for k, v in obj.items()}
    if isinstance(obj, list | tuple):
        return [to_jsonable(v) for v in obj]
    if isinstance(obj, np.ndarray):
        return to_jsonable(obj.tolist())
    if isinstance(obj, np.integer):
        return int(obj)
    if isinstance(obj, float | np.floating):
        x = float(obj)
        return x if math.isfinite(x) else None
    return obj


def _json_default(obj: Any) -> Any:
    """``default`` of :func:`dumps_jsonable`: what :func:`to_jsonable` does to the types the C
    encoder does not know; a non-finite NumPy float raises, so that the caller falls back."""
    if isinstance(obj, np.ndarray):
        return to_jsonable(obj.tolist())
    if isinstance(obj, np.integer):
        return int(obj)
    if isinstance(obj, np.floating):
        x = float(obj)
        if math.isfinite(x):
            return x
        raise ValueError("non-finite float")
    raise TypeError(f"Object of type {type(obj).__name__} is not JSON serializable")


_CONTAINERS = (dict, list, tuple)


def _str_keys(obj: Any) -> bool:
    """Whether every dict key inside ``obj`` (through dicts, lists and tuples) is a ``str``."""
    if isinstance(obj, dict):
        for k, v in obj.items():
            if type(k) is not str or (isinstance(v, _CONTAINERS) and not _str_keys(v)):
                return False
    elif isinstance(obj, list | tuple):
        for v in obj:
            if isinstance(v, _CONTAINERS) and not _str_keys(v):
                return False
    return True


def dumps_jsonable(obj: Any) -> str:
    """``json.dumps(to_jsonable(obj))``, the same text, mostly by the C encoder.

    The encoder handles NumPy scalars and arrays through ``default``; a non-finite float makes it
    raise (``allow_nan=False``), and dict keys other than ``str`` (which ``to_jsonable`` writes
    with ``str()``, the encoder differently for ``True``/``None``) are checked first: both cases,
    and any error, take the exact route through :func:`to_jsonable`. About 2 x faster for a
    ``SimulationResult.meta``.
    """
    if _str_keys(obj):
        try:
            return json.dumps(obj, default=_json_default, allow_nan=False)
        except (TypeError, ValueError):
            pass
    return json.dumps(to_jsonable(obj))


def write_json(path: str | Path, obj: Any) -> None:
    """Write ``obj`` as indented JSON atomically."""
    with atomic_open(path, "w", encoding="utf-8") as fh:
        json.dump(to_jsonable(obj), fh, indent=2)
        fh.write("\n")


# ---------------------------------------------------------------------------------- CWRU data


@dataclass(frozen=True)
class CwruRecord:
    """One CWRU Bearing Data Center record.

    Attributes
    ----------
    path : Path
        Source file.
    number : str
        Record number (e.g. ``"097"``).
    channels : dict[str, ndarray]
        Acceleration per channel (``"DE"``, ``"FE"``, ``"BA"``) [g] as stored by CWRU.
    rpm : float or None
        Shaft speed stored in the file (``X###RPM``) [r/min].
    """

    path: Path
    number: str
    channels: dict[str, np.ndarray]
    rpm: float | None

    def acceleration(self, channel: str = "DE") -> np.ndarray:
        """Acceleration of ``channel`` in [m/s^2] (CWRU stores g; 1 g = 9.80665 m/s^2)."""
        ch = channel.upper()
        if ch not in self.channels:
            raise ConfigError(
                f"channel = {channel!r} not in {self.path.name}; valid: {', '.join(self.channels)}"
            )
        return self.channels[ch] * 9.80665


_KEY = re.compile(r"^X(\d+)_(DE|FE|BA)_time$")


def read_cwru_mat(path: str | Path) -> CwruRecord:
    """Read a CWRU ``.mat`` file (keys ``X###_DE_time``, ``X###_FE_time``, ``X###_BA_time``,
    ``X###RPM``)."""
    from scipy.io import loadmat

    p = Path(path)
    try:
        data = loadmat(p)
    except (OSError, ValueError, TypeError) as exc:
        raise ConfigError(f"file = {str(p)!r} is not a readable MATLAB .mat file ({exc})") from None
    channels: dict[str, np.ndarray] = {}
    numbers = set()
    for key, val in data.items():
        m = _KEY.match(key)
        if m:
            numbers.add(m.group(1))
            channels[m.group(2)] = np.asarray(val, dtype=float).ravel()
    if not channels:
        raise ConfigError(
            f"file = {str(p)!r} has no CWRU channel (expected keys X###_DE_time / X###_FE_time)"
        )
    number = sorted(numbers)[0]
    rpm = None
    for key, val in data.items():
        if re.match(r"^X\d+RPM$", key):
            rpm = float(np.asarray(val).ravel()[0])
    return CwruRecord(p, number, channels, rpm)
